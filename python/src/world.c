/* world.c — shapedem.World: an sd_world built and stepped from Python,
 * every call a thin wrapper of one public C call (the headers of include/shapedem/).
 *
 * Invariant: arguments are converted and checked (convert.c) before the
 * engine is called, and the engine checks everything before it changes
 * anything, so a call that raises leaves the world as it was; step()
 * releases the GIL with the world marked busy, and every method refuses a
 * busy world (another thread stepping it) instead of racing it.
 */
#include "common.h"

#include <string.h>

int sdpy_world_usable(PyWorld *self)
{
    if (!self->w) {
        PyErr_SetString(sdpy_error, "the world is closed");
        return -1;
    }
    if (self->busy) {
        PyErr_SetString(sdpy_error, "the world is stepping in another thread");
        return -1;
    }
    return 0;
}

#define SDPY_USABLE(self)                                                                          \
    do {                                                                                           \
        if (sdpy_world_usable(self) < 0)                                                           \
            return NULL;                                                                           \
    } while (0)

PyObject *sdpy_world_wrap(sd_world *w, PyObject *owner)
{
    PyWorld *o = PyObject_New(PyWorld, &sdpy_world_type);
    if (!o) {
        sd_world_destroy(w);
        return NULL;
    }
    o->w = w;
    o->busy = 0;
    Py_XINCREF(owner);
    o->owner = owner;
    return (PyObject *)o;
}

static void sdpy_world_dealloc(PyWorld *self)
{
    sd_world_destroy(self->w);
    Py_XDECREF(self->owner);
    PyObject_Free(self);
}

/* a periodic mask from "x", "xy", "xyz", ... */
static int sdpy_periodic(const char *s, unsigned *out)
{
    *out = 0;
    for (; *s; ++s) {
        if (*s == 'x')
            *out |= SD_PERIODIC_X;
        else if (*s == 'y')
            *out |= SD_PERIODIC_Y;
        else if (*s == 'z')
            *out |= SD_PERIODIC_Z;
        else {
            PyErr_Format(sdpy_input_error, "periodic: expected the letters of the periodic axes (\"xy\"), got %c", *s);
            return -1;
        }
    }
    return 0;
}

static PyObject *sdpy_world_new(PyTypeObject *type, PyObject *args, PyObject *kw)
{
    static char *names[] = {"dt", "gravity", "dimension", "seed", "threads", "law", "skin", "solver",
                            "local_damping", "periodic", "domain_lo", "domain_hi", "multi_contact", "backend",
                            "max_overlap", NULL};
    sd_world_def d = sd_world_def_default();
    PyObject *gravity = NULL, *lo = NULL, *hi = NULL;
    unsigned long long seed = d.seed;
    const char *law = "hertz_mindlin", *solver = "cells", *periodic = "", *multi = "average", *backend = "auto";
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|$dOiKisdsdsOOssd", names, &d.dt, &gravity, &d.dimension, &seed,
                                     &d.threads, &law, &d.skin, &solver, &d.local_damping, &periodic, &lo, &hi,
                                     &multi, &backend, &d.max_overlap))
        return NULL;
    d.seed = seed;
    if ((gravity && sdpy_v3(gravity, "gravity", &d.gravity) < 0) || (lo && sdpy_v3(lo, "domain_lo", &d.domain_lo) < 0) ||
        (hi && sdpy_v3(hi, "domain_hi", &d.domain_hi) < 0) || sdpy_periodic(periodic, &d.periodic) < 0)
        return NULL;
    d.law = sd_contact_law_from_name(law);
    if (d.law == SD_LAW_COUNT)
        return PyErr_Format(sdpy_input_error, "law: unknown contact law '%s'", law);
    if (strcmp(solver, "cells") == 0 || strcmp(solver, "grid") == 0)
        d.solver = solver[0] == 'g' ? SD_SOLVER_GRID : SD_SOLVER_CELLS;
    else
        return PyErr_Format(sdpy_input_error, "solver: expected 'cells' or 'grid', got '%s'", solver);
    if (strcmp(multi, "average") == 0 || strcmp(multi, "sum") == 0)
        d.multi_contact = multi[0] == 's' ? SD_MULTI_CONTACT_SUM : SD_MULTI_CONTACT_AVERAGE;
    else
        return PyErr_Format(sdpy_input_error, "multi_contact: expected 'average' or 'sum', got '%s'", multi);
    d.backend = sd_backend_kind_from_name(backend);
    if (d.backend == SD_BACKEND_COUNT)
        return PyErr_Format(sdpy_input_error, "backend: expected 'auto', 'cpu' or 'cuda', got '%s'", backend);
    sd_world *w;
    sd_error err;
    if (sd_world_create(&d, &w, &err) != SD_OK)
        return sdpy_raise(&err);
    (void)type;
    return sdpy_world_wrap(w, NULL);
}

/* ---- materials ---------------------------------------------------------------- */

static PyObject *sdpy_world_add_material(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"name", "density", "youngs_modulus", "poisson_ratio", "restitution", "friction",
                            "rolling_friction", "stiffness", "tangential_stiffness_ratio", "damping",
                            "volume_stiffness", "volume_face_omega_dt", NULL};
    SDPY_USABLE(self);
    sd_material_def m = sd_material_def_default();
    const char *name = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|$zddddddddddd", names, &name, &m.density, &m.youngs_modulus,
                                     &m.poisson_ratio, &m.restitution, &m.friction, &m.rolling_friction, &m.stiffness,
                                     &m.tangential_stiffness_ratio, &m.damping, &m.volume_stiffness,
                                     &m.volume_face_omega_dt))
        return NULL;
    if (name)
        m.name = name;
    sd_error err;
    int k = sd_world_add_material(self->w, &m, &err);
    return k < 0 ? sdpy_raise(&err) : PyLong_FromLong(k);
}

static PyObject *sdpy_world_set_interaction(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"a", "b", "restitution", "friction", "rolling_friction", "stiffness", "damping",
                            "volume_stiffness", "law", NULL};
    SDPY_USABLE(self);
    sd_interaction_def d = sd_interaction_def_default();
    int a, b;
    const char *law = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "ii|$ddddddz", names, &a, &b, &d.restitution, &d.friction,
                                     &d.rolling_friction, &d.stiffness, &d.damping, &d.volume_stiffness, &law))
        return NULL;
    if (law) {
        d.law = (int)sd_contact_law_from_name(law);
        if (d.law == SD_LAW_COUNT)
            return PyErr_Format(sdpy_input_error, "law: unknown contact law '%s'", law);
    }
    sd_error err;
    if (sd_world_set_interaction(self->w, a, b, &d, &err) != SD_OK)
        return sdpy_raise(&err);
    Py_RETURN_NONE;
}

static PyObject *sdpy_world_find_material(PyWorld *self, PyObject *arg)
{
    SDPY_USABLE(self);
    const char *name = PyUnicode_AsUTF8(arg);
    return name ? PyLong_FromLong(sd_world_find_material(self->w, name)) : NULL;
}

