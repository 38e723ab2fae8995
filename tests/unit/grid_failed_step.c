/* grid_failed_step.c — the grid solver after a step that failed (probe F3)
 * and its contact statistics:
 *  - a pour so fast that eq. 11 (one cell per step) stops the first step,
 *    some spheres carried below or above the grid (1e4 m/s) or within it
 *    (1000 m/s): the step fails with the eq. 11 message, the statistics
 *    read the moved spheres without leaving the grid (the crash of F3 was an
 *    out-of-bounds stencil read), they agree with a brute-force count over
 *    the spheres inside the grid, and a further step or prepare is refused;
 *  - a speed whose square overflows: the NaN guard stops the step, the
 *    sphere keeps no cell, the statistics read nothing out of the grid;
 *  - two spheres in one cell (a conflict): the pair of the sphere without a
 *    cell is counted once, like any other (it was missed before).
 * Brute force: every pair of spheres closer than the sum of their radii.
 */
#include <string.h>

#include "test.h"

#include "grid/grid.h"
#include "world/world.h"

static int mat;

static sd_world *world(double dt, int open_top)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dt = dt;
    d.law = SD_LAW_LINEAR;
    d.gravity = sd_test_v(0, 0, -9.81);
    d.solver = SD_SOLVER_GRID;
    d.threads = 1;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "m";
    m.density = 1592;
    m.stiffness = 1e4;
    mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    sd_test_require(sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.1, 0.04, 0.2),
                                     open_top ? SD_BOX_ZMAX : 0u, mat, &err) >= 0,
                    "box", &err);
    return w;
}

/* Contacts and the kinetic energy by brute force, over the spheres whose
 * centre is in the grid (the statistics leave the others out). */
static void brute(const sd_world *w, long *contacts, double *ovl, double *ek, size_t *outside)
{
    const sd_grid_state *g = w->grid_state;
    size_t n = sd_world_particle_count(w);
    *contacts = 0;
    *ovl = 0;
    *ek = 0;
    *outside = 0;
    for (size_t a = 0; a < n; ++a) {
        sd_particle_state pa;
        sd_world_get_particle(w, a, &pa);
        double v2 = pa.velocity.x * pa.velocity.x + pa.velocity.y * pa.velocity.y + pa.velocity.z * pa.velocity.z;
        *ek += 0.5 * pa.mass * v2;
        if (sd_grid_cell_of(g, g->part[a].x) == SD_GRID_OUTSIDE) {
            (*outside)++;
            continue;
        }
        for (size_t b = a + 1; b < n; ++b) {
            if (sd_grid_cell_of(g, g->part[b].x) == SD_GRID_OUTSIDE)
                continue;
            sd_particle_state pb;
            sd_world_get_particle(w, b, &pb);
            double dx = pa.position.x - pb.position.x, dy = pa.position.y - pb.position.y,
                   dz = pa.position.z - pb.position.z;
            double delta = pa.radius + pb.radius - sqrt(dx * dx + dy * dy + dz * dz);
            if (delta > 0) {
                (*contacts)++;
                double r = fmin(pa.radius, pb.radius);
                *ovl = fmax(*ovl, delta / r);
            }
        }
    }
}

static void failed_pour(double speed, int open_top)
{
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_world *w = world(2e-5, open_top);
    sd_grid_pour_def p = sd_grid_pour_def_default();
    p.radius = 0.003;
    p.material = mat;
    p.height = 0.1;
    p.count = 50;
    p.vz_range = speed;
    sd_test_require(sd_grid_set_pour(w, &p, &err) == SD_OK, "pour", &err);
    sd_status st = sd_world_step(w, 5, &err);
    printf("pour at %g m/s: %s\n", speed, err.msg);
    CHECK(st == SD_ERR_PHYSICS && strstr(err.msg, "eq. 11") != NULL);
    sd_grid_info gi;
    sd_grid_get_info(w, &gi);
    CHECK(gi.failed_step == 1 && gi.poured == 50 && sd_world_step_count(w) == 0);
    /* the statistics: inside the grid, and the same as brute force */
    sd_stats s;
    sd_world_stats(w, &s);
    long contacts;
    double ovl, ek;
    size_t outside;
    brute(w, &contacts, &ovl, &ek, &outside);
    printf("pour at %g m/s: %zu spheres, %zu outside the grid; contacts %ld (brute force %ld), max overlap ratio "
           "%.6g (%.6g)\n",
           speed, sd_world_particle_count(w), outside, s.contacts, contacts, s.max_overlap_ratio, ovl);
    CHECK(sd_world_particle_count(w) == 50);
    CHECK(s.contacts == contacts);
    CHECK_NEAR("max overlap ratio vs brute force", s.max_overlap_ratio, ovl, 1e-12);
    CHECK_REL("kinetic energy (J) vs brute force", s.kinetic_translational, ek, 1e-12);
    /* every cell holder is where its cell says, and no cell is held twice */
    const sd_grid_state *g = w->grid_state;
    int bad = 0;
    for (size_t k = 0; k < g->n; ++k)
        if (g->home[k] != SD_GRID_OVER)
            bad += g->cell[g->home[k]] != (int32_t)k || g->home[k] != sd_grid_cell_of(g, g->part[k].x);
    CHECK(bad == 0);
    /* no further step: the forces are those of the step before */
    memset(&err, 0, sizeof err);
    st = sd_world_step(w, 1, &err);
    printf("step after the failure: %s\n", err.msg);
    CHECK(st != SD_OK && strstr(err.msg, "stopped at step 1") != NULL);
    CHECK(sd_world_prepare(w, &err) != SD_OK);
    sd_world_stats(w, &s); /* still readable */
    CHECK(s.contacts == contacts);
    sd_world_destroy(w);
}

