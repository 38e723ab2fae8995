/* mpi_run.c — `shapedem run` under mpirun (mpi_run.h): the shapedem-mpi
 * program's side of the run command. Every rank builds the scene and keeps
 * its part (src/mpi/: sd_mpi_attach_built); rank 0 runs the schedule of
 * main.c's run on the whole world gathered (sd_mpi_view) and drives the
 * others (sd_mpi_drive), which write nothing.
 *
 * Failures before the run (bad input, a refused scene) are agreed over
 * the ranks, so one message is printed and every rank returns the same
 * status: no rank waits in a collective for one that returned. A guard
 * that trips inside a step stops every rank at that step (sd_mpi_drive_step):
 * rank 0 writes failed-<step>.h5 and summary.txt as a serial run does;
 * other failures inside a step end the job from the rank that met them
 * (sd_mpi_fail).
 */
#define _POSIX_C_SOURCE 200809L

#include <mpi.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "cli/commands.h"
#include "cli/mpi_run.h"
#include "core/alloc.h"
#include "io/run.h"
#include "io/scene.h"
#include "mpi/mpi.h"
#include "world/snapshot.h"

struct sd_cli_mpi {
    sd_mpi *m;
    sd_mpi_drive d;
    int rank, size;
};

/* Every rank: its scene-built world against rank 0's (issue 31): the
 * scene hash's parts and the start particles, so a stale or edited copy
 * of the scene on one node (another gravity, density, dt) is refused
 * before anything runs or is written; 0, or 2 with msg filled. */
