/* scene_parse.c — reads a scene file (YAML) into an sd_scene.
 *
 * The whole document is loaded as a node tree first (yaml_parser_load), so
 * every node knows its line. Each mapping is then checked against the key
 * table (scene_keys.c): unknown keys, keys of another generator or wall
 * type, duplicate keys, wrong types, out-of-range values and missing
 * required keys are all errors that name the file, the 1-based line and the
 * dotted key path (materials[1].density).
 *
 * Invariant: sd_scene_load returns either a scene in which every value has
 * been checked (types, ranges, material names, cross-key rules such as
 * "exactly one of steps and duration") or an error and no scene; it never
 * prints and never leaves anything allocated behind.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#include <yaml.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/mesh.h"
#include "io/scene.h"
#include "io/scene_keys.h"
/* Only the shape kinds and SD_SHAPE_MAX_VERTICES are wanted from shape.h;
 * its vector header's sd_v3 would clash with this file's sd_v3 (sd_v3d
 * from three doubles), so it is renamed while the header is read. */
#define sd_v3 sd_v3_core
#include "shape/polylib.h"
#include "shape/shape.h"
#include "shape/shape2d.h"
#undef sd_v3

/* ---- parse context and errors ------------------------------------------ */

typedef struct sd_parse {
    yaml_document_t *doc;
    const char *path;
    sd_scene *s;
    sd_error *err;
    double total; /* particles of the generators and the pour read so far */
} sd_parse;

/* A checked value of any key type (the fields used depend on the type). */
typedef struct sd_value {
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
} sd_value;

static int sd_line(const yaml_node_t *n) { return n ? (int)n->start_mark.line + 1 : 0; }

SD_PRINTF(4, 5)
static sd_status sd_fail(sd_parse *p, int line, const char *key, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return sd_error_set(p->err, SD_ERR_INPUT, p->path, line, key, "%s", msg);
}

/* "path.key", or "key" at the top level. */
static const char *sd_kp(char *buf, size_t size, const char *path, const char *key)
{
    if (path[0])
        snprintf(buf, size, "%s.%s", path, key);
    else
        snprintf(buf, size, "%s", key);
    return buf;
}

static const char *sd_scalar(const yaml_node_t *n) { return (const char *)n->data.scalar.value; }

/* The tag the loader gave n: an explicit one, or the default (str) for an
 * untagged scalar. */
static const char *sd_tag(const yaml_node_t *n) { return n->tag ? (const char *)n->tag : YAML_STR_TAG; }

static int sd_is_null(const yaml_node_t *n)
{
    if (!n)
        return 1;
    if (n->type != YAML_SCALAR_NODE || n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE)
        return 0;
    const char *t = sd_scalar(n);
    return !t[0] || !strcmp(t, "~") || !strcmp(t, "null") || !strcmp(t, "Null") ||
           !strcmp(t, "NULL");
}

/* What was found, for "expected X, got Y" messages. */
static const char *sd_desc(const yaml_node_t *n, char *buf, size_t size)
{
    if (sd_is_null(n)) {
        snprintf(buf, size, "nothing");
    } else if (n->type == YAML_SCALAR_NODE) {
        /* escaped: a double-quoted "\e[31m" would reach the terminal */
        const char *t = sd_scalar(n);
        char esc[100]; /* sd_escape ends it with "..." when the escapes do not fit */
        sd_escape(esc, sizeof esc, t, strlen(t) > 60 ? 60 : strlen(t));
        const char *q = n->data.scalar.style == YAML_PLAIN_SCALAR_STYLE ? "" : "\"";
        const char *tag = sd_tag(n), *std = "tag:yaml.org,2002:";
        char pre[48] = "";
        if (n->data.scalar.style == YAML_ANY_SCALAR_STYLE)
            snprintf(pre, sizeof pre, "the string !!str ");
        else if (strcmp(tag, YAML_STR_TAG))
            snprintf(pre, sizeof pre, "%s%.30s ", strncmp(tag, std, strlen(std)) ? "" : "!!",
                     strncmp(tag, std, strlen(std)) ? tag : tag + strlen(std));
        if (pre[0])
            q = "";
        char all[160];
        snprintf(all, sizeof all, "%s%s%s%s%s", pre, q, esc, strlen(t) > 60 ? "..." : "", q);
        size_t l = strlen(all) < size ? strlen(all) : size - 1; /* cut, as snprintf would */
        memcpy(buf, all, l);
        buf[l] = '\0';
    } else if (n->type == YAML_SEQUENCE_NODE) {
        long len = (long)(n->data.sequence.items.top - n->data.sequence.items.start);
        snprintf(buf, size, "a list of %ld item%s", len, len == 1 ? "" : "s");
    } else {
        snprintf(buf, size, "a mapping");
    }
    return buf;
}

static size_t sd_seq_len(const yaml_node_t *n)
{
    return n && n->type == YAML_SEQUENCE_NODE
               ? (size_t)(n->data.sequence.items.top - n->data.sequence.items.start)
               : 0;
}

static yaml_node_t *sd_seq_item(sd_parse *p, const yaml_node_t *n, size_t i)
{
    return yaml_document_get_node(p->doc, n->data.sequence.items.start[i]);
}

static yaml_node_t *sd_map_get(sd_parse *p, const yaml_node_t *map, const char *key)
{
    if (!map || map->type != YAML_MAPPING_NODE)
        return NULL;
    for (yaml_node_pair_t *q = map->data.mapping.pairs.start; q < map->data.mapping.pairs.top; ++q) {
        yaml_node_t *k = yaml_document_get_node(p->doc, q->key);
        if (k && k->type == YAML_SCALAR_NODE && !strcmp(sd_scalar(k), key))
            return yaml_document_get_node(p->doc, q->value);
    }
    return NULL;
}

/* ---- scalars ------------------------------------------------------------ */

/* A scalar that reads as a finite number: a plain (untagged) scalar, or one
 * tagged !!float or !!int in any style (!!float "1.0e7"). Only digits,
 * signs, '.' and exponents are allowed, so "inf", "nan", hex and strings
 * are not numbers: a quoted "2500", `!!str 2500` (style
 * YAML_ANY_SCALAR_STYLE, see sd_mark_tagged) and other tags are strings. */
static int sd_scalar_number(const yaml_node_t *n, double *out)
{
    if (!n || n->type != YAML_SCALAR_NODE)
        return 0;
    const char *tag = sd_tag(n);
    int numeric = !strcmp(tag, YAML_FLOAT_TAG) || !strcmp(tag, YAML_INT_TAG);
    if (!numeric && (strcmp(tag, YAML_STR_TAG) || n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE))
        return 0;
    const char *t = sd_scalar(n);
    if (!t[0] || strspn(t, "0123456789+-.eE") != strlen(t) || !strpbrk(t, "0123456789"))
        return 0;
    char *end;
    errno = 0;
    double v = strtod(t, &end);
    if (*end || !isfinite(v) || (!strcmp(tag, YAML_INT_TAG) && v != floor(v)))
        return 0;
    *out = v;
    return 1;
}

/* An integer: digits read exactly (seeds above 2^53 keep every bit), or a
 * number with an integral value (2e4). */
static int sd_scalar_int(const yaml_node_t *n, long long *out)
{
    double v;
    if (!sd_scalar_number(n, &v))
        return 0;
    const char *t = sd_scalar(n);
    size_t skip = (t[0] == '+' || t[0] == '-') ? 1 : 0;
    if (t[skip] && strspn(t + skip, "0123456789") == strlen(t + skip)) {
        char *end;
        errno = 0;
        long long i = strtoll(t, &end, 10);
        if (errno == ERANGE)
            return 0;
        *out = i;
        return 1;
    }
    if (v != floor(v) || fabs(v) > 9007199254740992.0)
        return 0;
    *out = (long long)v;
    return 1;
}

/* Index of t in "a|b|c|", or -1. */
static int sd_choice_index(const char *choices, const char *t)
{
    int idx = 0;
    for (const char *c = choices; *c; ++idx) {
        size_t len = strcspn(c, "|");
        if (len > 0 && strlen(t) == len && !strncmp(c, t, len))
            return idx;
        c += len;
        if (*c == '|')
            ++c;
    }
    return -1;
}

static void sd_choices_list(const char *choices, char *buf, size_t size)
{
    size_t used = 0;
    buf[0] = '\0';
    for (const char *c = choices; *c && used + 1 < size;) {
        size_t len = strcspn(c, "|");
        if (len > 0) {
            int w = snprintf(buf + used, size - used, "%s%.*s", used ? ", " : "", (int)len, c);
            used += w > 0 ? (size_t)w : 0;
        }
        c += len;
        if (*c == '|')
            ++c;
    }
}

/* ---- typed values ------------------------------------------------------- */

/* what: " for x" on vector components; alt: the other forms the key takes
 * (" or [x, y, z]"), named only when the value is not a number at all. */
static sd_status sd_read_number(sd_parse *p, const sd_scene_key *k, yaml_node_t *n,
                                const char *key, const char *what, const char *alt, double *out)
{
    char got[96];
    const char *r = sd_scene_range_text(k->range);
    if (!sd_scalar_number(n, out)) {
        /* a number written as a string: say why it is not read as one */
        char *end;
        const char *t = n && n->type == YAML_SCALAR_NODE ? sd_scalar(n) : "";
        double x = strtod(t, &end);
        const char *why = t[0] && !*end && isfinite(x) && !strcmp(sd_tag(n), YAML_STR_TAG) &&
                                  n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE
                              ? " (a string in YAML: write the number without quotes or !!str)"
                              : "";
        return sd_fail(p, sd_line(n), key, "expected a number%s%s%s%s, got %s%s", r[0] ? " " : "", r,
                       what, alt, sd_desc(n, got, sizeof got), why);
    }
    if (!sd_scene_range_ok(k->range, *out))
        return sd_fail(p, sd_line(n), key, "expected a number %s%s, got %s", r, what,
                       sd_desc(n, got, sizeof got));
    return SD_OK;
}

static sd_status sd_read_int(sd_parse *p, const sd_scene_key *k, yaml_node_t *n, const char *key,
                             const char *what, long long *out)
{
    char got[96];
    const char *r = sd_scene_range_text(k->range);
    if (!sd_scalar_int(n, out) || !sd_scene_range_ok(k->range, (double)*out))
        return sd_fail(p, sd_line(n), key, "expected an integer%s%s%s, got %s", r[0] ? " " : "",
                       r, what, sd_desc(n, got, sizeof got));
    return SD_OK;
}

/* [x, y, z]: three numbers, each in the key's range. */
static sd_status sd_read_vec3(sd_parse *p, const sd_scene_key *k, yaml_node_t *n, const char *key,
                              double v[3], long long iv[3])
{
    char got[96];
    if (!n || n->type != YAML_SEQUENCE_NODE || sd_seq_len(n) != 3)
        return sd_fail(p, sd_line(n), key, "expected a list of 3 %s ([x, y, z]), got %s",
                       iv ? "integers" : "numbers", sd_desc(n, got, sizeof got));
    for (size_t i = 0; i < 3; ++i) {
        static const char *const axis[3] = {" for x", " for y", " for z"};
        yaml_node_t *item = sd_seq_item(p, n, i);
        sd_status st = iv ? sd_read_int(p, k, item, key, axis[i], &iv[i])
                          : sd_read_number(p, k, item, key, axis[i], "", &v[i]);
        if (st != SD_OK)
            return st;
        if (iv)
            v[i] = (double)iv[i];
    }
    return SD_OK;
}

/* [x, y]: two numbers, each in the key's range (planar shapes). */
static sd_status sd_read_vec2(sd_parse *p, const sd_scene_key *k, yaml_node_t *n, const char *key, double v[2])
{
    char got[96];
    if (!n || n->type != YAML_SEQUENCE_NODE || sd_seq_len(n) != 2)
        return sd_fail(p, sd_line(n), key, "expected a list of 2 numbers ([x, y]), got %s",
                       sd_desc(n, got, sizeof got));
    for (size_t i = 0; i < 2; ++i) {
        static const char *const axis[2] = {" for x", " for y"};
        sd_status st = sd_read_number(p, k, sd_seq_item(p, n, i), key, axis[i], "", &v[i]);
        if (st != SD_OK)
            return st;
    }
    return SD_OK;
}

static sd_status sd_read_string(sd_parse *p, const sd_scene_key *k, yaml_node_t *n,
                                const char *key, const char **out)
{
    char got[96];
    if (!n || n->type != YAML_SCALAR_NODE)
        return sd_fail(p, sd_line(n), key, "expected a %sstring, got %s",
                       k->range == SD_KR_NONEMPTY ? "non-empty " : "", sd_desc(n, got, sizeof got));
    *out = sd_is_null(n) ? "" : sd_scalar(n);
    if (k->range == SD_KR_NONEMPTY && !(*out)[0])
        return sd_fail(p, sd_line(n), key, "expected a non-empty string, got nothing");
    if (strlen(*out) >= SD_SCENE_PATH_MAX)
        return sd_fail(p, sd_line(n), key, "string too long (%zu characters, at most %d)",
                       strlen(*out), SD_SCENE_PATH_MAX - 1);
    return SD_OK;
}

static sd_status sd_read_choice(sd_parse *p, const sd_scene_key *k, yaml_node_t *n,
                                const char *key, int *out)
{
    char got[96], list[160];
    *out = (n && n->type == YAML_SCALAR_NODE) ? sd_choice_index(k->choices, sd_scalar(n)) : -1;
    if (*out < 0) {
        sd_choices_list(k->choices, list, sizeof list);
        return sd_fail(p, sd_line(n), key, "expected one of %s, got %s", list,
                       sd_desc(n, got, sizeof got));
    }
    return SD_OK;
}

/* The subkeys of {min: .., max: ..} forms: only min and max, both given. */
static sd_status sd_read_min_max(sd_parse *p, yaml_node_t *n, const char *key, yaml_node_t **mn,
                                 yaml_node_t **mx)
{
    char sub[160], got[96];
    for (yaml_node_pair_t *q = n->data.mapping.pairs.start; q < n->data.mapping.pairs.top; ++q) {
        yaml_node_t *kn = yaml_document_get_node(p->doc, q->key);
        const char *name = kn->type == YAML_SCALAR_NODE ? sd_scalar(kn) : "?";
        if (strcmp(name, "min") && strcmp(name, "max"))
            return sd_fail(p, sd_line(kn), sd_kp(sub, sizeof sub, key, name),
                           "unknown key %s (expected min and max)", sd_desc(kn, got, sizeof got));
    }
    *mn = sd_map_get(p, n, "min");
    *mx = sd_map_get(p, n, "max");
    if (!*mn || !*mx)
        return sd_fail(p, sd_line(n), sd_kp(sub, sizeof sub, key, *mn ? "max" : "min"),
                       "missing required key '%s'", *mn ? "max" : "min");
    return SD_OK;
}

