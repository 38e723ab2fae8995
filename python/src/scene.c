/* scene.c — shapedem.Scene and shapedem.Run: a scene file loaded, its
 * world built and run with the scene's output, as `shapedem run` does it
 * through the same public calls (include/shapedem/scene.h), so a Python
 * run writes the same stats.csv and frames, byte for byte.
 *
 * Invariant: a Run holds its Scene and World (the C run keeps pointers to
 * both until sd_run_close), is closed at most once, and advances with the
 * GIL released and its world marked busy, like World.step.
 */
#include "common.h"

#include <math.h>

/* ---- Scene ---------------------------------------------------------------------- */

static void sdpy_scene_dealloc(PyScene *self)
{
    sd_scene_free(self->s);
    PyObject_Free(self);
}

static PyObject *sdpy_scene_load(PyObject *cls, PyObject *arg)
{
    PyObject *path = NULL;
    if (!PyUnicode_FSConverter(arg, &path))
        return NULL;
    sd_scene *s;
    sd_error err;
    sd_status st = sd_scene_load(PyBytes_AS_STRING(path), &s, &err);
    Py_DECREF(path);
    if (st != SD_OK)
        return sdpy_raise(&err);
    PyScene *o = PyObject_New(PyScene, &sdpy_scene_type);
    if (!o) {
        sd_scene_free(s);
        return NULL;
    }
    o->s = s;
    return (PyObject *)o;
}

/* the overrides of `shapedem run --threads --steps`, for this scene */
static int sdpy_scene_overrides(PyScene *self, PyObject *threads, PyObject *steps)
{
    if (threads && threads != Py_None) {
        long t = PyLong_AsLong(threads);
        if (t < 1 || t > SD_SCENE_MAX_THREADS) {
            PyErr_Clear();
            PyErr_Format(sdpy_input_error, "threads: expected 1 .. %d", SD_SCENE_MAX_THREADS);
            return -1;
        }
        sd_scene_set_threads(self->s, (int)t);
    }
    if (steps && steps != Py_None) {
        long n = PyLong_AsLong(steps);
        if (n < 0) {
            PyErr_Clear();
            PyErr_Format(sdpy_input_error, "steps: expected >= 0");
            return -1;
        }
        sd_scene_set_steps(self->s, n);
    }
    return 0;
}

static PyObject *sdpy_scene_build(PyScene *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"threads", "steps", NULL};
    PyObject *threads = NULL, *steps = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|$OO", names, &threads, &steps) ||
        sdpy_scene_overrides(self, threads, steps) < 0)
        return NULL;
    sd_world *w;
    sd_error err;
    if (sd_scene_build(self->s, &w, &err) != SD_OK)
        return sdpy_raise(&err);
    return sdpy_world_wrap(w, (PyObject *)self);
}

static PyObject *sdpy_scene_run(PyScene *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"output", "threads", "steps", "files", "restart", NULL};
    PyObject *out_o = Py_None, *threads = NULL, *steps = NULL, *restart = Py_None;
    int files = 1;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|O$OOpO", names, &out_o, &threads, &steps, &files, &restart) ||
        sdpy_scene_overrides(self, threads, steps) < 0)
        return NULL;
    char dir[4096];
    if (out_o == Py_None)
        sd_scene_output_directory(self->s, dir, sizeof dir);
    else {
        PyObject *b = NULL;
        if (!PyUnicode_FSConverter(out_o, &b))
            return NULL;
        snprintf(dir, sizeof dir, "%s", PyBytes_AS_STRING(b));
        Py_DECREF(b);
    }
    sd_world *w;
    sd_error err;
    if (sd_scene_build(self->s, &w, &err) != SD_OK)
        return sdpy_raise(&err);
    PyWorld *world = (PyWorld *)sdpy_world_wrap(w, (PyObject *)self);
    if (!world)
        return NULL;
    if (restart != Py_None) { /* `shapedem run --restart CK.h5`: the world takes the checkpoint's state */
        PyObject *b = NULL;
        if (!PyUnicode_FSConverter(restart, &b)) {
            Py_DECREF(world);
            return NULL;
        }
        sd_status st = sd_checkpoint_restore(w, PyBytes_AS_STRING(b), &err);
        Py_DECREF(b);
        if (st != SD_OK) {
            Py_DECREF(world);
            return sdpy_raise(&err);
        }
    }
    sd_run *r;
    if (sd_run_open(self->s, w, files ? dir : NULL, &r, &err) != SD_OK) {
        Py_DECREF(world);
        return sdpy_raise(&err);
    }
    PyRun *run = PyObject_New(PyRun, &sdpy_run_type);
    if (!run) {
        sd_run_close(r, NULL);
        Py_DECREF(world);
        return NULL;
    }
    run->r = r;
    Py_INCREF(self);
    run->scene = self;
    run->world = world;
    return (PyObject *)run;
}

