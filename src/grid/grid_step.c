/* grid_step.c — the time step of the dense grid-stencil solver (seed 001).
 *
 *   pour a sheet when due ─► kick + drift ─► move particles to their new
 *   cells (conflicts, removals, eq. 11 check) ─► stencil forces ─► kick
 *
 * The same velocity Verlet as the general solver (world/step.c), with the
 * same single-source updates (dynamics/integrate.h) on the solver's own
 * compact state, and the same pair physics in the stencil kernel
 * (stencil.h), so a scene run with solver cells and with solver grid
 * follows the same trajectories (tests/validation/grid_vs_cells.c). Each
 * touching pair is evaluated once, by its owner; slabs of cells coloured
 * even/odd keep threads apart: no atomics, the same bits for any thread
 * count.
 */
#include <math.h>
#include <string.h>

#include "backend/cpu/parallel.h"
#include "backend/cuda/cuda.h"
#include "core/error.h"
#include "dynamics/integrate.h"
#include "grid/blocks.h"
#include "grid/grid.h"
#include "world/world.h"

static sd_grid_view sd_grid_view_of(const sd_world *w)
{
    const sd_grid_state *g = w->grid_state;
    sd_grid_view v;
    v.part = g->part;
    v.kinds = g->kinds;
    v.cell = g->cell;
    v.where = g->where;
    v.nx = g->nx;
    v.ny = g->ny;
    v.reach = g->reach;
    v.lo = g->lo;
    v.h = g->h;
    v.rmax = g->rmax;
    v.mix = w->mix;
    v.nm = (int)w->material_count;
    v.walls = g->walls;
    v.nwalls = g->nwalls;
    v.dt = w->dt;
    v.occ = g->reach == 2 && g->occ ? g->occ : NULL;
    v.stoff = g->stoff;
    v.qmask = g->qmask;
    v.inv_h = SD_R(1.0) / g->h;
    v.kind1 = g->nkinds == 1;
    v.runi = g->nkinds ? g->kinds[0].radius : SD_R(0.0);
    for (size_t e = 1; e < g->nkinds; ++e)
        if (g->kinds[e].radius != v.runi)
            v.runi = SD_R(0.0);
    return v;
}

/* Half kick of every particle with its force (v(t + dt) from v(t + dt/2));
 * with `drift`, the next step's half kick and drift follow in the same pass
 * (velocity Verlet; the same operations in the same order as separate
 * passes, as the general solver's sd_cpu_gather_kick_drift). */
static void sd_grid_kick(sd_world *w, int kicks, int drift)
{
    sd_grid_state *g = w->grid_state;
    sd_grid_part *part = g->part;
    const sd_grid_kind *kinds = g->kinds;
    const sd_vec3 *ft = g->ft;
    size_t n = g->n;
    sd_real dt = w->dt;
    sd_vec3 grav = w->gravity;
SD_PARALLEL_FOR
    for (size_t k = 0; k < n; ++k)
        sd_grid_kick_item(part, kinds, ft, k, kicks, drift, grav, dt);
}

sd_grid_blocks sd_grid_blocks_of(const sd_grid_state *g)
{
    sd_grid_blocks b;
    b.nx = g->nx;
    b.ny = g->ny;
    b.nz = g->nz;
    b.reach = g->reach;
    b.slab = g->slab;
    b.nslab = g->nslab;
    b.nband = g->nband;
    b.rowocc = g->rowocc;
    return b;
}

/* Contact forces of every particle. Each touching pair is evaluated once, by
 * its owner (stencil.h), which writes to its own particle and to partners
 * at most `reach` cells away: up in z (dz >= 0) and either way in y. The
 * inner grid is cut into blocks `reach` cells thick in z and in y; a block
 * writes only to itself, the next z slab and the neighbouring y bands, so
 * blocks of one colour — (z slab mod 2, y band mod 3), six colours — never
 * touch the same particle and run in parallel, colour after colour. Each
 * particle receives its contributions in an order fixed by the blocks, not
 * by the threads: the same bits for any thread count, without atomics.
 * Particles without a cell follow, serially; then the wall totals are summed
 * in block order. */
