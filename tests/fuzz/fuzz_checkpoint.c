/* fuzz_checkpoint.c — libFuzzer target: the checkpoint reader
 * (sd_checkpoint_decode, io/checkpoint.c) on arbitrary bytes.
 *
 * checkpoint.h promises that any bytes are either refused with a reason or
 * give back the snapshot that was written. Besides the sanitizers, a
 * snapshot that decodes is checked: its items sorted by name with data for
 * every nonempty item, its checksum the one recomputed from the items
 * (the reader verified it; a mismatch means it did not), and it encodes
 * and decodes again to the same checksum and item count.
 *
 * A checksum is not a validation of content (issue 31): anyone can
 * recompute it. So a snapshot of restore_scene.h's scene (its scene hash)
 * is also restored into a world freshly built from that scene and, when
 * accepted, stepped 5 steps: a forged value must be refused with a
 * message (world/restore_check.c) or be harmless, never a memory error or
 * a hang. Under libFuzzer a custom mutator makes such forgeries: it
 * decodes the input, mutates the bytes of one dataset (libFuzzer's own
 * mutations, the length kept), recomputes the checksum and encodes again,
 * so the mutants get past the reader's checks to the restore; an input
 * that does not decode gets libFuzzer's plain mutations.
 */
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "fuzz_util.h"
#include "io/checkpoint.h"
#include "io/ckpt_particles.h"
#include "restore_scene.h"
#include "world/snapshot.h"

#include <shapedem/scene.h>

