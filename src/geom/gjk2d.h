/* gjk2d.h — 2D GJK distance between the convex cores of two posed planar
 * bodies (shape/shape2d.h). Single source (SD_HD): C17 and CUDA C++, no
 * allocation, no printing, a fixed 3-point simplex, double precision.
 *
 * What: the Gilbert–Johnson–Keerthi iteration (seed 002 §2.2 uses the
 * classical GJK + EPA) on the Minkowski difference K = A − B of the two
 * CORES. It finds the point v of K closest to the origin; |v| is the core
 * distance and v = pa − pb gives a witness point on each core. The swept
 * radii are added by the caller (geom/epa2d.h, sd_contact2d_convex: shrink /
 * GJK / swell as in 3D, seed 004 §2.5). The closest point of a segment is its
 * clamped projection; of a triangle: the origin itself when its three
 * barycentric coordinates (signed areas) are ≥ 0, else the nearest of the
 * three edges (brute force over three edges: no fragile Voronoi-region
 * branching on the slivers that curved outlines produce near convergence).
 *
 * Invariant: the simplex holds 1–3 points w_i = a_i − b_i of K with the
 * support points that made them, and weights lambda_i ≥ 0 summing to 1 with
 * v = Σ λ_i w_i; |v| never grows between accepted iterations; the result is
 * never NaN (a non-finite support point ends with SD_GJK2D_DEGENERATE).
 *
 * Termination, in this order (DESIGN.md note "GJK/EPA", notes/algorithms.md
 * §C; L = the sum of the two bounding radii, so every tolerance is relative):
 *   0. (only when stop_beyond ≥ 0) a support point w in −v proves the core
 *      distance ≥ v·w/|v| > stop_beyond → SEPARATED, bounded = 1;
 *   1. duplicate support |w − w_i| ≤ 1e-12 L → SEPARATED;
 *   2. relative gap |v|² − v·w ≤ 1e-10 |v|² → SEPARATED;
 *   3. |v| ≤ 1e-12 L → TOUCHING (origin on the simplex: EPA decides);
 *   4. no progress |v_k| ≥ |v_{k−1}|(1 − 1e-14) → SEPARATED with the best v;
 *   5. a triangle enclosing the origin → OVERLAP;
 *   6. 64 iterations → MAX_ITER (the best v so far is kept).
 * Support calls count queries of K (one support of A and one of B each), the
 * unit of seed 002 Table 1 (2.9–6 calls per pair).
 */
#ifndef SD_GEOM_GJK2D_H
#define SD_GEOM_GJK2D_H

#include "shape/shape2d.h"

typedef enum {
    SD_GJK2D_SEPARATED,  /* cores apart: distance > 0 with witnesses */
    SD_GJK2D_TOUCHING,   /* origin on the final simplex (|v| ≤ 1e-12 L) */
    SD_GJK2D_OVERLAP,    /* final triangle encloses the origin */
    SD_GJK2D_DEGENERATE, /* non-finite support point (bad pose or shape) */
    SD_GJK2D_MAX_ITER    /* iteration cap; distance is the best upper bound */
} sd_gjk2d_status;

#define SD_GJK2D_MAX_ITERATIONS 64
#define SD_GJK2D_REL_GAP        SD_R(1e-10)
#define SD_GJK2D_ABS_TOL        SD_R(1e-12)
#define SD_GJK2D_NO_PROGRESS    SD_R(1e-14)

/* A posed core with its rotation evaluated once per query. */
typedef struct sd_gjk2d_body {
    const sd_shape2d *shape;
    const sd_real *pool;
    sd_vec2 x;
    sd_real c, s; /* cos θ, sin θ */
} sd_gjk2d_body;

typedef struct sd_gjk2d_vertex {
    sd_vec2 w; /* a − b */
    sd_vec2 a; /* support point of core A, world, m */
    sd_vec2 b; /* support point of core B, world, m */
} sd_gjk2d_vertex;

typedef struct sd_gjk2d_simplex {
    sd_gjk2d_vertex v[3];
    sd_real lambda[3];
    int n; /* 1..3 */
} sd_gjk2d_simplex;

