/* solver_api.c — the seams of issue 12 item 6 and the law table, through
 * the public API only:
 *  - solver dispatch: a cells world and a grid world built alike answer
 *    count, get_particle, find_particle and stats through the same calls,
 *    and follow the same trajectories (the grid solver's design promise,
 *    tests/validation/grid_vs_cells.c, here on a small case);
 *  - pour and outlet defs: the cookie check, the checks that need no
 *    solver, the cells solver's refusal, the grid solver's acceptance and
 *    sd_world_get_pour reading back what was set;
 *  - the law table's needs column drives sd_world_prepare's checks: a law
 *    needing a value refuses a material without it, naming the key;
 *  - new particles start from the field defaults (SD_PARTICLE_FIELDS).
 */
#include <math.h>
#include <string.h>

#include "test.h"

#include <shapedem/shapedem.h>

static sd_world *world(sd_solver solver, sd_contact_law law, double stiffness, double modulus, int *mat)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dt = 1e-5;
    d.law = law;
    d.solver = solver;
    d.threads = 1;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "grain";
    m.density = 2500;
    m.stiffness = stiffness;
    m.youngs_modulus = modulus;
    m.friction = 0.4;
    *mat = sd_world_add_material(w, &m, &err);
    sd_test_require(*mat >= 0, "material", &err);
    sd_test_require(sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(0.1, 0.1, 0.1), 0, *mat, &err) >= 0,
                    "box", &err);
    return w;
}

/* 27 equal spheres on a lattice, some touching the floor and each other. */
static void fill(sd_world *w, int mat)
{
    sd_error err;
    sd_sphere_def s[27];
    memset(s, 0, sizeof s);
    for (int k = 0; k < 27; ++k) {
        s[k].position = sd_test_v(0.02 + 0.0199 * (k % 3), 0.02 + 0.0199 * (k / 3 % 3), 0.00999 + 0.0199 * (k / 9));
        s[k].velocity = sd_test_v(0.01 * (k % 2), -0.02 * (k % 3 == 1), 0);
        s[k].radius = 0.01;
        s[k].material = mat;
    }
    sd_test_require(sd_world_add_spheres(w, 27, s, &err) == SD_OK, "spheres", &err);
}

static void test_dispatch(void)
{
    sd_error err;
    int mc, mg;
    sd_world *wc = world(SD_SOLVER_CELLS, SD_LAW_LINEAR, 1e4, 0, &mc);
    sd_world *wg = world(SD_SOLVER_GRID, SD_LAW_LINEAR, 1e4, 0, &mg);
    fill(wc, mc);
    fill(wg, mg);
    sd_test_require(sd_world_step(wc, 200, &err) == SD_OK, "cells step", &err);
    sd_test_require(sd_world_step(wg, 200, &err) == SD_OK, "grid step", &err);
    CHECK_NEAR("count, cells", (double)sd_world_particle_count(wc), 27, 0);
    CHECK_NEAR("count, grid", (double)sd_world_particle_count(wg), 27, 0);
    double dmax = 0;
    for (uint64_t id = 0; id < 27; ++id) {
        size_t kc = sd_world_find_particle(wc, id), kg = sd_world_find_particle(wg, id);
        CHECK(kc != (size_t)-1 && kg != (size_t)-1);
        sd_particle_state a, b;
        CHECK(sd_world_get_particle(wc, kc, &a) == SD_OK);
        CHECK(sd_world_get_particle(wg, kg, &b) == SD_OK);
        CHECK(a.id == id && b.id == id);
        double dx = a.position.x - b.position.x, dy = a.position.y - b.position.y, dz = a.position.z - b.position.z;
        dmax = fmax(dmax, sqrt(dx * dx + dy * dy + dz * dz));
    }
    CHECK_NEAR("largest position difference cells vs grid (m)", dmax, 0, 1e-9);
    sd_particle_state past;
    CHECK(sd_world_get_particle(wc, 27, &past) != SD_OK);
    CHECK(sd_world_get_particle(wg, 27, &past) != SD_OK);
    CHECK(sd_world_find_particle(wg, 12345) == (size_t)-1);
    sd_stats sc, sg;
    sd_world_stats(wc, &sc);
    sd_world_stats(wg, &sg);
    CHECK_REL("kinetic energy cells vs grid (J)", sg.kinetic_translational, sc.kinetic_translational, 1e-6);
    CHECK_REL("gravity potential cells vs grid (J)", sg.potential_gravity, sc.potential_gravity, 1e-9);
    CHECK_NEAR("contacts cells vs grid", (double)sg.contacts, (double)sc.contacts, 0);
    CHECK_NEAR("wall contacts cells vs grid", (double)sg.wall_contacts, (double)sc.wall_contacts, 0);
    CHECK(sc.wall_contacts >= 9); /* the bottom layer rests on the floor */
    sd_world_destroy(wc);
    sd_world_destroy(wg);
}

