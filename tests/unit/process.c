/* process.c — insertion and outlets of the cells solver (world/process.c):
 *  - all at once, a mix of two sphere laws and a template: every particle
 *    asked for goes in, no two bounding spheres overlap, the radii follow
 *    their laws (Kolmogorov-Smirnov at 1 %) and the mix its fractions (chi
 *    square at 1 %), particles placed before by another insertion or by
 *    hand included;
 *  - a mix by mass and a sieve table by mass: the counts follow the
 *    number fractions those mass fractions imply (chi square at 1 %);
 *  - a region too small: fewer inserted than asked, and a reason;
 *  - at a rate: the count at each time is the rate's;
 *  - an outlet under an open-bottom box fed by an insertion: present +
 *    removed = initial + inserted (and the masses) every 100 steps, with
 *    1 and 2 threads, the same bits;
 *  - bad input: a mix not summing to 1, a negative radius, a region
 *    outside the domain, each refused with its key;
 *  - a box spanning a periodic cell: spheres straddle the seams, none
 *    overlaps a particle or its image.
 */
#include <math.h>
#include <string.h>

#include "test.h"

#include <shapedem/process.h>
#include <shapedem/scene.h>

static sd_world *make_world(int threads, int *mat, int *mat2)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.threads = threads;
    d.dt = 1e-5;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "a";
    m.youngs_modulus = 1e7;
    *mat = sd_world_add_material(w, &m, &err);
    m.name = "b";
    *mat2 = sd_world_add_material(w, &m, &err);
    return w;
}

/* Kolmogorov-Smirnov distance of sorted sample x[0..n) from cdf. */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double ks_distance(double *x, size_t n, double (*cdf)(double, const void *), const void *ctx)
{
    qsort(x, n, sizeof *x, cmp_double);
    double d = 0;
    for (size_t k = 0; k < n; ++k) {
        double f = cdf(x[k], ctx);
        d = fmax(d, fmax(fabs(f - (double)k / (double)n), fabs((double)(k + 1) / (double)n - f)));
    }
    return d;
}

static double cdf_uniform(double r, const void *ctx)
{
    const sd_size_def *s = ctx;
    return r <= s->a ? 0 : r >= s->b ? 1 : (r - s->a) / (s->b - s->a);
}

static double phi(double z) { return 0.5 * erfc(-z / sqrt(2.0)); }

static double cdf_lognormal(double r, const void *ctx)
{
    const sd_size_def *s = ctx;
    double lo = phi(log(s->min / s->a) / s->b), hi = phi(log(s->max / s->a) / s->b);
    return (phi(log(r / s->a) / s->b) - lo) / (hi - lo);
}

/* Chi-square critical values at 1 % for 1..4 degrees of freedom. */
static const double chi2_crit[5] = {0, 6.635, 9.210, 11.345, 13.277};

static double chi2(const size_t *obs, const double *p, int k, size_t n)
{
    double c = 0;
    for (int i = 0; i < k; ++i) {
        double e = p[i] * (double)n;
        c += ((double)obs[i] - e) * ((double)obs[i] - e) / e;
    }
    return c;
}

/* The smallest gap between the bounding spheres of all particles
 * (negative: an overlap), brute force; with period > 0, between nearest
 * images on x and y (a cell periodic on both, of that side). */
static double min_gap_periodic(const sd_world *w, double period)
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
            if (period > 0) {
                dx -= period * round(dx / period);
                dy -= period * round(dy / period);
            }
            g = fmin(g, sqrt(dx * dx + dy * dy + dz * dz) - s[i].radius - s[j].radius);
        }
    free(s);
    return g;
}

static double min_gap(const sd_world *w) { return min_gap_periodic(w, 0.0); }

