/* wall_load.c — the reported wall force balances the weight of a settled
 * packing (static equilibrium), and the torque about the box centre
 * balances the weight's moment. 600 polydisperse spheres settle in an
 * open-top box; when at rest, the box carries m g (0.5 %).
 */
#include <string.h>

#include "test.h"

#include "core/rng.h"

int main(void)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dt = 1e-5;
    d.threads = 2;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 5e6;
    m.restitution = 0.3;
    m.friction = 0.4;
    int mat = sd_world_add_material(w, &m, &err);
    int box = sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.02, 0.03, 0.1), SD_BOX_ZMAX, mat, &err);
    sd_rng r = sd_rng_seed(5);
    sd_sphere_def s[600];
    double mass = 0, mx = 0, my = 0;
    for (int k = 0; k < 600; ++k) {
        int i = k % 8, j = (k / 8) % 12, l = k / 96;
        memset(&s[k], 0, sizeof s[k]);
        s[k].position = sd_test_v(0.00125 + 0.0025 * i, 0.00125 + 0.0025 * j, 0.0015 + 0.0025 * l);
        s[k].velocity = sd_test_v(sd_rng_range(&r, -0.05, 0.05), sd_rng_range(&r, -0.05, 0.05), 0);
        s[k].radius = sd_rng_range(&r, 0.0008, 0.0012);
        s[k].material = mat;
    }
    sd_world_add_spheres(w, 600, s, &err);
    sd_test_require(sd_world_step(w, 40000, &err) == SD_OK, "step", &err);
    for (size_t k = 0; k < 600; ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        mass += p.mass;
        mx += p.mass * p.position.x;
        my += p.mass * p.position.y;
    }
    sd_stats st;
    sd_world_stats(w, &st);
    sd_wall_info wi;
    sd_world_get_wall(w, (size_t)box, &wi);
    printf("     kinetic energy at the end %.3g J, %ld contacts, %ld wall contacts\n",
           st.kinetic_translational + st.kinetic_rotational, st.contacts, st.wall_contacts);
    CHECK_REL("box force z = weight (N)", wi.force.z, -mass * 9.81, 0.005);
    CHECK_NEAR("box force x (N)", wi.force.x, 0.0, 0.005 * mass * 9.81);
    /* torque about the box centre: r x F of the weight carried */
    double cx = 0.01, cy = 0.015;
    CHECK_NEAR("box torque x (N m)", wi.torque.x, -(my / mass - cy) * mass * 9.81, 0.005 * mass * 9.81 * 0.015);
    CHECK_NEAR("box torque y (N m)", wi.torque.y, (mx / mass - cx) * mass * 9.81, 0.005 * mass * 9.81 * 0.01);
    sd_world_destroy(w);
    return sd_test_summary();
}
