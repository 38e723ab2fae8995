/* cells.c — broad phase: uniform cell binning with a Verlet skin.
 *
 * At each rebuild the particles are sorted by cell (counting sort on the
 * linear cell index, z-major) and every SoA field is permuted, so neighbours
 * sit close in memory. Candidate pairs come from a half stencil (the own
 * cell with j > i, plus the 13 cells after it in linear order), counted per
 * particle, prefix-summed and filled (DESIGN.md rule 3). The list is valid
 * until some particle has moved more than half the skin (sd_broad_needs_rebuild).
 * History is carried by key (DESIGN.md engineering notes, seed 000 §2.2).
 */
#include "broad/cells.h"

#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/alloc.h"
#include "core/error.h"
#include "geom/sphere.h"
#include "world/world.h"

/* Candidate slots per particle in the first search; the grid scratch holds
 * them (and, before that, one field of the particle permutation). */
#define SD_PAIR_SLOTS 16
#define SD_GRID_SCRATCH (SD_PAIR_SLOTS * 4 > 32 ? SD_PAIR_SLOTS * 4 : 32)

static sd_status sd_grow(void **p, size_t need, size_t elem)
{
    void *q = sd_realloc(*p, need * elem);
    if (!q && need)
        return SD_ERR_MEMORY;
    *p = q;
    return SD_OK;
}

static sd_status sd_pairs_reserve(sd_pair_list *l, size_t cap)
{
    if (cap <= l->cap)
        return SD_OK;
    cap = cap + cap / 2 + 16;
    if (sd_grow((void **)&l->i, cap, sizeof *l->i) || sd_grow((void **)&l->j, cap, sizeof *l->j) ||
        sd_grow((void **)&l->key, cap, sizeof *l->key) || sd_grow((void **)&l->ds, cap, sizeof *l->ds) ||
        sd_grow((void **)&l->f, cap, sizeof *l->f) || sd_grow((void **)&l->t, 2 * cap, sizeof *l->t) || sd_grow((void **)&l->delta, cap, sizeof *l->delta) ||
        sd_grow((void **)&l->energy, cap, sizeof *l->energy) || sd_grow((void **)&l->gidx, 2 * cap, sizeof *l->gidx) ||
        sd_grow((void **)&l->warm, cap, sizeof *l->warm) || sd_grow((void **)&l->flip, cap, sizeof *l->flip) || sd_grow((void **)&l->iters, cap, sizeof *l->iters) ||
        sd_grow((void **)&l->supports, cap, sizeof *l->supports) || sd_grow((void **)&l->x0, cap, sizeof *l->x0) ||
        sd_grow((void **)&l->x0_ok, cap, sizeof *l->x0_ok))
        return SD_ERR_MEMORY;
    l->cap = cap;
    l->gidx_cap = 2 * cap;
    return SD_OK;
}

static sd_status sd_wpairs_reserve(sd_wall_pair_list *l, size_t cap)
{
    if (cap <= l->cap)
        return SD_OK;
    cap = cap + cap / 2 + 16;
    if (sd_grow((void **)&l->i, cap, sizeof *l->i) || sd_grow((void **)&l->wall, cap, sizeof *l->wall) ||
        sd_grow((void **)&l->sub, cap, sizeof *l->sub) || sd_grow((void **)&l->key, cap, sizeof *l->key) ||
        sd_grow((void **)&l->ds, cap, sizeof *l->ds) || sd_grow((void **)&l->f, cap, sizeof *l->f) ||
        sd_grow((void **)&l->t, cap, sizeof *l->t) || sd_grow((void **)&l->delta, cap, sizeof *l->delta) ||
        sd_grow((void **)&l->energy, cap, sizeof *l->energy) || sd_grow((void **)&l->c, cap, sizeof *l->c))
        return SD_ERR_MEMORY;
    l->cap = cap;
    return SD_OK;
}

