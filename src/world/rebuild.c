/* rebuild.c — the world's side of the broad phase: the world fills the
 * broad phase's input (broad/bins.h) from its arrays and tables, applies
 * the particle order the bins return (sd_particles_permute), makes the
 * ghosts, and has the pair lists rebuilt, the contact history carried by
 * key (DESIGN.md engineering notes). The broad phase itself never sees the
 * world; the threading policy and the wall marks are the world's.
 *
 * Periodic boundaries (seed 004 §2.8, the usual minimum-image scheme done
 * with images): at each rebuild the owned particles are wrapped into the
 * periodic box, then every owned particle within band = 2 r_max + skin of
 * a periodic face gets an image (a ghost) shifted by the period across it,
 * with the edge and corner images where it is near two or three faces. A
 * contact across the boundary is then an ordinary pair of an owned
 * particle and a ghost, evaluated once (broad/bins.h); each step the
 * ghosts follow their owners (the backend's ghost exchange stage,
 * dynamics/periodic.h). A period of at
 * least 2 band on every periodic axis guarantees that a particle meets at
 * most one image of another, never its own, and that every pair within
 * r_i + r_j + skin across a face has its image among the ghosts.
 *
 * Invariant: after a rebuild, x_ref and q_ref are the positions and
 * orientations the lists were built from (wrapped ones: a wrapped
 * particle's reference moves with it), the walls are marked at their
 * positions (servo.c), and ghosts p.n .. p.n + n_ghost - 1 hold copies of
 * their owners shifted by ghost_shift.
 */
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "contact/pair_poly.h"
#include "core/error.h"
#include "world/mesh.h"
#include "world/world.h"

void sd_world_broad_free(sd_world *w)
{
    sd_pairs_free(&w->pairs, &w->wpairs);
    sd_bins_free(&w->bins);
    sd_free(w->ghost_owner);
    sd_free(w->ghost_shift);
    w->ghost_owner = NULL;
    w->ghost_shift = NULL;
    w->n_ghost = w->ghost_cap = 0;
}

/* ---- periodic boundaries --------------------------------------------------- */

static const char sd_axis_name[3] = {'x', 'y', 'z'};

static sd_real sd_axis(sd_vec3 v, int a)
{
    return a == 0 ? v.x : (a == 1 ? v.y : v.z);
}

static void sd_axis_add(sd_vec3 *v, int a, sd_real d)
{
    if (a == 0)
        v->x += d;
    else if (a == 1)
        v->y += d;
    else
        v->z += d;
}

sd_status sd_world_check_periodic_def(const sd_world_def *def, sd_error *err)
{
    unsigned m = def->periodic;
    if (m == 0)
        return SD_OK;
    if (m & ~7u)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.periodic",
                            "expected periodic axes x, y, z (SD_PERIODIC_X | _Y | _Z), got the mask %u", m);
    if (def->dimension == 2 && (m & SD_PERIODIC_Z))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.periodic",
                            "dimension 2: only x and y can be periodic (the plane z = 0 has no z extent)");
    if (def->solver == SD_SOLVER_GRID)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.periodic",
                            "periodic boundaries run on the cells solver only (the grid solver's domain is a box "
                            "wall); use solver: cells");
    double lo[3] = {def->domain_lo.x, def->domain_lo.y, def->domain_lo.z};
    double hi[3] = {def->domain_hi.x, def->domain_hi.y, def->domain_hi.z};
    for (int a = 0; a < 3; ++a)
        if ((m & (1u << a)) && !(hi[a] > lo[a] && isfinite(hi[a] - lo[a])))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.domain",
                                "periodic axis %c: the domain needs max > min, got [%g, %g]", sd_axis_name[a], lo[a],
                                hi[a]);
    return SD_OK;
}

static sd_vec3 sd_domain_lo(const sd_world *w)
{
    return sd_v3((sd_real)w->def.domain_lo.x, (sd_real)w->def.domain_lo.y, (sd_real)w->def.domain_lo.z);
}

