/* restore_forged.c — a checkpoint whose content was changed and whose
 * checksums were recomputed is refused by the restore, naming the
 * dataset, before any value is used (issue 31, probe 3 finding 6: these
 * reached memory errors, hangs, or ran with exit 0).
 *
 * tests/unit/scenes/restore-forged.yaml (a rotating mesh drum, a cube
 * among spheres, an insertion, an outlet) is run 100 steps
 * and snapshotted; each case changes one value of the snapshot in memory
 * (the restore never sees a checksum: this is the resealed file) and
 * restores into a world freshly built from the scene: SD_ERR_INPUT with
 * err.key the dataset expected. The snapshot unchanged restores and
 * steps. Random bytes in walls/geom, walls/motion and world/process
 * (seeded, 50 cases each) are refused or restore into a world whose
 * next 5 steps run or stop with an error, never a crash.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "test.h"

#include <shapedem/scene.h>

#include "core/rng.h"
#include "world/snapshot.h"

static const char *src_dir;
static sd_scene *scene;

static sd_world *fresh(void)
{
    sd_error err;
    sd_world *w = NULL;
    sd_test_require(sd_scene_build(scene, &w, &err) == SD_OK, "build", &err);
    return w;
}

static sd_snap_item *item(sd_snapshot *s, const char *name)
{
    sd_snap_item *it = (sd_snap_item *)sd_snapshot_find(s, name);
    sd_test_require(it != NULL, name, NULL);
    return it;
}

/* Restores s into a fresh world; the status, err filled. */
static sd_status restore(const sd_snapshot *s, sd_error *err, long steps)
{
    sd_world *w = fresh();
    memset(err, 0, sizeof *err);
    sd_status st = sd_world_restore(w, s, err);
    if (st == SD_OK && steps > 0) {
        sd_error e2;
        (void)sd_world_step(w, steps, &e2);
    }
    sd_world_destroy(w);
    return st;
}

/* Writes `bytes` bytes of v at byte `at` of the item's data, restores,
 * checks SD_ERR_INPUT naming `want`, puts the bytes back. */
static void forge(sd_snapshot *s, const char *name, size_t at, const void *v, size_t bytes, const char *want,
                  const char *what)
{
    sd_snap_item *it = item(s, name);
    unsigned char keep[64];
    memcpy(keep, (char *)it->data + at, bytes);
    memcpy((char *)it->data + at, v, bytes);
    sd_error err;
    sd_status st = restore(s, &err, 0);
    int ok = st == SD_ERR_INPUT && strcmp(err.key, want) == 0;
    printf("%-4s %-34s -> %s: %s\n", ok ? "ok" : "FAIL", what, err.key, st == SD_OK ? "(restored)" : err.msg);
    CHECK(ok);
    memcpy((char *)it->data + at, keep, bytes);
}

static void forge_f64(sd_snapshot *s, const char *name, size_t index, double v, const char *want, const char *what)
{
    forge(s, name, 8 * index, &v, 8, want, what);
}

static void forge_i32(sd_snapshot *s, const char *name, size_t index, int32_t v, const char *what)
{
    forge(s, name, 4 * index, &v, 4, name, what);
}

/* Random bytes over a whole record item (rows of bytes), n times. */
static void scramble(sd_snapshot *s, const char *name, int n, uint64_t seed)
{
    sd_snap_item *it = item(s, name);
    size_t bytes = it->count * it->comps;
    unsigned char *keep = malloc(bytes);
    sd_test_require(keep != NULL, "memory", NULL);
    memcpy(keep, it->data, bytes);
    sd_rng r = sd_rng_seed(seed);
    int refused = 0, restored = 0;
    for (int k = 0; k < n; ++k) {
        /* a few random bytes, or all of a row random */
        unsigned char *d = it->data;
        memcpy(d, keep, bytes);
        if (k % 2 == 0) {
            for (size_t j = 0; j < bytes; ++j)
                d[j] = (unsigned char)sd_rng_next(&r);
        } else {
            for (int j = 0; j < 4; ++j)
                d[sd_rng_next(&r) % bytes] = (unsigned char)sd_rng_next(&r);
        }
        sd_error err;
        sd_status st = restore(s, &err, 5);
        refused += st != SD_OK;
        restored += st == SD_OK;
    }
    memcpy(it->data, keep, bytes);
    free(keep);
    printf("ok   %-34s %d cases: %d refused, %d restored and stepped (no crash)\n", name, n, refused, restored);
    CHECK(refused + restored == n);
}