static int sd_cli_mpi_same_scene(const sd_world *w, int rank, int size, char *msg, size_t msize)
{
    uint64_t mine[SD_SCENE_PART_COUNT + 1], first[SD_SCENE_PART_COUNT + 1];
    sd_world_scene_parts(w, mine);
    mine[SD_SCENE_PART_COUNT] = sd_world_particles_hash(w);
    memcpy(first, mine, sizeof first);
    MPI_Bcast(first, SD_SCENE_PART_COUNT + 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    if (memcmp(first, mine, sizeof mine) == 0)
        return 0;
    char what[512];
    if (sd_scene_parts_differ(first, mine, what, sizeof what) == 0)
        snprintf(what, sizeof what, "the start particles");
    snprintf(msg, msize, "its scene differs from rank 0's (%s differ; the scene files must be the same on every "
             "rank, docs/mpi.md)", what);
    (void)rank;
    (void)size;
    return 2;
}

/* Every rank: did any fail? The lowest rank that did prints its message
 * (rank 0's as the serial program would; another's with its rank), and
 * the worst status is returned everywhere (0 when none failed). */
static int sd_cli_mpi_agree(int rc, const char *msg, int rank, int size)
{
    int first = rc ? rank : size, low = size, worst = 0;
    MPI_Allreduce(&first, &low, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (low < size && rank == low) {
        if (rank == 0)
            fprintf(stderr, "shapedem: %s\n", msg);
        else
            fprintf(stderr, "shapedem: rank %d of %d: %s\n", rank, size, msg);
        fflush(stderr);
    }
    return worst;
}

static int sd_cli_mpi_status(sd_status st) { return st == SD_OK ? 0 : st == SD_ERR_INPUT ? 2 : 1; }

int sd_cli_mpi_begin(const void *cli, sd_cli_load_fn load, const char *restart, sd_scene **scene, sd_world **view,
                     sd_cli_mpi **out)
{
    *out = NULL;
    *view = NULL;
    MPI_Init(NULL, NULL);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    char msg[1536] = "";
    sd_world *w = NULL, *g = NULL;
    sd_mpi *m = NULL;
    sd_error err;
    memset(&err, 0, sizeof err);
    /* rank r of a node takes CUDA device r mod the node's devices (when
     * the scene's backend is cuda; chosen as the world is created) */
    int rc = sd_cli_mpi_agree(load(cli, sd_mpi_local_rank(), scene, &w, msg, sizeof msg), msg, rank, size);
    if (rc == 0)
        rc = sd_cli_mpi_agree(sd_cli_mpi_same_scene(w, rank, size, msg, sizeof msg), msg, rank, size);
    if (rc == 0 && (*scene)->output.checkpoint_minutes > 0) {
        /* a checkpoint makes every rank rebuild at the next step: at a
         * step count, the bits do not depend on the wall clock */
        snprintf(msg, sizeof msg, "%.1000s: output.checkpoint_minutes: checkpoints by wall time would make the results "
                 "depend on it under mpirun: use output.checkpoint_every (docs/mpi.md)", (*scene)->path);
        rc = sd_cli_mpi_agree(2, msg, rank, size);
    }
    /* --restart: the checkpoint's whole world on every rank, then split */
    if (rc == 0 && restart) {
        sd_status st = sd_checkpoint_restore(w, restart, &err);
        if (st != SD_OK)
            sd_error_format(&err, msg, sizeof msg);
        rc = sd_cli_mpi_agree(sd_cli_mpi_status(st), msg, rank, size);
    }
    if (rc == 0) {
        const sd_scene *sc = *scene; /* simulation.mpi_split */
        sd_mpi_split_req split = {{sc->mpi_split[0], sc->mpi_split[1], sc->mpi_split[2]}, sc->mpi_split_line};
        sd_status st =
            restart ? sd_mpi_attach_restored(w, &split, &m, &err) : sd_mpi_attach_built(w, &split, &m, &err);
        if (st != SD_OK && !err.file[0]) /* a refusal names the scene's key: say which scene */
            snprintf(err.file, sizeof err.file, "%.*s", (int)sizeof err.file - 1, (*scene)->path);
        if (st != SD_OK)
            sd_error_format(&err, msg, sizeof msg);
        rc = sd_cli_mpi_agree(sd_cli_mpi_status(st), msg, rank, size);
    }
    /* rank 0: the world the output reads, built again from the scene (its
     * particles and lists are replaced by the gathered ones) */
    if (rc == 0) {
        sd_status st = rank == 0 ? sd_scene_build(*scene, &g, &err) : SD_OK;
        if (st == SD_OK && rank == 0 && restart) /* the view starts as the checkpoint's world */
            st = sd_checkpoint_restore(g, restart, &err);
        if (st != SD_OK)
            sd_error_format(&err, msg, sizeof msg);
        rc = sd_cli_mpi_agree(sd_cli_mpi_status(st), msg, rank, size);
    }
    sd_cli_mpi *mp = rc == 0 ? sd_calloc(1, sizeof *mp) : NULL;
    if (rc == 0) {
        snprintf(msg, sizeof msg, "out of memory");
        rc = sd_cli_mpi_agree(mp ? 0 : 1, msg, rank, size);
    }
    if (rc != 0) {
        sd_free(mp);
        sd_world_destroy(g);
        sd_mpi_detach(w, m);
        sd_world_destroy(w);
        sd_scene_free(*scene);
        *scene = NULL;
        MPI_Finalize();
        return rc;
    }
    sd_mpi_set_rebalance(m, (*scene)->mpi_rebalance_every, 0); /* simulation.mpi_rebalance_every */
    sd_mpi_drive_time(w);
    mp->m = m;
    mp->rank = rank;
    mp->size = size;
    mp->d = (sd_mpi_drive){m, w, g};
    if (rank != 0) {
        /* the job's end comes from rank 0 (mpirun sends SIGTERM to every
         * rank: rank 0 writes its final checkpoint and then ends the run);
         * a signal sent to this rank alone reaches rank 0 with the steps */
        sd_mpi_drive_watch(&sd_cli_interrupted);
        signal(SIGINT, sd_cli_on_signal);
        signal(SIGTERM, sd_cli_on_signal);
        sd_mpi_follow(m, w);
        sd_scene_free(*scene);
        *scene = NULL;
        sd_cli_mpi_free(mp);
        return 0;
    }
    /* the decomposed world prepared, and its step-0 state gathered (a
     * restart's view is the checkpoint's world: its first rows are those
     * the writer wrote at that step) */
    sd_status st = restart ? SD_OK : sd_mpi_drive_view(&mp->d, &err);
    if (st != SD_OK) {
        sd_error_format(&err, msg, sizeof msg);
        fprintf(stderr, "shapedem: %s\n", msg);
        sd_cli_mpi_end(mp, NULL, NULL, 0);
        sd_world_destroy(g);
        sd_scene_free(*scene);
        *scene = NULL;
        sd_cli_mpi_free(mp);
        return 1;
    }
    *view = g;
    *out = mp;
    return -1;
}

void sd_cli_mpi_run(sd_cli_mpi *mp, sd_run *run)
{
    sd_mpi_drive_watch(&sd_cli_interrupted);
    sd_run_set_stepper(run, sd_mpi_drive_step, &mp->d);
    sd_run_set_checkpoint_writer(run, sd_mpi_drive_write, &mp->d);
}

void sd_cli_mpi_end(sd_cli_mpi *mp, sd_run *run, char *note, size_t size)
{
    char buf[4096];
    sd_mpi_drive_end(&mp->d, buf, sizeof buf);
    if (run)
        sd_run_set_note(run, buf);
    if (note)
        snprintf(note, size, "%s", buf);
}

int sd_cli_mpi_size(const sd_cli_mpi *mp) { return mp->size; }

const sd_world *sd_cli_mpi_part(const sd_cli_mpi *mp) { return mp->d.w; }

void sd_cli_mpi_free(sd_cli_mpi *mp)
{
    if (!mp)
        return;
    sd_mpi_detach(mp->d.w, mp->m);
    sd_world_destroy(mp->d.w);
    sd_free(mp);
    MPI_Finalize();
}
