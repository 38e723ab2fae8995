/* analysis.c — the analyses of shapedem/analysis.h other than porosity
 * (validation.porosity) on configurations with known answers:
 *  - coordination: a 3 x 3 x 3 simple cubic block of spheres pressed
 *    together on a floor: 54 contacts, mean 4, the distribution 8 / 12 / 6
 *    / 1 at Z = 3 / 4 / 5 / 6, 9 wall contacts; two dumbbells (composites)
 *    touching with both element pairs: one contact, not two;
 *  - a rigid rotation v = w x r: the binned velocity field equals w x r at
 *    each cell's centre (two particles per cell, symmetric about it), and
 *    the energies equal those of sd_world_stats and the closed forms;
 *  - speeds 0.05, 0.15, ..., 0.95 m/s: one particle per class of 0.1 m/s;
 *  - a column of equal spheres: the top, the mass-fraction height, the
 *    mean height;
 *  - a bed in a drum with its surface tilted at 30 degrees (a lattice
 *    turned by 30 degrees, positions jittered by 0.3 and 0.1 spacings
 *    along and across the surface): the surface angle within 1 degree; a conical heap of slope 30 degrees: the angle of
 * repose within 1 degree; the same two in 2D (a disc drum, a heap's two flanks);
 *  - the analysis: section of a scene, run: each CSV file exists with its
 *    header and a row per cadence.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "test.h"

#include <shapedem/analysis.h>
#include <shapedem/scene.h>

static const double PI = 3.14159265358979323846;

static sd_world *new_world(int threads, double gz, int *mat)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.threads = threads;
    d.dt = 1e-7;
    d.gravity = sd_test_v(0, 0, gz);
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "m";
    m.youngs_modulus = 1e7;
    m.density = 2500;
    *mat = sd_world_add_material(w, &m, &err);
    return w;
}

/* a tiny deterministic jitter in [-1, 1) */
static double jitter(unsigned k)
{
    unsigned x = k * 2654435761u + 12345u;
    x ^= x >> 13;
    x *= 0x5bd1e995u;
    x ^= x >> 15;
    return (double)(x % 20001u) / 10000.0 - 1.0;
}

