/* world2d.c — the planar mode (dimension 2): circle mass properties per unit
 * thickness, circle-circle and circle-wall contacts against the analytic
 * linear law of seed 002 (eqs. 8–10), the state staying in the plane, the
 * local damping of seed 002 §3.2 against its closed form, prescribed and
 * servo-controlled walls, the biaxial state, and the same bits with 1 and
 * 2 threads.
 */
#include <string.h>

#include "test.h"

#include "world/world.h"

static const double PI = 3.14159265358979323846;

/* A 2D world with the seed 002 law: linear, restitution 1 (no dashpot),
 * k_t = k_n, friction mu. */
static sd_world *make_world(double dt, sd_v3d g, double damping, double kn, double mu, int threads, int *mat)
{
    sd_world_def d = sd_world_def_default();
    d.dimension = 2;
    d.dt = dt;
    d.gravity = g;
    d.law = SD_LAW_LINEAR;
    d.local_damping = damping;
    d.threads = threads;
    sd_world *w;
    sd_error err;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "create", &err);
    sd_material_def m = sd_material_def_default();
    m.density = 2700;
    m.stiffness = kn;
    m.tangential_stiffness_ratio = 1.0;
    m.restitution = 1.0;
    m.friction = mu;
    *mat = sd_world_add_material(w, &m, &err);
    sd_test_require(*mat >= 0, "material", &err);
    return w;
}

/* Two circles overlapping by delta along a tilted line, circle 1 sliding
 * past circle 0 at vt; after n steps fills the normal and tangential force
 * on circle 0 (tangential along t = perp(e), e from 0 to 1). */
static void circle_pair(double vt, long n, double *fn, double *ft, double *gap, double *torque, int *planar,
                        double *mass)
{
    int mat;
    const double kn = 1e7, mu = 0.2, dt = 1e-6;
    sd_world *w = make_world(dt, sd_test_v(0, 0, 0), 0, kn, mu, 1, &mat);
    sd_error err;
    const double r1 = 0.02, r2 = 0.03, delta = 1e-4;
    const double c = cos(0.3), s = sin(0.3), dist = r1 + r2 - delta;
    sd_sphere_def sp[2];
    memset(sp, 0, sizeof sp);
    sp[0].position = sd_test_v(0, 0, 0);
    sp[0].radius = r1;
    sp[0].material = mat;
    sp[1].position = sd_test_v(dist * c, dist * s, 0);
    sp[1].radius = r2;
    sp[1].material = mat;
    sp[1].velocity = sd_test_v(-vt * s, vt * c, 0);
    sd_test_require(sd_world_add_spheres(w, 2, sp, &err) == SD_OK, "circles", &err);
    sd_test_require(sd_world_step(w, n, &err) == SD_OK, "step", &err);
    sd_particle_state a, b;
    sd_world_get_particle(w, sd_world_find_particle(w, 0), &a);
    sd_world_get_particle(w, sd_world_find_particle(w, 1), &b);
    double ex = b.position.x - a.position.x, ey = b.position.y - a.position.y, el = hypot(ex, ey);
    ex /= el;
    ey /= el;
    *ft = a.force.x * -ey + a.force.y * ex;
    *fn = -(a.force.x * ex + a.force.y * ey);
    *gap = r1 + r2 - el;
    *torque = a.torque.z;
    *planar = a.position.z == 0 && b.position.z == 0 && a.velocity.z == 0 && a.force.z == 0 &&
              a.angular_velocity.x == 0 && a.angular_velocity.y == 0 && a.torque.x == 0 && a.torque.y == 0;
    *mass = a.mass;
    sd_world_destroy(w);
}

