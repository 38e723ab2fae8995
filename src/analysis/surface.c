/* surface.c — the bed height, the free-surface angle of a drum and the
 * angle of repose of a heap (shapedem/analysis.h; issue 16's drum and heap
 * examples, seed 004 §4.2 and seed 000 §3.4 for the drum).
 *
 * Heights are along up (-gravity). A particle's highest point is its true
 * shape's support along up (analysis/bodies.c), so a cube lying flat tops
 * out at its face, not its bounding sphere.
 *
 * Bed height: the highest point of all; the height of the centres below
 * which a given fraction of the mass lies (sorted, accumulated); the
 * mass-weighted mean height.
 *
 * Surfaces: the particles are split into columns along a horizontal
 * coordinate s (drum: across the cross section; heap: the distance from
 * the heap's axis); each column's surface height is the highest point of
 * its particles (by their centre's column), taken at that particle's s;
 * the least-squares line h = a + b s through these points, for the
 * columns within the fit range, gives the angle atan |b|. A plane of
 * particles tilted at angle t gives b = tan t: every point lies on the
 * plane moved up by the particles' radius. The fit range
 * keeps out the apex and the toe of a heap, and the wall regions of a
 * drum, where the surface is not straight.
 *
 * Invariant: serial sums in storage order; the same bits for any thread
 * count.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/analysis.h"
#include "core/alloc.h"

typedef struct sd_an_hm {
    double h, m;
} sd_an_hm;

static int sd_an_dbl_cmp(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return a < b ? -1 : a > b;
}

/* share of the particles within the heap's radius */
#define SD_AN_HEAP_QUANTILE 0.98

static int sd_an_hm_cmp(const void *x, const void *y)
{
    const sd_an_hm *a = x, *b = y;
    return a->h < b->h ? -1 : a->h > b->h;
}

sd_status sd_world_bed_height(const sd_world *w, const sd_region_def *region, double fraction, sd_bed_height *out,
                              sd_error *err)
{
    if (!w || !out)
        return sd_error_null(err, "sd_world_bed_height", !w ? "world" : "out");
    memset(out, 0, sizeof *out);
    if (!(fraction > 0 && fraction <= 1))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "fraction", "expected a mass fraction in (0, 1], got %g",
                            fraction);
    sd_an_region r;
    sd_an_set set;
    sd_status st;
    if ((st = sd_an_region_make(region, w->dim2, &r, err)) != SD_OK || (st = sd_an_gather(w, &set, err)) != SD_OK)
        return st;
    sd_an_hm *v = sd_calloc(set.n ? set.n : 1, sizeof *v);
    if (!v) {
        sd_an_free(&set);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (bed height)");
    }
    size_t m = 0;
    double mt = 0, mh = 0, top = -HUGE_VAL;
    for (size_t k = 0; k < set.n; ++k) {
        const sd_an_body *b = &set.b[k];
        if (!sd_an_region_has(&r, b->x))
            continue;
        v[m].h = (double)sd_v3_dot(b->x, set.up);
        v[m].m = (double)b->mass;
        mt += v[m].m;
        mh += v[m].m * v[m].h;
        top = fmax(top, (double)sd_an_top(w, b, set.up));
        m++;
    }
    out->particles = m;
    if (m > 0) {
        int by_number = !(mt > 0); /* only fixed bodies: count them */
        if (by_number) {
            for (size_t k = 0; k < m; ++k) {
                v[k].m = 1.0;
                mh += v[k].h;
            }
            mt = (double)m;
        }
        qsort(v, m, sizeof *v, sd_an_hm_cmp);
        double acc = 0, want = fraction * mt;
        out->fraction_height = v[m - 1].h;
        for (size_t k = 0; k < m; ++k) {
            acc += v[k].m;
            if (acc >= want * (1.0 - 1e-12)) {
                out->fraction_height = v[k].h;
                break;
            }
        }
        out->top = top;
        out->mean = mh / mt;
    }
    sd_free(v);
    sd_an_free(&set);
    return SD_OK;
}

