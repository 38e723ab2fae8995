/* material.c — mixing two materials into the parameters of their contact,
 * and the time-step estimates printed by `shapedem check`.
 *
 * Mixing rules (documented in docs/physics.md): Hertz moduli combine as in
 * Hertz theory (Y*, G*); restitution, friction and rolling friction take
 * the mean of the two materials; the linear stiffness combines as two
 * springs in series times two (equal materials keep their k). An
 * interaction entry overrides any of these for its pair.
 */
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "world/world.h"

static double sd_mean(double a, double b) { return 0.5 * (a + b); }

sd_status sd_world_mix_materials(sd_world *w, sd_error *err)
{
    size_t nm = w->material_count;
    sd_pair_params *mix = sd_realloc(w->mix, (nm ? nm * nm : 1) * sizeof *mix);
    if (!mix)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    w->mix = mix;
    for (size_t a = 0; a < nm; ++a)
        for (size_t b = 0; b < nm; ++b) {
            const sd_material_def *ma = &w->materials[a].def, *mb = &w->materials[b].def;
            double e = sd_mean(ma->restitution, mb->restitution);
            double mu = sd_mean(ma->friction, mb->friction);
            double mur = sd_mean(ma->rolling_friction, mb->rolling_friction);
            double kn = (ma->stiffness > 0 && mb->stiffness > 0)
                            ? 2.0 * ma->stiffness * mb->stiffness / (ma->stiffness + mb->stiffness)
                            : 0.0;
            /* viscous coefficients add like parallel dashpots halved, as k does */
            double eta = (ma->damping > 0 && mb->damping > 0) ? 2.0 * ma->damping * mb->damping / (ma->damping + mb->damping) : 0.0;
            int law = (int)w->def.law;
            /* the last matching interaction wins */
            for (size_t k = 0; k < w->interaction_count; ++k) {
                const sd_interaction *it = &w->interactions[k];
                if (!((it->a == (int)a && it->b == (int)b) || (it->a == (int)b && it->b == (int)a)))
                    continue;
                if (it->def.restitution > 0)
                    e = it->def.restitution;
                if (it->def.friction >= 0)
                    mu = it->def.friction;
                if (it->def.rolling_friction >= 0)
                    mur = it->def.rolling_friction;
                if (it->def.stiffness > 0)
                    kn = it->def.stiffness;
                if (it->def.damping >= 0)
                    eta = it->def.damping;
                if (it->def.law >= 0)
                    law = it->def.law;
            }
            sd_pair_params *p = &mix[a * nm + b];
            memset(p, 0, sizeof *p);
            p->law = law;
            p->restitution = (sd_real)e;
            double le = log(e);
            p->log_e_factor = (sd_real)(le / sqrt(le * le + SD_PI_D * SD_PI_D));
            p->friction = (sd_real)mu;
            p->rolling = (sd_real)mur;
            p->kn = (sd_real)kn;
            p->eta = (sd_real)eta;
            p->kt_ratio = (sd_real)sd_mean(ma->tangential_stiffness_ratio, mb->tangential_stiffness_ratio);
            if (ma->youngs_modulus > 0 && mb->youngs_modulus > 0) {
                double va = ma->poisson_ratio, vb = mb->poisson_ratio;
                p->y_star = (sd_real)(1.0 / ((1 - va * va) / ma->youngs_modulus + (1 - vb * vb) / mb->youngs_modulus));
                p->g_star = (sd_real)(1.0 / (2 * (2 - va) * (1 + va) / ma->youngs_modulus +
                                             2 * (2 - vb) * (1 + vb) / mb->youngs_modulus));
                p->gt_over_gn = (sd_real)sqrt(4.0 * (double)p->g_star / (double)p->y_star);
            }
        }
    return SD_OK;
}

/* Checks that every material pair that can meet has what its law needs. */

sd_status sd_world_check_params(const sd_world *w, sd_error *err)
{
    size_t nm = w->material_count;
    char used[256] = {0};
    for (size_t k = 0; k < w->p.n; ++k)
        if ((size_t)w->p.material[k] < sizeof used)
            used[w->p.material[k]] = 1;
    for (size_t k = 0; k < w->wall_count; ++k)
        if ((size_t)w->walls[k].material < sizeof used)
            used[w->walls[k].material] = 1;
    for (size_t a = 0; a < nm && a < sizeof used; ++a)
        for (size_t b = a; b < nm && b < sizeof used; ++b) {
            if (!used[a] || !used[b])
                continue;
            const sd_pair_params *p = &w->mix[a * nm + b];
            if (p->law == SD_LAW_LINEAR && !(p->kn > 0))
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "stiffness",
                                    "materials '%s' and '%s' meet with the linear law but no stiffness is set "
                                    "(set materials[].stiffness or interactions[].stiffness, N/m)",
                                    w->materials[a].name, w->materials[b].name);
            if (p->law == SD_LAW_HERTZ_MINDLIN && !(p->y_star > 0))
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "youngs_modulus",
                                    "materials '%s' and '%s' meet with the Hertz-Mindlin law but a Young's "
                                    "modulus is missing (set materials[].youngs_modulus, Pa)",
                                    w->materials[a].name, w->materials[b].name);
        }
    return SD_OK;
}

