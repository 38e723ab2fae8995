/* replay.c — runs a fuzz target's entry (LLVMFuzzerTestOneInput) on every
 * file of the directories given, with the normal compiler and no libFuzzer:
 * the kept corpus and the regression inputs of past crashes run in the test
 * suite (fuzz.replay.NAME) on any machine.
 *
 *   fuzz_replay_NAME DIR...
 *
 * Files are run in name order (each directory sorted), so a failure is
 * reproducible; a missing directory is an error (a renamed corpus must not
 * pass silently with nothing run), and so is no file at all; names
 * starting with '.' are skipped (an empty regression directory keeps a
 * .keep file for git). A crash, a sanitizer report in a
 * sanitizer build, or a target's own invariant check ends the program
 * abnormally, and ctest reports the test failed; the file being run is
 * printed first. At the end: the number of files run per directory.
 */
#define _POSIX_C_SOURCE 200809L

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz_util.h"

static int sd_replay_cmp(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Reads the whole file into a malloc'd buffer of exactly its size (a
 * zero-length input gets a 1-byte buffer, so data is never NULL). */
static unsigned char *sd_replay_read(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 4096, n = 0;
    unsigned char *buf = malloc(cap);
    while (buf) {
        n += fread(buf + n, 1, cap - n, f);
        if (n < cap)
            break;
        unsigned char *q = realloc(buf, cap *= 2);
        if (!q) {
            free(buf);
            buf = NULL;
            break;
        }
        buf = q;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return NULL;
    }
    /* exactly size bytes, so a read past the input's end is caught */
    unsigned char *exact = buf ? malloc(n ? n : 1) : NULL;
    if (exact)
        memcpy(exact, buf, n);
    free(buf);
    *size = n;
    return exact;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s DIR...\n", argv[0]);
        return 2;
    }
    size_t total = 0;
    for (int a = 1; a < argc; ++a) {
        DIR *d = opendir(argv[a]);
        if (!d) {
            fprintf(stderr, "replay: cannot open the directory '%s'\n", argv[a]);
            return 1;
        }
        char **names = NULL;
        size_t count = 0, cap = 0;
        struct dirent *e;
        while ((e = readdir(d))) {
            if (e->d_name[0] == '.')
                continue;
            if (count == cap) {
                cap = cap ? 2 * cap : 64;
                char **q = realloc(names, cap * sizeof *q);
                if (!q) {
                    fprintf(stderr, "replay: out of memory\n");
                    return 1;
                }
                names = q;
            }
            if (!(names[count++] = strdup(e->d_name))) {
                fprintf(stderr, "replay: out of memory\n");
                return 1;
            }
        }
        closedir(d);
        if (count) /* qsort's array must not be NULL, even for 0 items */
            qsort(names, count, sizeof *names, sd_replay_cmp);
        size_t run = 0;
        for (size_t i = 0; i < count; ++i) {
            char path[4096];
            snprintf(path, sizeof path, "%s/%s", argv[a], names[i]);
            struct stat sb;
            if (stat(path, &sb) != 0 || !S_ISREG(sb.st_mode))
                continue;
            size_t size = 0;
            unsigned char *data = sd_replay_read(path, &size);
            if (!data) {
                fprintf(stderr, "replay: cannot read '%s'\n", path);
                return 1;
            }
            fprintf(stderr, "replay: %s (%zu bytes)\n", path, size);
            LLVMFuzzerTestOneInput(data, size);
            free(data);
            ++run;
        }
        for (size_t i = 0; i < count; ++i)
            free(names[i]);
        free(names);
        printf("replay: %zu inputs from %s: no crash\n", run, argv[a]);
        total += run;
    }
    if (total == 0) {
        fprintf(stderr, "replay: no input in any directory given\n");
        return 1;
    }
    return 0;
}
