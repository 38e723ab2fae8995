/* bins.c — broad phase: uniform cell binning with a Verlet skin (bins.h).
 *
 * At each rebuild the owned particles are sorted by cell (counting sort on
 * the linear cell index, z-major); the world permutes its arrays by the
 * order returned, so neighbours sit close in memory. Candidate pairs come
 * from a half stencil (the own cell after the particle, plus the 13 cells
 * after it in linear order), counted per particle and kind, prefix-summed
 * kind by kind and filled straight into their kind segments (DESIGN.md
 * rule 3): within a segment, pairs keep the order of the search. The list
 * is valid until some particle has moved more than half the skin (the
 * backend's rebuild test). History is carried by key (DESIGN.md
 * engineering notes, seed 000 §2.2): the kept entries are radix-sorted by
 * key and each new pair finds its entry by binary search.
 *
 * With ghosts the bins cover owned and ghost particles alike through an
 * index of the particles in cell order (item); the rules of bins.h decide
 * which of the pairs with a ghost are kept.
 */
#include "broad/bins.h"

#include <math.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/alloc.h"
#include "geom/clip.h"
#include "shape/shape.h"

/* Kinds per particle in the count scratch: the larger of the two lists'. */
#define SD_BINS_COUNT_KINDS \
    ((int)SD_PAIR_KIND_COUNT > (int)SD_WALL_PAIR_KIND_COUNT ? (int)SD_PAIR_KIND_COUNT : (int)SD_WALL_PAIR_KIND_COUNT)

/* Candidate slots per particle in the first search; the bins' scratch holds
 * them (and, before that, one field of the world's permutation). */
#define SD_PAIR_SLOTS 16
#define SD_BINS_SCRATCH (SD_PAIR_SLOTS * 4 > SD_BINS_PERMUTE_SCRATCH ? SD_PAIR_SLOTS * 4 : SD_BINS_PERMUTE_SCRATCH)

#define SD_BINS_FOR(in) SD_PRAGMA(omp parallel for schedule(static) num_threads((in)->threads) if ((in)->parallel))

static sd_status sd_bins_grow(void **p, size_t need, size_t elem)
{
    void *q = sd_realloc(*p, need * elem);
    if (!q && need)
        return SD_ERR_MEMORY;
    *p = q;
    return SD_OK;
}

void sd_bins_free(sd_bins *b)
{
    void *ptrs[] = {b->cell_start, b->cell, b->perm, b->item, b->pos, b->count, b->slot_kind, b->scratch};
    for (size_t k = 0; k < sizeof ptrs / sizeof ptrs[0]; ++k)
        sd_free(ptrs[k]);
    memset(b, 0, sizeof *b);
}

/* ---- history carry-over ------------------------------------------------- */

/* A carried value and its key (wall keys are written as pair keys: id, wall,
 * feature, 0). */
typedef struct sd_history {
    sd_pair_key key;
    sd_vec3 v;
} sd_history;

static SD_INLINE int sd_key_less(const sd_pair_key *a, const sd_pair_key *b)
{
    if (a->id_lo != b->id_lo)
        return a->id_lo < b->id_lo;
    if (a->id_hi != b->id_hi)
        return a->id_hi < b->id_hi;
    if (a->sub_lo != b->sub_lo)
        return a->sub_lo < b->sub_lo;
    return a->sub_hi < b->sub_hi;
}

static SD_INLINE int sd_key_equal(const sd_pair_key *a, const sd_pair_key *b)
{
    return a->id_lo == b->id_lo && a->id_hi == b->id_hi && a->sub_lo == b->sub_lo && a->sub_hi == b->sub_hi;
}

/* Field f of a key, least significant first: sub_hi, sub_lo, id_hi, id_lo. */
enum { SD_KEY_FIELDS = 4 };
static const int sd_key_width[SD_KEY_FIELDS] = {32, 32, 64, 64};

static SD_INLINE uint64_t sd_key_field(const sd_pair_key *k, int f)
{
    return f == 0 ? k->sub_hi : (f == 1 ? k->sub_lo : (f == 2 ? k->id_hi : k->id_lo));
}

/* Sorts h by key: least-significant-digit radix sort, 11 bits a pass, field
 * by field, skipping the passes whose digit is the same in every key (the
 * sub-indices of today's pairs, the high bits of small ids): as many passes
 * as the ids need, as with the 64-bit key before. Linear in the count,
 * which matters at every rebuild of a large list. tmp holds as many entries
 * as h; returns where the result is.
 *
 * Threaded when the world is: each thread counts the digits of its own
 * contiguous share, the offsets are laid out digit by digit and, within a
 * digit, share by share, and each thread scatters its share in order. That
 * is the stable order of the serial sort, which is unique: the same result
 * for any thread count. */
enum { SD_HIST_BITS = 11, SD_HIST_RADIX = 1 << SD_HIST_BITS };

static sd_history *sd_history_sort(int threads, int parallel, sd_history *h, sd_history *tmp, size_t m)
{
    const uint64_t mask = SD_HIST_RADIX - 1;
    uint64_t differ[SD_KEY_FIELDS];
    int nt = parallel && threads > 1 ? threads : 1;
    for (int f = 0; f < SD_KEY_FIELDS; ++f) {
        uint64_t all_or = 0, all_and = ~(uint64_t)0;
        if (nt > 1) {
            SD_PRAGMA(omp parallel for schedule(static) num_threads(nt) reduction(| : all_or) reduction(& : all_and))
            for (size_t k = 0; k < m; ++k) {
                uint64_t v = sd_key_field(&h[k].key, f);
                all_or |= v;
                all_and &= v;
            }
        } else /* no OpenMP region at all: each one costs a system call (core/base.h: SD_OMP_EACH) */
            for (size_t k = 0; k < m; ++k) {
                uint64_t v = sd_key_field(&h[k].key, f);
                all_or |= v;
                all_and &= v;
            }
        differ[f] = all_or ^ all_and;
    }
    size_t one[SD_HIST_RADIX];
    size_t *count = nt > 1 ? sd_malloc((size_t)nt * SD_HIST_RADIX * sizeof *count) : NULL;
    if (!count) { /* one thread (or no memory for the threads' counts) */
        count = one;
        nt = 1;
    }
    for (int f = 0; f < SD_KEY_FIELDS; ++f)
        for (int shift = 0; shift < sd_key_width[f]; shift += SD_HIST_BITS) {
            if (((differ[f] >> shift) & mask) == 0)
                continue; /* the same digit everywhere: already in order */
            if (nt == 1) { /* the same pass without a region (its barriers are system calls) */
                memset(count, 0, SD_HIST_RADIX * sizeof *count);
                for (size_t k = 0; k < m; ++k)
                    count[(sd_key_field(&h[k].key, f) >> shift) & mask]++;
                size_t sum = 0;
                for (size_t d = 0; d < SD_HIST_RADIX; ++d) {
                    size_t v = count[d];
                    count[d] = sum;
                    sum += v;
                }
                for (size_t k = 0; k < m; ++k)
                    tmp[count[(sd_key_field(&h[k].key, f) >> shift) & mask]++] = h[k];
            } else
            SD_PRAGMA(omp parallel num_threads(nt))
            {
                int t = 0;
#ifdef _OPENMP
                t = omp_get_thread_num();
                int got = omp_get_num_threads();
#else
                int got = 1;
#endif
                /* shares by the team actually running, so a smaller team
                 * still covers every entry (the order within a digit does
                 * not depend on how the entries are shared) */
                size_t k0 = m * (size_t)t / (size_t)got, k1 = m * (size_t)(t + 1) / (size_t)got;
                size_t *c = count + (size_t)t * SD_HIST_RADIX;
                memset(c, 0, SD_HIST_RADIX * sizeof *c);
                for (size_t k = k0; k < k1; ++k)
                    c[(sd_key_field(&h[k].key, f) >> shift) & mask]++;
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
                    tmp[c[(sd_key_field(&h[k].key, f) >> shift) & mask]++] = h[k];
            }
            sd_history *t = h;
            h = tmp;
            tmp = t;
        }
    if (count != one)
        sd_free(count);
    return h;
}

