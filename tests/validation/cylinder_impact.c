/* cylinder_impact.c — a cylinder dropped on a wall at angle theta, against
 * the analytic post-impact velocities of seed 000 eqs. 27–28 and seed 004
 * eqs. 22–23 (Kodam et al.).
 *
 * Table 1 of seed 000 / seed 004: D = 8 mm, L = 5.3 mm, rho = 1245 kg/m^3,
 * k_n = 1e5 N/m, e_n = 0.85, mu = 0, V = 1 m/s towards the wall, no gravity,
 * dt = 5e-6 s. The analytic solution is that of a rigid impact at the rim
 * point: with r_x the horizontal distance from the centre of mass to the
 * contact point (r cos(alpha + theta) in the seeds' notation), the normal
 * impulse J = (1 + e) M V / (1 + M r_x^2 / I_yy) gives
 *     omega_y+ = r_x J / I_yy,  V_z+ = J / M - V          (eqs. 27–28)
 * The true cylinder (sharp support-function shape) is tested; the
 * computed and analytic values are printed for theta = 0..90 deg and
 * asserted within 3 % of their scale for 10..80 deg (see below). With SD_VALIDATION_OUT set, a CSV is
 * written there for docs/validation/cylinder_impact.py.
 *
 * At 0 and 90 deg eqs. 27-28 do not apply, and the test says what does.
 * They assume the impulse acts at one rim point, off the centre of mass
 * by r_x; at 0 deg the whole end face lands (a surface contact), at 90 deg
 * a whole mantle line (a line contact, seed 004 §3.2), and the wall's
 * pressure on a face or line symmetric about the centre has its resultant
 * through the centre: r_x = 0 in eq. 27, J = (1 + e) M V, so V_z+ = e V
 * and omega_y+ = 0 (the formula with the rim point gives V_z+ = -0.47 and
 * -0.12 m/s and |omega_y+| of 330 and 370 rad/s there, printed in the
 * table). Asserted: V_z+ within 0.5 % of e V (seed 004 Fig. 9a; measured
 * 0.14 %, the linear law's time discretisation) and |omega_y+| below 1e-9
 * rad/s; validation.composite_cylinder_impact asserts the same for the
 * glued 10-slice cylinder. Before the plane contact took the midpoint of
 * a mantle line lying on the wall (geom/convex_contact.h) the true
 * cylinder left 90 deg at 0.913 m/s spinning at 17.4 rad/s, which fails
 * both (docs/validation/cylinder_impact.csv as eeb7496 wrote it, before
 * 85aabde; now rewritten).
 */
#include <stdlib.h>
#include <string.h>

#include "test.h"

static const double D = 8e-3, L = 5.3e-3, RHO = 1245, KN = 1e5, E = 0.85, V0 = 1.0;

typedef struct outcome {
    double vz, wy;
} outcome;

static outcome simulate(double theta, const char *kind, double margin)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.law = SD_LAW_LINEAR;
    d.dt = 5e-6;
    d.gravity = sd_test_v(0, 0, 0);
    d.threads = 1;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.density = RHO;
    m.stiffness = KN;
    m.restitution = E;
    m.friction = 0;
    int mat = sd_world_add_material(w, &m, &err);
    sd_shape_desc s = sd_shape_desc_default();
    s.kind = kind;
    s.size = sd_test_v(D, D, L);
    s.margin = margin;
    int shape = sd_world_add_shape(w, "cylinder", &s, &err);
    sd_test_require(shape >= 0, "shape", &err);
    sd_world_add_plane(w, "wall", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err);
    sd_body_def b;
    memset(&b, 0, sizeof b);
    double h = 0.5 * L, r = 0.5 * D;
    /* turn the axis (z) by theta about y; the lowest rim point is then
     * h cos(theta) + r sin(theta) below the centre */
    b.orientation[0] = cos(0.5 * theta);
    b.orientation[2] = sin(0.5 * theta);
    b.position = sd_test_v(0, 0, h * cos(theta) + r * sin(theta) + 1e-7);
    b.velocity = sd_test_v(0, 0, -V0);
    b.shape = shape;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    int touched = 0;
    for (int k = 0; k < 2000; ++k) {
        sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
        sd_stats st;
        sd_world_stats(w, &st);
        if (st.wall_contacts > 0)
            touched = 1;
        else if (touched)
            break; /* the first impact is over */
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
    double mass = RHO * 3.14159265358979323846 * r * r * L;
    double iyy = mass * (3 * r * r + L * L) / 12.0;
    /* contact point relative to the centre: the rim point (r, 0, -h) of the
     * body frame turned by theta about y, whose x is r cos(theta) - h sin(theta);
     * the wall pushes up (+z) */
    double rx = r * cos(theta) - h * sin(theta);
    double j = (1 + E) * mass * V0 / (1 + mass * rx * rx / iyy);
    outcome o;
    /* torque about y of an upward impulse at horizontal offset rx: -rx J */
    o.wy = -rx * j / iyy;
    o.vz = j / mass - V0;
    return o;
}

