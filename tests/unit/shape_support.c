/* shape_support.c — support functions (shape/support.h) against brute force.
 *
 * For every kind, sharp and rounded, the swept shape is sampled as the
 * Minkowski sum of a dense cloud on the core's surface (written here from
 * the geometry: faces, sides, caps, lateral cone, ellipsoid grid, hull
 * triangles) and a dense cloud of r·u, u on the unit sphere. The max of
 * d·x over that sum is the core cloud's max plus r times the sphere
 * cloud's max, so it is computed without forming the product. For 200
 * random directions (and axis, zero, tiny and huge ones) the support value
 * d·s(d) must never fall below the cloud's max (1e-12 relative) and may
 * exceed it only by the sampling resolution; the core support point must
 * lie in the core, within 1e-12 of its surface. Posed bodies
 * (sd_convex_support, sd_convex_support_core) the same, with the cloud moved.
 */
#include "test.h"

#include <string.h>

#include "core/rng.h"
#include "geom/hull.h"
#include "shape/shape_make.h"
#include "shape/support.h"

#define PI   SD_PI_D
#define MAXC 200000
static sd_vec3 cloud[MAXC];
static int nc;
static sd_vec3 sph[20000];
static int nsph;
static sd_vec3 pool[SD_SHAPE_MAX_VERTICES];
static sd_hull_workspace ws;
static sd_hull hull;

static void add(sd_vec3 p)
{
    if (nc < MAXC)
        cloud[nc++] = p;
}

static sd_shape make(sd_shape_def d)
{
    sd_shape s;
    sd_error err;
    size_t used = 0;
    sd_status st = sd_shape_make(&d, &s, pool, SD_SHAPE_MAX_VERTICES, &used, &err);
    sd_test_require(st == SD_OK, "sd_shape_make", &err);
    return s;
}

/* The core's surface, principal frame. */
static void core_cloud(const sd_shape *s)
{
    nc = 0;
    const int n = 120;
    sd_vec3 a = s->a, o = s->offset;
    switch (s->kind) {
    case SD_SHAPE_SPHERE:
        add(o);
        break;
    case SD_SHAPE_BOX:
        for (int f = 0; f < 6; ++f)
            for (int i = 0; i <= n; ++i)
                for (int j = 0; j <= n; ++j) {
                    double u = -1 + 2.0 * i / n, v = -1 + 2.0 * j / n, sg = (f & 1) ? 1 : -1;
                    add(f < 2 ? sd_v3(sg * a.x, u * a.y, v * a.z)
                              : (f < 4 ? sd_v3(u * a.x, sg * a.y, v * a.z) : sd_v3(u * a.x, v * a.y, sg * a.z)));
                }
        break;
    case SD_SHAPE_CYLINDER:
        for (int i = 0; i < 4 * n; ++i) {
            double ph = 2 * PI * i / (4 * n);
            for (int j = 0; j <= n; ++j) {
                add(sd_v3(a.x * cos(ph), a.x * sin(ph), -a.z + 2 * a.z * j / n)); /* side */
                double rho = a.x * j / n;
                add(sd_v3(rho * cos(ph), rho * sin(ph), a.z)); /* caps */
                add(sd_v3(rho * cos(ph), rho * sin(ph), -a.z));
            }
        }
        break;
    case SD_SHAPE_CONE:
        for (int i = 0; i < 4 * n; ++i) {
            double ph = 2 * PI * i / (4 * n);
            for (int j = 0; j <= n; ++j) {
                double t = (double)j / n;
                add(sd_v3_add(o, sd_v3(a.x * t * cos(ph), a.x * t * sin(ph), 0)));                   /* base */
                add(sd_v3_add(o, sd_v3(a.x * (1 - t) * cos(ph), a.x * (1 - t) * sin(ph), a.z * t))); /* lateral */
            }
        }
        break;
    case SD_SHAPE_ELLIPSOID:
        for (int i = 0; i <= 2 * n; ++i) {
            double th = PI * i / (2 * n);
            for (int j = 0; j < 4 * n; ++j) {
                double ph = 2 * PI * j / (4 * n);
                add(sd_v3(a.x * sin(th) * cos(ph), a.y * sin(th) * sin(ph), a.z * cos(th)));
            }
        }
        break;
    case SD_SHAPE_POLYHEDRON: {
        /* the hull's triangles, barycentric grids */
        sd_hull_status st = sd_hull_build(pool + s->vstart, s->vcount, &ws, &hull);
        sd_test_require(st == SD_HULL_OK, "hull of the template", NULL);
        const int m = 12;
        for (int t = 0; t < hull.ntri; ++t) {
            sd_vec3 A = pool[hull.tri[t][0]], B = pool[hull.tri[t][1]], C = pool[hull.tri[t][2]];
            for (int i = 0; i <= m; ++i)
                for (int j = 0; i + j <= m; ++j) {
                    double u = (double)i / m, v = (double)j / m;
                    add(sd_v3_add(A, sd_v3_add(sd_v3_scale(sd_v3_sub(B, A), u), sd_v3_scale(sd_v3_sub(C, A), v))));
                }
        }
        break;
    }
    }
}

