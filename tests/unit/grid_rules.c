/* grid_rules.c — the grid solver's rules and their errors (docs/grid-solver.md):
 *  - two particles competing for one cell: detected, counted, resolved in
 *    storage order (the first keeps the cell, the other goes to the overflow
 *    list and still interacts), never lost;
 *  - seed 001 eq. 11: dt above pi/5 sqrt(m/k) is rejected at prepare, a
 *    particle crossing more than one cell in a step stops the run;
 *  - domain: a box wall is required;
 *  - polydisperse: R_max/R_min up to 2 widens the stencil and matches solver
 *    cells; beyond 2 it is rejected with the reason;
 *  - outlet: a particle falling through the hole is removed and counted.
 */
#include <string.h>

#include "test.h"

#include "grid/grid.h"
#include "world/world.h"

static int mat;

static sd_world *world(sd_solver solver, double dt, double gz, int box)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dt = dt;
    d.law = SD_LAW_LINEAR;
    d.gravity = sd_test_v(0, 0, gz);
    d.solver = solver;
    d.threads = 1;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_test_material_set1();
    mat = sd_world_add_material(w, &m, &err);
    if (box)
        sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(1, 1, 1), 0, mat, &err);
    return w;
}

static void add(sd_world *w, double x, double y, double z, double r, double vx, double vz)
{
    sd_error err;
    sd_sphere_def s;
    memset(&s, 0, sizeof s);
    s.position = sd_test_v(x, y, z);
    s.velocity = sd_test_v(vx, 0, vz);
    s.radius = r;
    s.material = mat;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
}

