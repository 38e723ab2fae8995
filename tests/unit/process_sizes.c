/* process_sizes.c — size distributions for templates of every kind
 * (issue 16; world/scaled.c, world/process.c's size classes):
 *  - a scaled copy (sd_world_add_scaled_shape) of a box, a rounded
 *    cylinder, a polyhedron, a composite and a 2D polygon has the volume,
 *    moments and bounding radius of the same template built afresh at
 *    that scale (desc.scale, scaled elements and points), to 1e-12;
 *  - an insertion of a cube (log-normal equivalent radius), a polyhedron
 *    (uniform) and a composite (normal), 3,000 in all: everything asked
 *    for goes in with no bounding spheres overlapping, the mix follows
 *    its fractions (chi square at 1 %), each scaled copy's equivalent
 *    radius lies inside its class (the law's equal-probability quantiles,
 *    computed here from the law's own distribution function), the counts
 *    per class are equal (chi square at 1 %) and the classes' mean volume
 *    is the law's E[r^3] (quadrature here) to 0.1 %;
 *  - a mix by mass of spheres and log-normal cubes: the counts follow the
 *    number fractions the masses imply (chi square at 1 %);
 *  - 2D: polygons graded by a sieve table by mass: the counts per sieve
 *    class follow the number fractions f / E[r^2] (chi square at 1 %);
 *  - bad input: a negative radius for a template's law, too many classes,
 *    a later entry's unknown material: each refused with its key and no
 *    scaled copy left behind.
 */
#include <math.h>
#include <string.h>

#include "test.h"

#include <shapedem/process.h>


/* chi-square 1 % critical values, 1 .. 15 degrees of freedom */
static const double chi2_crit[16] = {0,      6.635,  9.210,  11.345, 13.277, 15.086, 16.812, 18.475,
                                     20.090, 21.666, 23.209, 24.725, 26.217, 27.688, 29.141, 30.578};

static double chi2(const size_t *obs, const double *p, int k, size_t n)
{
    double c = 0;
    for (int i = 0; i < k; ++i) {
        double e = p[i] * (double)n;
        c += ((double)obs[i] - e) * ((double)obs[i] - e) / e;
    }
    return c;
}

static double phi(double z) { return 0.5 * erfc(-z / sqrt(2.0)); }

/* The truncated law's distribution function (uniform, normal, log-normal). */
static double law_cdf(const sd_size_def *s, double r)
{
    if (s->kind == SD_SIZE_UNIFORM)
        return r <= s->a ? 0 : r >= s->b ? 1 : (r - s->a) / (s->b - s->a);
    double lo = s->min, hi = s->max;
    if (s->kind == SD_SIZE_NORMAL) {
        double a = phi((lo - s->a) / s->b), b = phi((hi - s->a) / s->b);
        return (phi((fmin(fmax(r, lo), hi) - s->a) / s->b) - a) / (b - a);
    }
    double a = phi(log(lo / s->a) / s->b), b = phi(log(hi / s->a) / s->b);
    return (phi(log(fmin(fmax(r, lo), hi) / s->a) / s->b) - a) / (b - a);
}

static double law_lo(const sd_size_def *s) { return s->kind == SD_SIZE_UNIFORM ? s->a : s->min; }
static double law_hi(const sd_size_def *s) { return s->kind == SD_SIZE_UNIFORM ? s->b : s->max; }

/* The radius with F(r) = u, by bisection. */
static double law_quantile(const sd_size_def *s, double u)
{
    double lo = law_lo(s), hi = law_hi(s);
    for (int k = 0; k < 200; ++k) {
        double m = 0.5 * (lo + hi);
        if (law_cdf(s, m) < u)
            lo = m;
        else
            hi = m;
    }
    return 0.5 * (lo + hi);
}

/* E[r^3] of the law, Simpson on F's increments over 20,000 cells. */
static double law_moment3(const sd_size_def *s)
{
    int n = 20000;
    double lo = law_lo(s), hi = law_hi(s), h = (hi - lo) / n, m = 0;
    for (int k = 0; k < n; ++k) {
        double a = lo + k * h, b = a + h, c = 0.5 * (a + b);
        double fa = law_cdf(s, a), fb = law_cdf(s, b);
        m += (fb - fa) * (a * a * a + 4 * c * c * c + b * b * b) / 6;
    }
    return m;
}

static void require_shape(const sd_world *w, int k, sd_shape_info *si)
{
    sd_test_require(k >= 0 && sd_world_get_shape(w, (size_t)k, si) == SD_OK, "shape info", NULL);
}

