/* emulate.h — the CUDA runtime calls and the kernel launch of the CUDA
 * backend, mapped to host code, so that the backend's own sources
 * (device.cu, particles.cu, pairs.cu, walls.cu, grid.cu) compiled as C++ by the host
 * compiler with SHAPEDEM_CUDA_EMULATE run on a machine without a GPU
 * (CI has none): the test-only library shapedem_cuda_emulated and
 * unit.cuda_emulated, which compares its states with the CPU backend's bit
 * for bit.
 *
 * Invariants: only what the backend uses is here. "Device" memory is a
 * separate host allocation, so a missing upload or read back shows as a
 * stale copy exactly as on a GPU; a kernel launch is a sequential loop over
 * the blocks and threads of its grid (the kernels use one thread per item,
 * no shared memory and no __syncthreads, so the order of the loop cannot
 * matter); atomics are plain read-modify-writes (one thread at a time).
 * What emulation cannot catch: a kernel that dereferences a host pointer
 * (it works here and faults on a GPU), races between threads, and the
 * device's own rounding (the reason for --fmad=false and the single-source
 * elementary functions).
 *
 * Test knobs, read at each probe and allocation (environment):
 *   SD_CUDA_EMULATE_DEVICES=N      N devices (default 1; 0: no device); the one the
 *                                  backend sets is recorded (sd_emu_device)
 *   SD_CUDA_EMULATE_DRIVER=11040   the driver's CUDA version (1000 x major + 10 x minor;
 *                                  below the runtime's 13000: too old)
 *   SD_CUDA_EMULATE_MEMORY=BYTES   device memory (allocations beyond it fail)
 */
#ifndef SD_BACKEND_CUDA_EMULATE_H
#define SD_BACKEND_CUDA_EMULATE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define __global__
#define __device__
#define __host__
#define __constant__

typedef enum cudaError {
    cudaSuccess = 0,
    cudaErrorInvalidValue = 1,
    cudaErrorMemoryAllocation = 2,
    cudaErrorInsufficientDriver = 35,
    cudaErrorNoDevice = 100,
    cudaErrorInvalidDevice = 101
} cudaError_t;

enum cudaMemcpyKind { cudaMemcpyHostToDevice = 1, cudaMemcpyDeviceToHost = 2, cudaMemcpyDeviceToDevice = 3 };

typedef struct sd_emu_stream *cudaStream_t;

struct dim3 {
    unsigned x, y, z;
};

struct cudaDeviceProp {
    char name[256];
    size_t totalGlobalMem;
    int major, minor;
    int multiProcessorCount;
};

#define CUDART_VERSION 13000

/* the running thread of the emulated grid (C++17 inline variables: one
 * for the whole program) */
inline dim3 threadIdx, blockIdx, blockDim, gridDim;

static inline long sd_emu_env(const char *name, long fallback)
{
    const char *s = getenv(name);
    return s && *s ? strtol(s, NULL, 10) : fallback;
}

/* bytes allocated, against SD_CUDA_EMULATE_MEMORY (default 64 GiB) */
inline size_t sd_emu_in_use;

static inline size_t sd_emu_memory(void)
{
    long m = sd_emu_env("SD_CUDA_EMULATE_MEMORY", -1);
    return m >= 0 ? (size_t)m : (size_t)64 << 30;
}

static inline const char *cudaGetErrorString(cudaError_t e)
{
    switch (e) {
    case cudaSuccess:
        return "no error";
    case cudaErrorInvalidValue:
        return "invalid argument";
    case cudaErrorMemoryAllocation:
        return "out of memory";
    case cudaErrorInsufficientDriver:
        return "CUDA driver version is insufficient for CUDA runtime version";
    case cudaErrorNoDevice:
        return "no CUDA-capable device is detected";
    case cudaErrorInvalidDevice:
        return "invalid device ordinal";
    }
    return "unknown error";
}

static inline cudaError_t cudaDriverGetVersion(int *v)
{
    *v = (int)sd_emu_env("SD_CUDA_EMULATE_DRIVER", CUDART_VERSION);
    return cudaSuccess;
}

static inline cudaError_t cudaRuntimeGetVersion(int *v)
{
    *v = CUDART_VERSION;
    return cudaSuccess;
}

static inline cudaError_t cudaGetDeviceCount(int *n)
{
    int drv;
    cudaDriverGetVersion(&drv);
    *n = 0;
    if (drv < CUDART_VERSION)
        return cudaErrorInsufficientDriver;
    *n = (int)sd_emu_env("SD_CUDA_EMULATE_DEVICES", 1);
    return *n > 0 ? cudaSuccess : cudaErrorNoDevice;
}

static inline cudaError_t cudaGetDeviceProperties(cudaDeviceProp *p, int dev)
{
    int n = 0;
    if (cudaGetDeviceCount(&n) != cudaSuccess || dev < 0 || dev >= n)
        return cudaErrorInvalidDevice;
    memset(p, 0, sizeof *p);
    snprintf(p->name, sizeof p->name, "emulated on the host");
    p->totalGlobalMem = sd_emu_memory();
    p->major = 9;
    p->minor = 0;
    p->multiProcessorCount = 1;
    return cudaSuccess;
}

