/* duration.c — durations as text (see duration.h): one rounding for the
 * text and for any comparison made on it. */
#include "core/duration.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define SD_DURATION_DAY 86400.0
#define SD_DURATION_YEAR (365.25 * SD_DURATION_DAY)

double sd_duration_shown(double s)
{
    if (!(s >= 0) || !isfinite(s))
        return -1;
    /* beyond three days in whole days, beyond a year in years to three
     * digits (a scene whose steps: is far too large: issue 31 printed "--") */
    if (s >= SD_DURATION_YEAR) {
        char buf[32];
        snprintf(buf, sizeof buf, "%.3g", s / SD_DURATION_YEAR);
        return strtod(buf, NULL) * SD_DURATION_YEAR;
    }
    if (s >= 3 * SD_DURATION_DAY)
        return SD_DURATION_DAY * round(s / SD_DURATION_DAY);
    double r = round(s); /* whole seconds: "59.6 s" is "1m00s", not "60s" */
    if (r >= 3600.0)     /* whole minutes above an hour: "1h29m59s" is "1h30m" */
        r = 60.0 * round(s / 60.0);
    return r;
}

void sd_duration_format(double s, char *buf, size_t size)
{
    double r = sd_duration_shown(s);
    if (r < 0) {
        snprintf(buf, size, "--");
        return;
    }
    if (r >= SD_DURATION_YEAR) {
        snprintf(buf, size, "%.3g years", r / SD_DURATION_YEAR);
        return;
    }
    if (r >= 3 * SD_DURATION_DAY) {
        snprintf(buf, size, "%.0f days", r / SD_DURATION_DAY);
        return;
    }
    long v = (long)r;
    if (v < 60)
        snprintf(buf, size, "%lds", v);
    else if (v < 3600)
        snprintf(buf, size, "%ldm%02lds", v / 60, v % 60);
    else
        snprintf(buf, size, "%ldh%02ldm", v / 3600, (v % 3600) / 60);
}