static void test_circle_pair(void)
{
    printf("-- circle-circle contact against the analytic law, seed 002 eqs. 8-10\n");
    const double kn = 1e7, mu = 0.2, dt = 1e-6, r1 = 0.02;
    double fn, ft, gap, torque, mass;
    int planar;
    circle_pair(0.01, 0, &fn, &ft, &gap, &torque, &planar, &mass);
    CHECK_REL("circle mass rho pi r^2 (kg per m)", mass, 2700 * PI * r1 * r1, 1e-14);
    CHECK_REL("F_n = k_n delta at rest (N)", fn, kn * 1e-4, 1e-9);
    long n = 10;
    circle_pair(0.01, n, &fn, &ft, &gap, &torque, &planar, &mass);
    CHECK_REL("F_n = k_n (r1 + r2 - d) after 10 steps (N)", fn, kn * gap, 1e-9);
    /* one increment k_t vt dt per evaluation: the initial one and n steps */
    CHECK_REL("F_t = F_t^0 + k_t dd_t, incremental (eq. 9) (N)", ft, kn * 0.01 * dt * (double)(n + 1), 1e-3);
    /* the contact point sits r1 - delta/2 from circle 0's centre: T = r x F_t */
    CHECK_REL("torque about z = (r1 - delta/2) F_t (N m)", torque, (r1 - 0.5 * gap) * ft, 1e-9);
    CHECK(planar);
    circle_pair(1.0, 200, &fn, &ft, &gap, &torque, &planar, &mass);
    CHECK_REL("sliding: |F_t| = mu F_n (eq. 9 cap) (N)", fabs(ft), mu * fn, 1e-9);
    CHECK(planar);
}

static void test_local_damping(void)
{
    printf("-- local damping (seed 002 3.2): free fall accelerates at g (1 - alpha)\n");
    int mat;
    const double alpha = 0.7, g = 9.8, dt = 1e-4;
    sd_world *w = make_world(dt, sd_test_v(0, -g, 0), alpha, 1e7, 0.2, 1, &mat);
    sd_error err;
    sd_sphere_def sp;
    memset(&sp, 0, sizeof sp);
    sp.radius = 0.02;
    sp.material = mat;
    sp.velocity = sd_test_v(0, -1e-3, 0); /* moving: sign(v) = -1 from the start */
    sp.angular_velocity = sd_test_v(0, 0, 0);
    CHECK(sd_world_add_spheres(w, 1, &sp, &err) == SD_OK);
    long n = 1000;
    CHECK(sd_world_step(w, n, &err) == SD_OK);
    sd_particle_state a;
    sd_world_get_particle(w, 0, &a);
    double t = (double)n * dt;
    CHECK_REL("v(t) = v0 - g (1 - alpha) t", a.velocity.y, -1e-3 - g * (1 - alpha) * t, 1e-12);
    CHECK(a.position.z == 0 && a.velocity.z == 0);
    sd_world_destroy(w);

    /* the same in 3D (per world component), and a sphere on a floor comes to
     * rest there with the floor carrying its weight */
    sd_world_def d = sd_world_def_default();
    d.dt = dt;
    d.gravity = sd_test_v(0, 0, -g);
    d.law = SD_LAW_LINEAR;
    d.local_damping = alpha;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "create 3D", &err);
    sd_material_def m = sd_material_def_default();
    m.stiffness = 1e5;
    m.restitution = 1.0;
    mat = sd_world_add_material(w, &m, &err);
    CHECK(sd_world_add_plane(w, "floor", sd_test_v(0, 0, -0.05), sd_test_v(0, 0, 1), mat, &err) == 0);
    sp.velocity = sd_test_v(0, 0, -1e-3);
    sp.material = mat;
    CHECK(sd_world_add_spheres(w, 1, &sp, &err) == SD_OK);
    CHECK(sd_world_step(w, 100, &err) == SD_OK);
    sd_world_get_particle(w, 0, &a);
    CHECK_REL("3D: v(t) = v0 - g (1 - alpha) t", a.velocity.z, -1e-3 - g * (1 - alpha) * 100 * dt, 1e-12);
    CHECK(sd_world_step(w, 20000, &err) == SD_OK);
    sd_world_get_particle(w, 0, &a);
    sd_wall_info wi;
    sd_world_get_wall(w, 0, &wi);
    CHECK_REL("3D: at rest, the floor carries m g (N)", -wi.force.z, a.mass * g, 1e-6);
    CHECK_NEAR("3D: at rest (m/s)", a.velocity.z, 0, 1e-6);
    sd_world_destroy(w);
}

