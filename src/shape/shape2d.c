/* shape2d.c — planar shape templates (host): validation, mass properties of
 * the swept shape, the move to the centroid, kind names, the 2D convex hull.
 *
 * Invariant: a template made here is stored about the centroid of its swept
 * shape (core ⊕ disc of `radius`), and its area and polar moment are those
 * of the swept shape, per unit density and unit thickness.
 *
 * Mass properties come from one idea, the triangle fan from the origin over
 * the outer boundary X (counter-clockwise):
 *     A = ½∮ X × dX,   S = ⅓∮ X (X × dX),   J_O = ¼∮ |X|² (X × dX)
 * (the area, first moment and polar moment about the origin of the thin
 * triangles (0, X, X + dX)); then c = S/A and J = J_O − A|c|². By kind:
 *   circle      closed form (πr², πr⁴/2);
 *   ellipse     sharp: πab, πab(a² + b²)/4. Rounded: the boundary by its
 *               support function h = p + r (seed 002 eqs. 3–4), for which
 *               X × X′ = h (h + h″) and h + h″ = a²b²/p³ + r; trapezoid rule
 *               in θ (periodic analytic integrand: geometric convergence),
 *               doubled until two levels agree to 1e-15;
 *   polygon     exact: each straight piece by the triangle formulas, the
 *               rounded corners (arcs of radius r) by 8-point Gauss–Legendre
 *               on sub-arcs of at most π/8 (error below 1e-16 relative);
 *   polybezier  sharp: Gauss–Legendre, 8 points per segment, exact (the
 *               integrands are polynomials of degree ≤ 11 in t). Rounded:
 *               the offset curve X = B + r N, X′ = B′(1 + rκ), composite
 *               Gauss–Legendre doubled until two levels agree to 1e-14,
 *               plus the corner arcs at joints where the tangent turns;
 *   fourier     the support-function form with h = p + r: the integrands are
 *               trigonometric polynomials of degree ≤ 4N, which the
 *               trapezoid rule on M > 4N points integrates exactly.
 * tests/unit/shape2d.c checks every kind against a fine polygon.
 * Seeds: 002 eqs. 2–5 (Fourier support function, convexity), 004 §2.5
 * (rounding: shrink / GJK / swell).
 */
#include "shape/shape2d.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"

#define SD_SHAPE2D_COOKIE 0x5D2D

/* ---- names --------------------------------------------------------------- */

static const char *const sd_shape2d_names[] = {
#define SD_X_NAME2(e, name, doc) name,
    SD_SHAPE2D_KINDS(SD_X_NAME2)
#undef SD_X_NAME2
};

const char *sd_shape2d_kind_name(int kind)
{
    return kind >= 0 && kind < SD_SHAPE2D_KIND_COUNT ? sd_shape2d_names[kind] : "unknown";
}

int sd_shape2d_kind_from_name(const char *name)
{
    for (int k = 0; name && k < SD_SHAPE2D_KIND_COUNT; ++k)
        if (strcmp(name, sd_shape2d_names[k]) == 0)
            return k;
    return -1;
}

sd_shape2d_desc sd_shape2d_desc_default(void)
{
    sd_shape2d_desc d;
    memset(&d, 0, sizeof d);
    d.kind = SD_SHAPE2D_CIRCLE;
    d.radius = SD_R(1.0);
    d.a = sd_v2(SD_R(1.0), SD_R(1.0));
    d.cookie = SD_SHAPE2D_COOKIE;
    return d;
}

/* ---- polygons and hulls ---------------------------------------------------- */

sd_real sd_polygon2d_area(const sd_vec2 *p, size_t n)
{
    /* the fan from p[0], not from the origin: an outline far from the
     * origin (a 2 cm circle at (1e8, 1e8)) would otherwise lose its area to
     * cancellation between products of size |p|² */
    sd_real s = SD_R(0.0);
    for (size_t i = 1; i + 1 < n; ++i)
        s += sd_v2_cross(sd_v2_sub(p[i], p[0]), sd_v2_sub(p[i + 1], p[0]));
    return SD_R(0.5) * s;
}

int sd_points2d_extent(const sd_vec2 *p, size_t n, sd_real *span, sd_real *reach)
{
    sd_real x0 = SD_R(0.0), x1 = SD_R(0.0), y0 = SD_R(0.0), y1 = SD_R(0.0), r = SD_R(0.0);
    for (size_t i = 0; i < n; ++i) {
        const sd_real x = p[i].x, y = p[i].y;
        if (!isfinite(x) || !isfinite(y))
            return 0;
        if (i == 0 || x < x0)
            x0 = x;
        if (i == 0 || x > x1)
            x1 = x;
        if (i == 0 || y < y0)
            y0 = y;
        if (i == 0 || y > y1)
            y1 = y;
        r = sd_max(r, sd_max(sd_fabs(x), sd_fabs(y)));
    }
    /* halves first: x1 - x0 overflows for coordinates of opposite sign near DBL_MAX */
    if (span)
        *span = SD_R(2.0) * sd_max(SD_R(0.5) * x1 - SD_R(0.5) * x0, SD_R(0.5) * y1 - SD_R(0.5) * y0);
    if (reach)
        *reach = r;
    return 1;
}

