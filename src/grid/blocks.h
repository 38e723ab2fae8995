/* blocks.h — the grid solver's step as items shared by the CPU loops
 * (grid_step.c, grid.c) and the CUDA kernels (backend/cuda/grid.cu): the
 * force pass of one block of cells, the kick and drift of one particle,
 * the sweep of one particle's history slots, one wall's total, and the
 * cell of a position. Single source (SD_HD, DESIGN.md rule 1): both
 * backends do the same operations in the same order, so they give the
 * same bits ([Naderi 2024] §3.2; docs/architecture.md).
 *
 * Invariants:
 *  - the inner grid is cut into blocks `slab` (= reach) cells thick in z
 *    and in y; a block's owners write only to their own block, the next z
 *    slab and the neighbouring y bands (stencil.h), so the blocks of one
 *    colour — (z slab mod 2, y band mod 3), six colours — touch disjoint
 *    particles: the CPU runs one colour's blocks on its threads, the GPU
 *    one kernel per colour with one thread per block; each particle gets
 *    its contributions in block order, whichever runs them, and no
 *    floating-point atomics are needed;
 *  - sd_grid_block_forces visits a block's owners in cell order (z, y, x),
 *    skipping the rows rowocc marks empty (a hint that only skips work).
 */
#ifndef SD_GRID_BLOCKS_H
#define SD_GRID_BLOCKS_H

#include "dynamics/integrate.h"
#include "grid/stencil.h"

/* The block layout of the force pass (a copy of the solver's geometry,
 * with its pointers into the memory of whoever runs it). */
typedef struct sd_grid_blocks {
    long nx, ny, nz;          /* cells, halo included */
    int reach;                /* stencil half width (cells) */
    long slab;                /* block edge in z and y (cells) */
    long nslab, nband;        /* blocks in z and in y */
    const uint8_t *rowocc;    /* per row of cells (z ny + y): 1 when it may hold a particle */
} sd_grid_blocks;

/* The blocks of one colour (0..5) and block e of them (s: z slab, t: y
 * band); the count is 0 when the colour has none. */
SD_HD static SD_INLINE long sd_grid_colour_count(const sd_grid_blocks *b, int colour)
{
    long s0 = colour / 3, t0 = colour % 3;
    long ns = (b->nslab - s0 + 1) / 2, nt = (b->nband - t0 + 2) / 3;
    return ns > 0 && nt > 0 ? ns * nt : 0;
}

SD_HD static SD_INLINE void sd_grid_colour_block(const sd_grid_blocks *b, int colour, long e, long *s, long *t)
{
    long s0 = colour / 3, t0 = colour % 3;
    long nt = (b->nband - t0 + 2) / 3;
    *s = s0 + 2 * (e / nt);
    *t = t0 + 3 * (e % nt);
}

/* The accumulator of block (s, t): the shared arrays, and the block's own
 * wall totals (slab_wall: 2 nwalls vectors per block, the last block being
 * the particles without a cell). */
SD_HD static SD_INLINE sd_grid_acc sd_grid_block_acc(sd_vec3 *ft, uint32_t *tag, sd_vec3 *ds, sd_vec3 *slab_wall,
                                                      size_t block, int nwalls, uint32_t epoch)
{
    sd_grid_acc a;
    a.ft = ft;
    a.tag = tag;
    a.ds = ds;
    a.wall_f = slab_wall + block * (size_t)nwalls * 2;
    a.wall_t = a.wall_f + nwalls;
    a.epoch = epoch;
    a.overflows = 0;
    return a;
}

/* The owners of block (s, t), in cell order; returns the contacts that
 * found no history slot. */
SD_HD static SD_INLINE long sd_grid_block_forces(const sd_grid_blocks *b, const sd_grid_view *v, sd_grid_acc *a,
                                                 long s, long t)
{
    long z0 = b->reach + s * b->slab, z1 = z0 + b->slab;
    long y0 = b->reach + t * b->slab, y1 = y0 + b->slab;
    if (z1 > b->nz - b->reach)
        z1 = b->nz - b->reach;
    if (y1 > b->ny - b->reach)
        y1 = b->ny - b->reach;
    long nx = b->nx, xa = b->reach, xb = b->nx - b->reach;
    for (long iz = z0; iz < z1; ++iz)
        for (long iy = y0; iy < y1; ++iy) {
            long r = iz * b->ny + iy;
            if (!b->rowocc[r])
                continue; /* an empty row of cells: nothing to read */
            const int32_t *row = v->cell + r * nx;
            if (v->occ) {
                /* the occupied cells of the row from its occupancy bits, a
                 * word at a time (no branch per cell) */
                long b0 = r * nx + xa, b1 = r * nx + xb;
                for (long wb = b0 & ~63L; wb < b1; wb += 64) {
                    uint64_t m = v->occ[wb >> 6];
                    if (wb < b0)
                        m &= ~(uint64_t)0 << (b0 - wb);
                    if (b1 - wb < 64)
                        m &= ((uint64_t)1 << (b1 - wb)) - 1u;
                    while (m) {
                        long ix = wb + sd_grid_ctz64(m) - r * nx;
                        m &= m - 1u;
                        sd_grid_owner_forces(v, a, (size_t)row[ix], ix, iy, iz);
                    }
                }
                continue;
            }
            for (long ix = xa; ix < xb; ++ix)
                if (row[ix] >= 0)
                    sd_grid_owner_forces(v, a, (size_t)row[ix], ix, iy, iz);
        }
    return a->overflows;
}