static sd_vec3 sd_domain_hi(const sd_world *w)
{
    return sd_v3((sd_real)w->def.domain_hi.x, (sd_real)w->def.domain_hi.y, (sd_real)w->def.domain_hi.z);
}

/* What a periodic world must satisfy whenever particles or walls change:
 * no wall across a periodic axis, a period of at least 2 (2 r_max + skin),
 * and (at the start) every particle inside the box. */
static sd_status sd_periodic_check(const sd_world *w, sd_error *err)
{
    unsigned m = w->def.periodic;
    const sd_particles *p = &w->p;
    for (size_t k = 0; k < w->wall_count; ++k)
        for (int a = 0; a < 3; ++a)
            if ((m & (1u << a)) && sd_wall_crosses_axis(&w->walls[k].geom, a))
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.periodic",
                                    "wall '%s' lies across the periodic axis %c (%s): periodic images would pass "
                                    "through it; make the axis non-periodic or the wall parallel to it",
                                    w->walls[k].name, sd_axis_name[a],
                                    w->walls[k].kind == SD_WALL_PLANE ? "its normal has a component along it"
                                                                      : "its faces on that axis are closed");
    sd_real rmax = 0;
    for (size_t k = 0; k < p->n; ++k)
        rmax = sd_max(rmax, p->radius[k]);
    sd_vec3 lo = sd_domain_lo(w), hi = sd_domain_hi(w);
    sd_real need = SD_R(2.0) * (SD_R(2.0) * rmax + w->skin);
    for (int a = 0; a < 3; ++a)
        if ((m & (1u << a)) && sd_axis(hi, a) - sd_axis(lo, a) < need)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.domain",
                                "periodic axis %c: the period %g m is shorter than 2 (2 r_max + skin) = %g m "
                                "(r_max = %g m, skin = %g m): a particle could meet two images of another",
                                sd_axis_name[a], (double)(sd_axis(hi, a) - sd_axis(lo, a)), (double)need,
                                (double)rmax, (double)w->skin);
    if (!w->prepared)
        for (size_t k = 0; k < p->n; ++k)
            for (int a = 0; a < 3; ++a) {
                sd_real x = sd_axis(p->x[k], a);
                if ((m & (1u << a)) && !(x >= sd_axis(lo, a) && x < sd_axis(hi, a)))
                    return sd_error_set(err, SD_ERR_INPUT, "", 0, "simulation.domain",
                                        "particle %zu (id %llu) lies outside the periodic box on axis %c: %c = %g m, "
                                        "the box is [%g, %g) m",
                                        k, (unsigned long long)p->id[k], sd_axis_name[a], sd_axis_name[a], (double)x,
                                        (double)sd_axis(lo, a), (double)sd_axis(hi, a));
            }
    return SD_OK;
}

void sd_world_wrap_periodic(const sd_world *w, sd_v3d *x)
{
    unsigned m = w->def.periodic;
    double *c[3] = {&x->x, &x->y, &x->z};
    const double lo[3] = {w->def.domain_lo.x, w->def.domain_lo.y, w->def.domain_lo.z};
    const double hi[3] = {w->def.domain_hi.x, w->def.domain_hi.y, w->def.domain_hi.z};
    for (int a = 0; a < 3; ++a) {
        if (!(m & (1u << a)))
            continue;
        double len = hi[a] - lo[a];
        while (*c[a] >= hi[a])
            *c[a] -= len;
        while (*c[a] < lo[a])
            *c[a] += len;
    }
}

/* Wraps the owned particles into the box on the periodic axes (a particle
 * moves less than half the skin between rebuilds, far less than a period,
 * but the loop is safe for any distance). */
