/* scene_gen.c — the particle generators of a scene (lattice, random, list,
 * csv) and the cell grid that finds overlapping spheres. A body of a shape
 * takes part as its bounding sphere (the shape's bounding radius about its
 * centre of mass), so bodies start out of contact whatever their
 * orientation; random orientations are uniform over all rotations
 * (Shoemake, "Uniform random rotations", Graphics Gems III, 1992).
 *
 * Invariant: the spheres depend only on the scene: each generator draws
 * from its own xoshiro stream seeded from (simulation.seed, generator
 * index), so the same scene gives the same spheres bit for bit, and editing
 * one generator does not change the spheres of another. Overlap searches
 * use a hashed cell grid with cells at least one largest diameter wide, so
 * they cost O(N) for spheres of similar size, never O(N^2).
 */
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "core/rng.h"
#include "io/scene.h"

/* ---- hashed cell grid --------------------------------------------------- */

#define SD_GEN_HASH_NONE ((size_t)-1)

typedef struct sd_gen_hash {
    double cell;     /* m, cell edge >= the largest diameter */
    size_t mask;     /* bucket count - 1 (a power of two) */
    size_t *head;    /* bucket -> last sphere inserted, or SD_GEN_HASH_NONE */
    size_t *next;    /* sphere -> previous sphere in its bucket */
} sd_gen_hash;

static int sd_gen_hash_init(sd_gen_hash *g, size_t capacity, double cell)
{
    size_t nb = 1024;
    while (nb < 2 * capacity)
        nb *= 2;
    g->cell = cell;
    g->mask = nb - 1;
    g->head = sd_malloc(nb * sizeof *g->head);
    g->next = sd_malloc((capacity ? capacity : 1) * sizeof *g->next);
    if (!g->head || !g->next) {
        sd_free(g->head);
        sd_free(g->next);
        return 0;
    }
    for (size_t i = 0; i < nb; ++i)
        g->head[i] = SD_GEN_HASH_NONE;
    return 1;
}

static void sd_gen_hash_free(sd_gen_hash *g)
{
    sd_free(g->head);
    sd_free(g->next);
}

/* Cell coordinate of x, clamped so far-away spheres cannot overflow. */
static int64_t sd_gen_hash_coord(const sd_gen_hash *g, double x)
{
    double c = floor(x / g->cell);
    if (!(c > -4.0e18))
        c = -4.0e18;
    if (c > 4.0e18)
        c = 4.0e18;
    return (int64_t)c;
}

/* Distinct cells may share a bucket: queries check true distances, so a
 * collision only costs time. */
static size_t sd_gen_hash_bucket(const sd_gen_hash *g, int64_t ix, int64_t iy, int64_t iz)
{
    uint64_t h = (uint64_t)ix * 0x9E3779B97F4A7C15ull;
    h ^= (uint64_t)iy * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= (uint64_t)iz * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    h ^= h >> 29;
    return (size_t)(h & g->mask);
}

static void sd_gen_hash_insert(sd_gen_hash *g, size_t i, sd_v3d p)
{
    size_t b = sd_gen_hash_bucket(g, sd_gen_hash_coord(g, p.x), sd_gen_hash_coord(g, p.y), sd_gen_hash_coord(g, p.z));
    g->next[i] = g->head[b];
    g->head[b] = i;
}

/* Smallest index of an inserted sphere that overlaps sphere q = (p, r) by
 * more than tol x the smaller radius and that accept (if any) keeps, or
 * SD_GEN_HASH_NONE. */
