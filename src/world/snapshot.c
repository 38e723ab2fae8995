/* snapshot.c — the world's state as named arrays (world/snapshot.h): the
 * one list of what a checkpoint holds, the copy into a snapshot and the
 * restore from one.
 *
 * The particle and pair fields come from their X-macro lists; the world's
 * own values from SD_WORLD_STATE and SD_WALL_STATE below; the solver's
 * from its sd_solver_ops.state. A restore lists the same refs after giving
 * the arrays the saved sizes, checks each saved item against its ref (name,
 * type, values per row, rows) and copies; an item on one side only is
 * refused by name, so a checkpoint never half-loads.
 */
#include "world/snapshot.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "world/mesh.h"
#include "world/process.h"
#include "world/restore_check.h"
#include "world/solver.h"
#include "world/view.h"
#include "world/world.h"

_Static_assert(sizeof(sd_real) == 8, "checkpoints store sd_real as 64-bit floats");
_Static_assert(sizeof(sd_vec3) == 3 * sizeof(sd_real), "sd_vec3 is three reals");
_Static_assert(sizeof(sd_quat) == 4 * sizeof(sd_real), "sd_quat is four reals");
_Static_assert(sizeof(long) == 8 && sizeof(size_t) == 8, "counters are 64-bit");

size_t sd_state_type_size(sd_state_type t)
{
    switch (t) {
    case SD_ST_F64:
    case SD_ST_I64:
    case SD_ST_U64:
        return 8;
    case SD_ST_I32:
    case SD_ST_U32:
        return 4;
    case SD_ST_U16:
        return 2;
    case SD_ST_U8:
    case SD_ST_BYTES:
    case SD_ST_TYPE_COUNT:
        return 1;
    }
    return 1;
}

const char *sd_state_type_name(sd_state_type t)
{
    static const char *names[] = {"f64", "i64", "u64", "i32", "u32", "u16", "u8", "bytes"};
    return (unsigned)t < SD_ST_TYPE_COUNT ? names[t] : "?";
}

/* The stored type of a C type, from a pointer to it: reals and the
 * vectors of reals as f64 (3 or 4 per row), integers as themselves, any
 * other struct as an opaque record of this build. */
#define SD_ST_OF(ptr)                                                                                      \
    _Generic((ptr), double *: SD_ST_F64, sd_vec3 *: SD_ST_F64, sd_quat *: SD_ST_F64, long *: SD_ST_I64,    \
             long long *: SD_ST_I64, unsigned long *: SD_ST_U64, int *: SD_ST_I32, unsigned *: SD_ST_U32,  \
             uint16_t *: SD_ST_U16, uint8_t *: SD_ST_U8, default: SD_ST_BYTES)
#define SD_ST_COMPS(ptr) (sizeof *(ptr) / sd_state_type_size(SD_ST_OF(ptr)))

int sd_state_add(sd_state_table *t, const char *name, sd_state_type type, size_t comps, size_t count, void *base,
                 size_t stride)
{
    if (t->n == t->cap) {
        size_t cap = t->cap ? 2 * t->cap : 64;
        sd_state_ref *r = sd_realloc(t->refs, cap * sizeof *r);
        if (!r) {
            t->oom = 1;
            return 0;
        }
        t->refs = r;
        t->cap = cap;
    }
    sd_state_ref *r = &t->refs[t->n++];
    memset(r, 0, sizeof *r);
    snprintf(r->name, sizeof r->name, "%s", name);
    r->type = type;
    r->comps = comps;
    r->count = count;
    r->base = base;
    r->stride = stride;
    return 1;
}

void sd_state_table_free(sd_state_table *t)
{
    sd_free(t->refs);
    t->refs = NULL;
    t->n = t->cap = 0;
}

/* ---- snapshots ---------------------------------------------------------------- */

void sd_snapshot_init(sd_snapshot *s) { memset(s, 0, sizeof *s); }

void sd_snapshot_free(sd_snapshot *s)
{
    for (size_t k = 0; k < s->n; ++k)
        sd_free(s->items[k].data);
    sd_free(s->items);
    memset(s, 0, sizeof *s);
}