/* Where the carried entries come from: n pairs with their keys (pair keys,
 * or wall keys when wkey is set) and values v; an entry is kept when its
 * value is non-zero (only == NULL: springs), or when only[k] is set (the
 * overlap hints). */
typedef struct sd_history_src {
    size_t n;
    const sd_pair_key *key;
    const sd_wall_pair_key *wkey;
    const sd_vec3 *v;
    const uint8_t *only;
} sd_history_src;

static int sd_history_keep(const sd_history_src *s, size_t k)
{
    return s->only ? s->only[k] != 0 : (s->v[k].x != 0 || s->v[k].y != 0 || s->v[k].z != 0);
}

static SD_INLINE sd_pair_key sd_wall_key_as_pair(sd_wall_pair_key k)
{
    sd_pair_key p;
    p.id_lo = k.id;
    p.id_hi = k.wall;
    p.sub_lo = k.sub;
    p.sub_hi = k.elem;
    return p;
}

/* Collects the entries worth keeping, sorted by key. Threaded like the
 * sort: each thread counts its share, then copies it to its place, so the
 * entries keep the pair-list order for any thread count. */
static sd_history *sd_history_collect(const sd_bins_input *in, const sd_history_src *s, size_t *count)
{
    enum { SHARES = 64 }; /* contiguous shares: the entries come out in pair-list order */
    size_t n = s->n;
    size_t before[SHARES + 1];
    SD_BINS_FOR(in)
    for (int q = 0; q < SHARES; ++q) {
        size_t c = 0;
        for (size_t k = n * (size_t)q / SHARES; k < n * (size_t)(q + 1) / SHARES; ++k)
            c += (size_t)sd_history_keep(s, k);
        before[q + 1] = c;
    }
    before[0] = 0;
    for (int q = 0; q < SHARES; ++q)
        before[q + 1] += before[q];
    size_t m = before[SHARES];
    *count = m;
    /* one block: the entries, then the radix sort's scratch */
    sd_history *h = sd_malloc(2 * (m ? m : 1) * sizeof *h);
    if (!h)
        return NULL;
    SD_BINS_FOR(in)
    for (int q = 0; q < SHARES; ++q) {
        size_t o = before[q];
        for (size_t k = n * (size_t)q / SHARES; k < n * (size_t)(q + 1) / SHARES; ++k)
            if (sd_history_keep(s, k)) {
                h[o].key = s->wkey ? sd_wall_key_as_pair(s->wkey[k]) : s->key[k];
                h[o].v = s->v[k];
                ++o;
            }
    }
    sd_history *sorted = sd_history_sort(in->threads, in->parallel, h, h + m, m);
    if (sorted != h)
        memcpy(h, sorted, m * sizeof *h);
    return h;
}

static const sd_history *sd_history_lookup(const sd_history *h, size_t n, const sd_pair_key *key)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (sd_key_less(&h[mid].key, key))
            lo = mid + 1;
        else
            hi = mid;
    }
    return (lo < n && sd_key_equal(&h[lo].key, key)) ? &h[lo] : NULL;
}

static sd_vec3 sd_history_find(const sd_history *h, size_t n, const sd_pair_key *key)
{
    const sd_history *e = sd_history_lookup(h, n, key);
    return e ? e->v : sd_v3_zero();
}

/* ---- cells ------------------------------------------------------------------ */

/* Sizes the bins for particles 0 .. n-1 and makes room for np particles. */
static sd_status sd_bins_setup(sd_bins *b, const sd_bins_input *in, size_t n, size_t np)
{
    const sd_vec3 *x = in->x;
    sd_vec3 lo = x[0], hi = x[0];
    sd_real rmax = 0;
    for (size_t k = 0; k < n; ++k) {
        lo = sd_v3_min(lo, x[k]);
        hi = sd_v3_max(hi, x[k]);
        rmax = sd_max(rmax, in->radius[k]);
    }
    sd_real h = SD_R(2.0) * rmax + in->skin;
    sd_vec3 ext = sd_v3_sub(hi, lo);
    /* keep the cell count near the particle count when the cloud is sparse
     * (a particle flying away must not make the grid huge) */
    double limit = (double)(4 * n + 64);
    for (;;) {
        double cx = floor((double)(ext.x / h)) + 1, cy = floor((double)(ext.y / h)) + 1,
               cz = floor((double)(ext.z / h)) + 1;
        if (cx * cy * cz <= limit) {
            b->nx = (int)cx;
            b->ny = (int)cy;
            b->nz = (int)cz;
            break;
        }
        h *= SD_R(1.26);
    }
    b->h = h;
    b->lo = lo;
    b->ncell = (size_t)b->nx * (size_t)b->ny * (size_t)b->nz;
    if (b->ncell + 1 > b->cell_cap) {
        if (sd_bins_grow((void **)&b->cell_start, b->ncell + 1, sizeof *b->cell_start))
            return SD_ERR_MEMORY;
        b->cell_cap = b->ncell + 1;
    }
    if (np > b->pcap) {
        size_t cap = np + np / 4 + 16;
        if (sd_bins_grow((void **)&b->cell, cap, sizeof *b->cell) || sd_bins_grow((void **)&b->perm, cap, sizeof *b->perm) ||
            sd_bins_grow((void **)&b->item, cap, sizeof *b->item) || sd_bins_grow((void **)&b->pos, cap, sizeof *b->pos) ||
            sd_bins_grow((void **)&b->count, SD_BINS_COUNT_KINDS * cap + 1, sizeof *b->count) ||
            sd_bins_grow((void **)&b->slot_kind, cap, SD_PAIR_SLOTS) || sd_bins_grow(&b->scratch, cap, SD_BINS_SCRATCH))
            return SD_ERR_MEMORY;
        b->pcap = cap;
    }
    return SD_OK;
}

