/* grid.h — the dense grid-stencil solver for (nearly) monodisperse spheres
 * (seed 001 §3.1–3.3, §4.1–4.2), chosen with sd_world_def.solver =
 * SD_SOLVER_GRID (scene key simulation.solver: grid).
 *
 * The domain (the union of the world's box walls) is a uniform grid of cubic
 * cells of edge R_min plus a halo of reach + 1 cells; each cell holds at most
 * one particle; contacts come from a fixed stencil around each particle's
 * cell (stencil.h).
 *
 * The solver keeps its own compact particle state (docs/grid-solver.md,
 * "Memory"): an 80-byte record per particle (position, velocity, spin,
 * stable id, kind), force and torque, the cell, and history slots; radius,
 * mass, inertia and material live once per kind of particle. At prepare it
 * takes over the spheres the world holds (sd_grid_absorb), array by array,
 * and the world's particle arrays are freed; the world's queries
 * (sd_world_particle_count, sd_world_get_particle, sd_world_find_particle,
 * sd_world_stats) read this state. Storage order is stable-id order (this
 * solver never re-sorts).
 *
 * Invariants kept between steps:
 *  - cell[c] is -1 or the storage index k of a particle with where[k] == c
 *    and home[k] == c; a particle that found its cell taken (a conflict) has
 *    home[k] == SD_GRID_OVER and is listed, in storage order, in over[];
 *  - every particle's centre lies in the inner grid (reach .. n - reach - 1
 *    cells on every axis), so the stencil never leaves the array; particles
 *    that leave it are removed and counted (outlets, open faces);
 *  - slot s of particle k holds the tangential spring of one touching
 *    contact (tag[k * SLOTS + s] != 0), keyed by the partner's stable id or
 *    the wall face, never by storage index; a particle pair's spring is in
 *    one slot of one of its two particles (stencil.h);
 *  - rowocc[z ny + y] is 1 when some particle holds a cell of that row
 *    (set when a cell is taken; cleared only when all cells are rebuilt,
 *    so a 1 may mark a row that has emptied since: a hint that skips rows).
 * See docs/grid-solver.md for the choices and their reasons.
 */
#ifndef SD_GRID_GRID_H
#define SD_GRID_GRID_H

#include <shapedem/shapedem.h>

#include "core/rng.h"
#include "grid/blocks.h"
#include "grid/stencil.h"

#define SD_GRID_OVER 0xffffffffu    /* home[k]: in the overflow list */
#define SD_GRID_OUTSIDE 0xfffffffeu /* where[k]: left the inner grid */

/* Layer-by-layer pouring (seed 001 §4.1): the public sd_pour_def
 * (shapedem.h), under the name the module's tests know. */
typedef sd_pour_def sd_grid_pour_def;

sd_grid_pour_def sd_grid_pour_def_default(void);

typedef struct sd_grid_pour {
    int active;
    sd_grid_pour_def def;
    sd_rng rng;
    double next_time;         /* s */
    size_t poured, layers, skipped;
} sd_grid_pour;

/* Counters, reported by sd_grid_get_info. */
typedef struct sd_grid_info {
    int active;               /* the world uses the grid solver and is prepared */
    double cell;              /* m, cell edge */
    int reach;                /* stencil half width: (2 reach + 1)^3 cells */
    long nx, ny, nz;          /* cells, halo included */
    long conflicts;           /* cell conflicts detected so far (steps x particles) */
    size_t in_overflow;       /* particles without a cell right now */
    size_t max_overflow;      /* the most at any step */
    long slot_overflows;      /* contact evaluations without a history slot */
    size_t removed;           /* particles that left the domain */
    size_t removed_outlet;    /* of which through the outlet hole (stats.csv `discharged`) */
    size_t escaped;           /* of which elsewhere: an open face, or past the grid (stats.csv `escaped`) */
    double removed_mass;      /* kg, of all removed particles */
    double removed_outlet_mass; /* kg, of those through the outlet (`discharged_mass`) */
    double escaped_mass;      /* kg, of those that escaped elsewhere (`escaped_mass`) */
    long failed_step;         /* the step that failed (the state is that step's drift; no further
                               * step is taken), 0 when none failed */
    size_t poured, pour_layers, pour_skipped;
    int outlet_open;          /* the outlet hole is open */
    double outlet_time;       /* s, when it opened (or will open) */
    double outlet_x0, outlet_x1, outlet_y0, outlet_y1; /* m, the hole */
    double domain_lo[3], domain_hi[3];                 /* m, the box walls' union */
    double dt_contact_limit;  /* s, pi/5 sqrt(m/k) (seed 001 eq. 11) */
    double max_speed;         /* m/s, at the last step */
    int slots_used_max;       /* the most history slots one particle held at any step */
    size_t bytes;             /* bytes held by the grid solver (particles, kinds, cells, slots, lists) */
} sd_grid_info;