static void sd_grid_forces(sd_world *w)
{
    sd_grid_state *g = w->grid_state;
    sd_grid_view v = sd_grid_view_of(w);
    size_t n = g->n;
    int nw = g->nwalls;
    g->epoch ^= SD_GRID_TAG_EPOCH;
    uint32_t epoch = g->epoch;
    sd_vec3 *ft = g->ft;
SD_PARALLEL_FOR
    for (size_t k = 0; k < 2 * n; ++k)
        ft[k] = sd_v3_zero();
    if (v.occ) {
        /* the occupancy bits of the kernel's equal-sphere path: cell
         * home[k] holds k (one bit per cell; serial, about 1 % of a step) */
        uint64_t *occ = g->occ;
        const uint32_t *home = g->home;
        memset(occ, 0, g->nocc * sizeof *occ);
        for (size_t k = 0; k < n; ++k)
            if (home[k] != SD_GRID_OVER)
                occ[home[k] >> 6] |= (uint64_t)1 << (home[k] & 63u);
    }
    sd_grid_blocks b = sd_grid_blocks_of(g);
    long nblock = b.nslab * b.nband, overflows = 0;
    for (size_t e = 0; e < (size_t)(nblock + 1) * (size_t)nw * 2; ++e)
        g->slab_wall[e] = sd_v3_zero();
    for (int colour = 0; colour < 6; ++colour) {
        long nb = sd_grid_colour_count(&b, colour);
SD_PRAGMA(omp parallel for schedule(dynamic, 1) num_threads(w->threads) if (w->parallel) reduction(+ : overflows))
        for (long e = 0; e < nb; ++e) {
            long s, t;
            sd_grid_colour_block(&b, colour, e, &s, &t);
            sd_grid_acc a = sd_grid_block_acc(ft, g->tag, g->ds, g->slab_wall, (size_t)(s * b.nband + t), nw, epoch);
            overflows += sd_grid_block_forces(&b, &v, &a, s, t);
        }
    }
    if (g->nover) {
        /* particles that lost a cell conflict: serially, in storage order */
        sd_grid_acc a = sd_grid_block_acc(ft, g->tag, g->ds, g->slab_wall, (size_t)nblock, nw, epoch);
        overflows += sd_grid_homeless_all(&v, &a, g->over, g->nover);
    }
    g->info.slot_overflows += overflows;
    /* springs of contacts that ended (not stamped this step) are forgotten,
     * as in the general engine */
    uint32_t *tag = g->tag;
    int used_max = g->info.slots_used_max;
SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel) reduction(max : used_max))
    for (size_t k = 0; k < n; ++k) {
        int used = sd_grid_sweep_item(tag, k, epoch);
        if (used > used_max)
            used_max = used;
    }
    g->info.slots_used_max = used_max;
    /* wall totals (the world's wall info, stats.csv, summary.txt): only the
     * grid's own copies of the world's walls, in world order */
    for (int k = 0; k < nw; ++k)
        sd_grid_wall_total(g->slab_wall, nblock, nw, k, &w->walls[k].force, &w->walls[k].torque);
}

/* Seed 001 eq. 11, first term: dt <= pi/5 sqrt(m/k) for the lightest
 * particle and the stiffest linear pair (the Hertz law has no constant k:
 * the world's own contact-duration check covers it). */
static double sd_grid_dt_limit(const sd_world *w)
{
    const sd_grid_state *g = w->grid_state;
    double mmin = INFINITY, kmax = 0;
    for (size_t k = 0; k < g->nkinds; ++k)
        if (g->kinds[k].inv_mass > 0)
            mmin = fmin(mmin, 1.0 / (double)g->kinds[k].inv_mass);
    if (g->pour.active) {
        double r = g->pour.def.radius;
        mmin = fmin(mmin, w->materials[g->pour.def.material].def.density * 4.0 / 3.0 * SD_PI_D * r * r * r);
    }
    size_t nm = w->material_count;
    for (size_t e = 0; e < nm * nm; ++e)
        if (sd_law_traits(w->mix[e].law) & SD_LAW_IS_LINEAR) /* a constant k_n (the law table) */
            kmax = fmax(kmax, (double)w->mix[e].kn);
    if (!(kmax > 0) || !isfinite(mmin))
        return INFINITY;
    return SD_PI_D / 5.0 * sqrt(mmin / kmax);
}

