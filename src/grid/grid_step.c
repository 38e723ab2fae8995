/* grid_step.c — the time step of the dense grid-stencil solver (seed 001).
 *
 *   pour a sheet when due ─► kick + drift ─► move particles to their new
 *   cells (conflicts, removals, eq. 11 check) ─► stencil forces ─► kick
 *
 * The same velocity Verlet as the general solver (world/step.c), calling the
 * same CPU loops for the kicks and the drift and the same pair physics in
 * the stencil kernel (stencil.h), so a scene run with solver cells and with
 * solver grid follows the same trajectories (tests/validation/grid_vs_cells.c).
 * Each particle computes its own force: no atomics, the same bits for any
 * thread count.
 */
#include <math.h>
#include <string.h>

#include "backend/cpu/loops.h"
#include "core/error.h"
#include "grid/grid.h"
#include "world/world.h"

static sd_grid_view sd_grid_view_of(const sd_world *w)
{
    const sd_grid_state *g = w->grid_state;
    const sd_particles *p = &w->p;
    sd_grid_view v;
    v.x = p->x;
    v.v = p->v;
    v.w = p->w;
    v.radius = p->radius;
    v.inv_mass = p->inv_mass;
    v.material = p->material;
    v.id = p->id;
    v.cell = g->cell;
    v.where = g->where;
    v.over = g->over;
    v.nover = g->nover;
    v.nx = g->nx;
    v.ny = g->ny;
    v.reach = g->reach;
    v.lo = g->lo;
    v.h = g->h;
    v.rmax = g->rmax;
    v.mix = w->mix;
    v.nm = (int)w->material_count;
    v.walls = g->walls;
    v.nwalls = g->nwalls;
    v.dt = w->dt;
    return v;
}

/* Contact forces of every particle (the stencil kernel, one particle per
 * iteration; each writes only its own force, torque and slots). */
static void sd_grid_forces(sd_world *w)
{
    sd_grid_state *g = w->grid_state;
    sd_particles *p = &w->p;
    sd_grid_view v = sd_grid_view_of(w);
    size_t n = p->n;
    long overflows = 0;
    uint32_t *tag = g->tag;
    sd_vec3 *ds = g->ds;
SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel) reduction(+ : overflows))
    for (size_t k = 0; k < n; ++k) {
        sd_grid_out o = sd_grid_particle_forces(&v, k, tag + k * SD_GRID_SLOTS, ds + k * SD_GRID_SLOTS);
        p->f[k] = o.f;
        p->t[k] = o.t;
        overflows += o.overflows;
    }
    g->info.slot_overflows += overflows;
}

/* Seed 001 eq. 11, first term: dt <= pi/5 sqrt(m/k) for the lightest
 * particle and the stiffest linear pair (the Hertz law has no constant k:
 * the world's own contact-duration check covers it). */
static double sd_grid_dt_limit(const sd_world *w)
{
    const sd_grid_state *g = w->grid_state;
    double mmin = INFINITY, kmax = 0;
    for (size_t k = 0; k < w->p.n; ++k)
        if (w->p.inv_mass[k] > 0)
            mmin = fmin(mmin, 1.0 / (double)w->p.inv_mass[k]);
    if (g->pour.active) {
        double r = g->pour.def.radius;
        mmin = fmin(mmin, w->materials[g->pour.def.material].def.density * 4.0 / 3.0 * SD_PI_D * r * r * r);
    }
    size_t nm = w->material_count;
    for (size_t e = 0; e < nm * nm; ++e)
        if (w->mix[e].law == SD_LAW_LINEAR)
            kmax = fmax(kmax, (double)w->mix[e].kn);
    if (!(kmax > 0) || !isfinite(mmin))
        return INFINITY;
    return SD_PI_D / 5.0 * sqrt(mmin / kmax);
}

