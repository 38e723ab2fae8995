/* items.h — one item function per interaction kind of contact/kinds.h:
 * everything one pair needs between the views and the contact numerics —
 * the bodies and posed shapes read from the particle arrays, the spring
 * seen from the lower stable id, the mixed parameters of the two
 * materials, the call into contact/pair*.h and the write-back of the
 * pair's slots. The CPU loops (backend/cpu/) call them now, one loop per
 * kind segment; CUDA kernels will call the same functions, one kernel per
 * segment (exaDEM's classified interactions, STYLE.md convention 10).
 *
 * Invariants: an item reads the views and writes only the slots of its own
 * pair e, so any order and any thread count give the same bits (DESIGN.md
 * rule 4); the history spring ds is stored as seen from the body with the
 * lower stable id (broad/pairs.h) and an item flips it on the way in and
 * out; no item takes sd_world, allocates or prints. The physics is that of
 * contact/: sphere contacts and Hertz / linear laws (seed 004 eqs. 9-16),
 * the convex narrow phase (seed 004 §2.5), the volume law of sharp
 * polyhedra (seed 000 eqs. 12-22) and the planar mode (seed 002); wall
 * features (planes, box faces, their lines in the plane) are those of
 * dynamics/walls.h. Which item a pair takes is decided once, at the
 * rebuild (broad/bins.h, sd_bins_pair_kind): the kind segment says it.
 *
 * Composites (seed 004 §2.5-2.6): the item of the element kinds is one
 * composite pair (or one particle and one wall feature), the run of its
 * element pairs in the segment. Each element pair is one contact with its
 * own history, evaluated like the pair of convex bodies it is (two sphere
 * elements by the analytic sphere contact, a clump as cheap as its
 * spheres; otherwise the convex narrow phase on the posed elements; two
 * sharp polyhedra under a volume law by the overlap volume), with the
 * lever arms from each composite's centre of mass, and the run is then
 * combined: model B (average, the default) divides every force, torque and
 * energy of the run by its number of touching element pairs N_c (eq. 21);
 * model A (sum) keeps the sum and divides the damping by sqrt(N_c)
 * (eq. 18; the depth laws' gamma_n and eta, the volume laws' zeta), N_c
 * found by a geometry-only pass over the run first. The run
 * is one item, so the combination needs no second pass and no atomics.
 *
 * Single source (SD_HD): compiles as C17 and as CUDA C++
 * (tests/cuda/items.cu).
 */
#ifndef SD_BACKEND_ITEMS_H
#define SD_BACKEND_ITEMS_H

#include <string.h>

#include "backend/view.h"
#include "contact/pair.h"
#include "contact/pair2d.h"
#include "contact/pair_convex.h"
#include "contact/pair_poly.h"
#include "dynamics/walls.h"
#include "geom/mesh_contact.h"
#include "geom/mesh_contact2d.h"

/* ---- views of one particle ----------------------------------------------- */

/* Particle k as a pair evaluation sees it; plain spheres get no rotational
 * term in the effective mass (their contacts are central). */
SD_HD static SD_HOT sd_body sd_item_body(const sd_step_view *v, size_t k)
{
    sd_body b;
    b.x = v->x[k];
    b.v = v->v[k];
    b.w = v->w[k];
    b.radius = v->radius[k];
    b.inv_mass = v->inv_mass[k];
    b.inv_inertia = v->shape[k] >= 0 ? v->inv_inertia[k] : sd_v3_zero();
    b.q = v->q[k];
    return b;
}

/* A plain sphere of a sphere pair: central contacts, so no orientation to
 * load in the hottest loop. */
SD_HD static SD_HOT sd_body sd_item_sphere_body(const sd_step_view *v, size_t k)
{
    sd_body b;
    b.x = v->x[k];
    b.v = v->v[k];
    b.w = v->w[k];
    b.radius = v->radius[k];
    b.inv_mass = v->inv_mass[k];
    b.inv_inertia = sd_v3_zero();
    b.q = sd_quat_identity();
    return b;
}

/* The posed 3D convex body of particle k, a shape template (shape >= 0). */
SD_HD static SD_INLINE sd_convex sd_item_shape_of(const sd_step_view *v, size_t k)
{
    sd_convex c;
    c.shape = &v->shapes[v->shape[k]];
    c.verts = v->verts;
    c.planes = v->planes;
    c.dtris = v->dtris;
    c.x = v->x[k];
    c.q = v->q[k];
    return c;
}

/* The same for any particle: a plain sphere becomes a point core swept by
 * its radius, written into *tmp. */
SD_HD static SD_INLINE sd_convex sd_item_convex_of(const sd_step_view *v, size_t k, sd_shape *tmp)
{
    if (v->shape[k] >= 0)
        return sd_item_shape_of(v, k);
    memset(tmp, 0, sizeof *tmp);
    tmp->kind = SD_SHAPE_SPHERE;
    tmp->radius = v->radius[k];
    tmp->bound = v->radius[k];
    sd_convex c;
    c.shape = tmp;
    c.verts = v->verts;
    c.planes = v->planes;
    c.dtris = v->dtris;
    c.x = v->x[k];
    c.q = v->q[k];
    return c;
}

/* The posed 2D convex body of particle k; a plain disc becomes a point
 * core swept by its radius, written into *tmp. */
SD_HD static SD_INLINE sd_convex2d sd_item_convex2d_of(const sd_step_view *v, size_t k, sd_shape2d *tmp)
{
    sd_convex2d c;
    if (v->shape[k] >= 0) {
        c.shape = &v->shapes2d[v->shape[k]];
    } else {
        memset(tmp, 0, sizeof *tmp);
        tmp->kind = SD_SHAPE2D_CIRCLE;
        tmp->radius = v->radius[k];
        tmp->bound = v->radius[k];
        tmp->eq_radius = v->radius[k];
        c.shape = tmp;
    }
    c.pool = v->pool2d;
    c.x = sd_v2(v->x[k].x, v->x[k].y);
    c.theta = sd_quat_angle_z(v->q[k]);
    return c;
}

/* m, radius of the sphere of the same volume: Hertz's R* for shapes. */
SD_HD static SD_INLINE sd_real sd_item_equivalent_radius(const sd_step_view *v, size_t k)
{
    int s = v->shape[k];
    return s >= 0 ? v->shape_req[s] : v->radius[k];
}

/* The mixed parameters of materials a and b. */
SD_HD static SD_HOT const sd_pair_params *sd_item_params(const sd_step_view *v, int32_t a, int32_t b)
{
    return &v->mix[(size_t)a * v->material_count + (size_t)b];
}

/* The shape kind of particle k (3D): plain spheres are spheres. */
SD_HD static SD_INLINE int sd_item_shape_kind(const sd_step_view *v, size_t k)
{
    int s = v->shape[k];
    return s >= 0 ? v->shapes[s].kind : SD_SHAPE_SPHERE;
}

/* The 2D shape kind of particle k: plain discs are circles. */
SD_HD static SD_INLINE int sd_item_shape2d_kind(const sd_step_view *v, size_t k)
{
    int s = v->shape[k];
    return s >= 0 ? v->shapes2d[s].kind : SD_SHAPE2D_CIRCLE;
}

/* ---- write-back ---------------------------------------------------------- */

/* The slots of particle pair e: the spring back in the lower id's frame. */
SD_HD static SD_HOT void sd_item_store(sd_pair_out *o, size_t e, int flip, sd_vec3 ds, const sd_pair_result *r)
{
    o->ds[e] = flip ? sd_v3_neg(ds) : ds;
    o->f[e] = r->f;
    o->t[2 * e] = r->ti;
    o->t[2 * e + 1] = r->tj;
    o->delta[e] = r->delta;
    o->energy[e] = r->energy;
}

/* The slots of wall pair e (its spring was updated in place). */
SD_HD static SD_HOT void sd_item_wall_store(sd_wall_pair_out *o, size_t e, sd_vec3 point, const sd_pair_result *r)
{
    o->f[e] = r->f;
    o->t[e] = r->ti;
    o->c[e] = point;
    o->delta[e] = r->delta;
    o->energy[e] = r->energy;
}

/* ---- particle-particle kinds --------------------------------------------- */

/* SD_PAIR_SPHERES: two plain spheres (or discs). */
SD_HD static SD_HOT void sd_item_spheres(const sd_step_view *v, sd_pair_out *o, size_t e)
{
    uint32_t i = o->i[e], j = o->j[e];
    /* a candidate that is apart and was apart has nothing to write: its
     * force, torques and spring are already zero (most of the skin's pairs,
     * and most of the memory traffic of this loop) */
    sd_real rs = v->radius[i] + v->radius[j];
    if (o->delta[e] <= 0 && sd_v3_norm2(sd_v3_sub(v->x[i], v->x[j])) >= rs * rs)
        return;
    sd_body a = sd_item_sphere_body(v, i), b = sd_item_sphere_body(v, j);
    const sd_pair_params *prm = sd_item_params(v, v->material[i], v->material[j]);
    int flip = o->flip[e];
    sd_vec3 ds = flip ? sd_v3_neg(o->ds[e]) : o->ds[e];
    sd_pair_result r = sd_pair_spheres(prm, &a, &b, &ds, v->dt);
    sd_item_store(o, e, flip, ds, &r);
}

