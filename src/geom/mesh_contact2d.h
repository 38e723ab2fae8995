/* mesh_contact2d.h — the geometry of a 2D body against one plane group of
 * a triangle-mesh wall cut by the plane z = 0 (the planar mode), for
 * backend/items.h's sd_item_mesh_convex2d: the 2D counterpart of
 * geom/mesh_contact.h's plane contacts.
 *
 *  - The group's plane meets z = 0 in a line (sd_mesh2d_group_line); the
 *    body meets that line as it meets a wall line (contact/pair2d.h).
 *  - The force is weighted by w = L_clip / L (seed 000 §2.4's clipped
 *    area, one dimension down): L is the length of the body's section by
 *    the line (its chord, sd_mesh2d_chord) and L_clip the part of it on
 *    the cuts of the group's near triangles by z = 0, each a segment of
 *    the line (sd_mesh2d_trace); the contact point moves to the middle of
 *    the supported part. A body whose whole width lies on the group is
 *    unweighted (w = 1 exactly, the point unmoved), so the contacts inside
 *    a group keep their bits; at the group's end the force falls with the
 *    supported length (before issue 30 it was all or nothing as the
 *    contact point crossed the end).
 *  - The ridge rule (backend/items.h, sd_item_mesh2d_ridge_yields, as
 *    sd_item_mesh_ridge_yields for 3D bodies): at a convex edge to
 *    another group the contact with the line the body sinks deeper into
 *    gives way to the other.
 *
 * Single source (SD_HD): plain structs, fixed workspaces, compiles as C17
 * and as C++.
 */
#ifndef SD_GEOM_MESH_CONTACT2D_H
#define SD_GEOM_MESH_CONTACT2D_H

#include "geom/mesh_contact.h"
#include "shape/shape2d.h"

/* Bisection steps of a chord end: the support direction's angle to 1.5e-9
 * rad, the end to about 1e-9 of the body's size on a curved side (exact on
 * a polygon's face, where the two bracketing support points are its ends). */
#define SD_MESH2D_CHORD_ITERS 30

/* The trace of group gr's plane on z = 0 (world): the line n2 . x = n2 .
 * l0, n2 unit, towards the particle side. 0 when the group is parallel to
 * z = 0 (no line). */
SD_HD static SD_INLINE int sd_mesh2d_group_line(const sd_mesh_view *m, const sd_wall_geom *wg, uint32_t gr,
                                                sd_vec2 *l0, sd_vec2 *n2)
{
    sd_vec3 p0, nw;
    sd_mesh_group_plane(m, wg, gr, &p0, &nw);
    sd_real nl = sd_sqrt(nw.x * nw.x + nw.y * nw.y);
    if (!(nl > SD_R(1e-9)))
        return 0;
    *n2 = sd_v2(nw.x / nl, nw.y / nl);
    /* the point of the plane's trace nearest the origin: n . x = n . p0 at z = 0 */
    sd_real off = sd_v3_dot(nw, p0) / nl;
    *l0 = sd_v2(n2->x * off, n2->y * off);
    return 1;
}

/* The cut of triangle tri by z = 0 (world) as the interval [*lo, *hi] of
 * the coordinate along t; 0 when the triangle misses the plane. */
SD_HD static SD_INLINE int sd_mesh2d_trace(const sd_mesh_view *m, const sd_wall_geom *wg, uint32_t tri, sd_vec2 t,
                                           sd_real *lo, sd_real *hi)
{
    sd_vec3 v[3];
    for (int k = 0; k < 3; ++k)
        v[k] = sd_mesh_to_world(wg->q, wg->trans, m->verts[m->tris[tri][k]]);
    int n = 0;
    for (int k = 0; k < 3; ++k) {
        sd_vec3 a = v[k], b = v[(k + 1) % 3];
        if ((a.z > SD_R(0.0) && b.z > SD_R(0.0)) || (a.z < SD_R(0.0) && b.z < SD_R(0.0)))
            continue;
        /* the edge meets z = 0: at its crossing, or along it when it lies there */
        sd_real s0, s1;
        if (a.z == b.z) {
            s0 = a.x * t.x + a.y * t.y;
            s1 = b.x * t.x + b.y * t.y;
        } else {
            sd_real u = a.z / (a.z - b.z);
            s0 = s1 = (a.x + u * (b.x - a.x)) * t.x + (a.y + u * (b.y - a.y)) * t.y;
        }
        sd_real smin = s0 < s1 ? s0 : s1, smax = s0 < s1 ? s1 : s0;
        *lo = n == 0 || smin < *lo ? smin : *lo;
        *hi = n == 0 || smax > *hi ? smax : *hi;
        ++n;
    }
    return n > 0;
}

/* One end of the chord that the line (l0, n2) cuts from body c: the point
 * of the body on the line furthest along u (+t or -t), found as the
 * support point along cos(a) u - sin(a) n2 whose height over the line is
 * zero (the height falls from the top, a = -pi/2, to the deepest point, a
 * = pi/2), bisected on a, the end taken where the chord between the two
 * bracketing support points crosses the line. */
