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
    .destroy = sd_grid_solver_destroy,
};
