/* mpi_run.h — `shapedem run` under mpirun: the shapedem-mpi program's side
 * of the run command (cli/mpi_run.c; docs/mpi.md). */
#ifndef SD_CLI_MPI_RUN_H
#define SD_CLI_MPI_RUN_H

#include <shapedem/scene.h>
#include <shapedem/shapedem.h>

/* The CLI's loader: the scene loaded, overridden (device: the CUDA device
 * slot, sd_scene_set_device; -1 keeps the default) and built; on bad input
 * msg gets the line to print after "shapedem: " and the exit status is
 * returned (0: loaded). */
typedef int (*sd_cli_load_fn)(const void *cli, int device, sd_scene **scene, sd_world **world, char *msg,
                              size_t size);

typedef struct sd_cli_mpi sd_cli_mpi;

/* MPI_Init, then every rank loads and builds the scene (load, with its
 * node-local rank as the device slot: one rank per GPU), and the ranks agree: bad
 * input on any rank is printed once (by the lowest rank that met it) and
 * every rank returns 2. Then the world is split over the ranks; restart,
 * when not NULL, is the checkpoint the split world continues from. Rank 0
 * returns -1 with *view the whole world gathered (the run's schedule runs
 * on it, io/run.c) and *out its state; the other ranks follow rank 0's
 * steps to the end and return their exit status. */
int sd_cli_mpi_begin(const void *cli, sd_cli_load_fn load, const char *restart, sd_scene **scene, sd_world **view,
                     sd_cli_mpi **out);
/* Rank 0: the run steps the ranks (io/run.h's stepper); its interrupt flag
 * (sd_cli_interrupted) is also set by a signal to any other rank, whose
 * handler sets that rank's (sd_mpi_drive_watch). */
void sd_cli_mpi_run(sd_cli_mpi *mp, sd_run *run);
/* Rank 0: the followers stop; the ranks' summary lines go to the run
 * (when not NULL) and into note. */
void sd_cli_mpi_end(sd_cli_mpi *mp, sd_run *run, char *note, size_t size);
/* The number of ranks. */
int sd_cli_mpi_size(const sd_cli_mpi *mp);
/* Rank 0's part of the world (its profile). */
const sd_world *sd_cli_mpi_part(const sd_cli_mpi *mp);
/* Rank 0's part freed, MPI_Finalize. */
void sd_cli_mpi_free(sd_cli_mpi *mp);

#endif
