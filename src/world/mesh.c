/* mesh.c — triangle-mesh walls in the world (seed 000 §2.4): adding a
 * mesh (prepared by geom/trimesh.c, kept in its own frame), its facet bins
 * (dynamics/meshwall.h), its rigid motion (fixed, translation, rotation
 * about an axis with a start time and a linear ramp, a prescribed table)
 * and the queries.
 *
 * Invariants: the mesh's vertices never change; its pose (q, trans in the
 * wall geometry) and its velocity field v(c) = velocity + omega x (c -
 * centre) are functions of time only, evaluated for the time the particles
 * drift to (velocity Verlet: positions and velocities at t + dt), so a run
 * cut into calls of any length gives the same bits. The facet bins are
 * rebuilt only when the particles' reach outgrows them (never for motion).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"
#include "world/mesh.h"
#include "world/view.h"
#include "world/world.h"

#define SD_COOKIE 0x5D5D
#define SD_PI_D 3.14159265358979323846

sd_mesh_def sd_mesh_def_default(void)
{
    sd_mesh_def d;
    memset(&d, 0, sizeof d);
    d.cookie = SD_COOKIE;
    return d;
}

sd_mesh_motion_def sd_mesh_motion_def_default(void)
{
    sd_mesh_motion_def d;
    memset(&d, 0, sizeof d);
    d.kind = SD_MESH_FIXED;
    d.axis = (sd_v3d){0, 0, 1};
    d.cookie = SD_COOKIE;
    return d;
}

static sd_mesh_store *sd_mesh_of(const sd_world *w, int wall)
{
    if (!w || wall < 0 || (size_t)wall >= w->wall_count || w->walls[wall].kind != SD_WALL_MESH)
        return NULL;
    return &w->meshes[w->walls[wall].mesh];
}

/* The view of mesh k (its arrays may have moved). */
static void sd_mesh_refresh_view(sd_world *w, size_t k)
{
    const sd_mesh_store *s = &w->meshes[k];
    sd_mesh_view *v = &w->mesh_views[k];
    v->tri_count = s->m.triangle_count;
    v->group_count = s->m.group_count;
    v->verts = s->m.vertices;
    v->tris = (const uint32_t(*)[3])s->m.triangles;
    v->group = s->m.group;
    v->flags = s->m.flags;
    v->nbr = (const uint32_t(*)[3])s->m.nbr;
    v->group_normal = s->m.group_normal;
    v->group_offset = s->m.group_offset;
    v->h = s->h;
    v->origin = s->origin;
    v->entry_count = s->entry_count;
    v->entry_key = s->entry_key;
    v->entry_tri = s->entry_tri;
}

