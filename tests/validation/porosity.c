/* porosity.c — the voxel porosity of shapedem/analysis.h (seed 004 §4.1)
 * against packings with known answers, each at 2-3 lattice resolutions:
 *  - spheres on a simple cubic lattice fill pi/6 of their cells
 *    (porosity 1 - pi/6): the error at the finest lattice (64 voxels per
 *    diameter) is below 2e-3 and below that of the coarsest;
 *  - cubes face to face fill their box: porosity 0 at every resolution;
 *  - a single regular tetrahedron (randomly turned): solid voxels x voxel
 *    volume converges to a^3 / (6 sqrt 2);
 *  - a composite of two overlapping spheres: the union's volume (the lens
 *    counted once), against the closed form;
 *  - 2D circles on a square lattice: area fraction pi/4;
 *  - the radial profile of a cylinder region around a coaxial cylinder of
 *    half its radius: solid inside, empty outside;
 *  - a periodic box: a sphere across the boundary counts with its image;
 *  - one body of every kind (rounded box, cylinder, cone, ellipsoid,
 *    rounded octahedron; 2D ellipse, rounded triangle, Fourier shape),
 *    turned: its voxel volume or area within 0.3 % of the template's;
 *  - 150 random spheres and turned tetrahedra, apart and inside a box:
 *    the sum of their volumes over the box's, within 0.2 % at a voxel of
 *    an eighth of the smallest radius;
 *  - 1 and 2 threads: the same counts.
 */
#include <math.h>
#include <string.h>

#include "test.h"

#include <shapedem/analysis.h>

static const double PI = 3.14159265358979323846;

static sd_world *new_world(int dim, int threads, int *mat)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.threads = threads;
    d.dimension = dim;
    d.dt = 1e-6;
    if (dim == 2)
        d.gravity = sd_test_v(0, -9.81, 0);
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "m";
    m.youngs_modulus = 1e7;
    *mat = sd_world_add_material(w, &m, &err);
    return w;
}

static sd_porosity box_porosity(const sd_world *w, sd_v3d lo, sd_v3d hi, double voxel, int threads)
{
    sd_error err;
    sd_porosity_def d = sd_porosity_def_default();
    d.region.kind = SD_REGION_BOX;
    d.region.lo = lo;
    d.region.hi = hi;
    d.voxel = voxel;
    d.threads = threads;
    sd_porosity po;
    sd_test_require(sd_world_porosity(w, &d, &po, NULL, NULL, &err) == SD_OK, "porosity", &err);
    return po;
}

static void spheres_lattice(void)
{
    printf("-- spheres on a simple cubic lattice, 4 x 4 x 4 (expected porosity 1 - pi/6)\n");
    int mat;
    sd_world *w = new_world(3, 2, &mat);
    const double r = 0.001, d = 2 * r;
    sd_sphere_def s[64];
    memset(s, 0, sizeof s);
    for (int k = 0; k < 64; ++k) {
        s[k].position = sd_test_v((k % 4 + 0.5) * d, (k / 4 % 4 + 0.5) * d, (k / 16 + 0.5) * d);
        s[k].radius = r;
        s[k].material = mat;
    }
    sd_error err;
    sd_test_require(sd_world_add_spheres(w, 64, s, &err) == SD_OK, "spheres", &err);
    const double expect = 1 - PI / 6;
    const int per_d[3] = {16, 32, 64}; /* voxels per diameter */
    double e[3];
    for (int k = 0; k < 3; ++k) {
        sd_porosity po = box_porosity(w, sd_test_v(0, 0, 0), sd_test_v(4 * d, 4 * d, 4 * d), d / per_d[k], 0);
        e[k] = fabs(po.porosity - expect);
        printf("   %2d voxels per diameter (%lld voxels): porosity %.6f, expected %.6f, error %.2e\n", per_d[k],
               po.voxels, po.porosity, expect, e[k]);
    }
    CHECK(e[2] < e[0]);
    CHECK_NEAR("porosity, 64 voxels per diameter", e[2] + expect, expect, 2e-3);
    /* the same counts on 1 and 2 threads */
    sd_porosity p1 = box_porosity(w, sd_test_v(0, 0, 0), sd_test_v(4 * d, 4 * d, 4 * d), d / 16, 1);
    sd_porosity p2 = box_porosity(w, sd_test_v(0, 0, 0), sd_test_v(4 * d, 4 * d, 4 * d), d / 16, 2);
    printf("   1 thread %lld solid of %lld, 2 threads %lld of %lld\n", p1.solid, p1.voxels, p2.solid, p2.voxels);
    CHECK(p1.solid == p2.solid && p1.voxels == p2.voxels);
    sd_world_destroy(w);
}

