/* items.cu — compile-only proof that the item functions of every
 * interaction kind (backend/items.h, on the views of backend/view.h) are
 * single source (DESIGN.md rule 1): one pair per thread, one kernel per
 * kind segment, as the CUDA backend will run them. CI compiles this with
 * nvcc (no GPU needed) and with the host C++ compiler (cxx.items). */
#include "backend/items.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#define SD_ITEM_INDEX ((size_t)(blockIdx.x * blockDim.x + threadIdx.x))
#else
#define SD_KERNEL static
#define SD_ITEM_INDEX ((size_t)0)
#endif

/* The particle-particle kinds: pairs [e0, e1) of one kind's segment. */
SD_KERNEL void sd_check_pair_kind(const sd_step_view *v, sd_pair_out *o, int kind, size_t e0, size_t e1,
                                  sd_overlap_workspace *ws)
{
    size_t e = e0 + SD_ITEM_INDEX;
    if (e >= e1)
        return;
    switch (kind) {
    case SD_PAIR_SPHERES:
        sd_item_spheres(v, o, e);
        break;
    case SD_PAIR_CONVEX:
        sd_item_convex(v, o, e);
        break;
    case SD_PAIR_POLY_VOLUME:
        sd_item_poly_volume(v, o, e, &ws[SD_ITEM_INDEX]);
        break;
    case SD_PAIR_CONVEX2D:
        sd_item_convex2d(v, o, e);
        break;
    case SD_PAIR_ELEMENTS:
        /* one thread per run of a composite pair's element pairs: the
         * thread whose pair starts a run evaluates and combines it */
        if (sd_item_elements_starts(o, e0, e)) {
            size_t end = e + 1;
            while (end < e1 && !sd_item_elements_starts(o, e0, end))
                ++end;
            (void)sd_item_elements(v, o, e, end, &ws[SD_ITEM_INDEX]);
        }
        break;
    default:
        break;
    }
}

/* The particle-wall kinds. */
SD_KERNEL void sd_check_wall_kind(const sd_step_view *v, sd_wall_pair_out *o, int kind, size_t e0, size_t e1)
{
    size_t e = e0 + SD_ITEM_INDEX;
    if (e >= e1)
        return;
    switch (kind) {
    case SD_WALL_PAIR_SPHERE:
        sd_item_wall_sphere(v, o, e);
        break;
    case SD_WALL_PAIR_CONVEX:
        sd_item_wall_convex(v, o, e);
        break;
    case SD_WALL_PAIR_POLY_VOLUME:
        sd_item_wall_poly_volume(v, o, e);
        break;
    case SD_WALL_PAIR_CONVEX2D:
        sd_item_wall_convex2d(v, o, e);
        break;
    case SD_WALL_PAIR_ELEMENTS:
        if (sd_item_wall_elements_starts(o, e0, e)) {
            size_t end = e + 1;
            while (end < e1 && !sd_item_wall_elements_starts(o, e0, end))
                ++end;
            (void)sd_item_wall_elements(v, o, e, end);
        }
        break;
    default:
        break;
    }
}

#if !defined(__CUDACC__)
/* keep the host compiler from warning about unused statics */
void sd_check_items_use(void);
void sd_check_items_use(void)
{
    (void)sd_check_pair_kind;
    (void)sd_check_wall_kind;
}
#endif
