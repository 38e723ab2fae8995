/* scene_mesh.c — triangle-mesh walls in a scene (walls: - type: mesh).
 *
 * Reads the mesh file (io/mesh.c: format checks), places it in the world
 * frame (world = position + R (scale x_file), R from the quaternion
 * `orientation` or the angles `rotation` in degrees), prepares it once (geom/trimesh.c: weld, clean, orient)
 * so that a broken mesh is refused at load with the scene line and key,
 * and reads the motion: section and its CSV time table. The world
 * prepares the same vertices again when the scene is built
 * (sd_world_add_mesh); loading refuses what the world would refuse.
 *
 * Invariant: on an error nothing of the wall is kept (the caller frees the
 * scene, and this wall's arrays are NULL or complete); every message names
 * the scene file, its line and the key, and the mesh or table file.
 */
#define _POSIX_C_SOURCE 200809L

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "geom/trimesh.h"
#include "io/lines.h"
#include "io/mesh.h"
#include "io/scene_sections.h"

/* The unit quaternion (w, x, y, z) of `rotation: [rx, ry, rz]` (degrees):
 * rx about x, then ry about y, then rz about z, all about the fixed world
 * axes, so R = Rz Ry Rx and q = qz qy qx. */
static void sd_mesh_rotation_quat(const double deg[3], double q[4])
{
    const double pi = 3.14159265358979323846;
    double h[3], c[3], s[3];
    for (int k = 0; k < 3; ++k) {
        h[k] = 0.5 * deg[k] * pi / 180.0;
        c[k] = cos(h[k]);
        s[k] = sin(h[k]);
    }
    /* qy qx, then qz (qy qx); each factor (cos, sin * axis) */
    double yx[4] = {c[1] * c[0], c[1] * s[0], s[1] * c[0], -s[1] * s[0]};
    q[0] = c[2] * yx[0] - s[2] * yx[3];
    q[1] = c[2] * yx[1] - s[2] * yx[2];
    q[2] = c[2] * yx[2] + s[2] * yx[1];
    q[3] = c[2] * yx[3] + s[2] * yx[0];
}

/* The motion's time table: rows of 5 numbers, t strictly increasing. */
static sd_status sd_mesh_table_read(sd_parse *p, sd_scene_wall *w, const char *file, int line, const char *key)
{
    if (sd_lines_is_directory(file))
        return sd_fail(p, line, key, "the motion table '%s' is a directory, not a file", file);
    FILE *f = fopen(file, "r");
    if (!f)
        return sd_fail(p, line, key, "cannot open the motion table '%s': %s", file, strerror(errno));
    size_t cap = 0, n = 0;
    double *rows = NULL;
    char buf[1024];
    int ln = 0, header_ok = 1;
    sd_status st = SD_OK;
    for (;;) {
        sd_lines_result lr = sd_lines_next(f, buf, sizeof buf, &ln);
        if (lr == SD_LINES_END)
            break;
        if (lr != SD_LINES_OK) {
            st = lr == SD_LINES_LONG  ? sd_fail(p, line, key, "%s line %d: longer than %zu characters", file, ln,
                                               sizeof buf - 2)
                 : lr == SD_LINES_NUL ? sd_fail(p, line, key, "%s line %d: a NUL byte (not a text table)", file, ln)
                                      : sd_fail(p, line, key, "%s: cannot read: %s", file, strerror(errno));
            break;
        }
        char *c = buf + strspn(buf, " \t\r\n");
        if (!*c || *c == '#')
            continue;
        double r[5];
        int k = 0;
        char *at = c, *end;
        for (; k < 5; ++k) {
            at += strspn(at, " \t");
            errno = 0;
            r[k] = strtod(at, &end);
            if (end == at || errno == ERANGE || !isfinite(r[k]) || (strpbrk(at, "xX") && strpbrk(at, "xX") < end))
                break;
            at = end + strspn(end, " \t");
            if (k < 4) {
                if (*at != ',')
                    break;
                ++at;
            }
        }
        at += strspn(at, " \t\r\n");
        if (k < 5 || *at) {
            /* a header names the columns (t,dx,dy,dz,angle_deg): only a
             * first line that starts with a name; a row that looks numeric
             * but does not parse (a comment after it, a hex number, an
             * empty field) is refused, never dropped */
            char *hend;
            (void)strtod(c, &hend); /* inf, nan: numbers, not names */
            if (header_ok && n == 0 && (isalpha((unsigned char)*c) || *c == '_') && hend == c) {
                header_ok = 0;
                continue;
            }
            char esc[80];
            sd_escape(esc, sizeof esc, c, strcspn(c, "\r\n"));
            st = sd_fail(p, line, key,
                         "%s line %d: expected 5 finite decimal numbers t, dx, dy, dz, angle_deg, got '%s'", file, ln,
                         esc);
            break;
        }
        header_ok = 0;
        if (n > 0 && !(r[0] > rows[5 * (n - 1)])) {
            st = sd_fail(p, line, key, "%s line %d: t = %g s does not increase (the row before has %g s)", file, ln,
                         r[0], rows[5 * (n - 1)]);
            break;
        }
        if (n == cap) {
            cap = cap ? 2 * cap : 64;
            double *nr = sd_realloc(rows, cap * 5 * sizeof *rows);
            if (!nr) {
                st = sd_yaml_oom(&p->y);
                break;
            }
            rows = nr;
        }
        memcpy(rows + 5 * n++, r, sizeof r);
    }
    fclose(f);
    if (st == SD_OK && n == 0)
        st = sd_fail(p, line, key, "the motion table '%s' has no rows (t, dx, dy, dz, angle_deg)", file);
    if (st != SD_OK) {
        sd_free(rows);
        return st;
    }
    w->mesh_table = rows;
    w->mesh_motion.table = rows;
    w->mesh_motion.table_rows = n;
    return SD_OK;
}

