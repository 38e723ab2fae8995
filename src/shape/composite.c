/* composite.c — composite templates of seed 004: validation, overlap test,
 * mass properties (exact sums, voxel lattice eqs. 7-8), principal frame.
 *
 * Invariant: a composite made here is in its principal frame (centre of
 * mass at the origin, principal axes along x, y, z) and its elements are
 * placed in that frame; given_com / given_q lead back to the frame the
 * elements were given in. See composite.h for the method.
 *
 * Moments are kept "raw" while they are summed: V, S = ∫x dV and
 * T = ∫x xᵀ dV about the given frame's origin (per unit density), so sums
 * and differences of bodies are plain additions; they become the centre of
 * mass and the second moments about it once at the end.
 */
#include "shape/composite.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "geom/convex_contact.h"
#include "geom/gjk.h"
#include "shape/support.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#define SD_FAIL(key, ...) sd_error_set(err, SD_ERR_INPUT, "", 0, key, __VA_ARGS__)

typedef struct sd_raw {
    sd_real v; /* m^3 */
    sd_vec3 s; /* m^4, ∫x dV */
    sd_mat3 t; /* m^5, ∫x xᵀ dV */
} sd_raw;

static sd_raw sd_raw_zero(void)
{
    sd_raw r;
    memset(&r, 0, sizeof r);
    return r;
}

static void sd_raw_add(sd_raw *a, sd_real k, const sd_raw *b)
{
    a->v += k * b->v;
    a->s = sd_v3_madd(a->s, k, b->s);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            a->t.m[i][j] += k * b->t.m[i][j];
}

/* centre of mass and second moments about it (parallel-axis theorem) */
static sd_mass sd_raw_to_mass(const sd_raw *r)
{
    sd_mass m;
    m.volume = r->v;
    m.com = r->v > 0 ? sd_v3_scale(r->s, SD_R(1.0) / r->v) : sd_v3_zero();
    const sd_real c[3] = {m.com.x, m.com.y, m.com.z};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m.second.m[i][j] = r->t.m[i][j] - r->v * c[i] * c[j];
    return m;
}

/* one convex element's raw moments in the given frame: its principal
 * second moments J = diag((Iy+Iz-Ix)/2, ...) rotated by R, then moved to
 * its centre x (Steiner) */
static sd_raw sd_raw_of_part(const sd_shape *s, const sd_composite_part *p)
{
    sd_raw r;
    const sd_vec3 I = s->inertia;
    sd_vec3 jd = sd_v3(SD_R(0.5) * (I.y + I.z - I.x), SD_R(0.5) * (I.x + I.z - I.y), SD_R(0.5) * (I.x + I.y - I.z));
    sd_mat3 R = sd_quat_to_mat3(p->q);
    sd_mat3 J = sd_mat3_mul(sd_mat3_mul(R, sd_mat3_diag(jd)), sd_mat3_transpose(R));
    const sd_real x[3] = {p->x.x, p->x.y, p->x.z};
    r.v = s->volume;
    r.s = sd_v3_scale(p->x, s->volume);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r.t.m[i][j] = J.m[i][j] + s->volume * x[i] * x[j];
    return r;
}

static sd_convex sd_part_body(const sd_composite_pools *pools, const sd_composite_part *p)
{
    sd_convex c;
    c.shape = &pools->shapes[p->shape];
    c.verts = pools->verts;
    c.x = p->x;
    c.q = p->q;
    c.planes = pools->planes;
    c.dtris = pools->dtris;
    return c;
}

int sd_composite_parts_overlap(const sd_composite_pools *pools, const sd_composite_part *a,
                               const sd_composite_part *b)
{
    const sd_shape *sa = &pools->shapes[a->shape], *sb = &pools->shapes[b->shape];
    sd_real reach = sa->bound + sb->bound;
    if (sd_v3_norm(sd_v3_sub(a->x, b->x)) >= reach)
        return 0; /* bounding spheres apart (or just touching) */
    sd_convex ca = sd_part_body(pools, a), cb = sd_part_body(pools, b);
    sd_convex_contact c = sd_convex_collide(&ca, &cb, NULL);
    /* faces glued flush (the 8 cubes of seed 004 Table 3) touch with a depth
     * at round-off level: 1e-9 of the size is far above it and far below
     * any overlap that changes a volume visibly */
    return c.touching && c.delta > SD_R(1e-9) * reach;
}

