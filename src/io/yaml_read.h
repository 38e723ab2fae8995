/* yaml_read.h — the typed YAML reader under the scene parser: a scene
 * file loaded as a libyaml node tree, and values read from it checked
 * against the rows of the key table (io/scene_keys.h).
 *
 * It knows YAML, the key table and the shape of a value (a number in a
 * range, [x, y, z], {min: a, max: b}, a choice, ...), never a section's
 * meaning: the section rules (scene_parse.c) say which keys a section has
 * and how they combine. Every error names the file, the 1-based line and
 * the dotted key path (materials[1].density).
 *
 * Invariant: sd_yaml_check_map has read every key of a mapping with its
 * row before sd_yaml_get is asked for one, so sd_yaml_get cannot fail; a
 * key that is absent reads as the table's default (numbers and vectors),
 * so defaults live in the table only.
 */
#ifndef SD_IO_YAML_READ_H
#define SD_IO_YAML_READ_H

#include <stddef.h>
#include <yaml.h>

#include <shapedem/shapedem.h>

#include "core/error.h"
#include "io/scene_keys.h"

/* The document being read and where its errors go. */
typedef struct sd_yaml {
    yaml_document_t *doc;
    const char *path; /* the file, for messages */
    sd_error *err;
} sd_yaml;

/* A checked value of any key type (the fields used depend on the type). */
typedef struct sd_yaml_value {
    yaml_node_t *node; /* NULL when the key is absent */
    int line;          /* 1-based line of the value, 0 when absent */
    double num;
    long long integer;
    double v[3];
    long long iv[3];
    const char *str;
    int choice;         /* SD_KT_ENUM: index of the choice */
    unsigned mask;      /* SD_KT_ENUM_LIST: bit per choice */
    double lo, hi;      /* SD_KT_NUM_OR_RANGE */
    sd_v3d box_lo, box_hi;
    const char *names[2];
    double q[4];        /* SD_KT_ORIENTATION with choice SD_ORIENT_FIXED: unit (w, x, y, z) */
} sd_yaml_value;

/* Loads the file at path (at most 64 MiB, one document, nesting at most
 * 64 deep; scalars tagged !!str or ! read as strings) into *doc, which the
 * caller deletes with yaml_document_delete. */
sd_status sd_yaml_load(const char *path, yaml_document_t *doc, sd_error *err);

/* Sets y->err (SD_ERR_INPUT) at line and key; returns its status. */
SD_PRINTF(4, 5)
sd_status sd_yaml_fail(const sd_yaml *y, int line, const char *key, const char *fmt, ...);
/* The SD_ERR_MEMORY error of y's file. */
sd_status sd_yaml_oom(const sd_yaml *y);

/* 1-based line of n, 0 for NULL. */
int sd_yaml_line(const yaml_node_t *n);
/* "path.key", or "key" at the top level. */
const char *sd_yaml_kp(char *buf, size_t size, const char *path, const char *key);
/* What n is, for "expected X, got Y" (file bytes escaped). */
const char *sd_yaml_desc(const yaml_node_t *n, char *buf, size_t size);
size_t sd_yaml_seq_len(const yaml_node_t *n);
yaml_node_t *sd_yaml_seq_item(const sd_yaml *y, const yaml_node_t *n, size_t i);
/* The value of key in map, or NULL. */
yaml_node_t *sd_yaml_map_get(const sd_yaml *y, const yaml_node_t *map, const char *key);
/* Line of key in map (of the key, not its value), or 1. */
int sd_yaml_key_line(const sd_yaml *y, yaml_node_t *map, const char *key);
/* "a, b, c" from "a|b|c". */
void sd_yaml_choices_list(const char *choices, char *buf, size_t size);

/* Item i of a section's list, which must be a mapping: its path
 * ("section[i]") in path, the node in *m; else "expected a mapping FORM,
 * got ...". The prologue every list section shares. */
sd_status sd_yaml_entry(const sd_yaml *y, const yaml_node_t *list, size_t i, const char *section, const char *form,
                        char *path, size_t path_size, yaml_node_t **m);

/* Reads n as row k's type into v (sd_yaml_value), with key in messages. */
sd_status sd_yaml_read_value(const sd_yaml *y, const sd_scene_key *k, yaml_node_t *n, const char *key,
                             sd_yaml_value *v);
/* One number in k's range; what: " for x" on components; alt: the other
 * forms the key takes, named when n is no number at all. */
sd_status sd_yaml_read_number(const sd_yaml *y, const sd_scene_key *k, yaml_node_t *n, const char *key,
                              const char *what, const char *alt, double *out);
sd_status sd_yaml_read_vec2(const sd_yaml *y, const sd_scene_key *k, yaml_node_t *n, const char *key, double v[2]);
/* [x, y, z]; iv non-NULL: integers. */
sd_status sd_yaml_read_vec3(const sd_yaml *y, const sd_scene_key *k, yaml_node_t *n, const char *key, double v[3],
                            long long iv[3]);

/* Checks every key of map against the rows of sec for one kind (a
 * generator, wall or shape type bit; SD_KIND_ALL elsewhere): known (else
 * a did-you-mean), applicable, not repeated, well-typed; then that the
 * required ones are there (line: the mapping's, for those). */
sd_status sd_yaml_check_map(const sd_yaml *y, yaml_node_t *map, sd_scene_section sec, unsigned kind,
                            const char *kind_name, const char *path, int line);
/* The value of a key already checked by sd_yaml_check_map. Returns 1 if
 * given; 0 if absent, with v holding the table default when it is a
 * number or a vector. */
int sd_yaml_get(const sd_yaml *y, yaml_node_t *map, sd_scene_section sec, const char *name, const char *path,
                sd_yaml_value *v);

/* A number key placed by the table: the double at offset (offsetof) in
 * a section's target struct. */
typedef struct sd_yaml_place {
    const char *key;
    size_t offset;
} sd_yaml_place;

/* Places each of the n keys of place (already checked by
 * sd_yaml_check_map) as a double at base + offset: its value, or the
 * table's default when absent. Every key of sec must be placed or named
 * in rules (a NULL-terminated list of the keys the section reads by
 * name), else SD_ERR_INTERNAL names it: a key added to the table and
 * forgotten in its section cannot become a silent default. */
sd_status sd_yaml_place_numbers(const sd_yaml *y, yaml_node_t *map, sd_scene_section sec, const char *path,
                                const sd_yaml_place *place, size_t n, const char *const *rules, void *base);

#endif
