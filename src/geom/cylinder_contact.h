/* cylinder_contact.h — penetration depth, normal and witness points of two
 * overlapping sharp cylinder cores, or of a sharp box core and a sharp
 * cylinder core, without EPA (issue 11 §5: EPA needs ~21 iterations on the
 * curved surfaces of cylinders and made sharp cylinders 5–6 times as costly
 * per step as sharp cubes).
 * Single source (SD_HD): C17 and CUDA C++, no allocation, no printing,
 * fixed workspaces.
 *
 * What: the depth is D = min over unit u of f(u) = h_K(u), K = A − B (the
 * distance from the origin, inside K, to K's boundary), and for these
 * bodies h_K has a closed form (d = c_A − c_B; a cylinder of radius R,
 * half length h and unit axis z; a box of half extents a_i on axes e_i):
 *     f(u) = u·d + Σ_bodies [ h |u·z| + R |u × z| ]  (cylinders)
 *                          [ Σ_i a_i |u·e_i| ]        (boxes).
 * f is smooth except on a finite set of great circles (u·z = 0: a
 * cylinder's side; u·e_i = 0: a box edge) and points (u = ±z: a cap; two
 * such circles crossing), so the sphere of directions splits into strata
 * (points, open arcs, open regions) on each of which f is smooth, and the
 * global minimiser u* is a critical point of f restricted to its stratum.
 * The candidates, one family per feature pair:
 *   points   u = ±z_A, ±z_B (cap on anything), ±(z_A × z_B) (side on side),
 *            ±e_i (box face on anything), ±(e_i × z) (box edge on side);
 *   arcs     a side's great circle (side of A on the rim of B; a box vertex
 *            on a side, where f is a sinusoid: closed form), a box edge's
 *            great circle (edge on rim): f = P cos α + Q sin α
 *            + R sqrt(cos²α + γ² sin²α) on each arc between crossings,
 *            whose local minima are found by sampling and a bracketed
 *            Newton iteration on f′;
 *   regions  rim on rim: at u* the closest boundary point p of K is
 *            p_A(θ) − p_B(φ) with both on the rims, and it is a local
 *            minimum of |p| over (θ, φ); for fixed θ that is the nearest
 *            point of B's rim circle (closed form), so θ* is a local
 *            minimum of G(θ) = dist(p_A(θ), rim B), found the same way;
 *            u* is the common normal of the two rim tangents.
 *            Vertex on rim is no candidate: the boundary point nearest an
 *            interior point has a single normal, and a vertex-rim point of
 *            K has an arc of them.
 * Every candidate u gives f(u) ≥ D, whatever its quality, and u* is among
 * them, so the least value is D (the global minimum): a missed or wrong
 * critical point can only be a candidate that is not the least, never a
 * wrong answer — provided the 1D searches bracket the minimum of u*'s
 * stratum. They sample every π/16 on arcs and every π/12 on rims (arcs
 * are cut at their points nearest the other axis, where f has a V of
 * width ~γ when the circle passes within γ of it, with 9 more samples
 * there when γ < 0.2 rad), prune the
 * intervals that a Lipschitz bound keeps above the best value so far, cut
 * every other interval in 4 and bracket wherever the derivative turns
 * from − to +. That density is what the test needed: tests/unit/
 * cylinder_contact.c checks the result against EPA's rigorous bracket on
 * 18,000 pairs (coarser sampling, or no cutting in 4, fails it), so the
 * bracketing is supported by that test, not by a proof.
 *
 * Witness points: x in A's supporting face for u* and x − D u* in B's
 * (face = point, segment, disc or rectangle, told apart at 1e-9 rad): a
 * point face gives x; two segments, their crossing (or the middle of their
 * overlap); a segment and a disc or rectangle, the middle of the part of
 * the segment inside it; two discs, the middle of their common chord on
 * the centre line; a disc and a rectangle, alternating projections from
 * the midpoint of the face centres (a point of their intersection).
 *
 * Output convention (that of sd_epa_result): normal n = −u* points from b
 * into a (moving a by depth·n separates them), pa − pb = −depth·n.
 * Status SD_CYLC_FALLBACK (a kind pair it does not handle, or no finite
 * result) asks the caller to run EPA instead.
 */
#ifndef SD_GEOM_CYLINDER_CONTACT_H
#define SD_GEOM_CYLINDER_CONTACT_H

#include "shape/support.h"

typedef enum { SD_CYLC_OK, SD_CYLC_FALLBACK } sd_cylc_status;

/* X(enum, name): the feature pair that gave the least candidate */
#define SD_CYLC_FEATURES(X)                                                                                            \
    X(SD_CYLC_CAP_A, "cap of a on b")                                                                                  \
    X(SD_CYLC_CAP_B, "cap of b on a")                                                                                  \
    X(SD_CYLC_SIDE_SIDE, "side on side (or box edge on side)")                                                         \
    X(SD_CYLC_SIDE_A, "side of a on b (rim or box vertex)")                                                            \
    X(SD_CYLC_SIDE_B, "side of b on a (rim or box vertex)")                                                            \
    X(SD_CYLC_RIM_RIM, "rim on rim")                                                                                   \
    X(SD_CYLC_BOX_FACE, "box face on cylinder")                                                                        \
    X(SD_CYLC_EDGE_RIM, "box edge on rim")

typedef enum {
#define SD_X_ENUM(e, name) e,
    SD_CYLC_FEATURES(SD_X_ENUM)
#undef SD_X_ENUM
        SD_CYLC_FEATURE_COUNT
} sd_cylc_feature;

typedef struct sd_cylc_result {
    int status;     /* sd_cylc_status */
    int feature;    /* sd_cylc_feature of the least candidate */
    sd_real depth;  /* m, penetration depth of the cores (>= 0) */
    sd_vec3 normal; /* unit, from b into a */
    sd_vec3 pa, pb; /* witness points, pa − pb = −depth·normal */
    int candidates; /* f evaluations, for the benchmarks */
} sd_cylc_result;

/* One body in the world: a cylinder (R, h, axis z) or a box (a, axes e). */
typedef struct sd_cylc_body {
    int box;      /* 1: box, 0: cylinder */
    sd_vec3 c;    /* m, centre of the core */
    sd_vec3 e[3]; /* unit axes (cylinder: e[2] is the axis) */
    sd_real R, h; /* m, cylinder radius and half length */
    sd_vec3 a;    /* m, box half extents */
} sd_cylc_body;

/* The symmetric part of a body's support: h(u) − u·c. */
SD_HD static SD_INLINE sd_real sd_cylc_hsym(const sd_cylc_body *b, sd_vec3 u)
{
    if (b->box)
        return b->a.x * sd_fabs(sd_v3_dot(u, b->e[0])) + b->a.y * sd_fabs(sd_v3_dot(u, b->e[1])) +
               b->a.z * sd_fabs(sd_v3_dot(u, b->e[2]));
    /* |u × z| rather than sqrt(1 − (u·z)²): exact near the axis */
    return b->h * sd_fabs(sd_v3_dot(u, b->e[2])) + b->R * sd_v3_norm(sd_v3_cross(u, b->e[2]));
}

