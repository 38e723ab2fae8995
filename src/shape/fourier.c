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
#include "shape/outline.h"

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
            A[(size_t)(2 * k - 1) * m + i] = sd_host_cos((sd_real)k * theta[i]);
            A[(size_t)(2 * k) * m + i] = sd_host_sin((sd_real)k * theta[i]);
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

/* Each β step changes one pair, so between the exact tests the grid values
 * of p + p″ are the rest of the series (fixed while the same pair is
 * reduced) plus that pair's term: O(grid) a step instead of O(grid N). The
 * sum is only a filter: when it comes within `tol` of passing, the exact
 * test (sd_fourier_convex) decides, so the steps taken are those of testing
 * exactly every time. */
typedef struct sd_reduce_grid {
    int grid, sel;
    sd_real *rest, *cs, *sn; /* rest of the series; cos, sin of sel θ_j */
} sd_reduce_grid;

static void sd_reduce_grid_select(sd_reduce_grid *g, const sd_real *c, int N, int sel)
{
    g->sel = sel;
    const sd_real kk = (sd_real)sel;
    const sd_real w = SD_R(1.0) - kk * kk;
    for (int j = 0; j < g->grid; ++j) {
        const sd_real th = SD_R(2.0) * SD_PI * (sd_real)j / (sd_real)g->grid;
        sd_real p, ddp;
        sd_fourier_eval(c, N, sd_host_cos(th), sd_host_sin(th), &p, (sd_real *)0, &ddp);
        g->cs[j] = sd_host_cos(kk * th);
        g->sn[j] = sd_host_sin(kk * th);
        g->rest[j] = p + ddp - w * (c[2 * sel - 1] * g->cs[j] + c[2 * sel] * g->sn[j]);
    }
}

/* could the series pass the exact test? (the filtered minimum minus the Taylor slack) */
static int sd_reduce_grid_maybe(const sd_reduce_grid *g, const sd_real *c, int N)
{
    const sd_real kk = (sd_real)g->sel, w = SD_R(1.0) - kk * kk;
    const sd_real a = w * c[2 * g->sel - 1], b = w * c[2 * g->sel];
    sd_real lo = SD_R(1e300);
    for (int j = 0; j < g->grid; ++j)
        lo = sd_min(lo, g->rest[j] + a * g->cs[j] + b * g->sn[j]);
    sd_real m2 = SD_R(0.0), size = SD_R(0.5) * sd_fabs(c[0]);
    for (int i = 2; i <= N; ++i) {
        const sd_real ii = (sd_real)i, mag = sd_sqrt(sd_sq(c[2 * i - 1]) + sd_sq(c[2 * i]));
        m2 += ii * ii * (ii * ii - SD_R(1.0)) * mag;
        size += ii * ii * mag;
    }
    const sd_real dth = SD_R(2.0) * SD_PI / (sd_real)g->grid;
    /* rounding of either sum is ~N 1e-16 of `size`; 1e-9 of it is ample */
    return lo - m2 * dth * dth / SD_R(8.0) >= SD_R(-1e-9) * size;
}

int sd_fourier_reduce(sd_real *c, int N, sd_real beta, sd_real eps_rel, int grid)
{
    const sd_real eps = eps_rel * SD_R(0.5) * c[0];
    int steps = 0;
    sd_reduce_grid g = {grid, 0, NULL, NULL, NULL};
    if (grid > 0) {
        g.rest = sd_malloc((size_t)grid * sizeof *g.rest);
        g.cs = sd_malloc((size_t)grid * sizeof *g.cs);
        g.sn = sd_malloc((size_t)grid * sizeof *g.sn);
    }
    const int fast = g.rest && g.cs && g.sn; /* else: the exact test every step (slower, same result) */
    for (;;) {
        if (g.sel == 0 || !fast || sd_reduce_grid_maybe(&g, c, N))
            if (sd_fourier_convex(c, N, grid, (sd_real *)0))
                break;
        if (steps >= SD_FOURIER_REDUCE_MAX_STEPS || !(beta > SD_R(0.0) && beta < SD_R(1.0))) {
            /* a β this close to 1 would take ~ln(1/ε)/(1 − β) steps per
             * pair: stop, as when only negligible pairs are left */
            for (int k = 2; k <= N; ++k)
                c[2 * k - 1] = c[2 * k] = SD_R(0.0);
            break;
        }
        int sel = 0;
        for (int k = N; k >= 2 && !sel; --k)
            if (sd_sqrt(sd_sq(c[2 * k - 1]) + sd_sq(c[2 * k])) > eps)
                sel = k;
        if (!sel) { /* only negligible pairs are left: drop them (then p + p″ = a0/2 > 0) */
            for (int k = 2; k <= N; ++k)
                c[2 * k - 1] = c[2 * k] = SD_R(0.0);
            break;
        }
        if (fast && sel != g.sel)
            sd_reduce_grid_select(&g, c, N, sel);
        c[2 * sel - 1] *= beta;
        c[2 * sel] *= beta;
        ++steps;
    }
    sd_free(g.rest);
    sd_free(g.cs);
    sd_free(g.sn);
    return steps;
}

