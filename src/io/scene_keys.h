/* scene_keys.h — the one table of scene-file keys (STYLE.md convention 14).
 *
 * Invariant: every key the parser accepts is a row of sd_scene_keys[], and
 * the parser accepts nothing else. The same rows give the type and range
 * checks, the defaults the parser applies, `shapedem help scene` and
 * docs/scene-format.md, so the documentation cannot drift from the parser.
 */
#ifndef SD_IO_SCENE_KEYS_H
#define SD_IO_SCENE_KEYS_H

#include <stddef.h>

/* Where a key may appear. */
typedef enum sd_scene_section {
    SD_SEC_ROOT,        /* top level of the file */
    SD_SEC_SIMULATION,  /* simulation: */
    SD_SEC_MATERIAL,    /* materials: - ... */
    SD_SEC_INTERACTION, /* interactions: - ... */
    SD_SEC_SHAPE,       /* shapes: - ... (one shape template) */
    SD_SEC_PARTICLES,   /* particles: - ... (one generator) */
    SD_SEC_SPHERE,      /* particles: - spheres: - ... (list generator) */
    SD_SEC_WALL,        /* walls: - ... */
    SD_SEC_OUTPUT,      /* output: */
    SD_SEC_POUR,        /* pour: (solver grid) */
    SD_SEC_OUTLET,      /* outlet: (solver grid) */
    SD_SEC_ELEMENT,     /* shapes: - type: composite, elements: - ... */
    SD_SEC_INSERT,      /* insert: - ... (cells solver) */
    SD_SEC_INSERT_MIX,  /* insert: - mix: - ... */
    SD_SEC_OUTLETS,     /* outlets: - ... (cells solver) */
    SD_SEC_MESH_MOTION, /* walls: - type: mesh, motion: */
    SD_SEC_ANALYSIS,    /* analysis: - ... (io/scene_analysis.c) */
    SD_SEC_STOP,        /* simulation: stop_when: (io/run.c) */
    SD_SEC_COUNT
} sd_scene_section;

/* The shape of a value. */
typedef enum sd_scene_type {
    SD_KT_MAP,          /* a mapping (a section) */
    SD_KT_LIST,         /* a list of mappings */
    SD_KT_NUMBER,       /* a YAML int or float */
    SD_KT_INT,          /* an integer (2e4 is fine, 2.5 is not) */
    SD_KT_STRING,       /* a scalar */
    SD_KT_ENUM,         /* one of the '|'-separated choices */
    SD_KT_ENUM_LIST,    /* a list of choices */
    SD_KT_VEC3,         /* [x, y, z] */
    SD_KT_INT3,         /* [nx, ny, nz] integers */
    SD_KT_ENUM_OR_INT3, /* one of the choices, or [nx, ny, nz] integers */
    SD_KT_NUM_OR_VEC3,  /* a number for all three axes, or [x, y, z] */
    SD_KT_NUM_OR_RANGE, /* a number, or {min: a, max: b} with a <= b */
    SD_KT_BOX,          /* {min: [x, y, z], max: [x, y, z]} with max > min */
    SD_KT_NAME_PAIR,    /* [name, name] */
    SD_KT_ORIENTATION,  /* identity, random, or a quaternion [w, x, y, z] (normalised) */
    SD_KT_VEC3_LIST,    /* a list of [x, y, z] */
    SD_KT_VEC2,         /* [x, y] (planar shapes) */
    SD_KT_VEC2_LIST,    /* a list of [x, y] (planar shapes) */
    SD_KT_NUM_LIST      /* a list of numbers (Fourier coefficients) */
} sd_scene_type;

/* The allowed values of a number (each component, for vectors). */
typedef enum sd_scene_range {
    SD_KR_ANY,
    SD_KR_POS,      /* > 0 */
    SD_KR_NONNEG,   /* >= 0 */
    SD_KR_UNIT,     /* in (0, 1] */
    SD_KR_POISSON,  /* in (-1, 0.5) */
    SD_KR_ONE,      /* >= 1 */
    SD_KR_NONEMPTY  /* strings: not empty */
} sd_scene_range;

/* Kinds a key applies to, within its section: generator kinds for
 * SD_SEC_PARTICLES (bit = 1 << sd_gen_kind), wall types for SD_SEC_WALL
 * (bit = 1 << kind, 0 plane, 1 box, 2 mesh), mesh motion types for
 * SD_SEC_MESH_MOTION (bit = 1 << SD_MESH_*), shape types for SD_SEC_SHAPE (bit =
 * 1 << sd_shape_kind); everything else uses SD_KIND_ALL. */
#define SD_KIND_ALL 0xffffu /* 16 kinds: the 3D and the 2D shape types */

typedef struct sd_scene_key {
    sd_scene_section section;
    const char *key;
    sd_scene_type type;
    sd_scene_range range;
    const char *choices;   /* SD_KT_ENUM / SD_KT_ENUM_LIST: "a|b|c" */
    unsigned kinds;        /* kinds it applies to */
    unsigned required;     /* kinds for which it must be given (0: optional) */
    const char *unit;      /* SI unit, or "" */
    const char *def;       /* default as written in a scene (parsed when the
                              key is absent, if it is a number or vector), or
                              a word such as "required" */
    const char *doc;       /* one-line meaning */
} sd_scene_key;

extern const sd_scene_key sd_scene_keys[];
extern const size_t sd_scene_key_count;

/* "simulation", "materials[]", ... for messages and help. */
const char *sd_scene_section_name(sd_scene_section sec);
/* Kind names of a section ("lattice|random|list|csv", "plane|box",
 * "sphere|box|...|"), or NULL. */
const char *sd_scene_section_kinds(sd_scene_section sec);
/* The row for key in sec, or NULL. */
const sd_scene_key *sd_scene_key_find(sd_scene_section sec, const char *key);
/* "number > 0", "integer >= 1", "[x, y, z]", ... for messages and help. */
const char *sd_scene_type_text(const sd_scene_key *k, char *buf, size_t size);
/* Range as text ("> 0", "in (0, 1]"), "" for SD_KR_ANY. */
const char *sd_scene_range_text(sd_scene_range r);
/* 1 if v lies in r. */
int sd_scene_range_ok(sd_scene_range r, double v);

/* A complete, valid scene: shown at the top of the markdown help and loaded
 * by tests/unit/test_scene.c, so the documented example always parses. */
extern const char sd_scene_example[];

#endif
