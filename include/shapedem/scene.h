/* scene.h — the public scene API: load a scene file, build its world, run
 * it and write its output, exactly as `shapedem run` does (the program
 * uses nothing else).
 *
 *     sd_scene *scene;
 *     sd_world *world;
 *     sd_run *run;
 *     sd_error err;
 *     if (sd_scene_load("settle.yaml", &scene, &err) != SD_OK) { ... err ... }
 *     if (sd_scene_build(scene, &world, &err) != SD_OK) { ... }
 *     if (sd_run_open(scene, world, "out/settle", &run, &err) != SD_OK) { ... }
 *     sd_status st = sd_run_advance(run, sd_scene_steps(scene), &err);
 *     sd_run_close(run, st == SD_OK ? &err : NULL);
 *     sd_world_destroy(world);
 *     sd_scene_free(scene);
 *
 * A scene is read-only data once loaded (but for the two overrides below);
 * the world it builds is an ordinary sd_world, stepped and queried through
 * shapedem.h. A run owns the output directory and the schedule of the
 * scene's output: section (frames every output.every steps and at the end,
 * stats.csv rows every output.stats_every steps, summary.txt at close).
 *
 * Invariant: every function returns an sd_status and fills err (file, line
 * and key of the scene for bad input); nothing prints. A run never writes
 * into a directory holding files it did not make, and every file it
 * writes is complete at every moment (temporary name, then rename).
 */
#ifndef SHAPEDEM_SCENE_H
#define SHAPEDEM_SCENE_H

#include <stdio.h>

#include <shapedem/shapedem.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- scenes --------------------------------------------------------------- */

typedef struct sd_scene sd_scene;

/* The most OpenMP threads simulation.threads and sd_scene_set_threads
 * take: far more than any node's cores, few enough that the thread stacks
 * (libgomp's default, 2-8 MiB each) stay within a machine's memory. */
#define SD_SCENE_MAX_THREADS 1024

/* Parses and checks a scene file (docs/scene-format.md). On error *out is
 * NULL and err names the file, line and key. */
sd_status sd_scene_load(const char *path, sd_scene **out, sd_error *err);
void sd_scene_free(sd_scene *s);

/* Builds the scene's world: materials, interactions, walls, shapes (scene
 * shape i is world shape i), the generated particles, and the pour and
 * outlet of the grid solver. Refuses overlaps at start, particles outside
 * the walls and an unstable time step, with file, line and key. The
 * caller destroys *out with sd_world_destroy. */
sd_status sd_scene_build(const sd_scene *s, sd_world **out, sd_error *err);

/* Overrides, applied before sd_scene_build (the CLI's --threads, --steps
 * and --backend): threads >= 1 replaces simulation.threads; steps >= 0
 * replaces the run length; a backend below SD_BACKEND_COUNT replaces
 * simulation.backend; device >= 0 is the CUDA device slot
 * (sd_world_def.device: under mpirun, the rank's node-local rank). */
void sd_scene_set_threads(sd_scene *s, int threads);
void sd_scene_set_steps(sd_scene *s, long steps);
void sd_scene_set_backend(sd_scene *s, sd_backend_kind backend);
void sd_scene_set_device(sd_scene *s, int device);

/* Steps of the run: simulation.steps, or duration / dt rounded up. */
long sd_scene_steps(const sd_scene *s);

/* What a program that runs or reports on a scene needs to know of it. */
typedef struct sd_scene_info {
    const char *path;             /* the scene file, as given to sd_scene_load */
    int dimension;                /* 3, or 2 (planar) */
    double dt;                    /* s */
    long steps;                   /* as sd_scene_steps */
    int threads;                  /* simulation.threads (0: OpenMP's default) */
    sd_solver solver;
    sd_contact_law law;           /* simulation.contact_law, the default of every pair */
    size_t material_count, shape_count, wall_count;
    long frame_every;             /* steps between frames (>= 1) */
    long stats_every;             /* steps between stats.csv rows (>= 1) */
    int write_frames;             /* output.formats has vtk */
    int write_stats;              /* output.formats has csv */
    const char *output_directory; /* output.directory, "" when not given */
    int has_pour, has_outlet;     /* pour: and outlet: (solver grid) */
} sd_scene_info;

void sd_scene_get_info(const sd_scene *s, sd_scene_info *out);

/* Names by index (NULL past the end), and the warning a shape's mesh file
 * left ("" when none; e.g. a nonconvex mesh taken as its hull). */
const char *sd_scene_material_name(const sd_scene *s, size_t i);
const char *sd_scene_shape_name(const sd_scene *s, size_t i);
const char *sd_scene_shape_warning(const sd_scene *s, size_t i);
/* A wall's name, and the repairs made to a mesh wall's file ("" when
 * none; e.g. degenerate facets dropped, wrongly wound ones turned). */
