/* shape_mass.c — mass properties of shape templates (shape/shape.c).
 *
 * Sharp shapes against their closed forms (sphere, box, cylinder, cone,
 * ellipsoid; polyhedra given as a box's 8 corners, a regular tetrahedron and
 * octahedron). Rounded shapes against computations written here, by other
 * routes than the library's: the swept box by slices (2D rounded rectangles
 * integrated over z), swept cylinders, cones and spheroids by Green's
 * theorem along the boundary of their meridian section, the triaxial swept
 * ellipsoid by the divergence theorem over its Gauss map, and rounded
 * polyhedra by ray casting (radial function from the centre, the point-to-
 * triangle distance, a quadrature over directions). Then margins (outer size
 * kept), translation and rotation invariance of polyhedra, and bad input.
 */
#include "test.h"
#include "test_quad.h"

#include <string.h>

#define M_PI SD_PI_D

#include "core/alloc.h"
#include "core/rng.h"
#include "shape/shape_make.h"
#include "shape/support.h"

static sd_vec3 verts[4 * SD_SHAPE_MAX_VERTICES];

static sd_shape make(sd_shape_def d)
{
    sd_shape s;
    sd_error err;
    size_t used = 0;
    sd_status st = sd_shape_make(&d, &s, verts, 4 * SD_SHAPE_MAX_VERTICES, &used, &err);
    sd_test_require(st == SD_OK, "sd_shape_make", &err);
    return s;
}

static sd_shape_def def_of(int kind, double x, double y, double z)
{
    sd_shape_def d = sd_shape_def_default();
    d.kind = kind;
    d.size = sd_v3(x, y, z);
    return d;
}

static void check_mass(const char *label, sd_shape s, double vol, double ix, double iy, double iz, double tol)
{
    char buf[160];
    snprintf(buf, sizeof buf, "%s: volume", label);
    CHECK_REL(buf, s.volume, vol, tol);
    snprintf(buf, sizeof buf, "%s: I_x", label);
    CHECK_REL(buf, s.inertia.x, ix, tol);
    snprintf(buf, sizeof buf, "%s: I_y", label);
    CHECK_REL(buf, s.inertia.y, iy, tol);
    snprintf(buf, sizeof buf, "%s: I_z", label);
    CHECK_REL(buf, s.inertia.z, iz, tol);
}

/* ---- Gauss–Legendre on [lo, hi] ------------------------------------------- */


#define NGL 64
static double glx[NGL], glw[NGL];

/* ---- swept box by slices ----------------------------------------------------- */

/* area, ∫x², ∫y² of the rectangle of half sides (a, b) swept by rho (2D) */
static void rounded_rect(double a, double b, double rho, double *A, double *jx, double *jy)
{
    double qa = a * a * M_PI * rho * rho / 4 + 2 * a * rho * rho * rho / 3 + M_PI * pow(rho, 4) / 16;
    double qb = b * b * M_PI * rho * rho / 4 + 2 * b * rho * rho * rho / 3 + M_PI * pow(rho, 4) / 16;
    *A = 4 * a * b + 4 * rho * (a + b) + M_PI * rho * rho;
    *jx = 4 * b * a * a * a / 3 + 2 * 2 * b * (pow(a + rho, 3) - a * a * a) / 3 + 2 * rho * 2 * a * a * a / 3 + 4 * qa;
    *jy = 4 * a * b * b * b / 3 + 2 * 2 * a * (pow(b + rho, 3) - b * b * b) / 3 + 2 * rho * 2 * b * b * b / 3 + 4 * qb;
}

static void swept_box_slices(double a, double b, double c, double r, double *vol, double in[3])
{
    double A, jx, jy;
    rounded_rect(a, b, r, &A, &jx, &jy);
    /* |z| <= c: the section is constant */
    double V = 2 * c * A, Jx = 2 * c * jx, Jy = 2 * c * jy, Jz = A * 2 * c * c * c / 3;
    /* caps: z = c + r sin ψ, section radius r cos ψ, dz = r cos ψ dψ (both caps) */
    for (int k = 0; k < NGL; ++k) {
        double psi = M_PI / 4 * (glx[k] + 1), wt = M_PI / 4 * glw[k] * r * cos(psi) * 2;
        double z = c + r * sin(psi);
        rounded_rect(a, b, r * cos(psi), &A, &jx, &jy);
        V += wt * A;
        Jx += wt * jx;
        Jy += wt * jy;
        Jz += wt * A * z * z;
    }
    *vol = V;
    in[0] = Jy + Jz;
    in[1] = Jx + Jz;
    in[2] = Jx + Jy;
}

/* ---- meridian sections by Green's theorem --------------------------------------
 * ∫∫ ρ^k z^m dρ dz = ∮ ρ^(k+1) z^m / (k+1) dz, counter-clockwise; the axis
 * (ρ = 0) adds nothing. Accumulates ∫ρ, ∫ρz, ∫ρz², ∫ρ³. */
