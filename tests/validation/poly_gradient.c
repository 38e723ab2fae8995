/* poly_gradient.c — the volume law's force and torque are minus the
 * gradient of its potential W(V) = 3/4 (E1/R1 + E2/R2) V^(4/3) (seed 000
 * eqs. 12-13 with A_n = |S|, n = S/|S|; notes/algorithms.md §H 17), and
 * every pair keeps action-reaction and angular momentum (§H 35).
 *
 * For random overlapping poses of polyhedron pairs (dodecahedron,
 * cube, random 16-point polyhedra), at rest (no damping, mu = 0): the force
 * on each body is checked against central differences of W over its
 * position, and its torque against central differences over a rotation
 * about its centre, steps h = 1e-6 L (L the sum of the bounding radii),
 * relative tolerance 1e-5 of the force (torque) magnitude. The same for a
 * polyhedron against a wall plane (geom/halfspace.h). Action-reaction:
 * F_j = -F_i exactly by construction; angular momentum: x_i × F_i + T_i +
 * x_j × F_j + T_j = 0 within 1e-12 |F| L.
 * All of it three times: seed 000's law, and the law with the face
 * regularisation (materials[].volume_face_omega_dt; contact/law_volume.h)
 * with the step chosen so that each pose's overlap volume lies below the
 * onset V0 (V0 = 4 V: W linear in V) or above it (V0 = V / 4): the
 * regularised law stays the gradient of its W(V) to the same tolerance.
 */
#include "poly_common.h"

#include "contact/pair_poly.h"
#include "core/rng.h"

static sd_overlap_workspace ws;
static sd_real onset; /* m^3, the regularisation's V0 the pair functions compute (bodies of radius 0: none) */
static double g_reg;  /* 0: seed 000's law; else the face regularisation with V0 = g_reg x the pose's V */

/* The regularised pair (law_volume.h): face_omega on, the bodies' bounding
 * radii set, and the step that puts V0 at g_reg times the overlap volume;
 * sets onset as sd_pair_volume_apply computes it. Returns the step (s). */
static sd_real regularise(sd_pair_params *pr, sd_body *ba, sd_body *bb, double kcoef, double volume)
{
    onset = 0;
    if (g_reg == 0)
        return SD_R(1e-6);
    pr->face_omega = SD_R(0.5);
    double rb = (double)ba->radius;
    if (bb->radius > 0 && (double)bb->radius < rb)
        rb = (double)bb->radius;
    double area = 3.14159265358979323846 * rb * rb, inv = (double)(ba->inv_mass + bb->inv_mass);
    double v23 = pow(g_reg * volume, 2.0 / 3.0);
    sd_real dt = (sd_real)sqrt(v23 * 0.25 / (kcoef * area * area * inv));
    onset = sd_volume_onset(pr, (sd_real)kcoef, SD_PI * (sd_real)rb * (sd_real)rb, (sd_real)inv, dt);
    return dt;
}

/* W of bodies a, b in their poses (0 apart). */
static double potential(const sd_pair_params *prm, const sd_convex *a, const sd_convex *b, double kcoef)
{
    sd_overlap o = sd_overlap_polyhedra(a, b, sd_v3_zero(), 0, &ws);
    if (o.status != SD_OVERLAP_OK)
        return 0.0;
    return (double)sd_volume_w(prm, (sd_real)kcoef, o.volume, o.area, onset);
}

static double potential_wall(const sd_pair_params *prm, const sd_convex *a, sd_vec3 n, sd_real h, double kcoef)
{
    sd_overlap o = sd_overlap_halfspace(a, n, h);
    if (o.status != SD_OVERLAP_OK)
        return 0.0;
    return (double)sd_volume_w(prm, (sd_real)kcoef, o.volume, o.area, onset);
}

static sd_vec3 axis(int k) { return sd_v3(k == 0, k == 1, k == 2); }

static sd_body body_at(const sd_convex *c, double mass, double inertia)
{
    sd_body b;
    memset(&b, 0, sizeof b);
    b.x = c->x;
    b.q = c->q;
    b.inv_mass = (sd_real)(1.0 / mass);
    b.inv_inertia = sd_v3((sd_real)(1.0 / inertia), (sd_real)(1.0 / inertia), (sd_real)(1.0 / inertia));
    return b;
}