/* The particles without a cell (over[0..nover), storage order), one after
 * the other: each with its stencil and walls, then with the later ones
 * (one caller only: they may touch any particle). */
SD_HD static SD_INLINE long sd_grid_homeless_all(const sd_grid_view *v, sd_grid_acc *a, const uint32_t *over,
                                                 size_t nover)
{
    for (size_t e = 0; e < nover; ++e) {
        sd_grid_homeless_forces(v, a, over[e]);
        for (size_t e2 = e + 1; e2 < nover; ++e2)
            sd_grid_add_pair(v, a, over[e], over[e2]);
    }
    return a->overflows;
}

/* Half kick of particle k with its force, `kicks` times (v(t + dt) from
 * v(t + dt/2), then the next step's), and with `drift` the drift after
 * them (velocity Verlet; sd_integrate_drift's position update). */
SD_HD static SD_INLINE void sd_grid_kick_item(sd_grid_part *part, const sd_grid_kind *kinds, const sd_vec3 *ft,
                                              size_t k, int kicks, int drift, sd_vec3 grav, sd_real dt)
{
    sd_real h = SD_R(0.5) * dt;
    sd_quat q = sd_quat_identity(); /* spheres: isotropic inertia, the frame does not matter */
    const sd_grid_kind *kd = &kinds[part[k].kind];
    for (int e = 0; e < kicks; ++e)
        sd_integrate_kick(&part[k].v, &part[k].w, q, ft[2 * k], ft[2 * k + 1], kd->inv_mass, kd->inv_inertia, grav,
                          h);
    if (drift && kd->inv_mass > 0)
        part[k].x = sd_v3_madd(part[k].x, dt, part[k].v);
}

/* Frees the slots of particle k not stamped with this step's epoch
 * (contacts that ended: their springs are forgotten, as in the general
 * engine); returns the slots still held. Branch-free. */
SD_HD static SD_INLINE int sd_grid_sweep_item(uint32_t *tag, size_t k, uint32_t epoch)
{
    int used = 0;
    for (int s = 0; s < SD_GRID_SLOTS; ++s) {
        uint32_t tg = tag[k * SD_GRID_SLOTS + (size_t)s];
        uint32_t keep = (tg & SD_GRID_TAG_EPOCH) == epoch;
        tag[k * SD_GRID_SLOTS + (size_t)s] = keep ? tg : 0u;
        used += (int)(keep & (tg != 0u));
    }
    return used;
}

/* Wall wi's force and torque: its blocks' totals in block order (nblock
 * blocks and the block of the particles without a cell). */
SD_HD static SD_INLINE void sd_grid_wall_total(const sd_vec3 *slab_wall, long nblock, int nwalls, int wi,
                                               sd_vec3 *force, sd_vec3 *torque)
{
    sd_vec3 fs = sd_v3_zero(), ts = sd_v3_zero();
    for (long s = 0; s <= nblock; ++s) {
        fs = sd_v3_add(fs, slab_wall[((size_t)s * (size_t)nwalls * 2) + (size_t)wi]);
        ts = sd_v3_add(ts, slab_wall[((size_t)s * (size_t)nwalls * 2) + (size_t)nwalls + (size_t)wi]);
    }
    *force = fs;
    *torque = ts;
}

/* The cell of position x (index into the cell array), or
 * 0xfffffffe (SD_GRID_OUTSIDE, grid.h) outside the inner grid or for NaN. */
SD_HD static SD_INLINE uint32_t sd_grid_cell_index(sd_vec3 lo, sd_real h, int reach, long nx, long ny, long nz,
                                                   sd_vec3 x)
{
    double fx = (double)((x.x - lo.x) / h), fy = (double)((x.y - lo.y) / h), fz = (double)((x.z - lo.z) / h);
    double r = (double)reach;
    /* written so that NaN fails too */
    if (!(fx >= r && fx < (double)nx - r && fy >= r && fy < (double)ny - r && fz >= r && fz < (double)nz - r))
        return 0xfffffffeu;
    long ix = (long)fx, iy = (long)fy, iz = (long)fz;
    return (uint32_t)((iz * ny + iy) * nx + ix);
}

#endif