static size_t sd_gen_hash_first_overlap(const sd_gen_hash *g, const sd_sphere_def *defs, sd_v3d p, double r,
                                    double tol, int (*accept)(void *, size_t, size_t), void *ctx, size_t q)
{
    int64_t cx = sd_gen_hash_coord(g, p.x), cy = sd_gen_hash_coord(g, p.y), cz = sd_gen_hash_coord(g, p.z);
    size_t best = SD_GEN_HASH_NONE;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                size_t b = sd_gen_hash_bucket(g, cx + dx, cy + dy, cz + dz);
                for (size_t k = g->head[b]; k != SD_GEN_HASH_NONE; k = g->next[k]) {
                    if (k >= best)
                        continue;
                    double ex = defs[k].position.x - p.x, ey = defs[k].position.y - p.y,
                           ez = defs[k].position.z - p.z;
                    double rs = defs[k].radius + r;
                    double smaller = defs[k].radius < r ? defs[k].radius : r;
                    double d2 = ex * ex + ey * ey + ez * ez;
                    if (d2 >= rs * rs)
                        continue;
                    if (rs - sqrt(d2) > tol * smaller && (!accept || accept(ctx, k, q)))
                        best = k;
                }
            }
    return best;
}

int sd_scene_find_overlap(size_t n, const sd_sphere_def *defs, double tol, size_t *oi, size_t *oj)
{
    return sd_scene_find_overlap_if(n, defs, tol, NULL, NULL, oi, oj);
}

int sd_scene_find_overlap_if(size_t n, const sd_sphere_def *defs, double tol,
                             int (*accept)(void *ctx, size_t i, size_t j), void *ctx, size_t *oi, size_t *oj)
{
    double rmax = 0.0;
    for (size_t k = 0; k < n; ++k)
        if (defs[k].radius > rmax)
            rmax = defs[k].radius;
    if (n < 2 || !(rmax > 0.0))
        return 0;
    sd_gen_hash g;
    if (!sd_gen_hash_init(&g, n, 2.0 * rmax))
        return -1;
    int found = 0;
    for (size_t j = 0; j < n && !found; ++j) {
        size_t i = sd_gen_hash_first_overlap(&g, defs, defs[j].position, defs[j].radius, tol, accept, ctx, j);
        if (i != SD_GEN_HASH_NONE) {
            *oi = i;
            *oj = j;
            found = 1;
        }
        sd_gen_hash_insert(&g, j, defs[j].position);
    }
    sd_gen_hash_free(&g);
    return found;
}

/* ---- generators --------------------------------------------------------- */

/* One stream per generator, so generators do not shift each other's draws. */
static sd_rng sd_gen_rng(uint64_t seed, size_t g)
{
    uint64_t x = seed ^ (0xD1B54A32D192ED03ull * (uint64_t)(g + 1));
    return sd_rng_seed(sd_rng_splitmix(&x));
}

static double sd_gen_radius(sd_rng *rng, const sd_scene_generator *g)
{
    /* Always one draw, so the stream does not depend on min == max. */
    return sd_rng_range(rng, g->radius_min, g->radius_max);
}

static void sd_gen_jitter(sd_rng *rng, const sd_scene_generator *g, sd_sphere_def *d, int planar)
{
    if (g->velocity_jitter > 0.0) {
        double j = g->velocity_jitter;
        d->velocity.x += sd_rng_range(rng, -j, j);
        d->velocity.y += sd_rng_range(rng, -j, j);
        double jz = sd_rng_range(rng, -j, j); /* always drawn: the same stream in 2D */
        if (!planar)
            d->velocity.z += jz;
    }
}

/* Orientation of a shaped body. Random: Shoemake's method, a unit
 * quaternion uniform on the 3-sphere (so a rotation uniform in SO(3)) from
 * three uniforms u1, u2, u3:
 *   q = (sqrt(u1) cos 2 pi u3, sqrt(1-u1) sin 2 pi u2, sqrt(1-u1) cos 2 pi u2, sqrt(u1) sin 2 pi u3).
 * Only shaped bodies draw, so scenes of spheres keep their streams. */
