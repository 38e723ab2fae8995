/* remove.c — removal of marked particles between steps (world/remove.c):
 *  - history: two packs far apart settle with friction; removing one of
 *    them mid-run keeps every tangential spring of the other by key, and
 *    100 steps later that pack is where it is in the world that kept both
 *    (to round-off: the sums' order may change with the forced rebuild; a
 *    lost or misplaced spring moves grains by far more than the tolerance);
 *  - consistency: after a removal in a periodic world (so ghosts go too)
 *    every array, ghost and pair refers to a present particle with the
 *    right stable id, the removed count and mass are what was marked, and
 *    the stats read the compacted lists;
 *  - determinism: a run that removes particles every few hundred steps
 *    gives the same bits with 1 and 2 threads (1,200 spheres, so the
 *    loops do run on threads).
 */
#include <math.h>
#include <string.h>

#include "test.h"

#include "core/rng.h"
#include "world/remove.h"
#include "world/world.h"

static uint64_t state_hash(const sd_world *w)
{
    uint64_t h = 1469598103934665603ull;
    size_t n = sd_world_particle_count(w);
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        double v[] = {(double)p.id,         p.position.x, p.position.y, p.position.z, p.velocity.x,
                      p.velocity.y,         p.velocity.z, p.quat[0],    p.quat[1],    p.quat[2],
                      p.angular_velocity.z, p.quat[3]};
        const unsigned char *b = (const unsigned char *)v;
        for (size_t i = 0; i < sizeof v; ++i) {
            h ^= b[i];
            h *= 1099511628211ull;
        }
    }
    return h;
}

static sd_world *make_world(int threads, unsigned periodic, int *mat)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.threads = threads;
    d.dt = 1e-5;
    d.skin = 2e-4; /* m, fixed so both worlds of a comparison rebuild alike */
    d.periodic = periodic;
    d.domain_lo = sd_test_v(0, 0, 0);
    d.domain_hi = sd_test_v(0.03, 0.03, 0.2);
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    m.friction = 0.5;
    *mat = sd_world_add_material(w, &m, &err);
    sd_test_require(*mat >= 0, "material", &err);
    return w;
}

/* n spheres on a jittered lattice in [x0, x0 + 0.03] x [0, 0.03] x [0, ...]. */
static void add_pack(sd_world *w, int mat, double x0, int n, uint64_t seed)
{
    sd_error err;
    sd_rng r = sd_rng_seed(seed);
    sd_sphere_def *s = calloc((size_t)n, sizeof *s);
    for (int k = 0; k < n; ++k) {
        int i = k % 12, j = (k / 12) % 12, l = k / 144;
        s[k].position = sd_test_v(x0 + 0.0012 + 0.0025 * i, 0.0012 + 0.0025 * j, 0.0012 + 0.0025 * l);
        s[k].velocity = sd_test_v(sd_rng_range(&r, -0.1, 0.1), sd_rng_range(&r, -0.1, 0.1), 0);
        s[k].radius = sd_rng_range(&r, 0.0009, 0.0012);
        s[k].material = mat;
    }
    sd_test_require(sd_world_add_spheres(w, (size_t)n, s, &err) == SD_OK, "spheres", &err);
    free(s);
}

static int beyond_half_metre(const sd_world *w, size_t k, void *ctx)
{
    (void)ctx;
    return w->p.x[k].x > 0.5;
}

