/* loops.c — CPU loops of the step pipeline (see loops.h).
 *
 * Every loop writes only its own element, with a static schedule, so the
 * result is the same bits for any number of threads (DESIGN.md rule 4).
 */
#include "backend/cpu/loops.h"

#include "contact/pair.h"
#include "dynamics/integrate.h"

static sd_body sd_body_of(const sd_particles *p, size_t k)
{
    sd_body b;
    b.x = p->x[k];
    b.v = p->v[k];
    b.w = p->w[k];
    b.radius = p->radius[k];
    b.inv_mass = p->inv_mass[k];
    return b;
}

void sd_cpu_kick_drift(sd_world *w)
{
    sd_particles *p = &w->p;
    size_t n = p->n;
    sd_real h = SD_R(0.5) * w->dt, dt = w->dt;
    sd_vec3 g = w->gravity;
SD_PARALLEL_FOR
    for (size_t k = 0; k < n; ++k) {
        sd_integrate_kick(&p->v[k], &p->w[k], p->q[k], p->f[k], p->t[k], p->inv_mass[k], p->inv_inertia[k], g, h);
        if (p->inv_mass[k] > 0)
            sd_integrate_drift(&p->x[k], &p->q[k], p->v[k], p->w[k], dt);
    }
}

void sd_cpu_kick(sd_world *w)
{
    sd_particles *p = &w->p;
    size_t n = p->n;
    sd_real h = SD_R(0.5) * w->dt;
    sd_vec3 g = w->gravity;
SD_PARALLEL_FOR
    for (size_t k = 0; k < n; ++k)
        sd_integrate_kick(&p->v[k], &p->w[k], p->q[k], p->f[k], p->t[k], p->inv_mass[k], p->inv_inertia[k], g, h);
}

void sd_cpu_pair_forces(sd_world *w)
{
    const sd_particles *p = &w->p;
    sd_pair_list *l = &w->pairs;
    size_t n = l->n, nm = w->material_count;
    sd_real dt = w->dt;
SD_PARALLEL_FOR
    for (size_t e = 0; e < n; ++e) {
        uint32_t i = l->i[e], j = l->j[e];
        sd_body a = sd_body_of(p, i), b = sd_body_of(p, j);
        const sd_pair_params *prm = &w->mix[(size_t)p->material[i] * nm + (size_t)p->material[j]];
        sd_pair_result r = sd_pair_spheres(prm, &a, &b, &l->ds[e], dt);
        l->f[e] = r.f;
        l->ti[e] = r.ti;
        l->tj[e] = r.tj;
        l->delta[e] = r.delta;
        l->energy[e] = r.energy;
    }
}

void sd_cpu_wall_forces(sd_world *w)
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
        sd_contact_geom g;
        int touching;
        if (wl->kind == SD_WALL_PLANE) {
            touching = sd_sphere_plane(a.x, a.radius, wl->point, wl->normal, &g);
        } else {
            int face = l->sub[e], axis = face / 2;
            sd_real value = axis == 0 ? ((face & 1) ? wl->hi.x : wl->lo.x)
                                      : (axis == 1 ? ((face & 1) ? wl->hi.y : wl->lo.y)
                                                   : ((face & 1) ? wl->hi.z : wl->lo.z));
            touching = sd_sphere_box_face(a.x, a.radius, axis, value, (face & 1) ? SD_R(-1.0) : SD_R(1.0), wl->lo,
                                          wl->hi, &g);
        }
        const sd_pair_params *prm = &w->mix[(size_t)p->material[i] * nm + (size_t)wl->material];
        sd_pair_result r = sd_pair_sphere_wall(prm, &a, &g, touching, &l->ds[e], dt);
        l->f[e] = r.f;
        l->t[e] = r.ti;
        l->c[e] = touching ? g.point : a.x;
        l->delta[e] = r.delta;
        l->energy[e] = r.energy;
    }
}

void sd_cpu_gather(sd_world *w)
{
    sd_particles *p = &w->p;
    const sd_pair_list *l = &w->pairs;
    const sd_wall_pair_list *wl = &w->wpairs;
    size_t n = p->n;
SD_PARALLEL_FOR
    for (size_t k = 0; k < n; ++k) {
        sd_vec3 f = sd_v3_zero(), t = sd_v3_zero();
        for (uint32_t g = l->gstart[k]; g < l->gstart[k + 1]; ++g) {
            uint32_t e = l->gidx[g] >> 1;
            if (l->gidx[g] & 1u) {
                f = sd_v3_sub(f, l->f[e]);
                t = sd_v3_add(t, l->tj[e]);
            } else {
                f = sd_v3_add(f, l->f[e]);
                t = sd_v3_add(t, l->ti[e]);
            }
        }
        for (uint32_t e = wl->start[k]; e < wl->start[k + 1]; ++e) {
            f = sd_v3_add(f, wl->f[e]);
            t = sd_v3_add(t, wl->t[e]);
        }
        p->f[k] = f;
        p->t[k] = t;
    }
}

void sd_cpu_wall_totals(sd_world *w)
{
    const sd_wall_pair_list *l = &w->wpairs;
    for (size_t k = 0; k < w->wall_count; ++k) {
        w->walls[k].force = sd_v3_zero();
        w->walls[k].torque = sd_v3_zero();
    }
    for (size_t e = 0; e < l->n; ++e) {
        if (l->delta[e] <= 0)
            continue;
        sd_wall *wl = &w->walls[l->wall[e]];
        /* the wall feels the opposite of the particle's contact force at the
         * contact point (rolling resistance torques are left out) */
        sd_vec3 fw = sd_v3_neg(l->f[e]);
        wl->force = sd_v3_add(wl->force, fw);
        wl->torque = sd_v3_add(wl->torque, sd_v3_cross(sd_v3_sub(l->c[e], wl->point), fw));
    }
}
