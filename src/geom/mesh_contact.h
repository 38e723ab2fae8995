/* mesh_contact.h — the geometry of a body against one plane group of a
 * triangle-mesh wall (seed 000 §2.4), for the mesh items of
 * backend/items.h.
 *
 *  - A sphere meets the group at the closest point of the group's near
 *    triangles. On a face: the plane contact (normal = the group's normal,
 *    the overlap from the plane). On an edge or a corner: a point contact
 *    along the line from that point to the centre, made only when the
 *    feature is active on that triangle (geom/trimesh.h's marks), so a
 *    sphere rolling across an inactive (coplanar or concave) seam feels only
 *    the faces beside it and a convex edge or corner contact appears once.
 *    A centre right above an inactive seam (the point on the seam is its
 *    projection) is a face contact: the plane continues across the seam.
 *    An active edge or corner contacts only when the centre lies in its
 *    Voronoi region against the facets of the other groups beside it
 *    (sd_mesh_feature_owns): over a neighbour's face that neighbour's
 *    group makes the one contact, so a sphere rolling over a ridge is
 *    never pushed by a face and an edge at once.
 *  - Any other body meets the group's plane as it would meet an infinite
 *    plane (contact/), its force weighted by w = A_clip / A, where A is the
 *    area of the body's section by the plane and A_clip the part of it
 *    inside the group's triangles, each clipped by Sutherland-Hodgman
 *    (geom/clip.h; seed 000 Algorithm VII); the contact point moves by the
 *    shift of the clipped area's centroid from the section's. Inside a
 *    group w = 1 to rounding, so a body crossing the seams of one plane
 *    feels one flat facet; at the group's rim the force falls with the
 *    supported area. A polyhedron's section is exact (the crossings of
 *    every pair of its vertices on the two sides of the plane, hulled);
 *    other shapes use the disc of radius sqrt(2 R_eq delta) about the
 *    contact point (the Hertzian patch of the equivalent sphere). At a
 *    convex edge to another group the contact of the plane the body sinks
 *    deeper into gives way to the other (backend/items.h,
 *    sd_item_mesh_ridge_yields, with sd_mesh_edge_convex here). Beyond an
 *    open edge the body meets the edge instead (the rim rule, below).
 *
 * Everything is computed in the mesh frame (the particle mapped into it);
 * normals and points go back to the world frame. Single source (SD_HD):
 * plain structs, fixed workspaces, compiles as C17 and as C++.
 */
#ifndef SD_GEOM_MESH_CONTACT_H
#define SD_GEOM_MESH_CONTACT_H

#include "dynamics/meshwall.h"
#include "dynamics/walls.h"
#include "geom/clip.h"
#include "geom/convex_contact.h"
#include "shape/support.h"
#include "geom/sphere.h"
#include "shape/shape.h"

#include <string.h>

/* Relative size below which a point's lateral offset from the plane
 * normal counts as none (a centre above a seam). */
#define SD_MESH_SEAM_TOL SD_R(1e-9)

/* The plane of group gr in the world frame: point p0, unit normal nw. */
SD_HD static SD_INLINE void sd_mesh_group_plane(const sd_mesh_view *m, const sd_wall_geom *wg, uint32_t gr,
                                                sd_vec3 *p0, sd_vec3 *nw)
{
    sd_vec3 n = m->group_normal[gr];
    *nw = sd_quat_rotate(wg->q, n);
    *p0 = sd_mesh_to_world(wg->q, wg->trans, sd_v3_scale(n, m->group_offset[gr]));
}

/* The thin-wall rule (issue 30; probe 3 finding 10): a plane group of a
 * closed part of the mesh acts only on a particle whose centre lies in
 * front of its plane, s = n . x_m - offset > 0 (s: the centre's height in
 * the mesh frame). Behind a closed part's face lies the part's solid, so
 * a centre there has come through the part. A slab thinner than the
 * particle used to take a particle sunk into its near face deeper than the
 * slab is thick as overlapped by its far face by nearly its whole size,
 * and that face pushed it on through (a 1 mm sphere through a 0.2 mm slab
 * from 5 m/s). With the rule only the face it entered pushes it, back out
 * the way it came, for as long as its centre has not crossed that face: a
 * closed part of any thickness holds a particle whose overlap stays below
 * the depth of its centre under its surface (a sphere's radius; the
 * overlap guard stops a run at half of it by default). Open parts (a
 * sheet, a hopper) keep the contact behind the plane as before (a sphere
 * to its radius behind), so a particle on a sheet's wrong side is taken as
 * overlapped and the guard names the side. tl: the group's near
 * triangles (all of one part: a plane group grows through shared manifold
 * edges only). */
SD_HD static SD_INLINE int sd_mesh_front(const sd_mesh_view *m, const uint32_t *tl, uint32_t nt, sd_real s)
{
    return s > SD_R(0.0) || nt == 0 || !(m->flags[tl[0]] & SD_MESH_CLOSED_BIT);
}

/* sd_mesh_front for a particle centred at x (world frame) against group gr. */
SD_HD static SD_INLINE int sd_mesh_front_at(const sd_mesh_view *m, const sd_wall_geom *wg, uint32_t gr,
                                            const uint32_t *tl, uint32_t nt, sd_vec3 x)
{
    sd_vec3 xm = sd_mesh_to_frame(wg->q, wg->trans, x);
    return sd_mesh_front(m, tl, nt, sd_v3_dot(m->group_normal[gr], xm) - m->group_offset[gr]);
}