sd_snap_item *sd_snapshot_add(sd_snapshot *s, const char *name, sd_state_type type, size_t comps, size_t count,
                              const void *data)
{
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 64;
        sd_snap_item *it = sd_realloc(s->items, cap * sizeof *it);
        if (!it)
            return NULL;
        s->items = it;
        s->cap = cap;
    }
    size_t es = sd_state_type_size(type);
    if (comps && count > (size_t)-1 / 2 / comps / es)
        return NULL;
    size_t bytes = count * comps * es;
    void *d = sd_malloc(bytes ? bytes : 1);
    if (!d)
        return NULL;
    if (data && bytes)
        memcpy(d, data, bytes);
    else
        memset(d, 0, bytes ? bytes : 1);
    sd_snap_item *it = &s->items[s->n++];
    memset(it, 0, sizeof *it);
    snprintf(it->name, sizeof it->name, "%s", name);
    it->type = type;
    it->comps = comps;
    it->count = count;
    it->data = d;
    return it;
}

static int sd_snap_item_cmp(const void *a, const void *b)
{
    return strcmp(((const sd_snap_item *)a)->name, ((const sd_snap_item *)b)->name);
}

void sd_snapshot_sort(sd_snapshot *s)
{
    if (s->n > 1)
        qsort(s->items, s->n, sizeof *s->items, sd_snap_item_cmp);
}

const sd_snap_item *sd_snapshot_find(const sd_snapshot *s, const char *name)
{
    size_t lo = 0, hi = s->n;
    while (lo < hi) { /* sorted by name */
        size_t mid = lo + (hi - lo) / 2;
        int c = strcmp(s->items[mid].name, name);
        if (c == 0)
            return &s->items[mid];
        if (c < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return NULL;
}

int sd_snapshot_get_u64(const sd_snapshot *s, const char *name, uint64_t *out)
{
    const sd_snap_item *it = sd_snapshot_find(s, name);
    if (!it || it->count != 1 || it->comps != 1)
        return 0;
    switch (it->type) {
    case SD_ST_U64:
    case SD_ST_I64: {
        uint64_t v;
        memcpy(&v, it->data, 8);
        *out = v;
        return it->type == SD_ST_U64 || (int64_t)v >= 0;
    }
    case SD_ST_U32:
    case SD_ST_I32: {
        uint32_t v;
        memcpy(&v, it->data, 4);
        *out = v;
        return it->type == SD_ST_U32 || (int32_t)v >= 0;
    }
    default:
        return 0;
    }
}

uint64_t sd_fnv1a(uint64_t h, const void *data, size_t n)
{
    const unsigned char *b = data;
    for (size_t k = 0; k < n; ++k) {
        h ^= b[k];
        h *= 0x100000001b3ull;
    }
    return h;
}

uint64_t sd_snapshot_checksum(const sd_snapshot *s)
{
    uint64_t h = SD_FNV_BASIS;
    for (size_t k = 0; k < s->n; ++k) {
        const sd_snap_item *it = &s->items[k];
        uint64_t head[3] = {(uint64_t)it->type, (uint64_t)it->comps, (uint64_t)it->count};
        h = sd_fnv1a(h, it->name, strlen(it->name) + 1);
        h = sd_fnv1a(h, head, sizeof head);
        h = sd_fnv1a(h, it->data, it->count * it->comps * sd_state_type_size(it->type));
    }
    return h;
}

/* ---- what the world lists ------------------------------------------------------ */

/* World-level state: X(name, pointer to the first value, values). Add a
 * line here for a new world-level value (insertion counters, an rng, ...);
 * its type comes from the pointer. */
#define SD_WORLD_STATE(X, w)                                                                             \
    X("world/step", &(w)->step, 1)                                                                       \
    X("world/time", &(w)->time, 1)                                                                       \
    X("world/next_id", &(w)->next_id, 1)                                                                 \
    X("world/dt", &(w)->dt, 1)                                                                           \
    X("world/gravity", &(w)->gravity, 1)                                                                 \
    X("world/local_damping", &(w)->local_damping, 1)                                                     \
    X("world/skin", &(w)->skin, 1)                                                                       \
    X("world/walls_moving", &(w)->walls_moving, 1)                                                       \
    X("world/biaxial_ref", &(w)->biaxial_ref, 1)                                                         \
    X("world/rebuilds", &(w)->rebuilds, 1)                                                               \
    X("world/dirty", &(w)->dirty, 1)                                                                     \
    X("world/has_shapes", &(w)->has_shapes, 1)                                                           \
    X("world/narrow", &(w)->narrow[0][0][0], SD_SHAPE_KIND_COUNT * SD_SHAPE_KIND_COUNT * 3)              \
    X("world/narrow2d", &(w)->narrow2d[0][0][0], SD_SHAPE2D_KIND_COUNT * SD_SHAPE2D_KIND_COUNT * 4)

/* Per-wall state, one row per wall: X(member). The geometry (moved by the
 * walls' motion), the last step's totals and the motion state; names,
 * kinds and materials come from the scene (and its hash). */
#define SD_WALL_STATE(X)                                                                                 \
    X(geom)                                                                                              \
    X(force)                                                                                             \
    X(torque)                                                                                            \
    X(motion)                                                                                            \
    X(moving)                                                                                            \
    X(velocity)                                                                                          \
    X(point_ref)                                                                                         \
    X(stiffness)                                                                                         \
    X(servo_i)                                                                                           \
    X(omega)

/* Per-mesh state, one row per mesh wall (world/mesh.h): X(member). The
 * pose at the last rebuild (the skin test of a moving mesh) and the cell
 * edge of its facet bins, which sd_world_meshes_resumed bins again at that
 * edge (the near facets come in the saved run's order); the facets, their
 * plane groups and the motion come from the scene. */
#define SD_MESH_STATE(X)                                                                                 \
    X(trans_ref)                                                                                         \
    X(q_ref)                                                                                             \
    X(h)

/* The sizes a restore gives the arrays: the saved one-value item name, or
 * 0 and a message. */
static sd_status sd_saved_size(const sd_state_table *t, const char *name, size_t *out, sd_error *err)
{
    uint64_t v;
    if (!sd_snapshot_get_u64(t->saved, name, &v))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, name, "the checkpoint lacks the size '%s' (or it is not a "
                            "single non-negative integer)", name);
    if (v > ((uint64_t)1 << 40))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, name, "the checkpoint's size '%s' = %llu is out of range",
                            name, (unsigned long long)v);
    *out = (size_t)v;
    return SD_OK;
}

