/* module.c — the extension module shapedem._shapedem: its exceptions, the
 * conversion of an engine error into one, and the module-level functions.
 * The classes live in world.c, view.c and scene.c; the package
 * (python/shapedem/__init__.py) re-exports them (docs/python.md).
 *
 * Invariant: an sd_error reaches Python as one exception whose str() is
 * sd_error_format's "file:line: key: msg" and whose attributes keep the
 * parts, so a caller can test e.key without parsing the text.
 */
#define SDPY_MODULE_C
#include "common.h"

#include <stdio.h>
#include <stdlib.h>

PyObject *sdpy_error, *sdpy_input_error, *sdpy_physics_error, *sdpy_stale_error;

/* sets o.name = value and drops the reference to value */
static int sdpy_set_attr(PyObject *o, const char *name, PyObject *value)
{
    int rc = value ? PyObject_SetAttrString(o, name, value) : -1;
    Py_XDECREF(value);
    return rc;
}

PyObject *sdpy_raise(const sd_error *err)
{
    char buf[1024];
    sd_error_format(err, buf, sizeof buf);
    PyObject *type = err->code == SD_ERR_INPUT ? sdpy_input_error
                     : err->code == SD_ERR_PHYSICS ? sdpy_physics_error
                                                   : sdpy_error;
    PyObject *exc = PyObject_CallFunction(type, "s", buf);
    if (!exc)
        return NULL;
    if (sdpy_set_attr(exc, "status", PyUnicode_FromString(sd_status_name(err->code))) == 0 &&
        sdpy_set_attr(exc, "file", PyUnicode_DecodeFSDefault(err->file)) == 0 &&
        sdpy_set_attr(exc, "line", PyLong_FromLong(err->line)) == 0 &&
        sdpy_set_attr(exc, "key", PyUnicode_FromString(err->key)) == 0 &&
        sdpy_set_attr(exc, "message", PyUnicode_FromString(err->msg)) == 0)
        PyErr_SetObject(type, exc);
    Py_DECREF(exc);
    return NULL;
}

static PyObject *sdpy_memory_in_use(PyObject *mod, PyObject *unused)
{
    return PyLong_FromSize_t(sd_memory_in_use());
}

static PyObject *sdpy_fields(PyObject *mod, PyObject *unused)
{
    PyObject *d = PyDict_New();
    for (int f = 0; d && f < SD_FIELD_COUNT; ++f) {
        PyObject *v = Py_BuildValue("{s:n,s:s,s:O}", "components", (Py_ssize_t)sd_field_components((sd_field)f),
                                    "unit", sd_field_unit((sd_field)f), "writable",
                                    sd_field_writable((sd_field)f) ? Py_True : Py_False);
        if (!v || PyDict_SetItemString(d, sd_field_name((sd_field)f), v) < 0) {
            Py_XDECREF(v);
            Py_DECREF(d);
            return NULL;
        }
        Py_DECREF(v);
    }
    return d;
}

/* `shapedem info FILE.h5` into a string (sd_checkpoint_print) */
static PyObject *sdpy_checkpoint_info(PyObject *mod, PyObject *arg)
{
    PyObject *path = NULL;
    if (!PyUnicode_FSConverter(arg, &path))
        return NULL;
    char *text = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&text, &size);
    if (!f) {
        Py_DECREF(path);
        return PyErr_NoMemory();
    }
    sd_error err;
    sd_status st = sd_checkpoint_print(f, PyBytes_AS_STRING(path), &err);
    fclose(f);
    Py_DECREF(path);
    PyObject *out = st == SD_OK ? PyUnicode_DecodeUTF8(text, (Py_ssize_t)size, "replace") : sdpy_raise(&err);
    free(text);
    return out;
}

static PyMethodDef sdpy_functions[] = {
    {"memory_in_use", sdpy_memory_in_use, METH_NOARGS,
     "memory_in_use() -> int\n\nBytes the engine holds now through its allocator (all worlds and scenes)."},
    {"fields", sdpy_fields, METH_NOARGS,
     "fields() -> dict\n\nThe particle fields World.get and World.set take: name -> components, unit, writable."},
    {"checkpoint_info", sdpy_checkpoint_info, METH_O,
     "checkpoint_info(path) -> str\n\nWhat a checkpoint file holds, as `shapedem info FILE.h5` prints it;\n"
     "raises shapedem.Error for a file that is not a sound checkpoint."},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef sdpy_module = {
    PyModuleDef_HEAD_INIT, "_shapedem",
    "The shapedem DEM engine's C extension; use the package `shapedem`, which re-exports it.", -1,
    sdpy_functions, NULL, NULL, NULL, NULL};

/* adds exception `name` (a subclass of bases) to m as *out */
static int sdpy_add_exception(PyObject *m, const char *name, PyObject *bases, const char *doc, PyObject **out)
{
    char full[64];
    snprintf(full, sizeof full, "shapedem.%s", name);
    *out = PyErr_NewExceptionWithDoc(full, doc, bases, NULL);
    if (!*out)
        return -1;
    Py_INCREF(*out);
    return PyModule_AddObject(m, name, *out);
}

PyMODINIT_FUNC PyInit__shapedem(void);
PyMODINIT_FUNC PyInit__shapedem(void)
{
    import_array();
    PyObject *m = PyModule_Create(&sdpy_module);
    if (!m)
        return NULL;
    PyObject *input_bases = NULL;
    int bad = sdpy_add_exception(m, "Error", NULL,
                                 "An error of the engine. str(e) is its message as the C library formats it\n"
                                 "(\"file:line: key: message\"); the attributes status, file, line, key and\n"
                                 "message keep the parts.",
                                 &sdpy_error) < 0;
    if (!bad) {
        input_bases = PyTuple_Pack(2, sdpy_error, PyExc_ValueError);
        bad = !input_bases ||
              sdpy_add_exception(m, "InputError", input_bases,
                                 "Bad input: a scene, a parameter, an array of the wrong shape or with NaN.\n"
                                 "Nothing was changed.",
                                 &sdpy_input_error) < 0 ||
              sdpy_add_exception(m, "PhysicsError", sdpy_error,
                                 "The state became invalid while stepping (NaN, a runaway speed, a deep\n"
                                 "overlap); the message names the particle by stable id.",
                                 &sdpy_physics_error) < 0 ||
              sdpy_add_exception(m, "StaleViewError", sdpy_error,
                                 "A View was read after the world's particle arrays changed (a rebuild, an\n"
                                 "insertion, a removal, a restore): take the view again from the world.",
                                 &sdpy_stale_error) < 0;
        Py_XDECREF(input_bases);
    }
    if (bad || sdpy_add_world_type(m) < 0 || sdpy_add_view_type(m) < 0 || sdpy_add_scene_types(m) < 0 ||
        PyModule_AddStringConstant(m, "version", SD_VERSION_STRING) < 0) {
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
