/* composites_settle.c — benchmark `composites-settle` (issue 15): 2,000
 * particles settling in a box under gravity, the same scene size for four
 * particle types, to give the cost ratio composite / convex / sphere that
 * seed 004 §2.5 puts at about 50x spheres:
 *   spheres   plain spheres of radius r
 *   cubes     convex cubes of edge 2 r (GJK/EPA)
 *   clumps    multi-sphere clumps, 4 spheres of radius r on a tetrahedron
 *   crosses   3D crosses of 7 cubes of edge 1.4 r (composites of convex elements)
 *   cross3d   seed 004's 3D cross: the cross3d preset, three cylinders of
 *             diameter 1.4 r and length 4.2 r through one centre
 *             (sd_world_add_composite_preset; overlapping elements)
 * Each case: particles on a loose lattice with random velocities, `warm`
 * steps to bring them into contact, then `steps` timed steps. Prints per
 * case particle-steps per second, element-pair tests per second and the
 * ratio to the sphere case (with one thread per CPU second of the process,
 * with more per wall second). The element-pair tests are the element pairs
 * that went through GJK (the world's narrow-phase counters, exact; pairs
 * whose element bounding spheres are apart, and pairs answered by the
 * separating-axis test on their warm direction, are culled before it and
 * not counted) plus, for the clumps, the sphere-element pairs, each tested by
 * the analytic sphere law (the element pairs in the list, read after every
 * 50-step chunk). element_pairs_per_s is all element pairs in the list,
 * read the same way. state_hash (FNV-1a of every particle's position,
 * velocity, spin and orientation at the end) shows whether a change kept
 * the bits (bench/ab). Build against a release library build, e.g.
 *   cmake -S . -B build-release -DCMAKE_BUILD_TYPE=Release && cmake --build build-release -j 2 --target shapedem_lib
 *   cc -O2 -std=c17 -fopenmp -Isrc -Iinclude bench/composites_settle.c \
 *      build-release/libshapedem.a $(pkg-config --libs yaml-0.1 hdf5-serial) -lm -o build-release/composites_settle
 *   build-release/composites_settle [--json] [threads] [steps] [warm]
 * --json: one JSON line per kind ({"case":"composites-settle","kind",
 * "particles","steps","threads","wall_s","cpu_s","psps","element_pair_tests_per_s",
 * "element_pairs_per_s","cost_vs_spheres","state_hash","load1"}), as bench/run prints them.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "world/world.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* s of CPU time of this process (all threads): on a shared, loaded machine
 * the one-thread figures are taken from it, wall time being mostly waiting */
static double cpu(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double frand(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (double)(*s >> 8) / 16777216.0;
}

enum { N = 2000 };

static int json;

static double load1(void)
{
    double l = -1;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &l) != 1)
            l = -1;
        fclose(f);
    }
    return l;
}

/* What one case measured. */
typedef struct result {
    double psps, tests, pairs, wall, cpu; /* pairs: element pairs in the list per second */
    unsigned long long hash;
} result;

/* FNV-1a over each particle's position, velocity, spin and orientation in
 * storage order (the same scene and steps give the same order). */
static unsigned long long state_hash(const sd_world *w)
{
    unsigned long long h = 1469598103934665603ull;
    for (size_t k = 0; k < sd_world_particle_count(w); ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        double v[] = {p.position.x, p.position.y, p.position.z, p.velocity.x, p.velocity.y, p.velocity.z,
                      p.angular_velocity.x, p.angular_velocity.y, p.angular_velocity.z, p.quat[0], p.quat[1],
                      p.quat[2], p.quat[3]};
        const unsigned char *b = (const unsigned char *)v;
        for (size_t i = 0; i < sizeof v; ++i) {
            h ^= b[i];
            h *= 1099511628211ull;
        }
    }
    return h;
}

