/* mesh_rim.c — bodies of every kind dropped past the open rims of meshes
 * (issue 30, defect 2; the rim rule of geom/mesh_contact.h).
 *
 * A plane contact of a shaped body used to take its depth against the
 * facet's plane extended past an open (boundary) edge: a rounded cube
 * falling through the outlet of the cone hopper sank into the cone's plane
 * continued below the rim and was kicked (20.7 % of its radius of
 * overlap where a sphere reached 0.9 %). Beyond a free edge the body now
 * meets the edge itself (a point contact along the direction that frees it).
 *
 * Each kind (sphere, rounded box, cylinder, ellipsoid, rounded polyhedron
 * under the Hertz-Mindlin law, sharp polyhedron under the volume law, a
 * composite of two rounded boxes, a clump of three spheres) is dropped at
 * 0.5 m/s, at NORI random orientations and offsets, past:
 *   - the outlet of the cone of scripts/make_meshes.py cone (384 facets:
 *     radius 9 mm at z = 0 to 30 mm at z = 35 mm, a cylinder to 60 mm;
 *     the body's centre within a bounding radius of the rim circle),
 *   - the free edge of a single sheet (z = 0, x < 0),
 *   - the edge or corner of a 5 mm square hole in a plate,
 * and, for the reference, on the analytic plane z = 0 in the same
 * orientations at the same speed (the same impact on a flat plane).
 *
 * Checks, each printed with computed, expected and tolerance:
 *  1. the worst overlap of each kind at each rim (stats' max_overlap_ratio,
 *     the overlap over half the body's smallest outer size) within
 *     RIM_MARGIN times its worst over the flat impacts. At a free edge the
 *     contact is a point contact under the same law with the same
 *     equivalent radius, the normal speed at most the impact speed: its
 *     depth is that of a flat impact, but the body meets the edge with a
 *     rounded edge or corner, or turned, so the normal speed of a later
 *     knock (a body tipping over the edge, landing on the cone below its
 *     first touch after the fall has sped it up) may exceed the flat
 *     impact's; 1.5 covers that (measured at most RIM_MEASURED below).
 *     Before the rule the rounded box reached 4-8 times its flat overlap.
 *  2. energy never gained: the total (kinetic, gravity, contact springs)
 *     never above its initial value by more than ETOL of the impact's
 *     kinetic energy (the integration's own error over a contact of ~10
 *     steps, measured below 1e-3 on the flat plane).
 *  3. rolling over an edge: a sphere and a cylinder rolling at 0.2 m/s
 *     and a rounded box sliding at 0.3 m/s off the sheet's free edge: the
 *     overlap within 1.5 times what the same body keeps rolling or sliding
 *     on the analytic plane, and energy never gained.
 */
#include "test.h"

#include <string.h>

#define PI 3.14159265358979323846
#define DT 1e-5      /* s, the hopper (the volume law's stability needs DT_VOLUME) */
#define DT_VOLUME 2e-6
#define V0 0.5     /* m/s, the impact speed */
#define NORI 10    /* orientations per kind and rim */
#define RIM_MARGIN 1.5
#define ETOL 0.01

enum { K_SPHERE, K_BOX, K_CYLINDER, K_ELLIPSOID, K_POLY, K_POLY_VOLUME, K_COMPOSITE, K_CLUMP, NKIND };
static const char *kind_name[NKIND] = {"sphere",    "rounded box",      "cylinder",  "ellipsoid",
                                       "polyhedron", "polyhedron (vol)", "composite", "clump"};
enum { G_FLAT, G_CONE, G_SHEET, G_HOLE, NGEOM };
static const char *geom_name[NGEOM] = {"flat plane", "cone outlet", "sheet edge", "square hole"};

#define HOLE 0.0025 /* m, half the hole's side */

/* ---- meshes ---------------------------------------------------------- */

typedef struct mesh_buf {
    sd_v3d v[1024];
    uint32_t t[1024][3];
    size_t nv, nt;
} mesh_buf;

static uint32_t mesh_vertex(mesh_buf *mb, double x, double y, double z)
{
    mb->v[mb->nv] = sd_test_v(x, y, z);
    return (uint32_t)mb->nv++;
}

/* Triangle (a, b, c), wound so that its normal's dot with `towards` is
 * positive. */
