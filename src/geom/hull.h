/* hull.h — 3D convex hull of a point set by incremental quickhull.
 *
 * Used for polyhedron templates (mass properties, the vertex set the support
 * function scans) and, next, for the dual-space overlap volume of two
 * polyhedra (seed 000 §2.4: polar transform, incremental quickhull,
 * unpolarise), which runs per contact pair: so the hull is single source
 * (SD_HD), allocates nothing and works in a caller-given fixed workspace.
 *
 * Algorithm (Barber, Dobkin, Huhdanpaa 1996): start from a tetrahedron of
 * extreme points; give every other point to the face it lies farthest above
 * (its outside set); repeatedly take the farthest point p of the first face
 * with a non-empty outside set, walk the faces p sees (depth first, which
 * yields the horizon as one ordered loop), replace them by a fan of
 * triangles from the horizon to p, and hand their outside points to the new
 * faces. A point within eps of a face plane is "on" it, never above it:
 * coplanar and duplicate points are dropped, not made into slivers.
 *
 * Invariants of the result: a closed, consistently oriented triangle mesh;
 * each triangle's vertices are counter-clockwise seen from outside, its
 * normal unit and outward; nbr[t][k] is the triangle across edge
 * tri[t][k] -> tri[t][k+1]; every input point lies below every triangle's
 * plane by at most eps. Triangles of one planar face share a face id (for
 * reporting; the triangulation itself is what volumes use), and vert[] lists
 * the extreme vertices only (a vertex that is a corner of at least three
 * distinct faces), ascending input index.
 *
 * Tolerance: eps = SD_HULL_REL_EPS * (max|x| + max|y| + max|z|) of the
 * input (its rounding scales with its coordinates); the arithmetic is done
 * about the centre of the points' bounding box. A horizon that is not
 * one loop (possible only for nearly degenerate input) restarts the build
 * with eps ten times larger, at most three times.
 */
#ifndef SD_GEOM_HULL_H
#define SD_GEOM_HULL_H

#include "shape/shape.h"

/* Most input points: a polyhedron's vertices, or the face planes of two
 * polyhedra in the dual-space overlap (at most 2V - 4 triangles each). */
#ifndef SD_HULL_MAX_POINTS
#define SD_HULL_MAX_POINTS (2 * SD_SHAPE_MAX_VERTICES)
#endif
/* A hull of n points has at most 2n - 4 triangles; the fan added in one
 * step may exceed the final count only briefly, hence the margin. */
#define SD_HULL_MAX_TRIS (2 * SD_HULL_MAX_POINTS + 8)

#if defined(SHAPEDEM_SINGLE)
#define SD_HULL_REL_EPS SD_R(2e-6)
#else
#define SD_HULL_REL_EPS SD_R(1e-14)
#endif

typedef enum sd_hull_status {
    SD_HULL_OK = 0,
    SD_HULL_TOO_FEW,    /* fewer than 4 points */
    SD_HULL_TOO_MANY,   /* more than SD_HULL_MAX_POINTS */
    SD_HULL_DEGENERATE, /* all points (within eps) on a line or a plane */
    SD_HULL_FAILED      /* numerically inconsistent even with a larger eps */
} sd_hull_status;

typedef struct sd_hull {
    int ntri;
    int tri[SD_HULL_MAX_TRIS][3];     /* input indices, counter-clockwise from outside */
    int nbr[SD_HULL_MAX_TRIS][3];     /* triangle across edge k: tri[k] -> tri[(k+1)%3] */
    sd_vec3 normal[SD_HULL_MAX_TRIS]; /* unit, outward */
    sd_real offset[SD_HULL_MAX_TRIS]; /* m, normal . x on the plane (input frame) */
    int face[SD_HULL_MAX_TRIS];       /* planar face id, 0 .. nface-1 */
    int nface;
    int nvert;                    /* extreme vertices */
    int vert[SD_HULL_MAX_POINTS]; /* their input indices, ascending */
    sd_real eps;                  /* m, the distance tolerance that was used */
} sd_hull;

