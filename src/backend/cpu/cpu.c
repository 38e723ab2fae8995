/* cpu.c — the CPU backend as a table of stages (backend/backend.h).
 *
 * Invariant: the CPU works on the host's own arrays, so the copy stages
 * (upload, read back) copy nothing (an upload forgets the last skin test); every other stage is one OpenMP loop of
 * particles.c, pairs.c or walls.c, and the rebuild is the host broad phase
 * (world/rebuild.c, broad/bins.c).
 */
#include "backend/cpu/cpu.h"
#include "world/rebuild.h"

static void sd_cpu_nothing(sd_stage *s)
{
    (void)s;
}

static void sd_cpu_rows_nothing(sd_stage *s, size_t first, size_t end)
{
    (void)s;
    (void)first;
    (void)end;
}

/* The host's arrays are the state; between calls the host may have moved
 * particles (setters, a restore, insertions), so the skin test of the last
 * drift no longer holds. */
static void sd_cpu_upload(sd_stage *s)
{
    s->skin_known = 0;
}

/* the CPU's stages cannot fail */
static sd_status sd_cpu_status(sd_stage *s, sd_error *err)
{
    (void)s;
    (void)err;
    return SD_OK;
}

const sd_backend sd_backend_cpu = {
    .name = "cpu",
    .upload = sd_cpu_upload,
    .upload_walls = sd_cpu_nothing,
    .kick_drift = sd_cpu_kick_drift,
    .needs_rebuild = sd_cpu_needs_rebuild,
    .rebuild = sd_world_rebuild,
    .exchange_ghosts = sd_cpu_exchange_ghosts,
    .forces = sd_cpu_forces,
    .wall_forces = sd_cpu_wall_forces,
    .wall_totals = sd_cpu_wall_totals,
    .gather = sd_cpu_gather,
    .gather_kick = sd_cpu_gather_kick,
    .gather_kick_drift = sd_cpu_gather_kick_drift,
    .check_finite = sd_cpu_check_finite,
    .min_radius = sd_cpu_min_radius,
    .read_back = sd_cpu_nothing,
    .read_back_wall_pairs = sd_cpu_nothing,
    .read_back_state = sd_cpu_rows_nothing,
    .upload_state = sd_cpu_rows_nothing,
    .release = sd_cpu_nothing,
    .status = sd_cpu_status,
};
