/* main.c — the shapedem program: run, check and help.
 *
 * The only place that prints and exits. Exit status: 0 success, 1 a run
 * that failed while stepping or writing, 2 bad input (command line or
 * scene), 130 interrupted. Bad input is reported as one line before any
 * output directory is created.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include <shapedem/process.h>
#include <shapedem/shapedem.h>

#include <shapedem/scene.h>

#include "cli/check_bounds.h"
#include "cli/check_report.h"
#include "cli/commands.h"
#include "cli/threads.h"
#include "core/duration.h"
#ifdef SHAPEDEM_CLI_MPI
#include "cli/mpi_run.h"
#endif

#define SD_STR(x) #x
#define SD_XSTR(x) SD_STR(x) /* a macro's value as a string literal */

volatile sig_atomic_t sd_cli_interrupted;
/* The world `run` steps: the first signal also asks it to stop
 * (sd_world_request_interrupt, one flag store), so that a long insertion
 * inside one step call stops within a particle, not at its end. */
static sd_world *volatile sd_cli_world;

/* The first SIGINT/SIGTERM asks the run to stop after the step in
 * progress (with a final checkpoint); a second one, for a run that does
 * not get there (a step that does not end), ends the process at once with
 * the signal's default action, as SIGKILL would: the files written so far
 * stay complete (each replaced atomically, CSV rows flushed whole). */
void sd_cli_on_signal(int sig)
{
    if (sd_cli_interrupted) {
        signal(sig, SIG_DFL);
        raise(sig);
        return;
    }
    sd_cli_interrupted = 1;
    sd_world_request_interrupt(sd_cli_world);
}

static size_t sd_peak_rss(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0)
        return 0;
    return (size_t)ru.ru_maxrss * 1024u; /* Linux reports KiB */
}

static void sd_usage(FILE *f)
{
    fprintf(f,
            "usage: shapedem run SCENE.yaml [-o DIR] [--threads N] [--steps N | --until-step S | --until-time T]\n"
            "                  [--restart CHECKPOINT.h5] [--backend auto|cpu|cuda] [--quiet] [--profile]\n"
            "                  [--bench NAME]\n"
            "       shapedem info CHECKPOINT.h5 [--csv]\n"
            "       shapedem check SCENE.yaml [--threads N] [--ranks N] [--steps N | --until-step S | --until-time T]\n"
            "       shapedem shape info KIND --size X[,Y,Z] [--rounding R] [--margin M] [--density RHO]\n"
            "       shapedem shape info SCENE.yaml\n"
            "       shapedem shape fit-fourier OUTLINE.csv [--order N] [--directions M] [--beta B]\n"
            "       shapedem render FRAME.vtu|frames.pvd -o PICTURE.png [--field F] [--view V] [--size WxH]\n"
            "                  [--movie]\n"
            "       shapedem help [scene [--markdown]]\n"
            "       shapedem --version\n"
            "\n"
            "  run     simulate the scene; writes frames.pvd (VTK), stats.csv and summary.txt\n"
            "          to DIR (default: output.directory of the scene, else out/<scene name>)\n"
            "  check   validate the scene and print what it would simulate\n"
            "  info    what a checkpoint holds (step, time, particles, datasets); --csv: its particles\n"
            "  shape fit-fourier  fit a convex Fourier-series support function ([Huang 2021]) to a\n"
            "          closed outline; prints coefficients, convexity, reduction, coverage\n"
            "  render  draw a frame's particles with their true shapes into a PNG, headless\n"
            "  help    this text; 'help scene' lists every scene key with unit and default\n"
            "\n"
            "  'shapedem COMMAND --help' prints the options of each command.\n");
}

/* The options of run and check, as `run --help` prints them. */
static void sd_usage_run_options(FILE *f, int run)
{
    fprintf(f,
            "  --threads N     OpenMP threads (default: simulation.threads, else OMP_NUM_THREADS, else\n"
            "                  the cores not busy with other processes at the start)\n"
            "  --steps N       run N steps instead of the scene's steps:; on a restart, N more steps\n"
            "                  from the checkpoint's step\n"
            "  --until-step S  run until step S, counted from the start of the run (on a restart too);\n"
            "                  refused when the checkpoint is past it\n"
            "  --until-time T  run until the simulated time T s (the first step at or after it;\n"
            "                  absolute as --until-step)\n");
    if (!run) {
        fprintf(f, "  --ranks N       how the MPI split would share the particles over N ranks\n"
                   "                  (the grid of boxes, each rank's box and particles)\n");
        return;
    }
    fprintf(f,
            "  -o DIR          output directory (default: output.directory of the scene, else\n"
            "                  out/<scene name>)\n"
            "  --restart F     continue the run of checkpoint F (written by this scene) bit for bit;\n"
            "                  without --steps or --until-*, up to the scene's steps: (docs/checkpoints.md)\n"
            "  --backend B     where the step runs: auto (a GPU when usable, else the CPU), cpu or\n"
            "                  cuda (default: simulation.backend, else auto)\n"
            "  --quiet         no progress line and no summary on the terminal\n"
            "  --bench NAME    write no files; print one JSON line of timings for case NAME\n"
            "  --profile       print the wall time of each stage of the step at the end\n"
            "\n"
            "  SIGINT/SIGTERM (Ctrl-C) stop the run after the step in progress (or before the next particle\n"
            "  of an insertion), write a final checkpoint and print the command that continues it; exit\n"
            "  status 130.\n");
}

