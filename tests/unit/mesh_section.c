/* mesh_section.c — the section of a body without vertices by a facet
 * plane (geom/mesh_contact.h, sd_mesh_convex_section: 24 rim points from
 * support points, seed 000 §2.4's overlap area for every kind), against
 * the analytic areas:
 *  - a sphere (point core, radius 10 mm) cut 6 mm from its centre: a disc
 *    of radius 8 mm; the 24-gon of rim points has (24/2pi) sin(2pi/24) of
 *    its area, and every rim point lies on the circle;
 *  - a rotated ellipsoid (semi-axes 30, 20, 10 mm) cut by a plane: an
 *    ellipse of area pi a b c / sqrt(n^T M n) (1 - d^2 / n^T M n), M =
 *    diag(a^2, b^2, c^2) in the body frame (the polygon within 1.5 %);
 *  - a cylinder (radius 10 mm, half length 25 mm) lying along x, cut
 *    4 mm below its axis: the rectangle 50 x 2 sqrt(100 - 16) mm, exact
 *    (its corners are support points of the cap rims);
 *  - a box (half edges 10, 15, 20 mm) cut parallel to a face: the 20 x 30
 *    mm rectangle, exact;
 *  - a plane that misses the body: no section;
 *  - the weight of the sphere's section on a triangle holding half of it:
 *    w = A_clip / A = 1/2 (the polygon is symmetric);
 *  - a polyhedron with 1,024 crossings (a 32-gon prism cut half way): the
 *    32-gon exactly (sd_mesh_poly_section keeps every crossing);
 *  - the root search against the golden-section search it replaced
 *    (issue 30: that search cost 38 support points and a sine and a
 *    cosine per rim point, 90 % of a hopper's step), for 600 random poses
 *    of rounded and sharp boxes, cylinders, cones, ellipsoids and spheres
 *    against a turned and moved mesh: the same section area and centroid
 *    (to 1e-6 of the area and of the body's size);
 *  - sd_clip_hull of 64 points with duplicates and collinear runs: the
 *    convex square (the old gift wrapping could return 64 points that
 *    were not convex, and their clipping overran its workspace).
 */
#include "test.h"

#include <string.h>

#include "geom/clip.h"
#include "geom/mesh_contact.h"

#define PI 3.14159265358979323846

/* ---- the reference: the golden-section search the root search replaced
 * (issue 30), kept here to show the new rim points are the same ---------- */

/* The section's support in plane direction u (seed 000 §2.4's section,
 * by LP duality): h_S(u) = min over t of h_K(u + t n) - t off, with
 * t = tan(phi): f(phi) = (h_K(d) - sin(phi) off) / cos(phi), d = cos(phi)
 * u + sin(phi) n, unimodal in phi on (-pi/2, pi/2). K is the rounded
 * body (core support plus the swept radius), all in the mesh frame;
 * *pt gets K's support point along d, a point of the section's rim at
 * the minimum. */
static sd_real sd_ref_section_f(const sd_convex *c, const sd_wall_geom *wg, sd_vec3 u, sd_vec3 n,
                                                 sd_real off, sd_real phi, sd_vec3 *pt)
{
    sd_real cp = sd_cos(phi), sp = sd_sin(phi);
    sd_vec3 dm = sd_v3_add(sd_v3_scale(u, cp), sd_v3_scale(n, sp));
    sd_vec3 dw = sd_quat_rotate(wg->q, dm);
    sd_vec3 sw = sd_v3_madd(sd_convex_support_core(c, dw), c->shape->radius, dw);
    *pt = sd_mesh_to_frame(wg->q, wg->trans, sw);
    return (sd_v3_dot(*pt, dm) - sp * off) / cp;
}

/* The section of a posed convex body (any kind: spheres, ellipsoids,
 * cylinders, cones, boxes, with their rounding) by the plane n . x = off
 * of the mesh frame, as the polygon of its rim points in
 * 24 plane directions, hulled, in the plane basis
 * (e1, e2); returns its vertex count (0 when the plane misses the body).
 * Each rim point is the support point of the body at the minimum of
 * sd_ref_section_f, found by golden-section search (34
 * steps: phi to 1e-7 rad), then put on the plane. */
