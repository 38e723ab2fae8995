/* start_overlap.h — how deep two particles overlap with their true shapes,
 * for the start-overlap check of the scene builder (io/scene_build.c),
 * before they are added to the world.
 *
 * It uses the step's own narrow phase, so a packing that a run wrote (its
 * positions and orientations) loads again exactly when the run itself saw
 * no more than its contact overlaps: two spheres analytically, any pair
 * with a shape template by shrink / GJK / swell (EPA when the cores touch;
 * geom/convex_contact.h), and two sharp polyhedra that meet under a volume
 * law by their exact overlap (geom/overlap.h), with the depth the volume
 * law takes (contact/pair_poly.h); against a box wall, by the shape's
 * support point along each face's outward normal. Planar (2D) shapes are
 * not handled here: callers keep their bounding circles.
 */
#ifndef SD_WORLD_START_OVERLAP_H
#define SD_WORLD_START_OVERLAP_H

#include <shapedem/shapedem.h>

/* One particle as the scene gives it: a sphere (shape -1, radius) or a
 * body of world shape `shape` at its centre of mass, orientation q (w, x,
 * y, z), principal frame to world. */
typedef struct sd_start_particle {
    sd_v3d position;
    double q[4];
    double radius;   /* m, the sphere's; ignored for a body */
    int shape;       /* world shape index, or -1 */
    int material;    /* world material index */
} sd_start_particle;

/* Depth (m) by which a and b overlap, <= 0 when they do not; *size gets
 * the smaller of the two sizes an overlap is measured against (a sphere's
 * radius, half a shape's smallest outer dimension: stats.csv's
 * max_overlap_ratio). The shapes of w must exist; w need not be prepared. */
double sd_start_overlap(const sd_world *w, const sd_start_particle *a, const sd_start_particle *b, double *size);

/* How far the particle reaches along the unit vector dir (m): the largest
 * dir . x over its outer surface (a sphere: dir . centre + radius). The
 * box-wall check uses it for each closed face. */
double sd_start_reach(const sd_world *w, const sd_start_particle *p, sd_v3d dir);

/* The size an overlap is measured against: a sphere's radius, half a
 * shape's smallest outer dimension. */
double sd_start_size(const sd_world *w, const sd_start_particle *p);

#endif