static void cubes_face_to_face(void)
{
    printf("-- 27 cubes face to face, turned by 90 degrees about z (expected porosity 0)\n");
    int mat;
    sd_world *w = new_world(3, 2, &mat);
    const double a = 0.002;
    sd_error err;
    sd_shape_desc sd = sd_shape_desc_default();
    sd.kind = "box";
    sd.size = sd_test_v(a, a, a);
    int cube = sd_world_add_shape(w, "cube", &sd, &err);
    sd_test_require(cube >= 0, "cube", &err);
    sd_body_def b[27];
    memset(b, 0, sizeof b);
    for (int k = 0; k < 27; ++k) {
        b[k].position = sd_test_v((k % 3 + 0.5) * a, (k / 3 % 3 + 0.5) * a, (k / 9 + 0.5) * a);
        b[k].shape = cube;
        b[k].material = mat;
        b[k].orientation[0] = cos(PI / 4); /* a quarter turn: the faces stay on the lattice */
        b[k].orientation[3] = sin(PI / 4);
    }
    sd_test_require(sd_world_add_bodies(w, 27, b, &err) == SD_OK, "cubes", &err);
    const int per_a[3] = {4, 10, 20};
    for (int k = 0; k < 3; ++k) {
        sd_porosity po = box_porosity(w, sd_test_v(0, 0, 0), sd_test_v(3 * a, 3 * a, 3 * a), a / per_a[k], 0);
        char label[96];
        snprintf(label, sizeof label, "porosity, %d voxels per edge (%lld)", per_a[k], po.voxels);
        CHECK_NEAR(label, po.porosity, 0.0, 0.0);
    }
    /* a box twice as tall: half empty */
    sd_porosity po = box_porosity(w, sd_test_v(0, 0, 0), sd_test_v(3 * a, 3 * a, 6 * a), a / 10, 0);
    CHECK_NEAR("porosity of a box twice the height", po.porosity, 0.5, 0.0);
    sd_world_destroy(w);
}

static void tetrahedron(void)
{
    printf("-- one regular tetrahedron, turned (expected volume a^3 / (6 sqrt 2))\n");
    int mat;
    sd_world *w = new_world(3, 2, &mat);
    const double s = 0.001; /* vertices (+-s, +-s, +-s) with an even number of minus signs */
    const sd_v3d v[4] = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
    const double edge = 2 * sqrt(2.0) * s, vol = edge * edge * edge / (6 * sqrt(2.0));
    sd_error err;
    sd_shape_desc sd = sd_shape_desc_default();
    sd.kind = "polyhedron";
    sd.vertices = v;
    sd.vertex_count = 4;
    int tet = sd_world_add_shape(w, "tet", &sd, &err);
    sd_test_require(tet >= 0, "tetrahedron", &err);
    sd_body_def b;
    memset(&b, 0, sizeof b);
    b.position = sd_test_v(0.0101, 0.0203, 0.0302);
    double q[4] = {0.9, 0.3, -0.2, 0.25}, qn = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int k = 0; k < 4; ++k)
        b.orientation[k] = q[k] / qn;
    b.shape = tet;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    const int per_edge[3] = {10, 20, 40};
    double e[3];
    const double h = 1.2 * edge; /* the box around it: its bounding sphere fits */
    for (int k = 0; k < 3; ++k) {
        sd_porosity po =
            box_porosity(w, sd_test_v(b.position.x - h, b.position.y - h, b.position.z - h),
                         sd_test_v(b.position.x + h, b.position.y + h, b.position.z + h), edge / per_edge[k], 0);
        double got = (double)po.solid * po.voxel[0] * po.voxel[1] * po.voxel[2];
        e[k] = fabs(got - vol) / vol;
        printf("   %2d voxels per edge: volume %.6e m^3, expected %.6e, relative error %.2e\n", per_edge[k], got, vol,
               e[k]);
    }
    CHECK(e[2] < e[0]);
    CHECK_NEAR("tetrahedron volume, relative error at 40 per edge", e[2], 0.0, 5e-3);
    sd_world_destroy(w);
}