int sd_world_add_mesh(sd_world *w, const char *name, const sd_mesh_def *def, sd_error *err)
{
    if (!w) {
        sd_error_null(err, "sd_world_add_mesh", "world");
        return -1;
    }
    const char *nm = name && name[0] ? name : "mesh";
    if (!def || def->cookie != SD_COOKIE) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "mesh", "mesh def not made by sd_mesh_def_default");
        return -1;
    }
    if (def->material < 0 || (size_t)def->material >= w->material_count) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "material", "mesh '%s': unknown material index %d", nm, def->material);
        return -1;
    }
    if (!def->vertices || !def->triangles || def->triangle_count == 0) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "mesh", "mesh '%s': no triangles", nm);
        return -1;
    }
    if (!(def->weld_tolerance >= 0) || !(def->coplanar_tolerance >= 0)) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "weld_tolerance", "mesh '%s': tolerances must be >= 0", nm);
        return -1;
    }
    if (w->mesh_count >= 65535) {
        sd_error_set(err, SD_ERR_INPUT, "", 0, "mesh", "too many meshes");
        return -1;
    }
    sd_trimesh tm;
    sd_trimesh_report rep;
    sd_status st = sd_trimesh_build_side(def->vertices, def->vertex_count, def->triangles, def->triangle_count,
                                         def->weld_tolerance, def->coplanar_tolerance,
                                         def->outside ? SD_TRIMESH_OUTSIDE : SD_TRIMESH_INSIDE, &tm, &rep, err);
    if (st != SD_OK)
        return -1;
    sd_mesh_store *ms = sd_realloc(w->meshes, (w->mesh_count + 1) * sizeof *ms);
    if (ms)
        w->meshes = ms;
    sd_mesh_view *mv = ms ? sd_realloc(w->mesh_views, (w->mesh_count + 1) * sizeof *mv) : NULL;
    if (mv)
        w->mesh_views = mv;
    double *vd = mv ? sd_malloc((tm.vertex_count ? tm.vertex_count : 1) * 3 * sizeof *vd) : NULL;
    if (!vd) {
        sd_trimesh_free(&tm);
        sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory for mesh '%s'", nm);
        return -1;
    }
    sd_mesh_store *s = &w->meshes[w->mesh_count];
    memset(s, 0, sizeof *s);
    s->m = tm;
    s->vertices_d = vd;
    sd_vec3 lo = tm.vertices[0], hi = tm.vertices[0];
    for (size_t k = 0; k < tm.vertex_count; ++k) {
        lo = sd_v3_min(lo, tm.vertices[k]);
        hi = sd_v3_max(hi, tm.vertices[k]);
        vd[3 * k] = (double)tm.vertices[k].x;
        vd[3 * k + 1] = (double)tm.vertices[k].y;
        vd[3 * k + 2] = (double)tm.vertices[k].z;
    }
    s->bb_lo = lo;
    s->bb_hi = hi;
    s->closed_side = rep.closed ? (def->outside ? SD_TRIMESH_OUTSIDE : SD_TRIMESH_INSIDE) : 0;
    s->motion = sd_mesh_motion_def_default();
    s->ref0 = sd_v3_scale(sd_v3_add(lo, hi), SD_R(0.5));
    s->extent = SD_R(0.5) * sd_v3_norm(sd_v3_sub(hi, lo));
    s->q_ref = sd_quat_identity();
    s->trans_ref = sd_v3_zero();
    sd_mesh_refresh_view(w, w->mesh_count);

    sd_wall wl;
    memset(&wl, 0, sizeof wl);
    wl.kind = SD_WALL_MESH;
    wl.point = s->ref0;
    wl.normal = sd_v3(SD_R(0.0), SD_R(0.0), SD_R(1.0));
    wl.lo = lo;
    wl.hi = hi;
    wl.q = sd_quat_identity();
    wl.trans = sd_v3_zero();
    wl.centre = s->ref0;
    wl.mesh = (int)w->mesh_count;
    wl.material = def->material;
    wl.torque_point = s->ref0;
    snprintf(wl.name, sizeof wl.name, "%s", nm);
    int k = sd_world_push_wall(w, &wl, err);
    if (k < 0) {
        sd_trimesh_free(&tm);
        sd_free(vd);
        return -1;
    }
    s->wall = k;
    w->mesh_count++;
    return k;
}

/* ---- motion ----------------------------------------------------------------- */

