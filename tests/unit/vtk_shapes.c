/* vtk_shapes.c — the shapes file of a frame (io/vtk_shapes.c) read back by
 * render's reader (render/read.c): every particle's cells enclose its
 * template's volume (divergence theorem on the written triangles, planar:
 * the shoelace area) within the tessellation error, and its points are the
 * template's surface posed at the particle's position and orientation.
 *
 * Flat faces are one cell each (a box 6, an icosahedron 20, a sharp
 * cylinder N + 2). Expected volumes: flat shapes (sharp boxes, polyhedra, a composite of two
 * apart boxes, planar polygons) exactly; a sharp cylinder or cone is a prism
 * or pyramid on the regular N-gon (N = the resolution), so its volume is
 * the template's times sin(2 pi / N) / (2 pi / N), and so is a circle's
 * area; curved shapes (spheres, ellipsoids, rounded boxes) are inscribed:
 * below the template, by at most (2 pi / N)^2 / 2 of it, and closer at a
 * finer resolution.
 */
#define _POSIX_C_SOURCE 200809L

#include "test.h"

#include "io/vtk.h"
#include "render/render.h"
#include "shape/surface.h"

#include <shapedem/scene.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846

static char tmpdir[256];

static const char *scene3d =
    "simulation: {dt: 1.0e-7, steps: 1, gravity: [0, 0, 0]}\n"
    "materials:\n"
    "  - {name: glass, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}\n"
    "shapes:\n"
    "  - {name: brick, type: box, size: [0.002, 0.0015, 0.001]}\n"
    "  - {name: rbrick, type: box, size: [0.002, 0.0015, 0.001], rounding: 0.0002}\n"
    "  - {name: rod, type: cylinder, diameter: 0.0015, length: 0.0025}\n"
    "  - {name: peak, type: cone, diameter: 0.002, height: 0.002}\n"
    "  - {name: pebble, type: ellipsoid, semi_axes: [0.0012, 0.0008, 0.0006]}\n"
    "  - {name: cube, type: polyhedron, preset: cube, size: 0.002}\n"
    "  - {name: d20, type: polyhedron, preset: icosahedron, size: 0.002}\n"
    "  - name: pair\n"
    "    type: composite\n"
    "    elements:\n"
    "      - {type: box, size: [0.001, 0.001, 0.001], position: [-0.001, 0, 0]}\n"
    "      - {type: box, size: [0.001, 0.0005, 0.0005], position: [0.001, 0, 0], orientation: [0.9238795, 0.3826834, 0, 0]}\n"
    "particles:\n"
    "  - generator: list\n"
    "    material: glass\n"
    "    spheres:\n"
    "      - {position: [0.00, 0, 0], radius: 0.001}\n"
    "      - {position: [0.01, 0, 0], shape: brick, orientation: random}\n"
    "      - {position: [0.02, 0, 0], shape: rbrick, orientation: random}\n"
    "      - {position: [0.03, 0, 0], shape: rod, orientation: random}\n"
    "      - {position: [0.04, 0, 0], shape: peak, orientation: random}\n"
    "      - {position: [0.05, 0, 0], shape: pebble, orientation: random}\n"
    "      - {position: [0.06, 0, 0], shape: cube, orientation: random}\n"
    "      - {position: [0.07, 0, 0], shape: d20, orientation: random}\n"
    "      - {position: [0.08, 0, 0], shape: pair, orientation: random}\n";

static const char *scene2d =
    "simulation: {dimension: 2, dt: 1.0e-6, steps: 1, gravity: [0, 0, 0], contact_law: linear}\n"
    "materials:\n"
    "  - {name: grain, density: 2700, stiffness: 1.0e7, restitution: 0.5, friction: 0.2}\n"
    "shapes:\n"
    "  - {name: disc, type: circle, radius: 0.01}\n"
    "  - {name: oval, type: ellipse, axes: [0.02, 0.01]}\n"
    "  - {name: tri, type: polygon, points: [[0, 0], [0.02, 0], [0.005, 0.015]]}\n"
    "particles:\n"
    "  - generator: list\n"
    "    material: grain\n"
    "    spheres:\n"
    "      - {position: [0.0, 0, 0], shape: disc}\n"
    "      - {position: [0.1, 0, 0], shape: oval, orientation: random}\n"
    "      - {position: [0.2, 0, 0], shape: tri, orientation: random}\n";

