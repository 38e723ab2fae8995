/* check_report.c — the estimates of `shapedem check` (see check_report.h).
 *
 * The run time comes from a timed trial, not a cost model: a few steps of
 * the scene's own world (or, when the scene pours, of a bed of the pour's
 * spheres resting in the scene's box, since the world is empty at the
 * start), timed on the threads the run will use, scaled by particle-steps.
 * It is rough: a trial sees the first steps only, and the cost per
 * particle-step changes as the packing settles (contacts per particle),
 * as walls move and with the machine's load; expect the run within about
 * a factor of 2-3 of it. For a pour it is an upper bound (the count
 * ramps up while the box fills).
 */
#define _POSIX_C_SOURCE 200809L

#include "cli/check_report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/duration.h"
#include "grid/grid.h"
#include "io/output.h"
#include "io/scene.h"
#include "io/scene_process.h"
#include "mpi/mpi.h"
#include "world/dt_report.h"
#include "world/process.h" /* sd_size_moment */

static double sd_check_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* What a material of this density is likely to be: sand, glass, rock,
 * metals and plastics lie in 300-25000 kg/m^3. */
static int sd_check_granular_density(double rho) { return rho >= 300.0 && rho <= 25000.0; }

void sd_check_count(const sd_scene *s, const sd_world *w, sd_check_counts *c)
{
    memset(c, 0, sizeof *c);
    c->now = sd_world_particle_count(w);
    c->rmin = HUGE_VAL;
    for (size_t k = 0; k < c->now; ++k) {
        sd_particle_state p;
        if (sd_world_get_particle(w, k, &p) != SD_OK)
            continue;
        c->bodies += p.shape >= 0;
        if (isfinite(p.mass))
            c->mass_now += p.mass;
        c->rmin = fmin(c->rmin, p.radius);
        c->rmax = fmax(c->rmax, p.radius);
        double rho = p.material >= 0 && (size_t)p.material < s->material_count
                         ? s->materials[p.material].def.density
                         : 0.0;
        if (sd_check_granular_density(rho) && p.radius > c->big_radius) {
            c->big_radius = p.radius;
            c->big_mass = p.mass;
            c->big_density = rho;
        }
    }
    sd_pour_def pd; /* the pour as the world gets it (the public scene query) */
    if (sd_scene_get_pour(s, &pd) && pd.count > 0) {
        double r = pd.radius, rho = s->materials[pd.material].def.density;
        double m = rho * 4.0 / 3.0 * SD_PI_D * r * r * r;
        c->poured = pd.count;
        c->mass_poured = m * (double)c->poured;
        c->rmin = fmin(c->rmin, r);
        c->rmax = fmax(c->rmax, r);
        if (sd_check_granular_density(rho) && r > c->big_radius) {
            c->big_radius = r;
            c->big_mass = m;
            c->big_density = rho;
        }
    }
    if (!isfinite(c->rmin))
        c->rmin = 0.0;
}

/* The smallest and largest radius a sphere size law draws: its bounds,
 * or its truncation, else the 0.1 % tails (3.09 standard deviations). */
static void sd_check_law_range(const sd_size_def *s, double *lo, double *hi)
{
    *lo = *hi = s->a;
    if (s->kind == SD_SIZE_UNIFORM) {
        *hi = s->b;
    } else if (s->kind == SD_SIZE_TABLE) {
        *lo = HUGE_VAL;
        *hi = 0;
        for (int c = 0; c < s->classes; ++c) {
            *lo = fmin(*lo, s->lo[c]);
            *hi = fmax(*hi, s->hi[c]);
        }
    } else if (s->kind == SD_SIZE_NORMAL || s->kind == SD_SIZE_LOGNORMAL) {
        int ln = s->kind == SD_SIZE_LOGNORMAL;
        double l = ln ? s->a * exp(-3.09 * s->b) : s->a - 3.09 * s->b;
        double h = ln ? s->a * exp(3.09 * s->b) : s->a + 3.09 * s->b;
        *lo = fmax(l, s->min);
        if (!(*lo > 0)) /* a normal law reaching 0 untruncated: a tenth of its mean */
            *lo = 0.1 * s->a;
        *hi = s->max > 0 ? fmin(h, s->max) : h;
    }
}

/* One probe particle of an insertion entry, twice: at the region's bottom
 * and top along gravity (the fall the time step's impact speed takes). */
typedef struct sd_check_probe_at {
    sd_v3d low, high, velocity;
    int material;
} sd_check_probe_at;