static void mesh_tri(mesh_buf *mb, uint32_t a, uint32_t b, uint32_t c, sd_v3d towards)
{
    sd_v3d p = mb->v[a], q = mb->v[b], r = mb->v[c];
    double ux = q.x - p.x, uy = q.y - p.y, uz = q.z - p.z, vx = r.x - p.x, vy = r.y - p.y, vz = r.z - p.z;
    double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    int flip = nx * towards.x + ny * towards.y + nz * towards.z < 0;
    uint32_t *t = mb->t[mb->nt++];
    t[0] = a;
    t[1] = flip ? c : b;
    t[2] = flip ? b : c;
}

/* scripts/make_meshes.py cone with its defaults: outlet 9 mm, radius 30 mm
 * at 35 mm, a cylinder to 60 mm; 48 segments, 2 rings, 2 layers. */
static void mesh_cone(mesh_buf *mb)
{
    const int seg = 48;
    const double rz[5][2] = {{0.009, 0.0}, {0.0195, 0.0175}, {0.03, 0.035}, {0.03, 0.0475}, {0.03, 0.06}};
    for (int k = 0; k < seg; ++k) {
        double t0 = 2 * PI * k / seg, t1 = 2 * PI * (k + 1) / seg;
        for (int j = 0; j < 4; ++j) {
            double ra = rz[j][0], za = rz[j][1], rb = rz[j + 1][0], zb = rz[j + 1][1];
            uint32_t a = mesh_vertex(mb, ra * cos(t0), ra * sin(t0), za);
            uint32_t b = mesh_vertex(mb, ra * cos(t1), ra * sin(t1), za);
            uint32_t c = mesh_vertex(mb, rb * cos(t1), rb * sin(t1), zb);
            uint32_t d = mesh_vertex(mb, rb * cos(t0), rb * sin(t0), zb);
            double tm = 0.5 * (t0 + t1);
            sd_v3d in = sd_test_v(-cos(tm), -sin(tm), 0); /* normals towards the axis */
            mesh_tri(mb, a, b, c, in);
            mesh_tri(mb, a, c, d, in);
        }
    }
}

/* A sheet z = 0 over x in [-20, 0] mm, y in [-20, 20] mm, normal up: its
 * free edge x = 0 runs along y. */
static void mesh_sheet(mesh_buf *mb)
{
    uint32_t a = mesh_vertex(mb, -0.02, -0.02, 0), b = mesh_vertex(mb, 0, -0.02, 0);
    uint32_t c = mesh_vertex(mb, 0, 0.02, 0), d = mesh_vertex(mb, -0.02, 0.02, 0);
    mesh_tri(mb, a, b, c, sd_test_v(0, 0, 1));
    mesh_tri(mb, a, c, d, sd_test_v(0, 0, 1));
}

/* A plate z = 0 over [-20, 20]^2 mm with the square hole [-HOLE, HOLE]^2:
 * eight triangles between the outer and the inner square, normal up. */
static void mesh_hole(mesh_buf *mb)
{
    const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
    uint32_t o[4], in[4];
    for (int k = 0; k < 4; ++k) {
        o[k] = mesh_vertex(mb, 0.02 * sx[k], 0.02 * sy[k], 0);
        in[k] = mesh_vertex(mb, HOLE * sx[k], HOLE * sy[k], 0);
    }
    for (int k = 0; k < 4; ++k) {
        int l = (k + 1) % 4;
        mesh_tri(mb, o[k], o[l], in[l], sd_test_v(0, 0, 1));
        mesh_tri(mb, o[k], in[l], in[k], sd_test_v(0, 0, 1));
    }
}

/* ---- worlds ---------------------------------------------------------- */

static double world_dt = DT; /* s, of the last world made */

