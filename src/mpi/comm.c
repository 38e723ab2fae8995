/* comm.c — the decomposed run's exchanges (mpi.h): the world's hooks
 * (sd_world_comm) over MPI_COMM_WORLD.
 *
 * A particle travels as one row: every field of SD_PARTICLE_FIELDS in
 * turn, copied byte for byte, so a ghost or a migrated particle is the
 * same bits as its owner's copy (the rows follow the list: a new field
 * travels without a change here). All traffic is one MPI_Alltoallv per
 * exchange: any rank may send to any other, so a box thinner than the
 * contact reach still gets every ghost it needs.
 */
#define _POSIX_C_SOURCE 200809L /* nanosleep (sd_mpi_fail) */
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/alloc.h"
#include "backend/backend.h"
#include "core/error.h"
#include "mpi/mpi.h"
#include "world/remove.h"
#include "world/solver.h"
#include "world/world.h"

struct sd_mpi {
    MPI_Comm comm;
    int rank, size;
    sd_mpi_grid grid;          /* the split in use (mpi/decomp.c) */
    int *scount, *sdispl, *rcount, *rdispl; /* per rank, in bytes */
    /* the ghost rows this rank sends each step: owned storage indices,
     * grouped by destination rank; and where the received ones sit */
    uint32_t *send_idx;
    sd_vec3 *send_shift;       /* m, the periodic shift of each sent row (zero: the particle as it is) */
    size_t send_n, send_cap;
    int *ghost_count;          /* per rank, rows sent (then received) */
    int *ghost_recv;           /* per rank, rows received */
    size_t ghost_base, ghost_n;
    unsigned char *sbuf, *rbuf;
    size_t sbuf_cap, rbuf_cap;
    size_t migrated;           /* particles this rank sent away, since attach */
    size_t carried;            /* and their pair and wall history entries sent with them */
    size_t carried_hints;      /* of which, entries holding a volume law's overlap hint */
    size_t carried_walls;      /* of which, wall pairs' entries */
    long rebalance_every;      /* steps between re-cuts (mpi/rebalance.c), 0 none */
    long rebalance_next;       /* the step from which the next rebuild re-cuts */
    long rebalances;           /* re-cuts made */
};

/* Set when this rank fails only because another rank reported a failure
 * in a vote (the ranks agree to fail alike, e.g. out of memory on one):
 * that rank reports it, this one keeps quiet (sd_mpi_fail). */
static int sd_failed_elsewhere;

int sd_mpi_failed_elsewhere(int bad, int any)
{
    if (any && !bad)
        sd_failed_elsewhere = 1;
    return any && !bad;
}

/* ---- rows ------------------------------------------------------------------ */

static size_t sd_row_size(void)
{
    size_t s = 0;
#define SD_X_SIZE(type, name, ...) s += sizeof(type);
    SD_PARTICLE_FIELDS(SD_X_SIZE)
#undef SD_X_SIZE
    return s;
}

/* Row of particle k; x_at, when not NULL, stands for its position (a
 * periodic image's). */
static unsigned char *sd_row_pack_at(const sd_particles *p, size_t k, const sd_vec3 *x_at, unsigned char *b)
{
#define SD_X_PACK(type, name, ...)                                                               \
    {                                                                                            \
        const void *src = &p->name[k];                                                           \
        if (x_at && (const void *)&p->name == (const void *)&p->x)                               \
            src = x_at;                                                                          \
        memcpy(b, src, sizeof(type));                                                            \
        b += sizeof(type);                                                                       \
    }
    SD_PARTICLE_FIELDS(SD_X_PACK)
#undef SD_X_PACK
    return b;
}

static unsigned char *sd_row_pack(const sd_particles *p, size_t k, unsigned char *b)
{
    return sd_row_pack_at(p, k, NULL, b);
}

static const unsigned char *sd_row_unpack(sd_particles *p, size_t k, const unsigned char *b)
{
#define SD_X_UNPACK(type, name, ...)          \
    memcpy(&p->name[k], b, sizeof(type)); \
    b += sizeof(type);
    SD_PARTICLE_FIELDS(SD_X_UNPACK)
#undef SD_X_UNPACK
    return b;
}

/* Keeps, of rows first .. n - 1, those whose dest[k - first] is rank, in
 * order, and drops the others (p->n shrinks); returns the new count. */
static size_t sd_rows_keep(sd_particles *p, size_t first, const int *dest, int rank)
{
    size_t keep = first;
    for (size_t k = first; k < p->n; ++k) {
        if (dest[k - first] != rank)
            continue;
        if (keep != k) {
#define SD_X_MOVE(type, name, ...) p->name[keep] = p->name[k];
            SD_PARTICLE_FIELDS(SD_X_MOVE)
#undef SD_X_MOVE
        }
        ++keep;
    }
    p->n = keep;
    ++p->generation;
    return keep;
}

static int sd_grow(unsigned char **buf, size_t *cap, size_t need)
{
    if (need <= *cap)
        return 0;
    size_t c = need + need / 2 + 64;
    unsigned char *q = sd_realloc(*buf, c);
    if (!q)
        return -1;
    *buf = q;
    *cap = c;
    return 0;
}

/* One all-to-all of bytes: scount (per rank) from sbuf, the counts
 * exchanged first; the received bytes in rbuf, rcount per rank. Returns the
 * bytes received, or (size_t)-1 without memory. */
static size_t sd_alltoall(sd_mpi *m)
{
    MPI_Alltoall(m->scount, 1, MPI_INT, m->rcount, 1, MPI_INT, m->comm);
    size_t sn = 0, rn = 0;
    for (int r = 0; r < m->size; ++r) {
        m->sdispl[r] = (int)sn;
        m->rdispl[r] = (int)rn;
        sn += (size_t)m->scount[r];
        rn += (size_t)m->rcount[r];
    }
    if (sd_grow(&m->rbuf, &m->rbuf_cap, rn) || sd_grow(&m->sbuf, &m->sbuf_cap, sn))
        return (size_t)-1;
    MPI_Alltoallv(m->sbuf, m->scount, m->sdispl, MPI_BYTE, m->rbuf, m->rcount, m->rdispl, MPI_BYTE, m->comm);
    return rn;
}