/* ---- coverage ----------------------------------------------------------------- */

/* Area of C ∩ R for a convex polygon C (w[0 .. K), counter-clockwise about
 * the origin, which lies inside it, starting at its smallest polar angle:
 * ang[j] = atan2 of w[j], increasing) and a simple polygon R (r[0 .. n),
 * relative to the same origin), signed as R's orientation.
 *
 * R's area is the signed sum of the triangles (0, r_i, r_i+1), and the
 * signed count of those triangles over a point is R's winding number
 * there, so area(C ∩ R) = Σ ± area(C ∩ triangle). C is star-shaped about
 * the origin, so inside the wedge of one triangle C ∩ triangle is the region
 * under min(radius of the segment, radius of C): a fan whose outer boundary
 * follows C's edges inside the wedge and the segment wherever the segment
 * is nearer. Each triangle costs a binary search for its first C edge plus
 * the C vertices inside its wedge, so a star-shaped outline costs
 * O(n log K + K), not the O(nK) of clipping R by every edge of C. */
static sd_real sd_convex_cap_area(const sd_vec2 *w, const sd_real *ang, size_t K, const sd_vec2 *r, size_t n)
{
    sd_real sum = SD_R(0.0);
    for (size_t i = 0; i < n; ++i) {
        sd_vec2 A = r[i], B = r[(i + 1) % n];
        const sd_real cr = sd_v2_cross(A, B);
        if (cr == SD_R(0.0))
            continue; /* a triangle with no area */
        sd_real sign = SD_R(1.0);
        if (cr < SD_R(0.0)) { /* a clockwise wedge: the same region counted negative */
            const sd_vec2 t = A;
            A = B;
            B = t;
            sign = SD_R(-1.0);
        }
        /* the C edge j (w[j] → w[j+1]) the ray through A leaves C by */
        const sd_real phi = sd_host_atan2(A.y, A.x);
        size_t j;
        if (phi < ang[0] || phi >= ang[K - 1]) {
            j = K - 1;
        } else {
            size_t lo = 0, hi = K - 1; /* ang[lo] <= phi < ang[hi] */
            while (hi - lo > 1) {
                const size_t mid = lo + (hi - lo) / 2;
                if (ang[mid] <= phi)
                    lo = mid;
                else
                    hi = mid;
            }
            j = lo;
        }
        /* atan2 and the cross product may disagree by rounding next to a
         * vertex: settle on the edge the cross products say (a few steps) */
        for (size_t g = 0; g < K && sd_v2_cross(w[j], A) < SD_R(0.0); ++g)
            j = (j + K - 1) % K;
        for (size_t g = 0; g < K && sd_v2_cross(A, w[(j + 1) % K]) < SD_R(0.0); ++g)
            j = (j + 1) % K;
        const sd_vec2 ab = sd_v2_sub(B, A);
        const sd_real cab = sd_v2_cross(A, ab); /* = cross(A, B) > 0 */
        /* P's radial partner on the segment, and P's side of it (>= 0: P is nearer) */
#define SD_SEG_AT(P) sd_v2_scale((P), cab / sd_v2_cross((P), ab))
#define SD_SIDE(P) sd_v2_cross(ab, sd_v2_sub((P), A))
        sd_vec2 e = sd_v2_sub(w[(j + 1) % K], w[j]);
        sd_vec2 P = sd_v2_scale(A, sd_v2_cross(w[j], e) / sd_v2_cross(A, e)), SP = A;
        sd_real sP = SD_SIDE(P);
        sd_real tri = SD_R(0.0);
        for (size_t g = 0; g <= K; ++g) {
            const sd_vec2 wn = w[(j + 1) % K];
            sd_vec2 Q, SQ;
            const int last = !(sd_v2_cross(wn, B) > SD_R(0.0)) || g == K;
            if (last) { /* B leaves C by this edge */
                Q = sd_v2_scale(B, sd_v2_cross(w[j], e) / sd_v2_cross(B, e));
                SQ = B;
            } else {
                Q = wn;
                SQ = SD_SEG_AT(Q);
            }
            const sd_real sQ = SD_SIDE(Q);
            if (sP >= SD_R(0.0) && sQ >= SD_R(0.0)) {
                tri += sd_v2_cross(P, Q); /* C's edge is the nearer */
            } else if (sP <= SD_R(0.0) && sQ <= SD_R(0.0)) {
                tri += sd_v2_cross(SP, SQ); /* the segment is */
            } else { /* they cross at X, on both lines */
                const sd_vec2 X = sd_v2_madd(P, sP / (sP - sQ), sd_v2_sub(Q, P));
                tri += sP > SD_R(0.0) ? sd_v2_cross(P, X) + sd_v2_cross(X, SQ) : sd_v2_cross(SP, X) + sd_v2_cross(X, Q);
            }
            if (last)
                break;
            j = (j + 1) % K;
            e = sd_v2_sub(w[(j + 1) % K], w[j]);
            P = Q;
            SP = SQ;
            sP = sQ;
        }
#undef SD_SEG_AT
#undef SD_SIDE
        sum += sign * SD_R(0.5) * tri;
    }
    return sum;
}