static void test_mix(void)
{
    sd_error err;
    int ma, mb;
    sd_world *w = make_world(1, &ma, &mb);
    sd_shape_desc sdsc = sd_shape_desc_default();
    sdsc.kind = "box";
    sdsc.size = sd_test_v(0.002, 0.003, 0.004);
    int cube = sd_world_add_shape(w, "brick", &sdsc, &err);
    sd_test_require(cube >= 0, "shape", &err);
    /* 200 spheres by hand in the middle of the region: insertion avoids them */
    sd_sphere_def pre[200];
    memset(pre, 0, sizeof pre);
    for (int k = 0; k < 200; ++k) {
        pre[k].position = sd_test_v(0.1 + 0.006 * (k % 6), 0.1 + 0.006 * (k / 6 % 6), 0.1 + 0.006 * (k / 36));
        pre[k].radius = 0.0029;
        pre[k].material = ma;
    }
    sd_test_require(sd_world_add_spheres(w, 200, pre, &err) == SD_OK, "spheres", &err);
    sd_insert_def d = sd_insert_def_default();
    d.region.kind = SD_REGION_BOX;
    d.region.lo = sd_test_v(0, 0, 0);
    d.region.hi = sd_test_v(0.2, 0.2, 0.2);
    d.entry_count = 3;
    d.entries[0].shape = -1;
    d.entries[0].material = ma;
    d.entries[0].size.kind = SD_SIZE_UNIFORM;
    d.entries[0].size.a = 0.001;
    d.entries[0].size.b = 0.002;
    d.entries[0].fraction = 0.5;
    d.entries[1].shape = -1;
    d.entries[1].material = mb;
    d.entries[1].size.kind = SD_SIZE_LOGNORMAL;
    d.entries[1].size.a = 0.0015;
    d.entries[1].size.b = 0.25;
    d.entries[1].size.min = 0.0008;
    d.entries[1].size.max = 0.003;
    d.entries[1].fraction = 0.3;
    d.entries[2].shape = cube;
    d.entries[2].material = ma;
    d.entries[2].fraction = 0.2;
    d.count = 3000;
    CHECK(sd_world_add_insertion(w, &d, &err) == 0);
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    sd_insert_info info;
    CHECK(sd_world_get_insertion(w, 0, &info) == SD_OK);
    printf("     asked %zu, inserted %zu, why '%s'\n", info.asked, info.inserted, info.why);
    CHECK(info.asked == 3000 && info.inserted == 3000 && info.done);
    CHECK(sd_world_particle_count(w) == 3200);
    double gap = min_gap(w);
    printf("     smallest gap between bounding spheres %.3g m\n", gap);
    CHECK_NEAR("overlap of bounding spheres (m), none", fmax(-gap, 0), 0, 0);
    size_t n = sd_world_particle_count(w), cnt[3] = {0, 0, 0}, n0 = 0, n1 = 0;
    double *r0 = calloc(n, sizeof *r0), *r1 = calloc(n, sizeof *r1);
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state s;
        sd_world_get_particle(w, k, &s);
        if (s.id < 200)
            continue;
        if (s.shape == cube)
            cnt[2]++;
        else if (s.material == ma)
            cnt[0]++, r0[n0++] = s.radius;
        else
            cnt[1]++, r1[n1++] = s.radius;
    }
    double p[3] = {0.5, 0.3, 0.2};
    double c2 = chi2(cnt, p, 3, 3000);
    printf("     mix by number: %zu %zu %zu of 3000 (expected 1500 900 600)\n", cnt[0], cnt[1], cnt[2]);
    CHECK_NEAR("mix chi-square (2 dof), below the 1 % value", fmin(c2, chi2_crit[2]), c2, 0);
    double d0 = ks_distance(r0, n0, cdf_uniform, &d.entries[0].size);
    double d1 = ks_distance(r1, n1, cdf_lognormal, &d.entries[1].size);
    printf("     KS uniform: D = %.4f over %zu (1 %% critical %.4f); log-normal: D = %.4f over %zu (%.4f)\n", d0, n0,
           1.628 / sqrt((double)n0), d1, n1, 1.628 / sqrt((double)n1));
    CHECK(d0 < 1.628 / sqrt((double)n0));
    CHECK(d1 < 1.628 / sqrt((double)n1));
    free(r0);
    free(r1);
    sd_world_destroy(w);
}

