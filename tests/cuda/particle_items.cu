/* particle_items.cu — compile-only proof that the particle items
 * (backend/particle_items.h: kicks, drift, gather, skin and finite tests,
 * ghosts) are single source (DESIGN.md rule 1), one particle per thread
 * as backend/cuda/particles.cu runs them. CI compiles this with nvcc (no
 * GPU needed) and with the host C++ compiler (cxx.particle_items). */
#include "backend/particle_items.h"

#if defined(__CUDACC__)
#define SD_KERNEL __global__
#define SD_ITEM_INDEX ((size_t)(blockIdx.x * blockDim.x + threadIdx.x))
#else
#define SD_KERNEL static
#define SD_ITEM_INDEX ((size_t)0)
#endif

SD_KERNEL void sd_check_particles(sd_step_view v, sd_pair_out l, sd_wall_pair_out wl, int *flag)
{
    size_t k = SD_ITEM_INDEX;
    if (k >= v.n_owned)
        return;
    int mode = sd_item_kick_mode(&v);
    sd_real h = SD_R(0.5) * v.dt;
    sd_item_gather_kick_drift(&l, &wl, mode, v.damping, &v, k, v.gravity, h, v.dt);
    sd_item_gather(&l, &wl, k, &v.f[k], &v.t[k]);
    sd_item_kick_drift(mode, v.damping, &v, k, v.gravity, h, v.dt);
    if (sd_item_skin_used(&v, k) || sd_item_nonfinite(&v, k))
        *flag = 1;
    if (v.n_total > v.n_owned)
        sd_item_ghost(&v, v.n_owned);
}

#if !defined(__CUDACC__)
/* the host pass: the kernel is used (no unused-function warning) */
void sd_check_particles_host(sd_step_view v, sd_pair_out l, sd_wall_pair_out wl, int *flag);
void sd_check_particles_host(sd_step_view v, sd_pair_out l, sd_wall_pair_out wl, int *flag)
{
    sd_check_particles(v, l, wl, flag);
}
#endif
