/* h5md.c — trajectory.h5md in the layout of H5MD 1.1 (see h5md.h).
 *
 * H5MD (de Buyl, Colberg and Höfling, Comput. Phys. Commun. 185 (2014)
 * 1546; specification 1.1 at nongnu.org/h5md): the group /h5md with the
 * attribute version = [1, 1] and the groups author (name) and creator
 * (name, version); particles in /particles/<group>, here one group `all`,
 * with a `box` group (attributes dimension and boundary, "periodic" or
 * "none" per axis; edges and offset of the periodic box) and one
 * time-dependent element per quantity: a group holding `step` (integer,
 * [T]), `time` (float, [T]) and `value` ([T, N] or [T, N, components]).
 * The standard's elements are position, velocity, force (D components, D
 * the dimension), species (the material index) and id (the stable id, -1
 * in rows past a frame's particle count); orientation (quaternion w, x, y,
 * z), angular_velocity (3 components, world frame), radius and shape (the
 * template index, -1 a plain sphere) are elements of shapedem's own, which
 * the standard allows beside its own. Every element shares the step and
 * time datasets of `position` (hard links, as the standard suggests).
 *
 * The particle dimension of the values is extensible, so inserted
 * particles add rows; rows a frame does not fill read as the fill value.
 * Object times are not recorded, so the same run gives the same bytes.
 */
#define _POSIX_C_SOURCE 200809L

#include "io/h5md.h"

#include "core/alloc.h"
#include "core/error.h"
#include "io/checkpoint.h" /* sd_h5_quiet */

#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* X(name, components (0: the dimension), integer, standard) */
#define SD_H5MD_ELEMENTS(X)                                                                                            \
    X(position, 0, 0)                                                                                                  \
    X(velocity, 0, 0)                                                                                                  \
    X(force, 0, 0)                                                                                                     \
    X(species, 1, 1)                                                                                                   \
    X(id, 1, 1)                                                                                                        \
    X(orientation, 4, 0)                                                                                               \
    X(angular_velocity, 3, 0)                                                                                          \
    X(radius, 1, 0)                                                                                                    \
    X(shape, 1, 1)

enum {
#define SD_X_ENUM(name, comps, integer) SD_H5MD_##name,
    SD_H5MD_ELEMENTS(SD_X_ENUM)
#undef SD_X_ENUM
        SD_H5MD_COUNT
};

static const char *const sd_h5md_names[SD_H5MD_COUNT] = {
#define SD_X_NAME(name, comps, integer) #name,
    SD_H5MD_ELEMENTS(SD_X_NAME)
#undef SD_X_NAME
};
static const int sd_h5md_comps[SD_H5MD_COUNT] = {
#define SD_X_COMPS(name, comps, integer) comps,
    SD_H5MD_ELEMENTS(SD_X_COMPS)
#undef SD_X_COMPS
};
static const int sd_h5md_integer[SD_H5MD_COUNT] = {
#define SD_X_INT(name, comps, integer) integer,
    SD_H5MD_ELEMENTS(SD_X_INT)
#undef SD_X_INT
};

struct sd_h5md {
    hid_t file;
    hid_t value[SD_H5MD_COUNT];
    hid_t step, time; /* position's, linked into the others */
    int dim;          /* 3, or 2 */
    long frames;
    char path[1024];
};

static int sd_h5md_components(const sd_h5md *h, int e)
{
    return sd_h5md_comps[e] ? sd_h5md_comps[e] : h->dim;
}

static sd_status sd_h5md_fail(const sd_h5md *h, const char *what, sd_error *err)
{
    return sd_error_set(err, SD_ERR_IO, h->path, 0, "", "cannot %s the H5MD trajectory (HDF5 refused)", what);
}

/* ---- writing attributes and datasets ----------------------------------------- */

static int sd_h5md_attr_str(hid_t obj, const char *name, const char *s)
{
    hid_t t = H5Tcopy(H5T_C_S1), sp = H5Screate(H5S_SCALAR);
    int ok = t >= 0 && sp >= 0 && H5Tset_size(t, strlen(s) + 1) >= 0 && H5Tset_strpad(t, H5T_STR_NULLTERM) >= 0;
    hid_t a = ok ? H5Acreate2(obj, name, t, sp, H5P_DEFAULT, H5P_DEFAULT) : -1;
    ok = a >= 0 && H5Awrite(a, t, s) >= 0;
    if (a >= 0)
        H5Aclose(a);
    if (sp >= 0)
        H5Sclose(sp);
    if (t >= 0)
        H5Tclose(t);
    return ok;
}