/* a hull point: q scaled into [-1, 1] (the orientation tests), p as given (the output) */
typedef struct sd_hull_pt {
    sd_vec2 q, p;
} sd_hull_pt;

static int sd_hull_less(const sd_hull_pt *a, const sd_hull_pt *b)
{
    return a->q.x < b->q.x || (a->q.x == b->q.x && a->q.y < b->q.y);
}

/* bottom-up merge sort of points by (x, y) (stable, no recursion); tmp holds n points */
static void sd_sort_points(sd_hull_pt *p, sd_hull_pt *tmp, size_t n)
{
    for (size_t w = 1; w < n; w *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * w) {
            size_t mid = lo + w < n ? lo + w : n, hi = lo + 2 * w < n ? lo + 2 * w : n;
            size_t i = lo, j = mid, k = lo;
            while (i < mid && j < hi)
                tmp[k++] = sd_hull_less(&p[j], &p[i]) ? p[j++] : p[i++];
            while (i < mid)
                tmp[k++] = p[i++];
            while (j < hi)
                tmp[k++] = p[j++];
        }
        memcpy(p, tmp, n * sizeof *p);
    }
}

/* keep c after the chain's last two points a, b only for a strict left turn.
 * The points are scaled into [-1, 1], so the products cannot overflow and
 * the test never sees NaN; `!(x > 0)` pops on NaN all the same, so that no
 * input can make the chain skip its pops and outgrow its buffer. */
static int sd_hull_keep(sd_vec2 a, sd_vec2 b, sd_vec2 c)
{
    return sd_v2_cross(sd_v2_sub(b, a), sd_v2_sub(c, a)) > SD_R(0.0);
}

size_t sd_hull2d(const sd_vec2 *pts, size_t n, sd_vec2 *hull, int *oom)
{
    if (oom)
        *oom = 0;
    sd_real span, reach;
    if (n < 3 || !sd_points2d_extent(pts, n, &span, &reach) || !(span > SD_R(0.0)))
        return 0; /* too few, not finite, or all one point */
    sd_hull_pt *p = sd_malloc(2 * n * sizeof *p);
    size_t *h = sd_malloc(2 * n * sizeof *h);
    if (!p || !h) {
        sd_free(p);
        sd_free(h);
        if (oom)
            *oom = 1;
        return 0;
    }
    /* Scaling by a power of two is exact (short of underflow), so the
     * orientation tests decide as they would unscaled, but their products
     * stay below 8: coordinates of 1e155 (whose squares overflow) or 1e-160
     * (whose squares underflow to 0) give the same hull as at unit size. */
    int e;
    (void)frexp((double)reach, &e);
    for (size_t i = 0; i < n; ++i) {
        p[i].p = pts[i];
        p[i].q = sd_v2((sd_real)ldexp((double)pts[i].x, -e), (sd_real)ldexp((double)pts[i].y, -e));
    }
    sd_sort_points(p, p + n, n);
    /* Andrew's monotone chain; collinear points are dropped. Each point is
     * pushed at most once per chain, so k < 2n: h (2n) never overflows. */
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
        while (k >= 2 && !sd_hull_keep(p[h[k - 2]].q, p[h[k - 1]].q, p[i].q))
            --k;
        h[k++] = i;
    }
    for (size_t i = n - 1, t = k + 1; i-- > 0;) {
        while (k >= t && !sd_hull_keep(p[h[k - 2]].q, p[h[k - 1]].q, p[i].q))
            --k;
        h[k++] = i;
    }
    size_t m = k > 1 ? k - 1 : 0; /* the last point repeats the first */
    if (m > n) /* a hull has each point at most once; cannot happen with the test above */
        m = 0;
    for (size_t j = 0; j < m; ++j) /* from the copy: hull may alias pts */
        hull[j] = p[h[j]].p;
    sd_free(p);
    sd_free(h);
    return m >= 3 ? m : 0;
}

/* ---- fan integrals ---------------------------------------------------------- */

typedef struct sd_fan {
    sd_real A, Sx, Sy, J; /* area, first moment, polar moment about the origin */
} sd_fan;

static const sd_real sd_gl8_x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                                    0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
static const sd_real sd_gl8_w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                                    0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

/* one quadrature node: point X with X × X′ = cr, weight w (in the parameter) */
static void sd_fan_node(sd_fan *f, sd_vec2 X, sd_real cr, sd_real w)
{
    const sd_real t = w * cr;
    f->A += SD_R(0.5) * t;
    f->Sx += X.x * t / SD_R(3.0);
    f->Sy += X.y * t / SD_R(3.0);
    f->J += SD_R(0.25) * sd_v2_norm2(X) * t;
}

/* straight piece a → b: the triangle (0, a, b) exactly */
static void sd_fan_segment(sd_fan *f, sd_vec2 a, sd_vec2 b)
{
    const sd_real T = SD_R(0.5) * sd_v2_cross(a, b);
    f->A += T;
    f->Sx += T * (a.x + b.x) / SD_R(3.0);
    f->Sy += T * (a.y + b.y) / SD_R(3.0);
    f->J += T * (sd_v2_norm2(a) + sd_v2_dot(a, b) + sd_v2_norm2(b)) / SD_R(6.0);
}

/* arc of radius r about c from angle p0 to p1 > p0: X = c + r u(φ),
 * X × X′ = r (c·u + r) */
