/* mesh_vs_plane.c — a body on an inclined plane given three ways: the
 * analytic plane, a mesh of 2 triangles and a mesh of irregular triangles
 * (a grid whose interior vertices are moved at random, so edges and
 * corners lie under the contact), issue 30.
 *
 *  1. At rest below the friction angle (20°, tan 20° = 0.36 < mu = 0.5):
 *     a 10 mm cube face-down, yawed by 0.01 rad about the plane's normal
 *     (no body lands exactly square), as a box (GJK plane contact) and as
 *     a polyhedron (convex law). After settling it must not move: the
 *     drift along the slope below 1e-6 of its size per second. Before the
 *     plane contact's depth and point were made continuous in the tilt
 *     (geom/convex_contact.h, sd_convex_plane) the cube rocked between a
 *     face, an edge and a corner for ever and walked UP the slope at
 *     ~21 um/s on the plane and on both meshes alike.
 *  2. Sliding above it (35°): the acceleration along the slope within
 *     0.5 % of g (sin 35° - mu cos 35°) on all three surfaces.
 *  3. Pushed sideways at 0.3 m/s on a horizontal floor: the box stops
 *     where the analytic plane's stops.
 *
 * The mesh runs must follow the analytic run: position within 1e-6 of the
 * body's size and orientation within 1e-6 rad. Inside one plane group the
 * mesh contact is the plane contact with its force weighted by the clipped
 * share of the section, 1 to rounding (geom/mesh_contact.h), so the runs
 * differ only by rounding, which a body at rest does not amplify; 1e-6 is
 * far above that and far below any physical difference (the creep moved the
 * cube 1e-5 m in 0.5 s). A sliding body integrates the rounding for longer,
 * so case 2 compares positions within 1e-5 of the distance slid.
 *
 * SD_MESH_VS_PLANE_LONG=1 measures the drift over 1 s instead of 0.2 s.
 * Each check prints computed, expected and tolerance.
 */
#include "test.h"

#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define SIDE 0.01  /* m, the cube's edge */
#define MU 0.5
#define DT 1e-5

enum { PLANE, MESH2, MESH_IRREGULAR, SURFACES };
static const char *surface_name[SURFACES] = {"plane", "2 triangles", "irregular"};

/* The square [-L, L]^2 of the slope's own frame (x down the slope, y
 * across, z its normal), n x n cells, interior vertices moved at random
 * by up to 0.4 of a cell, then turned by theta about y into the world. */
static int add_slope_mesh(sd_world *w, int mat, double theta, double L, int n, int jitter)
{
    double c = cos(theta), s = sin(theta), h = 2 * L / n;
    size_t nv = (size_t)(n + 1) * (size_t)(n + 1);
    sd_v3d *v = malloc(nv * sizeof *v);
    uint32_t(*t)[3] = malloc((size_t)(2 * n * n) * sizeof *t);
    unsigned seed = 12345u;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            double x = -L + i * h, y = -L + j * h;
            if (jitter && i > 0 && j > 0 && i < n && j < n) {
                seed = seed * 1103515245u + 12345u;
                x += 0.8 * h * ((double)(seed >> 8 & 0xffff) / 65535.0 - 0.5);
                seed = seed * 1103515245u + 12345u;
                y += 0.8 * h * ((double)(seed >> 8 & 0xffff) / 65535.0 - 0.5);
            }
            v[j * (n + 1) + i] = sd_test_v(c * x, y, -s * x);
        }
    size_t nt = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, cc = a + (uint32_t)n + 1, d = cc + 1;
            uint32_t tri[2][3] = {{a, b, d}, {a, d, cc}};
            if ((i + j) & 1) {
                tri[0][2] = cc;
                tri[1][0] = b;
            }
            memcpy(t[nt++], tri[0], sizeof tri[0]);
            memcpy(t[nt++], tri[1], sizeof tri[1]);
        }
    sd_error err;
    sd_mesh_def md = sd_mesh_def_default();
    md.vertices = v;
    md.vertex_count = nv;
    md.triangles = (const uint32_t(*)[3])t;
    md.triangle_count = nt;
    md.material = mat;
    int k = sd_world_add_mesh(w, "slope", &md, &err);
    sd_test_require(k >= 0, "mesh", &err);
    free(v);
    free(t);
    return k;
}

typedef struct body_run {
    double along, across, normal; /* m, the centre in the slope's frame */
    double q[4];
} body_run;

