/* main.c — the shapedem program: run, check and help.
 *
 * The only place that prints and exits. Exit status: 0 success, 1 a run
 * that failed while stepping or writing, 2 bad input (command line or
 * scene), 130 interrupted. Bad input is reported as one line before any
 * output directory is created.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <shapedem/shapedem.h>

#include "cli/check_report.h"
#include "cli/commands.h"
#include "io/output.h"
#include "io/scene.h"

#define SD_STR(x) #x
#define SD_XSTR(x) SD_STR(x) /* a macro's value as a string literal */

static volatile sig_atomic_t sd_interrupted;

static void sd_on_signal(int sig)
{
    (void)sig;
    sd_interrupted = 1;
}

static double sd_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
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
            "usage: shapedem run SCENE.yaml [-o DIR] [--threads N] [--steps N] [--quiet] [--bench NAME]\n"
            "       shapedem check SCENE.yaml [--threads N]\n"
            "       shapedem shape info KIND --size X[,Y,Z] [--rounding R] [--margin M] [--density RHO]\n"
            "       shapedem shape info SCENE.yaml\n"
            "       shapedem shape fit-fourier OUTLINE.csv [--order N] [--directions M] [--beta B]\n"
            "       shapedem help [scene [--markdown]]\n"
            "       shapedem --version\n"
            "\n"
            "  run     simulate the scene; writes frames.pvd (VTK), stats.csv and summary.txt\n"
            "          to DIR (default: output.directory of the scene, else out/<scene name>)\n"
            "  check   validate the scene and print what it would simulate\n"
            "  shape fit-fourier  fit a convex Fourier-series support function ([Huang 2021]) to a\n"
            "          closed outline; prints coefficients, convexity, reduction, coverage\n"
            "  help    this text; 'help scene' lists every scene key with unit and default\n"
            "\n"
            "  -o DIR       output directory\n"
            "  --threads N  OpenMP threads (default: simulation.threads, else OMP_NUM_THREADS)\n"
            "  --steps N    run N steps instead of the scene's (short runs)\n"
            "  --quiet      no progress line and no summary on the terminal\n"
            "  --bench NAME write no files; print one JSON line of timings for case NAME\n");
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
    long threads;
    long steps;
    int quiet;
    int markdown;
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
    if (argc < 2)
        return sd_usage_error("%s", "no command given");
    c->command = argv[1];
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
        } else if (!strcmp(a, "--steps")) {
            if (!next || sd_parse_long(next, 0, &c->steps))
                return sd_usage_error("--steps needs a whole number >= 0, got '%s'", next ? next : "");
            ++k;
        } else if (!strcmp(a, "--bench")) {
            if (!next)
                return sd_usage_error("%s needs a case name", a);
            c->bench = argv[++k];
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            c->quiet = 1;
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
    return 0;
}

/* Loads, applies the command-line overrides, builds. */
static int sd_load_world(const sd_cli *c, sd_scene **scene, sd_world **world)
{
    sd_error err;
    memset(&err, 0, sizeof err);
    if (!c->scene)
        return sd_usage_error("%s needs a scene file", c->command);
    if (sd_scene_load(c->scene, scene, &err) != SD_OK)
        return sd_cli_fail_input(&err);
    if (c->threads > 0)
        (*scene)->world.threads = (int)c->threads;
    if (c->steps >= 0)
        (*scene)->steps = c->steps;
    if (sd_scene_build(*scene, world, &err) != SD_OK) {
        sd_scene_free(*scene);
        *scene = NULL;
        return sd_cli_fail_input(&err);
    }
    return 0;
}

static void sd_default_outdir(const char *scene, char *buf, size_t size)
{
    const char *base = strrchr(scene, '/');
    base = base ? base + 1 : scene;
    size_t n = strlen(base);
    const char *dot = strrchr(base, '.');
    if (dot && dot != base)
        n = (size_t)(dot - base);
    snprintf(buf, size, "out/%.*s", (int)n, base);
}

static void sd_format_duration(double s, char *buf, size_t size)
{
    if (!(s >= 0) || s > 1e7)
        snprintf(buf, size, "--");
    else if (s < 60)
        snprintf(buf, size, "%.0fs", s);
    else if (s < 3600)
        snprintf(buf, size, "%dm%02ds", (int)(s / 60), (int)s % 60);
    else
        snprintf(buf, size, "%dh%02dm", (int)(s / 3600), ((int)s % 3600) / 60);
}

