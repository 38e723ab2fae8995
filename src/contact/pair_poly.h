/* pair_poly.h — one volume-law contact, end to end: the exact overlap of
 * two sharp polyhedra (geom/overlap.h, seed 000 §2.3) or of a polyhedron
 * and a wall plane (geom/halfspace.h), the relative motion at the contact
 * point, the law (contact/law_volume.h, seed 000 eqs. 12-20) and the force
 * and torques on both bodies (eqs. 21-22, plus the twisting couple).
 * Single source (SD_HD).
 *
 * Invariants: the force on i is minus the force on j; the torques about
 * each centre are arm × F ± the couple, so the total angular momentum about
 * any point is kept (tests/validation/poly_gradient.c checks both); the
 * pair's interior-point hint x0 is updated only by a successful overlap.
 */
#ifndef SD_CONTACT_PAIR_POLY_H
#define SD_CONTACT_PAIR_POLY_H

#include "contact/law_volume.h"
#include "contact/pair_convex.h"
#include "geom/halfspace.h"
#include "geom/overlap.h"

SD_HD static SD_INLINE int sd_law_is_volume(int law)
{
    return law == SD_LAW_VOLUME || law == SD_LAW_VOLUME_LINEAR;
}

/* A shape the volume laws can take: a sharp polyhedron. */
SD_HD static SD_INLINE int sd_shape_is_sharp_polyhedron(const sd_shape *s)
{
    return s->kind == SD_SHAPE_POLYHEDRON && s->radius == SD_R(0.0);
}

/* Applies a volume contact of known geometry to the two bodies, the
 * dashpot's effective mass (eq. 15's m_eff) taken at point cm: the contact
 * point itself for one contact (sd_pair_volume_apply); for a composite's
 * run of element contacts their centroid (backend/items.h), so N contacts
 * over a face damp like one at its centre, as the depth laws' runs do. */
SD_HD static SD_INLINE sd_pair_result sd_pair_volume_apply_at(const sd_pair_params *prm, const sd_body *a,
                                                              const sd_body *b, const sd_volume_geom *g,
                                                              sd_real kcoef, sd_real ktcoef, sd_vec3 *ds, sd_real dt,
                                                              sd_vec3 cm)
{
    sd_pair_result r;
    sd_vec3 arm_i = sd_v3_sub(g->point, a->x);
    sd_vec3 arm_j = sd_v3_sub(g->point, b->x);
    sd_vec3 vi = sd_v3_add(a->v, sd_v3_cross(a->w, arm_i));
    sd_vec3 vj = sd_v3_add(b->v, sd_v3_cross(b->w, arm_j));
    sd_real inv = sd_body_inv_mass_at(a, sd_v3_sub(cm, a->x), g->n) + sd_body_inv_mass_at(b, sd_v3_sub(cm, b->x), g->n);
    sd_real m_star = inv > SD_R(0.0) ? SD_R(1.0) / inv : SD_R(0.0);
    /* the regularisation's onset from constants of the pair (law_volume.h):
     * the smaller bounding radius (a wall has none) and the translational
     * masses, never the contact point's m_star, which moves */
    sd_real rb = a->radius;
    if (b->radius > SD_R(0.0) && (!(rb > SD_R(0.0)) || b->radius < rb))
        rb = b->radius;
    sd_volume_geom gr = *g;
    gr.onset = sd_volume_onset(prm, kcoef, SD_PI * rb * rb, a->inv_mass + b->inv_mass, dt);
    sd_volume_out o = sd_law_volume_eval(prm, &gr, kcoef, ktcoef, m_star, sd_v3_sub(vi, vj), ds, dt);
    r.f = o.force;
    r.ti = sd_v3_add(sd_v3_cross(arm_i, o.force), o.couple);
    r.tj = sd_v3_sub(sd_v3_cross(arm_j, sd_v3_neg(o.force)), o.couple);
    r.delta = g->depth;
    r.energy = o.energy;
    return r;
}

/* Applies a volume contact of known geometry to the two bodies. */
SD_HD static SD_INLINE sd_pair_result sd_pair_volume_apply(const sd_pair_params *prm, const sd_body *a, const sd_body *b,
                                                           const sd_volume_geom *g, sd_real kcoef, sd_real ktcoef,
                                                           sd_vec3 *ds, sd_real dt)
{
    return sd_pair_volume_apply_at(prm, a, b, g, kcoef, ktcoef, ds, dt, g->point);
}

/* The law's geometry from an overlap of A = i and B = j (normal from A
 * into B, so n = -normal; the couple on A, -W' twist normal, is W' twist n). */
SD_HD static SD_INLINE sd_volume_geom sd_volume_geom_of(const sd_overlap *ov, sd_real depth)
{
    sd_volume_geom g;
    g.volume = ov->volume;
    g.area = ov->area;
    g.n = sd_v3_neg(ov->normal);
    g.point = ov->point;
    g.twist = ov->twist;
    g.depth = depth;
    g.onset = SD_R(0.0); /* set by sd_pair_volume_apply */
    return g;
}

/* Narrow-phase statistics of one overlap evaluation (reported through the
 * convex pairs' narrow_stats): "iterations" counts the faces of the
 * intersection, "support calls" its vertices (dual triangles), at least 1
 * so that an evaluation that found no overlap still counts. */
SD_HD static SD_INLINE void sd_overlap_count(const sd_overlap *ov, sd_narrow_count *ns)
{
    ns->iterations = ov->faces;
    ns->supports = ov->vertices > 0 ? ov->vertices : 1;
}

