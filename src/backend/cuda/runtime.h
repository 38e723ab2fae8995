/* runtime.h — what the CUDA backend's sources include for the runtime: the
 * real one under nvcc, the host emulation (emulate.h) when the same
 * sources are compiled as C++ with SHAPEDEM_CUDA_EMULATE; and the launch
 * macro both understand (`<<< >>>` is not C++).
 */
#ifndef SD_BACKEND_CUDA_RUNTIME_H
#define SD_BACKEND_CUDA_RUNTIME_H

#if defined(SHAPEDEM_CUDA_EMULATE)
#include "backend/cuda/emulate.h"
#elif defined(__CUDACC__)
#include <cuda_runtime.h>
#define SD_CUDA_LAUNCH(kernel, blocks, threads, stream, ...) \
    kernel<<<(unsigned)(blocks), (unsigned)(threads), 0, (stream)>>>(__VA_ARGS__)
#else
#error "backend/cuda/ compiles under nvcc, or as C++ with SHAPEDEM_CUDA_EMULATE"
#endif

/* Threads per block of every kernel (one thread per item). */
#define SD_CUDA_BLOCK 128

/* The thread's item: one per thread of a 1D grid. */
#define SD_CUDA_ITEM() ((size_t)blockIdx.x * (size_t)blockDim.x + (size_t)threadIdx.x)

#endif