/* ---- particles -------------------------------------------------------------------- */

/* the stable ids of storage rows first .. count - 1 (just appended), or
 * None when the solver does not show them yet (the grid's, before prepare) */
static PyObject *sdpy_new_ids(PyWorld *self, size_t first)
{
    size_t count = sd_world_particle_count(self->w);
    npy_intp dims[1] = {(npy_intp)(count > first ? count - first : 0)};
    PyObject *ids = PyArray_SimpleNew(1, dims, NPY_UINT64);
    if (!ids)
        return NULL;
    uint64_t *d = PyArray_DATA((PyArrayObject *)ids);
    for (size_t k = first; k < count; ++k) {
        sd_particle_state ps;
        if (sd_world_get_particle(self->w, k, &ps) != SD_OK) {
            Py_DECREF(ids);
            Py_RETURN_NONE;
        }
        d[k - first] = ps.id;
    }
    return ids;
}

/* optional (n, 3) rows: NULL object gives NULL with no error */
static int sdpy_opt_rows(PyObject *o, const char *name, Py_ssize_t n, int cols, PyArrayObject **out)
{
    *out = NULL;
    if (!o || o == Py_None)
        return 0;
    *out = sdpy_rows(o, name, n, cols, 0);
    return *out ? 0 : -1;
}

static PyObject *sdpy_world_add_spheres(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"positions", "radii", "material", "velocities", "angular_velocities", NULL};
    SDPY_USABLE(self);
    PyObject *pos_o, *rad_o, *vel_o = NULL, *ang_o = NULL;
    int material;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "OOi|OO", names, &pos_o, &rad_o, &material, &vel_o, &ang_o))
        return NULL;
    PyArrayObject *pos = sdpy_rows(pos_o, "positions", -1, 3, 0), *rad = NULL, *vel = NULL, *ang = NULL;
    PyObject *out = NULL;
    if (!pos)
        return NULL;
    Py_ssize_t n = PyArray_DIM(pos, 0);
    rad = sdpy_rows(rad_o, "radii", n, 0, 1);
    if (!rad || sdpy_opt_rows(vel_o, "velocities", n, 3, &vel) < 0 ||
        sdpy_opt_rows(ang_o, "angular_velocities", n, 3, &ang) < 0)
        goto done;
    const double *x = PyArray_DATA(pos), *r = PyArray_DATA(rad);
    for (Py_ssize_t k = 0; k < n; ++k)
        if (!(r[k] > 0)) {
            char msg[128];
            PyOS_snprintf(msg, sizeof msg, "radii: radius %zd is %.17g, expected > 0", k, r[k]);
            PyErr_SetString(sdpy_input_error, msg);
            goto done;
        }
    sd_sphere_def *defs = PyMem_Calloc((size_t)n + 1, sizeof *defs);
    if (!defs) {
        PyErr_NoMemory();
        goto done;
    }
    for (Py_ssize_t k = 0; k < n; ++k) {
        defs[k].position = (sd_v3d){x[3 * k], x[3 * k + 1], x[3 * k + 2]};
        defs[k].radius = r[k];
        defs[k].material = material;
        if (vel) {
            const double *v = (const double *)PyArray_DATA(vel) + 3 * k;
            defs[k].velocity = (sd_v3d){v[0], v[1], v[2]};
        }
        if (ang) {
            const double *v = (const double *)PyArray_DATA(ang) + 3 * k;
            defs[k].angular_velocity = (sd_v3d){v[0], v[1], v[2]};
        }
    }
    size_t first = sd_world_particle_count(self->w);
    sd_error err;
    sd_status st = sd_world_add_spheres(self->w, (size_t)n, defs, &err);
    PyMem_Free(defs);
    out = st == SD_OK ? sdpy_new_ids(self, first) : sdpy_raise(&err);
done:
    Py_XDECREF(pos);
    Py_XDECREF(rad);
    Py_XDECREF(vel);
    Py_XDECREF(ang);
    return out;
}

static PyObject *sdpy_world_add_bodies(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"shape", "positions", "material", "orientations", "velocities", "angular_velocities",
                            NULL};
    SDPY_USABLE(self);
    PyObject *pos_o, *q_o = NULL, *vel_o = NULL, *ang_o = NULL;
    int shape, material;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "iOi|OOO", names, &shape, &pos_o, &material, &q_o, &vel_o, &ang_o))
        return NULL;
    PyArrayObject *pos = sdpy_rows(pos_o, "positions", -1, 3, 0), *q = NULL, *vel = NULL, *ang = NULL;
    PyObject *out = NULL;
    if (!pos)
        return NULL;
    Py_ssize_t n = PyArray_DIM(pos, 0);
    if (sdpy_opt_rows(q_o, "orientations", n, 4, &q) < 0 || sdpy_opt_rows(vel_o, "velocities", n, 3, &vel) < 0 ||
        sdpy_opt_rows(ang_o, "angular_velocities", n, 3, &ang) < 0)
        goto done;
    sd_body_def *defs = PyMem_Calloc((size_t)n + 1, sizeof *defs);
    if (!defs) {
        PyErr_NoMemory();
        goto done;
    }
    const double *x = PyArray_DATA(pos);
    for (Py_ssize_t k = 0; k < n; ++k) {
        defs[k].position = (sd_v3d){x[3 * k], x[3 * k + 1], x[3 * k + 2]};
        defs[k].shape = shape;
        defs[k].material = material;
        if (q)
            memcpy(defs[k].orientation, (const double *)PyArray_DATA(q) + 4 * k, 4 * sizeof(double));
        if (vel) {
            const double *v = (const double *)PyArray_DATA(vel) + 3 * k;
            defs[k].velocity = (sd_v3d){v[0], v[1], v[2]};
        }
        if (ang) {
            const double *v = (const double *)PyArray_DATA(ang) + 3 * k;
            defs[k].angular_velocity = (sd_v3d){v[0], v[1], v[2]};
        }
    }
    size_t first = sd_world_particle_count(self->w);
    sd_error err;
    sd_status st = sd_world_add_bodies(self->w, (size_t)n, defs, &err);
    PyMem_Free(defs);
    out = st == SD_OK ? sdpy_new_ids(self, first) : sdpy_raise(&err);
done:
    Py_XDECREF(pos);
    Py_XDECREF(q);
    Py_XDECREF(vel);
    Py_XDECREF(ang);
    return out;
}

/* ---- shapes ------------------------------------------------------------------------ */

