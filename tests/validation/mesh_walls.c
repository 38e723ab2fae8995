/* mesh_walls.c — triangle-mesh walls against their analytic counterparts
 * (seed 000 §2.4; issue 14's tests):
 *
 *  1. a sphere launched across a flat plane split into many triangles
 *     (a regular grid and a jittered one) behaves as on the analytic plane:
 *     normal force within 0.5 % of the plane run's at every step, the
 *     tangential force (the spring carried across the facets: one contact
 *     per plane group) within 0.5 % of mu m g, and the same rolling speed;
 *  2. a sphere resting in a concave edge of two facets, and in a corner of
 *     three: total wall force = weight within 0.5 %, no spin;
 *  3. spheres settled in a closed mesh box (12 triangles) against the
 *     analytic box wall: mean height and total wall force within 1 %;
 *  4. a box resting on a mesh turntable at rpm: it reaches omega r within
 *     1 %, and the torque the query reports on the mesh equals minus the
 *     moment of the particle's contact force and torque about the axis;
 *  5. the planar mode: a 2D ellipse dropped on a mesh floor cut by z = 0
 *     moves as on the plane wall: wall force within 0.5 %, height 0.1 %.
 *
 * Each check prints computed, expected, error and tolerance.
 */
#include "test.h"

#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

typedef struct mesh_buf {
    sd_v3d *v;
    uint32_t (*t)[3];
    size_t nv, nt, cv, ct;
} mesh_buf;

static size_t mb_vertex(mesh_buf *m, double x, double y, double z)
{
    if (m->nv == m->cv) {
        m->cv = m->cv ? 2 * m->cv : 64;
        m->v = realloc(m->v, m->cv * sizeof *m->v);
    }
    m->v[m->nv] = sd_test_v(x, y, z);
    return m->nv++;
}

static void mb_tri(mesh_buf *m, size_t a, size_t b, size_t c)
{
    if (m->nt == m->ct) {
        m->ct = m->ct ? 2 * m->ct : 64;
        m->t = realloc(m->t, m->ct * sizeof *m->t);
    }
    m->t[m->nt][0] = (uint32_t)a;
    m->t[m->nt][1] = (uint32_t)b;
    m->t[m->nt][2] = (uint32_t)c;
    m->nt++;
}

static void mb_free(mesh_buf *m)
{
    free(m->v);
    free(m->t);
    memset(m, 0, sizeof *m);
}

/* The square [-L, L]^2 at z = 0 as n x n cells of two triangles (normal +z);
 * jitter moves interior vertices by up to that fraction of a cell. */
static void mb_grid(mesh_buf *m, double L, int n, double jitter, unsigned seed)
{
    size_t base = m->nv;
    double h = 2 * L / n;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            double x = -L + i * h, y = -L + j * h;
            if (jitter > 0 && i > 0 && j > 0 && i < n && j < n) {
                seed = seed * 1103515245u + 12345u;
                x += jitter * h * ((double)(seed >> 8 & 0xffff) / 65535.0 - 0.5);
                seed = seed * 1103515245u + 12345u;
                y += jitter * h * ((double)(seed >> 8 & 0xffff) / 65535.0 - 0.5);
            }
            mb_vertex(m, x, y, 0);
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            size_t a = base + (size_t)(j * (n + 1) + i), b = a + 1, c = a + (size_t)(n + 1), d = c + 1;
            if ((i + j) & 1) {
                mb_tri(m, a, b, d);
                mb_tri(m, a, d, c);
            } else {
                mb_tri(m, a, b, c);
                mb_tri(m, b, d, c);
            }
        }
}

static sd_world *make_world(double g[3], double dt, int threads)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = SD_LAW_LINEAR;
    wd.dt = dt;
    wd.gravity = sd_test_v(g[0], g[1], g[2]);
    wd.threads = threads;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    return w;
}

static int add_material(sd_world *w, double e, double mu)
{
    sd_error err;
    sd_material_def m = sd_material_def_default();
    m.name = "steel";
    m.density = 2700;
    m.stiffness = 1e6;
    m.restitution = e;
    m.friction = mu;
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    return mat;
}

