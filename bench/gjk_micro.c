/* gjk_micro.c — micro-benchmark of the convex narrow phase: GJK distance,
 * and GJK + EPA through sd_convex_collide (geom/convex_contact.h), on fixed
 * random pairs per shape pair, one core. Prints pairs per second.
 *
 * Invariant: the pairs are a pure function of the seed (sd_rng), so runs on
 * one machine compare; each measurement keeps the best of several repeats
 * (bench/README.md: benchmarks keep the best, tests never time).
 * Seed 004 §2.5 (shrink / GJK / swell), seed 002 Table 1 (support calls).
 *
 * Build (header-only numerics; needs no library):
 *   cc -std=c17 -O2 -ffp-contract=off -Isrc -Iinclude bench/gjk_micro.c -lm -o build-release/gjk_micro
 * or in CMake: add_executable(gjk_micro bench/gjk_micro.c) with
 *   target_include_directories(gjk_micro PRIVATE src include) and target_link_libraries(gjk_micro m).
 * Run: gjk_micro [--json] [pairs per type, default 4096] [repeats, default 5]
 *      gjk_micro --packing [pairs, default 4000] [repeats, default 5]
 * --packing: the shallow contacts of issue 11 §5's packing (sharp cylinders
 * L = D = 2.62 mm and cubes of the same volume, placed at a penetration of
 * 0–2 % of the size along a random direction): µs per pair of GJK alone,
 * GJK + EPA (cubes; cylinders) and GJK + the closed form of
 * geom/cylinder_contact.h (cylinders), one core, best of the repeats, in
 * CPU time of the thread (CLOCK_THREAD_CPUTIME_ID), not wall time.
 *
 * Two sets of pairs per shape pair:
 *   random: centres 0.5–1.0 of the summed bounding radii apart, random
 *           orientations; about half the pairs touch and most of those have
 *           overlapping cores (EPA);
 *   dem:    rounded or margined shapes placed, along a random direction, at a
 *           swept gap uniform in [−ρ, +ρ] (ρ = ra + rb): the cores never
 *           overlap, half the swept bodies touch, as in a packing's candidate
 *           list with a skin. This is the narrow phase of a settling scene
 *           (GJK only: shrink / GJK / swell).
 * --json prints one line per set (bench/run case gjk-micro):
 *   {"case":"gjk-micro","set","pair","pairs","touching","cores_overlap",
 *    "gjk_pps","collide_pps","warm_pps","collide_us","warm_us","sup_cold","sup_warm"}
 * with pairs per second on one core (pps), µs per pair (us) and support
 * calls per pair (sup) cold and warm (the pair's cached direction, static
 * pairs).
 */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/rng.h"
#include "../tests/random_pose.h"
#include "geom/convex_contact.h"
#include "geom/cylinder_contact.h"

#define POOL_MAX (1 << 20)
static sd_vec3 pool[POOL_MAX];
static uint32_t pool_n;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* kind: SD_SHAPE_*; radius: the swept radius (rounded shapes) */
static sd_shape make_shape(sd_rng *r, int kind, double radius)
{
    sd_shape s;
    memset(&s, 0, sizeof s);
    s.kind = kind;
    s.radius = radius;
    double z = sd_rng_range(r, 0.3, 0.5);
    s.a = sd_v3(z * sd_rng_range(r, 0.6, 1), z * sd_rng_range(r, 0.6, 1), z * sd_rng_range(r, 0.6, 1));
    switch (kind) {
    case SD_SHAPE_SPHERE:
        s.a = sd_v3_zero();
        s.radius = z;
        s.bound = z;
        break;
    case SD_SHAPE_BOX:
        s.bound = sd_v3_norm(s.a) + radius;
        break;
    case SD_SHAPE_CYLINDER:
        s.a.y = s.a.x;
        s.bound = sqrt(s.a.x * s.a.x + s.a.z * s.a.z) + radius;
        break;
    case SD_SHAPE_CONE:
        s.a.y = s.a.x;
        s.a.z *= 2;
        s.offset = sd_v3(0, 0, -0.25 * s.a.z);
        s.bound = sd_max(0.75 * s.a.z, sqrt(s.a.x * s.a.x + 0.0625 * s.a.z * s.a.z)) + radius;
        break;
    case SD_SHAPE_ELLIPSOID:
        s.bound = sd_max(s.a.x, sd_max(s.a.y, s.a.z)) + radius;
        break;
    default: { /* polyhedron: 20 points on a squashed sphere */
        int n = 20;
        s.vstart = pool_n;
        s.vcount = (uint32_t)n;
        double b = 0;
        for (int i = 0; i < n; ++i) {
            sd_vec3 p = sd_v3_mul(rand_unit(r), s.a);
            pool[pool_n++] = p;
            b = sd_max(b, sd_v3_norm(p));
        }
        s.bound = b + radius;
    }
    }
    return s;
}

