/* scene_build.c — turns a loaded scene into a world, through the public
 * API (shapedem.h: materials, shapes, particles, walls, pour and outlet,
 * whichever solver runs), and checks what can only be checked once the
 * particles exist: overlaps at the start, particles outside walls, and a
 * time step above the stability limit. Beyond the public API it reads only
 * the kind lists (shape/shape.h, shape/shape2d.h: the scene's type names)
 * and the start-overlap measure (world/start_overlap.h), never a solver.
 *
 * Invariant: sd_scene_build returns either a complete world that passed
 * every check, or an error naming the scene file (or the CSV file a sphere
 * came from), the line and the key, and no world. Scene material i is world
 * material i, scene shape i is world shape i, and particle ids follow
 * generation order. Overlaps at the start are measured with the true
 * shapes (world/start_overlap.h; planar shapes by their bounding circle),
 * walls with the bounding sphere.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/scene.h"
#include "io/scene_from.h"
#include "io/scene_process.h"
#include "io/scene_keys.h"
#include "shape/shape.h"
#include "shape/shape2d.h"
#include "world/start_overlap.h"

#include <shapedem/process.h>

/* Scene type names in sd_shape_kind order: what sd_shape_desc.kind takes. */
static const char *const sd_shape_type_names[] = {
#define SD_X_NAME(e, name, doc) name,
    SD_SHAPE_KINDS(SD_X_NAME)
#undef SD_X_NAME
};

/* Overlap at the start allowed, as a fraction of the smaller size (a
 * sphere's radius, half a shape's smallest outer dimension): what a packing
 * written from a settled run carries in its resting contacts (well-resolved
 * DEM keeps overlaps below about 1 % of the radius), so that such a
 * packing loads again; more is a placement mistake. */
#define SD_SCENE_OVERLAP_TOL 1e-2
/* How far a particle may cross a closed wall at the start, as a fraction
 * of its size: the same resting-contact allowance as between particles
 * (a plane: how far its centre may lie behind it, x radius). */
#define SD_SCENE_WALL_TOL 1e-2

/* An error from the world API, completed with where in the scene it comes from. */
static sd_status sd_where(sd_error *err, sd_status st, const sd_scene *s, int line, const char *key)
{
    if (!err)
        return st;
    err->code = st;
    if (!err->file[0])
        snprintf(err->file, sizeof err->file, "%.*s", (int)sizeof err->file - 1, s->path);
    if (err->line <= 0)
        err->line = line;
    if (!err->key[0])
        snprintf(err->key, sizeof err->key, "%.*s", (int)sizeof err->key - 1, key);
    return st;
}

/* Names a sphere by where it was given: file, line and key. */
typedef struct sd_origin {
    const char *file;
    int line;
    char key[64];
} sd_origin;

/* A csv generator that reads a checkpoint of another run (io/scene_from.h):
 * its particles are named by the scene's line of file:. */
static int sd_gen_from_checkpoint(const sd_scene_generator *g)
{
    return g->kind == SD_GEN_CSV && sd_from_is_checkpoint(g->file);
}

static sd_origin sd_sphere_origin(const sd_scene *s, const sd_scene_spheres *sp, size_t k)
{
    sd_origin o;
    const sd_scene_generator *g = &s->generators[sp->gen[k]];
    o.file = g->kind == SD_GEN_CSV && !sd_gen_from_checkpoint(g) ? g->file : s->path;
    o.line = sp->line[k];
    if (g->kind == SD_GEN_LIST)
        snprintf(o.key, sizeof o.key, "particles[%d].spheres[%d]", sp->gen[k], sp->entry[k]);
    else
        snprintf(o.key, sizeof o.key, "particles[%d]", sp->gen[k]);
    return o;
}

/* "sphere 3 at (x, y, z) r 0.001" or "body 3 of shape 'cube' at (x, y, z),
 * bounding radius 0.001", for messages. */
static const char *sd_describe(const sd_scene *s, const sd_scene_spheres *sp, size_t k, char *buf,
                               size_t size)
{
    const sd_sphere_def *d = &sp->defs[k];
    if (sp->shape[k] >= 0)
        snprintf(buf, size, "body %zu of shape '%s' at (%g, %g, %g), bounding radius %g", k,
                 s->shapes[sp->shape[k]].name, d->position.x, d->position.y, d->position.z,
                 d->radius);
    else
        snprintf(buf, size, "sphere %zu at (%g, %g, %g) r %g", k, d->position.x, d->position.y,
                 d->position.z, d->radius);
    return buf;
}

/* The true shapes' test of a pair whose bounding spheres overlap
 * (world/start_overlap.h); planar shapes keep their bounding circles. */
