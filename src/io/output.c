/* output.c — the run output directory: frames (VTK XML), frames.pvd,
 * stats.csv and summary.txt.
 *
 * Invariants (see output.h): nothing is written into a non-empty directory
 * that lacks the .shapedem-output marker; a directory with the marker loses
 * only files whose names shapedem itself writes (particles_<digits>.vtu,
 * walls_<digits>.vtp, shapes_<digits>.vtp, frames.pvd, stats.csv, walls.csv, biaxial.csv,
 * trajectory.dump, trajectory.h5md, summary.txt and their ".<name>.tmp" temporaries); every
 * file except the CSVs and the trajectories is replaced atomically; the
 * trajectories get a frame, flushed, per frame, and a restart keeps their
 * frames before its step (sd_dump_keep, io/h5md.c); stats.csv, walls.csv (worlds with walls) and
 * biaxial.csv (2D boxes) are only ever appended to, one flushed row per call,
 * so a crash loses at most the row being written; a restart
 * (sd_output_def.resume_step) keeps their rows before its step and appends.
 *
 * The world is read only through the public API in shapedem.h.
 */
#define _POSIX_C_SOURCE 200809L

#include "io/output.h"

#include "core/alloc.h"
#include "core/error.h"
#include "world/solver.h"
#include "io/fsutil.h"
#include "io/h5md.h"
#include "io/vtk.h"
#include <shapedem/process.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SD_OUTPUT_MARKER ".shapedem-output"
#define SD_OUTPUT_KEY "output.directory"
#define SD_OUTPUT_NAME_MAX 48 /* "particles_" + up to 20 digits + ".vtu" */
#define SD_OUTPUT_BIAXIAL_HEADER                                                                               \
    "step,time,width,height,sigma_xx,sigma_yy,strain_axial,strain_lateral,strain_volumetric,stress_ratio\n"

struct sd_output {
    char *dir;
    char *scene;
    int vtk, csv;
    sd_vtk_shapes *shapes; /* the templates' surfaces when frames carry the true shapes, else NULL */
    long frames;          /* frames written so far = next frame number */
    double *frame_times;  /* s, one per frame, for frames.pvd */
    size_t frame_cap;
    FILE *stats;          /* stats.csv, opened at the first row */
    long resume_step;     /* sd_output_def.resume_step */
    size_t stats_walls;   /* walls in the header */
    size_t stats_solver;  /* the header has this many solver columns (world/solver.h) */
    long stats_rows;
    FILE *biaxial;        /* biaxial.csv (2D worlds with four walls), opened at the first row */
    FILE *walls;          /* walls.csv (worlds with walls), opened at the first row */
    int walls_csv;        /* write walls.csv (not in the size estimate's dry run) */
    FILE *dump;           /* trajectory.dump (sd_output_def.dump), else NULL */
    sd_dump_box dump_box;
    long dump_frames;     /* snapshots in trajectory.dump, those a restart kept included */
    sd_h5md *h5md;        /* trajectory.h5md (sd_output_def.h5md), else NULL */
};

static char *sd_output_strdup(const char *s)
{
    size_t n = strlen(s);
    char *p = sd_malloc(n + 1);
    if (p)
        memcpy(p, s, n + 1);
    return p;
}

/* ---- which files are ours ------------------------------------------------ */

static int sd_output_has_suffix(const char *s, size_t n, const char *suffix)
{
    size_t m = strlen(suffix);
    return n >= m && memcmp(s + n - m, suffix, m) == 0;
}

/* prefix, one or more digits, suffix — the frame file names. */
static int sd_output_is_frame_name(const char *s, size_t n, const char *prefix, const char *suffix)
{
    size_t a = strlen(prefix), b = strlen(suffix);
    if (n <= a + b || memcmp(s, prefix, a) != 0 || !sd_output_has_suffix(s, n, suffix))
        return 0;
    for (size_t i = a; i < n - b; ++i)
        if (s[i] < '0' || s[i] > '9')
            return 0;
    return 1;
}

/* A frame's files, by part (sd_vtk_dataset.part): prefix, number, suffix. */
static const char *const sd_output_part_prefix[3] = {"particles_", "walls_", "shapes_"};
static const char *const sd_output_part_suffix[3] = {".vtu", ".vtp", ".vtp"};

/* The file name of part `part` of frame f. */
static void sd_output_frame_file(char name[SD_OUTPUT_NAME_MAX], int part, long f)
{
    snprintf(name, SD_OUTPUT_NAME_MAX, "%s%06ld%s", sd_output_part_prefix[part], f, sd_output_part_suffix[part]);
}

/* The number of a frame file's name, -1 for any other name. */
static long sd_output_frame_number(const char *name)
{
    size_t n = strlen(name);
    for (int k = 0; k < 3; ++k)
        if (sd_output_is_frame_name(name, n, sd_output_part_prefix[k], sd_output_part_suffix[k]))
            return strtol(name + strlen(sd_output_part_prefix[k]), NULL, 10);
    return -1;
}

/* A checkpoint's name (io/checkpoint.c): checkpoint-<digits>.h5, or
 * failed-<digits>.h5 of a step that failed. */
static int sd_output_is_checkpoint_name(const char *s, size_t n)
{
    return sd_output_is_frame_name(s, n, "checkpoint-", ".h5") || sd_output_is_frame_name(s, n, "failed-", ".h5");
}

static int sd_output_is_ours(const char *name)
{
    const char *s = name;
    size_t n = strlen(name);
    if (n > 5 && name[0] == '.' && sd_output_has_suffix(name, n, ".tmp")) {
        s = name + 1; /* a temporary left by an interrupted run */
        n -= 5;
        /* a checkpoint's too (SIGKILL during its write): the checkpoints
         * themselves stay, their unfinished temporaries go */
        if (sd_output_is_checkpoint_name(s, n))
            return 1;
    }
    static const char *fixed[] = {"frames.pvd", "stats.csv", "summary.txt", "biaxial.csv", "walls.csv",
                                  "trajectory.dump", "trajectory.h5md"};
    for (size_t k = 0; k < sizeof fixed / sizeof fixed[0]; ++k)
        if (n == strlen(fixed[k]) && memcmp(s, fixed[k], n) == 0)
            return 1;
    for (int k = 0; k < 3; ++k)
        if (sd_output_is_frame_name(s, n, sd_output_part_prefix[k], sd_output_part_suffix[k]))
            return 1;
    return 0;
}

