/* particles.c — the CPU backend's loops over particles: kick and drift,
 * the gather of pair forces per particle (fused with the kicks), the skin
 * test, the finite check and the wall totals. No physics here: the
 * integrator is dynamics/integrate.h (seed 004 eq. 9, seed 000 eqs.
 * 23-26; seed 002's local damping and planar mode).
 *
 * Invariant: every loop writes only its own particle, with a static
 * schedule, and each particle sums its pairs in the fixed order of its
 * gather list (DESIGN.md rule 4: no atomics, the same bits for any number
 * of threads). The wall totals are summed serially in pair order.
 */
#include <math.h>

#include "backend/cpu/cpu.h"
#include "backend/cpu/parallel.h"
#include "dynamics/integrate.h"

/* Half kick of particle k with its current force and torque. */
static SD_HOT void sd_kick_one(const sd_step_view *v, size_t k, sd_vec3 g, sd_real h)
{
    sd_integrate_kick(&v->v[k], &v->w[k], v->q[k], v->f[k], v->t[k], v->inv_mass[k], v->inv_inertia[k], g, h);
}

/* The kick of a world: the plain 3D kick, local damping (seed 002) or the
 * planar mode. It is the same for every particle, so the loops choose it
 * once and run a copy specialised for it (a mode read inside the loop cost
 * the sphere step about 13 %). */
enum { SD_KICK_PLAIN, SD_KICK_DAMPED, SD_KICK_PLANAR };

static int sd_kick_mode_of(const sd_step_view *v)
{
    return v->dim2 ? SD_KICK_PLANAR : (v->damping > SD_R(0.0) ? SD_KICK_DAMPED : SD_KICK_PLAIN);
}

static SD_HOT void sd_kick_any(int mode, sd_real alpha, const sd_step_view *v, size_t k, sd_vec3 g, sd_real h)
{
    if (mode == SD_KICK_PLANAR)
        sd_integrate_kick2d(&v->v[k], &v->w[k], v->f[k], v->t[k], v->inv_mass[k], v->inv_inertia[k].z, g, h, alpha);
    else if (mode == SD_KICK_DAMPED)
        sd_integrate_kick_damped(&v->v[k], &v->w[k], v->q[k], v->f[k], v->t[k], v->inv_mass[k], v->inv_inertia[k],
                                 g, h, alpha);
    else
        sd_kick_one(v, k, g, h);
}

/* Half kick then drift of particle k (a fixed body does not move). */
static SD_HOT void sd_kick_drift_one(int mode, sd_real alpha, const sd_step_view *v, size_t k, sd_vec3 g, sd_real h,
                                     sd_real dt)
{
    sd_kick_any(mode, alpha, v, k, g, h);
    if (v->inv_mass[k] > 0)
        sd_integrate_drift(&v->x[k], &v->q[k], v->v[k], v->w[k], dt);
}

void sd_cpu_kick_drift(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    size_t n = v->n_owned;
    sd_real h = SD_R(0.5) * v->dt, dt = v->dt;
    sd_vec3 g = v->gravity;
    int mode = sd_kick_mode_of(v);
    sd_real alpha = v->damping;
SD_CPU_FOR(s->exec)
    for (size_t k = 0; k < n; ++k)
        sd_kick_drift_one(mode, alpha, v, k, g, h, dt);
}

/* Sums particle k's pair forces in gather-list order, then its wall pairs. */
static SD_HOT void sd_gather_one(const sd_pair_out *l, const sd_wall_pair_out *wl, size_t k, sd_vec3 *fo,
                                 sd_vec3 *to)
{
    sd_vec3 f = sd_v3_zero(), t = sd_v3_zero();
    for (uint32_t g = l->gstart[k]; g < l->gstart[k + 1]; ++g) {
        /* branch-free: j receives -F (multiplying by -1 is exact) and its
         * own torque at t[2e + 1] */
        uint32_t idx = l->gidx[g];
        sd_real sign = SD_R(1.0) - SD_R(2.0) * (sd_real)(idx & 1u);
        f = sd_v3_madd(f, sign, l->f[idx >> 1]);
        t = sd_v3_add(t, l->t[idx]);
    }
    for (uint32_t g = wl->gstart[k]; g < wl->gstart[k + 1]; ++g) {
        uint32_t e = wl->gidx[g]; /* wall order, whatever the kind segments */
        f = sd_v3_add(f, wl->f[e]);
        t = sd_v3_add(t, wl->t[e]);
    }
    *fo = f;
    *to = t;
}

void sd_cpu_gather(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    const sd_pair_out *l = &s->pairs;
    const sd_wall_pair_out *wl = &s->wpairs;
    size_t n = v->n_owned;
SD_CPU_FOR(s->exec)
    for (size_t k = 0; k < n; ++k)
        sd_gather_one(l, wl, k, &v->f[k], &v->t[k]);
}

/* One particle of the fused pass: gather, the kick that ends this step
 * (v(t + dt)), then the kick and drift that start the next (a particle may
 * move before the others are gathered: gathering reads only the pair
 * forces, never another particle's state). */
static SD_HOT void sd_gather_kick_drift_one(const sd_pair_out *l, const sd_wall_pair_out *wl, int mode, sd_real alpha,
                                            const sd_step_view *v, size_t k, sd_vec3 g, sd_real h, sd_real dt)
{
    sd_gather_one(l, wl, k, &v->f[k], &v->t[k]);
    sd_kick_any(mode, alpha, v, k, g, h);
    sd_kick_drift_one(mode, alpha, v, k, g, h, dt);
}