/* Checks n against row k and fills v. Absent keys are handled by sd_get. */
static sd_status sd_read_value(sd_parse *p, const sd_scene_key *k, yaml_node_t *n, const char *key,
                               sd_value *v)
{
    char got[96], sub[160];
    sd_status st = SD_OK;
    memset(v, 0, sizeof *v);
    v->node = n;
    v->line = sd_line(n);
    switch (k->type) {
    case SD_KT_MAP:
        if (!sd_is_null(n) && n->type != YAML_MAPPING_NODE)
            return sd_fail(p, v->line, key, "expected a mapping (key: value lines), got %s",
                           sd_desc(n, got, sizeof got));
        break;
    case SD_KT_LIST:
        if (!sd_is_null(n) && n->type != YAML_SEQUENCE_NODE)
            return sd_fail(p, v->line, key, "expected a list (lines starting with '- '), got %s",
                           sd_desc(n, got, sizeof got));
        break;
    case SD_KT_NUMBER: st = sd_read_number(p, k, n, key, "", "", &v->num); break;
    case SD_KT_INT:
        st = sd_read_int(p, k, n, key, "", &v->integer);
        v->num = (double)v->integer;
        break;
    case SD_KT_STRING: st = sd_read_string(p, k, n, key, &v->str); break;
    case SD_KT_ENUM:
        st = sd_read_choice(p, k, n, key, &v->choice);
        if (st == SD_OK)
            v->str = sd_scalar(n);
        break;
    case SD_KT_ENUM_LIST:
        if (sd_is_null(n))
            break;
        if (n->type != YAML_SEQUENCE_NODE)
            return sd_fail(p, v->line, key, "expected a list such as [a, b], got %s",
                           sd_desc(n, got, sizeof got));
        for (size_t i = 0; i < sd_seq_len(n); ++i) {
            int c;
            if ((st = sd_read_choice(p, k, sd_seq_item(p, n, i), key, &c)) != SD_OK)
                return st;
            v->mask |= 1u << c;
        }
        break;
    case SD_KT_VEC3: st = sd_read_vec3(p, k, n, key, v->v, NULL); break;
    case SD_KT_INT3: st = sd_read_vec3(p, k, n, key, v->v, v->iv); break;
    case SD_KT_NUM_OR_VEC3:
        if (n && n->type == YAML_SEQUENCE_NODE) {
            st = sd_read_vec3(p, k, n, key, v->v, NULL);
        } else {
            st = sd_read_number(p, k, n, key, "", " or [x, y, z]", &v->num);
            v->v[0] = v->v[1] = v->v[2] = v->num;
        }
        break;
    case SD_KT_NUM_OR_RANGE:
        if (n && n->type == YAML_MAPPING_NODE) {
            yaml_node_t *mn, *mx;
            if ((st = sd_read_min_max(p, n, key, &mn, &mx)) != SD_OK)
                return st;
            if ((st = sd_read_number(p, k, mn, sd_kp(sub, sizeof sub, key, "min"), "", "", &v->lo)))
                return st;
            if ((st = sd_read_number(p, k, mx, sd_kp(sub, sizeof sub, key, "max"), "", "", &v->hi)))
                return st;
            if (v->hi < v->lo)
                return sd_fail(p, sd_line(mx), sub, "expected max >= min (%g), got %g", v->lo,
                               v->hi);
        } else {
            st = sd_read_number(p, k, n, key, "", " or {min: a, max: b}", &v->lo);
            v->hi = v->lo;
        }
        v->num = v->hi;
        break;
    case SD_KT_BOX: {
        yaml_node_t *mn, *mx;
        double lo[3], hi[3];
        if (!n || n->type != YAML_MAPPING_NODE)
            return sd_fail(p, v->line, key, "expected {min: [x, y, z], max: [x, y, z]}, got %s",
                           sd_desc(n, got, sizeof got));
        if ((st = sd_read_min_max(p, n, key, &mn, &mx)) != SD_OK)
            return st;
        if ((st = sd_read_vec3(p, k, mn, sd_kp(sub, sizeof sub, key, "min"), lo, NULL)))
            return st;
        if ((st = sd_read_vec3(p, k, mx, sd_kp(sub, sizeof sub, key, "max"), hi, NULL)))
            return st;
        for (int a = 0; a < 3; ++a)
            if (!(hi[a] > lo[a]))
                return sd_fail(p, sd_line(mx), sub,
                               "expected max > min on every axis, got max %c = %g <= min %c = %g",
                               'x' + a, hi[a], 'x' + a, lo[a]);
        v->box_lo = (sd_v3d){lo[0], lo[1], lo[2]};
        v->box_hi = (sd_v3d){hi[0], hi[1], hi[2]};
        break;
    }
    case SD_KT_NAME_PAIR:
        if (!n || n->type != YAML_SEQUENCE_NODE || sd_seq_len(n) != 2)
            return sd_fail(p, v->line, key, "expected a list of 2 material names, got %s",
                           sd_desc(n, got, sizeof got));
        for (size_t i = 0; i < 2; ++i)
            if ((st = sd_read_string(p, k, sd_seq_item(p, n, i), key, &v->names[i])) != SD_OK)
                return st;
        break;
    case SD_KT_ORIENTATION:
        if (n && n->type == YAML_SEQUENCE_NODE) {
            static const char *const comp[4] = {" for w", " for x", " for y", " for z"};
            double norm = 0.0;
            if (sd_seq_len(n) != 4)
                return sd_fail(p, v->line, key,
                               "expected identity, random or a quaternion [w, x, y, z], got %s",
                               sd_desc(n, got, sizeof got));
            for (size_t i = 0; i < 4; ++i) {
                if ((st = sd_read_number(p, k, sd_seq_item(p, n, i), key, comp[i], "", &v->q[i])))
                    return st;
                norm += v->q[i] * v->q[i];
            }
            norm = sqrt(norm);
            if (!(norm > 1e-12) || !isfinite(norm))
                return sd_fail(p, v->line, key, "expected a non-zero quaternion [w, x, y, z], got %s",
                               sd_desc(n, got, sizeof got));
            for (size_t i = 0; i < 4; ++i)
                v->q[i] /= norm;
            v->choice = SD_ORIENT_FIXED;
        } else if (n && n->type == YAML_SCALAR_NODE && !strcmp(sd_scalar(n), "identity")) {
            v->choice = SD_ORIENT_IDENTITY;
        } else if (n && n->type == YAML_SCALAR_NODE && !strcmp(sd_scalar(n), "random")) {
            v->choice = SD_ORIENT_RANDOM;
        } else {
            return sd_fail(p, v->line, key,
                           "expected identity, random or a quaternion [w, x, y, z], got %s",
                           sd_desc(n, got, sizeof got));
        }
        break;
    case SD_KT_VEC3_LIST:
        if (!n || n->type != YAML_SEQUENCE_NODE)
            return sd_fail(p, v->line, key, "expected a list of [x, y, z], got %s",
                           sd_desc(n, got, sizeof got));
        for (size_t i = 0; i < sd_seq_len(n); ++i) {
            snprintf(sub, sizeof sub, "%s[%zu]", key, i);
            if ((st = sd_read_vec3(p, k, sd_seq_item(p, n, i), sub, v->v, NULL)) != SD_OK)
                return st;
        }
        break;
    case SD_KT_VEC2: st = sd_read_vec2(p, k, n, key, v->v); break;
    case SD_KT_VEC2_LIST:
        if (!n || n->type != YAML_SEQUENCE_NODE)
            return sd_fail(p, v->line, key, "expected a list of [x, y], got %s", sd_desc(n, got, sizeof got));
        for (size_t i = 0; i < sd_seq_len(n); ++i) {
            snprintf(sub, sizeof sub, "%s[%zu]", key, i);
            if ((st = sd_read_vec2(p, k, sd_seq_item(p, n, i), sub, v->v)) != SD_OK)
                return st;
        }
        break;
    case SD_KT_NUM_LIST:
        if (!n || n->type != YAML_SEQUENCE_NODE)
            return sd_fail(p, v->line, key, "expected a list of numbers such as [0.05, 0.001], got %s",
                           sd_desc(n, got, sizeof got));
        for (size_t i = 0; i < sd_seq_len(n); ++i) {
            snprintf(sub, sizeof sub, "%s[%zu]", key, i);
            if ((st = sd_read_number(p, k, sd_seq_item(p, n, i), sub, "", "", &v->num)) != SD_OK)
                return st;
        }
        break;
    }
    return st;
}

/* Edit distance of two short keys, for "did you mean" (capped inputs). */
static int sd_edit_distance(const char *a, const char *b)
{
    int la = (int)strlen(a), lb = (int)strlen(b);
    if (la > 40 || lb > 40)
        return 99;
    int row[41];
    for (int j = 0; j <= lb; ++j)
        row[j] = j;
    for (int i = 1; i <= la; ++i) {
        int diag = row[0];
        row[0] = i;
        for (int j = 1; j <= lb; ++j) {
            int up = row[j];
            int best = diag + (a[i - 1] != b[j - 1]);
            if (row[j] + 1 < best)
                best = row[j] + 1;
            if (row[j - 1] + 1 < best)
                best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[lb];
}

static sd_status sd_unknown_key(sd_parse *p, sd_scene_section sec, const char *name, int line,
                                const char *key)
{
    const char *best = NULL;
    int best_d = 3; /* suggest only close matches: a typo, not another key */
    char known[400];
    size_t used = 0;
    known[0] = '\0';
    for (size_t i = 0; i < sd_scene_key_count; ++i) {
        const sd_scene_key *k = &sd_scene_keys[i];
        if (k->section != sec)
            continue;
        int d = sd_edit_distance(name, k->key);
        if (d < best_d) {
            best_d = d;
            best = k->key;
        }
        if (used + 1 < sizeof known) {
            int w = snprintf(known + used, sizeof known - used, "%s%s", used ? ", " : "", k->key);
            used += w > 0 ? (size_t)w : 0;
        }
    }
    char esc[96]; /* the scene's bytes, escaped: a "\e[31m" key would reach the terminal */
    sd_escape(esc, sizeof esc, name, (size_t)-1);
    if (best)
        return sd_fail(p, line, key, "unknown key '%s' (did you mean '%s'?)", esc, best);
    return sd_fail(p, line, key, "unknown key '%s' (expected one of: %s)", esc, known);
}

/* Checks every key of map against the table rows of sec for one kind (a
 * generator or wall type bit, SD_KIND_ALL elsewhere): known, applicable,
 * not repeated, well-typed; then that the required ones are there. */
static sd_status sd_check_map(sd_parse *p, yaml_node_t *map, sd_scene_section sec, unsigned kind,
                              const char *kind_name, const char *path, int line)
{
    char key[160], got[96];
    sd_value v;
    sd_status st;
    if (map && map->type == YAML_MAPPING_NODE) {
        for (yaml_node_pair_t *q = map->data.mapping.pairs.start; q < map->data.mapping.pairs.top;
             ++q) {
            yaml_node_t *kn = yaml_document_get_node(p->doc, q->key);
            yaml_node_t *vn = yaml_document_get_node(p->doc, q->value);
            if (kn->type != YAML_SCALAR_NODE)
                return sd_fail(p, sd_line(kn), path, "expected a key name, got %s",
                               sd_desc(kn, got, sizeof got));
            const char *name = sd_scalar(kn);
            sd_kp(key, sizeof key, path, name);
            const sd_scene_key *k = sd_scene_key_find(sec, name);
            if (!k)
                return sd_unknown_key(p, sec, name, sd_line(kn), key);
            if (!(k->kinds & kind))
                return sd_fail(p, sd_line(kn), key, "key '%s' does not apply to %s", name,
                               kind_name);
            for (yaml_node_pair_t *r = map->data.mapping.pairs.start; r < q; ++r) {
                yaml_node_t *prev = yaml_document_get_node(p->doc, r->key);
                if (prev->type == YAML_SCALAR_NODE && !strcmp(sd_scalar(prev), name))
                    return sd_fail(p, sd_line(kn), key, "duplicate key '%s' (first given at line %d)",
                                   name, sd_line(prev));
            }
            if ((st = sd_read_value(p, k, vn, key, &v)) != SD_OK)
                return st;
        }
    }
    for (size_t i = 0; i < sd_scene_key_count; ++i) {
        const sd_scene_key *k = &sd_scene_keys[i];
        if (k->section == sec && (k->required & kind) && !sd_map_get(p, map, k->key))
            return sd_fail(p, line, sd_kp(key, sizeof key, path, k->key),
                           "missing required key '%s' (%s)", k->key, k->doc);
    }
    return SD_OK;
}

/* The value of a key already checked by sd_check_map. Returns 1 if given;
 * 0 if absent, with v holding the table default when it is a number or a
 * vector (so defaults live in the table only). */
static int sd_get(sd_parse *p, yaml_node_t *map, sd_scene_section sec, const char *name,
                  const char *path, sd_value *v)
{
    const sd_scene_key *k = sd_scene_key_find(sec, name);
    yaml_node_t *n = sd_map_get(p, map, name);
    memset(v, 0, sizeof *v);
    if (!k)
        return 0; /* a bug: every name used here is in the table */
    if (n) {
        char key[160];
        /* Cannot fail: sd_check_map has read the same node with the same row. */
        sd_read_value(p, k, n, sd_kp(key, sizeof key, path, name), v);
        return 1;
    }
    double a, b, c;
    if (sscanf(k->def, "[%lf , %lf , %lf ]", &a, &b, &c) == 3) {
        v->v[0] = a;
        v->v[1] = b;
        v->v[2] = c;
    } else if (sscanf(k->def, "%lf", &a) == 1) {
        v->num = v->lo = v->hi = a;
        v->integer = (long long)a;
    }
    return 0;
}

static sd_v3d sd_v3(const double v[3]) { return (sd_v3d){v[0], v[1], v[2]}; }

static int sd_find_material(const sd_scene *s, const char *name)
{
    for (size_t i = 0; i < s->material_count; ++i)
        if (!strcmp(s->materials[i].name, name))
            return (int)i;
    return -1;
}

static sd_status sd_material_ref(sd_parse *p, const char *name, int line, const char *key, int *out)
{
    *out = sd_find_material(p->s, name);
    if (*out >= 0)
        return SD_OK;
    char known[300];
    size_t used = 0;
    known[0] = '\0';
    for (size_t i = 0; i < p->s->material_count && used + 1 < sizeof known; ++i) {
        int w = snprintf(known + used, sizeof known - used, "%s%s", i ? ", " : "",
                         p->s->materials[i].name);
        used += w > 0 ? (size_t)w : 0;
    }
    char esc[96];
    sd_escape(esc, sizeof esc, name, (size_t)-1);
    return sd_fail(p, line, key, "unknown material '%s' (materials: %s)", esc, known);
}

/* ---- sections ----------------------------------------------------------- */

static sd_status sd_parse_simulation(sd_parse *p, yaml_node_t *root)
{
    sd_scene *s = p->s;
    yaml_node_t *sim = sd_map_get(p, root, "simulation");
    const char *path = "simulation";
    sd_value v;
    sd_status st;
    if ((st = sd_check_map(p, sim, SD_SEC_SIMULATION, SD_KIND_ALL, "", path, s->simulation_line)))
        return st;
    s->world = sd_world_def_default();

    sd_get(p, sim, SD_SEC_SIMULATION, "dimension", path, &v);
    if (v.integer != 3 && v.integer != 2)
        return sd_fail(p, v.line, "simulation.dimension", "expected 2 or 3, got %lld", v.integer);
    s->world.dimension = (int)v.integer;
    sd_get(p, sim, SD_SEC_SIMULATION, "local_damping", path, &v);
    if (!(v.num < 1.0))
        return sd_fail(p, v.line, "simulation.local_damping", "expected a coefficient in [0, 1), got %g", v.num);
    s->world.local_damping = v.num;

    sd_get(p, sim, SD_SEC_SIMULATION, "dt", path, &v);
    s->world.dt = v.num;
    s->dt_line = v.line;

    sd_value steps, duration;
    int has_steps = sd_get(p, sim, SD_SEC_SIMULATION, "steps", path, &steps);
    int has_duration = sd_get(p, sim, SD_SEC_SIMULATION, "duration", path, &duration);
    if (has_steps && has_duration)
        return sd_fail(p, duration.line, "simulation.duration",
                       "give either steps or duration, not both (steps is at line %d)", steps.line);
    if (!has_steps && !has_duration)
        return sd_fail(p, s->simulation_line, "simulation.steps",
                       "missing the run length: give steps or duration (s), exactly one");
    if (has_steps) {
        s->steps = (long)steps.integer;
    } else {
        double n = ceil(duration.num / s->world.dt - 1e-9);
        if (n > 1e15)
            return sd_fail(p, duration.line, "simulation.duration",
                           "duration / dt = %g steps is too many", n);
        s->steps = n > 0.0 ? (long)n : 0;
    }

    sd_get(p, sim, SD_SEC_SIMULATION, "gravity", path, &v);
    s->world.gravity = sd_v3(v.v);
    if (s->world.dimension == 2 && v.v[2] != 0.0)
        return sd_fail(p, v.line ? v.line : s->simulation_line, "simulation.gravity",
                       "dimension 2 needs gravity in the x-y plane, [gx, gy, 0]; got z = %g%s", v.v[2],
                       v.line ? "" : " (the default [0, 0, -9.81])");
    sd_get(p, sim, SD_SEC_SIMULATION, "seed", path, &v);
    s->world.seed = (uint64_t)v.integer;
    sd_get(p, sim, SD_SEC_SIMULATION, "threads", path, &v);
    if (v.integer > SD_SCENE_MAX_THREADS)
        return sd_fail(p, v.line, "simulation.threads",
                       "expected at most %d threads, got %lld (results are the same for any thread count; "
                       "0 uses all cores)",
                       SD_SCENE_MAX_THREADS, v.integer);
    s->world.threads = (int)v.integer;
    if (sd_get(p, sim, SD_SEC_SIMULATION, "contact_law", path, &v)) {
        s->world.law = sd_contact_law_from_name(v.str);
    } else {
        const sd_scene_key *k = sd_scene_key_find(SD_SEC_SIMULATION, "contact_law");
        s->world.law = sd_contact_law_from_name(k->def);
    }
    if (s->world.law == SD_LAW_COUNT)
        return sd_fail(p, v.line, "simulation.contact_law", "unknown contact law");
    sd_get(p, sim, SD_SEC_SIMULATION, "skin", path, &v);
    s->world.skin = v.num;
    /* choices in sd_solver order: cells, grid */
    if (sd_get(p, sim, SD_SEC_SIMULATION, "solver", path, &v))
        s->world.solver = v.choice == 1 ? SD_SOLVER_GRID : SD_SOLVER_CELLS;
    return SD_OK;
}

static sd_status sd_parse_materials(sd_parse *p, yaml_node_t *list, int line)
{
    sd_scene *s = p->s;
    size_t n = sd_seq_len(list);
    char path[64], key[96];
    sd_value v;
    sd_status st;
    if (n == 0)
        return sd_fail(p, line, "materials", "expected at least one material, got %s",
                       list ? "an empty list" : "nothing");
    s->materials = sd_calloc(n, sizeof *s->materials);
    if (!s->materials)
        return sd_error_set(p->err, SD_ERR_MEMORY, p->path, 0, "", "out of memory");
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m = sd_seq_item(p, list, i);
        sd_scene_material *sm = &s->materials[i];
        char got[96];
        snprintf(path, sizeof path, "materials[%zu]", i);
        if (m->type != YAML_MAPPING_NODE)
            return sd_fail(p, sd_line(m), path, "expected a mapping (name: ..., density: ...), got %s",
                           sd_desc(m, got, sizeof got));
        if ((st = sd_check_map(p, m, SD_SEC_MATERIAL, SD_KIND_ALL, "", path, sd_line(m))))
            return st;
        sm->line = sd_line(m);
        sd_get(p, m, SD_SEC_MATERIAL, "name", path, &v);
        if (strlen(v.str) >= SD_SCENE_NAME_MAX)
            return sd_fail(p, v.line, sd_kp(key, sizeof key, path, "name"),
                           "name longer than %d characters", SD_SCENE_NAME_MAX - 1);
        for (size_t j = 0; j < i; ++j)
            if (!strcmp(s->materials[j].name, v.str)) {
                return sd_fail(p, v.line, sd_kp(key, sizeof key, path, "name"),
                               "duplicate material name '%s' (materials[%zu], line %d)",
                               v.str, j, s->materials[j].line);
            }
        snprintf(sm->name, sizeof sm->name, "%s", v.str);
        s->material_count = i + 1;

        sd_material_def *d = &sm->def;
        *d = sd_material_def_default();
        sd_get(p, m, SD_SEC_MATERIAL, "density", path, &v);
        d->density = v.num;
        /* Absent means unset (0); the law checks below decide if it is needed. */
        d->youngs_modulus = sd_get(p, m, SD_SEC_MATERIAL, "youngs_modulus", path, &v) ? v.num : 0.0;
        sd_get(p, m, SD_SEC_MATERIAL, "poisson_ratio", path, &v);
        d->poisson_ratio = v.num;
        sd_get(p, m, SD_SEC_MATERIAL, "restitution", path, &v);
        d->restitution = v.num;
        sd_get(p, m, SD_SEC_MATERIAL, "friction", path, &v);
        d->friction = v.num;
        sd_get(p, m, SD_SEC_MATERIAL, "rolling_friction", path, &v);
        d->rolling_friction = v.num;
        sd_get(p, m, SD_SEC_MATERIAL, "stiffness", path, &v);
        d->stiffness = v.num;
        sd_get(p, m, SD_SEC_MATERIAL, "tangential_stiffness_ratio", path, &v);
        d->tangential_stiffness_ratio = v.num;
        sd_get(p, m, SD_SEC_MATERIAL, "damping", path, &v);
        d->damping = v.num;
        sd_get(p, m, SD_SEC_MATERIAL, "volume_stiffness", path, &v);
        d->volume_stiffness = v.num;
    }
    /* Names point into the array only now that it will not move. */
    for (size_t i = 0; i < n; ++i)
        s->materials[i].def.name = s->materials[i].name;
    return SD_OK;
}

static sd_status sd_parse_interactions(sd_parse *p, yaml_node_t *list)
{
    sd_scene *s = p->s;
    size_t n = sd_seq_len(list);
    char path[64], key[96], got[96];
    sd_value v;
    sd_status st;
    if (n == 0)
        return SD_OK;
    s->interactions = sd_calloc(n, sizeof *s->interactions);
    if (!s->interactions)
        return sd_error_set(p->err, SD_ERR_MEMORY, p->path, 0, "", "out of memory");
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m = sd_seq_item(p, list, i);
        sd_scene_interaction *si = &s->interactions[i];
        snprintf(path, sizeof path, "interactions[%zu]", i);
        if (m->type != YAML_MAPPING_NODE)
            return sd_fail(p, sd_line(m), path, "expected a mapping (between: [a, b], ...), got %s",
                           sd_desc(m, got, sizeof got));
        if ((st = sd_check_map(p, m, SD_SEC_INTERACTION, SD_KIND_ALL, "", path, sd_line(m))))
            return st;
        si->line = sd_line(m);
        sd_get(p, m, SD_SEC_INTERACTION, "between", path, &v);
        snprintf(key, sizeof key, "%s.between", path);
        if ((st = sd_material_ref(p, v.names[0], v.line, key, &si->mat_a)))
            return st;
        if ((st = sd_material_ref(p, v.names[1], v.line, key, &si->mat_b)))
            return st;
        for (size_t j = 0; j < i; ++j) {
            const sd_scene_interaction *o = &s->interactions[j];
            if ((o->mat_a == si->mat_a && o->mat_b == si->mat_b) ||
                (o->mat_a == si->mat_b && o->mat_b == si->mat_a))
                return sd_fail(p, v.line, key,
                               "a second interaction between '%s' and '%s' (the first is "
                               "interactions[%zu], line %d)",
                               v.names[0], v.names[1], j, o->line);
        }
        s->interaction_count = i + 1;
        si->def = sd_interaction_def_default();
        /* Absent keys keep the mixed value: a negative value in the def. */
        si->def.restitution = sd_get(p, m, SD_SEC_INTERACTION, "restitution", path, &v) ? v.num : -1.0;
        si->def.friction = sd_get(p, m, SD_SEC_INTERACTION, "friction", path, &v) ? v.num : -1.0;
        si->def.rolling_friction =
            sd_get(p, m, SD_SEC_INTERACTION, "rolling_friction", path, &v) ? v.num : -1.0;
        si->def.stiffness = sd_get(p, m, SD_SEC_INTERACTION, "stiffness", path, &v) ? v.num : -1.0;
        si->def.damping = sd_get(p, m, SD_SEC_INTERACTION, "damping", path, &v) ? v.num : -1.0;
        si->def.volume_stiffness = sd_get(p, m, SD_SEC_INTERACTION, "volume_stiffness", path, &v) ? v.num : -1.0;
        si->def.law = sd_get(p, m, SD_SEC_INTERACTION, "contact_law", path, &v)
                          ? (int)sd_contact_law_from_name(v.str)
                          : -1;
        if (si->def.law == SD_LAW_COUNT)
            return sd_fail(p, v.line, sd_kp(key, sizeof key, path, "contact_law"),
                           "unknown contact law");
    }
    return SD_OK;
}