/* SD_PAIR_CONVEX: a shape template on one side at least (3D). */
SD_HD static SD_INLINE void sd_item_convex(const sd_step_view *v, sd_pair_out *o, size_t e)
{
    uint32_t i = o->i[e], j = o->j[e];
    sd_shape si, sj;
    sd_convex ci = sd_item_convex_of(v, i, &si), cj = sd_item_convex_of(v, j, &sj);
    sd_body a = sd_item_body(v, i), b = sd_item_body(v, j);
    const sd_pair_params *prm = sd_item_params(v, v->material[i], v->material[j]);
    sd_real ra = sd_item_equivalent_radius(v, i), rb = sd_item_equivalent_radius(v, j);
    sd_narrow_count ns;
    int flip = o->flip[e];
    sd_vec3 ds = flip ? sd_v3_neg(o->ds[e]) : o->ds[e];
    sd_pair_result r = sd_pair_convex(prm, &a, &b, &ci, &cj, ra * rb / (ra + rb), &ds, &o->warm[e], v->dt, &ns);
    sd_item_store(o, e, flip, ds, &r);
    o->iters[e] = ns.iterations;
    o->supports[e] = ns.supports;
}

/* SD_PAIR_POLY_VOLUME: two sharp polyhedra under a volume law; ws is the
 * calling thread's overlap workspace (a few KB to tens of KB: one per
 * thread, never one per pair). */
SD_HD static SD_INLINE void sd_item_poly_volume(const sd_step_view *v, sd_pair_out *o, size_t e,
                                                sd_overlap_workspace *ws)
{
    uint32_t i = o->i[e], j = o->j[e];
    sd_narrow_count ns = {0, 0};
    int si = v->shape[i], sj = v->shape[j];
    int flip = o->flip[e];
    sd_vec3 ds = flip ? sd_v3_neg(o->ds[e]) : o->ds[e];
    sd_pair_result r;
    if (si < 0 || sj < 0 || !sd_shape_is_sharp_polyhedron(&v->shapes[si]) ||
        !sd_shape_is_sharp_polyhedron(&v->shapes[sj])) {
        r = sd_pair_none(&ds); /* refused at prepare time (world/material.c); never a force */
    } else {
        sd_convex ci = sd_item_shape_of(v, i), cj = sd_item_shape_of(v, j);
        sd_body a = sd_item_body(v, i), b = sd_item_body(v, j);
        const sd_pair_params *prm = sd_item_params(v, v->material[i], v->material[j]);
        r = sd_pair_poly(prm, &a, &b, &ci, &cj, v->shape_req[si], v->shape_req[sj], &ds, &o->x0[e], &o->x0_ok[e], ws,
                         v->dt, &ns);
    }
    sd_item_store(o, e, flip, ds, &r);
    o->iters[e] = ns.iterations;
    o->supports[e] = ns.supports;
}

/* SD_PAIR_CONVEX2D: a 2D shape template on one side at least. iters holds
 * 1 for a contact, 0 otherwise (seed 002 Table 1 counts the two apart). */
SD_HD static SD_INLINE void sd_item_convex2d(const sd_step_view *v, sd_pair_out *o, size_t e)
{
    uint32_t i = o->i[e], j = o->j[e];
    sd_shape2d si, sj;
    sd_convex2d ci = sd_item_convex2d_of(v, i, &si), cj = sd_item_convex2d_of(v, j, &sj);
    sd_body a = sd_item_body(v, i), b = sd_item_body(v, j);
    const sd_pair_params *prm = sd_item_params(v, v->material[i], v->material[j]);
    sd_real ra = ci.shape->eq_radius, rb = cj.shape->eq_radius;
    int flip = o->flip[e];
    sd_vec3 ds = flip ? sd_v3_neg(o->ds[e]) : o->ds[e];
    sd_vec2 warm = sd_v2(o->warm[e].x, o->warm[e].y);
    int supports = 0;
    sd_pair_result r = sd_pair_convex2d(prm, &a, &b, &ci, &cj, ra * rb / (ra + rb), &ds, &warm, v->dt, &supports);
    o->warm[e] = sd_v3(warm.x, warm.y, SD_R(0.0));
    sd_item_store(o, e, flip, ds, &r);
    o->iters[e] = r.delta > 0;
    o->supports[e] = supports;
}

/* ---- composite elements (seed 004 §2.5-2.6) ------------------------------ */

/* Element sub of particle k as a posed convex body: for a composite,
 * element estart + sub of its template, at x_e = x + R(q) e.x with
 * orientation q_e = q e.q (seed 004 eqs. 5-6, derived here, never stored);
 * any other particle is its own element 0 (a plain sphere a point core
 * written into *tmp). *req: the element's radius of equal volume, m (the
 * R* of Hertz and the E/R of the volume laws). */
SD_HD static SD_HOT sd_convex sd_item_element_of(const sd_step_view *v, size_t k, uint32_t sub, sd_shape *tmp,
                                                 sd_real *req)
{
    int s = v->shape[k];
    if (s >= 0 && v->shapes[s].kind == SD_SHAPE_COMPOSITE) {
        const sd_element *el = &v->elements[v->shapes[s].estart + sub];
        sd_convex c;
        c.shape = &v->shapes[el->shape];
        c.verts = v->verts;
        c.planes = v->planes;
        c.dtris = v->dtris;
        c.x = sd_v3_add(v->x[k], sd_quat_rotate(v->q[k], el->x));
        c.q = sd_quat_mul(v->q[k], el->q);
        *req = v->shape_req[el->shape];
        return c;
    }
    *req = sd_item_equivalent_radius(v, k);
    return sd_item_convex_of(v, k, tmp);
}

/* The posed elements of one side of a run (one composite pair): each
 * element derived once by sd_item_element_of and, when GJK asks, its
 * rotation matrix built once (sd_gjk_body_of), then reused by every
 * element pair of the run that names it. Two crosses of 7 cubes have up to
 * 49 element pairs but 14 elements; the same arithmetic on the same
 * inputs, so the same bits as posing each pair's elements anew. Elements
 * past SD_ITEM_POSE_CAP are posed again for each pair (in the spill slot). */
#define SD_ITEM_POSE_CAP 8

typedef struct sd_item_pose {
    sd_convex c;   /* the posed element */
    sd_gjk_body g; /* c with its rotation matrix, valid when has_m */
    sd_real req;   /* m, the element's radius of equal volume */
    int has_m;
} sd_item_pose;

typedef struct sd_item_poses {
    size_t k;      /* the particle */
    uint32_t have; /* bit s: slot s is posed */
    sd_shape tmp;  /* a plain sphere's point core (its element 0) */
    sd_item_pose p[SD_ITEM_POSE_CAP];
    sd_item_pose spill;
} sd_item_poses;

SD_HD static SD_INLINE void sd_item_poses_init(sd_item_poses *P, size_t k)
{
    P->k = k;
    P->have = 0;
}

/* Element sub of P's particle, posed (sd_item_element_of). */
SD_HD static SD_INLINE sd_item_pose *sd_item_pose_of(const sd_step_view *v, sd_item_poses *P, uint32_t sub)
{
    int cached = sub < SD_ITEM_POSE_CAP;
    sd_item_pose *p = cached ? &P->p[sub] : &P->spill;
    uint32_t bit = cached ? 1u << sub : 0u;
    if (P->have & bit)
        return p;
    p->c = sd_item_element_of(v, P->k, sub, &P->tmp, &p->req);
    p->has_m = 0;
    P->have |= bit;
    return p;
}

/* The GJK body of pose p: its rotation matrix built on the first call. */
SD_HD static SD_INLINE const sd_gjk_body *sd_item_pose_body(sd_item_pose *p)
{
    if (!p->has_m) {
        p->g = sd_gjk_body_of(&p->c);
        p->has_m = 1;
    }
    return &p->g;
}

/* The element sub-indices of pair e on i and on j (the key holds them in
 * stable-id order). */
SD_HD static SD_INLINE void sd_item_element_subs(const sd_pair_out *o, size_t e, uint32_t *si, uint32_t *sj)
{
    int flip = o->flip[e];
    *si = flip ? o->key[e].sub_hi : o->key[e].sub_lo;
    *sj = flip ? o->key[e].sub_lo : o->key[e].sub_hi;
}

/* 1 for a sphere element (a point core swept by its radius: the analytic
 * contact applies). */
SD_HD static SD_INLINE int sd_item_is_sphere(const sd_convex *c)
{
    return c->shape->kind == SD_SHAPE_SPHERE;
}

/* A contact of known geometry applied to the two particles (lever arms
 * from their centres of mass, seed 004 §2.6), as sd_pair_apply, except
 * that the dashpot's effective mass is the one seen at the point cm (m,
 * world): the centroid of the run's contact points. N_c contacts along a
 * line or over a face then damp like one contact at their centre (the
 * single-contact dynamics that model B's eq. 20 reproduces), and one
 * contact (cm its own point) is exactly sd_pair_apply's. */
