/* convex_contact.h — contact geometry (normal, point, overlap) of two posed
 * convex bodies, and of one body against a half-space wall.
 * Single source (SD_HD): C17 and CUDA C++, no allocation, no printing.
 *
 * What: seed 004 §2.5 shrink / GJK / swell. Every shape is a convex core
 * swept by a sphere of radius r (shape.h). GJK measures the core distance d;
 * while d < ra + rb the swept bodies overlap by δ = ra + rb − d along
 * n = (pa − pb)/d, exactly, with no EPA (n is taken from GJK's v = pa − pb). Only when the cores themselves
 * touch or overlap does EPA give the core depth D, and then δ = D + ra + rb
 * along EPA's normal (DESIGN.md note "GJK/EPA"; notes/algorithms.md §C).
 * Sharp cylinder–cylinder and box–cylinder cores (ra = rb = 0) take the
 * closed form of geom/cylinder_contact.h instead of EPA, which stays their
 * fallback.
 *
 * Invariants: n is unit and points from b to a (moving a along n reduces the
 * overlap); the contact point lies halfway between the two outer surfaces
 * along n: with pa, pb the witness (or deepest) points of the cores, A's
 * outer surface there is pa − ra·n and B's is pb + rb·n, and
 *     point = ½ (pa − ra·n + pb + rb·n).
 * In both branches (pa − ra·n) − (pb + rb·n) = −δ·n. Nothing is NaN, even
 * for coincident point cores (two spheres at one centre: n = +z).
 */
#ifndef SD_GEOM_CONVEX_CONTACT_H
#define SD_GEOM_CONVEX_CONTACT_H

#include "geom/cylinder_contact.h"
#include "geom/epa.h"
#include "shape/support.h" /* sd_shape_support_height */

typedef struct sd_convex_contact {
    int touching;                  /* 1 when the swept bodies overlap (delta > 0) */
    sd_vec3 n;                     /* unit, from b to a */
    sd_vec3 point;                 /* m, midway through the overlap */
    sd_real delta;                 /* m, overlap > 0 (negative: the gap when GJK measured one, or,
                                      when GJK stopped early, an upper bound of −gap) */
    int used_epa;                  /* the cores overlapped: EPA (or the closed form) gave the depth */
    int closed_form;               /* the depth came from geom/cylinder_contact.h, not EPA */
    int iterations, support_calls; /* GJK + EPA together */
    int status;                    /* sd_gjk_status of the core distance */
    int epa_status;                /* sd_epa_status when used_epa, else -1 */
    sd_real twist_arm;             /* m, sd_convex_plane only: the lever of the face's torsional
                                      friction (0: a point contact) */
} sd_convex_contact;

/* Rounding allowance of sd_convex_apart_along, relative to |d|_1 times the
 * pair's magnitudes (m). */
#define SD_CONVEX_APART_TOL SD_R(1e-11)

/* 1 when direction d proves the swept bodies A->c and B->c apart in the way
 * GJK's own first step on d (rule 0 of gjk.h) proves it, so that a caller
 * may skip GJK and keep GJK's answer (sd_convex_apart_warm).
 *
 * The test, a separating axis on the support functions (shape/support.h):
 *     u = d . (xa - xb) + h_a(Ra^T d) + h_b(Rb^T (-d))
 * is the largest value of d . (p - q) over points p of A's core and q of
 * B's (h: sd_shape_support_height, the core's height along a direction in
 * its principal frame). If u < -(ra + rb) |d|, every p and q lie more than
 * ra + rb apart along d/|d|, so the swept bodies (cores swept by ra, rb)
 * cannot touch: the test never rejects a touching pair, nor one within the
 * margin -u/|d| - (ra + rb) of touching.
 *
 * Why GJK's answer is the same, bit for bit: GJK's first support point
 * w = s_a(d) - s_b(-d), with stop_beyond = ra + rb (sd_convex_collide_bodies),
 * gives d . w <= u (the support points are points of the cores), and GJK
 * stops at once, SEPARATED and bounded, its direction d unchanged, when
 * d . w < 0 and (d . w)^2 > (ra + rb)^2 |d|^2. Both sides are computed in
 * floating point from the same d, positions and rotation matrices (entries
 * <= 1: unit quaternions, renormalised every step). Each rounds by a few
 * tens of ulp of |d|_1 (|xa|_1 + |xb|_1 + bound_a + bound_b) at most
 * (three-term dots and sums of those magnitudes; the support points are
 * core points up to a few ulp of the bound), so the allowance tol, 1e-11
 * of that (about 90,000 ulp), makes u + tol < -(ra + rb) |d| imply GJK's
 * rule 0 in floating point. The range checks keep GJK's squares normal and
 * every value finite (a non-finite pose is left to GJK, which reports it).
 * tests/unit/composite_cull.c checks both claims on random poses of every
 * kind. */
