/* cuda.h — the CUDA backend as the world sees it: whether a usable device
 * is there, and the stage table (backend/backend.h) that runs the cells
 * solver's step on it.
 *
 * Invariant: one header for three builds. With SHAPEDEM_CUDA the library
 * carries the real backend (device.cu, kernels.cu, table.c); without it,
 * absent.c answers "not compiled with CUDA" and has no table; the
 * test-only emulated build (SHAPEDEM_CUDA_EMULATE, emulate.h) compiles the
 * same .cu sources as C++ for the host, so CI runs the backend's logic
 * without a GPU. Plain C, callable from the world (world/backend.c).
 */
#ifndef SD_BACKEND_CUDA_CUDA_H
#define SD_BACKEND_CUDA_CUDA_H

#include <stddef.h>

#include "backend/backend.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What the probe found. */
typedef enum sd_cuda_probe_result {
    SD_CUDA_USABLE = 0,  /* a device the backend can run on */
    SD_CUDA_NOT_BUILT,   /* the library was built without the CUDA backend */
    SD_CUDA_NO_DEVICE,   /* no driver, or no device */
    SD_CUDA_OLD_DRIVER,  /* the driver is older than the runtime the backend was built with */
    SD_CUDA_ERROR        /* any other failure of the device query */
} sd_cuda_probe_result;

/* Asks for device 0. note gets the device's name when usable, else the
 * reason in words (e.g. "no CUDA device", "driver too old: it supports
 * CUDA 11.4, the backend was built for 13.0"). */
sd_cuda_probe_result sd_cuda_probe(char *note, size_t size);

/* The stage table, or NULL without the backend. */
const sd_backend *sd_cuda_backend(void);

#ifdef __cplusplus
}
#endif

#endif