/* Search state: the pair, and the least candidate so far. */
typedef struct sd_cylc_search {
    const sd_cylc_body *A, *B;
    sd_vec3 d; /* c_A − c_B */
    sd_real best;
    sd_vec3 u;
    int feature, evals;
} sd_cylc_search;

/* f(u) = h_K(u) for a unit u; keeps the least. */
SD_HD static SD_INLINE sd_real sd_cylc_try(sd_cylc_search *S, sd_vec3 u, int feature)
{
    sd_real f = sd_v3_dot(u, S->d) + sd_cylc_hsym(S->A, u) + sd_cylc_hsym(S->B, u);
    S->evals++;
    if (f < S->best) {
        S->best = f;
        S->u = u;
        S->feature = feature;
    }
    return f;
}

/* A unit vector normal to unit z (deterministic). */
SD_HD static SD_INLINE sd_vec3 sd_cylc_perp(sd_vec3 z)
{
    sd_vec3 t =
        sd_fabs(z.x) < SD_R(0.6) ? sd_v3(SD_R(1.0), SD_R(0.0), SD_R(0.0)) : sd_v3(SD_R(0.0), SD_R(1.0), SD_R(0.0));
    return sd_v3_normalize(sd_v3_cross(z, t));
}

/* x × y for unit x, y, as x × (y ∓ x): the same vector, but accurate to
 * its own size when the two are nearly parallel or antiparallel (then
 * y ∓ x is small and exact, and x × y would carry x's rounding). */
SD_HD static SD_INLINE sd_vec3 sd_cylc_cross(sd_vec3 x, sd_vec3 y)
{
    return sd_v3_cross(x, sd_v3_madd(y, sd_v3_dot(x, y) >= SD_R(0.0) ? SD_R(-1.0) : SD_R(1.0), x));
}

/* (c, s) rotated by the angle x: cos and sin by their Taylor series to
 * degree 9/10 for |x| ≤ 0.3 (error below 1e-13, and only a
 * reparametrisation: the result is renormalised and critical points of
 * f along the circle do not move), the library otherwise. */
SD_HD static SD_INLINE void sd_cylc_rot(sd_real c, sd_real s, sd_real x, sd_real *co, sd_real *so)
{
    sd_real cx, sx;
    if (sd_fabs(x) <= SD_R(0.3)) {
        sd_real x2 = x * x;
        cx = SD_R(1.0) -
             x2 * (SD_R(0.5) - x2 * (SD_R(1.0) / 24 -
                                     x2 * (SD_R(1.0) / 720 - x2 * (SD_R(1.0) / 40320 - x2 * (SD_R(1.0) / 3628800)))));
        sx = x * (SD_R(1.0) -
                  x2 * (SD_R(1.0) / 6 - x2 * (SD_R(1.0) / 120 - x2 * (SD_R(1.0) / 5040 - x2 * (SD_R(1.0) / 362880)))));
    } else {
        cx = sd_cos(x);
        sx = sd_sin(x);
    }
    sd_real cc = c * cx - s * sx, ss = s * cx + c * sx;
    sd_real k = SD_R(1.0) / sd_sqrt(cc * cc + ss * ss);
    *co = cc * k;
    *so = ss * k;
}

/* ---- arcs: phi(α) = P cos α + Q sin α + R sqrt(cos²α + g2 sin²α) ------
 * (u = cos α e1 + sin α e2 on a great circle; g2 = γ², the squared cosine
 * between the circle's normal and the cylinder axis whose |u × z| this is;
 * R = 0 for a sinusoid). Derivatives in α, with k = g2 − 1, S² = 1 + k s²:
 *   phi′ = −P s + Q c + R k s c / S
 *   phi″ = −P c − Q s + R k ((c² − s²) S² − k s² c²) / S³ */
typedef struct sd_cylc_arc {
    sd_real P, Q, R, g2;
} sd_cylc_arc;

SD_HD static SD_INLINE sd_real sd_cylc_phi(const sd_cylc_arc *f, sd_real c, sd_real s)
{
    return f->P * c + f->Q * s + f->R * sd_sqrt(c * c + f->g2 * s * s);
}

SD_HD static SD_INLINE void sd_cylc_phi_d(const sd_cylc_arc *f, sd_real c, sd_real s, sd_real *d1, sd_real *d2)
{
    sd_real k = f->g2 - SD_R(1.0);
    sd_real S2 = c * c + f->g2 * s * s;
    sd_real S = sd_sqrt(S2);
    if (!(S > SD_R(1e-300))) { /* on the kink itself (γ = 0, c = 0): no model */
        *d1 = -f->P * s + f->Q * c;
        *d2 = SD_R(-1.0);
        return;
    }
    *d1 = -f->P * s + f->Q * c + f->R * k * s * c / S;
    *d2 = -f->P * c - f->Q * s + f->R * k * ((c * c - s * s) * S2 - k * s * s * c * c) / (S2 * S);
}

/* The rim function: rim A's point p_A(θ) = c_A' + R_A (cos θ e1 + sin θ e2)
 * against rim B (centre c_B', axis z_B, radius R_B), through the scalars
 * it needs: w = c_A' − c_B', W1 = w·e1, W2 = w·e2, W0 = |w|², Z0 = w·z_B,
 * Z1 = e1·z_B, Z2 = e2·z_B (e1 ⊥ e2 unit). */
typedef struct sd_cylc_rim {
    sd_vec3 w, e1, e2, zb;
    sd_real Ra, Rb;
    sd_real W0, W1, W2, Z0, Z1, Z2;
} sd_cylc_rim;

SD_HD static SD_INLINE void sd_cylc_rim_init(sd_cylc_rim *f)
{
    f->W0 = sd_v3_norm2(f->w);
    f->W1 = sd_v3_dot(f->w, f->e1);
    f->W2 = sd_v3_dot(f->w, f->e2);
    f->Z0 = sd_v3_dot(f->w, f->zb);
    f->Z1 = sd_v3_dot(f->e1, f->zb);
    f->Z2 = sd_v3_dot(f->e2, f->zb);
}

/* g(θ) = |q|² − 2 R_B ρ + R_B² (the squared distance from p_A(θ) to rim
 * B), q = p_A(θ) − c_B' = w + r, r = R_A (c e1 + s e2), ρ = the distance
 * of q from B's axis; with q′ = t = R_A (−s e1 + c e2), q″ = −r,
 * z = q·z_B, m = ρ² = |q|² − z² (r·t = 0, |r| = |t| = R_A):
 *   |q|² = W0 + 2 R_A (c W1 + s W2) + R_A², q·t = R_A (c W2 − s W1),
 *   q·r = R_A (c W1 + s W2) + R_A², z = Z0 + R_A (c Z1 + s Z2),
 *   z′ = R_A (c Z2 − s Z1), r·z_B = R_A (c Z1 + s Z2);
 *   g′ = 2 q·t − 2 R_B ρ′, ρ′ = m′/(2ρ), m′ = 2 q·t − 2 z z′,
 *   g″ = 2(R_A² − q·r) − 2 R_B ρ″, ρ″ = (m″ − 2ρ′²)/(2ρ),
 *   m″ = 2(R_A² − q·r) − 2(z′² − z r·z_B). */
