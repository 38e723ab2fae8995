/* grid.cu — the grid solver's step on the device (backend cuda with
 * solver grid, [Naderi 2024]): the solver's compact state (grid/grid.h)
 * resident in device memory for a whole sd_grid_step call, the same items
 * as the CPU loops (grid/blocks.h, grid/stencil.h):
 *
 *   kick + drift (a thread per particle) ─► rebin (cells of the movers,
 *   conflicts) ─► forces: one kernel per colour of the blocks, a thread per
 *   block; the particles without a cell in one thread; the slot sweep; the
 *   wall totals (a thread per wall) ─► kick
 *
 * Invariants: no floating-point atomics. Each particle gets its contact
 * forces in block order within one colour and colour after colour, as on
 * the CPU (grid/blocks.h), so the same bits for any launch order. The
 * atomics here are on integers, whose result does not depend on the order:
 * the smallest storage index that claims a cell (the host's rule: in
 * storage order, the first claimant of a free cell takes it), the
 * occupancy bits, counters, the largest squared speed as the bits of a
 * non-negative double. Anything the device does not do (removals, which
 * renumber the storage; NaN and eq. 11 errors; a poured sheet; an outlet
 * opening) the host does on its arrays between a read back and an upload
 * (grid/grid_step.c), so it stays one code path.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "backend/cuda/state.h"
#include "grid/blocks.h"
extern "C" { /* C headers without their own guards */
#include "core/alloc.h"
#include "core/error.h"
#include "grid/grid.h"
}

/* counters of the small device buffer (unsigned long long each) */
enum {
    SD_CG_VMAX2 = 0, /* the bits of the largest |v|^2 (a non-negative double) */
    SD_CG_NAN,       /* 1 when some |v|^2 is NaN */
    SD_CG_OUTSIDE,   /* particles whose centre left the inner grid */
    SD_CG_CONFLICTS, /* new cell conflicts of this rebin */
    SD_CG_NOVER,     /* particles without a cell after it */
    SD_CG_OVERFLOWS, /* contacts without a history slot (force pass) */
    SD_CG_USED,      /* the most slots one particle holds (force pass) */
    SD_CG_COUNT
};

/* The arrays of the solver's state the device holds: X(member, type,
 * count): the one list behind the buffers, the uploads and the read backs
 * (all of them come back but the kinds, the tables and the wall copies,
 * which only the host changes). */
#define SD_CG_ARRAYS(X)                                                      \
    X(part, sd_grid_part, g->n, 1)                                           \
    X(ft, sd_vec3, 2 * g->n, 1)                                              \
    X(where, uint32_t, g->n, 1)                                              \
    X(home, uint32_t, g->n, 1)                                               \
    X(tag, uint32_t, g->n * SD_GRID_SLOTS, 1)                                \
    X(ds, sd_vec3, g->n * SD_GRID_SLOTS, 1)                                  \
    X(cell, int32_t, g->ncell, 1)                                            \
    X(rowocc, uint8_t, (size_t)(g->nz * g->ny), 1)                           \
    X(over, uint32_t, g->nover, 1)                                           \
    X(kinds, sd_grid_kind, g->nkinds, 0)                                     \
    X(walls, sd_grid_wall, (size_t)g->nwalls, 0)                             \
    X(stoff, long, (size_t)SD_GRID_HALF2, 0)                                 \
    X(qmask, uint64_t, (size_t)(SD_GRID_Q * SD_GRID_Q * SD_GRID_Q), 0)

typedef struct sd_cuda_grid {
    sd_cuda_state c; /* the stream and the first failure (sd_cuda_check) */
#define SD_X_BUF(member, type, count, back) sd_cuda_buf member;
    SD_CG_ARRAYS(SD_X_BUF)
#undef SD_X_BUF
    sd_cuda_buf mix, occ, slab_wall, flagk, cnt, wsum;
    size_t n, nover;
} sd_cuda_grid;

static sd_cuda_grid *sd_cg_of(sd_grid_state *g)
{
    if (g->device)
        return (sd_cuda_grid *)g->device;
    sd_cuda_grid *d = (sd_cuda_grid *)sd_calloc(1, sizeof *d);
    if (!d)
        return NULL;
    g->device = d;
    d->c.status = SD_OK;
    if (!sd_cuda_check(&d->c, cudaSetDevice(0), "grid start", "cudaSetDevice(0)"))
        (void)sd_cuda_check(&d->c, cudaStreamCreate(&d->c.stream), "grid start", "cudaStreamCreate");
    return d;
}

