/* math.c — the engine's own elementary functions (core/math.h) against
 * MPFR's correctly rounded results, and against libm.
 *
 * For sin, cos, atan2, cbrt, exp and log: 0.3 to 0.9 million arguments each (uniform
 * over the ranges the numerics use, log-uniform over the whole double
 * range, doubles next to multiples of pi/2 and near the reduction's
 * thresholds, subnormals), the maximum error in ulps of the exact result
 * printed and asserted <= 1; the special values (zeros with their signs,
 * infinities, NaN, exact cubes) checked exactly. libm's own maximum error
 * and how often it differs from ours are printed as a reference, not
 * asserted (libm is not the target, the exact value is).
 */
#include "test.h"

#include "core/math.h"
#include "core/rng.h"

#include <mpfr.h>
#include <stdint.h>
#include <string.h>

typedef struct fn_stat {
    double max_ulp, max_ulp_libm, worst_arg, worst_arg2, worst_libm;
    long count, differ_libm;
} fn_stat;

static mpfr_t g_exact, g_diff, g_ulp, g_x, g_y;

/* |got - exact| in ulps of exact (the ulp of the double binade the exact
 * value falls in; 2^-1074 below the normal range); exact holds MPFR's
 * value at 160 bits. NaN results must match NaN. */
static double ulp_error(double got)
{
    if (mpfr_nan_p(g_exact))
        return got != got ? 0.0 : (double)INFINITY;
    if (got != got)
        return INFINITY;
    if (mpfr_inf_p(g_exact))
        return (isinf(got) && (got > 0) == (mpfr_sgn(g_exact) > 0)) ? 0.0 : (double)INFINITY;
    if (mpfr_zero_p(g_exact))
        return got == 0.0 ? 0.0 : (double)INFINITY;
    double rounded = mpfr_get_d(g_exact, MPFR_RNDN); /* beyond DBL_MAX: its double is inf */
    if (isinf(rounded))
        return (isinf(got) && (got > 0) == (rounded > 0)) ? 0.0 : (double)INFINITY;
    long e = mpfr_get_exp(g_exact); /* exact = f 2^e, f in [1/2, 1) */
    long ue = e - 53;
    if (ue < -1074)
        ue = -1074;
    mpfr_sub_d(g_diff, g_exact, got, MPFR_RNDN);
    mpfr_abs(g_diff, g_diff, MPFR_RNDN);
    mpfr_set_ui_2exp(g_ulp, 1, ue, MPFR_RNDN);
    mpfr_div(g_diff, g_diff, g_ulp, MPFR_RNDN);
    return mpfr_get_d(g_diff, MPFR_RNDN);
}

static int same_bits(double a, double b)
{
    uint64_t ua, ub;
    memcpy(&ua, &a, 8);
    memcpy(&ub, &b, 8);
    return ua == ub || (a != a && b != b);
}

static void record(fn_stat *s, double ours, double theirs, double x, double y)
{
    double e = ulp_error(ours), el = ulp_error(theirs);
    if (e > s->max_ulp || e != e) {
        s->max_ulp = e != e ? (double)INFINITY : e;
        s->worst_arg = x;
        s->worst_arg2 = y;
    }
    if (el > s->max_ulp_libm) {
        s->max_ulp_libm = el;
        s->worst_libm = x;
    }
    s->differ_libm += !same_bits(ours, theirs);
    s->count++;
}

enum { F_SIN, F_COS, F_ATAN2, F_CBRT, F_EXP, F_LOG, F_COUNT };
static const char *fn_name[F_COUNT] = {"sin", "cos", "atan2", "cbrt", "exp", "log"};
static fn_stat stats[F_COUNT];

static void one(int f, double x, double y)
{
    mpfr_set_d(g_x, x, MPFR_RNDN);
    switch (f) {
    case F_SIN:
        mpfr_sin(g_exact, g_x, MPFR_RNDN);
        record(&stats[f], sd_math_sin(x), sin(x), x, 0);
        break;
    case F_COS:
        mpfr_cos(g_exact, g_x, MPFR_RNDN);
        record(&stats[f], sd_math_cos(x), cos(x), x, 0);
        break;
    case F_ATAN2:
        mpfr_set_d(g_y, y, MPFR_RNDN);
        mpfr_atan2(g_exact, g_y, g_x, MPFR_RNDN);
        record(&stats[f], sd_math_atan2(y, x), atan2(y, x), x, y);
        break;
    case F_CBRT:
        mpfr_cbrt(g_exact, g_x, MPFR_RNDN);
        record(&stats[f], sd_math_cbrt(x), cbrt(x), x, 0);
        break;
    case F_EXP:
        mpfr_exp(g_exact, g_x, MPFR_RNDN);
        record(&stats[f], sd_math_exp(x), exp(x), x, 0);
        break;
    default:
        mpfr_log(g_exact, g_x, MPFR_RNDN);
        record(&stats[f], sd_math_log(x), log(x), x, 0);
        break;
    }
}

static double from_bits(uint64_t u)
{
    double d;
    memcpy(&d, &u, 8);
    return d;
}