static PyObject *sdpy_world_add_shape(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"name", "kind", "size", "rounding", "margin", "scale", "vertices", NULL};
    SDPY_USABLE(self);
    sd_shape_desc d = sd_shape_desc_default();
    const char *name;
    PyObject *size_o = NULL, *vert_o = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "ss|$OdddO", names, &name, &d.kind, &size_o, &d.rounding, &d.margin,
                                     &d.scale, &vert_o))
        return NULL;
    if (size_o && PyFloat_Check(size_o))
        d.size.x = PyFloat_AsDouble(size_o); /* a sphere's radius */
    else if (size_o && sdpy_v3(size_o, "size", &d.size) < 0)
        return NULL;
    PyArrayObject *v = NULL;
    if (sdpy_opt_rows(vert_o, "vertices", -1, 3, &v) < 0)
        return NULL;
    if (v) {
        d.vertices = (const sd_v3d *)PyArray_DATA(v);
        d.vertex_count = (size_t)PyArray_DIM(v, 0);
    }
    sd_error err;
    int k = sd_world_add_shape(self->w, name, &d, &err);
    Py_XDECREF(v);
    return k < 0 ? sdpy_raise(&err) : PyLong_FromLong(k);
}

static PyObject *sdpy_world_add_composite(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"name", "elements", "lattice", NULL};
    SDPY_USABLE(self);
    const char *name;
    PyObject *elements;
    sd_composite_desc d = sd_composite_desc_default();
    if (!PyArg_ParseTupleAndKeywords(args, kw, "sO|$i", names, &name, &elements, &d.lattice))
        return NULL;
    PyObject *seq = PySequence_Fast(elements, "elements: expected a list of (shape, position[, orientation])");
    if (!seq)
        return NULL;
    Py_ssize_t n = PySequence_Fast_GET_SIZE(seq);
    sd_composite_element *el = PyMem_Calloc((size_t)n + 1, sizeof *el);
    PyObject *out = NULL;
    if (!el) {
        Py_DECREF(seq);
        return PyErr_NoMemory();
    }
    for (Py_ssize_t k = 0; k < n; ++k) {
        PyObject *pos = NULL, *q = NULL;
        PyObject *item = PySequence_Fast_GET_ITEM(seq, k);
        if (!PyTuple_Check(item) || !PyArg_ParseTuple(item, "iO|O", &el[k].shape, &pos, &q)) {
            PyErr_Clear();
            PyErr_Format(sdpy_input_error, "elements[%zd]: expected (shape index, position[, orientation (w, x, y, z)])",
                         k);
            goto done;
        }
        if (sdpy_v3(pos, "elements[].position", &el[k].position) < 0)
            goto done;
        if (q && q != Py_None) {
            PyArrayObject *qa = sdpy_rows(q, "elements[].orientation", 1, 4, 0);
            if (!qa)
                goto done;
            memcpy(el[k].orientation, PyArray_DATA(qa), 4 * sizeof(double));
            Py_DECREF(qa);
        }
    }
    d.elements = el;
    d.element_count = (size_t)n;
    sd_error err;
    int k = sd_world_add_composite(self->w, name, &d, &err);
    out = k < 0 ? sdpy_raise(&err) : PyLong_FromLong(k);
done:
    PyMem_Free(el);
    Py_DECREF(seq);
    return out;
}

static PyObject *sdpy_world_add_composite_preset(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"name", "preset", "length", "diameter", "width", "thickness", "count", NULL};
    SDPY_USABLE(self);
    const char *name;
    sd_composite_preset_def d = sd_composite_preset_def_default();
    if (!PyArg_ParseTupleAndKeywords(args, kw, "ss|$ddddi", names, &name, &d.preset, &d.length, &d.diameter, &d.width,
                                     &d.thickness, &d.count))
        return NULL;
    sd_error err;
    int k = sd_world_add_composite_preset(self->w, name, &d, &err);
    return k < 0 ? sdpy_raise(&err) : PyLong_FromLong(k);
}

static PyObject *sdpy_world_add_shape2d(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"name", "kind", "radius", "semi_axes", "points", "fourier_a", "fourier_b", NULL};
    SDPY_USABLE(self);
    const char *name;
    sd_shape2d_def d = sd_shape2d_def_default();
    PyObject *axes_o = NULL, *pts_o = NULL, *a_o = NULL, *b_o = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "ss|$dOOOO", names, &name, &d.kind, &d.radius, &axes_o, &pts_o, &a_o,
                                     &b_o))
        return NULL;
    PyArrayObject *axes = NULL, *pts = NULL, *fa = NULL, *fb = NULL;
    PyObject *out = NULL;
    if (sdpy_opt_rows(axes_o, "semi_axes", 1, 2, &axes) < 0 || sdpy_opt_rows(pts_o, "points", -1, 2, &pts) < 0 ||
        sdpy_opt_rows(a_o, "fourier_a", -1, 0, &fa) < 0 ||
        sdpy_opt_rows(b_o, "fourier_b", fa ? PyArray_DIM(fa, 0) - 1 : -1, 0, &fb) < 0)
        goto done;
    if (axes)
        memcpy(d.semi_axes, PyArray_DATA(axes), 2 * sizeof(double));
    if (pts) {
        d.points = PyArray_DATA(pts);
        d.point_count = (size_t)PyArray_DIM(pts, 0);
    }
    if (fa) {
        d.fourier_a = PyArray_DATA(fa);
        d.order = (int)PyArray_DIM(fa, 0) - 1;
        d.fourier_b = fb ? PyArray_DATA(fb) : NULL;
    }
    sd_error err;
    int k = sd_world_add_shape2d(self->w, name, &d, &err);
    out = k < 0 ? sdpy_raise(&err) : PyLong_FromLong(k);
done:
    Py_XDECREF(axes);
    Py_XDECREF(pts);
    Py_XDECREF(fa);
    Py_XDECREF(fb);
    return out;
}

static PyObject *sdpy_world_find_shape(PyWorld *self, PyObject *arg)
{
    SDPY_USABLE(self);
    const char *name = PyUnicode_AsUTF8(arg);
    return name ? PyLong_FromLong(sd_world_find_shape(self->w, name)) : NULL;
}

static PyObject *sdpy_v3_tuple(sd_v3d v)
{
    return Py_BuildValue("(ddd)", v.x, v.y, v.z);
}

static PyObject *sdpy_world_shape(PyWorld *self, PyObject *arg)
{
    SDPY_USABLE(self);
    Py_ssize_t k = PyLong_AsSsize_t(arg);
    if (k == -1 && PyErr_Occurred())
        return NULL;
    sd_shape_info si;
    if (k < 0 || sd_world_get_shape(self->w, (size_t)k, &si) != SD_OK)
        return PyErr_Format(PyExc_IndexError, "shape %zd: the world has %zu shapes", k,
                            sd_world_shape_count(self->w));
    return Py_BuildValue("{s:s,s:s,s:d,s:d,s:d,s:N,s:N,s:d,s:n,s:n,s:n}", "name", si.name, "kind", si.kind, "volume",
                         si.volume, "bounding_radius", si.bounding_radius, "equivalent_radius", si.equivalent_radius,
                         "inertia", sdpy_v3_tuple(si.inertia), "center_of_mass", sdpy_v3_tuple(si.center_of_mass),
                         "rounding", si.rounding, "vertex_count", (Py_ssize_t)si.vertex_count, "face_count",
                         (Py_ssize_t)si.face_count, "element_count", (Py_ssize_t)si.element_count);
}