/* ---- CSV particles ------------------------------------------------------ */

static char *sd_trim(char *t)
{
    while (*t == ' ' || *t == '\t')
        ++t;
    size_t n = strlen(t);
    while (n > 0 && (t[n - 1] == ' ' || t[n - 1] == '\t' || t[n - 1] == '\r' || t[n - 1] == '\n'))
        t[--n] = '\0';
    return t;
}

enum {
    SD_CSV_X, SD_CSV_Y, SD_CSV_Z, SD_CSV_R, SD_CSV_VX, SD_CSV_VY, SD_CSV_VZ, SD_CSV_SHAPE,
    SD_CSV_QW, SD_CSV_QX, SD_CSV_QY, SD_CSV_QZ, SD_CSV_WX, SD_CSV_WY, SD_CSV_WZ, SD_CSV_MATERIAL,
    SD_CSV_NCOL
};
static const char *const sd_csv_names[SD_CSV_NCOL] = {
    "x", "y", "z", "radius", "vx", "vy", "vz", "shape", "qw", "qx", "qy", "qz", "wx", "wy", "wz", "material"};

/* "a, b, c": the names of the scene's shapes (materials: 1) for messages. */
static const char *sd_csv_known(const sd_scene *s, int materials, char *buf, size_t size)
{
    size_t used = 0, n = materials ? s->material_count : s->shape_count;
    buf[0] = '\0';
    for (size_t i = 0; i < n && used + 1 < size; ++i) {
        int w = snprintf(buf + used, size - used, "%s%s", i ? ", " : "",
                         materials ? s->materials[i].name : s->shapes[i].name);
        used += w > 0 ? (size_t)w : 0;
    }
    return n ? buf : "none";
}

/* Grows the generator's entry arrays to cap entries (all or none grow, so a
 * failure leaves the list consistent). */
static int sd_csv_grow(sd_scene_generator *g, size_t cap)
{
    void *q;
    if (!(q = sd_realloc(g->list, cap * sizeof *g->list)))
        return 0;
    g->list = q;
    if (!(q = sd_realloc(g->list_lines, cap * sizeof *g->list_lines)))
        return 0;
    g->list_lines = q;
    if (!(q = sd_realloc(g->list_shape, cap * sizeof *g->list_shape)))
        return 0;
    g->list_shape = q;
    if (!(q = sd_realloc(g->list_orient, cap * sizeof *g->list_orient)))
        return 0;
    g->list_orient = q;
    if (!(q = sd_realloc(g->list_quat, cap * sizeof *g->list_quat)))
        return 0;
    g->list_quat = q;
    return 1;
}

/* Reads g->file: a header naming the columns, then one particle per row: a
 * sphere (radius) or a body of a shape (shape, with an orientation from
 * qw..qz or the generator's). Empty cells of optional columns take the
 * generator's value, so a packing of spheres and shapes fits one file.
 * Errors name the CSV file and its line; the key names the generator. */
static sd_status sd_read_csv(sd_parse *p, sd_scene_generator *g, const char *key, int file_line)
{
    FILE *f = fopen(g->file, "rb");
    if (!f)
        return sd_fail(p, file_line, key, "cannot open the CSV file '%s': %s", g->file,
                       strerror(errno));
    char buf[4096], known[300], esc[64]; /* esc: file bytes, escaped */
    int col_of[SD_CSV_NCOL]; /* column -> SD_CSV_* index */
    int ncols = 0, line = 0, have_header = 0;
    size_t cap = 0;
    sd_status st = SD_OK;
    while (fgets(buf, sizeof buf, f)) {
        ++line;
        if (!strchr(buf, '\n') && !feof(f)) {
            st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key, "line longer than %zu characters",
                              sizeof buf - 2);
            break;
        }
        char *t = sd_trim(buf);
        if (!t[0] || t[0] == '#')
            continue;
        if (!have_header) {
            int seen[SD_CSV_NCOL] = {0};
            for (char *c = t; c; ++ncols) {
                char *next = strchr(c, ',');
                if (next)
                    *next++ = '\0';
                char *name = sd_trim(c);
                int idx = -1;
                for (int j = 0; j < SD_CSV_NCOL; ++j)
                    if (!strcmp(name, sd_csv_names[j]))
                        idx = j;
                /* SD_CSV_NCOL distinct names: a longer header repeats one */
                if (idx < 0 || ncols >= SD_CSV_NCOL || seen[idx]) {
                    sd_escape(esc, sizeof esc, name, (size_t)-1);
                    st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                                      "%s column '%s' in the header (expected the columns x, y, z, "
                                      "radius and/or shape, and optionally vx, vy, vz, qw, qx, qy, "
                                      "qz, wx, wy, wz, material)",
                                      idx < 0 ? "unknown" : "repeated", esc);
                    goto done;
                }
                seen[idx] = 1;
                col_of[ncols] = idx;
                c = next;
            }
            for (int j = 0; j <= SD_CSV_R; ++j)
                if (!seen[j] && !(j == SD_CSV_R && (seen[SD_CSV_SHAPE] || g->shape >= 0))) {
                    st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                                      "the header line has no '%s' column (expected a header such "
                                      "as x,y,z,radius or x,y,z,shape)",
                                      sd_csv_names[j]);
                    goto done;
                }
            int nq = seen[SD_CSV_QW] + seen[SD_CSV_QX] + seen[SD_CSV_QY] + seen[SD_CSV_QZ];
            if (nq != 0 && nq != 4) {
                st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                                  "the header names %d of the orientation columns qw, qx, qy, qz "
                                  "(expected all four or none)",
                                  nq);
                goto done;
            }
            have_header = 1;
            continue;
        }
        char *cell[SD_CSV_NCOL] = {0};
        int col = 0;
        for (char *c = t; c; ++col) {
            char *next = strchr(c, ',');
            if (next)
                *next++ = '\0';
            if (col >= ncols) {
                st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                                  "expected %d values as in the header, got more", ncols);
                goto done;
            }
            cell[col_of[col]] = sd_trim(c);
            c = next;
        }
        if (col != ncols) {
            st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                              "expected %d values as in the header, got %d", ncols, col);
            goto done;
        }
        double val[SD_CSV_NCOL] = {0};
        int has[SD_CSV_NCOL] = {0};
        for (int j = 0; j < SD_CSV_NCOL; ++j) {
            if (!cell[j] || j == SD_CSV_SHAPE || j == SD_CSV_MATERIAL)
                continue;
            if (!cell[j][0] && j > SD_CSV_Z)
                continue; /* an empty optional cell: the generator's value */
            char *end;
            double x = strtod(cell[j], &end);
            if (!cell[j][0] || *end || !isfinite(x)) {
                sd_escape(esc, sizeof esc, cell[j], 40);
                st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                                  "column %s: expected a number, got '%s'", sd_csv_names[j], esc);
                goto done;
            }
            val[j] = x;
            has[j] = 1;
        }
        if (has[SD_CSV_R] && !(val[SD_CSV_R] > 0.0)) {
            st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                              "column radius: expected a number > 0, got %s", cell[SD_CSV_R]);
            goto done;
        }
        /* A sphere (radius) or a body of a shape (the row's, or the generator's). */
        int shape = -1;
        const char *sname = cell[SD_CSV_SHAPE] ? cell[SD_CSV_SHAPE] : "";
        if (sname[0]) {
            if (has[SD_CSV_R]) {
                st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                                  "give either radius (a sphere) or shape on a row, not both");
                goto done;
            }
            for (size_t i = 0; i < p->s->shape_count && shape < 0; ++i)
                if (!strcmp(p->s->shapes[i].name, sname))
                    shape = (int)i;
            if (shape < 0) {
                sd_escape(esc, sizeof esc, sname, 40);
                st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                                  "column shape: unknown shape '%s' (shapes: %s)", esc,
                                  sd_csv_known(p->s, 0, known, sizeof known));
                goto done;
            }
        } else if (!has[SD_CSV_R]) {
            if (g->shape < 0) {
                st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                                  "expected a radius (a sphere) or a shape name, got neither");
                goto done;
            }
            shape = g->shape;
        }
        sd_scene_orient orient = g->orient;
        double q[4] = {g->quat[0], g->quat[1], g->quat[2], g->quat[3]};
        int nq = has[SD_CSV_QW] + has[SD_CSV_QX] + has[SD_CSV_QY] + has[SD_CSV_QZ];
        if (nq != 0 && nq != 4) {
            st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                              "columns qw, qx, qy, qz: expected all four values or none, got %d", nq);
            goto done;
        }
        if (nq == 4) {
            if (shape < 0) {
                st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                                  "columns qw, qx, qy, qz: an orientation applies to bodies of a "
                                  "shape only (this row is a sphere: leave them empty)");
                goto done;
            }
            /* scaled by the largest component first, so that no square overflows */
            double m = 0.0, norm = 0.0;
            for (int k = 0; k < 4; ++k)
                m = fmax(m, fabs(val[SD_CSV_QW + k]));
            if (!(m > 0.0)) {
                st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                                  "columns qw, qx, qy, qz: expected a non-zero quaternion, got 0, 0, "
                                  "0, 0");
                goto done;
            }
            for (int k = 0; k < 4; ++k) {
                q[k] = val[SD_CSV_QW + k] / m;
                norm += q[k] * q[k];
            }
            norm = sqrt(norm);
            for (int k = 0; k < 4; ++k)
                q[k] /= norm;
            orient = SD_ORIENT_FIXED;
        }
        int material = g->material;
        if (cell[SD_CSV_MATERIAL] && cell[SD_CSV_MATERIAL][0]) {
            material = -1;
            for (size_t i = 0; i < p->s->material_count && material < 0; ++i)
                if (!strcmp(p->s->materials[i].name, cell[SD_CSV_MATERIAL]))
                    material = (int)i;
            if (material < 0) {
                sd_escape(esc, sizeof esc, cell[SD_CSV_MATERIAL], 40);
                st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key,
                                  "column material: unknown material '%s' (materials: %s)", esc,
                                  sd_csv_known(p->s, 1, known, sizeof known));
                goto done;
            }
        }
        if (g->list_count == cap) {
            size_t ncap = cap ? 2 * cap : 256;
            if (!sd_csv_grow(g, ncap)) {
                st = sd_error_set(p->err, SD_ERR_MEMORY, g->file, line, key, "out of memory");
                goto done;
            }
            cap = ncap;
        }
        size_t k = g->list_count;
        sd_sphere_def *d = &g->list[k];
        memset(d, 0, sizeof *d);
        d->position = (sd_v3d){val[SD_CSV_X], val[SD_CSV_Y], val[SD_CSV_Z]};
        d->radius = shape < 0 ? val[SD_CSV_R] : 0.0; /* a shape's bound is set at generation */
        /* Velocity columns override the generator's velocity, per component. */
        const sd_v3d v0 = g->velocity, w0 = g->angular_velocity;
        d->velocity = (sd_v3d){has[SD_CSV_VX] ? val[SD_CSV_VX] : v0.x, has[SD_CSV_VY] ? val[SD_CSV_VY] : v0.y,
                               has[SD_CSV_VZ] ? val[SD_CSV_VZ] : v0.z};
        d->angular_velocity = (sd_v3d){has[SD_CSV_WX] ? val[SD_CSV_WX] : w0.x,
                                       has[SD_CSV_WY] ? val[SD_CSV_WY] : w0.y,
                                       has[SD_CSV_WZ] ? val[SD_CSV_WZ] : w0.z};
        d->material = material;
        g->list_shape[k] = shape;
        g->list_orient[k] = orient;
        memcpy(g->list_quat[k], q, sizeof q);
        g->list_lines[k] = line;
        g->list_count = k + 1;
    }
    if (st == SD_OK && ferror(f))
        st = sd_error_set(p->err, SD_ERR_IO, g->file, line, key, "read error: %s", strerror(errno));
    else if (st == SD_OK && !have_header)
        st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line > 0 ? line : 0, key,
                          "the CSV file has no header line (expected a header such as "
                          "x,y,z,radius)");
    else if (st == SD_OK && g->list_count == 0)
        st = sd_error_set(p->err, SD_ERR_INPUT, g->file, line, key, "the CSV file has no particles");
