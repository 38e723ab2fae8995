/* loops.c — CPU loops of the step pipeline (see loops.h).
 *
 * Every loop writes only its own element, with a static schedule, so the
 * result is the same bits for any number of threads (DESIGN.md rule 4).
 */
#include "backend/cpu/loops.h"
#include "backend/cpu/poly.h"

#include "contact/pair.h"
#include "contact/pair_convex.h"
#include "dynamics/integrate.h"

/* A plain sphere: central contacts, so no rotational term and no
 * orientation to load in the hot sphere-sphere loop. */
static SD_HOT sd_body sd_sphere_body(const sd_particles *p, size_t k)
{
    sd_body b;
    b.x = p->x[k];
    b.v = p->v[k];
    b.w = p->w[k];
    b.radius = p->radius[k];
    b.inv_mass = p->inv_mass[k];
    b.inv_inertia = sd_v3_zero();
    b.q = sd_quat_identity();
    return b;
}

/* Half kick of particle k with its current force and torque. */
static SD_HOT void sd_kick_one(sd_particles *p, size_t k, sd_vec3 g, sd_real h)
{
    sd_integrate_kick(&p->v[k], &p->w[k], p->q[k], p->f[k], p->t[k], p->inv_mass[k], p->inv_inertia[k], g, h);
}

/* The kick of a world: the plain 3D kick, local damping (seed 002) or the
 * planar mode. It is the same for every particle of a world, so the loops
 * choose it once and run a copy specialised for it (a mode read inside the
 * loop through the world pointer cost the sphere step about 13 %). */
enum { SD_KICK_PLAIN, SD_KICK_DAMPED, SD_KICK_PLANAR };

static int sd_kick_mode_of(const sd_world *w)
{
    return w->dim2 ? SD_KICK_PLANAR : (w->local_damping > SD_R(0.0) ? SD_KICK_DAMPED : SD_KICK_PLAIN);
}

static SD_HOT void sd_kick_any(int mode, sd_real alpha, sd_particles *p, size_t k, sd_vec3 g, sd_real h)
{
    if (mode == SD_KICK_PLANAR)
        sd_integrate_kick2d(&p->v[k], &p->w[k], p->f[k], p->t[k], p->inv_mass[k], p->inv_inertia[k].z, g, h, alpha);
    else if (mode == SD_KICK_DAMPED)
        sd_integrate_kick_damped(&p->v[k], &p->w[k], p->q[k], p->f[k], p->t[k], p->inv_mass[k], p->inv_inertia[k],
                                 g, h, alpha);
    else
        sd_kick_one(p, k, g, h);
}

/* Half kick then drift of particle k (a fixed body does not move). */
static SD_HOT void sd_kick_drift_one(int mode, sd_real alpha, sd_particles *p, size_t k, sd_vec3 g, sd_real h,
                                     sd_real dt)
{
    sd_kick_any(mode, alpha, p, k, g, h);
    if (p->inv_mass[k] > 0)
        sd_integrate_drift(&p->x[k], &p->q[k], p->v[k], p->w[k], dt);
}

void sd_cpu_kick_drift(sd_world *w)
{
    sd_particles *p = &w->p;
    size_t n = p->n;
    sd_real h = SD_R(0.5) * w->dt, dt = w->dt;
    sd_vec3 g = w->gravity;
    int mode = sd_kick_mode_of(w);
    sd_real alpha = w->local_damping;
SD_PARALLEL_FOR
    for (size_t k = 0; k < n; ++k)
        sd_kick_drift_one(mode, alpha, p, k, g, h, dt);
}

void sd_cpu_kick(sd_world *w)
{
    sd_particles *p = &w->p;
    size_t n = p->n;
    sd_real h = SD_R(0.5) * w->dt;
    sd_vec3 g = w->gravity;
    int mode = sd_kick_mode_of(w);
    sd_real alpha = w->local_damping;
SD_PARALLEL_FOR
    for (size_t k = 0; k < n; ++k)
        sd_kick_any(mode, alpha, p, k, g, h);
}