SD_HD static SD_INLINE sd_pair_result sd_item_apply_at(const sd_pair_params *prm, const sd_body *a, const sd_body *b,
                                                       const sd_contact_geom *g, sd_real r_star, sd_vec3 *ds,
                                                       sd_real dt, sd_vec3 cm)
{
    sd_pair_result r;
    sd_vec3 arm_i = sd_v3_sub(g->point, a->x);
    sd_vec3 arm_j = sd_v3_sub(g->point, b->x);
    sd_vec3 vi = sd_v3_add(a->v, sd_v3_cross(a->w, arm_i));
    sd_vec3 vj = sd_v3_add(b->v, sd_v3_cross(b->w, arm_j));
    sd_real inv = sd_body_inv_mass_at(a, sd_v3_sub(cm, a->x), g->n) + sd_body_inv_mass_at(b, sd_v3_sub(cm, b->x), g->n);
    sd_real m_star = inv > SD_R(0.0) ? SD_R(1.0) / inv : SD_R(0.0);
    sd_contact_out o = sd_law_eval(prm, g->n, g->delta, r_star, m_star, sd_v3_sub(vi, vj), sd_v3_sub(a->w, b->w), ds, dt);
    r.f = o.force;
    r.ti = sd_v3_add(sd_v3_cross(arm_i, o.force), o.roll_torque);
    r.tj = sd_v3_sub(sd_v3_cross(arm_j, sd_v3_neg(o.force)), o.roll_torque);
    r.delta = g->delta;
    r.energy = o.energy;
    return r;
}

/* The contact geometry of element pair e: 1 touching (*g, *r_star the
 * pair's effective radius, m), 0 apart, -1 two sphere elements apart now
 * and at the last evaluation (nothing to write: the sphere loop's
 * shortcut, so a clump is as cheap as its spheres). Any other pair is the
 * convex narrow phase on the posed elements (shrink / GJK / swell, EPA
 * when the cores overlap; seed 004 §2.5), after their bounding spheres and
 * a separating-axis test on the pair's warm direction
 * (sd_convex_apart_warm: the pairs it answers are exactly pairs that GJK
 * would find apart at its first support point, with the same warm
 * direction afterwards, so the same bits). */
SD_HD static SD_INLINE int sd_item_element_geom(const sd_step_view *v, sd_pair_out *o, size_t e, sd_item_poses *Pi,
                                                sd_item_poses *Pj, sd_contact_geom *g, sd_real *r_star,
                                                sd_narrow_count *ns)
{
    uint32_t si, sj;
    sd_item_element_subs(o, e, &si, &sj);
    sd_item_pose *pi = sd_item_pose_of(v, Pi, si), *pj = sd_item_pose_of(v, Pj, sj);
    const sd_convex *ci = &pi->c, *cj = &pj->c;
    ns->iterations = 0;
    ns->supports = 0;
    if (sd_item_is_sphere(ci) && sd_item_is_sphere(cj)) {
        sd_real ra = ci->shape->radius, rb = cj->shape->radius, rs = ra + rb;
        if (o->delta[e] <= 0 && sd_v3_norm2(sd_v3_sub(ci->x, cj->x)) >= rs * rs)
            return -1;
        *r_star = ra * rb / (ra + rb);
        return sd_sphere_sphere(ci->x, ra, cj->x, rb, g);
    }
    sd_real reach = ci->shape->bound + cj->shape->bound;
    if (sd_v3_norm2(sd_v3_sub(ci->x, cj->x)) >= reach * reach)
        return 0;
    sd_real ri = pi->req, rj = pj->req;
    const sd_gjk_body *A = sd_item_pose_body(pi), *B = sd_item_pose_body(pj);
    /* apart along GJK's start direction (the pair's warm direction): GJK's
     * own first-step answer, warm direction included, without the query */
    if (sd_convex_apart_warm(A, B, &o->warm[e]))
        return 0;
    sd_convex_contact c = sd_convex_collide_bodies(A, B, &o->warm[e], 0);
    ns->iterations = c.iterations;
    ns->supports = c.support_calls;
    if (!c.touching)
        return 0;
    g->n = c.n;
    g->point = c.point;
    g->delta = c.delta;
    *r_star = ri * rj / (ri + rj);
    return 1;
}

/* Element pair e of two sharp polyhedra under a volume law, the exact
 * overlap of the posed elements (seed 000 eqs. 12-22): its geometry (1
 * and *g when they overlap; the pair's interior-point hint updated). */
SD_HD static SD_INLINE int sd_item_element_volume_geom(const sd_step_view *v, sd_pair_out *o, size_t e,
                                                       sd_overlap_workspace *ws, sd_volume_geom *g)
{
    uint32_t si, sj;
    sd_item_element_subs(o, e, &si, &sj);
    sd_shape ti, tj;
    sd_real ri, rj;
    sd_convex ci = sd_item_element_of(v, o->i[e], si, &ti, &ri), cj = sd_item_element_of(v, o->j[e], sj, &tj, &rj);
    sd_narrow_count ns = {0, 0};
    int t = 0;
    if (sd_shape_is_sharp_polyhedron(ci.shape) && sd_shape_is_sharp_polyhedron(cj.shape))
        t = sd_pair_poly_geom(&ci, &cj, &o->x0[e], &o->x0_ok[e], ws, &ns, g); /* else refused at prepare time */
    o->iters[e] = ns.iterations;
    o->supports[e] = ns.supports;
    return t;
}

/* ... and its law, lever arms from the particles' centres, the dashpot's
 * mass at cm (the run's centroid of overlap points). */
SD_HD static SD_INLINE void sd_item_element_volume_apply(const sd_step_view *v, sd_pair_out *o, size_t e,
                                                         const sd_pair_params *prm, sd_body a, sd_body b,
                                                         const sd_volume_geom *g, sd_vec3 cm)
{
    uint32_t si, sj;
    sd_item_element_subs(o, e, &si, &sj);
    sd_shape ti, tj;
    sd_real ri, rj;
    sd_convex ci = sd_item_element_of(v, o->i[e], si, &ti, &ri), cj = sd_item_element_of(v, o->j[e], sj, &tj, &rj);
    int flip = o->flip[e];
    sd_vec3 ds = flip ? sd_v3_neg(o->ds[e]) : o->ds[e];
    /* the onset area reads the bodies' radii: the elements' */
    a.radius = ci.shape->bound;
    b.radius = cj.shape->bound;
    sd_real kcoef = prm->young_a / ri + prm->young_b / rj;  /* eq. 13 */
    sd_real ktcoef = prm->shear_a / ri + prm->shear_b / rj; /* eq. 19 */
    sd_pair_result r = sd_pair_volume_apply_at(prm, &a, &b, g, kcoef, ktcoef, &ds, v->dt, cm);
    sd_item_store(o, e, flip, ds, &r);
}

/* Model A's damping for N_c contact points (seed 004 eq. 18): gamma_n of
 * one contact over sqrt(N_c), so that N_c summed contacts of equal
 * overlap restitute e_n (the viscous coefficient eta alike: N_c dashpots
 * against N_c springs). The volume laws' dashpot 2 zeta sqrt(m* F_e / d)
 * (contact/law_volume.h) is the same argument with zeta for -beta: N_c
 * of them against N_c springs have the damping ratio sqrt(N_c) zeta, so
 * every zeta(e, p) of the table is divided by sqrt(N_c) too. */
SD_HD static SD_INLINE sd_pair_params sd_item_params_sum(const sd_pair_params *prm, int nc)
{
    sd_pair_params p = *prm;
    sd_real s = SD_R(1.0) / sd_sqrt((sd_real)nc);
    p.log_e_factor *= s;
    p.eta *= s;
    for (int k = 0; k < SD_VOLUME_ZETA_N; ++k)
        p.zeta[k] *= s;
    return p;
}

/* Most touching element pairs of one run whose geometry is kept between
 * the two passes (a fixed workspace, 56 bytes each); beyond it the
 * geometry is computed again in the second pass (the same bits: the
 * narrow phase is deterministic, its warm start only a start). */
#define SD_ITEM_RUN_CAP 64

/* Model B (eq. 21): the mean over the run's contact points, forces,
 * torques and elastic energies (pairs apart hold zeros). */
SD_HD static SD_INLINE void sd_item_elements_average(sd_pair_out *o, size_t e0, size_t e1, int nc)
{
    if (nc <= 1)
        return;
    sd_real s = SD_R(1.0) / (sd_real)nc;
    for (size_t e = e0; e < e1; ++e) {
        o->f[e] = sd_v3_scale(o->f[e], s);
        o->t[2 * e] = sd_v3_scale(o->t[2 * e], s);
        o->t[2 * e + 1] = sd_v3_scale(o->t[2 * e + 1], s);
        o->energy[e] *= s;
    }
}

/* SD_PAIR_ELEMENTS: the run [e0, e1) of element pairs of one composite
 * pair (same i and j), each one contact with its own history, combined by
 * v->multi_contact (seed 004 §2.6). First pass: the geometry of every
 * pair, N_c and the centroid of the contact points; second pass: the law
 * on the touching pairs (model A with eq. 18's damping); model B then
 * divides the run by N_c. Returns N_c. ws: the thread's overlap workspace
 * (volume laws). */