/* An attribute of n values (n = 0: a scalar) of 32-bit integers. */
static int sd_h5md_attr_int(hid_t obj, const char *name, const int *v, hsize_t n)
{
    hid_t sp = n ? H5Screate_simple(1, &n, NULL) : H5Screate(H5S_SCALAR);
    hid_t a = sp >= 0 ? H5Acreate2(obj, name, H5T_STD_I32LE, sp, H5P_DEFAULT, H5P_DEFAULT) : -1;
    int ok = a >= 0 && H5Awrite(a, H5T_NATIVE_INT, v) >= 0;
    if (a >= 0)
        H5Aclose(a);
    if (sp >= 0)
        H5Sclose(sp);
    return ok;
}

/* The box's boundary attribute: one fixed-length string per axis. */
static int sd_h5md_attr_boundary(hid_t box, unsigned periodic, int dim)
{
    char b[3][9];
    memset(b, 0, sizeof b); /* the padding too: the same run, the same bytes */
    for (int k = 0; k < dim; ++k)
        snprintf(b[k], sizeof b[k], "%s", (periodic >> k) & 1u ? "periodic" : "none");
    hsize_t n = (hsize_t)dim;
    hid_t t = H5Tcopy(H5T_C_S1), sp = H5Screate_simple(1, &n, NULL);
    int ok = t >= 0 && sp >= 0 && H5Tset_size(t, sizeof b[0]) >= 0 && H5Tset_strpad(t, H5T_STR_NULLTERM) >= 0;
    hid_t a = ok ? H5Acreate2(box, "boundary", t, sp, H5P_DEFAULT, H5P_DEFAULT) : -1;
    ok = a >= 0 && H5Awrite(a, t, b) >= 0;
    if (a >= 0)
        H5Aclose(a);
    if (sp >= 0)
        H5Sclose(sp);
    if (t >= 0)
        H5Tclose(t);
    return ok;
}

/* A group created without object times (same bytes for the same run). */
static hid_t sd_h5md_group(hid_t parent, const char *name)
{
    hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
    if (gcpl < 0)
        return -1;
    hid_t g = H5Pset_obj_track_times(gcpl, 0) >= 0 ? H5Gcreate2(parent, name, H5P_DEFAULT, gcpl, H5P_DEFAULT) : -1;
    H5Pclose(gcpl);
    return g;
}

/* A chunked dataset of rank 1, 2 or 3, empty and extensible along its
 * first two axes (a third, of components, fixed at chunk[2]), whose
 * unwritten elements read as the fill value (-1, NaN). */
static hid_t sd_h5md_dataset(hid_t g, const char *name, hid_t type, int rank, const hsize_t *chunk, int integer)
{
    hsize_t zero[3] = {0, 0, 0}, max[3] = {H5S_UNLIMITED, H5S_UNLIMITED, H5S_UNLIMITED};
    if (rank == 3)
        max[2] = zero[2] = chunk[2];
    hid_t sp = H5Screate_simple(rank, zero, max), dcpl = H5Pcreate(H5P_DATASET_CREATE);
    const long long ifill = -1;
    const double dfill = NAN;
    int ok = sp >= 0 && dcpl >= 0 && H5Pset_chunk(dcpl, rank, chunk) >= 0 && H5Pset_obj_track_times(dcpl, 0) >= 0 &&
             H5Pset_fill_value(dcpl, integer ? H5T_NATIVE_LLONG : H5T_NATIVE_DOUBLE,
                               integer ? (const void *)&ifill : (const void *)&dfill) >= 0 &&
             H5Pset_fill_time(dcpl, H5D_FILL_TIME_IFSET) >= 0;
    hid_t d = ok ? H5Dcreate2(g, name, type, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT) : -1;
    if (dcpl >= 0)
        H5Pclose(dcpl);
    if (sp >= 0)
        H5Sclose(sp);
    return d;
}

