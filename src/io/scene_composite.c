/* scene_composite.c — a shapes: entry of type composite (seed 004, glued
 * convex elements): its elements (a convex shape listed before it, by name,
 * or inline: type and size keys), or a built-in preset (shape/complib.h),
 * and the lattice resolution.
 *
 * Invariant: when this returns SD_OK the composite's elements index convex
 * shapes listed before it. Inline and preset elements become shapes of
 * their own, named NAME.eK and marked hidden, inserted just before the
 * composite (equal preset parts share one), so a scene's shape index is
 * still the world's; every error names the file, line and key.
 */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/scene_keys.h"
#include "io/scene_sections.h"
#include "shape/complib.h"
#include "shape/composite.h"
#include "shape/polylib.h"
#include "shape/shape.h"

/* A hidden shape for element k of composite sh. */
static sd_status sd_hidden_shape(sd_parse *p, const sd_scene_shape *sh, size_t k, int line, const char *key,
                                 sd_scene_shape *out)
{
    memset(out, 0, sizeof *out);
    if (snprintf(out->name, sizeof out->name, "%s.e%zu", sh->name, k) >= (int)sizeof out->name)
        return sd_fail(p, line, key, "the composite's name is too long to name its element shapes (%s.e%zu)",
                       sh->name, k);
    for (size_t j = 0; j < p->s->shape_count; ++j)
        if (!strcmp(p->s->shapes[j].name, out->name))
            return sd_fail(p, line, key, "the element shape name '%s' is taken (shapes[%zu], line %d)", out->name,
                           p->s->shapes[j].entry, p->s->shapes[j].line);
    out->kind2d = -1;
    out->preset = -1;
    out->scale = 1;
    out->hidden = 1;
    out->line = line;
    out->entry = sh->entry;
    return SD_OK;
}

/* One inline element: type and its size keys (the element's map is checked). */
static sd_status sd_inline_element(sd_parse *p, yaml_node_t *m, const char *path, const sd_yaml_value *tv,
                                   sd_scene_shape *hs)
{
    static const int kinds[4] = {SD_SHAPE_SPHERE, SD_SHAPE_BOX, SD_SHAPE_CYLINDER, SD_SHAPE_ELLIPSOID};
    static const char *const need[4][2] = {{"radius", NULL}, {"size", NULL}, {"diameter", "length"}, {"semi_axes", NULL}};
    static const char *const sizes[5] = {"radius", "size", "diameter", "length", "semi_axes"};
    char key[128];
    sd_yaml_value v;
    int t = tv->choice;
    hs->kind = kinds[t];
    for (size_t k = 0; k < 5; ++k) {
        int wanted = (need[t][0] && !strcmp(need[t][0], sizes[k])) || (need[t][1] && !strcmp(need[t][1], sizes[k]));
        int given = sd_yaml_get(&p->y, m, SD_SEC_ELEMENT, sizes[k], path, &v);
        if (given && !wanted)
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, sizes[k]),
                           "%s does not apply to an inline %s element", sizes[k], sd_shape_kind_name(hs->kind));
        if (!given && wanted)
            return sd_fail(p, tv->line, sd_yaml_kp(key, sizeof key, path, sizes[k]),
                           "missing required key '%s' for an inline %s element", sizes[k],
                           sd_shape_kind_name(hs->kind));
    }
    switch (hs->kind) {
    case SD_SHAPE_SPHERE:
        sd_yaml_get(&p->y, m, SD_SEC_ELEMENT, "radius", path, &v);
        hs->size = (sd_v3d){v.num, v.num, v.num};
        break;
    case SD_SHAPE_BOX:
    case SD_SHAPE_ELLIPSOID:
        sd_yaml_get(&p->y, m, SD_SEC_ELEMENT, hs->kind == SD_SHAPE_BOX ? "size" : "semi_axes", path, &v);
        hs->size = (sd_v3d){v.v[0], v.v[1], v.v[2]};
        break;
    default: {
        sd_yaml_value l;
        sd_yaml_get(&p->y, m, SD_SEC_ELEMENT, "diameter", path, &v);
        sd_yaml_get(&p->y, m, SD_SEC_ELEMENT, "length", path, &l);
        hs->size = (sd_v3d){v.num, v.num, l.num};
        break;
    }
    }
    sd_yaml_get(&p->y, m, SD_SEC_ELEMENT, "rounding", path, &v);
    hs->rounding = v.num;
    return SD_OK;
}

static sd_composite_element sd_element_at(int shape, sd_v3d x, const double q[4])
{
    sd_composite_element e;
    memset(&e, 0, sizeof e);
    e.shape = shape;
    e.position = x;
    memcpy(e.orientation, q, sizeof e.orientation);
    return e;
}

