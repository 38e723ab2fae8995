/* scene_hash.c — the hash of what a scene defines for the physics, in
 * parts (issue 31): the one test that a checkpoint is restarted with the
 * scene that wrote it (world/snapshot.c), and that every rank of an MPI
 * run built the same world (mpi/drive.c).
 *
 * Invariant: every input that changes a trajectory enters exactly one
 * part; nothing that changes during a run does (a checkpoint's hash is
 * taken at its step, a restart's at step 0), so walls enter with the
 * geometry they were added with (sd_wall.geom0), not the moved one, and
 * the insertions and outlets with their definitions, not their counters.
 * Left out on purpose: the thread count, backend and device (same bits,
 * docs/checkpoints.md), the overlap guard's limit (it stops a run, never
 * changes one), the start particles (a restart takes the checkpoint's),
 * output and analysis. Values are hashed field by field (struct padding
 * never enters) and -0 as 0.
 */
#include <stdio.h>
#include <string.h>

#include "world/mesh.h"
#include "world/process.h"
#include "world/snapshot.h"
#include "world/world.h"

static const char *const sd_scene_part_docs[SD_SCENE_PART_COUNT] = {
#define SD_X_PART(NAME, doc) doc,
    SD_SCENE_PARTS(SD_X_PART)
#undef SD_X_PART
};

const char *sd_scene_part_doc(size_t k) { return k < SD_SCENE_PART_COUNT ? sd_scene_part_docs[k] : "?"; }

static uint64_t sd_hash_f64(uint64_t h, double x)
{
    if (x == 0)
        x = 0; /* -0 and 0 alike */
    return sd_fnv1a(h, &x, sizeof x);
}

static uint64_t sd_hash_i64(uint64_t h, int64_t x) { return sd_fnv1a(h, &x, sizeof x); }

static uint64_t sd_hash_str(uint64_t h, const char *s) { return sd_fnv1a(h, s ? s : "", s ? strlen(s) + 1 : 1); }

static uint64_t sd_hash_v3d(uint64_t h, sd_v3d v)
{
    return sd_hash_f64(sd_hash_f64(sd_hash_f64(h, v.x), v.y), v.z);
}

static uint64_t sd_hash_v3(uint64_t h, sd_vec3 v)
{
    return sd_hash_f64(sd_hash_f64(sd_hash_f64(h, (double)v.x), (double)v.y), (double)v.z);
}

static uint64_t sd_hash_q(uint64_t h, sd_quat q)
{
    return sd_hash_f64(sd_hash_f64(sd_hash_f64(sd_hash_f64(h, (double)q.w), (double)q.x), (double)q.y), (double)q.z);
}

static uint64_t sd_hash_reals(uint64_t h, const double *v, size_t n)
{
    for (size_t j = 0; j < n; ++j)
        h = sd_hash_f64(h, v[j]);
    return h;
}

static uint64_t sd_hash_settings(const sd_world *w)
{
    const sd_world_def *d = &w->def;
    uint64_t h = SD_FNV_BASIS;
    h = sd_hash_i64(h, d->dimension);
    h = sd_hash_f64(h, d->dt);
    h = sd_hash_v3d(h, d->gravity);
    h = sd_hash_i64(h, (int64_t)d->seed);
    h = sd_hash_i64(h, d->law);
    h = sd_hash_f64(h, d->skin);
    h = sd_hash_i64(h, d->solver);
    h = sd_hash_f64(h, d->local_damping);
    h = sd_hash_i64(h, d->periodic);
    h = sd_hash_v3d(h, d->domain_lo);
    h = sd_hash_v3d(h, d->domain_hi);
    return sd_hash_i64(h, d->multi_contact);
}

