/* insert_bounds.c — insertion on input that used to hang or place
 * particles where none belong (issue 31, probe 3 findings 8 and 11):
 *  - a region crossing a box's closed face, or a plane: every particle
 *    inserted lies inside the walls (its bounding sphere), where 9 of them
 *    used to start outside the box, silently;
 *  - a region entirely outside the walls: nothing inserted, and the reason
 *    says so;
 *  - all at once (a count, no rate) into a region that holds a few
 *    hundred: the insertion stops after SD_INSERT_GIVE_UP particles in a
 *    row found no spot, and says so (10^5 used to be tried 100 times each);
 *  - a log-normal law whose sigma draws infinite radii, and attempts above
 *    SD_INSERT_ATTEMPTS_MAX, are refused (the first used to loop forever
 *    in the placement grid, the second never to end).
 */
#include "test.h"

#include <string.h>

#include <shapedem/process.h>

static sd_world *sd_ib_world(int *mat)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.threads = 1;
    d.dt = 1e-5;
    d.gravity = sd_test_v(0, 0, -9.81);
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "a";
    m.youngs_modulus = 1e7;
    *mat = sd_world_add_material(w, &m, &err);
    sd_test_require(*mat >= 0, "material", &err);
    return w;
}

static sd_insert_def sd_ib_def(int mat, sd_v3d lo, sd_v3d hi, size_t count)
{
    sd_insert_def d = sd_insert_def_default();
    d.region.kind = SD_REGION_BOX;
    d.region.lo = lo;
    d.region.hi = hi;
    d.entry_count = 1;
    d.entries[0].shape = -1;
    d.entries[0].material = mat;
    d.entries[0].size.kind = SD_SIZE_FIXED;
    d.entries[0].size.a = 0.001;
    d.entries[0].fraction = 1;
    d.count = count;
    return d;
}

/* The smallest distance by which a particle's sphere lies inside the
 * half-spaces x >= 0 (box) and z >= 0 (box floor or plane); < 0: outside. */
static double sd_ib_worst(const sd_world *w, int axis)
{
    double worst = HUGE_VAL;
    for (size_t k = 0; k < sd_world_particle_count(w); ++k) {
        sd_particle_state s;
        sd_world_get_particle(w, k, &s);
        double c = axis == 0 ? s.position.x : s.position.z;
        worst = fmin(worst, c - s.radius);
    }
    return worst;
}

int main(void)
{
    sd_error err;
    int mat;
    /* 1. crossing the xmin face of a box (the probe's scene: box x in [0, 0.02]) */
    sd_world *w = sd_ib_world(&mat);
    sd_test_require(sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.02, 0.02, 0.05), SD_BOX_ZMAX, mat,
                                     &err) >= 0,
                    "box", &err);
    sd_insert_def d = sd_ib_def(mat, sd_test_v(-0.01, 0.003, 0.02), sd_test_v(0.01, 0.017, 0.04), 60);
    CHECK(sd_world_add_insertion(w, &d, &err) == 0);
    CHECK(sd_world_step(w, 1, &err) == SD_OK);
    sd_insert_info info;
    CHECK(sd_world_get_insertion(w, 0, &info) == SD_OK);
    printf("region across the box's xmin face: inserted %zu of %zu\n", info.inserted, info.asked);
    CHECK(info.inserted > 10);
    CHECK_NEAR("least depth inside the box face x = 0, clipped (m)", fmin(sd_ib_worst(w, 0), 0.0), 0.0, 0.0);
    sd_world_destroy(w);

    /* 2. crossing a floor plane z = 0.01 */
    w = sd_ib_world(&mat);
    sd_test_require(sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0.01), sd_test_v(0, 0, 1), mat, &err) >= 0,
                    "plane", &err);
    d = sd_ib_def(mat, sd_test_v(0, 0, 0), sd_test_v(0.02, 0.02, 0.02), 60);
    CHECK(sd_world_add_insertion(w, &d, &err) == 0);
    CHECK(sd_world_step(w, 1, &err) == SD_OK);
    CHECK(sd_world_get_insertion(w, 0, &info) == SD_OK);
    printf("region across a floor plane: inserted %zu of %zu\n", info.inserted, info.asked);
    CHECK(info.inserted > 10);
    CHECK_NEAR("least height above the plane z = 0.01 (m)", fmin(sd_ib_worst(w, 2) - 0.01, 0.0), 0.0, 1e-15);
    sd_world_destroy(w);

    /* 3. a region outside the box */
    w = sd_ib_world(&mat);
    sd_test_require(sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.02, 0.02, 0.05), SD_BOX_ZMAX, mat,
                                     &err) >= 0,
                    "box", &err);
    d = sd_ib_def(mat, sd_test_v(1, 1, 1), sd_test_v(1.01, 1.01, 1.01), 10);
    CHECK(sd_world_add_insertion(w, &d, &err) == 0);
    CHECK(sd_world_step(w, 1, &err) == SD_OK);
    CHECK(sd_world_get_insertion(w, 0, &info) == SD_OK);
    printf("region outside the box: inserted %zu of %zu: %s\n", info.inserted, info.asked, info.why);
    CHECK(info.inserted == 0 && sd_world_particle_count(w) == 0);
    CHECK(strstr(info.why, "outside the walls") != NULL);
    sd_world_destroy(w);

    /* 4. 10^5 at once into a region that holds a few hundred */
    w = sd_ib_world(&mat);
    d = sd_ib_def(mat, sd_test_v(0, 0, 0), sd_test_v(0.016, 0.016, 0.016), 100000);
    CHECK(sd_world_add_insertion(w, &d, &err) == 0);
    CHECK(sd_world_step(w, 1, &err) == SD_OK);
    CHECK(sd_world_get_insertion(w, 0, &info) == SD_OK);
    printf("10^5 at once into a small region: inserted %zu of %zu, done %d: %s\n", info.inserted, info.asked,
           info.done, info.why);
    CHECK(info.done && info.asked == 100000 && info.inserted > 100 && info.inserted < 1000);
    CHECK(strstr(info.why, "in a row") != NULL);
    sd_world_destroy(w);

    /* 5. refused: sigma 100, attempts above the maximum */
    w = sd_ib_world(&mat);
    d = sd_ib_def(mat, sd_test_v(0, 0, 0), sd_test_v(0.02, 0.02, 0.02), 10);
    d.entries[0].size.kind = SD_SIZE_LOGNORMAL;
    d.entries[0].size.b = 100;
    CHECK(sd_world_add_insertion(w, &d, &err) < 0 && err.code == SD_ERR_INPUT);
    printf("sigma 100: %s\n", err.msg);
    d.entries[0].size.b = 1.0; /* exp(8) = 2981 times the median: taken */
    CHECK(sd_world_add_insertion(w, &d, &err) == 0);
    d = sd_ib_def(mat, sd_test_v(0, 0, 0), sd_test_v(0.02, 0.02, 0.02), 10);
    d.attempts = SD_INSERT_ATTEMPTS_MAX + 1;
    CHECK(sd_world_add_insertion(w, &d, &err) < 0 && err.code == SD_ERR_INPUT);
    printf("attempts %d: %s\n", d.attempts, err.msg);
    sd_world_destroy(w);
    return sd_test_summary();
}
