/* parallel.h — the CPU backend's OpenMP loop pragmas.
 *
 * Invariant: static schedules give each thread the same block whatever the
 * run, dynamic ones hand out chunks in any order; both give the same bits
 * for any thread count because every item writes only its own slot
 * (DESIGN.md rule 4). Small worlds stay serial (sd_exec.parallel, decided
 * at rebuilds): forking threads costs more than it saves there.
 *
 * SD_CPU_EACH* and SD_CPU_TEAM take the sd_exec of a stage (backend/view.h). The older
 * SD_PARALLEL_FOR* read `w->threads` and `w->parallel` from the caller's
 * scope (a world, or any struct with those members); they moved here from
 * core/base.h so that the ground floor no longer knows the world's members.
 */
#ifndef SD_BACKEND_CPU_PARALLEL_H
#define SD_BACKEND_CPU_PARALLEL_H

#include "core/base.h"

/* The step's loops in a serial world must not enter libgomp at all: a
 * region with if (0) still runs libgomp's team start and end, whose
 * closing barrier wakes its futex with a system call every time (about
 * 1-3 us on a virtual machine, several regions per step). In a world of a
 * few particles that was most of the step: the reactor example, filled
 * one particle a second, made 6.4 futex calls a step, most of them in the
 * step's loops (particles.c, pairs.c, walls.c), the rest in the rebuilds.
 * So those loops are written once as a body (core/base.h: SD_OMP_EACH)
 * and run as a plain loop when serial.
 *
 * SD_CPU_EACH(ex, k, k0, k1, body): for (size_t k = k0; k < k1; ++k) body,
 * static schedule when ex.parallel; SD_CPU_EACH_DYNAMIC: dynamic chunks
 * of 64 (items of uneven cost); SD_CPU_ANY(ex, v, k, k0, k1, body): the
 * same with v |= reduced over the threads. Each item writes only its own
 * slot, so the bits do not depend on which runs (the invariant above). */
#define SD_CPU_EACH(ex, k, k0, k1, ...) SD_OMP_EACH((ex).parallel, (ex).threads, k, k0, k1, __VA_ARGS__)
#define SD_CPU_EACH_DYNAMIC(ex, k, k0, k1, ...)                                                                \
    do {                                                                                                       \
        const size_t k##_lo_ = (k0), k##_hi_ = (k1);                                                           \
        if ((ex).parallel) {                                                                                   \
            SD_PRAGMA(omp parallel for schedule(dynamic, 64) num_threads((ex).threads))                        \
            SD_LOOP_(k, __VA_ARGS__)                                                                       \
        } else                                                                                                 \
            SD_LOOP_(k, __VA_ARGS__)                                                                       \
    } while (0)
#define SD_CPU_ANY(ex, v, k, k0, k1, ...)                                                                      \
    do {                                                                                                       \
        const size_t k##_lo_ = (k0), k##_hi_ = (k1);                                                           \
        if ((ex).parallel) {                                                                                   \
            SD_PRAGMA(omp parallel for schedule(static) num_threads((ex).threads) reduction(| : v))            \
            SD_LOOP_(k, __VA_ARGS__)                                                                       \
        } else                                                                                                 \
            SD_LOOP_(k, __VA_ARGS__)                                                                       \
    } while (0)
/* SD_CPU_TEAM(ex, call): call run by a team of ex.threads when
 * ex.parallel, else once on this thread; call's loops are orphaned
 * `omp for` constructs, which share out over the team or, outside any
 * region, run whole on one thread without a barrier's system call. */
#define SD_CPU_TEAM(ex, call)                                                                                  \
    do {                                                                                                       \
        if ((ex).parallel) {                                                                                   \
            SD_PRAGMA(omp parallel num_threads((ex).threads))                                                  \
            call;                                                                                              \
        } else                                                                                                 \
            call;                                                                                              \
    } while (0)
#define SD_PARALLEL_FOR SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel))
#define SD_PARALLEL_FOR_DYNAMIC \
    SD_PRAGMA(omp parallel for schedule(dynamic, 64) num_threads(w->threads) if (w->parallel))
#define SD_PARALLEL_FOR_REDUCE_OR(v) \
    SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel) reduction(| : v))

#endif
