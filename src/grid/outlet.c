/* outlet.c — a hopper orifice for the grid solver (seed 001 §4.2): a
 * rectangular hole in the floor (zmin face) of the domain box.
 *
 * Invariant: the hole only changes the floor's geometry (stencil.h,
 * sd_grid_holed_floor: outside the hole the face, above it the hole's rim);
 * particles that fall through are removed once their centre is one radius
 * below the floor (they then touch nothing in the box), and counted with
 * their mass in sd_grid_info.removed_outlet / removed_mass, which gives the
 * discharge curve (mass fraction discharged against time).
 */
#include "core/error.h"
#include "grid/grid.h"
#include "world/world.h"

sd_status sd_grid_set_outlet(sd_world *w, double x0, double x1, double y0, double y1, sd_error *err)
{
    if (!(x1 > x0 && y1 > y0))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "outlet", "outlet needs x1 > x0 and y1 > y0");
    sd_grid_state *g = sd_grid_state_get(w);
    if (!g)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    g->outlet = 1;
    g->hx0 = (sd_real)x0;
    g->hx1 = (sd_real)x1;
    g->hy0 = (sd_real)y0;
    g->hy1 = (sd_real)y1;
    if (w->prepared && g->ncell) {
        /* opened during a run: only the floor changes, the state goes on */
        for (int k = 0; k < g->nwalls; ++k)
            if (g->walls[k].kind == SD_GRID_WALL_BOX) {
                g->walls[k].holed = 1;
                g->walls[k].hx0 = g->hx0;
                g->walls[k].hx1 = g->hx1;
                g->walls[k].hy0 = g->hy0;
                g->walls[k].hy1 = g->hy1;
            }
    }
    return SD_OK;
}
