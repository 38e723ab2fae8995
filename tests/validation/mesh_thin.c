/* mesh_thin.c — thin mesh walls hold their particles (issue 30 "thin
 * walls", issue 31 probe 3 finding 10; the rule in geom/mesh_contact.h,
 * sd_mesh_front).
 *
 * The probe's case: a closed box mesh 0.2 mm thick (`side: outside`, 12
 * facets, 0.1 m square, top face z = 0) hit by a 1 mm sphere of E = 10 MPa.
 * From 5 m/s the sphere sinks into the top face deeper than the slab is
 * thick; the bottom face then took it as overlapped by nearly its whole
 * size and pushed it on through (the overlap guard stopped the run; with
 * the guard off the sphere ended inside or below the slab). The same
 * impacts on an open sheet (two triangles, normals up) are checked too.
 *
 * Each case: a sphere (r 1 mm), a rounded box (2 mm, rounding 0.2 mm), a
 * rounded cylinder (2 mm across and long) and a composite of two 1.2 mm
 * rounded boxes, the shapes tilted, started 0.05 mm above the top face (the
 * box) or their bounding radius up (the others) at speed v, at 0, 30 and
 * 60 degrees from the normal, no gravity, Hertz-Mindlin (e 0.5, mu 0.3),
 * dt 1e-6 s, run 2 ms (the contact lasts about 0.2 ms). The speeds go up
 * to the one the overlap guard allows: each impact is run first on the
 * analytic plane z = 0 (a wall of any thickness), and printed with its
 * deepest overlap there, which must stay below the guard's limit (50 % of
 * the radius, the default; the composite's smaller elements reach it from
 * 9 m/s, so it stops at 7.5). On the slab and on the sheet the run must
 * finish (the guard never stops it), the particle must end above the top
 * face at the plane run's height and normal speed (1e-6 of the radius and
 * of the speed: far from the slab's edges its top face is the plane), and
 * its kinetic energy (translation and rotation) must not grow: at most the
 * energy it came with, to 1e-9. On the code before the rule every shape
 * on the slab fails from 1 m/s and the sphere from 5 m/s (the guard stops
 * the run, the body having gained energy); the sheet held before as now.
 */
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

enum { WALL_PLANE, WALL_SLAB, WALL_SHEET };
static const char *const wall_name[] = {"plane", "slab 0.2 mm", "sheet"};

static const double R = 1e-3, T = 2e-4, H = 0.05;

/* The closed slab |x|, |y| <= H, -T <= z <= 0 (12 facets, wound by the
 * mesh code: outside) or the sheet z = 0 (2 facets, normals up). */