typedef struct sd_gjk2d_result {
    int status;       /* sd_gjk2d_status */
    sd_real distance; /* m, core distance (0 when touching or overlapping; a lower bound when bounded) */
    sd_vec2 pa, pb;   /* witness points on the cores, world */
    sd_vec2 dir;      /* last search direction −v (from A towards B when separated) */
    int iterations, support_calls;
    int bounded; /* 1: stopped early, distance proved > stop_beyond */
    sd_gjk2d_simplex simplex;
} sd_gjk2d_result;

SD_HD static SD_INLINE sd_gjk2d_body sd_gjk2d_pose(const sd_convex2d *c)
{
    sd_gjk2d_body b;
    b.shape = c->shape;
    b.pool = c->pool;
    b.x = c->x;
    b.c = sd_cos(c->theta);
    b.s = sd_sin(c->theta);
    return b;
}

SD_HD static SD_INLINE sd_vec2 sd_gjk2d_body_support(const sd_gjk2d_body *b, sd_vec2 d)
{
    const sd_vec2 p = sd_shape2d_support_core(b->shape, b->pool, sd_v2_rotcs(d, b->c, -b->s));
    return sd_v2_add(b->x, sd_v2_rotcs(p, b->c, b->s));
}

/* The support point of K in direction d: s_A(d) − s_B(−d). */
SD_HD static SD_INLINE sd_gjk2d_vertex sd_gjk2d_support(const sd_gjk2d_body *a, const sd_gjk2d_body *b, sd_vec2 d)
{
    sd_gjk2d_vertex v;
    v.a = sd_gjk2d_body_support(a, d);
    v.b = sd_gjk2d_body_support(b, sd_v2_neg(d));
    v.w = sd_v2_sub(v.a, v.b);
    return v;
}

SD_HD static SD_INLINE int sd_gjk2d_finite(sd_vec2 p)
{
    const sd_real big = SD_R(1e300);
    return sd_fabs(p.x) <= big && sd_fabs(p.y) <= big;
}

SD_HD static SD_INLINE sd_real sd_gjk2d_length_scale(const sd_convex2d *a, const sd_convex2d *b)
{
    const sd_real L = a->shape->bound + b->shape->bound;
    return L > SD_R(0.0) ? L : SD_R(1.0);
}

/* Closest point of segment (p, q) to the origin: weight t of q in [0, 1]. */
SD_HD static SD_INLINE sd_real sd_gjk2d_segment_t(sd_vec2 p, sd_vec2 q)
{
    const sd_vec2 e = sd_v2_sub(q, p);
    const sd_real e2 = sd_v2_norm2(e);
    if (!(e2 > SD_R(0.0)))
        return SD_R(0.0);
    return sd_clamp(-sd_v2_dot(p, e) / e2, SD_R(0.0), SD_R(1.0));
}

/* Reduces s to the smallest sub-simplex holding its point closest to the
 * origin, sets the weights, returns that point. *inside = 1 when a triangle
 * encloses the origin (then the simplex keeps all three points). */
