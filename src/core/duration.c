/* duration.c — durations as text (see duration.h): one rounding for the
 * text and for any comparison made on it. */
#include "core/duration.h"

#include <math.h>
#include <stdio.h>

double sd_duration_shown(double s)
{
    if (!(s >= 0) || s > 1e7)
        return -1;
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
    long v = (long)r;
    if (v < 60)
        snprintf(buf, size, "%lds", v);
    else if (v < 3600)
        snprintf(buf, size, "%ldm%02lds", v / 60, v % 60);
    else
        snprintf(buf, size, "%ldh%02ldm", v / 3600, (v % 3600) / 60);
}
