/* shape_flake.c — mass properties of flat and long swept ellipsoids
 * (flakes and needles with a margin or a rounding).
 *
 * Regression for the heap overflow in the ellipsoid quadrature (the node
 * count doubled past its buffer when a 10:1 flake had not converged by 768
 * nodes), and a check that such shapes are still integrated to round-off:
 * spheroids against Green's theorem along the parallel curve of their
 * meridian ellipse (adaptive, so the rim or tip is resolved whatever the
 * aspect ratio) and against the Steiner formula for the volume,
 * V = V0 + S r + M r² + 4/3 π r³ (S the area, M = ∫ H dA = ∫ h dΩ the
 * integrated mean curvature, both closed forms for a spheroid); triaxial
 * flakes against the divergence theorem over the Gauss map, adaptive in both
 * angles. The cases include the four inputs of the fuzzing probe that wrote
 * past the buffer.
 */
#include "test.h"
#include "test_quad.h"

#include <string.h>

#define M_PI SD_PI_D

#include "shape/shape_make.h"

/* ---- adaptive Gauss–Legendre of a vector integrand ------------------------ */

#define NV 4
typedef void (*vfun)(double t, const void *ctx, double out[NV]);

/* the 8-point Gauss–Legendre rule on [-1, 1], by Newton on P_8 */
static double g8x[8], g8w[8];

static void gl_init(void) { gl_nodes(8, g8x, g8w); }

static void gl8(vfun f, const void *ctx, double a, double b, double out[NV])
{
    double v[NV];
    for (int k = 0; k < NV; ++k)
        out[k] = 0;
    for (int i = 0; i < 8; ++i) {
        f(0.5 * (a + b) + 0.5 * (b - a) * g8x[i], ctx, v);
        for (int k = 0; k < NV; ++k)
            out[k] += 0.5 * (b - a) * g8w[i] * v[k];
    }
}

/* whole panel vs its two halves; split until they agree to tol[k] (the
 * halves' sum is then much better than tol: the difference is the error of
 * the coarser estimate) */
static void adapt(vfun f, const void *ctx, double a, double b, const double whole[NV], const double *tol, int depth,
                  double out[NV])
{
    double l[NV], r[NV], m = 0.5 * (a + b);
    gl8(f, ctx, a, m, l);
    gl8(f, ctx, m, b, r);
    int ok = 1;
    for (int k = 0; k < NV; ++k)
        ok &= fabs(l[k] + r[k] - whole[k]) <= tol[k];
    if (ok || depth >= 30) {
        for (int k = 0; k < NV; ++k)
            out[k] += l[k] + r[k];
        return;
    }
    adapt(f, ctx, a, m, l, tol, depth + 1, out);
    adapt(f, ctx, m, b, r, tol, depth + 1, out);
}

/* ∫_a^b f, each component to about rel x its size */
static void integrate(vfun f, const void *ctx, double a, double b, double rel, double out[NV])
{
    enum { np = 16 };
    double whole[np][NV], tol[NV];
    for (int k = 0; k < NV; ++k)
        tol[k] = out[k] = 0;
    for (int p = 0; p < np; ++p) {
        gl8(f, ctx, a + (b - a) * p / np, a + (b - a) * (p + 1) / np, whole[p]);
        for (int k = 0; k < NV; ++k)
            tol[k] += rel * fabs(whole[p][k]);
    }
    for (int p = 0; p < np; ++p)
        adapt(f, ctx, a + (b - a) * p / np, a + (b - a) * (p + 1) / np, whole[p], tol, 0, out);
}

/* ---- spheroid: Green's theorem on the meridian section -------------------- */

/* Semi-axes A (equatorial, ρ) and C (polar, z), swept by r. Boundary
 * (ρ, z)(t) = (A sin t, C cos t) + r n(t); ∫∫ ρ^k z^m dρ dz =
 * ∮ ρ^(k+1) z^m/(k+1) dz. Components: ∫ρ, ∫ρz², ∫ρ³, (unused). */
typedef struct {
    double A, C, r;
} spheroid;

static void green_f(double t, const void *ctx, double out[NV])
{
    const spheroid *s = ctx;
    double gx = sin(t) / s->A, gz = cos(t) / s->C, gn = hypot(gx, gz);
    double dgx = cos(t) / s->A, dgz = -sin(t) / s->C;
    double nx = gx / gn, nz = gz / gn, dn = nx * dgx + nz * dgz;
    double rho = s->A * sin(t) + s->r * nx, z = s->C * cos(t) + s->r * nz;
    double dz = -s->C * sin(t) + s->r * (dgz - nz * dn) / gn;
    /* t runs from π to 0 (counter-clockwise): the sign goes in here */
    out[0] = -rho * rho / 2 * dz;
    out[1] = -rho * rho / 2 * z * z * dz;
    out[2] = -rho * rho * rho * rho / 4 * dz;
    out[3] = 0;
}