SD_HD static SD_INLINE sd_real sd_cylc_rim_g(const sd_cylc_rim *f, sd_real c, sd_real s, sd_real *d1, sd_real *d2)
{
    const sd_real Ra = f->Ra;
    sd_real wr = Ra * (c * f->W1 + s * f->W2);
    sd_real Qn = f->W0 + SD_R(2.0) * wr + Ra * Ra;
    sd_real zr = Ra * (c * f->Z1 + s * f->Z2);
    sd_real z = f->Z0 + zr;
    sd_real m = sd_max(Qn - z * z, SD_R(0.0));
    sd_real rho = sd_sqrt(m);
    sd_real g = Qn - SD_R(2.0) * f->Rb * rho + f->Rb * f->Rb;
    if (d1) {
        sd_real qt = Ra * (c * f->W2 - s * f->W1), zt = Ra * (c * f->Z2 - s * f->Z1), qr = wr + Ra * Ra;
        sd_real Q2 = SD_R(2.0) * (Ra * Ra - qr);
        if (rho > SD_R(1e-12) * (Ra + f->Rb + SD_R(1e-300))) {
            sd_real m1 = SD_R(2.0) * (qt - z * zt);
            sd_real m2 = Q2 - SD_R(2.0) * (zt * zt - z * zr);
            sd_real rho1 = m1 / (SD_R(2.0) * rho);
            sd_real rho2 = (m2 - SD_R(2.0) * rho1 * rho1) / (SD_R(2.0) * rho);
            *d1 = SD_R(2.0) * qt - SD_R(2.0) * f->Rb * rho1;
            *d2 = Q2 - SD_R(2.0) * f->Rb * rho2;
        } else { /* p_A on B's axis: g has a maximum-like kink here */
            *d1 = SD_R(2.0) * qt;
            *d2 = SD_R(-1.0);
        }
    }
    return g;
}

/* value (and derivatives) of either kind at angle offset x from (c0, s0) */
SD_HD static SD_INLINE sd_real sd_cylc_eval1(const sd_cylc_arc *arc, const sd_cylc_rim *rim, sd_real c, sd_real s,
                                             sd_real *d1, sd_real *d2)
{
    if (arc) {
        if (d1)
            sd_cylc_phi_d(arc, c, s, d1, d2);
        return sd_cylc_phi(arc, c, s);
    }
    return sd_cylc_rim_g(rim, c, s, d1, d2);
}

/* Local minimum of the function in the bracket [−hl, +hr] of offsets from
 * (c0, s0), where (c0, s0) is a sample no higher than its neighbours at
 * −hl and +hr: safeguarded Newton on the first derivative, bisection on
 * its sign when Newton leaves the bracket or the model is not convex. A
 * Newton step below 1e-13 rad ends the search only when the derivative
 * changes sign across it (else it is a kink's huge curvature — a piece's
 * end sits on f's kink — and the bracket is bisected). Returns (c, s). */
SD_HD static SD_INLINE void sd_cylc_refine(const sd_cylc_arc *arc, const sd_cylc_rim *rim, sd_real c0, sd_real s0,
                                           sd_real hl, sd_real hr, sd_real *co, sd_real *so)
{
    const sd_real eps = SD_R(1e-13);
    sd_real lo = -hl, hi = hr, x = SD_R(0.0);
    sd_real c = c0, s = s0, d1, d2;
    for (int it = 0; it < 60; ++it) {
        sd_cylc_eval1(arc, rim, c, s, &d1, &d2);
        if (d1 > SD_R(0.0))
            hi = x;
        else if (d1 < SD_R(0.0))
            lo = x;
        else
            break;
        if (hi - lo < eps)
            break;
        sd_real xn = d2 > SD_R(0.0) ? x - d1 / d2 : SD_R(0.5) * (lo + hi);
        if (!(xn > lo && xn < hi))
            xn = SD_R(0.5) * (lo + hi);
        if (sd_fabs(xn - x) < eps) {
            /* converged if the derivative changes sign over ±eps */
            sd_real xl = sd_max(lo, x - eps), xh = sd_min(hi, x + eps), cl, sl, ch, sh, e1, e2, f1, f2;
            sd_cylc_rot(c0, s0, xl, &cl, &sl);
            sd_cylc_rot(c0, s0, xh, &ch, &sh);
            sd_cylc_eval1(arc, rim, cl, sl, &e1, &e2);
            sd_cylc_eval1(arc, rim, ch, sh, &f1, &f2);
            if (e1 <= SD_R(0.0) && f1 >= SD_R(0.0))
                break;
            if (e1 > SD_R(0.0))
                hi = xl;
            if (f1 < SD_R(0.0))
                lo = xh;
            xn = SD_R(0.5) * (lo + hi);
        }
        x = xn;
        sd_cylc_rot(c0, s0, x, &c, &s);
    }
    *co = c;
    *so = s;
}

/* Scans the samples at offsets k·h from (c0, s0), k = 0..n (by rotation;
 * wrap: a closed circle of n samples, the last one's neighbour is the
 * first), for the local minima of the function (an arc's phi, or the rim
 * function g = G²).
 * Pruning: the function (rim: G = sqrt g) changes by at most `lip` per
 * radian, so over an interval of length h it stays above
 * (f_k + f_k+1 − lip h)/2; an interval whose bound exceeds `thr` (the best
 * depth so far, in the function's units) cannot hold the minimiser.
 * Every other interval is cut in SD_CYLC_SUB parts (two minima can sit in
 * one coarse interval where the function is small, as when two rims
 * nearly touch), each pruned the same way; a smooth interior minimum lies
 * where the derivative turns from negative to positive over a part, and
 * each such part is refined (at most SD_CYLC_MAX_MIN). An open arc's ends
 * are kinks of f (and point candidates of their own), where the
 * derivative is one-sided: an end no higher than its neighbour sample is
 * refined over that part. The refined points (c, s) go to out[]; returns
 * their count. */
