/* yaml_read.c — the typed YAML reader (see yaml_read.h): the file loaded
 * as a node tree, scalars read as numbers, integers, strings and choices,
 * the compound forms ([x, y, z], {min, max}, quaternions, lists) checked
 * component by component, and mappings checked against the key table.
 *
 * The whole document is loaded first (yaml_parser_load), so every node
 * knows its line. A number is a plain scalar, or one tagged !!float or
 * !!int; a quoted "2500" and `!!str 2500` are strings, told apart by a
 * pass over the events before loading (libyaml's loader gives `!!str 1.0`
 * the tag and style of a plain 1.0).
 *
 * Invariant: every function either fills its output from a checked node
 * or returns an error naming file, line and key; none prints.
 */
#define _POSIX_C_SOURCE 200809L

#include "io/yaml_read.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/alloc.h"
#include "io/scene.h" /* SD_SCENE_PATH_MAX, the orientation kinds */

/* ---- errors -------------------------------------------------------------- */

sd_status sd_yaml_fail(const sd_yaml *y, int line, const char *key, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return sd_error_set(y->err, SD_ERR_INPUT, y->path, line, key, "%s", msg);
}

sd_status sd_yaml_oom(const sd_yaml *y) { return sd_error_set(y->err, SD_ERR_MEMORY, y->path, 0, "", "out of memory"); }

/* ---- nodes --------------------------------------------------------------- */


int sd_yaml_line(const yaml_node_t *n) { return n ? (int)n->start_mark.line + 1 : 0; }

/* "path.key", or "key" at the top level. */
const char *sd_yaml_kp(char *buf, size_t size, const char *path, const char *key)
{
    if (path[0])
        snprintf(buf, size, "%s.%s", path, key);
    else
        snprintf(buf, size, "%s", key);
    return buf;
}

static const char *sd_yaml_scalar(const yaml_node_t *n) { return (const char *)n->data.scalar.value; }

/* The tag the loader gave n: an explicit one, or the default (str) for an
 * untagged scalar. */
static const char *sd_yaml_tag(const yaml_node_t *n) { return n->tag ? (const char *)n->tag : YAML_STR_TAG; }

static int sd_yaml_is_null(const yaml_node_t *n)
{
    if (!n)
        return 1;
    if (n->type != YAML_SCALAR_NODE || n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE)
        return 0;
    const char *t = sd_yaml_scalar(n);
    return !t[0] || !strcmp(t, "~") || !strcmp(t, "null") || !strcmp(t, "Null") ||
           !strcmp(t, "NULL");
}