/* After a failed step (sd_grid_fail) the particles hold that step's drift
 * but the forces of the step before: stepping on would integrate with the
 * wrong forces, so the world refuses (the statistics still read it). */
static sd_status sd_grid_refuse_failed(const sd_world *w, sd_error *err)
{
    const sd_grid_state *g = w->grid_state;
    if (g && g->info.failed_step)
        return sd_error_set(err, SD_ERR_PHYSICS, "", 0, "",
                            "the grid solver stopped at step %ld and cannot go on; build the world again",
                            g->info.failed_step);
    return SD_OK;
}

sd_status sd_grid_prepare(sd_world *w, sd_error *err)
{
    sd_status st = sd_grid_refuse_failed(w, err);
    if (st != SD_OK)
        return st;
    st = sd_world_mix_materials(w, err);
    if (st != SD_OK)
        return st;
    st = sd_world_check_params(w, err);
    if (st != SD_OK)
        return st;
    if (w->dim2)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.solver",
                            "solver grid is three-dimensional; use solver cells in dimension 2");
    if (!sd_grid_state_get(w))
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    st = sd_grid_absorb(w, err); /* the world's spheres become the solver's */
    if (st != SD_OK)
        return st;
    st = sd_grid_setup(w, err);
    if (st != SD_OK)
        return st;
    sd_grid_state *g = w->grid_state;
    double lim = sd_grid_dt_limit(w);
    g->info.dt_contact_limit = lim;
    if ((double)w->dt > lim)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.dt",
                            "time step %g s above the limit pi/5 sqrt(m/k) = %g s of eq. 11 of [Naderi 2024]",
                            (double)w->dt, lim);
    if (g->pour.active) {
        const sd_grid_pour_def *d = &g->pour.def;
        if (!(d->height - d->radius >= (double)g->dom_lo.z && d->height + d->radius <= (double)g->dom_hi.z))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "pour",
                                "pour height %g m must keep the sheet inside the box (z in [%g, %g])", d->height,
                                (double)g->dom_lo.z, (double)g->dom_hi.z);
    }
    st = sd_grid_place_all(w, err);
    if (st != SD_OK)
        return st;
    sd_grid_forces(w);
    w->dirty = 0;
    w->prepared = 1;
    return SD_OK;
}

/* ---- the step on the device (backend cuda) ------------------------------------------ */

/* The device's copy of the state, from the host arrays / back to them. */
static sd_status sd_grid_dev_put(sd_world *w, sd_error *err)
{
    return sd_cuda_grid_upload(w->grid_state, w->mix, (int)w->material_count, err);
}

static sd_status sd_grid_dev_get(sd_world *w, sd_error *err) { return sd_cuda_grid_read_back(w->grid_state, err); }

/* The force pass on the device (sd_grid_forces' stages), the wall totals
 * into the world's walls. */
static sd_status sd_grid_dev_forces(sd_world *w, sd_error *err)
{
    sd_grid_state *g = w->grid_state;
    sd_grid_view v = sd_grid_view_of(w);
    g->epoch ^= SD_GRID_TAG_EPOCH;
    int nw = g->nwalls;
    sd_vec3 *wf = g->slab_wall, *wt = g->slab_wall + nw; /* host scratch: the host pass is not run */
    sd_status st = sd_cuda_grid_forces(g, &v, wf, wt, err);
    if (st != SD_OK)
        return st;
    for (int k = 0; k < nw; ++k) {
        w->walls[k].force = wf[k];
        w->walls[k].torque = wt[k];
    }
    return SD_OK;
}

/* The rebinning on the device; what it leaves to the host (removals, a
 * NaN, eq. 11) the host's sd_grid_rebin does on the state read back. */
static sd_status sd_grid_dev_rebin(sd_world *w, sd_error *err)
{
    int host = 0;
    sd_status st = sd_cuda_grid_rebin(w->grid_state, w->dt, &host, err);
    if (st != SD_OK || !host)
        return st;
    if ((st = sd_grid_dev_get(w, err)) != SD_OK)
        return st;
    if ((st = sd_grid_rebin(w, err)) != SD_OK) {
        sd_grid_fail(w, w->step + 1);
        return st;
    }
    return sd_grid_dev_put(w, err);
}