int main(void)
{
    sd_error err;
    sd_grid_info gi;

    /* a conflict: centres 0.03 m apart inside one 0.05 m cell */
    {
        sd_world *w = world(SD_SOLVER_GRID, 1e-4, 0, 1);
        add(w, 0.5101, 0.5101, 0.5101, 0.05, 0, 0);
        add(w, 0.5301, 0.5301, 0.5201, 0.05, 0, 0);
        CHECK(sd_world_prepare(w, &err) == SD_OK);
        sd_grid_get_info(w, &gi);
        CHECK(gi.conflicts == 1 && gi.in_overflow == 1);
        CHECK(w->grid_state->home[0] != SD_GRID_OVER && w->grid_state->home[1] == SD_GRID_OVER);
        CHECK(sd_world_step(w, 300, &err) == SD_OK);
        sd_grid_get_info(w, &gi);
        sd_particle_state a, b;
        sd_world_get_particle(w, 0, &a);
        sd_world_get_particle(w, 1, &b);
        double d = sqrt(pow(a.position.x - b.position.x, 2) + pow(a.position.y - b.position.y, 2) +
                        pow(a.position.z - b.position.z, 2));
        printf("conflict: %ld detected, %zu still without a cell, centres now %.4f m apart\n", gi.conflicts,
               gi.in_overflow, d);
        CHECK(sd_world_particle_count(w) == 2);
        CHECK(gi.in_overflow == 0 && d > 0.1); /* pushed apart: the overflow particle interacted */
        sd_world_destroy(w);
    }
    /* eq. 11, first term: pi/5 sqrt(m/k) = 3.34e-3 s for Set I */
    {
        sd_world *w = world(SD_SOLVER_GRID, 5e-3, -9.8, 1);
        add(w, 0.5, 0.5, 0.5, 0.05, 0, 0);
        sd_status st = sd_world_prepare(w, &err);
        printf("dt too large: %s\n", err.msg);
        CHECK(st == SD_ERR_INPUT && strstr(err.msg, "eq. 11"));
        sd_world_destroy(w);
    }
    /* eq. 11, second term: 60 m/s x 1e-3 s = 1.2 cells in one step */
    {
        sd_world *w = world(SD_SOLVER_GRID, 1e-3, 0, 1);
        add(w, 0.2, 0.5, 0.5, 0.05, 60, 0);
        sd_status st = sd_world_step(w, 1, &err);
        printf("too fast: %s\n", err.msg);
        CHECK(st == SD_ERR_PHYSICS && strstr(err.msg, "eq. 11"));
        sd_world_destroy(w);
    }
    /* no box */
    {
        sd_world *w = world(SD_SOLVER_GRID, 1e-3, 0, 0);
        add(w, 0.5, 0.5, 0.5, 0.05, 0, 0);
        CHECK(sd_world_prepare(w, &err) == SD_ERR_INPUT && strstr(err.msg, "box"));
        sd_world_destroy(w);
    }
    /* radius ratio 3: rejected with the reason */
    {
        sd_world *w = world(SD_SOLVER_GRID, 1e-4, 0, 1);
        add(w, 0.3, 0.5, 0.5, 0.02, 0, 0);
        add(w, 0.7, 0.5, 0.5, 0.06, 0, 0);
        sd_status st = sd_world_prepare(w, &err);
        printf("ratio 3: %s\n", err.msg);
        CHECK(st == SD_ERR_INPUT && strstr(err.msg, "ratio"));
        sd_world_destroy(w);
    }
    /* radius ratio 1.5: stencil 7x7x7, same trajectories as solver cells */
    {
        sd_world *wc = world(SD_SOLVER_CELLS, 2e-4, -9.8, 1), *wg = world(SD_SOLVER_GRID, 2e-4, -9.8, 1);
        for (int k = 0; k < 216; ++k) {
            double r = 0.04 + 0.02 * (double)((k * 37) % 11) / 10.0;
            double x = 0.07 + 0.135 * (k % 6), y = 0.07 + 0.135 * ((k / 6) % 6), z = 0.07 + 0.135 * (k / 36);
            add(wc, x, y, z, r, 0.1 * ((k % 3) - 1), 0);
            add(wg, x, y, z, r, 0.1 * ((k % 3) - 1), 0);
        }
        CHECK(sd_world_step(wc, 2500, &err) == SD_OK);
        CHECK(sd_world_step(wg, 2500, &err) == SD_OK);
        sd_grid_get_info(wg, &gi);
        double e = 0;
        for (uint64_t id = 0; id < 216; ++id) {
            sd_particle_state a, b;
            sd_world_get_particle(wc, sd_world_find_particle(wc, id), &a);
            sd_world_get_particle(wg, sd_world_find_particle(wg, id), &b);
            e = fmax(e, fabs(a.position.x - b.position.x) + fabs(a.position.y - b.position.y) +
                            fabs(a.position.z - b.position.z));
        }
        sd_stats st;
        sd_world_stats(wg, &st);
        printf("polydisperse: reach %d, %ld contacts after 0.5 s\n", gi.reach, st.contacts);
        CHECK(gi.reach == 3 && st.contacts > 50);
        CHECK_NEAR("ratio 1.5: max position difference grid vs cells (m)", e, 0.0, 1e-9);
        sd_world_destroy(wc);
        sd_world_destroy(wg);
    }
    /* outlet: a particle dropped over the hole leaves and is counted */
    {
        sd_world *w = world(SD_SOLVER_GRID, 1e-4, -9.8, 1);
        CHECK(sd_grid_set_outlet(w, 0.4, 0.6, 0.0, 1.0, &err) == SD_OK);
        add(w, 0.5, 0.5, 0.2, 0.05, 0, 0);
        add(w, 0.2, 0.5, 0.2, 0.05, 0, 0); /* beside the hole: stays */
        CHECK(sd_world_step(w, 3000, &err) == SD_OK);
        sd_grid_get_info(w, &gi);
        sd_particle_state p;
        sd_world_get_particle(w, 0, &p);
        CHECK(sd_world_particle_count(w) == 1 && gi.removed == 1 && gi.removed_outlet == 1 && p.id == 1);
        /* it bounces (Set I is nearly elastic) but never below the floor */
        CHECK(p.position.z > 0.045);
        sd_world_destroy(w);
    }
    /* an outlet that opens later (outlet.open_at): the particle over the
     * hole rests on the floor until then, and leaves after */
    {
        sd_world *w = world(SD_SOLVER_GRID, 1e-4, -9.8, 1);
        CHECK(sd_grid_set_outlet_at(w, 0.4, 0.6, 0.0, 1.0, 0.25, &err) == SD_OK);
        add(w, 0.5, 0.5, 0.06, 0.05, 0, 0);
        CHECK(sd_world_step(w, 2000, &err) == SD_OK); /* 0.2 s: still closed */
        sd_grid_get_info(w, &gi);
        CHECK(sd_world_particle_count(w) == 1 && gi.removed == 0 && !gi.outlet_open);
        CHECK(sd_world_step(w, 3000, &err) == SD_OK); /* opens at 0.25 s */
        sd_grid_get_info(w, &gi);
        printf("outlet opening at 0.25 s: open %d, removed %zu through it, discharged mass %.4g kg\n", gi.outlet_open,
               gi.removed_outlet, gi.removed_mass);
        CHECK(gi.outlet_open && gi.removed_outlet == 1 && sd_world_particle_count(w) == 0);
        double m1 = 2700 * 4.0 / 3.0 * 3.14159265358979 * 0.05 * 0.05 * 0.05;
        CHECK_NEAR("discharged mass (kg), rho 4/3 pi R^3", gi.removed_mass, m1, 1e-9 * m1);
        sd_world_destroy(w);
    }
    /* out-of-range opening time: an error value, nothing changed */
    {
        sd_world *w = world(SD_SOLVER_GRID, 1e-4, -9.8, 1);
        CHECK(sd_grid_set_outlet_at(w, 0.4, 0.6, 0.0, 1.0, -1.0, &err) == SD_ERR_INPUT);
        CHECK(sd_grid_set_outlet_at(w, 0.6, 0.4, 0.0, 1.0, 0.0, &err) == SD_ERR_INPUT);
        sd_world_destroy(w);
    }
    return sd_test_summary();
}
