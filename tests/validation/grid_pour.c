/* grid_pour.c — poured packing on the grid solver (seed 001 §4.1, Case I
 * scaled to CI time).
 *
 * Case I pours 72,029 Set I spheres (R = 0.05 m) layer by layer into a
 * 5 m cube at 4 layers/s with dt = 1e-3 s; here 1,200 of them go into a
 * 1 m x 1 m x 2 m box: each sheet holds one sphere per two cells (10 x 10),
 * vertical velocities uniform in [-0.5, 0.5] m/s, horizontal ones in
 * [-0.1, 0.1] m/s, sheets at z = 1.9 m, 4 sheets/s, then 1.5 s of settling.
 *
 * Checks: every particle asked for is poured, none is lost or duplicated
 * (count and stable ids before and after settling), no cell conflict; the
 * packing fraction of the bed (below half its height, sphere caps exact) is
 * reported and lies in the random-packing range [0.50, 0.66]; the seed's own
 * measure (particle volume over the whole box) is printed too.
 */
#include <string.h>

#include "test.h"

#include "grid/grid.h"

#define NPOUR 1200

static double bed_fraction(sd_world *w, double cut)
{
    const double pi = 3.14159265358979;
    double vol = 0;
    for (size_t k = 0; k < sd_world_particle_count(w); ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        double r = p.radius, d = cut - p.position.z;
        if (d >= r)
            vol += 4.0 / 3.0 * pi * r * r * r;
        else if (d > -r)
            vol += pi * (r + d) * (r + d) * (2 * r - d) / 3.0;
    }
    return vol / (1.0 * 1.0 * cut);
}

static int ids_ok(sd_world *w)
{
    static unsigned char seen[NPOUR];
    memset(seen, 0, sizeof seen);
    for (size_t k = 0; k < sd_world_particle_count(w); ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        if (p.id >= NPOUR || seen[p.id])
            return 0;
        seen[p.id] = 1;
    }
    return 1;
}

int main(void)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dt = 1e-3;
    d.law = SD_LAW_LINEAR;
    d.gravity = sd_test_v(0, 0, -9.8);
    d.solver = SD_SOLVER_GRID;
    d.seed = 2024;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_test_material_set1();
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(1, 1, 2), 0, mat, &err) >= 0, "box",
                    &err);
    sd_grid_pour_def pd = sd_grid_pour_def_default();
    pd.radius = 0.05;
    pd.material = mat;
    pd.height = 1.9;
    pd.layers_per_second = 4;
    pd.count = NPOUR;
    sd_test_require(sd_grid_set_pour(w, &pd, &err) == SD_OK, "pour", &err);

    /* 12 sheets at 4 per second: the last one at t = 2.75 s */
    sd_test_require(sd_world_step(w, 3000, &err) == SD_OK, "pour", &err);
    sd_grid_info gi;
    sd_grid_get_info(w, &gi);
    size_t n_poured = sd_world_particle_count(w);
    printf("poured %zu particles in %zu sheets (%zu spots skipped as occupied)\n", gi.poured, gi.pour_layers,
           gi.pour_skipped);
    CHECK(gi.poured == NPOUR && n_poured == NPOUR && ids_ok(w));

    sd_test_require(sd_world_step(w, 1500, &err) == SD_OK, "settle", &err);
    sd_grid_get_info(w, &gi);
    sd_stats st;
    sd_world_stats(w, &st);
    double top = 0, vol = 0;
    for (size_t k = 0; k < sd_world_particle_count(w); ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        top = fmax(top, p.position.z + p.radius);
        vol += 4.0 / 3.0 * 3.14159265358979 * p.radius * p.radius * p.radius;
    }
    double phi = bed_fraction(w, 0.5 * top);
    printf("after 4.5 s: %zu particles, bed top %.3f m, kinetic energy %.3g J, %ld contacts, max overlap %.3g R\n",
           sd_world_particle_count(w), top, st.kinetic_translational, st.contacts, st.max_overlap_ratio);
    printf("packing fraction: bed (below %.3f m) %.4f; seed's measure (volume / whole 2 m box) %.4f\n", 0.5 * top,
           phi, vol / 2.0);
    printf("grid: conflicts %ld, slot overflows %ld, removed %zu, solver bytes %zu (%.0f per particle)\n",
           gi.conflicts, gi.slot_overflows, gi.removed, gi.bytes, (double)gi.bytes / NPOUR);
    CHECK(sd_world_particle_count(w) == NPOUR && ids_ok(w) && gi.removed == 0);
    CHECK(gi.conflicts == 0);
    CHECK(phi > 0.50 && phi < 0.66);
    sd_world_destroy(w);
    return sd_test_summary();
}
