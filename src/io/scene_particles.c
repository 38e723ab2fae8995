/* scene_particles.c — the particles: section of a scene: the lattice,
 * random, list and csv generators (the csv file read by io/csv.c, or a
 * checkpoint of another run by io/scene_from.c, moved by shift), their
 * spheres or bodies of a shape, orientations and velocities; and the
 * particle budget every generator and the pour count against.
 *
 * Invariant: a generator is filled only from checked values, with its
 * material and shape references resolved; the scene's particle total
 * stays within 1e9 and the machine's memory, else the scene is refused
 * before anything is built; every error names the file, line and key.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/csv.h"
#include "io/scene_from.h"
#include "io/scene_keys.h"
#include "io/scene_sections.h"

/* Bytes a particle takes while the world is built and run: `check`
 * measures 639-665 allocated bytes per sphere in the general engine (world
 * arrays and pair lists of spheres-settle-8000, and of copies with 1e6 and
 * 4e7 spheres) and docs/grid-solver.md 420-455 resident in the grid
 * solver; the lower ends are taken. */
#define SD_BYTES_PER_PARTICLE_CELLS 640.0
#define SD_BYTES_PER_PARTICLE_GRID 420.0
#define SD_SCENE_MAX_PARTICLES 1e9

/* The memory this process may use: 90 % of the machine's physical memory
 * (sysconf; the rest is the system's), or the address-space limit (ulimit
 * -v) when that is lower. what names which; *phys is the whole memory. */
static double sd_memory_limit(const char **what, double *phys)
{
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    *phys = pages > 0 && page > 0 ? (double)pages * (double)page : HUGE_VAL;
    double lim = 0.9 * *phys;
    *what = "memory this machine has";
    struct rlimit rl;
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY && (double)rl.rlim_cur < lim) {
        lim = (double)rl.rlim_cur;
        *what = "address space this process may use (ulimit -v)";
    }
    return lim;
}

/* Adds n particles (of the generator or pour at line/key) to the scene's
 * total, and refuses the scene before anything is built when the total
 * passes 1e9 or its memory will not fit: a one-digit slip in a count
 * (count: [20, 20, 100000]) would otherwise fill the machine for a minute
 * before failing. */
sd_status sd_count_particles(sd_parse *p, double n, int line, const char *key)
{
    p->total += n;
    if (p->total > SD_SCENE_MAX_PARTICLES)
        return sd_fail(p, line, key, "the scene makes %.0f particles up to here (%.0f here), more than the %g a scene "
                       "may have", p->total, n, SD_SCENE_MAX_PARTICLES);
    const char *what;
    double phys, per = p->s->world.solver == SD_SOLVER_GRID ? SD_BYTES_PER_PARTICLE_GRID : SD_BYTES_PER_PARTICLE_CELLS;
    double need = per * p->total, lim = sd_memory_limit(&what, &phys);
    if (need > lim)
        return sd_fail(p, line, key,
                       "the scene makes %.0f particles up to here (%.0f here), which need about %.1f GiB "
                       "(%.0f bytes each), more than the %.1f GiB of %s%s",
                       p->total, n, need / 1073741824.0, per, (lim < 0.9 * phys ? lim : phys) / 1073741824.0, what,
                       lim < 0.9 * phys ? "" : " (90 % of it is taken as usable)");
    return SD_OK;
}

