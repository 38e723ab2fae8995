/* walls.cu — the CUDA backend's kernels over particle-wall pairs: one
 * kernel per wall-pair kind (contact/kinds.h), one thread per pair calling
 * its item (backend/items.h), as backend/cpu/walls.c; and the wall totals.
 * No physics here. The mesh kinds are in walls_mesh.cu (large kernels that
 * compile in parallel with these).
 *
 * Invariants: an item writes only its own wall pair's slots. The wall
 * totals keep the CPU's summation order exactly (sd_cpu_wall_totals: the
 * gather list from its first entry to its last, particle by particle, wall
 * by wall): one thread per wall walks the whole list in that order and
 * adds the pairs of its wall, so the totals (and the servo walls that read
 * them) have the CPU's bits; a serial walk per wall, cheap next to the
 * pairs for the few walls of a scene (a mesh is one wall).
 */
#include <stdio.h>

#include "backend/cuda/state.h"
#include "backend/items.h"

/* One kernel per plane and box wall-pair kind but the composite runs (a template on the
 * kind: each instance holds only its own item, so a cheap kind does not
 * carry the registers of the dearest), one item per pair. */
template <int K> __global__ void sd_k_wall_kind(sd_step_view v, sd_wall_pair_out o, size_t e0, size_t e1)
{
    size_t e = e0 + SD_CUDA_ITEM();
    if (e >= e1)
        return;
    if (K == SD_WALL_PAIR_SPHERE)
        sd_item_wall_sphere(&v, &o, e);
    else if (K == SD_WALL_PAIR_CONVEX)
        sd_item_wall_convex(&v, &o, e);
    else if (K == SD_WALL_PAIR_POLY_VOLUME)
        sd_item_wall_poly_volume(&v, &o, e);
    else if (K == SD_WALL_PAIR_CONVEX2D)
        sd_item_wall_convex2d(&v, &o, e);
}

/* one run of a composite's elements against one feature (seed 004 §2.6),
 * evaluated by the thread of its first pair */
__global__ void sd_k_wall_elements(sd_step_view v, sd_wall_pair_out o, size_t e0, size_t e1)
{
    size_t e = e0 + SD_CUDA_ITEM();
    if (e >= e1 || !sd_item_wall_elements_starts(&o, e0, e))
        return;
    size_t end = e + 1;
    while (end < e1 && !sd_item_wall_elements_starts(&o, e0, end))
        ++end;
    (void)sd_item_wall_elements(&v, &o, e, end);
}

/* The wall totals of wall k (thread k), in the CPU's order. */
__global__ void sd_k_wall_totals(sd_step_view v, sd_wall_pair_out l, sd_vec3 *force, sd_vec3 *torque)
{
    size_t k = SD_CUDA_ITEM();
    if (k >= v.wall_count)
        return;
    sd_vec3 f = sd_v3_zero(), t = sd_v3_zero();
    sd_vec3 point = v.walls[k].g.point;
    for (size_t g = 0; g < l.n_gidx; ++g) {
        size_t e = l.gidx[g];
        if (l.delta[e] <= 0 || l.wall[e] != k)
            continue;
        /* the wall feels the opposite of the particle's contact force at the
         * contact point (rolling resistance torques are left out) */
        sd_vec3 fw = sd_v3_neg(l.f[e]);
        f = sd_v3_add(f, fw);
        t = sd_v3_add(t, sd_v3_cross(sd_v3_sub(l.c[e], point), fw));
    }
    force[k] = f;
    torque[k] = t;
}

extern "C" void sd_cuda_wall_forces(sd_stage *s)
{
    if (!sd_cuda_ok(s))
        return;
    sd_cuda_state *c = s->device;
    const sd_wall_pair_out *o = &c->wpairs;
    for (int k = 0; k < SD_WALL_PAIR_KIND_COUNT; ++k) {
        size_t e0 = o->kind_start[k], e1 = o->kind_start[k + 1];
        if (e1 <= e0)
            continue;
        unsigned nb = sd_cuda_blocks(e1 - e0);
        switch (k) {
#define SD_X_KIND(K)                                                                                 \
    case K:                                                                                          \
        SD_CUDA_LAUNCH(sd_k_wall_kind<K>, nb, SD_CUDA_BLOCK, c->stream, c->v, c->wpairs, e0, e1); \
        break;
            SD_X_KIND(SD_WALL_PAIR_SPHERE)
            SD_X_KIND(SD_WALL_PAIR_CONVEX)
            SD_X_KIND(SD_WALL_PAIR_POLY_VOLUME)
            SD_X_KIND(SD_WALL_PAIR_CONVEX2D)
#undef SD_X_KIND
        case SD_WALL_PAIR_ELEMENTS:
            SD_CUDA_LAUNCH(sd_k_wall_elements, nb, SD_CUDA_BLOCK, c->stream, c->v, c->wpairs, e0, e1);
            break;
        default:
            if (sd_cuda_mesh_wall_kind(c, k, e0, e1)) /* walls_mesh.cu */
                break;
            /* a kind without a kernel: the CPU's loops and these switches disagree */
            c->status = SD_ERR_INTERNAL;
            snprintf(c->message, sizeof c->message, "CUDA backend, wall forces: no kernel for wall-pair kind %d", k);
            return;
        }
        if (sd_cuda_launched(c, "wall forces"))
            return;
    }
}

/* On the device, then the few totals back to the host's s->wall_force and
 * s->wall_torque, which the world's walls (servo control, queries) read.
 * A serial walk of the wall pairs per wall: when no wall moves nothing
 * reads the totals before the state comes back, so read_back sums them
 * then (sd_cuda_wall_totals_now), from the same pairs of the last force
 * evaluation in the same order: the same bits, once per call rather than
 * every step. */
extern "C" void sd_cuda_wall_totals(sd_stage *s)
{
    if (!sd_cuda_ok(s) || s->v.wall_count == 0)
        return;
    if (!s->device->v.walls_moving) {
        s->device->totals_pending = 1;
        return;
    }
    sd_cuda_wall_totals_now(s);
}

void sd_cuda_wall_totals_now(sd_stage *s)
{
    if (!sd_cuda_ok(s) || s->v.wall_count == 0)
        return;
    sd_cuda_state *c = s->device;
    c->totals_pending = 0;
    size_t nw = c->v.wall_count;
    sd_vec3 *f = (sd_vec3 *)c->wall_force.p, *t = (sd_vec3 *)c->wall_torque.p;
    SD_CUDA_LAUNCH(sd_k_wall_totals, sd_cuda_blocks(nw), SD_CUDA_BLOCK, c->stream, c->v, c->wpairs, f, t);
    if (sd_cuda_launched(c, "wall totals") ||
        sd_cuda_check(c, cudaMemcpyAsync(s->wall_force, f, nw * sizeof *f, cudaMemcpyDeviceToHost, c->stream),
                      "wall totals", "the copy back") ||
        sd_cuda_check(c, cudaMemcpyAsync(s->wall_torque, t, nw * sizeof *t, cudaMemcpyDeviceToHost, c->stream),
                      "wall totals", "the copy back"))
        return;
    (void)sd_cuda_check(c, cudaStreamSynchronize(c->stream), "wall totals", "the copy back");
}
