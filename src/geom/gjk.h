/* gjk.h — GJK distance between the convex cores of two posed bodies.
 * Single source (SD_HD): compiles as C17 and as CUDA C++; no allocation, no
 * printing, fixed-size simplex, double precision.
 *
 * What: the Gilbert–Johnson–Keerthi iteration on the Minkowski difference
 * K = A − B of the two CORES (shape.h: every shape is a core swept by a
 * sphere; the caller adds the radii, seed 004 §2.5 shrink / GJK / swell, see
 * geom/convex_contact.h). It finds the point v of K closest to the origin;
 * |v| is the core distance and v = pa − pb gives witness points on each core.
 * The closest point of each simplex is found by the signed-volumes
 * sub-algorithm (Montanari, Petrinic & Barbieri 2017): the origin's
 * projection if its barycentric coordinates are all ≥ 0, else the nearest of
 * the faces / edges whose coordinate is ≤ 1e-9 (the former brute force over
 * all of them, restricted to those that can hold the answer): robust on the
 * slivers that curved cores produce near convergence. The simplex sits in
 * four fixed slots and is never copied; supports use the bodies' rotation
 * matrices, built once per query.
 *
 * Invariant: the simplex holds 1–4 support points w_i = a_i − b_i of K with
 * the support points a_i (of A) and b_i (of B) that made them, and barycentric
 * weights lambda_i ≥ 0 summing to 1 with v = Σ λ_i w_i; |v| never grows
 * between accepted iterations. The result is never NaN: a non-finite support
 * point ends the loop with SD_GJK_DEGENERATE.
 *
 * Termination, in this order (DESIGN.md engineering note "GJK/EPA",
 * notes/algorithms.md §C recommendation; L = sum of the two bounding radii):
 *   0. only when the caller asks (sd_gjk_distance_bounded, stop_beyond ≥ 0):
 *      a support point w in direction d proves the distance −d·w/|d| >
 *      stop_beyond → SEPARATED with bounded = 1 (the swept bodies of
 *      convex_contact.h cannot touch: nothing more is needed);
 *   1. duplicate support: |w − w_i| ≤ 1e-12 L for a simplex vertex → SEPARATED;
 *   2. relative gap |v|² − v·w ≤ 1e-10 |v|² → SEPARATED (distance exact to 1e-10);
 *   3. absolute |v| ≤ 1e-12 L → TOUCHING (the origin lies on the simplex:
 *      the cores touch or overlap; EPA tells which and how deep);
 *   4. no progress |v_k| ≥ |v_{k−1}|(1 − 1e-14) → SEPARATED with the best v;
 *   5. a tetrahedron that encloses the origin → OVERLAP;
 *   6. 64 iterations → SD_GJK_MAX_ITER (counted; the best v so far is kept).
 * Seed 002 Table 1 reports 2.9–6 support calls per pair for this loop.
 */
#ifndef SD_GEOM_GJK_H
#define SD_GEOM_GJK_H

#include "core/quat.h"
#include "core/vec.h"
#include "shape/shape.h"

/* The support function of a posed core. A test may substitute a reference
 * support (same signature) by defining SD_GJK_SUPPORT_CORE before including
 * this header; the engine uses shape/support.h. */
#ifndef SD_GJK_SUPPORT_CORE
#include "shape/support.h"
#define SD_GJK_SUPPORT_CORE sd_convex_support_core
#define SD_GJK_SUPPORT_FAST 1 /* the same support, with the rotation as a matrix */
#endif

typedef enum {
    SD_GJK_SEPARATED,  /* cores apart: distance > 0 with witnesses */
    SD_GJK_TOUCHING,   /* origin on the final simplex (|v| ≤ 1e-12 L): touch or overlap */
    SD_GJK_OVERLAP,    /* final tetrahedron encloses the origin */
    SD_GJK_DEGENERATE, /* non-finite support point (bad pose or shape) */
    SD_GJK_MAX_ITER    /* iteration cap; distance is the best upper bound found */
} sd_gjk_status;

#define SD_GJK_MAX_ITERATIONS 64
#define SD_GJK_REL_GAP SD_R(1e-10)
#define SD_GJK_ABS_TOL SD_R(1e-12)
#define SD_GJK_NO_PROGRESS SD_R(1e-14)

