/* scene_analysis.c — the analysis: section (issue 16; docs/analysis.md):
 * each entry names a type of shapedem/analysis.h, its region, bins and
 * cadence, and a CSV file of the run's output directory; this file reads
 * the entries (keys: rows of SD_SEC_ANALYSIS in io/scene_keys.c) and
 * writes their rows when io/run.c says they are due.
 *
 * Invariant: every error names the scene file, the line and the key (a
 * region outside the periodic domain, bins < 1, an unknown type, two
 * entries writing one file, a key of another type or region); a row is
 * written whole or not at all, each file flushed after its rows.
 */
#define _POSIX_C_SOURCE 200809L /* open_memstream (the size estimate) */

#include "io/scene_analysis.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "io/fsutil.h"
#include "io/output.h"

/* An analysis file under the name of a run's own file (sd_output_is_run_name). */
#define SD_AN_RUN_FILE                                                                                          \
    "%s is a file of the run's own output (frames, frames.pvd, the CSV series, summary.txt, checkpoints, the "   \
    ".shapedem-output marker): give this analysis another name or file"

static const char *const sd_an_type_names[SD_AN_TYPE_COUNT] = {
#define SD_X_AN_NAME(e, name, doc) name,
    SD_ANALYSIS_TYPES(SD_X_AN_NAME)
#undef SD_X_AN_NAME
};

/* Defaults the key table cannot hold as numbers (its default column says
 * the same words): bins per type, the fit range, the velocity cells. */
static int sd_an_default_bins(int type)
{
    return type == SD_AN_RADIAL_POROSITY ? 10 : 20;
}

/* The region's bounding box (cylinder: the box around its two end discs). */
static void sd_an_region_bounds(const sd_region_def *r, double lo[3], double hi[3])
{
    if (r->kind == SD_REGION_BOX) {
        lo[0] = r->lo.x, lo[1] = r->lo.y, lo[2] = r->lo.z;
        hi[0] = r->hi.x, hi[1] = r->hi.y, hi[2] = r->hi.z;
        return;
    }
    double n = sqrt(r->axis.x * r->axis.x + r->axis.y * r->axis.y + r->axis.z * r->axis.z);
    const double a[3] = {r->axis.x / n, r->axis.y / n, r->axis.z / n}, c[3] = {r->center.x, r->center.y, r->center.z};
    for (int k = 0; k < 3; ++k) {
        double e = fabs(a[k]) * 0.5 * r->length + r->radius * sqrt(fmax(0.0, 1.0 - a[k] * a[k]));
        lo[k] = c[k] - e;
        hi[k] = c[k] + e;
    }
}

