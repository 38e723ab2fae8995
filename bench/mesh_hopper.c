/* mesh_hopper.c — benchmark `mesh-hopper` (issue 14): 10,000 spheres and
 * 2,000 polyhedra discharging from a conical hopper meshed at two
 * resolutions (about 20,000 and 200,000 facets). Prints particle-steps per
 * second, facet tests per second (the near triangles the mesh items clip
 * or test, summed over the steps) and the ratio of the two meshes' costs;
 * the facet bins (world/mesh.c) should keep the finer mesh within 1.5x of
 * the coarser.
 *
 * The hopper: a cone from the orifice (radius 30 mm at z = 0) to radius
 * 150 mm at z = 0.3 m, then a cylinder to z = 0.6 m; open at the orifice.
 * Particles start on a lattice filling the cone and the cylinder's lower
 * part, so they meet the walls at once. Linear law, dt = 2e-5 s.
 *
 * Run by `bench/run --cases mesh-hopper`, which builds it as
 *   cc -std=c17 -O2 -fopenmp -Isrc -Iinclude bench/mesh_hopper.c build-release/libshapedem.a -lm \
 *      -o build-release/mesh_hopper
 * Run: mesh_hopper [steps, default 2000] [threads, default 2]
 * Output: one JSON line per mesh:
 *   {"case":"mesh-hopper","facets","particles","steps","threads","seconds","psps","facet_tests_per_s",
 *    "facet_tests_per_step","wall_pairs","discharged"}
 */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <shapedem/shapedem.h>

#include "world/world.h"

#define PI 3.14159265358979323846

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct mesh {
    sd_v3d *v;
    uint32_t (*t)[3];
    size_t nv, nt;
} mesh;

/* radius of the hopper wall at height z */
static double wall_r(double z) { return z < 0.3 ? 0.03 + (0.15 - 0.03) * z / 0.3 : 0.15; }

/* ns segments round, nr rings up the cone and nr * 2 / 3 up the cylinder,
 * 2 ns (rings) facets; right-hand normals inward. */
static void hopper(mesh *m, int ns, int nr)
{
    int nc = nr * 2 / 3, rings = nr + nc + 1;
    m->nv = (size_t)ns * (size_t)rings;
    m->nt = 2 * (size_t)ns * (size_t)(rings - 1);
    m->v = malloc(m->nv * sizeof *m->v);
    m->t = malloc(m->nt * sizeof *m->t);
    for (int j = 0; j < rings; ++j) {
        double z = j <= nr ? 0.3 * j / nr : 0.3 + 0.3 * (j - nr) / nc;
        double r = wall_r(z);
        for (int i = 0; i < ns; ++i) {
            double a = 2 * PI * i / ns;
            m->v[(size_t)j * (size_t)ns + (size_t)i] = (sd_v3d){r * cos(a), r * sin(a), z};
        }
    }
    size_t k = 0;
    for (int j = 0; j + 1 < rings; ++j)
        for (int i = 0; i < ns; ++i) {
            uint32_t a = (uint32_t)(j * ns + i), b = (uint32_t)(j * ns + (i + 1) % ns), c = a + (uint32_t)ns,
                     d = b + (uint32_t)ns;
            /* inward: (b - a) x (c - a) points to the axis for counter-clockwise a -> b */
            m->t[k][0] = a, m->t[k][1] = c, m->t[k][2] = b, ++k;
            m->t[k][0] = b, m->t[k][1] = c, m->t[k][2] = d, ++k;
        }
}