static void sd_fan_arc(sd_fan *f, sd_vec2 c, sd_real r, sd_real p0, sd_real p1)
{
    if (!(p1 > p0) || !(r > SD_R(0.0)))
        return;
    const int pieces = 1 + (int)((p1 - p0) / (SD_PI / SD_R(8.0)));
    const sd_real h = (p1 - p0) / (sd_real)pieces;
    for (int k = 0; k < pieces; ++k) {
        const sd_real mid = p0 + ((sd_real)k + SD_R(0.5)) * h;
        for (int g = 0; g < 8; ++g) {
            const sd_real phi = mid + SD_R(0.5) * h * sd_gl8_x[g];
            const sd_vec2 u = sd_v2(sd_host_cos(phi), sd_host_sin(phi));
            sd_fan_node(f, sd_v2_madd(c, r, u), r * (sd_v2_dot(c, u) + r), SD_R(0.5) * h * sd_gl8_w[g]);
        }
    }
}

/* cubic Bézier derivative and second derivative */
static sd_vec2 sd_bez_d1(const sd_vec2 *P, sd_real t)
{
    const sd_real u = SD_R(1.0) - t;
    const sd_vec2 d0 = sd_v2_sub(P[1], P[0]), d1 = sd_v2_sub(P[2], P[1]), d2 = sd_v2_sub(P[3], P[2]);
    return sd_v2(SD_R(3.0) * (u * u * d0.x + SD_R(2.0) * u * t * d1.x + t * t * d2.x),
                 SD_R(3.0) * (u * u * d0.y + SD_R(2.0) * u * t * d1.y + t * t * d2.y));
}

static sd_vec2 sd_bez_d2(const sd_vec2 *P, sd_real t)
{
    const sd_real u = SD_R(1.0) - t;
    const sd_vec2 e0 = sd_v2_add(sd_v2_sub(P[2], sd_v2_scale(P[1], SD_R(2.0))), P[0]);
    const sd_vec2 e1 = sd_v2_add(sd_v2_sub(P[3], sd_v2_scale(P[2], SD_R(2.0))), P[1]);
    return sd_v2(SD_R(6.0) * (u * e0.x + t * e1.x), SD_R(6.0) * (u * e0.y + t * e1.y));
}

/* one cubic segment offset by r (CCW, outward normal N = −perp(T)),
 * `pieces` composite 8-point Gauss–Legendre panels */
static void sd_fan_bezier(sd_fan *f, const sd_vec2 *P, sd_real r, int pieces)
{
    const sd_real h = SD_R(1.0) / (sd_real)pieces;
    for (int k = 0; k < pieces; ++k) {
        const sd_real mid = ((sd_real)k + SD_R(0.5)) * h;
        for (int g = 0; g < 8; ++g) {
            const sd_real t = mid + SD_R(0.5) * h * sd_gl8_x[g];
            const sd_vec2 B = sd_bezier3_point(P, t), d1 = sd_bez_d1(P, t);
            sd_vec2 X = B, Xp = d1;
            if (r > SD_R(0.0)) {
                const sd_real s = sd_v2_norm(d1);
                if (!(s > SD_R(0.0)))
                    continue;
                const sd_vec2 N = sd_v2(d1.y / s, -d1.x / s);
                const sd_real kappa = sd_v2_cross(d1, sd_bez_d2(P, t)) / (s * s * s);
                X = sd_v2_madd(B, r, N);
                Xp = sd_v2_scale(d1, SD_R(1.0) + r * kappa);
            }
            sd_fan_node(f, X, sd_v2_cross(X, Xp), SD_R(0.5) * h * sd_gl8_w[g]);
        }
    }
}

/* The 4 control points of polybézier segment k (closing on P0). */
static void sd_bez_segment(const sd_real *v, uint32_t n, uint32_t k, sd_vec2 *P)
{
    for (uint32_t i = 0; i < 4; ++i) {
        const uint32_t j = (3u * k + i) % n;
        P[i] = sd_v2(v[2 * j], v[2 * j + 1]);
    }
}

/* tangent direction at the start (end = 0) or end (end = 1) of a segment:
 * the first control-point difference that does not vanish */
static sd_vec2 sd_bez_end_tangent(const sd_vec2 *P, int end)
{
    for (int k = 1; k <= 3; ++k) {
        const sd_vec2 t = end ? sd_v2_sub(P[3], P[3 - k]) : sd_v2_sub(P[k], P[0]);
        if (sd_v2_norm2(t) > SD_R(0.0))
            return t;
    }
    return sd_v2(SD_R(1.0), SD_R(0.0));
}

static sd_real sd_angle_of(sd_vec2 n)
{
    return sd_host_atan2(n.y, n.x);
}

/* CCW turn from direction a to b in [0, 2π) */
static sd_real sd_turn(sd_vec2 a, sd_vec2 b)
{
    sd_real t = sd_host_atan2(sd_v2_cross(a, b), sd_v2_dot(a, b));
    return t < SD_R(0.0) ? t + SD_R(2.0) * SD_PI : t;
}

