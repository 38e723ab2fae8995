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

/* Drift: x += dt v, q turned by w dt (world-frame angular velocity). */
SD_HD static SD_HOT void sd_integrate_drift(sd_vec3 *x, sd_quat *q, sd_vec3 v, sd_vec3 w, sd_real dt)
{
    *x = sd_v3_madd(*x, dt, v);
    /* the product of two unit quaternions is unit up to rounding */
    *q = sd_quat_renormalize(sd_quat_mul(sd_quat_from_rotvec(sd_v3_scale(w, dt)), *q));
}

#endif
