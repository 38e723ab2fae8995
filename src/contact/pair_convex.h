/* pair_convex.h — one contact between bodies of which at least one is a
 * shape template: the convex narrow phase (shrink / GJK / swell, EPA when
 * the cores overlap; seed 004 §2.5) gives the contact geometry, then the
 * same law as spheres (pair.h). Single source (SD_HD).
 */
#ifndef SD_CONTACT_PAIR_CONVEX_H
#define SD_CONTACT_PAIR_CONVEX_H

#include "contact/pair.h"
#include "geom/convex_contact.h"

/* Narrow-phase statistics of one evaluation. */
typedef struct sd_narrow_count {
    int32_t iterations, supports;
} sd_narrow_count;

SD_HD static SD_INLINE sd_pair_result sd_pair_convex(const sd_pair_params *prm, const sd_body *a, const sd_body *b,
                                                     const sd_convex *ca, const sd_convex *cb, sd_real r_star,
                                                     sd_vec3 *ds, sd_vec3 *warm, sd_real dt, sd_narrow_count *ns)
{
    /* second level of the broad phase: bounding spheres (seed 000 §2.2,
     * Algorithm I); the candidate list holds pairs within the skin */
    sd_real reach = ca->shape->bound + cb->shape->bound;
    if (sd_v3_norm2(sd_v3_sub(ca->x, cb->x)) >= reach * reach) {
        ns->iterations = 0;
        ns->supports = 0;
        return sd_pair_none(ds);
    }
    const sd_gjk_body A = sd_gjk_body_of(ca), B = sd_gjk_body_of(cb);
    /* apart along GJK's start direction: GJK's own first-step answer, warm
     * direction included, without the query (sd_convex_apart_warm) */
    if (warm && sd_convex_apart_warm(&A, &B, warm)) {
        ns->iterations = 0;
        ns->supports = 0;
        return sd_pair_none(ds);
    }
    sd_convex_contact c = sd_convex_collide_bodies(&A, &B, warm, 0); /* only touching pairs matter */
    ns->iterations = c.iterations;
    ns->supports = c.support_calls;
    if (!c.touching)
        return sd_pair_none(ds);
    sd_contact_geom g;
    g.n = c.n;
    g.point = c.point;
    g.delta = c.delta;
    return sd_pair_apply(prm, a, b, &g, r_star, ds, dt);
}

/* A shape against a half-space wall (point p0, unit normal nw into free
 * space); *twist_arm (when not NULL): the lever of the contact's torsional
 * friction (sd_convex_plane; 0 for a point contact). */
SD_HD static SD_INLINE int sd_convex_wall_geom_twist(const sd_convex *ca, sd_vec3 p0, sd_vec3 nw, sd_contact_geom *g,
                                                     sd_narrow_count *ns, sd_real *twist_arm)
{
    sd_convex_contact c = sd_convex_plane(ca, p0, nw);
    ns->iterations = 0;
    ns->supports = c.support_calls;
    if (twist_arm)
        *twist_arm = c.touching ? c.twist_arm : SD_R(0.0);
    if (!c.touching)
        return 0;
    g->n = c.n;
    g->point = c.point;
    g->delta = c.delta;
    return 1;
}

SD_HD static SD_INLINE int sd_convex_wall_geom(const sd_convex *ca, sd_vec3 p0, sd_vec3 nw, sd_contact_geom *g,
                                               sd_narrow_count *ns)
{
    return sd_convex_wall_geom_twist(ca, p0, nw, g, ns, NULL);
}

/* Torsional friction of a face pressed on a wall (issue 30): a point
 * contact has none, so a cube set spinning on a slope pivoted about its
 * contact point for ever. The torque about the normal n opposes the spin
 * wn (rad/s, relative to the wall): mu F_n arm (Coulomb, arm from
 * sd_convex_wall_geom_twist), but never more than stops half the spin in
 * one step (0.5 |wn| / (dt n.I^-1.n)), so it brings a slow spin to rest
 * without reversing it (no history kept). Added to r->ti. */
SD_HD static SD_INLINE void sd_pair_wall_twist(const sd_pair_params *prm, const sd_body *a, sd_vec3 n, sd_real wn,
                                               sd_real arm, sd_real dt, sd_pair_result *r)
{
    sd_real fn = sd_v3_dot(r->f, n);
    if (!(arm > SD_R(0.0)) || !(fn > SD_R(0.0)) || wn == SD_R(0.0))
        return;
    sd_vec3 nb = sd_quat_rotate_inv(a->q, n);
    sd_real inv_i = nb.x * nb.x * a->inv_inertia.x + nb.y * nb.y * a->inv_inertia.y + nb.z * nb.z * a->inv_inertia.z;
    if (!(inv_i > SD_R(0.0)))
        return;
    sd_real t = prm->friction * fn * arm, stop = SD_R(0.5) * sd_fabs(wn) / (inv_i * dt);
    t = t < stop ? t : stop;
    r->ti = sd_v3_madd(r->ti, wn > SD_R(0.0) ? -t : t, n);
}

#endif
