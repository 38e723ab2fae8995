/* stencil.h — the per-particle kernel of the dense grid-stencil solver
 * (seed 001 §3.1–3.2): contact detection and contact forces from a fixed
 * stencil of cells around each particle's cell (the 5x5x5 filter of §3.2.1
 * for equal spheres), plus the walls. Single source (SD_HD): the CPU loop in
 * grid_step.c calls it once per particle; a CUDA kernel will call it once
 * per thread of one colour.
 *
 * Invariants:
 *  - each touching pair is evaluated exactly once per step, by its "owner":
 *    the particle whose forward half stencil holds the other (cells with a
 *    larger linear index within reach). The owner adds the force and torque
 *    to both particles. The caller must guarantee that no other thread
 *    touches either particle meanwhile (grid_step.c: blocks reach cells
 *    thick in z and y, run by colours), so there are no atomics and the
 *    sums come in a fixed order: the same bits for any thread count;
 *  - a pair is evaluated with the lower stable id as body i, and its
 *    tangential spring is kept as seen from that id, in one history slot of
 *    either particle (the lower id's when free), keyed by the partner's
 *    stable id and stamped with the step's epoch; slots not stamped in a
 *    step belong to contacts that ended and are freed after the pass;
 *  - the pair physics is the engine's own: sd_pair_spheres and
 *    sd_pair_wall (contact/pair.h), i.e. seed 001 eqs. 6–10 with the
 *    linear law, the same code the general solver runs.
 *
 * No allocation, no printing, fixed-size workspaces (DESIGN.md rule 1).
 */
#ifndef SD_GRID_STENCIL_H
#define SD_GRID_STENCIL_H

#include "contact/pair.h"
#include "dynamics/walls.h"

/* History slots per particle. Each touching pair keeps its spring in one
 * slot of either particle, so a particle needs slots for about half its
 * contacts plus its walls: 3-4 in a dense bed (coordination 6-7), never
 * more than 8 in the tests. A pair that finds no free slot in either
 * particle is still computed, without a stored spring, and counted as a
 * slot overflow (reported; zero in every test). */
#ifndef SD_GRID_SLOTS
#define SD_GRID_SLOTS 8
#endif

/* A cache hint for the CPU loops (no effect on results). */
#if defined(__GNUC__) && !defined(__CUDACC__)
#define SD_GRID_PREFETCH(p) __builtin_prefetch((const void *)(p))
#else
#define SD_GRID_PREFETCH(p) ((void)(p))
#endif

/* Largest stencil half width (radius ratio 2: ceil(2 * 2) = 4, 9x9x9). */
#define SD_GRID_MAX_REACH 4

/* Equal spheres (reach 2): the forward half of the 5x5x5 stencil has 62
 * cells, one bit each in a 64-bit mask; the owner's cell is cut into
 * SD_GRID_Q^3 sub-cells, each with the mask of the stencil cells a contact
 * can reach from it (grid.c, sd_grid_fast_tables). */
#define SD_GRID_HALF2 62
#define SD_GRID_Q 8

/* Slot tags: 0 = empty; a particle partner: 1 + its stable id (ids stay
 * below 2^30); a wall: SD_GRID_TAG_WALL | (wall << 3) | face (face 0..5 of
 * a box, 0 for a plane). SD_GRID_TAG_EPOCH holds the parity of the step
 * that last used the slot. */
#define SD_GRID_TAG_WALL 0x80000000u
#define SD_GRID_TAG_EPOCH 0x40000000u
#define SD_GRID_MAX_ID 0x3ffffffeu

enum { SD_GRID_WALL_PLANE = 0, SD_GRID_WALL_BOX = 1 };

/* A wall as the kernel sees it (a copy of the world's, plus the outlet). */
typedef struct sd_grid_wall {
    int kind;               /* SD_GRID_WALL_PLANE or SD_GRID_WALL_BOX */
    sd_vec3 point, normal;  /* plane */
    sd_vec3 lo, hi;         /* box */
    unsigned open_faces;    /* SD_BOX_* mask */
    int material;
    int holed;              /* box: the zmin face has the outlet hole below */
    sd_real hx0, hx1, hy0, hy1; /* m, the hole in the zmin face */
} sd_grid_wall;