/* Four plane walls around [0, W] x [0, H]; returns the index of the first. */
static void add_box(sd_world *w, double W, double H, int mat, int idx[4])
{
    sd_error err;
    idx[0] = sd_world_add_plane(w, "left", sd_test_v(0, 0, 0), sd_test_v(1, 0, 0), mat, &err);
    idx[1] = sd_world_add_plane(w, "right", sd_test_v(W, 0, 0), sd_test_v(-1, 0, 0), mat, &err);
    idx[2] = sd_world_add_plane(w, "bottom", sd_test_v(0, 0, 0), sd_test_v(0, 1, 0), mat, &err);
    idx[3] = sd_world_add_plane(w, "top", sd_test_v(0, H, 0), sd_test_v(0, -1, 0), mat, &err);
    sd_test_require(idx[0] >= 0 && idx[1] >= 0 && idx[2] >= 0 && idx[3] >= 0, "walls", &err);
}

static void test_servo(void)
{
    printf("-- servo wall: the stress it carries tracks the target\n");
    int mat;
    const double kn = 1e7, dt = 1e-5, r = 0.05, target = 2e4;
    sd_world *w = make_world(dt, sd_test_v(0, 0, 0), 0.7, kn, 0.2, 1, &mat);
    sd_error err;
    /* one circle in a box 2r wide and 4r tall, squeezed between left and a
     * servo-controlled right wall */
    int idx[4];
    const double H = 4 * r;
    add_box(w, 2 * r + 1e-3, H, mat, idx);
    sd_sphere_def sp;
    memset(&sp, 0, sizeof sp);
    sp.position = sd_test_v(r, 2 * r, 0);
    sp.radius = r;
    sp.material = mat;
    CHECK(sd_world_add_spheres(w, 1, &sp, &err) == SD_OK);
    sd_wall_motion_def m = sd_wall_motion_def_default();
    m.servo_stress = target;
    CHECK(sd_world_set_wall_motion(w, idx[1], &m, &err) == SD_OK);
    CHECK(sd_world_step(w, 20000, &err) == SD_OK);
    sd_wall_info wi;
    sd_world_get_wall(w, (size_t)idx[1], &wi);
    /* the stress is the force over the span between the perpendicular walls */
    CHECK_REL("servo wall stress (Pa)", -wi.force.x * -1.0 / H, target, 1e-3);
    /* equilibrium overlap of the two contacts: F = k delta each */
    CHECK_REL("wall position = 2r - F/k_n", wi.point.x, 2 * r - 2 * target * H / kn, 1e-3);
    sd_biaxial bx;
    CHECK(sd_world_biaxial(w, &bx) == SD_OK);
    CHECK_REL("biaxial sigma_xx (Pa)", bx.sigma_xx, target, 1e-3);

    printf("-- prescribed wall motion\n");
    m = sd_wall_motion_def_default();
    m.velocity = sd_test_v(0, -0.1, 0);
    m.move_start = sd_world_time(w) + 10 * dt;
    CHECK(sd_world_set_wall_motion(w, idx[3], &m, &err) == SD_OK);
    sd_world_get_wall(w, (size_t)idx[3], &wi);
    double y0 = wi.point.y;
    CHECK(sd_world_step(w, 110, &err) == SD_OK);
    sd_world_get_wall(w, (size_t)idx[3], &wi);
    CHECK_NEAR("top wall moved v (t - t_start) (m)", wi.point.y, y0 - 0.1 * 100 * dt, 1e-12);
    CHECK(sd_world_biaxial(w, &bx) == SD_OK);
    CHECK(bx.has_reference);
    CHECK_REL("axial strain from the start of loading", bx.strain_axial, 0.1 * 100 * dt / H, 1e-9);

    /* bad input: servo needs finite values, a plane, a known wall */
    m = sd_wall_motion_def_default();
    m.servo_stress = -1;
    CHECK(sd_world_set_wall_motion(w, idx[0], &m, &err) == SD_ERR_INPUT);
    m.servo_stress = 1;
    CHECK(sd_world_set_wall_motion(w, 17, &m, &err) == SD_ERR_INPUT);
    m.velocity = sd_test_v(0, 0, 1);
    CHECK(sd_world_set_wall_motion(w, idx[0], &m, &err) == SD_ERR_INPUT);
    sd_world_destroy(w);
}