/* Adds the pair: a body of template `shape` (>= 0) or a sphere of radius r. */
static void sd_check_probe_pair(sd_body_def *b, size_t *nb, sd_sphere_def *d, size_t *nd,
                                const sd_check_probe_at *at, int shape, double r)
{
    for (int k = 0; k < 2; ++k) {
        sd_v3d x = k ? at->high : at->low;
        if (shape >= 0) {
            b[*nb] = (sd_body_def){.position = x, .velocity = at->velocity, .shape = shape, .material = at->material};
            ++*nb;
        } else {
            d[*nd] = (sd_sphere_def){.position = x, .velocity = at->velocity, .radius = r, .material = at->material};
            ++*nd;
        }
    }
}

/* 1 when s is one or more decimal digits and nothing else: a scaled copy's
 * class number, not a composite copy's element (BASE_iIeEsK.eJ, which is
 * a template too but never a particle of its own). */
static int sd_check_all_digits(const char *s)
{
    if (!*s)
        return 0;
    for (; *s; ++s)
        if (*s < '0' || *s > '9')
            return 0;
    return 1;
}

/* The probe bodies of a template entry: its scaled copies (named
 * BASE_iIeEsK by sd_world_add_insertion, world/process.c), else the
 * template as it is. Returns their mean mass (kg; the classes of a law
 * are equally likely, each copy at the class's mean volume). */
static double sd_check_probe_template(const sd_world *w, const sd_scene *s, size_t i, int e,
                                      const sd_insert_entry *en, const sd_check_probe_at *at, sd_body_def *b,
                                      size_t *nb, sd_check_insert *ci)
{
    sd_shape_info si;
    if (sd_world_get_shape(w, (size_t)en->shape, &si) != SD_OK)
        return 0;
    char prefix[96];
    int len = snprintf(prefix, sizeof prefix, "%.40s_i%zue%ds", si.name ? si.name : "shape", i, e);
    double rho = s->materials[en->material].def.density, sum = 0;
    int found = 0;
    for (size_t k = 0; k < sd_world_shape_count(w); ++k) {
        sd_shape_info sk;
        if (sd_world_get_shape(w, k, &sk) != SD_OK || !sk.name || strncmp(sk.name, prefix, (size_t)len) != 0 ||
            !sd_check_all_digits(sk.name + len))
            continue;
        sd_check_probe_pair(b, nb, NULL, NULL, at, (int)k, 0);
        sum += rho * sk.volume;
        ci->rmin = fmin(ci->rmin, sk.bounding_radius);
        ci->rmax = fmax(ci->rmax, sk.bounding_radius);
        found++;
    }
    if (!found) {
        sd_check_probe_pair(b, nb, NULL, NULL, at, en->shape, 0);
        sum = rho * si.volume;
        ci->rmin = fmin(ci->rmin, si.bounding_radius);
        ci->rmax = fmax(ci->rmax, si.bounding_radius);
        found = 1;
    }
    return sum / found;
}

void sd_check_insertions(const sd_scene *s, sd_check_insert *ci)
{
    memset(ci, 0, sizeof *ci);
    ci->rmin = HUGE_VAL;
    const sd_scene_process *sp = s->process;
    if (!sp || sp->insert_count == 0)
        return;
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_world *w = NULL;
    if (sd_scene_build(s, &w, &err) != SD_OK) {
        sd_error_format(&err, ci->why, sizeof ci->why);
        return;
    }
    int dim2 = s->world.dimension == 2;
    sd_v3d g = s->world.gravity;
    double gn = sqrt(g.x * g.x + g.y * g.y + g.z * g.z);
    const double down[3] = {gn > 0 ? g.x / gn : 0, gn > 0 ? g.y / gn : 0, gn > 0 ? g.z / gn : 0};
    /* at most 2 bodies per class, SD_SIZE_SCALES_MAX classes per entry, or 4 spheres */
    size_t cap = sp->insert_count * SD_INSERT_MIX_MAX * 2 * SD_SIZE_SCALES_MAX, nb = 0, nd = 0;
    sd_body_def *b = malloc(cap * sizeof *b);
    sd_sphere_def *d = malloc(cap * sizeof *d);
    for (size_t i = 0; b && d && i < sp->insert_count; ++i) {
        const sd_insert_def *in = &sp->inserts[i];
        double lo[3], hi[3], c[3], ext = 0;
        sd_region_box(&in->region, lo, hi);
        for (int k = 0; k < 3; ++k) {
            c[k] = 0.5 * (lo[k] + hi[k]);
            ext += 0.5 * fabs(down[k]) * (hi[k] - lo[k]);
        }
        sd_check_probe_at at;
        at.low = (sd_v3d){c[0] + ext * down[0], c[1] + ext * down[1], c[2] + ext * down[2]};
        at.high = (sd_v3d){c[0] - ext * down[0], c[1] - ext * down[1], c[2] - ext * down[2]};
        /* the fastest the jitter makes it: each component's jitter along its sign */
        double j = in->velocity_jitter;
        at.velocity = (sd_v3d){in->velocity.x + (in->velocity.x < 0 ? -j : j),
                               in->velocity.y + (in->velocity.y < 0 ? -j : j),
                               dim2 ? 0.0 : in->velocity.z + (in->velocity.z < 0 ? -j : j)};
        double by_number = 0, by_mass = 0;
        for (int e = 0; e < in->entry_count; ++e) {
            const sd_insert_entry *en = &in->entries[e];
            at.material = en->material;
            double m;
            if (en->shape >= 0) {
                m = sd_check_probe_template(w, s, i, e, en, &at, b, &nb, ci);
            } else {
                double rlo, rhi, rho = s->materials[en->material].def.density;
                sd_check_law_range(&en->size, &rlo, &rhi);
                sd_check_probe_pair(NULL, NULL, d, &nd, &at, -1, rlo);
                if (rhi > rlo)
                    sd_check_probe_pair(NULL, NULL, d, &nd, &at, -1, rhi);
                ci->rmin = fmin(ci->rmin, rlo);
                ci->rmax = fmax(ci->rmax, rhi);
                m = dim2 ? rho * SD_PI_D * sd_size_moment(&en->size, 2)
                         : rho * 4.0 / 3.0 * SD_PI_D * sd_size_moment(&en->size, 3);
            }
            by_number += en->fraction * m;
            by_mass += m > 0 ? en->fraction / m : 0;
        }
        /* the mean particle's mass: a mix by mass has number shares f_e / m_e */
        double mean = in->mix_by_mass ? (by_mass > 0 ? 1.0 / by_mass : 0) : by_number;
        size_t n = in->count > 0 ? in->count : mean > 0 ? (size_t)ceil(in->mass / mean) : 0;
        ci->count += n;
        ci->mass += in->count > 0 ? (double)n * mean : in->mass;
    }
    int ok = b && d && (nb == 0 || sd_world_add_bodies(w, nb, b, &err) == SD_OK) &&
             (nd == 0 || sd_world_add_spheres(w, nd, d, &err) == SD_OK);
    if (!ok) {
        if (b && d)
            sd_error_format(&err, ci->why, sizeof ci->why);
        else
            snprintf(ci->why, sizeof ci->why, "out of memory for the insertions' probe");
        sd_world_destroy(w);
        w = NULL;
    }
    free(b);
    free(d);
    ci->probes = nb + nd;
    ci->probe = w;
}

