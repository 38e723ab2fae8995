/* bodies.c — shape templates and the rigid bodies made of them.
 *
 * A template is built once (src/shape: exact mass properties, principal
 * frame); a body stores only its template index, its mass and principal
 * moments (density times the template's), and its bounding radius for the
 * broad phase.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "shape/shape_make.h"
#include "world/world.h"

#define SD_COOKIE 0x5D5D

sd_shape_desc sd_shape_desc_default(void)
{
    sd_shape_desc d;
    memset(&d, 0, sizeof d);
    d.kind = "sphere";
    d.size.x = d.size.y = d.size.z = 1e-3;
    d.scale = 1.0;
    d.cookie = SD_COOKIE;
    return d;
}

int sd_world_find_shape(const sd_world *w, const char *name)
{
    if (!w)
        return -1;
    if (w->dim2) {
        for (size_t k = 0; k < w->shape2d_count; ++k)
            if (name && strcmp(w->shape2d_names[k], name) == 0)
                return (int)k;
        return -1;
    }
    for (size_t k = 0; k < w->shape_count; ++k)
        if (name && strcmp(w->shape_names[k], name) == 0)
            return (int)k;
    return -1;
}

/* A new shape's name: 1 to 63 characters, not taken (3D and 2D shapes). */
sd_status sd_world_check_shape_name(const sd_world *w, const char *name, sd_error *err)
{
    if (!name || !name[0] || strlen(name) >= 64)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "name", "a shape needs a name of 1 to 63 characters");
    if (sd_world_find_shape(w, name) >= 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "name", "shape '%s' defined twice", name);
    return SD_OK;
}

size_t sd_world_shape_count(const sd_world *w) { return !w ? 0 : w->dim2 ? w->shape2d_count : w->shape_count; }

