/* grid_solver.c — the dense grid-stencil solver (seed 001) as an
 * implementation of the solver interface (world/solver.h).
 *
 * Invariant: the solver's particles (absorbed at prepare, poured, minus the
 * removed ones) come first in storage order, in stable-id order; spheres
 * added to the world since the last prepare follow, read from the world's
 * own arrays until the next prepare absorbs them (grid.h, sd_grid_absorb).
 */
#include "grid/grid.h"
#include "world/solver.h"
#include "world/world.h"

static size_t sd_grid_solver_count(const sd_world *w) { return sd_grid_particle_count(w) + sd_cells_count(w); }

static sd_status sd_grid_solver_read(const sd_world *w, size_t k, sd_particle_state *out)
{
    size_t gn = sd_grid_particle_count(w);
    return k < gn ? sd_grid_get_particle(w, k, out) : sd_cells_read(w, k - gn, out);
}

static size_t sd_grid_solver_find(const sd_world *w, uint64_t id)
{
    size_t gk = sd_grid_find_particle(w, id);
    if (gk != (size_t)-1)
        return gk;
    size_t k = sd_cells_find(w, id);
    return k == (size_t)-1 ? k : sd_grid_particle_count(w) + k;
}

/* The solver's particles after the world's own arrays (stats.c summed
 * those), then its contacts from a stencil pass: it has no pair lists. */
static void sd_grid_solver_stats(const sd_world *w, sd_stat_sums *s)
{
    sd_grid_particle_stats(w, &s->ekt, &s->ekr, &s->epg, &s->vmax2);
    sd_grid_contact_stats(w, &s->contacts, &s->wall_contacts, &s->epe, &s->ovl);
}

static void sd_grid_solver_dt_inputs(const sd_world *w, sd_v3d gdir, sd_dt_inputs *in)
{
    sd_vec3 g = sd_v3((sd_real)gdir.x, (sd_real)gdir.y, (sd_real)gdir.z);
    in->any |= sd_grid_has_particles(w);
    sd_grid_dt_inputs(w, g, in->rmin, in->mmin, &in->vmax, &in->zlo, &in->zhi, &in->rsmall);
}

static void sd_item(sd_solver_item *items, size_t *n, size_t max, const char *key, const char *column, int integer,
                    int nv, const char *sep, double a, double b, double c)
{
    if (*n >= max)
        return;
    sd_solver_item *it = &items[(*n)++];
    it->key = key;
    it->column = column;
    it->integer = integer;
    it->n = nv;
    it->sep = sep;
    it->v[0] = a;
    it->v[1] = b;
    it->v[2] = c;
}

/* summary.txt's grid_* lines and stats.csv's pour and outlet columns
 * (docs/output.md, docs/grid-solver.md), in their order. */
static size_t sd_grid_solver_info(const sd_world *w, sd_solver_item *it, size_t max)
{
    sd_grid_info gi;
    sd_grid_get_info(w, &gi);
    size_t n = 0;
    if (!gi.active)
        return 0;
    sd_item(it, &n, max, "grid_cell_m", NULL, 0, 1, " ", gi.cell, 0, 0);
    sd_item(it, &n, max, "grid_cells", NULL, 1, 3, " x ", (double)gi.nx, (double)gi.ny, (double)gi.nz);
    sd_item(it, &n, max, "grid_poured", "poured", 1, 1, " ", (double)gi.poured, 0, 0);
    sd_item(it, &n, max, "grid_in_domain", "in_domain", 1, 1, " ", (double)sd_grid_solver_count(w), 0, 0);
    sd_item(it, &n, max, "grid_discharged", "discharged", 1, 1, " ", (double)gi.removed_outlet, 0, 0);
    sd_item(it, &n, max, "grid_discharged_mass_kg", "discharged_mass", 0, 1, " ", gi.removed_outlet_mass, 0, 0);
    sd_item(it, &n, max, "grid_escaped", "escaped", 1, 1, " ", (double)gi.escaped, 0, 0);
    sd_item(it, &n, max, "grid_escaped_mass_kg", "escaped_mass", 0, 1, " ", gi.escaped_mass, 0, 0);
    sd_item(it, &n, max, "grid_removed", "removed", 1, 1, " ", (double)gi.removed, 0, 0);
    if (gi.failed_step)
        sd_item(it, &n, max, "grid_failed_at_step", NULL, 1, 1, " ", (double)gi.failed_step, 0, 0);
    sd_item(it, &n, max, "grid_domain_min_m", NULL, 0, 3, " ", gi.domain_lo[0], gi.domain_lo[1], gi.domain_lo[2]);
    sd_item(it, &n, max, "grid_domain_max_m", NULL, 0, 3, " ", gi.domain_hi[0], gi.domain_hi[1], gi.domain_hi[2]);
    sd_item(it, &n, max, "grid_outlet_open", NULL, 1, 1, " ", (double)gi.outlet_open, 0, 0);
    if (gi.outlet_open || gi.outlet_time > 0) {
        sd_item(it, &n, max, "grid_outlet_time_s", NULL, 0, 1, " ", gi.outlet_time, 0, 0);
        sd_item(it, &n, max, "grid_outlet_x_m", NULL, 0, 2, " ", gi.outlet_x0, gi.outlet_x1, 0);
        sd_item(it, &n, max, "grid_outlet_y_m", NULL, 0, 2, " ", gi.outlet_y0, gi.outlet_y1, 0);
    }
    sd_item(it, &n, max, "grid_conflicts_resolved", "conflicts", 1, 1, " ", (double)gi.conflicts, 0, 0);
    sd_item(it, &n, max, "grid_max_without_cell", NULL, 1, 1, " ", (double)gi.max_overflow, 0, 0);
    sd_item(it, &n, max, "grid_slot_overflows", NULL, 1, 1, " ", (double)gi.slot_overflows, 0, 0);
    sd_item(it, &n, max, "grid_slots_used_max", NULL, 1, 1, " ", (double)gi.slots_used_max, 0, 0);
    sd_item(it, &n, max, "grid_solver_bytes", NULL, 1, 1, " ", (double)gi.bytes, 0, 0);
    return n;
}

static sd_status sd_grid_solver_set_outlet(sd_world *w, const sd_outlet_def *d, sd_error *err)
{
    return sd_grid_set_outlet_at(w, d->x0, d->x1, d->y0, d->y1, d->open_at, err);
}

static int sd_grid_solver_get_pour(const sd_world *w, sd_pour_def *out)
{
    const sd_grid_state *g = w->grid_state;
    if (!g || !g->pour.active)
        return 0;
    *out = g->pour.def;
    return 1;
}

static void sd_grid_solver_destroy(sd_world *w)
{
    sd_grid_state_free(w->grid_state);
    w->grid_state = NULL;
}

const sd_solver_ops sd_solver_grid = {
    .name = "grid",
    .prepare = sd_grid_prepare,
    .step = sd_grid_step,
    .count = sd_grid_solver_count,
    .read = sd_grid_solver_read,
    .find = sd_grid_solver_find,
    .stats = sd_grid_solver_stats,
    .dt_inputs = sd_grid_solver_dt_inputs,
    .info = sd_grid_solver_info,
    .set_pour = sd_grid_pour_set,
    .set_outlet = sd_grid_solver_set_outlet,
    .get_pour = sd_grid_solver_get_pour,
    .destroy = sd_grid_solver_destroy,
    .state = sd_grid_state_list,
    .resumed = sd_grid_state_resumed,
};