/* the device the last cudaSetDevice chose, -1 before any: a test reads it
 * (sd_cuda_emulated_device) to see which device a rank was given */
inline int sd_emu_device = -1;

static inline cudaError_t cudaSetDevice(int dev)
{
    int n = 0;
    if (cudaGetDeviceCount(&n) != cudaSuccess || dev < 0 || dev >= n)
        return cudaErrorInvalidDevice;
    sd_emu_device = dev;
    return cudaSuccess;
}

static inline cudaError_t cudaMemGetInfo(size_t *free_bytes, size_t *total)
{
    *total = sd_emu_memory();
    *free_bytes = *total > sd_emu_in_use ? *total - sd_emu_in_use : 0;
    return cudaSuccess;
}

/* each block carries its size in front, for the memory limit */
static inline cudaError_t cudaMalloc(void **p, size_t size)
{
    *p = NULL;
    if (sd_emu_in_use + size > sd_emu_memory())
        return cudaErrorMemoryAllocation;
    size_t *b = (size_t *)malloc(size + 16);
    if (!b)
        return cudaErrorMemoryAllocation;
    b[0] = size;
    sd_emu_in_use += size;
    *p = (char *)b + 16;
    return cudaSuccess;
}

static inline cudaError_t cudaFree(void *p)
{
    if (p) {
        size_t *b = (size_t *)(void *)((char *)p - 16);
        sd_emu_in_use -= b[0];
        free(b);
    }
    return cudaSuccess;
}

static inline cudaError_t cudaMallocHost(void **p, size_t size)
{
    *p = malloc(size ? size : 1);
    return *p ? cudaSuccess : cudaErrorMemoryAllocation;
}

static inline cudaError_t cudaFreeHost(void *p)
{
    free(p);
    return cudaSuccess;
}

static inline cudaError_t cudaMemcpy(void *dst, const void *src, size_t n, cudaMemcpyKind kind)
{
    (void)kind;
    if (n)
        memcpy(dst, src, n);
    return cudaSuccess;
}

static inline cudaError_t cudaMemcpyAsync(void *dst, const void *src, size_t n, cudaMemcpyKind kind, cudaStream_t s)
{
    (void)s;
    return cudaMemcpy(dst, src, n, kind);
}

static inline cudaError_t cudaMemsetAsync(void *dst, int value, size_t n, cudaStream_t s)
{
    (void)s;
    if (n)
        memset(dst, value, n);
    return cudaSuccess;
}

static inline cudaError_t cudaStreamCreate(cudaStream_t *s)
{
    *s = NULL;
    return cudaSuccess;
}

static inline cudaError_t cudaStreamDestroy(cudaStream_t s)
{
    (void)s;
    return cudaSuccess;
}

static inline cudaError_t cudaStreamSynchronize(cudaStream_t s)
{
    (void)s;
    return cudaSuccess;
}

static inline cudaError_t cudaGetLastError(void) { return cudaSuccess; }

static inline int atomicOr(int *a, int v)
{
    int old = *a;
    *a = old | v;
    return old;
}

static inline unsigned long long atomicAdd(unsigned long long *a, unsigned long long v)
{
    unsigned long long old = *a;
    *a = old + v;
    return old;
}

static inline unsigned long long atomicMin(unsigned long long *a, unsigned long long v)
{
    unsigned long long old = *a;
    *a = v < old ? v : old;
    return old;
}

static inline unsigned long long atomicOr(unsigned long long *a, unsigned long long v)
{
    unsigned long long old = *a;
    *a = old | v;
    return old;
}

static inline unsigned long long atomicMax(unsigned long long *a, unsigned long long v)
{
    unsigned long long old = *a;
    *a = v > old ? v : old;
    return old;
}

static inline unsigned int atomicMin(unsigned int *a, unsigned int v)
{
    unsigned int old = *a;
    *a = v < old ? v : old;
    return old;
}

/* kernel<<<blocks, threads, 0, stream>>>(args...) as loops over the grid */
#define SD_CUDA_LAUNCH(kernel, blocks, threads, stream, ...)                 \
    do {                                                                     \
        (void)(stream);                                                      \
        gridDim.x = (unsigned)(blocks);                                      \
        gridDim.y = gridDim.z = blockDim.y = blockDim.z = 1;                 \
        blockDim.x = (unsigned)(threads);                                    \
        threadIdx.y = threadIdx.z = blockIdx.y = blockIdx.z = 0;             \
        for (blockIdx.x = 0; blockIdx.x < gridDim.x; ++blockIdx.x)           \
            for (threadIdx.x = 0; threadIdx.x < blockDim.x; ++threadIdx.x)   \
                kernel(__VA_ARGS__);                                         \
    } while (0)

#endif