static uint64_t sd_hash_materials(const sd_world *w)
{
    uint64_t h = sd_hash_i64(SD_FNV_BASIS, (int64_t)w->material_count);
    for (size_t k = 0; k < w->material_count; ++k) {
        const sd_material_def *m = &w->materials[k].def;
        h = sd_hash_str(h, w->materials[k].name);
        double v[] = {m->density, m->youngs_modulus, m->poisson_ratio, m->restitution, m->friction,
                      m->rolling_friction, m->stiffness, m->tangential_stiffness_ratio, m->damping,
                      m->volume_stiffness, m->volume_face_omega_dt};
        h = sd_hash_reals(h, v, sizeof v / sizeof v[0]);
    }
    h = sd_hash_i64(h, (int64_t)w->interaction_count);
    for (size_t k = 0; k < w->interaction_count; ++k) {
        const sd_interaction *it = &w->interactions[k];
        double v[] = {it->def.restitution, it->def.friction, it->def.rolling_friction, it->def.stiffness,
                      it->def.damping, it->def.volume_stiffness};
        h = sd_hash_i64(sd_hash_i64(sd_hash_i64(h, it->a), it->b), it->def.law);
        h = sd_hash_reals(h, v, sizeof v / sizeof v[0]);
    }
    return h;
}

/* templates: names, kinds, sizes, mass properties and the pools their
 * geometry lives in (arrays of reals: no padding) */
static uint64_t sd_hash_shapes(const sd_world *w)
{
    uint64_t h = sd_hash_i64(SD_FNV_BASIS, (int64_t)w->shape_count);
    for (size_t k = 0; k < w->shape_count; ++k) {
        const sd_shape *s = &w->shapes[k];
        h = sd_hash_str(h, w->shape_names[k]);
        h = sd_hash_f64(h, (double)w->shape_req[k]);
        h = sd_hash_v3(h, w->shape_com[k]);
        h = sd_hash_i64(sd_hash_i64(h, s->kind), (int64_t)s->ecount);
        h = sd_hash_f64(sd_hash_f64(sd_hash_f64(h, (double)s->radius), (double)s->volume), (double)s->bound);
        h = sd_hash_v3(sd_hash_v3(h, s->a), s->inertia);
    }
    h = sd_fnv1a(h, w->verts, w->vert_count * sizeof *w->verts);
    h = sd_hash_i64(h, (int64_t)w->plane_count);
    h = sd_hash_i64(h, (int64_t)w->element_count);
    for (size_t k = 0; k < w->element_count; ++k) {
        const sd_element *e = &w->elements[k];
        h = sd_hash_q(sd_hash_v3(sd_hash_i64(h, e->shape), e->x), e->q);
    }
    h = sd_hash_i64(h, (int64_t)w->shape2d_count);
    for (size_t k = 0; k < w->shape2d_count; ++k)
        h = sd_hash_str(h, w->shape2d_names[k]);
    return sd_fnv1a(h, w->pool2d, w->pool2d_count * sizeof *w->pool2d);
}

/* every wall: name, kind, material, the geometry it was added with, its
 * prescribed or servo motion and a drum's spin */
static uint64_t sd_hash_walls(const sd_world *w)
{
    uint64_t h = sd_hash_i64(SD_FNV_BASIS, (int64_t)w->wall_count);
    for (size_t k = 0; k < w->wall_count; ++k) {
        const sd_wall *wl = &w->walls[k];
        const sd_wall_geom *g = &wl->geom0;
        const sd_wall_motion_def *m = &wl->motion;
        h = sd_hash_str(h, wl->name);
        h = sd_hash_i64(sd_hash_i64(sd_hash_i64(h, g->kind), wl->material), (int64_t)g->open_faces);
        h = sd_hash_v3(sd_hash_v3(sd_hash_v3(sd_hash_v3(h, g->point), g->normal), g->lo), g->hi);
        h = sd_hash_v3(sd_hash_v3(sd_hash_q(h, g->q), g->trans), g->centre);
        h = sd_hash_i64(h, g->mesh);
        h = sd_hash_i64(h, wl->moving);
        h = sd_hash_v3d(h, m->velocity);
        double v[] = {m->move_start, m->move_end, m->servo_stress, m->servo_start, m->servo_end, m->servo_gain,
                      m->servo_max_speed, wl->drum_w0, wl->drum_start, wl->drum_ramp};
        h = sd_hash_reals(h, v, sizeof v / sizeof v[0]);
    }
    return h;
}

