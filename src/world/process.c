/* process.c — insertion and outlets of the cells solver (shapedem/process.h,
 * issue 16), run between steps.
 *
 * The step (the solver table's step entry) is cut into chunks that end at
 * the next event: an outlet check or an insertion time. Chunking does not
 * change the state (step.c: a run cut into calls of any length gives the
 * same bits), so a world with no insertion or outlet steps exactly as
 * before. At an event, the outlets remove first (world/remove.c), then
 * the insertions add.
 *
 * Insertion is random sequential addition with retries (seed 004 §4.1):
 * a candidate position is drawn in the region (the particle's bounding
 * sphere inside it, except across the seam of a periodic axis that the
 * region spans whole) and taken when that sphere overlaps no bounding
 * sphere present — every owned particle, whichever generator or
 * insertion made it, and their periodic images — else drawn again, up to
 * `attempts` times. Bounding spheres make the check exact for spheres and
 * conservative for shapes; the new particles' images go in too. A new
 * particle touches nothing, so its force
 * at this time is zero and the prepared state stays valid: the step goes
 * on without a new prepare (which would evaluate the pairs a second time
 * and advance their springs twice); the next step rebuilds the lists.
 *
 * A region may be the inside of a closed triangle mesh: positions are
 * drawn in its box until the winding number (the triangles' solid angles)
 * puts one inside, with the bounding sphere clear of every triangle; its
 * triangles live in w->region_meshes, outside sd_process (a checkpoint
 * dataset of plain bytes). A template entry with a size law is a few
 * scaled copies of the template (world/scaled.c), one per class of the
 * law (sd_size_classes), each class's radius that of its mean volume.
 *
 * Invariant: present = initial + inserted - removed after every event;
 * everything random comes from each insertion's own xoshiro stream seeded
 * from (simulation seed, insertion index), drawn in a fixed order, so the
 * particles inserted do not depend on the thread count (the check itself
 * is serial).
 */
#include "world/process.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "geom/solid_angle.h"
#include "world/mesh.h"
#include "world/remove.h"
#include "world/view.h"
#include "world/world.h"

#define SD_COOKIE_PROCESS 0x5D16

static const double sd_pi = 3.14159265358979323846;

sd_size_def sd_size_def_fixed(double radius)
{
    sd_size_def s;
    memset(&s, 0, sizeof s);
    s.kind = SD_SIZE_FIXED;
    s.a = radius;
    return s;
}

sd_insert_def sd_insert_def_default(void)
{
    sd_insert_def d;
    memset(&d, 0, sizeof d);
    d.random_orientation = 1;
    d.attempts = 100;
    d.cookie = SD_COOKIE_PROCESS;
    return d;
}

sd_region_outlet_def sd_region_outlet_def_default(void)
{
    sd_region_outlet_def d;
    memset(&d, 0, sizeof d);
    d.check_every = 1;
    d.cookie = SD_COOKIE_PROCESS;
    return d;
}

static sd_process *sd_process_of(sd_world *w, sd_error *err)
{
    if (!w->process) {
        w->process = sd_calloc(1, sizeof *w->process);
        if (!w->process)
            sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    }
    return w->process;
}

void sd_world_process_free(sd_world *w)
{
    sd_free(w->process);
    w->process = NULL;
    if (w->region_meshes)
        for (int k = 0; k < SD_INSERTIONS_MAX; ++k)
            sd_free(w->region_meshes->slot[k].tri);
    sd_free(w->region_meshes);
    w->region_meshes = NULL;
}

/* ---- regions ------------------------------------------------------------ */

static sd_v3d sd_d3(double x, double y, double z)
{
    sd_v3d v = {x, y, z};
    return v;
}

static double sd_d3_dot(sd_v3d a, sd_v3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

static sd_v3d sd_d3_unit(sd_v3d a)
{
    double n = sqrt(sd_d3_dot(a, a));
    return sd_d3(a.x / n, a.y / n, a.z / n);
}

/* Two unit vectors e1, e2 with (e1, e2, a) right-handed and orthonormal. */
static void sd_region_basis(sd_v3d a, sd_v3d *e1, sd_v3d *e2)
{
    sd_v3d t = fabs(a.x) < 0.9 ? sd_d3(1, 0, 0) : sd_d3(0, 1, 0);
    double d = sd_d3_dot(t, a);
    *e1 = sd_d3_unit(sd_d3(t.x - d * a.x, t.y - d * a.y, t.z - d * a.z));
    *e2 = sd_d3(a.y * e1->z - a.z * e1->y, a.z * e1->x - a.x * e1->z, a.x * e1->y - a.y * e1->x);
}

/* ---- mesh regions --------------------------------------------------------- */

static int sd_edge_cmp(const void *a, const void *b)
{
    const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

typedef struct sd_vkey {
    double x, y, z;
    uint32_t i;
} sd_vkey;

static int sd_vkey_cmp(const void *a, const void *b)
{
    const sd_vkey *p = a, *q = b;
    if (p->x != q->x)
        return p->x < q->x ? -1 : 1;
    if (p->y != q->y)
        return p->y < q->y ? -1 : 1;
    if (p->z != q->z)
        return p->z < q->z ? -1 : 1;
    return (p->i > q->i) - (p->i < q->i);
}

/* A mesh region is a closed surface: indices in range, finite corners,
 * every edge in exactly two triangles, and a volume (divergence theorem,
 * either winding). */
static sd_status sd_region_mesh_check(const sd_region_def *r, const char *key, sd_error *err)
{
    size_t nt = r->triangle_count, nv = r->vertex_count;
    if (!r->vertices || !r->triangles || nt < 4 || nv < 4)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "a mesh region needs a closed mesh (at least 4 "
                            "triangles), got %zu triangles", nt);
    for (size_t v = 0; v < nv; ++v)
        if (!isfinite(r->vertices[v].x) || !isfinite(r->vertices[v].y) || !isfinite(r->vertices[v].z))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "mesh region: vertex %zu is not finite", v);
    /* vertices at the same point are one (an STL file repeats them per facet) */
    uint64_t *e = sd_malloc(3 * nt * sizeof *e);
    uint32_t *same = sd_malloc(nv * sizeof *same);
    sd_vkey *vk = sd_malloc(nv * sizeof *vk);
    if (!e || !same || !vk) {
        sd_free(e);
        sd_free(same);
        sd_free(vk);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, key, "out of memory (mesh region)");
    }
    for (size_t v = 0; v < nv; ++v)
        vk[v] = (sd_vkey){r->vertices[v].x, r->vertices[v].y, r->vertices[v].z, (uint32_t)v};
    qsort(vk, nv, sizeof *vk, sd_vkey_cmp);
    for (size_t v = 0, first = 0; v < nv; ++v) {
        if (v == 0 || vk[v].x != vk[first].x || vk[v].y != vk[first].y || vk[v].z != vk[first].z)
            first = v;
        same[vk[v].i] = vk[first].i;
    }
    sd_free(vk);
    double vol = 0;
    for (size_t t = 0; t < nt; ++t) {
        const uint32_t *c = r->triangles[t];
        if (c[0] >= nv || c[1] >= nv || c[2] >= nv) {
            sd_free(e);
            sd_free(same);
            return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "mesh region: triangle %zu has a vertex index past "
                                "the %zu vertices", t, nv);
        }
        for (int k = 0; k < 3; ++k) {
            uint64_t a = same[c[k]], b = same[c[(k + 1) % 3]];
            e[3 * t + k] = a < b ? (a << 32) | b : (b << 32) | a;
        }
        sd_v3d p = r->vertices[c[0]], q = r->vertices[c[1]], s = r->vertices[c[2]];
        vol += (p.x * (q.y * s.z - q.z * s.y) - p.y * (q.x * s.z - q.z * s.x) + p.z * (q.x * s.y - q.y * s.x)) / 6;
    }
    sd_free(same);
    qsort(e, 3 * nt, sizeof *e, sd_edge_cmp);
    size_t bad = 0;
    for (size_t i = 0; i < 3 * nt;) {
        size_t j = i;
        while (j < 3 * nt && e[j] == e[i])
            ++j;
        bad += j - i != 2;
        i = j;
    }
    sd_free(e);
    if (bad)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "a mesh region must be closed: %zu edges are not shared "
                            "by exactly two triangles", bad);
    if (!(fabs(vol) > 0))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "a mesh region encloses no volume");
    return SD_OK;
}

/* Copies the mesh into its slot (corners per triangle) with its box. */
static sd_status sd_region_mesh_store(sd_world *w, int slot, const sd_region_def *r, sd_error *err)
{
    if (!w->region_meshes) {
        w->region_meshes = sd_calloc(1, sizeof *w->region_meshes);
        if (!w->region_meshes)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "insert.region", "out of memory (mesh region)");
    }
    sd_region_mesh *m = &w->region_meshes->slot[slot];
    sd_free(m->tri);
    m->tri = sd_malloc(r->triangle_count * sizeof *m->tri);
    if (!m->tri)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "insert.region", "out of memory (mesh region)");
    m->count = r->triangle_count;
    for (int a = 0; a < 3; ++a)
        m->lo[a] = HUGE_VAL, m->hi[a] = -HUGE_VAL;
    for (size_t t = 0; t < m->count; ++t)
        for (int k = 0; k < 3; ++k) {
            sd_v3d v = r->vertices[r->triangles[t][k]];
            const double x[3] = {v.x, v.y, v.z};
            for (int a = 0; a < 3; ++a) {
                m->tri[t][3 * k + a] = x[a];
                m->lo[a] = fmin(m->lo[a], x[a]);
                m->hi[a] = fmax(m->hi[a], x[a]);
            }
        }
    return SD_OK;
}

/* Winding number of the closed mesh about p (geom/solid_angle.h): about
 * +-1 inside, 0 outside. */
static double sd_region_mesh_winding(const sd_region_mesh *m, const double p[3])
{
    double sum = 0;
    for (size_t t = 0; t < m->count; ++t) {
        const double *c = m->tri[t];
        double a[3], b[3], d[3];
        for (int k = 0; k < 3; ++k) {
            a[k] = c[k] - p[k];
            b[k] = c[3 + k] - p[k];
            d[k] = c[6 + k] - p[k];
        }
        sum += sd_solid_angle(a, b, d);
    }
    return sum / (4 * sd_pi);
}

