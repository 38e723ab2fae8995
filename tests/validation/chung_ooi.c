/* chung_ooi.c — tests 1 to 8 of the Chung & Ooi benchmark (Granular
 * Matter 13, 643-656, 2011), short forms, under Hertz-Mindlin, the wall
 * impacts each against an analytic plane and against a mesh wall holding
 * the same plane (two triangles):
 *
 *  - test 1, elastic normal impact of two identical spheres (no wall):
 *    alumina (E 380 GPa, nu 0.23, rho 4000 kg/m^3) and cast iron (E 100
 *    GPa, nu 0.25, rho 7000 kg/m^3), R 10 mm, 10 m/s each: peak force and
 *    contact time against Hertz's with R* = R/2, m* = m/2 (1 %, 2 %), the
 *    speeds after the speeds before (1e-3);
 *  - test 2, elastic normal impact of a sphere with a rigid wall:
 *    aluminium alloy (E 70 GPa, nu 0.33, rho 2700 kg/m^3) and nylon
 *    (E 2.5 GPa, nu 0.4, rho 1000 kg/m^3), R 0.1 m, 0.2 m/s. The peak
 *    force and the contact time against Hertz's: delta_max = (15 m v^2 /
 *    (16 E* sqrt R))^(2/5), F_max = 4/3 E* sqrt(R) delta_max^(3/2), t_c =
 *    2.9432 delta_max / v (1 % and 2 %, the time to the step); the rebound
 *    speed the impact speed (1e-3);
 *  - test 3, normal impacts of an alumina sphere (below) with the wall at
 *    e = 0.2 to 0.8: the rebound over the impact speed e (1 %: the LIGGGHTS
 *    damping form is not exact for Hertz's spring);
 *  - test 4, oblique impacts of an alumina sphere (E 380 GPa, nu 0.23,
 *    rho 4000 kg/m^3, R 2.5 mm, mu 0.092) at 3.9 m/s, incidence 10 to 80
 *    degrees from the normal: where the sphere slides throughout (tan theta
 *    > 7/2 mu (1 + e), above 32.8 degrees) the rigid-body sliding limit,
 *    v_t' = v_t - mu (1 + e) v_n and omega' = 5 mu (1 + e) v_n / (2 R)
 *    (1 %); below it printed;
 *  - test 5, a sphere on the wall at a constant normal speed and varying
 *    tangential speed: steel (E 208 GPa, nu 0.3, rho 7850) and polyethylene
 *    (E 1 GPa, nu 0.4, rho 1400), R 10 mm, 5 m/s, mu 0.3, e = 1 (Maw,
 *    Barber & Fawcett's elastic sphere): the normal peak force and contact
 *    time Hertz's at every tangential speed (1 %, 2 %), and where the
 *    sphere slides throughout (psi = v_t / (mu v_n) > 7/2 (1 + e) = 7) the
 *    recoil s' / (mu v_n') = psi - 7 (1 % of psi) and the spin r w' /
 *    (mu v_n) = 5 (2 %: the force acts at r - delta/2);
 *  - test 6, a sphere on the wall at constant normal and tangential speeds
 *    (0.2 m/s each, R 0.1 m) with a spin that sets the contact point's
 *    sliding speed s = v_t - r w0 from 0.1 to 1.2 m/s: aluminium alloy and
 *    nylon (test 2's), mu 0.4; sliding throughout (s > 7/2 mu (1 + e) v_n)
 *    the sliding limit, v_t' = v_t - mu (1 + e) v_n, w' = w0 + 5 mu (1 +
 *    e) v_n / (2 r) (1 %), and the rebound e (1 %);
 *  - test 7, two identical spheres (R 0.1 m, 0.2 m/s each) spinning the
 *    same way at w0 = 1 to 20 rad/s, their surfaces sliding at 2 R w0:
 *    aluminium alloy and copper (E 120 GPa, nu 0.35, rho 8900), mu 0.4;
 *  - test 8, a sphere (R 0.1 m, 0.2 m/s, spin w0) on a sphere twice its
 *    radius at rest, the same material (aluminium alloy, nylon), mu 0.4;
 *    for 7 and 8 the rigid-body values with the pair's reduced mass: the
 *    normal impulse m* (1 + e) v_c, the tangential mu times it while the
 *    surfaces slide (s > 7/2 mu (1 + e) v_c for two solid spheres of any
 *    sizes), sphere 1's tangential velocity and spin after (1 %) and the
 *    parting speed e v_c (1 %);
 *  - on the mesh every figure the plane's, to 1e-9 relative.
 *
 * Tests 6 to 8 assert the sliding limit at e = 1. At the benchmark's
 * e = 0.5 they print it: there the tangential impulse of a sliding
 * impact is 3-9 % below mu (1 + e) m* v_c (test 6 prints the ratio),
 * because the Hertz-Mindlin sliding spring (contact/law.h) holds
 * -(F_t + gamma_t v_t) / k_t, which points against the friction when the
 * dashpot alone exceeds mu F_n (a fast slide at the first steps), and
 * k_t, growing as sqrt(delta), scales it past the dashpot at the next
 * step: the friction drives the slide for the first sixth of the contact.
 * Open (issue 30): a fix changes the state hashes of every damped scene.
 *
 * The wall is the sphere's material 1,000 times stiffer (rigid to 0.1 % of
 * E*; Hertz's figures use the E* the run combines). The materials are
 * the benchmark's as recalled from its descriptions and from other codes'
 * benchmark scripts, not checked against the paper (it was not at hand):
 * each check is against Hertz's and the sliding limit's figures for the
 * parameters used, so a difference from the paper's materials changes the
 * case, not the verdict (docs/physics.md says which are recalled).
 * SD_CHUNG_OOI_CSV=FILE writes the sweeps of tests 4 to 8 as CSV,
 * docs/validation/chung_ooi.py plots them.
 */
