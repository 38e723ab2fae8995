/* absent.c — the CUDA backend's interface (backend/cuda/cuda.h) in a
 * library built without it (SHAPEDEM_CUDA=OFF, or AUTO without nvcc): no
 * device is ever usable and there is no stage table, so `backend: auto`
 * takes the CPU and `backend: cuda` is refused with the reason.
 */
#include <stdio.h>

#include "backend/cuda/cuda.h"
#include "core/error.h"

sd_cuda_probe_result sd_cuda_probe(int slot, int *device, char *note, size_t size)
{
    (void)slot;
    *device = 0;
    if (note && size)
        snprintf(note, size, "not compiled with CUDA");
    return SD_CUDA_NOT_BUILT;
}

const sd_backend *sd_cuda_backend(void) { return NULL; }

/* The grid solver's device step: never called (backend cuda is refused
 * before a world exists), but linked. */
static sd_status sd_cuda_grid_absent(sd_error *err)
{
    return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "simulation.backend", "not compiled with CUDA");
}

sd_status sd_cuda_grid_upload(struct sd_grid_state *g, const sd_pair_params *mix, int nm, sd_error *err)
{
    (void)g;
    (void)mix;
    (void)nm;
    return sd_cuda_grid_absent(err);
}

sd_status sd_cuda_grid_read_back(struct sd_grid_state *g, sd_error *err)
{
    (void)g;
    return sd_cuda_grid_absent(err);
}

sd_status sd_cuda_grid_kick(struct sd_grid_state *g, int kicks, int drift, sd_vec3 grav, sd_real dt,
                            sd_error *err)
{
    (void)g;
    (void)kicks;
    (void)drift;
    (void)grav;
    (void)dt;
    return sd_cuda_grid_absent(err);
}

sd_status sd_cuda_grid_rebin(struct sd_grid_state *g, sd_real dt, int *host, sd_error *err)
{
    (void)g;
    (void)dt;
    *host = 1;
    return sd_cuda_grid_absent(err);
}

sd_status sd_cuda_grid_forces(struct sd_grid_state *g, const struct sd_grid_view *v, sd_vec3 *wall_f,
                              sd_vec3 *wall_t, sd_error *err)
{
    (void)g;
    (void)v;
    (void)wall_f;
    (void)wall_t;
    return sd_cuda_grid_absent(err);
}

void sd_cuda_grid_free(struct sd_grid_state *g) { (void)g; }
