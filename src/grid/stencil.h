/* stencil.h — the per-particle kernel of the dense grid-stencil solver
 * (seed 001 §3.1–3.2): contact detection and contact forces of one particle
 * from a fixed stencil of (2 reach + 1)^3 cells around its own cell (5x5x5
 * for equal spheres), plus its walls. Single source (SD_HD): the CPU loop in
 * grid_step.c calls it once per particle; a CUDA kernel will call it once per
 * thread.
 *
 * Invariants:
 *  - every particle evaluates each of its contacts itself (the seed's
 *    "output is the force on the central cell"), so no two threads ever write
 *    the same memory and nothing is summed with atomics; a pair is always
 *    evaluated with the lower stable id as body i, so both particles of a
 *    pair compute the same bits and keep identical copies of the pair's
 *    tangential spring;
 *  - the pair physics is the engine's own: sd_pair_spheres and
 *    sd_pair_wall (contact/pair.h), i.e. seed 001 eqs. 6–10 with the
 *    linear law, the same code the general solver runs;
 *  - contacts are summed in a fixed order: stencil cells (z, then y, then x),
 *    then the overflow list, then walls in world order (box faces 0..5).
 *
 * No allocation, no printing, fixed-size workspaces (DESIGN.md rule 1).
 */
#ifndef SD_GRID_STENCIL_H
#define SD_GRID_STENCIL_H

#include "contact/pair.h"

/* History slots per particle: touching neighbours plus touching walls. Equal
 * spheres at small overlap touch at most 12 others (the kissing number);
 * more contacts than slots are still computed, but without a stored spring
 * (counted and reported as slot overflows). */
#ifndef SD_GRID_SLOTS
#define SD_GRID_SLOTS 12
#endif

/* Largest stencil half width (radius ratio 2: ceil(2 * 2) = 4, 9x9x9). */
#define SD_GRID_MAX_REACH 4

/* Slot tags: 0 = empty, 1 + stable id for a particle, SD_GRID_TAG_WALL |
 * (wall << 3) | face for a wall (face 0..5 of a box, 0 for a plane). */
#define SD_GRID_TAG_WALL 0x80000000u

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

/* Read-only view of everything the kernel needs. */
typedef struct sd_grid_view {
    const sd_vec3 *x, *v, *w;
    const sd_real *radius, *inv_mass;
    const int32_t *material;
    const uint64_t *id;
    const int32_t *cell;      /* per cell: storage index of its particle, or -1 */
    const uint32_t *where;    /* per particle: the cell its centre lies in */
    const uint32_t *over;     /* particles that lost a cell conflict */
    size_t nover;
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
} sd_grid_view;

typedef struct sd_grid_out {
    sd_vec3 f, t;             /* N, N m: total contact force and torque */
    int overflows;            /* contacts that found no free history slot */
} sd_grid_out;

SD_HD static SD_INLINE sd_body sd_grid_body(const sd_grid_view *g, size_t k)
{
    sd_body b;
    b.x = g->x[k];
    b.v = g->v[k];
    b.w = g->w[k];
    b.radius = g->radius[k];
    b.inv_mass = g->inv_mass[k];
    b.inv_inertia = sd_v3_zero(); /* spheres: central contacts */
    b.q = sd_quat_identity();
    return b;
}

