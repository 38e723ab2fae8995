/* shape_support.cu — compile-only proof that the shape support functions
 * (shape/support.h) and the quickhull (geom/hull.h) are single source
 * (DESIGN.md rule 1): they compile as CUDA C++ and can be called from a
 * kernel. Built by nvcc where the toolkit is installed and by the host C++
 * compiler always (tests/CMakeLists.txt). */
#include "geom/hull.h"
#include "shape/support.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#else
#define SD_KERNEL static
#endif

/* One body per thread: world-frame support points, swept and core. */
SD_KERNEL void sd_check_support(const sd_convex *bodies, const sd_vec3 *dirs, sd_vec3 *out, int n)
{
#if defined(__CUDACC__)
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int k = 0;
#endif
    if (k >= n)
        return;
    sd_vec3 a = sd_convex_support(&bodies[k], dirs[k]);
    sd_vec3 b = sd_convex_support_core(&bodies[k], sd_v3_neg(dirs[k]));
    out[k] = sd_v3_add(a, sd_shape_support(bodies[k].shape, bodies[k].verts, b));
}

/* One hull per thread, each in its own (global-memory) workspace. */
SD_KERNEL void sd_check_hull(const sd_vec3 *pts, int npts, sd_hull_workspace *ws, sd_hull *hulls, sd_real *vol, int n)
{
#if defined(__CUDACC__)
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int k = 0;
#endif
    if (k >= n)
        return;
    if (sd_hull_build(pts + (size_t)k * (size_t)npts, (size_t)npts, &ws[k], &hulls[k]) == SD_HULL_OK)
        vol[k] = sd_hull_volume(&hulls[k], pts + (size_t)k * (size_t)npts);
}

#if !defined(__CUDACC__)
void sd_check_use_shape(void);
void sd_check_use_shape(void)
{
    (void)sd_check_support;
    (void)sd_check_hull;
}
#endif