SD_HD static SD_HOT int sd_convex_apart_along(const sd_gjk_body *A, const sd_gjk_body *B, sd_vec3 d)
{
    const sd_convex *a = A->c, *b = B->c;
    const sd_real(*ma)[3] = A->R.m;
    const sd_real(*mb)[3] = B->R.m;
    sd_real d1 = sd_fabs(d.x) + sd_fabs(d.y) + sd_fabs(d.z);
    sd_real s = A->scale + B->scale;
    /* |d| in [1e-100, 1e100] and magnitudes below 1e100: u, tol and GJK's
     * squares stay finite and normal (false for NaN) */
    if (!(d1 >= SD_R(1e-100) && d1 <= SD_R(1e100) && s <= SD_R(1e100)))
        return 0;
    /* d in each principal frame, as sd_convex_support_core_m turns it */
    sd_vec3 da = sd_v3(ma[0][0] * d.x + ma[1][0] * d.y + ma[2][0] * d.z,
                       ma[0][1] * d.x + ma[1][1] * d.y + ma[2][1] * d.z,
                       ma[0][2] * d.x + ma[1][2] * d.y + ma[2][2] * d.z);
    sd_vec3 nd = sd_v3_neg(d);
    sd_vec3 db = sd_v3(mb[0][0] * nd.x + mb[1][0] * nd.y + mb[2][0] * nd.z,
                       mb[0][1] * nd.x + mb[1][1] * nd.y + mb[2][1] * nd.z,
                       mb[0][2] * nd.x + mb[1][2] * nd.y + mb[2][2] * nd.z);
    sd_real u = sd_v3_dot(d, sd_v3_sub(a->x, b->x)) + sd_shape_support_height(a->shape, a->verts, da) +
                sd_shape_support_height(b->shape, b->verts, db);
    sd_real tol = SD_CONVEX_APART_TOL * d1 * s;
    sd_real r = a->shape->radius + b->shape->radius;
    sd_real reach = r > SD_R(0.0) ? r * sd_v3_norm(d) : SD_R(0.0);
    /* tol >= 1e-150: -d . w > tol / 2 keeps GJK's (d . w)^2 > 0; u finite */
    return tol >= SD_R(1e-150) && u > -SD_R(1e300) && u + tol < -reach;
}

/* For a caller that needs only the touching pairs, before
 * sd_convex_collide_bodies(A, B, warm_dir, 0): 1 when GJK's start
 * direction (sd_gjk_start_dir of *warm_dir) proves the pair apart
 * (sd_convex_apart_along); *warm_dir is then set to that direction, as
 * GJK's rule 0 would leave it, and the pair is apart with every result of
 * sd_convex_collide_bodies's early answer (touching 0) but no GJK query.
 * Most element pairs of a composite bed that pass their bounding spheres
 * are answered here (backend/items.h). */
SD_HD static SD_HOT int sd_convex_apart_warm(const sd_gjk_body *A, const sd_gjk_body *B, sd_vec3 *warm_dir)
{
    sd_vec3 d = sd_gjk_start_dir(A->c, B->c, *warm_dir);
    if (!sd_convex_apart_along(A, B, d))
        return 0;
    *warm_dir = d;
    return 1;
}

/* Contact of the swept bodies A->c and B->c, their rotation matrices
 * given (sd_gjk_body_of; built once by a caller that queries one body many
 * times). warm_dir (may be NULL) holds the pair's cached GJK direction; it
 * is read as the start and updated. gap 0: a caller that needs only the
 * touching pairs skips the normal and the gap of a pair that GJK proved
 * apart early (bounded: touching 0, delta 0, n +z, point the midpoint);
 * every other field, and *warm_dir, as with gap 1. */
