/* lines.h — reading a text table line by line for the CSV readers (the
 * particle CSV of io/csv.c, a mesh's motion table in io/scene_mesh.c), so
 * that each refuses what is not text with the real reason: a directory
 * given as the file, a NUL byte in a line (binary data), a line longer
 * than the buffer. A UTF-8 byte-order mark at the start of the file is
 * skipped (spreadsheets write one).
 */
#ifndef SD_IO_LINES_H
#define SD_IO_LINES_H

#include <stddef.h>
#include <stdio.h>

typedef enum sd_lines_result {
    SD_LINES_OK,       /* a line in buf, NUL-terminated, with its '\n' when it had one */
    SD_LINES_END,      /* no more lines */
    SD_LINES_LONG,     /* the line does not fit in buf */
    SD_LINES_NUL,      /* the line holds a NUL byte */
    SD_LINES_ERROR     /* a read error (errno says which) */
} sd_lines_result;

/* 1 when path names a directory (fopen of a directory succeeds on Linux
 * and then reads nothing). */
int sd_lines_is_directory(const char *path);

/* Reads the next line of f into buf (cap bytes); line is the number of
 * the line read so far (0 before the first), incremented here. */
sd_lines_result sd_lines_next(FILE *f, char *buf, size_t cap, int *line);

#endif