double sd_check_pour_bytes(size_t poured)
{
    /* the solver's arrays per particle (grid.c, sd_grid_get_info's bytes):
     * record, force and torque, two cell indices, the history slots; a
     * pour grows them with a quarter of head room */
    double per = (double)(sizeof(sd_grid_part) + 2 * sizeof(sd_vec3) + 2 * sizeof(uint32_t) +
                          SD_GRID_SLOTS * (sizeof(uint32_t) + sizeof(sd_vec3)));
    return per * (1.25 * (double)poured + 64.0);
}

sd_world *sd_check_world(const sd_scene *s)
{
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_world *w = NULL;
    int ok = sd_world_create(&s->world, &w, &err) == SD_OK;
    for (size_t i = 0; ok && i < s->material_count; ++i) {
        sd_material_def md = s->materials[i].def;
        md.name = s->materials[i].name;
        ok = sd_world_add_material(w, &md, &err) >= 0;
    }
    for (size_t i = 0; ok && i < s->interaction_count; ++i)
        ok = sd_world_set_interaction(w, s->interactions[i].mat_a, s->interactions[i].mat_b,
                                      &s->interactions[i].def, &err) == SD_OK;
    if (!ok) {
        sd_world_destroy(w);
        return NULL;
    }
    return w;
}

/* A bed of the pour's spheres resting on the floor of the scene's box
 * walls: simple cubic, 2 r apart, up to `want` spheres. NULL when the box
 * holds none or the world refuses it. */