static double worst_f = 0, worst_t = 0, worst_l = 0;

static void check_pair(const sd_world *w, int sa, int sb, sd_rng *rng)
{
    const sd_pair_params *prm = &w->mix[0];
    sd_convex a, b;
    memset(&a, 0, sizeof a);
    a.shape = &w->shapes[sa];
    a.verts = w->verts;
    a.planes = w->planes;
    a.dtris = w->dtris;
    b = a;
    b.shape = &w->shapes[sb];
    sd_real ra = w->shape_req[sa], rb = w->shape_req[sb];
    double kcoef = (double)(prm->young_a / ra + prm->young_b / rb);
    double L = (double)(a.shape->bound + b.shape->bound);
    for (int attempt = 0; attempt < 100; ++attempt) {
        a.x = sd_v3(0, 0, 0);
        a.q = sd_quat_normalize(sd_quat_make((sd_real)sd_rng_range(rng, -1, 1), (sd_real)sd_rng_range(rng, -1, 1),
                                             (sd_real)sd_rng_range(rng, -1, 1), (sd_real)sd_rng_range(rng, -1, 1)));
        b.q = sd_quat_normalize(sd_quat_make((sd_real)sd_rng_range(rng, -1, 1), (sd_real)sd_rng_range(rng, -1, 1),
                                             (sd_real)sd_rng_range(rng, -1, 1), (sd_real)sd_rng_range(rng, -1, 1)));
        sd_vec3 u = sd_v3_normalize(sd_v3((sd_real)sd_rng_range(rng, -1, 1), (sd_real)sd_rng_range(rng, -1, 1),
                                          (sd_real)sd_rng_range(rng, -1, 1)));
        b.x = sd_v3_scale(u, (sd_real)(L * sd_rng_range(rng, 0.45, 0.75)));
        sd_overlap o = sd_overlap_polyhedra(&a, &b, sd_v3_zero(), 0, &ws);
        double vmin = fmin((double)a.shape->volume, (double)b.shape->volume);
        if (o.status != SD_OVERLAP_OK || o.volume < 1e-4 * vmin)
            continue;
        sd_body ba = body_at(&a, 1.0, 0.1), bb = body_at(&b, 2.0, 0.3);
        ba.radius = a.shape->bound;
        bb.radius = b.shape->bound;
        sd_pair_params pr0 = *prm;
        sd_real dt = regularise(&pr0, &ba, &bb, kcoef, (double)o.volume);
        prm = &pr0;
        sd_vec3 ds = sd_v3_zero(), x0 = sd_v3_zero();
        uint8_t ok = 0;
        sd_narrow_count ns;
        sd_pair_result r = sd_pair_poly(prm, &ba, &bb, &a, &b, ra, rb, &ds, &x0, &ok, &ws, dt, &ns);
        double h = 1e-6 * L, ht = 1e-6;
        double fd[3], fdb[3], td[3], tdb[3];
        for (int k = 0; k < 3; ++k) {
            sd_convex p = a, m = a;
            p.x = sd_v3_madd(a.x, (sd_real)h, axis(k));
            m.x = sd_v3_madd(a.x, (sd_real)-h, axis(k));
            fd[k] = -(potential(prm, &p, &b, kcoef) - potential(prm, &m, &b, kcoef)) / (2 * h);
            p = b;
            m = b;
            p.x = sd_v3_madd(b.x, (sd_real)h, axis(k));
            m.x = sd_v3_madd(b.x, (sd_real)-h, axis(k));
            fdb[k] = -(potential(prm, &a, &p, kcoef) - potential(prm, &a, &m, kcoef)) / (2 * h);
            p = a;
            m = a;
            p.q = sd_quat_mul(sd_quat_from_rotvec(sd_v3_scale(axis(k), (sd_real)ht)), a.q);
            m.q = sd_quat_mul(sd_quat_from_rotvec(sd_v3_scale(axis(k), (sd_real)-ht)), a.q);
            td[k] = -(potential(prm, &p, &b, kcoef) - potential(prm, &m, &b, kcoef)) / (2 * ht);
            p = b;
            m = b;
            p.q = sd_quat_mul(sd_quat_from_rotvec(sd_v3_scale(axis(k), (sd_real)ht)), b.q);
            m.q = sd_quat_mul(sd_quat_from_rotvec(sd_v3_scale(axis(k), (sd_real)-ht)), b.q);
            tdb[k] = -(potential(prm, &a, &p, kcoef) - potential(prm, &a, &m, kcoef)) / (2 * ht);
        }
        double fn = (double)sd_v3_norm(r.f), tn = fmax((double)sd_v3_norm(r.ti), (double)sd_v3_norm(r.tj));
        double ef = 0, et = 0;
        double f[3] = {(double)r.f.x, (double)r.f.y, (double)r.f.z};
        double ti[3] = {(double)r.ti.x, (double)r.ti.y, (double)r.ti.z}, tj[3] = {(double)r.tj.x, (double)r.tj.y, (double)r.tj.z};
        for (int k = 0; k < 3; ++k) {
            ef = fmax(ef, fmax(fabs(f[k] - fd[k]), fabs(-f[k] - fdb[k])) / fn);
            et = fmax(et, fmax(fabs(ti[k] - td[k]), fabs(tj[k] - tdb[k])) / tn);
        }
        /* total torque about the origin */
        sd_vec3 lt = sd_v3_add(sd_v3_add(sd_v3_cross(a.x, r.f), r.ti), sd_v3_add(sd_v3_cross(b.x, sd_v3_neg(r.f)), r.tj));
        double el = (double)sd_v3_norm(lt) / (fn * L);
        worst_f = fmax(worst_f, ef);
        worst_t = fmax(worst_t, et);
        worst_l = fmax(worst_l, el);
        return;
    }
    printf("FAIL no overlapping pose found for shapes %d, %d\n", sa, sb);
    sd_test_fail++;
}