static PyObject *sdpy_scene_info(PyScene *self, void *unused)
{
    sd_scene_info i;
    sd_scene_get_info(self->s, &i);
    return Py_BuildValue("{s:s,s:i,s:d,s:l,s:i,s:s,s:s,s:n,s:n,s:n,s:l,s:l,s:O,s:O,s:s}", "path", i.path,
                         "dimension", i.dimension, "dt", i.dt, "steps", i.steps, "threads", i.threads, "solver",
                         i.solver == SD_SOLVER_GRID ? "grid" : "cells", "contact_law", sd_contact_law_name(i.law),
                         "materials", (Py_ssize_t)i.material_count, "shapes", (Py_ssize_t)i.shape_count, "walls",
                         (Py_ssize_t)i.wall_count, "frame_every", i.frame_every, "stats_every", i.stats_every,
                         "write_frames", i.write_frames ? Py_True : Py_False, "write_stats",
                         i.write_stats ? Py_True : Py_False, "output_directory", i.output_directory);
}

static PyObject *sdpy_scene_steps(PyScene *self, void *unused)
{
    return PyLong_FromLong(sd_scene_steps(self->s));
}

static PyGetSetDef sdpy_scene_getset[] = {
    {"info", (getter)sdpy_scene_info, NULL, "What the scene defines: dimension, dt, steps, solver, output, ...", NULL},
    {"steps", (getter)sdpy_scene_steps, NULL, "Steps of the run (simulation.steps, or duration / dt).", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyMethodDef sdpy_scene_methods[] = {
    {"load", (PyCFunction)sdpy_scene_load, METH_O | METH_CLASS,
     "Scene.load(path) -> Scene\n\nParses and checks a scene file; InputError names the file, line and key."},
    {"build", (PyCFunction)(void (*)(void))sdpy_scene_build, METH_VARARGS | METH_KEYWORDS,
     "build(*, threads=None, steps=None) -> World\n\nThe scene's world, not stepped, with no output."},
    {"run", (PyCFunction)(void (*)(void))sdpy_scene_run, METH_VARARGS | METH_KEYWORDS,
     "run(output=None, *, threads=None, steps=None, files=True, restart=None) -> Run\n\n"
     "Builds the world and opens a run writing the scene's output (frames, stats.csv, summary.txt, the\n"
     "analyses) into output (None: the directory `shapedem run` would use), as `shapedem run` does;\n"
     "files=False writes nothing; restart continues from a checkpoint of this scene."},
    {NULL, NULL, 0, NULL}};

PyTypeObject sdpy_scene_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "shapedem.Scene",
    .tp_basicsize = sizeof(PyScene),
    .tp_dealloc = (destructor)sdpy_scene_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "A scene file, loaded and checked (Scene.load); build() makes its world, run() runs it.",
    .tp_methods = sdpy_scene_methods,
    .tp_getset = sdpy_scene_getset,
};

/* ---- Run ---------------------------------------------------------------------- */

/* closes the C run (summary.txt); 0 or -1 with the error raised */
static int sdpy_run_finish(PyRun *self)
{
    if (!self->r)
        return 0;
    sd_error err;
    sd_status st = sd_run_close(self->r, &err);
    self->r = NULL;
    if (st != SD_OK) {
        sdpy_raise(&err);
        return -1;
    }
    return 0;
}

static void sdpy_run_dealloc(PyRun *self)
{
    if (self->r)
        sd_run_close(self->r, NULL);
    Py_XDECREF(self->world);
    Py_XDECREF(self->scene);
    PyObject_Free(self);
}

static int sdpy_run_open(PyRun *self)
{
    if (!self->r) {
        PyErr_SetString(sdpy_error, "the run is closed");
        return -1;
    }
    return sdpy_world_usable(self->world);
}

/* advances up to steps (never past the scene's end) with the GIL released */
static int sdpy_run_steps(PyRun *self, long steps)
{
    sd_error err;
    sd_status st;
    self->world->busy = 1;
    Py_BEGIN_ALLOW_THREADS
    st = sd_run_advance(self->r, steps, &err);
    Py_END_ALLOW_THREADS
    self->world->busy = 0;
    if (st != SD_OK) {
        sdpy_raise(&err);
        return -1;
    }
    return 0;
}

static long sdpy_run_left(PyRun *self)
{
    sd_run_progress p;
    sd_run_get_progress(self->r, &p);
    return p.steps - p.done;
}

static PyObject *sdpy_run_advance(PyRun *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"steps", NULL};
    PyObject *steps_o = Py_None;
    if (sdpy_run_open(self) < 0 || !PyArg_ParseTupleAndKeywords(args, kw, "|O", names, &steps_o))
        return NULL;
    long steps = steps_o == Py_None ? sdpy_run_left(self) : PyLong_AsLong(steps_o);
    if (steps < 0) {
        PyErr_Clear();
        return PyErr_Format(sdpy_input_error, "steps: expected >= 0");
    }
    if (sdpy_run_steps(self, steps) < 0)
        return NULL;
    return PyBool_FromLong(sdpy_run_left(self) > 0);
}

