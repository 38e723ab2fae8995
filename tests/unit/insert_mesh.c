/* insert_mesh.c — insertion among mesh walls (issue 31: an inserted
 * particle was checked against plane, box and drum walls only):
 *  - a closed box mesh as the container, the region across its xmin face
 *    (the probe's box scene, the box made of 12 facets): every particle
 *    inserted lies inside, clear of the face by its radius, where before
 *    about half of them started across the face or outside;
 *  - the region beside the container, outside it and touching no facet:
 *    nothing inserted (the winding number), where before all were;
 *  - an open mesh floor (2 facets) across the region: no particle within
 *    its radius of the floor;
 *  - a closed cube as an obstacle (`outside`) in the middle of the region:
 *    no particle inside it or across its faces.
 * On the code before (ade592f) checks 1, 2, 3 and 4 fail.
 */
#include "test.h"

#include <string.h>

#include <shapedem/process.h>

static const double R = 0.001; /* m, the spheres' radius */

static sd_world *sd_im_world(int *mat)
{
    sd_error err;
    sd_world *w;
    sd_world_def d = sd_world_def_default();
    d.threads = 1;
    d.dt = 1e-5;
    d.gravity = sd_test_v(0, 0, -9.81);
    d.max_overlap = 0; /* no guard: on the code before, the checks below say what went wrong */
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "a";
    m.youngs_modulus = 1e7;
    *mat = sd_world_add_material(w, &m, &err);
    sd_test_require(*mat >= 0, "material", &err);
    return w;
}

/* A closed box mesh [lo, hi], 12 facets (the side: inside or outside). */
static void sd_im_box(sd_world *w, int mat, sd_v3d lo, sd_v3d hi, int outside)
{
    sd_v3d v[8];
    for (int k = 0; k < 8; ++k)
        v[k] = sd_test_v(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
    static const uint32_t t[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                      {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    sd_mesh_def md = sd_mesh_def_default();
    md.vertices = v;
    md.vertex_count = 8;
    md.triangles = t;
    md.triangle_count = 12;
    md.material = mat;
    md.outside = outside;
    sd_error err;
    sd_test_require(sd_world_add_mesh(w, outside ? "cube" : "box", &md, &err) >= 0, "mesh", &err);
}

static size_t sd_im_insert(sd_world *w, int mat, sd_v3d lo, sd_v3d hi, size_t count)
{
    sd_insert_def d = sd_insert_def_default();
    d.region.kind = SD_REGION_BOX;
    d.region.lo = lo;
    d.region.hi = hi;
    d.entry_count = 1;
    d.entries[0].shape = -1;
    d.entries[0].material = mat;
    d.entries[0].size.kind = SD_SIZE_FIXED;
    d.entries[0].size.a = R;
    d.entries[0].fraction = 1;
    d.count = count;
    sd_error err;
    sd_test_require(sd_world_add_insertion(w, &d, &err) == 0, "insertion", &err);
    sd_test_require(sd_world_step(w, 0, &err) == SD_OK, "step", &err); /* the insertion at step 0 */
    sd_insert_info info;
    sd_world_get_insertion(w, 0, &info);
    printf("  inserted %zu of %zu%s%s\n", info.inserted, info.asked, info.why[0] ? ": " : "", info.why);
    return info.inserted;
}

/* The least clearance of the spheres from the box [lo, hi]'s faces: the
 * depth inside it less the radius (inside = 1), or the distance outside
 * it less the radius (inside = 0); < 0 when a sphere crosses or is on the
 * wrong side. */
static double sd_im_clearance(const sd_world *w, sd_v3d lo, sd_v3d hi, int inside)
{
    double worst = HUGE_VAL;
    for (size_t k = 0; k < sd_world_particle_count(w); ++k) {
        sd_particle_state s;
        sd_world_get_particle(w, k, &s);
        const double x[3] = {s.position.x, s.position.y, s.position.z}, l[3] = {lo.x, lo.y, lo.z},
                     h[3] = {hi.x, hi.y, hi.z};
        double depth = HUGE_VAL, out2 = 0;
        for (int a = 0; a < 3; ++a) {
            depth = fmin(depth, fmin(x[a] - l[a], h[a] - x[a]));
            double o = fmax(l[a] - x[a], fmax(x[a] - h[a], 0.0));
            out2 += o * o;
        }
        worst = fmin(worst, inside ? depth - s.radius : (depth > 0 ? -depth : sqrt(out2)) - s.radius);
    }
    return worst;
}

int main(void)
{
    int mat;
    const sd_v3d blo = sd_test_v(0, 0, 0), bhi = sd_test_v(0.02, 0.02, 0.05);

    printf("1. a closed box mesh, the region across its xmin face\n");
    sd_world *w = sd_im_world(&mat);
    sd_im_box(w, mat, blo, bhi, 0);
    size_t n = sd_im_insert(w, mat, sd_test_v(-0.01, 0.003, 0.02), sd_test_v(0.01, 0.017, 0.04), 60);
    CHECK(n > 10);
    CHECK_NEAR("least clearance inside the box mesh, clipped (m)", fmin(sd_im_clearance(w, blo, bhi, 1), 0.0), 0.0,
               0.0);
    sd_world_destroy(w);

    printf("2. the region beside the box mesh, touching no facet\n");
    w = sd_im_world(&mat);
    sd_im_box(w, mat, blo, bhi, 0);
    n = sd_im_insert(w, mat, sd_test_v(0.03, 0.003, 0.02), sd_test_v(0.05, 0.017, 0.04), 20);
    CHECK(n == 0 && sd_world_particle_count(w) == 0);
    sd_world_destroy(w);

    printf("3. an open mesh floor at z = 0.01 across the region\n");
    w = sd_im_world(&mat);
    {
        const sd_v3d v[4] = {{-0.01, -0.01, 0.01}, {0.03, -0.01, 0.01}, {0.03, 0.03, 0.01}, {-0.01, 0.03, 0.01}};
        static const uint32_t t[2][3] = {{0, 1, 2}, {0, 2, 3}};
        sd_mesh_def md = sd_mesh_def_default();
        md.vertices = v;
        md.vertex_count = 4;
        md.triangles = t;
        md.triangle_count = 2;
        md.material = mat;
        sd_error err;
        sd_test_require(sd_world_add_mesh(w, "floor", &md, &err) >= 0, "floor", &err);
    }
    n = sd_im_insert(w, mat, sd_test_v(0, 0, 0), sd_test_v(0.02, 0.02, 0.02), 60);
    double worst = HUGE_VAL;
    for (size_t k = 0; k < sd_world_particle_count(w); ++k) {
        sd_particle_state s;
        sd_world_get_particle(w, k, &s);
        worst = fmin(worst, fabs(s.position.z - 0.01) - s.radius);
    }
    CHECK(n > 10);
    CHECK_NEAR("least clearance from the floor, clipped (m)", fmin(worst, 0.0), 0.0, 0.0);
    sd_world_destroy(w);

    printf("4. a closed cube obstacle in the middle of the region\n");
    w = sd_im_world(&mat);
    const sd_v3d clo = sd_test_v(0.005, 0.005, 0.005), chi = sd_test_v(0.015, 0.015, 0.015);
    sd_im_box(w, mat, clo, chi, 1);
    n = sd_im_insert(w, mat, sd_test_v(0, 0, 0), sd_test_v(0.02, 0.02, 0.02), 150);
    CHECK(n > 10);
    CHECK_NEAR("least clearance outside the cube, clipped (m)", fmin(sd_im_clearance(w, clo, chi, 0), 0.0), 0.0, 0.0);
    sd_world_destroy(w);
    return sd_test_summary();
}
