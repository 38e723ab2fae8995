/* pairs.c — memory of the pair lists, generated from their field lists
 * (broad/pairs.h): growth and release touch every field of
 * SD_PAIR_FIELDS / SD_WALL_PAIR_FIELDS, so a new field needs no code here.
 *
 * Invariant: every array of a list holds at least cap pairs (times its
 * slots per pair); the gather entries of the particle list hold 2 cap, of
 * the wall list cap.
 */
#include "broad/pairs.h"

#include <string.h>

#include "core/alloc.h"

static sd_status sd_pairs_grow(void **p, size_t need, size_t elem)
{
    void *q = sd_realloc(*p, need * elem);
    if (!q && need)
        return SD_ERR_MEMORY;
    *p = q;
    return SD_OK;
}

sd_status sd_pairs_reserve(sd_pair_list *l, size_t cap)
{
    if (cap <= l->cap)
        return SD_OK;
    cap = cap + cap / 2 + 16;
#define SD_X_GROW(type, name, per, role, doc)                                       \
    if (sd_pairs_grow((void **)&l->name, (per) * cap, sizeof *l->name) != SD_OK) \
        return SD_ERR_MEMORY;
    SD_PAIR_FIELDS(SD_X_GROW)
    if (sd_pairs_grow((void **)&l->gidx, 2 * cap, sizeof *l->gidx) != SD_OK)
        return SD_ERR_MEMORY;
    l->cap = cap;
    l->gidx_cap = 2 * cap;
    return SD_OK;
}

sd_status sd_pairs_reserve_walls(sd_wall_pair_list *l, size_t cap)
{
    if (cap <= l->cap)
        return SD_OK;
    cap = cap + cap / 2 + 16;
    SD_WALL_PAIR_FIELDS(SD_X_GROW)
#undef SD_X_GROW
    if (sd_pairs_grow((void **)&l->gidx, cap, sizeof *l->gidx) != SD_OK)
        return SD_ERR_MEMORY;
    l->cap = cap;
    return SD_OK;
}

void sd_pairs_free(sd_pair_list *l, sd_wall_pair_list *wl)
{
#define SD_X_FREE(type, name, per, role, doc) sd_free(l->name);
    SD_PAIR_FIELDS(SD_X_FREE)
    sd_free(l->gstart);
    sd_free(l->gidx);
    memset(l, 0, sizeof *l);
#undef SD_X_FREE
#define SD_X_FREE(type, name, per, role, doc) sd_free(wl->name);
    SD_WALL_PAIR_FIELDS(SD_X_FREE)
#undef SD_X_FREE
    sd_free(wl->gstart);
    sd_free(wl->gidx);
    sd_free(wl->tri);
    memset(wl, 0, sizeof *wl);
}
