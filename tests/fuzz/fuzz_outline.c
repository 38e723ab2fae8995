/* fuzz_outline.c — libFuzzer target: the outline reader of the Fourier
 * fit (sd_outline_read_csv, shape/outline.c) and the fit itself
 * (sd_fourier_fit_outline, seed 002 §2.3: check, hull, least squares,
 * reduction, coverage), what `shapedem shape fit-fourier FILE` runs,
 * with a coarser sampling (below).
 *
 * The input is the outline CSV. Besides the sanitizers it checks
 * outline.h's invariant (on SD_OK at least 3 finite points) and that a
 * fit that succeeds has finite coefficients with a_0 > 0.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "fuzz_util.h"
#include "shape/fourier.h"
#include "shape/outline.h"

#define SD_FUZZ_CHECK(c)                                                                                         \
    do {                                                                                                         \
        if (!(c)) {                                                                                              \
            fprintf(stderr, "fuzz_outline: invariant failed: %s\n", #c);                                         \
            __builtin_trap();                                                                                    \
        }                                                                                                        \
    } while (0)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[1024];
    sd_fuzz_write("outline.csv", data, size, path, sizeof path);
    sd_vec2 *pts = NULL;
    size_t n = 0;
    sd_error err;
    memset(&err, 0, sizeof err);
    sd_status st = sd_outline_read_csv(path, &pts, &n, &err);
    sd_fuzz_report("sd_outline_read_csv", st, &err);
    if (st != SD_OK) {
        SD_FUZZ_CHECK(err.msg[0] && !pts && n == 0);
        return 0;
    }
    SD_FUZZ_CHECK(n >= 3);
    for (size_t i = 0; i < n; ++i)
        SD_FUZZ_CHECK(isfinite(pts[i].x) && isfinite(pts[i].y));
    /* fewer support directions and convexity grid points than the
     * defaults (720, 4096): the same code paths at ~10x the fuzzer's
     * speed; a fit needs directions > 2N + 1 = 17 */
    sd_fourier_fit_opts o = sd_fourier_fit_opts_default();
    o.directions = 90;
    o.grid = 512;
    sd_fourier_fit f;
    memset(&err, 0, sizeof err);
    st = sd_fourier_fit_outline(pts, n, &o, &f, &err);
    sd_fuzz_report("sd_fourier_fit_outline", st, &err);
    if (st == SD_OK) {
        SD_FUZZ_CHECK(f.a[0] > 0);
        for (int k = 0; k <= f.order; ++k)
            SD_FUZZ_CHECK(isfinite(f.a[k]) && isfinite(f.b[k]));
    } else {
        SD_FUZZ_CHECK(err.msg[0]);
    }
    sd_free(pts);
    return 0;
}
