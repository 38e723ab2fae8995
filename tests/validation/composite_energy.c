/* composite_energy.c — composites (seed 004) under the multi-contact
 * models, two checks:
 *
 *  1. energy: 27 multi-sphere clumps (4 spheres on a tetrahedron) with
 *     e_n = 1, mu = 0 in a closed box, no gravity: with model A (sum) the
 *     element contacts are independent springs, so the total energy
 *     (kinetic + elastic) keeps within 0.1 % over at least 100
 *     collisions. The same for 27 3D crosses of 7 sharp cubes is printed
 *     (the depth law on sharp edges and corners is not exactly
 *     conservative: seed 004's law, not the combination). Model B (average, eq. 21) divides the springs
 *     of a composite pair by N_c, which jumps when an element pair starts
 *     or ends touching: it is not the gradient of one potential, and its
 *     drift is printed (not asserted) for the same run.
 *  2. determinism: 1,200 clumps and crosses settling in a box under
 *     gravity (enough particles for the threaded loops), 300 steps with 1
 *     and with 2 threads: the same bits for every particle.
 */
#include <string.h>

#include "test.h"

#include "core/rng.h"

static double total(const sd_stats *s)
{
    return s->kinetic_translational + s->kinetic_rotational + s->potential_gravity + s->potential_elastic;
}

/* The two composite templates: a clump of 4 spheres of radius r on a
 * regular tetrahedron (edge 2.2 r: no overlap) and a 3D cross of 7 cubes
 * of edge 1.4 r (a centre cube and six arms, face to face), both with
 * exact mass properties. */
static void templates(sd_world *w, double r, int *clump, int *cross)
{
    sd_error err;
    sd_shape_desc s = sd_shape_desc_default();
    s.kind = "sphere";
    s.size = sd_test_v(r, 0, 0);
    int ball = sd_world_add_shape(w, "ball", &s, &err);
    sd_test_require(ball >= 0, "ball", &err);
    sd_composite_element el[7];
    double a = 1.1 * r; /* half the edge: the spheres do not overlap */
    static const double tet[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    for (int k = 0; k < 4; ++k) {
        memset(&el[k], 0, sizeof el[k]);
        el[k].shape = ball;
        el[k].position = sd_test_v(a * tet[k][0] / sqrt(2.0), a * tet[k][1] / sqrt(2.0), a * tet[k][2] / sqrt(2.0));
    }
    sd_composite_desc cd = sd_composite_desc_default();
    cd.elements = el;
    cd.element_count = 4;
    *clump = sd_world_add_composite(w, "clump", &cd, &err);
    sd_test_require(*clump >= 0, "clump", &err);
    s.kind = "box";
    double c = 1.4 * r;
    s.size = sd_test_v(c, c, c);
    int cube = sd_world_add_shape(w, "cube", &s, &err);
    sd_test_require(cube >= 0, "cube", &err);
    /* a centre cube and six arm cubes: a 3D cross of edge c, span 3 c */
    static const double arm[7][3] = {{0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int k = 0; k < 7; ++k) {
        memset(&el[k], 0, sizeof el[k]);
        el[k].shape = cube;
        el[k].position = sd_test_v(c * arm[k][0], c * arm[k][1], c * arm[k][2]);
    }
    cd.element_count = 7;
    *cross = sd_world_add_composite(w, "cross", &cd, &err);
    sd_test_require(*cross >= 0, "cross", &err);
}

static double energy_run(int model, int only, long *collisions_out)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = SD_LAW_LINEAR;
    wd.dt = 2e-6;
    wd.gravity = sd_test_v(0, 0, 0);
    wd.threads = 1;
    wd.multi_contact = model;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.density = 2500;
    m.stiffness = 2e4;
    m.restitution = 1.0;
    m.friction = 0.0;
    int mat = sd_world_add_material(w, &m, &err);
    sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.02, 0.02, 0.02), 0, mat, &err);
    int clump, cross;
    double r = 0.0008;
    templates(w, r, &clump, &cross);
    sd_rng rng = sd_rng_seed(11);
    sd_body_def b[27];
    int n = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k, ++n) {
                memset(&b[n], 0, sizeof b[n]);
                b[n].position = sd_test_v(0.004 + 0.006 * i, 0.004 + 0.006 * j, 0.004 + 0.006 * k);
                b[n].velocity = sd_test_v(sd_rng_range(&rng, -0.4, 0.4), sd_rng_range(&rng, -0.4, 0.4),
                                          sd_rng_range(&rng, -0.4, 0.4));
                b[n].angular_velocity = sd_test_v(sd_rng_range(&rng, -50, 50), sd_rng_range(&rng, -50, 50),
                                                  sd_rng_range(&rng, -50, 50));
                b[n].shape = only == 1 ? clump : (only == 2 ? cross : (n % 2 ? clump : cross));
                b[n].material = mat;
            }
    sd_test_require(sd_world_add_bodies(w, (size_t)n, b, &err) == SD_OK, "bodies", &err);
    sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err);
    sd_stats st;
    sd_world_stats(w, &st);
    double e0 = total(&st), worst = 0;
    long collisions = 0, last = st.contacts + st.wall_contacts;
    for (int k = 0; k < 60000; ++k) {
        sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
        sd_world_stats(w, &st);
        long now = st.contacts + st.wall_contacts;
        if (now > last)
            collisions += now - last;
        last = now;
        worst = fmax(worst, fabs(total(&st) - e0) / e0);
    }
    sd_world_destroy(w);
    *collisions_out = collisions;
    return worst;
}