static void sd_gen_orient(sd_rng *rng, sd_scene_orient mode, const double fixed[4], double q[4], int planar)
{
    const double two_pi = 6.28318530717958647692;
    if (mode == SD_ORIENT_RANDOM && planar) {
        /* dimension 2: a uniform angle about z */
        double a = two_pi * sd_rng_uniform(rng);
        q[0] = cos(0.5 * a);
        q[1] = q[2] = 0.0;
        q[3] = sin(0.5 * a);
    } else if (mode == SD_ORIENT_RANDOM) {
        double u1 = sd_rng_uniform(rng), u2 = sd_rng_uniform(rng), u3 = sd_rng_uniform(rng);
        double a = sqrt(1.0 - u1), b = sqrt(u1);
        q[0] = b * cos(two_pi * u3);
        q[1] = a * sin(two_pi * u2);
        q[2] = a * cos(two_pi * u2);
        q[3] = b * sin(two_pi * u3);
    } else if (mode == SD_ORIENT_FIXED) {
        memcpy(q, fixed, 4 * sizeof *q);
    } else {
        q[0] = 1.0;
        q[1] = q[2] = q[3] = 0.0;
    }
}

static size_t sd_gen_count(const sd_scene_generator *g)
{
    switch (g->kind) {
    case SD_GEN_LATTICE: return (size_t)g->count[0] * (size_t)g->count[1] * (size_t)g->count[2];
    case SD_GEN_RANDOM: return (size_t)g->number;
    case SD_GEN_LIST:
    case SD_GEN_CSV: return g->list_count;
    }
    return 0;
}

/* Random sequential addition: each sphere draws its radius once, then
 * positions until one overlaps none of the spheres placed before it, by
 * this generator or by the generators before it (all[0 .. at), which
 * share the hash: two generators in one region must not stack their
 * particles on each other). The attempt budget bounds the time when the
 * box is too full to finish. */
static sd_status sd_gen_random(const sd_scene *s, size_t gi, double bound, sd_rng *rng, sd_sphere_def *all,
                               size_t at, double (*quat)[4], sd_error *err)
{
    const sd_scene_generator *g = &s->generators[gi];
    size_t n = (size_t)g->number;
    sd_sphere_def *defs = all + at;
    double rmax = g->shape >= 0 ? bound : g->radius_max;
    for (size_t k = 0; k < at; ++k)
        if (all[k].radius > rmax)
            rmax = all[k].radius;
    sd_gen_hash grid;
    /* Hashed cells one largest diameter wide: memory follows n, not the box. */
    if (!sd_gen_hash_init(&grid, at + n, 2.0 * rmax))
        return sd_error_set(err, SD_ERR_MEMORY, s->path, g->line, "", "out of memory");
    for (size_t k = 0; k < at; ++k)
        sd_gen_hash_insert(&grid, k, all[k].position);
    const double budget = 100.0 * (double)n + 100000.0;
    double attempts = 0.0;
    size_t placed = 0;
    while (placed < n && attempts < budget) {
        sd_sphere_def *d = &defs[placed];
        double r = sd_gen_radius(rng, g);
        if (g->shape >= 0)
            r = bound; /* the draw above is kept: one per particle, as for spheres */
        int ok = 0;
        while (!ok && attempts < budget) {
            attempts += 1.0;
            sd_v3d p = {sd_rng_range(rng, g->box_lo.x + r, g->box_hi.x - r),
                        sd_rng_range(rng, g->box_lo.y + r, g->box_hi.y - r),
                        sd_rng_range(rng, g->box_lo.z + r, g->box_hi.z - r)};
            if (s->world.dimension == 2)
                p.z = 0.0; /* the planar mode: z range ignored (one draw kept for the stream) */
            /* Zero tolerance: generated spheres may touch, never overlap. */
            if (sd_gen_hash_first_overlap(&grid, all, p, r, 0.0, NULL, NULL, 0) == SD_GEN_HASH_NONE) {
                memset(d, 0, sizeof *d);
                d->position = p;
                d->radius = r;
                ok = 1;
            }
        }
        if (!ok)
            break;
        d->velocity = g->velocity;
        d->angular_velocity = g->angular_velocity;
        d->material = g->material;
        if (g->shape >= 0)
            sd_gen_orient(rng, g->orient, g->quat, quat[placed], s->world.dimension == 2);
        sd_gen_jitter(rng, g, d, s->world.dimension == 2);
        sd_gen_hash_insert(&grid, at + placed, d->position);
        ++placed;
    }
    sd_gen_hash_free(&grid);
    if (placed < n) {
        double vol = 0.0;
        for (size_t k = 0; k < placed; ++k)
            vol += 4.0 / 3.0 * 3.14159265358979323846 * defs[k].radius * defs[k].radius *
                   defs[k].radius;
        double box = (g->box_hi.x - g->box_lo.x) * (g->box_hi.y - g->box_lo.y) *
                     (g->box_hi.z - g->box_lo.z);
        char key[64];
        snprintf(key, sizeof key, "particles[%zu].number", gi);
        return sd_error_set(err, SD_ERR_INPUT, s->path, g->line, key,
                            "placed only %zu of %zu %s in the box after %.0f attempts (they "
                            "fill %.0f%% of it; random placement stops near 30%%): use a larger "
                            "box or fewer particles",
                            placed, n, g->shape >= 0 ? "bounding spheres" : "spheres", attempts,
                            100.0 * vol / box);
    }
    return SD_OK;
}