int main(void)
{
    src_dir = getenv("SD_SOURCE_DIR");
    sd_test_require(src_dir != NULL, "SD_SOURCE_DIR is set (ctest sets it)", NULL);
    char path[4096];
    snprintf(path, sizeof path, "%s/tests/unit/scenes/restore-forged.yaml", src_dir);
    sd_error err;
    sd_test_require(sd_scene_load(path, &scene, &err) == SD_OK, path, &err);
    sd_world *w = fresh();
    sd_test_require(sd_world_step(w, 100, &err) == SD_OK, "100 steps", &err);
    sd_snapshot s;
    sd_test_require(sd_world_snapshot(w, &s, &err) == SD_OK, "snapshot", &err);
    sd_world_destroy(w);

    CHECK(restore(&s, &err, 5) == SD_OK);

    const double nan = NAN, inf = INFINITY;
    forge_i32(&s, "particles/shape", 0, 999, "shape 999");
    forge_i32(&s, "particles/shape", 0, 100000000, "shape 1e8");
    forge_i32(&s, "particles/shape", 0, -2, "shape -2");
    forge_i32(&s, "particles/material", 0, 99, "material 99");
    forge_i32(&s, "particles/material", 0, -1, "material -1");
    forge_f64(&s, "particles/radius", 0, -1, "particles/radius", "radius -1");
    forge_f64(&s, "particles/radius", 0, 0, "particles/radius", "radius 0");
    forge_f64(&s, "particles/radius", 0, nan, "particles/radius", "radius NaN");
    forge_f64(&s, "particles/radius", 0, 1e300, "particles/radius", "radius 1e300");
    forge_f64(&s, "particles/inv_mass", 0, -1, "particles/inv_mass", "inv_mass -1");
    forge_f64(&s, "particles/v", 0, inf, "particles/v", "v = inf");
    forge_f64(&s, "particles/x", 2, 1e300, "particles/x", "z = 1e300");
    for (int c = 0; c < 4; ++c) /* a zeroed quaternion */
        forge_f64(&s, "particles/q", c, 0, "particles/q", c == 0 ? "q.w = 0" : "q component 0");
    uint64_t big_id = UINT64_MAX;
    forge(&s, "particles/id", 0, &big_id, 8, "particles/id", "id 2^64-1");
    forge_f64(&s, "world/gravity", 2, nan, "world/gravity", "gravity NaN");
    forge_f64(&s, "world/gravity", 2, 9.81, "world/gravity", "gravity +9.81");
    forge_f64(&s, "world/dt", 0, nan, "world/dt", "dt NaN");
    forge_f64(&s, "world/dt", 0, 0, "world/dt", "dt 0");
    forge_f64(&s, "world/dt", 0, 1e-3, "world/dt", "dt 1e-3");
    forge_f64(&s, "world/skin", 0, -1, "world/skin", "skin -1");
    forge_f64(&s, "world/time", 0, nan, "world/time", "time NaN");
    forge_f64(&s, "world/time", 0, -1, "world/time", "time -1");
    long step = -5;
    forge(&s, "world/step", 0, &step, 8, "world/step", "step -5");
    forge_f64(&s, "meshes/h", 0, 1e-300, "meshes/h", "meshes/h 1e-300");
    forge_f64(&s, "meshes/h", 0, -1, "meshes/h", "meshes/h -1");
    /* a wall's kind in its geometry record (the first int) */
    int32_t kind = 1;
    forge(&s, "walls/geom", 0, &kind, 4, "walls/geom", "mesh wall made a box");
    /* the process record: every byte 0xff (a name with no NUL, counters
     * of 2^64-1) */
    {
        sd_snap_item *it = item(&s, "world/process");
        size_t bytes = it->count * it->comps;
        unsigned char *keep = malloc(bytes);
        sd_test_require(keep != NULL, "memory", NULL);
        memcpy(keep, it->data, bytes);
        memset(it->data, 0xff, bytes);
        sd_status st = restore(&s, &err, 0);
        int ok = st == SD_ERR_INPUT && strcmp(err.key, "world/process") == 0;
        printf("%-4s %-34s -> %s: %s\n", ok ? "ok" : "FAIL", "world/process all 0xff", err.key, err.msg);
        CHECK(ok);
        memcpy(it->data, keep, bytes);
        free(keep);
    }
    scramble(&s, "walls/geom", 50, 1);
    scramble(&s, "walls/motion", 50, 2);
    scramble(&s, "world/process", 50, 3);

    CHECK(restore(&s, &err, 5) == SD_OK); /* every forgery undone */
    sd_snapshot_free(&s);
    sd_scene_free(scene);
    return sd_test_summary();
}
