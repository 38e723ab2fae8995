/* gjk_epa.c — GJK distance, EPA depth and the convex contact features,
 * against independent oracles (libccd, qhull, duality certificates) and the
 * analytic regressions of notes/algorithms.md §H tests 1–9.
 *
 * Invariant checked: on random pairs of random shapes and poses away from
 * grazing contact (|signed distance| > 1e-6 L), GJK's intersect boolean agrees
 * with libccd, distances agree with an exact polytope oracle (qhull hull of
 * the Minkowski difference) or are certified by a separating plane (the
 * duality gap), depths agree with libccd's EPA and qhull; GJK never hits its
 * iteration cap nor a degenerate state. Seed 004 §2.5 (shrink/GJK/swell),
 * seed 002 Table 1 (support calls per pair, printed as statistics).
 *
 * The reference support functions here (sd_ref_support_core) are written
 * from the shape definitions in shape/shape.h, independently of
 * shape/support.h; they feed libccd and the certificates, so an error in
 * support.h cannot hide itself (the two are also compared directly).
 */
#include <stdint.h>
#include <string.h>
#include <time.h>

#include "core/quat.h"
#include "core/rng.h"
#include "random_pose.h"
#include "shape/shape.h"

/* ---------------------------------------------------------------------- */
/* Reference support of a posed core (world frame), from the definitions  */

static sd_vec3 sd_ref_support_local(const sd_shape *s, const sd_vec3 *pool, sd_vec3 d)
{
    sd_vec3 a = s->a;
    switch (s->kind) {
    case SD_SHAPE_SPHERE:
        return sd_v3_zero();
    case SD_SHAPE_BOX:
        return sd_v3(d.x >= 0 ? a.x : -a.x, d.y >= 0 ? a.y : -a.y, d.z >= 0 ? a.z : -a.z);
    case SD_SHAPE_CYLINDER: {
        double rxy = sqrt(d.x * d.x + d.y * d.y);
        double ux = rxy > 0 ? d.x / rxy : 0, uy = rxy > 0 ? d.y / rxy : 0;
        return sd_v3(a.x * ux, a.x * uy, d.z >= 0 ? a.z : -a.z);
    }
    case SD_SHAPE_CONE: {
        /* base disk at z = 0 (the core's reference point), apex at z = h */
        double rxy = sqrt(d.x * d.x + d.y * d.y);
        double ux = rxy > 0 ? d.x / rxy : 0, uy = rxy > 0 ? d.y / rxy : 0;
        double rim = a.x * rxy, apex = a.z * d.z;
        return apex > rim ? sd_v3(0, 0, a.z) : sd_v3(a.x * ux, a.x * uy, 0);
    }
    case SD_SHAPE_ELLIPSOID: {
        sd_vec3 ad = sd_v3(a.x * d.x, a.y * d.y, a.z * d.z);
        double n = sd_v3_norm(ad);
        if (!(n > 0))
            return sd_v3(a.x, 0, 0);
        return sd_v3(a.x * ad.x / n, a.y * ad.y / n, a.z * ad.z / n);
    }
    default: {
        const sd_vec3 *v = pool + s->vstart;
        int best = 0;
        double bd = sd_v3_dot(v[0], d);
        for (uint32_t i = 1; i < s->vcount; ++i) {
            double t = sd_v3_dot(v[i], d);
            if (t > bd) {
                bd = t;
                best = (int)i;
            }
        }
        return v[best];
    }
    }
}

static sd_vec3 sd_ref_support_core(const sd_convex *c, sd_vec3 d_world)
{
    sd_vec3 dl = sd_quat_rotate_inv(c->q, d_world);
    sd_vec3 p = sd_v3_add(c->shape->offset, sd_ref_support_local(c->shape, c->verts, dl));
    return sd_v3_add(c->x, sd_quat_rotate(c->q, p));
}

/* GJK and EPA use the engine's support (shape/support.h); the reference
 * above feeds the oracles, and the two are compared below. */
#include "geom/convex_contact.h"

#include "test.h"

#include <ccd/ccd.h>
#include <libqhull_r/qhull_ra.h>

/* ---------------------------------------------------------------------- */
/* Shapes                                                                  */

#define POOL_MAX 200000
static sd_vec3 g_pool[POOL_MAX];
static uint32_t g_pool_n;

static sd_shape shape_box(double hx, double hy, double hz, double r)
{
    sd_shape s;
    memset(&s, 0, sizeof s);
    s.kind = SD_SHAPE_BOX;
    s.a = sd_v3(hx, hy, hz);
    s.radius = r;
    s.bound = sqrt(hx * hx + hy * hy + hz * hz) + r;
    return s;
}
static sd_shape shape_sphere(double r)
{
    sd_shape s;
    memset(&s, 0, sizeof s);
    s.kind = SD_SHAPE_SPHERE;
    s.radius = r;
    s.bound = r;
    return s;
}
static sd_shape shape_ellipsoid(double ax, double ay, double az, double r)
{
    sd_shape s;
    memset(&s, 0, sizeof s);
    s.kind = SD_SHAPE_ELLIPSOID;
    s.a = sd_v3(ax, ay, az);
    s.radius = r;
    s.bound = sd_max(ax, sd_max(ay, az)) + r;
    return s;
}
static sd_shape shape_cylinder(double rad, double hl, double r)
{
    sd_shape s;
    memset(&s, 0, sizeof s);
    s.kind = SD_SHAPE_CYLINDER;
    s.a = sd_v3(rad, rad, hl);
    s.radius = r;
    s.bound = sqrt(rad * rad + hl * hl) + r;
    return s;
}
static sd_shape shape_cone(double rad, double h, double r)
{
    sd_shape s;
    memset(&s, 0, sizeof s);
    s.kind = SD_SHAPE_CONE;
    s.a = sd_v3(rad, rad, h);
    s.offset = sd_v3(0, 0, -0.25 * h); /* centre of mass of a solid cone */
    s.radius = r;
    s.bound = sd_max(0.75 * h, sqrt(rad * rad + 0.0625 * h * h)) + r;
    return s;
}
/* Polytope core: the hull of n random points (interior points included). */
static sd_shape shape_polytope(sd_rng *rng, int n, double size)
{
    sd_shape s;
    memset(&s, 0, sizeof s);
    s.kind = SD_SHAPE_POLYHEDRON;
    s.vstart = g_pool_n;
    s.vcount = (uint32_t)n;
    sd_vec3 sc = sd_v3(size * sd_rng_range(rng, 0.4, 1), size * sd_rng_range(rng, 0.4, 1), size * sd_rng_range(rng, 0.4, 1));
    sd_vec3 mean = sd_v3_zero();
    for (int i = 0; i < n; ++i) {
        sd_vec3 p;
        do {
            p = sd_v3(sd_rng_range(rng, -1, 1), sd_rng_range(rng, -1, 1), sd_rng_range(rng, -1, 1));
        } while (sd_v3_norm2(p) > 1 || sd_v3_norm2(p) < 0.04);
        p = sd_v3_scale(p, 1 / sd_v3_norm(p) * sd_rng_range(rng, 0.7, 1));
        g_pool[g_pool_n + (uint32_t)i] = sd_v3_mul(p, sc);
        mean = sd_v3_add(mean, g_pool[g_pool_n + (uint32_t)i]);
    }
    mean = sd_v3_scale(mean, 1.0 / n);
    double b = 0;
    for (int i = 0; i < n; ++i) {
        g_pool[g_pool_n + (uint32_t)i] = sd_v3_sub(g_pool[g_pool_n + (uint32_t)i], mean);
        b = sd_max(b, sd_v3_norm(g_pool[g_pool_n + (uint32_t)i]));
    }
    g_pool_n += (uint32_t)n;
    s.bound = b;
    return s;
}