static void coordination(void)
{
    printf("-- coordination: a 3 x 3 x 3 block pressed together on a floor\n");
    int mat;
    sd_world *w = new_world(2, -9.81, &mat);
    const double r = 0.001, d = 2 * r * (1 - 1e-3); /* every neighbour pair overlaps by 2 um */
    sd_sphere_def s[27];
    memset(s, 0, sizeof s);
    for (int k = 0; k < 27; ++k) {
        s[k].position = sd_test_v((k % 3) * d, (k / 3 % 3) * d, r * (1 - 1e-3) + (k / 9) * d);
        s[k].radius = r;
        s[k].material = mat;
    }
    sd_error err;
    sd_test_require(sd_world_add_spheres(w, 27, s, &err) == SD_OK, "spheres", &err);
    sd_test_require(sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err) >= 0, "floor",
                    &err);
    sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err);
    sd_coordination c;
    sd_test_require(sd_world_coordination(w, NULL, &c, &err) == SD_OK, "coordination", &err);
    CHECK_NEAR("particle contacts", (double)c.contacts, 54, 0);
    CHECK_NEAR("mean coordination number", c.mean, 4.0, 1e-12);
    CHECK_NEAR("wall contacts (the bottom layer)", (double)c.wall_contacts, 9, 0);
    CHECK_NEAR("mean with walls", c.mean_with_walls, (108.0 + 9.0) / 27.0, 1e-12);
    CHECK_NEAR("particles with Z = 3 (corners)", (double)c.histogram[3], 8, 0);
    CHECK_NEAR("particles with Z = 4 (edges)", (double)c.histogram[4], 12, 0);
    CHECK_NEAR("particles with Z = 5 (faces)", (double)c.histogram[5], 6, 0);
    CHECK_NEAR("particles with Z = 6 (the centre)", (double)c.histogram[6], 1, 0);
    CHECK_NEAR("rattlers", (double)c.rattlers, 0, 0);
    /* the bottom layer only: 4 corners (Z 3), 4 edges (Z 4), the middle (Z 5) */
    sd_region_def bottom;
    memset(&bottom, 0, sizeof bottom);
    bottom.kind = SD_REGION_BOX;
    bottom.lo = sd_test_v(-r, -r, 0);
    bottom.hi = sd_test_v(3 * d, 3 * d, 1.5 * r);
    sd_test_require(sd_world_coordination(w, &bottom, &c, &err) == SD_OK, "coordination", &err);
    CHECK_NEAR("bottom layer: particles", (double)c.particles, 9, 0);
    CHECK_NEAR("bottom layer: mean Z", c.mean, 33.0 / 9.0, 1e-12);
    CHECK_NEAR("bottom layer: contacts with one end in it", (double)c.contacts, 12 + 9, 0);
    CHECK_NEAR("bottom layer: wall contacts", (double)c.wall_contacts, 9, 0);
    sd_world_destroy(w);

    printf("-- coordination: two dumbbells side by side, touching with both element pairs\n");
    w = new_world(1, 0, &mat);
    sd_shape_desc sd = sd_shape_desc_default();
    sd.kind = "sphere";
    sd.size = sd_test_v(r, 0, 0);
    int ball = sd_world_add_shape(w, "ball", &sd, &err);
    sd_composite_element el[2];
    memset(el, 0, sizeof el);
    el[0].shape = el[1].shape = ball;
    el[0].position = sd_test_v(0, 0, -1.5 * r);
    el[1].position = sd_test_v(0, 0, 1.5 * r);
    sd_composite_desc cd = sd_composite_desc_default();
    cd.elements = el;
    cd.element_count = 2;
    int bell = sd_world_add_composite(w, "bell", &cd, &err);
    sd_test_require(bell >= 0, "dumbbell", &err);
    sd_body_def b[3];
    memset(b, 0, sizeof b);
    for (int k = 0; k < 3; ++k) {
        b[k].shape = bell;
        b[k].material = mat;
    }
    b[1].position = sd_test_v(2 * r * (1 - 1e-3), 0, 0);
    b[2].position = sd_test_v(0.05, 0, 0); /* alone: a rattler */
    sd_test_require(sd_world_add_bodies(w, 3, b, &err) == SD_OK, "bodies", &err);
    sd_test_require(sd_world_prepare(w, &err) == SD_OK, "prepare", &err);
    sd_stats st;
    sd_world_stats(w, &st);
    sd_test_require(sd_world_coordination(w, NULL, &c, &err) == SD_OK, "coordination", &err);
    printf("   element contacts in the pair list: %ld\n", st.contacts);
    CHECK_NEAR("composite contacts (2 element contacts, 1 pair)", (double)c.contacts, 1, 0);
    CHECK_NEAR("rattlers", (double)c.rattlers, 1, 0);
    CHECK(st.contacts >= 2); /* stats.csv counts the list's entries in contact: more than the one pair */
    sd_world_destroy(w);
}