static void composite_union(void)
{
    printf("-- a composite of two spheres overlapping by half a radius (expected the union's volume)\n");
    int mat;
    sd_world *w = new_world(3, 2, &mat);
    const double r = 0.001, c = 0.75 * r; /* centres at +-c: a lens of height 2r - 2c */
    sd_error err;
    sd_shape_desc sd = sd_shape_desc_default();
    sd.kind = "sphere";
    sd.size = sd_test_v(r, 0, 0);
    int sph = sd_world_add_shape(w, "ball", &sd, &err);
    sd_test_require(sph >= 0, "sphere template", &err);
    sd_composite_element el[2];
    memset(el, 0, sizeof el);
    el[0].shape = el[1].shape = sph;
    el[0].position = sd_test_v(-c, 0, 0);
    el[1].position = sd_test_v(c, 0, 0);
    sd_composite_desc cd = sd_composite_desc_default();
    cd.elements = el;
    cd.element_count = 2;
    int comp = sd_world_add_composite(w, "pair", &cd, &err);
    sd_test_require(comp >= 0, "composite", &err);
    sd_body_def b;
    memset(&b, 0, sizeof b);
    b.shape = comp;
    b.material = mat;
    b.orientation[0] = cos(0.3);
    b.orientation[2] = sin(0.3);
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    const double hcap = r - c, lens = 2 * PI * hcap * hcap * (3 * r - hcap) / 3;
    const double vol = 2 * (4 * PI * r * r * r / 3) - lens;
    sd_porosity po = box_porosity(w, sd_test_v(-2 * r, -2 * r, -2 * r), sd_test_v(2 * r, 2 * r, 2 * r), r / 25, 0);
    double got = (double)po.solid * po.voxel[0] * po.voxel[1] * po.voxel[2];
    CHECK_REL("composite union volume (m^3), 50 voxels per diameter", got, vol, 5e-3);
    sd_world_destroy(w);
}

static void circles_2d(void)
{
    printf("-- 2D: circles on a square lattice (expected area fraction pi/4)\n");
    int mat;
    sd_world *w = new_world(2, 2, &mat);
    const double r = 0.001, d = 2 * r;
    sd_sphere_def s[25];
    memset(s, 0, sizeof s);
    for (int k = 0; k < 25; ++k) {
        s[k].position = sd_test_v((k % 5 + 0.5) * d, (k / 5 + 0.5) * d, 0);
        s[k].radius = r;
        s[k].material = mat;
    }
    sd_error err;
    sd_test_require(sd_world_add_spheres(w, 25, s, &err) == SD_OK, "circles", &err);
    const int per_d[3] = {10, 40, 160};
    double e[3];
    for (int k = 0; k < 3; ++k) {
        sd_porosity po = box_porosity(w, sd_test_v(0, 0, 0), sd_test_v(5 * d, 5 * d, 0), d / per_d[k], 0);
        e[k] = fabs(po.solid_fraction - PI / 4);
        printf("   %2d pixels per diameter (%lld): area fraction %.6f, expected %.6f, error %.2e\n", per_d[k],
               po.voxels, po.solid_fraction, PI / 4, e[k]);
    }
    CHECK(e[2] < e[0]);
    CHECK_NEAR("2D area fraction, 160 pixels per diameter", e[2] + PI / 4, PI / 4, 2e-3);
    sd_world_destroy(w);
}

