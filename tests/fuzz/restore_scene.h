/* restore_scene.h — the scene whose checkpoints fuzz_checkpoint restores
 * (issue 31): spheres and a cube on a mesh floor beside a plane, an
 * insertion and an outlet, so a restore meets every kind of state the
 * probe forged (particles, walls, meshes, the process record). The seed
 * corpus/checkpoint/restore-base.h5 is this scene after 20 steps
 * (`fuzz_checkpoint_seed OUTDIR 20 restore-base`, checkpoint_seed.c).
 */
#ifndef SD_FUZZ_RESTORE_SCENE_H
#define SD_FUZZ_RESTORE_SCENE_H

#include <stddef.h>

#include "fuzz_util.h"

static const char sd_fuzz_restore_yaml[] =
    "simulation: {dt: 1.0e-5, steps: 20, seed: 5}\n"
    "materials: [{name: g, density: 2500, youngs_modulus: 1.0e7, friction: 0.4}]\n"
    "shapes: [{name: cube, type: box, size: 0.002}]\n"
    "particles:\n"
    "  - {generator: lattice, material: g, radius: 0.001, origin: [-0.004, -0.004, 0.0012], spacing: 0.0025, "
    "count: [4, 4, 2]}\n"
    "  - {generator: list, material: g, spheres: [{position: [0.008, 0.008, 0.003], shape: cube}]}\n"
    "insert: [{name: feed, region: box, min: [-0.01, -0.01, 0.01], max: [0.01, 0.01, 0.015], count: 10, "
    "rate: 50000, mix: [{material: g, radius: {min: 0.0008, max: 0.001}}]}]\n"
    "outlets: [{name: drain, region: box, min: [-1, -1, -1], max: [1, 1, -0.5]}]\n"
    "walls:\n"
    "  - {name: floor, type: mesh, file: floor.obj, material: g}\n"
    "  - {name: side, type: plane, point: [-0.015, 0, 0], normal: [1, 0, 0], material: g}\n";

/* a 4 cm floor at z = 0, wound to face +z */
static const char sd_fuzz_restore_obj[] =
    "v -0.02 -0.02 0\nv 0.02 -0.02 0\nv 0.02 0.02 0\nv -0.02 0.02 0\nf 1 2 3\nf 1 3 4\n";

/* Writes the scene and its mesh into the fuzz directory; the scene's path
 * in path. */
static inline const char *sd_fuzz_restore_write(char *path, size_t size)
{
    sd_fuzz_write("floor.obj", (const unsigned char *)sd_fuzz_restore_obj, sizeof sd_fuzz_restore_obj - 1, path,
                  size);
    return sd_fuzz_write("restore-base.yaml", (const unsigned char *)sd_fuzz_restore_yaml,
                         sizeof sd_fuzz_restore_yaml - 1, path, size);
}

#endif
