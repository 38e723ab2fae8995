/* scene_parse.c — reads a scene file (YAML) into an sd_scene: the section
 * rules and the cross-key checks.
 *
 * The file is loaded and its values read by the typed reader
 * (io/yaml_read.c), which checks each mapping against the key table
 * (scene_keys.c): unknown keys, keys of another generator or wall type,
 * duplicate keys, wrong types, out-of-range values and missing required
 * keys are all errors that name the file, the 1-based line and the dotted
 * key path (materials[1].density). Here: the root, simulation, materials,
 * interactions, walls, output, pour and outlet sections and what ties
 * keys together (exactly one of steps and duration, references by name,
 * the law needs); shapes: and particles: have their own files
 * (scene_shapes.c, scene_particles.c), their readers csv.c and mesh.c.
 *
 * Invariant: sd_scene_load returns either a scene in which every value has
 * been checked (types, ranges, material names, cross-key rules such as
 * "exactly one of steps and duration") or an error and no scene; it never
 * prints and never leaves anything allocated behind.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <yaml.h>

#include "contact/params.h" /* the law table's needs, for sd_check_laws */
#include "core/alloc.h"
#include "core/error.h"
#include "io/scene.h"
#include "io/scene_keys.h"
#include "io/scene_analysis.h"
#include "io/scene_process.h"
#include "io/scene_sections.h"
#include "io/yaml_read.h"
#include "mpi/mpi.h" /* SD_MPI_MAX_RANKS, for simulation.mpi_split */
#include "shape/shape.h" /* SD_SHAPE_POLYHEDRON, for the volume-law check */
#include "shape/surface.h" /* the range of output.shape_resolution */

/* ---- parse context and errors ------------------------------------------ */

sd_status sd_fail(sd_parse *p, int line, const char *key, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return sd_error_set(p->err, SD_ERR_INPUT, p->path, line, key, "%s", msg);
}

static int sd_find_material(const sd_scene *s, const char *name)
{
    for (size_t i = 0; i < s->material_count; ++i)
        if (!strcmp(s->materials[i].name, name))
            return (int)i;
    return -1;
}

sd_status sd_material_ref(sd_parse *p, const char *name, int line, const char *key, int *out)
{
    *out = sd_find_material(p->s, name);
    if (*out >= 0)
        return SD_OK;
    char known[300];
    size_t used = 0;
    known[0] = '\0';
    for (size_t i = 0; i < p->s->material_count && used + 1 < sizeof known; ++i) {
        int w = snprintf(known + used, sizeof known - used, "%s%s", i ? ", " : "",
                         p->s->materials[i].name);
        used += w > 0 ? (size_t)w : 0;
    }
    char esc[96];
    sd_escape(esc, sizeof esc, name, (size_t)-1);
    return sd_fail(p, line, key, "unknown material '%s' (materials: %s)", esc, known);
}

/* ---- sections ----------------------------------------------------------- */

/* simulation.stop_when: a condition io/run.c checks at each stats row.
 * An `after` at or past the run's end could never be checked: refused
 * rather than silently running the whole length. */
static sd_status sd_parse_stop(sd_parse *p, yaml_node_t *sim)
{
    sd_scene *s = p->s;
    yaml_node_t *m = sd_yaml_map_get(&p->y, sim, "stop_when");
    if (!m)
        return SD_OK;
    const char *path = "simulation.stop_when";
    sd_yaml_value v;
    sd_status st;
    s->stop_line = sd_yaml_line(m);
    if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_STOP, SD_KIND_ALL, "", path, s->stop_line)))
        return st;
    s->stop_given = 1;
    int has_ke = sd_yaml_get(&p->y, m, SD_SEC_STOP, "kinetic_energy_below", path, &v);
    s->stop_ke_below = has_ke ? v.num : 0.0;
    int ke_line = v.line;
    int has_speed = sd_yaml_get(&p->y, m, SD_SEC_STOP, "mean_speed_below", path, &v);
    s->stop_speed_below = has_speed ? v.num : 0.0;
    if (has_ke == has_speed)
        return sd_fail(p, has_ke ? ke_line : s->stop_line, "simulation.stop_when.kinetic_energy_below",
                       "expected one condition: kinetic_energy_below (J) or mean_speed_below (m/s), got %s",
                       has_ke ? "both" : "neither");
    int has_after = sd_yaml_get(&p->y, m, SD_SEC_STOP, "after", path, &v);
    s->stop_after = v.num;
    double end = (double)s->steps * s->world.dt;
    if (s->stop_after >= end)
        return sd_fail(p, has_after ? v.line : s->stop_line, "simulation.stop_when.after",
                       "expected a time before the run's end (%g s = %ld steps x dt), got %g s: the condition would "
                       "never be checked",
                       end, s->steps, s->stop_after);
    return SD_OK;
}

