/* scaled.c — a scaled copy of a shape template (sd_world_add_scaled_shape,
 * shapedem/process.h): how an insertion gives a size distribution to any
 * template kind without one template per particle (issue 16). The
 * insertion cuts the law into a few classes and makes one copy per class.
 *
 * Every length of a template is a length, so a copy scaled by s is the
 * template with every length times s: core dimensions, rounding, offsets,
 * bounding radius, vertices, face-plane offsets (the normals stay), dual
 * triangle points, element positions and bounds; the volume goes as s^3
 * (2D: the area as s^2), the principal moments per unit density as s^5
 * (2D: the polar moment per unit thickness as s^4). The principal frame
 * and the polyhedron's topology (faces, dual adjacency) are the same, so
 * nothing is rebuilt and the copy is exact to rounding. A composite's
 * copy scales its element templates too (one copy per distinct element
 * template, added before the composite's copy, as sd_world_add_composite
 * wants).
 *
 * Invariant: the copy is appended like any template (same arrays, same
 * name rules, prepared cleared); the original is untouched.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "shape/composite.h"
#include "world/world.h"

#include <shapedem/process.h>

static sd_status sd_scaled_grow(sd_world *w, size_t nv, size_t np, size_t nt, size_t ne, const char *name,
                                sd_error *err)
{
    sd_shape *shapes = sd_realloc(w->shapes, (w->shape_count + 1) * sizeof *shapes);
    if (shapes)
        w->shapes = shapes;
    char(*names)[64] = sd_realloc(w->shape_names, (w->shape_count + 1) * sizeof *names);
    if (names)
        w->shape_names = names;
    sd_real *req = sd_realloc(w->shape_req, (w->shape_count + 1) * sizeof *req);
    if (req)
        w->shape_req = req;
    sd_vec3 *com = sd_realloc(w->shape_com, (w->shape_count + 1) * sizeof *com);
    if (com)
        w->shape_com = com;
    int ok = shapes && names && req && com;
    if (ok && nv) {
        sd_vec3 *v = sd_realloc(w->verts, (w->vert_count + nv) * sizeof *v);
        ok = v != NULL;
        if (v)
            w->verts = v;
    }
    if (ok && np) {
        sd_plane *p = sd_realloc(w->planes, (w->plane_count + np) * sizeof *p);
        ok = p != NULL;
        if (p)
            w->planes = p;
    }
    if (ok && nt) {
        sd_dtri *t = sd_realloc(w->dtris, (w->dtri_count + nt) * sizeof *t);
        ok = t != NULL;
        if (t)
            w->dtris = t;
    }
    if (ok && ne) {
        sd_element *e = sd_realloc(w->elements, (w->element_count + ne) * sizeof *e);
        ok = e != NULL;
        if (e)
            w->elements = e;
    }
    if (!ok)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory adding the scaled shape '%s'", name);
    return SD_OK;
}

/* A convex 3D template k scaled by s, appended; its index or -1. */
static int sd_scaled_convex(sd_world *w, int k, sd_real s, const char *name, sd_error *err)
{
    const sd_shape src = w->shapes[k];
    size_t nv = src.vcount; /* a polyhedron's (or a shrunk core's) pool vertices */
    size_t np = src.kind == SD_SHAPE_POLYHEDRON ? src.fcount : 0, nt = src.kind == SD_SHAPE_POLYHEDRON ? src.tcount : 0;
    if (sd_scaled_grow(w, nv, np, nt, 0, name, err) != SD_OK)
        return -1;
    sd_shape c = src;
    c.radius *= s;
    c.a = sd_v3_scale(src.a, s);
    c.offset = sd_v3_scale(src.offset, s);
    c.bound *= s;
    c.volume *= s * s * s;
    c.inertia = sd_v3_scale(src.inertia, s * s * s * s * s);
    c.min_size *= s;
    c.given_com = sd_v3_scale(src.given_com, s);
    if (nv) {
        c.vstart = (uint32_t)w->vert_count;
        for (size_t i = 0; i < nv; ++i)
            w->verts[w->vert_count + i] = sd_v3_scale(w->verts[src.vstart + i], s);
        w->vert_count += nv;
    }
    if (np) {
        c.fstart = (uint32_t)w->plane_count;
        for (size_t i = 0; i < np; ++i) {
            sd_plane p = w->planes[src.fstart + i];
            p.h *= s;
            w->planes[w->plane_count + i] = p;
        }
        w->plane_count += np;
    }
    if (nt) {
        c.tstart = (uint32_t)w->dtri_count;
        for (size_t i = 0; i < nt; ++i) {
            sd_dtri t = w->dtris[src.tstart + i];
            t.v = sd_v3_scale(t.v, s);
            w->dtris[w->dtri_count + i] = t;
        }
        w->dtri_count += nt;
    }
    w->shapes[w->shape_count] = c;
    w->shape_com[w->shape_count] = sd_v3_scale(w->shape_com[k], s);
    w->shape_req[w->shape_count] = w->shape_req[k] * s;
    snprintf(w->shape_names[w->shape_count], 64, "%s", name);
    w->prepared = 0;
    return (int)w->shape_count++;
}

/* A composite k scaled by s: its distinct element templates scaled first
 * (named NAME.eJ), then the composite on them. */
