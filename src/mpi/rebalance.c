/* rebalance.c — the split cut again from the particles as they are now
 * (mpi.h: sd_mpi_recut), for simulation.mpi_rebalance_every.
 *
 * Every rank gathers every particle's (x, id) and computes the same cuts
 * (sd_mpi_split sorts by (x, id), so the ranks' order of arrival does not
 * matter). Memory: 16 bytes per particle of the whole world on each rank,
 * for the moment of the re-cut.
 */
#include <mpi.h>

#include "core/alloc.h"
#include "core/error.h"
#include "mpi/mpi.h"
#include "world/world.h"

sd_status sd_mpi_recut(const sd_world *w, int ranks, sd_mpi_cut *cuts, sd_error *err)
{
    int n = (int)w->p.n, counts[64], displ[64], total = 0;
    MPI_Allgather(&n, 1, MPI_INT, counts, 1, MPI_INT, MPI_COMM_WORLD);
    for (int r = 0; r < ranks; ++r) {
        displ[r] = total;
        total += counts[r];
    }
    double *x = sd_malloc((size_t)(n + total + 1) * sizeof *x);
    uint64_t *id = sd_malloc((size_t)(n + total + 1) * sizeof *id);
    int ok = x && id, all_ok = 0;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
    if (!all_ok) {
        sd_free(x);
        sd_free(id);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "rebalance: out of memory for %d positions", total);
    }
    /* this rank's first (the send buffer), then every rank's */
    for (int k = 0; k < n; ++k) {
        x[k] = (double)w->p.x[k].x;
        id[k] = w->p.id[k];
    }
    MPI_Allgatherv(x, n, MPI_DOUBLE, x + n, counts, displ, MPI_DOUBLE, MPI_COMM_WORLD);
    MPI_Allgatherv(id, n, MPI_UINT64_T, id + n, counts, displ, MPI_UINT64_T, MPI_COMM_WORLD);
    sd_status st = sd_mpi_split((size_t)total, x + n, id + n, ranks, cuts);
    sd_free(x);
    sd_free(id);
    if (st != SD_OK)
        return sd_error_set(err, st, "", 0, "", "rebalance: out of memory splitting %d particles", total);
    return SD_OK;
}
