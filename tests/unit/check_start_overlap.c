/* check_start_overlap.c — the true-shape overlap the scene builder checks
 * at the start (world/start_overlap.h), against closed forms:
 *  - two spheres: r_a + r_b - distance;
 *  - two rounded boxes face to face (core edge 2 mm swept by a rounding of
 *    0.1 mm: 2.2 mm outside) at centre distance d: 2.2 mm - d, whose
 *    bounding spheres overlap by far more;
 *  - the same boxes turned 45 degrees about z, their vertical edges
 *    crossing: the depth along a face normal (EPA on the cores);
 *  - a sphere against a box face: r + 1.1 mm - d;
 *  - a rounded cylinder's reach along its axis and across it;
 *  - sizes: a sphere's radius, half a shape's smallest outer dimension.
 */
#include <math.h>
#include <string.h>

#include "test.h"
#include "world/start_overlap.h"

int main(void)
{
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_world_def d = sd_world_def_default();
    d.dt = 1e-6;
    sd_world *w = NULL;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "create", &err);
    sd_material_def m = sd_material_def_default();
    m.density = 2500;
    m.youngs_modulus = 1e7;
    sd_test_require(sd_world_add_material(w, &m, &err) == 0, "material", &err);
    sd_shape_desc box = sd_shape_desc_default();
    box.kind = "box";
    box.size = sd_test_v(0.002, 0.002, 0.002);
    box.rounding = 1e-4;
    sd_test_require(sd_world_add_shape(w, "cube", &box, &err) == 0, "box", &err);
    sd_shape_desc cyl = sd_shape_desc_default();
    cyl.kind = "cylinder";
    cyl.size = sd_test_v(0.002, 0, 0.004); /* diameter 2 mm, length 4 mm */
    cyl.rounding = 1e-4;
    sd_test_require(sd_world_add_shape(w, "cyl", &cyl, &err) == 1, "cylinder", &err);

    double size;
    sd_start_particle s1 = {{0, 0, 0}, {1, 0, 0, 0}, 0.001, -1, 0};
    sd_start_particle s2 = {{0.0015, 0.0005, 0}, {1, 0, 0, 0}, 0.0008, -1, 0};
    CHECK_NEAR("spheres: r_a + r_b - distance (m)", sd_start_overlap(w, &s1, &s2, &size),
               0.0018 - sqrt(0.0015 * 0.0015 + 0.0005 * 0.0005), 1e-15);
    CHECK_NEAR("spheres: size is the smaller radius (m)", size, 0.0008, 0);

    const double tol = 1e-9; /* GJK on the cores, m */
    for (int k = 0; k < 3; ++k) {
        double dist = 0.0021 + 0.00005 * k; /* 0.1 mm into each other, 0.05 mm, touching */
        sd_start_particle a = {{0, 0, 0.01}, {1, 0, 0, 0}, 0, 0, 0}, b = {{dist, 0, 0.01}, {1, 0, 0, 0}, 0, 0, 0};
        char label[80];
        snprintf(label, sizeof label, "boxes face to face at %.5f m: 0.0022 - d", dist);
        CHECK_NEAR(label, sd_start_overlap(w, &a, &b, &size), 0.0022 - dist, tol);
    }
    CHECK_NEAR("boxes: size is half the outer edge (m)", size, 0.0011, 1e-15);
    {
        /* 2.5 mm apart: no overlap (gap 0.3 mm), though the bounding spheres
         * (1.83 mm each) overlap by 1.16 mm */
        sd_start_particle a = {{0, 0, 0.01}, {1, 0, 0, 0}, 0, 0, 0}, b = {{0.0025, 0, 0.01}, {1, 0, 0, 0}, 0, 0, 0};
        CHECK_NEAR("boxes 2.5 mm apart: the gap, -0.3 mm", sd_start_overlap(w, &a, &b, &size), -0.0003, tol);
    }
    {
        /* both turned 45 degrees about z: the cores' vertical edges cross
         * along x by 2 sqrt(2) mm - d; the shortest way apart is along a
         * face normal, 45 degrees off x: that over sqrt(2), plus the two
         * roundings (EPA on the cores, then the swept radii) */
        double c = cos(3.14159265358979323846 / 8), s = sin(3.14159265358979323846 / 8);
        sd_start_particle a = {{0, 0, 0.01}, {c, 0, 0, s}, 0, 0, 0}, b = {{0.0025, 0, 0.01}, {c, 0, 0, s}, 0, 0, 0};
        CHECK_NEAR("boxes turned 45 deg, 2.5 mm apart: depth", sd_start_overlap(w, &a, &b, &size),
                   (2 * sqrt(2.0) * 0.001 - 0.0025) / sqrt(2.0) + 0.0002, tol);
    }
    {
        sd_start_particle a = {{0, 0, 0.01}, {1, 0, 0, 0}, 0, 0, 0}, b = {{0, 0, 0.01 + 0.0018}, {1, 0, 0, 0}, 0.001, -1, 0};
        CHECK_NEAR("sphere on a box face: r + 1.1 mm - d", sd_start_overlap(w, &a, &b, &size), 0.0003, tol);
        CHECK_NEAR("sphere and box: size is the smaller (sphere 1 mm)", size, 0.001, 1e-15);
    }
    {
        sd_start_particle p = {{0.01, 0.02, 0.03}, {1, 0, 0, 0}, 0, 1, 0};
        sd_v3d up = {0, 0, 1}, side = {1, 0, 0};
        CHECK_NEAR("cylinder reach along its axis: z + 2.1 mm", sd_start_reach(w, &p, up), 0.0321, 1e-12);
        CHECK_NEAR("cylinder reach across: x + 1.1 mm", sd_start_reach(w, &p, side), 0.0111, 1e-12);
        CHECK_NEAR("cylinder size: half its outer diameter", sd_start_size(w, &p), 0.0011, 1e-15);
    }
    sd_world_destroy(w);
    return sd_test_summary();
}