#include "test.h"

#include <stdlib.h>
#include <string.h>

typedef struct impact {
    double fmax, tc, vn, vt, wy; /* N, s, m/s after, m/s after, rad/s after */
    double fnmax;                /* N, the peak of the normal force alone */
} impact;

/* A Hertz-Mindlin world without gravity on one thread, with the sphere
 * material (E, nu, rho, e, mu) in *ms; test 1 and the wall impacts share it. */
static sd_world *world_with_sphere(double dt, double E, double nu, double rho, double e, double mu, sd_material_def *md,
                                   int *ms)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = SD_LAW_HERTZ_MINDLIN;
    wd.dt = dt;
    wd.gravity = sd_test_v(0, 0, 0);
    wd.threads = 1;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    *md = sd_material_def_default();
    md->name = "sphere";
    md->density = rho;
    md->youngs_modulus = E;
    md->poisson_ratio = nu;
    md->restitution = e;
    md->friction = mu;
    *ms = sd_world_add_material(w, md, &err);
    sd_test_require(*ms >= 0, "material", &err);
    return w;
}

/* One sphere (radius r, material E, nu, rho, mu, restitution e) hitting the wall z = 0
 * (mesh = 1: two triangles of a 4 m square) at normal speed vn, moving
 * along +x at vt and spinning at w0 about +y (its contact point then slides
 * at vt - r w0); stepped until it leaves. */
static impact run_v(int mesh, double E, double nu, double rho, double mu, double e, double r, double vn, double vt,
                    double w0)
{
    sd_error err;
    sd_world *w;
    double m = rho * 4.0 / 3.0 * 3.14159265358979323846 * r * r * r;
    double es = 1.0 / ((1 - nu * nu) / E + (1 - nu * nu) / (1000 * E));
    double dmax = pow(15.0 * m * vn * vn / (16.0 * es * sqrt(r)), 0.4);
    double tc = 2.9432 * dmax / vn;
    double dt = tc / 400; /* 400 steps a contact */
    sd_material_def md;
    int ms;
    w = world_with_sphere(dt, E, nu, rho, e, mu, &md, &ms);
    md.name = "wall";
    md.youngs_modulus = 1000 * E;
    int mw = sd_world_add_material(w, &md, &err);
    sd_test_require(ms >= 0 && mw >= 0, "materials", &err);
    if (mesh) {
        sd_v3d vx[4] = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
        uint32_t tr[2][3] = {{0, 1, 2}, {0, 2, 3}};
        sd_mesh_def d = sd_mesh_def_default();
        d.vertices = vx;
        d.vertex_count = 4;
        d.triangles = (const uint32_t(*)[3])tr;
        d.triangle_count = 2;
        d.material = mw;
        sd_test_require(sd_world_add_mesh(w, "floor", &d, &err) >= 0, "mesh", &err);
    } else {
        sd_test_require(sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mw, &err) >= 0, "plane",
                        &err);
    }
    sd_sphere_def s = {0};
    s.position = sd_test_v(0, 0, r + 2 * vn * dt); /* two steps above the wall */
    s.velocity = sd_test_v(vt, 0, -vn);
    s.angular_velocity = sd_test_v(0, w0, 0);
    s.radius = r;
    s.material = ms;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    impact out = {0, 0, 0, 0, 0, 0};
    long touching = 0;
    for (int k = 0; k < 4000; ++k) {
        sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
        sd_wall_info wi;
        sd_world_get_wall(w, 0, &wi);
        double f = sqrt(wi.force.x * wi.force.x + wi.force.y * wi.force.y + wi.force.z * wi.force.z);
        if (fabs(wi.force.z) > 0)
            touching++;
        out.fmax = f > out.fmax ? f : out.fmax;
        out.fnmax = fabs(wi.force.z) > out.fnmax ? fabs(wi.force.z) : out.fnmax;
        if (touching > 0 && wi.force.z == 0 && k > 10)
            break;
    }
    sd_particle_state p;
    sd_world_get_particle(w, sd_world_find_particle(w, 0), &p);
    out.tc = (double)touching * dt;
    out.vn = p.velocity.z;
    out.vt = p.velocity.x;
    out.wy = p.angular_velocity.y;
    sd_world_destroy(w);
    return out;
}

/* The same at speed v, theta degrees from the normal, without spin. */
static impact run(int mesh, double E, double nu, double rho, double mu, double e, double r, double v, double theta)
{
    double th = theta * 3.14159265358979323846 / 180.0;
    return run_v(mesh, E, nu, rho, mu, e, r, v * cos(th), v * sin(th), 0.0);
}

/* Test 1: two identical spheres (radius r, E, nu, rho) meeting head on at
 * v each (no wall, no gravity): the peak force (m dv / dt of one sphere,
 * velocity Verlet's kick) and the contact time (the steps its velocity
 * changes), and the speed after. */
