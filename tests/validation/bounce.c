/* bounce.c — free fall and bounce on a plane (seed 001 §3.3, Set I), and
 * the measured restitution of both contact laws.
 *
 *  1. e_n = 1, linear law: the sphere returns to its release height (0.5 %).
 *  2. linear law, no gravity: the rebound speed over the impact speed equals
 *     e_n for e_n in {0.1, 0.5, 0.9} (seed 004 eq. 15), against a plane and
 *     for two equal spheres (1 %).
 *  3. Hertz-Mindlin: the measured restitution is reported against its input
 *     (the LIGGGHTS damping form is not exact for e_n; 5 % asserted).
 */
#include "test.h"

typedef struct drop {
    sd_world *w;
    int mat;
} drop;

static drop make_world(sd_contact_law law, double e, double gz, double dt)
{
    drop d;
    sd_error err;
    sd_world_def wd = sd_world_def_default();
    wd.law = law;
    wd.dt = dt;
    wd.gravity = sd_test_v(0, 0, gz);
    wd.threads = 1;
    sd_test_require(sd_world_create(&wd, &d.w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "rock";
    m.density = 2700;          /* seed 001 Table 1, Set I */
    m.stiffness = 50000;       /* N/m */
    m.youngs_modulus = 5e7;
    m.poisson_ratio = 0.3;
    m.restitution = e;
    m.friction = 0.5;
    d.mat = sd_world_add_material(d.w, &m, &err);
    sd_test_require(d.mat >= 0, "material", &err);
    sd_test_require(sd_world_add_plane(d.w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), d.mat, &err) >= 0,
                    "plane", &err);
    return d;
}

static void add_sphere(drop *d, double z, double vz, double x)
{
    sd_error err;
    sd_sphere_def s = {0};
    s.position = sd_test_v(x, 0, z);
    s.velocity = sd_test_v(0, 0, vz);
    s.radius = 0.05;
    s.material = d->mat;
    sd_test_require(sd_world_add_spheres(d->w, 1, &s, &err) == SD_OK, "sphere", &err);
}

static double vz_of(sd_world *w, uint64_t id)
{
    sd_particle_state p;
    sd_world_get_particle(w, sd_world_find_particle(w, id), &p);
    return p.velocity.z;
}

static double z_of(sd_world *w, uint64_t id)
{
    sd_particle_state p;
    sd_world_get_particle(w, sd_world_find_particle(w, id), &p);
    return p.position.z;
}

int main(void)
{
    sd_error err;
    /* 1. release height is recovered without damping */
    {
        drop d = make_world(SD_LAW_LINEAR, 1.0, -9.81, 1e-4);
        add_sphere(&d, 0.95, 0.0, 0.0);
        double zmax_after = 0;
        int hit = 0;
        for (int k = 0; k < 12000; ++k) {
            sd_test_require(sd_world_step(d.w, 1, &err) == SD_OK, "step", &err);
            double z = z_of(d.w, 0), vz = vz_of(d.w, 0);
            if (z < 0.05)
                hit = 1;
            if (hit && vz > 0 && z > zmax_after)
                zmax_after = z;
            if (hit && vz < 0 && zmax_after > 0.5)
                break;
        }
        CHECK_REL("e=1: apex after bounce (m), release 0.95", zmax_after, 0.95, 0.005);
        sd_world_destroy(d.w);
    }
    /* 2. linear law restitution, sphere-plane and sphere-sphere */
    const double es[] = {0.1, 0.5, 0.9};
    for (int k = 0; k < 3; ++k) {
        char label[96];
        drop d = make_world(SD_LAW_LINEAR, es[k], 0.0, 1e-5);
        add_sphere(&d, 0.0505, -1.0, 0.0);
        for (int s = 0; s < 4000; ++s)
            sd_world_step(d.w, 1, &err);
        snprintf(label, sizeof label, "linear, sphere-plane: e measured (e_n=%.1f)", es[k]);
        CHECK_REL(label, vz_of(d.w, 0) / 1.0, es[k], 0.01);
        sd_world_destroy(d.w);

        d = make_world(SD_LAW_LINEAR, es[k], 0.0, 1e-5);
        add_sphere(&d, 1.0, -0.5, 0.0);
        add_sphere(&d, 0.8995, 0.5, 0.0);
        for (int s = 0; s < 4000; ++s)
            sd_world_step(d.w, 1, &err);
        snprintf(label, sizeof label, "linear, sphere-sphere: e measured (e_n=%.1f)", es[k]);
        CHECK_REL(label, (vz_of(d.w, 0) - vz_of(d.w, 1)) / 1.0, es[k], 0.01);
        sd_world_destroy(d.w);
    }
    /* 3. Hertz-Mindlin: reported */
    for (int k = 0; k < 3; ++k) {
        char label[96];
        drop d = make_world(SD_LAW_HERTZ_MINDLIN, es[k], 0.0, 1e-5);
        add_sphere(&d, 0.0501, -1.0, 0.0);
        for (int s = 0; s < 3000; ++s)
            sd_world_step(d.w, 1, &err);
        snprintf(label, sizeof label, "hertz, sphere-plane: e measured (e_n=%.1f)", es[k]);
        CHECK_REL(label, vz_of(d.w, 0), es[k], 0.05);
        sd_world_destroy(d.w);
    }
    return sd_test_summary();
}
