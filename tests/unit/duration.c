/* duration.c — core/duration: the text of a duration and the value a
 * threshold is compared on agree (issue 31: `check` printed "run time about
 * 10m00s" and then warned that the run was "more than 10 minutes", the
 * text truncating 600.4 s while the warning compared the raw 600.4). */
#include "core/duration.h"
#include "test.h"

#include <string.h>

static void check_text(double s, const char *want)
{
    char buf[32];
    sd_duration_format(s, buf, sizeof buf);
    int ok = !strcmp(buf, want);
    printf("%-4s %12.3f s -> \"%s\" (expected \"%s\")\n", ok ? "ok" : "FAIL", s, buf, want);
    CHECK(ok);
}

int main(void)
{
    check_text(0.2, "0s");
    check_text(44.5, "45s");
    check_text(59.6, "1m00s");   /* not "60s" */
    check_text(600.4, "10m00s");
    check_text(600.6, "10m01s");
    check_text(659.7, "11m00s");  /* not "10m59s" */
    check_text(3599.6, "1h00m");  /* not "59m59s" or "60m00s" */
    check_text(5399.0, "1h30m");  /* 1h29m59s to the minute shown */
    check_text(-1.0, "--");
    check_text(NAN, "--");
    check_text(INFINITY, "--");
    /* beyond three days in days, beyond a year in years (issue 31: a
     * scene of steps: 9223372036854775807 printed "about --") */
    check_text(255600.0, "71h00m");
    check_text(2e7, "231 days");
    check_text(1e12, "3.17e+04 years");
    CHECK(sd_duration_shown(1e12) > 600.0); /* and the 10-minute warning still sees it */
    /* the 10-minute warning of `check` compares the shown value */
    CHECK(!(sd_duration_shown(600.4) > 600.0)); /* "10m00s" is not more than 10 minutes */
    CHECK(sd_duration_shown(600.6) > 600.0);    /* "10m01s" is */
    CHECK(sd_duration_shown(659.7) == 660.0);
    CHECK(sd_duration_shown(5399.0) == 5400.0);
    CHECK(sd_duration_shown(-3) < 0);
    return sd_test_summary();
}
