/* world.c — creating a world and filling it: materials, interactions,
 * particles, walls; the queries of the public API.
 *
 * Invariant: a def struct is accepted only when made by its default function
 * (the cookie), so a caller cannot pass an uninitialised one by mistake.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "backend/backend.h"
#include "core/alloc.h"
#include "core/error.h"
#include "world/mesh.h"
#include "world/process.h"
#include "world/solver.h"
#include "world/view.h"
#include "world/world.h"

#define SD_COOKIE 0x5D5D

/* ---- defs ------------------------------------------------------------------ */

sd_world_def sd_world_def_default(void)
{
    sd_world_def d;
    memset(&d, 0, sizeof d);
    d.dimension = 3;
    d.dt = 1e-5;
    d.gravity.z = -9.81;
    d.seed = 1;
    d.threads = 0;
    d.law = SD_LAW_HERTZ_MINDLIN;
    d.skin = 0;
    d.backend = SD_BACKEND_AUTO;
    d.max_overlap = (double)SD_GUARD_OVERLAP;
    d.cookie = SD_COOKIE;
    return d;
}

sd_material_def sd_material_def_default(void)
{
    sd_material_def m;
    memset(&m, 0, sizeof m);
    m.name = "default";
    m.density = 2500;
    m.youngs_modulus = 0;
    m.poisson_ratio = 0.3;
    m.restitution = 0.5;
    m.friction = 0.5;
    m.rolling_friction = 0;
    m.stiffness = 0;
    m.tangential_stiffness_ratio = 2.0 / 7.0;
    m.cookie = SD_COOKIE;
    return m;
}

sd_interaction_def sd_interaction_def_default(void)
{
    sd_interaction_def d;
    d.restitution = -1;
    d.friction = -1;
    d.rolling_friction = -1;
    d.stiffness = -1;
    d.damping = -1;
    d.volume_stiffness = -1;
    d.law = -1;
    d.cookie = SD_COOKIE;
    return d;
}

static const char *const sd_law_names[] = {
#define SD_X_NAME(e, name, doc, needs, traits) name,
    SD_CONTACT_LAWS(SD_X_NAME)
#undef SD_X_NAME
};

const char *sd_contact_law_name(sd_contact_law law)
{
    return (law >= 0 && law < SD_LAW_COUNT) ? sd_law_names[law] : "unknown";
}

unsigned sd_contact_law_needs(sd_contact_law law) { return sd_law_needs((int)law); }
unsigned sd_contact_law_traits(sd_contact_law law) { return sd_law_traits((int)law); }

sd_contact_law sd_contact_law_from_name(const char *name)
{
    for (int k = 0; k < SD_LAW_COUNT; ++k)
        if (name && strcmp(name, sd_law_names[k]) == 0)
            return (sd_contact_law)k;
    return SD_LAW_COUNT;
}

/* ---- particles ---------------------------------------------------------------- */

sd_status sd_particles_reserve(sd_particles *p, size_t cap)
{
    if (cap <= p->cap)
        return SD_OK;
    /* head room for later additions, but not on the first fill: a scene
     * that adds its particles in one go (a generator of millions) would
     * reserve half as much again and never use it */
    if (p->cap)
        cap = cap + cap / 2 + 64;
#define SD_X_GROW(type, name, ...)                                \
    {                                                             \
        type *q = sd_realloc(p->name, cap * sizeof(type));        \
        if (!q)                                                   \
            return SD_ERR_MEMORY;                                 \
        p->name = q;                                              \
    }
    SD_PARTICLE_FIELDS(SD_X_GROW)
#undef SD_X_GROW
    p->cap = cap;
    ++p->generation;
    return SD_OK;
}

void sd_particles_free(sd_particles *p)
{
#define SD_X_FREE(type, name, ...) sd_free(p->name);
    SD_PARTICLE_FIELDS(SD_X_FREE)
#undef SD_X_FREE
    uint64_t generation = p->generation + 1;
    memset(p, 0, sizeof *p);
    p->generation = generation;
}

