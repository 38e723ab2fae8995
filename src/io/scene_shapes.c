/* scene_shapes.c — the shapes: section of a scene (shape templates):
 * sphere, box, cylinder, cone, ellipsoid and polyhedron types in 3D (a
 * polyhedron from vertices, a mesh file or a built-in preset), and the
 * planar types in 2D; and the mesh file of a polyhedron, read by
 * io/mesh.c and checked here for convexity (seed 000 §2.1: templates are
 * convex; a nonconvex file is refused, or taken as its hull on request).
 *
 * Invariant: a shape is filled only from checked values; the vertices of
 * a polyhedron are distinct, at least 4 and at most SD_SHAPE_MAX_VERTICES,
 * and span a volume; every error names the scene file, line and key.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "io/mesh.h"
#include "io/scene_keys.h"
#include "io/scene_sections.h"
#include "shape/polylib.h"
#include "shape/shape.h"
#include "shape/shape2d.h"

static int sd_v3d_cmp(const void *pa, const void *pb)
{
    const sd_v3d *a = pa, *b = pb;
    if (a->x != b->x)
        return a->x < b->x ? -1 : 1;
    if (a->y != b->y)
        return a->y < b->y ? -1 : 1;
    if (a->z != b->z)
        return a->z < b->z ? -1 : 1;
    return 0;
}

/* The shape is the convex hull of a mesh file's vertices (io/mesh.c reads
 * the file); its faces only prove that the mesh is convex (seed 000 §2.1
 * templates are convex). Repeated vertices (STL repeats each in every
 * triangle) are dropped. A vertex or a face centre deeper than 1e-6 of the
 * mesh's size inside the hull makes the mesh non-convex: an error that
 * says how far, unless take_hull (then a warning in sh->warning). Errors
 * name the scene line of shapes[i].file, and the mesh file in the text. */