typedef struct sd_overlap_ctx {
    const sd_scene *s;
    const sd_scene_spheres *sp;
    const sd_world *w;
    const unsigned char *from; /* per generator: 1 for a checkpoint of another run */
    double depth, size; /* m, of the last pair accepted */
} sd_overlap_ctx;

static int sd_overlap_accept(void *ctx, size_t i, size_t j)
{
    sd_overlap_ctx *c = ctx;
    const sd_scene_spheres *sp = c->sp;
    const sd_sphere_def *a = &sp->defs[i], *b = &sp->defs[j];
    double depth, size;
    /* two particles of one checkpoint keep the contacts they had there (a
     * settled bed's overlaps are its resting contacts, whatever their depth;
     * the run's overlap guard still watches them) */
    if (sp->gen[i] == sp->gen[j] && c->from[sp->gen[i]])
        return 0;
    if (c->s->world.dimension == 2 && (sp->shape[i] >= 0 || sp->shape[j] >= 0)) {
        double dx = a->position.x - b->position.x, dy = a->position.y - b->position.y;
        depth = a->radius + b->radius - sqrt(dx * dx + dy * dy);
        size = a->radius < b->radius ? a->radius : b->radius;
    } else {
        sd_start_particle pa = {a->position, {1, 0, 0, 0}, a->radius, sp->shape[i], a->material};
        sd_start_particle pb = {b->position, {1, 0, 0, 0}, b->radius, sp->shape[j], b->material};
        memcpy(pa.q, sp->quat[i], sizeof pa.q);
        memcpy(pb.q, sp->quat[j], sizeof pb.q);
        depth = sd_start_overlap(c->w, &pa, &pb, &size);
    }
    if (!(depth > SD_SCENE_OVERLAP_TOL * size))
        return 0;
    c->depth = depth;
    c->size = size;
    return 1;
}

static sd_status sd_check_overlaps(const sd_scene *s, const sd_scene_spheres *sp, const sd_world *w, sd_error *err)
{
    size_t i, j;
    unsigned char *from = sd_calloc(s->generator_count ? s->generator_count : 1, 1);
    if (!from)
        return sd_error_set(err, SD_ERR_MEMORY, s->path, 0, "", "out of memory");
    for (size_t g = 0; g < s->generator_count; ++g)
        from[g] = (unsigned char)sd_gen_from_checkpoint(&s->generators[g]);
    sd_overlap_ctx ctx = {s, sp, w, from, 0.0, 0.0};
    /* candidates: bounding spheres that overlap at all; the true shapes decide */
    int found = sd_scene_find_overlap_if(sp->count, sp->defs, 0.0, sd_overlap_accept, &ctx, &i, &j);
    sd_free(from);
    if (found < 0)
        return sd_error_set(err, SD_ERR_MEMORY, s->path, 0, "", "out of memory");
    if (!found)
        return SD_OK;
    int shaped = sp->shape[i] >= 0 || sp->shape[j] >= 0;
    sd_origin oa = sd_sphere_origin(s, sp, i), ob = sd_sphere_origin(s, sp, j);
    char da[160], db[160];
    return sd_error_set(err, SD_ERR_INPUT, ob.file, ob.line, ob.key,
                        "particles overlap at the start by %.3g m (%.3g%% of the smaller %s; at most %g%% is "
                        "taken): %s and %s from %s (line %d)",
                        ctx.depth, 100.0 * ctx.depth / ctx.size,
                        shaped ? "size, a radius or half a shape's smallest outer dimension" : "radius",
                        100.0 * SD_SCENE_OVERLAP_TOL, sd_describe(s, sp, j, db, sizeof db),
                        sd_describe(s, sp, i, da, sizeof da), oa.key, oa.line);
}

/* How far particle d crosses wall w (m, > 0 means outside), and which
 * side; [lo, hi] is the particle's extent along each axis (its true shape). */