static void same_shape(const char *what, const sd_world *w, int a, int b)
{
    sd_shape_info x, y;
    require_shape(w, a, &x);
    require_shape(w, b, &y);
    char label[96];
    snprintf(label, sizeof label, "%s: volume (rel)", what);
    CHECK_REL(label, x.volume, y.volume, 1e-12);
    snprintf(label, sizeof label, "%s: bounding radius (rel)", what);
    CHECK_REL(label, x.bounding_radius, y.bounding_radius, 1e-12);
    double dm = 0;
    dm = fmax(dm, fabs(x.inertia.x - y.inertia.x));
    dm = fmax(dm, fabs(x.inertia.y - y.inertia.y));
    dm = fmax(dm, fabs(x.inertia.z - y.inertia.z));
    snprintf(label, sizeof label, "%s: principal moments (rel)", what);
    CHECK_NEAR(label, dm / fabs(y.inertia.x), 0, 1e-12);
}

static sd_world *world3d(int *mat)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dt = 1e-5;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    *mat = sd_world_add_material(w, &m, &err);
    return w;
}

static const sd_v3d tetra[5] = {{0.001, 0.0002, 0}, {-0.0008, 0.0009, 0.0001}, {-0.0004, -0.001, 0.0002},
                                {0.0001, 0.0001, 0.0012}, {0.0002, -0.0001, -0.0007}};

static void test_copies(void)
{
    sd_error err;
    int mat;
    sd_world *w = world3d(&mat);
    double s = 1.7;
    sd_shape_desc d = sd_shape_desc_default();
    d.kind = "box";
    d.size = sd_test_v(0.002, 0.003, 0.004);
    int box = sd_world_add_shape(w, "box", &d, &err);
    d.scale = s;
    int box_fresh = sd_world_add_shape(w, "box_fresh", &d, &err);
    same_shape("box x 1.7", w, sd_world_add_scaled_shape(w, box, s, "box_copy", &err), box_fresh);

    d = sd_shape_desc_default();
    d.kind = "cylinder";
    d.size = sd_test_v(0.003, 0, 0.002);
    d.rounding = 0.0002;
    int cyl = sd_world_add_shape(w, "cyl", &d, &err);
    d.scale = 0.45;
    int cyl_fresh = sd_world_add_shape(w, "cyl_fresh", &d, &err);
    same_shape("rounded cylinder x 0.45", w, sd_world_add_scaled_shape(w, cyl, 0.45, "cyl_copy", &err), cyl_fresh);

    d = sd_shape_desc_default();
    d.kind = "polyhedron";
    d.vertices = tetra;
    d.vertex_count = 5;
    int poly = sd_world_add_shape(w, "poly", &d, &err);
    d.scale = 2.3;
    int poly_fresh = sd_world_add_shape(w, "poly_fresh", &d, &err);
    same_shape("polyhedron x 2.3", w, sd_world_add_scaled_shape(w, poly, 2.3, "poly_copy", &err), poly_fresh);

    /* a composite of two boxes, apart (exact sums), and its fresh build on scaled elements */
    sd_composite_element el[2];
    memset(el, 0, sizeof el);
    el[0].shape = box;
    el[0].position = sd_test_v(0, 0, 0);
    el[1].shape = poly;
    el[1].position = sd_test_v(0.006, 0.001, 0);
    sd_composite_desc cd = sd_composite_desc_default();
    cd.elements = el;
    cd.element_count = 2;
    int comp = sd_world_add_composite(w, "comp", &cd, &err);
    sd_test_require(comp >= 0, "composite", &err);
    double t = 0.8;
    d = sd_shape_desc_default();
    d.kind = "box";
    d.size = sd_test_v(0.002, 0.003, 0.004);
    d.scale = t;
    el[0].shape = sd_world_add_shape(w, "box_t", &d, &err);
    d = sd_shape_desc_default();
    d.kind = "polyhedron";
    d.vertices = tetra;
    d.vertex_count = 5;
    d.scale = t;
    el[1].shape = sd_world_add_shape(w, "poly_t", &d, &err);
    el[1].position = sd_test_v(0.006 * t, 0.001 * t, 0);
    int comp_fresh = sd_world_add_composite(w, "comp_fresh", &cd, &err);
    int comp_copy = sd_world_add_scaled_shape(w, comp, t, "comp_copy", &err);
    same_shape("composite x 0.8", w, comp_copy, comp_fresh);
    sd_shape_info ci;
    require_shape(w, comp_copy, &ci);
    CHECK(ci.element_count == 2 && sd_world_find_shape(w, "comp_copy.e0") >= 0 &&
          sd_world_find_shape(w, "comp_copy.e1") >= 0);
    CHECK(sd_world_add_scaled_shape(w, box, -1, "bad", &err) == -1 && strcmp(err.key, "scale") == 0);
    CHECK(sd_world_add_scaled_shape(w, box, 2, "box", &err) == -1);
    sd_world_destroy(w);

    /* 2D: a polygon */
    sd_world_def wd = sd_world_def_default();
    wd.dimension = 2;
    wd.gravity = sd_test_v(0, -9.81, 0);
    wd.dt = 1e-5;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world 2d", &err);
    double pts[8] = {0, 0, 0.003, 0, 0.0035, 0.002, -0.0005, 0.0025}, pts2[8];
    sd_shape2d_def p2 = sd_shape2d_def_default();
    p2.kind = "polygon";
    p2.points = pts;
    p2.point_count = 4;
    p2.radius = 0.0001;
    int pg = sd_world_add_shape2d(w, "pg", &p2, &err);
    for (int k = 0; k < 8; ++k)
        pts2[k] = 1.6 * pts[k];
    p2.points = pts2;
    p2.radius = 1.6 * 0.0001;
    int pg_fresh = sd_world_add_shape2d(w, "pg_fresh", &p2, &err);
    same_shape("2D rounded polygon x 1.6", w, sd_world_add_scaled_shape(w, pg, 1.6, "pg_copy", &err), pg_fresh);
    sd_world_destroy(w);
}