/* 0 exact, 1 regular N-gon prism/pyramid/polygon, 2 inscribed curved */
static int expect_kind(const char *kind, int planar)
{
    if (planar)
        return !strcmp(kind, "circle") ? 1 : !strcmp(kind, "polygon") ? 0 : 2;
    if (!strcmp(kind, "cylinder") || !strcmp(kind, "cone"))
        return 1;
    if (!strcmp(kind, "sphere") || !strcmp(kind, "ellipsoid"))
        return 2;
    return 0;
}

static sd_world *load(const char *name, const char *text)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    FILE *fp = fopen(path, "w");
    sd_test_require(fp != NULL, "write the scene", NULL);
    fputs(text, fp);
    fclose(fp);
    sd_scene *s;
    sd_world *w;
    sd_error err;
    sd_test_require(sd_scene_load(path, &s, &err) == SD_OK, "load the scene", &err);
    sd_test_require(sd_scene_build(s, &w, &err) == SD_OK, "build the scene", &err);
    sd_scene_free(s);
    return w;
}

/* Writes w's shapes file at resolution res and reads it back; returns the
 * largest relative volume error of the curved shapes (for convergence). */
static double check_world(sd_world *w, int res, int planar, int report)
{
    char path[512];
    snprintf(path, sizeof path, "%s/shapes_%06d.vtp", tmpdir, res);
    sd_error err;
    sd_vtk_shapes *t;
    sd_test_require(sd_vtk_shapes_make(w, res, &t, &err) == SD_OK, "shapes table", &err);
    FILE *fp = fopen(path, "wb");
    sd_test_require(fp != NULL, "open the shapes file", NULL);
    sd_test_require(sd_vtk_write_shapes(fp, w, t, &err) == SD_OK, "write the shapes file", &err);
    fclose(fp);
    sd_render_frame f;
    sd_test_require(sd_render_frame_load(path, "id", &f, &err) == SD_OK, "read the shapes file back", &err);
    CHECK(f.planar == planar);

    double worst_curved = 0.0;
    size_t cell = 0;
    size_t n = sd_world_particle_count(w);
    for (size_t i = 0; i < n; ++i) {
        sd_particle_state p;
        CHECK(sd_world_get_particle(w, i, &p) == SD_OK);
        const struct sd_surface *tmpl;
        CHECK(sd_vtk_shapes_surface(t, w, p.shape, &tmpl, &err) == SD_OK);
        /* this particle's cells: the next tmpl->cell_count, all with its id */
        size_t c0 = cell, c1 = cell + tmpl->cell_count;
        CHECK(c1 <= f.cell_count);
        if (c1 > f.cell_count)
            break;
        int ids_ok = 1;
        for (size_t c = c0; c < c1; ++c)
            ids_ok &= f.cell_value[c] == (double)p.id;
        CHECK(ids_ok);
        /* volume of the written cells, about the particle's centre */
        double vol = 0.0, pose_err = 0.0;
        int64_t s0 = c0 ? f.ends[c0 - 1] : 0;
        int64_t first = s0;
        for (size_t c = c0; c < c1; ++c) {
            int64_t s1 = f.ends[c];
            double a[3], b[3], d[3];
            const double *x0 = f.points + 3 * f.conn[s0];
            for (int k = 0; k < 3; ++k)
                a[k] = x0[k] - (&p.position.x)[k];
            for (int64_t j = s0 + (planar ? 0 : 1); j + (planar ? 0 : 1) < s1; ++j) {
                const double *xb = f.points + 3 * f.conn[j];
                const double *xc = f.points + 3 * f.conn[planar ? (j + 1 < s1 ? j + 1 : s0) : j + 1];
                for (int k = 0; k < 3; ++k) {
                    b[k] = xb[k] - (&p.position.x)[k];
                    d[k] = xc[k] - (&p.position.x)[k];
                }
                if (planar)
                    vol += 0.5 * (b[0] * d[1] - b[1] * d[0]);
                else
                    vol += (a[0] * (b[1] * d[2] - b[2] * d[1]) + a[1] * (b[2] * d[0] - b[0] * d[2]) +
                            a[2] * (b[0] * d[1] - b[1] * d[0])) /
                           6.0;
            }
            s0 = s1;
        }
        /* pose: written point k = x + R(q) (scale template point k) */
        double sc = p.shape < 0 ? p.radius : 1.0, qw = p.quat[0], qx = p.quat[1], qy = p.quat[2], qz = p.quat[3];
        double R[3][3] = {{1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qw * qz), 2 * (qx * qz + qw * qy)},
                          {2 * (qx * qy + qw * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qw * qx)},
                          {2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx * qx + qy * qy)}};
        int64_t pbase = f.conn[first] - tmpl->conn[0]; /* the particle's first point */
        for (size_t k = 0; k < tmpl->point_count; ++k) {
            const double *v = tmpl->points + 3 * k, *x = f.points + 3 * (size_t)(pbase + (int64_t)k);
            for (int r = 0; r < 3; ++r) {
                double e = (&p.position.x)[r] + sc * (R[r][0] * v[0] + R[r][1] * v[1] + R[r][2] * v[2]);
                pose_err = fmax(pose_err, fabs(e - x[r]));
            }
        }
        cell = c1;

        sd_shape_info info;
        double expected;
        const char *kind = "sphere", *name = "sphere";
        if (p.shape >= 0) {
            CHECK(sd_world_get_shape(w, (size_t)p.shape, &info) == SD_OK);
            expected = info.volume;
            kind = info.kind;
            name = info.name;
        } else {
            expected = planar ? PI * p.radius * p.radius : 4.0 / 3.0 * PI * p.radius * p.radius * p.radius;
        }
        int ek = expect_kind(kind, planar);
        if (p.shape >= 0 && !strcmp(kind, "box") && info.rounding > 0.0)
            ek = 2;
        double h = 2.0 * PI / res, ngon = sin(h) / h;
        char label[96];
        snprintf(label, sizeof label, "%s (%s) N=%d %s", name, kind, res, planar ? "area" : "volume");
        if (ek == 0) {
            if (report)
                CHECK_REL(label, vol, expected, 1e-9);
        } else if (ek == 1) {
            if (report)
                CHECK_REL(label, vol, expected * ngon, 1e-9);
        } else {
            double rel = 1.0 - vol / expected, bound = 0.5 * h * h;
            worst_curved = fmax(worst_curved, rel);
            if (report) {
                printf("%-4s %-44s computed %-14.8g template %-14.8g deficit %.4g (0 < deficit <= %.4g)\n",
                       rel > 0.0 && rel <= bound ? "ok" : "FAIL", label, vol, expected, rel, bound);
                CHECK(rel > 0.0 && rel <= bound);
            }
        }
        /* flat faces are one polygon each: a box 6, an icosahedron 20, a
         * sharp cylinder N sides and 2 caps, a cone N sides and its base */
        long want = !strcmp(name, "brick") || !strcmp(name, "cube") ? 6
                  : !strcmp(name, "d20")                           ? 20
                  : !strcmp(name, "rod")                           ? res + 2
                  : !strcmp(name, "peak")                          ? res + 1
                  : !strcmp(name, "pair")                          ? 12
                                                                   : -1;
        if (report && want >= 0) {
            snprintf(label, sizeof label, "%s cells (one per flat face)", name);
            CHECK_NEAR(label, (double)(c1 - c0), (double)want, 0.0);
        }
        if (report) {
            snprintf(label, sizeof label, "%s pose: max |x - (x_c + R s)| (m)", name);
            CHECK_NEAR(label, pose_err, 0.0, 1e-15 + 1e-12 * sqrt(p.position.x * p.position.x + p.radius * p.radius));
        }
    }
    CHECK(cell == f.cell_count);
    sd_render_frame_free(&f);
    sd_vtk_shapes_free(t);
    remove(path);
    return worst_curved;
}

