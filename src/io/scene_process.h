/* scene_process.h — the insert: and outlets: sections of a scene (cells
 * solver; shapedem/process.h), parsed into the world's defs, built into a
 * world, and the outlet.csv series of a run.
 */
#ifndef SD_IO_SCENE_PROCESS_H
#define SD_IO_SCENE_PROCESS_H

#include <stdio.h>

#include <shapedem/process.h>

#include "io/scene_sections.h"

#define SD_SCENE_PROCESS_MAX 16

typedef struct sd_scene_process {
    size_t insert_count, outlet_count;
    sd_insert_def inserts[SD_SCENE_PROCESS_MAX];       /* name points at insert_names */
    char insert_names[SD_SCENE_PROCESS_MAX][SD_SCENE_NAME_MAX];
    int insert_lines[SD_SCENE_PROCESS_MAX];
    int insert_key_lines[SD_SCENE_PROCESS_MAX];         /* line of the region keys, for the domain error */
    sd_region_outlet_def outlets[SD_SCENE_PROCESS_MAX];
    char outlet_names[SD_SCENE_PROCESS_MAX][SD_SCENE_NAME_MAX];
    int outlet_lines[SD_SCENE_PROCESS_MAX];
    char outlet_warning[SD_SCENE_PROCESS_MAX][1320];    /* "" or FILE:LINE: outlets[K]: why no particle
                                                           may reach it (a path of SD_SCENE_PATH_MAX fits) */
    /* mesh regions (region: mesh): the file's vertices, scaled and placed,
     * and its triangles (sd_malloc'd; inserts[k].region points at them) */
    sd_v3d *mesh_vertices[SD_SCENE_PROCESS_MAX];
    uint32_t (*mesh_triangles[SD_SCENE_PROCESS_MAX])[3];
} sd_scene_process;

/* The axis-aligned box around a region (a mesh region: its lo, hi). */
void sd_region_box(const sd_region_def *r, double lo[3], double hi[3]);

/* Reads insert: and outlets: (absent: s->process stays NULL). */
sd_status sd_parse_process(sd_parse *p, yaml_node_t *root);
void sd_scene_process_free(sd_scene *s);
/* Adds the insertions and outlets to a built world; errors name the
 * scene line and key. */
sd_status sd_scene_build_process(const sd_scene *s, sd_world *w, sd_error *err);

/* outlet.csv (io/run.c): the header, then a row per stats row: time, the
 * accounting, and per outlet the count and mass removed, with the mass
 * flow rate since the previous row. */
void sd_outlet_csv_header(FILE *f, const sd_world *w);
void sd_outlet_csv_row(FILE *f, const sd_world *w, double *last_time, double *last_mass);

#endif
