/* mesh_engine.c — the numerics and the motions of mesh walls, checked
 * against values worked out by hand:
 *  - Sutherland–Hodgman (geom/clip.h, seed 000 Algorithm VII with the four
 *    standard cases): a unit square clipped by triangles that hold it, cut
 *    it, miss it; areas and centroids;
 *  - the closest point of a triangle and the feature it lies on;
 *  - the section of a cube by a plane through its centre at a tilt;
 *  - mesh motions: translation with a ramp, rotation at rpm with a ramp,
 *    a table, read back through sd_world_get_mesh after stepping.
 */
#include "test.h"

#include <string.h>

#include "geom/clip.h"
#include "geom/mesh_contact.h"

#define PI 3.14159265358979323846

static void test_clip(void)
{
    sd_vec2 sq[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    sd_vec2 out[SD_CLIP_MAX + 3], c;
    /* a triangle holding the square: the square itself */
    sd_vec2 big[3] = {{-1, -1}, {4, -1}, {-1, 4}};
    int n = sd_clip_triangle(sq, 4, big, out);
    CHECK_NEAR("square inside a triangle: area", sd_clip_area(out, n, &c), 1.0, 1e-15);
    CHECK_NEAR("square inside a triangle: centroid x", c.x, 0.5, 1e-15);
    /* the lower-left half: the triangle (0,0) (1,0) (0,1) cuts area 1/2, centroid 1/3 */
    sd_vec2 half[3] = {{0, 0}, {1, 0}, {0, 1}};
    n = sd_clip_triangle(sq, 4, half, out);
    CHECK_NEAR("square cut by its half triangle: area", sd_clip_area(out, n, &c), 0.5, 1e-15);
    CHECK_NEAR("square cut by its half triangle: centroid y", c.y, 1.0 / 3.0, 1e-15);
    /* a triangle crossing two sides: (0.5, -1) (2, 0.5) (0.5, 2) keeps x >= 0.5 and
     * the wedge: inside the square that is x in [0.5, 1], |y - 0.5| <= (x - 0.5) + 1.5 */
    sd_vec2 wedge[3] = {{0.5, -1}, {2, 0.5}, {0.5, 2}};
    n = sd_clip_triangle(sq, 4, wedge, out);
    CHECK_NEAR("square cut by a wedge: area (x >= 0.5)", sd_clip_area(out, n, NULL), 0.5, 1e-15);
    /* disjoint */
    sd_vec2 far[3] = {{3, 3}, {4, 3}, {3, 4}};
    n = sd_clip_triangle(sq, 4, far, out);
    CHECK_NEAR("disjoint: area", sd_clip_area(out, n, NULL), 0.0, 0.0);
    /* the hull of points with interior ones and duplicates */
    sd_vec2 pts[7] = {{0, 0}, {0.5, 0.5}, {1, 0}, {1, 1}, {0.2, 0.7}, {0, 1}, {1, 0}};
    int m = sd_clip_hull(pts, 7);
    CHECK_NEAR("hull of 7 points: corners", (double)m, 4.0, 0.0);
    CHECK_NEAR("hull of 7 points: area", sd_clip_area(pts, m, NULL), 1.0, 1e-15);
}

static void test_closest(void)
{
    sd_vec3 a = sd_v3(0, 0, 0), b = sd_v3(1, 0, 0), c = sd_v3(0, 1, 0);
    int f;
    sd_vec3 p = sd_clip_closest(sd_v3(0.2, 0.2, 1), a, b, c, &f);
    CHECK_NEAR("above the face: feature face", (double)f, (double)SD_CLIP_FACE, 0.0);
    CHECK_NEAR("above the face: point x", p.x, 0.2, 1e-15);
    p = sd_clip_closest(sd_v3(0.5, -1, 0.3), a, b, c, &f);
    CHECK_NEAR("beside edge 0 -> 1: feature", (double)f, (double)(SD_CLIP_EDGE0 + 0), 0.0);
    CHECK_NEAR("beside edge 0 -> 1: point x", p.x, 0.5, 1e-15);
    p = sd_clip_closest(sd_v3(1, 1, 0), a, b, c, &f);
    CHECK_NEAR("beside edge 1 -> 2: feature", (double)f, (double)(SD_CLIP_EDGE0 + 1), 0.0);
    CHECK_NEAR("beside edge 1 -> 2: point y", p.y, 0.5, 1e-15);
    p = sd_clip_closest(sd_v3(-1, 0.5, 0), a, b, c, &f);
    CHECK_NEAR("beside edge 2 -> 0: feature", (double)f, (double)(SD_CLIP_EDGE0 + 2), 0.0);
    p = sd_clip_closest(sd_v3(2, -1, 0), a, b, c, &f);
    CHECK_NEAR("beyond corner 1: feature", (double)f, (double)(SD_CLIP_CORNER0 + 1), 0.0);
}

static void test_section(void)
{
    /* a unit cube centred at the origin cut by z = 0: a unit square; cut by a
     * plane through the centre tilted by 30 degrees about x: a 1 x (1/cos 30) rectangle */
    sd_vec3 verts[8];
    for (int k = 0; k < 8; ++k)
        verts[k] = sd_v3((k & 1) ? 0.5 : -0.5, (k & 2) ? 0.5 : -0.5, (k & 4) ? 0.5 : -0.5);
    sd_shape sh;
    memset(&sh, 0, sizeof sh);
    sh.kind = SD_SHAPE_POLYHEDRON;
    sh.vcount = 8;
    sd_convex c;
    memset(&c, 0, sizeof c);
    c.shape = &sh;
    c.verts = verts;
    c.x = sd_v3_zero();
    c.q = sd_quat_identity();
    sd_wall_geom wg;
    memset(&wg, 0, sizeof wg);
    wg.q = sd_quat_identity();
    sd_vec2 sec[SD_CLIP_MAX + 3];
    sd_vec3 n = sd_v3(0, 0, 1), e1, e2;
    sd_clip_basis(n, &e1, &e2);
    int ns = sd_mesh_poly_section(&c, &wg, n, 0, e1, e2, sec);
    CHECK_NEAR("cube cut through its centre: section area", sd_clip_area(sec, ns, NULL), 1.0, 1e-14);
    n = sd_v3(0, sin(PI / 6), cos(PI / 6));
    sd_clip_basis(n, &e1, &e2);
    ns = sd_mesh_poly_section(&c, &wg, n, 0, e1, e2, sec);
    CHECK_NEAR("cube cut at 30 degrees: section area", sd_clip_area(sec, ns, NULL), 1.0 / cos(PI / 6), 1e-14);
}

static void test_motion(void)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = SD_LAW_LINEAR;
    wd.dt = 1e-3;
    wd.threads = 1;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "m";
    m.density = 1000;
    m.stiffness = 1e-2; /* soft: the checked time step allows dt = 1 ms; nothing touches */
    int mat = sd_world_add_material(w, &m, &err);
    sd_v3d v[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    uint32_t t[1][3] = {{0, 1, 2}};
    sd_mesh_def md = sd_mesh_def_default();
    md.vertices = v;
    md.vertex_count = 3;
    md.triangles = (const uint32_t(*)[3])t;
    md.triangle_count = 1;
    md.material = mat;
    int wa = sd_world_add_mesh(w, "a", &md, &err), wb = sd_world_add_mesh(w, "b", &md, &err),
        wc = sd_world_add_mesh(w, "c", &md, &err);
    sd_test_require(wa >= 0 && wb >= 0 && wc >= 0, "meshes", &err);
    sd_mesh_motion_def tr = sd_mesh_motion_def_default();
    tr.kind = SD_MESH_TRANSLATE;
    tr.velocity = sd_test_v(0.2, 0, 0);
    tr.start = 0.1;
    tr.ramp = 0.2;
    sd_test_require(sd_world_set_mesh_motion(w, wa, &tr, &err) == SD_OK, "translate", &err);
    sd_mesh_motion_def ro = sd_mesh_motion_def_default();
    ro.kind = SD_MESH_ROTATE;
    ro.axis_point = sd_test_v(1, 0, 0);
    ro.axis = sd_test_v(0, 0, 2); /* normalised */
    ro.rpm = 15; /* pi/2 rad/s */
    ro.ramp = 0.4;
    sd_test_require(sd_world_set_mesh_motion(w, wb, &ro, &err) == SD_OK, "rotate", &err);
    double rows[3][5] = {{0, 0, 0, 0, 0}, {0.5, 0.1, 0, 0, 90}, {2, 0.1, 0, 0, 90}};
    sd_mesh_motion_def tb = sd_mesh_motion_def_default();
    tb.kind = SD_MESH_TABLE;
    tb.axis = sd_test_v(0, 0, 1);
    tb.table = &rows[0][0];
    tb.table_rows = 3;
    sd_test_require(sd_world_set_mesh_motion(w, wc, &tb, &err) == SD_OK, "table", &err);
    sd_sphere_def s = {0};
    s.position = sd_test_v(0, 0, 5);
    s.radius = 0.01;
    s.material = mat;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    sd_test_require(sd_world_step(w, 250, &err) == SD_OK, "step", &err); /* t = 0.25 s */
    sd_mesh_info mi;
    double t_now = sd_world_time(w);
    sd_world_get_mesh(w, wa, &mi);
    /* 0.15 s into a 0.2 s ramp: 0.2 * 0.15^2 / (2 * 0.2) m, at 0.2 * 0.75 m/s */
    CHECK_NEAR("translate, in the ramp: x (m)", mi.translation[0], 0.2 * 0.15 * 0.15 / 0.4, 1e-12);
    CHECK_NEAR("translate, in the ramp: speed (m/s)", mi.velocity.x, 0.15, 1e-12);
    sd_world_get_mesh(w, wb, &mi);
    /* angle = w0 t^2 / (2 ramp), w0 = pi/2: the quaternion's angle; the axis point stays */
    double ang = PI / 2 * t_now * t_now / 0.8;
    CHECK_NEAR("rotate, in the ramp: quaternion w", mi.rotation[0], cos(ang / 2), 1e-12);
    CHECK_NEAR("rotate, in the ramp: omega z (rad/s)", mi.angular_velocity.z, PI / 2 * t_now / 0.4, 1e-12);
    /* x' = R (x - c) + c: the axis point maps to itself, R c + trans = c */
    double cxr = cos(ang) * 1 + mi.translation[0], cyr = sin(ang) * 1 + mi.translation[1];
    CHECK_NEAR("rotate: the axis point stays (x)", cxr, 1.0, 1e-12);
    CHECK_NEAR("rotate: the axis point stays (y)", cyr, 0.0, 1e-12);
    sd_world_get_mesh(w, wc, &mi);
    /* t = 0.25: halfway to row 2: d = 0.05, angle 45 deg */
    CHECK_NEAR("table at t = 0.25 s: quaternion w", mi.rotation[0], cos(PI / 8), 1e-12);
    /* the reference point (the triangle's box centre (0.5, 0.5, 0)) turned by 45 degrees
     * sits at sqrt(1/2) on y from the axis: its x speed is dd/dt - omega sqrt(1/2) */
    CHECK_NEAR("table at t = 0.25 s: reference point speed x (m/s)", mi.velocity.x, 0.2 - PI * sqrt(0.5), 1e-12);
    CHECK_NEAR("table at t = 0.25 s: angular rate (rad/s)", mi.angular_velocity.z, PI / 2 / 0.5, 1e-12);
    CHECK_NEAR("table at t = 0.25 s: the origin maps to d (m)", mi.translation[0], 0.05, 1e-12);
    /* refused input */
    sd_mesh_motion_def bad = tb;
    double rows_bad[2][5] = {{0, 0, 0, 0, 0}, {0, 1, 0, 0, 0}};
    bad.table = &rows_bad[0][0];
    bad.table_rows = 2;
    CHECK(sd_world_set_mesh_motion(w, wc, &bad, &err) == SD_ERR_INPUT);
    CHECK(strstr(err.msg, "increase") != NULL);
    CHECK(sd_world_set_mesh_motion(w, 99, &tb, &err) == SD_ERR_INPUT);
    sd_world_destroy(w);
}

int main(void)
{
    test_clip();
    test_closest();
    test_section();
    test_motion();
    return sd_test_summary();
}