static sd_status sd_parse_mesh_motion(sd_parse *p, yaml_node_t *mm, sd_scene_wall *w, const char *wpath)
{
    char path[96], key[128], kind_name[64];
    sd_yaml_value v;
    sd_status st;
    snprintf(path, sizeof path, "%s.motion", wpath);
    int line = sd_yaml_line(mm);
    yaml_node_t *tn = sd_yaml_map_get(&p->y, mm, "type");
    snprintf(key, sizeof key, "%s.type", path);
    if (!tn)
        return sd_fail(p, line, key, "missing required key 'type' (fixed, translate, rotate or table)");
    if ((st = sd_yaml_read_value(&p->y, sd_scene_key_find(SD_SEC_MESH_MOTION, "type"), tn, key, &v)))
        return st;
    sd_mesh_motion_def *d = &w->mesh_motion;
    *d = sd_mesh_motion_def_default();
    /* the choices are in SD_MESH_FIXED .. SD_MESH_TABLE order */
    d->kind = v.choice;
    snprintf(kind_name, sizeof kind_name, "a %s motion", v.str);
    if ((st = sd_yaml_check_map(&p->y, mm, SD_SEC_MESH_MOTION, 1u << d->kind, kind_name, path, line)))
        return st;
    w->has_mesh_motion = 1;
    if (sd_yaml_get(&p->y, mm, SD_SEC_MESH_MOTION, "velocity", path, &v))
        d->velocity = sd_parse_v3(v.v);
    if (sd_yaml_get(&p->y, mm, SD_SEC_MESH_MOTION, "axis_point", path, &v))
        d->axis_point = sd_parse_v3(v.v);
    if (d->kind == SD_MESH_ROTATE || d->kind == SD_MESH_TABLE) {
        int given = sd_yaml_get(&p->y, mm, SD_SEC_MESH_MOTION, "axis", path, &v);
        double len = sqrt(v.v[0] * v.v[0] + v.v[1] * v.v[1] + v.v[2] * v.v[2]);
        if (!(len > 0.0) || !isfinite(len))
            return sd_fail(p, given ? v.line : line, sd_yaml_kp(key, sizeof key, path, "axis"),
                           "expected a non-zero axis, got [%g, %g, %g]", v.v[0], v.v[1], v.v[2]);
        d->axis = (sd_v3d){v.v[0] / len, v.v[1] / len, v.v[2] / len};
        if (p->s->world.dimension == 2 && (d->axis.x != 0.0 || d->axis.y != 0.0))
            return sd_fail(p, given ? v.line : line, sd_yaml_kp(key, sizeof key, path, "axis"),
                           "dimension 2: a mesh turns about z only, got axis [%g, %g, %g]", v.v[0], v.v[1], v.v[2]);
    }
    if (sd_yaml_get(&p->y, mm, SD_SEC_MESH_MOTION, "rpm", path, &v))
        d->rpm = v.num;
    sd_yaml_get(&p->y, mm, SD_SEC_MESH_MOTION, "start", path, &v);
    d->start = d->kind == SD_MESH_TRANSLATE || d->kind == SD_MESH_ROTATE ? v.num : 0.0;
    sd_yaml_get(&p->y, mm, SD_SEC_MESH_MOTION, "ramp", path, &v);
    d->ramp = d->kind == SD_MESH_TRANSLATE || d->kind == SD_MESH_ROTATE ? v.num : 0.0;
    if (d->kind == SD_MESH_TRANSLATE && p->s->world.dimension == 2 && d->velocity.z != 0.0) {
        sd_yaml_get(&p->y, mm, SD_SEC_MESH_MOTION, "velocity", path, &v);
        return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "velocity"),
                       "dimension 2 needs a velocity with z = 0, got %g", d->velocity.z);
    }
    if (d->kind == SD_MESH_TABLE) {
        sd_yaml_get(&p->y, mm, SD_SEC_MESH_MOTION, "table", path, &v);
        char file[SD_SCENE_PATH_MAX];
        sd_yaml_kp(key, sizeof key, path, "table");
        if (!sd_resolve(p->path, v.str, file, sizeof file))
            return sd_fail(p, v.line, key, "path too long (at most %d characters)", SD_SCENE_PATH_MAX - 1);
        if ((st = sd_mesh_table_read(p, w, file, v.line, key)))
            return st;
    }
    return SD_OK;
}

