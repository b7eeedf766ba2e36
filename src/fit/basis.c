/* Uniform B-spline basis on integer knots and the exact Gram matrices of
 * its derivatives over one span. */
#include "fit_internal.h"

#include <math.h>
#include <string.h>

/* On unit-spaced knots the span of interest is [p, p+1] and the degree-q
 * splines alive there are N_{i,q}, i = p-q..p, supported on [i, i+q+1].
 * The Cox-de Boor recurrence reduces to
 *     N_{i,q}(x) = ((x - i) N_{i,q-1}(x) + (i + q + 1 - x) N_{i+1,q-1}(x)) / q
 * and derivatives to finite differences of lower degrees:
 *     N'_{i,q} = N_{i,q-1} - N_{i+1,q-1},
 *     N''_{i,q} = N_{i,q-2} - 2 N_{i+1,q-2} + N_{i+2,q-2}. */
static void basis_general(int p, double t, double N[3][FM_FIT_MAX_DEGREE + 1], int kmax)
{
    /* B[q][i] = N_{i,q}(p + t) for i = 0..p (zero where not alive). */
    double B[FM_FIT_MAX_DEGREE + 1][FM_FIT_MAX_DEGREE + 2];
    memset(B, 0, sizeof B);
    double x = p + t;
    B[0][p] = 1.0;
    for (int q = 1; q <= p; q++)
        for (int i = p - q; i <= p; i++) {
            double left = (x - i) * B[q - 1][i];
            double right = (i + q + 1 - x) * B[q - 1][i + 1];
            B[q][i] = (left + right) / q;
        }
    for (int i = 0; i <= p; i++) {
        N[0][i] = B[p][i];
        if (kmax < 3)
            continue;
        N[1][i] = B[p - 1][i] - B[p - 1][i + 1];
        N[2][i] = B[p - 2][i] - 2 * B[p - 2][i + 1] + (i + 2 <= p ? B[p - 2][i + 2] : 0.0);
    }
}

/* The cubic case written out (it is the default and runs per sample). */
static void basis_cubic(double t, double N[3][FM_FIT_MAX_DEGREE + 1], int kmax)
{
    double s = 1 - t, t2 = t * t, t3 = t2 * t;
    N[0][0] = s * s * s / 6;
    N[0][1] = (3 * t3 - 6 * t2 + 4) / 6;
    N[0][2] = (-3 * t3 + 3 * t2 + 3 * t + 1) / 6;
    N[0][3] = t3 / 6;
    if (kmax < 3)
        return;
    N[1][0] = -0.5 * s * s;
    N[1][1] = 1.5 * t2 - 2 * t;
    N[1][2] = -1.5 * t2 + t + 0.5;
    N[1][3] = 0.5 * t2;
    N[2][0] = s;
    N[2][1] = 3 * t - 2;
    N[2][2] = 1 - 3 * t;
    N[2][3] = t;
}

void fm_fit_basis(int p, double t, double N[3][FM_FIT_MAX_DEGREE + 1])
{
    if (p == 3)
        basis_cubic(t, N, 3);
    else
        basis_general(p, t, N, 3);
}

void fm_fit_basis_values(int p, double t, double N[3][FM_FIT_MAX_DEGREE + 1])
{
    if (p == 3)
        basis_cubic(t, N, 1);
    else
        basis_general(p, t, N, 1);
}

/* Gauss-Legendre nodes and weights on [0, 1] by Newton on P_n. */
static void gauss01(int n, double *x, double *w)
{
    for (int k = 0; k < n; k++) {
        double z = cos(3.14159265358979323846 * (k + 0.75) / (n + 0.5));
        double dp = 1;
        for (int it = 0; it < 100; it++) {
            double p0 = 1, p1 = z;
            for (int j = 2; j <= n; j++) {
                double p2 = ((2 * j - 1) * z * p1 - (j - 1) * p0) / j;
                p0 = p1;
                p1 = p2;
            }
            if (n == 1)
                p1 = z, p0 = 1;
            dp = n * (z * p1 - p0) / (z * z - 1);
            double dz = p1 / dp;
            z -= dz;
            if (fabs(dz) < 1e-16)
                break;
        }
        x[k] = 0.5 * (1 - z);
        w[k] = 1.0 / ((1 - z * z) * dp * dp);
    }
}

void fm_fit_span_gram(int p, double M[3][FM_FIT_MAX_DEGREE + 1][FM_FIT_MAX_DEGREE + 1])
{
    /* Products of degree 2p need p + 1 points to be integrated exactly. */
    int n = p + 1;
    double x[FM_FIT_MAX_DEGREE + 1], w[FM_FIT_MAX_DEGREE + 1];
    gauss01(n, x, w);
    memset(M, 0, sizeof(double) * 3 * (FM_FIT_MAX_DEGREE + 1) * (FM_FIT_MAX_DEGREE + 1));
    for (int g = 0; g < n; g++) {
        double N[3][FM_FIT_MAX_DEGREE + 1];
        fm_fit_basis(p, x[g], N);
        for (int k = 0; k < 3; k++)
            for (int a = 0; a <= p; a++)
                for (int b = 0; b <= p; b++)
                    M[k][a][b] += w[g] * N[k][a] * N[k][b];
    }
}

size_t fm_fit_locate(double x, double x0, double s, size_t n, double *t)
{
    double r = (x - x0) / s;
    double f = floor(r);
    size_t j;
    if (!(f >= 0))
        j = 0;
    else if (f >= (double)n)
        j = n - 1;
    else
        j = (size_t)f;
    *t = r - (double)j;
    return j;
}