static sd_status sd_parse_simulation(sd_parse *p, yaml_node_t *root)
{
    sd_scene *s = p->s;
    yaml_node_t *sim = sd_yaml_map_get(&p->y, root, "simulation");
    const char *path = "simulation";
    sd_yaml_value v;
    sd_status st;
    if ((st = sd_yaml_check_map(&p->y, sim, SD_SEC_SIMULATION, SD_KIND_ALL, "", path, s->simulation_line)))
        return st;
    s->world = sd_world_def_default();

    sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "dimension", path, &v);
    if (v.integer != 3 && v.integer != 2)
        return sd_fail(p, v.line, "simulation.dimension", "expected 2 or 3, got %lld", v.integer);
    s->world.dimension = (int)v.integer;
    sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "local_damping", path, &v);
    if (!(v.num < 1.0))
        return sd_fail(p, v.line, "simulation.local_damping", "expected a coefficient in [0, 1), got %g", v.num);
    s->world.local_damping = v.num;
    sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "multi_contact", path, &v);
    s->world.multi_contact = v.choice == 1 ? SD_MULTI_CONTACT_SUM : SD_MULTI_CONTACT_AVERAGE;

    sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "dt", path, &v);
    s->world.dt = v.num;
    s->dt_line = v.line;

    sd_yaml_value steps, duration;
    int has_steps = sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "steps", path, &steps);
    int has_duration = sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "duration", path, &duration);
    if (has_steps && has_duration)
        return sd_fail(p, duration.line, "simulation.duration",
                       "give either steps or duration, not both (steps is at line %d)", steps.line);
    if (!has_steps && !has_duration)
        return sd_fail(p, s->simulation_line, "simulation.steps",
                       "missing the run length: give steps or duration (s), exactly one");
    if (has_steps) {
        s->steps = (long)steps.integer;
    } else {
        double n = ceil(duration.num / s->world.dt - 1e-9);
        if (n > 1e15)
            return sd_fail(p, duration.line, "simulation.duration",
                           "duration / dt = %g steps is too many", n);
        s->steps = n > 0.0 ? (long)n : 0;
    }

    sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "gravity", path, &v);
    s->world.gravity = sd_parse_v3(v.v);
    if (s->world.dimension == 2 && v.v[2] != 0.0)
        return sd_fail(p, v.line ? v.line : s->simulation_line, "simulation.gravity",
                       "dimension 2 needs gravity in the x-y plane, [gx, gy, 0]; got z = %g%s", v.v[2],
                       v.line ? "" : " (the default [0, 0, -9.81])");
    sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "seed", path, &v);
    s->world.seed = (uint64_t)v.integer;
    sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "mpi_rebalance_every", path, &v);
    s->mpi_rebalance_every = (long)v.integer;
    /* simulation.mpi_split: auto, x, y, z (choices 0 .. 3) or [px, py, pz];
     * checked against the rank count when a run splits (mpi/plan.c) */
    if (sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "mpi_split", path, &v)) {
        s->mpi_split_line = v.line;
        if (v.choice < 0 && v.iv[0] * v.iv[1] * v.iv[2] > SD_MPI_MAX_RANKS)
            return sd_fail(p, v.line, "simulation.mpi_split",
                           "[%lld, %lld, %lld] makes %lld boxes: at most %d MPI ranks in this version", v.iv[0],
                           v.iv[1], v.iv[2], v.iv[0] * v.iv[1] * v.iv[2], SD_MPI_MAX_RANKS);
        for (int a = 0; a < 3; ++a)
            s->mpi_split[a] = v.choice < 0 ? (int)v.iv[a] : (v.choice == a + 1 ? -1 : (v.choice ? 1 : 0));
    }
    sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "threads", path, &v);
    if (v.integer > SD_SCENE_MAX_THREADS)
        return sd_fail(p, v.line, "simulation.threads",
                       "expected at most %d threads, got %lld (results are the same for any thread count; "
                       "0 uses all cores)",
                       SD_SCENE_MAX_THREADS, v.integer);
    s->world.threads = (int)v.integer;
    if (sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "contact_law", path, &v)) {
        s->world.law = sd_contact_law_from_name(v.str);
    } else {
        const sd_scene_key *k = sd_scene_key_find(SD_SEC_SIMULATION, "contact_law");
        s->world.law = sd_contact_law_from_name(k->def);
    }
    if (s->world.law == SD_LAW_COUNT)
        return sd_fail(p, v.line, "simulation.contact_law", "unknown contact law");
    sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "skin", path, &v);
    s->world.skin = v.num;
    if (sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "max_overlap", path, &v))
        s->world.max_overlap = v.num;
    /* choices in sd_solver order: cells, grid */
    if (sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "solver", path, &v))
        s->world.solver = v.choice == 1 ? SD_SOLVER_GRID : SD_SOLVER_CELLS;
    /* choices in SD_BACKENDS order: auto, cpu, cuda (the device is probed
     * when the world is built: world/backend.c) */
    if (sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "backend", path, &v)) {
        s->world.backend = (sd_backend_kind)v.choice;
        s->backend_line = v.line;
    }
    /* periodic boundaries (world/rebuild.c): choices x, y, z in the order
     * of SD_PERIODIC_X, _Y, _Z */
    if (sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "periodic", path, &v) && v.mask) {
        s->world.periodic = v.mask;
        if (s->world.dimension == 2 && (v.mask & SD_PERIODIC_Z))
            return sd_fail(p, v.line, "simulation.periodic", "dimension 2: only x and y can be periodic");
        if (s->world.solver == SD_SOLVER_GRID)
            return sd_fail(p, v.line, "simulation.periodic",
                           "periodic boundaries run on the cells solver only (the grid solver's domain is a box "
                           "wall); use solver: cells");
        int pline = v.line;
        if (!sd_yaml_get(&p->y, sim, SD_SEC_SIMULATION, "domain", path, &v))
            return sd_fail(p, pline, "simulation.domain",
                           "periodic boundaries need the periodic box, domain: {min: [x, y, z], max: [x, y, z]}");
        s->world.domain_lo = v.box_lo;
        s->world.domain_hi = v.box_hi;
    }
    return sd_parse_stop(p, sim);
}

/* No wall may lie across a periodic axis: a plane whose normal has a
 * component along it, a box with closed faces on it (dynamics/walls.h
 * decides the same for the world). */
static sd_status sd_check_periodic_walls(sd_parse *p)
{
    const sd_scene *s = p->s;
    static const char axis[3] = {'x', 'y', 'z'};
    char key[64];
    for (size_t k = 0; k < s->wall_count; ++k) {
        const sd_scene_wall *w = &s->walls[k];
        const double n[3] = {w->normal.x, w->normal.y, w->normal.z};
        for (int a = 0; a < 3; ++a) {
            if (!(s->world.periodic & (1u << a)))
                continue;
            if (w->kind == 2) {
                snprintf(key, sizeof key, "walls[%zu]", k);
                return sd_fail(p, w->line, key,
                               "mesh wall '%s' in a periodic scene: mesh walls do not take periodic images; make the "
                               "axes non-periodic", w->name);
            }
            int across = w->kind == 0 ? n[a] != 0.0 : (w->open_faces & (3u << (2 * a))) != (3u << (2 * a));
            if (w->kind == 3) /* only along its own axis, open at both ends (dynamics/walls.h) */
                across = fabs(n[a]) < 1.0 - 1e-12 || !w->drum_open_lo || !w->drum_open_hi;
            if (across) {
                snprintf(key, sizeof key, "walls[%zu]", k);
                return sd_fail(p, w->line, key,
                               "wall '%s' lies across the periodic axis %c (%s); make the axis non-periodic or "
                               "the wall parallel to it",
                               w->name, axis[a],
                               w->kind == 0   ? "its normal has a component along it"
                               : w->kind == 3 ? "a drum takes a periodic axis only along its own axis, with caps: none"
                                              : "its faces on that axis are closed: open them");
            }
        }
    }
    return SD_OK;
}

