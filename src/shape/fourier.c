/* fourier.c — Fourier-series support functions fitted to outlines (host):
 * hull, support sampling, least squares (eq. 2), convexity test (eq. 5) and
 * coefficient reduction (§2.3), percent coverage (§3.1). See fourier.h for
 * the procedure and the invariant (a returned fit is convex). Seed 002.
 */
#include "shape/fourier.h"

#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/error.h"

sd_fourier_fit_opts sd_fourier_fit_opts_default(void)
{
    sd_fourier_fit_opts o;
    o.order = 8;
    o.directions = 720;
    o.beta = SD_R(0.9);
    o.eps = SD_R(1e-6);
    o.grid = 4096;
    return o;
}

/* ---- least squares (Householder QR) ------------------------------------------ */

sd_real sd_fourier_lstsq(const sd_real *theta, const sd_real *h, size_t m, int N, sd_real *coef)
{
    const size_t p = 2 * (size_t)N + 1;
    if (N < 0 || m < p)
        return SD_R(-1.0);
    sd_real *A = sd_malloc(m * p * sizeof *A); /* column-major: A[j * m + i] */
    sd_real *b = sd_malloc(m * sizeof *b);
    if (!A || !b) {
        sd_free(A);
        sd_free(b);
        return SD_R(-1.0);
    }
    /* columns of eq. 2: ½, cos θ, sin θ, cos 2θ, sin 2θ, ... */
    for (size_t i = 0; i < m; ++i) {
        A[i] = SD_R(0.5);
        for (int k = 1; k <= N; ++k) {
            A[(size_t)(2 * k - 1) * m + i] = sd_cos((sd_real)k * theta[i]);
            A[(size_t)(2 * k) * m + i] = sd_sin((sd_real)k * theta[i]);
        }
        b[i] = h[i];
    }
    sd_real ok = SD_R(1.0);
    for (size_t k = 0; k < p; ++k) {
        sd_real *col = A + k * m;
        sd_real norm = SD_R(0.0);
        for (size_t i = k; i < m; ++i)
            norm += col[i] * col[i];
        norm = sd_sqrt(norm);
        if (!(norm > SD_R(0.0))) {
            ok = SD_R(-1.0); /* rank deficient: directions do not determine the series */
            break;
        }
        const sd_real alpha = col[k] > SD_R(0.0) ? -norm : norm;
        /* v = x − alpha e_k, stored in place of the column below the diagonal */
        col[k] -= alpha;
        sd_real vv = SD_R(0.0);
        for (size_t i = k; i < m; ++i)
            vv += col[i] * col[i];
        for (size_t j = k + 1; j < p; ++j) {
            sd_real *cj = A + j * m, s = SD_R(0.0);
            for (size_t i = k; i < m; ++i)
                s += col[i] * cj[i];
            s = SD_R(2.0) * s / vv;
            for (size_t i = k; i < m; ++i)
                cj[i] -= s * col[i];
        }
        sd_real s = SD_R(0.0);
        for (size_t i = k; i < m; ++i)
            s += col[i] * b[i];
        s = SD_R(2.0) * s / vv;
        for (size_t i = k; i < m; ++i)
            b[i] -= s * col[i];
        col[k] = alpha; /* R's diagonal */
    }
    sd_real rms = SD_R(-1.0);
    if (ok > SD_R(0.0)) {
        for (size_t kk = p; kk-- > 0;) {
            sd_real s = b[kk];
            for (size_t j = kk + 1; j < p; ++j)
                s -= A[j * m + kk] * coef[j];
            coef[kk] = s / A[kk * m + kk];
        }
        sd_real r2 = SD_R(0.0);
        for (size_t i = p; i < m; ++i)
            r2 += b[i] * b[i];
        rms = sd_sqrt(r2 / (sd_real)m);
    }
    sd_free(A);
    sd_free(b);
    return rms;
}

/* ---- convexity and reduction ---------------------------------------------------- */

static int sd_fourier_convex(const sd_real *c, int N, int grid, sd_real *lo_out)
{
    sd_real slack;
    const sd_real lo = sd_fourier_min_curvature_radius(c, N, grid, &slack);
    if (lo_out)
        *lo_out = lo;
    return lo - slack >= SD_R(0.0);
}

int sd_fourier_reduce(sd_real *c, int N, sd_real beta, sd_real eps_rel, int grid)
{
    const sd_real eps = eps_rel * SD_R(0.5) * c[0];
    int steps = 0;
    while (!sd_fourier_convex(c, N, grid, (sd_real *)0)) {
        int sel = 0;
        for (int k = N; k >= 2 && !sel; --k)
            if (sd_sqrt(sd_sq(c[2 * k - 1]) + sd_sq(c[2 * k])) > eps)
                sel = k;
        if (!sel) { /* only negligible pairs are left: drop them (then p + p″ = a0/2 > 0) */
            for (int k = 2; k <= N; ++k)
                c[2 * k - 1] = c[2 * k] = SD_R(0.0);
            break;
        }
        c[2 * sel - 1] *= beta;
        c[2 * sel] *= beta;
        ++steps;
    }
    return steps;
}