#define SD_CYLC_MAX_MIN 8
#define SD_CYLC_SUB     4
SD_HD static SD_INLINE int sd_cylc_scan(const sd_cylc_arc *arc, const sd_cylc_rim *rim, sd_real c0, sd_real s0,
                                        sd_real h, int n, int wrap, sd_real thr, sd_real lip,
                                        sd_real out[SD_CYLC_MAX_MIN][2])
{
    const sd_real hs = h / SD_CYLC_SUB;
    sd_real ch = sd_cos(h), sh = sd_sin(h), chs = sd_cos(hs), shs = sd_sin(hs), dd;
    int nm = 0;
    sd_real c = c0, s = s0, d, f = sd_cylc_eval1(arc, rim, c, s, &d, &dd);
    const sd_real f0 = f, d0 = d;
    for (int k = 0; k < n; ++k) {
        sd_real cn, sn, fn, dn;
        if (wrap && k == n - 1) { /* the closing interval ends at sample 0 */
            cn = c0;
            sn = s0;
            fn = f0;
            dn = d0;
        } else {
            cn = c * ch - s * sh;
            sn = s * ch + c * sh;
            fn = sd_cylc_eval1(arc, rim, cn, sn, &dn, &dd);
        }
        sd_real va = rim ? sd_sqrt(sd_max(f, SD_R(0.0))) : f, vb = rim ? sd_sqrt(sd_max(fn, SD_R(0.0))) : fn;
        if (!(SD_R(0.5) * (va + vb - lip * h) > thr)) {
            sd_real pc = c, ps = s, pf = f, pd = d, pv = va;
            for (int j = 1; j <= SD_CYLC_SUB; ++j) {
                sd_real qc, qs, qf, qd, qv;
                if (j < SD_CYLC_SUB) {
                    qc = pc * chs - ps * shs;
                    qs = ps * chs + pc * shs;
                    qf = sd_cylc_eval1(arc, rim, qc, qs, &qd, &dd);
                    qv = rim ? sd_sqrt(sd_max(qf, SD_R(0.0))) : qf;
                } else {
                    qc = cn;
                    qs = sn;
                    qf = fn;
                    qd = dn;
                    qv = vb;
                }
                int take = 0;
                if (pd < SD_R(0.0) && qd > SD_R(0.0))
                    take = 1;
                else if (!wrap && k == 0 && j == 1 && pf <= qf)
                    take = 1; /* just inside the start */
                else if (!wrap && k == n - 1 && j == SD_CYLC_SUB && qf <= pf)
                    take = 2; /* just inside the end */
                if (take && SD_R(0.5) * (pv + qv - lip * hs) > thr)
                    take = 0;
                if (take && nm < SD_CYLC_MAX_MIN) {
                    if (take == 1)
                        sd_cylc_refine(arc, rim, pc, ps, SD_R(0.0), hs, &out[nm][0], &out[nm][1]);
                    else
                        sd_cylc_refine(arc, rim, qc, qs, hs, SD_R(0.0), &out[nm][0], &out[nm][1]);
                    nm++;
                }
                pc = qc;
                ps = qs;
                pf = qf;
                pd = qd;
                pv = qv;
            }
        }
        c = cn;
        s = sn;
        f = fn;
        d = dn;
    }
    return nm;
}

/* The arc candidates of the great circle spanned by e1, e2 (unit,
 * orthogonal) for the part of f that is u·w + R |u × z| on α in
 * [α0, α0 + len] (u = cos α e1 + sin α e2), with e1·z = 0 so that
 * |u × z|² = cos²α + γ² sin²α (g2 = γ² = 1 − (e2·z)²). Samples every π/16
 * or closer; and where γ is small (the circle passes within γ of the axis,
 * at α = π/2 or 3π/2, where f has a V of width ~γ) 9 more at offsets
 * 0, ±γ/4, ±γ, ±4γ, ±16γ about that point when it lies in the arc. */
SD_HD static SD_INLINE void sd_cylc_arc_search(sd_cylc_search *S, sd_vec3 e1, sd_vec3 e2, sd_vec3 w, sd_real R,
                                               sd_real g2, sd_real off, sd_real a0, sd_real len, int feature)
{
    const sd_real pi = SD_R(3.14159265358979323846);
    sd_cylc_arc f;
    f.P = sd_v3_dot(w, e1); /* u·w = cos α (w·e1) + sin α (w·e2) */
    f.Q = sd_v3_dot(w, e2);
    f.R = R;
    f.g2 = g2;
    sd_real out[SD_CYLC_MAX_MIN][2];
    /* split at the points nearest the axis (α = π/2, 3π/2), where f has
     * its kink when γ → 0: each piece is smooth, its ends are refined */
    sd_real cut[4];
    int ncut = 0;
    cut[ncut++] = SD_R(0.0);
    for (int pole = 0; pole < 2; ++pole) {
        sd_real rel = (pole == 0 ? SD_R(0.5) : SD_R(1.5)) * pi - a0;
        if (rel < SD_R(0.0))
            rel += SD_R(2.0) * pi;
        if (rel > SD_R(1e-9) && rel < len - SD_R(1e-9))
            cut[ncut++] = rel;
    }
    if (ncut == 3 && cut[2] < cut[1]) {
        sd_real t = cut[1];
        cut[1] = cut[2];
        cut[2] = t;
    }
    cut[ncut] = len;
    for (int piece = 0; piece < ncut; ++piece) {
        sd_real b0 = a0 + cut[piece], bl = cut[piece + 1] - cut[piece];
        int n = (int)(bl / (pi / 16) + SD_R(0.999));
        if (n < 2)
            n = 2;
        /* f = phi + off on the circle; |phi′| ≤ sqrt(P² + Q²) + R */
        int nm = sd_cylc_scan(&f, NULL, sd_cos(b0), sd_sin(b0), bl / (sd_real)n, n, 0, S->best - off,
                              sd_sqrt(f.P * f.P + f.Q * f.Q) + f.R, out);
        for (int k = 0; k < nm; ++k)
            sd_cylc_try(S, sd_v3_add(sd_v3_scale(e1, out[k][0]), sd_v3_scale(e2, out[k][1])), feature);
    }
    if (!(R > SD_R(0.0) && g2 < SD_R(0.04)))
        return;
    const sd_real gam = sd_sqrt(g2);
    const sd_real offs[4] = {SD_R(0.25), SD_R(1.0), SD_R(4.0), SD_R(16.0)};
    for (int pole = 0; pole < 2; ++pole) {
        sd_real at = pole == 0 ? SD_R(0.5) * pi : SD_R(1.5) * pi;
        sd_real rel = at - a0; /* where the pole point sits in the arc */
        if (rel < SD_R(0.0))
            rel += SD_R(2.0) * pi;
        if (!(rel > SD_R(0.0) && rel < len))
            continue;
        sd_real cm = SD_R(0.0), sm = pole == 0 ? SD_R(1.0) : SD_R(-1.0);
        sd_real xs[9], fs[9], cs[9], ss[9];
        for (int k = 0; k < 4; ++k) {
            xs[3 - k] = -offs[k] * gam;
            xs[5 + k] = offs[k] * gam;
        }
        xs[4] = SD_R(0.0);
        for (int k = 0; k < 9; ++k) {
            sd_cylc_rot(cm, sm, xs[k], &cs[k], &ss[k]);
            fs[k] = sd_cylc_phi(&f, cs[k], ss[k]);
        }
        for (int k = 1; k < 8; ++k)
            if (fs[k] <= fs[k - 1] && fs[k] <= fs[k + 1] && rel + xs[k - 1] > SD_R(0.0) && rel + xs[k + 1] < len) {
                sd_real co, so;
                sd_cylc_refine(&f, NULL, cs[k], ss[k], xs[k] - xs[k - 1], xs[k + 1] - xs[k], &co, &so);
                sd_cylc_try(S, sd_v3_add(sd_v3_scale(e1, co), sd_v3_scale(e2, so)), feature);
            }
    }
}