/* ---- walls ----------------------------------------------------------------------- */

static PyObject *sdpy_world_add_plane(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"name", "point", "normal", "material", NULL};
    SDPY_USABLE(self);
    const char *name;
    PyObject *p_o, *n_o;
    int material;
    sd_v3d p, nrm;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "sOOi", names, &name, &p_o, &n_o, &material) ||
        sdpy_v3(p_o, "point", &p) < 0 || sdpy_v3(n_o, "normal", &nrm) < 0)
        return NULL;
    sd_error err;
    int k = sd_world_add_plane(self->w, name, p, nrm, material, &err);
    return k < 0 ? sdpy_raise(&err) : PyLong_FromLong(k);
}

static PyObject *sdpy_world_add_box(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"name", "lo", "hi", "material", "open_faces", NULL};
    static const char *faces[] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
    SDPY_USABLE(self);
    const char *name;
    PyObject *lo_o, *hi_o, *open_o = NULL;
    int material;
    sd_v3d lo, hi;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "sOOi|O", names, &name, &lo_o, &hi_o, &material, &open_o) ||
        sdpy_v3(lo_o, "lo", &lo) < 0 || sdpy_v3(hi_o, "hi", &hi) < 0)
        return NULL;
    unsigned mask = 0;
    if (open_o && open_o != Py_None) {
        PyObject *seq = PySequence_Fast(open_o, "open_faces: expected a list of face names (\"zmax\", ...)");
        if (!seq)
            return NULL;
        for (Py_ssize_t k = 0; k < PySequence_Fast_GET_SIZE(seq); ++k) {
            const char *f = PyUnicode_Check(PySequence_Fast_GET_ITEM(seq, k))
                                ? PyUnicode_AsUTF8(PySequence_Fast_GET_ITEM(seq, k))
                                : NULL;
            unsigned bit = 0;
            for (unsigned j = 0; f && j < 6; ++j)
                if (strcmp(f, faces[j]) == 0)
                    bit = 1u << j;
            if (!bit) {
                Py_DECREF(seq);
                return PyErr_Format(sdpy_input_error, "open_faces[%zd]: expected xmin, xmax, ymin, ymax, zmin or zmax", k);
            }
            mask |= bit;
        }
        Py_DECREF(seq);
    }
    sd_error err;
    int k = sd_world_add_box(self->w, name, lo, hi, mask, material, &err);
    return k < 0 ? sdpy_raise(&err) : PyLong_FromLong(k);
}

static PyObject *sdpy_world_add_drum(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"name", "center", "axis", "radius", "length", "material", "rpm", "start", "ramp",
                            "open_lo", "open_hi", NULL};
    SDPY_USABLE(self);
    sd_drum_def d = sd_drum_def_default();
    PyObject *c_o, *a_o;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "sOOddi|$ddddpp", names, &d.name, &c_o, &a_o, &d.radius, &d.length,
                                     &d.material, &d.rpm, &d.start, &d.ramp, &d.open_lo, &d.open_hi) ||
        sdpy_v3(c_o, "center", &d.center) < 0 || sdpy_v3(a_o, "axis", &d.axis) < 0)
        return NULL;
    sd_error err;
    int k = sd_world_add_drum(self->w, &d, &err);
    return k < 0 ? sdpy_raise(&err) : PyLong_FromLong(k);
}

static PyObject *sdpy_world_add_mesh(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"name", "vertices", "triangles", "material", "outside", "weld_tolerance",
                            "coplanar_tolerance", NULL};
    SDPY_USABLE(self);
    const char *name;
    PyObject *v_o, *t_o;
    sd_mesh_def d = sd_mesh_def_default();
    if (!PyArg_ParseTupleAndKeywords(args, kw, "sOOi|$pdd", names, &name, &v_o, &t_o, &d.material, &d.outside,
                                     &d.weld_tolerance, &d.coplanar_tolerance))
        return NULL;
    PyArrayObject *v = sdpy_rows(v_o, "vertices", -1, 3, 0);
    if (!v)
        return NULL;
    PyArrayObject *t = (PyArrayObject *)PyArray_FROMANY(t_o, NPY_INT64, 2, 2, NPY_ARRAY_CARRAY_RO);
    if (!t || PyArray_DIM(t, 1) != 3) {
        PyErr_Clear();
        Py_XDECREF(t);
        Py_DECREF(v);
        return PyErr_Format(sdpy_input_error, "triangles: expected an integer array of shape (m, 3)");
    }
    Py_ssize_t nt = PyArray_DIM(t, 0), nv = PyArray_DIM(v, 0);
    uint32_t(*tri)[3] = PyMem_Calloc((size_t)nt + 1, sizeof *tri);
    PyObject *out = NULL;
    const int64_t *ti = PyArray_DATA(t);
    if (!tri) {
        PyErr_NoMemory();
        goto done;
    }
    for (Py_ssize_t k = 0; k < 3 * nt; ++k) {
        if (ti[k] < 0 || ti[k] >= nv) {
            PyErr_Format(sdpy_input_error, "triangles: row %zd names vertex %lld, expected 0 .. %zd", k / 3,
                         (long long)ti[k], nv - 1);
            goto done;
        }
        tri[k / 3][k % 3] = (uint32_t)ti[k];
    }
    d.vertices = (const sd_v3d *)PyArray_DATA(v);
    d.vertex_count = (size_t)nv;
    d.triangles = (const uint32_t(*)[3])tri;
    d.triangle_count = (size_t)nt;
    sd_error err;
    int k = sd_world_add_mesh(self->w, name, &d, &err);
    out = k < 0 ? sdpy_raise(&err) : PyLong_FromLong(k);
done:
    PyMem_Free(tri);
    Py_DECREF(t);
    Py_DECREF(v);
    return out;
}

static PyObject *sdpy_world_set_wall_motion(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"wall", "velocity", "move_start", "move_end", "servo_stress", "servo_start",
                            "servo_end", "servo_gain", "servo_max_speed", NULL};
    SDPY_USABLE(self);
    sd_wall_motion_def d = sd_wall_motion_def_default();
    int wall;
    PyObject *v_o = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "i|$Odddddddd", names, &wall, &v_o, &d.move_start, &d.move_end,
                                     &d.servo_stress, &d.servo_start, &d.servo_end, &d.servo_gain,
                                     &d.servo_max_speed) ||
        (v_o && sdpy_v3(v_o, "velocity", &d.velocity) < 0))
        return NULL;
    sd_error err;
    if (sd_world_set_wall_motion(self->w, wall, &d, &err) != SD_OK)
        return sdpy_raise(&err);
    Py_RETURN_NONE;
}

