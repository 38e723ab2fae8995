/* grid.c — the grid solver's state: set-up of the uniform grid over the
 * domain, binning of particles into cells, cell conflicts, and removal of
 * particles that left the domain (seed 001 §3.1, §3.2.1).
 *
 * Invariants (grid.h): one particle per cell; a particle whose cell is taken
 * goes to the overflow list, in storage order, and is still seen by every
 * stencil (never lost); storage order is stable-id order and removals keep
 * it, so "first in storage order" is a deterministic tie-break.
 *
 * The particle state is the solver's own (grid.h): sd_grid_absorb moves the
 * world's spheres into it array by array, freeing each world array as soon
 * as it is copied, so the two copies never coexist in full.
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

#include "backend/cpu/parallel.h"
#include "backend/cuda/cuda.h"
#include "core/alloc.h"
#include "core/error.h"
#include "world/world.h"

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
    sd_free(g->part);
    sd_free(g->ft);
    sd_free(g->kinds);
    sd_free(g->khash);
    sd_free(g->where);
    sd_free(g->home);
    sd_free(g->tag);
    sd_free(g->ds);
    sd_free(g->over);
    sd_free(g->walls);
    sd_free(g->rowocc);
    sd_free(g->occ);
    sd_free(g->slab_wall);
    sd_cuda_grid_free(g);
    sd_free(g);
}

sd_grid_pour_def sd_grid_pour_def_default(void) { return sd_pour_def_default(); }

sd_status sd_grid_set_pour(sd_world *w, const sd_grid_pour_def *d, sd_error *err)
{
    return sd_world_set_pour(w, d, err);
}

sd_status sd_grid_pour_set(sd_world *w, const sd_pour_def *d, sd_error *err)
{
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
    info->outlet_open = g->outlet;
    info->outlet_time = g->outlet || g->outlet_pending ? g->outlet_time : 0.0;
    info->outlet_x0 = (double)g->hx0;
    info->outlet_x1 = (double)g->hx1;
    info->outlet_y0 = (double)g->hy0;
    info->outlet_y1 = (double)g->hy1;
    const sd_real lo[3] = {g->dom_lo.x, g->dom_lo.y, g->dom_lo.z}, hi[3] = {g->dom_hi.x, g->dom_hi.y, g->dom_hi.z};
    for (int a = 0; a < 3; ++a) {
        info->domain_lo[a] = (double)lo[a];
        info->domain_hi[a] = (double)hi[a];
    }
    info->bytes = g->ncell * sizeof(int32_t) + g->pcap * (sizeof(sd_grid_part) + 2 * sizeof(sd_vec3)) +
                  g->pcap * (2 * sizeof(uint32_t) + SD_GRID_SLOTS * (sizeof(uint32_t) + sizeof(sd_vec3))) +
                  g->kcap * sizeof(sd_grid_kind) + g->khcap * sizeof(uint32_t) + g->over_cap * sizeof(uint32_t) +
                  (size_t)g->nwalls * sizeof(sd_grid_wall) + (size_t)(g->nz * g->ny) + g->nocc * sizeof(uint64_t) +
                  (size_t)(g->nslab * g->nband + 1) * (size_t)g->nwalls * 2 * sizeof(sd_vec3);
}

/* ---- set-up ----------------------------------------------------------------- */

/* Grows the particle arrays to hold n particles: exactly n when `exact`
 * (taking over a known number), else with a quarter of head room
 * (pouring). */
/* Grows every per-particle array but the records (the caller grew those,
 * or will: g->part may be NULL here) to cap particles. */
static sd_status sd_grid_grow_rest(sd_grid_state *g, size_t cap)
{
    size_t old = g->pcap;
    sd_vec3 *ft = sd_realloc(g->ft, 2 * cap * sizeof *ft);
    if (!ft)
        return SD_ERR_MEMORY;
    g->ft = ft;
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
    /* new particles start with empty slots, no force and no cell (the
     * springs of an empty slot are never read) */
    memset(g->tag + old * SD_GRID_SLOTS, 0, (cap - old) * SD_GRID_SLOTS * sizeof *tag);
    /* their springs are never read, but the checkpoint holds them: zero, so
     * that two runs of the same scene write the same bits */
    memset(g->ds + old * SD_GRID_SLOTS, 0, (cap - old) * SD_GRID_SLOTS * sizeof *ds);
    memset(g->ft + 2 * old, 0, 2 * (cap - old) * sizeof *ft);
    for (size_t k = old; k < cap; ++k)
        g->home[k] = SD_GRID_OVER;
    g->pcap = cap;
    return SD_OK;
}

