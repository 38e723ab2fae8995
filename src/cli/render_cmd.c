/* render_cmd.c — `shapedem render`: pictures of a run's frames, headless
 * (src/render/, docs/output.md).
 *
 * Invariant: bad input (a missing file, a file that is not a frame, a bad
 * option) is one line on stderr naming the file or option, exit status 2,
 * and no picture written; a movie's frames share one colour range (the
 * range over all frames, unless --range gives one), so colours mean the
 * same value in every picture; a picture is written only over a regular
 * file that is none of the files it is drawn from (a FIFO, a device node,
 * a link or the input frame under -o is refused, exit 2, before anything
 * is written: sd_fs_check_output, as the run's own outputs).
 */
#define _POSIX_C_SOURCE 200809L

#include "cli/commands.h"
#include "core/alloc.h"
#include "cli/render_ckpt.h"
#include "io/checkpoint.h"
#include "io/fsutil.h"
#include "io/output.h"
#include "render/render.h"

#include <errno.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

static int sd_render_usage(FILE *f)
{
    fprintf(f, "usage: shapedem render FRAME.vtu|SHAPES.vtp|frames.pvd|CHECKPOINT.h5 -o PICTURE.png [--frame I]\n"
               "                       [--field NAME]\n"
               "                       [--view front|top|iso|AZ,EL] [--size WxH] [--colormap viridis|coolwarm|gray]\n"
               "                       [--range LO,HI] [--fit particles|all] [--no-colorbar] [--movie [--fps N]]\n"
               "                       [--scene SCENE.yaml]\n"
               "\n"
               "  draws a frame's particles with their true shapes (the run's shapes_NNNNNN.vtp, written\n"
               "  with output.formats: [vtk, csv, shapes]; without it, spheres of each particle's radius),\n"
               "  coloured by a field, walls and meshes drawn thin; no display needed; a checkpoint\n"
               "  (checkpoint-NNNNNN.h5, failed-NNNNNN.h5) draws its particles as spheres, without walls\n"
               "  --scene S     with a checkpoint: the scene that wrote it, whose world restored from the\n"
               "                checkpoint is drawn with its true shapes and walls\n"
               "  --frame I     frame I of a frames.pvd (0 the first, -1 the last: the default)\n"
               "  --field NAME  speed (the default) or any particle array (vectors by magnitude)\n"
               "  --view V      front (along +y), top (down -z), iso, or AZ,EL in degrees (default iso;\n"
               "                top for a planar run)\n"
               "  --size WxH    pixels (default 800x600)\n"
               "  --range LO,HI the field values at the ends of the colour map (default: the frame's)\n"
               "  --fit F       what the picture frames: particles (the default) or all (walls too)\n"
               "  --movie       every frame of a frames.pvd: PICTURE_000000.png, ... (and PICTURE.mp4\n"
               "                when ffmpeg is on the PATH), one colour range for all\n");
    return f == stdout ? 0 : 2;
}

static int sd_render_bad(const char *fmt, const char *arg)
{
    fprintf(stderr, "shapedem: render: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, " (see 'shapedem render --help')\n");
    return 2;
}

static int sd_parse_two(const char *s, char sep, double *a, double *b)
{
    char *e;
    errno = 0;
    *a = strtod(s, &e);
    if (e == s || *e != sep || errno)
        return -1;
    const char *t = e + 1;
    *b = strtod(t, &e);
    return (e == t || *e || errno) ? -1 : 0;
}

static int sd_ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && !strcmp(s + n - m, suffix);
}

/* 1 when an executable `name` is in a directory of PATH. */
static int sd_on_path(const char *name)
{
    const char *path = getenv("PATH");
    if (!path)
        return 0;
    char buf[4096];
    for (const char *p = path; *p;) {
        const char *c = strchr(p, ':');
        size_t n = c ? (size_t)(c - p) : strlen(p);
        if (n > 0 && n + strlen(name) + 2 < sizeof buf) {
            snprintf(buf, sizeof buf, "%.*s/%s", (int)n, p, name);
            if (access(buf, X_OK) == 0)
                return 1;
        }
        p += n + (c ? 1 : 0);
    }
    return 0;
}