int sd_world_add_shape(sd_world *w, const char *name, const sd_shape_desc *desc, sd_error *err)
{
    if (!w) {
        sd_error_null(err, "sd_world_add_shape", "world");
        return -1;
    }
    if (!desc || desc->cookie != SD_COOKIE) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "shapes", "shape desc not made by sd_shape_desc_default");
        return -1;
    }
    if (w->dim2) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "type", "shape kind '%s' is 3D; dimension 2 takes circle, ellipse, "
                     "polygon, polybezier or fourier", desc->kind ? desc->kind : "");
        return -1;
    }
    if (sd_world_check_shape_name(w, name, err) != SD_OK)
        return -1;
    int kind = sd_shape_kind_from_name(desc->kind);
    if (kind < 0 || kind >= SD_SHAPE_KIND_COUNT) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "type", "unknown shape kind '%s'", desc->kind ? desc->kind : "");
        return -1;
    }
    if (desc->vertex_count > 0 && !desc->vertices) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "vertices", "%zu vertices given, but the vertex array is NULL",
                     desc->vertex_count);
        return -1;
    }
    if (desc->vertex_count > SD_SHAPE_MAX_VERTICES) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "vertices", "a polyhedron may have at most %d vertices, got %zu",
                     SD_SHAPE_MAX_VERTICES, desc->vertex_count);
        return -1;
    }
    sd_vec3 in[SD_SHAPE_MAX_VERTICES];
    for (size_t k = 0; k < desc->vertex_count; ++k)
        in[k] = sd_v3((sd_real)desc->vertices[k].x, (sd_real)desc->vertices[k].y, (sd_real)desc->vertices[k].z);
    sd_shape_def def = sd_shape_def_default();
    def.kind = kind;
    def.size = sd_v3((sd_real)desc->size.x, (sd_real)desc->size.y, (sd_real)desc->size.z);
    def.rounding = (sd_real)desc->rounding;
    def.margin = (sd_real)desc->margin;
    def.scale = (sd_real)desc->scale;
    def.vertices = in;
    def.vertex_count = desc->vertex_count;

    /* room for the core's vertices in the pool: with a margin the shrunk
     * core of a polyhedron can have more corners than its input, one per
     * face of the dual hull of its F <= 2V - 4 face planes: 2F - 4 <= 4V */
    size_t room = 4 * desc->vertex_count + 1;
    sd_vec3 *pool = sd_realloc(w->verts, (w->vert_count + room) * sizeof *pool);
    sd_shape *shapes = sd_realloc(w->shapes, (w->shape_count + 1) * sizeof *shapes);
    char(*names)[64] = sd_realloc(w->shape_names, (w->shape_count + 1) * sizeof *names);
    sd_real *req = sd_realloc(w->shape_req, (w->shape_count + 1) * sizeof *req);
    if (req)
        w->shape_req = req;
    sd_vec3 *com = sd_realloc(w->shape_com, (w->shape_count + 1) * sizeof *com);
    if (com)
        w->shape_com = com;
    if (pool)
        w->verts = pool;
    if (shapes)
        w->shapes = shapes;
    if (names)
        w->shape_names = names;
    if (!pool || !shapes || !names || !req || !com) {
        sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory adding shape '%s'", name);
        return -1;
    }
    size_t used = 0;
    sd_shape s;
    if (sd_shape_make(&def, &s, w->verts + w->vert_count, room, &used, err) != SD_OK)
        return -1;
    s.vstart = (uint32_t)w->vert_count;
    s.vcount = (uint32_t)used;
    if (s.kind == SD_SHAPE_POLYHEDRON) {
        /* welded face planes and dual triangles (the exact overlap volume's
         * input), next to the vertex pool: at most 2 vcount planes, 4 vcount
         * dual triangles */
        sd_plane *pl = sd_realloc(w->planes, (w->plane_count + 2 * used) * sizeof *pl);
        if (pl)
            w->planes = pl;
        sd_dtri *dt = sd_realloc(w->dtris, (w->dtri_count + 4 * used) * sizeof *dt);
        if (dt)
            w->dtris = dt;
        if (!pl || !dt) {
            sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory adding shape '%s'", name);
            return -1;
        }
        size_t np = 0, nt = 0;
        if (sd_shape_faces(&s, w->verts, w->planes + w->plane_count, 2 * used, &np,
                           w->dtris + w->dtri_count, 4 * used, &nt, err) != SD_OK)
            return -1;
        s.fstart = (uint32_t)w->plane_count;
        s.tstart = (uint32_t)w->dtri_count;
        w->plane_count += np;
        w->dtri_count += nt;
    }
    w->vert_count += used;
    /* where the centre of mass sits in the frame the shape was given in */
    w->shape_com[w->shape_count] = s.given_com;
    w->shapes[w->shape_count] = s;
    w->shape_req[w->shape_count] = (sd_real)cbrt(3.0 * (double)s.volume / (4.0 * SD_PI_D));
    snprintf(w->shape_names[w->shape_count], 64, "%s", name);
    w->prepared = 0;
    return (int)w->shape_count++;
}

sd_status sd_world_get_shape(const sd_world *w, size_t k, sd_shape_info *out)
{
    if (!w || !out)
        return SD_ERR_INPUT;
    if (w->dim2)
        return sd_world_get_shape2d(w, k, out);
    if (k >= w->shape_count)
        return SD_ERR_INPUT;
    const sd_shape *s = &w->shapes[k];
    out->name = w->shape_names[k];
    out->kind = sd_shape_kind_name(s->kind);
    out->volume = (double)s->volume;
    out->bounding_radius = (double)s->bound;
    out->equivalent_radius = cbrt(3.0 * (double)s->volume / (4.0 * SD_PI_D));
    out->inertia.x = (double)s->inertia.x;
    out->inertia.y = (double)s->inertia.y;
    out->inertia.z = (double)s->inertia.z;
    out->center_of_mass.x = w->shape_com[k].x;
    out->center_of_mass.y = w->shape_com[k].y;
    out->center_of_mass.z = w->shape_com[k].z;
    out->rounding = (double)s->radius;
    out->vertex_count = s->vcount;
    out->face_count = s->fcount;
    out->overlap_face_limit = SD_OVERLAP_MAX_PLANES;
    for (int a = 0; a < 3; ++a) {
        /* column a of R(given_q): principal axis a in the given frame */
        sd_vec3 e = sd_quat_rotate(s->given_q, sd_v3(a == 0, a == 1, a == 2));
        out->axes[a].x = (double)e.x;
        out->axes[a].y = (double)e.y;
        out->axes[a].z = (double)e.z;
    }
    out->element_count = s->kind == SD_SHAPE_COMPOSITE ? s->ecount : 0;
    out->lattice = s->kind == SD_SHAPE_COMPOSITE ? s->mass_lattice : 0;
    out->lattice_error = s->kind == SD_SHAPE_COMPOSITE ? (double)s->mass_error : 0.0;
    return SD_OK;
}

