/* poly.h — CPU loops of the volume laws (poly.c): polyhedron pairs and
 * polyhedron walls under SD_LAW_VOLUME / SD_LAW_VOLUME_LINEAR. */
#ifndef SD_BACKEND_CPU_POLY_H
#define SD_BACKEND_CPU_POLY_H

#include "geom/overlap.h"
#include "world/world.h"

/* 1 when pair e of the particle pair list (resp. wall pair list) has a
 * volume law for its two materials. */
int sd_cpu_pair_is_volume(const sd_world *w, size_t e);
int sd_cpu_wall_pair_is_volume(const sd_world *w, size_t e);
/* Evaluates pair e (a volume-law pair) with the calling thread's workspace. */
void sd_cpu_poly_pair(sd_world *w, size_t e, sd_overlap_workspace *ws);
/* Every volume-law wall pair (the wall loop of loops.c skips them). */
void sd_cpu_poly_wall_forces(sd_world *w);

#endif
