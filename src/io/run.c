/* run.c — a run of a scene's world with its output (shapedem/scene.h):
 * the schedule of the scene's output: section around sd_world_step, over
 * the output writer (io/output.c). `shapedem run` is this plus a progress
 * line and a signal handler.
 *
 * The schedule: the frame and the stats.csv row of step 0 on the first
 * advance (a restarted world: its step's frame, and the CSV rows of its
 * step only where due, each CSV file kept up to that step and continued,
 * so the series match an uninterrupted run's byte for byte); then the world is stepped in chunks that end at the next
 * output event, a stats row at every multiple of stats_every, a frame at
 * every multiple of every and at the last step. Chunking does not change
 * the state: sd_world_step(w, a) then (w, b) gives the bits of (w, a + b).
 *
 * simulation.stop_when ends the run at the first stats row (at or after
 * its `after`, every insertion done) whose kinetic energy is below the
 * threshold: steps becomes done there, so that row is the last, with the
 * closing frame and analysis rows the end of a run gets.
 *
 * Invariant: done is the world's step, from first (its step at the open:
 * 0, or a restart's) to steps (the end step, never before first), so
 * done - first steps ran; after an error (failed) the run takes no further
 * step and writes nothing but the summary.
 */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/fsutil.h"
#include "io/output.h"
#include "io/run.h"
#include "io/scene.h"
#include "io/scene_analysis.h"
#include "io/scene_process.h"
#include <shapedem/analysis.h>

struct sd_run {
    const sd_scene *s;
    sd_world *w;
    sd_output *out;              /* NULL: a run without files */
    char dir[SD_SCENE_PATH_MAX + 16];
    long steps, every, stats_every, done;
    long first;                  /* the world's step at the open: steps run = done - first */
    int started, failed;
    int resumed;                 /* a restored world: the CSV series go on from its step */
    double stepping;             /* s of wall time inside sd_world_step */
    double psteps;               /* particle-steps (the count changes with a pour or an outlet) */
    /* checkpoints (io/checkpoint.c): every ckpt_every steps of the world
     * and every ckpt_seconds of wall time (0: not), into dir */
    long ckpt_every;
    double ckpt_seconds, ckpt_wall; /* s; wall clock of the last one */
    char ckpt_last[SD_SCENE_PATH_MAX + 48];
    FILE *outlet;                /* outlet.csv (cells outlets; io/scene_process.c), NULL when none */
    double outlet_t, outlet_m;   /* s, kg: time and mass removed at its last row */
    sd_analysis_run *an;         /* the scene's analysis: CSV series (io/scene_analysis.c), NULL when none */
    long asked_steps;            /* steps before a stop_when cut them */
    char stop[256];              /* simulation.stop_when: "" when not given, else what happened */
    int stopped;                 /* it was met: steps == done */
    sd_run_stepper stepper;      /* NULL: sd_world_step (io/run.h) */
    void *stepper_ctx;
    sd_run_ckpt_writer write_ckpt; /* NULL: sd_checkpoint_write (io/run.h) */
    void *write_ckpt_ctx;
    char *note;                  /* summary.txt's extra lines, NULL none */
};

/* simulation.stop_when at a stats row: met once its time has come, every
 * insertion has run out (a bed still being filled is not at rest) and the
 * kinetic energy (translational and rotational, sd_world_stats) or the
 * mean speed of the centres (sd_world_motion_stats) is below the
 * threshold. Then the run ends here and r->stop says so. */