static double sd_wall_excess(const sd_scene_wall *w, const sd_sphere_def *d, const double xlo[3],
                             const double xhi[3], const char **side, int planar)
{
    if (w->kind == 0) {
        *side = "plane";
        /* A plane keeps centres on the side its normal points to. */
        return -((d->position.x - w->point.x) * w->normal.x +
                 (d->position.y - w->point.y) * w->normal.y +
                 (d->position.z - w->point.z) * w->normal.z);
    }
    if (w->kind == 3) {
        /* a drum holds centres inside its mantle and between its closed caps */
        const double r[3] = {d->position.x - w->point.x, d->position.y - w->point.y, d->position.z - w->point.z};
        const double n[3] = {w->normal.x, w->normal.y, w->normal.z};
        double s = r[0] * n[0] + r[1] * n[1] + r[2] * n[2], q = 0, half = 0.5 * w->drum_length;
        for (int a = 0; a < 3; ++a)
            q += (r[a] - s * n[a]) * (r[a] - s * n[a]);
        double worst = sqrt(q) - w->drum_radius;
        *side = "mantle";
        if (!w->drum_open_hi && s - half > worst) {
            worst = s - half;
            *side = "high cap";
        }
        if (!w->drum_open_lo && -s - half > worst) {
            worst = -s - half;
            *side = "low cap";
        }
        return worst;
    }
    static const char *const faces[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
    const double lo[3] = {w->lo.x, w->lo.y, w->lo.z}, hi[3] = {w->hi.x, w->hi.y, w->hi.z};
    double worst = -HUGE_VAL;
    *side = "";
    for (int a = 0; a < (planar ? 2 : 3); ++a) { /* the planar mode has no z faces */
        /* Open faces do not hold anything in: spheres may start beyond them
         * (poured into an open-top box from above). */
        if (!(w->open_faces & (1u << (2 * a))) && lo[a] - xlo[a] > worst) {
            worst = lo[a] - xlo[a];
            *side = faces[2 * a];
        }
        if (!(w->open_faces & (1u << (2 * a + 1))) && xhi[a] - hi[a] > worst) {
            worst = xhi[a] - hi[a];
            *side = faces[2 * a + 1];
        }
    }
    return worst;
}

static sd_status sd_check_walls(const sd_scene *s, const sd_scene_spheres *sp, const sd_world *world,
                                sd_error *err)
{
    int boxes = 0;
    for (size_t wi = 0; wi < s->wall_count; ++wi)
        boxes |= s->walls[wi].kind == 1;
    for (size_t k = 0; k < sp->count; ++k) {
        const sd_sphere_def *d = &sp->defs[k];
        /* the extent along the axes: the true shape's support points in 3D
         * (a packing resting on a box floor loads again), the bounding
         * circle in the planar mode */
        const double c[3] = {d->position.x, d->position.y, d->position.z};
        double xlo[3] = {0, 0, 0}, xhi[3] = {0, 0, 0}, size = d->radius;
        sd_start_particle p = {d->position, {1, 0, 0, 0}, d->radius, sp->shape[k], d->material};
        int shaped = sp->shape[k] >= 0 && s->world.dimension != 2;
        if (shaped) {
            memcpy(p.q, sp->quat[k], sizeof p.q);
            size = sd_start_size(world, &p);
        }
        for (int a = 0; a < 3 && boxes; ++a) {
            sd_v3d e = {a == 0, a == 1, a == 2}, me = {-(a == 0), -(a == 1), -(a == 2)};
            xlo[a] = shaped ? -sd_start_reach(world, &p, me) : c[a] - d->radius;
            xhi[a] = shaped ? sd_start_reach(world, &p, e) : c[a] + d->radius;
        }
        for (size_t wi = 0; wi < s->wall_count; ++wi) {
            const sd_scene_wall *w = &s->walls[wi];
            const char *side;
            if (w->kind == 2) /* a mesh: which side a particle starts on is not checked */
                continue;
            double excess = sd_wall_excess(w, d, xlo, xhi, &side, s->world.dimension == 2);
            if (!(excess > SD_SCENE_WALL_TOL * size))
                continue;
            sd_origin o = sd_sphere_origin(s, sp, k);
            char dk[160];
            sd_describe(s, sp, k, dk, sizeof dk);
            if (w->kind == 0)
                return sd_error_set(err, SD_ERR_INPUT, o.file, o.line, o.key,
                                    "particle outside the walls: %s has its centre %.3g m behind "
                                    "plane '%s' (walls[%zu], line %d)",
                                    dk, excess, w->name, wi, w->line);
            if (w->kind == 3)
                return sd_error_set(err, SD_ERR_INPUT, o.file, o.line, o.key,
                                    "particle outside the walls: %s has its centre %.3g m beyond the %s of "
                                    "drum '%s' (walls[%zu], line %d)",
                                    dk, excess, side, w->name, wi, w->line);
            return sd_error_set(err, SD_ERR_INPUT, o.file, o.line, o.key,
                                "particle outside the walls: %s crosses the closed %s face of "
                                "box '%s' (walls[%zu], line %d) by %.3g m",
                                dk, side, w->name, wi, w->line, excess);
        }
    }
    return SD_OK;
}

/* The planar mode: every particle in the plane z = 0, moving in it. */
static sd_status sd_check_planar(const sd_scene *s, const sd_scene_spheres *sp, sd_error *err)
{
    if (s->world.dimension != 2)
        return SD_OK;
    for (size_t k = 0; k < sp->count; ++k) {
        const sd_sphere_def *d = &sp->defs[k];
        if (d->position.z == 0 && d->velocity.z == 0 && d->angular_velocity.x == 0 && d->angular_velocity.y == 0)
            continue;
        sd_origin o = sd_sphere_origin(s, sp, k);
        char dk[160];
        sd_describe(s, sp, k, dk, sizeof dk);
        return sd_error_set(err, SD_ERR_INPUT, o.file, o.line, o.key,
                            "dimension 2: %s must lie in the plane z = 0 with velocity z = 0 and angular "
                            "velocity about z only",
                            dk);
    }
    return SD_OK;
}

/* |v| without overflow for components up to the largest double. */
static double sd_norm3(sd_v3d v)
{
    double m = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
    if (!(m > 0.0) || !isfinite(m))
        return m;
    double x = v.x / m, y = v.y / m, z = v.z / m;
    return m * sqrt(x * x + y * y + z * z);
}

/* Start values no run survives (probe F8), refused with the key they came
 * from instead of a run that ends in NaN or inf with exit 0:
 *  - a position so far from the origin that doubles there resolve less
 *    than 1e-3 of the radius (contact depths are differences of
 *    positions), which also keeps m g z finite;
 *  - a speed that carries a particle more than its radius in one step, or
 *    a spin that turns its surface that far (|w| dt > 1 rad): contacts
 *    are then jumped over, whatever the time step's stability limit says;
 *  - a mass that is 0, inf or NaN (a density at the ends of the double
 *    range), and kinetic or potential energies that overflow;
 *  - gravity that moves a particle from rest more than the smallest
 *    radius in one step (g dt^2 > r).
 * Particle k of sp is particle k of w (added in order, before prepare). */
static sd_status sd_check_state(const sd_scene *s, const sd_scene_spheres *sp, const sd_world *w, sd_error *err)
{
    const double dt = s->world.dt;
    const sd_v3d g = s->world.gravity;
    double rmin = s->pour.given ? s->pour.radius : HUGE_VAL;
    char key[112], dk[160];
    for (size_t k = 0; k < sp->count; ++k) {
        const sd_sphere_def *d = &sp->defs[k];
        const sd_v3d x = d->position, v = d->velocity, av = d->angular_velocity;
        double r = d->radius;
        rmin = r < rmin ? r : rmin;
        double far = fmax(fabs(x.x), fmax(fabs(x.y), fabs(x.z)));
        double speed = sd_norm3(v), spin = sd_norm3(av);
        sd_particle_state p;
        double m = sd_world_get_particle(w, k, &p) == SD_OK ? p.mass : (double)NAN;
        double ke = 0.5 * m * (v.x * v.x + v.y * v.y + v.z * v.z);
        double pe = -m * (g.x * x.x + g.y * x.y + g.z * x.z);
        const char *field = NULL;
        char why[200];
        if (!(far * DBL_EPSILON <= 1e-3 * r)) {
            field = "position";
            snprintf(why, sizeof why,
                     "is %.3g m from the origin, where doubles resolve only %.3g m, more than 1e-3 of the "
                     "radius (values are SI: m)",
                     far, far * DBL_EPSILON);
        } else if (!(speed * dt <= r)) {
            field = "velocity";
            snprintf(why, sizeof why,
                     "speed %.3g m/s carries it %.3g radii in one step of %g s: contacts would be jumped "
                     "over (speed x dt must stay below the radius; values are SI: m/s)",
                     speed, speed * dt / r, dt);
        } else if (!(spin * dt <= 1.0)) {
            field = "angular_velocity";
            snprintf(why, sizeof why,
                     "spin %.3g rad/s turns it %.3g rad in one step of %g s: at most 1 rad per step "
                     "(values are SI: rad/s)",
                     spin, spin * dt, dt);
        } else if (!(m > 0.0 && isfinite(m))) {
            const sd_scene_material *mat = &s->materials[d->material];
            sd_describe(s, sp, k, dk, sizeof dk);
            snprintf(key, sizeof key, "materials[%d].density", d->material);
            return sd_error_set(err, SD_ERR_INPUT, s->path, mat->line, key,
                                "%g kg/m^3 gives %s a mass of %g kg; a mass must be finite and above 0",
                                mat->def.density, dk, m);
        } else if (!isfinite(ke)) {
            field = "velocity";
            snprintf(why, sizeof why, "gives a kinetic energy that overflows (mass %.3g kg, speed %.3g m/s)", m,
                     speed);
        } else if (!isfinite(pe)) {
            field = "position";
            snprintf(why, sizeof why, "gives a potential energy m g.x that overflows (mass %.3g kg)", m);
        }
        if (!field)
            continue;
        sd_origin o = sd_sphere_origin(s, sp, k);
        snprintf(key, sizeof key, "%s.%s", o.key, field);
        sd_describe(s, sp, k, dk, sizeof dk);
        return sd_error_set(err, SD_ERR_INPUT, o.file, o.line, key, "%s %s", dk, why);
    }
    double gn = sd_norm3(g);
    if (isfinite(rmin) && !(gn * dt * dt <= rmin))
        return sd_error_set(err, SD_ERR_INPUT, s->path, s->simulation_line, "simulation.gravity",
                            "gravity %.3g m/s^2 moves a particle at rest %.3g m in one step of %g s, more than "
                            "the smallest radius %.3g m (g dt^2 must stay below it; values are SI: m/s^2)",
                            gn, gn * dt * dt, dt, rmin);
    return SD_OK;
}

/* Adds the scene's shapes (scene shape i is world shape i) and fills
 * bound[i] with each one's bounding radius. An error from the world keeps
 * its message and gets the entry's line and key. */
/* A planar shape (dimension 2): scale multiplies every length. */
static int sd_build_shape2d(const sd_scene_shape *sh, sd_world *w, sd_error *err)
{
    static const char *const names[] = {
#define SD_X_NAME2(e, name, doc) name,
        SD_SHAPE2D_KINDS(SD_X_NAME2)
#undef SD_X_NAME2
    };
    double c = sh->scale;
    size_t nv = sh->kind2d == SD_SHAPE2D_FOURIER ? 2 * sh->fourier_count : 2 * sh->point_count;
    double *tmp = sd_malloc((nv ? nv : 1) * sizeof *tmp);
    if (!tmp) {
        sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
        return -1;
    }
    sd_shape2d_def d = sd_shape2d_def_default();
    d.kind = names[sh->kind2d];
    d.radius = c * (sh->kind2d == SD_SHAPE2D_CIRCLE ? sh->size.x : sh->rounding);
    d.semi_axes[0] = c * sh->axes[0];
    d.semi_axes[1] = c * sh->axes[1];
    if (sh->kind2d == SD_SHAPE2D_FOURIER) {
        for (size_t k = 0; k < sh->fourier_count; ++k) {
            tmp[k] = c * sh->fourier_a[k];
            tmp[sh->fourier_count + k] = c * sh->fourier_b[k];
        }
        d.fourier_a = tmp;
        d.fourier_b = tmp + sh->fourier_count;
        d.order = (int)sh->fourier_count - 1;
    } else if (sh->point_count) {
        for (size_t k = 0; k < 2 * sh->point_count; ++k)
            tmp[k] = c * sh->points[k];
        d.points = tmp;
        d.point_count = sh->point_count;
    }
    int idx = sd_world_add_shape2d(w, sh->name, &d, err);
    sd_free(tmp);
    return idx;
}

static sd_status sd_build_shapes(const sd_scene *s, sd_world *w, double *bound, sd_error *err)
{
    char key[160];
    for (size_t i = 0; i < s->shape_count; ++i) {
        const sd_scene_shape *sh = &s->shapes[i];
        if (sh->scaled_of < 0)
            continue; /* an element copy: the composite copy after it makes it */
        if (sh->scaled_of > 0) {
            /* a checkpoint's scaled copy (io/scene_from.c): made as the run's
             * insertion made it, the same factor on the same template, so
             * its geometry, mass and inertia are the same bits */
            sd_error_clear(err);
            int idx = sd_world_add_scaled_shape(w, sh->scaled_of - 1, sh->scaled_by, sh->name, err);
            snprintf(key, sizeof key, "particles[%zu].file", sh->entry);
            if (idx < 0) {
                err->key[0] = '\0';
                return sd_where(err, err->code != SD_OK ? err->code : SD_ERR_INPUT, s, sh->line, key);
            }
            sd_shape_info info;
            for (size_t j = i; j + 1 > 0 && (j == i || s->shapes[j].scaled_of < 0); --j) {
                if (idx != (int)i || sd_world_get_shape(w, j, &info) != SD_OK)
                    return sd_error_set(err, SD_ERR_INTERNAL, s->path, sh->line, key,
                                        "the world gave the scaled copy '%s' index %d, expected %zu", sh->name,
                                        idx, i);
                bound[j] = info.bounding_radius;
            }
            continue;
        }
        if (sh->kind2d >= 0) {
            sd_error_clear(err);
            int idx = sd_build_shape2d(sh, w, err);
            if (idx < 0) {
                /* the world names its own field: a key of the entry, or the entry */
                if (err->key[0] && sd_scene_key_find(SD_SEC_SHAPE, err->key))
                    snprintf(key, sizeof key, "shapes[%zu].%.100s", i, err->key);
                else
                    snprintf(key, sizeof key, "shapes[%zu]", i);
                err->key[0] = '\0';
                return sd_where(err, err->code != SD_OK ? err->code : SD_ERR_INPUT, s, sh->line, key);
            }
            snprintf(key, sizeof key, "shapes[%zu]", i);
            sd_shape_info info;
            if (idx != (int)i || sd_world_get_shape(w, i, &info) != SD_OK)
                return sd_error_set(err, SD_ERR_INTERNAL, s->path, sh->line, key,
                                    "the world gave shape index %d, expected %zu", idx, i);
            bound[i] = info.bounding_radius;
            continue;
        }
        int idx;
        sd_error_clear(err);
        if (sh->kind == SD_SHAPE_COMPOSITE) {
            /* its elements are shapes listed before it: scene index = world index */
            sd_composite_desc cd = sd_composite_desc_default();
            cd.elements = sh->elements;
            cd.element_count = sh->element_count;
            cd.lattice = sh->lattice;
            idx = sd_world_add_composite(w, sh->name, &cd, err);
        } else {
            sd_shape_desc d = sd_shape_desc_default();
            d.kind = sd_shape_type_names[sh->kind];
            d.size = sh->size;
            d.rounding = sh->rounding;
            d.margin = sh->margin;
            d.scale = sh->scale;
            d.vertices = sh->vertices;
            d.vertex_count = sh->vertex_count;
            idx = sd_world_add_shape(w, sh->name, &d, err);
        }
        if (idx < 0) {
            /* The world names its own field ("size", "vertices"): a key of the
             * entry (the file's entry: composites' element shapes are extra). */
            if (err->key[0] && sd_scene_key_find(SD_SEC_SHAPE, err->key))
                snprintf(key, sizeof key, "shapes[%zu].%.100s", sh->entry, err->key);
            else
                snprintf(key, sizeof key, "shapes[%zu]", sh->entry);
            err->key[0] = '\0';
            return sd_where(err, err->code != SD_OK ? err->code : SD_ERR_INPUT, s, sh->line, key);
        }
        snprintf(key, sizeof key, "shapes[%zu]", i);
        sd_shape_info info;
        if (idx != (int)i || sd_world_get_shape(w, i, &info) != SD_OK)
            return sd_error_set(err, SD_ERR_INTERNAL, s->path, sh->line, key,
                                "the world gave shape index %d, expected %zu", idx, i);
        bound[i] = info.bounding_radius;
    }
    return SD_OK;
}

/* Adds particles [at, end) of one generator, all spheres or all bodies. */
static sd_status sd_add_run(const sd_scene *s, sd_world *w, const sd_scene_spheres *sp, size_t at,
                            size_t end, sd_body_def *bodies, sd_error *err)
{
    char key[64];
    sd_status st;
    snprintf(key, sizeof key, "particles[%d]", sp->gen[at]);
    if (sp->shape[at] < 0) {
        st = sd_world_add_spheres(w, end - at, sp->defs + at, err);
    } else {
        for (size_t k = at; k < end; ++k) {
            const sd_sphere_def *d = &sp->defs[k];
            sd_body_def *b = &bodies[k - at];
            memset(b, 0, sizeof *b);
            b->position = d->position;
            b->velocity = d->velocity;
            b->angular_velocity = d->angular_velocity;
            memcpy(b->orientation, sp->quat[k], sizeof b->orientation);
            b->shape = sp->shape[k];
            b->material = d->material;
        }
        st = sd_world_add_bodies(w, end - at, bodies, err);
    }
    return st == SD_OK ? SD_OK : sd_where(err, st, s, s->generators[sp->gen[at]].line, key);
}

static sd_status sd_build(const sd_scene *s, sd_world *w, sd_scene_spheres *sp, sd_error *err)
{
    char key[96];
    sd_status st;
    for (size_t i = 0; i < s->material_count; ++i) {
        const sd_scene_material *m = &s->materials[i];
        sd_material_def d = m->def;
        d.name = m->name;
        snprintf(key, sizeof key, "materials[%zu]", i);
        int idx = sd_world_add_material(w, &d, err);
        if (idx < 0)
            return sd_where(err, err->code != SD_OK ? err->code : SD_ERR_INPUT, s, m->line, key);
        if (idx != (int)i)
            return sd_error_set(err, SD_ERR_INTERNAL, s->path, m->line, key,
                                "the world gave material index %d, expected %zu", idx, i);
    }
    for (size_t i = 0; i < s->interaction_count; ++i) {
        const sd_scene_interaction *in = &s->interactions[i];
        snprintf(key, sizeof key, "interactions[%zu]", i);
        if ((st = sd_world_set_interaction(w, in->mat_a, in->mat_b, &in->def, err)) != SD_OK)
            return sd_where(err, st, s, in->line, key);
    }
    for (size_t i = 0; i < s->wall_count; ++i) {
        const sd_scene_wall *wl = &s->walls[i];
        snprintf(key, sizeof key, "walls[%zu]", i);
        int idx;
        if (wl->kind == 2) { /* a mesh: placed at load (io/scene_mesh.c) */
            sd_mesh_def md = sd_mesh_def_default();
            md.vertices = wl->mesh_vertices;
            md.vertex_count = wl->mesh_vertex_count;
            md.triangles = (const uint32_t(*)[3])wl->mesh_triangles;
            md.triangle_count = wl->mesh_triangle_count;
            md.material = wl->material;
            md.weld_tolerance = wl->weld_tolerance;
            md.coplanar_tolerance = wl->coplanar_tolerance;
            md.outside = wl->outside;
            idx = sd_world_add_mesh(w, wl->name, &md, err);
        } else if (wl->kind == 3) { /* the analytic drum (shapedem/process.h) */
            sd_drum_def dd = sd_drum_def_default();
            dd.name = wl->name;
            dd.center = wl->point;
            dd.axis = wl->normal;
            dd.radius = wl->drum_radius;
            dd.length = wl->drum_length;
            dd.rpm = wl->drum_rpm;
            dd.start = wl->drum_start;
            dd.ramp = wl->drum_ramp;
            dd.open_lo = wl->drum_open_lo;
            dd.open_hi = wl->drum_open_hi;
            dd.material = wl->material;
            idx = sd_world_add_drum(w, &dd, err);
        } else {
            idx = wl->kind == 0 ? sd_world_add_plane(w, wl->name, wl->point, wl->normal, wl->material, err)
                                : sd_world_add_box(w, wl->name, wl->lo, wl->hi, wl->open_faces, wl->material, err);
        }
        if (idx < 0)
            return sd_where(err, err->code != SD_OK ? err->code : SD_ERR_INPUT, s, wl->line, key);
    }
    /* motions once every wall exists: a servo wall measures its length
     * between the walls across it */
    for (size_t i = 0; i < s->wall_count; ++i) {
        const sd_scene_wall *wl = &s->walls[i];
        if (wl->kind == 2) { /* a mesh's motion and torque point */
            sd_error_clear(err);
            if (wl->has_mesh_motion && (st = sd_world_set_mesh_motion(w, (int)i, &wl->mesh_motion, err)) != SD_OK) {
                snprintf(key, sizeof key, "walls[%zu].motion", i);
                err->key[0] = '\0';
                return sd_where(err, st, s, wl->line, key);
            }
            if (wl->has_torque_point &&
                (st = sd_world_set_wall_torque_point(w, (int)i, wl->torque_point, err)) != SD_OK) {
                snprintf(key, sizeof key, "walls[%zu].torque_point", i);
                err->key[0] = '\0';
                return sd_where(err, st, s, wl->line, key);
            }
            continue;
        }
        if (!wl->has_motion)
            continue;
        sd_error_clear(err);
        if ((st = sd_world_set_wall_motion(w, (int)i, &wl->motion, err)) != SD_OK) {
            snprintf(key, sizeof key, "walls[%zu].%.40s", i, err->key[0] ? err->key : "servo_stress");
            err->key[0] = '\0';
            return sd_where(err, st, s, wl->line, key);
        }
    }

    double *bound = sd_calloc(s->shape_count ? s->shape_count : 1, sizeof *bound);
    if (!bound)
        return sd_error_set(err, SD_ERR_MEMORY, s->path, 0, "", "out of memory");
    st = sd_build_shapes(s, w, bound, err);
    if (st == SD_OK)
        st = sd_scene_generate(s, bound, sp, err);
    sd_free(bound);
    if (st != SD_OK)
        return st;
    /* Check the spheres before the world sees them: cheaper, and the
     * messages can name the scene line each sphere came from. */
    if ((st = sd_check_overlaps(s, sp, w, err)) != SD_OK)
        return st;
    if ((st = sd_check_walls(s, sp, w, err)) != SD_OK)
        return st;
    if ((st = sd_check_planar(s, sp, err)) != SD_OK)
        return st;
    /* One call per run of spheres or bodies of a generator keeps ids in
     * generation order (a list may mix them). */
    size_t nbodies = 0;
    for (size_t k = 0; k < sp->count; ++k)
        nbodies += sp->shape[k] >= 0;
    sd_body_def *bodies = nbodies ? sd_malloc(nbodies * sizeof *bodies) : NULL;
    if (nbodies && !bodies)
        return sd_error_set(err, SD_ERR_MEMORY, s->path, 0, "", "out of memory (%zu bodies)",
                            nbodies);
    st = SD_OK;
    for (size_t at = 0; at < sp->count && st == SD_OK;) {
        size_t end = at;
        while (end < sp->count && sp->gen[end] == sp->gen[at] &&
               (sp->shape[end] >= 0) == (sp->shape[at] >= 0))
            ++end;
        st = sd_add_run(s, w, sp, at, end, bodies, err);
        at = end;
    }
    sd_free(bodies);
    if (st != SD_OK)
        return st;
    if ((st = sd_check_state(s, sp, w, err)) != SD_OK)
        return st;
    /* the world holds the particles now: the generated copy goes before
     * the world is prepared (where, with solver grid, the solver takes the
     * spheres over), so the two are never held at once with it */
    sd_scene_spheres_free(sp);

    /* pouring and the outlet (seed 001 4.1-4.2; the grid solver has them) */
    if (s->pour.given) {
        sd_pour_def pd = sd_pour_def_default();
        pd.radius = s->pour.radius;
        pd.material = s->pour.material;
        pd.height = s->pour.height;
        pd.layers_per_second = s->pour.rate;
        pd.count = (size_t)s->pour.count;
        pd.vz_range = s->pour.vertical_speed;
        pd.vh_range = s->pour.horizontal_speed;
        pd.start_time = s->pour.start;
        if ((st = sd_world_set_pour(w, &pd, err)) != SD_OK)
            return sd_where(err, st, s, s->pour.line, "pour");
    }
    if (s->outlet.given) {
        sd_outlet_def od = sd_outlet_def_default();
        od.x0 = s->outlet.lo[0];
        od.x1 = s->outlet.hi[0];
        od.y0 = s->outlet.lo[1];
        od.y1 = s->outlet.hi[1];
        od.open_at = s->outlet.open_at;
        if ((st = sd_world_set_outlet(w, &od, err)) != SD_OK)
            return sd_where(err, st, s, s->outlet.line, "outlet");
    }
    if ((st = sd_world_prepare(w, err)) != SD_OK)
        return sd_where(err, st, s, s->simulation_line, "simulation");
    double tc = 0.0;
    double rec = sd_world_recommended_dt(w, &tc);
    /* Five steps per contact is the least that resolves a collision; with
     * fewer, contacts gain energy and the packing explodes. */
    /* An estimate of 0 or NaN comes from values at the ends of the double
     * range (a modulus whose square overflows, a mass that underflows): the
     * limit cannot be checked, so the run is refused rather than left to
     * end in NaN (probe F8). INFINITY means no pair can touch. */
    if (!(tc > 0.0))
        return sd_error_set(err, SD_ERR_INPUT, s->path, s->dt_line, "simulation.dt",
                            "the stability limit cannot be computed: the estimated contact duration is %g s "
                            "(materials' stiffness or Young's modulus, densities, sizes or speeds at the ends "
                            "of the double range; values are SI: Pa, N/m, kg/m^3, m, m/s)",
                            tc);
    if (isfinite(tc) && s->world.dt > tc / 5.0)
        return sd_error_set(err, SD_ERR_INPUT, s->path, s->dt_line, "simulation.dt",
                            "time step above the stability limit: dt = %g s but the shortest "
                            "contact lasts about %g s, so dt must be at most %g s (1/5 of it); "
                            "recommended dt (for accuracy: about 50 steps per contact, and the "
                            "volume law's own limits) = %g s",
                            s->world.dt, tc, tc / 5.0, rec);
    return SD_OK;
}

sd_status sd_scene_build(const sd_scene *s, sd_world **out, sd_error *err)
{
    sd_world *w = NULL;
    sd_scene_spheres sp;
    sd_error local;
    if (!err)
        err = &local; /* the world API calls below read err back */
    memset(&sp, 0, sizeof sp);
    if (!out)
        return sd_error_null(err, "sd_scene_build", "out");
    *out = NULL;
    sd_error_clear(err);
    if (!s)
        return sd_error_null(err, "sd_scene_build", "scene");
    sd_status st = sd_world_create(&s->world, &w, err);
    if (st != SD_OK && !strcmp(err->key, "simulation.backend")) {
        /* the backend refused: blame where the choice was made, the
         * command line's --backend or the scene's backend: line */
        if (s->backend_cli) {
            snprintf(err->key, sizeof err->key, "--backend %s", sd_backend_kind_name(s->world.backend));
            return st;
        }
        return sd_where(err, st, s, s->backend_line > 0 ? s->backend_line : s->simulation_line, "");
    }
    if (st != SD_OK)
        return sd_where(err, st, s, s->simulation_line, "simulation");
    st = sd_build(s, w, &sp, err);
    if (st == SD_OK) /* insert: and outlets: (scene_process.c) */
        st = sd_scene_build_process(s, w, err);
    sd_scene_spheres_free(&sp);
    if (st != SD_OK) {
        sd_world_destroy(w);
        return st;
    }
    *out = w;
    return SD_OK;
}
