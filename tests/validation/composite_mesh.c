/* composite_mesh.c — composites against triangle-mesh walls (seed 004
 * §2.6 with seed 000 §2.4): each element of a composite meets each mesh
 * plane group as it would meet a plane, its contact weighted by its
 * section clipped to the group's triangles, one history per (element,
 * group), and the run of one group combined like the run against a plane
 * (model B, eq. 21).
 *
 * 1. A cube of edge 10 mm glued from 8 cubes, dropped with a small tilt
 *    onto the floor z = 0, once an analytic plane and once a mesh of 8
 *    triangles whose 9 vertices include the point under the cube (so its
 *    bottom elements lie across 4 triangles and their weights must add up
 *    to 1): after 0.6 s at rest the two agree in height (1e-9 m) and in
 *    the floor's vertical force (1e-6 relative, its mean over the last
 *    0.1 s), and the force is the weight within 2 % (the cube still
 *    rocks on its face at 0.6 s, |omega| about 0.02 rad/s, so the mean
 *    force is 0.4 % (model B) and 0.9 % (model A) off the weight).
 * 2. The same with model A (sum): the same rest height and force.
 * 3. Five 3D crosses (the cross3d preset, through sd_world_add_composite_
 *    preset) tumbling in a closed mesh drum of R = 50 mm, 24 mm deep,
 *    turning at 20 rpm about y: after 0.6 s none has left the drum, none
 *    has moved faster than the drum's rim could make it, and the bed has
 *    been carried round in the drum's sense (its mean angular momentum
 *    about the axis has the drum's sign).
 */
#include "test.h"

#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

static const double A = 0.01, RHO = 2500, KN = 1e4, DT = 1e-5;

typedef struct mesh_buf {
    sd_v3d v[256];
    uint32_t t[512][3];
    size_t nv, nt;
} mesh_buf;

static size_t vert(mesh_buf *m, double x, double y, double z)
{
    m->v[m->nv] = sd_test_v(x, y, z);
    return m->nv++;
}

static void tri(mesh_buf *m, size_t a, size_t b, size_t c)
{
    m->t[m->nt][0] = (uint32_t)a;
    m->t[m->nt][1] = (uint32_t)b;
    m->t[m->nt][2] = (uint32_t)c;
    m->nt++;
}

static sd_world *make_world(int model, double gz, double gx)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.law = SD_LAW_LINEAR;
    d.dt = DT;
    d.gravity = sd_test_v(gx, 0, gz);
    d.threads = 1;
    d.multi_contact = model;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    return w;
}

static int add_material(sd_world *w, double e, double mu)
{
    sd_error err;
    sd_material_def m = sd_material_def_default();
    m.density = RHO;
    m.stiffness = KN;
    m.restitution = e;
    m.friction = mu;
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    return mat;
}

typedef struct rest {
    double z, fz, weight;
} rest;

