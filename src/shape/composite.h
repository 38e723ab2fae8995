/* composite.h — composite templates (seed 004): non-convex particles glued
 * from convex elements, and their mass properties (host code).
 *
 * A composite is a list of convex templates (parts), each placed in the
 * composite's given frame. sd_composite_make turns it into an sd_shape of
 * kind SD_SHAPE_COMPOSITE plus its elements (sd_element, shape.h) in the
 * composite's principal frame: centre of mass at the origin, principal axes
 * along x, y, z (given_com / given_q keep the given frame, as for
 * polyhedra). Mass properties:
 *   no two elements overlap (GJK/EPA on every pair whose bounding spheres
 *     meet; touching counts as apart): exact sums of the elements' own
 *     volumes and second moments, moved by the parallel-axis theorem;
 *   some overlap: the exact sums minus the doubly counted volume, which is
 *     integrated on the structured voxel lattice of seed 004 §2.3 (eqs.
 *     7-8: cell centres X over a box around the body, each weighted by the
 *     number of elements containing it minus one). Only the overlap
 *     lenses are voxelised, so the error is that of the lattice on those
 *     lenses, far below the seed's lattice over the whole body at the same
 *     resolution. The estimated error is the change of the lens volume from
 *     n/2 to n points per direction, relative to the composite volume.
 * sd_composite_lattice is the seed's plain lattice over the whole union
 * (tests show it converging; it is also what the estimate is checked by).
 *
 * Determinism: the lattice sums are integer sums of cell indices (exact in
 * int64 for any order), turned into moments once, so any thread count
 * gives the same bits.
 */
#ifndef SD_SHAPE_COMPOSITE_H
#define SD_SHAPE_COMPOSITE_H

#include <stddef.h>

#include <shapedem/shapedem.h>

#include "shape/shape.h"
#include "shape/shape_make.h"

/* Most elements per composite (the 54-sphere cylinder of seed 004 Fig. 10
 * fits many times over; a fixed bound keeps element loops on a GPU finite). */
#define SD_COMPOSITE_MAX_ELEMENTS 1024
/* Default points per direction: two crossed cylinders of equal radius come
 * out within 3e-4 of the exact volume and moments (tests/unit/composite.c:
 * 2.0e-4 measured; 0.2 % is the seed's target), in about 0.5 s on 2 cores. */
#define SD_COMPOSITE_LATTICE_DEFAULT 200
/* 500^3 points take seconds; the 2000 documented before took minutes */
#define SD_COMPOSITE_LATTICE_MAX 500
/* Above this fraction of the elements' summed volume counted more than
 * once (the lattice's error on the excess then comes back multiplied by
 * more than 1 / (1 - 0.85) = 6.7), the union is integrated directly on the
 * lattice instead of the sum minus the excess (composite.c). Ordinary
 * clumps stay below it (the spheres9 preset shares 76 %), chains of many
 * overlapping elements do not (20 spheres 0.01 mm apart: 88 %; 180: 92 %). */
#define SD_COMPOSITE_EXCESS_MAX 0.85

/* The shapes and pools the elements' templates live in (the world's). */
typedef struct sd_composite_pools {
    const sd_shape *shapes;
    size_t shape_count;
    const sd_vec3 *verts;
    const sd_plane *planes;
    const sd_dtri *dtris;
} sd_composite_pools;

/* One element as given: a convex template in the composite's given frame. */
typedef struct sd_composite_part {
    int shape;  /* convex template index in pools->shapes */
    sd_vec3 x;  /* m, its centre of mass, given frame */
    sd_quat q;  /* its principal frame -> the given frame (normalised here) */
} sd_composite_part;

/* Builds the composite: *out (kind SD_SHAPE_COMPOSITE, estart 0, ecount n)
 * and elems[0 .. n) in its principal frame. lattice: points per direction
 * when elements overlap, 0 = SD_COMPOSITE_LATTICE_DEFAULT (over the box
 * around the overlaps, or the same budget spent pair by pair over the
 * overlapping pairs' own boxes when that gives finer cells); threads: OpenMP
 * threads for the lattice (<= 0: the runtime's choice; the result does not
 * depend on it). SD_ERR_INPUT with the key ("elements", "lattice") for a
 * bad input, SD_ERR_MEMORY on allocation failure. */
sd_status sd_composite_make(const sd_composite_pools *pools, const sd_composite_part *parts, size_t n, int lattice,
                            int threads, sd_shape *out, sd_element *elems, sd_error *err);

/* Overlap of parts a and b: 1 when their swept bodies overlap by more than
 * 1e-9 of their bounding radii (touching faces are apart), else 0. */
int sd_composite_parts_overlap(const sd_composite_pools *pools, const sd_composite_part *a,
                               const sd_composite_part *b);

/* The seed's voxel lattice (seed 004 eqs. 7-8) with n points per direction
 * over the parts' bounding box, given frame. union_mass: cells inside at
 * least one part; excess: cells weighted by (parts containing them - 1),
 * the volume counted twice or more by a plain sum. Either may be NULL.
 * Each cell contributes its centre's point mass plus its own second moment
 * (h^2/12 per axis), so a fully covered box is exact. */
sd_status sd_composite_lattice(const sd_composite_pools *pools, const sd_composite_part *parts, size_t n_parts,
                               int n, int threads, sd_mass *union_mass, sd_mass *excess);

/* Is point p (m, the template's principal frame) inside the swept shape s? */
int sd_composite_point_inside(const sd_shape *s, const sd_vec3 *verts, const sd_plane *planes, const sd_dtri *dtris,
                              sd_vec3 p);

#endif