/* Rows of a saved item (0 when absent: the compare step names it). */
static size_t sd_saved_rows(const sd_state_table *t, const char *name)
{
    const sd_snap_item *it = sd_snapshot_find(t->saved, name);
    return it ? it->count : 0;
}

static sd_status sd_grow_u32(uint32_t **p, size_t *cap, size_t need)
{
    if (need <= *cap)
        return SD_OK;
    uint32_t *q = sd_realloc(*p, need * sizeof *q);
    if (!q)
        return SD_ERR_MEMORY;
    *p = q;
    *cap = need;
    return SD_OK;
}

/* The cells solver's state: the particle arrays with their ghosts, the
 * ghosts' owners and shifts, both pair lists with every field, their kind
 * segments and gather lists. */
sd_status sd_cells_state(sd_world *w, sd_state_table *t, sd_error *err)
{
    sd_particles *p = &w->p;
    sd_pair_list *l = &w->pairs;
    sd_wall_pair_list *wl = &w->wpairs;
    if (t->saved) {
        size_t n = 0, ng = 0, np = 0, nwp = 0;
        sd_status st;
        if ((st = sd_saved_size(t, "particles/n", &n, err)) != SD_OK ||
            (st = sd_saved_size(t, "ghosts/n", &ng, err)) != SD_OK ||
            (st = sd_saved_size(t, "pairs/n", &np, err)) != SD_OK ||
            (st = sd_saved_size(t, "wall_pairs/n", &nwp, err)) != SD_OK)
            return st;
        size_t gs = sd_saved_rows(t, "pairs/gstart"), wgs = sd_saved_rows(t, "wall_pairs/gstart");
        size_t ntri = sd_saved_rows(t, "wall_pairs/tri");
        if (sd_particles_reserve(p, n + ng) != SD_OK || sd_grow_u32(&w->ghost_owner, &w->ghost_cap, ng) != SD_OK)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for %zu particles", n + ng);
        if (ng > 0) {
            sd_vec3 *sh = sd_realloc(w->ghost_shift, w->ghost_cap * sizeof *sh);
            if (!sh)
                return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for %zu ghosts", ng);
            w->ghost_shift = sh;
        }
        size_t lgs = l->gstart_cap, wlgs = wl->gstart_cap;
        if (sd_pairs_reserve(l, np) != SD_OK || sd_pairs_reserve_walls(wl, nwp) != SD_OK ||
            sd_grow_u32(&l->gstart, &lgs, gs) != SD_OK || sd_grow_u32(&wl->gstart, &wlgs, wgs) != SD_OK)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for %zu pairs", np + nwp);
        l->gstart_cap = lgs;
        wl->gstart_cap = wlgs;
        if (sd_grow_u32(&wl->tri, &wl->tri_cap, ntri) != SD_OK)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for %zu mesh triangles", ntri);
        wl->tri_n = ntri;
        p->n = n;
        ++p->generation;
        w->n_ghost = ng;
        l->n = np;
        wl->n = nwp;
    }
    size_t nt = p->n + w->n_ghost;
    sd_state_add(t, "particles/n", SD_ST_U64, 1, 1, &p->n, 8);
    sd_state_add(t, "ghosts/n", SD_ST_U64, 1, 1, &w->n_ghost, 8);
#define SD_X_PARTICLE(type, name, ...) \
    sd_state_add(t, "particles/" #name, SD_ST_OF(p->name), SD_ST_COMPS(p->name), nt, p->name, sizeof(type));
    SD_PARTICLE_FIELDS(SD_X_PARTICLE)
#undef SD_X_PARTICLE
    sd_state_add(t, "ghosts/owner", SD_ST_U32, 1, w->n_ghost, w->ghost_owner, sizeof(uint32_t));
    sd_state_add(t, "ghosts/shift", SD_ST_F64, 3, w->n_ghost, w->ghost_shift, sizeof(sd_vec3));

    sd_state_add(t, "pairs/n", SD_ST_U64, 1, 1, &l->n, 8);
    sd_state_add(t, "pairs/kind_start", SD_ST_U64, SD_PAIR_KIND_COUNT + 1, 1, l->kind_start, 0);
#define SD_X_PAIR(type, name, per, role, doc)                                                              \
    sd_state_add(t, "pairs/" #name, SD_ST_OF(l->name), (per) * SD_ST_COMPS(l->name), l->n, l->name,        \
                 (per) * sizeof(type));
    SD_PAIR_FIELDS(SD_X_PAIR)
#undef SD_X_PAIR
    /* gather lists: one start per owned particle and one more, once built
     * and current. A world changed since its last rebuild (dirty: particles
     * inserted or removed) has stale lists, shorter than the particle count
     * after an insertion, that the next step rebuilds before any use: none
     * are saved (their bytes would be read past the arrays and mean nothing) */
    int current = !w->dirty;
    size_t gs = t->saved ? sd_saved_rows(t, "pairs/gstart") : (l->gstart && current ? p->n + 1 : 0);
    sd_state_add(t, "pairs/gstart", SD_ST_U32, 1, gs, l->gstart, 4);
    sd_state_add(t, "pairs/gidx", SD_ST_U32, 1, gs ? 2 * l->n : 0, l->gidx, 4);

    sd_state_add(t, "wall_pairs/n", SD_ST_U64, 1, 1, &wl->n, 8);
    sd_state_add(t, "wall_pairs/kind_start", SD_ST_U64, SD_WALL_PAIR_KIND_COUNT + 1, 1, wl->kind_start, 0);
#define SD_X_WPAIR(type, name, per, role, doc)                                                             \
    sd_state_add(t, "wall_pairs/" #name, SD_ST_OF(wl->name), (per) * SD_ST_COMPS(wl->name), wl->n, wl->name, \
                 (per) * sizeof(type));
    SD_WALL_PAIR_FIELDS(SD_X_WPAIR)
#undef SD_X_WPAIR
    size_t wgs = t->saved ? sd_saved_rows(t, "wall_pairs/gstart") : (wl->gstart && current ? p->n + 1 : 0);
    sd_state_add(t, "wall_pairs/gstart", SD_ST_U32, 1, wgs, wl->gstart, 4);
    sd_state_add(t, "wall_pairs/gidx", SD_ST_U32, 1, wgs ? wl->n : 0, wl->gidx, 4);
    /* mesh pairs: the near triangles of each pair's plane group */
    sd_state_add(t, "wall_pairs/tri", SD_ST_U32, 1, wl->tri_n, wl->tri, 4);
    if (t->saved && ((gs != 0 && gs != p->n + 1) || (wgs != 0 && wgs != p->n + 1)))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "pairs/gstart",
                            "the checkpoint's gather lists have %zu and %zu starts for %zu particles", gs, wgs, p->n);
    if (t->saved) {
        /* lists the next step uses as they are must be there (the world's
         * own, made for the scene's particles, would index past them) */
        uint64_t dirty = 1;
        (void)sd_snapshot_get_u64(t->saved, "world/dirty", &dirty);
        if (!dirty && p->n > 0 && (gs == 0 || wgs == 0))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "pairs/gstart",
                                "the checkpoint lacks the gather lists of its %zu particles", p->n);
    }
    return SD_OK;
}