static void radial_profile(void)
{
    printf("-- radial profile: a cylinder region about a coaxial cylinder of half its radius\n");
    int mat;
    sd_world *w = new_world(3, 2, &mat);
    const double R = 0.01, L = 0.01;
    sd_error err;
    sd_shape_desc sd = sd_shape_desc_default();
    sd.kind = "cylinder";
    sd.size = sd_test_v(R, 0, 2 * L); /* diameter R: radius R/2; longer than the region */
    int cyl = sd_world_add_shape(w, "rod", &sd, &err);
    sd_test_require(cyl >= 0, "cylinder", &err);
    sd_body_def b;
    memset(&b, 0, sizeof b);
    b.shape = cyl;
    b.material = mat;
    /* the rod along x (a quarter turn about y), the region's axis too */
    b.orientation[0] = cos(PI / 4);
    b.orientation[2] = sin(PI / 4);
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "rod", &err);
    sd_porosity_def d = sd_porosity_def_default();
    d.region.kind = SD_REGION_CYLINDER;
    d.region.axis = sd_test_v(1, 0, 0);
    d.region.radius = R;
    d.region.length = L;
    d.voxel = R / 40;
    d.radial_bins = 4;
    long long rs[4], rv[4];
    sd_porosity po;
    sd_test_require(sd_world_porosity(w, &d, &po, rs, rv, &err) == SD_OK, "radial", &err);
    for (int k = 0; k < 4; ++k) {
        char label[64];
        snprintf(label, sizeof label, "solid fraction of annulus %d (%lld voxels)", k, rv[k]);
        CHECK_NEAR(label, (double)rs[k] / (double)rv[k], k < 2 ? 1.0 : 0.0, 0.0);
    }
    CHECK_NEAR("solid fraction of the cylinder region", po.solid_fraction, 0.25, 0.01);
    sd_world_destroy(w);
}

static void periodic_image(void)
{
    printf("-- periodic box: a sphere across x = 0 counts with its image\n");
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.dt = 1e-6;
    wd.periodic = SD_PERIODIC_X;
    wd.domain_lo = sd_test_v(0, 0, 0);
    wd.domain_hi = sd_test_v(0.01, 0.01, 0.01);
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    int mat = sd_world_add_material(w, &m, &err);
    sd_sphere_def s;
    memset(&s, 0, sizeof s);
    s.position = sd_test_v(0.0002, 0.005, 0.005);
    s.radius = 0.001;
    s.material = mat;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    sd_porosity po = box_porosity(w, sd_test_v(0, 0.0035, 0.0035), sd_test_v(0.01, 0.0065, 0.0065), 0.00004, 0);
    double got = (double)po.solid * po.voxel[0] * po.voxel[1] * po.voxel[2], vol = 4 * PI * 1e-9 / 3;
    CHECK_REL("sphere volume across the periodic boundary (m^3)", got, vol, 5e-3);
    sd_world_destroy(w);
}

/* One body of template `shape` at a turned pose; its voxel volume against
 * the template's own (sd_world_get_shape). */
