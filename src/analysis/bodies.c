/* bodies.c — the particles as the analyses see them (analysis/analysis.h):
 * gathered through the solver interface, regions, the inside test of each
 * shape kind and the highest point of a posed shape.
 *
 * Inside tests, per kind (the voxel porosity of seed 004 §4.1 needs the
 * true shapes, not their bounding spheres):
 *   sphere (shape -1)   |p - x| <= r, exact;
 *   convex templates    the point in the principal frame, then the
 *                       template's own test (shape/composite.h: boxes,
 *                       cylinders, cones and ellipsoids in closed form,
 *                       polyhedra by their face half-spaces, GJK to the
 *                       core for rounded points near a surface);
 *   composites          inside any element (seed 004 eqs. 5-6 pose each);
 *   2D shapes           the plane point in the body frame: a circle by its
 *                       radius, the others by 2D GJK from the point to the
 *                       core, inside when within the rounding radius.
 * A point on the boundary may go either way; the voxel count converges
 * all the same (the boundary has no volume).
 */
#include <math.h>
#include <string.h>

#include "analysis/analysis.h"
#include "contact/pair2d.h"
#include "core/alloc.h"
#include "geom/gjk2d.h"
#include "shape/composite.h"
#include "shape/support.h"

sd_status sd_an_gather(const sd_world *w, sd_an_set *out, sd_error *err)
{
    memset(out, 0, sizeof *out);
    out->dim2 = w->dim2;
    sd_vec3 g = w->gravity;
    sd_real gn = sd_v3_norm(g);
    out->up = gn > 0 ? sd_v3_scale(g, SD_R(-1.0) / gn) : (w->dim2 ? sd_v3(0, 1, 0) : sd_v3(0, 0, 1));
    size_t n = sd_world_particle_count(w);
    if (n == 0)
        return SD_OK;
    out->b = sd_calloc(n, sizeof *out->b);
    if (!out->b)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (analysis: %zu particles)", n);
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state ps;
        if (sd_world_get_particle(w, k, &ps) != SD_OK)
            continue;
        sd_an_body *b = &out->b[out->n++];
        b->x = sd_v3((sd_real)ps.position.x, (sd_real)ps.position.y, (sd_real)ps.position.z);
        b->v = sd_v3((sd_real)ps.velocity.x, (sd_real)ps.velocity.y, (sd_real)ps.velocity.z);
        b->w = sd_v3((sd_real)ps.angular_velocity.x, (sd_real)ps.angular_velocity.y, (sd_real)ps.angular_velocity.z);
        b->q = sd_quat_make((sd_real)ps.quat[0], (sd_real)ps.quat[1], (sd_real)ps.quat[2], (sd_real)ps.quat[3]);
        b->mass = isfinite(ps.mass) ? (sd_real)ps.mass : SD_R(0.0); /* a fixed body: no mass in the sums */
        b->bound = (sd_real)ps.radius;
        b->shape = ps.shape;
    }
    return SD_OK;
}

void sd_an_free(sd_an_set *s)
{
    sd_free(s->b);
    memset(s, 0, sizeof *s);
}

