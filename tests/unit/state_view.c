/* state_view.c — the zero-copy view of the particle arrays
 * (sd_world_state_view, sd_world_generation): its rows are the world's
 * live values in storage order with the ids beside them, a write through
 * sd_world_set_field is seen through the same pointers without a new
 * generation, and every change of the arrays' layout (a step's rebuild,
 * an added particle) gives a new generation. The grid solver is refused.
 */
#include <string.h>

#include "test.h"

/* every row of the view equals sd_world_get_particle of the same index */
static int view_matches(const sd_world *w, const sd_state_view *v)
{
    if (v->n != sd_world_particle_count(w))
        return 0;
    for (size_t k = 0; k < v->n; ++k) {
        sd_particle_state ps;
        if (sd_world_get_particle(w, k, &ps) != SD_OK || ps.id != v->id[k])
            return 0;
        const double *x = v->position + 3 * k, *u = v->velocity + 3 * k, *q = v->orientation + 4 * k;
        if (x[0] != ps.position.x || x[1] != ps.position.y || x[2] != ps.position.z || u[2] != ps.velocity.z ||
            q[0] != ps.quat[0] || v->radius[k] != ps.radius || v->material[k] != ps.material ||
            v->shape[k] != ps.shape || v->force[3 * k + 2] != ps.force.z)
            return 0;
    }
    return 1;
}

int main(void)
{
    sd_error e;
    sd_world_def d = sd_world_def_default();
    d.dt = 1e-5;
    d.gravity = (sd_v3d){0, 0, -9.81};
    sd_world *w;
    sd_test_require(sd_world_create(&d, &w, &e) == SD_OK, "world", &e);
    sd_material_def m = sd_material_def_default();
    m.density = 2500;
    m.youngs_modulus = 1e7;
    m.poisson_ratio = 0.3;
    m.restitution = 0.5;
    m.friction = 0.5;
    int mat = sd_world_add_material(w, &m, &e);
    sd_test_require(mat >= 0, "material", &e);
    sd_test_require(sd_world_add_plane(w, "floor", (sd_v3d){0, 0, 0}, (sd_v3d){0, 0, 1}, mat, &e) >= 0, "floor", &e);
    sd_sphere_def s[3];
    memset(s, 0, sizeof s);
    for (int k = 0; k < 3; ++k) {
        s[k].position = (sd_v3d){0.003 * k, 0.001 * k, 0.002 + 0.004 * k};
        s[k].radius = 0.001;
        s[k].material = mat;
    }
    sd_test_require(sd_world_add_spheres(w, 3, s, &e) == SD_OK, "spheres", &e);

    sd_state_view v;
    CHECK(sd_world_state_view(w, &v, &e) == SD_OK);
    CHECK(v.n == 3);
    CHECK(v.generation == sd_world_generation(w));
    CHECK(view_matches(w, &v));

    /* a write through the C API is seen in the same memory, same generation */
    uint64_t id = v.id[1];
    double vel[3] = {0.25, -0.5, 0.75};
    CHECK(sd_world_set_field(w, SD_FIELD_VELOCITY, &id, 1, vel, 3, &e) == SD_OK);
    CHECK(sd_world_generation(w) == v.generation);
    CHECK(v.velocity[3] == 0.25 && v.velocity[4] == -0.5 && v.velocity[5] == 0.75);

    /* a step rebuilds (reorders): a new generation, and a new view is live again */
    uint64_t g0 = v.generation;
    CHECK(sd_world_step(w, 20, &e) == SD_OK);
    CHECK(sd_world_generation(w) != g0);
    CHECK(sd_world_state_view(w, &v, &e) == SD_OK);
    CHECK(view_matches(w, &v));
    CHECK(v.position[2] != 0.002 || v.position[5] != 0.006); /* the particles moved */

    /* an added particle: a new generation */
    uint64_t g1 = sd_world_generation(w);
    s[0].position = (sd_v3d){0.02, 0, 0.002};
    CHECK(sd_world_add_spheres(w, 1, s, &e) == SD_OK);
    CHECK(sd_world_generation(w) != g1);
    CHECK(sd_world_state_view(w, &v, &e) == SD_OK);
    CHECK(v.n == 4 && view_matches(w, &v));
    sd_world_destroy(w);

    /* the grid solver keeps no arrays to view */
    d.solver = SD_SOLVER_GRID;
    sd_test_require(sd_world_create(&d, &w, &e) == SD_OK, "grid world", &e);
    CHECK(sd_world_state_view(w, &v, &e) == SD_ERR_INPUT);
    CHECK(strstr(e.msg, "grid") != NULL);
    CHECK(v.n == 0 && v.position == NULL);
    sd_world_destroy(w);
    return sd_test_summary();
}