/* Displacement d, angle a (rad) and their rates of a TABLE motion at t. */
static void sd_table_at(const sd_mesh_store *s, double t, double d[3], double *a, double dd[3], double *da)
{
    const double *r = s->table;
    size_t n = s->motion.table_rows;
    for (int k = 0; k < 3; ++k)
        dd[k] = 0;
    *da = 0;
    if (t <= r[0] || n == 1) {
        const double *row = t <= r[0] ? r : r + 5 * (n - 1);
        for (int k = 0; k < 3; ++k)
            d[k] = row[1 + k];
        *a = row[4] * SD_PI_D / 180.0;
        return;
    }
    if (t >= r[5 * (n - 1)]) {
        const double *row = r + 5 * (n - 1);
        for (int k = 0; k < 3; ++k)
            d[k] = row[1 + k];
        *a = row[4] * SD_PI_D / 180.0;
        return;
    }
    size_t lo = 0, hi = n - 1; /* r[5 lo] <= t < r[5 hi] */
    while (hi - lo > 1) {
        size_t mid = (lo + hi) / 2;
        if (r[5 * mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    const double *p = r + 5 * lo, *q = r + 5 * hi;
    double span = q[0] - p[0], u = (t - p[0]) / span;
    for (int k = 0; k < 3; ++k) {
        d[k] = p[1 + k] + u * (q[1 + k] - p[1 + k]);
        dd[k] = (q[1 + k] - p[1 + k]) / span;
    }
    *a = (p[4] + u * (q[4] - p[4])) * SD_PI_D / 180.0;
    *da = (q[4] - p[4]) / span * SD_PI_D / 180.0;
}

static sd_quat sd_axis_angle(sd_vec3 axis, double angle)
{
    double h = 0.5 * angle;
    sd_real s = (sd_real)sin(h);
    return sd_quat_make((sd_real)cos(h), axis.x * s, axis.y * s, axis.z * s);
}

static sd_vec3 sd_v3_of_d(sd_v3d v) { return sd_v3((sd_real)v.x, (sd_real)v.y, (sd_real)v.z); }

/* The pose and velocity field of mesh s at time t into its wall. */
static void sd_mesh_pose_at(const sd_mesh_store *s, sd_wall *wl, double t)
{
    const sd_mesh_motion_def *m = &s->motion;
    sd_quat q = sd_quat_identity();
    sd_vec3 trans = sd_v3_zero(), vel = sd_v3_zero(), omega = sd_v3_zero(), centre = s->ref0;
    sd_vec3 axis = sd_v3_of_d(m->axis), c = sd_v3_of_d(m->axis_point);
    double speed;
    switch (m->kind) {
    case SD_MESH_TRANSLATE: {
        double path = sd_wall_ramp_path(t, m->start, m->ramp, &speed);
        sd_vec3 v = sd_v3_of_d(m->velocity);
        trans = sd_v3_scale(v, (sd_real)path);
        vel = sd_v3_scale(v, (sd_real)speed);
        centre = sd_v3_add(s->ref0, trans);
        break;
    }
    case SD_MESH_ROTATE: {
        double w0 = m->rpm * 2.0 * SD_PI_D / 60.0; /* rad/s */
        double angle = w0 * sd_wall_ramp_path(t, m->start, m->ramp, &speed);
        q = sd_axis_angle(axis, angle);
        trans = sd_v3_sub(c, sd_quat_rotate(q, c)); /* x' = R (x - c) + c */
        omega = sd_v3_scale(axis, (sd_real)(w0 * speed));
        centre = c;
        break;
    }
    case SD_MESH_TABLE: {
        double d[3], dd[3], a, da;
        sd_table_at(s, t, d, &a, dd, &da);
        q = sd_axis_angle(axis, a);
        sd_vec3 dv = sd_v3((sd_real)d[0], (sd_real)d[1], (sd_real)d[2]);
        centre = sd_v3_add(c, dv); /* x' = R (x - c) + c + d */
        trans = sd_v3_sub(centre, sd_quat_rotate(q, c));
        vel = sd_v3((sd_real)dd[0], (sd_real)dd[1], (sd_real)dd[2]);
        omega = sd_v3_scale(axis, (sd_real)da);
        break;
    }
    default:
        break;
    }
    wl->q = q;
    wl->trans = trans;
    wl->centre = centre;
    wl->velocity = vel;
    wl->omega = omega;
    wl->point = sd_v3_add(sd_quat_rotate(q, s->ref0), trans);
}

sd_status sd_world_set_mesh_motion(sd_world *w, int wall, const sd_mesh_motion_def *d, sd_error *err)
{
    sd_mesh_store *s = sd_mesh_of(w, wall);
    if (!s)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "motion", "wall %d is not a mesh wall", wall);
    const char *nm = w->walls[wall].name;
    if (!d || d->cookie != SD_COOKIE)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "motion", "mesh motion def not made by sd_mesh_motion_def_default");
    if (d->kind < SD_MESH_FIXED || d->kind > SD_MESH_TABLE)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "motion", "mesh '%s': unknown motion kind %d", nm, d->kind);
    double vals[] = {d->velocity.x, d->velocity.y, d->velocity.z, d->axis_point.x, d->axis_point.y,
                     d->axis_point.z, d->axis.x,     d->axis.y,     d->axis.z,     d->rpm,
                     d->start,        d->ramp};
    for (size_t k = 0; k < sizeof vals / sizeof vals[0]; ++k)
        if (!isfinite(vals[k]))
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "motion", "mesh '%s': motion values must be finite", nm);
    if (d->ramp < 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "ramp", "mesh '%s': expected a ramp >= 0 s, got %g", nm, d->ramp);
    double an = sqrt(d->axis.x * d->axis.x + d->axis.y * d->axis.y + d->axis.z * d->axis.z);
    if ((d->kind == SD_MESH_ROTATE || d->kind == SD_MESH_TABLE) && !(an > 0))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "axis", "mesh '%s': the rotation axis must be non-zero", nm);
    if (w->dim2 && (d->kind == SD_MESH_ROTATE || d->kind == SD_MESH_TABLE) && (d->axis.x != 0 || d->axis.y != 0))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "axis", "mesh '%s': dimension 2 rotates about z only", nm);
    if (w->dim2 && d->kind == SD_MESH_TRANSLATE && d->velocity.z != 0)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "velocity", "mesh '%s': dimension 2 needs a velocity with z = 0",
                            nm);
    double *table = NULL;
    if (d->kind == SD_MESH_TABLE) {
        if (!d->table || d->table_rows == 0)
            return sd_error_set(err, SD_ERR_INPUT, "", 0, "table", "mesh '%s': a table motion needs rows", nm);
        for (size_t r = 0; r < d->table_rows; ++r) {
            for (int c = 0; c < 5; ++c)
                if (!isfinite(d->table[5 * r + c]))
                    return sd_error_set(err, SD_ERR_INPUT, "", 0, "table", "mesh '%s': table row %zu is not finite",
                                        nm, r + 1);
            if (r > 0 && !(d->table[5 * r] > d->table[5 * (r - 1)]))
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "table",
                                    "mesh '%s': table row %zu: times must increase (%g after %g)", nm, r + 1,
                                    d->table[5 * r], d->table[5 * (r - 1)]);
            if (w->dim2 && d->table[5 * r + 3] != 0)
                return sd_error_set(err, SD_ERR_INPUT, "", 0, "table", "mesh '%s': table row %zu: dimension 2 needs dz = 0",
                                    nm, r + 1);
        }
        table = sd_malloc(d->table_rows * 5 * sizeof *table);
        if (!table)
            return sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory");
        memcpy(table, d->table, d->table_rows * 5 * sizeof *table);
    }
    sd_free(s->table);
    s->table = table;
    s->motion = *d;
    s->motion.table = table;
    if (an > 0)
        s->motion.axis = (sd_v3d){d->axis.x / an, d->axis.y / an, d->axis.z / an};
    /* the farthest any vertex is from the centre of rotation (the skin test) */
    sd_vec3 c = (d->kind == SD_MESH_ROTATE || d->kind == SD_MESH_TABLE) ? sd_v3_of_d(d->axis_point) : s->ref0;
    sd_real ext = SD_R(0.0);
    for (size_t k = 0; k < s->m.vertex_count; ++k) {
        sd_real r = sd_v3_norm(sd_v3_sub(s->m.vertices[k], c));
        ext = r > ext ? r : ext;
    }
    s->extent = ext;
    sd_wall *wl = &w->walls[wall];
    if (d->kind == SD_MESH_ROTATE || d->kind == SD_MESH_TABLE)
        wl->torque_point = sd_v3_of_d(d->axis_point);
    if (d->kind != SD_MESH_FIXED)
        w->walls_moving = 1;
    sd_mesh_pose_at(s, wl, w->time);
    s->q_ref = wl->q;
    s->trans_ref = wl->trans;
    w->prepared = 0;
    return SD_OK;
}