int sd_output_is_run_name(const char *name)
{
    size_t n = strlen(name);
    const char *s = name;
    if (n > 5 && name[0] == '.' && sd_output_has_suffix(name, n, ".tmp")) {
        s = name + 1; /* the temporary of any of them */
        n -= 5;
    }
    static const char *more[] = {"outlet.csv", SD_OUTPUT_MARKER};
    for (size_t k = 0; k < sizeof more / sizeof more[0]; ++k)
        if (n == strlen(more[k]) && memcmp(s, more[k], n) == 0)
            return 1;
    return sd_output_is_ours(name) || sd_output_is_checkpoint_name(s, n);
}

typedef struct sd_output_scan {
    size_t entries;
    const char *example; /* a foreign entry's name, for the message */
    char example_buf[128];
} sd_output_scan;

static int sd_output_scan_visit(const char *name, void *ctx)
{
    sd_output_scan *sc = ctx;
    if (sc->entries++ == 0) {
        snprintf(sc->example_buf, sizeof sc->example_buf, "%s", name);
        sc->example = sc->example_buf;
    }
    return 0;
}

typedef struct sd_output_clean {
    const char *dir;
    int resume;           /* a restart: the CSV series and the dump stay (sd_output_open_csv,
                             sd_output_open_dump cut them) */
    long keep_frames;     /* a restart: frames numbered below this stay, and frames.pvd when > 0 */
    sd_status status;
    sd_error *err;
} sd_output_clean;

static int sd_output_clean_visit(const char *name, void *ctx)
{
    sd_output_clean *c = ctx;
    if (!sd_output_is_ours(name))
        return 0;
    if (c->resume && (!strcmp(name, "stats.csv") || !strcmp(name, "walls.csv") || !strcmp(name, "biaxial.csv") ||
                      !strcmp(name, "trajectory.dump") || !strcmp(name, "trajectory.h5md")))
        return 0;
    long f = sd_output_frame_number(name);
    if ((f >= 0 && f < c->keep_frames) || (c->keep_frames > 0 && !strcmp(name, "frames.pvd")))
        return 0;
    char *path = sd_fs_join(c->dir, name);
    if (!path) {
        c->status = sd_error_set(c->err, SD_ERR_MEMORY, c->dir, 0, "", "out of memory");
        return 1;
    }
    /* Only plain files: a directory or link under one of our names was made
     * by someone else. It is left alone and the run refused before anything
     * is written: appending to stats.csv through a link would change the
     * link's target outside the directory (probe F5). */
    const char *what = sd_fs_not_regular(path);
    if (what) {
        c->status = sd_error_set(c->err, SD_ERR_IO, path, 0, SD_OUTPUT_KEY,
                                 "%s, not a file shapedem wrote, has the name of one of a run's files; "
                                 "shapedem will not write through it: remove it or choose another directory",
                                 what);
        sd_free(path);
        return 1;
    }
    if (remove(path) != 0 && errno != ENOENT) {
        c->status = sd_error_set(c->err, SD_ERR_IO, path, 0, "",
                                 "cannot remove the previous run's file: %s", strerror(errno));
        sd_free(path);
        return 1;
    }
    sd_free(path);
    return 0;
}

/* ---- a restart's frames ---------------------------------------------------- */

static sd_status sd_output_write_pvd(sd_output *o, sd_error *err);

/* A restart into the first part's directory continues its frames, as the
 * CSV series: the frames before the restart time t stay, with their
 * numbers, and the series goes on after them, so the directory holds the
 * uninterrupted run's frames. frames.pvd tells which: its DataSets in the
 * order sd_output_write_pvd writes them, `parts` a frame, the times at 17
 * digits (exact). *kept 0, and the frames start again from 0, when there
 * is no frames.pvd or it is not in that layout (another output format, or
 * not a file we wrote); else *times holds the kept frames' times. */
static sd_status sd_output_resume_frames(const char *dir, size_t parts, double t, double **times, long *kept,
                                         sd_error *err)
{
    *times = NULL;
    *kept = 0;
    char *path = sd_fs_join(dir, "frames.pvd");
    if (!path)
        return sd_error_set(err, SD_ERR_MEMORY, dir, 0, "", "out of memory");
    void *buf = NULL;
    size_t size = 0;
    sd_status s = SD_OK;
    if (sd_fs_is_regular_file(path))
        s = sd_fs_read_all(path, "frames.pvd", &buf, &size, err);
    sd_free(path);
    if (s != SD_OK || !buf)
        return s;
    char *text = buf;
    size_t sets = 0;
    for (const char *p = text; (p = strstr(p, "<DataSet ")) != NULL; ++p)
        ++sets;
    double *tt = sd_malloc((sets / parts + 1) * sizeof *tt);
    if (!tt) {
        sd_free(buf);
        return sd_error_set(err, SD_ERR_MEMORY, dir, 0, "", "out of memory");
    }
    size_t i = 0;
    int ok = sets % parts == 0;
    for (const char *p = text; ok && (p = strstr(p, "<DataSet ")) != NULL; ++p, ++i) {
        const char *ts = strstr(p, "timestep=\""), *fs = strstr(p, "file=\""), *end = strchr(p, '>');
        ok = ts && fs && end && ts < end && fs < end;
        if (!ok)
            break;
        double ti = strtod(ts + 10, NULL);
        long f = (long)(i / parts);
        char want[SD_OUTPUT_NAME_MAX];
        int part = (int)(i % parts);
        sd_output_frame_file(want, part, f);
        size_t wn = strlen(want);
        ok = !strncmp(fs + 6, want, wn) && fs[6 + wn] == '"' && (part == 0 || ti == tt[f]);
        if (ok && part == 0)
            tt[f] = ti;
    }
    long k = 0;
    while (ok && (size_t)k < sets / parts && tt[k] < t)
        ++k;
    sd_free(buf);
    if (k == 0)
        sd_free(tt);
    else
        *times = tt;
    *kept = k;
    return SD_OK;
}

/* ---- open ------------------------------------------------------------------ */

/* trajectory.dump, created new or on a restart continued after its
 * snapshots before the restart step. */