typedef struct pair_set {
    const char *name;
    int ka, kb;
    double ra, rb;
    int dem; /* placed at a swept gap in [-(ra + rb), ra + rb] (see the top) */
} pair_set;

/* Centre distance along u at which the core distance is `target` > 0
 * (bisection: the core distance grows with the separation along a ray). */
static double place_at(sd_convex *A, sd_convex *B, sd_vec3 u, double target)
{
    double lo = 0, hi = A->shape->bound + B->shape->bound + target;
    for (int k = 0; k < 60; ++k) {
        double mid = 0.5 * (lo + hi);
        B->x = sd_v3_scale(u, mid);
        sd_gjk_result g = sd_gjk_distance(A, B, sd_v3_zero());
        if (g.distance < target)
            lo = mid;
        else
            hi = mid;
    }
    return hi;
}

/* --packing: see the top. Depth by bisection along u with EPA's depth. */
static void place_pen(sd_convex *A, sd_convex *B, sd_vec3 u, double target)
{
    double lo = 0, hi = A->shape->bound + B->shape->bound;
    for (int k = 0; k < 50; ++k) {
        double mid = 0.5 * (lo + hi);
        B->x = sd_v3_scale(u, mid);
        sd_gjk_result g = sd_gjk_distance(A, B, sd_v3_zero());
        double d = -1;
        if (g.status == SD_GJK_TOUCHING || g.status == SD_GJK_OVERLAP)
            d = sd_epa_penetration(A, B, &g).depth;
        if (d > target)
            lo = mid;
        else
            hi = mid;
    }
    B->x = sd_v3_scale(u, lo);
}

/* CPU time of this thread: the machine may be shared */
static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int packing(int n, int reps)
{
    sd_shape cyl, cube;
    memset(&cyl, 0, sizeof cyl);
    memset(&cube, 0, sizeof cube);
    cyl.kind = SD_SHAPE_CYLINDER;
    cyl.a = sd_v3(1.310370697e-3, 1.310370697e-3, 1.310370697e-3);
    cyl.bound = sqrt(2.0) * 1.310370697e-3;
    cube.kind = SD_SHAPE_BOX;
    cube.a = sd_v3(1.209e-3, 1.209e-3, 1.209e-3);
    cube.bound = sd_v3_norm(cube.a);
    sd_convex *A = malloc(sizeof(sd_convex) * (size_t)n), *B = malloc(sizeof(sd_convex) * (size_t)n);
    if (!A || !B)
        return 1;
    printf("gjk_micro --packing: %d pairs at 0-2 %% penetration per shape, best of %d, one core\n", n, reps);
    printf("%-10s %-22s %10s %10s %12s\n", "shape", "narrow phase", "us/pair", "x cubes", "overlapping");
    double cube_us = 0;
    volatile double sink = 0;
    for (int sh = 0; sh < 2; ++sh) {
        const sd_shape *s = sh == 0 ? &cube : &cyl;
        sd_rng r = sd_rng_seed(77u + (uint64_t)sh);
        for (int i = 0; i < n; ++i) {
            memset(&A[i], 0, sizeof A[i]);
            memset(&B[i], 0, sizeof B[i]);
            A[i].shape = B[i].shape = s;
            A[i].q = rand_quat(&r);
            B[i].q = rand_quat(&r);
            place_pen(&A[i], &B[i], rand_unit(&r), sd_rng_range(&r, 0, 0.02) * 2.62e-3);
        }
        int nvar = sh == 0 ? 2 : 3;
        for (int var = 0; var < nvar; ++var) {
            double best = 1e300;
            int ovl = 0;
            for (int k = 0; k < reps; ++k) {
                ovl = 0;
                double t0 = cpu_now();
                for (int i = 0; i < n; ++i) {
                    sd_gjk_result g = sd_gjk_distance(&A[i], &B[i], sd_v3_zero());
                    sink += g.distance;
                    if (var == 0 || !(g.status == SD_GJK_TOUCHING || g.status == SD_GJK_OVERLAP))
                        continue;
                    ovl++;
                    if (var == 1)
                        sink += sd_epa_penetration(&A[i], &B[i], &g).depth;
                    else
                        sink += sd_cylc_penetration(&A[i], &B[i]).depth;
                }
                best = sd_min(best, cpu_now() - t0);
            }
            double us = 1e6 * best / n;
            if (sh == 0 && var == 1)
                cube_us = us;
            const char *what = var == 0 ? "GJK alone" : (var == 1 ? "GJK + EPA" : "GJK + closed form");
            printf("%-10s %-22s %10.3f %10.2f %11.0f%%\n", sh == 0 ? "cube" : "cylinder", what, us,
                   cube_us > 0 && var > 0 ? us / cube_us : 0.0, 100.0 * ovl / n);
        }
    }
    free(A);
    free(B);
    return sink == 12345.678 ? 2 : 0;
}

