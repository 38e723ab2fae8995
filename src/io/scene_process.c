/* scene_process.c — the insert: and outlets: sections (cells solver,
 * shapedem/process.h; issue 16): particles inserted in a region at a rate
 * or all at once from a mix of templates and sphere size laws, and
 * regions that remove what enters them. The keys are rows of the one
 * table (io/scene_keys.c); this file applies the rules between them and
 * fills the world's defs, so the builder only hands them over.
 *
 * Invariant: every error names the scene file, the line and the key (a
 * mix that does not sum to 1, a negative radius, a region outside the
 * periodic domain, a solver without insertion, a mesh region's file);
 * a template entry takes the sphere size laws for its equivalent radius
 * (size_classes scaled copies), and an outlet that no
 * particle can reach is a warning, kept with the scene for the CLI.
 */
#include "io/scene_process.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "io/mesh.h"

/* A mesh region (insert only): the closed mesh of `file` (STL or OBJ,
 * relative to the scene), scaled then moved by position; its box in lo,
 * hi for the checks here. The world checks that it is closed. */
static sd_status sd_parse_mesh_region(sd_parse *p, yaml_node_t *m, const char *path, size_t slot, sd_region_def *r)
{
    sd_yaml_value v, sc, pos;
    char key[128], file[SD_SCENE_PATH_MAX];
    sd_scene_process *sp = p->s->process;
    sd_yaml_get(&p->y, m, SD_SEC_INSERT, "file", path, &v);
    sd_yaml_kp(key, sizeof key, path, "file");
    if (!sd_resolve(p->path, v.str, file, sizeof file))
        return sd_fail(p, v.line, key, "the path '%s' is too long", v.str);
    double scale = sd_yaml_get(&p->y, m, SD_SEC_INSERT, "scale", path, &sc) ? sc.num : 1.0;
    sd_yaml_get(&p->y, m, SD_SEC_INSERT, "position", path, &pos);
    sd_v3d shift = pos.node ? sd_parse_v3(pos.v) : (sd_v3d){0, 0, 0};
    sd_mesh mesh;
    sd_error merr;
    memset(&merr, 0, sizeof merr);
    sd_status st = sd_mesh_read(file, &mesh, &merr);
    if (st == SD_ERR_MEMORY)
        return sd_yaml_oom(&p->y);
    if (st != SD_OK)
        return sd_fail(p, v.line, key, "%s", merr.msg);
    sd_free(sp->mesh_vertices[slot]);
    sd_free(sp->mesh_triangles[slot]);
    sp->mesh_vertices[slot] = sd_malloc((mesh.vertex_count ? mesh.vertex_count : 1) * sizeof(sd_v3d));
    sp->mesh_triangles[slot] = sd_malloc((mesh.triangle_count ? mesh.triangle_count : 1) * sizeof *mesh.triangles);
    if (!sp->mesh_vertices[slot] || !sp->mesh_triangles[slot]) {
        sd_mesh_free(&mesh);
        return sd_yaml_oom(&p->y);
    }
    for (size_t k = 0; k < mesh.vertex_count; ++k) {
        sd_v3d x = mesh.vertices[k];
        sp->mesh_vertices[slot][k] = (sd_v3d){shift.x + scale * x.x, shift.y + scale * x.y, shift.z + scale * x.z};
    }
    memcpy(sp->mesh_triangles[slot], mesh.triangles, mesh.triangle_count * sizeof *mesh.triangles);
    r->vertices = sp->mesh_vertices[slot];
    r->vertex_count = mesh.vertex_count;
    r->triangles = (const uint32_t(*)[3])sp->mesh_triangles[slot];
    r->triangle_count = mesh.triangle_count;
    sd_mesh_free(&mesh);
    if (r->vertex_count == 0)
        return sd_fail(p, v.line, key, "the mesh file '%s' has no vertices", file);
    r->lo = r->hi = r->vertices[0];
    for (size_t k = 1; k < r->vertex_count; ++k) {
        sd_v3d x = r->vertices[k];
        r->lo = (sd_v3d){fmin(r->lo.x, x.x), fmin(r->lo.y, x.y), fmin(r->lo.z, x.z)};
        r->hi = (sd_v3d){fmax(r->hi.x, x.x), fmax(r->hi.y, x.y), fmax(r->hi.z, x.z)};
    }
    return SD_OK;
}

