/* scene_from.c — a csv generator whose file is a checkpoint of another run
 * (generator: csv, file: out/run/checkpoint-000500.h5; issue 17): a new
 * scene starts from the particles of that run, a settled bed reused under
 * a new load or in new equipment, for every particle kind (spheres,
 * convex shapes, polyhedra, composites, the planar kinds).
 *
 * The checkpoint is read by the checkpoint reader (io/checkpoint.c: its
 * checksums first) into a snapshot, never into a world. Its owned
 * particles (storage rows 0 .. particles/n - 1, not the periodic images)
 * become the generator's entries, in the order of their stable ids, with
 * their positions, velocities, spins and orientations exactly as saved;
 * the saved template of each is found in the new scene by name
 * (scene/shape_names; world/snapshot.c) and must be of the same kind
 * (scene/shape_kinds), its material by name too (scene/material_names),
 * else the generator's material. A template that is a scaled copy an
 * insertion made (TEMPLATE_iIeEsK, world/scaled.c; scene/shape_bases and
 * scene/shape_scales say of which template and by what factor) is made
 * again: the same factor on the scene's template of that name (same
 * kind), appended hidden to the scene's shapes, so the bodies keep the
 * bits of their geometry, mass and inertia. Contact history, forces and
 * walls stay behind: the new scene brings its own walls.
 *
 * Invariant (that of csv.c): on SD_OK, one entry per saved particle was
 * appended to the generator's entry arrays; on error the arrays hold
 * consistent rows and err names the scene file, the line of file: and its
 * key, and says what the checkpoint holds against what was expected.
 */
#include "io/scene_from.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/checkpoint.h"
#include "io/csv.h"
#include "shape/composite.h"
#include "shape/shape2d.h"
#include "shape/shape_make.h"

int sd_from_is_checkpoint(const char *path)
{
    size_t n = strlen(path);
    if (n >= 3 && strcmp(path + n - 3, ".h5") == 0)
        return 1;
    return sd_checkpoint_is_file(path);
}

/* A saved array of the particles: type and values per row as expected,
 * at least rows rows. */
static const sd_snap_item *sd_from_item(const sd_snapshot *s, const char *name, sd_state_type type, size_t comps,
                                        size_t rows)
{
    const sd_snap_item *it = sd_snapshot_find(s, name);
    if (!it || it->type != type || it->comps != comps || it->count < rows)
        return NULL;
    return it;
}

/* The scene's kind name of shape i, as the world's sd_shape_info names it. */
static const char *sd_from_scene_kind(const sd_scene *s, size_t i)
{
    const sd_scene_shape *sh = &s->shapes[i];
    return sh->kind2d >= 0 ? sd_shape2d_kind_name(sh->kind2d) : sd_shape_kind_name(sh->kind);
}

typedef struct sd_from_order {
    uint64_t id;
    size_t row;
} sd_from_order;

static int sd_from_order_cmp(const void *a, const void *b)
{
    const sd_from_order *x = a, *y = b;
    return x->id < y->id ? -1 : x->id > y->id;
}

/* A saved name row: NUL-terminated within its width (a damaged name is
 * cut there). */
static void sd_from_name(const sd_snap_item *it, size_t k, char *out)
{
    memcpy(out, (const char *)it->data + k * SD_SNAP_NAME, SD_SNAP_NAME);
    out[SD_SNAP_NAME - 1] = '\0';
}

/* The recipe of saved template k when it is a scaled copy (scene/
 * shape_bases, scene/shape_scales: world/scaled.c): 1 with *base and
 * *scale, 0 when it is none or the checkpoint predates the recipes, -1
 * when the recipe cannot be (a damaged file: a base out of range, itself
 * a copy, a factor not > 0). */