/* The generator's shape bound is checked here, where it is known: a lattice
 * must space bounding spheres apart, a random box must hold one. */
static sd_status sd_gen_check_bound(const sd_scene *s, size_t gi, double bound, sd_error *err)
{
    const sd_scene_generator *g = &s->generators[gi];
    const char *name = s->shapes[g->shape].name;
    char key[64];
    if (g->kind == SD_GEN_LATTICE) {
        const double sp[3] = {g->spacing.x, g->spacing.y, g->spacing.z};
        for (int a = 0; a < 3; ++a)
            if (sp[a] < 2.0 * bound) {
                snprintf(key, sizeof key, "particles[%zu].spacing", gi);
                return sd_error_set(err, SD_ERR_INPUT, s->path, g->spacing_line, key,
                                    "expected a spacing >= 2 x the bounding radius of shape '%s' "
                                    "(%g m), got %g along %c: the bodies could overlap",
                                    name, 2.0 * bound, sp[a], 'x' + a);
            }
    } else if (g->kind == SD_GEN_RANDOM) {
        const double ext[3] = {g->box_hi.x - g->box_lo.x, g->box_hi.y - g->box_lo.y,
                               g->box_hi.z - g->box_lo.z};
        for (int a = 0; a < 3; ++a)
            if (ext[a] < 2.0 * bound) {
                snprintf(key, sizeof key, "particles[%zu].box", gi);
                return sd_error_set(err, SD_ERR_INPUT, s->path, g->box_line, key,
                                    "the box is %g m wide along %c, less than the bounding "
                                    "diameter of shape '%s' (%g m)",
                                    ext[a], 'x' + a, name, 2.0 * bound);
            }
    }
    return SD_OK;
}

static int sd_gen_shaped(const sd_scene_generator *g)
{
    if (g->shape >= 0)
        return 1;
    /* list and csv: a shape per entry */
    if ((g->kind == SD_GEN_LIST || g->kind == SD_GEN_CSV) && g->list_shape)
        for (size_t k = 0; k < g->list_count; ++k)
            if (g->list_shape[k] >= 0)
                return 1;
    return 0;
}

