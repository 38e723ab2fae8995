/* particles.c — the CPU backend's loops over particles: kick and drift,
 * the gather of pair forces per particle (fused with the kicks), the skin
 * test, the finite check and the wall totals. No physics here: the
 * integrator is dynamics/integrate.h (seed 004 eq. 9, seed 000 eqs.
 * 23-26; seed 002's local damping and planar mode).
 *
 * The loop bodies are the items of backend/particle_items.h, which the
 * CUDA kernels call too.
 *
 * Invariant: every loop writes only its own particle, with a static
 * schedule, and each particle sums its pairs in the fixed order of its
 * gather list (DESIGN.md rule 4: no atomics, the same bits for any number
 * of threads). The wall totals are summed serially in pair order.
 */
#include <math.h>

#include "backend/cpu/cpu.h"
#include "backend/cpu/parallel.h"
#include "backend/particle_items.h"

/* The drift passes test the skin of each particle they have just moved
 * (sd_item_skin_used), so that the rebuild stage's question costs no pass
 * of its own over x and x_ref: the same answer, read while the particle is
 * in cache (issue 29). */
void sd_cpu_kick_drift(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    size_t n = v->n_owned;
    sd_real h = SD_R(0.5) * v->dt, dt = v->dt;
    sd_vec3 g = v->gravity;
    int mode = sd_item_kick_mode(v);
    sd_real alpha = v->damping;
    int used = 0;
    SD_CPU_ANY(s->exec, used, k, 0, n, sd_item_kick_drift(mode, alpha, v, k, g, h, dt);
               used |= sd_item_skin_used(v, k));
    s->skin_used = used;
    s->skin_known = 1;
}

void sd_cpu_gather(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    const sd_pair_out *l = &s->pairs;
    const sd_wall_pair_out *wl = &s->wpairs;
    size_t n = v->n_owned;
    SD_CPU_EACH(s->exec, k, 0, n, sd_item_gather(l, wl, k, &v->f[k], &v->t[k]));
}

void sd_cpu_gather_kick_drift(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    const sd_pair_out *l = &s->pairs;
    const sd_wall_pair_out *wl = &s->wpairs;
    size_t n = v->n_owned;
    sd_real h = SD_R(0.5) * v->dt, dt = v->dt;
    sd_vec3 g = v->gravity;
    int mode = sd_item_kick_mode(v);
    sd_real alpha = v->damping;
    int used = 0;
    if (mode == SD_KICK_PLAIN) { /* the common case, with the mode a constant */
        SD_CPU_ANY(s->exec, used, k, 0, n, sd_item_gather_kick_drift(l, wl, SD_KICK_PLAIN, SD_R(0.0), v, k, g, h, dt);
                   used |= sd_item_skin_used(v, k));
    } else {
        SD_CPU_ANY(s->exec, used, k, 0, n, sd_item_gather_kick_drift(l, wl, mode, alpha, v, k, g, h, dt);
                   used |= sd_item_skin_used(v, k));
    }
    s->skin_used = used;
    s->skin_known = 1;
}

void sd_cpu_gather_kick(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    const sd_pair_out *l = &s->pairs;
    const sd_wall_pair_out *wl = &s->wpairs;
    size_t n = v->n_owned;
    sd_real h = SD_R(0.5) * v->dt;
    sd_vec3 g = v->gravity;
    int mode = sd_item_kick_mode(v);
    sd_real alpha = v->damping;
    SD_CPU_EACH(s->exec, k, 0, n, sd_item_gather(l, wl, k, &v->f[k], &v->t[k]); sd_item_kick(mode, alpha, v, k, g, h));
}

/* The skin test (backend/particle_items.h): the last drift pass's answer
 * when it still holds, else a pass of its own. */
int sd_cpu_needs_rebuild(sd_stage *s)
{
    if (s->skin_known)
        return s->skin_used;
    const sd_step_view *v = &s->v;
    size_t n = v->n_owned;
    int need = 0;
    SD_CPU_ANY(s->exec, need, k, 0, n, need |= sd_item_skin_used(v, k));
    return need;
}

int sd_cpu_check_finite(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    size_t n = v->n_owned;
    int bad = 0;
    SD_CPU_ANY(s->exec, bad, k, 0, n, bad |= sd_item_nonfinite(v, k));
    return bad;
}

/* Each ghost takes its owner's state this step (the broad phase made them
 * at the rebuild; the pair items read them as particles). */
void sd_cpu_exchange_ghosts(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    size_t n0 = v->n_owned, n = v->n_total;
    if (n <= n0)
        return;
    SD_CPU_EACH(s->exec, k, n0, n, sd_item_ghost(v, k));
}

sd_real sd_cpu_min_radius(sd_stage *s)
{
    const sd_step_view *v = &s->v;
    sd_real r = INFINITY;
    for (size_t k = 0; k < v->n_owned; ++k)
        r = sd_min(r, v->radius[k]);
    return r;
}

void sd_cpu_wall_totals(sd_stage *s)
{
    const sd_wall_pair_out *l = &s->wpairs;
    const sd_wall_view *walls = s->v.walls;
    for (size_t k = 0; k < s->v.wall_count; ++k) {
        s->wall_force[k] = sd_v3_zero();
        s->wall_torque[k] = sd_v3_zero();
    }
    /* in the order of the gather lists (particle by particle, wall by wall),
     * which does not depend on the kind segments */
    for (size_t g = 0; g < l->n; ++g) {
        size_t e = l->gidx[g];
        if (l->delta[e] <= 0)
            continue;
        size_t k = l->wall[e];
        /* the wall feels the opposite of the particle's contact force at the
         * contact point (rolling resistance torques are left out) */
        sd_vec3 fw = sd_v3_neg(l->f[e]);
        s->wall_force[k] = sd_v3_add(s->wall_force[k], fw);
        s->wall_torque[k] = sd_v3_add(s->wall_torque[k], sd_v3_cross(sd_v3_sub(l->c[e], walls[k].g.point), fw));
    }
}
