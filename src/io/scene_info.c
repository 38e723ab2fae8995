/* scene_info.c — the public queries and overrides of a loaded scene
 * (shapedem/scene.h): what a runner or a report needs to know of a scene
 * without seeing its internal struct (io/scene.h).
 *
 * Invariant: the queries only read; the overrides change the values
 * the builder and the run read afterwards, nothing else.
 */
#include <stdio.h>
#include <string.h>

#include "io/scene.h"

void sd_scene_set_threads(sd_scene *s, int threads)
{
    if (s && threads >= 1)
        s->world.threads = threads;
}

void sd_scene_set_backend(sd_scene *s, sd_backend_kind backend)
{
    if (s && backend >= 0 && backend < SD_BACKEND_COUNT) {
        s->world.backend = backend;
        s->backend_cli = 1; /* a refusal names the option, not the scene (io/scene_build.c) */
    }
}

void sd_scene_set_device(sd_scene *s, int device)
{
    if (s && device >= 0)
        s->world.device = device;
}

void sd_scene_set_steps(sd_scene *s, long steps)
{
    if (s && steps >= 0)
        s->steps = steps;
}

long sd_scene_steps(const sd_scene *s) { return s ? s->steps : 0; }

void sd_scene_get_info(const sd_scene *s, sd_scene_info *out)
{
    if (!out)
        return;
    memset(out, 0, sizeof *out);
    if (!s)
        return;
    out->path = s->path;
    out->dimension = s->world.dimension;
    out->dt = s->world.dt;
    out->steps = s->steps;
    out->threads = s->world.threads;
    out->solver = s->world.solver;
    out->law = s->world.law;
    out->material_count = s->material_count;
    out->shape_count = s->shape_count;
    out->wall_count = s->wall_count;
    /* the parser makes both >= 1; a run never divides by less */
    out->frame_every = s->output.every > 0 ? s->output.every : 1;
    out->stats_every = s->output.stats_every > 0 ? s->output.stats_every : out->frame_every;
    out->write_frames = (s->output.formats & SD_OUT_VTK) != 0;
    out->write_stats = (s->output.formats & SD_OUT_CSV) != 0;
    out->output_directory = s->output.directory;
    out->has_pour = s->pour.given;
    out->has_outlet = s->outlet.given;
}

const char *sd_scene_material_name(const sd_scene *s, size_t i)
{
    return s && i < s->material_count ? s->materials[i].name : NULL;
}

const char *sd_scene_shape_name(const sd_scene *s, size_t i)
{
    return s && i < s->shape_count ? s->shapes[i].name : NULL;
}

const char *sd_scene_shape_warning(const sd_scene *s, size_t i)
{
    return s && i < s->shape_count ? s->shapes[i].warning : NULL;
}

const char *sd_scene_wall_name(const sd_scene *s, size_t i) { return s && i < s->wall_count ? s->walls[i].name : NULL; }

const char *sd_scene_wall_warning(const sd_scene *s, size_t i)
{
    return s && i < s->wall_count ? s->walls[i].warning : NULL;
}

int sd_scene_get_pour(const sd_scene *s, sd_pour_def *out)
{
    if (!s || !s->pour.given)
        return 0;
    if (!out)
        return 1;
    *out = sd_pour_def_default();
    out->radius = s->pour.radius;
    out->material = s->pour.material;
    out->height = s->pour.height;
    out->layers_per_second = s->pour.rate;
    out->count = (size_t)s->pour.count;
    out->vz_range = s->pour.vertical_speed;
    out->vh_range = s->pour.horizontal_speed;
    out->start_time = s->pour.start;
    return 1;
}

int sd_scene_get_outlet(const sd_scene *s, sd_outlet_def *out)
{
    if (!s || !s->outlet.given)
        return 0;
    if (!out)
        return 1;
    *out = sd_outlet_def_default();
    out->x0 = s->outlet.lo[0];
    out->x1 = s->outlet.hi[0];
    out->y0 = s->outlet.lo[1];
    out->y1 = s->outlet.hi[1];
    out->open_at = s->outlet.open_at;
    return 1;
}

void sd_scene_output_directory(const sd_scene *s, char *buf, size_t size)
{
    if (!buf || size == 0)
        return;
    buf[0] = '\0';
    if (!s)
        return;
    if (s->output.directory[0]) {
        snprintf(buf, size, "%s", s->output.directory);
        return;
    }
    const char *base = strrchr(s->path, '/');
    base = base ? base + 1 : s->path;
    size_t n = strlen(base);
    const char *dot = strrchr(base, '.');
    if (dot && dot != base)
        n = (size_t)(dot - base);
    snprintf(buf, size, "out/%.*s", (int)n, base);
}