/* ---- hooks ------------------------------------------------------------------ */

static int sd_hook_any(void *ctx, int flag)
{
    sd_mpi *m = ctx;
    int in = flag != 0, out = 0;
    MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, m->comm);
    return out;
}

static double sd_hook_min(void *ctx, double v)
{
    sd_mpi *m = ctx;
    double out = v;
    MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, MPI_MIN, m->comm);
    return out;
}

/* A history entry in transit: a pair's key or a wall pair's, and every
 * HISTORY field of its list (broad/pairs.h): the spring, and for a
 * particle pair the volume law's overlap hint (the interior point x0 of
 * the last overlap, seed 000 eqs. 12-22). The hint only lets the next
 * overlap skip its GJK gate (geom/overlap.h: the hull is built without
 * it), so it saves time on the receiving rank, not bits. */
typedef struct sd_hist_row {
    sd_pair_key key;
    sd_wall_pair_key wkey;
    sd_vec3 ds;
    sd_vec3 x0;
    int x0_ok; /* 1: x0 holds a point of the last overlap */
    int wall;  /* 1: a wall pair's entry */
} sd_hist_row;

/* The HISTORY fields are those sd_hist_row carries: a new one needs a
 * member there (and its line in sd_hist_of / the arrival). */
#define SD_X_HIST_COUNT(type, name, per, role, doc) +((role) == SD_PF_HISTORY)
_Static_assert(0 SD_PAIR_FIELDS(SD_X_HIST_COUNT) == 3 && 0 SD_WALL_PAIR_FIELDS(SD_X_HIST_COUNT) == 1,
               "sd_hist_row carries every HISTORY field of SD_PAIR_FIELDS and SD_WALL_PAIR_FIELDS");
#undef SD_X_HIST_COUNT

/* Pair e of a list carries history worth sending: a spring or, for a
 * particle pair, an overlap hint (the bins keep the same entries:
 * broad/bins.c, sd_history_keep). */
static int sd_hist_pair_keep(const sd_pair_list *l, size_t e)
{
    return l->ds[e].x != 0 || l->ds[e].y != 0 || l->ds[e].z != 0 || l->x0_ok[e];
}

static int sd_hist_wall_keep(const sd_wall_pair_list *l, size_t e)
{
    return l->ds[e].x != 0 || l->ds[e].y != 0 || l->ds[e].z != 0;
}

/* A departing particle: its id and the rank it goes to. */
typedef struct sd_leaver {
    uint64_t id;
    int dest;
} sd_leaver;

static int sd_leaver_cmp(const void *a, const void *b)
{
    uint64_t p = ((const sd_leaver *)a)->id, q = ((const sd_leaver *)b)->id;
    return p < q ? -1 : (p > q ? 1 : 0);
}

/* The rank a departing id goes to, or -1 when the id stays. */
static int sd_dest_of(const sd_leaver *v, size_t n, uint64_t id)
{
    sd_leaver key = {id, -1};
    const sd_leaver *f = n ? bsearch(&key, v, n, sizeof *v, sd_leaver_cmp) : NULL;
    return f ? f->dest : -1;
}

/* The rank whose box holds particle k's (x, id) now. */
static int sd_rank_at(const sd_mpi *m, const sd_particles *p, size_t k)
{
    double x[3] = {(double)p->x[k].x, (double)p->x[k].y, (double)p->x[k].z};
    return sd_mpi_grid_rank(&m->grid, x, p->id[k]);
}

/* Migration (mpi.h): the particles and their history, then the arrays
 * compacted and the arrivals appended. The entries with a zero spring and
 * no overlap hint carry nothing (the bins keep only the others:
 * broad/bins.c). The GJK warm start and the other ZERO fields start again
 * at every rebuild on every rank (broad/pairs.h), and every rank rebuilds
 * at the same step, so they need not travel. */
