/* meshwall.h — a triangle-mesh wall as the broad phase and the items see
 * it (seed 000 §2.4): the prepared mesh (geom/trimesh.h) in the mesh's own
 * frame, its plane groups, its active features and its facet bins, plus
 * the pose that places the mesh in the world.
 *
 * A mesh is rigid: its vertices never change in its own frame; its pose
 * (world = R(q) x_mesh + trans, dynamics/walls.h's sd_wall_geom q, trans)
 * moves with its motion. The facet bins are built once in the mesh frame
 * (world/mesh.c) and a particle is mapped into that frame to query them,
 * so a moving mesh never re-bins its facets.
 *
 * Facet bins: cubic cells of edge h over the mesh frame, keyed by a 64-bit
 * cell key (21 bits per axis, offset so keys are unsigned); the entries are
 * (key, triangle) sorted by key then triangle, every triangle listed in
 * each cell its plane crosses within its bounding box. A query of a box of
 * at most 2 x 2 x 2 cells (h >= the box edge) costs eight binary searches
 * and the facets in those cells, never a scan of the mesh.
 *
 * Single source (SD_HD): plain structs, no allocation, compiles as C17 and
 * as C++ (tests/cuda/mesh.cu).
 */
#ifndef SD_DYNAMICS_MESHWALL_H
#define SD_DYNAMICS_MESHWALL_H

#include "core/quat.h"
#include "core/vec.h"

#define SD_MESH_KEY_BITS 21
#define SD_MESH_KEY_BIAS (1 << 20)

/* One mesh wall: arrays in the mesh frame, owned by the world (world/mesh.c). */
typedef struct sd_mesh_view {
    size_t tri_count, group_count;
    const sd_vec3 *verts;          /* m, mesh frame */
    const uint32_t (*tris)[3];
    const uint32_t *group;         /* plane group of each triangle */
    const uint8_t *flags;          /* SD_TRIMESH_EDGE(k), SD_TRIMESH_CORNER(k), SD_TRIMESH_CLOSED of geom/trimesh.h */
    const uint32_t (*nbr)[3];      /* triangle across edge k, UINT32_MAX: none (boundary, non-manifold) */
    const sd_vec3 *group_normal;   /* unit, mesh frame, towards the particle side */
    const sd_real *group_offset;   /* m: n . x = offset */
    /* facet bins (mesh frame) */
    sd_real h;                     /* m, cell edge; 0 when not built */
    sd_vec3 origin;                /* m, the corner of cell (0, 0, 0) */
    size_t entry_count;
    const uint64_t *entry_key;     /* sorted */
    const uint32_t *entry_tri;
} sd_mesh_view;

/* Bit k (0..2): edge corner k -> k+1 active; bit 3 + k: corner k active
 * (the marks of geom/trimesh.h, repeated so device code needs no host header). */
#define SD_MESH_EDGE_BIT(k) (1u << (k))
#define SD_MESH_CORNER_BIT(k) (1u << (3 + (k)))
#define SD_MESH_CLOSED_BIT (1u << 6) /* the triangle's part is closed (SD_TRIMESH_CLOSED) */

SD_HD static SD_INLINE sd_vec3 sd_mesh_to_frame(sd_quat q, sd_vec3 trans, sd_vec3 x)
{
    return sd_quat_rotate_inv(q, sd_v3_sub(x, trans));
}

SD_HD static SD_INLINE sd_vec3 sd_mesh_to_world(sd_quat q, sd_vec3 trans, sd_vec3 xm)
{
    return sd_v3_add(sd_quat_rotate(q, xm), trans);
}

/* The cell index of coordinate c along one axis (clamped to the key range). */
SD_HD static SD_INLINE long sd_mesh_cell_of(sd_real c, sd_real o, sd_real h)
{
    sd_real f = sd_floor((c - o) / h);
    if (f < -(sd_real)SD_MESH_KEY_BIAS)
        f = -(sd_real)SD_MESH_KEY_BIAS;
    if (f > (sd_real)(SD_MESH_KEY_BIAS - 1))
        f = (sd_real)(SD_MESH_KEY_BIAS - 1);
    return (long)f;
}

SD_HD static SD_INLINE uint64_t sd_mesh_key(long i, long j, long k)
{
    return ((uint64_t)(i + SD_MESH_KEY_BIAS) << (2 * SD_MESH_KEY_BITS)) |
           ((uint64_t)(j + SD_MESH_KEY_BIAS) << SD_MESH_KEY_BITS) | (uint64_t)(k + SD_MESH_KEY_BIAS);
}

/* First entry with key >= k (binary search). */
SD_HD static SD_INLINE size_t sd_mesh_lower(const sd_mesh_view *m, uint64_t k)
{
    size_t lo = 0, hi = m->entry_count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (m->entry_key[mid] < k)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

#endif