void sd_broad_free(sd_pair_list *l, sd_wall_pair_list *wl, sd_grid *g)
{
    void *ptrs[] = {l->i, l->j, l->key, l->ds, l->f, l->t, l->delta, l->energy, l->gstart, l->gidx,
                    l->warm, l->iters, l->supports, l->flip, l->x0, l->x0_ok,
                    wl->i, wl->wall, wl->sub, wl->key, wl->ds, wl->f, wl->t, wl->delta, wl->energy, wl->start, wl->c,
                    g->cell_start, g->cell, g->perm, g->count, g->scratch};
    for (size_t k = 0; k < sizeof ptrs / sizeof ptrs[0]; ++k)
        sd_free(ptrs[k]);
    memset(l, 0, sizeof *l);
    memset(wl, 0, sizeof *wl);
    memset(g, 0, sizeof *g);
}

/* ---- history carry-over ------------------------------------------------- */

/* Sorts h by key: least-significant-digit radix sort, 11 bits a pass,
 * skipping the passes whose digit is the same in every key (the high bits
 * of small ids). Linear in the count, which matters at every rebuild of a
 * large list. tmp holds as many entries as h; returns where the result is.
 *
 * Threaded when the world is: each thread counts the digits of its own
 * contiguous share, the offsets are laid out digit by digit and, within a
 * digit, share by share, and each thread scatters its share in order. That
 * is the stable order of the serial sort, which is unique: the same result
 * for any thread count. */
enum { SD_HIST_BITS = 11, SD_HIST_RADIX = 1 << SD_HIST_BITS };

static sd_history *sd_history_sort(const sd_world *w, sd_history *h, sd_history *tmp, size_t m)
{
    const uint64_t mask = SD_HIST_RADIX - 1;
    uint64_t all_or = 0, all_and = ~(uint64_t)0;
    SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel) \
                  reduction(| : all_or) reduction(& : all_and))
    for (size_t k = 0; k < m; ++k) {
        all_or |= h[k].key;
        all_and &= h[k].key;
    }
    int nt = w->parallel && w->threads > 1 ? w->threads : 1;
    size_t one[SD_HIST_RADIX];
    size_t *count = nt > 1 ? sd_malloc((size_t)nt * SD_HIST_RADIX * sizeof *count) : NULL;
    if (!count) { /* one thread (or no memory for the threads' counts) */
        count = one;
        nt = 1;
    }
    for (int shift = 0; shift < 64; shift += SD_HIST_BITS) {
        if ((((all_or ^ all_and) >> shift) & mask) == 0)
            continue; /* the same digit everywhere: already in order */
        SD_PRAGMA(omp parallel num_threads(nt) if (nt > 1))
        {
            int t = 0;
#ifdef _OPENMP
            t = omp_get_thread_num();
            int got = omp_get_num_threads();
#else
            int got = 1;
#endif
            /* shares by the team actually running, so a smaller team still
             * covers every entry (the order within a digit does not depend
             * on how the entries are shared) */
            size_t k0 = m * (size_t)t / (size_t)got, k1 = m * (size_t)(t + 1) / (size_t)got;
            size_t *c = count + (size_t)t * SD_HIST_RADIX;
            memset(c, 0, SD_HIST_RADIX * sizeof *c);
            for (size_t k = k0; k < k1; ++k)
                c[(h[k].key >> shift) & mask]++;
            SD_PRAGMA(omp barrier)
            SD_PRAGMA(omp single)
            {
                size_t sum = 0;
                for (size_t d = 0; d < SD_HIST_RADIX; ++d)
                    for (int u = 0; u < got; ++u) {
                        size_t v = count[(size_t)u * SD_HIST_RADIX + d];
                        count[(size_t)u * SD_HIST_RADIX + d] = sum;
                        sum += v;
                    }
            }
            for (size_t k = k0; k < k1; ++k)
                tmp[c[(h[k].key >> shift) & mask]++] = h[k];
        }
        sd_history *t = h;
        h = tmp;
        tmp = t;
    }
    if (count != one)
        sd_free(count);
    return h;
}

/* Collects the entries worth keeping, sorted by key: those with a non-zero
 * spring v (only == NULL), or those marked in only[] (the overlap hints).
 * Threaded like the sort: each thread counts its share, then copies it to
 * its place, so the entries keep the pair-list order for any thread count. */
static int sd_history_keep(size_t k, const sd_vec3 *v, const uint8_t *only)
{
    return only ? only[k] != 0 : (v[k].x != 0 || v[k].y != 0 || v[k].z != 0);
}

