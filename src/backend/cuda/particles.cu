/* particles.cu — the CUDA backend's kernels over particles: kick and
 * drift, the gather (fused with the kicks), the skin test, the finite
 * check, the smallest radius and the ghosts. One thread per particle
 * calling the items of backend/particle_items.h, as the CPU loops
 * (backend/cpu/particles.c) do: the same operations in the same order,
 * the same bits (no floating-point atomics: each particle sums its own
 * pairs in its gather list's order).
 *
 * Invariants: a kernel writes only its own particle; the reductions are
 * exact in any order: an integer OR for the flags, a minimum over the bits
 * of positive doubles (their order as unsigned integers is their order as
 * numbers) for the smallest radius.
 */
#include <math.h>
#include <string.h>

#include "backend/cuda/state.h"
#include "backend/particle_items.h"

__global__ void sd_k_kick_drift(sd_step_view v, int mode, sd_real alpha, sd_vec3 g, sd_real h, sd_real dt)
{
    size_t k = SD_CUDA_ITEM();
    if (k < v.n_owned)
        sd_item_kick_drift(mode, alpha, &v, k, g, h, dt);
}

/* what: 0 gather, 1 gather and kick, 2 gather, kick, kick and drift */
__global__ void sd_k_gather(sd_step_view v, sd_pair_out l, sd_wall_pair_out wl, int what, int mode, sd_real alpha,
                            sd_vec3 g, sd_real h, sd_real dt)
{
    size_t k = SD_CUDA_ITEM();
    if (k >= v.n_owned)
        return;
    if (what == 2) {
        sd_item_gather_kick_drift(&l, &wl, mode, alpha, &v, k, g, h, dt);
        return;
    }
    sd_item_gather(&l, &wl, k, &v.f[k], &v.t[k]);
    if (what == 1)
        sd_item_kick(mode, alpha, &v, k, g, h);
}

__global__ void sd_k_skin(sd_step_view v, int *flag)
{
    size_t k = SD_CUDA_ITEM();
    if (k < v.n_owned && sd_item_skin_used(&v, k))
        atomicOr(flag, 1);
}

__global__ void sd_k_finite(sd_step_view v, int *flag)
{
    size_t k = SD_CUDA_ITEM();
    if (k < v.n_owned && sd_item_nonfinite(&v, k))
        atomicOr(flag, 1);
}

__global__ void sd_k_min_radius(sd_step_view v, unsigned long long *bits)
{
    size_t k = SD_CUDA_ITEM();
    if (k >= v.n_owned)
        return;
    sd_real r = v.radius[k];
    unsigned long long b;
    memcpy(&b, &r, sizeof b); /* r > 0: the bits order as the numbers */
    atomicMin(bits, b);
}

__global__ void sd_k_ghosts(sd_step_view v)
{
    size_t k = v.n_owned + SD_CUDA_ITEM();
    if (k < v.n_total)
        sd_item_ghost(&v, k);
}

extern "C" void sd_cuda_kick_drift(sd_stage *s)
{
    if (!sd_cuda_ok(s) || s->v.n_owned == 0)
        return;
    sd_cuda_state *c = s->device;
    const sd_step_view *v = &c->v;
    SD_CUDA_LAUNCH(sd_k_kick_drift, sd_cuda_blocks(v->n_owned), SD_CUDA_BLOCK, c->stream, *v, sd_item_kick_mode(v),
                   v->damping, v->gravity, SD_R(0.5) * v->dt, v->dt);
    (void)sd_cuda_launched(c, "kick and drift");
}

static void sd_cuda_gather_any(sd_stage *s, int what, const char *stage)
{
    if (!sd_cuda_ok(s) || s->v.n_owned == 0)
        return;
    sd_cuda_state *c = s->device;
    const sd_step_view *v = &c->v;
    SD_CUDA_LAUNCH(sd_k_gather, sd_cuda_blocks(v->n_owned), SD_CUDA_BLOCK, c->stream, *v, c->pairs, c->wpairs, what,
                   sd_item_kick_mode(v), v->damping, v->gravity, SD_R(0.5) * v->dt, v->dt);
    (void)sd_cuda_launched(c, stage);
}

