/* poly.c — CPU loops of the volume laws: polyhedron pairs and polyhedron
 * walls whose pair of materials uses SD_LAW_VOLUME or SD_LAW_VOLUME_LINEAR.
 * No physics here: each item calls contact/pair_poly.h (single source).
 *
 * Invariants: every item writes only its own slot (force, torques, spring,
 * hint), so the result is the same bits for any thread count (DESIGN.md
 * rule 4). The overlap workspace is one per thread, on that thread's stack
 * (geom/overlap.h sizes it; a few KB to tens of KB, never one per pair).
 */
#include "backend/cpu/loops.h"

#include "backend/cpu/poly.h"
#include "contact/pair_poly.h"

int sd_cpu_pair_is_volume(const sd_world *w, size_t e)
{
    const sd_particles *p = &w->p;
    const sd_pair_list *l = &w->pairs;
    uint32_t i = l->i[e], j = l->j[e];
    return sd_law_is_volume(w->mix[(size_t)p->material[i] * w->material_count + (size_t)p->material[j]].law);
}

int sd_cpu_wall_pair_is_volume(const sd_world *w, size_t e)
{
    const sd_particles *p = &w->p;
    const sd_wall_pair_list *l = &w->wpairs;
    uint32_t i = l->i[e];
    if (p->shape[i] < 0)
        return 0;
    size_t m = (size_t)p->material[i] * w->material_count + (size_t)w->walls[l->wall[e]].material;
    return sd_law_is_volume(w->mix[m].law);
}

static sd_convex sd_poly_convex(const sd_world *w, size_t k)
{
    const sd_particles *p = &w->p;
    sd_convex c;
    c.shape = &w->shapes[p->shape[k]];
    c.verts = w->verts;
    c.planes = w->planes;
    c.dtris = w->dtris;
    c.x = p->x[k];
    c.q = p->q[k];
    return c;
}

void sd_cpu_poly_pair(sd_world *w, size_t e, sd_overlap_workspace *ws)
{
    const sd_particles *p = &w->p;
    sd_pair_list *l = &w->pairs;
    uint32_t i = l->i[e], j = l->j[e];
    sd_narrow_count ns = {0, 0};
    int si = p->shape[i], sj = p->shape[j];
    sd_vec3 ds = l->flip[e] ? sd_v3_neg(l->ds[e]) : l->ds[e];
    sd_pair_result r;
    if (si < 0 || sj < 0 || !sd_shape_is_sharp_polyhedron(&w->shapes[si]) ||
        !sd_shape_is_sharp_polyhedron(&w->shapes[sj])) {
        /* refused at prepare time (world/material.c); never a force */
        r = sd_pair_none(&ds);
    } else {
        sd_convex ci = sd_poly_convex(w, i), cj = sd_poly_convex(w, j);
        sd_body a = sd_body_of(p, i), b = sd_body_of(p, j);
        const sd_pair_params *prm = &w->mix[(size_t)p->material[i] * w->material_count + (size_t)p->material[j]];
        r = sd_pair_poly(prm, &a, &b, &ci, &cj, w->shape_req[si], w->shape_req[sj], &ds, &l->x0[e], &l->x0_ok[e], ws,
                         w->dt, &ns);
    }
    l->ds[e] = l->flip[e] ? sd_v3_neg(ds) : ds;
    l->f[e] = r.f;
    l->t[2 * e] = r.ti;
    l->t[2 * e + 1] = r.tj;
    l->delta[e] = r.delta;
    l->energy[e] = r.energy;
    l->iters[e] = ns.iterations;
    l->supports[e] = ns.supports;
}

void sd_cpu_poly_wall_forces(sd_world *w)
{
    const sd_particles *p = &w->p;
    sd_wall_pair_list *l = &w->wpairs;
    size_t n = l->n, nm = w->material_count;
    sd_real dt = w->dt;
SD_PARALLEL_FOR_DYNAMIC
    for (size_t e = 0; e < n; ++e) {
        if (!sd_cpu_wall_pair_is_volume(w, e))
            continue; /* loops.c's wall loop did it */
        uint32_t i = l->i[e];
        const sd_wall *wl = &w->walls[l->wall[e]];
        sd_body a = sd_body_of(p, i);
        a.v = sd_v3_sub(a.v, wl->velocity); /* the law sees the relative velocity */
        const sd_pair_params *prm = &w->mix[(size_t)p->material[i] * nm + (size_t)wl->material];
        sd_vec3 p0, nw, point = a.x;
        sd_pair_result r;
        int s = p->shape[i];
        if (!sd_shape_is_sharp_polyhedron(&w->shapes[s]) || !sd_wall_feature_plane(wl, l->sub[e], a.x, &p0, &nw)) {
            r = sd_pair_none(&l->ds[e]);
        } else {
            sd_convex c = sd_poly_convex(w, i);
            r = sd_pair_poly_wall(prm, &a, &c, p0, nw, w->shape_req[s], &l->ds[e], dt, &point);
        }
        l->f[e] = r.f;
        l->t[e] = r.ti;
        l->c[e] = point;
        l->delta[e] = r.delta;
        l->energy[e] = r.energy;
    }
}