typedef struct sd_hull_workspace {
    sd_vec3 p[SD_HULL_MAX_POINTS]; /* input about the bounding-box centre */
    int pnext[SD_HULL_MAX_POINTS]; /* next point of the same outside set */
    int v[SD_HULL_MAX_TRIS][3];
    int nb[SD_HULL_MAX_TRIS][3];
    sd_vec3 n[SD_HULL_MAX_TRIS];
    sd_real d[SD_HULL_MAX_TRIS];
    int head[SD_HULL_MAX_TRIS];  /* first outside point, -1 if none */
    int state[SD_HULL_MAX_TRIS]; /* 0 free, 1 alive, 2 visible from the current point */
    int free_next[SD_HULL_MAX_TRIS];
    int stack_f[SD_HULL_MAX_TRIS], stack_e[SD_HULL_MAX_TRIS], stack_left[SD_HULL_MAX_TRIS];
    int hor_f[SD_HULL_MAX_TRIS], hor_e[SD_HULL_MAX_TRIS]; /* horizon: visible face, its edge */
    int newf[SD_HULL_MAX_TRIS];
    int vis[SD_HULL_MAX_TRIS];
    int pending[SD_HULL_MAX_POINTS]; /* outside points of removed faces */
    int remap[SD_HULL_MAX_TRIS];
    sd_real dcen[SD_HULL_MAX_TRIS]; /* plane offsets about the centre, by output triangle */
    int uf[SD_HULL_MAX_TRIS];
    int vface[SD_HULL_MAX_POINTS][3]; /* distinct face ids seen at a vertex (3 = extreme) */
    int vfaces[SD_HULL_MAX_POINTS];
    int nface_slots, free_head;
} sd_hull_workspace;

/* ---- internal steps -------------------------------------------------------- */

SD_HD static SD_INLINE sd_real sd_hull_dist(const sd_hull_workspace *ws, int f, sd_vec3 x)
{
    return sd_v3_dot(ws->n[f], x) - ws->d[f];
}

/* A new triangle (a, b, c) from the free list (or the end); -1 when full. */
SD_HD static SD_INLINE int sd_hull_face_new(sd_hull_workspace *ws, int a, int b, int c)
{
    int f;
    if (ws->free_head >= 0) {
        f = ws->free_head;
        ws->free_head = ws->free_next[f];
    } else {
        if (ws->nface_slots >= SD_HULL_MAX_TRIS)
            return -1;
        f = ws->nface_slots++;
    }
    ws->v[f][0] = a;
    ws->v[f][1] = b;
    ws->v[f][2] = c;
    ws->nb[f][0] = ws->nb[f][1] = ws->nb[f][2] = -1;
    ws->head[f] = -1;
    ws->state[f] = 1;
    /* normal from the cross product of the two edges at a; the plane offset
     * from the centroid averages the rounding of the three vertices */
    sd_vec3 pa = ws->p[a], pb = ws->p[b], pc = ws->p[c];
    sd_vec3 n = sd_v3_cross(sd_v3_sub(pb, pa), sd_v3_sub(pc, pa));
    n = sd_v3_normalize(n);
    ws->n[f] = n;
    ws->d[f] = sd_v3_dot(n, pa) / SD_R(3.0) + sd_v3_dot(n, pb) / SD_R(3.0) + sd_v3_dot(n, pc) / SD_R(3.0);
    return f;
}

SD_HD static SD_INLINE void sd_hull_face_free(sd_hull_workspace *ws, int f)
{
    ws->state[f] = 0;
    ws->free_next[f] = ws->free_head;
    ws->free_head = f;
}

/* Gives point i to the face among fs[0..nf) it lies farthest above (more
 * than eps); the face's farthest point stays at the head of its list. */