sd_status sd_parse_mesh_wall(sd_parse *p, yaml_node_t *m, sd_scene_wall *w, const char *path)
{
    sd_scene *s = p->s;
    char key[128];
    sd_yaml_value v;
    sd_status st;
    w->kind = 2;
    if (s->world.solver == SD_SOLVER_GRID)
        return sd_fail(p, w->line, sd_yaml_kp(key, sizeof key, path, "type"),
                       "mesh walls run on the cells solver only; use solver: cells");
    sd_yaml_get(&p->y, m, SD_SEC_WALL, "file", path, &v);
    int file_line = v.line;
    sd_yaml_kp(key, sizeof key, path, "file");
    if (!sd_resolve(p->path, v.str, w->file, sizeof w->file))
        return sd_fail(p, file_line, key, "path too long (at most %d characters)", SD_SCENE_PATH_MAX - 1);
    sd_yaml_get(&p->y, m, SD_SEC_WALL, "scale", path, &v);
    double scale = v.num;
    double q[4] = {1.0, 0.0, 0.0, 0.0};
    if (sd_yaml_get(&p->y, m, SD_SEC_WALL, "orientation", path, &v)) {
        if (v.choice == SD_ORIENT_RANDOM)
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "orientation"),
                           "a mesh wall needs identity or a quaternion [w, x, y, z], not random");
        if (v.choice == SD_ORIENT_FIXED)
            memcpy(q, v.q, sizeof q);
    }
    if (sd_yaml_get(&p->y, m, SD_SEC_WALL, "rotation", path, &v)) {
        sd_yaml_value ov;
        if (sd_yaml_get(&p->y, m, SD_SEC_WALL, "orientation", path, &ov))
            return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "rotation"),
                           "give either rotation (angles in degrees) or orientation (a quaternion), not both "
                           "(orientation is on line %d)",
                           ov.line);
        sd_mesh_rotation_quat(v.v, q);
    }
    sd_yaml_get(&p->y, m, SD_SEC_WALL, "position", path, &v);
    sd_v3d pos = sd_parse_v3(v.v);
    sd_yaml_get(&p->y, m, SD_SEC_WALL, "side", path, &v);
    w->outside = v.choice == 1;
    sd_yaml_get(&p->y, m, SD_SEC_WALL, "weld_tolerance", path, &v);
    w->weld_tolerance = v.num;
    sd_yaml_get(&p->y, m, SD_SEC_WALL, "coplanar_tolerance", path, &v);
    w->coplanar_tolerance = v.num;
    if (!(w->coplanar_tolerance < 1.0))
        return sd_fail(p, v.line, sd_yaml_kp(key, sizeof key, path, "coplanar_tolerance"),
                       "expected an angle below 1 rad, got %g", w->coplanar_tolerance);
    if (sd_yaml_get(&p->y, m, SD_SEC_WALL, "torque_point", path, &v)) {
        w->has_torque_point = 1;
        w->torque_point = sd_parse_v3(v.v);
    }
    yaml_node_t *mm = sd_yaml_map_get(&p->y, m, "motion");
    if (mm && (st = sd_parse_mesh_motion(p, mm, w, path)))
        return st;

    /* the file: format checks in io/mesh.c, its message names the file and line or facet */
    sd_mesh mesh;
    sd_error merr;
    memset(&merr, 0, sizeof merr);
    sd_yaml_kp(key, sizeof key, path, "file");
    if ((st = sd_mesh_read(w->file, &mesh, &merr)) != SD_OK) {
        if (st == SD_ERR_MEMORY)
            return sd_yaml_oom(&p->y);
        return sd_fail(p, file_line, key, "%s", merr.msg);
    }
    if (mesh.triangle_count == 0) {
        sd_mesh_free(&mesh);
        return sd_fail(p, file_line, key, "the mesh file '%s' has no facets", w->file);
    }
    w->mesh_vertices = sd_malloc(mesh.vertex_count * sizeof *w->mesh_vertices);
    if (!w->mesh_vertices) {
        sd_mesh_free(&mesh);
        return sd_yaml_oom(&p->y);
    }
    /* world = pos + R (scale x), R of the unit quaternion (w, x, y, z) */
    double qw = q[0], qx = q[1], qy = q[2], qz = q[3];
    double R[3][3] = {{1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qw * qz), 2 * (qx * qz + qw * qy)},
                      {2 * (qx * qy + qw * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qw * qx)},
                      {2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx * qx + qy * qy)}};
    for (size_t i = 0; i < mesh.vertex_count; ++i) {
        double x[3] = {scale * mesh.vertices[i].x, scale * mesh.vertices[i].y, scale * mesh.vertices[i].z};
        double y[3];
        for (int a = 0; a < 3; ++a)
            y[a] = R[a][0] * x[0] + R[a][1] * x[1] + R[a][2] * x[2];
        w->mesh_vertices[i] = (sd_v3d){pos.x + y[0], pos.y + y[1], pos.z + y[2]};
        if (!isfinite(w->mesh_vertices[i].x) || !isfinite(w->mesh_vertices[i].y) || !isfinite(w->mesh_vertices[i].z)) {
            sd_mesh_free(&mesh);
            return sd_fail(p, file_line, key,
                           "vertex %zu of '%s' is not finite once scaled by %g and placed; check scale:", i + 1,
                           w->file, scale);
        }
    }
    w->mesh_vertex_count = mesh.vertex_count;
    w->mesh_triangles = mesh.triangles; /* taken over: freed with the scene */
    w->mesh_triangle_count = mesh.triangle_count;
    mesh.triangles = NULL;
    sd_mesh_free(&mesh);

    /* prepare once here, so a mesh the world would refuse is refused at load */
    sd_trimesh tm;
    sd_trimesh_report rep;
    sd_error terr;
    memset(&terr, 0, sizeof terr);
    st = sd_trimesh_build_side(w->mesh_vertices, w->mesh_vertex_count, (const uint32_t(*)[3])w->mesh_triangles,
                               w->mesh_triangle_count, w->weld_tolerance, w->coplanar_tolerance,
                               w->outside ? SD_TRIMESH_OUTSIDE : SD_TRIMESH_INSIDE, &tm, &rep, &terr);
    if (st == SD_ERR_MEMORY)
        return sd_yaml_oom(&p->y);
    if (st != SD_OK)
        return sd_fail(p, file_line, key, "mesh file '%s' (facets numbered as triangles in file order): %s", w->file,
                       terr.msg);
    sd_trimesh_free(&tm);
    /* the repairs, for the warning ("wall NAME: ..."): facets are the file's triangles, 1-based */
    size_t used = 0;
    w->warning[0] = '\0';