/* The file's skeleton: /h5md, /particles/all/box and every element. */
static sd_status sd_h5md_create(sd_h5md *h, const sd_world *w, const sd_dump_box *box, sd_error *err)
{
    hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
    if (fcpl >= 0)
        H5Pset_obj_track_times(fcpl, 0);
    h->file = H5Fcreate(h->path, H5F_ACC_EXCL, fcpl >= 0 ? fcpl : H5P_DEFAULT, H5P_DEFAULT);
    if (fcpl >= 0)
        H5Pclose(fcpl);
    if (h->file < 0)
        return sd_error_set(err, SD_ERR_IO, h->path, 0, "", "cannot create the H5MD trajectory: %s",
                            errno ? strerror(errno) : "HDF5 refused");
    const int version[2] = {1, 1};
    hid_t g = sd_h5md_group(h->file, "h5md");
    hid_t author = g >= 0 ? sd_h5md_group(g, "author") : -1;
    hid_t creator = g >= 0 ? sd_h5md_group(g, "creator") : -1;
    int ok = g >= 0 && author >= 0 && creator >= 0 && sd_h5md_attr_int(g, "version", version, 2) &&
             sd_h5md_attr_str(author, "name", "shapedem") && sd_h5md_attr_str(creator, "name", "shapedem") &&
             sd_h5md_attr_str(creator, "version", SD_VERSION_STRING);
    if (creator >= 0)
        H5Gclose(creator);
    if (author >= 0)
        H5Gclose(author);
    if (g >= 0)
        H5Gclose(g);
    hid_t parts = ok ? sd_h5md_group(h->file, "particles") : -1;
    hid_t all = parts >= 0 ? sd_h5md_group(parts, "all") : -1;
    hid_t b = all >= 0 ? sd_h5md_group(all, "box") : -1;
    ok = b >= 0 && sd_h5md_attr_int(b, "dimension", &h->dim, 0) && sd_h5md_attr_boundary(b, box->periodic, h->dim);
    if (ok && box->periodic) {
        /* the periodic box: edges and lower corner, fixed in time */
        const double lo[3] = {box->domain_lo.x, box->domain_lo.y, box->domain_lo.z};
        const double hi[3] = {box->domain_hi.x, box->domain_hi.y, box->domain_hi.z};
        double edges[3];
        for (int k = 0; k < 3; ++k)
            edges[k] = hi[k] - lo[k];
        hsize_t n = (hsize_t)h->dim;
        hid_t sp = H5Screate_simple(1, &n, NULL);
        for (int k = 0; k < 2 && ok; ++k) {
            hid_t d = sp >= 0 ? H5Dcreate2(b, k ? "offset" : "edges", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT,
                                           H5P_DEFAULT)
                              : -1;
            ok = d >= 0 && H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, k ? lo : edges) >= 0;
            if (d >= 0)
                H5Dclose(d);
        }
        if (sp >= 0)
            H5Sclose(sp);
    }
    if (b >= 0)
        H5Gclose(b);
    /* rows of a chunk: the particles at the start, within 1 to 4096 */
    size_t n0 = sd_world_particle_count(w);
    hsize_t rows = n0 < 1 ? 1 : n0 > 4096 ? 4096 : (hsize_t)n0;
    for (int e = 0; e < SD_H5MD_COUNT && ok; ++e) {
        hid_t eg = sd_h5md_group(all, sd_h5md_names[e]);
        int c = sd_h5md_components(h, e), rank = sd_h5md_comps[e] == 1 ? 2 : 3;
        hsize_t chunk[3] = {1, rows, (hsize_t)c};
        hid_t type = sd_h5md_integer[e] ? (e == SD_H5MD_id ? H5T_STD_I64LE : H5T_STD_I32LE) : H5T_IEEE_F64LE;
        h->value[e] = eg >= 0 ? sd_h5md_dataset(eg, "value", type, rank, chunk, sd_h5md_integer[e]) : -1;
        ok = h->value[e] >= 0;
        if (ok && e == SD_H5MD_position) {
            hsize_t c1[1] = {64};
            h->step = sd_h5md_dataset(eg, "step", H5T_STD_I64LE, 1, c1, 1);
            h->time = sd_h5md_dataset(eg, "time", H5T_IEEE_F64LE, 1, c1, 0);
            ok = h->step >= 0 && h->time >= 0;
        } else if (ok) {
            ok = H5Lcreate_hard(all, "position/step", eg, "step", H5P_DEFAULT, H5P_DEFAULT) >= 0 &&
                 H5Lcreate_hard(all, "position/time", eg, "time", H5P_DEFAULT, H5P_DEFAULT) >= 0;
        }
        if (eg >= 0)
            H5Gclose(eg);
    }
    if (all >= 0)
        H5Gclose(all);
    if (parts >= 0)
        H5Gclose(parts);
    return ok ? SD_OK : sd_h5md_fail(h, "write the layout of", err);
}

