/* profile.c — the per-stage profile of the step (sd_profile, STYLE.md
 * convention 9): a small world of spheres, boxes and a floor is stepped and
 * every stage it runs must count one call per step (and one for the
 * prepare's forces), with times that are non-negative and add up to no
 * more than the wall time measured around the calls. No timing threshold:
 * only the bookkeeping is checked. */
#define _POSIX_C_SOURCE 200809L

#include <string.h>
#include <time.h>

#include "test.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(void)
{
    sd_error err;
    sd_world_def d = sd_world_def_default();
    d.dt = 1e-5;
    d.threads = 2;
    sd_world *w = NULL;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    sd_test_require(sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err) >= 0, "floor",
                    &err);
    sd_shape_desc box = sd_shape_desc_default();
    box.kind = "box";
    box.size = sd_test_v(0.002, 0.002, 0.002);
    int shape = sd_world_add_shape(w, "cube", &box, &err);
    sd_test_require(shape >= 0, "shape", &err);
    /* a row of spheres resting on the floor, 1 % apart (within the skin:
     * their candidate pairs stay in the list), and cubes on them */
    enum { NS = 8, NB = 4 };
    sd_sphere_def s[NS];
    memset(s, 0, sizeof s);
    for (int k = 0; k < NS; ++k) {
        s[k].position = sd_test_v(0.00202 * k, 0, 0.001);
        s[k].radius = 0.001;
        s[k].material = mat;
    }
    sd_test_require(sd_world_add_spheres(w, NS, s, &err) == SD_OK, "spheres", &err);
    sd_body_def b[NB];
    memset(b, 0, sizeof b);
    for (int k = 0; k < NB; ++k) {
        b[k].position = sd_test_v(0.00404 * k, 0, 0.00305);
        b[k].shape = shape;
        b[k].material = mat;
    }
    sd_test_require(sd_world_add_bodies(w, NB, b, &err) == SD_OK, "bodies", &err);

    const long steps = 50;
    double t0 = now_s();
    sd_test_require(sd_world_step(w, steps, &err) == SD_OK, "step", &err);
    double total = now_s() - t0;

    sd_profile p;
    sd_world_profile(w, &p);
    printf("%-12s %12s %8s\n", "stage", "seconds", "calls");
    double sum = 0;
    for (int k = 0; k < SD_PROFILE_STAGE_COUNT; ++k) {
        printf("%-12s %12.6f %8lld\n", sd_profile_stage_name(k), p.seconds[k], p.calls[k]);
        CHECK(p.seconds[k] >= 0);
        sum += p.seconds[k];
    }
    /* the prepare's forces count as one run of the force stages */
    CHECK_NEAR("rebuild stage calls", (double)p.calls[SD_PROFILE_REBUILD], (double)(steps + 1), 0);
    CHECK_NEAR("sphere pairs stage calls", (double)p.calls[SD_PROFILE_SPHERES], (double)(steps + 1), 0);
    CHECK_NEAR("convex pairs stage calls", (double)p.calls[SD_PROFILE_CONVEX], (double)(steps + 1), 0);
    CHECK_NEAR("walls stage calls", (double)p.calls[SD_PROFILE_WALLS], (double)(steps + 1), 0);
    CHECK_NEAR("integration stage calls", (double)p.calls[SD_PROFILE_INTEGRATION], (double)steps, 0);
    /* kinds absent from this world never run */
    CHECK_NEAR("polyhedron volume stage calls", (double)p.calls[SD_PROFILE_POLY_VOLUME], 0, 0);
    CHECK_NEAR("2D pairs stage calls", (double)p.calls[SD_PROFILE_CONVEX2D], 0, 0);
    CHECK_NEAR("output stage calls (nothing written)", (double)p.calls[SD_PROFILE_OUTPUT], 0, 0);
    printf("stages sum to %.6f s of %.6f s measured around sd_world_step\n", sum, total);
    CHECK(sum <= total);
    CHECK(sum > 0);

    /* the caller's output time */
    sd_world_profile_add(w, SD_PROFILE_OUTPUT, 0.25);
    sd_world_profile_add(w, SD_PROFILE_OUTPUT, -1.0); /* a clock that went back adds nothing */
    sd_world_profile(w, &p);
    CHECK_NEAR("output seconds after adding 0.25 s and -1 s", p.seconds[SD_PROFILE_OUTPUT], 0.25, 0);
    CHECK_NEAR("output calls", (double)p.calls[SD_PROFILE_OUTPUT], 2, 0);

    /* names: one per stage, distinct, NULL outside */
    for (int k = 0; k < SD_PROFILE_STAGE_COUNT; ++k) {
        CHECK(sd_profile_stage_name(k) != NULL);
        for (int j = 0; j < k; ++j)
            CHECK(strcmp(sd_profile_stage_name(k), sd_profile_stage_name(j)) != 0);
    }
    CHECK(sd_profile_stage_name(-1) == NULL);
    CHECK(sd_profile_stage_name(SD_PROFILE_STAGE_COUNT) == NULL);
    CHECK(strcmp(sd_profile_stage_name(SD_PROFILE_SPHERES), "spheres") == 0);
    sd_world_destroy(w);
    return sd_test_summary();
}
