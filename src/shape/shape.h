/* shape.h — shape kinds and templates, and the posed convex body that the
 * narrow phase (GJK, EPA) asks for support points.
 *
 * Every shape is a convex core swept by a sphere of radius `radius` (a
 * Minkowski sum): a sphere is a point core with its radius; a rounded box is
 * a box core with its rounding radius; a sharp shape has radius 0, or a
 * user-set margin (its core is shrunk by the margin and swept by it, seed 004
 * §2.5 shrink / GJK / swell). Templates live in their principal frame: the
 * centre of mass at the origin and the principal axes of inertia along x, y,
 * z, so a particle's orientation quaternion maps this frame to the world.
 *
 * Single source (DESIGN.md rule 1): the support function is SD_HD, takes
 * plain structs and reads polyhedron vertices from a shared vertex pool.
 */
#ifndef SD_SHAPE_SHAPE_H
#define SD_SHAPE_SHAPE_H

#include "core/quat.h"

/* X(enum, scene name, what the dimensions a mean) */
#define SD_SHAPE_KINDS(X)                                                                    \
    X(SD_SHAPE_SPHERE, "sphere", "point core; radius is the sphere's")                       \
    X(SD_SHAPE_BOX, "box", "a = half extents of the core")                                  \
    X(SD_SHAPE_CYLINDER, "cylinder", "a = (core radius, core radius, core half length), axis z") \
    X(SD_SHAPE_CONE, "cone", "a = (core base radius, core base radius, core height), axis z, apex up") \
    X(SD_SHAPE_ELLIPSOID, "ellipsoid", "a = core semi-axes")                                 \
    X(SD_SHAPE_POLYHEDRON, "polyhedron", "core = convex hull of vertices [vstart, vstart + vcount)") \
    X(SD_SHAPE_COMPOSITE, "composite", "elements [estart, estart + ecount) of the element pool")

typedef enum sd_shape_kind {
#define SD_X_ENUM(e, name, doc) e,
    SD_SHAPE_KINDS(SD_X_ENUM)
#undef SD_X_ENUM
    SD_SHAPE_KIND_COUNT
} sd_shape_kind;

/* Most vertices a polyhedron template may have (fixed GPU workspaces). */
#define SD_SHAPE_MAX_VERTICES 1024

/* Most welded face planes per polyhedron that the exact overlap volume
 * (geom/overlap.h) handles: its per-pair workspace is sized by it. A
 * template with more faces is still a valid shape for the GJK laws;
 * sd_overlap_polyhedra reports SD_OVERLAP_OVERFLOW for it (never a silent
 * truncation), and sd_shape_faces says so when the template is built. */
#ifndef SD_OVERLAP_MAX_PLANES
#define SD_OVERLAP_MAX_PLANES 64
#endif

/* One welded face of a polyhedron template (seed 000 §2.1: coplanar
 * triangles merged into one plane): the body is n . x <= h, principal frame. */
typedef struct sd_plane {
    sd_vec3 n; /* unit outward normal */
    sd_real h; /* m, offset: the face is n . x = h */
} sd_plane;

/* One vertex of a polyhedron template seen from its face planes: the dual
 * triangle (f[0], f[1], f[2]) of the polar dual hull (seed 000 §2.3). Three
 * of the faces meeting at the vertex, counter-clockwise seen from outside;
 * a vertex where k > 3 faces meet is k - 2 triangles at the same point.
 * nb[k] is the dual triangle across the dual edge f[k] -> f[k+1], i.e. the
 * vertex at the other end of the primal edge where faces f[k] and f[k+1]
 * meet. Together they are the vertex/face adjacency of the template.
 * nk[k] is the edge of nb[k] that leads back (nb[nb[k]].nb[nk[k]] is this
 * triangle), so a walk over the adjacency never searches. */
typedef struct sd_dtri {
    sd_vec3 v;      /* m, principal frame: where planes f[0..2] meet */
    uint16_t f[3];  /* face indices, 0 .. fcount - 1 */
    uint16_t nb[3]; /* dual triangle indices, 0 .. tcount - 1 */
    uint8_t nk[3];  /* edge index (0..2) of the twin dual edge in nb[k] */
} sd_dtri;

typedef struct sd_shape {
    int kind;            /* sd_shape_kind */
    sd_real radius;      /* m, radius of the sphere swept over the core (>= 0) */
    sd_vec3 a;           /* m, core dimensions, see SD_SHAPE_KINDS */
    sd_vec3 offset;      /* m, where the core's own reference point sits in the
                            principal frame (cone: its base centre is at -h/4
                            on z so the centre of mass is the origin) */
    uint32_t vstart, vcount; /* polyhedron: vertices (principal frame) in the pool */
    uint32_t fstart, fcount; /* polyhedron: welded face planes in the plane pool (core) */
    uint32_t tstart, tcount; /* polyhedron: dual triangles (vertex/face adjacency) in their pool */
    /* composite (seed 004): its convex elements in the element pool. A
     * composite is never a convex body: no support function, no GJK, no
     * plane contact of its own; the broad phase expands it into elements
     * (sd_element), each a convex template. radius, a and offset are 0. */
    uint32_t estart, ecount;
    sd_real bound;       /* m, bounding radius about the centre of mass, radius included */
    sd_real volume;      /* m^3, of the swept shape */
    sd_vec3 inertia;     /* m^5, principal second moments of the swept shape per
                            unit density (moment of inertia = density * inertia) */
    sd_real min_size;    /* m, smallest outer dimension (for overlap ratios) */
    /* Cold, host-side (set by sd_shape_make): where the principal frame sits
     * in the frame the shape was given in (polyhedron: its vertices' frame;
     * cone: base centre at the origin, apex up; other kinds: centred), so
     * x_given = given_com + rotate(given_q, x_principal). */
    sd_vec3 given_com;   /* m, centre of mass in the given frame */
    sd_quat given_q;     /* principal frame to the given frame (identity but for polyhedra
                            and composites) */
    /* Cold, host-side, composites: how the mass properties were found
     * (shape/composite.h): 0 = exact sums (no two elements overlap), else
     * the points per direction of the voxel lattice, with its estimated
     * relative error of the volume. */
    int mass_lattice;
    sd_real mass_error;
} sd_shape;

/* One convex element of a composite template (seed 004 §2.1): a convex
 * template (never a composite) rigidly placed in the composite's principal
 * frame. Its world pose for a composite at (x, q) is x_e = x + R(q) e.x,
 * q_e = q * e.q (seed 004 eqs. 5-6), derived when needed, never stored per
 * particle. */
typedef struct sd_element {
    int shape;     /* index of the element's convex template */
    sd_vec3 x;     /* m, element centre of mass in the composite's principal frame */
    sd_quat q;     /* element principal frame -> composite principal frame */
    sd_real bound; /* m, the element template's bounding radius (copy) */
} sd_element;

/* A convex body in the world: a shape with its pose. */
typedef struct sd_convex {
    const sd_shape *shape;
    const sd_vec3 *verts; /* the vertex pool (may be NULL without polyhedra) */
    sd_vec3 x;            /* m, centre of mass, world frame */
    sd_quat q;            /* principal frame to world frame */
    /* last, so positional initialisers {shape, verts, x, q} stay valid */
    const sd_plane *planes; /* the face-plane pool (NULL without polyhedra) */
    const sd_dtri *dtris;   /* the dual-triangle pool (NULL without polyhedra) */
} sd_convex;

#endif