static void rotation(void)
{
    printf("-- a rigid rotation about y: velocity field w x r, energies\n");
    int mat;
    sd_world *w = new_world(2, 0, &mat);
    const double om = 3.0, r = 0.0005, cell = 0.01; /* rad/s, m, m */
    enum { NC = 6, N = NC * NC * 2 };
    sd_sphere_def s[N];
    memset(s, 0, sizeof s);
    /* the grid spans [-0.03, 0.03]^2 in x, z; two particles per cell at
     * +-(dx, dz) from its centre */
    int n = 0;
    for (int j = 0; j < NC; ++j)
        for (int i = 0; i < NC; ++i)
            for (int k = 0; k < 2; ++k) {
                double sg = k ? 1.0 : -1.0;
                double x = -0.03 + (i + 0.5) * cell + sg * 0.002, z = -0.03 + (j + 0.5) * cell + sg * 0.003;
                s[n].position = sd_test_v(x, 0.0001 * sg, z);
                /* w x r with w = (0, om, 0): (om z, 0, -om x) */
                s[n].velocity = sd_test_v(om * z, 0, -om * x);
                s[n].angular_velocity = sd_test_v(0, om, 0);
                s[n].radius = r;
                s[n].material = mat;
                n++;
            }
    sd_error err;
    sd_test_require(sd_world_add_spheres(w, N, s, &err) == SD_OK, "spheres", &err);
    sd_velocity_field_def vd = sd_velocity_field_def_default();
    vd.region.kind = SD_REGION_BOX;
    vd.region.lo = sd_test_v(-0.03, -0.001, -0.03);
    vd.region.hi = sd_test_v(0.03, 0.001, 0.03);
    vd.plane = 1;
    vd.cells[0] = vd.cells[1] = NC;
    size_t cnt[NC * NC];
    sd_v3d mv[NC * NC];
    sd_test_require(sd_world_velocity_field(w, &vd, cnt, mv, &err) == SD_OK, "field", &err);
    double worst = 0;
    int counts_ok = 1;
    for (int j = 0; j < NC; ++j)
        for (int i = 0; i < NC; ++i) {
            double x = -0.03 + (i + 0.5) * cell, z = -0.03 + (j + 0.5) * cell;
            const sd_v3d *m = &mv[i + NC * j];
            worst = fmax(worst, fabs(m->x - om * z) + fabs(m->y) + fabs(m->z + om * x));
            counts_ok &= cnt[i + NC * j] == 2;
        }
    CHECK(counts_ok);
    CHECK_NEAR("velocity field - w x r at cell centres, worst (m/s)", worst, 0.0, 1e-12);
    sd_motion_stats ms;
    sd_test_require(sd_world_motion_stats(w, NULL, &ms, &err) == SD_OK, "motion", &err);
    sd_stats st;
    sd_world_stats(w, &st);
    double m1 = 2500 * 4 * PI * r * r * r / 3, ekt = 0, ekr = N * 0.5 * 0.4 * m1 * r * r * om * om;
    for (int k = 0; k < N; ++k)
        ekt += 0.5 * m1 * (s[k].velocity.x * s[k].velocity.x + s[k].velocity.z * s[k].velocity.z);
    CHECK_REL("translational kinetic energy (J)", ms.kinetic_translational, ekt, 1e-12);
    CHECK_REL("rotational kinetic energy (J)", ms.kinetic_rotational, ekr, 1e-12);
    CHECK_REL("rotational energy against sd_world_stats (J)", ms.kinetic_rotational, st.kinetic_rotational, 1e-12);
    CHECK_NEAR("mean velocity x (m/s, symmetric field)", ms.mean_velocity.x, 0.0, 1e-15);
    sd_world_destroy(w);
}

static void speeds_and_heights(void)
{
    printf("-- speeds 0.05 .. 0.95 m/s in classes of 0.1; a column of 10 spheres\n");
    int mat;
    sd_world *w = new_world(1, -9.81, &mat);
    const double r = 0.001;
    sd_sphere_def s[10];
    memset(s, 0, sizeof s);
    for (int k = 0; k < 10; ++k) {
        s[k].position = sd_test_v(0, 0, r + 2 * r * k);
        double v = 0.05 + 0.1 * k;
        s[k].velocity = sd_test_v(v * 0.6, 0, v * 0.8);
        s[k].radius = r;
        s[k].material = mat;
    }
    sd_error err;
    sd_test_require(sd_world_add_spheres(w, 10, s, &err) == SD_OK, "spheres", &err);
    size_t cnt[10];
    double top = 0;
    sd_test_require(sd_world_speed_histogram(w, NULL, 10, 1.0, cnt, &top, &err) == SD_OK, "histogram", &err);
    int one_each = 1;
    for (int k = 0; k < 10; ++k)
        one_each &= cnt[k] == 1;
    CHECK(one_each);
    CHECK_NEAR("histogram top (m/s)", top, 1.0, 0);
    sd_motion_stats ms;
    sd_test_require(sd_world_motion_stats(w, NULL, &ms, &err) == SD_OK, "motion", &err);
    CHECK_NEAR("mean speed (m/s)", ms.mean_speed, 0.5, 1e-12);
    CHECK_NEAR("largest speed (m/s)", ms.max_speed, 0.95, 1e-12);
    sd_bed_height bh;
    sd_test_require(sd_world_bed_height(w, NULL, 0.5, &bh, &err) == SD_OK, "bed", &err);
    CHECK_NEAR("bed top (m)", bh.top, 20 * r, 1e-15);
    CHECK_NEAR("height below which half the mass lies (m)", bh.fraction_height, 9 * r, 1e-15);
    CHECK_NEAR("mean height (m)", bh.mean, 10 * r, 1e-15);
    sd_world_destroy(w);
}

