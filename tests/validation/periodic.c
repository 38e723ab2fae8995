/* periodic.c — periodic boundaries (world/rebuild.c: images as ghosts,
 * broad/bins.h: each contact across the boundary once).
 *
 * 1. A free sphere crossing periodic faces keeps its velocity and spin bit
 *    for bit, and its wrapped position is the free flight modulo the period.
 * 2. A sphere pair across a corner of a fully periodic box, a sharp cube
 *    pair under the volume law across x, and a pair of 2D ellipses across
 *    y get the same forces and torques (to 1e-12 relative) as the same
 *    pairs in the middle of the domain, at the first evaluation and after
 *    some steps of sliding and spinning contact (the iterative 2D narrow
 *    phase: as well as the same pair merely moved there, see pair_case).
 * 3. 1,500 spheres in a periodic box without gravity, crossing the faces,
 *    give the same bits on 1 and 2 threads.
 * (The many-body conservation run is tests/validation/periodic_gas.c.)
 */
#include <string.h>

#include "test.h"

#include "core/rng.h"
#include "world/world.h"

#define L 0.02 /* m, the period */

static sd_world *world_of(int dim, unsigned periodic, int law, int threads)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dimension = dim;
    d.dt = 1e-6;
    d.gravity = sd_test_v(0, 0, 0);
    d.law = (sd_contact_law)law;
    d.threads = threads;
    d.skin = 2e-4;
    d.periodic = periodic;
    d.domain_lo = sd_test_v(-0.5 * L, -0.5 * L, dim == 2 ? -1 : -0.5 * L);
    d.domain_hi = sd_test_v(0.5 * L, 0.5 * L, dim == 2 ? 1 : 0.5 * L);
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    m.friction = 0.4;
    m.restitution = 0.6;
    sd_test_require(sd_world_add_material(w, &m, &err) >= 0, "material", &err);
    return w;
}

static sd_particle_state state_of(const sd_world *w, uint64_t id)
{
    sd_particle_state s;
    size_t k = sd_world_find_particle(w, id);
    sd_test_require(k != (size_t)-1 && sd_world_get_particle(w, k, &s) == SD_OK, "particle", NULL);
    return s;
}

/* ---- 1. crossing --------------------------------------------------------- */

static void crossing(void)
{
    sd_error err;
    sd_world *w = world_of(3, SD_PERIODIC_X | SD_PERIODIC_Y | SD_PERIODIC_Z, SD_LAW_HERTZ_MINDLIN, 1);
    sd_sphere_def s;
    memset(&s, 0, sizeof s);
    s.position = sd_test_v(0.003, -0.004, 0.002);
    s.velocity = sd_test_v(3.1, -1.7, 0.9);
    s.angular_velocity = sd_test_v(10.5, -20.25, 30.125);
    s.radius = 1e-3;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    long steps = 20000; /* 0.02 s: 3 periods in x, 1.7 in y, 0.9 in z */
    sd_test_require(sd_world_step(w, steps, &err) == SD_OK, "step", &err);
    sd_particle_state p = state_of(w, 0);
    CHECK_NEAR("velocity kept bit for bit (1 = yes)",
               (double)(memcmp(&p.velocity, &s.velocity, sizeof s.velocity) == 0), 1, 0);
    CHECK_NEAR("spin kept bit for bit (1 = yes)",
               (double)(memcmp(&p.angular_velocity, &s.angular_velocity, sizeof s.angular_velocity) == 0), 1, 0);
    double t = (double)steps * 1e-6;
    const double x0[3] = {s.position.x, s.position.y, s.position.z}, v[3] = {s.velocity.x, s.velocity.y, s.velocity.z};
    sd_v3d got = p.position;
    sd_world_wrap_periodic(w, &got);
    const double g[3] = {got.x, got.y, got.z};
    for (int a = 0; a < 3; ++a) {
        double free = x0[a] + v[a] * t, want = free - L * floor((free + 0.5 * L) / L);
        char label[64];
        snprintf(label, sizeof label, "wrapped position %c, m", "xyz"[a]);
        CHECK_NEAR(label, g[a], want, 1e-12);
    }
    CHECK(w->rebuilds > 10);
    sd_world_destroy(w);
}