/* Squared distance from p to triangle c (its closest point by regions:
 * a vertex, an edge or the face; Ericson, Real-Time Collision Detection 5.1.5). */
static double sd_tri_dist2(const double *c, const double p[3])
{
    double ab[3], ac[3], ap[3], q[3];
    for (int k = 0; k < 3; ++k) {
        ab[k] = c[3 + k] - c[k];
        ac[k] = c[6 + k] - c[k];
        ap[k] = p[k] - c[k];
    }
#define SD_DOT(u, v) ((u)[0] * (v)[0] + (u)[1] * (v)[1] + (u)[2] * (v)[2])
    double d1 = SD_DOT(ab, ap), d2 = SD_DOT(ac, ap), s = 0, t = 0;
    if (d1 <= 0 && d2 <= 0) {
        s = t = 0;
    } else {
        double bp[3], cp[3];
        for (int k = 0; k < 3; ++k) {
            bp[k] = p[k] - c[3 + k];
            cp[k] = p[k] - c[6 + k];
        }
        double d3 = SD_DOT(ab, bp), d4 = SD_DOT(ac, bp), d5 = SD_DOT(ab, cp), d6 = SD_DOT(ac, cp);
        double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
        if (d3 >= 0 && d4 <= d3)
            s = 1, t = 0;
        else if (vc <= 0 && d1 >= 0 && d3 <= 0)
            s = d1 / (d1 - d3), t = 0;
        else if (d6 >= 0 && d5 <= d6)
            s = 0, t = 1;
        else if (vb <= 0 && d2 >= 0 && d6 <= 0)
            s = 0, t = d2 / (d2 - d6);
        else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
            double u = (d4 - d3) / ((d4 - d3) + (d5 - d6));
            s = 1 - u, t = u;
        } else {
            double den = 1 / (va + vb + vc);
            s = vb * den, t = vc * den;
        }
    }
#undef SD_DOT
    for (int k = 0; k < 3; ++k)
        q[k] = c[k] + s * ab[k] + t * ac[k] - p[k];
    return q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
}

/* 1 when a sphere of radius b at p lies inside the closed mesh. */
static int sd_region_mesh_holds(const sd_region_mesh *m, const double p[3], double b)
{
    if (fabs(sd_region_mesh_winding(m, p)) < 0.5)
        return 0;
    for (size_t t = 0; t < m->count; ++t)
        if (sd_tri_dist2(m->tri[t], p) < b * b)
            return 0;
    return 1;
}

static sd_status sd_region_check(const sd_world *w, const sd_region_def *r, const char *key, int outlet,
                                 sd_error *err)
{
    int dim2 = w->def.dimension == 2;
    switch (r->kind) {
    case SD_REGION_BOX:
        if (!(r->hi.x > r->lo.x && r->hi.y > r->lo.y && (dim2 || r->hi.z > r->lo.z)))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "a box region needs max > min on every axis");
        break;
    case SD_REGION_CYLINDER:
    case SD_REGION_DISC:
        if (!(sd_d3_dot(r->axis, r->axis) > 0) || !(r->radius > 0) ||
            (r->kind == SD_REGION_CYLINDER && !(r->length > 0)))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, key,
                                "a %s region needs an axis, a radius > 0%s", r->kind == SD_REGION_DISC ? "disc"
                                                                                                    : "cylinder",
                                r->kind == SD_REGION_CYLINDER ? " and a length > 0" : "");
        if (r->kind == SD_REGION_DISC && outlet)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "an outlet is a box or a cylinder (a disc holds no "
                                                               "centres but those on it)");
        break;
    case SD_REGION_MESH:
        if (outlet)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "an outlet is a box or a cylinder");
        if (dim2)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "dimension 2: a mesh region is 3D only");
        return sd_region_mesh_check(r, key, err);
    default:
        return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "expected a box, cylinder or disc region");
    }
    return SD_OK;
}

/* The region's bounding box. */
static void sd_region_bbox(const sd_region_def *r, double lo[3], double hi[3])
{
    if (r->kind == SD_REGION_BOX || r->kind == SD_REGION_MESH) { /* a mesh keeps its box in lo, hi */
        lo[0] = r->lo.x, lo[1] = r->lo.y, lo[2] = r->lo.z;
        hi[0] = r->hi.x, hi[1] = r->hi.y, hi[2] = r->hi.z;
        return;
    }
    sd_v3d a = sd_d3_unit(r->axis);
    double ac[3] = {a.x, a.y, a.z}, c[3] = {r->center.x, r->center.y, r->center.z};
    double half = r->kind == SD_REGION_CYLINDER ? 0.5 * r->length : 0.0;
    for (int k = 0; k < 3; ++k) {
        double e = fabs(ac[k]) * half + r->radius * sqrt(fmax(0.0, 1.0 - ac[k] * ac[k]));
        lo[k] = c[k] - e;
        hi[k] = c[k] + e;
    }
}

size_t sd_world_insertion_bounds(const sd_world *w, double lo[3], double hi[3])
{
    for (int a = 0; a < 3; ++a)
        lo[a] = (double)INFINITY, hi[a] = -(double)INFINITY;
    size_t n = w->process ? w->process->insertion_count : 0;
    for (size_t k = 0; k < n; ++k) {
        double l[3], h[3];
        sd_region_bbox(&w->process->insertions[k].def.region, l, h);
        for (int a = 0; a < 3; ++a)
            lo[a] = fmin(lo[a], l[a]), hi[a] = fmax(hi[a], h[a]);
    }
    return n;
}

/* 1 when the point x lies in the region (outlets: the particle's centre). */
static int sd_region_contains(const sd_region_def *r, sd_v3d x)
{
    if (r->kind == SD_REGION_BOX)
        return x.x >= r->lo.x && x.x <= r->hi.x && x.y >= r->lo.y && x.y <= r->hi.y && x.z >= r->lo.z &&
               x.z <= r->hi.z;
    sd_v3d a = sd_d3_unit(r->axis);
    sd_v3d d = sd_d3(x.x - r->center.x, x.y - r->center.y, x.z - r->center.z);
    double s = sd_d3_dot(d, a);
    double q2 = sd_d3_dot(d, d) - s * s;
    return fabs(s) <= 0.5 * r->length && q2 <= r->radius * r->radius;
}

/* The axes on which a box region wraps: periodic, and the box spans the
 * whole period there. On such an axis a particle may straddle the seam
 * (its images on the other side are in the placing grid), so a centre is
 * drawn over the whole period; elsewhere the bounding sphere stays inside
 * the region. Without this a strip of one bounding radius each side of
 * the seam started empty. */
typedef struct sd_region_wrap {
    unsigned axes;        /* bit a: axis a wraps */
    double lo[3], hi[3];  /* m, the periodic box */
} sd_region_wrap;

static sd_region_wrap sd_region_wraps(const sd_world *w, const sd_region_def *r)
{
    sd_region_wrap wr;
    memset(&wr, 0, sizeof wr);
    if (r->kind != SD_REGION_BOX)
        return wr;
    const double dl[3] = {w->def.domain_lo.x, w->def.domain_lo.y, w->def.domain_lo.z};
    const double dh[3] = {w->def.domain_hi.x, w->def.domain_hi.y, w->def.domain_hi.z};
    const double rl[3] = {r->lo.x, r->lo.y, r->lo.z}, rh[3] = {r->hi.x, r->hi.y, r->hi.z};
    for (int a = 0; a < 3; ++a) {
        wr.lo[a] = dl[a];
        wr.hi[a] = dh[a];
        if (((w->def.periodic >> a) & 1u) && rl[a] <= dl[a] && rh[a] >= dh[a])
            wr.axes |= 1u << a;
    }
    return wr;
}

/* A uniform random centre for a bounding radius b in the region, the
 * sphere inside it (but across the seam of a wrapping axis, wr); 0 when
 * it cannot fit. Always the same number of draws per call for a region
 * kind (three), so the stream does not depend on the sizes. 2D: z = 0. A
 * mesh region (m) draws points in its box, three draws each, until one
 * holds the sphere, at most 64: 2 when none did (the attempt failed, as a
 * taken spot does). */
static int sd_region_draw(const sd_region_def *r, const sd_region_mesh *m, const sd_region_wrap *wr, double b,
                          int dim2, sd_rng *rng, sd_v3d *out)
{
    if (r->kind == SD_REGION_MESH) {
        if (!m || m->hi[0] - m->lo[0] < 2 * b || m->hi[1] - m->lo[1] < 2 * b || m->hi[2] - m->lo[2] < 2 * b)
            return 0;
        for (int k = 0; k < 64; ++k) {
            double p[3];
            for (int a = 0; a < 3; ++a)
                p[a] = m->lo[a] + b + sd_rng_uniform(rng) * (m->hi[a] - m->lo[a] - 2 * b);
            if (sd_region_mesh_holds(m, p, b)) {
                *out = sd_d3(p[0], p[1], p[2]);
                return 1;
            }
        }
        return 2;
    }
    double u1 = sd_rng_uniform(rng), u2 = sd_rng_uniform(rng), u3 = sd_rng_uniform(rng);
    if (r->kind == SD_REGION_BOX) {
        double ex = r->hi.x - r->lo.x - 2 * b, ey = r->hi.y - r->lo.y - 2 * b, ez = r->hi.z - r->lo.z - 2 * b;
        if (ex < 0 || ey < 0 || (!dim2 && ez < 0))
            return 0;
        *out = sd_d3(r->lo.x + b + u1 * ex, r->lo.y + b + u2 * ey, dim2 ? 0.0 : r->lo.z + b + u3 * ez);
        /* a wrapping axis: anywhere in [lo, hi) of the period */
        const double u[3] = {u1, u2, u3};
        double *o[3] = {&out->x, &out->y, &out->z};
        for (int a = 0; a < 3; ++a)
            if ((wr->axes >> a) & 1u) {
                double c = wr->lo[a] + u[a] * (wr->hi[a] - wr->lo[a]);
                *o[a] = c < wr->hi[a] ? c : wr->lo[a];
            }
        return 1;
    }
    double rr = r->radius - b;
    double half = r->kind == SD_REGION_CYLINDER ? 0.5 * r->length - b : 0.0;
    if (rr < 0 || half < 0)
        return 0;
    sd_v3d a = sd_d3_unit(r->axis), e1, e2;
    sd_region_basis(a, &e1, &e2);
    double rad = rr * sqrt(u1), ang = 2 * sd_pi * u2, s = (2 * u3 - 1) * half;
    double c1 = rad * cos(ang), c2 = rad * sin(ang);
    *out = sd_d3(r->center.x + c1 * e1.x + c2 * e2.x + s * a.x, r->center.y + c1 * e1.y + c2 * e2.y + s * a.y,
                 r->center.z + c1 * e1.z + c2 * e2.z + s * a.z);
    if (dim2)
        out->z = 0.0;
    return 1;
}