static void drum_surface(void)
{
    printf("-- a drum's bed with its surface at 30 degrees (jittered lattice)\n");
    int mat;
    sd_world *w = new_world(1, -9.81, &mat);
    const double R = 0.05, r = 0.0014, d = 0.003, t = 30 * PI / 180;
    sd_sphere_def s[2000];
    memset(s, 0, sizeof s);
    int n = 0;
    /* layers j <= 0 below the line h = tan(t) s through the axis, in the
     * frame turned by t: s along the surface, n down into the bed; the drum
     * axis is y, up is z, across the drum s = (x - c) . (up x axis) = -x */
    for (int j = 0; j < 12; ++j)
        for (int i = -40; i <= 40; ++i) {
            double a = i * d + 0.3 * d * jitter((unsigned)(n + 7)), b = -j * d + 0.1 * d * jitter((unsigned)(n + 911));
            double sx = a * cos(t) - b * sin(t), h = a * sin(t) + b * cos(t);
            double x = -sx, z = h;
            if (x * x + z * z > (R - r) * (R - r) || n >= 2000)
                continue;
            s[n].position = sd_test_v(x, 0.0002 * jitter((unsigned)n), z);
            s[n].radius = r;
            s[n].material = mat;
            n++;
        }
    sd_error err;
    sd_test_require(sd_world_add_spheres(w, (size_t)n, s, &err) == SD_OK, "spheres", &err);
    sd_region_def drum;
    memset(&drum, 0, sizeof drum);
    drum.kind = SD_REGION_CYLINDER;
    drum.axis = sd_test_v(0, 1, 0);
    drum.radius = R;
    drum.length = 0.01;
    const double fit[2] = {0.2, 0.8};
    sd_surface_fit f;
    sd_test_require(sd_world_drum_surface(w, &drum, 20, fit, &f, &err) == SD_OK, "drum", &err);
    printf("   %d spheres, %d columns fitted, rms %.2e m\n", n, f.columns, f.rms);
    CHECK_NEAR("drum free-surface angle (deg)", f.angle, 30.0, 1.0);
    CHECK(f.slope > 0);
    sd_world_destroy(w);
}

static void heap(void)
{
    printf("-- a conical heap of slope 30 degrees (rings of spheres on its surface)\n");
    int mat;
    sd_world *w = new_world(1, -9.81, &mat);
    const double r = 0.001, d = 2.05 * r, H = 0.02, t = 30 * PI / 180;
    static sd_sphere_def s[6000];
    memset(s, 0, sizeof s);
    int n = 0;
    for (int k = 0; k < 40 && n < 6000; ++k) {
        double rk = k * d, h = H - tan(t) * rk;
        if (h < r)
            break;
        int m = k == 0 ? 1 : (int)floor(2 * PI * rk / d);
        for (int i = 0; i < m && n < 6000; ++i) {
            double phi = 2 * PI * (i + 0.5 * jitter((unsigned)(n + 3))) / m;
            s[n].position = sd_test_v(0.01 + rk * cos(phi), -0.02 + rk * sin(phi), h);
            s[n].radius = r;
            s[n].material = mat;
            n++;
        }
        /* a layer under the surface, so the heap has a body */
        for (int i = 0; i < m && n < 6000 && h - 2 * d > r; ++i) {
            double phi = 2 * PI * (i + 0.5) / m;
            s[n].position = sd_test_v(0.01 + rk * cos(phi), -0.02 + rk * sin(phi), h - 2 * d);
            s[n].radius = r;
            s[n].material = mat;
            n++;
        }
    }
    sd_error err;
    sd_test_require(sd_world_add_spheres(w, (size_t)n, s, &err) == SD_OK, "spheres", &err);
    const double fit[2] = {0.2, 0.8};
    sd_surface_fit f;
    sd_test_require(sd_world_heap_angle(w, NULL, 20, fit, &f, &err) == SD_OK, "heap", &err);
    printf("   %d spheres, %d columns fitted, rms %.2e m\n", n, f.columns, f.rms);
    CHECK_NEAR("angle of repose (deg), centre of mass as axis", f.angle, 30.0, 1.0);
    CHECK(f.slope < 0);
    sd_world_destroy(w);
}

