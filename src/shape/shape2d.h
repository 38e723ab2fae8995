/* shape2d.h — planar (2D) shape kinds, their support functions, and the
 * posed 2D convex body that 2D GJK/EPA (geom/gjk2d.h, geom/epa2d.h) asks for
 * support points.
 *
 * Every 2D shape is a convex core swept by a disc of radius `radius` (the
 * same shrink / GJK / swell idea as the 3D shapes, seed 004 §2.5): a circle
 * is a point core with its radius; the other kinds are sharp (radius 0) or
 * rounded. Templates are stored about the centroid of the swept shape, so a
 * particle's position is its centre of mass and theta turns the body frame
 * into the world frame (counter-clockwise).
 *
 * Support functions (seed 002 §2.2, eq. 1: s(d) = argmax_{P in A} d·P):
 *   circle      the centre (point core): O(1)
 *   ellipse     (a² dx, b² dy)/sqrt(a² dx² + b² dy²): O(1)
 *   polygon     the vertex of largest d·P: O(vertices)
 *   polybezier  closed chain of m cubic Bézier segments (3m control points).
 *               The support is SOLVED ON THE CURVE: d·B(t) is a cubic in t,
 *               its stationary points are the roots of a quadratic, so the
 *               exact maximiser on each segment costs one square root. The
 *               control points only prune: a segment lies in the hull of its
 *               4 control points, so a segment whose best control point
 *               cannot beat the best curve point so far is skipped. (Taking
 *               the best control point itself would return a point off the
 *               curve — the support of the control polygon, not of the
 *               shape — and give contact points and depths of a different,
 *               larger body.) O(control points), one sqrt per active segment.
 *   fourier     seed 002 eqs. 2–4: with n = d/|d| = (cos θ, sin θ) and
 *               t = (−sin θ, cos θ), the support point is p(θ) n + p′(θ) t;
 *               cos kθ, sin kθ come from n by the angle-addition recurrence
 *               (no trigonometric call): O(order).
 *
 * Pool layout (sd_real values from pool[start]): polygon and polybezier:
 * count points as x0, y0, x1, y1, ... (polygon counter-clockwise, extreme
 * vertices only); fourier: count = 2N + 1 values a0, a1, b1, a2, b2, ..., aN,
 * bN of eq. 2 (p = a0/2 + Σ a_k cos kθ + b_k sin kθ), N the order.
 *
 * Single source (DESIGN.md rule 1): everything above the "host" marker is
 * SD_HD, allocation-free and compiles as C17 and CUDA C++.
 */
#ifndef SD_SHAPE_SHAPE2D_H
#define SD_SHAPE_SHAPE2D_H

#include "core/vec2.h"

/* X(enum, scene name, what the parameters mean) */
#define SD_SHAPE2D_KINDS(X)                                                                                            \
    X(SD_SHAPE2D_CIRCLE, "circle", "point core; radius is the circle's")                                               \
    X(SD_SHAPE2D_ELLIPSE, "ellipse", "a = semi-axes of the core along x, y")                                           \
    X(SD_SHAPE2D_POLYGON, "polygon", "core = convex hull of the vertices")                                             \
    X(SD_SHAPE2D_POLYBEZIER, "polybezier", "core = closed convex chain of cubic Bezier segments")                      \
    X(SD_SHAPE2D_FOURIER, "fourier", "core support function p(theta), seed 002 eq. 2")

/* clang-format off */
typedef enum sd_shape2d_kind {
#define SD_X_ENUM2(e, name, doc) e,
    SD_SHAPE2D_KINDS(SD_X_ENUM2)
#undef SD_X_ENUM2
    SD_SHAPE2D_KIND_COUNT
} sd_shape2d_kind;
/* clang-format on */

/* Fixed limits (fixed GPU workspaces, bounded per-call cost). */
#define SD_SHAPE2D_MAX_POINTS 1024 /* polygon vertices, polybezier control points */
#define SD_SHAPE2D_MAX_ORDER  64   /* Fourier order N */

typedef struct sd_shape2d {
    int kind;              /* sd_shape2d_kind */
    sd_real radius;        /* m, rounding swept over the core, >= 0 (circle: its radius) */
    sd_vec2 a;             /* m, ellipse semi-axes of the core */
    uint32_t start, count; /* coefficients / vertices / control points in the pool (layout above) */
    sd_real area;          /* m^2, of the swept shape */
    sd_real inertia;       /* m^4, polar second moment about the centroid per unit density
                              and unit thickness (moment of inertia = density * thickness * inertia) */
    sd_real bound;         /* m, circumradius about the centroid, radius included */
    sd_real min_size;      /* m, smallest width of the swept shape (for overlap ratios) */
    sd_real eq_radius;     /* m, radius of the circle of the same area */
    /* cold, host side: where the centroid sat in the frame the shape was given in */
    sd_vec2 given_com;
} sd_shape2d;

