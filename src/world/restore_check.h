/* restore_check.h — the checks a checkpoint restore makes of the values it
 * puts back (world/restore_check.c; issue 31): a resealed checksum is no
 * validation of content, so nothing restored is used before it is held to
 * its range, and what the scene defines comes from the scene.
 */
#ifndef SD_WORLD_RESTORE_CHECK_H
#define SD_WORLD_RESTORE_CHECK_H

#include "world/snapshot.h"

struct sd_wall;
struct sd_process;

/* The scene-built world's walls and insertions/outlets, kept across the
 * copy (their definitions go back after it). */
typedef struct sd_restore_kept {
    struct sd_wall *walls;
    struct sd_process *process;
} sd_restore_kept;

/* Every real of the snapshot's state items (not scene/) finite. */
sd_status sd_restore_check_items(const sd_snapshot *s, sd_error *err);
/* Copies what sd_restore_check_world puts back; SD_ERR_MEMORY. */
sd_status sd_restore_keep(const sd_world *w, sd_restore_kept *keep);
void sd_restore_kept_free(sd_restore_kept *keep);
/* After the copy, before any use: puts the scene's definitions back and
 * checks every restored value's range; SD_ERR_INPUT naming the dataset. */
sd_status sd_restore_check_world(sd_world *w, const sd_restore_kept *keep, sd_error *err);

#endif