/* The plain material keys, placed in sd_material_def by the table (their
 * defaults are the table's); the rest are read by name below. */
static const sd_yaml_place sd_material_place[] = {
    {"density", offsetof(sd_material_def, density)},
    {"poisson_ratio", offsetof(sd_material_def, poisson_ratio)},
    {"restitution", offsetof(sd_material_def, restitution)},
    {"friction", offsetof(sd_material_def, friction)},
    {"rolling_friction", offsetof(sd_material_def, rolling_friction)},
    {"stiffness", offsetof(sd_material_def, stiffness)},
    {"tangential_stiffness_ratio", offsetof(sd_material_def, tangential_stiffness_ratio)},
    {"damping", offsetof(sd_material_def, damping)},
    {"volume_stiffness", offsetof(sd_material_def, volume_stiffness)},
    {"volume_face_omega_dt", offsetof(sd_material_def, volume_face_omega_dt)},
};
static const char *const sd_material_rules[] = {"name", "youngs_modulus", NULL};

static sd_status sd_parse_materials(sd_parse *p, yaml_node_t *list, int line)
{
    sd_scene *s = p->s;
    size_t n = sd_yaml_seq_len(list);
    char path[64], key[96];
    sd_yaml_value v;
    sd_status st;
    if (n == 0)
        return sd_fail(p, line, "materials", "expected at least one material, got %s",
                       list ? "an empty list" : "nothing");
    s->materials = sd_calloc(n, sizeof *s->materials);
    if (!s->materials)
        return sd_yaml_oom(&p->y);
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m;
        if ((st = sd_yaml_entry(&p->y, list, i, "materials", "(name: ..., density: ...)", path, sizeof path, &m)))
            return st;
        sd_scene_material *sm = &s->materials[i];
        if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_MATERIAL, SD_KIND_ALL, "", path, sd_yaml_line(m))))
            return st;
        sm->line = sd_yaml_line(m);
        sd_yaml_get(&p->y, m, SD_SEC_MATERIAL, "name", path, &v);
        if (strlen(v.str) >= SD_SCENE_NAME_MAX)
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "name"),
                           "name longer than %d characters", SD_SCENE_NAME_MAX - 1);
        for (size_t j = 0; j < i; ++j)
            if (!strcmp(s->materials[j].name, v.str)) {
                return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "name"),
                               "duplicate material name '%s' (materials[%zu], line %d)",
                               v.str, j, s->materials[j].line);
            }
        snprintf(sm->name, sizeof sm->name, "%s", v.str);
        s->material_count = i + 1;

        sd_material_def *d = &sm->def;
        *d = sd_material_def_default();
        if ((st = sd_yaml_place_numbers(&p->y, m, SD_SEC_MATERIAL, path, sd_material_place,
                                        sizeof sd_material_place / sizeof sd_material_place[0],
                                        sd_material_rules, d)))
            return st;
        /* Absent means unset (0); the law checks below decide if it is needed. */
        d->youngs_modulus = sd_yaml_get(&p->y, m, SD_SEC_MATERIAL, "youngs_modulus", path, &v) ? v.num : 0.0;
    }
    /* Names point into the array only now that it will not move. */
    for (size_t i = 0; i < n; ++i)
        s->materials[i].def.name = s->materials[i].name;
    return SD_OK;
}

static sd_status sd_parse_interactions(sd_parse *p, yaml_node_t *list)
{
    sd_scene *s = p->s;
    size_t n = sd_yaml_seq_len(list);
    char path[64], key[96];
    sd_yaml_value v;
    sd_status st;
    if (n == 0)
        return SD_OK;
    s->interactions = sd_calloc(n, sizeof *s->interactions);
    if (!s->interactions)
        return sd_yaml_oom(&p->y);
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m;
        if ((st = sd_yaml_entry(&p->y, list, i, "interactions", "(between: [a, b], ...)", path, sizeof path, &m)))
            return st;
        sd_scene_interaction *si = &s->interactions[i];
        if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_INTERACTION, SD_KIND_ALL, "", path, sd_yaml_line(m))))
            return st;
        si->line = sd_yaml_line(m);
        sd_yaml_get(&p->y, m, SD_SEC_INTERACTION, "between", path, &v);
        snprintf(key, sizeof key, "%s.between", path);
        if ((st = sd_material_ref(p, v.names[0], v.line, key, &si->mat_a)))
            return st;
        if ((st = sd_material_ref(p, v.names[1], v.line, key, &si->mat_b)))
            return st;
        for (size_t j = 0; j < i; ++j) {
            const sd_scene_interaction *o = &s->interactions[j];
            if ((o->mat_a == si->mat_a && o->mat_b == si->mat_b) ||
                (o->mat_a == si->mat_b && o->mat_b == si->mat_a))
                return sd_fail(p, v.line, key,
                               "a second interaction between '%s' and '%s' (the first is "
                               "interactions[%zu], line %d)",
                               v.names[0], v.names[1], j, o->line);
        }
        s->interaction_count = i + 1;
        si->def = sd_interaction_def_default();
        /* Absent keys keep the mixed value: a negative value in the def. */
        si->def.restitution = sd_yaml_get(&p->y, m, SD_SEC_INTERACTION, "restitution", path, &v) ? v.num : -1.0;
        si->def.friction = sd_yaml_get(&p->y, m, SD_SEC_INTERACTION, "friction", path, &v) ? v.num : -1.0;
        si->def.rolling_friction =
            sd_yaml_get(&p->y, m, SD_SEC_INTERACTION, "rolling_friction", path, &v) ? v.num : -1.0;
        si->def.stiffness = sd_yaml_get(&p->y, m, SD_SEC_INTERACTION, "stiffness", path, &v) ? v.num : -1.0;
        si->def.damping = sd_yaml_get(&p->y, m, SD_SEC_INTERACTION, "damping", path, &v) ? v.num : -1.0;
        si->def.volume_stiffness = sd_yaml_get(&p->y, m, SD_SEC_INTERACTION, "volume_stiffness", path, &v) ? v.num : -1.0;
        si->def.law = sd_yaml_get(&p->y, m, SD_SEC_INTERACTION, "contact_law", path, &v)
                          ? (int)sd_contact_law_from_name(v.str)
                          : -1;
        if (si->def.law == SD_LAW_COUNT)
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "contact_law"),
                           "unknown contact law");
    }
    return SD_OK;
}

