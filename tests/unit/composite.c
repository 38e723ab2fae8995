/* composite.c — composite templates (seed 004): sd_world_add_composite and
 * its mass properties (shape/composite.c).
 *
 * Exact cases (no two elements overlap): 8 cubes glued face to face are one
 * cube of twice the edge; an L of two boxes, given off-centre and turned,
 * against its inertia tensor summed here box by box. Overlapping elements:
 * two spheres (the lens volume in closed form); the seed's lattice over a
 * sphere, a cylinder and two crossed cylinders converging to the closed
 * forms, the same bits for 1 and 2 threads. The built-in library against
 * closed forms (three crossed cylinders, a ring, a dumbbell) and seed 004
 * Table 2 (9 glued spheres). Bad input: each error.
 */
#include "test.h"

#include <math.h>
#include <string.h>

#include "core/quat.h"
#include "shape/complib.h"
#include "shape/composite.h"
#include "shape/shape_make.h"
#include "world/world.h"

static sd_world *new_world(void)
{
    sd_world_def wd = sd_world_def_default();
    wd.threads = 2;
    sd_world *w = NULL;
    sd_error err;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "sd_world_create", &err);
    return w;
}

static int add_box(sd_world *w, const char *name, double x, double y, double z)
{
    sd_shape_desc d = sd_shape_desc_default();
    d.kind = "box";
    d.size = sd_test_v(x, y, z);
    sd_error err;
    int k = sd_world_add_shape(w, name, &d, &err);
    sd_test_require(k >= 0, "sd_world_add_shape", &err);
    return k;
}

static int add_sphere(sd_world *w, const char *name, double r)
{
    sd_shape_desc d = sd_shape_desc_default();
    d.kind = "sphere";
    d.size = sd_test_v(r, r, r);
    sd_error err;
    int k = sd_world_add_shape(w, name, &d, &err);
    sd_test_require(k >= 0, "sd_world_add_shape", &err);
    return k;
}

static sd_composite_element elem(int shape, double x, double y, double z)
{
    sd_composite_element e;
    memset(&e, 0, sizeof e);
    e.shape = shape;
    e.position = sd_test_v(x, y, z);
    return e;
}

/* eigenvalues of a symmetric 3x3 matrix, ascending (trigonometric form) */
static void sym_eig3(const double a[3][3], double ev[3])
{
    double p1 = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    double q = (a[0][0] + a[1][1] + a[2][2]) / 3;
    if (p1 < 1e-300) {
        ev[0] = a[0][0];
        ev[1] = a[1][1];
        ev[2] = a[2][2];
    } else {
        double p2 = (a[0][0] - q) * (a[0][0] - q) + (a[1][1] - q) * (a[1][1] - q) + (a[2][2] - q) * (a[2][2] - q) +
                    2 * p1;
        double p = sqrt(p2 / 6), b[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                b[i][j] = (a[i][j] - (i == j ? q : 0)) / p;
        double r = (b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0]) +
                    b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0])) / 2;
        double phi = r <= -1 ? SD_PI_D / 3 : r >= 1 ? 0 : acos(r) / 3;
        ev[2] = q + 2 * p * cos(phi);
        ev[0] = q + 2 * p * cos(phi + 2 * SD_PI_D / 3);
        ev[1] = 3 * q - ev[0] - ev[2];
    }
    for (int i = 0; i < 3; ++i) /* sort */
        for (int j = i + 1; j < 3; ++j)
            if (ev[j] < ev[i]) {
                double t = ev[i];
                ev[i] = ev[j];
                ev[j] = t;
            }
}

static void sort3(double *v)
{
    for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j)
            if (v[j] < v[i]) {
                double t = v[i];
                v[i] = v[j];
                v[j] = t;
            }
}