SD_HD static SD_INLINE int sd_item_elements(const sd_step_view *v, sd_pair_out *o, size_t e0, size_t e1,
                                            sd_overlap_workspace *ws)
{
    uint32_t i = o->i[e0], j = o->j[e0];
    const sd_pair_params *prm = sd_item_params(v, v->material[i], v->material[j]);
    sd_body a = sd_item_body(v, i), b = sd_item_body(v, j);
    int nc = 0;
    if (sd_law_is_volume(prm->law)) {
        /* as the depth laws: the overlap geometry of every pair first, N_c
         * and the centroid of the overlaps, then the law, model A's zeta
         * divided by sqrt(N_c) (eq. 18), the dashpot's mass at the
         * centroid */
        sd_volume_geom vkeep[SD_ITEM_RUN_CAP];
        sd_vec3 cmv = sd_v3_zero();
        for (size_t e = e0; e < e1; ++e) {
            sd_volume_geom g;
            if (sd_item_element_volume_geom(v, o, e, ws, &g)) {
                if (nc < SD_ITEM_RUN_CAP)
                    vkeep[nc] = g;
                cmv = sd_v3_add(cmv, g.point);
                ++nc;
                o->delta[e] = SD_R(1.0); /* marks the overlapping pairs for the second pass */
            } else {
                int flip = o->flip[e];
                sd_vec3 ds = o->ds[e];
                sd_pair_result r = sd_pair_none(&ds);
                sd_item_store(o, e, flip, ds, &r);
            }
        }
        if (nc == 0)
            return 0;
        cmv = sd_v3_scale(cmv, SD_R(1.0) / (sd_real)nc);
        sd_pair_params sumv;
        if (v->multi_contact == SD_MULTI_CONTACT_SUM && nc > 1) {
            sumv = sd_item_params_sum(prm, nc);
            prm = &sumv;
        }
        int k = 0;
        for (size_t e = e0; e < e1 && k < nc; ++e) {
            if (!(o->delta[e] > SD_R(0.0)))
                continue;
            sd_volume_geom g;
            int ok = 1;
            if (k < SD_ITEM_RUN_CAP)
                g = vkeep[k];
            else /* beyond the workspace: the same overlap again, from its updated hint */
                ok = sd_item_element_volume_geom(v, o, e, ws, &g);
            ++k;
            if (ok) {
                sd_item_element_volume_apply(v, o, e, prm, a, b, &g, cmv);
            } else {
                int flip = o->flip[e];
                sd_vec3 ds = o->ds[e];
                sd_pair_result r = sd_pair_none(&ds);
                sd_item_store(o, e, flip, ds, &r);
            }
        }
        if (v->multi_contact == SD_MULTI_CONTACT_AVERAGE)
            sd_item_elements_average(o, e0, e1, nc);
        return nc;
    }
    sd_contact_geom keep[SD_ITEM_RUN_CAP];
    sd_real keep_r[SD_ITEM_RUN_CAP];
    sd_vec3 cm = sd_v3_zero();
    sd_item_poses Pi, Pj; /* the elements of i and of j, each posed once for the run */
    sd_item_poses_init(&Pi, i);
    sd_item_poses_init(&Pj, j);
    for (size_t e = e0; e < e1; ++e) {
        sd_contact_geom g;
        sd_real rs = SD_R(0.0);
        sd_narrow_count ns;
        int t = sd_item_element_geom(v, o, e, &Pi, &Pj, &g, &rs, &ns);
        o->iters[e] = ns.iterations;
        o->supports[e] = ns.supports;
        if (t > 0) {
            if (nc < SD_ITEM_RUN_CAP) {
                keep[nc] = g;
                keep_r[nc] = rs;
            }
            cm = sd_v3_add(cm, g.point);
            ++nc;
            o->delta[e] = g.delta; /* marks the touching pairs for the second pass */
        } else if (t == 0 && o->delta[e] > SD_R(0.0)) {
            /* apart now; a pair that was apart too (delta <= 0: the
             * rebuild and sd_pair_none leave its force, torques, energy
             * and spring zero) has nothing to write, as in the sphere
             * loop: most element pairs of a run, and most of its stores */
            int flip = o->flip[e];
            sd_vec3 ds = o->ds[e];
            sd_pair_result r = sd_pair_none(&ds);
            sd_item_store(o, e, flip, ds, &r);
        }
    }
    if (nc == 0)
        return 0;
    cm = sd_v3_scale(cm, SD_R(1.0) / (sd_real)nc);
    sd_pair_params sum;
    if (v->multi_contact == SD_MULTI_CONTACT_SUM && nc > 1) {
        sum = sd_item_params_sum(prm, nc);
        prm = &sum;
    }
    int k = 0;
    for (size_t e = e0; e < e1 && k < nc; ++e) {
        if (!(o->delta[e] > SD_R(0.0)))
            continue;
        /* Zeroed so the Release build sees them set on every path: both
         * branches below fill them for a touching element pair. */
        sd_contact_geom g;
        g.n = sd_v3(SD_R(0.0), SD_R(0.0), SD_R(0.0));
        g.point = g.n;
        g.delta = SD_R(0.0);
        sd_real rs = SD_R(0.0);
        if (k < SD_ITEM_RUN_CAP) {
            g = keep[k];
            rs = keep_r[k];
        } else {
            sd_narrow_count ns;
            (void)sd_item_element_geom(v, o, e, &Pi, &Pj, &g, &rs, &ns);
        }
        ++k;
        int flip = o->flip[e];
        sd_vec3 ds = flip ? sd_v3_neg(o->ds[e]) : o->ds[e];
        sd_pair_result r = sd_item_apply_at(prm, &a, &b, &g, rs, &ds, v->dt, cm);
        sd_item_store(o, e, flip, ds, &r);
    }
    if (v->multi_contact == SD_MULTI_CONTACT_AVERAGE)
        sd_item_elements_average(o, e0, e1, nc);
    return nc;
}

/* 1 when pair e begins a run of the element segment starting at e0 (a new
 * composite pair). */
SD_HD static SD_INLINE int sd_item_elements_starts(const sd_pair_out *o, size_t e0, size_t e)
{
    return e == e0 || o->i[e] != o->i[e - 1] || o->j[e] != o->j[e - 1];
}

/* ---- particle-wall kinds ------------------------------------------------- */

/* The particle of wall pair e, its velocity taken relative to the wall (a
 * moving wall: the law sees only the relative velocity). */
SD_HD static SD_HOT sd_body sd_item_wall_body(const sd_step_view *v, const sd_wall_view *wl, size_t i)
{
    sd_body a = sd_item_body(v, i);
    a.v = sd_v3_sub(a.v, wl->velocity);
    return a;
}

/* A drum turns as a rigid body at omega about its axis through centre, so
 * the law sees the particle's motion relative to it (seed 004 §4.2's
 * drum): v - omega x (x - centre) and w - omega. At the contact point the
 * relative velocity is then v + w x (c - x) - omega x (c - centre), the
 * surface speed omega x r taken off, and rolling resistance acts on the
 * spin relative to the wall. (The drum's translation velocity is 0.) */
SD_HD static SD_INLINE void sd_item_drum_relative(const sd_wall_view *wl, sd_body *a)
{
    a->v = sd_v3_sub(a->v, sd_v3_cross(wl->omega, sd_v3_sub(a->x, wl->g.centre)));
    a->w = sd_v3_sub(a->w, wl->omega);
}

/* SD_WALL_PAIR_SPHERE: a plain sphere (or disc) against a plane, a box
 * face or a drum feature; in the planar mode a box has no z faces. The
 * geometry needs only the centre and the radius, so a pair that is apart
 * (most of a box's pairs: every particle near a face, each step) writes
 * its empty result without loading the rest of the body or the law
 * (issue 29: the same slots as sd_pair_wall's, apart). */
SD_HD static SD_HOT void sd_item_wall_sphere(const sd_step_view *v, sd_wall_pair_out *o, size_t e)
{
    uint32_t i = o->i[e];
    const sd_wall_view *wl = &v->walls[o->wall[e]];
    sd_vec3 x = v->x[i];
    sd_real radius = v->radius[i];
    sd_contact_geom g;
    int touching = 0;
    if (wl->g.kind == SD_WALL_PLANE) {
        touching = sd_sphere_plane(x, radius, wl->g.point, wl->g.normal, &g);
    } else if (wl->g.kind == SD_WALL_DRUM) {
        /* the tangent plane at the radial projection: exact for a sphere */
        sd_vec3 p0, nw;
        touching = sd_wall_feature_plane(&wl->g, (int)o->sub[e], x, &p0, &nw) && sd_sphere_plane(x, radius, p0, nw, &g);
    } else if (!v->dim2 || o->sub[e] < 4) { /* the plane has no z faces */
        sd_wall_face f = sd_wall_box_face_of(wl->g.lo, wl->g.hi, o->sub[e]);
        touching = sd_sphere_box_face(x, radius, f.axis, f.value, f.dir, wl->g.lo, wl->g.hi, &g);
    }
    if (!touching) {
        sd_pair_result none = sd_pair_none(&o->ds[e]);
        sd_item_wall_store(o, e, x, &none);
        return;
    }
    sd_body a = sd_item_wall_body(v, wl, i);
    if (wl->g.kind == SD_WALL_DRUM)
        sd_item_drum_relative(wl, &a);
    const sd_pair_params *prm = sd_item_params(v, v->material[i], wl->material);
    sd_pair_result r = sd_pair_wall(prm, &a, &g, 1, a.radius, &o->ds[e], v->dt);
    sd_item_wall_store(o, e, g.point, &r);
}