static sd_history *sd_history_collect(const sd_world *w, size_t n, const uint64_t *key, const sd_vec3 *v,
                                      const uint8_t *only, size_t *count)
{
    enum { SHARES = 64 }; /* contiguous shares: the entries come out in pair-list order */
    size_t before[SHARES + 1];
    SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel))
    for (int s = 0; s < SHARES; ++s) {
        size_t c = 0;
        for (size_t k = n * (size_t)s / SHARES; k < n * (size_t)(s + 1) / SHARES; ++k)
            c += (size_t)sd_history_keep(k, v, only);
        before[s + 1] = c;
    }
    before[0] = 0;
    for (int s = 0; s < SHARES; ++s)
        before[s + 1] += before[s];
    size_t m = before[SHARES];
    *count = m;
    /* one block: the entries, then the radix sort's scratch */
    sd_history *h = sd_malloc(2 * (m ? m : 1) * sizeof *h);
    if (!h)
        return NULL;
    SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel))
    for (int s = 0; s < SHARES; ++s) {
        size_t o = before[s];
        for (size_t k = n * (size_t)s / SHARES; k < n * (size_t)(s + 1) / SHARES; ++k)
            if (sd_history_keep(k, v, only)) {
                h[o].key = key[k];
                h[o].v = v[k];
                ++o;
            }
    }
    sd_history *sorted = sd_history_sort(w, h, h + m, m);
    if (sorted != h)
        memcpy(h, sorted, m * sizeof *h);
    return h;
}

static const sd_history *sd_history_lookup(const sd_history *h, size_t n, uint64_t key)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (h[mid].key < key)
            lo = mid + 1;
        else
            hi = mid;
    }
    return (lo < n && h[lo].key == key) ? &h[lo] : NULL;
}

static sd_vec3 sd_history_find(const sd_history *h, size_t n, uint64_t key)
{
    const sd_history *e = sd_history_lookup(h, n, key);
    return e ? e->v : sd_v3_zero();
}

/* ---- grid ------------------------------------------------------------------ */

static sd_status sd_grid_setup(sd_world *w)
{
    sd_grid *g = &w->grid;
    sd_particles *p = &w->p;
    size_t n = p->n;
    sd_vec3 lo = p->x[0], hi = p->x[0];
    sd_real rmax = 0;
    for (size_t k = 0; k < n; ++k) {
        lo = sd_v3_min(lo, p->x[k]);
        hi = sd_v3_max(hi, p->x[k]);
        rmax = sd_max(rmax, p->radius[k]);
    }
    sd_real h = SD_R(2.0) * rmax + w->skin;
    sd_vec3 ext = sd_v3_sub(hi, lo);
    /* keep the cell count near the particle count when the cloud is sparse
     * (a particle flying away must not make the grid huge) */
    double limit = (double)(4 * n + 64);
    for (;;) {
        double cx = floor((double)(ext.x / h)) + 1, cy = floor((double)(ext.y / h)) + 1,
               cz = floor((double)(ext.z / h)) + 1;
        if (cx * cy * cz <= limit) {
            g->nx = (int)cx;
            g->ny = (int)cy;
            g->nz = (int)cz;
            break;
        }
        h *= SD_R(1.26);
    }
    g->h = h;
    g->lo = lo;
    g->ncell = (size_t)g->nx * (size_t)g->ny * (size_t)g->nz;
    if (g->ncell + 1 > g->cell_cap) {
        if (sd_grow((void **)&g->cell_start, g->ncell + 1, sizeof *g->cell_start))
            return SD_ERR_MEMORY;
        g->cell_cap = g->ncell + 1;
    }
    if (n > g->pcap) {
        size_t cap = n + n / 4 + 16;
        if (sd_grow((void **)&g->cell, cap, sizeof *g->cell) || sd_grow((void **)&g->perm, cap, sizeof *g->perm) ||
            sd_grow((void **)&g->count, cap + 1, sizeof *g->count) || sd_grow(&g->scratch, cap, SD_GRID_SCRATCH))
            return SD_ERR_MEMORY;
        g->pcap = cap;
    }
    return SD_OK;
}

