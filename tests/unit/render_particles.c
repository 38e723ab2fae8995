/* render_particles.c — render/read.c's frame of particles handed over as
 * arrays (what `shapedem render CK.h5` draws, issue 31): a failed run's
 * state with a particle that is not finite is drawn without it and the
 * description says so; the categorical fields name their values from the
 * lists given (a plain sphere is "sphere"), the others carry their unit;
 * a field the arrays lack is refused naming the file and --field. */
#include "render/render.h"
#include "test.h"

#include <math.h>
#include <string.h>

int main(void)
{
    const double x[9] = {0, 0, 0.001, 0.003, 0, 0.001, NAN, 0, 0.001};
    const double v[9] = {0, 0, -0.5, 0, 0.3, 0.4, 0, 0, 0};
    const double zero[9] = {0}, q[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    const double radius[3] = {0.001, 0.002, 0.001};
    const uint64_t id[3] = {7, 8, 9};
    const int32_t shape[3] = {-1, 0, 0}, material[3] = {1, 0, 1};
    const char shapes[1][64] = {"cube"}, materials[2][64] = {"glass", "steel"};
    sd_render_particles p = {.n = 3, .x = x, .v = v, .w = zero, .f = zero, .q = q, .radius = radius, .id = id,
                             .shape = shape, .material = material, .shape_count = 1, .material_count = 2,
                             .shape_names = shapes, .material_names = materials, .source = "failed-000150.h5"};
    sd_render_frame f;
    sd_error err;
    sd_render_def d = sd_render_def_default();
    char what[512];

    CHECK(sd_render_frame_particles(&p, "speed", &f, &err) == SD_OK);
    printf("speed: %zu spheres, %zu not finite, unit '%s', categorical %d\n", f.sphere_count, f.not_finite, f.unit,
           f.categorical);
    CHECK(f.sphere_count == 2 && f.not_finite == 1 && !strcmp(f.unit, "m/s") && !f.categorical);
    CHECK_NEAR("speed of particle 8 (|(0, 0.3, 0.4)|)", f.sphere_value[1], 0.5, 1e-15);
    CHECK(f.bounding_spheres == 1);
    sd_render_describe(&f, &d, what, sizeof what);
    printf("  %s\n", what);
    CHECK(!strcmp(what, "2 particles coloured by speed, 0.5 .. 0.5 m/s; 1 more not drawn (a position or radius not finite)"));
    sd_render_frame_free(&f);

    CHECK(sd_render_frame_particles(&p, "shape", &f, &err) == SD_OK);
    sd_render_describe(&f, &d, what, sizeof what);
    printf("shape: %s\n", what);
    CHECK(f.categorical && f.category_first == -1 && f.category_count == 2);
    CHECK(strstr(what, "coloured by shape: sphere (1), cube (1)") != NULL);
    CHECK(sd_render_category_t(&f, -1.0) == 0.0 && sd_render_category_t(&f, 0.0) == 1.0);
    sd_render_frame_free(&f);

    CHECK(sd_render_frame_particles(&p, "material", &f, &err) == SD_OK);
    sd_render_describe(&f, &d, what, sizeof what);
    printf("material: %s\n", what);
    CHECK(strstr(what, "coloured by material: glass (1), steel (1)") != NULL);
    sd_render_frame_free(&f);

    CHECK(sd_render_frame_particles(&p, "force", &f, &err) == SD_OK);
    CHECK(!strcmp(f.unit, "N"));
    sd_render_frame_free(&f);
    CHECK(sd_render_frame_particles(&p, "radius", &f, &err) == SD_OK);
    CHECK(!strcmp(f.unit, "m"));
    sd_render_frame_free(&f);

    memset(&err, 0, sizeof err);
    CHECK(sd_render_frame_particles(&p, "temperature", &f, &err) == SD_ERR_INPUT);
    printf("temperature: %s: %s: %s\n", err.file, err.key, err.msg);
    CHECK(!strcmp(err.file, "failed-000150.h5") && !strcmp(err.key, "--field") &&
          strstr(err.msg, "no field 'temperature'") != NULL);
    sd_render_frame_free(&f);
    return sd_test_summary();
}