/* ---- a restart ------------------------------------------------------------------ */

/* A string attribute equal to want. */
static int sd_h5md_attr_is(hid_t obj, const char *name, const char *want)
{
    if (H5Aexists(obj, name) <= 0)
        return 0;
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT), t = a >= 0 ? H5Aget_type(a) : -1;
    char buf[64] = "";
    int ok = t >= 0 && H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) == 0 && H5Tget_size(t) < sizeof buf;
    if (ok) {
        hid_t mt = H5Tcopy(H5T_C_S1);
        ok = mt >= 0 && H5Tset_size(mt, H5Tget_size(t)) >= 0 && H5Aread(a, mt, buf) >= 0;
        if (mt >= 0)
            H5Tclose(mt);
    }
    if (t >= 0)
        H5Tclose(t);
    if (a >= 0)
        H5Aclose(a);
    return ok && strcmp(buf, want) == 0;
}

/* The dataset at path with this rank and trailing size (0: any), or -1. */
static hid_t sd_h5md_open_dataset(hid_t f, const char *path, int rank, hsize_t last)
{
    if (H5Lexists(f, path, H5P_DEFAULT) <= 0)
        return -1;
    hid_t d = H5Dopen2(f, path, H5P_DEFAULT), sp = d >= 0 ? H5Dget_space(d) : -1;
    hsize_t dims[3] = {0, 0, 0};
    int ok = sp >= 0 && H5Sget_simple_extent_ndims(sp) == rank && H5Sget_simple_extent_dims(sp, dims, NULL) == rank &&
             (last == 0 || dims[rank - 1] == last);
    if (sp >= 0)
        H5Sclose(sp);
    if (!ok && d >= 0) {
        H5Dclose(d);
        d = -1;
    }
    return d;
}

/* Opens the trajectory at h->path and cuts it to its frames before step;
 * 0 when it is not one this run can continue (nothing is left open). */
