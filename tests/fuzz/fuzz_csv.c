/* fuzz_csv.c — libFuzzer target: the CSV particle reader (io/csv.c), as a
 * scene's csv generator reaches it.
 *
 * A fixed scene (two materials, a box and a cylinder shape, one csv
 * generator naming particles.csv) is written once; the input is the CSV
 * file, and each run loads the scene, so the rows also pass the checks
 * after the reader (orientations, shapes, materials). Besides the
 * sanitizers it checks that a failed load sets a message and leaves no
 * scene.
 */
#include <shapedem/scene.h>
#include <stdio.h>
#include <string.h>

#include "fuzz_util.h"

static const char sd_fuzz_csv_scene[] =
    "simulation:\n"
    "  dt: 1.0e-6\n"
    "  steps: 10\n"
    "materials:\n"
    "  - {name: glass, density: 2500, youngs_modulus: 1.0e7}\n"
    "  - {name: steel, density: 7800, youngs_modulus: 2.0e8}\n"
    "shapes:\n"
    "  - {name: cube, type: box, size: [0.002, 0.002, 0.002], rounding: 0.0001}\n"
    "  - {name: rod, type: cylinder, size: [0.001, 0.001, 0.004], rounding: 0.0001}\n"
    "particles:\n"
    "  - generator: csv\n"
    "    material: glass\n"
    "    file: particles.csv\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char scene[1024];
    char path[1024];
    if (!scene[0])
        sd_fuzz_write("scene.yaml", (const uint8_t *)sd_fuzz_csv_scene, sizeof sd_fuzz_csv_scene - 1, scene,
                      sizeof scene);
    sd_fuzz_write("particles.csv", data, size, path, sizeof path);
    sd_scene *s = NULL;
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_status st = sd_scene_load(scene, &s, &err);
    sd_fuzz_report("sd_scene_load", st, &err);
    if (st == SD_OK) {
        (void)sd_scene_steps(s);
        sd_scene_free(s);
    } else if (s || !err.msg[0]) {
        fprintf(stderr, "fuzz_csv: a failed load left a scene or no message\n");
        __builtin_trap();
    }
    return 0;
}