static impact pair(double E, double nu, double rho, double r, double v, double dt)
{
    sd_error err;
    sd_world *w;
    sd_material_def md;
    int ms;
    w = world_with_sphere(dt, E, nu, rho, 1.0, 0.0, &md, &ms);
    sd_sphere_def s[2];
    memset(s, 0, sizeof s);
    s[0].position = sd_test_v(-r - 2 * v * dt, 0, 0);
    s[0].velocity = sd_test_v(v, 0, 0);
    s[1].position = sd_test_v(r + 2 * v * dt, 0, 0);
    s[1].velocity = sd_test_v(-v, 0, 0);
    s[0].radius = s[1].radius = r;
    s[0].material = s[1].material = ms;
    sd_test_require(sd_world_add_spheres(w, 2, s, &err) == SD_OK, "spheres", &err);
    double m = rho * 4.0 / 3.0 * 3.14159265358979323846 * r * r * r, last = v;
    impact out = {0, 0, 0, 0, 0, 0};
    long touching = 0;
    for (int k = 0; k < 4000; ++k) {
        sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
        sd_particle_state p;
        sd_world_get_particle(w, sd_world_find_particle(w, 0), &p);
        double f = m * fabs(p.velocity.x - last) / dt;
        if (f > 0)
            touching++;
        else if (touching > 0)
            break;
        out.fmax = f > out.fmax ? f : out.fmax;
        last = p.velocity.x;
    }
    out.tc = (double)touching * dt;
    out.vn = -last;
    sd_world_destroy(w);
    return out;
}

/* Both walls' figures equal to 1e-9 relative. */
static void same(const char *what, double plane, double mesh)
{
    char label[160];
    snprintf(label, sizeof label, "%s: mesh vs plane", what);
    CHECK_NEAR(label, mesh, plane, 1e-9 * fabs(plane) + 1e-300);
}

/* Tests 7 and 8: sphere 1 (radius r1) at -x moving along +x at v1 and
 * sphere 2 (r2) at +x moving along -x at v2, of one material (E, nu, rho,
 * restitution e, friction mu), spinning at w1 and w2 about +y (their
 * surfaces then slide past each other at -(w1 r1 + w2 r2) along z), no
 * gravity; stepped until they part. Returns sphere 1's velocities after:
 * vn along x, vt along z, wy; the peak force m1 |dv1| / dt and the
 * contact time; *two: sphere 2's velocities after. */
static impact spheres2(double E, double nu, double rho, double mu, double e, double r1, double r2, double v1, double v2,
                       double w1, double w2, double dt, impact *two)
{
    sd_error err;
    sd_world *w;
    sd_material_def md;
    int ms;
    w = world_with_sphere(dt, E, nu, rho, e, mu, &md, &ms);
    sd_sphere_def s[2];
    memset(s, 0, sizeof s);
    s[0].position = sd_test_v(-r1 - 2 * v1 * dt, 0, 0); /* two steps apart */
    s[0].velocity = sd_test_v(v1, 0, 0);
    s[0].angular_velocity = sd_test_v(0, w1, 0);
    s[1].position = sd_test_v(r2 + 2 * v2 * dt, 0, 0);
    s[1].velocity = sd_test_v(-v2, 0, 0);
    s[1].angular_velocity = sd_test_v(0, w2, 0);
    s[0].radius = r1;
    s[1].radius = r2;
    s[0].material = s[1].material = ms;
    sd_test_require(sd_world_add_spheres(w, 2, s, &err) == SD_OK, "spheres", &err);
    double m1 = rho * 4.0 / 3.0 * 3.14159265358979323846 * r1 * r1 * r1;
    impact out = {0, 0, 0, 0, 0, 0};
    long touching = 0;
    sd_v3d last = s[0].velocity;
    for (int k = 0; k < 8000; ++k) {
        sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
        sd_particle_state p;
        sd_world_get_particle(w, sd_world_find_particle(w, 0), &p);
        double dvx = p.velocity.x - last.x, dvz = p.velocity.z - last.z;
        double f = m1 * sqrt(dvx * dvx + dvz * dvz) / dt;
        if (f > 0)
            touching++;
        else if (touching > 0)
            break;
        out.fmax = f > out.fmax ? f : out.fmax;
        out.fnmax = m1 * fabs(dvx) / dt > out.fnmax ? m1 * fabs(dvx) / dt : out.fnmax;
        last = p.velocity;
        out.wy = p.angular_velocity.y;
    }
    out.tc = (double)touching * dt;
    out.vn = last.x;
    out.vt = last.z;
    sd_particle_state p2;
    sd_world_get_particle(w, sd_world_find_particle(w, 1), &p2);
    *two = out;
    two->vn = p2.velocity.x;
    two->vt = p2.velocity.z;
    two->wy = p2.angular_velocity.y;
    sd_world_destroy(w);
    return out;
}

/* Hertz's contact time of an elastic impact at closing speed vc (E* es,
 * R* rs, m* ms): 2.9432 delta_max / vc (the time step is a 400th of it). */
static double hertz_tc(double es, double rs, double ms, double vc)
{
    return 2.9432 * pow(15.0 * ms * vc * vc / (16.0 * es * sqrt(rs)), 0.4) / vc;
}