static void test_bad_input(void)
{
    printf("-- planar bad input\n");
    sd_world_def d = sd_world_def_default();
    d.dimension = 2;
    sd_world *w;
    sd_error err;
    d.gravity = sd_test_v(0, -9.8, 1);
    CHECK(sd_world_create(&d, &w, &err) == SD_ERR_INPUT);
    d.gravity = sd_test_v(0, -9.8, 0);
    d.dimension = 4;
    CHECK(sd_world_create(&d, &w, &err) == SD_ERR_INPUT);
    d.dimension = 2;
    d.local_damping = 1.0;
    CHECK(sd_world_create(&d, &w, &err) == SD_ERR_INPUT);
    d.local_damping = 0.7;
    CHECK(sd_world_create(&d, &w, &err) == SD_OK);
    sd_material_def m = sd_material_def_default();
    int mat = sd_world_add_material(w, &m, &err);
    sd_sphere_def sp;
    memset(&sp, 0, sizeof sp);
    sp.radius = 0.01;
    sp.material = mat;
    sp.position = sd_test_v(0, 0, 0.5);
    CHECK(sd_world_add_spheres(w, 1, &sp, &err) == SD_ERR_INPUT);
    CHECK(sd_world_add_plane(w, "p", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err) < 0);
    sd_shape_desc sd = sd_shape_desc_default();
    CHECK(sd_world_add_shape(w, "s", &sd, &err) < 0);
    sd_world_destroy(w);
}

/* A small 2D pile in a box, stepped with 1 and 2 threads: the same bits. */
static void pile_state(int threads, double *out, size_t nout)
{
    int mat;
    sd_world *w = make_world(1e-4, sd_test_v(0, -9.8, 0), 0.7, 1e7, 0.2, threads, &mat);
    sd_error err;
    int idx[4];
    add_box(w, 1.0, 3.0, mat, idx);
    enum { N = 1200 };
    static sd_sphere_def sp[N];
    static sd_body_def bd[N];
    memset(sp, 0, sizeof sp);
    memset(bd, 0, sizeof bd);
    sd_shape2d_def d = sd_shape2d_def_default();
    d.kind = "ellipse";
    d.semi_axes[0] = 0.014;
    d.semi_axes[1] = 0.008;
    int ell = sd_world_add_shape2d(w, "ell", &d, &err);
    sd_test_require(ell >= 0, "ellipse", &err);
    int ns = 0, nb = 0;
    for (int k = 0; k < N; ++k) {
        sd_v3d x = sd_test_v(0.03 + 0.03 * (k % 32) + 0.002 * (k / 32 % 3), 0.03 + 0.06 * (k / 32), 0);
        if (k % 3 == 0) { /* every third an ellipse, turned */
            bd[nb].position = x;
            bd[nb].shape = ell;
            bd[nb].material = mat;
            bd[nb].orientation[0] = cos(0.1 * k);
            bd[nb].orientation[3] = sin(0.1 * k);
            ++nb;
        } else {
            sp[ns].position = x;
            sp[ns].radius = 0.010 + 0.001 * (k % 5);
            sp[ns].material = mat;
            ++ns;
        }
    }
    sd_test_require(sd_world_add_spheres(w, (size_t)ns, sp, &err) == SD_OK, "circles", &err);
    sd_test_require(sd_world_add_bodies(w, (size_t)nb, bd, &err) == SD_OK, "ellipses", &err);
    sd_test_require(sd_world_step(w, 1500, &err) == SD_OK, "step", &err);
    for (size_t k = 0; k < nout / 3 && k < N; ++k) {
        sd_particle_state s;
        sd_world_get_particle(w, sd_world_find_particle(w, k), &s);
        out[3 * k] = s.position.x;
        out[3 * k + 1] = s.position.y;
        out[3 * k + 2] = s.angular_velocity.z + s.position.z;
    }
    sd_world_destroy(w);
}

static void test_threads(void)
{
    printf("-- 1 and 2 threads give the same bits (800 circles, 400 ellipses)\n");
    static double a[3600], b[3600];
    pile_state(1, a, 3600);
    pile_state(2, b, 3600);
    CHECK(memcmp(a, b, sizeof a) == 0);
}

/* 2D shapes through the engine: two ellipses pressed tip to tip (the 2D
 * GJK/EPA depth along their common axis), an ellipse and a polygon resting
 * on a floor line (support point along the wall normal), and the narrow
 * statistics per pair type. */
