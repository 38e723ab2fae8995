/* gjk.h — GJK distance between the convex cores of two posed bodies.
 * Single source (SD_HD): compiles as C17 and as CUDA C++; no allocation, no
 * printing, fixed-size simplex, double precision.
 *
 * What: the Gilbert–Johnson–Keerthi iteration on the Minkowski difference
 * K = A − B of the two CORES (shape.h: every shape is a core swept by a
 * sphere; the caller adds the radii, seed 004 §2.5 shrink / GJK / swell, see
 * geom/convex_contact.h). It finds the point v of K closest to the origin;
 * |v| is the core distance and v = pa − pb gives witness points on each core.
 * The closest point of each simplex is found as in Johnson's sub-algorithm,
 * by brute force over sub-simplices (the origin's projection on the simplex
 * if it falls inside, else the best face / edge): robust on the slivers that
 * curved cores produce near convergence.
 *
 * Invariant: the simplex holds 1–4 support points w_i = a_i − b_i of K with
 * the support points a_i (of A) and b_i (of B) that made them, and barycentric
 * weights lambda_i ≥ 0 summing to 1 with v = Σ λ_i w_i; |v| never grows
 * between accepted iterations. The result is never NaN: a non-finite support
 * point ends the loop with SD_GJK_DEGENERATE.
 *
 * Termination, in this order (DESIGN.md engineering note "GJK/EPA",
 * notes/algorithms.md §C recommendation; L = sum of the two bounding radii):
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

#include "core/vec.h"
#include "shape/shape.h"

/* The support function of a posed core. A test may substitute a reference
 * support (same signature) by defining SD_GJK_SUPPORT_CORE before including
 * this header; the engine uses shape/support.h. */
#ifndef SD_GJK_SUPPORT_CORE
#include "shape/support.h"
#define SD_GJK_SUPPORT_CORE sd_convex_support_core
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

/* Keep only vertices i (and j, k) of the simplex with the given weights. */
SD_HD static SD_INLINE void sd_gjk_keep1(sd_gjk_simplex *s, int i)
{
    s->v[0] = s->v[i];
    s->lambda[0] = SD_R(1.0);
    s->n = 1;
}
SD_HD static SD_INLINE void sd_gjk_keep2(sd_gjk_simplex *s, int i, int j, sd_real li, sd_real lj)
{
    sd_gjk_vertex vi = s->v[i], vj = s->v[j];
    s->v[0] = vi;
    s->v[1] = vj;
    s->lambda[0] = li;
    s->lambda[1] = lj;
    s->n = 2;
}

/* Closest point of segment (s->v[i], s->v[j]) to the origin; reduces the simplex. */
SD_HD static SD_INLINE sd_vec3 sd_gjk_segment(sd_gjk_simplex *s, int i, int j)
{
    sd_vec3 a = s->v[i].w, b = s->v[j].w;
    sd_vec3 ab = sd_v3_sub(b, a);
    sd_real ab2 = sd_v3_norm2(ab);
    sd_real t = ab2 > SD_R(0.0) ? -sd_v3_dot(a, ab) / ab2 : SD_R(1.0);
    if (t <= SD_R(0.0)) {
        sd_gjk_keep1(s, i);
        return a;
    }
    if (t >= SD_R(1.0)) {
        sd_gjk_keep1(s, j);
        return b;
    }
    sd_gjk_keep2(s, i, j, SD_R(1.0) - t, t);
    /* a + t ab, minus its component along ab, so v ⟂ ab to rounding: the
     * relative-gap test then sees the exact distance */
    sd_vec3 v = sd_v3_madd(a, t, ab);
    return sd_v3_madd(v, -sd_v3_dot(v, ab) / ab2, ab);
}

/* Closest point of triangle (v[i], v[j], v[k]) to the origin; reduces the
 * simplex. Either the origin projects into the triangle (all three
 * sub-triangle areas about the projection are ≥ 0) and the projection is the
 * answer, or the answer lies on an edge, and the best of the three edges is
 * taken. This costs a little more than Voronoi-region tests (Ericson §5.1.5)
 * but cannot pick a wrong region on the slivers that curved shapes produce
 * near convergence, where the region products cancel and GJK would stall. */
