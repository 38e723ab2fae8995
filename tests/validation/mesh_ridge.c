/* mesh_ridge.c — bodies at a convex edge between two plane groups of a
 * mesh (issue 14's double push; the rules in geom/mesh_contact.h and
 * backend/items.h). The mesh: a flat group A (z = 0, x < 0) and a group B
 * sloping down at 30 degrees (x > 0) meeting in a ridge along y, each in
 * 32 triangles; its facets listed B first (the ridge edges are then active
 * on B's facets) and A first (on A's). No gravity, the linear law; each
 * check is one step of 1e-8 s from rest, the force read back.
 *
 *  1. a sphere (r 10 mm) whose centre follows the offset surface at
 *     r - delta0 (delta0 0.1 mm): over A, around the ridge and over B.
 *     Reference: the analytic solid {z <= 0} ∩ {z <= -x tan 30°}, whose
 *     nearest point gives the force k delta0 along the local normal (n_A,
 *     the ridge's radial direction, n_B). Before the rule, within
 *     sqrt(2 r delta0) = 1.4 mm of the ridge on one side the sphere got a
 *     face contact and an edge contact: up to twice the force.
 *  2. a rounded cube (10 mm, margin 0.1 mm: a 9.8 mm core) held flat on A at
 *     depth 0.2 mm, slid towards and over the ridge. Reference: the plane
 *     contact on A alone (the cube's part over the slope hangs in the
 *     air), i.e. the force of the cube on the analytic plane z = 0 times
 *     the share of its core's section over A, with no x component. Before the rule the slope's plane, which the
 *     cube sinks deep into behind the ridge, added a push along n_B.
 *  3. the same for a composite of two such cubes side by side (its
 *     elements' contacts, SD_WALL_PAIR_ELEMENTS, issue 30): each element
 *     feels only its share over A. Before the rule reached the elements
 *     the slope pushed them along n_B as it had pushed the cube.
 */
#include "test.h"

#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

static const double TH = 30.0 * PI / 180.0;

typedef struct ridge_mesh {
    sd_v3d v[2 * 25];
    uint32_t t[64][3];
    size_t nv, nt;
} ridge_mesh;

/* A: x in [-0.04, 0], B: x in [0, 0.04] along the slope; y in [-0.04, 0.04];
 * 4 x 4 cells of two triangles each. */
static void ridge_build(ridge_mesh *rm, int b_first)
{
    memset(rm, 0, sizeof *rm);
    for (int part = 0; part < 2; ++part) {
        int grp = b_first ? 1 - part : part; /* 0 = A, 1 = B */
        size_t base = rm->nv;
        for (int j = 0; j <= 4; ++j)
            for (int i = 0; i <= 4; ++i) {
                double s = 0.01 * i, y = -0.04 + 0.02 * j;
                rm->v[rm->nv++] = grp == 0 ? sd_test_v(-0.04 + s, y, 0)
                                           : sd_test_v(s * cos(TH), y, -s * sin(TH));
            }
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                uint32_t a = (uint32_t)(base + (size_t)(j * 5 + i)), b = a + 1, c = a + 5, d = c + 1;
                uint32_t tt[2][3] = {{a, b, d}, {a, d, c}}; /* normals up */
                memcpy(rm->t[rm->nt++], tt[0], sizeof tt[0]);
                memcpy(rm->t[rm->nt++], tt[1], sizeof tt[1]);
            }
    }
}

static sd_world *ridge_world(int mesh, int b_first, int *mat)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = SD_LAW_LINEAR;
    wd.dt = 1e-8;
    wd.gravity = sd_test_v(0, 0, 0);
    wd.threads = 1;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "steel";
    m.density = 2700;
    m.stiffness = 1e5;
    m.restitution = 0.5;
    m.friction = 0.3;
    *mat = sd_world_add_material(w, &m, &err);
    sd_test_require(*mat >= 0, "material", &err);
    if (mesh) {
        static ridge_mesh rm;
        ridge_build(&rm, b_first);
        sd_mesh_def md = sd_mesh_def_default();
        md.vertices = rm.v;
        md.vertex_count = rm.nv;
        md.triangles = (const uint32_t(*)[3])rm.t;
        md.triangle_count = rm.nt;
        md.material = *mat;
        sd_test_require(sd_world_add_mesh(w, "ridge", &md, &err) >= 0, "mesh", &err);
    } else {
        sd_test_require(sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), *mat, &err) >= 0,
                        "plane", &err);
    }
    return w;
}