/* ---- point inside a swept convex shape ------------------------------------- */

/* squared distance from (x, y) to the segment (ax, ay)-(bx, by) */
static sd_real sd_seg2_dist2(sd_real x, sd_real y, sd_real ax, sd_real ay, sd_real bx, sd_real by)
{
    sd_real ux = bx - ax, uy = by - ay, l2 = ux * ux + uy * uy;
    sd_real t = l2 > 0 ? ((x - ax) * ux + (y - ay) * uy) / l2 : SD_R(0.0);
    t = sd_max(SD_R(0.0), sd_min(SD_R(1.0), t));
    sd_real dx = x - ax - t * ux, dy = y - ay - t * uy;
    return dx * dx + dy * dy;
}

/* the general answer: GJK distance from the point to the core <= radius */
static int sd_inside_gjk(const sd_shape *s, const sd_vec3 *verts, const sd_plane *planes, const sd_dtri *dtris,
                         sd_vec3 p)
{
    sd_shape pt;
    memset(&pt, 0, sizeof pt);
    pt.kind = SD_SHAPE_SPHERE; /* a point core, radius 0 */
    pt.given_q = sd_quat_identity();
    sd_convex a, b;
    a.shape = s;
    a.verts = verts;
    a.x = sd_v3_zero();
    a.q = sd_quat_identity();
    a.planes = planes;
    a.dtris = dtris;
    b = a;
    b.shape = &pt;
    b.x = p;
    sd_gjk_result g = sd_gjk_distance(&a, &b, sd_v3_zero());
    if (g.status == SD_GJK_TOUCHING || g.status == SD_GJK_OVERLAP)
        return 1;
    return g.distance <= s->radius;
}

int sd_composite_point_inside(const sd_shape *s, const sd_vec3 *verts, const sd_plane *planes, const sd_dtri *dtris,
                              sd_vec3 p)
{
    const sd_vec3 c = sd_v3_sub(p, s->offset); /* about the core's reference point */
    const sd_real r = s->radius, r2 = r * r;
    switch (s->kind) {
    case SD_SHAPE_SPHERE:
        return sd_v3_dot(c, c) <= r2;
    case SD_SHAPE_BOX: {
        sd_real dx = sd_max(SD_R(0.0), sd_fabs(c.x) - s->a.x), dy = sd_max(SD_R(0.0), sd_fabs(c.y) - s->a.y),
                dz = sd_max(SD_R(0.0), sd_fabs(c.z) - s->a.z);
        return dx * dx + dy * dy + dz * dz <= r2;
    }
    case SD_SHAPE_CYLINDER: {
        sd_real dr = sd_max(SD_R(0.0), sd_sqrt(c.x * c.x + c.y * c.y) - s->a.x);
        sd_real dz = sd_max(SD_R(0.0), sd_fabs(c.z) - s->a.z);
        return dr * dr + dz * dz <= r2;
    }
    case SD_SHAPE_CONE: {
        /* the meridian half-section is the triangle (0,0), (R,0), (0,h) in
         * (rho, z); the distance to the solid is the distance to it */
        sd_real rho = sd_sqrt(c.x * c.x + c.y * c.y), z = c.z, R = s->a.x, h = s->a.z;
        if (z >= 0 && rho * h + z * R <= R * h)
            return 1;
        if (r <= 0)
            return 0;
        sd_real d2 = sd_min(sd_seg2_dist2(rho, z, 0, 0, R, 0), sd_seg2_dist2(rho, z, R, 0, 0, h));
        return d2 <= r2;
    }
    case SD_SHAPE_ELLIPSOID: {
        sd_real e = c.x * c.x / (s->a.x * s->a.x) + c.y * c.y / (s->a.y * s->a.y) + c.z * c.z / (s->a.z * s->a.z);
        if (e <= 1)
            return 1;
        if (r <= 0)
            return 0;
        /* the ellipsoid of semi-axes a + r lies inside the swept one (its
         * support sqrt(sum (a_i + r)^2 u_i^2) <= |A u| + r by Minkowski) */
        sd_real A = s->a.x + r, B = s->a.y + r, C = s->a.z + r;
        if (c.x * c.x / (A * A) + c.y * c.y / (B * B) + c.z * c.z / (C * C) <= 1)
            return 1;
        return sd_inside_gjk(s, verts, planes, dtris, p);
    }
    case SD_SHAPE_POLYHEDRON: {
        if (!planes || s->fcount == 0)
            return sd_inside_gjk(s, verts, planes, dtris, p);
        sd_real worst = -SD_R(1e300);
        for (uint32_t k = 0; k < s->fcount; ++k) {
            const sd_plane *pl = &planes[s->fstart + k];
            worst = sd_max(worst, sd_v3_dot(pl->n, c) - pl->h);
        }
        if (worst <= 0)
            return 1; /* in the core */
        if (worst > r)
            return 0; /* beyond a face plane pushed out by r */
        return sd_inside_gjk(s, verts, planes, dtris, p);
    }
    default:
        return 0; /* composites are never elements */
    }
}