SD_HD static SD_INLINE sd_convex_contact sd_convex_collide_bodies(const sd_gjk_body *A, const sd_gjk_body *B,
                                                                  sd_vec3 *warm_dir, int gap)
{
    sd_convex_contact c;
    const sd_convex *a = A->c, *b = B->c;
    const sd_real ra = a->shape->radius, rb = b->shape->radius;
    /* the swept bodies cannot touch once the core distance exceeds ra + rb:
     * GJK stops as soon as a support point proves it (gjk.h, rule 0) */
    sd_gjk_result g = sd_gjk_distance_bodies(A, B, warm_dir ? *warm_dir : sd_v3_zero(), ra + rb);
    if (warm_dir)
        *warm_dir = g.dir;
    c.status = g.status;
    c.epa_status = -1;
    c.used_epa = 0;
    c.closed_form = 0;
    c.iterations = g.iterations;
    c.support_calls = g.support_calls;
    c.touching = 0;
    c.n = sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0));
    c.point = sd_v3_scale(sd_v3_add(a->x, b->x), SD_R(0.5));
    c.delta = SD_R(0.0);
    if (g.status == SD_GJK_DEGENERATE || (g.bounded && !gap))
        return c;

    sd_vec3 pa = g.pa, pb = g.pb;
    if (g.status == SD_GJK_SEPARATED || g.status == SD_GJK_MAX_ITER) {
        /* shrink / GJK / swell: exact while the cores stay apart */
        sd_real d = g.distance;
        c.delta = ra + rb - d;
        /* n from v = −dir, which GJK keeps exactly; pa − pb carries the
         * rounding of the barycentric weights */
        if (d > SD_R(0.0) || g.bounded)
            c.n = sd_v3_normalize(sd_v3_neg(g.dir));
    } else {
        /* the cores touch or overlap. Sharp cylinder–cylinder and
         * box–cylinder cores (no margin, no rounding): the closed form of
         * geom/cylinder_contact.h (EPA needs ~21 iterations on their curved
         * sides, issue 11 §5); everything else, and its fallback: EPA */
        sd_cylc_result k;
        k.status = SD_CYLC_FALLBACK;
        if (ra == SD_R(0.0) && rb == SD_R(0.0) && sd_cylc_pair(a->shape->kind, b->shape->kind))
            k = sd_cylc_penetration(a, b);
        c.used_epa = 1;
        if (k.status == SD_CYLC_OK) {
            c.closed_form = 1;
            c.delta = k.depth;
            c.n = k.normal;
            pa = k.pa;
            pb = k.pb;
        } else {
            sd_epa_result e = sd_epa_penetration(a, b, &g);
            c.epa_status = e.status;
            c.iterations += e.iterations;
            c.support_calls += e.support_calls;
            c.delta = e.depth + ra + rb;
            c.n = e.normal;
            pa = e.pa;
            pb = e.pb;
        }
    }
    c.touching = c.delta > SD_R(0.0);
    c.point = sd_v3_scale(sd_v3_add(sd_v3_madd(pa, -ra, c.n), sd_v3_madd(pb, rb, c.n)), SD_R(0.5));
    return c;
}

/* Contact of the swept bodies a and b (sd_convex_collide_bodies). */
SD_HD static SD_INLINE sd_convex_contact sd_convex_collide(const sd_convex *a, const sd_convex *b, sd_vec3 *warm_dir)
{
    const sd_gjk_body A = sd_gjk_body_of(a), B = sd_gjk_body_of(b);
    return sd_convex_collide_bodies(&A, &B, warm_dir, 1);
}

/* Body-frame point p of a's core in the world (the pose convention of
 * shape.h: the core's reference point sits at `offset` in the principal frame). */
SD_HD static SD_INLINE sd_vec3 sd_convex_core_to_world(const sd_convex *a, sd_vec3 p)
{
    return sd_v3_add(a->x, sd_quat_rotate(a->q, sd_v3_add(a->shape->offset, p)));
}