static void sd_periodic_wrap(sd_world *w)
{
    unsigned m = w->def.periodic;
    sd_particles *p = &w->p;
    sd_vec3 lo = sd_domain_lo(w), hi = sd_domain_hi(w);
    for (int a = 0; a < 3; ++a) {
        if (!(m & (1u << a)))
            continue;
        sd_real l0 = sd_axis(lo, a), l1 = sd_axis(hi, a), len = l1 - l0;
        for (size_t k = 0; k < p->n; ++k) {
            while (sd_axis(p->x[k], a) >= l1)
                sd_axis_add(&p->x[k], a, -len);
            while (sd_axis(p->x[k], a) < l0)
                sd_axis_add(&p->x[k], a, len);
        }
    }
}

/* The images of owned particle k: the shifts (in periods) on each periodic
 * axis it may take, -1, 0 or +1, and their count less the particle itself.
 * out gets up to 7 shifts. */
int sd_world_periodic_images(const sd_world *w, size_t k, sd_real band, sd_vec3 *out)
{
    unsigned m = w->def.periodic;
    sd_vec3 lo = sd_domain_lo(w), hi = sd_domain_hi(w), x = w->p.x[k];
    sd_real opt[3][2];
    int nopt[3];
    for (int a = 0; a < 3; ++a) {
        opt[a][0] = 0;
        nopt[a] = 1;
        if (!(m & (1u << a)))
            continue;
        sd_real len = sd_axis(hi, a) - sd_axis(lo, a), c = sd_axis(x, a);
        /* near the low face: an image one period up; near the high face:
         * one down (a period of 2 band or more: never both) */
        if (c < sd_axis(lo, a) + band)
            opt[a][nopt[a]++] = len;
        else if (c >= sd_axis(hi, a) - band)
            opt[a][nopt[a]++] = -len;
    }
    int count = 0;
    for (int ix = 0; ix < nopt[0]; ++ix)
        for (int iy = 0; iy < nopt[1]; ++iy)
            for (int iz = 0; iz < nopt[2]; ++iz) {
                if (ix == 0 && iy == 0 && iz == 0)
                    continue;
                if (out)
                    out[count] = sd_v3(opt[0][ix], opt[1][iy], opt[2][iz]);
                ++count;
            }
    return count;
}

sd_status sd_world_ghosts_reserve(sd_world *w, size_t ng)
{
    if (ng > w->ghost_cap) {
        size_t cap = ng + ng / 2 + 16;
        uint32_t *o = sd_realloc(w->ghost_owner, cap * sizeof *o);
        if (!o)
            return SD_ERR_MEMORY;
        w->ghost_owner = o;
        sd_vec3 *s = sd_realloc(w->ghost_shift, cap * sizeof *s);
        if (!s)
            return SD_ERR_MEMORY;
        w->ghost_shift = s;
        w->ghost_cap = cap;
    }
    sd_particles *p = &w->p;
    if (p->n + ng > p->cap && sd_particles_reserve(p, p->n + ng) != SD_OK)
        return SD_ERR_MEMORY;
    return SD_OK;
}

/* Makes the ghosts of the (sorted) owned particles: counts, room after the
 * owned ones, then each image a copy of its owner with the shift. */
static sd_status sd_periodic_ghosts(sd_world *w)
{
    sd_particles *p = &w->p;
    size_t n = p->n;
    sd_real rmax = 0;
    for (size_t k = 0; k < n; ++k)
        rmax = sd_max(rmax, p->radius[k]);
    sd_real band = SD_R(2.0) * rmax + w->skin;
    size_t ng = 0;
    for (size_t k = 0; k < n; ++k)
        ng += (size_t)sd_world_periodic_images(w, k, band, NULL);
    if (sd_world_ghosts_reserve(w, ng) != SD_OK)
        return SD_ERR_MEMORY;
    size_t g = 0;
    for (size_t k = 0; k < n; ++k) {
        sd_vec3 sh[7];
        int c = sd_world_periodic_images(w, k, band, sh);
        for (int t = 0; t < c; ++t, ++g) {
            size_t d = n + g;
#define SD_X_COPY(type, name, ...) p->name[d] = p->name[k];
            SD_PARTICLE_FIELDS(SD_X_COPY)
#undef SD_X_COPY
            p->x[d] = sd_v3_add(p->x[k], sh[t]);
            w->ghost_owner[g] = (uint32_t)k;
            w->ghost_shift[g] = sh[t];
        }
    }
    w->n_ghost = ng;
    return SD_OK;
}

