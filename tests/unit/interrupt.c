/* interrupt.c — sd_world_request_interrupt (issue 31: the first SIGINT could
 * not stop one long placement, since signals were seen only between step
 * calls):
 *  - asked for before a call that starts with an insertion of 400
 *    particles, the call stops before the first particle (none placed,
 *    step 0, SD_ERR_INTERRUPTED), and the next call places all 400 and
 *    steps on to the same bits as a world never interrupted;
 *  - asked for before a call of 60 steps of a settling bed, the call stops
 *    after its first step, and 59 more give the uninterrupted world's bits
 *    (the step's fused kick and drift are split there as at any call's end);
 *  - the request is cleared by the call it stops.
 * With the insertion's look at the flag removed, the first check fails (400
 * placed); with the step's removed, the second (60 steps made).
 */
#include "test.h"

#include <string.h>

#include <shapedem/process.h>

static sd_world *sd_it_world(int insertion)
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
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    sd_test_require(sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.03, 0.03, 0.06), SD_BOX_ZMAX, mat,
                                     &err) >= 0,
                    "box", &err);
    if (insertion) {
        sd_insert_def id = sd_insert_def_default();
        id.region.kind = SD_REGION_BOX;
        id.region.lo = sd_test_v(0, 0, 0);
        id.region.hi = sd_test_v(0.03, 0.03, 0.06);
        id.entry_count = 1;
        id.entries[0].shape = -1;
        id.entries[0].material = mat;
        id.entries[0].size.kind = SD_SIZE_FIXED;
        id.entries[0].size.a = 0.001;
        id.entries[0].fraction = 1;
        id.count = 400; /* about 7 % of the box's volume: every one finds a spot */
        sd_test_require(sd_world_add_insertion(w, &id, &err) == 0, "insertion", &err);
    } else {
        sd_sphere_def sp[64];
        memset(sp, 0, sizeof sp);
        for (int k = 0; k < 64; ++k) {
            sp[k].position = sd_test_v(0.003 + 0.0032 * (k % 8), 0.015 + 0.0001 * (k % 3), 0.0011 + 0.0025 * (k / 8));
            sp[k].radius = 0.001;
            sp[k].material = mat;
        }
        sd_test_require(sd_world_add_spheres(w, 64, sp, &err) == SD_OK, "spheres", &err);
    }
    return w;
}

/* 1 when every particle of a has the bits of b's particle of the same id */
static int sd_it_same(const sd_world *a, const sd_world *b)
{
    if (sd_world_particle_count(a) != sd_world_particle_count(b) || sd_world_step_count(a) != sd_world_step_count(b))
        return 0;
    for (size_t k = 0; k < sd_world_particle_count(a); ++k) {
        sd_particle_state pa, pb;
        sd_world_get_particle(a, k, &pa);
        size_t j = sd_world_find_particle(b, pa.id);
        if (j == (size_t)-1 || sd_world_get_particle(b, j, &pb) != SD_OK)
            return 0;
        if (memcmp(&pa.position, &pb.position, sizeof pa.position) ||
            memcmp(&pa.velocity, &pb.velocity, sizeof pa.velocity))
            return 0;
    }
    return 1;
}

int main(void)
{
    sd_error err;
    for (int insertion = 1; insertion >= 0; --insertion) {
        sd_world *ref = sd_it_world(insertion), *w = sd_it_world(insertion);
        CHECK(sd_world_step(ref, 60, &err) == SD_OK);
        sd_world_request_interrupt(w);
        memset(&err, 0, sizeof err);
        sd_status st = sd_world_step(w, 60, &err);
        size_t n = sd_world_particle_count(w);
        long at = sd_world_step_count(w);
        printf("%s: interrupted call: %s (%s), %zu particles, step %ld\n",
               insertion ? "insertion of 400" : "64 settling", sd_status_name(st), err.msg, n, at);
        CHECK(st == SD_ERR_INTERRUPTED);
        CHECK(at == (insertion ? 0 : 1));
        CHECK(n == (insertion ? 0u : 64u));
        CHECK(sd_world_step(w, 60 - at, &err) == SD_OK); /* the request was cleared */
        printf("  continued to step %ld: %zu particles (uninterrupted %zu), same bits %d\n", sd_world_step_count(w),
               sd_world_particle_count(w), sd_world_particle_count(ref), sd_it_same(ref, w));
        CHECK(sd_world_particle_count(ref) == (insertion ? 400u : 64u));
        CHECK(sd_it_same(ref, w));
        sd_world_destroy(ref);
        sd_world_destroy(w);
    }
    sd_world_request_interrupt(NULL); /* ignored */
    return sd_test_summary();
}
