/* walls.h — the walls as one module (single source, SD_HD): wall kinds, the
 * features of a wall, and the geometry every user of a wall asks for.
 *
 * A wall is a list of features; a contact is always between a particle and
 * one feature, and the feature's index is the wall pair's sub-index (its
 * history key, broad/pairs.h). A plane has one feature (0); a box has its
 * six faces, face f lying on axis f / 2, at lo (f even, inward normal +e) or
 * hi (f odd, inward normal -e), the bit (1 << f) of open_faces set when the
 * face is left open (the SD_BOX_* flags of shapedem.h). A mesh (seed 000
 * §2.4) has one feature per plane group: too many to enumerate here, so
 * its features are found by its facet bins (dynamics/meshwall.h,
 * broad/bins.c) and its geometry carries its pose (q, trans: world =
 * R(q) x_mesh + trans) and the index of its mesh view.
 *
 * Invariant: this header is the only place where box faces are enumerated
 * and turned into planes, lines and sphere-face call data; the broad phase
 * (broad/bins.c), the item functions (backend/) and the grid solver's
 * kernel (grid/stencil.h) all call it, so they see the same wall. Plain
 * structs and reals in and out, no allocation, compiles as C and C++.
 */
#ifndef SD_DYNAMICS_WALLS_H
#define SD_DYNAMICS_WALLS_H

#include "core/quat.h"
#include "core/vec.h"
#include "core/vec2.h"

/* X(NAME, name, feature count, meaning) */
#define SD_WALL_KINDS(X)                                                                   \
    X(PLANE, plane, 1, "an infinite plane: the half-space its normal points away from")     \
    X(BOX, box, 6, "a box container: its closed faces, seen from inside")                  \
    X(MESH, mesh, 0, "a triangle mesh: one feature per plane group (dynamics/meshwall.h)")            \
    X(DRUM, drum, 3, "a rotating cylindrical drum seen from inside: mantle (0) and end caps (1, 2)")

enum sd_wall_kind {
#define SD_X_WALL(NAME, name, nf, doc) SD_WALL_##NAME,
    SD_WALL_KINDS(SD_X_WALL)
#undef SD_X_WALL
    SD_WALL_KIND_COUNT
};

/* The most features a wall of any kind has (the sub-index range). */
#define SD_WALL_MAX_FEATURES 6
/* Faces of a box. */
#define SD_WALL_BOX_FACES 6

/* The geometry of a wall, a POD a device view can carry. */
typedef struct sd_wall_geom {
    int kind;               /* enum sd_wall_kind */
    sd_vec3 point, normal;  /* m, -: plane (a box's point is its centre, for wall torques) */
    sd_vec3 lo, hi;         /* m: box corners */
    unsigned open_faces;    /* box: bit f set when face f is open */
    /* mesh: pose, centre of its velocity field (v(c) = velocity + omega x
     * (c - centre), sd_wall_view), mesh view index */
    sd_quat q;
    sd_vec3 trans, centre;
    int mesh;
} sd_wall_geom;

/* A drum (SD_WALL_DRUM) keeps its geometry in the common members: point =
 * the middle of its axis (m), normal = the unit axis, lo.x = radius (m),
 * lo.y = half length (m), open_faces bit 1 / bit 2 = end cap at
 * point - half normal / point + half normal left out (a drum open at both
 * ends runs with a periodic axis), centre = point (the velocity field is
 * omega x (c - centre), sd_wall_view.omega = 2 pi rpm / 60 along the axis).
 * Its mantle's feature plane is the tangent plane at the particle's
 * radial projection: exact for a sphere (the contact is along the radius),
 * a plane approximation of the curved wall for shapes (error ~ size^2 / R). */
#define SD_WALL_DRUM_CAP_LO 2u /* open_faces bit of cap 1 */
#define SD_WALL_DRUM_CAP_HI 4u /* open_faces bit of cap 2 */

/* Axial coordinate s and radial vector d (perpendicular to the axis) of x
 * in a drum. */
SD_HD static SD_INLINE sd_real sd_wall_drum_coords(const sd_wall_geom *w, sd_vec3 x, sd_vec3 *d)
{
    sd_vec3 r = sd_v3_sub(x, w->point);
    sd_real s = sd_v3_dot(r, w->normal);
    *d = sd_v3_sub(r, sd_v3_scale(w->normal, s));
    return s;
}

/* The path (distance or angle per unit speed) and speed fraction of a
 * motion that starts at `start` and whose speed rises linearly from 0 to
 * 1 over `ramp` (s; 0 = at once): speed = clamp((t - start) / ramp, 0, 1),
 * path its integral. The mesh motions (world/mesh.c) and the drum's
 * spin-up (world/process.c) both follow it. */
