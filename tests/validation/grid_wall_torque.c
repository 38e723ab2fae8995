/* grid_wall_torque.c — the torque the particles' contact forces exert on a
 * wall, about the wall's reference point (a plane's `point`, a box's
 * centre), as stats.csv (NAME_tx, NAME_ty, NAME_tz), summary.txt and
 * sd_world_get_wall report it, in both solvers that have walls:
 *  - solver cells, a plane whose point is off the sphere: one sphere at rest
 *    at an offset d from the point; two spheres of different radii;
 *  - solver cells and solver grid, a sphere at rest on a box floor, off the
 *    box centre.
 * Expected values:
 *  - to round-off: tau = (c - P) x F with F the reported wall force and c the
 *    contact point midway through the overlap (geom/sphere.h), i.e.
 *    c = x - (R - delta/2) n, delta = R - (x - P).n on the face plane;
 *  - physics: at rest every contact carries its sphere's weight, so
 *    F = sum -m g z and tau = sum (x_i - P) x (-m_i g z) (1e-6, the settling).
 * The grid solver's torque is also the same bits with 1 and 2 threads.
 */
#include <string.h>

#include "test.h"

#include "grid/grid.h"

#define G 9.81
#define PI 3.14159265358979323846

static int mat;

static sd_world *world(sd_solver solver, int threads)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dt = 1e-5;
    d.law = SD_LAW_LINEAR;
    d.gravity = sd_test_v(0, 0, -G);
    d.solver = solver;
    d.threads = threads;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "m";
    m.density = 2500;
    m.stiffness = 1e4;
    m.restitution = 0.3;
    m.friction = 0.5;
    mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    return w;
}

/* A sphere of radius r at (x, y) dropped on the plane z = z0 from 0.1 mm
 * above its rest height (overlap m g / k): it bounces (restitution 0.3)
 * and settles well within the 0.05 s run (decay time about 1 ms). */
static double add_resting(sd_world *w, double x, double y, double z0, double r)
{
    sd_error err;
    double m = 2500 * 4.0 / 3.0 * PI * r * r * r;
    sd_sphere_def s;
    memset(&s, 0, sizeof s);
    s.position = sd_test_v(x, y, z0 + r - m * G / 1e4 + 1e-4);
    s.radius = r;
    s.material = mat;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    return m;
}

static sd_v3d cross(sd_v3d a, sd_v3d b)
{
    return sd_test_v(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

static double norm(sd_v3d a) { return sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }

/* Compares the wall's torque with (c - P) x F for the one sphere on the
 * face z = z0 (normal +z), and with the weight's moment. */
static void check_one(const char *what, sd_world *w, int wall, sd_v3d P, double z0, double mass, sd_wall_info *out)
{
    sd_wall_info wi;
    sd_world_get_wall(w, (size_t)wall, &wi);
    sd_particle_state p;
    sd_world_get_particle(w, 0, &p);
    double delta = p.radius - (p.position.z - z0);
    sd_v3d c = sd_test_v(p.position.x, p.position.y, p.position.z - (p.radius - 0.5 * delta));
    sd_v3d rc = sd_test_v(c.x - P.x, c.y - P.y, c.z - P.z);
    sd_v3d t = cross(rc, wi.force);
    sd_v3d tw = cross(sd_test_v(p.position.x - P.x, p.position.y - P.y, 0), sd_test_v(0, 0, -mass * G));
    double scale = norm(wi.torque);
    char label[160];
    printf("%s: wall force (%.10g, %.10g, %.10g) N, torque (%.10g, %.10g, %.10g) N m about (%g, %g, %g)\n", what,
           wi.force.x, wi.force.y, wi.force.z, wi.torque.x, wi.torque.y, wi.torque.z, P.x, P.y, P.z);
    snprintf(label, sizeof label, "%s tau_x vs (c-P)xF", what);
    CHECK_NEAR(label, wi.torque.x, t.x, 1e-14 * scale);
    snprintf(label, sizeof label, "%s tau_y vs (c-P)xF", what);
    CHECK_NEAR(label, wi.torque.y, t.y, 1e-14 * scale);
    snprintf(label, sizeof label, "%s tau_z vs (c-P)xF", what);
    CHECK_NEAR(label, wi.torque.z, t.z, 1e-14 * scale);
    snprintf(label, sizeof label, "%s F_z vs -m g", what);
    CHECK_REL(label, wi.force.z, -mass * G, 1e-6);
    snprintf(label, sizeof label, "%s tau_x vs (x-P) x (-m g z)", what);
    CHECK_NEAR(label, wi.torque.x, tw.x, 1e-6 * scale);
    snprintf(label, sizeof label, "%s tau_y vs (x-P) x (-m g z)", what);
    CHECK_NEAR(label, wi.torque.y, tw.y, 1e-6 * scale);
    CHECK(scale > 1e-5); /* the offsets make a torque of order m g d */
    if (out)
        *out = wi;
}

/* One sphere on the floor of the box [0, 0.1] x [0, 0.08] x [0, 0.05],
 * 0.03 m left of and 0.025 m behind the centre (0.05, 0.04, 0.025). */
static sd_v3d box_case(sd_solver solver, int threads, const char *what)
{
    sd_error err;
    sd_world *w = world(solver, threads);
    int b = sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.1, 0.08, 0.05), 0, mat, &err);
    sd_test_require(b >= 0, "box", &err);
    double m = add_resting(w, 0.02, 0.015, 0.0, 0.004);
    if (solver == SD_SOLVER_GRID && threads > 1)
        sd_grid_set_parallel_min(w, 1); /* the threaded loops, for one sphere */
    sd_test_require(sd_world_step(w, 5000, &err) == SD_OK, "steps", &err);
    sd_wall_info wi;
    check_one(what, w, b, sd_test_v(0.05, 0.04, 0.025), 0.0, m, &wi);
    sd_world_destroy(w);
    return wi.torque;
}