/* The tables the input points into, made for one rebuild (a few bytes per
 * template, material pair and wall). */
typedef struct sd_rebuild_tables {
    uint8_t *shape_class;
    uint8_t *volume_law;
    sd_wall_geom *walls;
    int32_t *wall_material;
} sd_rebuild_tables;

static void sd_rebuild_tables_free(sd_rebuild_tables *t)
{
    sd_free(t->shape_class);
    sd_free(t->volume_law);
    sd_free(t->walls);
    sd_free(t->wall_material);
}

static sd_status sd_rebuild_input_of(const sd_world *w, sd_bins_input *in, sd_rebuild_tables *t)
{
    const sd_particles *p = &w->p;
    memset(in, 0, sizeof *in);
    memset(t, 0, sizeof *t);
    size_t ns = w->dim2 ? w->shape2d_count : w->shape_count, nm = w->material_count, nw = w->wall_count;
    t->shape_class = sd_malloc(ns ? ns : 1);
    t->volume_law = w->has_volume_law ? sd_malloc(nm > 0 ? nm * nm : 1) : NULL;
    t->walls = sd_malloc((nw ? nw : 1) * sizeof *t->walls);
    t->wall_material = sd_malloc((nw ? nw : 1) * sizeof *t->wall_material);
    if (!t->shape_class || (w->has_volume_law && !t->volume_law) || !t->walls || !t->wall_material) {
        sd_rebuild_tables_free(t);
        return SD_ERR_MEMORY;
    }
    for (size_t s = 0; s < ns; ++s)
        t->shape_class[s] = (uint8_t)(w->dim2 ? SD_CLASS_SHAPE2D
                                      : w->shapes[s].kind == SD_SHAPE_COMPOSITE
                                          ? SD_CLASS_COMPOSITE
                                          : (sd_shape_is_sharp_polyhedron(&w->shapes[s]) ? SD_CLASS_SHARP_POLY
                                                                                        : SD_CLASS_SHAPE));
    if (t->volume_law)
        for (size_t m = 0; m < nm * nm; ++m)
            t->volume_law[m] = (uint8_t)sd_law_is_volume(w->mix[m].law);
    for (size_t k = 0; k < nw; ++k) {
        t->walls[k] = w->walls[k].geom;
        t->wall_material[k] = w->walls[k].material;
    }
    in->n_owned = p->n;
    in->n_total = p->n + w->n_ghost;
    in->x = p->x;
    in->radius = p->radius;
    in->id = p->id;
    /* a world of plain spheres passes no shapes: every pair is a sphere pair */
    in->shape = w->has_shapes ? p->shape : NULL;
    in->shape_class = t->shape_class;
    in->shapes = w->dim2 ? NULL : w->shapes;
    in->elements = w->elements;
    in->q = p->q;
    in->material = p->material;
    in->ghost_owner = w->ghost_owner;
    in->material_count = nm;
    in->volume_law = t->volume_law;
    in->wall_count = nw;
    in->walls = t->walls;
    in->wall_material = t->wall_material;
    in->meshes = w->mesh_views;
    in->mesh_count = w->mesh_count;
    in->skin = w->skin;
    in->threads = w->threads;
    in->parallel = w->parallel;
    return SD_OK;
}