/* The grid solver's own compact particle state (grid.h): the hot record of
 * one particle, and the table of particle kinds (distinct radius, mass,
 * inertia and material) it points into, so equal spheres share one entry. */
typedef struct sd_grid_part {
    sd_vec3 x, v, w;          /* m, m/s, rad/s */
    uint32_t id;              /* stable id (below 2^30) */
    uint32_t kind;            /* index into the kind table */
} sd_grid_part;

typedef struct sd_grid_kind {
    sd_real radius, inv_mass; /* m, 1/kg (0: a fixed body) */
    sd_vec3 inv_inertia;      /* 1/(kg m^2), principal (isotropic for a sphere) */
    int32_t material;
    int32_t unused;
} sd_grid_kind;

/* Read-only view of everything the kernel needs. */
typedef struct sd_grid_view {
    const sd_grid_part *part;
    const sd_grid_kind *kinds;
    const int32_t *cell;      /* per cell: storage index of its particle, or -1 */
    const uint32_t *where;    /* per particle: the cell its centre lies in */
    long nx, ny;              /* cells along x and y (cell = (z ny + y) nx + x) */
    int reach;                /* stencil half width in cells */
    sd_vec3 lo;               /* m, corner of cell (0, 0, 0) */
    sd_real h;                /* m, cell edge */
    sd_real rmax;             /* m, largest radius */
    const sd_pair_params *mix;
    int nm;                   /* materials */
    const sd_grid_wall *walls;
    int nwalls;
    sd_real dt;
    /* equal-sphere path (reach 2; NULL occ: the generic scan): one bit per
     * cell, set when it holds a particle; the offsets of the half stencil's
     * cells; the reachable cells per sub-cell of the owner */
    const uint64_t *occ;
    const long *stoff;
    const uint64_t *qmask;
    sd_real inv_h;            /* 1/m, 1 / h (the sub-cell of the owner: a margin covers its rounding) */
    sd_real runi;             /* m, the radius when every kind has the same (else 0) */
    int kind1;                /* a single kind: every particle's is kinds[0] */
} sd_grid_view;

/* What the kernel writes: forces and torques of both particles of a pair,
 * the slots of both, and the totals on the walls of the caller's slab. */
typedef struct sd_grid_acc {
    sd_vec3 *ft;              /* N, N m: force 2k and torque 2k + 1 of particle k, zeroed before the pass */
    uint32_t *tag;            /* SD_GRID_SLOTS per particle */
    sd_vec3 *ds;              /* m, the springs of those slots */
    sd_vec3 *wall_f, *wall_t; /* N, N m: on each wall (nwalls), summed by this caller */
    uint32_t epoch;           /* 0 or SD_GRID_TAG_EPOCH: this step's stamp */
    long overflows;           /* contacts that found no free slot */
} sd_grid_acc;

SD_HD static SD_INLINE sd_body sd_grid_body(const sd_grid_view *g, size_t k)
{
    const sd_grid_part *p = &g->part[k];
    const sd_grid_kind *kd = g->kind1 ? g->kinds : &g->kinds[p->kind];
    sd_body b;
    b.x = p->x;
    b.v = p->v;
    b.w = p->w;
    b.radius = kd->radius;
    b.inv_mass = kd->inv_mass;
    b.inv_inertia = sd_v3_zero(); /* spheres: central contacts */
    b.q = sd_quat_identity();
    return b;
}

SD_HD static SD_INLINE sd_real sd_grid_radius(const sd_grid_view *g, size_t k)
{
    return g->kinds[g->part[k].kind].radius;
}

