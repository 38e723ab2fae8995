/* overlap_micro.c — micro-benchmark of the exact polyhedron overlap volume
 * (geom/overlap.h, seed 000 §2.3): overlapping pairs only, one core, pairs
 * per second for cube–cube, dodecahedron–dodecahedron and 32-face random
 * polyhedra (issue 4 target: >= 500,000 dodecahedron pairs per second per core).
 *
 * Invariant: the pairs are a pure function of the seed (sd_rng), so runs on
 * one machine compare; each measurement keeps the best of several repeats
 * (bench/README.md: benchmarks keep the best, tests never time).
 *
 * Pairs: both bodies of diameter 1 (circumscribed sphere), random
 * orientations, centres a uniform random fraction of the summed bounding
 * radii apart along a random direction; only pairs that overlap are kept.
 *   cold: no hint (the midpoint of the centres is tried as the interior
 *         point, else the GJK gate runs: gjk_share says how often);
 *   warm: the pair's previous x0 as the hint (a resting contact).
 *
 * Build (the numerics are headers; templates need three library files):
 *   cc -std=c17 -O2 -Isrc -Iinclude bench/overlap_micro.c src/shape/shape.c src/shape/polylib.c \
 *      src/core/alloc.c src/core/error.c -lm -o build-release/overlap_micro
 * Run: overlap_micro [--json] [pairs per type, default 4096] [repeats, default 5]
 * --json prints one line per pair type (bench/run case overlap-micro):
 *   {"case":"overlap-micro","pair","pairs","faces","cold_pps","warm_pps","cold_us","warm_us",
 *    "gjk_share","mean_faces","mean_vertices"}
 */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/error.h"
#include "core/rng.h"
#include "../tests/random_pose.h"
#include "geom/overlap.h"
#include "shape/polylib.h"
#include "shape/shape_make.h"

#define TV 256

typedef struct tpl {
    sd_shape s;
    sd_vec3 v[TV];
    sd_plane p[2 * TV];
    sd_dtri t[4 * TV];
} tpl;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int tpl_make(tpl *T, int preset, int faces, uint64_t seed)
{
    sd_poly_def d;
    memset(&d, 0, sizeof d);
    d.preset = preset;
    d.diameter = 1.0;
    d.faces = faces;
    d.seed = seed;
    sd_v3d vv[TV];
    sd_vec3 pts[TV];
    size_t n, used, np, nt;
    sd_error err;
    if (sd_polylib_vertices(&d, vv, TV, &n, &err) != SD_OK)
        return fprintf(stderr, "overlap_micro: %s\n", err.msg), 1;
    for (size_t k = 0; k < n; ++k)
        pts[k] = sd_v3(vv[k].x, vv[k].y, vv[k].z);
    sd_shape_def sd = sd_shape_def_default();
    sd.kind = SD_SHAPE_POLYHEDRON;
    sd.vertices = pts;
    sd.vertex_count = n;
    if (sd_shape_make(&sd, &T->s, T->v, TV, &used, &err) != SD_OK)
        return fprintf(stderr, "overlap_micro: %s\n", err.msg), 1;
    T->s.vstart = 0;
    T->s.vcount = (uint32_t)used;
    if (sd_shape_faces(&T->s, T->v, T->p, 2 * TV, &np, T->t, 4 * TV, &nt, &err) != SD_OK)
        return fprintf(stderr, "overlap_micro: %s\n", err.msg), 1;
    return 0;
}

/* A rotation from a point uniform in the unit 4-ball, normalised (also
 * uniform); not random_pose.h's formula, so that the poses, and the rates
 * recorded in bench/RESULTS.md, stay the same. */
static sd_quat rand_quat_ball(sd_rng *r)
{
    sd_quat q;
    double n2;
    do {
        q = sd_quat_make(sd_rng_range(r, -1, 1), sd_rng_range(r, -1, 1), sd_rng_range(r, -1, 1),
                         sd_rng_range(r, -1, 1));
        n2 = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
    } while (n2 > 1 || n2 < 1e-4);
    return sd_quat_normalize(q);
}

static sd_overlap_workspace ws;

