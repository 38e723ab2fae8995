/* decomp.c — the static split into a grid of boxes (mpi.h): pure
 * arithmetic, no MPI.
 *
 * The cuts nest: the particles sorted by (x, id) are cut into n[0] runs of
 * equal count; each run, sorted by (y, id), into n[1] runs; each of those,
 * sorted by (z, id), into n[2]. The stable id breaks every tie, so equal
 * positions split the same way on every rank and in every run.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "mpi/mpi.h"

typedef struct sd_mpi_key {
    double s;    /* m, the coordinate along the axis being sorted */
    double c[3]; /* m, the position */
    uint64_t id;
} sd_mpi_key;

/* (s, id) order: the coordinate first, the stable id breaks ties. */
static int sd_mpi_key_cmp(const void *a, const void *b)
{
    const sd_mpi_key *p = a, *q = b;
    if (p->s != q->s)
        return p->s < q->s ? -1 : 1;
    return p->id < q->id ? -1 : (p->id > q->id ? 1 : 0);
}

static int sd_mpi_below(double c, uint64_t id, const sd_mpi_cut *cut)
{
    return c < cut->x || (c == cut->x && id < cut->id);
}

/* The run of (c, id) among the parts - 1 sorted cuts. */
static int sd_mpi_run_of(const sd_mpi_cut *cuts, int parts, double c, uint64_t id)
{
    int lo = 0, hi = parts - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (sd_mpi_below(c, id, &cuts[mid]))
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

/* Where the cuts of each level start in g->cut[level]: level 0 has n0 - 1
 * cuts; level 1, n1 - 1 for each run i0 (at i0 (n1 - 1)); level 2, n2 - 1
 * for each (i0, i1) (at (i0 n1 + i1)(n2 - 1)). */
static size_t sd_mpi_level(const sd_mpi_grid *g, int level, int run)
{
    return (size_t)run * (size_t)(g->n[level] - 1);
}

/* Sorts k[0 .. n) along axis and cuts it into parts runs of equal count:
 * run r is k[floor(r n / parts) .. floor((r + 1) n / parts)); cuts gets
 * parts - 1 entries (a run with no particle for it and after: a cut above
 * everything), first the start of each run. */
static void sd_mpi_cut_runs(sd_mpi_key *k, size_t n, int axis, int parts, sd_mpi_cut *cuts, size_t *first)
{
    for (size_t t = 0; t < n; ++t)
        k[t].s = k[t].c[axis];
    qsort(k, n, sizeof *k, sd_mpi_key_cmp);
    for (int r = 0; r <= parts; ++r)
        first[r] = n * (size_t)r / (size_t)parts;
    for (int r = 1; r < parts; ++r)
        cuts[r - 1] =
            first[r] < n ? (sd_mpi_cut){k[first[r]].s, k[first[r]].id} : (sd_mpi_cut){(double)INFINITY, UINT64_MAX};
}

sd_status sd_mpi_grid_split(sd_mpi_grid *g, size_t n, const double *x, const uint64_t *id)
{
    g->by_extent = 0;
    if (g->n[0] * g->n[1] * g->n[2] <= 1)
        return SD_OK;
    sd_mpi_key *k = sd_malloc((n ? n : 1) * sizeof *k);
    if (!k)
        return SD_ERR_MEMORY;
    for (size_t t = 0; t < n; ++t)
        k[t] = (sd_mpi_key){0, {x[3 * t], x[3 * t + 1], x[3 * t + 2]}, id[t]};
    size_t f0[SD_MPI_MAX_RANKS + 1], f1[SD_MPI_MAX_RANKS + 1], f2[SD_MPI_MAX_RANKS + 1];
    sd_mpi_cut_runs(k, n, 0, g->n[0], g->cut[0], f0);
    for (int i0 = 0; i0 < g->n[0]; ++i0) {
        sd_mpi_key *k0 = k + f0[i0];
        size_t n0 = f0[i0 + 1] - f0[i0];
        sd_mpi_cut_runs(k0, n0, 1, g->n[1], &g->cut[1][sd_mpi_level(g, 1, i0)], f1);
        for (int i1 = 0; i1 < g->n[1]; ++i1)
            sd_mpi_cut_runs(k0 + f1[i1], f1[i1 + 1] - f1[i1], 2, g->n[2],
                            &g->cut[2][sd_mpi_level(g, 2, i0 * g->n[1] + i1)], f2);
    }
    sd_free(k);
    return SD_OK;
}

void sd_mpi_grid_even(sd_mpi_grid *g, const double lo[3], const double hi[3])
{
    g->by_extent = 1;
    /* every run of a level is cut at the same places (id 0: a particle
     * exactly on a cut goes above it) */
    for (int a = 0; a < 3; ++a) {
        int runs = a == 0 ? 1 : (a == 1 ? g->n[0] : g->n[0] * g->n[1]);
        for (int r = 0; r < runs; ++r)
            for (int c = 1; c < g->n[a]; ++c)
                g->cut[a][sd_mpi_level(g, a, r) + (size_t)(c - 1)] =
                    (sd_mpi_cut){lo[a] + (hi[a] - lo[a]) * c / g->n[a], 0};
    }
}

int sd_mpi_grid_rank(const sd_mpi_grid *g, const double x[3], uint64_t id)
{
    int i0 = sd_mpi_run_of(g->cut[0], g->n[0], x[0], id);
    int i1 = sd_mpi_run_of(&g->cut[1][sd_mpi_level(g, 1, i0)], g->n[1], x[1], id);
    int i2 = sd_mpi_run_of(&g->cut[2][sd_mpi_level(g, 2, i0 * g->n[1] + i1)], g->n[2], x[2], id);
    return (i0 * g->n[1] + i1) * g->n[2] + i2;
}

void sd_mpi_grid_box(const sd_mpi_grid *g, int r, double lo[3], double hi[3])
{
    int i[3] = {r / (g->n[1] * g->n[2]), (r / g->n[2]) % g->n[1], r % g->n[2]};
    int run[3] = {0, i[0], i[0] * g->n[1] + i[1]};
    for (int a = 0; a < 3; ++a) {
        const sd_mpi_cut *c = &g->cut[a][sd_mpi_level(g, a, run[a])];
        lo[a] = i[a] > 0 ? c[i[a] - 1].x : -(double)INFINITY;
        hi[a] = i[a] < g->n[a] - 1 ? c[i[a]].x : (double)INFINITY;
    }
}

int sd_mpi_grid_shape(const int req[3], int ranks, const double extent[3], int planar, int out[3])
{
    if (req[0] == 0 && req[1] == 0 && req[2] == 0) {
        /* auto: the factorisation px py pz = ranks with the least cut area
         * (sum over the axes of the cuts times the cross-section they cut,
         * for equal counts in a box of the particles' extent); ties to
         * more cuts along x, then y, as the enumeration meets them */
        double best = (double)INFINITY;
        out[0] = ranks, out[1] = out[2] = 1;
        for (int px = ranks; px >= 1; --px) {
            if (ranks % px)
                continue;
            for (int py = ranks / px; py >= 1; --py) {
                if ((ranks / px) % py)
                    continue;
                int pz = ranks / px / py;
                if (planar && pz > 1)
                    continue;
                double area = (px - 1) * extent[1] * extent[2] + (py - 1) * extent[0] * extent[2] +
                              (pz - 1) * extent[0] * extent[1];
                if (area < best) {
                    best = area;
                    out[0] = px, out[1] = py, out[2] = pz;
                }
            }
        }
        return 0;
    }
    long product = 1;
    for (int a = 0; a < 3; ++a) {
        out[a] = req[a] < 0 ? ranks : req[a]; /* -1: slabs along that axis */
        product *= out[a];
    }
    if (product != ranks || (planar && out[2] != 1))
        return -1;
    return 0;
}

void sd_mpi_grid_box_text(const sd_mpi_grid *g, int r, char *buf, size_t size)
{
    double lo[3], hi[3];
    sd_mpi_grid_box(g, r, lo, hi);
    size_t used = 0;
    for (int a = 0; a < 3 && used < size; ++a)
        used += (size_t)snprintf(buf + used, size - used, "%s[%.6g, %.6g]", a ? " x " : "", lo[a], hi[a]);
}

const char *sd_mpi_grid_how(const sd_mpi_grid *g)
{
    return g->by_extent ? "cut evenly over the insertion regions (fewer particles than ranks at the start)"
                        : "cut by (coordinate, stable id) into equal particle counts";
}
