/* drum_scene.c — the analytic drum from a scene file (walls: - type: drum;
 * tests/unit/scenes/drum-turn.yaml): a sphere started co-rotating on the
 * mantle of a drum turning at omega = 1 rad/s turns at the drum's speed,
 * omega (R - r), within 1 % at every check up to 0.15 s (before friction
 * gives way near 0.29 rad), then slips back: by 0.6 s it lags the drum by
 * more than 0.1 rad. The wall the scene made is the drum the keys say
 * (radius, half length, axis, caps), and drawn in the walls VTK file it is two rings of 48 points at radius R
 * and +-length/2, 48 mantle quads and the two closed caps.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"

#include <shapedem/scene.h>

#include "io/vtk.h"

static const double R = 0.1, r = 0.005, omega = 1.0;

static void scene_path(char *buf, size_t n, const char *rel)
{
    const char *root = getenv("SD_SOURCE_DIR");
    snprintf(buf, n, "%s/%s", root ? root : ".", rel);
}

/* Reads the raw little-endian appended block of a walls .vtp written by
 * sd_vtk_write_walls: the points are the array named position, at the
 * offset its DataArray tag gives. Returns the number of points read into
 * pts (x, y, z). */
static size_t read_wall_points(FILE *f, double **pts, size_t *polys)
{
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    rewind(f);
    unsigned char *b = malloc((size_t)size + 1);
    size_t got = fread(b, 1, (size_t)size, f);
    b[got] = 0;
    const char *np = strstr((const char *)b, "NumberOfPoints=\"");
    const char *app = strstr((const char *)b, "<AppendedData encoding=\"raw\">");
    const char *npo = strstr((const char *)b, "NumberOfPolys=\"");
    *polys = npo ? (size_t)strtoull(npo + 15, NULL, 10) : 0;
    size_t n = 0;
    *pts = NULL;
    if (np && app) {
        n = (size_t)strtoull(np + 16, NULL, 10);
        const unsigned char *p = (const unsigned char *)strchr(app, '_') + 1;
        const char *pos = strstr((const char *)b, "Name=\"position\"");
        const char *off = pos ? strstr(pos, "offset=\"") : NULL;
        p += off ? strtoull(off + 8, NULL, 10) : 0;
        uint64_t bytes = 0;
        memcpy(&bytes, p, 8);
        p += 8;
        if (bytes == 24 * n) {
            *pts = malloc(24 * n + 8);
            memcpy(*pts, p, 24 * n);
        } else {
            n = 0;
        }
    }
    free(b);
    return n;
}

int main(void)
{
    char path[1024];
    scene_path(path, sizeof path, "tests/unit/scenes/drum-turn.yaml");
    sd_error err;
    sd_scene *sc;
    sd_world *w;
    sd_test_require(sd_scene_load(path, &sc, &err) == SD_OK, "load", &err);
    sd_test_require(sd_scene_build(sc, &w, &err) == SD_OK, "build", &err);
    sd_wall_info wi;
    CHECK(sd_world_wall_count(w) == 1 && sd_world_get_wall(w, 0, &wi) == SD_OK);
    printf("     wall '%s': kind %d, radius %g m, half length %g m, axis [%g, %g, %g], open caps mask %u\n", wi.name,
           wi.kind, wi.lo.x, wi.lo.y, wi.normal.x, wi.normal.y, wi.normal.z, wi.open_faces);
    CHECK(wi.kind == 3 && fabs(wi.lo.x - R) < 1e-15 && fabs(wi.lo.y - 0.025) < 1e-15 && wi.normal.y == 1 &&
          wi.open_faces == 0);

    /* turning with the drum: the speed at every 0.01 s up to 0.15 s */
    double worst = 0, v_at = 0, t_at = 0;
    for (int k = 0; k < 15; ++k) {
        sd_test_require(sd_world_step(w, 1000, &err) == SD_OK, "step", &err);
        sd_particle_state p;
        sd_world_get_particle(w, 0, &p);
        double v = sqrt(p.velocity.x * p.velocity.x + p.velocity.z * p.velocity.z);
        double e = fabs(v - omega * (R - r)) / (omega * (R - r));
        if (e >= worst) {
            worst = e;
            v_at = v;
            t_at = sd_world_time(w);
        }
    }
    printf("     worst speed up to 0.15 s: %.6f m/s at %.2f s against omega (R - r) = %.6f m/s\n", v_at, t_at,
           omega * (R - r));
    CHECK_NEAR("speed / (omega (R - r)) - 1, while it turns with the drum", worst, 0, 0.01);
    /* then it slips: by 0.6 s the sphere lags the drum */
    sd_test_require(sd_world_step(w, 45000, &err) == SD_OK, "step", &err);
    sd_particle_state p;
    sd_world_get_particle(w, 0, &p);
    double th = atan2(-p.position.x, -p.position.z), t = sd_world_time(w);
    printf("     at %.2f s: the drum turned %.3f rad, the sphere is at %.3f rad\n", t, omega * t, th);
    CHECK(th < omega * t - 0.1);

    /* the walls VTK file: two rings of points on the mantle, at the caps;
     * cells: the mantle's quads and the two closed caps */
    FILE *f = tmpfile();
    sd_test_require(f != NULL, "tmpfile", NULL);
    CHECK(sd_vtk_write_walls(f, w, sd_vtk_plane_side(w), &err) == SD_OK);
    double *pts;
    size_t polys, n = read_wall_points(f, &pts, &polys);
    fclose(f);
    int ring_lo = 0, ring_hi = 0, off = 0;
    for (size_t k = 0; k < n; ++k) {
        double x = pts[3 * k], y = pts[3 * k + 1], z = pts[3 * k + 2], rho = sqrt(x * x + z * z);
        int on = fabs(rho - R) < 1e-12;
        ring_lo += on && fabs(y + 0.025) < 1e-12;
        ring_hi += on && fabs(y - 0.025) < 1e-12;
        off += !(on && fabs(fabs(y) - 0.025) < 1e-12);
    }
    printf("     walls VTK: %zu points, %d on the low ring, %d on the high ring, %d elsewhere; %zu cells\n", n,
           ring_lo, ring_hi, off, polys);
    CHECK(n == 96 && ring_lo == 48 && ring_hi == 48 && off == 0 && polys == 48 + 2);
    free(pts);
    sd_world_destroy(w);
    sd_scene_free(sc);
    return sd_test_summary();
}
