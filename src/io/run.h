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
/* Writes the state of the run's simulation as a checkpoint at path. */
typedef sd_status (*sd_run_ckpt_writer)(void *ctx, const char *path, sd_error *err);
/* The run calls write(ctx, path, err) for each checkpoint and for the
 * failed-<step>.h5 of a step that failed on the state, where it would call
 * sd_checkpoint_write(world, path, err) (a decomposed run writes from
 * every rank, and marks its worlds for a rebuild there: docs/mpi.md). */
void sd_run_set_checkpoint_writer(sd_run *r, sd_run_ckpt_writer write, void *ctx);
/* Lines (each ended by '\n') added to summary.txt; copied. */
void sd_run_set_note(sd_run *r, const char *lines);

#endif