static void one_kind(sd_world *w, int mat, int shape, const char *what, int dim2)
{
    sd_error err;
    sd_shape_info si;
    sd_test_require(shape >= 0 && sd_world_get_shape(w, (size_t)shape, &si) == SD_OK, what, &err);
    sd_body_def b;
    memset(&b, 0, sizeof b);
    b.shape = shape;
    b.material = mat;
    b.position = sd_test_v(0.1 * (shape + 1), dim2 ? 0.05 : 0.03, dim2 ? 0.0 : 0.02);
    if (dim2) {
        b.orientation[0] = cos(0.35);
        b.orientation[3] = sin(0.35);
    } else {
        double q[4] = {0.8, 0.35, -0.3, 0.4}, qn = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        for (int k = 0; k < 4; ++k)
            b.orientation[k] = q[k] / qn;
    }
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, what, &err);
    const double R = si.bounding_radius * 1.05, h = si.bounding_radius / 60;
    sd_porosity po = box_porosity(w, sd_test_v(b.position.x - R, b.position.y - R, dim2 ? 0 : b.position.z - R),
                                  sd_test_v(b.position.x + R, b.position.y + R, dim2 ? 0 : b.position.z + R), h, 0);
    double got = (double)po.solid * po.voxel[0] * po.voxel[1] * (dim2 ? 1.0 : po.voxel[2]);
    char label[96];
    snprintf(label, sizeof label, "%s %s (bounding radius / 60)", what, dim2 ? "area (m^2)" : "volume (m^3)");
    CHECK_REL(label, got, si.volume, 3e-3);
}

static void every_kind(void)
{
    printf("-- every shape kind, turned: voxel volume (area) against the template's\n");
    int mat;
    sd_world *w = new_world(3, 2, &mat);
    sd_error err;
    sd_shape_desc d = sd_shape_desc_default();
    d.kind = "box";
    d.size = sd_test_v(0.004, 0.002, 0.003);
    d.rounding = 0.0004;
    one_kind(w, mat, sd_world_add_shape(w, "rbox", &d, &err), "rounded box", 0);
    d = sd_shape_desc_default();
    d.kind = "cylinder";
    d.size = sd_test_v(0.004, 0, 0.003);
    one_kind(w, mat, sd_world_add_shape(w, "cyl", &d, &err), "cylinder", 0);
    d.kind = "cone";
    d.size = sd_test_v(0.004, 0, 0.004);
    one_kind(w, mat, sd_world_add_shape(w, "cone", &d, &err), "cone", 0);
    d.kind = "ellipsoid";
    d.size = sd_test_v(0.003, 0.002, 0.0012);
    one_kind(w, mat, sd_world_add_shape(w, "ell", &d, &err), "ellipsoid", 0);
    const sd_v3d oct[6] = {{0.002, 0, 0}, {-0.002, 0, 0}, {0, 0.002, 0}, {0, -0.002, 0}, {0, 0, 0.002}, {0, 0, -0.002}};
    d = sd_shape_desc_default();
    d.kind = "polyhedron";
    d.vertices = oct;
    d.vertex_count = 6;
    d.rounding = 0.0003;
    one_kind(w, mat, sd_world_add_shape(w, "roct", &d, &err), "rounded octahedron", 0);
    sd_world_destroy(w);

    w = new_world(2, 2, &mat);
    sd_shape2d_def d2 = sd_shape2d_def_default();
    d2.kind = "ellipse";
    d2.semi_axes[0] = 0.003;
    d2.semi_axes[1] = 0.0015;
    one_kind(w, mat, sd_world_add_shape2d(w, "ell2", &d2, &err), "ellipse", 1);
    const double tri[6] = {0, 0, 0.004, 0, 0.001, 0.003};
    d2 = sd_shape2d_def_default();
    d2.kind = "polygon";
    d2.points = tri;
    d2.point_count = 3;
    d2.radius = 0.0003;
    one_kind(w, mat, sd_world_add_shape2d(w, "rtri", &d2, &err), "rounded triangle", 1);
    const double fa[3] = {0.006, 0.0, 0.0004}, fb[2] = {0.0, 0.0002};
    d2 = sd_shape2d_def_default();
    d2.kind = "fourier";
    d2.fourier_a = fa;
    d2.fourier_b = fb;
    d2.order = 2;
    one_kind(w, mat, sd_world_add_shape2d(w, "four", &d2, &err), "Fourier shape", 1);
    sd_world_destroy(w);
}

/* Random sequential addition of bounding spheres in a box, fully inside
 * it and apart: the exact solid fraction is then the sum of the bodies'
 * volumes over the box's. Half spheres of radius 0.4-0.8 mm, half turned
 * tetrahedra (edge 1.41 mm): no alignment with the lattice. */