static SD_INLINE uint32_t sd_bins_cell(const sd_bins *b, sd_vec3 x)
{
    int cx = (int)((x.x - b->lo.x) / b->h), cy = (int)((x.y - b->lo.y) / b->h), cz = (int)((x.z - b->lo.z) / b->h);
    cx = cx < 0 ? 0 : (cx >= b->nx ? b->nx - 1 : cx);
    cy = cy < 0 ? 0 : (cy >= b->ny ? b->ny - 1 : cy);
    cz = cz < 0 ? 0 : (cz >= b->nz ? b->nz - 1 : cz);
    return (uint32_t)(((size_t)cz * (size_t)b->ny + (size_t)cy) * (size_t)b->nx + (size_t)cx);
}

/* Counting sort of particles 0 .. n-1 by cell into order (stable: storage
 * order within a cell); fills cell_start. */
static void sd_bins_count_sort(sd_bins *b, size_t n, uint32_t *order)
{
    memset(b->cell_start, 0, (b->ncell + 1) * sizeof *b->cell_start);
    for (size_t k = 0; k < n; ++k)
        b->cell_start[b->cell[k] + 1]++;
    for (size_t c = 0; c < b->ncell; ++c)
        b->cell_start[c + 1] += b->cell_start[c];
    for (size_t k = 0; k < n; ++k) {
        uint32_t c = b->cell[k];
        order[b->cell_start[c]++] = (uint32_t)k;
    }
    /* cell_start was advanced to the cell ends: shift back */
    for (size_t c = b->ncell; c > 0; --c)
        b->cell_start[c] = b->cell_start[c - 1];
    b->cell_start[0] = 0;
}

sd_status sd_bins_sort(sd_bins *b, const sd_bins_input *in, const uint32_t **perm, void **scratch)
{
    size_t n = in->n_owned;
    b->sorted_n = 0;
    if (n == 0) {
        *perm = NULL;
        *scratch = NULL;
        return SD_OK;
    }
    if (sd_bins_setup(b, in, n, in->n_total) != SD_OK)
        return SD_ERR_MEMORY;
    SD_BINS_FOR(in)
    for (size_t k = 0; k < n; ++k)
        b->cell[k] = sd_bins_cell(b, in->x[k]);
    sd_bins_count_sort(b, n, b->perm);
    b->sorted_n = n;
    *perm = b->perm;
    *scratch = b->scratch;
    return SD_OK;
}

/* ---- pair list ------------------------------------------------------------- */

static SD_INLINE int sd_bins_class(const sd_bins_input *in, size_t k)
{
    int32_t s = in->shape ? in->shape[k] : -1;
    return s < 0 ? SD_CLASS_SPHERE : in->shape_class[s];
}

static SD_INLINE int sd_bins_volume(const sd_bins_input *in, int32_t ma, int32_t mb)
{
    return in->volume_law ? in->volume_law[(size_t)ma * in->material_count + (size_t)mb] : 0;
}

/* The owned particle a ghost stands for (an owned particle stands for itself). */
static SD_INLINE size_t sd_bins_owner(const sd_bins_input *in, size_t k)
{
    return k < in->n_owned ? k : in->ghost_owner[k - in->n_owned];
}

/* ---- composite elements (seed 004 §2.5) ---------------------------------- */

/* The template of composite particle k, or NULL when k is not a composite. */
static SD_INLINE const sd_shape *sd_bins_composite(const sd_bins_input *in, size_t k)
{
    int32_t s = in->shape ? in->shape[k] : -1;
    return (s >= 0 && in->shape_class[s] == SD_CLASS_COMPOSITE) ? &in->shapes[s] : NULL;
}

/* The bounding sphere of element t of particle k: its centre (returned)
 * and radius *r (m). A particle that is not a composite is its own only
 * element, its bounding sphere. x_e = x + R(q) e.x (seed 004 eq. 6). */
static SD_INLINE sd_vec3 sd_bins_element_sphere(const sd_bins_input *in, size_t k, const sd_shape *c, uint32_t t,
                                                sd_real *r)
{
    if (!c) {
        *r = in->radius[k];
        return in->x[k];
    }
    const sd_element *e = &in->elements[c->estart + t];
    *r = e->bound;
    return sd_v3_add(in->x[k], sd_quat_rotate(in->q[k], e->x));
}

/* The element pairs of the candidate pair (i, j), i < j: those whose
 * element bounding spheres are closer than the sum of their radii plus
 * the skin, elements of i outer, of j inner. Returns their count; with l
 * set, writes them at l's cursor *cur (i, j, and the elements of i and j
 * in key.sub_lo / key.sub_hi, put in id order by the key pass). */
static uint32_t sd_bins_element_pairs(const sd_bins_input *in, size_t i, size_t j, sd_pair_list *l, size_t *cur)
{
    const sd_shape *ci = sd_bins_composite(in, i), *cj = sd_bins_composite(in, j);
    uint32_t ni = ci ? ci->ecount : 1, nj = cj ? cj->ecount : 1;
    uint32_t m = 0;
    enum { CACHE = 64 }; /* element spheres of j, computed once for all of i's */
    sd_vec3 xj[CACHE];
    sd_real rj[CACHE];
    for (uint32_t b = 0; b < nj && b < CACHE; ++b)
        xj[b] = sd_bins_element_sphere(in, j, cj, b, &rj[b]);
    for (uint32_t a = 0; a < ni; ++a) {
        sd_real ra;
        sd_vec3 xa = sd_bins_element_sphere(in, i, ci, a, &ra);
        ra += in->skin;
        for (uint32_t b = 0; b < nj; ++b) {
            sd_real rb;
            sd_vec3 xb = b < CACHE ? xj[b] : sd_bins_element_sphere(in, j, cj, b, &rb);
            if (b < CACHE)
                rb = rj[b];
            sd_real rs = ra + rb;
            if (!(sd_v3_norm2(sd_v3_sub(xa, xb)) < rs * rs))
                continue;
            if (l) {
                size_t e = (*cur)++;
                l->i[e] = (uint32_t)i;
                l->j[e] = (uint32_t)j;
                l->key[e].sub_lo = a;
                l->key[e].sub_hi = b;
            }
            ++m;
        }
    }
    return m;
}

/* Where the candidates of one particle go: the first cap of them (other
 * particle and kind) into out_j / out_k, or, with direct set, straight into
 * the list at the kind cursors (those of kind only_kind, or all if < 0). */
typedef struct sd_bins_sink {
    uint32_t *out_j;
    uint8_t *out_k;
    uint32_t cap;
    sd_pair_list *direct;
    size_t *cursor;
    uint32_t *kind_count; /* per kind, every candidate counted (or NULL) */
} sd_bins_sink;

/* Visits the candidates of particle a (owned or ghost): the particles in
 * its own cell after it and in the 13 cells after its own, closer than
 * r_a + r_b + skin, less the pairs bins.h rules out for ghosts; returns how
 * many there are. */
