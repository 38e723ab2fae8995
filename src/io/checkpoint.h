/* checkpoint.h — HDF5 checkpoints of a world's state (issue 17; the layout
 * is docs/checkpoints.md, readable from h5py).
 *
 * A checkpoint is an HDF5 file (Debian's libhdf5) made in memory, then
 * written under a temporary name, flushed, fsync'ed and renamed into place
 * (io/fsutil.h): a kill at any moment leaves the previous checkpoint whole.
 * Each state array of world/snapshot.h is one dataset "/group/name"
 * ((rows,) or (rows, values per row)); the root's attributes hold the
 * format name and version, the scene's hash, the step, the time and a
 * checksum of every dataset's bytes. A 512-byte user block before the
 * HDF5 data holds a header with the file's size and a checksum of all its
 * bytes, checked before HDF5 reads any of them (HDF5's own metadata checks
 * miss some damage, and libhdf5 1.10.8 mishandled one such file).
 *
 * The reader is context-free: bytes (a file or a buffer) in, a snapshot or
 * a message out, no world needed (the fuzz target calls
 * sd_checkpoint_decode). Whatever the bytes, it either refuses them with a
 * reason (not HDF5, truncated, another format or version, a dataset of an
 * unknown type or shape, sizes beyond the file, a checksum that does not
 * match) or returns the snapshot that was written.
 */
#ifndef SD_IO_CHECKPOINT_H
#define SD_IO_CHECKPOINT_H

#include <shapedem/shapedem.h>

#include "world/snapshot.h"

/* The HDF5 image of a snapshot, in *buf (sd_malloc'd, *size bytes). */
sd_status sd_checkpoint_encode(const sd_snapshot *s, void **buf, size_t *size, sd_error *err);

/* Reads an image into out (initialised here; free with sd_snapshot_free,
 * also after an error). The checksum is verified. */
sd_status sd_checkpoint_decode(const void *buf, size_t size, sd_snapshot *out, sd_error *err);

/* The same for a file; err names the path. */
sd_status sd_checkpoint_read_file(const char *path, sd_snapshot *out, sd_error *err);

/* 1 when the file at path starts with a checkpoint's header (its magic
 * only: the file may still be damaged), 0 otherwise or unreadable. */
int sd_checkpoint_is_file(const char *path);

/* Writes a snapshot to path atomically (temporary name, fsync, rename). */
sd_status sd_checkpoint_write_file(const sd_snapshot *s, const char *path, sd_error *err);

/* ---- one file written by every MPI process together (mpi/ckpt.c) ---------- */

/* What this process writes of one dataset: the dataset has `rows` rows in
 * the file; this process writes nseg runs of them, run k being rows
 * seg[2k] .. seg[2k] + seg[2k + 1] - 1, whose values are the snapshot
 * item's rows in turn (the item's count is the sum of the runs). */
typedef struct sd_ckpt_part {
    size_t rows;
    size_t nseg;
    const size_t *seg;
} sd_ckpt_part;

/* 1 when this build writes checkpoints collectively through MPI-IO (the
 * library compiled against a parallel HDF5, SHAPEDEM_HDF5_MPIIO: the
 * shapedem-mpi program), 0 otherwise (rank 0 then writes alone). */
int sd_checkpoint_collective(void);

/* Collective over MPI_COMM_WORLD: every process passes the same list of
 * items (names, types, values per row, in the same order), the same
 * header (step, time, checksum of the whole data, ...) and its parts[k]
 * of each item; the file is written under a temporary name through
 * MPI-IO, then rank 0 seals it (the header's size and checksum), flushes
 * it and renames it into place after every process has closed it. The
 * status is the same on every process; err is filled on rank 0. Returns
 * SD_ERR_INTERNAL where sd_checkpoint_collective() is 0. */
sd_status sd_checkpoint_write_collective(const sd_snapshot *s, const sd_ckpt_part *parts, const char *path,
                                         sd_error *err);

/* Before a first HDF5 call: HDF5 prints no error stack (unless SD_HDF5_DEBUG=1
 * in the environment) and has no exit handler (io/checkpoint.c says why);
 * the trajectory writer (io/h5md.c) calls it too. */
void sd_h5_quiet(void);

#endif