/* SD_WALL_PAIR_CONVEX: a 3D shape's support point against the plane of the
 * wall feature. */
SD_HD static SD_INLINE void sd_item_wall_convex(const sd_step_view *v, sd_wall_pair_out *o, size_t e)
{
    uint32_t i = o->i[e];
    const sd_wall_view *wl = &v->walls[o->wall[e]];
    sd_body a = sd_item_wall_body(v, wl, i);
    sd_contact_geom g;
    sd_convex c = sd_item_shape_of(v, i);
    sd_vec3 p0, nw;
    int inside = sd_wall_feature_plane(&wl->g, o->sub[e], a.x, &p0, &nw);
    sd_narrow_count ns;
    sd_real arm = SD_R(0.0);
    int touching = inside && sd_convex_wall_geom_twist(&c, p0, nw, &g, &ns, &arm);
    if (touching && wl->g.kind == SD_WALL_DRUM)
        sd_item_drum_relative(wl, &a);
    const sd_pair_params *prm = sd_item_params(v, v->material[i], wl->material);
    sd_pair_result r = sd_pair_wall(prm, &a, &g, touching, v->shape_req[v->shape[i]], &o->ds[e], v->dt);
    if (touching)
        sd_pair_wall_twist(prm, &a, g.n, sd_v3_dot(a.w, g.n), arm, v->dt, &r);
    sd_item_wall_store(o, e, touching ? g.point : a.x, &r);
}

/* SD_WALL_PAIR_POLY_VOLUME: a sharp polyhedron under a volume law against
 * the plane of the wall feature (the exact overlap with a half-space). */
SD_HD static SD_INLINE void sd_item_wall_poly_volume(const sd_step_view *v, sd_wall_pair_out *o, size_t e)
{
    uint32_t i = o->i[e];
    const sd_wall_view *wl = &v->walls[o->wall[e]];
    sd_body a = sd_item_wall_body(v, wl, i);
    const sd_pair_params *prm = sd_item_params(v, v->material[i], wl->material);
    sd_vec3 p0, nw, point = a.x;
    sd_pair_result r;
    int s = v->shape[i];
    if (!sd_shape_is_sharp_polyhedron(&v->shapes[s]) || !sd_wall_feature_plane(&wl->g, o->sub[e], a.x, &p0, &nw)) {
        r = sd_pair_none(&o->ds[e]);
    } else {
        sd_convex c = sd_item_shape_of(v, i);
        if (wl->g.kind == SD_WALL_DRUM)
            sd_item_drum_relative(wl, &a);
        r = sd_pair_poly_wall(prm, &a, &c, p0, nw, v->shape_req[s], &o->ds[e], v->dt, &point);
    }
    sd_item_wall_store(o, e, point, &r);
}

/* ---- shared by the mesh-wall kinds and the element runs against meshes --- */

/* The velocity of wall wl at point c (m/s): a mesh translates and turns. */
SD_HD static SD_INLINE sd_vec3 sd_item_wall_velocity_at(const sd_wall_view *wl, sd_vec3 c)
{
    return sd_v3_add(wl->velocity, sd_v3_cross(wl->omega, sd_v3_sub(c, wl->g.centre)));
}

/* The area weight of a shape's contact with the plane group of wall pair
 * e at world point pw with overlap delta: the section (exact for
 * polyhedra, of the core with the plane moved out by the rounding; for
 * the kinds without vertices the rounded body's own section, a polygon of
 * 24 rim points; the disc of radius sqrt(2 req delta) only when that has
 * no area, a contact just touching) clipped by the group's near
 * triangles. */
SD_HD static SD_INLINE sd_real sd_item_mesh_weight(const sd_wall_pair_out *o, size_t e, const sd_wall_view *wl,
                                                   const sd_mesh_view *m, const sd_convex *c, sd_vec3 pw,
                                                   sd_real delta, sd_real req, sd_vec3 *shift)
{
    uint32_t gr = o->sub[e];
    sd_vec3 n = m->group_normal[gr];
    sd_real off = m->group_offset[gr];
    sd_vec3 e1, e2;
    sd_clip_basis(n, &e1, &e2);
    sd_vec2 sec[SD_CLIP_MAX + 3];
    int ns = 0;
    sd_vec3 pm = sd_mesh_to_frame(wl->g.q, wl->g.trans, pw);
    pm = sd_v3_sub(pm, sd_v3_scale(n, sd_v3_dot(n, pm) - off)); /* onto the plane */
    if (c->shape->kind == SD_SHAPE_POLYHEDRON)
        ns = sd_mesh_poly_section(c, &wl->g, n, off + c->shape->radius, e1, e2, sec);
    else /* no vertex list: the rim by support points (spheres, ellipsoids, cylinders, cones, boxes) */
        ns = sd_mesh_convex_section(c, &wl->g, n, off, e1, e2, sec);
    if (ns < 3 || !(sd_clip_area(sec, ns, NULL) > 0))
        ns = sd_mesh_disc(pm, sd_sqrt(SD_R(2.0) * req * (delta > 0 ? delta : SD_R(0.0))), e1, e2, sec);
    sd_vec2 q = sd_v2(sd_v3_dot(pm, e1), sd_v3_dot(pm, e2));
    return sd_mesh_clip_weight(m, &wl->g, o->tri + o->tstart[e], o->tcount[e], e1, e2, sec, ns, q, shift);
}

/* A plane contact's result weighted by w, its point moved by shift (m):
 * force, torques and energy scale with w; the lever arm gains the shift. */
SD_HD static SD_INLINE void sd_item_mesh_scale(sd_pair_result *r, sd_real w, sd_vec3 shift)
{
    r->f = sd_v3_scale(r->f, w);
    r->ti = sd_v3_add(sd_v3_scale(r->ti, w), sd_v3_cross(shift, r->f));
    r->tj = sd_v3_scale(r->tj, w);
    r->energy *= w;
}

/* The plane kinds' rule at a convex ridge (issue 14: no double push). A
 * body near a convex edge between plane groups X and Y sinks into both
 * planes, but near the ridge the solid is the intersection of the two
 * half-spaces, and the overlap is pushed out along the plane it sinks
 * less deep into (the separating-axis choice): the contact with X, depth
 * delta (m), gives way (returns 1) when some group Y across a convex edge
 * of X's near triangles tl (nt) holds the body less deep (ties: the
 * lower group index keeps it). Y makes that contact itself: it is within
 * reach, since its edge is (and the centre is in front of it, where its
 * part is closed: sd_mesh_front). Depths are the support depths of c under
 * each plane (contact/'s plane contact). */
SD_HD static SD_INLINE int sd_item_mesh_ridge_yields(const sd_mesh_view *m, const sd_wall_geom *wg, uint32_t gr,
                                                     const uint32_t *tl, uint32_t nt, const sd_convex *c,
                                                     sd_real delta)
{
    sd_mesh_ridge_walk rw;
    sd_mesh_ridge_start(&rw);
    for (uint32_t gy; (gy = sd_mesh_ridge_next(m, gr, tl, nt, &rw)) != UINT32_MAX;) {
        /* Y makes no contact with a centre behind it on a closed part (the thin-wall rule) */
        if (!sd_mesh_front_at(m, wg, gy, &rw.nb, 1, c->x))
            continue;
        sd_vec3 p0, nw;
        sd_mesh_group_plane(m, wg, gy, &p0, &nw);
        sd_contact_geom g;
        sd_narrow_count cnt;
        if (sd_convex_wall_geom(c, p0, nw, &g, &cnt) && (g.delta < delta || (g.delta == delta && gy < gr)))
            return 1;
    }
    return 0;
}

/* The contact geometry of the element of wall pair e (SD_WALL_PAIR_ELEMENTS)
 * with its wall feature: a sphere element by the sphere's contact with the
 * plane, box face or drum, or with the closest active feature of a mesh
 * plane group's near triangles; any other by its support point against
 * the feature's plane (a mesh: the group's plane, the contact weighted by
 * the element's section clipped by the group's near triangles, *wgt and
 * *shift as sd_item_mesh_weight gives them; touching only where that
 * weight is positive; beyond a mesh's free edge, the edge's contact,
 * sd_mesh_rim_contact, unweighted). *c: the posed element; *req: its
 * equivalent radius, m; *p0, *nw: the feature's plane when *has_plane is
 * 1, the plane tangent to the element at the free edge when it is 2;
 * *wgt = 1 and *shift = 0 off meshes and at a free edge. */