static inline uint32_t sd_grid_cell(const sd_grid *g, sd_vec3 x)
{
    int cx = (int)((x.x - g->lo.x) / g->h), cy = (int)((x.y - g->lo.y) / g->h), cz = (int)((x.z - g->lo.z) / g->h);
    cx = cx < 0 ? 0 : (cx >= g->nx ? g->nx - 1 : cx);
    cy = cy < 0 ? 0 : (cy >= g->ny ? g->ny - 1 : cy);
    cz = cz < 0 ? 0 : (cz >= g->nz ? g->nz - 1 : cz);
    return (uint32_t)(((size_t)cz * (size_t)g->ny + (size_t)cy) * (size_t)g->nx + (size_t)cx);
}

/* Sorts particles by cell and fills cell_start. */
static void sd_grid_sort(sd_world *w)
{
    sd_grid *g = &w->grid;
    sd_particles *p = &w->p;
    size_t n = p->n;
    SD_PARALLEL_FOR
    for (size_t k = 0; k < n; ++k)
        g->cell[k] = sd_grid_cell(g, p->x[k]);
    memset(g->cell_start, 0, (g->ncell + 1) * sizeof *g->cell_start);
    for (size_t k = 0; k < n; ++k)
        g->cell_start[g->cell[k] + 1]++;
    for (size_t c = 0; c < g->ncell; ++c)
        g->cell_start[c + 1] += g->cell_start[c];
    /* stable counting sort: perm[new] = old */
    for (size_t k = 0; k < n; ++k) {
        uint32_t c = g->cell[k];
        g->perm[g->cell_start[c]++] = (uint32_t)k;
    }
    /* cell_start was advanced to the cell ends: shift back */
    for (size_t c = g->ncell; c > 0; --c)
        g->cell_start[c] = g->cell_start[c - 1];
    g->cell_start[0] = 0;
    sd_particles_permute(p, g->perm, g->scratch, w->threads, w->parallel);
    SD_PARALLEL_FOR
    for (size_t k = 0; k < n; ++k)
        g->cell[k] = sd_grid_cell(g, p->x[k]);
}

/* ---- pair list ------------------------------------------------------------- */

/* Visits the candidates of particle i, writes the first `cap` of them to
 * out_j and returns how many there are. */
static uint32_t sd_pairs_of(const sd_world *w, size_t i, uint32_t *out_j, uint32_t cap)
{
    const sd_grid *g = &w->grid;
    const sd_particles *p = &w->p;
    uint32_t c = g->cell[i];
    int cx = (int)(c % (uint32_t)g->nx);
    int cy = (int)((c / (uint32_t)g->nx) % (uint32_t)g->ny);
    int cz = (int)(c / ((uint32_t)g->nx * (uint32_t)g->ny));
    sd_vec3 xi = p->x[i];
    sd_real ri = p->radius[i] + w->skin;
    uint32_t m = 0;
    for (int dz = 0; dz <= 1; ++dz)
        for (int dy = (dz ? -1 : 0); dy <= 1; ++dy)
            for (int dx = ((dz || dy) ? -1 : 0); dx <= 1; ++dx) {
                int x = cx + dx, y = cy + dy, z = cz + dz;
                if (x < 0 || y < 0 || z >= g->nz || x >= g->nx || y >= g->ny)
                    continue;
                size_t nc = ((size_t)z * (size_t)g->ny + (size_t)y) * (size_t)g->nx + (size_t)x;
                size_t j0 = g->cell_start[nc], j1 = g->cell_start[nc + 1];
                if (nc == c)
                    j0 = i + 1;
                for (size_t j = j0; j < j1; ++j) {
                    sd_real rs = ri + p->radius[j];
                    if (sd_v3_norm2(sd_v3_sub(xi, p->x[j])) < rs * rs) {
                        if (m < cap)
                            out_j[m] = (uint32_t)j;
                        ++m;
                    }
                }
            }
    return m;
}

/* Moves the pairs that involve a shape template after the sphere-sphere
 * pairs, keeping the order within each kind (a stable partition, so the
 * list still depends only on the particle order). */