static void planar(void)
{
    printf("-- 2D: a disc drum's bed with its surface at 30 degrees; a heap of flanks at 30 degrees\n");
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.dimension = 2;
    d.dt = 1e-7;
    d.gravity = sd_test_v(0, -9.81, 0);
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.youngs_modulus = 1e7;
    int mat = sd_world_add_material(w, &m, &err);
    const double R = 0.05, r = 0.0014, sp = 0.003, t = 30 * PI / 180;
    static sd_sphere_def s[4000];
    memset(s, 0, sizeof s);
    int n = 0;
    /* in the disc drum about z, up is +y and across is e = up x z = +x */
    for (int j = 0; j < 12; ++j)
        for (int i = -40; i <= 40; ++i) {
            double a = i * sp + 0.3 * sp * jitter((unsigned)(n + 5)), b = -j * sp + 0.1 * sp * jitter((unsigned)n);
            double x = a * cos(t) - b * sin(t), y = a * sin(t) + b * cos(t);
            if (x * x + y * y > (R - r) * (R - r))
                continue;
            s[n].position = sd_test_v(x, y, 0);
            s[n].radius = r;
            s[n].material = mat;
            n++;
        }
    sd_test_require(sd_world_add_spheres(w, (size_t)n, s, &err) == SD_OK, "discs", &err);
    sd_region_def drum;
    memset(&drum, 0, sizeof drum);
    drum.kind = SD_REGION_CYLINDER;
    drum.axis = sd_test_v(0, 0, 1);
    drum.radius = R;
    const double fit[2] = {0.2, 0.8};
    sd_surface_fit f;
    sd_test_require(sd_world_drum_surface(w, &drum, 20, fit, &f, &err) == SD_OK, "drum", &err);
    CHECK_NEAR("2D drum free-surface angle (deg)", f.angle, 30.0, 1.0);
    sd_world_destroy(w);

    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    mat = sd_world_add_material(w, &m, &err);
    n = 0;
    for (int i = -30; i <= 30; ++i)
        for (int j = 0; j < 3; ++j) {
            double x = 0.02 + i * sp, y = 0.05 - tan(t) * fabs(i * sp) - j * 2 * sp;
            if (y < r)
                continue;
            s[n].position = sd_test_v(x, y, 0);
            s[n].radius = r;
            s[n].material = mat;
            n++;
        }
    sd_test_require(sd_world_add_spheres(w, (size_t)n, s, &err) == SD_OK, "discs", &err);
    sd_test_require(sd_world_heap_angle(w, NULL, 20, fit, &f, &err) == SD_OK, "heap", &err);
    CHECK_NEAR("2D heap angle of repose (deg)", f.angle, 30.0, 1.0);
    sd_world_destroy(w);
}

static int count_lines(const char *path, char *first, size_t size)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    char line[4096];
    int n = 0;
    while (fgets(line, sizeof line, f)) {
        if (n == 0 && first)
            snprintf(first, size, "%s", line);
        n++;
    }
    fclose(f);
    return n;
}

