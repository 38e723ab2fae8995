/* tally.h — the narrow-phase tallies of one 3D pair on the device (the
 * CPU's sd_tally3_add, backend/cpu/pairs.c): evaluations, iterations and
 * support calls per sorted pair of shape kinds, integer atomics into the
 * device's counters (exact in any order; read back adds them to the
 * world's). Shared by the pair kernels of pairs.cu, pairs_volume.cu and
 * pairs_elements.cu.
 */
#ifndef SD_BACKEND_CUDA_TALLY_H
#define SD_BACKEND_CUDA_TALLY_H

#include "backend/cuda/state.h"
#include "backend/items.h"

__device__ static inline void sd_k_tally3(const sd_step_view *v, const sd_pair_out *o, size_t e,
                                          unsigned long long *tally)
{
    if (o->supports[e] == 0)
        return; /* culled by the bounding spheres */
    int a = sd_item_shape_kind(v, o->i[e]), b = sd_item_shape_kind(v, o->j[e]);
    if (a > b) {
        int t = a;
        a = b;
        b = t;
    }
    unsigned long long *y = tally + ((size_t)a * SD_SHAPE_KIND_COUNT + (size_t)b) * 3;
    atomicAdd(&y[0], 1ull);
    atomicAdd(&y[1], (unsigned long long)o->iters[e]);
    atomicAdd(&y[2], (unsigned long long)o->supports[e]);
}

#endif