SD_HD static SD_INLINE sd_vec3 sd_gjk_triangle(sd_gjk_simplex *s, int i, int j, int k)
{
    sd_vec3 a = s->v[i].w, b = s->v[j].w, c = s->v[k].w;
    sd_vec3 nrm = sd_v3_cross(sd_v3_sub(b, a), sd_v3_sub(c, a));
    sd_real n2 = sd_v3_norm2(nrm);
    if (n2 > SD_R(0.0)) {
        /* the projection of the origin on the plane, from the normal: exactly
         * perpendicular to the face, so |v| is the true distance to the plane */
        sd_vec3 p = sd_v3_scale(nrm, sd_v3_dot(nrm, a) / n2);
        sd_real l0 = sd_v3_dot(nrm, sd_v3_cross(sd_v3_sub(b, p), sd_v3_sub(c, p)));
        sd_real l1 = sd_v3_dot(nrm, sd_v3_cross(sd_v3_sub(c, p), sd_v3_sub(a, p)));
        sd_real l2 = sd_v3_dot(nrm, sd_v3_cross(sd_v3_sub(a, p), sd_v3_sub(b, p)));
        sd_real ls = l0 + l1 + l2;
        if (l0 >= SD_R(0.0) && l1 >= SD_R(0.0) && l2 >= SD_R(0.0) && ls > SD_R(0.0)) {
            sd_gjk_vertex vi = s->v[i], vj = s->v[j], vk = s->v[k];
            s->v[0] = vi;
            s->v[1] = vj;
            s->v[2] = vk;
            s->lambda[0] = l0 / ls;
            s->lambda[1] = l1 / ls;
            s->lambda[2] = l2 / ls;
            s->n = 3;
            return p;
        }
    }
    sd_gjk_simplex s1 = *s, s2 = *s, s3 = *s;
    sd_vec3 p1 = sd_gjk_segment(&s1, i, j), p2 = sd_gjk_segment(&s2, i, k), p3 = sd_gjk_segment(&s3, j, k);
    sd_real q1 = sd_v3_norm2(p1), q2 = sd_v3_norm2(p2), q3 = sd_v3_norm2(p3);
    if (q1 <= q2 && q1 <= q3) {
        *s = s1;
        return p1;
    }
    if (q2 <= q3) {
        *s = s2;
        return p2;
    }
    *s = s3;
    return p3;
}

/* Closest point of the tetrahedron v[0..3] to the origin; sets *inside when
 * the origin is enclosed (then v = 0 and all four weights are kept). */
