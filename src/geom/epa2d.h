/* epa2d.h — 2D EPA penetration of two overlapping convex cores, and the
 * contact geometry of two posed planar bodies (sd_contact2d_convex).
 * Single source (SD_HD): C17 and CUDA C++, no allocation, no printing, fixed
 * arrays (SD_EPA2D_MAX_VERTS polygon vertices).
 *
 * EPA (seed 002 §2.2, "the classical GJK and EPA"): the depth is the
 * distance from the origin (inside K = A − B) to the boundary of K. A convex
 * polygon P ⊂ K of support points, counter-clockwise, gives on its nearest
 * edge a lower bound (the edge's distance f) and, along that edge's outward
 * normal n, an upper bound n·w (w the support of K). P grows by w, inserted
 * between the edge's ends, until the bounds meet.
 *
 * Invariant: P's vertices are support points of K in boundary order, so P is
 * convex and P ⊂ K. In 2D a new support point lies on the arc of ∂K cut off
 * by the edge it expands, so inserting it between that edge's ends keeps the
 * order: no horizon search is needed (unlike 3D, epa.h). Nothing divides by
 * a quantity that can vanish unchecked; the result is never NaN.
 *
 * Start: GJK's final simplex. A triangle is used as is; a segment through
 * the origin (aligned polygons, notes/algorithms.md §C, OpenRAL #215) gets
 * the supports along its two normals; a single point gets the supports along
 * ±x, ±y. If the support along a normal of the start segment adds nothing
 * beyond it, the origin is on ∂K: the cores just touch (TOUCHING, depth 0,
 * that normal) — the contact is not dropped (mujoco_warp #1526).
 *
 * Termination: n·w − f ≤ 1e-8·max(f, 1e-6 L) → OK (seed 002 Fig. 8: the
 * residual falls by ~1e6 in 10 iterations on smooth outlines); a duplicate
 * support → OK; 64 iterations or a full vertex array → CAPPED with the best
 * edge so far (its distance is a lower bound of the depth).
 *
 * Contact (sd_contact2d_convex): shrink / GJK / swell (seed 004 §2.5) as in
 * 3D (geom/convex_contact.h): while the cores are apart the swept bodies
 * overlap by δ = ra + rb − d exactly, along the GJK direction, with no EPA;
 * only when the cores touch or overlap does EPA give the core depth D and
 * δ = D + ra + rb. Sharp shapes (radius 0: polygons, Fourier, polybézier)
 * therefore always go through EPA when they overlap — as in seed 002.
 */
#ifndef SD_GEOM_EPA2D_H
#define SD_GEOM_EPA2D_H

#include "geom/gjk2d.h"

typedef enum {
    SD_EPA2D_OK,        /* converged: depth within the tolerance */
    SD_EPA2D_TOUCHING,  /* origin on ∂K: depth 0 */
    SD_EPA2D_CAPPED,    /* iteration or vertex cap: depth is a lower bound */
    SD_EPA2D_DEGENERATE /* K is flat (a point or a segment): depth 0 */
} sd_epa2d_status;

#define SD_EPA2D_MAX_VERTS      72
#define SD_EPA2D_MAX_ITERATIONS 64
#define SD_EPA2D_REL_TOL        SD_R(1e-8)

typedef struct sd_epa2d_result {
    int status;     /* sd_epa2d_status */
    sd_real depth;  /* m, core penetration depth ≥ 0 */
    sd_vec2 normal; /* unit, outward normal of K at its point nearest the origin:
                       from A into B (moving A by −depth·normal separates them) */
    sd_vec2 pa, pb; /* deepest points of the cores, world: pa − pb = depth·normal */
    int iterations, support_calls;
} sd_epa2d_result;

typedef struct sd_epa2d_poly {
    sd_gjk2d_vertex v[SD_EPA2D_MAX_VERTS];
    int n;
} sd_epa2d_poly;

/* Outward normal and signed distance of edge i → i+1 of the CCW polygon;
 * returns 0 for a zero-length edge. */