/* ---- size distributions -------------------------------------------------- */

static double sd_normal_draw(sd_rng *rng)
{
    /* Box-Muller, one of the pair (two draws per value, always) */
    double u1 = sd_rng_uniform(rng), u2 = sd_rng_uniform(rng);
    return sqrt(-2.0 * log(1.0 - u1)) * cos(2 * sd_pi * u2);
}

static double sd_size_hi(const sd_size_def *s) { return s->max > 0 ? s->max : HUGE_VAL; }

static sd_status sd_size_check(const sd_size_def *s, const char *key, sd_error *err)
{
    switch (s->kind) {
    case SD_SIZE_FIXED:
        if (!(s->a > 0))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "expected a radius > 0, got %g (a negative or zero "
                                "radius)", s->a);
        break;
    case SD_SIZE_UNIFORM:
        if (!(s->a > 0) || !(s->b >= s->a))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "expected radii 0 < min <= max, got [%g, %g]%s", s->a,
                                s->b, s->a <= 0 ? " (a negative or zero radius)" : "");
        break;
    case SD_SIZE_NORMAL:
    case SD_SIZE_LOGNORMAL:
        if (!(s->a > 0) || !(s->b >= 0) || s->min < 0 || s->max < 0 || (s->max > 0 && !(s->max > s->min)))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, key,
                                "expected a %s > 0, a spread >= 0 and truncation 0 <= min < max, got %g, %g, [%g, %g]%s",
                                s->kind == SD_SIZE_NORMAL ? "mean radius" : "median radius", s->a, s->b, s->min,
                                s->max, (s->a <= 0 || s->min < 0) ? " (a negative radius)" : "");
        if (s->b > 0) {
            /* the largest size the law draws (8 standard deviations, or its
             * max): finite and within SD_SIZE_SPREAD_MAX of the median, or
             * placement works with cells of an absurd (or infinite) size */
            double big = s->kind == SD_SIZE_NORMAL ? s->a + 8 * s->b : s->a * exp(8 * s->b);
            if (s->max > 0)
                big = fmin(big, s->max);
            if (!isfinite(big) || big > SD_SIZE_SPREAD_MAX * s->a)
                return sd_error_set(err, SD_ERR_INPUT, "", 0, key,
                                    "the %s law of %s %g, %s %g draws radii up to %.3g m, %.3g times its %s (at most "
                                    "%g): give a smaller spread or a truncation max",
                                    s->kind == SD_SIZE_NORMAL ? "normal" : "lognormal",
                                    s->kind == SD_SIZE_NORMAL ? "mean" : "median", s->a,
                                    s->kind == SD_SIZE_NORMAL ? "std" : "sigma", s->b, big, big / s->a,
                                    s->kind == SD_SIZE_NORMAL ? "mean" : "median", SD_SIZE_SPREAD_MAX);
        }
        if (s->kind == SD_SIZE_NORMAL && s->b > 0) {
            /* the truncated range must hold some of the law (redraws end) */
            double lo = fmax(s->min, 0.0), hi = sd_size_hi(s);
            double plo = 0.5 * erfc(-(lo - s->a) / (s->b * sqrt(2.0)));
            double phi = 0.5 * erfc(-(hi - s->a) / (s->b * sqrt(2.0)));
            if (!(phi - plo > 1e-3))
                return sd_error_set(err, SD_ERR_INPUT, "", 0, key,
                                    "the truncation [%g, %g] holds less than 0.1 %% of the normal law", lo, hi);
        }
        break;
    case SD_SIZE_TABLE: {
        if (s->classes < 1 || s->classes > SD_SIZE_CLASSES_MAX)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "expected 1 to %d size classes, got %d",
                                SD_SIZE_CLASSES_MAX, s->classes);
        double sum = 0;
        for (int c = 0; c < s->classes; ++c) {
            if (!(s->lo[c] > 0) || !(s->hi[c] >= s->lo[c]))
                return sd_error_set(err, SD_ERR_INPUT, "", 0, key,
                                    "size class %d: expected radii 0 < lo <= hi, got [%g, %g]%s", c, s->lo[c],
                                    s->hi[c], s->lo[c] <= 0 ? " (a negative or zero radius)" : "");
            if (!(s->fraction[c] >= 0))
                return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "size class %d: expected a fraction >= 0, got %g",
                                    c, s->fraction[c]);
            sum += s->fraction[c];
        }
        if (!(fabs(sum - 1.0) <= 1e-6))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "the size classes' fractions sum to %.9g, not 1",
                                sum);
        break;
    }
    default:
        return sd_error_set(err, SD_ERR_INPUT, "", 0, key, "unknown size distribution %d", s->kind);
    }
    return SD_OK;
}

/* E[r^d] of the distribution (d = 3: volume; 2 in the planar mode), by
 * midpoint quadrature of the density for the normal laws. */
double sd_size_moment(const sd_size_def *s, int d)
{
    switch (s->kind) {
    case SD_SIZE_FIXED: return pow(s->a, d);
    case SD_SIZE_UNIFORM:
        return s->b > s->a ? (pow(s->b, d + 1) - pow(s->a, d + 1)) / ((d + 1) * (s->b - s->a)) : pow(s->a, d);
    case SD_SIZE_TABLE: {
        double sum = 0, norm = 0;
        for (int c = 0; c < s->classes; ++c) {
            sd_size_def u = sd_size_def_fixed(s->lo[c]);
            u.kind = SD_SIZE_UNIFORM;
            u.b = s->hi[c];
            /* number fractions (the mass fractions turned to numbers) */
            double m = sd_size_moment(&u, d), f = s->by_mass ? s->fraction[c] / m : s->fraction[c];
            sum += f * m;
            norm += f;
        }
        return sum / norm;
    }
    default: {
        if (!(s->b > 0))
            return pow(s->a, d);
        int ln = s->kind == SD_SIZE_LOGNORMAL;
        double mu = ln ? log(s->a) : s->a, sg = s->b;
        double lo = mu - 8 * sg, hi = mu + 8 * sg;
        double tlo = fmax(s->min, 0.0), thi = sd_size_hi(s);
        if (ln) {
            lo = fmax(lo, tlo > 0 ? log(tlo) : lo);
            hi = fmin(hi, isfinite(thi) ? log(thi) : hi);
        } else {
            lo = fmax(lo, tlo);
            hi = fmin(hi, thi);
        }
        const int n = 4000;
        double sum = 0, norm = 0, h = (hi - lo) / n;
        for (int k = 0; k < n; ++k) {
            double y = lo + (k + 0.5) * h, z = (y - mu) / sg, pdf = exp(-0.5 * z * z);
            double r = ln ? exp(y) : y;
            sum += pdf * pow(r, d);
            norm += pdf;
        }
        return sum / norm;
    }
    }
}

static double sd_size_draw(const sd_insertion *ins, int e, sd_rng *rng)
{
    const sd_size_def *s = &ins->def.entries[e].size;
    switch (s->kind) {
    case SD_SIZE_FIXED: (void)sd_rng_uniform(rng); return s->a;
    case SD_SIZE_UNIFORM: return sd_rng_range(rng, s->a, s->b);
    case SD_SIZE_TABLE: {
        double u = sd_rng_uniform(rng);
        int c = 0;
        while (c + 1 < s->classes && u >= ins->class_cum[e][c])
            ++c;
        return sd_rng_range(rng, s->lo[c], s->hi[c]);
    }
    default: {
        double lo = fmax(s->min, 0.0), hi = sd_size_hi(s);
        for (int k = 0; k < 100000; ++k) {
            double z = sd_normal_draw(rng);
            double r = s->kind == SD_SIZE_LOGNORMAL ? s->a * exp(s->b * z) : s->a + s->b * z;
            if (r > 0 && r >= lo && r <= hi && isfinite(r))
                return r;
        }
        return s->a; /* unreachable for a range that holds 0.1 % of the law (sd_size_check) */
    }
    }
}

/* The classes of a template entry's size law (sd_insert_entry.size_classes):
 * their probabilities p (by number) and radii rep, (E[r^d | class])^(1/d)
 * so that the mean volume (d = 3; the area, d = 2, in the planar mode) is
 * the law's. A continuous law is cut into k classes of equal probability
 * on a fine grid of its density (midpoints, each cell's weight split at the
 * class edges); a sieve table (number fractions f) cuts each class into
 * k / classes of equal width, the radius uniform in each. Returns how many. */