/* V, I_axis (about the symmetry axis), I_perp */
static void spheroid_green(double A, double C, double r, double *V, double *iax, double *iperp)
{
    spheroid s = {A, C, r};
    double m[NV];
    integrate(green_f, &s, 0, M_PI, 1e-14, m);
    *V = 2 * M_PI * m[0];
    *iax = 2 * M_PI * m[2];
    *iperp = M_PI * m[2] + 2 * M_PI * m[1];
}

/* Steiner: V0 + S r + M r² + 4/3 π r³ with the spheroid's closed-form area
 * S and integrated mean curvature M = ∫_S² h dΩ, h = √(A² sin²ψ + C² cos²ψ) */
static double spheroid_steiner(double A, double C, double r)
{
    double V0 = 4.0 / 3 * M_PI * A * A * C, S, M;
    if (A > C) { /* oblate */
        double e = sqrt(1 - C * C / (A * A));
        S = 2 * M_PI * A * A + M_PI * C * C / e * log((1 + e) / (1 - e));
        M = 2 * M_PI * (C + A * asin(e) / e);
    } else { /* prolate */
        double e = sqrt(1 - A * A / (C * C)), k = sqrt(C * C - A * A);
        S = 2 * M_PI * A * A * (1 + C / (A * e) * asin(e));
        M = 2 * M_PI * (C + A * A / k * asinh(k / A));
    }
    return V0 + S * r + M * r * r + 4.0 / 3 * M_PI * r * r * r;
}

/* ---- triaxial: the Gauss map, adaptive in θ and φ ------------------------
 * X(n) = A²n/h + r n, h = |A n|, dS = (R1 R2 + r (R1 + R2) + r²) dΩ with
 * R1 R2 = a²b²c²/h⁴, R1 + R2 = tr A²/h - |A²n|²/h³; V = ⅓∮(h + r) dS,
 * ∫x x = ⅕∮(h + r) X_x² dS. Components: V, ∫x², ∫y², ∫z². */
typedef struct {
    double a, b, c, r, th;
} tri_ctx;

static void gauss_map_phi(double ph, const void *ctx, double out[NV])
{
    const tri_ctx *g = ctx;
    double nx = sin(g->th) * cos(ph), ny = sin(g->th) * sin(ph), nz = cos(g->th);
    double a = g->a, b = g->b, c = g->c, r = g->r;
    double h = sqrt(a * a * nx * nx + b * b * ny * ny + c * c * nz * nz);
    double A2n2 = pow(a, 4) * nx * nx + pow(b, 4) * ny * ny + pow(c, 4) * nz * nz;
    double k1k2 = a * a * b * b * c * c / pow(h, 4), ksum = (a * a + b * b + c * c) / h - A2n2 / (h * h * h);
    double dS = (k1k2 + r * ksum + r * r) * sin(g->th) * 8; /* 8 octants */
    double X = a * a * nx / h + r * nx, Y = b * b * ny / h + r * ny, Z = c * c * nz / h + r * nz;
    out[0] = (h + r) * dS / 3;
    out[1] = (h + r) * X * X * dS / 5;
    out[2] = (h + r) * Y * Y * dS / 5;
    out[3] = (h + r) * Z * Z * dS / 5;
}

static void gauss_map_theta(double th, const void *ctx, double out[NV])
{
    tri_ctx g = *(const tri_ctx *)ctx;
    g.th = th;
    integrate(gauss_map_phi, &g, 0, M_PI / 2, 1e-13, out);
}

static void triaxial_gauss_map(double a, double b, double c, double r, double *V, double in[3])
{
    tri_ctx g = {a, b, c, r, 0};
    double m[NV];
    integrate(gauss_map_theta, &g, 0, M_PI / 2, 1e-13, m);
    *V = m[0];
    in[0] = m[2] + m[3];
    in[1] = m[1] + m[3];
    in[2] = m[1] + m[2];
}

/* ---- the library ---------------------------------------------------------- */

static sd_shape make_ellipsoid(double x, double y, double z, double rounding, double margin)
{
    sd_shape_def d = sd_shape_def_default();
    d.kind = SD_SHAPE_ELLIPSOID;
    d.size = sd_v3(x, y, z);
    d.rounding = rounding;
    d.margin = margin;
    sd_shape s;
    sd_error err;
    size_t used = 0;
    sd_status st = sd_shape_make(&d, &s, NULL, 0, &used, &err);
    sd_test_require(st == SD_OK, "sd_shape_make", &err);
    return s;
}