/* ---- the voxel lattice (seed 004 §2.3, eqs. 7-8) ------------------------------ */

/* integer sums over cells (i, j, k) with weight c: sum c, sum c i_a,
 * sum c i_a i_b (xx, yy, zz, xy, yz, xz): exact in int64 for n <= 2000,
 * so the order of summation (threads) cannot change them */
typedef struct sd_isum {
    int64_t n, s[3], ss[6];
} sd_isum;

static void sd_isum_add(sd_isum *a, const sd_isum *b)
{
    a->n += b->n;
    for (int k = 0; k < 3; ++k)
        a->s[k] += b->s[k];
    for (int k = 0; k < 6; ++k)
        a->ss[k] += b->ss[k];
}

/* the cell-centre sums of eqs. 7-8 from the integer sums: X_a = lo_a +
 * h_a (i_a + 1/2); each cell adds its own second moment h_a^2 / 12 */
static sd_raw sd_isum_to_raw(const sd_isum *q, sd_vec3 lo, sd_vec3 h)
{
    const sd_real L[3] = {lo.x, lo.y, lo.z}, H[3] = {h.x, h.y, h.z};
    const sd_real N = (sd_real)q->n, cell = h.x * h.y * h.z;
    sd_real su[3], suu[3][3];
    for (int a = 0; a < 3; ++a)
        su[a] = (sd_real)q->s[a] + SD_R(0.5) * N;
    static const int ia[6] = {0, 1, 2, 0, 1, 0}, ib[6] = {0, 1, 2, 1, 2, 2};
    for (int k = 0; k < 6; ++k) {
        int a = ia[k], b = ib[k];
        sd_real v = (sd_real)q->ss[k] + SD_R(0.5) * ((sd_real)q->s[a] + (sd_real)q->s[b]) + SD_R(0.25) * N;
        suu[a][b] = suu[b][a] = v;
    }
    sd_raw r;
    r.v = N * cell;
    sd_real s[3];
    for (int a = 0; a < 3; ++a)
        s[a] = cell * (N * L[a] + H[a] * su[a]);
    r.s = sd_v3(s[0], s[1], s[2]);
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            sd_real t = N * L[a] * L[b] + L[a] * H[b] * su[b] + L[b] * H[a] * su[a] + H[a] * H[b] * suu[a][b];
            if (a == b)
                t += N * H[a] * H[a] / SD_R(12.0);
            r.t.m[a][b] = cell * t;
        }
    return r;
}

typedef struct sd_lat_elem {
    const sd_shape *s;
    sd_mat3 rt;      /* given frame -> element principal frame */
    sd_vec3 x;       /* m, element centre, given frame */
    sd_vec3 lo, hi;  /* m, its bounding box, given frame */
} sd_lat_elem;