static PyObject *sdpy_world_set_mesh_motion(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"wall", "kind", "velocity", "axis_point", "axis", "rpm", "start", "ramp", "table", NULL};
    static const char *kinds[] = {"fixed", "translate", "rotate", "table"};
    SDPY_USABLE(self);
    sd_mesh_motion_def d = sd_mesh_motion_def_default();
    int wall;
    const char *kind;
    PyObject *v_o = NULL, *p_o = NULL, *a_o = NULL, *t_o = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "is|$OOOdddO", names, &wall, &kind, &v_o, &p_o, &a_o, &d.rpm,
                                     &d.start, &d.ramp, &t_o) ||
        (v_o && sdpy_v3(v_o, "velocity", &d.velocity) < 0) || (p_o && sdpy_v3(p_o, "axis_point", &d.axis_point) < 0) ||
        (a_o && sdpy_v3(a_o, "axis", &d.axis) < 0))
        return NULL;
    d.kind = -1;
    for (int k = 0; k < 4; ++k)
        if (strcmp(kind, kinds[k]) == 0)
            d.kind = k; /* SD_MESH_FIXED .. SD_MESH_TABLE in this order */
    if (d.kind < 0)
        return PyErr_Format(sdpy_input_error, "kind: expected fixed, translate, rotate or table, got '%s'", kind);
    PyArrayObject *t = NULL;
    if (sdpy_opt_rows(t_o, "table", -1, 5, &t) < 0)
        return NULL;
    if (t) {
        d.table = PyArray_DATA(t);
        d.table_rows = (size_t)PyArray_DIM(t, 0);
    }
    sd_error err;
    sd_status st = sd_world_set_mesh_motion(self->w, wall, &d, &err);
    Py_XDECREF(t);
    if (st != SD_OK)
        return sdpy_raise(&err);
    Py_RETURN_NONE;
}

static PyObject *sdpy_world_wall(PyWorld *self, PyObject *arg)
{
    SDPY_USABLE(self);
    Py_ssize_t k = PyLong_AsSsize_t(arg);
    if (k == -1 && PyErr_Occurred())
        return NULL;
    sd_wall_info wi;
    if (k < 0 || sd_world_get_wall(self->w, (size_t)k, &wi) != SD_OK)
        return PyErr_Format(PyExc_IndexError, "wall %zd: the world has %zu walls", k, sd_world_wall_count(self->w));
    return Py_BuildValue("{s:s,s:i,s:N,s:N,s:N,s:N,s:N,s:N,s:I,s:i,s:N,s:N}", "name", wi.name, "kind", wi.kind,
                         "force", sdpy_v3_tuple(wi.force), "torque", sdpy_v3_tuple(wi.torque), "point",
                         sdpy_v3_tuple(wi.point), "normal", sdpy_v3_tuple(wi.normal), "lo", sdpy_v3_tuple(wi.lo),
                         "hi", sdpy_v3_tuple(wi.hi), "open_faces", wi.open_faces, "material", wi.material,
                         "velocity", sdpy_v3_tuple(wi.velocity), "angular_velocity",
                         sdpy_v3_tuple(wi.angular_velocity));
}

/* ---- stepping ------------------------------------------------------------------------ */

static PyObject *sdpy_world_prepare(PyWorld *self, PyObject *unused)
{
    SDPY_USABLE(self);
    sd_error err;
    if (sd_world_prepare(self->w, &err) != SD_OK)
        return sdpy_raise(&err);
    Py_RETURN_NONE;
}

static PyObject *sdpy_world_step(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"steps", NULL};
    long steps = 1;
    SDPY_USABLE(self);
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|l", names, &steps))
        return NULL;
    if (steps < 0)
        return PyErr_Format(sdpy_input_error, "steps: %ld, expected >= 0", steps);
    sd_error err;
    sd_status st;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS
    st = sd_world_step(self->w, steps, &err);
    Py_END_ALLOW_THREADS
    self->busy = 0;
    if (st != SD_OK)
        return sdpy_raise(&err);
    Py_RETURN_NONE;
}

/* ---- state ------------------------------------------------------------------------- */

static PyObject *sdpy_world_ids(PyWorld *self, PyObject *unused)
{
    SDPY_USABLE(self);
    npy_intp dims[1] = {(npy_intp)sd_world_particle_count(self->w)};
    PyObject *a = PyArray_SimpleNew(1, dims, NPY_UINT64);
    sd_error err;
    if (a && sd_world_get_ids(self->w, PyArray_DATA((PyArrayObject *)a), (size_t)dims[0], &err) != SD_OK) {
        Py_DECREF(a);
        return sdpy_raise(&err);
    }
    return a;
}

static PyObject *sdpy_world_get(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"field", "ids", NULL};
    SDPY_USABLE(self);
    PyObject *name, *ids_o = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O|O", names, &name, &ids_o))
        return NULL;
    int f = sdpy_field(name);
    if (f < 0)
        return NULL;
    PyArrayObject *ids = sdpy_ids(ids_o, "ids");
    if (!ids && PyErr_Occurred())
        return NULL;
    size_t n = ids ? (size_t)PyArray_DIM(ids, 0) : sd_world_particle_count(self->w);
    size_t c = sd_field_components((sd_field)f);
    npy_intp dims[2] = {(npy_intp)n, (npy_intp)c};
    PyObject *a = PyArray_SimpleNew(c > 1 ? 2 : 1, dims, NPY_DOUBLE);
    sd_error err;
    if (a && sd_world_get_field(self->w, (sd_field)f, ids ? PyArray_DATA(ids) : NULL, n,
                                PyArray_DATA((PyArrayObject *)a), n * c, &err) != SD_OK) {
        Py_CLEAR(a);
        sdpy_raise(&err);
    }
    Py_XDECREF(ids);
    return a;
}

static PyObject *sdpy_world_set(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"field", "values", "ids", NULL};
    SDPY_USABLE(self);
    PyObject *name, *v_o, *ids_o = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "OO|O", names, &name, &v_o, &ids_o))
        return NULL;
    int f = sdpy_field(name);
    if (f < 0)
        return NULL;
    PyArrayObject *ids = sdpy_ids(ids_o, "ids");
    if (!ids && PyErr_Occurred())
        return NULL;
    size_t n = ids ? (size_t)PyArray_DIM(ids, 0) : sd_world_particle_count(self->w);
    int c = (int)sd_field_components((sd_field)f);
    PyArrayObject *v = sdpy_rows(v_o, "values", (Py_ssize_t)n, c > 1 ? c : 0, 0);
    PyObject *out = NULL;
    if (v) {
        sd_error err;
        if (sd_world_set_field(self->w, (sd_field)f, ids ? PyArray_DATA(ids) : NULL, n, PyArray_DATA(v),
                               n * (size_t)c, &err) != SD_OK)
            sdpy_raise(&err);
        else
            out = Py_NewRef(Py_None);
    }
    Py_XDECREF(ids);
    Py_XDECREF(v);
    return out;
}

