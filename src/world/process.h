/* process.h — the state of the cells solver's insertions and outlets
 * (shapedem/process.h; issue 16), kept in the world as one plain struct of
 * fixed arrays (no pointers), so a checkpoint saves and restores it with
 * one copy (issue 17): the streams, counters and next times are all here.
 */
#ifndef SD_WORLD_PROCESS_H
#define SD_WORLD_PROCESS_H

#include <shapedem/process.h>

#include "core/rng.h"
#include "world/solver.h"

#define SD_INSERTIONS_MAX 16
#define SD_OUTLETS_MAX 16

typedef struct sd_insertion {
    sd_insert_def def;            /* def.name is NULL: the name is below */
    char name[64];
    sd_rng rng;                   /* its own stream of the world's seed */
    double entry_cum[SD_INSERT_MIX_MAX];  /* cumulative probability of each entry, by number */
    double class_cum[SD_INSERT_MIX_MAX][SD_SIZE_CLASSES_MAX]; /* table classes, by number */
    double bound[SD_INSERT_MIX_MAX];      /* m, bounding radius (shaped entries) */
    double body_mass[SD_INSERT_MIX_MAX];  /* kg, mass of a shaped entry's body */
    /* a template entry with a size law: its scaled copies, one per class,
     * template indices first + k stride (a composite's element copies sit
     * between its own); a continuous law's classes are equally likely, a
     * sieve table's are `per` equally likely ones in each sieve class
     * (class_cum). Kept small: this struct is a checkpoint dataset. */
    int scaled_count[SD_INSERT_MIX_MAX];  /* 0: the template as it is */
    int scaled_first[SD_INSERT_MIX_MAX], scaled_stride[SD_INSERT_MIX_MAX], scaled_per[SD_INSERT_MIX_MAX];
    int mesh;                     /* a mesh region: its slot in w->region_meshes, else -1 */
    size_t asked, inserted;       /* due so far; in */
    double mass;                  /* kg in */
    long next_step;               /* the next step at which it runs */
    int done;
    char why[256];
} sd_insertion;

typedef struct sd_outlet_state {
    sd_region_outlet_def def;     /* def.name is NULL */
    char name[64];
    size_t removed;
    double mass;                  /* kg */
    long next_step;               /* the next check */
} sd_outlet_state;

typedef struct sd_process {
    int started;                  /* the first step has run (initial counted) */
    size_t initial;
    size_t inserted, removed;
    double inserted_mass, removed_mass; /* kg */
    size_t insertion_count, outlet_count;
    sd_insertion insertions[SD_INSERTIONS_MAX];
    sd_outlet_state outlets[SD_OUTLETS_MAX];
} sd_process;

/* The triangles of the insertions' mesh regions, one slot per insertion,
 * outside sd_process (that struct is a checkpoint dataset of plain bytes:
 * a restored world keeps the slots its scene built). */
typedef struct sd_region_mesh {
    size_t count;
    double (*tri)[9];             /* m, the corners of each triangle */
    double lo[3], hi[3];          /* m, bounding box */
} sd_region_mesh;

typedef struct sd_region_meshes {
    sd_region_mesh slot[SD_INSERTIONS_MAX];
} sd_region_meshes;

/* E[r^d] of a size law (its truncation and a table's classes included;
 * by number). */
double sd_size_moment(const sd_size_def *s, int d);

/* The union of the insertion regions' bounding boxes into lo, hi (m: where
 * inserted particles' centres go; lo > hi on every axis when there is
 * none), for an MPI split made before the particles are in (mpi/plan.c).
 * Returns the number of insertions. */
size_t sd_world_insertion_bounds(const sd_world *w, double lo[3], double hi[3]);

/* The cells solver's step with the process events between steps (the
 * solver table's step entry, world.c). */
sd_status sd_cells_process_step(sd_world *w, long nsteps, sd_error *err);
/* The solver items (summary.txt, stats.csv) of the process. */
size_t sd_cells_process_info(const sd_world *w, sd_solver_item *items, size_t max);
void sd_world_process_free(sd_world *w);

#endif
