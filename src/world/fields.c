/* fields.c — particle fields in bulk by stable id: sd_world_get_ids,
 * sd_world_get_field, sd_world_set_field (include/shapedem/shapedem.h).
 *
 * Storage order changes at every pair-list rebuild (world/rebuild.c sorts
 * by cell); callers keep arrays in the order of the stable ids. Each call
 * lists (id, storage index) through the solver's read (world/solver.h, so
 * the grid solver's particles are seen too), sorts that list by id and
 * looks each wanted id up in it: O((N + n) log N), no state kept between
 * calls, so nothing goes stale when the world reorders or grows.
 *
 * Invariant: a call that fails writes nothing (the caller's array or the
 * world): sizes, ids and values are all checked first.
 *
 * The public field list (SD_FIELDS) names for each field the member of
 * sd_particle_state it is read from, and the setters are generated from
 * the query column of SD_PARTICLE_FIELDS (world/world.h), so a field is
 * declared once (STYLE.md convention 5).
 */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "world/solver.h"
#include "world/world.h"

/* each public field is a run of doubles of sd_particle_state */
#define SD_X_CHECK(e, name, member, comps, unit, writable, doc)                                              \
    _Static_assert(sizeof(((sd_particle_state *)0)->member) == (comps) * sizeof(double),                     \
                   "SD_FIELDS: " name " must be " #comps " doubles of sd_particle_state");
SD_FIELDS(SD_X_CHECK)
#undef SD_X_CHECK

typedef struct sd_field_desc {
    const char *name, *unit;
    size_t offset, comps;
    int writable;
} sd_field_desc;

static const sd_field_desc sd_field_descs[SD_FIELD_COUNT] = {
#define SD_X_DESC(e, name, member, comps, unit, writable, doc)                                               \
    [e] = {name, unit, offsetof(sd_particle_state, member), comps, writable},
    SD_FIELDS(SD_X_DESC)
#undef SD_X_DESC
};

static const sd_field_desc *sd_field_desc_of(sd_field field)
{
    return (int)field >= 0 && field < SD_FIELD_COUNT ? &sd_field_descs[field] : NULL;
}

const char *sd_field_name(sd_field field)
{
    const sd_field_desc *d = sd_field_desc_of(field);
    return d ? d->name : NULL;
}

size_t sd_field_components(sd_field field)
{
    const sd_field_desc *d = sd_field_desc_of(field);
    return d ? d->comps : 0;
}

const char *sd_field_unit(sd_field field)
{
    const sd_field_desc *d = sd_field_desc_of(field);
    return d ? d->unit : NULL;
}

int sd_field_writable(sd_field field)
{
    const sd_field_desc *d = sd_field_desc_of(field);
    return d ? d->writable : 0;
}

/* ---- the id index ------------------------------------------------------------ */

typedef struct sd_id_slot {
    uint64_t id;
    size_t index; /* storage index (the solver's) */
} sd_id_slot;

static int sd_id_slot_cmp(const void *a, const void *b)
{
    uint64_t x = ((const sd_id_slot *)a)->id, y = ((const sd_id_slot *)b)->id;
    return (x > y) - (x < y);
}

/* Every particle's (id, index), sorted by id, into *out (n entries; NULL
 * when there is none). */
static sd_status sd_fields_index(const sd_world *w, sd_id_slot **out, size_t *count, sd_error *err)
{
    size_t n = w->solver->count(w);
    *out = NULL;
    *count = n;
    if (n == 0)
        return SD_OK;
    sd_id_slot *ix = sd_malloc(n * sizeof *ix);
    if (!ix)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for the id index of %zu particles", n);
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state st;
        if (w->solver->read(w, k, &st) != SD_OK) {
            sd_free(ix);
            return sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "particle %zu of %zu cannot be read", k, n);
        }
        ix[k].id = st.id;
        ix[k].index = k;
    }
    qsort(ix, n, sizeof *ix, sd_id_slot_cmp);
    *out = ix;
    return SD_OK;
}

static const sd_id_slot *sd_fields_lookup(const sd_id_slot *ix, size_t n, uint64_t id)
{
    sd_id_slot key = {id, 0};
    return n ? bsearch(&key, ix, n, sizeof *ix, sd_id_slot_cmp) : NULL;
}

