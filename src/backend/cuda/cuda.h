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

/* Asks for the device of slot (>= 0): device slot mod the devices present
 * (one rank per GPU: rank r of a node takes device r mod n), its index in
 * *device (0 when none is usable). note gets "device d of n: " and the
 * device's name when usable, else the reason in words (e.g. "no CUDA
 * device", "driver too old: it supports CUDA 11.4, the backend was built
 * for 13.0"). */
sd_cuda_probe_result sd_cuda_probe(int slot, int *device, char *note, size_t size);

/* The emulated build only (SHAPEDEM_CUDA_EMULATE, tests): the device the
 * last cudaSetDevice chose, -1 before any (emulate.h). */
int sd_cuda_emulated_device(void);

/* The stage table, or NULL without the backend. */
const sd_backend *sd_cuda_backend(void);

/* The grid solver's step on the device (grid.cu; grid/grid_step.c calls
 * them when the world's backend is cuda). The device holds a copy of the
 * solver's state (grid/grid.h) in g->device: upload copies all of it
 * there (the call's start, and after any host change: a poured sheet, an
 * opened outlet, removals), read_back all of it to the host arrays. Each
 * returns SD_OK or the first device failure, naming the stage. */
struct sd_grid_state;
struct sd_grid_view;
sd_status sd_cuda_grid_upload(struct sd_grid_state *g, const sd_pair_params *mix, int nm, sd_error *err);
sd_status sd_cuda_grid_read_back(struct sd_grid_state *g, sd_error *err);
/* sd_grid_kick_item on every particle */
sd_status sd_cuda_grid_kick(struct sd_grid_state *g, int kicks, int drift, sd_vec3 grav, sd_real dt,
                            sd_error *err);
/* the rebinning of grid.c's sd_grid_rebin; *host = 1 (device cells not
 * touched) when the host must do it: a particle left the inner grid (its
 * removal renumbers the storage), a NaN, or eq. 11 of [Naderi 2024]
 * violated (the host's rebin reports it) */
sd_status sd_cuda_grid_rebin(struct sd_grid_state *g, sd_real dt, int *host, sd_error *err);
/* the force pass of grid_step.c (v: the host's view, its arrays replaced
 * by the device's); the wall totals into wall_f, wall_t (nwalls each) */
sd_status sd_cuda_grid_forces(struct sd_grid_state *g, const struct sd_grid_view *v, sd_vec3 *wall_f,
                              sd_vec3 *wall_t, sd_error *err);
/* frees g->device (no-op without it) */
void sd_cuda_grid_free(struct sd_grid_state *g);

#ifdef __cplusplus
}
#endif

#endif