static void test_by_mass(void)
{
    sd_error err;
    int ma, mb;
    sd_world *w = make_world(1, &ma, &mb);
    sd_insert_def d = sd_insert_def_default();
    d.region.kind = SD_REGION_CYLINDER;
    d.region.center = sd_test_v(0, 0, 0.1);
    d.region.axis = sd_test_v(0, 0, 1);
    d.region.radius = 0.1;
    d.region.length = 0.2;
    d.entry_count = 2;
    d.mix_by_mass = 1;
    d.entries[0].shape = -1;
    d.entries[0].material = ma;
    d.entries[0].size = sd_size_def_fixed(0.001);
    d.entries[0].fraction = 0.5;
    d.entries[1].shape = -1;
    d.entries[1].material = mb;
    d.entries[1].size.kind = SD_SIZE_TABLE;
    d.entries[1].size.classes = 3;
    d.entries[1].size.by_mass = 1;
    double lo[3] = {0.001, 0.0015, 0.002}, hi[3] = {0.0015, 0.002, 0.003}, f[3] = {0.2, 0.3, 0.5};
    for (int c = 0; c < 3; ++c) {
        d.entries[1].size.lo[c] = lo[c];
        d.entries[1].size.hi[c] = hi[c];
        d.entries[1].size.fraction[c] = f[c];
    }
    d.entries[1].fraction = 0.5;
    d.count = 3000;
    CHECK(sd_world_add_insertion(w, &d, &err) == 0);
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    size_t n = sd_world_particle_count(w), cnt[2] = {0, 0}, cls[3] = {0, 0, 0};
    double mass[2] = {0, 0};
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state s;
        sd_world_get_particle(w, k, &s);
        int e = s.material == ma ? 0 : 1;
        cnt[e]++;
        mass[e] += s.mass;
        if (e == 1)
            cls[s.radius < 0.0015 ? 0 : s.radius < 0.002 ? 1 : 2]++;
    }
    /* number fractions implied by the mass fractions: f / E[r^3] */
    double m3[3], pc[3], s3 = 0;
    for (int c = 0; c < 3; ++c) {
        m3[c] = (pow(hi[c], 4) - pow(lo[c], 4)) / (4 * (hi[c] - lo[c]));
        pc[c] = f[c] / m3[c];
        s3 += pc[c];
    }
    double mean3 = 0;
    for (int c = 0; c < 3; ++c) {
        pc[c] /= s3;
        mean3 += pc[c] * m3[c];
    }
    double pe[2] = {0.5 / 1e-9, 0.5 / mean3};
    double se = pe[0] + pe[1];
    pe[0] /= se;
    pe[1] /= se;
    printf("     by mass: %zu small, %zu graded (expected %.1f, %.1f); mass fraction of the small %.4f\n", cnt[0],
           cnt[1], pe[0] * (double)n, pe[1] * (double)n, mass[0] / (mass[0] + mass[1]));
    CHECK(n == 3000);
    double c2 = chi2(cnt, pe, 2, n);
    CHECK_NEAR("mix by mass chi-square (1 dof), below the 1 % value", fmin(c2, chi2_crit[1]), c2, 0);
    printf("     sieve classes: %zu %zu %zu (expected %.1f %.1f %.1f)\n", cls[0], cls[1], cls[2],
           pc[0] * (double)cnt[1], pc[1] * (double)cnt[1], pc[2] * (double)cnt[1]);
    double c3 = chi2(cls, pc, 3, cnt[1]);
    CHECK_NEAR("sieve classes by mass chi-square (2 dof), below 1 %", fmin(c3, chi2_crit[2]), c3, 0);
    double gap = min_gap(w);
    printf("     smallest gap between spheres %.3g m\n", gap);
    CHECK_NEAR("overlap of spheres (m), none", fmax(-gap, 0), 0, 0);
    sd_world_destroy(w);
}

static void test_full(void)
{
    sd_error err;
    int ma, mb;
    sd_world *w = make_world(1, &ma, &mb);
    sd_insert_def d = sd_insert_def_default();
    d.region.kind = SD_REGION_BOX;
    d.region.lo = sd_test_v(0, 0, 0);
    d.region.hi = sd_test_v(0.05, 0.05, 0.05);
    d.entry_count = 1;
    d.entries[0].shape = -1;
    d.entries[0].material = ma;
    d.entries[0].size = sd_size_def_fixed(0.01);
    d.entries[0].fraction = 1;
    d.count = 100;
    d.attempts = 50;
    CHECK(sd_world_add_insertion(w, &d, &err) == 0);
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    sd_insert_info info;
    sd_world_get_insertion(w, 0, &info);
    printf("     region too small: asked %zu, inserted %zu, why: %s\n", info.asked, info.inserted, info.why);
    CHECK(info.asked == 100 && info.inserted < 100 && info.inserted > 0 && info.why[0] && info.done);
    double gap = min_gap(w);
    printf("     smallest gap between spheres %.3g m\n", gap);
    CHECK_NEAR("overlap of spheres (m), none", fmax(-gap, 0), 0, 0);
    sd_world_destroy(w);
}