/* The corner of triangle nb that is not on edge (ia, ib). */
SD_HD static SD_INLINE uint32_t sd_mesh_far_corner(const sd_mesh_view *m, uint32_t nb, uint32_t ia, uint32_t ib)
{
    const uint32_t *nv = m->tris[nb];
    return nv[0] != ia && nv[0] != ib ? nv[0] : (nv[1] != ia && nv[1] != ib ? nv[1] : nv[2]);
}

/* The direction in the plane of triangle nb, square to its edge a -> b,
 * pointing into nb (from the edge towards its far corner c). */
SD_HD static SD_INLINE sd_vec3 sd_mesh_into(sd_vec3 a, sd_vec3 b, sd_vec3 c)
{
    sd_vec3 e = sd_v3_sub(b, a), u = sd_v3_sub(c, a);
    return sd_v3_sub(u, sd_v3_scale(e, sd_v3_dot(u, e) / sd_v3_dot(e, e)));
}

/* The Voronoi rule of active features (issue 14: no double push at a
 * convex edge between plane groups). xm's closest point on triangle t is
 * p, on t's active edge or corner f. The feature makes the contact only
 * when p is also the closest point of the facets of the other groups
 * beside it: for an edge, xm - p must not point over the neighbour's face
 * ((xm - p) . u <= 0, u into the neighbour square to the edge); for a
 * corner v, (xm - v) . (w - v) <= 0 for every edge v -> w of the facets
 * around it (walked through the neighbour links both ways, at most 64
 * facets each). Otherwise the point of the mesh nearest the centre lies
 * on another group's face or feature and that group makes the contact. */
SD_HD static SD_INLINE int sd_mesh_feature_owns(const sd_mesh_view *m, uint32_t t, int f, sd_vec3 p, sd_vec3 xm,
                                                sd_real r)
{
    if (!m->nbr)
        return 1;
    sd_vec3 d = sd_v3_sub(xm, p);
    const uint32_t *tv = m->tris[t];
    if (f < SD_CLIP_CORNER0) {
        int k = f - SD_CLIP_EDGE0;
        uint32_t nb = m->nbr[t][k];
        if (nb == UINT32_MAX || m->group[nb] == m->group[t])
            return 1;
        uint32_t ia = tv[k], ib = tv[(k + 1) % 3];
        sd_vec3 u = sd_mesh_into(m->verts[ia], m->verts[ib], m->verts[sd_mesh_far_corner(m, nb, ia, ib)]);
        /* right above the edge the neighbour's face claims the centre (its
         * seam tolerance), so the edge gives way there too */
        return !(sd_v3_dot(d, u) > -SD_MESH_SEAM_TOL * r * sd_v3_norm(u));
    }
    uint32_t vtx = tv[f - SD_CLIP_CORNER0];
    sd_vec3 v = m->verts[vtx];
    for (int dir = 0; dir < 2; ++dir) {
        uint32_t cur = t;
        for (int step = 0; step < 64; ++step) {
            const uint32_t *cv = m->tris[cur];
            int kv = cv[0] == vtx ? 0 : (cv[1] == vtx ? 1 : 2);
            /* the edges of other groups' facets (t's own group found the corner nearest) */
            for (int q = 1; q <= 2 && m->group[cur] != m->group[t]; ++q) {
                sd_vec3 ev = sd_v3_sub(m->verts[cv[(kv + q) % 3]], v);
                if (sd_v3_dot(d, ev) > -SD_MESH_SEAM_TOL * r * sd_v3_norm(ev))
                    return 0;
            }
            /* on to the facet across the edge leaving the corner (dir 0) or entering it (dir 1) */
            uint32_t nb = m->nbr[cur][dir == 0 ? kv : (kv + 2) % 3];
            if (nb == UINT32_MAX || nb == t)
                break;
            cur = nb;
        }
    }
    return 1;
}

/* 1 when feature f (sd_clip_closest's code) of triangle t lies on a free
 * (boundary) edge: the edge itself, or a corner at the end of one. Past a
 * free edge there is no wall behind the plane, so a body below the
 * plane's level meets the edge as one above it does (the rim rule). */
SD_HD static SD_INLINE int sd_mesh_feature_free(const sd_mesh_view *m, uint32_t t, int f)
{
    if (!m->nbr || f == SD_CLIP_FACE)
        return 0;
    if (f < SD_CLIP_CORNER0)
        return m->nbr[t][f - SD_CLIP_EDGE0] == UINT32_MAX;
    int k = f - SD_CLIP_CORNER0; /* edges k -> k + 1 and k + 2 -> k meet at corner k */
    return m->nbr[t][k] == UINT32_MAX || m->nbr[t][(k + 2) % 3] == UINT32_MAX;
}

/* A sphere (centre x, radius r, world frame) against group gr through its
 * nt near triangles tl. 1 and *g filled when touching. */