static uint32_t sd_bins_candidates(const sd_bins *b, const sd_bins_input *in, size_t a, const sd_bins_sink *sink)
{
    const size_t no = in->n_owned;
    const sd_vec3 *x = in->x;
    const sd_real *radius = in->radius;
    const int items = b->use_items;
    uint32_t c = b->cell[a];
    int cx = (int)(c % (uint32_t)b->nx);
    int cy = (int)((c / (uint32_t)b->nx) % (uint32_t)b->ny);
    int cz = (int)(c / ((uint32_t)b->nx * (uint32_t)b->ny));
    size_t pa = items ? b->pos[a] : a;
    sd_vec3 xa = x[a];
    sd_real ra = radius[a] + in->skin;
    int ca = sd_bins_class(in, a);
    int32_t ma = in->material[a];
    int ghost_a = a >= no;
    size_t own_a = sd_bins_owner(in, a);
    uint32_t m = 0;
    for (int dz = 0; dz <= 1; ++dz)
        for (int dy = (dz ? -1 : 0); dy <= 1; ++dy)
            for (int dx = ((dz || dy) ? -1 : 0); dx <= 1; ++dx) {
                int gx = cx + dx, gy = cy + dy, gz = cz + dz;
                if (gx < 0 || gy < 0 || gz >= b->nz || gx >= b->nx || gy >= b->ny)
                    continue;
                size_t nc = ((size_t)gz * (size_t)b->ny + (size_t)gy) * (size_t)b->nx + (size_t)gx;
                size_t t0 = b->cell_start[nc], t1 = b->cell_start[nc + 1];
                if (nc == c)
                    t0 = pa + 1;
                for (size_t t = t0; t < t1; ++t) {
                    size_t bb = items ? b->item[t] : t;
                    sd_real rs = ra + radius[bb];
                    if (!(sd_v3_norm2(sd_v3_sub(xa, x[bb])) < rs * rs))
                        continue;
                    if (ghost_a || bb >= no) {
                        /* bins.h: no ghost pairs, no pair with one's own
                         * image, and a contact through an image only from
                         * the side with the lower stable id */
                        size_t own_b = sd_bins_owner(in, bb);
                        if (ghost_a && bb >= no) {
                            /* the one pair of two ghosts: another rank's
                             * particle as it is and a local image, the
                             * former with the lower id (that rank evaluates
                             * the same pair through the image it was sent) */
                            int keep = (own_a < no && own_b == SD_GHOST_REMOTE && in->id[bb] < in->id[a]) ||
                                       (own_b < no && own_a == SD_GHOST_REMOTE && in->id[a] < in->id[bb]);
                            if (!keep)
                                continue;
                        } else {
                            if (own_a == own_b)
                                continue;
                            size_t o = ghost_a ? bb : a, g = ghost_a ? a : bb;
                            /* another rank's particle as it is: the pair is
                             * evaluated on both ranks, each gathering its
                             * own side; an image (local or another rank's)
                             * only from the lower id */
                            if (sd_bins_owner(in, g) != SD_GHOST_REMOTE && !(in->id[o] < in->id[g]))
                                continue;
                        }
                    }
                    int kind = sd_bins_pair_kind(ca, sd_bins_class(in, bb), sd_bins_volume(in, ma, in->material[bb]));
                    uint32_t np = 1;
                    if (kind == SD_PAIR_ELEMENTS) {
                        /* the second level: element bounding spheres */
                        np = sd_bins_element_pairs(in, a < bb ? a : bb, a < bb ? bb : a, sink->direct,
                                                   sink->direct ? &sink->cursor[kind] : NULL);
                        if (np == 0)
                            continue;
                    }
                    if (sink->kind_count)
                        sink->kind_count[kind] += np;
                    if (sink->direct) {
                        if (kind != SD_PAIR_ELEMENTS) {
                            size_t e = sink->cursor[kind]++;
                            sink->direct->i[e] = (uint32_t)(a < bb ? a : bb);
                            sink->direct->j[e] = (uint32_t)(a < bb ? bb : a);
                        }
                    } else if (m < sink->cap) {
                        sink->out_j[m] = (uint32_t)bb;
                        sink->out_k[m] = (uint8_t)kind;
                    }
                    ++m;
                }
            }
    return m;
}

/* The same for the plain case, a world of spheres without ghosts in the
 * order of the sort: every candidate is a sphere pair and j > a (the hot
 * path of large sphere beds, kept as lean as the search before kinds and
 * ghosts). Writes the first cap to out_j. */
static uint32_t sd_bins_candidates_spheres(const sd_bins *b, const sd_bins_input *in, size_t a, uint32_t *out_j,
                                           uint32_t cap)
{
    const sd_vec3 *x = in->x;
    const sd_real *radius = in->radius;
    uint32_t c = b->cell[a];
    int cx = (int)(c % (uint32_t)b->nx);
    int cy = (int)((c / (uint32_t)b->nx) % (uint32_t)b->ny);
    int cz = (int)(c / ((uint32_t)b->nx * (uint32_t)b->ny));
    sd_vec3 xa = x[a];
    sd_real ra = radius[a] + in->skin;
    uint32_t m = 0;
    for (int dz = 0; dz <= 1; ++dz)
        for (int dy = (dz ? -1 : 0); dy <= 1; ++dy)
            for (int dx = ((dz || dy) ? -1 : 0); dx <= 1; ++dx) {
                int gx = cx + dx, gy = cy + dy, gz = cz + dz;
                if (gx < 0 || gy < 0 || gz >= b->nz || gx >= b->nx || gy >= b->ny)
                    continue;
                size_t nc = ((size_t)gz * (size_t)b->ny + (size_t)gy) * (size_t)b->nx + (size_t)gx;
                size_t j0 = b->cell_start[nc], j1 = b->cell_start[nc + 1];
                if (nc == c)
                    j0 = a + 1;
                for (size_t j = j0; j < j1; ++j) {
                    sd_real rs = ra + radius[j];
                    if (sd_v3_norm2(sd_v3_sub(xa, x[j])) < rs * rs) {
                        if (m < cap)
                            out_j[m] = (uint32_t)j;
                        ++m;
                    }
                }
            }
    return m;
}

/* The bins of the build: with no ghosts, the cells of the sort (the world
 * has applied its order, so only each particle's cell is looked up again);
 * with ghosts, cells over all particles and an index in cell order. */
static sd_status sd_bins_prepare_build(sd_bins *b, const sd_bins_input *in)
{
    size_t n = in->n_total;
    if (n == in->n_owned && b->sorted_n == n) {
        b->use_items = 0;
        SD_BINS_FOR(in)
        for (size_t k = 0; k < n; ++k)
            b->cell[k] = sd_bins_cell(b, in->x[k]);
        return SD_OK;
    }
    if (sd_bins_setup(b, in, n, n) != SD_OK)
        return SD_ERR_MEMORY;
    SD_BINS_FOR(in)
    for (size_t k = 0; k < n; ++k)
        b->cell[k] = sd_bins_cell(b, in->x[k]);
    sd_bins_count_sort(b, n, b->item);
    for (size_t t = 0; t < n; ++t)
        b->pos[b->item[t]] = (uint32_t)t;
    b->use_items = 1;
    return SD_OK;
}