/* Index of the lowest set bit of m (m != 0). */
SD_HD static SD_INLINE int sd_grid_ctz64(uint64_t m)
{
#if defined(__CUDA_ARCH__)
    return __ffsll((long long)m) - 1;
#elif defined(__GNUC__)
    return __builtin_ctzll(m);
#else
    int e = 0;
    while (!(m & 1u)) {
        m >>= 1;
        ++e;
    }
    return e;
#endif
}

/* The slots of particle k holding key (epoch ignored), and the free ones,
 * as bit masks: all slots compared at once (SSE2 on the CPU when there are
 * 8), which spares a mispredicted exit per search. */
#if defined(__SSE2__) && !defined(__CUDACC__) && SD_GRID_SLOTS == 8
#define SD_GRID_SLOTS_SSE2 1
#include <emmintrin.h>
#endif

SD_HD static SD_INLINE unsigned sd_grid_slot_mask(const uint32_t *tag, uint32_t key, uint32_t ignore)
{
#ifdef SD_GRID_SLOTS_SSE2
    __m128i kv = _mm_set1_epi32((int)key), mv = _mm_set1_epi32((int)~ignore);
    __m128i t0 = _mm_loadu_si128((const __m128i *)(const void *)tag);
    __m128i t1 = _mm_loadu_si128((const __m128i *)(const void *)(tag + 4));
    __m128i c0 = _mm_cmpeq_epi32(_mm_and_si128(t0, mv), kv), c1 = _mm_cmpeq_epi32(_mm_and_si128(t1, mv), kv);
    return (unsigned)_mm_movemask_ps(_mm_castsi128_ps(c0)) | ((unsigned)_mm_movemask_ps(_mm_castsi128_ps(c1)) << 4);
#else
    unsigned m = 0;
    for (int s = 0; s < SD_GRID_SLOTS; ++s)
        m |= (unsigned)((tag[s] & ~ignore) == key) << s;
    return m;
#endif
}

/* Slot of particle k holding key (epoch ignored), or -1 (the first match,
 * as a scan would find). */
SD_HD static SD_INLINE int sd_grid_slot_find(const uint32_t *tag, uint32_t key)
{
    unsigned m = sd_grid_slot_mask(tag, key, SD_GRID_TAG_EPOCH);
    return m ? sd_grid_ctz64(m) : -1;
}

/* First free slot, or -1. */
SD_HD static SD_INLINE int sd_grid_slot_free(const uint32_t *tag)
{
    unsigned m = sd_grid_slot_mask(tag, 0u, 0u);
    return m ? sd_grid_ctz64(m) : -1;
}

/* The spring of pair (a, b) as seen from the lower stable id, wherever it
 * is kept (zero when the contact is new). Read-only: statistics use it. */
SD_HD static SD_INLINE sd_vec3 sd_grid_pair_spring(const uint32_t *tag, const sd_vec3 *ds, size_t a, size_t b,
                                                   const sd_grid_part *part)
{
    int s = sd_grid_slot_find(tag + a * SD_GRID_SLOTS, part[b].id + 1u);
    if (s >= 0)
        return ds[a * SD_GRID_SLOTS + (size_t)s];
    s = sd_grid_slot_find(tag + b * SD_GRID_SLOTS, part[a].id + 1u);
    if (s >= 0)
        return ds[b * SD_GRID_SLOTS + (size_t)s];
    return sd_v3_zero();
}

/* Floor of a box whose zmin face has a rectangular hole (the outlet,
 * seed 001 §4.2). Outside the hole it is the face itself
 * (sd_sphere_box_face); above the hole the nearest floor point is on the
 * hole's rim, on the nearest rim edge that is not a box side. */