static sd_status sd_hook_migrate(void *ctx, sd_world *w, sd_error *err)
{
    sd_mpi *m = ctx;
    sd_particles *p = &w->p;
    if (m->rebalance_every > 0 && w->step >= m->rebalance_next) { /* the same step on every rank */
        sd_status rst = sd_mpi_recut(w, &m->grid, err);
        if (rst != SD_OK)
            return rst;
        m->rebalances++;
        m->rebalance_next = w->step + m->rebalance_every;
    }
    size_t n = p->n, leave = 0, rs = sd_row_size();
    int *dest = sd_malloc((n ? n : 1) * sizeof *dest);
    if (!dest)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "migration: out of memory (%zu particles)", n);
    for (size_t k = 0; k < n; ++k) {
        dest[k] = sd_rank_at(m, p, k);
        leave += dest[k] != m->rank;
    }
    m->migrated += leave;
    /* the departing ids, sorted, with their ranks (history lookup) */
    sd_leaver *ids = sd_malloc((leave ? leave : 1) * sizeof *ids);
    if (!ids) {
        sd_free(dest);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "migration: out of memory (%zu particles)", n);
    }
    {
        size_t t = 0;
        for (size_t k = 0; k < n; ++k)
            if (dest[k] != m->rank)
                ids[t++] = (sd_leaver){p->id[k], dest[k]};
        qsort(ids, leave, sizeof *ids, sd_leaver_cmp);
    }
    /* per rank: rows, then history entries; sizes first */
    const sd_pair_list *l = &w->pairs;
    const sd_wall_pair_list *wl = &w->wpairs;
    size_t *nrow = sd_malloc((size_t)m->size * 2 * sizeof *nrow);
    sd_status st = SD_OK;
    if (!nrow)
        st = SD_ERR_MEMORY;
    size_t *nhist = nrow ? nrow + m->size : NULL;
    if (st == SD_OK) {
        memset(nrow, 0, (size_t)m->size * 2 * sizeof *nrow);
        for (size_t k = 0; k < n; ++k)
            if (dest[k] != m->rank)
                nrow[dest[k]]++;
        for (size_t e = 0; leave && e < l->n; ++e) {
            if (!sd_hist_pair_keep(l, e))
                continue;
            int a = sd_dest_of(ids, leave, l->key[e].id_lo), b = sd_dest_of(ids, leave, l->key[e].id_hi);
            size_t c = (size_t)(a >= 0) + (size_t)(b >= 0 && b != a);
            if (a >= 0)
                nhist[a]++;
            if (b >= 0 && b != a)
                nhist[b]++;
            if (l->x0_ok[e])
                m->carried_hints += c;
        }
        for (size_t e = 0; leave && e < wl->n; ++e) {
            if (!sd_hist_wall_keep(wl, e))
                continue;
            int a = sd_dest_of(ids, leave, wl->key[e].id);
            if (a >= 0) {
                nhist[a]++;
                m->carried_walls++;
            }
        }
        size_t total = 0;
        for (int r = 0; r < m->size; ++r)
            m->carried += nhist[r];
        for (int r = 0; r < m->size; ++r) {
            size_t b = 2 * sizeof(uint64_t) + nrow[r] * rs + nhist[r] * sizeof(sd_hist_row);
            m->scount[r] = (int)b;
            total += b;
        }
        if (sd_grow(&m->sbuf, &m->sbuf_cap, total))
            st = SD_ERR_MEMORY;
    }
    if (st == SD_OK) {
        /* each rank's block: two counts, the rows, the entries */
        unsigned char **cur = sd_malloc((size_t)m->size * sizeof *cur);
        if (!cur)
            st = SD_ERR_MEMORY;
        else {
            size_t off = 0;
            for (int r = 0; r < m->size; ++r) {
                cur[r] = m->sbuf + off;
                uint64_t c[2] = {nrow[r], nhist[r]};
                memcpy(cur[r], c, sizeof c);
                cur[r] += sizeof c;
                off += (size_t)m->scount[r];
            }
            for (size_t k = 0; k < n; ++k)
                if (dest[k] != m->rank)
                    cur[dest[k]] = sd_row_pack(p, k, cur[dest[k]]);
            for (size_t e = 0; leave && e < l->n; ++e) {
                if (!sd_hist_pair_keep(l, e))
                    continue;
                int a = sd_dest_of(ids, leave, l->key[e].id_lo), b = sd_dest_of(ids, leave, l->key[e].id_hi);
                sd_hist_row h;
                memset(&h, 0, sizeof h);
                h.key = l->key[e];
                h.ds = l->ds[e];
                h.x0 = l->x0[e];
                h.x0_ok = l->x0_ok[e];
                for (int t = 0; t < 2; ++t) {
                    int r = t ? b : a;
                    if (r < 0 || (t && b == a))
                        continue;
                    memcpy(cur[r], &h, sizeof h);
                    cur[r] += sizeof h;
                }
            }
            for (size_t e = 0; leave && e < wl->n; ++e) {
                if (!sd_hist_wall_keep(wl, e))
                    continue;
                int a = sd_dest_of(ids, leave, wl->key[e].id);
                if (a < 0)
                    continue;
                sd_hist_row h;
                memset(&h, 0, sizeof h);
                h.wkey = wl->key[e];
                h.ds = wl->ds[e];
                h.wall = 1;
                memcpy(cur[a], &h, sizeof h);
                cur[a] += sizeof h;
            }
            sd_free(cur);
        }
    }
    /* every rank takes part in the exchange, even after a failure here:
     * a rank that stopped would leave the others waiting */
    int bad = st != SD_OK, any_bad = 0;
    MPI_Allreduce(&bad, &any_bad, 1, MPI_INT, MPI_LOR, m->comm);
    sd_mpi_failed_elsewhere(bad, any_bad);
    if (any_bad) {
        sd_free(dest);
        sd_free(ids);
        sd_free(nrow);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "migration: out of memory on %s rank",
                            bad ? "this" : "another");
    }
    size_t rn = sd_alltoall(m);
    /* compaction of the staying particles, in order */
    size_t keep = sd_rows_keep(p, 0, dest, m->rank);
    sd_free(dest);
    sd_free(ids);
    sd_free(nrow);
    if (rn == (size_t)-1)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "migration: out of memory for the received rows");
    /* the arrivals: rows after the staying particles, entries after the
     * old lists' (the next build carries them by key) */
    size_t arrive = 0, hist = 0;
    for (int r = 0; r < m->size; ++r) {
        uint64_t c[2];
        memcpy(c, m->rbuf + m->rdispl[r], sizeof c);
        arrive += c[0];
        hist += c[1];
    }
    if (arrive == 0 && hist == 0)
        return SD_OK;
    if (sd_particles_reserve(p, keep + arrive) != SD_OK || sd_pairs_reserve(&w->pairs, w->pairs.n + hist) != SD_OK ||
        sd_pairs_reserve_walls(&w->wpairs, w->wpairs.n + hist) != SD_OK)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "migration: out of memory for %zu arriving particles",
                            arrive);
    for (int r = 0; r < m->size; ++r) {
        const unsigned char *b = m->rbuf + m->rdispl[r];
        uint64_t c[2];
        memcpy(c, b, sizeof c);
        b += sizeof c;
        for (uint64_t t = 0; t < c[0]; ++t)
            b = sd_row_unpack(p, p->n++, b);
        for (uint64_t t = 0; t < c[1]; ++t) {
            sd_hist_row h;
            memcpy(&h, b, sizeof h);
            b += sizeof h;
            if (h.wall) {
                size_t e = w->wpairs.n++;
                w->wpairs.key[e] = h.wkey;
                w->wpairs.ds[e] = h.ds;
            } else {
                size_t e = w->pairs.n++;
                w->pairs.key[e] = h.key;
                w->pairs.ds[e] = h.ds;
                w->pairs.x0_ok[e] = (uint8_t)h.x0_ok;
                w->pairs.x0[e] = h.x0;
            }
        }
    }
    return SD_OK;
}