static sd_status sd_output_open_dump(sd_output *o, sd_error *err)
{
    char *path = sd_fs_join(o->dir, "trajectory.dump");
    if (!path)
        return sd_error_set(err, SD_ERR_MEMORY, o->dir, 0, "", "out of memory");
    int kept = 0;
    sd_status s = o->resume_step > 0
                      ? sd_fs_resume_series(path, o->resume_step, sd_dump_keep, &o->dump_frames, &o->dump, &kept, err)
                      : sd_fs_create_append(path, &o->dump, err);
    if (!kept)
        o->dump_frames = 0;
    sd_free(path);
    return s;
}

/* Frees o and what it holds (its files closed already). */
static void sd_output_free(sd_output *o)
{
    if (o->dump)
        fclose(o->dump);
    sd_h5md_close(o->h5md, NULL);
    sd_free(o->frame_times);
    sd_vtk_shapes_free(o->shapes);
    sd_free(o->scene);
    sd_free(o->dir);
    sd_free(o);
}

static sd_status sd_output_prepare_dir(const char *dir, int resume, long keep_frames, sd_error *err)
{
    sd_status s = sd_fs_mkdir_p(dir, err);
    if (s != SD_OK)
        return s;
    char *marker = sd_fs_join(dir, SD_OUTPUT_MARKER);
    if (!marker)
        return sd_error_set(err, SD_ERR_MEMORY, dir, 0, "", "out of memory");
    int marked = sd_fs_is_regular_file(marker);
    sd_free(marker);

    if (!marked) {
        sd_output_scan sc;
        memset(&sc, 0, sizeof sc);
        s = sd_fs_list_dir(dir, sd_output_scan_visit, &sc, err);
        if (s != SD_OK)
            return s;
        if (sc.entries > 0)
            return sd_error_set(err, SD_ERR_IO, dir, 0, SD_OUTPUT_KEY,
                                "the directory holds files shapedem did not write (e.g. '%s') and "
                                "has no " SD_OUTPUT_MARKER " marker; shapedem will not write there, "
                                "so nothing you made is lost: choose a new or empty directory",
                                sc.example ? sc.example : "?");
    } else {
        sd_output_clean c = {dir, resume, keep_frames, SD_OK, err};
        s = sd_fs_list_dir(dir, sd_output_clean_visit, &c, err);
        if (s != SD_OK)
            return s;
        if (c.status != SD_OK)
            return c.status;
    }

    sd_atomic_file af;
    s = sd_fs_atomic_begin(&af, dir, SD_OUTPUT_MARKER, err);
    if (s != SD_OK)
        return s;
    fprintf(af.fp,
            "This directory was written by shapedem %s.\n"
            "The next run writing here replaces particles_*.vtu, walls_*.vtp, shapes_*.vtp, frames.pvd,\n"
            "stats.csv, walls.csv, biaxial.csv, trajectory.dump, trajectory.h5md and summary.txt; any other\n"
            "file is left alone.\n",
            SD_VERSION_STRING);
    return sd_fs_atomic_commit(&af, err);
}

sd_status sd_output_open(const sd_output_def *def, const sd_world *w, sd_output **out, sd_error *err)
{
    if (!out)
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "sd_output_open: out is NULL");
    *out = NULL;
    if (!def || !def->directory || !def->directory[0])
        return sd_error_set(err, SD_ERR_INPUT, "", 0, SD_OUTPUT_KEY,
                            "no output directory given");
    double *kept_times = NULL;
    long kept = 0;
    sd_status s = SD_OK;
    if (def->resume_step > 0 && w && (def->vtk || def->shapes))
        s = sd_output_resume_frames(def->directory, def->shapes ? 3 : 2, sd_world_time(w), &kept_times, &kept, err);
    if (s == SD_OK)
        s = sd_output_prepare_dir(def->directory, def->resume_step > 0, kept, err);
    if (s != SD_OK) {
        sd_free(kept_times);
        return s;
    }
    sd_output *o = sd_calloc(1, sizeof *o);
    if (!o) {
        sd_free(kept_times);
        return sd_error_set(err, SD_ERR_MEMORY, def->directory, 0, "", "out of memory");
    }
    o->frames = kept;
    o->frame_times = kept_times;
    o->frame_cap = (size_t)kept;
    o->dir = sd_output_strdup(def->directory);
    o->scene = sd_output_strdup(def->scene ? def->scene : "");
    if (!o->dir || !o->scene) {
        sd_output_free(o);
        return sd_error_set(err, SD_ERR_MEMORY, def->directory, 0, "", "out of memory");
    }
    o->vtk = def->vtk || def->shapes;
    o->csv = def->csv;
    o->resume_step = def->resume_step;
    o->walls_csv = def->csv;
    o->dump_box = def->dump_box;
    if (def->dump)
        s = sd_output_open_dump(o, err);
    if (s == SD_OK && def->h5md) {
        char *path = sd_fs_join(o->dir, "trajectory.h5md");
        s = path ? sd_h5md_open(path, w, &def->dump_box, o->resume_step, &o->h5md, err)
                 : sd_error_set(err, SD_ERR_MEMORY, o->dir, 0, "", "out of memory");
        sd_free(path);
    }
    if (s == SD_OK && def->shapes) {
        s = sd_vtk_shapes_make(w, def->shape_resolution ? def->shape_resolution : 24, &o->shapes, err);
    }
    /* the kept frames only, those after the restart gone with their files */
    if (s == SD_OK && kept > 0)
        s = sd_output_write_pvd(o, err);
    if (s != SD_OK) {
        sd_output_free(o);
        return s;
    }
    *out = o;
    return SD_OK;
}

/* ---- frames ---------------------------------------------------------------- */

/* The error from a writer names no file; give it the one being written. */
static sd_status sd_output_fail(sd_atomic_file *af, sd_status s, sd_error *err)
{
    if (err && !err->file[0] && af->final_path)
        snprintf(err->file, sizeof err->file, "%s", af->final_path);
    sd_fs_atomic_abort(af);
    return s;
}