struct sd_grid_state {
    /* particles (storage order = stable-id order) */
    size_t n, pcap;
    sd_grid_part *part;       /* hot record: x, v, w, id, kind */
    sd_vec3 *ft;              /* force 2k, torque 2k + 1 of the last step */
    uint32_t *where, *home;
    uint32_t *tag;            /* SD_GRID_SLOTS per particle */
    sd_vec3 *ds;
    /* kinds: distinct (radius, inverse mass, inverse inertia, material) */
    sd_grid_kind *kinds;
    size_t nkinds, kcap;
    uint32_t *khash;          /* open addressing, kind index + 1, 0 = empty */
    size_t khcap;
    /* geometry */
    sd_vec3 lo;               /* m, corner of cell (0, 0, 0) */
    sd_real h;                /* m, cell edge = smallest radius */
    sd_real rmax;             /* m, largest radius (present and poured) */
    int reach;
    long nx, ny, nz;
    size_t ncell;
    sd_vec3 dom_lo, dom_hi;   /* m, the box walls' union */
    int32_t *cell;
    /* conflicts */
    uint32_t *over;
    size_t nover, over_cap;
    /* the force pass: blocks of `slab` cells (= reach) in z and in y
     * (nslab x nband), a flag per row of cells that may hold a particle,
     * wall totals per block (+1 for the particles without a cell), and the
     * stamp of the current step */
    long slab, nslab, nband;
    uint8_t *rowocc;
    /* the equal-sphere fast path of the kernel (reach 2, stencil.h): one
     * bit per cell (set when the cell holds a particle; rebuilt from home[]
     * before each force pass), the offsets of the 62 cells of the half
     * stencil, and per sub-cell position of the owner the mask of those
     * cells a contact can reach */
    uint64_t *occ;
    size_t nocc;
    long stoff[SD_GRID_HALF2];
    uint64_t qmask[SD_GRID_Q * SD_GRID_Q * SD_GRID_Q];
    sd_vec3 *slab_wall;
    uint32_t epoch;
    /* walls as the kernel sees them */
    sd_grid_wall *walls;
    int nwalls;
    /* outlet: a hole in the zmin face of the domain box, open when
     * `outlet`, waiting for outlet_time when `outlet_pending` */
    int outlet, outlet_pending;
    double outlet_time;       /* s */
    sd_real hx0, hx1, hy0, hy1;
    sd_grid_pour pour;
    sd_grid_info info;
    size_t par_min;           /* fewest particles for threaded loops (0: SD_GRID_PARALLEL_MIN) */
    /* backend cuda: the device copy of this state (backend/cuda/grid.cu),
     * NULL on the CPU; between calls of sd_grid_step the host arrays above
     * are the state, the device's a copy made at the call's start */
    void *device;
};

typedef struct sd_grid_state sd_grid_state;

/* The world's grid state, created on first use (NULL when out of memory). */
sd_grid_state *sd_grid_state_get(sd_world *w);
void sd_grid_state_free(sd_grid_state *g);

/* Pours particles layer by layer from the first step on (or start_time):
 * sd_world_set_pour on a grid world (its checks, then sd_grid_pour_set). */
sd_status sd_grid_set_pour(sd_world *w, const sd_grid_pour_def *def, sd_error *err);
/* The solver's half of sd_world_set_pour (the def already checked). */
sd_status sd_grid_pour_set(sd_world *w, const sd_pour_def *def, sd_error *err);
/* Opens a rectangular hole [x0, x1] x [y0, y1] in the floor (zmin face) of
 * the domain box: particles fall through and are removed and counted once
 * their centre is one radius below the floor. May be called between steps
 * of a run (the orifice opens; nothing else changes). */
sd_status sd_grid_set_outlet(sd_world *w, double x0, double x1, double y0, double y1, sd_error *err);
/* The same hole, opened at simulated time t_open (s): the first step that
 * starts at or after it runs with the hole (scene key outlet.open_at). */
sd_status sd_grid_set_outlet_at(sd_world *w, double x0, double x1, double y0, double y1, double t_open,
                                sd_error *err);
/* Counters and sizes; info->active is 0 for a world on another solver. */
void sd_grid_get_info(const sd_world *w, sd_grid_info *info);