void sd_world_meshes_pose(sd_world *w, double t)
{
    for (size_t k = 0; k < w->mesh_count; ++k) {
        const sd_mesh_store *s = &w->meshes[k];
        if (s->motion.kind != SD_MESH_FIXED)
            sd_mesh_pose_at(s, &w->walls[s->wall], t);
    }
}

int sd_world_meshes_moved(const sd_world *w, sd_real lim)
{
    for (size_t k = 0; k < w->mesh_count; ++k) {
        const sd_mesh_store *s = &w->meshes[k];
        if (s->motion.kind == SD_MESH_FIXED)
            continue;
        const sd_wall *wl = &w->walls[s->wall];
        /* a point x of the mesh moved by at most |R - R_ref| |x - c| plus the
         * displacement of the pose at c: an angle times the extent */
        sd_vec3 c = (s->motion.kind == SD_MESH_TRANSLATE) ? s->ref0 : sd_v3_of_d(s->motion.axis_point);
        sd_vec3 now = sd_v3_add(sd_quat_rotate(wl->q, c), wl->trans);
        sd_vec3 then = sd_v3_add(sd_quat_rotate(s->q_ref, c), s->trans_ref);
        sd_real moved = sd_v3_norm(sd_v3_sub(now, then)) + sd_quat_angle_between(wl->q, s->q_ref) * s->extent;
        if (moved > lim)
            return 1;
    }
    return 0;
}

