/* fuzz_motion.c — libFuzzer target: a mesh wall's motion table (io/scene_mesh.c,
 * rows of t, dx, dy, dz, angle_deg), as a scene's `motion: {type: table}`
 * reaches it (issue 31: the probe attacked 36 tables by hand, and no
 * target read them).
 *
 * A fixed scene (one material, a 2-facet floor mesh written beside it, a
 * table motion naming motion.csv) is written once; the input is the table,
 * and each run loads the scene, so the rows also pass the checks after the
 * reader (t increasing, finite). A loaded scene is built and stepped twice,
 * so the motion is evaluated between its rows. Besides the sanitizers it
 * checks that a failed load sets a message and leaves no scene.
 */
#include <shapedem/scene.h>
#include <stdio.h>
#include <string.h>

#include "fuzz_util.h"

static const char sd_fuzz_motion_scene[] =
    "simulation: {dt: 1.0e-5, steps: 2}\n"
    "materials: [{name: g, density: 2500, youngs_modulus: 1.0e7}]\n"
    "walls:\n"
    "  - {name: floor, type: mesh, file: floor.obj, material: g, motion: {type: table, table: motion.csv}}\n"
    "particles: [{generator: lattice, material: g, radius: 0.001, origin: [0.005, 0.005, 0.003], spacing: 0.003,"
    " count: [2, 2, 1]}]\n";

static const char sd_fuzz_motion_floor[] = "v 0 0 0\nv 0.02 0 0\nv 0.02 0.02 0\nv 0 0.02 0\nf 1 2 3\nf 1 3 4\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char scene[1024];
    char path[1024];
    if (!scene[0]) {
        sd_fuzz_write("floor.obj", (const uint8_t *)sd_fuzz_motion_floor, sizeof sd_fuzz_motion_floor - 1, path,
                      sizeof path);
        sd_fuzz_write("scene.yaml", (const uint8_t *)sd_fuzz_motion_scene, sizeof sd_fuzz_motion_scene - 1, scene,
                      sizeof scene);
    }
    sd_fuzz_write("motion.csv", data, size, path, sizeof path);
    sd_scene *s = NULL;
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_status st = sd_scene_load(scene, &s, &err);
    sd_fuzz_report("sd_scene_load", st, &err);
    if (st == SD_OK) {
        sd_world *w = NULL;
        memset(&err, 0, sizeof err);
        st = sd_scene_build(s, &w, &err);
        sd_fuzz_report("sd_scene_build", st, &err);
        if (st == SD_OK) {
            st = sd_world_step(w, 2, &err);
            sd_fuzz_report("sd_world_step", st, &err);
        }
        sd_world_destroy(w);
        sd_scene_free(s);
    } else if (s || !err.msg[0]) {
        fprintf(stderr, "fuzz_motion: a failed load left a scene or no message\n");
        __builtin_trap();
    }
    return 0;
}