/* the parts' boxes (exact: supports along ±x, ±y, ±z) and their union */
static void sd_lattice_prepare(const sd_composite_pools *pools, const sd_composite_part *parts, size_t n,
                               sd_lat_elem *le, sd_vec3 *lo, sd_vec3 *hi)
{
    for (size_t e = 0; e < n; ++e) {
        sd_convex c = sd_part_body(pools, &parts[e]);
        le[e].s = c.shape;
        le[e].rt = sd_mat3_transpose(sd_quat_to_mat3(parts[e].q));
        le[e].x = parts[e].x;
        le[e].lo = sd_v3(sd_convex_support(&c, sd_v3(-1, 0, 0)).x, sd_convex_support(&c, sd_v3(0, -1, 0)).y,
                         sd_convex_support(&c, sd_v3(0, 0, -1)).z);
        le[e].hi = sd_v3(sd_convex_support(&c, sd_v3(1, 0, 0)).x, sd_convex_support(&c, sd_v3(0, 1, 0)).y,
                         sd_convex_support(&c, sd_v3(0, 0, 1)).z);
        if (e == 0) {
            *lo = le[e].lo;
            *hi = le[e].hi;
        } else {
            *lo = sd_v3(sd_min(lo->x, le[e].lo.x), sd_min(lo->y, le[e].lo.y), sd_min(lo->z, le[e].lo.z));
            *hi = sd_v3(sd_max(hi->x, le[e].hi.x), sd_max(hi->y, le[e].hi.y), sd_max(hi->z, le[e].hi.z));
        }
    }
}

static void sd_isum_cell(sd_isum *q, int64_t c, int64_t i, int64_t j, int64_t k)
{
    q->n += c;
    q->s[0] += c * i;
    q->s[1] += c * j;
    q->s[2] += c * k;
    q->ss[0] += c * i * i;
    q->ss[1] += c * j * j;
    q->ss[2] += c * k * k;
    q->ss[3] += c * i * j;
    q->ss[4] += c * j * k;
    q->ss[5] += c * i * k;
}

/* The lattice over the box [lo, hi] (NULL: the parts' bounding box, else
 * only where parts overlap: the union of the boxes of overlapping pairs). */
static sd_status sd_lattice_run(const sd_composite_pools *pools, const sd_composite_part *parts, size_t n_parts,
                                int n, int threads, int overlap_box, sd_mass *union_mass, sd_mass *excess)
{
    if (n_parts == 0 || n_parts > SD_COMPOSITE_MAX_ELEMENTS || n < 1 || n > SD_COMPOSITE_LATTICE_MAX)
        return SD_ERR_INPUT;
    sd_lat_elem *le = sd_malloc(n_parts * sizeof *le);
    /* per x slab: union sums and excess sums, reduced in slab order */
    sd_isum *slab = sd_calloc((size_t)n * 2, sizeof *slab);
    if (!le || !slab) {
        sd_free(le);
        sd_free(slab);
        return SD_ERR_MEMORY;
    }
    sd_vec3 lo = sd_v3_zero(), hi = sd_v3_zero();
    sd_lattice_prepare(pools, parts, n_parts, le, &lo, &hi);
    if (overlap_box) {
        /* the doubly counted volume lies in the boxes of overlapping pairs:
         * a lattice there has n points across the overlaps, not the body */
        int any = 0;
        for (size_t a = 0; a < n_parts; ++a)
            for (size_t b = a + 1; b < n_parts; ++b) {
                sd_vec3 l = sd_v3_max(le[a].lo, le[b].lo), h = sd_v3_min(le[a].hi, le[b].hi);
                if (!(l.x < h.x && l.y < h.y && l.z < h.z) || !sd_composite_parts_overlap(pools, &parts[a], &parts[b]))
                    continue;
                lo = any ? sd_v3_min(lo, l) : l;
                hi = any ? sd_v3_max(hi, h) : h;
                any = 1;
            }
        if (!any) { /* nothing counted twice */
            sd_free(le);
            sd_free(slab);
            if (union_mass)
                memset(union_mass, 0, sizeof *union_mass);
            if (excess)
                memset(excess, 0, sizeof *excess);
            return SD_OK;
        }
    }
    const sd_vec3 h = sd_v3_scale(sd_v3_sub(hi, lo), SD_R(1.0) / (sd_real)n);
    const int np = (int)n_parts;
#ifdef _OPENMP
    if (threads <= 0)
        threads = omp_get_max_threads();
#endif
    /* slabs are independent; dynamic: slabs through the middle cost most */
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads > 0 ? threads : 1)
    for (int i = 0; i < n; ++i) {
        int act[SD_COMPOSITE_MAX_ELEMENTS], act2[SD_COMPOSITE_MAX_ELEMENTS];
        sd_isum *su = &slab[2 * i], *se = &slab[2 * i + 1];
        const sd_real X = lo.x + h.x * ((sd_real)i + SD_R(0.5));
        int na = 0;
        for (int e = 0; e < np; ++e)
            if (X >= le[e].lo.x && X <= le[e].hi.x)
                act[na++] = e;
        if (na == 0)
            continue;
        for (int j = 0; j < n; ++j) {
            const sd_real Y = lo.y + h.y * ((sd_real)j + SD_R(0.5));
            int nb = 0;
            for (int a = 0; a < na; ++a)
                if (Y >= le[act[a]].lo.y && Y <= le[act[a]].hi.y)
                    act2[nb++] = act[a];
            if (nb == 0)
                continue;
            for (int k = 0; k < n; ++k) {
                const sd_vec3 P = sd_v3(X, Y, lo.z + h.z * ((sd_real)k + SD_R(0.5)));
                int64_t cnt = 0;
                for (int b = 0; b < nb; ++b) {
                    const sd_lat_elem *E = &le[act2[b]];
                    if (P.z < E->lo.z || P.z > E->hi.z)
                        continue;
                    sd_vec3 pl = sd_mat3_mulv(E->rt, sd_v3_sub(P, E->x));
                    cnt += sd_composite_point_inside(E->s, pools->verts, pools->planes, pools->dtris, pl);
                }
                if (cnt >= 1)
                    sd_isum_cell(su, 1, i, j, k);
                if (cnt >= 2)
                    sd_isum_cell(se, cnt - 1, i, j, k);
            }
        }
    }
    sd_isum tu, te;
    memset(&tu, 0, sizeof tu);
    memset(&te, 0, sizeof te);
    for (int i = 0; i < n; ++i) {
        sd_isum_add(&tu, &slab[2 * i]);
        sd_isum_add(&te, &slab[2 * i + 1]);
    }
    sd_raw ru = sd_isum_to_raw(&tu, lo, h), re = sd_isum_to_raw(&te, lo, h);
    if (union_mass)
        *union_mass = sd_raw_to_mass(&ru);
    if (excess)
        *excess = sd_raw_to_mass(&re);
    sd_free(le);
    sd_free(slab);
    return SD_OK;
}

