/* remove.c — removal of marked particles from a cells world between steps.
 *
 * Invariant kept: after a removal every particle array (SD_PARTICLE_FIELDS)
 * holds the survivors in their old relative order, owned ones first, then
 * the surviving periodic images (the ghosts of a removed particle go with
 * it) with ghost_owner remapped; every pair in the particle and wall pair
 * lists that touched a removed particle is dropped and the others are
 * renumbered, each keeping its history (SD_PF_HISTORY fields) and its
 * last evaluation, in its kind segment and in its old order. So anything
 * that reads the lists between steps (sd_world_stats, output) sees a
 * consistent world, and the next step rebuilds the lists (w->dirty), the
 * history carried by the stable keys as at any rebuild. The gather lists
 * are stale until that rebuild; nothing reads them before it (the
 * forces stage rebuilds before it gathers).
 *
 * Deterministic: one serial pass in storage order; the result does not
 * depend on the thread count. The forces already summed into the
 * survivors (p->f, p->t of the last step) keep the removed particle's
 * share: it was there at that time, and velocity Verlet's next half kick
 * (seed 004 eq. 9) uses the force at that time.
 */
#include "world/remove.h"

#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "world/solver.h"
#include "world/view.h"
#include "world/world.h"

#define SD_GONE UINT32_MAX

/* Drops the pairs of list l whose particle(s) are gone, renumbering the
 * others through map; kind segments keep their order. */
static void sd_remove_compact_pairs(sd_pair_list *l, const uint32_t *map)
{
    size_t out = 0;
    size_t start[SD_PAIR_KIND_COUNT + 1];
    for (int k = 0; k < SD_PAIR_KIND_COUNT; ++k) {
        start[k] = out;
        for (size_t e = l->kind_start[k]; e < l->kind_start[k + 1]; ++e) {
            uint32_t i = map[l->i[e]], j = map[l->j[e]];
            if (i == SD_GONE || j == SD_GONE)
                continue;
            if (out != e) {
#define SD_X_MOVE(type, name, per, role, doc)                 \
    for (size_t s = 0; s < (size_t)(per); ++s)                \
        l->name[out * (size_t)(per) + s] = l->name[e * (size_t)(per) + s];
                SD_PAIR_FIELDS(SD_X_MOVE)
#undef SD_X_MOVE
            }
            l->i[out] = i;
            l->j[out] = j;
            ++out;
        }
    }
    start[SD_PAIR_KIND_COUNT] = out;
    memcpy(l->kind_start, start, sizeof start);
    l->n = out;
}

static void sd_remove_compact_wall_pairs(sd_wall_pair_list *l, const uint32_t *map)
{
    size_t out = 0;
    size_t start[SD_WALL_PAIR_KIND_COUNT + 1];
    for (int k = 0; k < SD_WALL_PAIR_KIND_COUNT; ++k) {
        start[k] = out;
        for (size_t e = l->kind_start[k]; e < l->kind_start[k + 1]; ++e) {
            uint32_t i = map[l->i[e]];
            if (i == SD_GONE)
                continue;
            if (out != e) {
#define SD_X_MOVE(type, name, per, role, doc)                 \
    for (size_t s = 0; s < (size_t)(per); ++s)                \
        l->name[out * (size_t)(per) + s] = l->name[e * (size_t)(per) + s];
                SD_WALL_PAIR_FIELDS(SD_X_MOVE)
#undef SD_X_MOVE
            }
            l->i[out] = i;
            ++out;
        }
    }
    start[SD_WALL_PAIR_KIND_COUNT] = out;
    memcpy(l->kind_start, start, sizeof start);
    l->n = out;
}

sd_status sd_world_remove_particles(sd_world *w, const uint8_t *mark, sd_remove_result *out, sd_error *err)
{
    if (out)
        memset(out, 0, sizeof *out);
    if (w->solver != &sd_solver_cells)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "particle removal is for the cells solver (the grid "
                            "solver removes through its own outlet)");
    sd_particles *p = &w->p;
    size_t n = p->n, ng = w->n_ghost, total = n + ng;
    size_t gone = 0;
    double mass = 0;
    for (size_t k = 0; k < n; ++k)
        if (mark[k]) {
            ++gone;
            if (p->inv_mass[k] > 0)
                mass += 1.0 / (double)p->inv_mass[k];
        }
    if (gone == 0)
        return SD_OK;
    uint32_t *map = sd_malloc(total * sizeof *map);
    if (!map)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory removing %zu of %zu particles", gone, n);
    uint32_t next = 0;
    for (size_t k = 0; k < n; ++k)
        map[k] = mark[k] ? SD_GONE : next++;
    size_t n_new = next;
    /* a ghost goes with its owner; another rank's (src/mpi/, ghost_owner
     * SD_GHOST_REMOTE*) stays until the next rebuild remakes the ghosts */
    for (size_t g = 0; g < ng; ++g)
        map[n + g] = (w->ghost_owner[g] < SD_GHOST_REMOTE_IMAGE && map[w->ghost_owner[g]] == SD_GONE) ? SD_GONE : next++;
    size_t ng_new = next - n_new;
    /* in place, forwards: map[k] <= k and increasing */
    for (size_t k = 0; k < total; ++k) {
        uint32_t d = map[k];
        if (d == SD_GONE || d == k)
            continue;
#define SD_X_MOVE(type, name, ...) p->name[d] = p->name[k];
        SD_PARTICLE_FIELDS(SD_X_MOVE)
#undef SD_X_MOVE
    }
    for (size_t g = 0; g < ng; ++g) {
        uint32_t d = map[n + g];
        if (d == SD_GONE)
            continue;
        size_t gn = d - n_new;
        w->ghost_owner[gn] = w->ghost_owner[g] < SD_GHOST_REMOTE_IMAGE ? map[w->ghost_owner[g]] : w->ghost_owner[g];
        w->ghost_shift[gn] = w->ghost_shift[g];
    }
    p->n = n_new;
    ++p->generation;
    w->n_ghost = ng_new;
    sd_remove_compact_pairs(&w->pairs, map);
    sd_remove_compact_wall_pairs(&w->wpairs, map);
    sd_free(map);
    w->dirty = 1; /* new lists (and gather lists) before the next forces */
    /* the views carry the counts the first stages of the next step read
     * (kick and drift run before the rebuild) */
    if (w->prepared && sd_world_views(w) != SD_OK)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the views of %zu walls",
                            w->wall_count);
    if (out) {
        out->count = gone;
        out->mass = mass;
    }
    return SD_OK;
}

sd_status sd_world_remove_if(sd_world *w, sd_remove_pred pred, void *ctx, sd_remove_result *out, sd_error *err)
{
    if (out)
        memset(out, 0, sizeof *out);
    size_t n = w->p.n;
    if (n == 0)
        return SD_OK;
    uint8_t *mark = sd_malloc(n);
    if (!mark)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory marking %zu particles", n);
    size_t any = 0;
    for (size_t k = 0; k < n; ++k) {
        mark[k] = (uint8_t)(pred(w, k, ctx) != 0);
        any += mark[k];
    }
    sd_status st = any ? sd_world_remove_particles(w, mark, out, err) : SD_OK;
    sd_free(mark);
    return st;
}