void sd_world_meshes_mark(sd_world *w)
{
    for (size_t k = 0; k < w->mesh_count; ++k) {
        sd_mesh_store *s = &w->meshes[k];
        s->q_ref = w->walls[s->wall].q;
        s->trans_ref = w->walls[s->wall].trans;
    }
}

/* ---- facet bins ---------------------------------------------------------------- */

typedef struct sd_bin_entry {
    uint64_t key;
    uint32_t tri;
} sd_bin_entry;

static int sd_bin_entry_cmp(const void *a, const void *b)
{
    const sd_bin_entry *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return x->tri < y->tri ? -1 : (x->tri > y->tri);
}

static sd_real sd_comp(sd_vec3 v, int a) { return a == 0 ? v.x : (a == 1 ? v.y : v.z); }

/* Visits the cells triangle t may cross: the cell columns of its bounding
 * box along its dominant normal axis, and in each column the cells the
 * triangle's plane crosses over the column's footprint (clamped to the
 * box). Writes (key, t) into out when set; returns the count. */
static size_t sd_bin_triangle(const sd_mesh_store *s, sd_real h, sd_vec3 o, uint32_t t, sd_bin_entry *out)
{
    const uint32_t *tr = s->m.triangles[t];
    sd_vec3 a = s->m.vertices[tr[0]], b = s->m.vertices[tr[1]], c = s->m.vertices[tr[2]];
    sd_vec3 lo = sd_v3_min(a, sd_v3_min(b, c)), hi = sd_v3_max(a, sd_v3_max(b, c));
    sd_vec3 n = sd_v3_cross(sd_v3_sub(b, a), sd_v3_sub(c, a));
    sd_real an[3] = {sd_fabs(n.x), sd_fabs(n.y), sd_fabs(n.z)};
    int ax = an[0] >= an[1] && an[0] >= an[2] ? 0 : (an[1] >= an[2] ? 1 : 2);
    int au = (ax + 1) % 3, av = (ax + 2) % 3;
    sd_real nx = sd_comp(n, ax), nu = sd_comp(n, au), nv = sd_comp(n, av), off = sd_v3_dot(n, a);
    long u0 = sd_mesh_cell_of(sd_comp(lo, au), sd_comp(o, au), h), u1 = sd_mesh_cell_of(sd_comp(hi, au), sd_comp(o, au), h);
    long v0 = sd_mesh_cell_of(sd_comp(lo, av), sd_comp(o, av), h), v1 = sd_mesh_cell_of(sd_comp(hi, av), sd_comp(o, av), h);
    size_t m = 0;
    for (long iu = u0; iu <= u1; ++iu)
        for (long iv = v0; iv <= v1; ++iv) {
            sd_real cu[2] = {sd_comp(o, au) + (sd_real)iu * h, sd_comp(o, au) + (sd_real)(iu + 1) * h};
            sd_real cv[2] = {sd_comp(o, av) + (sd_real)iv * h, sd_comp(o, av) + (sd_real)(iv + 1) * h};
            for (int k = 0; k < 2; ++k) {
                cu[k] = cu[k] < sd_comp(lo, au) ? sd_comp(lo, au) : (cu[k] > sd_comp(hi, au) ? sd_comp(hi, au) : cu[k]);
                cv[k] = cv[k] < sd_comp(lo, av) ? sd_comp(lo, av) : (cv[k] > sd_comp(hi, av) ? sd_comp(hi, av) : cv[k]);
            }
            sd_real xmin = sd_comp(hi, ax), xmax = sd_comp(lo, ax);
            for (int i = 0; i < 2; ++i)
                for (int j = 0; j < 2; ++j) {
                    sd_real x = (off - nu * cu[i] - nv * cv[j]) / nx; /* on the plane */
                    xmin = x < xmin ? x : xmin;
                    xmax = x > xmax ? x : xmax;
                }
            xmin = xmin < sd_comp(lo, ax) ? sd_comp(lo, ax) : xmin;
            xmax = xmax > sd_comp(hi, ax) ? sd_comp(hi, ax) : xmax;
            long x0 = sd_mesh_cell_of(xmin, sd_comp(o, ax), h), x1 = sd_mesh_cell_of(xmax, sd_comp(o, ax), h);
            for (long ix = x0; ix <= x1; ++ix) {
                if (out) {
                    long idx[3];
                    idx[ax] = ix;
                    idx[au] = iu;
                    idx[av] = iv;
                    out[m].key = sd_mesh_key(idx[0], idx[1], idx[2]);
                    out[m].tri = t;
                }
                ++m;
            }
        }
    return m;
}