done:
    fclose(f);
    return st;
}

/* file relative to the scene file's directory (absolute paths kept). */
static int sd_resolve(const char *scene, const char *file, char *out, size_t size)
{
    const char *slash = strrchr(scene, '/');
    int n;
    if (file[0] == '/' || !slash)
        n = snprintf(out, size, "%s", file);
    else
        n = snprintf(out, size, "%.*s/%s", (int)(slash - scene), scene, file);
    return n >= 0 && (size_t)n < size;
}

/* ---- shapes ------------------------------------------------------------- */

static int sd_v3d_cmp(const void *pa, const void *pb)
{
    const sd_v3d *a = pa, *b = pb;
    if (a->x != b->x)
        return a->x < b->x ? -1 : 1;
    if (a->y != b->y)
        return a->y < b->y ? -1 : 1;
    if (a->z != b->z)
        return a->z < b->z ? -1 : 1;
    return 0;
}

/* The shape is the convex hull of a mesh file's vertices (io/mesh.c reads
 * the file); its faces only prove that the mesh is convex (seed 000 §2.1
 * templates are convex). Repeated vertices (STL repeats each in every
 * triangle) are dropped. A vertex or a face centre deeper than 1e-6 of the
 * mesh's size inside the hull makes the mesh non-convex: an error that
 * says how far, unless take_hull (then a warning in sh->warning). Errors
 * name the scene line of shapes[i].file, and the mesh file in the text. */
#define SD_MESH_CONVEX_REL 1e-6
#define SD_MESH_COORD_MAX 1e60 /* largest |coordinate| in a mesh file */
#define SD_MESH_COORD_MIN 1e-60 /* smallest extent of a mesh file's vertices */
static sd_status sd_read_mesh(sd_parse *p, sd_scene_shape *sh, const char *key, int line, int take_hull)
{
    sd_mesh mesh;
    sd_error merr;
    if (sd_mesh_read(sh->file, &mesh, &merr) != SD_OK) {
        if (merr.code == SD_ERR_MEMORY)
            return sd_error_set(p->err, SD_ERR_MEMORY, p->path, line, key, "out of memory");
        return sd_fail(p, line, key, "%s", merr.msg); /* the message names the mesh file and its line */
    }
    /* the face centres, then the vertices (sorted and made distinct below) */
    struct {
        sd_v3d *v;
        size_t n;
    } vb = {NULL, 0}, fc = {NULL, 0};
    fc.v = sd_malloc((mesh.face_count ? mesh.face_count : 1) * sizeof *fc.v);
    if (!fc.v) {
        sd_mesh_free(&mesh);
        return sd_error_set(p->err, SD_ERR_MEMORY, p->path, line, key, "out of memory");
    }
    for (size_t f = 0; f < mesh.face_count; ++f)
        fc.v[fc.n++] = sd_mesh_face_centre(&mesh, f);
    vb.v = mesh.vertices;
    vb.n = mesh.vertex_count;
    mesh.vertices = NULL; /* now the shape's */
    sd_mesh_free(&mesh);
    if (vb.n > 1)
        qsort(vb.v, vb.n, sizeof *vb.v, sd_v3d_cmp);
    size_t u = 0;
    for (size_t k = 0; k < vb.n; ++k)
        if (u == 0 || sd_v3d_cmp(&vb.v[u - 1], &vb.v[k]) != 0)
            vb.v[u++] = vb.v[k];
    sh->vertices = vb.v;
    sh->vertex_count = u;
    if (u < 4) {
        sd_free(fc.v);
        return sd_fail(p, line, key, "expected at least 4 distinct vertices in '%s', got %zu",
                       sh->file, u);
    }
    if (u > SD_SHAPE_MAX_VERTICES) {
        sd_free(fc.v);
        return sd_fail(p, line, key, "expected at most %d distinct vertices in '%s', got %zu",
                       SD_SHAPE_MAX_VERTICES, sh->file, u);
    }
    /* The hull's tests take products of up to four coordinates (normals of
     * edge cross products), which overflow past 1e77 and underflow below
     * 1e-77: such a file would read as flat. Refuse it, in the file's own
     * numbers (scale: is applied later), with a margin. */
    double big = 0.0, ext = 0.0;
    for (size_t k = 0; k < u; ++k)
        big = fmax(big, fmax(fabs(vb.v[k].x), fmax(fabs(vb.v[k].y), fabs(vb.v[k].z))));
    for (size_t k = 0; k < u; ++k)
        ext = fmax(ext, fmax(fabs(vb.v[k].x - vb.v[0].x), fmax(fabs(vb.v[k].y - vb.v[0].y),
                                                               fabs(vb.v[k].z - vb.v[0].z))));
    if (big > SD_MESH_COORD_MAX || (ext > 0.0 && ext < SD_MESH_COORD_MIN)) {
        sd_free(fc.v);
        return sd_fail(p, line, key,
                       "the vertices of '%s' %s %g in the file's units, too %s to compute its hull (it needs "
                       "coordinates of at most %g and a span of at least %g): write the mesh in other units "
                       "and set scale:",
                       sh->file, big > SD_MESH_COORD_MAX ? "reach" : "span only",
                       big > SD_MESH_COORD_MAX ? big : ext, big > SD_MESH_COORD_MAX ? "large" : "small",
                       SD_MESH_COORD_MAX, SD_MESH_COORD_MIN);
    }
    size_t which;
    double msize, depth = sd_mesh_concavity(vb.v, u, fc.v, fc.n, &which, &msize);
    sd_v3d wp = which < u ? vb.v[which] : fc.v[which - u];
    sd_free(fc.v);
    if (depth == -2)
        return sd_error_set(p->err, SD_ERR_MEMORY, p->path, line, key, "out of memory");
    if (depth < 0)
        return sd_fail(p, line, key, "the vertices of '%s' are flat (or coincide): a polyhedron needs volume",
                       sh->file);
    if (depth > SD_MESH_CONVEX_REL * msize) {
        char what[160];
        if (which < u)
            snprintf(what, sizeof what, "its vertex (%g, %g, %g)", wp.x, wp.y, wp.z);
        else
            snprintf(what, sizeof what, "the centre (%g, %g, %g) of its face %zu", wp.x, wp.y, wp.z,
                     which - u + 1);
        if (!take_hull)
            return sd_fail(p, line, key,
                           "'%s' is not convex: %s lies %g (%.3g %% of its size %g, in the file's units) "
                           "inside its convex hull; set nonconvex: hull to use the hull", sh->file, what, depth,
                           100.0 * depth / msize, msize);
        snprintf(sh->warning, sizeof sh->warning,
                 "'%.150s' is not convex (%s lies %.3g %% of its size inside its hull): using its convex hull",
                 sh->file, what, 100.0 * depth / msize);
    }
    return SD_OK;
}

sd_status sd_scene_read_mesh(const char *path, int take_hull, sd_v3d **vertices, size_t *count, char *warning,
                             size_t warning_size, sd_error *err)
{
    *vertices = NULL;
    *count = 0;
    sd_scene_shape sh;
    memset(&sh, 0, sizeof sh);
    if (strlen(path) >= sizeof sh.file)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "mesh file path longer than %zu bytes",
                            sizeof sh.file - 1);
    snprintf(sh.file, sizeof sh.file, "%s", path);
    /* no scene: messages name the mesh file alone (they all quote it) */
    sd_parse p;
    memset(&p, 0, sizeof p);
    p.path = "";
    p.err = err;
    sd_status st = sd_read_mesh(&p, &sh, "", 0, take_hull);
    if (st != SD_OK) {
        sd_free(sh.vertices);
        return st;
    }
    *vertices = sh.vertices;
    *count = sh.vertex_count;
    if (warning && warning_size)
        snprintf(warning, warning_size, "%s", sh.warning);
    return SD_OK;
}

static sd_status sd_shape_ref(sd_parse *p, const char *name, int line, const char *key, int *out)
{
    for (size_t i = 0; i < p->s->shape_count; ++i)
        if (!strcmp(p->s->shapes[i].name, name)) {
            *out = (int)i;
            return SD_OK;
        }
    char known[300];
    size_t used = 0;
    known[0] = '\0';
    for (size_t i = 0; i < p->s->shape_count && used + 1 < sizeof known; ++i) {
        int w = snprintf(known + used, sizeof known - used, "%s%s", i ? ", " : "",
                         p->s->shapes[i].name);
        used += w > 0 ? (size_t)w : 0;
    }
    char esc[96];
    sd_escape(esc, sizeof esc, name, (size_t)-1);
    if (!p->s->shape_count)
        return sd_fail(p, line, key, "unknown shape '%s' (the scene has no shapes: section)", esc);
    return sd_fail(p, line, key, "unknown shape '%s' (shapes: %s)", esc, known);
}

/* Cylinder and cone: size, or diameter and length (height). */
static sd_status sd_parse_axial(sd_parse *p, yaml_node_t *m, sd_scene_shape *sh, const char *path)
{
    const char *lk = sh->kind == SD_SHAPE_CYLINDER ? "length" : "height";
    char key[96];
    sd_value sz, d, l;
    int hs = sd_get(p, m, SD_SEC_SHAPE, "size", path, &sz);
    int hd = sd_get(p, m, SD_SEC_SHAPE, "diameter", path, &d);
    int hl = sd_get(p, m, SD_SEC_SHAPE, lk, path, &l);
    if (hs && (hd || hl))
        return sd_fail(p, hd ? d.line : l.line, sd_kp(key, sizeof key, path, hd ? "diameter" : lk),
                       "give either size or diameter and %s, not both (size is at line %d)", lk,
                       sz.line);
    if (hs) {
        sh->size = sd_v3(sz.v);
        return SD_OK;
    }
    if (!hd || !hl) {
        const char *miss = !hd && !hl ? "size" : !hd ? "diameter" : lk;
        return sd_fail(p, sh->line, sd_kp(key, sizeof key, path, miss),
                       "missing required key '%s' (give size, or diameter and %s)", miss, lk);
    }
    sh->size = (sd_v3d){d.num, d.num, l.num};
    return SD_OK;
}

/* The keys of a planar shape (dimension 2): radius, axes, points or the
 * Fourier coefficients; the shape itself is checked by the world
 * (sd_world_add_shape2d: convexity, hulls), whose message gets this entry's
 * line. */
static sd_status sd_parse_shape2d(sd_parse *p, yaml_node_t *m, sd_scene_shape *sh, const char *path)
{
    char key[96];
    sd_value v;
    sd_status st;
    switch (sh->kind2d) {
    case SD_SHAPE2D_CIRCLE:
        sd_get(p, m, SD_SEC_SHAPE, "radius", path, &v);
        sh->size = (sd_v3d){v.num, v.num, 0.0};
        break;
    case SD_SHAPE2D_ELLIPSE:
        sd_get(p, m, SD_SEC_SHAPE, "axes", path, &v);
        sh->axes[0] = v.v[0];
        sh->axes[1] = v.v[1];
        break;
    case SD_SHAPE2D_POLYGON:
    case SD_SHAPE2D_POLYBEZIER: {
        sd_get(p, m, SD_SEC_SHAPE, "points", path, &v);
        size_t np = sd_seq_len(v.node);
        sd_kp(key, sizeof key, path, "points");
        int bez = sh->kind2d == SD_SHAPE2D_POLYBEZIER;
        if (np < 3 || np > SD_SHAPE2D_MAX_POINTS || (bez && np % 3 != 0))
            return sd_fail(p, v.line, key, "expected %s (at most %d), got %zu",
                           bez ? "3m control points of m cubic segments, m >= 1" : "at least 3 points",
                           SD_SHAPE2D_MAX_POINTS, np);
        sh->points = sd_calloc(2 * np, sizeof *sh->points);
        if (!sh->points)
            return sd_error_set(p->err, SD_ERR_MEMORY, p->path, 0, "", "out of memory");
        const sd_scene_key *row = sd_scene_key_find(SD_SEC_SHAPE, "points");
        for (size_t k = 0; k < np; ++k)
            if ((st = sd_read_vec2(p, row, sd_seq_item(p, v.node, k), key, sh->points + 2 * k)))
                return st;
        sh->point_count = np;
        break;
    }
    case SD_SHAPE2D_FOURIER: {
        sd_value b;
        sd_get(p, m, SD_SEC_SHAPE, "fourier_a", path, &v);
        int hb = sd_get(p, m, SD_SEC_SHAPE, "fourier_b", path, &b);
        size_t na = sd_seq_len(v.node), nb = hb ? sd_seq_len(b.node) : 0;
        sd_kp(key, sizeof key, path, "fourier_a");
        if (na < 1 || na > SD_SHAPE2D_MAX_ORDER + 1)
            return sd_fail(p, v.line, key, "expected a_0 .. a_N, 1 to %d values, got %zu", SD_SHAPE2D_MAX_ORDER + 1,
                           na);
        if (hb && nb != na - 1)
            return sd_fail(p, b.line, sd_kp(key, sizeof key, path, "fourier_b"),
                           "expected b_1 .. b_N, %zu values (one fewer than fourier_a), got %zu", na - 1, nb);
        sh->fourier_a = sd_calloc(na, sizeof *sh->fourier_a);
        sh->fourier_b = sd_calloc(na, sizeof *sh->fourier_b);
        if (!sh->fourier_a || !sh->fourier_b)
            return sd_error_set(p->err, SD_ERR_MEMORY, p->path, 0, "", "out of memory");
        const sd_scene_key *row = sd_scene_key_find(SD_SEC_SHAPE, "fourier_a");
        for (size_t k = 0; k < na; ++k)
            if ((st = sd_read_number(p, row, sd_seq_item(p, v.node, k), key, "", "", &sh->fourier_a[k])))
                return st;
        for (size_t k = 0; k < nb; ++k)
            if ((st = sd_read_number(p, row, sd_seq_item(p, b.node, k), key, "", "", &sh->fourier_b[k])))
                return st;
        if (!(sh->fourier_a[0] > 0.0))
            return sd_fail(p, v.line, key, "expected a_0 > 0 (twice the mean radius), got %g", sh->fourier_a[0]);
        sh->fourier_count = na;
        break;
    }
    default:
        return sd_fail(p, sh->line, path, "unknown shape type");
    }
    return SD_OK;
}

