/* stats.c — run statistics: energies, contact counts, overlaps.
 *
 * Sums run serially in storage order so a run's statistics are the same
 * bits whatever the thread count.
 */
#include <math.h>
#include <string.h>

#include "grid/grid.h"
#include "world/world.h"

/* The size an overlap is measured against: a sphere's radius, half the
 * smallest outer dimension of a shape. */
static double sd_half_size(const sd_world *w, size_t k)
{
    int s = w->p.shape[k];
    if (s >= 0 && w->dim2) /* the planar mode's templates (shape/shape2d.h) */
        return 0.5 * (double)w->shapes2d[s].min_size;
    return s >= 0 ? 0.5 * (double)w->shapes[s].min_size : (double)w->p.radius[k];
}

void sd_world_stats(const sd_world *w, sd_stats *out)
{
    memset(out, 0, sizeof *out);
    const sd_particles *p = &w->p;
    out->time = w->time;
    out->step = w->step;
    double ekt = 0, ekr = 0, epg = 0, vmax2 = 0;
    for (size_t k = 0; k < p->n; ++k) {
        if (!(p->inv_mass[k] > 0))
            continue;
        double m = 1.0 / (double)p->inv_mass[k];
        double v2 = (double)sd_v3_norm2(p->v[k]);
        ekt += 0.5 * m * v2;
        /* rotational energy in the body frame: sum I_a w_a^2 / 2 */
        sd_vec3 wb = sd_quat_rotate_inv(p->q[k], p->w[k]);
        sd_vec3 ii = p->inv_inertia[k];
        ekr += 0.5 * ((double)(wb.x * wb.x / ii.x) + (double)(wb.y * wb.y / ii.y) + (double)(wb.z * wb.z / ii.z));
        epg -= m * (double)sd_v3_dot(w->gravity, p->x[k]);
        if (v2 > vmax2)
            vmax2 = v2;
    }
    sd_grid_particle_stats(w, &ekt, &ekr, &epg, &vmax2); /* solver grid: its own state (src/grid) */
    double epe = 0, ovl = 0;
    long contacts = 0, wcontacts = 0;
    const sd_pair_list *l = &w->pairs;
    for (size_t e = 0; e < l->n; ++e) {
        if (l->delta[e] <= 0)
            continue;
        contacts++;
        epe += (double)l->energy[e];
        double rmin = fmin(sd_half_size(w, l->i[e]), sd_half_size(w, l->j[e]));
        if ((double)l->delta[e] / rmin > ovl)
            ovl = (double)l->delta[e] / rmin;
    }
    const sd_wall_pair_list *wl = &w->wpairs;
    for (size_t e = 0; e < wl->n; ++e) {
        if (wl->delta[e] <= 0)
            continue;
        wcontacts++;
        epe += (double)wl->energy[e];
        double r = sd_half_size(w, wl->i[e]);
        if ((double)wl->delta[e] / r > ovl)
            ovl = (double)wl->delta[e] / r;
    }
    if (w->def.solver == SD_SOLVER_GRID) /* no pair lists: a stencil pass (src/grid) */
        sd_grid_contact_stats(w, &contacts, &wcontacts, &epe, &ovl);
    out->kinetic_translational = ekt;
    out->kinetic_rotational = ekr;
    out->potential_gravity = epg;
    out->potential_elastic = epe;
    out->contacts = contacts;
    out->wall_contacts = wcontacts;
    out->max_overlap_ratio = ovl;
    out->max_speed = sqrt(vmax2);
    out->rebuilds = w->rebuilds;
    out->pairs = l->n;
}