static sd_world *sd_check_bed(const sd_scene *s, size_t want, size_t *count)
{
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_world *w = NULL;
    *count = 0;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (size_t i = 0; i < s->wall_count; ++i) {
        const sd_scene_wall *wl = &s->walls[i];
        if (wl->kind != 1)
            continue;
        const double a[3] = {wl->lo.x, wl->lo.y, wl->lo.z}, b[3] = {wl->hi.x, wl->hi.y, wl->hi.z};
        for (int k = 0; k < 3; ++k) {
            lo[k] = fmin(lo[k], a[k]);
            hi[k] = fmax(hi[k], b[k]);
        }
    }
    double r = s->pour.radius, h = 2.0 * r * (1.0 + 1e-9);
    if (!(hi[0] > lo[0]) || !(r > 0))
        return NULL;
    long n[3];
    for (int k = 0; k < 3; ++k)
        n[k] = (long)floor((hi[k] - lo[k] - 2.0 * r) / h) + 1;
    if (n[0] < 1 || n[1] < 1 || n[2] < 1)
        return NULL;
    size_t layer = (size_t)n[0] * (size_t)n[1];
    size_t layers = (want + layer - 1) / layer;
    if (layers > (size_t)n[2])
        layers = (size_t)n[2];
    size_t total = layer * layers;
    sd_sphere_def *d = malloc(total * sizeof *d);
    if (!d)
        return NULL;
    size_t m = 0;
    for (size_t z = 0; z < layers; ++z)
        for (long y = 0; y < n[1]; ++y)
            for (long x = 0; x < n[0]; ++x) {
                memset(&d[m], 0, sizeof d[m]);
                d[m].position.x = lo[0] + r + (double)x * h;
                d[m].position.y = lo[1] + r + (double)y * h;
                d[m].position.z = lo[2] + r + (double)z * h;
                d[m].radius = r;
                d[m].material = s->pour.material;
                ++m;
            }
    w = sd_check_world(s);
    int ok = w != NULL;
    for (size_t i = 0; ok && i < s->wall_count; ++i) {
        const sd_scene_wall *wl = &s->walls[i];
        ok = (wl->kind == 0 ? sd_world_add_plane(w, wl->name, wl->point, wl->normal, wl->material, &err)
                            : sd_world_add_box(w, wl->name, wl->lo, wl->hi, wl->open_faces, wl->material, &err)) >= 0;
    }
    ok = ok && sd_world_add_spheres(w, total, d, &err) == SD_OK && sd_world_prepare(w, &err) == SD_OK;
    free(d);
    if (!ok) {
        sd_world_destroy(w);
        return NULL;
    }
    *count = total;
    return w;
}

void sd_check_time(const sd_scene *s, sd_world *w, size_t total, long steps, sd_check_trial *t)
{
    memset(t, 0, sizeof *t);
    t->ok = 1;
    sd_world *tw = w;
    if (s->pour.given && s->pour.count > 0) {
        /* the grid solver is threaded from SD_GRID_PARALLEL_MIN particles:
         * a bed of at least that many (or all) is timed as the run goes */
        size_t want = total < 2 * SD_GRID_PARALLEL_MIN ? total : 2 * SD_GRID_PARALLEL_MIN;
        tw = sd_check_bed(s, want, &t->particles);
        if (!tw) {
            tw = w;
            t->particles = sd_world_particle_count(w);
        } else {
            t->bed = 1;
        }
    } else {
        t->particles = sd_world_particle_count(w);
    }
    t->threads = sd_world_threads(tw);
    sd_error err;
    memset(&err, 0, sizeof err);
    double t0 = sd_check_now(), psteps = 0, plain_seconds = 0, plain_psteps = 0;
    long limit = steps < 200 ? steps : 200, plain = 0;
    for (;;) {
        /* enough: 0.25 s of steps that did not insert (at least 2); when
         * every step inserts, 2 steps and 1 s in all */
        double spent = sd_check_now() - t0;
        if (t->steps >= limit || (plain >= 2 && plain_seconds >= 0.25) || (plain < 2 && t->steps >= 2 && spent >= 1.0))
            break;
        size_t before = sd_world_particle_count(tw);
        double s0 = sd_check_now();
        if (sd_world_step(tw, 1, &err) != SD_OK) {
            char buf[400];
            sd_error_format(&err, buf, sizeof buf);
            snprintf(t->msg, sizeof t->msg, "the trial run stopped at step %ld: %s", sd_world_step_count(tw), buf);
            t->ok = 0;
            break;
        }
        double dts = sd_check_now() - s0, ps = 0.5 * (double)(before + sd_world_particle_count(tw));
        psteps += ps;
        t->steps++;
        if (sd_world_particle_count(tw) > before) { /* an insertion placed particles in this step */
            t->insert_steps++;
            t->insert_seconds += dts;
        } else {
            plain++;
            plain_seconds += dts;
            plain_psteps += ps;
        }
    }
    t->seconds = sd_check_now() - t0;
    if (!t->bed && sd_world_particle_count(tw) > t->particles) /* an insertion's first particles went in */
        t->particles = sd_world_particle_count(tw);
    sd_stats st;
    sd_world_stats(tw, &st);
    t->contacts = st.contacts + st.wall_contacts;
    if (plain > 0 && plain_psteps > 0) /* the placement once, the steps scaled */
        t->estimate = plain_seconds / plain_psteps * (double)total * (double)steps + t->insert_seconds;
    else if (t->steps > 0 && psteps > 0)
        t->estimate = t->seconds / psteps * (double)total * (double)steps;
    else if (t->steps > 0)
        t->estimate = t->seconds / (double)t->steps * (double)steps;
    /* the mesh walls: what they add to the particles against their facets
     * (cli/check_mesh.c); the probes take the largest particle and its material */
    double r = 0;
    int mat = 0;
    for (size_t k = 0; k < sd_world_particle_count(tw); ++k) {
        sd_particle_state ps;
        if (sd_world_get_particle(tw, k, &ps) == SD_OK && ps.radius > r) {
            r = ps.radius;
            mat = ps.material;
        }
    }
    if (!(r > 0) && s->pour.given) {
        r = s->pour.radius;
        mat = s->pour.material;
    }
    sd_check_mesh_time(s, r, mat, &t->mesh);
    sd_check_mesh_part(&t->mesh, r, total, steps);
    if (t->mesh.ok)
        t->estimate += t->mesh.seconds;
    if (tw != w)
        sd_world_destroy(tw);
}