static int sd_size_classes(const sd_size_def *s, int k, int d, const double *f, double *p, double *rep)
{
    if (s->kind == SD_SIZE_FIXED || (s->kind == SD_SIZE_UNIFORM && !(s->b > s->a)) ||
        ((s->kind == SD_SIZE_NORMAL || s->kind == SD_SIZE_LOGNORMAL) && !(s->b > 0))) {
        p[0] = 1.0;
        rep[0] = s->a;
        return 1;
    }
    if (s->kind == SD_SIZE_TABLE) {
        int m = k / s->classes > 1 ? k / s->classes : 1, n = 0;
        for (int c = 0; c < s->classes && n + m <= SD_SIZE_SCALES_MAX; ++c)
            for (int j = 0; j < m; ++j) {
                double h = (s->hi[c] - s->lo[c]) / m, lo = s->lo[c] + j * h, hi = lo + h;
                /* E[r^d] of r uniform in [lo, hi] */
                double md = h > 0 ? (pow(hi, d + 1) - pow(lo, d + 1)) / ((d + 1) * h) : pow(lo, d);
                p[n] = f[c] / m;
                rep[n++] = pow(md, 1.0 / d);
            }
        return n;
    }
    /* the density on a grid of y (r, or ln r for the log-normal law) */
    int ln = s->kind == SD_SIZE_LOGNORMAL;
    double lo, hi, mu = ln ? log(s->a) : s->a, sg = s->b;
    if (s->kind == SD_SIZE_UNIFORM) {
        lo = s->a;
        hi = s->b;
    } else {
        double tlo = fmax(s->min, 0.0), thi = sd_size_hi(s);
        lo = mu - 8 * sg;
        hi = mu + 8 * sg;
        if (ln) {
            lo = tlo > 0 ? fmax(lo, log(tlo)) : lo;
            hi = isfinite(thi) ? fmin(hi, log(thi)) : hi;
        } else {
            lo = fmax(lo, tlo);
            hi = fmin(hi, thi);
        }
    }
    enum { cells = 1 << 14 };
    double h = (hi - lo) / cells, total = 0;
    for (int c = 0; c < cells; ++c) {
        double z = (lo + (c + 0.5) * h - mu) / (sg > 0 ? sg : 1);
        total += s->kind == SD_SIZE_UNIFORM ? 1.0 : exp(-0.5 * z * z);
    }
    double acc_p[SD_SIZE_SCALES_MAX] = {0}, acc_m[SD_SIZE_SCALES_MAX] = {0};
    double need = total / k;
    int b = 0;
    for (int c = 0; c < cells; ++c) {
        double y = lo + (c + 0.5) * h, z = (y - mu) / (sg > 0 ? sg : 1);
        double wgt = s->kind == SD_SIZE_UNIFORM ? 1.0 : exp(-0.5 * z * z);
        double rd = pow(ln ? exp(y) : y, d);
        while (wgt > 0) {
            double take = b == k - 1 ? wgt : fmin(wgt, need);
            acc_p[b] += take;
            acc_m[b] += take * rd;
            wgt -= take;
            need -= take;
            if (need <= 0 && b < k - 1) {
                ++b;
                need = total / k;
            }
        }
    }
    for (int c = 0; c < k; ++c) {
        p[c] = acc_p[c] / total;
        rep[c] = pow(acc_m[c] / acc_p[c], 1.0 / d);
    }
    return k;
}

/* A template entry takes a size law unless its size is all zero. */
static int sd_entry_scaled(const sd_insert_entry *en)
{
    return en->shape >= 0 && !(en->size.kind == SD_SIZE_FIXED && en->size.a == 0);
}

/* ---- adding an insertion -------------------------------------------------- */

static double sd_material_density(const sd_world *w, int m) { return w->materials[m].def.density; }

int sd_world_add_insertion(sd_world *w, const sd_insert_def *d, sd_error *err)
{
    if (!w) {
        sd_error_null(err, "sd_world_add_insertion", "world");
        return -1;
    }
    if (!d || d->cookie != SD_COOKIE_PROCESS) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "insert", "insertion def not made by sd_insert_def_default");
        return -1;
    }
    if (w->solver != &sd_solver_cells) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "insert",
                     "insertion runs on the cells solver; the grid solver pours with its pour section");
        return -1;
    }
    if (sd_region_check(w, &d->region, "insert.region", 0, err) != SD_OK)
        return -1;
    if (d->entry_count < 1 || d->entry_count > SD_INSERT_MIX_MAX) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "insert.mix", "expected 1 to %d entries in the mix, got %d",
                     SD_INSERT_MIX_MAX, d->entry_count);
        return -1;
    }
    if (!(d->count > 0 || d->mass > 0) || d->mass < 0 || d->rate < 0 || d->mass_rate < 0 ||
        (d->rate > 0 && d->mass_rate > 0) || !(d->start >= 0) || d->attempts < 1 ||
        d->attempts > SD_INSERT_ATTEMPTS_MAX || !(d->velocity_jitter >= 0)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "insert",
                     "an insertion needs a count or a mass > 0, at most one of rate and mass_rate (>= 0), a start "
                     ">= 0 s, attempts in 1..%d and a velocity jitter >= 0", SD_INSERT_ATTEMPTS_MAX);
        return -1;
    }
    /* a mesh region: its box in lo, hi (the box checks below read them) */
    sd_region_def reg = d->region;
    if (reg.kind == SD_REGION_MESH) {
        reg.lo = reg.hi = reg.vertices[0];
        for (size_t v = 1; v < reg.vertex_count; ++v) {
            sd_v3d x = reg.vertices[v];
            reg.lo = sd_d3(fmin(reg.lo.x, x.x), fmin(reg.lo.y, x.y), fmin(reg.lo.z, x.z));
            reg.hi = sd_d3(fmax(reg.hi.x, x.x), fmax(reg.hi.y, x.y), fmax(reg.hi.z, x.z));
        }
    }
    /* the region must lie inside the domain where one is given */
    int has_domain = w->def.domain_hi.x > w->def.domain_lo.x || w->def.domain_hi.y > w->def.domain_lo.y ||
                     w->def.domain_hi.z > w->def.domain_lo.z;
    if (has_domain) {
        double lo[3], hi[3];
        sd_region_bbox(&reg, lo, hi);
        const double dl[3] = {w->def.domain_lo.x, w->def.domain_lo.y, w->def.domain_lo.z};
        const double dh[3] = {w->def.domain_hi.x, w->def.domain_hi.y, w->def.domain_hi.z};
        for (int a = 0; a < (w->def.dimension == 2 ? 2 : 3); ++a)
            if (dh[a] > dl[a] && (lo[a] < dl[a] || hi[a] > dh[a])) {
                sd_error_set(err, SD_ERR_INPUT, "", 0, "insert.region",
                             "the insertion region [%g, %g] on %c lies outside the domain [%g, %g]", lo[a], hi[a],
                             'x' + a, dl[a], dh[a]);
                return -1;
            }
    }
    sd_process *pr = sd_process_of(w, err);
    if (!pr)
        return -1;
    if (pr->insertion_count >= SD_INSERTIONS_MAX) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "insert", "at most %d insertions", SD_INSERTIONS_MAX);
        return -1;
    }
    sd_insertion ins;
    memset(&ins, 0, sizeof ins);
    ins.def = *d;
    ins.def.name = NULL;
    /* no pointers in the stored def (a checkpoint dataset): a mesh's
     * triangles go to the world's slot of this insertion */
    ins.def.region = reg;
    ins.def.region.vertices = NULL;
    ins.def.region.triangles = NULL;
    ins.mesh = -1;
    snprintf(ins.name, sizeof ins.name, "%s", d->name && d->name[0] ? d->name : "insert");
    double sum = 0, weight[SD_INSERT_MIX_MAX];
    /* the mix's sum first: nothing (no scaled template) is added for a mix refused */
    for (int e = 0; e < d->entry_count; ++e)
        sum += d->entries[e].fraction;
    if (!(fabs(sum - 1.0) <= 1e-6)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "insert.mix", "the mix fractions sum to %.9g, not 1", sum);
        return -1;
    }
    /* every entry's template, material and size law before any scaled
     * copy is made, so a refused insertion adds no template */
    for (int e = 0; e < d->entry_count; ++e) {
        const sd_insert_entry *en = &d->entries[e];
        sd_shape_info si;
        if (en->material < 0 || (size_t)en->material >= w->material_count) {
            sd_error_set(err, SD_ERR_INPUT, "", 0, "insert.mix.material", "entry %d: unknown material index %d", e,
                         en->material);
            return -1;
        }
        if (en->shape >= 0 && sd_world_get_shape(w, (size_t)en->shape, &si) != SD_OK) {
            sd_error_set(err, SD_ERR_INPUT, "", 0, "insert.mix.shape", "entry %d: unknown template index %d", e,
                         en->shape);
            return -1;
        }
        if ((en->shape < 0 || sd_entry_scaled(en)) && sd_size_check(&en->size, "insert.mix.radius", err) != SD_OK)
            return -1;
    }
    sum = 0;
    int dpow = w->def.dimension == 2 ? 2 : 3;
    double vol_c = w->def.dimension == 2 ? sd_pi : 4.0 / 3.0 * sd_pi;
    for (int e = 0; e < d->entry_count; ++e) {
        const sd_insert_entry *en = &d->entries[e];
        if (en->material < 0 || (size_t)en->material >= w->material_count) {
            sd_error_set(err, SD_ERR_INPUT, "", 0, "insert.mix.material", "entry %d: unknown material index %d", e,
                         en->material);
            return -1;
        }
        double mean_mass;
        if (en->shape >= 0) {
            sd_shape_info si;
            if (sd_world_get_shape(w, (size_t)en->shape, &si) != SD_OK) {
                sd_error_set(err, SD_ERR_INPUT, "", 0, "insert.mix.shape", "entry %d: unknown template index %d", e,
                             en->shape);
                return -1;
            }
            ins.bound[e] = si.bounding_radius;
            ins.body_mass[e] = sd_material_density(w, en->material) * si.volume;
            mean_mass = ins.body_mass[e];
            if (sd_entry_scaled(en)) {
                /* scaled copies, one per class of the law (sd_size_classes) */
                if (sd_size_check(&en->size, "insert.mix.radius", err) != SD_OK)
                    return -1;
                int k = en->size_classes ? en->size_classes : 16;
                if (k < 1 || k > SD_SIZE_SCALES_MAX) {
                    sd_error_set(err, SD_ERR_INPUT, "", 0, "insert.mix.size_classes",
                                 "entry %d: expected 1 to %d size classes, got %d", e, SD_SIZE_SCALES_MAX, k);
                    return -1;
                }
                double f[SD_SIZE_CLASSES_MAX], p[SD_SIZE_SCALES_MAX], rep[SD_SIZE_SCALES_MAX], norm = 0, cum = 0;
                int table = en->size.kind == SD_SIZE_TABLE;
                if (table && k < en->size.classes) {
                    sd_error_set(err, SD_ERR_INPUT, "", 0, "insert.mix.size_classes",
                                 "entry %d: size_classes %d is fewer than the table's %d classes", e, k,
                                 en->size.classes);
                    return -1;
                }
                for (int c = 0; en->size.kind == SD_SIZE_TABLE && c < en->size.classes; ++c) {
                    sd_size_def u = sd_size_def_fixed(en->size.lo[c]);
                    u.kind = SD_SIZE_UNIFORM;
                    u.b = en->size.hi[c];
                    f[c] = en->size.by_mass ? en->size.fraction[c] / sd_size_moment(&u, dpow) : en->size.fraction[c];
                    norm += f[c];
                }
                for (int c = 0; table && c < en->size.classes; ++c) {
                    f[c] /= norm;
                    cum += f[c];
                    ins.class_cum[e][c] = cum;
                }
                int n = sd_size_classes(&en->size, k, dpow, f, p, rep);
                mean_mass = 0;
                /* si.name points into the world's template table, which each
                 * added copy may move: keep the base name */
                char base[48];
                snprintf(base, sizeof base, "%.40s", si.name ? si.name : "shape");
                /* the copies are BASE_iIeEsK with I the insertion's number, or
                 * the next number whose names are all free: a scene that starts
                 * from a checkpoint of another run has that run's copies
                 * already (io/scene_from.c) */
                size_t tag = w->process ? w->process->insertion_count : (size_t)0;
                char name[96]; /* room for the widest counters (gcc's -Wformat-truncation) */
                for (int c = 0, tries = 0; c < n && tries < 1000; ++c) {
                    snprintf(name, sizeof name, "%s_i%zue%ds%d", base, tag, e, c);
                    if (sd_world_find_shape(w, name) >= 0) {
                        ++tag;
                        ++tries;
                        c = -1; /* again from the first class */
                    }
                }
                for (int c = 0; c < n; ++c) {
                    double sc = rep[c] / si.equivalent_radius;
                    snprintf(name, sizeof name, "%s_i%zue%ds%d", base, tag, e, c);
                    int idx = sd_world_add_scaled_shape(w, en->shape, sc, name, err);
                    if (idx < 0) {
                        snprintf(err->key, sizeof err->key, "insert.mix.shape");
                        return -1;
                    }
                    if (c == 0)
                        ins.scaled_first[e] = idx;
                    else if (c == 1)
                        ins.scaled_stride[e] = idx - ins.scaled_first[e];
                    mean_mass += p[c] * sd_material_density(w, en->material) * si.volume * pow(sc, dpow);
                }
                ins.scaled_count[e] = n;
                ins.scaled_per[e] = table ? n / en->size.classes : n;
            }
        } else {
            if (sd_size_check(&en->size, "insert.mix.radius", err) != SD_OK)
                return -1;
            if (en->size.kind == SD_SIZE_TABLE) {
                double c = 0, norm = 0, f[SD_SIZE_CLASSES_MAX];
                for (int k = 0; k < en->size.classes; ++k) {
                    sd_size_def u = sd_size_def_fixed(en->size.lo[k]);
                    u.kind = SD_SIZE_UNIFORM;
                    u.b = en->size.hi[k];
                    f[k] = en->size.by_mass ? en->size.fraction[k] / sd_size_moment(&u, dpow) : en->size.fraction[k];
                    norm += f[k];
                }
                for (int k = 0; k < en->size.classes; ++k) {
                    c += f[k] / norm;
                    ins.class_cum[e][k] = c;
                }
            }
            mean_mass = sd_material_density(w, en->material) * vol_c * sd_size_moment(&en->size, dpow);
        }
        if (!(en->fraction >= 0)) {
            sd_error_set(err, SD_ERR_INPUT, "", 0, "insert.mix.fraction", "entry %d: expected a fraction >= 0, got %g",
                         e, en->fraction);
            return -1;
        }
        sum += en->fraction;
        /* a mix by mass turned into probabilities by number */
        weight[e] = d->mix_by_mass ? en->fraction / mean_mass : en->fraction;
    }
    if (!(fabs(sum - 1.0) <= 1e-6)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "insert.mix", "the mix fractions sum to %.9g, not 1", sum);
        return -1;
    }
    double wsum = 0, c = 0;
    for (int e = 0; e < d->entry_count; ++e)
        wsum += weight[e];
    for (int e = 0; e < d->entry_count; ++e) {
        c += weight[e] / wsum;
        ins.entry_cum[e] = c;
    }
    size_t index = pr->insertion_count;
    if (reg.kind == SD_REGION_MESH) {
        if (sd_region_mesh_store(w, (int)index, &reg, err) != SD_OK)
            return -1;
        ins.mesh = (int)index;
    }
    uint64_t x = w->def.seed ^ (0xA0761D6478BD642Full * (uint64_t)(index + 1));
    ins.rng = sd_rng_seed(sd_rng_splitmix(&x));
    ins.next_step = (long)ceil(d->start / (double)w->dt - 1e-9);
    if (ins.next_step < w->step)
        ins.next_step = w->step;
    pr->insertions[pr->insertion_count++] = ins;
    return (int)index;
}

