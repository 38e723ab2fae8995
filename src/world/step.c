/* step.c — the time step, stage by stage (DESIGN.md data flow).
 *
 *   kick + drift ─► rebuild pairs when the skin is used up ─► pair forces
 *   ─► wall forces ─► gather per particle ─► kick ─► clock
 *
 * Within one call the gather and kick that end a step and the kick and
 * drift that start the next run as one pass over the particles (the same
 * operations in the same order, so the same bits as separate passes: a run
 * cut into calls of any length gives the same state).
 *
 * Velocity Verlet (seed 004 eq. 9): forces at the start of a step are the
 * ones computed at the end of the previous step, so sd_world_prepare
 * computes them once before the first step (sd_cells_prepare: the cells
 * solver's half of the solver interface, world/solver.h). Every stage is one loop of the
 * backend; the CUDA backend will provide the same stages.
 */
#include <math.h>

#include "backend/cpu/loops.h"
#include "backend/cpu/poly.h"
#include "broad/cells.h"
#include "core/error.h"
#include "world/solver.h"
#include "world/world.h"

static sd_real sd_min_radius(const sd_world *w)
{
    sd_real r = INFINITY;
    for (size_t k = 0; k < w->p.n; ++k)
        r = sd_min(r, w->p.radius[k]);
    return r;
}

/* Contact forces of every pair for the current positions and velocities,
 * stored per pair (the gather into particles follows). */
static sd_status sd_world_pair_forces(sd_world *w, sd_error *err)
{
    if (sd_broad_needs_rebuild(w)) {
        sd_status st = sd_broad_rebuild(w, err);
        if (st != SD_OK)
            return st;
    }
    sd_cpu_pair_forces(w);
    if (w->dim2) { /* the planar mode: 2D shapes (2D GJK/EPA) and wall lines */
        sd_cpu_convex2d_forces(w);
        if (w->pairs.n > w->pairs.n_sphere)
            sd_cpu_narrow2d_totals(w);
        sd_cpu_wall_forces2d(w);
        sd_cpu_wall_totals(w);
        return SD_OK;
    }
    sd_cpu_convex_forces(w);
    if (w->pairs.n > w->pairs.n_sphere)
        sd_cpu_narrow_totals(w);
    sd_cpu_wall_forces(w);
    if (w->has_volume_law)
        sd_cpu_poly_wall_forces(w); /* polyhedron walls under a volume law */
    sd_cpu_wall_totals(w);
    return SD_OK;
}

sd_status sd_cells_prepare(sd_world *w, sd_error *err)
{
    sd_status st = sd_world_mix_materials(w, err);
    if (st != SD_OK)
        return st;
    st = sd_world_check_params(w, err);
    if (st != SD_OK)
        return st;
    if (w->def.skin > 0)
        w->skin = (sd_real)w->def.skin;
    else if (w->p.n > 0)
        w->skin = SD_R(0.2) * sd_min_radius(w);
    else
        w->skin = SD_R(0.0);
    w->dirty = 1;
    st = sd_world_pair_forces(w, err);
    if (st != SD_OK)
        return st;
    sd_cpu_gather(w);
    w->prepared = 1;
    return SD_OK;
}

/* A NaN anywhere ends the run with a clear message rather than garbage:
 * position, velocity, spin and orientation (a NaN spin reaches x only
 * through contacts, so a free body would carry it silently). The squares
 * also catch values past ~1e154, whose energies (stats.csv) already
 * overflow to inf. One sum per particle: a NaN or inf in any term makes
 * the sum non-finite. */
static sd_status sd_world_check_finite(const sd_world *w, sd_error *err)
{
    const sd_particles *p = &w->p;
    int bad = 0;
    size_t n = p->n;
SD_PARALLEL_FOR_REDUCE_OR(bad)
    for (size_t k = 0; k < n; ++k)
        bad |= !isfinite(sd_v3_norm2(p->x[k]) + sd_v3_norm2(p->v[k]) + sd_v3_norm2(p->w[k]) + p->q[k].w +
                         p->q[k].x + p->q[k].y + p->q[k].z);
    if (bad)
        return sd_error_set(err, SD_ERR_PHYSICS, "", 0, "", "a particle state became NaN or infinite at step %ld "
                            "(time step too large for the stiffness?)", w->step);
    return SD_OK;
}

sd_status sd_cells_step(sd_world *w, long nsteps, sd_error *err)
{
    if (!w->prepared) {
        sd_status st = sd_cells_prepare(w, err);
        if (st != SD_OK)
            return st;
    }
    if (nsteps > 0) {
        sd_cpu_kick_drift(w);                        /* v(t + dt/2), x(t + dt) */
        sd_status st = sd_world_walls_drift(w, w->time, err); /* moving walls to t + dt (servo.c) */
        if (st != SD_OK)
            return st;
    }
    for (long s = 0; s < nsteps; ++s) {
        sd_status st = sd_world_pair_forces(w, err); /* per pair, at t + dt */
        if (st != SD_OK)
            return st;
        if (s + 1 < nsteps) {
            sd_cpu_gather_kick_drift(w);             /* F, v(t + dt); next v(t + 3dt/2), x(t + 2dt) */
            st = sd_world_walls_drift(w, w->time + (double)w->dt, err);
            if (st != SD_OK)
                return st;
        } else
            sd_cpu_gather_kick(w);                   /* F(t + dt), v(t + dt) */
        w->step++;
        w->time = (double)w->step * (double)w->dt;
        if ((w->step & 255) == 0 && (st = sd_world_check_finite(w, err)) != SD_OK)
            return st;
    }
    return sd_world_check_finite(w, err);
}
