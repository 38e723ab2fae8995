/* fourier.c — the Fourier-series fit of seed 002 §2.3 and §3.1: least
 * squares (eq. 2), support points (eqs. 3–4), convexity (eq. 5) and the
 * coefficient reduction, percent coverage.
 *
 *   - least squares: equal spacing gives the discrete Fourier transform;
 *     random directions recover an exact series;
 *   - a circle and an ellipse fitted from sampled outlines reproduce the
 *     analytic support functions, and their support points lie on them;
 *   - the reduction turns a non-convex series convex, and stops where the
 *     analytic bound says (a single pair: |c_n| ≤ (a0/2)/(n² − 1));
 *   - coverage of a known pair (circle in a square: π/4);
 *   - 16 irregular outlines (rounded polygons, seeded rock-like outlines,
 *     an L-shape whose hull is taken): p + p″ ≥ 0 on a fine grid after
 *     reduction for every one, coverage at order 8 above 95 % for the
 *     convex ones, and sd_shape2d_make accepts every fit.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/rng.h"
#include "shape/fourier.h"
#include "shape/outline.h"
#include "shape/shape2d.h"
#include "test.h"

static sd_real coef_of(const sd_fourier_fit *f, sd_real *c)
{
    c[0] = f->a[0];
    for (int k = 1; k <= f->order; ++k) {
        c[2 * k - 1] = f->a[k];
        c[2 * k] = f->b[k];
    }
    return c[0];
}

static double fs_p(const sd_real *c, int N, double th)
{
    sd_real p;
    sd_fourier_eval(c, N, cos(th), sin(th), &p, NULL, NULL);
    return p;
}

/* distance from q to the closed polygon's boundary */
static double dist_to_polygon(const sd_vec2 *p, size_t n, sd_vec2 q)
{
    double best = 1e300;
    for (size_t i = 0; i < n; ++i) {
        sd_vec2 a = sd_v2_sub(p[i], q), b = sd_v2_sub(p[(i + 1) % n], q), e = sd_v2_sub(b, a);
        double e2 = sd_v2_norm2(e), t = e2 > 0 ? -sd_v2_dot(a, e) / e2 : 0;
        t = t < 0 ? 0 : (t > 1 ? 1 : t);
        double d = sd_v2_norm(sd_v2_madd(a, t, e));
        if (d < best)
            best = d;
    }
    return best;
}

static sd_vec2 outline[8192], hullbuf[8192];

