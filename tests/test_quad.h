/* test_quad.h — Gauss-Legendre nodes and weights for the tests' own
 * reference integrals (independent of the library's quadrature in
 * src/shape/shape.c, so a test can judge it). Newton on the Legendre
 * recurrence from the usual cosine guess. */
#ifndef SD_TEST_QUAD_H
#define SD_TEST_QUAD_H
#include <math.h>


/* n nodes x[] on [-1, 1] in increasing order, weights w[]. */
static inline void gl_nodes(int n, double *x, double *w)
{
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double z = cos(3.14159265358979323846 * (i + 0.75) / (n + 0.5)), pp = 1;
        for (int it = 0; it < 100; ++it) {
            double p1 = 1, p2 = 0;
            for (int j = 1; j <= n; ++j) {
                double p3 = p2;
                p2 = p1;
                p1 = ((2.0 * j - 1) * z * p2 - (j - 1.0) * p3) / j;
            }
            pp = n * (z * p1 - p2) / (z * z - 1);
            double z1 = z;
            z = z1 - p1 / pp;
            if (fabs(z - z1) < 1e-16)
                break;
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        w[i] = w[n - 1 - i] = 2 / ((1 - z * z) * pp * pp);
    }
}

#endif
