/* fit_fourier.c — `shapedem shape fit-fourier OUTLINE.csv [--order N]
 * [--directions M] [--beta B]`: fits a Fourier-series support function to a
 * closed outline (seed 002 §2.3) and prints the coefficients, the convexity
 * test and reduction (eqs. 5–7), the percent coverage (§3.1) and a shape
 * entry to paste into a 2D scene (keys fourier_a, fourier_b).
 *
 * Invariant: bad input (a missing file, a bad row, a bad option) is one line
 * on stderr naming the file and line or the option, exit status 2, and
 * nothing on stdout.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <shapedem/shapedem.h>

#include "cli/commands.h"
#include "core/alloc.h"
#include "shape/fourier.h"
#include "shape/outline.h"

/* The usage: on stdout for --help (0), else on stderr (2). */
static int sd_fit_usage(FILE *f)
{
    fprintf(f,
            "usage: shapedem shape fit-fourier OUTLINE.csv [--order N] [--directions M] [--beta B]\n"
            "  OUTLINE.csv  closed outline, one 'x,y' point (m) per line ('#' comments, optional header)\n"
            "  --order N       Fourier order, 0..%d (default 8)\n"
            "  --directions M  support directions sampled (default 720)\n"
            "  --beta B        coefficient-reduction factor in (0, %g] (default 0.9)\n",
            SD_SHAPE2D_MAX_ORDER, (double)SD_FOURIER_BETA_MAX);
    return f == stdout ? 0 : 2;
}

static int sd_fit_num(const char *opt, const char *v, double *out)
{
    char *end;
    errno = 0;
    double x = strtod(v, &end);
    if (end == v || *end != '\0' || errno) {
        fprintf(stderr, "shapedem: %s: expected a number, got '%s'\n", opt, v);
        return 2;
    }
    *out = x;
    return 0;
}

static int sd_fit_int(const char *opt, const char *v, int *out)
{
    char *end;
    errno = 0;
    long x = strtol(v, &end, 10);
    if (end == v || *end != '\0' || errno || x < -1000000000L || x > 1000000000L) {
        fprintf(stderr, "shapedem: %s: expected an integer, got '%s'\n", opt, v);
        return 2;
    }
    *out = (int)x;
    return 0;
}

int sd_cmd_fit_fourier(int argc, char **argv)
{
    for (int k = 3; k < argc; ++k)
        if (!strcmp(argv[k], "--help") || !strcmp(argv[k], "-h"))
            return sd_fit_usage(stdout);
    if (argc < 4 || argv[3][0] == '-')
        return sd_fit_usage(stderr);
    const char *path = argv[3];
    sd_fourier_fit_opts o = sd_fourier_fit_opts_default();
    for (int k = 4; k < argc; ++k) {
        const char *a = argv[k], *v = k + 1 < argc ? argv[k + 1] : NULL;
        if (!v) {
            fprintf(stderr, "shapedem: %s needs a value (see 'shapedem shape fit-fourier')\n", a);
            return 2;
        }
        ++k;
        double x;
        int rc = 0;
        if (!strcmp(a, "--order"))
            rc = sd_fit_int(a, v, &o.order);
        else if (!strcmp(a, "--directions"))
            rc = sd_fit_int(a, v, &o.directions);
        else if (!strcmp(a, "--beta")) {
            rc = sd_fit_num(a, v, &x);
            o.beta = (sd_real)x;
        } else {
            fprintf(stderr, "shapedem: unknown option '%s' (see 'shapedem shape fit-fourier')\n", a);
            return 2;
        }
        if (rc)
            return rc;
    }
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_vec2 *pts = NULL;
    size_t n = 0;
    if (sd_outline_read_csv(path, &pts, &n, &err) != SD_OK)
        return sd_cli_fail_input(&err);
    sd_fourier_fit f;
    sd_status st = sd_fourier_fit_outline(pts, n, &o, &f, &err);
    sd_free(pts);
    if (st != SD_OK) {
        if (!err.file[0] && err.key[0] == '\0') /* an outline problem: name the file */
            snprintf(err.file, sizeof err.file, "%s", path);
        return sd_cli_fail_input(&err);
    }
    const int N = f.order;
    printf("outline            %s: %zu points, convex hull of %zu vertices\n", path, f.outline_points, f.hull_vertices);
    printf("fit                order %d, %d support directions, least-squares rms %.4g m\n", N, o.directions,
           (double)f.fit_rms);
    printf("origin             (%.10g, %.10g) m: the hull's centroid; the series is about this point\n",
           (double)f.origin.x, (double)f.origin.y);
    printf("convexity (eq. 5)  min p + p'' = %.4g m as fitted, %.4g m after reduction\n", (double)f.min_rho_fit,
           (double)f.min_rho);
    if (f.reduced)
        printf("reduction          needed: %d step%s of beta = %g on the highest pairs (eps = %g a0/2); "
               "effective order %d\n",
               f.reduction_steps, f.reduction_steps == 1 ? "" : "s", (double)o.beta, (double)o.eps, f.effective_order);
    else
        printf("reduction          not needed (effective order %d)\n", f.effective_order);
    printf("eq. 7 (sufficient) a0/2 - sum (n^2 - 1) |c_n| = %.4g m%s\n", (double)f.sufficient,
           f.sufficient >= 0 ? "" : " (< 0: eq. 7 is only sufficient; eq. 5 holds)");
    printf("area               outline %.6g m^2, hull %.6g m^2, Fourier shape %.6g m^2\n", (double)f.area_ref,
           (double)f.area_hull, (double)f.area_fs);
    printf("coverage           %.3f %% (1 - area(Fourier xor outline) / area(outline)); area ratio %.3f %%\n",
           100.0 * (double)f.coverage, 100.0 * (double)f.coverage_area_ratio);
    if (f.area_sym_diff > f.area_ref) /* the floor at 0 applied: say so rather than print a negative coverage */
        printf("note               the Fourier shape and the outline differ by %.6g m^2, more than the outline's "
               "area: a poor fit (a higher --order may help)\n",
               (double)f.area_sym_diff);
    printf("\n  n  %-20s %-20s\n", "a_n (m)", "b_n (m)");
    for (int k = 0; k <= N; ++k)
        printf("%3d  % -20.12g % -20.12g\n", k, (double)f.a[k], (double)f.b[k]);
    printf("\n# a 2D scene shape (simulation.dimension: 2):\n");
    printf("  - name: fitted\n    type: fourier\n    fourier_a: [");
    for (int k = 0; k <= N; ++k)
        printf("%s%.12g", k ? ", " : "", (double)f.a[k]);
    printf("]\n    fourier_b: [");
    for (int k = 1; k <= N; ++k)
        printf("%s%.12g", k > 1 ? ", " : "", (double)f.b[k]);
    printf("]\n");
    return 0;
}
