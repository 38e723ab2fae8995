/* stats.c — run statistics: energies, contact counts, overlaps.
 *
 * Sums run serially in storage order so a run's statistics are the same
 * bits whatever the thread count. The world's own particle arrays are
 * summed here; what a solver holds besides (the grid's own state) and its
 * contacts come through the solver interface (world/solver.h).
 */
#include <math.h>
#include <string.h>

#include "world/solver.h"
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

/* The contacts of the cells solver: its pair lists, in list order. */
void sd_cells_stats(const sd_world *w, sd_stat_sums *s)
{
    const sd_pair_list *l = &w->pairs;
    for (size_t e = 0; e < l->n; ++e) {
        if (l->delta[e] <= 0)
            continue;
        s->contacts++;
        s->epe += (double)l->energy[e];
        double rmin = fmin(sd_half_size(w, l->i[e]), sd_half_size(w, l->j[e]));
        if ((double)l->delta[e] / rmin > s->ovl)
            s->ovl = (double)l->delta[e] / rmin;
    }
    const sd_wall_pair_list *wl = &w->wpairs;
    for (size_t e = 0; e < wl->n; ++e) {
        if (wl->delta[e] <= 0)
            continue;
        s->wall_contacts++;
        s->epe += (double)wl->energy[e];
        double r = sd_half_size(w, wl->i[e]);
        if ((double)wl->delta[e] / r > s->ovl)
            s->ovl = (double)wl->delta[e] / r;
    }
    s->pairs = l->n;
}

void sd_world_stats(const sd_world *w, sd_stats *out)
{
    if (!out)
        return;
    memset(out, 0, sizeof *out);
    if (!w)
        return;
    const sd_particles *p = &w->p;
    out->time = w->time;
    out->step = w->step;
    sd_stat_sums s;
    memset(&s, 0, sizeof s);
    /* the world's own arrays (all a cells world holds; a grid world's
     * spheres added since its last prepare) */
    for (size_t k = 0; k < p->n; ++k) {
        if (!(p->inv_mass[k] > 0))
            continue;
        double m = 1.0 / (double)p->inv_mass[k];
        double v2 = (double)sd_v3_norm2(p->v[k]);
        s.ekt += 0.5 * m * v2;
        /* rotational energy in the body frame: sum I_a w_a^2 / 2 */
        sd_vec3 wb = sd_quat_rotate_inv(p->q[k], p->w[k]);
        sd_vec3 ii = p->inv_inertia[k];
        s.ekr += 0.5 * ((double)(wb.x * wb.x / ii.x) + (double)(wb.y * wb.y / ii.y) + (double)(wb.z * wb.z / ii.z));
        s.epg -= m * (double)sd_v3_dot(w->gravity, p->x[k]);
        if (v2 > s.vmax2)
            s.vmax2 = v2;
    }
    w->solver->stats(w, &s); /* the solver's own particles and its contacts (world/solver.h) */
    out->kinetic_translational = s.ekt;
    out->kinetic_rotational = s.ekr;
    out->potential_gravity = s.epg;
    out->potential_elastic = s.epe;
    out->contacts = s.contacts;
    out->wall_contacts = s.wall_contacts;
    out->max_overlap_ratio = s.ovl;
    out->max_speed = sqrt(s.vmax2);
    out->rebuilds = w->rebuilds;
    out->pairs = s.pairs;
}
