/* drive.c — `shapedem run` under mpirun (mpi.h: sd_mpi_drive): rank 0
 * runs the scene's schedule on the view (mpi/view.c) and broadcasts each
 * step count to the other ranks, which follow.
 *
 * Why one driver: every decision of the run (when to write, when
 * simulation.stop_when is met, a checkpoint due by the wall clock, an
 * interrupt) is then taken once, on rank 0, from the view: no rank can
 * decide otherwise and leave the others waiting in a collective. The
 * followers hold no schedule; they step when told and send their part of
 * the view.
 */
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <shapedem/scene.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/checkpoint.h"
#include "mpi/mpi.h"
#include "world/view.h"
#include "world/world.h"

enum { SD_DRIVE_STEP = 1, SD_DRIVE_VIEW = 2, SD_DRIVE_END = 3, SD_DRIVE_WRITE = 4 };

/* ---- where the time goes (summary.txt's mpi_ lines; bench/mpi) ---------------- */

/* This process's seconds inside its steps, and inside the exchanges among
 * them: the world's comm hooks (mpi/comm.c) timed by a copy of their table
 * whose known entries wrap the originals (an entry added later is kept,
 * untimed). The exchanges' time includes waiting for the slowest rank. */
static struct {
    sd_world_comm table;
    const sd_world_comm *orig;
    double exchange, step; /* s */
} sd_drive_time;

static double sd_drive_now(void) { return MPI_Wtime(); }

static int sd_timed_any(void *ctx, int flag)
{
    double t = sd_drive_now();
    int r = sd_drive_time.orig->any(ctx, flag);
    sd_drive_time.exchange += sd_drive_now() - t;
    return r;
}

static double sd_timed_min(void *ctx, double v)
{
    double t = sd_drive_now();
    double r = sd_drive_time.orig->min(ctx, v);
    sd_drive_time.exchange += sd_drive_now() - t;
    return r;
}

static sd_status sd_timed_migrate(void *ctx, sd_world *w, sd_error *err)
{
    double t = sd_drive_now();
    sd_status r = sd_drive_time.orig->migrate(ctx, w, err);
    sd_drive_time.exchange += sd_drive_now() - t;
    return r;
}

static sd_status sd_timed_ghosts(void *ctx, sd_world *w, sd_error *err)
{
    double t = sd_drive_now();
    sd_status r = sd_drive_time.orig->ghosts(ctx, w, err);
    sd_drive_time.exchange += sd_drive_now() - t;
    return r;
}

static void sd_timed_exchange(void *ctx, sd_world *w)
{
    double t = sd_drive_now();
    sd_drive_time.orig->exchange(ctx, w);
    sd_drive_time.exchange += sd_drive_now() - t;
}

void sd_mpi_drive_time(sd_world *w)
{
    if (!w->comm || w->comm == &sd_drive_time.table)
        return;
    sd_drive_time.orig = w->comm;
    sd_drive_time.table = *w->comm;
    sd_drive_time.table.any = sd_timed_any;
    sd_drive_time.table.min = sd_timed_min;
    sd_drive_time.table.migrate = sd_timed_migrate;
    sd_drive_time.table.ghosts = sd_timed_ghosts;
    sd_drive_time.table.exchange = sd_timed_exchange;
    w->comm = &sd_drive_time.table;
}

/* The interrupt flag this process watches (sd_mpi_drive_watch), NULL none. */
static volatile sig_atomic_t *sd_drive_stop;

void sd_mpi_drive_watch(volatile sig_atomic_t *flag) { sd_drive_stop = flag; }

/* One command: what, how many steps (a WRITE: the path's length), and a
 * WRITE's way (1: every rank into the file, 0: rank 0 from the view). */