/* After a cells restore: what prepare would leave but the forces, which
 * came with the state (velocity Verlet's first kick uses them). */
sd_status sd_cells_resumed(sd_world *w, sd_error *err)
{
    sd_status st = sd_world_mix_materials(w, err);
    if (st == SD_OK)
        st = sd_world_check_params(w, err);
    if (st != SD_OK)
        return st;
    w->parallel = sd_world_wants_parallel(w);
    /* the gather lists index owned particles and pairs: check them, so a
     * damaged (but checksummed) file can never index past the arrays */
    const sd_pair_list *l = &w->pairs;
    const sd_wall_pair_list *wl = &w->wpairs;
    size_t n = w->p.n, nt = n + w->n_ghost;
    for (size_t e = 0; e < l->n; ++e)
        if (l->i[e] >= n || l->j[e] >= nt)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "pairs/i", "pair %zu indexes particles %u and %u of %zu",
                                e, l->i[e], l->j[e], nt);
    for (size_t e = 0; e < wl->n; ++e)
        if (wl->i[e] >= n || wl->wall[e] >= w->wall_count || wl->tstart[e] > wl->tri_n ||
            wl->tcount[e] > wl->tri_n - wl->tstart[e])
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "wall_pairs/i", "wall pair %zu indexes particle %u, wall %u",
                                e, wl->i[e], wl->wall[e]);
    for (size_t g = 0; g < w->n_ghost; ++g)
        if (w->ghost_owner[g] >= n)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "ghosts/owner", "ghost %zu has owner %u of %zu", g,
                                w->ghost_owner[g], n);
    size_t kinds = SD_PAIR_KIND_COUNT, wkinds = SD_WALL_PAIR_KIND_COUNT;
    for (size_t k = 0; k < kinds; ++k)
        if (l->kind_start[k] > l->kind_start[k + 1] || l->kind_start[kinds] != l->n)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "pairs/kind_start", "kind segments out of order");
    for (size_t k = 0; k < wkinds; ++k)
        if (wl->kind_start[k] > wl->kind_start[k + 1] || wl->kind_start[wkinds] != wl->n)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "wall_pairs/kind_start", "kind segments out of order");
    /* particles removed since the last rebuild (world/remove.c): the
     * gather lists are stale and the next step rebuilds them before use */
    if (l->gstart && n > 0 && !w->dirty) {
        for (size_t k = 0; k < n; ++k)
            if (l->gstart[k] > l->gstart[k + 1])
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "pairs/gstart", "gather starts out of order");
        if (l->gstart[0] != 0 || l->gstart[n] > 2 * l->n)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "pairs/gstart", "gather starts out of range");
        for (size_t e = 0; e < l->gstart[n]; ++e)
            if (l->gidx[e] >= 2 * l->n)
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "pairs/gidx", "gather entry out of range");
    }
    /* a world saved dirty (changed since its last rebuild: an insertion, an
     * outlet, a checkpoint under mpirun) brings no gather lists, and the
     * arrays hold whatever the scene's build left there; the next step
     * rebuilds them, but the walls' drift before it reads the wall pairs in
     * gather order (servo.c's contact stiffness): the list's own order,
     * never indices that mean nothing */
    if (w->dirty)
        for (size_t g = 0; g < wl->n; ++g)
            wl->gidx[g] = (uint32_t)g;
    if (wl->gstart && n > 0 && !w->dirty) {
        for (size_t k = 0; k < n; ++k)
            if (wl->gstart[k] > wl->gstart[k + 1])
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "wall_pairs/gstart", "gather starts out of order");
        if (wl->gstart[0] != 0 || wl->gstart[n] > wl->n)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "wall_pairs/gstart", "gather starts out of range");
        for (size_t e = 0; e < wl->gstart[n]; ++e)
            if (wl->gidx[e] >= wl->n)
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "wall_pairs/gidx", "gather entry out of range");
    }
    for (size_t k = 0; k < nt; ++k) {
        int32_t s = w->p.shape[k], m = w->p.material[k];
        size_t ns = w->dim2 ? w->shape2d_count : w->shape_count;
        if (s < -1 || (s >= 0 && (size_t)s >= ns) || m < 0 || (size_t)m >= w->material_count)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "particles/shape",
                                "particle %zu has shape %d of %zu and material %d of %zu", k, (int)s, ns, (int)m,
                                w->material_count);
    }
    if (sd_world_meshes_resumed(w) != SD_OK)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the facet bins of %zu meshes",
                            w->mesh_count);
    if (sd_world_views(w) != SD_OK)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the views");
    w->prepared = 1;
    return SD_OK;
}

