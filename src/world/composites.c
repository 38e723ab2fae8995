/* composites.c — the public side of composite templates (seed 004): a
 * composite is a shape template like any other (its index goes into
 * sd_body_def.shape) whose elements live in the world's element pool.
 *
 * Invariant: shapes[k].estart / ecount of a composite index
 * elements[estart .. estart + ecount), in the composite's principal frame;
 * every element's template is convex and was added before the composite.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
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