int main(int argc, char **argv)
{
    if (argc > 1 && !strcmp(argv[1], "--packing"))
        return packing(argc > 2 ? atoi(argv[2]) : 4000, argc > 3 ? atoi(argv[3]) : 5);
    int json = argc > 1 && !strcmp(argv[1], "--json");
    if (json) {
        argc--;
        argv++;
    }
    int n = argc > 1 ? atoi(argv[1]) : 4096;
    int reps = argc > 2 ? atoi(argv[2]) : 5;
    if (n < 1 || reps < 1)
        return 1;
    const pair_set sets[] = {
        {"sphere-sphere (point cores)", SD_SHAPE_SPHERE, SD_SHAPE_SPHERE, 0, 0, 0},
        {"box-box", SD_SHAPE_BOX, SD_SHAPE_BOX, 0, 0, 0},
        {"rounded box-box (r=0.05)", SD_SHAPE_BOX, SD_SHAPE_BOX, 0.05, 0.05, 0},
        {"polyhedron-polyhedron (20 v)", SD_SHAPE_POLYHEDRON, SD_SHAPE_POLYHEDRON, 0, 0, 0},
        {"box-polyhedron", SD_SHAPE_BOX, SD_SHAPE_POLYHEDRON, 0, 0, 0},
        {"sphere-box", SD_SHAPE_SPHERE, SD_SHAPE_BOX, 0, 0, 0},
        {"cylinder-cone", SD_SHAPE_CYLINDER, SD_SHAPE_CONE, 0, 0, 0},
        {"ellipsoid-ellipsoid", SD_SHAPE_ELLIPSOID, SD_SHAPE_ELLIPSOID, 0, 0, 0},
        {"rounded ellipsoid-ellipsoid (r=0.05)", SD_SHAPE_ELLIPSOID, SD_SHAPE_ELLIPSOID, 0.05, 0.05, 0},
        /* dem: margins of 5-10 % of the size, shallow contacts, cores apart */
        {"sphere-sphere", SD_SHAPE_SPHERE, SD_SHAPE_SPHERE, 0, 0, 1},
        {"sphere-box (r=0.02)", SD_SHAPE_SPHERE, SD_SHAPE_BOX, 0, 0.02, 1},
        {"box-box (r=0.02)", SD_SHAPE_BOX, SD_SHAPE_BOX, 0.02, 0.02, 1},
        {"polyhedron-polyhedron (20 v, r=0.02)", SD_SHAPE_POLYHEDRON, SD_SHAPE_POLYHEDRON, 0.02, 0.02, 1},
        {"box-polyhedron (r=0.02)", SD_SHAPE_BOX, SD_SHAPE_POLYHEDRON, 0.02, 0.02, 1},
        {"sphere-ellipsoid (r=0.02)", SD_SHAPE_SPHERE, SD_SHAPE_ELLIPSOID, 0, 0.02, 1},
        {"box-cylinder (r=0.02)", SD_SHAPE_BOX, SD_SHAPE_CYLINDER, 0.02, 0.02, 1},
        {"cylinder-cone (r=0.02)", SD_SHAPE_CYLINDER, SD_SHAPE_CONE, 0.02, 0.02, 1},
        {"cylinder-cylinder (r=0.02)", SD_SHAPE_CYLINDER, SD_SHAPE_CYLINDER, 0.02, 0.02, 1},
        {"ellipsoid-ellipsoid (r=0.02)", SD_SHAPE_ELLIPSOID, SD_SHAPE_ELLIPSOID, 0.02, 0.02, 1},
        {"ellipsoid-polyhedron (r=0.02)", SD_SHAPE_ELLIPSOID, SD_SHAPE_POLYHEDRON, 0.02, 0.02, 1},
    };
    const int nsets = (int)(sizeof sets / sizeof sets[0]);
    sd_shape *sa = malloc(sizeof(sd_shape) * (size_t)n), *sb = malloc(sizeof(sd_shape) * (size_t)n);
    sd_convex *A = malloc(sizeof(sd_convex) * (size_t)n), *B = malloc(sizeof(sd_convex) * (size_t)n);
    sd_vec3 *warm = malloc(sizeof(sd_vec3) * (size_t)n);
    if (!sa || !sb || !A || !B || !warm)
        return 1;
    if (!json) {
        printf("gjk_micro: %d fixed random pairs per type, best of %d, one core\n", n, reps);
        printf("%-5s %-38s %8s %10s %12s %12s %12s %8s %8s\n", "set", "pair type", "overlap", "cores ovl",
               "GJK pairs/s", "collide/s", "warm/s", "sup/pair", "sup warm");
    }
    volatile double sink = 0;
    for (int t = 0; t < nsets; ++t) {
        sd_rng r = sd_rng_seed(1000u + (uint64_t)t);
        pool_n = 0;
        for (int i = 0; i < n; ++i) {
            sa[i] = make_shape(&r, sets[t].ka, sets[t].ra);
            sb[i] = make_shape(&r, sets[t].kb, sets[t].rb);
        }
        for (int i = 0; i < n; ++i) {
            /* random: centres 0.5–1.0 of the summed bounding radii apart:
             * about half the pairs touch */
            double sep = sd_rng_range(&r, 0.5, 1.0) * (sa[i].bound + sb[i].bound);
            A[i].shape = &sa[i];
            B[i].shape = &sb[i];
            A[i].verts = B[i].verts = pool;
            A[i].x = sd_v3_zero();
            sd_vec3 u = rand_unit(&r);
            B[i].x = sd_v3_scale(u, sep);
            A[i].q = rand_quat(&r);
            B[i].q = rand_quat(&r);
            if (sets[t].dem) {
                /* dem: a swept gap uniform in [-rho, rho], cores apart */
                double rho = sa[i].radius + sb[i].radius;
                double gap = sd_rng_range(&r, -1.0, 1.0) * rho;
                place_at(&A[i], &B[i], u, sd_max(rho + gap, 1e-3 * rho));
            }
        }
        int touching = 0, core_ovl = 0;
        long sup = 0;
        for (int i = 0; i < n; ++i) {
            warm[i] = sd_v3_zero();
            sd_convex_contact c = sd_convex_collide(&A[i], &B[i], &warm[i]);
            touching += c.touching;
            core_ovl += c.used_epa;
            sup += c.support_calls;
        }
        long supw = 0;
        for (int i = 0; i < n; ++i) {
            sd_convex_contact c = sd_convex_collide(&A[i], &B[i], &warm[i]);
            supw += c.support_calls;
        }
        double best_gjk = 1e300, best_col = 1e300, best_warm = 1e300;
        for (int k = 0; k < reps; ++k) {
            double t0 = now();
            for (int i = 0; i < n; ++i) {
                sd_gjk_result g = sd_gjk_distance(&A[i], &B[i], sd_v3_zero());
                sink += g.distance;
            }
            double t1 = now();
            for (int i = 0; i < n; ++i) {
                sd_convex_contact c = sd_convex_collide(&A[i], &B[i], NULL);
                sink += c.delta;
            }
            double t2 = now();
            for (int i = 0; i < n; ++i) { /* warm start from the previous pass (a static pair) */
                sd_convex_contact c = sd_convex_collide(&A[i], &B[i], &warm[i]);
                sink += c.delta;
            }
            double t3 = now();
            best_gjk = sd_min(best_gjk, t1 - t0);
            best_col = sd_min(best_col, t2 - t1);
            best_warm = sd_min(best_warm, t3 - t2);
        }
        const char *set = sets[t].dem ? "dem" : "random";
        if (json)
            printf("{\"case\":\"gjk-micro\",\"set\":\"%s\",\"pair\":\"%s\",\"pairs\":%d,\"touching\":%.3f,"
                   "\"cores_overlap\":%.3f,\"gjk_pps\":%.4g,\"collide_pps\":%.4g,\"warm_pps\":%.4g,\"collide_us\":%.4g,"
                   "\"warm_us\":%.4g,\"sup_cold\":%.2f,\"sup_warm\":%.2f}\n",
                   set, sets[t].name, n, (double)touching / n, (double)core_ovl / n, n / best_gjk, n / best_col,
                   n / best_warm, 1e6 * best_col / n, 1e6 * best_warm / n, (double)sup / n, (double)supw / n);
        else
            printf("%-5s %-38s %7.0f%% %9.0f%% %12.3g %12.3g %12.3g %8.2f %8.2f\n", sets[t].dem ? "dem" : "rand",
                   sets[t].name, 100.0 * touching / n, 100.0 * core_ovl / n, n / best_gjk, n / best_col, n / best_warm,
                   (double)sup / n, (double)supw / n);
    }
    if (!json)
        printf("(GJK pairs/s: sd_gjk_distance alone; collide/s: sd_convex_collide, GJK + EPA where the cores overlap,\n"
               " cold start; warm/s: the same with each pair's cached direction; sup/pair, sup warm: support calls of\n"
               " K = A - B per collide, cold and warm)\n");
    free(sa);
    free(sb);
    free(A);
    free(B);
    free(warm);
    return sink == 12345.678 ? 2 : 0;
}
