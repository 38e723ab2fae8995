/* mixed_packing.c — spheres, rounded boxes, cylinders, ellipsoids, cones
 * and polyhedra poured together into a closed box settle: no particle
 * leaves the box, the largest overlap stays below 2 % of the smallest body
 * size, the packing comes to rest, and the box carries the weight.
 * Scene: tests/validation/scenes/mixed-packing.yaml (150 bodies).
 */
#include <stdlib.h>
#include <string.h>

#include "test.h"

#include "io/scene.h"
#include "world/world.h"

/* The smallest outer dimension of body k (a sphere's diameter). */
static double body_size(const sd_world *w, size_t k)
{
    int s = w->p.shape[k];
    return s >= 0 ? (double)w->shapes[s].min_size : 2.0 * (double)w->p.radius[k];
}

int main(void)
{
    const char *src = getenv("SD_SOURCE_DIR");
    char path[1024];
    snprintf(path, sizeof path, "%s/tests/validation/scenes/mixed-packing.yaml", src ? src : ".");
    sd_error err;
    sd_scene *scene;
    sd_world *w;
    sd_test_require(sd_scene_load(path, &scene, &err) == SD_OK, "load", &err);
    scene->world.threads = 2;
    sd_test_require(sd_scene_build(scene, &w, &err) == SD_OK, "build", &err);
    size_t n = sd_world_particle_count(w);
    double worst = 0, smallest = 1e300;
    for (size_t k = 0; k < n; ++k)
        smallest = fmin(smallest, body_size(w, k));
    long chunk = scene->steps / 20;
    double fz_sum = 0;
    long fz_count = 0;
    for (int c = 0; c < 20; ++c) {
        if (c == 19) {
            /* the last chunk step by step: the box force averaged over it
             * (an instant still carries the pack's last vibrations) */
            for (long s = 0; s < chunk; ++s) {
                sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
                sd_wall_info wi;
                sd_world_get_wall(w, 0, &wi);
                fz_sum += wi.force.z;
                fz_count++;
            }
        } else

        sd_test_require(sd_world_step(w, chunk, &err) == SD_OK, "step", &err);
        /* overlaps of every contact, against the smaller body of the pair */
        for (size_t e = 0; e < w->pairs.n; ++e)
            if (w->pairs.delta[e] > 0)
                worst = fmax(worst, (double)w->pairs.delta[e] /
                                        fmin(body_size(w, w->pairs.i[e]), body_size(w, w->pairs.j[e])));
        for (size_t e = 0; e < w->wpairs.n; ++e)
            if (w->wpairs.delta[e] > 0)
                worst = fmax(worst, (double)w->wpairs.delta[e] / body_size(w, w->wpairs.i[e]));
    }
    long outside = 0;
    double mass = 0;
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        mass += p.mass;
        outside += p.position.x < 0 || p.position.x > 0.0204 || p.position.y < 0 || p.position.y > 0.0204 ||
                   p.position.z < 0 || p.position.z > 0.04;
    }
    sd_stats st;
    sd_world_stats(w, &st);
    printf("     %zu bodies, %ld contacts, %ld wall contacts, smallest body size %.3g m\n", n, st.contacts,
           st.wall_contacts, smallest);
    CHECK_NEAR("bodies outside the box", (double)outside, 0.0, 0.0);
    CHECK_NEAR("largest overlap / smaller body size", worst, 0.0, 0.02);
    CHECK_NEAR("kinetic energy per body at the end (J)", (st.kinetic_translational + st.kinetic_rotational) / (double)n,
               0.0, 1e-9);
    CHECK_REL("box force z, mean over the last 5 % of the run = weight (N)", fz_sum / (double)fz_count,
              -mass * 9.81, 0.02);
    sd_world_destroy(w);
    sd_scene_free(scene);
    return sd_test_summary();
}
