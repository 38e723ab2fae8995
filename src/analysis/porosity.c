/* porosity.c — packing fraction and porosity of a region by a voxel
 * lattice of the true particle shapes (seed 004 §4.1, "pixelating the
 * space occupied by the packing"; shapedem/analysis.h), and its radial
 * profile in a cylinder.
 *
 * The region is cut into voxels (a box: n_a = round(L_a / voxel) per axis,
 * edges L_a / n_a so they tile it; a cylinder: the same in its own frame
 * (e1, e2, axis) over the square [-R, R]^2 and its length, keeping the
 * voxels whose centre lies within R of the axis). A voxel is solid when
 * its centre lies inside some particle's true shape (analysis/bodies.c).
 * The fraction is the midpoint rule for the integral of the indicator, so
 * it converges as the lattice is refined (error O(voxel / size) at worst,
 * from the voxels the surfaces cut; docs/analysis.md).
 *
 * Cost: a particle bin (cells of at least twice the largest bounding
 * radius over the region's box, each particle listed in every cell its
 * bounding box meets) gives each voxel its few candidates, so the work is
 * voxels x (particles per cell), not voxels x N. Periodic images of the
 * particles that cross the periodic box are binned too.
 *
 * Determinism: counts are integers, summed per thread and added once, so
 * any thread count gives the same numbers.
 */
#include <math.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "analysis/analysis.h"
#include "core/alloc.h"

#define SD_COOKIE_ANALYSIS 0x5DA1

sd_porosity_def sd_porosity_def_default(void)
{
    sd_porosity_def d;
    memset(&d, 0, sizeof d);
    d.region.kind = SD_REGION_BOX;
    d.cookie = SD_COOKIE_ANALYSIS;
    return d;
}

/* The candidates: particles and their periodic images that can reach the
 * region's box, binned. */
typedef struct sd_an_bin {
    size_t n;
    sd_an_body *b; /* bodies (images shifted) */
    sd_vec3 lo;    /* m, corner of cell (0, 0, 0) */
    sd_real cs;    /* m, cell edge */
    int nc[3];
    uint32_t *start; /* nc[0] nc[1] nc[2] + 1 offsets into idx */
    uint32_t *idx;
} sd_an_bin;

static void sd_an_bin_free(sd_an_bin *g)
{
    sd_free(g->b);
    sd_free(g->start);
    sd_free(g->idx);
    memset(g, 0, sizeof *g);
}

static int sd_an_cell(const sd_an_bin *g, sd_real x, int a)
{
    const sd_real lo = a == 0 ? g->lo.x : a == 1 ? g->lo.y : g->lo.z;
    long c = (long)floor((double)((x - lo) / g->cs));
    return (int)(c < 0 ? 0 : c >= g->nc[a] ? g->nc[a] - 1 : c);
}