sd_status sd_world_add_bodies(sd_world *w, size_t n, const sd_body_def *defs, sd_error *err)
{
    if (!w)
        return sd_error_null(err, "sd_world_add_bodies", "world");
    if (n > 0 && !defs)
        return sd_error_null(err, "sd_world_add_bodies", "defs");
    if (w->dim2)
        return sd_world_add_bodies2d(w, n, defs, err);
    for (size_t k = 0; k < n; ++k) {
        const sd_body_def *d = &defs[k];
        if (d->shape < 0 || (size_t)d->shape >= w->shape_count)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "shape", "body %zu: unknown shape index %d", k, d->shape);
        if (d->material < 0 || (size_t)d->material >= w->material_count)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "material", "body %zu: unknown material index %d", k,
                                d->material);
        if (!isfinite(d->position.x) || !isfinite(d->position.y) || !isfinite(d->position.z))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "position", "body %zu: position is not finite", k);
    }
    sd_particles *p = &w->p;
    if (sd_particles_reserve(p, p->n + n))
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory adding %zu bodies", n);
    for (size_t k = 0; k < n; ++k) {
        const sd_body_def *d = &defs[k];
        const sd_shape *s = &w->shapes[d->shape];
        size_t e = p->n + k;
        sd_real rho = (sd_real)w->materials[d->material].def.density;
        sd_real mass = rho * s->volume;
        sd_quat q = sd_quat_make((sd_real)d->orientation[0], (sd_real)d->orientation[1], (sd_real)d->orientation[2],
                                 (sd_real)d->orientation[3]);
        sd_particles_init(p, e, w->next_id++); /* the defaults (world.h), then what differs */
        p->x[e] = sd_v3((sd_real)d->position.x, (sd_real)d->position.y, (sd_real)d->position.z);
        p->v[e] = sd_v3((sd_real)d->velocity.x, (sd_real)d->velocity.y, (sd_real)d->velocity.z);
        p->w[e] = sd_v3((sd_real)d->angular_velocity.x, (sd_real)d->angular_velocity.y,
                        (sd_real)d->angular_velocity.z);
        p->q[e] = sd_quat_normalize(q); /* a zero quaternion becomes the identity */
        p->radius[e] = s->bound;
        p->inv_mass[e] = SD_R(1.0) / mass;
        p->inv_inertia[e] = sd_v3(SD_R(1.0) / (rho * s->inertia.x), SD_R(1.0) / (rho * s->inertia.y),
                                  SD_R(1.0) / (rho * s->inertia.z));
        p->x_ref[e] = p->x[e];
        p->q_ref[e] = p->q[e];
        p->material[e] = d->material;
        p->shape[e] = d->shape;
    }
    p->n += n;
    w->has_shapes = 1;
    w->dirty = 1;
    w->prepared = 0;
    return SD_OK;
}

size_t sd_world_narrow_stats(const sd_world *w, sd_narrow_stats *out, size_t max)
{
    if (!w)
        return 0;
    if (!out)
        max = 0; /* only the count */
    if (w->dim2)
        return sd_world_narrow_stats2d(w, out, max);
    size_t m = 0;
    for (int a = 0; a < SD_SHAPE_KIND_COUNT; ++a)
        for (int b = a; b < SD_SHAPE_KIND_COUNT; ++b) {
            const long long *t = w->narrow[a][b];
            if (t[0] == 0)
                continue;
            if (m < max) {
                out[m].kind_a = sd_shape_kind_name(a);
                out[m].kind_b = sd_shape_kind_name(b);
                out[m].evaluations = t[0];
                out[m].iterations = t[1];
                out[m].support_calls = t[2];
                out[m].contacts = 0;
                out[m].contact_support_calls = 0;
            }
            ++m;
        }
    return m;
}