static sd_status sd_an_parse_region(sd_parse *p, yaml_node_t *m, const char *path, sd_scene_analysis_entry *e)
{
    char key[160];
    sd_yaml_value v, lo, hi;
    memset(&e->region, 0, sizeof e->region);
    int has_region = sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "region", path, &v);
    static const char *const box_keys[] = {"min", "max"}, *const cyl_keys[] = {"center", "axis", "radius", "length"};
    int planar = p->s->world.dimension == 2;
    if (!has_region) {
        for (int k = 0; k < 2; ++k)
            if (sd_yaml_map_get(&p->y, m, box_keys[k]))
                return sd_fail(p, sd_yaml_key_line(&p->y, m, box_keys[k]),
                               sd_yaml_kp(key, sizeof key, path, box_keys[k]),
                               "'%s' belongs to a region: give region: box with it", box_keys[k]);
        for (int k = 0; k < 4; ++k)
            if (sd_yaml_map_get(&p->y, m, cyl_keys[k]) && !(k == 0 && e->type == SD_AN_REPOSE_ANGLE))
                return sd_fail(p, sd_yaml_key_line(&p->y, m, cyl_keys[k]),
                               sd_yaml_kp(key, sizeof key, path, cyl_keys[k]),
                               "'%s' belongs to a region: give region: cylinder with it", cyl_keys[k]);
        return SD_OK;
    }
    int line = v.line;
    if (e->type == SD_AN_REPOSE_ANGLE)
        return sd_fail(p, line, sd_yaml_kp(key, sizeof key, path, "region"),
                       "repose_angle takes no region (the heap is found about center, default its centre of mass)");
    if (v.choice == 0) { /* box */
        for (int k = 0; k < 4; ++k)
            if (sd_yaml_map_get(&p->y, m, cyl_keys[k]))
                return sd_fail(p, sd_yaml_key_line(&p->y, m, cyl_keys[k]),
                               sd_yaml_kp(key, sizeof key, path, cyl_keys[k]),
                               "'%s' is a cylinder key; a box region takes min and max", cyl_keys[k]);
        if (!sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "min", path, &lo) ||
            !sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "max", path, &hi))
            return sd_fail(p, line, sd_yaml_kp(key, sizeof key, path, "region"), "a box region needs min and max");
        for (int a = 0; a < (planar ? 2 : 3); ++a)
            if (!(hi.v[a] > lo.v[a]))
                return sd_fail(p, hi.line, sd_yaml_kp(key, sizeof key, path, "max"),
                               "expected max > min on %c, got min %g, max %g", 'x' + a, lo.v[a], hi.v[a]);
        e->region.kind = SD_REGION_BOX;
        e->region.lo = sd_parse_v3(lo.v);
        e->region.hi = sd_parse_v3(hi.v);
    } else {
        for (int k = 0; k < 2; ++k)
            if (sd_yaml_map_get(&p->y, m, box_keys[k]))
                return sd_fail(
                    p, sd_yaml_key_line(&p->y, m, box_keys[k]), sd_yaml_kp(key, sizeof key, path, box_keys[k]),
                    "'%s' is a box key; a cylinder region takes center, axis, radius and length", box_keys[k]);
        sd_yaml_value c, ax, r, len;
        if (!sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "center", path, &c) ||
            !sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "radius", path, &r))
            return sd_fail(p, line, sd_yaml_kp(key, sizeof key, path, "region"),
                           "a cylinder region needs center and radius (and length in 3D)");
        int has_len = sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "length", path, &len);
        if (!planar && !has_len)
            return sd_fail(p, line, sd_yaml_kp(key, sizeof key, path, "length"),
                           "a cylinder region needs its length (m, along the axis)");
        sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "axis", path, &ax);
        if (!(ax.v[0] * ax.v[0] + ax.v[1] * ax.v[1] + ax.v[2] * ax.v[2] > 0))
            return sd_fail(p, ax.line ? ax.line : line, sd_yaml_kp(key, sizeof key, path, "axis"),
                           "expected a non-zero axis");
        if (planar && (ax.v[0] != 0 || ax.v[1] != 0))
            return sd_fail(p, ax.line, sd_yaml_kp(key, sizeof key, path, "axis"),
                           "in 2D a cylinder region is the disc of the plane: its axis is z, got [%g, %g, %g]", ax.v[0],
                           ax.v[1], ax.v[2]);
        e->region.kind = SD_REGION_CYLINDER;
        e->region.center = sd_parse_v3(c.v);
        e->region.axis = sd_parse_v3(ax.v);
        e->region.radius = r.num;
        e->region.length = has_len ? len.num : 0.0;
    }
    /* inside the periodic domain, where one is given (as insert: checks) */
    double rl[3], rh[3];
    sd_an_region_bounds(&e->region, rl, rh);
    const sd_world_def *wd = &p->s->world;
    const double dl[3] = {wd->domain_lo.x, wd->domain_lo.y, wd->domain_lo.z};
    const double dh[3] = {wd->domain_hi.x, wd->domain_hi.y, wd->domain_hi.z};
    for (int a = 0; a < (planar ? 2 : 3); ++a)
        if (dh[a] > dl[a] && (rl[a] < dl[a] - 1e-12 || rh[a] > dh[a] + 1e-12))
            return sd_fail(p, line, sd_yaml_kp(key, sizeof key, path, "region"),
                           "the analysis region spans [%g, %g] m on %c, outside the domain [%g, %g] m "
                           "(simulation.domain)",
                           rl[a], rh[a], 'x' + a, dl[a], dh[a]);
    return SD_OK;
}