/* The doubly counted volume pair by pair: a point inside k >= 2 parts is
 * counted k - 1 times by a plain sum, once for each part b it lies in
 * that is not the lowest-indexed part containing it; so each overlapping
 * pair (a, b), a < b, counts over its own box (the intersection of the two
 * parts' boxes) the points inside a and b and inside no part c < a. Cells
 * of edge about h (each pair's box cut into whole cells per axis), so a
 * thin overlap (the ring's wedges) is resolved on its own scale instead of
 * the scale of the whole body. Pairs in index order, each lattice's slabs
 * summed in integers: the same bits for any thread count. SD_ERR_MEMORY
 * on allocation failure. */
static sd_status sd_lattice_pairs(const sd_composite_pools *pools, const sd_composite_part *parts, size_t n_parts,
                                  const uint8_t *ov, sd_real h, int threads, sd_raw *excess)
{
    *excess = sd_raw_zero();
    sd_lat_elem *le = sd_malloc(n_parts * sizeof *le);
    if (!le)
        return SD_ERR_MEMORY;
    sd_vec3 ulo, uhi;
    sd_lattice_prepare(pools, parts, n_parts, le, &ulo, &uhi);
#ifdef _OPENMP
    if (threads <= 0)
        threads = omp_get_max_threads();
#endif
    sd_status st = SD_OK;
    for (size_t a = 0; a < n_parts && st == SD_OK; ++a)
        for (size_t b = a + 1; b < n_parts && st == SD_OK; ++b) {
            if (!ov[a * n_parts + b])
                continue;
            sd_vec3 lo = sd_v3_max(le[a].lo, le[b].lo), hi = sd_v3_min(le[a].hi, le[b].hi);
            sd_vec3 ext = sd_v3_sub(hi, lo);
            const sd_real E[3] = {ext.x, ext.y, ext.z};
            int nc[3];
            for (int d = 0; d < 3; ++d) {
                sd_real c = (sd_real)ceil((double)(E[d] / h));
                nc[d] = c < SD_R(1.0) ? 1 : (c > (sd_real)SD_COMPOSITE_LATTICE_MAX ? SD_COMPOSITE_LATTICE_MAX : (int)c);
            }
            const sd_vec3 hc = sd_v3(E[0] / (sd_real)nc[0], E[1] / (sd_real)nc[1], E[2] / (sd_real)nc[2]);
            sd_isum *slab = sd_calloc((size_t)nc[0], sizeof *slab);
            if (!slab) {
                st = SD_ERR_MEMORY;
                break;
            }
            const sd_lat_elem *A = &le[a], *B = &le[b];
            const int ia = (int)a;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads > 0 ? threads : 1)
            for (int i = 0; i < nc[0]; ++i) {
                const sd_real X = lo.x + hc.x * ((sd_real)i + SD_R(0.5));
                for (int j = 0; j < nc[1]; ++j) {
                    const sd_real Y = lo.y + hc.y * ((sd_real)j + SD_R(0.5));
                    for (int k = 0; k < nc[2]; ++k) {
                        const sd_vec3 P = sd_v3(X, Y, lo.z + hc.z * ((sd_real)k + SD_R(0.5)));
                        if (!sd_composite_point_inside(A->s, pools->verts, pools->planes, pools->dtris,
                                                       sd_mat3_mulv(A->rt, sd_v3_sub(P, A->x))) ||
                            !sd_composite_point_inside(B->s, pools->verts, pools->planes, pools->dtris,
                                                       sd_mat3_mulv(B->rt, sd_v3_sub(P, B->x))))
                            continue;
                        int lower = 0;
                        for (int c = 0; c < ia && !lower; ++c) {
                            const sd_lat_elem *C = &le[c];
                            if (P.x < C->lo.x || P.x > C->hi.x || P.y < C->lo.y || P.y > C->hi.y || P.z < C->lo.z ||
                                P.z > C->hi.z)
                                continue;
                            lower = sd_composite_point_inside(C->s, pools->verts, pools->planes, pools->dtris,
                                                              sd_mat3_mulv(C->rt, sd_v3_sub(P, C->x)));
                        }
                        if (!lower)
                            sd_isum_cell(&slab[i], 1, i, j, k);
                    }
                }
            }
            sd_isum t;
            memset(&t, 0, sizeof t);
            for (int i = 0; i < nc[0]; ++i)
                sd_isum_add(&t, &slab[i]);
            sd_free(slab);
            sd_raw r = sd_isum_to_raw(&t, lo, hc);
            sd_raw_add(excess, SD_R(1.0), &r);
        }
    sd_free(le);
    return st;
}