/* Grows the particle arrays to hold n particles: exactly n when `exact`
 * (taking over a known number), else with a quarter of head room
 * (pouring). */
static sd_status sd_grid_grow(sd_grid_state *g, size_t n, int exact)
{
    if (n <= g->pcap)
        return SD_OK;
    size_t cap = exact ? n : n + n / 4 + 64;
    sd_grid_part *part = sd_realloc(g->part, cap * sizeof *part);
    if (!part)
        return SD_ERR_MEMORY;
    g->part = part;
    return sd_grid_grow_rest(g, cap);
}

sd_status sd_grid_reserve(sd_grid_state *g, size_t n) { return sd_grid_grow(g, n, 0); }

/* ---- kinds -------------------------------------------------------------------- */

static uint64_t sd_grid_mix64(uint64_t h, sd_real x)
{
    uint64_t b = 0;
    memcpy(&b, &x, sizeof x < sizeof b ? sizeof x : sizeof b);
    h ^= b + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    return h * 0xFF51AFD7ED558CCDull;
}

static uint64_t sd_grid_kind_hash(const sd_grid_kind *k)
{
    uint64_t h = (uint64_t)(uint32_t)k->material * 0xC4CEB9FE1A85EC53ull;
    h = sd_grid_mix64(h, k->radius);
    h = sd_grid_mix64(h, k->inv_mass);
    h = sd_grid_mix64(h, k->inv_inertia.x);
    h = sd_grid_mix64(h, k->inv_inertia.y);
    return sd_grid_mix64(h, k->inv_inertia.z);
}

static int sd_grid_kind_same(const sd_grid_kind *a, const sd_grid_kind *b)
{
    return a->radius == b->radius && a->inv_mass == b->inv_mass && a->material == b->material &&
           a->inv_inertia.x == b->inv_inertia.x && a->inv_inertia.y == b->inv_inertia.y &&
           a->inv_inertia.z == b->inv_inertia.z;
}

/* Index of kind *k in the table, added when new; -1 when out of memory. */
static long sd_grid_kind_index(sd_grid_state *g, const sd_grid_kind *k)
{
    if (2 * (g->nkinds + 1) > g->khcap) {
        size_t cap = g->khcap ? 2 * g->khcap : 64;
        uint32_t *hs = sd_calloc(cap, sizeof *hs);
        if (!hs)
            return -1;
        for (size_t e = 0; e < g->nkinds; ++e) {
            size_t b = (size_t)sd_grid_kind_hash(&g->kinds[e]) & (cap - 1);
            while (hs[b])
                b = (b + 1) & (cap - 1);
            hs[b] = (uint32_t)(e + 1);
        }
        sd_free(g->khash);
        g->khash = hs;
        g->khcap = cap;
    }
    size_t b = (size_t)sd_grid_kind_hash(k) & (g->khcap - 1);
    while (g->khash[b]) {
        if (sd_grid_kind_same(&g->kinds[g->khash[b] - 1], k))
            return (long)g->khash[b] - 1;
        b = (b + 1) & (g->khcap - 1);
    }
    if (g->nkinds == g->kcap) {
        size_t cap = g->kcap ? 2 * g->kcap : 8;
        sd_grid_kind *ks = sd_realloc(g->kinds, cap * sizeof *ks);
        if (!ks)
            return -1;
        g->kinds = ks;
        g->kcap = cap;
    }
    g->kinds[g->nkinds] = *k;
    g->khash[b] = (uint32_t)(g->nkinds + 1);
    return (long)g->nkinds++;
}