static sd_world *packing(int threads)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = SD_LAW_LINEAR;
    wd.dt = 1e-5;
    wd.gravity = sd_test_v(0, 0, -9.81);
    wd.threads = threads;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.density = 2500;
    m.stiffness = 2e4;
    m.restitution = 0.5;
    m.friction = 0.4;
    int mat = sd_world_add_material(w, &m, &err);
    double r = 0.001;
    int clump, cross;
    templates(w, r, &clump, &cross);
    enum { NX = 10, NY = 10, NZ = 12 };
    double h = 5 * r;
    sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(NX * h, NY * h, NZ * h * 1.5), 0, mat, &err);
    sd_rng rng = sd_rng_seed(5);
    static sd_body_def b[NX * NY * NZ];
    int n = 0;
    for (int k = 0; k < NZ; ++k)
        for (int j = 0; j < NY; ++j)
            for (int i = 0; i < NX; ++i, ++n) {
                memset(&b[n], 0, sizeof b[n]);
                b[n].position = sd_test_v((i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h);
                b[n].velocity = sd_test_v(sd_rng_range(&rng, -1.5, 1.5), sd_rng_range(&rng, -1.5, 1.5),
                                          sd_rng_range(&rng, -1.5, 1.5));
                double qw = sd_rng_range(&rng, -1, 1), qx = sd_rng_range(&rng, -1, 1),
                       qy = sd_rng_range(&rng, -1, 1), qz = sd_rng_range(&rng, -1, 1);
                double ql = sqrt(qw * qw + qx * qx + qy * qy + qz * qz);
                b[n].orientation[0] = qw / ql;
                b[n].orientation[1] = qx / ql;
                b[n].orientation[2] = qy / ql;
                b[n].orientation[3] = qz / ql;
                b[n].shape = (i + j + k) % 2 ? clump : cross;
                b[n].material = mat;
            }
    sd_test_require(sd_world_add_bodies(w, (size_t)n, b, &err) == SD_OK, "bodies", &err);
    for (int s = 0; s < 3; ++s)
        sd_test_require(sd_world_step(w, 100, &err) == SD_OK, "step", &err);
    return w;
}

int main(void)
{
    /* only = 1: clumps; 2: crosses; 0: both */
    static const char *what[3] = {"clumps and crosses", "clumps of spheres", "crosses of cubes"};
    for (int only = 1; only <= 2; ++only) {
        long ca = 0, cb = 0;
        double da = energy_run(SD_MULTI_CONTACT_SUM, only, &ca), db = energy_run(SD_MULTI_CONTACT_AVERAGE, only, &cb);
        printf("%s, model A (sum):     %ld collisions, max relative energy drift %.3e\n", what[only], ca, da);
        printf("%s, model B (average): %ld collisions, max relative energy drift %.3e (reported only)\n", what[only],
               cb, db);
        if (only == 1) {
            CHECK(ca >= 100);
            CHECK_NEAR("clumps, model A: max relative energy drift", da, 0.0, 1e-3);
        }
    }
    sd_world *w1 = packing(1), *w2 = packing(2);
    sd_stats s1, s2;
    sd_world_stats(w1, &s1);
    sd_world_stats(w2, &s2);
    printf("packing: %zu composites, %ld contacts, %ld wall contacts, %zu candidate element pairs\n",
           (size_t)1200, s1.contacts, s1.wall_contacts, s1.pairs);
    size_t differ = 0;
    for (size_t k = 0; k < 1200; ++k) {
        sd_particle_state a, c;
        sd_world_get_particle(w1, k, &a);
        sd_world_get_particle(w2, k, &c);
        differ += memcmp(&a.position, &c.position, sizeof a.position) != 0 ||
                  memcmp(&a.velocity, &c.velocity, sizeof a.velocity) != 0 ||
                  memcmp(a.quat, c.quat, sizeof a.quat) != 0 ||
                  memcmp(&a.angular_velocity, &c.angular_velocity, sizeof a.angular_velocity) != 0;
    }
    CHECK(s1.contacts > 50);
    CHECK_NEAR("particles differing between 1 and 2 threads", (double)differ, 0.0, 0.0);
    sd_world_destroy(w1);
    sd_world_destroy(w2);
    return sd_test_summary();
}