void sd_cpu_pair_forces(sd_world *w)
{
    const sd_particles *p = &w->p;
    sd_pair_list *l = &w->pairs;
    size_t n = l->n_sphere, nm = w->material_count;
    sd_real dt = w->dt;
SD_PARALLEL_FOR
    for (size_t e = 0; e < n; ++e) {
        uint32_t i = l->i[e], j = l->j[e];
        /* a candidate that is apart and was apart has nothing to write: its
         * force, torques and spring are already zero (most of the skin's
         * pairs, and most of the memory traffic of this loop) */
        sd_real rs = p->radius[i] + p->radius[j];
        if (l->delta[e] <= 0 && sd_v3_norm2(sd_v3_sub(p->x[i], p->x[j])) >= rs * rs)
            continue;
        sd_body a = sd_sphere_body(p, i), b = sd_sphere_body(p, j);
        const sd_pair_params *prm = &w->mix[(size_t)p->material[i] * nm + (size_t)p->material[j]];
        /* the spring is stored as seen from the lower stable id: storage
         * order (hence which body is i) may flip at a rebuild, the key not */
        int flip = l->flip[e];
        sd_vec3 ds = flip ? sd_v3_neg(l->ds[e]) : l->ds[e];
        sd_pair_result r = sd_pair_spheres(prm, &a, &b, &ds, dt);
        l->ds[e] = flip ? sd_v3_neg(ds) : ds;
        l->f[e] = r.f;
        l->t[2 * e] = r.ti;
        l->t[2 * e + 1] = r.tj;
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
        if (w->has_volume_law && sd_cpu_wall_pair_is_volume(w, e))
            continue; /* polyhedra under a volume law: poly.c */
        uint32_t i = l->i[e];
        const sd_wall *wl = &w->walls[l->wall[e]];
        sd_body a = sd_body_of(p, i);
        /* a moving wall (servo.c): the law sees only the relative velocity,
         * so the body's velocity is taken relative to the wall */
        a.v = sd_v3_sub(a.v, wl->velocity);
        sd_contact_geom g;
        int touching;
        sd_real r_star = a.radius;
        if (p->shape[i] >= 0) {
            /* a shape: its support point against the wall's plane */
            sd_convex c;
            c.shape = &w->shapes[p->shape[i]];
            c.verts = w->verts;
            c.planes = w->planes;
            c.dtris = w->dtris;
            c.x = a.x;
            c.q = p->q[i];
            sd_vec3 p0, nw;
            int inside = sd_wall_feature_plane(wl, l->sub[e], a.x, &p0, &nw);
            sd_narrow_count ns;
            touching = inside && sd_convex_wall_geom(&c, p0, nw, &g, &ns);
            r_star = w->shape_req[p->shape[i]];
        } else if (wl->kind == SD_WALL_PLANE) {
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
        sd_pair_result r = sd_pair_wall(prm, &a, &g, touching, r_star, &l->ds[e], dt);
        l->f[e] = r.f;
        l->t[e] = r.ti;
        l->c[e] = touching ? g.point : a.x;
        l->delta[e] = r.delta;
        l->energy[e] = r.energy;
    }
}

/* Sums particle k's pair forces in gather-list order, then its wall pairs. */
static SD_HOT void sd_gather_one(const sd_world *w, size_t k, sd_vec3 *fo, sd_vec3 *to)
{
    const sd_pair_list *l = &w->pairs;
    const sd_wall_pair_list *wl = &w->wpairs;
    sd_vec3 f = sd_v3_zero(), t = sd_v3_zero();
    for (uint32_t g = l->gstart[k]; g < l->gstart[k + 1]; ++g) {
        /* branch-free: j receives -F (multiplying by -1 is exact) and its
         * own torque at t[2e + 1] */
        uint32_t idx = l->gidx[g];
        sd_real sign = SD_R(1.0) - SD_R(2.0) * (sd_real)(idx & 1u);
        f = sd_v3_madd(f, sign, l->f[idx >> 1]);
        t = sd_v3_add(t, l->t[idx]);
    }
    for (uint32_t e = wl->start[k]; e < wl->start[k + 1]; ++e) {
        f = sd_v3_add(f, wl->f[e]);
        t = sd_v3_add(t, wl->t[e]);
    }
    *fo = f;
    *to = t;
}

void sd_cpu_gather(sd_world *w)
{
    sd_particles *p = &w->p;
    size_t n = p->n;
SD_PARALLEL_FOR
    for (size_t k = 0; k < n; ++k)
        sd_gather_one(w, k, &p->f[k], &p->t[k]);
}

/* One particle of the fused pass: gather, the kick that ends this step
 * (v(t + dt)), then the kick and drift that start the next (a particle may
 * move before the others are gathered: gathering reads only the pair
 * forces, never another particle's state). */
static SD_HOT void sd_gather_kick_drift_one(const sd_world *w, int mode, sd_real alpha, sd_particles *p, size_t k,
                                            sd_vec3 g, sd_real h, sd_real dt)
{
    sd_gather_one(w, k, &p->f[k], &p->t[k]);
    sd_kick_any(mode, alpha, p, k, g, h);
    sd_kick_drift_one(mode, alpha, p, k, g, h, dt);
}

void sd_cpu_gather_kick_drift(sd_world *w)
{
    sd_particles *p = &w->p;
    size_t n = p->n;
    sd_real h = SD_R(0.5) * w->dt, dt = w->dt;
    sd_vec3 g = w->gravity;
    int mode = sd_kick_mode_of(w);
    sd_real alpha = w->local_damping;
    if (mode == SD_KICK_PLAIN) { /* the common case, with the mode a constant */
SD_PARALLEL_FOR
        for (size_t k = 0; k < n; ++k)
            sd_gather_kick_drift_one(w, SD_KICK_PLAIN, SD_R(0.0), p, k, g, h, dt);
    } else {
SD_PARALLEL_FOR
        for (size_t k = 0; k < n; ++k)
            sd_gather_kick_drift_one(w, mode, alpha, p, k, g, h, dt);
    }
}

void sd_cpu_gather_kick(sd_world *w)
{
    sd_particles *p = &w->p;
    size_t n = p->n;
    sd_real h = SD_R(0.5) * w->dt;
    sd_vec3 g = w->gravity;
    int mode = sd_kick_mode_of(w);
    sd_real alpha = w->local_damping;
SD_PARALLEL_FOR
    for (size_t k = 0; k < n; ++k) {
        sd_gather_one(w, k, &p->f[k], &p->t[k]);
        sd_kick_any(mode, alpha, p, k, g, h);
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