/* `shapedem COMMAND --help`: that command's usage, on stdout. */
static void sd_usage_command(FILE *f, const char *cmd)
{
    if (!strcmp(cmd, "run")) {
        fprintf(f, "usage: shapedem run SCENE.yaml [-o DIR] [--threads N] [--steps N | --until-step S | "
                   "--until-time T]\n"
                   "                    [--restart CHECKPOINT.h5] [--backend auto|cpu|cuda] [--quiet] [--profile]\n"
                   "                    [--bench NAME]\n"
                   "\n"
                   "  simulates the scene; writes frames.pvd (VTK), stats.csv and summary.txt to DIR\n"
                   "\n");
        sd_usage_run_options(f, 1);
    } else if (!strcmp(cmd, "check")) {
        fprintf(f, "usage: shapedem check SCENE.yaml [--threads N] [--ranks N] [--steps N | --until-step S | "
                   "--until-time T]\n"
                   "\n"
                   "  validates the scene and prints what it would simulate: particles, time step, output,\n"
                   "  memory, and a run time from a short timed trial; writes nothing\n"
                   "\n");
        sd_usage_run_options(f, 0);
    } else if (!strcmp(cmd, "help")) {
        fprintf(f, "usage: shapedem help [scene [--markdown]]\n"
                   "\n"
                   "  help            the commands\n"
                   "  help scene      every scene key with its unit and default (--markdown: as a table)\n");
    } else {
        sd_usage(f);
    }
}

int sd_cli_fail_input(const sd_error *err)
{
    char buf[1024];
    sd_error_format(err, buf, sizeof buf);
    fprintf(stderr, "shapedem: %s\n", buf);
    return 2;
}

static int sd_usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "shapedem: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, " (see 'shapedem help')\n");
    return 2;
}

typedef struct sd_cli {
    const char *command;
    const char *scene;
    const char *outdir;
    const char *bench;
    const char *restart;  /* --restart: the checkpoint to continue */
    long threads;
    long steps;           /* --steps: that many steps (more, on a restart); -1 not given */
    long until_step;      /* --until-step: the absolute end step; -1 not given */
    double until_time;    /* --until-time: the absolute end time, s; < 0 not given */
    int help;             /* --help or -h: the command's usage */
    int argc;             /* the command line, for the interrupt's hint (sd_cli_continue) */
    char **argv;
    long ranks;           /* check --ranks: the MPI split to report, 0 none */
    int backend;          /* --backend: an sd_backend_kind, SD_BACKEND_COUNT when not given */
    int quiet;
    int markdown;
    int profile;
    int restart_later;    /* shapedem-mpi: --restart is applied after the split (cli/mpi_run.c) */
} sd_cli;

static int sd_parse_long(const char *s, long lo, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < lo)
        return -1;
    *out = v;
    return 0;
}

static int sd_parse_args(int argc, char **argv, sd_cli *c)
{
    memset(c, 0, sizeof *c);
    c->threads = -1;
    c->steps = -1;
    c->until_step = -1;
    c->until_time = -1;
    c->backend = SD_BACKEND_COUNT;
    c->argc = argc;
    c->argv = argv;
    if (argc < 2)
        return sd_usage_error("%s", "no command given");
    c->command = argv[1];
    int ends = 0; /* how many of --steps, --until-step, --until-time */
    for (int k = 2; k < argc; ++k) {
        const char *a = argv[k];
        const char *next = k + 1 < argc ? argv[k + 1] : NULL;
        if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (!next)
                return sd_usage_error("%s needs a directory", a);
            c->outdir = argv[++k];
        } else if (!strcmp(a, "--threads")) {
            if (!next || sd_parse_long(next, 1, &c->threads) || c->threads > SD_SCENE_MAX_THREADS)
                return sd_usage_error("--threads needs a whole number from 1 to " SD_XSTR(SD_SCENE_MAX_THREADS)
                                      ", got '%s'",
                                      next ? next : "");
            ++k;
        } else if (!strcmp(a, "--ranks")) {
            if (!next || sd_parse_long(next, 1, &c->ranks) || c->ranks > 65536)
                return sd_usage_error("--ranks needs a whole number from 1 to 65536, got '%s'", next ? next : "");
            ++k;
        } else if (!strcmp(a, "--backend")) {
            if (!next || (c->backend = sd_backend_kind_from_name(next)) == SD_BACKEND_COUNT)
                return sd_usage_error("--backend needs auto, cpu or cuda, got '%s'", next ? next : "");
            ++k;
        } else if (!strcmp(a, "--steps")) {
            if (!next || sd_parse_long(next, 0, &c->steps))
                return sd_usage_error("--steps needs a whole number >= 0, got '%s'", next ? next : "");
            ++k;
            ++ends;
        } else if (!strcmp(a, "--until-step")) {
            if (!next || sd_parse_long(next, 0, &c->until_step))
                return sd_usage_error("--until-step needs a whole number >= 0 (a step number), got '%s'",
                                      next ? next : "");
            ++k;
            ++ends;
        } else if (!strcmp(a, "--until-time")) {
            char *end;
            double t = next ? strtod(next, &end) : -1;
            if (!next || end == next || *end || !(t >= 0) || !isfinite(t))
                return sd_usage_error("--until-time needs a time in seconds >= 0 (the simulated time to run to), "
                                      "got '%s'",
                                      next ? next : "");
            c->until_time = t;
            ++k;
            ++ends;
        } else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            c->help = 1;
        } else if (!strcmp(a, "--bench")) {
            if (!next)
                return sd_usage_error("%s needs a case name", a);
            c->bench = argv[++k];
        } else if (!strcmp(a, "--restart")) {
            if (!next)
                return sd_usage_error("%s needs a checkpoint file", a);
            c->restart = argv[++k];
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            c->quiet = 1;
        } else if (!strcmp(a, "--profile")) {
            c->profile = 1;
        } else if (!strcmp(a, "--markdown")) {
            c->markdown = 1;
        } else if (a[0] == '-' && a[1]) {
            return sd_usage_error("unknown option '%s'", a);
        } else if (!c->scene) {
            c->scene = a;
        } else {
            return sd_usage_error("unexpected argument '%s'", a);
        }
    }
    if (ends > 1 && !c->help)
        return sd_usage_error("%s", "give one of --steps, --until-step and --until-time: each says where the run ends");
    return 0;
}

