/* canonical.c — the pair order of every run, serial, threaded or
 * decomposed (bins.h, sd_pairs_canonical).
 *
 * Why: the search's order follows storage (the cell sort of the particles a
 * rank holds, ghosts after the owned ones), so a particle's force sum, a
 * floating-point sum whose bits depend on its order, would change with the
 * rank count, and the serial run would differ from mpirun's (issue 29). Here the order is made from stable ids alone: each pair is
 * evaluated with the body of lower id as i (the pair items are not
 * symmetric to the bit: contact point, lever arms), and each owned
 * particle's contributions are summed in the order of its partners' ids.
 * A pair of an owned particle and another rank's ghost is then the same
 * computation, on the same copies of the same state, on both ranks, and
 * each rank gathers its own side.
 *
 * Composites: the bins write a run of element pairs with the elements of
 * the body stored first outer, so the run's order, in which its item sums
 * N_c and the centroid of the contact points (backend/items.h,
 * sd_item_elements), would follow storage too; each run is put in the
 * order of its keys (lower id's element outer, the other's inner). A run
 * stays where the bins put it, contiguous, its (i, j) the same for all its
 * pairs.
 */
#include <string.h>

#include "broad/bins.h"
#include "core/alloc.h"

/* The owned particle that gathers particle k's side, or n_owned or more
 * (SD_GHOST_REMOTE, SD_GHOST_REMOTE_IMAGE) for another rank's. */
static size_t sd_canon_owner(const sd_bins_input *in, size_t k)
{
    return k < in->n_owned ? k : in->ghost_owner[k - in->n_owned];
}

/* Gather entry g = 2 e + side: is it before h? By (partner id, own
 * sub-index, partner sub-index); i has the lower id, so side 0's partner is
 * id_hi. */
static int sd_canon_before(const sd_pair_list *l, uint32_t g, uint32_t h)
{
    const sd_pair_key *a = &l->key[g >> 1], *b = &l->key[h >> 1];
    uint64_t pa = (g & 1) ? a->id_lo : a->id_hi, pb = (h & 1) ? b->id_lo : b->id_hi;
    if (pa != pb)
        return pa < pb;
    uint32_t oa = (g & 1) ? a->sub_hi : a->sub_lo, ob = (h & 1) ? b->sub_hi : b->sub_lo;
    if (oa != ob)
        return oa < ob;
    uint32_t qa = (g & 1) ? a->sub_lo : a->sub_hi, qb = (h & 1) ? b->sub_lo : b->sub_hi;
    return qa < qb;
}

/* Element pair e's sub-indices before f's, in key order (sub_lo, sub_hi). */
static int sd_canon_elem_before(const sd_pair_list *l, size_t e, size_t f)
{
    const sd_pair_key *a = &l->key[e], *b = &l->key[f];
    return a->sub_lo != b->sub_lo ? a->sub_lo < b->sub_lo : a->sub_hi < b->sub_hi;
}

/* Swaps pairs e and f in every field (the list's rows, SD_PAIR_FIELDS). */
static void sd_canon_swap(sd_pair_list *l, size_t e, size_t f)
{
#define SD_X_SWAP(type, name, per, role, doc)                      \
    for (size_t s = 0; s < (size_t)(per); ++s) {                 \
        type t = l->name[(size_t)(per) * e + s];                 \
        l->name[(size_t)(per) * e + s] = l->name[(size_t)(per) * f + s]; \
        l->name[(size_t)(per) * f + s] = t;                       \
    }
    SD_PAIR_FIELDS(SD_X_SWAP)
#undef SD_X_SWAP
}

/* Each run of element pairs (one composite pair: the same i and j) in key
 * order: an insertion sort of whole rows (a run holds a few to a few tens
 * of element pairs, often in order already). */
static void sd_canon_element_runs(sd_pair_list *l)
{
    size_t e0 = l->kind_start[SD_PAIR_ELEMENTS], e1 = l->kind_start[SD_PAIR_ELEMENTS + 1];
    for (size_t r = e0; r < e1;) {
        size_t end = r + 1;
        while (end < e1 && l->i[end] == l->i[r] && l->j[end] == l->j[r])
            ++end;
        for (size_t a = r + 1; a < end; ++a)
            for (size_t b = a; b > r && sd_canon_elem_before(l, b, b - 1); --b)
                sd_canon_swap(l, b, b - 1);
        r = end;
    }
}

sd_status sd_pairs_canonical(const sd_bins_input *in, sd_pair_list *l)
{
    size_t no = in->n_owned, total = l->n;
    for (size_t e = 0; e < total; ++e) {
        if (l->flip[e]) { /* i has the higher id: swap the bodies (the key and ds are by id already) */
            uint32_t t = l->i[e];
            l->i[e] = l->j[e];
            l->j[e] = t;
            l->flip[e] = 0;
        }
    }
    sd_canon_element_runs(l);
    uint32_t *cur = sd_malloc((no ? no : 1) * sizeof *cur);
    if (!cur)
        return SD_ERR_MEMORY;
    memset(l->gstart, 0, (no + 1) * sizeof *l->gstart);
    for (size_t e = 0; e < total; ++e)
        for (int side = 0; side < 2; ++side) {
            size_t o = sd_canon_owner(in, side ? l->j[e] : l->i[e]);
            if (o < no)
                l->gstart[o + 1]++;
        }
    for (size_t k = 0; k < no; ++k)
        l->gstart[k + 1] += l->gstart[k];
    memcpy(cur, l->gstart, no * sizeof *cur);
    for (size_t e = 0; e < total; ++e)
        for (int side = 0; side < 2; ++side) {
            size_t o = sd_canon_owner(in, side ? l->j[e] : l->i[e]);
            if (o < no)
                l->gidx[cur[o]++] = (uint32_t)(2 * e + (size_t)side);
        }
    sd_free(cur);
    /* each segment by partner id (a few entries for spheres: insertion sort) */
    SD_PRAGMA(omp parallel for schedule(static) num_threads(in->threads) if (in->parallel))
    for (size_t k = 0; k < no; ++k) {
        uint32_t *g = l->gidx + l->gstart[k];
        size_t m = l->gstart[k + 1] - l->gstart[k];
        for (size_t a = 1; a < m; ++a) {
            uint32_t v = g[a];
            size_t b = a;
            for (; b > 0 && sd_canon_before(l, v, g[b - 1]); --b)
                g[b] = g[b - 1];
            g[b] = v;
        }
    }
    return SD_OK;
}