static int sd_h5md_continue(sd_h5md *h, long step)
{
    h->file = H5Fopen(h->path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (h->file < 0)
        return 0;
    int dim = 0;
    hid_t b = H5Lexists(h->file, "particles/all/box", H5P_DEFAULT) > 0
                  ? H5Gopen2(h->file, "particles/all/box", H5P_DEFAULT)
                  : -1;
    if (b >= 0) {
        hid_t a = H5Aexists(b, "dimension") > 0 ? H5Aopen(b, "dimension", H5P_DEFAULT) : -1;
        if (a < 0 || H5Aread(a, H5T_NATIVE_INT, &dim) < 0)
            dim = 0;
        if (a >= 0)
            H5Aclose(a);
        H5Gclose(b);
    }
    hid_t c = H5Lexists(h->file, "h5md", H5P_DEFAULT) > 0 && H5Lexists(h->file, "h5md/creator", H5P_DEFAULT) > 0
                  ? H5Gopen2(h->file, "h5md/creator", H5P_DEFAULT)
                  : -1;
    int ok = c >= 0 && sd_h5md_attr_is(c, "name", "shapedem") && dim == h->dim;
    if (c >= 0)
        H5Gclose(c);
    char path[96];
    for (int e = 0; e < SD_H5MD_COUNT && ok; ++e) {
        snprintf(path, sizeof path, "particles/all/%s/value", sd_h5md_names[e]);
        int rank = sd_h5md_comps[e] == 1 ? 2 : 3;
        h->value[e] = sd_h5md_open_dataset(h->file, path, rank, rank == 3 ? (hsize_t)sd_h5md_components(h, e) : 0);
        ok = h->value[e] >= 0;
    }
    h->step = ok ? sd_h5md_open_dataset(h->file, "particles/all/position/step", 1, 0) : -1;
    h->time = h->step >= 0 ? sd_h5md_open_dataset(h->file, "particles/all/position/time", 1, 0) : -1;
    ok = ok && h->step >= 0 && h->time >= 0;
    hsize_t n = 0;
    long long *steps = NULL;
    if (ok) {
        hid_t sp = H5Dget_space(h->step);
        ok = sp >= 0 && H5Sget_simple_extent_dims(sp, &n, NULL) == 1;
        if (sp >= 0)
            H5Sclose(sp);
        steps = ok ? sd_malloc((n ? n : 1) * sizeof *steps) : NULL;
        ok = steps && (n == 0 || H5Dread(h->step, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, steps) >= 0);
    }
    hsize_t keep = 0;
    while (ok && keep < n && steps[keep] < step)
        ++keep;
    sd_free(steps);
    /* every element as many frames as the steps, then all cut to keep */
    for (int e = 0; e < SD_H5MD_COUNT && ok; ++e) {
        hid_t sp = H5Dget_space(h->value[e]);
        hsize_t dims[3];
        int rank = sp >= 0 ? H5Sget_simple_extent_dims(sp, dims, NULL) : -1;
        if (sp >= 0)
            H5Sclose(sp);
        ok = rank >= 2 && dims[0] >= n;
        if (ok) {
            dims[0] = keep;
            ok = H5Dset_extent(h->value[e], dims) >= 0;
        }
    }
    ok = ok && H5Dset_extent(h->step, &keep) >= 0 && H5Dset_extent(h->time, &keep) >= 0;
    if (!ok) {
        for (int e = 0; e < SD_H5MD_COUNT; ++e)
            if (h->value[e] >= 0)
                H5Dclose(h->value[e]);
        if (h->step >= 0)
            H5Dclose(h->step);
        if (h->time >= 0)
            H5Dclose(h->time);
        H5Fclose(h->file);
        h->file = h->step = h->time = -1;
        for (int e = 0; e < SD_H5MD_COUNT; ++e)
            h->value[e] = -1;
        return 0;
    }
    h->frames = (long)keep;
    return 1;
}

/* ---- the public calls ---------------------------------------------------------------- */

sd_status sd_h5md_open(const char *path, const sd_world *w, const sd_dump_box *box, long resume_step, sd_h5md **out,
                       sd_error *err)
{
    *out = NULL;
    sd_h5md *h = sd_calloc(1, sizeof *h);
    if (!h)
        return sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    if (strlen(path) >= sizeof h->path) {
        sd_free(h);
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "output path too long");
    }
    snprintf(h->path, sizeof h->path, "%s", path);
    h->dim = box->dimension == 2 ? 2 : 3;
    h->file = h->step = h->time = -1;
    for (int e = 0; e < SD_H5MD_COUNT; ++e)
        h->value[e] = -1;
    sd_h5_quiet();
    sd_status s = SD_OK;
    if (resume_step <= 0 || !sd_h5md_continue(h, resume_step)) {
        /* a new file; on a restart the one there was not ours to continue */
        if (resume_step > 0 && remove(path) != 0 && errno != ENOENT)
            s = sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot remove the file: %s", strerror(errno));
        errno = 0;
        if (s == SD_OK)
            s = sd_h5md_create(h, w, box, err);
    }
    if (s != SD_OK) {
        sd_h5md_close(h, NULL);
        return s;
    }
    *out = h;
    return SD_OK;
}

long sd_h5md_frames(const sd_h5md *h)
{
    return h ? h->frames : 0;
}

/* Frame row t of element e: n rows of c values from buf. */
static int sd_h5md_put(sd_h5md *h, int e, hsize_t t, size_t n, const void *buf)
{
    hid_t d = h->value[e], sp = H5Dget_space(d);
    hsize_t dims[3] = {0, 0, 0};
    int rank = sp >= 0 ? H5Sget_simple_extent_dims(sp, dims, NULL) : -1;
    if (sp >= 0)
        H5Sclose(sp);
    if (rank < 2)
        return 0;
    dims[0] = t + 1;
    if (dims[1] < n)
        dims[1] = n;
    if (H5Dset_extent(d, dims) < 0)
        return 0;
    if (n == 0)
        return 1;
    hsize_t start[3] = {t, 0, 0}, count[3] = {1, n, rank == 3 ? dims[2] : 1};
    hid_t fs = H5Dget_space(d), ms = H5Screate_simple(rank, count, NULL);
    int ok = fs >= 0 && ms >= 0 && H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) >= 0 &&
             H5Dwrite(d, sd_h5md_integer[e] ? (e == SD_H5MD_id ? H5T_NATIVE_LLONG : H5T_NATIVE_INT) : H5T_NATIVE_DOUBLE,
                      ms, fs, H5P_DEFAULT, buf) >= 0;
    if (ms >= 0)
        H5Sclose(ms);
    if (fs >= 0)
        H5Sclose(fs);
    return ok;
}

