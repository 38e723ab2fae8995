/* composite_lattice.c — the voxel lattice of §2.3 of [Rakotonirina 2019]
 * (eqs. 7-8, Fig. 3; docs/references.md) at up to 500 points per direction: relative errors of the
 * volume and principal moments of a sphere, a cylinder and two crossed
 * cylinders (Steinmetz intersection) against their closed forms, and the
 * time per run. tests/unit/composite.c checks 50, 100 and 200 points; this
 * is the long form. Build against a library build directory, e.g.
 *   cc -O2 -std=c17 -fopenmp -Isrc -Iinclude bench/composite_lattice.c \
 *      build-release/libshapedem.a -lyaml -lm -o build-release/composite_lattice
 *   build-release/composite_lattice 100 200 500
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "shape/composite.h"
#include "world/world.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* worst relative error of the volume and the three moments about x, y, z */
static double worst(const sd_mass *m, double V, const double I[3])
{
    double e = fabs((double)m->volume - V) / V;
    for (int a = 0; a < 3; ++a) {
        int b = (a + 1) % 3, c = (a + 2) % 3;
        double Ia = (double)(m->second.m[b][b] + m->second.m[c][c]);
        e = fmax(e, fabs(Ia - I[a]) / I[a]);
    }
    return e;
}

int main(int argc, char **argv)
{
    sd_world_def wd = sd_world_def_default();
    sd_world *w = NULL;
    sd_error err;
    if (sd_world_create(&wd, &w, &err) != SD_OK)
        return 1;
    const double R = 1e-3, L = 6e-3;
    sd_shape_desc d = sd_shape_desc_default();
    d.kind = "sphere";
    d.size = (sd_v3d){R, R, R};
    int sph = sd_world_add_shape(w, "s", &d, &err);
    d.kind = "cylinder";
    d.size = (sd_v3d){2 * R, 0, L};
    int cyl = sd_world_add_shape(w, "c", &d, &err);
    if (sph < 0 || cyl < 0)
        return 1;
    sd_composite_pools pools = {w->shapes, w->shape_count, w->verts, w->planes, w->dtris};
    sd_composite_part s1 = {sph, sd_v3(0, 0, 0), sd_quat_identity()};
    sd_composite_part c1 = {cyl, sd_v3(0, 0, 0), sd_quat_identity()};
    sd_composite_part two[2] = {{cyl, sd_v3(0, 0, 0), sd_quat_identity()},
                                {cyl, sd_v3(0, 0, 0), sd_quat_normalize(sd_quat_make(1, 1, 0, 0))}};
    const double Vs = 4.0 / 3 * SD_PI_D * R * R * R, Is = 0.4 * Vs * R * R;
    const double Vc = SD_PI_D * R * R * L, Jr = Vc * R * R / 4, Jl = Vc * L * L / 12;
    const double Vst = 16 * R * R * R / 3, Jsh = 16 * pow(R, 5) / 15, Jot = 64 * pow(R, 5) / 45;
    const double V2 = 2 * Vc - Vst, J2x = 2 * Jr - Jsh, J2y = Jr + Jl - Jot, J2z = J2y;
    const double Isph[3] = {Is, Is, Is}, Icyl[3] = {Jr + Jl, Jr + Jl, 2 * Jr}, I2[3] = {J2y + J2z, J2x + J2z, J2x + J2y};
    printf("points  sphere      cylinder    two-cyl     (worst rel. error of volume and moments; seconds)\n");
    for (int a = 1; a < argc; ++a) {
        int n = atoi(argv[a]);
        sd_mass m;
        double t0 = now();
        if (sd_composite_lattice(&pools, &s1, 1, n, 0, &m, NULL) != SD_OK)
            return 1;
        double es = worst(&m, Vs, Isph), t1 = now();
        if (sd_composite_lattice(&pools, &c1, 1, n, 0, &m, NULL) != SD_OK)
            return 1;
        double ec = worst(&m, Vc, Icyl), t2 = now();
        if (sd_composite_lattice(&pools, two, 2, n, 0, &m, NULL) != SD_OK)
            return 1;
        double e2 = worst(&m, V2, I2), t3 = now();
        printf("%6d  %.2e %4.1fs %.2e %4.1fs %.2e %4.1fs\n", n, es, t1 - t0, ec, t2 - t1, e2, t3 - t2);
    }
    sd_world_destroy(w);
    return 0;
}