/* ---- coverage ----------------------------------------------------------------- */

typedef struct sd_pbuf {
    sd_vec2 *p;
    size_t n, cap;
} sd_pbuf;

static int sd_pbuf_push(sd_pbuf *b, sd_vec2 v)
{
    if (b->n == b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 256;
        sd_vec2 *p = sd_realloc(b->p, cap * sizeof *p);
        if (!p)
            return 0;
        b->p = p;
        b->cap = cap;
    }
    b->p[b->n++] = v;
    return 1;
}

sd_status sd_fourier_coverage(const sd_real *coef, int N, sd_vec2 origin, const sd_vec2 *ref, size_t n,
                              sd_real *coverage, sd_real *area_fs, sd_real *area_common)
{
    const int K = 4096; /* FS polygon: inscribed, area low by ~(2π/K)²/6 relative */
    sd_vec2 *fs = sd_malloc((size_t)K * sizeof *fs);
    sd_pbuf in = {0, 0, 0}, out = {0, 0, 0};
    sd_status st = SD_OK;
    if (!fs) {
        st = SD_ERR_MEMORY;
        goto done;
    }
    const uint32_t count = 2u * (uint32_t)N + 1u;
    for (int j = 0; j < K; ++j) {
        const sd_real th = SD_R(2.0) * SD_PI * (sd_real)j / (sd_real)K;
        fs[j] = sd_v2_add(origin, sd_shape2d_support_fourier(coef, count, sd_v2(sd_cos(th), sd_sin(th))));
    }
    /* the hull of the support points: for a convex series it is the polygon
     * itself; it keeps a series that dips below eq. 5 by rounding from
     * producing a reversed edge (which would clip everything away) */
    int oom = 0;
    const size_t nfs = sd_hull2d(fs, (size_t)K, fs, &oom);
    if (oom) {
        st = SD_ERR_MEMORY;
        goto done;
    }
    const sd_real afs = nfs >= 3 ? sd_polygon2d_area(fs, nfs) : SD_R(0.0);
    sd_real aref = sd_polygon2d_area(ref, n);
    const int flip = aref < SD_R(0.0);
    aref = sd_fabs(aref);
    for (size_t i = 0; i < n; ++i)
        if (!sd_pbuf_push(&in, ref[flip ? n - 1 - i : i])) {
            st = SD_ERR_MEMORY;
            goto done;
        }
    /* Sutherland–Hodgman: the (possibly concave) reference clipped by each
     * edge of the convex FS polygon; the four standard cases (DESIGN.md) */
    for (size_t e = 0; e < nfs && in.n > 0; ++e) {
        const sd_vec2 c0 = fs[e], c1 = fs[(e + 1) % nfs];
        const sd_vec2 ce = sd_v2_sub(c1, c0);
        out.n = 0;
        for (size_t i = 0; i < in.n; ++i) {
            const sd_vec2 p = in.p[i], q = in.p[(i + 1) % in.n];
            const sd_real sp = sd_v2_cross(ce, sd_v2_sub(p, c0)), sq = sd_v2_cross(ce, sd_v2_sub(q, c0));
            const int pin = sp >= SD_R(0.0), qin = sq >= SD_R(0.0);
            int okp = 1;
            if (pin != qin) {
                const sd_real t = sp / (sp - sq);
                okp = sd_pbuf_push(&out, sd_v2_madd(p, t, sd_v2_sub(q, p)));
            }
            if (okp && qin)
                okp = sd_pbuf_push(&out, q);
            if (!okp) {
                st = SD_ERR_MEMORY;
                goto done;
            }
        }
        sd_pbuf t = in;
        in = out;
        out = t;
    }
    const sd_real acom = in.n >= 3 ? sd_fabs(sd_polygon2d_area(in.p, in.n)) : SD_R(0.0);
    if (coverage)
        *coverage = SD_R(1.0) - (afs + aref - SD_R(2.0) * acom) / aref;
    if (area_fs)
        *area_fs = afs;
    if (area_common)
        *area_common = acom;
done:
    sd_free(fs);
    sd_free(in.p);
    sd_free(out.p);
    return st;
}

/* ---- the whole fit ------------------------------------------------------------- */

