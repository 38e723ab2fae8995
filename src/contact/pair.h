/* pair.h — one contact, end to end: geometry, relative motion at the
 * contact point, law, and the force and torques on both bodies. Single
 * source (SD_HD): the CPU loops and the CUDA kernels call these per pair.
 */
#ifndef SD_CONTACT_PAIR_H
#define SD_CONTACT_PAIR_H

#include "contact/law.h"
#include "core/quat.h"
#include "geom/sphere.h"

/* The state of one body as the pair evaluation needs it. */
typedef struct sd_body {
    sd_vec3 x, v, w;
    sd_real radius, inv_mass;
    /* rotational inertia as seen by the dashpot: zero for spheres (a central
     * contact), the principal inverse moments and orientation for shapes */
    sd_vec3 inv_inertia;
    sd_quat q;
} sd_body;

/* Inverse of a body's effective mass along n at lever arm r from its
 * centre: 1/m + (r x n) . I^-1 (r x n). The dashpot of an off-centre
 * contact sees this mass (a cylinder hitting a wall on its rim), so the
 * restitution of the contact point is e_n for any impact geometry. */
SD_HD static SD_HOT sd_real sd_body_inv_mass_at(const sd_body *b, sd_vec3 r, sd_vec3 n)
{
    sd_real inv = b->inv_mass;
    if (b->inv_inertia.x == SD_R(0.0) && b->inv_inertia.y == SD_R(0.0) && b->inv_inertia.z == SD_R(0.0))
        return inv;
    sd_vec3 u = sd_quat_rotate_inv(b->q, sd_v3_cross(r, n));
    return inv + u.x * u.x * b->inv_inertia.x + u.y * u.y * b->inv_inertia.y + u.z * u.z * b->inv_inertia.z;
}

typedef struct sd_pair_result {
    sd_vec3 f;       /* N, on i */
    sd_vec3 ti, tj;  /* N m, on i and on j about their centres */
    sd_real delta;   /* m, overlap (negative gap when apart) */
    sd_real energy;  /* J */
} sd_pair_result;

/* Applies a contact to the two bodies once the geometry is known. */
SD_HD static SD_HOT sd_pair_result sd_pair_apply(const sd_pair_params *prm, const sd_body *a, const sd_body *b,
                                                    const sd_contact_geom *g, sd_real r_star, sd_vec3 *ds, sd_real dt)
{
    sd_pair_result r;
    sd_vec3 arm_i = sd_v3_sub(g->point, a->x);
    sd_vec3 arm_j = sd_v3_sub(g->point, b->x);
    sd_vec3 vi = sd_v3_add(a->v, sd_v3_cross(a->w, arm_i));
    sd_vec3 vj = sd_v3_add(b->v, sd_v3_cross(b->w, arm_j));
    sd_real inv = sd_body_inv_mass_at(a, arm_i, g->n) + sd_body_inv_mass_at(b, arm_j, g->n);
    sd_real m_star = inv > SD_R(0.0) ? SD_R(1.0) / inv : SD_R(0.0);
    sd_contact_out o = sd_law_eval(prm, g->n, g->delta, r_star, m_star, sd_v3_sub(vi, vj), sd_v3_sub(a->w, b->w), ds, dt);
    r.f = o.force;
    r.ti = sd_v3_add(sd_v3_cross(arm_i, o.force), o.roll_torque);
    r.tj = sd_v3_sub(sd_v3_cross(arm_j, sd_v3_neg(o.force)), o.roll_torque);
    r.delta = g->delta;
    r.energy = o.energy;
    return r;
}

SD_HD static SD_HOT sd_pair_result sd_pair_none(sd_vec3 *ds)
{
    sd_pair_result r;
    r.f = r.ti = r.tj = sd_v3_zero();
    r.delta = SD_R(0.0); /* apart: stats count only delta > 0 */
    r.energy = SD_R(0.0);
    *ds = sd_v3_zero(); /* a broken contact forgets its spring */
    return r;
}

/* Sphere–sphere. */
SD_HD static SD_HOT sd_pair_result sd_pair_spheres(const sd_pair_params *prm, const sd_body *a, const sd_body *b,
                                                      sd_vec3 *ds, sd_real dt)
{
    sd_contact_geom g;
    if (!sd_sphere_sphere(a->x, a->radius, b->x, b->radius, &g))
        return sd_pair_none(ds);
    sd_real r_star = a->radius * b->radius / (a->radius + b->radius);
    return sd_pair_apply(prm, a, b, &g, r_star, ds, dt);
}

/* A body against a wall feature: the wall is a body of infinite mass at
 * rest (moving walls will set v and w). r_star is the body's radius (its
 * equivalent radius for shapes). */
SD_HD static SD_HOT sd_pair_result sd_pair_wall(const sd_pair_params *prm, const sd_body *a,
                                                   const sd_contact_geom *g, int touching, sd_real r_star,
                                                   sd_vec3 *ds, sd_real dt)
{
    if (!touching)
        return sd_pair_none(ds);
    sd_body wall;
    wall.x = g->point;
    wall.v = sd_v3_zero();
    wall.w = sd_v3_zero();
    wall.radius = SD_R(0.0);
    wall.inv_mass = SD_R(0.0);
    wall.inv_inertia = sd_v3_zero();
    wall.q = sd_quat_identity();
    return sd_pair_apply(prm, a, &wall, g, r_star, ds, dt);
}

#endif
