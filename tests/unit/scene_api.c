/* scene_api.c — the public scene API (include/shapedem/scene.h) on the
 * documented example scene (sd_scene_example): the info a runner reads,
 * the overrides, the default output directory, the output schedule
 * (sd_run_steps_to_output), and that a run advanced in small chunks ends
 * in the same state, bit for bit, as one advance and as sd_world_step.
 * The program uses only the public headers (and the example scene text
 * of io/scene_keys.c).
 */
#define _POSIX_C_SOURCE 200809L

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <shapedem/scene.h>

#include "test.h"

extern const char sd_scene_example[]; /* io/scene_keys.c: a complete, valid scene */

static uint64_t sd_state_hash(const sd_world *w)
{
    uint64_t h = 1469598103934665603ull;
    for (size_t k = 0; k < sd_world_particle_count(w); ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        double v[] = {p.position.x, p.position.y, p.position.z, p.velocity.x, p.velocity.y, p.velocity.z};
        const unsigned char *b = (const unsigned char *)v;
        for (size_t i = 0; i < sizeof v; ++i)
            h = (h ^ b[i]) * 1099511628211ull;
    }
    return h;
}

/* Loads path with `steps` steps, builds it and advances a run without
 * files in chunks of `chunk` (0: one advance of everything). */
static uint64_t sd_run_hash(const char *path, long steps, long chunk, long *calls)
{
    sd_scene *s;
    sd_world *w;
    sd_run *r;
    sd_error err;
    sd_test_require(sd_scene_load(path, &s, &err) == SD_OK, "load", &err);
    sd_scene_set_steps(s, steps);
    sd_test_require(sd_scene_build(s, &w, &err) == SD_OK, "build", &err);
    sd_test_require(sd_run_open(s, w, NULL, &r, &err) == SD_OK, "run open", &err);
    CHECK(!strcmp(sd_run_directory(r), ""));
    *calls = 0;
    sd_run_progress pr;
    do {
        CHECK(sd_run_advance(r, chunk ? chunk : steps, &err) == SD_OK);
        ++*calls;
        sd_run_get_progress(r, &pr);
    } while (pr.done < pr.steps && *calls < 10000);
    CHECK(pr.done == steps && pr.steps == steps);
    /* past the end: nothing more */
    CHECK(sd_run_advance(r, 5, &err) == SD_OK);
    sd_run_get_progress(r, &pr);
    CHECK(pr.done == steps);
    CHECK(sd_world_step_count(w) == steps);
    uint64_t h = sd_state_hash(w);
    CHECK(sd_run_close(r, &err) == SD_OK);
    sd_world_destroy(w);
    sd_scene_free(s);
    return h;
}