/* The region keys of an insert or outlet entry (kind already chosen). */
static sd_status sd_parse_region(sd_parse *p, yaml_node_t *m, sd_scene_section sec, const char *path, int kind,
                                 size_t slot, sd_region_def *r)
{
    sd_yaml_value v;
    char key[128];
    memset(r, 0, sizeof *r);
    r->kind = kind;
    if (kind == SD_REGION_MESH) {
        if (p->s->world.dimension == 2)
            return sd_fail(p, sd_yaml_line(m), sd_yaml_kp(key, sizeof key, path, "region"),
                           "dimension 2: a mesh region is 3D only");
        return sd_parse_mesh_region(p, m, path, slot, r);
    }
    if (kind == SD_REGION_BOX) {
        sd_yaml_value lo, hi;
        sd_yaml_get(&p->y, m, sec, "min", path, &lo);
        sd_yaml_get(&p->y, m, sec, "max", path, &hi);
        int planar = p->s->world.dimension == 2;
        for (int a = 0; a < (planar ? 2 : 3); ++a)
            if (!(hi.v[a] > lo.v[a]))
                return sd_fail(p, hi.line, sd_yaml_kp(key, sizeof key, path, "max"),
                               "expected max > min on %c, got min %g, max %g", 'x' + a, lo.v[a], hi.v[a]);
        r->lo = sd_parse_v3(lo.v);
        r->hi = sd_parse_v3(hi.v);
        return SD_OK;
    }
    sd_yaml_get(&p->y, m, sec, "center", path, &v);
    r->center = sd_parse_v3(v.v);
    sd_yaml_get(&p->y, m, sec, "axis", path, &v);
    if (!(v.v[0] * v.v[0] + v.v[1] * v.v[1] + v.v[2] * v.v[2] > 0))
        return sd_fail(p, v.line ? v.line : sd_yaml_line(m), sd_yaml_kp(key, sizeof key, path, "axis"),
                       "expected a non-zero axis");
    r->axis = sd_parse_v3(v.v);
    sd_yaml_get(&p->y, m, sec, "radius", path, &v);
    r->radius = v.num;
    if (kind == SD_REGION_CYLINDER) {
        sd_yaml_get(&p->y, m, sec, "length", path, &v);
        r->length = v.num;
    }
    return SD_OK;
}

/* The region's box, for the domain and reach checks (and shapedem check's
 * probe of the insertions, cli/check_report.c). */
void sd_region_box(const sd_region_def *r, double lo[3], double hi[3])
{
    if (r->kind == SD_REGION_BOX || r->kind == SD_REGION_MESH) { /* a mesh keeps its box in lo, hi */
        lo[0] = r->lo.x, lo[1] = r->lo.y, lo[2] = r->lo.z;
        hi[0] = r->hi.x, hi[1] = r->hi.y, hi[2] = r->hi.z;
        return;
    }
    double n = sqrt(r->axis.x * r->axis.x + r->axis.y * r->axis.y + r->axis.z * r->axis.z);
    const double a[3] = {r->axis.x / n, r->axis.y / n, r->axis.z / n}, c[3] = {r->center.x, r->center.y, r->center.z};
    double half = r->kind == SD_REGION_CYLINDER ? 0.5 * r->length : 0;
    for (int k = 0; k < 3; ++k) {
        double e = fabs(a[k]) * half + r->radius * sqrt(fmax(0.0, 1.0 - a[k] * a[k]));
        lo[k] = c[k] - e;
        hi[k] = c[k] + e;
    }
}

