/* grid_snapshot.c — the grid solver's state for checkpoints (its
 * sd_solver_ops.state and .resumed, world/solver.h; world/snapshot.h says
 * what a checkpoint holds and how a restore uses the list).
 *
 * Listed: the particle records in storage order, their forces and torques
 * of the last step (velocity Verlet's next kick uses them), cells and
 * overflow list, history slots, the kind table and its hash, the row
 * hints, the epoch stamp of the history tags, the geometry (a restore
 * refuses another), the walls as the kernel sees them, the outlet, the pour
 * with its random generator, and the counters. Not listed: the occupancy
 * bits and per-block wall totals, which every force pass rebuilds.
 *
 * A restore prepares the freshly built world first (the scene's particles
 * are absorbed, the geometry set up, the checks of prepare made), then
 * every listed array takes the saved size and the saved bits.
 */
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "grid/grid.h"
#include "world/snapshot.h"
#include "world/solver.h"
#include "world/world.h"

static sd_status sd_grid_saved_size(const sd_state_table *t, const char *name, size_t *out, sd_error *err)
{
    uint64_t v;
    if (!sd_snapshot_get_u64(t->saved, name, &v) || v > ((uint64_t)1 << 40))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, name, "the checkpoint lacks the size '%s' or it is out of "
                            "range", name);
    *out = (size_t)v;
    return SD_OK;
}

static size_t sd_grid_saved_rows(const sd_state_table *t, const char *name)
{
    const sd_snap_item *it = sd_snapshot_find(t->saved, name);
    return it ? it->count : 0;
}

sd_status sd_grid_state_list(sd_world *w, sd_state_table *t, sd_error *err)
{
    sd_status st;
    if (t->saved && !w->prepared && (st = sd_grid_prepare(w, err)) != SD_OK)
        return st;
    sd_grid_state *g = w->grid_state;
    if (!g) {
        if (t->saved)
            return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "grid world without its state after prepare");
        return sd_cells_state(w, t, err); /* never prepared: the world's own arrays hold everything */
    }
    if (t->saved) {
        size_t n = 0, nk = 0, nover = 0;
        if ((st = sd_grid_saved_size(t, "grid/n", &n, err)) != SD_OK ||
            (st = sd_grid_saved_size(t, "grid/nkinds", &nk, err)) != SD_OK ||
            (st = sd_grid_saved_size(t, "grid/nover", &nover, err)) != SD_OK)
            return st;
        size_t kh = sd_grid_saved_rows(t, "grid/khash");
        if (kh & (kh - 1))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "grid/khash", "the kind hash has %zu slots, not a power "
                                "of two", kh);
        if (sd_grid_reserve(g, n) != SD_OK)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for %zu particles", n);
        if (nk > g->kcap) {
            sd_grid_kind *k = sd_realloc(g->kinds, nk * sizeof *k);
            if (!k)
                return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
            g->kinds = k;
            g->kcap = nk;
        }
        if (kh != g->khcap) {
            uint32_t *h = sd_realloc(g->khash, (kh ? kh : 1) * sizeof *h);
            if (!h)
                return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
            g->khash = h;
            g->khcap = kh;
        }
        if (nover > g->over_cap) {
            uint32_t *o = sd_realloc(g->over, nover * sizeof *o);
            if (!o)
                return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
            g->over = o;
            g->over_cap = nover;
        }
        g->n = n;
        g->nkinds = nk;
        g->nover = nover;
    }
    size_t n = g->n, rows = (size_t)(g->nz * g->ny);
    sd_state_add(t, "grid/n", SD_ST_U64, 1, 1, &g->n, 8);
    sd_state_add(t, "grid/part", SD_ST_BYTES, sizeof(sd_grid_part), n, g->part, sizeof(sd_grid_part));
    sd_state_add(t, "grid/ft", SD_ST_F64, 6, n, g->ft, 2 * sizeof(sd_vec3));
    sd_state_add(t, "grid/where", SD_ST_U32, 1, n, g->where, 4);
    sd_state_add(t, "grid/home", SD_ST_U32, 1, n, g->home, 4);
    sd_state_add(t, "grid/tag", SD_ST_U32, SD_GRID_SLOTS, n, g->tag, 4 * SD_GRID_SLOTS);
    sd_state_add(t, "grid/ds", SD_ST_F64, 3 * SD_GRID_SLOTS, n, g->ds, sizeof(sd_vec3) * SD_GRID_SLOTS);
    sd_state_add(t, "grid/nkinds", SD_ST_U64, 1, 1, &g->nkinds, 8);
    sd_state_add(t, "grid/kinds", SD_ST_BYTES, sizeof(sd_grid_kind), g->nkinds, g->kinds, sizeof(sd_grid_kind));
    sd_state_add(t, "grid/khash", SD_ST_U32, 1, g->khcap, g->khash, 4);
    sd_state_add(t, "grid/cell", SD_ST_I32, 1, g->ncell, g->cell, 4);
    sd_state_add(t, "grid/nover", SD_ST_U64, 1, 1, &g->nover, 8);
    sd_state_add(t, "grid/over", SD_ST_U32, 1, g->nover, g->over, 4);
    sd_state_add(t, "grid/rowocc", SD_ST_U8, 1, g->rowocc ? rows : 0, g->rowocc, 1);
    sd_state_add(t, "grid/epoch", SD_ST_U32, 1, 1, &g->epoch, 4);
    sd_state_add(t, "grid/rmax", SD_ST_F64, 1, 1, &g->rmax, 8);
    /* the geometry: equal after a prepare of the same scene (the cell
     * array's size is checked; these values are copied back unchanged) */
    sd_state_add(t, "grid/lo", SD_ST_F64, 3, 1, &g->lo, 0);
    sd_state_add(t, "grid/h", SD_ST_F64, 1, 1, &g->h, 0);
    sd_state_add(t, "grid/size", SD_ST_I64, 1, 1, &g->nx, 0);
    sd_state_add(t, "grid/size_y", SD_ST_I64, 1, 1, &g->ny, 0);
    sd_state_add(t, "grid/size_z", SD_ST_I64, 1, 1, &g->nz, 0);
    sd_state_add(t, "grid/walls", SD_ST_BYTES, sizeof(sd_grid_wall), (size_t)g->nwalls, g->walls,
                 sizeof(sd_grid_wall));
    sd_state_add(t, "grid/outlet", SD_ST_I32, 1, 1, &g->outlet, 0);
    sd_state_add(t, "grid/outlet_pending", SD_ST_I32, 1, 1, &g->outlet_pending, 0);
    sd_state_add(t, "grid/outlet_time", SD_ST_F64, 1, 1, &g->outlet_time, 0);
    sd_state_add(t, "grid/hole", SD_ST_F64, 1, 1, &g->hx0, 0);
    sd_state_add(t, "grid/hole_x1", SD_ST_F64, 1, 1, &g->hx1, 0);
    sd_state_add(t, "grid/hole_y0", SD_ST_F64, 1, 1, &g->hy0, 0);
    sd_state_add(t, "grid/hole_y1", SD_ST_F64, 1, 1, &g->hy1, 0);
    sd_state_add(t, "grid/pour", SD_ST_BYTES, sizeof(sd_grid_pour), 1, &g->pour, 0);
    sd_state_add(t, "grid/info", SD_ST_BYTES, sizeof(sd_grid_info), 1, &g->info, 0);
    /* spheres added to the world since the last prepare, in its own arrays */
    return sd_cells_state(w, t, err);
}

