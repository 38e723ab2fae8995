/* lines.c — line reading for the CSV tables (see lines.h). */
#define _POSIX_C_SOURCE 200809L

#include "io/lines.h"

#include <string.h>
#include <sys/stat.h>

int sd_lines_is_directory(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

sd_lines_result sd_lines_next(FILE *f, char *buf, size_t cap, int *line)
{
    /* byte by byte (tables are small): fgets cannot tell a NUL byte in a
     * line from the line's end */
    size_t n = 0;
    int c = EOF;
    while (n + 1 < cap && (c = getc_unlocked(f)) != EOF) {
        buf[n++] = (char)c;
        if (c == '\n')
            break;
    }
    buf[n] = '\0';
    if (n == 0 && c == EOF)
        return ferror(f) ? SD_LINES_ERROR : SD_LINES_END;
    ++*line;
    if (*line == 1 && n >= 3 && memcmp(buf, "\xef\xbb\xbf", 3) == 0) {
        memmove(buf, buf + 3, n - 2); /* the byte-order mark, with the terminator */
        n -= 3;
    }
    if (memchr(buf, '\0', n))
        return SD_LINES_NUL;
    if (n + 1 >= cap && buf[n - 1] != '\n') {
        int next = getc(f);
        if (next != EOF) {
            ungetc(next, f);
            return SD_LINES_LONG;
        }
    }
    return ferror(f) ? SD_LINES_ERROR : SD_LINES_OK;
}