const char *sd_scene_wall_name(const sd_scene *s, size_t i);
const char *sd_scene_wall_warning(const sd_scene *s, size_t i);


/* The scene's pour: and outlet: (solver grid) as the world gets them
 * (sd_world_set_pour / sd_world_set_outlet): 1 and *out filled when the
 * scene has the section, else 0. */
int sd_scene_get_pour(const sd_scene *s, sd_pour_def *out);
int sd_scene_get_outlet(const sd_scene *s, sd_outlet_def *out);

/* The directory a run of the scene writes to when none is given:
 * output.directory, else out/<scene file name without extension>. */
void sd_scene_output_directory(const sd_scene *s, char *buf, size_t size);

/* Prints the table of every scene key (section, key, type, unit, default,
 * meaning) and the rules the table cannot say: `shapedem help scene`.
 * markdown = 1 prints docs/scene-format.md, with an example scene at the
 * top. It is the same table the parser checks against. */
void sd_scene_print_keys(FILE *f, int markdown);

/* ---- runs ----------------------------------------------------------------- */

typedef struct sd_run sd_run;

/* Opens a run of world w (built from s) writing to dir, which is made if
 * needed and must be empty or a former shapedem output directory; dir
 * NULL runs without writing anything (timing only). Nothing is written
 * until the first sd_run_advance. w stays the caller's; the run keeps a
 * pointer to it and to s until sd_run_close. */
sd_status sd_run_open(const sd_scene *s, sd_world *w, const char *dir, sd_run **out, sd_error *err);

/* Steps the world up to `steps` steps further, never past the scene's
 * steps, writing each frame and stats.csv row as it falls due. The first
 * call writes the step-0 frame and row first (so sd_run_advance(run, 0)
 * writes only those). On a stepping or writing error the run stops where
 * it is; sd_run_close still writes the summary. SD_ERR_INTERRUPTED
 * (sd_world_request_interrupt) is no error of the run: it stopped between
 * two steps, before the output due next, and may be advanced again or
 * checkpointed there (sd_run_checkpoint), as `shapedem run` does. */
sd_status sd_run_advance(sd_run *r, long steps, sd_error *err);

/* Writes a checkpoint of the run's world now (between steps), as
 * DIR/checkpoint-<step>.h5 (six digits or more): what the scene's
 * output.checkpoint_every and checkpoint_minutes do, and what `shapedem
 * run` does at SIGINT and SIGTERM. Nothing for a run without files. */
sd_status sd_run_checkpoint(sd_run *r, sd_error *err);
/* The path of the last checkpoint the run wrote, "" when none. */
const char *sd_run_last_checkpoint(const sd_run *r);

/* Steps from now to the next frame or stats row (or the end): what a
 * caller that checks for an interrupt between outputs advances by. */
long sd_run_steps_to_output(const sd_run *r);

typedef struct sd_run_progress {
    long done, steps;             /* the world's step now, and the run's end step */
    double time;                  /* s, simulated time of the world */
    double wall_seconds;          /* of stepping only */
    double particle_steps_per_second;
    int threads;
    int stopped;                  /* simulation.stop_when was met: steps is where it stopped */
    long first;                   /* the step the run started at (a restart: its checkpoint's);
                                   * done - first steps ran */
} sd_run_progress;

void sd_run_get_progress(const sd_run *r, sd_run_progress *out);

/* simulation.stop_when: "met at step N ..." or "not met (...)"; "" when
 * the scene has none. summary.txt's stop_when line. */
const char *sd_run_stop_note(const sd_run *r);

/* The directory written to ("" for a run without output). */
const char *sd_run_directory(const sd_run *r);

/* Writes summary.txt (when the run writes files) and frees r. err may be
 * NULL when the caller has an error to report already. */
sd_status sd_run_close(sd_run *r, sd_error *err);

/* ---- checkpoints (docs/checkpoints.md) ------------------------------------- */

/* Writes the world's complete state (particles, contact history, walls and
 * their motion, the solver's state, step and time) to path, an HDF5 file,
 * atomically: a temporary beside it, flushed, renamed. Between steps only. */
sd_status sd_checkpoint_write(const sd_world *w, const char *path, sd_error *err);

/* Puts a checkpoint's state into w, a world freshly built from the scene
 * that wrote it (sd_scene_build, not stepped): the next sd_world_step
 * continues that run bit for bit, with any thread count. Refuses (err says
 * why, nothing changed that matters: destroy w) a file that is not a
 * checkpoint, is truncated or damaged (checksum), of another format
 * version, or of another scene (its hash). */
sd_status sd_checkpoint_restore(sd_world *w, const char *path, sd_error *err);

/* Prints what a checkpoint holds (`shapedem info FILE.h5`), after the
 * same checks as a restore but for the scene's. */
sd_status sd_checkpoint_print(FILE *f, const char *path, sd_error *err);

#ifdef __cplusplus
}
#endif

#endif
