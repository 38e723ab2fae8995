/* poly_law.c — unit checks of the volume laws (contact/law_volume.h) and
 * of the polyhedron/half-space overlap (geom/halfspace.h).
 *
 *  - damping calibration: the 1D model of exponent p with the calibrated
 *    zeta(e, p) rebounds with e (1e-6), and e = 1 gives zeta = 0;
 *  - half-space overlap of a cube, exact: face down V = a^2 d, |S| = a^2,
 *    point under the centre; edge down (45 deg) V = a d^2, |S| = 2 a d;
 *    corner down (body diagonal vertical) V = (sqrt 3 / 2) d^3,
 *    |S| = (3 sqrt 3 / 2) d^2, point on the diagonal; and the exponent the
 *    law reads from them: shape factor m = |S| d / V = 1, 2, 3;
 *  - the law: elastic force = W'(V) |S| along n, W' = dW/dV (central
 *    differences), no tension, the couple W' twist n, Coulomb cap;
 *  - a scene pair under a volume law that is not two sharp polyhedra is
 *    refused at prepare time with a message naming the shape and materials;
 *  - the pair's interior-point hint x0 survives a pair-list rebuild (found
 *    again by the pair's key, bit for bit).
 */
#include <string.h>

#include "test.h"

#include "contact/pair_poly.h"
#include "world/world.h"

static sd_world *cube_world(double a, int *shape)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.law = SD_LAW_VOLUME;
    d.dt = 1e-6;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    sd_world_add_material(w, &m, &err);
    sd_v3d v[8];
    int n = 0;
    for (int i = -1; i <= 1; i += 2)
        for (int j = -1; j <= 1; j += 2)
            for (int k = -1; k <= 1; k += 2)
                v[n++] = sd_test_v(0.5 * a * i, 0.5 * a * j, 0.5 * a * k);
    sd_shape_desc s = sd_shape_desc_default();
    s.kind = "polyhedron";
    s.vertices = v;
    s.vertex_count = 8;
    *shape = sd_world_add_shape(w, "cube", &s, &err);
    sd_test_require(*shape >= 0, "shape", &err);
    return w;
}

/* The cube posed so that its given-frame axes turn by q (principal frame
 * of a cube: any axes; given_q maps them back). */
static sd_convex cube_pose(const sd_world *w, int s, sd_quat q, sd_vec3 x)
{
    sd_convex c;
    memset(&c, 0, sizeof c);
    c.shape = &w->shapes[s];
    c.verts = w->verts;
    c.planes = w->planes;
    c.dtris = w->dtris;
    c.q = sd_quat_mul(q, w->shapes[s].given_q);
    c.x = x;
    return c;
}