static PyObject *sdpy_world_stats(PyWorld *self, PyObject *unused)
{
    SDPY_USABLE(self);
    sd_stats s;
    sd_world_stats(self->w, &s);
    return Py_BuildValue("{s:d,s:l,s:d,s:d,s:d,s:d,s:l,s:l,s:d,s:d,s:l,s:n}", "time", s.time, "step", s.step,
                         "kinetic_translational", s.kinetic_translational, "kinetic_rotational",
                         s.kinetic_rotational, "potential_gravity", s.potential_gravity, "potential_elastic",
                         s.potential_elastic, "contacts", s.contacts, "wall_contacts", s.wall_contacts,
                         "max_overlap_ratio", s.max_overlap_ratio, "max_speed", s.max_speed, "rebuilds",
                         s.rebuilds, "pairs", (Py_ssize_t)s.pairs);
}

static PyObject *sdpy_world_kinetic_energy(PyWorld *self, PyObject *unused)
{
    SDPY_USABLE(self);
    sd_stats s;
    sd_world_stats(self->w, &s);
    return PyFloat_FromDouble(s.kinetic_translational + s.kinetic_rotational);
}

static PyObject *sdpy_world_recommended_dt(PyWorld *self, PyObject *unused)
{
    SDPY_USABLE(self);
    double tc = 0;
    double dt = sd_world_recommended_dt(self->w, &tc);
    return Py_BuildValue("(dd)", dt, tc);
}

static PyObject *sdpy_world_checkpoint(PyWorld *self, PyObject *arg)
{
    SDPY_USABLE(self);
    PyObject *path = NULL;
    if (!PyUnicode_FSConverter(arg, &path))
        return NULL;
    sd_error err;
    sd_status st = sd_checkpoint_write(self->w, PyBytes_AS_STRING(path), &err);
    Py_DECREF(path);
    if (st != SD_OK)
        return sdpy_raise(&err);
    Py_RETURN_NONE;
}

static PyObject *sdpy_world_restore(PyWorld *self, PyObject *arg)
{
    SDPY_USABLE(self);
    PyObject *path = NULL;
    if (!PyUnicode_FSConverter(arg, &path))
        return NULL;
    sd_error err;
    sd_status st = sd_checkpoint_restore(self->w, PyBytes_AS_STRING(path), &err);
    Py_DECREF(path);
    if (st != SD_OK)
        return sdpy_raise(&err);
    Py_RETURN_NONE;
}

/* ---- analyses (analysis.h) ---------------------------------------------------------- */

static PyObject *sdpy_fit_dict(const sd_surface_fit *f)
{
    return Py_BuildValue("{s:d,s:d,s:d,s:i}", "angle", f->angle, "slope", f->slope, "rms", f->rms, "columns",
                         f->columns);
}

static PyObject *sdpy_world_drum_surface(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"center", "axis", "radius", "length", "bins", "fit", NULL};
    SDPY_USABLE(self);
    sd_region_def r = {.kind = SD_REGION_CYLINDER};
    PyObject *c_o, *a_o;
    int bins = 20;
    double fit[2] = {0.2, 0.8};
    if (!PyArg_ParseTupleAndKeywords(args, kw, "OOdd|$i(dd)", names, &c_o, &a_o, &r.radius, &r.length, &bins, &fit[0],
                                     &fit[1]) ||
        sdpy_v3(c_o, "center", &r.center) < 0 || sdpy_v3(a_o, "axis", &r.axis) < 0)
        return NULL;
    sd_surface_fit f;
    sd_error err;
    if (sd_world_drum_surface(self->w, &r, bins, fit, &f, &err) != SD_OK)
        return sdpy_raise(&err);
    return sdpy_fit_dict(&f);
}

static PyObject *sdpy_world_heap_angle(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"center", "bins", "fit", NULL};
    SDPY_USABLE(self);
    PyObject *c_o = NULL;
    int bins = 20;
    double fit[2] = {0.2, 0.8};
    sd_v3d c;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|$Oi(dd)", names, &c_o, &bins, &fit[0], &fit[1]) ||
        (c_o && c_o != Py_None && sdpy_v3(c_o, "center", &c) < 0))
        return NULL;
    sd_surface_fit f;
    sd_error err;
    if (sd_world_heap_angle(self->w, c_o && c_o != Py_None ? &c : NULL, bins, fit, &f, &err) != SD_OK)
        return sdpy_raise(&err);
    return sdpy_fit_dict(&f);
}

static PyObject *sdpy_world_bed_height(PyWorld *self, PyObject *args, PyObject *kw)
{
    static char *names[] = {"fraction", "lo", "hi", NULL};
    SDPY_USABLE(self);
    double fraction = 0.5;
    PyObject *lo_o = NULL, *hi_o = NULL;
    sd_region_def r = {.kind = SD_REGION_NONE};
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|$dOO", names, &fraction, &lo_o, &hi_o))
        return NULL;
    if (lo_o || hi_o) {
        r.kind = SD_REGION_BOX;
        if (!lo_o || !hi_o)
            return PyErr_Format(sdpy_input_error, "bed_height: a region needs both lo and hi");
        if (sdpy_v3(lo_o, "lo", &r.lo) < 0 || sdpy_v3(hi_o, "hi", &r.hi) < 0)
            return NULL;
    }
    sd_bed_height b;
    sd_error err;
    if (sd_world_bed_height(self->w, r.kind ? &r : NULL, fraction, &b, &err) != SD_OK)
        return sdpy_raise(&err);
    return Py_BuildValue("{s:n,s:d,s:d,s:d}", "particles", (Py_ssize_t)b.particles, "top", b.top, "fraction_height",
                         b.fraction_height, "mean", b.mean);
}

/* ---- properties ------------------------------------------------------------------- */

#define SDPY_VIEW_GETTER(prop, field)                                                              \
    static PyObject *sdpy_world_##prop(PyWorld *self, void *unused)                                \
    {                                                                                              \
        return sdpy_view_new(self, field);                                                         \
    }
SDPY_VIEW_GETTER(positions, "position")
SDPY_VIEW_GETTER(velocities, "velocity")
SDPY_VIEW_GETTER(angular_velocities, "angular_velocity")
SDPY_VIEW_GETTER(orientations, "orientation")
SDPY_VIEW_GETTER(forces, "force")
SDPY_VIEW_GETTER(torques, "torque")
SDPY_VIEW_GETTER(radii, "radius")
SDPY_VIEW_GETTER(materials, "material")
SDPY_VIEW_GETTER(shapes, "shape")
SDPY_VIEW_GETTER(storage_ids, "id")
#undef SDPY_VIEW_GETTER

