/* composite_cylinder_impact.c — seed 004 §3.2 (Table 1, Figs. 7-9): a
 * cylinder sliced into N equal glued slices (a composite of N cylinder
 * elements) hits a flat wall, no gravity, mu = 0.
 *
 * Table 1: D = 8 mm, L = 5.3 mm, rho = 1245 kg/m^3 (mass 3.1e-4 kg),
 * k_n = 1e5 N/m, e_n = 0.85, V = 1 m/s towards the wall, dt = 5e-6 s.
 *
 *  1. theta = 90 deg (axis parallel to the wall, a line contact, N contact
 *     points): the analytic post-impact velocities (seed 004 eqs. 22-23)
 *     are V_z+ = e_n V and omega_y+ = 0. A cylinder's support point on a
 *     line contact is one end of the line (a tie broken by rounding);
 *     seed 004 (Fig. 9b) sees the spurious spin of such a point fall like
 *     1/N as the slices spread their points along the line. Here the
 *     plane contact takes the midpoint of a mantle line lying within
 *     1e-9 L of the wall (geom/convex_contact.h), so every slice pushes at
 *     its own centre: with model B (average, eq. 21) V_z+ is within seed
 *     004's 0.5 % (Fig. 9a) for every N = 1..30 (0.14 %, the linear law's
 *     time discretisation at 36 steps per contact; before the midpoint,
 *     7.4 % at N = 1 and 0.5 % at N = 5, the lever arm of one end), and
 *     |omega_y+| stays at rounding level (below 1e-9 rad/s against the
 *     360 rad/s of the oblique impacts) for every N. Model B's contact
 *     duration and peak force do not depend on N (Fig. 8b, eq. 20);
 *     model A's duration falls like 1/sqrt(N) (eq. 19), so at a fixed dt
 *     its impacts are resolved by fewer and fewer steps (6 at N = 30): its
 *     V_z+ is printed only.
 *  2. theta = 0..90 deg: the true cylinder and the 10-slice composite
 *     agree (Fig. 7): printed, and asserted within 1 % of the impact
 *     speed (V_z+) and of the largest omega of the sweep for 10..80 deg.
 *     At 0 and 90 deg a face or a line lands flat, where eqs. 22-23's
 *     single rim point does not apply (validation.cylinder_impact says
 *     why): both rebound at e_n V within 0.5 % without spin (1e-9 rad/s).
 *  3. glued-sphere cylinders of 9 and 54 spheres (Fig. 10, Table 2: the
 *     spheres9 and spheres54 presets): run and their deviation from the
 *     true cylinder printed, not asserted
 *     (seed 004 finds them "markedly off" away from 0 and 90 deg).
 */
#include <stdlib.h>
#include <string.h>

#include "test.h"

static const double PI = 3.14159265358979323846;
static const double D = 8e-3, L = 5.3e-3, RHO = 1245, KN = 1e5, E = 0.85, V0 = 1.0, DT = 5e-6;

typedef struct outcome {
    double vz, wy;
    double duration; /* s, steps with a wall contact times dt */
    double fmax;     /* N, largest wall force during the impact */
} outcome;

typedef struct model {
    const char *kind;   /* "true": one cylinder; "slices": N glued slices; "spheres": glued spheres */
    int n;              /* slices, or spheres (9 or 54) */
    int multi_contact;  /* SD_MULTI_CONTACT_* */
} model;