/* Rigid-body impact with Coulomb friction (Maw, Barber & Fawcett's
 * rigid limit; Chung & Ooi's "sliding limit"): body 1 (mass m1, radius
 * r1, a solid sphere) meets body 2 (inverse mass im2, a solid sphere or a
 * wall: im2 = 0) at closing speed vc, the contact point of 1 sliding on 2
 * at s. The normal impulse is m* (1 + e) vc; the tangential one opposes s
 * and is mu times it while the contact slides, which it does throughout
 * when |s| > 7/2 mu (1 + e) vc (a solid sphere's tangential impulse J
 * changes s by J (1/m + r^2/I) = 7/2 J/m for each sphere); else the
 * contact sticks and J = |s| / (7/2 (1/m1 + im2)). Returns J (N s) and
 * sets *sliding. */
static double rigid_impulse(double m1, double im2, double e, double mu, double vc, double s, int *sliding)
{
    double ms = 1.0 / (1.0 / m1 + im2), jn = ms * (1 + e) * vc, jstick = fabs(s) / (3.5 * (1.0 / m1 + im2));
    *sliding = jstick > mu * jn;
    return *sliding ? mu * jn : jstick;
}

typedef struct co_mat {
    const char *name;
    double E, nu, rho;
} co_mat;

static const co_mat steel = {"steel", 2.08e11, 0.30, 7850}, polyethylene = {"polyethylene", 1.0e9, 0.40, 1400},
                    al_alloy = {"aluminium alloy", 7.0e10, 0.33, 2700}, nylon = {"nylon", 2.5e9, 0.40, 1000},
                    copper = {"copper", 1.2e11, 0.35, 8900};

/* One row of the sweep's CSV (mesh: NAN where no wall is involved). */
static void emit(FILE *fp, int test, const char *mat, double x, const char *q, double plane, double mesh, double rigid)
{
    if (fp)
        fprintf(fp, "%d,%s,%.9g,%s,%.9g,%.9g,%.9g\n", test, mat, x, q, plane, mesh, rigid);
}

/* Test 5: a sphere on the wall at constant normal speed vn and tangential
 * speeds s = psi mu vn (no spin), e = 1 (Maw, Barber & Fawcett's elastic
 * sphere). Normalised (Chung & Ooi's axes): the recoil psi' = s' / (mu
 * vn') and the spin r w' / (mu vn) against psi; rigid-body sliding where
 * psi > 7/2 (1 + e) = 7: psi' = psi - 7, r w' / (mu vn) = 5/2 (1 + e) = 5.
 * check: 1 asserts (sliding points and the mesh), 0 only computes. */
static void test5_point(FILE *fp, const co_mat *mt, double psi, int check)
{
    const double mu = 0.3, e = 1.0, r = 0.01, vn = 5.0;
    double m = mt->rho * 4.0 / 3.0 * 3.14159265358979323846 * r * r * r, s = psi * mu * vn;
    impact a = run_v(0, mt->E, mt->nu, mt->rho, mu, e, r, vn, s, 0.0);
    impact b = run_v(1, mt->E, mt->nu, mt->rho, mu, e, r, vn, s, 0.0);
    int sliding;
    double J = rigid_impulse(m, 0.0, e, mu, vn, s, &sliding);
    double vt_r = s - J / m, w_r = 2.5 * J / (m * r), vn_r = e * vn;
    double rec_a = (a.vt - r * a.wy) / (mu * a.vn), rec_b = (b.vt - r * b.wy) / (mu * b.vn);
    double rec_r = (vt_r - r * w_r) / (mu * vn_r);
    emit(fp, 5, mt->name, psi, "recoil", rec_a, rec_b, rec_r);
    emit(fp, 5, mt->name, psi, "spin", a.wy * r / (mu * vn), b.wy * r / (mu * vn), w_r * r / (mu * vn));
    if (!check)
        return;
    /* e = 1: the normal impact is Hertz's whatever the tangential motion */
    double es = 1.0 / ((1 - mt->nu * mt->nu) / mt->E + (1 - mt->nu * mt->nu) / (1000 * mt->E));
    double tc = hertz_tc(es, r, m, vn), dmax = pow(15.0 * m * vn * vn / (16.0 * es * sqrt(r)), 0.4);
    double fmax = 4.0 / 3.0 * es * sqrt(r) * pow(dmax, 1.5);
    printf("test 5, %s, psi %5.2f: normal F_max %.6g N (Hertz %.6g), t_c %.6g s (Hertz %.6g)\n", mt->name, psi, a.fnmax,
           fmax, a.tc, tc);
    printf("test 5, %s, psi = s/(mu vn) %5.2f: recoil s'/(mu vn') %8.5f (rigid %8.5f), r w'/(mu vn) %.5f "
           "(rigid %.5f)%s\n",
           mt->name, psi, rec_a, rec_r, a.wy * r / (mu * vn), w_r * r / (mu * vn), sliding ? "" : "  [sticks]");
    char label[160];
    snprintf(label, sizeof label, "test 5, %s, psi %g, plane: normal peak force vs Hertz (1 %%)", mt->name, psi);
    CHECK_REL(label, a.fnmax, fmax, 0.01);
    snprintf(label, sizeof label, "test 5, %s, psi %g, plane: contact time vs Hertz (2 %%)", mt->name, psi);
    CHECK_REL(label, a.tc, tc, 0.02);
    if (psi > 1.15 * 3.5 * (1 + e)) {
        snprintf(label, sizeof label, "test 5, %s, psi %g, plane: recoil vs the sliding limit (1 %% of psi)", mt->name,
                 psi);
        CHECK_NEAR(label, rec_a, rec_r, 0.01 * psi);
        /* the force acts at the middle of the overlap, r - delta/2 from the
         * centre: polyethylene at 5 m/s overlaps by 2.7 % of r at the peak,
         * which takes 1.1 % from the spin (steel's 0.1 %): 2 % */
        snprintf(label, sizeof label, "test 5, %s, psi %g, plane: spin vs the sliding limit (2 %%)", mt->name, psi);
        CHECK_REL(label, a.wy, w_r, 0.02);
    }
    snprintf(label, sizeof label, "test 5, %s, psi %g: tangential velocity", mt->name, psi);
    same(label, a.vt, b.vt);
    snprintf(label, sizeof label, "test 5, %s, psi %g: spin", mt->name, psi);
    same(label, a.wy, b.wy);
}

