/* poly_common.h — helpers shared by the volume-law validations
 * (tests/validation/poly_*.c): vertex lists of the test polyhedra, a world
 * with one material and the volume law, and orientations set from the
 * template's own face planes (templates live in their principal frame, whose
 * axes are arbitrary for isotropic or axisymmetric bodies). */
#ifndef SD_TEST_POLY_COMMON_H
#define SD_TEST_POLY_COMMON_H

#include <string.h>

#include "test.h"

#include "core/quat.h"
#include "world/world.h"

/* Regular dodecahedron of circumradius r: (±1,±1,±1), (0,±1/φ,±φ) and
 * cyclic permutations, scaled by r/√3. Writes 20 vertices. */
static inline void poly_dodecahedron(double r, sd_v3d *v)
{
    const double phi = 0.5 * (1.0 + sqrt(5.0)), ip = 1.0 / phi, s = r / sqrt(3.0);
    int n = 0;
    for (int a = -1; a <= 1; a += 2)
        for (int b = -1; b <= 1; b += 2)
            for (int c = -1; c <= 1; c += 2)
                v[n++] = sd_test_v(s * a, s * b, s * c);
    for (int a = -1; a <= 1; a += 2)
        for (int b = -1; b <= 1; b += 2) {
            v[n++] = sd_test_v(0, s * a * ip, s * b * phi);
            v[n++] = sd_test_v(s * a * ip, s * b * phi, 0);
            v[n++] = sd_test_v(s * b * phi, 0, s * a * ip);
        }
}

/* Cube of edge a centred at the origin: 8 vertices. */
static inline void poly_cube(double a, sd_v3d *v)
{
    int n = 0;
    for (int i = -1; i <= 1; i += 2)
        for (int j = -1; j <= 1; j += 2)
            for (int k = -1; k <= 1; k += 2)
                v[n++] = sd_test_v(0.5 * a * i, 0.5 * a * j, 0.5 * a * k);
}

/* Seed 000 §3.1's cylinder: an n-gon prism of diameter d (vertices on the
 * circle, one on +x) and length l along z, with the two cap centres (which
 * make its 80 triangles for n = 20; the hull drops them). Writes 2n + 2. */
static inline int poly_cylinder(int nside, double d, double l, sd_v3d *v)
{
    int n = 0;
    for (int k = 0; k < nside; ++k) {
        double t = 2.0 * 3.14159265358979323846 * k / nside;
        v[n++] = sd_test_v(0.5 * d * cos(t), 0.5 * d * sin(t), -0.5 * l);
        v[n++] = sd_test_v(0.5 * d * cos(t), 0.5 * d * sin(t), 0.5 * l);
    }
    v[n++] = sd_test_v(0, 0, -0.5 * l);
    v[n++] = sd_test_v(0, 0, 0.5 * l);
    return n;
}

/* Shortest-arc rotation taking unit a to unit b. */
static inline sd_quat poly_quat_between(sd_vec3 a, sd_vec3 b)
{
    sd_vec3 c = sd_v3_cross(a, b);
    double d = (double)sd_v3_dot(a, b);
    if (d < -1.0 + 1e-12) { /* opposite: any perpendicular axis */
        sd_vec3 p = fabs((double)a.x) < 0.9 ? sd_v3(1, 0, 0) : sd_v3(0, 1, 0);
        sd_vec3 ax = sd_v3_normalize(sd_v3_cross(a, p));
        return sd_quat_make(0, ax.x, ax.y, ax.z);
    }
    return sd_quat_normalize(sd_quat_make((sd_real)(1.0 + d), c.x, c.y, c.z));
}

/* A world with one material (E, nu, e, mu) and the given law. */
static inline sd_world *poly_world(sd_contact_law law, double dt, sd_v3d g, double young, double e, double mu,
                                   double density, int threads, int *mat)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.law = law;
    d.dt = dt;
    d.gravity = g;
    d.threads = threads;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "grain";
    m.density = density;
    m.youngs_modulus = young;
    m.poisson_ratio = 0.3;
    m.restitution = e;
    m.friction = mu;
    m.volume_stiffness = 1e10;
    *mat = sd_world_add_material(w, &m, &err);
    sd_test_require(*mat >= 0, "material", &err);
    return w;
}

static inline int poly_add_shape(sd_world *w, const char *name, const sd_v3d *v, size_t n)
{
    sd_error err;
    sd_shape_desc s = sd_shape_desc_default();
    s.kind = "polyhedron";
    s.vertices = v;
    s.vertex_count = n;
    int k = sd_world_add_shape(w, name, &s, &err);
    sd_test_require(k >= 0, "shape", &err);
    return k;
}

/* Orientation (w, x, y, z) that turns template face f of shape k to face
 * the unit world direction dir (its outward normal along dir). */
static inline void poly_face_towards(const sd_world *w, int k, int f, sd_vec3 dir, double q[4])
{
    const sd_shape *s = &w->shapes[k];
    sd_quat r = poly_quat_between(w->planes[s->fstart + (uint32_t)f].n, dir);
    q[0] = r.w;
    q[1] = r.x;
    q[2] = r.y;
    q[3] = r.z;
}

#endif