int sd_check_print_time(FILE *f, const sd_world *w, const sd_check_trial *t, size_t total, long steps,
                        size_t poured)
{
    char left[32];
    sd_duration_format(t->estimate, left, sizeof left);
    fprintf(f,
            "run time     %sabout %s on %d thread%s (timed trial: %ld steps of %s%zu particles in %.3g s",
            poured ? "at most " : "", left, t->threads, t->threads == 1 ? "" : "s", t->steps,
            t->bed ? "a bed of the pour's " : "", t->particles, t->seconds);
    fprintf(f, ", scaled to %ld steps of %zu particles%s", steps, total, poured ? " with every poured sphere in" : "");
    if (t->insert_steps) /* placement is paid once per particle, not per step */
        fprintf(f, "; %ld of its steps placed inserted particles, in %.3g s, counted once", t->insert_steps,
                t->insert_seconds);
    if (t->mesh.ok)
        fprintf(f, "; the particles against mesh walls timed apart, below");
    fprintf(f, "; rough, within a factor of 2-3)\n");
    if (t->mesh.ok) {
        char part[32];
        sd_duration_format(t->mesh.seconds, part, sizeof part);
        fprintf(f,
                "mesh walls   %s of it: %zu particles against the facets of %zu mesh wall%s (their %.4g m^2 over a "
                "particle's footprint (2 r)^2, at most all), %.3g s a particle-step more, timed on %zu spheres resting "
                "on the facets against the same spheres alone for %ld steps\n",
                part, t->mesh.against, t->mesh.meshes, t->mesh.meshes == 1 ? "" : "s", t->mesh.area,
                t->mesh.seconds_per_pstep, t->mesh.probes, t->mesh.steps);
    }
    /* what the first steps cannot see: the particles added later, the
     * contacts of a bed that settles, mesh walls reached later */
    size_t meshes = 0;
    for (size_t k = 0; k < sd_world_wall_count(w); ++k) {
        sd_mesh_info mi;
        meshes += sd_world_get_mesh(w, (int)k, &mi) == SD_OK;
    }
    int fewer = !t->bed && t->particles < total, loose = (double)t->contacts < 0.5 * (double)t->particles;
    if (t->mesh.ok)
        meshes = 0; /* timed apart above */
    if (t->steps < steps && (fewer || loose || meshes)) { /* else the trial was the whole run */
        fprintf(f, "untimed      the trial ran the first %ld steps with %zu", t->steps, t->particles);
        if (fewer)
            fprintf(f, " of the %zu particles (the rest come later)", total);
        else
            fprintf(f, " particles");
        fprintf(f, " and %ld contacts", t->contacts);
        fprintf(f, "; not timed:%s%s%s%s", fewer ? " the particles added later" : "",
                loose ? (fewer ? "," : "") : "", loose ? " the contacts of a settled bed" : "",
                meshes ? ((fewer || loose) ? ", mesh-wall contacts" : " mesh-wall contacts") : "");
        if (meshes)
            fprintf(f, " (%zu mesh wall%s)", meshes, meshes == 1 ? "" : "s");
        fprintf(f, ": the run may take longer than this estimate\n");
    }
    int n = 0;
    /* the shown value is compared, so the text and the warning agree */
    if (sd_duration_shown(t->estimate) > 600.0) {
        fprintf(f,
                "warning      the run is estimated at %s, more than 10 minutes: try it first with --steps N "
                "(a short run), or more --threads\n",
                left);
        n++;
    }
    return n;
}

/* The scaled copies of template `name` that insertions made (named
 * NAME_iIeEsK by sd_world_add_insertion): one per size class. */
static size_t sd_check_size_classes(const sd_world *w, const char *name)
{
    char prefix[64];
    int len = snprintf(prefix, sizeof prefix, "%.40s_i", name);
    size_t n = 0;
    for (size_t k = 0; k < sd_world_shape_count(w); ++k) {
        sd_shape_info sk;
        if (sd_world_get_shape(w, k, &sk) != SD_OK || !sk.name || strncmp(sk.name, prefix, (size_t)len) != 0)
            continue;
        /* the rest is IeEsK: digits, 'e', digits, 's', digits */
        const char *p = sk.name + len;
        int ok = 1;
        for (int part = 0; part < 3 && ok; ++part) {
            const char *d = p;
            while (*p >= '0' && *p <= '9')
                ++p;
            ok = p > d && (part == 2 ? *p == 0 : *p == (part == 0 ? 'e' : 's'));
            if (ok && part < 2)
                ++p;
        }
        n += ok;
    }
    return n;
}