static int add_mesh(sd_world *w, const char *name, const mesh_buf *mb, int mat)
{
    sd_error err;
    sd_mesh_def md = sd_mesh_def_default();
    md.vertices = mb->v;
    md.vertex_count = mb->nv;
    md.triangles = (const uint32_t(*)[3])mb->t;
    md.triangle_count = mb->nt;
    md.material = mat;
    int k = sd_world_add_mesh(w, name, &md, &err);
    sd_test_require(k >= 0, "mesh", &err);
    return k;
}

/* ---- 1. sliding and rolling across many facets ------------------------------------ */

typedef struct slide_run {
    double fz_max_dev, fx_end, vx_end, wy_end;
    double fz[4000], fx[4000];
} slide_run;

static void slide(int mesh_kind, double jitter, slide_run *out)
{
    const double r = 0.05, g = 9.81, mu = 0.5, v0 = 0.5;
    double gv[3] = {0, 0, -g};
    sd_world *w = make_world(gv, 1e-5, 1);
    sd_error err;
    int mat = add_material(w, 0.5, mu);
    mesh_buf mb = {0};
    if (mesh_kind == 0)
        sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err);
    else {
        mb_grid(&mb, 0.5, 40, jitter, 7u); /* cells of 25 mm: the sphere crosses dozens of facet edges */
        add_mesh(w, "floor", &mb, mat);
    }
    double mass = 2700 * 4.0 / 3.0 * PI * r * r * r, delta = mass * g / 1e6;
    sd_sphere_def s = {0};
    s.position = sd_test_v(-0.2, 0.013, r - delta);
    s.velocity = sd_test_v(v0, 0, 0);
    s.radius = r;
    s.material = mat;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    sd_particle_state p = {0};
    out->fz_max_dev = 0;
    for (int k = 0; k < 4000; ++k) {
        sd_test_require(sd_world_step(w, 10, &err) == SD_OK, "step", &err);
        sd_world_get_particle(w, 0, &p);
        out->fz[k] = p.force.z;
        out->fx[k] = p.force.x;
    }
    out->fx_end = p.force.x;
    out->vx_end = p.velocity.x;
    out->wy_end = p.angular_velocity.y;
    sd_world_destroy(w);
    mb_free(&mb);
}

static void test_sliding(void)
{
    static slide_run plane, grid, jit;
    slide(0, 0, &plane);
    slide(1, 0, &grid);
    slide(1, 0.5, &jit);
    const double mg = 2700 * 4.0 / 3.0 * PI * 0.05 * 0.05 * 0.05 * 9.81;
    double dz_g = 0, dz_j = 0, dx_g = 0, dx_j = 0;
    for (int k = 0; k < 4000; ++k) {
        dz_g = fmax(dz_g, fabs(grid.fz[k] - plane.fz[k]));
        dz_j = fmax(dz_j, fabs(jit.fz[k] - plane.fz[k]));
        dx_g = fmax(dx_g, fabs(grid.fx[k] - plane.fx[k]));
        dx_j = fmax(dx_j, fabs(jit.fx[k] - plane.fx[k]));
    }
    CHECK_NEAR("regular facets: max |Fz - Fz(plane)| / m g", dz_g / mg, 0.0, 0.005);
    CHECK_NEAR("jittered facets: max |Fz - Fz(plane)| / m g", dz_j / mg, 0.0, 0.005);
    CHECK_NEAR("regular facets: max |Fx - Fx(plane)| / (mu m g)", dx_g / (0.5 * mg), 0.0, 0.005);
    CHECK_NEAR("jittered facets: max |Fx - Fx(plane)| / (mu m g)", dx_j / (0.5 * mg), 0.0, 0.005);
    CHECK_REL("regular facets: rolling speed vs plane (m/s)", grid.vx_end, plane.vx_end, 0.001);
    CHECK_REL("jittered facets: rolling speed vs plane (m/s)", jit.vx_end, plane.vx_end, 0.001);
    CHECK_REL("plane: rolling speed vs 5/7 v0 (m/s)", plane.vx_end, 5.0 / 7.0 * 0.5, 0.01);
}