static sd_status sd_output_write_pvd(sd_output *o, sd_error *err)
{
    size_t parts = o->shapes ? 3 : 2; /* particles, walls, and shapes when written */
    size_t n = parts * (size_t)o->frames;
    sd_vtk_dataset *sets = sd_malloc((n ? n : 1) * sizeof *sets);
    char *names = sd_malloc((n ? n : 1) * SD_OUTPUT_NAME_MAX);
    if (!sets || !names) {
        sd_free(sets);
        sd_free(names);
        return sd_error_set(err, SD_ERR_MEMORY, o->dir, 0, "", "out of memory");
    }
    for (long f = 0; f < o->frames; ++f) {
        for (int part = 0; part < (int)parts; ++part) {
            size_t k = parts * (size_t)f + (size_t)part;
            char *name = names + SD_OUTPUT_NAME_MAX * k;
            sd_output_frame_file(name, part, f);
            sets[k].time = o->frame_times[f];
            sets[k].part = part;
            sets[k].file = name;
        }
    }
    sd_atomic_file af;
    sd_status s = sd_fs_atomic_begin(&af, o->dir, "frames.pvd", err);
    if (s == SD_OK) {
        s = sd_vtk_write_collection(af.fp, n, sets, err);
        s = (s == SD_OK) ? sd_fs_atomic_commit(&af, err) : sd_output_fail(&af, s, err);
    }
    sd_free(sets);
    sd_free(names);
    return s;
}

long sd_output_frame_count(const sd_output *o)
{
    return !o ? 0 : o->vtk ? o->frames : o->dump ? o->dump_frames : sd_h5md_frames(o->h5md);
}

/* One snapshot appended to trajectory.dump, flushed whole. */
static sd_status sd_output_dump(sd_output *o, const sd_world *w, sd_error *err)
{
    sd_status s = sd_dump_write(o->dump, w, &o->dump_box, err);
    if (s == SD_OK && (fflush(o->dump) != 0 || ferror(o->dump)))
        s = sd_error_set(err, SD_ERR_IO, "", 0, "", "write failed: %s", strerror(errno));
    if (s != SD_OK && err && !err->file[0])
        snprintf(err->file, sizeof err->file, "%s/trajectory.dump", o->dir);
    if (s == SD_OK)
        o->dump_frames++;
    return s;
}

sd_status sd_output_frame(sd_output *o, const sd_world *w, sd_error *err)
{
    if (!o || !w)
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "sd_output_frame: NULL argument");
    if (o->dump) {
        sd_status s = sd_output_dump(o, w, err);
        if (s != SD_OK)
            return s;
    }
    if (o->h5md) {
        sd_status s = sd_h5md_write(o->h5md, w, err);
        if (s != SD_OK)
            return s;
    }
    if (!o->vtk)
        return SD_OK;
    if ((size_t)o->frames == o->frame_cap) {
        size_t cap = o->frame_cap ? 2 * o->frame_cap : 64;
        double *t = sd_realloc(o->frame_times, cap * sizeof *t);
        if (!t)
            return sd_error_set(err, SD_ERR_MEMORY, o->dir, 0, "", "out of memory");
        o->frame_times = t;
        o->frame_cap = cap;
    }
    char name[SD_OUTPUT_NAME_MAX];
    sd_atomic_file af;

    sd_output_frame_file(name, 0, o->frames);
    sd_status s = sd_fs_atomic_begin(&af, o->dir, name, err);
    if (s != SD_OK)
        return s;
    s = sd_vtk_write_particles(af.fp, w, err);
    s = (s == SD_OK) ? sd_fs_atomic_commit(&af, err) : sd_output_fail(&af, s, err);
    if (s != SD_OK)
        return s;

    sd_output_frame_file(name, 1, o->frames);
    s = sd_fs_atomic_begin(&af, o->dir, name, err);
    if (s != SD_OK)
        return s;
    s = sd_vtk_write_walls(af.fp, w, sd_vtk_plane_side(w), err);
    s = (s == SD_OK) ? sd_fs_atomic_commit(&af, err) : sd_output_fail(&af, s, err);
    if (s != SD_OK)
        return s;

    if (o->shapes) {
        sd_output_frame_file(name, 2, o->frames);
        s = sd_fs_atomic_begin(&af, o->dir, name, err);
        if (s != SD_OK)
            return s;
        s = sd_vtk_write_shapes(af.fp, w, o->shapes, err);
        s = (s == SD_OK) ? sd_fs_atomic_commit(&af, err) : sd_output_fail(&af, s, err);
        if (s != SD_OK)
            return s;
    }

    o->frame_times[o->frames++] = sd_world_time(w);
    return sd_output_write_pvd(o, err);
}

/* ---- stats.csv -------------------------------------------------------------- */

static int sd_output_is_identifier(const char *s)
{
    if (!s || !s[0] || strlen(s) > 64)
        return 0;
    for (size_t i = 0; s[i]; ++i) {
        char c = s[i];
        int alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
        int digit = c >= '0' && c <= '9';
        if (!alpha && !(digit && i > 0))
            return 0;
    }
    return 1;
}

#define SD_OUTPUT_PREFIX_MAX 80

/* Column prefix for each wall: its name when that is an identifier not taken
 * by an earlier wall, else wall<index> (made unique the same way). */
static sd_status sd_output_wall_prefixes(const sd_world *w, size_t nw, char *pre, sd_error *err)
{
    for (size_t i = 0; i < nw; ++i) {
        sd_wall_info wi;
        sd_status s = sd_world_get_wall(w, i, &wi);
        if (s != SD_OK)
            return sd_error_set(err, s, "", 0, "", "cannot read wall %zu of the world", i);
        char *p = pre + i * SD_OUTPUT_PREFIX_MAX;
        if (sd_output_is_identifier(wi.name))
            snprintf(p, SD_OUTPUT_PREFIX_MAX, "%s", wi.name);
        else
            snprintf(p, SD_OUTPUT_PREFIX_MAX, "wall%zu", i);
        for (int attempt = 0;; ++attempt) {
            int taken = 0;
            for (size_t j = 0; j < i && !taken; ++j)
                taken = strcmp(p, pre + j * SD_OUTPUT_PREFIX_MAX) == 0;
            if (!taken)
                break;
            if (attempt == 0)
                snprintf(p, SD_OUTPUT_PREFIX_MAX, "wall%zu", i);
            else
                snprintf(p, SD_OUTPUT_PREFIX_MAX, "wall%zu_%d", i, attempt);
        }
    }
    return SD_OK;
}

