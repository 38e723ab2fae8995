/* render_ckpt.c — a checkpoint as a frame (see render_ckpt.h).
 *
 * With the scene, the restored world writes the three files of one frame
 * (particles, shapes, walls: io/vtk.h, the writers a run uses) into a
 * private temporary directory, the frame reader reads them back as it
 * reads a run's frames, and the directory is removed: one path from a world
 * to a picture, whether the world ran or was restored.
 */
#define _POSIX_C_SOURCE 200809L

#include "cli/render_ckpt.h"

#include <shapedem/scene.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/error.h"
#include "io/ckpt_particles.h"
#include "io/scene.h"
#include "io/vtk.h"

static sd_status sd_render_ckpt_spheres(const char *ck, const char *field, sd_render_frame *f, sd_error *err)
{
    sd_ckpt_particles p;
    sd_status s = sd_ckpt_particles_read(ck, &p, err);
    if (s == SD_OK) {
        sd_render_particles rp = {.n = p.n, .x = p.x, .v = p.v, .w = p.w, .f = p.f, .q = p.q, .radius = p.radius,
                                  .id = p.id, .shape = p.shape, .material = p.material,
                                  .shape_count = p.shape_count, .material_count = p.material_count,
                                  .shape_names = (const char(*)[64])p.shape_names,
                                  .material_names = (const char(*)[64])p.material_names, .source = ck};
        s = sd_render_frame_particles(&rp, field, f, err);
    }
    sd_ckpt_particles_free(&p);
    return s;
}

/* One frame file of w in dir: which 0 particles, 1 walls, 2 shapes. */
static sd_status sd_render_ckpt_file(const char *dir, const char *name, const sd_world *w, int which,
                                     int resolution, sd_error *err)
{
    char path[SD_RENDER_PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *fp = fopen(path, "wb");
    if (!fp)
        return sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot write a temporary frame file");
    sd_status s;
    if (which == 0) {
        s = sd_vtk_write_particles(fp, w, err);
    } else if (which == 1) {
        s = sd_vtk_write_walls(fp, w, sd_vtk_plane_side(w), err);
    } else {
        sd_vtk_shapes *t = NULL;
        s = sd_vtk_shapes_make(w, resolution, &t, err);
        if (s == SD_OK)
            s = sd_vtk_write_shapes(fp, w, t, err);
        sd_vtk_shapes_free(t);
    }
    if (fclose(fp) != 0 && s == SD_OK)
        s = sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot write a temporary frame file");
    return s;
}

sd_status sd_render_load_checkpoint(const char *ck, const char *scene, const char *field, sd_render_frame *f,
                                    sd_error *err)
{
    memset(f, 0, sizeof *f);
    if (!scene)
        return sd_render_ckpt_spheres(ck, field, f, err);
    sd_scene *sc = NULL;
    sd_world *w = NULL;
    sd_status s = sd_scene_load(scene, &sc, err);
    if (s == SD_OK)
        s = sd_scene_build(sc, &w, err);
    if (s == SD_OK) {
        s = sd_checkpoint_restore(w, ck, err); /* names ck on error */
    }
    static const char *names[3] = {"particles_000000.vtu", "walls_000000.vtp", "shapes_000000.vtp"};
    char dir[SD_RENDER_PATH_MAX] = "";
    if (s == SD_OK) {
        const char *tmp = getenv("TMPDIR");
        snprintf(dir, sizeof dir, "%s/shapedem-render-XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
        if (!mkdtemp(dir)) {
            s = sd_error_set(err, SD_ERR_IO, dir, 0, "", "cannot make a temporary directory for the frame");
            dir[0] = 0;
        }
    }
    for (int k = 0; s == SD_OK && k < 3; ++k)
        s = sd_render_ckpt_file(dir, names[k], w, k, sc->output.shape_resolution, err);
    if (s == SD_OK) {
        char path[SD_RENDER_PATH_MAX];
        snprintf(path, sizeof path, "%s/%s", dir, names[0]);
        s = sd_render_frame_load(path, field, f, err);
        if (s != SD_OK) /* a field it lacks: name the checkpoint, not the temporary */
            snprintf(err->file, sizeof err->file, "%s", ck);
        snprintf(f->source, sizeof f->source, "%s", ck);
    }
    if (dir[0]) {
        for (int k = 0; k < 3; ++k) {
            char path[SD_RENDER_PATH_MAX];
            snprintf(path, sizeof path, "%s/%s", dir, names[k]);
            remove(path);
        }
        rmdir(dir);
    }
    sd_world_destroy(w);
    sd_scene_free(sc);
    return s;
}
