/* determinism.c — the same scene gives the same bits with 1 and 2 threads
 * (DESIGN.md rule 4), here 2,000 spheres settling in a box with friction,
 * through many pair-list rebuilds, re-sorting and history carry-over.
 */
#include <string.h>

#include "test.h"

#include "core/rng.h"

/* FNV-1a over the state of every particle, in stable-id order. */
static uint64_t state_hash(const sd_world *w)
{
    uint64_t h = 1469598103934665603ull;
    size_t n = sd_world_particle_count(w);
    for (uint64_t id = 0; id < n; ++id) {
        sd_particle_state p;
        sd_world_get_particle(w, sd_world_find_particle(w, id), &p);
        double v[] = {p.position.x, p.position.y, p.position.z, p.velocity.x, p.velocity.y, p.velocity.z,
                      p.angular_velocity.x, p.angular_velocity.y, p.angular_velocity.z, p.quat[0], p.quat[1],
                      p.quat[2], p.quat[3]};
        const unsigned char *b = (const unsigned char *)v;
        for (size_t k = 0; k < sizeof v; ++k) {
            h ^= b[k];
            h *= 1099511628211ull;
        }
    }
    return h;
}

static uint64_t run(int threads, long steps, sd_stats *st)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.threads = threads;
    d.dt = 1e-5;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    m.restitution = 0.5;
    m.friction = 0.5;
    m.rolling_friction = 0.01;
    int mat = sd_world_add_material(w, &m, &err);
    sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.03, 0.03, 0.2), SD_BOX_ZMAX, mat, &err);
    sd_rng r = sd_rng_seed(11);
    sd_sphere_def s[2000];
    for (int k = 0; k < 2000; ++k) {
        int i = k % 12, j = (k / 12) % 12, l = k / 144;
        s[k] = (sd_sphere_def){0};
        s[k].position = sd_test_v(0.0012 + 0.0025 * i, 0.0012 + 0.0025 * j, 0.0012 + 0.0025 * l);
        s[k].velocity = sd_test_v(sd_rng_range(&r, -0.1, 0.1), sd_rng_range(&r, -0.1, 0.1), sd_rng_range(&r, -0.1, 0.1));
        s[k].radius = sd_rng_range(&r, 0.0009, 0.0012);
        s[k].material = mat;
    }
    sd_world_add_spheres(w, 2000, s, &err);
    sd_test_require(sd_world_step(w, steps, &err) == SD_OK, "step", &err);
    sd_world_stats(w, st);
    uint64_t h = state_hash(w);
    sd_world_destroy(w);
    return h;
}

int main(void)
{
    sd_stats a, b;
    uint64_t h1 = run(1, 8000, &a);
    uint64_t h2 = run(2, 8000, &b);
    printf("     1 thread : hash %016llx, %ld contacts, %ld rebuilds\n", (unsigned long long)h1, a.contacts, a.rebuilds);
    printf("     2 threads: hash %016llx, %ld contacts, %ld rebuilds\n", (unsigned long long)h2, b.contacts, b.rebuilds);
    CHECK(h1 == h2);
    CHECK(a.contacts == b.contacts);
    CHECK(a.rebuilds > 3);
    CHECK(a.contacts > 1000); /* the test exercises contacts and history */
    return sd_test_summary();
}