sd_status sd_world_state_list(sd_world *w, sd_state_table *t, sd_error *err)
{
    /* the solver first: on a restore a grid world takes over the scene's
     * particles at its prepare, before the world's arrays take their size */
    sd_status st = w->solver->state(w, t, err);
    if (st != SD_OK)
        return st;
#define SD_X_WORLD(name, ptr, nv) sd_state_add(t, name, SD_ST_OF(ptr), (nv) * SD_ST_COMPS(ptr), 1, (void *)(ptr), 0);
    SD_WORLD_STATE(SD_X_WORLD, w)
#undef SD_X_WORLD
    /* insertions and outlets (world/process.h): one plain struct without
     * pointers (the names are copied in), its streams and counters */
    sd_state_add(t, "world/process", SD_ST_BYTES, sizeof(struct sd_process), w->process ? 1 : 0, w->process, 0);
    sd_wall *wa = w->walls;
#define SD_X_WALL(member)                                                                                    \
    sd_state_add(t, "walls/" #member, SD_ST_OF(&wa->member), SD_ST_COMPS(&wa->member), w->wall_count,        \
                 wa ? (void *)&wa->member : NULL, sizeof(sd_wall));
    SD_WALL_STATE(SD_X_WALL)
#undef SD_X_WALL
    sd_mesh_store *ms = w->meshes;
#define SD_X_MESH(member)                                                                                    \
    sd_state_add(t, "meshes/" #member, SD_ST_OF(&ms->member), SD_ST_COMPS(&ms->member), w->mesh_count,       \
                 ms ? (void *)&ms->member : NULL, sizeof(sd_mesh_store));
    SD_MESH_STATE(SD_X_MESH)
#undef SD_X_MESH
    if (t->oom)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory listing the state");
    return SD_OK;
}