static sd_status sd_an_parse_entry(sd_parse *p, yaml_node_t *m, const char *path, sd_scene_analysis_entry *e)
{
    char key[160], kind_name[64];
    sd_yaml_value v;
    sd_status st;
    int line = sd_yaml_line(m);
    yaml_node_t *tn = sd_yaml_map_get(&p->y, m, "type");
    snprintf(key, sizeof key, "%s.type", path);
    if (!tn)
        return sd_fail(p, line, key,
                       "missing required key 'type' (porosity, radial_porosity, coordination, "
                       "velocity_field, speed_pdf, energy, bed_height, surface_angle, repose_angle)");
    if ((st = sd_yaml_read_value(&p->y, sd_scene_key_find(SD_SEC_ANALYSIS, "type"), tn, key, &v)))
        return st;
    e->type = v.choice;
    e->line = line;
    snprintf(kind_name, sizeof kind_name, "type %s", v.str);
    if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_ANALYSIS, 1u << v.choice, kind_name, path, line)))
        return st;
    const int planar = p->s->world.dimension == 2;
    if (e->type == SD_AN_COORDINATION && p->s->world.solver == SD_SOLVER_GRID)
        return sd_fail(p, v.line, key,
                       "coordination reads the cells solver's contact list; the grid solver "
                       "keeps none (simulation.solver: cells)");
    if ((st = sd_an_parse_region(p, m, path, e)))
        return st;
    if (e->type == SD_AN_RADIAL_POROSITY || e->type == SD_AN_SURFACE_ANGLE) {
        if (e->region.kind != SD_REGION_CYLINDER)
            return sd_fail(p, sd_yaml_key_line(&p->y, m, "region"), sd_yaml_kp(key, sizeof key, path, "region"),
                           "%s needs region: cylinder (%s)", sd_an_type_names[e->type],
                           e->type == SD_AN_SURFACE_ANGLE ? "the drum" : "the annuli are about its axis");
    }
    if (e->type == SD_AN_VELOCITY_FIELD && e->region.kind != SD_REGION_BOX)
        return sd_fail(p, sd_yaml_key_line(&p->y, m, "region"), sd_yaml_kp(key, sizeof key, path, "region"),
                       "velocity_field needs region: box (the slab whose particles are binned)");
    if (e->type == SD_AN_SURFACE_ANGLE && !planar) {
        const sd_v3d a = e->region.axis, g = p->s->world.gravity;
        double an = sqrt(a.x * a.x + a.y * a.y + a.z * a.z), gn = sqrt(g.x * g.x + g.y * g.y + g.z * g.z);
        double c = gn > 0 ? fabs(a.x * g.x + a.y * g.y + a.z * g.z) / (an * gn) : fabs(a.z) / an;
        if (c > 1.0 - 1e-6)
            return sd_fail(p, sd_yaml_key_line(&p->y, m, "axis"), sd_yaml_kp(key, sizeof key, path, "axis"),
                           "the drum's axis is vertical: its cross section has no free-surface angle");
    }
    /* name and file */
    if (sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "name", path, &v))
        snprintf(e->name, sizeof e->name, "%s", v.str);
    if (sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "file", path, &v)) {
        if (strchr(v.str, '/') || strchr(v.str, '\\') || strcmp(v.str, ".") == 0 || strcmp(v.str, "..") == 0 ||
            strlen(v.str) >= sizeof e->file)
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "file"),
                           "expected a plain file name (no directory, at most %zu characters) in the output "
                           "directory, got '%s'",
                           sizeof e->file - 1, v.str);
        if (sd_output_is_run_name(v.str)) /* as below, at the file: key's own line */
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "file"), SD_AN_RUN_FILE, v.str);
        snprintf(e->file, sizeof e->file, "%s", v.str);
    }
    /* cadence: every steps, or interval seconds rounded to steps */
    sd_yaml_value ev, iv;
    int has_every = sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "every", path, &ev);
    int has_int = sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "interval", path, &iv);
    if (has_every && has_int)
        return sd_fail(p, iv.line, sd_yaml_kp(key, sizeof key, path, "interval"),
                       "give at most one of every (steps) and interval (s)");
    e->every = p->s->output.stats_every > 0 ? p->s->output.stats_every : 1;
    if (has_every)
        e->every = (long)ev.integer;
    if (has_int) {
        double st_ = iv.num / p->s->world.dt;
        if (!(st_ < 1e15))
            return sd_fail(p, iv.line, sd_yaml_kp(key, sizeof key, path, "interval"), "interval %g s is too long",
                           iv.num);
        e->every = st_ < 1.0 ? 1 : (long)floor(st_ + 0.5);
    }
    /* the type's own keys */
    if (sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "voxel", path, &v)) {
        e->voxel = v.num;
        /* the lattice's size now, not hours into the run (sd_world_porosity's limit) */
        const sd_region_def *r = &e->region;
        double n = 1;
        if (r->kind == SD_REGION_BOX) {
            const double ext[3] = {r->hi.x - r->lo.x, r->hi.y - r->lo.y, planar ? 0 : r->hi.z - r->lo.z};
            for (int a = 0; a < 3; ++a)
                n *= ext[a] > 0 ? fmax(1.0, floor(ext[a] / v.num + 0.5)) : 1.0;
        } else if (r->kind == SD_REGION_CYLINDER) {
            double nr = fmax(1.0, floor(2 * r->radius / v.num + 0.5));
            n = nr * nr * (planar ? 1.0 : fmax(1.0, floor(r->length / v.num + 0.5)));
        }
        if (n > (double)SD_POROSITY_MAX_VOXELS)
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "voxel"),
                           "voxel %g m cuts the region into %.3g voxels, more than %.3g: take a larger voxel", v.num,
                           n, (double)SD_POROSITY_MAX_VOXELS);
    }
    e->bins = sd_an_default_bins(e->type);
    if (sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "bins", path, &v)) {
        /* each bin is a row per output: 10^5 bins wrote 963 MB in 200 steps */
        if (v.integer > SD_AN_BINS_MAX)
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "bins"),
                           "expected at most %d bins (each is a row of the file at every output), got %lld",
                           SD_AN_BINS_MAX, (long long)v.integer);
        e->bins = (int)v.integer;
    }
    if ((e->type == SD_AN_SURFACE_ANGLE || e->type == SD_AN_REPOSE_ANGLE) && e->bins < 2)
        return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "bins"),
                       "expected at least 2 columns for a line fit, got %d", e->bins);
    e->cells[0] = e->cells[1] = 10;
    if (sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "cells", path, &v)) {
        for (int k = 0; k < 2; ++k)
            if (!(v.v[k] >= 1) || v.v[k] != floor(v.v[k]) || v.v[k] > 10000)
                return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "cells"),
                               "expected two integers in 1..10000, got [%g, %g]", v.v[0], v.v[1]);
        e->cells[0] = (int)v.v[0];
        e->cells[1] = (int)v.v[1];
    }
    e->plane = planar ? 0 : 1; /* xz: a drum about y seen from the side */
    if (sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "plane", path, &v)) {
        e->plane = v.choice;
        if (planar && v.choice != 0)
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "plane"),
                           "the planar mode's velocity field lies in the xy plane");
    }
    if (sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "max_speed", path, &v))
        e->max_speed = v.num;
    sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "fraction", path, &v);
    e->fraction = v.num;
    e->fit[0] = 0.2;
    e->fit[1] = 0.8;
    if (sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "fit", path, &v)) {
        if (!(v.v[0] >= 0 && v.v[1] <= 1 && v.v[1] > v.v[0]))
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "fit"),
                           "expected [lo, hi] with 0 <= lo < hi <= 1, got [%g, %g]", v.v[0], v.v[1]);
        e->fit[0] = v.v[0];
        e->fit[1] = v.v[1];
    }
    if (e->type == SD_AN_REPOSE_ANGLE && sd_yaml_get(&p->y, m, SD_SEC_ANALYSIS, "center", path, &v)) {
        e->has_center = 1;
        e->center = sd_parse_v3(v.v);
    }
    return SD_OK;
}

