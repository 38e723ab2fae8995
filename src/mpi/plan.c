/* plan.c — the split a decomposed run starts with (mpi.h: sd_mpi_plan),
 * from the world every rank holds whole before sd_mpi_attach; no MPI in
 * it, so `shapedem check --ranks N` prints the same split in any build.
 */
#include <math.h>

#include "core/alloc.h"
#include "core/error.h"
#include "mpi/mpi.h"
#include "world/process.h"
#include "world/world.h"

sd_status sd_mpi_plan(const sd_world *w, const sd_mpi_split_req *req, int ranks, sd_mpi_grid *g, sd_error *err)
{
    static const sd_mpi_split_req auto_req = {{0, 0, 0}, 0};
    if (!req)
        req = &auto_req;
    *g = (sd_mpi_grid){.n = {1, 1, 1}};
    if (ranks > SD_MPI_MAX_RANKS)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "at most %d MPI ranks in this version, got %d",
                            SD_MPI_MAX_RANKS, ranks);
    const sd_particles *p = &w->p;
    size_t n = p->n;
    double *x = sd_malloc((n ? n : 1) * 3 * sizeof *x);
    if (!x)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory splitting %zu particles", n);
    /* the box holding the particles whole (centres +- bounding radius) */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t k = 0; k < n; ++k) {
        double c[3] = {(double)p->x[k].x, (double)p->x[k].y, (double)p->x[k].z}, r = (double)p->radius[k];
        for (int a = 0; a < 3; ++a) {
            x[3 * k + (size_t)a] = c[a];
            lo[a] = fmin(lo[a], c[a] - r);
            hi[a] = fmax(hi[a], c[a] + r);
        }
    }
    /* fewer particles than ranks while insertions will add more (a world
     * filled by insertion): the boxes share the insertion regions and the
     * particles there are evenly, rather than rank 0 owning every particle
     * until a re-cut */
    int even = 0;
    if (n < (size_t)ranks) {
        double il[3], ih[3];
        if (sd_world_insertion_bounds(w, il, ih) > 0) {
            even = 1;
            for (int a = 0; a < 3; ++a)
                lo[a] = fmin(lo[a], il[a]), hi[a] = fmax(hi[a], ih[a]);
        }
    }
    /* the extent for the grid's shape: an axis with next to no extent (a
     * flat region, one layer) keeps a thousandth of the largest, so that
     * cuts across the other two still cost what they cut */
    double ext[3], big = 0;
    for (int a = 0; a < 3; ++a) {
        ext[a] = hi[a] > lo[a] ? hi[a] - lo[a] : 0.0;
        big = fmax(big, ext[a]);
    }
    for (int a = 0; a < 3; ++a)
        ext[a] = fmax(ext[a], 1e-3 * big);
    sd_status st = SD_OK;
    if (sd_mpi_grid_shape(req->n, ranks, ext, w->def.dimension == 2, g->n) != 0) {
        int q = req->n[0] < 0 ? ranks : req->n[0], r = req->n[1] < 0 ? ranks : req->n[1],
            s = req->n[2] < 0 ? ranks : req->n[2];
        if (w->def.dimension == 2 && s != 1)
            st = sd_error_set(err, SD_ERR_INPUT, "", req->line, "simulation.mpi_split",
                              "the planar mode (dimension: 2) has no cuts along z: expected [px, py, 1], x or y");
        else
            st = sd_error_set(err, SD_ERR_INPUT, "", req->line, "simulation.mpi_split",
                              "[%d, %d, %d] makes %d boxes, but the run has %d MPI ranks: px py pz must equal the "
                              "rank count (or use auto, x, y or z)",
                              q, r, s, q * r * s, ranks);
    } else if (even) {
        sd_mpi_grid_even(g, lo, hi);
    } else if (sd_mpi_grid_split(g, n, x, p->id) != SD_OK) {
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory splitting %zu particles", n);
    }
    sd_free(x);
    return st;
}
