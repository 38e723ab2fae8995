/* math.h — the engine's own elementary functions (sd_math_*): sin, cos,
 * atan2, cbrt, exp and log in double precision, written once for the CPU
 * and the GPU (the numerics call the first four; exp and log are here for
 * the device code that will need them).
 *
 * Invariant: the same argument gives the same bits on every build. libm and
 * CUDA's libdevice each round sin, cos, atan2, cbrt ... in their own way
 * (both within an ulp or so, rarely the same way), so a state that calls
 * them drifts apart between the CPU and the GPU backends after a few steps.
 * These functions use only +, -, *, / and integer operations on the bits,
 * which IEEE 754 defines exactly and both targets implement exactly, and
 * small constant tables; so CPU and GPU get identical results as long as no
 * multiply-add is fused (the C build has -ffp-contract=off, device code
 * --fmad=false: docs/architecture.md, "Same bits on CPU and GPU"). The
 * error-free products that the accuracy rests on use __dmul_rn on the
 * device, which no compiler flag may fuse.
 *
 * Accuracy: within 1 ulp of the exact result for every double (unit.math
 * measures the maximum error against MPFR over millions of arguments and
 * edge cases; typical figures are 0.5x ulp, the final rounding plus a few
 * hundredths). How:
 *  - sin, cos: x = k pi/2 + r with r as a double-double (Cody–Waite with a
 *    4-piece pi/2 below 2^19, else Payne–Hanek on the integer mantissa with
 *    224 bits of 2/pi from a table of 40 words), then Taylor series on
 *    |r| <= pi/4 (truncation below 1e-19 relative), the leading terms in
 *    double-double so only the last addition rounds.
 *  - atan2: the quotient of the smaller by the larger |y|, |x| as a
 *    double-double, atan(j/8) from a table plus the Taylor series of
 *    atan(s), |s| <= 1/16, then pi/2 - . and pi - . in double-double.
 *  - cbrt: exponent divided by 3 on the bits, a quadratic first guess on
 *    [1, 8), Halley steps, one Newton correction with the residual a - y^3
 *    computed exactly.
 *  - exp: x = k ln 2 + r (Cody–Waite, ln 2 in two pieces), Taylor to r^15
 *    with 1 + r exact; log: 2 atanh((m - 1)/(m + 1)) on m in
 *    [sqrt(1/2), sqrt 2), the quotient as a double-double.
 * Constants: hexadecimal literals from MPFR (pi, 2/pi, atan(j/8), 1/n!),
 * each the correctly rounded double or the next double-double part.
 *
 * Single precision builds (SHAPEDEM_SINGLE) keep the float libm functions
 * (core/base.h); these are for the double build, the engine's default.
 */
#ifndef SD_CORE_MATH_H
#define SD_CORE_MATH_H

#include "core/base.h"

#include <string.h>

/* The products of the error-free transforms: never fused on the device,
 * whatever --fmad says (a fused split or two-product is no longer exact). */
#if defined(__CUDA_ARCH__)
#define SD_MATH_MUL(a, b) __dmul_rn((a), (b))
#else
#define SD_MATH_MUL(a, b) ((a) * (b))
#endif

/* An unevaluated sum hi + lo with |lo| <= ulp(hi) / 2. */
typedef struct sd_math_dd {
    double hi, lo;
} sd_math_dd;

