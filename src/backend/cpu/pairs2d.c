/* pairs2d.c — CPU loops of the planar mode: pairs that involve a 2D shape
 * template, and every particle against the walls (lines, and the x/y faces
 * of boxes). No physics here: each item calls contact/pair2d.h or the
 * sphere geometry of geom/sphere.h (a circle in the plane z = 0 is a sphere
 * cut through its centre, so the sphere formulas are the circle's).
 *
 * Invariant: every loop writes only its own pair's slots (DESIGN.md rule
 * 4); the statistics are integer sums in pair order.
 */
#include <string.h>

#include "backend/cpu/loops.h"

#include "contact/pair2d.h"

/* The 2D convex view of particle k; plain circles become point cores swept
 * by their radius, written into *tmp. */
static sd_convex2d sd_convex2d_of(const sd_world *w, size_t k, sd_shape2d *tmp)
{
    const sd_particles *p = &w->p;
    sd_convex2d c;
    if (p->shape[k] >= 0) {
        c.shape = &w->shapes2d[p->shape[k]];
    } else {
        memset(tmp, 0, sizeof *tmp);
        tmp->kind = SD_SHAPE2D_CIRCLE;
        tmp->radius = p->radius[k];
        tmp->bound = p->radius[k];
        tmp->eq_radius = p->radius[k];
        c.shape = tmp;
    }
    c.pool = w->pool2d;
    c.x = sd_v2(p->x[k].x, p->x[k].y);
    c.theta = sd_quat_angle_z(p->q[k]);
    return c;
}

void sd_cpu_convex2d_forces(sd_world *w)
{
    const sd_particles *p = &w->p;
    sd_pair_list *l = &w->pairs;
    size_t n0 = l->n_sphere, n = l->n, nm = w->material_count;
    sd_real dt = w->dt;
SD_PARALLEL_FOR_DYNAMIC
    for (size_t e = n0; e < n; ++e) {
        uint32_t i = l->i[e], j = l->j[e];
        sd_shape2d si, sj;
        sd_convex2d ci = sd_convex2d_of(w, i, &si), cj = sd_convex2d_of(w, j, &sj);
        sd_body a = sd_body_of(p, i), b = sd_body_of(p, j);
        const sd_pair_params *prm = &w->mix[(size_t)p->material[i] * nm + (size_t)p->material[j]];
        sd_real ra = ci.shape->eq_radius, rb = cj.shape->eq_radius;
        int flip = l->flip[e];
        sd_vec3 ds = flip ? sd_v3_neg(l->ds[e]) : l->ds[e];
        sd_vec2 warm = sd_v2(l->warm[e].x, l->warm[e].y);
        int supports = 0;
        sd_pair_result r = sd_pair_convex2d(prm, &a, &b, &ci, &cj, ra * rb / (ra + rb), &ds, &warm, dt, &supports);
        l->warm[e] = sd_v3(warm.x, warm.y, SD_R(0.0));
        l->ds[e] = flip ? sd_v3_neg(ds) : ds;
        l->f[e] = r.f;
        l->t[2 * e] = r.ti;
        l->t[2 * e + 1] = r.tj;
        l->delta[e] = r.delta;
        l->energy[e] = r.energy;
        l->iters[e] = r.delta > 0; /* in contact: seed 002 Table 1 separates the two */
        l->supports[e] = supports;
    }
}

void sd_cpu_narrow2d_totals(sd_world *w)
{
    const sd_particles *p = &w->p;
    const sd_pair_list *l = &w->pairs;
    for (size_t e = l->n_sphere; e < l->n; ++e) {
        if (l->supports[e] == 0)
            continue; /* culled by the bounding circles */
        int si = p->shape[l->i[e]], sj = p->shape[l->j[e]];
        int a = si >= 0 ? w->shapes2d[si].kind : SD_SHAPE2D_CIRCLE;
        int b = sj >= 0 ? w->shapes2d[sj].kind : SD_SHAPE2D_CIRCLE;
        if (a > b) {
            int t = a;
            a = b;
            b = t;
        }
        w->narrow2d[a][b][0] += 1;
        w->narrow2d[a][b][1] += l->iters[e];
        w->narrow2d[a][b][2] += l->supports[e];
        w->narrow2d[a][b][3] += l->iters[e] ? l->supports[e] : 0;
    }
}

