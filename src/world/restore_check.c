/* restore_check.c — what a checkpoint restore (world/snapshot.c) checks of
 * the values it puts back, before anything uses them (issue 31).
 *
 * A checkpoint's checksums say the file is the one written, not that its
 * content is sane: anyone can recompute them. So every restored value is
 * held to the range its use needs, and a value the scene defines (and its
 * hash covers) is taken from the scene, never from the file:
 *  - before the copy (sd_restore_check_items): every real is finite;
 *  - sd_restore_keep: the scene-built world's own walls' kinds and
 *    motions and its insertion and outlet definitions, kept aside;
 *  - after the copy (sd_restore_check_world): those put back, and the
 *    world's values (step, time, dt, gravity, skin, counters), every
 *    particle (shape and material indices, radius, position, mass,
 *    orientation, id), the walls' geometry, the meshes' poses and bin size, and the
 *    insertion and outlet counters checked against the scene.
 * Any failure is one SD_ERR_INPUT naming the dataset; the world is then
 * not usable (the caller discards it), and nothing downstream (the
 * solver's resumed checks, the first step) has seen the bad value.
 */
#include "world/restore_check.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "world/mesh.h"
#include "world/process.h"
#include "world/world.h"

/* m: beyond this a radius's cube (volume, mass) overflows a double */
#define SD_RESTORE_LENGTH_MAX 1e100
/* a mesh's facet bins, made at an edge h in [h_min, 4 h_min] with h_min
 * the largest particle reach (world/mesh.h), are refused below h_min / 64
 * of the restored particles (an insertion since the last rebuild may have
 * brought larger ones): finer bins are a forgery, and would hang the
 * binning */
#define SD_RESTORE_BIN_SLACK 64.0

static sd_status sd_restore_bad(sd_error *err, const char *dataset, const char *fmt, size_t row, double value)
{
    return sd_error_set(err, SD_ERR_INPUT, "", 0, dataset, "the checkpoint's '%s' row %zu is %g: %s", dataset, row,
                        value, fmt);
}

sd_status sd_restore_check_items(const sd_snapshot *s, sd_error *err)
{
    for (size_t k = 0; k < s->n; ++k) {
        const sd_snap_item *it = &s->items[k];
        if (it->type != SD_ST_F64 || strncmp(it->name, "scene/", 6) == 0)
            continue;
        size_t n = it->count * it->comps;
        for (size_t j = 0; j < n; ++j) {
            double v;
            memcpy(&v, (const char *)it->data + 8 * j, 8);
            if (!isfinite(v))
                return sd_error_set(err, SD_ERR_INPUT, "", 0, it->name, "the checkpoint's '%s' holds %g (row %zu): "
                                    "every real of the state is finite", it->name, v, it->comps ? j / it->comps : 0);
        }
    }
    return SD_OK;
}

sd_status sd_restore_keep(const sd_world *w, sd_restore_kept *keep)
{
    memset(keep, 0, sizeof *keep);
    if (w->wall_count) {
        keep->walls = sd_malloc(w->wall_count * sizeof *keep->walls);
        if (!keep->walls)
            return SD_ERR_MEMORY;
        memcpy(keep->walls, w->walls, w->wall_count * sizeof *keep->walls);
    }
    if (w->process) {
        keep->process = sd_malloc(sizeof *keep->process);
        if (!keep->process) {
            sd_restore_kept_free(keep);
            return SD_ERR_MEMORY;
        }
        memcpy(keep->process, w->process, sizeof *keep->process);
    }
    return SD_OK;
}

void sd_restore_kept_free(sd_restore_kept *keep)
{
    sd_free(keep->walls);
    sd_free(keep->process);
    memset(keep, 0, sizeof *keep);
}

static double sd_quat_len(sd_quat q)
{
    return sqrt((double)(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z));
}

/* integration keeps orientations normalised to rounding */
static int sd_quat_sane(sd_quat q) { return fabs(sd_quat_len(q) - 1.0) < 1e-6; }

