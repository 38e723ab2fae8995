/* clip.h — planar polygon clipping and triangle feature tests for mesh
 * walls (seed 000 §2.4): Sutherland–Hodgman clipping of a convex subject
 * polygon by a triangle (Algorithm VII with the standard four in/out
 * cases, DESIGN.md: our copy of the seed lost its negations), polygon area
 * and centroid, the closest point of a triangle with the feature it lies
 * on, and the section of a convex polyhedron by a plane.
 *
 * Conventions: 2D polygons are counter-clockwise (positive area) in a
 * plane basis (e1, e2) with e1 x e2 = n; clipping keeps the left side of
 * each counter-clockwise triangle edge (the seed keeps the right side of a
 * clockwise edge: the same half-plane). Intersections follow seed eqs.
 * 10-11. Fixed workspaces: a subject polygon has at most SD_CLIP_MAX
 * vertices and each of the triangle's three edges adds at most one.
 *
 * Single source (SD_HD): plain structs, no allocation, compiles as C17 and
 * as C++ (tests/cuda/mesh.cu).
 */
#ifndef SD_GEOM_CLIP_H
#define SD_GEOM_CLIP_H

#include "core/vec.h"
#include "core/vec2.h"

#define SD_CLIP_MAX 64

SD_HD static SD_INLINE sd_real sd_clip_cross(sd_vec2 a, sd_vec2 b) { return a.x * b.y - a.y * b.x; }

/* Area (m^2, positive for counter-clockwise) and centroid of polygon p. */
SD_HD static SD_INLINE sd_real sd_clip_area(const sd_vec2 *p, int n, sd_vec2 *centroid)
{
    sd_real a2 = SD_R(0.0), cx = SD_R(0.0), cy = SD_R(0.0);
    if (n < 3) {
        if (centroid)
            *centroid = n > 0 ? p[0] : sd_v2(SD_R(0.0), SD_R(0.0));
        return SD_R(0.0);
    }
    /* fan from p[0]: rounding stays relative to the polygon's size, not to
     * its distance from the origin */
    for (int k = 1; k + 1 < n; ++k) {
        sd_vec2 u = sd_v2(p[k].x - p[0].x, p[k].y - p[0].y), v = sd_v2(p[k + 1].x - p[0].x, p[k + 1].y - p[0].y);
        sd_real c = sd_clip_cross(u, v);
        a2 += c;
        cx += c * (u.x + v.x);
        cy += c * (u.y + v.y);
    }
    if (centroid)
        *centroid = a2 != SD_R(0.0) ? sd_v2(p[0].x + cx / (SD_R(3.0) * a2), p[0].y + cy / (SD_R(3.0) * a2)) : p[0];
    return SD_R(0.5) * a2;
}

/* Clips subject polygon p (n vertices, n <= SD_CLIP_MAX) by the
 * counter-clockwise triangle t into out (room for SD_CLIP_MAX + 3);
 * returns the vertex count of the overlap (0 when disjoint). */
SD_HD static SD_INLINE int sd_clip_triangle(const sd_vec2 *p, int n, const sd_vec2 t[3], sd_vec2 *out)
{
    sd_vec2 buf[2][SD_CLIP_MAX + 3];
    int m = n;
    for (int k = 0; k < n; ++k)
        buf[0][k] = p[k];
    int cur = 0;
    for (int e = 0; e < 3 && m > 0; ++e) {
        sd_vec2 v0 = t[e], v1 = t[(e + 1) % 3];
        sd_vec2 dir = sd_v2(v1.x - v0.x, v1.y - v0.y);
        const sd_vec2 *src = buf[cur];
        sd_vec2 *dst = buf[cur ^ 1];
        int q = 0;
        sd_vec2 v2 = src[m - 1];
        sd_real s2 = sd_clip_cross(dir, sd_v2(v2.x - v0.x, v2.y - v0.y));
        for (int k = 0; k < m; ++k) {
            sd_vec2 v3 = src[k];
            sd_real s3 = sd_clip_cross(dir, sd_v2(v3.x - v0.x, v3.y - v0.y));
            int in3 = s3 >= SD_R(0.0), in2 = s2 >= SD_R(0.0);
            /* a convex subject gains at most one vertex per edge; the bound
             * keeps a degenerate one inside the workspace */
            if (in3 != in2 && q < SD_CLIP_MAX + 3) {
                /* eqs. 10-11: the crossing of segment v2 v3 with the edge line */
                sd_real tt = s2 / (s2 - s3);
                dst[q++] = sd_v2(v2.x + (v3.x - v2.x) * tt, v2.y + (v3.y - v2.y) * tt);
            }
            if (in3 && q < SD_CLIP_MAX + 3)
                dst[q++] = v3; /* in -> in, out -> in: keep v3 */
            v2 = v3;
            s2 = s3;
        }
        m = q;
        cur ^= 1;
    }
    for (int k = 0; k < m; ++k)
        out[k] = buf[cur][k];
    return m;
}