#define SD_MESH_CONVEX_REL 1e-6
#define SD_MESH_COORD_MAX 1e60 /* largest |coordinate| in a mesh file */
#define SD_MESH_COORD_MIN 1e-60 /* smallest extent of a mesh file's vertices */
static sd_status sd_read_mesh(sd_parse *p, sd_scene_shape *sh, const char *key, int line, int take_hull)
{
    sd_mesh mesh;
    sd_error merr;
    if (sd_mesh_read(sh->file, &mesh, &merr) != SD_OK) {
        if (merr.code == SD_ERR_MEMORY)
            return sd_error_set(p->err, SD_ERR_MEMORY, p->path, line, key, "out of memory");
        return sd_fail(p, line, key, "%s", merr.msg); /* the message names the mesh file and its line */
    }
    /* the face centres, then the vertices (sorted and made distinct below) */
    struct {
        sd_v3d *v;
        size_t n;
    } vb = {NULL, 0}, fc = {NULL, 0};
    fc.v = sd_malloc((mesh.face_count ? mesh.face_count : 1) * sizeof *fc.v);
    if (!fc.v) {
        sd_mesh_free(&mesh);
        return sd_error_set(p->err, SD_ERR_MEMORY, p->path, line, key, "out of memory");
    }
    for (size_t f = 0; f < mesh.face_count; ++f)
        fc.v[fc.n++] = sd_mesh_face_centre(&mesh, f);
    vb.v = mesh.vertices;
    vb.n = mesh.vertex_count;
    mesh.vertices = NULL; /* now the shape's */
    sd_mesh_free(&mesh);
    if (vb.n > 1)
        qsort(vb.v, vb.n, sizeof *vb.v, sd_v3d_cmp);
    size_t u = 0;
    for (size_t k = 0; k < vb.n; ++k)
        if (u == 0 || sd_v3d_cmp(&vb.v[u - 1], &vb.v[k]) != 0)
            vb.v[u++] = vb.v[k];
    sh->vertices = vb.v;
    sh->vertex_count = u;
    if (u < 4) {
        sd_free(fc.v);
        return sd_fail(p, line, key, "expected at least 4 distinct vertices in '%s', got %zu",
                       sh->file, u);
    }
    if (u > SD_SHAPE_MAX_VERTICES) {
        sd_free(fc.v);
        return sd_fail(p, line, key, "expected at most %d distinct vertices in '%s', got %zu",
                       SD_SHAPE_MAX_VERTICES, sh->file, u);
    }
    /* The hull's tests take products of up to four coordinates (normals of
     * edge cross products), which overflow past 1e77 and underflow below
     * 1e-77: such a file would read as flat. Refuse it, in the file's own
     * numbers (scale: is applied later), with a margin. */
    double big = 0.0, ext = 0.0;
    for (size_t k = 0; k < u; ++k)
        big = fmax(big, fmax(fabs(vb.v[k].x), fmax(fabs(vb.v[k].y), fabs(vb.v[k].z))));
    for (size_t k = 0; k < u; ++k)
        ext = fmax(ext, fmax(fabs(vb.v[k].x - vb.v[0].x), fmax(fabs(vb.v[k].y - vb.v[0].y),
                                                               fabs(vb.v[k].z - vb.v[0].z))));
    if (big > SD_MESH_COORD_MAX || (ext > 0.0 && ext < SD_MESH_COORD_MIN)) {
        sd_free(fc.v);
        return sd_fail(p, line, key,
                       "the vertices of '%s' %s %g in the file's units, too %s to compute its hull (it needs "
                       "coordinates of at most %g and a span of at least %g): write the mesh in other units "
                       "and set scale:",
                       sh->file, big > SD_MESH_COORD_MAX ? "reach" : "span only",
                       big > SD_MESH_COORD_MAX ? big : ext, big > SD_MESH_COORD_MAX ? "large" : "small",
                       SD_MESH_COORD_MAX, SD_MESH_COORD_MIN);
    }
    size_t which;
    double msize, depth = sd_mesh_concavity(vb.v, u, fc.v, fc.n, &which, &msize);
    sd_v3d wp = which < u ? vb.v[which] : fc.v[which - u];
    sd_free(fc.v);
    if (depth == -2)
        return sd_error_set(p->err, SD_ERR_MEMORY, p->path, line, key, "out of memory");
    if (depth < 0)
        return sd_fail(p, line, key, "the vertices of '%s' are flat (or coincide): a polyhedron needs volume",
                       sh->file);
    if (depth > SD_MESH_CONVEX_REL * msize) {
        char what[160];
        if (which < u)
            snprintf(what, sizeof what, "its vertex (%g, %g, %g)", wp.x, wp.y, wp.z);
        else
            snprintf(what, sizeof what, "the centre (%g, %g, %g) of its face %zu", wp.x, wp.y, wp.z,
                     which - u + 1);
        if (!take_hull)
            return sd_fail(p, line, key,
                           "'%s' is not convex: %s lies %g (%.3g %% of its size %g, in the file's units) "
                           "inside its convex hull; set nonconvex: hull to use the hull", sh->file, what, depth,
                           100.0 * depth / msize, msize);
        snprintf(sh->warning, sizeof sh->warning,
                 "'%.150s' is not convex (%s lies %.3g %% of its size inside its hull): using its convex hull",
                 sh->file, what, 100.0 * depth / msize);
    }
    return SD_OK;
}

sd_status sd_scene_read_mesh(const char *path, int take_hull, sd_v3d **vertices, size_t *count, char *warning,
                             size_t warning_size, sd_error *err)
{
    *vertices = NULL;
    *count = 0;
    sd_scene_shape sh;
    memset(&sh, 0, sizeof sh);
    if (strlen(path) >= sizeof sh.file)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "mesh file path longer than %zu bytes",
                            sizeof sh.file - 1);
    snprintf(sh.file, sizeof sh.file, "%s", path);
    /* no scene: messages name the mesh file alone (they all quote it) */
    sd_parse p;
    memset(&p, 0, sizeof p);
    p.path = "";
    p.err = err;
    sd_status st = sd_read_mesh(&p, &sh, "", 0, take_hull);
    if (st != SD_OK) {
        sd_free(sh.vertices);
        return st;
    }
    *vertices = sh.vertices;
    *count = sh.vertex_count;
    if (warning && warning_size)
        snprintf(warning, warning_size, "%s", sh.warning);
    return SD_OK;
}

