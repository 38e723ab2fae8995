/* math.cu — compile-only proof that the engine's own elementary functions
 * (src/core/math.h) are single source: they compile as CUDA C++ with nvcc
 * (device code, where their error-free products use __dmul_rn) and as C++
 * with the host compiler. bench/gpu/math_bits.cu runs them on a device and
 * compares the bits with the CPU's. */
#include "core/math.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#else
#define SD_KERNEL static
#endif

/* One argument per thread: every function, every path (the reductions
 * included), written to out[6 i .. 6 i + 5]. */
SD_KERNEL void sd_check_math(const double *x, const double *y, double *out, int n)
{
#if defined(__CUDACC__)
    int i = (int)(blockIdx.x * blockDim.x + threadIdx.x);
#else
    int i = 0;
#endif
    if (i >= n)
        return;
    out[6 * i] = sd_math_sin(x[i]);
    out[6 * i + 1] = sd_math_cos(x[i]);
    out[6 * i + 2] = sd_math_atan2(y[i], x[i]);
    out[6 * i + 3] = sd_math_cbrt(x[i]);
    out[6 * i + 4] = sd_math_exp(y[i]);
    out[6 * i + 5] = sd_math_log(x[i]);
}

#if !defined(__CUDACC__)
/* keep the host compiler from warning about an unused static */
void sd_math_keep(void);
void sd_math_keep(void) { (void)&sd_check_math; }
#endif