sd_status sd_parse_composite(sd_parse *p, yaml_node_t *m, const char *path, size_t si, size_t more)
{
    sd_scene *s = p->s;
    sd_scene_shape *sh = &s->shapes[si];
    char key[128], epath[96];
    sd_yaml_value ev, pv, lv, v;
    sd_status st = SD_OK;
    int he = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "elements", path, &ev);
    int hp = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "preset", path, &pv);
    sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "lattice", path, &lv);
    sh->preset = -1;
    /* rounding and scale belong to the elements (each shape has its own) */
    static const char *const none[2] = {"rounding", "scale"};
    for (int k = 0; k < 2; ++k)
        if (sd_yaml_get(&p->y, m, SD_SEC_SHAPE, none[k], path, &v))
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, none[k]),
                           "a composite takes no %s: give it to its elements' shapes", none[k]);
    if (lv.integer < 4 || lv.integer > SD_COMPOSITE_LATTICE_MAX)
        return sd_fail(p, lv.line, sd_yaml_kp(key, sizeof key, path, "lattice"),
                       "expected 4 to %d points per direction, got %lld", SD_COMPOSITE_LATTICE_MAX, lv.integer);
    sh->lattice = (int)lv.integer;
    if (he && hp)
        return sd_fail(p, pv.line, sd_yaml_kp(key, sizeof key, path, "preset"),
                       "give elements or preset, not both (elements is at line %d)", ev.line);
    if (!he && !hp)
        return sd_fail(p, sh->line, sd_yaml_kp(key, sizeof key, path, "elements"),
                       "missing required key 'elements' (a list of convex elements, or preset: a built-in "
                       "composite)");
    /* the size keys of presets */
    static const char *const pkeys[5] = {"length", "diameter", "width", "thickness", "count"};
    static const unsigned pbits[5] = {SD_COMP_USES_LENGTH, SD_COMP_USES_DIAMETER, SD_COMP_USES_WIDTH,
                                      SD_COMP_USES_THICKNESS, SD_COMP_USES_COUNT};
    sd_yaml_value pval[5];
    int pgiven[5];
    for (int k = 0; k < 5; ++k)
        pgiven[k] = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, pkeys[k], path, &pval[k]);

    size_t nel = 0, nh = 0;
    sd_composite_element *el = NULL;
    sd_scene_shape *hid = NULL;
    if (hp) {
        if (pv.choice < SD_POLY_PRESET_COUNT)
            return sd_fail(p, pv.line, sd_yaml_kp(key, sizeof key, path, "preset"),
                           "'%s' is a polyhedron preset (type: polyhedron); composite presets are cross2d, "
                           "cross3d, lshape, tshape, ring, dumbbell, spheres9, spheres54", pv.str);
        sd_comp_def cd;
        memset(&cd, 0, sizeof cd);
        cd.preset = pv.choice - SD_POLY_PRESET_COUNT;
        sh->preset = cd.preset;
        unsigned uses = sd_complib_uses(cd.preset);
        for (int k = 0; k < 5; ++k) {
            if (pgiven[k] && !(uses & pbits[k]))
                return sd_fail(p, pval[k].line, sd_yaml_kp(key, sizeof key, path, pkeys[k]),
                               "%s does not apply to the %s preset", pkeys[k], pv.str);
            if (!pgiven[k] && (uses & pbits[k]))
                return sd_fail(p, sh->line, sd_yaml_kp(key, sizeof key, path, pkeys[k]),
                               "missing required key '%s' for the %s preset", pkeys[k], pv.str);
        }
        cd.length = pval[0].num;
        cd.diameter = pval[1].num;
        cd.width = pval[2].num;
        cd.thickness = pval[3].num;
        cd.count = pgiven[4] ? (int)pval[4].integer : 0;
        sd_comp_part parts[SD_COMP_MAX_PARTS];
        sd_error e2;
        if (sd_complib_parts(&cd, parts, SD_COMP_MAX_PARTS, &nel, &e2) != SD_OK) {
            char kk[24];
            snprintf(kk, sizeof kk, "%.20s", e2.key[0] ? e2.key : "preset");
            int line = pv.line;
            for (int k = 0; k < 5; ++k)
                if (!strcmp(kk, pkeys[k]) && pgiven[k])
                    line = pval[k].line;
            return sd_fail(p, line, sd_yaml_kp(key, sizeof key, path, kk), "%s", e2.msg);
        }
        el = sd_calloc(nel, sizeof *el);
        hid = sd_calloc(nel, sizeof *hid);
        if (!el || !hid) {
            st = sd_yaml_oom(&p->y);
            goto done;
        }
        for (size_t k = 0; k < nel; ++k) {
            int kind = sd_shape_kind_from_name(parts[k].kind);
            size_t h = 0;
            while (h < nh && !(hid[h].kind == kind && hid[h].size.x == parts[k].size.x &&
                               hid[h].size.y == parts[k].size.y && hid[h].size.z == parts[k].size.z))
                ++h;
            if (h == nh) {
                if ((st = sd_hidden_shape(p, sh, nh, pv.line, sd_yaml_kp(key, sizeof key, path, "preset"), &hid[nh])))
                    goto done;
                hid[nh].kind = kind;
                hid[nh].size = parts[k].size;
                ++nh;
            }
            el[k] = sd_element_at(-1 - (int)h, parts[k].position, parts[k].orientation);
        }
    } else {
        for (int k = 0; k < 5; ++k)
            if (pgiven[k])
                return sd_fail(p, pval[k].line, sd_yaml_kp(key, sizeof key, path, pkeys[k]),
                               "%s applies to a composite preset (preset: ...) only", pkeys[k]);
        nel = sd_yaml_seq_len(ev.node);
        if (nel < 1 || nel > SD_COMPOSITE_MAX_ELEMENTS)
            return sd_fail(p, ev.line, sd_yaml_kp(key, sizeof key, path, "elements"),
                           "expected 1 to %d elements, got %zu", SD_COMPOSITE_MAX_ELEMENTS, nel);
        el = sd_calloc(nel, sizeof *el);
        hid = sd_calloc(nel, sizeof *hid);
        if (!el || !hid) {
            st = sd_yaml_oom(&p->y);
            goto done;
        }
        char section[80];
        snprintf(section, sizeof section, "%s.elements", path);
        for (size_t k = 0; k < nel; ++k) {
            yaml_node_t *em;
            if ((st = sd_yaml_entry(&p->y, ev.node, k, section, "(shape: NAME or type: ..., position: [x, y, z])",
                                    epath, sizeof epath, &em)))
                goto done;
            int eline = sd_yaml_line(em);
            if ((st = sd_yaml_check_map(&p->y, em, SD_SEC_ELEMENT, SD_KIND_ALL, "", epath, eline)))
                goto done;
            sd_yaml_value nv, tv;
            int hn = sd_yaml_get(&p->y, em, SD_SEC_ELEMENT, "shape", epath, &nv);
            int ht = sd_yaml_get(&p->y, em, SD_SEC_ELEMENT, "type", epath, &tv);
            if (hn && ht) {
                st = sd_fail(p, tv.line, sd_yaml_kp(key, sizeof key, epath, "type"),
                             "give shape (a shape listed before) or type (an inline element), not both "
                             "(shape is at line %d)", nv.line);
                goto done;
            }
            if (!hn && !ht) {
                st = sd_fail(p, eline, sd_yaml_kp(key, sizeof key, epath, "shape"),
                             "missing required key 'shape' (the name of a convex shape listed before, or "
                             "type: sphere|box|cylinder|ellipsoid with its size)");
                goto done;
            }
            int idx;
            if (hn) {
                static const char *const sizes[6] = {"radius", "size", "diameter", "length", "semi_axes", "rounding"};
                for (int q = 0; q < 6; ++q)
                    if (sd_yaml_get(&p->y, em, SD_SEC_ELEMENT, sizes[q], epath, &v)) {
                        st = sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, epath, sizes[q]),
                                     "%s applies to an inline element (type: ...); the shape '%s' has its own",
                                     sizes[q], nv.str);
                        goto done;
                    }
                sd_yaml_kp(key, sizeof key, epath, "shape");
                if ((st = sd_shape_ref(p, nv.str, nv.line, key, &idx)))
                    goto done;
                if ((size_t)idx == si || s->shapes[idx].kind == SD_SHAPE_COMPOSITE) {
                    st = sd_fail(p, nv.line, key, "'%s' is a composite; elements are convex shapes", nv.str);
                    goto done;
                }
            } else {
                if ((st = sd_hidden_shape(p, sh, nh, tv.line, sd_yaml_kp(key, sizeof key, epath, "type"), &hid[nh])))
                    goto done;
                if ((st = sd_inline_element(p, em, epath, &tv, &hid[nh])))
                    goto done;
                idx = -1 - (int)nh++;
            }
            double q[4] = {1, 0, 0, 0};
            sd_yaml_value ov;
            if (sd_yaml_get(&p->y, em, SD_SEC_ELEMENT, "orientation", epath, &ov)) {
                if (ov.choice == SD_ORIENT_RANDOM) {
                    st = sd_fail(p, ov.line, sd_yaml_kp(key, sizeof key, epath, "orientation"),
                                 "an element's orientation is identity or a quaternion [w, x, y, z], not random");
                    goto done;
                }
                if (ov.choice == SD_ORIENT_FIXED)
                    memcpy(q, ov.q, sizeof q);
            }
            sd_yaml_get(&p->y, em, SD_SEC_ELEMENT, "position", epath, &v);
            el[k] = sd_element_at(idx, (sd_v3d){v.v[0], v.v[1], v.v[2]}, q);
        }
    }

    /* room for the hidden shapes before the composite and the entries to come */
    if (nh) {
        size_t need = si + nh + 1 + more;
        sd_scene_shape *grown = sd_realloc(s->shapes, need * sizeof *grown);
        if (!grown) {
            st = sd_yaml_oom(&p->y);
            goto done;
        }
        s->shapes = grown;
        memset(grown + si + 1, 0, (need - si - 1) * sizeof *grown);
        grown[si + nh] = grown[si];
        memcpy(grown + si, hid, nh * sizeof *hid);
        s->shape_count = si + nh + 1;
        sh = &grown[si + nh];
    }
    for (size_t k = 0; k < nel; ++k)
        if (el[k].shape < 0)
            el[k].shape = (int)si + (-1 - el[k].shape);
    sh->elements = el;
    sh->element_count = nel;
    el = NULL;
done:
    sd_free(el);
    sd_free(hid);
    return st;
}