static void sd_run_check_stop(sd_run *r)
{
    const sd_scene *s = r->s;
    if (!s->stop_given || r->stopped || r->done % r->stats_every != 0 || sd_world_time(r->w) < s->stop_after)
        return;
    for (size_t k = 0; k < sd_world_insertion_count(r->w); ++k) {
        sd_insert_info ii;
        if (sd_world_get_insertion(r->w, k, &ii) == SD_OK && !ii.done)
            return;
    }
    const char *what = "kinetic energy", *unit = "J";
    double value, below = s->stop_ke_below;
    if (s->stop_speed_below > 0) { /* the mean speed of the centres (shapedem/analysis.h, serial sums) */
        sd_motion_stats ms;
        sd_error e;
        if (sd_world_motion_stats(r->w, NULL, &ms, &e) != SD_OK)
            return;
        what = "mean speed", unit = "m/s";
        value = ms.mean_speed;
        below = s->stop_speed_below;
    } else {
        sd_stats st;
        sd_world_stats(r->w, &st);
        value = st.kinetic_translational + st.kinetic_rotational;
    }
    if (!(value < below)) {
        snprintf(r->stop, sizeof r->stop, "not met (%s %.4g %s at step %ld, t = %.6g s; below %.4g %s "
                 "after %.6g s asked)", what, value, unit, r->done, sd_world_time(r->w), below, unit, s->stop_after);
        return;
    }
    r->stopped = 1;
    r->steps = r->done;
    snprintf(r->stop, sizeof r->stop, "met at step %ld of %ld, t = %.6g s: %s %.4g %s below %.4g %s "
             "(checked from %.6g s on, at each stats row)", r->done, r->asked_steps, sd_world_time(r->w), what,
             value, unit, below, unit, s->stop_after);
}

/* outlet.csv: a row with each stats row, when the world has outlets. */
static void sd_run_outlet_row(sd_run *r)
{
    if (r->outlet) {
        sd_outlet_csv_row(r->outlet, r->w, &r->outlet_t, &r->outlet_m);
        fflush(r->outlet);
    }
}

/* A continued outlet.csv: the time and removed mass of its last row, from
 * which the first row after a restart rates the mass removed; every row
 * rates from the printed values (sd_outlet_csv_row), so the rate is the
 * uninterrupted run's. Left at 0 when none. */
static void sd_run_outlet_last(const char *path, double *t, double *m)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return;
    char line[4096], last[4096] = "";
    int rows = 0;
    while (fgets(line, sizeof line, f))
        if (rows++ > 0 && strchr(line, '\n'))
            memcpy(last, line, sizeof last);
    fclose(f);
    double v[8];
    if (sscanf(last, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &v[7]) == 8) {
        *t = v[0]; /* time, ..., removed_mass: the columns of sd_outlet_csv_header */
        *m = v[7];
    }
}

static double sd_run_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static size_t sd_run_peak_rss(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0)
        return 0;
    return (size_t)ru.ru_maxrss * 1024u; /* Linux reports KiB */
}