/* One template entry's classes: the copies' equivalent radii inside the
 * law's equal-probability classes, equal counts, the mean volume. */
static void check_classes(const char *what, const sd_world *w, const sd_insert_entry *en, int shape0,
                          const int *count_of_shape)
{
    int k = en->size_classes;
    size_t obs[32] = {0}, n = 0;
    double p[32], mean3 = 0;
    int inside = 0;
    for (int c = 0; c < k; ++c) {
        sd_shape_info si;
        require_shape(w, shape0 + c, &si);
        double lo = law_quantile(&en->size, (double)c / k), hi = law_quantile(&en->size, (double)(c + 1) / k);
        inside += si.equivalent_radius >= lo && si.equivalent_radius <= hi;
        obs[c] = (size_t)count_of_shape[shape0 + c];
        n += obs[c];
        p[c] = 1.0 / k;
        mean3 += pow(si.equivalent_radius, 3) / k;
    }
    printf("     %s: %d classes, %zu particles; class radii inside their quantiles: %d of %d\n", what, k, n, inside,
           k);
    CHECK(inside == k);
    char label[96];
    double c2 = chi2(obs, p, k, n);
    snprintf(label, sizeof label, "%s: class counts chi2 (%d dof) < 1 %%", what, k - 1);
    CHECK_NEAR(label, fmin(c2, chi2_crit[k - 1]), c2, 0);
    snprintf(label, sizeof label, "%s: classes' E[r^3] vs law (rel)", what);
    CHECK_REL(label, mean3, law_moment3(&en->size), 1e-3);
}

static double min_gap(const sd_world *w)
{
    size_t n = sd_world_particle_count(w);
    sd_particle_state *s = calloc(n, sizeof *s);
    for (size_t k = 0; k < n; ++k)
        sd_world_get_particle(w, k, &s[k]);
    double g = HUGE_VAL;
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j) {
            double dx = s[i].position.x - s[j].position.x, dy = s[i].position.y - s[j].position.y,
                   dz = s[i].position.z - s[j].position.z;
            g = fmin(g, sqrt(dx * dx + dy * dy + dz * dz) - s[i].radius - s[j].radius);
        }
    free(s);
    return g;
}