void sd_check_shapes_text(const sd_scene *s, const sd_world *w, char *buf, size_t size)
{
    size_t n = 0, used = 0; /* the composites' element shapes and checkpoint copies are hidden */
    for (size_t k = 0; k < s->shape_count; ++k)
        n += !s->shapes[k].hidden;
    int wrote = snprintf(buf, size, "%zu shape%s", n, n == 1 ? "" : "s");
    used = wrote > 0 ? (size_t)wrote : 0;
    int listed = 0;
    for (size_t k = 0; k < s->shape_count && used + 1 < size; ++k) {
        const char *name = s->shapes[k].name;
        size_t classes = s->shapes[k].hidden ? 0 : sd_check_size_classes(w, name);
        if (classes < 2)
            continue;
        if (n == 1)
            wrote = snprintf(buf + used, size - used, " in %zu sizes", classes);
        else
            wrote = snprintf(buf + used, size - used, "%s%s in %zu sizes", listed ? ", " : " (", name, classes);
        used += wrote > 0 ? (size_t)wrote : 0;
        used = used < size ? used : size; /* cut: the loop ends */
        listed++;
    }
    if (listed && n > 1 && used + 1 < size)
        snprintf(buf + used, size - used, ")");
}

/* gravity that is 9.81 m/s^2 written in another unit */
static const char *sd_check_gravity_unit(double g)
{
    if (g > 900.0 && g < 1100.0)
        return "cm/s^2 (981)";
    if (g > 9000.0 && g < 11000.0)
        return "mm/s^2 (9810)";
    if (g > 0.009 && g < 0.011)
        return "km/s^2 (0.00981)";
    return NULL;
}

int sd_check_units(FILE *f, const sd_scene *s, const sd_check_counts *c, double tc, double dt)
{
    int n = 0;
    if (c->big_radius > 0.5) {
        fprintf(f,
                "warning      particles of radius up to %.4g m (%.4g kg each at %.4g kg/m^3) look like a unit "
                "mistake: scene values are SI (m, kg, s), so a 1 mm radius is radius: 0.001\n",
                c->big_radius, c->big_mass, c->big_density);
        n++;
    }
    if (isfinite(tc) && tc > 0 && dt > 0 && tc / dt > 1000.0) {
        fprintf(f,
                "warning      dt = %.4g s is %.0f times below the shortest contact duration %.4g s (about 50 steps "
                "resolve a contact): a unit mistake? scene values are SI (s, m, kg)\n",
                dt, tc / dt, tc);
        n++;
    }
    const sd_v3d g = s->world.gravity;
    double gn = sqrt(g.x * g.x + g.y * g.y + g.z * g.z);
    const char *unit = sd_check_gravity_unit(gn);
    if (unit) {
        fprintf(f,
                "warning      gravity %.4g m/s^2 looks like 9.81 m/s^2 written in %s: scene values are SI "
                "(m/s^2)\n",
                gn, unit);
        n++;
    }
    for (size_t i = 0; i < s->material_count; ++i) {
        double rho = s->materials[i].def.density;
        if (rho > 0 && rho < 20.0) {
            fprintf(f,
                    "warning      material '%s' has density %.4g kg/m^3, like a gas: g/cm^3? scene values are SI "
                    "(kg/m^3; glass is 2500)\n",
                    s->materials[i].name, rho);
            n++;
        }
        double e = s->materials[i].def.youngs_modulus;
        if (e > 0 && e < 1000.0) {
            fprintf(f,
                    "warning      material '%s' has Young's modulus %.4g Pa, softer than any solid: GPa or MPa? "
                    "scene values are SI (Pa; glass is 6.3e10)\n",
                    s->materials[i].name, e);
            n++;
        }
    }
    return n;
}

void sd_check_format_bytes(double b, char *buf, size_t size)
{
    if (b < 1e3)
        snprintf(buf, size, "%.0f bytes", b);
    else if (b < 1e6)
        snprintf(buf, size, "%.1f kB", b / 1e3);
    else if (b < 1e9)
        snprintf(buf, size, "%.1f MB", b / 1e6);
    else
        snprintf(buf, size, "%.2f GB", b / 1e9);
}

void sd_check_print_stop(FILE *f, const sd_scene *s)
{
    if (s->stop_given)
        fprintf(f,
                "stop         at the first stats row (every %ld steps) from t = %.4g s whose %s is below "
                "%.4g %s (simulation.stop_when): the run may end before its steps; the run time and output below "
                "are for all of them\n",
                s->output.stats_every, s->stop_after, s->stop_speed_below > 0 ? "mean speed" : "kinetic energy",
                s->stop_speed_below > 0 ? s->stop_speed_below : s->stop_ke_below,
                s->stop_speed_below > 0 ? "m/s" : "J");
}