/* every mesh wall: its prepared facets (the file, scale, position,
 * rotation and side made them), their plane groups and its motion with a
 * table's rows */
static uint64_t sd_hash_meshes(const sd_world *w)
{
    uint64_t h = sd_hash_i64(SD_FNV_BASIS, (int64_t)w->mesh_count);
    for (size_t k = 0; k < w->mesh_count; ++k) {
        const sd_mesh_store *s = &w->meshes[k];
        const sd_trimesh *m = &s->m;
        const sd_mesh_motion_def *mo = &s->motion;
        h = sd_hash_i64(h, s->wall);
        h = sd_hash_i64(sd_hash_i64(h, (int64_t)m->vertex_count), (int64_t)m->triangle_count);
        h = sd_fnv1a(h, m->vertices, m->vertex_count * sizeof *m->vertices);
        h = sd_fnv1a(h, m->triangles, m->triangle_count * sizeof *m->triangles);
        h = sd_hash_i64(h, (int64_t)m->group_count);
        h = sd_fnv1a(h, m->group_normal, m->group_count * sizeof *m->group_normal);
        h = sd_fnv1a(h, m->group_offset, m->group_count * sizeof *m->group_offset);
        h = sd_hash_i64(h, mo->kind);
        h = sd_hash_v3d(sd_hash_v3d(sd_hash_v3d(h, mo->velocity), mo->axis_point), mo->axis);
        h = sd_hash_f64(sd_hash_f64(sd_hash_f64(h, mo->rpm), mo->start), mo->ramp);
        h = sd_hash_i64(h, (int64_t)mo->table_rows);
        if (s->table)
            h = sd_hash_reals(h, s->table, 5 * mo->table_rows);
    }
    return h;
}

static uint64_t sd_hash_region(uint64_t h, const sd_region_def *r, const sd_region_mesh *mesh)
{
    h = sd_hash_i64(h, r->kind);
    h = sd_hash_v3d(sd_hash_v3d(sd_hash_v3d(sd_hash_v3d(h, r->lo), r->hi), r->center), r->axis);
    h = sd_hash_f64(sd_hash_f64(h, r->radius), r->length);
    if (mesh) {
        h = sd_hash_i64(h, (int64_t)mesh->count);
        if (mesh->tri)
            h = sd_hash_reals(h, &mesh->tri[0][0], 9 * mesh->count);
    }
    return h;
}

static uint64_t sd_hash_size(uint64_t h, const sd_size_def *s)
{
    h = sd_hash_i64(sd_hash_i64(sd_hash_i64(h, s->kind), s->classes), s->by_mass);
    double v[] = {s->a, s->b, s->min, s->max};
    h = sd_hash_reals(h, v, 4);
    int nc = s->classes > 0 && s->classes <= SD_SIZE_CLASSES_MAX ? s->classes : 0;
    h = sd_hash_reals(h, s->lo, (size_t)nc);
    h = sd_hash_reals(h, s->hi, (size_t)nc);
    return sd_hash_reals(h, s->fraction, (size_t)nc);
}

/* the insertions' definitions: region (a mesh region's triangles),
 * mix, size laws, count or mass, rates, start, velocity, attempts */