SD_HD static SD_INLINE double sd_wall_ramp_path(double t, double start, double ramp, double *speed)
{
    double tau = t - start;
    if (tau <= 0) {
        *speed = 0;
        return 0;
    }
    if (ramp > 0 && tau < ramp) {
        *speed = tau / ramp;
        return 0.5 * tau * tau / ramp;
    }
    *speed = 1;
    return ramp > 0 ? tau - 0.5 * ramp : tau;
}

/* The call data of one box face: the plane axis = value with inward
 * normal sign dir (+1 at lo, -1 at hi), as geom/sphere.h's
 * sd_sphere_box_face takes it. */
typedef struct sd_wall_face {
    int axis;
    sd_real value;
    sd_real dir;
} sd_wall_face;

SD_HD static SD_INLINE sd_real sd_wall_comp(sd_vec3 v, int axis)
{
    return axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
}

/* 1 when face f of a box with these open faces is closed (a feature). */
SD_HD static SD_INLINE int sd_wall_box_face_closed(unsigned open_faces, int f)
{
    return !(open_faces & (1u << f));
}

/* Signed distance of x from the plane of box face f, positive inside. */
SD_HD static SD_INLINE sd_real sd_wall_box_face_gap(sd_vec3 lo, sd_vec3 hi, int f, sd_vec3 x)
{
    int axis = f / 2;
    return (f & 1) ? sd_wall_comp(hi, axis) - sd_wall_comp(x, axis) : sd_wall_comp(x, axis) - sd_wall_comp(lo, axis);
}

SD_HD static SD_INLINE sd_wall_face sd_wall_box_face_of(sd_vec3 lo, sd_vec3 hi, int f)
{
    sd_wall_face d;
    d.axis = f / 2;
    d.value = (f & 1) ? sd_wall_comp(hi, d.axis) : sd_wall_comp(lo, d.axis);
    d.dir = (f & 1) ? SD_R(-1.0) : SD_R(1.0);
    return d;
}

/* Number of feature slots of a wall (closed or not: sub-indices are the
 * slot numbers, so they do not change when a face opens). */
SD_HD static SD_INLINE int sd_wall_feature_count(const sd_wall_geom *w)
{
    if (w->kind == SD_WALL_MESH)
        return 0; /* plane groups come from the facet bins */
    if (w->kind == SD_WALL_DRUM)
        return 3;
    return w->kind == SD_WALL_BOX ? SD_WALL_BOX_FACES : 1;
}

/* 1 when feature f exists (a closed face, or the plane). */
SD_HD static SD_INLINE int sd_wall_feature_exists(const sd_wall_geom *w, int f)
{
    if (w->kind == SD_WALL_DRUM)
        return f == 0 || (f <= 2 && !(w->open_faces & (1u << f)));
    return w->kind == SD_WALL_BOX ? sd_wall_box_face_closed(w->open_faces, f) : f == 0;
}

/* The broad phase's test: feature f is within reach (bounding radius plus
 * skin) of a particle at x. A plane: the centre is less than reach in front
 * of it (or behind it). A box face: within reach on either side of its
 * plane (a particle that left through an open face is not caught by the
 * face behind it: sd_sphere_box_face's one-radius rule). */
SD_HD static SD_INLINE int sd_wall_feature_near(const sd_wall_geom *w, int f, sd_vec3 x, sd_real reach)
{
    if (w->kind == SD_WALL_PLANE)
        return sd_v3_dot(sd_v3_sub(x, w->point), w->normal) < reach;
    if (w->kind == SD_WALL_DRUM) {
        sd_vec3 d;
        sd_real s = sd_wall_drum_coords(w, x, &d), rho = sd_v3_norm(d), R = w->lo.x, h = w->lo.y;
        if (f == 0)
            return R - rho < reach && rho - R < reach && sd_fabs(s) < h + reach;
        sd_real gap = f == 1 ? s + h : h - s; /* > 0 inside */
        return gap < reach && gap > -reach && rho < R + reach;
    }
    sd_real s = sd_wall_box_face_gap(w->lo, w->hi, f, x);
    return s < reach && s > -reach;
}

/* The plane of feature f: the plane wall itself, or a closed box face
 * (inward normal, through the projection of x). Returns 0 when x does not
 * project inside the face's rectangle: a shape beside a box face meets it
 * only through the neighbouring face (box rims are not resolved for
 * shapes). */