static void test_mix(void)
{
    sd_error err;
    int mat;
    sd_world *w = world3d(&mat);
    sd_shape_desc d = sd_shape_desc_default();
    d.kind = "box";
    d.size = sd_test_v(0.002, 0.002, 0.002);
    int cube = sd_world_add_shape(w, "cube", &d, &err);
    d = sd_shape_desc_default();
    d.kind = "polyhedron";
    d.vertices = tetra;
    d.vertex_count = 5;
    int poly = sd_world_add_shape(w, "poly", &d, &err);
    sd_composite_element el[2];
    memset(el, 0, sizeof el);
    el[0].shape = cube;
    el[1].shape = cube;
    el[1].position = sd_test_v(0.002, 0, 0);
    sd_composite_desc cd = sd_composite_desc_default();
    cd.elements = el;
    cd.element_count = 2;
    int comp = sd_world_add_composite(w, "pair", &cd, &err);
    sd_test_require(cube >= 0 && poly >= 0 && comp >= 0, "templates", &err);
    size_t templates = sd_world_shape_count(w);

    sd_insert_def in = sd_insert_def_default();
    in.region.kind = SD_REGION_BOX;
    in.region.lo = sd_test_v(0, 0, 0);
    in.region.hi = sd_test_v(0.25, 0.25, 0.25);
    in.entry_count = 3;
    in.count = 3000;
    sd_insert_entry *e = in.entries;
    e[0].shape = cube;
    e[0].size.kind = SD_SIZE_LOGNORMAL;
    e[0].size.a = 0.0015;
    e[0].size.b = 0.2;
    e[0].size.min = 0.001;
    e[0].size.max = 0.0025;
    e[0].size_classes = 12;
    e[0].fraction = 0.4;
    e[1].shape = poly;
    e[1].size.kind = SD_SIZE_UNIFORM;
    e[1].size.a = 0.001;
    e[1].size.b = 0.002;
    e[1].size_classes = 8;
    e[1].fraction = 0.3;
    e[2].shape = comp;
    e[2].size.kind = SD_SIZE_NORMAL;
    e[2].size.a = 0.002;
    e[2].size.b = 0.0003;
    e[2].size.min = 0.0012;
    e[2].size.max = 0.0028;
    e[2].size_classes = 6;
    e[2].fraction = 0.3;
    for (int k = 0; k < 3; ++k)
        e[k].material = mat;
    CHECK(sd_world_add_insertion(w, &in, &err) == 0);
    /* the copies: 12 cubes, 8 polyhedra, 6 composites and their 6 element copies */
    size_t added = sd_world_shape_count(w) - templates;
    printf("     templates added by the insertion: %zu (expected 12 + 8 + 6 x 2)\n", added);
    CHECK(added == 12 + 8 + 6 * 2);
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    sd_insert_info info;
    sd_world_get_insertion(w, 0, &info);
    printf("     asked %zu, inserted %zu\n", info.asked, info.inserted);
    CHECK(info.asked == 3000 && info.inserted == 3000);
    double gap = min_gap(w);
    printf("     smallest gap between bounding spheres %.3g m\n", gap);
    CHECK_NEAR("overlap of bounding spheres (m), none", fmax(-gap, 0), 0, 0);

    int *count = calloc(sd_world_shape_count(w), sizeof *count);
    size_t n = sd_world_particle_count(w);
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state s;
        sd_world_get_particle(w, k, &s);
        if (s.shape >= 0)
            count[s.shape]++;
    }
    int c0 = sd_world_find_shape(w, "cube_i0e0s0"), c1 = sd_world_find_shape(w, "poly_i0e1s0"),
        c2i = sd_world_find_shape(w, "pair_i0e2s0");
    sd_test_require(c0 >= 0 && c1 >= 0 && c2i >= 0, "copies by name", NULL);
    size_t mix[3] = {0, 0, 0};
    for (int c = 0; c < 12; ++c)
        mix[0] += (size_t)count[c0 + c];
    for (int c = 0; c < 8; ++c)
        mix[1] += (size_t)count[c1 + c];
    /* the composite's copies follow each its own element copy */
    for (int c = 0; c < 6; ++c)
        mix[2] += (size_t)count[c2i + 2 * c];
    double pm[3] = {0.4, 0.3, 0.3};
    double cm = chi2(mix, pm, 3, 3000);
    printf("     mix: %zu %zu %zu of 3000 (expected 1200 900 900)\n", mix[0], mix[1], mix[2]);
    CHECK_NEAR("mix chi2 (2 dof) < 1 %", fmin(cm, chi2_crit[2]), cm, 0);
    check_classes("cube, log-normal", w, &e[0], c0, count);
    check_classes("polyhedron, uniform", w, &e[1], c1, count);
    /* composites: every other index (element copy, then composite) */
    int *cc = calloc(sd_world_shape_count(w), sizeof *cc);
    for (int c = 0; c < 6; ++c)
        cc[c2i + c] = count[c2i + 2 * c];
    sd_insert_entry e2 = e[2];
    int inside = 0;
    for (int c = 0; c < 6; ++c) {
        sd_shape_info si;
        require_shape(w, c2i + 2 * c, &si);
        inside += si.element_count == 2;
    }
    CHECK(inside == 6);
    /* the class check on a table of the composite copies' radii */
    {
        size_t obs[6];
        double p[6], mean3 = 0;
        int in_class = 0;
        for (int c = 0; c < 6; ++c) {
            sd_shape_info si;
            require_shape(w, c2i + 2 * c, &si);
            double lo = law_quantile(&e2.size, c / 6.0), hi = law_quantile(&e2.size, (c + 1) / 6.0);
            in_class += si.equivalent_radius >= lo && si.equivalent_radius <= hi;
            obs[c] = (size_t)cc[c2i + c];
            p[c] = 1.0 / 6;
            mean3 += pow(si.equivalent_radius, 3) / 6;
        }
        printf("     composite, normal: class radii inside their quantiles: %d of 6\n", in_class);
        CHECK(in_class == 6);
        double x2 = chi2(obs, p, 6, mix[2]);
        CHECK_NEAR("composite: class counts chi2 (5 dof) < 1 %", fmin(x2, chi2_crit[5]), x2, 0);
        CHECK_REL("composite: classes' E[r^3] vs law (rel)", mean3, law_moment3(&e2.size), 1e-3);
    }
    free(cc);
    free(count);
    sd_world_destroy(w);
}

