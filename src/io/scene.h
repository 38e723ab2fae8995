/* scene.h — a scene file, parsed: plain data between the YAML parser
 * (scene_parse.c) and the world builder (scene_build.c).
 *
 * Invariant: every value here has been type- and range-checked by the parser
 * and carries the line it came from, so the builder can report later errors
 * (overlaps at start, an unstable time step) with file, line and key.
 */
#ifndef SD_IO_SCENE_H
#define SD_IO_SCENE_H

#include <shapedem/shapedem.h>
#include <stdio.h>

#define SD_SCENE_NAME_MAX 64
#define SD_SCENE_PATH_MAX 1024

typedef enum sd_gen_kind {
    SD_GEN_LATTICE, /* a block of spheres on a simple cubic lattice */
    SD_GEN_RANDOM,  /* random non-overlapping spheres in a box */
    SD_GEN_LIST,    /* spheres given one by one in the scene */
    SD_GEN_CSV      /* spheres read from a CSV file */
} sd_gen_kind;

typedef struct sd_scene_generator {
    sd_gen_kind kind;
    int line;                     /* line of the generator's entry */
    int material;                 /* index into sd_scene.materials */
    double radius_min, radius_max;/* m; radius uniform in [min, max] */
    sd_v3d velocity;              /* m/s, mean initial velocity */
    double velocity_jitter;       /* m/s, uniform +- per component */
    /* lattice */
    sd_v3d origin;                /* m, centre of the first sphere */
    sd_v3d spacing;               /* m, per axis */
    int count[3];
    /* random */
    sd_v3d box_lo, box_hi;        /* m, the spheres lie fully inside */
    long number;
    /* list: spheres given in the scene (material set per entry) */
    size_t list_count;
    sd_sphere_def *list;
    int *list_lines;
    /* csv: path resolved relative to the scene file */
    char file[SD_SCENE_PATH_MAX];
} sd_scene_generator;

typedef struct sd_scene_material {
    char name[SD_SCENE_NAME_MAX];
    sd_material_def def;          /* def.name points at name above */
    int line;
} sd_scene_material;

typedef struct sd_scene_interaction {
    int mat_a, mat_b;
    sd_interaction_def def;
    int line;
} sd_scene_interaction;

typedef struct sd_scene_wall {
    char name[SD_SCENE_NAME_MAX];
    int kind;                     /* 0 plane, 1 box */
    sd_v3d point, normal;         /* plane */
    sd_v3d lo, hi;                /* box */
    unsigned open_faces;          /* SD_BOX_* mask */
    int material;
    int line;
} sd_scene_wall;

enum { SD_OUT_VTK = 1 << 0, SD_OUT_CSV = 1 << 1 };

typedef struct sd_scene_output {
    char directory[SD_SCENE_PATH_MAX]; /* "" = out/<scene file stem> */
    long every;                   /* steps between frames */
    long stats_every;             /* steps between stats.csv rows */
    unsigned formats;             /* SD_OUT_* mask */
} sd_scene_output;

typedef struct sd_scene {
    char path[SD_SCENE_PATH_MAX];
    sd_world_def world;
    int simulation_line;          /* line of the simulation: key, for errors */
    long steps;                   /* >= 0; from steps or duration/dt */
    int dt_line;                  /* line of simulation.dt, for errors */
    size_t material_count, interaction_count, generator_count, wall_count;
    sd_scene_material *materials;
    sd_scene_interaction *interactions;
    sd_scene_generator *generators;
    sd_scene_wall *walls;
    sd_scene_output output;
} sd_scene;

/* Parses and checks a scene file. On error *out is NULL and err names the
 * file, line and key. */
sd_status sd_scene_load(const char *path, sd_scene **out, sd_error *err);
void sd_scene_free(sd_scene *s);

/* Builds the world: materials, interactions, walls, generated particles.
 * Rejects overlaps at start beyond tolerance, particles outside walls and a
 * time step above the stability limit, with file, line and key. */
sd_status sd_scene_build(const sd_scene *s, sd_world **out, sd_error *err);

/* Prints the table of every scene key (section, key, type, unit, default,
 * meaning) and the rules the table cannot say. markdown = 1 prints
 * docs/scene-format.md, with an example scene at the top. The table is
 * src/io/scene_keys.c, the same one the parser checks against. */
void sd_scene_print_keys(FILE *f, int markdown);

/* ---- shared by the scene modules and their tests ------------------------ */

/* Every sphere of a scene in id order, with where it came from. */
typedef struct sd_scene_spheres {
    size_t count;
    sd_sphere_def *defs;
    int *gen;                     /* generator index of each sphere */
    int *entry;                   /* list/csv entry index, or -1 */
    int *line;                    /* scene line (csv: csv-file line) */
} sd_scene_spheres;

/* Runs the generators in order (what sd_scene_build adds to the world).
 * Deterministic from s->world.seed. Fails when the random generator cannot
 * place all its spheres. */
sd_status sd_scene_generate(const sd_scene *s, sd_scene_spheres *out, sd_error *err);
void sd_scene_spheres_free(sd_scene_spheres *sp);

/* Finds the first sphere j (in id order) that overlaps an earlier sphere i
 * by more than tol x the smaller radius, using a cell grid (O(N)).
 * Returns 1 and sets *i, *j when there is one, 0 when none, -1 when out of
 * memory. */
int sd_scene_find_overlap(size_t n, const sd_sphere_def *defs, double tol, size_t *i, size_t *j);

#endif