SD_HD static SD_INLINE uint64_t sd_math_bits(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

SD_HD static SD_INLINE double sd_math_from_bits(uint64_t u)
{
    double x;
    memcpy(&x, &u, sizeof x);
    return x;
}

/* 2^n for a normal exponent, -1022 <= n <= 1023 (exact). */
SD_HD static SD_INLINE double sd_math_pow2(int n) { return sd_math_from_bits((uint64_t)(n + 1023) << 52); }

/* ---- error-free transforms (Knuth, Dekker) ------------------------------ */

/* a + b = s + e exactly, any order of magnitude. */
SD_HD static SD_INLINE sd_math_dd sd_math_two_sum(double a, double b)
{
    sd_math_dd r;
    r.hi = a + b;
    double bb = r.hi - a;
    r.lo = (a - (r.hi - bb)) + (b - bb);
    return r;
}

/* the same for |a| >= |b| (or a == 0) */
SD_HD static SD_INLINE sd_math_dd sd_math_fast_two_sum(double a, double b)
{
    sd_math_dd r;
    r.hi = a + b;
    r.lo = b - (r.hi - a);
    return r;
}

/* a = hi + lo with 26-bit halves, so their products are exact; |a| < 2^995 */
SD_HD static SD_INLINE void sd_math_split(double a, double *hi, double *lo)
{
    double c = SD_MATH_MUL(134217729.0, a); /* 2^27 + 1 */
    *hi = c - (c - a);
    *lo = a - *hi;
}

/* a b = p + e exactly (no underflow or overflow in the halves' products) */
SD_HD static SD_INLINE sd_math_dd sd_math_two_prod(double a, double b)
{
    double ah, al, bh, bl;
    sd_math_split(a, &ah, &al);
    sd_math_split(b, &bh, &bl);
    sd_math_dd r;
    r.hi = SD_MATH_MUL(a, b);
    /* every product below is exact, so fusing them would change nothing */
    r.lo = ((ah * bh - r.hi) + ah * bl + al * bh) + al * bl;
    return r;
}

/* x + y for double-doubles, relative error about 2^-104 */
SD_HD static SD_INLINE sd_math_dd sd_math_dd_add(sd_math_dd x, sd_math_dd y)
{
    sd_math_dd s = sd_math_two_sum(x.hi, y.hi), t = sd_math_two_sum(x.lo, y.lo);
    s.lo += t.hi;
    s = sd_math_fast_two_sum(s.hi, s.lo);
    s.lo += t.lo;
    return sd_math_fast_two_sum(s.hi, s.lo);
}

SD_HD static SD_INLINE sd_math_dd sd_math_dd_add_d(sd_math_dd x, double y)
{
    sd_math_dd s = sd_math_two_sum(x.hi, y);
    s.lo += x.lo;
    return sd_math_fast_two_sum(s.hi, s.lo);
}

SD_HD static SD_INLINE sd_math_dd sd_math_dd_neg(sd_math_dd x)
{
    x.hi = -x.hi;
    x.lo = -x.lo;
    return x;
}

SD_HD static SD_INLINE sd_math_dd sd_math_dd_mul(sd_math_dd x, sd_math_dd y)
{
    sd_math_dd p = sd_math_two_prod(x.hi, y.hi);
    p.lo += x.hi * y.lo + x.lo * y.hi;
    return sd_math_fast_two_sum(p.hi, p.lo);
}

/* x / y, y != 0: one correction step from the remainder x - q y */
SD_HD static SD_INLINE sd_math_dd sd_math_dd_div(sd_math_dd x, sd_math_dd y)
{
    double q = x.hi / y.hi;
    sd_math_dd p = sd_math_two_prod(q, y.hi);
    double r = ((x.hi - p.hi) - p.lo + x.lo) - q * y.lo;
    return sd_math_fast_two_sum(q, r / y.hi);
}

/* ---- argument reduction modulo pi/2 -------------------------------------- */

/* |x| >= 2^19, finite: Payne–Hanek. |x| = m 2^e with m a 53-bit integer;
 * |x| 2/pi mod 4 needs the words of 2/pi from the one whose product with m
 * is no longer a multiple of 4 (the earlier ones only add multiples of 4),
 * and 7 of them (224 bits) leave an error below 2^-138 in the fraction,
 * whose magnitude is at least about 2^-62 for any double. Integer work, so
 * exact on every target. Returns k mod 4 and r = (frac) pi/2, |frac| <= 1/2. */
SD_HD static SD_INLINE int sd_math_rem_pio2_large(double ax, sd_math_dd *r)
{
    /* 2/pi = sum c[i] 2^(-32 (i + 1)) */
    static const uint32_t c[40] = {
        0xa2f9836e, 0x4e441529, 0xfc2757d1, 0xf534ddc0, 0xdb629599, 0x3c439041, 0xfe5163ab, 0xdebbc561,
        0xb7246e3a, 0x424dd2e0, 0x06492eea, 0x09d1921c, 0xfe1deb1c, 0xb129a73e, 0xe88235f5, 0x2ebb4484,
        0xe99c7026, 0xb45f7e41, 0x3991d639, 0x835339f4, 0x9c845f8b, 0xbdf9283b, 0x1ff897ff, 0xde05980f,
        0xef2f118b, 0x5a0a6d1f, 0x6d367ecf, 0x27cb09b7, 0x4f463f66, 0x9e5fea2d, 0x7527bac7, 0xebe5f17b,
        0x3d0739f7, 0x8a5292ea, 0x6bfb5fb1, 0x1f8d5d08, 0x56033046, 0xfc7b6bab, 0xf0cfbc20, 0x9af4361d,
    };
    uint64_t bits = sd_math_bits(ax);
    int e = (int)(bits >> 52) - 1075;
    uint64_t m = (bits & ((UINT64_C(1) << 52) - 1)) | (UINT64_C(1) << 52);
    int i0 = e >= 2 ? (e - 2) / 32 : 0; /* words before i0 give multiples of 4 */
    int s0 = e - 32 * (i0 + 1);         /* m c[i0] carries weight 2^s0 */
    /* b = m * (c[i0] ... c[i0 + 6]), little-endian 32-bit words */
    uint32_t b[9];
    uint64_t ml = m & 0xffffffffu, mh = m >> 32, carry = 0, t;
    for (int j = 0; j < 7; j++) {
        t = ml * c[i0 + 6 - j] + carry;
        b[j] = (uint32_t)t;
        carry = t >> 32;
    }
    b[7] = (uint32_t)carry;
    carry = 0;
    for (int j = 0; j < 7; j++) {
        t = mh * c[i0 + 6 - j] + b[j + 1] + carry;
        b[j + 1] = (uint32_t)t;
        carry = t >> 32;
    }
    b[8] = (uint32_t)carry;
    /* b's bit p has weight 2^(p + s0 - 192): the units bit is at p0 */
    int p0 = 192 - s0;
    uint32_t w[6]; /* w[0]: bits p0 .. p0 + 31, w[1..5]: the fraction, high first */
    for (int j = 0; j < 6; j++) {
        int pos = p0 - 32 * j, k = pos >> 5, sh = pos & 31;
        uint64_t lo = b[k], hi = k + 1 < 9 ? b[k + 1] : 0;
        w[j] = (uint32_t)(((hi << 32) | lo) >> sh);
    }
    int q = (int)(w[0] & 3u), neg = 0;
    if (w[1] & 0x80000000u) { /* fraction >= 1/2: take k + 1 and 1 - fraction */
        q = (q + 1) & 3;
        neg = 1;
        uint64_t borrow = 1;
        for (int j = 5; j >= 1; j--) {
            uint64_t v = (uint64_t)(uint32_t)~w[j] + borrow;
            w[j] = (uint32_t)v;
            borrow = v >> 32;
        }
    }
    sd_math_dd f = {(double)w[1] * 0x1p-32, 0.0};
    double scale = 0x1p-32;
    for (int j = 2; j < 6; j++) {
        scale *= 0x1p-32;
        f = sd_math_dd_add_d(f, (double)w[j] * scale);
    }
    const sd_math_dd pio2 = {0x1.921fb54442d18p+0, 0x1.1a62633145c07p-54};
    f = sd_math_dd_mul(f, pio2);
    *r = neg ? sd_math_dd_neg(f) : f;
    return q;
}

/* x = k pi/2 + r, |r| <= pi/4 (a hair more where the rounded k is taken);
 * returns k mod 4. Finite x only. */
SD_HD static SD_INLINE int sd_math_rem_pio2(double x, sd_math_dd *r)
{
    double ax = fabs(x);
    if (ax <= 0x1.921fb54442d18p-1) {
        r->hi = x;
        r->lo = 0.0;
        return 0;
    }
    if (ax < 0x1p19) {
        /* Cody–Waite: pi/2 = P1 + P2 + P3 + P4, P1..P3 of 33 bits, so k Pi is
         * exact for k < 2^20 and x - k P1 exact (Sterbenz) */
        const double P1 = 0x1.921fb544p+0, P2 = 0x1.0b4611a6p-34, P3 = 0x1.3198a2ep-69,
                     P4 = 0x1.b839a252049c1p-104;
        double k = (SD_MATH_MUL(x, 0x1.45f306dc9c883p-1) + 0x1.8p52) - 0x1.8p52; /* round(x 2/pi) */
        sd_math_dd s = sd_math_two_sum(x - SD_MATH_MUL(k, P1), -SD_MATH_MUL(k, P2));
        s = sd_math_dd_add_d(s, -SD_MATH_MUL(k, P3));
        s = sd_math_dd_add_d(s, -SD_MATH_MUL(k, P4)); /* its rounding: k 2^-157 */
        *r = s;
        return (int)((int64_t)k & 3);
    }
    int q = sd_math_rem_pio2_large(ax, r);
    if (x < 0.0) {
        *r = sd_math_dd_neg(*r);
        q = (4 - q) & 3;
    }
    return q;
}

/* ---- sin and cos on |r| <= pi/4 ----------------------------------------- */

/* sin(x + y) = x + (x^3 P(x^2) + y (1 - x^2/2)); Taylor to x^17 */
SD_HD static SD_INLINE double sd_math_ksin(sd_math_dd r)
{
    double x = r.hi, y = r.lo, z = x * x, v = z * x;
    double p = 0x1.952c77030ad4ap-49;  /*  1/17! */
    p = p * z - 0x1.ae7f3e733b81fp-41; /* -1/15! */
    p = p * z + 0x1.6124613a86d09p-33; /*  1/13! */
    p = p * z - 0x1.ae64567f544e4p-26; /* -1/11! */
    p = p * z + 0x1.71de3a556c734p-19; /*  1/9!  */
    p = p * z - 0x1.a01a01a01a01ap-13; /* -1/7!  */
    p = p * z + 0x1.1111111111111p-7;  /*  1/5!  */
    p = p * z - 0x1.5555555555555p-3;  /* -1/3!  */
    return x + (v * p + y * (1.0 - 0.5 * z));
}

/* cos(x + y) = (1 - h) + x^4 Q(x^2) with h = x^2/2 + x y, the 1 - x^2/2
 * part exact in double-double; Taylor to x^18 */
SD_HD static SD_INLINE double sd_math_kcos(sd_math_dd r)
{
    double x = r.hi, y = r.lo, z = x * x;
    sd_math_dd sq = sd_math_two_prod(x, x);
    sd_math_dd s = sd_math_two_sum(1.0, -0.5 * sq.hi);
    double q = -0x1.6827863b97d97p-53; /* -1/18! */
    q = q * z + 0x1.ae7f3e733b81fp-45; /*  1/16! */
    q = q * z - 0x1.93974a8c07c9dp-37; /* -1/14! */
    q = q * z + 0x1.1eed8eff8d898p-29; /*  1/12! */
    q = q * z - 0x1.27e4fb7789f5cp-22; /* -1/10! */
    q = q * z + 0x1.a01a01a01a01ap-16; /*  1/8!  */
    q = q * z - 0x1.6c16c16c16c17p-10; /* -1/6!  */
    q = q * z + 0x1.5555555555555p-5;  /*  1/4!  */
    return s.hi + (s.lo + (z * z * q - (0.5 * sq.lo + x * y)));
}

/* |x| < 2^-27: sin x = x and cos x = 1 correctly rounded (x^2/6 is below
 * half an ulp), which also keeps the sign of zero and subnormals exact */
#define SD_MATH_TINY 0x1p-27

SD_HD static SD_INLINE double sd_math_sin(double x)
{
    if (!(fabs(x) <= 0x1.fffffffffffffp1023))
        return x - x; /* NaN for inf and NaN */
    if (fabs(x) < SD_MATH_TINY)
        return x;
    sd_math_dd r;
    switch (sd_math_rem_pio2(x, &r)) {
    case 0: return sd_math_ksin(r);
    case 1: return sd_math_kcos(r);
    case 2: return -sd_math_ksin(r);
    default: return -sd_math_kcos(r);
    }
}

SD_HD static SD_INLINE double sd_math_cos(double x)
{
    if (!(fabs(x) <= 0x1.fffffffffffffp1023))
        return x - x;
    if (fabs(x) < SD_MATH_TINY)
        return 1.0;
    sd_math_dd r;
    switch (sd_math_rem_pio2(x, &r)) {
    case 0: return sd_math_kcos(r);
    case 1: return -sd_math_ksin(r);
    case 2: return -sd_math_kcos(r);
    default: return sd_math_ksin(r);
    }
}

/* ---- atan2 --------------------------------------------------------------- */

/* |v| with the sign of s (bits only: exact, NaN-safe) */
SD_HD static SD_INLINE double sd_math_copysign(double v, double s)
{
    uint64_t sign = UINT64_C(1) << 63;
    return sd_math_from_bits((sd_math_bits(v) & ~sign) | (sd_math_bits(s) & sign));
}

/* atan(t) for a double-double t in [0, 1]: atan(c) + atan(s) with c = j/8
 * the nearest eighth and s = (t - c)/(1 + c t), |s| <= 1/16, whose series
 * s - s^3/3 + ... - s^15/15 + s^17/17 leaves below 2^-70 relative */
SD_HD static SD_INLINE sd_math_dd sd_math_atan_dd(sd_math_dd t)
{
    static const double at[9][2] = {
        {0.0, 0.0},
        {0x1.fd5ba9aac2f6ep-4, -0x1.cd37686760c17p-59},
        {0x1.f5b75f92c80ddp-3, 0x1.8ab6e3cf7afbdp-57},
        {0x1.6f61941e4def1p-2, -0x1.c63aae6f6e918p-56},
        {0x1.dac670561bb4fp-2, 0x1.a2b7f222f65e2p-56},
        {0x1.1e00babdefeb4p-1, -0x1.928df287a668fp-58},
        {0x1.4978fa3269ee1p-1, 0x1.2419a87f2a458p-56},
        {0x1.700a7c5784634p-1, -0x1.8c34d25aadef6p-56},
        {0x1.921fb54442d18p-1, 0x1.1a62633145c07p-55},
    };
    int j = (int)(t.hi * 8.0 + 0.5);
    if (j > 8)
        j = 8;
    sd_math_dd s = t;
    if (j > 0) {
        double c = 0.125 * (double)j;
        sd_math_dd num = sd_math_dd_add_d(t, -c); /* t.hi - c is exact (Sterbenz) */
        sd_math_dd den = sd_math_two_prod(c, t.hi);
        den.lo += c * t.lo;
        den = sd_math_dd_add_d(sd_math_fast_two_sum(den.hi, den.lo), 1.0);
        s = sd_math_dd_div(num, den);
    }
    double z = s.hi * s.hi;
    double p = 0x1.e1e1e1e1e1e1ep-5;  /*  1/17 */
    p = p * z - 0x1.1111111111111p-4; /* -1/15 */
    p = p * z + 0x1.3b13b13b13b14p-4; /*  1/13 */
    p = p * z - 0x1.745d1745d1746p-4; /* -1/11 */
    p = p * z + 0x1.c71c71c71c71cp-4; /*  1/9  */
    p = p * z - 0x1.2492492492492p-3; /* -1/7  */
    p = p * z + 0x1.999999999999ap-3; /*  1/5  */
    p = p * z - 0x1.5555555555555p-2; /* -1/3  */
    sd_math_dd a = {at[j][0], at[j][1]};
    a = sd_math_dd_add(a, s);
    return sd_math_dd_add_d(a, s.hi * z * p);
}

/* The angle of (x, y) in (-pi, pi], C99 Annex F for zeros, infinities
 * and NaN. The quotient of the smaller by the larger magnitude is taken
 * as a double-double (its rounding alone would cost up to half an ulp),
 * after scaling both by a power of 2 into a range where its exact
 * remainder neither overflows nor underflows. */
SD_HD static SD_INLINE double sd_math_atan2(double y, double x)
{
    if (x != x || y != y)
        return x + y;
    const sd_math_dd pio2 = {0x1.921fb54442d18p+0, 0x1.1a62633145c07p-54};
    const sd_math_dd pi = {0x1.921fb54442d18p+1, 0x1.1a62633145c07p-53};
    double ax = fabs(x), ay = fabs(y);
    int swap = ay > ax, xneg = (int)(sd_math_bits(x) >> 63);
    double a = swap ? ax : ay, b = swap ? ay : ax; /* 0 <= a <= b */
    sd_math_dd r = {0.0, 0.0};
    if (b == 0.0) {
        /* both zero: r = 0 */
    } else if (a == b && !(b <= 0x1.fffffffffffffp1023)) {
        r.hi = 0x1.921fb54442d18p-1; /* both infinite: pi/4 */
        r.lo = 0x1.1a62633145c07p-55;
    } else {
        double t0 = a / b;
        if (t0 < 0x1p-60) {
            r.hi = t0; /* atan t = t (1 - t^2/3): t correctly rounded */
        } else {
            if (b > 0x1p900) {
                a *= 0x1p-960; /* a >= b 2^-61 stays normal */
                b *= 0x1p-960;
            } else if (b < 0x1p-900) {
                a *= 0x1p960;
                b *= 0x1p960;
            }
            sd_math_dd t = {a / b, 0.0};
            sd_math_dd p = sd_math_two_prod(t.hi, b);
            t.lo = ((a - p.hi) - p.lo) / b; /* a - p.hi exact (Sterbenz) */
            r = sd_math_atan_dd(sd_math_fast_two_sum(t.hi, t.lo));
        }
    }
    if (swap)
        r = sd_math_dd_add(pio2, sd_math_dd_neg(r));
    if (xneg)
        r = sd_math_dd_add(pi, sd_math_dd_neg(r));
    return sd_math_copysign(r.hi + r.lo, y);
}

/* ---- cbrt ---------------------------------------------------------------- */

/* Real cube root, odd; exact for perfect cubes of doubles that are exact. */
SD_HD static SD_INLINE double sd_math_cbrt(double x)
{
    if (x == 0.0 || !(fabs(x) <= 0x1.fffffffffffffp1023))
        return x + x; /* +-0, +-inf, NaN */
    uint64_t sign = sd_math_bits(x) & (UINT64_C(1) << 63);
    uint64_t u = sd_math_bits(x) ^ sign;
    int adj = 0;
    if (u < (UINT64_C(1) << 52)) { /* subnormal: scale by 2^54, cube root 2^18 */
        u = sd_math_bits(sd_math_from_bits(u) * 0x1p54);
        adj = -18;
    }
    int e = (int)(u >> 52) - 1023;
    int q = e >= 0 ? e / 3 : -((2 - e) / 3); /* floor(e / 3) */
    int rr = e - 3 * q;                       /* 0, 1, 2 */
    double a = sd_math_from_bits((u & ((UINT64_C(1) << 52) - 1)) | ((uint64_t)(1023 + rr) << 52)); /* [1, 8) */
    /* least-squares quadratic, relative error 2.2 % on [1, 8] */
    double y = 0.7777563431017407 + a * (0.25696922540341166 - 0.013362273432145418 * a);
    for (int i = 0; i < 3; i++) { /* Halley: the error cubes each step */
        double y3 = y * y * y;
        y = y * (y3 + 2.0 * a) / (2.0 * y3 + a);
    }
    /* Newton from the exact residual: a - y^3 = a - (c + ce) */
    sd_math_dd sq = sd_math_two_prod(y, y), cu = sd_math_two_prod(y, sq.hi);
    double ce = cu.lo + y * sq.lo;
    y += ((a - cu.hi) - ce) / (3.0 * sq.hi);
    return sd_math_copysign(y * sd_math_pow2(q + adj), sd_math_from_bits(sign));
}


/* ---- exp and log --------------------------------------------------------- */

/* ln 2 = L1 + L2, L1 of 41 bits so that k L1 is exact for |k| < 2^12 */
#define SD_MATH_LN2_1 0x1.62e42fefa2p-1
#define SD_MATH_LN2_2 0x1.9ef35793c7673p-41

/* e^x: x = k ln 2 + r, |r| <= ln 2 / 2 as a double-double, e^r = 1 + r +
 * r^2 (1/2! + r/3! + ... + r^13/15!) with 1 + r exact in double-double,
 * then 2^k in one or two exact scalings (the second, into the subnormal
 * range, is the only rounding there). */
SD_HD static SD_INLINE double sd_math_exp(double x)
{
    if (x != x)
        return x + x;
    if (x > 0x1.62e42fefa39efp+9) /* above ln(DBL_MAX): overflow */
        return sd_math_from_bits(UINT64_C(0x7ff0000000000000));
    if (x < -0x1.74910d52d3052p+9) /* below ln(2^-1075): rounds to +0 */
        return 0.0;
    if (fabs(x) < 0x1p-54)
        return 1.0 + x;
    double k = (SD_MATH_MUL(x, 0x1.71547652b82fep+0) + 0x1.8p52) - 0x1.8p52; /* round(x / ln 2) */
    sd_math_dd r = sd_math_two_sum(x - SD_MATH_MUL(k, SD_MATH_LN2_1), -SD_MATH_MUL(k, SD_MATH_LN2_2));
    double z = r.hi;
    double p = 0x1.ae7f3e733b81fp-41;  /* 1/15! */
    p = p * z + 0x1.93974a8c07c9dp-37; /* 1/14! */
    p = p * z + 0x1.6124613a86d09p-33; /* 1/13! */
    p = p * z + 0x1.1eed8eff8d898p-29; /* 1/12! */
    p = p * z + 0x1.ae64567f544e4p-26; /* 1/11! */
    p = p * z + 0x1.27e4fb7789f5cp-22; /* 1/10! */
    p = p * z + 0x1.71de3a556c734p-19; /* 1/9!  */
    p = p * z + 0x1.a01a01a01a01ap-16; /* 1/8!  */
    p = p * z + 0x1.a01a01a01a01ap-13; /* 1/7!  */
    p = p * z + 0x1.6c16c16c16c17p-10; /* 1/6!  */
    p = p * z + 0x1.1111111111111p-7;  /* 1/5!  */
    p = p * z + 0x1.5555555555555p-5;  /* 1/4!  */
    p = p * z + 0x1.5555555555555p-3;  /* 1/3!  */
    p = p * z + 0.5;
    sd_math_dd s = sd_math_two_sum(1.0, z);
    double y = s.hi + (s.lo + (r.lo * (1.0 + z) + z * z * p));
    int n = (int)k;
    if (n > 1023)
        return y * sd_math_pow2(n - 1) * 2.0;
    if (n < -1021)
        return y * sd_math_pow2(n + 54) * 0x1p-54;
    return y * sd_math_pow2(n);
}

/* ln x: x = 2^e m with m in [sqrt(1/2), sqrt 2), ln m = 2 atanh(s),
 * s = (m - 1)/(m + 1) as a double-double (|s| <= 0.172), the series
 * 2 s + 2 s^3 (1/3 + s^2/5 + ... + s^18/21), and e ln 2 in double-double. */
SD_HD static SD_INLINE double sd_math_log(double x)
{
    if (x != x)
        return x + x;
    if (x < 0.0)
        return sd_math_from_bits(UINT64_C(0x7ff8000000000000)); /* NaN */
    if (x == 0.0)
        return sd_math_from_bits(UINT64_C(0xfff0000000000000)); /* -inf */
    if (!(x <= 0x1.fffffffffffffp1023))
        return x; /* +inf */
    uint64_t u = sd_math_bits(x);
    int e = 0;
    if (u < (UINT64_C(1) << 52)) { /* subnormal */
        u = sd_math_bits(x * 0x1p54);
        e = -54;
    }
    e += (int)(u >> 52) - 1023;
    double m = sd_math_from_bits((u & ((UINT64_C(1) << 52) - 1)) | (UINT64_C(1023) << 52)); /* [1, 2) */
    if (m > 0x1.6a09e667f3bcdp+0) {
        m *= 0.5;
        e += 1;
    }
    double f = m - 1.0; /* exact (Sterbenz) */
    sd_math_dd num = {f, 0.0};
    sd_math_dd s = sd_math_dd_div(num, sd_math_two_sum(2.0, f));
    double z = s.hi * s.hi;
    double p = 0x1.8618618618618p-5;  /* 1/21 */
    p = p * z + 0x1.af286bca1af28p-5; /* 1/19 */
    p = p * z + 0x1.e1e1e1e1e1e1ep-5; /* 1/17 */
    p = p * z + 0x1.1111111111111p-4; /* 1/15 */
    p = p * z + 0x1.3b13b13b13b14p-4; /* 1/13 */
    p = p * z + 0x1.745d1745d1746p-4; /* 1/11 */
    p = p * z + 0x1.c71c71c71c71cp-4; /* 1/9  */
    p = p * z + 0x1.2492492492492p-3; /* 1/7  */
    p = p * z + 0x1.999999999999ap-3; /* 1/5  */
    p = p * z + 0x1.5555555555555p-2; /* 1/3  */
    sd_math_dd r = {2.0 * s.hi, 2.0 * s.lo};
    r = sd_math_dd_add_d(r, 2.0 * s.hi * z * p);
    double de = (double)e;
    sd_math_dd l = sd_math_two_prod(de, SD_MATH_LN2_2);
    l = sd_math_dd_add_d(l, de * SD_MATH_LN2_1); /* e L1 exact */
    r = sd_math_dd_add(l, r);
    return r.hi + r.lo;
}

#endif