/* Loads, applies the command-line overrides (and the CUDA device slot
 * under mpirun: cli/mpi_run.c; -1 none), builds; on bad input fills msg
 * with the one line to print after "shapedem: " and returns 2. */
static int sd_load_world_msg(const sd_cli *c, int device, sd_scene **scene, sd_world **world, char *msg,
                             size_t size)
{
    sd_error err;
    memset(&err, 0, sizeof err);
    *scene = NULL;
    *world = NULL;
    if (!c->scene) {
        snprintf(msg, size, "%s needs a scene file (see 'shapedem help')", c->command);
        return 2;
    }
    int failed = sd_scene_load(c->scene, scene, &err) != SD_OK;
    if (!failed) {
        sd_scene_info si;
        sd_scene_get_info(*scene, &si);
        if (c->threads > 0)
            sd_scene_set_threads(*scene, (int)c->threads);
        else if (si.threads == 0 && sd_threads_default() > 0) /* the free cores (cli/threads.c) */
            sd_scene_set_threads(*scene, sd_threads_default());
        else
            sd_threads_scene(si.threads); /* more than the free cores: may start the program again */
        sd_scene_set_backend(*scene, (sd_backend_kind)c->backend); /* SD_BACKEND_COUNT: the scene's */
        sd_scene_set_device(*scene, device);
        failed = sd_scene_build(*scene, world, &err) != SD_OK;
    }
    /* --restart: the checkpoint's state replaces the scene's start (refused
     * with the reason: another scene, version, a damaged file) */
    if (!failed && c->restart && !c->restart_later)
        failed = sd_checkpoint_restore(*world, c->restart, &err) != SD_OK;
    if (failed) {
        sd_error_format(&err, msg, size);
        sd_world_destroy(*world);
        sd_scene_free(*scene);
        *world = NULL;
        *scene = NULL;
        return 2;
    }
    return 0;
}

static int sd_load_world(const sd_cli *c, sd_scene **scene, sd_world **world)
{
    char msg[1200];
    int rc = sd_load_world_msg(c, -1, scene, world, msg, sizeof msg);
    if (rc)
        fprintf(stderr, "shapedem: %s\n", msg);
    return rc;
}

/* Where the run ends, as the scene's steps (the absolute end step the run
 * reads): --steps N is N steps from where the world is (a restart: N more
 * after its checkpoint's step), --until-step and --until-time are
 * absolute, and without them the scene's steps: stands. An end before the
 * world's step is refused (msg, 2) before any file is touched: running to
 * it would cut the CSV series and frames of the later steps (issue 31). */
static int sd_cli_end_step(const sd_cli *c, sd_scene *scene, const sd_world *w, char *msg, size_t size)
{
    long now = sd_world_step_count(w), end;
    double t = sd_world_time(w), dt = sd_world_dt(w);
    char asked[128];
    if (c->steps >= 0) {
        if (c->steps > LONG_MAX - now) {
            snprintf(msg, size, "--steps %ld: from step %ld that passes the largest step number", c->steps, now);
            return 2;
        }
        end = now + c->steps;
        snprintf(asked, sizeof asked, "--steps %ld", c->steps);
    } else if (c->until_step >= 0) {
        end = c->until_step;
        snprintf(asked, sizeof asked, "--until-step %ld", end);
    } else if (c->until_time >= 0) {
        /* the first step at or after the time, with a rounding allowance so
         * that a time printed from a step's gives that step */
        double n = (c->until_time - t) / dt;
        n = n > -1e-9 ? ceil(n - 1e-9) : floor(n);
        if (!(n < 9e18 - (double)now)) {
            snprintf(msg, size, "--until-time %.10g: at dt = %.4g s that is past the largest step number",
                     c->until_time, dt);
            return 2;
        }
        end = now + (long)n;
        snprintf(asked, sizeof asked, "--until-time %.10g s", c->until_time);
    } else {
        end = sd_scene_steps(scene);
        snprintf(asked, sizeof asked, "the scene's steps: %ld", end);
    }
    if (end < now) {
        snprintf(msg, size, "%s: %s ends the run at step %ld, before the checkpoint's step %ld (t = %.6g s) where it "
                 "starts; nothing was run or written. --steps N runs N more steps from there; --until-step S and "
                 "--until-time T end at step S or time T",
                 c->restart ? c->restart : c->scene, asked, end, now, t);
        return 2;
    }
    sd_scene_set_steps(scene, end);
    return 0;
}

