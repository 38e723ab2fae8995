/* composites.c — the public side of composite templates (seed 004): a
 * composite is a shape template like any other (its index goes into
 * sd_body_def.shape) whose elements live in the world's element pool.
 *
 * Invariant: shapes[k].estart / ecount of a composite index
 * elements[estart .. estart + ecount), in the composite's principal frame;
 * every element's template is convex and was added before the composite.
 * A preset (shape/complib.h) becomes element templates first, one per
 * distinct part size, then a composite like any other.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "shape/complib.h"
#include "shape/composite.h"
#include "world/world.h"

#define SD_COMPOSITE_COOKIE 0x5DC0

sd_composite_desc sd_composite_desc_default(void)
{
    sd_composite_desc d;
    memset(&d, 0, sizeof d);
    d.cookie = SD_COMPOSITE_COOKIE;
    return d;
}

int sd_world_add_composite(sd_world *w, const char *name, const sd_composite_desc *desc, sd_error *err)
{
    if (!w) {
        sd_error_null(err, "sd_world_add_composite", "world");
        return -1;
    }
    if (!desc || desc->cookie != SD_COMPOSITE_COOKIE) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "shapes", "composite desc not made by sd_composite_desc_default");
        return -1;
    }
    if (w->dim2) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "type", "composites are 3D; dimension 2 has no composite shapes");
        return -1;
    }
    if (sd_world_check_shape_name(w, name, err) != SD_OK)
        return -1;
    size_t n = desc->element_count;
    if (!desc->elements || n == 0) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "elements", "composite '%s' needs at least one element", name);
        return -1;
    }
    if (n > SD_COMPOSITE_MAX_ELEMENTS) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "elements", "composite '%s': at most %d elements, got %zu", name,
                     SD_COMPOSITE_MAX_ELEMENTS, n);
        return -1;
    }
    sd_composite_part *parts = sd_malloc(n * sizeof *parts);
    sd_element *el = sd_realloc(w->elements, (w->element_count + n) * sizeof *el);
    if (el)
        w->elements = el;
    sd_shape *shapes = sd_realloc(w->shapes, (w->shape_count + 1) * sizeof *shapes);
    if (shapes)
        w->shapes = shapes;
    char(*names)[64] = sd_realloc(w->shape_names, (w->shape_count + 1) * sizeof *names);
    if (names)
        w->shape_names = names;
    sd_real *req = sd_realloc(w->shape_req, (w->shape_count + 1) * sizeof *req);
    if (req)
        w->shape_req = req;
    sd_vec3 *com = sd_realloc(w->shape_com, (w->shape_count + 1) * sizeof *com);
    if (com)
        w->shape_com = com;
    if (!parts || !el || !shapes || !names || !req || !com) {
        sd_free(parts);
        sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory adding composite '%s'", name);
        return -1;
    }
    for (size_t e = 0; e < n; ++e) {
        const sd_composite_element *ce = &desc->elements[e];
        parts[e].shape = ce->shape;
        parts[e].x = sd_v3((sd_real)ce->position.x, (sd_real)ce->position.y, (sd_real)ce->position.z);
        parts[e].q = sd_quat_make((sd_real)ce->orientation[0], (sd_real)ce->orientation[1],
                                  (sd_real)ce->orientation[2], (sd_real)ce->orientation[3]);
    }
    sd_composite_pools pools = {w->shapes, w->shape_count, w->verts, w->planes, w->dtris};
    sd_shape s;
    sd_status st = sd_composite_make(&pools, parts, n, desc->lattice, w->threads, &s, w->elements + w->element_count,
                                     err);
    sd_free(parts);
    if (st != SD_OK)
        return -1;
    s.estart = (uint32_t)w->element_count;
    w->element_count += n;
    w->shape_com[w->shape_count] = s.given_com;
    w->shapes[w->shape_count] = s;
    w->shape_req[w->shape_count] = (sd_real)cbrt(3.0 * (double)s.volume / (4.0 * SD_PI_D));
    snprintf(w->shape_names[w->shape_count], 64, "%s", name);
    w->prepared = 0;
    return (int)w->shape_count++;
}

#define SD_COMPOSITE_PRESET_COOKIE 0x5DC1

sd_composite_preset_def sd_composite_preset_def_default(void)
{
    sd_composite_preset_def d;
    memset(&d, 0, sizeof d);
    d.cookie = SD_COMPOSITE_PRESET_COOKIE;
    return d;
}

sd_status sd_composite_preset(sd_world *w, const char *name, const sd_composite_preset_def *def,
                              sd_composite_element *out, size_t cap, size_t *n, sd_error *err)
{
    if (!n)
        return sd_error_null(err, "sd_composite_preset", "n");
    *n = 0;
    if (!w)
        return sd_error_null(err, "sd_composite_preset", "world");
    if (!out && cap > 0)
        return sd_error_null(err, "sd_composite_preset", "out");
    if (!def || def->cookie != SD_COMPOSITE_PRESET_COOKIE)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "preset",
                            "composite preset def not made by sd_composite_preset_def_default");
    sd_comp_def cd;
    memset(&cd, 0, sizeof cd);
    cd.preset = sd_complib_from_name(def->preset);
    if (cd.preset < 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "preset",
                            "unknown composite preset '%s' (cross2d, cross3d, lshape, tshape, ring, dumbbell, "
                            "spheres9, spheres54)",
                            def->preset ? def->preset : "(null)");
    /* a parameter the preset does not take is a mistake, not a no-op */
    static const char *const keys[5] = {"length", "diameter", "width", "thickness", "count"};
    static const unsigned bits[5] = {SD_COMP_USES_LENGTH, SD_COMP_USES_DIAMETER, SD_COMP_USES_WIDTH,
                                     SD_COMP_USES_THICKNESS, SD_COMP_USES_COUNT};
    const int given[5] = {def->length != 0, def->diameter != 0, def->width != 0, def->thickness != 0,
                          def->count != 0};
    unsigned uses = sd_complib_uses(cd.preset);
    for (int k = 0; k < 5; ++k)
        if (given[k] && !(uses & bits[k]))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, keys[k], "%s does not apply to the %s preset", keys[k],
                                def->preset);
    cd.length = def->length;
    cd.diameter = def->diameter;
    cd.width = def->width;
    cd.thickness = def->thickness;
    cd.count = def->count;
    sd_comp_part parts[SD_COMP_MAX_PARTS];
    size_t np = 0;
    sd_status st = sd_complib_parts(&cd, parts, SD_COMP_MAX_PARTS, &np, err);
    if (st != SD_OK)
        return st;
    if (np > cap)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "elements", "the %s preset makes %zu elements, room for %zu",
                            def->preset, np, cap);
    /* one template per distinct (kind, size), in order of first use */
    int tmpl[SD_COMP_MAX_PARTS];
    size_t nt = 0;
    for (size_t k = 0; k < np; ++k) {
        size_t h = 0;
        while (h < k && !(!strcmp(parts[h].kind, parts[k].kind) && parts[h].size.x == parts[k].size.x &&
                          parts[h].size.y == parts[k].size.y && parts[h].size.z == parts[k].size.z))
            ++h;
        if (h < k) {
            tmpl[k] = tmpl[h];
        } else {
            char en[96];
            if (snprintf(en, sizeof en, "%s.e%zu", name ? name : "", nt) >= (int)sizeof en)
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "name",
                                    "the composite's name is too long to name its element shapes");
            sd_shape_desc sdsc = sd_shape_desc_default();
            sdsc.kind = parts[k].kind;
            sdsc.size = parts[k].size;
            tmpl[k] = sd_world_add_shape(w, en, &sdsc, err);
            if (tmpl[k] < 0)
                return err ? err->code : SD_ERR_INPUT;
            ++nt;
        }
        memset(&out[k], 0, sizeof out[k]);
        out[k].shape = tmpl[k];
        out[k].position = parts[k].position;
        memcpy(out[k].orientation, parts[k].orientation, sizeof out[k].orientation);
    }
    *n = np;
    return SD_OK;
}

int sd_world_add_composite_preset(sd_world *w, const char *name, const sd_composite_preset_def *def, sd_error *err)
{
    sd_composite_element el[SD_COMP_MAX_PARTS];
    size_t n = 0;
    if (sd_composite_preset(w, name, def, el, SD_COMP_MAX_PARTS, &n, err) != SD_OK)
        return -1;
    sd_composite_desc cd = sd_composite_desc_default();
    cd.elements = el;
    cd.element_count = n;
    return sd_world_add_composite(w, name, &cd, err);
}