sd_status sd_grid_append(sd_grid_state *g, sd_vec3 x, sd_vec3 v, sd_vec3 wv, uint64_t id, const sd_grid_kind *kind)
{
    long kd = sd_grid_kind_index(g, kind);
    if (kd < 0)
        return SD_ERR_MEMORY;
    size_t k = g->n++;
    g->part[k].x = x;
    g->part[k].v = v;
    g->part[k].w = wv;
    g->part[k].id = (uint32_t)id;
    g->part[k].kind = (uint32_t)kd;
    g->ft[2 * k] = sd_v3_zero();
    g->ft[2 * k + 1] = sd_v3_zero();
    g->home[k] = SD_GRID_OVER;
    for (int s = 0; s < SD_GRID_SLOTS; ++s)
        g->tag[k * SD_GRID_SLOTS + (size_t)s] = 0;
    return SD_OK;
}

/* Frees one array of the world's particles (the solver took it over). */
#define SD_GRID_DROP(p, field) \
    do {                       \
        sd_free((p)->field);   \
        (p)->field = NULL;     \
    } while (0)

/* The world's spheres into the solver's state, array by array, so the two
 * copies never coexist in full (the peak is the world's arrays plus the
 * 80-byte records, not plus the whole solver state): the records first,
 * then every world array but force and torque is freed, then the rest of
 * the solver's arrays, then the world's force and torque go. */
sd_status sd_grid_absorb(sd_world *w, sd_error *err)
{
    sd_grid_state *g = w->grid_state;
    sd_particles *p = &w->p;
    if (!p->n)
        return SD_OK;
    for (size_t k = 0; k < p->n; ++k)
        if (p->shape[k] >= 0)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.solver",
                                "solver grid simulates spheres only (particle %zu is not a sphere)", g->n + k);
    if (w->next_id > SD_GRID_MAX_ID)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "particles",
                            "solver grid keys contacts by 30-bit stable ids (at most %u particles ever added)",
                            (unsigned)SD_GRID_MAX_ID);
    size_t n0 = g->n, n = n0 + p->n;
    /* exactly n when taking over a known number, head room when adding */
    size_t cap = n <= g->pcap ? g->pcap : (n0 == 0 ? n : n + n / 4 + 64);
    if (cap > g->pcap) {
        sd_grid_part *part = sd_realloc(g->part, cap * sizeof *part);
        if (!part)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory taking over %zu spheres", p->n);
        g->part = part;
    }
    for (size_t k = 0; k < p->n; ++k) {
        sd_grid_kind kd;
        memset(&kd, 0, sizeof kd);
        kd.radius = p->radius[k];
        kd.inv_mass = p->inv_mass[k];
        kd.inv_inertia = p->inv_inertia[k];
        kd.material = p->material[k];
        long kind = sd_grid_kind_index(g, &kd);
        if (kind < 0)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (particle kinds)");
        sd_grid_part *r = &g->part[n0 + k];
        r->x = p->x[k];
        r->v = p->v[k];
        r->w = p->w[k];
        r->id = (uint32_t)p->id[k];
        r->kind = (uint32_t)kind;
    }
    SD_GRID_DROP(p, x);
    SD_GRID_DROP(p, v);
    SD_GRID_DROP(p, w);
    SD_GRID_DROP(p, q);
    SD_GRID_DROP(p, radius);
    SD_GRID_DROP(p, inv_mass);
    SD_GRID_DROP(p, inv_inertia);
    SD_GRID_DROP(p, x_ref);
    SD_GRID_DROP(p, q_ref);
    SD_GRID_DROP(p, material);
    SD_GRID_DROP(p, shape);
    SD_GRID_DROP(p, id);
    /* the other arrays (the records are already in place) */
    if (cap > g->pcap && sd_grid_grow_rest(g, cap)) {
        size_t lost = p->n;
        sd_particles_free(p); /* half taken over: the world's copy is gone, the run cannot go on */
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory taking over %zu spheres", lost);
    }
    for (size_t k = 0; k < p->n; ++k) {
        g->ft[2 * (n0 + k)] = p->f[k];
        g->ft[2 * (n0 + k) + 1] = p->t[k];
        g->home[n0 + k] = SD_GRID_OVER;
        for (int s = 0; s < SD_GRID_SLOTS; ++s)
            g->tag[(n0 + k) * SD_GRID_SLOTS + (size_t)s] = 0;
    }
    g->n = n0 + p->n;
    sd_particles_free(p);
    w->dirty = 0;
    return SD_OK;
}

