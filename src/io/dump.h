/* dump.h — the trajectory as LAMMPS-style dump text (trajectory.dump),
 * the format OVITO, LAMMPS's read_dump, pizza.py/LPP and MDAnalysis read.
 *
 * Invariant: a snapshot is one block, ITEM: TIMESTEP / NUMBER OF ATOMS /
 * BOX BOUNDS / ATOMS with one line per particle in increasing stable id,
 * numbers at 17 significant digits (they read back to the same doubles);
 * a file cut inside a block (a crash) is recognised as such by
 * sd_dump_keep, which keeps only whole blocks.
 */
#ifndef SD_IO_DUMP_H
#define SD_IO_DUMP_H

#include <shapedem/shapedem.h>
#include <stdio.h>

/* What the box bounds say: the periodic axes (SD_PERIODIC_*) are the
 * periodic box domain_lo .. domain_hi ("pp"); the others the particles'
 * extent, radii included ("ss", shrink-wrapped in LAMMPS's words). */
typedef struct sd_dump_box {
    int dimension; /* the world's: 3, or 2 (the H5MD box, io/h5md.c) */
    unsigned periodic;
    sd_v3d domain_lo, domain_hi; /* m, read on the periodic axes */
} sd_dump_box;

/* The column names of the ATOMS line, after "ITEM: ATOMS ". */
#define SD_DUMP_COLUMNS "id type x y z vx vy vz fx fy fz omegax omegay omegaz radius quatw quati quatj quatk shape"

/* The particle of stable id `id` as the frames show it (the position of a
 * periodic image wrapped into the box); SD_ERR_INTERNAL when it is not
 * there. */
sd_status sd_dump_particle(const sd_world *w, uint64_t id, sd_particle_state *p, sd_error *err);

/* Appends one snapshot of w at its step count; SD_ERR_IO on a failed
 * write, SD_ERR_MEMORY when the id list cannot be allocated. */
sd_status sd_dump_write(FILE *fp, const sd_world *w, const sd_dump_box *box, sd_error *err);

/* For a restart at step (an sd_fs_keep_fn, io/fsutil.h): the bytes of text
 * (n bytes, a dump file) to keep, the whole blocks before the first with
 * TIMESTEP >= step, and their count in *(long *)blocks. Stops at the first
 * block that is not whole or not in this layout. */
long sd_dump_keep(const char *text, size_t n, long step, void *blocks);

#endif
