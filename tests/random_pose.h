/* random_pose.h — random directions and rotations for the tests and the
 * micro-benchmarks (bench/ includes it too), drawn from the engine's
 * seeded generator (core/rng.h) so every run sees the same poses.
 *
 * Host-only (libm's sin and cos): the engine's insertions draw their own
 * rotations (world/process.c, io/scene_gen.c) by the same formula.
 */
#ifndef SD_TEST_RANDOM_POSE_H
#define SD_TEST_RANDOM_POSE_H

#include <math.h>

#include "core/quat.h"
#include "core/rng.h"
#include "core/vec.h"

/* A direction uniform on the unit sphere: a point uniform in the ball by
 * rejection from the cube, normalised (the tiny centre is rejected too, so
 * the normalisation is well conditioned). */
static inline sd_vec3 rand_unit(sd_rng *r)
{
    sd_vec3 p;
    do {
        p = sd_v3(sd_rng_range(r, -1, 1), sd_rng_range(r, -1, 1), sd_rng_range(r, -1, 1));
    } while (sd_v3_norm2(p) > 1 || sd_v3_norm2(p) < 1e-4);
    return sd_v3_normalize(p);
}

/* A rotation uniform over SO(3) (Shoemake, "Uniform random rotations",
 * Graphics Gems III, 1992): a unit quaternion uniform on the 3-sphere from
 * three uniforms. */
static inline sd_quat rand_quat(sd_rng *r)
{
    double u1 = sd_rng_uniform(r), u2 = 2 * SD_PI_D * sd_rng_uniform(r), u3 = 2 * SD_PI_D * sd_rng_uniform(r);
    double s1 = sqrt(1 - u1), s2 = sqrt(u1);
    return sd_quat_make(s2 * cos(u3), s1 * sin(u2), s1 * cos(u2), s2 * sin(u3));
}

#endif
