/* poly_determinism.c — the volume-law pairs and walls give the same bits
 * with 1 and 2 threads (DESIGN.md rule 4: each pair writes its own slot,
 * each particle sums its pairs in a fixed order; the overlap workspace is
 * per thread and the per-pair hint x0 is history carried by key).
 *
 * 1200 dodecahedra and cubes (above SD_PARALLEL_MIN_PARTICLES, so the loops
 * really run on 2 threads) start on a tight lattice with random
 * orientations and velocities inside a box, some pairs overlapping, and
 * run 150 steps through several pair-list rebuilds; the final positions,
 * velocities, orientations and spins must be identical bit for bit.
 */
#include "poly_common.h"

#include "core/rng.h"

static void run(int threads, sd_particle_state *out, size_t n, long *rebuilds, long *contacts)
{
    int mat;
    sd_world *w = poly_world(SD_LAW_VOLUME, 2e-6, sd_test_v(0, 0, -9.81), 1e6, 0.5, 0.5, 2500, threads, &mat);
    w->def.skin = 2e-5; /* a thin skin: rebuilds every few steps, so the hints travel by key */
    sd_v3d v[20];
    poly_dodecahedron(0.005, v);
    int dod = poly_add_shape(w, "dodecahedron", v, 20);
    poly_cube(0.006, v);
    int cube = poly_add_shape(w, "cube", v, 8);
    sd_error err;
    sd_test_require(sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.09, 0.09, 0.2), 0, mat, &err) >= 0,
                    "box", &err);
    sd_rng rng = sd_rng_seed(5);
    sd_body_def *b = calloc(n, sizeof *b);
    for (size_t k = 0; k < n; ++k) {
        size_t ix = k % 10, iy = (k / 10) % 10, iz = k / 100;
        sd_quat q = sd_quat_normalize(sd_quat_make((sd_real)sd_rng_range(&rng, -1, 1), (sd_real)sd_rng_range(&rng, -1, 1),
                                                   (sd_real)sd_rng_range(&rng, -1, 1), (sd_real)sd_rng_range(&rng, -1, 1)));
        b[k].orientation[0] = q.w;
        b[k].orientation[1] = q.x;
        b[k].orientation[2] = q.y;
        b[k].orientation[3] = q.z;
        b[k].position = sd_test_v(0.006 + 0.0087 * (double)ix, 0.006 + 0.0087 * (double)iy, 0.006 + 0.0087 * (double)iz);
        b[k].velocity = sd_test_v(sd_rng_range(&rng, -0.3, 0.3), sd_rng_range(&rng, -0.3, 0.3), sd_rng_range(&rng, -0.3, 0.3));
        b[k].angular_velocity = sd_test_v(sd_rng_range(&rng, -20, 20), sd_rng_range(&rng, -20, 20), sd_rng_range(&rng, -20, 20));
        b[k].shape = (k % 3 == 0) ? cube : dod;
        b[k].material = mat;
    }
    sd_test_require(sd_world_add_bodies(w, n, b, &err) == SD_OK, "bodies", &err);
    free(b);
    sd_test_require(sd_world_step(w, 150, &err) == SD_OK, "step", &err);
    for (size_t k = 0; k < n; ++k)
        sd_world_get_particle(w, sd_world_find_particle(w, (uint64_t)k), &out[k]);
    sd_stats st;
    sd_world_stats(w, &st);
    *rebuilds = st.rebuilds;
    *contacts = st.contacts + st.wall_contacts;
    sd_world_destroy(w);
}

int main(void)
{
    const size_t n = 1200;
    sd_particle_state *a = calloc(n, sizeof *a), *b = calloc(n, sizeof *b);
    long r1, r2, c1, c2;
    run(1, a, n, &r1, &c1);
    run(2, b, n, &r2, &c2);
    printf("%zu bodies, 150 steps: %ld pair-list rebuilds, %ld contacts at the end\n", n, r1, c1);
    size_t diff = 0;
    for (size_t k = 0; k < n; ++k)
        diff += memcmp(&a[k].position, &b[k].position, sizeof a[k].position) != 0 ||
                memcmp(&a[k].velocity, &b[k].velocity, sizeof a[k].velocity) != 0 ||
                memcmp(&a[k].angular_velocity, &b[k].angular_velocity, sizeof a[k].angular_velocity) != 0 ||
                memcmp(a[k].quat, b[k].quat, sizeof a[k].quat) != 0;
    CHECK(c1 > 100);
    CHECK_NEAR("bodies whose state differs, 1 vs 2 threads", (double)diff, 0.0, 0.0);
    CHECK_NEAR("rebuilds, 1 vs 2 threads", (double)r2, (double)r1, 0.0);
    free(a);
    free(b);
    return sd_test_summary();
}