static void test_by_mass(void)
{
    sd_error err;
    int mat;
    sd_world *w = world3d(&mat);
    sd_shape_desc d = sd_shape_desc_default();
    d.kind = "box";
    d.size = sd_test_v(0.002, 0.002, 0.002);
    int cube = sd_world_add_shape(w, "cube", &d, &err);
    sd_insert_def in = sd_insert_def_default();
    in.region.kind = SD_REGION_BOX;
    in.region.lo = sd_test_v(0, 0, 0);
    in.region.hi = sd_test_v(0.2, 0.2, 0.2);
    in.entry_count = 2;
    in.mix_by_mass = 1;
    in.count = 2000;
    in.entries[0].shape = -1;
    in.entries[0].material = mat;
    in.entries[0].size = sd_size_def_fixed(0.001);
    in.entries[0].fraction = 0.5;
    in.entries[1].shape = cube;
    in.entries[1].material = mat;
    in.entries[1].size.kind = SD_SIZE_LOGNORMAL;
    in.entries[1].size.a = 0.0018;
    in.entries[1].size.b = 0.25;
    in.entries[1].size.min = 0.001;
    in.entries[1].size.max = 0.003;
    in.entries[1].fraction = 0.5;
    CHECK(sd_world_add_insertion(w, &in, &err) == 0);
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    size_t n = sd_world_particle_count(w), cnt[2] = {0, 0};
    double mass[2] = {0, 0};
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state s;
        sd_world_get_particle(w, k, &s);
        cnt[s.shape >= 0]++;
        mass[s.shape >= 0] += s.mass;
    }
    /* number fractions from equal masses: p ~ 1 / E[m] (same density) */
    double m_sphere = pow(0.001, 3), m_cube = law_moment3(&in.entries[1].size);
    double pe[2] = {1 / m_sphere, 1 / m_cube}, sum = pe[0] + pe[1];
    pe[0] /= sum;
    pe[1] /= sum;
    printf("     by mass: %zu spheres, %zu cubes of %zu (expected %.1f, %.1f); mass share of the spheres %.3f\n",
           cnt[0], cnt[1], n, pe[0] * (double)n, pe[1] * (double)n, mass[0] / (mass[0] + mass[1]));
    CHECK(n == 2000);
    double c2 = chi2(cnt, pe, 2, n);
    CHECK_NEAR("mix by mass chi2 (1 dof) < 1 %", fmin(c2, chi2_crit[1]), c2, 0);
    sd_world_destroy(w);
}