static sd_status sd_parse_list(sd_parse *p, sd_scene_generator *g, yaml_node_t *list,
                               const char *path, int has_material)
{
    size_t n = sd_yaml_seq_len(list);
    char ep[96], key[128], section[96];
    sd_yaml_value v;
    sd_status st;
    sd_yaml_kp(section, sizeof section, path, "spheres"); /* particles[i].spheres */
    if (n == 0)
        return sd_fail(p, sd_yaml_line(list), sd_yaml_kp(key, sizeof key, path, "spheres"),
                       "expected at least one sphere");
    g->list = sd_calloc(n, sizeof *g->list);
    g->list_lines = sd_calloc(n, sizeof *g->list_lines);
    g->list_shape = sd_calloc(n, sizeof *g->list_shape);
    g->list_orient = sd_calloc(n, sizeof *g->list_orient);
    g->list_quat = sd_calloc(n, sizeof *g->list_quat);
    if (!g->list || !g->list_lines || !g->list_shape || !g->list_orient || !g->list_quat)
        return sd_yaml_oom(&p->y);
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m;
        if ((st = sd_yaml_entry(&p->y, list, i, section, "{position: [x, y, z], radius: r}", ep, sizeof ep, &m)))
            return st;
        sd_sphere_def *d = &g->list[i];
        if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_SPHERE, SD_KIND_ALL, "", ep, sd_yaml_line(m))))
            return st;
        sd_yaml_get(&p->y, m, SD_SEC_SPHERE, "position", ep, &v);
        d->position = sd_parse_v3(v.v);
        /* A sphere (radius) or a body of a shape (its own, or the generator's). */
        sd_yaml_value rv;
        int has_radius = sd_yaml_get(&p->y, m, SD_SEC_SPHERE, "radius", ep, &rv);
        g->list_shape[i] = -1;
        if (sd_yaml_get(&p->y, m, SD_SEC_SPHERE, "shape", ep, &v)) {
            if (has_radius)
                return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, ep, "shape"),
                               "give either radius (a sphere) or shape, not both (radius is at "
                               "line %d)",
                               rv.line);
            if ((st = sd_shape_ref(p, v.str, v.line, sd_yaml_kp(key, sizeof key, ep, "shape"),
                                   &g->list_shape[i])))
                return st;
        } else if (has_radius) {
            d->radius = rv.num;
        } else if (g->shape >= 0) {
            g->list_shape[i] = g->shape;
        } else {
            return sd_fail(p, sd_yaml_line(m), sd_yaml_kp(key, sizeof key, ep, "radius"),
                           "missing required key 'radius' (or shape: NAME, here or as the "
                           "generator's shape)");
        }
        g->list_orient[i] = g->orient;
        memcpy(g->list_quat[i], g->quat, sizeof g->list_quat[i]);
        if (sd_yaml_get(&p->y, m, SD_SEC_SPHERE, "orientation", ep, &v)) {
            if (g->list_shape[i] < 0)
                return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, ep, "orientation"),
                               "orientation applies to bodies of a shape only (a sphere has none)");
            g->list_orient[i] = (sd_scene_orient)v.choice;
            memcpy(g->list_quat[i], v.q, sizeof g->list_quat[i]);
        }
        d->velocity = sd_yaml_get(&p->y, m, SD_SEC_SPHERE, "velocity", ep, &v) ? sd_parse_v3(v.v) : g->velocity;
        d->angular_velocity = sd_yaml_get(&p->y, m, SD_SEC_SPHERE, "angular_velocity", ep, &v)
                                  ? sd_parse_v3(v.v)
                                  : g->angular_velocity;
        if (sd_yaml_get(&p->y, m, SD_SEC_SPHERE, "material", ep, &v)) {
            if ((st = sd_material_ref(p, v.str, v.line, sd_yaml_kp(key, sizeof key, ep, "material"),
                                      &d->material)))
                return st;
        } else if (has_material) {
            d->material = g->material;
        } else {
            return sd_fail(p, sd_yaml_line(m), sd_yaml_kp(key, sizeof key, ep, "material"),
                           "missing material: give it here or as the generator's material");
        }
        g->list_lines[i] = sd_yaml_line(m);
        g->list_count = i + 1;
    }
    return SD_OK;
}