/* A cylinder's side circle (u ⊥ its axis x) against the other body Y.
 * Y a cylinder (axis y): e1 = x × y / |x × y|, e2 = e1 × x; u·y = β sin α
 * (β = |x × y|), |u × y|² = cos²α + γ² sin²α (γ = |x·y|); the two half
 * circles (sign of u·y) each have w = d + σ h_Y y, plus the constant R_X.
 * Y a box: on the side circle f = u·w + R_X with w = d + Σ σ_i a_i e_i on
 * each arc between the crossings with the box's circles (a sinusoid, no
 * curvature of its own): its minimum −|w_⊥| at u = −w_⊥/|w_⊥| for each of
 * the 8 sign choices (a u outside its arc is still a valid candidate). */
SD_HD static SD_INLINE void sd_cylc_side_circle(sd_cylc_search *S, const sd_cylc_body *X, const sd_cylc_body *Y,
                                                int feature)
{
    sd_vec3 x = X->e[2];
    if (Y->box) {
        for (int m = 0; m < 8; ++m) {
            sd_vec3 w = S->d;
            w = sd_v3_madd(w, (m & 1) ? Y->a.x : -Y->a.x, Y->e[0]);
            w = sd_v3_madd(w, (m & 2) ? Y->a.y : -Y->a.y, Y->e[1]);
            w = sd_v3_madd(w, (m & 4) ? Y->a.z : -Y->a.z, Y->e[2]);
            sd_vec3 wp = sd_v3_madd(w, -sd_v3_dot(w, x), x);
            sd_real n = sd_v3_norm(wp);
            if (n > SD_R(0.0))
                sd_cylc_try(S, sd_v3_scale(wp, SD_R(-1.0) / n), feature);
        }
        return;
    }
    sd_vec3 y = Y->e[2];
    sd_vec3 xy = sd_cylc_cross(x, y);
    sd_real beta = sd_v3_norm(xy);
    sd_vec3 e1 = beta > SD_R(1e-12) ? sd_v3_scale(xy, SD_R(1.0) / beta) : sd_cylc_perp(x);
    sd_vec3 e2 = sd_v3_cross(e1, x);
    sd_real gy = sd_v3_dot(x, y);
    sd_real g2 = gy * gy;
    if (!(beta > SD_R(1e-12)))
        g2 = SD_R(1.0);
    for (int sg = 0; sg < 2; ++sg) {
        sd_real sig = sg == 0 ? SD_R(1.0) : SD_R(-1.0); /* the sign of u·y on this half */
        sd_vec3 w = sd_v3_madd(S->d, sig * Y->h, y);
        /* ±w is Y's rim centre seen from X's centre (X = A: c_B − σ h_B y
         * = c_A − w; X = B: c_A + σ h_A y = c_B + w); the minimiser here
         * has |p| = D ≤ best with one end on X's side (R_X from X's axis
         * segment) and the other on that rim: prune when they are too far */
        sd_vec3 wp = sd_v3_madd(w, -sd_clamp(sd_v3_dot(w, x), -X->h, X->h), x);
        if (beta > SD_R(1e-12) && sd_v3_norm(wp) - X->R - Y->R > S->best)
            continue; /* (parallel axes: the whole circle is side on side) */
        /* the half circle from σ e1 through σ e2 to −σ e1 (u·y = σ β sin α
         * ≥ 0·σ there); |u × y|² = cos²α + γ² sin²α in this frame too.
         * f = u·w + R_X + R_Y |u × y|: the constant R_X does not move the
         * minima, and sd_cylc_try evaluates the whole f */
        sd_cylc_arc_search(S, sd_v3_scale(e1, sig), sd_v3_scale(e2, sig), w, Y->R, g2, X->R, SD_R(0.0),
                           SD_R(3.14159265358979323846), feature);
    }
}

/* Rim on rim: for each pair of caps (σ_A, σ_B) whose rims can come within
 * the best depth so far of each other, the local minima of G(θ) (24
 * samples round rim A), each giving u = the common normal of the two rim
 * tangents (and p/|p|) as candidates. */
SD_HD static SD_INLINE void sd_cylc_rim_rim(sd_cylc_search *S)
{
    const sd_cylc_body *A = S->A, *B = S->B;
    for (int m = 0; m < 4; ++m) {
        sd_real sa = (m & 1) ? SD_R(-1.0) : SD_R(1.0), sb = (m & 2) ? SD_R(-1.0) : SD_R(1.0);
        sd_cylc_rim f;
        /* rim centres: c_A + σ_A h_A z_A and c_B + σ_B h_B z_B */
        f.w = sd_v3_add(S->d, sd_v3_sub(sd_v3_scale(A->e[2], sa * A->h), sd_v3_scale(B->e[2], sb * B->h)));
        f.e1 = A->e[0];
        f.e2 = A->e[1];
        f.zb = B->e[2];
        f.Ra = A->R;
        f.Rb = B->R;
        sd_cylc_rim_init(&f);
        /* any two rim points are at least |w| − R_A − R_B apart, and the
         * rim-rim minimiser is |p| = D ≤ best apart */
        if (sd_v3_norm(f.w) - A->R - B->R > S->best)
            continue;
        sd_real out[SD_CYLC_MAX_MIN][2];
        int nm = sd_cylc_scan(NULL, &f, SD_R(1.0), SD_R(0.0), SD_R(2.0) * SD_R(3.14159265358979323846) / 24, 24, 1,
                              S->best, A->R, out);
        for (int k = 0; k < nm; ++k) {
            sd_real c = out[k][0], s = out[k][1];
            sd_vec3 r = sd_v3_add(sd_v3_scale(f.e1, c), sd_v3_scale(f.e2, s)); /* unit radial of rim A */
            sd_vec3 ta = sd_v3_sub(sd_v3_scale(f.e2, c), sd_v3_scale(f.e1, s));
            sd_vec3 q = sd_v3_madd(f.w, A->R, r);
            sd_vec3 qp = sd_v3_madd(q, -sd_v3_dot(q, f.zb), f.zb); /* radial part about B's axis */
            sd_real rho = sd_v3_norm(qp);
            if (!(rho > SD_R(0.0)))
                continue;
            sd_vec3 rb = sd_v3_scale(qp, SD_R(1.0) / rho);
            sd_vec3 p = sd_v3_madd(q, -B->R, rb); /* p_A − p_B */
            sd_vec3 tb = sd_v3_cross(f.zb, rb);
            sd_vec3 nn = sd_v3_cross(ta, tb);
            sd_real nl = sd_v3_norm(nn);
            if (nl > SD_R(1e-9)) {
                nn = sd_v3_scale(nn, SD_R(1.0) / nl);
                /* the outward sense: along p, or, when p vanishes (rims
                 * touching), the one that A's cap σ_A faces */
                sd_real sp = sd_v3_dot(nn, p);
                if (sp < SD_R(0.0) || (sp == SD_R(0.0) && sa * sd_v3_dot(nn, A->e[2]) < SD_R(0.0)))
                    nn = sd_v3_neg(nn);
                sd_cylc_try(S, nn, SD_CYLC_RIM_RIM);
            }
            sd_real pl = sd_v3_norm(p);
            if (pl > SD_R(0.0))
                sd_cylc_try(S, sd_v3_scale(p, SD_R(1.0) / pl), SD_CYLC_RIM_RIM);
        }
    }
}