/* The least-squares line through the columns whose centre lies in [s0,
 * s1] and that hold particles (h[c] > -inf); each column's point is its
 * highest particle's (sp[c], h[c]), a point of the surface itself; column
 * c's centre is s_lo + (c + 1/2) ds. */
static void sd_an_fit(const double *sp, const double *h, int bins, double s_lo, double ds, double s0, double s1,
                      sd_surface_fit *out)
{
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int c = 0; c < bins; ++c) {
        double sc = s_lo + ((double)c + 0.5) * ds, s = sp[c];
        if (sc < s0 || sc > s1 || !(h[c] > -HUGE_VAL))
            continue;
        n += 1, sx += s, sy += h[c], sxx += s * s, sxy += s * h[c];
    }
    out->columns = (int)n;
    double den = n * sxx - sx * sx;
    if (n < 2 || !(fabs(den) > 0))
        return;
    double b = (n * sxy - sx * sy) / den, a = (sy - b * sx) / n, rr = 0;
    for (int c = 0; c < bins; ++c) {
        double sc = s_lo + ((double)c + 0.5) * ds, s = sp[c];
        if (sc < s0 || sc > s1 || !(h[c] > -HUGE_VAL))
            continue;
        rr += (h[c] - a - b * s) * (h[c] - a - b * s);
    }
    out->slope = b;
    out->angle = atan(fabs(b)) * (180.0 / 3.14159265358979323846);
    out->rms = sqrt(rr / n);
}

static sd_status sd_an_fit_check(int bins, const double fit[2], sd_error *err)
{
    if (bins < 2)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "bins", "expected at least 2 columns, got %d", bins);
    if (!fit)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "fit", "the fit range is NULL (expected two fractions)");
    if (!(fit[0] >= 0 && fit[1] <= 1 && fit[1] > fit[0]))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "fit", "expected 0 <= fit[0] < fit[1] <= 1, got [%g, %g]", fit[0],
                            fit[1]);
    return SD_OK;
}

sd_status sd_world_drum_surface(const sd_world *w, const sd_region_def *drum, int bins, const double fit[2],
                                sd_surface_fit *out, sd_error *err)
{
    if (!w || !out)
        return sd_error_null(err, "sd_world_drum_surface", !w ? "world" : "out");
    memset(out, 0, sizeof *out);
    sd_status st;
    if ((st = sd_an_fit_check(bins, fit, err)) != SD_OK)
        return st;
    if (!drum || drum->kind != SD_REGION_CYLINDER)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "region", "the drum surface needs a cylinder region (the drum)");
    sd_an_region r;
    sd_an_set set;
    if ((st = sd_an_region_make(drum, w->dim2, &r, err)) != SD_OK || (st = sd_an_gather(w, &set, err)) != SD_OK)
        return st;
    /* up within the cross section, and the horizontal e across it */
    sd_vec3 u = sd_v3_sub(set.up, sd_v3_scale(r.a, sd_v3_dot(set.up, r.a)));
    sd_vec3 e = sd_v3_cross(set.up, r.a);
    if (!(sd_v3_norm(u) > SD_R(1e-6)) || !(sd_v3_norm(e) > SD_R(1e-6))) {
        sd_an_free(&set);
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "axis",
                            "the drum's axis is vertical: its cross section has no "
                            "free-surface angle");
    }
    u = sd_v3_normalize(u);
    e = sd_v3_normalize(e);
    double *h = sd_calloc(2u * (size_t)bins, sizeof *h), *sp = h + bins;
    if (!h) {
        sd_an_free(&set);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (drum surface)");
    }
    for (int c = 0; c < bins; ++c)
        h[c] = -HUGE_VAL;
    const double R = (double)r.radius, ds = 2.0 * R / bins;
    const double h0 = (double)sd_v3_dot(r.c, u);
    for (size_t k = 0; k < set.n; ++k) {
        const sd_an_body *b = &set.b[k];
        if (!sd_an_region_has(&r, b->x))
            continue;
        double s = (double)sd_v3_dot(sd_v3_sub(b->x, r.c), e);
        long c = (long)floor((s + R) / ds);
        c = c < 0 ? 0 : c >= bins ? bins - 1 : c;
        double top = (double)sd_an_top(w, b, u) - h0;
        if (top > h[c]) {
            h[c] = top;
            sp[c] = s;
        }
    }
    sd_an_fit(sp, h, bins, -R, ds, -R + 2.0 * R * fit[0], -R + 2.0 * R * fit[1], out);
    sd_free(h);
    sd_an_free(&set);
    return SD_OK;
}