void sd_check_print_grid(FILE *f, const sd_scene *s)
{
    sd_pour_def pd;
    sd_outlet_def od;
    if (sd_scene_get_pour(s, &pd))
        fprintf(f,
                "pour         %ld spheres of radius %.4g m (material %s), sheets at z = %.4g m, %.4g per s from "
                "t = %.4g s, speeds vz in +-%.3g m/s, vx, vy in +-%.3g m/s\n",
                (long)pd.count, pd.radius, sd_scene_material_name(s, (size_t)pd.material), pd.height,
                pd.layers_per_second, pd.start_time, pd.vz_range, pd.vh_range);
    if (sd_scene_get_outlet(s, &od))
        fprintf(f, "outlet       hole x in [%.4g, %.4g] m, y in [%.4g, %.4g] m in the box floor, opens at t = %.4g s\n",
                od.x0, od.x1, od.y0, od.y1, od.open_at);
}

void sd_check_print_output(FILE *f, const sd_scene *s, const sd_world *w, size_t total, long frames, long rows,
                           double end_time, size_t poured)
{
    sd_output_def od = {.directory = ".",
                        .vtk = (s->output.formats & SD_OUT_VTK) != 0,
                        .csv = (s->output.formats & SD_OUT_CSV) != 0,
                        .scene = s->path,
                        .shapes = (s->output.formats & SD_OUT_SHAPES) != 0,
                        .shape_resolution = s->output.shape_resolution,
                        .dump = (s->output.formats & SD_OUT_DUMP) != 0,
                        .h5md = (s->output.formats & SD_OUT_H5MD) != 0,
                        .dump_box = {s->world.dimension, s->world.periodic, s->world.domain_lo, s->world.domain_hi}};
    sd_output_size osz;
    sd_error oerr;
    memset(&oerr, 0, sizeof oerr);
    if (sd_output_estimate(&od, w, total, frames, rows, end_time, &osz, &oerr) != SD_OK)
        return;
    char tb[32], fb[32];
    sd_check_format_bytes(osz.total, tb, sizeof tb);
    sd_check_format_bytes(osz.frame_particles + osz.frame_walls + osz.frame_shapes, fb, sizeof fb);
    fprintf(f, "output       about %s (%.0f bytes): ", tb, osz.total);
    if (od.vtk)
        fprintf(f, "%ld frames x %s%s", frames, fb, poured ? " (at most: all poured spheres in)" : "");
    if (od.csv)
        fprintf(f, "%s%ld stats rows x %.0f bytes", od.vtk ? ", " : "", rows, osz.stats_row);
    if (od.dump) {
        sd_check_format_bytes(osz.frame_dump, fb, sizeof fb);
        fprintf(f, "%s%ld trajectory.dump snapshots x %s", od.vtk || od.csv ? ", " : "", frames, fb);
    }
    if (od.h5md) {
        sd_check_format_bytes(osz.frame_h5md, fb, sizeof fb);
        fprintf(f, "%s%ld trajectory.h5md frames x %s", od.vtk || od.csv || od.dump ? ", " : "", frames, fb);
    }
    fprintf(f, "\n");
}

/* The time step's reasons (docs/physics.md "Time step"): which limit set
 * the recommended step and, under the volume law, what the face contacts
 * do at the scene's dt. Returns the number of warnings printed. */