static sd_world *world_of(int kind, int geom, int *shape, double *bound)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.law = kind == K_POLY_VOLUME ? SD_LAW_VOLUME : SD_LAW_HERTZ_MINDLIN;
    wd.dt = kind == K_POLY_VOLUME ? DT_VOLUME : DT;
    world_dt = wd.dt;
    wd.gravity = sd_test_v(0, 0, -9.81);
    wd.threads = 1;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "m";
    m.density = 2500;
    m.youngs_modulus = 5e6;
    m.poisson_ratio = 0.3;
    m.restitution = 0.5;
    m.friction = 0.5;
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    if (geom == G_FLAT) {
        sd_test_require(sd_world_add_plane(w, "floor", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err) >= 0,
                        "plane", &err);
    } else {
        static mesh_buf mb;
        memset(&mb, 0, sizeof mb);
        if (geom == G_CONE)
            mesh_cone(&mb);
        else if (geom == G_SHEET)
            mesh_sheet(&mb);
        else
            mesh_hole(&mb);
        sd_mesh_def md = sd_mesh_def_default();
        md.vertices = mb.v;
        md.vertex_count = mb.nv;
        md.triangles = (const uint32_t(*)[3])mb.t;
        md.triangle_count = mb.nt;
        md.material = mat;
        sd_test_require(sd_world_add_mesh(w, "rim", &md, &err) >= 0, "mesh", &err);
    }
    sd_shape_desc d = sd_shape_desc_default();
    *shape = -1;
    *bound = 0.0015;
    sd_v3d pv[10];
    switch (kind) {
    case K_SPHERE:
        return w;
    case K_BOX:
        d.kind = "box";
        d.size = sd_test_v(0.0024, 0.0024, 0.0024);
        d.rounding = 0.0003;
        break;
    case K_CYLINDER:
        d.kind = "cylinder";
        d.size = sd_test_v(0.0026, 0, 0.003);
        break;
    case K_ELLIPSOID:
        d.kind = "ellipsoid";
        d.size = sd_test_v(0.0034, 0.0026, 0.0018);
        break;
    case K_POLY:
    case K_POLY_VOLUME: {
        /* an irregular convex decahedron, about 3 mm across */
        const double c[10][3] = {{1.4, 0.1, 0.2},  {-1.3, 0.3, -0.1}, {0.2, 1.5, 0.1},  {-0.1, -1.4, 0.3},
                                 {0.3, 0.2, 1.2},  {0.1, -0.3, -1.3}, {0.9, 0.9, -0.7}, {-0.8, -0.9, 0.8},
                                 {-0.9, 0.8, 0.7}, {0.8, -0.7, -0.9}};
        for (int k = 0; k < 10; ++k)
            pv[k] = sd_test_v(1e-3 * c[k][0], 1e-3 * c[k][1], 1e-3 * c[k][2]);
        d.kind = "polyhedron";
        d.vertices = pv;
        d.vertex_count = 10;
        if (kind == K_POLY)
            d.rounding = 0.0002;
        break;
    }
    default: {
        /* composite: two rounded 1.6 mm boxes side by side; clump: three
         * 0.8 mm spheres in an L */
        sd_shape_desc e = sd_shape_desc_default();
        if (kind == K_COMPOSITE) {
            e.kind = "box";
            e.size = sd_test_v(0.0014, 0.0014, 0.0014);
            e.rounding = 0.0001;
        } else {
            e.kind = "sphere";
            e.size = sd_test_v(0.0008, 0, 0);
        }
        int es = sd_world_add_shape(w, "element", &e, &err);
        sd_test_require(es >= 0, "element", &err);
        sd_composite_element el[3];
        memset(el, 0, sizeof el);
        int ne = kind == K_COMPOSITE ? 2 : 3;
        const double at[3][3] = {{-0.0008, 0, 0}, {0.0008, 0, 0}, {-0.0008, 0.0015, 0}};
        for (int k = 0; k < ne; ++k) {
            el[k].shape = es;
            el[k].position = sd_test_v(at[k][0], at[k][1], at[k][2]);
        }
        sd_composite_desc cd = sd_composite_desc_default();
        cd.elements = el;
        cd.element_count = (size_t)ne;
        *shape = sd_world_add_composite(w, "body", &cd, &err);
        sd_test_require(*shape >= 0, "composite", &err);
        break;
    }
    }
    if (*shape < 0) {
        *shape = sd_world_add_shape(w, "body", &d, &err);
        sd_test_require(*shape >= 0, "shape", &err);
    }
    sd_shape_info si;
    sd_test_require(sd_world_get_shape(w, (size_t)*shape, &si) == SD_OK, "shape info", NULL);
    *bound = si.bounding_radius;
    return w;
}

