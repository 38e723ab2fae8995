/* grid_vs_cells.c — the dense grid-stencil solver (solver grid, seed 001)
 * against the general engine (solver cells) on the same settling scene.
 *
 * 2,000 spheres of seed 001 Set I (R = 0.05 m, rho = 2700 kg/m^3,
 * k = 50,000 N/m, eta = 0.5 N s/m, mu = 0.5, k_t = k) start on a lattice of
 * spacing 0.105 m with random velocities of up to 0.2 m/s per component in a
 * closed box and settle under gravity (dt = 2e-4 s: the trajectories of a
 * dense granular flow are chaotic, and rounding differences of 1e-16 grow
 * about tenfold per 0.1 s of collisions, so 1,000 steps of 1e-3 s would
 * amplify them past 1e-9 whatever the solvers; over 0.2 s they stay ~1e-12).
 *  1. over the first 1,000 steps, while no two particles compete for a cell,
 *     every position agrees to 1e-9 relative to the box size and every
 *     velocity to 1e-9 relative to the fastest particle, and the force each
 *     solver reports on the box wall agrees to 1e-9 of the bed's weight;
 *  2. after settling, both packings have the same packing fraction within 1 %;
 *  3. the grid solver reports no conflicts, no lost particle, no contact
 *     without a history slot, and the same bits with 1 and 2 threads (its
 *     loops forced threaded: this scene is below SD_GRID_PARALLEL_MIN).
 */
#include <string.h>

#include "test.h"

#include "grid/grid.h"

#define NX 20
#define NY 10
#define NZ 10

static sd_world *make(sd_solver solver, int threads)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dt = 2e-4;
    d.law = SD_LAW_LINEAR;
    d.gravity = sd_test_v(0, 0, -9.8);
    d.solver = solver;
    d.threads = threads;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_test_material_set1();
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    const double r = 0.05, gap = 0.105;
    sd_test_require(sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(NX * gap, NY * gap, 3.0), 0, mat,
                                     &err) >= 0,
                    "box", &err);
    static sd_sphere_def s[NX * NY * NZ];
    unsigned long long x = 12345;
    for (int k = 0; k < NX * NY * NZ; ++k) {
        int i = k % NX, j = (k / NX) % NY, l = k / (NX * NY);
        memset(&s[k], 0, sizeof s[k]);
        s[k].position = sd_test_v((i + 0.5) * gap, (j + 0.5) * gap, 0.06 + l * gap);
        double v[3];
        for (int c = 0; c < 3; ++c) {
            x = x * 6364136223846793005ull + 1442695040888963407ull;
            v[c] = ((double)(x >> 11) / 9007199254740992.0 - 0.5) * 0.4;
        }
        s[k].velocity = sd_test_v(v[0], v[1], v[2]);
        s[k].radius = r;
        s[k].material = mat;
    }
    sd_test_require(sd_world_add_spheres(w, NX * NY * NZ, s, &err) == SD_OK, "spheres", &err);
    return w;
}

/* state of particle with stable id `id` */
static sd_particle_state get(sd_world *w, uint64_t id)
{
    sd_particle_state p;
    sd_world_get_particle(w, sd_world_find_particle(w, id), &p);
    return p;
}

/* Packing fraction of the bed below z = 0.4 m (about half its height):
 * the volume of every sphere below the cut (spherical caps counted exactly)
 * over the box's cross-section times 0.4 m. A cut inside the bed keeps the
 * loose surface and bouncing particles out of the measure. */
static double packing_fraction(sd_world *w)
{
    const double cut = 0.4, pi = 3.14159265358979;
    double vol = 0;
    size_t n = sd_world_particle_count(w);
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        double r = p.radius, d = cut - p.position.z; /* cut height above the centre */
        if (d >= r)
            vol += 4.0 / 3.0 * pi * r * r * r;
        else if (d > -r)
            vol += pi * (r + d) * (r + d) * (2 * r - d) / 3.0; /* cap below the cut */
    }
    return vol / (NX * 0.105 * NY * 0.105 * cut);
}