int main(void)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sd_vtk_shapes_XXXXXX");
    sd_test_require(mkdtemp(tmpdir) != NULL, "make a temporary directory", NULL);

    sd_world *w = load("shapes3d.yaml", scene3d);
    double e24 = check_world(w, 24, 0, 1);
    double e48 = check_world(w, 48, 0, 0);
    printf("curved shapes: largest volume deficit %.4g at N=24, %.4g at N=48 (ratio %.2f, about 4 for 1/N^2)\n", e24,
           e48, e24 / e48);
    CHECK(e48 < e24 / 3.0);
    /* the resolution range is enforced */
    sd_vtk_shapes *t;
    sd_error err;
    CHECK(sd_vtk_shapes_make(w, SD_SURFACE_RES_MIN - 1, &t, &err) == SD_ERR_INPUT);
    CHECK(sd_vtk_shapes_make(w, SD_SURFACE_RES_MAX + 1, &t, &err) == SD_ERR_INPUT);
    sd_world_destroy(w);

    w = load("shapes2d.yaml", scene2d);
    check_world(w, 24, 1, 1);
    sd_world_destroy(w);

    char path[512];
    snprintf(path, sizeof path, "%s/shapes3d.yaml", tmpdir);
    remove(path);
    snprintf(path, sizeof path, "%s/shapes2d.yaml", tmpdir);
    remove(path);
    rmdir(tmpdir);
    return sd_test_summary();
}