/* One value of a solver item (world/solver.h): counts as integers, the
 * rest with ten significant digits, as every other number we write. */
static void sd_solver_value_print(FILE *fp, const char *before, const sd_solver_item *it, int v)
{
    if (it->integer)
        fprintf(fp, "%s%lld", before, (long long)it->v[v]);
    else
        fprintf(fp, "%s%.10g", before, it->v[v]);
}

/* A CSV series of the run: created new, or on a restart continued after
 * its rows before the restart step (*kept: its header is there already). */
static sd_status sd_output_open_csv(const sd_output *o, const char *path, FILE **fp, int *kept, sd_error *err)
{
    *kept = 0;
    if (o->resume_step > 0)
        return sd_fs_resume_csv(path, o->resume_step, fp, kept, err);
    return sd_fs_create_append(path, fp, err);
}

/* stats.csv's header; with write 0 (a continued file has it) only the
 * column counts the rows follow. */
static sd_status sd_output_stats_header(sd_output *o, const sd_world *w, size_t nw, int write, sd_error *err)
{
    FILE *fp = write ? o->stats : NULL;
    char *pre = sd_malloc((nw ? nw : 1) * SD_OUTPUT_PREFIX_MAX);
    if (!pre)
        return sd_error_set(err, SD_ERR_MEMORY, o->dir, 0, "", "out of memory");
    sd_status s = sd_output_wall_prefixes(w, nw, pre, err);
    if (s == SD_OK) {
        if (fp)
            fprintf(fp, "step,time,kinetic_translational,kinetic_rotational,potential_gravity,"
                        "potential_elastic,total_energy,contacts,wall_contacts,"
                        "max_overlap_ratio,max_speed,rebuilds");
        for (size_t i = 0; i < nw && fp; ++i) {
            const char *p = pre + i * SD_OUTPUT_PREFIX_MAX;
            fprintf(fp, ",%s_fx,%s_fy,%s_fz,%s_tx,%s_ty,%s_tz", p, p, p, p, p, p);
        }
        /* the solver's own columns (the grid's pouring, outlet, cell
         * conflicts): fixed from here on, the world being prepared */
        sd_solver_item it[SD_SOLVER_ITEMS_MAX];
        size_t ni = sd_world_solver_items(w, it, SD_SOLVER_ITEMS_MAX);
        o->stats_solver = 0;
        for (size_t i = 0; i < ni; ++i)
            if (it[i].column) {
                if (fp)
                    fprintf(fp, ",%s", it[i].column);
                o->stats_solver++;
            }
        if (fp)
            fputc('\n', fp);
        o->stats_walls = nw;
    }
    sd_free(pre);
    return s;
}

/* biaxial.csv: one row per stats row when the world is a 2D box of four
 * plane walls (seed 002 §3.2; columns in docs/output.md). Appended and
 * flushed like stats.csv. */
static sd_status sd_output_biaxial(sd_output *o, const sd_world *w, sd_error *err)
{
    sd_biaxial b;
    if (sd_world_biaxial(w, &b) != SD_OK)
        return SD_OK;
    sd_status s = SD_OK;
    char *path = sd_fs_join(o->dir, "biaxial.csv");
    if (!path)
        return sd_error_set(err, SD_ERR_MEMORY, o->dir, 0, "", "out of memory");
    if (!o->biaxial) {
        /* created, never opened through a link (fsutil.h) */
        int kept;
        if ((s = sd_output_open_csv(o, path, &o->biaxial, &kept, err)) != SD_OK)
            goto done;
        if (!kept)
            fputs(SD_OUTPUT_BIAXIAL_HEADER, o->biaxial);
    }
    fprintf(o->biaxial, "%ld,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", sd_world_step_count(w),
            sd_world_time(w), b.width, b.height, b.sigma_xx, b.sigma_yy, b.strain_axial, b.strain_lateral,
            b.strain_volumetric, b.stress_ratio);
    if (fflush(o->biaxial) != 0 || ferror(o->biaxial))
        s = sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot write: %s", strerror(errno));
done:
    sd_free(path);
    return s;
}

/* walls.csv: one row per stats row when the world has walls: step, time,
 * then for each wall (stats.csv's prefixes) the force the particles exert
 * on it and its torque about the wall's torque point (sd_world_get_wall:
 * a mesh's torque_point, moved with the mesh; else the reference point).
 * Appended and flushed like stats.csv. */
static sd_status sd_output_walls(sd_output *o, const sd_world *w, sd_error *err)
{
    size_t nw = sd_world_wall_count(w);
    if (nw == 0)
        return SD_OK;
    sd_status s = SD_OK;
    char *path = sd_fs_join(o->dir, "walls.csv");
    if (!path)
        return sd_error_set(err, SD_ERR_MEMORY, o->dir, 0, "", "out of memory");
    if (!o->walls) {
        char *pre = sd_malloc(nw * SD_OUTPUT_PREFIX_MAX);
        if (!pre) {
            s = sd_error_set(err, SD_ERR_MEMORY, o->dir, 0, "", "out of memory");
            goto done;
        }
        s = sd_output_wall_prefixes(w, nw, pre, err);
        /* created, never opened through a link (fsutil.h) */
        int kept = 0;
        if (s == SD_OK)
            s = sd_output_open_csv(o, path, &o->walls, &kept, err);
        if (s == SD_OK && !kept) {
            fputs("step,time", o->walls);
            for (size_t i = 0; i < nw; ++i) {
                const char *p = pre + i * SD_OUTPUT_PREFIX_MAX;
                fprintf(o->walls, ",%s_fx,%s_fy,%s_fz,%s_tx,%s_ty,%s_tz", p, p, p, p, p, p);
            }
            fputc('\n', o->walls);
        }
        sd_free(pre);
        if (s != SD_OK)
            goto done;
    }
    fprintf(o->walls, "%ld,%.10g", sd_world_step_count(w), sd_world_time(w));
    for (size_t i = 0; i < nw; ++i) {
        sd_wall_info wi;
        if (sd_world_get_wall(w, i, &wi) != SD_OK) {
            memset(&wi, 0, sizeof wi); /* keep the column count */
            s = sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "cannot read wall %zu", i);
        }
        fprintf(o->walls, ",%.10g,%.10g,%.10g,%.10g,%.10g,%.10g", wi.force.x, wi.force.y, wi.force.z, wi.torque.x,
                wi.torque.y, wi.torque.z);
    }
    fputc('\n', o->walls);
    if (fflush(o->walls) != 0 || ferror(o->walls))
        s = sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot write: %s", strerror(errno));
