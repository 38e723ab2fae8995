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
                            "%g s, so dt must be at most %g s (1/5 of it); recommended dt = %g s",
                            (double)w->dt, tc, tc / 5.0, rec);
    w->dt_checked = (double)w->dt;
    w->dt_checked_n = n;
    return SD_OK;
}
