/* grid.h — the dense grid-stencil solver for (nearly) monodisperse spheres
 * (seed 001 §3.1–3.3, §4.1–4.2), chosen with sd_world_def.solver =
 * SD_SOLVER_GRID (scene key simulation.solver: grid).
 *
 * The domain (the union of the world's box walls) is a uniform grid of cubic
 * cells of edge R_min plus a halo of reach + 1 cells; each cell holds at most
 * one particle; contacts come from a fixed stencil around each particle's
 * cell (stencil.h). Particles keep the world's SoA state in storage order =
 * stable-id order (this solver never re-sorts them).
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
 *    the wall face, never by storage index.
 * See docs/grid-solver.md for the choices and their reasons.
 */
#ifndef SD_GRID_GRID_H
#define SD_GRID_GRID_H

#include <shapedem/shapedem.h>

#include "core/rng.h"
#include "grid/stencil.h"

#define SD_GRID_OVER 0xffffffffu    /* home[k]: in the overflow list */
#define SD_GRID_OUTSIDE 0xfffffffeu /* where[k]: left the inner grid */

/* Layer-by-layer pouring (seed 001 §4.1). */
typedef struct sd_grid_pour_def {
    double radius;            /* m */
    int material;             /* world material index */
    double height;            /* m, z of the centres of each new sheet */
    double layers_per_second; /* 1/s, feed rate (seed 001 Table 2: 4 or 8) */
    size_t count;             /* particles to pour in all */
    double vz_range;          /* m/s, vertical velocity uniform in [-vz, vz] (0.5) */
    double vh_range;          /* m/s, horizontal velocities uniform in [-vh, vh] (0.1) */
    double start_time;        /* s, time of the first sheet */
    int cookie;
} sd_grid_pour_def;

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
    size_t removed_outlet;    /* of which through the outlet hole */
    double removed_mass;      /* kg */
    size_t poured, pour_layers, pour_skipped;
    double dt_contact_limit;  /* s, pi/5 sqrt(m/k) (seed 001 eq. 11) */
    double max_speed;         /* m/s, at the last step */
    size_t bytes;             /* bytes held by the grid solver (cells, slots, lists) */
} sd_grid_info;

struct sd_grid_state {
    /* geometry */
    sd_vec3 lo;               /* m, corner of cell (0, 0, 0) */
    sd_real h;                /* m, cell edge = smallest radius */
    sd_real rmax;             /* m, largest radius (present and poured) */
    int reach;
    long nx, ny, nz;
    size_t ncell;
    sd_vec3 dom_lo, dom_hi;   /* m, the box walls' union */
    int32_t *cell;
    /* per particle */
    size_t pcap;
    uint32_t *where, *home;
    uint32_t *tag;            /* SD_GRID_SLOTS per particle */
    sd_vec3 *ds;
    /* conflicts */
    uint32_t *over;
    size_t nover, over_cap;
    /* walls as the kernel sees them */
    sd_grid_wall *walls;
    int nwalls;
    /* outlet: a hole in the zmin face of the domain box */
    int outlet;
    sd_real hx0, hx1, hy0, hy1;
    sd_grid_pour pour;
    sd_grid_info info;
};

typedef struct sd_grid_state sd_grid_state;

/* The world's grid state, created on first use (NULL when out of memory). */
sd_grid_state *sd_grid_state_get(sd_world *w);
void sd_grid_state_free(sd_grid_state *g);

/* Pours particles layer by layer from the first step on (or start_time). */
sd_status sd_grid_set_pour(sd_world *w, const sd_grid_pour_def *def, sd_error *err);
/* Opens a rectangular hole [x0, x1] x [y0, y1] in the floor (zmin face) of
 * the domain box: particles fall through and are removed and counted once
 * their centre is one radius below the floor. May be called between steps
 * of a run (the orifice opens; nothing else changes). */
sd_status sd_grid_set_outlet(sd_world *w, double x0, double x1, double y0, double y1, sd_error *err);
/* Counters and sizes; info->active is 0 for a world on another solver. */
void sd_grid_get_info(const sd_world *w, sd_grid_info *info);

/* The solver's entry points, called by sd_world_prepare / sd_world_step. */
sd_status sd_grid_prepare(sd_world *w, sd_error *err);
sd_status sd_grid_step(sd_world *w, long nsteps, sd_error *err);

/* grid.c, internal to the module */
sd_status sd_grid_setup(sd_world *w, sd_error *err);
sd_status sd_grid_reserve(sd_grid_state *g, size_t n);
/* Puts every particle in its cell (after set-up or removals). */
sd_status sd_grid_place_all(sd_world *w, sd_error *err);
/* Moves particles to their new cells after a drift; removes those that left. */
sd_status sd_grid_rebin(sd_world *w, sd_error *err);
/* Cell index of x, or SD_GRID_OUTSIDE. */
uint32_t sd_grid_cell_of(const sd_grid_state *g, sd_vec3 x);
/* Removes the particles flagged where[k] == SD_GRID_OUTSIDE, keeping order. */
void sd_grid_remove_outside(sd_world *w);

/* pour.c */
sd_status sd_grid_pour_step(sd_world *w, sd_error *err);

/* grid_step.c: contact statistics for sd_world_stats (read-only pass). */
void sd_grid_contact_stats(const sd_world *w, long *contacts, long *wall_contacts, double *energy,
                           double *max_overlap_ratio);

#endif