sd_status sd_parse_analysis(sd_parse *p, yaml_node_t *root)
{
    sd_yaml_value v;
    sd_status st;
    if (!sd_yaml_get(&p->y, root, SD_SEC_ROOT, "analysis", "", &v))
        return SD_OK;
    size_t n = sd_yaml_seq_len(v.node);
    if (n > SD_SCENE_ANALYSIS_MAX)
        return sd_fail(p, v.line, "analysis", "at most %d analyses, got %zu", SD_SCENE_ANALYSIS_MAX, n);
    sd_scene_analysis *sa = sd_calloc(1, sizeof *sa);
    if (!sa)
        return sd_yaml_oom(&p->y);
    p->s->analysis = sa;
    int seen[SD_AN_TYPE_COUNT] = {0};
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m;
        char path[64];
        if ((st = sd_yaml_entry(&p->y, v.node, i, "analysis", "(type: porosity|coordination|..., ...)", path,
                                sizeof path, &m)))
            return st;
        sd_scene_analysis_entry *e = &sa->e[i];
        if ((st = sd_an_parse_entry(p, m, path, e)))
            return st;
        if (!e->name[0]) { /* porosity, then porosity_1, ... */
            if (seen[e->type])
                snprintf(e->name, sizeof e->name, "%s_%d", sd_an_type_names[e->type], seen[e->type]);
            else
                snprintf(e->name, sizeof e->name, "%s", sd_an_type_names[e->type]);
        }
        seen[e->type]++;
        if (!e->file[0]) { /* NAME.csv (two members of one struct: no snprintf of one into the other) */
            size_t nl = strlen(e->name);
            nl = nl > sizeof e->file - 5 ? sizeof e->file - 5 : nl;
            memcpy(e->file, e->name, nl);
            memcpy(e->file + nl, ".csv", 5);
        }
        for (size_t k = 0; k < i; ++k)
            if (strcmp(sa->e[k].file, e->file) == 0) {
                char key[80];
                return sd_fail(p, e->line, sd_yaml_kp(key, sizeof key, path, "file"),
                               "analysis[%zu] writes %s already: give this entry another name or file", k, e->file);
            }
        /* a run's own file (io/output.c): its writes would replace the rows */
        if (sd_output_is_run_name(e->file)) {
            char key[80];
            return sd_fail(p, e->line, sd_yaml_kp(key, sizeof key, path, "file"), SD_AN_RUN_FILE, e->file);
        }
        sa->count = i + 1;
    }
    return SD_OK;
}