/* Packs the ghost rows of the send list, grouped by rank (ghost_count). */
static void sd_ghost_pack(sd_mpi *m, const sd_particles *p)
{
    size_t rs = sd_row_size();
    unsigned char *b = m->sbuf;
    for (size_t t = 0; t < m->send_n; ++t) {
        sd_vec3 sh = m->send_shift[t];
        if (sh.x == 0 && sh.y == 0 && sh.z == 0) {
            b = sd_row_pack(p, m->send_idx[t], b);
        } else {
            /* an image: the arithmetic of the local images
             * (sd_item_ghost), so both ranks see the same bits */
            sd_vec3 y = sd_v3_add(p->x[m->send_idx[t]], sh);
            b = sd_row_pack_at(p, m->send_idx[t], &y, b);
        }
    }
    for (int r = 0; r < m->size; ++r)
        m->scount[r] = (int)((size_t)m->ghost_count[r] * rs);
}

static void sd_ghost_unpack(sd_mpi *m, sd_particles *p)
{
    const unsigned char *b = m->rbuf;
    for (size_t g = 0; g < m->ghost_n; ++g)
        b = sd_row_unpack(p, m->ghost_base + g, b);
}

/* Adds send entry (k, shift) for rank r. */
static int sd_send_add(sd_mpi *m, size_t k, sd_vec3 sh)
{
    if (m->send_n == m->send_cap) {
        size_t c = m->send_cap * 2 + 64;
        uint32_t *q = sd_realloc(m->send_idx, c * sizeof *q);
        if (!q)
            return -1;
        m->send_idx = q;
        sd_vec3 *v = sd_realloc(m->send_shift, c * sizeof *v);
        if (!v)
            return -1;
        m->send_shift = v;
        m->send_cap = c;
    }
    m->send_idx[m->send_n] = (uint32_t)k;
    m->send_shift[m->send_n] = sh;
    m->send_n++;
    return 0;
}

/* 1 when y (m) lies within band (m) of the box [lo, hi] on every axis: a
 * particle there may touch, within the skin, one whose centre is in the
 * box (an empty box, lo = hi = +inf, is near nothing). */
static int sd_near_box(const double y[3], const double lo[3], const double hi[3], double band)
{
    for (int a = 0; a < 3; ++a)
        if (!(y[a] >= lo[a] - band && y[a] <= hi[a] + band))
            return 0;
    return 1;
}

/* 1 when the particle at x (m), moved by a period on one or more periodic
 * axes (period[a], m; 0 on the others; the domain from dlo), is near the
 * box (clamped to the domain on those axes): an image of one of the box's
 * particles may touch it there. Only a particle within 2 band of a
 * periodic face can be: one period away it lies beyond the domain by more
 * than band otherwise, so the 26 moves are tried for those only. */
static int sd_near_box_period(const double x[3], const double period[3], const double dlo[3], const double lo[3],
                              const double hi[3], double band)
{
    int edge = 0;
    for (int a = 0; a < 3; ++a)
        edge |= period[a] > 0 && (x[a] < dlo[a] + 2 * band || x[a] > dlo[a] + period[a] - 2 * band);
    if (!edge)
        return 0;
    for (int s = 1; s < 27; ++s) { /* the 26 moves (-1, 0, +1)^3 but none */
        int d[3] = {s % 3 - 1, (s / 3) % 3 - 1, s / 9 - 1};
        if ((d[0] && !period[0]) || (d[1] && !period[1]) || (d[2] && !period[2]) || (!d[0] && !d[1] && !d[2]))
            continue;
        double y[3] = {x[0] + d[0] * period[0], x[1] + d[1] * period[1], x[2] + d[2] * period[2]};
        if (sd_near_box(y, lo, hi, band))
            return 1;
    }
    return 0;
}

/* Ghosts (mpi.h): each owned particle, as it is and as each of its
 * periodic images (world/rebuild.c's rule and arithmetic), goes to every
 * rank whose box it is within reach of (on every axis: the corners' and
 * edges' neighbours too): to this rank's own ghosts as a local image
 * (ghost_owner k), to another rank as a row; those received are appended
 * after the local images. */