int main(void)
{
    sd_rng rng = sd_rng_seed(5);
    sd_error err;

    /* ---- least squares ------------------------------------------------------ */
    {
        enum { M = 360, N = 6 };
        sd_real th[M], h[M], c[2 * N + 1];
        for (int j = 0; j < M; ++j) {
            th[j] = 2 * SD_PI_D * j / M;
            h[j] = 1.0 + 0.3 * cos(th[j]) + 0.1 * sin(3 * th[j]) + 0.05 * cos(5 * th[j]) + 0.02 * cos(11 * th[j]) +
                   0.03 * fabs(sin(th[j]));
        }
        sd_real rms = sd_fourier_lstsq(th, h, M, N, c);
        CHECK(rms >= 0);
        double worst = 0;
        for (int k = 0; k <= N; ++k) {
            double ak = 0, bk = 0;
            for (int j = 0; j < M; ++j) {
                ak += 2.0 / M * h[j] * cos(k * th[j]);
                bk += 2.0 / M * h[j] * sin(k * th[j]);
            }
            worst = fmax(worst, fabs((k ? c[2 * k - 1] : c[0]) - ak));
            if (k)
                worst = fmax(worst, fabs(c[2 * k] - bk));
        }
        CHECK_NEAR("least squares = DFT for equal spacing, worst coefficient", worst, 0, 1e-13);

        /* random directions, exact series of order 4 fitted at order 6 */
        sd_real truth[2 * N + 1] = {2.0, 0.1, -0.2, 0.05, 0.03, -0.01, 0.02, 0.004, -0.003, 0, 0, 0, 0};
        for (int j = 0; j < M; ++j) {
            th[j] = sd_rng_range(&rng, 0, 2 * SD_PI_D);
            h[j] = fs_p(truth, N, th[j]);
        }
        rms = sd_fourier_lstsq(th, h, M, N, c);
        worst = 0;
        for (int i = 0; i < 2 * N + 1; ++i)
            worst = fmax(worst, fabs(c[i] - truth[i]));
        CHECK_NEAR("least squares, random directions: worst coefficient", worst, 0, 1e-12);
        CHECK_NEAR("least squares, random directions: rms residual", rms, 0, 1e-12);
    }

    sd_fourier_fit_opts o = sd_fourier_fit_opts_default();
    sd_fourier_fit fit;
    sd_real c[2 * SD_SHAPE2D_MAX_ORDER + 1];

    /* ---- circle from a sampled outline ------------------------------------------ */
    {
        const double R = 0.03, cx = 0.11, cy = -0.2;
        const int n = 2000;
        for (int i = 0; i < n; ++i)
            outline[i] = sd_v2(cx + R * cos(2 * SD_PI_D * i / n), cy + R * sin(2 * SD_PI_D * i / n));
        sd_test_require(sd_fourier_fit_outline(outline, n, &o, &fit, &err) == SD_OK, "fit circle", &err);
        coef_of(&fit, c);
        double worst_p = 0, worst_on = 0;
        for (int j = 0; j < 3600; ++j) {
            double th = 2 * SD_PI_D * j / 3600;
            worst_p = fmax(worst_p, fabs(fs_p(c, 8, th) - R));
            sd_vec2 x = sd_shape2d_support_fourier(c, 17, sd_v2(cos(th), sin(th)));
            worst_on = fmax(worst_on, fabs(sd_v2_norm(x) - R));
        }
        /* the sampled outline is an inscribed 2000-gon: R(1 − cos(π/2000)) = 3.7e-8 m */
        CHECK_NEAR("circle fit: max |p(theta) - R| / R", worst_p / R, 0, 3e-6);
        CHECK_NEAR("circle fit: support points on the circle, max error / R", worst_on / R, 0, 3e-6);
        CHECK_NEAR("circle fit: origin x (m)", fit.origin.x, cx, 1e-9);
        CHECK_NEAR("circle fit: origin y (m)", fit.origin.y, cy, 1e-9);
        CHECK(!fit.reduced);
        CHECK_NEAR("circle fit: coverage", fit.coverage, 1.0, 1e-5);
    }

    /* ---- ellipse from a sampled outline -------------------------------------------- */
    {
        const double a = 0.04, b = 0.02, phi = 0.3, cx = -0.05, cy = 0.02;
        const int n = 4000;
        for (int i = 0; i < n; ++i) {
            double t = 2 * SD_PI_D * i / n;
            sd_vec2 q = sd_v2_rot(sd_v2(a * cos(t), b * sin(t)), phi);
            outline[i] = sd_v2(cx + q.x, cy + q.y);
        }
        sd_fourier_fit_opts o2 = o;
        o2.order = 24;
        sd_test_require(sd_fourier_fit_outline(outline, n, &o2, &fit, &err) == SD_OK, "fit ellipse", &err);
        coef_of(&fit, c);
        double worst_p = 0, worst_on = 0;
        for (int j = 0; j < 3600; ++j) {
            double th = 2 * SD_PI_D * j / 3600, u = th - phi;
            double p = sqrt(a * a * cos(u) * cos(u) + b * b * sin(u) * sin(u));
            worst_p = fmax(worst_p, fabs(fs_p(c, 24, th) - p));
            /* the support point, back in the ellipse's frame, on x²/a² + y²/b² = 1 */
            sd_vec2 x = sd_v2_rot(sd_shape2d_support_fourier(c, 49, sd_v2(cos(th), sin(th))), -phi);
            double g = sqrt(x.x * x.x / (a * a) + x.y * x.y / (b * b));
            worst_on = fmax(worst_on, fabs(g - 1));
        }
        CHECK_NEAR("ellipse fit, order 24: max |p - p_exact| / a", worst_p / a, 0, 1e-5);
        CHECK_NEAR("ellipse fit, order 24: support points on the ellipse (level-1)", worst_on, 0, 1e-4);
        CHECK(!fit.reduced);
        o2.order = 8;
        sd_test_require(sd_fourier_fit_outline(outline, n, &o2, &fit, &err) == SD_OK, "fit ellipse 8", &err);
        printf("ellipse 2:1 at order 8: coverage %.5f, reduced %d\n", fit.coverage, fit.reduced);
        CHECK(fit.coverage > 0.99);
    }

    /* ---- the reduction: a non-convex series made convex --------------------------- */
    {
        const int N = 3;
        sd_real s[7] = {2.0, 0.0, 0.0, 0.0, 0.0, 0.2, 0.0}; /* p = 1 + 0.2 cos 3θ: p + p″ = 1 − 1.6 cos 3θ */
        sd_real lo0 = sd_fourier_min_curvature_radius(s, N, 4096, NULL);
        CHECK_NEAR("non-convex input: min p + p'' (eq. 6)", lo0, 1 - 1.6, 1e-12);
        int steps = sd_fourier_reduce(s, N, 0.9, 1e-6, 4096);
        sd_real lo = sd_fourier_min_curvature_radius(s, N, 65536, NULL);
        printf("reduction: %d steps, a3 = %.6f\n", steps, s[5]);
        CHECK(steps > 0);
        CHECK(lo >= 0);
        /* convex iff 8|a3| <= 1: the last step crossed 0.125 */
        CHECK(s[5] <= 0.125 && s[5] > 0.9 * 0.125 * 0.999);
        CHECK_NEAR("reduced a0 untouched", s[0], 2.0, 0);
    }

    /* ---- coverage of a known pair: a circle inscribed in a square -------------------- */
    {
        sd_real s[1] = {2.0}; /* p = 1 */
        sd_vec2 sq[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        sd_real cov, afs, acom;
        CHECK(sd_fourier_coverage(s, 0, sd_v2(0, 0), sq, 4, &cov, &afs, &acom) == SD_OK);
        CHECK_NEAR("coverage circle in square (pi/4)", cov, SD_PI_D / 4, 2e-6);
        CHECK_NEAR("intersection area (pi)", acom, SD_PI_D, 5e-6);
        sd_vec2 sq_cw[4] = {{-1, -1}, {-1, 1}, {1, 1}, {1, -1}};
        CHECK(sd_fourier_coverage(s, 0, sd_v2(0, 0), sq_cw, 4, &cov, NULL, NULL) == SD_OK);
        CHECK_NEAR("coverage, clockwise reference", cov, SD_PI_D / 4, 2e-6);
    }

    /* ---- 16 irregular outlines ------------------------------------------------------- */
    {
        printf("\n%-28s %6s %7s %8s %6s %9s %12s %10s\n", "outline", "points", "convex", "reduced", "steps",
               "eff.order", "min p+p''", "coverage");
        int ntot = 0, nconvex = 0, all_convex_after = 1, all_made = 1, nreduced = 0;
        double worst_cov = 1, sum_cov = 0, worst_on = 0;
        int nangular = 0;
        double worst_angular = 1;
        for (int s = 0; s < 16; ++s) {
            size_t n = 0;
            char name[64];
            int angular = 0;
            if (s < 8) {
                /* rounded polygons: triangle .. octagon, some stretched, corner
                 * radius a fraction of the inradius; the last three angular */
                static const int sides_[8] = {3, 4, 5, 6, 8, 3, 4, 3};
                static const double aspect_[8] = {1.0, 1.3, 1.0, 1.0, 1.0, 1.0, 1.3, 1.6};
                static const double round_[8] = {0.7, 0.7, 0.5, 0.4, 0.3, 0.3, 0.3, 0.5};
                int sides = sides_[s];
                double inr = 0.02 * cos(SD_PI_D / sides) * fmin(aspect_[s], 1.0);
                angular = s >= 5;
                n = sd_outline_rounded_polygon(sides, 0.02, aspect_[s], 0.1 * s, round_[s] * inr, 24, 40, outline);
                snprintf(name, sizeof name, "%d-gon x%.1f, corners %.2f", sides, aspect_[s], round_[s]);
            } else if (s < 15) { /* rock-like, from smooth to rough (concave) */
                double rough = 0.03 + 0.03 * (s - 8);
                n = sd_outline_rock(1000 + (uint64_t)s, 0.025, 1.0 + 0.1 * (s % 3), rough, outline, 1500);
                snprintf(name, sizeof name, "rock seed %d rough %.2f", 1000 + s, rough);
            } else { /* an L-shape: the fit takes its hull */
                sd_vec2 L[6] = {{0, 0}, {0.04, 0}, {0.04, 0.015}, {0.015, 0.015}, {0.015, 0.05}, {0, 0.05}};
                n = sd_outline_densify(L, 6, 200, outline);
                snprintf(name, sizeof name, "L-shape");
            }
            /* convex outline: its hull keeps every point (and the same area) */
            int oom;
            size_t nh = sd_hull2d(outline, n, hullbuf, &oom);
            double ah = sd_polygon2d_area(hullbuf, nh), ao = fabs(sd_polygon2d_area(outline, n));
            int convex = ah - ao <= 1e-9 * ah;
            sd_test_require(sd_fourier_fit_outline(outline, n, &o, &fit, &err) == SD_OK, name, &err);
            coef_of(&fit, c);
            sd_real fine = sd_fourier_min_curvature_radius(c, 8, 65536, NULL);
            all_convex_after &= fine >= 0;
            nreduced += fit.reduced;
            /* sd_shape2d_make accepts the fit */
            sd_real b1[SD_SHAPE2D_MAX_ORDER];
            for (int k = 1; k <= 8; ++k)
                b1[k - 1] = fit.b[k];
            sd_shape2d_desc d = sd_shape2d_desc_default();
            d.kind = SD_SHAPE2D_FOURIER;
            d.radius = 0;
            d.order = 8;
            d.fs_a = fit.a;
            d.fs_b = b1;
            sd_shape2d sh;
            sd_real pool[17];
            size_t used;
            all_made &= sd_shape2d_make(&d, &sh, pool, 17, &used, &err) == SD_OK;
            if (convex && angular) { /* reported, not held to 95 % (see docs/shapes.md) */
                ++nangular;
                worst_angular = fmin(worst_angular, fit.coverage);
            } else if (convex) {
                ++nconvex;
                worst_cov = fmin(worst_cov, fit.coverage);
                sum_cov += fit.coverage;
                /* support points near the (convex) outline */
                for (int j = 0; j < 720; ++j) {
                    double th = 2 * SD_PI_D * j / 720;
                    sd_vec2 x = sd_v2_add(fit.origin, sd_shape2d_support_fourier(c, 17, sd_v2(cos(th), sin(th))));
                    worst_on = fmax(worst_on, dist_to_polygon(outline, n, x) / sqrt(ao / SD_PI_D));
                }
            }
            ++ntot;
            printf("%-28s %6zu %7s %8s %6d %9d %12.4g %9.3f%%\n", name, n,
                   convex ? (angular ? "angular" : "yes") : "no", fit.reduced ? "yes" : "no", fit.reduction_steps,
                   fit.effective_order, (double)fine, 100 * fit.coverage);
        }
        printf("\n");
        printf("angular polygons (corner radius 0.3-0.5 of the inradius): worst coverage %.3f; the reduction\n"
               "must cut low harmonics too and the shape swells towards the disc of equal perimeter (docs/shapes.md)\n",
               worst_angular);
        CHECK(nangular == 3);
        CHECK(ntot >= 12);
        CHECK(nconvex >= 6);
        CHECK(nreduced >= 1); /* the set exercises the reduction */
        CHECK_NEAR("p + p'' >= 0 on 65536 points after reduction, all outlines", all_convex_after, 1, 0);
        CHECK_NEAR("sd_shape2d_make accepts every fit", all_made, 1, 0);
        CHECK_NEAR("worst coverage at order 8, convex outlines (> 0.95)", worst_cov, 1.0, 0.05);
        printf("mean coverage at order 8, convex outlines: %.4f (seed 002: 95.8 %% over its 12 templates)\n",
               sum_cov / (nconvex ? nconvex : 1));
        CHECK_NEAR("support points to the convex outlines, worst / eq. radius", worst_on, 0, 0.05);
    }

    /* ---- out of memory: every allocation of the fit may fail; the fit then
     * returns SD_ERR_MEMORY (never crashes, never returns a half fit as OK) --- */
    {
        size_t n = sd_outline_rock(3, 0.02, 1.1, 0.1, outline, 400);
        int bad = 0, failures = 0;
        for (long k = 1; k <= 12; ++k) {
            sd_alloc_fail_after(k);
            sd_status st = sd_fourier_fit_outline(outline, n, &o, &fit, &err);
            sd_alloc_fail_after(0);
            failures += st == SD_ERR_MEMORY;
            bad += !(st == SD_OK || st == SD_ERR_MEMORY);
        }
        printf("out of memory: %d of 12 injected failures reported as SD_ERR_MEMORY\n", failures);
        CHECK(bad == 0 && failures >= 4);
        CHECK(sd_fourier_fit_outline(outline, n, &o, &fit, &err) == SD_OK);
    }

    /* ---- bad input ------------------------------------------------------------------- */
    {
        sd_vec2 line3[3] = {{0, 0}, {1, 1}, {2, 2}};
        CHECK(sd_fourier_fit_outline(line3, 3, &o, &fit, &err) == SD_ERR_INPUT);
        printf("collinear outline: %s\n", err.msg);
        CHECK(sd_fourier_fit_outline(line3, 2, &o, &fit, &err) == SD_ERR_INPUT);
        sd_fourier_fit_opts bad = o;
        bad.beta = 1.0;
        CHECK(sd_fourier_fit_outline(outline, 100, &bad, &fit, &err) == SD_ERR_INPUT);
        bad = o;
        bad.order = 400;
        CHECK(sd_fourier_fit_outline(outline, 100, &bad, &fit, &err) == SD_ERR_INPUT);
    }
    return sd_test_summary();
}