void sd_particles_init(sd_particles *p, size_t e, uint64_t id)
{
#define SD_X_INIT(type, name, unit, doc, def, ...) p->name[e] = def;
    SD_PARTICLE_FIELDS(SD_X_INIT)
#undef SD_X_INIT
    p->id[e] = id;
    ++p->generation;
}

void sd_particles_permute(sd_particles *p, const uint32_t *perm, void *scratch, int threads, int parallel)
{
    size_t n = p->n;
#define SD_X_PERMUTE(type, name, ...)                                                                       \
    {                                                                                                       \
        _Static_assert(sizeof(type) <= 32, "scratch too small");                                            \
        type *tmp = (type *)scratch;                                                                        \
        SD_OMP_EACH(parallel, threads, k, 0, n, tmp[k] = p->name[perm[k]]);                                 \
        SD_OMP_EACH(parallel, threads, k, 0, n, p->name[k] = tmp[k]);                                      \
    }
    SD_PARTICLE_FIELDS(SD_X_PERMUTE)
#undef SD_X_PERMUTE
    ++p->generation;
}

/* ---- world ------------------------------------------------------------------------ */

static int sd_pick_threads(int requested)
{
#ifdef _OPENMP
    if (requested > 0)
        return requested;
    return omp_get_max_threads(); /* honours OMP_NUM_THREADS */
#else
    (void)requested;
    return 1;
#endif
}

sd_status sd_world_create(const sd_world_def *def, sd_world **out, sd_error *err)
{
    if (!out)
        return sd_error_null(err, "sd_world_create", "out");
    *out = NULL;
    if (!def || def->cookie != SD_COOKIE)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "world def not made by sd_world_def_default");
    if (def->dimension != 3 && def->dimension != 2)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.dimension", "expected 2 or 3, got %d",
                            def->dimension);
    if (def->dimension == 2 && def->gravity.z != 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.gravity",
                            "dimension 2: gravity must lie in the x-y plane (z = 0), got z = %g", def->gravity.z);
    if (def->dimension == 2 && def->solver == SD_SOLVER_GRID)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.solver",
                            "dimension 2 runs on the cells solver only (the grid solver is for 3D spheres)");
    if (!(def->local_damping >= 0 && def->local_damping < 1))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.local_damping",
                            "expected a local damping coefficient in [0, 1), got %g", def->local_damping);
    if (!(def->dt > 0) || !isfinite(def->dt))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.dt", "expected a time step > 0, got %g", def->dt);
    if (def->law < 0 || def->law >= SD_LAW_COUNT)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.contact_law", "unknown contact law %d", (int)def->law);
    if (def->skin < 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.skin", "expected a skin >= 0, got %g", def->skin);
    if (!(def->max_overlap >= 0) || !isfinite(def->max_overlap))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.max_overlap",
                            "expected an overlap fraction >= 0 (0 = no overlap guard), got %g", def->max_overlap);
    if (def->multi_contact != SD_MULTI_CONTACT_AVERAGE && def->multi_contact != SD_MULTI_CONTACT_SUM)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.multi_contact",
                            "expected average or sum, got %d", def->multi_contact);
    if (def->device < 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "expected a CUDA device slot >= 0, got %d", def->device);
    sd_status periodic_st = sd_world_check_periodic_def(def, err); /* world/rebuild.c */
    if (periodic_st != SD_OK)
        return periodic_st;
    sd_world *w = sd_calloc(1, sizeof *w);
    if (!w)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory creating the world");
    w->def = *def;
    w->threads = sd_pick_threads(def->threads);
    w->dt = (sd_real)def->dt;
    w->gravity = sd_v3((sd_real)def->gravity.x, (sd_real)def->gravity.y, (sd_real)def->gravity.z);
    w->dim2 = def->dimension == 2;
    w->local_damping = (sd_real)def->local_damping;
    /* the one place that asks which engine runs (world/solver.h) */
    w->solver = def->solver == SD_SOLVER_GRID ? &sd_solver_grid : &sd_solver_cells;
    /* and the one place that asks where its stages run (world/backend.c) */
    sd_status backend_st = sd_world_choose_backend(w, err);
    if (backend_st != SD_OK) {
        sd_free(w);
        return backend_st;
    }
    *out = w;
    return SD_OK;
}

