/* step.c — the time step of the cells solver, stage by stage (DESIGN.md
 * data flow).
 *
 *   kick + drift ─► rebuild pairs when the skin is used up ─► ghosts
 *   ─► pair forces, one kind segment at a time ─► wall forces, wall totals
 *   ─► gather per particle ─► kick ─► clock ─► finite check
 *
 * Each stage is an entry of the backend's stage table (backend/backend.h)
 * working on the views the world fills (world/view.c), never a loop of
 * its own here; each is timed into the world's profile (sd_profile: two
 * clock reads per stage per step).
 *
 * Within one call the gather and kick that end a step and the kick and
 * drift that start the next run as one pass over the particles (the same
 * operations in the same order, so the same bits as separate passes: a run
 * cut into calls of any length gives the same state).
 * sd_world_request_interrupt ends a call early, after a step: that step's
 * kick is then not fused with the next drift, as at any call's end, so an
 * interrupted run continued gives the same bits (tests/unit/interrupt.c).
 *
 * Velocity Verlet (seed 004 eq. 9): forces at the start of a step are the
 * ones computed at the end of the previous step, so sd_world_prepare
 * computes them once before the first step (sd_cells_prepare: the cells
 * solver's half of the solver interface, world/solver.h). The CUDA backend
 * provides the same stages on device copies of the same views.
 */
#include <math.h>

#include "backend/backend.h"
#include "core/error.h"
#include "world/profile.h"
#include "world/solver.h"
#include "world/view.h"
#include "world/world.h"

/* The profile has one stage per pair kind, in the kinds' order. */
_Static_assert(SD_PROFILE_SPHERES + SD_PAIR_SPHERES == SD_PROFILE_SPHERES &&
                   SD_PROFILE_SPHERES + SD_PAIR_CONVEX == SD_PROFILE_CONVEX &&
                   SD_PROFILE_SPHERES + SD_PAIR_POLY_VOLUME == SD_PROFILE_POLY_VOLUME &&
                   SD_PROFILE_SPHERES + SD_PAIR_CONVEX2D == SD_PROFILE_CONVEX2D &&
                   SD_PROFILE_SPHERES + SD_PAIR_ELEMENTS == SD_PROFILE_ELEMENTS &&
                   SD_PROFILE_SPHERES + SD_PAIR_KIND_COUNT == SD_PROFILE_WALLS,
               "SD_PROFILE_STAGES lists the pair kinds of contact/kinds.h in their order");

/* The stages' backend: the CPU's OpenMP loops or the CUDA kernels, chosen
 * when the world was created (world/backend.c: sd_world_def.backend and
 * the device probe). */
static const sd_backend *sd_backend_of(const sd_world *w)
{
    return w->backend ? w->backend : &sd_backend_cpu;
}

/* Broad phase: new pair lists when the skin is used up, a wall moved
 * beyond it or particles were added; the views follow the new arrays; then
 * the ghosts' state (another rank's particles, periodic images). */
static sd_status sd_stage_rebuild(sd_world *w, const sd_backend *be, sd_error *err)
{
    double t = sd_profile_now();
    int need = w->dirty || sd_world_walls_moved(w) || be->needs_rebuild(&w->stage);
    if (w->comm) /* the ranks rebuild together (migration and ghosts are collective) */
        need = w->comm->any(w->comm_ctx, need);
    if (need) {
        sd_status st = be->rebuild(w, err);
        if (st != SD_OK)
            return st;
        if (sd_world_views(w) != SD_OK)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the views of %zu walls",
                                w->wall_count);
        be->upload(&w->stage);
        if ((st = be->status(&w->stage, err)) != SD_OK)
            return st;
    }
    sd_stage *s = &w->stage;
    if (w->comm) {
        /* other ranks' particles: their owners' state of this step, sent
         * from and received into the host's rows (a device backend copies
         * the owned rows back before and the ghost rows up after; nothing
         * on the CPU) */
        be->read_back_state(s, 0, s->v.n_owned);
        w->comm->exchange(w->comm_ctx, w);
        be->upload_state(s, s->v.n_owned, s->v.n_total);
    }
    /* the local images (periodic) after that upload, which carried the
     * host's stale copies of them (independent of the exchange: an image
     * reads its own owner's row, the exchange writes other ranks' rows only) */
    be->exchange_ghosts(s);
    sd_profile_lap(w, SD_PROFILE_REBUILD, &t, 1);
    return SD_OK;
}

/* Contact forces of every pair for the current positions and velocities,
 * kind by kind, stored per pair (the gather into particles follows), then
 * the walls' totals. */
static sd_status sd_stage_forces(sd_world *w, const sd_backend *be, sd_error *err)
{
    sd_status st = sd_stage_rebuild(w, be, err);
    if (st != SD_OK)
        return st;
    sd_stage *s = &w->stage;
    double t = sd_profile_now();
    for (int k = 0; k < SD_PAIR_KIND_COUNT; ++k)
        if (s->pairs.kind_start[k + 1] > s->pairs.kind_start[k]) {
            be->forces(s, (sd_pair_kind)k);
            sd_profile_lap(w, (sd_profile_stage)(SD_PROFILE_SPHERES + k), &t, 1);
        }
    if (w->wall_count > 0) {
        be->wall_forces(s);
        be->wall_totals(s);
        sd_world_views_wall_totals(w);
        sd_profile_lap(w, SD_PROFILE_WALLS, &t, 1);
    }
    return SD_OK;
}