/* Contact of the swept body a with the half-space wall {x : (x − p0)·nplane < 0}
 * (nplane unit, pointing into free space; n of the result is nplane).
 *
 * The depth comes from the core's support point s in −nplane:
 * δ = r − (s − p0)·nplane, and the contact point is halfway through the
 * overlap below the deepest core point — except for the flat features.
 *
 * Boxes and polyhedra (issue 30): with d_i = max(0, r − h_i) the depths of
 * the core's corners (h_i their heights over the plane), the depth is the
 * Lehmer mean δ* = Σ d_i³ / Σ d_i² and the point lies below the corners'
 * centroid weighted by the gradient of δ*, g_i = d_i (3 d_i − 2 δ*) / Σ d_i².
 * δ* is the common depth of a face or an edge flat on the plane and the
 * depth of a lone corner (the old rule's two cases), and in between it
 * and the point move continuously with the tilt: the force F(δ*) applied
 * at that point is (up to Σ g_i, 1 in both limits) the gradient of the
 * potential U(δ*), so a tilted face feels a restoring moment and comes to
 * rest. The old rule (the deepest corner's depth, the point under the
 * corners within 1e-9 L of it) jumped between a face, an edge and a
 * corner at every slight tilt: a cube on a slope rocked for ever, its
 * friction spring carried from point to point, and walked uphill at
 * ~20 µm/s (tests/validation/mesh_vs_plane.c). Where shallow corners
 * outweigh the deep ones (Σ g_i < 1/2, a polyhedron of many corners
 * barely tilted into the plane) the deepest corner's depth and point are
 * kept.
 *
 * Cylinders and cones (a tie broken by rounding otherwise): the cap
 * centre for a cap tilted by less than 1e-9 L over its diameter, the
 * midpoint of a cylinder's mantle line tilted by less than 1e-9 L over its
 * length. */