size_t sd_world_insertion_count(const sd_world *w) { return w && w->process ? w->process->insertion_count : 0; }

sd_status sd_world_get_insertion(const sd_world *w, size_t k, sd_insert_info *out)
{
    if (!out)
        return SD_ERR_INPUT;
    memset(out, 0, sizeof *out);
    if (!w || !w->process || k >= w->process->insertion_count)
        return SD_ERR_INPUT;
    const sd_insertion *ins = &w->process->insertions[k];
    out->name = ins->name;
    out->asked = ins->asked;
    out->inserted = ins->inserted;
    out->mass = ins->mass;
    out->target = ins->def.count ? ins->def.count : ins->inserted;
    out->done = ins->done;
    snprintf(out->why, sizeof out->why, "%s", ins->why);
    return SD_OK;
}

/* ---- outlets --------------------------------------------------------------- */

int sd_world_add_outlet(sd_world *w, const sd_region_outlet_def *d, sd_error *err)
{
    if (!w) {
        sd_error_null(err, "sd_world_add_outlet", "world");
        return -1;
    }
    if (!d || d->cookie != SD_COOKIE_PROCESS) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "outlets", "outlet def not made by sd_region_outlet_def_default");
        return -1;
    }
    if (w->solver != &sd_solver_cells) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "outlets",
                     "region outlets run on the cells solver; the grid solver has its floor outlet (outlet:)");
        return -1;
    }
    if (sd_region_check(w, &d->region, "outlets.region", 1, err) != SD_OK)
        return -1;
    if (!(d->open_at >= 0) || !isfinite(d->open_at) || d->check_every < 1) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "outlets", "an outlet needs open_at >= 0 s and check_every >= 1 step");
        return -1;
    }
    sd_process *pr = sd_process_of(w, err);
    if (!pr)
        return -1;
    if (pr->outlet_count >= SD_OUTLETS_MAX) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "outlets", "at most %d outlets", SD_OUTLETS_MAX);
        return -1;
    }
    sd_outlet_state *o = &pr->outlets[pr->outlet_count];
    memset(o, 0, sizeof *o);
    o->def = *d;
    o->def.name = NULL;
    snprintf(o->name, sizeof o->name, "%s", d->name && d->name[0] ? d->name : "outlet");
    o->next_step = w->step;
    return (int)pr->outlet_count++;
}

size_t sd_world_outlet_count(const sd_world *w) { return w && w->process ? w->process->outlet_count : 0; }

sd_status sd_world_get_outlet(const sd_world *w, size_t k, sd_outlet_info *out)
{
    if (!out)
        return SD_ERR_INPUT;
    memset(out, 0, sizeof *out);
    if (!w || !w->process || k >= w->process->outlet_count)
        return SD_ERR_INPUT;
    const sd_outlet_state *o = &w->process->outlets[k];
    out->name = o->name;
    out->removed = o->removed;
    out->mass = o->mass;
    out->open = w->time >= o->def.open_at - 0.5 * (double)w->dt;
    return SD_OK;
}

void sd_world_get_process(const sd_world *w, sd_process_info *out)
{
    if (!out)
        return;
    memset(out, 0, sizeof *out);
    if (!w)
        return;
    const sd_process *pr = w->process;
    if (!pr) {
        out->initial = w->p.n;
        return;
    }
    out->initial = pr->started ? pr->initial : w->p.n;
    out->inserted = pr->inserted;
    out->removed = pr->removed;
    out->inserted_mass = pr->inserted_mass;
    out->removed_mass = pr->removed_mass;
}

typedef struct sd_outlet_ctx {
    const sd_region_def *region;
} sd_outlet_ctx;

static int sd_outlet_pred(const sd_world *w, size_t k, void *ctx)
{
    const sd_outlet_ctx *c = ctx;
    sd_v3d x = {(double)w->p.x[k].x, (double)w->p.x[k].y, (double)w->p.x[k].z};
    return sd_region_contains(c->region, x);
}

/* An outlet of a decomposed run (w->comm): each rank takes its own
 * particles in the region, and the count and mass every rank gets back
 * are those of all of them, the mass summed in stable-id order (the
 * world's comm), so the accounts are the same on every rank and rank
 * count. */
static sd_status sd_outlet_remove_ranks(sd_world *w, sd_outlet_ctx *ctx, sd_remove_result *res, sd_error *err)
{
    size_t n = w->p.n, m = 0;
    uint8_t *mark = sd_malloc(n ? n : 1);
    uint64_t *id = sd_malloc((n ? n : 1) * sizeof *id);
    double *mass = sd_malloc((n ? n : 1) * sizeof *mass);
    sd_status st = SD_OK;
    if (!mark || !id || !mass)
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory marking %zu particles", n);
    for (size_t k = 0; st == SD_OK && k < n; ++k) {
        mark[k] = (uint8_t)(sd_outlet_pred(w, k, ctx) != 0);
        if (mark[k]) {
            id[m] = w->p.id[k];
            mass[m] = w->p.inv_mass[k] > 0 ? 1.0 / (double)w->p.inv_mass[k] : 0.0;
            ++m;
        }
    }
    /* collective: every rank takes part, even one that failed above */
    size_t count = 0;
    double total = 0;
    sd_status cst = w->comm->removed_sum(w->comm_ctx, st == SD_OK ? m : 0, id, mass, &count, &total, err);
    if (st == SD_OK)
        st = cst;
    if (st == SD_OK && m > 0)
        st = sd_world_remove_particles(w, mark, NULL, err);
    sd_free(mark);
    sd_free(id);
    sd_free(mass);
    res->count = count;
    res->mass = total;
    return st;
}