/* The tables of the kernel's equal-sphere path (reach 2, stencil.h): the
 * offsets of the 62 cells of the forward half stencil in the kernel's bit
 * order (z, then y, then x), and for each of the SD_GRID_Q^3 sub-cells of
 * the owner's cell the mask of the stencil cells whose nearest point is
 * closer than 2 R_max (plus a margin of 1e-6 cell for rounding): a cell
 * beyond that cannot hold a partner in contact, whatever the positions. */
static void sd_grid_fast_tables(sd_grid_state *g)
{
    if (g->reach != 2)
        return;
    int e = 0, off[SD_GRID_HALF2][3];
    for (int dz = 0; dz <= 2; ++dz)
        for (int dy = dz ? -2 : 0; dy <= 2; ++dy)
            for (int dx = (dz || dy) ? -2 : 1; dx <= 2; ++dx) {
                off[e][0] = dx;
                off[e][1] = dy;
                off[e][2] = dz;
                g->stoff[e++] = ((long)dz * g->ny + dy) * g->nx + dx;
            }
    double lim = 2.0 * (double)g->rmax / (double)g->h + 1e-6;
    for (int q = 0; q < SD_GRID_Q * SD_GRID_Q * SD_GRID_Q; ++q) {
        int qa[3] = {q % SD_GRID_Q, (q / SD_GRID_Q) % SD_GRID_Q, q / (SD_GRID_Q * SD_GRID_Q)};
        uint64_t m = 0;
        for (int b = 0; b < SD_GRID_HALF2; ++b) {
            double gap2 = 0;
            for (int a = 0; a < 3; ++a) {
                /* the owner lies in [lo, hi] of its cell (cell units); the
                 * other cell spans [d, d + 1] */
                double lo = (double)qa[a] / SD_GRID_Q, hi = (double)(qa[a] + 1) / SD_GRID_Q, d = off[b][a];
                double gap = d > 0 ? d - hi : d < 0 ? lo - (d + 1) : 0.0;
                if (gap > 0)
                    gap2 += gap * gap;
            }
            if (gap2 < lim * lim)
                m |= (uint64_t)1 << b;
        }
        g->qmask[q] = m;
    }
}