SD_HD static SD_INLINE sd_vec2 sd_gjk2d_closest(sd_gjk2d_simplex *s, int *inside)
{
    *inside = 0;
    if (s->n == 1) {
        s->lambda[0] = SD_R(1.0);
        return s->v[0].w;
    }
    if (s->n == 2) {
        const sd_real t = sd_gjk2d_segment_t(s->v[0].w, s->v[1].w);
        if (t <= SD_R(0.0)) {
            s->n = 1;
            s->lambda[0] = SD_R(1.0);
            return s->v[0].w;
        }
        if (t >= SD_R(1.0)) {
            s->v[0] = s->v[1];
            s->n = 1;
            s->lambda[0] = SD_R(1.0);
            return s->v[0].w;
        }
        s->lambda[0] = SD_R(1.0) - t;
        s->lambda[1] = t;
        return sd_v2_madd(s->v[0].w, t, sd_v2_sub(s->v[1].w, s->v[0].w));
    }
    /* triangle: barycentric coordinates from the signed areas of the three
     * triangles the origin makes with the edges */
    const sd_vec2 A = s->v[0].w, B = s->v[1].w, C = s->v[2].w;
    const sd_real area = sd_v2_cross(sd_v2_sub(B, A), sd_v2_sub(C, A));
    const sd_real la = sd_v2_cross(B, C), lb = sd_v2_cross(C, A), lc = sd_v2_cross(A, B);
    if (area != SD_R(0.0)) {
        const sd_real sa = la / area, sb = lb / area, sc = lc / area;
        if (sa >= SD_R(0.0) && sb >= SD_R(0.0) && sc >= SD_R(0.0)) {
            s->lambda[0] = sa;
            s->lambda[1] = sb;
            s->lambda[2] = sc;
            *inside = 1;
            return sd_v2_zero();
        }
    }
    /* outside (or a flat triangle): the nearest of the three edges */
    int bi = 0;
    sd_real bt = SD_R(0.0), bd = SD_R(1e300);
    for (int e = 0; e < 3; ++e) {
        const sd_vec2 p = s->v[e].w, q = s->v[(e + 1) % 3].w;
        const sd_real t = sd_gjk2d_segment_t(p, q);
        const sd_real d2 = sd_v2_norm2(sd_v2_madd(p, t, sd_v2_sub(q, p)));
        if (d2 < bd) {
            bd = d2;
            bi = e;
            bt = t;
        }
    }
    const sd_gjk2d_vertex p = s->v[bi], q = s->v[(bi + 1) % 3];
    if (bt <= SD_R(0.0)) {
        s->v[0] = p;
        s->n = 1;
        s->lambda[0] = SD_R(1.0);
    } else if (bt >= SD_R(1.0)) {
        s->v[0] = q;
        s->n = 1;
        s->lambda[0] = SD_R(1.0);
    } else {
        s->v[0] = p;
        s->v[1] = q;
        s->n = 2;
        s->lambda[0] = SD_R(1.0) - bt;
        s->lambda[1] = bt;
    }
    return s->n == 1 ? s->v[0].w : sd_v2_madd(p.w, bt, sd_v2_sub(q.w, p.w));
}

SD_HD static SD_INLINE void sd_gjk2d_witness(sd_gjk2d_result *r)
{
    const sd_gjk2d_simplex *s = &r->simplex;
    r->pa = sd_v2_zero();
    r->pb = sd_v2_zero();
    for (int i = 0; i < s->n; ++i) {
        r->pa = sd_v2_madd(r->pa, s->lambda[i], s->v[i].a);
        r->pb = sd_v2_madd(r->pb, s->lambda[i], s->v[i].b);
    }
}

/* Core distance of a and b. warm: start direction (from a towards b; zero
 * for none). stop_beyond ≥ 0: stop as soon as the distance is proved larger
 * (rule 0); < 0: always measure. */
