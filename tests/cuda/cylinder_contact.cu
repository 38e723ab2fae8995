/* cylinder_contact.cu — compile-only proof that the closed-form cylinder
 * contact (geom/cylinder_contact.h) is single source (DESIGN.md rule 1):
 * it compiles as CUDA C++ and can be called from a kernel. Built by nvcc
 * where the toolkit is installed and by the host C++ compiler always
 * (tests/CMakeLists.txt). */
#include "geom/cylinder_contact.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#else
#define SD_KERNEL static
#endif

/* One pair per thread: the closed-form penetration of two posed cores. */
SD_KERNEL void sd_check_cylc(const sd_convex *a, const sd_convex *b, sd_cylc_result *out, int n)
{
#if defined(__CUDACC__)
    int k = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int k = 0;
#endif
    if (k >= n)
        return;
    out[k] = sd_cylc_penetration(&a[k], &b[k]);
}

#if !defined(__CUDACC__)
void sd_check_use_cylc(void);
void sd_check_use_cylc(void)
{
    (void)sd_check_cylc;
}
#endif