void sd_world_destroy(sd_world *w)
{
    if (!w)
        return;
    sd_particles_free(&w->p);
    sd_world_broad_free(w);
    if (w->backend)
        w->backend->release(&w->stage); /* its device copies */
    sd_world_views_free(w);
    sd_free(w->materials);
    sd_free(w->interactions);
    sd_free(w->mix);
    sd_free(w->walls);
    sd_world_meshes_free(w);
    w->solver->destroy(w);
    sd_world_process_free(w);
    sd_free(w->shapes);
    sd_free(w->shape_names);
    sd_free(w->shape_req);
    sd_free(w->shape_com);
    sd_free(w->verts);
    sd_free(w->planes);
    sd_free(w->dtris);
    sd_free(w->elements);
    sd_free(w->scaled);
    sd_free(w->shapes2d);
    sd_free(w->shape2d_names);
    sd_free(w->pool2d);
    sd_free(w);
}

int sd_world_add_material(sd_world *w, const sd_material_def *d, sd_error *err)
{
    if (!w) {
        sd_error_null(err, "sd_world_add_material", "world");
        return -1;
    }
    if (!d || d->cookie != SD_COOKIE) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "materials", "material def not made by sd_material_def_default");
        return -1;
    }
    const char *name = d->name ? d->name : "";
    if (!(d->density > 0)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "density", "expected a density > 0, got %g", d->density);
        return -1;
    }
    if (!(d->restitution > 0 && d->restitution <= 1)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "restitution", "expected a restitution in (0, 1], got %g",
                     d->restitution);
        return -1;
    }
    if (!(d->poisson_ratio > -1 && d->poisson_ratio < 0.5)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "poisson_ratio", "expected a Poisson ratio in (-1, 0.5), got %g",
                     d->poisson_ratio);
        return -1;
    }
    if (d->youngs_modulus < 0 || d->friction < 0 || d->rolling_friction < 0 || d->stiffness < 0 || d->damping < 0 ||
        !(d->tangential_stiffness_ratio > 0) || d->volume_stiffness < 0) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "", "material '%s': moduli, stiffness and friction must be >= 0",
                     name);
        return -1;
    }
    if (sd_world_find_material(w, name) >= 0) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "name", "material '%s' defined twice", name);
        return -1;
    }
    sd_material *m = sd_realloc(w->materials, (w->material_count + 1) * sizeof *m);
    if (!m) {
        sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
        return -1;
    }
    w->materials = m;
    m += w->material_count;
    memset(m, 0, sizeof *m);
    strncpy(m->name, name, sizeof m->name - 1);
    m->def = *d;
    m->def.name = NULL;
    w->prepared = 0;
    return (int)w->material_count++;
}

int sd_world_find_material(const sd_world *w, const char *name)
{
    for (size_t k = 0; w && k < w->material_count; ++k)
        if (name && strcmp(w->materials[k].name, name) == 0)
            return (int)k;
    return -1;
}

const char *sd_world_material_name(const sd_world *w, size_t index)
{
    return w && index < w->material_count ? w->materials[index].name : NULL;
}

sd_status sd_world_set_interaction(sd_world *w, int a, int b, const sd_interaction_def *d, sd_error *err)
{
    if (!w)
        return sd_error_null(err, "sd_world_set_interaction", "world");
    if (!d || d->cookie != SD_COOKIE)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "interactions", "def not made by sd_interaction_def_default");
    if (a < 0 || b < 0 || (size_t)a >= w->material_count || (size_t)b >= w->material_count)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "interactions", "unknown material index");
    if (d->restitution > 1 || d->restitution == 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "restitution", "expected a restitution in (0, 1], got %g",
                            d->restitution);
    if (d->law >= SD_LAW_COUNT)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "contact_law", "unknown contact law %d", d->law);
    sd_interaction *it = sd_realloc(w->interactions, (w->interaction_count + 1) * sizeof *it);
    if (!it)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    w->interactions = it;
    it[w->interaction_count].a = a;
    it[w->interaction_count].b = b;
    it[w->interaction_count].def = *d;
    w->interaction_count++;
    w->prepared = 0;
    return SD_OK;
}