/* A word of a shell command, quoted where the shell would split or expand it. */
static void sd_cli_shell_word(char *buf, size_t size, const char *word)
{
    size_t n = strlen(buf);
    int plain = word[0] != 0;
    for (const char *p = word; *p && plain; ++p)
        plain = strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=/.,:@%", *p) != NULL;
    if (plain) {
        snprintf(buf + n, size > n ? size - n : 0, " %s", word);
        return;
    }
    if (n + 3 < size) {
        buf[n++] = ' ';
        buf[n++] = '\'';
    }
    for (const char *p = word; *p && n + 6 < size; ++p) {
        if (*p == '\'') { /* 'it'\''s' */
            memcpy(buf + n, "'\\''", 4);
            n += 4;
        } else
            buf[n++] = *p;
    }
    if (n + 1 < size)
        buf[n++] = '\'';
    buf[n < size ? n : size - 1] = 0;
}

/* The command that continues an interrupted run from checkpoint ckpt: the
 * command line as given, with --restart ckpt, -o the directory written
 * (given or not, so the frames and rows go on in it) and the end as an
 * absolute --until-step (a --steps N given would count N more from the
 * checkpoint), every other option kept. Followed literally it finishes
 * the run the user started. */
static void sd_cli_continue(const sd_cli *c, const char *ckpt, const char *dir, long end, char *buf, size_t size)
{
    buf[0] = 0;
    snprintf(buf, size, "%s", c->argv[0]);
    for (int k = 1; k < c->argc; ++k) {
        const char *a = c->argv[k];
        if (!strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "--restart") || !strcmp(a, "--steps") ||
            !strcmp(a, "--until-step") || !strcmp(a, "--until-time")) {
            ++k; /* replaced below */
            continue;
        }
        sd_cli_shell_word(buf, size, a);
    }
    char num[32];
    sd_cli_shell_word(buf, size, "-o");
    sd_cli_shell_word(buf, size, dir);
    sd_cli_shell_word(buf, size, "--until-step");
    snprintf(num, sizeof num, "%ld", end);
    sd_cli_shell_word(buf, size, num);
    sd_cli_shell_word(buf, size, "--restart");
    sd_cli_shell_word(buf, size, ckpt);
}

/* The per-stage table of `run --profile` (sd_profile): seconds, share of
 * the stages' sum, calls, and the mean per call. */
static void sd_print_profile(const sd_world *w)
{
    sd_profile p;
    sd_world_profile(w, &p);
    double sum = 0;
    for (int k = 0; k < SD_PROFILE_STAGE_COUNT; ++k)
        sum += p.seconds[k];
    printf("profile: wall time per stage of the step\n");
    printf("  %-12s %12s %7s %10s %12s\n", "stage", "seconds", "share", "calls", "us/call");
    for (int k = 0; k < SD_PROFILE_STAGE_COUNT; ++k) {
        if (p.calls[k] == 0 && p.seconds[k] == 0)
            continue;
        printf("  %-12s %12.6f %6.1f%% %10lld %12.3f\n", sd_profile_stage_name(k), p.seconds[k],
               sum > 0 ? 100.0 * p.seconds[k] / sum : 0.0, p.calls[k],
               p.calls[k] > 0 ? 1e6 * p.seconds[k] / (double)p.calls[k] : 0.0);
    }
    printf("  %-12s %12.6f\n", "total", sum);
}

/* The scene's run through the public run API (shapedem/scene.h), with a
 * progress line on a terminal and a stop at an interrupt: it advances one
 * output interval (at most 200 steps on a terminal) at a time. */
