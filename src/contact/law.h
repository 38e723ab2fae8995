/* law.h — contact laws: force from contact geometry, relative velocity and
 * the tangential spring history. Single source for CPU and GPU (SD_HD).
 *
 * Conventions: n is the unit normal pointing from body j to body i, delta > 0
 * the overlap, v_rel = v_i - v_j at the contact point, w_rel = w_i - w_j.
 * The returned force acts on i (j receives its opposite).
 *
 * Laws (both with the tangential spring of Cundall–Strack, kept in the
 * global frame, turned into the current tangent plane each step and capped
 * by Coulomb; DESIGN.md engineering notes):
 *  - SD_LAW_LINEAR: seed 004 eq. 10, F_n = k_n delta - 2 gamma_n m* u_n with
 *    gamma_n from e_n by seed 004 eq. 16 (omega_0^2 = k_n / m*), the same
 *    gamma in the tangential dashpot, k_t = ratio * k_n. With a viscous
 *    coefficient eta set, the dashpots are -eta u_n and -eta v_t instead
 *    (seed 001 eqs. 6 and 8).
 *  - SD_LAW_HERTZ_MINDLIN: the LIGGGHTS `hertz tangential history` form,
 *    k_n = 4/3 Y* sqrt(R* delta), S_n = 2 Y* sqrt(R* delta),
 *    k_t = S_t = 8 G* sqrt(R* delta), gamma = -2 sqrt(5/6) beta sqrt(S m*).
 * Neither law clips the normal force at zero, so e_n is exactly the
 * restitution of seed 004 eq. 15 for the linear law.
 * Rolling resistance: constant directional torque (LIGGGHTS `cdt`),
 * T_r = -mu_r R* |F_n| w_rel/|w_rel|.
 */
#ifndef SD_CONTACT_LAW_H
#define SD_CONTACT_LAW_H

#include <shapedem/shapedem.h>

#include "contact/params.h"
#include "core/vec.h"

typedef struct sd_contact_out {
    sd_vec3 force;        /* N, on body i */
    sd_vec3 roll_torque;  /* N m, on body i (j gets the opposite) */
    sd_real fn;           /* N, signed normal force magnitude */
    sd_real energy;       /* J, elastic energy stored in the contact */
} sd_contact_out;

/* Turns the stored spring into the plane normal to n, keeping its length. */
SD_HD static SD_HOT sd_vec3 sd_law_rotate_spring(sd_vec3 ds, sd_vec3 n)
{
    sd_real len2 = sd_v3_norm2(ds);
    if (len2 <= SD_R(0.0))
        return ds;
    sd_vec3 t = sd_v3_madd(ds, -sd_v3_dot(ds, n), n);
    sd_real tl2 = sd_v3_norm2(t);
    if (tl2 <= SD_R(0.0))
        return sd_v3_zero();
    return sd_v3_scale(t, sd_sqrt(len2 / tl2));
}

/* Evaluates the pair's law. ds is the tangential spring (m), updated in
 * place; dt the time step; r_star the effective radius (m); m_star the
 * effective mass (kg). */
