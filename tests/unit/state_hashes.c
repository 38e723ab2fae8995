/* state_hashes.c — the refactor's safety net: every example and bench scene,
 * stepped a few hundred steps, ends in the state recorded here, bit for bit.
 *
 * The scenes cover every interaction kind the engine has (sphere pairs with
 * the linear and Hertz laws, convex shapes by GJK/EPA, sharp polyhedra under
 * the volume law, the planar mode, plane and box walls, moving and servo
 * walls, the grid solver with its pour and outlet, composites: clumps of
 * nine spheres and crosses of three cylinders, element pairs by the sphere
 * law and by GJK/EPA), so a change of the step
 * pipeline that changes one bit anywhere shows here. The hash is FNV-1a over
 * each particle's position, velocity, spin and orientation in stable-id
 * order, then each wall's force and torque.
 *
 * A deliberate physics change updates the table: run with SD_PRINT_HASHES=1
 * and paste the printed rows, saying why in the commit.
 */
#include <stdlib.h>
#include <string.h>

#include "test.h"

#include "io/scene.h"

typedef struct hash_case {
    const char *scene; /* relative to the source tree */
    long steps;        /* enough for the first contacts to form */
    long min_contacts; /* particle and wall contacts at the end, at least */
    uint64_t hash;
} hash_case;

static const hash_case cases[] = {
{"examples/settle-spheres.yaml", 5500, 100, 0x699180ead3985a3cull},
    {"examples/mixed-shapes.yaml", 14000, 20, 0xb8c09af496bc696full},
    {"examples/polyhedra-pour.yaml", 20000, 12, 0xde409d2ffc603954ull},
    {"examples/biaxial-2d.yaml", 5000, 40, 0x94b639b7bf1cca23ull},
    {"examples/hopper-grid.yaml", 3000, 0, 0xed59cf1690b88852ull},
    {"bench/scenes/convex-settle.yaml", 300, 40, 0x6caa7cf763c45cffull},
    {"bench/scenes/sharp-cubes-settle.yaml", 8000, 20, 0xb5e477a988b80d8aull},
    {"bench/scenes/spheres-settle-8000.yaml", 400, 40, 0xc31ffbdc5b99be6eull},
    {"tests/validation/scenes/mixed-packing.yaml", 14000, 20, 0xeecac5d823edad29ull},
    {"tests/unit/scenes/restart-composites.yaml", 8000, 5, 0xa3c2cf7d89f42f50ull},
};

static void mix(uint64_t *h, const void *data, size_t size)
{
    const unsigned char *b = data;
    for (size_t k = 0; k < size; ++k) {
        *h ^= b[k];
        *h *= 1099511628211ull;
    }
}

static uint64_t world_hash(const sd_world *w)
{
    uint64_t h = 1469598103934665603ull;
    size_t n = sd_world_particle_count(w);
    for (uint64_t id = 0, found = 0; found < n; ++id) {
        size_t k = sd_world_find_particle(w, id);
        if (k == (size_t)-1) {
            if (id > 64 * (uint64_t)n + 1000000) /* ids are dense enough; never loop forever */
                break;
            continue;
        }
        ++found;
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        double v[] = {p.position.x, p.position.y, p.position.z, p.velocity.x, p.velocity.y, p.velocity.z,
                      p.angular_velocity.x, p.angular_velocity.y, p.angular_velocity.z, p.quat[0], p.quat[1],
                      p.quat[2], p.quat[3]};
        mix(&h, &id, sizeof id);
        mix(&h, v, sizeof v);
    }
    for (size_t k = 0; k < sd_world_wall_count(w); ++k) {
        sd_wall_info wi;
        sd_world_get_wall(w, k, &wi);
        double v[] = {wi.force.x, wi.force.y, wi.force.z, wi.torque.x, wi.torque.y, wi.torque.z};
        mix(&h, v, sizeof v);
    }
    return h;
}

int main(void)
{
    const char *src = getenv("SD_SOURCE_DIR");
    int print = getenv("SD_PRINT_HASHES") != NULL;
    sd_test_require(src != NULL, "SD_SOURCE_DIR is set (ctest sets it)", NULL);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", src, cases[c].scene);
        sd_error err;
        sd_scene *s;
        sd_world *w;
        sd_test_require(sd_scene_load(path, &s, &err) == SD_OK, cases[c].scene, &err);
        sd_test_require(sd_scene_build(s, &w, &err) == SD_OK, cases[c].scene, &err);
        sd_test_require(sd_world_step(w, cases[c].steps, &err) == SD_OK, cases[c].scene, &err);
        sd_stats st;
        sd_world_stats(w, &st);
        uint64_t h = world_hash(w);
        if (print)
            printf("    {\"%s\", %ld, %ld, 0x%016llxull},\n", cases[c].scene, cases[c].steps, cases[c].min_contacts,
                   (unsigned long long)h);
        else {
            printf("  %-44s %5ld steps %6zu particles %6ld contacts: hash %016llx, expected %016llx\n",
                   cases[c].scene, cases[c].steps, sd_world_particle_count(w), st.contacts + st.wall_contacts,
                   (unsigned long long)h, (unsigned long long)cases[c].hash);
            CHECK(h == cases[c].hash);
            CHECK(st.contacts + st.wall_contacts >= cases[c].min_contacts); /* the scene exercises contacts */
        }
        sd_world_destroy(w);
        sd_scene_free(s);
    }
    return sd_test_summary();
}