static void test_rate(void)
{
    sd_error err;
    int ma, mb;
    sd_world *w = make_world(1, &ma, &mb);
    sd_world_add_box(w, "bin", sd_test_v(-0.05, -0.05, 0), sd_test_v(0.05, 0.05, 0.3), SD_BOX_ZMAX, ma, &err);
    sd_insert_def d = sd_insert_def_default();
    d.region.kind = SD_REGION_DISC;
    d.region.center = sd_test_v(0, 0, 0.25);
    d.region.axis = sd_test_v(0, 0, 1);
    d.region.radius = 0.04;
    d.entry_count = 1;
    d.entries[0].shape = -1;
    d.entries[0].material = ma;
    d.entries[0].size = sd_size_def_fixed(0.003);
    d.entries[0].fraction = 1;
    d.count = 60;
    d.rate = 1000; /* 1/s: one every 100 steps */
    d.start = 0.001;
    d.velocity = sd_test_v(0, 0, -1);
    CHECK(sd_world_add_insertion(w, &d, &err) == 0);
    int bad = 0;
    for (int k = 1; k <= 80; ++k) {
        sd_test_require(sd_world_step(w, 100, &err) == SD_OK, "step", &err);
        double t = sd_world_time(w);
        /* particles due by the last insertion time at or before t */
        size_t expect = t < 0.001 - 1e-12 ? 0 : (size_t)floor((t - 0.001) * 1000 + 1e-9) + 1;
        if (expect > 60)
            expect = 60;
        bad += sd_world_particle_count(w) != expect;
    }
    sd_insert_info info;
    sd_world_get_insertion(w, 0, &info);
    printf("     at 1000/s: %zu of %zu in after %.3f s, count off the rate at %d of 80 checks\n", info.inserted,
           info.asked, sd_world_time(w), bad);
    CHECK(bad == 0 && info.inserted == 60 && info.done);
    sd_world_destroy(w);
}

static uint64_t outlet_run(int threads, int *bad, size_t *removed)
{
    sd_error err;
    int ma, mb;
    sd_world *w = make_world(threads, &ma, &mb);
    sd_world_add_box(w, "chute", sd_test_v(0, 0, 0), sd_test_v(0.03, 0.03, 0.3), SD_BOX_ZMIN | SD_BOX_ZMAX, ma,
                     &err);
    sd_sphere_def s[1100];
    memset(s, 0, sizeof s);
    for (int k = 0; k < 1100; ++k) {
        s[k].position = sd_test_v(0.0013 + 0.0025 * (k % 11), 0.0013 + 0.0025 * (k / 11 % 11), 0.002 + 0.0025 * (k / 121));
        s[k].radius = 0.0011;
        s[k].material = ma;
    }
    sd_test_require(sd_world_add_spheres(w, 1100, s, &err) == SD_OK, "spheres", &err);
    sd_insert_def d = sd_insert_def_default();
    d.region.kind = SD_REGION_BOX;
    d.region.lo = sd_test_v(0, 0, 0.05);
    d.region.hi = sd_test_v(0.03, 0.03, 0.08);
    d.entry_count = 1;
    d.entries[0].shape = -1;
    d.entries[0].material = mb;
    d.entries[0].size.kind = SD_SIZE_UNIFORM;
    d.entries[0].size.a = 0.0008;
    d.entries[0].size.b = 0.0012;
    d.entries[0].fraction = 1;
    d.count = 400;
    d.rate = 20000;
    CHECK(sd_world_add_insertion(w, &d, &err) == 0);
    sd_region_outlet_def o = sd_region_outlet_def_default();
    o.name = "bottom";
    o.region.kind = SD_REGION_BOX;
    o.region.lo = sd_test_v(-1, -1, -1);
    o.region.hi = sd_test_v(1, 1, -0.002);
    o.check_every = 10;
    CHECK(sd_world_add_outlet(w, &o, &err) == 0);
    double m0 = 0;
    for (int k = 0; k < 1100; ++k)
        m0 += 2500 * 4.0 / 3.0 * 3.14159265358979323846 * pow(0.0011, 3);
    *bad = 0;
    for (int f = 0; f < 30; ++f) {
        sd_test_require(sd_world_step(w, 100, &err) == SD_OK, "step", &err);
        sd_process_info pi;
        sd_world_get_process(w, &pi);
        size_t n = sd_world_particle_count(w);
        double m = 0;
        for (size_t k = 0; k < n; ++k) {
            sd_particle_state ps;
            sd_world_get_particle(w, k, &ps);
            m += ps.mass;
        }
        *bad += n + pi.removed != pi.initial + pi.inserted;
        *bad += fabs(m + pi.removed_mass - m0 - pi.inserted_mass) > 1e-12 * m0;
        sd_outlet_info oi;
        sd_world_get_outlet(w, 0, &oi);
        *bad += oi.removed != pi.removed;
        *removed = pi.removed;
    }
    uint64_t h = 1469598103934665603ull;
    size_t n = sd_world_particle_count(w);
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state ps;
        sd_world_get_particle(w, k, &ps);
        double v[] = {(double)ps.id, ps.position.x, ps.position.y, ps.position.z, ps.velocity.z};
        const unsigned char *b = (const unsigned char *)v;
        for (size_t i = 0; i < sizeof v; ++i)
            h = (h ^ b[i]) * 1099511628211ull;
    }
    sd_world_destroy(w);
    return h;
}