static sd_status sd_parse_mix(sd_parse *p, yaml_node_t *list, const char *ipath, sd_insert_def *d)
{
    size_t n = sd_yaml_seq_len(list);
    char path[96], key[160];
    sd_yaml_value v;
    sd_status st;
    if (n == 0 || n > SD_INSERT_MIX_MAX)
        return sd_fail(p, sd_yaml_line(list), sd_yaml_kp(key, sizeof key, ipath, "mix"),
                       "expected 1 to %d entries in the mix, got %zu", SD_INSERT_MIX_MAX, n);
    double sum = 0;
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m;
        char sec[128];
        snprintf(sec, sizeof sec, "%s.mix", ipath);
        if ((st = sd_yaml_entry(&p->y, list, i, sec, "(material: ..., radius or shape: ...)", path, sizeof path, &m)))
            return st;
        if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_INSERT_MIX, SD_KIND_ALL, "", path, sd_yaml_line(m))))
            return st;
        sd_insert_entry *e = &d->entries[i];
        memset(e, 0, sizeof *e);
        e->shape = -1;
        sd_yaml_get(&p->y, m, SD_SEC_INSERT_MIX, "material", path, &v);
        if ((st = sd_material_ref(p, v.str, v.line, sd_yaml_kp(key, sizeof key, path, "material"), &e->material)))
            return st;
        sd_yaml_get(&p->y, m, SD_SEC_INSERT_MIX, "fraction", path, &v);
        e->fraction = v.num;
        sum += v.num;
        int has_shape = sd_yaml_get(&p->y, m, SD_SEC_INSERT_MIX, "shape", path, &v);
        if (has_shape && (st = sd_shape_ref(p, v.str, v.line, sd_yaml_kp(key, sizeof key, path, "shape"), &e->shape)))
            return st;
        sd_yaml_value dist, rad;
        int has_dist = sd_yaml_get(&p->y, m, SD_SEC_INSERT_MIX, "distribution", path, &dist);
        int has_rad = sd_yaml_get(&p->y, m, SD_SEC_INSERT_MIX, "radius", path, &rad);
        sd_yaml_value cls;
        if (sd_yaml_get(&p->y, m, SD_SEC_INSERT_MIX, "size_classes", path, &cls)) {
            if (!has_shape || !(has_dist || has_rad))
                return sd_fail(p, cls.line, sd_yaml_kp(key, sizeof key, path, "size_classes"),
                               "size_classes cuts a template's size law into scaled copies: give it with shape and "
                               "radius or distribution");
            if (cls.integer > SD_SIZE_SCALES_MAX)
                return sd_fail(p, cls.line, sd_yaml_kp(key, sizeof key, path, "size_classes"),
                               "expected 1 to %d size classes, got %lld", SD_SIZE_SCALES_MAX,
                               (long long)cls.integer);
            e->size_classes = (int)cls.integer;
        }
        /* a template without a size law keeps its own size (size all zero);
         * with one, the law is its equivalent radius' (shapedem/process.h) */
        if (has_shape && !has_dist && !has_rad)
            continue;
        sd_size_def *s = &e->size;
        int kind = has_dist ? dist.choice : (has_rad && rad.lo < rad.hi ? SD_SIZE_UNIFORM : SD_SIZE_FIXED);
        s->kind = kind;
        if (kind == SD_SIZE_FIXED || kind == SD_SIZE_UNIFORM) {
            if (!has_rad)
                return sd_fail(p, sd_yaml_line(m), sd_yaml_kp(key, sizeof key, path, "radius"),
                               "a sphere entry (or a template with a size law) needs radius (a number or {min, max}) or a distribution");
            s->a = rad.lo;
            s->b = rad.hi;
            if (!(rad.lo > 0))
                return sd_fail(p, rad.line, sd_yaml_kp(key, sizeof key, path, "radius"),
                               "expected radii > 0, got %g (a negative or zero radius in the size distribution)",
                               rad.lo);
        } else if (kind == SD_SIZE_NORMAL || kind == SD_SIZE_LOGNORMAL) {
            const char *ka = kind == SD_SIZE_NORMAL ? "mean" : "median";
            const char *kb = kind == SD_SIZE_NORMAL ? "std" : "sigma";
            sd_yaml_value va, vb;
            if (!sd_yaml_get(&p->y, m, SD_SEC_INSERT_MIX, ka, path, &va) ||
                !sd_yaml_get(&p->y, m, SD_SEC_INSERT_MIX, kb, path, &vb))
                return sd_fail(p, dist.line, sd_yaml_kp(key, sizeof key, path, "distribution"),
                               "a %s distribution needs %s and %s", kind == SD_SIZE_NORMAL ? "normal" : "lognormal",
                               ka, kb);
            if (!(va.num > 0))
                return sd_fail(p, va.line, sd_yaml_kp(key, sizeof key, path, ka),
                               "expected a %s radius > 0, got %g (a negative or zero radius in the size distribution)",
                               ka, va.num);
            s->a = va.num;
            s->b = vb.num;
            if (has_rad) {
                s->min = rad.lo;
                s->max = rad.hi > rad.lo ? rad.hi : 0;
                if (rad.lo < 0)
                    return sd_fail(p, rad.line, sd_yaml_kp(key, sizeof key, path, "radius"),
                                   "expected a truncation {min, max} >= 0, got min %g (a negative radius)", rad.lo);
            }
            /* the largest radius drawn (8 spreads, or the max) within
             * SD_SIZE_SPREAD_MAX of the median: a sigma of 100 draws
             * infinite radii (world/process.c refuses them too) */
            double big = kind == SD_SIZE_NORMAL ? s->a + 8 * s->b : s->a * exp(8 * s->b);
            if (s->max > 0)
                big = fmin(big, s->max);
            if (s->b > 0 && (!isfinite(big) || big > SD_SIZE_SPREAD_MAX * s->a))
                return sd_fail(p, vb.line, sd_yaml_kp(key, sizeof key, path, kb),
                               "%s %g draws radii up to %.3g m, %.3g times the %s %g m (at most %g): a smaller %s, "
                               "or a truncation radius: {min, max}",
                               kb, s->b, big, big / s->a, ka, s->a, SD_SIZE_SPREAD_MAX, kb);
        } else { /* table */
            sd_yaml_value cv, by;
            if (!sd_yaml_get(&p->y, m, SD_SEC_INSERT_MIX, "classes", path, &cv))
                return sd_fail(p, dist.line, sd_yaml_kp(key, sizeof key, path, "classes"),
                               "a table distribution needs classes: [[r_lo, r_hi, fraction], ...]");
            size_t nc = sd_yaml_seq_len(cv.node);
            if (nc == 0 || nc > SD_SIZE_CLASSES_MAX)
                return sd_fail(p, cv.line, sd_yaml_kp(key, sizeof key, path, "classes"),
                               "expected 1 to %d size classes, got %zu", SD_SIZE_CLASSES_MAX, nc);
            s->classes = (int)nc;
            double fs = 0;
            const sd_scene_key *row = sd_scene_key_find(SD_SEC_INSERT_MIX, "classes");
            for (size_t c = 0; c < nc; ++c) {
                double t[3];
                char ck[180];
                snprintf(ck, sizeof ck, "%s.classes[%zu]", path, c);
                yaml_node_t *item = sd_yaml_seq_item(&p->y, cv.node, c);
                if ((st = sd_yaml_read_vec3(&p->y, row, item, ck, t, NULL)))
                    return st;
                if (!(t[0] > 0) || !(t[1] >= t[0]) || !(t[2] >= 0))
                    return sd_fail(p, sd_yaml_line(item), ck,
                                   "expected [r_lo, r_hi, fraction] with 0 < r_lo <= r_hi and fraction >= 0, got "
                                   "[%g, %g, %g]%s", t[0], t[1], t[2],
                                   t[0] <= 0 ? " (a negative or zero radius in the size distribution)" : "");
                s->lo[c] = t[0];
                s->hi[c] = t[1];
                s->fraction[c] = t[2];
                fs += t[2];
            }
            if (!(fabs(fs - 1.0) <= 1e-6))
                return sd_fail(p, cv.line, sd_yaml_kp(key, sizeof key, path, "classes"),
                               "the class fractions sum to %.9g, expected 1", fs);
            sd_yaml_get(&p->y, m, SD_SEC_INSERT_MIX, "classes_by", path, &by);
            s->by_mass = by.node ? by.choice : 0;
        }
    }
    if (!(fabs(sum - 1.0) <= 1e-6))
        return sd_fail(p, sd_yaml_line(list), sd_yaml_kp(key, sizeof key, ipath, "mix"),
                       "the mix fractions sum to %.9g, expected 1 (by %s)", sum, d->mix_by_mass ? "mass" : "number");
    d->entry_count = (int)n;
    return SD_OK;
}