static int sd_cmd_run(const sd_cli *c)
{
    sd_scene *scene = NULL;
    sd_world *w = NULL;
    int rc = sd_load_world(c, &scene, &w);
    if (rc)
        return rc;
    for (size_t k = 0; k < scene->shape_count; ++k)
        if (scene->shapes[k].warning[0]) /* a mesh taken as its hull (nonconvex: hull) */
            fprintf(stderr, "shapedem: warning: shape %s: %s\n", scene->shapes[k].name, scene->shapes[k].warning);
    sd_error err;
    memset(&err, 0, sizeof err);
    long steps = scene->steps;
    long every = scene->output.every > 0 ? scene->output.every : 1;
    long stats_every = scene->output.stats_every > 0 ? scene->output.stats_every : every;
    sd_output *out = NULL;
    char dir[SD_SCENE_PATH_MAX + 16];
    if (!c->bench) {
        if (c->outdir)
            snprintf(dir, sizeof dir, "%s", c->outdir);
        else if (scene->output.directory[0])
            snprintf(dir, sizeof dir, "%s", scene->output.directory);
        else
            sd_default_outdir(c->scene, dir, sizeof dir);
        sd_output_def od = {dir, (scene->output.formats & SD_OUT_VTK) != 0, (scene->output.formats & SD_OUT_CSV) != 0,
                            c->scene};
        if (sd_output_open(&od, w, &out, &err) != SD_OK) {
            sd_world_destroy(w);
            sd_scene_free(scene);
            return sd_cli_fail_input(&err);
        }
    }
    signal(SIGINT, sd_on_signal);
    signal(SIGTERM, sd_on_signal);

    int tty = !c->quiet && !c->bench && isatty(STDERR_FILENO);
    size_t n = sd_world_particle_count(w);
    double stepping = 0, last_print = 0, psteps = 0;
    int failed = 0;
    if (out && (sd_output_frame(out, w, &err) != SD_OK || sd_output_stats(out, w, &err) != SD_OK))
        failed = 1;
    long done = 0;
    while (!failed && done < steps && !sd_interrupted) {
        /* step up to the next output event */
        long next = steps;
        long to_frame = every - done % every, to_stats = stats_every - done % stats_every;
        if (done + to_frame < next)
            next = done + to_frame;
        if (done + to_stats < next)
            next = done + to_stats;
        if (tty && next - done > 200)
            next = done + 200; /* keep the progress line alive */
        double t0 = sd_now();
        size_t n_before = sd_world_particle_count(w);
        if (sd_world_step(w, next - done, &err) != SD_OK) {
            failed = 1;
            break;
        }
        stepping += sd_now() - t0;
        /* the count changes when spheres are poured or leave (solver grid) */
        psteps += 0.5 * (double)(n_before + sd_world_particle_count(w)) * (double)(next - done);
        done = next;
        if (out && done % stats_every == 0 && sd_output_stats(out, w, &err) != SD_OK)
            failed = 1;
        if (out && !failed && (done % every == 0 || done == steps) && sd_output_frame(out, w, &err) != SD_OK)
            failed = 1;
        if (tty && (stepping - last_print > 0.5 || done == steps)) {
            last_print = stepping;
            double rate = stepping > 0 ? psteps / stepping : 0;
            char left[32];
            double left_ps = (double)sd_world_particle_count(w) * (double)(steps - done);
            sd_format_duration(rate > 0 ? left_ps / rate : -1, left, sizeof left);
            fprintf(stderr, "\rstep %ld/%ld  t = %.6g s  %5.1f%%  %.3g particle-steps/s  %s left   ", done, steps,
                    sd_world_time(w), steps ? 100.0 * (double)done / (double)steps : 100.0, rate, left);
            fflush(stderr);
        }
    }
    if (tty)
        fputc('\n', stderr);

    sd_run_summary sum;
    memset(&sum, 0, sizeof sum);
    sum.steps = done;
    sum.wall_seconds = stepping;
    sum.particle_steps_per_second = stepping > 0 ? psteps / stepping : 0;
    sum.threads = sd_world_threads(w);
    sum.peak_memory = sd_memory_peak();
    sum.peak_rss = sd_peak_rss();
    if (failed) {
        char buf[1024];
        sd_error_format(&err, buf, sizeof buf);
        fprintf(stderr, "shapedem: run stopped at step %ld: %s\n", sd_world_step_count(w), buf);
    }
    if (out) {
        sd_error cerr;
        memset(&cerr, 0, sizeof cerr);
        if (sd_output_close(out, w, &sum, &cerr) != SD_OK && !failed) {
            char buf[1024];
            sd_error_format(&cerr, buf, sizeof buf);
            fprintf(stderr, "shapedem: %s\n", buf);
            failed = 1;
        }
    }
    if (c->bench) {
        printf("{\"case\":\"%s\",\"particles\":%zu,\"steps\":%ld,\"threads\":%d,\"wall_s\":%.6f,\"psps\":%.6g,"
               "\"peak_rss_mib\":%.2f,\"peak_alloc_mib\":%.2f}\n",
               c->bench, n, done, sum.threads, stepping, sum.particle_steps_per_second,
               (double)sum.peak_rss / 1048576.0, (double)sum.peak_memory / 1048576.0);
    } else if (!c->quiet) {
        sd_stats st;
        sd_world_stats(w, &st);
        /* the count at the end, as summary.txt (a pour starts from none) */
        printf("shapedem: %zu particles, %ld steps (t = %.6g s) in %.2f s: %.3g particle-steps/s on %d thread%s\n",
               sd_world_particle_count(w), done, sd_world_time(w), stepping, sum.particle_steps_per_second, sum.threads,
               sum.threads == 1 ? "" : "s");
        printf("          kinetic energy %.6g J, %ld contacts, max overlap %.3g %% of radius; output in %s\n",
               st.kinetic_translational + st.kinetic_rotational, st.contacts, 100 * st.max_overlap_ratio, dir);
    }
    sd_world_destroy(w);
    sd_scene_free(scene);
    if (sd_interrupted) {
        fprintf(stderr, "shapedem: interrupted at step %ld; the files written so far are complete\n", done);
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
    if (rc)
        return rc;
    size_t mem = sd_memory_in_use() - mem0;
    size_t n = sd_world_particle_count(w);
    double tc = 0, rec = sd_world_recommended_dt(w, &tc);
    double dt = sd_world_dt(w);
    printf("scene        %s\n", c->scene);
    sd_check_counts cnt; /* the pour's spheres too (cli/check_report.c) */
    sd_check_count(scene, w, &cnt);
    size_t total = n + cnt.poured;
    size_t nshape = cnt.bodies;
    printf("particles    %zu: %zu spheres, %zu bodies of %zu shapes", n, n - nshape, nshape,
           sd_world_shape_count(w));
    if (cnt.poured)
        printf(", and %zu spheres the pour inserts: %zu in all", cnt.poured, total);
    if (total)
        printf("; radius (bounding radius for shapes) %.4g .. %.4g m", cnt.rmin, cnt.rmax);
    printf("\nsolver       %s", scene->world.solver == SD_SOLVER_GRID ? "grid (dense grid stencil, [Naderi 2024])"
                                                                     : "cells (cell binning + pair lists)");
    printf("\nmaterials    %zu:", scene->material_count);
    for (size_t k = 0; k < scene->material_count; ++k)
        printf(" %s", scene->materials[k].name);
    printf("\ncontact law  %s (default)\n", sd_contact_law_name(scene->world.law));
    printf("walls        %zu\n", sd_world_wall_count(w));
    if (scene->pour.given) /* solver grid: pouring and outlet (docs/grid-solver.md) */
        printf("pour         %ld spheres of radius %.4g m (material %s), sheets at z = %.4g m, %.4g per s from "
               "t = %.4g s, speeds vz in +-%.3g m/s, vx, vy in +-%.3g m/s\n",
               scene->pour.count, scene->pour.radius, scene->materials[scene->pour.material].name,
               scene->pour.height, scene->pour.rate, scene->pour.start, scene->pour.vertical_speed,
               scene->pour.horizontal_speed);
    if (scene->outlet.given)
        printf("outlet       hole x in [%.4g, %.4g] m, y in [%.4g, %.4g] m in the box floor, opens at t = %.4g s\n",
               scene->outlet.lo[0], scene->outlet.hi[0], scene->outlet.lo[1], scene->outlet.hi[1],
               scene->outlet.open_at);
    printf("steps        %ld x dt %.4g s = %.6g s simulated\n", scene->steps, dt, (double)scene->steps * dt);
    printf("contact      shortest estimated contact duration %.4g s (%.1f steps)\n", tc, tc / dt);
    printf("time step    %.4g s recommended; stability limit %.4g s\n", rec, tc / 5);
    printf("threads      %d\n", sd_world_threads(w));
    const char *unit2d = scene->world.dimension == 2 ? " per 1 m of thickness" : "";
    printf("mass         %.6g kg%s", cnt.mass_now + cnt.mass_poured, unit2d);
    if (cnt.poured)
        printf(": %.6g kg at the start and %.6g kg poured", cnt.mass_now, cnt.mass_poured);
    printf("\n");
    double memory = (double)mem + (cnt.poured ? sd_check_pour_bytes(cnt.poured) : 0.0);
    printf("memory       about %.1f MiB (%.0f bytes per particle) once the pair lists are built%s\n",
           memory / 1048576.0, total ? memory / (double)total : 0.0,
           cnt.poured ? ", all poured spheres in" : "");
    /* output: frames at step 0, every `every` steps and at the end; stats
     * rows at step 0 and every stats_every steps (sd_cmd_run) */
    long steps = scene->steps, every = scene->output.every > 0 ? scene->output.every : 1;
    long stats_every = scene->output.stats_every > 0 ? scene->output.stats_every : every;
    long frames = 1 + steps / every + (steps % every != 0), rows = 1 + steps / stats_every;
    sd_output_def od = {".", (scene->output.formats & SD_OUT_VTK) != 0, (scene->output.formats & SD_OUT_CSV) != 0,
                        c->scene};
    sd_output_size osz;
    sd_error oerr;
    memset(&oerr, 0, sizeof oerr);
    if (sd_output_estimate(&od, w, total, frames, rows, (double)steps * dt, &osz, &oerr) == SD_OK) {
        char tb[32], fb[32];
        sd_check_format_bytes(osz.total, tb, sizeof tb);
        sd_check_format_bytes(osz.frame_particles + osz.frame_walls, fb, sizeof fb);
        printf("output       about %s (%.0f bytes): ", tb, osz.total);
        if (od.vtk)
            printf("%ld frames x %s%s", frames, fb, cnt.poured ? " (at most: all poured spheres in)" : "");
        if (od.csv)
            printf("%s%ld stats rows x %.0f bytes", od.vtk ? ", " : "", rows, osz.stats_row);
        printf("\n");
    }
    int warnings = 0;
    if (dt > rec) {
        printf("warning      dt = %.4g s is above the recommended %.4g s: contacts are resolved in %.1f steps\n", dt,
               rec, tc / dt);
        warnings++;
    }
    warnings += sd_check_units(stdout, scene, &cnt, tc, dt);
    for (size_t k = 0; k < scene->shape_count; ++k)
        if (scene->shapes[k].warning[0]) { /* a mesh taken as its hull (nonconvex: hull) */
            printf("warning      shape %s: %s\n", scene->shapes[k].name, scene->shapes[k].warning);
            warnings++;
        }
    /* last: the trial steps the world */
    sd_check_trial tr;
    sd_check_time(scene, w, total, steps, &tr);
    if (tr.ok && tr.steps > 0) {
        char left[32];
        sd_format_duration(tr.estimate, left, sizeof left);
        printf("run time     %sabout %s on %d thread%s (timed trial: %ld steps of %s%zu particles in %.3g s, "
               "scaled to %ld steps%s; rough, within a factor of 2-3)\n",
               cnt.poured ? "at most " : "", left, tr.threads, tr.threads == 1 ? "" : "s", tr.steps,
               tr.bed ? "a bed of the pour's " : "", tr.particles, tr.seconds, steps,
               cnt.poured ? " with every poured sphere in" : "");
        if (tr.estimate > 600.0) {
            printf("warning      the run is estimated at %s, more than 10 minutes: try it first with --steps N "
                   "(a short run), or more --threads\n",
                   left);
            warnings++;
        }
    }
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

int main(int argc, char **argv)
{
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
    sd_cli c;
    int rc = sd_parse_args(argc, argv, &c);
    if (rc)
        return rc;
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