static sd_status sd_pairs_partition(sd_world *w)
{
    sd_pair_list *l = &w->pairs;
    const int32_t *shape = w->p.shape;
    size_t n = l->n, nconv = 0;
    if (w->has_shapes)
        for (size_t e = 0; e < n; ++e)
            nconv += shape[l->i[e]] >= 0 || shape[l->j[e]] >= 0;
    l->n_sphere = n - nconv;
    if (nconv == 0)
        return SD_OK;
    uint32_t *ti = sd_malloc(n * sizeof *ti), *tj = sd_malloc(n * sizeof *tj);
    uint64_t *tk = sd_malloc(n * sizeof *tk);
    sd_vec3 *td = sd_malloc(n * sizeof *td), *tx = sd_malloc(n * sizeof *tx);
    uint8_t *to_ = sd_malloc(n * sizeof *to_);
    if (!ti || !tj || !tk || !td || !tx || !to_) {
        sd_free(ti);
        sd_free(tj);
        sd_free(tk);
        sd_free(td);
        sd_free(tx);
        sd_free(to_);
        return SD_ERR_MEMORY;
    }
    size_t a = 0, b = l->n_sphere;
    for (size_t e = 0; e < n; ++e) {
        size_t to = (shape[l->i[e]] >= 0 || shape[l->j[e]] >= 0) ? b++ : a++;
        ti[to] = l->i[e];
        tj[to] = l->j[e];
        tk[to] = l->key[e];
        td[to] = l->ds[e];
        tx[to] = l->x0[e];
        to_[to] = l->x0_ok[e];
    }
    memcpy(l->i, ti, n * sizeof *ti);
    memcpy(l->j, tj, n * sizeof *tj);
    memcpy(l->key, tk, n * sizeof *tk);
    memcpy(l->ds, td, n * sizeof *td);
    memcpy(l->x0, tx, n * sizeof *tx);
    memcpy(l->x0_ok, to_, n * sizeof *to_);
    sd_free(ti);
    sd_free(tj);
    sd_free(tk);
    sd_free(td);
    sd_free(tx);
    sd_free(to_);
    return SD_OK;
}

static sd_status sd_pairs_build(sd_world *w)
{
    sd_particles *p = &w->p;
    sd_pair_list *l = &w->pairs;
    size_t n = p->n;
    uint32_t *cnt = w->grid.count;

    size_t nhist = 0, nhint = 0;
    sd_history *hist = sd_history_collect(w, l->n, l->key, l->ds, NULL, &nhist);
    if (!hist)
        return SD_ERR_MEMORY;
    /* overlap hints only where a volume law can use them (pairs.h) */
    int hinted = w->has_volume_law;
    sd_history *hints = hinted ? sd_history_collect(w, l->n, l->key, l->x0, l->x0_ok, &nhint) : NULL;
    if (hinted && !hints) {
        sd_free(hist);
        return SD_ERR_MEMORY;
    }

    /* one search per particle: its candidates go to a small fixed slot in
     * the grid scratch (SD_PAIR_SLOTS each); only a particle with more
     * candidates than that is searched again in the fill */
    uint32_t *slots = (uint32_t *)w->grid.scratch;
    SD_PARALLEL_FOR
    for (size_t i = 0; i < n; ++i)
        cnt[i] = sd_pairs_of(w, i, slots + i * SD_PAIR_SLOTS, SD_PAIR_SLOTS);
    size_t total = 0;
    for (size_t i = 0; i < n; ++i) {
        uint32_t c = cnt[i];
        cnt[i] = (uint32_t)total;
        total += c;
    }
    if (sd_pairs_reserve(l, total)) {
        sd_free(hist);
        sd_free(hints);
        return SD_ERR_MEMORY;
    }
    l->n = total;
    SD_PARALLEL_FOR
    for (size_t i = 0; i < n; ++i) {
        uint32_t off = cnt[i];
        uint32_t m = (i + 1 < n ? cnt[i + 1] : (uint32_t)total) - off;
        /* no pairs for i: skip, as l->j is NULL in a world without pairs
         * and memcpy from or to NULL is undefined even for 0 bytes */
        if (m == 0)
            continue;
        if (m <= SD_PAIR_SLOTS)
            memcpy(l->j + off, slots + i * SD_PAIR_SLOTS, m * sizeof *l->j);
        else
            sd_pairs_of(w, i, l->j + off, UINT32_MAX);
        for (uint32_t k = 0; k < m; ++k) {
            size_t e = off + k;
            l->i[e] = (uint32_t)i;
            uint64_t a = p->id[i], b = p->id[l->j[e]];
            l->key[e] = a < b ? (a << 32 | b) : (b << 32 | a);
            l->ds[e] = sd_history_find(hist, nhist, l->key[e]);
            if (hinted) {
                const sd_history *hh = sd_history_lookup(hints, nhint, l->key[e]);
                l->x0[e] = hh ? hh->v : sd_v3_zero();
                l->x0_ok[e] = hh != NULL;
            } else {
                l->x0_ok[e] = 0;
            }
            l->f[e] = sd_v3_zero();
            l->t[2 * e] = sd_v3_zero();
            l->t[2 * e + 1] = sd_v3_zero();
            l->delta[e] = 0;
            l->energy[e] = 0;
            l->warm[e] = sd_v3_zero();
            l->iters[e] = 0;
            l->supports[e] = 0;
        }
    }
    sd_free(hist);
    sd_free(hints);
    if (sd_pairs_partition(w) != SD_OK)
        return SD_ERR_MEMORY;
    SD_PARALLEL_FOR
    for (size_t e = 0; e < total; ++e) {
        l->flip[e] = p->id[l->i[e]] > p->id[l->j[e]];
        /* a pair that carries a spring is evaluated at the next step even if
         * it has just come apart, so that its spring is cleared (the force
         * loops skip pairs that were and are apart) */
        sd_vec3 s = l->ds[e];
        l->delta[e] = (s.x != 0 || s.y != 0 || s.z != 0) ? SD_R(1e-300) : SD_R(0.0);
    }

    /* gather lists, filled in pair order so every particle sums its pairs in
     * the same order whatever the thread count */
    if (n + 1 > l->gstart_cap) {
        if (sd_grow((void **)&l->gstart, n + 1, sizeof *l->gstart))
            return SD_ERR_MEMORY;
        l->gstart_cap = n + 1;
    }
    memset(l->gstart, 0, (n + 1) * sizeof *l->gstart);
    for (size_t e = 0; e < total; ++e) {
        l->gstart[l->i[e] + 1]++;
        l->gstart[l->j[e] + 1]++;
    }
    for (size_t i = 0; i < n; ++i)
        l->gstart[i + 1] += l->gstart[i];
    memcpy(cnt, l->gstart, n * sizeof *cnt);
    for (size_t e = 0; e < total; ++e) {
        l->gidx[cnt[l->i[e]]++] = (uint32_t)(2 * e);
        l->gidx[cnt[l->j[e]]++] = (uint32_t)(2 * e + 1);
    }
    return SD_OK;
}

