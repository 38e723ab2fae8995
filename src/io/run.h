/* run.h — what a run (io/run.c, shapedem/scene.h) takes besides the public
 * API: a decomposed run (src/mpi/, `shapedem run` under mpirun) runs the
 * schedule on rank 0 over the whole world gathered there (sd_mpi_view),
 * and steps the ranks' parts through a stepper instead of stepping that
 * world. */
#ifndef SD_IO_RUN_H
#define SD_IO_RUN_H

#include <shapedem/scene.h>

/* Advances the simulation by steps steps; afterwards the run's world holds
 * the state to write. */
typedef sd_status (*sd_run_stepper)(void *ctx, long steps, sd_error *err);

/* The run calls step(ctx, n, err) where it would call sd_world_step(w, n). */
void sd_run_set_stepper(sd_run *r, sd_run_stepper step, void *ctx);
/* before(ctx) is called before each checkpoint the run writes (a
 * decomposed run marks its worlds for a rebuild there: docs/mpi.md). */
void sd_run_set_checkpoint_hook(sd_run *r, void (*before)(void *ctx), void *ctx);
/* Lines (each ended by '\n') added to summary.txt; copied. */
void sd_run_set_note(sd_run *r, const char *lines);

#endif
