/* shape2d.c — planar shape templates (shape/shape2d.h): support functions,
 * mass properties, bound and width, validation.
 *
 *   - mass properties of every kind, sharp and rounded, against the fine
 *     polygon of its boundary (support points in K and 2K directions,
 *     Richardson-extrapolated: the chord error falls as 1/K²), and the
 *     closed forms of the circle and the sharp ellipse;
 *   - templates are stored about their centroid (the stored shape's first
 *     moment is zero) and given_com says where the centroid was;
 *   - support points maximise d·x over the fine boundary; the ellipse's is
 *     analytic; the polybézier's lies on the curve (not on its control
 *     polygon); the posed (world) support is the rotated body support;
 *   - bound ≥ every boundary point's distance and tight; min_size against
 *     the fine polygon's width;
 *   - bad descs are refused with a message (non-convex polybézier and
 *     Fourier series, collinear polygon, bad radii).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "shape/shape2d.h"
#include "test.h"

static sd_real pool[4096];
static size_t top;

static sd_status make(sd_shape2d_desc *d, sd_shape2d *s, sd_error *err)
{
    size_t used = 0;
    sd_status st = sd_shape2d_make(d, s, pool + top, sizeof pool / sizeof pool[0] - top, &used, err);
    if (st == SD_OK) {
        s->start = (uint32_t)top;
        top += used;
    }
    return st;
}

/* area, centroid and polar moment about the centroid of the fine polygon
 * of support points of the swept shape in K directions */
static void poly_mass(const sd_shape2d *s, int K, double *A, sd_vec2 *c, double *J)
{
    double a = 0, sx = 0, sy = 0, j = 0;
    sd_vec2 prev = sd_shape2d_support(s, pool, sd_v2(1, 0));
    for (int k = 1; k <= K; ++k) {
        double th = 2 * SD_PI_D * k / K;
        sd_vec2 p = sd_shape2d_support(s, pool, sd_v2(cos(th), sin(th)));
        double T = 0.5 * sd_v2_cross(prev, p);
        a += T;
        sx += T * (prev.x + p.x) / 3;
        sy += T * (prev.y + p.y) / 3;
        j += T * (sd_v2_norm2(prev) + sd_v2_dot(prev, p) + sd_v2_norm2(p)) / 6;
        prev = p;
    }
    *A = a;
    *c = sd_v2(sx / a, sy / a);
    *J = j - a * sd_v2_norm2(*c);
}

static void check_mass(const char *name, const sd_shape2d *s, double rel)
{
    double A1, A2, J1, J2;
    sd_vec2 c1, c2;
    poly_mass(s, 20000, &A1, &c1, &J1);
    poly_mass(s, 40000, &A2, &c2, &J2);
    double A = (4 * A2 - A1) / 3, J = (4 * J2 - J1) / 3;
    char label[128];
    snprintf(label, sizeof label, "%s: area vs fine polygon", name);
    CHECK_REL(label, s->area, A, rel);
    snprintf(label, sizeof label, "%s: polar moment vs fine polygon", name);
    CHECK_REL(label, s->inertia, J, rel);
    snprintf(label, sizeof label, "%s: centroid at the origin / bound", name);
    CHECK_NEAR(label, sd_v2_norm(c2) / s->bound, 0, 1e-9);
    /* the stored shape's own mass properties: centroid zero, same moments */
    double a;
    sd_vec2 c;
    double jj;
    sd_shape2d_mass(s, pool, &a, &c, &jj);
    snprintf(label, sizeof label, "%s: stored shape's centroid / bound", name);
    CHECK_NEAR(label, sd_v2_norm(c) / s->bound, 0, 1e-12);
    /* bound: no boundary point beyond it, and tight */
    double far = 0;
    for (int k = 0; k < 20000; ++k) {
        double th = 2 * SD_PI_D * k / 20000;
        far = fmax(far, sd_v2_norm(sd_shape2d_support(s, pool, sd_v2(cos(th), sin(th)))));
    }
    snprintf(label, sizeof label, "%s: boundary beyond the bound / bound", name);
    CHECK_NEAR(label, fmax(0, far - s->bound) / far, 0, 1e-14);
    snprintf(label, sizeof label, "%s: bound vs farthest boundary point", name);
    CHECK_REL(label, s->bound, far, 1e-3);
    /* min_size vs the polygon's width over 20000 directions */
    double w = 1e300;
    for (int k = 0; k < 10000; ++k) {
        double th = SD_PI_D * k / 10000;
        sd_vec2 d = sd_v2(cos(th), sin(th));
        w = fmin(w, sd_v2_dot(d, sd_v2_sub(sd_shape2d_support(s, pool, d), sd_shape2d_support(s, pool, sd_v2_neg(d)))));
    }
    /* the sampled width is an upper bound: first-order close at a polygon's
     * edge normal (a kink), second-order on smooth outlines */
    snprintf(label, sizeof label, "%s: min_size vs fine width", name);
    CHECK_REL(label, s->min_size, w, s->kind == SD_SHAPE2D_POLYGON ? 1e-4 : 1e-5);
    CHECK(s->min_size <= w * (1 + 1e-12) || s->kind != SD_SHAPE2D_POLYGON);
    CHECK_REL("eq_radius^2 pi = area", SD_PI_D * s->eq_radius * s->eq_radius, s->area, 1e-14);
}