static void sd_drive_bcast(long long *cmd)
{
    MPI_Bcast(cmd, 3, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
}

/* Every rank: n steps, in runs that end where the world checks its state
 * (world/step.c: the guards and the finite check, every 256 steps and at
 * the end of each call), so a guard that trips on one rank stops every
 * rank at the same step: after each run the ranks agree whether any
 * failed, and every rank returns the lowest failing rank's error, its
 * message naming that rank. Splitting a call into runs changes no bit of
 * the state (io/run.c). Any other failure comes from inside a step, where
 * the other ranks wait in an exchange: that rank ends the job
 * (sd_mpi_fail). The same reduction carries the interrupt flags
 * (sd_mpi_drive_watch): any rank's is every rank's after it. */
static sd_status sd_drive_steps(sd_mpi *m, sd_world *w, long n, sd_error *err)
{
    int rank = sd_mpi_rank(m), size = sd_mpi_size(m);
    while (n > 0) {
        long run = 256 - (w->step & 255);
        if (run > n)
            run = n;
        long end = w->step + run;
        sd_status st = sd_world_step(w, run, err);
        if (st != SD_OK && w->step != end)
            sd_mpi_fail(m, "step", st, err);
        int me[2] = {st != SD_OK ? rank : size, sd_drive_stop && *sd_drive_stop ? -1 : 0}, all[2];
        MPI_Allreduce(me, all, 2, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
        int low = all[0];
        if (all[1] < 0 && sd_drive_stop)
            *sd_drive_stop = 1;
        if (low == size) {
            n -= run;
            continue;
        }
        sd_error e;
        memset(&e, 0, sizeof e);
        if (rank == low && err)
            e = *err;
        int code = (int)st;
        MPI_Bcast(&code, 1, MPI_INT, low, MPI_COMM_WORLD);
        MPI_Bcast(&e, (int)sizeof e, MPI_BYTE, low, MPI_COMM_WORLD);
        if (err) {
            *err = e;
            if (size > 1)
                snprintf(err->msg, sizeof err->msg, "rank %d of %d: %.*s", low, size, (int)sizeof e.msg - 24, e.msg);
        }
        return (sd_status)code;
    }
    return SD_OK;
}

/* Every rank: the command's work, then the view gathered (also after a
 * failed step: the failed state is written from it). */
static sd_status sd_drive_do(sd_mpi *m, sd_world *w, sd_world *g, const long long *cmd, sd_error *err)
{
    double t = sd_drive_now();
    sd_status st = SD_OK;
    if (cmd[0] == SD_DRIVE_STEP)
        st = sd_drive_steps(m, w, (long)cmd[1], err);
    else if (!w->prepared) { /* a VIEW first prepares (collective: the rebuild's hooks) */
        st = sd_world_step(w, 0, err);
        if (st != SD_OK)
            sd_mpi_fail(m, "step", st, err);
    }
    sd_drive_time.step += sd_drive_now() - t;
    sd_error verr;
    memset(&verr, 0, sizeof verr);
    sd_status vs = sd_mpi_view(m, w, g, st == SD_OK ? err : &verr);
    return st != SD_OK ? st : vs;
}

/* Every rank: the state as a checkpoint at path, from every rank into one
 * file (mpi/ckpt.c: collective) or from the view on rank 0. A checkpoint's
 * state (the view) holds no pair lists for a step to use: every restart
 * rebuilds them at its first step, from the springs by key; the run that
 * wrote it does the same, on every rank, so a restart on any rank count
 * continues with its bits. */
static sd_status sd_drive_write(sd_mpi *m, sd_world *w, sd_world *g, int collective, const char *path,
                                sd_error *err)
{
    w->dirty = 1;
    if (g)
        g->dirty = 1;
    if (collective)
        return sd_mpi_checkpoint_write(m, w, g, path, err);
    return g ? sd_checkpoint_write(g, path, err) : SD_OK;
}

sd_status sd_mpi_drive_step(void *drive, long n, sd_error *err)
{
    sd_mpi_drive *d = drive;
    long long cmd[3] = {SD_DRIVE_STEP, n, 0};
    sd_drive_bcast(cmd);
    return sd_drive_do(d->m, d->w, d->g, cmd, err);
}

sd_status sd_mpi_drive_view(sd_mpi_drive *d, sd_error *err)
{
    long long cmd[3] = {SD_DRIVE_VIEW, 0, 0};
    sd_drive_bcast(cmd);
    return sd_drive_do(d->m, d->w, d->g, cmd, err);
}

/* The ranks' lines of summary.txt (rank 0) from every rank's count and
 * migrations, gathered. */
static void sd_drive_note(sd_mpi *m, const sd_world *w, char *note, size_t size)
{
    int ranks = sd_mpi_size(m);
    unsigned long long mine[2] = {w->p.n, sd_mpi_migrated(m)}, all[128];
    MPI_Gather(mine, 2, MPI_UNSIGNED_LONG_LONG, all, 2, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    double secs[2] = {sd_drive_time.step, sd_drive_time.exchange}, all_secs[128];
    MPI_Gather(secs, 2, MPI_DOUBLE, all_secs, 2, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    /* each rank's CUDA device (its node-local rank mod the node's devices,
     * world/backend.c), -1 on the CPU */
    int dev = strcmp(sd_world_backend(w), "cuda") == 0 ? w->stage.device_index : -1, all_dev[64];
    MPI_Gather(&dev, 1, MPI_INT, all_dev, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (!note)
        return;
    size_t used = 0;
#define SD_NOTE(...)                                                         \
    do {                                                                     \
        if (used < size)                                                     \
            used += (size_t)snprintf(note + used, size - used, __VA_ARGS__); \
    } while (0)
    SD_NOTE("mpi_ranks: %d\n", ranks);
    const sd_mpi_grid *g = sd_mpi_grid_of(m);
    SD_NOTE("mpi_split: %d x %d x %d boxes along x, y, z, %s at the start%s\nmpi_particles_per_rank:", g->n[0], g->n[1],
            g->n[2], sd_mpi_grid_how(g), sd_mpi_rebalances(m) > 0 ? ", by count at each re-cut" : "");
    unsigned long long moved = 0;
    for (int r = 0; r < ranks; ++r) {
        SD_NOTE(" %llu", all[2 * r]);
        moved += all[2 * r + 1];
    }
    SD_NOTE("\nmpi_migrations: %llu\nmpi_rebalances: %ld\nmpi_devices:", moved, sd_mpi_rebalances(m));
    for (int r = 0; r < ranks; ++r) {
        if (all_dev[r] >= 0)
            SD_NOTE(" cuda:%d", all_dev[r]);
        else
            SD_NOTE(" cpu");
    }
    SD_NOTE("\n");
    /* wall seconds per rank inside its steps, and of those inside the
     * exchanges (ghosts, migration, the rebuild vote: waiting included) */
    double share = 0;
    SD_NOTE("mpi_step_seconds:");
    for (int r = 0; r < ranks; ++r)
        SD_NOTE(" %.4g", all_secs[2 * r]);
    SD_NOTE("\nmpi_exchange_seconds:");
    for (int r = 0; r < ranks; ++r) {
        SD_NOTE(" %.4g", all_secs[2 * r + 1]);
        share += all_secs[2 * r] > 0 ? all_secs[2 * r + 1] / all_secs[2 * r] / ranks : 0;
    }
    SD_NOTE("\nmpi_exchange_share: %.4f\n", share);
    /* last: with many ranks a short buffer cuts this line only */
    SD_NOTE("mpi_boxes:");
    for (int r = 0; r < ranks; ++r) {
        char box[200];
        sd_mpi_grid_box_text(g, r, box, sizeof box);
        SD_NOTE("%s %s", r ? ";" : "", box);
    }
    SD_NOTE(" m (now)\n");
#undef SD_NOTE
}

sd_status sd_mpi_drive_write(void *drive, const char *path, sd_error *err)
{
    sd_mpi_drive *d = drive;
    size_t len = strlen(path);
    /* every rank into the one file where this build's HDF5 has MPI-IO,
     * unless SHAPEDEM_MPI_CHECKPOINT=rank0 (docs/mpi.md): rank 0 decides */
    const char *way = getenv("SHAPEDEM_MPI_CHECKPOINT");
    int collective = sd_checkpoint_collective() && !(way && !strcmp(way, "rank0"));
    long long cmd[3] = {SD_DRIVE_WRITE, (long long)len, collective};
    sd_drive_bcast(cmd);
    MPI_Bcast((void *)(uintptr_t)path, (int)len + 1, MPI_CHAR, 0, MPI_COMM_WORLD);
    return sd_drive_write(d->m, d->w, d->g, collective, path, err);
}

void sd_mpi_drive_end(sd_mpi_drive *d, char *note, size_t size)
{
    long long cmd[3] = {SD_DRIVE_END, 0, 0};
    sd_drive_bcast(cmd);
    sd_drive_note(d->m, d->w, note, size);
}

void sd_mpi_follow(sd_mpi *m, sd_world *w)
{
    for (;;) {
        long long cmd[3];
        sd_drive_bcast(cmd);
        if (cmd[0] == SD_DRIVE_END)
            break;
        sd_error err;
        memset(&err, 0, sizeof err);
        if (cmd[0] == SD_DRIVE_WRITE) { /* the file's path, then every rank writes */
            char *path = cmd[1] >= 0 && cmd[1] < (1 << 20) ? sd_malloc((size_t)cmd[1] + 1) : NULL;
            if (!path)
                sd_mpi_fail(m, "checkpoint", SD_ERR_MEMORY, NULL);
            MPI_Bcast(path, (int)cmd[1] + 1, MPI_CHAR, 0, MPI_COMM_WORLD);
            /* rank 0 reports the status, the same on every rank */
            (void)sd_drive_write(m, w, NULL, (int)cmd[2], path, &err);
            sd_free(path);
            continue;
        }
        (void)sd_drive_do(m, w, NULL, cmd, &err); /* a failed step or gather is rank 0's to report */
    }
    sd_drive_note(m, w, NULL, 0);
}

int sd_mpi_local_rank(void)
{
    /* the ranks that share this node's memory, in the order of their world
     * ranks (MPI errors are fatal: MPI_ERRORS_ARE_FATAL) */
    MPI_Comm node;
    int r = 0;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    MPI_Comm_rank(node, &r);
    MPI_Comm_free(&node);
    return r;
}

sd_status sd_mpi_attach_built(sd_world *w, const sd_mpi_split_req *split, sd_mpi **out, sd_error *err)
{
    if (w->step != 0 || w->time != 0) {
        *out = NULL;
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "sd_mpi_attach_built: the world has stepped");
    }
    /* what the serial prepare made: its pair lists (whose first force pass
     * started the springs of the pairs touching at step 0), its ghosts and
     * the rebuild it counted; the decomposed prepare makes them again */
    w->pairs.n = 0;
    memset(w->pairs.kind_start, 0, sizeof w->pairs.kind_start);
    w->wpairs.n = 0;
    memset(w->wpairs.kind_start, 0, sizeof w->wpairs.kind_start);
    w->n_ghost = 0;
    w->rebuilds = 0;
    w->prepared = 0;
    w->dirty = 1;
    return sd_mpi_attach(w, split, out, err);
}

sd_status sd_mpi_attach_restored(sd_world *w, const sd_mpi_split_req *split, sd_mpi **out, sd_error *err)
{
    /* the springs by key (and the volume law's overlap points): every
     * entry, the other ranks' particles' too, so that the first rebuild
     * finds each of this rank's pairs' history whoever held it */
    sd_pair_list *l = &w->pairs;
    size_t n = l->n;
    sd_pair_key *key = sd_malloc((n ? n : 1) * sizeof *key);
    sd_vec3 *ds = sd_malloc((n ? n : 1) * sizeof *ds), *x0 = sd_malloc((n ? n : 1) * sizeof *x0);
    uint8_t *x0_ok = sd_malloc(n ? n : 1);
    int kept = key && ds && x0 && x0_ok;
    if (kept) {
        memcpy(key, l->key, n * sizeof *key);
        memcpy(ds, l->ds, n * sizeof *ds);
        memcpy(x0, l->x0, n * sizeof *x0);
        memcpy(x0_ok, l->x0_ok, n);
    }
    l->n = 0;
    memset(l->kind_start, 0, sizeof l->kind_start);
    w->n_ghost = 0;  /* made again at the first rebuild */
    w->prepared = 0; /* for sd_mpi_attach (collective: every rank calls it); the forces came with the state */
    sd_status st = sd_mpi_attach(w, split, out, err);
    if (st == SD_OK && (!kept || sd_pairs_reserve(l, n) != SD_OK))
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory keeping %zu springs", n);
    if (st == SD_OK) {
        for (size_t e = 0; e < n; ++e) {
            l->i[e] = l->j[e] = 0; /* read by no one: the first step rebuilds before the forces */
            l->key[e] = key[e];
            l->ds[e] = ds[e];
            l->x0[e] = x0[e];
            l->x0_ok[e] = x0_ok[e];
        }
        l->n = n;
        for (int k = 1; k <= SD_PAIR_KIND_COUNT; ++k)
            l->kind_start[k] = n;
        w->dirty = 1;
        w->prepared = 1;
        /* the wall pairs left after the split: the walls' drift reads them
         * in gather order before the first rebuild (as in a dirty restore,
         * world/snapshot.c: the list's order) */
        for (size_t g = 0; g < w->wpairs.n; ++g)
            w->wpairs.gidx[g] = (uint32_t)g;
        if (sd_world_views(w) != SD_OK)
            st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the views");
    }
    sd_free(key);
    sd_free(ds);
    sd_free(x0);
    sd_free(x0_ok);
    return st;
}
