/* outline.c — reading closed outlines from CSV and generating irregular
 * ones (rock-like, rounded polygons) for the Fourier fit (seed 002 §2.3,
 * §3.1 uses 12 irregular templates; tests/unit/fourier.c makes its own set
 * here). Invariant: see outline.h (≥ 3 finite points, seeded determinism).
 */
#define _POSIX_C_SOURCE 200809L
#include "shape/outline.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/rng.h"

/* "x,y" with optional spaces; 1 on success */
static int sd_parse_xy(const char *s, double *x, double *y)
{
    char *end;
    errno = 0;
    *x = strtod(s, &end);
    if (end == s)
        return 0;
    s = end;
    while (*s == ' ' || *s == '\t')
        ++s;
    if (*s != ',')
        return 0;
    ++s;
    *y = strtod(s, &end);
    if (end == s)
        return 0;
    s = end;
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
        ++s;
    return *s == '\0';
}

/* two words separated by a comma: a header line */
static int sd_is_header(const char *s)
{
    int commas = 0, letters = 0;
    for (; *s; ++s) {
        if (*s == ',')
            ++commas;
        else if (isalpha((unsigned char)*s))
            ++letters;
        else if (!(*s == '_' || *s == ' ' || *s == '\t' || *s == '\r' || *s == '\n' || *s == '(' || *s == ')'))
            return 0;
    }
    return commas == 1 && letters >= 2;
}

sd_status sd_outline_read_csv(const char *path, sd_vec2 **pts, size_t *n, sd_error *err)
{
    *pts = NULL;
    *n = 0;
    FILE *f = fopen(path, "r");
    if (!f)
        return sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot open the outline: %s", strerror(errno));
    char line[4096];
    size_t cap = 0, cnt = 0;
    sd_vec2 *p = NULL;
    int lineno = 0, data_lines = 0;
    sd_status st = SD_OK;
    while (fgets(line, sizeof line, f)) {
        ++lineno;
        size_t len = strlen(line);
        if (len == sizeof line - 1 && line[len - 1] != '\n') {
            st = sd_error_set(err, SD_ERR_INPUT, path, lineno, "", "line longer than %zu characters", sizeof line - 2);
            break;
        }
        const char *s = line;
        while (*s == ' ' || *s == '\t')
            ++s;
        if (*s == '\0' || *s == '\n' || *s == '\r' || *s == '#')
            continue;
        double x, y;
        if (!sd_parse_xy(s, &x, &y)) {
            if (data_lines == 0 && sd_is_header(s)) {
                ++data_lines;
                continue;
            }
            line[strcspn(line, "\r\n")] = '\0';
            st = sd_error_set(err, SD_ERR_INPUT, path, lineno, "", "expected two numbers 'x,y' (m), got '%.60s'",
                              s[0] ? s : line);
            break;
        }
        ++data_lines;
        if (!isfinite(x) || !isfinite(y)) {
            st = sd_error_set(err, SD_ERR_INPUT, path, lineno, "", "the coordinates must be finite numbers");
            break;
        }
        if (cnt == cap) {
            size_t nc = cap ? 2 * cap : 256;
            sd_vec2 *q = sd_realloc(p, nc * sizeof *q);
            if (!q) {
                st = sd_error_set(err, SD_ERR_MEMORY, path, lineno, "", "out of memory reading the outline");
                break;
            }
            p = q;
            cap = nc;
        }
        p[cnt++] = sd_v2((sd_real)x, (sd_real)y);
    }
    if (st == SD_OK && ferror(f))
        st = sd_error_set(err, SD_ERR_IO, path, 0, "", "read error");
    fclose(f);
    if (st == SD_OK && cnt >= 2 && p[cnt - 1].x == p[0].x && p[cnt - 1].y == p[0].y)
        --cnt; /* the closing point */
    if (st == SD_OK && cnt < 3)
        st = sd_error_set(err, SD_ERR_INPUT, path, 0, "", "an outline needs at least 3 points, got %zu", cnt);
    if (st != SD_OK) {
        sd_free(p);
        return st;
    }
    *pts = p;
    *n = cnt;
    return SD_OK;
}