sd_status sd_an_region_make(const sd_region_def *r, int dim2, sd_an_region *out, sd_error *err)
{
    memset(out, 0, sizeof *out);
    out->kind = r ? r->kind : SD_REGION_NONE;
    if (out->kind == SD_REGION_NONE)
        return SD_OK;
    if (out->kind == SD_REGION_BOX) {
        out->lo = sd_v3((sd_real)r->lo.x, (sd_real)r->lo.y, dim2 ? SD_R(0.0) : (sd_real)r->lo.z);
        out->hi = sd_v3((sd_real)r->hi.x, (sd_real)r->hi.y, dim2 ? SD_R(0.0) : (sd_real)r->hi.z);
        if (!(out->hi.x > out->lo.x) || !(out->hi.y > out->lo.y) || (!dim2 && !(out->hi.z > out->lo.z)))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "region", "the region box is empty (expected max > min)");
        out->blo = out->lo;
        out->bhi = out->hi;
        return SD_OK;
    }
    if (out->kind != SD_REGION_CYLINDER)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "region", "expected a box or a cylinder region");
    sd_vec3 a = sd_v3((sd_real)r->axis.x, (sd_real)r->axis.y, (sd_real)r->axis.z);
    if (dim2)
        a = sd_v3(0, 0, 1); /* the disc of the plane */
    sd_real an = sd_v3_norm(a);
    if (!(an > 0) || !(r->radius > 0) || (!dim2 && !(r->length > 0)))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "region",
                            "the cylinder region needs a non-zero axis, radius > 0 and length > 0");
    out->a = sd_v3_scale(a, SD_R(1.0) / an);
    /* e1: the world axis least aligned with a, made orthogonal */
    sd_vec3 t = sd_fabs(out->a.x) < SD_R(0.6) ? sd_v3(1, 0, 0) : sd_v3(0, 1, 0);
    out->e1 = sd_v3_normalize(sd_v3_sub(t, sd_v3_scale(out->a, sd_v3_dot(t, out->a))));
    out->e2 = sd_v3_cross(out->a, out->e1);
    out->c = sd_v3((sd_real)r->center.x, (sd_real)r->center.y, dim2 ? SD_R(0.0) : (sd_real)r->center.z);
    out->radius = (sd_real)r->radius;
    out->half = dim2 ? SD_R(0.0) : SD_R(0.5) * (sd_real)r->length;
    const sd_real ax[3] = {out->a.x, out->a.y, out->a.z}, cc[3] = {out->c.x, out->c.y, out->c.z};
    sd_real lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
        sd_real e = sd_fabs(ax[k]) * out->half + out->radius * sd_sqrt(sd_max(SD_R(0.0), SD_R(1.0) - ax[k] * ax[k]));
        lo[k] = cc[k] - e;
        hi[k] = cc[k] + e;
    }
    out->blo = sd_v3(lo[0], lo[1], lo[2]);
    out->bhi = sd_v3(hi[0], hi[1], hi[2]);
    return SD_OK;
}

int sd_an_region_has(const sd_an_region *r, sd_vec3 x)
{
    switch (r->kind) {
    case SD_REGION_BOX:
        return x.x >= r->lo.x && x.x <= r->hi.x && x.y >= r->lo.y && x.y <= r->hi.y &&
               (r->lo.z == r->hi.z || (x.z >= r->lo.z && x.z <= r->hi.z));
    case SD_REGION_CYLINDER: {
        sd_vec3 d = sd_v3_sub(x, r->c);
        sd_real s = sd_v3_dot(d, r->a);
        if (r->half > 0 && sd_fabs(s) > r->half)
            return 0;
        sd_vec3 rad = sd_v3_sub(d, sd_v3_scale(r->a, s));
        return sd_v3_dot(rad, rad) <= r->radius * r->radius;
    }
    default:
        return 1;
    }
}

/* A 2D template: p in the body frame against the swept core. */
static int sd_an_inside2d(const sd_world *w, const sd_shape2d *s, sd_vec2 p)
{
    if (s->kind == SD_SHAPE2D_CIRCLE)
        return sd_v2_norm2(p) <= s->radius * s->radius;
    if (s->kind == SD_SHAPE2D_ELLIPSE && !(s->radius > 0))
        return p.x * p.x / (s->a.x * s->a.x) + p.y * p.y / (s->a.y * s->a.y) <= SD_R(1.0);
    sd_shape2d pt;
    memset(&pt, 0, sizeof pt);
    pt.kind = SD_SHAPE2D_CIRCLE; /* a point core, radius 0 */
    sd_convex2d a = {s, w->pool2d, sd_v2_zero(), SD_R(0.0)}, b = {&pt, NULL, p, SD_R(0.0)};
    sd_gjk2d_result g = sd_gjk2d_distance(&a, &b, sd_v2_zero());
    if (g.status == SD_GJK2D_TOUCHING || g.status == SD_GJK2D_OVERLAP)
        return 1;
    return g.distance <= s->radius;
}