SD_HD static SD_HOT sd_contact_out sd_law_eval(const sd_pair_params *p, sd_vec3 n, sd_real delta, sd_real r_star,
                                                  sd_real m_star, sd_vec3 v_rel, sd_vec3 w_rel, sd_vec3 *ds,
                                                  sd_real dt)
{
    sd_contact_out out;
    sd_real un = sd_v3_dot(v_rel, n);
    sd_vec3 vt = sd_v3_madd(v_rel, -un, n);
    sd_real kn = SD_R(0.0), kt = SD_R(0.0), gn = SD_R(0.0), gt = SD_R(0.0);
    out.energy = SD_R(0.0);
    /* every law has a case and there is no default: -Wswitch (and
     * -Werror) fails on a law added to SD_CONTACT_LAWS without one */
    switch ((sd_contact_law)p->law) {
    case SD_LAW_LINEAR:
        kn = p->kn;
        kt = p->kt_ratio * p->kn;
        /* seed 004 eq. 16 with omega_0 = sqrt(k_n / m*); eq. 10 damps with 2 gamma m* */
        if (p->eta > SD_R(0.0)) {
            gn = p->eta; /* seed 001 eqs. 6, 8: eta given directly */
        } else {
            sd_real omega0 = sd_sqrt(kn / m_star);
            sd_real gamma = -omega0 * p->log_e_factor;
            gn = SD_R(2.0) * gamma * m_star;
        }
        gt = gn;
        out.energy = SD_R(0.5) * kn * delta * delta;
        break;
    case SD_LAW_HERTZ_MINDLIN: {
        sd_real a = sd_sqrt(r_star * delta);
        sd_real sn = SD_R(2.0) * p->y_star * a;
        kn = SD_R(4.0) / SD_R(3.0) * p->y_star * a;
        kt = SD_R(8.0) * p->g_star * a; /* S_t */
        /* -2 sqrt(5/6) beta sqrt(S m*), beta <= 0; sqrt(S_t m*) is
         * sqrt(S_n m*) times the pair constant sqrt(4 G* / Y*) */
        gn = SD_R(-1.8257418583505538) * p->log_e_factor * sd_sqrt(sn * m_star);
        gt = gn * p->gt_over_gn;
        /* integral of 4/3 Y* sqrt(R*) d^{3/2} */
        out.energy = SD_R(0.4) * kn * delta * delta;
        break;
    }
    case SD_LAW_VOLUME:
    case SD_LAW_VOLUME_LINEAR:
    case SD_LAW_COUNT:
        /* the volume laws act on the overlap volume (contact/pair_poly.h)
         * and never reach a depth law: the world refuses, at prepare, a
         * pair under them that is not two sharp polyhedra (needs column);
         * no force rather than another law's */
        break;
    }
    sd_real fn = kn * delta - gn * un;
    out.fn = fn;

    /* tangential spring: rotate, integrate, cap (Coulomb) */
    sd_vec3 s = sd_law_rotate_spring(*ds, n);
    s = sd_v3_madd(s, dt, vt);
    sd_vec3 ft = sd_v3_sub(sd_v3_scale(s, -kt), sd_v3_scale(vt, gt));
    sd_real ft_max = p->friction * sd_fabs(fn);
    sd_real ft2 = sd_v3_norm2(ft);
    sd_real et = SD_R(0.5) * kt * sd_v3_norm2(s);
    if (ft2 > ft_max * ft_max) {
        sd_real ftn = sd_sqrt(ft2);
        ft = sd_v3_scale(ft, ft_max / ftn);
        /* keep the spring consistent with the sliding force */
        s = kt > SD_R(0.0) ? sd_v3_scale(sd_v3_madd(ft, gt, vt), SD_R(-1.0) / kt) : sd_v3_zero();
        /* The sliding spring is bookkeeping, not an elastic state: it holds
         * -(F_coulomb + gamma_t v_t)/k_t so that the next step's trial force
         * continues the sliding force (Luding 2008, Granular Matter 10,
         * eq. 19), and with the dashpot's share it can be far longer than
         * any elastic deflection. Counting 1/2 k_t |s|^2 as stored energy
         * made the reported total energy jump by up to 1.4 % above its
         * initial value at the first step of a sliding impact, where the
         * normal dashpot makes the Coulomb limit large while the overlap
         * is still ~0 (issue 11 §5 sweep). The energy reported for a
         * sliding contact is the elastic one, bounded by the Coulomb limit
         * of the elastic normal force mu k_n delta: at most
         * (mu k_n delta)^2 / (2 k_t). Only the reported energy changes;
         * the force and the spring are as before. */
        sd_real ce = p->friction * kn * delta;
        et = kt > SD_R(0.0) ? sd_min(SD_R(0.5) * kt * sd_v3_norm2(s), SD_R(0.5) * ce * ce / kt) : SD_R(0.0);
    }
    *ds = s;
    out.energy += et;
    out.force = sd_v3_madd(ft, fn, n);

    out.roll_torque = sd_v3_zero();
    if (p->rolling > SD_R(0.0)) {
        sd_real wl = sd_v3_norm(w_rel);
        if (wl > SD_R(1e-12))
            out.roll_torque = sd_v3_scale(w_rel, -p->rolling * r_star * sd_fabs(fn) / wl);
    }
    return out;
}

#endif