/* Contact duration of one contact between masses meeting at speed v. */
static double sd_contact_duration(const sd_pair_params *p, double m_star, double r_star, double v)
{
    if (p->law == SD_LAW_LINEAR) {
        /* seed 004 eq. 12 with gamma_n from eq. 16, or from eta directly */
        double w0 = sqrt((double)p->kn / m_star);
        double g = p->eta > 0 ? (double)p->eta / (2.0 * m_star) : -w0 * (double)p->log_e_factor;
        if (g >= w0)
            return SD_PI_D / w0; /* overdamped: the elastic time still bounds dt */
        return SD_PI_D / sqrt(w0 * w0 - g * g);
    }
    /* Hertz (elastic) duration: 2.87 (m*^2 / (R* Y*^2 v))^(1/5) */
    double y = (double)p->y_star;
    return 2.87 * pow(m_star * m_star / (r_star * y * y * v), 0.2);
}

double sd_world_recommended_dt(const sd_world *w, double *contact_duration)
{
    const sd_particles *p = &w->p;
    size_t nm = w->material_count;
    double tc_min = INFINITY, rayleigh_min = INFINITY;
    if (p->n == 0 || nm == 0) {
        if (contact_duration)
            *contact_duration = INFINITY;
        return INFINITY;
    }
    /* smallest sphere per material; characteristic impact speed from the
     * fastest particle and a fall through the packing's height */
    double rmin[256], mmin[256];
    for (size_t a = 0; a < 256; ++a)
        rmin[a] = mmin[a] = INFINITY;
    double vmax = 0, zlo = INFINITY, zhi = -INFINITY, rsmall = INFINITY;
    double g = sqrt((double)sd_v3_norm2(w->gravity));
    sd_vec3 gdir = g > 0 ? sd_v3_scale(w->gravity, (sd_real)(-1.0 / g)) : sd_v3(0, 0, 1);
    for (size_t k = 0; k < p->n; ++k) {
        int m = p->material[k];
        if (m < 0 || m >= 256)
            continue;
        double r = (double)p->radius[k];
        double mass = p->inv_mass[k] > 0 ? 1.0 / (double)p->inv_mass[k] : (double)INFINITY;
        if (r < rmin[m])
            rmin[m] = r;
        rsmall = fmin(rsmall, r);
        if (mass < mmin[m])
            mmin[m] = mass;
        vmax = fmax(vmax, (double)sd_v3_norm(p->v[k]));
        double h = (double)sd_v3_dot(p->x[k], gdir);
        zlo = fmin(zlo, h);
        zhi = fmax(zhi, h);
    }
    double v = fmax(vmax, fmax(sqrt(2 * g * (zhi - zlo + 2 * rsmall)), 1e-3));
    for (size_t a = 0; a < nm && a < 256; ++a) {
        if (!isfinite(rmin[a]))
            continue;
        const sd_material_def *ma = &w->materials[a].def;
        if (ma->youngs_modulus > 0) {
            double gmod = ma->youngs_modulus / (2 * (1 + ma->poisson_ratio));
            double tr = SD_PI_D * rmin[a] * sqrt(ma->density / gmod) / (0.1631 * ma->poisson_ratio + 0.8766);
            rayleigh_min = fmin(rayleigh_min, tr);
        }
        for (size_t b = 0; b < nm && b < 256; ++b) {
            const sd_pair_params *pp = &w->mix[a * nm + b];
            if ((pp->law == SD_LAW_LINEAR && !(pp->kn > 0)) || (pp->law != SD_LAW_LINEAR && !(pp->y_star > 0)))
                continue;
            int wall_b = 0;
            for (size_t k = 0; k < w->wall_count; ++k)
                wall_b |= w->walls[k].material == (int)b;
            if (isfinite(rmin[b])) {
                double ms = mmin[a] * mmin[b] / (mmin[a] + mmin[b]);
                double rs = rmin[a] * rmin[b] / (rmin[a] + rmin[b]);
                tc_min = fmin(tc_min, sd_contact_duration(pp, ms, rs, v));
            }
            if (wall_b)
                tc_min = fmin(tc_min, sd_contact_duration(pp, mmin[a], rmin[a], v));
        }
    }
    if (contact_duration)
        *contact_duration = tc_min;
    /* resolve a contact in about 50 steps, and stay under 20 % of the
     * Rayleigh time for Hertz materials */
    return fmin(tc_min / 50.0, 0.2 * rayleigh_min);
}