sd_status sd_world_add_spheres(sd_world *w, size_t n, const sd_sphere_def *defs, sd_error *err)
{
    if (!w)
        return sd_error_null(err, "sd_world_add_spheres", "world");
    if (n > 0 && !defs)
        return sd_error_null(err, "sd_world_add_spheres", "defs");
    for (size_t k = 0; k < n; ++k) {
        const sd_sphere_def *d = &defs[k];
        if (!(d->radius > 0) || !isfinite(d->radius))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "radius", "sphere %zu: expected a radius > 0, got %g", k,
                                d->radius);
        if (d->material < 0 || (size_t)d->material >= w->material_count)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "material", "sphere %zu: unknown material index %d", k,
                                d->material);
        if (!isfinite(d->position.x) || !isfinite(d->position.y) || !isfinite(d->position.z))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "position", "sphere %zu: position is not finite", k);
        if (w->dim2 && (d->position.z != 0 || d->velocity.z != 0 || d->angular_velocity.x != 0 ||
                        d->angular_velocity.y != 0))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "position",
                                "circle %zu: dimension 2 needs z = 0, velocity z = 0 and rotation about z only", k);
    }
    sd_particles *p = &w->p;
    if (sd_particles_reserve(p, p->n + n))
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory adding %zu spheres", n);
    for (size_t k = 0; k < n; ++k) {
        const sd_sphere_def *d = &defs[k];
        size_t e = p->n + k;
        sd_real r = (sd_real)d->radius;
        sd_real rho = (sd_real)w->materials[d->material].def.density;
        sd_real mass = rho * SD_R(4.0) / SD_R(3.0) * SD_PI * r * r * r;
        sd_real inertia = SD_R(0.4) * mass * r * r;
        if (w->dim2) {
            /* a circle, per unit thickness (1 m): m = rho pi r^2, polar moment m r^2 / 2 */
            mass = rho * SD_PI * r * r;
            inertia = SD_R(0.5) * mass * r * r;
        }
        sd_particles_init(p, e, w->next_id++); /* a plain sphere (shape -1), at rest in orientation */
        p->x[e] = sd_v3((sd_real)d->position.x, (sd_real)d->position.y, (sd_real)d->position.z);
        p->v[e] = sd_v3((sd_real)d->velocity.x, (sd_real)d->velocity.y, (sd_real)d->velocity.z);
        p->w[e] = sd_v3((sd_real)d->angular_velocity.x, (sd_real)d->angular_velocity.y,
                        (sd_real)d->angular_velocity.z);
        p->radius[e] = r;
        p->inv_mass[e] = SD_R(1.0) / mass;
        p->inv_inertia[e] = sd_v3(SD_R(1.0) / inertia, SD_R(1.0) / inertia, SD_R(1.0) / inertia);
        p->x_ref[e] = p->x[e];
        p->material[e] = d->material;
    }
    p->n += n;
    w->dirty = 1;
    w->prepared = 0;
    return SD_OK;
}

static int sd_add_wall(sd_world *w, const sd_wall *proto, sd_error *err)
{
    if (proto->material < 0 || (size_t)proto->material >= w->material_count) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "material", "wall: unknown material index %d", proto->material);
        return -1;
    }
    if (w->wall_count >= 4096) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "walls", "too many walls (at most 4096)");
        return -1;
    }
    sd_wall *wl = sd_realloc(w->walls, (w->wall_count + 1) * sizeof *wl);
    if (!wl) {
        sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
        return -1;
    }
    w->walls = wl;
    wl[w->wall_count] = *proto;
    wl[w->wall_count].point_ref = proto->point;
    wl[w->wall_count].geom0 = proto->geom;
    w->dirty = 1;
    w->prepared = 0;
    return (int)w->wall_count++;
}

int sd_world_push_wall(sd_world *w, const sd_wall *proto, sd_error *err) { return sd_add_wall(w, proto, err); }

