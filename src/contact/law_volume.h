/* law_volume.h — the overlap-volume contact laws of sharp polyhedra: force
 * from the overlap volume V, the area vector S of the intersection and its
 * contact point (geom/overlap.h for two polyhedra, geom/halfspace.h for a
 * wall). Single source (SD_HD): plain structs, no allocation, no printing.
 *
 * Conventions as in law.h: n is the unit normal from body j to body i, the
 * force returned acts on i (j receives its opposite), v_rel = v_i - v_j at
 * the contact point.
 *
 * Elastic part. Both laws derive the normal force from a potential W(V):
 * moving body i by dx changes V by -S.dx (S = |S| n_ij, the area vector of
 * the faces of the intersection lying on i, notes/algorithms.md §D), so
 * F_i = W'(V) |S| n and the couple left over when S.T != 0 is W'(V) twist n.
 *  - SD_LAW_VOLUME, seed 000 eqs. 12-13: F = k_n V^(1/3) with
 *    k_n = (E_i/R_i + E_j/R_j) A_n and A_n = |S|, i.e. W'(V) = c V^(1/3),
 *    W = 3/4 c V^(4/3), c = E_i/R_i + E_j/R_j (R: radius of the sphere of
 *    equal volume; a wall has R = infinity and adds nothing to c).
 *  - SD_LAW_VOLUME_LINEAR: F = k_V V (Yade's volumetric law with exponent 1),
 *    W'(V) = k_V V / |S|. This is the gradient of a potential only while |S|
 *    does not change with the overlap (prism-like contacts, e.g. face on
 *    face); the energy reported, k_V V^2 / (2 |S|), is exact there.
 * Seed 000's law is exactly conservative: with e = 1 and mu = 0, kinetic
 * energy plus W(V) is constant (tests/validation/poly_energy.c).
 *
 * Regularisation near V = 0 (SD_LAW_VOLUME, opt-in: materials[].
 * volume_face_omega_dt). A face of area A pressed in by d has V = A d and
 * F = c A^(4/3) d^(1/3), whose stiffness dF/dd = c A^2 / (3 V^(2/3)) is
 * infinite at zero overlap: a face landing or resting under a light load is
 * stiffer than any explicit step resolves (seed 000 Table 1, E = 1.15 GPa:
 * a face-on landing at 1 m/s lasts 0.25 us, half the table's dt = 0.5 us;
 * Table 2, a 25 mm cube resting under its weight at E = 1 MPa: d = 3e-13 m,
 * omega dt = 33 at dt = 10 us). With the regularisation on, below an onset
 * volume V0 the law is linear in V, W'(V) = c V / V0^(2/3), continuous with
 * c V^(1/3) at V0. It is still a function of V alone, and V0 is a constant
 * of the pair, so F = W'(V) S stays minus the gradient of W(V) = integral
 * of W' (energy conserving with e = 1, mu = 0, as before); W and W' are
 * continuous at V0 (only the stiffness jumps, by 3x down). V0
 * (sd_volume_onset) makes the largest face either body can have (pi R_b^2,
 * R_b the bounding radius) at zero overlap as stiff as the step resolves
 * with omega dt = face_omega on the pair's translational reduced mass; it
 * scales as dt^3, so the law tends to seed 000's as dt -> 0, and contacts
 * deeper than V0 feel seed 000's force exactly (the potential there differs
 * from the seed's by the constant c V0^(4/3) / 4 only). Why it is not on by
 * default: W(V) cannot tell a face from a vertex, and a vertex contact below
 * V0 is softened too (F ~ d^5 instead of d^3). At Table 1's dt the face
 * needs V0 ~ 1e-8 m^3 while a whole 1 m/s vertex impact stays below 5e-12
 * m^3 (W = 3/4 c V^(4/3) takes the kinetic energy), so the seed's own
 * oblique impacts (theta = 10..80 deg) would change by up to 11 % of V_z.
 *
 * Normal damping, seed 000 eqs. 14-15 adapted. Eq. 15 with a constant k_n
 * gives the restitution e only for a linear spring; the elastic force here
 * grows as a power p of the penetration depth d (face on face: V ~ d,
 * |S| ~ const, so p = 1/3; edge: p = 5/3; vertex: p = 3; for the linear
 * volume law p = 1, 2, 3). A dashpot c = 2 zeta sqrt(m* F_e / d) (the
 * secant stiffness F_e / d, which scales as d^(p-1)) makes the restitution
 * independent of the impact speed for any power law, and zeta(e, p) is
 * calibrated at prepare time so that a 1D impact of that exponent rebounds
 * with exactly e (world/material.c). The local exponent is read from the
 * geometry: m = |S| d / V is 1 for a prism, 2 for a wedge, 3 for a pyramid,
 * and p = (4m - 3)/3 (volume) or p = m (volume_linear). Like the Hertz law
 * with constant beta, e then depends on the impact speed only through how
 * far the contact departs from a power law (a dodecahedron's face contact
 * widens as it deepens: tests/validation/poly_drop.c prints e against speed).
 * Two regularisations: for p < 1 the secant stiffness diverges as d -> 0,
 * so the dashpot reads F_e / max(d, |u_n| dt) (the depth travelled in one
 * step, which vanishes as dt -> 0; it also guards the first step of a
 * contact, where d may be at rounding level); and the total normal force is
 * kept >= 0 (no tension: the calibration integrates the same clipped law).
 *
 * Tangential part, seed 000 eqs. 17-20: Cundall-Strack spring with history
 * (kept in the global frame, turned into the tangent plane each step,
 * capped by Coulomb), k_t = (G_i/R_i + G_j/R_j) A_n with G = E / (2 (1 +
 * nu)) (eq. 19) for the volume law, k_t = ratio k_V |S| for the linear one,
 * and the dashpot c_t = 2 |beta| sqrt(k_t m*) of eq. 20. Because k_t
 * follows the contact area, the spring is integrated incrementally
 * (dF_s = -k_t v_t dt) and the pair's history `ds` holds the spring force
 * F_s (N), not a displacement (see below).
 */