int main(void)
{
    failed_pour(1e4, 1); /* carried past the grid's bottom and its open top */
    failed_pour(1e4, 0);
    failed_pour(1000, 1); /* 6.7 cells: still inside the grid */

    /* the NaN guard's path: a sphere whose speed squared overflows stops
     * the first step; it keeps no cell, its neighbour in the grid does */
    {
        sd_error err;
        memset(&err, 0, sizeof err);
        sd_world *w = world(1e-5, 0);
        sd_sphere_def sp[2];
        memset(sp, 0, sizeof sp);
        sp[0].position = sd_test_v(0.03, 0.02, 0.1);
        sp[0].velocity = sd_test_v(1e200, 0, 0);
        sp[1].position = sd_test_v(0.07, 0.02, 0.1);
        sp[0].radius = sp[1].radius = 0.003;
        sp[0].material = sp[1].material = mat;
        if (sd_world_add_spheres(w, 2, sp, &err) != SD_OK) {
            printf("a speed of 1e200 m/s is refused when added (%s): nothing to step\n", err.msg);
        } else {
            sd_status st = sd_world_step(w, 1, &err);
            printf("overflowing speed: %s\n", err.msg);
            CHECK(st == SD_ERR_PHYSICS && strstr(err.msg, "NaN or infinite") != NULL);
            sd_grid_info gi;
            sd_grid_get_info(w, &gi);
            const sd_grid_state *g = w->grid_state;
            CHECK(gi.failed_step == 1 && g->n == 2);
            CHECK(g->home[0] == SD_GRID_OVER && g->home[1] != SD_GRID_OVER && g->nover == 0);
            sd_stats s;
            sd_world_stats(w, &s); /* reads nothing out of the grid */
            printf("overflowing speed: contacts %ld, kinetic energy %g J\n", s.contacts, s.kinetic_translational);
            CHECK(s.contacts == 0 && !isfinite(s.kinetic_translational));
        }
        sd_world_destroy(w);
    }

    /* a conflict: centres 0.0015 m apart in one 0.003 m cell; the sphere
     * without a cell has the larger id, so its pair is counted from the
     * overflow list */
    {
        sd_error err;
        sd_world *w = world(1e-5, 0);
        sd_sphere_def sp[2];
        memset(sp, 0, sizeof sp);
        sp[0].position = sd_test_v(0.0515, 0.0215, 0.1025); /* cell (20, 10, 37) of the halo'd grid */
        sp[1].position = sd_test_v(0.0525, 0.0225, 0.1030);
        sp[0].radius = sp[1].radius = 0.003;
        sp[0].material = sp[1].material = mat;
        sd_test_require(sd_world_add_spheres(w, 2, sp, &err) == SD_OK, "spheres", &err);
        sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err);
        sd_grid_info gi;
        sd_grid_get_info(w, &gi);
        sd_stats s;
        sd_world_stats(w, &s);
        long contacts;
        double ovl, ek;
        size_t outside;
        brute(w, &contacts, &ovl, &ek, &outside);
        printf("conflict: %zu without a cell; contacts %ld (brute force %ld), max overlap ratio %.6g (%.6g)\n",
               gi.in_overflow, s.contacts, contacts, s.max_overlap_ratio, ovl);
        CHECK(gi.in_overflow == 1 && contacts == 1);
        CHECK(s.contacts == contacts);
        CHECK_NEAR("max overlap ratio vs brute force", s.max_overlap_ratio, ovl, 1e-12);
        CHECK(s.potential_elastic > 0);
        sd_world_destroy(w);
    }
    return sd_test_summary();
}