/* The overlap geometry of two sharp polyhedra: 1 and *g when they overlap
 * (x0 / x0_ok the pair's interior-point hint, read and updated; ws the
 * calling thread's overlap workspace), else 0 with the hint dropped. */
SD_HD static SD_INLINE int sd_pair_poly_geom(const sd_convex *ca, const sd_convex *cb, sd_vec3 *x0, uint8_t *x0_ok,
                                             sd_overlap_workspace *ws, sd_narrow_count *ns, sd_volume_geom *g)
{
    ns->iterations = 0;
    ns->supports = 0;
    sd_real reach = ca->shape->bound + cb->shape->bound;
    if (sd_v3_norm2(sd_v3_sub(ca->x, cb->x)) >= reach * reach) {
        *x0_ok = 0;
        return 0;
    }
    sd_overlap ov = sd_overlap_polyhedra(ca, cb, *x0, *x0_ok, ws);
    sd_overlap_count(&ov, ns);
    if (ov.status != SD_OVERLAP_OK || !(ov.volume > SD_R(0.0)) || !(ov.area > SD_R(0.0))) {
        *x0_ok = 0;
        return 0;
    }
    *x0 = ov.x0;
    *x0_ok = 1;
    /* how far A reaches into B along the normal (the damping's exponent) */
    sd_vec3 nab = ov.normal;
    sd_real depth = sd_v3_dot(nab, sd_v3_sub(sd_convex_support_core(ca, nab), sd_convex_support_core(cb, sd_v3_neg(nab))));
    *g = sd_volume_geom_of(&ov, depth);
    return 1;
}

/* Two sharp polyhedra; ra, rb the radii of their equal-volume spheres (m);
 * x0 / x0_ok the pair's interior-point hint (read and updated); ws the
 * calling thread's overlap workspace. */
SD_HD static SD_INLINE sd_pair_result sd_pair_poly(const sd_pair_params *prm, const sd_body *a, const sd_body *b,
                                                   const sd_convex *ca, const sd_convex *cb, sd_real ra, sd_real rb,
                                                   sd_vec3 *ds, sd_vec3 *x0, uint8_t *x0_ok,
                                                   sd_overlap_workspace *ws, sd_real dt, sd_narrow_count *ns)
{
    sd_volume_geom g;
    if (!sd_pair_poly_geom(ca, cb, x0, x0_ok, ws, ns, &g))
        return sd_pair_none(ds);
    sd_real kcoef = prm->young_a / ra + prm->young_b / rb;   /* eq. 13 */
    sd_real ktcoef = prm->shear_a / ra + prm->shear_b / rb;  /* eq. 19 */
    return sd_pair_volume_apply(prm, a, b, &g, kcoef, ktcoef, ds, dt);
}

/* The half-space overlap of a sharp polyhedron with the wall plane
 * through p0, unit normal nw into free space: 1 and *g when they overlap. */
SD_HD static SD_INLINE int sd_pair_poly_wall_geom(const sd_convex *ca, sd_vec3 p0, sd_vec3 nw, sd_volume_geom *g)
{
    sd_vec3 n = sd_v3_neg(nw);
    sd_real h = -sd_v3_dot(nw, p0);
    if (sd_halfspace_depth(ca, n, h) <= SD_R(0.0))
        return 0;
    sd_overlap ov = sd_overlap_halfspace(ca, n, h);
    if (ov.status != SD_OVERLAP_OK)
        return 0;
    *g = sd_volume_geom_of(&ov, sd_halfspace_depth(ca, n, h));
    return 1;
}

/* A wall contact of known geometry g, the dashpot's mass at cm (as
 * sd_pair_volume_apply_at); the wall is flat (R = infinity): only the
 * particle's E/R enters eqs. 13 and 19. */
SD_HD static SD_INLINE sd_pair_result sd_pair_poly_wall_at(const sd_pair_params *prm, const sd_body *a,
                                                           const sd_volume_geom *g, sd_real ra, sd_vec3 *ds,
                                                           sd_real dt, sd_vec3 cm)
{
    sd_body wall;
    wall.x = g->point;
    wall.v = sd_v3_zero();
    wall.w = sd_v3_zero();
    wall.radius = SD_R(0.0);
    wall.inv_mass = SD_R(0.0);
    wall.inv_inertia = sd_v3_zero();
    wall.q = sd_quat_identity();
    return sd_pair_volume_apply_at(prm, a, &wall, g, prm->young_a / ra, prm->shear_a / ra, ds, dt, cm);
}

/* A sharp polyhedron against a wall plane through p0 with unit normal nw
 * into free space; a's velocity is relative to the wall; *point: where
 * the force acts (the overlap's centroid, else the centre). */
SD_HD static SD_INLINE sd_pair_result sd_pair_poly_wall(const sd_pair_params *prm, const sd_body *a, const sd_convex *ca,
                                                        sd_vec3 p0, sd_vec3 nw, sd_real ra, sd_vec3 *ds, sd_real dt,
                                                        sd_vec3 *point)
{
    *point = a->x;
    sd_volume_geom g;
    if (!sd_pair_poly_wall_geom(ca, p0, nw, &g))
        return sd_pair_none(ds);
    *point = g.point;
    return sd_pair_poly_wall_at(prm, a, &g, ra, ds, dt, g.point);
}

#endif
