/* planar_outline_check.c — sd_outline_check (shape/outline.h), the test
 * that an outline is a simple closed curve the coverage can be measured
 * against (robustness probe F9: a bow-tie gave -inf %, a random cloud
 * 193 %).
 *
 *   - its verdict against brute force (every pair of segments, O(n²)) on
 *     20,000 random polygons of 4 to 9 vertices on a 5 x 5 integer grid,
 *     where collinear edges, vertices on edges, repeated vertices and
 *     spikes are common, and on star-shaped ones (mostly simple);
 *   - a 10^5-vertex star-shaped outline is accepted; with one vertex moved
 *     across the outline it is refused, naming the segments involved;
 *   - consecutive repeated points and the closing point are accepted.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/error.h"
#include "core/rng.h"
#include "shape/outline.h"
#include "shape/shape2d.h"
#include "test.h"

static long orient(sd_vec2 a, sd_vec2 b, sd_vec2 c) /* exact on the integer grid */
{
    const double o = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    return (o > 0) - (o < 0);
}

static int on_seg(sd_vec2 a, sd_vec2 b, sd_vec2 c)
{
    return fmin(a.x, b.x) <= c.x && c.x <= fmax(a.x, b.x) && fmin(a.y, b.y) <= c.y && c.y <= fmax(a.y, b.y);
}

static int meet(sd_vec2 a, sd_vec2 b, sd_vec2 c, sd_vec2 d)
{
    const long o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0)
        return 1;
    return (!o1 && on_seg(a, b, c)) || (!o2 && on_seg(a, b, d)) || (!o3 && on_seg(c, d, a)) ||
           (!o4 && on_seg(c, d, b));
}

/* 1: a simple closed curve with area (after dropping consecutive repeats) */
static int brute_simple(const sd_vec2 *p, size_t n)
{
    sd_vec2 v[16];
    size_t m = 0;
    for (size_t i = 0; i < n; ++i)
        if (m == 0 || p[i].x != v[m - 1].x || p[i].y != v[m - 1].y)
            v[m++] = p[i];
    while (m > 1 && v[m - 1].x == v[0].x && v[m - 1].y == v[0].y)
        --m;
    if (m < 3)
        return 0;
    for (size_t i = 0; i < m; ++i)
        for (size_t j = i + 1; j < m; ++j) {
            if (v[i].x == v[j].x && v[i].y == v[j].y)
                return 0; /* a repeated vertex */
            const int adjacent = j == i + 1 || (i == 0 && j == m - 1);
            const sd_vec2 a = v[i], b = v[(i + 1) % m], c = v[j], d = v[(j + 1) % m];
            if (adjacent) { /* they share one end; overlapping beyond it is a spike */
                const sd_vec2 s = j == i + 1 ? b : a, x = j == i + 1 ? a : b, y = j == i + 1 ? d : c;
                if (orient(x, s, y) == 0 && (x.x - s.x) * (y.x - s.x) + (x.y - s.y) * (y.y - s.y) > 0)
                    return 0;
            } else if (meet(a, b, c, d)) {
                return 0;
            }
        }
    return fabs(sd_polygon2d_area(v, m)) > 0;
}

static sd_vec2 big[100001];

int main(void)
{
    sd_rng rng = sd_rng_seed(11);
    sd_error err;
    long agree = 0, total = 0, simple = 0;
    for (int t = 0; t < 20000; ++t) {
        sd_vec2 p[9];
        const int n = 4 + (int)(sd_rng_next(&rng) % 6);
        if (t % 2 == 0) {
            for (int i = 0; i < n; ++i)
                p[i] = sd_v2((double)(sd_rng_next(&rng) % 5), (double)(sd_rng_next(&rng) % 5));
        } else { /* star-shaped about (2, 2): sorted by angle */
            double ang[9];
            for (int i = 0; i < n; ++i) {
                p[i] = sd_v2((double)(sd_rng_next(&rng) % 5), (double)(sd_rng_next(&rng) % 5));
                ang[i] = atan2(p[i].y - 2.0 + 1e-3, p[i].x - 2.0 + 1e-3);
            }
            for (int i = 1; i < n; ++i)
                for (int j = i; j > 0 && ang[j] < ang[j - 1]; --j) {
                    const double ta = ang[j];
                    ang[j] = ang[j - 1];
                    ang[j - 1] = ta;
                    const sd_vec2 tp = p[j];
                    p[j] = p[j - 1];
                    p[j - 1] = tp;
                }
        }
        const int want = brute_simple(p, (size_t)n);
        sd_error_clear(&err);
        const sd_status st = sd_outline_check(p, (size_t)n, &err);
        const int got = st == SD_OK;
        ++total;
        simple += want;
        if (got == want) {
            ++agree;
        } else if (total - agree <= 5) {
            printf("FAIL polygon %d (brute force says %s):", t, want ? "simple" : "not simple");
            for (int i = 0; i < n; ++i)
                printf(" (%g, %g)", p[i].x, p[i].y);
            printf(" -> %s\n", err.msg);
        }
    }
    printf("     %ld random polygons, %ld simple by brute force\n", total, simple);
    CHECK_NEAR("verdicts that agree with brute force", (double)agree, (double)total, 0);
    CHECK(simple > 2000 && simple < total - 2000); /* both kinds well represented */

    /* a large star-shaped outline: accepted; one vertex moved across it: refused */
    const size_t n = 100000;
    for (size_t i = 0; i < n; ++i) {
        const double th = 2 * SD_PI_D * (double)i / (double)n;
        const double r = 0.02 * (1 + 0.3 * cos(7 * th) + 0.05 * sin(331 * th));
        big[i] = sd_v2(r * cos(th), r * sin(th));
    }
    big[n] = big[0]; /* the closing point */
    CHECK(sd_outline_check(big, n + 1, &err) == SD_OK);
    const sd_vec2 keep = big[40000];
    big[40000] = sd_v2(-big[40000].x * 1.5, -big[40000].y * 1.5); /* across the middle */
    sd_error_clear(&err);
    const sd_status st = sd_outline_check(big, n, &err);
    printf("%-4s 10^5 points, point 40001 moved across: %s\n",
           st == SD_ERR_INPUT && strstr(err.msg, "point 40001") ? "ok" : "FAIL", err.msg);
    CHECK(st == SD_ERR_INPUT && strstr(err.msg, "point 40001"));
    big[40000] = keep;
    /* a doubled point is harmless */
    big[500] = big[499];
    CHECK(sd_outline_check(big, n, &err) == SD_OK);
    return sd_test_summary();
}