/* support points maximise d·x over the boundary samples (a support point
 * must be at least as far along d as any boundary point) */
static void check_support(const char *name, const sd_shape2d *s)
{
    static sd_vec2 bd[8192];
    for (int k = 0; k < 8192; ++k) {
        double th = 2 * SD_PI_D * k / 8192;
        bd[k] = sd_shape2d_support(s, pool, sd_v2(cos(th), sin(th)));
    }
    double worst = 0;
    for (int t = 0; t < 500; ++t) {
        double th = 0.0123 + 2 * SD_PI_D * t / 500;
        sd_vec2 d = sd_v2(cos(th), sin(th));
        double best = -1e300;
        for (int k = 0; k < 8192; ++k)
            best = fmax(best, sd_v2_dot(d, bd[k]));
        worst = fmax(worst, best - sd_v2_dot(d, sd_shape2d_support(s, pool, sd_v2_scale(d, 3.7))));
    }
    char label[128];
    snprintf(label, sizeof label, "%s: support beaten by a boundary point / bound", name);
    CHECK_NEAR(label, worst / s->bound, 0, 1e-14);
}

int main(void)
{
    sd_error err;
    sd_shape2d s;

    /* circle */
    sd_shape2d_desc d = sd_shape2d_desc_default();
    d.kind = SD_SHAPE2D_CIRCLE;
    d.radius = 0.025;
    CHECK(make(&d, &s, &err) == SD_OK);
    CHECK_REL("circle area", s.area, SD_PI_D * 0.025 * 0.025, 1e-15);
    CHECK_REL("circle polar moment pi r^4 / 2", s.inertia, SD_PI_D * pow(0.025, 4) / 2, 1e-15);
    CHECK_NEAR("circle bound", s.bound, 0.025, 0);
    check_mass("circle", &s, 1e-9);

    /* ellipse: closed forms when sharp, quadrature when rounded */
    d = sd_shape2d_desc_default();
    d.kind = SD_SHAPE2D_ELLIPSE;
    d.radius = 0;
    d.a = sd_v2(0.04, 0.015);
    CHECK(make(&d, &s, &err) == SD_OK);
    CHECK_REL("ellipse area pi a b", s.area, SD_PI_D * 0.04 * 0.015, 1e-15);
    CHECK_REL("ellipse polar moment", s.inertia, SD_PI_D * 0.04 * 0.015 * (0.04 * 0.04 + 0.015 * 0.015) / 4, 1e-15);
    check_mass("ellipse", &s, 1e-9);
    check_support("ellipse", &s);
    {
        double th = 0.7, worst = 0;
        for (int k = 0; k < 100; ++k, th += 0.06) {
            sd_vec2 p = sd_shape2d_support(&s, pool, sd_v2(cos(th), sin(th)));
            worst = fmax(worst, fabs(p.x * p.x / (0.04 * 0.04) + p.y * p.y / (0.015 * 0.015) - 1));
            /* the normal of the ellipse at p is d */
            sd_vec2 n = sd_v2_normalize(sd_v2(p.x / (0.04 * 0.04), p.y / (0.015 * 0.015)));
            worst = fmax(worst, fabs(sd_v2_cross(n, sd_v2(cos(th), sin(th)))));
        }
        CHECK_NEAR("ellipse support on the ellipse, normal along d", worst, 0, 1e-14);
    }
    d.radius = 0.003;
    CHECK(make(&d, &s, &err) == SD_OK);
    check_mass("rounded ellipse", &s, 1e-9);

    /* polygon: hull of the points, exact mass, rounded too */
    sd_vec2 pts[7] = {{0.03, 0.0},     {0.01, 0.02},   {-0.02, 0.015}, {0.0, 0.0},
                      {-0.025, -0.01}, {0.005, -0.02}, {0.01, 0.005}};
    d = sd_shape2d_desc_default();
    d.kind = SD_SHAPE2D_POLYGON;
    d.radius = 0;
    d.points = pts;
    d.point_count = 7;
    CHECK(make(&d, &s, &err) == SD_OK);
    CHECK_NEAR("polygon keeps its 5 hull vertices", s.count, 5, 0);
    check_mass("polygon", &s, 1e-9);
    check_support("polygon", &s);
    {
        /* a unit square given off-centre: area 1, J = 1/6, given_com = its centre */
        sd_vec2 sq[4] = {{2, 3}, {3, 3}, {3, 4}, {2, 4}};
        sd_shape2d_desc q = d;
        q.points = sq;
        q.point_count = 4;
        sd_shape2d t;
        CHECK(make(&q, &t, &err) == SD_OK);
        CHECK_NEAR("unit square area", t.area, 1, 1e-15);
        CHECK_NEAR("unit square polar moment 1/6", t.inertia, 1.0 / 6, 1e-14);
        CHECK_NEAR("unit square given_com x", t.given_com.x, 2.5, 1e-15);
        CHECK_NEAR("unit square given_com y", t.given_com.y, 3.5, 1e-15);
        CHECK_NEAR("unit square min_size", t.min_size, 1, 1e-15);
        CHECK_NEAR("unit square bound", t.bound, sqrt(0.5), 1e-15);
        /* rounded square: A = 1 + 4r + pi r^2 */
        q.radius = 0.1;
        CHECK(make(&q, &t, &err) == SD_OK);
        CHECK_NEAR("rounded unit square area 1 + 4r + pi r^2", t.area, 1 + 0.4 + SD_PI_D * 0.01, 1e-14);
        CHECK_NEAR("rounded unit square min_size", t.min_size, 1.2, 1e-15);
    }
    d.radius = 0.004;
    CHECK(make(&d, &s, &err) == SD_OK);
    check_mass("rounded polygon", &s, 1e-9);

    /* polybézier: a stretched 4-arc circle, and a lens with corners */
    const double k = 0.5522847498;
    sd_vec2 bz[12] = {{0.045, 0},          {0.045, 0.03 * k},  {0.045 * k, 0.03},  {0, 0.03},
                      {-0.045 * k, 0.03},  {-0.045, 0.03 * k}, {-0.045, 0},        {-0.045, -0.03 * k},
                      {-0.045 * k, -0.03}, {0, -0.03},         {0.045 * k, -0.03}, {0.045, -0.03 * k}};
    d = sd_shape2d_desc_default();
    d.kind = SD_SHAPE2D_POLYBEZIER;
    d.radius = 0;
    d.points = bz;
    d.point_count = 12;
    CHECK(make(&d, &s, &err) == SD_OK);
    check_mass("polybezier", &s, 1e-9);
    check_support("polybezier", &s);
    {
        /* the support lies on the curve: at d = (1, 1)/√2 the control polygon
         * would give (0.045, 0.0166) or (0.0249, 0.03), the curve a point
         * strictly inside their hull */
        sd_vec2 p = sd_shape2d_support(&s, pool, sd_v2(1, 1));
        sd_vec2 q1 = sd_v2(0.045, 0.03 * k), q2 = sd_v2(0.045 * k, 0.03);
        CHECK(p.x + p.y < fmax(q1.x + q1.y, q2.x + q2.y) - 1e-4);
        /* and it is on the curve: solve B(t) = p for t on the first segment */
        double best = 1e300, bt = 0;
        sd_vec2 P[4] = {bz[0], bz[1], bz[2], bz[3]};
        for (int i = 0; i <= 20000; ++i) {
            double dd = sd_v2_norm(sd_v2_sub(sd_bezier3_point(P, i / 20000.0), p));
            if (dd < best) {
                best = dd;
                bt = i / 20000.0;
            }
        }
        /* refine t by ternary search around the best sample */
        double lo = fmax(0, bt - 1e-4), hi = fmin(1, bt + 1e-4);
        for (int it = 0; it < 200; ++it) {
            double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
            if (sd_v2_norm(sd_v2_sub(sd_bezier3_point(P, m1), p)) < sd_v2_norm(sd_v2_sub(sd_bezier3_point(P, m2), p)))
                hi = m2;
            else
                lo = m1;
        }
        best = sd_v2_norm(sd_v2_sub(sd_bezier3_point(P, 0.5 * (lo + hi)), p));
        CHECK_NEAR("polybezier support point on the curve (m)", best, 0, 1e-9);
    }
    d.radius = 0.002;
    CHECK(make(&d, &s, &err) == SD_OK);
    check_mass("rounded polybezier", &s, 1e-9);
    sd_vec2 lens[6] = {{-0.04, 0}, {-0.02, 0.025}, {0.02, 0.025}, {0.04, 0}, {0.02, -0.015}, {-0.02, -0.015}};
    d.points = lens;
    d.point_count = 6;
    d.radius = 0;
    CHECK(make(&d, &s, &err) == SD_OK);
    check_mass("polybezier lens", &s, 1e-9);
    check_support("polybezier lens", &s);
    d.radius = 0.003;
    CHECK(make(&d, &s, &err) == SD_OK);
    check_mass("rounded polybezier lens", &s, 1e-9);
    {
        /* clockwise input is accepted (reversed): same area */
        sd_vec2 cw[6];
        for (int i = 0; i < 6; ++i)
            cw[i] = lens[(6 - i) % 6];
        sd_shape2d_desc q = d;
        q.points = cw;
        sd_shape2d t;
        CHECK(make(&q, &t, &err) == SD_OK);
        CHECK_REL("clockwise polybezier: same area", t.area, s.area, 1e-14);
    }

    /* Fourier: exact trapezoid integration */
    sd_real fa[5] = {0.06, 0.002, 0.003, 0.0008, 0.0003}, fb[4] = {-0.001, 0.001, 0.0012, 0.0};
    d = sd_shape2d_desc_default();
    d.kind = SD_SHAPE2D_FOURIER;
    d.radius = 0;
    d.order = 4;
    d.fs_a = fa;
    d.fs_b = fb;
    CHECK(make(&d, &s, &err) == SD_OK);
    check_mass("fourier", &s, 1e-9);
    check_support("fourier", &s);
    {
        /* area from the support function, A = ½∫(p² − p′²) = π(a0/2)² − (π/2)Σ(n² − 1)(a_n² + b_n²)
         * (the n = 1 pair only moves the shape) */
        double A = SD_PI_D * 0.03 * 0.03;
        for (int n = 2; n <= 4; ++n)
            A -= SD_PI_D / 2 * (n * n - 1) * (fa[n] * fa[n] + fb[n - 1] * fb[n - 1]);
        CHECK_REL("fourier area, closed form", s.area, A, 1e-13);
    }
    {
        /* even harmonics only, plus the (a1, b1) pair: a centrally symmetric
         * body moved by (a1, b1), so its centroid is (a1, b1) */
        sd_real ea[5] = {0.06, 0.002, 0.003, 0.0, 0.0003}, eb[4] = {-0.001, 0.001, 0.0, 0.0004};
        sd_shape2d_desc q = d;
        q.fs_a = ea;
        q.fs_b = eb;
        sd_shape2d t;
        CHECK(make(&q, &t, &err) == SD_OK);
        CHECK_NEAR("symmetric fourier given_com x = a1", t.given_com.x, 0.002, 1e-15);
        CHECK_NEAR("symmetric fourier given_com y = b1", t.given_com.y, -0.001, 1e-15);
        CHECK_NEAR("stored a1 after the move", pool[t.start + 1], 0, 1e-18);
    }
    d.radius = 0.002;
    CHECK(make(&d, &s, &err) == SD_OK);
    check_mass("rounded fourier", &s, 1e-9);

    /* posed support = rotated body support + position */
    {
        sd_convex2d c = {&s, pool, sd_v2(1.5, -2), 0.9};
        sd_vec2 dir = sd_v2(0.3, -0.8);
        sd_vec2 w = sd_convex2d_support(&c, dir);
        sd_vec2 b = sd_v2_add(c.x, sd_v2_rot(sd_shape2d_support(&s, pool, sd_v2_rot(dir, -0.9)), 0.9));
        CHECK_NEAR("posed support vs body support", sd_v2_norm(sd_v2_sub(w, b)), 0, 1e-15);
        sd_vec2 z = sd_convex2d_support(&c, sd_v2(0, 0));
        CHECK(isfinite(z.x) && isfinite(z.y));
    }

    /* ---- bad descs --------------------------------------------------------------- */
    d = sd_shape2d_desc_default();
    d.kind = SD_SHAPE2D_CIRCLE;
    d.radius = -1;
    CHECK(make(&d, &s, &err) == SD_ERR_INPUT);
    printf("negative circle: %s: %s\n", err.key, err.msg);
    d.kind = SD_SHAPE2D_ELLIPSE;
    d.radius = 0;
    d.a = sd_v2(0.01, 0);
    CHECK(make(&d, &s, &err) == SD_ERR_INPUT);
    d = sd_shape2d_desc_default();
    d.kind = SD_SHAPE2D_POLYGON;
    d.radius = 0;
    sd_vec2 col[3] = {{0, 0}, {1, 1}, {2, 2}};
    d.points = col;
    d.point_count = 3;
    CHECK(make(&d, &s, &err) == SD_ERR_INPUT);
    printf("collinear polygon: %s: %s\n", err.key, err.msg);
    {
        /* a non-convex polybézier: a kidney */
        sd_vec2 kid[6] = {{-0.04, 0}, {-0.02, 0.025}, {0.02, 0.025}, {0.04, 0}, {0.02, 0.01}, {-0.02, 0.01}};
        d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_POLYBEZIER;
        d.radius = 0;
        d.points = kid;
        d.point_count = 6;
        CHECK(make(&d, &s, &err) == SD_ERR_INPUT);
        printf("non-convex polybezier: %s: %s\n", err.key, err.msg);
        d.point_count = 5;
        CHECK(make(&d, &s, &err) == SD_ERR_INPUT);
    }
    {
        sd_real ba[4] = {2.0, 0, 0, 0.2}, bb[3] = {0, 0, 0}; /* p + p″ = 1 − 1.6 cos 3θ */
        d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_FOURIER;
        d.radius = 0;
        d.order = 3;
        d.fs_a = ba;
        d.fs_b = bb;
        CHECK(make(&d, &s, &err) == SD_ERR_INPUT);
        printf("non-convex Fourier: %s: %s\n", err.key, err.msg);
        ba[3] = 0.125; /* exactly at the bound: min p + p″ = 0, accepted */
        CHECK(make(&d, &s, &err) == SD_OK);
        ba[0] = -1;
        CHECK(make(&d, &s, &err) == SD_ERR_INPUT);
    }

    /* names */
    for (int kk = 0; kk < SD_SHAPE2D_KIND_COUNT; ++kk)
        CHECK(sd_shape2d_kind_from_name(sd_shape2d_kind_name(kk)) == kk);
    CHECK(sd_shape2d_kind_from_name("sphere") == -1);
    CHECK(sd_shape2d_pool_reals(SD_SHAPE2D_POLYGON, 5) == 10 && sd_shape2d_pool_reals(SD_SHAPE2D_FOURIER, 17) == 17);
    return sd_test_summary();
}
