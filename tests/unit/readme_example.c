/* readme_example.c — the library example of README.md, compiled and run
 * (STYLE.md: examples in docs are compiled in CI). Keep the two in step. */
#include "test.h"

int main(void)
{
    /* --- README example begins --- */
    sd_world_def d = sd_world_def_default();
    d.dt = 1e-5;
    sd_world *w;
    sd_error err;
    if (sd_world_create(&d, &w, &err) != SD_OK) { /* err.msg says why */ }
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    int glass = sd_world_add_material(w, &m, &err);
    sd_world_add_plane(w, "floor", (sd_v3d){0, 0, 0}, (sd_v3d){0, 0, 1}, glass, &err);
    sd_sphere_def s = {.position = {0, 0, 0.01}, .radius = 0.001, .material = glass};
    sd_world_add_spheres(w, 1, &s, &err);
    sd_world_step(w, 1000, &err);
    /* --- README example ends --- */
    sd_particle_state p;
    CHECK(sd_world_get_particle(w, 0, &p) == SD_OK);
    /* 10 ms of free fall from 1 cm: z = 0.01 - g t^2 / 2 */
    CHECK_NEAR("sphere height after 10 ms of free fall (m)", p.position.z, 0.01 - 0.5 * 9.81 * 1e-4, 1e-9);
    sd_world_destroy(w);
    return sd_test_summary();
}
