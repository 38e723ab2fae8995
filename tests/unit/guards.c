/* guards.c — the library's time-step check and the numerical guards
 * (issue 17):
 *  - sd_world_step with dt above the stability limit (1/5 of the shortest
 *    contact) returns SD_ERR_INPUT with the limit, and steps below it;
 *  - an overlap beyond half the smaller radius, a particle crossing more
 *    than a broad-phase cell per step, and a NaN state each stop the step
 *    with SD_ERR_PHYSICS naming the particle's stable id, the step and a
 *    likely cause; against a mesh the cause names the mesh's side (issue
 *    30: a sphere above an open floor wound downwards is "overlapped" by
 *    its whole size at once, and the message used to blame only the
 *    stiffness).
 */
#include <string.h>

#include "test.h"

static sd_world *spheres(double dt, size_t n, const sd_sphere_def *s)
{
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_world_def d = sd_world_def_default();
    d.dt = dt;
    d.gravity = sd_test_v(0, 0, 0);
    d.threads = 1;
    sd_world *w = NULL;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "create", &err);
    sd_material_def m = sd_material_def_default();
    m.density = 2500;
    m.youngs_modulus = 1e7;
    sd_test_require(sd_world_add_material(w, &m, &err) == 0, "material", &err);
    sd_test_require(sd_world_add_spheres(w, n, s, &err) == SD_OK, "spheres", &err);
    return w;
}

static sd_sphere_def sphere(double x, double vx, double r)
{
    sd_sphere_def s;
    memset(&s, 0, sizeof s);
    s.position = sd_test_v(x, 0, 0);
    s.velocity = sd_test_v(vx, 0, 0);
    s.radius = r;
    return s;
}

static void expect(const char *what, sd_world *w, long steps, sd_status want, const char *needle1,
                   const char *needle2)
{
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_status st = sd_world_step(w, steps, &err);
    printf("%-28s status %d (want %d): %s\n", what, (int)st, (int)want, st == SD_OK ? "ok" : err.msg);
    CHECK(st == want);
    if (needle1)
        CHECK(strstr(err.msg, needle1) != NULL);
    if (needle2)
        CHECK(strstr(err.msg, needle2) != NULL);
}

int main(void)
{
    /* two spheres 1 mm in radius approaching at 0.1 m/s */
    sd_sphere_def pair[2] = {sphere(0, 0.05, 0.001), sphere(0.0021, -0.05, 0.001)};
    sd_world *w = spheres(1e-6, 2, pair);
    sd_error err;
    sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err); /* the estimate reads the mixed materials */
    double tc = 0;
    double rec = sd_world_recommended_dt(w, &tc);
    printf("contact duration %.4g s, stability limit %.4g s, recommended %.4g s\n", tc, tc / 5, rec);
    CHECK(tc > 0 && tc < 1);
    sd_world_destroy(w);

    w = spheres(tc / 5 * 1.5, 2, pair); /* 1.5 x the limit */
    expect("dt 1.5 x the limit", w, 10, SD_ERR_INPUT, "stability limit", NULL);
    sd_world_destroy(w);
    w = spheres(tc / 5 * 0.5, 2, pair); /* half the limit */
    expect("dt 0.5 x the limit", w, 10, SD_OK, NULL, NULL);
    sd_world_destroy(w);

    /* overlap: centres 0.8 mm apart, radii 1 mm (120 % of a radius) */
    sd_sphere_def deep[2] = {sphere(0, 0, 0.001), sphere(0.0008, 0, 0.001)};
    w = spheres(1e-8, 2, deep);
    expect("deep overlap", w, 1, SD_ERR_PHYSICS, "id 0 and id 1 overlap", "stiffness too low");
    sd_world_destroy(w);

    /* runaway: a sphere shot at 2 km/s, with a time step below the
     * stability limit its speed gives (Hertz: the contact shortens with
     * the impact speed), crosses several cells of about 2.4 mm (2 r +
     * skin) per step */
    sd_sphere_def fast[2] = {sphere(0, 0, 0.001), sphere(0.01, 2000, 0.001)};
    w = spheres(1e-9, 2, fast);
    sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err);
    double tcf = 0;
    sd_world_recommended_dt(w, &tcf);
    sd_world_destroy(w);
    double dtf = 0.4 * tcf / 5;
    printf("2 km/s: contact duration %.4g s, dt %.4g s: %.3g m per step\n", tcf, dtf, 2000 * dtf);
    CHECK(2000 * dtf > 0.003);
    w = spheres(dtf, 2, fast);
    expect("a cell per step", w, 1, SD_ERR_PHYSICS, "particle id 1 moves", "time step too large");
    sd_world_destroy(w);

    /* a mesh floor wound downwards (its particle side below): a sphere
     * 1 mm in radius right above it is behind the facets, 190 % deep */
    {
        sd_sphere_def above = sphere(0, 0, 0.001);
        above.position.z = 0.0009;
        w = spheres(1e-6, 1, &above);
        sd_v3d fv[4] = {{-0.01, -0.01, 0}, {0.01, -0.01, 0}, {0.01, 0.01, 0}, {-0.01, 0.01, 0}};
        uint32_t ft[2][3] = {{0, 2, 1}, {0, 3, 2}}; /* clockwise from above: normals -z */
        sd_mesh_def md = sd_mesh_def_default();
        md.vertices = fv;
        md.vertex_count = 4;
        md.triangles = (const uint32_t(*)[3])ft;
        md.triangle_count = 2;
        sd_test_require(sd_world_add_mesh(w, "floor", &md, &err) >= 0, "mesh", &err);
        expect("mesh: from its far side", w, 1, SD_ERR_PHYSICS, "overlaps wall 'floor'", "mesh's far side");
        sd_world_destroy(w);
    }

    /* NaN: the particle named */
    sd_sphere_def nan2[2] = {sphere(0, 0, 0.001), sphere(0.01, NAN, 0.001)};
    w = spheres(1e-6, 2, nan2);
    expect("NaN velocity", w, 1, SD_ERR_PHYSICS, "particle id 1", "NaN or infinite");
    sd_world_destroy(w);
    return sd_test_summary();
}