SD_HD static SD_INLINE int sd_item_wall_element_geom(const sd_step_view *v, const sd_wall_pair_out *o, size_t e,
                                                     sd_convex *c, sd_shape *tmp, sd_real *req, sd_contact_geom *g,
                                                     sd_vec3 *p0, sd_vec3 *nw, int *has_plane, sd_real *wgt,
                                                     sd_vec3 *shift)
{
    const sd_wall_view *wl = &v->walls[o->wall[e]];
    *c = sd_item_element_of(v, o->i[e], o->elem[e], tmp, req);
    *has_plane = 0;
    *wgt = SD_R(1.0);
    *shift = sd_v3_zero();
    if (wl->g.kind == SD_WALL_MESH) {
        const sd_mesh_view *m = &v->meshes[wl->g.mesh];
        if (sd_item_is_sphere(c)) {
            *req = c->shape->radius;
            return sd_mesh_sphere_geom(m, &wl->g, o->sub[e], o->tri + o->tstart[e], o->tcount[e], c->x,
                                       c->shape->radius, g);
        }
        sd_mesh_group_plane(m, &wl->g, o->sub[e], p0, nw);
        *has_plane = 1;
        sd_narrow_count ns;
        if (!sd_mesh_front_at(m, &wl->g, o->sub[e], o->tri + o->tstart[e], o->tcount[e], c->x) ||
            !sd_convex_wall_geom(c, *p0, *nw, g, &ns))
            return 0; /* behind a closed part's face (the thin-wall rule), or apart */
        /* the rim rule for elements as for whole bodies (issue 30): beyond
         * a free edge, the edge's contact and its tangent plane */
        if (sd_mesh_beyond_rim(m, &wl->g, o->sub[e], o->tri + o->tstart[e], o->tcount[e], c)) {
            sd_vec3 foot;
            *has_plane = 0;
            if (!sd_mesh_rim_contact(m, &wl->g, o->tri + o->tstart[e], o->tcount[e], c, g, &foot))
                return 0;
            *p0 = foot;
            *nw = g->n;
            *has_plane = 2;
            return 1;
        }
        /* the ridge rule for elements as for whole bodies (issue 30) */
        if (sd_item_mesh_ridge_yields(m, &wl->g, o->sub[e], o->tri + o->tstart[e], o->tcount[e], c, g->delta))
            return 0;
        *wgt = sd_item_mesh_weight(o, e, wl, m, c, g->point, g->delta, *req, shift);
        return *wgt > SD_R(0.0);
    }
    if (sd_item_is_sphere(c)) {
        sd_real r = c->shape->radius;
        *req = r;
        if (wl->g.kind == SD_WALL_PLANE)
            return sd_sphere_plane(c->x, r, wl->g.point, wl->g.normal, g);
        if (wl->g.kind == SD_WALL_DRUM) { /* its turning speed: sd_item_wall_elements */
            sd_vec3 q0, qn;
            return sd_wall_feature_plane(&wl->g, (int)o->sub[e], c->x, &q0, &qn) && sd_sphere_plane(c->x, r, q0, qn, g);
        }
        sd_wall_face f = sd_wall_box_face_of(wl->g.lo, wl->g.hi, (int)o->sub[e]);
        return sd_sphere_box_face(c->x, r, f.axis, f.value, f.dir, wl->g.lo, wl->g.hi, g);
    }
    if (!sd_wall_feature_plane(&wl->g, (int)o->sub[e], c->x, p0, nw))
        return 0;
    *has_plane = 1;
    sd_narrow_count ns;
    return sd_convex_wall_geom(c, *p0, *nw, g, &ns);
}

/* The overlap of element e's sharp polyhedron with its wall feature's
 * plane (seed 000's half-space overlap), for a mesh weighted by its
 * section clipped to the group's near triangles (*wgt, *shift; 1 and 0
 * off meshes): 1 and *g when they overlap (and, on a mesh, the weight is
 * positive). *c and *req: the posed element and its equivalent radius. */
SD_HD static SD_INLINE int sd_item_wall_element_volume_geom(const sd_step_view *v, const sd_wall_pair_out *o, size_t e,
                                                            sd_convex *c, sd_shape *tmp, sd_real *req,
                                                            sd_volume_geom *g, sd_real *wgt, sd_vec3 *shift)
{
    const sd_wall_view *wl = &v->walls[o->wall[e]];
    sd_contact_geom cg;
    sd_vec3 p0, nw;
    int has_plane;
    int touching = sd_item_wall_element_geom(v, o, e, c, tmp, req, &cg, &p0, &nw, &has_plane, wgt, shift);
    *wgt = SD_R(1.0);
    *shift = sd_v3_zero();
    if (!has_plane || !sd_shape_is_sharp_polyhedron(c->shape) || !sd_pair_poly_wall_geom(c, p0, nw, g))
        return 0;
    if (has_plane == 2) {
        /* at a free edge: the overlap with the tangent plane there, its
         * force applied at the edge's contact point (the rim rule) */
        if (!touching)
            return 0;
        *shift = sd_v3_sub(cg.point, g->point);
        return 1;
    }
    if (wl->g.kind == SD_WALL_MESH) {
        /* the thin-wall rule, then the ridge rule on the support depths, as
         * sd_item_mesh_poly_volume */
        const sd_mesh_view *m = &v->meshes[wl->g.mesh];
        if (!sd_mesh_front_at(m, &wl->g, o->sub[e], o->tri + o->tstart[e], o->tcount[e], c->x))
            return 0;
        sd_contact_geom gx;
        sd_narrow_count cnt;
        if (sd_convex_wall_geom(c, p0, nw, &gx, &cnt) &&
            sd_item_mesh_ridge_yields(m, &wl->g, o->sub[e], o->tri + o->tstart[e], o->tcount[e], c, gx.delta))
            return 0;
        *wgt = sd_item_mesh_weight(o, e, wl, &v->meshes[wl->g.mesh], c, g->point, g->depth, *req, shift);
        return *wgt > SD_R(0.0);
    }
    return 1;
}

/* SD_WALL_PAIR_ELEMENTS under a volume law: the run's half-space overlaps
 * first (N_c, the centroid of their points), then the law on each, model
 * A's zeta divided by sqrt(N_c) (eq. 18), the dashpot's mass at the
 * centroid, as the depth laws' runs. a: the particle, its motion relative
 * to the wall. Returns N_c. */
SD_HD static SD_INLINE int sd_item_wall_elements_volume(const sd_step_view *v, sd_wall_pair_out *o, size_t e0,
                                                        size_t e1, const sd_pair_params *prm, sd_body a)
{
    sd_volume_geom keep[SD_ITEM_RUN_CAP];
    sd_real keep_w[SD_ITEM_RUN_CAP];
    sd_vec3 keep_s[SD_ITEM_RUN_CAP];
    sd_vec3 cm = sd_v3_zero();
    int nc = 0;
    for (size_t e = e0; e < e1; ++e) {
        sd_convex c;
        sd_shape tmp;
        sd_real req, wgt;
        sd_vec3 shift;
        sd_volume_geom g;
        if (sd_item_wall_element_volume_geom(v, o, e, &c, &tmp, &req, &g, &wgt, &shift)) {
            if (nc < SD_ITEM_RUN_CAP) {
                keep[nc] = g;
                keep_w[nc] = wgt;
                keep_s[nc] = shift;
            }
            cm = sd_v3_add(cm, g.point);
            ++nc;
            o->delta[e] = SD_R(1.0); /* marks the overlapping elements for the second pass */
        } else {
            sd_pair_result r = sd_pair_none(&o->ds[e]);
            sd_item_wall_store(o, e, c.x, &r);
        }
    }
    if (nc == 0)
        return 0;
    cm = sd_v3_scale(cm, SD_R(1.0) / (sd_real)nc);
    sd_pair_params sum;
    if (v->multi_contact == SD_MULTI_CONTACT_SUM && nc > 1) {
        sum = sd_item_params_sum(prm, nc);
        prm = &sum;
    }
    const sd_wall_view *wl = &v->walls[o->wall[e0]];
    int k = 0;
    for (size_t e = e0; e < e1 && k < nc; ++e) {
        if (!(o->delta[e] > SD_R(0.0)))
            continue;
        sd_shape tmp;
        sd_real req, wgt = SD_R(1.0);
        sd_vec3 shift = sd_v3_zero();
        sd_volume_geom g;
        /* the posed element again (cheap) for its radius; its overlap
         * from the first pass, or again beyond the workspace */
        sd_convex c = sd_item_element_of(v, o->i[e], o->elem[e], &tmp, &req);
        int ok = 1;
        if (k < SD_ITEM_RUN_CAP) {
            g = keep[k];
            wgt = keep_w[k];
            shift = keep_s[k];
        } else {
            ok = sd_item_wall_element_volume_geom(v, o, e, &c, &tmp, &req, &g, &wgt, &shift);
        }
        ++k;
        if (!ok) {
            sd_pair_result r = sd_pair_none(&o->ds[e]);
            sd_item_wall_store(o, e, c.x, &r);
            continue;
        }
        sd_body ae = a;
        ae.radius = c.shape->bound; /* the onset area reads the element's radius */
        sd_pair_result r = sd_pair_poly_wall_at(prm, &ae, &g, req, &o->ds[e], v->dt, cm);
        if (wl->g.kind == SD_WALL_MESH)
            sd_item_mesh_scale(&r, wgt, shift);
        sd_item_wall_store(o, e, sd_v3_add(g.point, shift), &r);
    }
    if (v->multi_contact == SD_MULTI_CONTACT_AVERAGE && nc > 1) {
        sd_real s = SD_R(1.0) / (sd_real)nc;
        for (size_t e = e0; e < e1; ++e) {
            o->f[e] = sd_v3_scale(o->f[e], s);
            o->t[e] = sd_v3_scale(o->t[e], s);
            o->energy[e] *= s;
        }
    }
    return nc;
}