void sd_cpu_gather_kick_drift(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    const sd_pair_out *l = &s->pairs;
    const sd_wall_pair_out *wl = &s->wpairs;
    size_t n = v->n_owned;
    sd_real h = SD_R(0.5) * v->dt, dt = v->dt;
    sd_vec3 g = v->gravity;
    int mode = sd_kick_mode_of(v);
    sd_real alpha = v->damping;
    if (mode == SD_KICK_PLAIN) { /* the common case, with the mode a constant */
SD_CPU_FOR(s->exec)
        for (size_t k = 0; k < n; ++k)
            sd_gather_kick_drift_one(l, wl, SD_KICK_PLAIN, SD_R(0.0), v, k, g, h, dt);
    } else {
SD_CPU_FOR(s->exec)
        for (size_t k = 0; k < n; ++k)
            sd_gather_kick_drift_one(l, wl, mode, alpha, v, k, g, h, dt);
    }
}

void sd_cpu_gather_kick(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    const sd_pair_out *l = &s->pairs;
    const sd_wall_pair_out *wl = &s->wpairs;
    size_t n = v->n_owned;
    sd_real h = SD_R(0.5) * v->dt;
    sd_vec3 g = v->gravity;
    int mode = sd_kick_mode_of(v);
    sd_real alpha = v->damping;
SD_CPU_FOR(s->exec)
    for (size_t k = 0; k < n; ++k) {
        sd_gather_one(l, wl, k, &v->f[k], &v->t[k]);
        sd_kick_any(mode, alpha, v, k, g, h);
    }
}

/* The skin test (DESIGN.md engineering notes): no surface point of a body
 * moved more than |dx| + R |dtheta| (a bound on vertex displacement,
 * algorithms.md section B) beyond half the skin. */
int sd_cpu_needs_rebuild(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    size_t n = v->n_owned;
    sd_real lim2 = sd_sq(SD_R(0.5) * v->skin);
    int need = 0;
    if (!v->has_shapes) {
        /* a sphere's bounding sphere does not change with rotation */
SD_CPU_FOR_REDUCE_OR(s->exec, need)
        for (size_t k = 0; k < n; ++k)
            need |= sd_v3_norm2(sd_v3_sub(v->x[k], v->x_ref[k])) > lim2;
        return need;
    }
    sd_real lim = SD_R(0.5) * v->skin;
SD_CPU_FOR_REDUCE_OR(s->exec, need)
    for (size_t k = 0; k < n; ++k) {
        sd_real d = sd_v3_norm(sd_v3_sub(v->x[k], v->x_ref[k]));
        if (v->shape[k] >= 0)
            d += v->radius[k] * sd_quat_angle_between(v->q[k], v->q_ref[k]);
        need |= d > lim;
    }
    return need;
}

/* One sum per particle: a NaN or inf in any term makes the sum non-finite
 * (the squares also catch values past ~1e154, whose energies already
 * overflow); the spin and orientation are included since a NaN spin
 * reaches x only through contacts. */
int sd_cpu_check_finite(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    size_t n = v->n_owned;
    int bad = 0;
SD_CPU_FOR_REDUCE_OR(s->exec, bad)
    for (size_t k = 0; k < n; ++k)
        bad |= !isfinite(sd_v3_norm2(v->x[k]) + sd_v3_norm2(v->v[k]) + sd_v3_norm2(v->w[k]) + v->q[k].w +
                         v->q[k].x + v->q[k].y + v->q[k].z);
    return bad;
}

/* Each ghost takes its owner's state this step: the position shifted by its
 * image offset, the velocities and orientation as they are (the broad
 * phase made them at the rebuild; the pair items read them as particles). */
void sd_cpu_exchange_ghosts(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    size_t n0 = v->n_owned, n = v->n_total;
    if (n <= n0)
        return;
SD_CPU_FOR(s->exec)
    for (size_t k = n0; k < n; ++k) {
        uint32_t o = v->ghost_owner[k - n0];
        v->x[k] = sd_v3_add(v->x[o], v->ghost_shift[k - n0]);
        v->v[k] = v->v[o];
        v->w[k] = v->w[o];
        v->q[k] = v->q[o];
    }
}

sd_real sd_cpu_min_radius(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    sd_real r = INFINITY;
    for (size_t k = 0; k < v->n_owned; ++k)
        r = sd_min(r, v->radius[k]);
    return r;
}

void sd_cpu_wall_totals(sd_stage *s)
{
    const sd_wall_pair_out *l = &s->wpairs;
    const sd_wall_view *walls = s->v.walls;
    for (size_t k = 0; k < s->v.wall_count; ++k) {
        s->wall_force[k] = sd_v3_zero();
        s->wall_torque[k] = sd_v3_zero();
    }
    /* in the order of the gather lists (particle by particle, wall by wall),
     * which does not depend on the kind segments */
    for (size_t g = 0; g < l->n; ++g) {
        size_t e = l->gidx[g];
        if (l->delta[e] <= 0)
            continue;
        size_t k = l->wall[e];
        /* the wall feels the opposite of the particle's contact force at the
         * contact point (rolling resistance torques are left out) */
        sd_vec3 fw = sd_v3_neg(l->f[e]);
        s->wall_force[k] = sd_v3_add(s->wall_force[k], fw);
        s->wall_torque[k] = sd_v3_add(s->wall_torque[k], sd_v3_cross(sd_v3_sub(l->c[e], walls[k].g.point), fw));
    }
}