static void sd_fan_polybezier(sd_fan *f, const sd_real *v, uint32_t n, sd_real r, int pieces)
{
    const uint32_t m = n / 3u;
    for (uint32_t k = 0; k < m; ++k) {
        sd_vec2 P[4];
        sd_bez_segment(v, n, k, P);
        sd_fan_bezier(f, P, r, pieces);
        if (r > SD_R(0.0)) { /* the corner arc at the segment's end, if the tangent turns */
            sd_vec2 Q[4];
            sd_bez_segment(v, n, (k + 1) % m, Q);
            const sd_vec2 tin = sd_bez_end_tangent(P, 1), tout = sd_bez_end_tangent(Q, 0);
            const sd_real turn = sd_host_atan2(sd_v2_cross(tin, tout), sd_v2_dot(tin, tout));
            if (turn > SD_R(0.0)) {
                const sd_real a0 = sd_angle_of(sd_v2(tin.y, -tin.x));
                sd_fan_arc(f, P[3], r, a0, a0 + turn);
            }
        }
    }
}

/* Support-function form over θ (trapezoid, M nodes): h = p + r, ρ = h + h″. */
static void sd_fan_support(sd_fan *f, const sd_shape2d *s, const sd_real *pool, int M)
{
    const sd_real w = SD_R(2.0) * SD_PI / (sd_real)M;
    const sd_real r = s->radius;
    for (int j = 0; j < M; ++j) {
        const sd_real th = w * (sd_real)j;
        const sd_real c = sd_host_cos(th), sn = sd_host_sin(th);
        sd_real p, dp, rho;
        if (s->kind == SD_SHAPE2D_ELLIPSE) {
            const sd_real a2 = s->a.x * s->a.x, b2 = s->a.y * s->a.y;
            p = sd_sqrt(a2 * c * c + b2 * sn * sn);
            dp = (b2 - a2) * sn * c / p;
            rho = a2 * b2 / (p * p * p);
        } else {
            sd_real ddp;
            sd_fourier_eval(pool + s->start, (int)((s->count - 1u) / 2u), c, sn, &p, &dp, &ddp);
            rho = p + ddp;
        }
        const sd_real h = p + r;
        const sd_vec2 X = sd_v2(h * c - dp * sn, h * sn + dp * c);
        sd_fan_node(f, X, h * (rho + r), w);
    }
}

static sd_fan sd_fan_of(const sd_shape2d *s, const sd_real *pool)
{
    sd_fan f = {0, 0, 0, 0};
    const sd_real r = s->radius;
    switch (s->kind) {
    case SD_SHAPE2D_CIRCLE:
        f.A = SD_PI * r * r;
        f.J = SD_R(0.5) * SD_PI * r * r * r * r;
        break;
    case SD_SHAPE2D_ELLIPSE:
        if (!(r > SD_R(0.0))) {
            f.A = SD_PI * s->a.x * s->a.y;
            f.J = SD_R(0.25) * f.A * (s->a.x * s->a.x + s->a.y * s->a.y);
        } else {
            sd_fan prev = {0, 0, 0, 0};
            for (int M = 256; M <= (1 << 18); M *= 2) {
                sd_fan cur = {0, 0, 0, 0};
                sd_fan_support(&cur, s, pool, M);
                f = cur;
                if (M > 256 && sd_fabs(cur.A - prev.A) <= SD_R(1e-15) * cur.A &&
                    sd_fabs(cur.J - prev.J) <= SD_R(1e-15) * cur.J)
                    break;
                prev = cur;
            }
            f.Sx = f.Sy = SD_R(0.0); /* symmetric about the centre */
        }
        break;
    case SD_SHAPE2D_POLYGON: {
        const sd_real *v = pool + s->start;
        const uint32_t n = s->count;
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t j = (i + 1) % n, h = (i + n - 1) % n;
            const sd_vec2 p = sd_v2(v[2 * i], v[2 * i + 1]), q = sd_v2(v[2 * j], v[2 * j + 1]);
            if (r > SD_R(0.0)) {
                const sd_vec2 o = sd_v2(v[2 * h], v[2 * h + 1]);
                const sd_vec2 ein = sd_v2_sub(p, o), eout = sd_v2_sub(q, p);
                const sd_vec2 nout = sd_v2_normalize(sd_v2(eout.y, -eout.x));
                const sd_real a0 = sd_angle_of(sd_v2(ein.y, -ein.x));
                sd_fan_arc(&f, p, r, a0, a0 + sd_turn(ein, eout));
                sd_fan_segment(&f, sd_v2_madd(p, r, nout), sd_v2_madd(q, r, nout));
            } else {
                sd_fan_segment(&f, p, q);
            }
        }
        break;
    }
    case SD_SHAPE2D_POLYBEZIER:
        if (!(r > SD_R(0.0))) {
            sd_fan_polybezier(&f, pool + s->start, s->count, r, 1);
        } else {
            sd_fan prev = {0, 0, 0, 0};
            for (int pieces = 4; pieces <= 4096; pieces *= 2) {
                sd_fan cur = {0, 0, 0, 0};
                sd_fan_polybezier(&cur, pool + s->start, s->count, r, pieces);
                f = cur;
                if (pieces > 4 && sd_fabs(cur.A - prev.A) <= SD_R(1e-14) * sd_fabs(cur.A) &&
                    sd_fabs(cur.J - prev.J) <= SD_R(1e-14) * sd_fabs(cur.J))
                    break;
                prev = cur;
            }
        }
        break;
    case SD_SHAPE2D_FOURIER:
        sd_fan_support(&f, s, pool, 8 * (int)s->count + 64);
        break;
    default:
        break;
    }
    return f;
}