int main(void)
{
    /* the largest analytic omega+ over the sweep */
    double W_MAX = 0;
    for (int deg = 0; deg <= 90; ++deg)
        W_MAX = fmax(W_MAX, fabs(analytic(deg * 3.14159265358979323846 / 180.0).wy));
    const char *csv = getenv("SD_VALIDATION_OUT");
    FILE *f = NULL;
    if (csv) {
        char path[1024];
        snprintf(path, sizeof path, "%s/cylinder_impact.csv", csv);
        f = fopen(path, "w");
        if (f)
            fprintf(f, "theta_deg,vz_analytic,vz_computed,wy_analytic,wy_computed\n");
    }
    printf("theta  Vz+ analytic  Vz+ computed  err%%   wy+ analytic  wy+ computed  err%%\n");
    for (int deg = 0; deg <= 90; deg += 5) {
        double th = deg * 3.14159265358979323846 / 180.0;
        outcome a = analytic(th), c = simulate(th, "cylinder", 0.0);
        double ev = 100 * fabs(c.vz - a.vz) / fabs(a.vz);
        double ew = fabs(a.wy) > 1e-9 ? 100 * fabs(c.wy - a.wy) / fabs(a.wy) : 0;
        printf("%5d  %12.6f  %12.6f  %5.2f  %12.4f  %12.4f  %5.2f\n", deg, a.vz, c.vz, ev, a.wy, c.wy, ew);
        if (f)
            fprintf(f, "%d,%.9g,%.9g,%.9g,%.9g\n", deg, a.vz, c.vz, a.wy, c.wy);
        if (deg >= 10 && deg <= 80) {
            /* 3 % of each quantity's scale: V_z+ crosses zero near 27 deg and
             * omega+ near 56.5 deg (rim point below the centre), where a
             * relative error means nothing; the scales are the impact speed
             * and the largest analytic omega+ of the sweep. What remains is
             * the cylinder turning by about 2 deg during the 0.11 ms
             * contact, which the instantaneous-impact solution ignores. */
            char label[64];
            snprintf(label, sizeof label, "theta %2d deg: Vz+ (m/s)", deg);
            CHECK_NEAR(label, c.vz, a.vz, 0.03 * V0);
            snprintf(label, sizeof label, "theta %2d deg: wy+ (rad/s)", deg);
            CHECK_NEAR(label, c.wy, a.wy, 0.03 * W_MAX);
        }
        if (deg == 0 || deg == 90) {
            /* a face (0) or a line (90) lands flat: V_z+ = e V, no spin (above) */
            char label[64];
            snprintf(label, sizeof label, "theta %2d deg, flat: Vz+ = e V (m/s)", deg);
            CHECK_REL(label, c.vz, E * V0, 0.005);
            snprintf(label, sizeof label, "theta %2d deg, flat: |wy+| (rad/s)", deg);
            CHECK_NEAR(label, fabs(c.wy), 0.0, 1e-9);
        }
    }
    if (f)
        fclose(f);
    return sd_test_summary();
}
