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

/* One precision for state, chosen at build time (STYLE.md convention 6). */
#if defined(SHAPEDEM_SINGLE)
typedef float sd_real;
#define SD_R(x) x##f
#define sd_sqrt sqrtf
#define sd_fabs fabsf
#define sd_sin sinf
#define sd_cos cosf
#define sd_atan2 atan2f
#define sd_log logf
#define sd_exp expf
#define sd_pow powf
#define sd_floor floorf
#else
typedef double sd_real;
#define SD_R(x) x
#define sd_sqrt sqrt
#define sd_fabs fabs
#define sd_sin sin
#define sd_cos cos
#define sd_atan2 atan2
#define sd_log log
#define sd_exp exp
#define sd_pow pow
#define sd_floor floor
#endif

/* A pragma from a macro (the CPU backend's OpenMP loops build theirs with
 * it: backend/cpu/parallel.h). */
#define SD_PRAGMA(x) _Pragma(#x)

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