static outcome simulate(double theta, model md)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.law = SD_LAW_LINEAR;
    d.dt = DT;
    d.gravity = sd_test_v(0, 0, 0);
    d.threads = 1;
    d.multi_contact = md.multi_contact;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.density = RHO;
    m.stiffness = KN;
    m.restitution = E;
    m.friction = 0;
    int mat = sd_world_add_material(w, &m, &err);
    int shape = -1;
    sd_shape_desc s = sd_shape_desc_default();
    if (!strcmp(md.kind, "true")) {
        s.kind = "cylinder";
        s.size = sd_test_v(D, D, L);
        shape = sd_world_add_shape(w, "cylinder", &s, &err);
    } else if (!strcmp(md.kind, "slices")) {
        s.kind = "cylinder";
        s.size = sd_test_v(D, D, L / md.n);
        int slice = sd_world_add_shape(w, "slice", &s, &err);
        sd_test_require(slice >= 0, "slice", &err);
        sd_composite_element el[64];
        for (int k = 0; k < md.n; ++k) {
            memset(&el[k], 0, sizeof el[k]);
            el[k].shape = slice;
            el[k].position = sd_test_v(0, 0, -0.5 * L + (k + 0.5) * L / md.n);
        }
        sd_composite_desc cd = sd_composite_desc_default();
        cd.elements = el;
        cd.element_count = (size_t)md.n;
        shape = sd_world_add_composite(w, "glued", &cd, &err);
    } else {
        /* the presets of seed 004 Fig. 10 (shape/complib.c; their volumes
         * against Table 2: unit.composite) */
        sd_composite_preset_def pd = sd_composite_preset_def_default();
        pd.preset = md.n == 9 ? "spheres9" : "spheres54";
        pd.diameter = D;
        pd.length = L;
        shape = sd_world_add_composite_preset(w, "glued-spheres", &pd, &err);
    }
    sd_test_require(shape >= 0, "shape", &err);
    sd_world_add_plane(w, "wall", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err);
    sd_body_def b;
    memset(&b, 0, sizeof b);
    double h = 0.5 * L, r = 0.5 * D;
    /* the axis (z) turned by theta about y; the lowest rim point is then
     * h cos(theta) + r sin(theta) below the centre (composites: their
     * principal frame, whose axis is the cylinder's by symmetry) */
    b.orientation[0] = cos(0.5 * theta);
    b.orientation[2] = sin(0.5 * theta);
    b.position = sd_test_v(0, 0, h * fabs(cos(theta)) + r * sin(theta) + 1e-7);
    b.velocity = sd_test_v(0, 0, -V0);
    b.shape = shape;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    int touched = 0, steps = 0;
    double fmax = 0;
    for (int k = 0; k < 4000; ++k) {
        sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
        sd_stats st;
        sd_world_stats(w, &st);
        if (st.wall_contacts > 0) {
            touched = 1;
            ++steps;
            sd_wall_info wi;
            if (sd_world_get_wall(w, 0, &wi) == SD_OK)
                fmax = fmax > fabs(wi.force.z) ? fmax : fabs(wi.force.z);
        } else if (touched)
            break; /* the first impact is over */
    }
    sd_particle_state p;
    sd_world_get_particle(w, 0, &p);
    sd_world_destroy(w);
    outcome o = {p.velocity.z, p.angular_velocity.y, steps * DT, fmax};
    return o;
}

