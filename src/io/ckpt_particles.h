/* ckpt_particles.h — a checkpoint's particles as a table, for looking at a
 * run's state without HDF5 tools: `shapedem info CK.h5 --csv` lists them,
 * `shapedem render CK.h5` draws them (issue 31: a failed-NNNNNN.h5 could
 * not be looked at).
 *
 * Invariant: a table that reads without error has n rows in every column,
 * each row's shape index in [-1, shape_count) and material index in
 * [0, material_count), and a NUL-terminated name for each template and
 * material; a file that is not a checkpoint, is damaged (the reader's
 * checks, io/checkpoint.h) or lacks one of these columns is refused with a
 * message naming the file. The rows are the owned particles in storage
 * order (particles 0 .. particles/n - 1; a periodic run's images are not
 * listed), as the frame of the same step writes them, but for positions
 * in a periodic run: stored, not wrapped into the box as frames show them
 * (a checkpoint does not keep the domain; the scene does).
 */
#ifndef SD_IO_CKPT_PARTICLES_H
#define SD_IO_CKPT_PARTICLES_H

#include <stdint.h>
#include <stdio.h>

#include <shapedem/shapedem.h>

#include "world/snapshot.h"

typedef struct sd_ckpt_particles {
    size_t n;
    const double *x, *v, *w, *f; /* m, m/s, rad/s, N: 3 per row */
    const double *q;             /* unit quaternion w, x, y, z: 4 per row */
    const double *radius;        /* m (a shaped particle's bounding radius) */
    const uint64_t *id;
    const int32_t *shape;        /* template index, -1 for a plain sphere */
    const int32_t *material;
    size_t shape_count, material_count;
    char (*shape_names)[SD_SNAP_NAME], (*material_names)[SD_SNAP_NAME];
    long step;
    double time;                 /* s */
    int dimension;
    sd_snapshot snap;            /* owns the columns */
} sd_ckpt_particles;

/* Reads path's particles (out is set up here: free it with
 * sd_ckpt_particles_free, also after an error). */
sd_status sd_ckpt_particles_read(const char *path, sd_ckpt_particles *out, sd_error *err);
void sd_ckpt_particles_free(sd_ckpt_particles *p);

/* The same from a snapshot already read (sd_checkpoint_decode: the fuzz
 * target's buffers), which out takes over (*snap is left empty); path
 * names the source in messages. */
sd_status sd_ckpt_particles_take(sd_snapshot *snap, const char *path, sd_ckpt_particles *out, sd_error *err);

/* The table as CSV: a header, then one row per particle with every value
 * at full precision (%.17g: the bits of the checkpoint): id, x, y, z, vx,
 * vy, vz, wx, wy, wz, qw, qx, qy, qz, radius, shape (the template's name,
 * empty for a plain sphere), material (its name), fx, fy, fz (the contact
 * force of the last step). Names with a comma or a quote are quoted. */
sd_status sd_ckpt_particles_print_csv(FILE *f, const sd_ckpt_particles *p, sd_error *err);

#endif