SD_HD static SD_INLINE sd_vec3 sd_gjk_tetrahedron(sd_gjk_simplex *s, int *inside)
{
    /* face f is opposite vertex f; the origin is outside face f when it and
     * vertex f lie strictly on opposite sides of the face's plane */
    const int fi[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    sd_vec3 p[4];
    for (int m = 0; m < 4; ++m)
        p[m] = s->v[m].w;
    sd_real vol = sd_v3_dot(sd_v3_sub(p[1], p[0]), sd_v3_cross(sd_v3_sub(p[2], p[0]), sd_v3_sub(p[3], p[0])));
    int outside_any = 0;
    *inside = 0;
    for (int f = 0; f < 4; ++f) {
        sd_vec3 a = p[fi[f][0]], b = p[fi[f][1]], c = p[fi[f][2]];
        sd_vec3 nrm = sd_v3_cross(sd_v3_sub(b, a), sd_v3_sub(c, a));
        sd_real so = -sd_v3_dot(nrm, a);                  /* origin side */
        sd_real sv = sd_v3_dot(nrm, sd_v3_sub(p[f], a)); /* vertex side */
        /* a flat tetrahedron (sv = 0) encloses nothing: treat every face as a candidate */
        if (sv == SD_R(0.0) || so * sv < SD_R(0.0))
            outside_any = 1;
    }
    if (!outside_any && vol != SD_R(0.0)) {
        /* barycentric weights are the signed sub-volumes of the origin's tetrahedra */
        for (int f = 0; f < 4; ++f) {
            sd_vec3 a = p[fi[f][0]], b = p[fi[f][1]], c = p[fi[f][2]];
            sd_real sub = sd_v3_dot(sd_v3_cross(sd_v3_sub(b, a), sd_v3_sub(c, a)), sd_v3_neg(a));
            /* vertex f's weight: volume (origin, face f) over volume (vertex f, face f) */
            sd_real full = sd_v3_dot(sd_v3_cross(sd_v3_sub(b, a), sd_v3_sub(c, a)), sd_v3_sub(p[f], a));
            s->lambda[f] = sub / full;
        }
        s->n = 4;
        *inside = 1;
        return sd_v3_zero();
    }
    sd_gjk_simplex best = *s;
    sd_vec3 bestv = sd_v3_zero();
    sd_real bestd = SD_R(-1.0);
    /* the origin is outside: the nearest point is on the surface, so the best
     * of all four faces is right even where rounding blurs the side tests */
    for (int f = 0; f < 4; ++f) {
        sd_gjk_simplex t = *s;
        sd_vec3 v = sd_gjk_triangle(&t, fi[f][0], fi[f][1], fi[f][2]);
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

/* Closest point of the simplex to the origin; reduces it to the smallest
 * subset that holds that point. Returns 1 if a tetrahedron encloses the origin. */
SD_HD static SD_INLINE int sd_gjk_solve(sd_gjk_simplex *s, sd_vec3 *v)
{
    int inside = 0;
    switch (s->n) {
    case 1:
        s->lambda[0] = SD_R(1.0);
        *v = s->v[0].w;
        break;
    case 2:
        *v = sd_gjk_segment(s, 0, 1);
        break;
    case 3:
        *v = sd_gjk_triangle(s, 0, 1, 2);
        break;
    default:
        *v = sd_gjk_tetrahedron(s, &inside);
        break;
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

/* GJK distance between the cores of a and b. warm_dir: a search direction
 * to start from (the previous result's dir for this pair), or zero for the
 * centre-to-centre direction. */
SD_HD static SD_INLINE sd_gjk_result sd_gjk_distance(const sd_convex *a, const sd_convex *b, sd_vec3 warm_dir)
{
    sd_gjk_result r;
    const sd_real L = sd_gjk_length_scale(a, b);
    const sd_real abs_tol2 = sd_sq(SD_GJK_ABS_TOL * L);

    sd_vec3 d = warm_dir;
    if (!(sd_v3_norm2(d) > SD_R(0.0)) || !sd_gjk_finite(d))
        d = sd_v3_sub(b->x, a->x); /* K's near side faces the origin along xb − xa */
    if (!(sd_v3_norm2(d) > SD_R(0.0)))
        d = sd_v3(SD_R(1.0), SD_R(0.0), SD_R(0.0));

    r.status = SD_GJK_MAX_ITER;
    r.iterations = 0;
    r.support_calls = 1;
    r.simplex.n = 1;
    r.simplex.v[0] = sd_gjk_support(a, b, d);
    r.simplex.lambda[0] = SD_R(1.0);
    r.dir = d;
    sd_vec3 v = r.simplex.v[0].w;
    sd_real vv = sd_v3_norm2(v);

    if (!sd_gjk_finite(v)) {
        r.status = SD_GJK_DEGENERATE;
    } else {
        while (r.iterations < SD_GJK_MAX_ITERATIONS) {
            r.iterations++;
            if (vv <= abs_tol2) { /* 3: the origin lies on the simplex */
                r.status = SD_GJK_TOUCHING;
                break;
            }
            d = sd_v3_neg(v);
            r.dir = d;
            sd_gjk_vertex w = sd_gjk_support(a, b, d);
            r.support_calls++;
            if (!sd_gjk_finite(w.w)) {
                r.status = SD_GJK_DEGENERATE;
                break;
            }
            /* 1: a support point already in the simplex: K has nothing nearer */
            int dup = 0;
            for (int i = 0; i < r.simplex.n; ++i)
                if (sd_v3_norm2(sd_v3_sub(w.w, r.simplex.v[i].w)) <= abs_tol2)
                    dup = 1;
            if (dup) {
                r.status = SD_GJK_SEPARATED;
                break;
            }
            /* 2: v·w is a lower bound of |v|·distance; close enough to |v|² */
            if (vv - sd_v3_dot(v, w.w) <= SD_GJK_REL_GAP * vv) {
                r.status = SD_GJK_SEPARATED;
                break;
            }
            sd_gjk_simplex prev = r.simplex;
            r.simplex.v[r.simplex.n++] = w;
            sd_vec3 vn;
            int inside = sd_gjk_solve(&r.simplex, &vn);
            if (inside) { /* 5 */
                v = vn;
                vv = SD_R(0.0);
                r.status = SD_GJK_OVERLAP;
                break;
            }
            sd_real vvn = sd_v3_norm2(vn);
            if (!(vvn <= abs_tol2) && vvn >= vv * sd_sq(SD_R(1.0) - SD_GJK_NO_PROGRESS)) {
                /* 4: rounding stalls the descent; the previous simplex is the best */
                r.simplex = prev;
                r.status = SD_GJK_SEPARATED;
                break;
            }
            v = vn;
            vv = vvn;
        }
        if (r.status == SD_GJK_MAX_ITER && vv <= abs_tol2)
            r.status = SD_GJK_TOUCHING; /* converged on the very last iteration */
    }

    if (r.status == SD_GJK_DEGENERATE) {
        r.distance = SD_R(0.0);
        r.pa = a->x;
        r.pb = b->x;
        r.dir = sd_v3(SD_R(1.0), SD_R(0.0), SD_R(0.0));
        return r;
    }
    sd_gjk_witnesses(&r.simplex, &r.pa, &r.pb);
    if (r.status == SD_GJK_SEPARATED || r.status == SD_GJK_MAX_ITER) {
        r.distance = sd_sqrt(vv);
        r.dir = sd_v3_neg(v);
    } else {
        r.distance = SD_R(0.0);
    }
    return r;
}

#endif
