/* overlap.cu — compile-only proof that the exact polyhedron overlap volume
 * (geom/overlap.h) is single source (DESIGN.md rule 1): it compiles as CUDA
 * C++ and can be called from a kernel, one pair per thread, each with its
 * own fixed workspace (seed 000 §2.3: one thread per contact pair). Built by
 * nvcc where the toolkit is installed and by the host C++ compiler always
 * (tests/CMakeLists.txt). */
#include "geom/overlap.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#else
#define SD_KERNEL static
#endif

SD_KERNEL void sd_check_overlap(const sd_convex *a, const sd_convex *b, const sd_vec3 *hint, sd_overlap_workspace *ws,
                                sd_overlap *out, int n)
{
#if defined(__CUDACC__)
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int k = 0;
#endif
    if (k >= n)
        return;
    out[k] = sd_overlap_polyhedra(&a[k], &b[k], hint[k], 1, &ws[k]);
}

#if !defined(__CUDACC__)
void sd_check_use_overlap(void);
void sd_check_use_overlap(void)
{
    (void)sd_check_overlap;
}
#endif
