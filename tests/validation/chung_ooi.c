/* chung_ooi.c — tests 1 to 4 of the Chung & Ooi benchmark (Granular
 * Matter 13, 643-656, 2011), short forms, under Hertz-Mindlin with e = 1
 * (elastic), the wall impacts each against an analytic plane and against
 * a mesh wall holding the same plane (two triangles):
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
 *  - on the mesh every figure the plane's, to 1e-9 relative.
 *
 * The wall is the sphere's material 1,000 times stiffer (rigid to 0.1 % of
 * E*; Hertz's figures use the E* the run combines). The materials are
 * the benchmark's as recalled from its descriptions, not checked against
 * the paper (it was not at hand): each check is against Hertz's and the
 * sliding limit's figures for the parameters used, so a difference from
 * the paper's materials changes the case, not the verdict. The oblique
 * sweep, every 2 degrees on both walls: SD_CHUNG_OOI_CSV=FILE writes it as
 * CSV, docs/validation/chung_ooi.py plots it.
 */
#include "test.h"

#include <string.h>

typedef struct impact {
    double fmax, tc, vn, vt, wy; /* N, s, m/s after, m/s after, rad/s after */
} impact;

/* A Hertz-Mindlin world without gravity on one thread, with the sphere
 * material (E, nu, rho, e, mu) in *ms; test 1 and the wall impacts share it. */
static sd_world *world_with_sphere(double dt, double E, double nu, double rho, double e, double mu,
                                   sd_material_def *md, int *ms)
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
 * (mesh = 1: two triangles of a 4 m square) at speed v, theta degrees
 * from the normal, moving along +x; stepped until it leaves. */
static impact run(int mesh, double E, double nu, double rho, double mu, double e, double r, double v, double theta)
{
    sd_error err;
    sd_world *w;
    double th = theta * 3.14159265358979323846 / 180.0;
    double vn = v * cos(th), vt = v * sin(th);
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
        sd_test_require(sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mw, &err) >= 0,
                        "plane", &err);
    }
    sd_sphere_def s = {0};
    s.position = sd_test_v(0, 0, r + 2 * vn * dt); /* two steps above the wall */
    s.velocity = sd_test_v(vt, 0, -vn);
    s.radius = r;
    s.material = ms;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    impact out = {0, 0, 0, 0, 0};
    long touching = 0;
    for (int k = 0; k < 4000; ++k) {
        sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
        sd_wall_info wi;
        sd_world_get_wall(w, 0, &wi);
        double f = sqrt(wi.force.x * wi.force.x + wi.force.y * wi.force.y + wi.force.z * wi.force.z);
        if (fabs(wi.force.z) > 0)
            touching++;
        out.fmax = f > out.fmax ? f : out.fmax;
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
    impact out = {0, 0, 0, 0, 0};
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
        double es = 1.0 / ((1 - mats[k].nu * mats[k].nu) / mats[k].E + (1 - mats[k].nu * mats[k].nu) / (1000 * mats[k].E));
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
           "sliding limit where tan theta > %.4f\n", 3.5 * mu * 2);
    for (int deg = 10; deg <= 80; deg += 10) {
        impact a = run(0, E, nu, rho, mu, 1.0, r, v, deg);
        impact b = run(1, E, nu, rho, mu, 1.0, r, v, deg);
        double th = deg * 3.14159265358979323846 / 180.0, vn = v * cos(th), vt = v * sin(th);
        double vt_lim = vt - mu * 2 * vn, w_lim = 5 * mu * 2 * vn / (2 * r); /* +y: friction along -x below the centre */
        printf("  %2d  e_t %.5f (sliding limit %.5f)  w'R/v_t %.5f (limit %.5f)  rebound %.3f deg\n", deg, a.vt / vt,
               vt_lim / vt, a.wy * r / vt, w_lim * r / vt, atan2(a.vt, a.vn) * 180 / 3.14159265358979323846);
        char label[160];
        if (tan(th) > 3.5 * mu * 2) {
            snprintf(label, sizeof label, "test 4, %d deg, plane: tangential velocity vs the sliding limit (1 %%)", deg);
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
    /* the sweep for docs/validation/chung_ooi.py: every 2 degrees, both walls */
    const char *csv = getenv("SD_CHUNG_OOI_CSV");
    FILE *fp = csv ? fopen(csv, "w") : NULL;
    if (fp) {
        fprintf(fp, "theta_deg,et_plane,spin_plane,rebound_plane_deg,et_mesh,spin_mesh,rebound_mesh_deg,"
                    "et_sliding,spin_sliding\n");
        for (int deg = 2; deg <= 88; deg += 2) {
            impact a = run(0, E, nu, rho, mu, 1.0, r, v, deg);
            impact b = run(1, E, nu, rho, mu, 1.0, r, v, deg);
            double th = deg * 3.14159265358979323846 / 180.0, vn = v * cos(th), vt = v * sin(th);
            double rad = 180 / 3.14159265358979323846;
            fprintf(fp, "%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", deg, a.vt / vt, a.wy * r / vt,
                    atan2(a.vt, a.vn) * rad, b.vt / vt, b.wy * r / vt, atan2(b.vt, b.vn) * rad,
                    1 - mu * 2 * vn / vt, 5 * mu * 2 * vn / (2 * vt));
        }
        fclose(fp);
        printf("wrote %s\n", csv);
    }
    return sd_test_summary();
}