static int sd_cmd_run(const sd_cli *c)
{
    sd_scene *scene = NULL;
    sd_world *w = NULL;
#ifdef SHAPEDEM_CLI_MPI
    /* under mpirun (cli/mpi_run.c): every rank builds the scene and keeps
     * its part; rank 0 goes on below with the whole world gathered (w), the
     * others follow its steps and return here at the end */
    sd_cli_mpi *mp = NULL;
    sd_cli cm = *c;
    cm.restart_later = 1; /* the checkpoint goes into the split world (cli/mpi_run.c) */
    int rc = sd_cli_mpi_begin(&cm, (sd_cli_load_fn)sd_load_world_msg, c->restart, &scene, &w, &mp);
    if (rc >= 0)
        return rc;
#else
    int rc = sd_load_world(c, &scene, &w);
    if (rc)
        return rc;
#endif
    sd_scene_info info;
    sd_scene_get_info(scene, &info);
    for (size_t k = 0; k < info.shape_count; ++k)
        if (sd_scene_shape_warning(scene, k)[0]) /* a mesh taken as its hull (nonconvex: hull) */
            fprintf(stderr, "shapedem: warning: shape %s: %s\n", sd_scene_shape_name(scene, k),
                    sd_scene_shape_warning(scene, k));
    for (size_t k = 0; k < info.wall_count; ++k)
        if (sd_scene_wall_warning(scene, k)[0]) /* a mesh wall's file repaired */
            fprintf(stderr, "shapedem: warning: wall %s: %s\n", sd_scene_wall_name(scene, k),
                    sd_scene_wall_warning(scene, k));
    for (size_t k = 0; sd_scene_outlet_warning(scene, k); ++k)
        if (sd_scene_outlet_warning(scene, k)[0]) /* outlets: one no particle can reach */
            fprintf(stderr, "shapedem: warning: %s\n", sd_scene_outlet_warning(scene, k));
    sd_error err;
    memset(&err, 0, sizeof err);
    char dir[1040];
    if (c->outdir)
        snprintf(dir, sizeof dir, "%s", c->outdir);
    else
        sd_scene_output_directory(scene, dir, sizeof dir);
    sd_run *run = NULL;
    char msg[1200];
    rc = sd_cli_end_step(c, scene, w, msg, sizeof msg); /* --steps, --until-*: before any file */
    if (!rc && sd_run_open(scene, w, c->bench ? NULL : dir, &run, &err) != SD_OK) {
        sd_error_format(&err, msg, sizeof msg);
        rc = 2;
    }
    if (rc) {
#ifdef SHAPEDEM_CLI_MPI
        sd_cli_mpi_end(mp, NULL, NULL, 0);
        sd_cli_mpi_free(mp);
#endif
        sd_world_destroy(w);
        sd_scene_free(scene);
        fprintf(stderr, "shapedem: %s\n", msg);
        return 2;
    }
#ifdef SHAPEDEM_CLI_MPI
    sd_cli_mpi_run(mp, run);
#endif
    sd_cli_world = w;
    signal(SIGINT, sd_cli_on_signal);
    signal(SIGTERM, sd_cli_on_signal);

    int tty = !c->quiet && !c->bench && isatty(STDERR_FILENO);
    char why[256]; /* how many threads and why (cli/threads.c), above the progress line */
    sd_threads_describe(c->threads, info.threads, sd_world_threads(w), why, sizeof why);
    if (tty)
        fprintf(stderr, "shapedem: running on %s\n", why);
    size_t n = sd_world_particle_count(w);
    double last_print = 0;
    sd_run_progress pr;
    sd_status ast = sd_run_advance(run, 0, &err); /* the frame and the stats row of step 0 */
    int failed = ast != SD_OK;
    sd_run_get_progress(run, &pr);
    /* steps per advance: up to the next output, but no longer than about
     * 0.1-0.4 s of stepping at the rate so far, so that an interrupt is acted
     * on within a fraction of a second (chunks change no bit: io/run.c) */
    long chunk_max = 1;
    while (!failed && pr.done < pr.steps && !sd_cli_interrupted) {
        long chunk = sd_run_steps_to_output(run);
        if (chunk > chunk_max)
            chunk = chunk_max;
        double wall0 = pr.wall_seconds;
        long done0 = pr.done;
        ast = sd_run_advance(run, chunk, &err);
        failed = ast != SD_OK && ast != SD_ERR_INTERRUPTED; /* interrupted: stopped between steps */
        sd_run_get_progress(run, &pr);
        double took = pr.wall_seconds - wall0;
        if (pr.done > done0 && took < 0.1 && chunk == chunk_max && chunk_max < LONG_MAX / 2)
            chunk_max *= 2;
        else if (took > 0.4 && chunk_max > 1)
            chunk_max /= 2;
        if (tty && (pr.wall_seconds - last_print > 0.5 || pr.done == pr.steps)) {
            last_print = pr.wall_seconds;
            double rate = pr.particle_steps_per_second;
            char left[32];
            double left_ps = (double)sd_world_particle_count(w) * (double)(pr.steps - pr.done);
            long total = pr.steps - pr.first, ran = pr.done - pr.first;
            sd_duration_format(rate > 0 ? left_ps / rate : -1, left, sizeof left);
            /* a restart: the world's step and end step, and the steps this run made of its own */
            if (pr.first > 0)
                fprintf(stderr, "\rstep %ld/%ld (%ld of %ld since the restart)  t = %.6g s  %5.1f%%  %.3g "
                        "particle-steps/s  %s left   ", pr.done, pr.steps, ran, total, pr.time,
                        total ? 100.0 * (double)ran / (double)total : 100.0, rate, left);
            else
                fprintf(stderr, "\rstep %ld/%ld  t = %.6g s  %5.1f%%  %.3g particle-steps/s  %s left   ", pr.done,
                        pr.steps, pr.time, total ? 100.0 * (double)ran / (double)total : 100.0, rate, left);
            fflush(stderr);
        }
    }
    if (tty)
        fputc('\n', stderr);
    /* SIGINT/SIGTERM: a final checkpoint where the run stopped (the loop
     * stops between chunks, so the world is between steps) */
    char ckpt[1100] = "", again[4096] = "";
    sd_status ckpt_st = SD_OK;
    if (sd_cli_interrupted && !failed && !c->bench) {
        sd_error cerr0;
        memset(&cerr0, 0, sizeof cerr0);
        ckpt_st = sd_run_checkpoint(run, &cerr0);
        if (ckpt_st != SD_OK) {
            char buf[1024];
            sd_error_format(&cerr0, buf, sizeof buf);
            fprintf(stderr, "shapedem: the final checkpoint failed: %s\n", buf);
        } else {
            snprintf(ckpt, sizeof ckpt, "%s", sd_run_last_checkpoint(run));
            char *at = again;
#ifdef SHAPEDEM_CLI_MPI
            if (sd_cli_mpi_size(mp) > 1) /* the same ranks again (any count continues the bits) */
                at += snprintf(again, sizeof again, "mpirun -np %d ", sd_cli_mpi_size(mp));
#endif
            sd_cli_continue(c, ckpt, dir, pr.steps, at, sizeof again - (size_t)(at - again));
        }
    }
    size_t peak_memory = sd_memory_peak(), peak_rss = sd_peak_rss();
    if (failed) {
        char buf[1024];
        sd_error_format(&err, buf, sizeof buf);
        fprintf(stderr, "shapedem: run stopped at step %ld: %s\n", sd_world_step_count(w), buf);
    }
    sd_error cerr;
    memset(&cerr, 0, sizeof cerr);
    char stop_note[256]; /* the run is freed by sd_run_close */
    snprintf(stop_note, sizeof stop_note, "%s", sd_run_stop_note(run));
    char ranks_note[4096] = ""; /* under mpirun: the ranks' lines of summary.txt */
#ifdef SHAPEDEM_CLI_MPI
    sd_cli_mpi_end(mp, run, ranks_note, sizeof ranks_note);
#endif
    if (sd_run_close(run, &cerr) != SD_OK && !failed) {
        char buf[1024];
        sd_error_format(&cerr, buf, sizeof buf);
        fprintf(stderr, "shapedem: %s\n", buf);
        failed = 1;
    }
    if (c->bench) {
        printf("{\"case\":\"%s\",\"particles\":%zu,\"steps\":%ld,\"threads\":%d,\"wall_s\":%.6f,\"psps\":%.6g,"
               "\"peak_rss_mib\":%.2f,\"peak_alloc_mib\":%.2f}\n",
               c->bench, n, pr.done - pr.first, pr.threads, pr.wall_seconds, pr.particle_steps_per_second,
               (double)peak_rss / 1048576.0, (double)peak_memory / 1048576.0);
    } else if (!c->quiet) {
        sd_stats st;
        sd_world_stats(w, &st);
        /* the count at the end, as summary.txt (a pour starts from none) */
        printf("shapedem: %zu particles, %ld steps (t = %.6g s) in %.2f s: %.3g particle-steps/s on %d thread%s\n",
               sd_world_particle_count(w), pr.done - pr.first, sd_world_time(w), pr.wall_seconds,
               pr.particle_steps_per_second, pr.threads, pr.threads == 1 ? "" : "s");
        if (pr.first > 0) /* the steps above are this run's, from the checkpoint's */
            printf("          restarted at step %ld, now at step %ld\n", pr.first, pr.done);
        printf("          kinetic energy %.6g J, %ld contacts, max overlap %.3g %% of radius; output in %s\n",
               st.kinetic_translational + st.kinetic_rotational, st.contacts, 100 * st.max_overlap_ratio, dir);
        printf("          backend %s (%s)\n", sd_world_backend(w), sd_world_backend_note(w));
        if (stop_note[0]) /* simulation.stop_when, as summary.txt */
            printf("          stop_when %s\n", stop_note);
        if (ranks_note[0]) /* mpirun: the split, as summary.txt */
            printf("%s", ranks_note);
    }
    /* insertions that fell short: one line each (also in summary.txt) */
    for (size_t k = 0; k < sd_world_insertion_count(w); ++k) {
        sd_insert_info ii;
        if (sd_world_get_insertion(w, k, &ii) == SD_OK && ii.inserted < ii.asked)
            fprintf(stderr, "shapedem: insert %s: inserted %zu of the %zu asked for: %s\n", ii.name, ii.inserted,
                    ii.asked, ii.why);
    }
#ifdef SHAPEDEM_CLI_MPI
    if (c->profile) /* rank 0's part: the stages of its own steps */
        sd_print_profile(sd_cli_mpi_part(mp));
#else
    if (c->profile)
        sd_print_profile(w);
#endif
#ifdef SHAPEDEM_CLI_MPI
    sd_cli_mpi_free(mp); /* rank 0's part (w is the gathered world) */
#endif
    sd_cli_world = NULL;
    sd_world_destroy(w);
    sd_scene_free(scene);
    if (sd_cli_interrupted) {
        if (ckpt_st == SD_OK && ckpt[0])
            fprintf(stderr, "shapedem: interrupted at step %ld; the files written so far are complete; "
                    "continue with: %s\n", pr.done, again);
        else
            fprintf(stderr, "shapedem: interrupted at step %ld; the files written so far are complete\n", pr.done);
        return 130;
    }
    return failed ? 1 : 0;
}

