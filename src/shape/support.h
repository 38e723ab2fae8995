/* support.h — support points of the shape kinds and of posed convex bodies.
 *
 * The support point of a convex set K in direction d is any s(d) in K with
 * d . s(d) = max_{x in K} d . x (seed 002 §2.2; seed 000 §2.3 for the
 * polyhedra). Every shape is a core swept by a sphere of radius r, and the
 * support of a Minkowski sum is the sum of the supports:
 *     s(d) = s_core(d) + r d / |d|.
 *
 * Invariants: the result is always a point of the core (or of the swept
 * shape) and never NaN, whatever d: d need not be unit; a tiny d is rescaled
 * by its largest component before any square, so it neither underflows nor
 * overflows; d = 0 is read as d = +z (every core point maximises 0 . x, so
 * any answer is right; this one is deterministic). Ties (faces, edges) are
 * broken toward the + side of each axis, and among polyhedron vertices
 * toward the lowest index, so the answer is a pure function of (shape, d).
 *
 * Single source (DESIGN.md rule 1): SD_HD, no allocation, no printing.
 */
#ifndef SD_SHAPE_SUPPORT_H
#define SD_SHAPE_SUPPORT_H

#include "shape/shape.h"

/* d scaled so that its largest component has magnitude 1 (or +z for d = 0).
 * The support of every kind depends only on the direction of d, and this
 * scaling keeps every later square in the normal range. */
SD_HD static SD_INLINE sd_vec3 sd_shape_dir_scaled(sd_vec3 d)
{
    sd_real m = sd_max(sd_fabs(d.x), sd_max(sd_fabs(d.y), sd_fabs(d.z)));
    if (!(m > SD_R(0.0))) /* zero (or NaN): a fixed, valid direction */
        return sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0));
    /* one division, not three: 1/m is finite for every normal m (and for
     * m = inf it is 0, read as +z below); a subnormal m divides, since its
     * reciprocal overflows */
    if (m >= SD_R(1e-300)) {
        sd_real k = SD_R(1.0) / m;
        sd_vec3 u = sd_v3(d.x * k, d.y * k, d.z * k);
        if (!(u.x == u.x && u.y == u.y && u.z == u.z)) /* inf · 0 */
            return sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0));
        return u;
    }
    return sd_v3(d.x / m, d.y / m, d.z / m);
}

/* +1 for x >= 0, -1 otherwise: a face's support is then its + corner. */
SD_HD static SD_INLINE sd_real sd_shape_sign(sd_real x)
{
    return x >= SD_R(0.0) ? SD_R(1.0) : SD_R(-1.0);
}

/* Support point of the core, principal frame, for direction d. The cases
 * work in the core's own frame (cone: base centre at the origin, apex at
 * +a.z); s->offset then moves the point into the principal frame (zero for
 * every kind but the cone, whose centre of mass is not its base centre). */
SD_HD static SD_INLINE sd_vec3 sd_shape_support_core(const sd_shape *s, const sd_vec3 *verts, sd_vec3 d)
{
    sd_vec3 u = sd_shape_dir_scaled(d);
    sd_vec3 p;
    switch (s->kind) {
    case SD_SHAPE_BOX:
        p = sd_v3(sd_shape_sign(u.x) * s->a.x, sd_shape_sign(u.y) * s->a.y, sd_shape_sign(u.z) * s->a.z);
        break;
    case SD_SHAPE_CYLINDER: {
        /* rim point of the end cap facing d: radius a.x along d's xy part */
        sd_real rxy = sd_sqrt(u.x * u.x + u.y * u.y);
        sd_real z = sd_shape_sign(u.z) * s->a.z;
        if (rxy > SD_R(0.0)) {
            sd_real k = s->a.x / rxy;
            p = sd_v3(k * u.x, k * u.y, z);
        } else /* d along the axis: the cap centre is a maximiser */
            p = sd_v3(SD_R(0.0), SD_R(0.0), z);
        break;
    }
    case SD_SHAPE_CONE: {
        /* a cone is the hull of its apex and its base circle: the support is
         * whichever of the two supports is higher along d (apex on ties) */
        sd_real rxy = sd_sqrt(u.x * u.x + u.y * u.y);
        sd_real h_apex = s->a.z * u.z, h_rim = s->a.x * rxy;
        if (h_apex >= h_rim)
            p = sd_v3(SD_R(0.0), SD_R(0.0), s->a.z);
        else if (rxy > SD_R(0.0)) {
            sd_real k = s->a.x / rxy;
            p = sd_v3(k * u.x, k * u.y, SD_R(0.0));
        }
        else /* d = -z: the base centre */
            p = sd_v3_zero();
        break;
    }
    case SD_SHAPE_ELLIPSOID: {
        /* x = A^2 d / |A d|, A = diag(a): the point of x^T A^-2 x = 1 whose
         * normal A^-2 x is parallel to d */
        sd_vec3 ad = sd_v3(s->a.x * u.x, s->a.y * u.y, s->a.z * u.z);
        sd_real n = sd_v3_norm(ad); /* >= min(a) since max |u_i| = 1 */
        if (n > SD_R(0.0)) {
            sd_real k = SD_R(1.0) / n; /* n ≥ min(a): 1/n is finite */
            p = sd_v3(s->a.x * ad.x * k, s->a.y * ad.y * k, s->a.z * ad.z * k);
        } else {
            p = sd_v3_zero();
        }
        break;
    }
    case SD_SHAPE_POLYHEDRON: {
        /* linear scan of the hull vertices; strict > keeps the lowest index */
        p = sd_v3_zero();
        if (verts && s->vcount > 0) {
            const sd_vec3 *v = verts + s->vstart;
            uint32_t best = 0;
            sd_real hb = sd_v3_dot(u, v[0]);
            for (uint32_t k = 1; k < s->vcount; ++k) {
                sd_real h = sd_v3_dot(u, v[k]);
                if (h > hb) {
                    hb = h;
                    best = k;
                }
            }
            p = v[best];
        }
        break;
    }
    case SD_SHAPE_COMPOSITE:
        /* never reached: a composite is not convex; the broad phase expands
         * it into its elements (sd_element, shape.h), each a convex template
         * asked here in its own frame. Its point answer keeps a stray call
         * finite. */
    case SD_SHAPE_SPHERE:
    default:
        p = sd_v3_zero(); /* a point core */
        break;
    }
    /* every core is described about its own reference point (the cone's base
     * centre); offset places that point in the principal frame */
    return sd_v3_add(p, s->offset);
}

