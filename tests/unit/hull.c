/* hull.c — the quickhull of geom/hull.h against qhull (the oracle) on random
 * clouds, points on a sphere, cube faces crowded with coplanar points and
 * duplicates, and a cloud far from the origin; plus the mesh invariants
 * (closed, consistently oriented, every point below every plane, Euler's
 * V - E + F = 2) and the degenerate inputs that must be refused. */
#include "test.h"

#include <libqhull_r/qhull_ra.h>
#include <string.h>

#include "core/rng.h"
#include "geom/hull.h"

static sd_hull_workspace ws;
static sd_hull hull;
static sd_vec3 pts[SD_HULL_MAX_POINTS];
static coordT coords[3 * SD_HULL_MAX_POINTS];

/* qhull's volume and vertex count of the same points (default options:
 * facets merged, so points on a face or an edge are not vertices). */
static int qhull_ref(const sd_vec3 *p, int n, double *vol, int *nvert)
{
    qhT qh_qh;
    qhT *qh = &qh_qh;
    for (int i = 0; i < n; ++i) {
        coords[3 * i] = p[i].x;
        coords[3 * i + 1] = p[i].y;
        coords[3 * i + 2] = p[i].z;
    }
    qh_zero(qh, stderr);
    char opts[] = "qhull";
    int rc = qh_new_qhull(qh, 3, n, coords, False, opts, NULL, stderr);
    if (rc == 0) {
        qh_getarea(qh, qh->facet_list);
        *vol = qh->totvol;
        *nvert = qh->num_vertices;
    }
    qh_freeqhull(qh, !qh_ALL);
    int curlong, totlong;
    qh_memfreeshort(qh, &curlong, &totlong);
    return rc;
}

/* Mesh invariants; returns the worst height of a point above a plane. */
static double check_mesh(const char *label, const sd_vec3 *p, int n)
{
    int bad_nbr = 0, bad_normal = 0;
    for (int t = 0; t < hull.ntri; ++t)
        for (int k = 0; k < 3; ++k) {
            int u = hull.nbr[t][k], a = hull.tri[t][k], b = hull.tri[t][(k + 1) % 3], found = 0;
            if (u < 0 || u >= hull.ntri) {
                bad_nbr++;
                continue;
            }
            for (int j = 0; j < 3; ++j)
                found |= hull.tri[u][j] == b && hull.tri[u][(j + 1) % 3] == a;
            bad_nbr += !found;
        }
    for (int t = 0; t < hull.ntri; ++t)
        bad_normal += fabs(sd_v3_norm(hull.normal[t]) - 1.0) > 1e-12;
    double worst = 0;
    for (int t = 0; t < hull.ntri; ++t)
        for (int i = 0; i < n; ++i)
            worst = fmax(worst, sd_v3_dot(hull.normal[t], p[i]) - hull.offset[t]);
    /* Euler over the vertices the triangulation uses */
    static char used[SD_HULL_MAX_POINTS];
    memset(used, 0, sizeof used);
    int nv = 0;
    for (int t = 0; t < hull.ntri; ++t)
        for (int k = 0; k < 3; ++k)
            if (!used[hull.tri[t][k]]) {
                used[hull.tri[t][k]] = 1;
                nv++;
            }
    int euler = nv - 3 * hull.ntri / 2 + hull.ntri;
    char buf[160];
    snprintf(buf, sizeof buf, "%s: neighbour links", label);
    CHECK_NEAR(buf, bad_nbr + bad_normal, 0, 0);
    snprintf(buf, sizeof buf, "%s: Euler V-E+F", label);
    CHECK_NEAR(buf, euler, 2, 0);
    snprintf(buf, sizeof buf, "%s: max height above a plane / eps", label);
    CHECK_NEAR(buf, worst / hull.eps, 0, 1.0);
    return worst;
}

static void compare(const char *label, const sd_vec3 *p, int n)
{
    sd_hull_status st = sd_hull_build(p, (size_t)n, &ws, &hull);
    CHECK(st == SD_HULL_OK);
    if (st != SD_HULL_OK) {
        printf("FAIL %s: status %d\n", label, (int)st);
        return;
    }
    double qv = 0;
    int qn = 0;
    sd_test_require(qhull_ref(p, n, &qv, &qn) == 0, "qhull", NULL);
    char buf[160];
    snprintf(buf, sizeof buf, "%s: volume vs qhull", label);
    CHECK_REL(buf, sd_hull_volume(&hull, p), qv, 1e-12);
    snprintf(buf, sizeof buf, "%s: vertex count vs qhull", label);
    CHECK_NEAR(buf, hull.nvert, qn, 0);
    check_mesh(label, p, n);
}

