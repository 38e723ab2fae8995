/* csv.c — the CSV particle file of a csv generator (see csv.h).
 *
 * A header names the columns (any order, each at most once); then one
 * particle per row: a sphere (radius) or a body of a shape (shape, with an
 * orientation from qw..qz or the generator's). Empty cells of optional
 * columns take the generator's value, so a packing of spheres and shapes
 * fits one file. Lines starting with # and blank lines are skipped.
 *
 * Invariant: on SD_OK, g->list_count rows were appended to the
 * generator's entry arrays, each with its CSV line; on error the arrays
 * hold the rows read so far (all arrays the same length, freed with the
 * scene) and err names the CSV file, its line and the generator's key.
 */
#define _POSIX_C_SOURCE 200809L

#include "io/csv.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/lines.h"

static char *sd_csv_trim(char *t)
{
    while (*t == ' ' || *t == '\t')
        ++t;
    size_t n = strlen(t);
    while (n > 0 && (t[n - 1] == ' ' || t[n - 1] == '\t' || t[n - 1] == '\r' || t[n - 1] == '\n'))
        t[--n] = '\0';
    return t;
}

enum {
    SD_CSV_X, SD_CSV_Y, SD_CSV_Z, SD_CSV_R, SD_CSV_VX, SD_CSV_VY, SD_CSV_VZ, SD_CSV_SHAPE,
    SD_CSV_QW, SD_CSV_QX, SD_CSV_QY, SD_CSV_QZ, SD_CSV_WX, SD_CSV_WY, SD_CSV_WZ, SD_CSV_MATERIAL,
    SD_CSV_NCOL
};
static const char *const sd_csv_names[SD_CSV_NCOL] = {
    "x", "y", "z", "radius", "vx", "vy", "vz", "shape", "qw", "qx", "qy", "qz", "wx", "wy", "wz", "material"};

const char *sd_csv_known(const sd_scene *s, int materials, char *buf, size_t size)
{
    size_t used = 0, n = materials ? s->material_count : s->shape_count;
    buf[0] = '\0';
    for (size_t i = 0; i < n && used + 1 < size; ++i) {
        if (!materials && s->shapes[i].hidden)
            continue;
        int w = snprintf(buf + used, size - used, "%s%s", used ? ", " : "",
                         materials ? s->materials[i].name : s->shapes[i].name);
        used += w > 0 ? (size_t)w : 0;
    }
    return used ? buf : "none";
}

int sd_csv_grow(sd_scene_generator *g, size_t cap)
{
    void *q;
    if (!(q = sd_realloc(g->list, cap * sizeof *g->list)))
        return 0;
    g->list = q;
    if (!(q = sd_realloc(g->list_lines, cap * sizeof *g->list_lines)))
        return 0;
    g->list_lines = q;
    if (!(q = sd_realloc(g->list_shape, cap * sizeof *g->list_shape)))
        return 0;
    g->list_shape = q;
    if (!(q = sd_realloc(g->list_orient, cap * sizeof *g->list_orient)))
        return 0;
    g->list_orient = q;
    if (!(q = sd_realloc(g->list_quat, cap * sizeof *g->list_quat)))
        return 0;
    g->list_quat = q;
    return 1;
}

/* Reads g->file: a header naming the columns, then one particle per row: a
 * sphere (radius) or a body of a shape (shape, with an orientation from
 * qw..qz or the generator's). Empty cells of optional columns take the
 * generator's value, so a packing of spheres and shapes fits one file.
 * Errors name the CSV file and its line; the key names the generator. */
