/* A reference B-spline basis for the tests that read surfaces back (shared
 * by the unit tests; independent of the library's own evaluation). */
#ifndef FM_TEST_BSPLINE_H
#define FM_TEST_BSPLINE_H

#include <stddef.h>

/* Cox-de Boor: the four non-zero cubic basis values at t (knots U, n
 * control points) into N, and the index of the first. */
static inline size_t fm_test_cubic_basis(const double *U, size_t n, double t, double N[4])
{
    size_t s = 3;
    while (s + 1 < n && U[s + 1] <= t)
        s++;
    double left[4], right[4];
    N[0] = 1;
    for (int j = 1; j <= 3; j++) {
        left[j] = t - U[s + 1 - (size_t)j];
        right[j] = U[s + (size_t)j] - t;
        double saved = 0;
        for (int r = 0; r < j; r++) {
            double tmp = N[r] / (right[r + 1] + left[j - r]);
            N[r] = saved + right[r + 1] * tmp;
            saved = left[j - r] * tmp;
        }
        N[j] = saved;
    }
    return s - 3;
}

#endif
