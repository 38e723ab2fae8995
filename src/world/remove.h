/* remove.h — taking particles out of a cells world between steps (issue
 * 16: outlets; issue 17: particles that leave the domain).
 *
 * Internal to the library (the public outlets and insertion go through
 * shapedem.h). See remove.c for the invariant it keeps.
 */
#ifndef SD_WORLD_REMOVE_H
#define SD_WORLD_REMOVE_H

#include <shapedem/shapedem.h>

#include <stdint.h>

/* What a removal took out: particles and their mass (kg; fixed bodies,
 * inverse mass 0, count in `count` but add no mass), summed in storage
 * order. */
typedef struct sd_remove_result {
    size_t count;
    double mass;
} sd_remove_result;

/* Removes the owned particles k < sd_cells_count(w) with mark[k] != 0
 * (mark indexed by storage index), and their periodic images. Survivors
 * keep their relative storage order and stable ids; the pair lists and
 * their history are compacted with them and the next step rebuilds the
 * lists. out (may be NULL) gets what went. Cells solver only: the grid
 * solver has its own outlet (SD_ERR_INPUT otherwise). Allocates a map of
 * 4 bytes per particle only when something is removed. */
sd_status sd_world_remove_particles(sd_world *w, const uint8_t *mark, sd_remove_result *out, sd_error *err);

/* The same with a predicate: particle k (storage index) goes when
 * pred(w, k, ctx) != 0. The predicate is called once per owned particle in
 * storage order, before anything moves. */
typedef int (*sd_remove_pred)(const sd_world *w, size_t k, void *ctx);
sd_status sd_world_remove_if(sd_world *w, sd_remove_pred pred, void *ctx, sd_remove_result *out, sd_error *err);

#endif
