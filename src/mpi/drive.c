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
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "mpi/mpi.h"
#include "world/view.h"
#include "world/world.h"

enum { SD_DRIVE_STEP = 1, SD_DRIVE_VIEW = 2, SD_DRIVE_END = 3, SD_DRIVE_CHECKPOINT = 4 };

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

/* One command: what, and how many steps. */
static void sd_drive_bcast(long long *cmd)
{
    MPI_Bcast(cmd, 2, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
}

/* Every rank: the command's work. Step errors end the job from the rank
 * that met them (no other rank could go on without it). */
static sd_status sd_drive_do(sd_mpi *m, sd_world *w, sd_world *g, const long long *cmd, sd_error *err)
{
    if (cmd[0] == SD_DRIVE_CHECKPOINT) {
        /* a checkpoint's state (the view) holds no pair lists for a step to
         * use: every restart rebuilds them at its first step, from the
         * springs by key; the run that wrote it does the same, on every
         * rank, so a restart on any rank count continues with its bits */
        w->dirty = 1;
        if (g)
            g->dirty = 1;
        return SD_OK;
    }
    if (cmd[0] == SD_DRIVE_STEP || !w->prepared) { /* a VIEW first prepares (collective: the rebuild's hooks) */
        double t = sd_drive_now();
        sd_status st = sd_world_step(w, cmd[0] == SD_DRIVE_STEP ? (long)cmd[1] : 0, err);
        sd_drive_time.step += sd_drive_now() - t;
        if (st != SD_OK)
            sd_mpi_fail(m, "step", st, err);
    }
    return sd_mpi_view(m, w, g, err);
}

sd_status sd_mpi_drive_step(void *drive, long n, sd_error *err)
{
    sd_mpi_drive *d = drive;
    long long cmd[2] = {SD_DRIVE_STEP, n};
    sd_drive_bcast(cmd);
    return sd_drive_do(d->m, d->w, d->g, cmd, err);
}

sd_status sd_mpi_drive_view(sd_mpi_drive *d, sd_error *err)
{
    long long cmd[2] = {SD_DRIVE_VIEW, 0};
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
    if (!note)
        return;
    size_t used = 0;
#define SD_NOTE(...)                                                         \
    do {                                                                     \
        if (used < size)                                                     \
            used += (size_t)snprintf(note + used, size - used, __VA_ARGS__); \
    } while (0)
    SD_NOTE("mpi_ranks: %d\n", ranks);
    SD_NOTE("mpi_split: along x by (x, stable id) into equal particle counts at the start%s; ",
            sd_mpi_rebalances(m) > 0 ? " and at each re-cut" : "");
    const sd_mpi_cut *cuts = sd_mpi_cuts(m);
    if (ranks == 1)
        SD_NOTE("one rank, no cut");
    else
        SD_NOTE("cuts now at x =");
    for (int r = 0; r + 1 < ranks; ++r)
        SD_NOTE(" %.10g", cuts[r].x);
    SD_NOTE("%s\nmpi_particles_per_rank:", ranks > 1 ? " m" : "");
    unsigned long long moved = 0;
    for (int r = 0; r < ranks; ++r) {
        SD_NOTE(" %llu", all[2 * r]);
        moved += all[2 * r + 1];
    }
    SD_NOTE("\nmpi_migrations: %llu\nmpi_rebalances: %ld\n", moved, sd_mpi_rebalances(m));
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
#undef SD_NOTE
}

void sd_mpi_drive_checkpoint(void *drive)
{
    sd_mpi_drive *d = drive;
    long long cmd[2] = {SD_DRIVE_CHECKPOINT, 0};
    sd_drive_bcast(cmd);
    (void)sd_drive_do(d->m, d->w, d->g, cmd, NULL);
}

void sd_mpi_drive_end(sd_mpi_drive *d, char *note, size_t size)
{
    long long cmd[2] = {SD_DRIVE_END, 0};
    sd_drive_bcast(cmd);
    sd_drive_note(d->m, d->w, note, size);
}

void sd_mpi_follow(sd_mpi *m, sd_world *w)
{
    for (;;) {
        long long cmd[2];
        sd_drive_bcast(cmd);
        if (cmd[0] == SD_DRIVE_END)
            break;
        sd_error err;
        memset(&err, 0, sizeof err);
        (void)sd_drive_do(m, w, NULL, cmd, &err); /* a failed gather is rank 0's to report */
    }
    sd_drive_note(m, w, NULL, 0);
}

sd_status sd_mpi_attach_built(sd_world *w, sd_mpi **out, sd_error *err)
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
    return sd_mpi_attach(w, out, err);
}

sd_status sd_mpi_attach_restored(sd_world *w, sd_mpi **out, sd_error *err)
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
    sd_status st = sd_mpi_attach(w, out, err);
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
