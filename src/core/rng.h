/* rng.h — seeded random numbers that are the same on every platform.
 *
 * xoshiro256** seeded through splitmix64 (public-domain algorithms by
 * Blackman and Vigna). Only integer arithmetic decides the stream; doubles
 * are built from the top 53 bits, so results never depend on the libc.
 */
#ifndef SD_CORE_RNG_H
#define SD_CORE_RNG_H

#include "base.h"

typedef struct sd_rng {
    uint64_t s[4];
} sd_rng;

SD_HD static SD_INLINE uint64_t sd_rng_splitmix(uint64_t *x)
{
    uint64_t z = (*x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

SD_HD static SD_INLINE sd_rng sd_rng_seed(uint64_t seed)
{
    sd_rng r;
    uint64_t x = seed;
    for (int i = 0; i < 4; ++i)
        r.s[i] = sd_rng_splitmix(&x);
    return r;
}

SD_HD static SD_INLINE uint64_t sd_rng_rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

SD_HD static SD_INLINE uint64_t sd_rng_next(sd_rng *r)
{
    uint64_t *s = r->s;
    uint64_t out = sd_rng_rotl(s[1] * 5u, 7) * 9u;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = sd_rng_rotl(s[3], 45);
    return out;
}

/* Uniform in [0, 1). */
SD_HD static SD_INLINE double sd_rng_uniform(sd_rng *r)
{
    return (double)(sd_rng_next(r) >> 11) * (1.0 / 9007199254740992.0);
}

/* Uniform in [lo, hi). */
SD_HD static SD_INLINE double sd_rng_range(sd_rng *r, double lo, double hi)
{
    return lo + (hi - lo) * sd_rng_uniform(r);
}

#endif
