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

struct sd_state_table; /* world/snapshot.h */

/* Sums of sd_world_stats (analysis/stats.c): the world's own particle
 * arrays are summed first, then the solver adds what it holds. */
typedef struct sd_stat_sums {
    double ekt, ekr, epg, vmax2; /* J, J, J, (m/s)^2 */
    double epe, ovl;             /* J; largest overlap / half size */
    long contacts, wall_contacts;
    size_t pairs;                /* candidate pairs held */
} sd_stat_sums;

/* One line of solver-specific output: a summary.txt key with one to three
 * values, and (when column is set) a stats.csv column holding the first. */
typedef struct sd_solver_item {
    const char *key;     /* summary.txt key */
    const char *column;  /* stats.csv column, NULL: summary only */
    int n;               /* values, 1..3 */
    int integer;         /* printed as integers (counts) rather than %.10g */
    const char *sep;     /* between values: " " or " x " */
    double v[3];
} sd_solver_item;

#define SD_SOLVER_ITEMS_MAX 32

/* Inputs of sd_world_recommended_dt (material.c) for the particles the
 * solver holds or will insert: per material (256 entries) the smallest
 * radius and mass, the fastest speed and the extent along gdir. */
typedef struct sd_dt_inputs {
    double rmin[256], mmin[256];
    double vmax, zlo, zhi, rsmall;
    int any;             /* some particle, present or to come */
} sd_dt_inputs;

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
    /* adds the solver's own particles and its contacts to the sums */
    void (*stats)(const sd_world *w, sd_stat_sums *s);
    /* adds the particles the solver holds or will insert (beyond the
     * world's own arrays, which material.c reads) */
    void (*dt_inputs)(const sd_world *w, sd_v3d gdir, sd_dt_inputs *in);
    /* solver-specific output lines (none: 0); the same keys and columns
     * for the whole run once the world is prepared */
    size_t (*info)(const sd_world *w, sd_solver_item *items, size_t max);
    /* pouring and an outlet (the def checked by world.c: cookie, ranges
     * that need no solver) */
    sd_status (*set_pour)(sd_world *w, const sd_pour_def *def, sd_error *err);
    sd_status (*set_outlet)(sd_world *w, const sd_outlet_def *def, sd_error *err);
    int (*get_pour)(const sd_world *w, sd_pour_def *out);
    /* frees the solver's own state (the world frees its own arrays) */
    void (*destroy)(sd_world *w);
    /* checkpoints (world/snapshot.h): lists the solver's state into t; on
     * a restore (t->saved set) first gives its arrays the saved sizes (a
     * grid world prepares first, taking over the scene's particles) */
    sd_status (*state)(sd_world *w, struct sd_state_table *t, sd_error *err);
    /* after a restore copied the state: the world as it was when listed,
     * prepared, its forces those saved (nothing is recomputed) */
    sd_status (*resumed)(sd_world *w, sd_error *err);
} sd_solver_ops;

/* The two implementations. */
extern const sd_solver_ops sd_solver_cells; /* world.c, its step in step.c */
extern const sd_solver_ops sd_solver_grid;  /* grid/grid_solver.c */

/* The cells engine (world/step.c). */
sd_status sd_cells_prepare(sd_world *w, sd_error *err);
/* Its checkpoint state and resumption (world/snapshot.c). */
sd_status sd_cells_state(sd_world *w, struct sd_state_table *t, sd_error *err);
sd_status sd_cells_resumed(sd_world *w, sd_error *err);
sd_status sd_cells_step(sd_world *w, long nsteps, sd_error *err);

/* The world's own particle arrays (world.c): what the cells solver reads,
 * and where the grid solver finds the spheres added since its last
 * prepare. */
size_t sd_cells_count(const sd_world *w);
sd_status sd_cells_read(const sd_world *w, size_t k, sd_particle_state *out);
size_t sd_cells_find(const sd_world *w, uint64_t id);
/* The cells solver's contacts from its pair lists (analysis/stats.c). */
void sd_cells_stats(const sd_world *w, sd_stat_sums *s);

/* The world's solver's items (world.c; io/output.c writes them). */
size_t sd_world_solver_items(const sd_world *w, sd_solver_item *items, size_t max);

#endif