/* A box edge's circle (u ⊥ e_i) against cylinder Y: f = u·w + R_Y |u × y|
 * on the arcs between the crossings with u·e_j = 0, u·e_k = 0 (at ±e_k,
 * ±e_j) and u·y = 0 (at ±e1, e1 = e_i × y / |e_i × y|). In the frame
 * e1, e2 = e1 × e_i: u·y = β sin α, |u × y|² = cos²α + γ² sin²α, γ = |e_i·y|. */
SD_HD static SD_INLINE void sd_cylc_edge_circle(sd_cylc_search *S, const sd_cylc_body *X, int i, const sd_cylc_body *Y)
{
    const sd_real pi = SD_R(3.14159265358979323846);
    sd_vec3 ei = X->e[i], y = Y->e[2];
    sd_vec3 xy = sd_cylc_cross(ei, y);
    sd_real beta = sd_v3_norm(xy);
    sd_vec3 e1 = beta > SD_R(1e-12) ? sd_v3_scale(xy, SD_R(1.0) / beta) : sd_cylc_perp(ei);
    sd_vec3 e2 = sd_v3_cross(e1, ei);
    sd_real gy = sd_v3_dot(ei, y);
    sd_real g2 = beta > SD_R(1e-12) ? gy * gy : SD_R(1.0);
    int j = (i + 1) % 3, k = (i + 2) % 3;
    const sd_real aa[3] = {X->a.x, X->a.y, X->a.z};
    /* crossing angles in [0, 2π): 0, π, and those of ±e_j, ±e_k */
    sd_real ang[6];
    ang[0] = SD_R(0.0);
    ang[1] = pi;
    sd_vec3 ej = X->e[j], ek = X->e[k];
    sd_real tj = sd_atan2(sd_v3_dot(ej, e2), sd_v3_dot(ej, e1)), tk = sd_atan2(sd_v3_dot(ek, e2), sd_v3_dot(ek, e1));
    ang[2] = tj;
    ang[3] = tj + pi;
    ang[4] = tk;
    ang[5] = tk + pi;
    for (int m = 2; m < 6; ++m) {
        while (ang[m] < SD_R(0.0))
            ang[m] += SD_R(2.0) * pi;
        while (ang[m] >= SD_R(2.0) * pi)
            ang[m] -= SD_R(2.0) * pi;
    }
    for (int m = 1; m < 6; ++m) /* insertion sort */
        for (int q = m; q > 0 && ang[q] < ang[q - 1]; --q) {
            sd_real t = ang[q];
            ang[q] = ang[q - 1];
            ang[q - 1] = t;
        }
    for (int m = 0; m < 6; ++m) {
        sd_real a0 = ang[m], a1 = m < 5 ? ang[m + 1] : ang[0] + SD_R(2.0) * pi;
        sd_real len = a1 - a0;
        if (!(len > SD_R(1e-9)))
            continue;
        sd_real am = SD_R(0.5) * (a0 + a1);
        sd_vec3 um = sd_v3_add(sd_v3_scale(e1, sd_cos(am)), sd_v3_scale(e2, sd_sin(am)));
        sd_vec3 w = S->d;
        w = sd_v3_madd(w, sd_v3_dot(um, ej) >= SD_R(0.0) ? aa[j] : -aa[j], ej);
        w = sd_v3_madd(w, sd_v3_dot(um, ek) >= SD_R(0.0) ? aa[k] : -aa[k], ek);
        w = sd_v3_madd(w, sd_v3_dot(um, y) >= SD_R(0.0) ? Y->h : -Y->h, y);
        sd_cylc_arc_search(S, e1, e2, w, Y->R, g2, SD_R(0.0), a0, len, SD_CYLC_EDGE_RIM);
    }
}

/* ---- the supporting faces and the witness point ---------------------- */

typedef struct sd_cylc_face {
    int kind;     /* 0 point, 1 segment, 2 disc, 3 rectangle */
    sd_vec3 p;    /* point; segment, disc or rectangle centre */
    sd_vec3 t[2]; /* segment direction (t[0]); rectangle edge directions */
    sd_real l[2]; /* segment half length; disc radius (l[0]); rectangle half sides */
    sd_vec3 n;    /* disc normal */
} sd_cylc_face;

/* The face of body b supporting direction u (within `tol` rad). */
SD_HD static SD_INLINE sd_cylc_face sd_cylc_face_of(const sd_cylc_body *b, sd_vec3 u, sd_real tol)
{
    sd_cylc_face F;
    F.p = b->c;
    F.kind = 0;
    F.t[0] = F.t[1] = F.n = sd_v3_zero();
    F.l[0] = F.l[1] = SD_R(0.0);
    if (b->box) {
        const sd_real aa[3] = {b->a.x, b->a.y, b->a.z};
        int nf = 0;
        for (int i = 0; i < 3; ++i) {
            sd_real t = sd_v3_dot(u, b->e[i]);
            if (sd_fabs(t) <= tol && nf < 2) {
                F.t[nf] = b->e[i];
                F.l[nf] = aa[i];
                nf++;
            } else
                F.p = sd_v3_madd(F.p, t >= SD_R(0.0) ? aa[i] : -aa[i], b->e[i]);
        }
        F.kind = nf == 0 ? 0 : (nf == 1 ? 1 : 3);
        return F;
    }
    sd_vec3 z = b->e[2];
    sd_real t = sd_v3_dot(u, z);
    sd_vec3 rp = sd_v3_madd(u, -t, z);
    sd_real sp = sd_v3_norm(rp);
    if (sp <= tol) { /* the cap */
        F.kind = 2;
        F.p = sd_v3_madd(b->c, t >= SD_R(0.0) ? b->h : -b->h, z);
        F.n = z;
        F.l[0] = b->R;
        return F;
    }
    sd_vec3 r = sd_v3_scale(rp, SD_R(1.0) / sp);
    if (sd_fabs(t) <= tol) { /* a side line */
        F.kind = 1;
        F.p = sd_v3_madd(b->c, b->R, r);
        F.t[0] = z;
        F.l[0] = b->h;
        return F;
    }
    F.p = sd_v3_madd(sd_v3_madd(b->c, t >= SD_R(0.0) ? b->h : -b->h, z), b->R, r);
    return F;
}