done:
    sd_free(path);
    return s;
}

sd_status sd_output_stats(sd_output *o, const sd_world *w, sd_error *err)
{
    if (!o || !w)
        return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "sd_output_stats: NULL argument");
    if (!o->csv)
        return SD_OK;
    char *path = sd_fs_join(o->dir, "stats.csv");
    if (!path)
        return sd_error_set(err, SD_ERR_MEMORY, o->dir, 0, "", "out of memory");
    sd_status s = SD_OK;
    size_t nw = sd_world_wall_count(w);
    if (!o->stats) {
        /* Append mode: a write can never truncate earlier rows. Created
         * new (the previous run's file was removed at open), or on a
         * restart continued after its rows before the restart step; never
         * opened through a link (fsutil.h). */
        int kept;
        if ((s = sd_output_open_csv(o, path, &o->stats, &kept, err)) != SD_OK)
            goto done;
        s = sd_output_stats_header(o, w, nw, !kept, err);
        if (s != SD_OK)
            goto done;
    } else if (nw != o->stats_walls) {
        s = sd_error_set(err, SD_ERR_INPUT, path, 0, "",
                         "the world has %zu walls but stats.csv was started with %zu; "
                         "walls must be added before the first stats row",
                         nw, o->stats_walls);
        goto done;
    }

    sd_stats st;
    sd_world_stats(w, &st);
    double total = st.kinetic_translational + st.kinetic_rotational + st.potential_gravity +
                   st.potential_elastic;
    fprintf(o->stats, "%ld,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%ld,%ld,%.10g,%.10g,%ld", st.step,
            st.time, st.kinetic_translational, st.kinetic_rotational, st.potential_gravity,
            st.potential_elastic, total, st.contacts, st.wall_contacts, st.max_overlap_ratio,
            st.max_speed, st.rebuilds);
    for (size_t i = 0; i < nw; ++i) {
        sd_wall_info wi;
        if (sd_world_get_wall(w, i, &wi) != SD_OK) {
            /* Keep the column count: the row stays well-formed. */
            memset(&wi, 0, sizeof wi);
            s = sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "cannot read wall %zu", i);
        }
        /* the torque about the wall's reference point (a plane's point, a
         * box's centre), summed by each solver in a fixed order */
        fprintf(o->stats, ",%.10g,%.10g,%.10g,%.10g,%.10g,%.10g", wi.force.x, wi.force.y, wi.force.z, wi.torque.x,
                wi.torque.y, wi.torque.z);
    }
    if (o->stats_solver) {
        sd_solver_item it[SD_SOLVER_ITEMS_MAX];
        size_t ni = sd_world_solver_items(w, it, SD_SOLVER_ITEMS_MAX), nc = 0;
        for (size_t i = 0; i < ni && nc < o->stats_solver; ++i)
            if (it[i].column) {
                sd_solver_value_print(o->stats, ",", &it[i], 0);
                nc++;
            }
        for (; nc < o->stats_solver; ++nc) /* keep the column count: the row stays well-formed */
            fputs(",0", o->stats);
    }
    fputc('\n', o->stats);
    if (fflush(o->stats) != 0 || ferror(o->stats)) {
        s = sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot write: %s", strerror(errno));
        goto done;
    }
    o->stats_rows++;
    s = sd_output_biaxial(o, w, err);
    if (s == SD_OK && o->walls_csv)
        s = sd_output_walls(o, w, err);
done:
    sd_free(path);
    return s;
}

/* ---- close and summary.txt -------------------------------------------------- */