/* Is p in the core (within tol)? Returns its distance outside the core. */
static double core_excess(const sd_shape *s, sd_vec3 p)
{
    sd_vec3 a = s->a;
    p = sd_v3_sub(p, s->offset);
    switch (s->kind) {
    case SD_SHAPE_SPHERE:
        return sd_v3_norm(p);
    case SD_SHAPE_BOX:
        return fmax(fmax(fabs(p.x) - a.x, fabs(p.y) - a.y), fabs(p.z) - a.z);
    case SD_SHAPE_CYLINDER:
        return fmax(hypot(p.x, p.y) - a.x, fabs(p.z) - a.z);
    case SD_SHAPE_CONE: {
        double rho = hypot(p.x, p.y), sl = hypot(a.x, a.z);
        /* below the base, or outside the slant plane through the rim and apex */
        return fmax(-p.z, (a.z * rho + a.x * p.z - a.x * a.z) / sl);
    }
    case SD_SHAPE_ELLIPSOID:
        return (sqrt(sd_sq(p.x / a.x) + sd_sq(p.y / a.y) + sd_sq(p.z / a.z)) - 1) * fmin(a.x, fmin(a.y, a.z));
    case SD_SHAPE_POLYHEDRON: {
        double best = 1e300;
        for (uint32_t k = 0; k < s->vcount; ++k)
            best = fmin(best, sd_v3_norm(sd_v3_sub(p, pool[s->vstart + k])));
        return best; /* a polyhedron's support is one of its vertices */
    }
    }
    return 1e300;
}

/* max over the cloud of d . (x + R c) */
static double cloud_max(sd_vec3 d, sd_quat q, sd_vec3 x)
{
    sd_vec3 dl = sd_quat_rotate_inv(q, d);
    double m = -1e300;
    for (int i = 0; i < nc; ++i)
        m = fmax(m, sd_v3_dot(dl, cloud[i]));
    return m + sd_v3_dot(d, x);
}

static double sphere_max(sd_vec3 d)
{
    double m = -1e300;
    for (int i = 0; i < nsph; ++i)
        m = fmax(m, sd_v3_dot(d, sph[i]));
    return m;
}

static sd_vec3 rand_dir(sd_rng *r)
{
    for (;;) {
        sd_vec3 v = sd_v3(sd_rng_range(r, -1, 1), sd_rng_range(r, -1, 1), sd_rng_range(r, -1, 1));
        double l = sd_v3_norm(v);
        if (l > 0.1 && l <= 1)
            return sd_v3_scale(v, 1 / l);
    }
}