static sd_status sd_hook_ghosts(void *ctx, sd_world *w, sd_error *err)
{
    sd_mpi *m = ctx;
    sd_particles *p = &w->p;
    size_t n = p->n, rs = sd_row_size();
    double rmax = 0;
    for (size_t k = 0; k < n; ++k)
        rmax = rmax > (double)p->radius[k] ? rmax : (double)p->radius[k];
    double all = rmax;
    MPI_Allreduce(&rmax, &all, 1, MPI_DOUBLE, MPI_MAX, m->comm);
    /* the reach of a pair (world/rebuild.c's band, from the largest radius
     * of all ranks): a particle within it of a box may touch, within the
     * skin, one of the box's particles */
    sd_real band = SD_R(2.0) * (sd_real)all + w->skin;
    double lo[SD_MPI_MAX_RANKS][3], hi[SD_MPI_MAX_RANKS][3], period[3];
    int oom = m->size > SD_MPI_MAX_RANKS;
    for (int r = 0; !oom && r < m->size; ++r)
        sd_mpi_grid_box(&m->grid, r, lo[r], hi[r]);
    double span[3] = {w->def.domain_hi.x - w->def.domain_lo.x, w->def.domain_hi.y - w->def.domain_lo.y,
                      w->def.domain_hi.z - w->def.domain_lo.z};
    double dlo[3] = {w->def.domain_lo.x, w->def.domain_lo.y, w->def.domain_lo.z};
    for (int a = 0; a < 3; ++a) /* SD_PERIODIC_X, _Y, _Z: bits 0, 1, 2 */
        period[a] = (w->def.periodic & (1u << a)) ? span[a] : 0.0;
    int periodic = period[0] > 0 || period[1] > 0 || period[2] > 0;
    /* on a periodic axis every owned particle lies in the domain now (the
     * rebuild wrapped it before the migration), so a box's open outer face
     * closes at the domain's: else every particle one period away would be
     * within reach of the outer boxes, and sent there for nothing (an
     * empty box, +inf to +inf, stays empty) */
    for (int r = 0; !oom && r < m->size; ++r)
        for (int a = 0; a < 3; ++a)
            if (period[a] > 0) {
                lo[r][a] = fmax(lo[r][a], dlo[a]);
                hi[r][a] = fmin(hi[r][a], dlo[a] + span[a]);
            }
    /* per rank in turn, so the rows come out grouped by destination */
    m->send_n = 0;
    size_t n_local = 0;
    for (int r = 0; !oom && r < m->size; ++r) {
        m->ghost_count[r] = 0;
        for (size_t k = 0; !oom && k < n; ++k) {
            sd_vec3 sh[8];
            sh[0] = sd_v3_zero();
            int c = 1 + (w->def.periodic ? sd_world_periodic_images(w, k, band, sh + 1) : 0);
            for (int t = 0; t < c; ++t) {
                if (r == m->rank) {
                    /* every image of an owned particle is a local ghost,
                     * as in the serial run (made below) */
                    n_local += t > 0;
                    continue;
                }
                sd_vec3 v = t ? sd_v3_add(p->x[k], sh[t]) : p->x[k];
                double y[3] = {(double)v.x, (double)v.y, (double)v.z};
                /* the particle as it is also goes where an image of one of
                 * rank r's particles (one period away) may touch it: a
                 * contact through an image is evaluated at the lower id's
                 * true position (broad/bins.h), on both ranks */
                int near = sd_near_box(y, lo[r], hi[r], (double)band);
                if (!near && t == 0 && periodic)
                    near = sd_near_box_period(y, period, dlo, lo[r], hi[r], (double)band);
                if (!near)
                    continue;
                if (sd_send_add(m, k, sh[t])) {
                    oom = 1;
                    break;
                }
                m->ghost_count[r]++;
            }
        }
    }
    if (!oom && (sd_grow(&m->sbuf, &m->sbuf_cap, m->send_n * rs) ||
                 sd_world_ghosts_reserve(w, w->n_ghost + n_local) != SD_OK))
        oom = 1;
    int any = 0;
    MPI_Allreduce(&oom, &any, 1, MPI_INT, MPI_LOR, m->comm);
    sd_mpi_failed_elsewhere(oom, any);
    if (any) {
        m->send_n = 0;
        m->ghost_n = 0;
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "ghosts: out of memory on %s rank", oom ? "this" : "another");
    }
    /* the local images, as sd_periodic_ghosts makes them */
    {
        size_t g = w->n_ghost;
        for (size_t k = 0; k < n; ++k) {
            sd_vec3 sh[7];
            int c = w->def.periodic ? sd_world_periodic_images(w, k, band, sh) : 0;
            for (int t = 0; t < c; ++t) {
                sd_vec3 y = sd_v3_add(p->x[k], sh[t]);
                size_t d = n + g;
#define SD_X_COPY(type, name, ...) p->name[d] = p->name[k];
                SD_PARTICLE_FIELDS(SD_X_COPY)
#undef SD_X_COPY
                p->x[d] = y;
                w->ghost_owner[g] = (uint32_t)k;
                w->ghost_shift[g] = sh[t];
                ++g;
            }
        }
        w->n_ghost = g;
    }
    sd_ghost_pack(m, p);
    size_t rn = sd_alltoall(m);
    if (rn == (size_t)-1)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "ghosts: out of memory for the received rows");
    size_t got = rn / rs;
    m->ghost_base = n + w->n_ghost;
    m->ghost_n = got;
    if (sd_world_ghosts_reserve(w, w->n_ghost + got) != SD_OK)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "ghosts: out of memory for %zu ghosts", got);
    sd_ghost_unpack(m, p);
    /* which of the received rows are images: one byte per row, the same
     * grouping (the pair rules of broad/bins.h tell them apart) */
    for (size_t t = 0; t < m->send_n; ++t) {
        sd_vec3 sh = m->send_shift[t];
        m->sbuf[t] = (unsigned char)!(sh.x == 0 && sh.y == 0 && sh.z == 0);
    }
    for (int r = 0; r < m->size; ++r)
        m->scount[r] = m->ghost_count[r];
    if (sd_alltoall(m) != got)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "ghosts: out of memory for the image marks");
    for (size_t g = 0; g < got; ++g) {
        w->ghost_owner[w->n_ghost + g] = m->rbuf[g] ? SD_GHOST_REMOTE_IMAGE : SD_GHOST_REMOTE;
        w->ghost_shift[w->n_ghost + g] = sd_v3_zero();
    }
    w->n_ghost += got;
    return SD_OK;
}

/* Each step: the same rows again, in the same order (the counts are those
 * of the rebuild, so the received rows land on the same ghosts). */
static void sd_hook_exchange(void *ctx, sd_world *w)
{
    sd_mpi *m = ctx;
    size_t rs = sd_row_size();
    sd_ghost_pack(m, &w->p);
    size_t rn = sd_alltoall(m);
    if (rn == (size_t)-1 || rn != m->ghost_n * rs) { /* no memory: the buffers hold the sizes of the rebuild */
        fprintf(stderr, "shapedem: rank %d: ghost exchange: out of memory or rows lost (%zu bytes for %zu ghosts)\n",
                m->rank, rn, m->ghost_n);
        MPI_Abort(m->comm, 1);
    }
    sd_ghost_unpack(m, &w->p);
}

/* ---- insertions and outlets (world/process.c) --------------------------------- */

static unsigned long long sd_hook_sum(void *ctx, unsigned long long v)
{
    sd_mpi *m = ctx;
    unsigned long long out = v;
    MPI_Allreduce(&v, &out, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, m->comm);
    return out;
}

/* Gathers count doubles per rank (each rank's block in rank order) into
 * *out on every rank; *total gets the count. -1 without memory on some
 * rank (every rank then frees and fails alike). */