static void test_history(void)
{
    sd_error err;
    int ma, mb;
    sd_world *a = make_world(1, 0, &ma), *b = make_world(1, 0, &mb);
    sd_world *ws[2] = {a, b};
    for (int k = 0; k < 2; ++k) {
        int m = k ? mb : ma;
        sd_world_add_box(ws[k], "box", sd_test_v(0, 0, 0), sd_test_v(0.03, 0.03, 0.2), SD_BOX_ZMAX, m, &err);
        sd_world_add_box(ws[k], "far", sd_test_v(1, 0, 0), sd_test_v(1.03, 0.03, 0.2), SD_BOX_ZMAX, m, &err);
        add_pack(ws[k], m, 0, 300, 5);
        add_pack(ws[k], m, 1, 300, 6);
        sd_test_require(sd_world_step(ws[k], 3000, &err) == SD_OK, "step", &err);
    }
    /* the springs of the surviving pairs, by key, before the removal */
    size_t np = a->pairs.n, kept = 0, same = 0;
    sd_pair_key *keys = calloc(np, sizeof *keys);
    sd_vec3 *ds = calloc(np, sizeof *ds);
    for (size_t e = 0; e < np; ++e)
        if (a->p.x[a->pairs.i[e]].x < 0.5 && sd_v3_norm(a->pairs.ds[e]) > 0) {
            keys[kept] = a->pairs.key[e];
            ds[kept++] = a->pairs.ds[e];
        }
    sd_stats st;
    sd_world_stats(a, &st);
    long contacts_before = st.contacts;
    sd_remove_result res;
    CHECK(sd_world_remove_if(a, beyond_half_metre, NULL, &res, &err) == SD_OK);
    CHECK(res.count == 300);
    CHECK(sd_world_particle_count(a) == 300);
    sd_world_stats(a, &st);
    printf("     contacts before removal %ld, after %ld\n", contacts_before, st.contacts);
    CHECK(st.contacts > 0 && st.contacts < contacts_before);
    for (size_t q = 0; q < kept; ++q)
        for (size_t e = 0; e < a->pairs.n; ++e)
            if (a->pairs.key[e].id_lo == keys[q].id_lo && a->pairs.key[e].id_hi == keys[q].id_hi) {
                same += sd_v3_norm(sd_v3_sub(a->pairs.ds[e], ds[q])) == 0;
                break;
            }
    printf("     tangential springs kept bit for bit by key: %zu of %zu (largest %.3g m)\n", same, kept,
           (double)sd_v3_norm(ds[0]));
    CHECK(kept > 0 && same == kept);
    free(keys);
    free(ds);
    /* 100 steps on: the pack left behind follows the world that kept the
     * other pack (the packs never meet) to round-off; a spring lost or
     * given to the wrong pair moves grains by ~1e-5 m in that time */
    sd_test_require(sd_world_step(a, 100, &err) == SD_OK, "step a after", &err);
    sd_test_require(sd_world_step(b, 100, &err) == SD_OK, "step b after", &err);
    double dmax = 0;
    for (uint64_t id = 0; id < 300; ++id) {
        sd_particle_state pa, pb;
        size_t ka = sd_world_find_particle(a, id), kb = sd_world_find_particle(b, id);
        CHECK(ka != (size_t)-1 && kb != (size_t)-1);
        sd_world_get_particle(a, ka, &pa);
        sd_world_get_particle(b, kb, &pb);
        dmax = fmax(dmax, fabs(pa.position.x - pb.position.x) + fabs(pa.position.y - pb.position.y) +
                              fabs(pa.position.z - pb.position.z));
    }
    CHECK_NEAR("pack after removal vs kept: max |dx| (m)", dmax, 0, 1e-10);
    sd_world_destroy(a);
    sd_world_destroy(b);
}

static int near_low_x(const sd_world *w, size_t k, void *ctx)
{
    (void)ctx;
    return w->p.x[k].x < 0.003 || w->p.id[k] % 7 == 3;
}