/* sd_grid_step's loop with the state on the device for the whole call
 * (uploaded at its start, read back at its end, and around the host's
 * stages: an outlet that opens, a sheet poured). The same stages in the
 * same order as the host loop below, through the same items (blocks.h):
 * the same bits. */
static sd_status sd_grid_step_device(sd_world *w, long nsteps, sd_error *err)
{
    sd_grid_state *g = w->grid_state;
    sd_status st = sd_grid_dev_put(w, err);
    for (long s = 0; s < nsteps && st == SD_OK; ++s) {
        int fused = !g->pour.active;
        /* the host's stages change the host arrays: the device's state
         * comes back first, and goes up again after */
        int opens = sd_grid_outlet_due(w), pours = g->pour.active && sd_grid_pour_due(w);
        if ((opens || pours) && (st = sd_grid_dev_get(w, err)) != SD_OK)
            break;
        if (opens)
            sd_grid_outlet_step(w); /* the holed walls */
        if (pours && (st = sd_grid_pour_step(w, err)) != SD_OK) {
            sd_grid_fail(w, w->step + 1);
            return st;
        }
        if ((opens || pours) && (st = sd_grid_dev_put(w, err)) != SD_OK)
            break;
        if (!fused || s == 0)
            st = sd_cuda_grid_kick(g, 1, 1, w->gravity, w->dt, err);
        if (st == SD_OK && (st = sd_grid_dev_rebin(w, err)) != SD_OK)
            return st; /* the host's rebin failed (sd_grid_fail done), or the device did */
        if (st == SD_OK)
            st = sd_grid_dev_forces(w, err);
        if (st == SD_OK)
            st = fused && s + 1 < nsteps ? sd_cuda_grid_kick(g, 2, 1, w->gravity, w->dt, err)
                                         : sd_cuda_grid_kick(g, 1, 0, w->gravity, w->dt, err);
        if (st != SD_OK)
            break;
        w->step++;
        w->time = (double)w->step * (double)w->dt;
    }
    if (st != SD_OK)
        return st;
    return sd_grid_dev_get(w, err);
}

sd_status sd_grid_step(sd_world *w, long nsteps, sd_error *err)
{
    sd_status st;
    if ((st = sd_grid_refuse_failed(w, err)) != SD_OK)
        return st;
    if (!w->prepared && (st = sd_grid_prepare(w, err)) != SD_OK)
        return st;
    if (w->backend != &sd_backend_cpu)
        return sd_grid_step_device(w, nsteps, err);
    sd_grid_state *g = w->grid_state;
    for (long s = 0; s < nsteps; ++s) {
        /* without pouring, this step's last kick and the next step's kick
         * and drift run as one pass (the same bits as separate passes) */
        int fused = !g->pour.active;
        if (g->outlet_pending)
            sd_grid_outlet_step(w);
        if (g->pour.active && (st = sd_grid_pour_step(w, err)) != SD_OK) {
            sd_grid_fail(w, w->step + 1); /* a sheet may be half poured */
            return st;
        }
        if (!fused || s == 0)
            sd_grid_kick(w, 1, 1);                 /* v(t + dt/2), x(t + dt) */
        if ((st = sd_grid_rebin(w, err)) != SD_OK) { /* cells at t + dt */
            sd_grid_fail(w, w->step + 1);          /* cells back in step with the moved particles */
            return st;
        }
        sd_grid_forces(w);                         /* F(t + dt) */
        if (fused && s + 1 < nsteps)
            sd_grid_kick(w, 2, 1);                 /* v(t + dt); v(t + 3dt/2), x(t + 2dt) */
        else
            sd_grid_kick(w, 1, 0);                 /* v(t + dt) */
        w->step++;
        w->time = (double)w->step * (double)w->dt;
    }
    return SD_OK;
}

/* ---- statistics ---------------------------------------------------------------- */

