/* math_bits.cu — the engine's own elementary functions (src/core/math.h)
 * on the GPU give the CPU's bits: a million arguments per function (sin,
 * cos, atan2, cbrt, exp of y 200 in [-600, 600], log of |x|; the
 * kinds unit.math uses: the numerics' angles, the whole double range,
 * neighbours of multiples of pi/2, cube roots of grain volumes), each
 * function evaluated by a kernel and by the host, every result compared
 * bit for bit; prints the count that differ and an FNV-1a digest of the
 * results, exit status 1 when any differ.
 *
 * Built by bench/gpu/run with nvcc --fmad=false (the backend's flags).
 * Compiled without nvcc (as C++ or C: `cc -x c`), it computes the host
 * side only and prints the same digest, which bench/gpu/run compares
 * between the C build, the C++ build and the device. */
#include "core/math.h"
#include "core/rng.h"

#include <stdio.h>
#include <stdlib.h>

#define SD_MB_FUNCS 6

#if defined(__CUDACC__)
__global__ void sd_mb_kernel(const double *x, const double *y, double *out, int n)
{
    int i = (int)(blockIdx.x * blockDim.x + threadIdx.x);
    if (i >= n)
        return;
    out[6 * i] = sd_math_sin(x[i]);
    out[6 * i + 1] = sd_math_cos(x[i]);
    out[6 * i + 2] = sd_math_atan2(y[i], x[i]);
    out[6 * i + 3] = sd_math_cbrt(x[i]);
    out[6 * i + 4] = sd_math_exp(y[i] * 200.0);
    out[6 * i + 5] = sd_math_log(fabs(x[i]));
}
#endif

static double sd_mb_from_bits(uint64_t u) { return sd_math_from_bits(u); }

/* arguments: 1/4 uniform in [-20, 20], 1/4 log-uniform over all doubles,
 * 1/4 next to k pi/2, 1/4 grain volumes (m^3, 1e-27 .. 1e-6) */
static void sd_mb_args(double *x, double *y, int n)
{
    sd_rng r = sd_rng_seed(13);
    for (int i = 0; i < n; i++) {
        uint64_t u = sd_rng_next(&r);
        switch (i & 3) {
        case 0: x[i] = sd_rng_range(&r, -20.0, 20.0); break;
        case 1: x[i] = sd_mb_from_bits(u & ~(UINT64_C(0x7ff) << 52) ? u : u ^ 1); break;
        case 2: x[i] = sd_mb_from_bits(sd_math_bits((double)(u % 1000000) * 0x1.921fb54442d18p+0) + u % 5 - 2); break;
        default: x[i] = sd_rng_range(&r, 1e-27, 1e-6); break;
        }
        if ((sd_math_bits(x[i]) & (UINT64_C(0x7ff) << 52)) == (UINT64_C(0x7ff) << 52))
            x[i] = 1.5; /* no inf or NaN: their bits are compared by unit.math */
        y[i] = sd_rng_range(&r, -3.0, 3.0);
    }
}

static uint64_t sd_mb_digest(const double *v, size_t n)
{
    uint64_t h = UINT64_C(1469598103934665603);
    for (size_t i = 0; i < n; i++) {
        uint64_t u = sd_math_bits(v[i]);
        for (int b = 0; b < 8; b++) {
            h ^= (u >> (8 * b)) & 0xffu;
            h *= UINT64_C(1099511628211);
        }
    }
    return h;
}

int main(int argc, char **argv)
{
    int n = argc > 1 ? atoi(argv[1]) : 1000000;
    double *x = (double *)malloc(sizeof(double) * (size_t)n), *y = (double *)malloc(sizeof(double) * (size_t)n);
    double *host = (double *)malloc(sizeof(double) * SD_MB_FUNCS * (size_t)n);
    if (!x || !y || !host) {
        fprintf(stderr, "math_bits: out of memory\n");
        return 2;
    }
    sd_mb_args(x, y, n);
    for (int i = 0; i < n; i++) {
        host[6 * i] = sd_math_sin(x[i]);
        host[6 * i + 1] = sd_math_cos(x[i]);
        host[6 * i + 2] = sd_math_atan2(y[i], x[i]);
        host[6 * i + 3] = sd_math_cbrt(x[i]);
        host[6 * i + 4] = sd_math_exp(y[i] * 200.0);
        host[6 * i + 5] = sd_math_log(fabs(x[i]));
    }
    printf("math_bits: %d arguments x %d functions, host digest %016llx\n", n, SD_MB_FUNCS,
           (unsigned long long)sd_mb_digest(host, SD_MB_FUNCS * (size_t)n));
    int status = 0;
#if defined(__CUDACC__)
    double *dx, *dy, *dout;
    size_t bytes = sizeof(double) * (size_t)n;
    double *dev = (double *)malloc(SD_MB_FUNCS * bytes);
    if (cudaMalloc(&dx, bytes) != cudaSuccess || cudaMalloc(&dy, bytes) != cudaSuccess ||
        cudaMalloc(&dout, SD_MB_FUNCS * bytes) != cudaSuccess || !dev) {
        fprintf(stderr, "math_bits: no device memory (%s)\n", cudaGetErrorString(cudaGetLastError()));
        return 2;
    }
    cudaMemcpy(dx, x, bytes, cudaMemcpyHostToDevice);
    cudaMemcpy(dy, y, bytes, cudaMemcpyHostToDevice);
    sd_mb_kernel<<<(n + 127) / 128, 128>>>(dx, dy, dout, n);
    cudaError_t err = cudaDeviceSynchronize();
    if (err == cudaSuccess)
        err = cudaMemcpy(dev, dout, SD_MB_FUNCS * bytes, cudaMemcpyDeviceToHost);
    if (err != cudaSuccess) {
        fprintf(stderr, "math_bits: kernel: %s\n", cudaGetErrorString(err));
        return 2;
    }
    static const char *names[SD_MB_FUNCS] = {"sin", "cos", "atan2", "cbrt", "exp", "log"};
    long differ[SD_MB_FUNCS] = {0, 0, 0, 0, 0, 0};
    for (size_t i = 0; i < SD_MB_FUNCS * (size_t)n; i++)
        if (sd_math_bits(host[i]) != sd_math_bits(dev[i])) {
            if (differ[i % SD_MB_FUNCS]++ == 0)
                printf("  first %s difference: x = %a: host %a device %a\n", names[i % SD_MB_FUNCS], x[i / SD_MB_FUNCS],
                       host[i], dev[i]);
        }
    for (int f = 0; f < SD_MB_FUNCS; f++) {
        printf("math_bits: %-5s %ld of %d differ between host and device\n", names[f], differ[f], n);
        status |= differ[f] != 0;
    }
    printf("math_bits: device digest %016llx\n",
           (unsigned long long)sd_mb_digest(dev, SD_MB_FUNCS * (size_t)n));
    cudaFree(dx);
    cudaFree(dy);
    cudaFree(dout);
    free(dev);
#endif
    free(x);
    free(y);
    free(host);
    return status;
}
