/* view.c — shapedem.View: one particle field of a world, zero-copy, in
 * storage order (sd_world_state_view), e.g. World.positions.
 *
 * Invariant: a View reads the world's memory only while the world's
 * generation (sd_world_generation) is the one the view was taken at and
 * the world is not stepping in another thread; otherwise every read raises
 * shapedem.StaleViewError instead of reading memory a rebuild reordered or
 * freed. np.asarray(view) (the buffer protocol, __array__) hands out the
 * live memory itself, read-only, checked when it is handed out: such an
 * array is the caller's to drop before the next step (docs/python.md).
 * Indexing a view returns a copy, checked at each read.
 */
#include "common.h"

#include <string.h>

typedef struct PyView {
    PyObject_HEAD
    PyWorld *world;
    const char *name;   /* "position", ... the sd_state_view member */
    uint64_t generation;
    void *data;
    Py_ssize_t n, cols; /* rows, values per row (1: a one-dimensional view) */
    int type;           /* NPY_DOUBLE, NPY_INT32 or NPY_UINT64 */
    Py_ssize_t shape[2], strides[2];
} PyView;

/* the members of sd_state_view a View may show, with their shapes */
static const struct {
    const char *name;
    size_t offset;
    int cols, type;
} sdpy_view_fields[] = {
    {"position", offsetof(sd_state_view, position), 3, NPY_DOUBLE},
    {"velocity", offsetof(sd_state_view, velocity), 3, NPY_DOUBLE},
    {"angular_velocity", offsetof(sd_state_view, angular_velocity), 3, NPY_DOUBLE},
    {"orientation", offsetof(sd_state_view, orientation), 4, NPY_DOUBLE},
    {"force", offsetof(sd_state_view, force), 3, NPY_DOUBLE},
    {"torque", offsetof(sd_state_view, torque), 3, NPY_DOUBLE},
    {"radius", offsetof(sd_state_view, radius), 1, NPY_DOUBLE},
    {"material", offsetof(sd_state_view, material), 1, NPY_INT32},
    {"shape", offsetof(sd_state_view, shape), 1, NPY_INT32},
    {"id", offsetof(sd_state_view, id), 1, NPY_UINT64},
};

PyObject *sdpy_view_new(PyWorld *world, const char *name)
{
    if (sdpy_world_usable(world) < 0)
        return NULL;
    size_t k = 0;
    while (strcmp(sdpy_view_fields[k].name, name) != 0)
        ++k;
    sd_state_view sv;
    sd_error err;
    if (sd_world_state_view(world->w, &sv, &err) != SD_OK)
        return sdpy_raise(&err);
    PyView *v = PyObject_New(PyView, &sdpy_view_type);
    if (!v)
        return NULL;
    Py_INCREF(world);
    v->world = world;
    v->name = sdpy_view_fields[k].name;
    v->generation = sv.generation;
    memcpy(&v->data, (const char *)&sv + sdpy_view_fields[k].offset, sizeof v->data);
    v->n = (Py_ssize_t)sv.n;
    v->cols = sdpy_view_fields[k].cols;
    v->type = sdpy_view_fields[k].type;
    Py_ssize_t item = v->type == NPY_INT32 ? 4 : 8;
    v->shape[0] = v->n;
    v->shape[1] = v->cols;
    v->strides[0] = item * v->cols;
    v->strides[1] = item;
    return (PyObject *)v;
}

static void sdpy_view_dealloc(PyView *v)
{
    Py_XDECREF(v->world);
    PyObject_Free(v);
}

/* 0 when the view may be read, else -1 with StaleViewError */
static int sdpy_view_live(PyView *v)
{
    if (v->world->busy || !v->world->w) {
        PyErr_Format(sdpy_stale_error, "the %s view cannot be read while its world is stepping", v->name);
        return -1;
    }
    uint64_t now = sd_world_generation(v->world->w);
    if (now != v->generation) {
        PyErr_Format(sdpy_stale_error,
                     "the %s view is stale: the world's particle arrays changed since it was taken (a "
                     "rebuild, an insertion, a removal or a restore; generation %llu, now %llu); take it "
                     "again from the world",
                     v->name, (unsigned long long)v->generation, (unsigned long long)now);
        return -1;
    }
    return 0;
}