int sd_resolve(const char *scene, const char *file, char *out, size_t size)
{
    const char *slash = strrchr(scene, '/');
    int n;
    if (file[0] == '/' || !slash)
        n = snprintf(out, size, "%s", file);
    else
        n = snprintf(out, size, "%.*s/%s", (int)(slash - scene), scene, file);
    return n >= 0 && (size_t)n < size;
}

/* ---- walls and output --------------------------------------------------- */

/* Moving walls (servo.c): a prescribed velocity and/or a servo target. */
static sd_status sd_parse_wall_motion(sd_parse *p, yaml_node_t *m, sd_scene_wall *w, const char *path)
{
    char key[96];
    sd_yaml_value v, vs, ve;
    sd_wall_motion_def *d = &w->motion;
    *d = sd_wall_motion_def_default();
    int any = 0;
    if (sd_yaml_get(&p->y, m, SD_SEC_WALL, "velocity", path, &v)) {
        any = 1;
        d->velocity = sd_parse_v3(v.v);
        if (p->s->world.dimension == 2 && v.v[2] != 0.0)
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "velocity"),
                           "dimension 2 needs a velocity with z = 0, got %g", v.v[2]);
    }
    int hs = sd_yaml_get(&p->y, m, SD_SEC_WALL, "move_start", path, &vs);
    int he = sd_yaml_get(&p->y, m, SD_SEC_WALL, "move_end", path, &ve);
    d->move_start = vs.num;
    d->move_end = he ? ve.num : -1.0;
    if (he && !(ve.num > vs.num))
        return sd_fail(p, ve.line, sd_yaml_kp(key, sizeof key, path, "move_end"),
                       "expected move_end > move_start (%g s), got %g s", vs.num, ve.num);
    any |= hs | he;
    if (sd_yaml_get(&p->y, m, SD_SEC_WALL, "servo_stress", path, &v)) {
        any = 1;
        d->servo_stress = v.num;
    }
    hs = sd_yaml_get(&p->y, m, SD_SEC_WALL, "servo_start", path, &vs);
    he = sd_yaml_get(&p->y, m, SD_SEC_WALL, "servo_end", path, &ve);
    d->servo_start = vs.num;
    d->servo_end = he ? ve.num : -1.0;
    if (he && !(ve.num > vs.num))
        return sd_fail(p, ve.line, sd_yaml_kp(key, sizeof key, path, "servo_end"),
                       "expected servo_end > servo_start (%g s), got %g s", vs.num, ve.num);
    any |= hs | he;
    if (sd_yaml_get(&p->y, m, SD_SEC_WALL, "servo_gain", path, &v)) {
        any = 1;
        d->servo_gain = v.num;
    }
    if (sd_yaml_get(&p->y, m, SD_SEC_WALL, "servo_max_speed", path, &v)) {
        any = 1;
        d->servo_max_speed = v.num;
    }
    w->has_motion = any;
    return SD_OK;
}

/* The analytic rotating drum (type: drum; shapedem/process.h). */
static sd_status sd_parse_drum_wall(sd_parse *p, yaml_node_t *m, sd_scene_wall *w, const char *path)
{
    sd_yaml_value v;
    char key[96];
    if (p->s->world.dimension == 2)
        return sd_fail(p, w->line, sd_yaml_kp(key, sizeof key, path, "type"),
                       "dimension 2: the drum wall is 3D only (a planar drum is a ring of planes or a mesh)");
    sd_yaml_get(&p->y, m, SD_SEC_WALL, "center", path, &v);
    w->point = sd_parse_v3(v.v);
    sd_yaml_get(&p->y, m, SD_SEC_WALL, "axis", path, &v);
    double len = v.node ? sqrt(v.v[0] * v.v[0] + v.v[1] * v.v[1] + v.v[2] * v.v[2]) : 1.0;
    if (!(len > 0.0) || !isfinite(len))
        return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "axis"), "expected a non-zero axis, got [%g, %g, %g]",
                       v.v[0], v.v[1], v.v[2]);
    w->normal = v.node ? (sd_v3d){v.v[0] / len, v.v[1] / len, v.v[2] / len} : (sd_v3d){0, 0, 1};
    sd_yaml_get(&p->y, m, SD_SEC_WALL, "radius", path, &v);
    w->drum_radius = v.num;
    sd_yaml_get(&p->y, m, SD_SEC_WALL, "length", path, &v);
    w->drum_length = v.num;
    w->drum_rpm = sd_yaml_get(&p->y, m, SD_SEC_WALL, "rpm", path, &v) ? v.num : 0.0;
    w->drum_start = sd_yaml_get(&p->y, m, SD_SEC_WALL, "start", path, &v) ? v.num : 0.0;
    w->drum_ramp = sd_yaml_get(&p->y, m, SD_SEC_WALL, "ramp", path, &v) ? v.num : 0.0;
    /* caps: both|none|low|high, the closed ones */
    int caps = sd_yaml_get(&p->y, m, SD_SEC_WALL, "caps", path, &v) ? v.choice : 0;
    w->drum_open_lo = caps == 1 || caps == 3;
    w->drum_open_hi = caps == 1 || caps == 2;
    return SD_OK;
}

