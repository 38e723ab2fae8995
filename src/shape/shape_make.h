/* shape_make.h — building shape templates (host code): validation, exact
 * mass properties of the swept shape, the move to the principal frame.
 *
 * A def describes the shape a user means; sd_shape_make turns it into an
 * sd_shape (shape.h) whose core, swept by `radius`, is that shape, placed
 * with its centre of mass at the origin and its principal axes along x, y, z.
 *
 * Two ways to round a shape (at most one per def):
 *   rounding r: the core has the given size; the shape is the core swept by
 *               a sphere of radius r, so it is 2r larger overall;
 *   margin m:   the shape keeps the given outer size; the core is the given
 *               body shrunk by m on every side (its inner parallel body),
 *               swept back by m, which rounds edges and corners with radius
 *               m (seed 004 §2.5: shrink, GJK on the cores, swell). For the
 *               ellipsoid the core is the ellipsoid of semi-axes a - m (the
 *               inner parallel body of an ellipsoid is no ellipsoid); the
 *               swept shape then has the given semi-axes along x, y, z.
 * Mass properties are those of the swept shape, exactly (closed forms) for
 * every kind but the rounded ellipsoid, which is integrated numerically to
 * a relative 1e-13 (see shape.c).
 */
#ifndef SD_SHAPE_SHAPE_MAKE_H
#define SD_SHAPE_SHAPE_MAKE_H

#include <stdio.h>

#include <shapedem/shapedem.h>

#include "core/mat3.h"
#include "geom/hull.h"
#include "shape/shape.h"

typedef struct sd_shape_def {
    int kind;                /* sd_shape_kind */
    sd_vec3 size;            /* m: box: full edge lengths; cylinder: (diameter, -, length);
                                cone: (base diameter, -, height); ellipsoid: semi-axes;
                                sphere: (radius, -, -); polyhedron: unused */
    sd_real rounding;        /* m, >= 0: the core has `size`, swept by a sphere of this radius */
    sd_real margin;          /* m, >= 0: the outer size is `size`; core shrunk by it, swept by it */
    sd_real scale;           /* -, > 0, multiplies every length (size, rounding, margin, vertices) */
    const sd_vec3 *vertices; /* polyhedron: points in any frame; the core is their hull */
    size_t vertex_count;     /* 4 .. SD_SHAPE_MAX_VERTICES */
    int cookie;              /* set by sd_shape_def_default */
} sd_shape_def;

sd_shape_def sd_shape_def_default(void);

/* Builds a template. Polyhedra write their hull vertices (principal frame,
 * extreme vertices only, in ascending order of their input index) to
 * verts_out[0 .. *verts_used); out->vstart is 0 and out->vcount = *verts_used,
 * so a caller that copies them into a pool at offset k sets vstart = k.
 * verts_cap must hold the hull's vertices: at most vertex_count without a
 * margin; with a margin the shrunk core may have up to 4 * vertex_count
 * (one corner per face of the dual hull of its at most 2 vertex_count - 4
 * face planes).
 * Other kinds use no vertices (*verts_used = 0). Returns SD_ERR_INPUT with a
 * message for a bad def, SD_ERR_MEMORY when an allocation fails. */
sd_status sd_shape_make(const sd_shape_def *def, sd_shape *out, sd_vec3 *verts_out, size_t verts_cap,
                        size_t *verts_used, sd_error *err);

/* Welded face planes and the vertex/face adjacency of a polyhedron template
 * (seed 000 §2.1), in its principal frame, from its hull vertices
 * verts[s->vstart .. + s->vcount). Triangles of the hull whose vertices lie
 * within SD_SHAPE_WELD_REL x (core bounding radius) of a face's plane are
 * grown into one face (region growing from the largest free triangle, first
 * against its plane, then against the face's own fitted plane, so a gently
 * curved tessellation never chains into one face and a thin seed tilted by
 * round-off does not split a polygon); each face gets the unit
 * area-weighted normal of its triangles and the offset h = max n . v over its
 * vertices, so every vertex satisfies every plane. The dual triangles are the
 * hull of the polar points n_f / h_f about the centre of mass (seed 000
 * eqs. 4-5), each with the vertex where its three planes meet. Writes
 * planes[0 .. *nplanes) and tris[0 .. *ntris); s->fcount / s->tcount are set,
 * fstart / tstart are 0 (the caller places them in its pools). Caps: at most
 * 2 s->vcount planes and 4 s->vcount dual triangles are ever written. Other
 * kinds get no planes. SD_ERR_INPUT for a template whose planes do not close
 * (a bad hull), SD_ERR_MEMORY when an allocation fails. */
/* 1e-5: a vertex list typed to 5 or more significant digits (φ as
 * 1.618034, STL floats) welds to the faces meant (tests/unit/shape_weld.c),
 * while the sides of a 500-gon prism up to 5 diameters long (neighbours
 * 3e-5 of its size apart or more) stay apart. sd_shape_make uses it too. */
#define SD_SHAPE_WELD_REL SD_R(1e-5)
sd_status sd_shape_faces(sd_shape *s, const sd_vec3 *verts, sd_plane *planes, size_t planes_cap, size_t *nplanes,
                         sd_dtri *tris, size_t tris_cap, size_t *ntris, sd_error *err);

/* Scene names from the SD_SHAPE_KINDS list; from_name returns -1 if unknown. */
const char *sd_shape_kind_name(int kind);
int sd_shape_kind_from_name(const char *name);

/* Kind, size, volume, centre of mass, principal moments, bounding radius;
 * the _density form adds the mass and moments at that density (kg/m^3). */
void sd_shape_print_info(FILE *f, const sd_shape *s, const sd_vec3 *verts);
void sd_shape_print_info_density(FILE *f, const sd_shape *s, const sd_vec3 *verts, double density);

/* ---- lower-level pieces (tests, composites) ------------------------------- */

/* Mass properties per unit density: volume (m^3), centre of mass (m) and
 * second moments about it, J = integral of (x - c)(x - c)^T dV (m^5); the
 * inertia tensor is tr(J) 1 - J. */
typedef struct sd_mass {
    sd_real volume;
    sd_vec3 com;
    sd_mat3 second;
} sd_mass;

/* The hull h of pts swept by a sphere of radius r >= 0, exactly:
 * core tetrahedra + face prisms + edge wedges (dihedral exterior angle) +
 * vertex spherical sectors (the normal cones). SD_ERR_MEMORY on failure. */
sd_status sd_mass_swept_hull(const sd_vec3 *pts, const sd_hull *h, sd_real r, sd_mass *out);

/* Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations:
 * a = v diag(w) v^T, v a rotation (det +1), columns the eigenvectors. */
void sd_mat3_sym_eigen(sd_mat3 a, sd_vec3 *w, sd_mat3 *v);

/* Unit quaternion (w >= 0) of a rotation matrix. */
sd_quat sd_quat_from_mat3(const sd_mat3 *m);

/* Minimum width of the hull (m): the least distance between two parallel
 * supporting planes, over face normals and antipodal edge pairs. */
sd_real sd_hull_min_width(const sd_vec3 *pts, const sd_hull *h);

#endif
