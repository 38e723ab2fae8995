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

/* ---- particle-wall kinds ------------------------------------------------- */

/* The particle of wall pair e, its velocity taken relative to the wall (a
 * moving wall: the law sees only the relative velocity). */
SD_HD static SD_HOT sd_body sd_item_wall_body(const sd_step_view *v, const sd_wall_view *wl, size_t i)
{
    sd_body a = sd_item_body(v, i);
    a.v = sd_v3_sub(a.v, wl->velocity);
    return a;
}

/* SD_WALL_PAIR_SPHERE: a plain sphere (or disc) against a plane or a box
 * face; in the planar mode a box has no z faces. */
SD_HD static SD_HOT void sd_item_wall_sphere(const sd_step_view *v, sd_wall_pair_out *o, size_t e)
{
    uint32_t i = o->i[e];
    const sd_wall_view *wl = &v->walls[o->wall[e]];
    sd_body a = sd_item_wall_body(v, wl, i);
    sd_contact_geom g;
    int touching = 0;
    if (wl->g.kind == SD_WALL_PLANE) {
        touching = sd_sphere_plane(a.x, a.radius, wl->g.point, wl->g.normal, &g);
    } else if (!v->dim2 || o->sub[e] < 4) { /* the plane has no z faces */
        sd_wall_face f = sd_wall_box_face_of(wl->g.lo, wl->g.hi, o->sub[e]);
        touching = sd_sphere_box_face(a.x, a.radius, f.axis, f.value, f.dir, wl->g.lo, wl->g.hi, &g);
    }
    const sd_pair_params *prm = sd_item_params(v, v->material[i], wl->material);
    sd_pair_result r = sd_pair_wall(prm, &a, &g, touching, a.radius, &o->ds[e], v->dt);
    sd_item_wall_store(o, e, touching ? g.point : a.x, &r);
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
    int touching = inside && sd_convex_wall_geom(&c, p0, nw, &g, &ns);
    const sd_pair_params *prm = sd_item_params(v, v->material[i], wl->material);
    sd_pair_result r = sd_pair_wall(prm, &a, &g, touching, v->shape_req[v->shape[i]], &o->ds[e], v->dt);
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
        r = sd_pair_poly_wall(prm, &a, &c, p0, nw, v->shape_req[s], &o->ds[e], v->dt, &point);
    }
    sd_item_wall_store(o, e, point, &r);
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

#endif
