/* mat3.h — 3x3 matrices by value (inertia tensors, rotations). */
#ifndef SD_CORE_MAT3_H
#define SD_CORE_MAT3_H

#include "vec.h"

typedef struct sd_mat3 {
    sd_real m[3][3];
} sd_mat3;

SD_HD static SD_INLINE sd_mat3 sd_mat3_diag(sd_vec3 d)
{
    sd_mat3 a;
    a.m[0][0] = d.x; a.m[0][1] = 0;   a.m[0][2] = 0;
    a.m[1][0] = 0;   a.m[1][1] = d.y; a.m[1][2] = 0;
    a.m[2][0] = 0;   a.m[2][1] = 0;   a.m[2][2] = d.z;
    return a;
}
SD_HD static SD_INLINE sd_vec3 sd_mat3_mulv(sd_mat3 a, sd_vec3 v)
{
    return sd_v3(a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z,
                 a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z,
                 a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z);
}
SD_HD static SD_INLINE sd_vec3 sd_mat3_tmulv(sd_mat3 a, sd_vec3 v)
{
    return sd_v3(a.m[0][0] * v.x + a.m[1][0] * v.y + a.m[2][0] * v.z,
                 a.m[0][1] * v.x + a.m[1][1] * v.y + a.m[2][1] * v.z,
                 a.m[0][2] * v.x + a.m[1][2] * v.y + a.m[2][2] * v.z);
}
SD_HD static SD_INLINE sd_mat3 sd_mat3_mul(sd_mat3 a, sd_mat3 b)
{
    sd_mat3 c;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            c.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
    return c;
}
SD_HD static SD_INLINE sd_mat3 sd_mat3_transpose(sd_mat3 a)
{
    sd_mat3 t;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            t.m[i][j] = a.m[j][i];
    return t;
}

#endif