/* One value of a 1-D series at row t. */
static int sd_h5md_put_series(hid_t d, hsize_t t, hid_t mtype, const void *v)
{
    hsize_t n = t + 1, one = 1;
    if (H5Dset_extent(d, &n) < 0)
        return 0;
    hid_t fs = H5Dget_space(d), ms = H5Screate_simple(1, &one, NULL);
    int ok = fs >= 0 && ms >= 0 && H5Sselect_hyperslab(fs, H5S_SELECT_SET, &t, NULL, &one, NULL) >= 0 &&
             H5Dwrite(d, mtype, ms, fs, H5P_DEFAULT, v) >= 0;
    if (ms >= 0)
        H5Sclose(ms);
    if (fs >= 0)
        H5Sclose(fs);
    return ok;
}

sd_status sd_h5md_write(sd_h5md *h, const sd_world *w, sd_error *err)
{
    size_t n = sd_world_particle_count(w), m = n ? n : 1;
    int dim = h->dim;
    /* the particles in id order, each quantity in its own block */
    uint64_t *ids = sd_malloc(m * sizeof *ids);
    double *x = sd_malloc(m * (3 * (size_t)dim + 8) * sizeof *x);
    int *ints = sd_malloc(2 * m * sizeof *ints);
    long long *id = sd_malloc(m * sizeof *id);
    if (!ids || !x || !ints || !id) {
        sd_free(ids), sd_free(x), sd_free(ints), sd_free(id);
        return sd_error_set(err, SD_ERR_MEMORY, h->path, 0, "", "out of memory");
    }
    double *v = x + (size_t)dim * m, *f = v + (size_t)dim * m, *q = f + (size_t)dim * m, *om = q + 4 * m,
           *r = om + 3 * m;
    int *species = ints, *shape = ints + m;
    sd_status s = sd_world_get_ids(w, ids, n, err);
    for (size_t i = 0; i < n && s == SD_OK; ++i) {
        sd_particle_state p;
        s = sd_dump_particle(w, ids[i], &p, err);
        const double px[3] = {p.position.x, p.position.y, p.position.z};
        const double pv[3] = {p.velocity.x, p.velocity.y, p.velocity.z};
        const double pf[3] = {p.force.x, p.force.y, p.force.z};
        for (int k = 0; k < dim; ++k) {
            x[(size_t)dim * i + (size_t)k] = px[k];
            v[(size_t)dim * i + (size_t)k] = pv[k];
            f[(size_t)dim * i + (size_t)k] = pf[k];
        }
        for (int k = 0; k < 4; ++k)
            q[4 * i + (size_t)k] = p.quat[k];
        om[3 * i] = p.angular_velocity.x;
        om[3 * i + 1] = p.angular_velocity.y;
        om[3 * i + 2] = p.angular_velocity.z;
        r[i] = p.radius;
        species[i] = p.material;
        shape[i] = p.shape;
        id[i] = (long long)p.id;
    }
    const void *buf[SD_H5MD_COUNT] = {x, v, f, species, id, q, om, r, shape};
    hsize_t t = (hsize_t)h->frames;
    long long step = sd_world_step_count(w);
    double time = sd_world_time(w);
    int ok = s == SD_OK;
    for (int e = 0; e < SD_H5MD_COUNT && ok; ++e)
        ok = sd_h5md_put(h, e, t, n, buf[e]);
    ok = ok && sd_h5md_put_series(h->step, t, H5T_NATIVE_LLONG, &step) &&
         sd_h5md_put_series(h->time, t, H5T_NATIVE_DOUBLE, &time) && H5Fflush(h->file, H5F_SCOPE_LOCAL) >= 0;
    sd_free(ids), sd_free(x), sd_free(ints), sd_free(id);
    if (s != SD_OK)
        return s;
    if (!ok)
        return sd_h5md_fail(h, "write a frame to", err);
    h->frames++;
    return SD_OK;
}

sd_status sd_h5md_close(sd_h5md *h, sd_error *err)
{
    if (!h)
        return SD_OK;
    int ok = 1;
    for (int e = 0; e < SD_H5MD_COUNT; ++e)
        if (h->value[e] >= 0)
            ok &= H5Dclose(h->value[e]) >= 0;
    if (h->step >= 0)
        ok &= H5Dclose(h->step) >= 0;
    if (h->time >= 0)
        ok &= H5Dclose(h->time) >= 0;
    if (h->file >= 0)
        ok &= H5Fclose(h->file) >= 0;
    sd_status s = ok ? SD_OK : sd_h5md_fail(h, "close", err);
    sd_free(h);
    return s;
}