static void test_shapes(void)
{
    printf("-- 2D shapes: ellipse pair, shapes on a floor\n");
    int mat;
    const double kn = 1e7, g = 9.8;
    sd_world *w = make_world(1e-4, sd_test_v(0, 0, 0), 0, kn, 0.2, 1, &mat);
    sd_error err;
    sd_shape2d_def d = sd_shape2d_def_default();
    d.kind = "ellipse";
    d.semi_axes[0] = 0.03;
    d.semi_axes[1] = 0.015;
    int ell = sd_world_add_shape2d(w, "ell", &d, &err);
    CHECK(ell == 0);
    sd_shape_info info;
    CHECK(sd_world_get_shape(w, (size_t)ell, &info) == SD_OK);
    CHECK_REL("ellipse area pi a b (m^2)", info.volume, PI * 0.03 * 0.015, 1e-12);
    sd_body_def b[2];
    memset(b, 0, sizeof b);
    const double delta = 1e-4;
    b[0].shape = b[1].shape = ell;
    b[0].material = b[1].material = mat;
    b[1].position = sd_test_v(0.06 - delta, 0, 0);
    CHECK(sd_world_add_bodies(w, 2, b, &err) == SD_OK);
    sd_particle_state a;
    sd_world_get_particle(w, 0, &a);
    CHECK_REL("ellipse mass rho pi a b (kg per m)", a.mass, 2700 * PI * 0.03 * 0.015, 1e-12);
    CHECK(sd_world_prepare(w, &err) == SD_OK);
    sd_world_get_particle(w, sd_world_find_particle(w, 0), &a);
    CHECK_REL("ellipses tip to tip: F = k_n delta (N)", -a.force.x, kn * delta, 1e-6);
    CHECK_NEAR("ellipses tip to tip: no sideways force (N)", a.force.y, 0, 1e-4 * kn * delta);
    sd_narrow_stats ns[4];
    CHECK(sd_world_narrow_stats(w, ns, 4) == 1 && !strcmp(ns[0].kind_a, "ellipse") && ns[0].contacts == 1);
    sd_world_destroy(w);

    /* resting on a floor under gravity with local damping: overlap m g / k */
    w = make_world(1e-4, sd_test_v(0, -g, 0), 0.7, kn, 0.2, 1, &mat);
    ell = sd_world_add_shape2d(w, "ell", &d, &err);
    d = sd_shape2d_def_default();
    d.kind = "polygon";
    const double sq[8] = {-0.02, -0.01, 0.02, -0.01, 0.02, 0.01, -0.02, 0.01};
    d.points = sq;
    d.point_count = 4;
    int box = sd_world_add_shape2d(w, "box", &d, &err);
    CHECK(box == 1);
    CHECK(sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 1, 0), mat, &err) == 0);
    memset(b, 0, sizeof b);
    b[0].shape = ell;
    b[1].shape = box;
    b[0].material = b[1].material = mat;
    b[0].position = sd_test_v(0, 0.0151, 0);
    b[1].position = sd_test_v(0.1, 0.0101, 0);
    CHECK(sd_world_add_bodies(w, 2, b, &err) == SD_OK);
    CHECK(sd_world_step(w, 5000, &err) == SD_OK);
    double m_e = 2700 * PI * 0.03 * 0.015, m_b = 2700 * 0.04 * 0.02;
    sd_particle_state e0, e1;
    sd_world_get_particle(w, sd_world_find_particle(w, 0), &e0);
    sd_world_get_particle(w, sd_world_find_particle(w, 1), &e1);
    CHECK_REL("ellipse on the floor: centre at b - m g / k (m)", e0.position.y, 0.015 - m_e * g / kn, 1e-6);
    CHECK_REL("rectangle on the floor: centre at h/2 - m g / k (m)", e1.position.y, 0.01 - m_b * g / kn, 1e-6);
    sd_wall_info wi;
    sd_world_get_wall(w, 0, &wi);
    CHECK_REL("floor carries both weights (N)", -wi.force.y, (m_e + m_b) * g, 1e-6);
    sd_world_destroy(w);
}

int main(void)
{
    test_shapes();
    test_circle_pair();
    test_local_damping();
    test_servo();
    test_bad_input();
    test_threads();
    return sd_test_summary();
}
