/* csv.h — reads the particles of a csv generator (generator: csv, file:)
 * into the generator's entry list, as a list generator's entries.
 *
 * Context-free: it reads the CSV file named in g->file and the scene's
 * material and shape names (for the material and shape columns); it knows
 * nothing of the YAML parser. Errors name the CSV file and its line, with
 * key (particles[i].file) as the key; a file that cannot be opened is
 * reported at the scene's line file_line instead.
 */
#ifndef SD_IO_CSV_H
#define SD_IO_CSV_H

#include "io/scene.h"

sd_status sd_csv_read(const sd_scene *s, sd_scene_generator *g, const char *key, int file_line, sd_error *err);

/* What the two readers of a csv generator's file share (this one and the
 * checkpoint's, io/scene_from.c). */
/* "a, b, c": the names of the scene's shapes (not the hidden ones made for
 * a composite's elements or a checkpoint's scaled copies), or with
 * materials = 1 of its materials, for messages; "none" for none. */
const char *sd_csv_known(const sd_scene *s, int materials, char *buf, size_t size);
/* Grows g's entry arrays to cap entries: all or none grow, so that a
 * failure (0) leaves the list consistent; 1 when grown. */
int sd_csv_grow(sd_scene_generator *g, size_t cap);

#endif