static int sd_v3_same(sd_vec3 a, sd_vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

static int sd_v3_finite(sd_vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }

/* walls/geom is a record of bytes: its reals are checked here */
static int sd_geom_finite(const sd_wall *wl)
{
    return sd_v3_finite(wl->point) && sd_v3_finite(wl->normal) && sd_v3_finite(wl->lo) && sd_v3_finite(wl->hi) &&
           sd_v3_finite(wl->trans) && sd_v3_finite(wl->centre) && isfinite(wl->q.w) && isfinite(wl->q.x) &&
           isfinite(wl->q.y) && isfinite(wl->q.z);
}

static sd_status sd_restore_check_clock(const sd_world *w, sd_error *err)
{
    const sd_world_def *d = &w->def;
    if (w->step < 0)
        return sd_restore_bad(err, "world/step", "expected a step >= 0", 0, (double)w->step);
    if (!(w->time >= 0))
        return sd_restore_bad(err, "world/time", "expected a time >= 0 s", 0, (double)w->time);
    /* set from the scene's definition only (world.c), which the hash covers */
    if (w->dt != (sd_real)d->dt)
        return sd_restore_bad(err, "world/dt", "the scene's time step differs", 0, (double)w->dt);
    if (w->gravity.x != (sd_real)d->gravity.x || w->gravity.y != (sd_real)d->gravity.y ||
        w->gravity.z != (sd_real)d->gravity.z)
        return sd_restore_bad(err, "world/gravity", "the scene's gravity differs", 0, (double)w->gravity.z);
    if (w->local_damping != (sd_real)d->local_damping)
        return sd_restore_bad(err, "world/local_damping", "the scene's local damping differs", 0,
                              (double)w->local_damping);
    if (!(w->skin >= 0) || w->skin > SD_RESTORE_LENGTH_MAX)
        return sd_restore_bad(err, "world/skin", "expected a skin >= 0 m", 0, (double)w->skin);
    if ((w->walls_moving | w->dirty | w->has_shapes) & ~1)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "world/dirty", "the checkpoint's flags world/walls_moving, "
                            "world/dirty, world/has_shapes are %d, %d, %d: expected 0 or 1", w->walls_moving,
                            w->dirty, w->has_shapes);
    if (w->rebuilds < 0)
        return sd_restore_bad(err, "world/rebuilds", "expected a count >= 0", 0, (double)w->rebuilds);
    return SD_OK;
}

static sd_status sd_restore_check_particles(const sd_world *w, sd_error *err)
{
    const sd_particles *p = &w->p;
    size_t nt = p->n + w->n_ghost;
    size_t ns = w->dim2 ? w->shape2d_count : w->shape_count;
    for (size_t k = 0; k < nt; ++k) {
        int32_t s = p->shape[k], m = p->material[k];
        if (s < -1 || (s >= 0 && (size_t)s >= ns))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "particles/shape", "the checkpoint's particle %zu has "
                                "shape %d; the scene has %zu templates (-1: a sphere)", k, (int)s, ns);
        if (m < 0 || (size_t)m >= w->material_count)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "particles/material", "the checkpoint's particle %zu has "
                                "material %d; the scene has %zu", k, (int)m, w->material_count);
        double r = (double)p->radius[k];
        if (!(r > 0) || r > SD_RESTORE_LENGTH_MAX)
            return sd_restore_bad(err, "particles/radius", "expected a radius > 0 m", k, r);
        /* a 3D body's radius is its template's bounding radius (bodies.c) */
        if (!w->dim2 && s >= 0 && p->radius[k] != w->shapes[s].bound)
            return sd_restore_bad(err, "particles/radius", "its template's bounding radius differs", k, r);
        /* the scene's rule for start positions (io/scene_build.c): where
         * doubles resolve less than 1e-3 of the radius, contact depths
         * mean nothing */
        double far = fmax(fabs((double)p->x[k].x), fmax(fabs((double)p->x[k].y), fabs((double)p->x[k].z)));
        if (!(far * DBL_EPSILON <= 1e-3 * r))
            return sd_restore_bad(err, "particles/x", "so far from the origin that doubles there do not resolve "
                                  "its radius", k, far);
        if (!(p->inv_mass[k] >= 0))
            return sd_restore_bad(err, "particles/inv_mass", "expected an inverse mass >= 0 (0: fixed)", k,
                                  (double)p->inv_mass[k]);
        sd_vec3 ii = p->inv_inertia[k];
        if (!(ii.x >= 0 && ii.y >= 0 && ii.z >= 0))
            return sd_restore_bad(err, "particles/inv_inertia", "expected inverse moments >= 0", k,
                                  (double)sd_min(ii.x, sd_min(ii.y, ii.z)));
        if (!sd_quat_sane(p->q[k]))
            return sd_restore_bad(err, "particles/q", "expected a unit quaternion (its norm)", k,
                                  (double)sd_quat_len(p->q[k]));
        if (!sd_quat_sane(p->q_ref[k]))
            return sd_restore_bad(err, "particles/q_ref", "expected a unit quaternion (its norm)", k,
                                  (double)sd_quat_len(p->q_ref[k]));
        if (p->id[k] >= w->next_id)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "particles/id", "the checkpoint's particle %zu has id "
                                "%llu, not below world/next_id %llu", k, (unsigned long long)p->id[k],
                                (unsigned long long)w->next_id);
    }
    return SD_OK;
}

