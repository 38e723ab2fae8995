/* gjk2d.c — 2D GJK / EPA / sd_contact2d_convex against independent
 * references (notes/algorithms.md §H test 33; issue 5 "2D GJK/EPA against
 * brute-force polygon distance/penetration").
 *
 * References:
 *   - circle–circle: the analytic |x_b − x_a| − ra − rb, normal, point;
 *   - Fourier order 0 (p = R) against the same analytic circle law;
 *   - every other pair (circle, ellipse, polygon, polybézier, Fourier, sharp
 *     and rounded, in all combinations): each body replaced by a polygon of
 *     4096 of its boundary points, the Minkowski difference of the two
 *     polygons built by the edge merge, then the distance from the origin to
 *     it (apart) or the distance to its nearest edge (overlap) — no GJK and
 *     no support function in the reference; a few pairs are also checked by
 *     the O(n·m) vertex–edge brute force;
 *   - aligned squares, where GJK ends on a segment through the origin
 *     (the OpenRAL #215 case in 2D) and exact touching.
 * The polygons are inscribed, so they are smaller than the bodies by at most
 * R(1 − cos(π/4096)) ≈ 3e-7 R: tolerances are 2e-6 L for lengths and 3e-3 rad
 * for normals (the nearest polygon edge may tilt by half the angular step).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "geom/gjk2d.h"
#include "shape/shape2d.h"
#include "test.h"

#define NPOLY 4096

static sd_real pool[8192];
static size_t pool_top;

static sd_shape2d make(sd_shape2d_desc *d)
{
    sd_shape2d s;
    sd_error err;
    size_t used;
    sd_status st = sd_shape2d_make(d, &s, pool + pool_top, sizeof pool / sizeof pool[0] - pool_top, &used, &err);
    sd_test_require(st == SD_OK, "sd_shape2d_make", &err);
    s.start = (uint32_t)pool_top;
    pool_top += used;
    return s;
}

/* boundary polygon of a posed swept body: support points in K uniform
 * directions, consecutive duplicates (polygon vertices) dropped */
static int body_polygon(const sd_convex2d *c, sd_vec2 *out, int K)
{
    int n = 0;
    for (int j = 0; j < K; ++j) {
        double th = 2.0 * SD_PI_D * j / K;
        sd_vec2 p = sd_convex2d_support(c, sd_v2(cos(th), sin(th)));
        if (n == 0 || sd_v2_norm(sd_v2_sub(p, out[n - 1])) > 1e-13)
            out[n++] = p;
    }
    while (n > 1 && sd_v2_norm(sd_v2_sub(out[0], out[n - 1])) <= 1e-13)
        --n;
    return n;
}

static int lowest(const sd_vec2 *p, int n)
{
    int b = 0;
    for (int i = 1; i < n; ++i)
        if (p[i].y < p[b].y || (p[i].y == p[b].y && p[i].x < p[b].x))
            b = i;
    return b;
}

/* Minkowski sum of convex CCW polygons P and R by the edge merge */
static int minkowski(const sd_vec2 *P, int n, const sd_vec2 *R, int m, sd_vec2 *out)
{
    int i0 = lowest(P, n), j0 = lowest(R, m), i = 0, j = 0, k = 0;
    while (i < n || j < m) {
        sd_vec2 a = P[(i0 + i) % n], b = R[(j0 + j) % m];
        out[k++] = sd_v2_add(a, b);
        sd_vec2 ea = sd_v2_sub(P[(i0 + i + 1) % n], a), eb = sd_v2_sub(R[(j0 + j + 1) % m], b);
        double cr = sd_v2_cross(ea, eb);
        if (j >= m || (i < n && cr > 0))
            ++i;
        else if (i >= n || cr < 0)
            ++j;
        else {
            ++i;
            ++j;
        }
    }
    return k;
}

typedef struct ref_result {
    int inside;
    double dist; /* distance from the origin to K (apart) or depth (inside) */
    sd_vec2 n;   /* from a into b */
} ref_result;

