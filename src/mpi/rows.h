/* rows.h — a pair or a wall pair as one row of bytes (every field of
 * SD_PAIR_FIELDS / SD_WALL_PAIR_FIELDS in turn, (per) values each), for
 * the files of the decomposition that move pairs between ranks: the view
 * on rank 0 (view.c) and the collective checkpoint (ckpt.c). A field added
 * to a list travels without a change here.
 *
 * SD_ROWS_CODEC(prefix, list_type, FIELDS) defines, for one field list:
 *   size_t prefix_size(void)                          bytes of a row
 *   unsigned char *prefix_pack(l, e, b)               row e of l into b
 *   void prefix_unpack(l, e, b)                       b into row e of l
 *   size_t prefix_key_offset(void)                    where the key lies in a row
 */
#ifndef SD_MPI_ROWS_H
#define SD_MPI_ROWS_H

#include <stdlib.h>
#include <string.h>

#include "broad/pairs.h"

#define SD_ROWS_X_SIZE(type, name, per, ...) s += (per) * sizeof(type);
#define SD_ROWS_X_PACK(type, name, per, ...)                     \
    memcpy(b, &l->name[(per) * e], (per) * sizeof(type)); \
    b += (per) * sizeof(type);
#define SD_ROWS_X_UNPACK(type, name, per, ...)                   \
    memcpy(&l->name[(per) * e], b, (per) * sizeof(type)); \
    b += (per) * sizeof(type);
#define SD_ROWS_X_AT(type, name, per, ...)                        \
    if ((const void *)&probe.name == (const void *)&probe.key) \
        at = s;                                                \
    s += (per) * sizeof(type);

#define SD_ROWS_CODEC(prefix, list_type, FIELDS)                                          \
    static inline size_t prefix##_size(void)                                              \
    {                                                                                     \
        size_t s = 0;                                                                     \
        FIELDS(SD_ROWS_X_SIZE)                                                            \
        return s;                                                                         \
    }                                                                                     \
    static inline unsigned char *prefix##_pack(const list_type *l, size_t e, unsigned char *b) \
    {                                                                                     \
        FIELDS(SD_ROWS_X_PACK)                                                            \
        return b;                                                                         \
    }                                                                                     \
    static inline void prefix##_unpack(list_type *l, size_t e, const unsigned char *b)    \
    {                                                                                     \
        FIELDS(SD_ROWS_X_UNPACK)                                                          \
    }                                                                                     \
    static inline size_t prefix##_key_offset(void)                                        \
    {                                                                                     \
        size_t s = 0, at = 0;                                                             \
        list_type probe;                                                                  \
        FIELDS(SD_ROWS_X_AT)                                                              \
        return at;                                                                        \
    }

SD_ROWS_CODEC(sd_rows_pair, sd_pair_list, SD_PAIR_FIELDS)
SD_ROWS_CODEC(sd_rows_wpair, sd_wall_pair_list, SD_WALL_PAIR_FIELDS)

/* A received row and what it sorts by, in turn (k[0] first). */
typedef struct sd_rows_rec {
    uint64_t k[4];
    const unsigned char *row;
} sd_rows_rec;

static inline int sd_rows_rec_cmp(const void *x, const void *y)
{
    const sd_rows_rec *p = x, *q = y;
    for (int t = 0; t < 4; ++t)
        if (p->k[t] != q->k[t])
            return p->k[t] < q->k[t] ? -1 : 1;
    return 0;
}

static inline int sd_rows_id_cmp(const void *x, const void *y)
{
    uint64_t p = *(const uint64_t *)x, q = *(const uint64_t *)y;
    return p < q ? -1 : (p > q ? 1 : 0);
}

/* The index of stable id `id` in ids (n of them, sorted); 0 when absent
 * (every body of a pair is some rank's particle: the id is there). */
static inline size_t sd_rows_index(const uint64_t *ids, size_t n, uint64_t id)
{
    const uint64_t *f = n ? bsearch(&id, ids, n, sizeof *ids, sd_rows_id_cmp) : NULL;
    return f ? (size_t)(f - ids) : 0;
}

/* The kind segment row e lies in (kind_start: kinds + 1 starts). */
static inline int32_t sd_rows_kind_of(const size_t *kind_start, int kinds, size_t e)
{
    int32_t k = 0;
    while (k + 1 < kinds && e >= kind_start[k + 1])
        ++k;
    return k;
}

/* What a row sorts by, in turn (k[0] first), in the view and in a
 * checkpoint: a pair by (kind, key: id_lo, id_hi, sub_lo, sub_hi), a wall
 * pair by (kind, wall, id, sub, elem): the kind in the upper half of k[0],
 * the wall in the lower. */
static inline void sd_rows_pair_order(int32_t kind, const unsigned char *row, uint64_t k[4])
{
    sd_pair_key key;
    memcpy(&key, row + sd_rows_pair_key_offset(), sizeof key);
    k[0] = (uint64_t)kind;
    k[1] = key.id_lo;
    k[2] = key.id_hi;
    k[3] = (uint64_t)key.sub_lo << 32 | key.sub_hi;
}

static inline void sd_rows_wpair_order(int32_t kind, const unsigned char *row, uint64_t k[4])
{
    sd_wall_pair_key key;
    memcpy(&key, row + sd_rows_wpair_key_offset(), sizeof key);
    k[0] = (uint64_t)kind << 32 | key.wall;
    k[1] = key.id;
    k[2] = key.sub;
    k[3] = key.elem;
}

#endif
