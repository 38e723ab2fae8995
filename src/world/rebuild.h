/* rebuild.h — the world's side of the broad phase (world/rebuild.c), on the
 * opaque world: the backend's rebuild stage calls it without seeing
 * sd_world's insides. */
#ifndef SD_WORLD_REBUILD_H
#define SD_WORLD_REBUILD_H

#include <shapedem/shapedem.h>

/* Fills the broad phase's input (broad/bins.h), applies its particle
 * order, makes the ghosts and has the pair lists rebuilt with their
 * history carried by key; x_ref, q_ref and the wall marks follow. */
sd_status sd_world_rebuild(sd_world *w, sd_error *err);
/* The memory of the pair lists, bins and ghosts. */
void sd_world_broad_free(sd_world *w);

#endif