sd_status sd_shape_ref(sd_parse *p, const char *name, int line, const char *key, int *out)
{
    for (size_t i = 0; i < p->s->shape_count; ++i)
        if (!strcmp(p->s->shapes[i].name, name)) {
            *out = (int)i;
            return SD_OK;
        }
    char known[300];
    size_t used = 0;
    known[0] = '\0';
    for (size_t i = 0; i < p->s->shape_count && used + 1 < sizeof known; ++i) {
        int w = snprintf(known + used, sizeof known - used, "%s%s", i ? ", " : "",
                         p->s->shapes[i].name);
        used += w > 0 ? (size_t)w : 0;
    }
    char esc[96];
    sd_escape(esc, sizeof esc, name, (size_t)-1);
    if (!p->s->shape_count)
        return sd_fail(p, line, key, "unknown shape '%s' (the scene has no shapes: section)", esc);
    return sd_fail(p, line, key, "unknown shape '%s' (shapes: %s)", esc, known);
}

/* Cylinder and cone: size, or diameter and length (height). */
static sd_status sd_parse_axial(sd_parse *p, yaml_node_t *m, sd_scene_shape *sh, const char *path)
{
    const char *lk = sh->kind == SD_SHAPE_CYLINDER ? "length" : "height";
    char key[96];
    sd_yaml_value sz, d, l;
    int hs = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "size", path, &sz);
    int hd = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "diameter", path, &d);
    int hl = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, lk, path, &l);
    if (hs && (hd || hl))
        return sd_fail(p, hd ? d.line : l.line, sd_yaml_kp(key, sizeof key, path, hd ? "diameter" : lk),
                       "give either size or diameter and %s, not both (size is at line %d)", lk,
                       sz.line);
    if (hs) {
        sh->size = sd_parse_v3(sz.v);
        return SD_OK;
    }
    if (!hd || !hl) {
        const char *miss = !hd && !hl ? "size" : !hd ? "diameter" : lk;
        return sd_fail(p, sh->line, sd_yaml_kp(key, sizeof key, path, miss),
                       "missing required key '%s' (give size, or diameter and %s)", miss, lk);
    }
    sh->size = (sd_v3d){d.num, d.num, l.num};
    return SD_OK;
}

/* The keys of a planar shape (dimension 2): radius, axes, points or the
 * Fourier coefficients; the shape itself is checked by the world
 * (sd_world_add_shape2d: convexity, hulls), whose message gets this entry's
 * line. */
