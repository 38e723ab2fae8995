/* convex.c — CPU loops of the convex narrow phase: pairs that involve a
 * shape template, and shapes against walls. No physics here: each item
 * calls the single-source functions of contact/pair_convex.h.
 */
#include <string.h>

#include "backend/cpu/loops.h"
#include "backend/cpu/poly.h"

#include "contact/pair_convex.h"

/* The convex view of particle k; plain spheres become point cores swept by
 * their radius, written into *tmp. */
static sd_convex sd_convex_of(const sd_world *w, size_t k, sd_shape *tmp)
{
    const sd_particles *p = &w->p;
    sd_convex c;
    if (p->shape[k] >= 0) {
        c.shape = &w->shapes[p->shape[k]];
    } else {
        memset(tmp, 0, sizeof *tmp);
        tmp->kind = SD_SHAPE_SPHERE;
        tmp->radius = p->radius[k];
        tmp->bound = p->radius[k];
        c.shape = tmp;
    }
    c.verts = w->verts;
    c.planes = w->planes;
    c.dtris = w->dtris;
    c.x = p->x[k];
    c.q = p->q[k];
    return c;
}

/* Radius of the sphere of the same volume: the R* of Hertz for shapes. */
static sd_real sd_equivalent_radius(const sd_world *w, size_t k)
{
    int s = w->p.shape[k];
    return s >= 0 ? w->shape_req[s] : w->p.radius[k];
}


void sd_cpu_convex_forces(sd_world *w)
{
    const sd_particles *p = &w->p;
    sd_pair_list *l = &w->pairs;
    size_t n0 = l->n_sphere, n = l->n, nm = w->material_count;
    sd_real dt = w->dt;
SD_PRAGMA(omp parallel num_threads(w->threads) if (w->parallel))
    {
    /* one overlap workspace per thread, for the volume-law pairs (poly.c) */
    sd_overlap_workspace ws;
SD_PRAGMA(omp for schedule(dynamic, 64))
    for (size_t e = n0; e < n; ++e) {
        if (w->has_volume_law && sd_cpu_pair_is_volume(w, e)) {
            sd_cpu_poly_pair(w, e, &ws);
            continue;
        }
        uint32_t i = l->i[e], j = l->j[e];
        sd_shape si, sj;
        sd_convex ci = sd_convex_of(w, i, &si), cj = sd_convex_of(w, j, &sj);
        sd_body a = sd_body_of(p, i), b = sd_body_of(p, j);
        const sd_pair_params *prm = &w->mix[(size_t)p->material[i] * nm + (size_t)p->material[j]];
        sd_real ra = sd_equivalent_radius(w, i), rb = sd_equivalent_radius(w, j);
        sd_narrow_count ns;
        /* the spring is kept as seen from the lower stable id (pairs.h) */
        int flip = l->flip[e];
        sd_vec3 ds = flip ? sd_v3_neg(l->ds[e]) : l->ds[e];
        sd_pair_result r = sd_pair_convex(prm, &a, &b, &ci, &cj, ra * rb / (ra + rb), &ds, &l->warm[e], dt, &ns);
        l->ds[e] = flip ? sd_v3_neg(ds) : ds;
        l->f[e] = r.f;
        l->t[2 * e] = r.ti;
        l->t[2 * e + 1] = r.tj;
        l->delta[e] = r.delta;
        l->energy[e] = r.energy;
        l->iters[e] = ns.iterations;
        l->supports[e] = ns.supports;
    }
    }
}

/* Adds this step's convex evaluations to the per-kind totals, serially in
 * pair order (integer sums: exact whatever the order anyway). */
void sd_cpu_narrow_totals(sd_world *w)
{
    const sd_particles *p = &w->p;
    const sd_pair_list *l = &w->pairs;
    for (size_t e = l->n_sphere; e < l->n; ++e) {
        if (l->supports[e] == 0)
            continue; /* culled by the bounding spheres */
        int si = p->shape[l->i[e]], sj = p->shape[l->j[e]];
        int a = si >= 0 ? w->shapes[si].kind : SD_SHAPE_SPHERE;
        int b = sj >= 0 ? w->shapes[sj].kind : SD_SHAPE_SPHERE;
        if (a > b) {
            int t = a;
            a = b;
            b = t;
        }
        w->narrow[a][b][0] += 1;
        w->narrow[a][b][1] += l->iters[e];
        w->narrow[a][b][2] += l->supports[e];
    }
}