/* A world with the slope (theta rad) as surface, and the cube (kind 0:
 * box, 1: polyhedron) face-down on it at distance x0 down the slope,
 * yawed by yaw about the normal, moving at v0 down the slope. */
static sd_world *make(int surface, int kind, double theta, double x0, double yaw, double v0)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = SD_LAW_HERTZ_MINDLIN;
    wd.dt = DT;
    wd.gravity = sd_test_v(0, 0, -9.81);
    wd.threads = 1;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "m";
    m.density = 2500;
    m.youngs_modulus = 1e7;
    m.poisson_ratio = 0.3;
    m.restitution = 0.3;
    m.friction = MU;
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    double c = cos(theta), s = sin(theta);
    if (surface == PLANE)
        sd_test_require(sd_world_add_plane(w, "slope", sd_test_v(0, 0, 0), sd_test_v(s, 0, c), mat, &err) >= 0,
                        "plane", &err);
    else if (surface == MESH2)
        add_slope_mesh(w, mat, theta, 0.15, 1, 0);
    else
        add_slope_mesh(w, mat, theta, 0.15, 20, 1); /* cells of 15 mm: the cube always spans edges */
    sd_shape_desc sd = sd_shape_desc_default();
    sd_v3d cv[8];
    if (kind == 0) {
        sd.kind = "box";
        sd.size = sd_test_v(SIDE, SIDE, SIDE);
    } else {
        sd.kind = "polyhedron";
        for (int k = 0; k < 8; ++k)
            cv[k] = sd_test_v(k & 1 ? SIDE / 2 : -SIDE / 2, k & 2 ? SIDE / 2 : -SIDE / 2, k & 4 ? SIDE / 2 : -SIDE / 2);
        sd.vertices = cv;
        sd.vertex_count = 8;
    }
    int shp = sd_world_add_shape(w, "cube", &sd, &err);
    sd_test_require(shp >= 0, "shape", &err);
    sd_body_def b;
    memset(&b, 0, sizeof b);
    double h = SIDE / 2; /* resting on a face: the overlap (~8 um) settles within the first steps */
    b.position = sd_test_v(c * x0 + s * h, 0, -s * x0 + c * h);
    b.velocity = sd_test_v(c * v0, 0, -s * v0);
    /* q = q_y(theta) q_z(yaw): yawed in the slope's frame, then tilted with it */
    double c0 = cos(theta / 2), s0 = sin(theta / 2), cy = cos(yaw / 2), sy = sin(yaw / 2);
    b.orientation[0] = c0 * cy;
    b.orientation[1] = -s0 * sy;
    b.orientation[2] = s0 * cy;
    b.orientation[3] = c0 * sy;
    b.shape = shp;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    return w;
}

static body_run state(sd_world *w, double theta)
{
    sd_particle_state p;
    sd_world_get_particle(w, 0, &p);
    double c = cos(theta), s = sin(theta);
    body_run r;
    r.along = c * p.position.x - s * p.position.z;
    r.across = p.position.y;
    r.normal = s * p.position.x + c * p.position.z;
    memcpy(r.q, p.quat, sizeof r.q);
    return r;
}

static void step(sd_world *w, double t)
{
    sd_error err;
    sd_test_require(sd_world_step(w, (long)(t / DT + 0.5), &err) == SD_OK, "step", &err);
}

/* The angle between two orientations, rad. */
static double angle_between(const double a[4], const double b[4])
{
    /* the rotation a^-1 b = (w, v): its angle is 2 atan2(|v|, |w|), exact near 0 */
    double w = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    double vx = a[0] * b[1] - a[1] * b[0] - a[2] * b[3] + a[3] * b[2];
    double vy = a[0] * b[2] + a[1] * b[3] - a[2] * b[0] - a[3] * b[1];
    double vz = a[0] * b[3] - a[1] * b[2] + a[2] * b[1] - a[3] * b[0];
    return 2 * atan2(sqrt(vx * vx + vy * vy + vz * vz), fabs(w));
}

static void compare(const char *what, const body_run *m, const body_run *p, double tol_x)
{
    char label[128];
    double dx = sqrt((m->along - p->along) * (m->along - p->along) + (m->across - p->across) * (m->across - p->across) +
                     (m->normal - p->normal) * (m->normal - p->normal));
    snprintf(label, sizeof label, "%s: |x - x(plane)| / size", what);
    CHECK_NEAR(label, dx / SIDE, 0.0, tol_x / SIDE);
    snprintf(label, sizeof label, "%s: angle to plane run (rad)", what);
    CHECK_NEAR(label, angle_between(m->q, p->q), 0.0, 1e-6);
}