static sd_status sd_restore_check_walls(sd_world *w, const sd_restore_kept *keep, sd_error *err)
{
    for (size_t k = 0; k < w->wall_count; ++k) {
        sd_wall *wl = &w->walls[k];
        const sd_wall *sc = &keep->walls[k];
        /* what the scene defines: its kind, faces, mesh, axis, a drum's
         * size; a mesh's pose and a wall's place move, their reals are
         * finite (sd_restore_check_items) */
        int same = wl->kind == sc->kind && wl->open_faces == sc->open_faces && wl->mesh == sc->mesh &&
                   wl->moving == sc->moving && sd_geom_finite(wl);
        if (same && wl->kind != SD_WALL_MESH)
            same = sd_v3_same(wl->normal, sc->normal);
        if (same && wl->kind == SD_WALL_DRUM)
            same = sd_v3_same(wl->lo, sc->lo) && sd_v3_same(wl->point, sc->point);
        if (same && wl->kind == SD_WALL_MESH)
            same = sd_quat_sane(wl->q);
        if (!same)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "walls/geom", "the checkpoint's wall %zu ('%s') is not the "
                                "scene's: its kind, faces, axis, size or pose differ", k, sc->name);
        if (!(wl->stiffness >= 0))
            return sd_restore_bad(err, "walls/stiffness", "expected a stiffness >= 0 N/m", k, (double)wl->stiffness);
        wl->motion = sc->motion; /* the scene's (hashed); the file's is the same or forged */
    }
    for (size_t k = 0; k < w->mesh_count; ++k) {
        const sd_mesh_store *ms = &w->meshes[k];
        if (!sd_quat_sane(ms->q_ref))
            return sd_restore_bad(err, "meshes/q_ref", "expected a unit quaternion (its norm)", k,
                                  (double)sd_quat_len(ms->q_ref));
        sd_real reach = 0;
        for (size_t j = 0; j < w->p.n; ++j)
            reach = sd_max(reach, w->p.radius[j]);
        reach += w->skin;
        if (!(ms->h >= 0) || (ms->h > 0 && (double)ms->h < (double)reach / SD_RESTORE_BIN_SLACK) ||
            ms->h > SD_RESTORE_LENGTH_MAX)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "meshes/h", "the checkpoint's mesh %zu bins its facets at "
                                "%g m: expected 0 (none yet) or at least 1/%g of the particles' reach %g m", k,
                                (double)ms->h, SD_RESTORE_BIN_SLACK, (double)reach);
    }
    return SD_OK;
}

/* The insertions' and outlets' definitions from the scene; their
 * counters, streams and next times from the file, checked. */
static sd_status sd_restore_check_process(sd_world *w, const sd_restore_kept *keep, sd_error *err)
{
    sd_process *p = w->process;
    const sd_process *sc = keep->process;
    if (!p)
        return SD_OK;
    p->insertion_count = sc->insertion_count;
    p->outlet_count = sc->outlet_count;
    if ((p->started & ~1) || !(p->inserted_mass >= 0) || !(p->removed_mass >= 0) || !isfinite(p->inserted_mass) ||
        !isfinite(p->removed_mass))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "world/process", "the checkpoint's insertion and outlet "
                            "totals are out of range");
    for (size_t k = 0; k < sc->insertion_count; ++k) {
        sd_insertion *in = &p->insertions[k];
        const sd_insertion *si = &sc->insertions[k];
        sd_insertion saved = *in; /* next_step -1: done (process.c) */
        *in = *si; /* definition, name and the tables made from them */
        in->rng = saved.rng;
        in->asked = saved.asked;
        in->inserted = saved.inserted;
        in->mass = saved.mass;
        in->next_step = saved.next_step;
        in->done = saved.done;
        memcpy(in->why, saved.why, sizeof in->why);
        in->why[sizeof in->why - 1] = '\0';
        if (in->inserted > in->asked || !(in->mass >= 0) || !isfinite(in->mass) || in->next_step < -1 ||
            (in->done & ~1) || (in->def.count > 0 && in->asked > in->def.count))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "world/process", "the checkpoint's insertion %zu ('%s') "
                                "has counters out of range (asked %zu, inserted %zu, mass %g kg, next step %ld)", k,
                                in->name, in->asked, in->inserted, in->mass, in->next_step);
    }
    for (size_t k = 0; k < sc->outlet_count; ++k) {
        sd_outlet_state *o = &p->outlets[k];
        sd_outlet_state saved = *o;
        *o = sc->outlets[k];
        o->removed = saved.removed;
        o->mass = saved.mass;
        o->next_step = saved.next_step;
        if (!(o->mass >= 0) || !isfinite(o->mass) || o->next_step < 0)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "world/process", "the checkpoint's outlet %zu ('%s') has "
                                "counters out of range (mass %g kg, next step %ld)", k, o->name, o->mass,
                                o->next_step);
    }
    return SD_OK;
}

sd_status sd_restore_check_world(sd_world *w, const sd_restore_kept *keep, sd_error *err)
{
    sd_status st = sd_restore_check_clock(w, err);
    if (st == SD_OK)
        st = sd_restore_check_particles(w, err);
    if (st == SD_OK)
        st = sd_restore_check_walls(w, keep, err);
    if (st == SD_OK)
        st = sd_restore_check_process(w, keep, err);
    return st;
}