static void test_outlet(void)
{
    int bad1, bad2;
    size_t rem1, rem2;
    uint64_t h1 = outlet_run(1, &bad1, &rem1), h2 = outlet_run(2, &bad2, &rem2);
    printf("     outlet: removed %zu (1 thread) %zu (2 threads); accounting off at %d, %d of 30 frames x 3; "
           "hashes %016llx %016llx\n",
           rem1, rem2, bad1, bad2, (unsigned long long)h1, (unsigned long long)h2);
    CHECK(rem1 > 100 && rem1 == rem2);
    CHECK(bad1 == 0 && bad2 == 0);
    CHECK(h1 == h2);
}

static void test_bad(void)
{
    sd_error err;
    int ma, mb;
    sd_world *w = make_world(1, &ma, &mb);
    sd_insert_def d = sd_insert_def_default();
    d.region.kind = SD_REGION_BOX;
    d.region.lo = sd_test_v(0, 0, 0);
    d.region.hi = sd_test_v(0.1, 0.1, 0.1);
    d.entry_count = 2;
    d.entries[0].shape = d.entries[1].shape = -1;
    d.entries[0].size = d.entries[1].size = sd_size_def_fixed(0.001);
    d.entries[0].fraction = 0.5;
    d.entries[1].fraction = 0.4;
    d.count = 10;
    CHECK(sd_world_add_insertion(w, &d, &err) == -1);
    printf("     %s: %s\n", err.key, err.msg);
    CHECK(strcmp(err.key, "insert.mix") == 0);
    d.entries[1].fraction = 0.5;
    d.entries[1].size.kind = SD_SIZE_NORMAL;
    d.entries[1].size.a = -0.001;
    d.entries[1].size.b = 0.0001;
    CHECK(sd_world_add_insertion(w, &d, &err) == -1);
    printf("     %s: %s\n", err.key, err.msg);
    CHECK(strcmp(err.key, "insert.mix.radius") == 0 && strstr(err.msg, "negative"));
    sd_world_destroy(w);
    /* a periodic domain: the region must lie inside it */
    sd_world_def wd = sd_world_def_default();
    wd.periodic = SD_PERIODIC_X;
    wd.domain_lo = sd_test_v(0, 0, 0);
    wd.domain_hi = sd_test_v(0.05, 0, 0);
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    sd_world_add_material(w, &m, &err);
    d.entries[1].size = sd_size_def_fixed(0.001);
    d.entries[0].material = d.entries[1].material = 0;
    CHECK(sd_world_add_insertion(w, &d, &err) == -1);
    printf("     %s: %s\n", err.key, err.msg);
    CHECK(strcmp(err.key, "insert.region") == 0);
    sd_world_destroy(w);
}

/* Two random generators in one box: the second avoids the first's
 * spheres (it placed them on top of each other before; the build then
 * refused the scene for overlaps at the start). */