/* An upper bound on the (cell, triangle) entries sd_bin_triangle makes at
 * cell edge h, without visiting the cells: the cell columns of the
 * triangle's box across its dominant normal axis, times the cells one
 * column can hold (the plane rises by at most (|n_u| + |n_v|) / |n_x| <= 2
 * cell edges across a column, so at most 4 cells), counted in double so a
 * huge footprint cannot overflow. */
static double sd_bin_estimate(const sd_mesh_store *s, sd_real h, sd_vec3 o)
{
    double total = 0;
    for (size_t t = 0; t < s->m.triangle_count; ++t) {
        const uint32_t *tr = s->m.triangles[t];
        sd_vec3 a = s->m.vertices[tr[0]], b = s->m.vertices[tr[1]], c = s->m.vertices[tr[2]];
        sd_vec3 lo = sd_v3_min(a, sd_v3_min(b, c)), hi = sd_v3_max(a, sd_v3_max(b, c));
        sd_vec3 n = sd_v3_cross(sd_v3_sub(b, a), sd_v3_sub(c, a));
        sd_real an[3] = {sd_fabs(n.x), sd_fabs(n.y), sd_fabs(n.z)};
        int ax = an[0] >= an[1] && an[0] >= an[2] ? 0 : (an[1] >= an[2] ? 1 : 2); /* as sd_bin_triangle */
        double cells[3];
        for (int k = 0; k < 3; ++k)
            cells[k] = (double)(sd_mesh_cell_of(sd_comp(hi, k), sd_comp(o, k), h) -
                                sd_mesh_cell_of(sd_comp(lo, k), sd_comp(o, k), h) + 1);
        total += cells[(ax + 1) % 3] * cells[(ax + 2) % 3] * fmin(cells[ax], 4.0);
    }
    return total;
}