static void test_consistency(void)
{
    sd_error err;
    int mat;
    sd_world *w = make_world(1, SD_PERIODIC_X | SD_PERIODIC_Y, &mat);
    sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err);
    add_pack(w, mat, 0, 400, 9);
    sd_test_require(sd_world_step(w, 1500, &err) == SD_OK, "step", &err);
    size_t n0 = w->p.n, ng0 = w->n_ghost, expect = 0;
    double mass = 0;
    for (size_t k = 0; k < n0; ++k)
        if (near_low_x(w, k, NULL)) {
            ++expect;
            mass += 1.0 / (double)w->p.inv_mass[k];
        }
    sd_remove_result res;
    CHECK(sd_world_remove_if(w, near_low_x, NULL, &res, &err) == SD_OK);
    printf("     removed %zu of %zu (ghosts %zu -> %zu), mass %.6g kg\n", res.count, n0, ng0, w->n_ghost, res.mass);
    CHECK(res.count == expect && expect > 0);
    CHECK_REL("removed mass (kg)", res.mass, mass, 1e-14);
    CHECK(w->p.n == n0 - expect);
    CHECK(w->n_ghost < ng0);
    int bad = 0;
    for (size_t k = 0; k < w->p.n; ++k)
        bad += near_low_x(w, k, NULL) && w->p.x[k].x < 0.003 ? 1 : 0;
    for (size_t k = 0; k < w->p.n; ++k)
        bad += w->p.id[k] % 7 == 3;
    for (size_t g = 0; g < w->n_ghost; ++g) {
        size_t o = w->ghost_owner[g], d = w->p.n + g;
        bad += o >= w->p.n;
        bad += w->p.id[d] != w->p.id[o];
        bad += sd_v3_norm(sd_v3_sub(w->p.x[d], sd_v3_add(w->p.x[o], w->ghost_shift[g]))) > 1e-12;
    }
    for (size_t e = 0; e < w->pairs.n; ++e) {
        uint32_t i = w->pairs.i[e], j = w->pairs.j[e];
        bad += i >= w->p.n || j >= w->p.n + w->n_ghost;
        uint64_t lo = w->p.id[i] < w->p.id[j] ? w->p.id[i] : w->p.id[j];
        uint64_t hi = w->p.id[i] < w->p.id[j] ? w->p.id[j] : w->p.id[i];
        bad += w->pairs.key[e].id_lo != lo || w->pairs.key[e].id_hi != hi;
    }
    for (size_t e = 0; e < w->wpairs.n; ++e)
        bad += w->wpairs.i[e] >= w->p.n || w->wpairs.key[e].id != w->p.id[w->wpairs.i[e]];
    CHECK(w->pairs.kind_start[SD_PAIR_KIND_COUNT] == w->pairs.n);
    printf("     inconsistent entries after removal: %d\n", bad);
    CHECK(bad == 0);
    sd_stats st;
    sd_world_stats(w, &st);
    CHECK(st.contacts > 0);
    sd_test_require(sd_world_step(w, 500, &err) == SD_OK, "step after", &err);
    CHECK(sd_world_particle_count(w) == n0 - expect);
    sd_world_destroy(w);
}

static int in_column(const sd_world *w, size_t k, void *ctx)
{
    double x0 = *(const double *)ctx;
    return w->p.x[k].x > x0 && w->p.x[k].x < x0 + 0.004;
}

static uint64_t run_threads(int threads, size_t *left)
{
    sd_error err;
    int mat;
    sd_world *w = make_world(threads, 0, &mat);
    sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.03, 0.03, 0.2), SD_BOX_ZMAX, mat, &err);
    add_pack(w, mat, 0, 1200, 13);
    for (int round = 0; round < 3; ++round) {
        sd_test_require(sd_world_step(w, 200, &err) == SD_OK, "step", &err);
        double x0 = 0.004 + 0.008 * round;
        sd_remove_result res;
        sd_test_require(sd_world_remove_if(w, in_column, &x0, &res, &err) == SD_OK, "remove", &err);
    }
    sd_test_require(sd_world_step(w, 200, &err) == SD_OK, "step", &err);
    *left = sd_world_particle_count(w);
    uint64_t h = state_hash(w);
    sd_world_destroy(w);
    return h;
}

static void test_threads(void)
{
    size_t n1, n2;
    uint64_t h1 = run_threads(1, &n1), h2 = run_threads(2, &n2);
    printf("     1 thread: %zu particles left, hash %016llx; 2 threads: %zu, %016llx\n", n1, (unsigned long long)h1,
           n2, (unsigned long long)h2);
    CHECK(n1 == n2 && n1 < 1200);
    CHECK(h1 == h2);
}

int main(void)
{
    test_history();
    test_consistency();
    test_threads();
    return sd_test_summary();
}
