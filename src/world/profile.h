/* profile.h — the step's per-stage wall time (sd_profile, STYLE.md
 * convention 9), kept in the world: a monotonic clock read at stage
 * boundaries (profile.c), never inside a loop over particles or pairs. */
#ifndef SD_WORLD_PROFILE_H
#define SD_WORLD_PROFILE_H

#include "world/world.h"

/* s, a monotonic clock (CLOCK_MONOTONIC): only differences mean anything. */
double sd_profile_now(void);

/* Ends a stage that began at *t: adds its time (and one call when count)
 * and starts the next stage at the same instant, so one clock read serves
 * both boundaries. */
static inline void sd_profile_lap(sd_world *w, sd_profile_stage stage, double *t, int count)
{
    double now = sd_profile_now();
    w->profile.seconds[stage] += now - *t;
    w->profile.calls[stage] += count;
    *t = now;
}

#endif