int main(void)
{
    sd_error err;

    /* 8 cubes of edge 1 mm glued face to face: a cube of edge 2 mm, exactly
     * (the touching faces are not an overlap: no lattice) */
    {
        sd_world *w = new_world();
        int cube = add_box(w, "c", 1e-3, 1e-3, 1e-3);
        sd_composite_element e[8];
        for (int k = 0; k < 8; ++k)
            e[k] = elem(cube, (k & 1) ? 0.5e-3 : -0.5e-3, (k & 2) ? 0.5e-3 : -0.5e-3, (k & 4) ? 0.5e-3 : -0.5e-3);
        sd_composite_desc cd = sd_composite_desc_default();
        cd.elements = e;
        cd.element_count = 8;
        int k = sd_world_add_composite(w, "cube8", &cd, &err);
        sd_test_require(k == 1, "sd_world_add_composite", &err);
        sd_shape_info si;
        CHECK_OK(sd_world_get_shape(w, (size_t)k, &si));
        CHECK(strcmp(si.kind, "composite") == 0);
        double V = 8e-9, I = V * 4e-6 / 6; /* m (a^2 + a^2) / 12, a = 2 mm */
        CHECK_REL("8 cubes: volume", si.volume, V, 1e-12);
        CHECK_REL("8 cubes: I1", si.inertia.x, I, 1e-12);
        CHECK_REL("8 cubes: I2", si.inertia.y, I, 1e-12);
        CHECK_REL("8 cubes: I3", si.inertia.z, I, 1e-12);
        CHECK_REL("8 cubes: bounding radius", si.bounding_radius, sqrt(3.0) * 1e-3, 1e-12);
        CHECK_NEAR("8 cubes: centre of mass x", si.center_of_mass.x, 0, 1e-18);
        const sd_shape *s = &w->shapes[k];
        CHECK(s->kind == SD_SHAPE_COMPOSITE && s->ecount == 8 && s->estart == 0 && s->mass_lattice == 0);
        CHECK(w->element_count == 8 && w->elements[3].shape == cube);
        CHECK_REL("8 cubes: element bound copy", w->elements[5].bound, sqrt(3.0) * 0.5e-3, 1e-12);
        /* bodies of it, like any template */
        int mat;
        sd_material_def md = sd_material_def_default();
        mat = sd_world_add_material(w, &md, &err);
        sd_body_def bd;
        memset(&bd, 0, sizeof bd);
        bd.shape = k;
        bd.material = mat;
        CHECK_OK(sd_world_add_bodies(w, 1, &bd, &err));
        CHECK_REL("8 cubes: body radius", w->p.radius[0], sqrt(3.0) * 1e-3, 1e-12);
        CHECK_REL("8 cubes: body mass", 1.0 / w->p.inv_mass[0], md.density * V, 1e-12);
        /* a second composite after it: its elements follow in the pool */
        sd_composite_element e2[2] = {elem(cube, 0, 0, 0), elem(cube, 1e-3, 0, 0)};
        cd.elements = e2;
        cd.element_count = 2;
        int k2 = sd_world_add_composite(w, "pair", &cd, &err);
        sd_test_require(k2 == 2, "sd_world_add_composite", &err);
        CHECK(w->shapes[k2].estart == 8 && w->shapes[k2].ecount == 2 && w->element_count == 10);
        /* its centre of mass in the given frame is between the two cubes */
        CHECK_OK(sd_world_get_shape(w, (size_t)k2, &si));
        CHECK_NEAR("pair: given centre of mass x", si.center_of_mass.x, 0.5e-3, 1e-15);
        /* principal frame: the long axis (x) has the smallest moment, and
         * the elements sit at -+0.5 mm along the principal axis of it */
        const sd_element *pe = &w->elements[8];
        double len0 = sqrt((double)sd_v3_dot(pe[0].x, pe[0].x)), len1 = sqrt((double)sd_v3_dot(pe[1].x, pe[1].x));
        CHECK_REL("pair: element 0 offset", len0, 0.5e-3, 1e-12);
        CHECK_REL("pair: element 1 offset", len1, 0.5e-3, 1e-12);
        sd_world_destroy(w);
    }

    /* an L of two boxes (2x1x1 mm and 1x1x1 mm on its end, touching),
     * given off-centre and turned by q: the principal moments are those of
     * the inertia tensor summed here from the boxes' own closed forms */
    {
        sd_world *w = new_world();
        int bar = add_box(w, "bar", 2e-3, 1e-3, 1e-3), cube = add_box(w, "cube", 1e-3, 1e-3, 1e-3);
        const double off[3] = {3e-3, -1e-3, 2e-3};
        sd_quat q = sd_quat_normalize(sd_quat_make(0.9, 0.2, -0.3, 0.25));
        sd_vec3 c0 = sd_v3(1e-3, 0.5e-3, 0.5e-3), c1 = sd_v3(1.5e-3, 1.5e-3, 0.5e-3);
        sd_vec3 r0 = sd_quat_rotate(q, c0), r1 = sd_quat_rotate(q, c1);
        sd_composite_element e[2] = {elem(bar, off[0] + r0.x, off[1] + r0.y, off[2] + r0.z),
                                     elem(cube, off[0] + r1.x, off[1] + r1.y, off[2] + r1.z)};
        for (int k = 0; k < 2; ++k) {
            e[k].orientation[0] = q.w;
            e[k].orientation[1] = q.x;
            e[k].orientation[2] = q.y;
            e[k].orientation[3] = q.z;
        }
        sd_composite_desc cd = sd_composite_desc_default();
        cd.elements = e;
        cd.element_count = 2;
        int k = sd_world_add_composite(w, "L", &cd, &err);
        sd_test_require(k >= 0, "sd_world_add_composite", &err);
        sd_shape_info si;
        CHECK_OK(sd_world_get_shape(w, (size_t)k, &si));
        /* in the L's own frame: boxes (dims, centre), parallel axis theorem */
        const double dims[2][3] = {{2e-3, 1e-3, 1e-3}, {1e-3, 1e-3, 1e-3}};
        const double cen[2][3] = {{1e-3, 0.5e-3, 0.5e-3}, {1.5e-3, 1.5e-3, 0.5e-3}};
        double V = 0, com[3] = {0, 0, 0}, It[3][3] = {{0}};
        for (int b = 0; b < 2; ++b) {
            double v = dims[b][0] * dims[b][1] * dims[b][2];
            V += v;
            for (int i = 0; i < 3; ++i)
                com[i] += v * cen[b][i];
        }
        for (int i = 0; i < 3; ++i)
            com[i] /= V;
        for (int b = 0; b < 2; ++b) {
            double v = dims[b][0] * dims[b][1] * dims[b][2], d[3];
            for (int i = 0; i < 3; ++i)
                d[i] = cen[b][i] - com[i];
            double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            for (int i = 0; i < 3; ++i) {
                int j1 = (i + 1) % 3, j2 = (i + 2) % 3;
                It[i][i] += v * (dims[b][j1] * dims[b][j1] + dims[b][j2] * dims[b][j2]) / 12;
                for (int j = 0; j < 3; ++j)
                    It[i][j] += v * ((i == j ? dd : 0) - d[i] * d[j]);
            }
        }
        double ev[3];
        sym_eig3(It, ev);
        double got[3] = {si.inertia.x, si.inertia.y, si.inertia.z};
        sort3(got);
        CHECK_REL("L: volume", si.volume, V, 1e-12);
        CHECK_REL("L: I1", got[0], ev[0], 1e-9);
        CHECK_REL("L: I2", got[1], ev[1], 1e-9);
        CHECK_REL("L: I3", got[2], ev[2], 1e-9);
        sd_vec3 cw = sd_quat_rotate(q, sd_v3(com[0], com[1], com[2]));
        CHECK_NEAR("L: given centre of mass x", si.center_of_mass.x, off[0] + cw.x, 1e-15);
        CHECK_NEAR("L: given centre of mass y", si.center_of_mass.y, off[1] + cw.y, 1e-15);
        CHECK_NEAR("L: given centre of mass z", si.center_of_mass.z, off[2] + cw.z, 1e-15);
        /* the elements' poses map back to the given ones: x_given = c + R(given_q) e.x */
        const sd_shape *s = &w->shapes[k];
        for (int b = 0; b < 2; ++b) {
            const sd_element *el = &w->elements[s->estart + (uint32_t)b];
            sd_vec3 xg = sd_v3_add(s->given_com, sd_quat_rotate(s->given_q, el->x));
            CHECK_NEAR("L: element position back in the given frame", sd_v3_norm(sd_v3_sub(
                           xg, sd_v3((sd_real)e[b].position.x, (sd_real)e[b].position.y, (sd_real)e[b].position.z))),
                       0, 1e-15);
            sd_quat qg = sd_quat_mul(s->given_q, el->q);
            CHECK_NEAR("L: element orientation back in the given frame", sd_quat_angle_between(qg, q), 0, 1e-7);
        }
        sd_world_destroy(w);
    }

    /* two overlapping spheres (R = 1 mm, centres d = 1 mm apart): the
     * lattice takes off the lens pi (4R + d)(2R - d)^2 / 12 */
    {
        sd_world *w = new_world();
        int sph = add_sphere(w, "s", 1e-3);
        sd_composite_element e[2] = {elem(sph, 0, 0, 0), elem(sph, 1e-3, 0, 0)};
        sd_composite_desc cd = sd_composite_desc_default();
        cd.elements = e;
        cd.element_count = 2;
        cd.lattice = 100;
        int k = sd_world_add_composite(w, "twin", &cd, &err);
        sd_test_require(k >= 0, "sd_world_add_composite", &err);
        double R = 1e-3, d = 1e-3, lens = SD_PI_D * (4 * R + d) * (2 * R - d) * (2 * R - d) / 12;
        double V = 2 * 4.0 / 3 * SD_PI_D * R * R * R - lens;
        sd_shape_info si;
        CHECK_OK(sd_world_get_shape(w, (size_t)k, &si));
        CHECK(w->shapes[k].mass_lattice == 100);
        CHECK_REL("two spheres: volume (lattice 100 on the lens)", si.volume, V, 1e-3);
        CHECK_NEAR("two spheres: centre of mass x", si.center_of_mass.x, 0.5e-3, 1e-9);
        printf("two spheres: estimated error %.3g, actual %.3g\n", (double)w->shapes[k].mass_error,
               fabs(si.volume - V) / V);
        sd_world_destroy(w);
    }

    /* the seed's lattice over the whole body (seed 004 eqs. 7-8, Fig. 3)
     * converges to the exact values: a sphere, a cylinder and two
     * cylinders crossed at right angles (their intersection is the
     * Steinmetz solid: volume 16 R^3 / 3, second moments 16 R^5 / 15 along
     * the shared axis and 64 R^5 / 45 along the two others). 500 points per
     * direction take seconds per shape on two cores: that run is
     * bench/composite_lattice.c; here 50, 100, 200. */
    {
        sd_world *w = new_world();
        const double R = 1e-3, L = 6e-3;
        int sph = add_sphere(w, "s", R);
        sd_shape_desc d = sd_shape_desc_default();
        d.kind = "cylinder";
        d.size = sd_test_v(2 * R, 0, L);
        int cyl = sd_world_add_shape(w, "cyl", &d, &err);
        sd_test_require(cyl >= 0, "sd_world_add_shape", &err);
        sd_composite_pools pools = {w->shapes, w->shape_count, w->verts, w->planes, w->dtris};
        sd_quat qx = sd_quat_normalize(sd_quat_make(1, 1, 0, 0)); /* 90 deg about x: axis z -> -y */
        sd_composite_part one_s = {sph, sd_v3(0.2e-3, -0.1e-3, 0.3e-3), sd_quat_identity()};
        sd_composite_part one_c = {cyl, sd_v3(0, 0, 0), sd_quat_normalize(sd_quat_make(0.9, 0.1, 0.3, -0.2))};
        sd_composite_part two[2] = {{cyl, sd_v3(0, 0, 0), sd_quat_identity()}, {cyl, sd_v3(0, 0, 0), qx}};
        const double Vs = 4.0 / 3 * SD_PI_D * R * R * R, Is = 0.4 * Vs * R * R;
        const double Vc = SD_PI_D * R * R * L, Jr = Vc * R * R / 4, Jl = Vc * L * L / 12;
        const double Vst = 16 * R * R * R / 3, Jsh = 16 * pow(R, 5) / 15, Jot = 64 * pow(R, 5) / 45;
        /* union of cylinders along z and y: J = A + B - Steinmetz (shared axis x) */
        const double V2 = 2 * Vc - Vst, J2x = 2 * Jr - Jsh, J2y = Jr + Jl - Jot, J2z = Jr + Jl - Jot;
        const double I2[3] = {J2y + J2z, J2x + J2z, J2x + J2y};
        const double Ic_axial = 2 * Jr, Ic_trans = Jr + Jl;
        const int res[3] = {50, 100, 200};
        double err_first[3] = {0, 0, 0}, err_last[3] = {0, 0, 0};
        for (int r = 0; r < 3; ++r) {
            int n = res[r];
            sd_mass m;
            double e[3];
            CHECK_OK(sd_composite_lattice(&pools, &one_s, 1, n, 2, &m, NULL));
            double ei = fabs((double)(m.second.m[0][0] + m.second.m[1][1]) - Is) / Is;
            e[0] = fmax(fabs((double)m.volume - Vs) / Vs, ei);
            printf("lattice %3d  sphere:        volume %.6e (exact %.6e, rel. error %.2e), Izz rel. error %.2e\n", n,
                   (double)m.volume, Vs, fabs((double)m.volume - Vs) / Vs, ei);
            CHECK_OK(sd_composite_lattice(&pools, &one_c, 1, n, 2, &m, NULL));
            /* turned cylinder: the moments are the tensor's eigenvalues */
            double t[3][3], ev[3];
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    t[i][j] = (i == j ? (double)(m.second.m[0][0] + m.second.m[1][1] + m.second.m[2][2]) : 0) -
                              (double)m.second.m[i][j];
            sym_eig3(t, ev);
            double ec = fmax(fabs(ev[0] - Ic_axial) / Ic_axial, fmax(fabs(ev[1] - Ic_trans), fabs(ev[2] - Ic_trans)) / Ic_trans);
            e[1] = fmax(fabs((double)m.volume - Vc) / Vc, ec);
            printf("lattice %3d  cylinder:      volume %.6e (exact %.6e, rel. error %.2e), moments rel. error %.2e\n", n,
                   (double)m.volume, Vc, fabs((double)m.volume - Vc) / Vc, ec);
            sd_mass ex;
            CHECK_OK(sd_composite_lattice(&pools, two, 2, n, 2, &m, &ex));
            double e2 = fabs((double)m.volume - V2) / V2;
            for (int a = 0; a < 3; ++a) {
                int b = (a + 1) % 3, c = (a + 2) % 3;
                double Ia = (double)(m.second.m[b][b] + m.second.m[c][c]);
                e2 = fmax(e2, fabs(Ia - I2[a]) / I2[a]);
            }
            e[2] = e2;
            printf("lattice %3d  two cylinders: volume %.6e (exact %.6e, rel. error %.2e), worst of volume and "
                   "moments %.2e; doubly counted %.6e (exact %.6e)\n",
                   n, (double)m.volume, V2, fabs((double)m.volume - V2) / V2, e2, (double)ex.volume, Vst);
            for (int k = 0; k < 3; ++k) {
                if (r == 0)
                    err_first[k] = e[k];
                err_last[k] = e[k];
            }
        }
        const char *names[3] = {"sphere", "cylinder", "two cylinders"};
        for (int k = 0; k < 3; ++k) {
            char label[96];
            snprintf(label, sizeof label, "lattice 200, %s: worst rel. error (< 2e-3)", names[k]);
            CHECK_NEAR(label, err_last[k], 0, 2e-3);
            snprintf(label, sizeof label, "lattice %s: error at 200 below error at 50", names[k]);
            CHECK(err_last[k] < err_first[k]);
            printf("%s: error 50 -> 200: %.2e -> %.2e\n", names[k], err_first[k], err_last[k]);
        }
        /* same bits for 1 and 2 threads (integer cell sums) */
        sd_mass m1, m2, x1, x2;
        CHECK_OK(sd_composite_lattice(&pools, two, 2, 64, 1, &m1, &x1));
        CHECK_OK(sd_composite_lattice(&pools, two, 2, 64, 2, &m2, &x2));
        CHECK(memcmp(&m1, &m2, sizeof m1) == 0 && memcmp(&x1, &x2, sizeof x1) == 0);

        /* the composite itself (exact sums minus the lattice's doubly
         * counted lens) at the default resolution */
        sd_composite_element ce[2] = {elem(cyl, 0, 0, 0), elem(cyl, 0, 0, 0)};
        ce[1].orientation[0] = qx.w;
        ce[1].orientation[1] = qx.x;
        sd_composite_desc cd = sd_composite_desc_default();
        cd.elements = ce;
        cd.element_count = 2;
        int k = sd_world_add_composite(w, "cross2", &cd, &err);
        sd_test_require(k >= 0, "sd_world_add_composite", &err);
        sd_shape_info si;
        CHECK_OK(sd_world_get_shape(w, (size_t)k, &si));
        CHECK(w->shapes[k].mass_lattice == SD_COMPOSITE_LATTICE_DEFAULT);
        double got[3] = {si.inertia.x, si.inertia.y, si.inertia.z}, want[3] = {I2[0], I2[1], I2[2]};
        sort3(got);
        sort3(want);
        CHECK_REL("crossed cylinders (default lattice): volume", si.volume, V2, 1e-3);
        CHECK_REL("crossed cylinders (default lattice): I1", got[0], want[0], 1e-3);
        CHECK_REL("crossed cylinders (default lattice): I2", got[1], want[1], 1e-3);
        CHECK_REL("crossed cylinders (default lattice): I3", got[2], want[2], 1e-3);
        printf("crossed cylinders: estimated error %.2e, actual volume error %.2e\n", (double)w->shapes[k].mass_error,
               fabs(si.volume - V2) / V2);
        sd_world_destroy(w);
    }

    /* the built-in library (shape/complib.h): flush presets exact, the
     * overlapping ones against closed forms where there is one */
    {
        sd_world *w = new_world();
        struct {
            sd_comp_def d;
            double volume; /* exact, 0: none known */
            double tol;
            int exact;     /* expected without a lattice */
        } cases[8];
        memset(cases, 0, sizeof cases);
        const double L = 4e-3, D = 1e-3, W = 1e-3, T = 0.5e-3, R = 0.5 * D;
        cases[0].d = (sd_comp_def){SD_COMP_CROSS2D, L, 0, W, T, 0};
        cases[0].volume = (2 * L * W - W * W) * T;
        cases[0].tol = 1e-12;
        cases[0].exact = 1;
        /* three cylinders: 3 V_cyl - 3 Steinmetz + the tricylinder 8 (2 - sqrt 2) R^3 */
        cases[1].d = (sd_comp_def){SD_COMP_CROSS3D, L, D, 0, 0, 0};
        cases[1].volume = 3 * SD_PI_D * R * R * L - 3 * 16 * R * R * R / 3 + 8 * (2 - sqrt(2.0)) * R * R * R;
        cases[1].tol = 1e-3;
        cases[2].d = (sd_comp_def){SD_COMP_LSHAPE, L, 0, W, T, 0};
        cases[2].volume = (2 * L - W) * W * T;
        cases[2].tol = 1e-12;
        cases[2].exact = 1;
        cases[3].d = (sd_comp_def){SD_COMP_TSHAPE, L, 0, W, T, 0};
        cases[3].volume = (2 * L - W) * W * T;
        cases[3].tol = 1e-12;
        cases[3].exact = 1;
        /* ring of 12 boxes: the regular 12-gon annulus between the outer
         * 12-gon (apothem D/2) and the inner one (apothem D/2 - W), times length */
        {
            const double Dr = 8e-3, Wr = 1e-3, Lr = 2e-3;
            cases[4].d = (sd_comp_def){SD_COMP_RING, Lr, Dr, Wr, 0, 12};
            double ao = 0.5 * Dr, ai = ao - Wr, k = 12 * tan(SD_PI_D / 12);
            cases[4].volume = k * (ao * ao - ai * ai) * Lr;
            /* the 0.2 % target: 9.5e-5 measured with a lattice per overlapping
             * pair (2.7e-3 with one lattice over all the overlaps) */
            cases[4].tol = 2e-3;
        }
        /* dumbbell: two spheres + the bar, less the bar inside each sphere
         * (a cylinder to the sphere's surface and the cap beyond it) */
        {
            const double Dd = 2e-3, Ld = 4e-3, wb = 0.5e-3, Rs = 0.5 * Dd, rb = 0.5 * wb;
            cases[5].d = (sd_comp_def){SD_COMP_DUMBBELL, Ld, Dd, wb, 0, 0};
            double c = sqrt(Rs * Rs - rb * rb), h = Rs - c;
            double inside = SD_PI_D * rb * rb * c + SD_PI_D * h * h * (3 * Rs - h) / 3;
            cases[5].volume = 2 * 4.0 / 3 * SD_PI_D * pow(Rs, 3) + SD_PI_D * rb * rb * Ld - 2 * inside;
            cases[5].tol = 1e-3;
        }
        cases[6].d = (sd_comp_def){SD_COMP_SPHERES9, 5.3e-3, 8e-3, 0, 0, 0};
        cases[7].d = (sd_comp_def){SD_COMP_SPHERES54, 5.3e-3, 8e-3, 0, 0, 0};
        for (int c = 0; c < 8; ++c) {
            sd_comp_part parts[SD_COMP_MAX_PARTS];
            size_t np = 0;
            CHECK_OK(sd_complib_parts(&cases[c].d, parts, SD_COMP_MAX_PARTS, &np, &err));
            sd_composite_element ce[SD_COMP_MAX_PARTS];
            for (size_t k = 0; k < np; ++k) {
                char nm[32];
                snprintf(nm, sizeof nm, "p%d_%zu", c, k);
                sd_shape_desc d = sd_shape_desc_default();
                d.kind = parts[k].kind;
                d.size = parts[k].size;
                ce[k].shape = sd_world_add_shape(w, nm, &d, &err);
                sd_test_require(ce[k].shape >= 0, "sd_world_add_shape (preset part)", &err);
                ce[k].position = parts[k].position;
                memcpy(ce[k].orientation, parts[k].orientation, sizeof ce[k].orientation);
            }
            sd_composite_desc cd = sd_composite_desc_default();
            cd.elements = ce;
            cd.element_count = np;
            int k = sd_world_add_composite(w, sd_complib_name(cases[c].d.preset), &cd, &err);
            sd_test_require(k >= 0, "sd_world_add_composite (preset)", &err);
            sd_shape_info si;
            CHECK_OK(sd_world_get_shape(w, (size_t)k, &si));
            char label[96];
            if (cases[c].volume > 0) {
                snprintf(label, sizeof label, "preset %s: volume", sd_complib_name(cases[c].d.preset));
                CHECK_REL(label, si.volume, cases[c].volume, cases[c].tol);
            } else {
                printf("preset %s: %zu elements, volume %.4e m^3, moments %.4e %.4e %.4e m^5, lattice %d, est. "
                       "error %.1e\n",
                       sd_complib_name(cases[c].d.preset), np, si.volume, si.inertia.x, si.inertia.y, si.inertia.z,
                       si.lattice, si.lattice_error);
            }
            CHECK((si.lattice == 0) == cases[c].exact);
        }
        /* Table 2 of seed 004 gives the 9-sphere cylinder (D 8 mm, L 5.3 mm)
         * a volume of 1.948e-7 m^3 and the 54-sphere one 2.244e-7, whose
         * layout the paper does not give: ours (shape/complib.c) takes its
         * sphere radius from that volume; with the two layers of spheres
         * of diameter L/2 it had before, touching at the mid-plane, it
         * held 2.168e-7 (-3.4 %) and failed here */
        int k9 = sd_world_find_shape(w, "spheres9");
        sd_shape_info si;
        CHECK_OK(sd_world_get_shape(w, (size_t)k9, &si));
        CHECK_REL("spheres9: volume against seed 004 Table 2 (1.948e-7, 3 digits)", si.volume, 1.948e-7, 1e-3);
        int k54 = sd_world_find_shape(w, "spheres54");
        CHECK_OK(sd_world_get_shape(w, (size_t)k54, &si));
        CHECK_REL("spheres54: volume against seed 004 Table 2 (2.244e-7, 0.5 %)", si.volume, 2.244e-7, 5e-3);
        /* bad parameters name the key */
        sd_comp_part parts[SD_COMP_MAX_PARTS];
        size_t np;
        sd_comp_def bad = {SD_COMP_RING, 2e-3, 8e-3, 1e-3, 0, 2};
        CHECK(sd_complib_parts(&bad, parts, SD_COMP_MAX_PARTS, &np, &err) == SD_ERR_INPUT && !strcmp(err.key, "count"));
        bad = (sd_comp_def){SD_COMP_CROSS2D, 1e-3, 0, 2e-3, 1e-3, 0};
        CHECK(sd_complib_parts(&bad, parts, SD_COMP_MAX_PARTS, &np, &err) == SD_ERR_INPUT && !strcmp(err.key, "width"));
        bad = (sd_comp_def){SD_COMP_CROSS3D, 0, 1e-3, 0, 0, 0};
        CHECK(sd_complib_parts(&bad, parts, SD_COMP_MAX_PARTS, &np, &err) == SD_ERR_INPUT && !strcmp(err.key, "length"));
        sd_world_destroy(w);
    }

    /* bad input: one message each, nothing added */
    {
        sd_world *w = new_world();
        int cube = add_box(w, "c", 1e-3, 1e-3, 1e-3);
        sd_composite_element e[2] = {elem(cube, 0, 0, 0), elem(cube, 1e-3, 0, 0)};
        sd_composite_desc cd = sd_composite_desc_default();
        cd.elements = e;
        cd.element_count = 0;
        CHECK(sd_world_add_composite(w, "none", &cd, &err) < 0 && strcmp(err.key, "elements") == 0);
        cd.element_count = 2;
        e[1].shape = 7;
        CHECK(sd_world_add_composite(w, "bad", &cd, &err) < 0 && strstr(err.msg, "unknown shape"));
        e[1].shape = cube;
        cd.lattice = 2;
        CHECK(sd_world_add_composite(w, "bad", &cd, &err) < 0 && strcmp(err.key, "lattice") == 0);
        cd.lattice = 0;
        e[1].position.x = NAN;
        CHECK(sd_world_add_composite(w, "bad", &cd, &err) < 0 && strstr(err.msg, "not finite"));
        e[1].position.x = 1e-3;
        int k = sd_world_add_composite(w, "ok", &cd, &err);
        CHECK(k == 1);
        sd_composite_element nest = elem(k, 0, 0, 0);
        cd.elements = &nest;
        cd.element_count = 1;
        CHECK(sd_world_add_composite(w, "nested", &cd, &err) < 0 && strstr(err.msg, "convex"));
        CHECK(sd_world_add_composite(w, "ok", &cd, &err) < 0 && strstr(err.msg, "twice"));
        sd_composite_desc raw;
        memset(&raw, 0, sizeof raw);
        CHECK(sd_world_add_composite(w, "raw", &raw, &err) < 0);
        CHECK(sd_world_shape_count(w) == 2 && w->element_count == 2);
        sd_world_destroy(w);
    }
    return sd_test_summary();
}