static void run(const char *kind, int threads, int steps, int warm, result *res)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.law = SD_LAW_LINEAR;
    d.dt = 1e-5;
    d.gravity = (sd_v3d){0, 0, -9.81};
    d.threads = threads;
    if (sd_world_create(&d, &w, &err) != SD_OK)
        exit(1);
    sd_material_def m = sd_material_def_default();
    m.density = 2500;
    m.stiffness = 2e4;
    m.restitution = 0.5;
    m.friction = 0.4;
    int mat = sd_world_add_material(w, &m, &err);
    double r = 0.001;
    int shape = -1;
    sd_shape_desc s = sd_shape_desc_default();
    sd_composite_element el[7];
    sd_composite_desc cd = sd_composite_desc_default();
    cd.elements = el;
    if (!strcmp(kind, "cubes")) {
        s.kind = "box";
        s.size = (sd_v3d){2 * r, 2 * r, 2 * r};
        shape = sd_world_add_shape(w, "cube", &s, &err);
    } else if (!strcmp(kind, "clumps")) {
        s.kind = "sphere";
        s.size = (sd_v3d){r, 0, 0};
        int ball = sd_world_add_shape(w, "ball", &s, &err);
        static const double tet[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
        for (int k = 0; k < 4; ++k) {
            memset(&el[k], 0, sizeof el[k]);
            el[k].shape = ball;
            el[k].position = (sd_v3d){1.1 * r * tet[k][0] / sqrt(2.0), 1.1 * r * tet[k][1] / sqrt(2.0),
                                      1.1 * r * tet[k][2] / sqrt(2.0)};
        }
        cd.element_count = 4;
        shape = sd_world_add_composite(w, "clump", &cd, &err);
    } else if (!strcmp(kind, "cross3d")) {
        sd_composite_preset_def pd = sd_composite_preset_def_default();
        pd.preset = "cross3d";
        pd.diameter = 1.4 * r;
        pd.length = 4.2 * r;
        shape = sd_world_add_composite_preset(w, "cross3d", &pd, &err);
    } else if (!strcmp(kind, "crosses")) {
        s.kind = "box";
        double c = 1.4 * r;
        s.size = (sd_v3d){c, c, c};
        int cube = sd_world_add_shape(w, "cube", &s, &err);
        static const double arm[7][3] = {{0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        for (int k = 0; k < 7; ++k) {
            memset(&el[k], 0, sizeof el[k]);
            el[k].shape = cube;
            el[k].position = (sd_v3d){c * arm[k][0], c * arm[k][1], c * arm[k][2]};
        }
        cd.element_count = 7;
        shape = sd_world_add_composite(w, "cross", &cd, &err);
    }
    if (strcmp(kind, "spheres") && shape < 0) {
        char msg[512];
        sd_error_format(&err, msg, sizeof msg);
        fprintf(stderr, "%s: %s\n", kind, msg);
        exit(1);
    }
    enum { NX = 12, NY = 12 };
    double h = 4.5 * r;
    int nz = (N + NX * NY - 1) / (NX * NY);
    sd_world_add_box(w, "box", (sd_v3d){0, 0, 0}, (sd_v3d){NX * h, NY * h, nz * h * 2}, 0, mat, &err);
    static sd_body_def b[N];
    static sd_sphere_def sp[N];
    unsigned seed = 12345;
    for (int n = 0; n < N; ++n) {
        int i = n % NX, j = (n / NX) % NY, k = n / (NX * NY);
        sd_v3d x = {(i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h};
        sd_v3d v = {frand(&seed) - 0.5, frand(&seed) - 0.5, -frand(&seed)};
        memset(&b[n], 0, sizeof b[n]);
        memset(&sp[n], 0, sizeof sp[n]);
        b[n].position = sp[n].position = x;
        b[n].velocity = sp[n].velocity = v;
        b[n].material = sp[n].material = mat;
        sp[n].radius = r;
        double qw = frand(&seed) - 0.5, qx = frand(&seed) - 0.5, qy = frand(&seed) - 0.5, qz = frand(&seed) - 0.5;
        double ql = sqrt(qw * qw + qx * qx + qy * qy + qz * qz);
        b[n].orientation[0] = qw / ql;
        b[n].orientation[1] = qx / ql;
        b[n].orientation[2] = qy / ql;
        b[n].orientation[3] = qz / ql;
        b[n].shape = shape;
    }
    if (!strcmp(kind, "spheres"))
        sd_world_add_spheres(w, N, sp, &err);
    else
        sd_world_add_bodies(w, N, b, &err);
    if (sd_world_step(w, warm, &err) != SD_OK)
        exit(1);
    long long gjk0 = w->narrow[SD_SHAPE_COMPOSITE][SD_SHAPE_COMPOSITE][0];
    double t0 = now(), c0 = cpu(), pairs = 0;
    int chunk = 50;
    for (int k = 0; k < steps; k += chunk) {
        sd_world_step(w, chunk, &err);
        const sd_pair_list *l = &w->pairs;
        pairs += (double)chunk * (double)(l->kind_start[SD_PAIR_ELEMENTS + 1] - l->kind_start[SD_PAIR_ELEMENTS]);
    }
    double t = now() - t0, c = cpu() - c0;
    /* element pairs through GJK; a clump's element pairs are all spheres,
     * each tested by the sphere law */
    double tests = (double)(w->narrow[SD_SHAPE_COMPOSITE][SD_SHAPE_COMPOSITE][0] - gjk0);
    if (!strcmp(kind, "clumps"))
        tests += pairs;
    sd_stats st;
    sd_world_stats(w, &st);
    /* per CPU second with one thread, per wall second with more */
    double tt = threads == 1 ? c : t;
    double psps = (double)N * steps / tt;
    res->psps = psps;
    res->tests = tests / tt;
    res->pairs = pairs / tt;
    res->wall = t;
    res->cpu = c;
    res->hash = state_hash(w);
    if (!json)
        printf("%-8s threads %d: %8.0f particle-steps/s, %10.0f element-pair tests/s (%10.0f element pairs/s), "
               "%ld contacts, %ld wall contacts, %zu candidate pairs, %.2f s wall, %.2f s CPU, state %016llx\n",
               kind, threads, psps, tests / tt, pairs / tt, st.contacts, st.wall_contacts, st.pairs, t, c, res->hash);
    fflush(stdout);
    sd_world_destroy(w);
}

int main(int argc, char **argv)
{
    int a0 = 1;
    if (argc > 1 && !strcmp(argv[1], "--json")) {
        json = 1;
        a0 = 2;
    }
    int threads = argc > a0 ? atoi(argv[a0]) : 1, steps = argc > a0 + 1 ? atoi(argv[a0 + 1]) : 1000,
        warm = argc > a0 + 2 ? atoi(argv[a0 + 2]) : 1000;
    enum { K = 5 };
    static const char *kinds[K] = {"spheres", "cubes", "clumps", "crosses", "cross3d"};
    result r[K];
    double p[K];
    for (int k = 0; k < K; ++k) {
        run(kinds[k], threads, steps, warm, &r[k]);
        p[k] = r[k].psps;
        if (json)
            printf("{\"case\":\"composites-settle\",\"kind\":\"%s\",\"particles\":%d,\"steps\":%d,\"threads\":%d,"
                   "\"wall_s\":%.4g,\"cpu_s\":%.4g,\"psps\":%.4g,\"element_pair_tests_per_s\":%.4g,"
                   "\"element_pairs_per_s\":%.4g,\"cost_vs_spheres\":%.3g,\"state_hash\":\"%016llx\",\"load1\":%.2f}\n",
                   kinds[k], N, steps, threads, r[k].wall, r[k].cpu, p[k], r[k].tests, r[k].pairs, p[0] / p[k],
                   r[k].hash, load1());
        fflush(stdout);
    }
    if (!json)
        printf("cost per particle-step relative to spheres: cubes %.1fx, clumps of 4 spheres %.1fx, crosses of 7 cubes "
               "%.1fx, cross3d %.1fx (crosses / cubes %.1fx)\n",
               p[0] / p[1], p[0] / p[2], p[0] / p[3], p[0] / p[4], p[1] / p[3]);
    return 0;
}
