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
#include "shape/shape2d.h"

/* strtod also reads hexadecimal floats (0x1p-1), which YAML scenes do not
 * take: a number here is decimal only. 1 if s[0 .. len) is hexadecimal. */
static int sd_is_hex(const char *s, size_t len)
{
    for (size_t i = 0; i + 1 < len; ++i)
        if (s[i] == '0' && (s[i + 1] == 'x' || s[i + 1] == 'X'))
            return 1;
    return 0;
}

/* "x,y" with optional spaces; 1 on success, -1 for a hexadecimal number */
static int sd_parse_xy(const char *s, double *x, double *y)
{
    char *end;
    errno = 0;
    *x = strtod(s, &end);
    if (end == s)
        return 0;
    if (sd_is_hex(s, (size_t)(end - s)))
        return -1;
    s = end;
    while (*s == ' ' || *s == '\t')
        ++s;
    if (*s != ',')
        return 0;
    ++s;
    *y = strtod(s, &end);
    if (end == s)
        return 0;
    if (sd_is_hex(s, (size_t)(end - s)))
        return -1;
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
        const int parsed = sd_parse_xy(s, &x, &y);
        if (parsed < 0) {
            st = sd_error_set(err, SD_ERR_INPUT, path, lineno, "",
                              "hexadecimal numbers (0x...) are not accepted: write x,y as decimal numbers (m)");
            break;
        }
        if (!parsed) {
            if (data_lines == 0 && sd_is_header(s)) {
                ++data_lines;
                continue;
            }
            /* the row as the user would type it: raw bytes (binary
             * garbage, terminal escapes, \r) escaped, not echoed */
            char shown[256];
            size_t row = strlen(s);
            if (row > 0 && s[row - 1] == '\n') /* the line ending is not part of the row */
                --row;
            if (row > 0 && s[row - 1] == '\r')
                --row;
            st = sd_error_set(err, SD_ERR_INPUT, path, lineno, "", "expected two numbers 'x,y' (m), got '%s'",
                              sd_escape(shown, sizeof shown, s, row < 60 ? row : 60));
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
            r += amp[k] * sd_host_cos((sd_real)k * phi + ph[k]);
        out[i] = sd_v2(aspect * R * r * sd_host_cos(phi), R * r * sd_host_sin(phi));
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
        v[i] = sd_v2(aspect * R * sd_host_cos(a), R * sd_host_sin(a));
    }
    size_t k = 0;
    sd_vec2 T2prev = sd_v2_zero();
    sd_vec2 first_T1 = sd_v2_zero();
    for (int i = 0; i <= sides; ++i) {
        const sd_vec2 c = v[i % sides], p = v[(i + sides - 1) % sides], q = v[(i + 1) % sides];
        const sd_vec2 u1 = sd_v2_normalize(sd_v2_sub(p, c)), u2 = sd_v2_normalize(sd_v2_sub(q, c));
        const sd_real alpha = sd_host_atan2(sd_fabs(sd_v2_cross(u1, u2)), sd_v2_dot(u1, u2)); /* interior angle */
        const sd_real t = r / sd_host_sin(SD_R(0.5) * alpha) * sd_host_cos(SD_R(0.5) * alpha);
        const sd_vec2 T1 = sd_v2_madd(c, t, u1), T2 = sd_v2_madd(c, t, u2);
        if (i > 0) /* the edge from the previous corner's T2 to this T1, inner points */
            for (int j = 1; j <= per_edge; ++j)
                out[k++] = sd_v2_madd(T2prev, (sd_real)j / (sd_real)(per_edge + 1), sd_v2_sub(T1, T2prev));
        if (i == sides)
            break;
        if (i == 0)
            first_T1 = T1;
        const sd_vec2 C = sd_v2_madd(c, r / sd_host_sin(SD_R(0.5) * alpha), sd_v2_normalize(sd_v2_add(u1, u2)));
        const sd_real a0 = sd_host_atan2(T1.y - C.y, T1.x - C.x);
        const sd_real sweep = SD_PI - alpha;
        for (int j = 0; j < per_corner; ++j) {
            const sd_real a = a0 + sweep * (sd_real)j / (sd_real)(per_corner - 1);
            out[k++] = sd_v2(C.x + r * sd_host_cos(a), C.y + r * sd_host_sin(a));
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

/* ---- checking an outline: extent, simplicity, area -------------------------------- */

/* sign of the orientation of c about the directed line a → b (+1 left) */
static int sd_orient(sd_vec2 a, sd_vec2 b, sd_vec2 c)
{
    const sd_real o = sd_v2_cross(sd_v2_sub(b, a), sd_v2_sub(c, a));
    return (o > SD_R(0.0)) - (o < SD_R(0.0));
}

/* c on the segment a-b, given that the three are collinear */
static int sd_on_segment(sd_vec2 a, sd_vec2 b, sd_vec2 c)
{
    return sd_min(a.x, b.x) <= c.x && c.x <= sd_max(a.x, b.x) && sd_min(a.y, b.y) <= c.y && c.y <= sd_max(a.y, b.y);
}

/* the closed segments a-b and c-d share a point */
static int sd_segments_meet(sd_vec2 a, sd_vec2 b, sd_vec2 c, sd_vec2 d)
{
    const int o1 = sd_orient(a, b, c), o2 = sd_orient(a, b, d), o3 = sd_orient(c, d, a), o4 = sd_orient(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0)
        return 1;
    return (o1 == 0 && sd_on_segment(a, b, c)) || (o2 == 0 && sd_on_segment(a, b, d)) ||
           (o3 == 0 && sd_on_segment(c, d, a)) || (o4 == 0 && sd_on_segment(c, d, b));
}

static int sd_pt_less(sd_vec2 a, sd_vec2 b)
{
    return a.x < b.x || (a.x == b.x && a.y < b.y);
}

/* A sweep event: a segment's left end (insert) or right end (remove). */
typedef struct sd_sweep_ev {
    sd_vec2 p;
    uint32_t seg;
    uint32_t insert; /* 0: remove (first at a common point), 1: insert */
} sd_sweep_ev;

static int sd_ev_cmp(const void *va, const void *vb)
{
    const sd_sweep_ev *a = va, *b = vb;
    if (a->p.x != b->p.x)
        return a->p.x < b->p.x ? -1 : 1;
    if (a->p.y != b->p.y)
        return a->p.y < b->p.y ? -1 : 1;
    if (a->insert != b->insert)
        return a->insert < b->insert ? -1 : 1;
    return (a->seg > b->seg) - (a->seg < b->seg);
}

/* The sweep state: the segments crossing the sweep line, ordered bottom to
 * top, in a treap (seeded priorities: deterministic, O(log n) expected). */
typedef struct sd_sweep {
    const sd_vec2 *v; /* deduplicated vertices; segment i is v[i] → v[i + 1 mod m] */
    uint32_t m;
    uint32_t *l, *r, *up, *prio; /* children, parent, priority; SD_NIL for none */
    uint32_t root;
} sd_sweep;

#define SD_NIL UINT32_MAX

static sd_vec2 sd_seg_lo(const sd_sweep *s, uint32_t i)
{
    const sd_vec2 a = s->v[i], b = s->v[(i + 1) % s->m];
    return sd_pt_less(a, b) ? a : b;
}

static sd_vec2 sd_seg_hi(const sd_sweep *s, uint32_t i)
{
    const sd_vec2 a = s->v[i], b = s->v[(i + 1) % s->m];
    return sd_pt_less(a, b) ? b : a;
}

static int sd_seg_adjacent(const sd_sweep *s, uint32_t i, uint32_t j)
{
    return (i + 1) % s->m == j || (j + 1) % s->m == i;
}

static int sd_segs_meet(const sd_sweep *s, uint32_t i, uint32_t j)
{
    return !sd_seg_adjacent(s, i, j) &&
           sd_segments_meet(s->v[i], s->v[(i + 1) % s->m], s->v[j], s->v[(j + 1) % s->m]);
}

/* Is the segment a (inserted now, at its left end) above segment t of the
 * state? 0 / 1, or -1 when a's left end lies on t (they touch). */
static int sd_seg_above(const sd_sweep *s, uint32_t a, uint32_t t)
{
    const sd_vec2 p = sd_seg_lo(s, a), tl = sd_seg_lo(s, t), th = sd_seg_hi(s, t);
    int o = sd_orient(tl, th, p);
    if (o == 0) {
        if (!sd_seg_adjacent(s, a, t))
            return -1; /* t is active, so tl <= p < th in sweep order: p lies on t */
        o = sd_orient(tl, th, sd_seg_hi(s, a)); /* both start at p: by the far ends (not collinear: no backtrack) */
    }
    return o > 0;
}

static void sd_rotate_up(sd_sweep *s, uint32_t x)
{
    const uint32_t p = s->up[x], g = s->up[p];
    if (s->l[p] == x) {
        s->l[p] = s->r[x];
        if (s->r[x] != SD_NIL)
            s->up[s->r[x]] = p;
        s->r[x] = p;
    } else {
        s->r[p] = s->l[x];
        if (s->l[x] != SD_NIL)
            s->up[s->l[x]] = p;
        s->l[x] = p;
    }
    s->up[p] = x;
    s->up[x] = g;
    if (g == SD_NIL)
        s->root = x;
    else if (s->l[g] == p)
        s->l[g] = x;
    else
        s->r[g] = x;
}

/* inserts a; returns 0, or 1 + t when a touches segment t on the way down */
static uint32_t sd_sweep_insert(sd_sweep *s, uint32_t a)
{
    s->l[a] = s->r[a] = s->up[a] = SD_NIL;
    if (s->root == SD_NIL) {
        s->root = a;
        return 0;
    }
    uint32_t x = s->root;
    for (;;) {
        const int above = sd_seg_above(s, a, x);
        if (above < 0)
            return 1u + x;
        uint32_t *next = above ? &s->r[x] : &s->l[x];
        if (*next == SD_NIL) {
            *next = a;
            s->up[a] = x;
            break;
        }
        x = *next;
    }
    while (s->up[a] != SD_NIL && s->prio[a] > s->prio[s->up[a]])
        sd_rotate_up(s, a);
    return 0;
}

static uint32_t sd_sweep_next(const sd_sweep *s, uint32_t x, int dir) /* dir 1: above, 0: below */
{
    const uint32_t *fw = dir ? s->r : s->l, *bw = dir ? s->l : s->r;
    if (fw[x] != SD_NIL) {
        x = fw[x];
        while (bw[x] != SD_NIL)
            x = bw[x];
        return x;
    }
    while (s->up[x] != SD_NIL && fw[s->up[x]] == x)
        x = s->up[x];
    return s->up[x];
}

static void sd_sweep_remove(sd_sweep *s, uint32_t a)
{
    /* rotate a down (its higher-priority child up) until it is a leaf */
    while (s->l[a] != SD_NIL || s->r[a] != SD_NIL) {
        uint32_t c = s->l[a];
        if (c == SD_NIL || (s->r[a] != SD_NIL && s->prio[s->r[a]] > s->prio[c]))
            c = s->r[a];
        sd_rotate_up(s, c);
    }
    const uint32_t p = s->up[a];
    if (p == SD_NIL)
        s->root = SD_NIL;
    else if (s->l[p] == a)
        s->l[p] = SD_NIL;
    else
        s->r[p] = SD_NIL;
}

sd_status sd_outline_check(const sd_vec2 *pts, size_t n, sd_error *err)
{
    if (n >= 2 && pts[n - 1].x == pts[0].x && pts[n - 1].y == pts[0].y)
        --n; /* the closing point */
    if (n < 3)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "an outline needs at least 3 points, got %zu", n);
    if (n >= (size_t)UINT32_MAX / 2)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "an outline may have at most %u points, got %zu",
                            (unsigned)(UINT32_MAX / 2 - 1), n);
    sd_real span = SD_R(0.0), reach = SD_R(0.0);
    if (!sd_points2d_extent(pts, n, &span, &reach))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "the outline's coordinates must be finite numbers");
    /* areas are sums of products of coordinate differences (m^2): keep
     * span² and n·span² well inside double precision */
    if (span > SD_OUTLINE_SPAN_MAX || span < SD_OUTLINE_SPAN_MIN)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                            "the outline spans %g m: its area (m^2) would over- or underflow; coordinates are in "
                            "metres and the outline must span %g to %g m",
                            (double)span, (double)SD_OUTLINE_SPAN_MIN, (double)SD_OUTLINE_SPAN_MAX);
    if (span < SD_R(1e-10) * reach)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                            "the outline is %g m across but lies %g m from the origin: its coordinates keep fewer "
                            "than 7 significant digits of its shape; subtract a point near it from every point",
                            (double)span, (double)reach);

    /* consecutive duplicates (a doubled point) are harmless: drop them */
    sd_vec2 *v = sd_malloc(n * sizeof *v);
    uint32_t *orig = sd_malloc(n * sizeof *orig);
    sd_sweep_ev *ev = sd_malloc(2 * n * sizeof *ev);
    uint32_t *tree = sd_malloc(4 * n * sizeof *tree);
    sd_status st = SD_OK;
    if (!v || !orig || !ev || !tree) {
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory checking the outline");
        goto done;
    }
    uint32_t m = 0;
    for (size_t i = 0; i < n; ++i)
        if (m == 0 || pts[i].x != v[m - 1].x || pts[i].y != v[m - 1].y) {
            v[m] = pts[i];
            orig[m++] = (uint32_t)i;
        }
    while (m > 1 && v[m - 1].x == v[0].x && v[m - 1].y == v[0].y)
        --m;
    if (m < 3) {
        st = sd_error_set(err, SD_ERR_INPUT, "", 0, "", "the outline has fewer than 3 distinct points");
        goto done;
    }
    /* a point where the outline turns straight back over itself (a spike
     * of no width) */
    for (uint32_t i = 0; i < m; ++i) {
        const sd_vec2 a = v[(i + m - 1) % m], b = v[i], c = v[(i + 1) % m];
        if (sd_orient(a, b, c) == 0 && sd_v2_dot(sd_v2_sub(a, b), sd_v2_sub(c, b)) > SD_R(0.0)) {
            st = sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                              "the outline turns back over itself at point %u (%.9g, %.9g): it must be a simple "
                              "closed curve",
                              orig[i] + 1u, (double)b.x, (double)b.y);
            goto done;
        }
    }
    sd_sweep s = {v, m, tree, tree + m, tree + 2 * (size_t)m, tree + 3 * (size_t)m, SD_NIL};
    sd_rng rng = sd_rng_seed(0x5eedu);
    for (uint32_t i = 0; i < m; ++i) {
        s.prio[i] = (uint32_t)(sd_rng_next(&rng) >> 32);
        ev[2 * i] = (sd_sweep_ev){sd_seg_lo(&s, i), i, 1u};
        ev[2 * i + 1] = (sd_sweep_ev){sd_seg_hi(&s, i), i, 0u};
    }
    qsort(ev, 2 * (size_t)m, sizeof *ev, sd_ev_cmp);
    /* a vertex visited twice (the outline pinched to a point): every
     * vertex is the end of exactly two segments, so a point in more than two
     * events is a repeated vertex */
    for (size_t i = 2; i < 2 * (size_t)m; ++i)
        if (ev[i].p.x == ev[i - 2].p.x && ev[i].p.y == ev[i - 2].p.y) {
            st = sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                              "the outline passes through (%.9g, %.9g) twice: it must be a simple closed curve",
                              (double)ev[i].p.x, (double)ev[i].p.y);
            goto done;
        }
    /* Shamos & Hoey (1976): sweep left to right keeping the segments that
     * cross the sweep line in order; the leftmost crossing or touching pair
     * becomes neighbours in that order before the sweep passes it, so it is
     * enough to test each new pair of neighbours: O(n log n). */
    uint32_t hit_a = SD_NIL, hit_b = SD_NIL;
    for (size_t e = 0; e < 2 * (size_t)m && hit_a == SD_NIL; ++e) {
        const uint32_t a = ev[e].seg;
        if (ev[e].insert) {
            const uint32_t t = sd_sweep_insert(&s, a);
            if (t) {
                hit_a = a;
                hit_b = t - 1u;
                break;
            }
            const uint32_t lo = sd_sweep_next(&s, a, 0), hi = sd_sweep_next(&s, a, 1);
            if (lo != SD_NIL && sd_segs_meet(&s, a, lo))
                hit_a = a, hit_b = lo;
            else if (hi != SD_NIL && sd_segs_meet(&s, a, hi))
                hit_a = a, hit_b = hi;
        } else {
            const uint32_t lo = sd_sweep_next(&s, a, 0), hi = sd_sweep_next(&s, a, 1);
            sd_sweep_remove(&s, a);
            if (lo != SD_NIL && hi != SD_NIL && sd_segs_meet(&s, lo, hi))
                hit_a = lo, hit_b = hi;
        }
    }
    if (hit_a != SD_NIL) {
        const uint32_t i = hit_a < hit_b ? hit_a : hit_b, j = hit_a < hit_b ? hit_b : hit_a;
        st = sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                          "the outline crosses or touches itself: its segment from point %u (%.9g, %.9g) to "
                          "point %u meets its segment from point %u (%.9g, %.9g) to point %u; it must be a "
                          "simple closed curve",
                          orig[i] + 1u, (double)v[i].x, (double)v[i].y, orig[(i + 1) % m] + 1u, orig[j] + 1u,
                          (double)v[j].x, (double)v[j].y, orig[(j + 1) % m] + 1u);
        goto done;
    }
    /* area: a simple outline has one; a flat one (a sliver of width 1e-12
     * of its length) has too little for any coverage to mean anything */
    const sd_real area = sd_fabs(sd_polygon2d_area(v, m));
    if (!(area > SD_OUTLINE_FLAT * span * span)) {
        st = sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                          "the outline is flat: it spans %g m but encloses %g m^2 (less than %g of span^2)",
                          (double)span, (double)area, (double)SD_OUTLINE_FLAT);
        goto done;
    }
done:
    sd_free(v);
    sd_free(orig);
    sd_free(ev);
    sd_free(tree);
    return st;
}