void sd_shape2d_mass(const sd_shape2d *s, const sd_real *pool, sd_real *area, sd_vec2 *centroid, sd_real *polar)
{
    const sd_fan f = sd_fan_of(s, pool);
    const sd_vec2 c = f.A > SD_R(0.0) ? sd_v2(f.Sx / f.A, f.Sy / f.A) : sd_v2_zero();
    if (area)
        *area = f.A;
    if (centroid)
        *centroid = c;
    if (polar)
        *polar = f.J - f.A * sd_v2_norm2(c);
}

sd_real sd_fourier_min_curvature_radius(const sd_real *c, int n, int k, sd_real *bound_slack)
{
    sd_real lo = SD_R(1e300);
    for (int j = 0; j < k; ++j) {
        const sd_real th = SD_R(2.0) * SD_PI * (sd_real)j / (sd_real)k;
        sd_real p, ddp;
        sd_fourier_eval(c, n, sd_host_cos(th), sd_host_sin(th), &p, (sd_real *)0, &ddp);
        lo = sd_min(lo, p + ddp);
    }
    if (bound_slack) {
        /* |(p + p″)″| ≤ Σ k²(k² − 1)|c_k|; a minimum lies within Δ/2 of a node */
        sd_real m2 = SD_R(0.0);
        for (int i = 2; i <= n; ++i) {
            const sd_real ii = (sd_real)i;
            m2 += ii * ii * (ii * ii - SD_R(1.0)) * sd_sqrt(sd_sq(c[2 * i - 1]) + sd_sq(c[2 * i]));
        }
        const sd_real dth = SD_R(2.0) * SD_PI / (sd_real)k;
        *bound_slack = m2 * dth * dth / SD_R(8.0);
    }
    return lo;
}

/* ---- bound and width ----------------------------------------------------- */

static sd_real sd_shape2d_bound_of(const sd_shape2d *s, const sd_real *pool)
{
    const sd_real *v = pool + s->start;
    sd_real b = SD_R(0.0);
    switch (s->kind) {
    case SD_SHAPE2D_ELLIPSE:
        b = sd_max(s->a.x, s->a.y);
        break;
    case SD_SHAPE2D_POLYGON:
        for (uint32_t i = 0; i < s->count; ++i)
            b = sd_max(b, sd_sqrt(v[2 * i] * v[2 * i] + v[2 * i + 1] * v[2 * i + 1]));
        break;
    case SD_SHAPE2D_POLYBEZIER: {
        /* samples plus a Lipschitz margin: |B′| ≤ 3 max |P_{i+1} − P_i| */
        const int K = 8192;
        for (uint32_t k = 0; k < s->count / 3u; ++k) {
            sd_vec2 P[4];
            sd_bez_segment(v, s->count, k, P);
            sd_real lip = SD_R(0.0);
            for (int i = 0; i < 3; ++i)
                lip = sd_max(lip, SD_R(3.0) * sd_v2_norm(sd_v2_sub(P[i + 1], P[i])));
            for (int j = 0; j <= K; ++j)
                b = sd_max(b, sd_v2_norm(sd_bezier3_point(P, (sd_real)j / (sd_real)K)) + lip * SD_R(0.5) / (sd_real)K);
        }
        break;
    }
    case SD_SHAPE2D_FOURIER: {
        /* samples of |x(θ)| plus a Lipschitz margin: |x′| = p + p″ ≤ ½a0 + Σ (k² − 1)|c_k| */
        const int n = (int)((s->count - 1u) / 2u), K = 16384;
        sd_real lip = SD_R(0.5) * v[0];
        for (int i = 2; i <= n; ++i)
            lip += ((sd_real)(i * i) - SD_R(1.0)) * sd_sqrt(sd_sq(v[2 * i - 1]) + sd_sq(v[2 * i]));
        for (int j = 0; j < K; ++j) {
            const sd_real th = SD_R(2.0) * SD_PI * (sd_real)j / (sd_real)K;
            b = sd_max(b, sd_v2_norm(sd_shape2d_support_fourier(v, s->count, sd_v2(sd_host_cos(th), sd_host_sin(th)))));
        }
        b += lip * SD_PI / (sd_real)K;
        break;
    }
    default:
        break;
    }
    return b + s->radius;
}

/* width of the core across direction θ */
static sd_real sd_shape2d_width_at(const sd_shape2d *s, const sd_real *pool, sd_real th)
{
    const sd_vec2 d = sd_v2(sd_host_cos(th), sd_host_sin(th));
    return sd_v2_dot(d, sd_v2_sub(sd_shape2d_support_core(s, pool, d), sd_shape2d_support_core(s, pool, sd_v2_neg(d))));
}

