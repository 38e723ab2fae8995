/* pairs_elements.cu — the CUDA backend's kernel of the ELEMENTS segment:
 * composites (seed 004 §2.5-2.6), one thread per run of the element pairs
 * of one composite pair, calling sd_item_elements (backend/items.h) as the
 * CPU loop does: the run's contacts and their multi-contact combination in
 * one pass, no second kernel and no atomics on forces.
 *
 * Invariant: the thread of a run's first pair evaluates the whole run
 * (the other threads return), with overlap workspace t of its batch
 * (pairs_volume.cu's batches); a run may end past its batch, never past
 * the segment.
 */
#include "backend/cuda/tally.h"

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

void sd_cuda_forces_elements(sd_cuda_state *c, size_t e0, size_t e1)
{
    sd_overlap_workspace *ws = (sd_overlap_workspace *)c->ws.p;
    unsigned long long *tally = (unsigned long long *)c->tally.p;
    size_t nb = c->ws_count;
    for (size_t b = e0; b < e1; b += nb) {
        size_t end = b + nb < e1 ? b + nb : e1;
        SD_CUDA_LAUNCH(sd_k_elements, sd_cuda_blocks(end - b), SD_CUDA_BLOCK, c->stream, c->v, c->pairs, e0, e1, b,
                       end, ws, tally);
    }
}