static sd_status sd_bins_pairs(sd_bins *b, const sd_bins_input *in, sd_pair_list *l)
{
    enum { K = SD_PAIR_KIND_COUNT };
    size_t n = in->n_total, no = in->n_owned;
    uint32_t *cnt = b->count; /* cnt[kind * n + particle], then its offsets */

    size_t nhist = 0, nhint = 0;
    sd_history_src hs = {l->n, l->key, NULL, l->ds, NULL};
    sd_history *hist = sd_history_collect(in, &hs, &nhist);
    if (!hist)
        return SD_ERR_MEMORY;
    /* overlap hints only where a volume law can use them (pairs.h) */
    int hinted = in->volume_law != NULL;
    sd_history_src hn = {l->n, l->key, NULL, l->x0, l->x0_ok};
    sd_history *hints = hinted ? sd_history_collect(in, &hn, &nhint) : NULL;
    if (hinted && !hints) {
        sd_free(hist);
        return SD_ERR_MEMORY;
    }

    /* one search per particle: its candidates go to a small fixed slot in
     * the scratch (SD_PAIR_SLOTS each), counted by kind; only a particle
     * with more candidates than that is searched again in the fill */
    uint32_t *slots = (uint32_t *)b->scratch;
    uint8_t *kinds = b->slot_kind;
    unsigned present = 0;
    const int plain = !b->use_items && n == no && !in->shape;
    if (plain) {
        SD_BINS_FOR(in)
        for (size_t a = 0; a < n; ++a)
            cnt[a] = sd_bins_candidates_spheres(b, in, a, slots + a * SD_PAIR_SLOTS, SD_PAIR_SLOTS);
        present = 1u << SD_PAIR_SPHERES;
    } else
    SD_PRAGMA(omp parallel for schedule(static) num_threads(in->threads) if (in->parallel) reduction(| : present))
    for (size_t a = 0; a < n; ++a) {
        uint32_t ck[K] = {0};
        sd_bins_sink s = {slots + a * SD_PAIR_SLOTS, kinds + a * SD_PAIR_SLOTS, SD_PAIR_SLOTS, NULL, NULL, ck};
        (void)sd_bins_candidates(b, in, a, &s);
        for (int k = 0; k < K; ++k) {
            cnt[(size_t)k * n + a] = ck[k];
            present |= (unsigned)(ck[k] != 0) << k;
        }
    }
    /* offsets, kind by kind (the kind segments), particle by particle */
    size_t total = 0;
    for (int k = 0; k < K; ++k) {
        l->kind_start[k] = total;
        if (!(present & (1u << k)))
            continue;
        uint32_t *c = cnt + (size_t)k * n;
        for (size_t a = 0; a < n; ++a) {
            uint32_t v = c[a];
            c[a] = (uint32_t)total;
            total += v;
        }
    }
    l->kind_start[K] = total;
    if (total > UINT32_MAX / 2 || sd_pairs_reserve(l, total)) {
        sd_free(hist);
        sd_free(hints);
        return SD_ERR_MEMORY;
    }
    l->n = total;
    if (plain) {
        SD_BINS_FOR(in)
        for (size_t a = 0; a < n; ++a) {
            uint32_t off = cnt[a];
            uint32_t m = (a + 1 < n ? cnt[a + 1] : (uint32_t)total) - off;
            /* no pairs for a: skip, as l->j is NULL in a world without
             * pairs and memcpy from or to NULL is undefined even for 0 bytes */
            if (m == 0)
                continue;
            if (m <= SD_PAIR_SLOTS)
                memcpy(l->j + off, slots + a * SD_PAIR_SLOTS, m * sizeof *l->j);
            else
                sd_bins_candidates_spheres(b, in, a, l->j + off, UINT32_MAX);
            for (uint32_t t = 0; t < m; ++t)
                l->i[off + t] = (uint32_t)a;
        }
    } else
    SD_BINS_FOR(in)
    for (size_t a = 0; a < n; ++a) {
        size_t cur[K];
        size_t m = 0;
        for (int k = 0; k < K; ++k) {
            cur[k] = (present & (1u << k)) ? cnt[(size_t)k * n + a] : 0;
            size_t next = (present & (1u << k)) ? (a + 1 < n ? cnt[(size_t)k * n + a + 1] : l->kind_start[k + 1]) : 0;
            m += next - cur[k];
        }
        if (m == 0)
            continue;
        /* element pairs are many pairs per candidate: such a particle is
         * searched again, its element pairs written in place */
        int elem = (present & (1u << SD_PAIR_ELEMENTS)) &&
                   (a + 1 < n ? cnt[(size_t)SD_PAIR_ELEMENTS * n + a + 1] : l->kind_start[SD_PAIR_ELEMENTS + 1]) >
                       cnt[(size_t)SD_PAIR_ELEMENTS * n + a];
        if (m <= SD_PAIR_SLOTS && !elem) {
            for (size_t t = 0; t < m; ++t) {
                size_t bb = slots[a * SD_PAIR_SLOTS + t];
                size_t e = cur[kinds[a * SD_PAIR_SLOTS + t]]++;
                l->i[e] = (uint32_t)(a < bb ? a : bb);
                l->j[e] = (uint32_t)(a < bb ? bb : a);
            }
        } else {
            sd_bins_sink s = {NULL, NULL, 0, l, cur, NULL};
            (void)sd_bins_candidates(b, in, a, &s);
        }
    }
    /* per pair: the key, the carried history, the fields that start at
     * zero, the spring's side */
    SD_BINS_FOR(in)
    for (size_t e = 0; e < total; ++e) {
        uint32_t i = l->i[e], j = l->j[e];
        uint64_t a = in->id[i], c = in->id[j];
        sd_pair_key key;
        key.id_lo = a < c ? a : c;
        key.id_hi = a < c ? c : a;
        key.sub_lo = 0;
        key.sub_hi = 0;
        if (e >= l->kind_start[SD_PAIR_ELEMENTS] && e < l->kind_start[SD_PAIR_ELEMENTS + 1]) {
            /* the fill left the elements of i and j here: in id order now */
            uint32_t si = l->key[e].sub_lo, sj = l->key[e].sub_hi;
            key.sub_lo = a < c ? si : sj;
            key.sub_hi = a < c ? sj : si;
        }
        l->key[e] = key;
#define SD_X_ZERO(type, name, per, role, doc) \
    if ((role) == SD_PF_ZERO)                 \
        memset(&l->name[(size_t)(per) * e], 0, (size_t)(per) * sizeof *l->name);
        SD_PAIR_FIELDS(SD_X_ZERO)
#undef SD_X_ZERO
        sd_vec3 s = sd_history_find(hist, nhist, &key);
        l->ds[e] = s;
        if (hinted) {
            const sd_history *hh = sd_history_lookup(hints, nhint, &key);
            l->x0[e] = hh ? hh->v : sd_v3_zero();
            l->x0_ok[e] = hh != NULL;
        } else {
            l->x0[e] = sd_v3_zero();
            l->x0_ok[e] = 0;
        }
        l->flip[e] = a > c;
        /* a pair that carries a spring is evaluated at the next step even if
         * it has just come apart, so that its spring is cleared (the force
         * loops skip pairs that were and are apart) */
        l->delta[e] = (s.x != 0 || s.y != 0 || s.z != 0) ? SD_R(1e-300) : SD_R(0.0);
    }
    sd_free(hist);
    sd_free(hints);

    /* gather lists for the owned particles, filled in pair order so every
     * particle sums its pairs in the same order whatever the thread count.
     * The side of a ghost goes to its owner: the owner receives the pair's
     * reaction, and momentum is conserved exactly. (An MPI backend replaces
     * this reverse gather by its own exchange: the reaction on a ghost of
     * another rank is sent back to that rank.) */
    if (no + 1 > l->gstart_cap) {
        if (sd_bins_grow((void **)&l->gstart, no + 1, sizeof *l->gstart))
            return SD_ERR_MEMORY;
        l->gstart_cap = no + 1;
    }
    memset(l->gstart, 0, (no + 1) * sizeof *l->gstart);
    for (size_t e = 0; e < total; ++e)
        for (int side = 0; side < 2; ++side) {
            size_t o = sd_bins_owner(in, side ? l->j[e] : l->i[e]);
            if (o < no) /* another rank's particle: gathered there */
                l->gstart[o + 1]++;
        }
    for (size_t i = 0; i < no; ++i)
        l->gstart[i + 1] += l->gstart[i];
    memcpy(cnt, l->gstart, no * sizeof *cnt);
    for (size_t e = 0; e < total; ++e)
        for (int side = 0; side < 2; ++side) {
            size_t o = sd_bins_owner(in, side ? l->j[e] : l->i[e]);
            if (o < no)
                l->gidx[cnt[o]++] = (uint32_t)(2 * e + (size_t)side);
        }
    return SD_OK;
}