/* Keys that only a polyhedron preset takes, refused without one. */
static sd_status sd_no_preset_keys(sd_parse *p, yaml_node_t *m, const char *path)
{
    static const char *const only[] = {"size", "diameter", "length", "edge", "sides", "faces", "vertex_count", "seed"};
    char key[96];
    sd_value v;
    for (size_t k = 0; k < sizeof only / sizeof only[0]; ++k)
        if (sd_get(p, m, SD_SEC_SHAPE, only[k], path, &v))
            return sd_fail(p, v.line, sd_kp(key, sizeof key, path, only[k]),
                           "%s applies to a polyhedron preset (preset: ...) only", only[k]);
    return SD_OK;
}

/* A built-in polyhedron (shape/polylib.h): its keys are checked against
 * the preset, then its vertices are made here, as if the scene gave them. */
static sd_status sd_parse_preset(sd_parse *p, yaml_node_t *m, sd_scene_shape *sh, const char *path,
                                 const sd_value *pv)
{
    char key[96];
    sd_poly_def d;
    memset(&d, 0, sizeof d);
    d.preset = pv->choice;
    d.seed = 1;
    const char *name = sd_polylib_name(d.preset);
    const int platonic = d.preset <= SD_POLY_ICOSAHEDRON;
    const int axial = d.preset == SD_POLY_PRISM || d.preset == SD_POLY_CYLINDER;
    const int rnd = d.preset == SD_POLY_RANDOM;
    sd_value sz, dm, ln, ed, sdv, fcv, vcv, sev;
    int hs = sd_get(p, m, SD_SEC_SHAPE, "size", path, &sz);
    int hd = sd_get(p, m, SD_SEC_SHAPE, "diameter", path, &dm);
    int hl = sd_get(p, m, SD_SEC_SHAPE, "length", path, &ln);
    int he = sd_get(p, m, SD_SEC_SHAPE, "edge", path, &ed);
    int hsd = sd_get(p, m, SD_SEC_SHAPE, "sides", path, &sdv);
    int hfc = sd_get(p, m, SD_SEC_SHAPE, "faces", path, &fcv);
    int hvc = sd_get(p, m, SD_SEC_SHAPE, "vertex_count", path, &vcv);
    int hse = sd_get(p, m, SD_SEC_SHAPE, "seed", path, &sev);
    /* keys another preset takes */
    struct {
        int given, ok;
        const sd_value *v;
        const char *k, *who;
    } chk[] = {
        {he, platonic, &ed, "edge", "the Platonic presets"},
        {hd, axial, &dm, "diameter", "the prism and cylinder presets"},
        {hl, axial, &ln, "length", "the prism and cylinder presets"},
        {hsd, axial, &sdv, "sides", "the prism and cylinder presets"},
        {hfc, rnd, &fcv, "faces", "the random preset"},
        {hvc, rnd, &vcv, "vertex_count", "the random preset"},
        {hse, rnd, &sev, "seed", "the random preset"},
    };
    for (size_t k = 0; k < sizeof chk / sizeof chk[0]; ++k)
        if (chk[k].given && !chk[k].ok)
            return sd_fail(p, chk[k].v->line, sd_kp(key, sizeof key, path, chk[k].k),
                           "%s applies to %s, not to %s", chk[k].k, chk[k].who, name);
    if (axial) {
        if (hs && (hd || hl))
            return sd_fail(p, hd ? dm.line : ln.line, sd_kp(key, sizeof key, path, hd ? "diameter" : "length"),
                           "give either size or diameter and length, not both (size is at line %d)", sz.line);
        if (hs) {
            d.diameter = sz.v[0];
            d.length = sz.v[2];
        } else if (hd && hl) {
            d.diameter = dm.num;
            d.length = ln.num;
        } else {
            const char *miss = !hd && !hl ? "size" : !hd ? "diameter" : "length";
            return sd_fail(p, sh->line, sd_kp(key, sizeof key, path, miss),
                           "missing required key '%s' (a %s needs size [diameter, -, length], or diameter "
                           "and length)", miss, name);
        }
        if (!hsd)
            return sd_fail(p, sh->line, sd_kp(key, sizeof key, path, "sides"),
                           "missing required key 'sides' (the number of sides of the %s, 3 to %d)", name,
                           SD_POLY_MAX_SIDES);
        if (sdv.integer < 3 || sdv.integer > SD_POLY_MAX_SIDES)
            return sd_fail(p, sdv.line, sd_kp(key, sizeof key, path, "sides"), "expected 3 to %d sides, got %lld",
                           SD_POLY_MAX_SIDES, sdv.integer);
        d.sides = (int)sdv.integer;
    } else {
        if (hs && he)
            return sd_fail(p, ed.line, sd_kp(key, sizeof key, path, "edge"),
                           "give either size or edge, not both (size is at line %d)", sz.line);
        if (!hs && !he)
            return sd_fail(p, sh->line, sd_kp(key, sizeof key, path, "size"),
                           "missing required key 'size' (the diameter of the %s's circumscribed sphere%s)", name,
                           platonic ? ", or edge: its edge length" : "");
        if (hs && !(sz.v[0] == sz.v[1] && sz.v[1] == sz.v[2]))
            return sd_fail(p, sz.line, sd_kp(key, sizeof key, path, "size"),
                           "expected one number, the diameter of the %s's circumscribed sphere", name);
        d.diameter = hs ? sz.v[0] : sd_polylib_edge_to_diameter(d.preset, ed.num);
    }
    if (rnd) {
        if (hfc == hvc)
            return sd_fail(p, hfc ? vcv.line : sh->line, sd_kp(key, sizeof key, path, hfc ? "vertex_count" : "faces"),
                           hfc ? "give either faces or vertex_count, not both"
                               : "missing required key 'faces' (or vertex_count) for the random preset");
        const sd_value *cv = hfc ? &fcv : &vcv;
        if (cv->integer < 4 || cv->integer > SD_POLY_MAX_RANDOM)
            return sd_fail(p, cv->line, sd_kp(key, sizeof key, path, hfc ? "faces" : "vertex_count"),
                           "expected 4 to %d, got %lld", SD_POLY_MAX_RANDOM, cv->integer);
        if (hfc)
            d.faces = (int)cv->integer;
        else
            d.points = (int)cv->integer;
        if (hse)
            d.seed = (uint64_t)sev.integer;
    }
    size_t n = sd_polylib_vertex_count(&d), got = 0;
    sh->vertices = sd_calloc(n ? n : 1, sizeof *sh->vertices);
    if (!sh->vertices)
        return sd_error_set(p->err, SD_ERR_MEMORY, p->path, 0, "", "out of memory");
    sd_error e2;
    if (sd_polylib_vertices(&d, sh->vertices, n, &got, &e2) != SD_OK) {
        char kk[24]; /* polylib names one of the short keys above */
        snprintf(kk, sizeof kk, "%.20s", e2.key[0] ? e2.key : "preset");
        return sd_fail(p, pv->line, sd_kp(key, sizeof key, path, kk), "%s", e2.msg);
    }
    sh->vertex_count = got;
    return SD_OK;
}

static sd_status sd_parse_shapes(sd_parse *p, yaml_node_t *list)
{
    sd_scene *s = p->s;
    size_t n = sd_seq_len(list);
    char path[64], key[96], got[96], kind_name[64], choices[160];
    sd_value v;
    sd_status st;
    if (n == 0)
        return SD_OK;
    s->shapes = sd_calloc(n, sizeof *s->shapes);
    if (!s->shapes)
        return sd_error_set(p->err, SD_ERR_MEMORY, p->path, 0, "", "out of memory");
    const sd_scene_key *type_row = sd_scene_key_find(SD_SEC_SHAPE, "type");
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m = sd_seq_item(p, list, i);
        sd_scene_shape *sh = &s->shapes[i];
        snprintf(path, sizeof path, "shapes[%zu]", i);
        if (m->type != YAML_MAPPING_NODE)
            return sd_fail(p, sd_line(m), path, "expected a mapping (name: ..., type: ..., ...), got %s",
                           sd_desc(m, got, sizeof got));
        sh->line = sd_line(m);
        /* The type decides which keys apply, so read it first. */
        yaml_node_t *tn = sd_map_get(p, m, "type");
        snprintf(key, sizeof key, "%s.type", path);
        if (!tn) {
            sd_choices_list(type_row->choices, choices, sizeof choices);
            return sd_fail(p, sh->line, key, "missing required key 'type' (%s)", choices);
        }
        if ((st = sd_read_value(p, type_row, tn, key, &v)))
            return st;
        sh->kind = v.choice;
        /* planar types follow the 3D ones in the choices (scene.h) */
        sh->kind2d = sh->kind >= SD_SHAPE_KIND_COUNT ? sh->kind - SD_SHAPE_KIND_COUNT : -1;
        if ((sh->kind2d >= 0) != (s->world.dimension == 2))
            return sd_fail(p, v.line, key, "shape type '%s' is %s, but simulation.dimension is %d%s", v.str,
                           sh->kind2d >= 0 ? "planar (2D)" : "3D", s->world.dimension,
                           s->world.dimension == 2 ? " (planar types: circle, ellipse, polygon, polybezier, fourier)"
                                                   : " (set dimension: 2 for planar shapes)");
        snprintf(kind_name, sizeof kind_name, "a %s shape", v.str);
        if ((st = sd_check_map(p, m, SD_SEC_SHAPE, 1u << sh->kind, kind_name, path, sh->line)))
            return st;
        s->shape_count = i + 1; /* so sd_scene_free sees its vertices */

        sd_get(p, m, SD_SEC_SHAPE, "name", path, &v);
        sd_kp(key, sizeof key, path, "name");
        if (strlen(v.str) >= SD_SCENE_NAME_MAX)
            return sd_fail(p, v.line, key, "name longer than %d characters", SD_SCENE_NAME_MAX - 1);
        for (size_t j = 0; j < i; ++j)
            if (!strcmp(s->shapes[j].name, v.str))
                return sd_fail(p, v.line, key, "duplicate shape name '%s' (shapes[%zu], line %d)",
                               v.str, j, s->shapes[j].line);
        snprintf(sh->name, sizeof sh->name, "%s", v.str);

        sd_value rv, mv;
        int hr = sd_get(p, m, SD_SEC_SHAPE, "rounding", path, &rv);
        int hm = sd_get(p, m, SD_SEC_SHAPE, "margin", path, &mv);
        if (hr && hm)
            return sd_fail(p, mv.line, sd_kp(key, sizeof key, path, "margin"),
                           "give at most one of rounding and margin (rounding is at line %d)",
                           rv.line);
        sh->rounding = rv.num;
        sh->margin = mv.num;
        sd_get(p, m, SD_SEC_SHAPE, "scale", path, &v);
        sh->scale = v.num;

        switch (sh->kind) {
        case SD_SHAPE_SPHERE:
            sd_get(p, m, SD_SEC_SHAPE, "radius", path, &v);
            sh->size = (sd_v3d){v.num, v.num, v.num};
            break;
        case SD_SHAPE_BOX:
            sd_get(p, m, SD_SEC_SHAPE, "size", path, &v);
            sh->size = sd_v3(v.v);
            break;
        case SD_SHAPE_CYLINDER:
        case SD_SHAPE_CONE:
            if ((st = sd_parse_axial(p, m, sh, path)))
                return st;
            break;
        case SD_SHAPE_ELLIPSOID:
            sd_get(p, m, SD_SEC_SHAPE, "semi_axes", path, &v);
            sh->size = sd_v3(v.v);
            break;
        case SD_SHAPE_POLYHEDRON: {
            sd_value vv, fv, pv, ncv;
            int hv = sd_get(p, m, SD_SEC_SHAPE, "vertices", path, &vv);
            int hf = sd_get(p, m, SD_SEC_SHAPE, "file", path, &fv);
            int hp = sd_get(p, m, SD_SEC_SHAPE, "preset", path, &pv);
            int hnc = sd_get(p, m, SD_SEC_SHAPE, "nonconvex", path, &ncv);
            if (hv + hf + hp > 1) {
                const sd_value *second = hp ? &pv : &fv;
                return sd_fail(p, second->line, sd_kp(key, sizeof key, path, hp ? "preset" : "file"),
                               "give one of vertices, file and preset, not more (%s is at line %d)",
                               hv ? "vertices" : "file", hv ? vv.line : fv.line);
            }
            if (!hv && !hf && !hp)
                return sd_fail(p, sh->line, sd_kp(key, sizeof key, path, "vertices"),
                               "missing required key 'vertices' (or file: an OBJ or STL file, or "
                               "preset: a built-in polyhedron)");
            if (hnc && !hf)
                return sd_fail(p, ncv.line, sd_kp(key, sizeof key, path, "nonconvex"),
                               "nonconvex applies to a mesh file (file:) only");
            if (hp) {
                if ((st = sd_parse_preset(p, m, sh, path, &pv)))
                    return st;
                break;
            }
            if ((st = sd_no_preset_keys(p, m, path)))
                return st;
            if (hf) {
                sd_kp(key, sizeof key, path, "file");
                if (!sd_resolve(p->path, fv.str, sh->file, sizeof sh->file))
                    return sd_fail(p, fv.line, key, "path too long");
                if ((st = sd_read_mesh(p, sh, key, fv.line, hnc && ncv.choice == 1)))
                    return st;
                break;
            }
            size_t nv = sd_seq_len(vv.node);
            sd_kp(key, sizeof key, path, "vertices");
            if (nv < 4)
                return sd_fail(p, vv.line, key,
                               "expected at least 4 vertices (a hull with volume), got %zu", nv);
            if (nv > SD_SHAPE_MAX_VERTICES)
                return sd_fail(p, vv.line, key, "expected at most %d vertices, got %zu",
                               SD_SHAPE_MAX_VERTICES, nv);
            sh->vertices = sd_calloc(nv, sizeof *sh->vertices);
            if (!sh->vertices)
                return sd_error_set(p->err, SD_ERR_MEMORY, p->path, 0, "", "out of memory");
            const sd_scene_key *row = sd_scene_key_find(SD_SEC_SHAPE, "vertices");
            for (size_t k = 0; k < nv; ++k) {
                double x[3];
                /* Cannot fail: sd_check_map has read every item. */
                if ((st = sd_read_vec3(p, row, sd_seq_item(p, vv.node, k), key, x, NULL)))
                    return st;
                sh->vertices[k] = sd_v3(x);
            }
            sh->vertex_count = nv;
            break;
        }
        default:
            if (sh->kind2d >= 0) {
                if ((st = sd_parse_shape2d(p, m, sh, path)))
                    return st;
                break;
            }
            return sd_fail(p, sh->line, path, "unknown shape type");
        }
    }
    return SD_OK;
}

/* ---- particles ---------------------------------------------------------- */

/* Bytes a particle takes while the world is built and run: `check`
 * measures 639-665 allocated bytes per sphere in the general engine (world
 * arrays and pair lists of spheres-settle-8000, and of copies with 1e6 and
 * 4e7 spheres) and docs/grid-solver.md 420-455 resident in the grid
 * solver; the lower ends are taken. */
#define SD_BYTES_PER_PARTICLE_CELLS 640.0
#define SD_BYTES_PER_PARTICLE_GRID 420.0
#define SD_SCENE_MAX_PARTICLES 1e9

/* The memory this process may use: 90 % of the machine's physical memory
 * (sysconf; the rest is the system's), or the address-space limit (ulimit
 * -v) when that is lower. what names which; *phys is the whole memory. */