static void test_generators(void)
{
    const char *path = "process_two_generators.yaml";
    FILE *f = fopen(path, "w");
    sd_test_require(f != NULL, "scene file", NULL);
    fprintf(f, "simulation:\n  dt: 1.0e-5\n  steps: 1\nmaterials:\n  - name: glass\n    density: 2500\n"
               "    youngs_modulus: 1.0e7\nparticles:\n");
    for (int g = 0; g < 2; ++g)
        fprintf(f, "  - generator: random\n    material: glass\n    radius: {min: 0.001, max: 0.0015}\n"
                   "    box: {min: [0, 0, 0], max: [0.03, 0.03, 0.03]}\n    number: 300\n");
    fclose(f);
    sd_error err;
    sd_scene *sc;
    sd_world *w = NULL;
    sd_test_require(sd_scene_load(path, &sc, &err) == SD_OK, "load", &err);
    sd_status st = sd_scene_build(sc, &w, &err);
    if (st != SD_OK) {
        char buf[1024];
        sd_error_format(&err, buf, sizeof buf);
        printf("     build refused: %s\n", buf);
    }
    CHECK(st == SD_OK);
    if (st == SD_OK) {
        double gap = min_gap(w);
        printf("     two random generators in one box: %zu spheres, smallest gap %.3g m\n",
               sd_world_particle_count(w), gap);
        CHECK(sd_world_particle_count(w) == 600);
        CHECK_NEAR("overlap between the generators' spheres (m), none", fmax(-gap, 0), 0, 0);
        sd_world_destroy(w);
    }
    sd_scene_free(sc);
    remove(path);
}

/* Insertion into a box that spans a periodic cell on x and y (issue 16):
 * the spheres cover the seams (before, each bounding sphere was kept
 * inside the box, so a strip one radius wide each side of a seam stayed
 * empty) and none overlaps another or another's periodic image. */
static void test_periodic_seam(void)
{
    sd_error err;
    sd_world *w;
    const double L = 0.02, r = 0.001;
    sd_world_def wd = sd_world_def_default();
    wd.dt = 1e-5;
    wd.periodic = SD_PERIODIC_X | SD_PERIODIC_Y;
    wd.domain_lo = sd_test_v(0, 0, 0);
    wd.domain_hi = sd_test_v(L, L, 0.02);
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    int mat = sd_world_add_material(w, &m, &err);
    sd_insert_def d = sd_insert_def_default();
    d.region.kind = SD_REGION_BOX;
    d.region.lo = sd_test_v(0, 0, 0.001);
    d.region.hi = sd_test_v(L, L, 0.011);
    d.entry_count = 1;
    d.entries[0].shape = -1;
    d.entries[0].material = mat;
    d.entries[0].size = sd_size_def_fixed(r);
    d.entries[0].fraction = 1;
    d.count = 250; /* a solid fraction of 0.26 */
    d.attempts = 1000;
    CHECK(sd_world_add_insertion(w, &d, &err) == 0);
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    sd_insert_info info;
    sd_world_get_insertion(w, 0, &info);
    size_t n = sd_world_particle_count(w);
    printf("     periodic box: asked %zu, inserted %zu (%zu particles)\n", info.asked, info.inserted, n);
    CHECK(info.inserted == 250 && n == 250);
    sd_particle_state *p = calloc(n, sizeof *p);
    for (size_t k = 0; k < n; ++k)
        sd_world_get_particle(w, k, &p[k]);
    double gap = min_gap_periodic(w, L); /* by the nearest images on x and y */
    /* spheres across a seam: their centre within r of x = 0 (or L), of y = 0 */
    size_t across_x = 0, across_y = 0, inside = 0;
    for (size_t k = 0; k < n; ++k) {
        double x = p[k].position.x, y = p[k].position.y;
        across_x += x < r || x > L - r;
        across_y += y < r || y > L - r;
        inside += x >= 0 && x < L && y >= 0 && y < L;
    }
    free(p);
    /* uniform centres: 2r/L of them within r of a seam, 25 of 250 */
    double expect = (double)n * 2 * r / L;
    printf("     smallest gap to a particle or an image %.3g m; across the x seam %zu, the y seam %zu "
           "(uniform: %.0f each; at least half asserted)\n",
           gap, across_x, across_y, expect);
    CHECK_NEAR("overlap of spheres or images (m), none", fmax(-gap, 0), 0, 0);
    CHECK((double)across_x >= 0.5 * expect && (double)across_y >= 0.5 * expect);
    CHECK(inside == n);
    sd_world_destroy(w);
}

int main(void)
{
    test_periodic_seam();
    test_generators();
    test_bad();
    test_mix();
    test_by_mass();
    test_full();
    test_rate();
    test_outlet();
    return sd_test_summary();
}