/* The point of face F nearest x. */
SD_HD static SD_INLINE sd_vec3 sd_cylc_face_project(const sd_cylc_face *F, sd_vec3 x)
{
    sd_vec3 v = sd_v3_sub(x, F->p);
    switch (F->kind) {
    case 1:
        return sd_v3_madd(F->p, sd_clamp(sd_v3_dot(v, F->t[0]), -F->l[0], F->l[0]), F->t[0]);
    case 2: {
        sd_vec3 in = sd_v3_madd(v, -sd_v3_dot(v, F->n), F->n);
        sd_real r = sd_v3_norm(in);
        if (r > F->l[0])
            in = sd_v3_scale(in, F->l[0] / r);
        return sd_v3_add(F->p, in);
    }
    case 3:
        return sd_v3_madd(sd_v3_madd(F->p, sd_clamp(sd_v3_dot(v, F->t[0]), -F->l[0], F->l[0]), F->t[0]),
                          sd_clamp(sd_v3_dot(v, F->t[1]), -F->l[1], F->l[1]), F->t[1]);
    default:
        return F->p;
    }
}

/* Two segments in (nearly) one plane: the point of the first nearest the
 * second (their crossing; for parallel ones the middle of their overlap). */
SD_HD static SD_INLINE sd_vec3 sd_cylc_segments(const sd_cylc_face *P, const sd_cylc_face *Q)
{
    sd_vec3 r = sd_v3_sub(P->p, Q->p);
    sd_real b = sd_v3_dot(P->t[0], Q->t[0]), dp = sd_v3_dot(P->t[0], r), dq = sd_v3_dot(Q->t[0], r);
    sd_real den = SD_R(1.0) - b * b;
    sd_real sp;
    if (den > SD_R(1e-12)) {
        /* the lines' closest points: P.p + sp t_P and Q.p + sq t_Q */
        sp = (b * dq - dp) / den;
        sd_real sq = (dq - b * dp) / den;
        sq = sd_clamp(sq, -Q->l[0], Q->l[0]);
        /* sp again from the clamped sq, then clamped */
        sp = sd_clamp(sd_v3_dot(P->t[0], sd_v3_sub(sd_v3_madd(Q->p, sq, Q->t[0]), P->p)), -P->l[0], P->l[0]);
    } else {
        /* parallel: Q's extent along t_P, intersected with P's */
        sd_real mid = -dp, ext = Q->l[0];
        sd_real lo = sd_max(-P->l[0], mid - ext), hi = sd_min(P->l[0], mid + ext);
        sp = lo <= hi ? SD_R(0.5) * (lo + hi) : (mid > SD_R(0.0) ? P->l[0] : -P->l[0]);
    }
    return sd_v3_madd(P->p, sp, P->t[0]);
}

/* Segment S against a disc or rectangle O in (nearly) the same plane: the
 * middle of the interval of S inside O, or S's point nearest O's centre
 * when they do not meet. */
SD_HD static SD_INLINE sd_vec3 sd_cylc_clip(const sd_cylc_face *Sg, const sd_cylc_face *O)
{
    sd_vec3 t = Sg->t[0];
    sd_vec3 r = sd_v3_sub(Sg->p, O->p); /* segment point at s: r + s t, from O's centre */
    sd_real lo = -Sg->l[0], hi = Sg->l[0];
    if (O->kind == 2) {
        /* in-plane: |r_p + s t_p|² ≤ R² */
        sd_vec3 rp = sd_v3_madd(r, -sd_v3_dot(r, O->n), O->n), tp = sd_v3_madd(t, -sd_v3_dot(t, O->n), O->n);
        sd_real A2 = sd_v3_norm2(tp), B1 = sd_v3_dot(rp, tp), C0 = sd_v3_norm2(rp) - O->l[0] * O->l[0];
        if (A2 > SD_R(0.0)) {
            sd_real disc = B1 * B1 - A2 * C0;
            sd_real sm = -B1 / A2; /* nearest approach */
            if (disc >= SD_R(0.0)) {
                sd_real q = sd_sqrt(disc) / A2;
                lo = sd_max(lo, sm - q);
                hi = sd_min(hi, sm + q);
            } else
                lo = hi = sd_clamp(sm, lo, hi);
        }
    } else {
        /* the two slabs |(r + s t)·e_k| ≤ l_k */
        for (int k = 0; k < 2; ++k) {
            sd_real a = sd_v3_dot(r, O->t[k]), b = sd_v3_dot(t, O->t[k]);
            if (sd_fabs(b) > SD_R(1e-300)) {
                sd_real s1 = (-O->l[k] - a) / b, s2 = (O->l[k] - a) / b;
                lo = sd_max(lo, sd_min(s1, s2));
                hi = sd_min(hi, sd_max(s1, s2));
            }
        }
    }
    sd_real s = lo <= hi ? SD_R(0.5) * (lo + hi) : sd_clamp(-sd_v3_dot(r, t), -Sg->l[0], Sg->l[0]);
    return sd_v3_madd(Sg->p, s, t);
}

/* ---- the contact ------------------------------------------------------ */

/* Depth, normal and witnesses of bodies A and B (cylinder–cylinder or
 * box–cylinder, in either order), whose cores overlap. L: the pair's length
 * scale (tolerances). */