static void check_shape(const char *label, sd_shape s, double res, sd_rng *rng)
{
    core_cloud(&s);
    double size = s.bound, worst_low = 0, worst_high = 0, worst_core = 0, worst_pose = 0, worst_pose_core = 0;
    int nan = 0;
    sd_quat q = sd_quat_normalize(sd_quat_make(sd_rng_range(rng, -1, 1), sd_rng_range(rng, -1, 1),
                                               sd_rng_range(rng, -1, 1), sd_rng_range(rng, -1, 1)));
    sd_vec3 x = sd_v3(sd_rng_range(rng, -5, 5), sd_rng_range(rng, -5, 5), sd_rng_range(rng, -5, 5));
    sd_convex body = {&s, pool, x, q, NULL, NULL};
    for (int k = 0; k < 200 + 6; ++k) {
        sd_vec3 d = k < 200 ? rand_dir(rng)
                            : sd_v3(k == 200   ? 1
                                    : k == 201 ? -1
                                               : 0,
                                    k == 202   ? 1
                                    : k == 203 ? -1
                                               : 0,
                                    k == 204   ? 1
                                    : k == 205 ? -1
                                               : 0);
        /* principal frame; d given at an odd length */
        sd_vec3 sc = sd_shape_support_core(&s, pool, sd_v3_scale(d, 3.7));
        sd_vec3 sw = sd_shape_support(&s, pool, sd_v3_scale(d, 0.01));
        nan += !isfinite(sw.x) || !isfinite(sw.y) || !isfinite(sw.z);
        double ref = cloud_max(d, sd_quat_identity(), sd_v3_zero()) + s.radius * sphere_max(d);
        double h = sd_v3_dot(d, sw);
        worst_low = fmax(worst_low, (ref - h) / size);
        worst_high = fmax(worst_high, (h - ref) / size);
        worst_core = fmax(worst_core, core_excess(&s, sc) / size);
        /* the core support is where d . x is largest on the core */
        worst_low = fmax(worst_low, (cloud_max(d, sd_quat_identity(), sd_v3_zero()) - sd_v3_dot(d, sc)) / size);
        /* posed */
        sd_vec3 pw = sd_convex_support(&body, d), pc = sd_convex_support_core(&body, d);
        double refp = cloud_max(d, q, x) + s.radius * sphere_max(d);
        worst_pose = fmax(worst_pose, fabs(sd_v3_dot(d, pw) - refp) / size);
        /* the posed core point, moved back to the principal frame, is in the core */
        sd_vec3 back = sd_quat_rotate_inv(q, sd_v3_sub(pc, x));
        worst_pose_core = fmax(worst_pose_core, core_excess(&s, back) / size);
        worst_low = fmax(worst_low, (refp - sd_v3_dot(d, pw)) / size);
    }
    char buf[160];
    snprintf(buf, sizeof buf, "%s: cloud max above d.s(d) (rel)", label);
    CHECK_NEAR(buf, worst_low, 0, 1e-12);
    snprintf(buf, sizeof buf, "%s: d.s(d) above cloud max (rel)", label);
    CHECK_NEAR(buf, worst_high, 0, res);
    snprintf(buf, sizeof buf, "%s: core point outside the core (rel)", label);
    CHECK_NEAR(buf, worst_core, 0, 1e-12);
    snprintf(buf, sizeof buf, "%s: posed vs moved cloud (rel)", label);
    CHECK_NEAR(buf, worst_pose, 0, res);
    snprintf(buf, sizeof buf, "%s: posed core point in the core (rel)", label);
    CHECK_NEAR(buf, worst_pose_core, 0, 1e-12);
    CHECK(nan == 0);

    /* degenerate directions: zero, subnormal, huge; never NaN, always in the core */
    sd_vec3 odd[5] = {sd_v3(0, 0, 0), sd_v3(4.9e-324, 0, -4.9e-324), sd_v3(1e-300, 2e-300, -1e-300),
                      sd_v3(1e300, -1e300, 1e300), sd_v3(0, -0.0, 0)};
    int bad = 0;
    for (int k = 0; k < 5; ++k) {
        sd_vec3 c = sd_shape_support_core(&s, pool, odd[k]), w = sd_shape_support(&s, pool, odd[k]);
        sd_vec3 wp = sd_convex_support(&body, odd[k]);
        bad += !isfinite(c.x + c.y + c.z + w.x + w.y + w.z + wp.x + wp.y + wp.z);
        bad += core_excess(&s, c) > 1e-12 * size;
        bad += fabs(sd_v3_norm(sd_v3_sub(w, c)) - s.radius) > 1e-12 * size;
    }
    snprintf(buf, sizeof buf, "%s: zero/tiny/huge directions bad", label);
    CHECK_NEAR(buf, bad, 0, 0);
    /* a tiny direction and its normal-size copy give the same support */
    sd_vec3 d = sd_v3(0.3, -0.8, 0.5);
    sd_vec3 s1 = sd_shape_support(&s, pool, d), s2 = sd_shape_support(&s, pool, sd_v3_scale(d, 1e-200));
    snprintf(buf, sizeof buf, "%s: support(1e-200 d) vs support(d)", label);
    CHECK_NEAR(buf, sd_v3_norm(sd_v3_sub(s1, s2)) / size, 0, 1e-15);
}