static int sd_scaled_composite(sd_world *w, int k, sd_real s, const char *name, sd_error *err)
{
    const sd_shape src = w->shapes[k];
    size_t n = src.ecount;
    int from[SD_COMPOSITE_MAX_ELEMENTS], to[SD_COMPOSITE_MAX_ELEMENTS], distinct = 0;
    char ename[80];
    for (size_t e = 0; e < n; ++e) {
        int t = w->elements[src.estart + e].shape, j = 0;
        while (j < distinct && from[j] != t)
            ++j;
        if (j < distinct)
            continue;
        snprintf(ename, sizeof ename, "%s.e%d", name, distinct);
        if (strlen(ename) >= 64 || sd_world_check_shape_name(w, ename, err) != SD_OK) {
            sd_error_set(err, SD_ERR_INPUT, "", 0, "shape", "no free name for an element of the scaled shape '%s'",
                         name);
            return -1;
        }
        from[distinct] = t;
        to[distinct] = sd_scaled_convex(w, t, s, ename, err);
        if (to[distinct] < 0)
            return -1;
        ++distinct;
    }
    if (sd_scaled_grow(w, 0, 0, 0, n, name, err) != SD_OK)
        return -1;
    sd_shape c = w->shapes[k];
    c.bound *= s;
    c.volume *= s * s * s;
    c.inertia = sd_v3_scale(src.inertia, s * s * s * s * s);
    c.min_size *= s;
    c.given_com = sd_v3_scale(src.given_com, s);
    c.estart = (uint32_t)w->element_count;
    for (size_t e = 0; e < n; ++e) {
        sd_element el = w->elements[src.estart + e];
        int j = 0;
        while (from[j] != el.shape)
            ++j;
        el.shape = to[j];
        el.x = sd_v3_scale(el.x, s);
        el.bound *= s;
        w->elements[w->element_count + e] = el;
    }
    w->element_count += n;
    w->shapes[w->shape_count] = c;
    w->shape_com[w->shape_count] = sd_v3_scale(w->shape_com[k], s);
    w->shape_req[w->shape_count] = w->shape_req[k] * s;
    snprintf(w->shape_names[w->shape_count], 64, "%s", name);
    w->prepared = 0;
    return (int)w->shape_count++;
}

/* A planar template k scaled by s: every pool value is a length
 * (polygon and control points, Fourier coefficients). */
static int sd_scaled_2d(sd_world *w, int k, sd_real s, const char *name, sd_error *err)
{
    const sd_shape2d src = w->shapes2d[k];
    size_t np = sd_shape2d_pool_reals(src.kind, src.count);
    sd_real *pool = np ? sd_realloc(w->pool2d, (w->pool2d_count + np) * sizeof *pool) : w->pool2d;
    if (np && pool)
        w->pool2d = pool;
    sd_shape2d *shapes = sd_realloc(w->shapes2d, (w->shape2d_count + 1) * sizeof *shapes);
    if (shapes)
        w->shapes2d = shapes;
    char(*names)[64] = sd_realloc(w->shape2d_names, (w->shape2d_count + 1) * sizeof *names);
    if (names)
        w->shape2d_names = names;
    if ((np && !pool) || !shapes || !names) {
        sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory adding the scaled shape '%s'", name);
        return -1;
    }
    sd_shape2d c = src;
    c.radius *= s;
    c.a = sd_v2_scale(src.a, s);
    c.area *= s * s;
    c.inertia *= s * s * s * s;
    c.bound *= s;
    c.min_size *= s;
    c.eq_radius *= s;
    c.given_com = sd_v2_scale(src.given_com, s);
    if (np) {
        c.start = (uint32_t)w->pool2d_count;
        for (size_t i = 0; i < np; ++i)
            w->pool2d[w->pool2d_count + i] = w->pool2d[src.start + i] * s;
        w->pool2d_count += np;
    }
    w->shapes2d[w->shape2d_count] = c;
    snprintf(w->shape2d_names[w->shape2d_count], 64, "%s", name);
    w->prepared = 0;
    return (int)w->shape2d_count++;
}

int sd_world_add_scaled_shape(sd_world *w, int shape, double scale, const char *name, sd_error *err)
{
    if (!w) {
        sd_error_null(err, "sd_world_add_scaled_shape", "world");
        return -1;
    }
    size_t ns = w->dim2 ? w->shape2d_count : w->shape_count;
    if (shape < 0 || (size_t)shape >= ns) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "shape", "unknown template index %d", shape);
        return -1;
    }
    if (!(scale > 0) || !isfinite(scale)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "scale", "expected a scale > 0, got %g", scale);
        return -1;
    }
    if (sd_world_check_shape_name(w, name, err) != SD_OK)
        return -1;
    struct sd_scaled_copy *rec = sd_realloc(w->scaled, (w->scaled_count + 1) * sizeof *rec);
    if (!rec) {
        sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory adding the scaled shape '%s'", name);
        return -1;
    }
    w->scaled = rec;
    sd_real s = (sd_real)scale;
    int idx = w->dim2                                      ? sd_scaled_2d(w, shape, s, name, err)
              : w->shapes[shape].kind == SD_SHAPE_COMPOSITE ? sd_scaled_composite(w, shape, s, name, err)
                                                            : sd_scaled_convex(w, shape, s, name, err);
    if (idx >= 0) /* the copy's recipe, for a checkpoint's readers (sd_world_scaled_of) */
        w->scaled[w->scaled_count++] = (struct sd_scaled_copy){idx, shape, scale};
    return idx;
}

int sd_world_scaled_of(const sd_world *w, size_t shape, int *base, double *scale)
{
    for (size_t k = 0; k < w->scaled_count; ++k)
        if (w->scaled[k].index == (int)shape) {
            *base = w->scaled[k].base;
            *scale = w->scaled[k].scale;
            return 1;
        }
    return 0;
}
