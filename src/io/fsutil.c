/* fsutil.c — mkdir -p, directory listing and atomic file replacement
 * (see fsutil.h for the invariant). Errors become sd_status values with the
 * path in err->file and strerror(errno) in err->msg.
 */
#define _POSIX_C_SOURCE 200809L

#include "io/fsutil.h"

#include "core/alloc.h"
#include "core/error.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

char *sd_fs_join(const char *dir, const char *name)
{
    size_t nd = strlen(dir), nn = strlen(name);
    int slash = nd > 0 && dir[nd - 1] != '/';
    char *p = sd_malloc(nd + (size_t)slash + nn + 1);
    if (!p)
        return NULL;
    memcpy(p, dir, nd);
    if (slash)
        p[nd] = '/';
    memcpy(p + nd + (size_t)slash, name, nn + 1);
    return p;
}

/* mkdir that treats an existing directory as success. */
static int sd_fs_mkdir_one(const char *path)
{
    if (mkdir(path, 0777) == 0)
        return 0;
    int e = errno;
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        return 0;
    errno = (e == EEXIST) ? ENOTDIR : e;
    return -1;
}

sd_status sd_fs_mkdir_p(const char *path, sd_error *err)
{
    if (!path || !path[0])
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "output.directory",
                            "the output directory name is empty");
    size_t n = strlen(path);
    char *buf = sd_malloc(n + 1);
    if (!buf)
        return sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    memcpy(buf, path, n + 1);
    /* Create each prefix ending before a '/', then the whole path. */
    for (size_t i = 1; i <= n; ++i) {
        if (i < n && buf[i] != '/')
            continue;
        if (i < n && buf[i - 1] == '/')
            continue; /* "a//b": the prefix was made already */
        char saved = buf[i];
        buf[i] = '\0';
        int rc = sd_fs_mkdir_one(buf);
        int e = errno;
        buf[i] = saved;
        if (rc != 0) {
            buf[i] = '\0';
            sd_status s = sd_error_set(err, SD_ERR_IO, buf, 0, "output.directory",
                                       "cannot create directory: %s", strerror(e));
            sd_free(buf);
            return s;
        }
    }
    sd_free(buf);
    return SD_OK;
}

int sd_fs_is_regular_file(const char *path)
{
    struct stat st;
    return lstat(path, &st) == 0 && S_ISREG(st.st_mode);
}

const char *sd_fs_not_regular(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0 || S_ISREG(st.st_mode))
        return NULL;
    if (S_ISLNK(st.st_mode))
        return "a symbolic link";
    if (S_ISDIR(st.st_mode))
        return "a directory";
    if (S_ISFIFO(st.st_mode))
        return "a FIFO";
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode))
        return "a device node";
    if (S_ISSOCK(st.st_mode))
        return "a socket";
    return "not a regular file";
}

int sd_fs_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return a && b && stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

sd_status sd_fs_check_output(const char *path, const char *option, const char *const *inputs, size_t n,
                             sd_error *err)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return SD_OK; /* nothing there: a new file */
    const char *what = sd_fs_not_regular(path);
    if (what)
        return sd_error_set(err, SD_ERR_INPUT, path, 0, option,
                            "it is %s, not a regular file: shapedem writes a new file or over a regular one, never "
                            "over a link, a directory, a FIFO or a device; choose another name",
                            what);
    for (size_t k = 0; k < n; ++k)
        if (inputs[k] && sd_fs_same_file(path, inputs[k]))
            return sd_error_set(err, SD_ERR_INPUT, path, 0, option,
                                "it is the input %s (the same file): writing there would destroy what is "
                                "read; choose another name",
                                inputs[k]);
    return SD_OK;
}

/* Opens path for writing without following a symbolic link in its last
 * component (O_NOFOLLOW: ELOOP) and without blocking on a FIFO (O_NONBLOCK:
 * ENXIO without a reader), and insists on a regular file, so nothing but a
 * plain file in the output directory is ever written. */
static FILE *sd_fs_open_plain(const char *path, int flags, const char *mode)
{
    int fd = open(path, flags | O_WRONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0666);
    if (fd < 0)
        return NULL;
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        errno = EINVAL;
        return NULL;
    }
    int fl = fcntl(fd, F_GETFL);
    if (fl != -1)
        (void)fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
    FILE *fp = fdopen(fd, mode);
    if (!fp) {
        int e = errno;
        close(fd);
        errno = e;
    }
    return fp;
}