/* A 2D convex body in the world: a shape with its pose. */
typedef struct sd_convex2d {
    const sd_shape2d *shape;
    const sd_real *pool; /* the coefficient / vertex pool (may be NULL for circles and ellipses) */
    sd_vec2 x;           /* m, centroid, world frame */
    sd_real theta;       /* rad, body frame to world frame, counter-clockwise */
} sd_convex2d;

/* Number of sd_real values a shape of this kind and count uses in the pool. */
SD_HD static SD_INLINE uint32_t sd_shape2d_pool_reals(int kind, uint32_t count)
{
    return (kind == SD_SHAPE2D_POLYGON || kind == SD_SHAPE2D_POLYBEZIER) ? 2u * count
                                                                         : (kind == SD_SHAPE2D_FOURIER ? count : 0u);
}

/* The Fourier support function at the direction (c1, s1) = (cos θ, sin θ):
 * p, p′ and p″ of eq. 2 from the interleaved coefficients c = a0, a1, b1, ...
 * (order n). cos kθ, sin kθ by the angle-addition recurrence. */
SD_HD static SD_INLINE void sd_fourier_eval(const sd_real *c, int n, sd_real c1, sd_real s1, sd_real *p, sd_real *dp,
                                            sd_real *ddp)
{
    sd_real ck = c1, sk = s1;
    sd_real v = SD_R(0.5) * c[0], d1 = SD_R(0.0), d2 = SD_R(0.0);
    for (int k = 1; k <= n; ++k) {
        const sd_real ak = c[2 * k - 1], bk = c[2 * k];
        const sd_real kk = (sd_real)k;
        const sd_real cs = ak * ck + bk * sk; /* a_k cos kθ + b_k sin kθ */
        v += cs;
        d1 += kk * (bk * ck - ak * sk);
        d2 -= kk * kk * cs;
        const sd_real cn = ck * c1 - sk * s1;
        sk = sk * c1 + ck * s1;
        ck = cn;
    }
    *p = v;
    if (dp)
        *dp = d1;
    if (ddp)
        *ddp = d2;
}

/* Direction used for a zero query direction (any fixed unit vector will do:
 * every point of the core is a support point of the zero direction). */
SD_HD static SD_INLINE sd_vec2 sd_shape2d_safe_dir(sd_vec2 d)
{
    return (d.x == SD_R(0.0) && d.y == SD_R(0.0)) ? sd_v2(SD_R(1.0), SD_R(0.0)) : d;
}

/* Polygon core: the vertex of largest d·P (ties: the first). */
SD_HD static SD_INLINE sd_vec2 sd_shape2d_support_polygon(const sd_real *v, uint32_t n, sd_vec2 d)
{
    uint32_t best = 0;
    sd_real bd = v[0] * d.x + v[1] * d.y;
    for (uint32_t i = 1; i < n; ++i) {
        sd_real e = v[2 * i] * d.x + v[2 * i + 1] * d.y;
        if (e > bd) {
            bd = e;
            best = i;
        }
    }
    return sd_v2(v[2 * best], v[2 * best + 1]);
}

/* Point of the cubic Bézier segment P0..P3 at parameter t. */
SD_HD static SD_INLINE sd_vec2 sd_bezier3_point(const sd_vec2 *P, sd_real t)
{
    const sd_real u = SD_R(1.0) - t;
    const sd_real b0 = u * u * u, b1 = SD_R(3.0) * u * u * t, b2 = SD_R(3.0) * u * t * t, b3 = t * t * t;
    return sd_v2(b0 * P[0].x + b1 * P[1].x + b2 * P[2].x + b3 * P[3].x,
                 b0 * P[0].y + b1 * P[1].y + b2 * P[2].y + b3 * P[3].y);
}