static double worst_wf = 0, worst_wt = 0;

static void check_wall(const sd_world *w, int sa, sd_rng *rng)
{
    const sd_pair_params *prm = &w->mix[0];
    sd_convex a;
    memset(&a, 0, sizeof a);
    a.shape = &w->shapes[sa];
    a.verts = w->verts;
    a.planes = w->planes;
    a.dtris = w->dtris;
    sd_real ra = w->shape_req[sa];
    double kcoef = (double)(prm->young_a / ra), L = (double)a.shape->bound;
    a.q = sd_quat_normalize(sd_quat_make((sd_real)sd_rng_range(rng, -1, 1), (sd_real)sd_rng_range(rng, -1, 1),
                                         (sd_real)sd_rng_range(rng, -1, 1), (sd_real)sd_rng_range(rng, -1, 1)));
    sd_vec3 nw = sd_v3_normalize(sd_v3((sd_real)sd_rng_range(rng, -0.3, 0.3), (sd_real)sd_rng_range(rng, -0.3, 0.3), 1));
    sd_vec3 low = sd_convex_support_core(&a, sd_v3_neg(nw));
    sd_vec3 p0 = sd_v3_madd(low, (sd_real)(L * sd_rng_range(rng, 0.05, 0.4)), nw); /* the plane cuts into a */
    sd_body ba = body_at(&a, 1.0, 0.1), wall;
    ba.radius = a.shape->bound;
    memset(&wall, 0, sizeof wall);
    sd_vec3 n = sd_v3_neg(nw);
    sd_real h = -sd_v3_dot(nw, p0);
    sd_pair_params pr0 = *prm;
    sd_real dt = regularise(&pr0, &ba, &wall, kcoef, (double)sd_overlap_halfspace(&a, n, h).volume);
    prm = &pr0;
    sd_vec3 ds = sd_v3_zero(), point;
    sd_pair_result r = sd_pair_poly_wall(prm, &ba, &a, p0, nw, ra, &ds, dt, &point);
    double hh = 1e-6 * L, ht = 1e-6, fn = (double)sd_v3_norm(r.f), tn = (double)sd_v3_norm(r.ti), ef = 0, et = 0;
    double f[3] = {(double)r.f.x, (double)r.f.y, (double)r.f.z}, t[3] = {(double)r.ti.x, (double)r.ti.y, (double)r.ti.z};
    for (int k = 0; k < 3; ++k) {
        sd_convex p = a, m = a;
        p.x = sd_v3_madd(a.x, (sd_real)hh, axis(k));
        m.x = sd_v3_madd(a.x, (sd_real)-hh, axis(k));
        double fd = -(potential_wall(prm, &p, n, h, kcoef) - potential_wall(prm, &m, n, h, kcoef)) / (2 * hh);
        p = a;
        m = a;
        p.q = sd_quat_mul(sd_quat_from_rotvec(sd_v3_scale(axis(k), (sd_real)ht)), a.q);
        m.q = sd_quat_mul(sd_quat_from_rotvec(sd_v3_scale(axis(k), (sd_real)-ht)), a.q);
        double td = -(potential_wall(prm, &p, n, h, kcoef) - potential_wall(prm, &m, n, h, kcoef)) / (2 * ht);
        ef = fmax(ef, fabs(f[k] - fd) / fn);
        et = fmax(et, fabs(t[k] - td) / tn);
    }
    worst_wf = fmax(worst_wf, ef);
    worst_wt = fmax(worst_wt, et);
}