SD_HD static SD_INLINE int sd_mesh_sphere_geom(const sd_mesh_view *m, const sd_wall_geom *wg, uint32_t gr,
                                               const uint32_t *tl, uint32_t nt, sd_vec3 x, sd_real r,
                                               sd_contact_geom *g)
{
    sd_vec3 xm = sd_mesh_to_frame(wg->q, wg->trans, x);
    sd_vec3 n = m->group_normal[gr];
    sd_real s = sd_v3_dot(n, xm) - m->group_offset[gr];
    if (s >= r || s <= -r || nt == 0)
        return 0; /* apart, or behind the plane by a radius (it left through the back) */
    sd_real best = SD_R(-1.0);
    sd_vec3 bp = xm;
    int bf = 0;
    uint32_t bt = 0;
    for (uint32_t k = 0; k < nt; ++k) {
        uint32_t t = tl[k];
        const uint32_t *tv = m->tris[t];
        int f;
        sd_vec3 p = sd_clip_closest(xm, m->verts[tv[0]], m->verts[tv[1]], m->verts[tv[2]], &f);
        sd_real d2 = sd_v3_norm2(sd_v3_sub(xm, p));
        if (best < 0 || d2 < best) {
            best = d2;
            bp = p;
            bf = f;
            bt = t;
        }
    }
    if (!(best < r * r))
        return 0;
    sd_vec3 d = sd_v3_sub(xm, bp);
    sd_vec3 lat = sd_v3_sub(d, sd_v3_scale(n, sd_v3_dot(d, n)));
    int face = bf == SD_CLIP_FACE || sd_v3_norm2(lat) <= sd_sq(SD_MESH_SEAM_TOL * r);
    sd_vec3 nm;
    sd_real delta;
    if (face) {
        if (!(s > -r) || !sd_mesh_front(m, tl, nt, s))
            return 0;
        nm = n;
        delta = r - s;
    } else {
        unsigned bit = bf >= SD_CLIP_CORNER0 ? SD_MESH_CORNER_BIT(bf - SD_CLIP_CORNER0) : SD_MESH_EDGE_BIT(bf - SD_CLIP_EDGE0);
        if (!(m->flags[bt] & bit))
            return 0; /* inactive: the faces beside it make the contact */
        if (!(s > SD_R(0.0)) && !sd_mesh_feature_free(m, bt, bf))
            return 0; /* behind the plane at a joined edge: the faces make it (or it is inside) */
        if (!sd_mesh_feature_owns(m, bt, bf, bp, xm, r))
            return 0; /* the centre is over a neighbouring group's face: that group's contact */
        sd_real dist = sd_sqrt(best);
        nm = sd_v3_scale(d, SD_R(1.0) / dist);
        delta = r - dist;
    }
    g->n = sd_quat_rotate(wg->q, nm);
    g->delta = delta;
    g->point = sd_v3_madd(x, -(r - SD_R(0.5) * delta), g->n);
    return 1;
}

/* 1 when q lies in triangle t projected on the plane basis (e1, e2). */
SD_HD static SD_INLINE int sd_mesh_in_triangle(sd_vec2 q, const sd_vec2 t[3])
{
    int pos = 0, neg = 0;
    for (int k = 0; k < 3; ++k) {
        sd_vec2 a = t[k], b = t[(k + 1) % 3];
        sd_real c = sd_clip_cross(sd_v2(b.x - a.x, b.y - a.y), sd_v2(q.x - a.x, q.y - a.y));
        pos |= c > 0;
        neg |= c < 0;
    }
    return !(pos && neg);
}

/* The section of posed polyhedron core c (vertices in the world frame
 * through its pose) by the plane n . x = off of the mesh frame, in the
 * plane basis (e1, e2), hulled into sec; returns its vertex count. */
SD_HD static SD_INLINE int sd_mesh_poly_section(const sd_convex *c, const sd_wall_geom *wg, sd_vec3 n, sd_real off,
                                                sd_vec3 e1, sd_vec3 e2, sd_vec2 *sec)
{
    enum { MAXV = 64 };
    const sd_shape *sh = c->shape;
    uint32_t nv = sh->vcount < (uint32_t)MAXV ? sh->vcount : (uint32_t)MAXV;
    sd_vec3 vm[MAXV];
    sd_real hv[MAXV];
    for (uint32_t k = 0; k < nv; ++k) {
        sd_vec3 vw = sd_v3_add(c->x, sd_quat_rotate(c->q, sd_v3_add(c->verts[sh->vstart + k], sh->offset)));
        vm[k] = sd_mesh_to_frame(wg->q, wg->trans, vw);
        hv[k] = sd_v3_dot(n, vm[k]) - off;
    }
    /* every crossing goes into sec; a full workspace is hulled (a section
     * has few corners) and filling goes on, so no crossing is left out */
    int np = 0;
    for (uint32_t i = 0; i < nv; ++i) {
        if (hv[i] > 0)
            continue;
        for (uint32_t j = 0; j < nv; ++j) {
            if (hv[i] == 0 ? j > 0 : !(hv[j] > 0))
                continue;
            sd_vec3 p = vm[i];
            if (hv[i] < 0) {
                /* the segment between two points of a convex body lies in
                 * it: every crossing is in the section, and the section's
                 * corners (crossings of its edges) are among them */
                sd_real u = hv[i] / (hv[i] - hv[j]);
                p = sd_v3_add(vm[i], sd_v3_scale(sd_v3_sub(vm[j], vm[i]), u));
            }
            if (np == SD_CLIP_MAX && (np = sd_clip_hull(sec, np)) == SD_CLIP_MAX)
                return np; /* SD_CLIP_MAX corners already: the section as it is */
            sec[np++] = sd_v2(sd_v3_dot(p, e1), sd_v3_dot(p, e2));
        }
    }
    return sd_clip_hull(sec, np);
}

