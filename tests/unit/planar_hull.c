/* planar_hull.c — the 2D hull and polygon templates under extreme
 * coordinates (robustness probe F2).
 *
 *   - sd_hull2d never writes more than n points, whatever the input: the
 *     probe's reproducers (a square of side 1e155, whose cross products
 *     overflowed to NaN and made the chain grow to ~2n; points of 1e-160,
 *     whose products underflowed to 0; a 2 cm circle at (1e8, 1e8); 1000
 *     points on a circle of radius 1e160) give the hull a unit-size copy
 *     gives, scaled; a NaN point gives 0 and writes nothing;
 *   - each hull is checked against the definition: its vertices are input
 *     points, it turns left at every vertex, and every input point lies
 *     inside it (orientation tests in long double on the points scaled by
 *     the same power of two);
 *   - sd_shape2d_make refuses the 1e160 polygon with a message naming
 *     'points' (it smashed the stack), and a polygon given around
 *     (1e5, 1e5) gets the area, polar moment and bound of the same polygon
 *     about the origin (they were wrong by cancellation: a negative moment
 *     of inertia and the centroid 167 m off).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "shape/shape2d.h"
#include "test.h"

enum { CAP = 2100, GUARD = 64 };
static sd_vec2 pts[CAP], hull[CAP + GUARD];

/* runs the hull with a guard zone after hull[n]; returns its size, -1 if the guard was written */
static long hull_guarded(size_t n)
{
    for (size_t i = 0; i < CAP + GUARD; ++i)
        hull[i] = sd_v2(12345.0, -12345.0);
    int oom = 0;
    const size_t h = sd_hull2d(pts, n, hull, &oom);
    for (size_t i = n; i < n + GUARD; ++i)
        if (hull[i].x != 12345.0 || hull[i].y != -12345.0)
            return -1;
    return oom ? -2 : (long)h;
}

/* the hull is a convex CCW polygon of input points containing every input point */
static int hull_valid(size_t n, size_t h, double scale)
{
    for (size_t i = 0; i < h; ++i) {
        int found = 0;
        for (size_t j = 0; j < n && !found; ++j)
            found = hull[i].x == pts[j].x && hull[i].y == pts[j].y;
        if (!found)
            return 0;
    }
    for (size_t i = 0; i < h; ++i) {
        const sd_vec2 a = hull[i], b = hull[(i + 1) % h];
        const long double ax = (long double)a.x * scale, ay = (long double)a.y * scale;
        const long double ex = (long double)b.x * scale - ax, ey = (long double)b.y * scale - ay;
        for (size_t j = 0; j < n; ++j) {
            const long double px = (long double)pts[j].x * scale - ax, py = (long double)pts[j].y * scale - ay;
            const long double o = ex * py - ey * px;
            /* inside or on the edge line, to rounding of the unit-size points */
            if (o < -1e-15L * (fabsl(ex * py) + fabsl(ey * px)))
                return 0;
        }
        const sd_vec2 c = hull[(i + 2) % h];
        const long double cx = (long double)c.x * scale - ax, cy = (long double)c.y * scale - ay;
        if (!(ex * cy - ey * cx > 0))
            return 0; /* a strict left turn at every vertex */
    }
    return 1;
}

static void check_hull(const char *label, size_t n, size_t expect_h, double scale)
{
    const long h = hull_guarded(n);
    char buf[160];
    snprintf(buf, sizeof buf, "%s: hull size (guard untouched)", label);
    CHECK_NEAR(buf, (double)h, (double)expect_h, 0);
    if (h > 0) {
        const int ok = hull_valid(n, (size_t)h, scale);
        printf("%-4s %s: vertices are input points, convex, contain every point\n", ok ? "ok" : "FAIL", label);
        CHECK(ok);
    }
}

static void circle(size_t n, double cx, double cy, double r)
{
    for (size_t i = 0; i < n; ++i) {
        const double t = 2 * SD_PI_D * (double)i / (double)n;
        pts[i] = sd_v2(cx + r * cos(t), cy + r * sin(t));
    }
}

