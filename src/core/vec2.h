/* vec2.h — 2-vectors by value, for the planar mode (DESIGN.md rule 9).
 *
 * The same conventions as vec.h: small types by value, every function SD_HD
 * so support functions, 2D GJK/EPA and contact code compile as C17 and as
 * CUDA C++. Invariant: nothing here returns NaN for finite input
 * (sd_v2_normalize of a zero vector is zero).
 */
#ifndef SD_CORE_VEC2_H
#define SD_CORE_VEC2_H

#include "base.h"

typedef struct sd_vec2 {
    sd_real x, y;
} sd_vec2;

SD_HD static SD_INLINE sd_vec2 sd_v2(sd_real x, sd_real y)
{
    sd_vec2 r;
    r.x = x;
    r.y = y;
    return r;
}
SD_HD static SD_INLINE sd_vec2 sd_v2_zero(void)
{
    return sd_v2(SD_R(0.0), SD_R(0.0));
}
SD_HD static SD_INLINE sd_vec2 sd_v2_add(sd_vec2 a, sd_vec2 b)
{
    return sd_v2(a.x + b.x, a.y + b.y);
}
SD_HD static SD_INLINE sd_vec2 sd_v2_sub(sd_vec2 a, sd_vec2 b)
{
    return sd_v2(a.x - b.x, a.y - b.y);
}
SD_HD static SD_INLINE sd_vec2 sd_v2_neg(sd_vec2 a)
{
    return sd_v2(-a.x, -a.y);
}
SD_HD static SD_INLINE sd_vec2 sd_v2_scale(sd_vec2 a, sd_real s)
{
    return sd_v2(a.x * s, a.y * s);
}
/* a + s*b */
SD_HD static SD_INLINE sd_vec2 sd_v2_madd(sd_vec2 a, sd_real s, sd_vec2 b)
{
    return sd_v2(a.x + s * b.x, a.y + s * b.y);
}
SD_HD static SD_INLINE sd_real sd_v2_dot(sd_vec2 a, sd_vec2 b)
{
    return a.x * b.x + a.y * b.y;
}
/* z component of the 3D cross product (a.x, a.y, 0) × (b.x, b.y, 0) */
SD_HD static SD_INLINE sd_real sd_v2_cross(sd_vec2 a, sd_vec2 b)
{
    return a.x * b.y - a.y * b.x;
}
/* a rotated by +90°: (−y, x); the tangent t(θ) of the unit normal n(θ) */
SD_HD static SD_INLINE sd_vec2 sd_v2_perp(sd_vec2 a)
{
    return sd_v2(-a.y, a.x);
}
SD_HD static SD_INLINE sd_real sd_v2_norm2(sd_vec2 a)
{
    return sd_v2_dot(a, a);
}
SD_HD static SD_INLINE sd_real sd_v2_norm(sd_vec2 a)
{
    return sd_sqrt(sd_v2_dot(a, a));
}
SD_HD static SD_INLINE sd_vec2 sd_v2_normalize(sd_vec2 a)
{
    sd_real n = sd_v2_norm(a);
    return n > SD_R(0.0) ? sd_v2_scale(a, SD_R(1.0) / n) : sd_v2_zero();
}
/* a rotated by the angle whose cosine and sine are c, s (counter-clockwise) */
SD_HD static SD_INLINE sd_vec2 sd_v2_rotcs(sd_vec2 a, sd_real c, sd_real s)
{
    return sd_v2(c * a.x - s * a.y, s * a.x + c * a.y);
}
/* a rotated by theta (rad, counter-clockwise) */
SD_HD static SD_INLINE sd_vec2 sd_v2_rot(sd_vec2 a, sd_real theta)
{
    return sd_v2_rotcs(a, sd_cos(theta), sd_sin(theta));
}
/* a rotated by −theta: the world-to-body map of a direction */
SD_HD static SD_INLINE sd_vec2 sd_v2_rot_inv(sd_vec2 a, sd_real theta)
{
    return sd_v2_rotcs(a, sd_cos(theta), -sd_sin(theta));
}

#endif