static int sd_cmd_check(const sd_cli *c)
{
    size_t mem0 = sd_memory_in_use();
    sd_scene *scene = NULL;
    sd_world *w = NULL;
    int rc = sd_load_world(c, &scene, &w);
    char msg[1200];
    if (!rc && (rc = sd_cli_end_step(c, scene, w, msg, sizeof msg)) != 0) { /* --steps, --until-* */
        fprintf(stderr, "shapedem: %s\n", msg);
        sd_world_destroy(w);
        sd_scene_free(scene);
    }
    if (rc)
        return rc;
    size_t mem = sd_memory_in_use() - mem0;
    sd_scene_info info;
    sd_scene_get_info(scene, &info);
    size_t n = sd_world_particle_count(w);
    /* the insertions' particles, absent at the start: the estimates that
     * read particles read a probe of them (cli/check_report.c) */
    sd_check_insert ins;
    sd_check_insertions(scene, &ins);
    const sd_world *est = ins.probe ? ins.probe : w;
    double tc = 0, rec = sd_world_recommended_dt(est, &tc);
    double dt = sd_world_dt(w);
    printf("scene        %s\n", c->scene);
    sd_check_counts cnt; /* the pour's spheres too (cli/check_report.c) */
    sd_check_count(scene, w, &cnt);
    size_t total = n + cnt.poured + ins.count;
    size_t nshape = cnt.bodies;
    if (ins.count) {
        cnt.rmin = n ? fmin(cnt.rmin, ins.rmin) : ins.rmin;
        cnt.rmax = fmax(cnt.rmax, ins.rmax);
    }
    char shapes[256]; /* as the user wrote them: size classes are one shape */
    sd_check_shapes_text(scene, w, shapes, sizeof shapes);
    printf("particles    %zu: %zu spheres, %zu bodies of %s", n, n - nshape, nshape, shapes);
    if (cnt.poured)
        printf(", and %zu spheres the pour inserts: %zu in all", cnt.poured, total);
    if (ins.count)
        printf(", and %zu particles the insertions add: %zu in all", ins.count, total);
    if (total)
        printf("; radius (bounding radius for shapes) %.4g .. %.4g m", cnt.rmin, cnt.rmax);
    if (ins.count && ins.probe)
        printf("\ninsertions   the time step, contact and output estimates include them: a probe of %zu particles "
               "(each size class of each entry at the bottom and top of its region, at its velocity)",
               ins.probes);
    else if (ins.why[0])
        printf("\ninsertions   not in the estimates (the probe failed: %s)", ins.why);
    printf("\nsolver       %s", info.solver == SD_SOLVER_GRID ? "grid (dense grid stencil, [Naderi 2024])"
                                                              : "cells (cell binning + pair lists)");
    printf("\nmaterials    %zu:", info.material_count);
    for (size_t k = 0; k < info.material_count; ++k)
        printf(" %s", sd_scene_material_name(scene, k));
    printf("\ncontact law  %s (default)\n", sd_contact_law_name(info.law));
    printf("walls        %zu\n", sd_world_wall_count(w));
    /* each mesh's facets, box and size against the particles' (inserted ones included) */
    int mesh_warnings = sd_check_print_meshes(stdout, w, cnt.rmin, cnt.rmax);
    sd_check_print_grid(stdout, scene); /* solver grid: pouring and outlet (docs/grid-solver.md) */
    printf("steps        %ld x dt %.4g s = %.6g s simulated\n", info.steps, dt, (double)info.steps * dt);
    sd_check_print_stop(stdout, scene);
    printf("contact      shortest estimated contact duration %.4g s (%.1f steps)\n", tc, tc / dt);
    printf("time step    %.4g s recommended; stability limit %.4g s\n", rec, tc / 5);
    char why[256];
    sd_threads_describe(c->threads, info.threads, sd_world_threads(w), why, sizeof why);
    printf("threads      %s\n", why);
    if (c->ranks > 0) /* the MPI split, the grid of boxes by particle count (mpi/mpi.h) */
        sd_check_print_ranks(stdout, scene, w, c->ranks);
    printf("backend      %s (%s)\n", sd_world_backend(w), sd_world_backend_note(w));
    const char *unit2d = info.dimension == 2 ? " per 1 m of thickness" : "";
    printf("mass         %.6g kg%s", cnt.mass_now + cnt.mass_poured + ins.mass, unit2d);
    if (cnt.poured)
        printf(": %.6g kg at the start and %.6g kg poured", cnt.mass_now, cnt.mass_poured);
    if (ins.count)
        printf(": %.6g kg at the start and about %.6g kg inserted", cnt.mass_now, ins.mass);
    printf("\n");
    double memory = (double)mem + (cnt.poured ? sd_check_pour_bytes(cnt.poured) : 0.0);
    if (!ins.count) /* with insertions: after the trial, which inserts (below) */
        printf("memory       about %.1f MiB (%.0f bytes per particle) once the pair lists are built%s\n",
               memory / 1048576.0, total ? memory / (double)total : 0.0,
               cnt.poured ? ", all poured spheres in" : "");
    /* output: frames at step 0, every `every` steps and at the end; stats
     * rows at step 0 and every stats_every steps (io/run.c) */
    long steps = info.steps, every = info.frame_every, stats_every = info.stats_every;
    long frames = steps / every + (steps % every != 0), rows = steps / stats_every;
    frames += frames < LONG_MAX; /* and step 0's; steps: up to LONG_MAX is accepted */
    rows += rows < LONG_MAX;
    sd_check_print_output(stdout, scene, est, total, frames, rows, (double)steps * dt, cnt.poured);
    int warnings = mesh_warnings + sd_check_print_analysis_size(stdout, scene, steps);
    warnings += sd_check_print_regions(stdout, scene, w); /* insertion regions across the walls */
    if (dt > rec) {
        printf("warning      dt = %.4g s is above the recommended %.4g s: contacts are resolved in %.1f steps\n", dt,
               rec, tc / dt);
        warnings++;
    }
    warnings += sd_check_print_dt(stdout, est); /* what set the step; the volume law's face contacts */
    warnings += sd_check_units(stdout, scene, &cnt, tc, dt);
    for (size_t k = 0; k < info.shape_count; ++k)
        if (sd_scene_shape_warning(scene, k)[0]) { /* a mesh taken as its hull (nonconvex: hull) */
            printf("warning      shape %s: %s\n", sd_scene_shape_name(scene, k), sd_scene_shape_warning(scene, k));
            warnings++;
        }
    for (size_t k = 0; k < info.wall_count; ++k)
        if (sd_scene_wall_warning(scene, k)[0]) { /* a mesh wall's file repaired */
            printf("warning      wall %s: %s\n", sd_scene_wall_name(scene, k), sd_scene_wall_warning(scene, k));
            warnings++;
        }
    for (size_t k = 0; sd_scene_outlet_warning(scene, k); ++k)
        if (sd_scene_outlet_warning(scene, k)[0]) { /* outlets: one no particle can reach */
            printf("warning      %s\n", sd_scene_outlet_warning(scene, k));
            warnings++;
        }
    /* last: the trial steps the world */
    sd_world_destroy(ins.probe);
    size_t mem_trial = sd_memory_in_use();
    sd_check_trial tr;
    sd_check_time(scene, w, total, steps, &tr);
    if (ins.count) {
        /* the trial's first steps insert (all at once, or the first of a
         * rate): the memory they added, per particle present, scaled to all */
        size_t now = sd_world_particle_count(w), used = sd_memory_in_use();
        double grown = used > mem_trial ? (double)(used - mem_trial) : 0.0;
        if (now > n)
            memory += grown / (double)(now - n) * (double)ins.count;
        printf("memory       about %.1f MiB (%.0f bytes per particle) once the pair lists are built, every inserted "
               "particle in (%s)\n",
               memory / 1048576.0, total ? memory / (double)total : 0.0,
               now > n ? "scaled from the trial's" : "the trial inserted none: the start's only");
    }
    if (tr.ok && tr.steps > 0)
        warnings += sd_check_print_time(stdout, w, &tr, total, steps, cnt.poured);
    if (!tr.ok) {
        printf("run time     unknown: %s\n", tr.msg);
        printf("check: the scene loads, but its run fails in the first steps\n");
        sd_world_destroy(w);
        sd_scene_free(scene);
        return 1;
    }
    printf("%s\n", warnings ? "check: ok, with warnings" : "check: ok");
    sd_world_destroy(w);
    sd_scene_free(scene);
    return 0;
}

