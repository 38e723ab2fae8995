/* pairs.h — candidate pair lists, the unit of parallel work (DESIGN.md
 * rule 3), their history keys, and the field lists that declare them once.
 *
 * Invariants: pairs are built from per-particle counts and a prefix sum, so
 * their order depends only on the particle order, never on thread count.
 * The pairs of a list sit in kind segments (contact/kinds.h): kind k owns
 * pairs kind_start[k] .. kind_start[k+1]-1, the kind decided once at the
 * rebuild; within a segment pairs keep the order of the search. Each pair
 * stores its own force and torques; owned particles sum their pairs in the
 * fixed order of the gather lists (rule 4: no atomics, the same bits with
 * any number of threads). History (the tangential spring, the overlap
 * hint) is keyed by stable ids and sub-indices and carried across rebuilds
 * by search (rule 5).
 *
 * Every per-pair array is declared once in SD_PAIR_FIELDS /
 * SD_WALL_PAIR_FIELDS; the struct members, their growth, their release and
 * their reset at a rebuild come from these lists (broad/pairs.c). Adding a
 * per-pair field is one row.
 */
#ifndef SD_BROAD_PAIRS_H
#define SD_BROAD_PAIRS_H

#include <shapedem/shapedem.h>

#include "contact/kinds.h"
#include "core/vec.h"

/* The history key of a particle pair: the two stable ids (lower first) and
 * a sub-index on each side (sub_lo on the lower id's side: its composite
 * element in an ELEMENTS pair, 0 otherwise). 64-bit
 * ids, so ids from many ranks or long runs with insertion never alias. */
typedef struct sd_pair_key {
    uint64_t id_lo, id_hi;
    uint32_t sub_lo, sub_hi;
} sd_pair_key;

/* The history key of a particle-wall pair: the particle's stable id, the
 * wall index, the wall feature (box face 0..5, 0 for a plane, a mesh plane
 * group later) and the particle's composite element (0 for other
 * particles). */
typedef struct sd_wall_pair_key {
    uint64_t id;
    uint32_t wall, sub;
    uint32_t elem;
} sd_wall_pair_key;

/* Roles of a field at a rebuild: BUILT fields are written by the builder
 * (indices, key, flip), HISTORY fields are carried by key, ZERO fields
 * start at zero. */
enum { SD_PF_BUILT, SD_PF_HISTORY, SD_PF_ZERO };

/* X(type, name, slots per pair, role, meaning) */
#define SD_PAIR_FIELDS(X)                                                                                  \
    X(uint32_t, i, 1, SD_PF_BUILT, "storage index of the first body, always owned (i < j)")                \
    X(uint32_t, j, 1, SD_PF_BUILT, "storage index of the second body, owned or a ghost")                   \
    X(sd_pair_key, key, 1, SD_PF_BUILT, "history key: stable ids (a ghost's are its owner's)")             \
    X(uint8_t, flip, 1, SD_PF_BUILT, "1 when i has the higher stable id (negate ds)")                      \
    X(sd_vec3, ds, 1, SD_PF_HISTORY,                                                                      \
      "m, tangential spring (N, the spring force, for the volume laws), global frame, as seen from the "   \
      "body with the lower stable id: storage order may flip at a rebuild, the key does not")              \
    X(sd_vec3, x0, 1, SD_PF_HISTORY,                                                                      \
      "m, polyhedron pairs under a volume law: interior point of the last overlap (geom/overlap.h)")       \
    X(uint8_t, x0_ok, 1, SD_PF_HISTORY, "1 when x0 holds a point of the last overlap")                     \
    X(sd_vec3, f, 1, SD_PF_ZERO, "N, force on i")                                                          \
    X(sd_vec3, t, 2, SD_PF_ZERO, "N m, torques: t[2e] on i, t[2e + 1] on j")                               \
    X(sd_real, delta, 1, SD_PF_ZERO, "m, overlap at the last evaluation (<= 0 apart)")                     \
    X(sd_real, energy, 1, SD_PF_ZERO, "J, elastic energy at the last evaluation")                          \
    X(sd_vec3, warm, 1, SD_PF_ZERO, "convex pairs: GJK warm-start direction")                              \
    X(int32_t, iters, 1, SD_PF_ZERO, "convex pairs: GJK + EPA iterations at the last evaluation")          \
    X(int32_t, supports, 1, SD_PF_ZERO, "convex pairs: support calls at the last evaluation")