static PyObject *sdpy_world_particle_count(PyWorld *self, void *unused)
{
    SDPY_USABLE(self);
    return PyLong_FromSize_t(sd_world_particle_count(self->w));
}
static PyObject *sdpy_world_wall_count(PyWorld *self, void *unused)
{
    SDPY_USABLE(self);
    return PyLong_FromSize_t(sd_world_wall_count(self->w));
}
static PyObject *sdpy_world_shape_count(PyWorld *self, void *unused)
{
    SDPY_USABLE(self);
    return PyLong_FromSize_t(sd_world_shape_count(self->w));
}
static PyObject *sdpy_world_step_count(PyWorld *self, void *unused)
{
    SDPY_USABLE(self);
    return PyLong_FromLong(sd_world_step_count(self->w));
}
static PyObject *sdpy_world_time(PyWorld *self, void *unused)
{
    SDPY_USABLE(self);
    return PyFloat_FromDouble(sd_world_time(self->w));
}
static PyObject *sdpy_world_dt(PyWorld *self, void *unused)
{
    SDPY_USABLE(self);
    return PyFloat_FromDouble(sd_world_dt(self->w));
}
static PyObject *sdpy_world_threads(PyWorld *self, void *unused)
{
    SDPY_USABLE(self);
    return PyLong_FromLong(sd_world_threads(self->w));
}
static PyObject *sdpy_world_backend(PyWorld *self, void *unused)
{
    SDPY_USABLE(self);
    return PyUnicode_FromFormat("%s (%s)", sd_world_backend(self->w), sd_world_backend_note(self->w));
}
static PyObject *sdpy_world_generation(PyWorld *self, void *unused)
{
    SDPY_USABLE(self);
    return PyLong_FromUnsignedLongLong(sd_world_generation(self->w));
}
static PyObject *sdpy_world_material_names(PyWorld *self, void *unused)
{
    SDPY_USABLE(self);
    PyObject *l = PyList_New(0);
    const char *name;
    for (size_t k = 0; l && (name = sd_world_material_name(self->w, k)) != NULL; ++k) {
        PyObject *s = PyUnicode_FromString(name);
        if (!s || PyList_Append(l, s) < 0)
            Py_CLEAR(l);
        Py_XDECREF(s);
    }
    return l;
}

static Py_ssize_t sdpy_world_len(PyWorld *self)
{
    return sdpy_world_usable(self) < 0 ? -1 : (Py_ssize_t)sd_world_particle_count(self->w);
}

