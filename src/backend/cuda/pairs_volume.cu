/* pairs_volume.cu — the CUDA backend's kernel of the POLY_VOLUME segment:
 * sharp polyhedra under a volume law (seed 000 eqs. 12-22), one thread per
 * pair calling sd_item_poly_volume (backend/items.h) as the CPU loop does.
 *
 * Invariant: each pair needs an overlap workspace (tens of KB): the
 * segment runs in batches of at most ws_count pairs, thread t of a batch
 * using workspace t of the device array sized at upload (seed 000 §2.3's
 * batches sized to free memory); batches on one stream run one after the
 * other, so a workspace is never shared by two live threads.
 */
#include "backend/cuda/tally.h"

__global__ void sd_k_poly_volume(sd_step_view v, sd_pair_out o, size_t e0, size_t e1, sd_overlap_workspace *ws,
                                 unsigned long long *tally)
{
    size_t t = SD_CUDA_ITEM(), e = e0 + t;
    if (e >= e1)
        return;
    sd_item_poly_volume(&v, &o, e, &ws[t]);
    sd_k_tally3(&v, &o, e, tally);
}

void sd_cuda_forces_volume(sd_cuda_state *c, size_t e0, size_t e1)
{
    sd_overlap_workspace *ws = (sd_overlap_workspace *)c->ws.p;
    unsigned long long *tally = (unsigned long long *)c->tally.p;
    size_t nb = c->ws_count;
    for (size_t b = e0; b < e1; b += nb) {
        size_t end = b + nb < e1 ? b + nb : e1;
        SD_CUDA_LAUNCH(sd_k_poly_volume, sd_cuda_blocks(end - b), SD_CUDA_BLOCK, c->stream, c->v, c->pairs, b, end,
                       ws, tally);
    }
}
