/* mesh_ridge2d.c — a 2D body at a convex edge between two plane groups of
 * a mesh cut by z = 0 (the planar mode; issue 30: the ridge rule for the
 * planar kind, geom/mesh_contact2d.h and backend/items.h). The mesh, as
 * tests/validation/mesh_ridge.c's but standing on z = 0: a flat group A
 * (y = 0, x < 0) and a group B sloping down at 30 degrees (x > 0) meeting
 * in a ridge along z, each a strip z in [-10, 10] mm of 8 triangles; its
 * facets listed B first (the ridge edges then active on B's facets) and A
 * first. No gravity, the linear law; each check is one step of 1e-8 s from
 * rest, the force read back.
 *
 * A rounded square (core 9.8 mm, rounding 0.5 mm) held flat on A at depth
 * 0.2 mm, slid towards and over the ridge. Reference: the contact with A
 * alone (the square's part beyond the ridge hangs over the slope), i.e.
 * the force on the analytic wall y = 0 times the share of the square's
 * chord (its section by the line y = 0, half-length 4.9 mm + sqrt(r^2 - (r
 * - d)^2) = 5.3 mm) over A, with no x component: within 1e-3 of the
 * analytic wall's force. Before the rule the contact with A was all or
 * nothing as its point (the middle of the pressed face) crossed the ridge:
 * the force dropped from the whole to none with the square half over A,
 * an error of half the force (measured on the code before it, in the
 * commit message); nor did the slope, which the square sinks deep into
 * behind the ridge, give way.
 */
#include "test.h"

#include <string.h>

#define PI 3.14159265358979323846

static const double TH = 30.0 * PI / 180.0;

typedef struct strip_mesh {
    sd_v3d v[2 * 15];
    uint32_t t[32][3];
    size_t nv, nt;
} strip_mesh;

/* A: x in [-0.04, 0] on y = 0, B: s in [0, 0.04] along the slope; z in
 * [-0.01, 0.01]; 4 x 1 cells of two triangles each. */
static void strip_build(strip_mesh *sm, int b_first)
{
    memset(sm, 0, sizeof *sm);
    for (int part = 0; part < 2; ++part) {
        int grp = b_first ? 1 - part : part; /* 0 = A, 1 = B */
        size_t base = sm->nv;
        for (int j = 0; j <= 1; ++j)
            for (int i = 0; i <= 4; ++i) {
                double s = 0.01 * i, z = -0.01 + 0.02 * j;
                sm->v[sm->nv++] = grp == 0 ? sd_test_v(-0.04 + s, 0, z) : sd_test_v(s * cos(TH), -s * sin(TH), z);
            }
        for (int i = 0; i < 4; ++i) {
            uint32_t a = (uint32_t)(base + (size_t)i), b = a + 1, c = a + 5, d = c + 1;
            uint32_t tt[2][3] = {{a, c, d}, {a, d, b}}; /* (c - a) x (d - a): the normal up the y side */
            memcpy(sm->t[sm->nt++], tt[0], sizeof tt[0]);
            memcpy(sm->t[sm->nt++], tt[1], sizeof tt[1]);
        }
    }
}

/* The force on the rounded square centred at x after one step, on the mesh
 * (b_first: B's facets listed first) or on the analytic wall y = 0. */
static sd_v3d square_force(int mesh, int b_first, double hc, double r, sd_v3d x)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = SD_LAW_LINEAR;
    wd.dt = 1e-8;
    wd.dimension = 2;
    wd.gravity = sd_test_v(0, 0, 0);
    wd.threads = 1;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "steel";
    m.density = 2700;
    m.stiffness = 1e5;
    m.restitution = 0.5;
    m.friction = 0.3;
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    if (mesh) {
        static strip_mesh sm;
        strip_build(&sm, b_first);
        sd_mesh_def md = sd_mesh_def_default();
        md.vertices = sm.v;
        md.vertex_count = sm.nv;
        md.triangles = (const uint32_t(*)[3])sm.t;
        md.triangle_count = sm.nt;
        md.material = mat;
        sd_test_require(sd_world_add_mesh(w, "ridge", &md, &err) >= 0, "mesh", &err);
    } else {
        sd_test_require(sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 1, 0), mat, &err) >= 0,
                        "plane", &err);
    }
    const double pts[8] = {-hc, -hc, hc, -hc, hc, hc, -hc, hc};
    sd_shape2d_def d = sd_shape2d_def_default();
    d.kind = "polygon";
    d.points = pts;
    d.point_count = 4;
    d.radius = r;
    int shape = sd_world_add_shape2d(w, "square", &d, &err);
    sd_test_require(shape >= 0, "square", &err);
    sd_body_def b = {0};
    b.position = x;
    b.orientation[0] = 1;
    b.shape = shape;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    sd_particle_state p = {0};
    sd_world_get_particle(w, 0, &p);
    sd_world_destroy(w);
    return p.force;
}

int main(void)
{
    const double hc = 0.0049, r = 0.0005, d0 = 2e-4;
    const double yc = hc + r - d0;                                /* the lowest point d0 below y = 0 */
    const double half = hc + sqrt(r * r - (r - d0) * (r - d0)); /* the chord's half-length */
    sd_v3d fref = square_force(0, 0, hc, r, sd_test_v(0, yc, 0));
    printf("square on the analytic wall at depth %g m: force %.10g N\n", d0, fref.y);
    CHECK(fref.y > 0);
    for (int b_first = 1; b_first >= 0; --b_first) {
        double worst = 0, worst_at = 0, worst_x = 0;
        /* centre x from -half - 4 mm (the chord all over A) to +0.8 half (most of it beyond the ridge) */
        for (int q = 0; q <= 36; ++q) {
            double xc = -half - 0.004 + q * (0.004 + 1.8 * half) / 36;
            double over_a = (half - xc) / (2 * half);
            over_a = over_a > 1 ? 1 : (over_a < 0 ? 0 : over_a);
            sd_v3d f = square_force(1, b_first, hc, r, sd_test_v(xc, yc, 0));
            double err = sqrt(pow(f.x, 2) + pow(f.y - fref.y * over_a, 2) + pow(f.z, 2));
            if (err > worst) {
                worst = err;
                worst_at = xc;
            }
            worst_x = fmax(worst_x, fabs(f.x));
        }
        char label[96];
        printf("  worst at centre x = %.4g m\n", worst_at);
        snprintf(label, sizeof label, "square over the ridge (%s first): max |F - F_A share| / F_ref",
                 b_first ? "B" : "A");
        CHECK_NEAR(label, worst / fref.y, 0.0, 1e-3);
        snprintf(label, sizeof label, "square over the ridge (%s first): max |F_x| / F_ref", b_first ? "B" : "A");
        CHECK_NEAR(label, worst_x / fref.y, 0.0, 1e-3);
    }
    return sd_test_summary();
}