sd_status sd_run_open(const sd_scene *s, sd_world *w, const char *dir, sd_run **out, sd_error *err)
{
    if (!out)
        return sd_error_null(err, "sd_run_open", "out");
    *out = NULL;
    if (!s || !w)
        return sd_error_null(err, "sd_run_open", !s ? "scene" : "world");
    sd_scene_info info;
    sd_scene_get_info(s, &info);
    sd_run *r = sd_calloc(1, sizeof *r);
    if (!r)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    r->s = s;
    r->w = w;
    r->steps = info.steps;
    r->every = info.frame_every;
    r->stats_every = info.stats_every;
    r->asked_steps = r->steps;
    if (s->stop_given)
        snprintf(r->stop, sizeof r->stop, "not met (not checked yet: after %.6g s)", s->stop_after);
    /* a restarted world (sd_checkpoint_restore) continues the schedule;
     * one already past the end is refused before a file is touched: the
     * CSV series and frames would be cut back to the end step, and the
     * output of the steps after it lost (issue 31) */
    if (sd_world_step_count(w) > r->steps) {
        long at = sd_world_step_count(w), end = r->steps;
        sd_free(r);
        return sd_error_set(err, SD_ERR_INPUT, s->path, 0, "steps",
                            "the world is at step %ld, past the run's end step %ld: nothing to run, and nothing "
                            "written",
                            at, end);
    }
    r->done = r->first = sd_world_step_count(w);
    r->resumed = r->done > 0;
    r->ckpt_every = s->output.checkpoint_every;
    r->ckpt_seconds = 60.0 * s->output.checkpoint_minutes;
    r->ckpt_wall = sd_run_now();
    if (dir) {
        if (strlen(dir) >= sizeof r->dir) {
            sd_free(r);
            return sd_error_set(err, SD_ERR_INPUT, dir, 0, "", "output directory path too long");
        }
        snprintf(r->dir, sizeof r->dir, "%s", dir);
        sd_output_def od = {.directory = r->dir,
                            .vtk = info.write_frames,
                            .csv = info.write_stats,
                            .shapes = (s->output.formats & SD_OUT_SHAPES) != 0,
                            .shape_resolution = s->output.shape_resolution,
                            .dump = (s->output.formats & SD_OUT_DUMP) != 0,
                            .h5md = (s->output.formats & SD_OUT_H5MD) != 0,
                            .dump_box = {s->world.dimension, s->world.periodic, s->world.domain_lo, s->world.domain_hi},
                            .scene = s->path,
                            .resume_step = r->resumed ? r->done : 0};
        sd_status st = sd_output_open(&od, w, &r->out, err);
        if (st != SD_OK) {
            sd_free(r);
            return st;
        }
        if (sd_world_outlet_count(w) > 0) {
            char path[sizeof r->dir + 16];
            snprintf(path, sizeof path, "%s/outlet.csv", r->dir);
            int kept = 0;
            if (r->resumed)
                st = sd_fs_resume_csv(path, r->done, &r->outlet, &kept, err);
            else {
                remove(path);
                st = sd_fs_create_append(path, &r->outlet, err);
            }
            if (st != SD_OK) {
                sd_output_close(r->out, w, NULL, NULL);
                sd_free(r);
                return st;
            }
            if (!kept)
                sd_outlet_csv_header(r->outlet, w);
            else
                sd_run_outlet_last(path, &r->outlet_t, &r->outlet_m);
        }
        if ((st = sd_analysis_run_open(s, r->dir, r->resumed ? r->done : 0, &r->an, err)) != SD_OK) {
            if (r->outlet)
                fclose(r->outlet);
            sd_output_close(r->out, w, NULL, NULL);
            sd_free(r);
            return st;
        }
    }
    *out = r;
    return SD_OK;
}

long sd_run_steps_to_output(const sd_run *r)
{
    if (!r)
        return 0;
    long next = r->steps;
    long to_frame = r->every - r->done % r->every, to_stats = r->stats_every - r->done % r->stats_every;
    if (r->done + to_frame < next)
        next = r->done + to_frame;
    if (r->done + to_stats < next)
        next = r->done + to_stats;
    if (r->ckpt_every > 0 && r->done + (r->ckpt_every - r->done % r->ckpt_every) < next)
        next = r->done + (r->ckpt_every - r->done % r->ckpt_every);
    long to_an = sd_analysis_run_next(r->an, r->done); /* LONG_MAX: none */
    if (to_an < next - r->done)
        next = r->done + to_an;
    return next - r->done;
}

/* The world's state as a checkpoint file at path: the run's writer (a
 * decomposed run's: every rank, io/run.h) or sd_checkpoint_write. */
static sd_status sd_run_write_state(sd_run *r, const char *path, sd_error *err)
{
    return r->write_ckpt ? r->write_ckpt(r->write_ckpt_ctx, path, err) : sd_checkpoint_write(r->w, path, err);
}