static int sd_from_recipe(const sd_snap_item *bases, const sd_snap_item *scales, size_t ns, size_t k, int *base,
                          double *scale)
{
    if (!bases || !scales || bases->type != SD_ST_I32 || bases->comps != 1 || bases->count != ns ||
        scales->type != SD_ST_F64 || scales->comps != 1 || scales->count != ns)
        return 0;
    int32_t b;
    memcpy(&b, (const int32_t *)bases->data + k, sizeof b);
    memcpy(scale, (const double *)scales->data + k, sizeof *scale);
    if (b == -1)
        return 0;
    int32_t bb = -2;
    if (b >= 0 && (size_t)b < ns)
        memcpy(&bb, (const int32_t *)bases->data + b, sizeof bb);
    *base = b;
    return (size_t)b != k && bb == -1 && *scale > 0 && isfinite(*scale) ? 1 : -1;
}

/* Appends to s's shapes (hidden, after its own) the scaled copy named
 * name of s's template b by scale, as sd_world_add_scaled_shape will make
 * it at build (io/scene_build.c), so that scene and world indices stay
 * one: a composite's copy after one copy of each distinct element
 * template, NAME.eJ in the order of first use. Its index, or -1 (memory,
 * or a name too long for an element copy). */
static int sd_from_add_copy(sd_scene *s, size_t b, double scale, const char *name, int line, size_t gen)
{
    const sd_scene_shape *src = &s->shapes[b];
    int from[SD_COMPOSITE_MAX_ELEMENTS];
    size_t distinct = 0;
    if (src->kind2d < 0 && src->kind == SD_SHAPE_COMPOSITE)
        for (size_t e = 0; e < src->element_count; ++e) {
            size_t j = 0;
            while (j < distinct && from[j] != src->elements[e].shape)
                ++j;
            if (j == distinct)
                from[distinct++] = src->elements[e].shape;
        }
    sd_scene_shape *grown = sd_realloc(s->shapes, (s->shape_count + distinct + 1) * sizeof *grown);
    if (!grown)
        return -1;
    s->shapes = grown;
    for (size_t j = 0; j <= distinct; ++j) {
        /* the copied template's scalar fields, none of its arrays (the
         * world copies its own) */
        sd_scene_shape *c = &grown[s->shape_count + j];
        *c = grown[j < distinct ? (size_t)from[j] : b];
        c->vertices = NULL;
        c->vertex_count = 0;
        c->points = NULL;
        c->point_count = 0;
        c->fourier_a = c->fourier_b = NULL;
        c->fourier_count = 0;
        c->elements = NULL;
        c->element_count = 0;
        c->file[0] = c->warning[0] = '\0';
        c->hidden = 1;
        c->line = line;
        c->scaled_of = j < distinct ? -1 : (int)b + 1;
        c->scaled_by = scale;
        c->entry = gen; /* a copy's messages name the generator */
        int w = j < distinct ? snprintf(c->name, sizeof c->name, "%s.e%zu", name, j)
                             : snprintf(c->name, sizeof c->name, "%s", name);
        if (w < 0 || (size_t)w >= sizeof c->name)
            return -1;
    }
    s->shape_count += distinct + 1;
    return (int)(s->shape_count - 1);
}

/* Saved template si, named in names and kinds, is a copy of saved
 * template b by sc (recipe 1; -1: a recipe that cannot be): *shape, the
 * scene's template of that name found already (-1: none), becomes the
 * copy made anew (sd_from_add_copy) from the scene's template of b's
 * name, which must be of b's kind; one found already must be the same
 * copy (a scene that reads two checkpoints), same template, same factor
 * bits. Else an error that names the file, file_line and key. */