sd_status sd_fs_create_append(const char *path, FILE **fp, sd_error *err)
{
    *fp = sd_fs_open_plain(path, O_CREAT | O_EXCL | O_APPEND, "a");
    if (*fp)
        return SD_OK;
    int e = errno;
    const char *what = e == EEXIST ? sd_fs_not_regular(path) : NULL;
    if (what)
        return sd_error_set(err, SD_ERR_IO, path, 0, "",
                            "cannot create the file: %s is in the way (shapedem does not write through it; "
                            "remove it or choose another directory)",
                            what);
    return sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot create the file: %s", strerror(e));
}

sd_status sd_fs_read_all(const char *path, const char *what, void **buf, size_t *size, sd_error *err)
{
    *buf = NULL;
    *size = 0;
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot open the %s: %s", what, strerror(errno));
    void *b = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n == cap) {
            size_t nc = cap ? 2 * cap : 1 << 16;
            void *q = sd_realloc(b, nc);
            if (!q) {
                sd_free(b);
                fclose(fp);
                return sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory reading the %s", what);
            }
            b = q;
            cap = nc;
        }
        size_t got = fread((char *)b + n, 1, cap - n, fp);
        n += got;
        if (got == 0)
            break;
    }
    int bad = ferror(fp);
    fclose(fp);
    if (bad) {
        sd_free(b);
        return sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot read the %s", what);
    }
    *buf = b;
    *size = n;
    return SD_OK;
}

/* The length of the rows of a CSV file (text f of n bytes) to keep: the
 * header and every row before the first whose `step` column is at least
 * step (or is not a number). -1 when there is no header with a step
 * column. */
static long sd_fs_csv_keep(const char *f, size_t n, long step, void *ctx)
{
    (void)ctx;
    const char *eol = memchr(f, '\n', n);
    if (!eol)
        return -1;
    int col = -1, c = 0;
    for (const char *a = f; a < eol; ++c) {
        const char *b = a;
        while (b < eol && *b != ',')
            ++b;
        if (b - a == 4 && memcmp(a, "step", 4) == 0)
            col = c;
        a = b < eol ? b + 1 : eol;
    }
    if (col < 0)
        return -1;
    size_t at = (size_t)(eol - f) + 1;
    while (at < n) {
        const char *row = f + at, *end = memchr(row, '\n', n - at);
        if (!end)
            break; /* a row cut short by a crash: dropped */
        const char *a = row;
        for (int k = 0; k < col && a < end; ++k) {
            const char *b = memchr(a, ',', (size_t)(end - a));
            a = b ? b + 1 : end;
        }
        char num[32];
        size_t len = 0;
        while (a + len < end && a[len] != ',' && len + 1 < sizeof num)
            ++len;
        memcpy(num, a, len);
        num[len] = '\0';
        char *stop;
        long v = strtol(num, &stop, 10);
        if (len == 0 || *stop != '\0' || v >= step)
            break;
        at = (size_t)(end - f) + 1;
    }
    return (long)at;
}

sd_status sd_fs_resume_csv(const char *path, long step, FILE **fp, int *kept, sd_error *err)
{
    return sd_fs_resume_series(path, step, sd_fs_csv_keep, NULL, fp, kept, err);
}

sd_status sd_fs_resume_series(const char *path, long step, sd_fs_keep_fn keep_fn, void *ctx, FILE **fp, int *kept,
                              sd_error *err)
{
    *fp = NULL;
    *kept = 0;
    if (!sd_fs_is_regular_file(path))
        return sd_fs_create_append(path, fp, err); /* nothing there (or in the way: its message) */
    void *text = NULL;
    size_t n = 0;
    sd_status st = sd_fs_read_all(path, "file", &text, &n, err);
    if (st != SD_OK)
        return st;
    long keep = keep_fn(text, n, step, ctx);
    sd_free(text);
    if (keep < 0) { /* not a series this run can continue: a new one */
        if (remove(path) != 0)
            return sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot remove the file: %s", strerror(errno));
        return sd_fs_create_append(path, fp, err);
    }
    *fp = sd_fs_open_plain(path, O_APPEND, "a");
    if (!*fp || ftruncate(fileno(*fp), (off_t)keep) != 0) {
        int e = errno;
        if (*fp)
            fclose(*fp);
        *fp = NULL;
        return sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot continue the file: %s", strerror(e));
    }
    *kept = 1;
    return SD_OK;
}

