/* sphere.h — analytic contact geometry of spheres against spheres, planes
 * and box faces. Single source (SD_HD).
 *
 * Each function fills an sd_contact_geom when the bodies overlap and returns
 * 1, else 0. The normal points from the other body (j or the wall) towards
 * sphere i; the contact point lies midway through the overlap.
 */
#ifndef SD_GEOM_SPHERE_H
#define SD_GEOM_SPHERE_H

#include "core/vec.h"

typedef struct sd_contact_geom {
    sd_vec3 n;      /* unit normal, from j (or wall) to i */
    sd_vec3 point;  /* m, contact point */
    sd_real delta;  /* m, overlap > 0 */
} sd_contact_geom;

SD_HD static SD_HOT int sd_sphere_sphere(sd_vec3 xi, sd_real ri, sd_vec3 xj, sd_real rj, sd_contact_geom *g)
{
    sd_vec3 d = sd_v3_sub(xi, xj);
    sd_real dist2 = sd_v3_norm2(d);
    sd_real rs = ri + rj;
    if (dist2 >= rs * rs)
        return 0;
    sd_real dist = sd_sqrt(dist2);
    /* coincident centres: any normal is as good; pick +z so nothing is NaN */
    g->n = dist > SD_R(0.0) ? sd_v3_scale(d, SD_R(1.0) / dist) : sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0));
    g->delta = rs - dist;
    g->point = sd_v3_madd(xi, -(ri - SD_R(0.5) * g->delta), g->n);
    return 1;
}

/* Half-space wall through point p with unit normal nw (the side it points to
 * is free space). */
SD_HD static SD_HOT int sd_sphere_plane(sd_vec3 x, sd_real r, sd_vec3 p, sd_vec3 nw, sd_contact_geom *g)
{
    sd_real s = sd_v3_dot(sd_v3_sub(x, p), nw);
    if (s >= r)
        return 0;
    g->n = nw;
    g->delta = r - s;
    g->point = sd_v3_madd(x, -(r - SD_R(0.5) * g->delta), nw);
    return 1;
}

/* One face of a box container: the rectangle of the plane axis = value
 * (axis 0, 1, 2), inward normal sign `dir` (+1 or -1), bounded by lo/hi on
 * the two other axes. A sphere whose centre projects inside the rectangle
 * meets the face plane (only from at most one radius behind it, so spheres
 * that escaped through an open face are not pulled back through a closed
 * one); otherwise it meets the rectangle's rim from the inner side only. */
SD_HD static SD_HOT int sd_sphere_box_face(sd_vec3 x, sd_real r, int axis, sd_real value, sd_real dir, sd_vec3 lo,
                                              sd_vec3 hi, sd_contact_geom *g)
{
    sd_real c[3] = {x.x, x.y, x.z};
    const sd_real l[3] = {lo.x, lo.y, lo.z};
    const sd_real h[3] = {hi.x, hi.y, hi.z};
    sd_real s = (c[axis] - value) * dir; /* signed distance on the inner side */
    if (s >= r || s <= -r)
        return 0;
    int inside = 1;
    sd_real q[3];
    for (int k = 0; k < 3; ++k) {
        if (k == axis) {
            q[k] = value;
            continue;
        }
        q[k] = sd_clamp(c[k], l[k], h[k]);
        if (q[k] != c[k])
            inside = 0;
    }
    if (inside) {
        sd_real nn[3] = {SD_R(0.0), SD_R(0.0), SD_R(0.0)};
        nn[axis] = dir;
        g->n = sd_v3(nn[0], nn[1], nn[2]);
        g->delta = r - s;
    } else {
        if (s <= SD_R(0.0))
            return 0;
        sd_vec3 d = sd_v3_sub(x, sd_v3(q[0], q[1], q[2]));
        sd_real dist2 = sd_v3_norm2(d);
        if (dist2 >= r * r || dist2 <= SD_R(0.0))
            return 0;
        sd_real dist = sd_sqrt(dist2);
        g->n = sd_v3_scale(d, SD_R(1.0) / dist);
        g->delta = r - dist;
    }
    g->point = sd_v3_madd(x, -(r - SD_R(0.5) * g->delta), g->n);
    return 1;
}

#endif
