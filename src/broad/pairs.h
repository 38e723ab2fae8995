/* pairs.h — candidate pair lists, the unit of parallel work (DESIGN.md
 * rule 3), and the cell grid that builds them.
 *
 * Invariants: pairs are built from per-particle counts and a prefix sum, so
 * their order depends only on the particle order, never on thread count.
 * Each pair stores its own force and torques; particles sum their pairs in
 * the fixed order of the gather lists (rule 4: no atomics, same bits with any
 * number of threads). History (the tangential spring) is keyed by stable ids
 * and carried across rebuilds by binary search (rule 5).
 */
#ifndef SD_BROAD_PAIRS_H
#define SD_BROAD_PAIRS_H

#include "core/vec.h"

typedef struct sd_pair_list {
    size_t n, cap;
    size_t n_sphere;       /* pairs [0, n_sphere) are sphere-sphere, the rest
                              involve a shape template (convex narrow phase):
                              each loop then runs one homogeneous kind */
    uint32_t *i, *j;       /* storage indices, i < j */
    uint64_t *key;         /* (min id << 32) | max id */
    sd_vec3 *ds;           /* m, tangential spring (history; N, the spring force, for
                              the volume laws: contact/law_volume.h), global frame, as
                              seen from the body with the lower stable id:
                              storage order (which body is i) may flip at a
                              rebuild, the key does not */
    uint8_t *flip;         /* 1 when i has the higher stable id (negate ds) */
    sd_vec3 *f;            /* N, force on i */
    sd_vec3 *t;            /* N m, torques: t[2e] on i, t[2e + 1] on j, so a
                              gather entry 2e + side indexes its torque */
    sd_real *delta;        /* m, overlap at the last evaluation (<= 0 apart) */
    sd_real *energy;       /* J, elastic energy at the last evaluation */
    sd_vec3 *warm;         /* convex pairs: GJK warm-start direction */
    int32_t *iters;        /* convex pairs: GJK + EPA iterations at the last evaluation */
    int32_t *supports;     /* convex pairs: support calls at the last evaluation */
    sd_vec3 *x0;           /* m, world: polyhedron pairs under a volume law, the
                              interior point of the overlap at the last
                              evaluation (the next one's hint, geom/overlap.h);
                              history, carried across rebuilds like ds */
    uint8_t *x0_ok;        /* 1 when x0 holds a point of the last overlap */
    /* gather lists: particle k owns entries gstart[k] .. gstart[k+1]-1 of
     * gidx; an entry is 2 * pair + (0 if k is the pair's i, 1 if j) */
    uint32_t *gstart, *gidx;
    size_t gstart_cap, gidx_cap;
} sd_pair_list;

typedef struct sd_wall_pair_list {
    size_t n, cap;
    uint32_t *i;           /* storage index of the particle */
    uint16_t *wall, *sub;  /* wall index; face of a box (0..5), 0 for planes */
    uint64_t *key;         /* (id << 20) | (wall << 4) | sub */
    sd_vec3 *ds, *f, *t;   /* spring, force and torque on the particle */
    sd_vec3 *c;            /* m, contact point (for the wall's torque) */
    sd_real *delta, *energy;
    uint32_t *start;       /* particle k owns pairs start[k] .. start[k+1]-1 */
    size_t start_cap;
} sd_wall_pair_list;

typedef struct sd_grid {
    sd_vec3 lo;            /* m, lower corner */
    sd_real h;             /* m, cell edge */
    int nx, ny, nz;
    size_t ncell, cell_cap;
    uint32_t *cell_start;  /* ncell + 1 entries */
    uint32_t *cell;        /* per particle, its cell */
    uint32_t *perm;        /* per particle, scratch for the counting sort */
    uint32_t *count;       /* per particle, scratch counts */
    void *scratch;         /* permutation scratch, 32 bytes per particle */
    size_t pcap;
} sd_grid;

/* History entry for the carry-over at rebuilds: the carried vector is a
 * tangential spring, or (in a separate list, only in worlds with a volume
 * law) a polyhedron pair's overlap hint x0. One 32-byte entry type for both
 * keeps the sphere path's sort as light as it was before the hints. */
typedef struct sd_history {
    uint64_t key;
    sd_vec3 v;
} sd_history;

#endif