static sd_status sd_outlets_run(sd_world *w, sd_error *err)
{
    sd_process *pr = w->process;
    for (size_t k = 0; k < pr->outlet_count; ++k) {
        sd_outlet_state *o = &pr->outlets[k];
        if (w->step < o->next_step)
            continue;
        long open_step = (long)ceil(o->def.open_at / (double)w->dt - 1e-9);
        if (w->step >= open_step) {
            sd_outlet_ctx ctx = {&o->def.region};
            sd_remove_result res;
            sd_status st = w->comm ? sd_outlet_remove_ranks(w, &ctx, &res, err)
                                   : sd_world_remove_if(w, sd_outlet_pred, &ctx, &res, err);
            if (st != SD_OK)
                return st;
            o->removed += res.count;
            o->mass += res.mass;
            pr->removed += res.count;
            pr->removed_mass += res.mass;
        }
        long next = w->step + 1;
        if (next < open_step)
            next = open_step;
        long ce = o->def.check_every;
        o->next_step = ((next + ce - 1) / ce) * ce;
    }
    return SD_OK;
}

/* ---- placing -------------------------------------------------------------- */

/* The spheres a new particle must not overlap: the owned particles (their
 * bounding spheres), their periodic images, and those placed in this
 * batch, in a uniform grid of cells over the region's box. */
typedef struct sd_place_grid {
    double lo[3], cell;
    int64_t nc[3];
    size_t n, cap;
    sd_v3d *x;
    double *r;
    size_t *next;   /* per sphere */
    size_t *head;   /* per cell */
} sd_place_grid;

#define SD_PLACE_NONE ((size_t)-1)

static void sd_place_grid_free(sd_place_grid *g)
{
    sd_free(g->x);
    sd_free(g->r);
    sd_free(g->next);
    sd_free(g->head);
    memset(g, 0, sizeof *g);
}

static int64_t sd_place_cell(const sd_place_grid *g, sd_v3d x, int64_t c[3])
{
    const double xs[3] = {x.x, x.y, x.z};
    for (int a = 0; a < 3; ++a) {
        double f = floor((xs[a] - g->lo[a]) / g->cell);
        if (f < 0 || f >= (double)g->nc[a])
            return -1;
        c[a] = (int64_t)f;
    }
    return (c[2] * g->nc[1] + c[1]) * g->nc[0] + c[0];
}

static int sd_place_push(sd_place_grid *g, sd_v3d x, double r)
{
    int64_t c[3];
    int64_t cell = sd_place_cell(g, x, c);
    if (cell < 0)
        return 1; /* too far from the region to matter */
    if (g->n == g->cap) {
        size_t cap = g->cap ? 2 * g->cap : 1024;
        sd_v3d *nx = sd_realloc(g->x, cap * sizeof *nx);
        if (!nx)
            return 0;
        g->x = nx;
        double *nr = sd_realloc(g->r, cap * sizeof *nr);
        if (!nr)
            return 0;
        g->r = nr;
        size_t *nn = sd_realloc(g->next, cap * sizeof *nn);
        if (!nn)
            return 0;
        g->next = nn;
        g->cap = cap;
    }
    g->x[g->n] = x;
    g->r[g->n] = r;
    g->next[g->n] = g->head[cell];
    g->head[cell] = g->n;
    g->n++;
    return 1;
}

/* 1 when the bounding sphere (centre x, radius b) lies inside every
 * plane, box and drum wall: in front of a plane, within a box's closed
 * faces (x, y only in 2D), inside a drum's mantle and closed caps. A
 * region that crosses the walls gets its particles inside them only (a
 * particle placed across a wall would start deep in it: the overlap guard
 * stops the run, or the wall kicks it); one outside them places none.
 * Mesh walls: clear of every facet, inside a closed container and outside
 * a closed obstacle (world/mesh_clear.c). */
static int sd_place_inside_walls(const sd_world *w, sd_v3d x, double b, int dim2)
{
    const sd_vec3 c = sd_v3((sd_real)x.x, (sd_real)x.y, (sd_real)x.z);
    const sd_real r = (sd_real)b;
    for (size_t k = 0; k < w->wall_count; ++k) {
        const sd_wall *wl = &w->walls[k];
        if (wl->kind == SD_WALL_PLANE) {
            if (sd_v3_dot(sd_v3_sub(c, wl->point), wl->normal) < r)
                return 0;
        } else if (wl->kind == SD_WALL_BOX) {
            const sd_real lo[3] = {wl->lo.x, wl->lo.y, wl->lo.z}, hi[3] = {wl->hi.x, wl->hi.y, wl->hi.z};
            const sd_real cc[3] = {c.x, c.y, c.z};
            for (int a = 0; a < (dim2 ? 2 : 3); ++a)
                if ((!(wl->open_faces & (1u << (2 * a))) && cc[a] - r < lo[a]) ||
                    (!(wl->open_faces & (1u << (2 * a + 1))) && cc[a] + r > hi[a]))
                    return 0;
        } else if (wl->kind == SD_WALL_DRUM) {
            sd_vec3 d;
            sd_real s = sd_wall_drum_coords(&wl->geom, c, &d), half = wl->lo.y;
            if (sd_v3_norm(d) + r > wl->lo.x || (!(wl->open_faces & SD_WALL_DRUM_CAP_HI) && s + r > half) ||
                (!(wl->open_faces & SD_WALL_DRUM_CAP_LO) && s - r < -half))
                return 0;
        }
    }
    return w->mesh_count == 0 || sd_world_meshes_clear(w, x, b);
}

static int sd_place_free_spot(const sd_place_grid *g, sd_v3d x, double r)
{
    int64_t c[3];
    if (sd_place_cell(g, x, c) < 0)
        return 1;
    for (int64_t dz = -1; dz <= 1; ++dz)
        for (int64_t dy = -1; dy <= 1; ++dy)
            for (int64_t dx = -1; dx <= 1; ++dx) {
                int64_t cx = c[0] + dx, cy = c[1] + dy, cz = c[2] + dz;
                if (cx < 0 || cy < 0 || cz < 0 || cx >= g->nc[0] || cy >= g->nc[1] || cz >= g->nc[2])
                    continue;
                for (size_t k = g->head[(cz * g->nc[1] + cy) * g->nc[0] + cx]; k != SD_PLACE_NONE; k = g->next[k]) {
                    double ex = g->x[k].x - x.x, ey = g->x[k].y - x.y, ez = g->x[k].z - x.z, rs = g->r[k] + r;
                    if (ex * ex + ey * ey + ez * ez < rs * rs)
                        return 0;
                }
            }
    return 1;
}

/* A sphere and its images one period away on each periodic axis (those
 * far from the region fall outside the grid and are left out); 0 when out
 * of memory. */
static int sd_place_push_images(const sd_world *w, sd_place_grid *g, sd_v3d x, double r)
{
    const unsigned per = w->def.periodic;
    const double len[3] = {w->def.domain_hi.x - w->def.domain_lo.x, w->def.domain_hi.y - w->def.domain_lo.y,
                           w->def.domain_hi.z - w->def.domain_lo.z};
    int lim[3];
    for (int a = 0; a < 3; ++a)
        lim[a] = (per >> a) & 1u;
    for (int ix = -lim[0]; ix <= lim[0]; ++ix)
        for (int iy = -lim[1]; iy <= lim[1]; ++iy)
            for (int iz = -lim[2]; iz <= lim[2]; ++iz) {
                sd_v3d y = {x.x + ix * len[0], x.y + iy * len[1], x.z + iz * len[2]};
                if (!sd_place_push(g, y, r))
                    return 0;
            }
    return 1;
}

/* Builds the grid of what is present near the region; rnew is the largest
 * bounding radius the batch may place. */
static sd_status sd_place_grid_build(const sd_world *w, const sd_region_def *reg, double rnew, sd_place_grid *g)
{
    memset(g, 0, sizeof *g);
    const sd_particles *p = &w->p;
    /* a decomposed run: every rank's particles (xr, 4 doubles each) */
    double *xr = NULL;
    size_t np = p->n;
    if (w->comm) {
        sd_error e;
        if (w->comm->all_spheres(w->comm_ctx, w, &xr, &np, &e) != SD_OK)
            return SD_ERR_MEMORY;
    }
    double rmax = rnew;
    for (size_t k = 0; k < np; ++k)
        rmax = fmax(rmax, xr ? xr[4 * k + 3] : (double)p->radius[k]);
    double lo[3], hi[3];
    sd_region_bbox(reg, lo, hi);
    if (w->def.dimension == 2)
        lo[2] = hi[2] = 0.0;
    g->cell = 2.0 * rmax;
    double margin = 2.0 * rmax; /* a neighbour's centre lies within r_new + r_j of the region */
    if (!(rmax > 0) || !isfinite(rmax) || !(hi[0] - lo[0] + 2 * margin < 1e300) ||
        !(hi[1] - lo[1] + 2 * margin < 1e300) || !(hi[2] - lo[2] + 2 * margin < 1e300)) {
        sd_free(xr);
        return SD_ERR_INPUT; /* sd_size_check refuses such sizes; never loop on them */
    }
    size_t cells = 0;
    /* each pass doubles the cell: from a finite size, 2^22 cells within
     * about 1,100 passes whatever the region */
    for (int pass = 0; pass < 2200; ++pass) {
        cells = 1;
        for (int a = 0; a < 3; ++a) {
            g->lo[a] = lo[a] - margin;
            g->nc[a] = (int64_t)ceil((hi[a] - lo[a] + 2 * margin) / g->cell) + 1;
            cells *= (size_t)g->nc[a];
        }
        if (cells <= ((size_t)1 << 22))
            break;
        g->cell *= 2.0; /* coarser cells for a large region of small grains: still correct */
    }
    if (cells > ((size_t)1 << 22)) {
        sd_free(xr);
        return SD_ERR_INPUT;
    }
    g->head = sd_malloc(cells * sizeof *g->head);
    if (!g->head) {
        sd_free(xr);
        return SD_ERR_MEMORY;
    }
    for (size_t c = 0; c < cells; ++c)
        g->head[c] = SD_PLACE_NONE;
    for (size_t k = 0; k < np; ++k) {
        sd_v3d x;
        double r;
        if (xr) {
            x = (sd_v3d){xr[4 * k], xr[4 * k + 1], xr[4 * k + 2]};
            r = xr[4 * k + 3];
        } else {
            x = (sd_v3d){(double)p->x[k].x, (double)p->x[k].y, (double)p->x[k].z};
            r = (double)p->radius[k];
        }
        if (!sd_place_push_images(w, g, x, r)) {
            sd_free(xr);
            return SD_ERR_MEMORY;
        }
    }
    sd_free(xr);
    return SD_OK;
}