static sd_status sd_from_scaled(sd_scene *s, const sd_scene_generator *g, const sd_snap_item *names,
                                const sd_snap_item *kinds, size_t si, int b, double sc, int recipe,
                                unsigned long long pid, int *shape, const char *key, int file_line, sd_error *err)
{
    char name[SD_SNAP_NAME], base[SD_SNAP_NAME], kind[SD_SNAP_NAME], esc[80], eb[80], known[512];
    sd_from_name(names, si, name);
    sd_escape(esc, sizeof esc, name, 40);
    if (recipe < 0)
        return sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                            "the checkpoint '%s': template '%s' is a scaled copy whose recipe is damaged "
                            "(scene/shape_bases %d of %zu templates, scene/shape_scales %g)",
                            g->file, esc, b, names->count, sc);
    sd_from_name(names, (size_t)b, base);
    sd_from_name(kinds, (size_t)b, kind);
    sd_escape(eb, sizeof eb, base, 40);
    int here = -1;
    for (size_t i = 0; i < s->shape_count && here < 0; ++i)
        if (!s->shapes[i].scaled_of && !strcmp(s->shapes[i].name, base))
            here = (int)i;
    if (*shape >= 0) {
        const sd_scene_shape *f = &s->shapes[*shape];
        if (f->scaled_of > 0 && (f->scaled_of - 1 != here || memcmp(&f->scaled_by, &sc, sizeof sc) != 0))
            return sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                                "the checkpoint '%s': template '%s' is a copy of '%s' scaled by %.17g, but "
                                "this scene has a copy of that name already (from another checkpoint, line "
                                "%d) of '%s' scaled by %.17g; give the runs' insertions other names",
                                g->file, esc, eb, sc, f->line, s->shapes[f->scaled_of - 1].name, f->scaled_by);
        return SD_OK; /* a template of the scene's own, or the same copy again */
    }
    if (here < 0)
        return sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                            "the checkpoint '%s': particle id %llu is of template '%s', a copy of '%s' scaled "
                            "by %.17g that an insertion made; this scene's shapes: does not define '%s' "
                            "(shapes: %s), from which the copy is made again", g->file, pid, esc, eb, sc, eb,
                            sd_csv_known(s, 0, known, sizeof known));
    const char *hk = sd_from_scene_kind(s, (size_t)here);
    if (!hk || strcmp(hk, kind) != 0) {
        char ek[80];
        sd_escape(ek, sizeof ek, kind, 40);
        return sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                            "the checkpoint '%s': template '%s' is a copy of '%s' scaled by %.17g, and '%s' "
                            "is a %s there, a %s in this scene (line %d); a template must keep its kind",
                            g->file, esc, eb, sc, eb, ek, hk ? hk : "?", s->shapes[here].line);
    }
    *shape = sd_from_add_copy(s, (size_t)here, sc, name, file_line, (size_t)(g - s->generators));
    if (*shape < 0)
        return sd_error_set(err, SD_ERR_MEMORY, s->path, file_line, key,
                            "out of memory (or no room for its elements' names) making the copy '%s' of '%s'",
                            esc, eb);
    return SD_OK;
}

