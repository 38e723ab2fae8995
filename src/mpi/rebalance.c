/* rebalance.c — the split cut again from the particles as they are now
 * (mpi.h: sd_mpi_recut), for simulation.mpi_rebalance_every.
 *
 * Every rank gathers every particle's position and id and computes the
 * same cuts, with the same grid shape (sd_mpi_grid_split sorts by
 * coordinate and id, so the ranks' order of arrival does not matter).
 * Memory: 32 bytes per particle of the whole world on each rank, for the
 * moment of the re-cut.
 */
#include <mpi.h>

#include "core/alloc.h"
#include "core/error.h"
#include "mpi/mpi.h"
#include "world/world.h"

sd_status sd_mpi_recut(const sd_world *w, sd_mpi_grid *g, sd_error *err)
{
    int ranks = g->n[0] * g->n[1] * g->n[2];
    int n = (int)w->p.n, counts[SD_MPI_MAX_RANKS], displ[SD_MPI_MAX_RANKS], total = 0;
    MPI_Allgather(&n, 1, MPI_INT, counts, 1, MPI_INT, MPI_COMM_WORLD);
    for (int r = 0; r < ranks; ++r) {
        displ[r] = total;
        total += counts[r];
    }
    double *x = sd_malloc((size_t)(n + total + 1) * 3 * sizeof *x);
    uint64_t *id = sd_malloc((size_t)(n + total + 1) * sizeof *id);
    int ok = x && id, all_ok = 0;
    MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
    sd_mpi_failed_elsewhere(!ok, !all_ok);
    if (!all_ok) {
        sd_free(x);
        sd_free(id);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "rebalance: out of memory for %d positions on %s rank",
                            total, ok ? "another" : "this");
    }
    /* this rank's first (the send buffer), then every rank's */
    for (int k = 0; k < n; ++k) {
        x[3 * k] = (double)w->p.x[k].x;
        x[3 * k + 1] = (double)w->p.x[k].y;
        x[3 * k + 2] = (double)w->p.x[k].z;
        id[k] = w->p.id[k];
    }
    MPI_Allgatherv(id, n, MPI_UINT64_T, id + n, counts, displ, MPI_UINT64_T, MPI_COMM_WORLD);
    for (int r = 0; r < ranks; ++r) { /* three doubles per particle */
        counts[r] *= 3;
        displ[r] *= 3;
    }
    MPI_Allgatherv(x, 3 * n, MPI_DOUBLE, x + 3 * n, counts, displ, MPI_DOUBLE, MPI_COMM_WORLD);
    sd_status st = sd_mpi_grid_split(g, (size_t)total, x + 3 * n, id + n);
    sd_free(x);
    sd_free(id);
    if (st != SD_OK)
        return sd_error_set(err, st, "", 0, "", "rebalance: out of memory splitting %d particles", total);
    return SD_OK;
}