/* PICTURE.png -> PICTURE_NNNNNN.png (or PICTURE.mp4 for k < 0). */
static void sd_movie_name(const char *out, long k, char *buf, size_t size)
{
    size_t n = strlen(out);
    if (sd_ends_with(out, ".png"))
        n -= 4;
    if (k < 0)
        snprintf(buf, size, "%.*s.mp4", (int)n, out);
    else
        snprintf(buf, size, "%.*s_%06ld.png", (int)n, out, k);
}

/* --scene SCENE.yaml: the scene a checkpoint's world is restored in (cli/render_ckpt.c) */
static const char *sd_render_scene;

/* The frame's sibling of another part (particles_N.vtu -> shapes_N.vtp,
 * walls_N.vtp), "" for a name of no such series. */
static void sd_render_sibling(const char *frame, const char *from, const char *to, char *buf, size_t size)
{
    const char *slash = strrchr(frame, '/');
    const char *base = slash ? slash + 1 : frame;
    size_t dir = (size_t)(base - frame), n = strlen(from);
    buf[0] = 0;
    if (strncmp(base, from, n) != 0 || strlen(base) < n + 4)
        return;
    snprintf(buf, size, "%.*s%s%.*s.vtp", (int)dir, frame, to, (int)(strlen(base) - n - 4), base + n);
}

/* The files pictures are drawn from, which none may replace: the
 * collection, its frames (or the one frame) and their siblings. */
typedef struct sd_render_inputs {
    const char **path;
    size_t n;
    char *buf;
} sd_render_inputs;

/* frames: n paths (sd_render_pvd_list's); pvd may be NULL;
 * --scene's file (a checkpoint's) is one too. */
static int sd_render_inputs_make(const char *pvd, char *const *frames, size_t n, sd_render_inputs *in)
{
    size_t bytes = pvd ? strlen(pvd) + 1 : 0;
    for (size_t k = 0; k < n; ++k)
        bytes += 4 * (strlen(frames[k]) + 16);
    in->n = 0;
    in->path = sd_malloc((4 * n + 2) * sizeof *in->path);
    in->buf = sd_malloc(bytes ? bytes : 1);
    if (!in->path || !in->buf) {
        sd_free(in->path);
        sd_free(in->buf);
        fprintf(stderr, "shapedem: render: out of memory\n");
        return 1;
    }
    char *at = in->buf;
    if (sd_render_scene)
        in->path[in->n++] = sd_render_scene;
    if (pvd) {
        in->path[in->n++] = at;
        at += snprintf(at, strlen(pvd) + 1, "%s", pvd) + 1;
    }
    static const char *const sib[3][2] = {{"particles_", "shapes_"}, {"particles_", "walls_"}, {"shapes_", "walls_"}};
    for (size_t k = 0; k < n; ++k) {
        const char *f = frames[k];
        size_t len = strlen(f) + 16;
        in->path[in->n++] = at;
        at += snprintf(at, len, "%s", f) + 1;
        for (int j = 0; j < 3; ++j) {
            sd_render_sibling(f, sib[j][0], sib[j][1], at, len);
            if (at[0]) {
                in->path[in->n++] = at;
                at += strlen(at) + 1;
            }
        }
    }
    return 0;
}

static void sd_render_inputs_free(sd_render_inputs *in)
{
    sd_free(in->path);
    sd_free(in->buf);
}

/* A picture's path (and render/draw.c's temporary beside it, written
 * first) may be replaced: not a FIFO, device, link or directory, and none
 * of the inputs (sd_fs_check_output, as the run's own outputs). */
