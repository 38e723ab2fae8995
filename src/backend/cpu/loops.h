/* loops.h — the CPU backend: OpenMP loops over particles and pairs. No
 * physics lives here; each loop body calls the single-source SD_HD
 * functions of contact/, geom/ and dynamics/ (DESIGN.md rule 1). */
#ifndef SD_BACKEND_CPU_LOOPS_H
#define SD_BACKEND_CPU_LOOPS_H

#include "contact/pair.h"
#include "world/world.h"

/* The state of particle k as the pair evaluation needs it; plain spheres
 * get no rotational term in the effective mass (their contacts are central). */
static SD_HOT sd_body sd_body_of(const sd_particles *p, size_t k)
{
    sd_body b;
    b.x = p->x[k];
    b.v = p->v[k];
    b.w = p->w[k];
    b.radius = p->radius[k];
    b.inv_mass = p->inv_mass[k];
    b.inv_inertia = p->shape[k] >= 0 ? p->inv_inertia[k] : sd_v3_zero();
    b.q = p->q[k];
    return b;
}

/* First half kick and drift of every particle (velocity Verlet). */
void sd_cpu_kick_drift(sd_world *w);
/* Second half kick. */
void sd_cpu_kick(sd_world *w);
/* Force and torques of every particle-particle pair, into the pair list. */
void sd_cpu_pair_forces(sd_world *w);
/* Force and torque of every particle-wall pair, into the wall pair list. */
void sd_cpu_wall_forces(sd_world *w);
/* Force and torques of every pair that involves a shape template. */
void sd_cpu_convex_forces(sd_world *w);
/* Accumulates the narrow-phase statistics of the convex pairs. */
void sd_cpu_narrow_totals(sd_world *w);
/* Each particle sums its pairs in list order (deterministic reduction). */
void sd_cpu_gather(sd_world *w);
/* The same, followed by the second half kick of the particle (one pass). */
void sd_cpu_gather_kick(sd_world *w);
/* Gather and second kick of this step, then the first kick and the drift of
 * the next step, in one pass (the same operations in the same order as the
 * separate loops, so the same bits). */
void sd_cpu_gather_kick_drift(sd_world *w);
/* Planar mode (pairs2d.c): pairs that involve a 2D shape template, their
 * narrow-phase statistics, and every particle against the walls. */
void sd_cpu_convex2d_forces(sd_world *w);
void sd_cpu_narrow2d_totals(sd_world *w);
void sd_cpu_wall_forces2d(sd_world *w);
/* Total force and torque on each wall, summed in pair order. */
void sd_cpu_wall_totals(sd_world *w);

#endif