int main(void)
{
    sd_rng rng = sd_rng_seed(21);
    /* Fibonacci sphere: spacing ~ sqrt(4 pi / n) = 0.025 rad, so the sphere
     * cloud's max falls short of 1 by at most ~ 0.025^2 / 2 ~ 3e-4 */
    nsph = 20000;
    for (int i = 0; i < nsph; ++i) {
        double z = 1 - (2.0 * i + 1) / nsph, rr = sqrt(1 - z * z), ph = i * PI * (3 - sqrt(5.0));
        sph[i] = sd_v3(rr * cos(ph), rr * sin(ph), z);
    }
    /* The resolution allowed above the cloud: the curved core clouds have an
     * angular step of 2 pi / 480 (max short by R (1 - cos(step/2)) ~ 2e-5 R),
     * the sphere cloud 3e-4 r; flat faces and vertices are sampled exactly. */
    const double res = 1e-3;
    for (int rounded = 0; rounded < 3; ++rounded) {
        double r = rounded == 1 ? 0.07 : 0, m = rounded == 2 ? 0.05 : 0;
        const char *tag = rounded == 0 ? "sharp" : (rounded == 1 ? "rounded" : "margin");
        char label[96];
        sd_shape_def d = sd_shape_def_default();
        d.rounding = r;
        d.margin = m;

        d.kind = SD_SHAPE_SPHERE;
        d.size = sd_v3(0.4, 0, 0);
        snprintf(label, sizeof label, "%s sphere", tag);
        check_shape(label, make(d), res, &rng);

        d.kind = SD_SHAPE_BOX;
        d.size = sd_v3(0.6, 1.0, 1.6);
        snprintf(label, sizeof label, "%s box", tag);
        check_shape(label, make(d), res, &rng);

        d.kind = SD_SHAPE_CYLINDER;
        d.size = sd_v3(0.8, 0, 1.5);
        snprintf(label, sizeof label, "%s cylinder", tag);
        check_shape(label, make(d), res, &rng);

        d.kind = SD_SHAPE_CONE;
        d.size = sd_v3(1.0, 0, 1.2);
        snprintf(label, sizeof label, "%s cone", tag);
        check_shape(label, make(d), res, &rng);

        d.kind = SD_SHAPE_ELLIPSOID;
        d.size = sd_v3(0.3, 0.6, 1.0);
        snprintf(label, sizeof label, "%s ellipsoid", tag);
        check_shape(label, make(d), res, &rng);

        /* a random polyhedron (40 points near an ellipsoid, some inside) */
        sd_vec3 p[40];
        for (int i = 0; i < 40; ++i) {
            sd_vec3 u = rand_dir(&rng);
            p[i] = sd_v3(0.5 * u.x + 2, 0.8 * u.y - 1, 0.35 * u.z + 0.5);
            if (i % 4 == 0)
                p[i] = sd_v3_scale(sd_v3_add(p[i], sd_v3(-2, 1, -0.5)), 0.3);
        }
        d.kind = SD_SHAPE_POLYHEDRON;
        d.vertices = p;
        d.vertex_count = 40;
        snprintf(label, sizeof label, "%s polyhedron", tag);
        check_shape(label, make(d), res, &rng);
        d.vertices = NULL;
        d.vertex_count = 0;
    }
    /* ties: a box face and a polyhedron face pick a deterministic corner */
    {
        sd_shape_def d = sd_shape_def_default();
        d.kind = SD_SHAPE_BOX;
        d.size = sd_v3(2, 2, 2);
        sd_shape s = make(d);
        sd_vec3 c = sd_shape_support_core(&s, NULL, sd_v3(0, 0, 1));
        CHECK(c.x == 1 && c.y == 1 && c.z == 1);
        c = sd_shape_support_core(&s, NULL, sd_v3(-0.0, 0, -1));
        CHECK(c.x == 1 && c.y == 1 && c.z == -1);
    }
    return sd_test_summary();
}
