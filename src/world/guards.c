/* guards.c — the library's own time-step check (issue 17): sd_world_step
 * refuses a time step above the stability limit, as sd_scene_build and
 * `shapedem check` do, rather than step a world whose contacts gain energy
 * until every particle is blown out of its box.
 *
 * The limit is 1/5 of the shortest estimated contact duration
 * (sd_world_recommended_dt; seed 004 eqs. 12, 16 for the linear law, seed
 * 001 eq. 11 for the grid): with fewer than five steps per contact a
 * collision is not resolved. It is computed again only when the time step
 * or the particle count changed since the last check, so stepping in short
 * calls costs nothing more. An estimate that is not finite and positive
 * (no pair can touch, or values at the ends of the double range) is not
 * refused here: the finite-state check of the step catches what follows.
 */
#include <math.h>

#include "core/error.h"
#include "world/solver.h"
#include "world/world.h"

sd_status sd_world_check_dt(sd_world *w, sd_error *err)
{
    size_t n = w->solver->count(w);
    if (w->prepared && (double)w->dt == w->dt_checked && n == w->dt_checked_n)
        return SD_OK;
    if (!w->prepared) {
        /* the estimate reads the mixed materials */
        sd_status st = w->solver->prepare(w, err);
        if (st != SD_OK)
            return st;
        n = w->solver->count(w);
    }
    double tc = 0;
    double rec = sd_world_recommended_dt(w, &tc);
    if (isfinite(tc) && tc > 0 && (double)w->dt > tc / 5.0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.dt",
                            "time step above the stability limit: dt = %g s but the shortest contact lasts about "
                            "%g s, so dt must be at most %g s (1/5 of it); recommended dt (for accuracy: about 50 steps "
                            "per contact, and the volume law's own limits) = %g s",
                            (double)w->dt, tc, tc / 5.0, rec);
    w->dt_checked = (double)w->dt;
    w->dt_checked_n = n;
    return SD_OK;
}

/* ---- numerical guards ---------------------------------------------------------
 * Checked with the step's finite-state check (every 256 steps and at the
 * end of each sd_world_step call, world/step.c): each names the particle
 * by its stable id, the step and the likely cause, and stops the run with
 * SD_ERR_PHYSICS (io/run.c then writes the state for inspection). */

/* The first particle whose state is NaN, infinite or so large that its
 * squares overflow (the backend's finite check sums squares). */
sd_status sd_world_guard_nonfinite(sd_world *w, sd_error *err)
{
    const sd_particles *p = &w->p;
    for (size_t k = 0; k < p->n; ++k) {
        double s = (double)(sd_v3_norm2(p->x[k]) + sd_v3_norm2(p->v[k]) + sd_v3_norm2(p->w[k]) +
                            p->q[k].w * p->q[k].w + p->q[k].x * p->q[k].x + p->q[k].y * p->q[k].y +
                            p->q[k].z * p->q[k].z);
        if (!isfinite(s))
            return sd_error_set(err, SD_ERR_PHYSICS, "", 0, "",
                                "particle id %llu: its state became NaN or infinite at step %ld (time step too "
                                "large for the stiffness?)",
                                (unsigned long long)p->id[k], w->step);
    }
    return SD_OK;
}

sd_status sd_world_guards(sd_world *w, sd_error *err)
{
    const sd_particles *p = &w->p;
    size_t n = p->n;
    if (w->guards_off)
        return SD_OK;
    /* a particle that crosses more than a cell of the broad phase in one
     * step can pass through a neighbour or a wall unseen */
    sd_real cell = w->bins.h;
    if (cell > 0)
        for (size_t k = 0; k < n; ++k) {
            sd_real d = sd_v3_norm(p->v[k]) * w->dt;
            if (d > cell)
                return sd_error_set(err, SD_ERR_PHYSICS, "", 0, "",
                                    "particle id %llu moves %g m per step at step %ld (speed %g m/s), more than a "
                                    "cell of the broad phase (%g m): time step too large, or the particle was shot "
                                    "out of an overlap (stiffness too low for the load)",
                                    (unsigned long long)p->id[k], (double)d, w->step, (double)sd_v3_norm(p->v[k]),
                                    (double)cell);
        }
    /* an overlap beyond max_overlap of the smaller size (simulation.
     * max_overlap, 0.5 by default, 0 = off): the contact law no longer
     * describes it */
    const sd_real lim = (sd_real)w->def.max_overlap;
    if (!(lim > 0))
        return SD_OK;
    const sd_pair_list *l = &w->pairs;
    for (size_t e = 0; e < l->n; ++e) {
        sd_real r = sd_min(p->radius[l->i[e]], p->radius[l->j[e]]);
        if (l->delta[e] > lim * r)
            return sd_error_set(err, SD_ERR_PHYSICS, "", 0, "",
                                "particles id %llu and id %llu overlap by %g m at step %ld, %.0f %% of the smaller "
                                "one's radius (the guard's limit is %.0f %%, simulation.max_overlap): stiffness too low "
                                "for the load, or time step too large",
                                (unsigned long long)p->id[l->i[e]], (unsigned long long)p->id[l->j[e]],
                                (double)l->delta[e], w->step, 100.0 * (double)(l->delta[e] / r),
                                100.0 * (double)lim);
    }
    const sd_wall_pair_list *wl = &w->wpairs;
    for (size_t e = 0; e < wl->n; ++e) {
        sd_real r = p->radius[wl->i[e]];
        if (!(wl->delta[e] > lim * r))
            continue;
        /* a mesh holds its particles on the side its facets' normals point
         * to: a particle that came from the other side (an open sheet
         * wound the wrong way, a closed mesh given the wrong `side:`) or
         * through a part thinner than its reach is "overlapped" by up to
         * its whole size at once (issue 30) */
        const sd_wall *wall = &w->walls[wl->wall[e]];
        const char *why = wall->kind == SD_WALL_MESH
                              ? "the particle is on the mesh's far side (the particles' side is the one its facets' "
                                "normals point to: `side:` of a closed mesh, the file's winding for an open one), "
                                "it passed through a part of the mesh thinner than its size, or the stiffness is "
                                "too low for the load or the time step too large"
                              : "stiffness too low for the load, or time step too large";
        return sd_error_set(err, SD_ERR_PHYSICS, "", 0, "",
                            "particle id %llu overlaps wall '%s' by %g m at step %ld, %.0f %% of its radius "
                            "(the guard's limit is %.0f %%, simulation.max_overlap): %s",
                            (unsigned long long)p->id[wl->i[e]], wall->name, (double)wl->delta[e], w->step,
                            100.0 * (double)(wl->delta[e] / r), 100.0 * (double)lim, why);
    }
    return SD_OK;
}