/* ---- save and restore ---------------------------------------------------------- */

static void sd_gather_rows(void *dst, const sd_state_ref *r)
{
    size_t row = r->comps * sd_state_type_size(r->type);
    for (size_t k = 0; k < r->count; ++k)
        memcpy((char *)dst + k * row, (const char *)r->base + k * r->stride, row);
}

static void sd_scatter_rows(const sd_state_ref *r, const void *src)
{
    size_t row = r->comps * sd_state_type_size(r->type);
    for (size_t k = 0; k < r->count; ++k)
        memcpy((char *)r->base + k * r->stride, (const char *)src + k * row, row);
}

/* What the scene named, for readers of the checkpoint other than a
 * restart (a new scene that starts from its particles, io/scene_from.c;
 * h5py): per template its name, kind, volume (2D: area) and bounding
 * radius, and for a scaled copy the template it copies and the factor
 * (else -1 and 1), per material its name; the particles' shape and material
 * columns index them. Fixed-width rows padded with zeros, so the bytes
 * depend on the names only. A restart skips them (the scene's hash covers
 * what they say). */
static sd_status sd_snapshot_scene_items(const sd_world *w, sd_snapshot *s)
{
    size_t ns = sd_world_shape_count(w), nm = w->material_count;
    sd_snap_item *names = sd_snapshot_add(s, "scene/shape_names", SD_ST_BYTES, SD_SNAP_NAME, ns, NULL);
    sd_snap_item *kinds = sd_snapshot_add(s, "scene/shape_kinds", SD_ST_BYTES, SD_SNAP_NAME, ns, NULL);
    sd_snap_item *sizes = sd_snapshot_add(s, "scene/shape_sizes", SD_ST_F64, 2, ns, NULL);
    sd_snap_item *mats = sd_snapshot_add(s, "scene/material_names", SD_ST_BYTES, SD_SNAP_NAME, nm, NULL);
    sd_snap_item *bases = sd_snapshot_add(s, "scene/shape_bases", SD_ST_I32, 1, ns, NULL);
    sd_snap_item *scales = sd_snapshot_add(s, "scene/shape_scales", SD_ST_F64, 1, ns, NULL);
    if (!names || !kinds || !sizes || !mats || !bases || !scales)
        return SD_ERR_MEMORY;
    /* the items may have moved as the list grew: look them up again */
    names = &s->items[s->n - 6];
    kinds = &s->items[s->n - 5];
    sizes = &s->items[s->n - 4];
    mats = &s->items[s->n - 3];
    bases = &s->items[s->n - 2];
    scales = &s->items[s->n - 1];
    for (size_t k = 0; k < ns; ++k) {
        /* a scaled copy of an insertion (world/scaled.c): its template and
         * factor, so that a new scene makes the same copy; else -1 and 1 */
        int b = -1;
        double sc = 1.0;
        if (!sd_world_scaled_of(w, k, &b, &sc)) {
            b = -1;
            sc = 1.0;
        }
        int32_t b32 = b;
        memcpy((int32_t *)bases->data + k, &b32, sizeof b32);
        memcpy((double *)scales->data + k, &sc, sizeof sc);
        sd_shape_info si;
        if (sd_world_get_shape(w, k, &si) != SD_OK)
            continue;
        /* snprintf stops at the NUL: the zeros after it stay */
        snprintf((char *)names->data + k * SD_SNAP_NAME, SD_SNAP_NAME, "%s", si.name ? si.name : "");
        snprintf((char *)kinds->data + k * SD_SNAP_NAME, SD_SNAP_NAME, "%s", si.kind ? si.kind : "");
        double v[2] = {si.volume, si.bounding_radius};
        memcpy((double *)sizes->data + 2 * k, v, sizeof v);
    }
    for (size_t k = 0; k < nm; ++k)
        snprintf((char *)mats->data + k * SD_SNAP_NAME, SD_SNAP_NAME, "%s", w->materials[k].name);
    /* the scene hash's parts, so a refused restart names the part that
     * differs (world/scene_hash.c) */
    uint64_t part[SD_SCENE_PART_COUNT];
    sd_world_scene_parts(w, part);
    return sd_snapshot_add(s, "scene/parts", SD_ST_U64, SD_SCENE_PART_COUNT, 1, part) ? SD_OK : SD_ERR_MEMORY;
}