sd_status sd_from_checkpoint_read(sd_scene *s, sd_scene_generator *g, const char *key, int file_line,
                                  sd_error *err)
{
    sd_snapshot snap;
    sd_error e2;
    memset(&e2, 0, sizeof e2);
    sd_status st = sd_checkpoint_read_file(g->file, &snap, &e2);
    if (st != SD_OK) {
        sd_snapshot_free(&snap);
        return sd_error_set(err, st == SD_ERR_MEMORY ? SD_ERR_MEMORY : SD_ERR_INPUT, s->path, file_line, key,
                            "cannot start from the checkpoint '%s': %s", g->file, e2.msg);
    }
    char known[512], esc[80];
    int dim = s->world.dimension == 2 ? 2 : 3;
    uint64_t n64 = 0;
    const sd_snap_item *names = sd_snapshot_find(&snap, "scene/shape_names");
    const sd_snap_item *kinds = sd_snapshot_find(&snap, "scene/shape_kinds");
    const sd_snap_item *mats = sd_snapshot_find(&snap, "scene/material_names");
    const sd_snap_item *bases = sd_snapshot_find(&snap, "scene/shape_bases");
    const sd_snap_item *scales = sd_snapshot_find(&snap, "scene/shape_scales");
    if (snap.dimension != dim)
        st = sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                          "the checkpoint '%s' is of a %dD run, this scene is %dD", g->file, snap.dimension, dim);
    else if (strcmp(snap.solver, "cells") != 0)
        st = sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                          "the checkpoint '%s' is of the %s solver, whose particles are kept in its own layout: "
                          "start from a frame instead (scripts/frame_to_csv.py)", g->file, snap.solver);
    else if (!sd_snapshot_get_u64(&snap, "particles/n", &n64) || n64 > ((uint64_t)1 << 32))
        st = sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                          "the checkpoint '%s' lacks its particle count (particles/n)", g->file);
    else if (!names || !kinds || !mats || names->type != SD_ST_BYTES || names->comps != SD_SNAP_NAME ||
             kinds->type != SD_ST_BYTES || kinds->comps != SD_SNAP_NAME || kinds->count != names->count ||
             mats->type != SD_ST_BYTES || mats->comps != SD_SNAP_NAME)
        st = sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                          "the checkpoint '%s' does not name its templates and materials (scene/shape_names, "
                          "scene/shape_kinds, scene/material_names: written by shapedem %s, format %u)",
                          g->file, snap.writer, snap.version);
    if (st != SD_OK) {
        sd_snapshot_free(&snap);
        return st;
    }
    size_t n = (size_t)n64, ns = names->count, nm = mats->count;
    const sd_snap_item *x = sd_from_item(&snap, "particles/x", SD_ST_F64, 3, n);
    const sd_snap_item *v = sd_from_item(&snap, "particles/v", SD_ST_F64, 3, n);
    const sd_snap_item *w = sd_from_item(&snap, "particles/w", SD_ST_F64, 3, n);
    const sd_snap_item *q = sd_from_item(&snap, "particles/q", SD_ST_F64, 4, n);
    const sd_snap_item *r = sd_from_item(&snap, "particles/radius", SD_ST_F64, 1, n);
    const sd_snap_item *sh = sd_from_item(&snap, "particles/shape", SD_ST_I32, 1, n);
    const sd_snap_item *mt = sd_from_item(&snap, "particles/material", SD_ST_I32, 1, n);
    const sd_snap_item *id = sd_from_item(&snap, "particles/id", SD_ST_U64, 1, n);
    if (!x || !v || !w || !q || !r || !sh || !mt || !id) {
        sd_snapshot_free(&snap);
        return sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                            "the checkpoint '%s' lacks one of particles/x, v, w, q, radius, shape, material, id "
                            "for its %zu particles (or holds another type)", g->file, n);
    }
    if (n == 0) {
        sd_snapshot_free(&snap);
        return sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key, "the checkpoint '%s' has no particles",
                            g->file);
    }
    /* each saved template and material found once, on first use */
    int *shape_map = sd_malloc((ns ? ns : 1) * sizeof *shape_map);
    int *mat_map = sd_malloc((nm ? nm : 1) * sizeof *mat_map);
    sd_from_order *order = sd_malloc(n * sizeof *order);
    size_t base = g->list_count;
    if (!shape_map || !mat_map || !order || !sd_csv_grow(g, base + n)) {
        st = sd_error_set(err, SD_ERR_MEMORY, s->path, file_line, key, "out of memory for %zu particles", n);
        goto done;
    }
    for (size_t k = 0; k < ns; ++k)
        shape_map[k] = -2; /* not looked up yet */
    for (size_t k = 0; k < nm; ++k)
        mat_map[k] = -2;
    const double *xd = x->data, *vd = v->data, *wd = w->data, *qd = q->data, *rd = r->data;
    const int32_t *shd = sh->data, *mtd = mt->data;
    const uint64_t *idd = id->data;
    for (size_t k = 0; k < n; ++k) {
        order[k].id = idd[k];
        order[k].row = k;
    }
    qsort(order, n, sizeof *order, sd_from_order_cmp);
    for (size_t o = 0; o < n; ++o) {
        size_t k = order[o].row;
        unsigned long long pid = (unsigned long long)idd[k];
        double vals[14] = {xd[3 * k], xd[3 * k + 1], xd[3 * k + 2], vd[3 * k], vd[3 * k + 1], vd[3 * k + 2],
                           wd[3 * k], wd[3 * k + 1], wd[3 * k + 2], qd[4 * k], qd[4 * k + 1], qd[4 * k + 2],
                           qd[4 * k + 3], rd[k]};
        for (int c = 0; c < 14; ++c)
            if (!isfinite(vals[c])) {
                st = sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                                  "the checkpoint '%s': particle id %llu has a state that is not finite (a "
                                  "failed-*.h5 of a run stopped by a guard is for inspection only)", g->file, pid);
                goto done;
            }
        int32_t si = shd[k], mi = mtd[k];
        if (si < -1 || (si >= 0 && (size_t)si >= ns) || mi < 0 || (size_t)mi >= nm) {
            st = sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                              "the checkpoint '%s': particle id %llu has template %d of %zu and material %d of %zu",
                              g->file, pid, (int)si, ns, (int)mi, nm);
            goto done;
        }
        int shape = -1;
        if (si >= 0) {
            if (shape_map[si] == -2) {
                char name[SD_SNAP_NAME], kind[SD_SNAP_NAME];
                sd_from_name(names, (size_t)si, name);
                sd_from_name(kinds, (size_t)si, kind);
                shape_map[si] = -1;
                for (size_t i = 0; i < s->shape_count && shape_map[si] < 0; ++i)
                    if (!strcmp(s->shapes[i].name, name))
                        shape_map[si] = (int)i;
                int b = -1;
                double sc = 1.0;
                int recipe = sd_from_recipe(bases, scales, ns, (size_t)si, &b, &sc);
                if (recipe != 0 && (st = sd_from_scaled(s, g, names, kinds, (size_t)si, b, sc, recipe, pid,
                                                        &shape_map[si], key, file_line, err)) != SD_OK)
                    goto done;
                if (shape_map[si] < 0) {
                    sd_escape(esc, sizeof esc, name, 40);
                    st = sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                                      "the checkpoint '%s': particle id %llu is of template '%s', which this "
                                      "scene's shapes: does not define (shapes: %s); templates are matched by name",
                                      g->file, pid, esc, sd_csv_known(s, 0, known, sizeof known));
                    goto done;
                }
                const char *here = sd_from_scene_kind(s, (size_t)shape_map[si]);
                if (!here || strcmp(here, kind) != 0) {
                    sd_escape(esc, sizeof esc, name, 40);
                    char ek[80];
                    sd_escape(ek, sizeof ek, kind, 40);
                    st = sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key,
                                      "the checkpoint '%s': template '%s' is a %s there, a %s in this scene "
                                      "(line %d); a template must keep its kind", g->file, esc, ek,
                                      here ? here : "?", s->shapes[shape_map[si]].line);
                    goto done;
                }
            }
            shape = shape_map[si];
        }
        if (mat_map[mi] == -2) {
            char name[SD_SNAP_NAME];
            sd_from_name(mats, (size_t)mi, name);
            mat_map[mi] = g->material; /* a material this scene does not name: the generator's */
            for (size_t i = 0; i < s->material_count; ++i)
                if (!strcmp(s->materials[i].name, name)) {
                    mat_map[mi] = (int)i;
                    break;
                }
        }
        size_t e = g->list_count;
        sd_sphere_def *d = &g->list[e];
        memset(d, 0, sizeof *d);
        d->position = (sd_v3d){vals[0], vals[1], vals[2]};
        d->velocity = (sd_v3d){vals[3], vals[4], vals[5]};
        d->angular_velocity = (sd_v3d){vals[6], vals[7], vals[8]};
        d->radius = shape < 0 ? vals[13] : 0.0; /* a shape's bound is set at generation */
        d->material = mat_map[mi];
        g->list_shape[e] = shape;
        g->list_orient[e] = shape >= 0 ? SD_ORIENT_FIXED : g->orient;
        if (shape >= 0)
            memcpy(g->list_quat[e], &vals[9], 4 * sizeof(double));
        else
            memcpy(g->list_quat[e], g->quat, sizeof g->quat);
        g->list_lines[e] = file_line;
        g->list_count = e + 1;
    }
done:
    sd_free(shape_map);
    sd_free(mat_map);
    sd_free(order);
    sd_snapshot_free(&snap);
    return st;
}
