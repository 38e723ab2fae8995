/* grid_seed001.c — seed 001 §3.3 single-particle validation, run on the
 * grid solver (solver grid) with the seed's Set I: R = 0.05 m,
 * rho = 2700 kg/m^3, k = 50,000 N/m, eta = 0.5 N s/m, mu = 0.5 (particle and
 * surface alike), dt = 1e-3 s, g = 9.8 m/s^2. The floor is the zmin face of
 * the grid's domain box.
 *
 *  1. free fall from 0.95 m without damping: the sphere comes back to 0.95 m
 *     (0.5 %);
 *  2. free fall with damping: the height history matches the analytic one
 *     (free flight, then the damped linear oscillator of seed 001 eq. 6 under
 *     gravity during each contact, solved in closed form), over 3 s
 *     (max error 0.5 % of the drop height);
 *  3. sliding at sqrt(2) m/s with the rotation locked (the seed's test): the
 *     sphere stops after v0^2 / (2 mu g) = 0.204 m (1 %); free to roll, it
 *     leaves slip at 5/7 of v0 and rolls (w R = v) (1 %, averaged over the
 *     ringing of the soft tangential spring).
 */
#include <string.h>

#include "test.h"

#include "world/world.h"

static const double R = 0.05, RHO = 2700, K = 50000, ETA = 0.5, MU = 0.5, G = 9.8, DT = 1e-3;
static const double PI = 3.14159265358979323846;

static sd_world *make(double eta, double restitution, sd_v3d x, sd_v3d v)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dt = DT;
    d.law = SD_LAW_LINEAR;
    d.gravity = sd_test_v(0, 0, -G);
    d.solver = SD_SOLVER_GRID;
    d.threads = 1;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "set1";
    m.density = RHO;
    m.stiffness = K;
    m.damping = eta;
    m.restitution = restitution;
    m.tangential_stiffness_ratio = 1;
    m.friction = MU;
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    sd_test_require(sd_world_add_box(w, "box", sd_test_v(-1, -1, 0), sd_test_v(1, 1, 2), 0, mat, &err) >= 0, "box",
                    &err);
    sd_sphere_def s;
    memset(&s, 0, sizeof s);
    s.position = x;
    s.velocity = v;
    s.radius = R;
    s.material = mat;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    return w;
}

static sd_particle_state state(sd_world *w)
{
    sd_particle_state p;
    sd_world_get_particle(w, 0, &p);
    return p;
}

/* Analytic height of the centre: u = z - R; flight u'' = -g; contact (u < 0)
 * m u'' = -m g - k u - eta u' (seed 001 eq. 6 against a rigid floor). */
typedef struct bounce {
    double m, t0, u0, v0; /* current phase starts at t0 with u0, v0 */
    int contact;
} bounce;

static void contact_state(const bounce *b, double t, double *u, double *v)
{
    double m = b->m, wn = sqrt(K / m), zeta = ETA / (2.0 * sqrt(K * m)), wd = wn * sqrt(1 - zeta * zeta);
    double ueq = -m * G / K, a = b->u0 - ueq, c = (b->v0 + zeta * wn * a) / wd, s = t - b->t0;
    double e = exp(-zeta * wn * s);
    *u = ueq + e * (a * cos(wd * s) + c * sin(wd * s));
    *v = e * (-zeta * wn * (a * cos(wd * s) + c * sin(wd * s)) + (-a * wd * sin(wd * s) + c * wd * cos(wd * s)));
}

/* Height at time t, advancing the phases of b monotonically. */
static double analytic_z(bounce *b, double t)
{
    for (;;) {
        if (!b->contact) {
            /* lands when u0 + v0 s - g s^2/2 = 0 */
            double s_land = (b->v0 + sqrt(b->v0 * b->v0 + 2 * G * b->u0)) / G;
            if (t < b->t0 + s_land) {
                double s = t - b->t0;
                return R + b->u0 + b->v0 * s - 0.5 * G * s * s;
            }
            b->v0 = b->v0 - G * s_land;
            b->u0 = 0;
            b->t0 += s_land;
            b->contact = 1;
            continue;
        }
        /* leaves when u returns to 0 from below: bisection on a bracket */
        double lo = 1e-9, hi = lo, u, v;
        do {
            hi += 1e-4;
            contact_state(b, b->t0 + hi, &u, &v);
        } while (u < 0 && hi < 1.0);
        for (int it = 0; it < 100; ++it) {
            double mid = 0.5 * (lo + hi);
            contact_state(b, b->t0 + mid, &u, &v);
            if (u < 0)
                lo = mid;
            else
                hi = mid;
        }
        if (t < b->t0 + hi) {
            contact_state(b, t, &u, &v);
            return R + u;
        }
        contact_state(b, b->t0 + hi, &u, &v);
        b->t0 += hi;
        b->u0 = 0;
        b->v0 = v;
        b->contact = 0;
    }
}