static int sd_render_check_out(const char *png, const sd_render_inputs *in)
{
    /* nor a file of a run's output directory (its marker there) under a
     * name the run writes: a frame, frames.pvd, a CSV series, a checkpoint */
    const char *slash = strrchr(png, '/');
    char marker[SD_RENDER_PATH_MAX + 32];
    snprintf(marker, sizeof marker, "%.*s.shapedem-output", slash ? (int)(slash - png + 1) : 0, png);
    if (sd_output_is_run_name(slash ? slash + 1 : png) && sd_fs_is_regular_file(marker)) {
        fprintf(stderr, "shapedem: %s: -o: a run's own output file (its directory has %s): the picture would "
                        "replace it; choose another name\n", png, marker);
        return 2;
    }
    char tmp[SD_RENDER_PATH_MAX + 16];
    snprintf(tmp, sizeof tmp, "%s.tmp", png);
    sd_error err;
    memset(&err, 0, sizeof err);
    if (sd_fs_check_output(png, "-o", in->path, in->n, &err) != SD_OK ||
        sd_fs_check_output(tmp, "-o", in->path, in->n, &err) != SD_OK)
        return sd_cli_fail_input(&err);
    return 0;
}

/* say: print what the picture shows (one picture; a movie says it once);
 * in: the files no picture may replace (sd_render_check_out) */
static int sd_render_one(const char *frame, const char *field, sd_render_def *d, int view_given, const char *png,
                         int say, const sd_render_inputs *in)
{
    int rc = sd_render_check_out(png, in);
    if (rc)
        return rc;
    sd_render_frame f;
    sd_error err;
    int ckpt = sd_checkpoint_is_file(frame);
    sd_status s = ckpt ? sd_render_load_checkpoint(frame, sd_render_scene, field, &f, &err)
                       : sd_render_frame_load(frame, field, &f, &err);
    if (s != SD_OK)
        return sd_cli_fail_input(&err);
    if (!view_given && f.planar)
        sd_render_view("top", &d->azimuth, &d->elevation);
    if (ckpt && !sd_render_scene)
        fprintf(stderr, "shapedem: render: %s is a checkpoint: its particles are drawn as spheres of their radius "
                        "(a shaped particle's bounding sphere), without the walls (--scene SCENE.yaml, the scene "
                        "that wrote it, draws true shapes and walls)\n", frame);
    else if (f.bounding_spheres)
        fprintf(stderr, "shapedem: render: %s has no shapes file: shaped particles are drawn as their bounding "
                        "spheres (write output.formats: [vtk, csv, shapes])\n", frame);
    s = sd_render_png(&f, d, png, &err);
    if (s == SD_OK && say) {
        char what[1024];
        sd_render_describe(&f, d, what, sizeof what);
        printf("wrote %s: %s\n", png, what);
    }
    sd_render_frame_free(&f);
    if (s != SD_OK) {
        rc = sd_cli_fail_input(&err);
        return s == SD_ERR_INPUT ? rc : 1;
    }
    return 0;
}

