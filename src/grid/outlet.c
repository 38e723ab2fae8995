/* outlet.c — a hopper orifice for the grid solver (seed 001 §4.2): a
 * rectangular hole in the floor (zmin face) of the domain box.
 *
 * Invariant: the hole only changes the floor's geometry (stencil.h,
 * sd_grid_holed_floor: outside the hole the face, above it the hole's rim);
 * particles that fall through are removed once their centre is one radius
 * below the floor (they then touch nothing in the box), and counted with
 * their mass in sd_grid_info.removed_outlet / removed_mass, which gives the
 * discharge curve (mass fraction discharged against time). The hole may
 * open at a given time (fill, settle, open: seed 001 §4.2): it opens at the
 * start of the first step at or after that time.
 */
#include <math.h>

#include "core/error.h"
#include "grid/grid.h"
#include "world/world.h"

/* Makes the hole part of the floor the kernel sees (between steps). */
static void sd_grid_open_outlet(sd_grid_state *g)
{
    g->outlet = 1;
    g->outlet_pending = 0;
    for (int k = 0; k < g->nwalls; ++k)
        if (g->walls[k].kind == SD_GRID_WALL_BOX) {
            g->walls[k].holed = 1;
            g->walls[k].hx0 = g->hx0;
            g->walls[k].hx1 = g->hx1;
            g->walls[k].hy0 = g->hy0;
            g->walls[k].hy1 = g->hy1;
        }
}

sd_status sd_grid_set_outlet_at(sd_world *w, double x0, double x1, double y0, double y1, double t_open,
                                sd_error *err)
{
    if (!(x1 > x0 && y1 > y0))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "outlet", "outlet needs x1 > x0 and y1 > y0");
    if (!(t_open >= 0) || !isfinite(t_open))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "outlet.open_at", "outlet opening time must be >= 0 s");
    sd_grid_state *g = sd_grid_state_get(w);
    if (!g)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    g->hx0 = (sd_real)x0;
    g->hx1 = (sd_real)x1;
    g->hy0 = (sd_real)y0;
    g->hy1 = (sd_real)y1;
    g->outlet = 0;
    g->outlet_pending = 1;
    g->outlet_time = t_open;
    g->info.outlet_time = t_open;
    sd_grid_outlet_step(w);
    return SD_OK;
}

sd_status sd_grid_set_outlet(sd_world *w, double x0, double x1, double y0, double y1, sd_error *err)
{
    return sd_grid_set_outlet_at(w, x0, x1, y0, y1, w->time, err);
}

int sd_grid_outlet_due(const sd_world *w)
{
    const sd_grid_state *g = w->grid_state;
    return g && g->outlet_pending && !(w->time + 0.5 * (double)w->dt < g->outlet_time);
}

void sd_grid_outlet_step(sd_world *w)
{
    sd_grid_state *g = w->grid_state;
    if (!sd_grid_outlet_due(w))
        return;
    /* before set-up the walls are not copied yet: sd_grid_setup holes them */
    g->outlet = 1;
    g->outlet_pending = 0;
    g->info.outlet_open = 1;
    if (g->ncell)
        sd_grid_open_outlet(g);
}