static void sd_output_summary_text(FILE *fp, const sd_output *o, const sd_world *w,
                                   const sd_run_summary *sum)
{
    const double mib = 1024.0 * 1024.0;
    fprintf(fp, "# shapedem %s run summary (SI units)\n", SD_VERSION_STRING);
    fprintf(fp, "scene: %s\n", o->scene[0] ? o->scene : "(none)");
    if (w) {
        fprintf(fp, "particles: %zu\n", sd_world_particle_count(w));
        fprintf(fp, "walls: %zu\n", sd_world_wall_count(w));
    }
    if (sum) {
        fprintf(fp, "steps_run: %ld\n", sum->steps);
        fprintf(fp, "start_step: %ld\n", sum->first); /* a restart's checkpoint step, else 0 */
    }
    if (w) {
        fprintf(fp, "step: %ld\n", sd_world_step_count(w));
        fprintf(fp, "time_step_s: %.10g\n", sd_world_dt(w));
        fprintf(fp, "simulated_time_s: %.10g\n", sd_world_time(w));
    }
    if (sum) {
        fprintf(fp, "wall_seconds: %.6g\n", sum->wall_seconds);
        fprintf(fp, "particle_steps_per_second: %.6g\n", sum->particle_steps_per_second);
        fprintf(fp, "threads: %d\n", sum->threads);
        if (w) /* which backend ran the step, and why (world/backend.c) */
            fprintf(fp, "backend: %s (%s)\n", sd_world_backend(w), sd_world_backend_note(w));
        fprintf(fp, "peak_memory_MiB: %.3f\n", (double)sum->peak_memory / mib);
        fprintf(fp, "peak_rss_MiB: %.3f\n", (double)sum->peak_rss / mib);
        if (sum->stop && sum->stop[0])
            fprintf(fp, "stop_when: %s\n", sum->stop);
        if (sum->note)
            fputs(sum->note, fp);
    }
    fprintf(fp, "frames: %ld\n", o->frames);
    fprintf(fp, "stats_rows: %ld\n", o->stats_rows);
    if (!w)
        return;
    sd_stats st;
    sd_world_stats(w, &st);
    fprintf(fp, "kinetic_translational_J: %.10g\n", st.kinetic_translational);
    fprintf(fp, "kinetic_rotational_J: %.10g\n", st.kinetic_rotational);
    fprintf(fp, "potential_gravity_J: %.10g\n", st.potential_gravity);
    fprintf(fp, "potential_elastic_J: %.10g\n", st.potential_elastic);
    fprintf(fp, "total_energy_J: %.10g\n", st.kinetic_translational + st.kinetic_rotational +
                                               st.potential_gravity + st.potential_elastic);
    fprintf(fp, "contacts: %ld\n", st.contacts);
    fprintf(fp, "wall_contacts: %ld\n", st.wall_contacts);
    fprintf(fp, "max_overlap_ratio: %.10g\n", st.max_overlap_ratio);
    fprintf(fp, "max_speed_m_per_s: %.10g\n", st.max_speed);
    fprintf(fp, "pair_list_rebuilds: %ld\n", st.rebuilds);
    /* the solver's own lines (solver grid: docs/grid-solver.md) */
    sd_solver_item it[SD_SOLVER_ITEMS_MAX];
    size_t ni = sd_world_solver_items(w, it, SD_SOLVER_ITEMS_MAX);
    for (size_t i = 0; i < ni; ++i) {
        fprintf(fp, "%s:", it[i].key);
        for (int v = 0; v < it[i].n; ++v)
            sd_solver_value_print(fp, v == 0 ? " " : it[i].sep, &it[i], v);
        fputc('\n', fp);
    }
    /* insertions and outlets of the cells solver (shapedem/process.h) */
    for (size_t i = 0; i < sd_world_insertion_count(w); ++i) {
        sd_insert_info ii;
        if (sd_world_get_insertion(w, i, &ii) == SD_OK)
            fprintf(fp, "insert %s: asked %zu, inserted %zu, mass_kg %.10g%s%s\n", ii.name, ii.asked, ii.inserted,
                    ii.mass, ii.inserted < ii.asked ? ", why: " : "", ii.inserted < ii.asked ? ii.why : "");
    }
    for (size_t i = 0; i < sd_world_outlet_count(w); ++i) {
        sd_outlet_info oi;
        if (sd_world_get_outlet(w, i, &oi) == SD_OK)
            fprintf(fp, "outlet %s: removed %zu, mass_kg %.10g\n", oi.name, oi.removed, oi.mass);
    }
    size_t nw = sd_world_wall_count(w);
    for (size_t i = 0; i < nw; ++i) {
        sd_wall_info wi;
        if (sd_world_get_wall(w, i, &wi) != SD_OK)
            continue;
        fprintf(fp, "wall %zu (%s) force_N: %.10g %.10g %.10g\n", i,
                wi.name && wi.name[0] ? wi.name : "unnamed", wi.force.x, wi.force.y, wi.force.z);
        fprintf(fp, "wall %zu (%s) torque_N_m: %.10g %.10g %.10g\n", i,
                wi.name && wi.name[0] ? wi.name : "unnamed", wi.torque.x, wi.torque.y, wi.torque.z);
    }
    /* convex narrow phase per pair type: mean GJK (+EPA) iterations and
     * support calls per evaluation over the whole run */
    sd_narrow_stats ns[64];
    size_t nn = sd_world_narrow_stats(w, ns, 64);
    for (size_t i = 0; i < nn && i < 64; ++i) {
        double ev = (double)ns[i].evaluations;
        if (ns[i].iterations == 0 && ns[i].contacts > 0) { /* planar mode: seed 002 Table 1 */
            long long apart = ns[i].evaluations - ns[i].contacts;
            fprintf(fp, "narrow_phase %s-%s: evaluations %lld, mean_support_calls %.3f, contact %lld with "
                        "mean_support_calls %.3f, no_contact %lld with mean_support_calls %.3f\n",
                    ns[i].kind_a, ns[i].kind_b, ns[i].evaluations, (double)ns[i].support_calls / ev,
                    ns[i].contacts, (double)ns[i].contact_support_calls / (double)ns[i].contacts, apart,
                    apart > 0 ? (double)(ns[i].support_calls - ns[i].contact_support_calls) / (double)apart : 0.0);
            continue;
        }
        fprintf(fp, "narrow_phase %s-%s: evaluations %lld, mean_iterations %.3f, mean_support_calls %.3f\n",
                ns[i].kind_a, ns[i].kind_b, ns[i].evaluations, (double)ns[i].iterations / ev,
                (double)ns[i].support_calls / ev);
    }
    /* wall time per stage of the step (sd_profile), up to this summary */
    sd_profile pr;
    sd_world_profile(w, &pr);
    for (int k = 0; k < SD_PROFILE_STAGE_COUNT; ++k)
        if (pr.calls[k] > 0 || pr.seconds[k] > 0)
            fprintf(fp, "profile %s: seconds %.6g, calls %lld\n", sd_profile_stage_name(k), pr.seconds[k],
                    pr.calls[k]);
}

/* Closes one of the appended series (*fp NULL when it was never opened);
 * the first failure is the one *s keeps. */
static void sd_output_close_file(const sd_output *o, FILE **fp, const char *name, sd_status *s, sd_error *err)
{
    if (!*fp)
        return;
    if (fclose(*fp) != 0 && *s == SD_OK)
        *s = sd_error_set(err, SD_ERR_IO, o->dir, 0, "", "cannot close %s: %s", name, strerror(errno));
    *fp = NULL;
}

sd_status sd_output_close(sd_output *o, const sd_world *w, const sd_run_summary *sum, sd_error *err)
{
    if (!o)
        return SD_OK;
    sd_status s = SD_OK;
    sd_output_close_file(o, &o->stats, "stats.csv", &s, err);
    sd_output_close_file(o, &o->biaxial, "biaxial.csv", &s, err);
    sd_output_close_file(o, &o->walls, "walls.csv", &s, err);
    sd_output_close_file(o, &o->dump, "trajectory.dump", &s, err);
    sd_status sh = sd_h5md_close(o->h5md, s == SD_OK ? err : NULL);
    o->h5md = NULL;
    if (s == SD_OK)
        s = sh;
    /* The first error is the one reported. */
    sd_error err2;
    sd_error *e2 = (s == SD_OK) ? err : &err2;
    sd_atomic_file af;
    sd_status s2 = sd_fs_atomic_begin(&af, o->dir, "summary.txt", e2);
    if (s2 == SD_OK) {
        sd_output_summary_text(af.fp, o, w, sum);
        s2 = sd_fs_atomic_commit(&af, e2);
    }
    if (s == SD_OK)
        s = s2;
    sd_output_free(o);
    return s;
}