SD_HD static SD_INLINE int sd_epa2d_edge(const sd_epa2d_poly *P, int i, sd_vec2 *n, sd_real *dist)
{
    const sd_vec2 p = P->v[i].w, q = P->v[(i + 1) % P->n].w;
    const sd_vec2 e = sd_v2_sub(q, p);
    const sd_real len = sd_v2_norm(e);
    if (!(len > SD_R(0.0)))
        return 0;
    *n = sd_v2(e.y / len, -e.x / len);
    *dist = sd_v2_dot(*n, p);
    return 1;
}

SD_HD static SD_INLINE void sd_epa2d_insert(sd_epa2d_poly *P, int after, sd_gjk2d_vertex w)
{
    for (int k = P->n; k > after + 1; --k)
        P->v[k] = P->v[k - 1];
    P->v[after + 1] = w;
    P->n++;
}

/* Fills r from edge i of P (the closest point of the edge to the origin). */
SD_HD static SD_INLINE void sd_epa2d_finish(const sd_epa2d_poly *P, int i, sd_vec2 n, sd_real dist, sd_epa2d_result *r)
{
    const sd_gjk2d_vertex p = P->v[i], q = P->v[(i + 1) % P->n];
    const sd_real t = sd_gjk2d_segment_t(p.w, q.w);
    r->normal = n;
    r->depth = sd_max(dist, SD_R(0.0));
    r->pa = sd_v2_madd(p.a, t, sd_v2_sub(q.a, p.a));
    r->pb = sd_v2_madd(p.b, t, sd_v2_sub(q.b, p.b));
}

/* Penetration of the cores of a and b, starting from GJK's final simplex g
 * (status TOUCHING or OVERLAP). */