static double sd_memory_limit(const char **what, double *phys)
{
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    *phys = pages > 0 && page > 0 ? (double)pages * (double)page : HUGE_VAL;
    double lim = 0.9 * *phys;
    *what = "memory this machine has";
    struct rlimit rl;
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY && (double)rl.rlim_cur < lim) {
        lim = (double)rl.rlim_cur;
        *what = "address space this process may use (ulimit -v)";
    }
    return lim;
}

/* Adds n particles (of the generator or pour at line/key) to the scene's
 * total, and refuses the scene before anything is built when the total
 * passes 1e9 or its memory will not fit: a one-digit slip in a count
 * (count: [20, 20, 100000]) would otherwise fill the machine for a minute
 * before failing. */
static sd_status sd_count_particles(sd_parse *p, double n, int line, const char *key)
{
    p->total += n;
    if (p->total > SD_SCENE_MAX_PARTICLES)
        return sd_fail(p, line, key, "the scene makes %.0f particles up to here (%.0f here), more than the %g a scene "
                       "may have", p->total, n, SD_SCENE_MAX_PARTICLES);
    const char *what;
    double phys, per = p->s->world.solver == SD_SOLVER_GRID ? SD_BYTES_PER_PARTICLE_GRID : SD_BYTES_PER_PARTICLE_CELLS;
    double need = per * p->total, lim = sd_memory_limit(&what, &phys);
    if (need > lim)
        return sd_fail(p, line, key,
                       "the scene makes %.0f particles up to here (%.0f here), which need about %.1f GiB "
                       "(%.0f bytes each), more than the %.1f GiB of %s%s",
                       p->total, n, need / 1073741824.0, per, (lim < 0.9 * phys ? lim : phys) / 1073741824.0, what,
                       lim < 0.9 * phys ? "" : " (90 % of it is taken as usable)");
    return SD_OK;
}

static sd_status sd_parse_list(sd_parse *p, sd_scene_generator *g, yaml_node_t *list,
                               const char *path, int has_material)
{
    size_t n = sd_seq_len(list);
    char ep[96], key[128], got[96];
    sd_value v;
    sd_status st;
    if (n == 0)
        return sd_fail(p, sd_line(list), sd_kp(key, sizeof key, path, "spheres"),
                       "expected at least one sphere");
    g->list = sd_calloc(n, sizeof *g->list);
    g->list_lines = sd_calloc(n, sizeof *g->list_lines);
    g->list_shape = sd_calloc(n, sizeof *g->list_shape);
    g->list_orient = sd_calloc(n, sizeof *g->list_orient);
    g->list_quat = sd_calloc(n, sizeof *g->list_quat);
    if (!g->list || !g->list_lines || !g->list_shape || !g->list_orient || !g->list_quat)
        return sd_error_set(p->err, SD_ERR_MEMORY, p->path, 0, "", "out of memory");
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m = sd_seq_item(p, list, i);
        sd_sphere_def *d = &g->list[i];
        snprintf(ep, sizeof ep, "%s.spheres[%zu]", path, i);
        if (m->type != YAML_MAPPING_NODE)
            return sd_fail(p, sd_line(m), ep, "expected a mapping {position: [x, y, z], radius: r}, got %s",
                           sd_desc(m, got, sizeof got));
        if ((st = sd_check_map(p, m, SD_SEC_SPHERE, SD_KIND_ALL, "", ep, sd_line(m))))
            return st;
        sd_get(p, m, SD_SEC_SPHERE, "position", ep, &v);
        d->position = sd_v3(v.v);
        /* A sphere (radius) or a body of a shape (its own, or the generator's). */
        sd_value rv;
        int has_radius = sd_get(p, m, SD_SEC_SPHERE, "radius", ep, &rv);
        g->list_shape[i] = -1;
        if (sd_get(p, m, SD_SEC_SPHERE, "shape", ep, &v)) {
            if (has_radius)
                return sd_fail(p, v.line, sd_kp(key, sizeof key, ep, "shape"),
                               "give either radius (a sphere) or shape, not both (radius is at "
                               "line %d)",
                               rv.line);
            if ((st = sd_shape_ref(p, v.str, v.line, sd_kp(key, sizeof key, ep, "shape"),
                                   &g->list_shape[i])))
                return st;
        } else if (has_radius) {
            d->radius = rv.num;
        } else if (g->shape >= 0) {
            g->list_shape[i] = g->shape;
        } else {
            return sd_fail(p, sd_line(m), sd_kp(key, sizeof key, ep, "radius"),
                           "missing required key 'radius' (or shape: NAME, here or as the "
                           "generator's shape)");
        }
        g->list_orient[i] = g->orient;
        memcpy(g->list_quat[i], g->quat, sizeof g->list_quat[i]);
        if (sd_get(p, m, SD_SEC_SPHERE, "orientation", ep, &v)) {
            if (g->list_shape[i] < 0)
                return sd_fail(p, v.line, sd_kp(key, sizeof key, ep, "orientation"),
                               "orientation applies to bodies of a shape only (a sphere has none)");
            g->list_orient[i] = (sd_scene_orient)v.choice;
            memcpy(g->list_quat[i], v.q, sizeof g->list_quat[i]);
        }
        d->velocity = sd_get(p, m, SD_SEC_SPHERE, "velocity", ep, &v) ? sd_v3(v.v) : g->velocity;
        d->angular_velocity = sd_get(p, m, SD_SEC_SPHERE, "angular_velocity", ep, &v)
                                  ? sd_v3(v.v)
                                  : g->angular_velocity;
        if (sd_get(p, m, SD_SEC_SPHERE, "material", ep, &v)) {
            if ((st = sd_material_ref(p, v.str, v.line, sd_kp(key, sizeof key, ep, "material"),
                                      &d->material)))
                return st;
        } else if (has_material) {
            d->material = g->material;
        } else {
            return sd_fail(p, sd_line(m), sd_kp(key, sizeof key, ep, "material"),
                           "missing material: give it here or as the generator's material");
        }
        g->list_lines[i] = sd_line(m);
        g->list_count = i + 1;
    }
    return SD_OK;
}

static sd_status sd_parse_particles(sd_parse *p, yaml_node_t *list, int line)
{
    sd_scene *s = p->s;
    size_t n = sd_seq_len(list);
    char path[64], key[96], got[96], kind_name[64];
    sd_value v;
    sd_status st;
    if (n == 0)
        return sd_fail(p, line, "particles", "expected at least one generator, got %s",
                       list ? "an empty list" : "nothing");
    s->generators = sd_calloc(n, sizeof *s->generators);
    if (!s->generators)
        return sd_error_set(p->err, SD_ERR_MEMORY, p->path, 0, "", "out of memory");
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m = sd_seq_item(p, list, i);
        sd_scene_generator *g = &s->generators[i];
        s->generator_count = i + 1; /* so sd_scene_free sees its lists */
        snprintf(path, sizeof path, "particles[%zu]", i);
        if (m->type != YAML_MAPPING_NODE)
            return sd_fail(p, sd_line(m), path, "expected a mapping (generator: ..., ...), got %s",
                           sd_desc(m, got, sizeof got));
        g->line = sd_line(m);
        /* The generator decides which keys apply, so read it first. */
        yaml_node_t *gn = sd_map_get(p, m, "generator");
        snprintf(key, sizeof key, "%s.generator", path);
        if (!gn)
            return sd_fail(p, g->line, key,
                           "missing required key 'generator' (lattice, random, list or csv)");
        if ((st = sd_read_value(p, sd_scene_key_find(SD_SEC_PARTICLES, "generator"), gn, key, &v)))
            return st;
        g->kind = (sd_gen_kind)v.choice;
        snprintf(kind_name, sizeof kind_name, "a %s generator", v.str);
        if ((st = sd_check_map(p, m, SD_SEC_PARTICLES, 1u << g->kind, kind_name, path, g->line)))
            return st;

        int has_material = sd_get(p, m, SD_SEC_PARTICLES, "material", path, &v);
        if (has_material &&
            (st = sd_material_ref(p, v.str, v.line, sd_kp(key, sizeof key, path, "material"),
                                  &g->material)))
            return st;
        sd_get(p, m, SD_SEC_PARTICLES, "velocity", path, &v);
        g->velocity = sd_v3(v.v);
        sd_get(p, m, SD_SEC_PARTICLES, "velocity_jitter", path, &v);
        g->velocity_jitter = v.num;
        sd_get(p, m, SD_SEC_PARTICLES, "angular_velocity", path, &v);
        g->angular_velocity = sd_v3(v.v);
        /* Spheres (radius) or bodies of a shape (shape), exactly one. */
        sd_value rv;
        int has_radius = sd_get(p, m, SD_SEC_PARTICLES, "radius", path, &rv);
        if (has_radius) {
            g->radius_min = rv.lo;
            g->radius_max = rv.hi;
        }
        g->shape = -1;
        if (sd_get(p, m, SD_SEC_PARTICLES, "shape", path, &v)) {
            sd_kp(key, sizeof key, path, "shape");
            if (has_radius)
                return sd_fail(p, v.line, key,
                               "give either radius (spheres) or shape (bodies of a shape), not "
                               "both (radius is at line %d)",
                               rv.line);
            if ((st = sd_shape_ref(p, v.str, v.line, key, &g->shape)))
                return st;
        } else if (!has_radius && g->kind != SD_GEN_LIST && g->kind != SD_GEN_CSV) {
            return sd_fail(p, g->line, sd_kp(key, sizeof key, path, "radius"),
                           "missing required key 'radius' (or shape: NAME for bodies of a shape)");
        }
        sd_value ov;
        int has_orient = sd_get(p, m, SD_SEC_PARTICLES, "orientation", path, &ov);
        g->orient = has_orient ? (sd_scene_orient)ov.choice : SD_ORIENT_RANDOM;
        memcpy(g->quat, ov.q, sizeof g->quat);
        if (has_orient && g->shape < 0 && g->kind != SD_GEN_LIST && g->kind != SD_GEN_CSV)
            return sd_fail(p, ov.line, sd_kp(key, sizeof key, path, "orientation"),
                           "orientation applies to bodies of a shape only (give shape: NAME)");

        switch (g->kind) {
        case SD_GEN_LATTICE: {
            sd_get(p, m, SD_SEC_PARTICLES, "origin", path, &v);
            g->origin = sd_v3(v.v);
            sd_value sp;
            sd_get(p, m, SD_SEC_PARTICLES, "spacing", path, &sp);
            g->spacing = sd_v3(sp.v);
            g->spacing_line = sp.line; /* a shape's bound is checked at generation */
            for (int a = 0; a < 3; ++a)
                if (sp.v[a] < 2.0 * g->radius_max)
                    return sd_fail(p, sp.line, sd_kp(key, sizeof key, path, "spacing"),
                                   "expected a spacing >= 2 x the largest radius (%g m), got %g "
                                   "along %c: the spheres would overlap",
                                   2.0 * g->radius_max, sp.v[a], 'x' + a);
            sd_get(p, m, SD_SEC_PARTICLES, "count", path, &v);
            double total = v.v[0] * v.v[1] * v.v[2];
            if (v.iv[0] > 100000000 || v.iv[1] > 100000000 || v.iv[2] > 100000000 || total > 1e9)
                return sd_fail(p, v.line, sd_kp(key, sizeof key, path, "count"),
                               "expected at most 1e9 spheres in all, got %g", total);
            for (int a = 0; a < 3; ++a)
                g->count[a] = (int)v.iv[a];
            break;
        }
        case SD_GEN_RANDOM: {
            sd_get(p, m, SD_SEC_PARTICLES, "box", path, &v);
            g->box_lo = v.box_lo;
            g->box_hi = v.box_hi;
            g->box_line = v.line;
            double ext[3] = {v.box_hi.x - v.box_lo.x, v.box_hi.y - v.box_lo.y,
                             v.box_hi.z - v.box_lo.z};
            for (int a = 0; a < 3; ++a)
                if (ext[a] < 2.0 * g->radius_max)
                    return sd_fail(p, v.line, sd_kp(key, sizeof key, path, "box"),
                                   "the box is %g m wide along %c, less than the largest "
                                   "diameter (%g m)",
                                   ext[a], 'x' + a, 2.0 * g->radius_max);
            sd_get(p, m, SD_SEC_PARTICLES, "number", path, &v);
            if (v.integer > 1000000000)
                return sd_fail(p, v.line, sd_kp(key, sizeof key, path, "number"),
                               "expected at most 1e9 spheres, got %lld", v.integer);
            g->number = (long)v.integer;
            break;
        }
        case SD_GEN_LIST:
            sd_get(p, m, SD_SEC_PARTICLES, "spheres", path, &v);
            if ((st = sd_parse_list(p, g, v.node, path, has_material)))
                return st;
            if (has_orient) {
                int shaped = 0;
                for (size_t k = 0; k < g->list_count; ++k)
                    shaped |= g->list_shape[k] >= 0;
                if (!shaped)
                    return sd_fail(p, ov.line, sd_kp(key, sizeof key, path, "orientation"),
                                   "orientation applies to bodies of a shape only (no entry has "
                                   "a shape)");
            }
            break;
        case SD_GEN_CSV:
            sd_get(p, m, SD_SEC_PARTICLES, "file", path, &v);
            sd_kp(key, sizeof key, path, "file");
            if (!sd_resolve(p->path, v.str, g->file, sizeof g->file))
                return sd_fail(p, v.line, key, "path too long");
            if ((st = sd_read_csv(p, g, key, v.line)))
                return st;
            if (has_orient) {
                int shaped = 0;
                for (size_t k = 0; k < g->list_count; ++k)
                    shaped |= g->list_shape[k] >= 0;
                if (!shaped)
                    return sd_fail(p, ov.line, sd_kp(key, sizeof key, path, "orientation"),
                                   "orientation applies to bodies of a shape only (no row has a "
                                   "shape)");
            }
            break;
        }
        static const char *const count_key[] = {"count", "number", "spheres", "file"};
        const char *ck = count_key[g->kind];
        double made = g->kind == SD_GEN_LATTICE  ? (double)g->count[0] * g->count[1] * g->count[2]
                      : g->kind == SD_GEN_RANDOM ? (double)g->number
                                                 : (double)g->list_count;
        if ((st = sd_count_particles(p, made, sd_line(sd_map_get(p, m, ck)), sd_kp(key, sizeof key, path, ck))))
            return st;
    }
    return SD_OK;
}

/* ---- walls and output --------------------------------------------------- */

/* Moving walls (servo.c): a prescribed velocity and/or a servo target. */
static sd_status sd_parse_wall_motion(sd_parse *p, yaml_node_t *m, sd_scene_wall *w, const char *path)
{
    char key[96];
    sd_value v, vs, ve;
    sd_wall_motion_def *d = &w->motion;
    *d = sd_wall_motion_def_default();
    int any = 0;
    if (sd_get(p, m, SD_SEC_WALL, "velocity", path, &v)) {
        any = 1;
        d->velocity = sd_v3(v.v);
        if (p->s->world.dimension == 2 && v.v[2] != 0.0)
            return sd_fail(p, v.line, sd_kp(key, sizeof key, path, "velocity"),
                           "dimension 2 needs a velocity with z = 0, got %g", v.v[2]);
    }
    int hs = sd_get(p, m, SD_SEC_WALL, "move_start", path, &vs);
    int he = sd_get(p, m, SD_SEC_WALL, "move_end", path, &ve);
    d->move_start = vs.num;
    d->move_end = he ? ve.num : -1.0;
    if (he && !(ve.num > vs.num))
        return sd_fail(p, ve.line, sd_kp(key, sizeof key, path, "move_end"),
                       "expected move_end > move_start (%g s), got %g s", vs.num, ve.num);
    any |= hs | he;
    if (sd_get(p, m, SD_SEC_WALL, "servo_stress", path, &v)) {
        any = 1;
        d->servo_stress = v.num;
    }
    hs = sd_get(p, m, SD_SEC_WALL, "servo_start", path, &vs);
    he = sd_get(p, m, SD_SEC_WALL, "servo_end", path, &ve);
    d->servo_start = vs.num;
    d->servo_end = he ? ve.num : -1.0;
    if (he && !(ve.num > vs.num))
        return sd_fail(p, ve.line, sd_kp(key, sizeof key, path, "servo_end"),
                       "expected servo_end > servo_start (%g s), got %g s", vs.num, ve.num);
    any |= hs | he;
    if (sd_get(p, m, SD_SEC_WALL, "servo_gain", path, &v)) {
        any = 1;
        d->servo_gain = v.num;
    }
    if (sd_get(p, m, SD_SEC_WALL, "servo_max_speed", path, &v)) {
        any = 1;
        d->servo_max_speed = v.num;
    }
    w->has_motion = any;
    return SD_OK;
}