/* The most entries the bins of a mesh of n triangles may hold: 2^20, or 8
 * per triangle for large meshes (12 bytes each kept, 28 while sorting). A
 * mesh whose triangles are large against the particles (a CAD floor of two
 * triangles under millimetre grains, a mesh left in millimetres) would
 * otherwise need one entry per cell of its area: its cells are made
 * coarser instead. A query stays right at any cell edge (it visits every
 * cell its box touches and keeps the triangles within reach, in triangle
 * order), only slower where a cell holds many triangles. */
static double sd_bin_cap(size_t n) { return fmax(1048576.0, 8.0 * (double)n); }

static sd_status sd_mesh_bin(sd_mesh_store *s, sd_real h)
{
    /* the key range is 2^21 cells per axis: coarsen for huge meshes (and
     * for a cell edge that is not a positive finite number, as a forged
     * checkpoint may hold) */
    sd_real span = sd_v3_norm(sd_v3_sub(s->bb_hi, s->bb_lo));
    int coarse = 0;
    if (!(h > 0) || !(span / h <= (sd_real)(SD_MESH_KEY_BIAS - 2))) {
        h = span / (sd_real)(SD_MESH_KEY_BIAS - 2);
        coarse = 1;
    }
    if (!(h > 0) || !isfinite((double)h))
        return SD_ERR_INPUT;
    /* bound the entries: the count falls as 1/h^2 for large triangles, so
     * a step of sqrt(estimate / cap) lands near the cap; doubling after a
     * few steps ends the loop whatever the mesh */
    double cap = sd_bin_cap(s->m.triangle_count);
    for (int it = 0; it < 200; ++it) {
        double est = sd_bin_estimate(s, h, s->bb_lo);
        if (est <= cap)
            break;
        double f = it < 8 ? 1.05 * sqrt(est / cap) : 2.0;
        h = (sd_real)((double)h * fmax(f, 1.05));
        coarse = 1;
    }
    sd_vec3 o = s->bb_lo;
    size_t total = 0;
    for (size_t t = 0; t < s->m.triangle_count; ++t)
        total += sd_bin_triangle(s, h, o, (uint32_t)t, NULL);
    sd_bin_entry *e = sd_malloc((total ? total : 1) * sizeof *e);
    uint64_t *keys = e ? sd_malloc((total ? total : 1) * sizeof *keys) : NULL;
    uint32_t *tris = keys ? sd_malloc((total ? total : 1) * sizeof *tris) : NULL;
    if (!tris) {
        sd_free(e);
        sd_free(keys);
        return SD_ERR_MEMORY;
    }
    size_t m = 0;
    for (size_t t = 0; t < s->m.triangle_count; ++t)
        m += sd_bin_triangle(s, h, o, (uint32_t)t, e + m);
    qsort(e, m, sizeof *e, sd_bin_entry_cmp);
    for (size_t k = 0; k < m; ++k) {
        keys[k] = e[k].key;
        tris[k] = e[k].tri;
    }
    sd_free(e);
    sd_free(s->entry_key);
    sd_free(s->entry_tri);
    s->entry_key = keys;
    s->entry_tri = tris;
    s->entry_count = m;
    s->h = h;
    s->coarse = coarse;
    s->origin = o;
    return SD_OK;
}

sd_status sd_world_meshes_bins(sd_world *w, sd_real h_min)
{
    if (!(h_min > 0))
        h_min = SD_R(1e-3);
    for (size_t k = 0; k < w->mesh_count; ++k) {
        sd_mesh_store *s = &w->meshes[k];
        /* cells of 2 reach when built (a query box, 2 reach wide, spans at
         * most 2 x 2 x 2 of them), kept while within [reach, 4 reach]: few
         * facets per query beyond the particle's neighbourhood */
        if (s->h >= h_min && s->h <= SD_R(4.0) * h_min)
            continue;
        /* keep a grid made coarser than asked (key range, entry cap):
         * binning again at a finer edge would be made as coarse again */
        if (s->coarse && s->h >= h_min && s->entry_count > 0)
            continue;
        sd_status st = sd_mesh_bin(s, SD_R(2.0) * h_min);
        if (st != SD_OK)
            return st;
        sd_mesh_refresh_view(w, k);
    }
    return SD_OK;
}