/* the glued cube on an analytic (mesh = 0) or a mesh floor, 0.4 s */
static rest glued_cube(int mesh, int model)
{
    sd_error err;
    sd_world *w = make_world(model, -9.81, 0);
    int mat = add_material(w, 0.1, 0.3);
    sd_shape_desc s = sd_shape_desc_default();
    s.kind = "box";
    s.size = sd_test_v(0.5 * A, 0.5 * A, 0.5 * A);
    int small = sd_world_add_shape(w, "cubelet", &s, &err);
    sd_test_require(small >= 0, "cubelet", &err);
    sd_composite_element el[8];
    for (int k = 0; k < 8; ++k) {
        memset(&el[k], 0, sizeof el[k]);
        el[k].shape = small;
        el[k].position = sd_test_v((k & 1 ? 0.25 : -0.25) * A, (k & 2 ? 0.25 : -0.25) * A, (k & 4 ? 0.25 : -0.25) * A);
    }
    sd_composite_desc cd = sd_composite_desc_default();
    cd.elements = el;
    cd.element_count = 8;
    int shape = sd_world_add_composite(w, "glued cube", &cd, &err);
    sd_test_require(shape >= 0, "composite", &err);
    int wall;
    if (!mesh) {
        wall = sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err);
    } else {
        /* 2 x 2 squares of 0.05 m, two triangles each, normal +z; the
         * middle vertex (0, 0, 0) is under the cube's centre */
        static mesh_buf mb;
        memset(&mb, 0, sizeof mb);
        for (int j = 0; j <= 2; ++j)
            for (int i = 0; i <= 2; ++i)
                vert(&mb, -0.05 + 0.05 * i, -0.05 + 0.05 * j, 0);
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
                size_t a = (size_t)(3 * j + i), b = a + 1, c = a + 3, dd = c + 1;
                tri(&mb, a, b, dd);
                tri(&mb, a, dd, c);
            }
        sd_mesh_def md = sd_mesh_def_default();
        md.vertices = mb.v;
        md.vertex_count = mb.nv;
        md.triangles = (const uint32_t(*)[3])mb.t;
        md.triangle_count = mb.nt;
        md.material = mat;
        wall = sd_world_add_mesh(w, "floor", &md, &err);
    }
    sd_test_require(wall >= 0, "floor", &err);
    sd_body_def b;
    memset(&b, 0, sizeof b);
    double h = 0.5 * 5 * PI / 180; /* 5 deg about x then 5 deg about y */
    b.orientation[0] = cos(h) * cos(h);
    b.orientation[1] = cos(h) * sin(h);
    b.orientation[2] = sin(h) * cos(h);
    b.orientation[3] = -sin(h) * sin(h);
    b.position = sd_test_v(0, 0, 0.5 * A + 0.002);
    b.shape = shape;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    sd_test_require(sd_world_step(w, 50000, &err) == SD_OK, "step", &err);
    /* the floor's force averaged over the last 0.1 s (a resting body's
     * contacts still ring at the 1e-3 level) */
    double fz = 0;
    for (int k = 0; k < 1000; ++k) {
        sd_test_require(sd_world_step(w, 10, &err) == SD_OK, "step", &err);
        sd_wall_info wi;
        sd_test_require(sd_world_get_wall(w, (size_t)wall, &wi) == SD_OK, "wall", &err);
        fz -= wi.force.z / 1000;
    }
    sd_particle_state p;
    sd_world_get_particle(w, 0, &p);
    sd_shape_info si;
    sd_world_get_shape(w, (size_t)shape, &si);
    rest r = {p.position.z, fz, RHO * si.volume * 9.81};
    sd_world_destroy(w);
    return r;
}

/* a closed drum about y through the origin: n segments round, two caps */
static void drum_mesh(mesh_buf *m, double R, double depth, int n)
{
    memset(m, 0, sizeof *m);
    for (int k = 0; k < n; ++k) {
        double th = 2 * PI * k / n;
        vert(m, R * cos(th), -0.5 * depth, R * sin(th));
        vert(m, R * cos(th), 0.5 * depth, R * sin(th));
    }
    size_t c0 = vert(m, 0, -0.5 * depth, 0), c1 = vert(m, 0, 0.5 * depth, 0);
    for (int k = 0; k < n; ++k) {
        size_t a = (size_t)(2 * k), b = (size_t)(2 * ((k + 1) % n));
        tri(m, a, b, a + 1);
        tri(m, b, b + 1, a + 1);
        tri(m, c0, b, a);
        tri(m, c1, a + 1, b + 1);
    }
}