int main(int argc, char **argv)
{
    int json = 0, npairs = 4096, repeats = 5, pos = 0;
    for (int k = 1; k < argc; ++k) {
        if (!strcmp(argv[k], "--json"))
            json = 1;
        else if (pos++ == 0)
            npairs = atoi(argv[k]);
        else
            repeats = atoi(argv[k]);
    }
    if (npairs < 1 || repeats < 1) {
        fprintf(stderr, "usage: overlap_micro [--json] [pairs per type] [repeats]\n");
        return 2;
    }
    static tpl T;
    sd_convex *A = malloc((size_t)npairs * sizeof *A), *B = malloc((size_t)npairs * sizeof *B);
    sd_vec3 *x0 = malloc((size_t)npairs * sizeof *x0);
    if (!A || !B || !x0)
        return fprintf(stderr, "overlap_micro: out of memory\n"), 1;
    struct {
        const char *name;
        int preset, faces;
    } sets[] = {{"cube-cube", SD_POLY_CUBE, 0},
                {"dodecahedron-dodecahedron", SD_POLY_DODECAHEDRON, 0},
                {"random32-random32", SD_POLY_RANDOM, 32}};
    if (!json)
        printf("%-27s %6s %6s %12s %12s %9s %9s %6s %6s %6s\n", "pair", "pairs", "faces", "cold pairs/s",
               "warm pairs/s", "cold us", "warm us", "gjk %", "faces", "verts");
    for (size_t s = 0; s < sizeof sets / sizeof sets[0]; ++s) {
        if (tpl_make(&T, sets[s].preset, sets[s].faces, 5))
            return 1;
        sd_rng r = sd_rng_seed(2026 + s);
        int m = 0, gjk = 0;
        double faces = 0, verts = 0;
        const double reach = 2 * T.s.bound;
        while (m < npairs) {
            sd_convex a, b;
            a.shape = b.shape = &T.s;
            a.verts = b.verts = T.v;
            a.planes = b.planes = T.p;
            a.dtris = b.dtris = T.t;
            a.x = sd_v3_zero();
            a.q = rand_quat_ball(&r);
            b.x = sd_v3_scale(rand_unit(&r), sd_rng_uniform(&r) * reach);
            b.q = rand_quat_ball(&r);
            sd_overlap o = sd_overlap_polyhedra(&a, &b, sd_v3_zero(), 0, &ws);
            if (o.status != SD_OVERLAP_OK)
                continue;
            A[m] = a;
            B[m] = b;
            x0[m] = o.x0;
            faces += o.faces;
            verts += o.vertices;
            /* would the cold call have needed GJK? (the midpoint outside a plane) */
            sd_vec3 mid = sd_v3_scale(sd_v3_add(a.x, b.x), 0.5);
            int out = 0;
            for (int c = 0; c < 2; ++c) {
                const sd_convex *cv = c ? &b : &a;
                for (uint32_t f = 0; f < T.s.fcount; ++f) {
                    sd_vec3 n = sd_quat_rotate(cv->q, T.p[f].n);
                    out |= sd_v3_dot(n, sd_v3_sub(mid, cv->x)) >= T.p[f].h - SD_OVERLAP_HINT_REL * reach;
                }
            }
            gjk += out;
            ++m;
        }
        double best_cold = 1e300, best_warm = 1e300, sink = 0;
        for (int rep = 0; rep < repeats; ++rep) {
            double t0 = now();
            for (int i = 0; i < npairs; ++i)
                sink += sd_overlap_polyhedra(&A[i], &B[i], sd_v3_zero(), 0, &ws).volume;
            double t1 = now();
            for (int i = 0; i < npairs; ++i)
                sink += sd_overlap_polyhedra(&A[i], &B[i], x0[i], 1, &ws).volume;
            double t2 = now();
            best_cold = best_cold < t1 - t0 ? best_cold : t1 - t0;
            best_warm = best_warm < t2 - t1 ? best_warm : t2 - t1;
        }
        if (sink < 0)
            printf("impossible\n");
        double cps = npairs / best_cold, wps = npairs / best_warm;
        if (json)
            printf("{\"case\":\"overlap-micro\",\"pair\":\"%s\",\"pairs\":%d,\"faces\":%u,\"cold_pps\":%.0f,"
                   "\"warm_pps\":%.0f,\"cold_us\":%.4g,\"warm_us\":%.4g,\"gjk_share\":%.4g,\"mean_faces\":%.3g,"
                   "\"mean_vertices\":%.3g}\n",
                   sets[s].name, npairs, T.s.fcount, cps, wps, 1e6 / cps, 1e6 / wps, (double)gjk / npairs,
                   faces / npairs, verts / npairs);
        else
            printf("%-27s %6d %6u %12.0f %12.0f %9.3f %9.3f %6.1f %6.1f %6.1f\n", sets[s].name, npairs, T.s.fcount, cps,
                   wps, 1e6 / cps, 1e6 / wps, 100.0 * gjk / npairs, faces / npairs, verts / npairs);
    }
    free(A);
    free(B);
    free(x0);
    return 0;
}
