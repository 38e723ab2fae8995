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

/* The plane of a wall feature: the plane wall itself, or a closed box face
 * (inward normal). Returns 0 when x does not project inside the face's
 * rectangle: a shape beside a box face meets it only through the
 * neighbouring face (box rims are not resolved for shapes). */
static inline int sd_wall_feature_plane(const sd_wall *wl, int face, sd_vec3 x, sd_vec3 *p0, sd_vec3 *n)
{
    if (wl->kind == SD_WALL_PLANE) {
        *p0 = wl->point;
        *n = wl->normal;
        return 1;
    }
    int axis = face / 2;
    sd_real lo[3] = {wl->lo.x, wl->lo.y, wl->lo.z}, hi[3] = {wl->hi.x, wl->hi.y, wl->hi.z}, c[3] = {x.x, x.y, x.z};
    for (int k = 0; k < 3; ++k)
        if (k != axis && (c[k] < lo[k] || c[k] > hi[k]))
            return 0;
    sd_real nn[3] = {0, 0, 0}, pp[3] = {c[0], c[1], c[2]};
    nn[axis] = (face & 1) ? SD_R(-1.0) : SD_R(1.0);
    pp[axis] = (face & 1) ? hi[axis] : lo[axis];
    *p0 = sd_v3(pp[0], pp[1], pp[2]);
    *n = sd_v3(nn[0], nn[1], nn[2]);
    return 1;
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