/* The support function of the core, principal frame: h(d) = max over the
 * core of d . x (m times |d|), the height of the core along d, in closed
 * form where the kind has one (no support point built, d not rescaled):
 *   box        sum_k a_k |d_k|
 *   cylinder   a_z |d_z| + a_x |(d_x, d_y)|     (the rim of the cap facing d)
 *   cone       max(a_z d_z, a_x |(d_x, d_y)|)   (apex or base rim, core frame)
 *   ellipsoid  |A d|, A = diag(a)
 *   polyhedron max_k d . v_k
 *   sphere     0 (a point core)
 * plus d . offset. Equal to d . sd_shape_support_core(s, verts, d) up to
 * rounding (the support point is a maximiser). A caller that compares it
 * with GJK's answers must allow for that rounding and keep |d| in the
 * normal range of its squares (geom/convex_contact.h, sd_convex_apart_along). */
SD_HD static SD_INLINE sd_real sd_shape_support_height(const sd_shape *s, const sd_vec3 *verts, sd_vec3 d)
{
    sd_real h;
    switch (s->kind) {
    case SD_SHAPE_BOX:
        h = s->a.x * sd_fabs(d.x) + s->a.y * sd_fabs(d.y) + s->a.z * sd_fabs(d.z);
        break;
    case SD_SHAPE_CYLINDER:
        h = s->a.z * sd_fabs(d.z) + s->a.x * sd_sqrt(d.x * d.x + d.y * d.y);
        break;
    case SD_SHAPE_CONE:
        h = sd_max(s->a.z * d.z, s->a.x * sd_sqrt(d.x * d.x + d.y * d.y));
        break;
    case SD_SHAPE_ELLIPSOID:
        h = sd_v3_norm(sd_v3(s->a.x * d.x, s->a.y * d.y, s->a.z * d.z));
        break;
    case SD_SHAPE_POLYHEDRON:
        h = SD_R(0.0); /* no vertices: the point answer of sd_shape_support_core */
        if (verts && s->vcount > 0) {
            const sd_vec3 *v = verts + s->vstart;
            h = sd_v3_dot(d, v[0]);
            for (uint32_t k = 1; k < s->vcount; ++k)
                h = sd_max(h, sd_v3_dot(d, v[k]));
        }
        break;
    case SD_SHAPE_COMPOSITE: /* never reached (no support function); a point */
    case SD_SHAPE_SPHERE:
    default:
        h = SD_R(0.0);
        break;
    }
    return h + sd_v3_dot(d, s->offset);
}

/* Support point of the swept shape: core support plus radius along d. */
SD_HD static SD_INLINE sd_vec3 sd_shape_support(const sd_shape *s, const sd_vec3 *verts, sd_vec3 d)
{
    sd_vec3 p = sd_shape_support_core(s, verts, d);
    if (s->radius > SD_R(0.0)) {
        sd_vec3 u = sd_shape_dir_scaled(d);
        p = sd_v3_madd(p, s->radius / sd_v3_norm(u), u); /* |u| in [1, sqrt 3] */
    }
    return p;
}

/* World-frame support of a posed body's core: rotate d into the principal
 * frame, take the support there, rotate back and add the centre of mass. */
SD_HD static SD_INLINE sd_vec3 sd_convex_support_core(const sd_convex *c, sd_vec3 d_world)
{
    sd_vec3 dl = sd_quat_rotate_inv(c->q, d_world);
    return sd_v3_add(c->x, sd_quat_rotate(c->q, sd_shape_support_core(c->shape, c->verts, dl)));
}

/* The same with the body's rotation given as a matrix R (principal frame to
 * world, sd_quat_to_mat3(c->q)): two 3×3 products instead of two quaternion
 * rotations, for loops (GJK) that query one pose many times. */
SD_HD static SD_INLINE sd_vec3 sd_convex_support_core_m(const sd_convex *c, const sd_mat3 *R, sd_vec3 d_world)
{
    const sd_real(*m)[3] = R->m;
    sd_vec3 dl = sd_v3(m[0][0] * d_world.x + m[1][0] * d_world.y + m[2][0] * d_world.z,
                       m[0][1] * d_world.x + m[1][1] * d_world.y + m[2][1] * d_world.z,
                       m[0][2] * d_world.x + m[1][2] * d_world.y + m[2][2] * d_world.z);
    sd_vec3 p = sd_shape_support_core(c->shape, c->verts, dl);
    return sd_v3(c->x.x + m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z,
                 c->x.y + m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z,
                 c->x.z + m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z);
}

/* World-frame support of a posed body, swept radius included. */
SD_HD static SD_INLINE sd_vec3 sd_convex_support(const sd_convex *c, sd_vec3 d_world)
{
    sd_vec3 dl = sd_quat_rotate_inv(c->q, d_world);
    return sd_v3_add(c->x, sd_quat_rotate(c->q, sd_shape_support(c->shape, c->verts, dl)));
}

#endif
