/* grid.c — the grid solver's state: set-up of the uniform grid over the
 * domain, binning of particles into cells, cell conflicts, and removal of
 * particles that left the domain (seed 001 §3.1, §3.2.1).
 *
 * Invariants (grid.h): one particle per cell; a particle whose cell is taken
 * goes to the overflow list, in storage order, and is still seen by every
 * stencil (never lost); storage order is stable-id order and removals keep
 * it, so "first in storage order" is a deterministic tie-break.
 *
 * Cell size (docs/grid-solver.md): the edge is R_min, as in the seed's
 * published code, not the paper's 2R/sqrt(3). Two centres in one cell are
 * closer than sqrt(3) R, i.e. they overlap by more than 13 % of the
 * diameter, so conflicts only come with a broken simulation; with the
 * paper's edge any overlapping pair may share a cell. A contact between
 * radii R_i, R_j (distance < R_i + R_j <= 2 R_max) spans at most
 * ceil(2 R_max / R_min) cells on every axis: that is the stencil's reach
 * (2, the 5x5x5 stencil, for equal spheres).
 */
#include "grid/grid.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "world/world.h"

#define SD_GRID_COOKIE 0x6D1D

sd_grid_state *sd_grid_state_get(sd_world *w)
{
    if (!w->grid_state)
        w->grid_state = sd_calloc(1, sizeof(sd_grid_state));
    return w->grid_state;
}

void sd_grid_state_free(sd_grid_state *g)
{
    if (!g)
        return;
    sd_free(g->cell);
    sd_free(g->where);
    sd_free(g->home);
    sd_free(g->tag);
    sd_free(g->ds);
    sd_free(g->over);
    sd_free(g->walls);
    sd_free(g);
}

sd_grid_pour_def sd_grid_pour_def_default(void)
{
    sd_grid_pour_def d;
    memset(&d, 0, sizeof d);
    d.layers_per_second = 4;   /* seed 001 Table 2, Case I */
    d.vz_range = 0.5;          /* seed 001 §4.1 */
    d.vh_range = 0.1;
    d.cookie = SD_GRID_COOKIE;
    return d;
}

sd_status sd_grid_set_pour(sd_world *w, const sd_grid_pour_def *d, sd_error *err)
{
    if (!d || d->cookie != SD_GRID_COOKIE)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "pour", "pour def not made by sd_grid_pour_def_default");
    if (!(d->radius > 0) || d->material < 0 || (size_t)d->material >= w->material_count)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "pour", "pour needs a radius > 0 and a known material");
    if (!(d->layers_per_second > 0) || d->vz_range < 0 || d->vh_range < 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "pour", "pour needs a feed rate > 0 and velocity ranges >= 0");
    sd_grid_state *g = sd_grid_state_get(w);
    if (!g)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    memset(&g->pour, 0, sizeof g->pour);
    g->pour.active = 1;
    g->pour.def = *d;
    g->pour.rng = sd_rng_seed(w->def.seed ^ 0x9017A9E5u);
    g->pour.next_time = d->start_time;
    w->prepared = 0;
    return SD_OK;
}

void sd_grid_get_info(const sd_world *w, sd_grid_info *info)
{
    memset(info, 0, sizeof *info);
    const sd_grid_state *g = w->grid_state;
    if (!g || w->def.solver != SD_SOLVER_GRID)
        return;
    *info = g->info;
    info->active = g->ncell > 0;
    info->cell = (double)g->h;
    info->reach = g->reach;
    info->nx = g->nx;
    info->ny = g->ny;
    info->nz = g->nz;
    info->in_overflow = g->nover;
    info->poured = g->pour.poured;
    info->pour_layers = g->pour.layers;
    info->pour_skipped = g->pour.skipped;
    info->bytes = g->ncell * sizeof(int32_t) +
                  g->pcap * (2 * sizeof(uint32_t) + SD_GRID_SLOTS * (sizeof(uint32_t) + sizeof(sd_vec3))) +
                  g->over_cap * sizeof(uint32_t) + (size_t)g->nwalls * sizeof(sd_grid_wall);
}

/* ---- set-up ----------------------------------------------------------------- */