#ifndef SD_CONTACT_LAW_VOLUME_H
#define SD_CONTACT_LAW_VOLUME_H

#include <shapedem/shapedem.h>

#include "contact/law.h"

/* Exponent grid of the damping table: p_k = 1/3 + k/3, k = 0 .. N-1. */
#define SD_VOLUME_P_MIN (SD_R(1.0) / SD_R(3.0))
#define SD_VOLUME_P_STEP (SD_R(1.0) / SD_R(3.0))

/* Contact geometry of a volume contact, in the law's convention. */
typedef struct sd_volume_geom {
    sd_real volume; /* m^3, V */
    sd_real area;   /* m^2, |S| = A_n */
    sd_vec3 n;      /* unit, from j to i */
    sd_vec3 point;  /* m, world: contact point (line of action of S) */
    sd_real twist;  /* m^3, (S.T)/|S| seen from j to i: the couple on i is W' twist n */
    sd_real depth;  /* m, extent of the overlap along n (> 0) */
    sd_real onset;  /* m^3, V0 of the regularisation (sd_volume_onset), 0 = none */
} sd_volume_geom;

typedef struct sd_volume_out {
    sd_vec3 force;  /* N, on i */
    sd_vec3 couple; /* N m, on i (j gets the opposite) */
    sd_real fn;     /* N, normal force (>= 0) */
    sd_real energy; /* J, W(V) + tangential spring energy */
} sd_volume_out;

/* Onset volume V0 (m^3) of the volume law's regularisation (see the note
 * above): the face contact's stiffness at zero overlap, c A_ref^2 / V0^(2/3),
 * is set to m_ref (Omega / dt)^2 with Omega = p->face_omega, i.e.
 *     V0 = (c A_ref^2 dt^2 / (m_ref Omega^2))^(3/2),
 * from constants of the pair only (c = kcoef, Pa/m; A_ref = pi R_b^2, m^2,
 * R_b the smaller bounding radius, no face of either body is larger;
 * inv_mass = 1/m_i + 1/m_j, 1/kg, translational; dt, s), so W stays a
 * function of V alone. 0 (the seed's law unchanged) when the pair has no
 * face_omega (the default), for volume_linear, or when dt, the area or the
 * mass is not positive. */