sd_status sd_run_checkpoint(sd_run *r, sd_error *err)
{
    if (!r)
        return sd_error_null(err, "sd_run_checkpoint", "run");
    if (!r->out)
        return SD_OK; /* a run without files writes no checkpoint either */
    char path[sizeof r->ckpt_last];
    snprintf(path, sizeof path, "%s/checkpoint-%06ld.h5", r->dir, sd_world_step_count(r->w));
    sd_status st = sd_run_write_state(r, path, err);
    if (st == SD_OK) {
        snprintf(r->ckpt_last, sizeof r->ckpt_last, "%s", path);
        r->ckpt_wall = sd_run_now();
    }
    return st;
}

const char *sd_run_last_checkpoint(const sd_run *r) { return r ? r->ckpt_last : NULL; }

/* A checkpoint falls due at multiples of checkpoint_every and when
 * checkpoint_minutes of wall time have passed since the last one. */
static int sd_run_checkpoint_due(const sd_run *r)
{
    return (r->ckpt_every > 0 && r->done % r->ckpt_every == 0) ||
           (r->ckpt_seconds > 0 && sd_run_now() - r->ckpt_wall >= r->ckpt_seconds);
}

/* After a step that failed on the state (a guard, NaN): the state as it
 * is, written for inspection (failed-<step>.h5, not a restart point), its
 * path added to the message. */
static void sd_run_failed_state(sd_run *r, sd_error *err)
{
    if (!r->out || !err || err->code != SD_ERR_PHYSICS)
        return;
    char path[sizeof r->ckpt_last];
    snprintf(path, sizeof path, "%s/failed-%06ld.h5", r->dir, sd_world_step_count(r->w));
    sd_error e2;
    memset(&e2, 0, sizeof e2);
    if (sd_run_write_state(r, path, &e2) == SD_OK) {
        size_t n = strlen(err->msg);
        snprintf(err->msg + n, sizeof err->msg - n, "; the state is in %s for inspection", path);
    }
}

sd_status sd_run_advance(sd_run *r, long steps, sd_error *err)
{
    sd_status st = SD_OK;
    if (!r)
        return sd_error_null(err, "sd_run_advance", "run");
    if (r->failed)
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "the run stopped at an earlier error");
    if (!r->started) {
        r->started = 1;
        double t0 = sd_run_now();
        /* a restart continues the CSV series and the frames: their rows and
         * frame at this step only when due, as the uninterrupted run wrote
         * them; a frame all the same where no frame was kept (another
         * directory), so the series shows where it starts */
        int row = !r->resumed || r->done % r->stats_every == 0;
        int frame = !r->resumed || r->done % r->every == 0 || sd_output_frame_count(r->out) == 0;
        if (r->out && ((frame && (st = sd_output_frame(r->out, r->w, err)) != SD_OK) ||
                       (row && (st = sd_output_stats(r->out, r->w, err)) != SD_OK))) {
            r->failed = 1;
            return st;
        }
        if (row)
            sd_run_outlet_row(r);
        if ((st = sd_analysis_run_rows(r->an, r->w, r->done, r->steps, err)) != SD_OK) {
            r->failed = 1;
            return st;
        }
        if (r->out) /* the output stage of the world's profile (sd_profile) */
            sd_world_profile_add(r->w, SD_PROFILE_OUTPUT, sd_run_now() - t0);
    }
    long left = r->steps - r->done;
    long target = r->done + (steps < 0 ? 0 : steps < left ? steps : left);
    while (r->done < target) {
        long next = r->done + sd_run_steps_to_output(r);
        if (next > target)
            next = target;
        double t0 = sd_run_now();
        size_t n_before = sd_world_particle_count(r->w);
        st = r->stepper ? r->stepper(r->stepper_ctx, next - r->done, err) : sd_world_step(r->w, next - r->done, err);
        if (st == SD_ERR_INTERRUPTED) {
            /* stopped between two steps before the next output (or inside
             * an insertion at this step): the run goes on from there, or
             * writes its checkpoint there (sd_run_checkpoint) */
            long at = sd_world_step_count(r->w);
            r->stepping += sd_run_now() - t0;
            r->psteps += (double)sd_world_particle_count(r->w) * (double)(at - r->done);
            r->done = at;
            return st;
        }
        if (st != SD_OK) {
            r->failed = 1;
            sd_run_failed_state(r, err);
            return st;
        }
        double t1 = sd_run_now();
        r->stepping += t1 - t0;
        /* the count changes when spheres are poured or leave (solver grid) */
        r->psteps += 0.5 * (double)(n_before + sd_world_particle_count(r->w)) * (double)(next - r->done);
        r->done = next;
        if (r->out && r->done % r->stats_every == 0 && (st = sd_output_stats(r->out, r->w, err)) != SD_OK)
            r->failed = 1;
        if (r->done % r->stats_every == 0)
            sd_run_outlet_row(r);
        if (!r->failed)
            sd_run_check_stop(r); /* before the frame: a run that stops here closes with one */
        if (r->out && !r->failed && (r->done % r->every == 0 || r->done == r->steps) &&
            (st = sd_output_frame(r->out, r->w, err)) != SD_OK)
            r->failed = 1;
        if (r->out && !r->failed && sd_run_checkpoint_due(r) && (st = sd_run_checkpoint(r, err)) != SD_OK)
            r->failed = 1;
        if (!r->failed && (st = sd_analysis_run_rows(r->an, r->w, r->done, r->steps, err)) != SD_OK)
            r->failed = 1;
        if (r->out)
            sd_world_profile_add(r->w, SD_PROFILE_OUTPUT, sd_run_now() - t1);
        if (r->failed)
            return st;
    }
    return SD_OK;
}