/* The force on a sphere of radius r at centre x after one step. */
static sd_v3d sphere_force(int mesh, int b_first, double r, sd_v3d x)
{
    int mat;
    sd_world *w = ridge_world(mesh, b_first, &mat);
    sd_error err;
    sd_sphere_def s = {0};
    s.position = x;
    s.radius = r;
    s.material = mat;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    sd_particle_state p = {0};
    sd_world_get_particle(w, 0, &p);
    sd_world_destroy(w);
    return p.force;
}

static void test_sphere(void)
{
    const double r = 0.01, d0 = 1e-4, d = r - d0;
    sd_v3d fref = sphere_force(0, 0, r, sd_test_v(0, 0, d));
    double k_d0 = fref.z;
    printf("sphere on the analytic plane at depth %g m: force %.10g N\n", d0, k_d0);
    for (int b_first = 1; b_first >= 0; --b_first) {
        double worst = 0, worst_at = 0;
        int n = 0;
        /* path: s from -4 mm (over A) through the ridge's arc to +4 mm (over B) */
        for (int q = 0; q <= 40; ++q, ++n) {
            double s = -0.004 + 0.0002 * q;
            sd_v3d x, nrm;
            if (s <= 0) {
                x = sd_test_v(s, 0.003, d);
                nrm = sd_test_v(0, 0, 1);
            } else if (s < 0.001) { /* the arc around the ridge: angle s / 1 mm x 30 degrees */
                double phi = TH * s / 0.001;
                nrm = sd_test_v(sin(phi), 0, cos(phi));
                x = sd_test_v(d * nrm.x, 0.003, d * nrm.z);
            } else { /* over B, (s - 1 mm) down the slope */
                double u = s - 0.001;
                nrm = sd_test_v(sin(TH), 0, cos(TH));
                x = sd_test_v(u * cos(TH) + d * nrm.x, 0.003, -u * sin(TH) + d * nrm.z);
            }
            sd_v3d f = sphere_force(1, b_first, r, x);
            double err = sqrt(pow(f.x - k_d0 * nrm.x, 2) + pow(f.y - k_d0 * nrm.y, 2) + pow(f.z - k_d0 * nrm.z, 2));
            if (err > worst) {
                worst = err;
                worst_at = s;
            }
        }
        char label[96];
        snprintf(label, sizeof label, "sphere over the ridge (%s first): max |F - F_ref| / k d0", b_first ? "B" : "A");
        printf("  %d positions, worst at s = %.4g m\n", n, worst_at);
        CHECK_NEAR(label, worst / k_d0, 0.0, 1e-6);
    }
}

/* The force on a rounded cube (core half edge h, margin mg) centred at x,
 * unrotated; composite: two of them glued side by side along y. */
static int composite_mode;

/* The orientation (w, x, y, z) that shows shape s as it was given: its
 * principal axes (columns of R, principal to given frame) as a quaternion. */
static void given_frame(const sd_world *w, int s, double q[4])
{
    sd_shape_info info;
    sd_test_require(sd_world_get_shape(w, (size_t)s, &info) == SD_OK, "shape info", NULL);
    double R[3][3];
    for (int c = 0; c < 3; ++c) {
        R[0][c] = info.axes[c].x;
        R[1][c] = info.axes[c].y;
        R[2][c] = info.axes[c].z;
    }
    double det = R[0][0] * (R[1][1] * R[2][2] - R[1][2] * R[2][1]) - R[0][1] * (R[1][0] * R[2][2] - R[1][2] * R[2][0]) +
                 R[0][2] * (R[1][0] * R[2][1] - R[1][1] * R[2][0]);
    sd_test_require(det > 0.5, "principal axes right-handed", NULL);
    double t = R[0][0] + R[1][1] + R[2][2];
    if (t > 0) {
        double r = sqrt(1 + t) * 2;
        q[0] = r / 4, q[1] = (R[2][1] - R[1][2]) / r, q[2] = (R[0][2] - R[2][0]) / r, q[3] = (R[1][0] - R[0][1]) / r;
    } else if (R[0][0] > R[1][1] && R[0][0] > R[2][2]) {
        double r = sqrt(1 + R[0][0] - R[1][1] - R[2][2]) * 2;
        q[0] = (R[2][1] - R[1][2]) / r, q[1] = r / 4, q[2] = (R[0][1] + R[1][0]) / r, q[3] = (R[0][2] + R[2][0]) / r;
    } else if (R[1][1] > R[2][2]) {
        double r = sqrt(1 + R[1][1] - R[0][0] - R[2][2]) * 2;
        q[0] = (R[0][2] - R[2][0]) / r, q[1] = (R[0][1] + R[1][0]) / r, q[2] = r / 4, q[3] = (R[1][2] + R[2][1]) / r;
    } else {
        double r = sqrt(1 + R[2][2] - R[0][0] - R[1][1]) * 2;
        q[0] = (R[1][0] - R[0][1]) / r, q[1] = (R[0][2] + R[2][0]) / r, q[2] = (R[1][2] + R[2][1]) / r, q[3] = r / 4;
    }
}