sd_status sd_grid_setup(sd_world *w, sd_error *err)
{
    sd_grid_state *g = sd_grid_state_get(w);
    if (!g)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
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
    for (size_t k = 0; k < g->n; ++k) {
        rmin = sd_min(rmin, g->kinds[g->part[k].kind].radius);
        rmax = sd_max(rmax, g->kinds[g->part[k].kind].radius);
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
    /* slabs for the force pass: `reach` cells thick, so an owner writes only
     * to its own slab and the next one (grid_step.c) */
    g->slab = g->reach;
    g->nslab = (g->nz - 2 * g->reach + g->slab - 1) / g->slab;
    g->nband = (g->ny - 2 * g->reach + g->slab - 1) / g->slab;
    uint8_t *rowocc = sd_realloc(g->rowocc, (size_t)(g->nz * g->ny));
    if (!rowocc)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    g->rowocc = rowocc;
    /* one bit per cell, two words of padding for the kernel's unaligned
     * reads of a row's bits */
    size_t nocc = ncell / 64 + 2;
    if (nocc != g->nocc || !g->occ) {
        uint64_t *occ = sd_realloc(g->occ, nocc * sizeof *occ);
        if (!occ)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
        g->occ = occ;
        g->nocc = nocc;
    }
    memset(g->occ, 0, nocc * sizeof *g->occ);
    sd_grid_fast_tables(g);
    sd_vec3 *sw = sd_realloc(g->slab_wall, (size_t)(g->nslab * g->nband + 1) * (w->wall_count ? w->wall_count : 1) * 2 *
                                               sizeof *sw);
    if (!sw)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    g->slab_wall = sw;
    if (sd_grid_grow(g, g->n > 0 ? g->n : 1, 1)) /* non-empty arrays; no head room */
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
    return sd_grid_cell_index(g->lo, g->h, g->reach, g->nx, g->ny, g->nz, x);
}

/* Takes cell where[k] for k, or puts k in the overflow list (a conflict). */
static sd_status sd_grid_claim(sd_grid_state *g, size_t k)
{
    uint32_t c = g->where[k];
    if (g->cell[c] < 0) {
        g->cell[c] = (int32_t)k;
        g->home[k] = c;
        g->rowocc[c / (uint32_t)g->nx] = 1; /* a hint: cleared only when all cells are rebuilt */
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
    size_t n = g->n, m = 0;
    for (size_t k = 0; k < n; ++k) {
        if (g->where[k] == SD_GRID_OUTSIDE) {
            const sd_grid_kind *kd = &g->kinds[g->part[k].kind];
            double mass = kd->inv_mass > 0 ? 1.0 / (double)kd->inv_mass : 0.0;
            g->info.removed++;
            g->info.removed_mass += mass;
            /* below the floor inside the hole: discharged; anywhere else (an
             * open top or side face) it escaped, counted apart so that the
             * discharge curve holds the outlet's mass only */
            sd_vec3 x = g->part[k].x;
            if (g->outlet && x.z < g->dom_lo.z && x.x > g->hx0 && x.x < g->hx1 && x.y > g->hy0 && x.y < g->hy1) {
                g->info.removed_outlet++;
                g->info.removed_outlet_mass += mass;
            } else {
                g->info.escaped++;
                g->info.escaped_mass += mass;
            }
            continue;
        }
        if (m != k) {
            g->part[m] = g->part[k];
            g->ft[2 * m] = g->ft[2 * k];
            g->ft[2 * m + 1] = g->ft[2 * k + 1];
            g->where[m] = g->where[k];
            g->home[m] = g->home[k];
            memcpy(g->tag + m * SD_GRID_SLOTS, g->tag + k * SD_GRID_SLOTS, SD_GRID_SLOTS * sizeof *g->tag);
            memcpy(g->ds + m * SD_GRID_SLOTS, g->ds + k * SD_GRID_SLOTS, SD_GRID_SLOTS * sizeof *g->ds);
        }
        ++m;
    }
    for (size_t k = m; k < n; ++k) {
        memset(g->tag + k * SD_GRID_SLOTS, 0, SD_GRID_SLOTS * sizeof *g->tag);
        g->home[k] = SD_GRID_OVER;
    }
    g->n = m;
}

sd_status sd_grid_place_all(sd_world *w, sd_error *err)
{
    sd_grid_state *g = w->grid_state;
    for (size_t c = 0; c < g->ncell; ++c)
        g->cell[c] = -1;
    g->nover = 0;
    size_t out = 0;
    for (size_t k = 0; k < g->n; ++k) {
        g->where[k] = sd_grid_cell_of(g, g->part[k].x);
        out += g->where[k] == SD_GRID_OUTSIDE;
    }
    if (out) {
        sd_grid_remove_outside(w);
        for (size_t k = 0; k < g->n; ++k)
            g->where[k] = sd_grid_cell_of(g, g->part[k].x);
    }
    for (size_t k = 0; k < g->n; ++k) {
        g->home[k] = g->where[k]; /* any conflict here counts as a new one */
        if (sd_grid_claim(g, k))
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (cell conflicts)");
    }
    sd_grid_note_overflow(g);
    sd_grid_mark_rows(g, g->n);
    sd_grid_set_parallel(w);
    return SD_OK;
}

void sd_grid_fail(sd_world *w, long step)
{
    sd_grid_state *g = w->grid_state;
    if (!g || !g->ncell)
        return;
    /* A failed step leaves where[] at the new positions while cell[] and
     * home[] still hold the old ones (the rebinning stopped at its checks),
     * or leaves a sheet half poured: rebuild the cells from the positions
     * now held, without allocating where it can be helped (this is an error
     * path; the overflow list grows only if it can). A particle outside the
     * inner grid (it escaped, or its position is NaN) keeps no cell and is
     * not in the overflow list: the stencil never reads around it, and it is
     * kept, not removed, so the statistics still show it. */
    for (size_t c = 0; c < g->ncell; ++c)
        g->cell[c] = -1;
    g->nover = 0;
    for (size_t k = 0; k < g->n; ++k) {
        g->where[k] = sd_grid_cell_of(g, g->part[k].x);
        g->home[k] = SD_GRID_OVER;
        if (g->where[k] == SD_GRID_OUTSIDE)
            continue;
        if (g->cell[g->where[k]] < 0) {
            g->cell[g->where[k]] = (int32_t)k;
            g->home[k] = g->where[k];
            continue;
        }
        if (g->nover == g->over_cap) {
            size_t cap = g->over_cap * 2 + 64;
            uint32_t *o = sd_realloc(g->over, cap * sizeof *o);
            if (!o)
                continue; /* left out of the contact statistics only */
            g->over = o;
            g->over_cap = cap;
        }
        g->over[g->nover++] = (uint32_t)k;
    }
    sd_grid_mark_rows(g, g->n);
    if (!g->info.failed_step)
        g->info.failed_step = step;
}

void sd_grid_mark_rows(sd_grid_state *g, size_t n)
{
    memset(g->rowocc, 0, (size_t)(g->nz * g->ny));
    for (size_t k = 0; k < n; ++k)
        if (g->home[k] != SD_GRID_OVER)
            g->rowocc[g->home[k] / (uint32_t)g->nx] = 1;
}

#define SD_PARALLEL_FOR_REDUCE_MAX(v) \
    SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel) reduction(max : v))