sd_status sd_scene_generate(const sd_scene *s, const double *shape_bound, sd_scene_spheres *out,
                            sd_error *err)
{
    memset(out, 0, sizeof *out);
    size_t total = 0;
    for (size_t gi = 0; gi < s->generator_count; ++gi) {
        total += sd_gen_count(&s->generators[gi]);
        if (!shape_bound && sd_gen_shaped(&s->generators[gi]))
            return sd_error_set(err, SD_ERR_INTERNAL, s->path, s->generators[gi].line, "",
                                "sd_scene_generate: bounding radii of the shapes not given");
    }
    size_t cap = total ? total : 1;
    out->defs = sd_calloc(cap, sizeof *out->defs);
    out->gen = sd_malloc(cap * sizeof *out->gen);
    out->entry = sd_malloc(cap * sizeof *out->entry);
    out->line = sd_malloc(cap * sizeof *out->line);
    out->shape = sd_malloc(cap * sizeof *out->shape);
    out->quat = sd_malloc(cap * sizeof *out->quat);
    if (!out->defs || !out->gen || !out->entry || !out->line || !out->shape || !out->quat) {
        sd_scene_spheres_free(out);
        return sd_error_set(err, SD_ERR_MEMORY, s->path, 0, "", "out of memory (%zu spheres)",
                            total);
    }
    size_t at = 0;
    for (size_t gi = 0; gi < s->generator_count; ++gi) {
        const sd_scene_generator *g = &s->generators[gi];
        sd_rng rng = sd_gen_rng(s->world.seed, gi);
        size_t n = sd_gen_count(g);
        sd_sphere_def *defs = out->defs + at;
        double(*quat)[4] = out->quat + at;
        double bound = g->shape >= 0 ? shape_bound[g->shape] : 0.0;
        /* list and csv entries carry their own shape (the generator's is their default) */
        const int *entry_shape = (g->kind == SD_GEN_LIST || g->kind == SD_GEN_CSV) ? g->list_shape : NULL;
        for (size_t k = 0; k < n; ++k) {
            out->shape[at + k] = entry_shape ? entry_shape[k] : g->shape;
            sd_gen_orient(&rng, SD_ORIENT_IDENTITY, NULL, quat[k], s->world.dimension == 2); /* no draw */
        }
        if (g->shape >= 0 && g->kind != SD_GEN_LIST && g->kind != SD_GEN_CSV) {
            sd_status st = sd_gen_check_bound(s, gi, bound, err);
            if (st != SD_OK) {
                sd_scene_spheres_free(out);
                return st;
            }
        }
        switch (g->kind) {
        case SD_GEN_LATTICE: {
            size_t k = 0;
            /* x varies fastest, then y, then z: layers from the bottom up. */
            for (int iz = 0; iz < g->count[2]; ++iz)
                for (int iy = 0; iy < g->count[1]; ++iy)
                    for (int ix = 0; ix < g->count[0]; ++ix, ++k) {
                        sd_sphere_def *d = &defs[k];
                        d->position = (sd_v3d){g->origin.x + ix * g->spacing.x,
                                               g->origin.y + iy * g->spacing.y,
                                               g->origin.z + iz * g->spacing.z};
                        d->radius = sd_gen_radius(&rng, g);
                        d->velocity = g->velocity;
                        d->angular_velocity = g->angular_velocity;
                        d->material = g->material;
                        if (g->shape >= 0) {
                            d->radius = bound;
                            sd_gen_orient(&rng, g->orient, g->quat, quat[k], s->world.dimension == 2);
                        }
                        sd_gen_jitter(&rng, g, d, s->world.dimension == 2);
                    }
            break;
        }
        case SD_GEN_RANDOM: {
            sd_status st = sd_gen_random(s, gi, bound, &rng, out->defs, at, quat, err);
            if (st != SD_OK) {
                sd_scene_spheres_free(out);
                return st;
            }
            break;
        }
        case SD_GEN_LIST:
        case SD_GEN_CSV:
            for (size_t k = 0; k < n; ++k) {
                defs[k] = g->list[k];
                if (entry_shape && entry_shape[k] >= 0) {
                    defs[k].radius = shape_bound[g->list_shape[k]];
                    sd_gen_orient(&rng, g->list_orient[k], g->list_quat[k], quat[k], s->world.dimension == 2);
                }
                sd_gen_jitter(&rng, g, &defs[k], s->world.dimension == 2);
            }
            break;
        }
        for (size_t k = 0; k < n; ++k) {
            out->gen[at + k] = (int)gi;
            int listed = g->kind == SD_GEN_LIST || g->kind == SD_GEN_CSV;
            out->entry[at + k] = listed ? (int)k : -1;
            out->line[at + k] = listed ? g->list_lines[k] : g->line;
        }
        at += n;
    }
    out->count = at;
    return SD_OK;
}

void sd_scene_spheres_free(sd_scene_spheres *sp)
{
    if (!sp)
        return;
    sd_free(sp->defs);
    sd_free(sp->gen);
    sd_free(sp->entry);
    sd_free(sp->line);
    sd_free(sp->shape);
    sd_free(sp->quat);
    memset(sp, 0, sizeof *sp);
}