/* Test 6: a sphere on the wall at constant normal and tangential speeds
 * (vn = vt = 0.2 m/s) and varying spin w0, so that its contact point
 * meets the wall sliding at s = vt - r w0 = vn tan(incidence), e = 0.5,
 * mu = 0.4: back spin (w0 < 0) adds to s, top spin takes from it. Chung &
 * Ooi's axes: beta = -s' / s against chi = 7/2 mu (1 + e) vn / s, and the
 * tangent of the recoil, s' / vn', against tan(incidence); sliding where
 * chi < 1: beta = chi - 1. */
static void test6_point(FILE *fp, const co_mat *mt, double tan_in, double e, int check)
{
    const double mu = 0.4, r = 0.1, vn = 0.2, vt = 0.2;
    double m = mt->rho * 4.0 / 3.0 * 3.14159265358979323846 * r * r * r, s = tan_in * vn, w0 = (vt - s) / r;
    impact a = run_v(0, mt->E, mt->nu, mt->rho, mu, e, r, vn, vt, w0);
    impact b = run_v(1, mt->E, mt->nu, mt->rho, mu, e, r, vn, vt, w0);
    int sliding;
    double J = rigid_impulse(m, 0.0, e, mu, vn, s, &sliding);
    double vt_r = vt - J / m, w_r = w0 + 2.5 * J / (m * r), chi = 3.5 * mu * (1 + e) * vn / s;
    double s_a = a.vt - r * a.wy, s_b = b.vt - r * b.wy, s_r = vt_r - r * w_r;
    char name[64];
    snprintf(name, sizeof name, "%s (e %g)", mt->name, e);
    emit(fp, 6, name, chi, "beta", -s_a / s, -s_b / s, -s_r / s);
    emit(fp, 6, name, tan_in, "tan_recoil", s_a / a.vn, s_b / b.vn, s_r / (e * vn));
    if (!check)
        return;
    printf("test 6, %s, tan(incidence) %4.2f (w0 %+.4f rad/s, chi %.3f): beta %8.5f (rigid %8.5f), "
           "tan(recoil) %8.5f (rigid %8.5f), tangential impulse / rigid %.4f%s\n",
           name, tan_in, w0, chi, -s_a / s, -s_r / s, s_a / a.vn, s_r / (e * vn), (vt - a.vt) / (vt - vt_r),
           sliding ? "" : "  [sticks]");
    char label[160];
    if (chi < 0.85) {
        snprintf(label, sizeof label, "test 6, %s, tan %g, plane: normal rebound / vn vs e (1 %%)", name, tan_in);
        CHECK_REL(label, a.vn / vn, e, 0.01);
    }
    if (chi < 0.85 && e == 1.0) {
        snprintf(label, sizeof label, "test 6, %s, tan %g, plane: tangential velocity vs the sliding limit (1 %%)",
                 mt->name, tan_in);
        CHECK_REL(label, a.vt, vt_r, 0.01);
        snprintf(label, sizeof label, "test 6, %s, tan %g, plane: spin vs the sliding limit (1 %%)", mt->name, tan_in);
        CHECK_REL(label, a.wy, w_r, 0.01);
    }
    snprintf(label, sizeof label, "test 6, %s, tan %g: tangential velocity", mt->name, tan_in);
    same(label, a.vt, b.vt);
    snprintf(label, sizeof label, "test 6, %s, tan %g: spin", mt->name, tan_in);
    same(label, a.wy, b.wy);
    snprintf(label, sizeof label, "test 6, %s, tan %g: normal velocity", mt->name, tan_in);
    same(label, a.vn, b.vn);
}

/* Tests 7 and 8 share the two-sphere impact: sphere 1 (r1) at v1 with spin
 * w0 meets sphere 2 (r2, at v2, spin w2 = k2 w0) of the same material,
 * e = 0.5, mu = 0.4; sphere 1's tangential velocity and spin after, against
 * the rigid-body values (the sliding limit where the surfaces slide
 * throughout, else sticking: J = |s| / (7/2 (1/m1 + 1/m2))). */
typedef struct pair_case {
    double vt, wy, vn;       /* computed: sphere 1 after */
    double vt_r, wy_r, vn_r; /* rigid body */
    double s;                /* the initial sliding speed of 1 on 2 (m/s) */
    double s1, s1_r;         /* the sliding speed after: computed, rigid body */
    double sep, sep_r;       /* the speed the centres part at after: computed, rigid body (e vc) */
    int sliding;
} pair_case;