sd_status sd_fourier_coverage(const sd_real *coef, int N, sd_vec2 origin, const sd_vec2 *ref, size_t n,
                              sd_real *coverage, sd_real *area_fs, sd_real *area_common)
{
    const size_t K = 4096; /* FS polygon: inscribed, area low by ~(2π/K)²/6 relative */
    sd_vec2 *fs = sd_malloc(K * sizeof *fs);
    sd_vec2 *w = sd_malloc(K * sizeof *w);
    sd_real *ang = sd_malloc(K * sizeof *ang);
    sd_vec2 *r = sd_malloc((n ? n : 1) * sizeof *r);
    sd_status st = SD_OK;
    if (!fs || !w || !ang || !r) {
        st = SD_ERR_MEMORY;
        goto done;
    }
    const uint32_t count = 2u * (uint32_t)N + 1u;
    for (size_t j = 0; j < K; ++j) {
        const sd_real th = SD_R(2.0) * SD_PI * (sd_real)j / (sd_real)K;
        fs[j] = sd_shape2d_support_fourier(coef, count, sd_v2(sd_host_cos(th), sd_host_sin(th))); /* about origin */
    }
    /* the hull of the support points: for a convex series it is the polygon
     * itself; it keeps a series that dips below eq. 5 by rounding from
     * producing a reversed edge */
    int oom = 0;
    const size_t nfs = sd_hull2d(fs, K, fs, &oom);
    if (oom) {
        st = SD_ERR_MEMORY;
        goto done;
    }
    const sd_real afs = nfs >= 3 ? sd_polygon2d_area(fs, nfs) : SD_R(0.0);
    const sd_real aref_signed = sd_polygon2d_area(ref, n);
    const sd_real aref = sd_fabs(aref_signed);
    sd_real acom = SD_R(0.0);
    if (nfs >= 3 && aref > SD_R(0.0)) {
        /* the fan centre: the FS polygon's centroid (inside it, as it is
         * convex), from its first vertex so that it keeps its digits */
        sd_vec2 c = sd_v2_zero();
        for (size_t j = 1; j + 1 < nfs; ++j) {
            const sd_vec2 p = sd_v2_sub(fs[j], fs[0]), q = sd_v2_sub(fs[j + 1], fs[0]);
            c = sd_v2_madd(c, sd_v2_cross(p, q), sd_v2_add(p, q));
        }
        c = sd_v2_add(fs[0], sd_v2_scale(c, SD_R(1.0) / (SD_R(6.0) * afs)));
        size_t j0 = 0;
        for (size_t j = 0; j < nfs; ++j) {
            w[j] = sd_v2_sub(fs[j], c);
            ang[j] = sd_host_atan2(w[j].y, w[j].x);
            if (ang[j] < ang[j0])
                j0 = j;
        }
        /* start at the smallest angle, so that the angles increase */
        for (size_t j = 0; j < nfs; ++j) {
            fs[j] = w[(j0 + j) % nfs];
            ang[j] = sd_host_atan2(fs[j].y, fs[j].x);
        }
        for (size_t i = 0; i < n; ++i)
            r[i] = sd_v2_sub(sd_v2_sub(ref[i], origin), c);
        acom = sd_convex_cap_area(fs, ang, nfs, r, n);
        if (aref_signed < SD_R(0.0))
            acom = -acom;
        /* the intersection is no larger than either area: rounding must not make it so */
        acom = sd_max(SD_R(0.0), sd_min(acom, sd_min(afs, aref)));
    }
    if (coverage) /* in [0, 1] by construction: 1 − |F △ R|/|R|, floored at 0 */
        *coverage = aref > SD_R(0.0) ? sd_max(SD_R(0.0), SD_R(1.0) - (afs + aref - SD_R(2.0) * acom) / aref)
                                     : SD_R(0.0);
    if (area_fs)
        *area_fs = afs;
    if (area_common)
        *area_common = acom;
done:
    sd_free(fs);
    sd_free(w);
    sd_free(ang);
    sd_free(r);
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
    if (!(o.beta > SD_R(0.0) && o.beta <= SD_FOURIER_BETA_MAX))
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "--beta",
                            "the reduction factor must be in (0, %g] (each step multiplies a pair by beta, so a "
                            "beta near 1 takes about 14 / (1 - beta) steps per pair), got %.17g",
                            (double)SD_FOURIER_BETA_MAX, (double)o.beta);
    if (!(o.eps > SD_R(0.0) && o.eps < SD_R(1.0)) || o.grid < 64)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "bad tolerance or grid");
    if (n >= 2 && pts[n - 1].x == pts[0].x && pts[n - 1].y == pts[0].y)
        --n; /* the closing point */
    if (n < 3)
        return sd_error_set(err, SD_ERR_INPUT, "", 0, "", "an outline needs at least 3 points, got %zu", n);
    /* an outline the coverage can be measured against: finite, a sane
     * span, a simple closed curve, not flat (probe F2, F9) */
    sd_status cst = sd_outline_check(pts, n, err);
    if (cst != SD_OK)
        return cst;
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
    out->area_ref = sd_fabs(sd_polygon2d_area(pts, n));
    /* a simple outline whose area is a sliver of its hull's (a zigzag that
     * almost retraces itself) has nothing a convex fit could cover */
    if (!(out->area_ref > SD_FOURIER_MIN_HULL_FRACTION * out->area_hull)) {
        st = sd_error_set(err, SD_ERR_INPUT, "", 0, "",
                          "the outline encloses %g m^2, only %.3g of its convex hull's %g m^2: it is not the "
                          "outline of a particle",
                          (double)out->area_ref, (double)(out->area_ref / out->area_hull), (double)out->area_hull);
        goto done;
    }
    /* the hull's area centroid: the series is fitted about it. Summed
     * from the first hull vertex: from the origin, a 2 cm circle at
     * (1e5, 1e5) m came out 60 m off */
    sd_vec2 c = sd_v2_zero();
    for (size_t i = 1; i + 1 < nh; ++i) {
        const sd_vec2 p = sd_v2_sub(hull[i], hull[0]), q = sd_v2_sub(hull[i + 1], hull[0]);
        c = sd_v2_madd(c, sd_v2_cross(p, q), sd_v2_add(p, q));
    }
    c = sd_v2_add(hull[0], sd_v2_scale(c, SD_R(1.0) / (SD_R(6.0) * out->area_hull)));
    out->origin = c;
    /* eq. 1: support values of the hull about c. The maximising vertex of
     * a convex polygon turns with the direction, so one walk round the
     * hull serves all M directions: O(M + n), not O(M n) (a 10^6-vertex
     * hull took seconds). */
    size_t iv = 0;
    for (size_t j = 0; j < M; ++j) {
        th[j] = SD_R(2.0) * SD_PI * (sd_real)j / (sd_real)M;
        const sd_vec2 d = sd_v2(sd_host_cos(th[j]), sd_host_sin(th[j]));
        sd_real best = sd_v2_dot(sd_v2_sub(hull[iv], c), d);
        if (j == 0) { /* the first direction by a scan */
            for (size_t i = 1; i < nh; ++i) {
                const sd_real e = sd_v2_dot(sd_v2_sub(hull[i], c), d);
                if (e > best) {
                    best = e;
                    iv = i;
                }
            }
        }
        for (size_t g = 0; g < nh; ++g) { /* then forward while it rises */
            const size_t nx = (iv + 1) % nh;
            const sd_real e = sd_v2_dot(sd_v2_sub(hull[nx], c), d);
            if (!(e > best))
                break;
            best = e;
            iv = nx;
        }
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
    for (int k = 0; k < 2 * N + 1; ++k)
        if (!isfinite(coef[k])) {
            st = sd_error_set(err, SD_ERR_INTERNAL, "", 0, "", "the least-squares fit gave a non-finite coefficient");
            goto done;
        }
    if (sd_fourier_coverage(coef, N, c, pts, n, &out->coverage, &out->area_fs, &out->area_common) != SD_OK) {
        st = sd_error_set(err, SD_ERR_MEMORY, "", 0, "", "out of memory measuring the coverage");
        goto done;
    }
    out->area_sym_diff = out->area_fs + out->area_ref - SD_R(2.0) * out->area_common;
    out->coverage_area_ratio = sd_max(SD_R(0.0), SD_R(1.0) - sd_fabs(out->area_fs - out->area_ref) / out->area_ref);
done:
    sd_free(hull);
    sd_free(th);
    sd_free(h);
    return st;
}
