/* energy.c — with e_n = 1 and mu = 0 the total energy (kinetic + gravity
 * + elastic) of spheres bouncing in a closed box drifts less than 0.1 %
 * over at least 100 collisions, for both laws.
 */
#include "test.h"

#include "core/rng.h"

static double total(const sd_stats *s)
{
    return s->kinetic_translational + s->kinetic_rotational + s->potential_gravity + s->potential_elastic;
}

static void run(sd_contact_law law, const char *name)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = law;
    wd.dt = 2e-6;
    wd.gravity = sd_test_v(0, 0, -9.81);
    wd.threads = 2;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "glass";
    m.density = 2500;
    m.stiffness = 2e4;
    m.youngs_modulus = 1e7;
    m.restitution = 1.0;
    m.friction = 0.0;
    int mat = sd_world_add_material(w, &m, &err);
    sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.02, 0.02, 0.02), 0, mat, &err);
    sd_rng rng = sd_rng_seed(7);
    sd_sphere_def s[27];
    int n = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k, ++n) {
                s[n] = (sd_sphere_def){0};
                s[n].position = sd_test_v(0.004 + 0.006 * i, 0.004 + 0.006 * j, 0.004 + 0.006 * k);
                s[n].velocity = sd_test_v(sd_rng_range(&rng, -0.3, 0.3), sd_rng_range(&rng, -0.3, 0.3),
                                          sd_rng_range(&rng, -0.3, 0.3));
                s[n].radius = 0.001 + 0.0005 * sd_rng_uniform(&rng);
                s[n].material = mat;
            }
    sd_world_add_spheres(w, (size_t)n, s, &err);
    sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err);
    sd_stats st;
    sd_world_stats(w, &st);
    double e0 = total(&st), worst = 0;
    long collisions = 0, last = st.contacts + st.wall_contacts;
    for (int k = 0; k < 150000; ++k) {
        sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
        sd_world_stats(w, &st);
        long now = st.contacts + st.wall_contacts;
        if (now > last)
            collisions += now - last;
        last = now;
        double drift = fabs(total(&st) - e0) / e0;
        if (drift > worst)
            worst = drift;
    }
    char label[96];
    snprintf(label, sizeof label, "%s: collisions (at least 100)", name);
    CHECK_NEAR(label, (double)(collisions >= 100), 1.0, 0.0);
    printf("     %s: %ld collisions, energy %.8g J at start\n", name, collisions, e0);
    snprintf(label, sizeof label, "%s: max relative energy drift", name);
    CHECK_NEAR(label, worst, 0.0, 1e-3);
    sd_world_destroy(w);
}

int main(void)
{
    run(SD_LAW_LINEAR, "linear");
    run(SD_LAW_HERTZ_MINDLIN, "hertz");
    return sd_test_summary();
}