/* The area weight of a body's contact with group gr (seed 000 §2.4): sec
 * (ns vertices, counter-clockwise, plane basis e1, e2 of the group's mesh
 * normal) clipped by the group's near triangles. Returns w in [0, 1] and
 * in *shift the move of the centroid (world frame, m). When the section
 * has no area (a corner or an edge just touching), w is 1 or 0 as the
 * point q (plane basis) lies on a triangle or not. */
SD_HD static SD_INLINE sd_real sd_mesh_clip_weight(const sd_mesh_view *m, const sd_wall_geom *wg, const uint32_t *tl,
                                                   uint32_t nt, sd_vec3 e1, sd_vec3 e2, const sd_vec2 *sec, int ns,
                                                   sd_vec2 q, sd_vec3 *shift)
{
    *shift = sd_v3_zero();
    sd_vec2 c0 = sd_v2(SD_R(0.0), SD_R(0.0)); /* set by sd_clip_area when ns >= 3; zero keeps -Wmaybe-uninitialized quiet */
    sd_real a0 = ns >= 3 ? sd_clip_area(sec, ns, &c0) : SD_R(0.0);
    sd_real asum = SD_R(0.0), cx = SD_R(0.0), cy = SD_R(0.0);
    int inside = 0;
    for (uint32_t k = 0; k < nt; ++k) {
        const uint32_t *tv = m->tris[tl[k]];
        sd_vec2 t[3];
        for (int v = 0; v < 3; ++v)
            t[v] = sd_v2(sd_v3_dot(m->verts[tv[v]], e1), sd_v3_dot(m->verts[tv[v]], e2));
        if (sd_clip_cross(sd_v2(t[1].x - t[0].x, t[1].y - t[0].y), sd_v2(t[2].x - t[0].x, t[2].y - t[0].y)) < 0) {
            sd_vec2 tmp = t[1];
            t[1] = t[2];
            t[2] = tmp;
        }
        if (!(a0 > 0)) {
            inside |= sd_mesh_in_triangle(q, t);
            continue;
        }
        sd_vec2 out[SD_CLIP_MAX + 3];
        int no = sd_clip_triangle(sec, ns, t, out);
        sd_vec2 cc;
        sd_real a = sd_clip_area(out, no, &cc);
        if (a > 0) {
            asum += a;
            cx += a * cc.x;
            cy += a * cc.y;
        }
    }
    if (!(a0 > 0))
        return inside ? SD_R(1.0) : SD_R(0.0);
    if (!(asum > 0))
        return SD_R(0.0);
    sd_real w = asum / a0;
    w = w > SD_R(1.0) ? SD_R(1.0) : w;
    sd_real dx = cx / asum - c0.x, dy = cy / asum - c0.y;
    *shift = sd_quat_rotate(wg->q, sd_v3_add(sd_v3_scale(e1, dx), sd_v3_scale(e2, dy)));
    return w;
}

/* A disc of radius a about point p (mesh frame) in the plane basis: a
 * 16-gon, counter-clockwise. */
SD_HD static SD_INLINE int sd_mesh_disc(sd_vec3 p, sd_real a, sd_vec3 e1, sd_vec3 e2, sd_vec2 *sec)
{
    /* cos and sin of k pi / 8 */
    const sd_real c8[16] = {SD_R(1.0), SD_R(0.9238795325112867), SD_R(0.7071067811865476), SD_R(0.3826834323650898),
                            SD_R(0.0), SD_R(-0.3826834323650898), SD_R(-0.7071067811865476), SD_R(-0.9238795325112867),
                            SD_R(-1.0), SD_R(-0.9238795325112867), SD_R(-0.7071067811865476), SD_R(-0.3826834323650898),
                            SD_R(0.0), SD_R(0.3826834323650898), SD_R(0.7071067811865476), SD_R(0.9238795325112867)};
    sd_real px = sd_v3_dot(p, e1), py = sd_v3_dot(p, e2);
    for (int k = 0; k < 16; ++k)
        sec[k] = sd_v2(px + a * c8[k], py + a * c8[(k + 12) % 16]);
    return 16;
}

/* 1 when the far corner of nb (across edge k of t) lies behind t's group
 * plane: the edge is a convex ridge seen from the particle side. */
SD_HD static SD_INLINE int sd_mesh_edge_convex(const sd_mesh_view *m, uint32_t t, int k, uint32_t nb)
{
    const uint32_t *tv = m->tris[t];
    uint32_t ia = tv[k], ib = tv[(k + 1) % 3];
    sd_vec3 a = m->verts[ia], d = sd_v3_sub(m->verts[sd_mesh_far_corner(m, nb, ia, ib)], a);
    return sd_v3_dot(m->group_normal[m->group[t]], d) < -SD_MESH_SEAM_TOL * sd_v3_norm(d);
}

/* The ridge rule's candidates (backend/items.h): the groups across the
 * convex edges of group gr's near triangles tl (nt), walked in the order
 * of the triangles and their edges, each given once (the first
 * SD_MESH_RIDGE_SEEN distinct ones are remembered; past them a group may
 * come again, which changes no answer). */
#define SD_MESH_RIDGE_SEEN 8

typedef struct sd_mesh_ridge_walk {
    uint32_t k;  /* the near triangle */
    int q, ns;   /* its next edge; groups remembered */
    uint32_t nb; /* the triangle across the edge of the group last given */
    uint32_t seen[SD_MESH_RIDGE_SEEN];
} sd_mesh_ridge_walk;

