/* view.c — the world fills the backend's views (backend/view.h): the
 * particle arrays, shape tables, mixed parameters, walls and pair lists as
 * plain pointers and counts, so that no backend stage sees sd_world.
 *
 * Invariant: the views are refilled after everything that can move the
 * arrays they point into — prepare (materials mixed, particles added) and
 * every pair-list rebuild (arrays grown, particles permuted) — and the wall
 * copies after every wall motion (each step); the wall totals the backend
 * sums go back into the world's walls after each force evaluation.
 */
#include "world/view.h"

#include "core/alloc.h"

/* The pair lists are sorted into kind segments by the broad phase
 * (broad/bins.c), which records them in kind_start. */
static void sd_view_pairs(sd_world *w)
{
    sd_stage *s = &w->stage;
    const sd_pair_list *l = &w->pairs;
    sd_pair_out *o = &s->pairs;
    o->n = l->n;
    for (size_t k = 0; k <= SD_PAIR_KIND_COUNT; ++k)
        o->kind_start[k] = l->kind_start[k];
    o->i = l->i;
    o->j = l->j;
    o->flip = l->flip;
    o->key = l->key;
    o->ds = l->ds;
    o->f = l->f;
    o->t = l->t;
    o->delta = l->delta;
    o->energy = l->energy;
    o->warm = l->warm;
    o->iters = l->iters;
    o->supports = l->supports;
    o->x0 = l->x0;
    o->x0_ok = l->x0_ok;
    o->gstart = l->gstart;
    o->gidx = l->gidx;
    /* the gather lists' lengths, for a backend that copies them: those of
     * the last rebuild, none while stale (w->dirty: the next step rebuilds
     * them before it gathers) */
    int fresh = l->gstart && !w->dirty;
    o->n_gstart = fresh ? w->p.n + 1 : 0;
    o->n_gidx = fresh ? l->gstart[w->p.n] : 0;

    const sd_wall_pair_list *wl = &w->wpairs;
    sd_wall_pair_out *wo = &s->wpairs;
    wo->n = wl->n;
    for (size_t k = 0; k <= SD_WALL_PAIR_KIND_COUNT; ++k)
        wo->kind_start[k] = wl->kind_start[k];
    wo->i = wl->i;
    wo->wall = wl->wall;
    wo->sub = wl->sub;
    wo->tstart = wl->tstart;
    wo->tcount = wl->tcount;
    wo->tri = wl->tri;
    wo->n_tri = wl->tri_n;
    wo->elem = wl->elem;
    wo->ds = wl->ds;
    wo->f = wl->f;
    wo->t = wl->t;
    wo->c = wl->c;
    wo->delta = wl->delta;
    wo->energy = wl->energy;
    wo->gstart = wl->gstart;
    wo->gidx = wl->gidx;
    fresh = wl->gstart && !w->dirty;
    wo->n_gstart = fresh ? w->p.n + 1 : 0;
    wo->n_gidx = fresh ? wl->n : 0;
}

sd_status sd_world_views(sd_world *w)
{
    sd_stage *s = &w->stage;
    sd_step_view *v = &s->v;
    const sd_particles *p = &w->p;
    s->skin_known = 0; /* a rebuild set x_ref = x: the next drift tests the skin again */
    v->n_owned = p->n;
    v->n_total = p->n + w->n_ghost;
    v->ghost_owner = w->ghost_owner;
    v->ghost_shift = w->ghost_shift;
    v->x = p->x;
    v->v = p->v;
    v->w = p->w;
    v->q = p->q;
    v->f = p->f;
    v->t = p->t;
    v->radius = p->radius;
    v->inv_mass = p->inv_mass;
    v->inv_inertia = p->inv_inertia;
    v->x_ref = p->x_ref;
    v->q_ref = p->q_ref;
    v->material = p->material;
    v->shape = p->shape;
    v->id = p->id;
    v->shapes = w->shapes;
    v->verts = w->verts;
    v->planes = w->planes;
    v->dtris = w->dtris;
    v->elements = w->elements;
    v->shape_req = w->shape_req;
    v->shape_count = w->shape_count;
    v->vert_count = w->vert_count;
    v->plane_count = w->plane_count;
    v->dtri_count = w->dtri_count;
    v->element_count = w->element_count;
    v->shape2d_count = w->shape2d_count;
    v->pool2d_count = w->pool2d_count;
    v->shapes2d = w->shapes2d;
    v->pool2d = w->pool2d;
    v->mix = w->mix;
    v->material_count = w->material_count;
    v->dt = w->dt;
    v->gravity = w->gravity;
    v->damping = w->local_damping;
    v->skin = w->skin;
    v->dim2 = w->dim2;
    v->has_shapes = w->has_shapes;
    v->multi_contact = w->def.multi_contact;
    v->walls_moving = w->walls_moving;
    s->exec.threads = w->threads;
    s->exec.parallel = w->parallel;
    s->narrow = w->narrow;
    s->narrow2d = w->narrow2d;
    sd_view_pairs(w);
    if (w->wall_count > s->wall_cap) {
        size_t cap = w->wall_count;
        sd_wall_view *wv = sd_realloc(s->walls, cap * sizeof *wv);
        if (wv)
            s->walls = wv;
        sd_vec3 *f = wv ? sd_realloc(s->wall_force, cap * sizeof *f) : NULL;
        if (f)
            s->wall_force = f;
        sd_vec3 *t = f ? sd_realloc(s->wall_torque, cap * sizeof *t) : NULL;
        if (!t)
            return SD_ERR_MEMORY;
        s->wall_torque = t;
        s->wall_cap = cap;
    }
    v->walls = s->walls;
    v->wall_count = w->wall_count;
    v->meshes = w->mesh_views;
    v->mesh_count = w->mesh_count;
    sd_world_views_walls(w);
    return SD_OK;
}

void sd_world_views_params(sd_world *w)
{
    sd_step_view *v = &w->stage.v;
    v->dt = w->dt;
    v->gravity = w->gravity;
    v->damping = w->local_damping;
    sd_world_views_walls(w);
}

void sd_world_views_walls(sd_world *w)
{
    sd_stage *s = &w->stage;
    for (size_t k = 0; k < w->wall_count && k < s->wall_cap; ++k) {
        const sd_wall *wl = &w->walls[k];
        sd_wall_view *o = &s->walls[k];
        o->g = wl->geom;
        o->material = wl->material;
        o->velocity = wl->velocity;
        o->omega = wl->omega;
    }
}

void sd_world_views_wall_totals(sd_world *w)
{
    const sd_stage *s = &w->stage;
    for (size_t k = 0; k < w->wall_count; ++k) {
        w->walls[k].force = s->wall_force[k];
        w->walls[k].torque = s->wall_torque[k];
    }
}

void sd_world_views_free(sd_world *w)
{
    sd_stage *s = &w->stage;
    sd_free(s->walls);
    sd_free(s->wall_force);
    sd_free(s->wall_torque);
    s->walls = NULL;
    s->wall_force = s->wall_torque = NULL;
    s->wall_cap = 0;
}