/* SD_WALL_PAIR_ELEMENTS: the run [e0, e1) of the elements of one particle
 * against one wall feature (a mesh: one plane group), evaluated and
 * combined as the particle pairs are (two passes, the dashpot's mass at
 * the contacts' centroid, seed 004 §2.6). Against a mesh each element's
 * contact is weighted by its clipped section as a convex particle's is
 * (sd_item_mesh_convex), so a composite on a flat mesh is the composite on
 * the analytic plane; the weight is applied after the law, before the
 * combination. Returns N_c. */
SD_HD static SD_INLINE int sd_item_wall_elements(const sd_step_view *v, sd_wall_pair_out *o, size_t e0, size_t e1)
{
    uint32_t i = o->i[e0];
    const sd_wall_view *wl = &v->walls[o->wall[e0]];
    const sd_pair_params *prm = sd_item_params(v, v->material[i], wl->material);
    sd_body a = sd_item_wall_body(v, wl, i);
    /* a drum or a mesh: the composite's motion relative to the wall's
     * rigid motion, right at every contact point of the run
     * (sd_item_drum_relative; a mesh's translation left by the line
     * above) */
    if (wl->g.kind == SD_WALL_DRUM || wl->g.kind == SD_WALL_MESH)
        sd_item_drum_relative(wl, &a);
    if (sd_law_is_volume(prm->law))
        return sd_item_wall_elements_volume(v, o, e0, e1, prm, a);
    sd_contact_geom keep[SD_ITEM_RUN_CAP];
    sd_real keep_r[SD_ITEM_RUN_CAP], keep_w[SD_ITEM_RUN_CAP];
    sd_vec3 keep_s[SD_ITEM_RUN_CAP];
    sd_vec3 cm = sd_v3_zero();
    int nc = 0;
    for (size_t e = e0; e < e1; ++e) {
        sd_convex c;
        sd_shape tmp;
        sd_real req, wgt;
        sd_contact_geom g;
        sd_vec3 p0, nw, shift;
        int has_plane;
        int t = sd_item_wall_element_geom(v, o, e, &c, &tmp, &req, &g, &p0, &nw, &has_plane, &wgt, &shift);
        if (t) {
            if (nc < SD_ITEM_RUN_CAP) {
                keep[nc] = g;
                keep_r[nc] = req;
                keep_w[nc] = wgt;
                keep_s[nc] = shift;
            }
            cm = sd_v3_add(cm, g.point);
            ++nc;
            o->delta[e] = g.delta;
        } else {
            sd_pair_result r = sd_pair_none(&o->ds[e]);
            sd_item_wall_store(o, e, c.x, &r);
        }
    }
    if (nc > 0) {
        cm = sd_v3_scale(cm, SD_R(1.0) / (sd_real)nc);
        sd_pair_params sum;
        if (v->multi_contact == SD_MULTI_CONTACT_SUM && nc > 1) {
            sum = sd_item_params_sum(prm, nc);
            prm = &sum;
        }
        sd_body wall;
        wall.v = sd_v3_zero();
        wall.w = sd_v3_zero();
        wall.radius = SD_R(0.0);
        wall.inv_mass = SD_R(0.0);
        wall.inv_inertia = sd_v3_zero();
        wall.q = sd_quat_identity();
        int k = 0;
        for (size_t e = e0; e < e1 && k < nc; ++e) {
            if (!(o->delta[e] > SD_R(0.0)))
                continue;
            sd_contact_geom g;
            sd_real rs, wgt;
            sd_vec3 shift;
            if (k < SD_ITEM_RUN_CAP) {
                g = keep[k];
                rs = keep_r[k];
                wgt = keep_w[k];
                shift = keep_s[k];
            } else {
                sd_convex c;
                sd_shape tmp;
                sd_vec3 p0, nw;
                int has_plane;
                (void)sd_item_wall_element_geom(v, o, e, &c, &tmp, &rs, &g, &p0, &nw, &has_plane, &wgt, &shift);
            }
            ++k;
            wall.x = g.point; /* the wall: infinite mass at rest (a's velocity is relative to it) */
            sd_pair_result r = sd_item_apply_at(prm, &a, &wall, &g, rs, &o->ds[e], v->dt, cm);
            if (wl->g.kind == SD_WALL_MESH)
                sd_item_mesh_scale(&r, wgt, shift);
            sd_item_wall_store(o, e, sd_v3_add(g.point, shift), &r);
        }
    }
    if (v->multi_contact == SD_MULTI_CONTACT_AVERAGE && nc > 1) {
        sd_real s = SD_R(1.0) / (sd_real)nc;
        for (size_t e = e0; e < e1; ++e) {
            o->f[e] = sd_v3_scale(o->f[e], s);
            o->t[e] = sd_v3_scale(o->t[e], s);
            o->energy[e] *= s;
        }
    }
    return nc;
}

/* 1 when wall pair e begins a run of the element segment starting at e0
 * (a new particle, wall or feature). */
SD_HD static SD_INLINE int sd_item_wall_elements_starts(const sd_wall_pair_out *o, size_t e0, size_t e)
{
    return e == e0 || o->i[e] != o->i[e - 1] || o->wall[e] != o->wall[e - 1] || o->sub[e] != o->sub[e - 1];
}

/* SD_WALL_PAIR_CONVEX2D: a 2D shape against a wall line. */
SD_HD static SD_INLINE void sd_item_wall_convex2d(const sd_step_view *v, sd_wall_pair_out *o, size_t e)
{
    uint32_t i = o->i[e];
    const sd_wall_view *wl = &v->walls[o->wall[e]];
    sd_body a = sd_item_wall_body(v, wl, i);
    sd_contact_geom g;
    sd_shape2d tmp;
    sd_convex2d c = sd_item_convex2d_of(v, i, &tmp);
    sd_vec2 p0, nw;
    int touching = sd_wall_feature_line(&wl->g, o->sub[e], a.x, &p0, &nw) && sd_convex2d_wall_geom(&c, p0, nw, &g);
    const sd_pair_params *prm = sd_item_params(v, v->material[i], wl->material);
    sd_pair_result r = sd_pair_wall(prm, &a, &g, touching, c.shape->eq_radius, &o->ds[e], v->dt);
    sd_item_wall_store(o, e, touching ? g.point : a.x, &r);
}

/* ---- mesh-wall kinds (seed 000 §2.4; geom/mesh_contact.h) ---------------- */

/* SD_WALL_PAIR_MESH_SPHERE: a plain sphere (or disc) against a plane
 * group: the closest active feature of its near triangles. */
SD_HD static SD_HOT void sd_item_mesh_sphere(const sd_step_view *v, sd_wall_pair_out *o, size_t e)
{
    uint32_t i = o->i[e];
    const sd_wall_view *wl = &v->walls[o->wall[e]];
    const sd_mesh_view *m = &v->meshes[wl->g.mesh];
    sd_body a = sd_item_body(v, i);
    sd_contact_geom g;
    int touching = sd_mesh_sphere_geom(m, &wl->g, o->sub[e], o->tri + o->tstart[e], o->tcount[e], a.x, a.radius, &g);
    if (touching)
        a.v = sd_v3_sub(a.v, sd_item_wall_velocity_at(wl, g.point)); /* the law sees the relative velocity */
    const sd_pair_params *prm = sd_item_params(v, v->material[i], wl->material);
    sd_pair_result r = sd_pair_wall(prm, &a, &g, touching, a.radius, &o->ds[e], v->dt);
    sd_item_wall_store(o, e, touching ? g.point : a.x, &r);
}

/* SD_WALL_PAIR_MESH_CONVEX: a 3D shape against a plane group: the plane
 * contact (support point), weighted by the clipped area. */