/* Shoemake's uniform rotation (as io/scene_gen.c); about z in 2D. Always
 * three draws. */
static void sd_place_orient(sd_rng *rng, int random, int dim2, double q[4])
{
    double u1 = sd_rng_uniform(rng), u2 = sd_rng_uniform(rng), u3 = sd_rng_uniform(rng);
    if (!random) {
        q[0] = 1, q[1] = q[2] = q[3] = 0;
    } else if (dim2) {
        q[0] = cos(sd_pi * u1), q[1] = q[2] = 0, q[3] = sin(sd_pi * u1);
    } else {
        double a = sqrt(1.0 - u1), b = sqrt(u1);
        q[0] = b * cos(2 * sd_pi * u3);
        q[1] = a * sin(2 * sd_pi * u2);
        q[2] = a * cos(2 * sd_pi * u2);
        q[3] = b * sin(2 * sd_pi * u3);
    }
}

/* How many particles insertion ins owes at step s (rate, mass rate or all
 * at once); for a mass target, 1 while mass is owed. */
static size_t sd_insert_due(const sd_world *w, const sd_insertion *ins, long s)
{
    const sd_insert_def *d = &ins->def;
    double t = (double)s * (double)w->dt, dt = (double)w->dt;
    if (t < d->start - 0.5 * dt)
        return ins->inserted;
    if (d->count > 0) {
        double due = d->rate > 0 ? floor((t - d->start) * d->rate + 1e-9) + 1.0 : (double)d->count;
        if (d->mass_rate > 0) /* a count at a mass rate: one more each time the mass falls behind */
            due = (double)ins->inserted + (ins->mass <= d->mass_rate * (t - d->start) + 1e-15 ? 1.0 : 0.0);
        return due < (double)d->count ? (size_t)due : d->count;
    }
    /* a mass target */
    if (ins->mass >= d->mass)
        return ins->inserted;
    if (d->mass_rate > 0)
        return ins->inserted + (ins->mass <= d->mass_rate * (t - d->start) + 1e-15 ? 1u : 0u);
    if (d->rate > 0) {
        double due = floor((t - d->start) * d->rate + 1e-9) + 1.0;
        return due > (double)ins->inserted ? ins->inserted + 1 : ins->inserted;
    }
    return ins->inserted + 1; /* all at once: until the mass is in */
}

/* Class c's copy's bounding radius (m). */
static double sd_scaled_bound(const sd_world *w, const sd_insertion *ins, int e, int c)
{
    sd_shape_info si;
    if (sd_world_get_shape(w, (size_t)(ins->scaled_first[e] + c * ins->scaled_stride[e]), &si) != SD_OK)
        return 0.0;
    return si.bounding_radius;
}

/* The class of uniform u: equally likely classes, or for a sieve table
 * its sieve class by class_cum and then one of its `per` equal ones. */
static int sd_scaled_class(const sd_insertion *ins, int e, double u)
{
    int n = ins->scaled_count[e], per = ins->scaled_per[e];
    if (per == n) {
        int c = (int)(u * n);
        return c < n ? c : n - 1;
    }
    int k = 0, classes = n / per;
    while (k + 1 < classes && u >= ins->class_cum[e][k])
        ++k;
    double lo = k ? ins->class_cum[e][k - 1] : 0.0, hi = ins->class_cum[e][k];
    int j = hi > lo ? (int)((u - lo) / (hi - lo) * per) : 0;
    return k * per + (j < per ? (j < 0 ? 0 : j) : per - 1);
}

/* After a batch that added particles to a prepared world (added): the new
 * particles touch nothing, so the prepared state holds (see the note at
 * the top); the views take the new count, and a world prepared empty gets
 * the skin prepare would have given it (rmin_new: the smallest new radius). */
static sd_status sd_insert_settle(sd_world *w, int added, double rmin_new, sd_error *err)
{
    if (!added)
        return SD_OK;
    w->prepared = 1;
    if (w->skin == 0 && !(w->def.skin > 0))
        w->skin = (sd_real)(0.2 * rmin_new);
    sd_status st = sd_world_check_params(w, err);
    if (st != SD_OK)
        return st;
    if (sd_world_views(w) != SD_OK)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the views");
    return SD_OK;
}

/* Places what insertion ins owes now; records why some did not fit. */
static sd_status sd_insert_run(sd_world *w, sd_insertion *ins, sd_error *err)
{
    sd_process *pr = w->process;
    const sd_insert_def *d = &ins->def;
    int dim2 = w->def.dimension == 2;
    int all_at_once = !(d->rate > 0) && !(d->mass_rate > 0);
    double rnew = 0;
    for (int e = 0; e < d->entry_count; ++e) {
        const sd_insert_entry *en = &d->entries[e];
        double b = en->shape >= 0 ? ins->bound[e] : 0;
        for (int c = 0; c < ins->scaled_count[e]; ++c)
            b = c == 0 ? sd_scaled_bound(w, ins, e, c) : fmax(b, sd_scaled_bound(w, ins, e, c));
        if (en->shape < 0) {
            const sd_size_def *s = &en->size;
            b = s->kind == SD_SIZE_FIXED ? s->a : s->kind == SD_SIZE_UNIFORM ? s->b : 0;
            if (s->kind == SD_SIZE_TABLE)
                for (int c = 0; c < s->classes; ++c)
                    b = fmax(b, s->hi[c]);
            if (s->kind == SD_SIZE_NORMAL || s->kind == SD_SIZE_LOGNORMAL)
                b = s->max > 0 ? s->max : (s->kind == SD_SIZE_NORMAL ? s->a + 8 * s->b : s->a * exp(8 * s->b));
        }
        rnew = fmax(rnew, b);
    }
    sd_place_grid g;
    sd_status st = sd_place_grid_build(w, &d->region, rnew, &g);
    if (st != SD_OK) {
        sd_place_grid_free(&g);
        return sd_error_set(err, st, "", 0, "", st == SD_ERR_MEMORY ? "out of memory for the insertion check"
                            : "the insertion region or the particle sizes are too large for the insertion check "
                              "(bounding radius %g m)", rnew);
    }
    int was_prepared = w->prepared;
    const sd_region_wrap wrap = sd_region_wraps(w, &d->region);
    size_t n_before = w->p.n; /* a decomposed run: the new ones go to their ranks below */
    double rmin_new = HUGE_VAL;
    size_t failed = 0, before = ins->inserted;
    int in_a_row = 0; /* consecutive particles that found no spot */
    int interrupted = 0;
    for (;;) {
        size_t due = sd_insert_due(w, ins, w->step);
        if (ins->inserted + failed >= due)
            break;
        /* sd_world_request_interrupt: stop before this particle; the
         * placed ones stay, the rest are tried at this step on the next
         * call, from the stream where it stopped */
        if (sd_world_interrupt_due(w)) {
            interrupted = 1;
            break;
        }
        /* all at once: a region that refused SD_INSERT_GIVE_UP particles in
         * a row is full; trying the rest (10^6 of them, each `attempts`
         * times) would only take time */
        if (all_at_once && in_a_row >= SD_INSERT_GIVE_UP) {
            size_t left = due - ins->inserted - failed;
            failed += left;
            size_t len = strlen(ins->why);
            snprintf(ins->why + len, sizeof ins->why - len, "; the last %zu not tried after %d in a row found none",
                     left, SD_INSERT_GIVE_UP);
            break;
        }
        /* one particle: its entry, size, orientation and velocity, then positions */
        double u = sd_rng_uniform(&ins->rng);
        int e = 0;
        while (e + 1 < d->entry_count && u >= ins->entry_cum[e])
            ++e;
        const sd_insert_entry *en = &d->entries[e];
        int shape = en->shape;
        double r, b;
        if (ins->scaled_count[e] > 0) {
            /* a class of the law: one draw, as sd_size_draw takes for a template as it is */
            int c = sd_scaled_class(ins, e, sd_rng_uniform(&ins->rng));
            shape = ins->scaled_first[e] + c * ins->scaled_stride[e];
            r = b = sd_scaled_bound(w, ins, e, c);
        } else {
            r = sd_size_draw(ins, e, &ins->rng);
            b = en->shape >= 0 ? ins->bound[e] : r;
        }
        double q[4];
        sd_place_orient(&ins->rng, d->random_orientation, dim2, q);
        sd_v3d v = d->velocity;
        if (d->velocity_jitter > 0) {
            double j = d->velocity_jitter;
            v.x += sd_rng_range(&ins->rng, -j, j);
            v.y += sd_rng_range(&ins->rng, -j, j);
            double jz = sd_rng_range(&ins->rng, -j, j);
            if (!dim2)
                v.z += jz;
        }
        sd_v3d x;
        int ok = 0, fits = 1, outside = 0;
        const sd_region_mesh *rm = ins->mesh >= 0 && w->region_meshes ? &w->region_meshes->slot[ins->mesh] : NULL;
        for (int a = 0; a < d->attempts && !ok; ++a) {
            int drawn = sd_region_draw(&d->region, rm, &wrap, b, dim2, &ins->rng, &x);
            if (!drawn) {
                fits = 0;
                break;
            }
            ok = drawn == 1 && sd_place_free_spot(&g, x, b);
            if (ok && !sd_place_inside_walls(w, x, b, dim2)) {
                ok = 0;
                ++outside;
            }
        }
        if (!ok) {
            ++failed;
            ++in_a_row;
            if (fits && outside == d->attempts)
                snprintf(ins->why, sizeof ins->why,
                         "at t = %.6g s a particle found every one of its %d positions outside the walls (the "
                         "region lies outside them)",
                         w->time, d->attempts);
            else if (fits)
                snprintf(ins->why, sizeof ins->why,
                         "at t = %.6g s a particle of bounding radius %g m found no free spot in %d attempts (the "
                         "region is full%s)",
                         w->time, b, d->attempts, outside ? ", or outside the walls" : "");
            else
                snprintf(ins->why, sizeof ins->why,
                         "at t = %.6g s a particle of bounding radius %g m is larger than the region", w->time, b);
            continue; /* the loop ends once the due count is tried */
        }
        sd_status ast;
        if (en->shape >= 0) {
            sd_body_def bd;
            memset(&bd, 0, sizeof bd);
            bd.position = x;
            bd.velocity = v;
            memcpy(bd.orientation, q, sizeof q);
            bd.shape = shape;
            bd.material = en->material;
            ast = sd_world_add_bodies(w, 1, &bd, err);
        } else {
            sd_sphere_def sp;
            memset(&sp, 0, sizeof sp);
            sp.position = x;
            sp.velocity = v;
            sp.radius = r;
            sp.material = en->material;
            ast = sd_world_add_spheres(w, 1, &sp, err);
        }
        if (ast != SD_OK) {
            sd_place_grid_free(&g);
            return ast;
        }
        double m = 1.0 / (double)w->p.inv_mass[w->p.n - 1];
        in_a_row = 0;
        ins->inserted++;
        ins->mass += m;
        pr->inserted++;
        pr->inserted_mass += m;
        rmin_new = fmin(rmin_new, (double)w->p.radius[w->p.n - 1]);
        if (!sd_place_push_images(w, &g, x, b)) {
            sd_place_grid_free(&g);
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the insertion check");
        }
        /* a mass target: stop once the mass is in */
        if (d->count == 0 && ins->mass >= d->mass)
            break;
    }
    sd_place_grid_free(&g);
    if (interrupted) {
        ins->asked = ins->inserted + failed; /* so far (a checkpoint now holds inserted <= asked) */
        ins->next_step = w->step;
        st = sd_insert_settle(w, ins->inserted > before && was_prepared, rmin_new, err);
        return st != SD_OK ? st : sd_world_interrupted(w, err);
    }
    /* a decomposed run: every rank drew, checked and added the same
     * particles, with the same ids; each keeps its own (collective: every
     * rank runs the same insertion at the same step) */
    if (w->comm && (st = w->comm->keep_owned(w->comm_ctx, w, n_before, err)) != SD_OK)
        return st;
    ins->asked = ins->inserted + failed;
    if (d->count > 0 && ins->asked < ins->inserted)
        ins->asked = ins->inserted;
    /* when it is done, and when it runs next */
    int complete = d->count > 0 ? ins->inserted >= d->count : ins->mass >= d->mass;
    if (complete || all_at_once) {
        ins->done = 1;
        if (!complete && d->count > 0)
            ins->asked = d->count;
        ins->next_step = -1;
    } else if (d->rate > 0) {
        /* the next particle's time; the ones that did not fit are tried again then */
        double tn = d->start + (double)ins->inserted / d->rate;
        long sn = (long)ceil(tn / (double)w->dt - 1e-9);
        if (failed)
            sn = w->step + (long)ceil(1.0 / (d->rate * (double)w->dt)); /* one insertion period later */
        ins->next_step = sn > w->step ? sn : w->step + 1;
    } else {
        double tn = d->start + ins->mass / d->mass_rate;
        long sn = (long)ceil(tn / (double)w->dt - 1e-9);
        if (failed)
            sn = w->step + 1 + (long)ceil(ins->mass / fmax(1.0, (double)ins->inserted) / d->mass_rate / (double)w->dt);
        ins->next_step = sn > w->step ? sn : w->step + 1;
    }
    return sd_insert_settle(w, ins->inserted > before && was_prepared, rmin_new, err);
}

