/* kinds.h — the interaction kinds: every candidate pair belongs to exactly
 * one kind, decided once per pair when the pair list is rebuilt, and each
 * kind is evaluated by one item function (backend/items.h) in one
 * homogeneous loop on the CPU, one kernel on a GPU (STYLE.md convention 10,
 * exaDEM's classification of interactions).
 *
 * Invariant: the pair lists hold their pairs in kind segments, in the order
 * of these lists; kind k owns pairs kind_start[k] .. kind_start[k+1]-1 of
 * its list (broad/pairs.h). Adding a kind is one row here plus its item
 * function; room is left for mesh facet groups. The element kinds (seed
 * 004 §2.5-2.6) are the only ones whose pairs are not whole particles: an
 * ELEMENTS pair is one element of each side (a non-composite side is its
 * own element 0), and the element pairs of one composite pair (of one
 * particle and one wall feature) sit next to each other in their segment,
 * so the multi-contact combination is a segmented pass over them.
 *
 * X(NAME, name, meaning)
 */
#ifndef SD_CONTACT_KINDS_H
#define SD_CONTACT_KINDS_H

#include "core/base.h"

/* Particle-particle kinds. */
#define SD_PAIR_KINDS(X)                                                                                  \
    X(SPHERES, spheres, "two plain spheres (3D) or discs (2D): the exact sphere contact")                 \
    X(CONVEX, convex, "3D, a shape template on one side at least: GJK/EPA on cores and margins")          \
    X(POLY_VOLUME, poly_volume, "3D, sharp polyhedra under a volume law: the exact overlap volume")       \
    X(CONVEX2D, convex2d, "planar mode, a 2D shape template on one side at least: 2D GJK/EPA")            \
    X(ELEMENTS, elements,                                                                               \
      "3D, a composite on one side at least: one element pair (sub-indices), combined per composite pair")

/* Particle-wall kinds (the wall feature, plane or box face, is the pair's sub-index). */
#define SD_WALL_PAIR_KINDS(X)                                                                            \
    X(SPHERE, sphere, "a plain sphere or disc against a wall feature")                                   \
    X(CONVEX, convex, "a 3D shape template against a wall feature's plane (support point)")              \
    X(POLY_VOLUME, poly_volume, "a sharp polyhedron under a volume law against a wall feature's plane")  \
    X(CONVEX2D, convex2d, "a 2D shape template against a wall line")                                    \
    X(ELEMENTS, elements, "one element of a composite against a wall feature, combined per feature")     \
    X(MESH_SPHERE, mesh_sphere, "a plain sphere against a mesh plane group: the closest active feature") \
    X(MESH_CONVEX, mesh_convex, "a 3D shape against a mesh plane group: plane contact, clipped area")    \
    X(MESH_POLY_VOLUME, mesh_poly_volume,                                                               \
      "a sharp polyhedron under a volume law against a mesh plane group: half-space overlap, clipped area") \
    X(MESH_CONVEX2D, mesh_convex2d, "a 2D shape against a mesh plane group cut by the plane z = 0")

typedef enum sd_pair_kind {
#define SD_X_KIND(NAME, name, doc) SD_PAIR_##NAME,
    SD_PAIR_KINDS(SD_X_KIND)
#undef SD_X_KIND
    SD_PAIR_KIND_COUNT
} sd_pair_kind;

typedef enum sd_wall_pair_kind {
#define SD_X_KIND(NAME, name, doc) SD_WALL_PAIR_##NAME,
    SD_WALL_PAIR_KINDS(SD_X_KIND)
#undef SD_X_KIND
    SD_WALL_PAIR_KIND_COUNT
} sd_wall_pair_kind;

#endif
