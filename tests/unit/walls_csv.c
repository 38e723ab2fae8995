/* walls_csv.c — walls.csv (io/output.c, docs/output.md): a run of a
 * turning mesh drum with a charge of spheres and a plane under it writes
 * walls.csv with step, time and six named columns per wall (drum_fx ..
 * drum_tz, floor_fx .. floor_tz), one row per stats row; its last row is
 * what sd_world_get_wall reports at the end (force, and the torque about
 * the drum's torque_point), to the ten digits it prints (a non-zero
 * vertical force and torque: the charge presses on the drum and rides up
 * its wall); stats.csv keeps
 * the same wall columns with the same numbers.
 */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <shapedem/scene.h>
#include <stdlib.h>
#include <string.h>

/* Reads a CSV file: its header into hdr, its rows into rows (at most
 * maxr rows of at most maxc numbers); returns the row count, -1 when the
 * file is missing. *ncol gets the header's column count. */
static int sd_read_csv(const char *path, char *hdr, size_t hn, double *rows, int maxr, int maxc, int *ncol)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    static char line[1 << 16];
    if (!fgets(line, sizeof line, f)) {
        fclose(f);
        return 0;
    }
    line[strcspn(line, "\r\n")] = 0;
    size_t len = strlen(line) < hn - 1 ? strlen(line) : hn - 1;
    memcpy(hdr, line, len);
    hdr[len] = 0;
    *ncol = 1;
    for (char *c = line; *c; ++c)
        *ncol += *c == ',';
    int n = 0;
    while (n < maxr && fgets(line, sizeof line, f)) {
        char *at = line;
        for (int k = 0; k < maxc && *at && *at != '\n'; ++k) {
            rows[n * maxc + k] = strtod(at, &at);
            if (*at == ',')
                ++at;
        }
        ++n;
    }
    fclose(f);
    return n;
}

int main(void)
{
    const char *src = getenv("SD_SOURCE_DIR");
    sd_test_require(src != NULL, "SD_SOURCE_DIR (set by ctest)", NULL);
    char dir[256], path[700], out[400];
    snprintf(dir, sizeof dir, "%s/sd_walls_csv_XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    sd_test_require(mkdtemp(dir) != NULL, "mkdtemp", NULL);
    snprintf(path, sizeof path, "%s/drum.yaml", dir);
    snprintf(out, sizeof out, "%s/out", dir);
    FILE *f = fopen(path, "w");
    sd_test_require(f != NULL, path, NULL);
    /* 60 spheres in the drum of examples/meshes (radius 60 mm, axis y),
     * turning at 30 rpm from the start; a plane below the drum touches
     * nothing but has its columns */
    fprintf(f,
            "simulation: {dt: 1.0e-5, steps: 30000, gravity: [0, 0, -9.81], seed: 3}\n"
            "materials: [{name: glass, density: 2500, youngs_modulus: 5.0e6, restitution: 0.5, friction: 0.5}]\n"
            "particles: [{generator: random, material: glass, radius: 0.003, number: 60,"
            " box: {min: [-0.03, -0.015, -0.05], max: [0.03, 0.015, -0.02]}}]\n"
            "walls:\n"
            "  - {type: mesh, name: drum, file: %s/examples/meshes/drum.obj, material: glass,"
            " torque_point: [0, 0, 0],\n"
            "     motion: {type: rotate, axis_point: [0, 0, 0], axis: [0, 1, 0], rpm: 30}}\n"
            "  - {type: plane, name: floor, point: [0, 0, -0.2], normal: [0, 0, 1], material: glass}\n"
            "output: {every: 30000, stats_every: 5000}\n",
            src);
    fclose(f);

    sd_scene *s;
    sd_world *w;
    sd_run *r;
    sd_error err;
    sd_test_require(sd_scene_load(path, &s, &err) == SD_OK, "load", &err);
    sd_test_require(sd_scene_build(s, &w, &err) == SD_OK, "build", &err);
    sd_test_require(sd_run_open(s, w, out, &r, &err) == SD_OK, "run open", &err);
    CHECK(sd_run_advance(r, sd_scene_steps(s), &err) == SD_OK);
    sd_wall_info wi[2];
    for (size_t k = 0; k < 2; ++k)
        CHECK(sd_world_get_wall(w, k, &wi[k]) == SD_OK);
    CHECK(sd_run_close(r, &err) == SD_OK);

    enum { MAXR = 16, MAXC = 64 };
    static double rows[MAXR * MAXC], srows[MAXR * MAXC];
    char hdr[4096], shdr[4096];
    int nc = 0, snc = 0;
    snprintf(path, sizeof path, "%s/walls.csv", out);
    int n = sd_read_csv(path, hdr, sizeof hdr, rows, MAXR, MAXC, &nc);
    printf("walls.csv: %d rows, %d columns\nheader: %s\n", n, nc, hdr);
    CHECK(n == 7); /* steps 0, 5000, ..., 30000 */
    CHECK(!strcmp(hdr, "step,time,drum_fx,drum_fy,drum_fz,drum_tx,drum_ty,drum_tz,"
                       "floor_fx,floor_fy,floor_fz,floor_tx,floor_ty,floor_tz"));
    CHECK(nc == 14);
    if (n >= 1) {
        const double *last = rows + (n - 1) * MAXC;
        CHECK_NEAR("last row: step", last[0], 30000.0, 0.0);
        double api[12] = {wi[0].force.x,  wi[0].force.y,  wi[0].force.z,  wi[0].torque.x,
                          wi[0].torque.y, wi[0].torque.z, wi[1].force.x,  wi[1].force.y,
                          wi[1].force.z,  wi[1].torque.x, wi[1].torque.y, wi[1].torque.z};
        const char *names[12] = {"drum_fx",  "drum_fy",  "drum_fz",  "drum_tx",  "drum_ty",  "drum_tz",
                                 "floor_fx", "floor_fy", "floor_fz", "floor_tx", "floor_ty", "floor_tz"};
        for (int k = 0; k < 12; ++k) {
            char label[64];
            snprintf(label, sizeof label, "%s vs sd_world_get_wall", names[k]);
            CHECK_NEAR(label, last[2 + k], api[k], 1e-9 * fabs(api[k]) + 1e-300);
        }
        /* the charge presses on the drum and rides up its turning wall */
        CHECK(last[4] < 0.0);
        CHECK(wi[0].torque.y != 0.0); /* the charge rides up the turning wall */
    }
    /* stats.csv keeps the wall columns: the same numbers */
    snprintf(path, sizeof path, "%s/stats.csv", out);
    int sn = sd_read_csv(path, shdr, sizeof shdr, srows, MAXR, MAXC, &snc);
    CHECK(sn == n);
    const char *at = strstr(shdr, ",drum_fx");
    CHECK(at != NULL);
    if (at && sn == n && n > 0) {
        int col = 1;
        for (const char *c = shdr; c < at; ++c)
            col += *c == ',';
        double maxd = 0;
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < 12; ++k)
                maxd = fmax(maxd, fabs(srows[i * MAXC + col + k] - rows[i * MAXC + 2 + k]));
        CHECK_NEAR("stats.csv wall columns - walls.csv, max", maxd, 0.0, 0.0);
    }
    sd_world_destroy(w);
    sd_scene_free(s);
    return sd_test_summary();
}
