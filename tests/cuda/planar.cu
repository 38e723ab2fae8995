/* planar.cu — compile-only proof that the planar mode's per-pair and
 * per-particle numerics are single source (DESIGN.md rule 1, rule 9): the
 * 2D pair evaluation (contact/pair2d.h: 2D GJK/EPA, the seed 002 law, wall
 * lines), the 2D kick with local damping (dynamics/integrate.h) and the
 * servo law (dynamics/servo.h) compile as CUDA C++ and can be called from a
 * kernel. Built by nvcc where the toolkit is installed and by the host C++
 * compiler always (tests/CMakeLists.txt). */
#include "contact/pair2d.h"
#include "dynamics/integrate.h"
#include "dynamics/servo.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#else
#define SD_KERNEL static
#endif

/* One pair per thread: two 2D bodies and their posed shapes. */
SD_KERNEL void sd_check_pair2d(const sd_pair_params *prm, const sd_body *a, const sd_body *b, const sd_convex2d *ca,
                               const sd_convex2d *cb, sd_vec3 *ds, sd_vec2 *warm, sd_pair_result *out, int *supports,
                               int n)
{
#if defined(__CUDACC__)
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int k = 0;
#endif
    if (k >= n)
        return;
    out[k] =
        sd_pair_convex2d(prm, &a[k], &b[k], &ca[k], &cb[k], SD_R(0.01), &ds[k], &warm[k], SD_R(1e-4), &supports[k]);
    sd_contact_geom g;
    if (sd_convex2d_wall_geom(&ca[k], sd_v2_zero(), sd_v2(SD_R(0.0), SD_R(1.0)), &g))
        out[k].delta += g.delta;
}

/* One particle per thread: the planar half kick with local damping, and a
 * servo velocity. */
SD_KERNEL void sd_check_kick2d(sd_vec3 *v, sd_vec3 *w, const sd_vec3 *f, const sd_vec3 *t, const sd_real *inv_mass,
                               sd_real *speed, int n)
{
#if defined(__CUDACC__)
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int k = 0;
#endif
    if (k >= n)
        return;
    sd_integrate_kick2d(&v[k], &w[k], f[k], t[k], inv_mass[k], inv_mass[k], sd_v3(SD_R(0.0), SD_R(-9.8), SD_R(0.0)),
                        SD_R(5e-5), SD_R(0.7));
    sd_integrate_kick_damped(&v[k], &w[k], sd_quat_identity(), f[k], t[k], inv_mass[k], sd_v3(1, 1, 1), sd_v3_zero(),
                             SD_R(5e-5), SD_R(0.7));
    sd_real integral = SD_R(0.0);
    speed[k] =
        sd_servo_speed(f[k].x, SD_R(1e5), sd_servo_auto_gain(SD_R(1.0), SD_R(1e7), SD_R(1e-4)), SD_R(0.1), &integral);
}

#if !defined(__CUDACC__)
void sd_check_use_planar(void);
void sd_check_use_planar(void)
{
    (void)sd_check_pair2d;
    (void)sd_check_kick2d;
}
#endif
