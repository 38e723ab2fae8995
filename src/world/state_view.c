/* state_view.c — the particle arrays as they are, for readers that must
 * not copy: sd_world_generation and sd_world_state_view
 * (include/shapedem/shapedem.h; the Python binding's numpy views,
 * docs/python.md).
 *
 * Invariant: a view's pointers are the world's own arrays (owned
 * particles only, rows 0 .. p.n - 1) and its generation is the arrays'
 * (sd_particles.generation, world/world.h), which every change of where
 * the arrays are or which particle a slot holds advances; a reader that
 * finds the world's generation still equal to the view's reads live
 * memory of the particles the id array names.
 */
#include <string.h>

#include "core/error.h"
#include "world/world.h"

/* the public view hands out double, int32 and uint64 arrays: the state
 * must be stored in exactly those (sd_real double, sd_vec3 and sd_quat
 * without padding) */
#if !defined(SHAPEDEM_SINGLE)
_Static_assert(sizeof(sd_vec3) == 3 * sizeof(double), "sd_state_view: sd_vec3 must be 3 doubles");
_Static_assert(sizeof(sd_quat) == 4 * sizeof(double), "sd_state_view: sd_quat must be 4 doubles (w, x, y, z)");
_Static_assert(offsetof(sd_quat, w) == 0, "sd_state_view: orientation is (w, x, y, z)");
#endif

uint64_t sd_world_generation(const sd_world *w)
{
    return w ? w->p.generation : 0;
}

sd_status sd_world_state_view(const sd_world *w, sd_state_view *out, sd_error *err)
{
    if (out)
        memset(out, 0, sizeof *out);
    if (!w || !out)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "sd_world_state_view: %s is NULL", w ? "out" : "world");
#if defined(SHAPEDEM_SINGLE)
    return sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                        "sd_world_state_view: this build stores single-precision reals; use sd_world_get_field");
#else
    if (w->def.solver == SD_SOLVER_GRID)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                            "sd_world_state_view: the grid solver keeps its particles in its grid, not in "
                            "arrays to view; use sd_world_get_field");
    const sd_particles *p = &w->p;
    out->generation = p->generation;
    out->n = p->n;
    if (p->n == 0)
        return SD_OK;
    out->position = &p->x[0].x;
    out->velocity = &p->v[0].x;
    out->angular_velocity = &p->w[0].x;
    out->orientation = &p->q[0].w;
    out->force = &p->f[0].x;
    out->torque = &p->t[0].x;
    out->radius = p->radius;
    out->material = p->material;
    out->shape = p->shape;
    out->id = p->id;
    return SD_OK;
#endif
}
