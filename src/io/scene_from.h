/* scene_from.h — a csv generator's file that is a checkpoint of another
 * run (generator: csv, file: run/checkpoint-000500.h5): its particles, of
 * every kind, become the generator's entries (scene_from.c; the format is
 * docs/checkpoints.md).
 */
#ifndef SD_IO_SCENE_FROM_H
#define SD_IO_SCENE_FROM_H

#include "io/scene.h"

/* 1 when the generator's file is to be read as a checkpoint: its name ends
 * in .h5, or it starts with the checkpoint header. */
int sd_from_is_checkpoint(const char *path);

/* Appends the checkpoint g->file's owned particles, in stable-id order, to
 * g's entries: position, velocity, spin and (shapes) orientation as saved,
 * the template found by name among s's shapes (same kind, else refused),
 * the material by name (else g->material). A template that is a scaled
 * copy an insertion made (world/scaled.c) is made again from the scene's
 * template of its base's name (same kind), appended to s's shapes hidden.
 * Errors (SD_ERR_INPUT; a file
 * that cannot be read, is damaged, of the other dimension or the grid
 * solver, a template this scene lacks) name s's file, file_line and key. */
sd_status sd_from_checkpoint_read(sd_scene *s, sd_scene_generator *g, const char *key, int file_line,
                                  sd_error *err);

#endif