static sd_vec3 rand_unit(sd_rng *r)
{
    for (;;) {
        sd_vec3 v = sd_v3(sd_rng_range(r, -1, 1), sd_rng_range(r, -1, 1), sd_rng_range(r, -1, 1));
        double l = sd_v3_norm(v);
        if (l > 0.1 && l <= 1)
            return sd_v3_scale(v, 1 / l);
    }
}

static void shuffle(sd_vec3 *p, int n, sd_rng *r)
{
    for (int i = n - 1; i > 0; --i) {
        int j = (int)(sd_rng_next(r) % (uint64_t)(i + 1));
        sd_vec3 t = p[i];
        p[i] = p[j];
        p[j] = t;
    }
}

int main(void)
{
    sd_rng r = sd_rng_seed(11);

    /* random clouds in a box, several sizes */
    for (int trial = 0; trial < 5; ++trial) {
        int n = 8 + trial * 200;
        for (int i = 0; i < n; ++i)
            pts[i] = sd_v3(sd_rng_range(&r, -1, 1), sd_rng_range(&r, -0.5, 0.5), sd_rng_range(&r, -2, 2));
        char label[64];
        snprintf(label, sizeof label, "box cloud n=%d", n);
        compare(label, pts, n);
    }

    /* points on a sphere: all extreme */
    for (int i = 0; i < 2000; ++i)
        pts[i] = rand_unit(&r);
    compare("sphere n=2000", pts, 2000);
    CHECK_NEAR("sphere n=2000: every point a vertex", hull.nvert, 2000, 0);

    /* a cube's faces crowded with coplanar points (grids, edges, corners),
     * duplicates and interior points, in random order: 8 vertices, 6 faces */
    int n = 0;
    const int g = 7;
    for (int f = 0; f < 6; ++f)
        for (int i = 0; i < g; ++i)
            for (int j = 0; j < g; ++j) {
                double u = -1 + 2.0 * i / (g - 1), v = -1 + 2.0 * j / (g - 1), s = (f & 1) ? 1 : -1;
                pts[n++] = f < 2 ? sd_v3(s, u, v) : (f < 4 ? sd_v3(u, s, v) : sd_v3(u, v, s));
            }
    for (int i = 0; i < 100; ++i)
        pts[n++] = pts[(int)(sd_rng_next(&r) % 200u)]; /* duplicates */
    for (int i = 0; i < 100; ++i)
        pts[n++] = sd_v3(sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1));
    for (int i = 0; i < 200; ++i) { /* random points on random faces */
        double u = sd_rng_range(&r, -1, 1), v = sd_rng_range(&r, -1, 1);
        int f = (int)(sd_rng_next(&r) % 6u);
        double s = (f & 1) ? 1 : -1;
        pts[n++] = f < 2 ? sd_v3(s, u, v) : (f < 4 ? sd_v3(u, s, v) : sd_v3(u, v, s));
    }
    shuffle(pts, n, &r);
    compare("crowded cube faces", pts, n);
    CHECK_NEAR("crowded cube: vertices", hull.nvert, 8, 0);
    CHECK_NEAR("crowded cube: planar faces", hull.nface, 6, 0);
    CHECK_REL("crowded cube: volume", sd_hull_volume(&hull, pts), 8.0, 1e-14);

    /* a rotated, crowded cube far from the origin */
    sd_quat q = sd_quat_normalize(sd_quat_make(0.3, -0.5, 0.7, 0.2));
    for (int i = 0; i < n; ++i)
        pts[i] = sd_v3_add(sd_quat_rotate(q, pts[i]), sd_v3(1e3, -2e3, 5e2));
    compare("crowded cube rotated, at 1e3", pts, n);
    CHECK_NEAR("crowded cube rotated: vertices", hull.nvert, 8, 0);
    CHECK_NEAR("crowded cube rotated: planar faces", hull.nface, 6, 0);

    /* a random cloud where every point appears three times */
    for (int i = 0; i < 300; ++i)
        pts[i] = sd_v3(sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1));
    for (int i = 0; i < 600; ++i)
        pts[300 + i] = pts[i % 300];
    shuffle(pts, 900, &r);
    compare("tripled cloud", pts, 900);

    /* a cylinder-like set: two coplanar circles (many coplanar faces) */
    for (int i = 0; i < 400; ++i) {
        double a = 2 * SD_PI_D * i / 200;
        pts[i] = sd_v3(cos(a), sin(a), i < 200 ? -1 : 1);
    }
    compare("prism on 200-gons", pts, 400);
    CHECK_NEAR("prism on 200-gons: planar faces", hull.nface, 202, 0);

    /* an integer lattice: coplanar faces, collinear edges, and every
     * interior point exactly on many planes of the growing hull */
    n = 0;
    for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 9; ++j)
            for (int k = 0; k < 9; ++k)
                pts[n++] = sd_v3(i, j, k);
    shuffle(pts, n, &r);
    compare("9^3 lattice", pts, n);
    CHECK_NEAR("9^3 lattice: vertices", hull.nvert, 8, 0);
    /* a lattice rotated by a rational-free rotation, and a thin slab */
    for (int i = 0; i < n; ++i)
        pts[i] = sd_quat_rotate(q, pts[i]);
    compare("9^3 lattice rotated", pts, n);
    CHECK_NEAR("9^3 lattice rotated: vertices", hull.nvert, 8, 0);
    for (int i = 0; i < 1000; ++i)
        pts[i] = sd_v3(sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1), 1e-6 * sd_rng_range(&r, -1, 1));
    compare("slab 1e-6 thick", pts, 1000);
    /* the largest input: points on a sphere, perturbed by 1e-9 */
    for (int i = 0; i < SD_HULL_MAX_POINTS; ++i)
        pts[i] = sd_v3_scale(rand_unit(&r), 1 + 1e-9 * sd_rng_range(&r, -1, 1));
    compare("sphere n=max", pts, SD_HULL_MAX_POINTS);

    /* many small structured clouds: random boxes' faces crowded with
     * points, rotated and moved, with duplicates */
    int fails = 0;
    double worst_vol = 0;
    for (int trial = 0; trial < 200; ++trial) {
        sd_vec3 h = sd_v3(sd_rng_range(&r, 0.1, 2), sd_rng_range(&r, 0.1, 2), sd_rng_range(&r, 0.1, 2));
        sd_quat qt = sd_quat_normalize(sd_quat_make(sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1),
                                                    sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1)));
        sd_vec3 x = sd_v3(sd_rng_range(&r, -10, 10), sd_rng_range(&r, -10, 10), sd_rng_range(&r, -10, 10));
        int m = 8 + (int)(sd_rng_next(&r) % 120u);
        for (int i = 0; i < m; ++i) {
            sd_vec3 p =
                sd_v3(h.x * sd_rng_range(&r, -1, 1), h.y * sd_rng_range(&r, -1, 1), h.z * sd_rng_range(&r, -1, 1));
            if (i < 8)
                p = sd_v3((i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z);
            else if (i % 3) { /* on a face */
                int f = (int)(sd_rng_next(&r) % 3u);
                double sg = (sd_rng_next(&r) & 1) ? 1 : -1;
                if (f == 0)
                    p.x = sg * h.x;
                if (f == 1)
                    p.y = sg * h.y;
                if (f == 2)
                    p.z = sg * h.z;
            }
            pts[i] = sd_v3_add(sd_quat_rotate(qt, p), x);
        }
        for (int i = 0; i < 10; ++i)
            pts[m + i] = pts[(int)(sd_rng_next(&r) % (uint64_t)m)];
        m += 10;
        shuffle(pts, m, &r);
        double qv = 0;
        int qn = 0;
        if (sd_hull_build(pts, (size_t)m, &ws, &hull) != SD_HULL_OK || qhull_ref(pts, m, &qv, &qn) != 0) {
            fails++;
            continue;
        }
        worst_vol = fmax(worst_vol, fabs(sd_hull_volume(&hull, pts) - qv) / qv);
        fails += hull.nvert != 8 || qn != 8 || hull.nface != 6;
    }
    CHECK_NEAR("200 crowded boxes: failures (8 vertices, 6 faces)", fails, 0, 0);
    CHECK_NEAR("200 crowded boxes: worst volume vs qhull (rel)", worst_vol, 0, 1e-12);

    /* refusals */
    CHECK(sd_hull_build(pts, 3, &ws, &hull) == SD_HULL_TOO_FEW);
    CHECK(sd_hull_build(pts, SD_HULL_MAX_POINTS + 1, &ws, &hull) == SD_HULL_TOO_MANY);
    for (int i = 0; i < 50; ++i)
        pts[i] = sd_v3(sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1), 0.25);
    CHECK(sd_hull_build(pts, 50, &ws, &hull) == SD_HULL_DEGENERATE);
    for (int i = 0; i < 50; ++i) {
        double t = sd_rng_range(&r, -1, 1);
        pts[i] = sd_v3(t, 2 * t, -t);
    }
    CHECK(sd_hull_build(pts, 50, &ws, &hull) == SD_HULL_DEGENERATE);
    for (int i = 0; i < 50; ++i)
        pts[i] = sd_v3(1, 2, 3);
    CHECK(sd_hull_build(pts, 50, &ws, &hull) == SD_HULL_DEGENERATE);
    return sd_test_summary();
}