/* The argument checks shared by get and set: world, field, sizes. */
static sd_status sd_fields_args(const sd_world *w, sd_field field, const uint64_t *ids, size_t n, const void *buf,
                                size_t len, const char *call, const sd_field_desc **desc, sd_error *err)
{
    if (!w)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "%s: world is NULL", call);
    const sd_field_desc *d = sd_field_desc_of(field);
    if (!d)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "%s: unknown field %d (0 to %d)", call, (int)field,
                            SD_FIELD_COUNT - 1);
    size_t count = w->solver->count(w);
    if (!ids && n != count)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "%s: no ids given, so n must be the %zu particles, got %zu",
                            call, count, n);
    if (n > 0 && !buf)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "%s: the array of values is NULL", call);
    if (n > SIZE_MAX / d->comps || len != n * d->comps)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                            "%s: %zu particles of field '%s' take %zu values (%zu each), the array holds %zu", call,
                            n, d->name, n <= SIZE_MAX / d->comps ? n * d->comps : SIZE_MAX, d->comps, len);
    *desc = d;
    return SD_OK;
}

/* The storage index of each wanted particle, into slot[0 .. n). */
static sd_status sd_fields_resolve(const sd_world *w, const uint64_t *ids, size_t n, const char *call,
                                   size_t **slot, sd_error *err)
{
    sd_id_slot *ix;
    size_t count;
    *slot = NULL;
    sd_status st = sd_fields_index(w, &ix, &count, err);
    if (st != SD_OK || n == 0) {
        sd_free(ix);
        return st;
    }
    size_t *out = sd_malloc(n * sizeof *out);
    if (!out) {
        sd_free(ix);
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "%s: out of memory for %zu indices", call, n);
    }
    for (size_t k = 0; k < n; ++k) {
        if (!ids) { /* all of them, in id order */
            out[k] = ix[k].index;
            continue;
        }
        const sd_id_slot *e = sd_fields_lookup(ix, count, ids[k]);
        if (!e) {
            sd_free(ix);
            sd_free(out);
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "%s: ids[%zu] = %llu is not a particle of the world",
                                call, k, (unsigned long long)ids[k]);
        }
        out[k] = e->index;
    }
    sd_free(ix);
    *slot = out;
    return SD_OK;
}

sd_status sd_world_get_ids(const sd_world *w, uint64_t *ids, size_t n, sd_error *err)
{
    if (!w)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "sd_world_get_ids: world is NULL");
    size_t count = w->solver->count(w);
    if (n != count)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "sd_world_get_ids: the world has %zu particles, n is %zu",
                            count, n);
    if (n > 0 && !ids)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "sd_world_get_ids: ids is NULL");
    sd_id_slot *ix;
    sd_status st = sd_fields_index(w, &ix, &count, err);
    if (st != SD_OK)
        return st;
    for (size_t k = 0; k < count; ++k)
        ids[k] = ix[k].id;
    sd_free(ix);
    return SD_OK;
}

sd_status sd_world_get_field(const sd_world *w, sd_field field, const uint64_t *ids, size_t n, double *out,
                             size_t out_len, sd_error *err)
{
    const sd_field_desc *d = NULL;
    size_t *slot;
    sd_status st = sd_fields_args(w, field, ids, n, out, out_len, "sd_world_get_field", &d, err);
    if (st == SD_OK)
        st = sd_fields_resolve(w, ids, n, "sd_world_get_field", &slot, err);
    if (st != SD_OK)
        return st;
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state ps;
        w->solver->read(w, slot[k], &ps); /* the index came from the same solver: always present */
        memcpy(out + k * d->comps, (const char *)&ps + d->offset, d->comps * sizeof(double));
    }
    sd_free(slot);
    return SD_OK;
}