static sd_convex body(const sd_shape *s, sd_vec3 x, sd_quat q)
{
    sd_convex c;
    c.shape = s;
    c.verts = g_pool;
    c.x = x;
    c.q = q;
    return c;
}

/* ---------------------------------------------------------------------- */
/* libccd oracle                                                           */

static void ccd_support(const void *obj, const ccd_vec3_t *dir, ccd_vec3_t *out)
{
    sd_vec3 p = sd_ref_support_core((const sd_convex *)obj, sd_v3(ccdVec3X(dir), ccdVec3Y(dir), ccdVec3Z(dir)));
    ccdVec3Set(out, p.x, p.y, p.z);
}
static void ccd_center(const void *obj, ccd_vec3_t *out)
{
    const sd_convex *c = (const sd_convex *)obj;
    ccdVec3Set(out, c->x.x, c->x.y, c->x.z);
}
static void ccd_setup(ccd_t *ccd)
{
    CCD_INIT(ccd);
    ccd->support1 = ccd_support;
    ccd->support2 = ccd_support;
    ccd->center1 = ccd_center;
    ccd->center2 = ccd_center;
    ccd->max_iterations = 500;
    ccd->epa_tolerance = 1e-12;
    ccd->mpr_tolerance = 1e-12;
}

/* ---------------------------------------------------------------------- */
/* Exact polytope oracle: the hull of {a_i − b_j} by qhull                 */

static sd_vec3 tri_closest(sd_vec3 a, sd_vec3 b, sd_vec3 c)
{
    /* closest point of a triangle to the origin: the plane projection if it
     * lies inside, else the best of the three edges (plain, not Voronoi tests) */
    sd_vec3 n = sd_v3_cross(sd_v3_sub(b, a), sd_v3_sub(c, a));
    double n2 = sd_v3_norm2(n);
    if (n2 > 0) {
        sd_vec3 p = sd_v3_scale(n, sd_v3_dot(n, a) / n2);
        double l0 = sd_v3_dot(sd_v3_cross(sd_v3_sub(b, p), sd_v3_sub(c, p)), n);
        double l1 = sd_v3_dot(sd_v3_cross(sd_v3_sub(c, p), sd_v3_sub(a, p)), n);
        double l2 = sd_v3_dot(sd_v3_cross(sd_v3_sub(a, p), sd_v3_sub(b, p)), n);
        if (l0 >= 0 && l1 >= 0 && l2 >= 0)
            return p;
    }
    sd_vec3 e[3][2] = {{a, b}, {b, c}, {c, a}};
    sd_vec3 best = a;
    for (int k = 0; k < 3; ++k) {
        sd_vec3 p = e[k][0], q = e[k][1], pq = sd_v3_sub(q, p);
        double t = sd_v3_norm2(pq) > 0 ? -sd_v3_dot(p, pq) / sd_v3_norm2(pq) : 0;
        t = sd_clamp(t, 0, 1);
        sd_vec3 x = sd_v3_madd(p, t, pq);
        if (sd_v3_norm2(x) < sd_v3_norm2(best))
            best = x;
    }
    return best;
}

/* Signed distance of the origin from the hull (> 0 outside, −depth inside). */
static int qhull_signed_distance(const sd_convex *a, const sd_convex *b, double *out)
{
    static coordT pts[3 * 4096];
    int na = (int)a->shape->vcount, nb = (int)b->shape->vcount;
    sd_vec3 va[64], vb[64];
    for (int i = 0; i < na; ++i)
        va[i] = sd_v3_add(a->x, sd_quat_rotate(a->q, g_pool[a->shape->vstart + (uint32_t)i]));
    for (int j = 0; j < nb; ++j)
        vb[j] = sd_v3_add(b->x, sd_quat_rotate(b->q, g_pool[b->shape->vstart + (uint32_t)j]));
    int n = 0;
    for (int i = 0; i < na; ++i)
        for (int j = 0; j < nb; ++j) {
            sd_vec3 w = sd_v3_sub(va[i], vb[j]);
            pts[3 * n] = w.x;
            pts[3 * n + 1] = w.y;
            pts[3 * n + 2] = w.z;
            n++;
        }
    qhT qh_qh;
    qhT *qh = &qh_qh;
    qh_zero(qh, stderr);
    char flags[] = "qhull Qt";
    int exitcode = qh_new_qhull(qh, 3, n, pts, False, flags, NULL, stderr);
    double outside = 1e300, depth = 1e300;
    int any_out = 0;
    if (!exitcode) {
        facetT *facet;
        vertexT *vertex, **vertexp;
        FORALLfacets {
            double off = facet->offset; /* normal·x + offset <= 0 inside */
            if (off > 0)
                any_out = 1;
            depth = sd_min(depth, -off);
            sd_vec3 t[3];
            int k = 0;
            FOREACHvertex_(facet->vertices) {
                if (k < 3)
                    t[k] = sd_v3(vertex->point[0], vertex->point[1], vertex->point[2]);
                k++;
            }
            if (k == 3)
                outside = sd_min(outside, sd_v3_norm(tri_closest(t[0], t[1], t[2])));
        }
    }
    int curlong, totlong;
    qh_freeqhull(qh, !qh_ALL);
    qh_memfreeshort(qh, &curlong, &totlong);
    if (exitcode)
        return 0;
    *out = any_out ? outside : -depth;
    return 1;
}

