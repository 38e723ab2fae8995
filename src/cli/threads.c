/* threads.c — the thread count and OpenMP's wait policy of `run` and
 * `check` (threads.h).
 *
 * Why: the step runs dozens of short OpenMP regions (backend/cpu/,
 * world/rebuild.c); at each one's end a thread that arrives first waits
 * for the others. libgomp's default is to spin 300,000 times before it
 * sleeps. On a machine whose cores are all busy (another run, a build)
 * the thread it waits for is not running, so the spinning burns the very
 * time slice that thread needs: on the project's 2-core VM under load
 * (bench/threads_load) 2 threads took 10x the time of 1. Sleeping at once
 * (OMP_WAIT_POLICY=passive) cures that, but on an idle machine each region
 * then pays a futex wake-up and 2 threads ran 2x slower than with
 * spinning, slower than 1 thread. So the choice depends on whether the
 * threads will find free cores:
 *   - the default count is the cores not busy with other processes at the
 *     start (at least 1), so a default run never oversubscribes and keeps
 *     libgomp's spinning;
 *   - a count asked for (--threads, OMP_NUM_THREADS) above the free cores
 *     waits passively, unless the user set OMP_WAIT_POLICY or
 *     GOMP_SPINCOUNT (then theirs).
 * libgomp reads its environment once, when it is loaded, so the policy is
 * set by starting the program again with it (execv of /proc/self/exe, a
 * millisecond). Busy cores are the runnable tasks of /proc/stat
 * (procs_running, this process's one thread left out), averaged over five
 * samples 10 ms apart: the instantaneous count, where the load average
 * trails a load that has just started or ended by a minute.
 * simulation.threads is known only once the scene is read: a scene asking
 * for more threads than free cores starts the program again then, before
 * the world is built (sd_threads_scene). None of this changes results: the bits are
 * the same on any thread count (docs/physics.md, determinism). */
#define _GNU_SOURCE /* sched_getaffinity, CPU_COUNT */

#include "cli/threads.h"

#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* carried across the restart: "cores busy passive", so that the child
 * neither samples again nor takes the policy for the user's */
#define SD_THREADS_ENV "SHAPEDEM_THREADS_PLAN"

static struct {
    int known;   /* sampled (or carried) */
    int cores;   /* CPUs this process may run on */
    double busy; /* other runnable tasks at the start */
    int passive; /* OMP_WAIT_POLICY=passive set here */
    int applied; /* sd_threads_default gave the scene its count */
    char **argv; /* main's, to start again with */
} sd_plan;

static int sd_threads_cores(void)
{
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0)
        return CPU_COUNT(&set);
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (int)n : 1;
}

/* runnable tasks now (procs_running of /proc/stat), -1 unknown */
static int sd_threads_running(void)
{
    FILE *f = fopen("/proc/stat", "r");
    if (!f)
        return -1;
    char line[256];
    int n = -1;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "procs_running %d", &n) == 1)
            break;
    fclose(f);
    return n;
}

static double sd_threads_busy(void)
{
    double sum = 0;
    int got = 0;
    for (int k = 0; k < 5; ++k) {
        if (k) {
            struct timespec ts = {0, 10000000};
            nanosleep(&ts, NULL);
        }
        int n = sd_threads_running();
        if (n >= 1) {
            sum += n - 1; /* this process, running as it reads */
            got++;
        }
    }
    return got ? sum / got : 0.0;
}

static int sd_threads_free(void)
{
    int free_cores = sd_plan.cores - (int)(sd_plan.busy + 0.5);
    return free_cores < 1 ? 1 : free_cores;
}

static long sd_threads_asked(int argc, char **argv)
{
    for (int k = 2; k + 1 < argc; ++k)
        if (!strcmp(argv[k], "--threads"))
            return strtol(argv[k + 1], NULL, 10); /* checked later by the parser */
    const char *env = getenv("OMP_NUM_THREADS");
    return env && *env ? strtol(env, NULL, 10) : 0;
}

/* Starts the program again waiting passively, when the user left the wait
 * to us and it is not an MPI rank; returns when it did not. */