int sd_world_add_plane(sd_world *w, const char *name, sd_v3d point, sd_v3d normal, int material, sd_error *err)
{
    if (!w) {
        sd_error_null(err, "sd_world_add_plane", "world");
        return -1;
    }
    sd_wall wl;
    memset(&wl, 0, sizeof wl);
    sd_vec3 nv = sd_v3((sd_real)normal.x, (sd_real)normal.y, (sd_real)normal.z);
    if (!(sd_v3_norm(nv) > 0)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "normal", "plane normal must be non-zero");
        return -1;
    }
    if (w->dim2 && normal.z != 0) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "normal", "dimension 2: a plane wall is a line, its normal needs z = 0");
        return -1;
    }
    wl.kind = SD_WALL_PLANE;
    wl.point = sd_v3((sd_real)point.x, (sd_real)point.y, (sd_real)point.z);
    wl.normal = sd_v3_normalize(nv);
    wl.material = material;
    snprintf(wl.name, sizeof wl.name, "%s", name && name[0] ? name : "plane");
    return sd_add_wall(w, &wl, err);
}

int sd_world_add_box(sd_world *w, const char *name, sd_v3d lo, sd_v3d hi, unsigned open_faces, int material,
                     sd_error *err)
{
    if (!w) {
        sd_error_null(err, "sd_world_add_box", "world");
        return -1;
    }
    sd_wall wl;
    memset(&wl, 0, sizeof wl);
    if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "max", "box max must exceed min on every axis");
        return -1;
    }
    if (w->dim2 && !(lo.z < 0 && hi.z > 0)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "min", "dimension 2: a box must span z = 0 (its z faces are left out)");
        return -1;
    }
    if (w->dim2)
        open_faces |= SD_BOX_ZMIN | SD_BOX_ZMAX; /* the plane z = 0 has no z faces */
    wl.kind = SD_WALL_BOX;
    wl.lo = sd_v3((sd_real)lo.x, (sd_real)lo.y, (sd_real)lo.z);
    wl.hi = sd_v3((sd_real)hi.x, (sd_real)hi.y, (sd_real)hi.z);
    wl.point = sd_v3_scale(sd_v3_add(wl.lo, wl.hi), SD_R(0.5));
    wl.open_faces = open_faces & 63u;
    wl.material = material;
    snprintf(wl.name, sizeof wl.name, "%s", name && name[0] ? name : "box");
    return sd_add_wall(w, &wl, err);
}

/* ---- queries ---------------------------------------------------------------------- */

/* ---- the solver interface (world/solver.h) ------------------------------------- */

sd_status sd_world_prepare(sd_world *w, sd_error *err)
{
    return w ? w->solver->prepare(w, err) : sd_error_null(err, "sd_world_prepare", "world");
}

sd_status sd_world_step(sd_world *w, long nsteps, sd_error *err)
{
    if (!w)
        return sd_error_null(err, "sd_world_step", "world");
    /* the stability limit, as the scene loader and `shapedem check` see it (guards.c) */
    sd_status st = nsteps > 0 ? sd_world_check_dt(w, err) : SD_OK;
    return st != SD_OK ? st : w->solver->step(w, nsteps, err);
}
/* Async-signal-safe: one store to a volatile sig_atomic_t. */
void sd_world_request_interrupt(sd_world *w)
{
    if (w)
        w->interrupt = 1;
}

int sd_world_interrupt_due(const sd_world *w) { return w->interrupt && !w->comm; }

sd_status sd_world_interrupted(sd_world *w, sd_error *err)
{
    w->interrupt = 0;
    return sd_error_set(err, SD_ERR_INTERRUPTED, "", 0, "", "interrupted at step %ld (sd_world_request_interrupt)",
                        w->step);
}

size_t sd_world_particle_count(const sd_world *w) { return w ? w->solver->count(w) : 0; }
sd_status sd_world_get_particle(const sd_world *w, size_t k, sd_particle_state *out)
{
    return w && out ? w->solver->read(w, k, out) : SD_ERR_INPUT;
}
size_t sd_world_find_particle(const sd_world *w, uint64_t id) { return w ? w->solver->find(w, id) : (size_t)-1; }