static void halfspace_cases(void)
{
    const double a = 0.01, d = 1e-4;
    int s;
    sd_world *w = cube_world(a, &s);
    sd_vec3 n = sd_v3(0, 0, -1); /* the wall's solid is z < 0: n . x > h with h = 0 */
    char label[96];
    /* face down, centre at (1, 2, a/2 - d) mm */
    sd_convex c = cube_pose(w, s, sd_quat_identity(), sd_v3(SD_R(0.001), SD_R(0.002), (sd_real)(0.5 * a - d)));
    sd_overlap o = sd_overlap_halfspace(&c, n, 0);
    CHECK(o.status == SD_OVERLAP_OK);
    CHECK_REL("face down: V (m^3)", o.volume, a * a * d, 1e-9);
    CHECK_REL("face down: |S| (m^2)", o.area, a * a, 1e-9);
    CHECK_NEAR("face down: point x (m)", o.point.x, 0.001, 1e-12);
    CHECK_NEAR("face down: point y (m)", o.point.y, 0.002, 1e-12);
    CHECK_NEAR("face down: point z (m)", o.point.z, 0.0, 1e-15);
    CHECK_NEAR("face down: normal z", o.normal.z, -1.0, 0.0);
    CHECK_NEAR("face down: shape factor m", sd_volume_exponent(SD_LAW_VOLUME_LINEAR, o.area,
                                                            sd_halfspace_depth(&c, n, 0), o.volume), 1.0, 1e-9);
    /* edge down: 45 deg about x, the lowest edge a/sqrt 2 below the centre */
    sd_quat q45 = sd_quat_from_rotvec(sd_v3(SD_R(0.7853981633974483), 0, 0));
    c = cube_pose(w, s, q45, sd_v3(0, 0, (sd_real)(a / sqrt(2.0) - d)));
    o = sd_overlap_halfspace(&c, n, 0);
    CHECK_REL("edge down: V = a d^2 (m^3)", o.volume, a * d * d, 1e-9);
    CHECK_REL("edge down: |S| = 2 a d (m^2)", o.area, 2 * a * d, 1e-9);
    CHECK_NEAR("edge down: shape factor m", sd_volume_exponent(SD_LAW_VOLUME_LINEAR, o.area,
                                                            sd_halfspace_depth(&c, n, 0), o.volume), 2.0, 1e-6);
    /* corner down: the body diagonal (1, 1, 1) turned onto -z */
    sd_vec3 diag = sd_v3_normalize(sd_v3(1, 1, 1));
    sd_vec3 ax = sd_v3_cross(diag, sd_v3(0, 0, -1));
    sd_real ang = sd_atan2(sd_v3_norm(ax), sd_v3_dot(diag, sd_v3(0, 0, -1)));
    sd_quat qc = sd_quat_from_rotvec(sd_v3_scale(sd_v3_normalize(ax), ang));
    c = cube_pose(w, s, qc, sd_v3(SD_R(0.003), 0, (sd_real)(0.5 * a * sqrt(3.0) - d)));
    o = sd_overlap_halfspace(&c, n, 0);
    CHECK_REL("corner down: V = (sqrt3/2) d^3 (m^3)", o.volume, 0.5 * sqrt(3.0) * d * d * d, 1e-6);
    CHECK_REL("corner down: |S| = (3 sqrt3/2) d^2 (m^2)", o.area, 1.5 * sqrt(3.0) * d * d, 1e-6);
    CHECK_NEAR("corner down: point x, under the corner (m)", o.point.x, 0.003, 1e-12);
    CHECK_NEAR("corner down: point y (m)", o.point.y, 0.0, 1e-12);
    CHECK_NEAR("corner down: shape factor m", sd_volume_exponent(SD_LAW_VOLUME_LINEAR, o.area,
                                                              sd_halfspace_depth(&c, n, 0), o.volume), 3.0, 1e-6);
    /* apart: no overlap */
    c = cube_pose(w, s, sd_quat_identity(), sd_v3(0, 0, (sd_real)(0.5 * a + 1e-9)));
    o = sd_overlap_halfspace(&c, n, 0);
    CHECK(o.status == SD_OVERLAP_NONE);
    /* dV/dh = -|S| for a random pose (the plane moved into the body) */
    sd_quat qr = sd_quat_normalize(sd_quat_make(SD_R(0.3), SD_R(-0.5), SD_R(0.7), SD_R(0.2)));
    c = cube_pose(w, s, qr, sd_v3(0, 0, SD_R(0.004)));
    sd_real h = SD_R(-0.002), dh = SD_R(1e-9);
    sd_overlap op = sd_overlap_halfspace(&c, n, h + dh), om = sd_overlap_halfspace(&c, n, h - dh);
    o = sd_overlap_halfspace(&c, n, h);
    snprintf(label, sizeof label, "random pose: -dV/dh / |S|");
    CHECK_REL(label, -(op.volume - om.volume) / (2 * dh) / o.area, 1.0, 1e-6);
    sd_world_destroy(w);
}

static void calibration(void)
{
    const double es[4] = {0.1, 0.5, 0.85, 0.99};
    double worst = 0;
    for (int k = 0; k < 4; ++k) {
        sd_real z[SD_VOLUME_ZETA_N];
        sd_volume_zeta_table(es[k], z);
        for (int j = 0; j < SD_VOLUME_ZETA_N; j += 2) {
            double p = (double)SD_VOLUME_P_MIN + j * (double)SD_VOLUME_P_STEP;
            worst = fmax(worst, fabs(sd_volume_rebound_model(p, (double)z[j]) - es[k]));
        }
    }
    CHECK_NEAR("1D model rebound with calibrated zeta vs e", worst, 0.0, 1e-6);
    sd_real z1[SD_VOLUME_ZETA_N];
    sd_volume_zeta_table(1.0, z1);
    CHECK_NEAR("e = 1: zeta", (double)z1[0] + (double)z1[SD_VOLUME_ZETA_N - 1], 0.0, 0.0);
}