/* the live memory as a read-only ndarray whose base is the view */
static PyObject *sdpy_view_ndarray(PyView *v)
{
    if (sdpy_view_live(v) < 0)
        return NULL;
    npy_intp dims[2] = {v->n, v->cols};
    static double empty[4];
    PyObject *a = PyArray_New(&PyArray_Type, v->cols > 1 ? 2 : 1, dims, v->type, NULL, v->data ? v->data : empty,
                              0, NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED, NULL);
    if (!a)
        return NULL;
    Py_INCREF(v);
    if (PyArray_SetBaseObject((PyArrayObject *)a, (PyObject *)v) < 0) {
        Py_DECREF(a);
        return NULL;
    }
    return a;
}

static PyObject *sdpy_view_array(PyView *v, PyObject *args, PyObject *kw)
{
    static char *names[] = {"dtype", "copy", NULL};
    PyObject *dtype = Py_None, *copy = Py_None;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|OO", names, &dtype, &copy))
        return NULL;
    PyObject *a = sdpy_view_ndarray(v);
    if (!a)
        return NULL;
    int want_copy = copy != Py_None && PyObject_IsTrue(copy);
    if (dtype != Py_None || want_copy) {
        PyArray_Descr *descr = NULL;
        if (dtype != Py_None && !PyArray_DescrConverter(dtype, &descr)) {
            Py_DECREF(a);
            return NULL;
        }
        PyObject *b = descr ? PyArray_CastToType((PyArrayObject *)a, descr, 0)
                            : PyArray_NewCopy((PyArrayObject *)a, NPY_CORDER);
        Py_DECREF(a);
        return b;
    }
    return a;
}

static PyObject *sdpy_view_copy(PyView *v, PyObject *unused)
{
    PyObject *a = sdpy_view_ndarray(v);
    if (!a)
        return NULL;
    PyObject *b = PyArray_NewCopy((PyArrayObject *)a, NPY_CORDER);
    Py_DECREF(a);
    return b;
}

static PyObject *sdpy_view_getitem(PyView *v, PyObject *key)
{
    PyObject *a = sdpy_view_ndarray(v);
    if (!a)
        return NULL;
    PyObject *r = PyObject_GetItem(a, key);
    Py_DECREF(a);
    if (r && PyArray_Check(r)) { /* a copy: nothing of the live memory outlives the check */
        PyObject *c = PyArray_NewCopy((PyArrayObject *)r, NPY_CORDER);
        Py_DECREF(r);
        return c;
    }
    return r;
}

/* iterates over a copy of the rows, taken now */
static PyObject *sdpy_view_iter(PyView *v)
{
    PyObject *c = sdpy_view_copy(v, NULL);
    if (!c)
        return NULL;
    PyObject *it = PyObject_GetIter(c);
    Py_DECREF(c);
    return it;
}

static Py_ssize_t sdpy_view_len(PyView *v)
{
    return sdpy_view_live(v) < 0 ? -1 : v->n;
}

static int sdpy_view_getbuffer(PyView *v, Py_buffer *b, int flags)
{
    if (sdpy_view_live(v) < 0) {
        b->obj = NULL;
        return -1;
    }
    if (flags & PyBUF_WRITABLE) {
        PyErr_Format(PyExc_BufferError, "the %s view is read-only: write with World.set", v->name);
        b->obj = NULL;
        return -1;
    }
    static double empty[4];
    b->buf = v->data ? v->data : empty;
    Py_INCREF(v);
    b->obj = (PyObject *)v;
    b->itemsize = v->strides[1];
    b->len = v->n * v->cols * b->itemsize;
    b->readonly = 1;
    b->ndim = v->cols > 1 ? 2 : 1;
    b->format = (flags & PyBUF_FORMAT) ? (v->type == NPY_DOUBLE ? "d" : v->type == NPY_INT32 ? "i" : "Q") : NULL;
    b->shape = (flags & PyBUF_ND) ? v->shape : NULL;
    b->strides = (flags & PyBUF_STRIDES) == PyBUF_STRIDES ? v->strides : NULL;
    b->suboffsets = NULL;
    b->internal = NULL;
    return 0;
}

