/* pairs.cu — the CUDA backend's kernels over particle pairs: one kernel
 * per interaction kind segment (contact/kinds.h), one thread per pair
 * calling that kind's item (backend/items.h), exactly as the CPU loops of
 * backend/cpu/pairs.c; no physics here.
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

#include "backend/cuda/state.h"
#include "backend/items.h"

/* 3D tallies of pair e (the CPU's sd_tally3_add): evaluations, iterations
 * and support calls per sorted pair of shape kinds. */
__device__ static void sd_k_tally3(const sd_step_view *v, const sd_pair_out *o, size_t e, unsigned long long *tally)
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

__global__ void sd_k_poly_volume(sd_step_view v, sd_pair_out o, size_t e0, size_t e1, sd_overlap_workspace *ws,
                                 unsigned long long *tally)
{
    size_t t = SD_CUDA_ITEM(), e = e0 + t;
    if (e >= e1)
        return;
    sd_item_poly_volume(&v, &o, e, &ws[t]);
    sd_k_tally3(&v, &o, e, tally);
}

/* Pairs [e0, e1) of a batch of the ELEMENTS segment [s0, s1): the thread of
 * a run's first pair evaluates the run, which may end past e1. */
__global__ void sd_k_elements(sd_step_view v, sd_pair_out o, size_t s0, size_t s1, size_t e0, size_t e1,
                              sd_overlap_workspace *ws, unsigned long long *tally)
{
    size_t t = SD_CUDA_ITEM(), e = e0 + t;
    if (e >= e1 || !sd_item_elements_starts(&o, s0, e))
        return;
    size_t end = e + 1;
    while (end < s1 && !sd_item_elements_starts(&o, s0, end))
        ++end;
    (void)sd_item_elements(&v, &o, e, end, &ws[t]);
    for (size_t k = e; k < end; ++k)
        sd_k_tally3(&v, &o, k, tally);
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
    sd_overlap_workspace *ws = (sd_overlap_workspace *)c->ws.p;
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
        for (size_t b = e0; b < e1 && nb > 0; b += nb) {
            size_t end = b + nb < e1 ? b + nb : e1;
            SD_CUDA_LAUNCH(sd_k_poly_volume, sd_cuda_blocks(end - b), SD_CUDA_BLOCK, c->stream, c->v, c->pairs, b,
                           end, ws, tally);
        }
        break;
    case SD_PAIR_CONVEX2D:
        SD_CUDA_LAUNCH(sd_k_convex2d, sd_cuda_blocks(e1 - e0), SD_CUDA_BLOCK, c->stream, c->v, c->pairs, e0, e1,
                       tally);
        stage = "2D pairs";
        break;
    case SD_PAIR_ELEMENTS:
        stage = "composite element pairs";
        for (size_t b = e0; b < e1 && nb > 0; b += nb) {
            size_t end = b + nb < e1 ? b + nb : e1;
            SD_CUDA_LAUNCH(sd_k_elements, sd_cuda_blocks(end - b), SD_CUDA_BLOCK, c->stream, c->v, c->pairs, e0, e1,
                           b, end, ws, tally);
        }
        break;
    case SD_PAIR_KIND_COUNT:
        return;
    }
    (void)sd_cuda_check(c, cudaGetLastError(), stage, "the kernel launch");
}