sd_status sd_fourier_fit_outline(const sd_vec2 *pts, size_t n, const sd_fourier_fit_opts *opts, sd_fourier_fit *out,
                                 sd_error *err)
{
    const sd_fourier_fit_opts o = opts ? *opts : sd_fourier_fit_opts_default();
    memset(out, 0, sizeof *out);
    if (o.order < 0 || o.order > SD_SHAPE2D_MAX_ORDER)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "--order", "the order must be 0 .. %d, got %d",
                            SD_SHAPE2D_MAX_ORDER, o.order);
    if (o.directions <= 2 * o.order + 1 || o.directions > 1000000)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "--directions",
                            "need more support directions than coefficients (> %d, <= 1000000), got %d",
                            2 * o.order + 1, o.directions);
    if (!(o.beta > SD_R(0.0) && o.beta < SD_R(1.0)))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "--beta", "the reduction factor must be in (0, 1), got %g",
                            (double)o.beta);
    if (!(o.eps > SD_R(0.0) && o.eps < SD_R(1.0)) || o.grid < 64)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "bad tolerance or grid");
    if (n >= 2 && pts[n - 1].x == pts[0].x && pts[n - 1].y == pts[0].y)
        --n; /* the closing point */
    if (n < 3)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "an outline needs at least 3 points, got %zu", n);
    out->order = o.order;
    out->outline_points = n;

    sd_status st = SD_OK;
    sd_vec2 *hull = sd_malloc(n * sizeof *hull);
    const size_t M = (size_t)o.directions;
    sd_real *th = sd_malloc(M * sizeof *th), *h = sd_malloc(M * sizeof *h);
    sd_real coef[2 * SD_SHAPE2D_MAX_ORDER + 1];
    int oom = 0;
    size_t nh = hull && th && h ? sd_hull2d(pts, n, hull, &oom) : 0;
    if (!hull || !th || !h || oom) {
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory fitting an outline");
        goto done;
    }
    if (nh < 3) {
        st = sd_error_set(err, SD_ERR_INPUT, "", 0, "", "the outline's points are collinear (no area)");
        goto done;
    }
    out->hull_vertices = nh;
    out->area_hull = sd_polygon2d_area(hull, nh);
    /* the hull's area centroid: the series is fitted about it */
    sd_vec2 c = sd_v2_zero();
    for (size_t i = 0; i < nh; ++i) {
        const sd_vec2 p = hull[i], q = hull[(i + 1) % nh];
        c = sd_v2_madd(c, sd_v2_cross(p, q), sd_v2_add(p, q));
    }
    c = sd_v2_scale(c, SD_R(1.0) / (SD_R(6.0) * out->area_hull));
    out->origin = c;
    /* eq. 1: support values of the hull about c */
    for (size_t j = 0; j < M; ++j) {
        th[j] = SD_R(2.0) * SD_PI * (sd_real)j / (sd_real)M;
        const sd_vec2 d = sd_v2(sd_cos(th[j]), sd_sin(th[j]));
        sd_real best = -SD_R(1e300);
        for (size_t i = 0; i < nh; ++i)
            best = sd_max(best, sd_v2_dot(sd_v2_sub(hull[i], c), d));
        h[j] = best;
    }
    const int N = o.order;
    out->fit_rms = sd_fourier_lstsq(th, h, M, N, coef);
    if (out->fit_rms < SD_R(0.0)) {
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "least squares failed (out of memory)");
        goto done;
    }
    out->min_rho_fit = sd_fourier_min_curvature_radius(coef, N, o.grid, (sd_real *)0);
    out->reduction_steps = sd_fourier_reduce(coef, N, o.beta, o.eps, o.grid);
    out->reduced = out->reduction_steps > 0 || out->min_rho_fit < SD_R(0.0);
    out->min_rho = sd_fourier_min_curvature_radius(coef, N, o.grid, (sd_real *)0);
    out->sufficient = SD_R(0.5) * coef[0];
    out->effective_order = 0;
    for (int k = 1; k <= N; ++k) {
        const sd_real mag = sd_sqrt(sd_sq(coef[2 * k - 1]) + sd_sq(coef[2 * k]));
        out->sufficient -= ((sd_real)(k * k) - SD_R(1.0)) * mag;
        if (mag > SD_R(0.0))
            out->effective_order = k;
    }
    out->a[0] = coef[0];
    out->b[0] = SD_R(0.0);
    for (int k = 1; k <= N; ++k) {
        out->a[k] = coef[2 * k - 1];
        out->b[k] = coef[2 * k];
    }
    out->area_ref = sd_fabs(sd_polygon2d_area(pts, n));
    if (sd_fourier_coverage(coef, N, c, pts, n, &out->coverage, &out->area_fs, &out->area_common) != SD_OK) {
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory measuring the coverage");
        goto done;
    }
    out->coverage_area_ratio = SD_R(1.0) - sd_fabs(out->area_fs - out->area_ref) / out->area_ref;
done:
    sd_free(hull);
    sd_free(th);
    sd_free(h);
    return st;
}