SD_HD static SD_INLINE void sd_hull_assign(sd_hull_workspace *ws, int i, const int *fs, int nf, sd_real eps)
{
    int best = -1;
    sd_real bd = eps;
    for (int k = 0; k < nf; ++k) {
        sd_real h = sd_hull_dist(ws, fs[k], ws->p[i]);
        if (h > bd) {
            bd = h;
            best = fs[k];
        }
    }
    if (best < 0)
        return; /* inside or on the hull: dropped */
    int h0 = ws->head[best];
    if (h0 >= 0 && sd_hull_dist(ws, best, ws->p[h0]) >= bd) {
        /* not farther than the head: insert after it */
        ws->pnext[i] = ws->pnext[h0];
        ws->pnext[h0] = i;
    } else {
        ws->pnext[i] = h0;
        ws->head[best] = i;
    }
}

/* Index k of the edge b -> a in face f, or -1. */
SD_HD static SD_INLINE int sd_hull_edge_index(const sd_hull_workspace *ws, int f, int b, int a)
{
    for (int k = 0; k < 3; ++k)
        if (ws->v[f][k] == b && ws->v[f][(k + 1) % 3] == a)
            return k;
    return -1;
}

SD_HD static SD_INLINE int sd_hull_uf_find(int *uf, int x)
{
    while (uf[x] != x) {
        uf[x] = uf[uf[x]];
        x = uf[x];
    }
    return x;
}

