/* grid_stencil.cu — compile-only proof that the grid solver's per-particle
 * kernel (src/grid/stencil.h, seed 001 §3.2) is single source (DESIGN.md
 * rule 1): it compiles as CUDA C++ with nvcc and as C++ with the host
 * compiler, and can be called one particle per thread, as the CUDA backend
 * will. */
#include "grid/stencil.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#else
#define SD_KERNEL static
#endif

/* One particle per thread: force, torque and springs of particle k. */
SD_KERNEL void sd_check_grid_stencil(sd_grid_view view, uint32_t *tag, sd_vec3 *ds, sd_vec3 *f, sd_vec3 *t, int n)
{
#if defined(__CUDACC__)
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int k = 0;
#endif
    if (k >= n)
        return;
    sd_grid_out o = sd_grid_particle_forces(&view, (size_t)k, tag + (size_t)k * SD_GRID_SLOTS,
                                            ds + (size_t)k * SD_GRID_SLOTS);
    f[k] = o.f;
    t[k] = o.t;
}

#if !defined(__CUDACC__)
/* keep the host compiler from warning about an unused static */
void sd_grid_stencil_keep(void);
void sd_grid_stencil_keep(void) { (void)&sd_check_grid_stencil; }
#endif