typedef struct {
    double s1, sz, szz, s3;
} rev;

static void green_point(rev *m, double rho, double z, double dz, double wt)
{
    m->s1 += wt * rho * rho / 2 * dz;
    m->sz += wt * rho * rho / 2 * z * dz;
    m->szz += wt * rho * rho / 2 * z * z * dz;
    m->s3 += wt * pow(rho, 4) / 4 * dz;
}

static void green_line(rev *m, double r0, double z0, double r1, double z1)
{
    for (int k = 0; k < NGL; ++k) {
        double t = 0.5 * (glx[k] + 1);
        green_point(m, r0 + t * (r1 - r0), z0 + t * (z1 - z0), z1 - z0, 0.5 * glw[k]);
    }
}

static void green_arc(rev *m, double cr, double cz, double R, double f0, double f1)
{
    for (int k = 0; k < NGL; ++k) {
        double f = f0 + 0.5 * (glx[k] + 1) * (f1 - f0);
        green_point(m, cr + R * cos(f), cz + R * sin(f), R * cos(f) * (f1 - f0), 0.5 * glw[k]);
    }
}

static void rev_props(const rev *m, double *vol, double *zc, double in[3])
{
    *vol = 2 * M_PI * m->s1;
    *zc = m->sz / m->s1;
    in[2] = 2 * M_PI * m->s3;
    in[0] = in[1] = M_PI * m->s3 + 2 * M_PI * m->szz - *vol * *zc * *zc;
}

/* ---- swept triaxial ellipsoid over its Gauss map ----------------------------
 * Outer surface by its normal n: X = A²n/h + r n, h = |A n|, area element
 * (R1 + r)(R2 + r) dΩ, R1 R2 = a²b²c²/h⁴, R1 + R2 = tr A²/h - |A²n|²/h³;
 * V = ⅓∮ (h + r) dS, ∫xx = ⅕∮ (h + r) x² dS. */
static void ellipsoid_gauss_map(double a, double b, double c, double r, int n, double *vol, double in[3])
{
    double *x = malloc(sizeof(double) * (size_t)n), *w = malloc(sizeof(double) * (size_t)n);
    gl_nodes(n, x, w);
    double V = 0, J[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        double th = M_PI / 4 * (x[i] + 1);
        for (int j = 0; j < n; ++j) {
            double ph = M_PI / 4 * (x[j] + 1);
            double nx = sin(th) * cos(ph), ny = sin(th) * sin(ph), nz = cos(th);
            double h = sqrt(a * a * nx * nx + b * b * ny * ny + c * c * nz * nz);
            double A2n2 = pow(a, 4) * nx * nx + pow(b, 4) * ny * ny + pow(c, 4) * nz * nz;
            double k1k2 = a * a * b * b * c * c / pow(h, 4), ksum = (a * a + b * b + c * c) / h - A2n2 / (h * h * h);
            double dS = (k1k2 + r * ksum + r * r) * sin(th) * w[i] * w[j] * (M_PI / 4) * (M_PI / 4) * 8;
            double X = a * a * nx / h + r * nx, Y = b * b * ny / h + r * ny, Z = c * c * nz / h + r * nz;
            V += (h + r) * dS / 3;
            J[0] += (h + r) * X * X * dS / 5;
            J[1] += (h + r) * Y * Y * dS / 5;
            J[2] += (h + r) * Z * Z * dS / 5;
        }
    }
    free(x);
    free(w);
    *vol = V;
    in[0] = J[1] + J[2];
    in[1] = J[0] + J[2];
    in[2] = J[0] + J[1];
}

/* ---- rounded polyhedra by ray casting -------------------------------------- */

/* closest point of triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5) */
static sd_vec3 closest_on_triangle(sd_vec3 p, sd_vec3 a, sd_vec3 b, sd_vec3 c)
{
    sd_vec3 ab = sd_v3_sub(b, a), ac = sd_v3_sub(c, a), ap = sd_v3_sub(p, a);
    double d1 = sd_v3_dot(ab, ap), d2 = sd_v3_dot(ac, ap);
    if (d1 <= 0 && d2 <= 0)
        return a;
    sd_vec3 bp = sd_v3_sub(p, b);
    double d3 = sd_v3_dot(ab, bp), d4 = sd_v3_dot(ac, bp);
    if (d3 >= 0 && d4 <= d3)
        return b;
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
        return sd_v3_madd(a, d1 / (d1 - d3), ab);
    sd_vec3 cp = sd_v3_sub(p, c);
    double d5 = sd_v3_dot(ab, cp), d6 = sd_v3_dot(ac, cp);
    if (d6 >= 0 && d5 <= d6)
        return c;
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
        return sd_v3_madd(a, d2 / (d2 - d6), ac);
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return sd_v3_madd(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), sd_v3_sub(c, b));
    double den = 1 / (va + vb + vc);
    return sd_v3_add(a, sd_v3_add(sd_v3_scale(ab, vb * den), sd_v3_scale(ac, vc * den)));
}

