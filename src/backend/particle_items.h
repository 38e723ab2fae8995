/* particle_items.h — one item function per particle stage: the kicks and
 * the drift (dynamics/integrate.h: seed 004 eq. 9, seed 000 eqs. 23-26,
 * seed 002's local damping and planar mode), the gather of a particle's
 * pair forces in its gather-list order, the skin test, the finite test and
 * a ghost's copy of its owner. The CPU loops (backend/cpu/particles.c) and
 * the CUDA kernels (backend/cuda/kernels.cu) call these same functions, so
 * both do the same operations in the same order: the same bits.
 *
 * Invariants: an item writes only particle k; the gather reads only pair
 * forces (never another particle's state), so a particle may kick and
 * drift before the others are gathered; no item allocates, prints or sees
 * sd_world. Single source (SD_HD): compiles as C17 and as CUDA C++.
 */
#ifndef SD_BACKEND_PARTICLE_ITEMS_H
#define SD_BACKEND_PARTICLE_ITEMS_H

#include "backend/view.h"
#include "dynamics/integrate.h"

/* The kick of a world: the plain 3D kick, local damping (seed 002) or the
 * planar mode, the same for every particle (the CPU loops choose it once
 * and run a copy specialised for it). */
enum { SD_KICK_PLAIN, SD_KICK_DAMPED, SD_KICK_PLANAR };

SD_HD static SD_INLINE int sd_item_kick_mode(const sd_step_view *v)
{
    return v->dim2 ? SD_KICK_PLANAR : (v->damping > SD_R(0.0) ? SD_KICK_DAMPED : SD_KICK_PLAIN);
}

/* Half kick (h = dt / 2) of particle k with its current force and torque. */
SD_HD static SD_HOT void sd_item_kick(int mode, sd_real alpha, const sd_step_view *v, size_t k, sd_vec3 g, sd_real h)
{
    if (mode == SD_KICK_PLANAR)
        sd_integrate_kick2d(&v->v[k], &v->w[k], v->f[k], v->t[k], v->inv_mass[k], v->inv_inertia[k].z, g, h, alpha);
    else if (mode == SD_KICK_DAMPED)
        sd_integrate_kick_damped(&v->v[k], &v->w[k], v->q[k], v->f[k], v->t[k], v->inv_mass[k], v->inv_inertia[k],
                                 g, h, alpha);
    else
        sd_integrate_kick(&v->v[k], &v->w[k], v->q[k], v->f[k], v->t[k], v->inv_mass[k], v->inv_inertia[k], g, h);
}

/* Half kick then drift of particle k (a fixed body does not move). */
SD_HD static SD_HOT void sd_item_kick_drift(int mode, sd_real alpha, const sd_step_view *v, size_t k, sd_vec3 g,
                                            sd_real h, sd_real dt)
{
    sd_item_kick(mode, alpha, v, k, g, h);
    if (v->inv_mass[k] > 0)
        sd_integrate_drift(&v->x[k], &v->q[k], v->v[k], v->w[k], dt);
}

/* Sums particle k's pair forces in gather-list order, then its wall pairs
 * in wall order (whatever the kind segments), into fo, to. */
SD_HD static SD_HOT void sd_item_gather(const sd_pair_out *l, const sd_wall_pair_out *wl, size_t k, sd_vec3 *fo,
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
        uint32_t e = wl->gidx[g];
        f = sd_v3_add(f, wl->f[e]);
        t = sd_v3_add(t, wl->t[e]);
    }
    *fo = f;
    *to = t;
}

/* One particle of the fused pass: gather, the kick that ends this step
 * (v(t + dt)), then the kick and drift that start the next. */
SD_HD static SD_HOT void sd_item_gather_kick_drift(const sd_pair_out *l, const sd_wall_pair_out *wl, int mode,
                                                   sd_real alpha, const sd_step_view *v, size_t k, sd_vec3 g,
                                                   sd_real h, sd_real dt)
{
    sd_item_gather(l, wl, k, &v->f[k], &v->t[k]);
    sd_item_kick(mode, alpha, v, k, g, h);
    sd_item_kick_drift(mode, alpha, v, k, g, h, dt);
}

/* The skin test of particle k (DESIGN.md engineering notes): 1 when a
 * surface point may have moved more than |dx| + R |dtheta| (a bound on
 * vertex displacement, algorithms.md section B) beyond half the skin. A
 * world of plain spheres compares squares (a sphere's bounding sphere does
 * not change with rotation). */
SD_HD static SD_INLINE int sd_item_skin_used(const sd_step_view *v, size_t k)
{
    if (!v->has_shapes)
        return sd_v3_norm2(sd_v3_sub(v->x[k], v->x_ref[k])) > sd_sq(SD_R(0.5) * v->skin);
    sd_real d = sd_v3_norm(sd_v3_sub(v->x[k], v->x_ref[k]));
    if (v->shape[k] >= 0)
        d += v->radius[k] * sd_quat_angle_between(v->q[k], v->q_ref[k]);
    return d > SD_R(0.5) * v->skin;
}

/* 1 when particle k's state is not finite: one sum per particle, a NaN or
 * inf in any term makes it non-finite (the squares also catch values past
 * ~1e154, whose energies already overflow), and s - s is 0 exactly for a
 * finite s (isfinite without libm, the same on the device). */
SD_HD static SD_INLINE int sd_item_nonfinite(const sd_step_view *v, size_t k)
{
    sd_real s = sd_v3_norm2(v->x[k]) + sd_v3_norm2(v->v[k]) + sd_v3_norm2(v->w[k]) + v->q[k].w + v->q[k].x +
                v->q[k].y + v->q[k].z;
    return !(s - s == SD_R(0.0));
}

/* Ghost k (n_owned <= k < n_total) takes its owner's state this step: the
 * position shifted by its image offset, the velocities and orientation as
 * they are. */
SD_HD static SD_INLINE void sd_item_ghost(const sd_step_view *v, size_t k)
{
    uint32_t o = v->ghost_owner[k - v->n_owned];
    if (o >= UINT32_MAX - 1)
        return; /* another rank's particle or image (SD_GHOST_REMOTE*): the decomposition's exchange fills it */
    v->x[k] = sd_v3_add(v->x[o], v->ghost_shift[k - v->n_owned]);
    v->v[k] = v->v[o];
    v->w[k] = v->w[o];
    v->q[k] = v->q[o];
}

#endif
