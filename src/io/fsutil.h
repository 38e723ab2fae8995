/* fsutil.h — the few file-system operations the output module needs:
 * mkdir -p, listing a directory, and atomic file replacement.
 *
 * Invariant: a file written through sd_fs_atomic_* appears under its final
 * name complete or not at all. It is written to ".<name>.tmp" in the same
 * directory (so rename() stays on one file system), flushed, fsync'ed and
 * renamed over the final name; on any failure the temporary is removed.
 *
 * POSIX only (mkdir, opendir, fsync, rename).
 */
#ifndef SD_IO_FSUTIL_H
#define SD_IO_FSUTIL_H

#include <shapedem/shapedem.h>
#include <stdio.h>

/* "dir/name" in memory from sd_malloc (free with sd_free), or NULL. */
char *sd_fs_join(const char *dir, const char *name);

/* Creates path and every missing parent (mode 0777 before umask). An
 * existing directory is fine; an existing non-directory is SD_ERR_IO. */
sd_status sd_fs_mkdir_p(const char *path, sd_error *err);

/* 1 if path names a regular file (symbolic links are not followed). */
int sd_fs_is_regular_file(const char *path);

/* NULL when path names a regular file or nothing; else what it is ("a
 * symbolic link", "a directory", "a FIFO", "a device node", "a socket",
 * "not a regular file"), for messages.
 * Symbolic links are not followed. */
const char *sd_fs_not_regular(const char *path);

/* 1 when a and b both exist and are the same file (device and inode, links
 * followed): an output that would replace one of its own inputs. */
int sd_fs_same_file(const char *a, const char *b);

/* Whether path may be replaced by an output that `option` names (a
 * command's -o): SD_OK when it names nothing or a regular file that is
 * none of the n inputs; else SD_ERR_INPUT naming it and what it is (a
 * link, a directory, a FIFO or device node: the run's own outputs refuse
 * the same entries, sd_fs_not_regular) or which input it is. */
sd_status sd_fs_check_output(const char *path, const char *option, const char *const *inputs, size_t n,
                             sd_error *err);

/* Creates path for appending; fails (SD_ERR_IO, with strerror) when
 * anything already has that name, a symbolic link included: O_CREAT |
 * O_EXCL never follows a link, so a link left under one of a run's names
 * cannot redirect the writes to a file outside the directory. */
sd_status sd_fs_create_append(const char *path, FILE **fp, sd_error *err);

/* The whole of file path in *buf (*size bytes; sd_free it); what names
 * the file in the messages ("checkpoint"). */
sd_status sd_fs_read_all(const char *path, const char *what, void **buf, size_t *size, sd_error *err);

/* A CSV series a restarted run continues (io/run.c): keeps the header and
 * the rows before the first whose `step` column is at least step, cuts the
 * rest and opens path for appending after them (*kept = 1); with nothing
 * there, or a file without a step column in its header, creates it anew
 * (*kept = 0: write the header). Never through a link, as above. */
sd_status sd_fs_resume_csv(const char *path, long step, FILE **fp, int *kept, sd_error *err);
/* The same for any series of records by step: keep(text, n, step, ctx)
 * gives the bytes of the file's text to keep, -1 when it is not a series
 * this run can continue (then it is created anew, *kept = 0). */
typedef long (*sd_fs_keep_fn)(const char *text, size_t n, long step, void *ctx);
sd_status sd_fs_resume_series(const char *path, long step, sd_fs_keep_fn keep, void *ctx, FILE **fp, int *kept,
                              sd_error *err);

/* Calls visit(name, ctx) for each entry of dir except "." and "..";
 * stops early when visit returns non-zero. */
sd_status sd_fs_list_dir(const char *dir, int (*visit)(const char *name, void *ctx), void *ctx,
                         sd_error *err);

typedef struct sd_atomic_file {
    FILE *fp;         /* write here between begin and commit/abort */
    char *tmp_path;   /* dir/.name.tmp */
    char *final_path; /* dir/name */
} sd_atomic_file;

/* Opens dir/.name.tmp for writing ("wb"). On failure af holds nothing. */
sd_status sd_fs_atomic_begin(sd_atomic_file *af, const char *dir, const char *name, sd_error *err);
/* Checks for write errors, flushes, fsyncs, closes and renames into place;
 * on failure removes the temporary. af is released either way. */
sd_status sd_fs_atomic_commit(sd_atomic_file *af, sd_error *err);
/* Closes and removes the temporary; af is released. Safe on a released af. */
void sd_fs_atomic_abort(sd_atomic_file *af);

#endif
