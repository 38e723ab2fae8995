/* vec.h — 3-vectors by value.
 *
 * Small math types are passed by value (STYLE.md, Box2D model); every
 * function is SD_HD so contact and integrator code can use them on the GPU.
 */
#ifndef SD_CORE_VEC_H
#define SD_CORE_VEC_H

#include "base.h"

typedef struct sd_vec3 {
    sd_real x, y, z;
} sd_vec3;

SD_HD static SD_INLINE sd_vec3 sd_v3(sd_real x, sd_real y, sd_real z)
{
    sd_vec3 r;
    r.x = x;
    r.y = y;
    r.z = z;
    return r;
}
SD_HD static SD_INLINE sd_vec3 sd_v3_zero(void) { return sd_v3(SD_R(0.0), SD_R(0.0), SD_R(0.0)); }
SD_HD static SD_INLINE sd_vec3 sd_v3_add(sd_vec3 a, sd_vec3 b) { return sd_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
SD_HD static SD_INLINE sd_vec3 sd_v3_sub(sd_vec3 a, sd_vec3 b) { return sd_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
SD_HD static SD_INLINE sd_vec3 sd_v3_neg(sd_vec3 a) { return sd_v3(-a.x, -a.y, -a.z); }
SD_HD static SD_INLINE sd_vec3 sd_v3_scale(sd_vec3 a, sd_real s) { return sd_v3(a.x * s, a.y * s, a.z * s); }
/* a + s*b, the workhorse of the integrator */
SD_HD static SD_INLINE sd_vec3 sd_v3_madd(sd_vec3 a, sd_real s, sd_vec3 b)
{
    return sd_v3(a.x + s * b.x, a.y + s * b.y, a.z + s * b.z);
}
SD_HD static SD_INLINE sd_vec3 sd_v3_mul(sd_vec3 a, sd_vec3 b) { return sd_v3(a.x * b.x, a.y * b.y, a.z * b.z); }
SD_HD static SD_INLINE sd_real sd_v3_dot(sd_vec3 a, sd_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
SD_HD static SD_INLINE sd_vec3 sd_v3_cross(sd_vec3 a, sd_vec3 b)
{
    return sd_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
SD_HD static SD_INLINE sd_real sd_v3_norm2(sd_vec3 a) { return sd_v3_dot(a, a); }
SD_HD static SD_INLINE sd_real sd_v3_norm(sd_vec3 a) { return sd_sqrt(sd_v3_dot(a, a)); }
SD_HD static SD_INLINE sd_vec3 sd_v3_min(sd_vec3 a, sd_vec3 b)
{
    return sd_v3(sd_min(a.x, b.x), sd_min(a.y, b.y), sd_min(a.z, b.z));
}
SD_HD static SD_INLINE sd_vec3 sd_v3_max(sd_vec3 a, sd_vec3 b)
{
    return sd_v3(sd_max(a.x, b.x), sd_max(a.y, b.y), sd_max(a.z, b.z));
}
/* Unit vector, or zero for a zero input (no NaN ever leaves here). */
SD_HD static SD_INLINE sd_vec3 sd_v3_normalize(sd_vec3 a)
{
    sd_real n = sd_v3_norm(a);
    return n > SD_R(0.0) ? sd_v3_scale(a, SD_R(1.0) / n) : sd_v3_zero();
}

#endif
