/* fuzz_scene.c — libFuzzer target: the scene parser (sd_scene_load) on an
 * arbitrary YAML file.
 *
 * The input is the scene file itself. Beside it lie a convex mesh
 * (cube.obj) and a CSV particle file (spheres.csv), so a mutated scene that
 * names them reaches the polyhedron `file:` and csv-generator paths as
 * well. A scene that loads is queried through the public getters (what the
 * CLI does next). Only loading is fuzzed, not sd_scene_build: a valid scene
 * may ask for 10^9 particles, which is a legitimate request, not a bug.
 */
#include <shapedem/scene.h>
#include <stdio.h>
#include <string.h>

#include "fuzz_util.h"

static const char sd_fuzz_cube_obj[] =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
static const char sd_fuzz_spheres_csv[] = "x,y,z,radius\n0,0,0.01,0.001\n0.003,0,0.01,0.001\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int ready;
    char path[1024];
    if (!ready) {
        sd_fuzz_write("cube.obj", (const uint8_t *)sd_fuzz_cube_obj, sizeof sd_fuzz_cube_obj - 1, path, sizeof path);
        sd_fuzz_write("spheres.csv", (const uint8_t *)sd_fuzz_spheres_csv, sizeof sd_fuzz_spheres_csv - 1, path,
                      sizeof path);
        ready = 1;
    }
    sd_fuzz_write("scene.yaml", data, size, path, sizeof path);
    sd_scene *s = NULL;
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_status st = sd_scene_load(path, &s, &err);
    sd_fuzz_report("sd_scene_load", st, &err);
    if (st == SD_OK) {
        sd_scene_info info;
        sd_scene_get_info(s, &info);
        (void)sd_scene_steps(s);
        for (size_t i = 0; i < info.material_count; ++i)
            (void)strlen(sd_scene_material_name(s, i));
        for (size_t i = 0; i < info.shape_count; ++i) {
            (void)strlen(sd_scene_shape_name(s, i));
            (void)strlen(sd_scene_shape_warning(s, i));
        }
        char dir[1024];
        sd_scene_output_directory(s, dir, sizeof dir);
        sd_pour_def pour;
        sd_outlet_def outlet;
        (void)sd_scene_get_pour(s, &pour);
        (void)sd_scene_get_outlet(s, &outlet);
        sd_scene_free(s);
    } else if (s) {
        fprintf(stderr, "fuzz_scene: sd_scene_load failed but left a scene\n");
        __builtin_trap();
    } else if (!err.msg[0]) {
        fprintf(stderr, "fuzz_scene: sd_scene_load failed without a message\n");
        __builtin_trap();
    }
    return 0;
}