static sd_scene_process *sd_process_scene(sd_parse *p)
{
    if (!p->s->process)
        p->s->process = sd_calloc(1, sizeof *p->s->process);
    return p->s->process;
}

static sd_status sd_parse_inserts(sd_parse *p, yaml_node_t *list)
{
    size_t n = sd_yaml_seq_len(list);
    char path[64], key[128], kind_name[64];
    sd_yaml_value v;
    sd_status st;
    sd_scene_process *sp = sd_process_scene(p);
    if (!sp)
        return sd_yaml_oom(&p->y);
    if (n > SD_SCENE_PROCESS_MAX)
        return sd_fail(p, sd_yaml_line(list), "insert", "at most %d insertions, got %zu", SD_SCENE_PROCESS_MAX, n);
    if (p->s->world.solver == SD_SOLVER_GRID)
        return sd_fail(p, sd_yaml_line(list), "insert",
                       "insert: runs on the cells solver; the grid solver pours with its pour: section");
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m;
        if ((st = sd_yaml_entry(&p->y, list, i, "insert", "(region: box|cylinder|disc|mesh, mix: ..., count: ...)", path,
                                sizeof path, &m)))
            return st;
        int line = sd_yaml_line(m);
        yaml_node_t *rn = sd_yaml_map_get(&p->y, m, "region");
        snprintf(key, sizeof key, "%s.region", path);
        if (!rn)
            return sd_fail(p, line, key, "missing required key 'region' (box, cylinder, disc or mesh)");
        if ((st = sd_yaml_read_value(&p->y, sd_scene_key_find(SD_SEC_INSERT, "region"), rn, key, &v)))
            return st;
        int kind = v.choice + 1; /* box|cylinder|disc -> SD_REGION_BOX .. */
        snprintf(kind_name, sizeof kind_name, "a %s region", v.str);
        if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_INSERT, 1u << v.choice, kind_name, path, line)))
            return st;
        sd_insert_def *d = &sp->inserts[i];
        *d = sd_insert_def_default();
        sp->insert_lines[i] = line;
        sp->insert_key_lines[i] = v.line;
        if (sd_yaml_get(&p->y, m, SD_SEC_INSERT, "name", path, &v))
            snprintf(sp->insert_names[i], SD_SCENE_NAME_MAX, "%s", v.str);
        else
            snprintf(sp->insert_names[i], SD_SCENE_NAME_MAX, "insert%zu", i);
        d->name = sp->insert_names[i];
        if ((st = sd_parse_region(p, m, SD_SEC_INSERT, path, kind, i, &d->region)))
            return st;
        sd_yaml_get(&p->y, m, SD_SEC_INSERT, "mix_by", path, &v);
        d->mix_by_mass = v.node ? v.choice : 0;
        sd_yaml_get(&p->y, m, SD_SEC_INSERT, "mix", path, &v);
        if ((st = sd_parse_mix(p, v.node, path, d)))
            return st;
        sd_yaml_value cnt, mass;
        int has_count = sd_yaml_get(&p->y, m, SD_SEC_INSERT, "count", path, &cnt);
        int has_mass = sd_yaml_get(&p->y, m, SD_SEC_INSERT, "mass", path, &mass);
        if (has_count == has_mass)
            return sd_fail(p, line, sd_yaml_kp(key, sizeof key, path, "count"),
                           "give exactly one of count (particles) and mass (kg)");
        if (has_count) {
            d->count = (size_t)cnt.integer;
            if ((st = sd_count_particles(p, (double)cnt.integer, cnt.line, sd_yaml_kp(key, sizeof key, path, "count"))))
                return st;
        } else {
            d->mass = mass.num;
        }
        sd_yaml_value rate, mrate;
        int has_rate = sd_yaml_get(&p->y, m, SD_SEC_INSERT, "rate", path, &rate);
        int has_mrate = sd_yaml_get(&p->y, m, SD_SEC_INSERT, "mass_rate", path, &mrate);
        if (has_rate && has_mrate)
            return sd_fail(p, mrate.line, sd_yaml_kp(key, sizeof key, path, "mass_rate"),
                           "give at most one of rate (particles/s) and mass_rate (kg/s)");
        d->rate = has_rate ? rate.num : 0;
        d->mass_rate = has_mrate ? mrate.num : 0;
        sd_yaml_get(&p->y, m, SD_SEC_INSERT, "start", path, &v);
        d->start = v.num;
        sd_yaml_get(&p->y, m, SD_SEC_INSERT, "velocity", path, &v);
        d->velocity = sd_parse_v3(v.v);
        sd_yaml_get(&p->y, m, SD_SEC_INSERT, "velocity_jitter", path, &v);
        d->velocity_jitter = v.num;
        sd_yaml_get(&p->y, m, SD_SEC_INSERT, "orientation", path, &v);
        d->random_orientation = v.node ? v.choice == 0 : 1;
        if (sd_yaml_get(&p->y, m, SD_SEC_INSERT, "attempts", path, &v) && v.integer > SD_INSERT_ATTEMPTS_MAX)
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "attempts"),
                           "expected at most %d positions per particle, got %lld", SD_INSERT_ATTEMPTS_MAX,
                           (long long)v.integer);
        d->attempts = v.node ? (int)v.integer : 100;
        /* inside the domain where one is given (periodic boxes) */
        const sd_world_def *wd = &p->s->world;
        double lo[3], hi[3];
        sd_region_box(&d->region, lo, hi);
        const double dl[3] = {wd->domain_lo.x, wd->domain_lo.y, wd->domain_lo.z};
        const double dh[3] = {wd->domain_hi.x, wd->domain_hi.y, wd->domain_hi.z};
        for (int a = 0; a < (wd->dimension == 2 ? 2 : 3); ++a)
            if (dh[a] > dl[a] && (lo[a] < dl[a] - 1e-12 || hi[a] > dh[a] + 1e-12))
                return sd_fail(p, sp->insert_key_lines[i], sd_yaml_kp(key, sizeof key, path, "region"),
                               "the insertion region spans [%g, %g] m on %c, outside the domain [%g, %g] m "
                               "(simulation.domain)", lo[a], hi[a], 'x' + a, dl[a], dh[a]);
        sp->insert_count = i + 1;
    }
    return SD_OK;
}