static void test_pour_outlet(void)
{
    sd_error err;
    int mc, mg;
    sd_world *wc = world(SD_SOLVER_CELLS, SD_LAW_LINEAR, 1e4, 0, &mc);
    sd_world *wg = world(SD_SOLVER_GRID, SD_LAW_LINEAR, 1e4, 0, &mg);

    sd_pour_def raw;
    memset(&raw, 0, sizeof raw); /* not made by sd_pour_def_default */
    raw.radius = 0.005;
    CHECK(sd_world_set_pour(wg, &raw, &err) == SD_ERR_INPUT);
    CHECK(strcmp(err.key, "pour") == 0 && strstr(err.msg, "sd_pour_def_default") != NULL);
    sd_outlet_def oraw;
    memset(&oraw, 0, sizeof oraw);
    CHECK(sd_world_set_outlet(wg, &oraw, &err) == SD_ERR_INPUT);
    CHECK(strstr(err.msg, "sd_outlet_def_default") != NULL);

    sd_pour_def pd = sd_pour_def_default();
    CHECK_NEAR("default feed rate (1/s)", pd.layers_per_second, 4, 0);
    pd.material = mg;
    pd.radius = -1; /* a check that needs no solver */
    CHECK(sd_world_set_pour(wg, &pd, &err) == SD_ERR_INPUT && strstr(err.msg, "radius") != NULL);
    pd.radius = 0.005;
    pd.height = 0.08;
    pd.count = 50;
    CHECK(sd_world_set_pour(wc, &pd, &err) == SD_ERR_INPUT);
    printf("     cells solver says: %s\n", err.msg);
    CHECK(strcmp(err.key, "pour") == 0 && strstr(err.msg, "solver grid") != NULL);
    sd_pour_def back;
    CHECK(sd_world_get_pour(wc, &back) == 0);
    CHECK(sd_world_set_pour(wg, &pd, &err) == SD_OK);
    CHECK(sd_world_get_pour(wg, &back) == 1);
    CHECK_NEAR("pour radius read back (m)", back.radius, 0.005, 0);
    CHECK_NEAR("pour count read back", (double)back.count, 50, 0);

    sd_outlet_def od = sd_outlet_def_default();
    od.x0 = 0.04;
    od.x1 = 0.03; /* x1 < x0 */
    od.y0 = 0.04;
    od.y1 = 0.06;
    CHECK(sd_world_set_outlet(wg, &od, &err) == SD_ERR_INPUT && strstr(err.msg, "x1 > x0") != NULL);
    od.x1 = 0.06;
    CHECK(sd_world_set_outlet(wc, &od, &err) == SD_ERR_INPUT && strstr(err.msg, "solver grid") != NULL);
    CHECK(sd_world_set_outlet(wg, &od, &err) == SD_OK);
    /* the pour fills the box through the solver interface: the count grows */
    sd_test_require(sd_world_step(wg, 3000, &err) == SD_OK, "grid pour", &err);
    size_t n = sd_world_particle_count(wg);
    printf("     grid world after 3000 steps of pouring: %zu spheres\n", n);
    CHECK(n > 0);
    sd_world_destroy(wc);
    sd_world_destroy(wg);
}

/* A law needing a value refuses a material without it, naming the key. */
static void test_law_needs(void)
{
    sd_error err;
    struct {
        sd_contact_law law;
        double stiffness, modulus;
        const char *key;
    } rows[] = {
        {SD_LAW_LINEAR, 0, 1e7, "stiffness"},
        {SD_LAW_HERTZ_MINDLIN, 1e4, 0, "youngs_modulus"},
    };
    for (size_t r = 0; r < sizeof rows / sizeof rows[0]; ++r) {
        int m;
        sd_world *w = world(SD_SOLVER_CELLS, rows[r].law, rows[r].stiffness, rows[r].modulus, &m);
        fill(w, m);
        CHECK(sd_world_prepare(w, &err) == SD_ERR_INPUT);
        printf("     %s law: %s: %s\n", sd_contact_law_name(rows[r].law), err.key, err.msg);
        CHECK(strcmp(err.key, rows[r].key) == 0);
        CHECK(strstr(err.msg, sd_contact_law_name(rows[r].law)) != NULL);
        sd_world_destroy(w);
    }
    /* the columns themselves */
    CHECK(sd_contact_law_needs(SD_LAW_LINEAR) & SD_LAW_NEEDS_STIFFNESS);
    CHECK(sd_contact_law_needs(SD_LAW_HERTZ_MINDLIN) & SD_LAW_NEEDS_MODULUS);
    CHECK(sd_contact_law_needs(SD_LAW_VOLUME) & SD_LAW_NEEDS_SHARP);
    CHECK(sd_contact_law_needs(SD_LAW_VOLUME_LINEAR) & SD_LAW_NEEDS_VOLUME_STIFFNESS);
    CHECK(sd_contact_law_traits(SD_LAW_LINEAR) & SD_LAW_IS_LINEAR);
    for (int law = 0; law < SD_LAW_COUNT; ++law)
        CHECK(sd_contact_law_traits((sd_contact_law)law) != 0); /* every row says what it is */
    CHECK(sd_contact_law_needs(SD_LAW_COUNT) == 0 && sd_contact_law_traits(SD_LAW_COUNT) == 0);
}

/* A new sphere starts from the field defaults: identity orientation, no
 * force or torque, no shape. */
static void test_defaults(void)
{
    sd_error err;
    int m;
    sd_world *w = world(SD_SOLVER_CELLS, SD_LAW_LINEAR, 1e4, 0, &m);
    sd_sphere_def s;
    memset(&s, 0, sizeof s);
    s.position = sd_test_v(0.05, 0.05, 0.05);
    s.radius = 0.01;
    s.material = m;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    sd_particle_state p;
    CHECK(sd_world_get_particle(w, 0, &p) == SD_OK);
    CHECK(p.quat[0] == 1 && p.quat[1] == 0 && p.quat[2] == 0 && p.quat[3] == 0);
    CHECK(p.force.x == 0 && p.force.y == 0 && p.force.z == 0 && p.torque.z == 0);
    CHECK(p.shape == -1 && p.material == m && p.id == 0);
    CHECK_REL("mass (kg)", p.mass, 2500 * 4.0 / 3.0 * 3.14159265358979323846 * 1e-6, 1e-12);
    sd_world_destroy(w);
}

int main(void)
{
    test_dispatch();
    test_pour_outlet();
    test_law_needs();
    test_defaults();
    return sd_test_summary();
}