/* Value checks of one particle's values v of field d (nothing written). */
static sd_status sd_fields_check_value(const sd_world *w, const sd_field_desc *d, const double *v, size_t k,
                                       sd_error *err)
{
    for (size_t c = 0; c < d->comps; ++c)
        if (!isfinite(v[c]))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, d->name,
                                "sd_world_set_field: value %zu of particle %zu is not finite", c, k);
    if (d->offset == offsetof(sd_particle_state, quat)) {
        double norm = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
        if (!(fabs(norm - 1.0) <= 1e-6))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, d->name,
                                "sd_world_set_field: the orientation of particle %zu has norm %.17g, expected a "
                                "unit quaternion (within 1e-6)", k, norm);
        if (w->dim2 && (v[1] != 0 || v[2] != 0))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, d->name,
                                "sd_world_set_field: dimension 2: particle %zu may turn about z only "
                                "(orientation (cos(a/2), 0, 0, sin(a/2)))", k);
        return SD_OK;
    }
    if (!w->dim2)
        return SD_OK;
    if (d->offset == offsetof(sd_particle_state, angular_velocity) ? (v[0] != 0 || v[1] != 0) : v[2] != 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, d->name,
                            "sd_world_set_field: dimension 2: particle %zu must stay in the plane (%s)", k,
                            d->offset == offsetof(sd_particle_state, angular_velocity) ? "rotation about z only"
                                                                                       : "z = 0");
    return SD_OK;
}

/* Writes v into particle k of the world's arrays: the setters of the
 * writable queries of SD_PARTICLE_FIELDS (V3 and QUAT; the others are
 * derived or fixed). Returns 0 when the field has no setter. */
static int sd_fields_write(sd_particles *p, size_t off, size_t k, const double *v)
{
#define SD_SET_V3(name, member)                                                                              \
    if (off == offsetof(sd_particle_state, member)) {                                                         \
        p->name[k] = sd_v3((sd_real)v[0], (sd_real)v[1], (sd_real)v[2]);                                     \
        return 1;                                                                                             \
    }
#define SD_SET_QUAT(name, member)                                                                            \
    if (off == offsetof(sd_particle_state, member)) {                                                         \
        p->name[k].w = (sd_real)v[0], p->name[k].x = (sd_real)v[1];                                           \
        p->name[k].y = (sd_real)v[2], p->name[k].z = (sd_real)v[3];                                           \
        return 1;                                                                                             \
    }
#define SD_SET_REAL(name, member)
#define SD_SET_INVERSE(name, member)
#define SD_SET_INT(name, member)
#define SD_SET_U64(name, member)
#define SD_SET_NONE(name, member)
#define SD_X_SET(type, name, unit, doc, def, query, member) SD_SET_##query(name, member)
    SD_PARTICLE_FIELDS(SD_X_SET)
#undef SD_X_SET
#undef SD_SET_V3
#undef SD_SET_QUAT
#undef SD_SET_REAL
#undef SD_SET_INVERSE
#undef SD_SET_INT
#undef SD_SET_U64
#undef SD_SET_NONE
    return 0;
}

sd_status sd_world_set_field(sd_world *w, sd_field field, const uint64_t *ids, size_t n, const double *values,
                             size_t values_len, sd_error *err)
{
    const sd_field_desc *d = NULL;
    sd_status st = sd_fields_args(w, field, ids, n, values, values_len, "sd_world_set_field", &d, err);
    if (st != SD_OK)
        return st;
    if (!d->writable)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, d->name,
                            "sd_world_set_field: field '%s' is read-only (writable: position, velocity, "
                            "angular_velocity, orientation)", d->name);
    if (w->solver != &sd_solver_cells)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, d->name,
                            "sd_world_set_field: the %s solver's particles cannot be set (cells solver only)",
                            w->solver->name);
    for (size_t k = 0; k < n; ++k)
        if ((st = sd_fields_check_value(w, d, values + k * d->comps, k, err)) != SD_OK)
            return st;
    size_t *slot;
    if ((st = sd_fields_resolve(w, ids, n, "sd_world_set_field", &slot, err)) != SD_OK)
        return st;
    for (size_t k = 0; k < n; ++k)
        if (!sd_fields_write(&w->p, d->offset, slot[k], values + k * d->comps)) {
            sd_free(slot); /* only before the first write: every writable field has a setter */
            return sd_error_set(err, SD_ERR_INTERNAL, "", 0, d->name,
                                "sd_world_set_field: field '%s' has no setter in SD_PARTICLE_FIELDS", d->name);
        }
    sd_free(slot);
    /* new pair lists (and periodic images) at the next step: a particle
     * may have moved by more than the skin */
    if (n > 0)
        w->dirty = 1;
    return SD_OK;
}