static void test_table_2d(void)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.dimension = 2;
    wd.gravity = sd_test_v(0, -9.81, 0);
    wd.dt = 1e-5;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world 2d", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    int mat = sd_world_add_material(w, &m, &err);
    double pts[6] = {0, 0, 0.002, 0, 0.001, 0.0017};
    sd_shape2d_def p2 = sd_shape2d_def_default();
    p2.kind = "polygon";
    p2.points = pts;
    p2.point_count = 3;
    int tri = sd_world_add_shape2d(w, "tri", &p2, &err);
    sd_test_require(tri >= 0, "2D template", &err);
    sd_insert_def in = sd_insert_def_default();
    in.region.kind = SD_REGION_BOX;
    in.region.lo = sd_test_v(0, 0, 0);
    in.region.hi = sd_test_v(0.5, 0.5, 0);
    in.entry_count = 1;
    in.count = 2000;
    sd_insert_entry *e = &in.entries[0];
    e->shape = tri;
    e->material = mat;
    e->fraction = 1;
    e->size.kind = SD_SIZE_TABLE;
    e->size.classes = 3;
    e->size.by_mass = 1;
    double lo[3] = {0.001, 0.0015, 0.002}, hi[3] = {0.0015, 0.002, 0.003}, f[3] = {0.2, 0.3, 0.5};
    for (int c = 0; c < 3; ++c) {
        e->size.lo[c] = lo[c];
        e->size.hi[c] = hi[c];
        e->size.fraction[c] = f[c];
    }
    e->size_classes = 6;
    CHECK(sd_world_add_insertion(w, &in, &err) == 0);
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    size_t n = sd_world_particle_count(w), obs[3] = {0, 0, 0};
    int outside = 0;
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state s;
        sd_world_get_particle(w, k, &s);
        sd_shape_info si;
        require_shape(w, s.shape, &si);
        int c = si.equivalent_radius < 0.0015 ? 0 : si.equivalent_radius < 0.002 ? 1 : 2;
        outside += si.equivalent_radius < lo[c] || si.equivalent_radius > hi[c];
        obs[c]++;
    }
    /* number fractions of mass fractions: f / E[r^2], E[r^2] of r uniform in the class */
    double p[3], s = 0;
    for (int c = 0; c < 3; ++c) {
        p[c] = f[c] / ((pow(hi[c], 3) - pow(lo[c], 3)) / (3 * (hi[c] - lo[c])));
        s += p[c];
    }
    for (int c = 0; c < 3; ++c)
        p[c] /= s;
    printf("     2D sieve table by mass: %zu %zu %zu of %zu (expected %.1f %.1f %.1f), outside their class %d\n",
           obs[0], obs[1], obs[2], n, p[0] * (double)n, p[1] * (double)n, p[2] * (double)n, outside);
    CHECK(n == 2000 && outside == 0);
    double c2 = chi2(obs, p, 3, n);
    CHECK_NEAR("2D sieve classes by mass chi2 (2 dof) < 1 %", fmin(c2, chi2_crit[2]), c2, 0);
    sd_world_destroy(w);
}

static void test_bad(void)
{
    sd_error err;
    int mat;
    sd_world *w = world3d(&mat);
    sd_shape_desc d = sd_shape_desc_default();
    d.kind = "box";
    int cube = sd_world_add_shape(w, "cube", &d, &err);
    sd_insert_def in = sd_insert_def_default();
    in.region.kind = SD_REGION_BOX;
    in.region.hi = sd_test_v(0.1, 0.1, 0.1);
    in.entry_count = 1;
    in.count = 10;
    in.entries[0].shape = cube;
    in.entries[0].material = mat;
    in.entries[0].fraction = 1;
    in.entries[0].size.kind = SD_SIZE_UNIFORM;
    in.entries[0].size.a = -0.001;
    in.entries[0].size.b = 0.002;
    CHECK(sd_world_add_insertion(w, &in, &err) == -1);
    printf("     %s: %s\n", err.key, err.msg);
    CHECK(strcmp(err.key, "insert.mix.radius") == 0 && strstr(err.msg, "negative"));
    in.entries[0].size.a = 0.001;
    in.entries[0].size_classes = 40;
    CHECK(sd_world_add_insertion(w, &in, &err) == -1);
    printf("     %s: %s\n", err.key, err.msg);
    CHECK(strcmp(err.key, "insert.mix.size_classes") == 0);
    /* a later entry's bad material: refused before entry 0's copies are made */
    in.entries[0].size_classes = 4;
    in.entries[0].fraction = 0.5;
    in.entry_count = 2;
    in.entries[1] = in.entries[0];
    in.entries[1].shape = -1;
    in.entries[1].material = 7;
    CHECK(sd_world_add_insertion(w, &in, &err) == -1);
    printf("     %s: %s\n", err.key, err.msg);
    CHECK(strcmp(err.key, "insert.mix.material") == 0);
    printf("     templates after three refused insertions: %zu (expected 1)\n", sd_world_shape_count(w));
    CHECK(sd_world_shape_count(w) == 1); /* nothing added for refused insertions */
    sd_world_destroy(w);
}

int main(void)
{
    test_copies();
    test_mix();
    test_by_mass();
    test_table_2d();
    test_bad();
    return sd_test_summary();
}
