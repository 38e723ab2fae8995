/* integrate.h — per-particle time integration (single source, SD_HD).
 *
 * Velocity Verlet in kick–drift–kick form, which is the leap-frog scheme of
 * seed 004 eq. 9 written with whole-step velocities: the first kick plus the
 * drift give U(t + dt/2) and x(t + dt); the second kick, after the new
 * forces, gives U(t + dt) for output and for the dashpots.
 *
 * Rotation follows seed 000 eqs. 23–26: the torque is taken into the body
 * frame (H^T T), the body-frame Euler equations I w' + w x (I w) = T advance
 * w, and the orientation turns by the exact rotation of angle |w| dt (the
 * closed-form integral of eq. 26 for constant w over the step).
 */
#ifndef SD_DYNAMICS_INTEGRATE_H
#define SD_DYNAMICS_INTEGRATE_H

#include "core/quat.h"

/* Half kick: v += h (F/m + g), w by the Euler equations. inv_mass = 0 marks
 * a body that does not move (gravity is not applied to it either). */
SD_HD static SD_HOT void sd_integrate_kick(sd_vec3 *v, sd_vec3 *w, sd_quat q, sd_vec3 f, sd_vec3 t, sd_real inv_mass,
                                              sd_vec3 inv_inertia, sd_vec3 gravity, sd_real h)
{
    if (inv_mass <= SD_R(0.0))
        return;
    *v = sd_v3_madd(*v, h, sd_v3_madd(gravity, inv_mass, f));
    if (inv_inertia.x == inv_inertia.y && inv_inertia.y == inv_inertia.z) {
        /* isotropic body (spheres): w x (I w) vanishes, no frame change needed */
        *w = sd_v3_madd(*w, h * inv_inertia.x, t);
        return;
    }
    sd_vec3 wb = sd_quat_rotate_inv(q, *w);
    sd_vec3 tb = sd_quat_rotate_inv(q, t);
    sd_vec3 iw = sd_v3(wb.x / inv_inertia.x, wb.y / inv_inertia.y, wb.z / inv_inertia.z);
    sd_vec3 rhs = sd_v3_sub(tb, sd_v3_cross(wb, iw));
    wb = sd_v3_madd(wb, h, sd_v3_mul(inv_inertia, rhs));
    *w = sd_quat_rotate(q, wb);
}

/* Local non-viscous damping (seed 002 §3.2, its ref. [4]: Cundall's
 * velocity-based local damping, as in PFC): a force component f acting on a
 * body moving with velocity component v becomes f - alpha |f| sign(v). It
 * removes a fixed fraction of the power of the unbalanced force, whatever
 * the mass, so a packing comes to rest without a viscous drag that would
 * depend on the velocity scale; sign(0) = 0, so a body at rest is not held. */
SD_HD static SD_INLINE sd_real sd_local_damp(sd_real f, sd_real v, sd_real alpha)
{
    sd_real d = alpha * sd_fabs(f);
    return v > SD_R(0.0) ? f - d : (v < SD_R(0.0) ? f + d : f);
}

SD_HD static SD_INLINE sd_vec3 sd_local_damp3(sd_vec3 f, sd_vec3 v, sd_real alpha)
{
    return sd_v3(sd_local_damp(f.x, v.x, alpha), sd_local_damp(f.y, v.y, alpha), sd_local_damp(f.z, v.z, alpha));
}

/* Half kick with local damping (3D): the unbalanced force is the contact
 * force plus the weight, the unbalanced torque the contact torque; both are
 * damped per world component before the kick above. */
SD_HD static SD_INLINE void sd_integrate_kick_damped(sd_vec3 *v, sd_vec3 *w, sd_quat q, sd_vec3 f, sd_vec3 t,
                                                     sd_real inv_mass, sd_vec3 inv_inertia, sd_vec3 gravity,
                                                     sd_real h, sd_real alpha)
{
    if (inv_mass <= SD_R(0.0))
        return;
    sd_vec3 fu = sd_v3_madd(f, SD_R(1.0) / inv_mass, gravity);
    sd_vec3 fd = sd_local_damp3(fu, *v, alpha);
    sd_vec3 td = sd_local_damp3(t, *w, alpha);
    sd_integrate_kick(v, w, q, fd, td, inv_mass, inv_inertia, sd_v3_zero(), h);
}

/* Half kick of the planar mode (DESIGN.md rule 9): translation in x-y,
 * rotation about z only, with the polar moment 1/inv_inertia_z (every 2D
 * body is isotropic in the plane, so the Euler equations reduce to
 * I w' = T_z). The out-of-plane components are held at exactly zero, so
 * rounding can never lift the state out of the plane. alpha = 0: no damping. */
SD_HD static SD_HOT void sd_integrate_kick2d(sd_vec3 *v, sd_vec3 *w, sd_vec3 f, sd_vec3 t, sd_real inv_mass,
                                             sd_real inv_inertia_z, sd_vec3 gravity, sd_real h, sd_real alpha)
{
    if (inv_mass <= SD_R(0.0))
        return;
    sd_real fx = f.x, fy = f.y, tz = t.z;
    if (alpha > SD_R(0.0)) {
        sd_real m = SD_R(1.0) / inv_mass;
        fx = sd_local_damp(fx + m * gravity.x, v->x, alpha);
        fy = sd_local_damp(fy + m * gravity.y, v->y, alpha);
        tz = sd_local_damp(tz, w->z, alpha);
        *v = sd_v3(v->x + h * inv_mass * fx, v->y + h * inv_mass * fy, SD_R(0.0));
    } else {
        *v = sd_v3(v->x + h * (gravity.x + inv_mass * fx), v->y + h * (gravity.y + inv_mass * fy), SD_R(0.0));
    }
    *w = sd_v3(SD_R(0.0), SD_R(0.0), w->z + h * inv_inertia_z * tz);
}

/* Drift: x += dt v, q turned by w dt (world-frame angular velocity). */
SD_HD static SD_HOT void sd_integrate_drift(sd_vec3 *x, sd_quat *q, sd_vec3 v, sd_vec3 w, sd_real dt)
{
    *x = sd_v3_madd(*x, dt, v);
    /* the product of two unit quaternions is unit up to rounding */
    *q = sd_quat_renormalize(sd_quat_mul(sd_quat_from_rotvec(sd_v3_scale(w, dt)), *q));
}

#endif