static void law(void)
{
    sd_pair_params p;
    memset(&p, 0, sizeof p);
    p.law = SD_LAW_VOLUME;
    p.restitution = 1;
    p.friction = 0.5;
    p.kv = 1e9;
    p.kt_ratio = 0.3;
    double kc = 2e9, V = 3e-9, A = 2e-5;
    double dw = (double)sd_volume_dw(&p, (sd_real)kc, (sd_real)V, (sd_real)A, 0);
    double hV = 1e-6 * V;
    double fd = ((double)sd_volume_w(&p, (sd_real)kc, (sd_real)(V + hV), (sd_real)A, 0) -
                 (double)sd_volume_w(&p, (sd_real)kc, (sd_real)(V - hV), (sd_real)A, 0)) / (2 * hV);
    CHECK_REL("volume: W'(V) vs dW/dV", dw, fd, 1e-8);
    CHECK_REL("volume: W'(V) = c V^(1/3)", dw, kc * cbrt(V), 1e-12);
    p.law = SD_LAW_VOLUME_LINEAR;
    CHECK_REL("volume_linear: W'(V) |S| = k_V V", (double)sd_volume_dw(&p, (sd_real)kc, (sd_real)V, (sd_real)A, 0) * A,
              1e9 * V, 1e-12);
    p.law = SD_LAW_VOLUME;
    sd_volume_geom g;
    g.volume = (sd_real)V;
    g.area = (sd_real)A;
    g.n = sd_v3(0, 0, 1);
    g.point = sd_v3_zero();
    g.twist = SD_R(1e-7);
    g.depth = SD_R(1e-4);
    g.onset = SD_R(0.0);
    sd_vec3 ds = sd_v3_zero();
    /* sliding: v_t = 1 m/s along x for 10 ms stretches the spring by 1 cm:
     * k_t |s| = 200 N, above mu F_n */
    sd_volume_out o = sd_law_volume_eval(&p, &g, (sd_real)kc, SD_R(1e9), SD_R(0.01), sd_v3(1, 0, 0), &ds, SD_R(1e-2));
    CHECK_REL("elastic normal force = W' |S| (N)", o.force.z, dw * A, 1e-12);
    CHECK_REL("Coulomb cap: |F_t| = mu F_n (N)", -o.force.x, 0.5 * dw * A, 1e-12);
    CHECK_REL("couple = W' twist n (N m)", o.couple.z, dw * 1e-7, 1e-12);
    /* separating fast with damping: the force never pulls */
    p.restitution = SD_R(0.3);
    sd_volume_zeta_table(0.3, p.zeta);
    p.log_e_factor = (sd_real)(log(0.3) / sqrt(log(0.3) * log(0.3) + 3.14159265358979323846 * 3.14159265358979323846));
    ds = sd_v3_zero();
    o = sd_law_volume_eval(&p, &g, (sd_real)kc, SD_R(1e9), SD_R(0.01), sd_v3(0, 0, 50), &ds, SD_R(1e-6));
    CHECK_NEAR("no tension: F_n when separating fast (N)", o.fn, 0.0, 0.0);
}

static void refusal(void)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.law = SD_LAW_VOLUME;
    d.dt = 1e-6;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "glass";
    m.youngs_modulus = 1e7;
    int mat = sd_world_add_material(w, &m, &err);
    sd_shape_desc s = sd_shape_desc_default();
    s.kind = "box";
    s.size = sd_test_v(0.01, 0.01, 0.01);
    int box = sd_world_add_shape(w, "brick", &s, &err);
    sd_body_def b;
    memset(&b, 0, sizeof b);
    b.shape = box;
    b.material = mat;
    sd_world_add_bodies(w, 1, &b, &err);
    sd_status st = sd_world_prepare(w, &err);
    printf("     prepare says: %s\n", err.msg);
    CHECK(st == SD_ERR_INPUT);
    CHECK(strstr(err.msg, "'brick'") != NULL && strstr(err.msg, "'glass'") != NULL && strstr(err.msg, "volume") != NULL);
    sd_world_destroy(w);
}

static void hint_carry(void)
{
    sd_error err;
    int s;
    sd_world *w = cube_world(0.01, &s);
    sd_body_def b[2];
    memset(b, 0, sizeof b);
    b[0].shape = b[1].shape = s;
    b[1].position = sd_test_v(0.009, 0.001, 0.0005);
    b[1].orientation[0] = 0.9;
    b[1].orientation[3] = 0.3;
    sd_test_require(sd_world_add_bodies(w, 2, b, &err) == SD_OK, "bodies", &err);
    sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err);
    const sd_pair_list *l = &w->pairs;
    CHECK(l->n == 1 && l->x0_ok[0] == 1);
    sd_vec3 x0 = l->x0[0];
    sd_pair_key key = l->key[0];
    sd_test_require(sd_world_rebuild(w, &err) == SD_OK, "rebuild", &err);
    CHECK(l->n == 1 && memcmp(&l->key[0], &key, sizeof key) == 0);
    CHECK_NEAR("hint flag after a rebuild", (double)l->x0_ok[0], 1.0, 0.0);
    CHECK_NEAR("hint after a rebuild: same bits (1 = yes)", (double)(memcmp(&x0, &l->x0[0], sizeof x0) == 0), 1.0,
               0.0);
    sd_world_destroy(w);
}

int main(void)
{
    hint_carry();
    calibration();
    halfspace_cases();
    law();
    refusal();
    return sd_test_summary();
}
