/* base.h — precision, the single-source marker and the math functions every
 * numeric header uses.
 *
 * Invariant: everything here compiles as C17 and as CUDA C++ (DESIGN.md
 * rule 1). SD_HD is empty under a C compiler and `__host__ __device__` under
 * nvcc, so the same inline function serves the CPU loops and the GPU kernels.
 */
#ifndef SD_CORE_BASE_H
#define SD_CORE_BASE_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#if defined(__CUDACC__)
#define SD_HD __host__ __device__
#define SD_INLINE __forceinline__
#define SD_HOT SD_INLINE
#else
#define SD_HD
#define SD_INLINE inline
/* the per-pair and per-particle kernels of the hot loops: inlined even when
 * the compiler's size heuristics would not (they run 10^8 times a second) */
#if defined(__GNUC__)
#define SD_HOT inline __attribute__((always_inline))
#else
#define SD_HOT inline
#endif
#endif

/* The engine's own elementary functions (core/math.h): the same bits on
 * the CPU and the GPU. Included here, after SD_HD, so every numeric header
 * that names sd_sin ... gets them. */
#include "core/math.h"

/* One precision for state, chosen at build time (STYLE.md convention 6).
 *
 * sd_sin, sd_cos, sd_atan2, sd_cbrt are what the numerics (SD_HD code)
 * call: in double, the single-source ones of core/math.h, so a GPU kernel
 * and a CPU loop round alike; sqrt, fabs and floor are exact in IEEE 754 on
 * both and stay libm's. sd_host_* are the platform's libm for host-only
 * set-up code (template mass properties, outlines, Fourier fits), whose
 * results reach a kernel only as data uploaded once. sd_log, sd_exp and
 * sd_pow are host-only too: no SD_HD code calls them
 * (tests/cli/sd_hd_libm.sh checks it). */
#if defined(SHAPEDEM_SINGLE)
typedef float sd_real;
#define SD_R(x) x##f
#define sd_sqrt sqrtf
#define sd_fabs fabsf
#define sd_sin sinf /* single precision keeps libm: no same-bits promise */
#define sd_cos cosf
#define sd_atan2 atan2f
#define sd_cbrt cbrtf
#define sd_host_sin sinf
#define sd_host_cos cosf
#define sd_host_atan2 atan2f
#define sd_log logf
#define sd_exp expf
#define sd_pow powf
#define sd_floor floorf
#else
typedef double sd_real;
#define SD_R(x) x
#define sd_sqrt sqrt
#define sd_fabs fabs
#define sd_sin sd_math_sin
#define sd_cos sd_math_cos
#define sd_atan2 sd_math_atan2
#define sd_cbrt sd_math_cbrt
#define sd_host_sin sin
#define sd_host_cos cos
#define sd_host_atan2 atan2
#define sd_log log
#define sd_exp exp
#define sd_pow pow
#define sd_floor floor
#endif

/* A pragma from a macro (the CPU backend's OpenMP loops build theirs with
 * it: backend/cpu/parallel.h). */
#define SD_PRAGMA(x) _Pragma(#x)

/* SD_OMP_EACH(par, nth, k, k0, k1, body): for (size_t k = k0; k < k1; ++k)
 * body, over nth threads (static schedule) when par, else a plain loop
 * that never enters the OpenMP runtime: a region with if (0) still ends
 * with libgomp's barrier, which wakes a futex with a system call (1-3 us
 * on a virtual machine) every time, and a small world's step and rebuild
 * run dozens of them (backend/cpu/parallel.h). Items must write only
 * their own slots, so both give the same bits. */
#define SD_LOOP_(k, ...)                                                                                       \
    for (size_t k = k##_lo_; k < k##_hi_; ++k) {                                                               \
        __VA_ARGS__;                                                                                           \
    }
#define SD_OMP_EACH(par, nth, k, k0, k1, ...)                                                                  \
    do {                                                                                                       \
        const size_t k##_lo_ = (k0), k##_hi_ = (k1);                                                           \
        if (par) {                                                                                             \
            SD_PRAGMA(omp parallel for schedule(static) num_threads(nth))                                      \
            SD_LOOP_(k, __VA_ARGS__)                                                                           \
        } else                                                                                                 \
            SD_LOOP_(k, __VA_ARGS__)                                                                           \
    } while (0)

#define SD_PI SD_R(3.14159265358979323846)
#define SD_PI_D 3.14159265358979323846 /* always double: parameter set-up */

SD_HD static SD_INLINE sd_real sd_min(sd_real a, sd_real b) { return a < b ? a : b; }
SD_HD static SD_INLINE sd_real sd_max(sd_real a, sd_real b) { return a > b ? a : b; }
SD_HD static SD_INLINE sd_real sd_clamp(sd_real x, sd_real lo, sd_real hi)
{
    return x < lo ? lo : (x > hi ? hi : x);
}
SD_HD static SD_INLINE sd_real sd_sq(sd_real x) { return x * x; }

#endif