void sd_scene_analysis_free(sd_scene *s)
{
    sd_free(s->analysis);
    s->analysis = NULL;
}

/* ---- the run's series ------------------------------------------------------- */

struct sd_analysis_run {
    const sd_scene_analysis *sa;
    size_t count;
    FILE *f[SD_SCENE_ANALYSIS_MAX];
    long last[SD_SCENE_ANALYSIS_MAX]; /* step of the last row, -1 none */
};

static void sd_an_header(FILE *f, const sd_scene_analysis_entry *e)
{
    switch (e->type) {
    case SD_AN_POROSITY:
        fprintf(f, "time,step,voxels,solid_voxels,solid_fraction,porosity,voxel_a,voxel_b,voxel_c,volume\n");
        break;
    case SD_AN_RADIAL_POROSITY:
        fprintf(f, "time,step,bin,r_inner,r_outer,voxels,solid_voxels,solid_fraction,porosity\n");
        break;
    case SD_AN_COORDINATION:
        fprintf(f, "time,step,particles,contacts,wall_contacts,mean,mean_with_walls,rattlers");
        for (int k = 0; k < SD_COORDINATION_MAX; ++k)
            fprintf(f, ",z%d", k);
        fprintf(f, ",z%d_or_more\n", SD_COORDINATION_MAX);
        break;
    case SD_AN_VELOCITY_FIELD:
        fprintf(f, "time,step,i,j,u,v,count,vx,vy,vz\n");
        break;
    case SD_AN_SPEED_PDF:
        fprintf(f, "time,step,bin,speed_lo,speed_hi,count,pdf\n");
        break;
    case SD_AN_ENERGY:
        fprintf(f, "time,step,particles,mass,kinetic_translational,kinetic_rotational,kinetic_total,mean_speed,"
                   "max_speed,mean_vx,mean_vy,mean_vz\n");
        break;
    case SD_AN_BED_HEIGHT:
        fprintf(f, "time,step,particles,top,fraction_height,mean_height\n");
        break;
    case SD_AN_SURFACE_ANGLE:
    case SD_AN_REPOSE_ANGLE:
        fprintf(f, "time,step,angle_deg,slope,rms,columns\n");
        break;
    default:
        break;
    }
}

