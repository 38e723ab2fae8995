/* test.h — the tiny test harness every test program shares.
 *
 * CHECK prints the failing expression with file and line and counts it;
 * CHECK_NEAR prints computed, expected and tolerance; a test's main ends
 * with `return sd_test_summary();`, which prints "N passed, M failed".
 */
#ifndef SD_TEST_H
#define SD_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <shapedem/shapedem.h>

static int sd_test_pass, sd_test_fail;

#define CHECK(cond)                                                             \
    do {                                                                        \
        if (cond) {                                                             \
            sd_test_pass++;                                                     \
        } else {                                                                \
            sd_test_fail++;                                                     \
            printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond);              \
        }                                                                       \
    } while (0)

/* |computed - expected| <= tol; prints a table row either way */
#define CHECK_NEAR(label, computed, expected, tol)                                               \
    do {                                                                                         \
        double c_ = (computed), e_ = (expected), t_ = (tol);                                     \
        int ok_ = fabs(c_ - e_) <= t_;                                                           \
        printf("%-4s %-44s computed %-14.8g expected %-14.8g error %-10.3g tol %.3g\n",          \
               ok_ ? "ok" : "FAIL", label, c_, e_, fabs(c_ - e_), t_);                          \
        if (ok_)                                                                                 \
            sd_test_pass++;                                                                      \
        else                                                                                     \
            sd_test_fail++;                                                                      \
    } while (0)

/* relative: |computed - expected| <= rel * |expected| */
#define CHECK_REL(label, computed, expected, rel) CHECK_NEAR(label, computed, expected, (rel) * fabs((double)(expected)))

#define CHECK_OK(expr)                                                          \
    do {                                                                        \
        sd_error e_;                                                            \
        sd_status s_ = (expr);                                                  \
        (void)e_;                                                               \
        CHECK(s_ == SD_OK);                                                     \
    } while (0)

static inline int sd_test_summary(void)
{
    printf("%d passed, %d failed\n", sd_test_pass, sd_test_fail);
    return sd_test_fail ? 1 : 0;
}

/* Aborts the test program with a message (set-up failures). */
static inline void sd_test_require(int ok, const char *what, const sd_error *err)
{
    if (ok)
        return;
    char buf[1024] = "";
    if (err)
        sd_error_format(err, buf, sizeof buf);
    printf("FAIL set-up: %s: %s\n", what, buf);
    exit(1);
}

static inline sd_v3d sd_test_v(double x, double y, double z)
{
    sd_v3d v = {x, y, z};
    return v;
}

/* The grid tests' material: [Naderi 2024]'s parameter set 1 (density
 * 2700 kg/m^3, k = 5e4 N/m, damping 0.5, k_t = k_n, mu = 0.5). */
static inline sd_material_def sd_test_material_set1(void)
{
    sd_material_def m = sd_material_def_default();
    m.name = "set1";
    m.density = 2700;
    m.stiffness = 50000;
    m.damping = 0.5;
    m.tangential_stiffness_ratio = 1;
    m.friction = 0.5;
    return m;
}

#endif