sd_status sd_composite_lattice(const sd_composite_pools *pools, const sd_composite_part *parts, size_t n_parts,
                               int n, int threads, sd_mass *union_mass, sd_mass *excess)
{
    return sd_lattice_run(pools, parts, n_parts, n, threads, 0, union_mass, excess);
}

static sd_raw sd_raw_of_mass(const sd_mass *m)
{
    sd_raw r;
    const sd_real c[3] = {m->com.x, m->com.y, m->com.z};
    r.v = m->volume;
    r.s = sd_v3_scale(m->com, m->volume);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r.t.m[i][j] = m->second.m[i][j] + m->volume * c[i] * c[j];
    return r;
}

/* ---- the template ----------------------------------------------------------- */

sd_status sd_composite_make(const sd_composite_pools *pools, const sd_composite_part *parts_in, size_t n, int lattice,
                            int threads, sd_shape *out, sd_element *elems, sd_error *err)
{
    if (!pools || !out || !elems)
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "sd_composite_make: missing pools or output");
    if (!parts_in || n == 0)
        return SD_FAIL("elements", "a composite needs at least one element");
    if (n > SD_COMPOSITE_MAX_ELEMENTS)
        return SD_FAIL("elements", "a composite may have at most %d elements, got %zu", SD_COMPOSITE_MAX_ELEMENTS, n);
    if (lattice == 0)
        lattice = SD_COMPOSITE_LATTICE_DEFAULT;
    if (lattice < 4 || lattice > SD_COMPOSITE_LATTICE_MAX)
        return SD_FAIL("lattice", "expected 4 to %d lattice points per direction, got %d", SD_COMPOSITE_LATTICE_MAX,
                       lattice);
    sd_composite_part *parts = sd_malloc(n * sizeof *parts);
    if (!parts)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory building a composite");
    sd_status st = SD_OK;
    for (size_t e = 0; e < n && st == SD_OK; ++e) {
        parts[e] = parts_in[e];
        int k = parts[e].shape;
        if (k < 0 || (size_t)k >= pools->shape_count)
            st = SD_FAIL("elements", "element %zu: unknown shape index %d", e, k);
        else if (pools->shapes[k].kind == SD_SHAPE_COMPOSITE)
            st = SD_FAIL("elements", "element %zu: a composite cannot be an element (elements are convex)", e);
        else if (!isfinite(parts[e].x.x) || !isfinite(parts[e].x.y) || !isfinite(parts[e].x.z))
            st = SD_FAIL("elements", "element %zu: position is not finite", e);
        else if (!isfinite(parts[e].q.w) || !isfinite(parts[e].q.x) || !isfinite(parts[e].q.y) ||
                 !isfinite(parts[e].q.z))
            st = SD_FAIL("elements", "element %zu: orientation is not finite", e);
        else
            parts[e].q = sd_quat_normalize(parts[e].q); /* zero -> identity */
    }
    if (st != SD_OK) {
        sd_free(parts);
        return st;
    }

    /* exact sums of the elements, then the doubly counted volume off */
    sd_raw tot = sd_raw_zero();
    for (size_t e = 0; e < n; ++e) {
        sd_raw r = sd_raw_of_part(&pools->shapes[parts[e].shape], &parts[e]);
        sd_raw_add(&tot, SD_R(1.0), &r);
    }
    int overlap = 0;
    for (size_t a = 0; a < n && !overlap; ++a)
        for (size_t b = a + 1; b < n && !overlap; ++b)
            overlap = sd_composite_parts_overlap(pools, &parts[a], &parts[b]);
    memset(out, 0, sizeof *out);
    out->kind = SD_SHAPE_COMPOSITE;
    out->mass_lattice = 0;
    out->mass_error = 0;
    if (overlap) {
        /* Two ways to the doubly counted volume, the same budget of about
         * lattice^3 points: one lattice over the union of the overlapping
         * pairs' boxes (sd_lattice_run), or one per overlapping pair over
         * its own box (sd_lattice_pairs) with cells of the edge that
         * spends twice that budget over the sum of the pairs' boxes. The
         * pairs win when their boxes are small against the union's (thin
         * overlaps spread round a body: the ring's wedges); the finer of
         * the two cell edges decides. */
        uint8_t *ov = sd_calloc(n * n, 1);
        if (!ov) {
            sd_free(parts);
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory building a composite");
        }
        sd_lat_elem *le = sd_malloc(n * sizeof *le);
        sd_vec3 ulo = sd_v3_zero(), uhi = sd_v3_zero(), plo = sd_v3_zero(), phi = sd_v3_zero();
        sd_real sum_pairs = 0;
        int any = 0;
        if (le) {
            sd_lattice_prepare(pools, parts, n, le, &ulo, &uhi);
            for (size_t a = 0; a < n; ++a)
                for (size_t b = a + 1; b < n; ++b) {
                    sd_vec3 l = sd_v3_max(le[a].lo, le[b].lo), hh = sd_v3_min(le[a].hi, le[b].hi);
                    if (!(l.x < hh.x && l.y < hh.y && l.z < hh.z) ||
                        !sd_composite_parts_overlap(pools, &parts[a], &parts[b]))
                        continue;
                    ov[a * n + b] = 1;
                    sum_pairs += (hh.x - l.x) * (hh.y - l.y) * (hh.z - l.z);
                    plo = any ? sd_v3_min(plo, l) : l;
                    phi = any ? sd_v3_max(phi, hh) : hh;
                    any = 1;
                }
            sd_free(le);
        }
        sd_vec3 ue = sd_v3_sub(phi, plo);
        sd_real h_union = sd_max(ue.x, sd_max(ue.y, ue.z)) / (sd_real)lattice;
        sd_real h_pairs = (sd_real)cbrt((double)sum_pairs / (2.0 * (double)lattice * (double)lattice * (double)lattice));
        sd_raw rex = sd_raw_zero(), rex_half = sd_raw_zero();
        /* The sum minus the doubly counted volume is right when that excess
         * is a modest part of the sum; where points lie in many elements
         * (a chain of heavily overlapping spheres: each point in 20 of
         * them) the excess is most of the sum, and the lattice's relative
         * error on it comes back multiplied by sum / (sum - excess) (+15 %
         * at 180 spheres, a negative volume at 1,024). A coarse lattice
         * (32 points per direction) tells which; then the union itself is
         * integrated on the lattice over the whole body (seed 004 eqs.
         * 7-8), with an error relative to the union. */
        int direct = 0;
        if (le) {
            sd_mass coarse;
            st = sd_lattice_run(pools, parts, n, 32, threads, 0, &coarse, NULL);
            direct = st == SD_OK && coarse.volume < (SD_R(1.0) - SD_R(SD_COMPOSITE_EXCESS_MAX)) * tot.v;
        }
        if (!le || st != SD_OK) {
            st = le ? st : SD_ERR_MEMORY;
        } else if (direct) {
            sd_mass um, um_half;
            st = sd_lattice_run(pools, parts, n, lattice, threads, 0, &um, NULL);
            if (st == SD_OK)
                st = sd_lattice_run(pools, parts, n, lattice / 2, threads, 0, &um_half, NULL);
            if (st == SD_OK) {
                tot = sd_raw_of_mass(&um);
                out->mass_error = um.volume > 0 ? sd_fabs(um.volume - um_half.volume) / um.volume : SD_R(0.0);
            }
        } else if (any && h_pairs < h_union) {
            st = sd_lattice_pairs(pools, parts, n, ov, h_pairs, threads, &rex);
            if (st == SD_OK)
                st = sd_lattice_pairs(pools, parts, n, ov, SD_R(2.0) * h_pairs, threads, &rex_half);
        } else {
            sd_mass ex, ex_half;
            st = sd_lattice_run(pools, parts, n, lattice, threads, 1, NULL, &ex);
            if (st == SD_OK)
                st = sd_lattice_run(pools, parts, n, lattice / 2, threads, 1, NULL, &ex_half);
            rex = sd_raw_of_mass(&ex);
            rex_half = sd_raw_of_mass(&ex_half);
        }
        sd_free(ov);
        if (st != SD_OK) {
            sd_free(parts);
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory integrating a composite's lattice");
        }
        if (!direct) {
            sd_raw_add(&tot, SD_R(-1.0), &rex);
            out->mass_error = tot.v > 0 ? sd_fabs(rex.v - rex_half.v) / tot.v : SD_R(0.0);
        }
        out->mass_lattice = lattice;
    }
    sd_mass m = sd_raw_to_mass(&tot);
    /* inertia tensor about the centre of mass, I = tr(J) 1 - J, diagonalised */
    sd_mat3 I;
    sd_real tr = m.second.m[0][0] + m.second.m[1][1] + m.second.m[2][2];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            I.m[i][j] = (i == j ? tr : SD_R(0.0)) - m.second.m[i][j];
    sd_vec3 w;
    sd_mat3 V;
    sd_mat3_sym_eigen(I, &w, &V);
    if (!(m.volume > 0) || !(w.x > 0) || !(w.y > 0) || !(w.z > 0)) {
        sd_free(parts);
        return SD_FAIL("elements", "the composite has no volume or a non-positive principal moment "
                                   "(volume %g m^3, moments %g %g %g m^5)",
                       (double)m.volume, (double)w.x, (double)w.y, (double)w.z);
    }
    out->volume = m.volume;
    out->inertia = w;
    out->given_com = m.com;
    out->given_q = sd_quat_from_mat3(&V);
    out->estart = 0;
    out->ecount = (uint32_t)n;
    /* elements into the principal frame: x' = Vᵀ (x - c), q' = q_V* q */
    sd_quat qv_inv = sd_quat_conj(out->given_q);
    sd_real bound = 0, min_size = 0;
    for (size_t e = 0; e < n; ++e) {
        const sd_shape *s = &pools->shapes[parts[e].shape];
        elems[e].shape = parts[e].shape;
        elems[e].x = sd_mat3_tmulv(V, sd_v3_sub(parts[e].x, m.com));
        elems[e].q = sd_quat_normalize(sd_quat_mul(qv_inv, parts[e].q));
        elems[e].bound = s->bound;
        bound = sd_max(bound, sd_v3_norm(elems[e].x) + s->bound);
        min_size = e == 0 ? s->min_size : sd_min(min_size, s->min_size);
    }
    out->bound = bound;
    out->min_size = min_size;
    sd_free(parts);
    return SD_OK;
}
