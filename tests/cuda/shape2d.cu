/* shape2d.cu — compile-only proof that the 2D shapes (shape/shape2d.h), 2D
 * GJK (geom/gjk2d.h), 2D EPA and the 2D contact (geom/epa2d.h) are single
 * source (DESIGN.md rule 1): they compile as CUDA C++ and can be called from
 * a kernel. Built by nvcc where the toolkit is installed and by the host C++
 * compiler always (tests/CMakeLists.txt). */
#include "geom/epa2d.h"
#include "geom/gjk2d.h"
#include "shape/shape2d.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#else
#define SD_KERNEL static
#endif

/* One pair per thread: the contact with a warm start and a call counter. */
SD_KERNEL void sd_check_contact2d(const sd_convex2d *a, const sd_convex2d *b, sd_vec2 *warm, sd_contact2d *out,
                                  int *calls, int n)
{
#if defined(__CUDACC__)
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int k = 0;
#endif
    if (k >= n)
        return;
    out[k] = sd_contact2d_convex(&a[k], &b[k], &warm[k], &calls[k]);
}

/* One body per thread: swept and core support points, and eq. 5 at theta. */
SD_KERNEL void sd_check_support2d(const sd_convex2d *bodies, const sd_vec2 *dirs, sd_vec2 *out, sd_real *rho, int n)
{
#if defined(__CUDACC__)
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int k = 0;
#endif
    if (k >= n)
        return;
    sd_vec2 p = sd_convex2d_support(&bodies[k], dirs[k]);
    sd_vec2 q = sd_convex2d_support_core(&bodies[k], sd_v2_neg(dirs[k]));
    out[k] = sd_v2_add(p, sd_v2_rot(q, bodies[k].theta));
    const sd_shape2d *s = bodies[k].shape;
    if (s->kind == SD_SHAPE2D_FOURIER) {
        sd_real p0, d1, d2;
        sd_fourier_eval(bodies[k].pool + s->start, (int)((s->count - 1u) / 2u), dirs[k].x, dirs[k].y, &p0, &d1, &d2);
        rho[k] = p0 + d2;
    }
}

#if !defined(__CUDACC__)
void sd_check_use_shape2d(void);
void sd_check_use_shape2d(void)
{
    (void)sd_check_contact2d;
    (void)sd_check_support2d;
}
#endif