SD_HD static SD_INLINE int sd_grid_holed_floor(sd_vec3 x, sd_real r, const sd_grid_wall *wl, sd_contact_geom *g)
{
    int in_hole = x.x > wl->hx0 && x.x < wl->hx1 && x.y > wl->hy0 && x.y < wl->hy1;
    if (!in_hole)
        return sd_sphere_box_face(x, r, 2, wl->lo.z, SD_R(1.0), wl->lo, wl->hi, g);
    /* distances to the rim edges that carry floor (an edge on a box side
     * leaves nothing to touch) */
    sd_real best = r; /* only rim edges closer than one radius can touch */
    sd_vec3 q = x;
    if (wl->hx0 > wl->lo.x && x.x - wl->hx0 < best) {
        best = x.x - wl->hx0;
        q = sd_v3(wl->hx0, x.y, wl->lo.z);
    }
    if (wl->hx1 < wl->hi.x && wl->hx1 - x.x < best) {
        best = wl->hx1 - x.x;
        q = sd_v3(wl->hx1, x.y, wl->lo.z);
    }
    if (wl->hy0 > wl->lo.y && x.y - wl->hy0 < best) {
        best = x.y - wl->hy0;
        q = sd_v3(x.x, wl->hy0, wl->lo.z);
    }
    if (wl->hy1 < wl->hi.y && wl->hy1 - x.y < best) {
        best = wl->hy1 - x.y;
        q = sd_v3(x.x, wl->hy1, wl->lo.z);
    }
    if (!(best < r))
        return 0;
    sd_vec3 d = sd_v3_sub(x, q);
    sd_real dist2 = sd_v3_norm2(d);
    if (dist2 >= r * r || dist2 <= SD_R(0.0))
        return 0;
    sd_real dist = sd_sqrt(dist2);
    g->n = sd_v3_scale(d, SD_R(1.0) / dist);
    g->delta = r - dist;
    g->point = sd_v3_madd(x, -(r - SD_R(0.5) * g->delta), g->n);
    return 1;
}

/* No history slot for a pair (all taken in both particles). */
#define SD_GRID_NO_SLOT ((size_t)-1)

/* The history slot of touching pair (k, j), kept by either particle (found
 * by the partner's stable id), or a new one — in body i (the lower stable
 * id) when it has room, else in body j, its spring zeroed — stamped with
 * this step's epoch; SD_GRID_NO_SLOT when both are full. */
SD_HD static SD_INLINE size_t sd_grid_pair_slot(const sd_grid_view *g, sd_grid_acc *a, size_t k, size_t j)
{
    uint32_t idk = g->part[k].id, idj = g->part[j].id;
    size_t i = idk < idj ? k : j, jj = i == k ? j : k;
    uint32_t key_i = g->part[jj].id + 1u, key_j = g->part[i].id + 1u;
    uint32_t *ti = a->tag + i * SD_GRID_SLOTS, *tj = a->tag + jj * SD_GRID_SLOTS;
    int s = sd_grid_slot_find(ti, key_i);
    if (s >= 0) {
        ti[s] = key_i | a->epoch;
        return i * SD_GRID_SLOTS + (size_t)s;
    }
    if ((s = sd_grid_slot_find(tj, key_j)) >= 0) {
        tj[s] = key_j | a->epoch;
        return jj * SD_GRID_SLOTS + (size_t)s;
    }
    size_t slot;
    if ((s = sd_grid_slot_free(ti)) >= 0) {
        ti[s] = key_i | a->epoch;
        slot = i * SD_GRID_SLOTS + (size_t)s;
    } else if ((s = sd_grid_slot_free(tj)) >= 0) {
        tj[s] = key_j | a->epoch;
        slot = jj * SD_GRID_SLOTS + (size_t)s;
    } else {
        return SD_GRID_NO_SLOT;
    }
    a->ds[slot] = sd_v3_zero();
    return slot;
}

/* One touching particle pair (k, j) with its slot (sd_grid_pair_slot),
 * evaluated once: the force and torques go to both particles (k's to
 * fk, tk, which the caller keeps for it: the same sums in the same order
 * as in a->ft, without a store and a load per pair), the spring back to
 * the slot. */