/* origin vs the convex CCW polygon K = A − B */
static ref_result origin_vs(const sd_vec2 *K, int k)
{
    ref_result r;
    int inside = 1;
    double best_in = 1e300, best_out = 1e300;
    sd_vec2 n_in = sd_v2(1, 0), p_out = sd_v2(0, 0);
    for (int i = 0; i < k; ++i) {
        sd_vec2 p = K[i], q = K[(i + 1) % k], e = sd_v2_sub(q, p);
        double len = sd_v2_norm(e);
        if (len <= 0)
            continue;
        sd_vec2 n = sd_v2(e.y / len, -e.x / len);
        double d = sd_v2_dot(n, p); /* > 0: origin on the inner side */
        if (d < 0)
            inside = 0;
        if (d < best_in) {
            best_in = d;
            n_in = n;
        }
        double t = sd_gjk2d_segment_t(p, q);
        sd_vec2 c = sd_v2_madd(p, t, e);
        if (sd_v2_norm(c) < best_out) {
            best_out = sd_v2_norm(c);
            p_out = c;
        }
    }
    r.inside = inside;
    if (inside) {
        r.dist = best_in;
        r.n = n_in; /* outward normal of K: from a into b */
    } else {
        r.dist = best_out;
        r.n = sd_v2_normalize(sd_v2_neg(p_out));
    }
    return r;
}

static sd_vec2 polyA[NPOLY], polyB[NPOLY], negB[NPOLY], K[2 * NPOLY + 4];

static ref_result reference(const sd_convex2d *a, const sd_convex2d *b)
{
    int n = body_polygon(a, polyA, NPOLY), m = body_polygon(b, polyB, NPOLY);
    for (int i = 0; i < m; ++i)
        negB[i] = sd_v2_neg(polyB[i]);
    int k = minkowski(polyA, n, negB, m, K);
    return origin_vs(K, k);
}

/* O(n·m) vertex–edge brute force (separated polygons only) */
static double brute_distance(const sd_convex2d *a, const sd_convex2d *b, int K_)
{
    static sd_vec2 pa[1024], pb[1024];
    int n = body_polygon(a, pa, K_), m = body_polygon(b, pb, K_);
    double best = 1e300;
    for (int pass = 0; pass < 2; ++pass) {
        const sd_vec2 *P = pass ? pb : pa, *Q = pass ? pa : pb;
        int np = pass ? m : n, nq = pass ? n : m;
        for (int i = 0; i < np; ++i)
            for (int j = 0; j < nq; ++j) {
                sd_vec2 q0 = sd_v2_sub(Q[j], P[i]), q1 = sd_v2_sub(Q[(j + 1) % nq], P[i]);
                double t = sd_gjk2d_segment_t(q0, q1);
                double d = sd_v2_norm(sd_v2_madd(q0, t, sd_v2_sub(q1, q0)));
                if (d < best)
                    best = d;
            }
    }
    return best;
}

static double angle_between(sd_vec2 u, sd_vec2 v)
{
    return fabs(atan2(sd_v2_cross(u, v), sd_v2_dot(u, v)));
}