static PyObject *sdpy_view_repr(PyView *v)
{
    if (sdpy_view_live(v) < 0) {
        PyErr_Clear();
        return PyUnicode_FromFormat("<shapedem.View %s, stale>", v->name);
    }
    return PyUnicode_FromFormat("<shapedem.View %s, %zd particles, generation %llu>", v->name, v->n,
                                (unsigned long long)v->generation);
}

static PyObject *sdpy_view_valid(PyView *v, void *unused)
{
    int ok = sdpy_view_live(v) == 0;
    PyErr_Clear();
    return PyBool_FromLong(ok);
}

static PyObject *sdpy_view_shape(PyView *v, void *unused)
{
    if (sdpy_view_live(v) < 0)
        return NULL;
    return v->cols > 1 ? Py_BuildValue("(nn)", v->n, v->cols) : Py_BuildValue("(n)", v->n);
}

static PyObject *sdpy_view_dtype(PyView *v, void *unused)
{
    return (PyObject *)PyArray_DescrFromType(v->type);
}

static PyObject *sdpy_view_ndim(PyView *v, void *unused)
{
    return PyLong_FromLong(v->cols > 1 ? 2 : 1);
}

static PyObject *sdpy_view_generation(PyView *v, void *unused)
{
    return PyLong_FromUnsignedLongLong(v->generation);
}

static PyObject *sdpy_view_field(PyView *v, void *unused)
{
    return PyUnicode_FromString(v->name);
}

static PyGetSetDef sdpy_view_getset[] = {
    {"valid", (getter)sdpy_view_valid, NULL, "True while the view may be read (same generation, world idle).", NULL},
    {"shape", (getter)sdpy_view_shape, NULL, "(n, components), or (n,) for one value per particle.", NULL},
    {"dtype", (getter)sdpy_view_dtype, NULL, "float64 (int32 for material and shape, uint64 for id).", NULL},
    {"ndim", (getter)sdpy_view_ndim, NULL, "2, or 1 for one value per particle.", NULL},
    {"generation", (getter)sdpy_view_generation, NULL, "The world's generation when the view was taken.", NULL},
    {"field", (getter)sdpy_view_field, NULL, "The field shown: position, velocity, ..., id.", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyMethodDef sdpy_view_methods[] = {
    {"__array__", (PyCFunction)(void (*)(void))sdpy_view_array, METH_VARARGS | METH_KEYWORDS,
     "__array__(dtype=None, copy=None) -> numpy.ndarray\n\nThe live memory, read-only, without a copy (unless\n"
     "dtype or copy asks for one). Raises StaleViewError when the view is stale."},
    {"copy", (PyCFunction)sdpy_view_copy, METH_NOARGS, "copy() -> numpy.ndarray\n\nA copy of the values now."},
    {NULL, NULL, 0, NULL}};

static PyMappingMethods sdpy_view_mapping = {(lenfunc)sdpy_view_len, (binaryfunc)sdpy_view_getitem, NULL};
static PyBufferProcs sdpy_view_buffer = {(getbufferproc)sdpy_view_getbuffer, NULL};

PyTypeObject sdpy_view_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "shapedem.View",
    .tp_basicsize = sizeof(PyView),
    .tp_dealloc = (destructor)sdpy_view_dealloc,
    .tp_repr = (reprfunc)sdpy_view_repr,
    .tp_as_mapping = &sdpy_view_mapping,
    .tp_as_buffer = &sdpy_view_buffer,
    .tp_iter = (getiterfunc)sdpy_view_iter,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "One particle field of a world in storage order, without a copy (World.positions, ...).\n\n"
              "Rows are particles in the engine's storage order, which a rebuild changes; World.storage_ids\n"
              "is the stable id of each row. Any read after the world's particle arrays changed raises\n"
              "StaleViewError. Indexing returns a copy; numpy.asarray(view) is the live memory, read-only.",
    .tp_methods = sdpy_view_methods,
    .tp_getset = sdpy_view_getset,
};

int sdpy_add_view_type(PyObject *m)
{
    if (PyType_Ready(&sdpy_view_type) < 0)
        return -1;
    Py_INCREF(&sdpy_view_type);
    return PyModule_AddObject(m, "View", (PyObject *)&sdpy_view_type);
}
