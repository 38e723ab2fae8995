/* process_mesh.c — insertion into a mesh region (issue 16; region kind
 * SD_REGION_MESH, `region: mesh` in a scene): the region is an L-shaped
 * prism, a closed non-convex mesh of 20 triangles.
 *  - 600 spheres all at once: all go in, no two overlap, every centre
 *    lies inside the L (checked here on the polygon, not on the mesh) and
 *    every sphere clear of the L's faces (its distance to the boundary,
 *    computed here from the polygon's edges and the two caps, >= r), and
 *    the notch of the L (inside the mesh's box, outside the mesh) holds
 *    none; the same with the mesh wound the other way (winding -1);
 *  - the same region from a scene (an OBJ file, scale and position);
 *  - bad input: a mesh with a triangle missing (not closed) is refused
 *    with the key insert.region, and an outlet cannot be a mesh.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test.h"

#include <shapedem/process.h>
#include <shapedem/scene.h>

/* the L in x-y, counter-clockwise; extruded over z in [0, H] */
static const double L[6][2] = {{0, 0}, {0.06, 0}, {0.06, 0.02}, {0.02, 0.02}, {0.02, 0.06}, {0, 0.06}};
static const double H = 0.02;

static sd_v3d verts[12];
static uint32_t tris[20][3];

/* The prism's 12 vertices (bottom 0-5, top 6-11) and 20 triangles, wound
 * outward (flip: inward). */
static void make_l(int flip)
{
    for (int k = 0; k < 6; ++k) {
        verts[k] = sd_test_v(L[k][0], L[k][1], 0);
        verts[6 + k] = sd_test_v(L[k][0], L[k][1], H);
    }
    int n = 0;
    /* caps: a fan from the reflex corner 3, which sees every other corner */
    static const int fan[4][2] = {{4, 5}, {5, 0}, {0, 1}, {1, 2}};
    for (int k = 0; k < 4; ++k) {
        uint32_t a = 3, b = (uint32_t)fan[k][0], c = (uint32_t)fan[k][1];
        tris[n][0] = a, tris[n][1] = c, tris[n][2] = b; /* bottom, normal -z */
        ++n;
        tris[n][0] = 6 + a, tris[n][1] = 6 + b, tris[n][2] = 6 + c; /* top, +z */
        ++n;
    }
    for (uint32_t k = 0; k < 6; ++k) { /* sides, normal outward for a counter-clockwise polygon */
        uint32_t k1 = (k + 1) % 6;
        tris[n][0] = k, tris[n][1] = k1, tris[n][2] = 6 + k1;
        ++n;
        tris[n][0] = k, tris[n][1] = 6 + k1, tris[n][2] = 6 + k;
        ++n;
    }
    if (flip)
        for (int t = 0; t < 20; ++t) {
            uint32_t s = tris[t][1];
            tris[t][1] = tris[t][2];
            tris[t][2] = s;
        }
}

static int in_l(double x, double y)
{
    return x >= 0 && y >= 0 && ((x <= 0.06 && y <= 0.02) || (x <= 0.02 && y <= 0.06));
}

/* distance from (x, y) to the L's boundary polygon */
static double edge_dist(double x, double y)
{
    double d = HUGE_VAL;
    for (int k = 0; k < 6; ++k) {
        const double *a = L[k], *b = L[(k + 1) % 6];
        double ex = b[0] - a[0], ey = b[1] - a[1];
        double t = ((x - a[0]) * ex + (y - a[1]) * ey) / (ex * ex + ey * ey);
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        double dx = a[0] + t * ex - x, dy = a[1] + t * ey - y;
        d = fmin(d, sqrt(dx * dx + dy * dy));
    }
    return d;
}

static sd_world *world(int *mat)
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

/* checks a world's particles against the L (shifted by (dx, dy, dz)) */
static void check_inside(const char *what, const sd_world *w, size_t expect, double dx, double dy, double dz)
{
    size_t n = sd_world_particle_count(w);
    int outside = 0, touching = 0, notch = 0, overlaps = 0;
    double closest = HUGE_VAL;
    sd_particle_state *s = calloc(n, sizeof *s);
    for (size_t k = 0; k < n; ++k) {
        sd_world_get_particle(w, k, &s[k]);
        double x = s[k].position.x - dx, y = s[k].position.y - dy, z = s[k].position.z - dz;
        outside += !in_l(x, y) || z < 0 || z > H;
        notch += x > 0.02 && y > 0.02;
        double gap = fmin(edge_dist(x, y), fmin(z, H - z)) - s[k].radius;
        closest = fmin(closest, gap);
        touching += gap < -1e-12;
        for (size_t j = 0; j < k; ++j) {
            double ex = s[j].position.x - s[k].position.x, ey = s[j].position.y - s[k].position.y,
                   ez = s[j].position.z - s[k].position.z;
            overlaps += sqrt(ex * ex + ey * ey + ez * ez) < s[j].radius + s[k].radius;
        }
    }
    free(s);
    printf("     %s: %zu particles (expected %zu); centres outside the L %d, in its notch %d, spheres crossing its "
           "faces %d (closest gap %.3g m), overlapping pairs %d\n",
           what, n, expect, outside, notch, touching, closest, overlaps);
    CHECK(n == expect);
    CHECK(outside == 0 && notch == 0 && touching == 0 && overlaps == 0);
}