SD_HD static SD_INLINE sd_epa2d_result sd_epa2d_penetration(const sd_convex2d *ca, const sd_convex2d *cb,
                                                            const sd_gjk2d_result *g)
{
    sd_epa2d_result r;
    const sd_gjk2d_body A = sd_gjk2d_pose(ca), B = sd_gjk2d_pose(cb);
    const sd_real L = sd_gjk2d_length_scale(ca, cb);
    const sd_real dup2 = sd_sq(SD_R(1e-12) * L);
    sd_epa2d_poly P;
    r.iterations = 0;
    r.support_calls = 0;
    r.depth = SD_R(0.0);
    r.normal = sd_v2_normalize(g->dir);
    if (!(sd_v2_norm2(r.normal) > SD_R(0.0)))
        r.normal = sd_v2(SD_R(1.0), SD_R(0.0));
    r.pa = g->pa;
    r.pb = g->pb;
    r.status = SD_EPA2D_DEGENERATE;

    const sd_gjk2d_simplex *s = &g->simplex;
    P.n = 0;
    if (s->n == 3) {
        P.v[0] = s->v[0];
        if (sd_v2_cross(sd_v2_sub(s->v[1].w, s->v[0].w), sd_v2_sub(s->v[2].w, s->v[0].w)) >= SD_R(0.0)) {
            P.v[1] = s->v[1];
            P.v[2] = s->v[2];
        } else {
            P.v[1] = s->v[2];
            P.v[2] = s->v[1];
        }
        P.n = 3;
    } else if (s->n == 2 && sd_v2_norm2(sd_v2_sub(s->v[1].w, s->v[0].w)) > dup2) {
        /* the origin on the segment: add the supports along its normals; the
         * CCW order is p, (right), q, (left) */
        const sd_vec2 m = sd_v2_normalize(sd_v2_perp(sd_v2_sub(s->v[1].w, s->v[0].w)));
        const sd_gjk2d_vertex left = sd_gjk2d_support(&A, &B, m);
        const sd_gjk2d_vertex right = sd_gjk2d_support(&A, &B, sd_v2_neg(m));
        r.support_calls += 2;
        if (!sd_gjk2d_finite(left.w) || !sd_gjk2d_finite(right.w))
            return r;
        const sd_real off = sd_v2_dot(m, s->v[0].w); /* the segment's offset along m (~0) */
        const sd_real tol = SD_R(1e-12) * L;
        const sd_real hl = sd_v2_dot(m, left.w) - off, hr = off - sd_v2_dot(m, right.w);
        if (hl <= tol || hr <= tol) { /* K lies on one side of the segment's line */
            r.status = SD_EPA2D_TOUCHING;
            r.normal = hl <= hr ? m : sd_v2_neg(m);
            r.depth = SD_R(0.0);
            const sd_real t = s->lambda[1];
            r.pa = sd_v2_madd(s->v[0].a, t, sd_v2_sub(s->v[1].a, s->v[0].a));
            r.pb = sd_v2_madd(s->v[0].b, t, sd_v2_sub(s->v[1].b, s->v[0].b));
            return r;
        }
        P.v[0] = s->v[0];
        P.v[1] = right;
        P.v[2] = s->v[1];
        P.v[3] = left;
        P.n = 4;
    } else {
        /* a single point: supports along +x, +y, −x, −y (boundary order) */
        const sd_vec2 dirs[4] = {
            {SD_R(1.0), SD_R(0.0)}, {SD_R(0.0), SD_R(1.0)}, {SD_R(-1.0), SD_R(0.0)}, {SD_R(0.0), SD_R(-1.0)}};
        for (int k = 0; k < 4; ++k) {
            const sd_gjk2d_vertex w = sd_gjk2d_support(&A, &B, dirs[k]);
            r.support_calls++;
            if (!sd_gjk2d_finite(w.w))
                return r;
            if (P.n == 0 ||
                (sd_v2_norm2(sd_v2_sub(w.w, P.v[P.n - 1].w)) > dup2 && sd_v2_norm2(sd_v2_sub(w.w, P.v[0].w)) > dup2))
                P.v[P.n++] = w;
        }
        if (P.n < 3) { /* K is a point or a segment: the cores only touch */
            r.status = SD_EPA2D_TOUCHING;
            r.depth = SD_R(0.0);
            return r;
        }
    }

    int best = 0;
    sd_vec2 bn = r.normal;
    sd_real bd = SD_R(0.0);
    for (;;) {
        /* the nearest edge (smallest signed distance) */
        best = -1;
        bd = SD_R(1e300);
        for (int i = 0; i < P.n; ++i) {
            sd_vec2 n;
            sd_real dist;
            if (sd_epa2d_edge(&P, i, &n, &dist) && dist < bd) {
                bd = dist;
                bn = n;
                best = i;
            }
        }
        if (best < 0) /* every edge has zero length: cannot happen with n ≥ 3 distinct points */
            return r;
        if (r.iterations >= SD_EPA2D_MAX_ITERATIONS || P.n >= SD_EPA2D_MAX_VERTS) {
            r.status = SD_EPA2D_CAPPED;
            break;
        }
        r.iterations++;
        const sd_gjk2d_vertex w = sd_gjk2d_support(&A, &B, bn);
        r.support_calls++;
        if (!sd_gjk2d_finite(w.w)) {
            r.status = SD_EPA2D_DEGENERATE;
            break;
        }
        const sd_real gap = sd_v2_dot(bn, w.w) - bd;
        const sd_real tol = SD_EPA2D_REL_TOL * sd_max(bd, SD_R(1e-6) * L);
        const int dup = sd_v2_norm2(sd_v2_sub(w.w, P.v[best].w)) <= dup2 ||
                        sd_v2_norm2(sd_v2_sub(w.w, P.v[(best + 1) % P.n].w)) <= dup2;
        if (gap <= tol || dup) {
            r.status = bd <= SD_R(1e-12) * L ? SD_EPA2D_TOUCHING : SD_EPA2D_OK;
            break;
        }
        sd_epa2d_insert(&P, best, w);
    }
    sd_epa2d_finish(&P, best, bn, bd, &r);
    return r;
}

/* ---- contact of two posed bodies ------------------------------------------ */

typedef enum {
    SD_CONTACT2D_SEPARATED, /* the swept bodies are apart: depth < 0 */
    SD_CONTACT2D_TOUCHING,  /* they just touch: depth 0 (to 1e-12 L) */
    SD_CONTACT2D_OVERLAP,   /* they overlap: depth > 0 */
    SD_CONTACT2D_DEGENERATE /* a non-finite pose or shape: no contact */
} sd_contact2d_status;

