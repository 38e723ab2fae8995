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
#include "contact/law_volume.h"
#include "core/error.h"
#include "shape/shape_make.h"
#include "world/solver.h"
#include "world/dt_report.h"
#include "world/world.h"

static double sd_mean(double a, double b) { return 0.5 * (a + b); }

/* ---- damping of the volume laws (contact/law_volume.h) -------------------- */

/* Normal force of the 1D model of a volume contact, in units where the
 * elastic force is x^p and the mass 1: x^p plus the dashpot
 * 2 zeta sqrt(F_e / x) x' of law_volume.h, never pulling (no tension). */
static double sd_volume_model_force(double x, double v, double p, double zeta)
{
    if (x <= 0)
        return 0;
    double f = pow(x, p) + 2.0 * zeta * pow(x, 0.5 * (p - 1.0)) * v;
    return f > 0 ? f : 0;
}

/* Rebound speed over impact speed of the 1D model (RK4). For p < 1 the
 * dashpot diverges at x = 0 (integrably): the loss over the first 1e-7 is
 * taken in closed form and the step is kept below the dashpot's time scale. */
static double sd_volume_model_rebound(double p, double zeta)
{
    double q = 0.5 * (p + 1.0);
    double x = 1e-7, v = 1.0 - 2.0 * zeta * pow(x, q) / q - pow(x, p + 1.0) / (p + 1.0);
    double t = 0;
    while (t < 60.0) {
        double h = 2e-3;
        if (p < 1 && zeta > 0)
            h = fmin(h, 0.05 * pow(x, 0.5 * (1.0 - p)) / (2.0 * zeta));
        h = fmax(h, 1e-9);
        double k1x = v, k1v = -sd_volume_model_force(x, v, p, zeta);
        double k2x = v + 0.5 * h * k1v, k2v = -sd_volume_model_force(x + 0.5 * h * k1x, k2x, p, zeta);
        double k3x = v + 0.5 * h * k2v, k3v = -sd_volume_model_force(x + 0.5 * h * k2x, k3x, p, zeta);
        double k4x = v + h * k3v, k4v = -sd_volume_model_force(x + h * k3x, k4x, p, zeta);
        x += h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
        v += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
        t += h;
        if (x <= 0)
            return v < 0 ? -v : 0;
    }
    return v < 0 ? -v : 0; /* still creeping out: e is ~0 at such damping */
}

/* zeta such that the 1D model of exponent p rebounds with e (bisection;
 * the rebound falls as zeta grows). */
