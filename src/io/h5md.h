/* h5md.h — the trajectory as an H5MD file (trajectory.h5md): HDF5 in the
 * layout of H5MD 1.1, the particle-trajectory standard (docs/output.md;
 * cli.trajectory_h5md reads it with h5py).
 *
 * Invariant: every time-dependent element of /particles/all has as many
 * rows as the step and time datasets it shares with the others, one a
 * frame; particles in increasing stable id, the rows past a frame's count
 * (a frame after removals) at the fill value (NaN, id -1). The file is
 * flushed after each frame.
 */
#ifndef SD_IO_H5MD_H
#define SD_IO_H5MD_H

#include <shapedem/shapedem.h>
#include "io/dump.h" /* sd_dump_box */

typedef struct sd_h5md sd_h5md;

/* Creates path (nothing may be there), or with resume_step > 0 continues
 * the file there after its frames before that step; a file that is not
 * such a trajectory of a world of this dimension, or that HDF5 cannot open
 * (a crash inside a write), is replaced by a new one. */
sd_status sd_h5md_open(const char *path, const sd_world *w, const sd_dump_box *box, long resume_step, sd_h5md **out,
                       sd_error *err);
/* Appends a frame of w at its step and time. */
sd_status sd_h5md_write(sd_h5md *h, const sd_world *w, sd_error *err);
/* Frames in the file: written and, on a restart, kept. */
long sd_h5md_frames(const sd_h5md *h);
/* Closes and frees h (NULL: nothing). */
sd_status sd_h5md_close(sd_h5md *h, sd_error *err);

#endif