static int sd_ref_convex_section(const sd_convex *c, const sd_wall_geom *wg, sd_vec3 n, sd_real off,
                                                  sd_vec3 e1, sd_vec3 e2, sd_vec2 *sec)
{
    const sd_real half = SD_R(1.5707963267948966) - SD_R(1e-9), g = SD_R(0.6180339887498949);
    /* cos and sin of k 2 pi / 24 */
    const sd_real cs[6] = {SD_R(1.0), SD_R(0.9659258262890683), SD_R(0.8660254037844386), SD_R(0.7071067811865476),
                           SD_R(0.5), SD_R(0.25881904510252074)};
    int np = 0;
    for (int k = 0; k < 24; ++k) {
        int q = k % 6, quad = k / 6;
        sd_real ca = cs[q], sa = q == 0 ? SD_R(0.0) : cs[6 - q]; /* angle q pi / 12 in this quadrant */
        sd_real cx = quad == 0 ? ca : (quad == 1 ? -sa : (quad == 2 ? -ca : sa));
        sd_real cy = quad == 0 ? sa : (quad == 1 ? ca : (quad == 2 ? -sa : -ca));
        sd_vec3 u = sd_v3_add(sd_v3_scale(e1, cx), sd_v3_scale(e2, cy));
        sd_real a = -half, b = half;
        sd_real x1 = b - g * (b - a), x2 = a + g * (b - a);
        sd_vec3 p1, p2; /* the support points at x1, x2 (unused past the search) */
        sd_real f1 = sd_ref_section_f(c, wg, u, n, off, x1, &p1), f2 = sd_ref_section_f(c, wg, u, n, off, x2, &p2);
        for (int it = 0; it < 34; ++it) {
            if (f1 <= f2) {
                b = x2;
                x2 = x1;
                f2 = f1;
                p2 = p1;
                x1 = b - g * (b - a);
                f1 = sd_ref_section_f(c, wg, u, n, off, x1, &p1);
            } else {
                a = x1;
                x1 = x2;
                f1 = f2;
                p1 = p2;
                x2 = a + g * (b - a);
                f2 = sd_ref_section_f(c, wg, u, n, off, x2, &p2);
            }
        }
        /* the support points at the bracket's ends: on a smooth rim both
         * are on the plane; at a kink (an edge or a corner of a box, a
         * cylinder's cap rim) they are the two ends of the edge crossing
         * it, and the rim point is where that segment (inside the body)
         * meets the plane */
        sd_vec3 pa, pb;
        (void)sd_ref_section_f(c, wg, u, n, off, a, &pa);
        (void)sd_ref_section_f(c, wg, u, n, off, b, &pb);
        sd_real ha = sd_v3_dot(n, pa) - off, hb = sd_v3_dot(n, pb) - off;
        sd_vec3 p;
        if ((ha <= SD_R(0.0) && hb >= SD_R(0.0)) || (ha >= SD_R(0.0) && hb <= SD_R(0.0)))
            p = ha == hb ? pa : sd_v3_add(pa, sd_v3_scale(sd_v3_sub(pb, pa), ha / (ha - hb)));
        else if (sd_fabs(ha) <= SD_R(1e-6) * (c->shape->bound > 0 ? c->shape->bound : SD_R(1.0)))
            p = pa;
        else
            return 0; /* the rim is off the plane: the plane misses the body */
        p = sd_v3_sub(p, sd_v3_scale(n, sd_v3_dot(n, p) - off));
        sec[np++] = sd_v2(sd_v3_dot(p, e1), sd_v3_dot(p, e2));
    }
    return sd_clip_hull(sec, np);
}

/* Section area and centroid by sd_mesh_convex_section (ref = 0) or by the
 * reference search (ref = 1) of body c against the plane n . x = off of
 * a mesh posed by wg. */
static double sd_sec_both(const sd_convex *c, const sd_wall_geom *wg, sd_vec3 n, double off, int ref, sd_vec2 *cen)
{
    sd_vec3 e1, e2;
    sd_vec2 sec[SD_CLIP_MAX + 3];
    sd_clip_basis(n, &e1, &e2);
    int ns = ref ? sd_ref_convex_section(c, wg, n, (sd_real)off, e1, e2, sec)
                 : sd_mesh_convex_section(c, wg, n, (sd_real)off, e1, e2, sec);
    *cen = sd_v2(0, 0);
    return ns >= 3 ? sd_clip_area(sec, ns, cen) : 0.0;
}

static double sd_sec_rand(unsigned *st)
{
    *st = *st * 1664525u + 1013904223u;
    return (double)(*st >> 8) / 16777216.0;
}