static sd_status sd_parse_walls(sd_parse *p, yaml_node_t *list)
{
    sd_scene *s = p->s;
    size_t n = sd_seq_len(list);
    char path[64], key[96], got[96], kind_name[64];
    sd_value v;
    sd_status st;
    if (n == 0)
        return SD_OK;
    s->walls = sd_calloc(n, sizeof *s->walls);
    if (!s->walls)
        return sd_error_set(p->err, SD_ERR_MEMORY, p->path, 0, "", "out of memory");
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m = sd_seq_item(p, list, i);
        sd_scene_wall *w = &s->walls[i];
        snprintf(path, sizeof path, "walls[%zu]", i);
        if (m->type != YAML_MAPPING_NODE)
            return sd_fail(p, sd_line(m), path, "expected a mapping (type: plane|box, ...), got %s",
                           sd_desc(m, got, sizeof got));
        w->line = sd_line(m);
        yaml_node_t *tn = sd_map_get(p, m, "type");
        snprintf(key, sizeof key, "%s.type", path);
        if (!tn)
            return sd_fail(p, w->line, key, "missing required key 'type' (plane or box)");
        if ((st = sd_read_value(p, sd_scene_key_find(SD_SEC_WALL, "type"), tn, key, &v)))
            return st;
        w->kind = v.choice;
        snprintf(kind_name, sizeof kind_name, "a %s wall", v.str);
        if ((st = sd_check_map(p, m, SD_SEC_WALL, 1u << w->kind, kind_name, path, w->line)))
            return st;
        s->wall_count = i + 1;
        if (sd_get(p, m, SD_SEC_WALL, "name", path, &v)) {
            if (strlen(v.str) >= SD_SCENE_NAME_MAX)
                return sd_fail(p, v.line, sd_kp(key, sizeof key, path, "name"),
                               "name longer than %d characters", SD_SCENE_NAME_MAX - 1);
            snprintf(w->name, sizeof w->name, "%s", v.str);
        } else {
            snprintf(w->name, sizeof w->name, "wall%zu", i);
        }
        sd_get(p, m, SD_SEC_WALL, "material", path, &v);
        if ((st = sd_material_ref(p, v.str, v.line, sd_kp(key, sizeof key, path, "material"),
                                  &w->material)))
            return st;
        if (w->kind == 0) {
            sd_get(p, m, SD_SEC_WALL, "point", path, &v);
            w->point = sd_v3(v.v);
            sd_get(p, m, SD_SEC_WALL, "normal", path, &v);
            double len = sqrt(v.v[0] * v.v[0] + v.v[1] * v.v[1] + v.v[2] * v.v[2]);
            if (!(len > 0.0) || !isfinite(len))
                return sd_fail(p, v.line, sd_kp(key, sizeof key, path, "normal"),
                               "expected a non-zero normal, got [%g, %g, %g]", v.v[0], v.v[1],
                               v.v[2]);
            w->normal = (sd_v3d){v.v[0] / len, v.v[1] / len, v.v[2] / len};
        } else {
            sd_value lo, hi;
            sd_get(p, m, SD_SEC_WALL, "min", path, &lo);
            sd_get(p, m, SD_SEC_WALL, "max", path, &hi);
            for (int a = 0; a < 3; ++a)
                if (!(hi.v[a] > lo.v[a]))
                    return sd_fail(p, hi.line, sd_kp(key, sizeof key, path, "max"),
                                   "expected max > min on every axis, got max %c = %g <= min %c = %g",
                                   'x' + a, hi.v[a], 'x' + a, lo.v[a]);
            w->lo = sd_v3(lo.v);
            w->hi = sd_v3(hi.v);
            /* The choice order xmin xmax ymin ... matches the SD_BOX_* bits. */
            sd_get(p, m, SD_SEC_WALL, "open", path, &v);
            w->open_faces = v.mask;
        }
        if (s->world.dimension == 2 && w->kind == 0 && w->normal.z != 0.0)
            return sd_fail(p, w->line, sd_kp(key, sizeof key, path, "normal"),
                           "dimension 2: a plane is a line in x-y, its normal needs z = 0");
        if ((st = sd_parse_wall_motion(p, m, w, path)))
            return st;
    }
    return SD_OK;
}

static sd_status sd_parse_output(sd_parse *p, yaml_node_t *root, int line)
{
    sd_scene *s = p->s;
    yaml_node_t *out = sd_map_get(p, root, "output");
    const char *path = "output";
    sd_value v;
    sd_status st;
    if ((st = sd_check_map(p, out, SD_SEC_OUTPUT, SD_KIND_ALL, "", path, line)))
        return st;
    if (sd_get(p, out, SD_SEC_OUTPUT, "directory", path, &v))
        snprintf(s->output.directory, sizeof s->output.directory, "%s", v.str);
    s->output.every = sd_get(p, out, SD_SEC_OUTPUT, "every", path, &v) ? (long)v.integer
                                                                       : s->steps / 100;
    if (s->output.every < 1)
        s->output.every = 1;
    s->output.stats_every = sd_get(p, out, SD_SEC_OUTPUT, "stats_every", path, &v)
                                ? (long)v.integer
                                : s->output.every / 10;
    if (s->output.stats_every < 1)
        s->output.stats_every = 1;
    /* The choice order vtk|csv matches SD_OUT_VTK, SD_OUT_CSV. */
    s->output.formats =
        sd_get(p, out, SD_SEC_OUTPUT, "formats", path, &v) ? v.mask : (SD_OUT_VTK | SD_OUT_CSV);
    return SD_OK;
}

/* ---- pour and outlet (solver grid, src/grid) ----------------------------- */

static int sd_key_line(sd_parse *p, yaml_node_t *map, const char *key);

/* The union of the box walls: the grid solver's domain. 0 when there is none. */
static int sd_scene_box_union(const sd_scene *s, sd_v3d *lo, sd_v3d *hi)
{
    int n = 0;
    for (size_t i = 0; i < s->wall_count; ++i) {
        const sd_scene_wall *w = &s->walls[i];
        if (w->kind != 1)
            continue;
        if (!n++) {
            *lo = w->lo;
            *hi = w->hi;
            continue;
        }
        lo->x = fmin(lo->x, w->lo.x), lo->y = fmin(lo->y, w->lo.y), lo->z = fmin(lo->z, w->lo.z);
        hi->x = fmax(hi->x, w->hi.x), hi->y = fmax(hi->y, w->hi.y), hi->z = fmax(hi->z, w->hi.z);
    }
    return n;
}

/* pour: and outlet: need solver grid and a box wall. */
static sd_status sd_grid_section_needs(sd_parse *p, const char *sec, int line, sd_v3d *lo, sd_v3d *hi)
{
    if (p->s->world.solver != SD_SOLVER_GRID)
        return sd_fail(p, line, sec, "%s needs simulation.solver: grid (the dense grid-stencil solver)", sec);
    if (!sd_scene_box_union(p->s, lo, hi))
        return sd_fail(p, line, sec, "%s needs a box wall (the grid solver's domain)", sec);
    return SD_OK;
}

static sd_status sd_parse_pour(sd_parse *p, yaml_node_t *root)
{
    sd_scene_pour *pr = &p->s->pour;
    yaml_node_t *m = sd_map_get(p, root, "pour");
    const char *path = "pour";
    char key[96];
    sd_value v;
    sd_status st;
    if (!m)
        return SD_OK;
    pr->given = 1;
    pr->line = sd_key_line(p, root, "pour");
    if ((st = sd_check_map(p, m, SD_SEC_POUR, SD_KIND_ALL, "", path, pr->line)))
        return st;
    sd_v3d lo, hi;
    if ((st = sd_grid_section_needs(p, path, pr->line, &lo, &hi)))
        return st;
    sd_get(p, m, SD_SEC_POUR, "material", path, &v);
    if ((st = sd_material_ref(p, v.str, v.line, sd_kp(key, sizeof key, path, "material"), &pr->material)))
        return st;
    sd_get(p, m, SD_SEC_POUR, "radius", path, &v);
    pr->radius = v.num;
    sd_get(p, m, SD_SEC_POUR, "height", path, &v);
    pr->height = v.num;
    if (!(v.num - pr->radius >= lo.z && v.num + pr->radius <= hi.z))
        return sd_fail(p, v.line, "pour.height",
                       "expected a height that keeps the sheet inside the box (z of the centres in [%g, %g] m), "
                       "got %g",
                       lo.z + pr->radius, hi.z - pr->radius, v.num);
    if (hi.x - lo.x < 2 * pr->radius || hi.y - lo.y < 2 * pr->radius)
        return sd_fail(p, pr->line, "pour.radius", "the box is narrower than one poured sphere (radius %g m)",
                       pr->radius);
    sd_get(p, m, SD_SEC_POUR, "layers_per_second", path, &v);
    pr->rate = v.num;
    sd_get(p, m, SD_SEC_POUR, "vertical_speed", path, &v);
    pr->vertical_speed = v.num;
    sd_get(p, m, SD_SEC_POUR, "horizontal_speed", path, &v);
    pr->horizontal_speed = v.num;
    sd_get(p, m, SD_SEC_POUR, "start", path, &v);
    pr->start = v.num;
    sd_get(p, m, SD_SEC_POUR, "packing_fraction", path, &v);
    pr->packing_fraction = v.num;
    int has_count = sd_get(p, m, SD_SEC_POUR, "count", path, &v);
    long long count = has_count ? v.integer : 0;
    int has_fill = sd_get(p, m, SD_SEC_POUR, "fill_height", path, &v);
    if (has_count == has_fill)
        return sd_fail(p, pr->line, path, "pour needs exactly one of count and fill_height, got %s",
                       has_count ? "both" : "neither");
    if (has_fill) {
        pr->fill_height = v.num;
        if (lo.z + v.num > hi.z)
            return sd_fail(p, v.line, "pour.fill_height", "expected a fill height within the box (at most %g m), got %g",
                           hi.z - lo.z, v.num);
        double sphere = 4.0 / 3.0 * 3.14159265358979323846 * pr->radius * pr->radius * pr->radius;
        count = (long long)floor(pr->packing_fraction * (hi.x - lo.x) * (hi.y - lo.y) * v.num / sphere);
        if (count < 1)
            return sd_fail(p, v.line, "pour.fill_height", "fill height %g m holds no sphere of radius %g m", v.num,
                           pr->radius);
    }
    if (count > 1000000000LL)
        return sd_fail(p, pr->line, "pour.count", "expected at most 1e9 spheres, got %lld", count);
    pr->count = (long)count;
    if ((st = sd_count_particles(p, (double)count, has_fill ? v.line : sd_line(sd_map_get(p, m, "count")),
                                 has_fill ? "pour.fill_height" : "pour.count")))
        return st;
    return SD_OK;
}

static sd_status sd_parse_outlet(sd_parse *p, yaml_node_t *root)
{
    sd_scene_outlet *o = &p->s->outlet;
    yaml_node_t *m = sd_map_get(p, root, "outlet");
    const char *path = "outlet";
    sd_value v;
    sd_status st;
    if (!m)
        return SD_OK;
    o->given = 1;
    o->line = sd_key_line(p, root, "outlet");
    if ((st = sd_check_map(p, m, SD_SEC_OUTLET, SD_KIND_ALL, "", path, o->line)))
        return st;
    sd_v3d lo, hi;
    if ((st = sd_grid_section_needs(p, path, o->line, &lo, &hi)))
        return st;
    sd_get(p, m, SD_SEC_OUTLET, "min", path, &v);
    o->lo[0] = v.v[0], o->lo[1] = v.v[1];
    int line = v.line;
    sd_get(p, m, SD_SEC_OUTLET, "max", path, &v);
    o->hi[0] = v.v[0], o->hi[1] = v.v[1];
    if (!(o->hi[0] > o->lo[0] && o->hi[1] > o->lo[1]))
        return sd_fail(p, v.line, "outlet.max", "expected max > min on x and y, got min [%g, %g], max [%g, %g]",
                       o->lo[0], o->lo[1], o->hi[0], o->hi[1]);
    if (o->hi[0] <= lo.x || o->lo[0] >= hi.x || o->hi[1] <= lo.y || o->lo[1] >= hi.y)
        return sd_fail(p, line, "outlet.min",
                       "the hole [%g, %g] x [%g, %g] misses the box floor [%g, %g] x [%g, %g]", o->lo[0], o->hi[0],
                       o->lo[1], o->hi[1], lo.x, hi.x, lo.y, hi.y);
    sd_get(p, m, SD_SEC_OUTLET, "open_at", path, &v);
    o->open_at = v.num;
    return SD_OK;
}

/* ---- cross checks ------------------------------------------------------- */

/* A material needs youngs_modulus when a hertz_mindlin contact involves it,
 * and a stiffness when a linear contact involves it and the pair's
 * interaction sets none. Contacts are particle-particle and particle-wall,
 * so only materials that particles or walls use count. Checked here, where
 * the line of the material is known; sd_world_prepare checks again. */
static sd_status sd_check_laws(sd_parse *p)
{
    sd_scene *s = p->s;
    size_t nm = s->material_count;
    unsigned char *use = sd_calloc(nm ? nm : 1, 1); /* bit 0: particles, bit 1: walls */
    if (!use)
        return sd_error_set(p->err, SD_ERR_MEMORY, p->path, 0, "", "out of memory");
    for (size_t g = 0; g < s->generator_count; ++g) {
        const sd_scene_generator *gen = &s->generators[g];
        if (gen->kind == SD_GEN_LIST || gen->kind == SD_GEN_CSV) /* a material per entry */
            for (size_t i = 0; i < gen->list_count; ++i)
                use[gen->list[i].material] |= 1;
        else
            use[gen->material] |= 1;
    }
    for (size_t w = 0; w < s->wall_count; ++w)
        use[s->walls[w].material] |= 2;
    sd_status st = SD_OK;
    for (size_t a = 0; a < nm && st == SD_OK; ++a) {
        for (size_t b = 0; b < nm && st == SD_OK; ++b) {
            if (!((use[a] & 1) && use[b]) && !((use[b] & 1) && use[a]))
                continue; /* no contact between these two materials */
            const sd_scene_interaction *in = NULL;
            for (size_t i = 0; i < s->interaction_count; ++i) {
                const sd_scene_interaction *c = &s->interactions[i];
                if ((c->mat_a == (int)a && c->mat_b == (int)b) ||
                    (c->mat_a == (int)b && c->mat_b == (int)a))
                    in = c;
            }
            int law = (in && in->def.law >= 0) ? in->def.law : (int)s->world.law;
            const sd_scene_material *m = &s->materials[a];
            char key[96];
            if (law == SD_LAW_HERTZ_MINDLIN && !(m->def.youngs_modulus > 0.0)) {
                snprintf(key, sizeof key, "materials[%zu].youngs_modulus", a);
                st = sd_fail(p, m->line, key,
                             "missing youngs_modulus (Pa): the hertz_mindlin contact between "
                             "'%s' and '%s' needs it",
                             m->name, s->materials[b].name);
            } else if (law == SD_LAW_LINEAR && !(m->def.stiffness > 0.0) &&
                       !(in && in->def.stiffness > 0.0)) {
                snprintf(key, sizeof key, "materials[%zu].stiffness", a);
                st = sd_fail(p, m->line, key,
                             "missing stiffness (N/m): the linear contact between '%s' and '%s' "
                             "needs it (or set stiffness in their interaction)",
                             m->name, s->materials[b].name);
            } else if (law == SD_LAW_VOLUME && (use[a] & 1) && !(m->def.youngs_modulus > 0.0)) {
                snprintf(key, sizeof key, "materials[%zu].youngs_modulus", a);
                st = sd_fail(p, m->line, key,
                             "missing youngs_modulus (Pa): the volume contact between '%s' and '%s' "
                             "needs it (eq. 13 of [Xu n.d.])",
                             m->name, s->materials[b].name);
            } else if (law == SD_LAW_VOLUME_LINEAR && !(m->def.volume_stiffness > 0.0) &&
                       !(in && in->def.volume_stiffness > 0.0)) {
                snprintf(key, sizeof key, "materials[%zu].volume_stiffness", a);
                st = sd_fail(p, m->line, key,
                             "missing volume_stiffness (N/m^3): the volume_linear contact between '%s' "
                             "and '%s' needs it (or set volume_stiffness in their interaction)",
                             m->name, s->materials[b].name);
            }
        }
    }
    /* The volume laws take sharp polyhedra only (the overlap volume exists
     * for them); world/material.c checks again at prepare time. */
    for (size_t g = 0; g < s->generator_count && st == SD_OK; ++g) {
        const sd_scene_generator *gen = &s->generators[g];
        int listed = gen->kind == SD_GEN_LIST || gen->kind == SD_GEN_CSV; /* per entry */
        size_t cnt = listed ? gen->list_count : 1;
        for (size_t i = 0; i < cnt && st == SD_OK; ++i) {
            int a = listed ? gen->list[i].material : gen->material;
            int sh = (listed && gen->list_shape) ? gen->list_shape[i] : gen->shape;
            const sd_scene_shape *ss = sh >= 0 ? &s->shapes[sh] : NULL;
            if (ss && ss->kind == SD_SHAPE_POLYHEDRON && !(ss->rounding > 0) && !(ss->margin > 0))
                continue;
            for (size_t b = 0; b < nm && st == SD_OK; ++b) {
                if (!use[b])
                    continue;
                const sd_scene_interaction *in = NULL;
                for (size_t k = 0; k < s->interaction_count; ++k) {
                    const sd_scene_interaction *c = &s->interactions[k];
                    if ((c->mat_a == a && c->mat_b == (int)b) || (c->mat_a == (int)b && c->mat_b == a))
                        in = c;
                }
                int law = (in && in->def.law >= 0) ? in->def.law : (int)s->world.law;
                if (law != SD_LAW_VOLUME && law != SD_LAW_VOLUME_LINEAR)
                    continue;
                char key[96];
                snprintf(key, sizeof key, "particles[%zu]", g);
                char what[96];
                if (ss)
                    snprintf(what, sizeof what, "shape '%s'", ss->name);
                else
                    snprintf(what, sizeof what, "spheres");
                st = sd_fail(p, gen->line, key,
                             "%s (material '%s') meet material '%s' under the %s law, which takes "
                             "sharp polyhedra only (type polyhedron, no rounding or margin); give this pair "
                             "another law (interactions: contact_law hertz_mindlin or linear)",
                             what, s->materials[a].name, s->materials[b].name,
                             sd_contact_law_name((sd_contact_law)law));
            }
        }
    }
    sd_free(use);
    return st;
}