sd_status sd_world_snapshot(const sd_world *wc, sd_snapshot *s, sd_error *err)
{
    sd_world *w = (sd_world *)wc; /* listing only reads */
    sd_snapshot_init(s);
    sd_state_table t;
    memset(&t, 0, sizeof t);
    sd_status st = sd_world_state_list(w, &t, err);
    for (size_t k = 0; st == SD_OK && k < t.n; ++k) {
        const sd_state_ref *r = &t.refs[k];
        sd_snap_item *it = sd_snapshot_add(s, r->name, r->type, r->comps, r->count, NULL);
        if (!it)
            st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory copying '%s'", r->name);
        else if (r->count)
            sd_gather_rows(it->data, r);
    }
    sd_state_table_free(&t);
    if (st == SD_OK && sd_snapshot_scene_items(w, s) != SD_OK)
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory copying the template names");
    if (st != SD_OK) {
        sd_snapshot_free(s);
        return st;
    }
    sd_snapshot_sort(s);
    s->version = SD_SNAPSHOT_VERSION;
    s->scene_hash = sd_world_scene_hash(w);
    s->step = w->step;
    s->time = w->time;
    s->dimension = w->dim2 ? 2 : 3;
    snprintf(s->solver, sizeof s->solver, "%s", w->solver->name);
    snprintf(s->writer, sizeof s->writer, "%s", SD_VERSION_STRING);
    s->checksum = sd_snapshot_checksum(s);
    return SD_OK;
}

static int sd_snap_is_scene(const sd_snap_item *it) { return strncmp(it->name, "scene/", 6) == 0; }

static int sd_ref_cmp(const void *a, const void *b)
{
    return strcmp(((const sd_state_ref *)a)->name, ((const sd_state_ref *)b)->name);
}