SD_HD static SD_INLINE void sd_mesh_ridge_start(sd_mesh_ridge_walk *w)
{
    w->k = 0;
    w->q = 0;
    w->ns = 0;
}

/* The next group of the walk, UINT32_MAX when done (or without neighbours). */
SD_HD static SD_INLINE uint32_t sd_mesh_ridge_next(const sd_mesh_view *m, uint32_t gr, const uint32_t *tl, uint32_t nt,
                                                   sd_mesh_ridge_walk *w)
{
    if (!m->nbr)
        return UINT32_MAX;
    for (; w->k < nt; ++w->k, w->q = 0)
        while (w->q < 3) {
            int q = w->q++;
            uint32_t nb = m->nbr[tl[w->k]][q];
            if (nb == UINT32_MAX || m->group[nb] == gr)
                continue;
            uint32_t gy = m->group[nb];
            int dup = 0;
            for (int s = 0; s < w->ns; ++s)
                dup |= w->seen[s] == gy;
            if (dup || !sd_mesh_edge_convex(m, tl[w->k], q, nb))
                continue;
            if (w->ns < SD_MESH_RIDGE_SEEN)
                w->seen[w->ns++] = gy;
            w->nb = nb;
            return gy;
        }
    return UINT32_MAX;
}

/* Directions of the support-point section of a body without vertices
 * (sd_mesh_convex_section): a disc's area comes out (24/2pi) sin(2pi/24)
 * = 0.9886 of the true one, the same factor for its clipped part, so the
 * weight w = A_clip / A is not biased by it. */
#define SD_MESH_SECTION_DIRS 24
/* At most this many support points per rim point once bracketed: a smooth
 * rim takes a handful; a sharp edge or corner across the plane (a jump of
 * the height g below) is closed on by a halving at least every third step. */
#define SD_MESH_SECTION_ITERS 64

/* The support point of the swept body (core plus radius) in its principal
 * frame along direction (1 - s^2) u + 2 s n, s in [-1, 1]: u at s = 0, +n
 * at s = 1, -n at s = -1 (s is the tangent of half the angle turned from
 * u towards n, so no sine or cosine is needed), and its height g = n . p
 * - off above the plane. */
SD_HD static SD_INLINE sd_vec3 sd_mesh_section_support(const sd_shape *sh, const sd_vec3 *verts, sd_vec3 u, sd_vec3 n,
                                                       sd_real off, sd_real s, sd_real *g)
{
    /* u and n are unit and square to each other: |d| = 1 + s^2 exactly,
     * so the swept radius needs no norm */
    sd_vec3 d = sd_v3_add(sd_v3_scale(u, SD_R(1.0) - s * s), sd_v3_scale(n, SD_R(2.0) * s));
    sd_vec3 p = sd_v3_madd(sd_shape_support_core(sh, verts, d), sh->radius / (SD_R(1.0) + s * s), d);
    *g = sd_v3_dot(n, p) - off;
    return p;
}

/* The s in (-1, 1) whose direction (1 - s^2) u + 2 s n is square to the
 * chord e: (1 - s^2) a + 2 s b = 0, a = u . e, b = n . e; of its two
 * roots (their product is -1) the one of magnitude below 1; 2 (none) when
 * e is square to both u and n. */
SD_HD static SD_INLINE sd_real sd_mesh_section_square(sd_vec3 u, sd_vec3 n, sd_vec3 e)
{
    sd_real a = sd_v3_dot(u, e), b = sd_v3_dot(n, e);
    sd_real den = b + (b >= SD_R(0.0) ? SD_R(1.0) : SD_R(-1.0)) * sd_sqrt(a * a + b * b);
    return den != SD_R(0.0) ? -a / den : SD_R(2.0);
}

/* What one rim point leaves to the next (24 directions turning by 15
 * degrees): its root s, the first step to bracket the next from it, and
 * the chord (c0, c1, heights h0 < 0 < h1) of the face it lay on, if any. */
typedef struct sd_mesh_rim_state {
    sd_real s, step, h0, h1;
    int chord;
    sd_vec3 c0, c1;
} sd_mesh_rim_state;

/* The section's rim point along plane direction u (body frame; the plane
 * n . p = off): the support point whose height g(s) is zero. g never
 * decreases with s (the support point of a turning direction climbs the
 * body), so the root is bracketed: from the last rim point's root the
 * bracket grows by steps, quadrupled, to where g changes sign (the body's
 * lowest and highest points, plo at s = -1 and phi at s = 1, close it at
 * worst); then regula falsi with the Illinois halving, every other step
 * replaced by the chord step below, until |g| is below tol, the two ends'
 * points are within dist of each other, or the bracket is 1e-12 wide.
 * The chord step takes the direction square to the chord between the
 * ends' points: when no point of the body lies above the chord along it,
 * the chord lies on a face of the body (g jumps there: a flat face, or a
 * sharp edge or corner crossing the plane) and the rim point is where it
 * crosses the plane. A face found so is tried first for the next
 * direction (a polygon-like section has few corners: one support point
 * then gives the rim point). */