int main(void)
{
    sd_error err;
    /* 1. no damping: back to the release height */
    {
        sd_world *w = make(0.0, 1.0, sd_test_v(0, 0, 0.95), sd_test_v(0, 0, 0));
        double zmax = 0;
        int hit = 0;
        for (int k = 0; k < 1500; ++k) {
            sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
            sd_particle_state p = state(w);
            hit |= p.position.z < R;
            if (hit && p.position.z > zmax)
                zmax = p.position.z;
        }
        CHECK_REL("grid, no damping: apex after the bounce (m)", zmax, 0.95, 0.005);
        sd_world_destroy(w);
    }
    /* 2. damping eta = 0.5: height history against the analytic one */
    {
        sd_world *w = make(ETA, 0.5, sd_test_v(0, 0, 0.95), sd_test_v(0, 0, 0));
        bounce b = {RHO * 4.0 / 3.0 * PI * R * R * R, 0.0, 0.95 - R, 0.0, 0};
        double err_max = 0, zmin_an = 1;
        for (int k = 1; k <= 3000; ++k) {
            sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
            double za = analytic_z(&b, k * DT);
            err_max = fmax(err_max, fabs(state(w).position.z - za));
            zmin_an = fmin(zmin_an, za);
        }
        printf("damped bounce: analytic lowest centre %.6f m (static overlap %.3g m)\n", zmin_an,
               b.m * G / K);
        CHECK_NEAR("grid, eta=0.5: max |z - z_analytic| over 3 s (m)", err_max, 0.0, 0.005 * 0.95);
        sd_world_destroy(w);
    }
    /* 3. sliding: rotation locked, then free */
    {
        double mass = RHO * 4.0 / 3.0 * PI * R * R * R, d0 = mass * G / K;
        const double v0 = sqrt(2.0);
        sd_world *w = make(ETA, 0.5, sd_test_v(-0.5, 0, R - d0), sd_test_v(v0, 0, 0));
        w->p.inv_inertia[0] = sd_v3(0, 0, 0); /* no rotation: the seed's sliding body */
        sd_test_require(sd_world_step(w, 450, &err) == SD_OK, "slide", &err);
        double x450 = state(w).position.x;
        sd_test_require(sd_world_step(w, 150, &err) == SD_OK, "slide", &err);
        sd_particle_state p = state(w);
        CHECK_REL("grid, locked rotation: sliding distance (m)", p.position.x + 0.5, v0 * v0 / (2 * MU * G), 0.01);
        /* at rest it still rings on the tangential spring (eta = 0.5 damps
         * it slowly): +-0.15 mm, so "stopped" means it no longer advances */
        CHECK_NEAR("grid, locked rotation: advance from 0.45 s to 0.6 s (m)", p.position.x - x450, 0.0, 5e-4);
        sd_world_destroy(w);

        /* free to roll: slip ends at t* = 2 v0 / (7 mu g) = 0.08 s; averaged
         * over 0.2-0.5 s, beyond the ringing of the soft spring */
        w = make(ETA, 0.5, sd_test_v(-0.5, 0, R - d0), sd_test_v(v0, 0, 0));
        sd_test_require(sd_world_step(w, 200, &err) == SD_OK, "roll", &err);
        double vsum = 0, wsum = 0;
        for (int k = 0; k < 300; ++k) {
            sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "roll", &err);
            p = state(w);
            vsum += p.velocity.x;
            wsum += p.angular_velocity.y * R;
        }
        CHECK_REL("grid, free sphere: mean speed once rolling (m/s)", vsum / 300, 5.0 / 7.0 * v0, 0.01);
        CHECK_REL("grid, free sphere: mean w R / v once rolling", wsum / vsum, 1.0, 0.01);
        sd_world_destroy(w);
    }
    return sd_test_summary();
}