/* ---- wall pairs ------------------------------------------------------------ */

/* ---- mesh walls (dynamics/meshwall.h) ----------------------------------------- */

/* Triangles of one mesh within reach of one particle that fit the stack
 * workspace; a particle with more (a large body on a fine mesh) queries
 * again into a heap buffer of the size it needs (sd_bins_mesh_near), so no
 * facet is ever left out. */
enum { SD_BINS_MESH_MAXT = 2048 };

static void sd_bins_sort_u64(uint64_t *a, uint32_t n)
{
    /* Shell sort (Ciura's gaps, extended by 2.25 for the long lists of a
     * large body on a fine mesh): no allocation, a total order */
    static const uint32_t gaps[] = {90927, 40412, 17961, 7983, 3548, 1577, 701, 301, 132, 57, 23, 10, 4, 1};
    for (int g = 0; g < 14; ++g) {
        uint32_t h = gaps[g];
        for (uint32_t i = h; i < n; ++i) {
            uint64_t v = a[i];
            uint32_t j = i;
            while (j >= h && a[j - h] > v) {
                a[j] = a[j - h];
                j -= h;
            }
            a[j] = v;
        }
    }
}

/* The triangles of mesh wall wg within distance r of x (the particle
 * mapped into the mesh frame: the facet bins never move), as (group << 32
 * | triangle), the first cap of them in buf; returns how many there are
 * (a triangle met in several cells counted each time). Cells of edge
 * h >= 2 r: at most 2 x 2 x 2 cells. */
static uint32_t sd_bins_mesh_query(const sd_bins_input *in, const sd_wall_geom *wg, sd_vec3 x, sd_real r,
                                   uint64_t *buf, uint32_t cap)
{
    if (!in->meshes || (size_t)wg->mesh >= in->mesh_count)
        return 0;
    const sd_mesh_view *mv = &in->meshes[wg->mesh];
    if (!(mv->h > 0) || mv->entry_count == 0)
        return 0;
    sd_vec3 xm = sd_mesh_to_frame(wg->q, wg->trans, x);
    sd_real h = mv->h;
    long i0 = sd_mesh_cell_of(xm.x - r, mv->origin.x, h), i1 = sd_mesh_cell_of(xm.x + r, mv->origin.x, h);
    long j0 = sd_mesh_cell_of(xm.y - r, mv->origin.y, h), j1 = sd_mesh_cell_of(xm.y + r, mv->origin.y, h);
    long k0 = sd_mesh_cell_of(xm.z - r, mv->origin.z, h), k1 = sd_mesh_cell_of(xm.z + r, mv->origin.z, h);
    uint32_t n = 0;
    sd_real r2 = r * r;
    for (long i = i0; i <= i1; ++i)
        for (long j = j0; j <= j1; ++j)
            for (long k = k0; k <= k1; ++k) {
                uint64_t key = sd_mesh_key(i, j, k);
                for (size_t e = sd_mesh_lower(mv, key); e < mv->entry_count && mv->entry_key[e] == key; ++e) {
                    uint32_t t = mv->entry_tri[e];
                    const uint32_t *tv = mv->tris[t];
                    int feature;
                    sd_vec3 c = sd_clip_closest(xm, mv->verts[tv[0]], mv->verts[tv[1]], mv->verts[tv[2]], &feature);
                    if (sd_v3_norm2(sd_v3_sub(xm, c)) >= r2)
                        continue;
                    if (n < cap)
                        buf[n] = ((uint64_t)mv->group[t] << 32) | t;
                    ++n;
                }
            }
    return n;
}

/* A particle's near triangles of one mesh (sd_bins_mesh_query) sorted and
 * unique, in stack (SD_BINS_MESH_MAXT entries) or, when more are near,
 * in *heap (grown to *heap_cap entries; the caller frees it); *out points
 * to them. Returns how many; sets *oom and returns 0 when the heap
 * buffer cannot grow. */
static uint32_t sd_bins_mesh_near(const sd_bins_input *in, const sd_wall_geom *wg, sd_vec3 x, sd_real r,
                                  uint64_t *stack, uint64_t **heap, size_t *heap_cap, const uint64_t **out,
                                  int *oom)
{
    uint64_t *buf = stack;
    uint32_t n = sd_bins_mesh_query(in, wg, x, r, stack, SD_BINS_MESH_MAXT);
    if (n > SD_BINS_MESH_MAXT) {
        if (n > *heap_cap) {
            uint64_t *h = sd_realloc(*heap, (size_t)n * sizeof *h);
            if (!h) {
                *oom = 1;
                *out = stack;
                return 0;
            }
            *heap = h;
            *heap_cap = n;
        }
        buf = *heap;
        n = sd_bins_mesh_query(in, wg, x, r, buf, n);
    }
    sd_bins_sort_u64(buf, n);
    uint32_t u = 0;
    for (uint32_t q = 0; q < n; ++q)
        if (u == 0 || buf[q] != buf[u - 1])
            buf[u++] = buf[q];
    *out = buf;
    return u;
}

