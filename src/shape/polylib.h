/* polylib.h — the built-in library of convex polyhedra (host code): the
 * five Platonic solids, n-gon prisms, n-sided cylinders as seed 000 §3.1
 * builds them, and seeded random convex polyhedra.
 *
 * Each preset writes the vertex set of one polyhedron; sd_shape_make then
 * takes its hull, welds coplanar triangles into faces (seed 000 §2.1) and
 * moves it to its principal frame. Sizes are set by the circumscribed
 * sphere, so every preset of diameter D fits in a ball of diameter D:
 *   platonic   size = circumscribed diameter (or, through sd_polylib_edge_to_size,
 *              an edge length);
 *   prism      `sides`-gon of circumscribed diameter D (vertices on the circle)
 *              and length L along z: 2n vertices, n + 2 faces;
 *   cylinder   the same solid with the two cap centres added, the template of
 *              seed 000 §3.1: for n = 20, 42 vertices and 80 triangles
 *              (20 per cap fanned from its centre, 40 on the side), 22 welded faces;
 *   random     `points` = N: N points uniform on the circumscribed sphere
 *              (every one a vertex); `faces` = F: F planes tangent to a sphere
 *              at uniform random normals (every one a face), rescaled so its
 *              farthest vertex lies on the circumscribed sphere. Same seed,
 *              same polyhedron, on every platform (core/rng.h).
 */
#ifndef SD_SHAPE_POLYLIB_H
#define SD_SHAPE_POLYLIB_H

#include <stdint.h>

#include <shapedem/shapedem.h>

#include "core/vec.h"

/* X(enum, scene name, what it is) */
#define SD_POLY_PRESETS(X)                                                                                             \
    X(SD_POLY_TETRAHEDRON, "tetrahedron", "regular tetrahedron, 4 faces")                                              \
    X(SD_POLY_CUBE, "cube", "cube, 6 faces")                                                                           \
    X(SD_POLY_OCTAHEDRON, "octahedron", "regular octahedron, 8 faces")                                                 \
    X(SD_POLY_DODECAHEDRON, "dodecahedron", "regular dodecahedron, 12 faces")                                          \
    X(SD_POLY_ICOSAHEDRON, "icosahedron", "regular icosahedron, 20 faces")                                             \
    X(SD_POLY_PRISM, "prism", "right prism on a regular n-gon (sides), axis z")                                        \
    X(SD_POLY_CYLINDER, "cylinder", "n-sided cylinder with cap centres (seed 000 §3.1), axis z")                       \
    X(SD_POLY_RANDOM, "random", "seeded random convex polyhedron (points or faces)")

typedef enum sd_poly_preset {
#define SD_X_ENUM(e, name, doc) e,
    SD_POLY_PRESETS(SD_X_ENUM)
#undef SD_X_ENUM
        SD_POLY_PRESET_COUNT
} sd_poly_preset;

/* Most vertices a preset may ask for (random faces: 2F - 4 vertices). */
#define SD_POLY_MAX_SIDES  500
#define SD_POLY_MAX_RANDOM 500

typedef struct sd_poly_def {
    int preset;      /* sd_poly_preset */
    double diameter; /* m, of the circumscribed sphere (prism/cylinder: of the n-gon's circle) */
    double length;   /* m, prism/cylinder length along z */
    int sides;       /* prism/cylinder: n >= 3 */
    int points;      /* random: number of points on the sphere (>= 4), or 0 */
    int faces;       /* random: number of tangent planes (>= 4), or 0; give one of points, faces */
    uint64_t seed;   /* random */
} sd_poly_def;

/* Writes the vertices to out[0 .. *count); cap must be at least
 * sd_polylib_vertex_count(def). SD_ERR_INPUT with a message (key named) for
 * a bad def. */
sd_status sd_polylib_vertices(const sd_poly_def *def, sd_v3d *out, size_t cap, size_t *count, sd_error *err);
/* Vertices the def will produce (0 for a bad def). */
size_t sd_polylib_vertex_count(const sd_poly_def *def);
/* The circumscribed diameter of a Platonic solid of edge length a (0 otherwise). */
double sd_polylib_edge_to_diameter(int preset, double a);

/* How far a mesh is from convex: the largest depth, below the boundary of
 * the convex hull of pts[0..n), of a mesh vertex or of the centre of a mesh
 * face (centres[0..nc)), in m; *which is the index of that point (vertices
 * first, then face centres: which >= n is face which - n) and *size the
 * hull's diameter (largest vertex distance, m). A convex mesh has depth 0
 * up to rounding; a dent or a face folded inward shows as its depth.
 * Returns -1 if the hull fails (flat or too many points), -2 when out of
 * memory. */
double sd_mesh_concavity(const sd_v3d *pts, size_t n, const sd_v3d *centres, size_t nc, size_t *which, double *size);

const char *sd_polylib_name(int preset);
int sd_polylib_from_name(const char *name); /* -1 if unknown */

#endif