SD_HD static SD_HOT void sd_grid_pair_eval(const sd_grid_view *g, sd_grid_acc *a, size_t k, size_t j, size_t slot,
                                           sd_vec3 *fk, sd_vec3 *tk)
{
    /* canonical orientation: body i is the lower stable id */
    uint32_t idk = g->part[k].id, idj = g->part[j].id;
    int k_is_i = idk < idj;
    size_t i = k_is_i ? k : j, jj = k_is_i ? j : k;
    sd_body bi = sd_grid_body(g, i), bj = sd_grid_body(g, jj);
    const sd_pair_params *prm =
        g->kind1 ? &g->mix[(size_t)g->kinds[0].material * (size_t)g->nm + (size_t)g->kinds[0].material]
                 : &g->mix[(size_t)g->kinds[g->part[i].kind].material * (size_t)g->nm +
                           (size_t)g->kinds[g->part[jj].kind].material];
    int kept = slot != SD_GRID_NO_SLOT;
    sd_vec3 ds = kept ? a->ds[slot] : sd_v3_zero();
    sd_pair_result r = sd_pair_spheres(prm, &bi, &bj, &ds, g->dt);
    if (kept)
        a->ds[slot] = ds;
    else
        a->overflows++;
    /* body i gets +f and ti, body j gets -f (x - f is x + (-f), bit for
     * bit) and tj */
    sd_vec3 *ftp = a->ft + 2 * j;
    if (k_is_i) {
        *fk = sd_v3_add(*fk, r.f);
        *tk = sd_v3_add(*tk, r.ti);
        ftp[0] = sd_v3_sub(ftp[0], r.f);
        ftp[1] = sd_v3_add(ftp[1], r.tj);
    } else {
        ftp[0] = sd_v3_add(ftp[0], r.f);
        ftp[1] = sd_v3_add(ftp[1], r.ti);
        *fk = sd_v3_sub(*fk, r.f);
        *tk = sd_v3_add(*tk, r.tj);
    }
}

/* One touching particle pair (k, j), evaluated once: its slot, then the
 * contact. */
SD_HD static SD_HOT void sd_grid_pair_touching(const sd_grid_view *g, sd_grid_acc *a, size_t k, size_t j)
{
    size_t slot = sd_grid_pair_slot(g, a, k, j);
    sd_vec3 fk = a->ft[2 * k], tk = a->ft[2 * k + 1];
    sd_grid_pair_eval(g, a, k, j, slot, &fk, &tk);
    a->ft[2 * k] = fk;
    a->ft[2 * k + 1] = tk;
}

/* Any pair (k, j): evaluated when touching; a pair that is not touching
 * leaves its slot, if any, unstamped, so it is freed after the pass. */
SD_HD static SD_INLINE void sd_grid_add_pair(const sd_grid_view *g, sd_grid_acc *a, size_t k, size_t j)
{
    sd_vec3 d = sd_v3_sub(g->part[k].x, g->part[j].x);
    sd_real rs = sd_grid_radius(g, k) + sd_grid_radius(g, j);
    if (sd_v3_norm2(d) < rs * rs)
        sd_grid_pair_touching(g, a, k, j);
}

/* One wall feature of particle k (same geometry calls as the general
 * solver's wall loop, so both solvers see the same wall). */
SD_HD static SD_INLINE void sd_grid_add_wall(const sd_grid_view *g, sd_grid_acc *a, size_t k, int wi, int face,
                                             const sd_contact_geom *geo)
{
    sd_body b = sd_grid_body(g, k);
    const sd_pair_params *prm =
        &g->mix[(size_t)g->kinds[g->part[k].kind].material * (size_t)g->nm + (size_t)g->walls[wi].material];
    uint32_t key = SD_GRID_TAG_WALL | ((uint32_t)wi << 3) | (uint32_t)face;
    uint32_t *tk = a->tag + k * SD_GRID_SLOTS;
    int s = sd_grid_slot_find(tk, key);
    if (s < 0 && (s = sd_grid_slot_free(tk)) >= 0)
        a->ds[k * SD_GRID_SLOTS + (size_t)s] = sd_v3_zero();
    sd_vec3 ds = s >= 0 ? a->ds[k * SD_GRID_SLOTS + (size_t)s] : sd_v3_zero();
    sd_pair_result r = sd_pair_wall(prm, &b, geo, 1, b.radius, &ds, g->dt);
    if (s >= 0) {
        a->ds[k * SD_GRID_SLOTS + (size_t)s] = ds;
        tk[s] = key | a->epoch;
    } else {
        a->overflows++;
    }
    a->ft[2 * k] = sd_v3_add(a->ft[2 * k], r.f);
    a->ft[2 * k + 1] = sd_v3_add(a->ft[2 * k + 1], r.ti);
    /* the wall feels the opposite force at the contact point (as the general
     * solver's sd_cpu_wall_totals; rolling torques left out) */
    sd_vec3 fw = sd_v3_neg(r.f);
    a->wall_f[wi] = sd_v3_add(a->wall_f[wi], fw);
    a->wall_t[wi] = sd_v3_add(a->wall_t[wi], sd_v3_cross(sd_v3_sub(geo->point, g->walls[wi].point), fw));
}

