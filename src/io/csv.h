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

#endif