/* ---------------------------------------------------------------------- */
/* Statistics per pair type                                                */

enum { NK = 6 };
static const char *kind_name[NK] = {"sphere", "box", "cylinder", "cone", "ellipsoid", "polytope"};
typedef struct pair_stats {
    long pairs, epa_runs, gjk_iter, gjk_sup, epa_iter, epa_sup, maxiter, degenerate, epa_capped, epa_degen;
    long disagree, grazing;
    double max_witness_err, max_dist_err_q, max_dist_gap, max_depth_err_ccd, max_depth_err_q, max_depth_gap;
    long ccd_n, ccd_agree, ccd_capped_lb, ccd_bracket, ccd_above_ub, ccd_other, ccd_beats_us;
    double max_depth_gap_capped;
} pair_stats;
static pair_stats g_stats[NK][NK];
static double g_support_err;

static sd_shape random_shape(sd_rng *rng, int kind)
{
    double s = sd_rng_range(rng, 0.3, 1.0);
    switch (kind) {
    case SD_SHAPE_SPHERE:
        return shape_sphere(s);
    case SD_SHAPE_BOX:
        return shape_box(s * sd_rng_range(rng, 0.3, 1), s * sd_rng_range(rng, 0.3, 1), s * sd_rng_range(rng, 0.3, 1), 0);
    case SD_SHAPE_CYLINDER:
        return shape_cylinder(s * sd_rng_range(rng, 0.3, 1), s * sd_rng_range(rng, 0.3, 1), 0);
    case SD_SHAPE_CONE:
        return shape_cone(s * sd_rng_range(rng, 0.3, 1), s * sd_rng_range(rng, 0.5, 1.5), 0);
    case SD_SHAPE_ELLIPSOID:
        return shape_ellipsoid(s * sd_rng_range(rng, 0.3, 1), s * sd_rng_range(rng, 0.3, 1), s * sd_rng_range(rng, 0.3, 1), 0);
    default:
        return shape_polytope(rng, 4 + (int)(sd_rng_next(rng) % 17), s);
    }
}

/* h_K(u) = h_A(u) + h_B(−u) with the reference supports */
static double ref_hK(const sd_convex *a, const sd_convex *b, sd_vec3 u)
{
    return sd_v3_dot(u, sd_ref_support_core(a, u)) - sd_v3_dot(u, sd_ref_support_core(b, sd_v3_neg(u)));
}