/* ---- entry points ------------------------------------------------------- */

static int sd_key_line(sd_parse *p, yaml_node_t *map, const char *key)
{
    for (yaml_node_pair_t *q = map->data.mapping.pairs.start; q < map->data.mapping.pairs.top; ++q) {
        yaml_node_t *k = yaml_document_get_node(p->doc, q->key);
        if (k->type == YAML_SCALAR_NODE && !strcmp(sd_scalar(k), key))
            return sd_line(k);
    }
    return 1;
}

static sd_status sd_parse_root(sd_parse *p, yaml_node_t *root)
{
    char got[96];
    sd_value v;
    sd_status st;
    if (!root)
        return sd_fail(p, 1, "", "the scene file is empty (expected simulation, materials and "
                                 "particles sections)");
    if (root->type != YAML_MAPPING_NODE)
        return sd_fail(p, sd_line(root), "",
                       "expected a mapping of sections (simulation:, materials:, ...), got %s",
                       sd_desc(root, got, sizeof got));
    if ((st = sd_check_map(p, root, SD_SEC_ROOT, SD_KIND_ALL, "", "", 1)))
        return st;
    p->s->simulation_line = sd_key_line(p, root, "simulation");
    if ((st = sd_parse_simulation(p, root)))
        return st;
    /* Materials first: the other sections refer to them by name. */
    sd_get(p, root, SD_SEC_ROOT, "materials", "", &v);
    if ((st = sd_parse_materials(p, v.node, sd_key_line(p, root, "materials"))))
        return st;
    sd_get(p, root, SD_SEC_ROOT, "interactions", "", &v);
    if ((st = sd_parse_interactions(p, v.node)))
        return st;
    /* Shapes before particles: generators refer to them by name. */
    sd_get(p, root, SD_SEC_ROOT, "shapes", "", &v);
    if ((st = sd_parse_shapes(p, v.node)))
        return st;
    /* particles may be left out when a pour fills the box (solver grid) */
    if (sd_get(p, root, SD_SEC_ROOT, "particles", "", &v) || !sd_map_get(p, root, "pour"))
        if ((st = sd_parse_particles(p, v.node, sd_key_line(p, root, "particles"))))
            return st;
    sd_get(p, root, SD_SEC_ROOT, "walls", "", &v);
    if ((st = sd_parse_walls(p, v.node)))
        return st;
    if ((st = sd_parse_output(p, root, sd_map_get(p, root, "output") ? sd_key_line(p, root, "output") : 1)))
        return st;
    if ((st = sd_parse_pour(p, root)) || (st = sd_parse_outlet(p, root)))
        return st;
    return sd_check_laws(p);
}

/* ---- reading the file ---------------------------------------------------- */

/* Limits checked before libyaml builds the node tree. libyaml's scanner
 * costs time quadratic in the depth of flow nesting ([[[...]]]: 30,000
 * levels take 5 s, 100,000 take 95 s), and its node tree takes about 100
 * bytes per node, so both are capped first. A scene nests 6 levels (root,
 * particles, a generator, spheres, an entry, a position); lists of more
 * particles than a few hundred thousand belong in a CSV file. */
#define SD_SCENE_MAX_DEPTH 64
#define SD_SCENE_MAX_BYTES (64L << 20)

/* 1-based line of byte offset off in buf (the reader reports offsets). */
static int sd_line_of_offset(const unsigned char *buf, size_t len, size_t off)
{
    int line = 1;
    for (size_t k = 0; k < off && k < len; ++k)
        line += buf[k] == '\n';
    return line;
}

/* A libyaml failure as one message with the file's line. */
static sd_status sd_yaml_error(const yaml_parser_t *parser, const char *path, const unsigned char *buf,
                               size_t len, sd_error *err)
{
    const char *problem = parser->problem ? parser->problem : "syntax error";
    if (parser->error == YAML_MEMORY_ERROR)
        return sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    if (parser->error == YAML_READER_ERROR) {
        /* Bad bytes: libyaml gives a byte offset, and a value that is the
         * offending byte (octet messages) or the decoded character. */
        char what[32] = "";
        if (parser->problem_value >= 0 && strstr(problem, "octet"))
            snprintf(what, sizeof what, " (byte 0x%02X)", (unsigned)parser->problem_value & 0xFFu);
        else if (parser->problem_value >= 0)
            snprintf(what, sizeof what, " (U+%04X)", (unsigned)parser->problem_value);
        int utf = strstr(problem, "UTF-8") != NULL;
        return sd_error_set(err, SD_ERR_INPUT, path, sd_line_of_offset(buf, len, parser->problem_offset), "",
                            "cannot read the scene file: %s%s%s", problem, what,
                            utf ? ": the file must be UTF-8 text (an editor set to Latin-1 writes a mu or "
                                  "degree sign as one such byte; save the file as UTF-8)"
                                : "");
    }
    if (parser->context)
        return sd_error_set(err, SD_ERR_INPUT, path, (int)parser->problem_mark.line + 1, "",
                            "invalid YAML: %s (%s at line %d)", problem, parser->context,
                            (int)parser->context_mark.line + 1);
    return sd_error_set(err, SD_ERR_INPUT, path, (int)parser->problem_mark.line + 1, "", "invalid YAML: %s",
                        problem);
}

/* The whole file, NUL-terminated, at most SD_SCENE_MAX_BYTES. */
static sd_status sd_read_scene_file(const char *path, unsigned char **out, size_t *len, sd_error *err)
{
    *out = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "cannot open the scene file: %s", strerror(errno));
    size_t cap = 0, n = 0;
    unsigned char *buf = NULL;
    sd_status st = SD_OK;
    for (;;) {
        if (n + 1 >= cap) {
            size_t nc = cap ? 2 * cap : 65536;
            unsigned char *nb = sd_realloc(buf, nc);
            if (!nb) {
                st = sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
                break;
            }
            buf = nb;
            cap = nc;
        }
        size_t got = fread(buf + n, 1, cap - 1 - n, f);
        n += got;
        if (n > (size_t)SD_SCENE_MAX_BYTES) {
            st = sd_error_set(err, SD_ERR_INPUT, path, 0, "",
                              "the scene file is larger than %ld MiB (long particle lists belong in a CSV "
                              "file: generator: csv)",
                              SD_SCENE_MAX_BYTES >> 20);
            break;
        }
        if (got == 0) {
            if (ferror(f))
                st = sd_error_set(err, SD_ERR_IO, path, 0, "", "cannot read the scene file: %s", strerror(errno));
            break;
        }
    }
    fclose(f);
    if (st != SD_OK) {
        sd_free(buf);
        return st;
    }
    buf[n] = '\0';
    *out = buf;
    *len = n;
    return SD_OK;
}

/* Explicitly tagged string scalars, by their start index: libyaml's loader
 * gives `!!str 1.0` the same tag and style as a plain 1.0, so the events
 * are the only place that tells them apart. */
typedef struct sd_tagged {
    size_t *index;
    size_t n, cap;
} sd_tagged;

/* One pass over the events before loading: refuses nesting deeper than
 * SD_SCENE_MAX_DEPTH at the line where it passes the limit (the scanner's
 * cost stays linear up to there), and lists the scalars tagged !!str or !.
 * Syntax errors are reported here, as the loader would. */
static sd_status sd_yaml_prescan(const unsigned char *buf, size_t len, const char *path, sd_tagged *tg,
                                 sd_error *err)
{
    yaml_parser_t parser;
    if (!yaml_parser_initialize(&parser))
        return sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    yaml_parser_set_input_string(&parser, buf, len);
    sd_status st = SD_OK;
    int depth = 0, done = 0, docs = 0, end_line = 0; /* end_line: the '...' of the first document */
    while (!done && st == SD_OK) {
        yaml_event_t ev;
        if (!yaml_parser_parse(&parser, &ev)) {
            if (end_line && parser.problem && strstr(parser.problem, "<document start>"))
                st = sd_error_set(err, SD_ERR_INPUT, path, (int)parser.problem_mark.line + 1, "",
                                  "text after '...' (line %d), which ends the YAML document, would be ignored; "
                                  "a scene is one document: remove the '...' line",
                                  end_line);
            else
                st = sd_yaml_error(&parser, path, buf, len, err);
            break;
        }
        switch (ev.type) {
        case YAML_DOCUMENT_START_EVENT:
            /* A second document would be dropped without a word. */
            if (docs++)
                st = sd_error_set(err, SD_ERR_INPUT, path, (int)ev.start_mark.line + 1, "",
                                  "'---' starts a second YAML document%s, which would be ignored; a scene is "
                                  "one document: remove this line",
                                  end_line ? " after '...'" : "");
            break;
        case YAML_DOCUMENT_END_EVENT:
            if (!ev.data.document_end.implicit && !end_line)
                end_line = (int)ev.start_mark.line + 1;
            break;
        case YAML_SEQUENCE_START_EVENT:
        case YAML_MAPPING_START_EVENT:
            if (++depth > SD_SCENE_MAX_DEPTH)
                st = sd_error_set(err, SD_ERR_INPUT, path, (int)ev.start_mark.line + 1, "",
                                  "lists and mappings nested more than %d deep (a scene needs 6 levels)",
                                  SD_SCENE_MAX_DEPTH);
            break;
        case YAML_SEQUENCE_END_EVENT:
        case YAML_MAPPING_END_EVENT: --depth; break;
        case YAML_SCALAR_EVENT: {
            const char *tag = (const char *)ev.data.scalar.tag;
            if (tag && (!strcmp(tag, YAML_STR_TAG) || !strcmp(tag, "!"))) {
                if (tg->n == tg->cap) {
                    size_t nc = tg->cap ? 2 * tg->cap : 16;
                    size_t *ni = sd_realloc(tg->index, nc * sizeof *ni);
                    if (!ni) {
                        st = sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
                        break;
                    }
                    tg->index = ni;
                    tg->cap = nc;
                }
                tg->index[tg->n++] = ev.start_mark.index; /* increasing: events come in file order */
            }
            break;
        }
        case YAML_STREAM_END_EVENT: done = 1; break;
        default: break;
        }
        yaml_event_delete(&ev);
    }
    yaml_parser_delete(&parser);
    return st;
}

/* Marks the scalars the prescan found tagged as strings with the style no
 * loaded scalar has (YAML_ANY_SCALAR_STYLE), so that they read as strings,
 * never as numbers or null. */
static void sd_mark_tagged(yaml_document_t *doc, const sd_tagged *tg)
{
    if (!tg->n)
        return;
    for (yaml_node_t *n = doc->nodes.start; n < doc->nodes.top; ++n) {
        if (n->type != YAML_SCALAR_NODE)
            continue;
        size_t lo = 0, hi = tg->n, at = n->start_mark.index;
        while (lo < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (tg->index[mid] < at)
                lo = mid + 1;
            else
                hi = mid;
        }
        if (lo < tg->n && tg->index[lo] == at)
            n->data.scalar.style = YAML_ANY_SCALAR_STYLE;
    }
}

sd_status sd_scene_load(const char *path, sd_scene **out, sd_error *err)
{
    sd_error_clear(err);
    *out = NULL;
    struct stat sb;
    if (stat(path, &sb) != 0)
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "cannot open the scene file: %s",
                            strerror(errno));
    if (S_ISDIR(sb.st_mode))
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "is a directory, not a scene file");
    if (strlen(path) >= SD_SCENE_PATH_MAX)
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "path too long");
    unsigned char *buf;
    size_t len;
    sd_status st = sd_read_scene_file(path, &buf, &len, err);
    if (st != SD_OK)
        return st;
    sd_tagged tg = {NULL, 0, 0};
    if ((st = sd_yaml_prescan(buf, len, path, &tg, err)) != SD_OK) {
        sd_free(tg.index);
        sd_free(buf);
        return st;
    }

    yaml_parser_t parser;
    yaml_document_t doc, next;
    if (!yaml_parser_initialize(&parser)) {
        sd_free(tg.index);
        sd_free(buf);
        return sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    }
    yaml_parser_set_input_string(&parser, buf, len);
    if (!yaml_parser_load(&parser, &doc)) {
        st = sd_yaml_error(&parser, path, buf, len, err);
        yaml_parser_delete(&parser);
        sd_free(tg.index);
        sd_free(buf);
        return st;
    }
    /* A scene is one document: anything after a '...' line or a second
     * '---' would otherwise be dropped without a word. */
    if (!yaml_parser_load(&parser, &next)) {
        st = sd_yaml_error(&parser, path, buf, len, err);
    } else {
        if (yaml_document_get_root_node(&next)) /* the prescan refuses it first */
            st = sd_error_set(err, SD_ERR_INPUT, path, (int)next.start_mark.line + 1, "",
                              "a second YAML document starts here, which would be ignored; a scene is "
                              "one document");
        yaml_document_delete(&next);
    }
    sd_mark_tagged(&doc, &tg);
    sd_free(tg.index);

    sd_scene *s = NULL;
    if (st == SD_OK && !(s = sd_calloc(1, sizeof *s))) {
        st = sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    } else if (st == SD_OK) {
        snprintf(s->path, sizeof s->path, "%s", path);
        sd_parse p = {&doc, path, s, err, 0.0};
        st = sd_parse_root(&p, yaml_document_get_root_node(&doc));
    }
    yaml_document_delete(&doc);
    yaml_parser_delete(&parser);
    sd_free(buf);
    if (st != SD_OK) {
        sd_scene_free(s);
        return st;
    }
    *out = s;
    return SD_OK;
}

void sd_scene_free(sd_scene *s)
{
    if (!s)
        return;
    for (size_t i = 0; i < s->generator_count; ++i) {
        sd_free(s->generators[i].list);
        sd_free(s->generators[i].list_lines);
        sd_free(s->generators[i].list_shape);
        sd_free(s->generators[i].list_orient);
        sd_free(s->generators[i].list_quat);
    }
    for (size_t i = 0; i < s->shape_count; ++i) {
        sd_free(s->shapes[i].vertices);
        sd_free(s->shapes[i].points);
        sd_free(s->shapes[i].fourier_a);
        sd_free(s->shapes[i].fourier_b);
    }
    sd_free(s->shapes);
    sd_free(s->generators);
    sd_free(s->materials);
    sd_free(s->interactions);
    sd_free(s->walls);
    sd_free(s);
}