static sd_status sd_parse_shape2d(sd_parse *p, yaml_node_t *m, sd_scene_shape *sh, const char *path)
{
    char key[96];
    sd_yaml_value v;
    sd_status st;
    switch (sh->kind2d) {
    case SD_SHAPE2D_CIRCLE:
        sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "radius", path, &v);
        sh->size = (sd_v3d){v.num, v.num, 0.0};
        break;
    case SD_SHAPE2D_ELLIPSE:
        sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "axes", path, &v);
        sh->axes[0] = v.v[0];
        sh->axes[1] = v.v[1];
        break;
    case SD_SHAPE2D_POLYGON:
    case SD_SHAPE2D_POLYBEZIER: {
        sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "points", path, &v);
        size_t np = sd_yaml_seq_len(v.node);
        sd_yaml_kp(key, sizeof key, path, "points");
        int bez = sh->kind2d == SD_SHAPE2D_POLYBEZIER;
        if (np < 3 || np > SD_SHAPE2D_MAX_POINTS || (bez && np % 3 != 0))
            return sd_fail(p, v.line, key, "expected %s (at most %d), got %zu",
                           bez ? "3m control points of m cubic segments, m >= 1" : "at least 3 points",
                           SD_SHAPE2D_MAX_POINTS, np);
        sh->points = sd_calloc(2 * np, sizeof *sh->points);
        if (!sh->points)
            return sd_yaml_oom(&p->y);
        const sd_scene_key *row = sd_scene_key_find(SD_SEC_SHAPE, "points");
        for (size_t k = 0; k < np; ++k)
            if ((st = sd_yaml_read_vec2(&p->y, row, sd_yaml_seq_item(&p->y, v.node, k), key, sh->points + 2 * k)))
                return st;
        sh->point_count = np;
        break;
    }
    case SD_SHAPE2D_FOURIER: {
        sd_yaml_value b;
        sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "fourier_a", path, &v);
        int hb = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "fourier_b", path, &b);
        size_t na = sd_yaml_seq_len(v.node), nb = hb ? sd_yaml_seq_len(b.node) : 0;
        sd_yaml_kp(key, sizeof key, path, "fourier_a");
        if (na < 1 || na > SD_SHAPE2D_MAX_ORDER + 1)
            return sd_fail(p, v.line, key, "expected a_0 .. a_N, 1 to %d values, got %zu", SD_SHAPE2D_MAX_ORDER + 1,
                           na);
        if (hb && nb != na - 1)
            return sd_fail(p, b.line, sd_yaml_kp(key, sizeof key, path, "fourier_b"),
                           "expected b_1 .. b_N, %zu values (one fewer than fourier_a), got %zu", na - 1, nb);
        sh->fourier_a = sd_calloc(na, sizeof *sh->fourier_a);
        sh->fourier_b = sd_calloc(na, sizeof *sh->fourier_b);
        if (!sh->fourier_a || !sh->fourier_b)
            return sd_yaml_oom(&p->y);
        const sd_scene_key *row = sd_scene_key_find(SD_SEC_SHAPE, "fourier_a");
        for (size_t k = 0; k < na; ++k)
            if ((st = sd_yaml_read_number(&p->y, row, sd_yaml_seq_item(&p->y, v.node, k), key, "", "", &sh->fourier_a[k])))
                return st;
        for (size_t k = 0; k < nb; ++k)
            if ((st = sd_yaml_read_number(&p->y, row, sd_yaml_seq_item(&p->y, b.node, k), key, "", "", &sh->fourier_b[k])))
                return st;
        if (!(sh->fourier_a[0] > 0.0))
            return sd_fail(p, v.line, key, "expected a_0 > 0 (twice the mean radius), got %g", sh->fourier_a[0]);
        sh->fourier_count = na;
        break;
    }
    default:
        return sd_fail(p, sh->line, path, "unknown shape type");
    }
    return SD_OK;
}

/* Keys that only a polyhedron preset takes, refused without one. */
static sd_status sd_no_preset_keys(sd_parse *p, yaml_node_t *m, const char *path)
{
    static const char *const only[] = {"size", "diameter", "length", "edge", "sides", "faces", "vertex_count", "seed"};
    char key[96];
    sd_yaml_value v;
    for (size_t k = 0; k < sizeof only / sizeof only[0]; ++k)
        if (sd_yaml_get(&p->y, m, SD_SEC_SHAPE, only[k], path, &v))
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, only[k]),
                           "%s applies to a polyhedron preset (preset: ...) only", only[k]);
    return SD_OK;
}

/* A built-in polyhedron (shape/polylib.h): its keys are checked against
 * the preset, then its vertices are made here, as if the scene gave them. */
