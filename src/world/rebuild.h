/* rebuild.h — the world's side of the broad phase (world/rebuild.c), on the
 * opaque world: the backend's rebuild stage calls it without seeing
 * sd_world's insides. */
#ifndef SD_WORLD_REBUILD_H
#define SD_WORLD_REBUILD_H

#include <shapedem/shapedem.h>

#include "core/vec.h"

/* Fills the broad phase's input (broad/bins.h), applies its particle
 * order, makes the ghosts and has the pair lists rebuilt with their
 * history carried by key; x_ref, q_ref and the wall marks follow. */
sd_status sd_world_rebuild(sd_world *w, sd_error *err);
/* The periodic axes of a world def are possible: not z in 2D, not with the
 * grid solver, a box with domain_hi > domain_lo on each (keys
 * "simulation.periodic", "simulation.domain"). */
sd_status sd_world_check_periodic_def(const sd_world_def *def, sd_error *err);
/* Wraps a position into the periodic box on the periodic axes (between
 * rebuilds an owned particle may stand up to half the skin outside it);
 * leaves it alone in a world without periodic axes. */
void sd_world_wrap_periodic(const sd_world *w, sd_v3d *x);
/* Room for ng ghosts after the owned particles: the ghost tables and the
 * particle arrays (periodic images here, other ranks' particles in
 * src/mpi/). */
sd_status sd_world_ghosts_reserve(sd_world *w, size_t ng);
/* The periodic images owned particle k takes at a rebuild, for the reach
 * band: their shifts (up to 7) in out (when not NULL), their count
 * returned (0 off the faces). */
int sd_world_periodic_images(const sd_world *w, size_t k, sd_real band, sd_vec3 *out);
/* The memory of the pair lists, bins and ghosts. */
void sd_world_broad_free(sd_world *w);

#endif
