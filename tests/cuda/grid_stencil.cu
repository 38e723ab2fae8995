/* grid_stencil.cu — compile-only proof that the grid solver's per-particle
 * kernel (src/grid/stencil.h, seed 001 §3.2) is single source (DESIGN.md
 * rule 1): it compiles as CUDA C++ with nvcc and as C++ with the host
 * compiler, and can be called one owner particle per thread, as the CUDA
 * backend will. */
#include "grid/stencil.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#else
#define SD_KERNEL static
#endif

/* One owner per thread (the caller launches one colour of slabs at a time,
 * so no two threads touch the same particle): forces, torques, springs. */
SD_KERNEL void sd_check_grid_stencil(sd_grid_view view, sd_grid_acc acc, const uint32_t *owners, const long *cells,
                                     int n)
{
#if defined(__CUDACC__)
    int e = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int e = 0;
#endif
    if (e >= n)
        return;
    sd_grid_owner_forces(&view, &acc, (size_t)owners[e], cells[3 * e], cells[3 * e + 1], cells[3 * e + 2]);
}

#if !defined(__CUDACC__)
/* keep the host compiler from warning about an unused static */
void sd_grid_stencil_keep(void);
void sd_grid_stencil_keep(void) { (void)&sd_check_grid_stencil; }
#endif
