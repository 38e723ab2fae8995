/* quat.h — unit quaternions for orientation (seed 000 eqs. 25–26).
 *
 * q = (w, x, y, z) maps body-frame vectors to the world frame:
 * v_world = q v_body q*. The rotation matrix of seed 000 eq. 25 is sd_quat_to_mat3.
 */
#ifndef SD_CORE_QUAT_H
#define SD_CORE_QUAT_H

#include "mat3.h"
#include "vec.h"

typedef struct sd_quat {
    sd_real w, x, y, z;
} sd_quat;

SD_HD static SD_INLINE sd_quat sd_quat_make(sd_real w, sd_real x, sd_real y, sd_real z)
{
    sd_quat q;
    q.w = w;
    q.x = x;
    q.y = y;
    q.z = z;
    return q;
}
SD_HD static SD_INLINE sd_quat sd_quat_identity(void) { return sd_quat_make(SD_R(1.0), SD_R(0.0), SD_R(0.0), SD_R(0.0)); }

SD_HD static SD_INLINE sd_quat sd_quat_mul(sd_quat a, sd_quat b)
{
    return sd_quat_make(a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
                        a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
                        a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
                        a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w);
}
SD_HD static SD_INLINE sd_quat sd_quat_conj(sd_quat q) { return sd_quat_make(q.w, -q.x, -q.y, -q.z); }

SD_HD static SD_INLINE sd_quat sd_quat_normalize(sd_quat q)
{
    sd_real n = sd_sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (n <= SD_R(0.0))
        return sd_quat_identity();
    sd_real s = SD_R(1.0) / n;
    return sd_quat_make(q.w * s, q.x * s, q.y * s, q.z * s);
}

/* Renormalises a quaternion whose norm is 1 up to rounding (the product of
 * two unit quaternions): one Newton step of 1/sqrt from 1, s = (3 - |q|^2)/2,
 * is exact to rounding there and needs no square root or division. */
SD_HD static SD_INLINE sd_quat sd_quat_renormalize(sd_quat q)
{
    sd_real n2 = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
    sd_real s = SD_R(1.5) - SD_R(0.5) * n2;
    return sd_quat_make(q.w * s, q.x * s, q.y * s, q.z * s);
}

/* Rotation by angle |axis_angle| about axis_angle/|axis_angle|. */
SD_HD static SD_INLINE sd_quat sd_quat_from_rotvec(sd_vec3 r)
{
    sd_real a2 = sd_v3_norm2(r);
    sd_real h2 = SD_R(0.25) * a2; /* (a/2)^2 */
    sd_real c, s;
    if (h2 < SD_R(1e-4)) {
        /* a/2 < 0.01: the series to h^6 is exact in double precision (next
         * terms below 1e-20) and avoids sin/cos in the per-step update */
        c = SD_R(1.0) - h2 * (SD_R(0.5) - h2 * (SD_R(1.0) / SD_R(24.0) - h2 / SD_R(720.0)));
        s = SD_R(0.5) * (SD_R(1.0) - h2 * (SD_R(1.0) / SD_R(6.0) - h2 * (SD_R(1.0) / SD_R(120.0) - h2 / SD_R(5040.0))));
    } else {
        sd_real a = sd_sqrt(a2), h = SD_R(0.5) * a;
        c = sd_cos(h);
        s = sd_sin(h) / a;
    }
    return sd_quat_make(c, r.x * s, r.y * s, r.z * s);
}

SD_HD static SD_INLINE sd_vec3 sd_quat_rotate(sd_quat q, sd_vec3 v)
{
    /* v + 2 u x (u x v + w v), u = vector part: fewer flops than q v q*. */
    sd_vec3 u = sd_v3(q.x, q.y, q.z);
    sd_vec3 t = sd_v3_add(sd_v3_cross(u, v), sd_v3_scale(v, q.w));
    return sd_v3_madd(v, SD_R(2.0), sd_v3_cross(u, t));
}
SD_HD static SD_INLINE sd_vec3 sd_quat_rotate_inv(sd_quat q, sd_vec3 v) { return sd_quat_rotate(sd_quat_conj(q), v); }

/* Seed 000 eq. 25 (rotation matrix H of a unit quaternion, q0 = w). */
SD_HD static SD_INLINE sd_mat3 sd_quat_to_mat3(sd_quat q)
{
    sd_mat3 m;
    m.m[0][0] = 1 - 2 * (q.y * q.y + q.z * q.z);
    m.m[0][1] = 2 * (q.x * q.y - q.w * q.z);
    m.m[0][2] = 2 * (q.x * q.z + q.w * q.y);
    m.m[1][0] = 2 * (q.x * q.y + q.w * q.z);
    m.m[1][1] = 1 - 2 * (q.x * q.x + q.z * q.z);
    m.m[1][2] = 2 * (q.y * q.z - q.w * q.x);
    m.m[2][0] = 2 * (q.x * q.z - q.w * q.y);
    m.m[2][1] = 2 * (q.y * q.z + q.w * q.x);
    m.m[2][2] = 1 - 2 * (q.x * q.x + q.y * q.y);
    return m;
}

/* Rotation angle (rad) between two unit quaternions, in [0, pi]. */
SD_HD static SD_INLINE sd_real sd_quat_angle_between(sd_quat a, sd_quat b)
{
    sd_real d = sd_fabs(a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z);
    d = sd_min(d, SD_R(1.0));
    /* 2 acos(d) via atan2 for accuracy near d = 1 */
    return SD_R(2.0) * sd_atan2(sd_sqrt(SD_R(1.0) - d * d), d);
}

#endif