/* The near triangles of every mesh pair (tstart, tcount into l->tri), in
 * particle order, then each particle's pairs in gather order (wall by
 * wall, groups ascending: the order of sd_bins_mesh_query's runs). */
static sd_status sd_bins_mesh_tris(sd_bins *b, const sd_bins_input *in, sd_wall_pair_list *l)
{
    size_t n = in->n_owned;
    uint32_t *ptot = b->count; /* free again after the pair placement: n + 1 entries */
    int oom = 0;
    for (int pass = 0; pass < 2; ++pass) {
        SD_PRAGMA(omp parallel for schedule(static) num_threads(in->threads) if (in->parallel) reduction(| : oom))
        for (size_t a = 0; a < n; ++a) {
            uint32_t g0 = l->gstart[a], g1 = l->gstart[a + 1];
            uint32_t off = pass ? ptot[a] : 0, tot = 0;
            uint64_t stack[SD_BINS_MESH_MAXT], *heap = NULL;
            size_t heap_cap = 0;
            const uint64_t *buf = stack;
            uint32_t nt = 0, q = 0;
            int cur = -1;
            for (uint32_t g = g0; g < g1; ++g) {
                uint32_t e = l->gidx[g];
                const sd_wall_geom *wg = &in->walls[l->wall[e]];
                if (wg->kind != SD_WALL_MESH)
                    continue;
                if ((int)l->wall[e] != cur) {
                    cur = (int)l->wall[e];
                    nt = sd_bins_mesh_near(in, wg, in->x[a], in->radius[a] + in->skin, stack, &heap, &heap_cap, &buf,
                                           &oom);
                    q = 0;
                }
                if (g > g0 && l->wall[l->gidx[g - 1]] == l->wall[e] && l->sub[l->gidx[g - 1]] == l->sub[e]) {
                    /* the next element of a composite against the same
                     * group: the same near triangles */
                    if (pass) {
                        l->tstart[e] = l->tstart[l->gidx[g - 1]];
                        l->tcount[e] = l->tcount[l->gidx[g - 1]];
                    }
                    continue;
                }
                while (q < nt && (uint32_t)(buf[q] >> 32) < l->sub[e])
                    ++q;
                uint32_t q0 = q;
                while (q < nt && (uint32_t)(buf[q] >> 32) == l->sub[e]) {
                    if (pass)
                        l->tri[off + tot + (q - q0)] = (uint32_t)(buf[q] & 0xffffffffu);
                    ++q;
                }
                if (pass) {
                    l->tstart[e] = off + tot;
                    l->tcount[e] = q - q0;
                }
                tot += q - q0;
            }
            if (!pass)
                ptot[a] = tot;
            sd_free(heap);
        }
        if (oom)
            return SD_ERR_MEMORY;
        if (!pass) {
            size_t sum = 0;
            for (size_t a = 0; a < n; ++a) {
                uint32_t v = ptot[a];
                ptot[a] = (uint32_t)sum;
                sum += v;
            }
            if (sum > l->tri_cap) {
                if (sd_bins_grow((void **)&l->tri, sum, sizeof *l->tri))
                    return SD_ERR_MEMORY;
                l->tri_cap = sum;
            }
            l->tri_n = sum;
        }
    }
    return SD_OK;
}

/* 1 when the bounding sphere of element t of composite particle a, grown
 * by the skin, reaches one of the nt triangles tl (group << 32 | triangle,
 * sd_bins_mesh_query's entries) of mesh wall wg. */
static int sd_bins_element_near_mesh(const sd_bins_input *in, const sd_wall_geom *wg, const sd_shape *comp, size_t a,
                                     uint32_t t, const uint64_t *tl, uint32_t nt)
{
    const sd_mesh_view *mv = &in->meshes[wg->mesh];
    sd_real re;
    sd_vec3 xe = sd_mesh_to_frame(wg->q, wg->trans, sd_bins_element_sphere(in, a, comp, t, &re));
    sd_real r = re + in->skin;
    for (uint32_t q = 0; q < nt; ++q) {
        const uint32_t *tv = mv->tris[(uint32_t)(tl[q] & 0xffffffffu)];
        int feature;
        sd_vec3 c = sd_clip_closest(xe, mv->verts[tv[0]], mv->verts[tv[1]], mv->verts[tv[2]], &feature);
        if (sd_v3_norm2(sd_v3_sub(xe, c)) < r * r)
            return 1;
    }
    return 0;
}

/* Visits the wall candidates of owned particle a: the features within its
 * reach (bounding radius plus skin), wall by wall, feature by feature
 * (dynamics/walls.h), and for a composite, within such a feature, each
 * element whose bounding sphere is within the skin of it (seed 004 §2.5).
 * With out_w set, writes candidates skip .. skip + cap - 1 (wall, feature,
 * element, kind) there; counts them all per kind into kind_count. */
static uint32_t sd_bins_wall_candidates(const sd_bins_input *in, size_t a, uint32_t skip, uint32_t cap,
                                        uint16_t *out_w, uint32_t *out_f, uint32_t *out_e, uint8_t *out_k,
                                        uint32_t *kind_count, int *oom)
{
    sd_vec3 x = in->x[a];
    sd_real reach = in->radius[a] + in->skin;
    int ca = sd_bins_class(in, a);
    int32_t ma = in->material[a];
    const sd_shape *comp = ca == SD_CLASS_COMPOSITE ? sd_bins_composite(in, a) : NULL;
    uint32_t ne = comp ? comp->ecount : 1;
    uint32_t m = 0;
    for (size_t wi = 0; wi < in->wall_count; ++wi) {
        const sd_wall_geom *wg = &in->walls[wi];
        if (wg->kind == SD_WALL_MESH) {
            /* one candidate per plane group with a triangle within reach,
             * groups ascending (seed 000 §2.4) */
            int kind = sd_bins_mesh_pair_kind(ca, sd_bins_volume(in, ma, in->wall_material[wi]));
            uint64_t stack[SD_BINS_MESH_MAXT], *heap = NULL;
            size_t heap_cap = 0;
            const uint64_t *buf;
            uint32_t nt = sd_bins_mesh_near(in, wg, x, reach, stack, &heap, &heap_cap, &buf, oom);
            for (uint32_t q = 0; q < nt; ++q) {
                uint32_t g = (uint32_t)(buf[q] >> 32);
                if (q > 0 && (uint32_t)(buf[q - 1] >> 32) == g)
                    continue;
                /* a composite: each element whose bounding sphere (plus
                 * the skin) reaches a triangle of this group, elements
                 * ascending within the group (one run per group) */
                uint32_t q1 = q;
                while (q1 < nt && (uint32_t)(buf[q1] >> 32) == g)
                    ++q1;
                for (uint32_t t = 0; t < ne; ++t) {
                    if (comp && !sd_bins_element_near_mesh(in, wg, comp, a, t, buf + q, q1 - q))
                        continue;
                    if (kind_count)
                        kind_count[kind]++;
                    if (out_w && m >= skip && m - skip < cap) {
                        out_w[m - skip] = (uint16_t)wi;
                        out_f[m - skip] = g;
                        out_e[m - skip] = t;
                        out_k[m - skip] = (uint8_t)kind;
                    }
                    ++m;
                }
            }
            sd_free(heap);
            continue;
        }
        int nf = sd_wall_feature_count(wg);
        for (int f = 0; f < nf; ++f) {
            if (!sd_wall_feature_exists(wg, f) || !sd_wall_feature_near(wg, f, x, reach))
                continue;
            int kind = sd_bins_wall_pair_kind(ca, sd_bins_volume(in, ma, in->wall_material[wi]));
            for (uint32_t t = 0; t < ne; ++t) {
                if (comp) {
                    sd_real re;
                    sd_vec3 xe = sd_bins_element_sphere(in, a, comp, t, &re);
                    if (!sd_wall_feature_near(wg, f, xe, re + in->skin))
                        continue;
                }
                if (kind_count)
                    kind_count[kind]++;
                if (out_w && m >= skip && m - skip < cap) {
                    out_w[m - skip] = (uint16_t)wi;
                    out_f[m - skip] = (uint16_t)f;
                    out_e[m - skip] = t;
                    out_k[m - skip] = (uint8_t)kind;
                }
                ++m;
            }
        }
    }
    return m;
}