SD_HD static SD_INLINE sd_vec3 sd_mesh_section_rim(const sd_shape *sh, const sd_vec3 *verts, sd_vec3 u, sd_vec3 n,
                                                   sd_real off, sd_real tol, sd_real dist, sd_vec3 plo, sd_real glo,
                                                   sd_vec3 phi, sd_real ghi, sd_mesh_rim_state *st)
{
    sd_real s0 = SD_R(-1.0), s1 = SD_R(1.0), g0 = glo, g1 = ghi, g, sg = st->s;
    sd_vec3 p0 = plo, p1 = phi, p;
    int have = 0;
    if (st->chord) {
        /* the last face, square to this direction */
        sd_real sq = sd_mesh_section_square(u, n, sd_v3_sub(st->c1, st->c0));
        if (sq > SD_R(-1.0) && sq < SD_R(1.0)) {
            p = sd_mesh_section_support(sh, verts, u, n, off, sq, &g);
            sd_vec3 d = sd_v3_add(sd_v3_scale(u, SD_R(1.0) - sq * sq), sd_v3_scale(n, SD_R(2.0) * sq));
            if (sd_v3_dot(d, sd_v3_sub(p, st->c0)) <= tol * (SD_R(1.0) + sq * sq)) {
                st->s = sq;
                return sd_v3_add(st->c0, sd_v3_scale(sd_v3_sub(st->c1, st->c0), st->h0 / (st->h0 - st->h1)));
            }
            sg = sq;
            have = 1;
        }
    }
    st->chord = 0;
    st->s = sg;
    if (!have)
        p = sd_mesh_section_support(sh, verts, u, n, off, sg, &g);
    if (sd_fabs(g) <= tol)
        return p;
    /* grow the bracket from the guess towards the root */
    int up = g < SD_R(0.0);
    if (up)
        s0 = sg, p0 = p, g0 = g;
    else
        s1 = sg, p1 = p, g1 = g;
    for (sd_real s = sg, step = st->step;; step *= SD_R(4.0)) {
        s = up ? s + step : s - step;
        if (up ? s >= s1 : s <= s0)
            break; /* the far end (-1 or 1) closes it */
        p = sd_mesh_section_support(sh, verts, u, n, off, s, &g);
        if (sd_fabs(g) <= tol) {
            st->s = s;
            return p;
        }
        if ((g < SD_R(0.0)) != up) {
            if (up)
                s1 = s, p1 = p, g1 = g;
            else
                s0 = s, p0 = p, g0 = g;
            break;
        }
        if (up)
            s0 = s, p0 = p, g0 = g;
        else
            s1 = s, p1 = p, g1 = g;
    }
    /* f0, f1: the ends' heights as regula falsi weighs them (halved by Illinois) */
    sd_real f0 = g0, f1 = g1;
    int side = 0;
    for (int it = 0; it < SD_MESH_SECTION_ITERS && s1 - s0 > SD_R(1e-12); ++it) {
        if (sd_v3_norm2(sd_v3_sub(p1, p0)) <= dist * dist)
            break;
        int chord = it % 2 == 1;
        sd_real s = chord ? sd_mesh_section_square(u, n, sd_v3_sub(p1, p0)) : (s0 * f1 - s1 * f0) / (f1 - f0);
        if (!(s > s0 && s < s1))
            s = SD_R(0.5) * (s0 + s1);
        p = sd_mesh_section_support(sh, verts, u, n, off, s, &g);
        if (sd_fabs(g) <= tol) {
            st->s = s;
            return p;
        }
        if (chord) {
            sd_vec3 d = sd_v3_add(sd_v3_scale(u, SD_R(1.0) - s * s), sd_v3_scale(n, SD_R(2.0) * s));
            if (sd_v3_dot(d, sd_v3_sub(p, p0)) <= tol * (SD_R(1.0) + s * s)) {
                st->chord = 1, st->c0 = p0, st->c1 = p1, st->h0 = g0, st->h1 = g1;
                break; /* on a face */
            }
        }
        if (g < SD_R(0.0)) {
            s0 = s, p0 = p, g0 = f0 = g;
            if (side == -1 && !chord)
                f1 *= SD_R(0.5);
            side = -1;
        } else {
            s1 = s, p1 = p, g1 = f1 = g;
            if (side == 1 && !chord)
                f0 *= SD_R(0.5);
            side = 1;
        }
    }
    sd_real w = g0 / (g0 - g1);
    st->s = s0 + w * (s1 - s0);
    return sd_v3_add(p0, sd_v3_scale(sd_v3_sub(p1, p0), w));
}

/* The section of a posed convex body (any kind: spheres, ellipsoids,
 * cylinders, cones, boxes, with their rounding) by the plane n . x = off
 * of the mesh frame, as the polygon of its rim points in
 * SD_MESH_SECTION_DIRS plane directions, hulled, in the plane basis
 * (e1, e2); returns its vertex count (0 when the plane misses the body).
 *
 * The rim point along plane direction u is the body's support point along
 * d = u + t n at the t where that point lies on the plane (seed 000
 * §2.4's section, by LP duality: h_S(u) = min over t of h_K(u + t n) -
 * t off, whose derivative in t is n . s(u + t n) - off), found by
 * sd_mesh_section_rim to 1e-12 of the body's size, the first from the
 * direction of a sphere's rim at the same depth, each next from the last.
 * Everything is done in the body's principal frame (the plane and its
 * basis turned into it once), so each step is one support point of the
 * template. */