static int sd_allgather_doubles(sd_mpi *m, const double *mine, int count, double **out, size_t *total)
{
    int *cnt = sd_malloc((size_t)m->size * 2 * sizeof *cnt);
    int ok = cnt != NULL, all = 0;
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_LAND, m->comm);
    sd_mpi_failed_elsewhere(!ok, !all);
    if (!all) {
        sd_free(cnt);
        return -1;
    }
    int *displ = cnt + m->size;
    MPI_Allgather(&count, 1, MPI_INT, cnt, 1, MPI_INT, m->comm);
    size_t t = 0;
    for (int r = 0; r < m->size; ++r) {
        displ[r] = (int)t;
        t += (size_t)cnt[r];
    }
    double *buf = sd_malloc((t ? t : 1) * sizeof *buf);
    ok = buf != NULL;
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_LAND, m->comm);
    sd_mpi_failed_elsewhere(!ok, !all);
    if (!all) {
        sd_free(cnt);
        sd_free(buf);
        return -1;
    }
    MPI_Allgatherv(mine, count, MPI_DOUBLE, buf, cnt, displ, MPI_DOUBLE, m->comm);
    sd_free(cnt);
    *out = buf;
    *total = t;
    return 0;
}

/* What an insertion must not overlap (world.h): every rank's owned
 * particles, centre and bounding radius, as world/process.c reads them
 * (the same double conversions), so every rank checks against the same
 * spheres as a serial run holding them all. */
static sd_status sd_hook_all_spheres(void *ctx, const sd_world *w, double **xr, size_t *n, sd_error *err)
{
    sd_mpi *m = ctx;
    const sd_particles *p = &w->p;
    double *mine = sd_malloc((p->n ? p->n : 1) * 4 * sizeof *mine);
    for (size_t k = 0; mine && k < p->n; ++k) {
        mine[4 * k] = (double)p->x[k].x;
        mine[4 * k + 1] = (double)p->x[k].y;
        mine[4 * k + 2] = (double)p->x[k].z;
        mine[4 * k + 3] = (double)p->radius[k];
    }
    size_t t = 0;
    int bad = sd_allgather_doubles(m, mine, mine ? (int)(4 * p->n) : 0, xr, &t);
    sd_free(mine);
    if (bad || !mine) {
        sd_free(bad ? NULL : *xr);
        *xr = NULL;
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "insertion: out of memory gathering the particles");
    }
    *n = t / 4;
    return SD_OK;
}

/* Inserted particles first .. n - 1 (every rank added them alike) stay on
 * the rank that owns them by the split's rule, as a migration would put
 * them: the others' rows are dropped, in place. They are the last rows and
 * touch nothing yet: no pair or ghost names them, and the add made the
 * world due for a rebuild on every rank, which makes the lists and the
 * ghosts again (until then the lists' indices stay as a serial insertion
 * leaves them: sd_world_remove_particles would drop the pairs whose ghost
 * slot the add wrote over, and their springs with them). */
static sd_status sd_hook_keep_owned(void *ctx, sd_world *w, size_t first, sd_error *err)
{
    sd_mpi *m = ctx;
    sd_particles *p = &w->p;
    if (first >= p->n)
        return SD_OK; /* nothing inserted (on any rank: they all drew alike) */
    int *dest = sd_malloc((p->n - first) * sizeof *dest);
    if (!dest)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "insertion: out of memory (%zu particles)", p->n - first);
    for (size_t k = first; k < p->n; ++k)
        dest[k - first] = sd_rank_at(m, p, k);
    sd_rows_keep(p, first, dest, m->rank);
    sd_free(dest);
    return SD_OK;
}

typedef struct sd_id_mass {
    double id, mass; /* the id as a double: exact below 2^53 */
} sd_id_mass;

static int sd_id_mass_cmp(const void *a, const void *b)
{
    double p = ((const sd_id_mass *)a)->id, q = ((const sd_id_mass *)b)->id;
    return p < q ? -1 : (p > q ? 1 : 0);
}

/* The outlets' accounts (world.h): every rank's (id, mass), sorted by id,
 * summed in that order. */
static sd_status sd_hook_removed_sum(void *ctx, size_t n, const uint64_t *id, const double *mass, size_t *count,
                                     double *total, sd_error *err)
{
    sd_mpi *m = ctx;
    double *mine = sd_malloc((n ? n : 1) * 2 * sizeof *mine);
    for (size_t k = 0; mine && k < n; ++k) {
        mine[2 * k] = (double)id[k];
        mine[2 * k + 1] = mass[k];
    }
    double *all = NULL;
    size_t t = 0;
    int bad = sd_allgather_doubles(m, mine, mine ? (int)(2 * n) : 0, &all, &t);
    sd_free(mine);
    *count = 0;
    *total = 0;
    if (bad || !mine) {
        sd_free(bad ? NULL : all);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "outlet: out of memory gathering the removed particles");
    }
    sd_id_mass *v = (sd_id_mass *)all;
    qsort(v, t / 2, sizeof *v, sd_id_mass_cmp);
    for (size_t k = 0; k < t / 2; ++k)
        *total += v[k].mass;
    *count = t / 2;
    sd_free(all);
    return SD_OK;
}

/* A servo wall's pair in transit: its key (as doubles: ids exact below
 * 2^53) and its four values. */
typedef struct sd_wall_rec {
    double wall, id, sub, elem, v[4];
} sd_wall_rec;

static int sd_wall_rec_cmp(const void *a, const void *b)
{
    const sd_wall_rec *p = a, *q = b;
    const double *x = &p->wall, *y = &q->wall;
    for (int c = 0; c < 4; ++c)
        if (x[c] != y[c])
            return x[c] < y[c] ? -1 : 1;
    return 0;
}

/* The servo walls' sums (world.h): every rank's wall pairs gathered,
 * sorted by key, summed per wall in that order. */