sd_status sd_world_meshes_resumed(sd_world *w)
{
    for (size_t k = 0; k < w->mesh_count; ++k) {
        sd_mesh_store *s = &w->meshes[k];
        if (s->h == 0)
            continue; /* never binned: the next rebuild bins it */
        /* any other edge is binned now (sd_mesh_bin bounds a forged one):
         * a mesh left unbinned would be invisible until the next rebuild */
        sd_status st = sd_mesh_bin(s, s->h);
        if (st != SD_OK)
            return st;
        sd_mesh_refresh_view(w, k);
    }
    return SD_OK;
}

void sd_world_meshes_free(sd_world *w)
{
    for (size_t k = 0; k < w->mesh_count; ++k) {
        sd_mesh_store *s = &w->meshes[k];
        sd_trimesh_free(&s->m);
        sd_free(s->vertices_d);
        sd_free(s->entry_key);
        sd_free(s->entry_tri);
        sd_free(s->table);
    }
    sd_free(w->meshes);
    sd_free(w->mesh_views);
    w->meshes = NULL;
    w->mesh_views = NULL;
    w->mesh_count = 0;
}

/* ---- queries ------------------------------------------------------------------- */

sd_status sd_world_set_wall_torque_point(sd_world *w, int wall, sd_v3d point, sd_error *err)
{
    if (!w)
        return sd_error_null(err, "sd_world_set_wall_torque_point", "world");
    if (wall < 0 || (size_t)wall >= w->wall_count)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "torque_point", "unknown wall index %d", wall);
    if (!isfinite(point.x) || !isfinite(point.y) || !isfinite(point.z))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "torque_point", "wall '%s': the torque point must be finite",
                            w->walls[wall].name);
    w->walls[wall].torque_point = sd_v3_of_d(point);
    w->walls[wall].has_torque_point = 1;
    return SD_OK;
}

sd_vec3 sd_world_wall_torque_about(const sd_world *w, size_t k)
{
    const sd_wall *wl = &w->walls[k];
    /* the stage sums the torque about wl->point; about p it is that plus
     * (point - p) x F. A mesh's torque point moves with the mesh. */
    sd_vec3 p;
    if (wl->kind == SD_WALL_MESH)
        p = sd_mesh_to_world(wl->q, wl->trans, wl->torque_point);
    else if (wl->has_torque_point)
        p = wl->torque_point;
    else
        return wl->torque;
    return sd_v3_add(wl->torque, sd_v3_cross(sd_v3_sub(wl->point, p), wl->force));
}

sd_status sd_world_get_mesh(const sd_world *w, int wall, sd_mesh_info *out)
{
    const sd_mesh_store *s = sd_mesh_of(w, wall);
    if (!s || !out)
        return SD_ERR_INPUT;
    const sd_wall *wl = &w->walls[wall];
    out->vertex_count = s->m.vertex_count;
    out->triangle_count = s->m.triangle_count;
    out->group_count = s->m.group_count;
    out->vertices = s->vertices_d;
    out->triangles = (const uint32_t(*)[3])s->m.triangles;
    out->group = s->m.group;
    out->translation[0] = (double)wl->trans.x;
    out->translation[1] = (double)wl->trans.y;
    out->translation[2] = (double)wl->trans.z;
    out->rotation[0] = (double)wl->q.w;
    out->rotation[1] = (double)wl->q.x;
    out->rotation[2] = (double)wl->q.y;
    out->rotation[3] = (double)wl->q.z;
    /* velocity of the reference point */
    sd_vec3 vref = sd_v3_add(wl->velocity, sd_v3_cross(wl->omega, sd_v3_sub(wl->point, wl->centre)));
    out->velocity = (sd_v3d){(double)vref.x, (double)vref.y, (double)vref.z};
    out->angular_velocity = (sd_v3d){(double)wl->omega.x, (double)wl->omega.y, (double)wl->omega.z};
    return SD_OK;
}