static sd_status sd_bins_wall_pairs(sd_bins *b, const sd_bins_input *in, sd_wall_pair_list *l)
{
    enum { K = SD_WALL_PAIR_KIND_COUNT };
    size_t n = in->n_owned; /* ghosts get no wall pairs */
    if (n + 1 > l->gstart_cap) {
        if (sd_bins_grow((void **)&l->gstart, n + 1, sizeof *l->gstart))
            return SD_ERR_MEMORY;
        l->gstart_cap = n + 1;
    }
    size_t nhist = 0;
    sd_history_src hs = {l->n, NULL, l->key, l->ds, NULL};
    sd_history *hist = sd_history_collect(in, &hs, &nhist);
    if (!hist)
        return SD_ERR_MEMORY;
    uint32_t *cnt = b->count; /* cnt[kind * n + particle], then its offsets */
    unsigned present = 0;
    int oom = 0;
    SD_PRAGMA(omp parallel for schedule(static) num_threads(in->threads) if (in->parallel) reduction(| : present, oom))
    for (size_t a = 0; a < n; ++a) {
        uint32_t ck[K] = {0};
        l->gstart[a + 1] = sd_bins_wall_candidates(in, a, 0, 0, NULL, NULL, NULL, NULL, ck, &oom);
        for (int k = 0; k < K; ++k) {
            cnt[(size_t)k * n + a] = ck[k];
            present |= (unsigned)(ck[k] != 0) << k;
        }
    }
    if (oom) {
        sd_free(hist);
        return SD_ERR_MEMORY;
    }
    l->gstart[0] = 0;
    for (size_t a = 0; a < n; ++a)
        l->gstart[a + 1] += l->gstart[a];
    size_t total = 0;
    for (int k = 0; k < K; ++k) {
        l->kind_start[k] = total;
        if (!(present & (1u << k)))
            continue;
        uint32_t *c = cnt + (size_t)k * n;
        for (size_t a = 0; a < n; ++a) {
            uint32_t v = c[a];
            c[a] = (uint32_t)total;
            total += v;
        }
    }
    l->kind_start[K] = total;
    if (sd_pairs_reserve_walls(l, total)) {
        sd_free(hist);
        return SD_ERR_MEMORY;
    }
    l->n = total;
    SD_PRAGMA(omp parallel for schedule(static) num_threads(in->threads) if (in->parallel) reduction(| : oom))
    for (size_t a = 0; a < n; ++a) {
        uint32_t g0 = l->gstart[a], m = l->gstart[a + 1] - g0;
        if (m == 0)
            continue;
        enum { MAXF = 64 };
        uint16_t ow[MAXF];
        uint32_t of[MAXF], oe[MAXF];
        uint8_t ok[MAXF];
        size_t cur[K];
        for (int k = 0; k < K; ++k)
            cur[k] = (present & (1u << k)) ? cnt[(size_t)k * n + a] : 0;
        /* MAXF candidates at a time (a particle near many features, or a
         * composite with many elements near one, walks them again) */
        for (uint32_t t0 = 0; t0 < m; t0 += MAXF) {
            (void)sd_bins_wall_candidates(in, a, t0, MAXF, ow, of, oe, ok, NULL, &oom);
            uint32_t got = m - t0 < MAXF ? m - t0 : MAXF;
            for (uint32_t t = 0; t < got; ++t) {
                size_t e = cur[ok[t]]++;
                l->i[e] = (uint32_t)a;
                l->wall[e] = ow[t];
                l->sub[e] = of[t];
                l->elem[e] = oe[t];
                l->gidx[g0 + t0 + t] = (uint32_t)e;
            }
        }
    }
    if (oom) {
        sd_free(hist);
        return SD_ERR_MEMORY;
    }
    SD_BINS_FOR(in)
    for (size_t e = 0; e < total; ++e) {
        uint32_t a = l->i[e];
        sd_wall_pair_key key;
        memset(&key, 0, sizeof key); /* its 4 bytes of padding too: checkpoints compare bit for bit */
        key.id = in->id[a];
        key.wall = l->wall[e];
        key.sub = l->sub[e];
        key.elem = l->elem[e];
        l->key[e] = key;
        l->tstart[e] = 0;
        l->tcount[e] = 0;
#define SD_X_ZERO(type, name, per, role, doc) \
    if ((role) == SD_PF_ZERO)                 \
        memset(&l->name[(size_t)(per) * e], 0, (size_t)(per) * sizeof *l->name);
        SD_WALL_PAIR_FIELDS(SD_X_ZERO)
#undef SD_X_ZERO
        sd_pair_key pk = sd_wall_key_as_pair(key);
        l->ds[e] = sd_history_find(hist, nhist, &pk);
        l->c[e] = in->x[a];
    }
    sd_free(hist);
    return in->mesh_count > 0 ? sd_bins_mesh_tris(b, in, l) : SD_OK;
}

sd_status sd_bins_build(sd_bins *b, const sd_bins_input *in, sd_pair_list *l, sd_wall_pair_list *wl)
{
    if (in->n_total == 0) {
        l->n = 0;
        memset(l->kind_start, 0, sizeof l->kind_start);
        wl->n = 0;
        memset(wl->kind_start, 0, sizeof wl->kind_start);
        return SD_OK;
    }
    sd_status st = sd_bins_prepare_build(b, in);
    if (st == SD_OK)
        st = sd_bins_pairs(b, in, l);
    if (st == SD_OK)
        st = sd_bins_wall_pairs(b, in, wl);
    b->sorted_n = 0;
    return st;
}