/* The walls of particle k: the halo's mirror particle of k across a wall
 * plane is at distance 2 s; its contact is evaluated as the sphere-plane
 * contact (overlap R - s), i.e. the wall itself (docs/grid-solver.md). */
SD_HD static SD_INLINE void sd_grid_walls_of(const sd_grid_view *g, sd_grid_acc *a, size_t k)
{
    sd_vec3 x = g->part[k].x;
    sd_real r = sd_grid_radius(g, k);
    for (int wi = 0; wi < g->nwalls; ++wi) {
        const sd_grid_wall *wl = &g->walls[wi];
        sd_contact_geom geo;
        if (wl->kind == SD_GRID_WALL_PLANE) {
            if (sd_sphere_plane(x, r, wl->point, wl->normal, &geo))
                sd_grid_add_wall(g, a, k, wi, 0, &geo);
            continue;
        }
        /* most particles are a radius or more inside every face: then the
         * face loop below skips all six (s >= r), so skip it at once */
        if (x.x - wl->lo.x >= r && wl->hi.x - x.x >= r && x.y - wl->lo.y >= r && wl->hi.y - x.y >= r &&
            x.z - wl->lo.z >= r && wl->hi.z - x.z >= r)
            continue;
        /* the box's faces as the walls module enumerates them (dynamics/walls.h) */
        for (int face = 0; face < SD_WALL_BOX_FACES; ++face) {
            if (!sd_wall_box_face_closed(wl->open_faces, face))
                continue;
            sd_real s = sd_wall_box_face_gap(wl->lo, wl->hi, face, x);
            if (!(s < r && s > -r))
                continue;
            int touching;
            if (face == 4 && wl->holed) {
                touching = sd_grid_holed_floor(x, r, wl, &geo);
            } else {
                sd_wall_face fd = sd_wall_box_face_of(wl->lo, wl->hi, face);
                touching = sd_sphere_box_face(x, r, fd.axis, fd.value, fd.dir, wl->lo, wl->hi, &geo);
            }
            if (touching)
                sd_grid_add_wall(g, a, k, wi, face, &geo);
        }
    }
}

/* Bits [b, b + 5) of the occupancy bitmap (the words after b's exist: the
 * bitmap has two words of padding). */
SD_HD static SD_INLINE uint64_t sd_grid_occ5(const uint64_t *occ, long b)
{
    size_t i = (size_t)b >> 6;
    unsigned s = (unsigned)b & 63u;
    return ((occ[i] >> s) | ((occ[i + 1] << 1) << (63u - s))) & 0x1fu;
}

/* The candidates of owner k in cell c = (ix, iy, iz) for equal spheres
 * (reach 2), into cand in stencil order (z, then y, then x: the order of
 * the generic scan, so the contacts are summed in the same order): the
 * occupied cells of the half stencil, from the bitmap (13 reads of 5 bits
 * instead of 62 cell reads), masked by the cells reachable from k's
 * sub-cell (a cell whose nearest point is 2 R or more away holds no
 * partner), then only those closer than the sum of the radii. */
