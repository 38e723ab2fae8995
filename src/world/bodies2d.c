/* bodies2d.c — the planar mode's shape templates and rigid bodies
 * (DESIGN.md rule 9; seed 002 §2).
 *
 * A 2D template is built once by src/shape/shape2d.c (area, polar moment,
 * centroid, bound) and its coefficients / vertices / control points are
 * copied into the world's pool of reals. A body stores the template index,
 * its mass and polar moment per unit thickness (1 m): m = rho * area,
 * I = rho * polar (kg/m^... times 1 m), held isotropic in inv_inertia so the
 * 3D helpers that read it (effective mass, energies) see I for rotation
 * about z. Bodies of a circle template become plain circles (shape -1), so
 * circle-circle contacts take the analytic sphere path of the engine.
 *
 * Invariant: in a 2D world every particle has z = 0, no velocity along z
 * and an orientation that is a rotation about z.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "world/world.h"

#define SD_COOKIE 0x5D5D

static const char *const sd_kind2d_names[] = {
#define SD_X_NAME2(e, name, doc) name,
    SD_SHAPE2D_KINDS(SD_X_NAME2)
#undef SD_X_NAME2
};

sd_shape2d_def sd_shape2d_def_default(void)
{
    sd_shape2d_def d;
    memset(&d, 0, sizeof d);
    d.kind = "circle";
    d.radius = 0; /* circles must set it; for the other kinds it is a rounding */
    d.cookie = SD_COOKIE;
    return d;
}

int sd_world_add_shape2d(sd_world *w, const char *name, const sd_shape2d_def *def, sd_error *err)
{
    if (!w) {
        sd_error_null(err, "sd_world_add_shape2d", "world");
        return -1;
    }
    if (!def || def->cookie != SD_COOKIE) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "shapes", "2D shape def not made by sd_shape2d_def_default");
        return -1;
    }
    if (!w->dim2) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "type", "2D shape '%s' needs simulation.dimension 2",
                     def->kind ? def->kind : "");
        return -1;
    }
    if (sd_world_check_shape_name(w, name, err) != SD_OK)
        return -1;
    int kind = sd_shape2d_kind_from_name(def->kind);
    if (kind < 0) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "type", "unknown 2D shape kind '%s'", def->kind ? def->kind : "");
        return -1;
    }
    if (def->point_count > SD_SHAPE2D_MAX_POINTS) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "points", "a 2D shape may have at most %d points, got %zu",
                     SD_SHAPE2D_MAX_POINTS, def->point_count);
        return -1;
    }
    if (def->order < 0 || def->order > SD_SHAPE2D_MAX_ORDER) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "order", "expected a Fourier order in [0, %d], got %d",
                     SD_SHAPE2D_MAX_ORDER, def->order);
        return -1;
    }
    /* fixed host scratch: the desc's points and coefficients as sd_real */
    static const size_t cap = 2 * SD_SHAPE2D_MAX_POINTS + 2 * SD_SHAPE2D_MAX_ORDER + 1;
    sd_vec2 pts[SD_SHAPE2D_MAX_POINTS];
    sd_real fa[SD_SHAPE2D_MAX_ORDER + 1], fb[SD_SHAPE2D_MAX_ORDER + 1];
    sd_shape2d_desc desc = sd_shape2d_desc_default();
    desc.kind = kind;
    desc.radius = (sd_real)def->radius;
    desc.a = sd_v2((sd_real)def->semi_axes[0], (sd_real)def->semi_axes[1]);
    if (def->points)
        for (size_t k = 0; k < def->point_count; ++k)
            pts[k] = sd_v2((sd_real)def->points[2 * k], (sd_real)def->points[2 * k + 1]);
    desc.points = def->points ? pts : NULL;
    desc.point_count = def->points ? def->point_count : 0;
    if (kind == SD_SHAPE2D_FOURIER) {
        if (!def->fourier_a || (def->order > 0 && !def->fourier_b)) {
            sd_error_set(err, SD_ERR_INPUT, "", 0, "fourier", "a Fourier shape needs a_0..a_N and b_1..b_N");
            return -1;
        }
        for (int k = 0; k <= def->order; ++k)
            fa[k] = (sd_real)def->fourier_a[k];
        for (int k = 0; k < def->order; ++k)
            fb[k] = (sd_real)def->fourier_b[k];
        desc.fs_a = fa;
        desc.fs_b = def->order > 0 ? fb : NULL;
        desc.order = def->order;
    }
    sd_real *pool = sd_realloc(w->pool2d, (w->pool2d_count + cap) * sizeof *pool);
    if (pool)
        w->pool2d = pool;
    sd_shape2d *shapes = sd_realloc(w->shapes2d, (w->shape2d_count + 1) * sizeof *shapes);
    if (shapes)
        w->shapes2d = shapes;
    char(*names)[64] = sd_realloc(w->shape2d_names, (w->shape2d_count + 1) * sizeof *names);
    if (names)
        w->shape2d_names = names;
    if (!pool || !shapes || !names) {
        sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory adding shape '%s'", name);
        return -1;
    }
    sd_shape2d s;
    size_t used = 0;
    if (sd_shape2d_make(&desc, &s, w->pool2d + w->pool2d_count, cap, &used, err) != SD_OK)
        return -1;
    s.start = (uint32_t)w->pool2d_count;
    w->pool2d_count += used;
    w->shapes2d[w->shape2d_count] = s;
    snprintf(w->shape2d_names[w->shape2d_count], 64, "%s", name);
    w->prepared = 0;
    return (int)w->shape2d_count++;
}

