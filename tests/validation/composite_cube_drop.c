/* composite_cube_drop.c — seed 004 §3.3 (Table 3, Fig. 12): a cube of edge
 * 2 mm and the same cube glued from 8 cubes of edge 1 mm (no overlap,
 * exact mass properties), dropped from a centre height of 0.08 m onto a
 * flat wall under gravity, e_n = 0.9, mu = 0, k_n = 1e5 N/m, dt = 2e-6 s,
 * model B (seed 004 eq. 21). Density 1250 kg/m^3: mass 1e-5 kg, so the
 * contact duration of Table 3 (T_c = 3.15e-5 s).
 *
 * For the initial angles (theta_x, theta_y) = (10, 10), (25, 25) and
 * (75, 75) deg the heights of the two agree within 1 % of the drop height
 * through the first impact and up to the apex of the first rebound (seed
 * 004: "quasi-perfect agreement"); at (0, 0) the face lands flat, the 4
 * bottom elements' contacts cancel their torques and the glued cube does
 * not turn (|omega| below 1e-9 rad/s after the impact).
 */
#include <string.h>

#include "test.h"

static const double PI = 3.14159265358979323846;
static const double A = 2e-3, RHO = 1250, KN = 1e5, E = 0.9, H0 = 0.08, DT = 2e-6;

static sd_world *make(double tx, double ty, int glued)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.law = SD_LAW_LINEAR;
    d.dt = DT;
    d.gravity = sd_test_v(0, 0, -9.81);
    d.threads = 1;
    d.multi_contact = SD_MULTI_CONTACT_AVERAGE;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.density = RHO;
    m.stiffness = KN;
    m.restitution = E;
    m.friction = 0;
    int mat = sd_world_add_material(w, &m, &err);
    sd_shape_desc s = sd_shape_desc_default();
    s.kind = "box";
    int shape;
    if (!glued) {
        s.size = sd_test_v(A, A, A);
        shape = sd_world_add_shape(w, "cube", &s, &err);
    } else {
        s.size = sd_test_v(0.5 * A, 0.5 * A, 0.5 * A);
        int small = sd_world_add_shape(w, "cubelet", &s, &err);
        sd_test_require(small >= 0, "cubelet", &err);
        sd_composite_element el[8];
        for (int k = 0; k < 8; ++k) {
            memset(&el[k], 0, sizeof el[k]);
            el[k].shape = small;
            el[k].position = sd_test_v((k & 1 ? 0.25 : -0.25) * A, (k & 2 ? 0.25 : -0.25) * A, (k & 4 ? 0.25 : -0.25) * A);
        }
        sd_composite_desc cd = sd_composite_desc_default();
        cd.elements = el;
        cd.element_count = 8;
        shape = sd_world_add_composite(w, "glued cube", &cd, &err);
    }
    sd_test_require(shape >= 0, "shape", &err);
    sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err);
    sd_body_def b;
    memset(&b, 0, sizeof b);
    /* turned by theta_x about x, then by theta_y about y: q = q_y q_x */
    double cx = cos(0.5 * tx), sx = sin(0.5 * tx), cy = cos(0.5 * ty), sy = sin(0.5 * ty);
    b.orientation[0] = cy * cx;
    b.orientation[1] = cy * sx;
    b.orientation[2] = sy * cx;
    b.orientation[3] = -sy * sx;
    b.position = sd_test_v(0, 0, H0);
    b.shape = shape;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    return w;
}

int main(void)
{
    static const double angles[4][2] = {{0, 0}, {10, 10}, {25, 25}, {75, 75}};
    printf("(tx, ty) deg   max |z_true - z_glued| m   of H0   apex true m   apex glued m   |w| true   |w| glued\n");
    for (int c = 0; c < 4; ++c) {
        double tx = angles[c][0] * PI / 180, ty = angles[c][1] * PI / 180;
        sd_world *wt = make(tx, ty, 0), *wg = make(tx, ty, 1);
        sd_error err;
        double dz = 0, apex_t = 0, apex_g = 0;
        int bounced_t = 0, bounced_g = 0, done = 0;
        sd_particle_state pt, pg;
        /* samples every 50 steps (0.1 ms), until both have passed the apex
         * of their first rebound */
        for (int k = 0; k < 4000 && !done; ++k) {
            sd_test_require(sd_world_step(wt, 50, &err) == SD_OK, "step", &err);
            sd_test_require(sd_world_step(wg, 50, &err) == SD_OK, "step", &err);
            sd_world_get_particle(wt, 0, &pt);
            sd_world_get_particle(wg, 0, &pg);
            dz = fmax(dz, fabs(pt.position.z - pg.position.z));
            bounced_t |= pt.velocity.z > 0;
            bounced_g |= pg.velocity.z > 0;
            if (bounced_t)
                apex_t = fmax(apex_t, pt.position.z);
            if (bounced_g)
                apex_g = fmax(apex_g, pg.position.z);
            done = bounced_t && bounced_g && pt.velocity.z < 0 && pg.velocity.z < 0;
        }
        double wt_n = sqrt(pt.angular_velocity.x * pt.angular_velocity.x + pt.angular_velocity.y * pt.angular_velocity.y +
                           pt.angular_velocity.z * pt.angular_velocity.z);
        double wg_n = sqrt(pg.angular_velocity.x * pg.angular_velocity.x + pg.angular_velocity.y * pg.angular_velocity.y +
                           pg.angular_velocity.z * pg.angular_velocity.z);
        printf("(%2.0f, %2.0f)        %12.4e           %6.3f%%   %10.6f   %10.6f   %9.3e  %9.3e\n", angles[c][0],
               angles[c][1], dz, 100 * dz / H0, apex_t, apex_g, wt_n, wg_n);
        char label[96];
        CHECK(done);
        snprintf(label, sizeof label, "(%2.0f, %2.0f) deg: heights agree within 1 %% of H0 (m)", angles[c][0],
                 angles[c][1]);
        CHECK_NEAR(label, dz, 0.0, 0.01 * H0);
        snprintf(label, sizeof label, "(%2.0f, %2.0f) deg: rebound apex as the true cube's (m)", angles[c][0],
                 angles[c][1]);
        CHECK_NEAR(label, apex_g, apex_t, 0.01 * H0);
        if (c == 0)
            CHECK_NEAR("(0, 0) deg: glued cube's spin after the impact (rad/s)", wg_n, 0.0, 1e-9);
        sd_world_destroy(wt);
        sd_world_destroy(wg);
    }
    return sd_test_summary();
}
