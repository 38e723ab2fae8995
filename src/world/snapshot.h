/* snapshot.h — the world's complete state as a list of named arrays, for
 * checkpoints that restart bit for bit (issue 17; io/checkpoint.c writes
 * and reads them as HDF5, docs/checkpoints.md).
 *
 * Two types:
 *  - sd_state_ref: a named array inside a live world (base pointer, rows,
 *    values per row, stride between rows), listed by sd_world_state_list
 *    (snapshot.c); saving gathers the rows, restoring scatters them back;
 *  - sd_snapshot: owned copies of those arrays plus a header (format
 *    version, the scene's hash, step, time, solver, dimension), plain data
 *    that the checkpoint reader fills from a file or a buffer without any
 *    world (context-free: the fuzz target reads buffers into it).
 *
 * Invariant: what the world lists is exactly what a restore must put back
 * for the next sd_world_step to give the bits of the run that never
 * stopped: the particle arrays in storage order (ghosts included), the
 * pair lists with every field and their gather lists (the force sums keep
 * their order), the walls' motion state, the clock, the solver's own
 * state. Nothing derived from the scene alone (materials, templates) is
 * listed for a restart; the scene's hash says the world was built from the
 * same physics. A snapshot also holds scene/ items that name the templates
 * and materials the particles' columns index (sd_world_snapshot adds them;
 * a restore skips them), so a new scene can take the particles over by
 * name (io/scene_from.c). Names sort the items (the checksum's order).
 *
 * Where state is declared (adding state is one line in one of these):
 *  - a particle field: SD_PARTICLE_FIELDS (world/world.h), saved as
 *    "particles/<name>" automatically;
 *  - a pair field: SD_PAIR_FIELDS / SD_WALL_PAIR_FIELDS (broad/pairs.h),
 *    saved as "pairs/<name>" and "wall_pairs/<name>" automatically;
 *  - a world-level value: SD_WORLD_STATE in snapshot.c (the insertions and
 *    outlets, world/process.h, are one record beside it);
 *  - a per-wall value: SD_WALL_STATE in snapshot.c; a per-mesh value
 *    (world/mesh.h's store): SD_MESH_STATE there;
 *  - a solver's own state: its sd_solver_ops.state (world/solver.h; the
 *    grid's in grid/grid_solver.c).
 */
#ifndef SD_WORLD_SNAPSHOT_H
#define SD_WORLD_SNAPSHOT_H

#include <shapedem/shapedem.h>

#include <stddef.h>
#include <stdint.h>

/* The checkpoint format's version: a change of what is listed (a field
 * added, renamed or resized) makes old files unreadable by name or count
 * anyway; the version says so in one line. Version 3: the scene hash
 * covers mesh walls, drums, insertions and outlets, and scene/parts holds
 * its parts (a version 2 file's hash means something else). */
#define SD_SNAPSHOT_VERSION 3
/* The oldest version read: its datasets are version 3's but scene/parts,
 * so `shapedem info` and a new scene's csv generator still read it; only
 * a restart refuses it (its hash means another thing). */
#define SD_SNAPSHOT_VERSION_OLDEST 2

/* Bytes of a name row of the scene/ items (template and material names,
 * zero-padded): what the world keeps, 63 characters and the NUL. */
#define SD_SNAP_NAME 64

typedef enum sd_state_type {
    SD_ST_F64,
    SD_ST_I64,
    SD_ST_U64,
    SD_ST_I32,
    SD_ST_U32,
    SD_ST_U16,
    SD_ST_U8,
    SD_ST_BYTES, /* an opaque record of this build (comps bytes per row) */
    SD_ST_TYPE_COUNT
} sd_state_type;

/* Bytes of one value of a type (1 for BYTES). */
size_t sd_state_type_size(sd_state_type t);
const char *sd_state_type_name(sd_state_type t);

typedef struct sd_state_ref {
    char name[64];      /* "group/name" */
    sd_state_type type;
    size_t comps;       /* values per row (bytes per row for BYTES) */
    size_t count;       /* rows */
    void *base;         /* row 0 (may be NULL when count is 0) */
    size_t stride;      /* bytes from one row to the next */
} sd_state_ref;

typedef struct sd_snapshot sd_snapshot;

typedef struct sd_state_table {
    size_t n, cap;
    sd_state_ref *refs;
    int oom;                    /* a ref could not be added */
    const sd_snapshot *saved;   /* restoring: the saved state whose sizes the arrays take; NULL saving */
} sd_state_table;

/* Appends a ref; 0, and t->oom set, when out of memory. */
int sd_state_add(sd_state_table *t, const char *name, sd_state_type type, size_t comps, size_t count,
                 void *base, size_t stride);
void sd_state_table_free(sd_state_table *t);

/* ---- snapshots: owned state ------------------------------------------------ */

typedef struct sd_snap_item {
    char name[64];
    sd_state_type type;
    size_t comps, count;
    void *data;         /* count * comps * sd_state_type_size(type) bytes, sd_malloc'd */
} sd_snap_item;