SD_HD static SD_INLINE int sd_wall_feature_plane(const sd_wall_geom *w, int f, sd_vec3 x, sd_vec3 *p0, sd_vec3 *n)
{
    if (w->kind == SD_WALL_PLANE) {
        *p0 = w->point;
        *n = w->normal;
        return 1;
    }
    if (w->kind == SD_WALL_DRUM) {
        sd_vec3 d;
        sd_real s = sd_wall_drum_coords(w, x, &d), rho = sd_v3_norm(d), R = w->lo.x, h = w->lo.y;
        if (f == 0) {
            if (!(rho > SD_R(0.0)) || sd_fabs(s) > h)
                return 0; /* on the axis (no direction) or beyond a cap */
            sd_vec3 u = sd_v3_scale(d, SD_R(1.0) / rho);
            *p0 = sd_v3_add(sd_v3_add(w->point, sd_v3_scale(w->normal, s)), sd_v3_scale(u, R));
            *n = sd_v3_scale(u, SD_R(-1.0)); /* inward: towards the axis */
            return 1;
        }
        if (rho > R)
            return 0;
        sd_real sign = f == 1 ? SD_R(-1.0) : SD_R(1.0);
        *p0 = sd_v3_add(x, sd_v3_scale(w->normal, sign * h - s));
        *n = sd_v3_scale(w->normal, -sign); /* cap 1 faces +axis, cap 2 faces -axis */
        return 1;
    }
    int axis = f / 2;
    sd_real lo[3] = {w->lo.x, w->lo.y, w->lo.z}, hi[3] = {w->hi.x, w->hi.y, w->hi.z}, c[3] = {x.x, x.y, x.z};
    for (int k = 0; k < 3; ++k)
        if (k != axis && (c[k] < lo[k] || c[k] > hi[k]))
            return 0;
    sd_real nn[3] = {0, 0, 0}, pp[3] = {c[0], c[1], c[2]};
    nn[axis] = (f & 1) ? SD_R(-1.0) : SD_R(1.0);
    pp[axis] = (f & 1) ? hi[axis] : lo[axis];
    *p0 = sd_v3(pp[0], pp[1], pp[2]);
    *n = sd_v3(nn[0], nn[1], nn[2]);
    return 1;
}

/* The line of feature f in the plane z = 0 (planar mode): a plane wall, or
 * an x or y face of a box (inward normal). Returns 0 when x lies beyond the
 * face's ends (the neighbouring face takes it), and for the z faces, which
 * do not exist in the plane. */
SD_HD static SD_INLINE int sd_wall_feature_line(const sd_wall_geom *w, int f, sd_vec3 x, sd_vec2 *p0, sd_vec2 *n)
{
    if (w->kind == SD_WALL_DRUM)
        return 0; /* 3D only (refused in the planar mode) */
    if (w->kind == SD_WALL_PLANE) {
        *p0 = sd_v2(w->point.x, w->point.y);
        *n = sd_v2(w->normal.x, w->normal.y);
        return 1;
    }
    int axis = f / 2;
    sd_real sign = (f & 1) ? SD_R(-1.0) : SD_R(1.0);
    if (axis == 0) {
        if (x.y < w->lo.y || x.y > w->hi.y)
            return 0;
        *p0 = sd_v2((f & 1) ? w->hi.x : w->lo.x, x.y);
        *n = sd_v2(sign, SD_R(0.0));
    } else if (axis == 1) {
        if (x.x < w->lo.x || x.x > w->hi.x)
            return 0;
        *p0 = sd_v2(x.x, (f & 1) ? w->hi.y : w->lo.y);
        *n = sd_v2(SD_R(0.0), sign);
    } else {
        return 0;
    }
    return 1;
}

/* 1 when a wall reaches across the periodic axis a (0, 1, 2) of a domain:
 * a plane whose normal has a component along a, or a box whose closed
 * faces on that axis would cut the periodic images apart (any box spanning
 * the axis: its faces are planes normal to a). Used to refuse the scene. */
SD_HD static SD_INLINE int sd_wall_crosses_axis(const sd_wall_geom *w, int a)
{
    if (w->kind == SD_WALL_MESH)
        return 0; /* a mesh is a body inside the domain; its facets are not wrapped */
    if (w->kind == SD_WALL_DRUM) /* the mantle is invariant along its own axis only; caps cut it */
        return sd_fabs(sd_wall_comp(w->normal, a)) < SD_R(1.0) - SD_R(1e-12) ||
               (w->open_faces & (SD_WALL_DRUM_CAP_LO | SD_WALL_DRUM_CAP_HI)) != (SD_WALL_DRUM_CAP_LO | SD_WALL_DRUM_CAP_HI);
    if (w->kind == SD_WALL_PLANE)
        return sd_wall_comp(w->normal, a) != SD_R(0.0);
    return sd_wall_box_face_closed(w->open_faces, 2 * a) || sd_wall_box_face_closed(w->open_faces, 2 * a + 1);
}

#endif