static void add_body(sd_world *w, int kind, int shape, sd_v3d x, sd_v3d v, sd_v3d omega, const double q[4])
{
    sd_error err;
    if (kind == K_SPHERE) {
        sd_sphere_def s;
        memset(&s, 0, sizeof s);
        s.position = x;
        s.velocity = v;
        s.angular_velocity = omega;
        s.radius = 0.0015;
        s.material = 0;
        sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
        return;
    }
    sd_body_def b;
    memset(&b, 0, sizeof b);
    b.position = x;
    b.velocity = v;
    b.angular_velocity = omega;
    memcpy(b.orientation, q, sizeof b.orientation);
    b.shape = shape;
    b.material = 0;
    sd_test_require(sd_world_add_bodies(w, 1, &b, &err) == SD_OK, "body", &err);
}

/* The body's mechanical energy (kinetic and gravity), J. */
static double energy(const sd_stats *s)
{
    return s->kinetic_translational + s->kinetic_rotational + s->potential_gravity;
}

typedef struct run_out {
    double overlap; /* the worst max_overlap_ratio */
    double gain;    /* the largest rise of the mechanical energy over the initial, J, while in
                       flight (no contact) and at the end */
    double z;       /* m, the centre's height at the end */
} run_out;

/* Steps for t seconds or until the body has fallen below zlow; the
 * overlap is recorded while the centre is at x > xnear. The
 * energy is compared out of contact: in a contact the springs hold some
 * of it (and the tangential spring's share is not the work it stored),
 * out of contact the body can only have lost energy. */
static run_out run(sd_world *w, double t, double zlow, double xnear)
{
    sd_error err;
    run_out o = {0, 0, 0};
    sd_stats s;
    sd_world_stats(w, &s);
    double e0 = energy(&s);
    long n = (long)(t / world_dt + 0.5);
    for (long k = 0; k < n; ++k) {
        sd_test_require(sd_world_step(w, 1, &err) == SD_OK, "step", &err);
        sd_world_stats(w, &s);
        sd_particle_state p;
        sd_world_get_particle(w, 0, &p);
        if (p.position.x > xnear)
            o.overlap = fmax(o.overlap, s.max_overlap_ratio);
        o.z = p.position.z;
        int last = k == n - 1 || p.position.z < zlow;
        if (s.wall_contacts == 0 || last)
            o.gain = fmax(o.gain, energy(&s) - e0);
        if (p.position.z < zlow)
            break;
    }
    return o;
}

/* ---- 1 and 2: drops -------------------------------------------------- */

static unsigned rng_state = 20261207u;
static double urand(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (double)(rng_state >> 8) / 16777216.0;
}

/* A random unit quaternion (Shoemake). */
static void random_quat(double q[4])
{
    double u1 = urand(), u2 = urand(), u3 = urand();
    double a = sqrt(1 - u1), b = sqrt(u1);
    q[0] = a * sin(2 * PI * u2);
    q[1] = a * cos(2 * PI * u2);
    q[2] = b * sin(2 * PI * u3);
    q[3] = b * cos(2 * PI * u3);
}

static double worst_rim[NKIND][NGEOM];

static void test_drops(void)
{
    for (int kind = 0; kind < NKIND; ++kind) {
        double worst[NGEOM] = {0}, gain[NGEOM] = {0}, ke = 0;
        for (int o = 0; o < NORI; ++o) {
            double q[4], u = urand(), vv = urand();
            random_quat(q);
            for (int geom = 0; geom < NGEOM; ++geom) {
                int shape;
                double bound;
                sd_world *w = world_of(kind, geom, &shape, &bound);
                double z0 = bound + 0.0002, phi = 2 * PI * vv;
                sd_v3d x = sd_test_v(0, 0, z0);
                if (geom == G_CONE) {
                    /* the centre from 0.8 bounding radii inside the rim to
                     * 0.2 outside, above the cone's surface there */
                    double r = 0.009 + (u * 1.0 - 0.8) * bound;
                    double zs = (r + bound - 0.009) / 0.6;
                    x = sd_test_v(r * cos(phi), r * sin(phi), z0 + (zs > 0 ? zs : 0));
                } else if (geom == G_SHEET) {
                    /* the centre over the sheet, up to 0.6 bounding radii
                     * from the edge: the body lands across the edge and tips
                     * off (the sheet's back is no wall: a mesh is one-sided,
                     * and a body swinging round the edge under it would meet
                     * its back as a deep overlap, docs/mesh-walls.md) */
                    x = sd_test_v(-u * 0.6 * bound, 0, z0);
                } else if (geom == G_HOLE) {
                    /* along an edge of the hole, corners included */
                    x = sd_test_v(HOLE + (u * 1.2 - 0.6) * bound, HOLE * (2.2 * vv - 1.0), z0);
                }
                add_body(w, kind, shape, x, sd_test_v(0, 0, -V0), sd_test_v(0, 0, 0), q);
                sd_particle_state p;
                sd_world_get_particle(w, 0, &p);
                ke = 0.5 * p.mass * V0 * V0;
                run_out r = run(w, 0.03, -0.01, -1.0);
                sd_world_destroy(w);
                worst[geom] = fmax(worst[geom], r.overlap);
                gain[geom] = fmax(gain[geom], r.gain / ke);
            }
        }
        for (int geom = 0; geom < NGEOM; ++geom) {
            char label[128];
            worst_rim[kind][geom] = worst[geom];
            if (geom != G_FLAT) {
                snprintf(label, sizeof label, "%s, %s: worst overlap ratio", kind_name[kind], geom_name[geom]);
                CHECK_NEAR(label, worst[geom], worst[G_FLAT], (RIM_MARGIN - 1) * worst[G_FLAT]);
            }
            snprintf(label, sizeof label, "%s, %s: energy gained / impact KE", kind_name[kind], geom_name[geom]);
            CHECK_NEAR(label, gain[geom], 0.0, ETOL);
        }
    }
}

