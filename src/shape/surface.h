/* surface.h — a template's surface as a polygon mesh in its principal frame,
 * for pictures (VTK shapes files, `shapedem render`), never for contacts.
 *
 * Every convex kind is drawn as the convex hull of its support points
 * s(d) = argmax_{x in K} d . x over a fixed set of directions d (seed 002
 * §2.2, seed 000 §2.3): the hull of points of K lies inside K, so the mesh
 * is inscribed, exact for flat shapes (a sharp box gives its 8 corners, a
 * sharp polyhedron its own vertices, a sharp cylinder a prism of
 * `resolution` sides) and converging to K as the resolution grows (the
 * volume error of a sphere falls as 1/resolution^2). A composite (seed 004)
 * is its elements' meshes placed in its frame; a planar (2D) outline is one
 * polygon in z = 0, its support points around the circle of directions.
 *
 * Cells are convex polygons: one per planar face of the hull (a box is 6
 * quads, a cylinder N side quads and 2 caps), triangles where the surface
 * curves. Invariant: 3D meshes are closed and every cell is wound
 * counter-clockwise seen from outside (outward normals), so the divergence
 * theorem on their fans gives the enclosed volume (sd_surface_measure); a planar polygon is
 * counter-clockwise, its shoelace sum its area. Host code: allocates through
 * the allocator hook, built once per template and only posed afterwards.
 */
#ifndef SD_SHAPE_SURFACE_H
#define SD_SHAPE_SURFACE_H

#include "shape/shape.h"
#include "shape/shape2d.h"

#include <shapedem/shapedem.h>

/* Directions per full turn: the range of output.shape_resolution. */
#define SD_SURFACE_RES_MIN 8
#define SD_SURFACE_RES_MAX 64

typedef struct sd_surface {
    size_t point_count;
    double *points;      /* m, x y z per point, principal frame */
    size_t cell_count;
    size_t conn_count;
    int64_t *conn;       /* point indices of every cell (a convex polygon), cell after cell */
    int64_t *ends;       /* cell k is conn[ends[k-1] .. ends[k]) (ends[-1] = 0) */
    int planar;          /* one polygon in z = 0 (2D outlines), else triangles */
} sd_surface;

/* A convex 3D template (any kind but the composite) at `resolution`
 * directions per turn; SD_ERR_INPUT for a bad resolution or a composite,
 * SD_ERR_MEMORY. */
sd_status sd_surface_convex(const sd_shape *s, const sd_vec3 *verts, int resolution, sd_surface *out,
                            sd_error *err);
/* A composite: each element's convex mesh moved to x_e + R(q_e) x (seed
 * 004 eqs. 5-6), cells element after element. */
sd_status sd_surface_composite(const sd_shape *s, const sd_element *elements, const sd_shape *shapes,
                               const sd_vec3 *verts, int resolution, sd_surface *out, sd_error *err);
/* A planar outline: one counter-clockwise polygon in z = 0. */
sd_status sd_surface_outline(const sd_shape2d *s, const sd_real *pool, int resolution, sd_surface *out,
                             sd_error *err);
/* The unit sphere (3D) or unit circle (planar): plain spheres, scaled by
 * their radius when posed. */
sd_status sd_surface_unit_ball(int planar, int resolution, sd_surface *out, sd_error *err);

/* Enclosed volume (m^3, divergence theorem: sum over triangles of
 * a . (b x c) / 6) or, planar, the polygons' area (m^2). */
double sd_surface_measure(const sd_surface *s);

void sd_surface_free(sd_surface *s);

#endif
