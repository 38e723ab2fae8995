/* sliding.c — a sphere launched horizontally on a plane with friction
 * leaves slip at 5/7 of its launch speed.
 *
 * Analytic (rigid sphere, Coulomb friction mu, gravity g): while slipping,
 * v = v0 - mu g t and w R = 5/2 mu g t; slip ends at t* = 2 v0 / (7 mu g)
 * with v = 5/7 v0, then the sphere rolls. v0 = sqrt(2) m/s, mu = 0.5.
 * Both laws are checked (1 % on speed and on t*).
 */
#include "test.h"

static void run(sd_contact_law law, const char *name)
{
    sd_error err;
    sd_world *w;
    const double v0 = sqrt(2.0), mu = 0.5, g = 9.81, r = 0.05;
    sd_world_def wd = sd_world_def_default();
    wd.law = law;
    wd.dt = 1e-5;
    wd.gravity = sd_test_v(0, 0, -g);
    wd.threads = 1;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "steel";
    m.density = 2700;
    m.stiffness = 1e7;
    m.youngs_modulus = 1e9;
    m.restitution = 0.5;
    m.friction = mu;
    int mat = sd_world_add_material(w, &m, &err);
    sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err);
    /* start resting at the static overlap so the normal force is mg at once */
    double mass = 2700 * 4.0 / 3.0 * 3.14159265358979 * r * r * r;
    double delta = law == SD_LAW_LINEAR ? mass * g / 1e7 : 0;
    if (law == SD_LAW_HERTZ_MINDLIN) {
        double ys = 1.0 / (2 * (1 - 0.09) / 1e9);
        delta = pow(mass * g / (4.0 / 3.0 * ys * sqrt(r)), 2.0 / 3.0);
    }
    sd_sphere_def s = {0};
    s.position = sd_test_v(0, 0, r - delta);
    s.velocity = sd_test_v(v0, 0, 0);
    s.radius = r;
    s.material = mat;
    sd_world_add_spheres(w, 1, &s, &err);
    double t_star = 2 * v0 / (7 * mu * g), t_end = -1;
    sd_particle_state p = {0};
    for (int k = 0; k < 20000; ++k) {
        sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
        sd_world_get_particle(w, 0, &p);
        /* slip ends when the speed first reaches its rolling value; the
         * tangential spring rings around it afterwards */
        if (t_end < 0 && p.velocity.x <= 5.0 / 7.0 * v0)
            t_end = sd_world_time(w);
    }
    char label[96];
    snprintf(label, sizeof label, "%s: rolling speed (m/s)", name);
    CHECK_REL(label, p.velocity.x, 5.0 / 7.0 * v0, 0.01);
    snprintf(label, sizeof label, "%s: end of slip t* (s)", name);
    CHECK_REL(label, t_end, t_star, 0.01);
    snprintf(label, sizeof label, "%s: rolling w R / v", name);
    CHECK_REL(label, p.angular_velocity.y * r / p.velocity.x, 1.0, 0.001);
    sd_world_destroy(w);
}

int main(void)
{
    run(SD_LAW_LINEAR, "linear");
    run(SD_LAW_HERTZ_MINDLIN, "hertz");
    return sd_test_summary();
}