static sd_status sd_an_bin_make(const sd_world *w, const sd_an_set *set, const sd_an_region *r, sd_an_bin *g,
                                sd_error *err)
{
    memset(g, 0, sizeof *g);
    /* periodic shifts on the periodic axes: -1, 0, +1 periods */
    const unsigned per = w->def.periodic;
    const sd_vec3 L =
        sd_v3((sd_real)(w->def.domain_hi.x - w->def.domain_lo.x), (sd_real)(w->def.domain_hi.y - w->def.domain_lo.y),
              (sd_real)(w->def.domain_hi.z - w->def.domain_lo.z));
    int sx = (per & SD_PERIODIC_X) ? 1 : 0, sy = (per & SD_PERIODIC_Y) ? 1 : 0, sz = (per & SD_PERIODIC_Z) ? 1 : 0;
    size_t cap = set->n * (size_t)((2 * sx + 1) * (2 * sy + 1) * (2 * sz + 1));
    g->b = sd_calloc(cap ? cap : 1, sizeof *g->b);
    if (!g->b)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (porosity candidates)");
    sd_real rmax = 0;
    for (size_t k = 0; k < set->n; ++k) {
        const sd_an_body *b = &set->b[k];
        for (int i = -sx; i <= sx; ++i)
            for (int j = -sy; j <= sy; ++j)
                for (int l = -sz; l <= sz; ++l) {
                    sd_vec3 x = sd_v3_add(b->x, sd_v3((sd_real)i * L.x, (sd_real)j * L.y, (sd_real)l * L.z));
                    if (x.x + b->bound < r->blo.x || x.x - b->bound > r->bhi.x || x.y + b->bound < r->blo.y ||
                        x.y - b->bound > r->bhi.y || x.z + b->bound < r->blo.z || x.z - b->bound > r->bhi.z)
                        continue;
                    g->b[g->n] = *b;
                    g->b[g->n].x = x;
                    g->n++;
                    rmax = sd_max(rmax, b->bound);
                }
    }
    /* cells of at least 2 rmax, at most ~2^21 of them */
    sd_vec3 ext = sd_v3_sub(r->bhi, r->blo);
    double vol = (double)sd_max(ext.x, SD_R(1e-300)) * (double)sd_max(ext.y, SD_R(1e-300)) *
                 (double)(set->dim2 ? SD_R(1.0) : sd_max(ext.z, SD_R(1e-300)));
    double cs = fmax(2.0 * (double)rmax, set->dim2 ? sqrt(vol / 2.0e6) : cbrt(vol / 2.0e6));
    if (!(cs > 0))
        cs = 1.0;
    g->cs = (sd_real)cs;
    g->lo = r->blo;
    const sd_real e[3] = {ext.x, ext.y, ext.z};
    size_t ncell = 1;
    for (int a = 0; a < 3; ++a) {
        g->nc[a] = (set->dim2 && a == 2) ? 1 : (int)fmin(4096.0, floor((double)e[a] / cs) + 1.0);
        ncell *= (size_t)g->nc[a];
    }
    g->start = sd_calloc(ncell + 1, sizeof *g->start);
    if (!g->start)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (porosity bins)");
    /* two passes: count per cell, then fill in body order */
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) {
            for (size_t c = 0; c < ncell; ++c)
                g->start[c + 1] += g->start[c];
            g->idx = sd_calloc(g->start[ncell] ? g->start[ncell] : 1, sizeof *g->idx);
            if (!g->idx)
                return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (porosity bins)");
        }
        for (size_t k = 0; k < g->n; ++k) {
            const sd_an_body *b = &g->b[k];
            int c0[3] = {sd_an_cell(g, b->x.x - b->bound, 0), sd_an_cell(g, b->x.y - b->bound, 1),
                         sd_an_cell(g, b->x.z - b->bound, 2)};
            int c1[3] = {sd_an_cell(g, b->x.x + b->bound, 0), sd_an_cell(g, b->x.y + b->bound, 1),
                         sd_an_cell(g, b->x.z + b->bound, 2)};
            for (int cz = c0[2]; cz <= c1[2]; ++cz)
                for (int cy = c0[1]; cy <= c1[1]; ++cy)
                    for (int cx = c0[0]; cx <= c1[0]; ++cx) {
                        size_t c = (size_t)cx + (size_t)g->nc[0] * ((size_t)cy + (size_t)g->nc[1] * (size_t)cz);
                        if (pass == 0)
                            g->start[c + 1]++;
                        else
                            g->idx[g->start[c]++] = (uint32_t)k;
                    }
        }
        if (pass == 1) /* start[c] now holds the end of cell c: shift back */
            for (size_t c = ncell; c > 0; --c)
                g->start[c] = g->start[c - 1];
        if (pass == 1)
            g->start[0] = 0;
    }
    return SD_OK;
}

static int sd_an_solid(const sd_world *w, const sd_an_bin *g, sd_vec3 p)
{
    size_t c = (size_t)sd_an_cell(g, p.x, 0) +
               (size_t)g->nc[0] * ((size_t)sd_an_cell(g, p.y, 1) + (size_t)g->nc[1] * (size_t)sd_an_cell(g, p.z, 2));
    for (uint32_t e = g->start[c]; e < g->start[c + 1]; ++e)
        if (sd_an_inside(w, &g->b[g->idx[e]], p))
            return 1;
    return 0;
}

