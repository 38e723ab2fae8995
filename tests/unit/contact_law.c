/* contact_law.c — the contact laws against their closed forms, and the
 * tangential history carried across a pair-list rebuild by key. */
#include <string.h>

#include "test.h"

#include "contact/law.h"
#include "world/world.h"

static sd_pair_params params(int law)
{
    sd_pair_params p = {0};
    p.law = law;
    double e = 0.5, le = log(e);
    p.restitution = e;
    p.log_e_factor = le / sqrt(le * le + 3.14159265358979323846 * 3.14159265358979323846);
    p.y_star = 1e7;
    p.g_star = 4e6;
    p.kn = 1e4;
    p.kt_ratio = 2.0 / 7.0;
    p.friction = 0.4;
    return p;
}

int main(void)
{
    sd_vec3 n = sd_v3(0, 0, 1), ds = sd_v3_zero();
    /* Hertz, at rest: F = 4/3 Y* sqrt(R*) delta^(3/2) */
    sd_pair_params h = params(SD_LAW_HERTZ_MINDLIN);
    double d = 1e-5, rs = 5e-4, ms = 1e-3;
    sd_contact_out o = sd_law_eval(&h, n, d, rs, ms, sd_v3_zero(), sd_v3_zero(), &ds, 1e-6);
    CHECK_REL("hertz static normal force (N)", o.force.z, 4.0 / 3.0 * 1e7 * sqrt(rs) * pow(d, 1.5), 1e-12);
    CHECK_REL("hertz elastic energy (J)", o.energy, 8.0 / 15.0 * 1e7 * sqrt(rs) * pow(d, 2.5), 1e-12);
    /* linear, approaching at 0.1 m/s: F = k d - 2 gamma m* u_n, gamma by seed 004 eq. 16 */
    sd_pair_params l = params(SD_LAW_LINEAR);
    ds = sd_v3_zero();
    o = sd_law_eval(&l, n, d, rs, ms, sd_v3(0, 0, -0.1), sd_v3_zero(), &ds, 1e-6);
    double w0 = sqrt(1e4 / ms), gam = -w0 * log(0.5) / sqrt(3.14159265358979323846 * 3.14159265358979323846 + log(0.5) * log(0.5));
    CHECK_REL("linear normal force with dashpot (N)", o.force.z, 1e4 * d + 2 * gam * ms * 0.1, 1e-12);
    /* tangential: sliding caps at mu |F_n| and the spring is rescaled */
    ds = sd_v3_zero();
    o = sd_law_eval(&l, n, d, rs, ms, sd_v3(10.0, 0, 0), sd_v3_zero(), &ds, 1e-3);
    CHECK_REL("coulomb cap |F_t| = mu |F_n|", fabs(o.force.x), 0.4 * fabs(o.force.z), 1e-12);
    CHECK(o.force.x < 0);
    /* the spring turns with the normal and keeps its length */
    sd_vec3 s = sd_law_rotate_spring(sd_v3(1e-6, 0, 1e-7), sd_v3(0, 0, 1));
    CHECK_NEAR("rotated spring: normal part", s.z, 0.0, 1e-20);
    CHECK_REL("rotated spring: length kept", sd_v3_norm(s), sqrt(1e-12 + 1e-14), 1e-12);

    /* history survives a rebuild and a re-sort: two spheres pressed and
     * sheared, then the list rebuilt; the spring is found again by key */
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.gravity = sd_test_v(0, 0, 0);
    wd.threads = 1;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    int mat = sd_world_add_material(w, &m, &err);
    sd_sphere_def sp[3];
    memset(sp, 0, sizeof sp);
    sp[0].position = sd_test_v(0.01, 0, 0); /* stored first, sorts last */
    sp[0].radius = 0.001;
    sp[1].position = sd_test_v(0, 0, 0.00199);
    sp[1].velocity = sd_test_v(0.01, 0, 0);
    sp[1].radius = 0.001;
    sp[2].position = sd_test_v(0, 0, 0);
    sp[2].radius = 0.001;
    for (int k = 0; k < 3; ++k)
        sp[k].material = mat;
    sd_world_add_spheres(w, 3, sp, &err);
    wd.dt = 1e-7;
    w->dt = 1e-7;
    sd_test_require(sd_world_step(w, 20, &err) == SD_OK, "step", &err);
    CHECK(w->pairs.n >= 1);
    sd_vec3 before = w->pairs.ds[0];
    sd_pair_key key = w->pairs.key[0];
    CHECK(sd_v3_norm(before) > 0);
    w->dirty = 1; /* force a rebuild on the next step */
    long r0 = w->rebuilds;
    w->dt = 0; /* a zero step: nothing moves, the spring only needs to be found */
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    CHECK(w->rebuilds == r0 + 1);
    int found = 0;
    for (size_t e = 0; e < w->pairs.n; ++e)
        if (memcmp(&w->pairs.key[e], &key, sizeof key) == 0) {
            found = 1;
            CHECK_NEAR("spring after rebuild (x), m", w->pairs.ds[e].x, before.x, 0.0);
            CHECK_NEAR("spring after rebuild (y), m", w->pairs.ds[e].y, before.y, 0.0);
        }
    CHECK(found);
    sd_world_destroy(w);
    return sd_test_summary();
}