/* What was found, for "expected X, got Y" messages. */
const char *sd_yaml_desc(const yaml_node_t *n, char *buf, size_t size)
{
    if (sd_yaml_is_null(n)) {
        snprintf(buf, size, "nothing");
    } else if (n->type == YAML_SCALAR_NODE) {
        /* escaped: a double-quoted "\e[31m" would reach the terminal */
        const char *t = sd_yaml_scalar(n);
        char esc[100]; /* sd_escape ends it with "..." when the escapes do not fit */
        sd_escape(esc, sizeof esc, t, strlen(t) > 60 ? 60 : strlen(t));
        const char *q = n->data.scalar.style == YAML_PLAIN_SCALAR_STYLE ? "" : "\"";
        const char *tag = sd_yaml_tag(n), *std = "tag:yaml.org,2002:";
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

size_t sd_yaml_seq_len(const yaml_node_t *n)
{
    return n && n->type == YAML_SEQUENCE_NODE
               ? (size_t)(n->data.sequence.items.top - n->data.sequence.items.start)
               : 0;
}

yaml_node_t *sd_yaml_seq_item(const sd_yaml *y, const yaml_node_t *n, size_t i)
{
    return yaml_document_get_node(y->doc, n->data.sequence.items.start[i]);
}

yaml_node_t *sd_yaml_map_get(const sd_yaml *y, const yaml_node_t *map, const char *key)
{
    if (!map || map->type != YAML_MAPPING_NODE)
        return NULL;
    for (yaml_node_pair_t *q = map->data.mapping.pairs.start; q < map->data.mapping.pairs.top; ++q) {
        yaml_node_t *k = yaml_document_get_node(y->doc, q->key);
        if (k && k->type == YAML_SCALAR_NODE && !strcmp(sd_yaml_scalar(k), key))
            return yaml_document_get_node(y->doc, q->value);
    }
    return NULL;
}

/* ---- scalars ------------------------------------------------------------ */

/* A scalar that reads as a finite number: a plain (untagged) scalar, or one
 * tagged !!float or !!int in any style (!!float "1.0e7"). Only digits,
 * signs, '.' and exponents are allowed, so "inf", "nan", hex and strings
 * are not numbers: a quoted "2500", `!!str 2500` (style
 * YAML_ANY_SCALAR_STYLE, see sd_yaml_mark_tagged) and other tags are strings. */
static int sd_yaml_scalar_number(const yaml_node_t *n, double *out)
{
    if (!n || n->type != YAML_SCALAR_NODE)
        return 0;
    const char *tag = sd_yaml_tag(n);
    int numeric = !strcmp(tag, YAML_FLOAT_TAG) || !strcmp(tag, YAML_INT_TAG);
    if (!numeric && (strcmp(tag, YAML_STR_TAG) || n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE))
        return 0;
    const char *t = sd_yaml_scalar(n);
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
static int sd_yaml_scalar_int(const yaml_node_t *n, long long *out)
{
    double v;
    if (!sd_yaml_scalar_number(n, &v))
        return 0;
    const char *t = sd_yaml_scalar(n);
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
static int sd_yaml_choice_index(const char *choices, const char *t)
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

void sd_yaml_choices_list(const char *choices, char *buf, size_t size)
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
sd_status sd_yaml_read_number(const sd_yaml *y, const sd_scene_key *k, yaml_node_t *n,
                                const char *key, const char *what, const char *alt, double *out)
{
    char got[96];
    const char *r = sd_scene_range_text(k->range);
    if (!sd_yaml_scalar_number(n, out)) {
        /* a number written as a string: say why it is not read as one */
        char *end;
        const char *t = n && n->type == YAML_SCALAR_NODE ? sd_yaml_scalar(n) : "";
        double x = strtod(t, &end);
        const char *why = t[0] && !*end && isfinite(x) && !strcmp(sd_yaml_tag(n), YAML_STR_TAG) &&
                                  n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE
                              ? " (a string in YAML: write the number without quotes or !!str)"
                              : "";
        return sd_yaml_fail(y, sd_yaml_line(n), key, "expected a number%s%s%s%s, got %s%s", r[0] ? " " : "", r,
                       what, alt, sd_yaml_desc(n, got, sizeof got), why);
    }
    if (!sd_scene_range_ok(k->range, *out))
        return sd_yaml_fail(y, sd_yaml_line(n), key, "expected a number %s%s, got %s", r, what,
                       sd_yaml_desc(n, got, sizeof got));
    return SD_OK;
}

static sd_status sd_yaml_read_int(const sd_yaml *y, const sd_scene_key *k, yaml_node_t *n, const char *key,
                             const char *what, long long *out)
{
    char got[96];
    const char *r = sd_scene_range_text(k->range);
    if (!sd_yaml_scalar_int(n, out) || !sd_scene_range_ok(k->range, (double)*out))
        return sd_yaml_fail(y, sd_yaml_line(n), key, "expected an integer%s%s%s, got %s", r[0] ? " " : "",
                       r, what, sd_yaml_desc(n, got, sizeof got));
    return SD_OK;
}

/* [x, y, z]: three numbers, each in the key's range. */
sd_status sd_yaml_read_vec3(const sd_yaml *y, const sd_scene_key *k, yaml_node_t *n, const char *key,
                              double v[3], long long iv[3])
{
    char got[96];
    if (!n || n->type != YAML_SEQUENCE_NODE || sd_yaml_seq_len(n) != 3)
        return sd_yaml_fail(y, sd_yaml_line(n), key, "expected a list of 3 %s ([x, y, z]), got %s",
                       iv ? "integers" : "numbers", sd_yaml_desc(n, got, sizeof got));
    for (size_t i = 0; i < 3; ++i) {
        static const char *const axis[3] = {" for x", " for y", " for z"};
        yaml_node_t *item = sd_yaml_seq_item(y, n, i);
        sd_status st = iv ? sd_yaml_read_int(y, k, item, key, axis[i], &iv[i])
                          : sd_yaml_read_number(y, k, item, key, axis[i], "", &v[i]);
        if (st != SD_OK)
            return st;
        if (iv)
            v[i] = (double)iv[i];
    }
    return SD_OK;
}

/* [x, y]: two numbers, each in the key's range (planar shapes). */
sd_status sd_yaml_read_vec2(const sd_yaml *y, const sd_scene_key *k, yaml_node_t *n, const char *key, double v[2])
{
    char got[96];
    if (!n || n->type != YAML_SEQUENCE_NODE || sd_yaml_seq_len(n) != 2)
        return sd_yaml_fail(y, sd_yaml_line(n), key, "expected a list of 2 numbers ([x, y]), got %s",
                       sd_yaml_desc(n, got, sizeof got));
    for (size_t i = 0; i < 2; ++i) {
        static const char *const axis[2] = {" for x", " for y"};
        sd_status st = sd_yaml_read_number(y, k, sd_yaml_seq_item(y, n, i), key, axis[i], "", &v[i]);
        if (st != SD_OK)
            return st;
    }
    return SD_OK;
}

static sd_status sd_yaml_read_string(const sd_yaml *y, const sd_scene_key *k, yaml_node_t *n,
                                const char *key, const char **out)
{
    char got[96];
    if (!n || n->type != YAML_SCALAR_NODE)
        return sd_yaml_fail(y, sd_yaml_line(n), key, "expected a %sstring, got %s",
                       k->range == SD_KR_NONEMPTY ? "non-empty " : "", sd_yaml_desc(n, got, sizeof got));
    *out = sd_yaml_is_null(n) ? "" : sd_yaml_scalar(n);
    if (k->range == SD_KR_NONEMPTY && !(*out)[0])
        return sd_yaml_fail(y, sd_yaml_line(n), key, "expected a non-empty string, got nothing");
    if (strlen(*out) >= SD_SCENE_PATH_MAX)
        return sd_yaml_fail(y, sd_yaml_line(n), key, "string too long (%zu characters, at most %d)",
                       strlen(*out), SD_SCENE_PATH_MAX - 1);
    return SD_OK;
}

static sd_status sd_yaml_read_choice(const sd_yaml *y, const sd_scene_key *k, yaml_node_t *n,
                                const char *key, int *out)
{
    char got[96], list[160];
    *out = (n && n->type == YAML_SCALAR_NODE) ? sd_yaml_choice_index(k->choices, sd_yaml_scalar(n)) : -1;
    if (*out < 0) {
        sd_yaml_choices_list(k->choices, list, sizeof list);
        return sd_yaml_fail(y, sd_yaml_line(n), key, "expected one of %s, got %s", list,
                       sd_yaml_desc(n, got, sizeof got));
    }
    return SD_OK;
}

/* The subkeys of {min: .., max: ..} forms: only min and max, both given. */
static sd_status sd_yaml_read_min_max(const sd_yaml *y, yaml_node_t *n, const char *key, yaml_node_t **mn,
                                 yaml_node_t **mx)
{
    char sub[160], got[96];
    for (yaml_node_pair_t *q = n->data.mapping.pairs.start; q < n->data.mapping.pairs.top; ++q) {
        yaml_node_t *kn = yaml_document_get_node(y->doc, q->key);
        const char *name = kn->type == YAML_SCALAR_NODE ? sd_yaml_scalar(kn) : "?";
        if (strcmp(name, "min") && strcmp(name, "max"))
            return sd_yaml_fail(y, sd_yaml_line(kn), sd_yaml_kp(sub, sizeof sub, key, name),
                           "unknown key %s (expected min and max)", sd_yaml_desc(kn, got, sizeof got));
    }
    *mn = sd_yaml_map_get(y, n, "min");
    *mx = sd_yaml_map_get(y, n, "max");
    if (!*mn || !*mx)
        return sd_yaml_fail(y, sd_yaml_line(n), sd_yaml_kp(sub, sizeof sub, key, *mn ? "max" : "min"),
                       "missing required key '%s'", *mn ? "max" : "min");
    return SD_OK;
}

/* Checks n against row k and fills v. Absent keys are handled by sd_yaml_get. */
sd_status sd_yaml_read_value(const sd_yaml *y, const sd_scene_key *k, yaml_node_t *n, const char *key,
                               sd_yaml_value *v)
{
    char got[96], sub[160];
    sd_status st = SD_OK;
    memset(v, 0, sizeof *v);
    v->node = n;
    v->line = sd_yaml_line(n);
    switch (k->type) {
    case SD_KT_MAP:
        if (!sd_yaml_is_null(n) && n->type != YAML_MAPPING_NODE)
            return sd_yaml_fail(y, v->line, key, "expected a mapping (key: value lines), got %s",
                           sd_yaml_desc(n, got, sizeof got));
        break;
    case SD_KT_LIST:
        if (!sd_yaml_is_null(n) && n->type != YAML_SEQUENCE_NODE)
            return sd_yaml_fail(y, v->line, key, "expected a list (lines starting with '- '), got %s",
                           sd_yaml_desc(n, got, sizeof got));
        break;
    case SD_KT_NUMBER: st = sd_yaml_read_number(y, k, n, key, "", "", &v->num); break;
    case SD_KT_INT:
        st = sd_yaml_read_int(y, k, n, key, "", &v->integer);
        v->num = (double)v->integer;
        break;
    case SD_KT_STRING: st = sd_yaml_read_string(y, k, n, key, &v->str); break;
    case SD_KT_ENUM:
        st = sd_yaml_read_choice(y, k, n, key, &v->choice);
        if (st == SD_OK)
            v->str = sd_yaml_scalar(n);
        break;
    case SD_KT_ENUM_LIST:
        if (sd_yaml_is_null(n))
            break;
        if (n->type != YAML_SEQUENCE_NODE)
            return sd_yaml_fail(y, v->line, key, "expected a list such as [a, b], got %s",
                           sd_yaml_desc(n, got, sizeof got));
        for (size_t i = 0; i < sd_yaml_seq_len(n); ++i) {
            int c;
            if ((st = sd_yaml_read_choice(y, k, sd_yaml_seq_item(y, n, i), key, &c)) != SD_OK)
                return st;
            v->mask |= 1u << c;
        }
        break;
    case SD_KT_VEC3: st = sd_yaml_read_vec3(y, k, n, key, v->v, NULL); break;
    case SD_KT_INT3: st = sd_yaml_read_vec3(y, k, n, key, v->v, v->iv); break;
    case SD_KT_ENUM_OR_INT3:
        v->choice = -1; /* the list */
        if (n && n->type == YAML_SEQUENCE_NODE)
            st = sd_yaml_read_vec3(y, k, n, key, v->v, v->iv);
        else
            st = sd_yaml_read_choice(y, k, n, key, &v->choice);
        break;
    case SD_KT_NUM_OR_VEC3:
        if (n && n->type == YAML_SEQUENCE_NODE) {
            st = sd_yaml_read_vec3(y, k, n, key, v->v, NULL);
        } else {
            st = sd_yaml_read_number(y, k, n, key, "", " or [x, y, z]", &v->num);
            v->v[0] = v->v[1] = v->v[2] = v->num;
        }
        break;
    case SD_KT_NUM_OR_RANGE:
        if (n && n->type == YAML_MAPPING_NODE) {
            yaml_node_t *mn, *mx;
            if ((st = sd_yaml_read_min_max(y, n, key, &mn, &mx)) != SD_OK)
                return st;
            if ((st = sd_yaml_read_number(y, k, mn, sd_yaml_kp(sub, sizeof sub, key, "min"), "", "", &v->lo)))
                return st;
            if ((st = sd_yaml_read_number(y, k, mx, sd_yaml_kp(sub, sizeof sub, key, "max"), "", "", &v->hi)))
                return st;
            if (v->hi < v->lo)
                return sd_yaml_fail(y, sd_yaml_line(mx), sub, "expected max >= min (%g), got %g", v->lo,
                               v->hi);
        } else {
            st = sd_yaml_read_number(y, k, n, key, "", " or {min: a, max: b}", &v->lo);
            v->hi = v->lo;
        }
        v->num = v->hi;
        break;
    case SD_KT_BOX: {
        yaml_node_t *mn, *mx;
        double lo[3], hi[3];
        if (!n || n->type != YAML_MAPPING_NODE)
            return sd_yaml_fail(y, v->line, key, "expected {min: [x, y, z], max: [x, y, z]}, got %s",
                           sd_yaml_desc(n, got, sizeof got));
        if ((st = sd_yaml_read_min_max(y, n, key, &mn, &mx)) != SD_OK)
            return st;
        if ((st = sd_yaml_read_vec3(y, k, mn, sd_yaml_kp(sub, sizeof sub, key, "min"), lo, NULL)))
            return st;
        if ((st = sd_yaml_read_vec3(y, k, mx, sd_yaml_kp(sub, sizeof sub, key, "max"), hi, NULL)))
            return st;
        for (int a = 0; a < 3; ++a)
            if (!(hi[a] > lo[a]))
                return sd_yaml_fail(y, sd_yaml_line(mx), sub,
                               "expected max > min on every axis, got max %c = %g <= min %c = %g",
                               'x' + a, hi[a], 'x' + a, lo[a]);
        v->box_lo = (sd_v3d){lo[0], lo[1], lo[2]};
        v->box_hi = (sd_v3d){hi[0], hi[1], hi[2]};
        break;
    }
    case SD_KT_NAME_PAIR:
        if (!n || n->type != YAML_SEQUENCE_NODE || sd_yaml_seq_len(n) != 2)
            return sd_yaml_fail(y, v->line, key, "expected a list of 2 material names, got %s",
                           sd_yaml_desc(n, got, sizeof got));
        for (size_t i = 0; i < 2; ++i)
            if ((st = sd_yaml_read_string(y, k, sd_yaml_seq_item(y, n, i), key, &v->names[i])) != SD_OK)
                return st;
        break;
    case SD_KT_ORIENTATION:
        if (n && n->type == YAML_SEQUENCE_NODE) {
            static const char *const comp[4] = {" for w", " for x", " for y", " for z"};
            double norm = 0.0;
            if (sd_yaml_seq_len(n) != 4)
                return sd_yaml_fail(y, v->line, key,
                               "expected identity, random or a quaternion [w, x, y, z], got %s",
                               sd_yaml_desc(n, got, sizeof got));
            for (size_t i = 0; i < 4; ++i) {
                if ((st = sd_yaml_read_number(y, k, sd_yaml_seq_item(y, n, i), key, comp[i], "", &v->q[i])))
                    return st;
                norm += v->q[i] * v->q[i];
            }
            norm = sqrt(norm);
            if (!(norm > 1e-12) || !isfinite(norm))
                return sd_yaml_fail(y, v->line, key, "expected a non-zero quaternion [w, x, y, z], got %s",
                               sd_yaml_desc(n, got, sizeof got));
            for (size_t i = 0; i < 4; ++i)
                v->q[i] /= norm;
            v->choice = SD_ORIENT_FIXED;
        } else if (n && n->type == YAML_SCALAR_NODE && !strcmp(sd_yaml_scalar(n), "identity")) {
            v->choice = SD_ORIENT_IDENTITY;
        } else if (n && n->type == YAML_SCALAR_NODE && !strcmp(sd_yaml_scalar(n), "random")) {
            v->choice = SD_ORIENT_RANDOM;
        } else {
            return sd_yaml_fail(y, v->line, key,
                           "expected identity, random or a quaternion [w, x, y, z], got %s",
                           sd_yaml_desc(n, got, sizeof got));
        }
        break;
    case SD_KT_VEC3_LIST:
        if (!n || n->type != YAML_SEQUENCE_NODE)
            return sd_yaml_fail(y, v->line, key, "expected a list of [x, y, z], got %s",
                           sd_yaml_desc(n, got, sizeof got));
        for (size_t i = 0; i < sd_yaml_seq_len(n); ++i) {
            snprintf(sub, sizeof sub, "%s[%zu]", key, i);
            if ((st = sd_yaml_read_vec3(y, k, sd_yaml_seq_item(y, n, i), sub, v->v, NULL)) != SD_OK)
                return st;
        }
        break;
    case SD_KT_VEC2: st = sd_yaml_read_vec2(y, k, n, key, v->v); break;
    case SD_KT_VEC2_LIST:
        if (!n || n->type != YAML_SEQUENCE_NODE)
            return sd_yaml_fail(y, v->line, key, "expected a list of [x, y], got %s", sd_yaml_desc(n, got, sizeof got));
        for (size_t i = 0; i < sd_yaml_seq_len(n); ++i) {
            snprintf(sub, sizeof sub, "%s[%zu]", key, i);
            if ((st = sd_yaml_read_vec2(y, k, sd_yaml_seq_item(y, n, i), sub, v->v)) != SD_OK)
                return st;
        }
        break;
    case SD_KT_NUM_LIST:
        if (!n || n->type != YAML_SEQUENCE_NODE)
            return sd_yaml_fail(y, v->line, key, "expected a list of numbers such as [0.05, 0.001], got %s",
                           sd_yaml_desc(n, got, sizeof got));
        for (size_t i = 0; i < sd_yaml_seq_len(n); ++i) {
            snprintf(sub, sizeof sub, "%s[%zu]", key, i);
            if ((st = sd_yaml_read_number(y, k, sd_yaml_seq_item(y, n, i), sub, "", "", &v->num)) != SD_OK)
                return st;
        }
        break;
    }
    return st;
}

/* Edit distance of two short keys, for "did you mean" (capped inputs). */
static int sd_yaml_edit_distance(const char *a, const char *b)
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

static sd_status sd_yaml_unknown_key(const sd_yaml *y, sd_scene_section sec, const char *name, int line,
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
        int d = sd_yaml_edit_distance(name, k->key);
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
        return sd_yaml_fail(y, line, key, "unknown key '%s' (did you mean '%s'?)", esc, best);
    return sd_yaml_fail(y, line, key, "unknown key '%s' (expected one of: %s)", esc, known);
}

/* Checks every key of map against the table rows of sec for one kind (a
 * generator or wall type bit, SD_KIND_ALL elsewhere): known, applicable,
 * not repeated, well-typed; then that the required ones are there. */
sd_status sd_yaml_check_map(const sd_yaml *y, yaml_node_t *map, sd_scene_section sec, unsigned kind,
                              const char *kind_name, const char *path, int line)
{
    char key[160], got[96];
    sd_yaml_value v;
    sd_status st;
    if (map && map->type == YAML_MAPPING_NODE) {
        for (yaml_node_pair_t *q = map->data.mapping.pairs.start; q < map->data.mapping.pairs.top;
             ++q) {
            yaml_node_t *kn = yaml_document_get_node(y->doc, q->key);
            yaml_node_t *vn = yaml_document_get_node(y->doc, q->value);
            if (kn->type != YAML_SCALAR_NODE)
                return sd_yaml_fail(y, sd_yaml_line(kn), path, "expected a key name, got %s",
                               sd_yaml_desc(kn, got, sizeof got));
            const char *name = sd_yaml_scalar(kn);
            sd_yaml_kp(key, sizeof key, path, name);
            const sd_scene_key *k = sd_scene_key_find(sec, name);
            if (!k)
                return sd_yaml_unknown_key(y, sec, name, sd_yaml_line(kn), key);
            if (!(k->kinds & kind))
                return sd_yaml_fail(y, sd_yaml_line(kn), key, "key '%s' does not apply to %s", name,
                               kind_name);
            for (yaml_node_pair_t *r = map->data.mapping.pairs.start; r < q; ++r) {
                yaml_node_t *prev = yaml_document_get_node(y->doc, r->key);
                if (prev->type == YAML_SCALAR_NODE && !strcmp(sd_yaml_scalar(prev), name))
                    return sd_yaml_fail(y, sd_yaml_line(kn), key, "duplicate key '%s' (first given at line %d)",
                                   name, sd_yaml_line(prev));
            }
            if ((st = sd_yaml_read_value(y, k, vn, key, &v)) != SD_OK)
                return st;
        }
    }
    for (size_t i = 0; i < sd_scene_key_count; ++i) {
        const sd_scene_key *k = &sd_scene_keys[i];
        if (k->section == sec && (k->required & kind) && !sd_yaml_map_get(y, map, k->key))
            return sd_yaml_fail(y, line, sd_yaml_kp(key, sizeof key, path, k->key),
                           "missing required key '%s' (%s)", k->key, k->doc);
    }
    return SD_OK;
}

/* The value of a key already checked by sd_yaml_check_map. Returns 1 if given;
 * 0 if absent, with v holding the table default when it is a number or a
 * vector (so defaults live in the table only). */
int sd_yaml_get(const sd_yaml *y, yaml_node_t *map, sd_scene_section sec, const char *name,
                  const char *path, sd_yaml_value *v)
{
    const sd_scene_key *k = sd_scene_key_find(sec, name);
    yaml_node_t *n = sd_yaml_map_get(y, map, name);
    memset(v, 0, sizeof *v);
    if (!k)
        return 0; /* a bug: every name used here is in the table */
    if (n) {
        char key[160];
        /* Cannot fail: sd_yaml_check_map has read the same node with the same row. */
        sd_yaml_read_value(y, k, n, sd_yaml_kp(key, sizeof key, path, name), v);
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


int sd_yaml_key_line(const sd_yaml *y, yaml_node_t *map, const char *key)
{
    for (yaml_node_pair_t *q = map->data.mapping.pairs.start; q < map->data.mapping.pairs.top; ++q) {
        yaml_node_t *k = yaml_document_get_node(y->doc, q->key);
        if (k->type == YAML_SCALAR_NODE && !strcmp(sd_yaml_scalar(k), key))
            return sd_yaml_line(k);
    }
    return 1;
}

sd_status sd_yaml_entry(const sd_yaml *y, const yaml_node_t *list, size_t i, const char *section, const char *form,
                        char *path, size_t path_size, yaml_node_t **m)
{
    char got[96];
    snprintf(path, path_size, "%s[%zu]", section, i);
    *m = sd_yaml_seq_item(y, list, i);
    if ((*m)->type != YAML_MAPPING_NODE)
        return sd_yaml_fail(y, sd_yaml_line(*m), path, "expected a mapping %s, got %s", form,
                            sd_yaml_desc(*m, got, sizeof got));
    return SD_OK;
}

sd_status sd_yaml_place_numbers(const sd_yaml *y, yaml_node_t *map, sd_scene_section sec, const char *path,
                                const sd_yaml_place *place, size_t n, const char *const *rules, void *base)
{
    for (size_t i = 0; i < sd_scene_key_count; ++i) {
        const sd_scene_key *k = &sd_scene_keys[i];
        if (k->section != sec)
            continue;
        int known = 0;
        for (size_t j = 0; j < n && !known; ++j)
            known = !strcmp(place[j].key, k->key) && (k->type == SD_KT_NUMBER || k->type == SD_KT_INT);
        for (const char *const *r = rules; *r && !known; ++r)
            known = !strcmp(*r, k->key);
        if (!known)
            return sd_error_set(y->err, SD_ERR_INTERNAL, y->path, 0, k->key,
                                "a bug: key '%s' of %s is neither placed nor read by its section", k->key,
                                sd_scene_section_name(sec));
    }
    for (size_t j = 0; j < n; ++j) {
        sd_yaml_value v;
        sd_yaml_get(y, map, sec, place[j].key, path, &v);
        memcpy((char *)base + place[j].offset, &v.num, sizeof v.num);
    }
    return SD_OK;
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
static int sd_yaml_line_of_offset(const unsigned char *buf, size_t len, size_t off)
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
        return sd_error_set(err, SD_ERR_INPUT, path, sd_yaml_line_of_offset(buf, len, parser->problem_offset), "",
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
static sd_status sd_yaml_read_file(const char *path, unsigned char **out, size_t *len, sd_error *err)
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
typedef struct sd_yaml_tagged {
    size_t *index;
    size_t n, cap;
} sd_yaml_tagged;

/* One pass over the events before loading: refuses nesting deeper than
 * SD_SCENE_MAX_DEPTH at the line where it passes the limit (the scanner's
 * cost stays linear up to there), and lists the scalars tagged !!str or !.
 * Syntax errors are reported here, as the loader would. */
static sd_status sd_yaml_prescan(const unsigned char *buf, size_t len, const char *path, sd_yaml_tagged *tg,
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
static void sd_yaml_mark_tagged(yaml_document_t *doc, const sd_yaml_tagged *tg)
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

sd_status sd_yaml_load(const char *path, yaml_document_t *doc, sd_error *err)
{
    unsigned char *buf;
    size_t len;
    sd_status st = sd_yaml_read_file(path, &buf, &len, err);
    if (st != SD_OK)
        return st;
    sd_yaml_tagged tg = {NULL, 0, 0};
    if ((st = sd_yaml_prescan(buf, len, path, &tg, err)) != SD_OK) {
        sd_free(tg.index);
        sd_free(buf);
        return st;
    }
    yaml_parser_t parser;
    yaml_document_t next;
    if (!yaml_parser_initialize(&parser)) {
        sd_free(tg.index);
        sd_free(buf);
        return sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    }
    yaml_parser_set_input_string(&parser, buf, len);
    if (!yaml_parser_load(&parser, doc)) {
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
    sd_yaml_mark_tagged(doc, &tg);
    sd_free(tg.index);
    /* the document holds copies of its scalars: the parser and the text go */
    yaml_parser_delete(&parser);
    sd_free(buf);
    if (st != SD_OK)
        yaml_document_delete(doc);
    return st;
}
