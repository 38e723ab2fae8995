/* halfspace.h — exact overlap of a sharp convex polyhedron with a
 * half-space (a plane wall or a box face): volume, area vector and contact
 * point, in the struct of geom/overlap.h, so the volume laws treat a wall
 * like a body. Single source (SD_HD): fixed-size arrays, no allocation.
 *
 * Convention: the solid half-space is B = {x : n . x > h} (n points into
 * the wall's solid, h its offset); the overlap I = A ∩ B. A wall whose free
 * side has unit normal nw through point p0 is n = -nw, h = -nw . p0.
 *
 * Method (divergence theorem, notes/algorithms.md §D). I is bounded by the
 * parts of A's faces inside B and by the cut face on the plane. Each face
 * polygon of A (its vertices lying on the face plane, ordered by angle) is
 * clipped to n . x >= h (Sutherland–Hodgman against one plane, the four
 * standard cases of DESIGN.md). With p0 a point of the cut plane, the cut
 * face adds nothing to the pyramid sum, so
 *     V = 1/3 Σ_f (h_f - n_f . p0) a_f,
 * over the clipped faces f (area a_f, unit normal n_f, offset h_f). The
 * faces of I lying on A give S_A = Σ a_f n_f, which by closure equals
 * a_cut n (the cut face's area along n): area = n . S_A and normal = n
 * exactly (a plane cannot tilt the normal). Their moment T_A = Σ a_f
 * (c_f - p0) × n_f locates the line of action (x_c × S = T about p0); the
 * point on it in the cut plane is the cut face's centroid, and the twist is
 * zero since S ∥ n. Force and torque of a potential W(V) are then the exact
 * gradient (the cut face's centroid is where a uniform pressure on it acts).
 *
 * Face incidence comes from the template's dual triangles (sd_dtri): the
 * vertices of face f are the points where f meets two other welded planes,
 * so the body clipped here is exactly the intersection of its face planes,
 * the same body geom/overlap.h sees (input vertices of a nearly coplanar
 * face, welded into one plane, lie slightly off it). A face has at most
 * SD_HALFSPACE_MAX_FACE_VERTS entries, more is SD_OVERLAP_OVERFLOW (never a
 * silent truncation).
 */
#ifndef SD_GEOM_HALFSPACE_H
#define SD_GEOM_HALFSPACE_H

#include "geom/overlap.h"
#include "shape/support.h"

#define SD_HALFSPACE_MAX_FACE_VERTS 64