sd_status sd_world_porosity(const sd_world *w, const sd_porosity_def *def, sd_porosity *out, long long *radial_solid,
                            long long *radial_voxels, sd_error *err)
{
    if (!w || !out)
        return sd_error_null(err, "sd_world_porosity", !w ? "world" : "out");
    memset(out, 0, sizeof *out);
    if (!def || def->cookie != SD_COOKIE_ANALYSIS)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                            "sd_porosity_def not initialised with sd_porosity_def_default");
    if (def->region.kind != SD_REGION_BOX && def->region.kind != SD_REGION_CYLINDER)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "region", "porosity needs a box or a cylinder region");
    if (!(def->voxel > 0))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "voxel", "expected a voxel edge > 0, got %g", def->voxel);
    const int nb = def->radial_bins;
    if (nb < 0 || (nb > 0 && def->region.kind != SD_REGION_CYLINDER))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "bins", "radial bins need a cylinder region (and bins >= 1)");
    sd_an_region r;
    sd_status st = sd_an_region_make(&def->region, w->dim2, &r, err);
    if (st != SD_OK)
        return st;
    const int cyl = r.kind == SD_REGION_CYLINDER;
    /* the lattice: n[0] x n[1] x n[2] voxels of edges h over the extent E
     * (box: world axes; cylinder: e1, e2, axis) */
    double E[3], h[3];
    long long n[3];
    if (cyl) {
        E[0] = E[1] = 2.0 * (double)r.radius;
        E[2] = 2.0 * (double)r.half;
    } else {
        E[0] = (double)(r.hi.x - r.lo.x), E[1] = (double)(r.hi.y - r.lo.y), E[2] = (double)(r.hi.z - r.lo.z);
    }
    double total = 1;
    for (int a = 0; a < 3; ++a) {
        n[a] = (w->dim2 && a == 2) ? 1 : (long long)fmax(1.0, floor(E[a] / def->voxel + 0.5));
        h[a] = (w->dim2 && a == 2) ? 1.0 : E[a] / (double)n[a];
        total *= (double)n[a];
    }
    if (total > (double)SD_POROSITY_MAX_VOXELS)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "voxel",
                            "voxel %g m gives %.3g voxels, more than %.3g: take a larger voxel", def->voxel, total,
                            (double)SD_POROSITY_MAX_VOXELS);
    sd_an_set set;
    if ((st = sd_an_gather(w, &set, err)) != SD_OK)
        return st;
    sd_an_bin g;
    if ((st = sd_an_bin_make(w, &set, &r, &g, err)) != SD_OK) {
        sd_an_bin_free(&g);
        sd_an_free(&set);
        return st;
    }
    int threads = def->threads > 0 ? def->threads : w->threads;
    if (threads < 1)
        threads = 1;
    long long *tb = NULL; /* per-thread radial counts: solid, voxels */
    if (nb > 0) {
        tb = sd_calloc((size_t)threads * (size_t)nb * 2u, sizeof *tb);
        if (!tb) {
            sd_an_bin_free(&g);
            sd_an_free(&set);
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (radial bins)");
        }
    }
    const long long rows = n[1] * n[2];
    long long solid = 0, voxels = 0;
    const double R2 = (double)r.radius * (double)r.radius;
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads) reduction(+ : solid, voxels)
    for (long long t = 0; t < rows; ++t) {
        long long j = t % n[1], k = t / n[1];
        long long *mine = NULL;
#ifdef _OPENMP
        if (tb)
            mine = tb + (size_t)omp_get_thread_num() * (size_t)nb * 2u;
#else
        mine = tb;
#endif
        for (long long i = 0; i < n[0]; ++i) {
            double u = ((double)i + 0.5) * h[0], v = ((double)j + 0.5) * h[1], s = ((double)k + 0.5) * h[2];
            sd_vec3 p;
            int bin = 0;
            if (cyl) {
                u -= (double)r.radius;
                v -= (double)r.radius;
                s = w->dim2 ? 0.0 : s - (double)r.half;
                double rr = u * u + v * v;
                if (rr > R2)
                    continue;
                p = sd_v3_add(r.c, sd_v3_add(sd_v3_scale(r.e1, (sd_real)u),
                                             sd_v3_add(sd_v3_scale(r.e2, (sd_real)v), sd_v3_scale(r.a, (sd_real)s))));
                if (nb > 0) {
                    bin = (int)(sqrt(rr) / (double)r.radius * nb);
                    bin = bin >= nb ? nb - 1 : bin;
                }
            } else {
                p = sd_v3(r.lo.x + (sd_real)u, r.lo.y + (sd_real)v, w->dim2 ? SD_R(0.0) : r.lo.z + (sd_real)s);
            }
            int in = sd_an_solid(w, &g, p);
            voxels += 1;
            solid += in;
            if (mine) {
                mine[2 * bin] += in;
                mine[2 * bin + 1] += 1;
            }
        }
    }
    out->voxels = voxels;
    out->solid = solid;
    out->solid_fraction = voxels > 0 ? (double)solid / (double)voxels : 0.0;
    out->porosity = 1.0 - out->solid_fraction;
    for (int a = 0; a < 3; ++a)
        out->voxel[a] = (w->dim2 && a == 2) ? 0.0 : h[a];
    out->volume = (double)voxels * h[0] * h[1] * (w->dim2 ? 1.0 : h[2]);
    if (nb > 0) {
        for (int b = 0; b < nb; ++b) {
            long long sb = 0, vb = 0;
            for (int t = 0; t < threads; ++t) {
                sb += tb[((size_t)t * (size_t)nb + (size_t)b) * 2u];
                vb += tb[((size_t)t * (size_t)nb + (size_t)b) * 2u + 1u];
            }
            if (radial_solid)
                radial_solid[b] = sb;
            if (radial_voxels)
                radial_voxels[b] = vb;
        }
    }
    sd_free(tb);
    sd_an_bin_free(&g);
    sd_an_free(&set);
    return SD_OK;
}