/* One attempt at tolerance eps. */
SD_HD static SD_INLINE sd_hull_status sd_hull_try(sd_hull_workspace *ws, int n, sd_real eps)
{
    ws->nface_slots = 0;
    ws->free_head = -1;
    /* --- initial tetrahedron: the two farthest apart of the six axis
     * extremes, the point farthest from their line, the point farthest
     * from their plane (ties: lowest index) */
    int ext[6];
    for (int k = 0; k < 6; ++k)
        ext[k] = 0;
    for (int i = 1; i < n; ++i) {
        sd_vec3 q = ws->p[i];
        if (q.x < ws->p[ext[0]].x)
            ext[0] = i;
        if (q.x > ws->p[ext[1]].x)
            ext[1] = i;
        if (q.y < ws->p[ext[2]].y)
            ext[2] = i;
        if (q.y > ws->p[ext[3]].y)
            ext[3] = i;
        if (q.z < ws->p[ext[4]].z)
            ext[4] = i;
        if (q.z > ws->p[ext[5]].z)
            ext[5] = i;
    }
    int i0 = ext[0], i1 = ext[1];
    sd_real best = -SD_R(1.0);
    for (int a = 0; a < 6; ++a)
        for (int b = a + 1; b < 6; ++b) {
            sd_real l2 = sd_v3_norm2(sd_v3_sub(ws->p[ext[a]], ws->p[ext[b]]));
            if (l2 > best) {
                best = l2;
                i0 = ext[a];
                i1 = ext[b];
            }
        }
    if (!(sd_sqrt(best) > eps))
        return SD_HULL_DEGENERATE; /* all points coincide */
    sd_vec3 e = sd_v3_normalize(sd_v3_sub(ws->p[i1], ws->p[i0]));
    int i2 = -1;
    best = eps;
    for (int i = 0; i < n; ++i) {
        sd_vec3 r = sd_v3_sub(ws->p[i], ws->p[i0]);
        sd_real dl = sd_v3_norm(sd_v3_cross(r, e));
        if (dl > best) {
            best = dl;
            i2 = i;
        }
    }
    if (i2 < 0)
        return SD_HULL_DEGENERATE; /* collinear */
    sd_vec3 pn = sd_v3_normalize(sd_v3_cross(sd_v3_sub(ws->p[i1], ws->p[i0]), sd_v3_sub(ws->p[i2], ws->p[i0])));
    int i3 = -1;
    best = eps;
    sd_real side = SD_R(0.0);
    for (int i = 0; i < n; ++i) {
        sd_real h = sd_v3_dot(pn, sd_v3_sub(ws->p[i], ws->p[i0]));
        if (sd_fabs(h) > best) {
            best = sd_fabs(h);
            i3 = i;
            side = h;
        }
    }
    if (i3 < 0)
        return SD_HULL_DEGENERATE; /* coplanar */
    if (side > SD_R(0.0)) {        /* keep i3 below the plane (i0, i1, i2) */
        int t = i1;
        i1 = i2;
        i2 = t;
    }
    int f0 = sd_hull_face_new(ws, i0, i1, i2);
    int f1 = sd_hull_face_new(ws, i0, i3, i1);
    int f2 = sd_hull_face_new(ws, i1, i3, i2);
    int f3 = sd_hull_face_new(ws, i2, i3, i0);
    int fs[4];
    fs[0] = f0;
    fs[1] = f1;
    fs[2] = f2;
    fs[3] = f3;
    for (int a = 0; a < 4; ++a)
        for (int k = 0; k < 3; ++k)
            for (int b = 0; b < 4; ++b) {
                int j = sd_hull_edge_index(ws, fs[b], ws->v[fs[a]][(k + 1) % 3], ws->v[fs[a]][k]);
                if (b != a && j >= 0)
                    ws->nb[fs[a]][k] = fs[b];
            }
    for (int i = 0; i < n; ++i)
        if (i != i0 && i != i1 && i != i2 && i != i3)
            sd_hull_assign(ws, i, fs, 4, eps);

    /* --- add the farthest outside point of the first face that has one */
    for (;;) {
        int fa = -1;
        for (int f = 0; f < ws->nface_slots; ++f)
            if (ws->state[f] == 1 && ws->head[f] >= 0) {
                fa = f;
                break;
            }
        if (fa < 0)
            break;
        int ip = ws->head[fa];
        sd_vec3 p = ws->p[ip];
        ws->head[fa] = ws->pnext[ip];

        /* depth-first walk of the visible faces; the horizon comes out as
         * an ordered loop (each face entered by edge j continues at j+1) */
        int nvis = 0, nhor = 0, top = 0;
        ws->state[fa] = 2;
        ws->vis[nvis++] = fa;
        ws->stack_f[0] = fa;
        ws->stack_e[0] = 0;
        ws->stack_left[0] = 3;
        top = 1;
        while (top > 0) {
            int t = top - 1;
            if (ws->stack_left[t] == 0) {
                --top;
                continue;
            }
            int f = ws->stack_f[t], k = ws->stack_e[t];
            ws->stack_e[t] = (k + 1) % 3;
            ws->stack_left[t]--;
            int g = ws->nb[f][k];
            if (g < 0)
                return SD_HULL_FAILED;
            if (ws->state[g] == 2)
                continue; /* an edge inside the visible region */
            if (sd_hull_dist(ws, g, p) > eps) {
                int j = sd_hull_edge_index(ws, g, ws->v[f][(k + 1) % 3], ws->v[f][k]);
                if (j < 0 || top >= SD_HULL_MAX_TRIS)
                    return SD_HULL_FAILED;
                ws->state[g] = 2;
                ws->vis[nvis++] = g;
                ws->stack_f[top] = g;
                ws->stack_e[top] = (j + 1) % 3;
                ws->stack_left[top] = 2;
                ++top;
            } else {
                ws->hor_f[nhor] = f;
                ws->hor_e[nhor] = k;
                ++nhor;
            }
        }
        /* the horizon must be one closed loop, or the visible region was
         * not a disc (nearly degenerate input): retry with a larger eps */
        if (nhor < 3)
            return SD_HULL_FAILED;
        for (int h = 0; h < nhor; ++h) {
            int f = ws->hor_f[h], k = ws->hor_e[h];
            int fn = ws->hor_f[(h + 1) % nhor], kn = ws->hor_e[(h + 1) % nhor];
            if (ws->v[f][(k + 1) % 3] != ws->v[fn][kn])
                return SD_HULL_FAILED;
        }
        /* outside points of the visible faces wait for the new faces */
        int npend = 0;
        for (int a = 0; a < nvis; ++a)
            for (int i = ws->head[ws->vis[a]]; i >= 0; i = ws->pnext[i])
                ws->pending[npend++] = i;
        /* the fan: triangle (a, b, p) on each horizon edge a -> b. Record
         * the edges first: freeing the visible faces recycles their slots. */
        for (int h = 0; h < nhor; ++h) {
            int f = ws->hor_f[h], k = ws->hor_e[h];
            ws->stack_f[h] = ws->v[f][k];           /* a */
            ws->stack_e[h] = ws->v[f][(k + 1) % 3]; /* b */
            ws->stack_left[h] = ws->nb[f][k];       /* the face that stays */
        }
        for (int a = 0; a < nvis; ++a)
            sd_hull_face_free(ws, ws->vis[a]);
        for (int h = 0; h < nhor; ++h) {
            int f = sd_hull_face_new(ws, ws->stack_f[h], ws->stack_e[h], ip);
            if (f < 0)
                return SD_HULL_FAILED;
            ws->newf[h] = f;
            int g = ws->stack_left[h];
            int j = sd_hull_edge_index(ws, g, ws->stack_e[h], ws->stack_f[h]);
            if (j < 0)
                return SD_HULL_FAILED;
            ws->nb[f][0] = g;
            ws->nb[g][j] = f;
        }
        for (int h = 0; h < nhor; ++h) {
            ws->nb[ws->newf[h]][1] = ws->newf[(h + 1) % nhor];
            ws->nb[ws->newf[h]][2] = ws->newf[(h + nhor - 1) % nhor];
        }
        for (int a = 0; a < npend; ++a)
            sd_hull_assign(ws, ws->pending[a], ws->newf, nhor, eps);
    }
    return SD_HULL_OK;
}