SD_HD static SD_INLINE int sd_grid_touching2(const sd_grid_view *g, size_t k, long ix, long iy, long iz, long c,
                                            int32_t *cand)
{
    const uint64_t *occ = g->occ;
    const long *off = g->stoff;
    /* row (dz = 0, dy = 0): dx = 1, 2 -> bits 0, 1; the 12 full rows after
     * it, 5 bits each from bit 2 */
    uint64_t m = sd_grid_occ5(occ, c + 1) & 0x3u;
    for (int r = 0; r < 12; ++r)
        m |= sd_grid_occ5(occ, c + off[2 + 5 * r]) << (2 + 5 * r);
    /* the owner's sub-cell (a product by 1/h may put the fraction an ulp
     * outside [0, 1) or in the next sub-cell: the clamp and the tables'
     * margin of 1e-6 cell cover that) */
    sd_vec3 xk = g->part[k].x;
    double fx = (double)((xk.x - g->lo.x) * g->inv_h) - (double)ix,
           fy = (double)((xk.y - g->lo.y) * g->inv_h) - (double)iy,
           fz = (double)((xk.z - g->lo.z) * g->inv_h) - (double)iz;
    int qx = (int)(fx * SD_GRID_Q), qy = (int)(fy * SD_GRID_Q), qz = (int)(fz * SD_GRID_Q);
    qx = qx < 0 ? 0 : qx > SD_GRID_Q - 1 ? SD_GRID_Q - 1 : qx;
    qy = qy < 0 ? 0 : qy > SD_GRID_Q - 1 ? SD_GRID_Q - 1 : qy;
    qz = qz < 0 ? 0 : qz > SD_GRID_Q - 1 ? SD_GRID_Q - 1 : qz;
    m &= g->qmask[(qz * SD_GRID_Q + qy) * SD_GRID_Q + qx];
    sd_real rk = sd_grid_radius(g, k);
    int nt = 0;
    if (g->runi > SD_R(0.0)) {
        /* one radius: the same sum rk + rk for every partner */
        sd_real rs = rk + rk, rs2 = rs * rs;
        while (m) {
            int e = sd_grid_ctz64(m);
            m &= m - 1u;
            int32_t j = g->cell[c + off[e]];
            sd_vec3 d = sd_v3_sub(xk, g->part[j].x);
            cand[nt] = j;
            nt += sd_v3_norm2(d) < rs2;
        }
    } else {
        while (m) {
            int e = sd_grid_ctz64(m);
            m &= m - 1u;
            int32_t j = g->cell[c + off[e]];
            sd_vec3 d = sd_v3_sub(xk, g->part[j].x);
            sd_real rs = rk + sd_grid_radius(g, (size_t)j);
            cand[nt] = j;
            nt += sd_v3_norm2(d) < rs * rs;
        }
    }
    return nt;
}

/* The kernel: particle k, in its cell (ix, iy, iz), as owner. Visits the
 * forward half of its (2 reach + 1)^3 stencil (seed 001 §3.2.1): dz > 0, or
 * dz = 0 and dy > 0, or dz = dy = 0 and dx > 0 — every pair of occupied
 * cells within reach once — then its walls. Cells z, then y, then x: a
 * fixed order (equal spheres: sd_grid_touching2, the same order). The
 * caller passes the cell's coordinates (it walks the cells), which spares
 * integer divisions per particle. */