static sd_status sd_parse_outlets(sd_parse *p, yaml_node_t *list)
{
    size_t n = sd_yaml_seq_len(list);
    char path[64], key[128], kind_name[64];
    sd_yaml_value v;
    sd_status st;
    sd_scene_process *sp = sd_process_scene(p);
    if (!sp)
        return sd_yaml_oom(&p->y);
    if (n > SD_SCENE_PROCESS_MAX)
        return sd_fail(p, sd_yaml_line(list), "outlets", "at most %d outlets, got %zu", SD_SCENE_PROCESS_MAX, n);
    if (p->s->world.solver == SD_SOLVER_GRID)
        return sd_fail(p, sd_yaml_line(list), "outlets",
                       "outlets: run on the cells solver; the grid solver has its floor outlet (outlet:)");
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m;
        if ((st = sd_yaml_entry(&p->y, list, i, "outlets", "(region: box|cylinder, ...)", path, sizeof path, &m)))
            return st;
        int line = sd_yaml_line(m);
        yaml_node_t *rn = sd_yaml_map_get(&p->y, m, "region");
        snprintf(key, sizeof key, "%s.region", path);
        if (!rn)
            return sd_fail(p, line, key, "missing required key 'region' (box or cylinder)");
        if ((st = sd_yaml_read_value(&p->y, sd_scene_key_find(SD_SEC_OUTLETS, "region"), rn, key, &v)))
            return st;
        int kind = v.choice + 1;
        snprintf(kind_name, sizeof kind_name, "a %s region", v.str);
        if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_OUTLETS, 1u << v.choice, kind_name, path, line)))
            return st;
        sd_region_outlet_def *o = &sp->outlets[i];
        *o = sd_region_outlet_def_default();
        sp->outlet_lines[i] = line;
        if (sd_yaml_get(&p->y, m, SD_SEC_OUTLETS, "name", path, &v)) {
            /* the name heads two columns of outlet.csv: a comma, a quote or
             * a line break in it would split the header */
            for (const char *c = v.str; *c; ++c)
                if (*c == ',' || *c == '"' || (unsigned char)*c < 0x20 || *c == 0x7f) {
                    char nkey[96];
                    snprintf(nkey, sizeof nkey, "%s.name", path);
                    return sd_fail(p, v.line, nkey, "the name heads columns of outlet.csv: it may not hold a comma, "
                                   "a double quote or a control character (a line break, a tab)");
                }
            snprintf(sp->outlet_names[i], SD_SCENE_NAME_MAX, "%s", v.str);
        } else
            snprintf(sp->outlet_names[i], SD_SCENE_NAME_MAX, "outlet%zu", i);
        o->name = sp->outlet_names[i];
        if ((st = sd_parse_region(p, m, SD_SEC_OUTLETS, path, kind, i, &o->region)))
            return st;
        sd_yaml_get(&p->y, m, SD_SEC_OUTLETS, "open_at", path, &v);
        o->open_at = v.num;
        sd_yaml_get(&p->y, m, SD_SEC_OUTLETS, "check_every", path, &v);
        o->check_every = v.node ? (long)v.integer : 1;
        sp->outlet_count = i + 1;
    }
    return SD_OK;
}