#ifndef SHAPEDEM_CLI_MPI
/* `shapedem run` started by mpirun (or another MPI launcher: its
 * environment says so): this program has no MPI in it, so that the serial
 * build never needs libmpi to load; it hands the run to shapedem-mpi, the
 * same commands with MPI (cli/mpi_run.c), installed beside it when built
 * with SHAPEDEM_MPI. Returns -1 when not started by a launcher (and for a
 * launcher's single process without shapedem-mpi: a serial run). */
static int sd_mpi_handoff(char **argv)
{
    const char *sz = getenv("OMPI_COMM_WORLD_SIZE"), *rk = getenv("OMPI_COMM_WORLD_RANK");
    if (!sz) { /* MPICH's and Slurm's PMI */
        sz = getenv("PMI_SIZE");
        rk = getenv("PMI_RANK");
    }
    if (!sz)
        return -1;
    long size = strtol(sz, NULL, 10), rank = rk ? strtol(rk, NULL, 10) : 0;
#ifdef SHAPEDEM_HAVE_MPI
    (void)size; /* one process too: the decomposed run's bits are those of any rank count */
    char path[4096];
    ssize_t n = readlink("/proc/self/exe", path, sizeof path - 32);
    if (n > 0) {
        path[n] = 0;
        char *slash = strrchr(path, '/');
        snprintf(slash ? slash + 1 : path, 32, "shapedem-mpi");
        argv[0] = path;
        execv(path, argv);
    }
    if (rank == 0)
        fprintf(stderr, "shapedem: started by an MPI launcher, but cannot start %s: %s (it is built and installed "
                "beside shapedem with SHAPEDEM_MPI; docs/mpi.md)\n", n > 0 ? path : "shapedem-mpi",
                strerror(errno));
    return 2;
#else
    (void)argv;
    if (size <= 1)
        return -1;
    if (rank == 0)
        fprintf(stderr, "shapedem: started by an MPI launcher with %ld processes, but this shapedem was built "
                "without MPI, so each would run the whole scene alone: build with -DSHAPEDEM_MPI=ON "
                "(docs/mpi.md), or run one process\n", size);
    return 2;
#endif
}
#endif