sd_pour_def sd_pour_def_default(void)
{
    sd_pour_def d;
    memset(&d, 0, sizeof d);
    d.layers_per_second = 4; /* seed 001 Table 2, Case I */
    d.vz_range = 0.5;        /* seed 001 §4.1 */
    d.vh_range = 0.1;
    d.cookie = SD_COOKIE;
    return d;
}

sd_outlet_def sd_outlet_def_default(void)
{
    sd_outlet_def d;
    memset(&d, 0, sizeof d);
    d.cookie = SD_COOKIE;
    return d;
}

/* What needs no solver is checked here, once; the solver checks the rest
 * (the pour height against its domain, at prepare). */
sd_status sd_world_set_pour(sd_world *w, const sd_pour_def *d, sd_error *err)
{
    if (!w)
        return sd_error_null(err, "sd_world_set_pour", "world");
    if (!d || d->cookie != SD_COOKIE)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "pour", "pour def not made by sd_pour_def_default");
    if (!(d->radius > 0) || !isfinite(d->radius) || d->material < 0 || (size_t)d->material >= w->material_count)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "pour", "pour needs a radius > 0 and a known material");
    if (!(d->layers_per_second > 0) || !(d->vz_range >= 0) || !(d->vh_range >= 0))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "pour", "pour needs a feed rate > 0 and velocity ranges >= 0");
    return w->solver->set_pour(w, d, err);
}

sd_status sd_world_set_outlet(sd_world *w, const sd_outlet_def *d, sd_error *err)
{
    if (!w)
        return sd_error_null(err, "sd_world_set_outlet", "world");
    if (!d || d->cookie != SD_COOKIE)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "outlet", "outlet def not made by sd_outlet_def_default");
    if (!(d->x1 > d->x0 && d->y1 > d->y0))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "outlet", "outlet needs x1 > x0 and y1 > y0");
    if (!(d->open_at >= 0) || !isfinite(d->open_at))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "outlet.open_at", "outlet opening time must be >= 0 s");
    return w->solver->set_outlet(w, d, err);
}

int sd_world_get_pour(const sd_world *w, sd_pour_def *out)
{
    if (!w)
        return 0;
    sd_pour_def ignored;
    return w->solver->get_pour(w, out ? out : &ignored);
}

size_t sd_world_solver_items(const sd_world *w, sd_solver_item *items, size_t max)
{
    return w->solver->info(w, items, max);
}

static void sd_cells_destroy(sd_world *w) { (void)w; /* the world's arrays are all it has */ }

/* The world's own arrays are all the cells solver holds: nothing to add. */
static void sd_cells_dt_inputs(const sd_world *w, sd_v3d gdir, sd_dt_inputs *in)
{
    (void)w;
    (void)gdir;
    (void)in;
}

/* The grid's layer pour and floor hole; the cells solver inserts and
 * removes through shapedem/process.h (world/process.c). */
static sd_status sd_cells_set_pour(sd_world *w, const sd_pour_def *d, sd_error *err)
{
    (void)w;
    (void)d;
    return sd_error_set(err, SD_ERR_INPUT, "", 0, "pour",
                        "the layer pour needs solver grid (simulation.solver: grid); the cells solver inserts "
                        "particles with an insert: section (sd_world_add_insertion)");
}

static sd_status sd_cells_set_outlet(sd_world *w, const sd_outlet_def *d, sd_error *err)
{
    (void)w;
    (void)d;
    return sd_error_set(err, SD_ERR_INPUT, "", 0, "outlet",
                        "the floor outlet needs solver grid (simulation.solver: grid); the cells solver removes "
                        "particles with an outlets: section (sd_world_add_outlet)");
}

static int sd_cells_get_pour(const sd_world *w, sd_pour_def *out)
{
    (void)w;
    (void)out;
    return 0;
}