sd_status sd_world_get_shape2d(const sd_world *w, size_t k, sd_shape_info *out)
{
    if (k >= w->shape2d_count)
        return SD_ERR_INPUT;
    const sd_shape2d *s = &w->shapes2d[k];
    memset(out, 0, sizeof *out);
    out->name = w->shape2d_names[k];
    out->kind = sd_kind2d_names[s->kind];
    out->volume = (double)s->area; /* per unit thickness: m^2 x 1 m */
    out->bounding_radius = (double)s->bound;
    out->equivalent_radius = (double)s->eq_radius;
    out->inertia.x = out->inertia.y = out->inertia.z = (double)s->inertia;
    out->center_of_mass.x = (double)s->given_com.x;
    out->center_of_mass.y = (double)s->given_com.y;
    out->rounding = (double)s->radius;
    out->vertex_count = s->count;
    return SD_OK;
}

sd_status sd_world_add_bodies2d(sd_world *w, size_t n, const sd_body_def *defs, sd_error *err)
{
    for (size_t k = 0; k < n; ++k) {
        const sd_body_def *d = &defs[k];
        if (d->shape < 0 || (size_t)d->shape >= w->shape2d_count)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "shape", "body %zu: unknown shape index %d", k, d->shape);
        if (d->material < 0 || (size_t)d->material >= w->material_count)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "material", "body %zu: unknown material index %d", k,
                                d->material);
        if (!isfinite(d->position.x) || !isfinite(d->position.y))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "position", "body %zu: position is not finite", k);
        if (d->position.z != 0 || d->velocity.z != 0 || d->angular_velocity.x != 0 || d->angular_velocity.y != 0 ||
            d->orientation[1] != 0 || d->orientation[2] != 0)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "position",
                                "body %zu: dimension 2 needs z = 0, velocity z = 0 and rotation about z only", k);
    }
    sd_particles *p = &w->p;
    if (sd_particles_reserve(p, p->n + n))
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory adding %zu bodies", n);
    int any_shape = 0;
    for (size_t k = 0; k < n; ++k) {
        const sd_body_def *d = &defs[k];
        const sd_shape2d *s = &w->shapes2d[d->shape];
        size_t e = p->n + k;
        sd_real rho = (sd_real)w->materials[d->material].def.density;
        /* per unit thickness (1 m): m = rho A, I = rho J (J polar moment per unit density) */
        sd_real mass = rho * s->area, inertia = rho * s->inertia;
        int circle = s->kind == SD_SHAPE2D_CIRCLE;
        sd_quat q = sd_quat_make((sd_real)d->orientation[0], SD_R(0.0), SD_R(0.0), (sd_real)d->orientation[3]);
        sd_particles_init(p, e, w->next_id++); /* the defaults (world.h), then what differs */
        p->x[e] = sd_v3((sd_real)d->position.x, (sd_real)d->position.y, SD_R(0.0));
        p->v[e] = sd_v3((sd_real)d->velocity.x, (sd_real)d->velocity.y, SD_R(0.0));
        p->w[e] = sd_v3(SD_R(0.0), SD_R(0.0), (sd_real)d->angular_velocity.z);
        p->q[e] = circle ? sd_quat_identity() : sd_quat_normalize(q); /* zero: identity */
        p->radius[e] = circle ? s->radius : s->bound;
        p->inv_mass[e] = SD_R(1.0) / mass;
        p->inv_inertia[e] = sd_v3(SD_R(1.0) / inertia, SD_R(1.0) / inertia, SD_R(1.0) / inertia);
        p->x_ref[e] = p->x[e];
        p->q_ref[e] = p->q[e];
        p->material[e] = d->material;
        p->shape[e] = circle ? -1 : d->shape;
        any_shape |= !circle;
    }
    p->n += n;
    if (any_shape)
        w->has_shapes = 1;
    w->dirty = 1;
    w->prepared = 0;
    return SD_OK;
}

size_t sd_world_narrow_stats2d(const sd_world *w, sd_narrow_stats *out, size_t max)
{
    size_t m = 0;
    for (int a = 0; a < SD_SHAPE2D_KIND_COUNT; ++a)
        for (int b = a; b < SD_SHAPE2D_KIND_COUNT; ++b) {
            const long long *t = w->narrow2d[a][b];
            if (t[0] == 0)
                continue;
            if (m < max) {
                out[m].kind_a = sd_kind2d_names[a];
                out[m].kind_b = sd_kind2d_names[b];
                out[m].evaluations = t[0];
                out[m].iterations = 0;
                out[m].support_calls = t[2];
                out[m].contacts = t[1];
                out[m].contact_support_calls = t[3];
            }
            ++m;
        }
    return m;
}
