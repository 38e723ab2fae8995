/* view.h — the world's side of the backend views (world/view.c): fills
 * w->stage from the world's arrays, refreshes the wall copies, and brings
 * the wall totals back. */
#ifndef SD_WORLD_VIEW_H
#define SD_WORLD_VIEW_H

#include "world/world.h"

/* Refills every view (after prepare and after each rebuild). SD_ERR_MEMORY
 * when the wall copies cannot grow. */
sd_status sd_world_views(sd_world *w);
/* The world's step parameters (dt, gravity, damping) and walls into the
 * views again: at each sd_world_step call, so that a change made between
 * calls takes effect without a prepare. */
void sd_world_views_params(sd_world *w);
/* Copies the walls' geometry and velocity into their views (each step). */
void sd_world_views_walls(sd_world *w);
/* Copies the wall totals of the backend back into the world's walls. */
void sd_world_views_wall_totals(sd_world *w);
void sd_world_views_free(sd_world *w);

#endif