#define SD_WALL_PAIR_FIELDS(X)                                                                             \
    X(uint32_t, i, 1, SD_PF_BUILT, "storage index of the particle (owned: ghosts get no wall pairs)")      \
    X(uint16_t, wall, 1, SD_PF_BUILT, "wall index")                                                        \
    X(uint32_t, sub, 1, SD_PF_BUILT, "wall feature (dynamics/walls.h): box face 0..5, 0 for a plane, a mesh's plane group") \
    X(uint32_t, tstart, 1, SD_PF_BUILT, "mesh pairs: first of the group's near triangles in the list's tri array") \
    X(uint32_t, tcount, 1, SD_PF_BUILT, "mesh pairs: how many (0 for other walls)")                         \
    X(uint32_t, elem, 1, SD_PF_BUILT, "composite element of the particle (ELEMENTS pairs), 0 otherwise")    \
    X(sd_wall_pair_key, key, 1, SD_PF_BUILT, "history key")                                                \
    X(sd_vec3, ds, 1, SD_PF_HISTORY, "m, tangential spring, global frame")                                 \
    X(sd_vec3, f, 1, SD_PF_ZERO, "N, force on the particle")                                               \
    X(sd_vec3, t, 1, SD_PF_ZERO, "N m, torque on the particle")                                            \
    X(sd_vec3, c, 1, SD_PF_BUILT, "m, contact point (for the wall's torque); the centre until touching")   \
    X(sd_real, delta, 1, SD_PF_ZERO, "m, overlap at the last evaluation")                                  \
    X(sd_real, energy, 1, SD_PF_ZERO, "J, elastic energy at the last evaluation")

#define SD_X_PAIR_MEMBER(type, name, per, role, doc) type *name;

typedef struct sd_pair_list {
    size_t n, cap;
    size_t kind_start[SD_PAIR_KIND_COUNT + 1]; /* kind k: pairs kind_start[k] .. kind_start[k+1]-1 */
    SD_PAIR_FIELDS(SD_X_PAIR_MEMBER)
    /* gather lists: owned particle k owns entries gstart[k] .. gstart[k+1]-1
     * of gidx; an entry is 2 * pair + (0 if k is the pair's i, 1 if j or
     * the owner of the ghost j) */
    uint32_t *gstart, *gidx;
    size_t gstart_cap, gidx_cap;
} sd_pair_list;

typedef struct sd_wall_pair_list {
    size_t n, cap;
    size_t kind_start[SD_WALL_PAIR_KIND_COUNT + 1];
    SD_WALL_PAIR_FIELDS(SD_X_PAIR_MEMBER)
    /* gather lists: owned particle k owns entries gstart[k] .. gstart[k+1]-1
     * of gidx, the indices of its wall pairs in wall and feature order (the
     * order of the search, whatever their kind segments): the sum per
     * particle, and per wall over the particles in order, is then the same
     * whatever the kinds */
    uint32_t *gstart, *gidx;
    size_t gstart_cap;
    /* mesh pairs: the near triangles of each pair's plane group (tstart, tcount) */
    uint32_t *tri;
    size_t tri_n, tri_cap;
} sd_wall_pair_list;

#undef SD_X_PAIR_MEMBER

/* broad/pairs.c: growth to at least cap pairs (gather entries included),
 * release, and the reset of the ZERO fields of pair e. */
sd_status sd_pairs_reserve(sd_pair_list *l, size_t cap);
sd_status sd_pairs_reserve_walls(sd_wall_pair_list *l, size_t cap);
void sd_pairs_free(sd_pair_list *l, sd_wall_pair_list *wl);

#endif