static int finite3(sd_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

/* One random pair; the special modes place the bodies face to face or edge
 * to edge. */
static void random_pair(sd_rng *rng, int mode)
{
    int ka = (int)(sd_rng_next(rng) % NK), kb = (int)(sd_rng_next(rng) % NK);
    if (mode > 0) {
        ka = (sd_rng_next(rng) & 1) ? SD_SHAPE_BOX : SD_SHAPE_POLYHEDRON;
        kb = (sd_rng_next(rng) & 1) ? SD_SHAPE_BOX : SD_SHAPE_POLYHEDRON;
        if (mode == 1)
            ka = kb = SD_SHAPE_BOX;
    }
    uint32_t pool_mark = g_pool_n;
    sd_shape sa = random_shape(rng, ka), sb = random_shape(rng, kb);
    sd_quat qa = rand_quat(rng), qb = rand_quat(rng);
    sd_vec3 xa = sd_v3(sd_rng_range(rng, -1, 1), sd_rng_range(rng, -1, 1), sd_rng_range(rng, -1, 1));
    sd_vec3 dir = rand_unit(rng);
    double L = sa.bound + sb.bound;
    double sep = sd_rng_range(rng, 0.1, 1.1) * L;
    if (mode == 1) {
        /* face to face: same orientation, offset along a body axis so the
         * faces are parallel (the origin then sits on a flat face of K) */
        qb = qa;
        int ax = (int)(sd_rng_next(rng) % 3);
        sd_vec3 e = sd_v3(ax == 0, ax == 1, ax == 2);
        double ha = ax == 0 ? sa.a.x : ax == 1 ? sa.a.y : sa.a.z, hb = ax == 0 ? sb.a.x : ax == 1 ? sb.a.y : sb.a.z;
        sd_vec3 lat = sd_v3(sd_rng_range(rng, -0.3, 0.3), sd_rng_range(rng, -0.3, 0.3), sd_rng_range(rng, -0.3, 0.3));
        lat = sd_v3_sub(lat, sd_v3_scale(e, sd_v3_dot(lat, e)));
        double gap = sd_rng_range(rng, -0.5, 0.5) * (ha + hb);
        dir = sd_quat_rotate(qa, sd_v3_add(sd_v3_scale(e, ha + hb + gap), lat));
        sep = 1;
    }
    if (mode == 2) {
        /* near-contact: separations around the touching distance along dir */
        sep = sd_rng_range(rng, 0.2, 0.9) * L;
    }
    sd_vec3 xb = sd_v3_madd(xa, sep, dir);
    sd_convex A = body(&sa, xa, qa), B = body(&sb, xb, qb);
    for (int k = 0; k < 2; ++k) {
        /* engine vs reference support: the same support value h(u) */
        sd_vec3 u = rand_unit(rng);
        const sd_convex *c = k ? &B : &A;
        double h1 = sd_v3_dot(u, sd_convex_support_core(c, u)), h2 = sd_v3_dot(u, sd_ref_support_core(c, u));
        g_support_err = sd_max(g_support_err, fabs(h1 - h2) / L);
    }
    pair_stats *st = &g_stats[ka < kb ? ka : kb][ka < kb ? kb : ka];
    st->pairs++;

    sd_gjk_result g = sd_gjk_distance(&A, &B, sd_v3_zero());
    st->gjk_iter += g.iterations;
    st->gjk_sup += g.support_calls;
    if (g.status == SD_GJK_MAX_ITER)
        st->maxiter++;
    if (g.status == SD_GJK_DEGENERATE)
        st->degenerate++;
    CHECK(finite3(g.pa) && finite3(g.pb) && isfinite(g.distance));
    int ours_hit = g.status == SD_GJK_OVERLAP || g.status == SD_GJK_TOUCHING;
    double signed_d = g.distance;
    sd_epa_result e;
    memset(&e, 0, sizeof e);
    if (ours_hit) {
        e = sd_epa_penetration(&A, &B, &g);
        st->epa_runs++;
        st->epa_iter += e.iterations;
        st->epa_sup += e.support_calls;
        if (e.status == SD_EPA_CAPPED)
            st->epa_capped++;
        if (e.status == SD_EPA_DEGENERATE)
            st->epa_degen++;
        CHECK(finite3(e.normal) && finite3(e.pa) && finite3(e.pb) && isfinite(e.depth));
        CHECK(fabs(sd_v3_norm(e.normal) - 1) < 1e-12);
        signed_d = -e.depth;
    }

    /* the exact oracle for two polytopes (boxes are polytopes too) */
    int poly_a = ka == SD_SHAPE_BOX || ka == SD_SHAPE_POLYHEDRON, poly_b = kb == SD_SHAPE_BOX || kb == SD_SHAPE_POLYHEDRON;
    double qd = 0;
    int have_q = 0;
    if (poly_a && poly_b) {
        /* boxes as 8-vertex polytopes in the pool, for the oracle only */
        sd_shape ta = sa, tb = sb;
        sd_shape *ps[2] = {&ta, &tb};
        for (int k = 0; k < 2; ++k)
            if (ps[k]->kind == SD_SHAPE_BOX) {
                ps[k]->vstart = g_pool_n;
                ps[k]->vcount = 8;
                for (int i = 0; i < 8; ++i)
                    g_pool[g_pool_n++] = sd_v3((i & 1) ? ps[k]->a.x : -ps[k]->a.x, (i & 2) ? ps[k]->a.y : -ps[k]->a.y,
                                               (i & 4) ? ps[k]->a.z : -ps[k]->a.z);
            }
        sd_convex TA = body(&ta, xa, qa), TB = body(&tb, xb, qb);
        have_q = qhull_signed_distance(&TA, &TB, &qd);
        CHECK(have_q);
    }

    /* libccd: boolean and depth */
    ccd_t ccd;
    ccd_setup(&ccd);
    int ccd_hit = ccdGJKIntersect(&A, &B, &ccd);
    double ref_d = have_q ? qd : signed_d;
    if (fabs(ref_d) <= 1e-6 * L) {
        st->grazing++;
    } else {
        if (ccd_hit != ours_hit) {
            st->disagree++;
            printf("  disagree %s-%s: ours %d (d %.3e) ccd %d\n", kind_name[ka], kind_name[kb], ours_hit, signed_d, ccd_hit);
        }
        if (have_q && (ref_d > 0) != !ours_hit) {
            st->disagree++;
            printf("  disagree %s-%s: ours %d (d %.3e) qhull d %.3e\n", kind_name[ka], kind_name[kb], ours_hit, signed_d, qd);
        }
    }
    if (!ours_hit) {
        /* duality certificate: the plane ⟂ n between the witnesses separates
         * the cores by at least −h_A(−n) − h_B(n) (reference supports) */
        sd_vec3 n = sd_v3_normalize(sd_v3_neg(g.dir)); /* v = pa − pb, kept exactly */
        double lb = -ref_hK(&A, &B, sd_v3_neg(n));
        st->max_witness_err = sd_max(st->max_witness_err, fabs(sd_v3_norm(sd_v3_sub(g.pa, g.pb)) - g.distance) / L);
        double gap = (g.distance - lb) / sd_max(g.distance, 1e-6 * L);
        st->max_dist_gap = sd_max(st->max_dist_gap, gap);
        if (getenv("SD_DEBUG") && (gap > 1e-6 || fabs(sd_v3_norm(sd_v3_sub(g.pa, g.pb)) - g.distance) > 1e-12 * L))
            printf("  dbg %s-%s status %d n %d it %d d %.6e |pa-pb| %.6e lb %.6e lam %g %g %g %g\n", kind_name[ka], kind_name[kb], g.status,
                   g.simplex.n, g.iterations, g.distance, sd_v3_norm(sd_v3_sub(g.pa, g.pb)), lb, g.simplex.lambda[0],
                   g.simplex.lambda[1], g.simplex.lambda[2], g.simplex.lambda[3]);
        if (have_q)
            st->max_dist_err_q = sd_max(st->max_dist_err_q, fabs(g.distance - qd) / sd_max(qd, 1e-6 * L));
    } else {
        /* the depth along EPA's own normal is an upper bound h_K(−normal) */
        double ub = ref_hK(&A, &B, sd_v3_neg(e.normal));
        if (have_q && qd < 0)
            st->max_depth_err_q = sd_max(st->max_depth_err_q, fabs(e.depth + qd) / sd_max(-qd, 1e-6 * L));
        ccd_real_t depth;
        ccd_vec3_t cdir, cpos;
        int converged = e.status == SD_EPA_OK || e.status == SD_EPA_TOUCHING;
        if (!converged)
            st->max_depth_gap_capped = sd_max(st->max_depth_gap_capped, (ub - e.depth) / sd_max(e.depth, 1e-6 * L));
        else
            st->max_depth_gap = sd_max(st->max_depth_gap, (ub - e.depth) / sd_max(e.depth, 1e-6 * L));
        if (ccd_hit && ccdGJKPenetration(&A, &B, &ccd, &depth, &cdir, &cpos) == 0) {
            st->ccd_n++;
            double scale = sd_max(e.depth, 1e-6 * L);
            double err = fabs(e.depth - depth) / scale;
            /* libccd's direction gives a certified upper bound of the true
             * depth: ours must never exceed it (else libccd found a shorter
             * way out and we are wrong) */
            sd_vec3 u = sd_v3(ccdVec3X(&cdir), ccdVec3Y(&cdir), ccdVec3Z(&cdir));
            double ccd_ub = 1e300;
            if (sd_v3_norm2(u) > 0) {
                u = sd_v3_normalize(u);
                ccd_ub = sd_min(ref_hK(&A, &B, u), ref_hK(&A, &B, sd_v3_neg(u)));
            }
            if (converged && e.depth > ccd_ub + 1e-6 * scale) {
                st->ccd_beats_us++;
                printf("  libccd shallower %s-%s: ours %.9e (status %d) ccd %.9e h_K(ccd dir) %.9e\n", kind_name[ka],
                       kind_name[kb], e.depth, e.status, depth, ccd_ub);
            }
            if (err <= 1e-6) {
                st->ccd_agree++;
                st->max_depth_err_ccd = sd_max(st->max_depth_err_ccd, err);
            } else if (depth <= e.depth + 1e-9 * scale && e.depth <= ccd_ub + 1e-6 * scale) {
                /* libccd stopped early: its depth is its polytope's face (a
                 * lower bound) and ours lies in its own bracket */
                st->ccd_bracket++;
            } else if (depth > ub + 1e-6 * scale) {
                /* above h_K along our normal, a certified upper bound */
                st->ccd_above_ub++;
                if (getenv("SD_DEBUG"))
                    printf("  ccd-above-ub %s-%s ours %.9e ccd %.9e h_K(our n) %.9e h_K(ccd dir) %.9e\n", kind_name[ka],
                           kind_name[kb], e.depth, depth, ub, ccd_ub);
            } else if (!converged && e.depth <= depth + 1e-9 * scale) {
                st->ccd_capped_lb++; /* our capped run: its depth is a lower bound, below libccd's */
            } else {
                st->ccd_other++;
                printf("  ccd-other %s-%s ours %.9e (status %d) ccd %.9e h_K(our n) %.9e h_K(ccd dir) %.9e\n", kind_name[ka],
                       kind_name[kb], e.depth, e.status, depth, ub, ccd_ub);
            }
        }
    }
    g_pool_n = pool_mark;
}

/* ---------------------------------------------------------------------- */
/* §H regressions 1–9                                                      */

static void regressions(void)
{
    sd_shape cube = shape_box(0.5, 0.5, 0.5, 0), cube2 = shape_box(1, 1, 1, 0);
    sd_quat I = sd_quat_identity();
    sd_vec3 z0 = sd_v3_zero();
    char label[128];

    /* 1 */
    sd_convex A = body(&cube, z0, I), B = body(&cube, sd_v3(3, 0, 0), I);
    sd_gjk_result g = sd_gjk_distance(&A, &B, z0);
    CHECK(g.status == SD_GJK_SEPARATED);
    CHECK_NEAR("H1 cubes 3 apart: d", g.distance, 2.0, 1e-12);
    CHECK_NEAR("H1 witness a.x", g.pa.x, 0.5, 1e-12);
    CHECK_NEAR("H1 witness b.x", g.pb.x, 2.5, 1e-12);

    /* 2 */
    B = body(&cube, sd_v3(2, 0, 0), sd_quat_from_rotvec(sd_v3(0, 0, SD_PI_D / 4)));
    g = sd_gjk_distance(&A, &B, z0);
    CHECK_NEAR("H2 45deg cube: d", g.distance, 2 - sqrt(2) / 2 - 0.5, 1e-12);

    /* 3 */
    B = body(&cube, sd_v3(2, 2, 2), I);
    g = sd_gjk_distance(&A, &B, z0);
    CHECK_NEAR("H3 corner to corner: d", g.distance, sqrt(3), 1e-12);

    /* 4: smooth shapes (spheres as ellipsoid cores) */
    sd_shape ball = shape_ellipsoid(1, 1, 1, 0);
    sd_rng r4 = sd_rng_seed(4);
    sd_convex S1 = body(&ball, z0, I), S2 = body(&ball, sd_v3(3, 0, 0), rand_quat(&r4));
    int worst_it = 0;
    double worst_err = 0;
    for (int k = 0; k < 100; ++k) {
        S2.x = sd_v3_scale(rand_unit(&r4), 3);
        g = sd_gjk_distance(&S1, &S2, rand_unit(&r4));
        worst_it = g.iterations > worst_it ? g.iterations : worst_it;
        worst_err = sd_max(worst_err, fabs(g.distance - 1));
    }
    CHECK_NEAR("H4 unit spheres 3 apart: max |d - 1| (100 dirs)", worst_err, 0, 1e-9);
    printf("     H4 most GJK iterations: %d (< 30)\n", worst_it);
    CHECK(worst_it < 30);

    /* 5: exactly touching */
    B = body(&cube, sd_v3(1, 0, 0), I);
    g = sd_gjk_distance(&A, &B, z0);
    CHECK(g.status == SD_GJK_TOUCHING || fabs(g.distance) <= 1e-12);
    CHECK(isfinite(g.distance) && finite3(g.pa));
    if (g.status != SD_GJK_SEPARATED) {
        sd_epa_result e = sd_epa_penetration(&A, &B, &g);
        CHECK_NEAR("H5 touching cubes: EPA depth", e.depth, 0, 1e-12);
        CHECK(finite3(e.normal));
    }
    /* corner on corner: GJK's very first support is the origin (1-point simplex) */
    B = body(&cube, sd_v3(1, 1, 1), I);
    g = sd_gjk_distance(&A, &B, z0);
    CHECK(g.status == SD_GJK_TOUCHING && g.simplex.n == 1);
    {
        sd_epa_result e = sd_epa_penetration(&A, &B, &g);
        CHECK(e.status == SD_EPA_TOUCHING && e.depth == 0 && finite3(e.normal));
    }

    /* 6: libccd #25 */
    sd_rng r6 = sd_rng_seed(6);
    double worst6 = 0, worstn6 = 0;
    int nan6 = 0;
    for (int k = 0; k < 100; ++k) {
        A = body(&cube2, z0, I);
        B = body(&cube2, sd_v3(0, 0, 1.9), I);
        sd_vec3 w = k == 0 ? sd_v3(1, 0, 0) : rand_unit(&r6);
        g = sd_gjk_distance(&A, &B, w);
        sd_epa_result e = sd_epa_penetration(&A, &B, &g);
        nan6 += !(finite3(e.normal) && isfinite(e.depth));
        worst6 = sd_max(worst6, fabs(e.depth - 0.1));
        worstn6 = sd_max(worstn6, 1 - fabs(e.normal.z));
        /* and through the contact features, with a warm start */
        sd_vec3 warm = w;
        sd_convex_contact c = sd_convex_collide(&A, &B, &warm);
        worst6 = sd_max(worst6, fabs(c.delta - 0.1));
        worstn6 = sd_max(worstn6, fabs(c.n.z + 1)); /* from b (above) to a: −z */
    }
    CHECK_NEAR("H6 ccd#25 side-2 cubes 1.9 apart: max |depth - 0.1|", worst6, 0, 1e-12);
    CHECK_NEAR("H6 max (1 - |n.z|), 100 initial dirs", worstn6, 0, 1e-12);
    CHECK(nan6 == 0);

    /* 7 */
    A = body(&cube, z0, I);
    B = body(&cube, sd_v3(0.3, 0, 0), I);
    g = sd_gjk_distance(&A, &B, z0);
    sd_epa_result e = sd_epa_penetration(&A, &B, &g);
    CHECK_NEAR("H7 unit cubes 0.3 apart: depth", e.depth, 0.7, 1e-12);
    CHECK_NEAR("H7 |n.x|", fabs(e.normal.x), 1, 1e-12);
    sd_rng r7 = sd_rng_seed(7);
    double worst7 = 0;
    for (int k = 0; k < 100; ++k) {
        sd_quat q = rand_quat(&r7);
        A = body(&cube, z0, q);
        B = body(&cube, sd_quat_rotate(q, sd_v3(0.3, 0, 0)), q);
        g = sd_gjk_distance(&A, &B, rand_unit(&r7));
        e = sd_epa_penetration(&A, &B, &g);
        worst7 = sd_max(worst7, fabs(e.depth - 0.7));
    }
    CHECK_NEAR("H7 rotated (100 rotations): max |depth - 0.7|", worst7, 0, 1e-9);

    /* 8: simplices of 2 and 3 points that hold the origin (OpenRAL #215) */
    A = body(&cube, z0, I);
    B = body(&cube, sd_v3(0.3, 0, 0), I);
    sd_gjk_result h;
    memset(&h, 0, sizeof h);
    h.status = SD_GJK_TOUCHING;
    h.simplex.n = 2;
    h.simplex.v[0].a = sd_v3(0.5, 0, 0);
    h.simplex.v[0].b = sd_v3(-0.2, 0, 0);
    h.simplex.v[1].a = sd_v3(-0.5, 0, 0);
    h.simplex.v[1].b = sd_v3(0.8, 0, 0);
    for (int k = 0; k < 2; ++k) {
        h.simplex.v[k].w = sd_v3_sub(h.simplex.v[k].a, h.simplex.v[k].b);
        h.simplex.lambda[k] = k == 0 ? 1.3 / 2.0 : 0.7 / 2.0;
    }
    e = sd_epa_penetration(&A, &B, &h);
    CHECK_NEAR("H8 EPA from a 2-point simplex: depth", e.depth, 0.7, 1e-12);
    CHECK_NEAR("H8 2-point |n.x|", fabs(e.normal.x), 1, 1e-12);
    h.simplex.n = 3;
    h.simplex.v[0].a = sd_v3(0.5, 0, 0);
    h.simplex.v[0].b = sd_v3(-0.2, 0, 0);
    h.simplex.v[1].a = sd_v3(-0.5, 0.5, 0);
    h.simplex.v[1].b = sd_v3(0.8, -0.5, 0);
    h.simplex.v[2].a = sd_v3(-0.5, -0.5, 0);
    h.simplex.v[2].b = sd_v3(0.8, 0.5, 0);
    for (int k = 0; k < 3; ++k) {
        h.simplex.v[k].w = sd_v3_sub(h.simplex.v[k].a, h.simplex.v[k].b);
        h.simplex.lambda[k] = 1.0 / 3.0;
    }
    e = sd_epa_penetration(&A, &B, &h);
    CHECK_NEAR("H8 EPA from a 3-point simplex: depth", e.depth, 0.7, 1e-12);
    CHECK_NEAR("H8 3-point |n.x|", fabs(e.normal.x), 1, 1e-12);
    /* and from whatever GJK ends with on axis-aligned boxes, any start */
    sd_rng r8 = sd_rng_seed(8);
    double worst8 = 0;
    int sizes[5] = {0, 0, 0, 0, 0};
    for (int k = 0; k < 200; ++k) {
        sd_vec3 w = k < 6 ? sd_v3(k / 2 == 0 ? 1 - 2 * (k & 1) : 0, k / 2 == 1 ? 1 - 2 * (k & 1) : 0, k / 2 == 2 ? 1 - 2 * (k & 1) : 0)
                          : rand_unit(&r8);
        g = sd_gjk_distance(&A, &B, w);
        sizes[g.simplex.n]++;
        e = sd_epa_penetration(&A, &B, &g);
        worst8 = sd_max(worst8, fabs(e.depth - 0.7));
    }
    printf("     H8 GJK final simplex sizes 1/2/3/4: %d/%d/%d/%d\n", sizes[1], sizes[2], sizes[3], sizes[4]);
    CHECK_NEAR("H8 aligned boxes, 200 starts: max |depth - 0.7|", worst8, 0, 1e-12);

    /* 9: sphere R = 0.5 at (0,0,0.9) on a unit cube: swell path vs EPA path */
    sd_shape sph = shape_sphere(0.5), ell = shape_ellipsoid(0.5, 0.5, 0.5, 0);
    sd_convex P = body(&sph, sd_v3(0, 0, 0.9), I), C = body(&cube, z0, I);
    sd_convex_contact c = sd_convex_collide(&P, &C, NULL);
    CHECK(c.touching && !c.used_epa);
    CHECK_NEAR("H9 sphere on cube, swell: delta", c.delta, 0.1, 1e-12);
    CHECK_NEAR("H9 swell: n.z", c.n.z, 1, 1e-12);
    CHECK_NEAR("H9 swell: point z (midway)", c.point.z, 0.45, 1e-12);
    sd_convex E = body(&ell, sd_v3(0, 0, 0.9), I);
    sd_convex_contact c2 = sd_convex_collide(&E, &C, NULL);
    CHECK(c2.touching && c2.used_epa);
    CHECK_NEAR("H9 sphere on cube, EPA: delta", c2.delta, 0.1, 1e-12);
    CHECK_NEAR("H9 swell vs EPA: |delta diff|", fabs(c.delta - c2.delta), 0, 1e-8);
    CHECK_NEAR("H9 swell vs EPA: |n diff|", sd_v3_norm(sd_v3_sub(c.n, c2.n)), 0, 1e-8);
    CHECK_NEAR("H9 swell vs EPA: |point diff|", sd_v3_norm(sd_v3_sub(c.point, c2.point)), 0, 1e-8);

    /* shrink/swell for rounded boxes: two rounded unit cubes, cores 0.8 wide, r = 0.1 */
    sd_shape rb = shape_box(0.4, 0.4, 0.4, 0.1);
    sd_convex R1 = body(&rb, z0, I), R2 = body(&rb, sd_v3(0.95, 0.1, 0), I);
    c = sd_convex_collide(&R1, &R2, NULL);
    CHECK_NEAR("rounded cubes 0.95 apart: delta", c.delta, 0.05, 1e-12);
    CHECK_NEAR("rounded cubes: n.x (b to a)", c.n.x, -1, 1e-12);
    CHECK_NEAR("rounded cubes: point x", c.point.x, 0.475, 1e-12);
    /* cores overlapping: EPA depth plus both radii */
    R2.x = sd_v3(0.7, 0, 0);
    c = sd_convex_collide(&R1, &R2, NULL);
    CHECK(c.used_epa);
    CHECK_NEAR("rounded cubes 0.7 apart (cores overlap): delta", c.delta, 0.3, 1e-12);
    CHECK_NEAR("rounded cubes 0.7 apart: point x", c.point.x, 0.35, 1e-12);

    /* spheres (point cores), including coincident centres */
    sd_shape s1 = shape_sphere(0.5), s2 = shape_sphere(0.3);
    sd_convex Q1 = body(&s1, z0, I), Q2 = body(&s2, sd_v3(0, 0.7, 0), I);
    c = sd_convex_collide(&Q1, &Q2, NULL);
    CHECK_NEAR("point-core spheres: delta", c.delta, 0.1, 1e-12);
    CHECK_NEAR("point-core spheres: n.y", c.n.y, -1, 1e-12);
    CHECK_NEAR("point-core spheres: point y", c.point.y, 0.45, 1e-12);
    Q2.x = z0;
    c = sd_convex_collide(&Q1, &Q2, NULL);
    CHECK(c.touching && finite3(c.n) && finite3(c.point));
    CHECK_NEAR("coincident spheres: delta", c.delta, 0.8, 1e-12);
    CHECK_NEAR("coincident spheres: |n|", sd_v3_norm(c.n), 1, 1e-12);

    /* half-space walls */
    sd_convex W = body(&cube, sd_v3(0.2, -0.3, 0.49), sd_quat_from_rotvec(sd_v3(0, 0, 0.3)));
    c = sd_convex_plane(&W, z0, sd_v3(0, 0, 1));
    CHECK_NEAR("cube on floor: delta", c.delta, 0.01, 1e-12);
    snprintf(label, sizeof label, "cube on floor: point under the centre (x)");
    CHECK_NEAR(label, c.point.x, 0.2, 1e-12);
    CHECK_NEAR("cube on floor: point y", c.point.y, -0.3, 1e-12);
    CHECK_NEAR("cube on floor: point z (midway)", c.point.z, -0.005, 1e-12);
    W.q = sd_quat_from_rotvec(sd_v3(1e-12, 0, 0.3)); /* a face tilted by rounding: still the centre */
    c = sd_convex_plane(&W, z0, sd_v3(0, 0, 1));
    CHECK_NEAR("cube tilted 1e-12 rad: point x", c.point.x, 0.2, 1e-9);
    W.q = sd_quat_from_rotvec(sd_v3(0.1, 0, 0)); /* clearly tilted: the lowest edge's midpoint */
    c = sd_convex_plane(&W, z0, sd_v3(0, 0, 1));
    CHECK_NEAR("cube tilted 0.1 rad about x: point x (edge midpoint)", c.point.x, 0.2, 1e-12);
    sd_shape cyl = shape_cylinder(0.3, 0.5, 0.05), cone = shape_cone(0.4, 1.0, 0);
    sd_convex Cy = body(&cyl, sd_v3(1, 2, 0.54), I);
    c = sd_convex_plane(&Cy, z0, sd_v3(0, 0, 1));
    CHECK_NEAR("standing cylinder: delta", c.delta, 0.01, 1e-12);
    CHECK_NEAR("standing cylinder: point x (cap centre)", c.point.x, 1, 1e-12);
    CHECK_NEAR("standing cylinder: point y", c.point.y, 2, 1e-12);
    sd_convex Co = body(&cone, sd_v3(0, 0, 0.24), I);
    c = sd_convex_plane(&Co, z0, sd_v3(0, 0, 1));
    CHECK_NEAR("cone on its base: delta", c.delta, 0.01, 1e-12);
    CHECK_NEAR("cone on its base: point x", c.point.x, 0, 1e-12);
    CHECK_NEAR("cone on its base: point z", c.point.z, -0.005, 1e-12);
}

/* The early stop of sd_gjk_distance_bounded (gjk.h rule 0), as
 * sd_convex_collide uses it: on random pairs with random swept radii, a
 * bounded answer must be a true lower bound above the threshold (so the
 * swept bodies do not touch), and the contact decision (touching or not)
 * must equal the one of the full-accuracy query; with warm starts too. */
static void bounded_stop(void)
{
    sd_rng rng = sd_rng_seed(77);
    int wrong_bound = 0, wrong_touch = 0, stopped = 0, n = 4000;
    for (int k = 0; k < n; ++k) {
        int ka = (int)(sd_rng_next(&rng) % NK), kb = (int)(sd_rng_next(&rng) % NK);
        g_pool_n = 0;
        sd_shape sa = random_shape(&rng, ka), sb = random_shape(&rng, kb);
        double stop = sd_rng_range(&rng, 0, 0.3);
        double L = sa.bound + sb.bound;
        sd_vec3 xb = sd_v3_scale(rand_unit(&rng), sd_rng_range(&rng, 0.3, 1.4) * L);
        sd_convex A = body(&sa, sd_v3_zero(), rand_quat(&rng)), B = body(&sb, xb, rand_quat(&rng));
        sd_vec3 warm = (k & 1) ? rand_unit(&rng) : sd_v3_zero();
        sd_gjk_result full = sd_gjk_distance(&A, &B, sd_v3_zero());
        sd_gjk_result g = sd_gjk_distance_bounded(&A, &B, warm, stop);
        int full_sep = full.status == SD_GJK_SEPARATED || full.status == SD_GJK_MAX_ITER;
        if (g.bounded) {
            stopped++;
            /* a lower bound, above the threshold */
            if (!(g.distance > stop) || !full_sep || g.distance > full.distance * (1 + 1e-12) + 1e-12 * L)
                wrong_bound++;
        } else if (g.status == SD_GJK_SEPARATED || g.status == SD_GJK_MAX_ITER) {
            if (!full_sep || fabs(g.distance - full.distance) > 1e-9 * L)
                wrong_bound++;
        }
        /* the contact decision with threshold stop (full: distance < stop;
         * away from the boundary by 1e-9 L) */
        double fd = full_sep ? full.distance : 0;
        if (fabs(fd - stop) > 1e-9 * L) {
            int touch_full = fd < stop;
            int touch_b = !(g.bounded || ((g.status == SD_GJK_SEPARATED || g.status == SD_GJK_MAX_ITER) && g.distance >= stop));
            wrong_touch += touch_full != touch_b;
        }
    }
    printf("bounded GJK: %d of %d queries stopped early\n", stopped, n);
    CHECK_NEAR("bounded GJK: wrong lower bounds or distances", wrong_bound, 0, 0);
    CHECK_NEAR("bounded GJK: contact decisions that differ from the full query", wrong_touch, 0, 0);
    CHECK(stopped > n / 10);
}

int main(void)
{
    regressions();
    bounded_stop();

    /* (a) random pairs against the oracles */
    sd_rng rng = sd_rng_seed(20240611);
    const int n_random = 10000, n_face = 1000, n_near = 1000;
    clock_t t0 = clock();
    for (int k = 0; k < n_random; ++k)
        random_pair(&rng, 0);
    for (int k = 0; k < n_face; ++k)
        random_pair(&rng, (k & 1) ? 1 : 3);
    for (int k = 0; k < n_near; ++k)
        random_pair(&rng, 2);
    double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;

    /* (c) statistics */
    printf("\n%-20s %6s %6s %6s %6s %6s %6s %5s %5s %5s %9s %9s %9s %9s %9s\n", "pair", "n", "gjkIt", "gjkSup", "epaN",
           "epaIt", "epaSup", "cap", "graz", "dis", "dErrQ", "dGap", "DErrCcd", "DErrQ", "DGap");
    pair_stats tot;
    memset(&tot, 0, sizeof tot);
    for (int i = 0; i < NK; ++i)
        for (int j = i; j < NK; ++j) {
            pair_stats *s = &g_stats[i][j];
            if (!s->pairs)
                continue;
            char name[32];
            snprintf(name, sizeof name, "%s-%s", kind_name[i], kind_name[j]);
            printf("%-20s %6ld %6.2f %6.2f %6ld %6.2f %6.2f %5ld %5ld %5ld %9.2e %9.2e %9.2e %9.2e %9.2e\n", name, s->pairs,
                   (double)s->gjk_iter / (double)s->pairs, (double)s->gjk_sup / (double)s->pairs, s->epa_runs,
                   s->epa_runs ? (double)s->epa_iter / (double)s->epa_runs : 0.0,
                   s->epa_runs ? (double)s->epa_sup / (double)s->epa_runs : 0.0, s->epa_capped, s->grazing, s->disagree,
                   s->max_dist_err_q, s->max_dist_gap, s->max_depth_err_ccd, s->max_depth_err_q, s->max_depth_gap);
            tot.pairs += s->pairs;
            tot.gjk_iter += s->gjk_iter;
            tot.gjk_sup += s->gjk_sup;
            tot.epa_runs += s->epa_runs;
            tot.maxiter += s->maxiter;
            tot.degenerate += s->degenerate;
            tot.epa_capped += s->epa_capped;
            tot.epa_degen += s->epa_degen;
            tot.disagree += s->disagree;
            tot.grazing += s->grazing;
            tot.max_dist_err_q = sd_max(tot.max_dist_err_q, s->max_dist_err_q);
            tot.max_witness_err = sd_max(tot.max_witness_err, s->max_witness_err);
            tot.max_dist_gap = sd_max(tot.max_dist_gap, s->max_dist_gap);
            tot.max_depth_err_ccd = sd_max(tot.max_depth_err_ccd, s->max_depth_err_ccd);
            tot.max_depth_err_q = sd_max(tot.max_depth_err_q, s->max_depth_err_q);
            tot.max_depth_gap = sd_max(tot.max_depth_gap, s->max_depth_gap);
            tot.max_depth_gap_capped = sd_max(tot.max_depth_gap_capped, s->max_depth_gap_capped);
            tot.ccd_n += s->ccd_n;
            tot.ccd_agree += s->ccd_agree;
            tot.ccd_bracket += s->ccd_bracket;
            tot.ccd_above_ub += s->ccd_above_ub;
            tot.ccd_other += s->ccd_other;
            tot.ccd_capped_lb += s->ccd_capped_lb;
            tot.ccd_beats_us += s->ccd_beats_us;
        }
    printf("columns: mean GJK iterations and support calls (one call = one support of A and one of B) per pair;\n"
           "EPA runs, mean iterations and support calls per run, capped runs; grazing pairs skipped for the boolean;\n"
           "disagreements; max relative errors: distance vs qhull, distance duality gap, depth vs libccd (where it\n"
           "converged), depth vs "
           "qhull, depth bracket h_K(n) - depth of converged EPA runs.\n");
    printf("%ld pairs in %.2f s: mean GJK support calls %.2f; MAX_ITER %ld, DEGENERATE %ld; EPA %ld runs, capped %ld, "
           "degenerate %ld\n\n",
           tot.pairs, secs, (double)tot.gjk_sup / (double)tot.pairs, tot.maxiter, tot.degenerate, tot.epa_runs,
           tot.epa_capped, tot.epa_degen);
    printf("libccd depth (ccdGJKPenetration, epa_tolerance 1e-12) on %ld overlapping pairs: %ld agree to 1e-6;\n"
           "%ld where libccd stopped early (its depth, a polytope lower bound, is below ours and ours lies in its\n"
           "bracket [depth, h_K(its direction)]); %ld where libccd's depth exceeds h_K along our normal (a certified\n"
           "upper bound: libccd wrong); %ld of our capped runs (flagged; a lower bound, below libccd); %ld other; %ld where libccd's direction is shallower than our depth (we\n"
           "would be wrong). Capped EPA runs: max bracket %.2e (relative).\n\n",
           tot.ccd_n, tot.ccd_agree, tot.ccd_bracket, tot.ccd_above_ub, tot.ccd_capped_lb, tot.ccd_other, tot.ccd_beats_us,
           tot.max_depth_gap_capped);
    CHECK(tot.ccd_other == 0);
    CHECK(tot.ccd_beats_us == 0);
    CHECK(tot.epa_capped <= tot.epa_runs / 100); /* curved kinks only, flagged */
    CHECK(tot.max_depth_gap_capped < 1e-2);
    CHECK_NEAR("support.h vs reference support: max |h - h_ref| / L", g_support_err, 0, 1e-14);
    CHECK(tot.maxiter == 0);
    CHECK(tot.degenerate == 0);
    CHECK(tot.disagree == 0);
    CHECK_NEAR("random: max | |pa - pb| - d | / L", tot.max_witness_err, 0, 1e-10);
    CHECK_NEAR("random: max distance error vs qhull (rel)", tot.max_dist_err_q, 0, 1e-6);
    CHECK_NEAR("random: max distance duality gap (rel)", tot.max_dist_gap, 0, 1e-6);
    CHECK_NEAR("random: max depth error vs qhull (rel)", tot.max_depth_err_q, 0, 1e-6);
    CHECK_NEAR("random: max depth gap along EPA normal (rel)", tot.max_depth_gap, 0, 1e-6);
    return sd_test_summary();
}