/* ---- the drum wall (dynamics/walls.h, SD_WALL_DRUM) ------------------------------ */

sd_drum_def sd_drum_def_default(void)
{
    sd_drum_def d;
    memset(&d, 0, sizeof d);
    d.axis.z = 1;
    d.cookie = SD_COOKIE_PROCESS;
    return d;
}

int sd_world_add_drum(sd_world *w, const sd_drum_def *d, sd_error *err)
{
    if (!w) {
        sd_error_null(err, "sd_world_add_drum", "world");
        return -1;
    }
    if (!d || d->cookie != SD_COOKIE_PROCESS) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "walls", "drum def not made by sd_drum_def_default");
        return -1;
    }
    double an = sqrt(sd_d3_dot(d->axis, d->axis));
    if (!(d->start >= 0) || !(d->ramp >= 0) || !isfinite(d->start) || !isfinite(d->ramp)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "ramp", "drum: expected start >= 0 s and ramp >= 0 s, got %g and %g",
                     d->start, d->ramp);
        return -1;
    }
    if (!(an > 0) || !(d->radius > 0) || !(d->length > 0) || !isfinite(d->rpm)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "walls", "a drum needs a non-zero axis, a radius > 0, a length > 0 and "
                                                        "a finite rpm");
        return -1;
    }
    if (w->dim2) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "walls", "dimension 2: the drum wall is 3D only");
        return -1;
    }
    sd_wall wl;
    memset(&wl, 0, sizeof wl);
    wl.kind = SD_WALL_DRUM;
    wl.point = sd_v3((sd_real)d->center.x, (sd_real)d->center.y, (sd_real)d->center.z);
    wl.normal = sd_v3((sd_real)(d->axis.x / an), (sd_real)(d->axis.y / an), (sd_real)(d->axis.z / an));
    wl.lo = sd_v3((sd_real)d->radius, (sd_real)(0.5 * d->length), SD_R(0.0));
    wl.hi = wl.lo;
    wl.open_faces = (d->open_lo ? SD_WALL_DRUM_CAP_LO : 0u) | (d->open_hi ? SD_WALL_DRUM_CAP_HI : 0u);
    wl.centre = wl.point;
    wl.q = sd_quat_identity();
    /* rad/s: 2 pi rpm / 60 about +axis, once spun up */
    wl.drum_w0 = 2.0 * sd_pi * d->rpm / 60.0;
    wl.drum_start = d->start;
    wl.drum_ramp = d->ramp;
    double frac = 1; /* without start and ramp: at rpm from the first step on */
    if (d->start > 0 || d->ramp > 0)
        (void)sd_wall_ramp_path(w->time, wl.drum_start, wl.drum_ramp, &frac);
    wl.omega = sd_v3_scale(wl.normal, (sd_real)(wl.drum_w0 * frac));
    /* a drum that spins up changes its speed in the walls' drift of each
     * step; one at constant speed needs no drift (and keeps its bits) */
    if (d->start > 0 || d->ramp > 0)
        w->walls_moving = 1;
    wl.material = d->material;
    snprintf(wl.name, sizeof wl.name, "%s", d->name && d->name[0] ? d->name : "drum");
    return sd_world_push_wall(w, &wl, err);
}

void sd_world_drums_spin(sd_world *w, double t)
{
    for (size_t k = 0; k < w->wall_count; ++k) {
        sd_wall *wl = &w->walls[k];
        if (wl->kind != SD_WALL_DRUM || (wl->drum_start <= 0 && wl->drum_ramp <= 0))
            continue;
        double frac;
        (void)sd_wall_ramp_path(t, wl->drum_start, wl->drum_ramp, &frac);
        wl->omega = sd_v3_scale(wl->normal, (sd_real)(wl->drum_w0 * frac));
    }
}

/* ---- the step ---------------------------------------------------------------- */

static sd_status sd_process_events(sd_world *w, sd_error *err)
{
    sd_process *pr = w->process;
    sd_status st = sd_outlets_run(w, err);
    if (st != SD_OK)
        return st;
    for (size_t k = 0; k < pr->insertion_count; ++k) {
        sd_insertion *ins = &pr->insertions[k];
        if (ins->done || w->step < ins->next_step)
            continue;
        st = sd_insert_run(w, ins, err);
        if (st != SD_OK)
            return st;
    }
    return SD_OK;
}

/* Steps to the next event from now (at least 1). */
static long sd_process_next(const sd_world *w)
{
    const sd_process *pr = w->process;
    long next = LONG_MAX;
    for (size_t k = 0; k < pr->outlet_count; ++k)
        if (pr->outlets[k].next_step < next)
            next = pr->outlets[k].next_step;
    for (size_t k = 0; k < pr->insertion_count; ++k)
        if (!pr->insertions[k].done && pr->insertions[k].next_step < next)
            next = pr->insertions[k].next_step;
    return next <= w->step ? 1 : next - w->step;
}

sd_status sd_cells_process_step(sd_world *w, long nsteps, sd_error *err)
{
    sd_process *pr = w->process;
    if (!pr || (pr->insertion_count == 0 && pr->outlet_count == 0))
        return sd_cells_step(w, nsteps, err);
    if (!pr->started) {
        pr->started = 1;
        pr->initial = w->comm ? (size_t)w->comm->sum(w->comm_ctx, w->p.n) : w->p.n;
    }
    long done = 0;
    sd_status st = SD_OK;
    /* the events of the current step (an insertion at start 0 fills the
     * world before its first prepare) */
    if ((st = sd_process_events(w, err)) != SD_OK)
        return st;
    while (done < nsteps) {
        long chunk = sd_process_next(w);
        if (chunk > nsteps - done)
            chunk = nsteps - done;
        if ((st = sd_cells_step(w, chunk, err)) != SD_OK)
            return st;
        done += chunk;
        if ((st = sd_process_events(w, err)) != SD_OK)
            return st;
    }
    if (nsteps == 0 && !w->prepared)
        return sd_cells_step(w, 0, err);
    return SD_OK;
}

/* summary.txt and stats.csv: the accounting (the run's asked-for and
 * inserted per insertion, removed per outlet). */
size_t sd_cells_process_info(const sd_world *w, sd_solver_item *items, size_t max)
{
    const sd_process *pr = w->process;
    if (!pr || max < 4)
        return 0;
    size_t n = 0;
    sd_solver_item it;
    memset(&it, 0, sizeof it);
    it.n = 1;
    it.integer = 1;
    it.sep = " ";
    it.key = "particles_initial";
    it.v[0] = (double)(pr->started ? pr->initial : w->p.n);
    items[n++] = it;
    it.key = "particles_inserted";
    it.column = "inserted";
    it.v[0] = (double)pr->inserted;
    items[n++] = it;
    it.key = "particles_removed";
    it.column = "removed";
    it.v[0] = (double)pr->removed;
    items[n++] = it;
    it.key = "mass_removed";
    it.column = "removed_mass";
    it.integer = 0;
    it.v[0] = pr->removed_mass;
    items[n++] = it;
    return n;
}