static sd_status sd_parse_walls(sd_parse *p, yaml_node_t *list)
{
    sd_scene *s = p->s;
    size_t n = sd_yaml_seq_len(list);
    char path[64], key[96], kind_name[64];
    sd_yaml_value v;
    sd_status st;
    if (n == 0)
        return SD_OK;
    s->walls = sd_calloc(n, sizeof *s->walls);
    if (!s->walls)
        return sd_yaml_oom(&p->y);
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m;
        if ((st = sd_yaml_entry(&p->y, list, i, "walls", "(type: plane|box|mesh|drum, ...)", path, sizeof path,
                                &m)))
            return st;
        sd_scene_wall *w = &s->walls[i];
        w->line = sd_yaml_line(m);
        yaml_node_t *tn = sd_yaml_map_get(&p->y, m, "type");
        snprintf(key, sizeof key, "%s.type", path);
        if (!tn)
            return sd_fail(p, w->line, key, "missing required key 'type' (plane, box, mesh or drum)");
        if ((st = sd_yaml_read_value(&p->y, sd_scene_key_find(SD_SEC_WALL, "type"), tn, key, &v)))
            return st;
        w->kind = v.choice;
        snprintf(kind_name, sizeof kind_name, "a %s wall", v.str);
        if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_WALL, 1u << w->kind, kind_name, path, w->line)))
            return st;
        s->wall_count = i + 1;
        if (sd_yaml_get(&p->y, m, SD_SEC_WALL, "name", path, &v)) {
            if (strlen(v.str) >= SD_SCENE_NAME_MAX)
                return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "name"),
                               "name longer than %d characters", SD_SCENE_NAME_MAX - 1);
            snprintf(w->name, sizeof w->name, "%s", v.str);
        } else {
            snprintf(w->name, sizeof w->name, "wall%zu", i);
        }
        sd_yaml_get(&p->y, m, SD_SEC_WALL, "material", path, &v);
        if ((st = sd_material_ref(p, v.str, v.line, sd_yaml_kp(key, sizeof key, path, "material"),
                                  &w->material)))
            return st;
        if (w->kind == 2) {
            if ((st = sd_parse_mesh_wall(p, m, w, path)))
                return st;
        } else if (w->kind == 3) {
            if ((st = sd_parse_drum_wall(p, m, w, path)))
                return st;
        } else if (w->kind == 0) {
            sd_yaml_get(&p->y, m, SD_SEC_WALL, "point", path, &v);
            w->point = sd_parse_v3(v.v);
            sd_yaml_get(&p->y, m, SD_SEC_WALL, "normal", path, &v);
            double len = sqrt(v.v[0] * v.v[0] + v.v[1] * v.v[1] + v.v[2] * v.v[2]);
            if (!(len > 0.0) || !isfinite(len))
                return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "normal"),
                               "expected a non-zero normal, got [%g, %g, %g]", v.v[0], v.v[1],
                               v.v[2]);
            w->normal = (sd_v3d){v.v[0] / len, v.v[1] / len, v.v[2] / len};
        } else {
            sd_yaml_value lo, hi;
            sd_yaml_get(&p->y, m, SD_SEC_WALL, "min", path, &lo);
            sd_yaml_get(&p->y, m, SD_SEC_WALL, "max", path, &hi);
            for (int a = 0; a < 3; ++a)
                if (!(hi.v[a] > lo.v[a]))
                    return sd_fail(p, hi.line, sd_yaml_kp(key, sizeof key, path, "max"),
                                   "expected max > min on every axis, got max %c = %g <= min %c = %g",
                                   'x' + a, hi.v[a], 'x' + a, lo.v[a]);
            w->lo = sd_parse_v3(lo.v);
            w->hi = sd_parse_v3(hi.v);
            /* The choice order xmin xmax ymin ... matches the SD_BOX_* bits. */
            sd_yaml_get(&p->y, m, SD_SEC_WALL, "open", path, &v);
            w->open_faces = v.mask;
        }
        if (s->world.dimension == 2 && w->kind == 0 && w->normal.z != 0.0)
            return sd_fail(p, w->line, sd_yaml_kp(key, sizeof key, path, "normal"),
                           "dimension 2: a plane is a line in x-y, its normal needs z = 0");
        if ((st = sd_parse_wall_motion(p, m, w, path)))
            return st;
    }
    return SD_OK;
}

static sd_status sd_parse_output(sd_parse *p, yaml_node_t *root, int line)
{
    sd_scene *s = p->s;
    yaml_node_t *out = sd_yaml_map_get(&p->y, root, "output");
    const char *path = "output";
    sd_yaml_value v;
    sd_status st;
    if ((st = sd_yaml_check_map(&p->y, out, SD_SEC_OUTPUT, SD_KIND_ALL, "", path, line)))
        return st;
    if (sd_yaml_get(&p->y, out, SD_SEC_OUTPUT, "directory", path, &v))
        snprintf(s->output.directory, sizeof s->output.directory, "%s", v.str);
    s->output.every = sd_yaml_get(&p->y, out, SD_SEC_OUTPUT, "every", path, &v) ? (long)v.integer
                                                                       : s->steps / 100;
    if (s->output.every < 1)
        s->output.every = 1;
    s->output.stats_every = sd_yaml_get(&p->y, out, SD_SEC_OUTPUT, "stats_every", path, &v)
                                ? (long)v.integer
                                : s->output.every / 10;
    if (s->output.stats_every < 1)
        s->output.stats_every = 1;
    /* The choice order vtk|csv|shapes|dump|h5md matches SD_OUT_VTK, SD_OUT_CSV, SD_OUT_SHAPES, SD_OUT_DUMP,
     * SD_OUT_H5MD;
     * the shapes files go with the frames, so shapes brings vtk. */
    s->output.formats =
        sd_yaml_get(&p->y, out, SD_SEC_OUTPUT, "formats", path, &v) ? v.mask : (SD_OUT_VTK | SD_OUT_CSV);
    if (s->output.formats & SD_OUT_SHAPES)
        s->output.formats |= SD_OUT_VTK;
    s->output.shape_resolution = 24;
    if (sd_yaml_get(&p->y, out, SD_SEC_OUTPUT, "shape_resolution", path, &v)) {
        if (v.integer < SD_SURFACE_RES_MIN || v.integer > SD_SURFACE_RES_MAX)
            return sd_fail(p, v.line, "output.shape_resolution",
                           "shape_resolution is %lld; it must be %d to %d directions per turn",
                           (long long)v.integer, SD_SURFACE_RES_MIN, SD_SURFACE_RES_MAX);
        s->output.shape_resolution = (int)v.integer;
    }
    s->output.checkpoint_every = sd_yaml_get(&p->y, out, SD_SEC_OUTPUT, "checkpoint_every", path, &v) ? (long)v.integer : 0;
    s->output.checkpoint_minutes =
        sd_yaml_get(&p->y, out, SD_SEC_OUTPUT, "checkpoint_minutes", path, &v) ? v.num : 0.0;
    return SD_OK;
}

