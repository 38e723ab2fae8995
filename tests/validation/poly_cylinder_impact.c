/* poly_cylinder_impact.c — seed 000 §3.1: a cylinder modelled as a
 * polyhedron (20-gon prism with its cap centres: 42 vertices, 80 triangles,
 * 22 welded faces) hits a wall at angle theta under the volume law
 * (seed 000 eqs. 12-20), against the rigid-impact solution eqs. 27-28.
 *
 * Table 1 of seed 000: D = 8 mm, L = 5.3 mm, rho = 1245 kg/m^3, E = 1.15e9
 * Pa, nu = 0.35, mu = 0, e = 0.85, dt = 5e-7 s, V_z- = 1 m/s, no gravity.
 * The analytic solution uses this polyhedron's own mass and I_yy (the
 * seed notes they differ slightly from the smooth cylinder's) and the
 * lowest rim vertex (r, 0, -L/2) turned by theta about y, whose horizontal
 * offset from the centre is r_x = r cos(alpha + theta) = r cos(theta) -
 * (L/2) sin(theta):
 *     omega_y+ = -r_x J / I_yy,  V_z+ = J / m - V,  J = (1 + e) m V / (1 + m r_x^2 / I_yy)
 * (the seed's eqs. 27-28 with its sign of omega). Tolerance: 3 % of each
 * quantity's scale over theta = 10..75 deg, as tests/validation/
 * cylinder_impact.c for the smooth cylinder (V_z+ crosses zero near 27
 * deg, omega+ near 56.5 deg: a relative error means nothing there; the
 * scales are V and the largest |omega+| of the sweep), and 4 % at 80 deg,
 * where the side edge through the struck vertex lies only 10 deg from the
 * wall: the volume contact (0.2 mm deep, vertex-like, F ~ d^3) spreads
 * along that edge toward the centre, shortening the lever arm that the
 * point impact assumes (measured 3.3 % in V_z+). At 0 and 90 deg a whole
 * face lands flat and the point-impact solution does not apply (printed,
 * not asserted), as the seed notes for very low and high angles; such a
 * face contact (F ~ d^(1/3)) lasts about 0.25 us at 1 m/s, shorter than
 * Table 1's step, so those two angles run with dt = 5 ns (and bounce
 * flat: V_z+ = e V, no spin). shapedem's own dt estimate for the law
 * (world/material.c) is printed.
 * With SD_VALIDATION_OUT set, the table is written there as
 * poly_cylinder_impact.csv (docs/validation/poly_cylinder_impact.py).
 */
#include "poly_common.h"

static const double D = 8e-3, L = 5.3e-3, RHO = 1245, E = 1.15e9, EN = 0.85, V0 = 1.0;

typedef struct outcome {
    double vz, wy;
} outcome;

static double g_mass, g_iyy;

static double g_rec_dt, g_tc;

static outcome simulate(double theta, double dt)
{
    int mat;
    sd_world *w = poly_world(SD_LAW_VOLUME, dt, sd_test_v(0, 0, 0), E, EN, 0.0, RHO, 1, &mat);
    w->materials[mat].def.poisson_ratio = 0.35;
    sd_v3d v[42];
    int nv = poly_cylinder(20, D, L, v);
    int s = poly_add_shape(w, "cylinder", v, (size_t)nv);
    sd_error err;
    sd_world_add_plane(w, "wall", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err);
    const sd_shape *sh = &w->shapes[s];
    /* the body's pose: the given frame (axis z, a rim vertex on +x) turned
     * by theta about y; the template is in its principal frame */
    sd_quat tilt = sd_quat_make((sd_real)cos(0.5 * theta), 0, (sd_real)sin(0.5 * theta), 0);
    sd_quat q = sd_quat_mul(tilt, sh->given_q);
    double low = 1e9;
    for (uint32_t k = 0; k < sh->vcount; ++k)
        low = fmin(low, (double)sd_quat_rotate(q, w->verts[sh->vstart + k]).z);
    /* mass and I_yy of the given frame's y axis (world y) */
    sd_mat3 rg = sd_quat_to_mat3(sh->given_q);
    g_mass = RHO * (double)sh->volume;
    g_iyy = 0;
    for (int k = 0; k < 3; ++k) {
        double c = (double)rg.m[1][k];
        double ik = k == 0 ? (double)sh->inertia.x : (k == 1 ? (double)sh->inertia.y : (double)sh->inertia.z);
        g_iyy += c * c * ik * RHO;
    }
    sd_body_def b;
    memset(&b, 0, sizeof b);
    b.orientation[0] = q.w;
    b.orientation[1] = q.x;
    b.orientation[2] = q.y;
    b.orientation[3] = q.z;
    b.position = sd_test_v(0, 0, -low + 1e-7);
    b.velocity = sd_test_v(0, 0, -V0);
    b.shape = s;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err);
    g_rec_dt = sd_world_recommended_dt(w, &g_tc);
    int touched = 0;
    for (int k = 0; k < 400000; ++k) {
        sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
        sd_stats st;
        sd_world_stats(w, &st);
        if (st.wall_contacts > 0)
            touched = 1;
        else if (touched)
            break;
    }
    sd_particle_state p;
    sd_world_get_particle(w, 0, &p);
    sd_world_destroy(w);
    outcome o = {p.velocity.z, p.angular_velocity.y};
    return o;
}