static sd_status sd_parse_preset(sd_parse *p, yaml_node_t *m, sd_scene_shape *sh, const char *path,
                                 const sd_yaml_value *pv)
{
    char key[96];
    sd_poly_def d;
    memset(&d, 0, sizeof d);
    d.preset = pv->choice;
    d.seed = 1;
    const char *name = sd_polylib_name(d.preset);
    const int platonic = d.preset <= SD_POLY_ICOSAHEDRON;
    const int axial = d.preset == SD_POLY_PRISM || d.preset == SD_POLY_CYLINDER;
    const int rnd = d.preset == SD_POLY_RANDOM;
    sd_yaml_value sz, dm, ln, ed, sdv, fcv, vcv, sev;
    int hs = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "size", path, &sz);
    int hd = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "diameter", path, &dm);
    int hl = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "length", path, &ln);
    int he = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "edge", path, &ed);
    int hsd = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "sides", path, &sdv);
    int hfc = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "faces", path, &fcv);
    int hvc = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "vertex_count", path, &vcv);
    int hse = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "seed", path, &sev);
    /* keys another preset takes */
    struct {
        int given, ok;
        const sd_yaml_value *v;
        const char *k, *who;
    } chk[] = {
        {he, platonic, &ed, "edge", "the Platonic presets"},
        {hd, axial, &dm, "diameter", "the prism and cylinder presets"},
        {hl, axial, &ln, "length", "the prism and cylinder presets"},
        {hsd, axial, &sdv, "sides", "the prism and cylinder presets"},
        {hfc, rnd, &fcv, "faces", "the random preset"},
        {hvc, rnd, &vcv, "vertex_count", "the random preset"},
        {hse, rnd, &sev, "seed", "the random preset"},
    };
    for (size_t k = 0; k < sizeof chk / sizeof chk[0]; ++k)
        if (chk[k].given && !chk[k].ok)
            return sd_fail(p, chk[k].v->line, sd_yaml_kp(key, sizeof key, path, chk[k].k),
                           "%s applies to %s, not to %s", chk[k].k, chk[k].who, name);
    if (axial) {
        if (hs && (hd || hl))
            return sd_fail(p, hd ? dm.line : ln.line, sd_yaml_kp(key, sizeof key, path, hd ? "diameter" : "length"),
                           "give either size or diameter and length, not both (size is at line %d)", sz.line);
        if (hs) {
            d.diameter = sz.v[0];
            d.length = sz.v[2];
        } else if (hd && hl) {
            d.diameter = dm.num;
            d.length = ln.num;
        } else {
            const char *miss = !hd && !hl ? "size" : !hd ? "diameter" : "length";
            return sd_fail(p, sh->line, sd_yaml_kp(key, sizeof key, path, miss),
                           "missing required key '%s' (a %s needs size [diameter, -, length], or diameter "
                           "and length)", miss, name);
        }
        if (!hsd)
            return sd_fail(p, sh->line, sd_yaml_kp(key, sizeof key, path, "sides"),
                           "missing required key 'sides' (the number of sides of the %s, 3 to %d)", name,
                           SD_POLY_MAX_SIDES);
        if (sdv.integer < 3 || sdv.integer > SD_POLY_MAX_SIDES)
            return sd_fail(p, sdv.line, sd_yaml_kp(key, sizeof key, path, "sides"), "expected 3 to %d sides, got %lld",
                           SD_POLY_MAX_SIDES, sdv.integer);
        d.sides = (int)sdv.integer;
    } else {
        if (hs && he)
            return sd_fail(p, ed.line, sd_yaml_kp(key, sizeof key, path, "edge"),
                           "give either size or edge, not both (size is at line %d)", sz.line);
        if (!hs && !he)
            return sd_fail(p, sh->line, sd_yaml_kp(key, sizeof key, path, "size"),
                           "missing required key 'size' (the diameter of the %s's circumscribed sphere%s)", name,
                           platonic ? ", or edge: its edge length" : "");
        if (hs && !(sz.v[0] == sz.v[1] && sz.v[1] == sz.v[2]))
            return sd_fail(p, sz.line, sd_yaml_kp(key, sizeof key, path, "size"),
                           "expected one number, the diameter of the %s's circumscribed sphere", name);
        d.diameter = hs ? sz.v[0] : sd_polylib_edge_to_diameter(d.preset, ed.num);
    }
    if (rnd) {
        if (hfc == hvc)
            return sd_fail(p, hfc ? vcv.line : sh->line, sd_yaml_kp(key, sizeof key, path, hfc ? "vertex_count" : "faces"),
                           hfc ? "give either faces or vertex_count, not both"
                               : "missing required key 'faces' (or vertex_count) for the random preset");
        const sd_yaml_value *cv = hfc ? &fcv : &vcv;
        if (cv->integer < 4 || cv->integer > SD_POLY_MAX_RANDOM)
            return sd_fail(p, cv->line, sd_yaml_kp(key, sizeof key, path, hfc ? "faces" : "vertex_count"),
                           "expected 4 to %d, got %lld", SD_POLY_MAX_RANDOM, cv->integer);
        if (hfc)
            d.faces = (int)cv->integer;
        else
            d.points = (int)cv->integer;
        if (hse)
            d.seed = (uint64_t)sev.integer;
    }
    size_t n = sd_polylib_vertex_count(&d), got = 0;
    sh->vertices = sd_calloc(n ? n : 1, sizeof *sh->vertices);
    if (!sh->vertices)
        return sd_yaml_oom(&p->y);
    sd_error e2;
    if (sd_polylib_vertices(&d, sh->vertices, n, &got, &e2) != SD_OK) {
        char kk[24]; /* polylib names one of the short keys above */
        snprintf(kk, sizeof kk, "%.20s", e2.key[0] ? e2.key : "preset");
        return sd_fail(p, pv->line, sd_yaml_kp(key, sizeof key, path, kk), "%s", e2.msg);
    }
    sh->vertex_count = got;
    return SD_OK;
}