static void check_spheroid(const char *label, double x, double y, double z, double rounding, double margin,
                           double tol)
{
    sd_shape s = make_ellipsoid(x, y, z, rounding, margin);
    /* the core is the given semi-axes less the margin, swept by it */
    double r = margin > 0 ? margin : rounding;
    double cx = x - margin, cy = y - margin, cz = z - margin;
    /* the symmetry axis is the one whose two partners are equal */
    int ax = cy == cz ? 0 : (cx == cz ? 1 : 2);
    double A = ax == 0 ? cy : cx, C = ax == 0 ? cx : (ax == 1 ? cy : cz);
    double V, iax, iperp;
    spheroid_green(A, C, r, &V, &iax, &iperp);
    double I[3] = {iperp, iperp, iperp};
    I[ax] = iax;
    char buf[200];
    printf("-- %s: semi-axes (%g, %g, %g) m, %s %g m\n", label, x, y, z, margin > 0 ? "margin" : "rounding", r);
    snprintf(buf, sizeof buf, "%s: volume vs Steiner", label);
    CHECK_REL(buf, s.volume, spheroid_steiner(A, C, r), tol);
    snprintf(buf, sizeof buf, "%s: volume vs Green", label);
    CHECK_REL(buf, s.volume, V, tol);
    snprintf(buf, sizeof buf, "%s: I_x vs Green", label);
    CHECK_REL(buf, s.inertia.x, I[0], tol);
    snprintf(buf, sizeof buf, "%s: I_y vs Green", label);
    CHECK_REL(buf, s.inertia.y, I[1], tol);
    snprintf(buf, sizeof buf, "%s: I_z vs Green", label);
    CHECK_REL(buf, s.inertia.z, I[2], tol);
    CHECK_REL("  bound = longest core semi-axis + r", s.bound, fmax(cx, fmax(cy, cz)) + r, 1e-15);
}

static void check_triaxial(const char *label, double x, double y, double z, double rounding, double margin,
                           double tol)
{
    sd_shape s = make_ellipsoid(x, y, z, rounding, margin);
    double r = margin > 0 ? margin : rounding;
    double V, in[3];
    triaxial_gauss_map(x - margin, y - margin, z - margin, r, &V, in);
    char buf[200];
    printf("-- %s: semi-axes (%g, %g, %g) m, %s %g m\n", label, x, y, z, margin > 0 ? "margin" : "rounding", r);
    snprintf(buf, sizeof buf, "%s: volume vs Gauss map", label);
    CHECK_REL(buf, s.volume, V, tol);
    snprintf(buf, sizeof buf, "%s: I_x vs Gauss map", label);
    CHECK_REL(buf, s.inertia.x, in[0], tol);
    snprintf(buf, sizeof buf, "%s: I_y vs Gauss map", label);
    CHECK_REL(buf, s.inertia.y, in[1], tol);
    snprintf(buf, sizeof buf, "%s: I_z vs Gauss map", label);
    CHECK_REL(buf, s.inertia.z, in[2], tol);
}

int main(void)
{
    gl_init();
    /* the probe's four inputs that overflowed the node buffer */
    check_spheroid("probe flake 10:1", 0.005, 0.005, 0.0005, 0, 1e-4, 1e-12);
    check_spheroid("probe needle 20:1", 0.02, 0.001, 0.001, 1e-5, 0, 1e-12);
    check_spheroid("probe needle 50:1", 0.05, 0.001, 0.001, 1e-4, 0, 1e-12);
    check_spheroid("probe flake 20:1", 0.02, 0.02, 0.001, 0, 5e-5, 1e-12);
    /* the same from the command line of the probe: --size 0.01,0.01,0.0001 */
    check_spheroid("probe flake 100:1", 0.01, 0.01, 0.0001, 1e-5, 0, 1e-12);
    /* far beyond: 1000:1 sheets and needles, a thin margin */
    check_spheroid("sheet 1000:1", 0.01, 0.01, 1e-5, 1e-6, 0, 1e-12);
    check_spheroid("needle 1000:1, axis z", 1e-5, 1e-5, 0.01, 0, 2e-6, 1e-12);
    check_spheroid("needle 200:1, axis y", 1e-4, 0.02, 1e-4, 1e-6, 0, 1e-12);
    /* not flat: a plain rounded spheroid still right */
    check_spheroid("round spheroid 2:1", 0.002, 0.002, 0.001, 2e-4, 0, 1e-12);
    /* triaxial flakes and needles (no symmetry axis) */
    check_triaxial("triaxial flake 15:10:1", 0.006, 0.004, 0.0004, 0, 1e-4, 1e-11);
    check_triaxial("triaxial needle 40:2:1", 0.02, 0.001, 0.0005, 1e-5, 0, 1e-11);
    return sd_test_summary();
}