int main(void)
{
    char dir[256], path[300];
    snprintf(dir, sizeof dir, "%s/sd_scene_api_XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    sd_test_require(mkdtemp(dir) != NULL, "mkdtemp", NULL);
    snprintf(path, sizeof path, "%s/example.yaml", dir);
    FILE *f = fopen(path, "w");
    sd_test_require(f != NULL, path, NULL);
    fputs(sd_scene_example, f);
    fclose(f);

    sd_scene *s;
    sd_error err;
    sd_test_require(sd_scene_load(path, &s, &err) == SD_OK, "load the example scene", &err);
    sd_scene_info in;
    sd_scene_get_info(s, &in);
    printf("example scene: dimension %d, dt %g s, %ld steps, solver %d, law %s, %zu materials, %zu shapes, "
           "%zu walls, frames every %ld, stats every %ld\n",
           in.dimension, in.dt, in.steps, (int)in.solver, sd_contact_law_name(in.law), in.material_count,
           in.shape_count, in.wall_count, in.frame_every, in.stats_every);
    CHECK(!strcmp(in.path, path));
    CHECK(in.dimension == 3);
    CHECK(in.dt > 0 && in.steps > 0 && in.steps == sd_scene_steps(s));
    CHECK(in.frame_every >= 1 && in.stats_every >= 1);
    CHECK(in.material_count >= 1 && sd_scene_material_name(s, 0) != NULL);
    CHECK(sd_scene_material_name(s, in.material_count) == NULL);
    CHECK(sd_scene_shape_name(s, in.shape_count) == NULL && sd_scene_shape_warning(s, in.shape_count) == NULL);
    CHECK(!in.has_pour && !in.has_outlet);

    /* overrides; values out of range are ignored */
    sd_scene_set_steps(s, 7);
    sd_scene_set_threads(s, 3);
    sd_scene_set_steps(s, -1);
    sd_scene_set_threads(s, 0);
    sd_scene_get_info(s, &in);
    CHECK(in.steps == 7 && sd_scene_steps(s) == 7 && in.threads == 3);

    /* the default output directory: output.directory, else out/<stem> */
    char out[1100];
    sd_scene_output_directory(s, out, sizeof out);
    printf("default output directory: %s (output.directory '%s')\n", out, in.output_directory);
    if (in.output_directory[0])
        CHECK(!strcmp(out, in.output_directory));
    else
        CHECK(!strcmp(out, "out/example"));
    sd_scene_free(s);

    /* the output schedule: frames every 4, stats every 3, 10 steps */
    snprintf(path, sizeof path, "%s/sched.yaml", dir);
    f = fopen(path, "w");
    sd_test_require(f != NULL, path, NULL);
    fputs("simulation: {dt: 1.0e-5, steps: 10, gravity: [0, 0, -9.81]}\n"
          "materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]\n"
          "particles: [{generator: lattice, material: m, radius: 0.001, origin: [0, 0, 0.01], spacing: 0.003,"
          " count: [3, 3, 2]}]\n"
          "walls: [{type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}]\n"
          "output: {every: 4, stats_every: 3}\n",
          f);
    fclose(f);
    sd_world *w;
    sd_run *r;
    sd_test_require(sd_scene_load(path, &s, &err) == SD_OK, "load the schedule scene", &err);
    sd_scene_output_directory(s, out, sizeof out); /* no output.directory: out/<file stem> */
    printf("default output directory without output.directory: %s (expected out/sched)\n", out);
    CHECK(!strcmp(out, "out/sched"));
    sd_test_require(sd_scene_build(s, &w, &err) == SD_OK, "build", &err);
    sd_test_require(sd_run_open(s, w, NULL, &r, &err) == SD_OK, "run open", &err);
    /* from step 0: stats at 3, 6, 9, frames at 4, 8 and 10 (the end) */
    static const long want[] = {3, 4, 6, 8, 9, 10};
    long at = 0;
    int sched_ok = 1;
    for (size_t k = 0; k < sizeof want / sizeof want[0]; ++k) {
        long n = sd_run_steps_to_output(r);
        sched_ok &= at + n == want[k];
        printf("  next output at step %ld (expected %ld)\n", at + n, want[k]);
        CHECK(sd_run_advance(r, n, &err) == SD_OK);
        at += n;
    }
    CHECK(sched_ok);
    CHECK(sd_run_steps_to_output(r) == 0);
    CHECK(sd_run_close(r, &err) == SD_OK);
    sd_world_destroy(w);
    sd_scene_free(s);

    /* chunking does not change the state */
    long calls1, calls7;
    uint64_t h1 = sd_run_hash(path, 60, 0, &calls1), h7 = sd_run_hash(path, 60, 7, &calls7);
    printf("60 steps: one advance (%ld call) hash %016llx, chunks of 7 (%ld calls) hash %016llx\n", calls1,
           (unsigned long long)h1, calls7, (unsigned long long)h7);
    CHECK(calls1 == 1 && calls7 == 9);
    CHECK(h1 == h7);
    /* and is the state sd_world_step gives */
    sd_test_require(sd_scene_load(path, &s, &err) == SD_OK, "load", &err);
    sd_test_require(sd_scene_build(s, &w, &err) == SD_OK, "build", &err);
    CHECK(sd_world_step(w, 60, &err) == SD_OK);
    uint64_t hw = sd_state_hash(w);
    printf("sd_world_step(60) hash %016llx\n", (unsigned long long)hw);
    CHECK(hw == h1);
    sd_world_destroy(w);
    sd_scene_free(s);

    /* the pour of a grid scene, as the scene gives it and as the world got it */
    const char *src = getenv("SD_SOURCE_DIR");
    if (src) {
        char hop[1024];
        snprintf(hop, sizeof hop, "%s/examples/hopper-grid.yaml", src);
        sd_test_require(sd_scene_load(hop, &s, &err) == SD_OK, "load examples/hopper-grid.yaml", &err);
        sd_pour_def sp, wp;
        sd_outlet_def so;
        sd_scene_info hi;
        sd_scene_get_info(s, &hi);
        CHECK(hi.has_pour && hi.has_outlet && sd_scene_get_pour(s, &sp) == 1 && sd_scene_get_outlet(s, &so) == 1);
        sd_test_require(sd_scene_build(s, &w, &err) == SD_OK, "build the hopper", &err);
        CHECK(sd_world_get_pour(w, &wp) == 1);
        printf("hopper pour: %zu spheres of radius %g m at z = %g m (world: %zu, %g m, %g m); outlet x in [%g, %g]\n",
               sp.count, sp.radius, sp.height, wp.count, wp.radius, wp.height, so.x0, so.x1);
        CHECK(sp.count == wp.count && sp.radius == wp.radius && sp.height == wp.height &&
              sp.layers_per_second == wp.layers_per_second && sp.material == wp.material);
        CHECK(so.x1 > so.x0 && so.y1 > so.y0);
        sd_world_destroy(w);
        sd_scene_free(s);
    } else {
        printf("SD_SOURCE_DIR not set: the hopper's pour not checked\n");
    }
    /* a scene without them */
    sd_test_require(sd_scene_load(path, &s, &err) == SD_OK, "load", &err);
    sd_pour_def none;
    CHECK(sd_scene_get_pour(s, &none) == 0);
    sd_scene_free(s);

    unlink(path);
    snprintf(path, sizeof path, "%s/example.yaml", dir);
    unlink(path);
    rmdir(dir);
    return sd_test_summary();
}