SD_HD static SD_INLINE sd_vec2 sd_mesh2d_chord_end(const sd_convex2d *c, sd_vec2 l0, sd_vec2 n2, sd_vec2 u,
                                                   sd_vec2 ptop, sd_real htop, sd_vec2 pbot, sd_real hbot)
{
    sd_real a0 = SD_R(-1.5707963267948966), a1 = SD_R(1.5707963267948966);
    for (int it = 0; it < SD_MESH2D_CHORD_ITERS; ++it) {
        if (ptop.x == pbot.x && ptop.y == pbot.y)
            break; /* one support point: a corner on the line */
        sd_real a = SD_R(0.5) * (a0 + a1);
        sd_vec2 d = sd_v2_sub(sd_v2_scale(u, sd_cos(a)), sd_v2_scale(n2, sd_sin(a)));
        sd_vec2 p = sd_convex2d_support(c, d);
        sd_real h = sd_v2_dot(sd_v2_sub(p, l0), n2);
        if (h >= SD_R(0.0))
            a0 = a, ptop = p, htop = h;
        else
            a1 = a, pbot = p, hbot = h;
    }
    sd_real w = htop > SD_R(0.0) ? htop / (htop - hbot) : SD_R(0.0);
    return sd_v2_add(ptop, sd_v2_scale(sd_v2_sub(pbot, ptop), w));
}

/* The chord that the line (l0, n2) cuts from body c, as the interval
 * [*s0, *s1] of the coordinate along t = (-n2.y, n2.x); 0 when the line
 * does not cross the body. */
SD_HD static SD_INLINE int sd_mesh2d_chord(const sd_convex2d *c, sd_vec2 l0, sd_vec2 n2, sd_real *s0, sd_real *s1)
{
    sd_vec2 t = sd_v2(-n2.y, n2.x);
    sd_vec2 ptop = sd_convex2d_support(c, n2), pbot = sd_convex2d_support(c, sd_v2_neg(n2));
    sd_real htop = sd_v2_dot(sd_v2_sub(ptop, l0), n2), hbot = sd_v2_dot(sd_v2_sub(pbot, l0), n2);
    if (!(htop > SD_R(0.0) && hbot < SD_R(0.0)))
        return 0;
    *s1 = sd_v2_dot(sd_mesh2d_chord_end(c, l0, n2, t, ptop, htop, pbot, hbot), t);
    *s0 = sd_v2_dot(sd_mesh2d_chord_end(c, l0, n2, sd_v2_neg(t), ptop, htop, pbot, hbot), t);
    return *s1 > *s0;
}

/* The length of [s0, s1] on the cuts of the near triangles tl (nt), and
 * the sum of the covered parts' middles times their lengths in *mom. */
SD_HD static SD_INLINE sd_real sd_mesh2d_cover(const sd_mesh_view *m, const sd_wall_geom *wg, const uint32_t *tl,
                                               uint32_t nt, sd_vec2 t, sd_real s0, sd_real s1, sd_real *mom)
{
    sd_real len = SD_R(0.0);
    *mom = SD_R(0.0);
    for (uint32_t k = 0; k < nt; ++k) {
        sd_real lo, hi;
        if (!sd_mesh2d_trace(m, wg, tl[k], t, &lo, &hi))
            continue;
        lo = lo > s0 ? lo : s0;
        hi = hi < s1 ? hi : s1;
        if (hi > lo) {
            len += hi - lo;
            *mom += (hi - lo) * SD_R(0.5) * (lo + hi);
        }
    }
    return len;
}

/* The weight of a 2D body's contact with group gr's line (l0, n2) through
 * its near triangles tl (nt), and in *shift the move of the contact point
 * (world, m, z = 0): 1 and no move when the body's whole width along the
 * line lies on the triangles' cuts (two support points), else the share
 * of its chord on them, the point moved to the middle of that share. */
SD_HD static SD_INLINE sd_real sd_mesh2d_weight(const sd_mesh_view *m, const sd_wall_geom *wg, const uint32_t *tl,
                                                uint32_t nt, const sd_convex2d *c, sd_vec2 l0, sd_vec2 n2,
                                                sd_vec3 *shift)
{
    *shift = sd_v3_zero();
    sd_vec2 t = sd_v2(-n2.y, n2.x);
    sd_real w0 = sd_v2_dot(sd_convex2d_support(c, sd_v2_neg(t)), t), w1 = sd_v2_dot(sd_convex2d_support(c, t), t);
    sd_real mom, s0, s1;
    /* the width covered to rounding (the cuts of neighbours meet at a
     * crossing computed twice): the contact inside a group, as before */
    if (sd_mesh2d_cover(m, wg, tl, nt, t, w0, w1, &mom) >= (w1 - w0) * (SD_R(1.0) - SD_R(1e-9)))
        return SD_R(1.0);
    if (!sd_mesh2d_chord(c, l0, n2, &s0, &s1))
        return SD_R(0.0);
    sd_real len = sd_mesh2d_cover(m, wg, tl, nt, t, s0, s1, &mom);
    if (!(len > SD_R(0.0)))
        return SD_R(0.0);
    if (len >= (s1 - s0) * (SD_R(1.0) - SD_R(1e-9)))
        return SD_R(1.0); /* the chord on the group: inside it, as above */
    sd_real mid = mom / len - SD_R(0.5) * (s0 + s1);
    *shift = sd_v3(t.x * mid, t.y * mid, SD_R(0.0));
    sd_real w = len / (s1 - s0);
    return w < SD_R(1.0) ? w : SD_R(1.0);
}

#endif