sd_status sd_fs_list_dir(const char *dir, int (*visit)(const char *name, void *ctx), void *ctx,
                         sd_error *err)
{
    DIR *d = opendir(dir);
    if (!d)
        return sd_error_set(err, SD_ERR_IO, dir, 0, "", "cannot list directory: %s",
                            strerror(errno));
    struct dirent *e;
    errno = 0;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        if (visit(e->d_name, ctx))
            break;
        errno = 0;
    }
    int failed = (e == NULL && errno != 0);
    int saved = errno;
    closedir(d);
    if (failed)
        return sd_error_set(err, SD_ERR_IO, dir, 0, "", "cannot list directory: %s",
                            strerror(saved));
    return SD_OK;
}

static void sd_atomic_release(sd_atomic_file *af)
{
    sd_free(af->tmp_path);
    sd_free(af->final_path);
    af->fp = NULL;
    af->tmp_path = NULL;
    af->final_path = NULL;
}

sd_status sd_fs_atomic_begin(sd_atomic_file *af, const char *dir, const char *name, sd_error *err)
{
    af->fp = NULL;
    af->final_path = sd_fs_join(dir, name);
    size_t nn = strlen(name);
    char *tmp_name = sd_malloc(nn + 6);
    if (tmp_name) {
        tmp_name[0] = '.';
        memcpy(tmp_name + 1, name, nn);
        memcpy(tmp_name + 1 + nn, ".tmp", 5);
    }
    af->tmp_path = tmp_name ? sd_fs_join(dir, tmp_name) : NULL;
    sd_free(tmp_name);
    if (!af->final_path || !af->tmp_path) {
        sd_atomic_release(af);
        return sd_error_set(err, SD_ERR_MEMORY, dir, 0, "", "out of memory");
    }
    /* A temporary left by an interrupted run is a plain file and is
     * truncated; a link under its name is refused (ELOOP), never followed. */
    af->fp = sd_fs_open_plain(af->tmp_path, O_CREAT | O_TRUNC, "wb");
    if (!af->fp) {
        int e = errno;
        const char *what = sd_fs_not_regular(af->tmp_path);
        sd_status s = what ? sd_error_set(err, SD_ERR_IO, af->tmp_path, 0, "",
                                          "cannot create file: %s is in the way (shapedem does not write "
                                          "through it; remove it or choose another directory)",
                                          what)
                           : sd_error_set(err, SD_ERR_IO, af->tmp_path, 0, "", "cannot create file: %s",
                                          strerror(e));
        sd_atomic_release(af);
        return s;
    }
    return SD_OK;
}

/* Makes the rename itself durable; best effort (some file systems refuse). */
static void sd_fs_sync_parent(const char *path)
{
    const char *slash = strrchr(path, '/');
    char *dir = NULL;
    if (slash) {
        size_t n = slash == path ? 1 : (size_t)(slash - path);
        dir = sd_malloc(n + 1);
        if (!dir)
            return;
        memcpy(dir, path, n);
        dir[n] = '\0';
    }
    int fd = open(dir ? dir : ".", O_RDONLY);
    if (fd >= 0) {
        (void)fsync(fd);
        close(fd);
    }
    sd_free(dir);
}

sd_status sd_fs_atomic_commit(sd_atomic_file *af, sd_error *err)
{
    if (!af->fp)
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "atomic file committed twice");
    int e = 0;
    if (ferror(af->fp))
        e = errno ? errno : EIO;
    if (!e && fflush(af->fp) != 0)
        e = errno;
    if (!e && fsync(fileno(af->fp)) != 0)
        e = errno;
    if (fclose(af->fp) != 0 && !e)
        e = errno;
    af->fp = NULL;
    if (e) {
        sd_status s = sd_error_set(err, SD_ERR_IO, af->final_path, 0, "", "cannot write file: %s",
                                   strerror(e));
        remove(af->tmp_path);
        sd_atomic_release(af);
        return s;
    }
    if (rename(af->tmp_path, af->final_path) != 0) {
        sd_status s = sd_error_set(err, SD_ERR_IO, af->final_path, 0, "",
                                   "cannot rename the finished file into place: %s",
                                   strerror(errno));
        remove(af->tmp_path);
        sd_atomic_release(af);
        return s;
    }
    sd_fs_sync_parent(af->final_path);
    sd_atomic_release(af);
    return SD_OK;
}

void sd_fs_atomic_abort(sd_atomic_file *af)
{
    if (af->fp) {
        fclose(af->fp);
        af->fp = NULL;
    }
    if (af->tmp_path)
        remove(af->tmp_path);
    sd_atomic_release(af);
}