static sd_real sd_shape2d_width_of(const sd_shape2d *s, const sd_real *pool)
{
    sd_real w = SD_R(1e300);
    if (s->kind == SD_SHAPE2D_CIRCLE)
        return SD_R(2.0) * s->radius;
    if (s->kind == SD_SHAPE2D_ELLIPSE)
        return SD_R(2.0) * (sd_min(s->a.x, s->a.y) + s->radius);
    if (s->kind == SD_SHAPE2D_POLYGON) {
        /* the minimum width of a convex polygon is attained at an edge normal */
        const sd_real *v = pool + s->start;
        for (uint32_t i = 0; i < s->count; ++i) {
            const uint32_t j = (i + 1) % s->count;
            const sd_vec2 e = sd_v2(v[2 * j] - v[2 * i], v[2 * j + 1] - v[2 * i + 1]);
            const sd_vec2 n = sd_v2_normalize(sd_v2(e.y, -e.x));
            const sd_vec2 far = sd_shape2d_support_core(s, pool, sd_v2_neg(n));
            w = sd_min(w, sd_v2_dot(n, sd_v2(v[2 * i], v[2 * i + 1])) - sd_v2_dot(n, far));
        }
        return w + SD_R(2.0) * s->radius;
    }
    /* directions over a half turn, then a ternary search about the best
     * (the width is smooth there for smooth outlines; a corner of a
     * polybézier only makes the search stop at a sample-accurate value) */
    const int K = 2048;
    sd_real best = SD_R(0.0);
    for (int j = 0; j < K; ++j) {
        const sd_real th = SD_PI * (sd_real)j / (sd_real)K;
        const sd_real wj = sd_shape2d_width_at(s, pool, th);
        if (wj < w) {
            w = wj;
            best = th;
        }
    }
    sd_real lo = best - SD_PI / (sd_real)K, hi = best + SD_PI / (sd_real)K;
    for (int it = 0; it < 60; ++it) {
        const sd_real m1 = lo + (hi - lo) / SD_R(3.0), m2 = hi - (hi - lo) / SD_R(3.0);
        if (sd_shape2d_width_at(s, pool, m1) < sd_shape2d_width_at(s, pool, m2))
            hi = m2;
        else
            lo = m1;
    }
    w = sd_min(w, sd_shape2d_width_at(s, pool, SD_R(0.5) * (lo + hi)));
    return w + SD_R(2.0) * s->radius;
}

/* ---- building a template ---------------------------------------------------- */

#define SD_FAIL2(key, ...) sd_error_set(err, SD_ERR_INPUT, "", 0, key, __VA_ARGS__)

static int sd_ok_pos(sd_real x)
{
    return isfinite(x) && x > SD_R(0.0);
}

/* A closed chain of cubic segments is convex and counter-clockwise when its
 * tangent turns only left and by 2π in all (sampled at 64 points per segment
 * and at the joints). */
static int sd_polybezier_convex(const sd_real *v, uint32_t n, sd_real *total)
{
    const uint32_t m = n / 3u;
    sd_vec2 prev = sd_v2_zero(), first = sd_v2_zero();
    int have = 0;
    sd_real turn = SD_R(0.0);
    for (uint32_t k = 0; k < m; ++k) {
        sd_vec2 P[4];
        sd_bez_segment(v, n, k, P);
        for (int j = 0; j <= 64; ++j) {
            sd_vec2 t = j == 0 ? sd_bez_end_tangent(P, 0)
                               : (j == 64 ? sd_bez_end_tangent(P, 1) : sd_bez_d1(P, (sd_real)j / SD_R(64.0)));
            if (!(sd_v2_norm2(t) > SD_R(0.0)))
                continue;
            if (have) {
                const sd_real c = sd_v2_cross(prev, t), d = sd_v2_dot(prev, t);
                const sd_real a = sd_host_atan2(c, d);
                if (a < SD_R(-1e-9)) {
                    *total = SD_R(-1.0); /* turns back (right) */
                    return 0;
                }
                turn += a;
            } else {
                first = t;
            }
            prev = t;
            have = 1;
        }
    }
    if (have)
        turn += sd_host_atan2(sd_v2_cross(prev, first), sd_v2_dot(prev, first));
    *total = turn;
    return sd_fabs(turn - SD_R(2.0) * SD_PI) <= SD_R(1e-6);
}

/* Sizes whose fourth power (the polar moment, m^4) over- or underflows in
 * double precision are refused here, with the size, rather than later as
 * "no area" or a NaN moment of inertia. */
#define SD_SHAPE2D_SPAN_MAX SD_R(1e70)
#define SD_SHAPE2D_SPAN_MIN SD_R(1e-70)

/* span and reach (as sd_points2d_extent) of n points stored x0, y0, x1, y1, ... */
static int sd_pool_extent(const sd_real *v, uint32_t n, sd_real *span, sd_real *reach)
{
    sd_real x0 = v[0], x1 = v[0], y0 = v[1], y1 = v[1], r = SD_R(0.0);
    for (uint32_t i = 0; i < n; ++i) {
        x0 = sd_min(x0, v[2 * i]);
        x1 = sd_max(x1, v[2 * i]);
        y0 = sd_min(y0, v[2 * i + 1]);
        y1 = sd_max(y1, v[2 * i + 1]);
        r = sd_max(r, sd_max(sd_fabs(v[2 * i]), sd_fabs(v[2 * i + 1])));
    }
    *span = sd_max(x1 - x0, y1 - y0);
    *reach = r;
    return 1;
}