/* ---- 2. pairs across the boundary ------------------------------------------- */

/* Adds the pair: body 0 at a, body 1 at a + d, both wrapped into the box by
 * the caller's choice of a; kind 0 spheres, 1 sharp cubes, 2 ellipses (2D). */
static void add_pair(sd_world *w, int kind, sd_v3d a, sd_v3d d)
{
    sd_error err;
    sd_v3d b = sd_test_v(a.x + d.x, a.y + d.y, a.z + d.z);
    sd_world_wrap_periodic(w, &b);
    sd_v3d va = sd_test_v(0.05, -0.02, kind == 2 ? 0 : 0.01), vb = sd_test_v(-0.04, 0.03, kind == 2 ? 0 : -0.02);
    sd_v3d wa = sd_test_v(kind == 2 ? 0 : 3, kind == 2 ? 0 : -2, 5), wb = sd_test_v(kind == 2 ? 0 : -1, kind == 2 ? 0 : 4, -6);
    if (kind == 0) {
        sd_sphere_def s[2];
        memset(s, 0, sizeof s);
        s[0].position = a;
        s[1].position = b;
        s[0].velocity = va;
        s[1].velocity = vb;
        s[0].angular_velocity = wa;
        s[1].angular_velocity = wb;
        s[0].radius = 1e-3;
        s[1].radius = 0.9e-3;
        sd_test_require(sd_world_add_spheres(w, 2, s, &err) == SD_OK, "spheres", &err);
        return;
    }
    int shape;
    if (kind == 1) {
        sd_v3d v[8];
        int n = 0;
        for (int i = -1; i <= 1; i += 2)
            for (int j = -1; j <= 1; j += 2)
                for (int k = -1; k <= 1; k += 2)
                    v[n++] = sd_test_v(1e-3 * i, 1e-3 * j, 1e-3 * k);
        sd_shape_desc sd = sd_shape_desc_default();
        sd.kind = "polyhedron";
        sd.vertices = v;
        sd.vertex_count = 8;
        shape = sd_world_add_shape(w, "cube", &sd, &err);
    } else {
        sd_shape2d_def sd = sd_shape2d_def_default();
        sd.kind = "ellipse";
        sd.semi_axes[0] = 1.2e-3;
        sd.semi_axes[1] = 0.7e-3;
        shape = sd_world_add_shape2d(w, "ellipse", &sd, &err);
    }
    sd_test_require(shape >= 0, "shape", &err);
    sd_body_def bd[2];
    memset(bd, 0, sizeof bd);
    bd[0].position = a;
    bd[1].position = b;
    bd[0].velocity = va;
    bd[1].velocity = vb;
    bd[0].angular_velocity = wa;
    bd[1].angular_velocity = wb;
    bd[0].shape = bd[1].shape = shape;
    bd[0].orientation[0] = 1;
    bd[1].orientation[0] = 0.95;
    bd[1].orientation[3] = 0.3;
    if (kind == 1)
        bd[1].orientation[1] = 0.1;
    sd_test_require(sd_world_add_bodies(w, 2, bd, &err) == SD_OK, "bodies", &err);
}

static double rel_diff(sd_v3d a, sd_v3d b)
{
    double n = sqrt(b.x * b.x + b.y * b.y + b.z * b.z);
    double d = sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
    return n > 0 ? d / n : d;
}

/* The force of the pair in the middle, across the boundary (edge: where
 * body 0 sits), and, as the reference for what moving a pair does to the
 * bits at all, the same pair moved to edge in a world without periodic
 * axes (only the iterative 2D narrow phase feels it: its tolerances are
 * relative, its iterations start from the moved coordinates). The pair
 * across the boundary must agree with the middle to 1e-12, or at worst as
 * well as the moved pair does. */