/* Builds the hull of pts[0..n). Returns SD_HULL_OK and fills *out. */
SD_HD static SD_INLINE sd_hull_status sd_hull_build(const sd_vec3 *pts, size_t n, sd_hull_workspace *ws, sd_hull *out)
{
    out->ntri = out->nface = out->nvert = 0;
    out->eps = SD_R(0.0);
    if (n < 4)
        return SD_HULL_TOO_FEW;
    if (n > SD_HULL_MAX_POINTS)
        return SD_HULL_TOO_MANY;
    int np = (int)n;
    /* work about the bounding-box centre: the tolerance then scales with
     * the size of the set, not with its distance from the origin */
    sd_vec3 lo = pts[0], hi = pts[0];
    for (int i = 1; i < np; ++i) {
        lo = sd_v3_min(lo, pts[i]);
        hi = sd_v3_max(hi, pts[i]);
    }
    sd_vec3 c = sd_v3_scale(sd_v3_add(lo, hi), SD_R(0.5));
    for (int i = 0; i < np; ++i)
        ws->p[i] = sd_v3_sub(pts[i], c);
    /* the input's own rounding is relative to its coordinates, not to the
     * set's extent: a cube's face points at 1e3 from the origin are coplanar
     * only to ~1e-13, so the tolerance follows max |coordinate| per axis */
    sd_vec3 m = sd_v3_max(sd_v3(sd_fabs(lo.x), sd_fabs(lo.y), sd_fabs(lo.z)),
                          sd_v3(sd_fabs(hi.x), sd_fabs(hi.y), sd_fabs(hi.z)));
    if (!(m.x + m.y + m.z < SD_R(1e300)))
        return SD_HULL_DEGENERATE; /* NaN or infinite input */
    sd_real eps = SD_HULL_REL_EPS * (m.x + m.y + m.z);
    sd_hull_status st = SD_HULL_FAILED;
    for (int attempt = 0; attempt < 4; ++attempt, eps *= SD_R(10.0)) {
        st = sd_hull_try(ws, np, eps);
        if (st != SD_HULL_FAILED)
            break;
    }
    if (st != SD_HULL_OK)
        return st;
    out->eps = eps;

    /* --- compact the live triangles, in slot order */
    int nt = 0;
    for (int f = 0; f < ws->nface_slots; ++f)
        ws->remap[f] = ws->state[f] == 1 ? nt++ : -1;
    for (int f = 0; f < ws->nface_slots; ++f) {
        int t = ws->remap[f];
        if (t < 0)
            continue;
        for (int k = 0; k < 3; ++k) {
            out->tri[t][k] = ws->v[f][k];
            out->nbr[t][k] = ws->remap[ws->nb[f][k]];
        }
        out->normal[t] = ws->n[f];
        out->offset[t] = ws->d[f] + sd_v3_dot(ws->n[f], c);
        ws->dcen[t] = ws->d[f];
    }
    out->ntri = nt;

    /* --- planar faces: join neighbours whose opposite vertices lie within
     * eps of each other's plane (both ways, so joining is symmetric) */
    for (int t = 0; t < nt; ++t)
        ws->uf[t] = t;
    for (int t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) {
            int u = out->nbr[t][k];
            if (u < t)
                continue;
            int ot = out->tri[t][(k + 2) % 3];
            int ou = -1;
            for (int j = 0; j < 3; ++j)
                if (out->tri[u][j] != out->tri[t][k] && out->tri[u][j] != out->tri[t][(k + 1) % 3])
                    ou = out->tri[u][j];
            /* measured about the centre, where eps was set */
            sd_real hu = sd_v3_dot(out->normal[u], ws->p[ot]) - ws->dcen[u];
            sd_real ht = sd_v3_dot(out->normal[t], ws->p[ou]) - ws->dcen[t];
            if (sd_fabs(hu) <= eps && sd_fabs(ht) <= eps) {
                int ra = sd_hull_uf_find(ws->uf, t), rb = sd_hull_uf_find(ws->uf, u);
                if (ra != rb)
                    ws->uf[ra < rb ? rb : ra] = ra < rb ? ra : rb;
            }
        }
    int nf = 0;
    for (int t = 0; t < nt; ++t)
        ws->remap[t] = -1;
    for (int t = 0; t < nt; ++t) {
        int r = sd_hull_uf_find(ws->uf, t);
        if (ws->remap[r] < 0)
            ws->remap[r] = nf++;
        out->face[t] = ws->remap[r];
    }
    out->nface = nf;

    /* --- extreme vertices: corners of three or more distinct faces */
    for (int i = 0; i < np; ++i)
        ws->vfaces[i] = 0;
    for (int t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) {
            int i = out->tri[t][k], fid = out->face[t], seen = 0;
            for (int j = 0; j < ws->vfaces[i] && j < 3; ++j)
                seen |= ws->vface[i][j] == fid;
            if (!seen && ws->vfaces[i] < 3)
                ws->vface[i][ws->vfaces[i]++] = fid;
        }
    int nv = 0;
    for (int i = 0; i < np; ++i)
        if (ws->vfaces[i] >= 3)
            out->vert[nv++] = i;
    out->nvert = nv;
    return SD_HULL_OK;
}

/* Volume enclosed by the hull (m^3): tetrahedra from one hull vertex. */
SD_HD static SD_INLINE sd_real sd_hull_volume(const sd_hull *h, const sd_vec3 *pts)
{
    if (h->ntri == 0)
        return SD_R(0.0);
    sd_vec3 o = pts[h->tri[0][0]];
    sd_real v6 = SD_R(0.0);
    for (int t = 0; t < h->ntri; ++t) {
        sd_vec3 a = sd_v3_sub(pts[h->tri[t][0]], o), b = sd_v3_sub(pts[h->tri[t][1]], o),
                c = sd_v3_sub(pts[h->tri[t][2]], o);
        v6 += sd_v3_dot(a, sd_v3_cross(b, c));
    }
    return v6 / SD_R(6.0);
}

#endif
