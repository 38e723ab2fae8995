/* output.h — what a run writes: VTK XML frames (.vtu particles, .vtp
 * walls) gathered in frames.pvd, stats.csv, walls.csv and summary.txt.
 *
 * Invariant: every file is written to a temporary name in the same
 * directory and renamed into place, so an interrupted run never leaves a
 * truncated file; frames.pvd is rewritten the same way after each frame.
 * trajectory.dump and trajectory.h5md are appended to, flushed per frame.
 * A directory that is not empty and was not made by shapedem (no
 * .shapedem-output marker) is never written into.
 */
#ifndef SD_IO_OUTPUT_H
#define SD_IO_OUTPUT_H

#include <shapedem/shapedem.h>
#include "io/dump.h"

typedef struct sd_output sd_output;

typedef struct sd_output_def {
    const char *directory;
    int vtk;            /* write frames */
    int csv;            /* write stats.csv */
    const char *scene;  /* scene path, recorded in the summary */
    int shapes;         /* with each frame, the true shapes (shapes_NNNNNN.vtp, io/vtk_shapes.c) */
    int shape_resolution; /* directions per turn of curved surfaces (0: 24) */
    int dump;           /* with each frame, a snapshot appended to trajectory.dump (io/dump.h) */
    int h5md;           /* with each frame, a frame appended to trajectory.h5md (io/h5md.h) */
    sd_dump_box dump_box; /* their box: the dimension and the periodic axes */
    long resume_step;   /* > 0: a restart at this step: stats.csv, walls.csv and biaxial.csv keep
                           their rows before it and go on (sd_fs_resume_csv), and the frames
                           (frames.pvd) those before it; 0: a new run */
} sd_output_def;

typedef struct sd_run_summary {
    long steps;               /* steps run (a restart: since its checkpoint) */
    double wall_seconds;      /* of stepping only */
    double particle_steps_per_second;
    int threads;
    size_t peak_memory;       /* bytes, shapedem allocator peak */
    size_t peak_rss;          /* bytes, process peak resident set */
    const char *stop;         /* simulation.stop_when: what happened, NULL or "" when not given */
    const char *note;         /* more lines (each ended by '\n'), NULL none: a decomposed run's ranks */
    long first;               /* the step the run started at (a restart: its checkpoint's) */
} sd_run_summary;

sd_status sd_output_open(const sd_output_def *def, const sd_world *w, sd_output **out, sd_error *err);
/* 1 when a run writes a file of this name in its directory: frames and
 * frames.pvd, the CSV series, outlet.csv, summary.txt, checkpoints
 * (checkpoint-N.h5, failed-N.h5), the .shapedem-output marker, and the
 * ".<name>.tmp" temporary of each; an analysis file may not take one. */
int sd_output_is_run_name(const char *name);
sd_status sd_output_frame(sd_output *o, const sd_world *w, sd_error *err);
/* Frames in the directory's series: written so far, and on a restart
 * those of the first part kept before the restart time. */
long sd_output_frame_count(const sd_output *o);
sd_status sd_output_stats(sd_output *o, const sd_world *w, sd_error *err);
/* What a run of the world w would write (shapedem check), in bytes: one
 * particle frame at `particles` particles, one walls frame, frames.pvd
 * after `frames` frames, the stats.csv header and a row, biaxial.csv's
 * (0 unless the world is a biaxial box), walls.csv's (0 without walls),
 * summary.txt, and the total for
 * `frames` frames and `rows` stats rows. Reads w as it is now; writes
 * nothing to disk. def gives the formats (NULL: both). */
typedef struct sd_output_size {
    double frame_particles, frame_walls, pvd;
    double frame_shapes; /* def->shapes: one shapes file, the world's particles scaled to `particles` */
    double frame_dump;   /* def->dump: one trajectory.dump snapshot, scaled the same way */
    double frame_h5md;   /* def->h5md: one trajectory.h5md frame, its values' bytes */
    double stats_header, stats_row, biaxial_header, biaxial_row;
    double walls_header, walls_row;   /* walls.csv (0 without walls) */
    double summary, total;
} sd_output_size;
sd_status sd_output_estimate(const sd_output_def *def, const sd_world *w, size_t particles, long frames,
                             long rows, double end_time, sd_output_size *out, sd_error *err);

/* Writes summary.txt and frees o (also on error). */
sd_status sd_output_close(sd_output *o, const sd_world *w, const sd_run_summary *sum, sd_error *err);

#endif