static int sd_render_movie(const char *pvd, const char *field, sd_render_def *d, int view_given, const char *out,
                           int fps)
{
    char **paths;
    size_t n;
    sd_error err;
    if (sd_render_pvd_list(pvd, &paths, &n, &err) != SD_OK)
        return sd_cli_fail_input(&err);
    int rc = 0;
    if (!d->fixed_range) { /* one range for every picture */
        double lo = 0.0, hi = 0.0;
        for (size_t k = 0; k < n && !rc; ++k) {
            sd_render_frame f;
            if (sd_render_frame_load(paths[k], field, &f, &err) != SD_OK) {
                rc = sd_cli_fail_input(&err);
                break;
            }
            double a, b;
            sd_render_frame_range(&f, &a, &b);
            if (k == 0 || a < lo)
                lo = a;
            if (k == 0 || b > hi)
                hi = b;
            sd_render_frame_free(&f);
        }
        d->fixed_range = 1;
        d->lo = lo;
        d->hi = hi;
    }
    char name[SD_RENDER_PATH_MAX + 32], mp4[SD_RENDER_PATH_MAX + 32];
    sd_render_inputs in;
    int made = !rc && (rc = sd_render_inputs_make(pvd, paths, n, &in)) == 0;
    for (size_t k = 0; k < n && !rc; ++k) {
        sd_movie_name(out, (long)k, name, sizeof name);
        rc = sd_render_one(paths[k], field, d, view_given, name, k + 1 == n, &in);
    }
    sd_movie_name(out, -1, mp4, sizeof mp4);
    if (!rc && sd_on_path("ffmpeg")) /* ffmpeg -y replaces what is there */
        rc = sd_render_check_out(mp4, &in);
    if (made)
        sd_render_inputs_free(&in);
    sd_free(paths);
    if (rc)
        return rc;
    printf("wrote %zu pictures\n", n);
    if (!sd_on_path("ffmpeg")) {
        printf("no ffmpeg on the PATH: no MP4\n");
        return 0;
    }
    char pattern[SD_RENDER_PATH_MAX + 32], rate[16];
    snprintf(pattern, sizeof pattern, "%.*s_%%06d.png", (int)(strlen(out) - (sd_ends_with(out, ".png") ? 4 : 0)),
             out);
    snprintf(rate, sizeof rate, "%d", fps);
    /* even sizes: the yuv420p that players expect halves the chroma */
    char *argv[] = {"ffmpeg", "-y", "-loglevel", "error", "-framerate", rate, "-i", pattern, "-vf",
                    "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p", mp4, NULL};
    pid_t pid;
    if (posix_spawnp(&pid, "ffmpeg", NULL, NULL, argv, environ) != 0) {
        fprintf(stderr, "shapedem: render: cannot start ffmpeg\n");
        return 1;
    }
    int st = 0;
    if (waitpid(pid, &st, 0) < 0 || !WIFEXITED(st) || WEXITSTATUS(st) != 0) {
        fprintf(stderr, "shapedem: render: ffmpeg failed; the PNG pictures are there\n");
        return 1;
    }
    printf("wrote %s\n", mp4);
    return 0;
}