SD_HD static SD_INLINE void sd_item_mesh_convex(const sd_step_view *v, sd_wall_pair_out *o, size_t e)
{
    uint32_t i = o->i[e];
    const sd_wall_view *wl = &v->walls[o->wall[e]];
    const sd_mesh_view *m = &v->meshes[wl->g.mesh];
    sd_body a = sd_item_body(v, i);
    sd_convex c = sd_item_shape_of(v, i);
    sd_vec3 p0, nw;
    sd_mesh_group_plane(m, &wl->g, o->sub[e], &p0, &nw);
    sd_contact_geom g;
    sd_narrow_count ns;
    sd_real req = v->shape_req[v->shape[i]];
    sd_real arm = SD_R(0.0);
    int touching = sd_mesh_front_at(m, &wl->g, o->sub[e], o->tri + o->tstart[e], o->tcount[e], a.x) &&
                   sd_convex_wall_geom_twist(&c, p0, nw, &g, &ns, &arm);
    sd_real wgt = SD_R(0.0);
    sd_vec3 shift = sd_v3_zero();
    const uint32_t *tl = o->tri + o->tstart[e];
    if (touching && sd_mesh_beyond_rim(m, &wl->g, o->sub[e], tl, o->tcount[e], &c)) {
        /* the rim rule: beyond a free edge, the edge's point contact */
        sd_vec3 foot;
        touching = sd_mesh_rim_contact(m, &wl->g, tl, o->tcount[e], &c, &g, &foot);
        arm = SD_R(0.0);
        wgt = SD_R(1.0);
    } else {
        touching = touching && !sd_item_mesh_ridge_yields(m, &wl->g, o->sub[e], tl, o->tcount[e], &c, g.delta);
        if (touching) {
            wgt = sd_item_mesh_weight(o, e, wl, m, &c, g.point, g.delta, req, &shift);
            touching = wgt > 0;
        }
    }
    if (touching)
        a.v = sd_v3_sub(a.v, sd_item_wall_velocity_at(wl, g.point));
    const sd_pair_params *prm = sd_item_params(v, v->material[i], wl->material);
    sd_pair_result r = sd_pair_wall(prm, &a, &g, touching, req, &o->ds[e], v->dt);
    if (touching) {
        sd_pair_wall_twist(prm, &a, g.n, sd_v3_dot(sd_v3_sub(a.w, wl->omega), g.n), arm, v->dt, &r);
        sd_item_mesh_scale(&r, wgt, shift);
    }
    sd_item_wall_store(o, e, touching ? sd_v3_add(g.point, shift) : a.x, &r);
}

/* SD_WALL_PAIR_MESH_POLY_VOLUME: a sharp polyhedron under a volume law
 * against a plane group: the exact half-space overlap, weighted by the
 * clipped area of the section. */
SD_HD static SD_INLINE void sd_item_mesh_poly_volume(const sd_step_view *v, sd_wall_pair_out *o, size_t e)
{
    uint32_t i = o->i[e];
    const sd_wall_view *wl = &v->walls[o->wall[e]];
    const sd_mesh_view *m = &v->meshes[wl->g.mesh];
    sd_body a = sd_item_body(v, i);
    const sd_pair_params *prm = sd_item_params(v, v->material[i], wl->material);
    int s = v->shape[i];
    sd_vec3 point = a.x;
    sd_pair_result r;
    if (s < 0 || !sd_shape_is_sharp_polyhedron(&v->shapes[s]) ||
        !sd_mesh_front_at(m, &wl->g, o->sub[e], o->tri + o->tstart[e], o->tcount[e], a.x)) {
        r = sd_pair_none(&o->ds[e]); /* (or behind a closed part's face: the thin-wall rule) */
    } else {
        sd_vec3 p0, nw;
        sd_mesh_group_plane(m, &wl->g, o->sub[e], &p0, &nw);
        sd_convex c = sd_item_shape_of(v, i);
        const uint32_t *tl = o->tri + o->tstart[e];
        /* the ridge rule on the support depths (the law's own depth is a
         * volume's); beyond a free edge the rim rule: the overlap with the
         * plane tangent to the body at the edge, its force applied at the
         * edge's contact point */
        sd_contact_geom gx;
        sd_narrow_count cnt;
        int plane = sd_convex_wall_geom(&c, p0, nw, &gx, &cnt);
        int rim = plane && sd_mesh_beyond_rim(m, &wl->g, o->sub[e], tl, o->tcount[e], &c);
        int yields = 0;
        if (rim) {
            sd_vec3 at;
            yields = !sd_mesh_rim_contact(m, &wl->g, tl, o->tcount[e], &c, &gx, &at);
            p0 = at;
            nw = gx.n;
        } else {
            yields = plane && sd_item_mesh_ridge_yields(m, &wl->g, o->sub[e], tl, o->tcount[e], &c, gx.delta);
        }
        /* the wall's velocity at the centre's foot on the plane (the overlap's
         * centroid is not known before the law runs) */
        sd_vec3 foot = sd_v3_sub(a.x, sd_v3_scale(nw, sd_v3_dot(sd_v3_sub(a.x, p0), nw)));
        a.v = sd_v3_sub(a.v, sd_item_wall_velocity_at(wl, foot));
        r = yields ? sd_pair_none(&o->ds[e]) : sd_pair_poly_wall(prm, &a, &c, p0, nw, v->shape_req[s], &o->ds[e], v->dt, &point);
        if (r.delta > 0 && rim) {
            sd_item_mesh_scale(&r, SD_R(1.0), sd_v3_sub(gx.point, point));
            point = gx.point;
        } else if (r.delta > 0) {
            sd_vec3 shift;
            sd_real wgt = sd_item_mesh_weight(o, e, wl, m, &c, point, r.delta, v->shape_req[s], &shift);
            if (wgt > 0) {
                sd_item_mesh_scale(&r, wgt, shift);
                point = sd_v3_add(point, shift);
            } else {
                r = sd_pair_none(&o->ds[e]);
                point = a.x;
            }
        }
    }
    sd_item_wall_store(o, e, point, &r);
}

/* The ridge rule of the planar mode (issue 30): the contact of body c with
 * group gr, depth delta (m), gives way (1) when some group across a
 * convex edge of gr's near triangles tl (nt) has a line the body sinks
 * less deep into (ties: the lower group index keeps it). */
SD_HD static SD_INLINE int sd_item_mesh2d_ridge_yields(const sd_mesh_view *m, const sd_wall_geom *wg, uint32_t gr,
                                                       const uint32_t *tl, uint32_t nt, const sd_convex2d *c,
                                                       sd_real delta)
{
    sd_mesh_ridge_walk rw;
    sd_mesh_ridge_start(&rw);
    for (uint32_t gy; (gy = sd_mesh_ridge_next(m, gr, tl, nt, &rw)) != UINT32_MAX;) {
        sd_vec2 l0, n2;
        sd_contact_geom g;
        if (sd_mesh2d_group_line(m, wg, gy, &l0, &n2) && sd_convex2d_wall_geom(c, l0, n2, &g) &&
            (g.delta < delta || (g.delta == delta && gy < gr)))
            return 1;
    }
    return 0;
}

/* SD_WALL_PAIR_MESH_CONVEX2D: a 2D shape against a plane group cut by the
 * plane z = 0 (the planar mode; geom/mesh_contact2d.h): the group's plane
 * meets z = 0 in a line, the 2D wall-line contact is made against it,
 * weighted by the share of the body's chord on the cuts of the group's
 * near triangles (1 when its whole width lies on them), and it gives way
 * at a convex edge to a group whose line the body sinks less deep into
 * (the ridge rule). A group parallel to z = 0 makes no line. */
SD_HD static SD_INLINE void sd_item_mesh_convex2d(const sd_step_view *v, sd_wall_pair_out *o, size_t e)
{
    uint32_t i = o->i[e];
    const sd_wall_view *wl = &v->walls[o->wall[e]];
    const sd_mesh_view *m = &v->meshes[wl->g.mesh];
    const uint32_t *tl = o->tri + o->tstart[e];
    sd_body a = sd_item_body(v, i);
    sd_vec2 l0, n2;
    sd_contact_geom g;
    sd_real wgt = SD_R(1.0);
    sd_vec3 shift = sd_v3_zero();
    int touching = 0;
    if (sd_mesh2d_group_line(m, &wl->g, o->sub[e], &l0, &n2) &&
        sd_mesh_front_at(m, &wl->g, o->sub[e], o->tri + o->tstart[e], o->tcount[e], a.x)) {
        sd_shape2d tmp;
        sd_convex2d c = sd_item_convex2d_of(v, i, &tmp);
        touching = sd_convex2d_wall_geom(&c, l0, n2, &g) &&
                   !sd_item_mesh2d_ridge_yields(m, &wl->g, o->sub[e], tl, o->tcount[e], &c, g.delta);
        if (touching) {
            wgt = sd_mesh2d_weight(m, &wl->g, tl, o->tcount[e], &c, l0, n2, &shift);
            touching = wgt > 0;
        }
        if (touching)
            a.v = sd_v3_sub(a.v, sd_item_wall_velocity_at(wl, g.point));
    }
    const sd_pair_params *prm = sd_item_params(v, v->material[i], wl->material);
    sd_real req = v->shape[i] >= 0 ? v->shapes2d[v->shape[i]].eq_radius : v->radius[i];
    sd_pair_result r = sd_pair_wall(prm, &a, &g, touching, req, &o->ds[e], v->dt);
    int part = touching && wgt < SD_R(1.0); /* at the group's end: the supported share */
    if (part)
        sd_item_mesh_scale(&r, wgt, shift);
    sd_item_wall_store(o, e, touching ? (part ? sd_v3_add(g.point, shift) : g.point) : a.x, &r);
}

#endif
