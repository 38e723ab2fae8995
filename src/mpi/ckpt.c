/* ckpt.c — a checkpoint written by every rank into one HDF5 file (mpi.h:
 * sd_mpi_checkpoint_write), the same file as rank 0 writes from the view
 * (view.c, io/checkpoint.c): the same datasets, rows and attributes, so a
 * restart on any rank count, or in the serial program, reads either.
 *
 * The datasets are the view's snapshot (world/snapshot.c: the one list),
 * taken on rank 0; their names, types and sizes are broadcast. The small
 * ones (world/, walls/, meshes/, scene/, ghosts/, the counts, the kind
 * segments, the gather lists) rank 0 writes alone. The rows of the
 * particles, pairs and wall pairs, the bulk of the file, go from the ranks
 * that hold them to the rank whose block of the file's order they fall in
 * (one MPI_Alltoallv per kind of row):
 *   particles: by stable id; rank r holds rows [r N / R, (r + 1) N / R);
 *   pairs: by (kind, key), to the rank whose particle block holds the
 *          pair's lower id: per kind a contiguous run of rows, the ranks'
 *          runs in rank order;
 *   wall pairs: by (kind, wall, key), to the rank whose particle block
 *          holds the particle: a run per (kind, wall) segment.
 * Each rank rewrites the indices as the view does (a pair's i and j, a
 * wall pair's i: the bodies' rows in the file; flip 0; no mesh triangles)
 * and writes its runs as hyperslabs, collectively through MPI-IO.
 *
 * The file's checksum (FNV-1a over every dataset in name order) is
 * sequential: each dataset's runs are hashed rank after rank, the running
 * value passed along (one message per rank and run of rows).
 *
 * Cost: every rank holds every stable id (8 bytes a particle, as a re-cut
 * does) to find each body's row; rank 0 makes the view's snapshot for the
 * small datasets (the view is there anyway: the frames read it).
 */
#include <mpi.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/checkpoint.h"
#include "mpi/mpi.h"
#include "mpi/rows.h"
#include "world/snapshot.h"
#include "world/world.h"

enum { SD_CK_PARTICLES, SD_CK_PAIRS, SD_CK_WPAIRS, SD_CK_GROUPS, SD_CK_MAX_FIELDS = 64 };
enum { SD_CK_TAG = 0x5dc }; /* the checksum's messages */

static const char *const sd_ck_prefix[SD_CK_GROUPS] = {"particles/", "pairs/", "wall_pairs/"};

/* A field of a row: its name, where it lies in the row and its bytes
 * (those of its dataset's row). */
typedef struct sd_ck_field {
    const char *name;
    size_t at, bytes;
} sd_ck_field;

#define SD_CK_X_COUNT(...) +1
_Static_assert(0 SD_PARTICLE_FIELDS(SD_CK_X_COUNT) <= SD_CK_MAX_FIELDS, "particle fields");
_Static_assert(0 SD_PAIR_FIELDS(SD_CK_X_COUNT) <= SD_CK_MAX_FIELDS, "pair fields");
_Static_assert(0 SD_WALL_PAIR_FIELDS(SD_CK_X_COUNT) <= SD_CK_MAX_FIELDS, "wall pair fields");
#undef SD_CK_X_COUNT

/* The fields of a group's rows, in the order the rows are packed
 * (sd_mpi_row_pack, mpi/rows.h); returns how many. */