static void pair_case(const char *name, int kind, int dim, unsigned periodic, int law, sd_v3d edge, sd_v3d d,
                      long steps)
{
    sd_error err;
    sd_world *mid = world_of(dim, periodic, law, 1), *across = world_of(dim, periodic, law, 1),
             *moved = world_of(dim, 0, law, 1);
    add_pair(mid, kind, sd_test_v(-0.5 * d.x, -0.5 * d.y, -0.5 * d.z), d);
    add_pair(across, kind, edge, d);
    add_pair(moved, kind, edge, d); /* no wrap: the pair sticks out of the box */
    sd_test_require(sd_world_prepare(mid, &err) == SD_OK, "prepare", &err);
    sd_test_require(sd_world_prepare(across, &err) == SD_OK, "prepare", &err);
    sd_test_require(sd_world_prepare(moved, &err) == SD_OK, "prepare", &err);
    char label_ref[96];
    for (int round = 0; round < 2; ++round) {
        if (round == 1) {
            sd_test_require(sd_world_step(mid, steps, &err) == SD_OK, "step", &err);
            sd_test_require(sd_world_step(across, steps, &err) == SD_OK, "step", &err);
            sd_test_require(sd_world_step(moved, steps, &err) == SD_OK, "step", &err);
        }
        sd_particle_state m0 = state_of(mid, 0), m1 = state_of(mid, 1), a0 = state_of(across, 0),
                          a1 = state_of(across, 1), t0 = state_of(moved, 0), t1 = state_of(moved, 1);
        double ref = fmax(fmax(rel_diff(t0.force, m0.force), rel_diff(t1.force, m1.force)),
                          fmax(rel_diff(t0.torque, m0.torque), rel_diff(t1.torque, m1.torque)));
        double tol = fmax(1e-12, ref);
        printf("     %s: the moved pair (no periodic axes) differs from the middle by %.3g (relative)\n", name, ref);
        /* the reference widens the tolerance only within the narrow phase's
         * own relative tolerances (1e-8 and tighter), never to anything */
        snprintf(label_ref, sizeof label_ref, "%s %s: moved pair vs middle, rel. diff", name, round ? "later" : "start");
        CHECK_NEAR(label_ref, ref, 0, 1e-9);
        double fn = sqrt(m0.force.x * m0.force.x + m0.force.y * m0.force.y + m0.force.z * m0.force.z);
        char label[96];
        snprintf(label, sizeof label, "%s: |F| > 0 in contact (%s), N", name, round ? "later" : "start");
        CHECK(fn > 0);
        printf("     %s\n", label);
        snprintf(label, sizeof label, "%s %s: force on 0, rel. diff", name, round ? "later" : "start");
        CHECK_NEAR(label, rel_diff(a0.force, m0.force), 0, tol);
        snprintf(label, sizeof label, "%s %s: force on 1, rel. diff", name, round ? "later" : "start");
        CHECK_NEAR(label, rel_diff(a1.force, m1.force), 0, tol);
        snprintf(label, sizeof label, "%s %s: torque on 0, rel. diff", name, round ? "later" : "start");
        CHECK_NEAR(label, rel_diff(a0.torque, m0.torque), 0, tol);
        snprintf(label, sizeof label, "%s %s: torque on 1, rel. diff", name, round ? "later" : "start");
        CHECK_NEAR(label, rel_diff(a1.torque, m1.torque), 0, tol);
        /* momentum: the ghost's reaction reaches its owner */
        sd_v3d sum = sd_test_v(a0.force.x + a1.force.x, a0.force.y + a1.force.y, a0.force.z + a1.force.z);
        snprintf(label, sizeof label, "%s %s: |F0 + F1| / |F0|", name, round ? "later" : "start");
        CHECK_NEAR(label, sqrt(sum.x * sum.x + sum.y * sum.y + sum.z * sum.z) / fn, 0, 1e-14);
    }
    CHECK(across->n_ghost > 0);
    sd_world_destroy(mid);
    sd_world_destroy(across);
    sd_world_destroy(moved);
}

/* ---- 3. threads ------------------------------------------------------------- */

