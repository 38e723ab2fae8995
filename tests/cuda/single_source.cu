/* single_source.cu — compile-only proof of DESIGN.md rule 1: every
 * single-source numeric header compiles as CUDA C++ and its functions can
 * be called from a kernel. CI compiles this with nvcc (no GPU needed) and
 * with the host C++ compiler. Add every new SD_HD header here. */
#include "broad/bins.h"
#include "contact/law.h"
#include "contact/pair.h"
#include "contact/pair_convex.h"
#include "contact/params.h"
#include "core/base.h"
#include "core/mat3.h"
#include "core/quat.h"
#include "core/rng.h"
#include "core/vec.h"
#include "dynamics/integrate.h"
#include "dynamics/walls.h"
#include "geom/convex_contact.h"
#include "geom/epa.h"
#include "geom/gjk.h"
#include "geom/hull.h"
#include "geom/sphere.h"
#include "shape/shape.h"
#include "shape/support.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#else
#define SD_KERNEL static
#endif

/* One pair per thread, as the CUDA backend will run it. */
SD_KERNEL void sd_check_pairs(const sd_pair_params *prm, const sd_body *a, const sd_body *b, sd_vec3 *ds,
                              sd_pair_result *out, int n, sd_real dt)
{
#if defined(__CUDACC__)
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int k = 0;
#endif
    if (k >= n)
        return;
    out[k] = sd_pair_spheres(prm, &a[k], &b[k], &ds[k], dt);
    sd_contact_geom g;
    int touching = sd_sphere_box_face(a[k].x, a[k].radius, 2, SD_R(0.0), SD_R(1.0), sd_v3_zero(), sd_v3_zero(), &g);
    sd_pair_result wr = sd_pair_wall(prm, &a[k], &g, touching, a[k].radius, &ds[k], dt);
    out[k].f = sd_v3_add(out[k].f, wr.f);
    if (sd_sphere_plane(a[k].x, a[k].radius, sd_v3_zero(), sd_v3(0, 0, 1), &g))
        out[k].delta += g.delta;
}

/* One particle per thread: the integrator. */
SD_KERNEL void sd_check_integrate(sd_vec3 *x, sd_vec3 *v, sd_vec3 *w, sd_quat *q, const sd_vec3 *f, const sd_vec3 *t,
                                  int n, sd_real dt)
{
#if defined(__CUDACC__)
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int k = 0;
#endif
    if (k >= n)
        return;
    sd_integrate_kick(&v[k], &w[k], q[k], f[k], t[k], SD_R(1.0), sd_v3(1, 2, 3), sd_v3(0, 0, -9.81), dt / 2);
    sd_integrate_drift(&x[k], &q[k], v[k], w[k], dt);
    sd_rng r = sd_rng_seed((uint64_t)k);
    x[k].x += (sd_real)sd_rng_uniform(&r) * SD_R(0.0);
    sd_mat3 m = sd_quat_to_mat3(q[k]);
    x[k] = sd_v3_add(x[k], sd_v3_scale(sd_mat3_tmulv(sd_mat3_mul(m, sd_mat3_transpose(m)), x[k]), SD_R(0.0)));
}

#if !defined(__CUDACC__)
/* keep the host compiler from warning about unused statics */
void sd_check_use(void);
void sd_check_use(void)
{
    (void)sd_check_pairs;
    (void)sd_check_integrate;
}
#endif