int main(void)
{
    sd_error err;
    (void)err;
    sd_rng rng = sd_rng_seed(20261125);

    /* ---- circle–circle: exact ------------------------------------------- */
    {
        sd_shape2d_desc d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_CIRCLE;
        d.radius = 0.02;
        sd_shape2d c1 = make(&d);
        d.radius = 0.035;
        sd_shape2d c2 = make(&d);
        double worst_d = 0, worst_n = 0, worst_p = 0;
        int bad_status = 0;
        for (int t = 0; t < 2000; ++t) {
            sd_convex2d a = {&c1, pool, sd_v2(sd_rng_range(&rng, -1, 1), sd_rng_range(&rng, -1, 1)),
                             sd_rng_range(&rng, -3, 3)};
            double ang = sd_rng_range(&rng, 0, 2 * SD_PI_D), dist = sd_rng_range(&rng, 0.001, 0.12);
            sd_vec2 u = sd_v2(cos(ang), sin(ang));
            sd_convex2d b = {&c2, pool, sd_v2_madd(a.x, dist, u), sd_rng_range(&rng, -3, 3)};
            sd_contact2d c = sd_contact2d_convex_skin(&a, &b, NULL, NULL, 1.0);
            double depth = 0.055 - dist;
            worst_d = fmax(worst_d, fabs(c.depth - depth));
            worst_n = fmax(worst_n, angle_between(c.normal, u));
            /* the point halfway between the surfaces */
            sd_vec2 pt = sd_v2_madd(a.x, 0.02 + 0.5 * (dist - 0.055), u);
            worst_p = fmax(worst_p, sd_v2_norm(sd_v2_sub(c.point, pt)));
            bad_status += (depth > 1e-9 && c.status != SD_CONTACT2D_OVERLAP) ||
                          (depth < -1e-9 && c.status != SD_CONTACT2D_SEPARATED);
        }
        CHECK_NEAR("circle-circle depth, worst of 2000 (m)", worst_d, 0, 1e-15);
        CHECK_NEAR("circle-circle normal, worst angle (rad)", worst_n, 0, 1e-13);
        CHECK_NEAR("circle-circle point, worst error (m)", worst_p, 0, 1e-15);
        CHECK_NEAR("circle-circle status mismatches", bad_status, 0, 0);

        /* coincident centres: no NaN, full overlap */
        sd_convex2d a = {&c1, pool, sd_v2(0.1, 0.2), 0}, b = {&c2, pool, sd_v2(0.1, 0.2), 0};
        sd_contact2d c = sd_contact2d_convex(&a, &b, NULL, NULL);
        CHECK(c.status == SD_CONTACT2D_OVERLAP);
        CHECK_NEAR("coincident circles depth (m)", c.depth, 0.055, 1e-15);
        CHECK(isfinite(c.normal.x) && isfinite(c.normal.y) && fabs(sd_v2_norm(c.normal) - 1) < 1e-15);
    }

    /* ---- Fourier order 0 (p = R) is a circle: analytic distances ---------- */
    {
        sd_real a0[1] = {2 * 0.03};
        sd_shape2d_desc d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_FOURIER;
        d.radius = 0;
        d.order = 0;
        d.fs_a = a0;
        sd_shape2d f = make(&d);
        CHECK_REL("FS order 0 area (pi R^2)", f.area, SD_PI_D * 0.03 * 0.03, 1e-14);
        double worst = 0;
        for (int t = 0; t < 500; ++t) {
            double dist = sd_rng_range(&rng, 0.061, 0.2), ang = sd_rng_range(&rng, 0, 6.3);
            sd_convex2d a = {&f, pool, sd_v2(0, 0), sd_rng_range(&rng, -3, 3)};
            sd_convex2d b = {&f, pool, sd_v2(dist * cos(ang), dist * sin(ang)), sd_rng_range(&rng, -3, 3)};
            sd_gjk2d_result g = sd_gjk2d_distance(&a, &b, sd_v2_zero());
            worst = fmax(worst, fabs(g.distance - (dist - 0.06)));
        }
        CHECK_NEAR("FS circle-circle GJK distance, worst of 500 (m)", worst, 0, 1e-12);
    }

    /* ---- ellipse vs circle against the exact point–ellipse distance -------- */
    {
        const double ea = 0.04, eb = 0.015, rc = 0.01;
        sd_shape2d_desc d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_ELLIPSE;
        d.radius = 0;
        d.a = sd_v2(ea, eb);
        sd_shape2d el = make(&d);
        d.kind = SD_SHAPE2D_CIRCLE;
        d.radius = rc;
        sd_shape2d ci = make(&d);
        double worst = 0, worst_n = 0;
        int n_over = 0;
        for (int t = 0; t < 400; ++t) {
            /* circle centre at a random point outside the ellipse (in its frame) */
            double ang = sd_rng_range(&rng, 0, 2 * SD_PI_D), s = sd_rng_range(&rng, 1.02, 2.0);
            sd_vec2 c = sd_v2(s * ea * cos(ang), s * eb * sin(ang));
            /* reference: min over t of |c − (a cos t, b sin t)|, dense then golden section */
            int nk = 20000, bk = 0;
            double best = 1e300;
            for (int k = 0; k < nk; ++k) {
                double u = 2 * SD_PI_D * k / nk;
                double dd = hypot(c.x - ea * cos(u), c.y - eb * sin(u));
                if (dd < best) {
                    best = dd;
                    bk = k;
                }
            }
            double lo = 2 * SD_PI_D * (bk - 1) / nk, hi = 2 * SD_PI_D * (bk + 1) / nk;
            for (int it = 0; it < 200; ++it) {
                double m1 = lo + (hi - lo) * 0.381966, m2 = hi - (hi - lo) * 0.381966;
                if (hypot(c.x - ea * cos(m1), c.y - eb * sin(m1)) < hypot(c.x - ea * cos(m2), c.y - eb * sin(m2)))
                    hi = m2;
                else
                    lo = m1;
            }
            double u = 0.5 * (lo + hi);
            sd_vec2 foot = sd_v2(ea * cos(u), eb * sin(u));
            double dref = hypot(c.x - foot.x, c.y - foot.y) - rc; /* < 0: overlap */
            sd_vec2 nref = sd_v2_normalize(sd_v2_sub(c, foot));
            /* pose both bodies: ellipse turned by phi at x0 */
            double phi = sd_rng_range(&rng, -3, 3);
            sd_vec2 x0 = sd_v2(sd_rng_range(&rng, -1, 1), sd_rng_range(&rng, -1, 1));
            sd_convex2d A = {&el, pool, x0, phi}, B = {&ci, pool, sd_v2_add(x0, sd_v2_rot(c, phi)), 0.3};
            sd_contact2d k = sd_contact2d_convex_skin(&A, &B, NULL, NULL, 1.0);
            worst = fmax(worst, fabs(k.depth + dref));
            worst_n = fmax(worst_n, angle_between(k.normal, sd_v2_rot(nref, phi)));
            n_over += dref < 0;
        }
        printf("ellipse-circle: %d of 400 overlapping\n", n_over);
        /* GJK stops at a relative gap of 1e-10 in the distance (L ~ 0.05 m);
         * the direction of v then holds to ~sqrt(1e-10) */
        CHECK_NEAR("ellipse-circle depth vs exact point-ellipse distance (m)", worst, 0, 1e-11);
        CHECK_NEAR("ellipse-circle normal vs the ellipse normal (rad)", worst_n, 0, 2e-5);
    }

    /* ---- the shape zoo ---------------------------------------------------- */
    enum { NZOO = 10 };
    sd_shape2d zoo[NZOO];
    const char *zname[NZOO];
    {
        sd_shape2d_desc d = sd_shape2d_desc_default();
        int z = 0;
        d.kind = SD_SHAPE2D_CIRCLE;
        d.radius = 0.025;
        zname[z] = "circle";
        zoo[z++] = make(&d);

        d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_ELLIPSE;
        d.radius = 0;
        d.a = sd_v2(0.04, 0.018);
        zname[z] = "ellipse";
        zoo[z++] = make(&d);
        d.radius = 0.004;
        zname[z] = "rounded ellipse";
        zoo[z++] = make(&d);

        sd_vec2 hex[6];
        for (int i = 0; i < 6; ++i)
            hex[i] = sd_v2(0.03 * cos(i * SD_PI_D / 3 + 0.2) * (i % 2 ? 1.0 : 0.8), 0.03 * sin(i * SD_PI_D / 3 + 0.2));
        d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_POLYGON;
        d.radius = 0;
        d.points = hex;
        d.point_count = 6;
        zname[z] = "polygon";
        zoo[z++] = make(&d);
        d.radius = 0.003;
        zname[z] = "rounded polygon";
        zoo[z++] = make(&d);

        /* a stretched circle of 4 cubic arcs (G1) and a lens with corners */
        const double k = 0.5522847498;
        sd_vec2 bz[12] = {{0.045, 0},          {0.045, 0.03 * k},  {0.045 * k, 0.03},  {0, 0.03},
                          {-0.045 * k, 0.03},  {-0.045, 0.03 * k}, {-0.045, 0},        {-0.045, -0.03 * k},
                          {-0.045 * k, -0.03}, {0, -0.03},         {0.045 * k, -0.03}, {0.045, -0.03 * k}};
        d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_POLYBEZIER;
        d.radius = 0;
        d.points = bz;
        d.point_count = 12;
        zname[z] = "polybezier";
        zoo[z++] = make(&d);
        sd_vec2 lens[6] = {{-0.04, 0}, {-0.02, 0.025}, {0.02, 0.025}, {0.04, 0}, {0.02, -0.015}, {-0.02, -0.015}};
        d.points = lens;
        d.point_count = 6;
        zname[z] = "polybezier lens";
        zoo[z++] = make(&d);
        d.radius = 0.002;
        zname[z] = "rounded lens";
        zoo[z++] = make(&d);

        sd_real fa[5] = {0.06, 0.0, 0.003, 0.0008, 0.0003}, fb[4] = {0.0, 0.001, 0.0012, 0.0};
        d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_FOURIER;
        d.radius = 0;
        d.order = 4;
        d.fs_a = fa;
        d.fs_b = fb;
        zname[z] = "fourier";
        zoo[z++] = make(&d);
        d.radius = 0.002;
        zname[z] = "rounded fourier";
        zoo[z++] = make(&d);
    }

    /* every pair of the zoo, random poses from deep overlap to well apart */
    double worst_len = 0, worst_ang = 0;
    int status_bad = 0, total = 0, capped = 0;
    long calls_contact = 0, n_contact = 0, calls_apart = 0, n_apart = 0;
    const char *wa = "", *wb = "";
    for (int i = 0; i < NZOO; ++i)
        for (int j = i; j < NZOO; ++j)
            for (int t = 0; t < 12; ++t) {
                sd_convex2d a = {&zoo[i], pool, sd_v2(sd_rng_range(&rng, -0.5, 0.5), sd_rng_range(&rng, -0.5, 0.5)),
                                 sd_rng_range(&rng, -3.2, 3.2)};
                double L = zoo[i].bound + zoo[j].bound;
                double dist = L * sd_rng_range(&rng, 0.25, 1.3), ang = sd_rng_range(&rng, 0, 6.3);
                sd_convex2d b = {&zoo[j], pool, sd_v2_madd(a.x, dist, sd_v2(cos(ang), sin(ang))),
                                 sd_rng_range(&rng, -3.2, 3.2)};
                ref_result r = reference(&a, &b);
                int calls = 0;
                sd_contact2d c = sd_contact2d_convex_skin(&a, &b, NULL, &calls, 10 * L);
                double ref_depth = r.inside ? r.dist : -r.dist;
                double e = fabs(c.depth - ref_depth), an = angle_between(c.normal, r.n);
                /* near-touching pairs: the normal of a polygon vertex is ill defined */
                if (fabs(ref_depth) < 1e-4 * L)
                    an = 0;
                if (e > worst_len || an > worst_ang) {
                    wa = zname[i];
                    wb = zname[j];
                }
                worst_len = fmax(worst_len, e / L);
                worst_ang = fmax(worst_ang, an);
                capped += c.used_epa && c.epa_status == SD_EPA2D_CAPPED;
                status_bad += (ref_depth > 1e-5 * L && c.status != SD_CONTACT2D_OVERLAP) ||
                              (ref_depth < -1e-5 * L && c.status != SD_CONTACT2D_SEPARATED);
                ++total;
                /* the same pair as the engine calls it (skin 0) for the call counts */
                calls = 0;
                sd_contact2d_convex(&a, &b, NULL, &calls);
                if (ref_depth > 0) {
                    calls_contact += calls;
                    n_contact++;
                } else {
                    calls_apart += calls;
                    n_apart++;
                }
            }
    printf("zoo pairs: %d, worst length error at %s / %s\n", total, wa, wb);
    CHECK_NEAR("zoo depth/distance vs polygon Minkowski, worst / L", worst_len, 0, 2e-6);
    CHECK_NEAR("zoo normal vs polygon Minkowski, worst (rad)", worst_ang, 0, 3e-3);
    CHECK_NEAR("zoo status mismatches", status_bad, 0, 0);
    CHECK_NEAR("zoo EPA runs that hit the cap", capped, 0, 0);
    printf("average support calls: %.2f per overlapping pair (%ld), %.2f per pair apart (%ld)\n",
           (double)calls_contact / (double)(n_contact ? n_contact : 1), n_contact,
           (double)calls_apart / (double)(n_apart ? n_apart : 1), n_apart);

    /* EPA depth (with its polish on curved outlines) against the depth as
     * the minimum over θ of the support function of K = A − B of the cores
     * (origin inside K): 20000 directions, then a golden-section search
     * around the best — no polygon, no EPA. Sharp pairs that overlap. */
    {
        const int kinds[6] = {8, 1, 3, 5, 6, 9};
        double worst = 0, worst_n = 0;
        int n = 0;
        for (int t = 0; t < 240; ++t) {
            const sd_shape2d *sa = &zoo[kinds[t % 6]], *sb = &zoo[kinds[(t / 6) % 6]];
            double L = sa->bound + sb->bound, ang = sd_rng_range(&rng, 0, 6.3);
            sd_convex2d a = {sa, pool, sd_v2(0.1, -0.2), sd_rng_range(&rng, -3.2, 3.2)};
            sd_convex2d b = {sb, pool, sd_v2_madd(a.x, L * sd_rng_range(&rng, 0.3, 0.6), sd_v2(cos(ang), sin(ang))),
                             sd_rng_range(&rng, -3.2, 3.2)};
            sd_contact2d c = sd_contact2d_convex(&a, &b, NULL, NULL);
            if (!c.used_epa)
                continue;
            sd_gjk2d_body A = sd_gjk2d_pose(&a), B = sd_gjk2d_pose(&b);
            double best = 1e300, bt = 0;
            for (int k = 0; k < 20000; ++k) {
                double th = 2 * SD_PI_D * k / 20000;
                sd_vec2 u = sd_v2(cos(th), sin(th));
                double h = sd_v2_dot(u, sd_gjk2d_support(&A, &B, u).w);
                if (h < best) {
                    best = h;
                    bt = th;
                }
            }
            double lo = bt - 2 * SD_PI_D / 20000, hi = bt + 2 * SD_PI_D / 20000;
            for (int it = 0; it < 100; ++it) {
                double m1 = lo + (hi - lo) * 0.381966, m2 = hi - (hi - lo) * 0.381966;
                sd_vec2 u1 = sd_v2(cos(m1), sin(m1)), u2 = sd_v2(cos(m2), sin(m2));
                if (sd_v2_dot(u1, sd_gjk2d_support(&A, &B, u1).w) < sd_v2_dot(u2, sd_gjk2d_support(&A, &B, u2).w))
                    hi = m2;
                else
                    lo = m1;
            }
            sd_vec2 u = sd_v2(cos(0.5 * (lo + hi)), sin(0.5 * (lo + hi)));
            double ref = fmin(best, sd_v2_dot(u, sd_gjk2d_support(&A, &B, u).w)) + sa->radius + sb->radius;
            worst = fmax(worst, fabs(c.depth - ref) / L);
            if (best > 1e-6 * L) /* the direction is defined */
                worst_n = fmax(worst_n, angle_between(c.normal, u));
            ++n;
        }
        printf("EPA vs min of the support function: %d overlapping pairs\n", n);
        CHECK(n > 150);
        /* EPA stops when its bounds agree to 1e-8 of the depth (~0.3 L here) */
        CHECK_NEAR("EPA depth vs min over theta of h_K, worst / L", worst, 0, 1e-8);
        CHECK_NEAR("EPA normal vs argmin of h_K, worst (rad)", worst_n, 0, 3e-4);
    }

    /* Support calls per pair type, as in seed 002 Table 1: sharp shapes of
     * the five kinds, pairs in contact at an overlap of 0.5 % of the smaller
     * size (a DEM contact) and pairs apart by 0–50 % of it (broad-phase
     * neighbours). The engine's call (skin 0); GJK alone and GJK + EPA. */
    {
        const int kinds[5] = {8, 0, 1, 3, 5}; /* fourier, circle, ellipse, polygon, polybezier */
        const char *kn[5] = {"FS", "circle", "ellipse", "polygon", "polybez"};
        printf("\nsupport calls per pair (GJK / GJK+EPA in contact; GJK apart), 100 poses each:\n%-8s", "");
        for (int j = 0; j < 5; ++j)
            printf(" %-20s", kn[j]);
        printf("\n");
        double worst_avg = 0;
        for (int i = 0; i < 5; ++i) {
            printf("%-8s", kn[i]);
            for (int j = 0; j < 5; ++j) {
                if (j < i) {
                    printf(" %-20s", "");
                    continue;
                }
                const sd_shape2d *sa = &zoo[kinds[i]], *sb = &zoo[kinds[j]];
                long g_in = 0, t_in = 0, g_out = 0;
                for (int t = 0; t < 100; ++t) {
                    double ang = sd_rng_range(&rng, 0, 6.3);
                    sd_vec2 u = sd_v2(cos(ang), sin(ang));
                    sd_convex2d a = {sa, pool, sd_v2(0, 0), sd_rng_range(&rng, -3.2, 3.2)};
                    sd_convex2d b = {sb, pool, sd_v2(0, 0), sd_rng_range(&rng, -3.2, 3.2)};
                    double size = fmin(sa->min_size, sb->min_size), target = 0.005 * size;
                    double lo = 0, hi = sa->bound + sb->bound;
                    for (int it = 0; it < 50; ++it) { /* depth decreases with the separation */
                        double mid = 0.5 * (lo + hi);
                        b.x = sd_v2_scale(u, mid);
                        if (sd_contact2d_convex_skin(&a, &b, NULL, NULL, 1.0).depth > target)
                            lo = mid;
                        else
                            hi = mid;
                    }
                    b.x = sd_v2_scale(u, lo);
                    int calls = 0;
                    sd_contact2d_convex(&a, &b, NULL, &calls);
                    t_in += calls;
                    g_in += sd_gjk2d_distance_bounded(&a, &b, sd_v2_zero(), sa->radius + sb->radius).support_calls;
                    b.x = sd_v2_scale(u, lo + sd_rng_range(&rng, 0.005, 0.5) * size);
                    calls = 0;
                    sd_contact2d_convex(&a, &b, NULL, &calls);
                    g_out += calls;
                }
                char cell[64];
                snprintf(cell, sizeof cell, "%.2f/%.2f; %.2f", g_in / 100.0, t_in / 100.0, g_out / 100.0);
                printf(" %-20s", cell);
                worst_avg = fmax(worst_avg, t_in / 100.0);
            }
            printf("\n");
        }
        printf("(seed 002 Table 1, GJK in a packing: 2.9-6.0)\n\n");
        CHECK(worst_avg < 40);
    }

    /* O(n·m) brute force for a few separated pairs (1000-gons) */
    {
        double worst = 0;
        for (int t = 0; t < 6; ++t) {
            int i = t % NZOO, j = (3 * t + 1) % NZOO;
            sd_convex2d a = {&zoo[i], pool, sd_v2(0, 0), 0.3 * t};
            double L = zoo[i].bound + zoo[j].bound;
            sd_convex2d b = {&zoo[j], pool, sd_v2(1.1 * L, 0.2 * L), -0.7 * t};
            sd_gjk2d_result g = sd_gjk2d_distance(&a, &b, sd_v2_zero());
            double bf = brute_distance(&a, &b, 1000) + zoo[i].radius + zoo[j].radius; /* core distance */
            worst = fmax(worst, fabs(g.distance - bf) / L);
        }
        CHECK_NEAR("GJK vs O(n m) vertex-edge brute force (1000-gons), worst / L", worst, 0, 2e-5);
    }

    /* ---- aligned squares: GJK ends on a segment; exact touching ------------ */
    {
        sd_vec2 sq[4] = {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
        sd_shape2d_desc d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_POLYGON;
        d.radius = 0;
        d.points = sq;
        d.point_count = 4;
        sd_shape2d s = make(&d);
        sd_convex2d a = {&s, pool, sd_v2(0, 0), 0}, b = {&s, pool, sd_v2(0.7, 0), 0};
        sd_contact2d c = sd_contact2d_convex(&a, &b, NULL, NULL);
        CHECK_NEAR("squares offset 0.7: depth", c.depth, 0.3, 1e-14);
        CHECK_NEAR("squares offset 0.7: normal x", c.normal.x, 1, 1e-14);
        CHECK(c.status == SD_CONTACT2D_OVERLAP && c.used_epa);
        b.x = sd_v2(1.0, 0);
        c = sd_contact2d_convex(&a, &b, NULL, NULL);
        CHECK(c.status == SD_CONTACT2D_TOUCHING);
        CHECK_NEAR("squares exactly touching: depth", c.depth, 0, 1e-14);
        CHECK(isfinite(c.normal.x) && isfinite(c.normal.y));
        CHECK_NEAR("squares exactly touching: normal x", fabs(c.normal.x), 1, 1e-12);
        b.x = sd_v2(0.3, 0.95);
        c = sd_contact2d_convex(&a, &b, NULL, NULL);
        CHECK_NEAR("squares offset (0.3, 0.95): depth", c.depth, 0.05, 1e-14);
        CHECK_NEAR("squares offset (0.3, 0.95): normal y", c.normal.y, 1, 1e-14);
        /* warm start: the second query of the same pair finds the same answer */
        sd_vec2 warm = sd_v2_zero();
        int calls = 0;
        b.x = sd_v2(1.2, 0.1);
        sd_contact2d c1 = sd_contact2d_convex_skin(&a, &b, &warm, &calls, 1.0);
        int first = calls;
        sd_contact2d c2 = sd_contact2d_convex_skin(&a, &b, &warm, &calls, 1.0);
        CHECK_NEAR("warm-started distance (m)", c2.depth, c1.depth, 1e-15);
        CHECK_NEAR("squares apart by 0.2: depth", c1.depth, -0.2, 1e-14);
        printf("support calls: cold %d, warm %d\n", first, calls - first);
        CHECK(calls - first <= first);
        /* skin 0: GJK may stop at the first support that proves the gap > 0;
         * the depth is then an upper bound of −gap */
        sd_contact2d c3 = sd_contact2d_convex(&a, &b, NULL, NULL);
        CHECK(c3.status == SD_CONTACT2D_SEPARATED && c3.depth < 0 && c3.depth >= -0.2 - 1e-14);
    }

    /* ---- non-finite pose: DEGENERATE, no NaN -------------------------------- */
    {
        sd_convex2d a = {&zoo[1], pool, sd_v2((sd_real)nan(""), 0), 0}, b = {&zoo[3], pool, sd_v2(0, 0), 0};
        sd_contact2d c = sd_contact2d_convex(&a, &b, NULL, NULL);
        CHECK(c.status == SD_CONTACT2D_DEGENERATE);
        CHECK(isfinite(c.normal.x) && isfinite(c.depth));
    }
    return sd_test_summary();
}