SD_HD static SD_INLINE sd_real sd_volume_onset(const sd_pair_params *p, sd_real kcoef, sd_real area_ref,
                                               sd_real inv_mass, sd_real dt)
{
    if (p->law != SD_LAW_VOLUME || !(p->face_omega > SD_R(0.0)) || !(kcoef > SD_R(0.0)) ||
        !(area_ref > SD_R(0.0)) || !(inv_mass > SD_R(0.0)) || !(dt > SD_R(0.0)))
        return SD_R(0.0);
    sd_real s = kcoef * area_ref * area_ref * dt * dt * inv_mass / (p->face_omega * p->face_omega);
    return s * sd_sqrt(s); /* s = V0^(2/3) */
}

/* W'(V) (N/m^2) of the law: c V^(1/3) for V >= V0 and c V / V0^(2/3)
 * below (onset V0, 0 = none), or k_V V / |S|. */
SD_HD static SD_INLINE sd_real sd_volume_dw(const sd_pair_params *p, sd_real kcoef, sd_real volume, sd_real area,
                                            sd_real onset)
{
    if (p->law == SD_LAW_VOLUME_LINEAR)
        return area > SD_R(0.0) ? p->kv * volume / area : SD_R(0.0);
    if (volume < onset) {
        sd_real c0 = sd_cbrt(onset); /* V0^(1/3) */
        return kcoef * volume / (c0 * c0);
    }
    return kcoef * sd_cbrt(volume);
}

/* W(V) (J), the integral of W' from 0: c V^2 / (2 V0^(2/3)) below V0,
 * 3/4 c V^(4/3) - 1/4 c V0^(4/3) above (continuous at V0, and W' too);
 * or k_V V^2 / (2 |S|). */
SD_HD static SD_INLINE sd_real sd_volume_w(const sd_pair_params *p, sd_real kcoef, sd_real volume, sd_real area,
                                           sd_real onset)
{
    if (p->law == SD_LAW_VOLUME_LINEAR)
        return area > SD_R(0.0) ? SD_R(0.5) * p->kv * volume * volume / area : SD_R(0.0);
    if (onset > SD_R(0.0)) {
        sd_real c0 = sd_cbrt(onset);
        if (volume < onset)
            return SD_R(0.5) * kcoef * volume * volume / (c0 * c0);
        return SD_R(0.75) * kcoef * volume * sd_cbrt(volume) - SD_R(0.25) * kcoef * onset * c0;
    }
    return SD_R(0.75) * kcoef * volume * sd_cbrt(volume); /* V^(4/3) */
}

/* Shape factor m = |S| d / V of the contact, in [1, 3]. */
SD_HD static SD_INLINE sd_real sd_volume_shape_factor(sd_real area, sd_real depth, sd_real volume)
{
    sd_real m = volume > SD_R(0.0) ? area * depth / volume : SD_R(1.0);
    return sd_clamp(m, SD_R(1.0), SD_R(3.0));
}

/* Force-depth exponent p of the contact from its shape factor m = |S| d / V. */
SD_HD static SD_INLINE sd_real sd_volume_exponent(int law, sd_real area, sd_real depth, sd_real volume)
{
    sd_real m = sd_volume_shape_factor(area, depth, volume);
    return law == SD_LAW_VOLUME_LINEAR ? m : (SD_R(4.0) * m - SD_R(3.0)) / SD_R(3.0);
}

/* zeta(e, p), linear in p between the calibrated exponents. */
SD_HD static SD_INLINE sd_real sd_volume_zeta(const sd_pair_params *p, sd_real expo)
{
    sd_real u = sd_clamp((expo - SD_VOLUME_P_MIN) / SD_VOLUME_P_STEP, SD_R(0.0), (sd_real)(SD_VOLUME_ZETA_N - 1));
    int k = (int)u;
    if (k >= SD_VOLUME_ZETA_N - 1)
        return p->zeta[SD_VOLUME_ZETA_N - 1];
    sd_real t = u - (sd_real)k;
    return p->zeta[k] + t * (p->zeta[k + 1] - p->zeta[k]);
}

