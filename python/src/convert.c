/* convert.c — Python arguments into the engine's values, checked before
 * anything is changed: vectors, arrays of rows, ids and field names.
 *
 * Invariant: a converter either returns what the engine may take as it is
 * (finite values, the shape asked for, C order, float64 or uint64) or
 * raises shapedem.InputError naming the argument and what was expected,
 * so a call that raises has changed nothing (docs/python.md, "Errors").
 */
#include "common.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int sdpy_v3(PyObject *o, const char *name, sd_v3d *out)
{
    PyArrayObject *a = (PyArrayObject *)PyArray_FROMANY(o, NPY_DOUBLE, 1, 1, NPY_ARRAY_CARRAY_RO);
    if (!a || PyArray_DIM(a, 0) != 3) {
        PyErr_Clear();
        Py_XDECREF(a);
        PyErr_Format(sdpy_input_error, "%s: expected three numbers (x, y, z)", name);
        return -1;
    }
    const double *v = PyArray_DATA(a);
    if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) {
        Py_DECREF(a);
        PyErr_Format(sdpy_input_error, "%s: every component must be finite", name);
        return -1;
    }
    *out = (sd_v3d){v[0], v[1], v[2]};
    Py_DECREF(a);
    return 0;
}

PyArrayObject *sdpy_rows(PyObject *o, const char *name, Py_ssize_t n, int cols, int allow_scalar)
{
    PyArrayObject *a = (PyArrayObject *)PyArray_FROMANY(o, NPY_DOUBLE, 0, 2, NPY_ARRAY_CARRAY_RO);
    if (!a) {
        PyErr_Clear();
        PyErr_Format(sdpy_input_error, "%s: expected an array of numbers", name);
        return NULL;
    }
    if (PyArray_NDIM(a) == 0 && allow_scalar && n >= 0 && cols == 0) {
        /* one value for every row */
        double v = *(const double *)PyArray_DATA(a);
        Py_DECREF(a);
        npy_intp dims[1] = {n};
        a = (PyArrayObject *)PyArray_SimpleNew(1, dims, NPY_DOUBLE);
        if (!a)
            return NULL;
        double *d = PyArray_DATA(a);
        for (Py_ssize_t k = 0; k < n; ++k)
            d[k] = v;
    }
    int want_nd = cols ? 2 : 1;
    /* a single row (3,) for one particle is taken as (1, 3) */
    if (cols && PyArray_NDIM(a) == 1 && PyArray_DIM(a, 0) == cols && n <= 1) {
        npy_intp dims[2] = {1, cols};
        PyArray_Dims shape = {dims, 2};
        PyArrayObject *b = (PyArrayObject *)PyArray_Newshape(a, &shape, NPY_CORDER);
        Py_DECREF(a);
        if (!b)
            return NULL;
        a = b;
    }
    if (PyArray_NDIM(a) != want_nd || (cols && PyArray_DIM(a, 1) != cols) || (n >= 0 && PyArray_DIM(a, 0) != n)) {
        char want[64];
        if (cols && n >= 0)
            snprintf(want, sizeof want, "(%zd, %d)", n, cols);
        else if (cols)
            snprintf(want, sizeof want, "(n, %d)", cols);
        else if (n >= 0)
            snprintf(want, sizeof want, "(%zd,)", n);
        else
            snprintf(want, sizeof want, "(n,)");
        PyObject *shape = PyObject_GetAttrString((PyObject *)a, "shape");
        PyErr_Format(sdpy_input_error, "%s: expected an array of shape %s, got shape %R", name, want, shape);
        Py_XDECREF(shape);
        Py_DECREF(a);
        return NULL;
    }
    const double *d = PyArray_DATA(a);
    npy_intp size = PyArray_SIZE(a);
    for (npy_intp k = 0; k < size; ++k)
        if (!isfinite(d[k])) {
            PyErr_Format(sdpy_input_error, "%s: value %zd (row %zd) is not finite", name, (Py_ssize_t)k,
                         (Py_ssize_t)(cols ? k / cols : k));
            Py_DECREF(a);
            return NULL;
        }
    return a;
}

PyArrayObject *sdpy_ids(PyObject *o, const char *name)
{
    if (o == NULL || o == Py_None)
        return NULL;
    PyArrayObject *a = (PyArrayObject *)PyArray_FROMANY(o, NPY_UINT64, 1, 1, NPY_ARRAY_CARRAY_RO | NPY_ARRAY_FORCECAST);
    if (!a) {
        PyErr_Clear();
        PyErr_Format(sdpy_input_error, "%s: expected a one-dimensional array of stable ids", name);
    }
    return a;
}

int sdpy_field(PyObject *name)
{
    const char *s = PyUnicode_Check(name) ? PyUnicode_AsUTF8(name) : NULL;
    for (int f = 0; s && f < SD_FIELD_COUNT; ++f)
        if (strcmp(s, sd_field_name((sd_field)f)) == 0)
            return f;
    PyErr_Format(sdpy_input_error, "unknown field %R: expected one of position, velocity, angular_velocity, "
                                   "orientation, force, torque, radius, mass", name);
    return -1;
}

PyObject *sdpy_dict_doubles(const char *const *names, const double *values, size_t n)
{
    PyObject *d = PyDict_New();
    for (size_t k = 0; d && k < n; ++k) {
        PyObject *v = PyFloat_FromDouble(values[k]);
        if (!v || PyDict_SetItemString(d, names[k], v) < 0) {
            Py_XDECREF(v);
            Py_CLEAR(d);
        } else
            Py_DECREF(v);
    }
    return d;
}