static void add_mesh(sd_world *w, int kind, int mat)
{
    static const sd_v3d slab_v[8] = {{-H, -H, -T}, {H, -H, -T}, {H, H, -T}, {-H, H, -T},
                                     {-H, -H, 0},  {H, -H, 0},  {H, H, 0},  {-H, H, 0}};
    static const uint32_t slab_t[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                           {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    static const sd_v3d sheet_v[4] = {{-H, -H, 0}, {H, -H, 0}, {H, H, 0}, {-H, H, 0}};
    static const uint32_t sheet_t[2][3] = {{0, 1, 2}, {0, 2, 3}};
    sd_error err;
    sd_mesh_def md = sd_mesh_def_default();
    if (kind == WALL_SLAB) {
        md.vertices = slab_v;
        md.vertex_count = 8;
        md.triangles = slab_t;
        md.triangle_count = 12;
        md.outside = 1;
    } else {
        md.vertices = sheet_v;
        md.vertex_count = 4;
        md.triangles = sheet_t;
        md.triangle_count = 2;
    }
    md.material = mat;
    sd_test_require(sd_world_add_mesh(w, "thin", &md, &err) >= 0, "mesh", &err);
}

typedef struct impact {
    int ok;           /* the run finished (no guard stopped it) */
    double z, vz;     /* m, m/s: the centre's height and normal speed at the end */
    double ke0, ke1;  /* J: kinetic energy at the start and at the end */
    double max_ratio; /* the deepest overlap over the run / the radius (sd_stats' ratio) */
} impact;

enum { KIND_SPHERE, KIND_BOX, KIND_CYLINDER, KIND_COMPOSITE, KIND_COUNT };
static const char *const kind_name[] = {"sphere", "box", "cylinder", "composite"};

/* The shape of kind `kind` (not a sphere): the rounded box, a rounded
 * cylinder (2 mm across and long, rounding 0.2 mm) or a composite of two
 * rounded boxes of 1.2 mm side by side (1.1 mm apart: the contact code of
 * composite elements). */
static int add_shape(sd_world *w, int kind)
{
    sd_error err;
    sd_shape_desc sh = sd_shape_desc_default();
    sh.kind = kind == KIND_CYLINDER ? "cylinder" : "box";
    sh.size = sd_test_v(1.6 * R, 1.6 * R, 1.6 * R); /* outer 2 mm: the rounding adds 2 x 0.2 mm */
    sh.rounding = 0.2 * R;
    if (kind == KIND_COMPOSITE)
        sh.size = sd_test_v(0.8 * R, 0.8 * R, 0.8 * R);
    int shape = sd_world_add_shape(w, kind_name[kind], &sh, &err);
    sd_test_require(shape >= 0, "shape", &err);
    if (kind != KIND_COMPOSITE)
        return shape;
    sd_composite_element el[2];
    memset(el, 0, sizeof el);
    for (int k = 0; k < 2; ++k) {
        el[k].shape = shape;
        el[k].position = sd_test_v(0, k ? 0.55 * R : -0.55 * R, 0);
    }
    sd_composite_desc cd = sd_composite_desc_default();
    cd.elements = el;
    cd.element_count = 2;
    shape = sd_world_add_composite(w, "pair", &cd, &err);
    sd_test_require(shape >= 0, "composite", &err);
    return shape;
}

/* One impact: a body of kind `kind` at speed v, angle th (rad) from the
 * normal, on wall kind `wall`. */
static impact run_impact(int wall, int kind, double v, double th)
{
    sd_error err;
    sd_world *w;
    sd_world_def wd = sd_world_def_default();
    wd.dt = 1e-6;
    wd.gravity = sd_test_v(0, 0, 0);
    wd.threads = 1;
    sd_test_require(sd_world_create(&wd, &w, &err) == SD_OK, "world", &err);
    sd_material_def m = sd_material_def_default();
    m.name = "m";
    m.density = 2500;
    m.youngs_modulus = 1e7;
    m.poisson_ratio = 0.3;
    m.restitution = 0.5;
    m.friction = 0.3;
    int mat = sd_world_add_material(w, &m, &err);
    sd_test_require(mat >= 0, "material", &err);
    if (wall == WALL_PLANE)
        sd_test_require(sd_world_add_plane(w, "thin", sd_test_v(0, 0, 0), sd_test_v(0, 0, 1), mat, &err) >= 0,
                        "plane", &err);
    else
        add_mesh(w, wall, mat);
    sd_v3d vel = sd_test_v(v * sin(th), 0, -v * cos(th));
    if (kind != KIND_SPHERE) {
        int shape = add_shape(w, kind);
        /* tilted 20 degrees about x, then 10 about y: a corner and an edge
         * lead, the centre sqrt(3) R ... R above the lowest point */
        double a = 10.0 * PI / 180.0, b = 5.0 * PI / 180.0;
        double qa[4] = {cos(a), sin(a), 0, 0}, qb[4] = {cos(b), 0, sin(b), 0};
        sd_body_def bd = {0};
        bd.orientation[0] = qb[0] * qa[0] - qb[2] * qa[2];
        bd.orientation[1] = qb[0] * qa[1] + qb[2] * qa[3];
        bd.orientation[2] = qb[0] * qa[2] + qb[2] * qa[0];
        bd.orientation[3] = qb[0] * qa[3] - qb[2] * qa[1];
        bd.shape = shape;
        bd.material = mat;
        bd.velocity = vel;
        /* its lowest point 0.05 mm above z = 0: the support along -z of the
         * rounded box (half 1 mm) turned by the orientation */
        double q0 = bd.orientation[0], q1 = bd.orientation[1], q2 = bd.orientation[2], q3 = bd.orientation[3];
        /* the body frame's axes' z components: row 3 of the rotation matrix */
        double r31 = 2 * (q1 * q3 - q0 * q2), r32 = 2 * (q2 * q3 + q0 * q1), r33 = 1 - 2 * (q1 * q1 + q2 * q2);
        double core = 0.8 * R; /* the core's half side: the box's half side less the rounding */
        double low = core * (fabs(r31) + fabs(r32) + fabs(r33)) + 0.2 * R;
        if (kind != KIND_BOX) { /* the others start their bounding radius up: a longer approach */
            sd_shape_info si;
            sd_test_require(sd_world_get_shape(w, (size_t)shape, &si) == SD_OK, "shape info", &err);
            low = si.bounding_radius;
        }
        bd.position = sd_test_v(0, 0, low + 0.05e-3);
        sd_test_require(sd_world_add_bodies(w, 1, &bd, &err) == SD_OK, "body", &err);
    } else {
        sd_sphere_def s = {0};
        s.position = sd_test_v(0, 0, R + 0.05e-3);
        s.radius = R;
        s.material = mat;
        s.velocity = vel;
        sd_test_require(sd_world_add_spheres(w, 1, &s, &err) == SD_OK, "sphere", &err);
    }
    impact r = {0};
    sd_stats st;
    sd_world_stats(w, &st);
    r.ke0 = st.kinetic_translational + st.kinetic_rotational;
    r.ok = 1;
    for (int k = 0; k < 200 && r.ok; ++k) {
        r.ok = sd_world_step(w, 10, &err) == SD_OK;
        sd_world_stats(w, &st);
        if (st.max_overlap_ratio > r.max_ratio)
            r.max_ratio = st.max_overlap_ratio;
    }
    sd_particle_state p = {0};
    sd_world_get_particle(w, 0, &p);
    r.z = p.position.z;
    r.vz = p.velocity.z;
    r.ke1 = st.kinetic_translational + st.kinetic_rotational;
    sd_world_destroy(w);
    return r;
}

int main(void)
{
    const double speeds[] = {1, 2.5, 5, 7.5, 9, 12};
    const double angles[] = {0, 30, 60};
    const double guard = 0.5; /* simulation.max_overlap's default */
    for (int kind = 0; kind < KIND_COUNT; ++kind)
        for (size_t a = 0; a < sizeof angles / sizeof angles[0]; ++a)
            for (size_t s = 0; s < sizeof speeds / sizeof speeds[0]; ++s) {
                double v = speeds[s], th = angles[a] * PI / 180.0;
                if (kind == KIND_COMPOSITE && v > 7.5)
                    continue; /* its smaller elements reach the guard's 50 % on the plane from 9 m/s */
                impact ref = run_impact(WALL_PLANE, kind, v, th);
                printf("%-9s %4.1f m/s at %2.0f deg: on the plane overlap %5.1f %% of the radius (guard %.0f %%), "
                       "kinetic energy %.3g -> %.3g J\n",
                       kind_name[kind], v, angles[a], 100 * ref.max_ratio, 100 * guard, ref.ke0, ref.ke1);
                /* the speed is one the guard allows on a wall of any thickness */
                CHECK(ref.ok && ref.max_ratio < guard);
                for (int wall = WALL_SLAB; wall <= WALL_SHEET; ++wall) {
                    impact r = run_impact(wall, kind, v, th);
                    printf("    on the %-11s: %s, centre at z = %+.6g m (> 0; the plane's %+.6g) moving at "
                           "%+.6g m/s (the plane's %+.6g), kinetic energy %.3g -> %.3g J (at most %.3g), "
                           "overlap %5.1f %%\n",
                           wall_name[wall], r.ok ? "ran" : "STOPPED", r.z, ref.z, r.vz, ref.vz, r.ke0, r.ke1, r.ke0,
                           100 * r.max_ratio);
                    CHECK(r.ok);
                    CHECK(r.z > 0);
                    /* far from the slab's edges its top face is the plane: the
                     * same rebound (a tumbling body may be on its way down to
                     * a second touch at the end, on both) */
                    CHECK(fabs(r.z - ref.z) <= 1e-6 * R);
                    CHECK(fabs(r.vz - ref.vz) <= 1e-6 * v);
                    CHECK(r.ke1 <= r.ke0 * (1 + 1e-9));
                }
            }
    return sd_test_summary();
}