static sd_status sd_hook_wall_sums(void *ctx, size_t n, const sd_wall_pair_key *key, const double *v, size_t wall_count,
                                   double *out, sd_error *err)
{
    sd_mpi *m = ctx;
    sd_wall_rec *mine = sd_malloc((n ? n : 1) * sizeof *mine);
    for (size_t k = 0; mine && k < n; ++k) {
        mine[k].wall = (double)key[k].wall;
        mine[k].id = (double)key[k].id;
        mine[k].sub = (double)key[k].sub;
        mine[k].elem = (double)key[k].elem;
        memcpy(mine[k].v, v + 4 * k, sizeof mine[k].v);
    }
    enum { PER = (int)(sizeof(sd_wall_rec) / sizeof(double)) };
    double *all = NULL;
    size_t t = 0;
    int bad = sd_allgather_doubles(m, (const double *)mine, mine ? (int)(PER * n) : 0, &all, &t);
    sd_free(mine);
    for (size_t k = 0; out && k < 4 * wall_count; ++k)
        out[k] = 0;
    if (bad || !mine || !out) {
        sd_free(bad ? NULL : all);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "servo walls: out of memory gathering the wall contacts");
    }
    sd_wall_rec *r = (sd_wall_rec *)all;
    size_t nr = t / PER;
    qsort(r, nr, sizeof *r, sd_wall_rec_cmp);
    for (size_t k = 0; k < nr; ++k) {
        size_t wk = (size_t)r[k].wall;
        if (wk < wall_count)
            for (int c = 0; c < 4; ++c)
                out[4 * wk + (size_t)c] += r[k].v[c];
    }
    sd_free(all);
    return SD_OK;
}

static const sd_world_comm sd_mpi_hooks = {
    .any = sd_hook_any,
    .min = sd_hook_min,
    .migrate = sd_hook_migrate,
    .ghosts = sd_hook_ghosts,
    .exchange = sd_hook_exchange,
    .sum = sd_hook_sum,
    .all_spheres = sd_hook_all_spheres,
    .keep_owned = sd_hook_keep_owned,
    .removed_sum = sd_hook_removed_sum,
    .wall_sums = sd_hook_wall_sums,
};

/* ---- attach, gather, fail --------------------------------------------------- */

static sd_status sd_mpi_refuse(const sd_world *w, sd_error *err)
{
    if (w->solver != &sd_solver_cells)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.solver",
                            "MPI ranks run the cells solver only (the grid solver is not decomposed yet)");
    /* either backend: the hooks work on the host's arrays, and the step
     * copies a device backend's rows around them (world/step.c: the
     * migration and the ghosts inside the rebuild, which reads back before
     * and uploads after; the state rows around each exchange; the servo
     * walls' pairs before the wall motion). Each rank's device is chosen
     * when its world is created (sd_world_def.device: the node-local rank,
     * sd_mpi_local_rank) */
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (size > SD_MPI_MAX_RANKS)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "at most %d MPI ranks in this version, got %d",
                            SD_MPI_MAX_RANKS, size);
    /* every particle kind is decomposed: spheres, convex shapes, sharp
     * polyhedra (their overlap hints travel with the pair history),
     * composites (element runs in key order, broad/canonical.c) and the
     * planar mode; the ghost reach is 2 r + skin from the largest bounding
     * radius, a composite's enclosing all its elements */
    /* walls: every rank holds all of them and moves them by the same
     * function of time (prescribed velocities, mesh motions, a drum's
     * spin-up), so they stay the same bits everywhere; a particle's wall
     * pairs are its own (owned particles only), and their springs travel
     * by key. A servo wall reads its force and contact stiffness, sums
     * over every rank's particles: world/servo.c takes them in the order
     * of the wall pairs' keys (wall_sums). Meshes: every rank has the whole
     * mesh; the near facets of a particle come from a query by distance,
     * so they are the same whatever each rank's facet bins are. */
    /* insertions and outlets: every rank runs each event at the same step;
     * an insertion draws, checks against every rank's particles and adds
     * alike everywhere, then each rank keeps its own; an outlet's accounts
     * are summed in stable-id order (world.h's hooks, world/process.c) */
    if (w->prepared)
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "sd_mpi_attach: the world has already stepped");
    return SD_OK;
}