sd_status sd_parse_particles(sd_parse *p, yaml_node_t *list, int line)
{
    sd_scene *s = p->s;
    size_t n = sd_yaml_seq_len(list);
    char path[64], key[96], kind_name[64];
    sd_yaml_value v;
    sd_status st;
    if (n == 0)
        return sd_fail(p, line, "particles", "expected at least one generator, got %s",
                       list ? "an empty list" : "nothing");
    s->generators = sd_calloc(n, sizeof *s->generators);
    if (!s->generators)
        return sd_yaml_oom(&p->y);
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m;
        if ((st = sd_yaml_entry(&p->y, list, i, "particles", "(generator: ..., ...)", path, sizeof path, &m)))
            return st;
        sd_scene_generator *g = &s->generators[i];
        s->generator_count = i + 1; /* so sd_scene_free sees its lists */
        g->line = sd_yaml_line(m);
        /* The generator decides which keys apply, so read it first. */
        yaml_node_t *gn = sd_yaml_map_get(&p->y, m, "generator");
        snprintf(key, sizeof key, "%s.generator", path);
        if (!gn)
            return sd_fail(p, g->line, key,
                           "missing required key 'generator' (lattice, random, list or csv)");
        if ((st = sd_yaml_read_value(&p->y, sd_scene_key_find(SD_SEC_PARTICLES, "generator"), gn, key, &v)))
            return st;
        g->kind = (sd_gen_kind)v.choice;
        snprintf(kind_name, sizeof kind_name, "a %s generator", v.str);
        if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_PARTICLES, 1u << g->kind, kind_name, path, g->line)))
            return st;

        int has_material = sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "material", path, &v);
        if (has_material &&
            (st = sd_material_ref(p, v.str, v.line, sd_yaml_kp(key, sizeof key, path, "material"),
                                  &g->material)))
            return st;
        sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "velocity", path, &v);
        g->velocity = sd_parse_v3(v.v);
        sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "velocity_jitter", path, &v);
        g->velocity_jitter = v.num;
        sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "angular_velocity", path, &v);
        g->angular_velocity = sd_parse_v3(v.v);
        /* Spheres (radius) or bodies of a shape (shape), exactly one. */
        sd_yaml_value rv;
        int has_radius = sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "radius", path, &rv);
        if (has_radius) {
            g->radius_min = rv.lo;
            g->radius_max = rv.hi;
        }
        g->shape = -1;
        if (sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "shape", path, &v)) {
            sd_yaml_kp(key, sizeof key, path, "shape");
            if (has_radius)
                return sd_fail(p, v.line, key,
                               "give either radius (spheres) or shape (bodies of a shape), not "
                               "both (radius is at line %d)",
                               rv.line);
            if ((st = sd_shape_ref(p, v.str, v.line, key, &g->shape)))
                return st;
        } else if (!has_radius && g->kind != SD_GEN_LIST && g->kind != SD_GEN_CSV) {
            return sd_fail(p, g->line, sd_yaml_kp(key, sizeof key, path, "radius"),
                           "missing required key 'radius' (or shape: NAME for bodies of a shape)");
        }
        sd_yaml_value ov;
        int has_orient = sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "orientation", path, &ov);
        g->orient = has_orient ? (sd_scene_orient)ov.choice : SD_ORIENT_RANDOM;
        memcpy(g->quat, ov.q, sizeof g->quat);
        if (has_orient && g->shape < 0 && g->kind != SD_GEN_LIST && g->kind != SD_GEN_CSV)
            return sd_fail(p, ov.line, sd_yaml_kp(key, sizeof key, path, "orientation"),
                           "orientation applies to bodies of a shape only (give shape: NAME)");

        switch (g->kind) {
        case SD_GEN_LATTICE: {
            sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "origin", path, &v);
            g->origin = sd_parse_v3(v.v);
            sd_yaml_value sp;
            sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "spacing", path, &sp);
            g->spacing = sd_parse_v3(sp.v);
            g->spacing_line = sp.line; /* a shape's bound is checked at generation */
            for (int a = 0; a < 3; ++a)
                if (sp.v[a] < 2.0 * g->radius_max)
                    return sd_fail(p, sp.line, sd_yaml_kp(key, sizeof key, path, "spacing"),
                                   "expected a spacing >= 2 x the largest radius (%g m), got %g "
                                   "along %c: the spheres would overlap",
                                   2.0 * g->radius_max, sp.v[a], 'x' + a);
            sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "count", path, &v);
            double total = v.v[0] * v.v[1] * v.v[2];
            if (v.iv[0] > 100000000 || v.iv[1] > 100000000 || v.iv[2] > 100000000 || total > 1e9)
                return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "count"),
                               "expected at most 1e9 spheres in all, got %g", total);
            for (int a = 0; a < 3; ++a)
                g->count[a] = (int)v.iv[a];
            break;
        }
        case SD_GEN_RANDOM: {
            sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "box", path, &v);
            g->box_lo = v.box_lo;
            g->box_hi = v.box_hi;
            g->box_line = v.line;
            double ext[3] = {v.box_hi.x - v.box_lo.x, v.box_hi.y - v.box_lo.y,
                             v.box_hi.z - v.box_lo.z};
            for (int a = 0; a < 3; ++a)
                if (ext[a] < 2.0 * g->radius_max)
                    return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "box"),
                                   "the box is %g m wide along %c, less than the largest "
                                   "diameter (%g m)",
                                   ext[a], 'x' + a, 2.0 * g->radius_max);
            sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "number", path, &v);
            if (v.integer > 1000000000)
                return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "number"),
                               "expected at most 1e9 spheres, got %lld", v.integer);
            g->number = (long)v.integer;
            break;
        }
        case SD_GEN_LIST:
            sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "spheres", path, &v);
            if ((st = sd_parse_list(p, g, v.node, path, has_material)))
                return st;
            if (has_orient) {
                int shaped = 0;
                for (size_t k = 0; k < g->list_count; ++k)
                    shaped |= g->list_shape[k] >= 0;
                if (!shaped)
                    return sd_fail(p, ov.line, sd_yaml_kp(key, sizeof key, path, "orientation"),
                                   "orientation applies to bodies of a shape only (no entry has "
                                   "a shape)");
            }
            break;
        case SD_GEN_CSV:
            sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "file", path, &v);
            sd_yaml_kp(key, sizeof key, path, "file");
            if (!sd_resolve(p->path, v.str, g->file, sizeof g->file))
                return sd_fail(p, v.line, key, "path too long");
            /* a checkpoint of another run (scene_from.c), else a CSV file */
            if ((st = sd_from_is_checkpoint(g->file) ? sd_from_checkpoint_read(p->s, g, key, v.line, p->err)
                                                     : sd_csv_read(p->s, g, key, v.line, p->err)))
                return st;
            if (sd_yaml_get(&p->y, m, SD_SEC_PARTICLES, "shift", path, &v)) {
                /* the whole bed moved, e.g. into new equipment */
                for (size_t k = 0; k < g->list_count; ++k) {
                    g->list[k].position.x += v.v[0];
                    g->list[k].position.y += v.v[1];
                    g->list[k].position.z += v.v[2];
                }
            }
            if (has_orient) {
                int shaped = 0;
                for (size_t k = 0; k < g->list_count; ++k)
                    shaped |= g->list_shape[k] >= 0;
                if (!shaped)
                    return sd_fail(p, ov.line, sd_yaml_kp(key, sizeof key, path, "orientation"),
                                   "orientation applies to bodies of a shape only (no row has a "
                                   "shape)");
            }
            break;
        }
        static const char *const count_key[] = {"count", "number", "spheres", "file"};
        const char *ck = count_key[g->kind];
        double made = g->kind == SD_GEN_LATTICE  ? (double)g->count[0] * g->count[1] * g->count[2]
                      : g->kind == SD_GEN_RANDOM ? (double)g->number
                                                 : (double)g->list_count;
        if ((st = sd_count_particles(p, made, sd_yaml_line(sd_yaml_map_get(&p->y, m, ck)), sd_yaml_kp(key, sizeof key, path, ck))))
            return st;
    }
    return SD_OK;
}

