/* scene_sections.h — what the section rules of the scene parser share
 * across their files: scene_parse.c (root, simulation, materials,
 * interactions, walls, output, pour, outlet, the cross-key checks),
 * scene_shapes.c (shapes:) and scene_particles.c (particles:).
 *
 * The values themselves are read by the typed reader (io/yaml_read.h);
 * these are the rules of a scene: references by name, paths relative to
 * the scene file, the particle budget.
 *
 * Invariant: every function either fills the scene or returns an error
 * naming the scene file, line and key (sd_fail); none prints.
 */
#ifndef SD_IO_SCENE_SECTIONS_H
#define SD_IO_SCENE_SECTIONS_H

#include <yaml.h>

#include "core/error.h"
#include "io/scene.h"
#include "io/yaml_read.h"

/* The scene being read. path and err are y's, repeated for the section
 * rules' own messages (sd_fail, and the out-of-memory errors). */
typedef struct sd_parse {
    sd_yaml y;
    const char *path;
    sd_scene *s;
    sd_error *err;
    double total; /* particles of the generators and the pour read so far */
} sd_parse;

/* An SD_ERR_INPUT error in the scene file at line and key. */
SD_PRINTF(4, 5)
sd_status sd_fail(sd_parse *p, int line, const char *key, const char *fmt, ...);

static inline sd_v3d sd_parse_v3(const double v[3])
{
    sd_v3d r = {v[0], v[1], v[2]};
    return r;
}

/* The index of the material (shape) called name, else an error that
 * lists the scene's names. */
sd_status sd_material_ref(sd_parse *p, const char *name, int line, const char *key, int *out);
sd_status sd_shape_ref(sd_parse *p, const char *name, int line, const char *key, int *out);

/* file relative to the scene file's directory (absolute paths kept);
 * 0 when it does not fit in size. */
int sd_resolve(const char *scene, const char *file, char *out, size_t size);

/* Adds n particles (of the generator or pour at line/key) to the scene's
 * total; refuses the scene past 1e9 particles or the machine's memory. */
sd_status sd_count_particles(sd_parse *p, double n, int line, const char *key);

/* The shapes: and particles: sections (scene_shapes.c, scene_particles.c). */
sd_status sd_parse_shapes(sd_parse *p, yaml_node_t *list);
/* A shapes: entry of type composite at scene index si, with more entries
 * still to come (scene_composite.c): may insert its element shapes before
 * it, so the composite ends at s->shapes[s->shape_count - 1]. */
sd_status sd_parse_composite(sd_parse *p, yaml_node_t *m, const char *path, size_t si, size_t more);
sd_status sd_parse_particles(sd_parse *p, yaml_node_t *list, int line);
/* A walls: entry of type mesh, its other keys checked (scene_mesh.c). */
sd_status sd_parse_mesh_wall(sd_parse *p, yaml_node_t *m, sd_scene_wall *w, const char *path);

#endif