/* ---- 2. concave edge and corner ------------------------------------------------------ */

static void rest_in(int corner)
{
    const double r = 0.02, g = 9.81;
    double gv[3] = {0, 0, -g};
    sd_error err;
    mesh_buf mb = {0};
    if (!corner) {
        /* a V of two facets strips at +-30 degrees about the x axis, meeting at y = 0, z = 0 */
        double L = 0.2, c = cos(PI / 6), s = sin(PI / 6);
        size_t a0 = mb_vertex(&mb, -L, 0, 0), a1 = mb_vertex(&mb, L, 0, 0);
        size_t l0 = mb_vertex(&mb, -L, -L * c, L * s), l1 = mb_vertex(&mb, L, -L * c, L * s);
        size_t r0 = mb_vertex(&mb, -L, L * c, L * s), r1 = mb_vertex(&mb, L, L * c, L * s);
        mb_tri(&mb, a0, l1, a1); /* right-hand normals up-and-inward: the particle side */
        mb_tri(&mb, a0, l0, l1);
        mb_tri(&mb, a0, r1, r0);
        mb_tri(&mb, a0, a1, r1);
    } else {
        /* the corner of three quarter planes x = 0, y = 0, z = 0, gravity along -(1, 1, 1) */
        double L = 0.2;
        size_t o = mb_vertex(&mb, 0, 0, 0), x = mb_vertex(&mb, L, 0, 0), y = mb_vertex(&mb, 0, L, 0),
               z = mb_vertex(&mb, 0, 0, L), xy = mb_vertex(&mb, L, L, 0), yz = mb_vertex(&mb, 0, L, L),
               zx = mb_vertex(&mb, L, 0, L);
        mb_tri(&mb, o, x, xy); /* z = 0, normal +z */
        mb_tri(&mb, o, xy, y);
        mb_tri(&mb, o, y, yz); /* x = 0, normal +x */
        mb_tri(&mb, o, yz, z);
        mb_tri(&mb, o, z, zx); /* y = 0, normal +y */
        mb_tri(&mb, o, zx, x);
        double k = g / sqrt(3.0);
        gv[0] = gv[1] = gv[2] = -k;
    }
    sd_world *w = make_world(gv, 1e-5, 1);
    int mat = add_material(w, 0.3, 0.5);
    int wall = add_mesh(w, corner ? "corner" : "vee", &mb, mat);
    sd_sphere_def s = {0};
    s.position = corner ? sd_test_v(0.03, 0.035, 0.04) : sd_test_v(0.01, 0.005, 0.06);
    s.radius = r;
    s.material = mat;
    sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    sd_test_require(sd_world_step(w, 60000, &err) == SD_OK, "step", &err);
    sd_wall_info wi;
    sd_world_get_wall(w, (size_t)wall, &wi);
    sd_particle_state p = {0};
    sd_world_get_particle(w, 0, &p);
    double mg = 2700 * 4.0 / 3.0 * PI * r * r * r * g;
    double fw = sqrt(wi.force.x * wi.force.x + wi.force.y * wi.force.y + wi.force.z * wi.force.z);
    double spin = sqrt(p.angular_velocity.x * p.angular_velocity.x + p.angular_velocity.y * p.angular_velocity.y +
                       p.angular_velocity.z * p.angular_velocity.z);
    CHECK_REL(corner ? "corner of 3 facets: |wall force| vs m g (N)" : "concave edge: |wall force| vs m g (N)", fw, mg,
              0.005);
    CHECK_NEAR(corner ? "corner of 3 facets: spin |w| r (m/s)" : "concave edge: spin |w| r (m/s)", spin * r, 0.0, 1e-6);
    sd_world_destroy(w);
    mb_free(&mb);
}

/* ---- 3. closed mesh box vs analytic box ----------------------------------------------- */