sd_status sd_analysis_run_open(const sd_scene *s, const char *dir, long resume_step, sd_analysis_run **out,
                               sd_error *err)
{
    *out = NULL;
    if (!s->analysis || s->analysis->count == 0 || !dir)
        return SD_OK;
    sd_analysis_run *a = sd_calloc(1, sizeof *a);
    if (!a)
        return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
    a->sa = s->analysis;
    for (size_t k = 0; k < a->sa->count; ++k) {
        const sd_scene_analysis_entry *e = &a->sa->e[k];
        char path[SD_SCENE_PATH_MAX + 96];
        snprintf(path, sizeof path, "%s/%s", dir, e->file);
        a->last[k] = resume_step > 0 ? 0 : -1; /* a restart writes no row before one is due */
        /* as the run's own CSV files (io/output.c): a plain file of an
         * earlier run is replaced (continued by a restart); a link or a
         * directory under the name is refused, never written through */
        const char *what = sd_fs_not_regular(path);
        if (what) {
            sd_analysis_run_close(a);
            return sd_error_set(err, SD_ERR_IO, path, 0, "",
                                "%s has the name of analysis '%s''s file; shapedem "
                                "will not write through it",
                                what, e->name);
        }
        int kept = 0;
        sd_status st;
        if (resume_step > 0)
            st = sd_fs_resume_csv(path, resume_step, &a->f[k], &kept, err);
        else {
            remove(path);
            st = sd_fs_create_append(path, &a->f[k], err);
        }
        if (st != SD_OK) {
            sd_analysis_run_close(a);
            return st;
        }
        a->count = k + 1;
        if (!kept)
            sd_an_header(a->f[k], e);
        fflush(a->f[k]);
    }
    *out = a;
    return SD_OK;
}

double sd_analysis_estimate_bytes(const sd_scene *s, long steps, size_t *files)
{
    *files = 0;
    const sd_scene_analysis *sa = s->analysis;
    if (!sa)
        return 0.0;
    double total = 0;
    for (size_t k = 0; k < sa->count; ++k) {
        const sd_scene_analysis_entry *e = &sa->e[k];
        char *buf = NULL;
        size_t len = 0;
        FILE *f = open_memstream(&buf, &len);
        if (!f)
            continue;
        sd_an_header(f, e);
        fclose(f);
        double cols = 1;
        for (size_t c = 0; c < len; ++c)
            cols += buf[c] == ',';
        free(buf);
        /* rows at step 0, every `every` steps and at the end */
        double outputs = 2.0 + (double)(steps > 0 ? steps : 0) / (double)(e->every > 0 ? e->every : 1);
        double per = e->type == SD_AN_SPEED_PDF || e->type == SD_AN_RADIAL_POROSITY ? (double)e->bins
                     : e->type == SD_AN_VELOCITY_FIELD ? (double)e->cells[0] * (double)e->cells[1]
                                                       : 1.0;
        total += (double)len + outputs * per * cols * 10.0;
        ++*files;
    }
    return total;
}

long sd_analysis_run_next(const sd_analysis_run *a, long done)
{
    long next = LONG_MAX;
    if (!a)
        return next;
    for (size_t k = 0; k < a->count; ++k) {
        long ev = a->sa->e[k].every, to = ev - done % ev;
        if (to < next)
            next = to;
    }
    return next;
}