/* a double with uniformly random bits of a random finite exponent in
 * [lo, hi] (log-uniform magnitude), random sign */
static double log_uniform(sd_rng *r, int lo, int hi)
{
    uint64_t m = sd_rng_next(r) & ((UINT64_C(1) << 52) - 1);
    int e = lo + (int)(sd_rng_next(r) % (uint64_t)(hi - lo + 1));
    uint64_t sign = (sd_rng_next(r) & 1) << 63;
    if (e < -1022) /* subnormal */
        return from_bits(sign | (m >> (-1022 - e)));
    return from_bits(sign | ((uint64_t)(e + 1023) << 52) | m);
}

static double next_up(double x, long k)
{
    uint64_t u;
    memcpy(&u, &x, 8);
    return from_bits(u + (uint64_t)k);
}

static void check_special(const char *what, double got, double want)
{
    int ok = same_bits(got, want);
    printf("%-4s special %-28s got %-24a want %a\n", ok ? "ok" : "FAIL", what, got, want);
    if (ok)
        sd_test_pass++;
    else
        sd_test_fail++;
}

int main(void)
{
    mpfr_inits2(160, g_exact, g_diff, g_ulp, (mpfr_ptr)0);
    mpfr_inits2(53, g_x, g_y, (mpfr_ptr)0);
    sd_rng r = sd_rng_seed(20261202);
    const int n = 100000; /* per kind of argument and function */

    for (int i = 0; i < n; i++) {
        /* the numerics' range: angles of a few turns, accumulated rotations */
        double u = sd_rng_range(&r, -20.0, 20.0);
        one(F_SIN, u, 0);
        one(F_COS, u, 0);
        /* the whole double range, subnormals included */
        double v = log_uniform(&r, -1074, 1023);
        one(F_SIN, v, 0);
        one(F_COS, v, 0);
        one(F_CBRT, v, 0);
        /* medium (Cody-Waite) and just above its limit (Payne-Hanek) */
        double w = log_uniform(&r, -2, 25);
        one(F_SIN, w, 0);
        one(F_COS, w, 0);
        /* atan2: directions of unit-scale vectors, and arbitrary pairs */
        double ax = sd_rng_range(&r, -1.0, 1.0), ay = sd_rng_range(&r, -1.0, 1.0);
        one(F_ATAN2, ax, ay);
        one(F_ATAN2, log_uniform(&r, -1074, 1023), log_uniform(&r, -1074, 1023));
        double bx = log_uniform(&r, -30, 30);
        one(F_ATAN2, bx, bx * sd_rng_range(&r, -1.2, 1.2)); /* near the diagonals */
        one(F_ATAN2, bx, bx * log_uniform(&r, -70, 0));      /* near the axes */
        /* cbrt over the volume law's range (m^3 of grains) and near cubes */
        one(F_CBRT, log_uniform(&r, -90, -20), 0);
        double c = (double)(1 + (long)(sd_rng_next(&r) % 100000));
        one(F_CBRT, next_up(c * c * c, (long)(sd_rng_next(&r) % 7) - 3), 0);
        /* exp over its whole finite range and near 0; log over every
         * positive double, near 1 and at the sqrt 2 seam */
        one(F_EXP, sd_rng_range(&r, -746.0, 710.0), 0);
        one(F_EXP, log_uniform(&r, -60, 3), 0);
        one(F_LOG, fabs(log_uniform(&r, -1074, 1023)), 0);
        one(F_LOG, 1.0 + sd_rng_range(&r, -1e-3, 1e-3), 0);
        one(F_LOG, next_up(0x1.6a09e667f3bcdp+0 * ldexp(1.0, (int)(sd_rng_next(&r) % 200) - 100),
                           (long)(sd_rng_next(&r) % 2001) - 1000), 0);
    }
    /* next to multiples of pi/2, where the reduction cancels: k pi/2 rounded
     * and its neighbours, k up to 2^36, and the hardest known double
     * (6381956970095103 2^797, |x mod pi/2| ~ 2^-61) */
    for (long k = 1; k < 120000; k++) {
        double kk = k < 60000 ? (double)k : ldexp((double)(k - 59999), 20) + (double)k;
        double x = kk * 0x1.921fb54442d18p+0;
        for (int d = -2; d <= 2; d++) {
            one(F_SIN, next_up(x, d), 0);
            one(F_COS, next_up(x, d), 0);
        }
    }
    one(F_SIN, ldexp(6381956970095103.0, 797), 0);
    one(F_COS, ldexp(6381956970095103.0, 797), 0);
    one(F_SIN, 0x1p19, 0); /* the Cody-Waite / Payne-Hanek seam */
    one(F_SIN, next_up(0x1p19, -1), 0);
    one(F_COS, 0x1p19, 0);
    one(F_COS, next_up(0x1p19, -1), 0);
    one(F_SIN, 0x1.fffffffffffffp1023, 0);
    one(F_COS, 0x1.fffffffffffffp1023, 0);
    one(F_SIN, 0x1p-27, 0); /* the tiny-argument seam */
    one(F_SIN, next_up(0x1p-27, -1), 0);
    one(F_COS, 0x1p-27, 0);

    printf("%-6s %10s %14s %14s %14s   worst argument (ours; libm's x)\n", "fn", "arguments", "max ulp",
           "libm max ulp", "differ libm");
    for (int f = 0; f < F_COUNT; f++) {
        fn_stat *s = &stats[f];
        printf("%-6s %10ld %14.4f %14.4f %14ld   %a %a; %a\n", fn_name[f], s->count, s->max_ulp, s->max_ulp_libm,
               s->differ_libm, s->worst_arg, s->worst_arg2, s->worst_libm);
    }
    for (int f = 0; f < F_COUNT; f++) {
        char label[64];
        snprintf(label, sizeof label, "%s: max error (ulp), %ld arguments", fn_name[f], stats[f].count);
        CHECK_NEAR(label, stats[f].max_ulp, 0.0, 1.0);
    }

    const double inf = INFINITY, nan_ = NAN, pi = 0x1.921fb54442d18p+1, pio2 = 0x1.921fb54442d18p+0,
                 pio4 = 0x1.921fb54442d18p-1, tpio4 = 0x1.2d97c7f3321d2p+1;
    check_special("sin(+0)", sd_math_sin(0.0), 0.0);
    check_special("sin(-0)", sd_math_sin(-0.0), -0.0);
    check_special("sin(+inf)", sd_math_sin(inf), nan_);
    check_special("sin(nan)", sd_math_sin(nan_), nan_);
    check_special("sin(-min subnormal)", sd_math_sin(-0x1p-1074), -0x1p-1074);
    check_special("cos(-0)", sd_math_cos(-0.0), 1.0);
    check_special("cos(-inf)", sd_math_cos(-inf), nan_);
    check_special("atan2(+0, +0)", sd_math_atan2(0.0, 0.0), 0.0);
    check_special("atan2(-0, +0)", sd_math_atan2(-0.0, 0.0), -0.0);
    check_special("atan2(+0, -0)", sd_math_atan2(0.0, -0.0), pi);
    check_special("atan2(-0, -0)", sd_math_atan2(-0.0, -0.0), -pi);
    check_special("atan2(-0, -1)", sd_math_atan2(-0.0, -1.0), -pi);
    check_special("atan2(1, +0)", sd_math_atan2(1.0, 0.0), pio2);
    check_special("atan2(-1, -0)", sd_math_atan2(-1.0, -0.0), -pio2);
    check_special("atan2(+inf, +inf)", sd_math_atan2(inf, inf), pio4);
    check_special("atan2(-inf, -inf)", sd_math_atan2(-inf, -inf), -tpio4);
    check_special("atan2(1, -inf)", sd_math_atan2(1.0, -inf), pi);
    check_special("atan2(-1, +inf)", sd_math_atan2(-1.0, inf), -0.0);
    check_special("atan2(+inf, 5)", sd_math_atan2(inf, 5.0), pio2);
    check_special("atan2(nan, 1)", sd_math_atan2(nan_, 1.0), nan_);
    check_special("atan2(1, nan)", sd_math_atan2(1.0, nan_), nan_);
    check_special("atan2(1, 1)", sd_math_atan2(1.0, 1.0), pio4);
    check_special("cbrt(-0)", sd_math_cbrt(-0.0), -0.0);
    check_special("cbrt(-inf)", sd_math_cbrt(-inf), -inf);
    check_special("cbrt(nan)", sd_math_cbrt(nan_), nan_);
    check_special("cbrt(-8)", sd_math_cbrt(-8.0), -2.0);
    check_special("cbrt(2^-1074)", sd_math_cbrt(0x1p-1074), 0x1p-358);
    check_special("cbrt(2^999)", sd_math_cbrt(0x1p999), 0x1p333);
    check_special("exp(0)", sd_math_exp(0.0), 1.0);
    check_special("exp(-inf)", sd_math_exp(-inf), 0.0);
    check_special("exp(+inf)", sd_math_exp(inf), inf);
    check_special("exp(nan)", sd_math_exp(nan_), nan_);
    check_special("exp(710)", sd_math_exp(710.0), inf);
    check_special("exp(-746)", sd_math_exp(-746.0), 0.0);
    check_special("exp(-745.1)", sd_math_exp(-745.1), 0x1p-1074);
    check_special("log(1)", sd_math_log(1.0), 0.0);
    check_special("log(+0)", sd_math_log(0.0), -inf);
    check_special("log(-0)", sd_math_log(-0.0), -inf);
    check_special("log(-1)", sd_math_log(-1.0), nan_);
    check_special("log(+inf)", sd_math_log(inf), inf);
    check_special("log(nan)", sd_math_log(nan_), nan_);
    check_special("log(2)", sd_math_log(2.0), 0x1.62e42fefa39efp-1);
    mpfr_clears(g_exact, g_diff, g_ulp, g_x, g_y, (mpfr_ptr)0);
    mpfr_free_cache();
    return sd_test_summary();
}