int sd_check_print_dt(FILE *f, const sd_world *w)
{
    sd_dt_report r;
    sd_world_dt_report(w, &r);
    double dt = sd_world_dt(w);
    int n = 0;
    if (isfinite(r.recommended))
        fprintf(f, "dt limit     the recommended step is set by: %s\n", r.limit);
    if (r.mesh_radius > 0) {
        /* the thin-wall rule (docs/mesh-walls.md): a closed mesh part of any
         * thickness holds a particle while its centre stays in front of the
         * face it entered, i.e. its overlap below its radius */
        double pct = 100 * r.mesh_depth / r.mesh_radius, lim = r.guard > 0 && r.guard < 1 ? r.guard : 1;
        fprintf(f,
                "mesh walls   an impact at %.3g m/s (the speed of the contact estimate) sinks a particle of radius %.3g m by %.3g m, "
                "%.0f %% of its radius (elastic): a closed mesh part of any thickness holds it while that stays "
                "below 100 %%%s\n",
                r.speed, r.mesh_radius, r.mesh_depth, pct,
                r.guard > 0 ? "; the overlap guard stops a run deeper than simulation.max_overlap" : "");
        if (pct >= 100 * lim) {
            fprintf(f,
                    "warning      an impact at %.3g m/s overlaps a particle by %.0f %% of its radius on a mesh wall, "
                    "beyond %s: %s; raise the stiffness or lower the speed\n",
                    r.speed, pct, r.guard > 0 && r.guard < 1 ? "the overlap guard's limit" : "its radius",
                    r.guard > 0 && r.guard < 1 ? "the run will stop there"
                                               : "it may pass through a mesh part thinner than its size");
            n++;
        }
    }
    if (r.volume_skipped) {
        fprintf(f, "warning      out of memory: the volume-law time-step estimates were not made, so the "
                   "recommended step leaves out the sharp polyhedra's face contacts\n");
        n++;
    }
    if (!r.volume)
        return n;
    if (r.onset > 0)
        fprintf(f,
                "volume law   regularised below V0 = %.3g m^3 at dt = %.4g s (a face sunk %.3g m, %.3g %% of R_eq = "
                "%.4g m; volume_face_omega_dt): below it F is linear in V, above it seed 000's law\n",
                r.onset, dt, r.onset_depth, 100 * r.onset_depth / r.onset_radius, r.onset_radius);
    fprintf(f, "face landing flat at %.3g m/s: lasts %.4g s (%.1f steps), %.3g m deep%s; seed 000's unregularised "
               "law: %.4g s\n",
            r.speed, r.impact, r.impact / dt, r.impact_depth,
            r.onset > 0 ? (r.impact_inside ? ", inside the regularised range of that pair" : ", beyond the regularised range of that pair") : "",
            r.seed_impact);
    if (isfinite(r.rest_dt)) {
        int resolved = r.onset > 0 ? r.rest_inside || dt <= r.rest_dt : dt <= r.rest_dt;
        fprintf(f,
                "resting face under its weight: %.3g m deep under seed 000's law, where dF/dd needs dt <= %.4g s "
                "(the resting-face limit, omega dt <= 1)%s\n",
                r.rest_depth, r.rest_dt,
                r.onset > 0 && r.rest_inside ? "; at this dt it rests inside the regularised range, resolved with "
                                               "omega dt <= volume_face_omega_dt"
                                             : "");
        if (!resolved) {
            fprintf(f,
                    "warning      dt = %.4g s is above the resting-face limit %.4g s: a face resting under a light "
                    "load buzzes instead of settling (the face contact is infinitely stiff at zero overlap); set "
                    "materials[].volume_face_omega_dt: 0.5 to regularise it, or lower dt\n",
                    dt, r.rest_dt);
            n++;
        }
    }
    if (r.onset == 0 && r.seed_impact < 5 * dt) {
        fprintf(f,
                "warning      a face landing flat lasts %.4g s, %.1f steps of dt = %.4g s: it gains energy; set "
                "materials[].volume_face_omega_dt: 0.5 to regularise it, or lower dt\n",
                r.seed_impact, r.seed_impact / dt, dt);
        n++;
    }
    return n;
}

void sd_check_print_ranks(FILE *f, const sd_scene *s, const sd_world *w, long ranks)
{
    const char *note =
#ifdef SHAPEDEM_HAVE_MPI
        "";
#else
        " [this build has no MPI: configure with -DSHAPEDEM_MPI=ON]";
#endif
    int r = (int)ranks;
    sd_mpi_split_req req = {{s->mpi_split[0], s->mpi_split[1], s->mpi_split[2]}, s->mpi_split_line};
    sd_mpi_grid *g = malloc(sizeof *g);
    size_t *count = calloc((size_t)r, sizeof *count);
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_status st = g && count ? sd_mpi_plan(w, &req, r, g, &err) : SD_ERR_MEMORY;
    if (st != SD_OK) {
        char msg[1024];
        sd_error_format(&err, msg, sizeof msg);
        fprintf(f, "warning      %ld MPI ranks: %s%s\n", ranks, st == SD_ERR_MEMORY && !msg[0] ? "out of memory" : msg,
                note);
        free(g);
        free(count);
        return;
    }
    size_t n = sd_world_particle_count(w);
    for (size_t k = 0; k < n; ++k) {
        sd_particle_state p;
        sd_world_get_particle(w, k, &p);
        double x[3] = {p.position.x, p.position.y, p.position.z};
        count[sd_mpi_grid_rank(g, x, p.id)]++;
    }
    const char *ask = s->mpi_split_line ? "as simulation.mpi_split asks" : "simulation.mpi_split auto: least cut area";
    fprintf(f, "ranks        %d: %d x %d x %d boxes along x, y, z (%s), %s (particles at the start)%s\n", r, g->n[0],
            g->n[1], g->n[2], ask, sd_mpi_grid_how(g), note);
    for (int c = 0; c < r; ++c) {
        char box[200];
        sd_mpi_grid_box_text(g, c, box, sizeof box);
        fprintf(f, "  rank %-6d %s m: %zu particles\n", c, box, count[c]);
    }
    free(g);
    free(count);
}