/* ---- 3: over the edge ------------------------------------------------ */

static void test_roll(int kind, const char *what, double v, int rolling)
{
    double ov[2], gain[2], z[2];
    for (int geom = 0; geom < 2; ++geom) { /* the analytic plane, the sheet */
        int shape;
        double bound;
        sd_world *w = world_of(kind, geom == 0 ? G_FLAT : G_SHEET, &shape, &bound);
        double q[4] = {1, 0, 0, 0}, h = bound;
        if (kind == K_CYLINDER) { /* on its side, axis along y */
            q[0] = cos(PI / 4);
            q[1] = sin(PI / 4);
            h = 0.0013;
        } else if (kind == K_BOX) {
            h = 0.0015;
        }
        /* rolling: omega_y = v / h; starts 4 mm from the edge, touching */
        sd_v3d omega = sd_test_v(0, rolling ? v / h : 0, 0);
        add_body(w, kind, shape, sd_test_v(-0.004, 0, h), sd_test_v(v, 0, 0), omega, q);
        sd_particle_state p;
        sd_world_get_particle(w, 0, &p);
        /* the overlap from a bounding radius before the edge on */
        run_out r = run(w, 0.06, -0.01, -bound);
        sd_world_destroy(w);
        ov[geom] = r.overlap;
        gain[geom] = r.gain / (0.5 * p.mass * v * v);
        z[geom] = r.z;
    }
    char label[128];
    printf("%-4s %s: the centre's height at the end %.4g m (below -2 mm: it fell off the edge)\n",
           z[1] < -0.002 ? "ok" : "FAIL", what, z[1]);
    CHECK(z[1] < -0.002);
    snprintf(label, sizeof label, "%s over the edge: overlap ratio", what);
    CHECK_NEAR(label, ov[1], ov[0], 0.5 * ov[0]);
    snprintf(label, sizeof label, "%s over the edge: energy gained / KE", what);
    CHECK_NEAR(label, gain[1], 0.0, ETOL);
}

int main(void)
{
    test_drops();
    printf("worst overlap ratio (rim / flat):\n");
    for (int kind = 0; kind < NKIND; ++kind)
        printf("  %-18s flat %.4f  cone %.4f (%.2f)  sheet %.4f (%.2f)  hole %.4f (%.2f)\n", kind_name[kind],
               worst_rim[kind][G_FLAT], worst_rim[kind][G_CONE], worst_rim[kind][G_CONE] / worst_rim[kind][G_FLAT],
               worst_rim[kind][G_SHEET], worst_rim[kind][G_SHEET] / worst_rim[kind][G_FLAT], worst_rim[kind][G_HOLE],
               worst_rim[kind][G_HOLE] / worst_rim[kind][G_FLAT]);
    test_roll(K_SPHERE, "sphere rolling", 0.2, 1);
    test_roll(K_CYLINDER, "cylinder rolling", 0.2, 1);
    test_roll(K_BOX, "rounded box sliding", 0.3, 0);
    return sd_test_summary();
}
