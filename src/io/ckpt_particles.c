/* ckpt_particles.c — a checkpoint's particles as a table (see
 * ckpt_particles.h): the columns are the snapshot's own arrays, checked
 * for their type, width and rows; the names are copied out NUL-terminated.
 */
#include "io/ckpt_particles.h"

#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/checkpoint.h"

/* Column `name` of the saved state: type and values per row as expected,
 * at least rows rows; NULL otherwise. */
static const void *sd_ckpt_column(const sd_snapshot *s, const char *name, sd_state_type type, size_t comps,
                                  size_t rows)
{
    const sd_snap_item *it = sd_snapshot_find(s, name);
    if (!it || it->type != type || it->comps != comps || it->count < rows || (rows && !it->data))
        return NULL;
    return it->data;
}

/* The names of scene/ item `name` (rows of SD_SNAP_NAME bytes), each cut
 * at its last byte so that it ends in a NUL whatever the file holds. */
static int sd_ckpt_names(const sd_snapshot *s, const char *name, char (**out)[SD_SNAP_NAME], size_t *count)
{
    const sd_snap_item *it = sd_snapshot_find(s, name);
    if (!it || it->type != SD_ST_BYTES || it->comps != SD_SNAP_NAME || (it->count && !it->data))
        return 0;
    char(*v)[SD_SNAP_NAME] = sd_malloc((it->count ? it->count : 1) * sizeof *v);
    if (!v)
        return -1;
    if (it->count)
        memcpy(v, it->data, it->count * sizeof *v);
    for (size_t k = 0; k < it->count; ++k)
        v[k][SD_SNAP_NAME - 1] = '\0';
    *out = v;
    *count = it->count;
    return 1;
}

void sd_ckpt_particles_free(sd_ckpt_particles *p)
{
    if (!p)
        return;
    sd_snapshot_free(&p->snap);
    sd_free(p->shape_names);
    sd_free(p->material_names);
    memset(p, 0, sizeof *p);
}

sd_status sd_ckpt_particles_read(const char *path, sd_ckpt_particles *out, sd_error *err)
{
    sd_snapshot snap;
    memset(out, 0, sizeof *out);
    sd_status st = sd_checkpoint_read_file(path, &snap, err);
    if (st != SD_OK) {
        sd_snapshot_free(&snap);
        return st;
    }
    return sd_ckpt_particles_take(&snap, path, out, err);
}

sd_status sd_ckpt_particles_take(sd_snapshot *snap, const char *path, sd_ckpt_particles *out, sd_error *err)
{
    memset(out, 0, sizeof *out);
    out->snap = *snap;
    sd_snapshot_init(snap);
    const sd_snapshot *s = &out->snap;
    out->step = s->step;
    out->time = s->time;
    out->dimension = s->dimension;
    uint64_t n = 0;
    if (strcmp(s->solver, "cells") != 0)
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "",
                            "a checkpoint of the %.15s solver keeps its particles in that solver's own layout: "
                            "look at a frame of the run instead", s->solver);
    if (!sd_snapshot_get_u64(s, "particles/n", &n) || n > ((uint64_t)1 << 32))
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "the checkpoint lacks its particle count (particles/n)");
    size_t rows = (size_t)n;
    out->n = rows;
    out->x = sd_ckpt_column(s, "particles/x", SD_ST_F64, 3, rows);
    out->v = sd_ckpt_column(s, "particles/v", SD_ST_F64, 3, rows);
    out->w = sd_ckpt_column(s, "particles/w", SD_ST_F64, 3, rows);
    out->f = sd_ckpt_column(s, "particles/f", SD_ST_F64, 3, rows);
    out->q = sd_ckpt_column(s, "particles/q", SD_ST_F64, 4, rows);
    out->radius = sd_ckpt_column(s, "particles/radius", SD_ST_F64, 1, rows);
    out->id = sd_ckpt_column(s, "particles/id", SD_ST_U64, 1, rows);
    out->shape = sd_ckpt_column(s, "particles/shape", SD_ST_I32, 1, rows);
    out->material = sd_ckpt_column(s, "particles/material", SD_ST_I32, 1, rows);
    if (rows && (!out->x || !out->v || !out->w || !out->f || !out->q || !out->radius || !out->id || !out->shape ||
                 !out->material))
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "",
                            "the checkpoint lacks one of particles/x, v, w, f, q, radius, id, shape, material for "
                            "its %zu particles (or holds another type)", rows);
    int a = sd_ckpt_names(s, "scene/shape_names", &out->shape_names, &out->shape_count);
    int b = a < 0 ? 0 : sd_ckpt_names(s, "scene/material_names", &out->material_names, &out->material_count);
    if (a < 0 || b < 0)
        return sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    if (!a || !b)
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "",
                            "the checkpoint does not name its templates and materials (scene/shape_names, "
                            "scene/material_names: written by shapedem %.31s, format %u)", s->writer, s->version);
    for (size_t k = 0; k < rows; ++k) {
        int32_t si = out->shape[k], mi = out->material[k];
        if (si < -1 || (si >= 0 && (size_t)si >= out->shape_count) || mi < 0 ||
            (size_t)mi >= out->material_count)
            return sd_error_set(err, SD_ERR_INPUT, path, 0, "",
                                "particle id %llu has template %d of %zu and material %d of %zu (a damaged "
                                "checkpoint)", (unsigned long long)out->id[k], (int)si, out->shape_count, (int)mi,
                                out->material_count);
    }
    return SD_OK;
}

/* A CSV field: as it is, or quoted (quotes doubled) when it holds a comma,
 * a quote or a line break. */
static void sd_ckpt_csv_name(FILE *f, const char *s)
{
    if (!strpbrk(s, ",\"\r\n")) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; ++s) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

sd_status sd_ckpt_particles_print_csv(FILE *f, const sd_ckpt_particles *p, sd_error *err)
{
    fprintf(f, "id,x,y,z,vx,vy,vz,wx,wy,wz,qw,qx,qy,qz,radius,shape,material,fx,fy,fz\n");
    for (size_t k = 0; k < p->n; ++k) {
        const double *x = p->x + 3 * k, *v = p->v + 3 * k, *w = p->w + 3 * k, *q = p->q + 4 * k;
        fprintf(f, "%llu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,",
                (unsigned long long)p->id[k], x[0], x[1], x[2], v[0], v[1], v[2], w[0], w[1], w[2], q[0], q[1], q[2],
                q[3], p->radius[k]);
        if (p->shape[k] >= 0)
            sd_ckpt_csv_name(f, p->shape_names[p->shape[k]]);
        fputc(',', f);
        sd_ckpt_csv_name(f, p->material_names[p->material[k]]);
        fprintf(f, ",%.17g,%.17g,%.17g\n", p->f[3 * k], p->f[3 * k + 1], p->f[3 * k + 2]);
    }
    if (fflush(f) != 0 || ferror(f))
        return sd_error_set(err, SD_ERR_IO, "", 0, "", "cannot write the particles' CSV");
    return SD_OK;
}