static double sd_sec_area(sd_shape *sh, sd_vec3 x, sd_quat q, sd_vec3 n, double off, sd_vec2 *sec, int *ns)
{
    sd_convex c;
    memset(&c, 0, sizeof c);
    c.shape = sh;
    c.x = x;
    c.q = q;
    sd_wall_geom wg;
    memset(&wg, 0, sizeof wg);
    wg.q = sd_quat_identity();
    sd_vec3 e1, e2;
    sd_clip_basis(n, &e1, &e2);
    *ns = sd_mesh_convex_section(&c, &wg, n, (sd_real)off, e1, e2, sec);
    return *ns >= 3 ? sd_clip_area(sec, *ns, NULL) : 0.0;
}

static sd_shape sd_sec_shape(int kind, double ax, double ay, double az, double radius)
{
    sd_shape sh;
    memset(&sh, 0, sizeof sh);
    sh.kind = kind;
    sh.a = sd_v3(ax, ay, az);
    sh.radius = radius;
    sh.bound = sqrt(ax * ax + ay * ay + az * az) + radius;
    return sh;
}

int main(void)
{
    sd_vec2 sec[SD_CLIP_MAX + 3];
    int ns;
    const double poly24 = 24.0 / (2 * PI) * sin(2 * PI / 24);

    /* sphere: point core at z = 6 mm, radius 10 mm, cut by z = 0 */
    sd_shape sp = sd_sec_shape(SD_SHAPE_SPHERE, 0, 0, 0, 0.01);
    double a = sd_sec_area(&sp, sd_v3(0.001, -0.002, 0.006), sd_quat_identity(), sd_v3(0, 0, 1), 0.0, sec, &ns);
    double disc = PI * (0.01 * 0.01 - 0.006 * 0.006);
    printf("sphere section: %d rim points\n", ns);
    CHECK(ns == 24);
    CHECK_REL("sphere cut 6 mm off centre: area / (24-gon of the 8 mm disc)", a, poly24 * disc, 1e-6);
    double rim = 0;
    for (int k = 0; k < ns; ++k) {
        sd_vec3 e1, e2;
        sd_clip_basis(sd_v3(0, 0, 1), &e1, &e2);
        /* the centre's coordinates in the plane basis */
        double cx = 0.001 * e1.x - 0.002 * e1.y, cy = 0.001 * e2.x - 0.002 * e2.y;
        rim = fmax(rim, fabs(hypot(sec[k].x - cx, sec[k].y - cy) - 0.008));
    }
    CHECK_NEAR("sphere: rim points off the 8 mm circle, max (m)", rim, 0.0, 1e-9);

    /* the weight on a triangle holding the half x >= x_c of it */
    {
        sd_vec3 e1, e2;
        sd_clip_basis(sd_v3(0, 0, 1), &e1, &e2);
        sd_vec2 c0;
        double a0 = sd_clip_area(sec, ns, &c0);
        /* a big triangle whose edge runs through the disc's centre along e2 */
        sd_vec2 t[3] = {{c0.x, c0.y - 1}, {c0.x + 2, c0.y}, {c0.x, c0.y + 1}};
        sd_vec2 out[SD_CLIP_MAX + 3];
        int no = sd_clip_triangle(sec, ns, t, out);
        CHECK_NEAR("sphere section on a triangle holding half: w", sd_clip_area(out, no, NULL) / a0, 0.5, 1e-9);
    }

    /* ellipsoid, turned 40 degrees about (1, 1, 1) / sqrt 3, cut by the plane n . x = d */
    {
        sd_shape el = sd_sec_shape(SD_SHAPE_ELLIPSOID, 0.03, 0.02, 0.01, 0.0);
        double s40 = sin(0.5 * 40 * PI / 180) / sqrt(3.0);
        sd_quat q = sd_quat_make(cos(0.5 * 40 * PI / 180), s40, s40, s40);
        sd_vec3 n = sd_v3_normalize(sd_v3(0.2, -0.3, 1.0));
        double d = -0.004; /* the centre (origin) 4 mm in front of the plane */
        a = sd_sec_area(&el, sd_v3(0, 0, 0), q, n, d, sec, &ns);
        sd_vec3 nb = sd_quat_rotate_inv(q, n); /* the normal in the body frame */
        double nmn = 0.03 * 0.03 * nb.x * nb.x + 0.02 * 0.02 * nb.y * nb.y + 0.01 * 0.01 * nb.z * nb.z;
        double exact = PI * 0.03 * 0.02 * 0.01 / sqrt(nmn) * (1 - d * d / nmn);
        printf("ellipsoid section: %d rim points, area %.6g m^2, analytic %.6g m^2, ratio %.5f\n", ns, a, exact,
               a / exact);
        CHECK_REL("tilted ellipsoid: section area vs the analytic ellipse (1.5 %)", a, exact, 0.015);
    }

    /* cylinder along x (its axis z turned onto x), cut 4 mm below the axis */
    {
        sd_shape cy = sd_sec_shape(SD_SHAPE_CYLINDER, 0.01, 0.01, 0.025, 0.0);
        sd_quat q = sd_quat_make(cos(PI / 4), 0, sin(PI / 4), 0); /* 90 degrees about y: z -> x */
        a = sd_sec_area(&cy, sd_v3(0, 0, 0.004), q, sd_v3(0, 0, 1), 0.0, sec, &ns);
        double exact = 0.05 * 2 * sqrt(0.01 * 0.01 - 0.004 * 0.004);
        CHECK_REL("lying cylinder: section area vs the rectangle", a, exact, 1e-7);
    }

    /* box cut parallel to its z faces */
    {
        sd_shape bx = sd_sec_shape(SD_SHAPE_BOX, 0.01, 0.015, 0.02, 0.0);
        a = sd_sec_area(&bx, sd_v3(0, 0, 0.005), sd_quat_identity(), sd_v3(0, 0, 1), 0.0, sec, &ns);
        CHECK_REL("box cut parallel to a face: section area vs 20 x 30 mm", a, 0.02 * 0.03, 1e-9);
        a = sd_sec_area(&bx, sd_v3(0, 0, 0.05), sd_quat_identity(), sd_v3(0, 0, 1), 0.0, sec, &ns);
        CHECK(ns == 0);
        CHECK_NEAR("box 50 mm above the plane: no section", a, 0.0, 0.0);
    }
    /* the root search against the golden-section search it replaced:
     * random bodies of every kind without vertices, random poses, a mesh
     * frame turned and moved, planes through the body */
    {
        unsigned st = 30;
        double worst_a = 0, worst_c = 0;
        int cut = 0, agree_miss = 1;
        for (int trial = 0; trial < 600; ++trial) {
            static const int kinds[5] = {SD_SHAPE_BOX, SD_SHAPE_CYLINDER, SD_SHAPE_CONE, SD_SHAPE_ELLIPSOID,
                                         SD_SHAPE_SPHERE};
            int kind = kinds[trial % 5];
            double ax = 0.001 + 0.003 * sd_sec_rand(&st), ay = 0.001 + 0.003 * sd_sec_rand(&st);
            double az = 0.001 + 0.003 * sd_sec_rand(&st);
            double rr = (trial / 5) % 2 ? 0.0004 * sd_sec_rand(&st) : 0.0; /* rounded and sharp */
            if (kind == SD_SHAPE_SPHERE)
                ax = ay = az = 0, rr = 0.002 + 0.001 * sd_sec_rand(&st);
            if (kind == SD_SHAPE_CYLINDER || kind == SD_SHAPE_CONE)
                ay = ax;
            sd_shape sh = sd_sec_shape(kind, ax, ay, az, rr);
            sd_quat q = sd_quat_normalize(sd_quat_make(sd_sec_rand(&st) - 0.5, sd_sec_rand(&st) - 0.5,
                                                       sd_sec_rand(&st) - 0.5, sd_sec_rand(&st) - 0.5));
            sd_wall_geom wg;
            memset(&wg, 0, sizeof wg);
            wg.q = sd_quat_normalize(sd_quat_make(1.0, 0.3, -0.2, 0.5));
            wg.trans = sd_v3(0.01, -0.02, 0.005);
            sd_convex c;
            memset(&c, 0, sizeof c);
            c.shape = &sh;
            c.x = sd_v3(0.02 * sd_sec_rand(&st), 0.02 * sd_sec_rand(&st), 0.02 * sd_sec_rand(&st));
            c.q = q;
            sd_vec3 n = sd_v3_normalize(sd_v3(sd_sec_rand(&st) - 0.5, sd_sec_rand(&st) - 0.5, sd_sec_rand(&st) - 0.5));
            /* the plane at a random height through the body (and now and then past it) */
            sd_vec3 xm = sd_quat_rotate_inv(wg.q, sd_v3_sub(c.x, wg.trans));
            double off = sd_v3_dot(n, xm) + (2.4 * sd_sec_rand(&st) - 1.2) * sh.bound;
            sd_vec2 c0, c1;
            double a0 = sd_sec_both(&c, &wg, n, off, 1, &c0), a1 = sd_sec_both(&c, &wg, n, off, 0, &c1);
            if (a0 > 0 || a1 > 0) {
                cut++;
                worst_a = fmax(worst_a, fabs(a1 - a0) / fmax(a0, a1));
                worst_c = fmax(worst_c, hypot(c1.x - c0.x, c1.y - c0.y) / sh.bound);
            }
            /* a plane that grazes the body may give a sliver of no area either way */
            agree_miss &= (a0 > 1e-6 * sh.bound * sh.bound) <= (a1 > 0) && (a1 > 1e-6 * sh.bound * sh.bound) <= (a0 > 0);
        }
        printf("root search vs golden-section search: %d of 600 planes cut the body; largest area difference "
               "%.3g (relative), centroid %.3g (of the body's size)\n", cut, worst_a, worst_c);
        CHECK(cut > 300);
        CHECK(agree_miss);
        CHECK_NEAR("root vs golden-section search: section area, largest relative difference", worst_a, 0.0, 1e-6);
        CHECK_NEAR("root vs golden-section search: centroid, largest difference / size", worst_c, 0.0, 1e-6);
    }
    /* a polyhedron with many crossings: a prism over a regular 32-gon
     * (64 vertices) cut half way up: 32 x 32 crossings, every one kept
     * (they used to be cut at the first 64), the section the 32-gon */
    {
        static sd_vec3 pv[64];
        for (int k = 0; k < 32; ++k)
            for (int z = 0; z < 2; ++z)
                pv[2 * k + z] = sd_v3(0.01 * cos(2 * PI * k / 32), 0.01 * sin(2 * PI * k / 32), z ? 0.01 : -0.01);
        sd_shape pr;
        memset(&pr, 0, sizeof pr);
        pr.kind = SD_SHAPE_POLYHEDRON;
        pr.vcount = 64;
        sd_convex c;
        memset(&c, 0, sizeof c);
        c.shape = &pr;
        c.verts = pv;
        c.x = sd_v3(0, 0, 0.002);
        c.q = sd_quat_identity();
        sd_wall_geom wg;
        memset(&wg, 0, sizeof wg);
        wg.q = sd_quat_identity();
        sd_vec3 e1, e2;
        sd_clip_basis(sd_v3(0, 0, 1), &e1, &e2);
        ns = sd_mesh_poly_section(&c, &wg, sd_v3(0, 0, 1), 0.0, e1, e2, sec);
        double gon = 0.5 * 32 * 0.01 * 0.01 * sin(2 * PI / 32);
        printf("32-gon prism section: %d corners\n", ns);
        CHECK(ns >= 32); /* the 32 corners, and edge midpoints kept by round-off */
        CHECK_REL("32-gon prism cut half way: section area vs the 32-gon", ns >= 3 ? sd_clip_area(sec, ns, NULL) : 0.0,
                  gon, 1e-12);
    }
    /* the hull of points with duplicates and collinear runs: convex, the square */
    {
        sd_vec2 pts[SD_CLIP_MAX];
        int n = 0;
        for (int r = 0; r < 4 && n < SD_CLIP_MAX; ++r)
            for (int k = 0; k <= 10 && n + 4 <= SD_CLIP_MAX; ++k) {
                double t = 0.1 * k;
                pts[n++] = sd_v2(t, 0);
                pts[n++] = sd_v2(1, t);
                pts[n++] = sd_v2(1 - t, 1);
                pts[n++] = sd_v2(0, 1 - t + 1e-17 * k); /* duplicates to round-off */
            }
        int m = sd_clip_hull(pts, n);
        int convex = 1;
        for (int k = 0; k < m; ++k) {
            sd_vec2 pa = pts[k], pb = pts[(k + 1) % m], pc = pts[(k + 2) % m];
            convex &= sd_clip_cross(sd_v2(pb.x - pa.x, pb.y - pa.y), sd_v2(pc.x - pa.x, pc.y - pa.y)) > 0;
        }
        printf("hull of %d points with duplicates and collinear runs: %d corners\n", n, m);
        CHECK(convex && m == 4);
        CHECK_NEAR("that hull's area", sd_clip_area(pts, m, NULL), 1.0, 1e-15);
    }
    return sd_test_summary();
}