/* 1. at rest on 20° */
static void test_rest(int kind, double measure)
{
    const double theta = 20 * PI / 180, settle = 0.2;
    body_run end[SURFACES];
    for (int sf = 0; sf < SURFACES; ++sf) {
        sd_world *w = make(sf, kind, theta, 0.0, 0.01, 0.0);
        step(w, settle);
        body_run a = state(w, theta);
        step(w, measure);
        end[sf] = state(w, theta);
        sd_world_destroy(w);
        double drift = sqrt((end[sf].along - a.along) * (end[sf].along - a.along) +
                            (end[sf].across - a.across) * (end[sf].across - a.across)) / measure;
        char label[128];
        snprintf(label, sizeof label, "%s on %s, 20 deg: drift / size (1/s)", kind ? "polyhedron" : "box",
                 surface_name[sf]);
        CHECK_NEAR(label, drift / SIDE, 0.0, 1e-6);
    }
    for (int sf = MESH2; sf < SURFACES; ++sf) {
        char what[96];
        snprintf(what, sizeof what, "%s on %s, 20 deg", kind ? "polyhedron" : "box", surface_name[sf]);
        compare(what, &end[sf], &end[PLANE], 1e-6 * SIDE);
    }
}

/* 2. sliding on 35° */
static void test_slide(int kind)
{
    const double theta = 35 * PI / 180, t0 = 0.05, t1 = 0.25;
    const double acc = 9.81 * (sin(theta) - MU * cos(theta));
    body_run end[SURFACES];
    for (int sf = 0; sf < SURFACES; ++sf) {
        sd_world *w = make(sf, kind, theta, -0.1, 0.01, 0.0);
        step(w, t0);
        body_run a = state(w, theta);
        sd_particle_state p;
        sd_world_get_particle(w, 0, &p);
        double va = cos(theta) * p.velocity.x - sin(theta) * p.velocity.z;
        step(w, t1 - t0);
        end[sf] = state(w, theta);
        sd_world_destroy(w);
        /* x(t1) - x(t0) = va (t1 - t0) + a (t1 - t0)^2 / 2 */
        double T = t1 - t0, got = 2 * (end[sf].along - a.along - va * T) / (T * T);
        char label[128];
        snprintf(label, sizeof label, "%s on %s, 35 deg: acceleration (m/s^2)", kind ? "polyhedron" : "box",
                 surface_name[sf]);
        CHECK_REL(label, got, acc, 0.005);
    }
    for (int sf = MESH2; sf < SURFACES; ++sf) {
        char what[96];
        snprintf(what, sizeof what, "%s on %s, 35 deg", kind ? "polyhedron" : "box", surface_name[sf]);
        compare(what, &end[sf], &end[PLANE], 1e-5 * fabs(end[PLANE].along + 0.1));
    }
}

/* 3. pushed sideways on a horizontal floor */
static void test_push(void)
{
    body_run end[SURFACES];
    for (int sf = 0; sf < SURFACES; ++sf) {
        sd_world *w = make(sf, 0, 0.0, -0.05, 0.01, 0.3);
        step(w, 0.15); /* stops after v0 / (mu g) = 0.061 s */
        end[sf] = state(w, 0.0);
        sd_world_destroy(w);
    }
    double slid = end[PLANE].along + 0.05, expect = 0.3 * 0.3 / (2 * MU * 9.81);
    CHECK_REL("box pushed on the plane: distance slid (m)", slid, expect, 0.01);
    for (int sf = MESH2; sf < SURFACES; ++sf) {
        char what[96];
        snprintf(what, sizeof what, "box pushed on %s", surface_name[sf]);
        compare(what, &end[sf], &end[PLANE], 1e-6 * SIDE);
    }
}

int main(void)
{
    int longrun = getenv("SD_MESH_VS_PLANE_LONG") && atoi(getenv("SD_MESH_VS_PLANE_LONG"));
    double measure = longrun ? 1.0 : 0.2;
    for (int kind = 0; kind < 2; ++kind) {
        test_rest(kind, measure);
        test_slide(kind);
    }
    test_push();
    return sd_test_summary();
}
