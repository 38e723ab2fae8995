/* cells.h — the broad phase: cell grid, pair lists, rebuild criterion. */
#ifndef SD_BROAD_CELLS_H
#define SD_BROAD_CELLS_H

#include <shapedem/shapedem.h>

#include "broad/pairs.h"

/* Sorts the particles by cell and rebuilds both pair lists, carrying the
 * contact history by key. */
sd_status sd_broad_rebuild(sd_world *w, sd_error *err);
/* 1 when some particle moved more than half the skin since the last rebuild,
 * or particles were added. */
int sd_broad_needs_rebuild(const sd_world *w);
void sd_broad_free(sd_pair_list *l, sd_wall_pair_list *wl, sd_grid *g);

#endif