sd_status sd_grid_state_resumed(sd_world *w, sd_error *err)
{
    sd_grid_state *g = w->grid_state;
    if (!g)
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "grid world without its state");
    /* indices a damaged (yet checksummed) or crafted file could send past
     * the arrays */
    for (size_t k = 0; k < g->n; ++k) {
        if (g->part[k].kind >= g->nkinds)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "grid/part", "particle %zu has kind %u of %zu", k,
                                g->part[k].kind, g->nkinds);
        if ((g->where[k] >= g->ncell && g->where[k] != SD_GRID_OUTSIDE) ||
            (g->home[k] >= g->ncell && g->home[k] != SD_GRID_OVER))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "grid/where", "particle %zu has a cell past the grid", k);
    }
    for (size_t c = 0; c < g->ncell; ++c)
        if (g->cell[c] < -1 || (g->cell[c] >= 0 && (size_t)g->cell[c] >= g->n))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "grid/cell", "cell %zu holds particle %d of %zu", c,
                                (int)g->cell[c], g->n);
    for (size_t e = 0; e < g->nover; ++e)
        if (g->over[e] >= g->n)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "grid/over", "overflow entry %zu is particle %u of %zu", e,
                                g->over[e], g->n);
    for (size_t k = 0; k < g->nkinds; ++k)
        if (g->kinds[k].material < 0 || (size_t)g->kinds[k].material >= w->material_count)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "grid/kinds", "kind %zu has material %d", k,
                                (int)g->kinds[k].material);
    for (size_t k = 0; k < g->khcap; ++k)
        if (g->khash[k] > g->nkinds)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "grid/khash", "kind hash slot %zu out of range", k);
    sd_grid_set_parallel(w);
    w->prepared = 1;
    return SD_OK;
}