/* Moving walls to time t + dt (servo.c), and their views. */
static sd_status sd_stage_walls_drift(sd_world *w, const sd_backend *be, double t, sd_error *err)
{
    if (w->wall_count == 0)
        return SD_OK;
    /* a servo wall's gain reads the wall pairs' overlaps on the host: a
     * device backend brings them back first (the wall totals are already
     * there: the wall totals stage leaves them in s->wall_force) */
    if (w->walls_moving)
        be->read_back_wall_pairs(&w->stage);
    sd_status st = sd_world_walls_drift(w, t, err);
    if (st != SD_OK)
        return st;
    sd_world_views_walls(w);
    be->upload_walls(&w->stage);
    return SD_OK;
}

/* A NaN anywhere ends the run with a clear message rather than garbage,
 * naming the particle; then the guards (guards.c: runaway speed, deep
 * overlap). */
static sd_status sd_stage_check_finite(sd_world *w, const sd_backend *be, sd_error *err)
{
    int bad = be->check_finite(&w->stage);
    /* the guards (and the NaN report's particle) read the state on the
     * host: a device backend copies it back first */
    be->read_back(&w->stage);
    sd_status st = be->status(&w->stage, err);
    if (st != SD_OK)
        return st;
    sd_world_views_wall_totals(w); /* a device may sum them only with the read back (fixed walls) */
    if (bad) {
        if (sd_world_guard_nonfinite(w, err) != SD_OK)
            return SD_ERR_PHYSICS;
        return sd_error_set(err, SD_ERR_PHYSICS, "", 0, "", "a particle state became NaN or infinite at step %ld "
                            "(time step too large for the stiffness?)", w->step);
    }
    return sd_world_guards(w, err);
}

sd_status sd_cells_prepare(sd_world *w, sd_error *err)
{
    sd_status st = sd_world_mix_materials(w, err);
    if (st != SD_OK)
        return st;
    st = sd_world_check_params(w, err);
    if (st != SD_OK)
        return st;
    const sd_backend *be = sd_backend_of(w);
    if (sd_world_views(w) != SD_OK)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the views of %zu walls",
                            w->wall_count);
    be->upload(&w->stage);
    if ((st = be->status(&w->stage, err)) != SD_OK)
        return st;
    if (w->def.skin > 0)
        w->skin = (sd_real)w->def.skin;
    else if (w->comm) { /* the same skin on every rank: from the smallest radius of all */
        double rmin = w->comm->min(w->comm_ctx, w->p.n > 0 ? (double)be->min_radius(&w->stage) : (double)INFINITY);
        w->skin = isfinite(rmin) ? SD_R(0.2) * (sd_real)rmin : SD_R(0.0);
    } else if (w->p.n > 0)
        w->skin = SD_R(0.2) * be->min_radius(&w->stage);
    else
        w->skin = SD_R(0.0);
    w->dirty = 1; /* the rebuild refills the views, with the skin */
    st = sd_stage_forces(w, be, err);
    if (st != SD_OK)
        return st;
    double t = sd_profile_now();
    be->gather(&w->stage);
    be->read_back(&w->stage); /* the step-0 frame shows these forces */
    sd_profile_lap(w, SD_PROFILE_INTEGRATION, &t, 0);
    if ((st = be->status(&w->stage, err)) != SD_OK)
        return st;
    sd_world_views_wall_totals(w);
    w->prepared = 1;
    return SD_OK;
}

sd_status sd_cells_step(sd_world *w, long nsteps, sd_error *err)
{
    if (!w->prepared) {
        sd_status st = sd_cells_prepare(w, err);
        if (st != SD_OK)
            return st;
    }
    const sd_backend *be = sd_backend_of(w);
    sd_stage *s = &w->stage;
    sd_world_views_params(w);
    /* between calls the host may have changed the state (insertions and
     * outlets, a restore, the public setters; the last call ended with a
     * read back): a device backend takes the host's copy again */
    be->upload(s);
    be->upload_walls(s);
    sd_status st0 = be->status(s, err);
    if (st0 != SD_OK)
        return st0;
    double t = sd_profile_now();
    if (nsteps > 0) {
        be->kick_drift(s);                                  /* v(t + dt/2), x(t + dt) */
        sd_status st = sd_stage_walls_drift(w, be, w->time, err); /* moving walls to t + dt */
        if (st != SD_OK)
            return st;
        sd_profile_lap(w, SD_PROFILE_INTEGRATION, &t, 0);
    }
    int stop = 0; /* sd_world_request_interrupt: this step is the last (its kick not fused with the next drift) */
    for (long k = 0; k < nsteps && !stop; ++k) {
        sd_status st = sd_stage_forces(w, be, err);         /* per pair, at t + dt */
        if (st != SD_OK)
            return st;
        t = sd_profile_now();
        stop = k + 1 < nsteps && sd_world_interrupt_due(w);
        if (k + 1 < nsteps && !stop) {
            be->gather_kick_drift(s);                       /* F, v(t + dt); next v(t + 3dt/2), x(t + 2dt) */
            st = sd_stage_walls_drift(w, be, w->time + (double)w->dt, err);
            if (st != SD_OK)
                return st;
        } else
            be->gather_kick(s);                             /* F(t + dt), v(t + dt) */
        w->step++;
        w->time = (double)w->step * (double)w->dt;
        if ((w->step & 255) == 0 && (st = sd_stage_check_finite(w, be, err)) != SD_OK)
            return st;
        sd_profile_lap(w, SD_PROFILE_INTEGRATION, &t, 1);
    }
    /* the finite check reads the state back: output and queries see it */
    sd_status st = sd_stage_check_finite(w, be, err);
    return st == SD_OK && stop ? sd_world_interrupted(w, err) : st;
}
