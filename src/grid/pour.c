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

#include "core/error.h"
#include "grid/grid.h"
#include "world/world.h"

/* 1 when a sphere of radius r at x touches no particle (grid stencil). */
static int sd_pour_free(const sd_grid_state *g, sd_vec3 x, sd_real r)
{
    uint32_t c = sd_grid_cell_of(g, x);
    if (c == SD_GRID_OUTSIDE || g->cell[c] >= 0)
        return 0;
    long nxy = g->nx * g->ny;
    for (int dz = -g->reach; dz <= g->reach; ++dz)
        for (int dy = -g->reach; dy <= g->reach; ++dy)
            for (int dx = -g->reach; dx <= g->reach; ++dx) {
                int32_t j = g->cell[(long)c + dz * nxy + dy * g->nx + dx];
                if (j < 0)
                    continue;
                sd_real rs = r + g->kinds[g->part[j].kind].radius;
                if (sd_v3_norm2(sd_v3_sub(x, g->part[j].x)) < rs * rs)
                    return 0;
            }
    for (size_t e = 0; e < g->nover; ++e) {
        size_t j = g->over[e];
        sd_real rs = r + g->kinds[g->part[j].kind].radius;
        if (sd_v3_norm2(sd_v3_sub(x, g->part[j].x)) < rs * rs)
            return 0;
    }
    return 1;
}

int sd_grid_pour_due(const sd_world *w)
{
    const sd_grid_pour *pr = &w->grid_state->pour;
    return pr->active && pr->poured < pr->def.count && !(w->time + 0.5 * (double)w->dt < pr->next_time);
}

sd_status sd_grid_pour_step(sd_world *w, sd_error *err)
{
    sd_grid_state *g = w->grid_state;
    sd_grid_pour *pr = &g->pour;
    if (!sd_grid_pour_due(w))
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
    if (w->next_id + cap > SD_GRID_MAX_ID)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "pour",
                            "solver grid keys contacts by 30-bit stable ids (at most %u particles ever added)",
                            (unsigned)SD_GRID_MAX_ID);
    if (sd_grid_reserve(g, g->n + cap + 1))
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory pouring %zu particles", cap);
    /* the kind of a poured sphere: mass and inertia as sd_world_add_spheres
     * computes them */
    sd_grid_kind kd;
    memset(&kd, 0, sizeof kd);
    sd_real rho = (sd_real)w->materials[d->material].def.density;
    sd_real mass = rho * SD_R(4.0) / SD_R(3.0) * SD_PI * r * r * r;
    sd_real inertia = SD_R(0.4) * mass * r * r;
    kd.radius = r;
    kd.inv_mass = SD_R(1.0) / mass;
    kd.inv_inertia = sd_v3(SD_R(1.0) / inertia, SD_R(1.0) / inertia, SD_R(1.0) / inertia);
    kd.material = d->material;
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
            if (!sd_pour_free(g, x, r)) {
                pr->skipped++;
                continue;
            }
            if (sd_grid_append(g, x, sd_v3((sd_real)vx, (sd_real)vy, (sd_real)vz), sd_v3_zero(), w->next_id, &kd))
                return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (particle kinds)");
            w->next_id++;
            ++m;
        }
    /* the spots were free (checked above, against the particles before this
     * sheet: the sheet's own spheres are 2 R apart and just touch): each new
     * particle takes its cell */
    for (size_t k = g->n - m; k < g->n; ++k) {
        g->where[k] = sd_grid_cell_of(g, g->part[k].x);
        g->cell[g->where[k]] = (int32_t)k;
        g->home[k] = g->where[k];
    }
    sd_grid_mark_rows(g, g->n);
    pr->poured += m;
    pr->layers++;
    sd_grid_set_parallel(w);
    return SD_OK;
}