void sd_run_get_progress(const sd_run *r, sd_run_progress *out)
{
    if (!out)
        return;
    memset(out, 0, sizeof *out);
    if (!r)
        return;
    out->done = r->done;
    out->first = r->first;
    out->steps = r->steps;
    out->time = sd_world_time(r->w);
    out->wall_seconds = r->stepping;
    out->particle_steps_per_second = r->stepping > 0 ? r->psteps / r->stepping : 0;
    out->threads = sd_world_threads(r->w);
    out->stopped = r->stopped;
}

const char *sd_run_stop_note(const sd_run *r) { return r ? r->stop : NULL; }

void sd_run_set_stepper(sd_run *r, sd_run_stepper step, void *ctx)
{
    r->stepper = step;
    r->stepper_ctx = ctx;
}

void sd_run_set_checkpoint_writer(sd_run *r, sd_run_ckpt_writer write, void *ctx)
{
    r->write_ckpt = write;
    r->write_ckpt_ctx = ctx;
}

void sd_run_set_note(sd_run *r, const char *lines)
{
    sd_free(r->note);
    size_t n = strlen(lines);
    r->note = sd_malloc(n + 1);
    if (r->note)
        memcpy(r->note, lines, n + 1);
}

const char *sd_run_directory(const sd_run *r) { return !r ? NULL : r->out ? r->dir : ""; }

sd_status sd_run_close(sd_run *r, sd_error *err)
{
    if (!r)
        return SD_OK;
    sd_status st = SD_OK;
    if (r->outlet)
        fclose(r->outlet);
    sd_analysis_run_close(r->an);
    if (r->out) {
        sd_run_summary sum;
        memset(&sum, 0, sizeof sum);
        sum.steps = r->done - r->first;
        sum.first = r->first;
        sum.wall_seconds = r->stepping;
        sum.particle_steps_per_second = r->stepping > 0 ? r->psteps / r->stepping : 0;
        sum.threads = sd_world_threads(r->w);
        sum.peak_memory = sd_memory_peak();
        sum.peak_rss = sd_run_peak_rss();
        sum.stop = r->stop;
        sum.note = r->note;
        sd_error local;
        memset(&local, 0, sizeof local);
        st = sd_output_close(r->out, r->w, &sum, err ? err : &local);
    }
    sd_free(r->note);
    sd_free(r);
    return st;
}