struct sd_snapshot {
    uint32_t version;           /* SD_SNAPSHOT_VERSION of the writer */
    uint64_t scene_hash;        /* sd_world_scene_hash of the world saved */
    uint64_t checksum;          /* sd_snapshot_checksum of the items */
    long step;
    double time;                /* s */
    int dimension;              /* 3 or 2 */
    char solver[16];            /* "cells" or "grid" */
    char writer[32];            /* shapedem version string of the writer */
    size_t n, cap;
    sd_snap_item *items;        /* sorted by name */
};

void sd_snapshot_init(sd_snapshot *s);
void sd_snapshot_free(sd_snapshot *s);
/* Appends an item holding a copy of count rows of comps values (data may
 * be NULL: zeroed); returns it or NULL out of memory. Call sd_snapshot_sort
 * after the last. */
sd_snap_item *sd_snapshot_add(sd_snapshot *s, const char *name, sd_state_type type, size_t comps, size_t count,
                              const void *data);
void sd_snapshot_sort(sd_snapshot *s);
const sd_snap_item *sd_snapshot_find(const sd_snapshot *s, const char *name);
/* A one-value integer item (U64, I64, I32, U32) as uint64; 0 when absent or
 * not such an item. */
int sd_snapshot_get_u64(const sd_snapshot *s, const char *name, uint64_t *out);
/* FNV-1a 64 over every item in order: name, type, comps, count, bytes. */
uint64_t sd_snapshot_checksum(const sd_snapshot *s);
/* 64-bit FNV-1a of bytes, chained from h (start with SD_FNV_BASIS). */
#define SD_FNV_BASIS 0xcbf29ce484222325ull
uint64_t sd_fnv1a(uint64_t h, const void *data, size_t n);

/* ---- the world --------------------------------------------------------------- */

/* Lists every piece of the world's state (header comment) into t. Saving
 * (t->saved NULL): refs into the world as it is. Restoring (t->saved set):
 * first gives the arrays the saved sizes, then lists them. */
sd_status sd_world_state_list(sd_world *w, sd_state_table *t, sd_error *err);

/* Copies the world's whole state into s (header filled, items sorted). */
sd_status sd_world_snapshot(const sd_world *w, sd_snapshot *s, sd_error *err);

/* Puts a snapshot's state into w, a world freshly built from the same
 * scene (never stepped): refuses a snapshot of another version, scene
 * (hash), solver or dimension, one that lacks an item the world has or has
 * one the world does not know, or whose sizes do not match, naming it.
 * Afterwards w is prepared and its next step is the saved run's next step.
 * The checksum is the reader's business (io/checkpoint.c). */
sd_status sd_world_restore(sd_world *w, const sd_snapshot *s, sd_error *err);

/* The scene's physics in parts (world/scene_hash.c), each hashed alone, so
 * a refused restart or MPI rank can say which part differs: X(NAME, what
 * it covers, as a message names it). */
#define SD_SCENE_PARTS(X)                                                                                 \
    X(SETTINGS, "the simulation settings (dimension, dt, gravity, seed, contact law, skin, solver, "       \
                "local damping, periodic box, multi_contact)")                                              \
    X(MATERIALS, "the materials or interactions")                                                          \
    X(SHAPES, "the shape templates")                                                                       \
    X(WALLS, "the walls (name, kind, material, geometry, motion, drum radius, length, centre, rpm)")        \
    X(MESHES, "the mesh walls (file, scale, position, rotation, side, motion, rpm, axis, motion table)")     \
    X(INSERTIONS, "the insertions (region, mix, size laws, count, mass, rate, start, velocity, attempts)")  \
    X(OUTLETS, "the outlets (region, open_at, check_every)")

enum {
#define SD_X_PART(NAME, doc) SD_SCENE_##NAME,
    SD_SCENE_PARTS(SD_X_PART)
#undef SD_X_PART
    SD_SCENE_PART_COUNT
};

/* The hash of each part of what the scene defines for the physics and a
 * restart (or every MPI rank) must share; the output, analysis, start
 * particles, thread count, backend and overlap guard are left out
 * (scene_hash.c says why). */
void sd_world_scene_parts(const sd_world *w, uint64_t part[SD_SCENE_PART_COUNT]);
/* The FNV-1a 64 hash of the parts: the checkpoint's scene_hash. */
uint64_t sd_world_scene_hash(const sd_world *w);
/* The hash of the particles as built (every field of the owned ones, in
 * storage order): with the parts, what every MPI rank compares with rank
 * 0's before it splits the world (cli/mpi_run.c). */
uint64_t sd_world_particles_hash(const sd_world *w);
/* What part k covers (the SD_SCENE_PARTS text). */
const char *sd_scene_part_doc(size_t k);
/* The number of parts that differ between a and b; their texts, joined by
 * ", ", in buf (truncated to size). */
size_t sd_scene_parts_differ(const uint64_t a[SD_SCENE_PART_COUNT], const uint64_t b[SD_SCENE_PART_COUNT],
                             char *buf, size_t size);

#endif