static PyObject *sdpy_run_close(PyRun *self, PyObject *unused)
{
    if (sdpy_run_finish(self) < 0)
        return NULL;
    Py_RETURN_NONE;
}

static PyObject *sdpy_run_enter(PyRun *self, PyObject *unused)
{
    return Py_NewRef(self);
}

static PyObject *sdpy_run_exit(PyRun *self, PyObject *args)
{
    if (sdpy_run_finish(self) < 0)
        return NULL;
    Py_RETURN_FALSE;
}

static PyObject *sdpy_run_checkpoint(PyRun *self, PyObject *unused)
{
    if (sdpy_run_open(self) < 0)
        return NULL;
    sd_error err;
    if (sd_run_checkpoint(self->r, &err) != SD_OK)
        return sdpy_raise(&err);
    return PyUnicode_DecodeFSDefault(sd_run_last_checkpoint(self->r));
}

/* the iterator of Run.every */
typedef struct PyEvery {
    PyObject_HEAD
    PyRun *run;
    long chunk;
    int started;
} PyEvery;

static PyObject *sdpy_run_every(PyRun *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"seconds", NULL};
    double seconds;
    if (sdpy_run_open(self) < 0 || !PyArg_ParseTupleAndKeywords(args, kw, "d", names, &seconds))
        return NULL;
    double dt = sd_world_dt(self->world->w);
    if (!(seconds > 0) || !isfinite(seconds)) {
        PyErr_SetString(sdpy_input_error, "every: seconds must be > 0 and finite");
        return NULL;
    }
    PyEvery *it = PyObject_New(PyEvery, &sdpy_every_type);
    if (!it)
        return NULL;
    it->chunk = (long)llround(seconds / dt);
    if (it->chunk < 1)
        it->chunk = 1;
    Py_INCREF(self);
    it->run = self;
    it->started = 0;
    return (PyObject *)it;
}

static void sdpy_every_dealloc(PyEvery *it)
{
    Py_XDECREF(it->run);
    PyObject_Free(it);
}

static PyObject *sdpy_every_next(PyEvery *it)
{
    PyRun *run = it->run;
    if (!run->r || sdpy_run_left(run) <= 0)
        return NULL; /* StopIteration */
    if (sdpy_run_open(run) < 0 || sdpy_run_steps(run, it->chunk) < 0)
        return NULL;
    it->started = 1;
    return PyFloat_FromDouble(sd_world_time(run->world->w));
}

