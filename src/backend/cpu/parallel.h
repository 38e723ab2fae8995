/* parallel.h — the CPU backend's OpenMP loop pragmas.
 *
 * Invariant: static schedules give each thread the same block whatever the
 * run, dynamic ones hand out chunks in any order; both give the same bits
 * for any thread count because every item writes only its own slot
 * (DESIGN.md rule 4). Small worlds stay serial (sd_exec.parallel, decided
 * at rebuilds): forking threads costs more than it saves there.
 *
 * SD_CPU_FOR* take the sd_exec of a stage (backend/view.h). The older
 * SD_PARALLEL_FOR* read `w->threads` and `w->parallel` from the caller's
 * scope (a world, or any struct with those members); they moved here from
 * core/base.h so that the ground floor no longer knows the world's members.
 */
#ifndef SD_BACKEND_CPU_PARALLEL_H
#define SD_BACKEND_CPU_PARALLEL_H

#include "core/base.h"

#define SD_CPU_FOR(ex) SD_PRAGMA(omp parallel for schedule(static) num_threads((ex).threads) if ((ex).parallel))
/* items of very uneven cost (the convex narrow phase): dynamic chunks */
#define SD_CPU_FOR_DYNAMIC(ex) \
    SD_PRAGMA(omp parallel for schedule(dynamic, 64) num_threads((ex).threads) if ((ex).parallel))
#define SD_CPU_FOR_REDUCE_OR(ex, v) \
    SD_PRAGMA(omp parallel for schedule(static) num_threads((ex).threads) if ((ex).parallel) reduction(| : v))
#define SD_CPU_REGION(ex) SD_PRAGMA(omp parallel num_threads((ex).threads) if ((ex).parallel))

#define SD_PARALLEL_FOR SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel))
#define SD_PARALLEL_FOR_DYNAMIC \
    SD_PRAGMA(omp parallel for schedule(dynamic, 64) num_threads(w->threads) if (w->parallel))
#define SD_PARALLEL_FOR_REDUCE_OR(v) \
    SD_PRAGMA(omp parallel for schedule(static) num_threads(w->threads) if (w->parallel) reduction(| : v))

#endif
