/* shape_weld.c — polyhedra typed with rounded coordinates, with and without
 * a margin.
 *
 * Regression for the icosahedron of examples/mixed-shapes.yaml (φ given to
 * 6 decimals, margin 0.08), which was refused: the margin shrink re-cut the
 * face planes and, where five of them meet, the slightly bent input made a
 * cluster of near-duplicate corners and sliver faces. A sweep: every
 * Platonic preset, a prism and the seed 000 cylinder (with cap centres),
 * axis-aligned and in random orientations, with each coordinate rounded to
 * 7, 6 and 5 decimals (as a user types them, body circumradius about 1.9),
 * at margins 0 to 0.3: each template must build, have the corners and faces
 * of the exact solid, and its volume and moments must match those of the
 * exact solid (same orientation and margin) to the round-off of its input.
 * Then the probe's minimal case, and a too-rounded input that must still be
 * refused with a message that says what to do.
 */
#include "test.h"

#include <string.h>

#include "core/rng.h"
#include "shape/polylib.h"
#include "shape/shape_make.h"

#define TV 512

typedef struct tpl {
    sd_shape s;
    sd_vec3 v[TV];
    sd_plane p[2 * TV];
    sd_dtri t[4 * TV];
} tpl;

/* template and faces of pts scaled by scale with margin; SD_OK or the error */
static sd_status build(tpl *T, const sd_vec3 *pts, size_t n, double scale, double margin, sd_error *err)
{
    sd_shape_def d = sd_shape_def_default();
    d.kind = SD_SHAPE_POLYHEDRON;
    d.vertices = pts;
    d.vertex_count = n;
    d.scale = scale;
    d.margin = margin;
    size_t used, np, nt;
    sd_status st = sd_shape_make(&d, &T->s, T->v, TV, &used, err);
    if (st != SD_OK)
        return st;
    T->s.vstart = 0;
    T->s.vcount = (uint32_t)used;
    return sd_shape_faces(&T->s, T->v, T->p, 2 * TV, &np, T->t, 4 * TV, &nt, err);
}

static double round_to(double x, int decimals)
{
    double f = pow(10.0, decimals);
    return round(x * f) / f;
}

typedef struct preset_case {
    sd_poly_def pd;
    const char *name;
    int corners, faces;
} preset_case;

static sd_poly_def pdef(int preset, double diameter, int sides, double length)
{
    sd_poly_def d;
    memset(&d, 0, sizeof d);
    d.preset = preset;
    d.diameter = diameter;
    d.sides = sides;
    d.length = length;
    d.seed = 1;
    return d;
}

