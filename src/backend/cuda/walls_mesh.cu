/* walls_mesh.cu — the CUDA backend's kernels of the mesh wall-pair kinds
 * (contact/kinds.h MESH_*): a particle against one plane group of a
 * triangle-mesh wall (seed 000 §2.4), one thread per pair calling its item
 * (backend/items.h) as backend/cpu/walls.c does; no physics here.
 *
 * Invariant: an item writes only its own wall pair's slots; the mesh's
 * facets are the device copies of device.cu (sd_cuda_put_meshes), in the
 * mesh frame, the pose in the wall view.
 */
#include "backend/cuda/state.h"
#include "backend/items.h"

/* one kernel per mesh kind (a template on the kind, as walls.cu) */
template <int K> __global__ void sd_k_mesh_kind(sd_step_view v, sd_wall_pair_out o, size_t e0, size_t e1)
{
    size_t e = e0 + SD_CUDA_ITEM();
    if (e >= e1)
        return;
    if (K == SD_WALL_PAIR_MESH_SPHERE)
        sd_item_mesh_sphere(&v, &o, e);
    else if (K == SD_WALL_PAIR_MESH_CONVEX)
        sd_item_mesh_convex(&v, &o, e);
    else if (K == SD_WALL_PAIR_MESH_POLY_VOLUME)
        sd_item_mesh_poly_volume(&v, &o, e);
    else if (K == SD_WALL_PAIR_MESH_CONVEX2D)
        sd_item_mesh_convex2d(&v, &o, e);
}

int sd_cuda_mesh_wall_kind(sd_cuda_state *c, int kind, size_t e0, size_t e1)
{
    unsigned nb = sd_cuda_blocks(e1 - e0);
    switch (kind) {
#define SD_X_KIND(K)                                                                                 \
    case K:                                                                                          \
        SD_CUDA_LAUNCH(sd_k_mesh_kind<K>, nb, SD_CUDA_BLOCK, c->stream, c->v, c->wpairs, e0, e1); \
        return 1;
        SD_X_KIND(SD_WALL_PAIR_MESH_SPHERE)
        SD_X_KIND(SD_WALL_PAIR_MESH_CONVEX)
        SD_X_KIND(SD_WALL_PAIR_MESH_POLY_VOLUME)
        SD_X_KIND(SD_WALL_PAIR_MESH_CONVEX2D)
#undef SD_X_KIND
    default:
        return 0;
    }
}