sd_status sd_grid_reserve(sd_grid_state *g, size_t n)
{
    if (n <= g->pcap)
        return SD_OK;
    size_t cap = n + n / 4 + 64, old = g->pcap;
    uint32_t *where = sd_realloc(g->where, cap * sizeof *where);
    if (!where)
        return SD_ERR_MEMORY;
    g->where = where;
    uint32_t *home = sd_realloc(g->home, cap * sizeof *home);
    if (!home)
        return SD_ERR_MEMORY;
    g->home = home;
    uint32_t *tag = sd_realloc(g->tag, cap * SD_GRID_SLOTS * sizeof *tag);
    if (!tag)
        return SD_ERR_MEMORY;
    g->tag = tag;
    sd_vec3 *ds = sd_realloc(g->ds, cap * SD_GRID_SLOTS * sizeof *ds);
    if (!ds)
        return SD_ERR_MEMORY;
    g->ds = ds;
    /* new particles start with empty slots and no cell */
    memset(g->tag + old * SD_GRID_SLOTS, 0, (cap - old) * SD_GRID_SLOTS * sizeof *tag);
    memset(g->ds + old * SD_GRID_SLOTS, 0, (cap - old) * SD_GRID_SLOTS * sizeof *ds);
    for (size_t k = old; k < cap; ++k)
        g->home[k] = SD_GRID_OVER;
    g->pcap = cap;
    return SD_OK;
}

sd_status sd_grid_setup(sd_world *w, sd_error *err)
{
    sd_grid_state *g = sd_grid_state_get(w);
    if (!g)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    const sd_particles *p = &w->p;

    /* the domain: the union of the box walls */
    int boxes = 0;
    for (size_t k = 0; k < w->wall_count; ++k) {
        const sd_wall *wl = &w->walls[k];
        if (wl->kind != SD_WALL_BOX)
            continue;
        g->dom_lo = boxes ? sd_v3_min(g->dom_lo, wl->lo) : wl->lo;
        g->dom_hi = boxes ? sd_v3_max(g->dom_hi, wl->hi) : wl->hi;
        boxes++;
    }
    if (!boxes)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.solver",
                            "solver grid needs a box wall: the box is the grid's domain");

    /* radii: present particles and the ones to be poured */
    sd_real rmin = (sd_real)INFINITY, rmax = 0;
    for (size_t k = 0; k < p->n; ++k) {
        rmin = sd_min(rmin, p->radius[k]);
        rmax = sd_max(rmax, p->radius[k]);
    }
    if (g->pour.active) {
        rmin = sd_min(rmin, (sd_real)g->pour.def.radius);
        rmax = sd_max(rmax, (sd_real)g->pour.def.radius);
    }
    if (!(rmax > 0))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "particles",
                            "solver grid needs particles (or a pour) to size its cells");
    /* polydisperse extension (seed 001 §3.2.1): the stencil widens with
     * R_max / R_min; beyond 2 its cost (9^3 cells and up) defeats the method */
    if (rmax > SD_R(2.0) * rmin)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.solver",
                            "solver grid supports radius ratios R_max/R_min up to 2 (stencil 9x9x9); "
                            "this scene has %g (R_min %g m, R_max %g m): use solver cells",
                            (double)(rmax / rmin), (double)rmin, (double)rmax);
    for (size_t k = 0; k < p->n; ++k)
        if (p->shape[k] >= 0)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.solver",
                                "solver grid simulates spheres only (particle %zu is not a sphere)", k);
    g->h = rmin;
    g->rmax = rmax;
    g->reach = (int)ceil(2.0 * (double)rmax / (double)rmin - 1e-12);
    if (g->reach < 2)
        g->reach = 2;
    int halo = g->reach + 1;
    sd_vec3 ext = sd_v3_sub(g->dom_hi, g->dom_lo);
    double cx = ceil((double)(ext.x / g->h)) + 2 * halo, cy = ceil((double)(ext.y / g->h)) + 2 * halo,
           cz = ceil((double)(ext.z / g->h)) + 2 * halo;
    if (cx * cy * cz >= 4.0e9)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "walls",
                            "the grid over the box would have %.3g cells of %g m (at most 4e9)", cx * cy * cz,
                            (double)g->h);
    g->nx = (long)cx;
    g->ny = (long)cy;
    g->nz = (long)cz;
    g->lo = sd_v3_sub(g->dom_lo, sd_v3((sd_real)halo * g->h, (sd_real)halo * g->h, (sd_real)halo * g->h));
    size_t ncell = (size_t)g->nx * (size_t)g->ny * (size_t)g->nz;
    if (ncell != g->ncell || !g->cell) {
        int32_t *cell = sd_realloc(g->cell, ncell * sizeof *cell);
        if (!cell)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for %zu grid cells", ncell);
        g->cell = cell;
        g->ncell = ncell;
    }
    if (p->n >= 0x7fffffffu)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "particles", "solver grid holds at most 2^31 - 1 particles");
    if (sd_grid_reserve(g, p->n + 1))
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");

    /* walls as the kernel sees them; the outlet holes every box floor */
    sd_grid_wall *gw = sd_realloc(g->walls, (w->wall_count ? w->wall_count : 1) * sizeof *gw);
    if (!gw)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    g->walls = gw;
    g->nwalls = (int)w->wall_count;
    for (size_t k = 0; k < w->wall_count; ++k) {
        const sd_wall *wl = &w->walls[k];
        memset(&gw[k], 0, sizeof gw[k]);
        gw[k].kind = wl->kind == SD_WALL_PLANE ? SD_GRID_WALL_PLANE : SD_GRID_WALL_BOX;
        gw[k].point = wl->point;
        gw[k].normal = wl->normal;
        gw[k].lo = wl->lo;
        gw[k].hi = wl->hi;
        gw[k].open_faces = wl->open_faces;
        gw[k].material = wl->material;
        if (g->outlet && wl->kind == SD_WALL_BOX) {
            gw[k].holed = 1;
            gw[k].hx0 = g->hx0;
            gw[k].hx1 = g->hx1;
            gw[k].hy0 = g->hy0;
            gw[k].hy1 = g->hy1;
        }
    }
    return SD_OK;
}