/* One point of K = A − B with the support points that made it. */
typedef struct sd_gjk_vertex {
    sd_vec3 w; /* a − b */
    sd_vec3 a; /* support point of core A, world, m */
    sd_vec3 b; /* support point of core B, world, m */
} sd_gjk_vertex;

typedef struct sd_gjk_simplex {
    sd_gjk_vertex v[4];
    sd_real lambda[4]; /* barycentric weights of the closest point */
    int n;             /* 1..4 */
} sd_gjk_simplex;

typedef struct sd_gjk_result {
    int status;        /* sd_gjk_status */
    sd_real distance;  /* m, core distance (0 when touching or overlapping) */
    sd_vec3 pa, pb;    /* witness points on the cores, world */
    sd_vec3 dir;       /* last search direction, for warm starts: −v when
                          separated (v = pa − pb exactly; the witnesses match
                          it to ~1e-11 L, the weights of a sliver are less exact) */
    int iterations, support_calls; /* support calls count K = A − B queries (one of A and one of B each) */
    int bounded;       /* 1: stopped early, the distance proved > stop_beyond
                          (sd_gjk_distance_bounded); distance is a lower bound */
    sd_gjk_simplex simplex;
} sd_gjk_result;

/* The support point of K in direction d: s_A(d) − s_B(−d). */
SD_HD static SD_INLINE sd_gjk_vertex sd_gjk_support(const sd_convex *a, const sd_convex *b, sd_vec3 d)
{
    sd_gjk_vertex v;
    v.a = SD_GJK_SUPPORT_CORE(a, d);
    v.b = SD_GJK_SUPPORT_CORE(b, sd_v3_neg(d));
    v.w = sd_v3_sub(v.a, v.b);
    return v;
}

/* |x| is finite for every component (false for NaN and ±inf). */
SD_HD static SD_INLINE int sd_gjk_finite(sd_vec3 p)
{
    const sd_real big = SD_R(1e300);
    return sd_fabs(p.x) <= big && sd_fabs(p.y) <= big && sd_fabs(p.z) <= big;
}

/* The pair's length scale L (tolerances are relative to it). */
SD_HD static SD_INLINE sd_real sd_gjk_length_scale(const sd_convex *a, const sd_convex *b)
{
    sd_real L = a->shape->bound + b->shape->bound;
    return L > SD_R(0.0) ? L : SD_R(1.0); /* two bare points: any scale will do */
}

/* ---- the closest-point sub-algorithm: signed volumes ------------------
 *
 * Montanari, Petrinic & Barbieri 2017 (ACM TOG 36(3) 30, "Improving the
 * GJK algorithm for faster and more reliable distance queries between
 * convex objects"), §3: the barycentric coordinates of the origin's
 * projection on a k-simplex are ratios of signed volumes (determinants);
 * the projection lies in the simplex when every coordinate has the sign of
 * the whole, and otherwise the answer lies on a facet whose coordinate is
 * not positive. Triangles are measured in the coordinate plane on which
 * their shadow is largest (S2D), which keeps the areas of the thin triangles
 * of curved cores well conditioned where the products of Voronoi-region
 * tests cancel. Two safeguards over the paper: facets whose coordinate is
 * below SD_GJK_SV_NEAR (rounding may have flipped its sign) are candidates
 * too, and among the candidates the nearest is kept (as the former brute
 * force over all facets did), so a blurred sign cannot pick a far facet.
 *
 * The functions work on the points p[] of K only and return a selection
 * (indices into p[] and weights); the simplex is never copied. */
#define SD_GJK_SV_NEAR SD_R(1e-9)

typedef struct sd_gjk_sel {
    int n;             /* 1..4 points kept */
    int idx[4];        /* their indices into p[] */
    sd_real lambda[4]; /* their barycentric weights, ≥ 0, sum 1 */
} sd_gjk_sel;