#define SD_FUZZ_CHECK(c)                                                                                         \
    do {                                                                                                         \
        if (!(c)) {                                                                                              \
            fprintf(stderr, "fuzz_checkpoint: invariant failed: %s\n", #c);                                      \
            __builtin_trap();                                                                                    \
        }                                                                                                        \
    } while (0)

/* The restore scene, loaded once, and the hash of the world it builds. */
static sd_scene *sd_fuzz_scene;
static uint64_t sd_fuzz_scene_hash;

static int sd_fuzz_restore_ready(void)
{
    static int tried;
    if (!tried) {
        tried = 1;
        char path[1024];
        sd_error err;
        memset(&err, 0, sizeof err);
        sd_world *w = NULL;
        sd_fuzz_restore_write(path, sizeof path);
        if (sd_scene_load(path, &sd_fuzz_scene, &err) != SD_OK || sd_scene_build(sd_fuzz_scene, &w, &err) != SD_OK) {
            fprintf(stderr, "fuzz_checkpoint: the restore scene does not build: %s\n", err.msg);
            __builtin_trap(); /* a harness problem */
        }
        sd_fuzz_scene_hash = sd_world_scene_hash(w);
        sd_world_destroy(w);
    }
    return sd_fuzz_scene != NULL;
}

/* Restores s into the restore scene's fresh world when it is that scene's,
 * and steps the world 5 steps when the restore accepts it. */
static void sd_fuzz_restore(const sd_snapshot *s)
{
    if (!sd_fuzz_restore_ready() || s->scene_hash != sd_fuzz_scene_hash || s->version != SD_SNAPSHOT_VERSION)
        return;
    sd_world *w = NULL;
    sd_error err;
    memset(&err, 0, sizeof err);
    if (sd_scene_build(sd_fuzz_scene, &w, &err) != SD_OK)
        __builtin_trap(); /* it built once */
    sd_status st = sd_world_restore(w, s, &err);
    sd_fuzz_report("sd_world_restore", st, &err);
    if (st != SD_OK)
        SD_FUZZ_CHECK(err.msg[0]);
    else {
        memset(&err, 0, sizeof err);
        st = sd_world_step(w, 5, &err);
        sd_fuzz_report("sd_world_step (5 after the restore)", st, &err);
    }
    sd_world_destroy(w);
}

#ifdef SD_FUZZ_LIBFUZZER
size_t LLVMFuzzerMutate(uint8_t *data, size_t size, size_t max_size);

/* A decodable input: one dataset's bytes mutated, the checksum resealed. */
size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max_size, unsigned int seed);
size_t LLVMFuzzerCustomMutator(uint8_t *data, size_t size, size_t max_size, unsigned int seed)
{
    sd_snapshot s;
    sd_error err;
    memset(&err, 0, sizeof err);
    if (seed % 8 == 0 || sd_checkpoint_decode(data, size, &s, &err) != SD_OK) {
        if (seed % 8 != 0)
            sd_snapshot_free(&s);
        return LLVMFuzzerMutate(data, size, max_size);
    }
    size_t pick = s.n ? (seed / 8) % s.n : 0, tries = 0;
    while (tries < s.n && s.items[pick].count * s.items[pick].comps == 0) {
        pick = (pick + 1) % s.n;
        ++tries;
    }
    size_t out = size;
    if (tries < s.n) {
        sd_snap_item *it = &s.items[pick];
        size_t bytes = it->count * it->comps * sd_state_type_size(it->type);
        (void)LLVMFuzzerMutate(it->data, bytes, bytes);
        s.checksum = sd_snapshot_checksum(&s);
        void *buf = NULL;
        size_t n = 0;
        if (sd_checkpoint_encode(&s, &buf, &n, &err) == SD_OK && n <= max_size) {
            memcpy(data, buf, n);
            out = n;
        }
        sd_free(buf);
    }
    sd_snapshot_free(&s);
    return out;
}
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sd_snapshot s;
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_status st = sd_checkpoint_decode(data, size, &s, &err);
    sd_fuzz_report("sd_checkpoint_decode", st, &err);
    if (st != SD_OK) {
        SD_FUZZ_CHECK(err.msg[0]);
        sd_snapshot_free(&s);
        return 0;
    }
    for (size_t i = 0; i < s.n; ++i) {
        const sd_snap_item *it = &s.items[i];
        SD_FUZZ_CHECK(it->type < SD_ST_TYPE_COUNT);
        SD_FUZZ_CHECK(memchr(it->name, '\0', sizeof it->name) != NULL);
        SD_FUZZ_CHECK(it->count * it->comps == 0 || it->data != NULL);
        if (i > 0)
            SD_FUZZ_CHECK(strcmp(s.items[i - 1].name, it->name) < 0);
    }
    SD_FUZZ_CHECK(sd_snapshot_checksum(&s) == s.checksum);
    void *buf = NULL;
    size_t n = 0;
    memset(&err, 0, sizeof err);
    st = sd_checkpoint_encode(&s, &buf, &n, &err);
    sd_fuzz_report("sd_checkpoint_encode", st, &err);
    if (st == SD_OK) {
        sd_snapshot again;
        memset(&err, 0, sizeof err);
        st = sd_checkpoint_decode(buf, n, &again, &err);
        sd_fuzz_report("sd_checkpoint_decode (again)", st, &err);
        SD_FUZZ_CHECK(st == SD_OK && again.n == s.n && again.checksum == s.checksum);
        sd_snapshot_free(&again);
    }
    sd_free(buf);
    sd_fuzz_restore(&s); /* before the particle table takes the snapshot */
    /* the particle table of `info --csv` and `render CK.h5` (io/ckpt_particles.h):
     * on SD_OK every row's indices name a template and a material */
    sd_ckpt_particles p;
    memset(&err, 0, sizeof err);
    st = sd_ckpt_particles_take(&s, "fuzz.h5", &p, &err);
    sd_fuzz_report("sd_ckpt_particles_take", st, &err);
    SD_FUZZ_CHECK(s.n == 0 && s.items == NULL);
    if (st == SD_OK) {
        for (size_t k = 0; k < p.n; ++k)
            SD_FUZZ_CHECK(p.shape[k] >= -1 && p.shape[k] < (int32_t)p.shape_count && p.material[k] >= 0 &&
                          p.material[k] < (int32_t)p.material_count);
        FILE *sink = fopen("/dev/null", "w");
        if (sink) {
            sd_ckpt_particles_print_csv(sink, &p, &err);
            fclose(sink);
        }
    } else {
        SD_FUZZ_CHECK(err.msg[0]);
    }
    sd_ckpt_particles_free(&p);
    sd_snapshot_free(&s);
    return 0;
}
