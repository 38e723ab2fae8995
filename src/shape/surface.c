/* surface.c — template surfaces for pictures (see surface.h for the
 * invariant): the hull of support points over a latitude-longitude set of
 * directions, or the polyhedron's own vertices when it is sharp.
 */
#include "shape/surface.h"

#include "core/alloc.h"
#include "core/error.h"
#include "geom/hull.h"
#include "shape/support.h"

#include <math.h>
#include <string.h>

#define SD_SURFACE_PI 3.14159265358979323846

static sd_status sd_surface_check_res(int res, sd_error *err)
{
    if (res < SD_SURFACE_RES_MIN || res > SD_SURFACE_RES_MAX)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "output.shape_resolution",
                            "the shape resolution is %d; it must be %d to %d directions per turn", res,
                            SD_SURFACE_RES_MIN, SD_SURFACE_RES_MAX);
    return SD_OK;
}

static sd_status sd_surface_alloc(sd_surface *out, size_t points, size_t cells, size_t conn, sd_error *err)
{
    memset(out, 0, sizeof *out);
    out->points = sd_malloc((points ? points : 1) * 3 * sizeof *out->points);
    out->ends = sd_malloc((cells ? cells : 1) * sizeof *out->ends);
    out->conn = sd_malloc((conn ? conn : 1) * sizeof *out->conn);
    if (!out->points || !out->ends || !out->conn) {
        sd_surface_free(out);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for a shape's surface");
    }
    out->point_count = points;
    out->cell_count = cells;
    out->conn_count = conn;
    return SD_OK;
}

void sd_surface_free(sd_surface *s)
{
    if (!s)
        return;
    sd_free(s->points);
    sd_free(s->ends);
    sd_free(s->conn);
    memset(s, 0, sizeof *s);
}

/* Appends p unless it equals (bit for bit) a point already there: a flat
 * face maps many directions to one corner, and the hull needs each once. */
static void sd_surface_add_point(sd_vec3 *pts, size_t *n, sd_vec3 p)
{
    for (size_t k = 0; k < *n; ++k)
        if (pts[k].x == p.x && pts[k].y == p.y && pts[k].z == p.z)
            return;
    pts[(*n)++] = p;
}

/* The boundary loop of hull face f (its triangles' edges whose neighbour
 * lies on another face), counter-clockwise from outside like the
 * triangles, into loop[]; its length, or 0 when the edges do not close into
 * one loop (then the face is written as its triangles). nxt[] is -1 for
 * every point on entry and on return. */
static int sd_surface_face_loop(const sd_hull *h, int f, int *nxt, int *loop, int cap)
{
    int edges = 0, start = -1;
    for (int t = 0; t < h->ntri; ++t) {
        if (h->face[t] != f)
            continue;
        for (int k = 0; k < 3; ++k)
            if (h->face[h->nbr[t][k]] != f) {
                int a = h->tri[t][k], b = h->tri[t][(k + 1) % 3];
                if (nxt[a] >= 0)
                    edges = -1000000; /* a corner twice: not one simple loop */
                nxt[a] = b;
                start = a;
                ++edges;
            }
    }
    int n = 0, ok = edges >= 3 && edges <= cap;
    for (int a = start; ok && n < edges; a = nxt[a]) {
        if (a < 0) {
            ok = 0;
            break;
        }
        loop[n++] = a;
        if (nxt[a] == start)
            break;
    }
    ok = ok && n == edges;
    for (int t = 0; t < h->ntri; ++t) /* reset the marks */
        if (h->face[t] == f)
            for (int k = 0; k < 3; ++k)
                nxt[h->tri[t][k]] = -1;
    return ok ? n : 0;
}

/* The hull of pts as one polygon per planar face (a box's 6 quads, a
 * cylinder's caps and side quads; a face whose edges do not form one loop
 * stays its triangles), on the points they use. */