sd_status sd_mpi_attach(sd_world *w, const sd_mpi_split_req *split, sd_mpi **out, sd_error *err)
{
    *out = NULL;
    sd_status st = sd_mpi_refuse(w, err);
    sd_mpi *m = sd_calloc(1, sizeof *m);
    if (st == SD_OK && !m)
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the decomposition");
    int size = 1, rank = 0;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    /* every rank must hold the same particles: their count and id sum agree */
    const sd_particles *p = &w->p;
    unsigned long long mine[2] = {p->n, 0}, lo[2], hi[2];
    for (size_t k = 0; k < p->n; ++k)
        mine[1] += p->id[k];
    MPI_Allreduce(mine, lo, 2, MPI_UNSIGNED_LONG_LONG, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(mine, hi, 2, MPI_UNSIGNED_LONG_LONG, MPI_MAX, MPI_COMM_WORLD);
    if (st == SD_OK && (lo[0] != hi[0] || lo[1] != hi[1]))
        st = sd_error_set(err, SD_ERR_INPUT, "", 0, "particles",
                          "the ranks built different worlds (%llu to %llu particles): every rank must read the "
                          "same scene", lo[0], hi[0]);
    if (m && st == SD_OK) {
        m->comm = MPI_COMM_WORLD;
        m->rank = rank;
        m->size = size;
        m->scount = sd_malloc((size_t)size * 6 * sizeof(int));
        if (!m->scount)
            st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the decomposition");
    }
    /* the split: every rank computes the same from the same world */
    if (st == SD_OK)
        st = sd_mpi_plan(w, split, size, &m->grid, err);
    uint8_t *mark = NULL;
    if (st == SD_OK) {
        m->sdispl = m->scount + size;
        m->rcount = m->scount + 2 * size;
        m->rdispl = m->scount + 3 * size;
        m->ghost_count = m->scount + 4 * size;
        m->ghost_recv = m->scount + 5 * size;
        mark = sd_malloc(p->n ? p->n : 1);
        if (!mark)
            st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory splitting %zu particles", p->n);
    }
    if (st == SD_OK) {
        for (size_t k = 0; k < p->n; ++k)
            mark[k] = (uint8_t)(sd_rank_at(m, p, k) != rank);
        st = sd_world_remove_particles(w, mark, NULL, err);
    }
    sd_free(mark);
    if (st != SD_OK) {
        if (m) {
            sd_free(m->scount);
            sd_free(m);
        }
        return st;
    }
    /* a device backend's copies were sized for the whole world (the
     * scene's build prepared it before the split): freed, so that the
     * next upload sizes them for this rank's part */
    if (w->backend)
        w->backend->release(&w->stage);
    w->comm = &sd_mpi_hooks;
    w->comm_ctx = m;
    *out = m;
    return SD_OK;
}

void sd_mpi_detach(sd_world *w, sd_mpi *m)
{
    if (!m)
        return;
    if (w && w->comm_ctx == m) {
        w->comm = NULL;
        w->comm_ctx = NULL;
    }
    sd_free(m->scount);
    sd_free(m->send_idx);
    sd_free(m->send_shift);
    sd_free(m->sbuf);
    sd_free(m->rbuf);
    sd_free(m);
}

int sd_mpi_rank(const sd_mpi *m) { return m->rank; }
int sd_mpi_size(const sd_mpi *m) { return m->size; }
size_t sd_mpi_migrated(const sd_mpi *m) { return m->migrated; }
size_t sd_mpi_carried(const sd_mpi *m) { return m->carried; }
size_t sd_mpi_carried_hints(const sd_mpi *m) { return m->carried_hints; }
size_t sd_mpi_carried_walls(const sd_mpi *m) { return m->carried_walls; }
size_t sd_mpi_ghosts(const sd_mpi *m) { return m->ghost_n; }

static int sd_state_cmp(const void *a, const void *b)
{
    const sd_particle_state *p = a, *q = b;
    return p->id < q->id ? -1 : (p->id > q->id ? 1 : 0);
}

sd_status sd_mpi_gather(const sd_mpi *m, const sd_world *w, sd_particle_state **out, size_t *n, sd_error *err)
{
    *out = NULL;
    *n = 0;
    size_t mine = w->p.n;
    sd_particle_state *s = sd_malloc((mine ? mine : 1) * sizeof *s);
    int *cnt = m->rank == 0 ? sd_malloc((size_t)m->size * 2 * sizeof *cnt) : NULL, *displ = cnt ? cnt + m->size : NULL;
    int ok = s != NULL && (m->rank != 0 || cnt), all_ok = 0;
    for (size_t k = 0; ok && k < mine; ++k)
        sd_world_get_particle(w, k, &s[k]);
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_LAND, m->comm);
    sd_mpi_failed_elsewhere(!ok, !all_ok);
    if (!all_ok) {
        sd_free(s);
        sd_free(cnt);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "gather: out of memory on %s rank",
                            ok ? "another" : "this");
    }
    int bytes = (int)(mine * sizeof *s);
    sd_particle_state *all = NULL;
    size_t total = 0;
    MPI_Gather(&bytes, 1, MPI_INT, cnt, 1, MPI_INT, 0, m->comm);
    if (m->rank == 0) {
        for (int r = 0; r < m->size; ++r) {
            displ[r] = (int)total;
            total += (size_t)cnt[r];
        }
        all = sd_malloc(total ? total : 1);
    }
    /* rank 0's buffer for every row: the others must not send into none */
    int got = m->rank != 0 || all;
    MPI_Bcast(&got, 1, MPI_INT, 0, m->comm);
    if (!got) {
        sd_mpi_failed_elsewhere(m->rank == 0 ? 1 : 0, 1);
        sd_free(s);
        sd_free(cnt);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "gather: out of memory on %s rank for %zu bytes",
                            m->rank == 0 ? "this" : "another", total);
    }
    MPI_Gatherv(s, bytes, MPI_BYTE, all, cnt, displ, MPI_BYTE, 0, m->comm);
    sd_free(s);
    sd_free(cnt);
    if (m->rank == 0) {
        *n = total / sizeof *all;
        qsort(all, *n, sizeof *all, sd_state_cmp);
        *out = all;
    }
    return SD_OK;
}

_Noreturn void sd_mpi_fail(const sd_mpi *m, const char *stage, sd_status st, const sd_error *err)
{
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    char buf[1024] = "";
    if (err)
        sd_error_format(err, buf, sizeof buf);
    /* A failure another rank reported in a vote (sd_mpi_failed_elsewhere):
     * that rank prints the one message and aborts the job; this one waits
     * for it to (an abort from here could end the job before its message
     * is out), at most 20 s, then ends the job itself, never a hang. */
    for (int t = 0; sd_failed_elsewhere && t < 200; ++t)
        nanosleep(&(struct timespec){0, 100000000L}, NULL);
    fprintf(stderr, "shapedem: rank %d of %d: %s failed (%s): %s\n", rank, size, stage,
            sd_status_name(st), buf);
    fflush(stderr);
    MPI_Abort(m ? m->comm : MPI_COMM_WORLD, st == SD_ERR_INPUT ? 2 : 1);
    abort(); /* MPI_Abort does not return */
}

/* ---- for the other files of the decomposition (mpi.h) ---------------------- */

size_t sd_mpi_row_size(void) { return sd_row_size(); }
unsigned char *sd_mpi_row_pack(const sd_particles *p, size_t k, unsigned char *b) { return sd_row_pack(p, k, b); }
const unsigned char *sd_mpi_row_unpack(sd_particles *p, size_t k, const unsigned char *b)
{
    return sd_row_unpack(p, k, b);
}
const sd_mpi_grid *sd_mpi_grid_of(const sd_mpi *m) { return &m->grid; }

void sd_mpi_set_rebalance(sd_mpi *m, long every, long from_step)
{
    m->rebalance_every = every;
    m->rebalance_next = from_step + every;
}
long sd_mpi_rebalances(const sd_mpi *m) { return m->rebalances; }