/* ---- size estimate (shapedem check) ------------------------------------------ */

/* Bytes written to a memory stream by the writers themselves, so the
 * estimate follows any change of format: a walls frame, the stats header
 * and one row of the world as it is, summary.txt, and the lines of
 * frames.pvd. Rows and pvd lines vary by a few digits over a run. */
sd_status sd_output_estimate(const sd_output_def *def, const sd_world *w, size_t particles, long frames,
                             long rows, double end_time, sd_output_size *out, sd_error *err)
{
    memset(out, 0, sizeof *out);
    sd_output o;
    memset(&o, 0, sizeof o);
    o.dir = (char *)".";
    o.scene = (char *)(def && def->scene ? def->scene : "");
    o.vtk = def ? def->vtk : 1;
    o.csv = def ? def->csv : 1;
    o.frames = frames;
    char *buf[4] = {NULL, NULL, NULL, NULL};
    size_t len[4] = {0, 0, 0, 0};
    FILE *fp[4] = {NULL, NULL, NULL, NULL};
    sd_status s = SD_OK;
    for (int k = 0; k < 4; ++k)
        if (!(fp[k] = open_memstream(&buf[k], &len[k])))
            s = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    if (s == SD_OK && o.vtk) {
        out->frame_particles = (double)sd_vtk_particles_bytes(w, particles);
        s = sd_vtk_write_walls(fp[0], w, sd_vtk_plane_side(w), err);
        fflush(fp[0]);
        out->frame_walls = (double)ftell(fp[0]);
        /* frames.pvd: its fixed part, then two DataSet lines per frame */
        sd_vtk_dataset sets[2] = {{end_time, 0, "particles_000000.vtu"}, {end_time, 1, "walls_000000.vtp"}};
        rewind(fp[0]);
        if (s == SD_OK)
            s = sd_vtk_write_collection(fp[0], 0, sets, err);
        double fixed = (double)ftell(fp[0]);
        rewind(fp[0]);
        if (s == SD_OK)
            s = sd_vtk_write_collection(fp[0], 2, sets, err);
        out->pvd = fixed + (double)frames * ((double)ftell(fp[0]) - fixed);
    }
    if (s == SD_OK && o.vtk && def && def->shapes) {
        /* the shapes file of the world as it is, per particle times the
         * particles a frame will hold (inserted ones like those present) */
        sd_vtk_shapes *t = NULL;
        s = sd_vtk_shapes_make(w, def->shape_resolution ? def->shape_resolution : 24, &t, err);
        rewind(fp[0]);
        if (s == SD_OK)
            s = sd_vtk_write_shapes(fp[0], w, t, err);
        sd_vtk_shapes_free(t);
        fflush(fp[0]);
        size_t n = sd_world_particle_count(w);
        out->frame_shapes = n ? (double)ftell(fp[0]) * (double)particles / (double)n : 0.0;
    }
    if (s == SD_OK && def && def->dump) {
        /* a snapshot of the world as it is, per particle times `particles` */
        rewind(fp[0]);
        s = sd_dump_write(fp[0], w, &def->dump_box, err);
        fflush(fp[0]);
        size_t n = sd_world_particle_count(w);
        out->frame_dump = n ? (double)ftell(fp[0]) * (double)particles / (double)n : (double)ftell(fp[0]);
    }
    if (s == SD_OK && def && def->h5md) {
        /* the values of a frame: 3 vectors of the dimension, a quaternion, a
         * spin, the radius (doubles), species, shape (4 bytes), id (8), and
         * the step and time; HDF5's chunk index adds a little */
        double d = def->dump_box.dimension == 2 ? 2.0 : 3.0;
        out->frame_h5md = (double)particles * (8.0 * (3.0 * d + 8.0) + 16.0) + 16.0;
    }
    if (s == SD_OK && o.csv) {
        o.stats = fp[1];
        o.biaxial = fp[2];
        s = sd_output_stats_header(&o, w, sd_world_wall_count(w), 1, err);
        out->stats_header = (double)ftell(fp[1]);
        if (s == SD_OK)
            s = sd_output_stats(&o, w, err);
        out->stats_row = (double)ftell(fp[1]) - out->stats_header;
        long brow = ftell(fp[2]);
        if (brow > 0) { /* a biaxial world: biaxial.csv gets a row per stats row */
            out->biaxial_header = (double)strlen(SD_OUTPUT_BIAXIAL_HEADER);
            out->biaxial_row = (double)brow;
        }
    }
    if (s == SD_OK && o.csv && sd_world_wall_count(w) > 0) {
        /* walls.csv: its header with the first row, then a second row */
        o.walls = fp[3];
        s = sd_output_walls(&o, w, err);
        double first = (double)ftell(fp[3]);
        if (s == SD_OK)
            s = sd_output_walls(&o, w, err);
        out->walls_row = (double)ftell(fp[3]) - first;
        out->walls_header = first - out->walls_row;
    }
    if (s == SD_OK) {
        rewind(fp[0]);
        o.stats_rows = rows;
        sd_run_summary sum;
        memset(&sum, 0, sizeof sum);
        sd_output_summary_text(fp[0], &o, w, &sum);
        out->summary = (double)ftell(fp[0]);
    }
    for (int k = 0; k < 4; ++k) {
        if (fp[k])
            fclose(fp[k]);
        free(buf[k]);
    }
    if (s != SD_OK)
        return s;
    double nf = o.vtk ? (double)frames : 0.0, nr = o.csv ? (double)rows : 0.0;
    out->total = nf * (out->frame_particles + out->frame_walls + out->frame_shapes) + (double)frames * (out->frame_dump + out->frame_h5md) +
                 out->pvd + out->stats_header +
                 nr * out->stats_row + (out->biaxial_row > 0 ? out->biaxial_header + nr * out->biaxial_row : 0.0) +
                 (out->walls_row > 0 ? out->walls_header + nr * out->walls_row : 0.0) +
                 out->summary + (double)sizeof "This directory was written by shapedem" + 160.0;
    return SD_OK;
}