SD_HD static SD_INLINE sd_cylc_result sd_cylc_bodies(const sd_cylc_body *A, const sd_cylc_body *B, sd_real L)
{
    sd_cylc_result res;
    res.status = SD_CYLC_FALLBACK;
    res.feature = 0;
    res.depth = SD_R(0.0);
    res.normal = sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0));
    res.pa = A->c;
    res.pb = B->c;
    res.candidates = 0;
    sd_cylc_search S;
    S.A = A;
    S.B = B;
    S.d = sd_v3_sub(A->c, B->c);
    S.best = SD_R(1e300);
    S.u = sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0));
    S.feature = 0;
    S.evals = 0;
    if (A->box && B->box)
        return res;
    /* points: caps and faces, then the crossings of the smooth strata */
    for (int sg = 0; sg < 2; ++sg) {
        sd_real sig = sg == 0 ? SD_R(1.0) : SD_R(-1.0);
        for (int side = 0; side < 2; ++side) {
            const sd_cylc_body *X = side == 0 ? A : B;
            if (X->box)
                for (int i = 0; i < 3; ++i)
                    sd_cylc_try(&S, sd_v3_scale(X->e[i], sig), SD_CYLC_BOX_FACE);
            else
                sd_cylc_try(&S, sd_v3_scale(X->e[2], sig), side == 0 ? SD_CYLC_CAP_A : SD_CYLC_CAP_B);
        }
    }
    const sd_cylc_body *C = A->box ? B : A; /* a cylinder */
    const sd_cylc_body *O = A->box ? A : B; /* the other body */
    if (!O->box) {
        sd_vec3 n = sd_cylc_cross(A->e[2], B->e[2]);
        sd_real nl = sd_v3_norm(n);
        if (nl > SD_R(1e-12)) {
            n = sd_v3_scale(n, SD_R(1.0) / nl);
            sd_cylc_try(&S, n, SD_CYLC_SIDE_SIDE);
            sd_cylc_try(&S, sd_v3_neg(n), SD_CYLC_SIDE_SIDE);
        }
        /* rim on rim first: it is the common shallow contact and gives
         * the tightest best value for the pruning */
        sd_cylc_side_circle(&S, A, B, SD_CYLC_SIDE_A);
        sd_cylc_side_circle(&S, B, A, SD_CYLC_SIDE_B);
        sd_cylc_rim_rim(&S);
    } else {
        for (int i = 0; i < 3; ++i) {
            sd_vec3 n = sd_cylc_cross(O->e[i], C->e[2]);
            sd_real nl = sd_v3_norm(n);
            if (nl > SD_R(1e-12)) {
                n = sd_v3_scale(n, SD_R(1.0) / nl);
                sd_cylc_try(&S, n, SD_CYLC_SIDE_SIDE);
                sd_cylc_try(&S, sd_v3_neg(n), SD_CYLC_SIDE_SIDE);
            }
        }
        sd_cylc_side_circle(&S, C, O, C == A ? SD_CYLC_SIDE_A : SD_CYLC_SIDE_B);
        for (int i = 0; i < 3; ++i)
            sd_cylc_edge_circle(&S, O, i, C);
    }
    res.candidates = S.evals;
    sd_real D = S.best;
    sd_vec3 u = S.u;
    if (!(D < SD_R(1e300)) || !(sd_fabs(u.x) <= SD_R(1.0) && sd_fabs(u.y) <= SD_R(1.0) && sd_fabs(u.z) <= SD_R(1.0)))
        return res;
    if (D < SD_R(0.0)) /* the cores do not overlap after all (rounding at touch) */
        D = SD_R(0.0);
    /* witnesses: x in F_A(u) and x − D u in F_B(−u) */
    const sd_real tol = SD_R(1e-9);
    sd_cylc_face FA = sd_cylc_face_of(A, u, tol), FB = sd_cylc_face_of(B, sd_v3_neg(u), tol);
    FB.p = sd_v3_madd(FB.p, D, u);
    sd_vec3 x;
    if (FA.kind == 0)
        x = FA.p;
    else if (FB.kind == 0)
        x = FB.p;
    else if (FA.kind == 1 && FB.kind == 1)
        x = sd_cylc_segments(&FA, &FB);
    else if (FA.kind == 1 || FB.kind == 1) {
        /* a segment against a disc or rectangle: the middle of the part of
         * the segment inside the other face (or its nearest point) */
        const sd_cylc_face *Sg = FA.kind == 1 ? &FA : &FB, *Ot = FA.kind == 1 ? &FB : &FA;
        x = sd_cylc_clip(Sg, Ot);
    } else if (FA.kind == 2 && FB.kind == 2) {
        /* two discs: the middle of their common chord of the centre line */
        sd_vec3 dc = sd_v3_sub(FB.p, FA.p);
        dc = sd_v3_madd(dc, -sd_v3_dot(dc, FA.n), FA.n);
        sd_real dl = sd_v3_norm(dc);
        if (dl > SD_R(0.0)) {
            sd_real lo = sd_max(-FA.l[0], dl - FB.l[0]), hi = sd_min(FA.l[0], dl + FB.l[0]);
            sd_real t = lo <= hi ? SD_R(0.5) * (lo + hi) : FA.l[0];
            x = sd_v3_madd(FA.p, t / dl, dc);
        } else
            x = FA.p;
    } else {
        /* alternating projections converge to a point of the intersection
         * (linearly; these faces meet at large angles or overlap) */
        x = sd_v3_scale(sd_v3_add(FA.p, FB.p), SD_R(0.5));
        for (int it = 0; it < 64; ++it)
            x = sd_cylc_face_project(&FA, sd_cylc_face_project(&FB, x));
    }
    (void)L;
    res.status = SD_CYLC_OK;
    res.feature = S.feature;
    res.depth = D;
    res.normal = sd_v3_neg(u);
    res.pa = x;
    res.pb = sd_v3_madd(x, -D, u);
    return res;
}

/* The body of a posed sharp core (cylinder or box), or 0 if it is neither. */
SD_HD static SD_INLINE int sd_cylc_body_of(const sd_convex *c, sd_cylc_body *b)
{
    const sd_shape *s = c->shape;
    if (s->kind != SD_SHAPE_CYLINDER && s->kind != SD_SHAPE_BOX)
        return 0;
    sd_mat3 m = sd_quat_to_mat3(c->q);
    b->box = s->kind == SD_SHAPE_BOX;
    b->c = sd_v3_add(c->x, sd_quat_rotate(c->q, s->offset));
    for (int i = 0; i < 3; ++i)
        b->e[i] = sd_v3(m.m[0][i], m.m[1][i], m.m[2][i]);
    b->a = s->a;
    b->R = s->a.x;
    b->h = s->a.z;
    return 1;
}

/* 1 for the kind pairs the closed form handles: cylinder–cylinder and
 * box–cylinder in either order. */
SD_HD static SD_INLINE int sd_cylc_pair(int ka, int kb)
{
    return (ka == SD_SHAPE_CYLINDER && (kb == SD_SHAPE_CYLINDER || kb == SD_SHAPE_BOX)) ||
           (ka == SD_SHAPE_BOX && kb == SD_SHAPE_CYLINDER);
}

/* The contact of two posed cores: cylinder–cylinder or box–cylinder (either
 * order); FALLBACK for other kinds (box–box included) or degenerate input. */
SD_HD static SD_INLINE sd_cylc_result sd_cylc_penetration(const sd_convex *a, const sd_convex *b)
{
    sd_cylc_body A, B;
    sd_cylc_result r;
    r.status = SD_CYLC_FALLBACK;
    r.feature = 0;
    r.depth = SD_R(0.0);
    r.normal = sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0));
    r.pa = a->x;
    r.pb = b->x;
    r.candidates = 0;
    if (!sd_cylc_body_of(a, &A) || !sd_cylc_body_of(b, &B) || (A.box && B.box))
        return r;
    sd_real L = a->shape->bound + b->shape->bound;
    return sd_cylc_bodies(&A, &B, L > SD_R(0.0) ? L : SD_R(1.0));
}

#endif