static uint64_t sd_hash_insertions(const sd_world *w)
{
    const sd_process *p = w->process;
    size_t n = p ? p->insertion_count : 0;
    uint64_t h = sd_hash_i64(SD_FNV_BASIS, (int64_t)n);
    for (size_t k = 0; k < n && k < SD_INSERTIONS_MAX; ++k) {
        const sd_insertion *in = &p->insertions[k];
        const sd_insert_def *d = &in->def;
        const sd_region_mesh *rm = in->mesh >= 0 && in->mesh < SD_INSERTIONS_MAX && w->region_meshes
                                       ? &w->region_meshes->slot[in->mesh]
                                       : NULL;
        h = sd_hash_str(h, in->name);
        h = sd_hash_region(h, &d->region, rm);
        h = sd_hash_i64(sd_hash_i64(h, d->entry_count), d->mix_by_mass);
        for (int e = 0; e < d->entry_count && e < SD_INSERT_MIX_MAX; ++e) {
            const sd_insert_entry *en = &d->entries[e];
            h = sd_hash_i64(sd_hash_i64(sd_hash_i64(h, en->shape), en->material), en->size_classes);
            h = sd_hash_size(sd_hash_f64(h, en->fraction), &en->size);
        }
        h = sd_hash_i64(h, (int64_t)d->count);
        double v[] = {d->mass, d->rate, d->mass_rate, d->start, d->velocity_jitter};
        h = sd_hash_reals(h, v, sizeof v / sizeof v[0]);
        h = sd_hash_v3d(h, d->velocity);
        h = sd_hash_i64(sd_hash_i64(h, d->random_orientation), d->attempts);
    }
    return h;
}

static uint64_t sd_hash_outlets(const sd_world *w)
{
    const sd_process *p = w->process;
    size_t n = p ? p->outlet_count : 0;
    uint64_t h = sd_hash_i64(SD_FNV_BASIS, (int64_t)n);
    for (size_t k = 0; k < n && k < SD_OUTLETS_MAX; ++k) {
        const sd_outlet_state *o = &p->outlets[k];
        h = sd_hash_str(h, o->name);
        h = sd_hash_region(h, &o->def.region, NULL);
        h = sd_hash_i64(sd_hash_f64(h, o->def.open_at), o->def.check_every);
    }
    return h;
}

void sd_world_scene_parts(const sd_world *w, uint64_t part[SD_SCENE_PART_COUNT])
{
    part[SD_SCENE_SETTINGS] = sd_hash_settings(w);
    part[SD_SCENE_MATERIALS] = sd_hash_materials(w);
    part[SD_SCENE_SHAPES] = sd_hash_shapes(w);
    part[SD_SCENE_WALLS] = sd_hash_walls(w);
    part[SD_SCENE_MESHES] = sd_hash_meshes(w);
    part[SD_SCENE_INSERTIONS] = sd_hash_insertions(w);
    part[SD_SCENE_OUTLETS] = sd_hash_outlets(w);
}

uint64_t sd_world_scene_hash(const sd_world *w)
{
    uint64_t part[SD_SCENE_PART_COUNT];
    sd_world_scene_parts(w, part);
    return sd_fnv1a(SD_FNV_BASIS, part, sizeof part);
}

size_t sd_scene_parts_differ(const uint64_t a[SD_SCENE_PART_COUNT], const uint64_t b[SD_SCENE_PART_COUNT],
                             char *buf, size_t size)
{
    size_t n = 0, len = 0;
    if (size)
        buf[0] = '\0';
    for (size_t k = 0; k < SD_SCENE_PART_COUNT; ++k) {
        if (a[k] == b[k])
            continue;
        if (len < size) {
            int c = snprintf(buf + len, size - len, "%s%s", n ? ", " : "", sd_scene_part_docs[k]);
            len += c > 0 ? (size_t)c : 0;
        }
        ++n;
    }
    return n;
}

uint64_t sd_world_particles_hash(const sd_world *w)
{
    const sd_particles *p = &w->p;
    size_t n = p->n;
    uint64_t h = sd_hash_i64(SD_FNV_BASIS, (int64_t)n);
#define SD_X_FIELD(type, name, ...) h = sd_fnv1a(h, p->name, n * sizeof(type));
    SD_PARTICLE_FIELDS(SD_X_FIELD)
#undef SD_X_FIELD
    return h;
}