/* Polybézier core: the exact maximiser of d·B(t) over the closed chain. */
SD_HD static SD_INLINE sd_vec2 sd_shape2d_support_polybezier(const sd_real *v, uint32_t n, sd_vec2 d)
{
    const uint32_t m = n / 3u; /* segments */
    sd_vec2 bp = sd_v2(v[0], v[1]);
    sd_real best = bp.x * d.x + bp.y * d.y;
    for (uint32_t k = 0; k < m; ++k) {
        sd_vec2 P[4];
        sd_real e[4];
        sd_real ub = -SD_R(1e300);
        for (int i = 0; i < 4; ++i) {
            const uint32_t j = (3u * k + (uint32_t)i) % n;
            P[i] = sd_v2(v[2 * j], v[2 * j + 1]);
            e[i] = P[i].x * d.x + P[i].y * d.y;
            ub = sd_max(ub, e[i]);
        }
        if (ub <= best) /* the segment lies in the hull of P0..P3: it cannot win */
            continue;
        if (e[3] > best) { /* the end point (the next segment's start) */
            best = e[3];
            bp = P[3];
        }
        /* (d·B)′(t)/3 = (1−t)² g0 + 2(1−t)t g1 + t² g2 = A t² + B t + C */
        const sd_real g0 = e[1] - e[0], g1 = e[2] - e[1], g2 = e[3] - e[2];
        const sd_real A = g0 - SD_R(2.0) * g1 + g2, B = SD_R(2.0) * (g1 - g0), C = g0;
        sd_real t[2];
        int nt = 0;
        const sd_real scale = sd_fabs(g0) + sd_fabs(g1) + sd_fabs(g2);
        if (sd_fabs(A) <= SD_R(1e-12) * scale) {
            if (sd_fabs(B) > SD_R(0.0))
                t[nt++] = -C / B;
        } else {
            const sd_real disc = B * B - SD_R(4.0) * A * C;
            if (disc >= SD_R(0.0)) {
                /* the cancellation-free pair of roots */
                const sd_real q = SD_R(-0.5) * (B + (B >= SD_R(0.0) ? sd_sqrt(disc) : -sd_sqrt(disc)));
                t[nt++] = q / A;
                if (q != SD_R(0.0))
                    t[nt++] = C / q;
            }
        }
        for (int i = 0; i < nt; ++i) {
            if (!(t[i] > SD_R(0.0) && t[i] < SD_R(1.0)))
                continue;
            const sd_vec2 q = sd_bezier3_point(P, t[i]);
            const sd_real f = q.x * d.x + q.y * d.y;
            if (f > best) {
                best = f;
                bp = q;
            }
        }
    }
    return bp;
}

/* Fourier core, eqs. 3–4: x = p n + p′ t. */
SD_HD static SD_INLINE sd_vec2 sd_shape2d_support_fourier(const sd_real *c, uint32_t count, sd_vec2 d)
{
    const sd_vec2 n = sd_v2_scale(d, SD_R(1.0) / sd_v2_norm(d));
    sd_real p, dp;
    sd_fourier_eval(c, (int)((count - 1u) / 2u), n.x, n.y, &p, &dp, (sd_real *)0);
    return sd_v2(p * n.x - dp * n.y, p * n.y + dp * n.x);
}

/* Support point of the core, body frame. */
SD_HD static SD_INLINE sd_vec2 sd_shape2d_support_core(const sd_shape2d *s, const sd_real *pool, sd_vec2 d)
{
    d = sd_shape2d_safe_dir(d);
    switch (s->kind) {
    case SD_SHAPE2D_ELLIPSE: {
        const sd_real ax = s->a.x * s->a.x * d.x, ay = s->a.y * s->a.y * d.y;
        const sd_real den = sd_sqrt(ax * d.x + ay * d.y);
        return den > SD_R(0.0) ? sd_v2(ax / den, ay / den) : sd_v2_zero();
    }
    case SD_SHAPE2D_POLYGON:
        return sd_shape2d_support_polygon(pool + s->start, s->count, d);
    case SD_SHAPE2D_POLYBEZIER:
        return sd_shape2d_support_polybezier(pool + s->start, s->count, d);
    case SD_SHAPE2D_FOURIER:
        return sd_shape2d_support_fourier(pool + s->start, s->count, d);
    case SD_SHAPE2D_CIRCLE:
    default:
        return sd_v2_zero();
    }
}

/* Support point of the swept shape (core + radius · d/|d|), body frame. */
SD_HD static SD_INLINE sd_vec2 sd_shape2d_support(const sd_shape2d *s, const sd_real *pool, sd_vec2 d)
{
    d = sd_shape2d_safe_dir(d);
    const sd_vec2 c = sd_shape2d_support_core(s, pool, d);
    return s->radius > SD_R(0.0) ? sd_v2_madd(c, s->radius / sd_v2_norm(d), d) : c;
}

/* World-frame support of the posed core. */
SD_HD static SD_INLINE sd_vec2 sd_convex2d_support_core(const sd_convex2d *c, sd_vec2 d)
{
    const sd_real co = sd_cos(c->theta), si = sd_sin(c->theta);
    const sd_vec2 p = sd_shape2d_support_core(c->shape, c->pool, sd_v2_rotcs(d, co, -si));
    return sd_v2_add(c->x, sd_v2_rotcs(p, co, si));
}

/* World-frame support of the posed swept shape. */
SD_HD static SD_INLINE sd_vec2 sd_convex2d_support(const sd_convex2d *c, sd_vec2 d)
{
    const sd_real co = sd_cos(c->theta), si = sd_sin(c->theta);
    const sd_vec2 p = sd_shape2d_support(c->shape, c->pool, sd_v2_rotcs(d, co, -si));
    return sd_v2_add(c->x, sd_v2_rotcs(p, co, si));
}