int sd_cmd_render(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *field = "speed";
    long frame = -1;
    int movie = 0, fps = 10, view_given = 0;
    sd_render_def d = sd_render_def_default();
    sd_render_view("iso", &d.azimuth, &d.elevation);
    for (int k = 2; k < argc; ++k) {
        const char *a = argv[k], *next = k + 1 < argc ? argv[k + 1] : NULL;
        if (!strcmp(a, "--help") || !strcmp(a, "-h"))
            return sd_render_usage(stdout);
        if (!strcmp(a, "-o")) {
            if (!next)
                return sd_render_bad("%s needs a picture file", a);
            out = next;
            ++k;
        } else if (!strcmp(a, "--field")) {
            if (!next || !next[0] || strlen(next) >= 60)
                return sd_render_bad("%s needs a field name", a);
            field = next;
            ++k;
        } else if (!strcmp(a, "--frame")) {
            char *e;
            errno = 0;
            frame = next ? strtol(next, &e, 10) : 0;
            if (!next || e == next || *e || errno)
                return sd_render_bad("--frame needs a whole number, got '%s'", next ? next : "");
            ++k;
        } else if (!strcmp(a, "--view")) {
            if (!next || (sd_render_view(next, &d.azimuth, &d.elevation) != 0 &&
                          (sd_parse_two(next, ',', &d.azimuth, &d.elevation) != 0 || d.elevation < -90.0 ||
                           d.elevation > 90.0)))
                return sd_render_bad("--view needs front, top, iso or AZ,EL in degrees (EL in [-90, 90]), got '%s'",
                                     next ? next : "");
            view_given = 1;
            ++k;
        } else if (!strcmp(a, "--size")) {
            double w, h;
            if (!next || sd_parse_two(next, 'x', &w, &h) != 0 || w != (int)w || h != (int)h || w < 16 || h < 16 ||
                w > 16384 || h > 16384)
                return sd_render_bad("--size needs WxH, whole pixels from 16 to 16384, got '%s'", next ? next : "");
            d.width = (int)w;
            d.height = (int)h;
            ++k;
        } else if (!strcmp(a, "--colormap")) {
            if (!next || (d.colormap = sd_render_colormap_of(next)) < 0)
                return sd_render_bad("--colormap needs viridis, coolwarm or gray, got '%s'", next ? next : "");
            ++k;
        } else if (!strcmp(a, "--range")) {
            if (!next || sd_parse_two(next, ',', &d.lo, &d.hi) != 0 || !(d.lo < d.hi))
                return sd_render_bad("--range needs LO,HI with LO < HI, got '%s'", next ? next : "");
            d.fixed_range = 1;
            ++k;
        } else if (!strcmp(a, "--fit")) {
            if (!next || (strcmp(next, "particles") && strcmp(next, "all")))
                return sd_render_bad("--fit needs particles or all, got '%s'", next ? next : "");
            d.fit_walls = !strcmp(next, "all");
            ++k;
        } else if (!strcmp(a, "--scene")) {
            if (!next || !next[0])
                return sd_render_bad("%s needs the scene file that wrote the checkpoint", a);
            sd_render_scene = next;
            ++k;
        } else if (!strcmp(a, "--no-colorbar")) {
            d.colorbar = 0;
        } else if (!strcmp(a, "--movie")) {
            movie = 1;
        } else if (!strcmp(a, "--fps")) {
            char *e;
            long v = next ? strtol(next, &e, 10) : 0;
            if (!next || e == next || *e || v < 1 || v > 120)
                return sd_render_bad("--fps needs a whole number from 1 to 120, got '%s'", next ? next : "");
            fps = (int)v;
            ++k;
        } else if (a[0] == '-') {
            return sd_render_bad("unknown option '%s'", a);
        } else if (!in) {
            in = a;
        } else {
            return sd_render_bad("unexpected argument '%s'", a);
        }
    }
    if (!in)
        return sd_render_bad("%s", "needs a frame file (particles_NNNNNN.vtu, shapes_NNNNNN.vtp, frames.pvd or a "
                                   "checkpoint .h5)");
    if (!out)
        return sd_render_bad("%s", "needs -o PICTURE.png");
    if (!sd_render_available()) {
        fprintf(stderr, "shapedem: render: this shapedem was built without rendering (cairo was not found at "
                        "build time: install libcairo2-dev, scripts/deps.sh does it, and build again)\n");
        return 2;
    }
    if (sd_render_scene && !sd_checkpoint_is_file(in))
        return sd_render_bad("--scene goes with a checkpoint (.h5), not '%s'", in);
    int is_pvd = sd_ends_with(in, ".pvd");
    if (movie && !is_pvd)
        return sd_render_bad("--movie needs a frames.pvd, got '%s'", in);
    if (movie)
        return sd_render_movie(in, field, &d, view_given, out, fps);
    if (!is_pvd) {
        sd_render_inputs ins;
        char *one[1] = {(char *)in}; /* read only */
        if (sd_render_inputs_make(NULL, one, 1, &ins))
            return 1;
        int rc = sd_render_one(in, field, &d, view_given, out, 1, &ins);
        sd_render_inputs_free(&ins);
        return rc;
    }
    char **paths;
    size_t n;
    sd_error err;
    if (sd_render_pvd_list(in, &paths, &n, &err) != SD_OK)
        return sd_cli_fail_input(&err);
    long i = frame < 0 ? (long)n + frame : frame;
    if (i < 0 || i >= (long)n) {
        sd_free(paths);
        fprintf(stderr, "shapedem: render: %s: --frame %ld: the collection has %zu frames (0 to %zu, or -1 for the "
                        "last)\n", in, frame, n, n - 1);
        return 2;
    }
    sd_render_inputs ins; /* every frame of the collection: none may become the picture */
    int rc = sd_render_inputs_make(in, paths, n, &ins);
    if (!rc) {
        rc = sd_render_one(paths[i], field, &d, view_given, out, 1, &ins);
        sd_render_inputs_free(&ins);
    }
    sd_free(paths);
    return rc;
}
