/* poly_drop.c — a regular dodecahedron dropped face-down on a plane under
 * the volume law (seed 000 eqs. 12-20; contact/law_volume.h).
 *
 * 1. Restitution: no gravity, the body meets the plane face-down at speed
 *    v0; the rebound speed over v0 must equal the set e_n within 2 % (the
 *    issue's tolerance) at v0 = 1 m/s, for e_n = 0.5 and 0.85. The table
 *    also shows e against the impact speed (0.1 .. 3 m/s): the damping is
 *    calibrated for the face contact's force-depth exponent p = 1/3, which a
 *    dodecahedron's face contact follows only while its cross-section is
 *    the face itself, so e drifts with speed as the contact widens. With
 *    the face flat the contact point is the face centre: no spin (algorithms
 *    §H 23) — asserted.
 * 2. Rest: with gravity and friction, dropped from 3 mm tilted by 15 deg, it
 *    bounces and comes to rest on a face: a face normal within 1e-3 rad of
 *    -z, speed below 1e-4 m/s, at the recommended step (which resolves the
 *    stiff face contact resting under the body's weight).
 */
#include "poly_common.h"

static const double R = 0.01, RHO = 2500, E = 1e6;

typedef struct drop {
    double e, spin, vt;
} drop;

static drop restitution(double en, double v0)
{
    int mat;
    sd_world *w = poly_world(SD_LAW_VOLUME, 5e-7, sd_test_v(0, 0, 0), E, en, 0.3, RHO, 1, &mat);
    sd_v3d v[20];
    poly_dodecahedron(R, v);
    int s = poly_add_shape(w, "dodecahedron", v, 20);
    sd_error err;
    sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err);
    sd_body_def b;
    memset(&b, 0, sizeof b);
    poly_face_towards(w, s, 0, sd_v3(0, 0, -1), b.orientation);
    double h = (double)w->planes[w->shapes[s].fstart].h;
    b.position = sd_test_v(0, 0, h + 1e-6);
    b.velocity = sd_test_v(0, 0, -v0);
    b.shape = s;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    int touched = 0;
    for (int k = 0; k < 200000; ++k) {
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
    drop d;
    d.e = p.velocity.z / v0;
    d.spin = sqrt(p.angular_velocity.x * p.angular_velocity.x + p.angular_velocity.y * p.angular_velocity.y +
                  p.angular_velocity.z * p.angular_velocity.z);
    d.vt = sqrt(p.velocity.x * p.velocity.x + p.velocity.y * p.velocity.y);
    return d;
}

static void rest(void)
{
    int mat;
    sd_world *w = poly_world(SD_LAW_VOLUME, 2e-6, sd_test_v(0, 0, -9.81), E, 0.5, 0.5, RHO, 1, &mat);
    sd_v3d v[20];
    poly_dodecahedron(R, v);
    int s = poly_add_shape(w, "dodecahedron", v, 20);
    sd_error err;
    sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err);
    sd_body_def b;
    memset(&b, 0, sizeof b);
    double q[4];
    poly_face_towards(w, s, 0, sd_v3(0, 0, -1), q);
    sd_quat tilt = sd_quat_from_rotvec(sd_v3(SD_R(15.0) * SD_PI / SD_R(180.0), 0, 0));
    sd_quat qb = sd_quat_mul(tilt, sd_quat_make(q[0], q[1], q[2], q[3]));
    b.orientation[0] = qb.w;
    b.orientation[1] = qb.x;
    b.orientation[2] = qb.y;
    b.orientation[3] = qb.z;
    b.position = sd_test_v(0, 0, R + 3e-3);
    b.shape = s;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    /* the recommended step: it resolves the face contact resting under the
     * body's weight (docs/physics.md; with the impact-only step, 2 us here,
     * the resting contact buzzes at ~4e-4 m/s instead of settling) */
    sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err);
    double tc, rec = sd_world_recommended_dt(w, &tc);
    w->dt = (sd_real)rec;
    w->def.dt = rec;
    printf("rest: recommended dt %.3e s (shortest impact %.3e s)\n", rec, tc);
    double t_end = 0;
    sd_particle_state p;
    long chunk = (long)(0.002 / rec) + 1;
    for (int k = 0; k < 400; ++k) { /* up to 0.8 s */
        sd_test_require(sd_world_step(w, chunk, &err) == SD_OK, "step", &err);
        sd_world_get_particle(w, 0, &p);
        double speed = sqrt(p.velocity.x * p.velocity.x + p.velocity.y * p.velocity.y + p.velocity.z * p.velocity.z);
        double spin = sqrt(p.angular_velocity.x * p.angular_velocity.x + p.angular_velocity.y * p.angular_velocity.y +
                           p.angular_velocity.z * p.angular_velocity.z);
        t_end = sd_world_time(w);
        if (getenv("SD_DEBUG_REST")) printf("t %.4f z %.6f speed %.3e spin %.3e\n", t_end, p.position.z, speed, spin);
        if (t_end > 0.1 && speed < 1e-5 && spin * R < 1e-5)
            break;
    }
    sd_world_get_particle(w, 0, &p);
    sd_quat qp = sd_quat_make(p.quat[0], p.quat[1], p.quat[2], p.quat[3]);
    double best = -2;
    const sd_shape *sh = &w->shapes[s];
    for (uint32_t f = 0; f < sh->fcount; ++f)
        best = fmax(best, -(double)sd_quat_rotate(qp, w->planes[sh->fstart + f].n).z);
    double speed = sqrt(p.velocity.x * p.velocity.x + p.velocity.y * p.velocity.y + p.velocity.z * p.velocity.z);
    printf("rest: after %.3f s, height %.6f m (face offset %.6f m), speed %.2e m/s\n", t_end, p.position.z,
           (double)w->planes[sh->fstart].h, speed);
    CHECK_NEAR("rest: angle of the lowest face to the floor (rad)", acos(fmin(1.0, best)), 0.0, 1e-3);
    CHECK_NEAR("rest: speed (m/s)", speed, 0.0, 1e-4);
    CHECK_NEAR("rest: centre height / face offset", p.position.z / (double)w->planes[sh->fstart].h, 1.0, 1e-3);
    sd_world_destroy(w);
}

int main(void)
{
    const double es[2] = {0.5, 0.85}, speeds[4] = {0.1, 0.3, 1.0, 3.0};
    printf("e_n set  v0 (m/s)  e measured  error %%   |w| after (rad/s)\n");
    for (int a = 0; a < 2; ++a)
        for (int k = 0; k < 4; ++k) {
            drop d = restitution(es[a], speeds[k]);
            printf("%6.2f  %8.2f  %10.5f  %7.3f  %10.2e\n", es[a], speeds[k], d.e, 100 * (d.e - es[a]) / es[a],
                   d.spin);
            if (speeds[k] == 1.0) {
                char label[80];
                snprintf(label, sizeof label, "e_n %.2f at 1 m/s: measured e", es[a]);
                CHECK_REL(label, d.e, es[a], 0.02);
                snprintf(label, sizeof label, "e_n %.2f at 1 m/s: spin after (rad/s)", es[a]);
                CHECK_NEAR(label, d.spin, 0.0, 1e-6);
            }
        }
    rest();
    return sd_test_summary();
}