int main(void)
{
    printf("glued cube (8 cubes, edge %.0f mm) at rest, 0.6 s\n", A * 1e3);
    printf("model      floor     z centre m        floor Fz N       weight N\n");
    for (int model = 0; model < 2; ++model) {
        rest pl = glued_cube(0, model), me = glued_cube(1, model);
        const char *mn = model == SD_MULTI_CONTACT_AVERAGE ? "B (avg)" : "A (sum)";
        printf("%-9s  plane  %16.10e  %14.8e  %14.8e\n", mn, pl.z, pl.fz, pl.weight);
        printf("%-9s  mesh   %16.10e  %14.8e  %14.8e\n", mn, me.z, me.fz, me.weight);
        char label[96];
        snprintf(label, sizeof label, "model %s: rest height on the mesh as on the plane (m)", mn);
        CHECK_NEAR(label, me.z, pl.z, 1e-9);
        snprintf(label, sizeof label, "model %s: floor force on the mesh as on the plane (N)", mn);
        CHECK_REL(label, me.fz, pl.fz, 1e-6);
        snprintf(label, sizeof label, "model %s: floor force = weight, 2 %% (N)", mn);
        CHECK_REL(label, me.fz, me.weight, 2e-2);
        snprintf(label, sizeof label, "model %s: resting on the floor, centre z (m)", mn);
        CHECK_NEAR(label, me.z, 0.5 * A, 0.1 * A);
    }

    /* 3. crosses in a turning mesh drum */
    {
        const double R = 0.05, depth = 0.024, rpm = 20;
        sd_error err;
        sd_world *w = make_world(SD_MULTI_CONTACT_AVERAGE, -9.81, 0);
        int mat = add_material(w, 0.5, 0.4);
        static mesh_buf mb;
        drum_mesh(&mb, R, depth, 48);
        sd_mesh_def md = sd_mesh_def_default();
        md.vertices = mb.v;
        md.vertex_count = mb.nv;
        md.triangles = (const uint32_t(*)[3])mb.t;
        md.triangle_count = mb.nt;
        md.material = mat;
        int drum = sd_world_add_mesh(w, "drum", &md, &err);
        sd_test_require(drum >= 0, "drum", &err);
        sd_mesh_motion_def mm = sd_mesh_motion_def_default();
        mm.kind = SD_MESH_ROTATE;
        mm.axis_point = sd_test_v(0, 0, 0);
        mm.axis = sd_test_v(0, 1, 0);
        mm.rpm = rpm;
        sd_test_require(sd_world_set_mesh_motion(w, drum, &mm, &err) == SD_OK, "motion", &err);
        sd_composite_preset_def pd = sd_composite_preset_def_default();
        pd.preset = "cross3d";
        pd.length = 0.02;
        pd.diameter = 0.005;
        int cross = sd_world_add_composite_preset(w, "cross", &pd, &err);
        sd_test_require(cross >= 0, "cross3d preset", &err);
        sd_body_def b[5];
        memset(b, 0, sizeof b);
        for (int k = 0; k < 5; ++k) {
            /* two rows, bounding spheres (10.3 mm) apart */
            b[k].position = k < 3 ? sd_test_v(-0.022 + 0.022 * k, 0, -0.015) : sd_test_v(k == 3 ? -0.011 : 0.011, 0, 0.01);
            b[k].orientation[0] = cos(0.3 * k);
            b[k].orientation[1] = sin(0.3 * k);
            b[k].shape = cross;
            b[k].material = mat;
        }
        sd_test_require(sd_world_add_bodies(w, 5, b, &err) == SD_OK, "crosses", &err);
        double rmax = 0, ymax = 0, vmax = 0, ly = 0, xm = 0;
        for (int c = 0; c < 60; ++c) {
            sd_test_require(sd_world_step(w, 1000, &err) == SD_OK, "step", &err);
            for (size_t k = 0; k < 5; ++k) {
                sd_particle_state p;
                sd_world_get_particle(w, k, &p);
                rmax = fmax(rmax, sqrt(p.position.x * p.position.x + p.position.z * p.position.z));
                ymax = fmax(ymax, fabs(p.position.y));
                vmax = fmax(vmax, sqrt(p.velocity.x * p.velocity.x + p.velocity.y * p.velocity.y +
                                       p.velocity.z * p.velocity.z));
                /* over the last 0.3 s: the angular momentum per mass
                 * about +y, (r x v)_y = z vx - x vz, and the mean x (the
                 * wall at the bottom moves to -x: the bed is dragged up
                 * the x < 0 side) */
                if (c >= 30) {
                    ly += (p.position.z * p.velocity.x - p.position.x * p.velocity.z) / (5 * 30);
                    xm += p.position.x / (5 * 30);
                }
            }
        }
        double omega = rpm * 2 * PI / 60, vfall = sqrt(2 * 9.81 * 2 * R);
        printf("crosses in the mesh drum, 0.6 s: max |r| %.5f m (R %.3f), max |y| %.5f m (half depth %.3f), "
               "max speed %.4f m/s (rim %.4f, free fall over 2R %.4f); over the last 0.3 s: mean L_y per mass "
               "%.4e m^2/s (drum's sense +), mean x %.5f m\n",
               rmax, R, ymax, 0.5 * depth, vmax, omega * R, vfall, ly, xm);
        CHECK_NEAR("crosses stay inside the drum radius (m)", rmax, 0.0, R);
        CHECK_NEAR("crosses stay between the drum's caps (m)", ymax, 0.0, 0.5 * depth);
        CHECK_NEAR("no cross faster than a fall across the drum (m/s)", vmax, 0.0, vfall);
        CHECK(ly > 0);
        CHECK(xm < 0);
        sd_world_destroy(w);
    }
    return sd_test_summary();
}
