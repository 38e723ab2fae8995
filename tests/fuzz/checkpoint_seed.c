/* checkpoint_seed.c — writes the seed checkpoints of fuzz_checkpoint:
 * each scene given is built, stepped a few steps (so there is contact
 * history) and checkpointed to OUTDIR/<scene stem>.h5.
 *
 *   fuzz_checkpoint_seed OUTDIR STEPS SCENE...
 *
 * The committed seeds (corpus/checkpoint/) were made with 20 steps of
 * corpus/scene/csv-and-mesh.yaml (run where cube.obj and spheres.csv lie),
 * corpus/scene/biaxial-2d-small.yaml and tests/unit/scenes/restart-grid
 * .yaml: the cells solver in 3D with a polyhedron and in 2D with servo
 * walls, the grid solver with pour and outlet; small scenes, so the seeds
 * stay small (the HDF5 metadata dominate). The name restore-base stands
 * for restore_scene.h's scene, written into a temporary directory: the
 * seed corpus/checkpoint/restore-base.h5 that fuzz_checkpoint restores.
 */
#include <shapedem/scene.h>
#include <shapedem/shapedem.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "restore_scene.h"

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: %s OUTDIR STEPS SCENE...\n", argv[0]);
        return 2;
    }
    const long steps = strtol(argv[2], NULL, 10);
    for (int a = 3; a < argc; ++a) {
        sd_error err;
        memset(&err, 0, sizeof err);
        sd_scene *s = NULL;
        sd_world *w = NULL;
        char msg[1024], out[4096], made[1024];
        const char *scene = argv[a];
        if (strcmp(scene, "restore-base") == 0)
            scene = sd_fuzz_restore_write(made, sizeof made);
        const char *base = strrchr(scene, '/');
        base = base ? base + 1 : scene;
        snprintf(out, sizeof out, "%s/%.*s.h5", argv[1], (int)strcspn(base, "."), base);
        if (sd_scene_load(scene, &s, &err) != SD_OK || sd_scene_build(s, &w, &err) != SD_OK ||
            sd_world_step(w, steps, &err) != SD_OK || sd_checkpoint_write(w, out, &err) != SD_OK) {
            sd_error_format(&err, msg, sizeof msg);
            fprintf(stderr, "checkpoint_seed: %s\n", msg);
            return 1;
        }
        printf("%s\n", out);
        sd_world_destroy(w);
        sd_scene_free(s);
    }
    return 0;
}
