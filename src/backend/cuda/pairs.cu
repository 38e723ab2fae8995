/* pairs.cu — the CUDA backend's kernels over particle pairs: one kernel
 * per interaction kind segment (contact/kinds.h), one thread per pair
 * calling that kind's item (backend/items.h), exactly as the CPU loops of
 * backend/cpu/pairs.c; no physics here. The volume law and the composite
 * runs have files of their own (pairs_volume.cu, pairs_elements.cu): their
 * kernels are the largest by far, and apart they compile in parallel.
 *
 * Invariants: an item writes only its own pair's slots, so the order of
 * the threads cannot change a bit. The volume law and the composite runs
 * need an overlap workspace each (tens of KB): they run in batches of at
 * most ws_count pairs, thread t of a batch using workspace t (device
 * memory sized at upload: seed 000 §2.3's batches sized to free memory),
 * never a workspace on the thread's stack. A composite run is evaluated by
 * the thread of its first element pair (the others return). The
 * narrow-phase tallies are integer atomics (exact in any order) into the
 * device's counters, which read back adds to the world's.
 */
#include <stdio.h>

#include "backend/cuda/tally.h"

__global__ void sd_k_spheres(sd_step_view v, sd_pair_out o, size_t e0, size_t e1)
{
    size_t e = e0 + SD_CUDA_ITEM();
    if (e < e1)
        sd_item_spheres(&v, &o, e);
}

__global__ void sd_k_convex(sd_step_view v, sd_pair_out o, size_t e0, size_t e1, unsigned long long *tally)
{
    size_t e = e0 + SD_CUDA_ITEM();
    if (e >= e1)
        return;
    sd_item_convex(&v, &o, e);
    sd_k_tally3(&v, &o, e, tally);
}

__global__ void sd_k_convex2d(sd_step_view v, sd_pair_out o, size_t e0, size_t e1, unsigned long long *tally)
{
    size_t e = e0 + SD_CUDA_ITEM();
    if (e >= e1)
        return;
    sd_item_convex2d(&v, &o, e);
    if (o.supports[e] == 0)
        return; /* culled by the bounding circles */
    int a = sd_item_shape2d_kind(&v, o.i[e]), b = sd_item_shape2d_kind(&v, o.j[e]);
    if (a > b) {
        int x = a;
        a = b;
        b = x;
    }
    unsigned long long *y = tally + SD_CUDA_TALLY3 + ((size_t)a * SD_SHAPE2D_KIND_COUNT + (size_t)b) * 4;
    atomicAdd(&y[0], 1ull);
    atomicAdd(&y[1], (unsigned long long)o.iters[e]);
    atomicAdd(&y[2], (unsigned long long)o.supports[e]);
    atomicAdd(&y[3], (unsigned long long)(o.iters[e] ? o.supports[e] : 0));
}

extern "C" void sd_cuda_forces(sd_stage *s, sd_pair_kind kind)
{
    if (!sd_cuda_ok(s))
        return;
    sd_cuda_state *c = s->device;
    size_t e0 = c->pairs.kind_start[kind], e1 = c->pairs.kind_start[kind + 1];
    if (e1 <= e0)
        return;
    unsigned long long *tally = (unsigned long long *)c->tally.p;
    size_t nb = c->ws_count;
    const char *stage = "pair forces";
    if ((kind == SD_PAIR_POLY_VOLUME || kind == SD_PAIR_ELEMENTS) && nb == 0) {
        /* upload sizes the workspaces whenever such pairs exist */
        c->status = SD_ERR_INTERNAL;
        snprintf(c->message, sizeof c->message, "CUDA backend, pair forces: no overlap workspaces for %zu pairs",
                 e1 - e0);
        return;
    }
    switch (kind) {
    case SD_PAIR_SPHERES:
        SD_CUDA_LAUNCH(sd_k_spheres, sd_cuda_blocks(e1 - e0), SD_CUDA_BLOCK, c->stream, c->v, c->pairs, e0, e1);
        stage = "sphere pairs";
        break;
    case SD_PAIR_CONVEX:
        SD_CUDA_LAUNCH(sd_k_convex, sd_cuda_blocks(e1 - e0), SD_CUDA_BLOCK, c->stream, c->v, c->pairs, e0, e1,
                       tally);
        stage = "convex pairs";
        break;
    case SD_PAIR_POLY_VOLUME:
        stage = "polyhedron volume pairs";
        sd_cuda_forces_volume(c, e0, e1); /* pairs_volume.cu */
        break;
    case SD_PAIR_CONVEX2D:
        SD_CUDA_LAUNCH(sd_k_convex2d, sd_cuda_blocks(e1 - e0), SD_CUDA_BLOCK, c->stream, c->v, c->pairs, e0, e1,
                       tally);
        stage = "2D pairs";
        break;
    case SD_PAIR_ELEMENTS:
        stage = "composite element pairs";
        sd_cuda_forces_elements(c, e0, e1); /* pairs_elements.cu */
        break;
    case SD_PAIR_KIND_COUNT:
        return;
    }
    (void)sd_cuda_launched(c, stage);
}