/* The solver's entry points, called by sd_world_prepare / sd_world_step. */
sd_status sd_grid_prepare(sd_world *w, sd_error *err);
sd_status sd_grid_step(sd_world *w, long nsteps, sd_error *err);

/* The world's particle queries on a grid world (world.c, stats.c): the
 * solver's particles come first (storage order), the world's own arrays
 * hold only spheres added since the last prepare. */
size_t sd_grid_particle_count(const sd_world *w);
sd_status sd_grid_get_particle(const sd_world *w, size_t k, sd_particle_state *out);
size_t sd_grid_find_particle(const sd_world *w, uint64_t id);
/* Kinetic energies, gravity potential and the largest squared speed of the
 * solver's particles, summed in storage order. */
void sd_grid_particle_stats(const sd_world *w, double *ekt, double *ekr, double *epg, double *vmax2);

/* For sd_world_recommended_dt (material.c): 1 when the solver holds or
 * will pour particles; and the smallest radius and mass per material (256
 * entries), the fastest speed and the extent along gdir of those particles
 * (the poured ones at the pour height, at the largest pour speed). */
int sd_grid_has_particles(const sd_world *w);
void sd_grid_dt_inputs(const sd_world *w, sd_vec3 gdir, double *rmin, double *mmin, double *vmax, double *zlo,
                       double *zhi, double *rsmall);

/* grid.c, internal to the module */
sd_status sd_grid_setup(sd_world *w, sd_error *err);
/* Moves the world's spheres into the solver's state (world arrays freed). */
sd_status sd_grid_absorb(sd_world *w, sd_error *err);
/* Appends one particle (capacity reserved by the caller). */
sd_status sd_grid_append(sd_grid_state *g, sd_vec3 x, sd_vec3 v, sd_vec3 wv, uint64_t id, const sd_grid_kind *kind);
sd_status sd_grid_reserve(sd_grid_state *g, size_t n);
/* Puts every particle in its cell (after set-up or removals). */
sd_status sd_grid_place_all(sd_world *w, sd_error *err);
/* Moves particles to their new cells after a drift; removes those that left. */
sd_status sd_grid_rebin(sd_world *w, sd_error *err);
/* The block layout of the force pass (blocks.h). */
sd_grid_blocks sd_grid_blocks_of(const sd_grid_state *g);
/* Cell index of x, or SD_GRID_OUTSIDE. */
uint32_t sd_grid_cell_of(const sd_grid_state *g, sd_vec3 x);
/* Removes the particles flagged where[k] == SD_GRID_OUTSIDE, keeping order. */
void sd_grid_remove_outside(sd_world *w);
/* Below this many particles the grid solver's loops run serially: a step
 * of a few thousand spheres takes well under a millisecond, less than the
 * seven fork-join points of a threaded step cost on a busy machine. */
#define SD_GRID_PARALLEL_MIN 4096
/* Decides w->parallel for the solver's particle count. */
void sd_grid_set_parallel(sd_world *w);
/* Tests: run the loops threaded from n particles on (0: the default). */
sd_status sd_grid_set_parallel_min(sd_world *w, size_t n);
/* Recomputes the row flags from the particles' cells. */
void sd_grid_mark_rows(sd_grid_state *g, size_t n);

/* After a step failed part way (eq. 11, NaN, out of memory): puts every
 * particle whose centre lies in the inner grid back in a cell from its
 * current position (the others keep none and are left out of the stencil
 * statistics), so the grid invariants hold again for the statistics, and
 * records the step in info.failed_step: the forces are those of the step
 * before, so the solver takes no further step (sd_grid_step refuses). */
void sd_grid_fail(sd_world *w, long step);

/* grid_snapshot.c: the solver's checkpoint state (sd_solver_ops.state and
 * .resumed, world/snapshot.h). */
struct sd_state_table;
sd_status sd_grid_state_list(sd_world *w, struct sd_state_table *t, sd_error *err);
sd_status sd_grid_state_resumed(sd_world *w, sd_error *err);

/* outlet.c: opens a scheduled outlet when its time has come (each step);
 * sd_grid_outlet_due: 1 when this step opens it. */
void sd_grid_outlet_step(sd_world *w);
int sd_grid_outlet_due(const sd_world *w);

/* pour.c: 1 when this step pours a sheet (sd_grid_pour_step does then) */
int sd_grid_pour_due(const sd_world *w);
sd_status sd_grid_pour_step(sd_world *w, sd_error *err);

/* grid_step.c: contact statistics for sd_world_stats (read-only pass). */
void sd_grid_contact_stats(const sd_world *w, long *contacts, long *wall_contacts, double *energy,
                           double *max_overlap_ratio);

#endif