static PyGetSetDef sdpy_world_getset[] = {
    {"positions", (getter)sdpy_world_positions, NULL, "View (n, 3) of the centres of mass, m, storage order.", NULL},
    {"velocities", (getter)sdpy_world_velocities, NULL, "View (n, 3) of the velocities, m/s, storage order.", NULL},
    {"angular_velocities", (getter)sdpy_world_angular_velocities, NULL,
     "View (n, 3) of the angular velocities, rad/s, world frame, storage order.", NULL},
    {"orientations", (getter)sdpy_world_orientations, NULL,
     "View (n, 4) of the orientations (w, x, y, z), body to world, storage order.", NULL},
    {"forces", (getter)sdpy_world_forces, NULL, "View (n, 3) of the contact forces of the last step, N.", NULL},
    {"torques", (getter)sdpy_world_torques, NULL, "View (n, 3) of the contact torques of the last step, N m.", NULL},
    {"radii", (getter)sdpy_world_radii, NULL, "View (n,) of the radii (bounding radius of a shaped body), m.", NULL},
    {"materials", (getter)sdpy_world_materials, NULL, "View (n,) int32 of the material indices.", NULL},
    {"shapes", (getter)sdpy_world_shapes, NULL, "View (n,) int32 of the shape indices (-1: a plain sphere).", NULL},
    {"storage_ids", (getter)sdpy_world_storage_ids, NULL,
     "View (n,) uint64 of the stable id of each storage row (beside the other views).", NULL},
    {"particle_count", (getter)sdpy_world_particle_count, NULL, "Particles now (also len(world)).", NULL},
    {"wall_count", (getter)sdpy_world_wall_count, NULL, "Walls.", NULL},
    {"shape_count", (getter)sdpy_world_shape_count, NULL, "Shape templates.", NULL},
    {"step_count", (getter)sdpy_world_step_count, NULL, "Steps taken.", NULL},
    {"time", (getter)sdpy_world_time, NULL, "Simulated time, s.", NULL},
    {"dt", (getter)sdpy_world_dt, NULL, "Time step, s.", NULL},
    {"threads", (getter)sdpy_world_threads, NULL, "OpenMP threads the world steps with.", NULL},
    {"backend", (getter)sdpy_world_backend, NULL, "The backend and why it was chosen, e.g. 'cpu (...)'.", NULL},
    {"generation", (getter)sdpy_world_generation, NULL,
     "Counts the changes of the particle arrays' layout; a View of another generation is stale.", NULL},
    {"material_names", (getter)sdpy_world_material_names, NULL, "The materials' names, by index.", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

#define SDPY_KW(f) (PyCFunction)(void (*)(void))(f), METH_VARARGS | METH_KEYWORDS
static PyMethodDef sdpy_world_methods[] = {
    {"add_material", SDPY_KW(sdpy_world_add_material),
     "add_material(*, name=None, density, youngs_modulus, poisson_ratio, restitution, friction, ...) -> int\n\n"
     "Adds a material (sd_material_def's members as keywords; SI units) and returns its index."},
    {"set_interaction", SDPY_KW(sdpy_world_set_interaction),
     "set_interaction(a, b, *, restitution, friction, rolling_friction, stiffness, damping, volume_stiffness,\n"
     "law) -> None\n\nOverrides for the pair of materials a, b (a value left out keeps the mixed one)."},
    {"find_material", (PyCFunction)sdpy_world_find_material, METH_O,
     "find_material(name) -> int\n\nThe index of a material by name, or -1."},
    {"add_spheres", SDPY_KW(sdpy_world_add_spheres),
     "add_spheres(positions, radii, material, velocities=None, angular_velocities=None) -> numpy.ndarray\n\n"
     "Adds spheres (positions (n, 3), radii (n,) or one number) and returns their stable ids (uint64).\n"
     "Everything is checked first: a radius <= 0, a NaN or a wrong shape raises InputError, nothing added."},
    {"add_bodies", SDPY_KW(sdpy_world_add_bodies),
     "add_bodies(shape, positions, material, orientations=None, velocities=None, angular_velocities=None)\n"
     "-> numpy.ndarray\n\nAdds rigid bodies of a shape template (orientations (n, 4) as (w, x, y, z));\n"
     "returns their stable ids."},
    {"add_shape", SDPY_KW(sdpy_world_add_shape),
     "add_shape(name, kind, *, size=(0, 0, 0), rounding=0, margin=0, scale=1, vertices=None) -> int\n\n"
     "A convex shape template: kind sphere (size = radius), box, cylinder, cone, ellipsoid or\n"
     "polyhedron (vertices (n, 3)); see sd_shape_desc. Returns its index."},
    {"add_composite", SDPY_KW(sdpy_world_add_composite),
     "add_composite(name, elements, *, lattice=0) -> int\n\nA composite of convex templates: elements is a\n"
     "list of (shape index, position[, orientation (w, x, y, z)]). Returns its index."},
    {"add_composite_preset", SDPY_KW(sdpy_world_add_composite_preset),
     "add_composite_preset(name, preset, *, length=0, diameter=0, width=0, thickness=0, count=0) -> int\n\n"
     "A built-in composite (cross2d, cross3d, lshape, tshape, ring, dumbbell, spheres9, spheres54)."},
    {"add_shape2d", SDPY_KW(sdpy_world_add_shape2d),
     "add_shape2d(name, kind, *, radius=0, semi_axes=None, points=None, fourier_a=None, fourier_b=None) -> int\n\n"
     "A planar template (dimension 2): circle, ellipse, polygon, polybezier or fourier."},
    {"find_shape", (PyCFunction)sdpy_world_find_shape, METH_O,
     "find_shape(name) -> int\n\nThe index of a shape template by name, or -1."},
    {"shape", (PyCFunction)sdpy_world_shape, METH_O,
     "shape(index) -> dict\n\nA template's name, kind, volume, radii, inertia per unit density, ..."},
    {"add_plane", SDPY_KW(sdpy_world_add_plane),
     "add_plane(name, point, normal, material) -> int\n\nA plane wall; returns its index."},
    {"add_box", SDPY_KW(sdpy_world_add_box),
     "add_box(name, lo, hi, material, open_faces=None) -> int\n\nA box container; open_faces lists faces left\n"
     "out (\"zmax\", ...)."},
    {"add_drum", SDPY_KW(sdpy_world_add_drum),
     "add_drum(name, center, axis, radius, length, material, *, rpm=0, start=0, ramp=0, open_lo=False,\n"
     "open_hi=False) -> int\n\nA rotating cylindrical drum (an analytic wall, cells solver, 3D)."},
    {"add_mesh", SDPY_KW(sdpy_world_add_mesh),
     "add_mesh(name, vertices, triangles, material, *, outside=False, weld_tolerance=0,\n"
     "coplanar_tolerance=0) -> int\n\nA triangle-mesh wall from arrays: vertices (n, 3) in m, triangles (m, 3)\n"
     "vertex indices."},
    {"set_wall_motion", SDPY_KW(sdpy_world_set_wall_motion),
     "set_wall_motion(wall, *, velocity, move_start, move_end, servo_stress, servo_start, servo_end,\n"
     "servo_gain, servo_max_speed) -> None\n\nA plane wall's prescribed or servo motion (sd_wall_motion_def)."},
    {"set_mesh_motion", SDPY_KW(sdpy_world_set_mesh_motion),
     "set_mesh_motion(wall, kind, *, velocity, axis_point, axis, rpm, start, ramp, table) -> None\n\n"
     "A mesh wall's motion: fixed, translate, rotate or table (rows t, dx, dy, dz, angle_deg)."},
    {"wall", (PyCFunction)sdpy_world_wall, METH_O,
     "wall(index) -> dict\n\nA wall's name, kind, force and torque on it, geometry and motion now."},
    {"prepare", (PyCFunction)sdpy_world_prepare, METH_NOARGS,
     "prepare() -> None\n\nComputes the first forces (the first step does it when not called)."},
    {"step", SDPY_KW(sdpy_world_step),
     "step(steps=1) -> None\n\nAdvances the world; releases the GIL while it runs (other Python threads run;\n"
     "this world refuses every call from them until it returns)."},
    {"ids", (PyCFunction)sdpy_world_ids, METH_NOARGS,
     "ids() -> numpy.ndarray\n\nThe stable ids of all particles, increasing (the order of get and set)."},
    {"get", SDPY_KW(sdpy_world_get),
     "get(field, ids=None) -> numpy.ndarray\n\nA copy of a field (shapedem.fields() lists them) in the order of\n"
     "ids, or of increasing id when ids is None: shape (n, components), or (n,) for one component."},
    {"set", SDPY_KW(sdpy_world_set),
     "set(field, values, ids=None) -> None\n\nWrites a writable field (position, velocity, angular_velocity,\n"
     "orientation) through the engine's checks; everything is checked before anything is written."},
    {"stats", (PyCFunction)sdpy_world_stats, METH_NOARGS,
     "stats() -> dict\n\nEnergies, contacts, overlap and speed extremes, rebuilds (sd_stats)."},
    {"kinetic_energy", (PyCFunction)sdpy_world_kinetic_energy, METH_NOARGS,
     "kinetic_energy() -> float\n\nTranslational plus rotational kinetic energy, J."},
    {"recommended_dt", (PyCFunction)sdpy_world_recommended_dt, METH_NOARGS,
     "recommended_dt() -> (dt, contact_duration)\n\nThe recommended time step and the shortest contact, s."},
    {"checkpoint", (PyCFunction)sdpy_world_checkpoint, METH_O,
     "checkpoint(path) -> None\n\nWrites the complete state to an HDF5 checkpoint (atomically)."},
    {"restore", (PyCFunction)sdpy_world_restore, METH_O,
     "restore(path) -> None\n\nPuts a checkpoint's state into this world, freshly built from the same scene."},
    {"drum_surface", SDPY_KW(sdpy_world_drum_surface),
     "drum_surface(center, axis, radius, length, *, bins=20, fit=(0.2, 0.8)) -> dict\n\n"
     "The free surface of the bed in a drum, fitted by a line: angle (degrees), slope, rms, columns."},
    {"heap_angle", SDPY_KW(sdpy_world_heap_angle),
     "heap_angle(*, center=None, bins=20, fit=(0.2, 0.8)) -> dict\n\nThe angle of repose of a heap."},
    {"bed_height", SDPY_KW(sdpy_world_bed_height),
     "bed_height(*, fraction=0.5, lo=None, hi=None) -> dict\n\nThe bed's top, the height below which\n"
     "`fraction` of the mass lies, and the mean height (in the box lo, hi when given)."},
    {NULL, NULL, 0, NULL}};
#undef SDPY_KW

static PySequenceMethods sdpy_world_sequence = {.sq_length = (lenfunc)sdpy_world_len};

PyTypeObject sdpy_world_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "shapedem.World",
    .tp_basicsize = sizeof(PyWorld),
    .tp_dealloc = (destructor)sdpy_world_dealloc,
    .tp_as_sequence = &sdpy_world_sequence,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "World(*, dt=1e-5, gravity=(0, 0, -9.81), dimension=3, seed=1, threads=0, law='hertz_mindlin',\n"
              "skin=0, solver='cells', local_damping=0, periodic='', domain_lo=(0, 0, 0), domain_hi=(0, 0, 0),\n"
              "multi_contact='average', backend='auto', max_overlap=0.5)\n\n"
              "A DEM world (sd_world): materials, shapes, walls and particles, stepped by step().",
    .tp_methods = sdpy_world_methods,
    .tp_getset = sdpy_world_getset,
    .tp_new = sdpy_world_new,
};

int sdpy_add_world_type(PyObject *m)
{
    if (PyType_Ready(&sdpy_world_type) < 0)
        return -1;
    Py_INCREF(&sdpy_world_type);
    return PyModule_AddObject(m, "World", (PyObject *)&sdpy_world_type);
}