static sd_status sd_surface_from_hull(const sd_vec3 *pts, size_t n, sd_surface *out, sd_error *err)
{
    sd_hull_workspace *ws = sd_malloc(sizeof *ws);
    sd_hull *h = sd_malloc(sizeof *h);
    int *map = sd_malloc((n ? n : 1) * sizeof *map);
    int *nxt = sd_malloc((n ? n : 1) * sizeof *nxt);
    int *loops = sd_malloc((3 * (size_t)SD_HULL_MAX_TRIS + 1) * sizeof *loops);
    int *lens = sd_malloc(((size_t)SD_HULL_MAX_TRIS + 1) * sizeof *lens);
    sd_status st = SD_OK;
    if (!ws || !h || !map || !nxt || !loops || !lens) {
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for a shape's surface");
        goto done;
    }
    if (sd_hull_build(pts, n, ws, h) != SD_HULL_OK) {
        st = sd_error_set(err, SD_ERR_INPUT, "", 0, "", "a shape's surface has no volume (its hull failed)");
        goto done;
    }
    for (size_t k = 0; k < n; ++k)
        map[k] = nxt[k] = -1;
    /* cells: each face's loop, or its triangles; loops[] holds every cell's
     * corners (input indices) one after another, lens[] their counts */
    size_t cells = 0, conn = 0;
    for (int f = 0; f < h->nface; ++f) {
        int m = sd_surface_face_loop(h, f, nxt, loops + conn, 3 * SD_HULL_MAX_TRIS - (int)conn);
        if (m > 0) {
            lens[cells++] = m;
            conn += (size_t)m;
            continue;
        }
        for (int t = 0; t < h->ntri; ++t)
            if (h->face[t] == f) {
                for (int c = 0; c < 3; ++c)
                    loops[conn++] = h->tri[t][c];
                lens[cells++] = 3;
            }
    }
    size_t used = 0;
    for (size_t k = 0; k < conn; ++k)
        if (map[loops[k]] < 0)
            map[loops[k]] = (int)used++;
    st = sd_surface_alloc(out, used, cells, conn, err);
    if (st != SD_OK)
        goto done;
    for (size_t k = 0; k < n; ++k)
        if (map[k] >= 0) {
            double *q = out->points + 3 * (size_t)map[k];
            q[0] = (double)pts[k].x;
            q[1] = (double)pts[k].y;
            q[2] = (double)pts[k].z;
        }
    int64_t end = 0;
    for (size_t c = 0; c < cells; ++c)
        out->ends[c] = end += lens[c];
    for (size_t k = 0; k < conn; ++k)
        out->conn[k] = map[loops[k]];
done:
    sd_free(ws);
    sd_free(h);
    sd_free(map);
    sd_free(nxt);
    sd_free(loops);
    sd_free(lens);
    return st;
}

sd_status sd_surface_convex(const sd_shape *s, const sd_vec3 *verts, int res, sd_surface *out, sd_error *err)
{
    memset(out, 0, sizeof *out);
    sd_status st = sd_surface_check_res(res, err);
    if (st != SD_OK)
        return st;
    if (s->kind == SD_SHAPE_COMPOSITE)
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "sd_surface_convex: a composite is not convex");
    /* res longitudes on res/2 - 1 rings and the two poles: at most
     * 64 * 31 + 2 = 1986 points, within the hull's SD_HULL_MAX_POINTS */
    int rings = res / 2;
    size_t cap = (size_t)res * (size_t)(rings - 1) + 2;
    if (s->kind == SD_SHAPE_POLYHEDRON && cap < s->vcount)
        cap = s->vcount;
    sd_vec3 *pts = sd_malloc(cap * sizeof *pts);
    if (!pts)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for a shape's surface");
    size_t n = 0;
    if (s->kind == SD_SHAPE_POLYHEDRON && !(s->radius > SD_R(0.0)) && verts) {
        /* a sharp polyhedron is exactly the hull of its vertices; directions
         * could miss a vertex whose normal cone is narrower than their
         * spacing */
        for (uint32_t k = 0; k < s->vcount; ++k)
            sd_surface_add_point(pts, &n, verts[s->vstart + k]);
    } else {
        for (int j = 0; j <= rings; ++j) {
            double th = SD_SURFACE_PI * j / rings;
            int nl = (j == 0 || j == rings) ? 1 : res;
            for (int i = 0; i < nl; ++i) {
                double ph = 2.0 * SD_SURFACE_PI * i / res;
                sd_vec3 d = sd_v3((sd_real)(sin(th) * cos(ph)), (sd_real)(sin(th) * sin(ph)), (sd_real)cos(th));
                sd_surface_add_point(pts, &n, sd_shape_support(s, verts, d));
            }
        }
    }
    st = sd_surface_from_hull(pts, n, out, err);
    sd_free(pts);
    return st;
}

sd_status sd_surface_composite(const sd_shape *s, const sd_element *elements, const sd_shape *shapes,
                               const sd_vec3 *verts, int res, sd_surface *out, sd_error *err)
{
    memset(out, 0, sizeof *out);
    sd_status st = sd_surface_check_res(res, err);
    if (st != SD_OK)
        return st;
    size_t ne = s->ecount;
    sd_surface *parts = sd_calloc(ne ? ne : 1, sizeof *parts);
    if (!parts)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for a shape's surface");
    size_t np = 0, nc = 0, nn = 0;
    for (size_t e = 0; e < ne && st == SD_OK; ++e) {
        st = sd_surface_convex(&shapes[elements[s->estart + e].shape], verts, res, &parts[e], err);
        np += parts[e].point_count;
        nc += parts[e].cell_count;
        nn += parts[e].conn_count;
    }
    if (st == SD_OK)
        st = sd_surface_alloc(out, np, nc, nn, err);
    if (st == SD_OK) {
        size_t p0 = 0, c0 = 0, n0 = 0;
        for (size_t e = 0; e < ne; ++e) {
            const sd_element *el = &elements[s->estart + e];
            const sd_surface *ps = &parts[e];
            for (size_t k = 0; k < ps->point_count; ++k) {
                const double *x = ps->points + 3 * k;
                sd_vec3 v = sd_v3_add(el->x, sd_quat_rotate(el->q, sd_v3((sd_real)x[0], (sd_real)x[1], (sd_real)x[2])));
                double *q = out->points + 3 * (p0 + k);
                q[0] = (double)v.x;
                q[1] = (double)v.y;
                q[2] = (double)v.z;
            }
            for (size_t k = 0; k < ps->conn_count; ++k)
                out->conn[n0 + k] = ps->conn[k] + (int64_t)p0;
            for (size_t k = 0; k < ps->cell_count; ++k)
                out->ends[c0 + k] = ps->ends[k] + (int64_t)n0;
            p0 += ps->point_count;
            c0 += ps->cell_count;
            n0 += ps->conn_count;
        }
    }
    for (size_t e = 0; e < ne; ++e)
        sd_surface_free(&parts[e]);
    sd_free(parts);
    if (st != SD_OK)
        sd_surface_free(out);
    return st;
}

