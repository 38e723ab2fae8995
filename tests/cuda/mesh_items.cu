/* mesh_items.cu — compile-only proof that the mesh-wall numerics
 * (geom/clip.h, geom/mesh_contact.h, dynamics/meshwall.h) and the mesh
 * items of backend/items.h are single source (DESIGN.md rule 1): one wall
 * pair per thread. CI compiles this with nvcc (no GPU needed) and with
 * the host C++ compiler (cxx.mesh_items). */
#include "backend/items.h"
#include "geom/clip.h"
#include "geom/mesh_contact.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#define SD_ITEM_INDEX ((size_t)(blockIdx.x * blockDim.x + threadIdx.x))
#else
#define SD_KERNEL static
#define SD_ITEM_INDEX ((size_t)0)
#endif

SD_KERNEL void sd_check_mesh_kind(const sd_step_view *v, sd_wall_pair_out *o, int kind, size_t e0, size_t e1)
{
    size_t e = e0 + SD_ITEM_INDEX;
    if (e >= e1)
        return;
    switch (kind) {
    case SD_WALL_PAIR_MESH_SPHERE:
        sd_item_mesh_sphere(v, o, e);
        break;
    case SD_WALL_PAIR_MESH_CONVEX:
        sd_item_mesh_convex(v, o, e);
        break;
    case SD_WALL_PAIR_MESH_POLY_VOLUME:
        sd_item_mesh_poly_volume(v, o, e);
        break;
    case SD_WALL_PAIR_MESH_CONVEX2D:
        sd_item_mesh_convex2d(v, o, e);
        break;
    default:
        break;
    }
}

/* The clipping numerics on their own: a triangle clipped by a triangle. */
SD_KERNEL void sd_check_clip(const sd_vec2 *subject, const sd_vec2 *tri, sd_real *area)
{
    sd_vec2 t[3] = {tri[0], tri[1], tri[2]};
    sd_vec2 out[SD_CLIP_MAX + 3];
    int n = sd_clip_triangle(subject, 3, t, out);
    area[SD_ITEM_INDEX] = sd_clip_area(out, n, NULL);
}

#if !defined(__CUDACC__)
void sd_check_mesh_use(void);
void sd_check_mesh_use(void)
{
    (void)sd_check_mesh_kind;
    (void)sd_check_clip;
}
#endif