int sd_an_inside(const sd_world *w, const sd_an_body *b, sd_vec3 p)
{
    sd_vec3 d = sd_v3_sub(p, b->x);
    if (sd_v3_dot(d, d) > b->bound * b->bound)
        return 0; /* beyond the bounding sphere: no shape reaches */
    if (b->shape < 0)
        return 1; /* a sphere (a circle) is its bounding sphere */
    if (w->dim2) {
        sd_real th = sd_quat_angle_z(b->q);
        return sd_an_inside2d(w, &w->shapes2d[b->shape], sd_v2_rot_inv(sd_v2(d.x, d.y), th));
    }
    const sd_shape *s = &w->shapes[b->shape];
    sd_vec3 pl = sd_quat_rotate_inv(b->q, d); /* principal frame */
    if (s->kind != SD_SHAPE_COMPOSITE)
        return sd_composite_point_inside(s, w->verts, w->planes, w->dtris, pl);
    for (uint32_t k = 0; k < s->ecount; ++k) {
        const sd_element *e = &w->elements[s->estart + k];
        sd_vec3 pe = sd_v3_sub(pl, e->x);
        if (sd_v3_dot(pe, pe) > e->bound * e->bound)
            continue;
        if (sd_composite_point_inside(&w->shapes[e->shape], w->verts, w->planes, w->dtris,
                                      sd_quat_rotate_inv(e->q, pe)))
            return 1;
    }
    return 0;
}

sd_real sd_an_top(const sd_world *w, const sd_an_body *b, sd_vec3 u)
{
    if (b->shape < 0)
        return sd_v3_dot(b->x, u) + b->bound;
    if (w->dim2) {
        const sd_shape2d *s = &w->shapes2d[b->shape];
        sd_real th = sd_quat_angle_z(b->q);
        sd_vec2 sp = sd_v2_rot(sd_shape2d_support(s, w->pool2d, sd_v2_rot_inv(sd_v2(u.x, u.y), th)), th);
        return b->x.x * u.x + b->x.y * u.y + sp.x * u.x + sp.y * u.y;
    }
    const sd_shape *s = &w->shapes[b->shape];
    sd_vec3 ul = sd_quat_rotate_inv(b->q, u);
    sd_real best;
    if (s->kind != SD_SHAPE_COMPOSITE) {
        best = sd_v3_dot(sd_shape_support(s, w->verts, ul), ul);
    } else {
        best = -SD_R(1e300);
        for (uint32_t k = 0; k < s->ecount; ++k) {
            const sd_element *e = &w->elements[s->estart + k];
            sd_vec3 ue = sd_quat_rotate_inv(e->q, ul);
            sd_real h = sd_v3_dot(e->x, ul) + sd_v3_dot(sd_shape_support(&w->shapes[e->shape], w->verts, ue), ue);
            best = sd_max(best, h);
        }
    }
    return sd_v3_dot(b->x, u) + best;
}

double sd_an_rot_energy(const sd_world *w, const sd_an_body *b)
{
    double m = (double)b->mass;
    if (!(m > 0))
        return 0.0;
    if (w->dim2) {
        double I = b->shape < 0 ? 0.5 * m * (double)(b->bound * b->bound)
                                : m * (double)w->shapes2d[b->shape].inertia / (double)w->shapes2d[b->shape].area;
        return 0.5 * I * (double)(b->w.z * b->w.z);
    }
    sd_vec3 wb = sd_quat_rotate_inv(b->q, b->w);
    sd_vec3 I;
    if (b->shape < 0) {
        sd_real i = SD_R(0.4) * b->mass * b->bound * b->bound;
        I = sd_v3(i, i, i);
    } else {
        const sd_shape *s = &w->shapes[b->shape];
        I = sd_v3_scale(s->inertia, b->mass / s->volume);
    }
    return 0.5 * ((double)(I.x * wb.x * wb.x) + (double)(I.y * wb.y * wb.y) + (double)(I.z * wb.z * wb.z));
}