static void random_mix(void)
{
    printf("-- 150 random spheres and tetrahedra, apart, in a 1.2 cm box (expected sum of volumes / box)\n");
    int mat;
    sd_world *w = new_world(3, 2, &mat);
    sd_error err;
    const double s = 0.0005, L = 0.012;
    const sd_v3d v[4] = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
    sd_shape_desc sd = sd_shape_desc_default();
    sd.kind = "polyhedron";
    sd.vertices = v;
    sd.vertex_count = 4;
    int tet = sd_world_add_shape(w, "tet", &sd, &err);
    sd_shape_info si;
    sd_test_require(tet >= 0 && sd_world_get_shape(w, (size_t)tet, &si) == SD_OK, "tetrahedron", &err);
    enum { N = 150 };
    double x[N][3], rb[N], total = 0;
    unsigned long long st = 88172645463325252ull;
    int n = 0;
    for (int tries = 0; n < N && tries < 200000; ++tries) {
        double u[7];
        for (int k = 0; k < 7; ++k) { /* xorshift64: a fixed sequence */
            st ^= st << 13, st ^= st >> 7, st ^= st << 17;
            u[k] = (double)(st >> 11) / 9007199254740992.0;
        }
        double r = n % 2 ? si.bounding_radius : 0.0004 + 0.0004 * u[3];
        double p[3] = {r + (L - 2 * r) * u[0], r + (L - 2 * r) * u[1], r + (L - 2 * r) * u[2]};
        int ok = 1;
        for (int j = 0; j < n && ok; ++j) {
            double dx = p[0] - x[j][0], dy = p[1] - x[j][1], dz = p[2] - x[j][2];
            ok = dx * dx + dy * dy + dz * dz > (r + rb[j]) * (r + rb[j]);
        }
        if (!ok)
            continue;
        x[n][0] = p[0], x[n][1] = p[1], x[n][2] = p[2], rb[n] = r;
        if (n % 2) {
            sd_body_def b;
            memset(&b, 0, sizeof b);
            b.position = sd_test_v(p[0], p[1], p[2]);
            double q[4] = {u[4] - 0.5, u[5] - 0.5, u[6] - 0.5, 0.3}, qn = 0;
            for (int k = 0; k < 4; ++k)
                qn += q[k] * q[k];
            for (int k = 0; k < 4; ++k)
                b.orientation[k] = q[k] / sqrt(qn);
            b.shape = tet;
            b.material = mat;
            sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "tetrahedron", &err);
            total += si.volume;
        } else {
            sd_sphere_def sp;
            memset(&sp, 0, sizeof sp);
            sp.position = sd_test_v(p[0], p[1], p[2]);
            sp.radius = r;
            sp.material = mat;
            sd_test_require(sd_world_add_spheres(w, 1, &sp, &err) == SD_OK, "sphere", &err);
            total += 4 * PI * r * r * r / 3;
        }
        n++;
    }
    const double expect = total / (L * L * L);
    const double vox[3] = {0.0002, 0.0001, 0.00005};
    double e[3];
    for (int k = 0; k < 3; ++k) {
        sd_porosity po = box_porosity(w, sd_test_v(0, 0, 0), sd_test_v(L, L, L), vox[k], 0);
        e[k] = fabs(po.solid_fraction - expect) / expect;
        printf("   voxel %.2g m (%lld voxels): solid fraction %.6f, expected %.6f, relative error %.2e\n", vox[k],
               po.voxels, po.solid_fraction, expect, e[k]);
    }
    printf("   %d bodies placed\n", n);
    CHECK(n == N);
    CHECK(e[2] < e[0]);
    CHECK_NEAR("random mix, relative error at voxel 0.05 mm", e[2], 0.0, 2e-3);
    sd_world_destroy(w);
}

int main(void)
{
    spheres_lattice();
    cubes_face_to_face();
    tetrahedron();
    composite_union();
    circles_2d();
    radial_profile();
    periodic_image();
    every_kind();
    random_mix();
    return sd_test_summary();
}