int main(void)
{
    sd_error err;
    const int n = NX * NY * NZ;
    sd_world *wc = make(SD_SOLVER_CELLS, 0), *wg = make(SD_SOLVER_GRID, 0);

    /* 1. trajectories, 1,000 steps, compared every 100 */
    double ex = 0, ev = 0, vmax = 0;
    for (int block = 0; block < 10; ++block) {
        sd_test_require(sd_world_step(wc, 100, &err) == SD_OK, "cells step", &err);
        sd_test_require(sd_world_step(wg, 100, &err) == SD_OK, "grid step", &err);
        for (int id = 0; id < n; ++id) {
            sd_particle_state a = get(wc, (uint64_t)id), b = get(wg, (uint64_t)id);
            double dx = fabs(a.position.x - b.position.x) + fabs(a.position.y - b.position.y) +
                        fabs(a.position.z - b.position.z);
            double dv = fabs(a.velocity.x - b.velocity.x) + fabs(a.velocity.y - b.velocity.y) +
                        fabs(a.velocity.z - b.velocity.z);
            double sp = sqrt(a.velocity.x * a.velocity.x + a.velocity.y * a.velocity.y +
                             a.velocity.z * a.velocity.z);
            ex = fmax(ex, dx);
            ev = fmax(ev, dv);
            vmax = fmax(vmax, sp);
        }
    }
    sd_grid_info gi;
    sd_grid_get_info(wg, &gi);
    sd_stats sc, sg;
    sd_world_stats(wc, &sc);
    sd_world_stats(wg, &sg);
    printf("after 1000 steps: contacts cells %ld grid %ld, wall contacts cells %ld grid %ld, conflicts %ld\n",
           sc.contacts, sg.contacts, sc.wall_contacts, sg.wall_contacts, gi.conflicts);
    CHECK(sc.contacts > 1000); /* the scene is dense and colliding by then */
    CHECK_NEAR("max position difference / box size (3 m)", ex / 3.0, 0.0, 1e-9);
    CHECK_NEAR("max velocity difference / fastest speed", ev / vmax, 0.0, 1e-9);
    CHECK(gi.conflicts == 0);
    CHECK(sc.contacts == sg.contacts && sc.wall_contacts == sg.wall_contacts);
    /* the force on each wall, reported by both solvers (sd_world_get_wall:
     * stats.csv and summary.txt read the same), against the bed's weight
     * as the scale */
    double weight = 0;
    for (int id = 0; id < n; ++id)
        weight += get(wc, (uint64_t)id).mass * 9.81;
    for (size_t k = 0; k < sd_world_wall_count(wc); ++k) {
        sd_wall_info a, b;
        sd_world_get_wall(wc, k, &a);
        sd_world_get_wall(wg, k, &b);
        double df = fabs(a.force.x - b.force.x) + fabs(a.force.y - b.force.y) + fabs(a.force.z - b.force.z);
        printf("wall %zu force: cells (%.6g, %.6g, %.6g) N, grid (%.6g, %.6g, %.6g) N\n", k, a.force.x, a.force.y,
               a.force.z, b.force.x, b.force.y, b.force.z);
        CHECK_NEAR("wall force difference / bed weight", df / weight, 0.0, 1e-9);
        CHECK(fabs(a.force.z) + fabs(b.force.z) > 0); /* the floor carries load by now */
    }

    /* 2. settle (1.8 s in all) and compare the packings */
    sd_test_require(sd_world_step(wc, 8000, &err) == SD_OK, "cells settle", &err);
    sd_test_require(sd_world_step(wg, 8000, &err) == SD_OK, "grid settle", &err);
    double pc = packing_fraction(wc), pg = packing_fraction(wg);
    sd_world_stats(wc, &sc);
    sd_world_stats(wg, &sg);
    printf("after 9000 steps (1.8 s): kinetic energy cells %.3g J grid %.3g J\n", sc.kinetic_translational,
           sg.kinetic_translational);
    CHECK_REL("packing fraction, grid vs cells", pg, pc, 0.01);
    sd_grid_get_info(wg, &gi);
    printf("grid: cell %.3g m, reach %d, %ld x %ld x %ld cells, conflicts %ld, slot overflows %ld (most slots "
           "held by one particle %d of %d), removed %zu, solver bytes %zu (%.0f per particle)\n",
           gi.cell, gi.reach, gi.nx, gi.ny, gi.nz, gi.conflicts, gi.slot_overflows, gi.slots_used_max, SD_GRID_SLOTS,
           gi.removed, gi.bytes, (double)gi.bytes / (double)n);
    CHECK(sd_world_particle_count(wg) == (size_t)n && gi.removed == 0);
    CHECK(gi.slot_overflows == 0);

    /* 3. the same bits with 1 and 2 threads (500 steps, the 2-thread world's
     * loops threaded although it is below SD_GRID_PARALLEL_MIN) */
    sd_world *w1 = make(SD_SOLVER_GRID, 1), *w2 = make(SD_SOLVER_GRID, 2);
    sd_test_require(sd_grid_set_parallel_min(w2, 1) == SD_OK, "threaded loops", &err);
    sd_world_step(w1, 500, &err);
    sd_world_step(w2, 500, &err);
    int same = 1;
    for (int id = 0; id < n; ++id) {
        sd_particle_state a = get(w1, (uint64_t)id), b = get(w2, (uint64_t)id);
        same &= memcmp(&a.position, &b.position, sizeof a.position) == 0 &&
                memcmp(&a.velocity, &b.velocity, sizeof a.velocity) == 0 &&
                memcmp(&a.angular_velocity, &b.angular_velocity, sizeof a.angular_velocity) == 0;
    }
    CHECK(same);
    sd_world_destroy(w1);
    sd_world_destroy(w2);
    sd_world_destroy(wc);
    sd_world_destroy(wg);
    return sd_test_summary();
}
