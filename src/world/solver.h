/* solver.h — the solver interface: the one seam between the world's public
 * entry points (world.c) and the engines that advance it.
 *
 * Two implementations: "cells" (the general engine: cell-list broad phase,
 * pair lists, every shape kind, world/step.c) and "grid" (the dense
 * grid-stencil solver for equal spheres of [Naderi 2024], src/grid). The
 * world picks one at creation from sd_world_def.solver and keeps it in
 * w->solver; sd_world_prepare, sd_world_step and the particle queries
 * dispatch through it, so no file outside the implementations and that one
 * choice asks which solver runs.
 *
 * Invariant: every entry is set (an implementation without a feature
 * answers with a clear message, never a NULL call); the table is host code
 * and is called once per public call, never per particle or per pair, so
 * the indirect call costs nothing on the hot path. The kernels below it
 * stay single-source SD_HD code taking plain views (DESIGN rule 6 forbids
 * function pointers in device code only).
 *
 * Particle indices seen through count/read/find are the solver's storage
 * order: for the grid, its own particles first, then spheres added to the
 * world since the last prepare.
 */
#ifndef SD_WORLD_SOLVER_H
#define SD_WORLD_SOLVER_H

#include <shapedem/shapedem.h>

typedef struct sd_solver_ops {
    const char *name; /* the scene-file name (simulation.solver) */
    /* mixes the materials, checks the parameters, computes the forces of
     * the current state (velocity Verlet needs them before the first kick) */
    sd_status (*prepare)(sd_world *w, sd_error *err);
    /* advances nsteps steps (prepares first when needed) */
    sd_status (*step)(sd_world *w, long nsteps, sd_error *err);
    /* particles now (the grid's count changes as it pours and discharges) */
    size_t (*count)(const sd_world *w);
    /* one particle by storage index; SD_ERR_INPUT past count */
    sd_status (*read)(const sd_world *w, size_t k, sd_particle_state *out);
    /* storage index of a stable id, (size_t)-1 when absent */
    size_t (*find)(const sd_world *w, uint64_t id);
    /* frees the solver's own state (the world frees its own arrays) */
    void (*destroy)(sd_world *w);
} sd_solver_ops;

/* The two implementations. */
extern const sd_solver_ops sd_solver_cells; /* world.c, its step in step.c */
extern const sd_solver_ops sd_solver_grid;  /* grid/grid_solver.c */

/* The cells engine (world/step.c). */
sd_status sd_cells_prepare(sd_world *w, sd_error *err);
sd_status sd_cells_step(sd_world *w, long nsteps, sd_error *err);

/* The world's own particle arrays (world.c): what the cells solver reads,
 * and where the grid solver finds the spheres added since its last
 * prepare. */
size_t sd_cells_count(const sd_world *w);
sd_status sd_cells_read(const sd_world *w, size_t k, sd_particle_state *out);
size_t sd_cells_find(const sd_world *w, uint64_t id);

#endif
