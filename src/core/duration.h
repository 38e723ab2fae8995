/* duration.h — a wall-clock duration as people read it ("45s", "10m00s",
 * "2h05m"), for `check`'s run-time estimate and the run's progress line.
 *
 * Invariant: what is printed and what is compared are the same number.
 * sd_duration_shown rounds a duration to the precision the text shows
 * (whole seconds below an hour, whole minutes above), so a threshold
 * tested on the shown value never contradicts the text: 600.4 s prints
 * "10m00s" and is not "more than 10 minutes".
 */
#ifndef SD_CORE_DURATION_H
#define SD_CORE_DURATION_H

#include <stddef.h>

/* s rounded to what sd_duration_format shows (s; negative, NaN or
 * infinite: -1, shown as "--"). */
double sd_duration_shown(double s);

/* "--", "45s", "10m00s", "2h05m", "12 days" or "3.2e+04 years" for s
 * seconds (rounded as above). */
void sd_duration_format(double s, char *buf, size_t size);

#endif
