/* rebuild.c — the world's side of the broad phase: the world fills the
 * broad phase's input (broad/bins.h) from its arrays and tables, applies
 * the particle order the bins return (sd_particles_permute), makes the
 * ghosts, and has the pair lists rebuilt, the contact history carried by
 * key (DESIGN.md engineering notes). The broad phase itself never sees the
 * world; the threading policy and the wall marks are the world's.
 *
 * Invariant: after a rebuild, x_ref and q_ref are the positions and
 * orientations the lists were built from, the walls are marked at their
 * positions (servo.c), and ghosts p.n .. p.n + n_ghost - 1 hold copies of
 * their owners.
 */
#include <string.h>

#include "core/alloc.h"
#include "contact/pair_poly.h"
#include "core/error.h"
#include "world/world.h"

void sd_world_broad_free(sd_world *w)
{
    sd_pairs_free(&w->pairs, &w->wpairs);
    sd_bins_free(&w->bins);
    sd_free(w->ghost_owner);
    sd_free(w->ghost_shift);
    w->ghost_owner = NULL;
    w->ghost_shift = NULL;
    w->n_ghost = w->ghost_cap = 0;
}

/* The tables the input points into, made for one rebuild (a few bytes per
 * template, material pair and wall). */
typedef struct sd_rebuild_tables {
    uint8_t *shape_class;
    uint8_t *volume_law;
    sd_wall_geom *walls;
    int32_t *wall_material;
} sd_rebuild_tables;

static void sd_rebuild_tables_free(sd_rebuild_tables *t)
{
    sd_free(t->shape_class);
    sd_free(t->volume_law);
    sd_free(t->walls);
    sd_free(t->wall_material);
}

static sd_status sd_rebuild_input_of(const sd_world *w, sd_bins_input *in, sd_rebuild_tables *t)
{
    const sd_particles *p = &w->p;
    memset(in, 0, sizeof *in);
    memset(t, 0, sizeof *t);
    size_t ns = w->dim2 ? w->shape2d_count : w->shape_count, nm = w->material_count, nw = w->wall_count;
    t->shape_class = sd_malloc(ns ? ns : 1);
    t->volume_law = w->has_volume_law ? sd_malloc(nm > 0 ? nm * nm : 1) : NULL;
    t->walls = sd_malloc((nw ? nw : 1) * sizeof *t->walls);
    t->wall_material = sd_malloc((nw ? nw : 1) * sizeof *t->wall_material);
    if (!t->shape_class || (w->has_volume_law && !t->volume_law) || !t->walls || !t->wall_material) {
        sd_rebuild_tables_free(t);
        return SD_ERR_MEMORY;
    }
    for (size_t s = 0; s < ns; ++s)
        t->shape_class[s] = (uint8_t)(w->dim2 ? SD_CLASS_SHAPE2D
                                              : (sd_shape_is_sharp_polyhedron(&w->shapes[s]) ? SD_CLASS_SHARP_POLY
                                                                                            : SD_CLASS_SHAPE));
    if (t->volume_law)
        for (size_t m = 0; m < nm * nm; ++m)
            t->volume_law[m] = (uint8_t)sd_law_is_volume(w->mix[m].law);
    for (size_t k = 0; k < nw; ++k) {
        t->walls[k] = w->walls[k].geom;
        t->wall_material[k] = w->walls[k].material;
    }
    in->n_owned = p->n;
    in->n_total = p->n + w->n_ghost;
    in->x = p->x;
    in->radius = p->radius;
    in->id = p->id;
    /* a world of plain spheres passes no shapes: every pair is a sphere pair */
    in->shape = w->has_shapes ? p->shape : NULL;
    in->shape_class = t->shape_class;
    in->material = p->material;
    in->ghost_owner = w->ghost_owner;
    in->material_count = nm;
    in->volume_law = t->volume_law;
    in->wall_count = nw;
    in->walls = t->walls;
    in->wall_material = t->wall_material;
    in->skin = w->skin;
    in->threads = w->threads;
    in->parallel = w->parallel;
    return SD_OK;
}

sd_status sd_world_rebuild(sd_world *w, sd_error *err)
{
    sd_particles *p = &w->p;
    /* the threading policy: small worlds stay serial (forking threads costs
     * more than it saves) */
    w->parallel = w->threads > 1 && p->n >= SD_PARALLEL_MIN_PARTICLES;
    if (p->n == 0) {
        memset(&w->pairs.kind_start, 0, sizeof w->pairs.kind_start);
        memset(&w->wpairs.kind_start, 0, sizeof w->wpairs.kind_start);
        w->pairs.n = 0;
        w->wpairs.n = 0;
        w->n_ghost = 0;
        w->rebuilds++;
        return SD_OK;
    }
    w->n_ghost = 0; /* made again below, after the owned particles are sorted */
    sd_bins_input in;
    sd_rebuild_tables tables;
    sd_status st = sd_rebuild_input_of(w, &in, &tables);
    if (st == SD_OK) {
        const uint32_t *perm;
        void *scratch;
        st = sd_bins_sort(&w->bins, &in, &perm, &scratch);
        if (st == SD_OK) {
            /* the pair lists hold their history under stable keys, so the
             * storage order may change under them */
            sd_particles_permute(p, perm, scratch, w->threads, w->parallel);
            in.n_total = p->n + w->n_ghost;
            in.ghost_owner = w->ghost_owner;
            st = sd_bins_build(&w->bins, &in, &w->pairs, &w->wpairs);
        }
        sd_rebuild_tables_free(&tables);
    }
    if (st != SD_OK)
        return sd_error_set(err, st, "", 0, "", "out of memory while building the pair list (%zu particles)", p->n);
    size_t n = p->n;
    SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel))
    for (size_t k = 0; k < n; ++k) {
        p->x_ref[k] = p->x[k];
        p->q_ref[k] = p->q[k];
    }
    sd_world_walls_mark(w); /* a wall and a particle may each use half the skin */
    w->rebuilds++;
    w->dirty = 0;
    return SD_OK;
}