int main(int argc, char **argv)
{
#ifndef SHAPEDEM_CLI_MPI
    if (argc >= 2 && !strcmp(argv[1], "run")) {
        int rc = sd_mpi_handoff(argv);
        if (rc >= 0)
            return rc;
    }
#endif
    if (argc >= 2 && (!strcmp(argv[1], "run") || !strcmp(argv[1], "check")))
        sd_threads_start(argc, argv); /* before any OpenMP region: may start the program again */
    if (argc >= 2 && (!strcmp(argv[1], "--version") || !strcmp(argv[1], "version"))) {
        printf("shapedem %s\n", SD_VERSION_STRING);
        return 0;
    }
    if (argc >= 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        sd_usage(stdout);
        return 0;
    }
    if (argc >= 2 && !strcmp(argv[1], "shape"))
        return sd_cmd_shape(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "render"))
        return sd_cmd_render(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "info")) /* cli/info_cmd.c */
        return sd_cmd_info(argc, argv);
    sd_cli c;
    int rc = sd_parse_args(argc, argv, &c);
    if (rc)
        return rc;
    if (c.help) { /* COMMAND --help: its usage (an unknown command: the commands) */
        sd_usage_command(stdout, c.command);
        return 0;
    }
    if (!strcmp(c.command, "run"))
        return sd_cmd_run(&c);
    if (!strcmp(c.command, "check"))
        return sd_cmd_check(&c);
    if (!strcmp(c.command, "help")) {
        if (c.scene && !strcmp(c.scene, "scene")) {
            sd_scene_print_keys(stdout, c.markdown);
            return 0;
        }
        if (c.scene) /* a topic that does not exist is a typo, not a request for the usage */
            return sd_usage_error("unknown help topic '%s' (the topics: scene)", c.scene);
        sd_usage(stdout);
        return 0;
    }
    return sd_usage_error("unknown command '%s'", c.command);
}
