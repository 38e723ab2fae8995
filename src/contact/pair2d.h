/* pair2d.h — one contact of the planar mode (DESIGN.md rule 9): 2D shapes
 * meet through the 2D GJK/EPA of geom/epa2d.h (seed 002 §2.2), walls are
 * lines met at the support point along their normal; the contact geometry
 * is then lifted to the plane z = 0 and goes through the same law as every
 * 3D contact (pair.h, law.h), so circles, shapes and spheres share one law.
 * With the linear law, restitution 1 (no dashpot), k_t / k_n = 1 and no
 * rolling friction, that law is seed 002 eqs. 8–10: F_n = k_n delta_n,
 * F_t = min(F_t^0 + k_t Delta delta_t, mu F_n), M_c = 0.
 *
 * Single source (SD_HD): plain structs in, no allocation, no printing.
 */
#ifndef SD_CONTACT_PAIR2D_H
#define SD_CONTACT_PAIR2D_H

#include "contact/pair.h"
#include "geom/epa2d.h"

/* The rotation angle about z of a planar orientation (w, 0, 0, z). */
SD_HD static SD_INLINE sd_real sd_quat_angle_z(sd_quat q)
{
    return SD_R(2.0) * sd_atan2(q.z, q.w);
}

/* Two 2D bodies; ca, cb their posed shapes. warm is the pair's GJK warm
 * start, *supports receives the support calls (0 when the bounding circles
 * are apart: no narrow phase ran). */
SD_HD static SD_INLINE sd_pair_result sd_pair_convex2d(const sd_pair_params *prm, const sd_body *a, const sd_body *b,
                                                       const sd_convex2d *ca, const sd_convex2d *cb, sd_real r_star,
                                                       sd_vec3 *ds, sd_vec2 *warm, sd_real dt, int *supports)
{
    *supports = 0;
    /* bounding circles first (seed 000 §2.2, Algorithm I, in 2D) */
    sd_real reach = ca->shape->bound + cb->shape->bound;
    if (sd_v2_norm2(sd_v2_sub(ca->x, cb->x)) >= reach * reach)
        return sd_pair_none(ds);
    sd_contact2d c = sd_contact2d_convex(ca, cb, warm, supports);
    if (!(c.depth > SD_R(0.0)))
        return sd_pair_none(ds);
    sd_contact_geom g;
    /* epa2d's normal points from a into b; the law's from j (b) to i (a) */
    g.n = sd_v3(-c.normal.x, -c.normal.y, SD_R(0.0));
    g.point = sd_v3(c.point.x, c.point.y, SD_R(0.0));
    g.delta = c.depth;
    return sd_pair_apply(prm, a, b, &g, r_star, ds, dt);
}

/* Half-angle (rad) of the two directions that bracket the wall's normal in
 * sd_convex2d_wall_geom: a face within this tilt of the wall is found as a
 * face (both its end points), not as one corner. */
#define SD_WALL2D_FACE_ANGLE SD_R(0.05)

/* A 2D shape against the line through p0 with unit normal nw (pointing into
 * free space). The depth is that of the deepest point, the support point
 * along -nw. The contact point is the penetration-weighted mean of the two
 * support points along -nw turned by +-SD_WALL2D_FACE_ANGLE: for a corner or
 * a curved side both are (nearly) the deepest point; for a polygon face
 * lying on the wall they are the face's two ends, so the force acts at the
 * middle of the pressed part of the face rather than at whichever end a
 * single support call returns (which would rock a flat face from corner to
 * corner). The weights vanish as an end leaves the wall, so the point moves
 * continuously as the body tilts (while the overlap is below the face
 * length times sin of the angle). Three support calls. */
SD_HD static SD_INLINE int sd_convex2d_wall_geom(const sd_convex2d *c, sd_vec2 p0, sd_vec2 nw, sd_contact_geom *g)
{
    sd_vec2 s = sd_convex2d_support(c, sd_v2_neg(nw));
    sd_real dist = sd_v2_dot(sd_v2_sub(s, p0), nw);
    if (dist >= SD_R(0.0))
        return 0;
    const sd_real ca = sd_cos(SD_WALL2D_FACE_ANGLE), sa = sd_sin(SD_WALL2D_FACE_ANGLE);
    sd_vec2 sp = sd_convex2d_support(c, sd_v2_rotcs(sd_v2_neg(nw), ca, sa));
    sd_vec2 sm = sd_convex2d_support(c, sd_v2_rotcs(sd_v2_neg(nw), ca, -sa));
    sd_real wp = sd_max(-sd_v2_dot(sd_v2_sub(sp, p0), nw), SD_R(0.0));
    sd_real wm = sd_max(-sd_v2_dot(sd_v2_sub(sm, p0), nw), SD_R(0.0));
    sd_vec2 q = (wp + wm > SD_R(0.0))
                    ? sd_v2_scale(sd_v2_add(sd_v2_scale(sp, wp), sd_v2_scale(sm, wm)), SD_R(1.0) / (wp + wm))
                    : s;
    g->n = sd_v3(nw.x, nw.y, SD_R(0.0));
    g->delta = -dist;
    /* on the contact point's foot at mid-overlap, like sd_sphere_plane */
    sd_real h = -sd_v2_dot(sd_v2_sub(q, p0), nw);
    q = sd_v2_madd(q, h - SD_R(0.5) * g->delta, nw);
    g->point = sd_v3(q.x, q.y, SD_R(0.0));
    return 1;
}

#endif