static double sd_volume_calibrate_zeta(double e, double p)
{
    if (e >= 1.0)
        return 0.0;
    double lo = 0.0, hi = 0.5;
    for (int k = 0; k < 60 && sd_volume_model_rebound(p, hi) > e; ++k)
        hi *= 2.0;
    for (int k = 0; k < 40; ++k) {
        double mid = 0.5 * (lo + hi);
        if (sd_volume_model_rebound(p, mid) > e)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

void sd_volume_zeta_table(double e, sd_real zeta[SD_VOLUME_ZETA_N])
{
    for (int k = 0; k < SD_VOLUME_ZETA_N; ++k)
        zeta[k] = (sd_real)sd_volume_calibrate_zeta(e, (double)SD_VOLUME_P_MIN + k * (double)SD_VOLUME_P_STEP);
}

double sd_volume_rebound_model(double p, double zeta) { return sd_volume_model_rebound(p, zeta); }

/* Fills mix[nm x nm] from the materials and interactions; returns 1 when
 * some pair uses a volume law. Reads w only (sd_world_dt_report mixes a
 * table of its own for a world not prepared yet). */
static int sd_mix_table(const sd_world *w, sd_pair_params *mix)
{
    size_t nm = w->material_count;
    int has_volume_law = 0;
    for (size_t a = 0; a < nm; ++a)
        for (size_t b = 0; b < nm; ++b) {
            const sd_material_def *ma = &w->materials[a].def, *mb = &w->materials[b].def;
            double e = sd_mean(ma->restitution, mb->restitution);
            double mu = sd_mean(ma->friction, mb->friction);
            double mur = sd_mean(ma->rolling_friction, mb->rolling_friction);
            double kn = (ma->stiffness > 0 && mb->stiffness > 0)
                            ? 2.0 * ma->stiffness * mb->stiffness / (ma->stiffness + mb->stiffness)
                            : 0.0;
            double kv = (ma->volume_stiffness > 0 && mb->volume_stiffness > 0)
                            ? 2.0 * ma->volume_stiffness * mb->volume_stiffness /
                                  (ma->volume_stiffness + mb->volume_stiffness)
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
                if (it->def.volume_stiffness > 0)
                    kv = it->def.volume_stiffness;
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
            /* volume laws: each body's own E and G enter eqs. 13 and 19 */
            p->young_a = (sd_real)ma->youngs_modulus;
            p->young_b = (sd_real)mb->youngs_modulus;
            p->shear_a = (sd_real)(ma->youngs_modulus / (2.0 * (1.0 + ma->poisson_ratio)));
            p->shear_b = (sd_real)(mb->youngs_modulus / (2.0 * (1.0 + mb->poisson_ratio)));
            p->kv = (sd_real)kv;
            /* the volume law's face regularisation: the smaller value set
             * (the stricter cap), off when neither material sets it */
            double fo = ma->volume_face_omega_dt > 0 ? ma->volume_face_omega_dt : mb->volume_face_omega_dt;
            if (mb->volume_face_omega_dt > 0 && mb->volume_face_omega_dt < fo)
                fo = mb->volume_face_omega_dt;
            p->face_omega = (sd_real)(fo > 0 ? fo : 0.0);
            if (sd_law_traits(law) & SD_LAW_IS_VOLUME) {
                has_volume_law = 1;
                /* the calibration costs ~0.1 s: reuse it for an equal e */
                int done = 0;
                for (size_t q = 0; q < a * nm + b && !done; ++q) {
                    const sd_pair_params *o = &mix[q];
                    if ((sd_law_traits(o->law) & SD_LAW_IS_VOLUME) && o->restitution == p->restitution) {
                        memcpy(p->zeta, o->zeta, sizeof p->zeta);
                        done = 1;
                    }
                }
                if (!done)
                    sd_volume_zeta_table(e, p->zeta);
            }
            if (ma->youngs_modulus > 0 && mb->youngs_modulus > 0) {
                double va = ma->poisson_ratio, vb = mb->poisson_ratio;
                p->y_star = (sd_real)(1.0 / ((1 - va * va) / ma->youngs_modulus + (1 - vb * vb) / mb->youngs_modulus));
                p->g_star = (sd_real)(1.0 / (2 * (2 - va) * (1 + va) / ma->youngs_modulus +
                                             2 * (2 - vb) * (1 + vb) / mb->youngs_modulus));
                p->gt_over_gn = (sd_real)sqrt(4.0 * (double)p->g_star / (double)p->y_star);
            }
        }
    return has_volume_law;
}

sd_status sd_world_mix_materials(sd_world *w, sd_error *err)
{
    size_t nm = w->material_count;
    sd_pair_params *mix = sd_realloc(w->mix, (nm ? nm * nm : 1) * sizeof *mix);
    if (!mix)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the table of %zu material pairs", nm * nm);
    w->mix = mix;
    w->has_volume_law = sd_mix_table(w, mix);
    return SD_OK;
}

/* The volume laws need the overlap volume, which exists for sharp polyhedra
 * only (no rounding, no margin): a particle of any other shape whose
 * material meets another one under a volume law is an error at prepare
 * time, naming the shape and the two materials (no silent fallback); a
 * composite passes when all its elements do, else its first element that
 * does not is named. */
static sd_status sd_world_check_volume_shapes(const sd_world *w, const char *used, sd_error *err)
{
    size_t nm = w->material_count;
    const sd_particles *p = &w->p;
    for (size_t k = 0; k < p->n; ++k) {
        /* planar mode: shape indexes the 2D templates, none of them a polyhedron */
        int a = p->material[k], s = w->dim2 ? -1 : p->shape[k];
        int sharp = s >= 0 && w->shapes[s].kind == SD_SHAPE_POLYHEDRON && w->shapes[s].radius == 0;
        if (sharp && w->shapes[s].fcount <= SD_OVERLAP_MAX_PLANES)
            continue;
        if (s >= 0 && w->shapes[s].kind == SD_SHAPE_COMPOSITE) {
            /* a composite's element pairs take the overlap volume
             * (backend/items.h): every element a sharp polyhedron the
             * workspace holds; else the first that is not is named */
            const sd_shape *c = &w->shapes[s];
            uint32_t t = 0;
            for (; t < c->ecount; ++t) {
                const sd_shape *es = &w->shapes[w->elements[c->estart + t].shape];
                if (!(es->kind == SD_SHAPE_POLYHEDRON && es->radius == 0 && es->fcount <= SD_OVERLAP_MAX_PLANES))
                    break;
            }
            if (t == c->ecount)
                continue;
            s = w->elements[c->estart + t].shape;
            sharp = w->shapes[s].kind == SD_SHAPE_POLYHEDRON && w->shapes[s].radius == 0;
        }
        for (size_t b = 0; b < nm && b < 256; ++b) {
            if (!used[b])
                continue;
            int law = w->mix[(size_t)a * nm + b].law;
            if (!(sd_law_needs(law) & SD_LAW_NEEDS_SHARP))
                continue;
            if (sharp) /* the overlap's fixed workspace (geom/overlap.h) holds this many faces per body */
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "contact_law",
                                    "shape '%s' has %u faces, more than the %d the exact overlap volume of the %s "
                                    "law takes (material '%s' meets '%s'); use fewer faces or another law",
                                    w->shape_names[s], w->shapes[s].fcount, SD_OVERLAP_MAX_PLANES,
                                    sd_contact_law_name((sd_contact_law)law), w->materials[a].name,
                                    w->materials[b].name);
            const char *what = s >= 0 ? w->shape_names[s] : (w->dim2 ? "(planar particle)" : "(plain sphere)");
            const char *kind = s >= 0 ? sd_shape_kind_name(w->shapes[s].kind) : "sphere";
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "contact_law",
                                "shape '%s' (%s%s, material '%s') meets material '%s' with the %s law, which "
                                "needs sharp polyhedra (type polyhedron, no rounding or margin); give this pair "
                                "another law (interactions[].contact_law: hertz_mindlin or linear)",
                                what, kind, s >= 0 && w->shapes[s].radius > 0 ? ", rounded" : "",
                                w->materials[a].name, w->materials[b].name, sd_contact_law_name((sd_contact_law)law));
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
    char used_p[256]; /* by particles (walls need no modulus for the volume law) */
    memcpy(used_p, used, sizeof used_p);
    for (size_t k = 0; k < w->wall_count; ++k)
        if ((size_t)w->walls[k].material < sizeof used)
            used[w->walls[k].material] = 1;
    for (size_t a = 0; a < nm; ++a) {
        double fo = w->materials[a].def.volume_face_omega_dt;
        if (!(fo >= 0 && fo <= 1)) /* omega dt = 2 is the explicit step's limit; 1 keeps a margin */
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "volume_face_omega_dt",
                                "material '%s': expected volume_face_omega_dt in (0, 1] (or 0 for off), got %g",
                                w->materials[a].name, fo);
    }
    sd_status st = sd_world_check_volume_shapes(w, used, err);
    if (st != SD_OK)
        return st;
    for (size_t a = 0; a < nm && a < sizeof used; ++a)
        for (size_t b = a; b < nm && b < sizeof used; ++b) {
            if (!used[a] || !used[b])
                continue;
            const sd_pair_params *p = &w->mix[a * nm + b];
            /* the law's needs column (shapedem.h SD_CONTACT_LAWS) */
            unsigned needs = sd_law_needs(p->law);
            for (unsigned f = 1; f <= needs; f <<= 1) {
                sd_law_need nd;
                if (!(needs & f) || !sd_law_need_of(f, &nd))
                    continue;
                int missing;
                if (f == SD_LAW_NEEDS_MODULUS)
                    missing = !(p->y_star > 0);
                else if (f == SD_LAW_NEEDS_PARTICLE_MODULUS) /* walls are rigid: only a particle's E */
                    missing = (!(p->young_a > 0) || !(p->young_b > 0)) && (!(p->young_a > 0) ? used_p[a] : used_p[b]);
                else if (f == SD_LAW_NEEDS_STIFFNESS)
                    missing = !(p->kn > 0);
                else
                    missing = !(p->kv > 0);
                if (missing)
                    return sd_error_set(err, SD_ERR_INPUT, "", 0, nd.key,
                                        "materials '%s' and '%s' meet with the %s law but no %s is set "
                                        "(set materials[].%s%s%s, %s)",
                                        w->materials[a].name, w->materials[b].name,
                                        sd_contact_law_name((sd_contact_law)p->law), nd.what, nd.key,
                                        nd.interaction_field >= 0 ? " or interactions[]." : "",
                                        nd.interaction_field >= 0 ? nd.key : "", nd.unit);
            }
        }
    return SD_OK;
}

/* ---- time step of the volume laws (docs/physics.md "Time step") ----------
 *
 * The estimates take a face landing flat, the stiffest contact, of area
 * A = pi R_eq^2 (R_eq the radius of the equal-volume sphere: a cube's face
 * is 0.83 of it, a dodecahedron's 0.72, a Table 1 cylinder's end 1.02),
 * against a wall or against a body like itself. */

/* Potential of the 1D face contact at depth x (m): W(A x) of law_volume.h. */
static double sd_volume_face_u(const sd_pair_params *p, double c, double area, double onset, double x)
{
    return (double)sd_volume_w(p, (sd_real)c, (sd_real)(area * x), (sd_real)area, (sd_real)onset);
}

/* A face landing flat at speed v on a contact of effective mass m (kg)
 * under the law with onset V0 (0: seed 000's law): its deepest overlap
 * (m) and its duration (s), by energy, t = 2 int_0^dmax dx / sqrt(v^2 -
 * 2 U(x) / m), in the variable x = dmax - u^2 (no singularity at dmax). */
static double sd_volume_face_impact(const sd_pair_params *p, double c, double area, double onset, double m, double v,
                                    double *dmax)
{
    double e = 0.5 * m * v * v, lo = 0, hi = 1e-15;
    while (sd_volume_face_u(p, c, area, onset, hi) < e && hi < 1e3)
        hi *= 2;
    for (int k = 0; k < 200 && hi - lo > 1e-14 * hi; ++k) {
        double mid = 0.5 * (lo + hi);
        if (sd_volume_face_u(p, c, area, onset, mid) < e)
            lo = mid;
        else
            hi = mid;
    }
    double d = 0.5 * (lo + hi);
    *dmax = d;
    double su = sqrt(d), f = (double)sd_volume_dw(p, (sd_real)c, (sd_real)(area * d), (sd_real)area, (sd_real)onset) * area;
    const int n = 400; /* Simpson; the integrand is smooth in u */
    double sum = 0;
    for (int k = 0; k <= n; ++k) {
        double u = su * k / n, g;
        if (k == 0) {
            g = f > 0 ? 2.0 / sqrt(2.0 * f / m) : 0.0; /* u -> 0: v^2 - 2U/m ~ 2 F(dmax) u^2 / m */
        } else {
            double r = v * v - 2.0 * sd_volume_face_u(p, c, area, onset, d - u * u) / m;
            g = r > 0 ? 2.0 * u / sqrt(r) : 0.0;
        }
        sum += g * (k == 0 || k == n ? 1.0 : (k % 2 ? 4.0 : 2.0));
    }
    return 2.0 * sum * su / n / 3.0;
}

/* What a volume-law pair of one (shape, material) against a partner gives:
 * the estimates of docs/physics.md, for the report and the step. */
typedef struct sd_volume_limits {
    double onset;        /* m^3, V0 at the world's dt */
    double onset_depth;  /* m, V0 / A: the face depth the regularisation covers */
    double impact;       /* s, face landing at v under the law as run */
    double impact_depth; /* m, its deepest overlap */
    double seed_impact;  /* s, the same under seed 000's unregularised law */
    double tangential;   /* s, pi / omega_t of the face contact's tangential spring */
    double rest_depth;   /* m, face resting under the weight, seed's law (0: no gravity) */
    double rest_dt;      /* s, 1 / omega of that resting face (the resting-face limit) */
} sd_volume_limits;

static sd_volume_limits sd_volume_pair_limits(const sd_world *w, const sd_pair_params *pp, double mass, double req,
                                              double rb, double inv_inertia, double v, double g, int wall)
{
    sd_volume_limits l;
    memset(&l, 0, sizeof l);
    double area = SD_PI_D * req * req, dt = (double)w->dt;
    double c = ((double)pp->young_a + (wall ? 0.0 : (double)pp->young_b)) / req;
    double ct = ((double)pp->shear_a + (wall ? 0.0 : (double)pp->shear_b)) / req;
    double inv = (wall ? 1.0 : 2.0) / mass; /* translational, 1/kg */
    l.onset = (double)sd_volume_onset(pp, (sd_real)c, (sd_real)(SD_PI_D * rb * rb), (sd_real)inv, (sd_real)dt);
    l.onset_depth = l.onset / area;
    l.impact = sd_volume_face_impact(pp, c, area, l.onset, 1.0 / inv, v, &l.impact_depth);
    double dpure;
    l.seed_impact = sd_volume_face_impact(pp, c, area, 0.0, 1.0 / inv, v, &dpure);
    /* tangential spring (eq. 19, k_t = c_t A) on the mass the contact
     * point sees sideways: 1/m + R_b^2 / I_min for each body */
    double kt = pp->law == SD_LAW_VOLUME ? ct * area : (double)pp->kt_ratio * (double)pp->kv * area;
    double inv_t = (wall ? 1.0 : 2.0) * (1.0 / mass + rb * rb * inv_inertia);
    l.tangential = kt > 0 ? SD_PI_D / sqrt(kt * inv_t) : (double)INFINITY;
    if (pp->law == SD_LAW_VOLUME && g > 0) {
        /* F = K d^(1/3), K = c A^(4/3): d = (m g / K)^3, dF/dd = m g / (3 d) */
        double k = c * pow(area, 4.0 / 3.0), f = mass * g;
        l.rest_depth = pow(f / k, 3.0);
        double omega = sqrt(f / (3.0 * l.rest_depth) / mass);
        l.rest_dt = 1.0 / omega;
    }
    return l;
}

/* Contact duration of one contact between masses meeting at speed v. */
static double sd_contact_duration(const sd_pair_params *p, double m_star, double r_star, double v)
{
    if (sd_law_traits(p->law) & SD_LAW_IS_LINEAR) {
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

/* The deepest overlap (m) of a body of mass m, radius r landing at speed v
 * on a flat wall, elastic (damping only makes it shallower): the work of
 * the normal force equals m v^2 / 2, Hertz (8/15) Y* sqrt(r) d^(5/2) or
 * linear k_n d^2 / 2. 0 for the volume laws (their landing is above). */
static double sd_impact_depth(const sd_pair_params *p, double m, double r, double v)
{
    unsigned t = sd_law_traits(p->law);
    if (t & SD_LAW_IS_LINEAR)
        return v * sqrt(m / (double)p->kn);
    if (t & SD_LAW_IS_HERTZ)
        return pow(15.0 * m * v * v / (16.0 * (double)p->y_star * sqrt(r)), 0.4);
    return 0.0;
}

/* Keeps the smaller of *best and t, and what it is. */
static void sd_dt_keep(double *best, const char **what, double t, const char *name)
{
    if (t < *best) {
        *best = t;
        *what = name;
    }
}

void sd_world_dt_report(const sd_world *w, sd_dt_report *r)
{
    memset(r, 0, sizeof *r);
    r->recommended = r->contact = INFINITY;
    r->limit = "no contact can form";
    r->onset_depth = r->rest_dt = r->seed_impact = INFINITY;
    r->guard = w->def.max_overlap;
    const sd_particles *p = &w->p;
    size_t nm = w->material_count;
    double tc_min = INFINITY, rayleigh_min = INFINITY;
    /* smallest sphere per material; characteristic impact speed from the
     * fastest particle and a fall through the packing's height */
    sd_dt_inputs in;
    for (size_t a = 0; a < 256; ++a)
        in.rmin[a] = in.mmin[a] = INFINITY;
    in.vmax = 0;
    in.zlo = INFINITY;
    in.zhi = -INFINITY;
    in.rsmall = INFINITY;
    in.any = p->n > 0;
    double *rmin = in.rmin, *mmin = in.mmin;
    double g = sqrt((double)sd_v3_norm2(w->gravity));
    sd_vec3 gdir = g > 0 ? sd_v3_scale(w->gravity, (sd_real)(-1.0 / g)) : sd_v3(0, 0, 1);
    /* the particles the solver holds besides the world's arrays, or will
     * insert (the grid's own state and its pour: world/solver.h) */
    sd_v3d gd = {(double)gdir.x, (double)gdir.y, (double)gdir.z};
    w->solver->dt_inputs(w, gd, &in);
    if (!in.any || nm == 0)
        return;
    /* the mixed pair table is made at prepare (and stale after a material
     * or interaction was added): a world not prepared gets one of its own */
    sd_pair_params *own = NULL;
    const sd_pair_params *mix = w->mix;
    if (!w->prepared || !mix) {
        own = sd_malloc(nm * nm * sizeof *own);
        if (!own) {
            r->recommended = r->contact = NAN;
            r->limit = "out of memory for the table of material pairs";
            return;
        }
        sd_mix_table(w, own);
        mix = own;
    }
    double vmax = in.vmax, zlo = in.zlo, zhi = in.zhi, rsmall = in.rsmall;
    for (size_t k = 0; k < p->n; ++k) {
        int m = p->material[k];
        if (m < 0 || m >= 256)
            continue;
        double rr = (double)p->radius[k];
        double mass = p->inv_mass[k] > 0 ? 1.0 / (double)p->inv_mass[k] : (double)INFINITY;
        if (rr < rmin[m])
            rmin[m] = rr;
        rsmall = fmin(rsmall, rr);
        if (mass < mmin[m])
            mmin[m] = mass;
        vmax = fmax(vmax, (double)sd_v3_norm(p->v[k]));
        double h = (double)sd_v3_dot(p->x[k], gdir);
        zlo = fmin(zlo, h);
        zhi = fmax(zhi, h);
    }
    double v = fmax(vmax, fmax(sqrt(2 * g * (zhi - zlo + 2 * rsmall)), 1e-3));
    r->speed = v;
    /* the volume laws' estimates need each body's shape: per distinct
     * (shape, material) of the sharp polyhedra, against each partner */
    double vol_rec = INFINITY;
    const char *vol_what = "";
    unsigned char *seen = w->shape_count ? sd_calloc(w->shape_count * (nm ? nm : 1), 1) : NULL;
    r->volume_skipped = w->shape_count > 0 && !seen && !w->dim2; /* out of memory: said by check */
    for (size_t k = 0; seen && !w->dim2 && k < p->n; ++k) {
        int a = p->material[k], s = p->shape[k];
        if (a < 0 || (size_t)a >= nm || a >= 256 || s < 0 || (size_t)s >= w->shape_count ||
            seen[(size_t)s * nm + (size_t)a] || w->shapes[s].kind != SD_SHAPE_POLYHEDRON || w->shapes[s].radius != 0 ||
            !(p->inv_mass[k] > 0))
            continue;
        seen[(size_t)s * nm + (size_t)a] = 1;
        const sd_shape *sh = &w->shapes[s];
        double mass = 1.0 / (double)p->inv_mass[k], req = (double)w->shape_req[s], rb = (double)sh->bound;
        double ii = fmax(fmax((double)p->inv_inertia[k].x, (double)p->inv_inertia[k].y), (double)p->inv_inertia[k].z);
        for (size_t b = 0; b < nm && b < 256; ++b) {
            const sd_pair_params *pp = &mix[(size_t)a * nm + b];
            if (!(sd_law_traits(pp->law) & SD_LAW_IS_VOLUME) || !sd_law_params_ready(pp))
                continue;
            int wall_b = 0;
            for (size_t q = 0; q < w->wall_count; ++q)
                wall_b |= w->walls[q].material == (int)b;
            for (int wall = 0; wall < 2; ++wall) {
                if (wall ? !wall_b : !isfinite(rmin[b]))
                    continue;
                sd_volume_limits l = sd_volume_pair_limits(w, pp, mass, req, rb, ii, v, g, wall);
                r->volume = 1;
                /* the stability limit's T_c (docs/physics.md "Time step"):
                 * the tangential half period and the face landing as run.
                 * Under seed 000's unregularised law a face is infinitely
                 * stiff at zero overlap by construction (its landing
                 * shortens without bound as the speed drops): that landing
                 * joins the recommended step and `shapedem check` warns
                 * about it, but it is not a limit a time step can meet */
                int seed_face = l.onset == 0 && pp->law == SD_LAW_VOLUME;
                tc_min = fmin(tc_min, seed_face ? l.tangential : fmin(l.impact, l.tangential));
                /* with the regularisation a face contact is resolved by
                 * construction (omega dt <= face_omega at zero overlap, and
                 * below face_omega / sqrt 3 beyond V0, at any dt): the
                 * tangential spring sets the step */
                sd_dt_keep(&vol_rec, &vol_what, l.tangential / 50.0,
                           "volume law: tangential spring of a face contact (pi / omega_t over 50)");
                /* seed 000's law (no regularisation): a face resting under its
                 * weight is the stiffest contact the load makes */
                if (l.onset == 0 && l.rest_depth > 0)
                    sd_dt_keep(&vol_rec, &vol_what, l.rest_dt,
                               "volume law: the resting-face limit (a face resting under its weight, omega dt <= 1)");
                int inside = l.impact_depth < l.onset_depth;
                if (l.onset == 0 && pp->law == SD_LAW_VOLUME_LINEAR)
                    sd_dt_keep(&vol_rec, &vol_what, l.impact / 50.0, "volume law: face-on landing (its duration over 50)");
                else if (l.onset == 0)
                    sd_dt_keep(&vol_rec, &vol_what, l.impact / 50.0,
                               "volume law: face-on landing under seed 000's law (its duration over 50)");
                if (l.onset_depth < r->onset_depth) {
                    r->onset = l.onset;
                    r->onset_depth = l.onset_depth;
                    r->onset_radius = req;
                }
                if (l.impact < r->impact || r->impact == 0) {
                    r->impact = l.impact;
                    r->impact_depth = l.impact_depth;
                    r->impact_inside = inside;
                    r->impact_onset_depth = l.onset_depth;
                }
                r->seed_impact = fmin(r->seed_impact, l.seed_impact);
                if (l.rest_depth > 0 && l.rest_dt < r->rest_dt) {
                    r->rest_dt = l.rest_dt;
                    r->rest_depth = l.rest_depth;
                    r->rest_inside = l.rest_depth < l.onset_depth;
                    r->rest_onset_depth = l.onset_depth;
                }
            }
        }
    }
    sd_free(seen);
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
            const sd_pair_params *pp = &mix[a * nm + b];
            if (!sd_law_params_ready(pp)) /* sd_world_check_params says why when it meets */
                continue;
            if (sd_law_traits(pp->law) & SD_LAW_IS_VOLUME)
                continue; /* above */
            int wall_b = 0, mesh_b = 0;
            for (size_t k = 0; k < w->wall_count; ++k) {
                wall_b |= w->walls[k].material == (int)b;
                mesh_b |= w->walls[k].material == (int)b && w->walls[k].kind == SD_WALL_MESH;
            }
            if (isfinite(rmin[b])) {
                double ms = mmin[a] * mmin[b] / (mmin[a] + mmin[b]);
                double rs = rmin[a] * rmin[b] / (rmin[a] + rmin[b]);
                tc_min = fmin(tc_min, sd_contact_duration(pp, ms, rs, v));
            }
            if (wall_b)
                tc_min = fmin(tc_min, sd_contact_duration(pp, mmin[a], rmin[a], v));
            if (mesh_b && isfinite(mmin[a])) {
                /* the thin-wall rule's margin (geom/mesh_contact.h, sd_mesh_front) */
                double d = sd_impact_depth(pp, mmin[a], rmin[a], v);
                if (r->mesh_radius == 0 || d / rmin[a] > r->mesh_depth / r->mesh_radius) {
                    r->mesh_depth = d;
                    r->mesh_radius = rmin[a];
                }
            }
        }
    }
    r->contact = tc_min;
    /* resolve a contact in about 50 steps, stay under 20 % of the Rayleigh
     * time of the materials with a modulus; the volume laws' own limits */
    double rec = INFINITY;
    const char *what = r->limit;
    double other = INFINITY;
    for (size_t a = 0; a < nm && a < 256; ++a)
        for (size_t b = 0; b < nm && b < 256; ++b)
            if (!(sd_law_traits(mix[a * nm + b].law) & SD_LAW_IS_VOLUME))
                other = 0; /* some pair is not a volume pair: tc_min may be its duration */
    if (other == 0)
        sd_dt_keep(&rec, &what, tc_min / 50.0, "contact duration over 50");
    sd_dt_keep(&rec, &what, 0.2 * rayleigh_min, "0.2 x the Rayleigh time");
    sd_dt_keep(&rec, &what, vol_rec, vol_what);
    r->recommended = rec;
    r->limit = what;
    sd_free(own);
}

double sd_world_recommended_dt(const sd_world *w, double *contact_duration)
{
    if (!w) {
        if (contact_duration)
            *contact_duration = (double)NAN;
        return (double)NAN;
    }
    sd_dt_report r;
    sd_world_dt_report(w, &r);
    if (contact_duration)
        *contact_duration = r.contact;
    return r.recommended;
}
