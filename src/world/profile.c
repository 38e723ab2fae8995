/* profile.c — the clock and the public queries of the per-stage profile
 * (profile.h; the stages are SD_PROFILE_STAGES of shapedem.h).
 *
 * Invariant: times only grow, by non-negative differences of a monotonic
 * clock; a call counts one run of its stage.
 */
#define _POSIX_C_SOURCE 200809L

#include "world/profile.h"

#include <string.h>
#include <time.h>

double sd_profile_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void sd_world_profile(const sd_world *w, sd_profile *out)
{
    if (!out)
        return;
    if (!w) {
        memset(out, 0, sizeof *out);
        return;
    }
    *out = w->profile;
}

void sd_world_profile_add(sd_world *w, sd_profile_stage stage, double seconds)
{
    if (!w || (int)stage < 0 || stage >= SD_PROFILE_STAGE_COUNT)
        return;
    w->profile.seconds[stage] += seconds > 0 ? seconds : 0.0;
    w->profile.calls[stage] += 1;
}

const char *sd_profile_stage_name(int stage)
{
    static const char *const names[] = {
#define SD_X_PROFILE(NAME, name, doc) #name,
        SD_PROFILE_STAGES(SD_X_PROFILE)
#undef SD_X_PROFILE
    };
    return stage >= 0 && stage < SD_PROFILE_STAGE_COUNT ? names[stage] : NULL;
}