int main(void)
{
    sd_error err;
    /* solver cells, a plane through (0.01, 0.02, 0) */
    {
        sd_world *w = world(SD_SOLVER_CELLS, 1);
        int pl = sd_world_add_plane(w, "floor", sd_test_v(0.01, 0.02, 0), sd_test_v(0, 0, 1), mat, &err);
        sd_test_require(pl >= 0, "plane", &err);
        double m = add_resting(w, 0.04, -0.03, 0.0, 0.005);
        sd_test_require(sd_world_step(w, 5000, &err) == SD_OK, "steps", &err);
        check_one("cells plane", w, pl, sd_test_v(0.01, 0.02, 0), 0.0, m, NULL);
        sd_world_destroy(w);
    }
    /* solver cells, a plane, two spheres of radii 5 and 3 mm on either side */
    {
        sd_world *w = world(SD_SOLVER_CELLS, 1);
        int pl = sd_world_add_plane(w, "floor", sd_test_v(0.01, 0.02, 0), sd_test_v(0, 0, 1), mat, &err);
        sd_test_require(pl >= 0, "plane", &err);
        double m1 = add_resting(w, 0.04, -0.03, 0.0, 0.005);
        double m2 = add_resting(w, -0.05, 0.06, 0.0, 0.003);
        sd_test_require(sd_world_step(w, 5000, &err) == SD_OK, "steps", &err);
        sd_wall_info wi;
        sd_world_get_wall(w, (size_t)pl, &wi);
        /* sum over both spheres of (x_i - P) x (-m_i g z) */
        sd_v3d t1 = cross(sd_test_v(0.04 - 0.01, -0.03 - 0.02, 0), sd_test_v(0, 0, -m1 * G));
        sd_v3d t2 = cross(sd_test_v(-0.05 - 0.01, 0.06 - 0.02, 0), sd_test_v(0, 0, -m2 * G));
        double scale = norm(wi.torque);
        printf("cells plane, two spheres: torque (%.10g, %.10g, %.10g) N m\n", wi.torque.x, wi.torque.y,
               wi.torque.z);
        CHECK_REL("cells plane 2 spheres F_z vs -(m1 + m2) g", wi.force.z, -(m1 + m2) * G, 1e-6);
        CHECK_NEAR("cells plane 2 spheres tau_x vs sum (x-P) x (-m g)", wi.torque.x, t1.x + t2.x, 1e-6 * scale);
        CHECK_NEAR("cells plane 2 spheres tau_y vs sum (x-P) x (-m g)", wi.torque.y, t1.y + t2.y, 1e-6 * scale);
        CHECK_NEAR("cells plane 2 spheres tau_z", wi.torque.z, 0.0, 1e-6 * scale);
        sd_world_destroy(w);
    }
    /* a box: the torque about its centre, in both solvers */
    sd_v3d tc = box_case(SD_SOLVER_CELLS, 1, "cells box");
    sd_v3d tg = box_case(SD_SOLVER_GRID, 1, "grid box");
    sd_v3d tg2 = box_case(SD_SOLVER_GRID, 2, "grid box, 2 threads");
    double scale = norm(tc);
    CHECK_NEAR("grid vs cells box tau_x", tg.x, tc.x, 1e-9 * scale);
    CHECK_NEAR("grid vs cells box tau_y", tg.y, tc.y, 1e-9 * scale);
    printf("grid box torque, 1 vs 2 threads: (%.17g, %.17g, %.17g) vs (%.17g, %.17g, %.17g)\n", tg.x, tg.y, tg.z,
           tg2.x, tg2.y, tg2.z);
    CHECK(memcmp(&tg, &tg2, sizeof tg) == 0);
    return sd_test_summary();
}