/* ---- pour and outlet (solver grid, src/grid) ----------------------------- */

/* The union of the box walls: the grid solver's domain. 0 when there is none. */
static int sd_scene_box_union(const sd_scene *s, sd_v3d *lo, sd_v3d *hi)
{
    int n = 0;
    for (size_t i = 0; i < s->wall_count; ++i) {
        const sd_scene_wall *w = &s->walls[i];
        if (w->kind != 1)
            continue;
        if (!n++) {
            *lo = w->lo;
            *hi = w->hi;
            continue;
        }
        lo->x = fmin(lo->x, w->lo.x), lo->y = fmin(lo->y, w->lo.y), lo->z = fmin(lo->z, w->lo.z);
        hi->x = fmax(hi->x, w->hi.x), hi->y = fmax(hi->y, w->hi.y), hi->z = fmax(hi->z, w->hi.z);
    }
    return n;
}

/* pour: and outlet: need solver grid and a box wall. */
static sd_status sd_grid_section_needs(sd_parse *p, const char *sec, int line, sd_v3d *lo, sd_v3d *hi)
{
    if (p->s->world.solver != SD_SOLVER_GRID)
        return sd_fail(p, line, sec, "%s needs simulation.solver: grid (the dense grid-stencil solver)", sec);
    if (!sd_scene_box_union(p->s, lo, hi))
        return sd_fail(p, line, sec, "%s needs a box wall (the grid solver's domain)", sec);
    return SD_OK;
}

static sd_status sd_parse_pour(sd_parse *p, yaml_node_t *root)
{
    sd_scene_pour *pr = &p->s->pour;
    yaml_node_t *m = sd_yaml_map_get(&p->y, root, "pour");
    const char *path = "pour";
    char key[96];
    sd_yaml_value v;
    sd_status st;
    if (!m)
        return SD_OK;
    pr->given = 1;
    pr->line = sd_yaml_key_line(&p->y, root, "pour");
    if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_POUR, SD_KIND_ALL, "", path, pr->line)))
        return st;
    sd_v3d lo, hi;
    if ((st = sd_grid_section_needs(p, path, pr->line, &lo, &hi)))
        return st;
    sd_yaml_get(&p->y, m, SD_SEC_POUR, "material", path, &v);
    if ((st = sd_material_ref(p, v.str, v.line, sd_yaml_kp(key, sizeof key, path, "material"), &pr->material)))
        return st;
    sd_yaml_get(&p->y, m, SD_SEC_POUR, "radius", path, &v);
    pr->radius = v.num;
    sd_yaml_get(&p->y, m, SD_SEC_POUR, "height", path, &v);
    pr->height = v.num;
    if (!(v.num - pr->radius >= lo.z && v.num + pr->radius <= hi.z))
        return sd_fail(p, v.line, "pour.height",
                       "expected a height that keeps the sheet inside the box (z of the centres in [%g, %g] m), "
                       "got %g",
                       lo.z + pr->radius, hi.z - pr->radius, v.num);
    if (hi.x - lo.x < 2 * pr->radius || hi.y - lo.y < 2 * pr->radius)
        return sd_fail(p, pr->line, "pour.radius", "the box is narrower than one poured sphere (radius %g m)",
                       pr->radius);
    sd_yaml_get(&p->y, m, SD_SEC_POUR, "layers_per_second", path, &v);
    pr->rate = v.num;
    sd_yaml_get(&p->y, m, SD_SEC_POUR, "vertical_speed", path, &v);
    pr->vertical_speed = v.num;
    sd_yaml_get(&p->y, m, SD_SEC_POUR, "horizontal_speed", path, &v);
    pr->horizontal_speed = v.num;
    sd_yaml_get(&p->y, m, SD_SEC_POUR, "start", path, &v);
    pr->start = v.num;
    sd_yaml_get(&p->y, m, SD_SEC_POUR, "packing_fraction", path, &v);
    pr->packing_fraction = v.num;
    int has_count = sd_yaml_get(&p->y, m, SD_SEC_POUR, "count", path, &v);
    long long count = has_count ? v.integer : 0;
    int has_fill = sd_yaml_get(&p->y, m, SD_SEC_POUR, "fill_height", path, &v);
    if (has_count == has_fill)
        return sd_fail(p, pr->line, path, "pour needs exactly one of count and fill_height, got %s",
                       has_count ? "both" : "neither");
    if (has_fill) {
        pr->fill_height = v.num;
        if (lo.z + v.num > hi.z)
            return sd_fail(p, v.line, "pour.fill_height", "expected a fill height within the box (at most %g m), got %g",
                           hi.z - lo.z, v.num);
        double sphere = 4.0 / 3.0 * 3.14159265358979323846 * pr->radius * pr->radius * pr->radius;
        count = (long long)floor(pr->packing_fraction * (hi.x - lo.x) * (hi.y - lo.y) * v.num / sphere);
        if (count < 1)
            return sd_fail(p, v.line, "pour.fill_height", "fill height %g m holds no sphere of radius %g m", v.num,
                           pr->radius);
    }
    if (count > 1000000000LL)
        return sd_fail(p, pr->line, "pour.count", "expected at most 1e9 spheres, got %lld", count);
    pr->count = (long)count;
    if ((st = sd_count_particles(p, (double)count, has_fill ? v.line : sd_yaml_line(sd_yaml_map_get(&p->y, m, "count")),
                                 has_fill ? "pour.fill_height" : "pour.count")))
        return st;
    return SD_OK;
}