SD_HD static SD_INLINE int sd_mesh_convex_section(const sd_convex *c, const sd_wall_geom *wg, sd_vec3 n, sd_real off,
                                                  sd_vec3 e1, sd_vec3 e2, sd_vec2 *sec)
{
    const sd_shape *sh = c->shape;
    /* the plane n . x = off and the mesh frame's basis in the body frame:
     * x_mesh = R_m^T (R_b p + x_b - trans), so n . x_mesh = nb . p + n . xc,
     * nb = R_b^T R_m n and xc the centre in the mesh frame */
    sd_quat qr = sd_quat_mul(sd_quat_conj(c->q), wg->q);
    sd_vec3 nb = sd_quat_rotate(qr, n), e1b = sd_quat_rotate(qr, e1), e2b = sd_quat_rotate(qr, e2);
    sd_vec3 xc = sd_mesh_to_frame(wg->q, wg->trans, c->x);
    sd_real offb = off - sd_v3_dot(n, xc), x1 = sd_v3_dot(xc, e1), x2 = sd_v3_dot(xc, e2);
    sd_real size = sh->bound > 0 ? sh->bound : SD_R(1.0);
    /* the lowest and the highest point along n: the brackets' far ends */
    sd_real glo, ghi;
    sd_vec3 plo = sd_mesh_section_support(sh, c->verts, e1b, nb, offb, SD_R(-1.0), &glo);
    sd_vec3 phi = sd_mesh_section_support(sh, c->verts, e1b, nb, offb, SD_R(1.0), &ghi);
    if (!(glo <= SD_R(0.0) && ghi >= SD_R(0.0)) || !(ghi > glo))
        return 0; /* the plane misses the body (or grazes a face of no height) */
    /* the first guess: the rim of a sphere of the body's height cut at its
     * depth, at angle theta from -n, cos theta = 1 - depth / radius, is
     * s = tan((theta - pi/2) / 2) = -cos theta / (1 + sin theta) */
    sd_real ct = SD_R(1.0) + SD_R(2.0) * glo / (ghi - glo);
    sd_mesh_rim_state st;
    st.s = -ct / (SD_R(1.0) + sd_sqrt(sd_max(SD_R(0.0), SD_R(1.0) - ct * ct)));
    st.step = SD_R(0.05);
    st.chord = 0;
    st.h0 = st.h1 = SD_R(0.0);
    st.c0 = st.c1 = plo;
    /* cos and sin of k 2 pi / 24 */
    const sd_real cs[6] = {SD_R(1.0), SD_R(0.9659258262890683), SD_R(0.8660254037844386), SD_R(0.7071067811865476),
                           SD_R(0.5), SD_R(0.25881904510252074)};
    int np = 0;
    for (int k = 0; k < SD_MESH_SECTION_DIRS; ++k) {
        int q = k % 6, quad = k / 6;
        sd_real ca = cs[q], sa = q == 0 ? SD_R(0.0) : cs[6 - q]; /* angle q pi / 12 in this quadrant */
        sd_real cx = quad == 0 ? ca : (quad == 1 ? -sa : (quad == 2 ? -ca : sa));
        sd_real cy = quad == 0 ? sa : (quad == 1 ? ca : (quad == 2 ? -sa : -ca));
        sd_vec3 u = sd_v3_add(sd_v3_scale(e1b, cx), sd_v3_scale(e2b, cy));
        sd_real sg = st.s;
        sd_vec3 p = sd_mesh_section_rim(sh, c->verts, u, nb, offb, SD_R(1e-12) * size, SD_R(1e-7) * size, plo, glo,
                                        phi, ghi, &st);
        /* the next direction's first step: a little more than this root moved */
        st.step = sd_max(SD_R(1e-3), SD_R(1.5) * sd_fabs(st.s - sg));
        st.s = sd_max(SD_R(-1.0) + SD_R(1e-9), sd_min(SD_R(1.0) - SD_R(1e-9), st.s));
        p = sd_v3_sub(p, sd_v3_scale(nb, sd_v3_dot(nb, p) - offb));
        sec[np++] = sd_v2(sd_v3_dot(p, e1b) + x1, sd_v3_dot(p, e2b) + x2);
    }
    return sd_clip_hull(sec, np);
}

/* ---- the rim rule (issue 30, defect 2) ---------------------------------
 *
 * A plane contact takes its depth against the group's plane extended
 * without end. Past an open (boundary) edge of the mesh there is no
 * wall: a body falling through a hopper's outlet sinks into the cone's
 * plane extended below the rim, often by a large part of its size, and
 * the area weight (the part of its section still over the facets) let a
 * share of that depth through as a kick (a rounded cube reached 20.7 % of
 * its radius at the rim of the cone hopper, a sphere 0.9 %). So when the
 * body's deepest point under the plane lies beyond the group's facets
 * across a boundary edge (sd_mesh_beyond_rim), the facet is a bounded
 * triangle of no thickness there and the body meets its free edges: each
 * boundary edge
 * of the near triangles is a segment, its contact with the body (core
 * swept by its rounding) is GJK's distance, or EPA's depth where the
 * segment cuts the core (geom/convex_contact.h), and the deepest one is
 * the group's contact (sd_mesh_rim_contact): a point contact along the
 * direction that frees the body from the edge, as a sphere's edge contact
 * (sd_mesh_sphere_geom) is, and a sphere meets a free edge from below
 * the plane's level too (sd_mesh_feature_free). Contacts whose deepest
 * point lies over a facet are untouched, bit for bit. */