SD_HD static SD_INLINE void sd_grid_owner_forces(const sd_grid_view *g, sd_grid_acc *a, size_t k, long ix, long iy,
                                                 long iz)
{
    long nxy = g->nx * g->ny;
    long c = (iz * g->ny + iy) * g->nx + ix;
    int rch = g->reach;
    sd_real rk = sd_grid_radius(g, k);
    int32_t cand[(SD_GRID_MAX_REACH + 1) * (2 * SD_GRID_MAX_REACH + 1) * (2 * SD_GRID_MAX_REACH + 1)];
    int nt;
    if (rch == 2 && g->occ) {
        nt = sd_grid_touching2(g, k, ix, iy, iz, c, cand);
    } else {
        /* radius ratios above 1 (reach 3 or 4), or no bitmap: candidates
         * first (a branch-free gather of the occupied cells of the half
         * stencil), then the distance tests, then the contacts: the
         * branches stay predictable */
        int nc = 0;
        for (int dz = 0; dz <= rch; ++dz) {
            for (int dy = dz ? -rch : 0; dy <= rch; ++dy) {
                int x0 = (dz || dy) ? -rch : 1, x1 = rch;
                const int32_t *row = g->cell + c + (long)dz * nxy + (long)dy * g->nx;
                for (int dx = x0; dx <= x1; ++dx) {
                    int32_t j = row[dx];
                    cand[nc] = j;
                    nc += j >= 0;
                }
            }
        }
        sd_vec3 xk = g->part[k].x;
        nt = 0;
        for (int e = 0; e < nc; ++e) {
            size_t j = (size_t)cand[e];
            sd_vec3 d = sd_v3_sub(xk, g->part[j].x);
            sd_real rs = rk + sd_grid_radius(g, j);
            cand[nt] = (int32_t)j;
            nt += sd_v3_norm2(d) < rs * rs;
        }
    }
    /* the touching partners' slots are read next: ask for them now (a
     * hint only; nothing under nvcc) */
    for (int e = 0; e < nt; ++e) {
        SD_GRID_PREFETCH(a->tag + (size_t)cand[e] * SD_GRID_SLOTS);
        SD_GRID_PREFETCH(a->ds + (size_t)cand[e] * SD_GRID_SLOTS);
        SD_GRID_PREFETCH(a->ds + (size_t)cand[e] * SD_GRID_SLOTS + 3);
        SD_GRID_PREFETCH(a->ds + (size_t)cand[e] * SD_GRID_SLOTS + 6);
        SD_GRID_PREFETCH(a->ft + 2 * (size_t)cand[e]);
        SD_GRID_PREFETCH(a->ft + 2 * (size_t)cand[e] + 1);
    }
    /* the slots of all touching pairs first (in pair order, so new slots
     * are taken as one pair at a time would), then the contacts: the
     * slots' dependent loads do not hold up the contacts' arithmetic */
    size_t slot[(SD_GRID_MAX_REACH + 1) * (2 * SD_GRID_MAX_REACH + 1) * (2 * SD_GRID_MAX_REACH + 1)];
    for (int e = 0; e < nt; ++e)
        slot[e] = sd_grid_pair_slot(g, a, k, (size_t)cand[e]);

    sd_vec3 fk = a->ft[2 * k], tk = a->ft[2 * k + 1];
    for (int e = 0; e < nt; ++e)
        sd_grid_pair_eval(g, a, k, (size_t)cand[e], slot[e], &fk, &tk);
    a->ft[2 * k] = fk;
    a->ft[2 * k + 1] = tk;
    sd_grid_walls_of(g, a, k);
}

/* A particle without a cell (it lost a cell conflict): its pairs with the
 * particles of its whole stencil, then its walls. The caller runs these
 * serially, after the slabs, and adds the pairs between two such particles
 * itself. */
SD_HD static SD_INLINE void sd_grid_homeless_forces(const sd_grid_view *g, sd_grid_acc *a, size_t k)
{
    long c = (long)g->where[k];
    long nxy = g->nx * g->ny;
    int rch = g->reach;
    for (int dz = -rch; dz <= rch; ++dz)
        for (int dy = -rch; dy <= rch; ++dy) {
            const int32_t *row = g->cell + c + (long)dz * nxy + (long)dy * g->nx;
            for (int dx = -rch; dx <= rch; ++dx) {
                int32_t j = row[dx];
                if (j >= 0 && (size_t)j != k)
                    sd_grid_add_pair(g, a, k, (size_t)j);
            }
        }
    sd_grid_walls_of(g, a, k);
}

#endif