static void sd_threads_restart(void)
{
    if (!sd_plan.argv || sd_plan.passive)
        return;
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT"))
        return; /* the user's choice */
    if (getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMI_SIZE"))
        return; /* an MPI rank: not restarted under its launcher */
    /* under valgrind /proc/self/exe is valgrind's tool, which refuses to be
     * started directly: the run would end there (memcheck.run_short) */
    const char *preload = getenv("LD_PRELOAD");
    if (preload && strstr(preload, "vgpreload"))
        return;
    char plan[96];
    snprintf(plan, sizeof plan, "%d %.2f 1", sd_plan.cores, sd_plan.busy);
    if (setenv("OMP_WAIT_POLICY", "passive", 1) || setenv(SD_THREADS_ENV, plan, 1))
        return;
    execv("/proc/self/exe", sd_plan.argv);
    /* could not start again: go on spinning, and say nothing set it */
    unsetenv("OMP_WAIT_POLICY");
    unsetenv(SD_THREADS_ENV);
}

void sd_threads_start(int argc, char **argv)
{
    sd_plan.argv = argv;
    const char *carried = getenv(SD_THREADS_ENV);
    if (carried && sscanf(carried, "%d %lf %d", &sd_plan.cores, &sd_plan.busy, &sd_plan.passive) == 3 &&
        sd_plan.cores >= 1) {
        sd_plan.known = 1;
        unsetenv(SD_THREADS_ENV); /* not for the programs this one starts */
        return;
    }
    sd_plan.cores = sd_threads_cores();
    sd_plan.busy = sd_threads_busy();
    sd_plan.known = 1;
    long asked = sd_threads_asked(argc, argv);
    if (asked > 1 && asked > sd_threads_free())
        sd_threads_restart(); /* else the default count, one thread, or enough free cores: spinning */
}

void sd_threads_scene(int scene_threads)
{
    if (sd_plan.known && scene_threads > 1 && scene_threads > sd_threads_free())
        sd_threads_restart();
}

int sd_threads_default(void)
{
    const char *env = getenv("OMP_NUM_THREADS");
    if (env && *env)
        return 0;
    if (!sd_plan.known)
        return 0;
    sd_plan.applied = 1;
    return sd_threads_free();
}

void sd_threads_describe(long cli_threads, int scene_threads, int used, char *buf, size_t size)
{
    const char *s = used == 1 ? "" : "s";
    const char *env = getenv("OMP_NUM_THREADS");
    size_t n;
    if (cli_threads > 0)
        n = (size_t)snprintf(buf, size, "%d thread%s (--threads %ld)", used, s, cli_threads);
    else if (scene_threads > 0 && !sd_plan.applied)
        n = (size_t)snprintf(buf, size, "%d thread%s (simulation.threads)", used, s);
    else if (env && *env && !sd_plan.applied)
        n = (size_t)snprintf(buf, size, "%d thread%s (from OMP_NUM_THREADS)", used, s);
    else if (sd_plan.known && sd_threads_free() < sd_plan.cores)
        n = (size_t)snprintf(buf, size,
                             "%d thread%s (%d of %d cores free: other processes kept %.1f busy at the start)", used, s,
                             sd_threads_free(), sd_plan.cores, sd_plan.busy);
    else
        n = (size_t)snprintf(buf, size, "%d thread%s (all %d cores)", used, s, sd_plan.known ? sd_plan.cores : used);
    if (n >= size || used <= 1)
        return;
    const char *wp = getenv("OMP_WAIT_POLICY"), *sc = getenv("GOMP_SPINCOUNT");
    if (sd_plan.passive)
        snprintf(buf + n, size - n, "; waiting passively: more threads than free cores (%d cores, %.1f busy)",
                 sd_plan.cores, sd_plan.busy);
    else if (wp || sc)
        snprintf(buf + n, size - n, "; waiting as %s%s%s%s", wp ? "OMP_WAIT_POLICY=" : "", wp ? wp : "",
                 sc ? (wp ? ", GOMP_SPINCOUNT=" : "GOMP_SPINCOUNT=") : "", sc ? sc : "");
}