static sd_status sd_cg_status(sd_cuda_grid *d, sd_error *err)
{
    if (!d)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "CUDA backend: out of host memory for the grid state");
    if (d->c.status == SD_OK)
        return SD_OK;
    return sd_error_set(err, d->c.status, "", 0, "", "%s", d->c.message);
}

/* host -> device, growing the buffer (at least one byte: no NULL buffers) */
static int sd_cg_put(sd_cuda_grid *d, sd_cuda_buf *b, const void *host, size_t bytes, const char *what)
{
    if (sd_cuda_reserve(&d->c, b, bytes ? bytes : 1, "grid upload", what))
        return 1;
    return bytes && sd_cuda_check(&d->c, cudaMemcpyAsync(b->p, host, bytes, cudaMemcpyHostToDevice, d->c.stream),
                                  "grid upload", what);
}

extern "C" sd_status sd_cuda_grid_upload(sd_grid_state *g, const sd_pair_params *mix, int nm, sd_error *err)
{
    sd_cuda_grid *d = sd_cg_of(g);
    if (!d || d->c.status != SD_OK)
        return sd_cg_status(d, err);
    int bad = 0;
#define SD_X_PUT(member, type, count, back) \
    bad = bad || sd_cg_put(d, &d->member, g->member, (count) * sizeof(type), #member);
    SD_CG_ARRAYS(SD_X_PUT)
#undef SD_X_PUT
    size_t nblock1 = (size_t)(g->nslab * g->nband + 1), nw = (size_t)(g->nwalls ? g->nwalls : 1);
    bad = bad || sd_cg_put(d, &d->mix, mix, (size_t)nm * (size_t)nm * sizeof *mix, "mix");
    bad = bad || sd_cg_put(d, &d->occ, g->occ, g->occ ? g->nocc * sizeof *g->occ : 0, "occ");
    bad = bad || sd_cuda_reserve(&d->c, &d->slab_wall, nblock1 * nw * 2 * sizeof(sd_vec3), "grid upload", "slab_wall");
    bad = bad || sd_cuda_reserve(&d->c, &d->flagk, g->n ? g->n : 1, "grid upload", "flags");
    bad = bad || sd_cuda_reserve(&d->c, &d->cnt, SD_CG_COUNT * sizeof(unsigned long long), "grid upload", "counters");
    bad = bad || sd_cuda_reserve(&d->c, &d->wsum, nw * 2 * sizeof(sd_vec3), "grid upload", "wall totals");
    /* the overflow list may hold every particle */
    bad = bad || (g->n > g->nover && sd_cuda_reserve(&d->c, &d->over, g->n * sizeof(uint32_t), "grid upload", "over"));
    if (!bad && g->nover) /* a reserve may have dropped the copy */
        (void)sd_cg_put(d, &d->over, g->over, g->nover * sizeof(uint32_t), "over");
    d->n = g->n;
    d->nover = g->nover;
    if (bad && d->c.status == SD_ERR_MEMORY) {
        /* the bytes the whole state needs, for the message */
        size_t need = 0;
#define SD_X_SIZE(member, type, count, back) need += (count) * sizeof(type);
        SD_CG_ARRAYS(SD_X_SIZE)
#undef SD_X_SIZE
        need += (size_t)nm * (size_t)nm * sizeof *mix + (g->occ ? g->nocc * sizeof *g->occ : 0) +
                nblock1 * nw * 2 * sizeof(sd_vec3) + g->n * (1 + sizeof(uint32_t));
        size_t free_b = 0, total = 0;
        (void)cudaMemGetInfo(&free_b, &total);
        char why[sizeof d->c.message];
        snprintf(why, sizeof why, "%s", d->c.message);
        snprintf(d->c.message, sizeof d->c.message,
                 "out of device memory: the grid solver's state of %zu particles and %zu cells needs %.1f MiB on "
                 "the device (%.1f MiB free of %.1f MiB; %.200s)",
                 g->n, g->ncell, (double)need / 1048576.0, (double)free_b / 1048576.0, (double)total / 1048576.0,
                 why);
        return sd_cg_status(d, err);
    }
    (void)sd_cuda_check(&d->c, cudaStreamSynchronize(d->c.stream), "grid upload", "the copies");
    return sd_cg_status(d, err);
}

extern "C" sd_status sd_cuda_grid_read_back(sd_grid_state *g, sd_error *err)
{
    sd_cuda_grid *d = sd_cg_of(g);
    if (!d || d->c.status != SD_OK)
        return sd_cg_status(d, err);
    if (d->nover > g->over_cap) {
        uint32_t *o = (uint32_t *)sd_realloc(g->over, d->nover * sizeof *o);
        if (!o)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (cell conflicts)");
        g->over = o;
        g->over_cap = d->nover;
    }
    g->nover = d->nover;
#define SD_X_BACK(member, type, count, back)                                                                   \
    if (back && (count) != 0)                                                                                 \
        (void)sd_cuda_check(&d->c,                                                                             \
                            cudaMemcpyAsync(g->member, d->member.p, (count) * sizeof(type),                    \
                                            cudaMemcpyDeviceToHost, d->c.stream),                              \
                            "grid read back", #member);
    SD_CG_ARRAYS(SD_X_BACK)
#undef SD_X_BACK
    (void)sd_cuda_check(&d->c, cudaStreamSynchronize(d->c.stream), "grid read back", "the copies");
    return sd_cg_status(d, err);
}

extern "C" void sd_cuda_grid_free(sd_grid_state *g)
{
    sd_cuda_grid *d = (sd_cuda_grid *)g->device;
    if (!d)
        return;
    sd_cuda_buf *all[] = {
#define SD_X_PTR(member, type, count, back) &d->member,
        SD_CG_ARRAYS(SD_X_PTR)
#undef SD_X_PTR
            &d->mix, &d->occ, &d->slab_wall, &d->flagk, &d->cnt, &d->wsum};
    for (size_t k = 0; k < sizeof all / sizeof all[0]; ++k)
        if (all[k]->p)
            (void)cudaFree(all[k]->p);
    if (d->c.stream)
        (void)cudaStreamDestroy(d->c.stream);
    sd_free(d);
    g->device = NULL;
}

/* ---- kernels ---------------------------------------------------------------- */

__global__ void sd_kg_kick(sd_grid_part *part, const sd_grid_kind *kinds, const sd_vec3 *ft, size_t n, int kicks,
                           int drift, sd_vec3 grav, sd_real dt)
{
    size_t k = SD_CUDA_ITEM();
    if (k < n)
        sd_grid_kick_item(part, kinds, ft, k, kicks, drift, grav, dt);
}

/* rebin A: the cell of every particle, the largest squared speed, NaN and
 * the particles outside */
__global__ void sd_kg_where(const sd_grid_part *part, size_t n, sd_vec3 lo, sd_real h, int reach, long nx, long ny,
                            long nz, uint32_t *where, unsigned long long *cnt)
{
    size_t k = SD_CUDA_ITEM();
    if (k >= n)
        return;
    where[k] = sd_grid_cell_index(lo, h, reach, nx, ny, nz, part[k].x);
    if (where[k] == SD_GRID_OUTSIDE)
        atomicAdd(&cnt[SD_CG_OUTSIDE], 1ull);
    double v2 = (double)sd_v3_norm2(part[k].v);
    if (v2 != v2) {
        atomicMax(&cnt[SD_CG_NAN], 1ull);
        return;
    }
    unsigned long long b;
    memcpy(&b, &v2, sizeof b); /* v2 >= 0: the bits order as the numbers */
    atomicMax(&cnt[SD_CG_VMAX2], b);
}

/* rebin B: a particle that changed cell leaves its old one */
__global__ void sd_kg_leave(const uint32_t *where, const uint32_t *home, int32_t *cell, size_t n)
{
    size_t k = SD_CUDA_ITEM();
    if (k < n && home[k] != SD_GRID_OVER && home[k] != where[k])
        cell[home[k]] = -1;
}

/* rebin C1: the claimants (movers and particles without a cell): 2 when
 * a particle that stays holds the new cell (a conflict), else 1 */
__global__ void sd_kg_claimants(const uint32_t *where, const uint32_t *home, const int32_t *cell, uint8_t *flagk,
                                size_t n)
{
    size_t k = SD_CUDA_ITEM();
    if (k < n)
        flagk[k] = home[k] == where[k] ? 0 : cell[where[k]] >= 0 ? 2 : 1;
}

/* rebin C2: of the claimants of a free cell, the first in storage order
 * takes it (-1 is the largest unsigned value) */
__global__ void sd_kg_claim(const uint32_t *where, const uint8_t *flagk, int32_t *cell, size_t n)
{
    size_t k = SD_CUDA_ITEM();
    if (k < n && flagk[k] == 1)
        atomicMin((unsigned int *)(void *)&cell[where[k]], (unsigned int)k);
}

/* rebin C3: the winners move in, the others are conflicts */
__global__ void sd_kg_settle(const uint32_t *where, uint32_t *home, const int32_t *cell, const uint8_t *flagk,
                             uint8_t *rowocc, long nx, size_t n, unsigned long long *cnt)
{
    size_t k = SD_CUDA_ITEM();
    if (k >= n || !flagk[k])
        return;
    if (flagk[k] == 1 && cell[where[k]] == (int32_t)k) {
        home[k] = where[k];
        rowocc[where[k] / (uint32_t)nx] = 1; /* a hint, as on the host */
        return;
    }
    if (home[k] != SD_GRID_OVER)
        atomicAdd(&cnt[SD_CG_CONFLICTS], 1ull); /* a new conflict */
    home[k] = SD_GRID_OVER;
    atomicAdd(&cnt[SD_CG_NOVER], 1ull);
}

/* the overflow list in storage order (one thread; only when it is not
 * empty, which is rare: a conflict needs an overlap of 0.27 radii) */
__global__ void sd_kg_over(const uint32_t *home, size_t n, uint32_t *over)
{
    if (SD_CUDA_ITEM() != 0)
        return;
    size_t m = 0;
    for (size_t k = 0; k < n; ++k)
        if (home[k] == SD_GRID_OVER)
            over[m++] = (uint32_t)k;
}

__global__ void sd_kg_occ(const uint32_t *home, size_t n, unsigned long long *occ)
{
    size_t k = SD_CUDA_ITEM();
    if (k < n && home[k] != SD_GRID_OVER)
        atomicOr(&occ[home[k] >> 6], 1ull << (home[k] & 63u));
}

/* one thread per block of the colour */
__global__ void sd_kg_blocks(sd_grid_blocks b, sd_grid_view v, sd_vec3 *ft, uint32_t *tag, sd_vec3 *ds,
                             sd_vec3 *slab_wall, uint32_t epoch, int colour, long nb, unsigned long long *cnt)
{
    size_t e = SD_CUDA_ITEM();
    if (e >= (size_t)nb)
        return;
    long s, t;
    sd_grid_colour_block(&b, colour, (long)e, &s, &t);
    sd_grid_acc a = sd_grid_block_acc(ft, tag, ds, slab_wall, (size_t)(s * b.nband + t), v.nwalls, epoch);
    long of = sd_grid_block_forces(&b, &v, &a, s, t);
    if (of)
        atomicAdd(&cnt[SD_CG_OVERFLOWS], (unsigned long long)of);
}

__global__ void sd_kg_homeless(sd_grid_view v, sd_vec3 *ft, uint32_t *tag, sd_vec3 *ds, sd_vec3 *slab_wall,
                               size_t nblock, uint32_t epoch, const uint32_t *over, size_t nover,
                               unsigned long long *cnt)
{
    if (SD_CUDA_ITEM() != 0)
        return;
    sd_grid_acc a = sd_grid_block_acc(ft, tag, ds, slab_wall, nblock, v.nwalls, epoch);
    long of = sd_grid_homeless_all(&v, &a, over, nover);
    if (of)
        atomicAdd(&cnt[SD_CG_OVERFLOWS], (unsigned long long)of);
}

__global__ void sd_kg_sweep(uint32_t *tag, size_t n, uint32_t epoch, unsigned long long *cnt)
{
    size_t k = SD_CUDA_ITEM();
    if (k >= n)
        return;
    int used = sd_grid_sweep_item(tag, k, epoch);
    if (used)
        atomicMax(&cnt[SD_CG_USED], (unsigned long long)used);
}

__global__ void sd_kg_walls(const sd_vec3 *slab_wall, long nblock, int nwalls, sd_vec3 *wsum)
{
    size_t wi = SD_CUDA_ITEM();
    if (wi < (size_t)nwalls)
        sd_grid_wall_total(slab_wall, nblock, nwalls, (int)wi, &wsum[wi], &wsum[(size_t)nwalls + wi]);
}

/* ---- stages ----------------------------------------------------------------- */

extern "C" sd_status sd_cuda_grid_kick(sd_grid_state *g, int kicks, int drift, sd_vec3 grav, sd_real dt,
                                       sd_error *err)
{
    sd_cuda_grid *d = sd_cg_of(g);
    if (!d || d->c.status != SD_OK || !d->n)
        return sd_cg_status(d, err);
    SD_CUDA_LAUNCH(sd_kg_kick, sd_cuda_blocks(d->n), SD_CUDA_BLOCK, d->c.stream, (sd_grid_part *)d->part.p,
                   (const sd_grid_kind *)d->kinds.p, (const sd_vec3 *)d->ft.p, d->n, kicks, drift, grav, dt);
    (void)sd_cuda_launched(&d->c, "grid kick");
    return sd_cg_status(d, err);
}

static int sd_cg_counters(sd_cuda_grid *d, unsigned long long *cnt, const char *stage)
{
    if (sd_cuda_check(&d->c,
                      cudaMemcpyAsync(cnt, d->cnt.p, SD_CG_COUNT * sizeof *cnt, cudaMemcpyDeviceToHost, d->c.stream),
                      stage, "the counters"))
        return 1;
    return sd_cuda_check(&d->c, cudaStreamSynchronize(d->c.stream), stage, "the kernels");
}

extern "C" sd_status sd_cuda_grid_rebin(sd_grid_state *g, sd_real dt, int *host, sd_error *err)
{
    *host = 0;
    sd_cuda_grid *d = sd_cg_of(g);
    if (!d || d->c.status != SD_OK)
        return sd_cg_status(d, err);
    size_t n = d->n;
    unsigned nb = sd_cuda_blocks(n);
    cudaStream_t st = d->c.stream;
    uint32_t *where = (uint32_t *)d->where.p, *home = (uint32_t *)d->home.p;
    int32_t *cell = (int32_t *)d->cell.p;
    unsigned long long *cnt = (unsigned long long *)d->cnt.p, hc[SD_CG_COUNT];
    if (sd_cuda_check(&d->c, cudaMemsetAsync(cnt, 0, SD_CG_COUNT * sizeof *cnt, st), "grid rebin", "the counters"))
        return sd_cg_status(d, err);
    if (n)
        SD_CUDA_LAUNCH(sd_kg_where, nb, SD_CUDA_BLOCK, st, (const sd_grid_part *)d->part.p, n, g->lo, g->h,
                       g->reach, g->nx, g->ny, g->nz, where, cnt);
    if (sd_cuda_launched(&d->c, "grid rebin") || sd_cg_counters(d, hc, "grid rebin"))
        return sd_cg_status(d, err);
    double vmax2;
    memcpy(&vmax2, &hc[SD_CG_VMAX2], sizeof vmax2);
    double hh = (double)g->h;
    if (hc[SD_CG_NAN] || hc[SD_CG_OUTSIDE] || vmax2 * (double)dt * (double)dt > hh * hh) {
        *host = 1; /* sd_grid_rebin on the host: removals, or its error */
        return SD_OK;
    }
    g->info.max_speed = sqrt(vmax2);
    if (n) {
        SD_CUDA_LAUNCH(sd_kg_leave, nb, SD_CUDA_BLOCK, st, where, home, cell, n);
        SD_CUDA_LAUNCH(sd_kg_claimants, nb, SD_CUDA_BLOCK, st, where, home, cell, (uint8_t *)d->flagk.p, n);
        SD_CUDA_LAUNCH(sd_kg_claim, nb, SD_CUDA_BLOCK, st, where, (const uint8_t *)d->flagk.p, cell, n);
        SD_CUDA_LAUNCH(sd_kg_settle, nb, SD_CUDA_BLOCK, st, where, home, cell, (const uint8_t *)d->flagk.p,
                       (uint8_t *)d->rowocc.p, g->nx, n, cnt);
    }
    if (sd_cuda_launched(&d->c, "grid rebin") || sd_cg_counters(d, hc, "grid rebin"))
        return sd_cg_status(d, err);
    d->nover = (size_t)hc[SD_CG_NOVER];
    if (d->nover)
        SD_CUDA_LAUNCH(sd_kg_over, 1, 1, st, home, n, (uint32_t *)d->over.p);
    g->info.conflicts += (long)hc[SD_CG_CONFLICTS];
    g->nover = d->nover; /* the host's list itself comes at the read back */
    if (g->nover > g->info.max_overflow)
        g->info.max_overflow = g->nover;
    (void)sd_cuda_launched(&d->c, "grid rebin");
    return sd_cg_status(d, err);
}

extern "C" sd_status sd_cuda_grid_forces(sd_grid_state *g, const sd_grid_view *hv, sd_vec3 *wall_f,
                                         sd_vec3 *wall_t, sd_error *err)
{
    sd_cuda_grid *d = sd_cg_of(g);
    if (!d || d->c.status != SD_OK)
        return sd_cg_status(d, err);
    size_t n = d->n;
    int nw = g->nwalls;
    cudaStream_t st = d->c.stream;
    sd_grid_view v = *hv;
    v.part = (const sd_grid_part *)d->part.p;
    v.kinds = (const sd_grid_kind *)d->kinds.p;
    v.cell = (const int32_t *)d->cell.p;
    v.where = (const uint32_t *)d->where.p;
    v.mix = (const sd_pair_params *)d->mix.p;
    v.walls = (const sd_grid_wall *)d->walls.p;
    v.occ = hv->occ ? (const uint64_t *)d->occ.p : NULL;
    v.stoff = (const long *)d->stoff.p;
    v.qmask = (const uint64_t *)d->qmask.p;
    sd_grid_blocks b = sd_grid_blocks_of(g);
    b.rowocc = (const uint8_t *)d->rowocc.p;
    long nblock = b.nslab * b.nband;
    sd_vec3 *ft = (sd_vec3 *)d->ft.p, *ds = (sd_vec3 *)d->ds.p, *slab_wall = (sd_vec3 *)d->slab_wall.p;
    uint32_t *tag = (uint32_t *)d->tag.p;
    unsigned long long *cnt = (unsigned long long *)d->cnt.p, hc[SD_CG_COUNT];
    const char *stage = "grid forces";
    /* zeros: all-zero bits are +0.0, as the host's sd_v3_zero() */
    if (sd_cuda_check(&d->c, cudaMemsetAsync(ft, 0, 2 * n * sizeof *ft, st), stage, "the forces") ||
        sd_cuda_check(&d->c, cudaMemsetAsync(cnt, 0, SD_CG_COUNT * sizeof *cnt, st), stage, "the counters") ||
        sd_cuda_check(&d->c,
                      cudaMemsetAsync(slab_wall, 0, (size_t)(nblock + 1) * (size_t)nw * 2 * sizeof(sd_vec3), st),
                      stage, "the wall totals"))
        return sd_cg_status(d, err);
    if (v.occ) {
        if (sd_cuda_check(&d->c, cudaMemsetAsync(d->occ.p, 0, g->nocc * sizeof(uint64_t), st), stage, "the bits"))
            return sd_cg_status(d, err);
        if (n)
            SD_CUDA_LAUNCH(sd_kg_occ, sd_cuda_blocks(n), SD_CUDA_BLOCK, st, (const uint32_t *)d->home.p, n,
                           (unsigned long long *)d->occ.p);
    }
    for (int colour = 0; colour < 6; ++colour) {
        long nb = sd_grid_colour_count(&b, colour);
        if (nb)
            SD_CUDA_LAUNCH(sd_kg_blocks, sd_cuda_blocks((size_t)nb), SD_CUDA_BLOCK, st, b, v, ft, tag, ds, slab_wall,
                           g->epoch, colour, nb, cnt);
    }
    if (d->nover)
        SD_CUDA_LAUNCH(sd_kg_homeless, 1, 1, st, v, ft, tag, ds, slab_wall, (size_t)nblock, g->epoch,
                       (const uint32_t *)d->over.p, d->nover, cnt);
    if (n)
        SD_CUDA_LAUNCH(sd_kg_sweep, sd_cuda_blocks(n), SD_CUDA_BLOCK, st, tag, n, g->epoch, cnt);
    if (nw) {
        sd_vec3 *wsum = (sd_vec3 *)d->wsum.p;
        SD_CUDA_LAUNCH(sd_kg_walls, sd_cuda_blocks((size_t)nw), SD_CUDA_BLOCK, st, (const sd_vec3 *)slab_wall,
                       nblock, nw, wsum);
        if (!sd_cuda_launched(&d->c, stage)) {
            (void)sd_cuda_check(&d->c, cudaMemcpyAsync(wall_f, wsum, (size_t)nw * sizeof *wsum,
                                                       cudaMemcpyDeviceToHost, st), stage, "the wall totals");
            (void)sd_cuda_check(&d->c, cudaMemcpyAsync(wall_t, wsum + nw, (size_t)nw * sizeof *wsum,
                                                       cudaMemcpyDeviceToHost, st), stage, "the wall totals");
        }
    }
    if (sd_cuda_launched(&d->c, stage) || sd_cg_counters(d, hc, stage))
        return sd_cg_status(d, err);
    g->info.slot_overflows += (long)hc[SD_CG_OVERFLOWS];
    if ((int)hc[SD_CG_USED] > g->info.slots_used_max)
        g->info.slots_used_max = (int)hc[SD_CG_USED];
    return SD_OK;
}
