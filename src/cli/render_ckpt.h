/* render_ckpt.h — a checkpoint as a frame for `shapedem render CK.h5`
 * (cli/render_ckpt.c). */
#ifndef SD_CLI_RENDER_CKPT_H
#define SD_CLI_RENDER_CKPT_H

#include "render/render.h"

/* The frame of checkpoint ck with field. Without a scene: its particles as
 * spheres of their radius, no walls (the checkpoint holds no template
 * geometry, and its walls only as this build's records). With the scene
 * that wrote it: the world built from the scene and restored from ck (the
 * restart's checks: the scene's hash, version, sizes), then drawn from the
 * frame files it writes, true shapes and walls included. Errors name ck
 * (or the scene). */
sd_status sd_render_load_checkpoint(const char *ck, const char *scene, const char *field, sd_render_frame *f,
                                    sd_error *err);

#endif