extern "C" void sd_cuda_gather(sd_stage *s) { sd_cuda_gather_any(s, 0, "gather"); }
extern "C" void sd_cuda_gather_kick(sd_stage *s) { sd_cuda_gather_any(s, 1, "gather and kick"); }
extern "C" void sd_cuda_gather_kick_drift(sd_stage *s) { sd_cuda_gather_any(s, 2, "gather, kick and drift"); }

/* A flag kernel's answer: 0 on a failure (status reports it). */
static int sd_cuda_flag(sd_stage *s, int finite, const char *stage)
{
    if (!sd_cuda_ok(s) || s->v.n_owned == 0)
        return 0;
    sd_cuda_state *c = s->device;
    int *flag = (int *)c->flag.p, host = 0;
    if (sd_cuda_check(c, cudaMemsetAsync(flag, 0, sizeof(int), c->stream), stage, "the flag"))
        return 0;
    if (finite)
        SD_CUDA_LAUNCH(sd_k_finite, sd_cuda_blocks(c->v.n_owned), SD_CUDA_BLOCK, c->stream, c->v, flag);
    else
        SD_CUDA_LAUNCH(sd_k_skin, sd_cuda_blocks(c->v.n_owned), SD_CUDA_BLOCK, c->stream, c->v, flag);
    (void)sd_cuda_launched(c, stage);
    if (sd_cuda_check(c, cudaMemcpyAsync(&host, flag, sizeof host, cudaMemcpyDeviceToHost, c->stream), stage,
                      "the flag") ||
        sd_cuda_check(c, cudaStreamSynchronize(c->stream), stage, "the flag"))
        return 0;
    return host;
}

extern "C" int sd_cuda_needs_rebuild(sd_stage *s) { return sd_cuda_flag(s, 0, "skin test"); }
extern "C" int sd_cuda_check_finite(sd_stage *s) { return sd_cuda_flag(s, 1, "finite check"); }

extern "C" sd_real sd_cuda_min_radius(sd_stage *s)
{
    sd_real inf = (sd_real)INFINITY, r = inf;
    if (!sd_cuda_ok(s) || s->v.n_owned == 0)
        return inf;
    sd_cuda_state *c = s->device;
    unsigned long long *bits = (unsigned long long *)c->minbits.p, host;
    memcpy(&host, &inf, sizeof host);
    if (sd_cuda_check(c, cudaMemcpyAsync(bits, &host, sizeof host, cudaMemcpyHostToDevice, c->stream), "min radius",
                      "the minimum"))
        return inf;
    SD_CUDA_LAUNCH(sd_k_min_radius, sd_cuda_blocks(c->v.n_owned), SD_CUDA_BLOCK, c->stream, c->v, bits);
    (void)sd_cuda_launched(c, "min radius");
    if (sd_cuda_check(c, cudaMemcpyAsync(&host, bits, sizeof host, cudaMemcpyDeviceToHost, c->stream), "min radius",
                      "the minimum") ||
        sd_cuda_check(c, cudaStreamSynchronize(c->stream), "min radius", "the minimum"))
        return inf;
    memcpy(&r, &host, sizeof r);
    return r;
}

extern "C" void sd_cuda_exchange_ghosts(sd_stage *s)
{
    if (!sd_cuda_ok(s) || s->v.n_total <= s->v.n_owned)
        return;
    sd_cuda_state *c = s->device;
    SD_CUDA_LAUNCH(sd_k_ghosts, sd_cuda_blocks(c->v.n_total - c->v.n_owned), SD_CUDA_BLOCK, c->stream, c->v);
    (void)sd_cuda_launched(c, "ghosts");
}
