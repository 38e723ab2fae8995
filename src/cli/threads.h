/* threads.h — how many OpenMP threads `run` and `check` use, why, and how
 * the threads wait for each other (cli/threads.c). */
#ifndef SD_CLI_THREADS_H
#define SD_CLI_THREADS_H

#include <stddef.h>

/* Called first in main for run and check, before any OpenMP region: looks
 * at how busy the machine is and, when the threads asked for would not all
 * find a free core and the user set neither OMP_WAIT_POLICY nor
 * GOMP_SPINCOUNT, starts this program again with OMP_WAIT_POLICY=passive
 * (libgomp reads it only when it loads). argv as main's; cli_threads the
 * Returns only when it did not start the program again. */
void sd_threads_start(int argc, char **argv);

/* The scene's simulation.threads (when no --threads overrides it), once
 * the scene is read and before any OpenMP region: more than the free cores
 * starts the program again waiting passively, as sd_threads_start does. */
void sd_threads_scene(int scene_threads);

/* The thread count a run uses when neither --threads, simulation.threads
 * nor OMP_NUM_THREADS says: the cores not busy with other processes at the
 * start, at least 1; 0 when OMP_NUM_THREADS is set (OpenMP's own default)
 * or sd_threads_start was not called. Called only when the count is used. */
int sd_threads_default(void);

/* "2 threads (all 2 cores)", "1 thread (--threads 1)", "1 thread (1 of 2
 * cores: 1.0 busy with other processes at the start)", "4 threads (from
 * OMP_NUM_THREADS)", "2 threads (simulation.threads)", then how they wait
 * when not libgomp's default ("; waiting passively: ..."). cli_threads:
 * --threads (<= 0 not given); scene_threads: simulation.threads (0 none);
 * used: the world's count. */
void sd_threads_describe(long cli_threads, int scene_threads, int used, char *buf, size_t size);

#endif
