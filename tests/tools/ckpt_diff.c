/* ckpt_diff.c — the command of tests/tools/ckpt_diff.h: compares two
 * checkpoints (io/checkpoint.h's reader, checksums verified) dataset by
 * dataset, bit for bit, printing per dataset the values that differ and
 * the largest difference relative to the field's scale.
 *
 *   sd_ckpt_diff [--tol REL] [--verbose] A.h5 B.h5
 *
 * Exit status: 0 the same bits (or every f64 field within REL of its scale
 * and everything else identical), 1 they differ, 2 a file could not be
 * read (the reason printed). bench/gpu/run calls it for every equality
 * case; the last line is the summary it puts in its table.
 */
#include "tools/ckpt_diff.h"

#include "io/checkpoint.h"

#include <stdlib.h>

static int sd_ckdiff_usage(void)
{
    fprintf(stderr, "usage: sd_ckpt_diff [--tol REL] [--verbose] A.h5 B.h5\n");
    return 2;
}

int main(int argc, char **argv)
{
    double tol = 0.0;
    int verbose = 0;
    const char *path[2] = {NULL, NULL};
    int np = 0;
    for (int k = 1; k < argc; k++) {
        if (!strcmp(argv[k], "--tol") && k + 1 < argc) {
            char *end;
            tol = strtod(argv[++k], &end);
            if (*end || !(tol >= 0.0)) {
                fprintf(stderr, "sd_ckpt_diff: --tol needs a relative tolerance >= 0, got '%s'\n", argv[k]);
                return 2;
            }
        } else if (!strcmp(argv[k], "--verbose") || !strcmp(argv[k], "-v")) {
            verbose = 1;
        } else if (argv[k][0] == '-' || np == 2) {
            return sd_ckdiff_usage();
        } else {
            path[np++] = argv[k];
        }
    }
    if (np != 2)
        return sd_ckdiff_usage();
    sd_snapshot s[2];
    sd_snapshot_init(&s[0]);
    sd_snapshot_init(&s[1]);
    for (int i = 0; i < 2; i++) {
        sd_error err;
        memset(&err, 0, sizeof err);
        if (sd_checkpoint_read_file(path[i], &s[i], &err) != SD_OK) {
            char buf[1024];
            sd_error_format(&err, buf, sizeof buf);
            fprintf(stderr, "sd_ckpt_diff: %s\n", buf);
            sd_snapshot_free(&s[0]);
            sd_snapshot_free(&s[1]);
            return 2;
        }
    }
    sd_ckdiff_result r;
    sd_ckdiff_compare(&s[0], &s[1], tol, verbose, stdout, &r);
    if (!r.differ && !r.header_differs)
        printf("ckpt_diff: identical: %zu datasets, step %ld, same bits\n", r.datasets, s[0].step);
    else
        printf("ckpt_diff: %s: %zu of %zu datasets differ%s, max relative difference %.3g (%s), tolerance %.3g\n",
               r.beyond || r.header_differs ? "DIFFERENT" : "within tolerance", r.differ, r.datasets,
               r.header_differs ? " and the headers" : "", r.max_rel, r.worst[0] ? r.worst : "-", tol);
    int status = r.beyond || r.header_differs ? 1 : 0;
    sd_snapshot_free(&s[0]);
    sd_snapshot_free(&s[1]);
    return status;
}