int main(void)
{
    /* the probe's outline: a square of side 1e155 (cross products 1e310: NaN) */
    pts[0] = sd_v2(0, 0);
    pts[1] = sd_v2(1e155, 0);
    pts[2] = sd_v2(1e155, 1e155);
    pts[3] = sd_v2(0, 1e155);
    check_hull("square of side 1e155", 4, 4, 1e-155);
    for (int i = 0; i < 4; ++i) /* all coordinates near the top of the range */
        pts[i] = sd_v2(pts[i].x * 1.7e153 - 8e307, pts[i].y * 1.7e153 - 8e307);
    check_hull("square at +-8e307", 4, 4, 1e-308);
    /* every point tiny (products underflow to 0: everything looked collinear) */
    for (int i = 0; i < 4; ++i)
        pts[i] = sd_v2(i == 1 || i == 2 ? 1e-160 : 0, i >= 2 ? 1e-160 : 0);
    check_hull("square of side 1e-160", 4, 4, 1e160);
    /* a 2 cm circle far from the origin, and one on a radius of 1e160 */
    circle(720, 1e8, 1e8, 0.02);
    {
        const long h = hull_guarded(720);
        printf("%-4s circle r = 0.02 m at (1e8, 1e8): hull %ld vertices of 720, <= 720 and >= 3\n",
               h >= 3 && h <= 720 ? "ok" : "FAIL", h);
        CHECK(h >= 3 && h <= 720);
        CHECK(h > 0 && hull_valid(720, (size_t)h, 1e-8));
    }
    circle(1000, 0, 0, 1e160);
    check_hull("1000 points on a circle of radius 1e160", 1000, 1000, 1e-160);
    circle(1000, 0, 0, 1.0);
    check_hull("the same circle at radius 1", 1000, 1000, 1.0);
    /* many points on the hull of a 2000-gon with duplicates and collinear
     * points between the vertices: still at most n */
    for (size_t i = 0; i < 2000; ++i) {
        const double t = 2 * SD_PI_D * (double)(i / 2) / 1000.0;
        pts[i] = sd_v2(1e150 * cos(t), 1e150 * sin(t)); /* each vertex twice */
    }
    check_hull("1000 vertices of radius 1e150, each twice", 2000, 1000, 1e-150);

    /* non-finite input: nothing written, 0 returned */
    circle(100, 0, 0, 1.0);
    pts[37] = sd_v2(NAN, 0.5);
    {
        const long h = hull_guarded(100);
        int untouched = 1;
        for (size_t i = 0; i < 100; ++i)
            untouched = untouched && hull[i].x == 12345.0;
        printf("%-4s a NaN point: hull size %ld (expected 0), output untouched %d\n",
               h == 0 && untouched ? "ok" : "FAIL", h, untouched);
        CHECK(h == 0 && untouched);
    }
    pts[37] = sd_v2(INFINITY, 0.5);
    CHECK(hull_guarded(100) == 0);

    /* ---- polygon templates ------------------------------------------------------ */
    sd_real pool[2 * SD_SHAPE2D_MAX_POINTS];
    size_t used = 0;
    sd_error err;
    sd_shape2d s;
    {
        static sd_vec2 big[1000];
        for (int i = 0; i < 1000; ++i) {
            const double t = 2 * SD_PI_D * i / 1000.0;
            big[i] = sd_v2(1e160 * cos(t), 1e160 * sin(t));
        }
        sd_shape2d_desc d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_POLYGON;
        d.radius = 0;
        d.points = big;
        d.point_count = 1000;
        sd_error_clear(&err);
        const sd_status st = sd_shape2d_make(&d, &s, pool, sizeof pool / sizeof pool[0], &used, &err);
        printf("%-4s polygon of 1000 points at radius 1e160: refused (status %d, key '%s': %s)\n",
               st == SD_ERR_INPUT && strcmp(err.key, "points") == 0 ? "ok" : "FAIL", (int)st, err.key, err.msg);
        CHECK(st == SD_ERR_INPUT && strcmp(err.key, "points") == 0);
    }
    {
        /* an overflowing size of the other kinds names its key (it said "the circle has no area", key 'type') */
        sd_shape2d_desc d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_CIRCLE;
        d.radius = 1e160;
        sd_error_clear(&err);
        const sd_status st = sd_shape2d_make(&d, &s, pool, sizeof pool / sizeof pool[0], &used, &err);
        printf("%-4s circle of radius 1e160: refused (status %d, key '%s': %s)\n",
               st == SD_ERR_INPUT && strcmp(err.key, "radius") == 0 ? "ok" : "FAIL", (int)st, err.key, err.msg);
        CHECK(st == SD_ERR_INPUT && strcmp(err.key, "radius") == 0);
    }
    {
        /* a 12-gon of radius 1 cm, rounded by 1 mm, about the origin and about (1e5, 1e5) */
        sd_vec2 at0[12], far[12];
        for (int i = 0; i < 12; ++i) {
            const double t = 2 * SD_PI_D * i / 12.0;
            at0[i] = sd_v2(0.01 * cos(t), 0.01 * sin(t));
            far[i] = sd_v2(1e5 + at0[i].x, 1e5 + at0[i].y);
        }
        sd_shape2d s0, s1;
        sd_real pool1[64];
        sd_shape2d_desc d = sd_shape2d_desc_default();
        d.kind = SD_SHAPE2D_POLYGON;
        d.radius = 0.001;
        d.points = at0;
        d.point_count = 12;
        sd_test_require(sd_shape2d_make(&d, &s0, pool, sizeof pool / sizeof pool[0], &used, &err) == SD_OK,
                        "12-gon at the origin", &err);
        d.points = far;
        sd_test_require(sd_shape2d_make(&d, &s1, pool1, 64, &used, &err) == SD_OK, "12-gon at (1e5, 1e5)", &err);
        /* the far copy's vertices carry ~1e-11 m of rounding (ulp of 1e5) */
        CHECK_REL("12-gon at (1e5, 1e5): area vs at the origin", s1.area, s0.area, 1e-8);
        CHECK_REL("12-gon at (1e5, 1e5): polar moment vs at the origin", s1.inertia, s0.inertia, 1e-7);
        CHECK_REL("12-gon at (1e5, 1e5): bound vs at the origin", s1.bound, s0.bound, 1e-8);
        CHECK_NEAR("12-gon at (1e5, 1e5): given centroid x (m)", s1.given_com.x, 1e5 + s0.given_com.x, 1e-9);
        CHECK_NEAR("12-gon at (1e5, 1e5): given centroid y (m)", s1.given_com.y, 1e5 + s0.given_com.y, 1e-9);
    }
    return sd_test_summary();
}