typedef struct sd_contact2d {
    int status;        /* sd_contact2d_status */
    sd_real depth;     /* m, > 0 when overlapping; < 0 when apart: −gap when measured,
                          else (gjk_bounded) an upper bound of −gap, below −skin */
    sd_vec2 normal;    /* unit, from a into b */
    sd_vec2 point;     /* m, contact point, world: midway between the two outer surfaces */
    int gjk_status;    /* sd_gjk2d_status of the core distance */
    int gjk_bounded;   /* GJK stopped early: the bodies are farther apart than the skin */
    int used_epa;      /* the cores touched or overlapped: EPA gave the depth */
    int epa_status;    /* sd_epa2d_status when used_epa, else -1 */
    int iterations;    /* GJK + EPA iterations */
    int support_calls; /* GJK + EPA support calls of K for this pair */
} sd_contact2d;

/* Contact of the swept bodies a and b. GJK stops as soon as the bodies are
 * proved farther apart than `skin` (m, ≥ 0). warm (may be NULL): the pair's
 * cached direction from a towards b, read as the start and updated to the
 * new normal. support_calls (may be NULL): INCREMENTED by this pair's
 * support calls (an accumulator per pair type, seed 002 Table 1). */
SD_HD static SD_INLINE sd_contact2d sd_contact2d_convex_skin(const sd_convex2d *a, const sd_convex2d *b, sd_vec2 *warm,
                                                             int *support_calls, sd_real skin)
{
    sd_contact2d c;
    const sd_real ra = a->shape->radius, rb = b->shape->radius;
    const sd_real L = sd_gjk2d_length_scale(a, b);
    const sd_gjk2d_result g =
        sd_gjk2d_distance_bounded(a, b, warm ? *warm : sd_v2_zero(), ra + rb + sd_max(skin, SD_R(0.0)));
    c.gjk_status = g.status;
    c.gjk_bounded = g.bounded;
    c.used_epa = 0;
    c.epa_status = -1;
    c.iterations = g.iterations;
    c.support_calls = g.support_calls;
    c.depth = SD_R(0.0);
    c.normal = sd_v2(SD_R(1.0), SD_R(0.0));
    c.point = sd_v2_scale(sd_v2_add(a->x, b->x), SD_R(0.5));
    c.status = SD_CONTACT2D_DEGENERATE;
    sd_vec2 pa = g.pa, pb = g.pb;
    if (g.status == SD_GJK2D_DEGENERATE) {
        if (support_calls)
            *support_calls += c.support_calls;
        return c;
    }
    if (g.status == SD_GJK2D_SEPARATED || g.status == SD_GJK2D_MAX_ITER) {
        /* shrink / GJK / swell: exact while the cores are apart; the normal
         * is −v (GJK keeps v exactly; pa − pb carries the weights' rounding) */
        c.depth = ra + rb - g.distance;
        const sd_vec2 n = sd_v2_normalize(g.dir);
        if (sd_v2_norm2(n) > SD_R(0.0))
            c.normal = n;
    } else {
        const sd_epa2d_result e = sd_epa2d_penetration(a, b, &g);
        c.used_epa = 1;
        c.epa_status = e.status;
        c.iterations += e.iterations;
        c.support_calls += e.support_calls;
        if (e.status == SD_EPA2D_DEGENERATE && !(ra + rb > SD_R(0.0))) {
            if (support_calls)
                *support_calls += c.support_calls;
            return c;
        }
        c.depth = e.depth + ra + rb;
        c.normal = e.normal;
        pa = e.pa;
        pb = e.pb;
    }
    const sd_real tol = SD_R(1e-12) * L;
    c.status =
        c.depth > tol ? SD_CONTACT2D_OVERLAP : (c.depth >= -tol ? SD_CONTACT2D_TOUCHING : SD_CONTACT2D_SEPARATED);
    /* A's outer surface along n is pa + ra n, B's is pb − rb n */
    c.point = sd_v2_scale(sd_v2_add(sd_v2_madd(pa, ra, c.normal), sd_v2_madd(pb, -rb, c.normal)), SD_R(0.5));
    if (warm)
        *warm = c.normal;
    if (support_calls)
        *support_calls += c.support_calls;
    return c;
}

/* The engine's entry point (skin 0): see sd_contact2d_convex_skin. */
SD_HD static SD_INLINE sd_contact2d sd_contact2d_convex(const sd_convex2d *a, const sd_convex2d *b, sd_vec2 *warm,
                                                        int *support_calls)
{
    return sd_contact2d_convex_skin(a, b, warm, support_calls, SD_R(0.0));
}

#endif