static pair_case spheres_spin(const co_mat *mt, double r1, double r2, double v1, double v2, double w0, double k2,
                              double e)
{
    const double mu = 0.4, pi = 3.14159265358979323846;
    double m1 = mt->rho * 4.0 / 3.0 * pi * r1 * r1 * r1, m2 = mt->rho * 4.0 / 3.0 * pi * r2 * r2 * r2;
    double es = mt->E / (2 * (1 - mt->nu * mt->nu)), rs = r1 * r2 / (r1 + r2), ms = m1 * m2 / (m1 + m2);
    double vc = v1 + v2;
    impact b;
    impact a = spheres2(mt->E, mt->nu, mt->rho, mu, e, r1, r2, v1, v2, w0, k2 * w0, hertz_tc(es, rs, ms, vc) / 400, &b);
    pair_case c;
    c.s = -(w0 * r1 + k2 * w0 * r2); /* along z, sphere 1's surface on sphere 2's */
    double J = rigid_impulse(m1, 1.0 / m2, e, mu, vc, c.s, &c.sliding);
    double sg = c.s > 0 ? 1.0 : -1.0;
    /* friction on 1 along -sign(s) z at its contact point +r1 x: torque
     * r1 x (-sign(s) J z) = +sign(s) J r1 about y */
    c.vt_r = -sg * J / m1;
    c.wy_r = w0 + sg * 2.5 * J / (m1 * r1);
    c.vn_r = v1 - (1 + e) * ms * vc / m1;
    c.vt = a.vt;
    c.wy = a.wy;
    c.vn = a.vn;
    /* the surfaces at the contact: 1's at +r1 x, 2's at -r2 x */
    c.s1 = (a.vt - a.wy * r1) - (b.vt + b.wy * r2);
    c.s1_r = c.s - sg * 3.5 * J * (1 / m1 + 1 / m2);
    c.sep = b.vn - a.vn;
    c.sep_r = e * vc;
    return c;
}