/* One particle pair of the statistics: counted when the spheres overlap. */
static void sd_grid_stats_pair(const sd_world *w, size_t k, size_t j, long *contacts, double *energy,
                               double *max_overlap_ratio)
{
    const sd_grid_state *g = w->grid_state;
    const sd_grid_part *part = g->part;
    const sd_grid_kind *kk = &g->kinds[part[k].kind], *kj = &g->kinds[part[j].kind];
    sd_real d = sd_v3_norm(sd_v3_sub(part[k].x, part[j].x));
    sd_real delta = kk->radius + kj->radius - d;
    if (!(delta > 0))
        return;
    (*contacts)++;
    const sd_pair_params *prm = &w->mix[(size_t)kk->material * w->material_count + (size_t)kj->material];
    sd_vec3 s = sd_grid_pair_spring(g->tag, g->ds, k, j, part);
    double kn = (double)prm->kn, kt = (double)(prm->kt_ratio * prm->kn);
    if (sd_law_traits(prm->law) & SD_LAW_IS_LINEAR)
        *energy += 0.5 * kn * (double)(delta * delta) + 0.5 * kt * (double)sd_v3_norm2(s);
    double ratio = (double)(delta / sd_min(kk->radius, kj->radius));
    if (ratio > *max_overlap_ratio)
        *max_overlap_ratio = ratio;
}

/* A read-only pass in a fixed order (storage order, then the overflow list
 * in its order): the same sums for any thread count. A particle in a cell
 * scans the stencil around the cell it holds (home[k], which cell[] agrees
 * with), so the pass reads inside the grid even when where[] has moved on;
 * its pairs with other cell holders count once, from the lower stable id.
 * A particle without a cell (a conflict) is in no cell a stencil reads, so
 * it counts its pairs with every cell holder around where[k] and with the
 * overflow particles after it. Particles outside the inner grid (only after
 * a failed step, sd_grid_fail) hold no cell and are not listed: their
 * pairs are not counted. */
void sd_grid_contact_stats(const sd_world *w, long *contacts, long *wall_contacts, double *energy,
                           double *max_overlap_ratio)
{
    const sd_grid_state *g = w->grid_state;
    *contacts = 0;
    *wall_contacts = 0;
    *energy = 0;
    *max_overlap_ratio = 0;
    if (!g || !g->ncell || !w->prepared)
        return;
    long nxy = g->nx * g->ny;
    const sd_grid_part *part = g->part;
    for (size_t k = 0; k < g->n; ++k) {
        /* walls: the slots tagged with a wall are the touching ones */
        const uint32_t *tag = g->tag + k * SD_GRID_SLOTS;
        for (int s = 0; s < SD_GRID_SLOTS; ++s)
            if (tag[s] & SD_GRID_TAG_WALL)
                (*wall_contacts)++;
        if (g->home[k] == SD_GRID_OVER)
            continue;
        long c = (long)g->home[k];
        for (int dz = -g->reach; dz <= g->reach; ++dz)
            for (int dy = -g->reach; dy <= g->reach; ++dy)
                for (int dx = -g->reach; dx <= g->reach; ++dx) {
                    int32_t j = g->cell[c + dz * nxy + dy * g->nx + dx];
                    if (j < 0 || part[j].id <= part[k].id)
                        continue;
                    sd_grid_stats_pair(w, k, (size_t)j, contacts, energy, max_overlap_ratio);
                }
    }
    for (size_t e = 0; e < g->nover; ++e) {
        size_t k = g->over[e];
        if (g->where[k] == SD_GRID_OUTSIDE)
            continue;
        long c = (long)g->where[k];
        for (int dz = -g->reach; dz <= g->reach; ++dz)
            for (int dy = -g->reach; dy <= g->reach; ++dy)
                for (int dx = -g->reach; dx <= g->reach; ++dx) {
                    int32_t j = g->cell[c + dz * nxy + dy * g->nx + dx];
                    if (j >= 0)
                        sd_grid_stats_pair(w, k, (size_t)j, contacts, energy, max_overlap_ratio);
                }
        for (size_t e2 = e + 1; e2 < g->nover; ++e2)
            sd_grid_stats_pair(w, k, g->over[e2], contacts, energy, max_overlap_ratio);
    }
}