sd_status sd_grid_prepare(sd_world *w, sd_error *err)
{
    sd_status st = sd_world_mix_materials(w, err);
    if (st != SD_OK)
        return st;
    st = sd_world_check_params(w, err);
    if (st != SD_OK)
        return st;
    if (!sd_grid_state_get(w))
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    st = sd_grid_setup(w, err);
    if (st != SD_OK)
        return st;
    sd_grid_state *g = w->grid_state;
    double lim = sd_grid_dt_limit(w);
    g->info.dt_contact_limit = lim;
    if ((double)w->dt > lim)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.dt",
                            "time step %g s above the limit pi/5 sqrt(m/k) = %g s of seed 001 eq. 11",
                            (double)w->dt, lim);
    if (g->pour.active) {
        const sd_grid_pour_def *d = &g->pour.def;
        if (!(d->height - d->radius >= (double)g->dom_lo.z && d->height + d->radius <= (double)g->dom_hi.z))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "pour",
                                "pour height %g m must keep the sheet inside the box (z in [%g, %g])", d->height,
                                (double)g->dom_lo.z, (double)g->dom_hi.z);
    }
    st = sd_grid_place_all(w, err);
    if (st != SD_OK)
        return st;
    sd_grid_forces(w);
    w->dirty = 0;
    w->prepared = 1;
    return SD_OK;
}

sd_status sd_grid_step(sd_world *w, long nsteps, sd_error *err)
{
    sd_status st;
    if (!w->prepared && (st = sd_grid_prepare(w, err)) != SD_OK)
        return st;
    sd_grid_state *g = w->grid_state;
    for (long s = 0; s < nsteps; ++s) {
        if (g->pour.active && (st = sd_grid_pour_step(w, err)) != SD_OK)
            return st;
        sd_cpu_kick_drift(w);                 /* v(t + dt/2), x(t + dt) */
        if ((st = sd_grid_rebin(w, err)) != SD_OK) /* cells at t + dt */
            return st;
        sd_grid_forces(w);                    /* F(t + dt) */
        sd_cpu_kick(w);                       /* v(t + dt) */
        w->step++;
        w->time = (double)w->step * (double)w->dt;
    }
    return SD_OK;
}

/* ---- statistics ---------------------------------------------------------------- */

void sd_grid_contact_stats(const sd_world *w, long *contacts, long *wall_contacts, double *energy,
                           double *max_overlap_ratio)
{
    const sd_grid_state *g = w->grid_state;
    const sd_particles *p = &w->p;
    *contacts = 0;
    *wall_contacts = 0;
    *energy = 0;
    *max_overlap_ratio = 0;
    if (!g || !g->ncell)
        return;
    long nxy = g->nx * g->ny;
    for (size_t k = 0; k < p->n; ++k) {
        const uint32_t *tag = g->tag + k * SD_GRID_SLOTS;
        const sd_vec3 *ds = g->ds + k * SD_GRID_SLOTS;
        /* particle pairs, each once (from its lower stable id) */
        long c = (long)g->where[k];
        for (int dz = -g->reach; dz <= g->reach; ++dz)
            for (int dy = -g->reach; dy <= g->reach; ++dy)
                for (int dx = -g->reach; dx <= g->reach; ++dx) {
                    int32_t j = g->cell[c + dz * nxy + dy * g->nx + dx];
                    if (j < 0 || p->id[j] <= p->id[k])
                        continue;
                    sd_real d = sd_v3_norm(sd_v3_sub(p->x[k], p->x[j]));
                    sd_real delta = p->radius[k] + p->radius[j] - d;
                    if (delta <= 0)
                        continue;
                    (*contacts)++;
                    const sd_pair_params *prm =
                        &w->mix[(size_t)p->material[k] * w->material_count + (size_t)p->material[j]];
                    sd_vec3 s = sd_grid_find_spring(tag, ds, (uint32_t)(p->id[j] + 1u));
                    double kn = (double)prm->kn, kt = (double)(prm->kt_ratio * prm->kn);
                    if (prm->law == SD_LAW_LINEAR)
                        *energy += 0.5 * kn * (double)(delta * delta) + 0.5 * kt * (double)sd_v3_norm2(s);
                    double ratio = (double)(delta / sd_min(p->radius[k], p->radius[j]));
                    if (ratio > *max_overlap_ratio)
                        *max_overlap_ratio = ratio;
                }
        /* walls: the slots tagged with a wall are the touching ones */
        for (int s = 0; s < SD_GRID_SLOTS; ++s)
            if (tag[s] & SD_GRID_TAG_WALL)
                (*wall_contacts)++;
    }
}