int main(void)
{
    int mat;
    sd_world *w = poly_world(SD_LAW_VOLUME, 1e-6, sd_test_v(0, 0, 0), 1e7, 1.0, 0.0, 2500, 1, &mat);
    sd_v3d v[64];
    poly_dodecahedron(0.01, v);
    int dod = poly_add_shape(w, "dodecahedron", v, 20);
    poly_cube(0.012, v);
    int cube = poly_add_shape(w, "cube", v, 8);
    sd_rng rng = sd_rng_seed(42);
    int rnd[3];
    for (int s = 0; s < 3; ++s) {
        for (int k = 0; k < 16; ++k) {
            double z = sd_rng_range(&rng, -1, 1), ph = sd_rng_range(&rng, 0, 6.283185307179586), rr = sqrt(1 - z * z);
            v[k] = sd_test_v(0.01 * rr * cos(ph), 0.01 * rr * sin(ph), 0.01 * z);
        }
        char name[16];
        snprintf(name, sizeof name, "random%d", s);
        rnd[s] = poly_add_shape(w, name, v, 16);
    }
    sd_error err;
    sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err);
    const int shapes[5] = {dod, cube, rnd[0], rnd[1], rnd[2]};
    for (int mode = 0; mode < 3; ++mode) {
    /* seed 000's law; then the face regularisation with every pose below
     * its onset V0 (the linear part) and above it (the shifted seed law) */
    const double regs[3] = {0.0, 4.0, 0.25};
    g_reg = regs[mode];
    worst_f = worst_t = worst_l = worst_wf = worst_wt = 0;
    printf("%s\n", mode == 0 ? "seed 000's law" : mode == 1 ? "regularised, V0 = 4 V (linear in V)"
                                                            : "regularised, V0 = V / 4 (seed's law shifted)");
    int pairs = 0;
    for (int rep = 0; rep < 8; ++rep)
        for (int x = 0; x < 5; ++x)
            for (int y = x; y < 5; ++y, ++pairs)
                check_pair(w, shapes[x], shapes[y], &rng);
    printf("%d random overlapping pairs (dodecahedron, cube, 3 random 16-point polyhedra)\n", pairs);
    CHECK_NEAR("pairs: max |F - (-dW/dx)| / |F|", worst_f, 0.0, 1e-5);
    CHECK_NEAR("pairs: max |T - (-dW/dtheta)| / |T|", worst_t, 0.0, 1e-5);
    CHECK_NEAR("pairs: max |total torque about 0| / (|F| L)", worst_l, 0.0, 1e-12);
    for (int rep = 0; rep < 40; ++rep)
        check_wall(w, shapes[rep % 5], &rng);
    printf("40 random polyhedron-wall poses\n");
    CHECK_NEAR("walls: max |F - (-dW/dx)| / |F|", worst_wf, 0.0, 1e-5);
    CHECK_NEAR("walls: max |T - (-dW/dtheta)| / |T|", worst_wt, 0.0, 1e-5);
    if (mode > 0)
        CHECK(onset > 0); /* the last pose had its V0: the regularised branch ran */
    }
    sd_world_destroy(w);
    return sd_test_summary();
}