/* ∫ over the body {x : dist(x, P) <= r} of 1 and x xᵀ, P the closed
 * triangle surface tris (centred at the origin, star-shaped from it):
 * ∫ = ∫_S² ρ(ω)^5/5 ω ωᵀ dΩ with ρ the radial function found by bisection.
 * ρ is only C¹ (its curvature jumps where faces meet edge cylinders), so a
 * product Gauss rule converges like n^-3, not exponentially: n = 96 is off
 * by up to 8e-6, n = 192 by up to 5e-7 relative (toward the library's value). */
static void rounded_by_rays(const sd_vec3 (*tris)[3], int nt, double r, double rmax, int n, double *vol, double J[3][3])
{
    double *x = malloc(sizeof(double) * (size_t)n), *w = malloc(sizeof(double) * (size_t)n);
    double *xp = malloc(sizeof(double) * (size_t)(2 * n)), *wp = malloc(sizeof(double) * (size_t)(2 * n));
    gl_nodes(n, x, w);
    gl_nodes(2 * n, xp, wp);
    *vol = 0;
    memset(J, 0, 9 * sizeof(double));
    for (int i = 0; i < n; ++i) {
        double ct = x[i], st = sqrt(1 - ct * ct);
        for (int j = 0; j < 2 * n; ++j) {
            double ph = M_PI * (xp[j] + 1);
            double om[3] = {st * cos(ph), st * sin(ph), ct};
            double lo = 0, hi = rmax;
            for (int it = 0; it < 55; ++it) {
                double t = 0.5 * (lo + hi), dmin = 1e300;
                sd_vec3 p = sd_v3(t * om[0], t * om[1], t * om[2]);
                /* outside the polyhedron: the distance to its surface */
                int inside = 1;
                for (int k = 0; k < nt; ++k) {
                    sd_vec3 nrm = sd_v3_cross(sd_v3_sub(tris[k][1], tris[k][0]), sd_v3_sub(tris[k][2], tris[k][0]));
                    if (sd_v3_dot(nrm, sd_v3_sub(p, tris[k][0])) > 0)
                        inside = 0;
                    sd_vec3 q = closest_on_triangle(p, tris[k][0], tris[k][1], tris[k][2]);
                    dmin = fmin(dmin, sd_v3_norm(sd_v3_sub(p, q)));
                }
                if (inside || dmin <= r)
                    lo = t;
                else
                    hi = t;
            }
            double rho = 0.5 * (lo + hi), wt = w[i] * wp[j] * M_PI;
            *vol += wt * pow(rho, 3) / 3;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    J[a][b] += wt * pow(rho, 5) / 5 * om[a] * om[b];
        }
    }
    free(x);
    free(w);
    free(xp);
    free(wp);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int main(void)
{
    gl_nodes(NGL, glx, glw);
    char label[160];

    /* ---- sharp shapes: closed forms ---- */
    {
        sd_shape s = make(def_of(SD_SHAPE_SPHERE, 0.3, 0, 0));
        double V = 4.0 / 3 * M_PI * 0.027, I = 0.4 * V * 0.09;
        check_mass("sphere R=0.3", s, V, I, I, I, 1e-14);
        CHECK_REL("sphere: bound", s.bound, 0.3, 1e-15);
    }
    {
        sd_shape s = make(def_of(SD_SHAPE_BOX, 1, 2, 3));
        check_mass("box 1x2x3", s, 6, 6 * 13 / 12.0, 6 * 10 / 12.0, 6 * 5 / 12.0, 1e-14);
        CHECK_REL("box: bound", s.bound, sqrt(14) / 2, 1e-15);
        CHECK_REL("box: min size", s.min_size, 1, 1e-15);
    }
    {
        double R = 0.4, L = 1.7;
        sd_shape s = make(def_of(SD_SHAPE_CYLINDER, 2 * R, 0, L));
        double V = M_PI * R * R * L;
        check_mass("cylinder R=0.4 L=1.7", s, V, V * (3 * R * R + L * L) / 12, V * (3 * R * R + L * L) / 12,
                   V * R * R / 2, 1e-14);
    }
    {
        double R = 0.5, h = 1.3;
        sd_shape s = make(def_of(SD_SHAPE_CONE, 2 * R, 0, h));
        double V = M_PI * R * R * h / 3, Ix = V * (3 * R * R / 20 + 3 * h * h / 80);
        check_mass("cone R=0.5 h=1.3", s, V, Ix, Ix, 0.3 * V * R * R, 1e-14);
        CHECK_NEAR("cone: base centre at -h/4", s.offset.z, -h / 4, 1e-15);
        CHECK_NEAR("cone: centre of mass h/4 above the base", s.given_com.z, h / 4, 1e-15);
        CHECK_REL("cone: bound (apex)", s.bound, 0.75 * h, 1e-15);
    }
    {
        double a = 0.3, b = 0.5, c = 0.9;
        sd_shape s = make(def_of(SD_SHAPE_ELLIPSOID, a, b, c));
        double V = 4.0 / 3 * M_PI * a * b * c;
        check_mass("ellipsoid 0.3,0.5,0.9", s, V, V * (b * b + c * c) / 5, V * (a * a + c * c) / 5,
                   V * (a * a + b * b) / 5, 1e-14);
    }
    /* polyhedra: a box's corners, a regular tetrahedron and octahedron */
    {
        sd_vec3 c8[8];
        for (int i = 0; i < 8; ++i)
            c8[i] = sd_v3((i & 1) ? 0.5 : -0.5, (i & 2) ? 1 : -1, (i & 4) ? 1.5 : -1.5);
        sd_shape_def d = def_of(SD_SHAPE_POLYHEDRON, 0, 0, 0);
        d.vertices = c8;
        d.vertex_count = 8;
        sd_shape s = make(d);
        check_mass("polyhedron: box 1x2x3 corners", s, 6, 2.5, 5, 6.5, 1e-14);
        CHECK_NEAR("polyhedron box: 8 hull vertices", s.vcount, 8, 0);
        CHECK_REL("polyhedron box: min width", s.min_size, 1, 1e-14);
        CHECK_REL("polyhedron box: bound", s.bound, sqrt(14) / 2, 1e-14);
        /* principal frame: the vertices are (±1.5, ±1, ±0.5) up to order */
        double worst = 0;
        for (uint32_t k = 0; k < s.vcount; ++k)
            worst =
                fmax(worst, fabs(fabs(verts[k].x) - 1.5) + fabs(fabs(verts[k].y) - 1) + fabs(fabs(verts[k].z) - 0.5));
        CHECK_NEAR("polyhedron box: vertices on the principal axes", worst, 0, 1e-14);
    }
    {
        double a = 0.7; /* edge */
        sd_vec3 t4[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
        sd_shape_def d = def_of(SD_SHAPE_POLYHEDRON, 0, 0, 0);
        d.vertices = t4;
        d.vertex_count = 4;
        d.scale = a / (2 * sqrt(2.0));
        sd_shape s = make(d);
        double V = a * a * a / (6 * sqrt(2.0)), I = V * a * a / 20;
        check_mass("regular tetrahedron a=0.7", s, V, I, I, I, 1e-13);
        CHECK_REL("tetrahedron: min width a/sqrt2 (edge-edge)", s.min_size, a / sqrt(2.0), 1e-13);
    }
    {
        double a = 1.1;
        sd_vec3 o6[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        sd_shape_def d = def_of(SD_SHAPE_POLYHEDRON, 0, 0, 0);
        d.vertices = o6;
        d.vertex_count = 6;
        d.scale = a / sqrt(2.0);
        sd_shape s = make(d);
        double V = sqrt(2.0) / 3 * a * a * a, I = V * a * a / 10;
        check_mass("regular octahedron a=1.1", s, V, I, I, I, 1e-13);
        CHECK_REL("octahedron: min width", s.min_size, 2 * a / sqrt(2.0) / sqrt(3.0), 1e-13);
    }

    /* ---- rounded shapes ---- */
    {
        sd_shape_def d = def_of(SD_SHAPE_SPHERE, 0.3, 0, 0);
        d.rounding = 0.1;
        sd_shape s = make(d);
        double V = 4.0 / 3 * M_PI * 0.064, I = 0.4 * V * 0.16;
        check_mass("sphere 0.3 rounded 0.1", s, V, I, I, I, 1e-14);
    }
    {
        double a = 0.5, b = 1, c = 1.5, r = 0.2;
        sd_shape_def d = def_of(SD_SHAPE_BOX, 2 * a, 2 * b, 2 * c);
        d.rounding = r;
        sd_shape s = make(d);
        double V, in[3];
        swept_box_slices(a, b, c, r, &V, in);
        check_mass("rounded box vs slices", s, V, in[0], in[1], in[2], 1e-13);
        CHECK_REL("rounded box: bound", s.bound, sqrt(a * a + b * b + c * c) + r, 1e-15);
        /* the same through the polyhedron path: corners, and corners plus
         * points on faces and edges (coplanar triangles, split edges) */
        sd_vec3 pts[8 + 6 * 25];
        int n = 0;
        for (int i = 0; i < 8; ++i)
            pts[n++] = sd_v3((i & 1) ? a : -a, (i & 2) ? b : -b, (i & 4) ? c : -c);
        sd_shape_def p = def_of(SD_SHAPE_POLYHEDRON, 0, 0, 0);
        p.vertices = pts;
        p.vertex_count = 8;
        p.rounding = r;
        sd_shape sp = make(p);
        check_mass("rounded box corners (polyhedron) vs slices", sp, V, in[2], in[1], in[0], 1e-13);
        for (int f = 0; f < 6; ++f)
            for (int i = 0; i < 5; ++i)
                for (int j = 0; j < 5; ++j) {
                    double u = -1 + i / 2.0, v = -1 + j / 2.0, sg = (f & 1) ? 1 : -1;
                    pts[n++] = f < 2 ? sd_v3(sg * a, u * b, v * c)
                                     : (f < 4 ? sd_v3(u * a, sg * b, v * c) : sd_v3(u * a, v * b, sg * c));
                }
        p.vertex_count = (size_t)n;
        sp = make(p);
        check_mass("rounded box crowded faces (polyhedron)", sp, V, in[2], in[1], in[0], 1e-13);
        CHECK_NEAR("rounded box crowded: 8 hull vertices stored", sp.vcount, 8, 0);
    }
    {
        double R = 0.4, H = 0.7, r = 0.15;
        sd_shape_def d = def_of(SD_SHAPE_CYLINDER, 2 * R, 0, 2 * H);
        d.rounding = r;
        sd_shape s = make(d);
        rev m = {0, 0, 0, 0};
        green_line(&m, 0, -H - r, R, -H - r);
        green_arc(&m, R, -H, r, -M_PI / 2, 0);
        green_line(&m, R + r, -H, R + r, H);
        green_arc(&m, R, H, r, 0, M_PI / 2);
        green_line(&m, R, H + r, 0, H + r);
        double V, zc, in[3];
        rev_props(&m, &V, &zc, in);
        check_mass("rounded cylinder vs Green", s, V, in[0], in[1], in[2], 1e-13);
        CHECK_NEAR("rounded cylinder: centroid", zc, 0, 1e-15);
    }
    {
        double R = 0.5, h = 1.2, r = 0.1, sl = sqrt(R * R + h * h), nr = h / sl, nz = R / sl, fn = atan2(R, h);
        sd_shape_def d = def_of(SD_SHAPE_CONE, 2 * R, 0, h);
        d.rounding = r;
        sd_shape s = make(d);
        rev m = {0, 0, 0, 0};
        green_line(&m, 0, -r, R, -r);
        green_arc(&m, R, 0, r, -M_PI / 2, fn);
        green_line(&m, R + r * nr, r * nz, r * nr, h + r * nz);
        green_arc(&m, 0, h, r, fn, M_PI / 2);
        double V, zc, in[3];
        rev_props(&m, &V, &zc, in);
        check_mass("rounded cone vs Green", s, V, in[0], in[1], in[2], 1e-13);
        CHECK_REL("rounded cone: base centre offset", s.offset.z, -zc, 1e-13);
        CHECK_REL("rounded cone: bound", s.bound, fmax(h - zc, sqrt(R * R + zc * zc)) + r, 1e-14);
    }
    {
        /* a rounded sphere-shaped ellipsoid is a sphere */
        sd_shape_def d = def_of(SD_SHAPE_ELLIPSOID, 0.4, 0.4, 0.4);
        d.rounding = 0.1;
        sd_shape s = make(d);
        double V = 4.0 / 3 * M_PI * 0.125, I = 0.4 * V * 0.25;
        check_mass("rounded ellipsoid, equal axes = sphere", s, V, I, I, I, 1e-13);
    }
    {
        /* spheroid: Green's theorem along the parallel curve of the meridian ellipse */
        double A = 1.0, C = 0.4, r = 0.1;
        sd_shape_def d = def_of(SD_SHAPE_ELLIPSOID, A, A, C);
        d.rounding = r;
        sd_shape s = make(d);
        rev m = {0, 0, 0, 0};
        const int nseg = 16;
        for (int g = 0; g < nseg; ++g)
            for (int k = 0; k < NGL; ++k) {
                /* t from π down to 0: bottom to top, counter-clockwise */
                double t = M_PI - M_PI * (g + 0.5 * (glx[k] + 1)) / nseg, dt = -M_PI / nseg;
                double gx = sin(t) / A, gz = cos(t) / C, gn = hypot(gx, gz);
                double dgx = cos(t) / A, dgz = -sin(t) / C;
                double nxr = gx / gn, nzr = gz / gn, dn = (nxr * dgx + nzr * dgz);
                double rho = A * sin(t) + r * nxr, z = C * cos(t) + r * nzr;
                double dz = (-C * sin(t) + r * (dgz - nzr * dn) / gn) * dt;
                green_point(&m, rho, z, dz, 0.5 * glw[k]);
            }
        double V, zc, in[3];
        rev_props(&m, &V, &zc, in);
        check_mass("rounded spheroid vs Green", s, V, in[0], in[1], in[2], 1e-12);
    }
    {
        double a = 0.3, b = 0.6, c = 1.0, r = 0.08;
        sd_shape_def d = def_of(SD_SHAPE_ELLIPSOID, a, b, c);
        d.rounding = r;
        sd_shape s = make(d);
        double V, in[3];
        ellipsoid_gauss_map(a, b, c, r, 400, &V, in);
        check_mass("rounded triaxial ellipsoid vs Gauss map", s, V, in[0], in[1], in[2], 1e-12);
        /* more elongated, thin rounding */
        d = def_of(SD_SHAPE_ELLIPSOID, 0.1, 0.5, 2.0);
        d.rounding = 0.01;
        s = make(d);
        ellipsoid_gauss_map(0.1, 0.5, 2.0, 0.01, 800, &V, in);
        check_mass("rounded ellipsoid 1:5:20 vs Gauss map", s, V, in[0], in[1], in[2], 1e-10);
    }
    {
        /* rounded regular tetrahedron by ray casting (isotropic: I = 2/3 ∫|x|²) */
        sd_vec3 t4[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
        double r = 0.3;
        sd_shape_def d = def_of(SD_SHAPE_POLYHEDRON, 0, 0, 0);
        d.vertices = t4;
        d.vertex_count = 4;
        d.rounding = r;
        sd_shape s = make(d);
        sd_vec3 tris[4][3] = {
            {t4[0], t4[1], t4[2]}, {t4[0], t4[3], t4[1]}, {t4[0], t4[2], t4[3]}, {t4[1], t4[3], t4[2]}};
        double V, J[3][3];
        rounded_by_rays((const sd_vec3(*)[3])tris, 4, r, sqrt(3.0) + r + 0.01, 192, &V, J);
        double I = J[0][0] + J[1][1]; /* per axis, by symmetry */
        check_mass("rounded tetrahedron vs ray casting", s, V, I, I, I, 1e-6);
        /* Steiner: V = V0 + r A0 + r² Σ L (π - dihedral)/2 + 4/3 π r³ */
        double e = 2 * sqrt(2.0), V0 = e * e * e / (6 * sqrt(2.0)), A0 = sqrt(3.0) * e * e;
        double dih = acos(1.0 / 3);
        double Vs = V0 + r * A0 + r * r * 6 * e * (M_PI - dih) / 2 + 4.0 / 3 * M_PI * r * r * r;
        CHECK_REL("rounded tetrahedron: Steiner volume", s.volume, Vs, 1e-14);
    }
    {
        sd_vec3 o6[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        double r = 0.25;
        sd_shape_def d = def_of(SD_SHAPE_POLYHEDRON, 0, 0, 0);
        d.vertices = o6;
        d.vertex_count = 6;
        d.rounding = r;
        sd_shape s = make(d);
        sd_vec3 tris[8][3];
        for (int k = 0; k < 8; ++k) {
            double sx = (k & 1) ? 1 : -1, sy = (k & 2) ? 1 : -1, sz = (k & 4) ? 1 : -1;
            sd_vec3 A = sd_v3(sx, 0, 0), B = sd_v3(0, sy, 0), C = sd_v3(0, 0, sz);
            int flip = (sx * sy * sz) < 0;
            tris[k][0] = A;
            tris[k][1] = flip ? C : B;
            tris[k][2] = flip ? B : C;
        }
        double V, J[3][3];
        rounded_by_rays((const sd_vec3(*)[3])tris, 8, r, 1 + r + 0.01, 192, &V, J);
        double I = J[0][0] + J[1][1];
        check_mass("rounded octahedron vs ray casting", s, V, I, I, I, 1e-6);
    }

    /* ---- margins: the outer size is kept ---- */
    {
        double m = 0.1;
        sd_shape_def d = def_of(SD_SHAPE_BOX, 1, 2, 3);
        d.margin = m;
        sd_shape s = make(d);
        double V, in[3];
        swept_box_slices(0.5 - m, 1 - m, 1.5 - m, m, &V, in);
        check_mass("box 1x2x3 margin 0.1", s, V, in[0], in[1], in[2], 1e-13);
        sd_vec3 sup = sd_shape_support(&s, NULL, sd_v3(1, 0, 0));
        CHECK_REL("box margin: outer half length kept", sup.x, 0.5, 1e-15);
        /* the same through the polyhedron path (dual-space shrink) */
        sd_vec3 c8[8];
        for (int i = 0; i < 8; ++i)
            c8[i] = sd_v3((i & 1) ? 0.5 : -0.5, (i & 2) ? 1 : -1, (i & 4) ? 1.5 : -1.5);
        sd_shape_def p = def_of(SD_SHAPE_POLYHEDRON, 0, 0, 0);
        p.vertices = c8;
        p.vertex_count = 8;
        p.margin = m;
        sd_shape sp = make(p);
        check_mass("polyhedron box margin 0.1", sp, V, in[2], in[1], in[0], 1e-13);
        CHECK_NEAR("polyhedron box margin: radius", sp.radius, m, 0);
    }
    {
        /* cone with a margin: same base plane and slant planes as the given cone */
        double R = 0.5, h = 1.2, m = 0.05;
        sd_shape_def d = def_of(SD_SHAPE_CONE, 2 * R, 0, h);
        d.margin = m;
        sd_shape s = make(d);
        sd_vec3 down = sd_shape_support(&s, NULL, sd_v3(0, 0, -1));
        CHECK_NEAR("cone margin: base plane kept", s.given_com.z + down.z, 0, 1e-15);
        double sl = sqrt(R * R + h * h);
        sd_vec3 n = sd_v3(h / sl, 0, R / sl);
        sd_vec3 side = sd_shape_support(&s, NULL, n);
        /* the given slant plane: n . x = n . (R, 0, 0) in the given frame */
        CHECK_NEAR("cone margin: slant plane kept", sd_v3_dot(n, side) + n.z * s.given_com.z, n.x * R, 1e-15);
        double Rc = s.a.x, hc = s.a.z;
        CHECK_REL("cone margin: core similar to the cone", Rc / hc, R / h, 1e-14);
    }
    {
        /* a regular tetrahedron shrunk by m is one whose inradius is m smaller */
        sd_vec3 t4[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
        double m = 0.1, inr = 1 / sqrt(3.0), k = (inr - m) / inr;
        sd_shape_def d = def_of(SD_SHAPE_POLYHEDRON, 0, 0, 0);
        d.vertices = t4;
        d.vertex_count = 4;
        d.margin = m;
        sd_shape s = make(d);
        sd_vec3 t4k[4];
        for (int i = 0; i < 4; ++i)
            t4k[i] = sd_v3_scale(t4[i], k);
        d.vertices = t4k;
        d.margin = 0;
        d.rounding = m;
        sd_shape s2 = make(d);
        check_mass("tetrahedron margin = shrunk tetrahedron rounded", s, s2.volume, s2.inertia.x, s2.inertia.y,
                   s2.inertia.z, 1e-13);
        CHECK_NEAR("tetrahedron margin: 4 core vertices", s.vcount, 4, 0);
    }

    /* ---- invariance: a random polyhedron in a random pose ---- */
    {
        sd_rng rng = sd_rng_seed(5);
        sd_vec3 p0[60], p1[60];
        for (int i = 0; i < 60; ++i) {
            double u = sd_rng_range(&rng, -1, 1), ph = sd_rng_range(&rng, 0, 2 * M_PI), s = sqrt(1 - u * u);
            p0[i] = sd_v3(0.9 * s * cos(ph), 0.5 * s * sin(ph), 0.3 * u);
            if (i % 3 == 0) /* some interior points */
                p0[i] = sd_v3_scale(p0[i], 0.5);
        }
        for (int rounded = 0; rounded < 2; ++rounded) {
            sd_quat q = sd_quat_normalize(sd_quat_make(0.2, 0.9, -0.4, 0.3));
            sd_vec3 tr = sd_v3(3.5, -7.25, 12.0);
            for (int i = 0; i < 60; ++i)
                p1[i] = sd_v3_add(sd_quat_rotate(q, p0[i]), tr);
            sd_shape_def d = def_of(SD_SHAPE_POLYHEDRON, 0, 0, 0);
            d.vertices = p0;
            d.vertex_count = 60;
            d.rounding = rounded ? 0.05 : 0;
            sd_shape s0 = make(d);
            sd_vec3 v0[60];
            memcpy(v0, verts, s0.vcount * sizeof *v0);
            d.vertices = p1;
            sd_shape s1 = make(d);
            const char *tag = rounded ? "rounded random polyhedron" : "random polyhedron";
            snprintf(label, sizeof label, "%s posed: volume", tag);
            CHECK_REL(label, s1.volume, s0.volume, 1e-13);
            double m0[3] = {s0.inertia.x, s0.inertia.y, s0.inertia.z},
                   m1[3] = {s1.inertia.x, s1.inertia.y, s1.inertia.z};
            qsort(m0, 3, sizeof(double), cmp_double);
            qsort(m1, 3, sizeof(double), cmp_double);
            for (int k = 0; k < 3; ++k) {
                snprintf(label, sizeof label, "%s posed: moment %d", tag, k);
                CHECK_REL(label, m1[k], m0[k], 1e-12);
            }
            snprintf(label, sizeof label, "%s posed: hull vertex count", tag);
            CHECK_NEAR(label, s1.vcount, s0.vcount, 0);
            /* same vertices in the principal frame, up to a proper flip of two axes */
            double best = 1e300;
            for (int f = 0; f < 4; ++f) {
                double sx = (f == 1 || f == 2) ? -1 : 1, sy = (f == 1 || f == 3) ? -1 : 1, sz = sx * sy;
                double worst = 0;
                for (uint32_t i = 0; i < s1.vcount; ++i) {
                    double dmin = 1e300;
                    for (uint32_t j = 0; j < s0.vcount; ++j)
                        dmin = fmin(dmin, sd_v3_norm(sd_v3_sub(sd_v3(sx * verts[i].x, sy * verts[i].y, sz * verts[i].z),
                                                               v0[j])));
                    worst = fmax(worst, dmin);
                }
                best = fmin(best, worst);
            }
            snprintf(label, sizeof label, "%s posed: principal-frame vertices", tag);
            CHECK_NEAR(label, best, 0, 1e-12);
            /* the pose is recovered: given frame = given_com + given_q principal */
            double worst = 0;
            for (uint32_t i = 0; i < s1.vcount; ++i) {
                sd_vec3 g = sd_v3_add(s1.given_com, sd_quat_rotate(s1.given_q, verts[i]));
                double dmin = 1e300;
                for (int j = 0; j < 60; ++j)
                    dmin = fmin(dmin, sd_v3_norm(sd_v3_sub(g, p1[j])));
                worst = fmax(worst, dmin);
            }
            snprintf(label, sizeof label, "%s: given_com + given_q maps back to input", tag);
            CHECK_NEAR(label, worst, 0, 1e-12);
            CHECK(s1.inertia.x <= s1.inertia.y && s1.inertia.y <= s1.inertia.z);
        }
    }

    /* ---- scale ---- */
    {
        sd_shape_def d = def_of(SD_SHAPE_BOX, 1, 2, 3);
        d.rounding = 0.1;
        d.scale = 1e-3;
        sd_shape s = make(d);
        double V, in[3];
        swept_box_slices(0.5e-3, 1e-3, 1.5e-3, 1e-4, &V, in);
        check_mass("rounded box scaled 1e-3", s, V, in[0], in[1], in[2], 1e-13);
    }

    /* ---- bad input ---- */
    {
        sd_shape s;
        sd_error err;
        size_t used;
        sd_shape_def d = def_of(SD_SHAPE_BOX, 1, -2, 3);
        CHECK(sd_shape_make(&d, &s, verts, 8, &used, &err) == SD_ERR_INPUT);
        printf("  refused: %s\n", err.msg);
        d = def_of(SD_SHAPE_BOX, 1, 2, 3);
        d.rounding = 0.1;
        d.margin = 0.1;
        CHECK(sd_shape_make(&d, &s, verts, 8, &used, &err) == SD_ERR_INPUT);
        printf("  refused: %s\n", err.msg);
        d.rounding = 0;
        d.margin = 0.5;
        CHECK(sd_shape_make(&d, &s, verts, 8, &used, &err) == SD_ERR_INPUT);
        printf("  refused: %s\n", err.msg);
        d = def_of(SD_SHAPE_CONE, 1, 0, 1);
        d.margin = 0.4;
        CHECK(sd_shape_make(&d, &s, verts, 8, &used, &err) == SD_ERR_INPUT);
        printf("  refused: %s\n", err.msg);
        sd_vec3 flat[5] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.5, 0}};
        d = def_of(SD_SHAPE_POLYHEDRON, 0, 0, 0);
        d.vertices = flat;
        d.vertex_count = 5;
        CHECK(sd_shape_make(&d, &s, verts, 8, &used, &err) == SD_ERR_INPUT);
        printf("  refused: %s\n", err.msg);
        d.vertex_count = 3;
        CHECK(sd_shape_make(&d, &s, verts, 8, &used, &err) == SD_ERR_INPUT);
        d.vertex_count = SD_SHAPE_MAX_VERTICES + 1;
        CHECK(sd_shape_make(&d, &s, verts, 8, &used, &err) == SD_ERR_INPUT);
        sd_shape_def raw;
        memset(&raw, 0, sizeof raw);
        CHECK(sd_shape_make(&raw, &s, verts, 8, &used, &err) == SD_ERR_INPUT);
        d = def_of(SD_SHAPE_BOX, 1, 1, 1);
        d.scale = 0;
        CHECK(sd_shape_make(&d, &s, verts, 8, &used, &err) == SD_ERR_INPUT);
        /* out of memory while building a polyhedron is an error, not a crash */
        sd_vec3 c8[8];
        for (int i = 0; i < 8; ++i)
            c8[i] = sd_v3((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
        d = def_of(SD_SHAPE_POLYHEDRON, 0, 0, 0);
        d.vertices = c8;
        d.vertex_count = 8;
        for (long k = 1; k <= 8; ++k) {
            sd_alloc_fail_after(k);
            sd_status st = sd_shape_make(&d, &s, verts, 8, &used, &err);
            sd_alloc_fail_after(0);
            CHECK(st == SD_OK || st == SD_ERR_MEMORY);
        }
    }
    /* names */
    for (int k = 0; k < SD_SHAPE_KIND_COUNT; ++k)
        CHECK(sd_shape_kind_from_name(sd_shape_kind_name(k)) == k);
    CHECK(sd_shape_kind_from_name("dodecahedron") == -1);
    CHECK(sd_shape_kind_from_name(NULL) == -1);

    /* the report */
    {
        sd_shape_def d = def_of(SD_SHAPE_CONE, 1, 0, 2);
        d.rounding = 0.05;
        sd_shape s = make(d);
        sd_shape_print_info_density(stdout, &s, NULL, 2500);
    }
    return sd_test_summary();
}