static int sd_points_out_of_range(const sd_vec2 *p, size_t n, sd_error *err, const char *key, const char *what)
{
    sd_real span = SD_R(0.0);
    (void)sd_points2d_extent(p, n, &span, (sd_real *)0);
    if (span > SD_SHAPE2D_SPAN_MAX || (span > SD_R(0.0) && span < SD_SHAPE2D_SPAN_MIN)) {
        SD_FAIL2(key,
                 "the %s span %g m: its area and moment of inertia (m^2, m^4) would over- or underflow; "
                 "sizes are in metres and must lie between %g and %g m",
                 what, (double)span, (double)SD_SHAPE2D_SPAN_MIN, (double)SD_SHAPE2D_SPAN_MAX);
        return 1;
    }
    return 0;
}

sd_status sd_shape2d_make(const sd_shape2d_desc *desc, sd_shape2d *out, sd_real *pool, size_t pool_cap,
                          size_t *pool_used, sd_error *err)
{
    if (pool_used)
        *pool_used = 0;
    if (!desc || desc->cookie != SD_SHAPE2D_COOKIE)
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "sd_shape2d_desc not made by sd_shape2d_desc_default");
    sd_shape2d s;
    memset(&s, 0, sizeof s);
    s.kind = desc->kind;
    s.radius = desc->radius;
    size_t used = 0;
    if (s.kind != SD_SHAPE2D_CIRCLE && !(isfinite(s.radius) && s.radius >= SD_R(0.0)))
        return SD_FAIL2("rounding", "the rounding radius must be >= 0, got %g", (double)s.radius);
    switch (s.kind) {
    case SD_SHAPE2D_CIRCLE:
        if (!sd_ok_pos(s.radius))
            return SD_FAIL2("radius", "a circle needs a radius > 0, got %g", (double)s.radius);
        break;
    case SD_SHAPE2D_ELLIPSE:
        if (!sd_ok_pos(desc->a.x) || !sd_ok_pos(desc->a.y))
            return SD_FAIL2("axes", "an ellipse needs semi-axes > 0, got (%g, %g)", (double)desc->a.x,
                            (double)desc->a.y);
        s.a = desc->a;
        break;
    case SD_SHAPE2D_POLYGON: {
        const size_t n = desc->points ? desc->point_count : 0;
        if (n < 3)
            return SD_FAIL2("points", "a polygon needs at least 3 vertices, got %zu", n);
        if (n > SD_SHAPE2D_MAX_POINTS)
            return SD_FAIL2("points", "a polygon may have at most %d vertices, got %zu", SD_SHAPE2D_MAX_POINTS, n);
        for (size_t i = 0; i < n; ++i)
            if (!isfinite(desc->points[i].x) || !isfinite(desc->points[i].y))
                return SD_FAIL2("points", "vertex %zu is not a finite number", i + 1);
        if (sd_points_out_of_range(desc->points, n, err, "points", "polygon's vertices"))
            return SD_ERR_INPUT;
        sd_vec2 hull[SD_SHAPE2D_MAX_POINTS];
        int oom;
        const size_t h = sd_hull2d(desc->points, n, hull, &oom);
        if (oom)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory building a polygon template");
        if (h < 3)
            return SD_FAIL2("points", "the polygon's vertices are collinear (no area)");
        if (pool_cap < 2 * h)
            return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "pool too small for a %zu-vertex polygon", h);
        for (size_t i = 0; i < h; ++i) {
            pool[2 * i] = hull[i].x;
            pool[2 * i + 1] = hull[i].y;
        }
        s.count = (uint32_t)h;
        used = 2 * h;
        break;
    }
    case SD_SHAPE2D_POLYBEZIER: {
        const size_t n = desc->points ? desc->point_count : 0;
        if (n < 3 || n % 3 != 0)
            return SD_FAIL2("points",
                            "a polybezier needs 3m control points (m cubic segments, m >= 1), got %zu", n);
        if (n > SD_SHAPE2D_MAX_POINTS)
            return SD_FAIL2("points", "a polybezier may have at most %d control points, got %zu",
                            SD_SHAPE2D_MAX_POINTS, n);
        if (pool_cap < 2 * n)
            return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "pool too small for %zu control points", n);
        for (size_t i = 0; i < n; ++i) {
            if (!isfinite(desc->points[i].x) || !isfinite(desc->points[i].y))
                return SD_FAIL2("points", "control point %zu is not a finite number", i + 1);
            pool[2 * i] = desc->points[i].x;
            pool[2 * i + 1] = desc->points[i].y;
        }
        if (sd_points_out_of_range(desc->points, n, err, "points", "polybezier's control points"))
            return SD_ERR_INPUT;
        s.count = (uint32_t)n;
        used = 2 * n;
        sd_fan f = {0, 0, 0, 0};
        sd_fan_polybezier(&f, pool, s.count, SD_R(0.0), 1);
        if (f.A < SD_R(0.0)) { /* clockwise: reverse the chain (segment k ↔ m − 1 − k) */
            for (size_t i = 0; i < n; ++i) {
                const size_t j = (n - i) % n;
                pool[2 * i] = desc->points[j].x;
                pool[2 * i + 1] = desc->points[j].y;
            }
        }
        sd_real turn = SD_R(0.0);
        if (!(sd_fabs(f.A) > SD_R(0.0)))
            return SD_FAIL2("points", "the polybezier encloses no area");
        if (!sd_polybezier_convex(pool, s.count, &turn)) {
            if (turn < SD_R(0.0))
                return SD_FAIL2("points", "the polybezier is not convex: its tangent turns back somewhere "
                                                  "(a convex closed curve turns one way only)");
            return SD_FAIL2("points",
                            "the polybezier is not a simple convex closed curve: its tangent turns by %.6g rad in "
                            "all, not 2 pi",
                            (double)turn);
        }
        break;
    }
    case SD_SHAPE2D_FOURIER: {
        const int N = desc->order;
        if (N < 0 || N > SD_SHAPE2D_MAX_ORDER)
            return SD_FAIL2("order", "the Fourier order must be 0 .. %d, got %d", SD_SHAPE2D_MAX_ORDER, N);
        if (!desc->fs_a || (N > 0 && !desc->fs_b))
            return SD_FAIL2("coefficients", "a Fourier shape needs a_0 .. a_N and b_1 .. b_N");
        const size_t n = 2 * (size_t)N + 1;
        if (pool_cap < n)
            return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "pool too small for %zu coefficients", n);
        pool[0] = desc->fs_a[0];
        for (int k = 1; k <= N; ++k) {
            pool[2 * k - 1] = desc->fs_a[k];
            pool[2 * k] = desc->fs_b[k - 1];
        }
        for (size_t i = 0; i < n; ++i)
            if (!isfinite(pool[i]))
                return SD_FAIL2("coefficients", "the Fourier coefficients must be finite numbers");
        if (!sd_ok_pos(pool[0]))
            return SD_FAIL2("coefficients", "a_0 must be > 0 (twice the mean of the support function), got %g",
                            (double)pool[0]);
        s.count = (uint32_t)n;
        used = n;
        /* seed 002 eq. 5 on a fine grid; a dip of 1e-9 of the mean radius is
         * rounding of printed coefficients, not a concavity */
        const sd_real lo = sd_fourier_min_curvature_radius(pool, N, 64 * N + 1024, (sd_real *)0);
        if (lo < SD_R(-1e-9) * SD_R(0.5) * pool[0])
            return SD_FAIL2("coefficients",
                            "the Fourier series is not convex: p + p'' reaches %.6g < 0 (eq. 5 of [Huang 2021]); "
                            "reduce the higher-order coefficients (shapedem shape fit-fourier does this)",
                            (double)lo);
        break;
    }
    default:
        return SD_FAIL2("type", "unknown 2D shape kind %d", s.kind);
    }

    /* mass properties in the given frame, then move to the centroid. A
     * polygon given far from the origin (vertices around (1e5, 1e5) for a
     * 1 cm body) would lose its digits to the fan from the origin — its
     * polar moment came out negative — so such a shape is integrated about
     * its first point instead. Only then: a shape near the origin keeps the
     * bits of its template (chaotic packings such as the biaxial validation
     * would otherwise change run to run of the code, not of the physics). */
    sd_vec2 p0 = sd_v2_zero();
    sd_real span = SD_R(0.0), reach = SD_R(0.0);
    if ((s.kind == SD_SHAPE2D_POLYGON || s.kind == SD_SHAPE2D_POLYBEZIER) &&
        sd_pool_extent(pool, s.count, &span, &reach) && reach > SD_R(4.0) * span) {
        p0 = sd_v2(pool[0], pool[1]);
        for (uint32_t i = 0; i < s.count; ++i) {
            pool[2 * i] -= p0.x;
            pool[2 * i + 1] -= p0.y;
        }
    }
    sd_real area, polar;
    sd_vec2 c;
    sd_shape2d_mass(&s, pool, &area, &c, &polar);
    if (!isfinite(area) || !isfinite(polar)) {
        /* the key the size came from */
        const char *size_key = s.kind == SD_SHAPE2D_ELLIPSE ? "axes"
                               : s.kind == SD_SHAPE2D_FOURIER ? "fourier_a"
                               : s.kind == SD_SHAPE2D_CIRCLE  ? "radius"
                                                              : "points";
        return SD_FAIL2(size_key, "the %s's area or moment of inertia (m^2, m^4) overflows: sizes are in metres",
                        sd_shape2d_kind_name(s.kind));
    }
    if (!(area > SD_R(0.0)))
        return SD_FAIL2("type", "the %s has no area", sd_shape2d_kind_name(s.kind));
    s.given_com = sd_v2_add(p0, c);
    if (s.kind == SD_SHAPE2D_POLYGON || s.kind == SD_SHAPE2D_POLYBEZIER) {
        for (uint32_t i = 0; i < s.count; ++i) {
            pool[2 * i] -= c.x;
            pool[2 * i + 1] -= c.y;
        }
    } else if (s.kind == SD_SHAPE2D_FOURIER && s.count >= 3) {
        /* p about c: p(θ) − c·n(θ), i.e. a1 −= cx, b1 −= cy */
        pool[1] -= c.x;
        pool[2] -= c.y;
    } else if (s.kind == SD_SHAPE2D_FOURIER) {
        s.given_com = sd_v2_zero(); /* order 0 is a circle about the origin */
    }
    s.area = area;
    s.inertia = polar;
    s.bound = sd_shape2d_bound_of(&s, pool);
    s.min_size = sd_shape2d_width_of(&s, pool);
    s.eq_radius = sd_sqrt(area / SD_PI);
    s.start = 0;
    *out = s;
    if (pool_used)
        *pool_used = used;
    return SD_OK;
}