/* One entry's rows at the world's present state. */
static sd_status sd_an_rows(sd_analysis_run *a, const sd_scene_analysis_entry *e, FILE *f, const sd_world *w,
                            sd_error *err)
{
    const double t = sd_world_time(w);
    const long step = sd_world_step_count(w);
    const sd_region_def *reg = e->region.kind != SD_REGION_NONE ? &e->region : NULL;
    sd_status st = SD_OK;
    switch (e->type) {
    case SD_AN_POROSITY:
    case SD_AN_RADIAL_POROSITY: {
        sd_porosity_def d = sd_porosity_def_default();
        d.region = e->region;
        d.voxel = e->voxel;
        d.radial_bins = e->type == SD_AN_RADIAL_POROSITY ? e->bins : 0;
        sd_porosity po;
        long long *rs = NULL, *rv = NULL;
        if (d.radial_bins > 0) {
            rs = sd_calloc((size_t)d.radial_bins * 2u, sizeof *rs);
            if (!rs)
                return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (radial porosity)");
            rv = rs + d.radial_bins;
        }
        if ((st = sd_world_porosity(w, &d, &po, rs, rv, err)) != SD_OK) {
            sd_free(rs);
            return st;
        }
        if (e->type == SD_AN_POROSITY) {
            fprintf(f, "%.10g,%ld,%lld,%lld,%.10g,%.10g,%.6g,%.6g,%.6g,%.10g\n", t, step, po.voxels, po.solid,
                    po.solid_fraction, po.porosity, po.voxel[0], po.voxel[1], po.voxel[2], po.volume);
        } else {
            double dr = e->region.radius / d.radial_bins;
            for (int b = 0; b < d.radial_bins; ++b) {
                double sf = rv[b] > 0 ? (double)rs[b] / (double)rv[b] : 0.0;
                fprintf(f, "%.10g,%ld,%d,%.10g,%.10g,%lld,%lld,%.10g,%.10g\n", t, step, b, b * dr, (b + 1) * dr, rv[b],
                        rs[b], sf, rv[b] > 0 ? 1.0 - sf : 0.0);
            }
        }
        sd_free(rs);
        break;
    }
    case SD_AN_COORDINATION: {
        sd_coordination c;
        if ((st = sd_world_coordination(w, reg, &c, err)) != SD_OK)
            return st;
        fprintf(f, "%.10g,%ld,%zu,%ld,%ld,%.10g,%.10g,%zu", t, step, c.particles, c.contacts, c.wall_contacts, c.mean,
                c.mean_with_walls, c.rattlers);
        for (int k = 0; k <= SD_COORDINATION_MAX; ++k)
            fprintf(f, ",%zu", c.histogram[k]);
        fprintf(f, "\n");
        break;
    }
    case SD_AN_VELOCITY_FIELD: {
        sd_velocity_field_def d = sd_velocity_field_def_default();
        d.region = e->region;
        d.plane = e->plane;
        d.cells[0] = e->cells[0];
        d.cells[1] = e->cells[1];
        size_t nc = (size_t)e->cells[0] * (size_t)e->cells[1];
        size_t *cnt = sd_calloc(nc, sizeof *cnt);
        sd_v3d *mv = sd_calloc(nc, sizeof *mv);
        if (!cnt || !mv) {
            sd_free(cnt);
            sd_free(mv);
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (velocity field)");
        }
        if ((st = sd_world_velocity_field(w, &d, cnt, mv, err)) == SD_OK) {
            const int au = e->plane == 2 ? 1 : 0, av = e->plane == 0 ? 1 : 2;
            const double lo[3] = {e->region.lo.x, e->region.lo.y, e->region.lo.z};
            const double hi[3] = {e->region.hi.x, e->region.hi.y, e->region.hi.z};
            const double du = (hi[au] - lo[au]) / e->cells[0], dv = (hi[av] - lo[av]) / e->cells[1];
            for (int j = 0; j < e->cells[1]; ++j)
                for (int i = 0; i < e->cells[0]; ++i) {
                    size_t c = (size_t)i + (size_t)e->cells[0] * (size_t)j;
                    fprintf(f, "%.10g,%ld,%d,%d,%.10g,%.10g,%zu,%.10g,%.10g,%.10g\n", t, step, i, j,
                            lo[au] + (i + 0.5) * du, lo[av] + (j + 0.5) * dv, cnt[c], mv[c].x, mv[c].y, mv[c].z);
                }
        }
        sd_free(cnt);
        sd_free(mv);
        break;
    }
    case SD_AN_SPEED_PDF: {
        size_t *cnt = sd_calloc((size_t)e->bins, sizeof *cnt);
        if (!cnt)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory (speed pdf)");
        double top = 0;
        if ((st = sd_world_speed_histogram(w, reg, e->bins, e->max_speed, cnt, &top, err)) == SD_OK) {
            size_t total = 0;
            for (int b = 0; b < e->bins; ++b)
                total += cnt[b];
            double dv = top / e->bins;
            for (int b = 0; b < e->bins; ++b)
                fprintf(f, "%.10g,%ld,%d,%.10g,%.10g,%zu,%.10g\n", t, step, b, b * dv, (b + 1) * dv, cnt[b],
                        total > 0 && dv > 0 ? (double)cnt[b] / ((double)total * dv) : 0.0);
        }
        sd_free(cnt);
        break;
    }
    case SD_AN_ENERGY: {
        sd_motion_stats m;
        if ((st = sd_world_motion_stats(w, reg, &m, err)) != SD_OK)
            return st;
        fprintf(f, "%.10g,%ld,%zu,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", t, step, m.particles,
                m.mass, m.kinetic_translational, m.kinetic_rotational, m.kinetic_translational + m.kinetic_rotational,
                m.mean_speed, m.max_speed, m.mean_velocity.x, m.mean_velocity.y, m.mean_velocity.z);
        break;
    }
    case SD_AN_BED_HEIGHT: {
        sd_bed_height b;
        if ((st = sd_world_bed_height(w, reg, e->fraction, &b, err)) != SD_OK)
            return st;
        fprintf(f, "%.10g,%ld,%zu,%.10g,%.10g,%.10g\n", t, step, b.particles, b.top, b.fraction_height, b.mean);
        break;
    }
    case SD_AN_SURFACE_ANGLE:
    case SD_AN_REPOSE_ANGLE: {
        sd_surface_fit s;
        if (e->type == SD_AN_SURFACE_ANGLE)
            st = sd_world_drum_surface(w, &e->region, e->bins, e->fit, &s, err);
        else
            st = sd_world_heap_angle(w, e->has_center ? &e->center : NULL, e->bins, e->fit, &s, err);
        if (st != SD_OK)
            return st;
        fprintf(f, "%.10g,%ld,%.10g,%.10g,%.10g,%d\n", t, step, s.angle, s.slope, s.rms, s.columns);
        break;
    }
    default:
        break;
    }
    (void)a;
    return st;
}

sd_status sd_analysis_run_rows(sd_analysis_run *a, const sd_world *w, long done, long last, sd_error *err)
{
    if (!a)
        return SD_OK;
    for (size_t k = 0; k < a->count; ++k) {
        const sd_scene_analysis_entry *e = &a->sa->e[k];
        if (a->last[k] == done || (a->last[k] >= 0 && done % e->every != 0 && done != last))
            continue;
        sd_status st = sd_an_rows(a, e, a->f[k], w, err);
        if (st != SD_OK) {
            /* the key of the entry, for the message */
            char msg[sizeof err->msg];
            snprintf(msg, sizeof msg, "%s", err->msg);
            return sd_error_set(err, st, e->file, 0, err->key, "analysis '%s': %s", e->name, msg);
        }
        fflush(a->f[k]);
        a->last[k] = done;
    }
    return SD_OK;
}

void sd_analysis_run_close(sd_analysis_run *a)
{
    if (!a)
        return;
    for (size_t k = 0; k < a->count; ++k)
        if (a->f[k])
            fclose(a->f[k]);
    sd_free(a);
}
