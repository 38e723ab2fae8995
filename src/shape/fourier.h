/* fourier.h — fitting a Fourier-series support function to an outline
 * (host code), seed 002 §2.3 and §3.1.
 *
 * The procedure (seed 002 Fig. 3):
 *   0. the outline is checked (sd_outline_check: a simple closed curve, not
 *      flat, a span whose square stays in range; and an area of at least
 *      SD_FOURIER_MIN_HULL_FRACTION of its hull's), so that the coverage
 *      below means something;
 *   1. the outline's convex hull (a reference shape must be made convex);
 *   2. support values h_j = max_i P_i·n(θ_j) of the hull about its area
 *      centroid, for M equally spaced directions (eq. 1);
 *   3. least squares for a0, a_n, b_n of eq. 2 (Householder QR, so the
 *      directions need not be equally spaced; with equal spacing the answer
 *      is the discrete Fourier transform, which tests/unit/fourier.c checks);
 *   4. convexity, eq. 5: p + p″ ≥ 0, tested on a grid of θ with a Taylor
 *      margin that makes the sampled test a proof for every θ
 *      (sd_fourier_min_curvature_radius);
 *   5. if not convex, the coefficient reduction of §2.3: take the last pair
 *      (a_n, b_n) with sqrt(a_n² + b_n²) > ε and multiply it by β; repeat
 *      until eq. 5 holds. ε = 1e-6 · a0/2 (the seed's 1e-6, relative to the
 *      mean radius so the result does not depend on the outline's unit);
 *      pairs left below ε when eq. 5 still fails are set to zero (n = 1
 *      never matters: (n² − 1) = 0 in eq. 6);
 *   6. percent coverage (§3.1, area based): 1 − area(FS △ reference) /
 *      area(reference), the symmetric difference of the fitted shape and the
 *      ORIGINAL outline (not its hull), floored at 0 (in [0, 1] by
 *      construction); the plain area ratio 1 − |A_FS − A_ref| / A_ref is
 *      reported too.
 * Invariant: a fit returned with status SD_OK is convex (eq. 5 proved on
 * the grid with the margin), so sd_shape2d_make accepts it.
 */
#ifndef SD_SHAPE_FOURIER_H
#define SD_SHAPE_FOURIER_H

#include <stddef.h>

#include "shape/shape2d.h"

typedef struct sd_fourier_fit_opts {
    int order;      /* N, 0 .. SD_SHAPE2D_MAX_ORDER (default 8) */
    int directions; /* M support directions, > 2N + 1 (default 720: every 0.5°) */
    sd_real beta;   /* reduction factor in (0, 1) (default 0.9) */
    sd_real eps;    /* negligible-pair tolerance relative to a0/2 (default 1e-6) */
    int grid;       /* θ points for eq. 5 (default 4096) */
} sd_fourier_fit_opts;

sd_fourier_fit_opts sd_fourier_fit_opts_default(void);

/* Bounds on the reduction's work: the largest β the fit accepts (steps per
 * pair grow as ln(1/ε)/(1 − β): ~1,400 at 0.99), and a cap on the β steps
 * of sd_fourier_reduce for any β (past it the pairs n >= 2 are dropped). */
#define SD_FOURIER_BETA_MAX          SD_R(0.99)
#define SD_FOURIER_REDUCE_MAX_STEPS  200000
/* the least outline area, relative to its convex hull's, a fit accepts */
#define SD_FOURIER_MIN_HULL_FRACTION SD_R(1e-3)

typedef struct sd_fourier_fit {
    int order;                           /* N asked for */
    int effective_order;                 /* highest n with a nonzero pair after reduction */
    sd_real a[SD_SHAPE2D_MAX_ORDER + 1]; /* a_0 .. a_N of eq. 2, about `origin` */
    sd_real b[SD_SHAPE2D_MAX_ORDER + 1]; /* b_0 (always 0) .. b_N */
    sd_vec2 origin;                      /* outline-frame point the series is about (hull centroid) */
    size_t outline_points, hull_vertices;
    sd_real fit_rms;                      /* rms of p(θ_j) − h_j after least squares, m */
    sd_real min_rho_fit;                  /* min of p + p″ on the grid before reduction, m */
    sd_real min_rho;                      /* the same after reduction (≥ slack) */
    sd_real sufficient;                   /* eq. 7 left side after reduction (≥ 0: convex by eq. 7 too) */
    int reduced;                          /* 1: the reduction was needed */
    int reduction_steps;                  /* β multiplications */
    sd_real area_ref, area_hull, area_fs; /* m² */
    sd_real area_common;                  /* m², area of FS ∩ reference */
    sd_real area_sym_diff;                /* m², area(FS △ ref) */
    sd_real coverage;                     /* 1 − area(FS △ ref)/area(ref), fraction, floored at 0 */
    sd_real coverage_area_ratio;          /* 1 − |A_FS − A_ref|/A_ref, fraction, floored at 0 */
} sd_fourier_fit;

/* Fits the outline pts[0 .. n) (a closed curve, either orientation; the
 * closing point may repeat the first). SD_ERR_INPUT for too few points, an
 * outline sd_outline_check refuses (self-intersecting, flat, a span out of
 * range), one whose area is below SD_FOURIER_MIN_HULL_FRACTION of its
 * hull's, or bad options; SD_ERR_MEMORY when an allocation fails. */
sd_status sd_fourier_fit_outline(const sd_vec2 *pts, size_t n, const sd_fourier_fit_opts *opts, sd_fourier_fit *out,
                                 sd_error *err);

/* ---- the pieces (tests) --------------------------------------------------- */

/* Least squares for the 2N + 1 coefficients (interleaved a0, a1, b1, ...) of
 * eq. 2 from m samples (theta[j], h[j]), by Householder QR. Returns the rms
 * residual, or a negative value when m ≤ 2N or an allocation fails. */
sd_real sd_fourier_lstsq(const sd_real *theta, const sd_real *h, size_t m, int N, sd_real *coef);

/* The reduction of step 5 on interleaved coefficients; returns the number
 * of β steps (at most SD_FOURIER_REDUCE_MAX_STEPS) and leaves the
 * coefficients convex by the margin test. */
int sd_fourier_reduce(sd_real *coef, int N, sd_real beta, sd_real eps_rel, int grid);

/* 1 − area(F △ R)/area(R), floored at 0, for the Fourier shape
 * (interleaved coefficients, about `origin`; a 4096-gon of its support
 * points) and the closed reference polygon R (any orientation, simple, may
 * be concave); also returns the areas (may be NULL). area(F ∩ R) by a fan
 * over R's edges clipped to the convex F, O(n log 4096) for a star-shaped
 * R (fourier.c). */
sd_status sd_fourier_coverage(const sd_real *coef, int N, sd_vec2 origin, const sd_vec2 *ref, size_t n,
                              sd_real *coverage, sd_real *area_fs, sd_real *area_common);

#endif