/* Outlet k's warning, at its place in the scene file as errors are
 * (file:line: key: what), so the user finds the entry it is about. */
static void sd_outlet_warn(sd_scene *s, size_t k, const char *what)
{
    sd_scene_process *sp = s->process;
    snprintf(sp->outlet_warning[k], sizeof sp->outlet_warning[k], "%s:%d: outlets[%zu]: %s", s->path,
             sp->outlet_lines[k], k, what);
}

/* A warning when no particle can reach outlet k: gravity pulls every
 * particle away from it (all of them, and every insertion region, lie
 * below it along the gravity vector, none moving up), or it lies outside
 * every closed box wall that holds them. Heuristic, never an error. */
static void sd_outlet_reach(sd_scene *s, const sd_scene_spheres *sp_all, size_t k)
{
    sd_scene_process *sp = s->process;
    double olo[3], ohi[3];
    sd_region_box(&sp->outlets[k].region, olo, ohi);
    const double g[3] = {s->world.gravity.x, s->world.gravity.y, s->world.gravity.z};
    double gn = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    char out[256];
    sp->outlet_warning[k][0] = '\0';
    if (gn > 0) {
        /* height against gravity: h(x) = -g.x / |g| */
        double top_outlet = -HUGE_VAL, low_outlet = HUGE_VAL;
        for (int c = 0; c < 8; ++c) {
            double x[3] = {(c & 1) ? ohi[0] : olo[0], (c & 2) ? ohi[1] : olo[1], (c & 4) ? ohi[2] : olo[2]};
            double h = -(g[0] * x[0] + g[1] * x[1] + g[2] * x[2]) / gn;
            top_outlet = fmax(top_outlet, h);
            low_outlet = fmin(low_outlet, h);
        }
        double top = -HUGE_VAL;
        int up = 0;
        for (size_t i = 0; i < sp_all->count; ++i) {
            const sd_sphere_def *d = &sp_all->defs[i];
            top = fmax(top, -(g[0] * d->position.x + g[1] * d->position.y + g[2] * d->position.z) / gn + d->radius);
            up |= -(g[0] * d->velocity.x + g[1] * d->velocity.y + g[2] * d->velocity.z) > 0;
        }
        for (size_t i = 0; i < sp->insert_count; ++i) {
            double lo[3], hi[3];
            sd_region_box(&sp->inserts[i].region, lo, hi);
            const sd_v3d u = sp->inserts[i].velocity;
            up |= -(g[0] * u.x + g[1] * u.y + g[2] * u.z) > 0 || sp->inserts[i].velocity_jitter > 0;
            for (int c = 0; c < 8; ++c) {
                double x[3] = {(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]};
                top = fmax(top, -(g[0] * x[0] + g[1] * x[1] + g[2] * x[2]) / gn);
            }
        }
        if (!up && low_outlet > top && (sp_all->count > 0 || sp->insert_count > 0)) {
            snprintf(out, 256, "outlet '%s' lies above every particle and insertion region (by %g m against "
                               "gravity) and nothing moves up: no particle can reach it",
                     sp->outlet_names[k], low_outlet - top);
            sd_outlet_warn(s, k, out);
            return;
        }
    }
    /* a closed box wall that holds every particle and misses the outlet */
    for (size_t wi = 0; wi < s->wall_count; ++wi) {
        const sd_scene_wall *wl = &s->walls[wi];
        if (wl->kind != 1 || wl->open_faces != 0)
            continue;
        const double blo[3] = {wl->lo.x, wl->lo.y, wl->lo.z}, bhi[3] = {wl->hi.x, wl->hi.y, wl->hi.z};
        int apart = 0;
        for (int a = 0; a < 3; ++a)
            apart |= ohi[a] < blo[a] || olo[a] > bhi[a];
        if (apart) {
            snprintf(out, 256, "outlet '%s' lies outside the closed box wall '%s': no particle can reach it",
                     sp->outlet_names[k], wl->name);
            sd_outlet_warn(s, k, out);
            return;
        }
    }
}