PyTypeObject sdpy_every_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "shapedem.RunEvery",
    .tp_basicsize = sizeof(PyEvery),
    .tp_dealloc = (destructor)sdpy_every_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "The iterator of Run.every: each next() advances the run by a chunk and gives the time.",
    .tp_iter = PyObject_SelfIter,
    .tp_iternext = (iternextfunc)sdpy_every_next,
};

static PyObject *sdpy_run_world(PyRun *self, void *unused)
{
    return Py_NewRef(self->world);
}

static PyObject *sdpy_run_progress(PyRun *self, void *unused)
{
    if (sdpy_run_open(self) < 0)
        return NULL;
    sd_run_progress p;
    sd_run_get_progress(self->r, &p);
    return Py_BuildValue("{s:l,s:l,s:d,s:d,s:d,s:i,s:O,s:l}", "done", p.done, "steps", p.steps, "time", p.time,
                         "wall_seconds", p.wall_seconds, "particle_steps_per_second", p.particle_steps_per_second,
                         "threads", p.threads, "stopped", p.stopped ? Py_True : Py_False, "first", p.first);
}

static PyObject *sdpy_run_directory(PyRun *self, void *unused)
{
    if (sdpy_run_open(self) < 0)
        return NULL;
    return PyUnicode_DecodeFSDefault(sd_run_directory(self->r));
}

static PyObject *sdpy_run_closed(PyRun *self, void *unused)
{
    return PyBool_FromLong(self->r == NULL);
}

static PyGetSetDef sdpy_run_getset[] = {
    {"world", (getter)sdpy_run_world, NULL, "The run's World (its views, stats and analyses).", NULL},
    {"progress", (getter)sdpy_run_progress, NULL, "Steps done and to do, time, wall seconds of stepping, ...", NULL},
    {"directory", (getter)sdpy_run_directory, NULL, "The output directory (\"\" when the run writes nothing).", NULL},
    {"closed", (getter)sdpy_run_closed, NULL, "True once close() has run.", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyMethodDef sdpy_run_methods[] = {
    {"advance", (PyCFunction)(void (*)(void))sdpy_run_advance, METH_VARARGS | METH_KEYWORDS,
     "advance(steps=None) -> bool\n\nSteps up to `steps` further (None: to the end), writing frames and\n"
     "stats rows as they fall due; releases the GIL. True while steps are left."},
    {"every", (PyCFunction)(void (*)(void))sdpy_run_every, METH_VARARGS | METH_KEYWORDS,
     "every(seconds) -> iterator of float\n\nAdvances in chunks of `seconds` of simulated time (rounded to\n"
     "whole steps) to the end, giving the world's time after each."},
    {"checkpoint", (PyCFunction)sdpy_run_checkpoint, METH_NOARGS,
     "checkpoint() -> str\n\nWrites DIR/checkpoint-<step>.h5 now and returns its path."},
    {"close", (PyCFunction)sdpy_run_close, METH_NOARGS,
     "close() -> None\n\nWrites summary.txt and ends the run (also at the end of a with block)."},
    {"__enter__", (PyCFunction)sdpy_run_enter, METH_NOARGS, NULL},
    {"__exit__", (PyCFunction)sdpy_run_exit, METH_VARARGS, NULL},
    {NULL, NULL, 0, NULL}};

PyTypeObject sdpy_run_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "shapedem.Run",
    .tp_basicsize = sizeof(PyRun),
    .tp_dealloc = (destructor)sdpy_run_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "A run of a scene writing its output, as `shapedem run` does (Scene.run).",
    .tp_methods = sdpy_run_methods,
    .tp_getset = sdpy_run_getset,
};

int sdpy_add_scene_types(PyObject *m)
{
    if (PyType_Ready(&sdpy_scene_type) < 0 || PyType_Ready(&sdpy_run_type) < 0 ||
        PyType_Ready(&sdpy_every_type) < 0)
        return -1;
    Py_INCREF(&sdpy_scene_type);
    Py_INCREF(&sdpy_run_type);
    if (PyModule_AddObject(m, "Scene", (PyObject *)&sdpy_scene_type) < 0 ||
        PyModule_AddObject(m, "Run", (PyObject *)&sdpy_run_type) < 0)
        return -1;
    return 0;
}