sd_status sd_surface_outline(const sd_shape2d *s, const sd_real *pool, int res, sd_surface *out, sd_error *err)
{
    memset(out, 0, sizeof *out);
    sd_status st = sd_surface_check_res(res, err);
    if (st != SD_OK)
        return st;
    int sharp_polygon = s->kind == SD_SHAPE2D_POLYGON && !(s->radius > SD_R(0.0));
    size_t cap = sharp_polygon ? s->count : (size_t)res;
    sd_vec2 *pts = sd_malloc((cap ? cap : 1) * sizeof *pts);
    if (!pts)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for a shape's surface");
    size_t n = 0;
    if (sharp_polygon) {
        /* the polygon's own vertices, counter-clockwise (shape2d.h pool layout) */
        for (uint32_t k = 0; k < s->count; ++k)
            pts[n++] = sd_v2(pool[s->start + 2 * k], pool[s->start + 2 * k + 1]);
    } else {
        /* support points counter-clockwise around the circle of directions;
         * a corner answers several directions and is kept once */
        for (int i = 0; i < res; ++i) {
            double ph = 2.0 * SD_SURFACE_PI * i / res;
            sd_vec2 p = sd_shape2d_support(s, pool, sd_v2((sd_real)cos(ph), (sd_real)sin(ph)));
            if (n > 0 && p.x == pts[n - 1].x && p.y == pts[n - 1].y)
                continue;
            pts[n++] = p;
        }
        while (n > 1 && pts[n - 1].x == pts[0].x && pts[n - 1].y == pts[0].y)
            --n;
    }
    if (n < 3) {
        sd_free(pts);
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "a planar shape's outline has fewer than 3 corners");
    }
    st = sd_surface_alloc(out, n, 1, n, err);
    if (st == SD_OK) {
        out->planar = 1;
        for (size_t k = 0; k < n; ++k) {
            out->points[3 * k] = (double)pts[k].x;
            out->points[3 * k + 1] = (double)pts[k].y;
            out->points[3 * k + 2] = 0.0;
            out->conn[k] = (int64_t)k;
        }
        out->ends[0] = (int64_t)n;
    }
    sd_free(pts);
    return st;
}

sd_status sd_surface_unit_ball(int planar, int res, sd_surface *out, sd_error *err)
{
    if (planar) {
        sd_shape2d c;
        memset(&c, 0, sizeof c);
        c.kind = SD_SHAPE2D_CIRCLE;
        c.radius = SD_R(1.0);
        return sd_surface_outline(&c, NULL, res, out, err);
    }
    sd_shape b;
    memset(&b, 0, sizeof b);
    b.kind = SD_SHAPE_SPHERE;
    b.radius = SD_R(1.0);
    return sd_surface_convex(&b, NULL, res, out, err);
}

double sd_surface_measure(const sd_surface *s)
{
    double sum = 0.0;
    int64_t start = 0;
    for (size_t c = 0; c < s->cell_count; ++c) {
        int64_t end = s->ends[c];
        if (s->planar) {
            /* shoelace: twice the signed area */
            for (int64_t k = start; k < end; ++k) {
                const double *a = s->points + 3 * s->conn[k];
                const double *b = s->points + 3 * s->conn[k + 1 < end ? k + 1 : start];
                sum += 0.5 * (a[0] * b[1] - a[1] * b[0]);
            }
        } else {
            /* fan of the cell from its first point, each triangle a . (b x c) / 6 */
            const double *a = s->points + 3 * s->conn[start];
            for (int64_t k = start + 1; k + 1 < end; ++k) {
                const double *b = s->points + 3 * s->conn[k];
                const double *c2 = s->points + 3 * s->conn[k + 1];
                sum += (a[0] * (b[1] * c2[2] - b[2] * c2[1]) + a[1] * (b[2] * c2[0] - b[0] * c2[2]) +
                        a[2] * (b[0] * c2[1] - b[1] * c2[0])) /
                       6.0;
            }
        }
        start = end;
    }
    return sum;
}