static void insert_l(int flip)
{
    sd_error err;
    int mat;
    sd_world *w = world(&mat);
    make_l(flip);
    sd_insert_def d = sd_insert_def_default();
    d.region.kind = SD_REGION_MESH;
    d.region.vertices = verts;
    d.region.vertex_count = 12;
    d.region.triangles = (const uint32_t(*)[3])tris;
    d.region.triangle_count = 20;
    d.entry_count = 1;
    d.entries[0].shape = -1;
    d.entries[0].material = mat;
    d.entries[0].size.kind = SD_SIZE_UNIFORM;
    d.entries[0].size.a = 0.0008;
    d.entries[0].size.b = 0.0012;
    d.entries[0].fraction = 1;
    d.count = 600;
    CHECK(sd_world_add_insertion(w, &d, &err) == 0);
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    sd_insert_info info;
    sd_world_get_insertion(w, 0, &info);
    CHECK(info.inserted == 600 && info.asked == 600);
    check_inside(flip ? "L wound inward" : "L wound outward", w, 600, 0, 0, 0);
    sd_world_destroy(w);
}

static void scene_l(void)
{
    make_l(0);
    FILE *f = fopen("process_mesh_l.obj", "w");
    sd_test_require(f != NULL, "obj file", NULL);
    /* in millimetres: the scene scales by 1e-3 and moves it */
    for (int k = 0; k < 12; ++k)
        fprintf(f, "v %.17g %.17g %.17g\n", 1e3 * verts[k].x, 1e3 * verts[k].y, 1e3 * verts[k].z);
    for (int t = 0; t < 20; ++t)
        fprintf(f, "f %u %u %u\n", tris[t][0] + 1, tris[t][1] + 1, tris[t][2] + 1);
    fclose(f);
    f = fopen("process_mesh_l.yaml", "w");
    sd_test_require(f != NULL, "scene file", NULL);
    fprintf(f, "simulation: {dt: 1.0e-5, steps: 1}\nmaterials:\n  - {name: glass, density: 2500, youngs_modulus: 1.0e7}\n"
               "insert:\n  - region: mesh\n    file: process_mesh_l.obj\n    scale: 0.001\n"
               "    position: [0.1, 0.2, 0.3]\n    count: 300\n    mix:\n      - {material: glass, radius: 0.001}\n"
               "output: {formats: []}\n");
    fclose(f);
    sd_error err;
    sd_scene *sc;
    sd_world *w;
    sd_test_require(sd_scene_load("process_mesh_l.yaml", &sc, &err) == SD_OK, "load", &err);
    sd_test_require(sd_scene_build(sc, &w, &err) == SD_OK, "build", &err);
    sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
    check_inside("from a scene (OBJ in mm, scale 0.001, moved)", w, 300, 0.1, 0.2, 0.3);
    sd_world_destroy(w);
    sd_scene_free(sc);
    remove("process_mesh_l.obj");
    remove("process_mesh_l.yaml");
}

static void bad(void)
{
    sd_error err;
    int mat;
    sd_world *w = world(&mat);
    make_l(0);
    sd_insert_def d = sd_insert_def_default();
    d.region.kind = SD_REGION_MESH;
    d.region.vertices = verts;
    d.region.vertex_count = 12;
    d.region.triangles = (const uint32_t(*)[3])tris;
    d.region.triangle_count = 19; /* one missing: an open mesh */
    d.entry_count = 1;
    d.entries[0].shape = -1;
    d.entries[0].material = mat;
    d.entries[0].size = sd_size_def_fixed(0.001);
    d.entries[0].fraction = 1;
    d.count = 10;
    CHECK(sd_world_add_insertion(w, &d, &err) == -1);
    printf("     %s: %s\n", err.key, err.msg);
    CHECK(strcmp(err.key, "insert.region") == 0 && strstr(err.msg, "closed"));
    sd_region_outlet_def o = sd_region_outlet_def_default();
    o.region = d.region;
    o.region.triangle_count = 20;
    CHECK(sd_world_add_outlet(w, &o, &err) == -1);
    printf("     %s: %s\n", err.key, err.msg);
    sd_world_destroy(w);
}

int main(void)
{
    insert_l(0);
    insert_l(1);
    scene_l();
    bad();
    return sd_test_summary();
}