uint32_t sd_grid_cell_of(const sd_grid_state *g, sd_vec3 x)
{
    double fx = (double)((x.x - g->lo.x) / g->h), fy = (double)((x.y - g->lo.y) / g->h),
           fz = (double)((x.z - g->lo.z) / g->h);
    double r = (double)g->reach;
    /* written so that NaN fails too */
    if (!(fx >= r && fx < (double)g->nx - r && fy >= r && fy < (double)g->ny - r && fz >= r &&
          fz < (double)g->nz - r))
        return SD_GRID_OUTSIDE;
    long ix = (long)fx, iy = (long)fy, iz = (long)fz;
    return (uint32_t)((iz * g->ny + iy) * g->nx + ix);
}

/* Takes cell where[k] for k, or puts k in the overflow list (a conflict). */
static sd_status sd_grid_claim(sd_grid_state *g, size_t k)
{
    uint32_t c = g->where[k];
    if (g->cell[c] < 0) {
        g->cell[c] = (int32_t)k;
        g->home[k] = c;
        return SD_OK;
    }
    if (g->nover == g->over_cap) {
        size_t cap = g->over_cap * 2 + 64;
        uint32_t *o = sd_realloc(g->over, cap * sizeof *o);
        if (!o)
            return SD_ERR_MEMORY;
        g->over = o;
        g->over_cap = cap;
    }
    g->over[g->nover++] = (uint32_t)k;
    if (g->home[k] != SD_GRID_OVER)
        g->info.conflicts++; /* a new conflict (not one carried from the last step) */
    g->home[k] = SD_GRID_OVER;
    return SD_OK;
}

static void sd_grid_note_overflow(sd_grid_state *g)
{
    if (g->nover > g->info.max_overflow)
        g->info.max_overflow = g->nover;
}

void sd_grid_remove_outside(sd_world *w)
{
    sd_grid_state *g = w->grid_state;
    sd_particles *p = &w->p;
    size_t n = p->n, m = 0;
    for (size_t k = 0; k < n; ++k) {
        if (g->where[k] == SD_GRID_OUTSIDE) {
            g->info.removed++;
            if (p->inv_mass[k] > 0)
                g->info.removed_mass += 1.0 / (double)p->inv_mass[k];
            sd_vec3 x = p->x[k];
            if (g->outlet && x.z < g->dom_lo.z && x.x > g->hx0 && x.x < g->hx1 && x.y > g->hy0 && x.y < g->hy1)
                g->info.removed_outlet++;
            continue;
        }
        if (m != k) {
#define SD_X_MOVE(type, name, unit, doc) p->name[m] = p->name[k];
            SD_PARTICLE_FIELDS(SD_X_MOVE)
#undef SD_X_MOVE
            g->where[m] = g->where[k];
            g->home[m] = g->home[k];
            memcpy(g->tag + m * SD_GRID_SLOTS, g->tag + k * SD_GRID_SLOTS, SD_GRID_SLOTS * sizeof *g->tag);
            memcpy(g->ds + m * SD_GRID_SLOTS, g->ds + k * SD_GRID_SLOTS, SD_GRID_SLOTS * sizeof *g->ds);
        }
        ++m;
    }
    for (size_t k = m; k < n; ++k) {
        memset(g->tag + k * SD_GRID_SLOTS, 0, SD_GRID_SLOTS * sizeof *g->tag);
        memset(g->ds + k * SD_GRID_SLOTS, 0, SD_GRID_SLOTS * sizeof *g->ds);
        g->home[k] = SD_GRID_OVER;
    }
    p->n = m;
}