/* The squared distance from p to segment a-b (any frame). */
SD_HD static SD_INLINE sd_real sd_mesh_seg_dist2(sd_vec3 p, sd_vec3 a, sd_vec3 b)
{
    sd_vec3 ab = sd_v3_sub(b, a), ap = sd_v3_sub(p, a);
    sd_real l2 = sd_v3_dot(ab, ab), t = l2 > SD_R(0.0) ? sd_v3_dot(ap, ab) / l2 : SD_R(0.0);
    t = t < SD_R(0.0) ? SD_R(0.0) : (t > SD_R(1.0) ? SD_R(1.0) : t);
    return sd_v3_norm2(sd_v3_sub(ap, sd_v3_scale(ab, t)));
}

/* 1 when body c's contact with group gr belongs to the rim: the deepest
 * point of its core under the group's plane (the support point along the
 * inward normal; of a face lying flat, the one the support function
 * returns) has its foot on none of the near triangles tl (nt), and the
 * nearest of their points to that foot lies on a boundary edge (one
 * facet; its corners included). Across an edge to another group the faces
 * and the ridge rule decide, as before. Not the plane contact's point:
 * a box's or polyhedron's (the corners' Lehmer mean, convex_contact.h)
 * stays over the facets while a corner hangs deep beyond the edge. */
SD_HD static SD_INLINE int sd_mesh_beyond_rim(const sd_mesh_view *m, const sd_wall_geom *wg, uint32_t gr,
                                              const uint32_t *tl, uint32_t nt, const sd_convex *c)
{
    if (!m->nbr || nt == 0)
        return 0;
    sd_vec3 n = m->group_normal[gr];
    sd_vec3 q = sd_mesh_to_frame(wg->q, wg->trans, sd_convex_support_core(c, sd_v3_neg(sd_quat_rotate(wg->q, n))));
    q = sd_v3_sub(q, sd_v3_scale(n, sd_v3_dot(n, q) - m->group_offset[gr])); /* onto the plane */
    sd_real d_all = SD_R(-1.0), d_rim = SD_R(-1.0);
    for (uint32_t k = 0; k < nt; ++k) {
        const uint32_t *tv = m->tris[tl[k]];
        int f;
        sd_vec3 p = sd_clip_closest(q, m->verts[tv[0]], m->verts[tv[1]], m->verts[tv[2]], &f);
        if (f == SD_CLIP_FACE)
            return 0; /* over a facet */
        sd_real d2 = sd_v3_norm2(sd_v3_sub(q, p));
        d_all = d_all < SD_R(0.0) || d2 < d_all ? d2 : d_all;
        for (int e = 0; e < 3; ++e)
            if (m->nbr[tl[k]][e] == UINT32_MAX) {
                sd_real de = sd_mesh_seg_dist2(q, m->verts[tv[e]], m->verts[tv[(e + 1) % 3]]);
                d_rim = d_rim < SD_R(0.0) || de < d_rim ? de : d_rim;
            }
    }
    /* the nearest point is on a boundary edge (to rounding of the squares) */
    return d_rim >= SD_R(0.0) && d_rim <= d_all * (SD_R(1.0) + SD_R(1e-9));
}

/* The contact of posed body c with the boundary edges of the near
 * triangles tl (nt) of a mesh: the deepest of the segments' contacts, 1
 * and *g when one touches (n from the edge to the body, the point midway
 * through the overlap); *foot: the edge's witness point (world frame),
 * where the tangent plane {x : (x - foot) . n = 0} touches the segment. */
SD_HD static SD_INLINE int sd_mesh_rim_contact(const sd_mesh_view *m, const sd_wall_geom *wg, const uint32_t *tl,
                                               uint32_t nt, const sd_convex *c, sd_contact_geom *g, sd_vec3 *foot)
{
    int found = 0;
    for (uint32_t k = 0; k < nt; ++k) {
        const uint32_t *tv = m->tris[tl[k]];
        for (int e = 0; e < 3; ++e) {
            if (m->nbr[tl[k]][e] != UINT32_MAX)
                continue;
            /* the segment as a posed polyhedron of two vertices about its midpoint */
            sd_vec3 a = sd_mesh_to_world(wg->q, wg->trans, m->verts[tv[e]]);
            sd_vec3 b = sd_mesh_to_world(wg->q, wg->trans, m->verts[tv[(e + 1) % 3]]);
            sd_vec3 mid = sd_v3_scale(sd_v3_add(a, b), SD_R(0.5));
            sd_vec3 sv[2];
            sv[0] = sd_v3_sub(a, mid);
            sv[1] = sd_v3_sub(b, mid);
            sd_shape sh;
            memset(&sh, 0, sizeof sh);
            sh.kind = SD_SHAPE_POLYHEDRON;
            sh.vcount = 2;
            sh.bound = sd_v3_norm(sv[0]);
            sd_convex s;
            s.shape = &sh;
            s.verts = sv;
            s.planes = NULL;
            s.dtris = NULL;
            s.x = mid;
            s.q = sd_quat_identity();
            sd_convex_contact cc = sd_convex_collide(c, &s, NULL);
            if (!cc.touching || (found && !(cc.delta > g->delta)))
                continue;
            found = 1;
            g->n = cc.n;
            g->delta = cc.delta;
            g->point = cc.point;
            /* the segment's side of the overlap: half the depth back along n */
            *foot = sd_v3_madd(cc.point, SD_R(0.5) * cc.delta, cc.n);
        }
    }
    return found;
}

#endif