static int run(int ns, int nr, long steps, int threads)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = SD_LAW_LINEAR;
    wd.dt = 2e-5;
    wd.gravity = (sd_v3d){0, 0, -9.81};
    wd.threads = threads;
    if (sd_world_create(&wd, &w, &err) != SD_OK)
        return fprintf(stderr, "world: %s\n", err.msg), 1;
    sd_material_def md = sd_material_def_default();
    md.name = "grain";
    md.density = 2500;
    md.stiffness = 2e4;
    md.restitution = 0.3;
    md.friction = 0.5;
    int mat = sd_world_add_material(w, &md, &err);
    mesh m = {0};
    hopper(&m, ns, nr);
    sd_mesh_def mdef = sd_mesh_def_default();
    mdef.vertices = m.v;
    mdef.vertex_count = m.nv;
    mdef.triangles = (const uint32_t(*)[3])m.t;
    mdef.triangle_count = m.nt;
    mdef.material = mat;
    int wall = sd_world_add_mesh(w, "hopper", &mdef, &err);
    if (wall < 0)
        return fprintf(stderr, "mesh: %s\n", err.msg), 1;
    sd_shape_desc sh = sd_shape_desc_default();
    sh.kind = "polyhedron";
    sd_v3d oct[6] = {{0.004, 0, 0}, {-0.004, 0, 0}, {0, 0.004, 0}, {0, -0.004, 0}, {0, 0, 0.004}, {0, 0, -0.004}};
    sh.vertices = oct;
    sh.vertex_count = 6;
    sh.margin = 0.0005;
    int shape = sd_world_add_shape(w, "octahedron", &sh, &err);
    if (shape < 0)
        return fprintf(stderr, "shape: %s\n", err.msg), 1;
    /* a lattice of 9 mm cells inside the hopper, from z = 0.02 m up */
    enum { NS = 10000, NP = 2000 };
    sd_sphere_def *sp = calloc(NS, sizeof *sp);
    sd_body_def *bp = calloc(NP, sizeof *bp);
    size_t ks = 0, kp = 0, cell = 0;
    const double h = 0.009;
    for (double z = 0.02; ks < NS || kp < NP; z += h) {
        double r = wall_r(z) - 0.0046; /* 4.3 mm from the cone (normal), 0.6 mm inside the reach */
        for (double x = -r; x <= r; x += h)
            for (double y = -r; y <= r; y += h) {
                if (x * x + y * y > r * r)
                    continue;
                if (cell++ % 6 == 5 && kp < NP) {
                    bp[kp].position = (sd_v3d){x, y, z};
                    bp[kp].shape = shape;
                    bp[kp].material = mat;
                    ++kp;
                } else if (ks < NS) {
                    sp[ks].position = (sd_v3d){x, y, z};
                    sp[ks].radius = 0.004;
                    sp[ks].material = mat;
                    ++ks;
                }
            }
    }
    if (sd_world_add_spheres(w, NS, sp, &err) != SD_OK || sd_world_add_bodies(w, NP, bp, &err) != SD_OK)
        return fprintf(stderr, "particles: %s\n", err.msg), 1;
    free(sp);
    free(bp);
    if (sd_world_step(w, 500, &err) != SD_OK) /* warm up: contacts with the walls form */
        return fprintf(stderr, "step: %s\n", err.msg), 1;
    double tests = 0, t0 = now();
    const long chunk = 50;
    for (long s = 0; s < steps; s += chunk) {
        if (sd_world_step(w, chunk, &err) != SD_OK)
            return fprintf(stderr, "step: %s\n", err.msg), 1;
        /* the near triangles every mesh pair visits each step, sampled per chunk */
        const sd_wall_pair_list *l = &w->wpairs;
        double per = 0;
        for (size_t e = l->kind_start[SD_WALL_PAIR_MESH_SPHERE]; e < l->kind_start[SD_WALL_PAIR_MESH_CONVEX2D]; ++e)
            per += l->tcount[e];
        tests += per * (double)chunk;
    }
    double sec = now() - t0;
    long below = 0;
    for (size_t k = 0; k < sd_world_particle_count(w); ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        below += p.position.z < 0;
    }
    const sd_wall_pair_list *l = &w->wpairs;
    printf("{\"case\":\"mesh-hopper\",\"facets\":%zu,\"particles\":%d,\"steps\":%ld,\"threads\":%d,\"seconds\":%.3f,"
           "\"psps\":%.0f,\"facet_tests_per_s\":%.0f,\"facet_tests_per_step\":%.0f,\"wall_pairs\":%zu,"
           "\"discharged\":%ld}\n",
           m.nt, NS + NP, steps, threads, sec, (double)(NS + NP) * (double)steps / sec, tests / sec,
           tests / (double)steps, l->n, below);
    fflush(stdout);
    sd_world_destroy(w);
    free(m.v);
    free(m.t);
    return 0;
}

int main(int argc, char **argv)
{
    long steps = argc > 1 ? atol(argv[1]) : 2000;
    int threads = argc > 2 ? atoi(argv[2]) : 2;
    /* 2 * 100 * (60 + 40) = 20,000 facets; 2 * 316 * (190 + 126) = 199,712 */
    if (run(100, 60, steps, threads))
        return 1;
    return run(316, 190, steps, threads);
}
