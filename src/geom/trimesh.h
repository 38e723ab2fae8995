/* trimesh.h — preparing a triangle mesh for use as a wall (seed 000 §2.4):
 * weld, clean, orient, group coplanar facets, mark the active features.
 *
 * Host code, run once when a mesh wall is added; the per-step numerics
 * (clipping, areas, feature tests) read its output and live elsewhere.
 *
 * What sd_trimesh_build does, in order:
 *  1. weld: vertices closer than weld_tol (m; 0 = 1e-9 of the bounding-box
 *     diagonal) become one, the lowest-numbered one of the cluster;
 *  2. drop degenerate facets (two corners welded together, or a height
 *     below weld_tol: zero area for the mesh's purposes) and duplicated
 *     facets (the same three welded vertices in any order: the first one
 *     is kept), counting both;
 *  3. orient: across every edge shared by exactly two facets the windings
 *     must run opposite ways; each connected part keeps the winding of the
 *     majority of its facets (ties: of its lowest-numbered facet) and the
 *     others are turned (counted in `flipped`). A part that cannot be wound
 *     consistently (a Möbius strip) is an error naming a facet. A closed
 *     part (every edge shared by two facets) is then wound so that its
 *     right-hand normals point to the particle side: inward for
 *     sd_trimesh_build (a drum, a closed box), outward for
 *     sd_trimesh_build_side(..., SD_TRIMESH_OUTSIDE) (an obstacle);
 *     that global turn is not counted as flips. An open part keeps the
 *     side its (majority) winding's right-hand normal points to;
 *  4. plane groups: facets joined through shared edges whose unit normals
 *     agree with the group's first facet within coplanar_tol (rad; 0 =
 *     1e-6), grown breadth first from the lowest-numbered facet;
 *  5. active features (the rule the contact code relies on):
 *     - an edge shared by two facets of one plane group is inactive;
 *     - an edge shared by two facets meeting concavely (the far corner of
 *       the other facet lies on the particle side of this facet's plane)
 *       or flat is inactive;
 *     - a convex shared edge is active on exactly one of its two facets,
 *       the lower-numbered one (in the output numbering);
 *     - a boundary edge (one facet) is active on it; an edge shared by
 *       more than two facets (non-manifold) is active on the lowest one;
 *     - a corner is active on exactly one incident facet, the lowest-
 *       numbered, unless every edge incident to it is inactive (flat or
 *       concave surroundings), when it is inactive on all of them.
 *     An inactive edge or corner must not make a contact of its own: the
 *     facet faces next to it do, so a body crossing a flat or concave seam
 *     feels the forces of the faces only;
 *  6. the triangles of closed parts are marked SD_TRIMESH_CLOSED: behind
 *     each lies the part's solid, so a particle whose centre is behind one
 *     came through the part (the thin-wall rule, geom/mesh_contact.h).
 *
 * Invariant: on SD_OK every output array is allocated (sd_malloc), every
 * index is < vertex_count, every triangle has three distinct vertices and
 * nonzero area, no two triangles share their vertex set, group[t] <
 * group_count, and group_normal[g] is a unit vector; on an error *out is
 * empty and nothing is allocated. Deterministic: the output depends only
 * on the input arrays (no hashing of addresses, sorts with full ties).
 */
#ifndef SD_GEOM_TRIMESH_H
#define SD_GEOM_TRIMESH_H

#include <stddef.h>
#include <stdint.h>

#include <shapedem/shapedem.h>

#include "core/vec.h"

#define SD_TRIMESH_EDGE(k)   (1u << (k))       /* edge corner k -> k+1 (mod 3) active on this triangle */
#define SD_TRIMESH_CORNER(k) (1u << (3 + (k))) /* corner k active on this triangle */
#define SD_TRIMESH_CLOSED    (1u << 6)         /* the triangle's part is closed: behind it lies the part's solid */

/* The side particles are on, for closed parts of a mesh. */
enum { SD_TRIMESH_INSIDE = 1, SD_TRIMESH_OUTSIDE = -1 };

typedef struct sd_trimesh {
    size_t vertex_count, triangle_count, group_count;
    /* m, welded: the vertices facets use, in order of their lowest input index */
    sd_vec3 *vertices;
    /* consistently wound where the mesh is orientable; degenerate and duplicate facets dropped */
    uint32_t (*triangles)[3];
    /* plane group of each triangle: connected (through shared edges) coplanar facets */
    uint32_t *group;
    /* per triangle: SD_TRIMESH_EDGE(k), SD_TRIMESH_CORNER(k), SD_TRIMESH_CLOSED */
    uint8_t *flags;
    /* unit normal of each plane group (the particle side; closed meshes: inward by default) */
    sd_vec3 *group_normal;
    /* m: n . x = offset on the group's plane */
    sd_real *group_offset;
    /* per triangle: its facet index in the input (0-based) */
    uint32_t *source;
    /* per triangle: the triangle across edge k (corner k -> k + 1), UINT32_MAX
     * for a boundary or non-manifold edge (the contact's Voronoi tests at
     * active edges and corners, geom/mesh_contact.h) */
    uint32_t (*nbr)[3];
} sd_trimesh;

typedef struct sd_trimesh_report {
    size_t welded;                                           /* input vertices merged into another one */
    size_t degenerate, duplicates;                           /* facets dropped */
    size_t flipped;                                          /* facets turned to agree with their neighbours */
    int closed;                                              /* 1 when every edge is shared by exactly two facets */
    size_t first_degenerate, first_duplicate, first_flipped; /* 1-based input facet of the first of each, 0 = none */
    size_t nonmanifold; /* edges shared by more than two facets (kept; their facets are not oriented across them) */
    size_t parts;       /* connected parts (through shared manifold edges) */
} sd_trimesh_report;

/* Prepares a mesh; closed parts face inward (SD_TRIMESH_INSIDE). rep may
 * be NULL. Errors (SD_ERR_INPUT, err->file "" — the caller names its
 * file): an index out of range, a non-finite coordinate, a part that
 * cannot be oriented, no facet left after cleaning; SD_ERR_MEMORY. */
sd_status sd_trimesh_build(const sd_v3d *v, size_t nv, const uint32_t (*t)[3], size_t nt, double weld_tol,
                           double coplanar_tol, sd_trimesh *out, sd_trimesh_report *rep, sd_error *err);
/* The same with the side of closed parts chosen (SD_TRIMESH_INSIDE or SD_TRIMESH_OUTSIDE). */
sd_status sd_trimesh_build_side(const sd_v3d *v, size_t nv, const uint32_t (*t)[3], size_t nt, double weld_tol,
                                double coplanar_tol, int side, sd_trimesh *out, sd_trimesh_report *rep, sd_error *err);
void sd_trimesh_free(sd_trimesh *m);

#endif