/* Finds the spring stored under tag in the old slots (zero when new). */
SD_HD static SD_INLINE sd_vec3 sd_grid_find_spring(const uint32_t *tag, const sd_vec3 *ds, uint32_t want)
{
    for (int s = 0; s < SD_GRID_SLOTS; ++s)
        if (tag[s] == want)
            return ds[s];
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

/* One contact of particle k: evaluates it when touching, keeps its spring in
 * the new slots, adds its force and torque to *o. */
SD_HD static SD_INLINE void sd_grid_add_pair(const sd_grid_view *g, size_t k, size_t j, const uint32_t *old_tag,
                                             const sd_vec3 *old_ds, uint32_t *new_tag, sd_vec3 *new_ds, int *m,
                                             sd_grid_out *o)
{
    sd_vec3 d = sd_v3_sub(g->x[k], g->x[j]);
    sd_real rs = g->radius[k] + g->radius[j];
    if (sd_v3_norm2(d) >= rs * rs)
        return; /* not touching: a contact that ends forgets its spring */
    /* canonical orientation: body i is the lower stable id */
    int k_is_i = g->id[k] < g->id[j];
    size_t i = k_is_i ? k : j, jj = k_is_i ? j : k;
    sd_body a = sd_grid_body(g, i), b = sd_grid_body(g, jj);
    const sd_pair_params *prm = &g->mix[(size_t)g->material[i] * (size_t)g->nm + (size_t)g->material[jj]];
    uint32_t tag = (uint32_t)(g->id[j] + 1u);
    sd_vec3 ds = sd_grid_find_spring(old_tag, old_ds, tag);
    sd_pair_result r = sd_pair_spheres(prm, &a, &b, &ds, g->dt);
    if (*m < SD_GRID_SLOTS) {
        new_tag[*m] = tag;
        new_ds[*m] = ds;
        ++*m;
    } else {
        o->overflows++;
    }
    if (k_is_i) {
        o->f = sd_v3_add(o->f, r.f);
        o->t = sd_v3_add(o->t, r.ti);
    } else {
        o->f = sd_v3_sub(o->f, r.f);
        o->t = sd_v3_add(o->t, r.tj);
    }
}

/* One wall feature of particle k (same geometry calls as the general
 * solver's wall loop, so both solvers see the same wall). */
SD_HD static SD_INLINE void sd_grid_add_wall(const sd_grid_view *g, size_t k, int wi, int face, int touching,
                                             const sd_contact_geom *geo, const uint32_t *old_tag,
                                             const sd_vec3 *old_ds, uint32_t *new_tag, sd_vec3 *new_ds, int *m,
                                             sd_grid_out *o)
{
    if (!touching)
        return;
    sd_body a = sd_grid_body(g, k);
    const sd_pair_params *prm = &g->mix[(size_t)g->material[k] * (size_t)g->nm + (size_t)g->walls[wi].material];
    uint32_t tag = SD_GRID_TAG_WALL | ((uint32_t)wi << 3) | (uint32_t)face;
    sd_vec3 ds = sd_grid_find_spring(old_tag, old_ds, tag);
    sd_pair_result r = sd_pair_wall(prm, &a, geo, touching, a.radius, &ds, g->dt);
    if (*m < SD_GRID_SLOTS) {
        new_tag[*m] = tag;
        new_ds[*m] = ds;
        ++*m;
    } else {
        o->overflows++;
    }
    o->f = sd_v3_add(o->f, r.f);
    o->t = sd_v3_add(o->t, r.ti);
}

/* The kernel: force and torque on particle k, and its updated springs
 * (tag, ds: its SD_GRID_SLOTS slots, read and rewritten in place). */
SD_HD static SD_INLINE sd_grid_out sd_grid_particle_forces(const sd_grid_view *g, size_t k, uint32_t *tag, sd_vec3 *ds)
{
    sd_grid_out o;
    o.f = sd_v3_zero();
    o.t = sd_v3_zero();
    o.overflows = 0;
    uint32_t new_tag[SD_GRID_SLOTS];
    sd_vec3 new_ds[SD_GRID_SLOTS];
    int m = 0;

    /* the stencil: (2 reach + 1)^3 cells around k's cell (seed 001 §3.2.1).
     * A cell farther from k's centre than r_k + R_max cannot hold a partner:
     * gap[axis][o] is the distance along the axis from the centre to the
     * slab of cells at offset o, so such cells (and whole rows) are skipped
     * before their memory is read. The visiting order stays fixed. */
    long c = (long)g->where[k];
    long nxy = g->nx * g->ny;
    int rch = g->reach;
    sd_real gap2[3][2 * SD_GRID_MAX_REACH + 1];
    {
        long iz = c / nxy, iy = (c / g->nx) % g->ny, ix = c % g->nx;
        sd_real f[3];
        f[0] = (g->x[k].x - g->lo.x) / g->h - (sd_real)ix;
        f[1] = (g->x[k].y - g->lo.y) / g->h - (sd_real)iy;
        f[2] = (g->x[k].z - g->lo.z) / g->h - (sd_real)iz;
        for (int a = 0; a < 3; ++a)
            for (int off = -rch; off <= rch; ++off) {
                sd_real gp = off > 0 ? ((sd_real)off - f[a]) : (off < 0 ? ((sd_real)(-off - 1) + f[a]) : SD_R(0.0));
                gp = gp > SD_R(0.0) ? gp * g->h : SD_R(0.0);
                gap2[a][off + rch] = gp * gp;
            }
    }
    sd_real cut2 = sd_sq(g->radius[k] + g->rmax);
    /* candidates first (a branch-free gather of the occupied cells), then
     * the contacts: the scan's branches stay predictable */
    int32_t cand[(2 * SD_GRID_MAX_REACH + 1) * (2 * SD_GRID_MAX_REACH + 1) * (2 * SD_GRID_MAX_REACH + 1)];
    int nc = 0;
    for (int dz = -rch; dz <= rch; ++dz) {
        sd_real gz = gap2[2][dz + rch];
        if (gz >= cut2)
            continue;
        for (int dy = -rch; dy <= rch; ++dy) {
            sd_real gyz = gz + gap2[1][dy + rch];
            if (gyz >= cut2)
                continue;
            /* the cells of the row within reach form one run of offsets */
            int x0 = -rch, x1 = rch;
            while (gyz + gap2[0][x0 + rch] >= cut2)
                ++x0;
            while (gyz + gap2[0][x1 + rch] >= cut2)
                --x1;
            const int32_t *row = g->cell + c + (long)dz * nxy + (long)dy * g->nx;
            for (int dx = x0; dx <= x1; ++dx) {
                int32_t j = row[dx];
                cand[nc] = j;
                nc += (j >= 0) & ((size_t)j != k);
            }
        }
    }
    for (int e = 0; e < nc; ++e)
        sd_grid_add_pair(g, k, (size_t)cand[e], tag, ds, new_tag, new_ds, &m, &o);
    /* particles that lost a cell conflict live outside the cells */
    for (size_t e = 0; e < g->nover; ++e) {
        size_t j = g->over[e];
        if (j != k)
            sd_grid_add_pair(g, k, j, tag, ds, new_tag, new_ds, &m, &o);
    }

    /* walls: the halo's mirror particle of k across a wall plane is at
     * distance 2 s; its contact is evaluated as the sphere-plane contact
     * (overlap R - s), i.e. the wall itself (docs/grid-solver.md) */
    sd_vec3 x = g->x[k];
    sd_real r = g->radius[k];
    for (int wi = 0; wi < g->nwalls; ++wi) {
        const sd_grid_wall *wl = &g->walls[wi];
        sd_contact_geom geo;
        if (wl->kind == SD_GRID_WALL_PLANE) {
            int touching = sd_sphere_plane(x, r, wl->point, wl->normal, &geo);
            sd_grid_add_wall(g, k, wi, 0, touching, &geo, tag, ds, new_tag, new_ds, &m, &o);
            continue;
        }
        const sd_real cx[3] = {x.x, x.y, x.z};
        const sd_real lo[3] = {wl->lo.x, wl->lo.y, wl->lo.z};
        const sd_real hi[3] = {wl->hi.x, wl->hi.y, wl->hi.z};
        for (int face = 0; face < 6; ++face) {
            if (wl->open_faces & (1u << face))
                continue;
            int axis = face / 2;
            sd_real s = (face & 1) ? hi[axis] - cx[axis] : cx[axis] - lo[axis];
            if (!(s < r && s > -r))
                continue;
            int touching;
            if (face == 4 && wl->holed)
                touching = sd_grid_holed_floor(x, r, wl, &geo);
            else
                touching = sd_sphere_box_face(x, r, axis, (face & 1) ? hi[axis] : lo[axis],
                                              (face & 1) ? SD_R(-1.0) : SD_R(1.0), wl->lo, wl->hi, &geo);
            sd_grid_add_wall(g, k, wi, face, touching, &geo, tag, ds, new_tag, new_ds, &m, &o);
        }
    }

    for (int s = 0; s < SD_GRID_SLOTS; ++s) {
        tag[s] = s < m ? new_tag[s] : 0u;
        ds[s] = s < m ? new_ds[s] : sd_v3_zero();
    }
    return o;
}

#endif