const sd_solver_ops sd_solver_cells = {
    .name = "cells",
    .prepare = sd_cells_prepare,
    .step = sd_cells_process_step, /* sd_cells_step between the insertions and outlets (world/process.c) */
    .count = sd_cells_count,
    .read = sd_cells_read,
    .find = sd_cells_find,
    .stats = sd_cells_stats,
    .dt_inputs = sd_cells_dt_inputs,
    .info = sd_cells_process_info,
    .set_pour = sd_cells_set_pour,
    .set_outlet = sd_cells_set_outlet,
    .get_pour = sd_cells_get_pour,
    .destroy = sd_cells_destroy,
    .state = sd_cells_state,
    .resumed = sd_cells_resumed,
};

size_t sd_cells_count(const sd_world *w) { return w->p.n; }
size_t sd_world_wall_count(const sd_world *w) { return w ? w->wall_count : 0; }
long sd_world_step_count(const sd_world *w) { return w ? w->step : 0; }
double sd_world_time(const sd_world *w) { return w ? w->time : (double)NAN; }
double sd_world_dt(const sd_world *w) { return w ? (double)w->dt : (double)NAN; }
int sd_world_threads(const sd_world *w) { return w ? w->threads : 0; }

int sd_world_wants_parallel(const sd_world *w)
{
    size_t min = w->shape_count > 0 ? SD_PARALLEL_MIN_SHAPED : SD_PARALLEL_MIN_PARTICLES;
    return w->threads > 1 && w->p.n >= min;
}

static sd_v3d sd_v3d_of(sd_vec3 v)
{
    sd_v3d r = {(double)v.x, (double)v.y, (double)v.z};
    return r;
}

sd_status sd_cells_read(const sd_world *w, size_t k, sd_particle_state *out)
{
    const sd_particles *p = &w->p;
    if (k >= p->n)
        return SD_ERR_INPUT;
    /* every public field, from the query column of SD_PARTICLE_FIELDS */
#define SD_QUERY_V3(dst, val) dst = sd_v3d_of(val);
#define SD_QUERY_QUAT(dst, val)                                                                      \
    dst[0] = (double)(val).w, dst[1] = (double)(val).x, dst[2] = (double)(val).y, dst[3] = (double)(val).z;
#define SD_QUERY_REAL(dst, val) dst = (double)(val);
#define SD_QUERY_INVERSE(dst, val) dst = (val) > 0 ? 1.0 / (double)(val) : (double)INFINITY;
#define SD_QUERY_INT(dst, val) dst = (int)(val);
#define SD_QUERY_U64(dst, val) dst = (val);
#define SD_QUERY_NONE(dst, val)
#define SD_X_QUERY(type, name, unit, doc, def, query, member) SD_QUERY_##query(out->member, p->name[k])
    SD_PARTICLE_FIELDS(SD_X_QUERY)
#undef SD_X_QUERY
#undef SD_QUERY_V3
#undef SD_QUERY_QUAT
#undef SD_QUERY_REAL
#undef SD_QUERY_INVERSE
#undef SD_QUERY_INT
#undef SD_QUERY_U64
#undef SD_QUERY_NONE
    return SD_OK;
}

size_t sd_cells_find(const sd_world *w, uint64_t id)
{
    for (size_t k = 0; k < w->p.n; ++k)
        if (w->p.id[k] == id)
            return k;
    return (size_t)-1;
}

sd_status sd_world_get_wall(const sd_world *w, size_t k, sd_wall_info *out)
{
    if (!w || !out || k >= w->wall_count)
        return SD_ERR_INPUT;
    const sd_wall *wl = &w->walls[k];
    out->name = wl->name;
    out->kind = wl->kind;
    out->force = sd_v3d_of(wl->force);
    out->torque = sd_v3d_of(sd_world_wall_torque_about(w, k));
    out->point = sd_v3d_of(wl->point);
    out->normal = sd_v3d_of(wl->normal);
    out->lo = sd_v3d_of(wl->lo);
    out->hi = sd_v3d_of(wl->hi);
    out->open_faces = wl->open_faces;
    out->material = wl->material;
    out->velocity = sd_v3d_of(wl->velocity);
    out->angular_velocity = sd_v3d_of(wl->omega);
    return SD_OK;
}