SD_HD static SD_INLINE sd_gjk2d_result sd_gjk2d_distance_bounded(const sd_convex2d *ca, const sd_convex2d *cb,
                                                                 sd_vec2 warm, sd_real stop_beyond)
{
    sd_gjk2d_result r;
    const sd_gjk2d_body A = sd_gjk2d_pose(ca), B = sd_gjk2d_pose(cb);
    const sd_real L = sd_gjk2d_length_scale(ca, cb);
    const sd_real dup2 = sd_sq(SD_R(1e-12) * L);
    /* every field set, the unused simplex slots too: the result is copied
     * whole, and compilers rightly warn about copying indeterminate values */
    for (int i = 0; i < 3; ++i) {
        r.simplex.v[i].w = r.simplex.v[i].a = r.simplex.v[i].b = sd_v2_zero();
        r.simplex.lambda[i] = SD_R(0.0);
    }
    r.pa = r.pb = sd_v2_zero();
    r.bounded = 0;
    r.iterations = 0;
    r.distance = SD_R(0.0);
    sd_vec2 d = warm;
    if (!(sd_v2_norm2(d) > SD_R(0.0)))
        d = sd_v2_sub(cb->x, ca->x);
    if (!(sd_v2_norm2(d) > SD_R(0.0)))
        d = sd_v2(SD_R(1.0), SD_R(0.0));
    r.simplex.n = 1;
    r.simplex.v[0] = sd_gjk2d_support(&A, &B, d);
    r.simplex.lambda[0] = SD_R(1.0);
    r.support_calls = 1;
    r.dir = d;
    if (!sd_gjk2d_finite(r.simplex.v[0].w)) {
        r.status = SD_GJK2D_DEGENERATE;
        r.pa = r.pb = sd_v2_zero();
        return r;
    }
    sd_vec2 v = r.simplex.v[0].w;
    /* rule 0 on the first support: every x of K has x·d ≤ w·d */
    if (stop_beyond >= SD_R(0.0)) {
        const sd_real dn = sd_v2_norm(d);
        const sd_real lower = -sd_v2_dot(v, d) / dn;
        if (lower > stop_beyond) {
            r.status = SD_GJK2D_SEPARATED;
            r.bounded = 1;
            r.distance = lower;
            sd_gjk2d_witness(&r);
            return r;
        }
    }
    sd_real vn = sd_v2_norm(v);
    r.status = SD_GJK2D_MAX_ITER;
    while (r.iterations < SD_GJK2D_MAX_ITERATIONS) {
        if (vn <= SD_GJK2D_ABS_TOL * L) { /* rule 3 */
            r.status = SD_GJK2D_TOUCHING;
            break;
        }
        r.iterations++;
        d = sd_v2_neg(v);
        r.dir = d;
        const sd_gjk2d_vertex w = sd_gjk2d_support(&A, &B, d);
        r.support_calls++;
        if (!sd_gjk2d_finite(w.w)) {
            r.status = SD_GJK2D_DEGENERATE;
            break;
        }
        const sd_real vw = sd_v2_dot(v, w.w);
        if (stop_beyond >= SD_R(0.0) && vw > stop_beyond * vn) { /* rule 0 */
            r.status = SD_GJK2D_SEPARATED;
            r.bounded = 1;
            r.distance = vw / vn;
            sd_gjk2d_witness(&r);
            return r;
        }
        int dup = 0;
        for (int i = 0; i < r.simplex.n; ++i)
            dup |= sd_v2_norm2(sd_v2_sub(w.w, r.simplex.v[i].w)) <= dup2;
        if (dup || vn * vn - vw <= SD_GJK2D_REL_GAP * vn * vn) { /* rules 1, 2 */
            r.status = SD_GJK2D_SEPARATED;
            break;
        }
        const sd_gjk2d_simplex keep = r.simplex;
        r.simplex.v[r.simplex.n++] = w;
        int inside;
        const sd_vec2 nv = sd_gjk2d_closest(&r.simplex, &inside);
        if (inside) { /* rule 5 */
            r.status = SD_GJK2D_OVERLAP;
            v = nv;
            vn = SD_R(0.0);
            break;
        }
        const sd_real nn = sd_v2_norm(nv);
        if (nn >= vn * (SD_R(1.0) - SD_GJK2D_NO_PROGRESS)) { /* rule 4 */
            r.simplex = keep;
            r.status = SD_GJK2D_SEPARATED;
            break;
        }
        v = nv;
        vn = nn;
    }
    if ((r.status == SD_GJK2D_SEPARATED || r.status == SD_GJK2D_MAX_ITER) && vn > SD_R(0.0))
        r.dir = sd_v2_neg(v); /* the final v (rule 6 may have moved it after the last query) */
    if (r.status == SD_GJK2D_TOUCHING || r.status == SD_GJK2D_OVERLAP)
        r.distance = SD_R(0.0);
    else if (r.status != SD_GJK2D_DEGENERATE)
        r.distance = vn;
    sd_gjk2d_witness(&r);
    if (r.status == SD_GJK2D_DEGENERATE)
        r.distance = SD_R(0.0);
    return r;
}

SD_HD static SD_INLINE sd_gjk2d_result sd_gjk2d_distance(const sd_convex2d *a, const sd_convex2d *b, sd_vec2 warm)
{
    return sd_gjk2d_distance_bounded(a, b, warm, SD_R(-1.0));
}

#endif

/* the contact (sd_contact2d_convex) lives in epa2d.h; either header gives both */
#include "geom/epa2d.h"
