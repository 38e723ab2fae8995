/* decomp.c — the static split along x (mpi.h): pure arithmetic, no MPI. */
#include <math.h>
#include <stdlib.h>

#include "core/alloc.h"
#include "mpi/mpi.h"

typedef struct sd_mpi_key {
    double x;
    uint64_t id;
} sd_mpi_key;

/* (x, id) order: x first, the stable id breaks ties, so equal positions
 * still split the same way on every rank and in every run. */
static int sd_mpi_key_cmp(const void *a, const void *b)
{
    const sd_mpi_key *p = a, *q = b;
    if (p->x != q->x)
        return p->x < q->x ? -1 : 1;
    return p->id < q->id ? -1 : (p->id > q->id ? 1 : 0);
}

static int sd_mpi_below(double x, uint64_t id, const sd_mpi_cut *c)
{
    return x < c->x || (x == c->x && id < c->id);
}

sd_status sd_mpi_split(size_t n, const double *x, const uint64_t *id, int ranks, sd_mpi_cut *cuts)
{
    if (ranks <= 1)
        return SD_OK;
    sd_mpi_key *k = sd_malloc((n ? n : 1) * sizeof *k);
    if (!k)
        return SD_ERR_MEMORY;
    for (size_t t = 0; t < n; ++t)
        k[t] = (sd_mpi_key){x[t], id[t]};
    qsort(k, n, sizeof *k, sd_mpi_key_cmp);
    for (int r = 1; r < ranks; ++r) {
        size_t first = n * (size_t)r / (size_t)ranks; /* rank r's first particle */
        /* no particle for rank r and after: a cut above everything */
        cuts[r - 1] = first < n ? (sd_mpi_cut){k[first].x, k[first].id} : (sd_mpi_cut){(double)INFINITY, UINT64_MAX};
    }
    sd_free(k);
    return SD_OK;
}

int sd_mpi_rank_of(const sd_mpi_cut *cuts, int ranks, double x, uint64_t id)
{
    /* the cuts are sorted: the first cut above (x, id) ends its rank */
    int lo = 0, hi = ranks - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (sd_mpi_below(x, id, &cuts[mid]))
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

void sd_mpi_slab(const sd_mpi_cut *cuts, int ranks, int r, double *lo, double *hi)
{
    *lo = r > 0 ? cuts[r - 1].x : -(double)INFINITY;
    *hi = r < ranks - 1 ? cuts[r].x : (double)INFINITY;
}