/* S1D: closest point of segment (p[i], p[j]) to the origin. */
SD_HD static SD_INLINE sd_vec3 sd_gjk_sv_segment(const sd_vec3 *p, int i, int j, sd_gjk_sel *s)
{
    sd_vec3 a = p[i], b = p[j];
    sd_vec3 ab = sd_v3_sub(b, a);
    sd_real ab2 = sd_v3_norm2(ab);
    sd_real t = ab2 > SD_R(0.0) ? -sd_v3_dot(a, ab) / ab2 : SD_R(1.0);
    if (t <= SD_R(0.0)) {
        s->n = 1;
        s->idx[0] = i;
        s->lambda[0] = SD_R(1.0);
        return a;
    }
    if (t >= SD_R(1.0)) {
        s->n = 1;
        s->idx[0] = j;
        s->lambda[0] = SD_R(1.0);
        return b;
    }
    s->n = 2;
    s->idx[0] = i;
    s->idx[1] = j;
    s->lambda[0] = SD_R(1.0) - t;
    s->lambda[1] = t;
    /* a + t ab, minus its component along ab, so v ⟂ ab to rounding: the
     * relative-gap test then sees the exact distance */
    sd_vec3 v = sd_v3_madd(a, t, ab);
    return sd_v3_madd(v, -sd_v3_dot(v, ab) / ab2, ab);
}

/* 2D cross product of x and y in the coordinate plane (k1, k2). */
SD_HD static SD_INLINE sd_real sd_gjk_cross2(sd_vec3 x, sd_vec3 y, int drop)
{
    if (drop == 0)
        return x.y * y.z - x.z * y.y;
    if (drop == 1)
        return x.z * y.x - x.x * y.z;
    return x.x * y.y - x.y * y.x;
}

/* S2D: closest point of triangle (p[i], p[j], p[k]) to the origin, given
 * its normal nrm = (p[j] − p[i]) × (p[k] − p[i]). */
SD_HD static SD_INLINE sd_vec3 sd_gjk_sv_triangle_n(const sd_vec3 *p, int i, int j, int k, sd_vec3 nrm,
                                                     sd_gjk_sel *s)
{
    sd_vec3 a = p[i], b = p[j], c = p[k];
    sd_real n2 = sd_v3_norm2(nrm);
    /* candidate edges when the projection falls outside: (i,j), (i,k), (j,k),
     * opposite k, j and i */
    int cand[3] = {1, 1, 1};
    if (n2 > SD_R(0.0)) {
        /* the projection of the origin on the plane, from the normal: exactly
         * perpendicular to the face, so |v| is the true distance to the plane */
        sd_vec3 q = sd_v3_scale(nrm, sd_v3_dot(nrm, a) / n2);
        /* signed areas in the coordinate plane of the largest shadow: the
         * one that drops the normal's largest component (Montanari eq. 12) */
        sd_real ax = sd_fabs(nrm.x), ay = sd_fabs(nrm.y), az = sd_fabs(nrm.z);
        int drop = ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
        sd_real mu = drop == 0 ? nrm.x : (drop == 1 ? nrm.y : nrm.z); /* the shadow's area, ×2, signed */
        sd_vec3 qa = sd_v3_sub(a, q), qb = sd_v3_sub(b, q), qc = sd_v3_sub(c, q);
        sd_real l0 = sd_gjk_cross2(qb, qc, drop);
        sd_real l1 = sd_gjk_cross2(qc, qa, drop);
        sd_real l2 = sd_gjk_cross2(qa, qb, drop);
        if (mu < SD_R(0.0)) {
            l0 = -l0;
            l1 = -l1;
            l2 = -l2;
        }
        sd_real ls = l0 + l1 + l2;
        if (l0 >= SD_R(0.0) && l1 >= SD_R(0.0) && l2 >= SD_R(0.0) && ls > SD_R(0.0)) {
            s->n = 3;
            s->idx[0] = i;
            s->idx[1] = j;
            s->idx[2] = k;
            s->lambda[0] = l0 / ls;
            s->lambda[1] = l1 / ls;
            s->lambda[2] = l2 / ls;
            return q;
        }
        if (ls > SD_R(0.0)) {
            sd_real near = SD_GJK_SV_NEAR * ls;
            cand[0] = l2 <= near;
            cand[1] = l1 <= near;
            cand[2] = l0 <= near;
            if (!cand[0] && !cand[1] && !cand[2])
                cand[0] = cand[1] = cand[2] = 1;
        }
    }
    sd_gjk_sel best, t;
    sd_vec3 bestv = sd_v3_zero();
    sd_real bestd = SD_R(-1.0);
    const int e0[3] = {i, i, j}, e1[3] = {j, k, k};
    best.n = 0;
    for (int e = 0; e < 3; ++e) {
        if (!cand[e])
            continue;
        sd_vec3 v = sd_gjk_sv_segment(p, e0[e], e1[e], &t);
        sd_real d = sd_v3_norm2(v);
        if (bestd < SD_R(0.0) || d < bestd) {
            bestd = d;
            best = t;
            bestv = v;
        }
    }
    *s = best;
    return bestv;
}