static sd_v3d cube_force(int mesh, int b_first, double h, double mg, sd_v3d x)
{
    int mat;
    sd_world *w = ridge_world(mesh, b_first, &mat);
    sd_error err;
    sd_v3d v[8];
    for (int k = 0; k < 8; ++k)
        v[k] = sd_test_v((k & 1) ? h : -h, (k & 2) ? h : -h, (k & 4) ? h : -h);
    sd_shape_desc sh = sd_shape_desc_default();
    sh.kind = "polyhedron";
    sh.vertices = v;
    sh.vertex_count = 8;
    sh.margin = mg;
    int shape = sd_world_add_shape(w, "cube", &sh, &err);
    sd_test_require(shape >= 0, "shape", &err);
    if (composite_mode) {
        sd_composite_element el[2];
        memset(el, 0, sizeof el);
        for (int k = 0; k < 2; ++k) {
            el[k].shape = shape;
            el[k].position = sd_test_v(0, k ? 1.2 * h : -1.2 * h, 0);
        }
        sd_composite_desc cd = sd_composite_desc_default();
        cd.elements = el;
        cd.element_count = 2;
        shape = sd_world_add_composite(w, "pair", &cd, &err);
        sd_test_require(shape >= 0, "composite", &err);
    }
    sd_body_def b = {0};
    b.position = x;
    b.orientation[0] = 1;
    if (composite_mode) /* as glued: the principal frame turned back to the given one */
        given_frame(w, shape, b.orientation);
    b.shape = shape;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    sd_particle_state p = {0};
    sd_world_get_particle(w, 0, &p);
    sd_world_destroy(w);
    return p.force;
}

static void test_cube(const char *what)
{
    const double h = 0.005, mg = 0.0001, d0 = 2e-4;
    /* the depth on the analytic plane fixes the height: the lowest point d0 below z = 0 */
    double zc = 0;
    {
        /* find the core's half height plus rounding: the force on the plane is
         * linear in the depth, so two probes give the surface's height */
        sd_v3d f1 = cube_force(0, 0, h, mg, sd_test_v(0, 0, h));
        sd_v3d f2 = cube_force(0, 0, h, mg, sd_test_v(0, 0, h - 1e-4));
        double k = (f2.z - f1.z) / 1e-4, zs = h + f1.z / k; /* centre height at first touch */
        zc = zs - d0;
    }
    sd_v3d fref = cube_force(0, 0, h, mg, sd_test_v(0, 0, zc));
    printf("%s on the analytic plane at depth %g m: force %.10g N\n", what, d0, fref.z);
    for (int b_first = 1; b_first >= 0; --b_first) {
        double worst = 0, worst_at = 0;
        /* centre x from -h - 4 mm (the core's face all over A) to +0.8 h (most of it over B) */
        for (int q = 0; q <= 24; ++q) {
            double xc = -h - 0.004 + q * (0.004 + 1.8 * h) / 24;
            double hc = h - mg; /* the core: the vertices given, shrunk by the margin */
            double over_a = (hc - xc) / (2 * hc);
            over_a = over_a > 1 ? 1 : (over_a < 0 ? 0 : over_a);
            sd_v3d f = cube_force(1, b_first, h, mg, sd_test_v(xc, 0.002, zc));
            double err = sqrt(pow(f.x, 2) + pow(f.y, 2) + pow(f.z - fref.z * over_a, 2));
            if (err > worst) {
                worst = err;
                worst_at = xc;
            }
        }
        char label[96];
        snprintf(label, sizeof label, "%s over the ridge (%s first): max |F - F_A share| / F_ref", what,
                 b_first ? "B" : "A");
        printf("  worst at centre x = %.4g m\n", worst_at);
        CHECK_NEAR(label, worst / fref.z, 0.0, 1e-3);
    }
}

int main(void)
{
    test_sphere();
    test_cube("cube");
    composite_mode = 1;
    test_cube("composite");
    return sd_test_summary();
}