#define SD_WARN(...)                                                                                                   \
    do {                                                                                                               \
        int n_ = snprintf(w->warning + used, sizeof w->warning - used, __VA_ARGS__);                                   \
        used += n_ > 0 && (size_t)n_ < sizeof w->warning - used ? (size_t)n_ : 0;                                      \
    } while (0)
    if (rep.degenerate)
        SD_WARN("%sdropped %zu degenerate (zero-area) facet%s, the first facet %zu", used ? "; " : "", rep.degenerate,
                rep.degenerate > 1 ? "s" : "", rep.first_degenerate);
    if (rep.duplicates)
        SD_WARN("%sdropped %zu duplicated facet%s, the first facet %zu", used ? "; " : "", rep.duplicates,
                rep.duplicates > 1 ? "s" : "", rep.first_duplicate);
    if (rep.flipped)
        SD_WARN("%sturned %zu facet%s wound against their neighbours, the first facet %zu", used ? "; " : "",
                rep.flipped, rep.flipped > 1 ? "s" : "", rep.first_flipped);
    if (rep.nonmanifold)
        SD_WARN("%s%zu edge%s shared by more than two facets", used ? "; " : "", rep.nonmanifold,
                rep.nonmanifold > 1 ? "s" : "");
#undef SD_WARN
    return SD_OK;
}