int main(void)
{
    /* 1. theta = 90 deg, N = 1..30 slices */
    printf("theta = 90 deg: analytic Vz+ = %.6f m/s, wy+ = 0 (seed 004 eqs. 22-23)\n", E * V0);
    printf("model  N   Vz+ computed  err%%     |wy+| rad/s   duration s   peak force N\n");
    static const int ns[] = {1, 2, 3, 5, 8, 10, 15, 20, 25, 30};
    enum { NN = sizeof ns / sizeof ns[0] };
    outcome ob[NN], oa[NN];
    for (int k = 0; k < NN; ++k) {
        model mb = {"slices", ns[k], SD_MULTI_CONTACT_AVERAGE};
        model ma = {"slices", ns[k], SD_MULTI_CONTACT_SUM};
        ob[k] = simulate(0.5 * PI, mb);
        oa[k] = simulate(0.5 * PI, ma);
        double eb = 100 * fabs(ob[k].vz - E * V0) / (E * V0), ea = 100 * fabs(oa[k].vz - E * V0) / (E * V0);
        printf("B     %2d  %12.6f  %6.3f  %12.4e  %11.4e  %10.3f\n", ns[k], ob[k].vz, eb, fabs(ob[k].wy),
               ob[k].duration, ob[k].fmax);
        printf("A     %2d  %12.6f  %6.3f  %12.4e  %11.4e  %10.3f\n", ns[k], oa[k].vz, ea, fabs(oa[k].wy),
               oa[k].duration, oa[k].fmax);
        char label[96];
        snprintf(label, sizeof label, "model B, N = %2d: Vz+ within 0.5 %% (m/s)", ns[k]);
        CHECK_REL(label, ob[k].vz, E * V0, 0.005);
        if (k > 0) {
            /* the error of V_z+ comes from the spurious spin (below), and
             * falls with it */
            snprintf(label, sizeof label, "model B, N = %2d: Vz+ error below N = %d's", ns[k], ns[k - 1]);
            CHECK(fabs(ob[k].vz - E * V0) <= fabs(ob[k - 1].vz - E * V0) + 1e-9);
            printf("%s\n", label);
        }
        snprintf(label, sizeof label, "model B, N = %2d: duration as N = 1 (s)", ns[k]);
        CHECK_NEAR(label, ob[k].duration, ob[0].duration, 2.5 * DT);
        /* model A: T_c(N) = T_c(1) / sqrt(N) (eq. 19) */
        snprintf(label, sizeof label, "model A, N = %2d: duration T_c(1)/sqrt(N) (s)", ns[k]);
        CHECK_NEAR(label, oa[k].duration, oa[0].duration / sqrt((double)ns[k]), 2.5 * DT);
    }
    /* model B: the peak force of one contact point whatever N (eq. 20),
     * against N = 30, for every N */
    for (int k = 0; k < NN - 1; ++k) {
        char label[96];
        snprintf(label, sizeof label, "model B, N = %2d: peak force as N = 30 (N)", ns[k]);
        CHECK_REL(label, ob[k].fmax, ob[NN - 1].fmax, 0.01);
    }
    /* no spurious spin of the line contact for any N (seed 004 Fig. 9b
     * has it fall like 1/N; the midpoint removes it) */
    for (int k = 0; k < NN; ++k) {
        char label[96];
        snprintf(label, sizeof label, "model B, N = %2d: |wy+| at rounding level (rad/s)", ns[k]);
        CHECK_NEAR(label, fabs(ob[k].wy), 0.0, 1e-9);
    }

    /* 2. the true cylinder against the 10-slice composite, theta 0..90 */
    double wmax = 0;
    outcome tr[19], gl[19];
    for (int k = 0; k <= 18; ++k) {
        double th = 5.0 * k * PI / 180.0;
        model mt = {"true", 1, SD_MULTI_CONTACT_AVERAGE}, mg = {"slices", 10, SD_MULTI_CONTACT_AVERAGE};
        tr[k] = simulate(th, mt);
        gl[k] = simulate(th, mg);
        wmax = fmax(wmax, fabs(tr[k].wy));
    }
    for (int k = 0; k <= 18; k += 18) {
        const outcome *o[2] = {&tr[k], &gl[k]};
        for (int g = 0; g < 2; ++g) {
            char label[96];
            snprintf(label, sizeof label, "theta %2d deg, flat, %s: Vz+ = e V (m/s)", 5 * k, g ? "glued" : "true");
            CHECK_REL(label, o[g]->vz, E * V0, 0.005);
            snprintf(label, sizeof label, "theta %2d deg, flat, %s: |wy+| (rad/s)", 5 * k, g ? "glued" : "true");
            CHECK_NEAR(label, fabs(o[g]->wy), 0.0, 1e-9);
        }
    }
    printf("theta  Vz+ true    Vz+ glued(10)   wy+ true    wy+ glued(10)\n");
    for (int k = 0; k <= 18; ++k) {
        printf("%5d  %10.6f  %12.6f  %11.4f  %12.4f\n", 5 * k, tr[k].vz, gl[k].vz, tr[k].wy, gl[k].wy);
        if (k >= 2 && k <= 16) {
            char label[96];
            snprintf(label, sizeof label, "theta %2d deg: glued Vz+ as the true cylinder's (m/s)", 5 * k);
            CHECK_NEAR(label, gl[k].vz, tr[k].vz, 0.01 * V0);
            snprintf(label, sizeof label, "theta %2d deg: glued wy+ as the true cylinder's (rad/s)", 5 * k);
            CHECK_NEAR(label, gl[k].wy, tr[k].wy, 0.01 * wmax);
        }
    }

    /* 3. glued-sphere cylinders: reported, not asserted */
    printf("glued spheres (deviation from the true cylinder, reported only)\n");
    printf("theta  Vz+ true   Vz+ 9 sph  Vz+ 54 sph   wy+ true   wy+ 9 sph  wy+ 54 sph\n");
    for (int k = 0; k <= 18; k += 3) {
        double th = 5.0 * k * PI / 180.0;
        model m9 = {"spheres", 9, SD_MULTI_CONTACT_AVERAGE}, m54 = {"spheres", 54, SD_MULTI_CONTACT_AVERAGE};
        outcome a = simulate(th, m9), c = simulate(th, m54);
        printf("%5d  %9.5f  %9.5f  %10.5f  %9.3f  %9.3f  %10.3f\n", 5 * k, tr[k].vz, a.vz, c.vz, tr[k].wy, a.wy,
               c.wy);
    }
    return sd_test_summary();
}