sd_status sd_grid_rebin(sd_world *w, sd_error *err)
{
    sd_grid_state *g = w->grid_state;
    const sd_grid_part *part = g->part;
    size_t n = g->n;
    uint32_t *where = g->where, *home = g->home;
    int32_t *cell = g->cell;

    /* A: the new cell of every particle, the fastest speed, NaN */
    double vmax2 = 0;
    int bad = 0;
SD_PARALLEL_FOR_REDUCE_MAX(vmax2)
    for (size_t k = 0; k < n; ++k) {
        where[k] = sd_grid_cell_of(g, part[k].x);
        double v2 = (double)sd_v3_norm2(part[k].v);
        if (v2 > vmax2 || v2 != v2)
            vmax2 = v2 != v2 ? (double)INFINITY : v2;
    }
    if (!isfinite(vmax2))
        bad = 1;
    for (size_t k = 0; k < n && !bad; ++k)
        if (where[k] == SD_GRID_OUTSIDE && !isfinite((double)(part[k].x.x + part[k].x.y + part[k].x.z)))
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
                            "eq. 11 of [Naderi 2024] violated at step %ld: a particle moves %.3g m/s, so dt %g s "
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

/* ---- the world's particle queries ------------------------------------------------ */

static sd_v3d sd_grid_v3d(sd_vec3 v)
{
    sd_v3d r = {(double)v.x, (double)v.y, (double)v.z};
    return r;
}

size_t sd_grid_particle_count(const sd_world *w)
{
    return w->grid_state && w->def.solver == SD_SOLVER_GRID ? w->grid_state->n : 0;
}

sd_status sd_grid_get_particle(const sd_world *w, size_t k, sd_particle_state *out)
{
    const sd_grid_state *g = w->grid_state;
    if (!g || k >= g->n)
        return SD_ERR_INPUT;
    const sd_grid_part *p = &g->part[k];
    const sd_grid_kind *kd = &g->kinds[p->kind];
    memset(out, 0, sizeof *out);
    out->id = p->id;
    out->position = sd_grid_v3d(p->x);
    out->velocity = sd_grid_v3d(p->v);
    out->angular_velocity = sd_grid_v3d(p->w);
    out->force = sd_grid_v3d(g->ft[2 * k]);
    out->torque = sd_grid_v3d(g->ft[2 * k + 1]);
    /* a sphere's orientation changes nothing in its contacts: the solver
     * does not carry it (docs/grid-solver.md) */
    out->quat[0] = 1.0;
    out->radius = (double)kd->radius;
    out->mass = kd->inv_mass > 0 ? 1.0 / (double)kd->inv_mass : (double)INFINITY;
    out->material = kd->material;
    out->shape = -1;
    return SD_OK;
}

size_t sd_grid_find_particle(const sd_world *w, uint64_t id)
{
    const sd_grid_state *g = w->grid_state;
    if (!g || w->def.solver != SD_SOLVER_GRID)
        return (size_t)-1;
    /* storage order is stable-id order: a binary search */
    size_t lo = 0, hi = g->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (g->part[mid].id < id)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < g->n && g->part[lo].id == id ? lo : (size_t)-1;
}

void sd_grid_particle_stats(const sd_world *w, double *ekt, double *ekr, double *epg, double *vmax2)
{
    const sd_grid_state *g = w->grid_state;
    if (!g || w->def.solver != SD_SOLVER_GRID)
        return;
    for (size_t k = 0; k < g->n; ++k) {
        const sd_grid_part *p = &g->part[k];
        const sd_grid_kind *kd = &g->kinds[p->kind];
        if (!(kd->inv_mass > 0))
            continue;
        double m = 1.0 / (double)kd->inv_mass;
        double v2 = (double)sd_v3_norm2(p->v);
        *ekt += 0.5 * m * v2;
        sd_vec3 ii = kd->inv_inertia;
        if (ii.x > 0 && ii.y > 0 && ii.z > 0)
            *ekr += 0.5 * ((double)(p->w.x * p->w.x / ii.x) + (double)(p->w.y * p->w.y / ii.y) +
                           (double)(p->w.z * p->w.z / ii.z));
        *epg -= m * (double)sd_v3_dot(w->gravity, p->x);
        if (v2 > *vmax2)
            *vmax2 = v2;
    }
}

int sd_grid_has_particles(const sd_world *w)
{
    const sd_grid_state *g = w->grid_state;
    return g && w->def.solver == SD_SOLVER_GRID && (g->n > 0 || g->pour.active);
}

static void sd_grid_dt_one(double r, double mass, int m, double speed, double h, double *rmin, double *mmin,
                           double *vmax, double *zlo, double *zhi, double *rsmall)
{
    if (m < 0 || m >= 256)
        return;
    rmin[m] = fmin(rmin[m], r);
    mmin[m] = fmin(mmin[m], mass);
    *rsmall = fmin(*rsmall, r);
    *vmax = fmax(*vmax, speed);
    *zlo = fmin(*zlo, h);
    *zhi = fmax(*zhi, h);
}

void sd_grid_dt_inputs(const sd_world *w, sd_vec3 gdir, double *rmin, double *mmin, double *vmax, double *zlo,
                       double *zhi, double *rsmall)
{
    if (!sd_grid_has_particles(w))
        return;
    const sd_grid_state *g = w->grid_state;
    for (size_t k = 0; k < g->n; ++k) {
        const sd_grid_kind *kd = &g->kinds[g->part[k].kind];
        double mass = kd->inv_mass > 0 ? 1.0 / (double)kd->inv_mass : (double)INFINITY;
        sd_grid_dt_one((double)kd->radius, mass, kd->material, (double)sd_v3_norm(g->part[k].v),
                       (double)sd_v3_dot(g->part[k].x, gdir), rmin, mmin, vmax, zlo, zhi, rsmall);
    }
    if (g->pour.active) {
        const sd_grid_pour_def *d = &g->pour.def;
        double r = d->radius;
        double mass = w->materials[d->material].def.density * 4.0 / 3.0 * SD_PI_D * r * r * r;
        double speed = sqrt(d->vz_range * d->vz_range + 2 * d->vh_range * d->vh_range);
        sd_vec3 top = sd_v3(g->dom_lo.x, g->dom_lo.y, (sd_real)d->height), bottom = g->dom_lo;
        sd_grid_dt_one(r, mass, d->material, speed, (double)sd_v3_dot(top, gdir), rmin, mmin, vmax, zlo, zhi, rsmall);
        sd_grid_dt_one(r, mass, d->material, speed, (double)sd_v3_dot(bottom, gdir), rmin, mmin, vmax, zlo, zhi,
                       rsmall);
    }
}

void sd_grid_set_parallel(sd_world *w)
{
    const sd_grid_state *g = w->grid_state;
    size_t lim = g->par_min ? g->par_min : SD_GRID_PARALLEL_MIN;
    w->parallel = w->threads > 1 && g->n >= lim;
}

sd_status sd_grid_set_parallel_min(sd_world *w, size_t n)
{
    sd_grid_state *g = sd_grid_state_get(w);
    if (!g)
        return SD_ERR_MEMORY;
    g->par_min = n;
    return SD_OK;
}