/* The law. kcoef = E_i/R_i + E_j/R_j (Pa/m), ktcoef = G_i/R_i + G_j/R_j
 * (Pa/m; both unused by volume_linear); m_star the effective mass at the
 * contact point along n (kg); ds the tangential spring (m), updated. */
SD_HD static SD_INLINE sd_volume_out sd_law_volume_eval(const sd_pair_params *p, const sd_volume_geom *g, sd_real kcoef,
                                                        sd_real ktcoef, sd_real m_star, sd_vec3 v_rel, sd_vec3 *ds,
                                                        sd_real dt)
{
    sd_volume_out out;
    sd_vec3 n = g->n;
    sd_real dw = sd_volume_dw(p, kcoef, g->volume, g->area, g->onset);
    sd_real fe = dw * g->area; /* eqs. 12-13: k_n V^(1/3) with A_n = |S| */
    sd_real un = sd_v3_dot(v_rel, n);
    sd_vec3 vt = sd_v3_madd(v_rel, -un, n);

    /* normal dashpot (eq. 14) with the calibrated ratio (see the note) */
    sd_real cn = SD_R(0.0);
    if (p->restitution < SD_R(1.0) && g->depth > SD_R(0.0) && m_star > SD_R(0.0)) {
        sd_real expo = sd_volume_exponent(p->law, g->area, g->depth, g->volume);
        if (p->law == SD_LAW_VOLUME && g->volume < g->onset) /* F = c |S| V / V0^(2/3): p = 2m - 1 (<= 5) */
            expo = SD_R(2.0) * sd_volume_shape_factor(g->area, g->depth, g->volume) - SD_R(1.0);
        /* secant stiffness F_e / d, read at no less than the depth the
         * contact point travels in one step: on the first and last step of a
         * contact d can be anything down to rounding (1e-18 m), where F_e / d
         * means nothing (a face contact's diverges as d^(-2/3)) */
        sd_real reach = sd_fabs(un) * dt;
        sd_real ksec = fe / (g->depth > reach ? g->depth : reach);
        cn = SD_R(2.0) * sd_volume_zeta(p, expo) * sd_sqrt(m_star * ksec);
    }
    sd_real fn = fe - cn * un;
    if (fn < SD_R(0.0))
        fn = SD_R(0.0); /* no tension */
    out.fn = fn;

    /* tangential spring (eqs. 17-20) in incremental form: the history holds
     * the spring force F_s = -k_t Δs (N), turned into the tangent plane,
     * incremented by -k_t v_t dt, then capped. k_t follows |S|, which can
     * jump by orders of magnitude when a vertex contact becomes a face
     * contact: a stored displacement would then release k_t(new)/k_t(old)
     * times the energy it stored (a measured pump of 10x the kinetic energy
     * of a rocking body); the stored force cannot. */
    sd_real kt = p->law == SD_LAW_VOLUME_LINEAR ? p->kt_ratio * p->kv * g->area : ktcoef * g->area;
    sd_real ct = m_star > SD_R(0.0) ? SD_R(-2.0) * p->log_e_factor * sd_sqrt(kt * m_star) : SD_R(0.0);
    sd_vec3 fs = sd_law_rotate_spring(*ds, n);
    fs = sd_v3_madd(fs, -kt * dt, vt);
    sd_vec3 ft = sd_v3_madd(fs, -ct, vt);
    sd_real ft_max = p->friction * fn;
    sd_real ft2 = sd_v3_norm2(ft);
    if (ft2 > ft_max * ft_max) {
        sd_real ftn = sd_sqrt(ft2);
        ft = ftn > SD_R(0.0) ? sd_v3_scale(ft, ft_max / ftn) : sd_v3_zero();
        fs = sd_v3_madd(ft, ct, vt); /* the spring carries what the dashpot does not */
    }
    *ds = fs;
    out.force = sd_v3_madd(ft, fn, n);
    out.couple = sd_v3_scale(n, dw * g->twist);
    out.energy = sd_volume_w(p, kcoef, g->volume, g->area, g->onset) + (kt > SD_R(0.0) ? SD_R(0.5) * sd_v3_norm2(fs) / kt : SD_R(0.0));
    return out;
}

#endif