static size_t sd_ck_fields(int group, sd_ck_field *out)
{
    size_t n = 0, at = 0;
#define SD_CK_X_P(type, name, ...)                         \
    out[n++] = (sd_ck_field){#name, at, sizeof(type)}; \
    at += sizeof(type);
#define SD_CK_X_L(type, name, per, ...)                            \
    out[n++] = (sd_ck_field){#name, at, (per) * sizeof(type)}; \
    at += (per) * sizeof(type);
    if (group == SD_CK_PARTICLES) {
        SD_PARTICLE_FIELDS(SD_CK_X_P)
    } else if (group == SD_CK_PAIRS) {
        SD_PAIR_FIELDS(SD_CK_X_L)
    } else {
        SD_WALL_PAIR_FIELDS(SD_CK_X_L)
    }
#undef SD_CK_X_P
#undef SD_CK_X_L
    return n;
}

static size_t sd_ck_at(const sd_ck_field *f, size_t n, const char *name)
{
    for (size_t k = 0; k < n; ++k)
        if (!strcmp(f[k].name, name))
            return f[k].at;
    return 0;
}

/* The group and field of a dataset of rows, or -1 for a small one. */
static int sd_ck_row_item(const char *name, const sd_ck_field (*fields)[SD_CK_MAX_FIELDS],
                          const size_t *nfields, size_t *field)
{
    for (int g = 0; g < SD_CK_GROUPS; ++g) {
        size_t pl = strlen(sd_ck_prefix[g]);
        if (strncmp(name, sd_ck_prefix[g], pl) != 0)
            continue;
        for (size_t k = 0; k < nfields[g]; ++k)
            if (!strcmp(name + pl, fields[g][k].name)) {
                *field = k;
                return g;
            }
    }
    return -1;
}

/* This rank's rows of a group, in the file's order, and where they go. */
typedef struct sd_ck_block {
    unsigned char *rows; /* n rows of rs bytes */
    size_t n, rs;
    size_t segs;         /* the group's segments (kinds, kind x wall; 1 for the particles) */
    uint64_t *count;     /* every rank's rows per segment: count[r * segs + j] */
    size_t nseg, *seg;   /* this rank's runs: (first row in the file, rows) */
} sd_ck_block;

static void sd_ck_block_free(sd_ck_block *b)
{
    sd_free(b->rows);
    sd_free(b->count);
    sd_free(b->seg);
    memset(b, 0, sizeof *b);
}

static void *sd_ck_alloc(size_t bytes) { return sd_malloc(bytes ? bytes : 1); }

/* Every rank: is every rank fine? */
static int sd_ck_all(int ok)
{
    int all = 0;
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
    return all;
}

/* The row of stable id `id` in the file (ids sorted). */
static uint64_t sd_ck_pos(const uint64_t *ids, size_t n, uint64_t id) { return (uint64_t)sd_rows_index(ids, n, id); }

/* The first row of rank r's block of n particles, and the rank whose block
 * holds row pos: blocks [floor(r n / R), floor((r + 1) n / R)). */
static uint64_t sd_ck_block_start(uint64_t n, int r, int size) { return n * (uint64_t)r / (uint64_t)size; }

static int sd_ck_block_of(uint64_t n, uint64_t pos, int size)
{
    return (int)(((pos + 1) * (uint64_t)size - 1) / n);
}

/* Records of rs bytes to their ranks (dest[k]); *out gets the records this
 * rank receives, in rank order (*nout of them). Collective; 0 on any
 * rank's failure (no memory, more than 2 GiB to one rank). */
static int sd_ck_exchange(const unsigned char *rec, size_t n, size_t rs, const int *dest, int size,
                          unsigned char **out, size_t *nout)
{
    *out = NULL;
    *nout = 0;
    int *sc = sd_calloc(4 * (size_t)size, sizeof *sc), *sd = sc + size, *rc = sc + 2 * size, *rd = sc + 3 * size;
    size_t *fill = sd_calloc((size_t)size, sizeof *fill);
    unsigned char *send = sd_ck_alloc(n * rs);
    int ok = sc && fill && send;
    if (ok) {
        size_t *cnt = fill;
        for (size_t k = 0; k < n; ++k)
            cnt[dest[k]]++;
        size_t at = 0;
        for (int r = 0; r < size; ++r) {
            ok = ok && cnt[r] * rs <= INT32_MAX && at * rs <= INT32_MAX;
            sc[r] = (int)(cnt[r] * rs);
            sd[r] = (int)(at * rs);
            at += cnt[r];
            cnt[r] = (size_t)sd[r] / (rs ? rs : 1); /* now the next free record of rank r */
        }
        for (size_t k = 0; ok && k < n; ++k)
            memcpy(send + rs * cnt[dest[k]]++, rec + rs * k, rs);
    }
    if (!sd_ck_all(ok)) {
        sd_free(sc);
        sd_free(fill);
        sd_free(send);
        return 0;
    }
    MPI_Alltoall(sc, 1, MPI_INT, rc, 1, MPI_INT, MPI_COMM_WORLD);
    size_t total = 0;
    for (int r = 0; r < size; ++r) {
        rd[r] = (int)total;
        total += (size_t)rc[r];
    }
    unsigned char *recv = total <= INT32_MAX ? sd_ck_alloc(total) : NULL;
    if (!sd_ck_all(recv != NULL)) {
        sd_free(recv);
        sd_free(sc);
        sd_free(fill);
        sd_free(send);
        return 0;
    }
    MPI_Alltoallv(send, sc, sd, MPI_BYTE, recv, rc, rd, MPI_BYTE, MPI_COMM_WORLD);
    sd_free(sc);
    sd_free(fill);
    sd_free(send);
    *out = recv;
    *nout = rs ? total / rs : 0;
    return 1;
}

/* sd_ck_exchange when every rank is ok so far; rec and dest freed. */
static int sd_ck_send(int ok, unsigned char *rec, size_t n, size_t rs, int *dest, int size, unsigned char **out,
                      size_t *nout)
{
    ok = sd_ck_all(ok) && sd_ck_exchange(rec, n, rs, dest, size, out, nout);
    sd_free(rec);
    sd_free(dest);
    return ok;
}

/* The runs of a block from every rank's counts per segment: segment j's
 * rows of rank r follow the whole segments before j and the other ranks'
 * rows of j before r. Collective (the counts are gathered); 0 out of
 * memory on any rank. */
static int sd_ck_runs(sd_ck_block *b, const uint64_t *mine, int rank, int size)
{
    b->count = sd_malloc((size_t)size * b->segs * sizeof *b->count);
    b->seg = sd_malloc(2 * (b->segs ? b->segs : 1) * sizeof *b->seg);
    if (!sd_ck_all(b->count && b->seg))
        return 0;
    MPI_Allgather(mine, (int)b->segs, MPI_UINT64_T, b->count, (int)b->segs, MPI_UINT64_T, MPI_COMM_WORLD);
    uint64_t before = 0;
    b->nseg = 0;
    for (size_t j = 0; j < b->segs; ++j) {
        uint64_t start = before;
        for (int r = 0; r < size; ++r) {
            if (r == rank && b->count[(size_t)r * b->segs + j] > 0) {
                b->seg[2 * b->nseg] = (size_t)start;
                b->seg[2 * b->nseg + 1] = (size_t)b->count[(size_t)r * b->segs + j];
                b->nseg++;
            }
            start += b->count[(size_t)r * b->segs + j];
        }
        before = start;
    }
    return 1;
}

/* This rank's block of particles: its owned particles' rows to the ranks
 * whose blocks hold them, placed by stable id. */
static int sd_ck_particles(const sd_world *w, const uint64_t *ids, size_t n_all, size_t id_at, int rank, int size,
                           sd_ck_block *b)
{
    size_t n = w->p.n, rs = sd_mpi_row_size();
    unsigned char *rec = sd_ck_alloc(n * rs), *got = NULL;
    int *dest = sd_malloc((n ? n : 1) * sizeof *dest);
    int ok = rec && dest;
    for (size_t k = 0; ok && k < n; ++k) {
        sd_mpi_row_pack(&w->p, k, rec + k * rs);
        dest[k] = sd_ck_block_of(n_all, sd_ck_pos(ids, n_all, w->p.id[k]), size);
    }
    size_t ng = 0;
    if (!sd_ck_send(ok, rec, n, rs, dest, size, &got, &ng))
        return 0;
    uint64_t start = sd_ck_block_start(n_all, rank, size);
    b->rs = rs;
    b->n = ng;
    b->rows = sd_ck_alloc(ng * rs);
    b->segs = 1;
    ok = b->rows != NULL;
    for (size_t k = 0; ok && k < ng; ++k) {
        uint64_t id;
        memcpy(&id, got + k * rs + id_at, sizeof id);
        uint64_t at = sd_ck_pos(ids, n_all, id) - start;
        ok = at < ng;
        if (ok)
            memcpy(b->rows + at * rs, got + k * rs, rs);
    }
    sd_free(got);
    uint64_t mine = ng;
    return sd_ck_all(ok) && sd_ck_runs(b, &mine, rank, size);
}

/* This rank's pairs (wall: 0) or wall pairs (1) in the file's order: each
 * sent to the rank whose particle block holds its lower id (its particle),
 * sorted there by (kind, key), its indices made the file's. */
static int sd_ck_pairs(const sd_world *w, int wall, const uint64_t *ids, size_t n_all, const sd_ck_field *f,
                       size_t nf, int rank, int size, sd_ck_block *b)
{
    const sd_pair_list *l = &w->pairs;
    const sd_wall_pair_list *wl = &w->wpairs;
    size_t n_own = w->p.n, ln = wall ? wl->n : l->n;
    size_t rs = sizeof(int32_t) + (wall ? sd_rows_wpair_size() : sd_rows_pair_size());
    unsigned char *rec = sd_ck_alloc(ln * rs), *got = NULL;
    int *dest = sd_malloc((ln ? ln : 1) * sizeof *dest);
    int ok = rec && dest;
    size_t n = 0;
    for (size_t e = 0; ok && e < ln; ++e) {
        unsigned char *r = rec + n * rs;
        int32_t kind;
        uint64_t id;
        if (wall) {
            kind = sd_rows_kind_of(wl->kind_start, SD_WALL_PAIR_KIND_COUNT, e);
            sd_rows_wpair_pack(wl, e, r + sizeof kind);
            id = wl->key[e].id;
        } else {
            if (l->i[e] >= n_own)
                continue; /* the lower id is another rank's ghost here: its owner sends the pair (as view.c) */
            kind = sd_rows_kind_of(l->kind_start, SD_PAIR_KIND_COUNT, e);
            sd_rows_pair_pack(l, e, r + sizeof kind);
            id = l->key[e].id_lo;
        }
        memcpy(r, &kind, sizeof kind);
        dest[n++] = n_all ? sd_ck_block_of(n_all, sd_ck_pos(ids, n_all, id), size) : 0;
    }
    size_t ng = 0;
    if (!sd_ck_send(ok, rec, n, rs, dest, size, &got, &ng))
        return 0;
    size_t walls = w->wall_count ? w->wall_count : 1;
    b->segs = wall ? (size_t)SD_WALL_PAIR_KIND_COUNT * walls : (size_t)SD_PAIR_KIND_COUNT;
    b->rs = rs - sizeof(int32_t);
    b->n = ng;
    sd_rows_rec *q = sd_malloc((ng ? ng : 1) * sizeof *q);
    uint64_t *mine = sd_calloc(b->segs, sizeof *mine);
    b->rows = sd_ck_alloc(ng * b->rs);
    ok = q && mine && b->rows;
    for (size_t k = 0; ok && k < ng; ++k) {
        int32_t kind;
        memcpy(&kind, got + k * rs, sizeof kind);
        q[k].row = got + k * rs + sizeof kind;
        if (wall)
            sd_rows_wpair_order(kind, q[k].row, q[k].k);
        else
            sd_rows_pair_order(kind, q[k].row, q[k].k);
    }
    if (ok)
        qsort(q, ng, sizeof *q, sd_rows_rec_cmp);
    /* the view's indices: the bodies' rows in the file (a periodic image's
     * partner is its owner), flip 0, no mesh triangles */
    size_t i_at = sd_ck_at(f, nf, "i"), key_at = sd_ck_at(f, nf, "key");
    for (size_t k = 0; ok && k < ng; ++k) {
        unsigned char *r = b->rows + k * b->rs;
        memcpy(r, q[k].row, b->rs);
        uint32_t i, j;
        if (wall) {
            sd_wall_pair_key key;
            memcpy(&key, r + key_at, sizeof key);
            i = (uint32_t)sd_ck_pos(ids, n_all, key.id);
            uint32_t zero = 0;
            memcpy(r + sd_ck_at(f, nf, "tstart"), &zero, sizeof zero);
            memcpy(r + sd_ck_at(f, nf, "tcount"), &zero, sizeof zero);
            mine[(q[k].k[0] >> 32) * walls + (q[k].k[0] & 0xffffffffu)]++;
        } else {
            sd_pair_key key;
            memcpy(&key, r + key_at, sizeof key);
            i = (uint32_t)sd_ck_pos(ids, n_all, key.id_lo);
            j = (uint32_t)sd_ck_pos(ids, n_all, key.id_hi);
            memcpy(r + sd_ck_at(f, nf, "j"), &j, sizeof j);
            uint8_t flip = 0;
            memcpy(r + sd_ck_at(f, nf, "flip"), &flip, sizeof flip);
            mine[q[k].k[0]]++;
        }
        memcpy(r + i_at, &i, sizeof i);
    }
    sd_free(q);
    sd_free(got);
    ok = sd_ck_all(ok) && sd_ck_runs(b, mine, rank, size);
    sd_free(mine);
    return ok;
}

/* The snapshot's header and its items' names, types and sizes, as rank 0
 * lists them, on every rank. */
typedef struct sd_ck_head {
    uint32_t version;
    int32_t dimension;
    uint64_t scene_hash, n;
    int64_t step;
    double time;
    char solver[16], writer[32];
} sd_ck_head;

typedef struct sd_ck_item_head {
    char name[64];
    int32_t type;
    uint64_t comps, count;
} sd_ck_item_head;

/* s: every item; rank 0's small ones with their rows (the view's), the
 * rest empty; rows[k]: item k's rows in the file. */
static int sd_ck_list(const sd_world *g, int rank, sd_snapshot *s, size_t **rows, sd_error *err)
{
    sd_snapshot full;
    sd_snapshot_init(&full);
    int ok = rank != 0 || sd_world_snapshot(g, &full, err) == SD_OK;
    if (!sd_ck_all(ok)) {
        sd_snapshot_free(&full);
        return 0;
    }
    sd_ck_head h;
    memset(&h, 0, sizeof h);
    if (rank == 0) {
        h = (sd_ck_head){full.version, full.dimension, full.scene_hash, full.n, full.step, full.time, "", ""};
        memcpy(h.solver, full.solver, sizeof h.solver);
        memcpy(h.writer, full.writer, sizeof h.writer);
    }
    MPI_Bcast(&h, (int)sizeof h, MPI_BYTE, 0, MPI_COMM_WORLD);
    sd_ck_item_head *ih = sd_calloc(h.n ? h.n : 1, sizeof *ih);
    *rows = sd_malloc((h.n ? h.n : 1) * sizeof **rows);
    ok = ih && *rows;
    for (size_t k = 0; ok && rank == 0 && k < h.n; ++k) {
        memcpy(ih[k].name, full.items[k].name, sizeof ih[k].name);
        ih[k].type = (int32_t)full.items[k].type;
        ih[k].comps = full.items[k].comps;
        ih[k].count = full.items[k].count;
    }
    if (sd_ck_all(ok))
        MPI_Bcast(ih, (int)(h.n * sizeof *ih), MPI_BYTE, 0, MPI_COMM_WORLD);
    else
        ok = 0;
    s->version = h.version;
    s->scene_hash = h.scene_hash;
    s->step = (long)h.step;
    s->time = h.time;
    s->dimension = h.dimension;
    memcpy(s->solver, h.solver, sizeof s->solver);
    memcpy(s->writer, h.writer, sizeof s->writer);
    /* rank 0 keeps the small items' rows (every item's, until the rows
     * of the large ones replace them); the others only their shapes */
    for (size_t k = 0; ok && k < h.n; ++k) {
        (*rows)[k] = (size_t)ih[k].count;
        sd_snap_item *it = sd_snapshot_add(s, ih[k].name, (sd_state_type)ih[k].type, (size_t)ih[k].comps, 0, NULL);
        ok = it != NULL;
        if (ok && rank == 0) { /* taken over, not copied */
            sd_free(it->data);
            it->data = full.items[k].data;
            it->count = full.items[k].count;
            full.items[k].data = NULL;
        }
    }
    sd_free(ih);
    sd_snapshot_free(&full);
    if (!sd_ck_all(ok)) {
        sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory listing the checkpoint's datasets");
        return 0;
    }
    return 1;
}

/* The running FNV-1a through every rank's bytes in rank order: rank 0
 * starts from h; the value is rank 0's on return. */
static uint64_t sd_ck_chain(uint64_t h, const void *b, size_t n, int rank, int size)
{
    if (rank > 0)
        MPI_Recv(&h, 1, MPI_UINT64_T, rank - 1, SD_CK_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    h = sd_fnv1a(h, b, n);
    if (size > 1)
        MPI_Send(&h, 1, MPI_UINT64_T, (rank + 1) % size, SD_CK_TAG, MPI_COMM_WORLD);
    if (rank == 0 && size > 1)
        MPI_Recv(&h, 1, MPI_UINT64_T, size - 1, SD_CK_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return h;
}

/* sd_snapshot_checksum of the file's items, from every rank's runs. */
static uint64_t sd_ck_checksum(const sd_snapshot *s, const size_t *rows, const int *group,
                               const sd_ck_block *blk, int rank, int size)
{
    uint64_t h = SD_FNV_BASIS;
    for (size_t k = 0; k < s->n; ++k) {
        const sd_snap_item *it = &s->items[k];
        size_t rb = it->comps * sd_state_type_size(it->type);
        if (rank == 0) {
            uint64_t head[3] = {(uint64_t)it->type, (uint64_t)it->comps, (uint64_t)rows[k]};
            h = sd_fnv1a(h, it->name, strlen(it->name) + 1);
            h = sd_fnv1a(h, head, sizeof head);
            if (group[k] < 0)
                h = sd_fnv1a(h, it->data, rows[k] * rb);
        }
        if (group[k] < 0)
            continue;
        const sd_ck_block *b = &blk[group[k]];
        size_t mine = 0; /* this rank's rows before segment j */
        for (size_t j = 0; j < b->segs; ++j) {
            uint64_t total = 0;
            for (int r = 0; r < size; ++r)
                total += b->count[(size_t)r * b->segs + j];
            size_t c = (size_t)b->count[(size_t)rank * b->segs + j];
            if (total > 0)
                h = sd_ck_chain(h, (const unsigned char *)it->data + mine * rb, c * rb, rank, size);
            mine += c;
        }
    }
    MPI_Bcast(&h, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    return h;
}

sd_status sd_mpi_checkpoint_write(const sd_mpi *m, const sd_world *w, const sd_world *g, const char *path,
                                  sd_error *err)
{
    int rank = sd_mpi_rank(m), size = sd_mpi_size(m);
    sd_snapshot s;
    sd_snapshot_init(&s);
    sd_ck_block blk[SD_CK_GROUPS];
    memset(blk, 0, sizeof blk);
    sd_ck_field fields[SD_CK_GROUPS][SD_CK_MAX_FIELDS];
    size_t nfields[SD_CK_GROUPS];
    for (int k = 0; k < SD_CK_GROUPS; ++k)
        nfields[k] = sd_ck_fields(k, fields[k]);
    size_t *rows = NULL, *whole = NULL;
    int *group = NULL;
    uint64_t *ids = NULL;
    sd_ckpt_part *parts = NULL;
    sd_status st = SD_OK;
    if (!sd_ck_list(g, rank, &s, &rows, err)) {
        st = SD_ERR_MEMORY;
        goto done;
    }
    /* every stable id, sorted: the particles' rows in the file */
    int n_own = (int)w->p.n, *cnt = sd_malloc(2 * (size_t)size * sizeof *cnt);
    int ok = cnt != NULL && w->p.n <= INT32_MAX;
    if (!sd_ck_all(ok)) {
        sd_free(cnt);
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory gathering the stable ids");
        goto done;
    }
    MPI_Allgather(&n_own, 1, MPI_INT, cnt, 1, MPI_INT, MPI_COMM_WORLD);
    size_t n_all = 0;
    for (int r = 0; r < size; ++r) {
        cnt[size + r] = (int)n_all;
        n_all += (size_t)cnt[r];
    }
    ids = sd_malloc((n_all ? n_all : 1) * sizeof *ids);
    if (!sd_ck_all(ids != NULL && n_all <= INT32_MAX)) {
        sd_free(cnt);
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory gathering %zu stable ids", n_all);
        goto done;
    }
    MPI_Allgatherv(w->p.id, n_own, MPI_UINT64_T, ids, cnt, cnt + size, MPI_UINT64_T, MPI_COMM_WORLD);
    sd_free(cnt);
    qsort(ids, n_all, sizeof *ids, sd_rows_id_cmp);
    /* the rows of the particles, pairs and wall pairs to their blocks */
    if (!sd_ck_particles(w, ids, n_all, sd_ck_at(fields[0], nfields[0], "id"), rank, size, &blk[SD_CK_PARTICLES]) ||
        !sd_ck_pairs(w, 0, ids, n_all, fields[1], nfields[1], rank, size, &blk[SD_CK_PAIRS]) ||
        !sd_ck_pairs(w, 1, ids, n_all, fields[2], nfields[2], rank, size, &blk[SD_CK_WPAIRS])) {
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory sharing the checkpoint's rows out");
        goto done;
    }
    /* each dataset: this rank's rows and runs of it */
    group = sd_malloc((s.n ? s.n : 1) * sizeof *group);
    parts = sd_calloc(s.n ? s.n : 1, sizeof *parts);
    whole = sd_calloc(2 * (s.n ? s.n : 1), sizeof *whole);
    ok = group && parts && whole;
    const char *bad = NULL;
    for (size_t k = 0; ok && k < s.n; ++k) {
        sd_snap_item *it = &s.items[k];
        size_t f = 0;
        group[k] = sd_ck_row_item(it->name, fields, nfields, &f);
        parts[k].rows = rows[k];
        if (group[k] < 0) { /* rank 0 writes it whole */
            whole[2 * k + 1] = rows[k];
            parts[k].nseg = rank == 0 && rows[k] > 0;
            parts[k].seg = &whole[2 * k];
            continue;
        }
        const sd_ck_block *b = &blk[group[k]];
        size_t rb = it->comps * sd_state_type_size(it->type), total = 0;
        for (size_t j = 0; j < (size_t)size * b->segs; ++j)
            total += (size_t)b->count[j];
        if (rb != fields[group[k]][f].bytes || total != rows[k])
            bad = it->name; /* the view's list and the rows here disagree */
        void *d = sd_ck_alloc(b->n * rb);
        if (!d) {
            ok = 0;
            break;
        }
        for (size_t r = 0; !bad && r < b->n; ++r)
            memcpy((unsigned char *)d + r * rb, b->rows + r * b->rs + fields[group[k]][f].at, rb);
        sd_free(it->data);
        it->data = d;
        it->count = b->n;
        parts[k].nseg = b->nseg;
        parts[k].seg = b->seg;
    }
    if (!sd_ck_all(ok && !bad)) {
        st = ok ? sd_error_set(err, SD_ERR_INTERNAL, "", 0, bad ? bad : "", "the checkpoint's dataset '%s' has "
                               "other rows on the ranks than in the view", bad ? bad : "?")
                : sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the checkpoint's rows");
        goto done;
    }
    s.checksum = sd_ck_checksum(&s, rows, group, blk, rank, size);
    st = sd_checkpoint_write_collective(&s, parts, path, err);
done:
    for (int k = 0; k < SD_CK_GROUPS; ++k)
        sd_ck_block_free(&blk[k]);
    sd_snapshot_free(&s);
    sd_free(rows);
    sd_free(whole);
    sd_free(group);
    sd_free(parts);
    sd_free(ids);
    return st;
}