static void scene_section(void)
{
    printf("-- a scene's analysis: section, run for 20 steps\n");
    char scene[128], dir[128];
    snprintf(scene, sizeof scene, "/tmp/sd_unit_analysis_%ld.yaml", (long)getpid());
    snprintf(dir, sizeof dir, "/tmp/sd_unit_analysis_%ld", (long)getpid());
    FILE *f = fopen(scene, "w");
    sd_test_require(f != NULL, "scene file", NULL);
    fprintf(f, "simulation: {dt: 1.0e-5, steps: 20}\n"
               "materials:\n  - {name: m, density: 2500, youngs_modulus: 1.0e7}\n"
               "particles:\n  - {generator: lattice, material: m, radius: 0.001, origin: [0.002, 0.002, 0.002], "
               "spacing: 0.0025, count: [4, 4, 4]}\n"
               "walls:\n  - {name: box, type: box, min: [0, 0, 0], max: [0.012, 0.012, 0.05], material: m}\n"
               "output: {every: 10, stats_every: 5, formats: [csv]}\n"
               "analysis:\n"
               "  - {type: porosity, region: box, min: [0, 0, 0], max: [0.012, 0.012, 0.012], voxel: 0.0004}\n"
               "  - {type: radial_porosity, region: cylinder, center: [0.006, 0.006, 0.006], radius: 0.005, "
               "length: 0.01, voxel: 0.0004, bins: 5, every: 10}\n"
               "  - {type: coordination}\n"
               "  - {type: energy, interval: 1.0e-4}\n"
               "  - {type: speed_pdf, bins: 4}\n"
               "  - {type: velocity_field, region: box, min: [0, 0, 0], max: [0.012, 0.012, 0.05], plane: xz, "
               "cells: [3, 5]}\n"
               "  - {type: bed_height}\n"
               "  - {type: repose_angle, name: heap}\n"
               "  - {type: energy, file: energy_box.csv, region: box, min: [0, 0, 0], max: [0.006, 0.012, 0.05]}\n");
    fclose(f);
    sd_error err;
    sd_scene *s;
    sd_world *w;
    sd_test_require(sd_scene_load(scene, &s, &err) == SD_OK, "load", &err);
    sd_test_require(sd_scene_build(s, &w, &err) == SD_OK, "build", &err);
    sd_run *run;
    sd_test_require(sd_run_open(s, w, dir, &run, &err) == SD_OK, "open", &err);
    sd_test_require(sd_run_advance(run, 20, &err) == SD_OK, "advance", &err);
    sd_test_require(sd_run_close(run, &err) == SD_OK, "close", &err);
    /* rows at steps 0, 5, 10, 15, 20 (every = stats_every = 5), 0, 10, 20 for every 10 */
    struct {
        const char *file, *head;
        int lines;
    } want[] = {
        {"porosity.csv", "time,step,voxels", 1 + 5},
        {"radial_porosity.csv", "time,step,bin,r_inner", 1 + 3 * 5},
        {"coordination.csv", "time,step,particles,contacts", 1 + 5},
        {"energy.csv", "time,step,particles,mass", 1 + 3},
        {"speed_pdf.csv", "time,step,bin,speed_lo", 1 + 5 * 4},
        {"velocity_field.csv", "time,step,i,j,u,v", 1 + 5 * 15},
        {"bed_height.csv", "time,step,particles,top", 1 + 5},
        {"heap.csv", "time,step,angle_deg", 1 + 5},
        {"energy_box.csv", "time,step,particles,mass", 1 + 5},
    };
    for (size_t k = 0; k < sizeof want / sizeof want[0]; ++k) {
        char path[256], first[4096] = "", label[128];
        snprintf(path, sizeof path, "%s/%s", dir, want[k].file);
        int n = count_lines(path, first, sizeof first);
        snprintf(label, sizeof label, "lines of %s", want[k].file);
        CHECK_NEAR(label, n, want[k].lines, 0);
        CHECK(strncmp(first, want[k].head, strlen(want[k].head)) == 0);
    }
    /* the porosity row at step 0: 64 spheres of r 1 mm in 0.012^2 x 0.012 */
    char ppath[256];
    snprintf(ppath, sizeof ppath, "%s/porosity.csv", dir);
    FILE *pf = fopen(ppath, "r");
    char line[512];
    double t0, sf = 0;
    long st0, vox, sol;
    if (pf && fgets(line, sizeof line, pf) && fgets(line, sizeof line, pf) &&
        sscanf(line, "%lf,%ld,%ld,%ld,%lf", &t0, &st0, &vox, &sol, &sf) == 5) {
        double expect = 64 * 4 * PI * 1e-9 / 3 / (0.012 * 0.012 * 0.012);
        CHECK_NEAR("porosity.csv solid fraction at step 0", sf, expect, 0.01);
    } else {
        CHECK(!"porosity.csv row");
    }
    if (pf)
        fclose(pf);
    sd_world_destroy(w);
    sd_scene_free(s);
    remove(scene);
    for (size_t k = 0; k < sizeof want / sizeof want[0]; ++k) { /* the files of this run only */
        char path[256];
        snprintf(path, sizeof path, "%s/%s", dir, want[k].file);
        remove(path);
    }
}

int main(void)
{
    coordination();
    rotation();
    speeds_and_heights();
    drum_surface();
    heap();
    planar();
    scene_section();
    return sd_test_summary();
}