sd_status sd_world_heap_angle(const sd_world *w, const sd_v3d *center, int bins, const double fit[2],
                              sd_surface_fit *out, sd_error *err)
{
    if (!w || !out)
        return sd_error_null(err, "sd_world_heap_angle", !w ? "world" : "out");
    memset(out, 0, sizeof *out);
    sd_status st;
    if ((st = sd_an_fit_check(bins, fit, err)) != SD_OK)
        return st;
    sd_an_set set;
    if ((st = sd_an_gather(w, &set, err)) != SD_OK)
        return st;
    if (set.n == 0) {
        sd_an_free(&set);
        return SD_OK;
    }
    sd_vec3 c;
    if (center) {
        c = sd_v3((sd_real)center->x, (sd_real)center->y, (sd_real)center->z);
    } else { /* the centre of mass (by number when all are fixed) */
        double m = 0, cx = 0, cy = 0, cz = 0;
        for (size_t k = 0; k < set.n; ++k) {
            double mk = set.b[k].mass > 0 ? (double)set.b[k].mass : 1e-300;
            m += mk, cx += mk * (double)set.b[k].x.x, cy += mk * (double)set.b[k].x.y, cz += mk * (double)set.b[k].x.z;
        }
        c = sd_v3((sd_real)(cx / m), (sd_real)(cy / m), (sd_real)(cz / m));
    }
    double *rad = sd_calloc(set.n, sizeof *rad), *h = sd_calloc(2u * (size_t)bins, sizeof *h);
    if (!rad || !h) {
        sd_free(rad);
        sd_free(h);
        sd_an_free(&set);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (heap angle)");
    }
    double *srt = sd_calloc(set.n, sizeof *srt);
    if (!srt) {
        sd_free(rad);
        sd_free(h);
        sd_an_free(&set);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (heap angle)");
    }
    for (size_t k = 0; k < set.n; ++k) {
        sd_vec3 d = sd_v3_sub(set.b[k].x, c);
        d = sd_v3_sub(d, sd_v3_scale(set.up, sd_v3_dot(d, set.up))); /* horizontal part */
        rad[k] = srt[k] = (double)sd_v3_norm(d);
    }
    /* the heap's radius: 98 % of the centres lie within it, so the few
     * that rolled far away do not stretch the columns */
    qsort(srt, set.n, sizeof *srt, sd_an_dbl_cmp);
    size_t q = (size_t)ceil(SD_AN_HEAP_QUANTILE * (double)set.n);
    const double R = srt[(q > 0 ? q : 1) - 1];
    sd_free(srt);
    for (int k = 0; k < bins; ++k)
        h[k] = -HUGE_VAL;
    if (R > 0) {
        const double ds = R / bins;
        for (size_t k = 0; k < set.n; ++k) {
            if (rad[k] > R)
                continue;
            long b = (long)floor(rad[k] / ds);
            b = b < 0 ? 0 : b >= bins ? bins - 1 : b;
            double top = (double)sd_an_top(w, &set.b[k], set.up);
            if (top > h[b]) {
                h[b] = top;
                h[bins + b] = rad[k];
            }
        }
        sd_an_fit(h + bins, h, bins, 0.0, ds, R * fit[0], R * fit[1], out);
    }
    sd_free(rad);
    sd_free(h);
    sd_an_free(&set);
    return SD_OK;
}