sd_status sd_csv_read(const sd_scene *s, sd_scene_generator *g, const char *key, int file_line, sd_error *err)
{
    if (sd_lines_is_directory(g->file))
        return sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key, "the CSV file '%s' is a directory, not a file",
                            g->file);
    FILE *f = fopen(g->file, "rb");
    if (!f)
        return sd_error_set(err, SD_ERR_INPUT, s->path, file_line, key, "cannot open the CSV file '%s': %s", g->file,
                            strerror(errno));
    char buf[4096], known[300], esc[64]; /* esc: file bytes, escaped */
    int col_of[SD_CSV_NCOL]; /* column -> SD_CSV_* index */
    int ncols = 0, line = 0, have_header = 0;
    size_t cap = 0;
    sd_status st = SD_OK;
    for (;;) {
        sd_lines_result lr = sd_lines_next(f, buf, sizeof buf, &line);
        if (lr == SD_LINES_END)
            break;
        if (lr != SD_LINES_OK) {
            st = lr == SD_LINES_LONG  ? sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                                     "line longer than %zu characters", sizeof buf - 2)
                 : lr == SD_LINES_NUL ? sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                                     "a NUL byte in the line (not a text CSV file)")
                                      : sd_error_set(err, SD_ERR_INPUT, g->file, line, key, "cannot read: %s",
                                                     strerror(errno));
            break;
        }
        char *t = sd_csv_trim(buf);
        if (!t[0] || t[0] == '#')
            continue;
        if (!have_header) {
            int seen[SD_CSV_NCOL] = {0};
            for (char *c = t; c; ++ncols) {
                char *next = strchr(c, ',');
                if (next)
                    *next++ = '\0';
                char *name = sd_csv_trim(c);
                int idx = -1;
                for (int j = 0; j < SD_CSV_NCOL; ++j)
                    if (!strcmp(name, sd_csv_names[j]))
                        idx = j;
                /* SD_CSV_NCOL distinct names: a longer header repeats one */
                if (idx < 0 || ncols >= SD_CSV_NCOL || seen[idx]) {
                    sd_escape(esc, sizeof esc, name, (size_t)-1);
                    st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                      "%s column '%s' in the header (expected the columns x, y, z, "
                                      "radius and/or shape, and optionally vx, vy, vz, qw, qx, qy, "
                                      "qz, wx, wy, wz, material)",
                                      idx < 0 ? "unknown" : "repeated", esc);
                    goto done;
                }
                seen[idx] = 1;
                col_of[ncols] = idx;
                c = next;
            }
            for (int j = 0; j <= SD_CSV_R; ++j)
                if (!seen[j] && !(j == SD_CSV_R && (seen[SD_CSV_SHAPE] || g->shape >= 0))) {
                    st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                      "the header line has no '%s' column (expected a header such "
                                      "as x,y,z,radius or x,y,z,shape)",
                                      sd_csv_names[j]);
                    goto done;
                }
            int nq = seen[SD_CSV_QW] + seen[SD_CSV_QX] + seen[SD_CSV_QY] + seen[SD_CSV_QZ];
            if (nq != 0 && nq != 4) {
                st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                  "the header names %d of the orientation columns qw, qx, qy, qz "
                                  "(expected all four or none)",
                                  nq);
                goto done;
            }
            have_header = 1;
            continue;
        }
        char *cell[SD_CSV_NCOL] = {0};
        int col = 0;
        for (char *c = t; c; ++col) {
            char *next = strchr(c, ',');
            if (next)
                *next++ = '\0';
            if (col >= ncols) {
                st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                  "expected %d values as in the header, got more", ncols);
                goto done;
            }
            cell[col_of[col]] = sd_csv_trim(c);
            c = next;
        }
        if (col != ncols) {
            st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                              "expected %d values as in the header, got %d", ncols, col);
            goto done;
        }
        double val[SD_CSV_NCOL] = {0};
        int has[SD_CSV_NCOL] = {0};
        for (int j = 0; j < SD_CSV_NCOL; ++j) {
            if (!cell[j] || j == SD_CSV_SHAPE || j == SD_CSV_MATERIAL)
                continue;
            if (!cell[j][0] && j > SD_CSV_Z)
                continue; /* an empty optional cell: the generator's value */
            char *end;
            double x = strtod(cell[j], &end);
            if (!cell[j][0] || *end || !isfinite(x)) {
                sd_escape(esc, sizeof esc, cell[j], 40);
                st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                  "column %s: expected a number, got '%s'", sd_csv_names[j], esc);
                goto done;
            }
            val[j] = x;
            has[j] = 1;
        }
        if (has[SD_CSV_R] && !(val[SD_CSV_R] > 0.0)) {
            st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                              "column radius: expected a number > 0, got %s", cell[SD_CSV_R]);
            goto done;
        }
        /* A sphere (radius) or a body of a shape (the row's, or the generator's). */
        int shape = -1;
        const char *sname = cell[SD_CSV_SHAPE] ? cell[SD_CSV_SHAPE] : "";
        if (sname[0]) {
            if (has[SD_CSV_R]) {
                st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                  "give either radius (a sphere) or shape on a row, not both");
                goto done;
            }
            for (size_t i = 0; i < s->shape_count && shape < 0; ++i)
                if (!strcmp(s->shapes[i].name, sname))
                    shape = (int)i;
            if (shape < 0) {
                sd_escape(esc, sizeof esc, sname, 40);
                st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                  "column shape: unknown shape '%s' (shapes: %s)", esc,
                                  sd_csv_known(s, 0, known, sizeof known));
                goto done;
            }
        } else if (!has[SD_CSV_R]) {
            if (g->shape < 0) {
                st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                  "expected a radius (a sphere) or a shape name, got neither");
                goto done;
            }
            shape = g->shape;
        }
        sd_scene_orient orient = g->orient;
        double q[4] = {g->quat[0], g->quat[1], g->quat[2], g->quat[3]};
        int nq = has[SD_CSV_QW] + has[SD_CSV_QX] + has[SD_CSV_QY] + has[SD_CSV_QZ];
        if (nq != 0 && nq != 4) {
            st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                              "columns qw, qx, qy, qz: expected all four values or none, got %d", nq);
            goto done;
        }
        if (nq == 4) {
            if (shape < 0) {
                st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                  "columns qw, qx, qy, qz: an orientation applies to bodies of a "
                                  "shape only (this row is a sphere: leave them empty)");
                goto done;
            }
            /* scaled by the largest component first, so that no square overflows */
            double m = 0.0, norm = 0.0;
            for (int k = 0; k < 4; ++k)
                m = fmax(m, fabs(val[SD_CSV_QW + k]));
            if (!(m > 0.0)) {
                st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                  "columns qw, qx, qy, qz: expected a non-zero quaternion, got 0, 0, "
                                  "0, 0");
                goto done;
            }
            for (int k = 0; k < 4; ++k) {
                q[k] = val[SD_CSV_QW + k] / m;
                norm += q[k] * q[k];
            }
            norm = sqrt(norm);
            for (int k = 0; k < 4; ++k)
                q[k] /= norm;
            orient = SD_ORIENT_FIXED;
        }
        int material = g->material;
        if (cell[SD_CSV_MATERIAL] && cell[SD_CSV_MATERIAL][0]) {
            material = -1;
            for (size_t i = 0; i < s->material_count && material < 0; ++i)
                if (!strcmp(s->materials[i].name, cell[SD_CSV_MATERIAL]))
                    material = (int)i;
            if (material < 0) {
                sd_escape(esc, sizeof esc, cell[SD_CSV_MATERIAL], 40);
                st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key,
                                  "column material: unknown material '%s' (materials: %s)", esc,
                                  sd_csv_known(s, 1, known, sizeof known));
                goto done;
            }
        }
        if (g->list_count == cap) {
            size_t ncap = cap ? 2 * cap : 256;
            if (!sd_csv_grow(g, ncap)) {
                st = sd_error_set(err, SD_ERR_MEMORY, g->file, line, key, "out of memory");
                goto done;
            }
            cap = ncap;
        }
        size_t k = g->list_count;
        sd_sphere_def *d = &g->list[k];
        memset(d, 0, sizeof *d);
        d->position = (sd_v3d){val[SD_CSV_X], val[SD_CSV_Y], val[SD_CSV_Z]};
        d->radius = shape < 0 ? val[SD_CSV_R] : 0.0; /* a shape's bound is set at generation */
        /* Velocity columns override the generator's velocity, per component. */
        const sd_v3d v0 = g->velocity, w0 = g->angular_velocity;
        d->velocity = (sd_v3d){has[SD_CSV_VX] ? val[SD_CSV_VX] : v0.x, has[SD_CSV_VY] ? val[SD_CSV_VY] : v0.y,
                               has[SD_CSV_VZ] ? val[SD_CSV_VZ] : v0.z};
        d->angular_velocity = (sd_v3d){has[SD_CSV_WX] ? val[SD_CSV_WX] : w0.x,
                                       has[SD_CSV_WY] ? val[SD_CSV_WY] : w0.y,
                                       has[SD_CSV_WZ] ? val[SD_CSV_WZ] : w0.z};
        d->material = material;
        g->list_shape[k] = shape;
        g->list_orient[k] = orient;
        memcpy(g->list_quat[k], q, sizeof q);
        g->list_lines[k] = line;
        g->list_count = k + 1;
    }
    if (st == SD_OK && ferror(f))
        st = sd_error_set(err, SD_ERR_IO, g->file, line, key, "read error: %s", strerror(errno));
    else if (st == SD_OK && !have_header)
        st = sd_error_set(err, SD_ERR_INPUT, g->file, line > 0 ? line : 0, key,
                          "the CSV file has no header line (expected a header such as "
                          "x,y,z,radius)");
    else if (st == SD_OK && g->list_count == 0)
        st = sd_error_set(err, SD_ERR_INPUT, g->file, line, key, "the CSV file has no particles");
done:
    fclose(f);
    return st;
}