static sd_status sd_parse_outlet(sd_parse *p, yaml_node_t *root)
{
    sd_scene_outlet *o = &p->s->outlet;
    yaml_node_t *m = sd_yaml_map_get(&p->y, root, "outlet");
    const char *path = "outlet";
    sd_yaml_value v;
    sd_status st;
    if (!m)
        return SD_OK;
    o->given = 1;
    o->line = sd_yaml_key_line(&p->y, root, "outlet");
    if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_OUTLET, SD_KIND_ALL, "", path, o->line)))
        return st;
    sd_v3d lo, hi;
    if ((st = sd_grid_section_needs(p, path, o->line, &lo, &hi)))
        return st;
    sd_yaml_get(&p->y, m, SD_SEC_OUTLET, "min", path, &v);
    o->lo[0] = v.v[0], o->lo[1] = v.v[1];
    int line = v.line;
    sd_yaml_get(&p->y, m, SD_SEC_OUTLET, "max", path, &v);
    o->hi[0] = v.v[0], o->hi[1] = v.v[1];
    if (!(o->hi[0] > o->lo[0] && o->hi[1] > o->lo[1]))
        return sd_fail(p, v.line, "outlet.max", "expected max > min on x and y, got min [%g, %g], max [%g, %g]",
                       o->lo[0], o->lo[1], o->hi[0], o->hi[1]);
    if (o->hi[0] <= lo.x || o->lo[0] >= hi.x || o->hi[1] <= lo.y || o->lo[1] >= hi.y)
        return sd_fail(p, line, "outlet.min",
                       "the hole [%g, %g] x [%g, %g] misses the box floor [%g, %g] x [%g, %g]", o->lo[0], o->hi[0],
                       o->lo[1], o->hi[1], lo.x, hi.x, lo.y, hi.y);
    sd_yaml_get(&p->y, m, SD_SEC_OUTLET, "open_at", path, &v);
    o->open_at = v.num;
    return SD_OK;
}

/* ---- cross checks ------------------------------------------------------- */

/* A material needs youngs_modulus when a hertz_mindlin contact involves it,
 * and a stiffness when a linear contact involves it and the pair's
 * interaction sets none. Contacts are particle-particle and particle-wall,
 * so only materials that particles or walls use count. Checked here, where
 * the line of the material is known; sd_world_prepare checks again. */
static sd_status sd_check_laws(sd_parse *p)
{
    sd_scene *s = p->s;
    size_t nm = s->material_count;
    unsigned char *use = sd_calloc(nm ? nm : 1, 1); /* bit 0: particles, bit 1: walls */
    if (!use)
        return sd_yaml_oom(&p->y);
    for (size_t g = 0; g < s->generator_count; ++g) {
        const sd_scene_generator *gen = &s->generators[g];
        if (gen->kind == SD_GEN_LIST || gen->kind == SD_GEN_CSV) /* a material per entry */
            for (size_t i = 0; i < gen->list_count; ++i)
                use[gen->list[i].material] |= 1;
        else
            use[gen->material] |= 1;
    }
    for (size_t w = 0; w < s->wall_count; ++w)
        use[s->walls[w].material] |= 2;
    sd_status st = SD_OK;
    for (size_t a = 0; a < nm && st == SD_OK; ++a) {
        for (size_t b = 0; b < nm && st == SD_OK; ++b) {
            if (!((use[a] & 1) && use[b]) && !((use[b] & 1) && use[a]))
                continue; /* no contact between these two materials */
            const sd_scene_interaction *in = NULL;
            for (size_t i = 0; i < s->interaction_count; ++i) {
                const sd_scene_interaction *c = &s->interactions[i];
                if ((c->mat_a == (int)a && c->mat_b == (int)b) ||
                    (c->mat_a == (int)b && c->mat_b == (int)a))
                    in = c;
            }
            int law = (in && in->def.law >= 0) ? in->def.law : (int)s->world.law;
            const sd_scene_material *m = &s->materials[a];
            /* the law's needs column (shapedem.h SD_CONTACT_LAWS, read
             * through contact/params.h, as sd_world_check_params does) */
            unsigned needs = sd_law_needs(law);
            for (unsigned f = 1; f <= needs && st == SD_OK; f <<= 1) {
                sd_law_need nd;
                if (!(needs & f) || !sd_law_need_of(f, &nd))
                    continue;
                if (nd.particles_only && !(use[a] & 1))
                    continue; /* a wall's material: walls are rigid */
                if (sd_law_need_field(&m->def, nd.material_field) > 0.0 ||
                    (in && nd.interaction_field >= 0 &&
                     sd_law_need_field(&in->def, (size_t)nd.interaction_field) > 0.0))
                    continue;
                char key[96], also[96] = "";
                snprintf(key, sizeof key, "materials[%zu].%s", a, nd.key);
                if (nd.interaction_field >= 0)
                    snprintf(also, sizeof also, " (or set %s in their interaction)", nd.key);
                st = sd_fail(p, m->line, key, "missing %s (%s): the %s contact between '%s' and '%s' needs it%s%s",
                             nd.key, nd.unit, sd_contact_law_name((sd_contact_law)law), m->name,
                             s->materials[b].name, nd.note, also);
            }
        }
    }
    /* The volume laws take sharp polyhedra only (the overlap volume exists
     * for them); world/material.c checks again at prepare time. */
    for (size_t g = 0; g < s->generator_count && st == SD_OK; ++g) {
        const sd_scene_generator *gen = &s->generators[g];
        int listed = gen->kind == SD_GEN_LIST || gen->kind == SD_GEN_CSV; /* per entry */
        size_t cnt = listed ? gen->list_count : 1;
        for (size_t i = 0; i < cnt && st == SD_OK; ++i) {
            int a = listed ? gen->list[i].material : gen->material;
            int sh = (listed && gen->list_shape) ? gen->list_shape[i] : gen->shape;
            const sd_scene_shape *ss = sh >= 0 ? &s->shapes[sh] : NULL;
            if (ss && ss->kind == SD_SHAPE_POLYHEDRON && !(ss->rounding > 0) && !(ss->margin > 0))
                continue;
            for (size_t b = 0; b < nm && st == SD_OK; ++b) {
                if (!use[b])
                    continue;
                const sd_scene_interaction *in = NULL;
                for (size_t k = 0; k < s->interaction_count; ++k) {
                    const sd_scene_interaction *c = &s->interactions[k];
                    if ((c->mat_a == a && c->mat_b == (int)b) || (c->mat_a == (int)b && c->mat_b == a))
                        in = c;
                }
                int law = (in && in->def.law >= 0) ? in->def.law : (int)s->world.law;
                if (!(sd_law_needs(law) & SD_LAW_NEEDS_SHARP))
                    continue;
                char key[96];
                snprintf(key, sizeof key, "particles[%zu]", g);
                char what[96];
                if (ss)
                    snprintf(what, sizeof what, "shape '%s'", ss->name);
                else
                    snprintf(what, sizeof what, "spheres");
                st = sd_fail(p, gen->line, key,
                             "%s (material '%s') meet material '%s' under the %s law, which takes "
                             "sharp polyhedra only (type polyhedron, no rounding or margin); give this pair "
                             "another law (interactions: contact_law hertz_mindlin or linear)",
                             what, s->materials[a].name, s->materials[b].name,
                             sd_contact_law_name((sd_contact_law)law));
            }
        }
    }
    sd_free(use);
    return st;
}