/* ---- wall pairs ------------------------------------------------------------ */

/* Visits the wall candidates of particle i (a face or plane within the skin). */
static uint32_t sd_wall_pairs_of(const sd_world *w, size_t i, sd_wall_pair_list *out, size_t off)
{
    const sd_particles *p = &w->p;
    sd_vec3 x = p->x[i];
    sd_real reach = p->radius[i] + w->skin;
    uint32_t m = 0;
    for (size_t wi = 0; wi < w->wall_count; ++wi) {
        const sd_wall *wl = &w->walls[wi];
        if (wl->kind == SD_WALL_PLANE) {
            sd_real s = sd_v3_dot(sd_v3_sub(x, wl->point), wl->normal);
            if (s < reach) {
                if (out) {
                    out->wall[off + m] = (uint16_t)wi;
                    out->sub[off + m] = 0;
                }
                ++m;
            }
            continue;
        }
        const sd_real c[3] = {x.x, x.y, x.z};
        const sd_real lo[3] = {wl->lo.x, wl->lo.y, wl->lo.z};
        const sd_real hi[3] = {wl->hi.x, wl->hi.y, wl->hi.z};
        for (int face = 0; face < 6; ++face) {
            if (wl->open_faces & (1u << face))
                continue;
            int axis = face / 2;
            sd_real s = (face & 1) ? hi[axis] - c[axis] : c[axis] - lo[axis];
            if (s < reach && s > -reach) {
                if (out) {
                    out->wall[off + m] = (uint16_t)wi;
                    out->sub[off + m] = (uint16_t)face;
                }
                ++m;
            }
        }
    }
    return m;
}

