/* check_guard.c — the run's NaN guard and the frame writers' errors
 * (probe F8, F13):
 *  - a free body whose spin is NaN ends the step with SD_ERR_PHYSICS (the
 *    guard checked only x and v, and a free body's NaN spin reaches only
 *    its orientation, so such runs ended with exit 0 and NaN frames);
 *  - a NaN orientation does the same;
 *  - a speed of 1e160 m/s (finite, but its kinetic energy overflows in
 *    stats.csv) does too;
 *  - a finite state passes;
 *  - a frame written to a full device (/dev/full) fails with the system's
 *    reason, not a bare "write failed".
 */
#include <errno.h>
#include <string.h>

#include "io/vtk.h"
#include "test.h"

/* One free body of a cube shape (or a sphere), no gravity, nothing to hit. */
static sd_world *one_particle(int body, sd_v3d v, sd_v3d spin, const double q[4])
{
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_world_def d = sd_world_def_default();
    d.dt = 1e-6;
    d.gravity = sd_test_v(0, 0, 0);
    d.threads = 1;
    sd_world *w = NULL;
    sd_test_require(sd_world_create(&d, &w, &err) == SD_OK, "create", &err);
    sd_material_def m = sd_material_def_default();
    m.density = 2500;
    m.youngs_modulus = 1e7;
    sd_test_require(sd_world_add_material(w, &m, &err) == 0, "material", &err);
    if (body) {
        sd_shape_desc sd = sd_shape_desc_default();
        sd.kind = "box";
        sd.size = sd_test_v(0.002, 0.002, 0.002);
        sd_test_require(sd_world_add_shape(w, "cube", &sd, &err) == 0, "shape", &err);
        sd_body_def b;
        memset(&b, 0, sizeof b);
        b.position = sd_test_v(0, 0, 0.01);
        b.velocity = v;
        b.angular_velocity = spin;
        memcpy(b.orientation, q, sizeof b.orientation);
        b.shape = 0;
        sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    } else {
        sd_sphere_def s;
        memset(&s, 0, sizeof s);
        s.position = sd_test_v(0, 0, 0.01);
        s.velocity = v;
        s.angular_velocity = spin;
        s.radius = 0.001;
        sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    }
    return w;
}

static void expect_step(const char *what, sd_world *w, sd_status want)
{
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_status st = sd_world_step(w, 10, &err);
    char buf[512] = "";
    if (st != SD_OK)
        sd_error_format(&err, buf, sizeof buf);
    printf("%s: status %d (want %d) %s\n", what, (int)st, (int)want, buf);
    CHECK(st == want);
    if (want == SD_ERR_PHYSICS)
        CHECK(strstr(buf, "NaN or infinite") != NULL);
    sd_world_destroy(w);
}

int main(void)
{
    const double id[4] = {1, 0, 0, 0}, nanq[4] = {NAN, 0, 0, 0};
    const sd_v3d zero = sd_test_v(0, 0, 0);
    expect_step("finite body", one_particle(1, sd_test_v(0.1, 0, 0), sd_test_v(1, 2, 3), id), SD_OK);
    expect_step("body with NaN spin", one_particle(1, zero, sd_test_v(NAN, 0, 0), id), SD_ERR_PHYSICS);
    expect_step("body with inf spin", one_particle(1, zero, sd_test_v(0, INFINITY, 0), id), SD_ERR_PHYSICS);
    expect_step("body with NaN orientation", one_particle(1, zero, zero, nanq), SD_ERR_PHYSICS);
    expect_step("sphere with NaN spin", one_particle(0, zero, sd_test_v(0, 0, NAN), id), SD_ERR_PHYSICS);
    expect_step("sphere at 1e160 m/s", one_particle(0, sd_test_v(1e160, 0, 0), zero, id), SD_ERR_PHYSICS);

    /* a full disk: the writers keep errno's text (unbuffered, so the
     * writes themselves fail, as a large frame's do, not the final flush) */
    FILE *full = fopen("/dev/full", "w");
    if (full) {
        setvbuf(full, NULL, _IONBF, 0);
        sd_world *w = one_particle(0, zero, zero, id);
        sd_error err;
        memset(&err, 0, sizeof err);
        sd_status st = sd_vtk_write_particles(full, w, &err);
        char buf[512] = "";
        sd_error_format(&err, buf, sizeof buf);
        printf("frame to /dev/full: status %d, '%s' (want '%s')\n", (int)st, buf, strerror(ENOSPC));
        CHECK(st == SD_ERR_IO);
        CHECK(strstr(buf, strerror(ENOSPC)) != NULL);
        fclose(full);
        full = fopen("/dev/full", "w");
        if (full)
            setvbuf(full, NULL, _IONBF, 0);
        memset(&err, 0, sizeof err);
        st = full ? sd_vtk_write_walls(full, w, 1.0, &err) : SD_ERR_IO;
        sd_error_format(&err, buf, sizeof buf);
        printf("walls to /dev/full: status %d, '%s'\n", (int)st, buf);
        CHECK(st == SD_ERR_IO && strstr(buf, strerror(ENOSPC)) != NULL);
        if (full)
            fclose(full);
        sd_world_destroy(w);
    } else {
        printf("no /dev/full here: the write-error check is skipped\n");
    }
    return sd_test_summary();
}