static outcome analytic(double theta)
{
    double h = 0.5 * L, r = 0.5 * D;
    double rx = r * cos(theta) - h * sin(theta);
    double j = (1 + EN) * g_mass * V0 / (1 + g_mass * rx * rx / g_iyy);
    outcome o;
    o.wy = -rx * j / g_iyy;
    o.vz = j / g_mass - V0;
    return o;
}

int main(void)
{
    const double PI = 3.14159265358979323846;
    outcome sim[19];
    /* 0 and 90 deg land a face flat: that contact is so stiff (F ~ d^(1/3))
     * that it lasts ~0.25 us, less than Table 1's step; those two use 5 ns */
    for (int k = 0; k <= 18; ++k)
        sim[k] = simulate(k * 5 * PI / 180.0, (k == 0 || k == 18) ? 5e-9 : 5e-7);
    printf("polyhedral cylinder: mass %.6e kg, I_yy %.6e kg m^2 (Table 1: 2.047e-9)\n", g_mass, g_iyy);
    printf("shapedem's estimate: shortest contact %.3e s (a face landing flat), recommended dt %.3e s\n", g_tc,
           g_rec_dt);
    double wmax = 0;
    for (int deg = 0; deg <= 90; ++deg)
        wmax = fmax(wmax, fabs(analytic(deg * PI / 180.0).wy));
    const char *dir = getenv("SD_VALIDATION_OUT");
    FILE *f = NULL;
    if (dir) {
        char path[1024];
        snprintf(path, sizeof path, "%s/poly_cylinder_impact.csv", dir);
        f = fopen(path, "w");
        if (f)
            fprintf(f, "theta_deg,vz_analytic,vz_computed,wy_analytic,wy_computed\n");
    }
    printf("theta  Vz+ analytic  Vz+ computed  err/V %%  wy+ analytic  wy+ computed  err/wmax %%\n");
    for (int k = 0; k <= 18; ++k) {
        int deg = 5 * k;
        outcome a = analytic(deg * PI / 180.0), c = sim[k];
        printf("%5d  %12.6f  %12.6f  %7.2f  %12.4f  %12.4f  %7.2f\n", deg, a.vz, c.vz, 100 * fabs(c.vz - a.vz) / V0,
               a.wy, c.wy, 100 * fabs(c.wy - a.wy) / wmax);
        if (f)
            fprintf(f, "%d,%.9g,%.9g,%.9g,%.9g\n", deg, a.vz, c.vz, a.wy, c.wy);
        if (deg >= 10 && deg <= 80) {
            char label[64];
            snprintf(label, sizeof label, "theta %2d deg: Vz+ (m/s)", deg);
            double tol = deg <= 75 ? 0.03 : 0.04;
            CHECK_NEAR(label, c.vz, a.vz, tol * V0);
            snprintf(label, sizeof label, "theta %2d deg: wy+ (rad/s)", deg);
            CHECK_NEAR(label, c.wy, a.wy, tol * wmax);
        }
    }
    if (f)
        fclose(f);
    return sd_test_summary();
}