int main(void)
{
    /* test 1: elastic normal impact of two identical spheres: R* = R/2,
     * m* = m/2, E* = E / (2 (1 - nu^2)), each at v (2 v closing) */
    static const struct {
        const char *name;
        double E, nu, rho;
    } t1[2] = {{"alumina", 3.8e11, 0.23, 4000}, {"cast iron", 1.0e11, 0.25, 7000}};
    for (int k = 0; k < 2; ++k) {
        double r = 0.01, v = 10, m = t1[k].rho * 4.0 / 3.0 * 3.14159265358979323846 * r * r * r;
        double es = t1[k].E / (2 * (1 - t1[k].nu * t1[k].nu)), rs = r / 2, ms = m / 2;
        double dmax = pow(15.0 * ms * (2 * v) * (2 * v) / (16.0 * es * sqrt(rs)), 0.4);
        double fmax = 4.0 / 3.0 * es * sqrt(rs) * pow(dmax, 1.5), tc = 2.9432 * dmax / (2 * v);
        impact a = pair(t1[k].E, t1[k].nu, t1[k].rho, r, v, tc / 400);
        char label[160];
        printf("test 1, %s: F_max %.6g N (Hertz %.6g), t_c %.6g s (Hertz %.6g), speed after %.6g m/s of %g\n",
               t1[k].name, a.fmax, fmax, a.tc, tc, a.vn, v);
        snprintf(label, sizeof label, "test 1, %s: peak force vs Hertz (1 %%)", t1[k].name);
        CHECK_REL(label, a.fmax, fmax, 0.01);
        snprintf(label, sizeof label, "test 1, %s: contact time vs Hertz (2 %%)", t1[k].name);
        CHECK_REL(label, a.tc, tc, 0.02);
        snprintf(label, sizeof label, "test 1, %s: speed after (e = 1)", t1[k].name);
        CHECK_REL(label, a.vn, v, 1e-3);
    }
    /* test 2: elastic normal impact with a rigid wall */
    static const struct {
        const char *name;
        double E, nu, rho;
    } mats[2] = {{"aluminium alloy", 7.0e10, 0.33, 2700}, {"nylon", 2.5e9, 0.4, 1000}};
    for (int k = 0; k < 2; ++k) {
        double r = 0.1, v = 0.2, m = mats[k].rho * 4.0 / 3.0 * 3.14159265358979323846 * r * r * r;
        double es =
            1.0 / ((1 - mats[k].nu * mats[k].nu) / mats[k].E + (1 - mats[k].nu * mats[k].nu) / (1000 * mats[k].E));
        double dmax = pow(15.0 * m * v * v / (16.0 * es * sqrt(r)), 0.4);
        double fmax = 4.0 / 3.0 * es * sqrt(r) * pow(dmax, 1.5), tc = 2.9432 * dmax / v;
        impact a = run(0, mats[k].E, mats[k].nu, mats[k].rho, 0.0, 1.0, r, v, 0.0);
        impact b = run(1, mats[k].E, mats[k].nu, mats[k].rho, 0.0, 1.0, r, v, 0.0);
        char label[160];
        printf("test 2, %s: F_max %.6g N (Hertz %.6g), t_c %.6g s (Hertz %.6g), rebound %.6g m/s of 0.2\n",
               mats[k].name, a.fmax, fmax, a.tc, tc, a.vn);
        snprintf(label, sizeof label, "test 2, %s, plane: peak force vs Hertz (1 %%)", mats[k].name);
        CHECK_REL(label, a.fmax, fmax, 0.01);
        snprintf(label, sizeof label, "test 2, %s, plane: contact time vs Hertz (2 %%)", mats[k].name);
        CHECK_REL(label, a.tc, tc, 0.02);
        snprintf(label, sizeof label, "test 2, %s, plane: rebound speed (e = 1)", mats[k].name);
        CHECK_REL(label, a.vn, v, 1e-3);
        snprintf(label, sizeof label, "test 2, %s: peak force", mats[k].name);
        same(label, a.fmax, b.fmax);
        snprintf(label, sizeof label, "test 2, %s: contact time", mats[k].name);
        same(label, a.tc, b.tc);
        snprintf(label, sizeof label, "test 2, %s: rebound speed", mats[k].name);
        same(label, a.vn, b.vn);
    }
    const double E = 3.8e11, nu = 0.23, rho = 4000, mu = 0.092, r = 0.0025, v = 3.9;
    /* test 3: normal impacts with the wall at restitution e below 1: the
     * rebound speed over the impact speed against e (the LIGGGHTS damping
     * form is not exact for Hertz's spring; here within 0.16 %: 1 %) */
    for (int k = 1; k <= 4; ++k) {
        double e = 0.2 * k;
        impact a = run(0, E, nu, rho, 0.0, e, r, v, 0.0);
        impact b = run(1, E, nu, rho, 0.0, e, r, v, 0.0);
        char label[160];
        snprintf(label, sizeof label, "test 3, e = %.1f, plane: rebound / impact speed vs e (1 %%)", e);
        CHECK_REL(label, a.vn / v, e, 0.01);
        snprintf(label, sizeof label, "test 3, e = %.1f: rebound speed", e);
        same(label, a.vn, b.vn);
    }
    /* test 4: oblique impacts of alumina at 3.9 m/s */
    printf("test 4: theta (deg), tangential restitution v_t'/v_t, spin w' R / v_t, rebound angle (deg); "
           "sliding limit where tan theta > %.4f\n",
           3.5 * mu * 2);
    for (int deg = 10; deg <= 80; deg += 10) {
        impact a = run(0, E, nu, rho, mu, 1.0, r, v, deg);
        impact b = run(1, E, nu, rho, mu, 1.0, r, v, deg);
        double th = deg * 3.14159265358979323846 / 180.0, vn = v * cos(th), vt = v * sin(th);
        double vt_lim = vt - mu * 2 * vn,
               w_lim = 5 * mu * 2 * vn / (2 * r); /* +y: friction along -x below the centre */
        printf("  %2d  e_t %.5f (sliding limit %.5f)  w'R/v_t %.5f (limit %.5f)  rebound %.3f deg\n", deg, a.vt / vt,
               vt_lim / vt, a.wy * r / vt, w_lim * r / vt, atan2(a.vt, a.vn) * 180 / 3.14159265358979323846);
        char label[160];
        if (tan(th) > 3.5 * mu * 2) {
            snprintf(label, sizeof label, "test 4, %d deg, plane: tangential velocity vs the sliding limit (1 %%)",
                     deg);
            CHECK_REL(label, a.vt, vt_lim, 0.01);
            snprintf(label, sizeof label, "test 4, %d deg, plane: spin vs the sliding limit (1 %%)", deg);
            CHECK_REL(label, a.wy, w_lim, 0.01);
        }
        snprintf(label, sizeof label, "test 4, %d deg: tangential velocity", deg);
        same(label, a.vt, b.vt);
        snprintf(label, sizeof label, "test 4, %d deg: spin", deg);
        same(label, a.wy, b.wy);
        snprintf(label, sizeof label, "test 4, %d deg: normal velocity", deg);
        same(label, a.vn, b.vn);
    }
    /* test 5: constant normal, varying tangential speed (steel and
     * polyethylene, e = 1, mu = 0.3): asserted at 8, 10 and 14 (sliding) */
    static const double psis[] = {1, 2, 4, 6, 8, 10, 14};
    for (int k = 0; k < 7; ++k) {
        test5_point(NULL, &steel, psis[k], 1);
        test5_point(NULL, &polyethylene, psis[k], 1);
    }
    /* test 6: constant normal and tangential speeds, varying spin (aluminium
     * alloy and nylon, mu = 0.4): sliding where tan(incidence) > 7/2 mu (1 +
     * e); the sliding limit asserted at e = 1, the benchmark's e = 0.5
     * printed against it (see the note at the top) */
    static const double tans[] = {0.5, 1, 2, 3, 4, 6};
    for (int ie = 0; ie < 2; ++ie)
        for (int k = 0; k < 6; ++k) {
            test6_point(NULL, &al_alloy, tans[k], ie ? 0.5 : 1.0, 1);
            test6_point(NULL, &nylon, tans[k], ie ? 0.5 : 1.0, 1);
        }
    /* test 7: two identical spheres (R 0.1 m, 0.2 m/s each) spinning the
     * same way at w0, their surfaces sliding at 2 R w0 (aluminium alloy and
     * copper); test 8: a sphere (R 0.1 m, 0.2 m/s, spin w0) on a sphere
     * twice its radius at rest (aluminium alloy and nylon); e = 1 asserted,
     * e = 0.5 printed */
    static const double w7[] = {1, 2, 4, 6, 10, 20};
    const co_mat *m7[2] = {&al_alloy, &copper}, *m8[2] = {&al_alloy, &nylon};
    for (int ie = 0; ie < 2; ++ie)
        for (int t = 7; t <= 8; ++t)
            for (int k = 0; k < 6; ++k)
                for (int j = 0; j < 2; ++j) {
                    const co_mat *mt = t == 7 ? m7[j] : m8[j];
                    double e = ie ? 0.5 : 1.0;
                    /* test 8's spin from the tangent of the contact point's incidence (as test 6's) */
                    double w0 = t == 7 ? w7[k] : -tans[k] * 0.2 / 0.1;
                    pair_case c = t == 7 ? spheres_spin(mt, 0.1, 0.1, 0.2, 0.2, w0, 1.0, e)
                                         : spheres_spin(mt, 0.1, 0.2, 0.2, 0.0, w0, 0.0, e);
                    double vc = 0.4 - 0.2 * (t == 8), lim = 3.5 * 0.4 * (1 + e) * vc;
                    printf("test %d, %s, e %g, w0 %+7.3f rad/s (slides at %.4f m/s of %.4f): v_t' %+.6f m/s (rigid "
                           "%+.6f), w' %+.5f rad/s (rigid %+.5f), parting %.6f (e v_c %.6f)%s\n",
                           t, mt->name, e, w0, fabs(c.s), lim, c.vt, c.vt_r, c.wy, c.wy_r, c.sep, c.sep_r,
                           c.sliding ? "" : "  [sticks]");
                    if (fabs(c.s) > 1.15 * lim) {
                        char label[160];
                        snprintf(label, sizeof label, "test %d, %s, e %g, w0 %g: parting speed vs e v_c (1 %%)", t,
                                 mt->name, e, w0);
                        CHECK_REL(label, c.sep, c.sep_r, 0.01);
                        if (e < 1)
                            continue;
                        snprintf(label, sizeof label,
                                 "test %d, %s, w0 %g: tangential velocity vs the sliding limit (1 %%)", t, mt->name,
                                 w0);
                        CHECK_REL(label, c.vt, c.vt_r, 0.01);
                        snprintf(label, sizeof label, "test %d, %s, w0 %g: spin vs the sliding limit (1 %%)", t,
                                 mt->name, w0);
                        CHECK_REL(label, c.wy, c.wy_r, 0.01);
                    }
                }
    /* the sweeps for docs/validation/chung_ooi.py, one row a point and
     * quantity: test, material, x, quantity, plane, mesh (NaN without a
     * wall), rigid body (the sliding limit, or sticking below it) */
    const char *csv = getenv("SD_CHUNG_OOI_CSV");
    FILE *fp = csv ? fopen(csv, "w") : NULL;
    if (fp) {
        fprintf(fp, "test,material,x,quantity,plane,mesh,rigid\n");
        for (int deg = 2; deg <= 88; deg += 2) {
            impact a = run(0, E, nu, rho, mu, 1.0, r, v, deg);
            impact b = run(1, E, nu, rho, mu, 1.0, r, v, deg);
            double th = deg * 3.14159265358979323846 / 180.0, vn = v * cos(th), vt = v * sin(th);
            double rad = 180 / 3.14159265358979323846, m = rho * 4.0 / 3.0 * 3.14159265358979323846 * r * r * r;
            int sliding;
            double J = rigid_impulse(m, 0.0, 1.0, mu, vn, vt, &sliding);
            emit(fp, 4, "alumina", deg, "et", a.vt / vt, b.vt / vt, (vt - J / m) / vt);
            emit(fp, 4, "alumina", deg, "spin", a.wy * r / vt, b.wy * r / vt, 2.5 * J / (m * vt));
            emit(fp, 4, "alumina", deg, "rebound", atan2(a.vt, a.vn) * rad, atan2(b.vt, b.vn) * rad,
                 atan2(vt - J / m, vn) * rad);
        }
        for (double psi = 0.5; psi <= 14.01; psi += 0.5) {
            test5_point(fp, &steel, psi, 0);
            test5_point(fp, &polyethylene, psi, 0);
        }
        for (int ie = 0; ie < 2; ++ie) {
            double e = ie ? 0.5 : 1.0;
            for (double ti = 0.25; ti <= 7.01; ti += 0.25)
                for (int j = 0; j < 2; ++j) {
                    test6_point(fp, j ? &nylon : &al_alloy, ti, e, 0);
                    pair_case c = spheres_spin(m8[j], 0.1, 0.2, 0.2, 0.0, -ti * 0.2 / 0.1, 0.0, e);
                    char name[64];
                    snprintf(name, sizeof name, "%s (e %g)", m8[j]->name, e);
                    emit(fp, 8, name, 3.5 * 0.4 * (1 + e) * 0.2 / c.s, "beta", -c.s1 / c.s, NAN, -c.s1_r / c.s);
                    emit(fp, 8, name, ti, "tan_recoil", c.s1 / c.sep, NAN, c.s1_r / c.sep_r);
                }
            for (double w0 = 0.5; w0 <= 25.01; w0 += 0.5)
                for (int j = 0; j < 2; ++j) {
                    pair_case c = spheres_spin(m7[j], 0.1, 0.1, 0.2, 0.2, w0, 1.0, e);
                    char name[64];
                    snprintf(name, sizeof name, "%s (e %g)", m7[j]->name, e);
                    emit(fp, 7, name, w0, "vt", c.vt, NAN, c.vt_r);
                    emit(fp, 7, name, w0, "spin", c.wy, NAN, c.wy_r);
                }
        }
        fclose(fp);
        printf("wrote %s\n", csv);
    }
    return sd_test_summary();
}