/* The plane basis (e1, e2) of unit normal n, e1 x e2 = n. */
SD_HD static SD_INLINE void sd_clip_basis(sd_vec3 n, sd_vec3 *e1, sd_vec3 *e2)
{
    sd_vec3 a = sd_fabs(n.x) < SD_R(0.6) ? sd_v3(SD_R(1.0), SD_R(0.0), SD_R(0.0))
                                          : sd_v3(SD_R(0.0), SD_R(1.0), SD_R(0.0));
    *e1 = sd_v3_normalize(sd_v3_sub(a, sd_v3_scale(n, sd_v3_dot(a, n))));
    *e2 = sd_v3_cross(n, *e1);
}

/* Feature codes of sd_clip_closest. */
enum { SD_CLIP_FACE = 0, SD_CLIP_EDGE0 = 1, SD_CLIP_CORNER0 = 4 };

/* Closest point of triangle (a, b, c) to p (Voronoi regions, as in
 * Ericson's Real-Time Collision Detection §5.1.5), with the feature it
 * lies on: SD_CLIP_FACE, SD_CLIP_EDGE0 + k (edge corner k -> k + 1) or
 * SD_CLIP_CORNER0 + k. */
SD_HD static SD_INLINE sd_vec3 sd_clip_closest(sd_vec3 p, sd_vec3 a, sd_vec3 b, sd_vec3 c, int *feature)
{
    sd_vec3 ab = sd_v3_sub(b, a), ac = sd_v3_sub(c, a), ap = sd_v3_sub(p, a);
    sd_real d1 = sd_v3_dot(ab, ap), d2 = sd_v3_dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) {
        *feature = SD_CLIP_CORNER0 + 0;
        return a;
    }
    sd_vec3 bp = sd_v3_sub(p, b);
    sd_real d3 = sd_v3_dot(ab, bp), d4 = sd_v3_dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) {
        *feature = SD_CLIP_CORNER0 + 1;
        return b;
    }
    sd_real vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        *feature = SD_CLIP_EDGE0 + 0;
        return sd_v3_madd(a, d1 / (d1 - d3), ab);
    }
    sd_vec3 cp = sd_v3_sub(p, c);
    sd_real d5 = sd_v3_dot(ab, cp), d6 = sd_v3_dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) {
        *feature = SD_CLIP_CORNER0 + 2;
        return c;
    }
    sd_real vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        *feature = SD_CLIP_EDGE0 + 2; /* edge c -> a */
        return sd_v3_madd(a, d2 / (d2 - d6), ac);
    }
    sd_real va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        *feature = SD_CLIP_EDGE0 + 1;
        return sd_v3_madd(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), sd_v3_sub(c, b));
    }
    sd_real den = SD_R(1.0) / (va + vb + vc);
    *feature = SD_CLIP_FACE;
    return sd_v3_add(a, sd_v3_add(sd_v3_scale(ab, vb * den), sd_v3_scale(ac, vc * den)));
}

/* Counter-clockwise convex hull (in place, returns its size) of n points
 * (at most SD_CLIP_MAX are read): Andrew's monotone chain on the points
 * sorted by (x, y), so duplicated and collinear points (a section whose
 * crossings coincide, rounding) are dropped and the result is always a
 * convex polygon of at most n vertices, starting at the lowest-leftmost
 * point. (Gift wrapping could cycle on near-duplicates and return
 * SD_CLIP_MAX points that were not convex, whose clipping then overran
 * sd_clip_triangle's workspace: mesh-drum crashed at step 165,000.) */
SD_HD static SD_INLINE int sd_clip_hull(sd_vec2 *p, int n)
{
    if (n > SD_CLIP_MAX)
        n = SD_CLIP_MAX;
    if (n < 3)
        return n;
    for (int i = 1; i < n; ++i) { /* insertion sort: few points */
        sd_vec2 v = p[i];
        int j = i - 1;
        while (j >= 0 && (p[j].x > v.x || (p[j].x == v.x && p[j].y > v.y))) {
            p[j + 1] = p[j];
            --j;
        }
        p[j + 1] = v;
    }
    sd_vec2 h[2 * SD_CLIP_MAX + 1];
    int m = 0;
    for (int i = 0; i < n; ++i) { /* lower chain, left to right */
        while (m >= 2 && sd_clip_cross(sd_v2(h[m - 1].x - h[m - 2].x, h[m - 1].y - h[m - 2].y),
                                       sd_v2(p[i].x - h[m - 2].x, p[i].y - h[m - 2].y)) <= SD_R(0.0))
            --m;
        h[m++] = p[i];
    }
    for (int i = n - 2, lo = m + 1; i >= 0; --i) { /* upper chain, right to left */
        while (m >= lo && sd_clip_cross(sd_v2(h[m - 1].x - h[m - 2].x, h[m - 1].y - h[m - 2].y),
                                        sd_v2(p[i].x - h[m - 2].x, p[i].y - h[m - 2].y)) <= SD_R(0.0))
            --m;
        h[m++] = p[i];
    }
    --m; /* the chain ends where it started */
    for (int k = 0; k < m; ++k)
        p[k] = h[k];
    return m;
}

#endif