int main(void)
{
    const double D = 3.804226; /* circumscribed diameter, as the example's icosahedron */
    const double scale = 0.00063;
    const preset_case cases[] = {
        {pdef(SD_POLY_TETRAHEDRON, D, 0, 0), "tetrahedron", 4, 4},
        {pdef(SD_POLY_CUBE, D, 0, 0), "cube", 8, 6},
        {pdef(SD_POLY_OCTAHEDRON, D, 0, 0), "octahedron", 6, 8},
        {pdef(SD_POLY_DODECAHEDRON, D, 0, 0), "dodecahedron", 20, 12},
        {pdef(SD_POLY_ICOSAHEDRON, D, 0, 0), "icosahedron", 12, 20},
        {pdef(SD_POLY_PRISM, D, 6, 2.0), "hexagonal prism", 12, 8},
        {pdef(SD_POLY_CYLINDER, D, 20, 2.5), "20-sided cylinder + cap centres", 40, 22},
    };
    const double margins[] = {0, 0.01, 0.05, 0.08, 0.1, 0.3};
    const int decimals[] = {7, 6, 5};
    static tpl T, E;
    sd_rng rng = sd_rng_seed(11);
    int built = 0, tried = 0;
    double worst_rel[3] = {0, 0, 0};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        sd_v3d vv[TV];
        size_t n;
        sd_error err;
        sd_test_require(sd_polylib_vertices(&cases[c].pd, vv, TV, &n, &err) == SD_OK, "sd_polylib_vertices", &err);
        for (int orient = 0; orient < 4; ++orient) {
            /* orientation 0: as the preset gives it; then random rotations */
            sd_quat q = sd_quat_identity();
            if (orient > 0)
                q = sd_quat_normalize(sd_quat_make(sd_rng_range(&rng, -1, 1), sd_rng_range(&rng, -1, 1),
                                                   sd_rng_range(&rng, -1, 1), sd_rng_range(&rng, -1, 1)));
            sd_vec3 exact[TV], typed[TV];
            for (size_t k = 0; k < n; ++k)
                exact[k] = sd_quat_rotate(q, sd_v3(vv[k].x, vv[k].y, vv[k].z));
            for (size_t di = 0; di < sizeof decimals / sizeof decimals[0]; ++di) {
                int dec = decimals[di];
                for (size_t k = 0; k < n; ++k)
                    typed[k] = sd_v3(round_to(exact[k].x, dec), round_to(exact[k].y, dec), round_to(exact[k].z, dec));
                for (size_t mi = 0; mi < sizeof margins / sizeof margins[0]; ++mi) {
                    double m = margins[mi];
                    ++tried;
                    sd_test_require(build(&E, exact, n, scale, m, &err) == SD_OK, "exact solid", &err);
                    sd_status st = build(&T, typed, n, scale, m, &err);
                    char label[200];
                    snprintf(label, sizeof label, "%s, orientation %d, %d decimals, margin %g", cases[c].name, orient,
                             dec, m);
                    if (st != SD_OK) {
                        printf("FAIL %s: refused: %s: %s\n", label, err.key, err.msg);
                        CHECK(st == SD_OK);
                        continue;
                    }
                    ++built;
                    /* the exact solid's counts, and the typed one's */
                    int ok_counts = (int)E.s.vcount == cases[c].corners && (int)E.s.fcount == cases[c].faces &&
                                    (int)T.s.vcount == cases[c].corners && (int)T.s.fcount == cases[c].faces;
                    if (!ok_counts)
                        printf("FAIL %s: corners %u (exact %u, expected %d), faces %u (exact %u, expected %d)\n",
                               label, T.s.vcount, E.s.vcount, cases[c].corners, T.s.fcount, E.s.fcount,
                               cases[c].faces);
                    CHECK(ok_counts);
                    /* each coordinate is off by up to 0.5e-dec of a body of
                     * circumradius 1.9: the volume and moments by a few
                     * times that, relative */
                    double tol = 20 * 0.5 * pow(10.0, -dec);
                    double ev = fabs(T.s.volume - E.s.volume) / E.s.volume;
                    double ei = 0;
                    for (int a = 0; a < 3; ++a) {
                        double ti = a == 0 ? T.s.inertia.x : (a == 1 ? T.s.inertia.y : T.s.inertia.z);
                        double xi = a == 0 ? E.s.inertia.x : (a == 1 ? E.s.inertia.y : E.s.inertia.z);
                        ei = fmax(ei, fabs(ti - xi) / xi);
                    }
                    worst_rel[di] = fmax(worst_rel[di], fmax(ev, ei));
                    if (!(ev <= tol && ei <= tol))
                        printf("FAIL %s: volume off by %.3g, moments by %.3g relative (tol %.3g)\n", label, ev, ei,
                               tol);
                    CHECK(ev <= tol && ei <= tol);
                }
            }
        }
    }
    printf("-- sweep: %d of %d rounded templates built with the exact solid's corners and faces\n", built, tried);
    for (size_t di = 0; di < sizeof decimals / sizeof decimals[0]; ++di)
        CHECK_NEAR("  worst relative volume/moment error vs exact", worst_rel[di], 0,
                   20 * 0.5 * pow(10.0, -decimals[di]));

    /* the probe's minimal case: φ to 6 decimals, scale 0.00063, every margin */
    {
        const double p = 1.618034;
        sd_vec3 ico[12] = {{0, 1, p},  {0, 1, -p},  {0, -1, p},  {0, -1, -p}, {1, p, 0},  {1, -p, 0},
                           {-1, p, 0}, {-1, -p, 0}, {p, 0, 1},   {p, 0, -1},  {-p, 0, 1}, {-p, 0, -1}};
        for (size_t mi = 0; mi < sizeof margins / sizeof margins[0]; ++mi) {
            sd_error err;
            sd_status st = build(&T, ico, 12, scale, margins[mi], &err);
            char label[120];
            snprintf(label, sizeof label, "probe icosahedron, margin %g: corners", margins[mi]);
            if (st != SD_OK)
                printf("FAIL probe icosahedron, margin %g: %s\n", margins[mi], err.msg);
            CHECK(st == SD_OK);
            CHECK_NEAR(label, T.s.vcount, 12, 0);
            snprintf(label, sizeof label, "probe icosahedron, margin %g: faces", margins[mi]);
            CHECK_NEAR(label, T.s.fcount, 20, 0);
        }
    }

    /* near-duplicate corners typed twice (as an STL's float round-off gives
     * them): welded into one */
    {
        sd_vec3 cube[16];
        for (int k = 0; k < 8; ++k) {
            cube[k] = sd_v3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
            cube[8 + k] = sd_v3_add(cube[k], sd_v3(1e-9 * (k + 1), -2e-9, 3e-9));
        }
        for (int mi = 0; mi < 2; ++mi) {
            sd_error err;
            sd_status st = build(&T, cube, 16, 1.0, mi ? 0.1 : 0, &err);
            CHECK(st == SD_OK);
            CHECK_NEAR(mi ? "doubled cube corners, margin 0.1: corners" : "doubled cube corners: corners", T.s.vcount,
                       8, 0);
            CHECK_NEAR(mi ? "doubled cube corners, margin 0.1: faces" : "doubled cube corners: faces", T.s.fcount, 6,
                       0);
        }
    }
    return sd_test_summary();
}