sd_status sd_parse_process(sd_parse *p, yaml_node_t *root)
{
    sd_yaml_value v;
    sd_status st;
    if (sd_yaml_get(&p->y, root, SD_SEC_ROOT, "insert", "", &v) && (st = sd_parse_inserts(p, v.node)))
        return st;
    if (sd_yaml_get(&p->y, root, SD_SEC_ROOT, "outlets", "", &v) && (st = sd_parse_outlets(p, v.node)))
        return st;
    if (p->s->process && p->s->process->outlet_count) {
        /* the reach warnings need the generators' particles */
        double *bound = NULL;
        sd_scene_spheres sp;
        sd_error e2;
        int shaped = p->s->shape_count > 0;
        if (shaped) {
            bound = sd_calloc(p->s->shape_count, sizeof *bound);
            if (!bound)
                return sd_yaml_oom(&p->y);
        }
        if (sd_scene_generate(p->s, bound, &sp, &e2) == SD_OK) {
            for (size_t k = 0; k < p->s->process->outlet_count; ++k)
                sd_outlet_reach(p->s, &sp, k);
            sd_scene_spheres_free(&sp);
        }
        sd_free(bound);
    }
    return SD_OK;
}

void sd_scene_process_free(sd_scene *s)
{
    for (int k = 0; s->process && k < SD_SCENE_PROCESS_MAX; ++k) {
        sd_free(s->process->mesh_vertices[k]);
        sd_free(s->process->mesh_triangles[k]);
    }
    sd_free(s->process);
    s->process = NULL;
}