static sd_status sd_wall_pairs_build(sd_world *w)
{
    sd_particles *p = &w->p;
    sd_wall_pair_list *l = &w->wpairs;
    size_t n = p->n;
    if (n + 1 > l->start_cap) {
        if (sd_grow((void **)&l->start, n + 1, sizeof *l->start))
            return SD_ERR_MEMORY;
        l->start_cap = n + 1;
    }
    size_t nhist = 0;
    sd_history *hist = sd_history_collect(w, l->n, l->key, l->ds, NULL, &nhist);
    if (!hist)
        return SD_ERR_MEMORY;
    SD_PARALLEL_FOR
    for (size_t i = 0; i < n; ++i)
        l->start[i + 1] = sd_wall_pairs_of(w, i, NULL, 0);
    l->start[0] = 0;
    for (size_t i = 0; i < n; ++i)
        l->start[i + 1] += l->start[i];
    size_t total = l->start[n];
    if (sd_wpairs_reserve(l, total)) {
        sd_free(hist);
        return SD_ERR_MEMORY;
    }
    l->n = total;
    SD_PARALLEL_FOR
    for (size_t i = 0; i < n; ++i) {
        size_t off = l->start[i];
        uint32_t m = sd_wall_pairs_of(w, i, l, off);
        for (uint32_t k = 0; k < m; ++k) {
            size_t e = off + k;
            l->i[e] = (uint32_t)i;
            l->key[e] = (p->id[i] << 20) | ((uint64_t)l->wall[e] << 4) | l->sub[e];
            l->ds[e] = sd_history_find(hist, nhist, l->key[e]);
            l->f[e] = sd_v3_zero();
            l->t[e] = sd_v3_zero();
            l->c[e] = p->x[i];
            l->delta[e] = 0;
            l->energy[e] = 0;
        }
    }
    sd_free(hist);
    return SD_OK;
}

/* ---- public to the world ------------------------------------------------------ */

sd_status sd_broad_rebuild(sd_world *w, sd_error *err)
{
    sd_particles *p = &w->p;
    w->parallel = w->threads > 1 && p->n >= SD_PARALLEL_MIN_PARTICLES;
    if (p->n == 0) {
        w->pairs.n = 0;
        w->pairs.n_sphere = 0;
        w->wpairs.n = 0;
        w->rebuilds++;
        return SD_OK;
    }
    /* the pair list's storage indices die with the sort below: move the
     * history to stable keys first (done inside the builders) */
    sd_status st = sd_grid_setup(w);
    if (st == SD_OK) {
        sd_grid_sort(w);
        st = sd_pairs_build(w);
    }
    if (st == SD_OK)
        st = sd_wall_pairs_build(w);
    if (st != SD_OK)
        return sd_error_set(err, st, "", 0, "", "out of memory while building the pair list (%zu particles)", p->n);
    size_t n = p->n;
    SD_PARALLEL_FOR
    for (size_t k = 0; k < n; ++k) {
        p->x_ref[k] = p->x[k];
        p->q_ref[k] = p->q[k];
    }
    sd_world_walls_mark(w);
    w->rebuilds++;
    w->dirty = 0;
    return SD_OK;
}

int sd_broad_needs_rebuild(const sd_world *w)
{
    if (w->dirty || sd_world_walls_moved(w)) /* a wall and a particle may each use half the skin */
        return 1;
    const sd_particles *p = &w->p;
    size_t n = p->n;
    sd_real lim2 = sd_sq(SD_R(0.5) * w->skin);
    int need = 0;
    if (!w->has_shapes) {
        /* a sphere's bounding sphere does not change with rotation */
SD_PARALLEL_FOR_REDUCE_OR(need)
        for (size_t k = 0; k < n; ++k)
            need |= sd_v3_norm2(sd_v3_sub(p->x[k], p->x_ref[k])) > lim2;
        return need;
    }
    /* no surface point of a body moved more than |dx| + R |dtheta| (a
     * bound on vertex displacement, algorithms.md section B) */
    sd_real lim = SD_R(0.5) * w->skin;
SD_PARALLEL_FOR_REDUCE_OR(need)
    for (size_t k = 0; k < n; ++k) {
        sd_real d = sd_v3_norm(sd_v3_sub(p->x[k], p->x_ref[k]));
        if (p->shape[k] >= 0)
            d += p->radius[k] * sd_quat_angle_between(p->q[k], p->q_ref[k]);
        need |= d > lim;
    }
    return need;
}
