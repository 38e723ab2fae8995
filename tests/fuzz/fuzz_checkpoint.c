/* fuzz_checkpoint.c — libFuzzer target: the checkpoint reader
 * (sd_checkpoint_decode, io/checkpoint.c) on arbitrary bytes.
 *
 * checkpoint.h promises that any bytes are either refused with a reason or
 * give back the snapshot that was written. Besides the sanitizers, a
 * snapshot that decodes is checked: its items sorted by name with data for
 * every nonempty item, its checksum the one recomputed from the items
 * (the reader verified it; a mismatch means it did not), and it encodes
 * and decodes again to the same checksum and item count.
 */
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "fuzz_util.h"
#include "io/checkpoint.h"
#include "io/ckpt_particles.h"
#include "world/snapshot.h"

#define SD_FUZZ_CHECK(c)                                                                                         \
    do {                                                                                                         \
        if (!(c)) {                                                                                              \
            fprintf(stderr, "fuzz_checkpoint: invariant failed: %s\n", #c);                                      \
            __builtin_trap();                                                                                    \
        }                                                                                                        \
    } while (0)

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