sd_status sd_scene_build_process(const sd_scene *s, sd_world *w, sd_error *err)
{
    const sd_scene_process *sp = s->process;
    if (!sp)
        return SD_OK;
    char key[300];
    for (size_t i = 0; i < sp->insert_count; ++i)
        if (sd_world_add_insertion(w, &sp->inserts[i], err) < 0) {
            snprintf(key, sizeof key, "insert[%zu]%s%s", i, err->key[0] ? "." : "",
                     strncmp(err->key, "insert.", 7) == 0 ? err->key + 7 : err->key);
            char msg[sizeof err->msg];
            snprintf(msg, sizeof msg, "%s", err->msg);
            return sd_error_set(err, SD_ERR_INPUT, s->path, sp->insert_lines[i], key, "%s", msg);
        }
    for (size_t i = 0; i < sp->outlet_count; ++i)
        if (sd_world_add_outlet(w, &sp->outlets[i], err) < 0) {
            snprintf(key, sizeof key, "outlets[%zu]", i);
            char msg[sizeof err->msg];
            snprintf(msg, sizeof msg, "%s", err->msg);
            return sd_error_set(err, SD_ERR_INPUT, s->path, sp->outlet_lines[i], key, "%s", msg);
        }
    return SD_OK;
}

const char *sd_scene_outlet_warning(const sd_scene *s, size_t k)
{
    if (!s || !s->process || k >= s->process->outlet_count)
        return NULL;
    return s->process->outlet_warning[k];
}

/* ---- outlet.csv -------------------------------------------------------------- */

void sd_outlet_csv_header(FILE *f, const sd_world *w)
{
    fprintf(f, "time,step,particles,initial,inserted,removed,inserted_mass,removed_mass");
    for (size_t k = 0; k < sd_world_outlet_count(w); ++k) {
        sd_outlet_info oi;
        sd_world_get_outlet(w, k, &oi);
        fprintf(f, ",%s_count,%s_mass", oi.name, oi.name);
    }
    fprintf(f, ",mass_rate_out\n");
}

/* A value as the row prints it (ten significant digits) and as it reads
 * back from the file. */
static double sd_outlet_printed(double x)
{
    char buf[32];
    snprintf(buf, sizeof buf, "%.10g", x);
    return strtod(buf, NULL);
}

void sd_outlet_csv_row(FILE *f, const sd_world *w, double *last_time, double *last_mass)
{
    sd_process_info pi;
    sd_world_get_process(w, &pi);
    double t = sd_world_time(w);
    fprintf(f, "%.10g,%ld,%zu,%zu,%zu,%zu,%.10g,%.10g", t, sd_world_step_count(w), sd_world_particle_count(w),
            pi.initial, pi.inserted, pi.removed, pi.inserted_mass, pi.removed_mass);
    for (size_t k = 0; k < sd_world_outlet_count(w); ++k) {
        sd_outlet_info oi;
        sd_world_get_outlet(w, k, &oi);
        fprintf(f, ",%zu,%.10g", oi.removed, oi.mass);
    }
    /* kg/s over the interval since the previous row (0 on the first), from
     * the time and removed mass as the two rows print them: the rate a
     * reader gets from the columns, and the one a restart gets from the
     * kept rows (io/run.c), so a continued file is the uninterrupted one's */
    double tp = sd_outlet_printed(t), mp = sd_outlet_printed(pi.removed_mass);
    double rate = tp > *last_time ? (mp - *last_mass) / (tp - *last_time) : 0.0;
    fprintf(f, ",%.10g\n", rate);
    *last_time = tp;
    *last_mass = mp;
}