/* The line of a wall feature in the plane: a plane wall, or an x or y face
 * of a box (inward normal). Returns 0 when x lies beyond the face's ends:
 * a body beside a box face meets it only through the neighbouring face. */
static int sd_wall_line(const sd_wall *wl, int face, sd_vec3 x, sd_vec2 *p0, sd_vec2 *n)
{
    if (wl->kind == SD_WALL_PLANE) {
        *p0 = sd_v2(wl->point.x, wl->point.y);
        *n = sd_v2(wl->normal.x, wl->normal.y);
        return 1;
    }
    int axis = face / 2;
    sd_real sign = (face & 1) ? SD_R(-1.0) : SD_R(1.0);
    if (axis == 0) {
        if (x.y < wl->lo.y || x.y > wl->hi.y)
            return 0;
        *p0 = sd_v2((face & 1) ? wl->hi.x : wl->lo.x, x.y);
        *n = sd_v2(sign, SD_R(0.0));
    } else {
        if (x.x < wl->lo.x || x.x > wl->hi.x)
            return 0;
        *p0 = sd_v2(x.x, (face & 1) ? wl->hi.y : wl->lo.y);
        *n = sd_v2(SD_R(0.0), sign);
    }
    return 1;
}

void sd_cpu_wall_forces2d(sd_world *w)
{
    const sd_particles *p = &w->p;
    sd_wall_pair_list *l = &w->wpairs;
    size_t n = l->n, nm = w->material_count;
    sd_real dt = w->dt;
SD_PARALLEL_FOR
    for (size_t e = 0; e < n; ++e) {
        uint32_t i = l->i[e];
        const sd_wall *wl = &w->walls[l->wall[e]];
        sd_body a = sd_body_of(p, i);
        a.v = sd_v3_sub(a.v, wl->velocity); /* the law sees the velocity relative to a moving wall */
        sd_contact_geom g;
        int touching = 0;
        sd_real r_star = a.radius;
        if (p->shape[i] >= 0) {
            sd_shape2d tmp;
            sd_convex2d c = sd_convex2d_of(w, i, &tmp);
            sd_vec2 p0, nw;
            touching = sd_wall_line(wl, l->sub[e], a.x, &p0, &nw) && sd_convex2d_wall_geom(&c, p0, nw, &g);
            r_star = c.shape->eq_radius;
        } else if (wl->kind == SD_WALL_PLANE) {
            touching = sd_sphere_plane(a.x, a.radius, wl->point, wl->normal, &g);
        } else if (l->sub[e] < 4) { /* z faces do not exist in the plane */
            int face = l->sub[e], axis = face / 2;
            sd_real value = axis == 0 ? ((face & 1) ? wl->hi.x : wl->lo.x) : ((face & 1) ? wl->hi.y : wl->lo.y);
            touching =
                sd_sphere_box_face(a.x, a.radius, axis, value, (face & 1) ? SD_R(-1.0) : SD_R(1.0), wl->lo, wl->hi, &g);
        }
        const sd_pair_params *prm = &w->mix[(size_t)p->material[i] * nm + (size_t)wl->material];
        sd_pair_result r = sd_pair_wall(prm, &a, &g, touching, r_star, &l->ds[e], dt);
        l->f[e] = r.f;
        l->t[e] = r.ti;
        l->c[e] = touching ? g.point : a.x;
        l->delta[e] = r.delta;
        l->energy[e] = r.energy;
    }
}