SD_HD static SD_INLINE sd_vec3 sd_gjk_sv_triangle(const sd_vec3 *p, int i, int j, int k, sd_gjk_sel *s)
{
    sd_vec3 nrm = sd_v3_cross(sd_v3_sub(p[j], p[i]), sd_v3_sub(p[k], p[i]));
    return sd_gjk_sv_triangle_n(p, i, j, k, nrm, s);
}

/* S3D: closest point of the tetrahedron p[0..3] to the origin; sets *inside
 * when the origin is enclosed (then v = 0 and all four weights are kept). */
SD_HD static SD_INLINE sd_vec3 sd_gjk_sv_tetrahedron(const sd_vec3 *p, sd_gjk_sel *s, int *inside)
{
    /* face f is opposite vertex f, and the four faces are wound alike, so
     * so[f] = 6 × the signed volume of (face f, origin) and their sum is
     * 6 × the signed volume of the tetrahedron (Montanari et al. 2017 §3.3:
     * det M is the sum of the cofactors C_j). The origin's weight for vertex
     * f is so[f] / Σ so, and the origin is enclosed when every so[f] has one
     * strict sign.
     *
     * Why not so[f] / sv[f], with sv[f] = n_f · (p_f − a) measured per face
     * (what this function did before)? On curved cores GJK's late support
     * points cluster (three within 3e-9 m of each other on a 2.6 mm
     * cylinder's rim), and the tetrahedron becomes a needle: each sv[f] is
     * then the difference of terms ~1e8 times larger than itself, its sign is
     * rounding noise, and with four independent noisy signs the test "so[f]
     * and sv[f] agree for every f" passed for an origin 4.5e-5 m outside K
     * (weights 3e9 instead of summing to 1). GJK reported OVERLAP, EPA then
     * found the cores touching (depth 0), and a margined pair's overlap
     * jumped from 7.7e-6 m to ra + rb = 5.24e-5 m for one step: a 16-fold
     * energy gain (issue 11 §5). The so[f] of that needle are accurate
     * (relative error ~1e-9; they measure the origin's distance from each
     * face, not the needle's thickness), and their signs are mixed, as they
     * must be. Which tetrahedra appear depends on the warm-start direction,
     * hence on friction (the spin) and on the pair-list rebuilds. */
    const int fi[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    sd_vec3 nrm[4];
    sd_real so[4], det = SD_R(0.0), sabs = SD_R(0.0);
    int npos = 0, nneg = 0;
    for (int f = 0; f < 4; ++f) {
        sd_vec3 a = p[fi[f][0]];
        nrm[f] = sd_v3_cross(sd_v3_sub(p[fi[f][1]], a), sd_v3_sub(p[fi[f][2]], a));
        so[f] = -sd_v3_dot(nrm[f], a); /* origin side */
        det += so[f];
        sabs += sd_fabs(so[f]);
        npos += so[f] > SD_R(0.0);
        nneg += so[f] < SD_R(0.0);
    }
    *inside = 0;
    if (npos == 4 || nneg == 4) {
        /* one sign: Σ so adds like terms, no cancellation, weights in (0, 1) */
        s->n = 4;
        for (int f = 0; f < 4; ++f) {
            s->idx[f] = f;
            s->lambda[f] = so[f] / det;
        }
        *inside = 1;
        return sd_v3_zero();
    }
    /* the origin is outside: the nearest point is on a face whose weight
     * so[f] / det is not positive (or nearly so: rounding blurs the signs).
     * When det itself is lost in the cancellation of Σ so (a flat or needle
     * tetrahedron) no sign can be trusted and every face is tried. */
    const int trust = sd_fabs(det) > SD_R(1e-6) * sabs;
    sd_gjk_sel best, t;
    sd_vec3 bestv = sd_v3_zero();
    sd_real bestd = SD_R(-1.0);
    best.n = 0;
    for (int pass = trust ? 0 : 1; pass < 2 && bestd < SD_R(0.0); ++pass)
        for (int f = 0; f < 4; ++f) {
            /* pass 0: the candidates; pass 1 (none was, or det is noise): every face */
            if (pass == 0 && !(so[f] * det <= SD_GJK_SV_NEAR * det * det))
                continue;
            sd_vec3 v = sd_gjk_sv_triangle_n(p, fi[f][0], fi[f][1], fi[f][2], nrm[f], &t);
            sd_real d = sd_v3_norm2(v);
            if (bestd < SD_R(0.0) || d < bestd) {
                bestd = d;
                best = t;
                bestv = v;
            }
        }
    *s = best;
    return bestv;
}

/* Closest point of the simplex p[0..n−1] to the origin, as a selection of
 * its points. Returns 1 if a tetrahedron encloses the origin. */
SD_HD static SD_INLINE int sd_gjk_sv_solve(const sd_vec3 *p, int n, sd_gjk_sel *s, sd_vec3 *v)
{
    int inside = 0;
    switch (n) {
    case 1:
        s->n = 1;
        s->idx[0] = 0;
        s->lambda[0] = SD_R(1.0);
        *v = p[0];
        break;
    case 2:
        *v = sd_gjk_sv_segment(p, 0, 1, s);
        break;
    case 3:
        *v = sd_gjk_sv_triangle(p, 0, 1, 2, s);
        break;
    default:
        *v = sd_gjk_sv_tetrahedron(p, s, &inside);
        break;
    }
    return inside;
}

/* Closest point of the simplex to the origin; reduces it to the smallest
 * subset that holds that point. Returns 1 if a tetrahedron encloses the origin. */
SD_HD static SD_INLINE int sd_gjk_solve(sd_gjk_simplex *s, sd_vec3 *v)
{
    sd_vec3 p[4];
    sd_gjk_vertex y[4];
    sd_gjk_sel sel;
    for (int m = 0; m < s->n; ++m) {
        p[m] = s->v[m].w;
        y[m] = s->v[m];
    }
    int inside = sd_gjk_sv_solve(p, s->n, &sel, v);
    s->n = sel.n;
    for (int m = 0; m < sel.n; ++m) {
        s->v[m] = y[sel.idx[m]];
        s->lambda[m] = sel.lambda[m];
    }
    return inside;
}

/* Witness points pa = Σ λ a_i, pb = Σ λ b_i. */
SD_HD static SD_INLINE void sd_gjk_witnesses(const sd_gjk_simplex *s, sd_vec3 *pa, sd_vec3 *pb)
{
    sd_vec3 a = sd_v3_zero(), b = sd_v3_zero();
    for (int i = 0; i < s->n; ++i) {
        a = sd_v3_madd(a, s->lambda[i], s->v[i].a);
        b = sd_v3_madd(b, s->lambda[i], s->v[i].b);
    }
    *pa = a;
    *pb = b;
}

/* One body of a GJK query: the posed core with its rotation as a matrix,
 * built once per query, so that a support costs two 3×3 products rather than
 * two quaternion rotations (shape/support.h, sd_convex_support_core_m). */
typedef struct sd_gjk_body {
    const sd_convex *c;
    sd_mat3 R;     /* principal frame to world, from c->q */
    sd_real scale; /* m, |x|_1 + bound: the size of the body's coordinates, which
                      sets their rounding (geom/convex_contact.h, sd_convex_apart_along) */
} sd_gjk_body;

SD_HD static SD_INLINE sd_gjk_body sd_gjk_body_of(const sd_convex *c)
{
    sd_gjk_body b;
    b.c = c;
    b.R = sd_quat_to_mat3(c->q);
    b.scale = sd_fabs(c->x.x) + sd_fabs(c->x.y) + sd_fabs(c->x.z) + c->shape->bound;
    return b;
}

/* The support point of K in direction d, into *v. */
SD_HD static SD_INLINE void sd_gjk_support_body(const sd_gjk_body *a, const sd_gjk_body *b, sd_vec3 d, sd_gjk_vertex *v)
{
#ifdef SD_GJK_SUPPORT_FAST
    v->a = sd_convex_support_core_m(a->c, &a->R, d);
    v->b = sd_convex_support_core_m(b->c, &b->R, sd_v3_neg(d));
#else
    v->a = SD_GJK_SUPPORT_CORE(a->c, d);
    v->b = SD_GJK_SUPPORT_CORE(b->c, sd_v3_neg(d));
#endif
    v->w = sd_v3_sub(v->a, v->b);
}

/* GJK's first search direction: warm_dir, the pair's cached direction,
 * when it is finite and not zero; else xb − xa (K's near side faces the
 * origin along it); else +x. sd_convex_apart_along tests the same
 * direction before GJK (geom/convex_contact.h). */
SD_HD static SD_INLINE sd_vec3 sd_gjk_start_dir(const sd_convex *a, const sd_convex *b, sd_vec3 warm_dir)
{
    sd_vec3 d = warm_dir;
    if (!(sd_v3_norm2(d) > SD_R(0.0)) || !sd_gjk_finite(d))
        d = sd_v3_sub(b->x, a->x);
    if (!(sd_v3_norm2(d) > SD_R(0.0)))
        d = sd_v3(SD_R(1.0), SD_R(0.0), SD_R(0.0));
    return d;
}

/* GJK distance between the cores of a and b. warm_dir: a search direction
 * to start from (the previous result's dir for this pair), or zero for the
 * centre-to-centre direction.
 *
 * stop_beyond ≥ 0 asks for an early answer: as soon as a support point
 * proves the core distance greater than stop_beyond (the lower bound
 * −d·w/|d| of the search direction d and its support point w, Gilbert,
 * Johnson & Keerthi 1988 §V), the loop ends with SD_GJK_SEPARATED and
 * r.bounded = 1; distance is then that lower bound (not the distance),
 * the witnesses are the current simplex's, and dir is the direction that
 * separates, the best warm start for the next query. A negative
 * stop_beyond never stops early (sd_gjk_distance). The bodies carry their
 * rotation matrices (sd_gjk_body_of): a caller that queries one body
 * against many builds it once (a composite's element, posed once for all
 * the element pairs of its run, backend/items.h); the same matrices, so
 * the same bits as sd_gjk_distance_bounded. Always inlined: the result
 * (its simplex 0.4 KB) is then built in the caller's frame, not copied out
 * at every query (3 % of a composite bed's instructions). */
SD_HD static SD_HOT sd_gjk_result sd_gjk_distance_bodies(const sd_gjk_body *pA, const sd_gjk_body *pB,
                                                         sd_vec3 warm_dir, sd_real stop_beyond)
{
    sd_gjk_result r;
    const sd_convex *a = pA->c, *b = pB->c;
    const sd_real L = sd_gjk_length_scale(a, b);
    const sd_real abs_tol2 = sd_sq(SD_GJK_ABS_TOL * L);
    const int bound_on = stop_beyond >= SD_R(0.0);
    const sd_real stop2 = bound_on ? stop_beyond * stop_beyond : SD_R(0.0);

    sd_vec3 d = sd_gjk_start_dir(a, b, warm_dir);

    /* the simplex lives in four fixed slots y[]; act[0..na−1] are the slots
     * in use with weights lam[]; a new point takes a free slot, so neither
     * reducing nor rejecting a step copies any vertex */
    sd_gjk_vertex y[4];
    int act[4], na = 1;
    sd_real lam[4];
    r.status = SD_GJK_MAX_ITER;
    r.bounded = 0;
    r.iterations = 0;
    r.support_calls = 1;
    sd_gjk_support_body(pA, pB, d, &y[0]);
    act[0] = 0;
    lam[0] = SD_R(1.0);
    r.dir = d;
    sd_vec3 v = y[0].w;
    sd_real vv = sd_v3_norm2(v);
    sd_real lower = SD_R(0.0); /* the distance's lower bound when bounded */

    if (!sd_gjk_finite(v)) {
        r.status = SD_GJK_DEGENERATE;
    } else {
        /* 0: the first support point may already prove the distance large */
        sd_real dw = sd_v3_dot(d, v);
        if (bound_on && dw < SD_R(0.0) && dw * dw > stop2 * sd_v3_norm2(d)) {
            r.status = SD_GJK_SEPARATED;
            r.bounded = 1;
            lower = -dw / sd_v3_norm(d);
        }
        while (!r.bounded && r.iterations < SD_GJK_MAX_ITERATIONS) {
            r.iterations++;
            if (vv <= abs_tol2) { /* 3: the origin lies on the simplex */
                r.status = SD_GJK_TOUCHING;
                break;
            }
            d = sd_v3_neg(v);
            r.dir = d;
            /* a free slot for the new point */
            int used = 0;
            for (int m = 0; m < na; ++m)
                used |= 1 << act[m];
            int f = 0;
            while (used & (1 << f))
                ++f;
            sd_gjk_vertex *w = &y[f];
            sd_gjk_support_body(pA, pB, d, w);
            r.support_calls++;
            if (!sd_gjk_finite(w->w)) {
                r.status = SD_GJK_DEGENERATE;
                break;
            }
            sd_real vw = sd_v3_dot(v, w->w);
            /* 0: v·w/|v| bounds the distance from below */
            if (bound_on && vw > SD_R(0.0) && vw * vw > stop2 * vv) {
                r.status = SD_GJK_SEPARATED;
                r.bounded = 1;
                lower = vw / sd_sqrt(vv);
                break;
            }
            /* 1: a support point already in the simplex: K has nothing nearer */
            int dup = 0;
            for (int m = 0; m < na; ++m)
                if (sd_v3_norm2(sd_v3_sub(w->w, y[act[m]].w)) <= abs_tol2)
                    dup = 1;
            if (dup) {
                r.status = SD_GJK_SEPARATED;
                break;
            }
            /* 2: v·w is a lower bound of |v|·distance; close enough to |v|² */
            if (vv - vw <= SD_GJK_REL_GAP * vv) {
                r.status = SD_GJK_SEPARATED;
                break;
            }
            sd_vec3 p[4];
            int slot[4];
            for (int m = 0; m < na; ++m) {
                slot[m] = act[m];
                p[m] = y[act[m]].w;
            }
            slot[na] = f;
            p[na] = w->w;
            sd_gjk_sel sel;
            sd_vec3 vn;
            int inside = sd_gjk_sv_solve(p, na + 1, &sel, &vn);
            if (inside) { /* 5 */
                na = 4;
                for (int m = 0; m < 4; ++m) {
                    act[m] = slot[sel.idx[m]];
                    lam[m] = sel.lambda[m];
                }
                v = vn;
                vv = SD_R(0.0);
                r.status = SD_GJK_OVERLAP;
                break;
            }
            sd_real vvn = sd_v3_norm2(vn);
            if (!(vvn <= abs_tol2) && vvn >= vv * sd_sq(SD_R(1.0) - SD_GJK_NO_PROGRESS)) {
                /* 4: rounding stalls the descent; the previous simplex is the best */
                r.status = SD_GJK_SEPARATED;
                break;
            }
            na = sel.n;
            for (int m = 0; m < sel.n; ++m) {
                act[m] = slot[sel.idx[m]];
                lam[m] = sel.lambda[m];
            }
            v = vn;
            vv = vvn;
        }
        if (r.status == SD_GJK_MAX_ITER && vv <= abs_tol2)
            r.status = SD_GJK_TOUCHING; /* converged on the very last iteration */
    }

    r.simplex.n = na;
    for (int m = 0; m < na; ++m) {
        r.simplex.v[m] = y[act[m]];
        r.simplex.lambda[m] = lam[m];
    }
    if (r.status == SD_GJK_DEGENERATE) {
        r.distance = SD_R(0.0);
        r.pa = a->x;
        r.pb = b->x;
        r.dir = sd_v3(SD_R(1.0), SD_R(0.0), SD_R(0.0));
        return r;
    }
    sd_gjk_witnesses(&r.simplex, &r.pa, &r.pb);
    if (r.bounded) {
        r.distance = lower; /* the lower bound of the direction that separated */
    } else if (r.status == SD_GJK_SEPARATED || r.status == SD_GJK_MAX_ITER) {
        r.distance = sd_sqrt(vv);
        r.dir = sd_v3_neg(v);
    } else {
        r.distance = SD_R(0.0);
    }
    return r;
}

/* sd_gjk_distance_bodies on two posed convex bodies. */
SD_HD static SD_INLINE sd_gjk_result sd_gjk_distance_bounded(const sd_convex *a, const sd_convex *b, sd_vec3 warm_dir,
                                                             sd_real stop_beyond)
{
    const sd_gjk_body A = sd_gjk_body_of(a), B = sd_gjk_body_of(b);
    return sd_gjk_distance_bodies(&A, &B, warm_dir, stop_beyond);
}

/* GJK distance between the cores of a and b (no early stop). */
SD_HD static SD_INLINE sd_gjk_result sd_gjk_distance(const sd_convex *a, const sd_convex *b, sd_vec3 warm_dir)
{
    return sd_gjk_distance_bounded(a, b, warm_dir, SD_R(-1.0));
}

#endif
