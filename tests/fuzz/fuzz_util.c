/* fuzz_util.c — the fuzz targets' temporary directory (see fuzz_util.h).
 * Linked into every target, under libFuzzer and under the replay driver. */
#define _POSIX_C_SOURCE 200809L
#define _DEFAULT_SOURCE /* mkdtemp */

#include "fuzz_util.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char sd_fuzz_tmp[512];

/* Removes the directory and the files the targets left in it (flat: the
 * targets write plain files only). */
static void sd_fuzz_cleanup(void)
{
    if (!sd_fuzz_tmp[0])
        return;
    DIR *d = opendir(sd_fuzz_tmp);
    if (d) {
        struct dirent *e;
        char p[1024];
        while ((e = readdir(d))) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
                continue;
            snprintf(p, sizeof p, "%s/%s", sd_fuzz_tmp, e->d_name);
            unlink(p);
        }
        closedir(d);
    }
    rmdir(sd_fuzz_tmp);
}

const char *sd_fuzz_dir(void)
{
    if (!sd_fuzz_tmp[0]) {
        const char *t = getenv("TMPDIR");
        snprintf(sd_fuzz_tmp, sizeof sd_fuzz_tmp, "%s/sd-fuzz-XXXXXX", t && t[0] ? t : "/tmp");
        if (!mkdtemp(sd_fuzz_tmp)) {
            perror("sd_fuzz_dir: mkdtemp");
            abort();
        }
        atexit(sd_fuzz_cleanup);
    }
    return sd_fuzz_tmp;
}

const char *sd_fuzz_write(const char *name, const uint8_t *data, size_t size, char *path, size_t path_size)
{
    snprintf(path, path_size, "%s/%s", sd_fuzz_dir(), name);
    FILE *f = fopen(path, "wb");
    if (!f || (size && fwrite(data, 1, size, f) != size) || fclose(f) != 0) {
        perror("sd_fuzz_write");
        abort();
    }
    return path;
}

void sd_fuzz_report(const char *stage, sd_status st, const sd_error *err)
{
    static int verbose = -1;
    if (verbose < 0)
        verbose = getenv("SD_FUZZ_VERBOSE") != NULL;
    if (!verbose)
        return;
    char msg[1024];
    if (st == SD_OK)
        snprintf(msg, sizeof msg, "ok");
    else
        sd_error_format(err, msg, sizeof msg);
    fprintf(stderr, "  %s: %s\n", stage, msg);
}