sd_status sd_world_rebuild(sd_world *w, sd_error *err)
{
    sd_particles *p = &w->p;
    /* the threading policy: small worlds stay serial (forking threads costs
     * more than it saves) */
    w->n_ghost = 0; /* made again below, after the owned particles are sorted */
    if (w->comm) {
        /* a decomposed run: the particles that left this rank's sub-domain
         * go to their new owners first (collective: every rank, even one
         * holding nothing), by their wrapped positions; the decomposition
         * makes the periodic images too, its own and the other ranks' */
        if (w->def.periodic) {
            sd_status pst = w->dirty ? sd_periodic_check(w, err) : SD_OK;
            if (pst != SD_OK)
                return pst;
            sd_periodic_wrap(w);
        }
        sd_status mst = w->comm->migrate(w->comm_ctx, w, err);
        if (mst != SD_OK)
            return mst;
    }
    w->parallel = sd_world_wants_parallel(w);
    if (p->n == 0) {
        if (w->comm) { /* this rank still takes part in the ghost exchange */
            sd_status gst = w->comm->ghosts(w->comm_ctx, w, err);
            if (gst != SD_OK)
                return gst;
        }
        memset(&w->pairs.kind_start, 0, sizeof w->pairs.kind_start);
        memset(&w->wpairs.kind_start, 0, sizeof w->wpairs.kind_start);
        w->pairs.n = 0;
        w->wpairs.n = 0;
        w->rebuilds++;
        return SD_OK;
    }
    if (w->def.periodic && !w->comm) {
        sd_status pst = w->dirty ? sd_periodic_check(w, err) : SD_OK;
        if (pst != SD_OK)
            return pst;
        sd_periodic_wrap(w);
    }
    if (w->mesh_count > 0) {
        /* facet bins of about twice the largest reach (world/mesh.c keeps
         * cells in [reach, 4 reach], builds them at 2 reach): a query box
         * (2 reach) spans at most 2 x 2 x 2 cells of 8 reach^3 each */
        sd_real reach = SD_R(0.0);
        for (size_t k = 0; k < p->n; ++k)
            reach = p->radius[k] > reach ? p->radius[k] : reach;
        sd_status mst = sd_world_meshes_bins(w, reach + w->skin);
        if (mst != SD_OK)
            return sd_error_set(err, mst, "", 0, "", "out of memory for the facet bins of %zu meshes", w->mesh_count);
    }
    sd_bins_input in;
    sd_rebuild_tables tables;
    sd_status st = sd_rebuild_input_of(w, &in, &tables);
    if (st == SD_OK) {
        const uint32_t *perm;
        void *scratch;
        st = sd_bins_sort(&w->bins, &in, &perm, &scratch);
        if (st == SD_OK) {
            /* the pair lists hold their history under stable keys, so the
             * storage order may change under them */
            sd_particles_permute(p, perm, scratch, w->threads, w->parallel);
            if (w->def.periodic && !w->comm)
                st = sd_periodic_ghosts(w);
            if (st == SD_OK && w->comm)
                st = w->comm->ghosts(w->comm_ctx, w, err);
            /* the arrays may have grown for the ghosts */
            in.x = p->x;
            in.q = p->q;
            in.radius = p->radius;
            in.id = p->id;
            in.shape = w->has_shapes ? p->shape : NULL;
            in.material = p->material;
            in.n_total = p->n + w->n_ghost;
            in.ghost_owner = w->ghost_owner;
            if (st == SD_OK)
                st = sd_bins_build(&w->bins, &in, &w->pairs, &w->wpairs);
            /* every run, serial, threaded or decomposed, sums in the order
             * of stable ids (bins.h), so that mpirun -np N writes the
             * plain run's bits */
            if (st == SD_OK)
                st = sd_pairs_canonical(&in, &w->pairs);
        }
        sd_rebuild_tables_free(&tables);
    }
    if (st != SD_OK)
        return sd_error_set(err, st, "", 0, "", "out of memory while building the pair list (%zu particles)", p->n);
    size_t n = p->n;
    SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel))
    for (size_t k = 0; k < n; ++k) {
        p->x_ref[k] = p->x[k];
        p->q_ref[k] = p->q[k];
    }
    sd_world_walls_mark(w); /* a wall and a particle may each use half the skin */
    w->rebuilds++;
    w->dirty = 0;
    return SD_OK;
}