/* Overlap of the posed sharp polyhedron a with B = {x : n . x > h}. */
SD_HD static SD_INLINE sd_overlap sd_overlap_halfspace(const sd_convex *a, sd_vec3 n, sd_real h)
{
    sd_overlap o;
    o.status = SD_OVERLAP_NONE;
    o.volume = SD_R(0.0);
    o.area = SD_R(0.0);
    o.normal = n;
    o.point = a->x;
    o.twist = SD_R(0.0);
    o.x0 = a->x;
    o.centroid = a->x;
    o.s_a = o.s_b = sd_v3_zero();
    o.faces = o.vertices = 0;
    const sd_shape *s = a->shape;
    const sd_dtri *dt = a->dtris + s->tstart;
    const sd_plane *pl = a->planes + s->fstart;
    /* body frame: B = {y : nb . y > hb} */
    sd_vec3 nb = sd_quat_rotate_inv(a->q, n);
    sd_real hb = h - sd_v3_dot(n, a->x);
    uint32_t deep = 0;
    sd_real dmax = sd_v3_dot(nb, dt[0].v) - hb;
    for (uint32_t k = 1; k < s->tcount; ++k) {
        sd_real d = sd_v3_dot(nb, dt[k].v) - hb;
        if (d > dmax) {
            dmax = d;
            deep = k;
        }
    }
    if (!(dmax > SD_R(0.0)))
        return o; /* apart or touching */
    /* a point of the cut plane near the overlap: sums about it stay small */
    sd_vec3 p0 = sd_v3_madd(dt[deep].v, -dmax, nb);
    sd_real vol = SD_R(0.0);
    sd_vec3 sa = sd_v3_zero(), ta = sd_v3_zero();
    int nfaces = 0;
    sd_vec3 poly[SD_HALFSPACE_MAX_FACE_VERTS];
    sd_real ang[SD_HALFSPACE_MAX_FACE_VERTS];
    sd_vec3 clip[SD_HALFSPACE_MAX_FACE_VERTS + 1];
    for (uint32_t f = 0; f < s->fcount; ++f) {
        sd_vec3 nf = pl[f].n;
        sd_real hf = pl[f].h;
        /* the face's vertices: the dual triangles that hold plane f (a
         * vertex where k > 3 faces meet comes k - 2 times: repeated points
         * sort next to each other and add nothing); skip faces wholly
         * outside B */
        int m = 0, inside = 0;
        for (uint32_t k = 0; k < s->tcount; ++k) {
            if (dt[k].f[0] != f && dt[k].f[1] != f && dt[k].f[2] != f)
                continue;
            if (m == SD_HALFSPACE_MAX_FACE_VERTS) {
                o.status = SD_OVERLAP_OVERFLOW;
                return o;
            }
            poly[m++] = dt[k].v;
            inside |= sd_v3_dot(nb, dt[k].v) - hb > SD_R(0.0);
        }
        if (m < 3 || !inside)
            continue;
        /* order counter-clockwise about nf, by angle around the mean */
        sd_vec3 c = sd_v3_zero();
        for (int k = 0; k < m; ++k)
            c = sd_v3_add(c, poly[k]);
        c = sd_v3_scale(c, SD_R(1.0) / (sd_real)m);
        sd_vec3 u = sd_v3_sub(poly[0], c);
        u = sd_v3_normalize(sd_v3_madd(u, -sd_v3_dot(u, nf), nf));
        sd_vec3 w = sd_v3_cross(nf, u);
        for (int k = 0; k < m; ++k) {
            sd_vec3 r = sd_v3_sub(poly[k], c);
            ang[k] = sd_atan2(sd_v3_dot(r, w), sd_v3_dot(r, u));
        }
        for (int k = 1; k < m; ++k) { /* insertion sort: faces are small */
            sd_vec3 pv = poly[k];
            sd_real av = ang[k];
            int j = k - 1;
            while (j >= 0 && ang[j] > av) {
                poly[j + 1] = poly[j];
                ang[j + 1] = ang[j];
                --j;
            }
            poly[j + 1] = pv;
            ang[j + 1] = av;
        }
        /* clip to nb . y >= hb: in->in keep q; out->in add I and q; in->out
         * add I; out->out nothing */
        int mc = 0;
        for (int k = 0; k < m; ++k) {
            sd_vec3 pp = poly[k], q = poly[(k + 1) % m];
            sd_real dp = sd_v3_dot(nb, pp) - hb, dq = sd_v3_dot(nb, q) - hb;
            int ip = dp >= SD_R(0.0), iq = dq >= SD_R(0.0);
            if (ip != iq) {
                sd_real t = dp / (dp - dq);
                clip[mc++] = sd_v3_madd(pp, t, sd_v3_sub(q, pp));
            }
            if (iq)
                clip[mc++] = q;
        }
        if (mc < 3)
            continue;
        /* area and centroid of the clipped polygon, fan from its first vertex */
        sd_real af = SD_R(0.0);
        sd_vec3 cf = sd_v3_zero();
        for (int k = 1; k + 1 < mc; ++k) {
            sd_vec3 e1 = sd_v3_sub(clip[k], clip[0]), e2 = sd_v3_sub(clip[k + 1], clip[0]);
            sd_real at = SD_R(0.5) * sd_v3_dot(nf, sd_v3_cross(e1, e2));
            af += at;
            /* centroid relative to p0: (clip0 + clipk + clipk+1)/3 - p0 */
            sd_vec3 ct = sd_v3_sub(sd_v3_scale(sd_v3_add(clip[0], sd_v3_add(clip[k], clip[k + 1])), SD_R(1.0) / SD_R(3.0)), p0);
            cf = sd_v3_madd(cf, at, ct);
        }
        if (!(af > SD_R(0.0)))
            continue;
        vol += (hf - sd_v3_dot(nf, p0)) * af / SD_R(3.0);
        sa = sd_v3_madd(sa, af, nf);
        ++nfaces;
        ta = sd_v3_add(ta, sd_v3_cross(cf, nf)); /* cf already carries a_f */
    }
    sd_real area = sd_v3_dot(sa, nb);
    if (!(vol > SD_R(0.0)) || !(area > SD_R(0.0))) {
        o.status = SD_OVERLAP_DEGENERATE; /* a sliver below rounding: no force */
        return o;
    }
    /* x_c - p0 = (S × T) / |S|^2 with S = area nb: in the cut plane */
    sd_vec3 rc = sd_v3_scale(sd_v3_cross(nb, ta), SD_R(1.0) / area);
    rc = sd_v3_madd(rc, -sd_v3_dot(rc, nb), nb);
    sd_vec3 xc = sd_v3_add(p0, rc);
    o.status = SD_OVERLAP_OK;
    o.volume = vol;
    o.area = area;
    o.normal = n;
    o.point = sd_v3_add(a->x, sd_quat_rotate(a->q, xc));
    o.twist = SD_R(0.0);
    o.s_a = sd_quat_rotate(a->q, sa);
    o.s_b = sd_v3_neg(o.s_a);
    o.faces = nfaces + 1; /* A's clipped faces and the cut face */
    /* a point inside I: halfway from the cut-face centroid to the deepest vertex */
    o.x0 = sd_v3_add(a->x, sd_quat_rotate(a->q, sd_v3_scale(sd_v3_add(xc, dt[deep].v), SD_R(0.5))));
    return o;
}

/* Depth of the overlap along n (m): how far A reaches into B. */
SD_HD static SD_INLINE sd_real sd_halfspace_depth(const sd_convex *a, sd_vec3 n, sd_real h)
{
    return sd_v3_dot(n, sd_convex_support_core(a, n)) - h;
}

#endif
