/* start_overlap.c — the true-shape overlap of two particles given by the
 * scene (see start_overlap.h for what it uses and why).
 */
#include "world/start_overlap.h"

#include <math.h>
#include <string.h>

#include "contact/pair_poly.h"
#include "core/alloc.h"
#include "world/world.h"

/* The law two materials meet with: the last interaction entry for the
 * pair that sets one, else the world's default (as material.c mixes). */
static int sd_start_law(const sd_world *w, int a, int b)
{
    int law = (int)w->def.law;
    for (size_t k = 0; k < w->interaction_count; ++k) {
        const sd_interaction *it = &w->interactions[k];
        if (((it->a == a && it->b == b) || (it->a == b && it->b == a)) && it->def.law >= 0)
            law = it->def.law;
    }
    return law;
}

static sd_convex sd_start_convex(const sd_world *w, const sd_start_particle *p, sd_shape *tmp)
{
    sd_convex c;
    if (p->shape >= 0) {
        c.shape = &w->shapes[p->shape];
    } else { /* a point core swept by the radius, as the step sees a sphere */
        memset(tmp, 0, sizeof *tmp);
        tmp->kind = SD_SHAPE_SPHERE;
        tmp->radius = (sd_real)p->radius;
        tmp->bound = (sd_real)p->radius;
        tmp->min_size = (sd_real)(2.0 * p->radius);
        c.shape = tmp;
    }
    c.verts = w->verts;
    c.planes = w->planes;
    c.dtris = w->dtris;
    c.x = sd_v3((sd_real)p->position.x, (sd_real)p->position.y, (sd_real)p->position.z);
    c.q = sd_quat_normalize(sd_quat_make((sd_real)p->q[0], (sd_real)p->q[1], (sd_real)p->q[2], (sd_real)p->q[3]));
    return c;
}

double sd_start_overlap(const sd_world *w, const sd_start_particle *a, const sd_start_particle *b, double *size)
{
    sd_shape ta, tb;
    sd_convex ca = sd_start_convex(w, a, &ta), cb = sd_start_convex(w, b, &tb);
    double sa = 0.5 * (double)ca.shape->min_size, sb = 0.5 * (double)cb.shape->min_size;
    *size = sa < sb ? sa : sb;
    double dx = a->position.x - b->position.x, dy = a->position.y - b->position.y, dz = a->position.z - b->position.z;
    double dist = sqrt(dx * dx + dy * dy + dz * dz);
    if (a->shape < 0 && b->shape < 0)
        return a->radius + b->radius - dist;
    if (dist >= (double)(ca.shape->bound + cb.shape->bound))
        return (double)(ca.shape->bound + cb.shape->bound) - dist;
    if (sd_shape_is_sharp_polyhedron(ca.shape) && sd_shape_is_sharp_polyhedron(cb.shape) &&
        sd_law_is_volume(sd_start_law(w, a->material, b->material))) {
        sd_overlap_workspace *ws = sd_malloc(sizeof *ws);
        if (ws) {
            sd_overlap ov = sd_overlap_polyhedra(&ca, &cb, sd_v3_zero(), 0, ws);
            sd_free(ws);
            if (ov.status != SD_OVERLAP_OK || !(ov.volume > SD_R(0.0)))
                return 0.0;
            sd_vec3 n = ov.normal; /* how far A reaches into B along the normal, as the law measures it */
            return (double)sd_v3_dot(n, sd_v3_sub(sd_convex_support_core(&ca, n), sd_convex_support_core(&cb, sd_v3_neg(n))));
        }
    }
    sd_convex_contact c = sd_convex_collide(&ca, &cb, NULL);
    return c.touching ? (double)c.delta : (c.status == SD_GJK_DEGENERATE ? 0.0 : (double)c.delta);
}

double sd_start_reach(const sd_world *w, const sd_start_particle *p, sd_v3d dir)
{
    if (p->shape < 0)
        return p->position.x * dir.x + p->position.y * dir.y + p->position.z * dir.z + p->radius;
    sd_shape t;
    sd_convex c = sd_start_convex(w, p, &t);
    sd_vec3 d = sd_v3((sd_real)dir.x, (sd_real)dir.y, (sd_real)dir.z);
    return (double)sd_v3_dot(sd_convex_support(&c, d), d);
}

double sd_start_size(const sd_world *w, const sd_start_particle *p)
{
    return p->shape < 0 ? p->radius : 0.5 * (double)w->shapes[p->shape].min_size;
}