/* Corner i of a box or polyhedron core, in the body frame. */
SD_HD static SD_INLINE sd_vec3 sd_convex_plane_corner(const sd_shape *sh, const sd_vec3 *verts, int i)
{
    if (sh->kind == SD_SHAPE_BOX)
        return sd_v3((i & 1) ? sh->a.x : -sh->a.x, (i & 2) ? sh->a.y : -sh->a.y, (i & 4) ? sh->a.z : -sh->a.z);
    return verts[sh->vstart + (uint32_t)i];
}
SD_HD static SD_INLINE sd_convex_contact sd_convex_plane(const sd_convex *a, sd_vec3 p0, sd_vec3 nplane)
{
    sd_convex_contact c;
    const sd_shape *sh = a->shape;
    const sd_real r = sh->radius;
    const sd_real L = sh->bound > SD_R(0.0) ? sh->bound : SD_R(1.0);
    const sd_real tol = SD_R(1e-9) * L;
    sd_vec3 s = SD_GJK_SUPPORT_CORE(a, sd_v3_neg(nplane));
    c.status = sd_gjk_finite(s) ? SD_GJK_SEPARATED : SD_GJK_DEGENERATE;
    c.epa_status = -1;
    c.used_epa = 0;
    c.closed_form = 0;
    c.iterations = 0;
    c.support_calls = 1;
    c.n = nplane;
    c.twist_arm = SD_R(0.0);
    if (c.status == SD_GJK_DEGENERATE) {
        c.touching = 0;
        c.delta = SD_R(0.0);
        c.point = a->x;
        return c;
    }
    sd_real h = sd_v3_dot(sd_v3_sub(s, p0), nplane);
    c.delta = r - h;
    c.touching = c.delta > SD_R(0.0);

    sd_vec3 nl = sd_quat_rotate_inv(a->q, nplane); /* wall normal in the body frame */
    sd_vec3 cen = s;
    if ((sh->kind == SD_SHAPE_BOX || sh->kind == SD_SHAPE_POLYHEDRON) && c.touching) {
        /* the corners' depths d_i = r - h_i (0 when not below the swept
         * surface), h_i their heights over the plane: the plane's height
         * in the body frame is hp, so h_i = p_i . nl - hp */
        int nv = sh->kind == SD_SHAPE_BOX ? 8 : (int)sh->vcount;
        sd_real hp = sd_v3_dot(sd_v3_sub(p0, sd_convex_core_to_world(a, sd_v3_zero())), nplane);
        sd_real s1 = SD_R(0.0), s2 = SD_R(0.0), s3 = SD_R(0.0), m2 = SD_R(0.0);
        sd_vec3 m1 = sd_v3_zero();
        for (int i = 0; i < nv; ++i) {
            sd_vec3 p = sd_convex_plane_corner(sh, a->verts, i);
            sd_real di = sd_max(SD_R(0.0), r - (sd_v3_dot(p, nl) - hp));
            sd_vec3 pt = sd_v3_madd(p, -sd_v3_dot(p, nl), nl); /* in the plane */
            s1 += di;
            s2 += di * di;
            s3 += di * di * di;
            m1 = sd_v3_madd(m1, di * di, pt);
            m2 += di * di * sd_v3_dot(pt, pt);
        }
        /* the torsional lever: 2/3 of the corners' RMS distance (weights
         * d_i^2) from their centre in the plane, the (2/3) R of a disc
         * pressed evenly (a square face of side L gets 0.47 L, its exact
         * 0.38 L); 0 for a lone corner */
        if (s2 > SD_R(0.0)) {
            sd_real var = m2 / s2 - sd_v3_dot(m1, m1) / (s2 * s2);
            c.twist_arm = var > SD_R(0.0) ? SD_R(2.0) / SD_R(3.0) * sd_sqrt(var) : SD_R(0.0);
        }
        /* delta* = s3 / s2 and its gradient d_i (3 d_i - 2 delta*) / s2,
         * summing to 3 - 2 delta* s1 / s2 (1 on a face or a corner) */
        sd_real ds = s2 > SD_R(0.0) ? s3 / s2 : SD_R(0.0);
        sd_real gsum = s2 > SD_R(0.0) ? SD_R(3.0) - SD_R(2.0) * ds * s1 / s2 : SD_R(0.0);
        if (gsum >= SD_R(0.5)) {
            sd_vec3 sum = sd_v3_zero();
            for (int i = 0; i < nv; ++i) {
                sd_vec3 p = sd_convex_plane_corner(sh, a->verts, i);
                sd_real di = sd_max(SD_R(0.0), r - (sd_v3_dot(p, nl) - hp));
                sum = sd_v3_madd(sum, di * (SD_R(3.0) * di - SD_R(2.0) * ds), p);
            }
            cen = sd_convex_core_to_world(a, sd_v3_scale(sum, SD_R(1.0) / (gsum * s2)));
            c.delta = ds;
        }
    } else if (sh->kind == SD_SHAPE_CYLINDER || sh->kind == SD_SHAPE_CONE) {
        /* a cap of radius R tilted by angle t dips 2 R sin t across */
        sd_real sin_t = sd_sqrt(sd_max(SD_R(0.0), SD_R(1.0) - nl.z * nl.z));
        if (SD_R(2.0) * sh->a.x * sin_t <= tol) {
            /* cylinder: cap at ±half length; cone: the base (at the core's
             * reference point) when the wall is below it, else the apex */
            sd_real zc;
            if (sh->kind == SD_SHAPE_CYLINDER)
                zc = nl.z > SD_R(0.0) ? -sh->a.z : sh->a.z;
            else
                zc = nl.z > SD_R(0.0) ? SD_R(0.0) : sh->a.z;
            cen = sd_convex_core_to_world(a, sd_v3(SD_R(0.0), SD_R(0.0), zc));
        } else if (sh->kind == SD_SHAPE_CYLINDER && SD_R(2.0) * sh->a.z * sd_fabs(nl.z) <= tol) {
            /* a cylinder on its side: the mantle line of length 2 a.z,
             * tilted by asin |nl.z|, dips 2 a.z |nl.z| along it; the
             * support returns one end (a tie broken by rounding), whose
             * lever arm spins the body (seed 004 §3.2, Fig. 9b): take the
             * line's midpoint */
            sd_vec3 sl = sd_v3_sub(sd_quat_rotate_inv(a->q, sd_v3_sub(s, a->x)), sh->offset);
            cen = sd_convex_core_to_world(a, sd_v3(sl.x, sl.y, SD_R(0.0)));
        }
    }
    sd_real hc = sd_v3_dot(sd_v3_sub(cen, p0), nplane);
    c.point = sd_v3_madd(cen, -(hc + SD_R(0.5) * c.delta), nplane);
    return c;
}

#endif