sd_status sd_parse_shapes(sd_parse *p, yaml_node_t *list)
{
    sd_scene *s = p->s;
    size_t n = sd_yaml_seq_len(list);
    char path[64], key[96], kind_name[64], choices[160];
    sd_yaml_value v;
    sd_status st;
    if (n == 0)
        return SD_OK;
    s->shapes = sd_calloc(n, sizeof *s->shapes);
    if (!s->shapes)
        return sd_yaml_oom(&p->y);
    const sd_scene_key *type_row = sd_scene_key_find(SD_SEC_SHAPE, "type");
    for (size_t i = 0; i < n; ++i) {
        yaml_node_t *m;
        if ((st = sd_yaml_entry(&p->y, list, i, "shapes", "(name: ..., type: ..., ...)", path, sizeof path, &m)))
            return st;
        /* scene index: composites may have put element shapes before it */
        const size_t si = s->shape_count;
        sd_scene_shape *sh = &s->shapes[si];
        sh->entry = i;
        sh->preset = -1;
        sh->line = sd_yaml_line(m);
        /* The type decides which keys apply, so read it first. */
        yaml_node_t *tn = sd_yaml_map_get(&p->y, m, "type");
        snprintf(key, sizeof key, "%s.type", path);
        if (!tn) {
            sd_yaml_choices_list(type_row->choices, choices, sizeof choices);
            return sd_fail(p, sh->line, key, "missing required key 'type' (%s)", choices);
        }
        if ((st = sd_yaml_read_value(&p->y, type_row, tn, key, &v)))
            return st;
        sh->kind = v.choice;
        /* planar types follow the 3D ones in the choices (scene.h) */
        sh->kind2d = sh->kind >= SD_SHAPE_KIND_COUNT ? sh->kind - SD_SHAPE_KIND_COUNT : -1;
        if ((sh->kind2d >= 0) != (s->world.dimension == 2))
            return sd_fail(p, v.line, key, "shape type '%s' is %s, but simulation.dimension is %d%s", v.str,
                           sh->kind2d >= 0 ? "planar (2D)" : "3D", s->world.dimension,
                           s->world.dimension == 2 ? " (planar types: circle, ellipse, polygon, polybezier, fourier)"
                                                   : " (set dimension: 2 for planar shapes)");
        snprintf(kind_name, sizeof kind_name, "a %s shape", v.str);
        if ((st = sd_yaml_check_map(&p->y, m, SD_SEC_SHAPE, 1u << sh->kind, kind_name, path, sh->line)))
            return st;
        s->shape_count = si + 1; /* so sd_scene_free sees its vertices */

        sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "name", path, &v);
        sd_yaml_kp(key, sizeof key, path, "name");
        if (strlen(v.str) >= SD_SCENE_NAME_MAX)
            return sd_fail(p, v.line, key, "name longer than %d characters", SD_SCENE_NAME_MAX - 1);
        for (size_t j = 0; j < si; ++j)
            if (!strcmp(s->shapes[j].name, v.str))
                return sd_fail(p, v.line, key, "duplicate shape name '%s' (shapes[%zu], line %d%s)",
                               v.str, s->shapes[j].entry, s->shapes[j].line,
                               s->shapes[j].hidden ? ", an element shape of a composite" : "");
        snprintf(sh->name, sizeof sh->name, "%s", v.str);

        sd_yaml_value rv, mv;
        int hr = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "rounding", path, &rv);
        int hm = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "margin", path, &mv);
        if (hr && hm)
            return sd_fail(p, mv.line, sd_yaml_kp(key, sizeof key, path, "margin"),
                           "give at most one of rounding and margin (rounding is at line %d)",
                           rv.line);
        sh->rounding = rv.num;
        sh->margin = mv.num;
        sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "scale", path, &v);
        sh->scale = v.num;

        switch (sh->kind) {
        case SD_SHAPE_SPHERE:
            sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "radius", path, &v);
            sh->size = (sd_v3d){v.num, v.num, v.num};
            break;
        case SD_SHAPE_BOX:
            sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "size", path, &v);
            sh->size = sd_parse_v3(v.v);
            break;
        case SD_SHAPE_CYLINDER:
        case SD_SHAPE_CONE:
            if ((st = sd_parse_axial(p, m, sh, path)))
                return st;
            break;
        case SD_SHAPE_ELLIPSOID:
            sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "semi_axes", path, &v);
            sh->size = sd_parse_v3(v.v);
            break;
        case SD_SHAPE_POLYHEDRON: {
            sd_yaml_value vv, fv, pv, ncv;
            int hv = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "vertices", path, &vv);
            int hf = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "file", path, &fv);
            int hp = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "preset", path, &pv);
            int hnc = sd_yaml_get(&p->y, m, SD_SEC_SHAPE, "nonconvex", path, &ncv);
            if (hv + hf + hp > 1) {
                const sd_yaml_value *second = hp ? &pv : &fv;
                return sd_fail(p, second->line, sd_yaml_kp(key, sizeof key, path, hp ? "preset" : "file"),
                               "give one of vertices, file and preset, not more (%s is at line %d)",
                               hv ? "vertices" : "file", hv ? vv.line : fv.line);
            }
            if (!hv && !hf && !hp)
                return sd_fail(p, sh->line, sd_yaml_kp(key, sizeof key, path, "vertices"),
                               "missing required key 'vertices' (or file: an OBJ or STL file, or "
                               "preset: a built-in polyhedron)");
            if (hnc && !hf)
                return sd_fail(p, ncv.line, sd_yaml_kp(key, sizeof key, path, "nonconvex"),
                               "nonconvex applies to a mesh file (file:) only");
            if (hp) {
                if ((st = sd_parse_preset(p, m, sh, path, &pv)))
                    return st;
                break;
            }
            if ((st = sd_no_preset_keys(p, m, path)))
                return st;
            if (hf) {
                sd_yaml_kp(key, sizeof key, path, "file");
                if (!sd_resolve(p->path, fv.str, sh->file, sizeof sh->file))
                    return sd_fail(p, fv.line, key, "path too long");
                if ((st = sd_read_mesh(p, sh, key, fv.line, hnc && ncv.choice == 1)))
                    return st;
                break;
            }
            size_t nv = sd_yaml_seq_len(vv.node);
            sd_yaml_kp(key, sizeof key, path, "vertices");
            if (nv < 4)
                return sd_fail(p, vv.line, key,
                               "expected at least 4 vertices (a hull with volume), got %zu", nv);
            if (nv > SD_SHAPE_MAX_VERTICES)
                return sd_fail(p, vv.line, key, "expected at most %d vertices, got %zu",
                               SD_SHAPE_MAX_VERTICES, nv);
            sh->vertices = sd_calloc(nv, sizeof *sh->vertices);
            if (!sh->vertices)
                return sd_yaml_oom(&p->y);
            const sd_scene_key *row = sd_scene_key_find(SD_SEC_SHAPE, "vertices");
            for (size_t k = 0; k < nv; ++k) {
                double x[3];
                /* Cannot fail: sd_yaml_check_map has read every item. */
                if ((st = sd_yaml_read_vec3(&p->y, row, sd_yaml_seq_item(&p->y, vv.node, k), key, x, NULL)))
                    return st;
                sh->vertices[k] = sd_parse_v3(x);
            }
            sh->vertex_count = nv;
            break;
        }
        case SD_SHAPE_COMPOSITE:
            /* last: it may move this entry (sh is stale after it) */
            if ((st = sd_parse_composite(p, m, path, si, n - i - 1)))
                return st;
            break;
        default:
            if (sh->kind2d >= 0) {
                if ((st = sd_parse_shape2d(p, m, sh, path)))
                    return st;
                break;
            }
            return sd_fail(p, sh->line, path, "unknown shape type");
        }
    }
    return SD_OK;
}