static void box_run(int mesh, double *mean_z, double *force_z)
{
    double gv[3] = {0, 0, -9.81};
    sd_world *w = make_world(gv, 2e-5, 2);
    sd_error err;
    int mat = add_material(w, 0.3, 0.4);
    const double L = 0.1;
    int wall;
    mesh_buf mb = {0};
    if (!mesh) {
        wall = sd_world_add_box(w, "box", sd_test_v(0, 0, 0), sd_test_v(L, L, L), 0, mat, &err);
    } else {
        size_t v[8];
        for (int k = 0; k < 8; ++k)
            v[k] = mb_vertex(&mb, (k & 1) ? L : 0, (k & 2) ? L : 0, (k & 4) ? L : 0);
        /* six faces, two triangles each; trimesh winds the closed box inward */
        int f[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
        for (int k = 0; k < 6; ++k) {
            mb_tri(&mb, v[f[k][0]], v[f[k][1]], v[f[k][2]]);
            mb_tri(&mb, v[f[k][0]], v[f[k][2]], v[f[k][3]]);
        }
        wall = add_mesh(w, "box", &mb, mat);
    }
    enum { N = 27 };
    sd_sphere_def s[N];
    memset(s, 0, sizeof s);
    for (int k = 0; k < N; ++k) {
        s[k].position = sd_test_v(0.02 + 0.03 * (k % 3) + 0.002 * (k % 2), 0.02 + 0.03 * (k / 3 % 3),
                                  0.015 + 0.03 * (k / 9));
        s[k].radius = 0.01;
        s[k].material = mat;
    }
    sd_test_require(sd_world_add_spheres(w, N, s, &err) == SD_OK, "spheres", &err);
    sd_test_require(sd_world_step(w, 40000, &err) == SD_OK, "step", &err);
    double z = 0;
    sd_particle_state p = {0};
    for (size_t k = 0; k < N; ++k) {
        sd_world_get_particle(w, k, &p);
        z += p.position.z / N;
    }
    sd_wall_info wi;
    sd_world_get_wall(w, (size_t)wall, &wi);
    *mean_z = z;
    *force_z = wi.force.z;
    sd_world_destroy(w);
    mb_free(&mb);
}

static void test_box(void)
{
    double zb, fb, zm, fm;
    box_run(0, &zb, &fb);
    box_run(1, &zm, &fm);
    CHECK_REL("closed mesh box: mean height vs analytic box (m)", zm, zb, 0.01);
    CHECK_REL("closed mesh box: wall force z vs analytic box (N)", fm, fb, 0.01);
    double weight = 27 * 2700 * 4.0 / 3.0 * PI * 1e-6 * 9.81;
    CHECK_REL("closed mesh box: wall force z vs weight (N)", -fm, weight, 0.01);
}

/* ---- 4. turntable ----------------------------------------------------------------- */

static void test_turntable(void)
{
    double gv[3] = {0, 0, -9.81};
    sd_world *w = make_world(gv, 1e-5, 1);
    sd_error err;
    int mat = add_material(w, 0.3, 0.8);
    mesh_buf mb = {0};
    mb_grid(&mb, 0.3, 12, 0.3, 3u);
    int wall = add_mesh(w, "table", &mb, mat);
    const double rpm = 30, rad = 0.15;
    sd_mesh_motion_def md = sd_mesh_motion_def_default();
    md.kind = SD_MESH_ROTATE;
    md.axis_point = sd_test_v(0, 0, 0);
    md.axis = sd_test_v(0, 0, 1);
    md.rpm = rpm;
    md.ramp = 0.2; /* s: gently, so the box sticks */
    sd_test_require(sd_world_set_mesh_motion(w, wall, &md, &err) == SD_OK, "motion", &err);
    sd_shape_desc sh = sd_shape_desc_default();
    sh.kind = "box";
    sh.size = sd_test_v(0.02, 0.02, 0.02);
    sh.margin = 0.001;
    int shape = sd_world_add_shape(w, "cube", &sh, &err);
    sd_test_require(shape >= 0, "shape", &err);
    sd_body_def b = {0};
    b.position = sd_test_v(rad, 0, 0.00999);
    b.shape = shape;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    sd_test_require(sd_world_step(w, 60000, &err) == SD_OK, "step", &err);
    sd_particle_state p = {0};
    sd_world_get_particle(w, 0, &p);
    double rr = sqrt(p.position.x * p.position.x + p.position.y * p.position.y);
    double vt = (-p.position.y * p.velocity.x + p.position.x * p.velocity.y) / rr;
    double omega = rpm * 2 * PI / 60;
    CHECK_REL("turntable: tangential speed vs omega r (m/s)", vt, omega * rr, 0.01);
    CHECK_REL("turntable: radius kept (m)", rr, rad, 0.01);
    sd_wall_info wi;
    sd_world_get_wall(w, (size_t)wall, &wi);
    /* the mesh feels -F at the contacts: its torque about the axis point is
     * minus the particle's contact moment about it, (x - 0) x F + T */
    double mz = -(p.position.x * p.force.y - p.position.y * p.force.x + p.torque.z);
    double scale = fabs(p.force.x) * rr + fabs(p.force.y) * rr + 1e-12;
    CHECK_NEAR("turntable: mesh torque z vs -(moment of the contact) (N m)", wi.torque.z, mz, 1e-9 * scale + 1e-15);
    sd_world_destroy(w);
    mb_free(&mb);
}

/* ---- 5. planar mode: a 2D ellipse on a mesh floor cut by z = 0 ----------------------- */

static void planar_run(int mesh, double *y, double *fy, double *weight)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = SD_LAW_LINEAR;
    wd.dt = 1e-5;
    wd.dimension = 2;
    wd.gravity = sd_test_v(0, -9.81, 0);
    wd.threads = 1;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    int mat = add_material(w, 0.3, 0.5);
    int wall;
    mesh_buf mb = {0};
    if (!mesh) {
        wall = sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 1, 0), mat, &err);
    } else {
        /* the plane y = 0 (normal +y) as a strip x in [-0.3, 0.3], z in [-0.05, 0.05] of 12 x 2 cells */
        for (int j = 0; j <= 2; ++j)
            for (int i = 0; i <= 12; ++i)
                mb_vertex(&mb, -0.3 + 0.05 * i + (j == 1 && i > 0 && i < 12 ? 0.013 : 0), 0, -0.05 + 0.05 * j);
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 12; ++i) {
                size_t a = (size_t)(j * 13 + i), b = a + 1, c = a + 13, d = c + 1;
                mb_tri(&mb, a, c, d); /* (c - a) x (d - a) along +y */
                mb_tri(&mb, a, d, b);
            }
        wall = add_mesh(w, "floor", &mb, mat);
    }
    sd_shape2d_def d = sd_shape2d_def_default();
    d.kind = "ellipse";
    d.semi_axes[0] = 0.02;
    d.semi_axes[1] = 0.01;
    int ell = sd_world_add_shape2d(w, "ell", &d, &err);
    sd_test_require(ell >= 0, "ellipse", &err);
    sd_body_def b = {0};
    b.position = sd_test_v(0.01, 0.02, 0);
    b.orientation[0] = cos(0.15);
    b.orientation[3] = sin(0.15);
    b.shape = ell;
    b.material = mat;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
    sd_test_require(sd_world_step(w, 60000, &err) == SD_OK, "step", &err);
    sd_particle_state p = {0};
    sd_world_get_particle(w, 0, &p);
    sd_wall_info wi;
    sd_world_get_wall(w, (size_t)wall, &wi);
    *y = p.position.y;
    *fy = wi.force.y;
    *weight = 2700 * PI * 0.02 * 0.01 * 9.81; /* per 1 m of thickness */
    sd_world_destroy(w);
    mb_free(&mb);
}

static void test_planar(void)
{
    double yp, fp, wt, ym, fm;
    planar_run(0, &yp, &fp, &wt);
    planar_run(1, &ym, &fm, &wt);
    CHECK_REL("planar: ellipse on a mesh floor, wall force vs the plane wall's (N)", fm, fp, 0.005);
    (void)wt; /* the ellipse still rocks at the end (no rolling resistance): the plane run is the reference */
    CHECK_REL("planar: resting height vs the plane wall's (m)", ym, yp, 0.001);
}

int main(void)
{
    test_sliding();
    rest_in(0);
    rest_in(1);
    test_box();
    test_turntable();
    test_planar();
    return sd_test_summary();
}