/* ---- entry points ------------------------------------------------------- */

static sd_status sd_parse_root(sd_parse *p, yaml_node_t *root)
{
    char got[96];
    sd_yaml_value v;
    sd_status st;
    if (!root)
        return sd_fail(p, 1, "", "the scene file is empty (expected simulation, materials and "
                                 "particles sections)");
    if (root->type != YAML_MAPPING_NODE)
        return sd_fail(p, sd_yaml_line(root), "",
                       "expected a mapping of sections (simulation:, materials:, ...), got %s",
                       sd_yaml_desc(root, got, sizeof got));
    if ((st = sd_yaml_check_map(&p->y, root, SD_SEC_ROOT, SD_KIND_ALL, "", "", 1)))
        return st;
    p->s->simulation_line = sd_yaml_key_line(&p->y, root, "simulation");
    if ((st = sd_parse_simulation(p, root)))
        return st;
    /* Materials first: the other sections refer to them by name. */
    sd_yaml_get(&p->y, root, SD_SEC_ROOT, "materials", "", &v);
    if ((st = sd_parse_materials(p, v.node, sd_yaml_key_line(&p->y, root, "materials"))))
        return st;
    sd_yaml_get(&p->y, root, SD_SEC_ROOT, "interactions", "", &v);
    if ((st = sd_parse_interactions(p, v.node)))
        return st;
    /* Shapes before particles: generators refer to them by name. */
    sd_yaml_get(&p->y, root, SD_SEC_ROOT, "shapes", "", &v);
    if ((st = sd_parse_shapes(p, v.node)))
        return st;
    /* particles may be left out when a pour fills the box (solver grid) */
    if (sd_yaml_get(&p->y, root, SD_SEC_ROOT, "particles", "", &v) ||
        (!sd_yaml_map_get(&p->y, root, "pour") && !sd_yaml_map_get(&p->y, root, "insert")))
        if ((st = sd_parse_particles(p, v.node, sd_yaml_key_line(&p->y, root, "particles"))))
            return st;
    sd_yaml_get(&p->y, root, SD_SEC_ROOT, "walls", "", &v);
    if ((st = sd_parse_walls(p, v.node)) || (st = sd_check_periodic_walls(p)))
        return st;
    if ((st = sd_parse_output(p, root, sd_yaml_map_get(&p->y, root, "output") ? sd_yaml_key_line(&p->y, root, "output") : 1)))
        return st;
    if ((st = sd_parse_pour(p, root)) || (st = sd_parse_outlet(p, root)))
        return st;
    if ((st = sd_parse_process(p, root))) /* insert: and outlets: (scene_process.c) */
        return st;
    if ((st = sd_parse_analysis(p, root))) /* analysis: (scene_analysis.c) */
        return st;
    return sd_check_laws(p);
}

sd_status sd_scene_load(const char *path, sd_scene **out, sd_error *err)
{
    sd_error_clear(err);
    if (!out)
        return sd_error_null(err, "sd_scene_load", "out");
    *out = NULL;
    if (!path)
        return sd_error_null(err, "sd_scene_load", "path");
    struct stat sb;
    if (stat(path, &sb) != 0)
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "cannot open the scene file: %s",
                            strerror(errno));
    if (S_ISDIR(sb.st_mode))
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "is a directory, not a scene file");
    if (strlen(path) >= SD_SCENE_PATH_MAX)
        return sd_error_set(err, SD_ERR_INPUT, path, 0, "", "path too long");
    yaml_document_t doc;
    sd_status st = sd_yaml_load(path, &doc, err);
    if (st != SD_OK)
        return st;
    sd_scene *s = sd_calloc(1, sizeof *s);
    if (!s) {
        st = sd_error_set(err, SD_ERR_MEMORY, path, 0, "", "out of memory");
    } else {
        snprintf(s->path, sizeof s->path, "%s", path);
        sd_parse p = {{&doc, path, err}, path, s, err, 0.0};
        st = sd_parse_root(&p, yaml_document_get_root_node(&doc));
    }
    yaml_document_delete(&doc);
    if (st != SD_OK) {
        sd_scene_free(s);
        return st;
    }
    *out = s;
    return SD_OK;
}

void sd_scene_free(sd_scene *s)
{
    if (!s)
        return;
    sd_scene_process_free(s);
    sd_scene_analysis_free(s);
    for (size_t i = 0; i < s->generator_count; ++i) {
        sd_free(s->generators[i].list);
        sd_free(s->generators[i].list_lines);
        sd_free(s->generators[i].list_shape);
        sd_free(s->generators[i].list_orient);
        sd_free(s->generators[i].list_quat);
    }
    for (size_t i = 0; i < s->shape_count; ++i) {
        sd_free(s->shapes[i].vertices);
        sd_free(s->shapes[i].points);
        sd_free(s->shapes[i].fourier_a);
        sd_free(s->shapes[i].fourier_b);
        sd_free(s->shapes[i].elements);
    }
    sd_free(s->shapes);
    sd_free(s->generators);
    sd_free(s->materials);
    sd_free(s->interactions);
    for (size_t i = 0; i < s->wall_count; ++i) { /* mesh walls (scene_mesh.c) */
        sd_free(s->walls[i].mesh_vertices);
        sd_free(s->walls[i].mesh_triangles);
        sd_free(s->walls[i].mesh_table);
    }
    sd_free(s->walls);
    sd_free(s);
}
