/* table.c — the CUDA backend as a table of stages (backend/backend.h), in
 * a build with SHAPEDEM_CUDA (or the test-only emulated one).
 *
 * Invariant: every stage but the rebuild works on the device copies of the
 * views (state.h; device.cu, particles.cu, pairs.cu, walls.cu). The
 * rebuild stays host code for now (docs/architecture.md): it reads the
 * state back, so the broad phase bins the current positions and carries
 * the current history, then calls the world's rebuild (world/rebuild.c,
 * the one exception to "no backend sees sd_world", as in cpu/cpu.c); the
 * world refills the views and step.c's upload copies them to the device.
 * In a decomposed run (src/mpi/) the migration and the ghosts run inside
 * that host rebuild, between the read back and the upload; the ghost
 * exchange of every other step goes through the host's rows
 * (read_back_state of the owned rows before it, upload_state of the ghost
 * rows after it: step.c).
 */
#include "backend/cuda/cuda.h"
#include "backend/cuda/state.h"
#include "world/rebuild.h"
#include "world/world.h"

static sd_status sd_cuda_rebuild(sd_world *w, sd_error *err)
{
    sd_cuda_read_back(&w->stage); /* positions and history as they are now */
    sd_status st = sd_cuda_status(&w->stage, err);
    if (st != SD_OK)
        return st;
    return sd_world_rebuild(w, err);
}

static const sd_backend sd_backend_cuda_table = {
    .name = "cuda",
    .upload = sd_cuda_upload,
    .upload_walls = sd_cuda_upload_walls,
    .kick_drift = sd_cuda_kick_drift,
    .needs_rebuild = sd_cuda_needs_rebuild,
    .rebuild = sd_cuda_rebuild,
    .exchange_ghosts = sd_cuda_exchange_ghosts,
    .forces = sd_cuda_forces,
    .wall_forces = sd_cuda_wall_forces,
    .wall_totals = sd_cuda_wall_totals,
    .gather = sd_cuda_gather,
    .gather_kick = sd_cuda_gather_kick,
    .gather_kick_drift = sd_cuda_gather_kick_drift,
    .check_finite = sd_cuda_check_finite,
    .min_radius = sd_cuda_min_radius,
    .read_back = sd_cuda_read_back,
    .read_back_wall_pairs = sd_cuda_read_back_wall_pairs,
    .read_back_state = sd_cuda_read_back_state,
    .upload_state = sd_cuda_upload_state,
    .release = sd_cuda_release,
    .status = sd_cuda_status,
};

const sd_backend *sd_cuda_backend(void) { return &sd_backend_cuda_table; }