static uint64_t hash_run(int threads, long *crossed)
{
    sd_error err;
    sd_world *w = world_of(3, SD_PERIODIC_X | SD_PERIODIC_Y | SD_PERIODIC_Z, SD_LAW_HERTZ_MINDLIN, threads);
    enum { N = 1500 };
    static sd_sphere_def s[N];
    sd_rng r = sd_rng_seed(7);
    /* a 12 x 12 x 11 lattice less some, spacing 1.6 mm in the 20 mm box */
    size_t n = 0;
    for (int i = 0; i < 12 && n < N; ++i)
        for (int j = 0; j < 12 && n < N; ++j)
            for (int k = 0; k < 11 && n < N; ++k, ++n) {
                memset(&s[n], 0, sizeof s[n]);
                s[n].position = sd_test_v(-0.5 * L + 0.8e-3 + 1.65e-3 * i, -0.5 * L + 0.8e-3 + 1.65e-3 * j,
                                          -0.5 * L + 0.8e-3 + 1.8e-3 * k);
                s[n].velocity = sd_test_v(sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1), sd_rng_range(&r, -1, 1));
                s[n].radius = sd_rng_range(&r, 0.6e-3, 0.8e-3);
            }
    sd_test_require(sd_world_add_spheres(w, n, s, &err) == SD_OK, "spheres", &err);
    sd_test_require(sd_world_step(w, 1500, &err) == SD_OK, "step", &err);
    uint64_t h = 1469598103934665603ull;
    *crossed = 0;
    for (uint64_t id = 0; id < n; ++id) {
        sd_particle_state p = state_of(w, id);
        const unsigned char *b = (const unsigned char *)&p.position;
        for (size_t q = 0; q < 3 * sizeof(double); ++q)
            h = (h ^ b[q]) * 1099511628211ull;
        b = (const unsigned char *)&p.velocity;
        for (size_t q = 0; q < 3 * sizeof(double); ++q)
            h = (h ^ b[q]) * 1099511628211ull;
        double dx = fabs(p.position.x - s[id].position.x), dy = fabs(p.position.y - s[id].position.y),
               dz = fabs(p.position.z - s[id].position.z);
        *crossed += dx > 0.5 * L || dy > 0.5 * L || dz > 0.5 * L;
    }
    sd_world_destroy(w);
    return h;
}

static void threads(void)
{
    long c1, c2;
    uint64_t h1 = hash_run(1, &c1), h2 = hash_run(2, &c2);
    printf("     state hash 1 thread %016llx, 2 threads %016llx; %ld particles wrapped\n", (unsigned long long)h1,
           (unsigned long long)h2, c1);
    CHECK_NEAR("same state on 1 and 2 threads (1 = yes)", (double)(h1 == h2), 1, 0);
    CHECK(c1 > 20 && c1 == c2);
}

int main(void)
{
    crossing();
    /* spheres across the (x, y) edge of a fully periodic box */
    pair_case("spheres", 0, 3, SD_PERIODIC_X | SD_PERIODIC_Y | SD_PERIODIC_Z, SD_LAW_HERTZ_MINDLIN,
              sd_test_v(0.5 * L - 0.6e-3, 0.5 * L - 0.4e-3, 0.001), sd_test_v(1.5e-3, 0.9e-3, 0.4e-3), 40);
    /* sharp cubes under the volume law across x */
    pair_case("cubes, volume law", 1, 3, SD_PERIODIC_X, SD_LAW_VOLUME, sd_test_v(0.5 * L - 0.9e-3, 0.002, -0.001),
              sd_test_v(1.98e-3, 0.3e-3, 0.2e-3), 8);
    /* 2D ellipses across y */
    pair_case("ellipses (2D)", 2, 2, SD_PERIODIC_X | SD_PERIODIC_Y, SD_LAW_HERTZ_MINDLIN,
              sd_test_v(0.003, 0.5 * L - 0.5e-3, 0), sd_test_v(0.3e-3, 1.2e-3, 0), 40);
    threads();
    return sd_test_summary();
}
