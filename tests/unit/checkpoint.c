/* checkpoint.c — a damaged checkpoint is refused cleanly, never loaded as
 * if good and never a crash (issue 17).
 *
 * A checkpoint of a small periodic run (256 particles with contacts) is
 * made in memory; then
 *  - the file cut at every 4 KiB boundary must be refused;
 *  - the file with one byte flipped (every 11th byte of the first 4 KiB,
 *    where HDF5 keeps its superblock and root metadata, then every 307th:
 *    about 1,200 files, each a different bit of its byte)
 *    must be refused, or read back as exactly the snapshot written (a flip
 *    in bytes no reader uses, the header's zero padding);
 *  - a snapshot of another format version, and a restore into a world of
 *    another scene, are refused with a message saying why;
 *  - the intact file reads back bit for bit.
 */
#include <stdlib.h>
#include <string.h>

#include "test.h"

#include <shapedem/scene.h>

#include "core/alloc.h"
#include "io/checkpoint.h"
#include "world/snapshot.h"

static int same_snapshot(const sd_snapshot *a, const sd_snapshot *b)
{
    if (a->n != b->n || a->scene_hash != b->scene_hash || a->step != b->step || a->checksum != b->checksum ||
        memcmp(&a->time, &b->time, sizeof a->time) || a->version != b->version || a->dimension != b->dimension ||
        strcmp(a->solver, b->solver))
        return 0;
    for (size_t k = 0; k < a->n; ++k) {
        const sd_snap_item *x = &a->items[k], *y = &b->items[k];
        if (strcmp(x->name, y->name) || x->type != y->type || x->count != y->count || x->comps != y->comps ||
            memcmp(x->data, y->data, x->count * x->comps * sd_state_type_size(x->type)))
            return 0;
    }
    return 1;
}

static sd_world *build(const char *src, const char *scene, sd_scene **s)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", src, scene);
    sd_error err;
    sd_world *w;
    sd_test_require(sd_scene_load(path, s, &err) == SD_OK, scene, &err);
    sd_test_require(sd_scene_build(*s, &w, &err) == SD_OK, scene, &err);
    return w;
}

int main(void)
{
    const char *src = getenv("SD_SOURCE_DIR");
    sd_test_require(src != NULL, "SD_SOURCE_DIR is set (ctest sets it)", NULL);
    sd_scene *scene;
    sd_world *w = build(src, "examples/periodic-chute.yaml", &scene);
    sd_error err;
    sd_test_require(sd_world_step(w, 1000, &err) == SD_OK, "steps", &err);
    sd_snapshot s;
    sd_test_require(sd_world_snapshot(w, &s, &err) == SD_OK, "snapshot", &err);
    void *buf;
    size_t size;
    sd_test_require(sd_checkpoint_encode(&s, &buf, &size, &err) == SD_OK, "encode", &err);

    sd_snapshot r;
    CHECK(sd_checkpoint_decode(buf, size, &r, &err) == SD_OK);
    CHECK(same_snapshot(&s, &r));
    sd_snapshot_free(&r);

    /* truncated at every 4 KiB boundary (and at 0 and 1 byte short) */
    long cuts = 0, cut_refused = 0;
    for (size_t cut = 0; cut < size; cut += 4096) {
        ++cuts;
        if (sd_checkpoint_decode(buf, cut, &r, &err) != SD_OK)
            ++cut_refused;
        sd_snapshot_free(&r);
    }
    ++cuts;
    if (sd_checkpoint_decode(buf, size - 1, &r, &err) != SD_OK)
        ++cut_refused;
    sd_snapshot_free(&r);
    printf("truncated: %ld cuts of a %zu-byte checkpoint, %ld refused (expected all)\n", cuts, size, cut_refused);
    CHECK(cut_refused == cuts);

    /* one byte flipped */
    unsigned char *bad = malloc(size);
    sd_test_require(bad != NULL, "memory", NULL);
    long flips = 0, refused = 0, unchanged = 0, wrong = 0;
    char first_reason[512] = "";
    for (size_t pos = 0; pos < size; pos += pos < 4096 ? 11 : 307) {
        memcpy(bad, buf, size);
        bad[pos] ^= (unsigned char)(1u << (pos % 8));
        ++flips;
        sd_status st = sd_checkpoint_decode(bad, size, &r, &err);
        if (st != SD_OK) {
            ++refused;
            if (!first_reason[0] && pos >= 4096)
                snprintf(first_reason, sizeof first_reason, "%s", err.msg);
        } else if (same_snapshot(&s, &r))
            ++unchanged;
        else {
            ++wrong;
            if (wrong <= 3)
                printf("FAIL byte %zu flipped: loaded as good with other content\n", pos);
        }
        sd_snapshot_free(&r);
    }
    printf("flipped: %ld single-byte flips, %ld refused, %ld read back unchanged (bytes no reader uses: the header's padding), "
           "%ld loaded with other content (expected 0)\n", flips, refused, unchanged, wrong);
    printf("  e.g. a flip in the data: %s\n", first_reason);
    CHECK(wrong == 0);
    CHECK(refused > flips / 2); /* most bytes are data or checksummed metadata */
    free(bad);

    /* another format version */
    s.version = SD_SNAPSHOT_VERSION + 1;
    void *buf2;
    size_t size2;
    sd_test_require(sd_checkpoint_encode(&s, &buf2, &size2, &err) == SD_OK, "encode", &err);
    CHECK(sd_checkpoint_decode(buf2, size2, &r, &err) == SD_ERR_INPUT);
    printf("another version: %s\n", err.msg);
    CHECK(strstr(err.msg, "version") != NULL);
    sd_snapshot_free(&r);
    sd_free(buf2);
    s.version = SD_SNAPSHOT_VERSION;

    /* another scene: the periodic chute's state into the settling spheres */
    sd_scene *other;
    sd_world *w2 = build(src, "examples/settle-spheres.yaml", &other);
    CHECK(sd_world_restore(w2, &s, &err) == SD_ERR_INPUT);
    printf("another scene: %s\n", err.msg);
    CHECK(strstr(err.msg, "another scene") != NULL);
    sd_world_destroy(w2);
    sd_scene_free(other);

    /* not HDF5 at all, and nothing */
    CHECK(sd_checkpoint_decode("scene: not a checkpoint\n", 24, &r, &err) == SD_ERR_INPUT);
    CHECK(sd_checkpoint_decode(buf, 0, &r, &err) == SD_ERR_INPUT);

    sd_free(buf);
    sd_snapshot_free(&s);
    sd_world_destroy(w);
    sd_scene_free(scene);
    return sd_test_summary();
}