size_t sd_outline_rock(uint64_t seed, sd_real R, sd_real aspect, sd_real roughness, sd_vec2 *out, size_t n)
{
    sd_rng rng = sd_rng_seed(seed);
    sd_real amp[9] = {0}, ph[9] = {0};
    for (int k = 2; k <= 8; ++k) {
        amp[k] = roughness * (sd_real)sd_rng_range(&rng, 0.5, 1.0) * sd_pow((sd_real)k, SD_R(-1.2));
        ph[k] = (sd_real)sd_rng_range(&rng, 0.0, 2.0 * SD_PI_D);
    }
    for (size_t i = 0; i < n; ++i) {
        const sd_real phi = SD_R(2.0) * SD_PI * (sd_real)i / (sd_real)n;
        sd_real r = SD_R(1.0);
        for (int k = 2; k <= 8; ++k)
            r += amp[k] * sd_cos((sd_real)k * phi + ph[k]);
        out[i] = sd_v2(aspect * R * r * sd_cos(phi), R * r * sd_sin(phi));
    }
    return n;
}

size_t sd_outline_rounded_polygon(int sides, sd_real R, sd_real aspect, sd_real rot, sd_real r, int per_corner,
                                  int per_edge, sd_vec2 *out)
{
    sd_vec2 v[64];
    if (sides < 3 || sides > 64 || per_corner < 2 || per_edge < 0)
        return 0;
    for (int i = 0; i < sides; ++i) {
        const sd_real a = rot + SD_R(2.0) * SD_PI * (sd_real)i / (sd_real)sides;
        v[i] = sd_v2(aspect * R * sd_cos(a), R * sd_sin(a));
    }
    size_t k = 0;
    sd_vec2 T2prev = sd_v2_zero();
    sd_vec2 first_T1 = sd_v2_zero();
    for (int i = 0; i <= sides; ++i) {
        const sd_vec2 c = v[i % sides], p = v[(i + sides - 1) % sides], q = v[(i + 1) % sides];
        const sd_vec2 u1 = sd_v2_normalize(sd_v2_sub(p, c)), u2 = sd_v2_normalize(sd_v2_sub(q, c));
        const sd_real alpha = sd_atan2(sd_fabs(sd_v2_cross(u1, u2)), sd_v2_dot(u1, u2)); /* interior angle */
        const sd_real t = r / sd_sin(SD_R(0.5) * alpha) * sd_cos(SD_R(0.5) * alpha);
        const sd_vec2 T1 = sd_v2_madd(c, t, u1), T2 = sd_v2_madd(c, t, u2);
        if (i > 0) /* the edge from the previous corner's T2 to this T1, inner points */
            for (int j = 1; j <= per_edge; ++j)
                out[k++] = sd_v2_madd(T2prev, (sd_real)j / (sd_real)(per_edge + 1), sd_v2_sub(T1, T2prev));
        if (i == sides)
            break;
        if (i == 0)
            first_T1 = T1;
        const sd_vec2 C = sd_v2_madd(c, r / sd_sin(SD_R(0.5) * alpha), sd_v2_normalize(sd_v2_add(u1, u2)));
        const sd_real a0 = sd_atan2(T1.y - C.y, T1.x - C.x);
        const sd_real sweep = SD_PI - alpha;
        for (int j = 0; j < per_corner; ++j) {
            const sd_real a = a0 + sweep * (sd_real)j / (sd_real)(per_corner - 1);
            out[k++] = sd_v2(C.x + r * sd_cos(a), C.y + r * sd_sin(a));
        }
        T2prev = T2;
    }
    (void)first_T1;
    return k;
}

size_t sd_outline_densify(const sd_vec2 *poly, size_t np, int per_edge, sd_vec2 *out)
{
    size_t k = 0;
    if (per_edge < 1)
        per_edge = 1;
    for (size_t i = 0; i < np; ++i) {
        const sd_vec2 p = poly[i], q = poly[(i + 1) % np];
        for (int j = 0; j < per_edge; ++j)
            out[k++] = sd_v2_madd(p, (sd_real)j / (sd_real)per_edge, sd_v2_sub(q, p));
    }
    return k;
}
