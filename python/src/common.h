/* common.h — what the files of the Python binding share: the object
 * layouts, the exceptions and the argument converters (docs/python.md).
 *
 * Invariant: every call into the engine is made with the GIL held, except
 * sd_world_step and sd_run_advance, which release it with the world marked
 * busy (PyWorld.busy), so that no other thread reaches the same world until
 * they return; every engine error becomes a shapedem.Error carrying the
 * engine's message (file, line, key where it has them).
 */
#ifndef SDPY_COMMON_H
#define SDPY_COMMON_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>

#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#define PY_ARRAY_UNIQUE_SYMBOL sdpy_ARRAY_API
#ifndef SDPY_MODULE_C
#define NO_IMPORT_ARRAY
#endif
#include <numpy/arrayobject.h>

#include <shapedem/analysis.h>
#include <shapedem/process.h>
#include <shapedem/scene.h>
#include <shapedem/shapedem.h>

/* shapedem.World: an sd_world and who owns it */
typedef struct PyWorld {
    PyObject_HEAD
    sd_world *w;
    PyObject *owner; /* the Scene it was built from (kept alive by the world), or NULL */
    int busy;        /* stepping in another thread with the GIL released */
} PyWorld;

/* shapedem.Scene */
typedef struct PyScene {
    PyObject_HEAD
    sd_scene *s;
} PyScene;

/* shapedem.Run: a run of a scene's world writing the scene's output */
typedef struct PyRun {
    PyObject_HEAD
    sd_run *r;       /* NULL once closed */
    PyScene *scene;
    PyWorld *world;
} PyRun;

extern PyTypeObject sdpy_world_type, sdpy_view_type, sdpy_scene_type, sdpy_run_type, sdpy_every_type;
extern PyObject *sdpy_error, *sdpy_input_error, *sdpy_physics_error, *sdpy_stale_error;

/* raises the exception of err (shapedem.InputError for bad input, ...)
 * with its formatted message and the attributes status, file, line, key,
 * message; returns NULL */
PyObject *sdpy_raise(const sd_error *err);
/* 0, or -1 with shapedem.Error raised when the world is missing or busy */
int sdpy_world_usable(PyWorld *self);
/* a new shapedem.World around w (owner may be NULL) */
PyObject *sdpy_world_wrap(sd_world *w, PyObject *owner);

/* ---- converters (convert.c): each returns 0, or -1 with an exception
 * naming the argument, and changes nothing on failure ---- */
/* a finite 3-vector from any sequence of three numbers */
int sdpy_v3(PyObject *o, const char *name, sd_v3d *out);
/* a C-contiguous float64 array of shape (n, cols) (cols 0: shape (n,)),
 * every value finite; n < 0 takes the array's rows, else requires them.
 * A scalar is broadcast to n rows when allow_scalar. New reference. */
PyArrayObject *sdpy_rows(PyObject *o, const char *name, Py_ssize_t n, int cols, int allow_scalar);
/* the uint64 ids of a sequence, or NULL (with no error) for None */
PyArrayObject *sdpy_ids(PyObject *o, const char *name);
/* the index of a field by name ("position", ...) or -1 with ValueError */
int sdpy_field(PyObject *name);
/* a dict of the pairs given: name, double ... NULL-terminated list */
PyObject *sdpy_dict_doubles(const char *const *names, const double *values, size_t n);

int sdpy_add_view_type(PyObject *m);
int sdpy_add_scene_types(PyObject *m);
int sdpy_add_world_type(PyObject *m);
PyObject *sdpy_view_new(PyWorld *world, const char *name);

#endif