/* ---- host: building templates (shape2d.c) ---------------------------------- */
#include <stddef.h>

#include <shapedem/shapedem.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sd_shape2d_desc {
    int kind;              /* sd_shape2d_kind */
    sd_real radius;        /* m: circle: its radius (> 0); other kinds: rounding swept over the core (>= 0) */
    sd_vec2 a;             /* m, ellipse: semi-axes (> 0) */
    const sd_vec2 *points; /* polygon: vertices in any order (the core is their convex hull, >= 3 not
                              collinear); polybezier: 3m control points P0..P(3m−1) of m cubic segments
                              (segment k: P3k, P3k+1, P3k+2, P3k+3, the last closing on P0), forming a
                              convex curve, either orientation */
    size_t point_count;
    const sd_real *fs_a; /* fourier: a_0 .. a_N of eq. 2 (N + 1 values, a_0 > 0) */
    const sd_real *fs_b; /* fourier: b_1 .. b_N (N values; NULL when N = 0) */
    int order;           /* fourier: N, 0 .. SD_SHAPE2D_MAX_ORDER */
    int cookie;          /* set by sd_shape2d_desc_default */
} sd_shape2d_desc;

sd_shape2d_desc sd_shape2d_desc_default(void);

/* Builds a template about the centroid of the swept shape: area, polar
 * moment, bound, min_size, eq_radius, given_com. Writes the kind's pool
 * values to pool[0 .. *pool_used) and sets out->start = 0 (a caller that
 * copies them into a shared pool at offset k sets start = k). pool_cap must
 * hold 2 * point_count values (polygon, polybezier) or 2N + 1 (fourier).
 * Bad desc: SD_ERR_INPUT with a message naming what is wrong (a Fourier
 * series that is not convex, p + p″ < 0 somewhere, eq. 5, is refused). */
sd_status sd_shape2d_make(const sd_shape2d_desc *desc, sd_shape2d *out, sd_real *pool, size_t pool_cap,
                          size_t *pool_used, sd_error *err);

/* Scene names from SD_SHAPE2D_KINDS; from_name returns -1 if unknown. */
const char *sd_shape2d_kind_name(int kind);
int sd_shape2d_kind_from_name(const char *name);

/* Area (m^2), centroid (m) and polar second moment about the centroid (m^4)
 * of the swept shape as stored (pool values from pool[s->start]). Exact for
 * circle, ellipse (sharp), polygon (sharp or rounded) and fourier (the
 * integrands are trigonometric polynomials, integrated by a trapezoid rule
 * that is exact for them); the rounded ellipse and the polybézier use
 * adaptive Gauss–Legendre quadrature to ~1e-13 relative (shape2d.c). */
void sd_shape2d_mass(const sd_shape2d *s, const sd_real *pool, sd_real *area, sd_vec2 *centroid, sd_real *polar);

/* Convex hull of n points (Andrew's monotone chain): writes the extreme
 * vertices counter-clockwise to hull (capacity n; it may be pts itself),
 * returns their number (0 for collinear, coincident, too few or
 * non-finite points). Never writes more than n points, whatever the input:
 * the orientation tests run on the points scaled by a power of two into
 * [-1, 1], so huge or tiny coordinates cannot overflow them. Uses O(n)
 * scratch from the allocator; returns 0 (and *oom = 1 when oom is not
 * NULL) if it fails. */
size_t sd_hull2d(const sd_vec2 *pts, size_t n, sd_vec2 *hull, int *oom);

/* Signed area of a closed polygon (> 0 counter-clockwise), summed as a
 * fan from p[0] (so far from the origin it keeps its digits). */
sd_real sd_polygon2d_area(const sd_vec2 *p, size_t n);

/* Extent of n points: *span the larger side of their bounding box, *reach
 * the largest |coordinate| (either may be NULL). Returns 0 (and sets
 * nothing) when a coordinate is not finite. */
int sd_points2d_extent(const sd_vec2 *p, size_t n, sd_real *span, sd_real *reach);

/* Smallest p(θ) + p″(θ) of a Fourier series (interleaved coefficients, order
 * n) over k equally spaced θ; *bound_slack (may be NULL) receives the most
 * the minimum over all θ can lie below the sampled one (Taylor bound:
 * Δ²/8 · Σ k²(k²−1)|c_k|), so sampled − slack ≥ 0 proves eq. 5 everywhere. */
sd_real sd_fourier_min_curvature_radius(const sd_real *c, int n, int k, sd_real *bound_slack);

#ifdef __cplusplus
}
#endif

#endif