sd_status sd_grid_place_all(sd_world *w, sd_error *err)
{
    sd_grid_state *g = w->grid_state;
    sd_particles *p = &w->p;
    for (size_t c = 0; c < g->ncell; ++c)
        g->cell[c] = -1;
    g->nover = 0;
    size_t out = 0;
    for (size_t k = 0; k < p->n; ++k) {
        g->where[k] = sd_grid_cell_of(g, p->x[k]);
        out += g->where[k] == SD_GRID_OUTSIDE;
    }
    if (out) {
        sd_grid_remove_outside(w);
        for (size_t k = 0; k < p->n; ++k)
            g->where[k] = sd_grid_cell_of(g, p->x[k]);
    }
    for (size_t k = 0; k < p->n; ++k) {
        g->home[k] = g->where[k]; /* any conflict here counts as a new one */
        if (sd_grid_claim(g, k))
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (cell conflicts)");
    }
    sd_grid_note_overflow(g);
    w->parallel = w->threads > 1 && p->n >= SD_PARALLEL_MIN_PARTICLES;
    return SD_OK;
}

#define SD_PARALLEL_FOR_REDUCE_MAX(v) \
    SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel) reduction(max : v))

sd_status sd_grid_rebin(sd_world *w, sd_error *err)
{
    sd_grid_state *g = w->grid_state;
    sd_particles *p = &w->p;
    size_t n = p->n;
    uint32_t *where = g->where, *home = g->home;
    int32_t *cell = g->cell;

    /* A: the new cell of every particle, the fastest speed, NaN */
    double vmax2 = 0;
    int bad = 0;
SD_PARALLEL_FOR_REDUCE_MAX(vmax2)
    for (size_t k = 0; k < n; ++k) {
        where[k] = sd_grid_cell_of(g, p->x[k]);
        double v2 = (double)sd_v3_norm2(p->v[k]);
        if (v2 > vmax2 || v2 != v2)
            vmax2 = v2 != v2 ? (double)INFINITY : v2;
    }
    if (!isfinite(vmax2))
        bad = 1;
    for (size_t k = 0; k < n && !bad; ++k)
        if (where[k] == SD_GRID_OUTSIDE && !isfinite((double)(p->x[k].x + p->x[k].y + p->x[k].z)))
            bad = 1;
    if (bad)
        return sd_error_set(err, SD_ERR_PHYSICS, "", 0, "", "a particle state became NaN or infinite at step %ld "
                            "(time step too large for the stiffness?)", w->step + 1);
    g->info.max_speed = sqrt(vmax2);
    /* seed 001 eq. 11, second term: no particle may cross more than one cell
     * per step. Checked every step; a violation is an error (the time step is
     * never changed behind the user's back, so runs stay reproducible). */
    double dt = (double)w->dt, hh = (double)g->h;
    if (vmax2 * dt * dt > hh * hh)
        return sd_error_set(err, SD_ERR_PHYSICS, "", 0, "simulation.dt",
                            "seed 001 eq. 11 violated at step %ld: a particle moves %.3g m/s, so dt %g s "
                            "carries it %.3g cells in one step (at most 1); use dt <= %.3g s",
                            w->step + 1, sqrt(vmax2), dt, sqrt(vmax2) * dt / hh, hh / sqrt(vmax2));

    /* B: particles that changed cell leave their old one (each clears its
     * own cell: no two threads touch the same memory) */
SD_PARALLEL_FOR
    for (size_t k = 0; k < n; ++k)
        if (home[k] != SD_GRID_OVER && home[k] != where[k])
            cell[home[k]] = -1;

    /* C: in storage order, movers and overflow particles take their new
     * cell; a taken cell is a conflict (the particle that already holds it,
     * or the one first in storage order, keeps it) */
    size_t out = 0;
    g->nover = 0;
    for (size_t k = 0; k < n; ++k) {
        if (home[k] == where[k])
            continue;
        if (where[k] == SD_GRID_OUTSIDE) {
            home[k] = SD_GRID_OVER;
            out++;
            continue;
        }
        if (sd_grid_claim(g, k))
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (cell conflicts)");
    }
    if (out) {
        /* storage indices shift: place everything again */
        sd_grid_remove_outside(w);
        return sd_grid_place_all(w, err);
    }
    sd_grid_note_overflow(g);
    return SD_OK;
}