sd_status sd_world_restore(sd_world *w, const sd_snapshot *s, sd_error *err)
{
    if (s->version == 2)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "checkpoint format version 2 (written by shapedem %s), "
                            "whose scene hash leaves out mesh walls, drums, insertions and outlets: this shapedem "
                            "restarts version %u only; restart it with the shapedem that wrote it, or start a new "
                            "scene from its particles (a csv generator, docs/checkpoints.md)", s->writer,
                            SD_SNAPSHOT_VERSION);
    if (s->version != SD_SNAPSHOT_VERSION)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "checkpoint format version %u, this shapedem reads "
                            "version %u (written by shapedem %s)", s->version, SD_SNAPSHOT_VERSION, s->writer);
    if (w->step != 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "a checkpoint restores into a world freshly built from "
                            "its scene, not one already stepped (step %ld)", w->step);
    if (strcmp(s->solver, w->solver->name) != 0 || s->dimension != (w->dim2 ? 2 : 3))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "the checkpoint is of a %dD run on the %s solver, the "
                            "scene is %dD on the %s solver", s->dimension, s->solver, w->dim2 ? 2 : 3,
                            w->solver->name);
    uint64_t h = sd_world_scene_hash(w);
    if (s->scene_hash != h) {
        /* name the parts that differ where the file lists them */
        uint64_t part[SD_SCENE_PART_COUNT];
        char what[512];
        sd_world_scene_parts(w, part);
        const sd_snap_item *it = sd_snapshot_find(s, "scene/parts");
        if (!it || it->type != SD_ST_U64 || it->comps != SD_SCENE_PART_COUNT || it->count != 1 ||
            sd_scene_parts_differ(it->data, part, what, sizeof what) == 0)
            snprintf(what, sizeof what, "materials, shapes, walls, time step or another setting of the physics");
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "the checkpoint was written by another scene: %s differ "
                            "(scene hash %016llx, this scene's is %016llx)", what,
                            (unsigned long long)s->scene_hash, (unsigned long long)h);
    }
    sd_state_table t;
    memset(&t, 0, sizeof t);
    t.saved = s;
    sd_status st = sd_world_state_list(w, &t, err);
    if (st == SD_OK) {
        qsort(t.refs, t.n, sizeof *t.refs, sd_ref_cmp);
        /* both sorted by name: a merge finds what only one side has (the
         * scene/ items describe the scene for other readers: not state) */
        size_t a = 0, b = 0;
        while (st == SD_OK && (a < t.n || b < s->n)) {
            if (b < s->n && sd_snap_is_scene(&s->items[b])) {
                ++b;
                continue;
            }
            int c = a == t.n ? 1 : b == s->n ? -1 : strcmp(t.refs[a].name, s->items[b].name);
            if (c < 0)
                st = sd_error_set(err, SD_ERR_INPUT, "", 0, t.refs[a].name, "the checkpoint lacks '%s' (written "
                                  "by another version of shapedem?)", t.refs[a].name);
            else if (c > 0)
                st = sd_error_set(err, SD_ERR_INPUT, "", 0, s->items[b].name, "the checkpoint holds '%s', which "
                                  "this shapedem does not know (written by another version?)", s->items[b].name);
            else {
                const sd_state_ref *r = &t.refs[a];
                const sd_snap_item *it = &s->items[b];
                if (r->type != it->type || r->comps != it->comps || r->count != it->count)
                    st = sd_error_set(err, SD_ERR_INPUT, "", 0, r->name, "'%s' is %zu x %zu %s in the checkpoint, "
                                      "expected %zu x %zu %s", r->name, it->count, it->comps,
                                      sd_state_type_name(it->type), r->count, r->comps, sd_state_type_name(r->type));
                ++a;
                ++b;
            }
        }
    }
    /* every real finite before the copy; the scene's definitions kept
     * aside, then the copied values checked before any use (a checksum can
     * be recomputed: it validates no content; world/restore_check.c) */
    sd_restore_kept keep;
    memset(&keep, 0, sizeof keep);
    if (st == SD_OK)
        st = sd_restore_check_items(s, err);
    if (st == SD_OK && sd_restore_keep(w, &keep) != SD_OK)
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory keeping the scene's walls");
    /* all checked: now copy (the sizes first were set by the listing) */
    for (size_t k = 0, j = 0; st == SD_OK && k < t.n; ++k, ++j) {
        while (sd_snap_is_scene(&s->items[j]))
            ++j;
        const sd_snap_item *it = &s->items[j];
        if (t.refs[k].count)
            sd_scatter_rows(&t.refs[k], it->data);
    }
    sd_state_table_free(&t);
    if (st == SD_OK)
        st = sd_restore_check_world(w, &keep, err);
    sd_restore_kept_free(&keep);
    if (st != SD_OK)
        return st;
    return w->solver->resumed(w, err);
}
