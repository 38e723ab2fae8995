/* pour.c — layer-by-layer pouring for the grid solver (seed 001 §4.1).
 *
 * Every 1/rate seconds a sheet of particles is laid at the pour height: one
 * particle centred on every two adjacent cells along x and y (centre spacing
 * 2 cells = 2 R), each with a vertical velocity uniform in [-vz, vz] and
 * horizontal ones uniform in [-vh, vh] (seed 001 §4.1: 0.5 and 0.1 m/s).
 *
 * Invariants: a sheet position is used only when no particle is within the
 * two radii (so a new particle never starts in contact and never competes
 * for a cell); a blocked position is skipped and counted. Random numbers are
 * drawn in a fixed order from the world seed, so pours repeat exactly.
 */
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "grid/grid.h"
#include "world/world.h"

/* 1 when a sphere of radius r at x touches no particle (grid stencil). */
static int sd_pour_free(const sd_world *w, const sd_grid_state *g, sd_vec3 x, sd_real r)
{
    uint32_t c = sd_grid_cell_of(g, x);
    if (c == SD_GRID_OUTSIDE || g->cell[c] >= 0)
        return 0;
    const sd_particles *p = &w->p;
    long nxy = g->nx * g->ny;
    for (int dz = -g->reach; dz <= g->reach; ++dz)
        for (int dy = -g->reach; dy <= g->reach; ++dy)
            for (int dx = -g->reach; dx <= g->reach; ++dx) {
                int32_t j = g->cell[(long)c + dz * nxy + dy * g->nx + dx];
                if (j < 0)
                    continue;
                sd_real rs = r + p->radius[j];
                if (sd_v3_norm2(sd_v3_sub(x, p->x[j])) < rs * rs)
                    return 0;
            }
    for (size_t e = 0; e < g->nover; ++e) {
        sd_real rs = r + p->radius[g->over[e]];
        if (sd_v3_norm2(sd_v3_sub(x, p->x[g->over[e]])) < rs * rs)
            return 0;
    }
    return 1;
}

sd_status sd_grid_pour_step(sd_world *w, sd_error *err)
{
    sd_grid_state *g = w->grid_state;
    sd_grid_pour *pr = &g->pour;
    if (!pr->active || pr->poured >= pr->def.count || w->time + 0.5 * (double)w->dt < pr->next_time)
        return SD_OK;
    pr->next_time += 1.0 / pr->def.layers_per_second;
    const sd_grid_pour_def *d = &pr->def;
    sd_real r = (sd_real)d->radius, step = SD_R(2.0) * g->h;
    if (step < SD_R(2.0) * r)
        step = SD_R(2.0) * r;
    /* sheet positions inside the domain box, one radius from its sides */
    long nx = (long)((g->dom_hi.x - g->dom_lo.x - SD_R(2.0) * r) / step) + 1;
    long ny = (long)((g->dom_hi.y - g->dom_lo.y - SD_R(2.0) * r) / step) + 1;
    if (nx < 1 || ny < 1)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "pour", "the box is narrower than one poured particle");
    size_t want = d->count - pr->poured;
    size_t cap = (size_t)nx * (size_t)ny;
    if (cap > want)
        cap = want;
    sd_sphere_def *defs = sd_malloc(cap * sizeof *defs);
    if (!defs)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    size_t m = 0;
    for (long iy = 0; iy < ny && m < cap; ++iy)
        for (long ix = 0; ix < nx && m < cap; ++ix) {
            sd_vec3 x = sd_v3(g->dom_lo.x + r + step * (sd_real)ix, g->dom_lo.y + r + step * (sd_real)iy,
                              (sd_real)d->height);
            /* draw the velocities whether or not the spot is free, so one
             * blocked spot does not change every later particle */
            double vx = sd_rng_range(&pr->rng, -d->vh_range, d->vh_range);
            double vy = sd_rng_range(&pr->rng, -d->vh_range, d->vh_range);
            double vz = sd_rng_range(&pr->rng, -d->vz_range, d->vz_range);
            if (!sd_pour_free(w, g, x, r)) {
                pr->skipped++;
                continue;
            }
            memset(&defs[m], 0, sizeof defs[m]);
            defs[m].position.x = (double)x.x;
            defs[m].position.y = (double)x.y;
            defs[m].position.z = (double)x.z;
            defs[m].velocity.x = vx;
            defs[m].velocity.y = vy;
            defs[m].velocity.z = vz;
            defs[m].radius = d->radius;
            defs[m].material = d->material;
            ++m;
        }
    size_t n0 = w->p.n;
    sd_status st = m ? sd_world_add_spheres(w, m, defs, err) : SD_OK;
    sd_free(defs);
    if (st != SD_OK)
        return st;
    w->prepared = 1; /* the solver places the new particles itself */
    w->dirty = 0;
    if (sd_grid_reserve(g, w->p.n + 1))
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    for (size_t k = n0; k < w->p.n; ++k) {
        g->where[k] = sd_grid_cell_of(g, w->p.x[k]);
        g->cell[g->where[k]] = (int32_t)k; /* free: checked above */
        g->home[k] = g->where[k];
    }
    pr->poured += m;
    pr->layers++;
    w->parallel = w->threads > 1 && w->p.n >= SD_PARALLEL_MIN_PARTICLES;
    return SD_OK;
}
