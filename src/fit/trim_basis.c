/* B-splines on the general knot vectors of the pieces (refinement makes
 * them non-uniform): span search, basis values and derivatives
 * (Cox-de Boor with the triangular table of Piegl and Tiller's
 * "The NURBS Book", algorithm A2.3, written anew), evaluation. */
#include "trim_internal.h"

#include <math.h>
#include <stdlib.h>

double trim_wrap(const trim_piece *pc, double t)
{
    if (pc->periodic) {
        t = fmod(t, pc->len);
        if (t < 0)
            t += pc->len;
        /* fmod of a tiny negative can round up to len itself. */
        return t < pc->len ? t : 0.0;
    }
    return t < 0 ? 0 : t > pc->len ? pc->len : t;
}

size_t trim_span(const trim_piece *pc, double t)
{
    size_t lo = 0, hi = pc->nspans;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (pc->brk[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

void trim_basis(const trim_piece *pc, size_t k, double t, int nd, double ders[3][TRIM_P + 1])
{
    enum { p = TRIM_P };
    const double *U = pc->knots + k + p; /* U[0] is the span's left knot */
    /* ndu[j][r], r < j: knot differences; r >= j: basis of degree r. */
    double ndu[p + 1][p + 1], left[p + 1], right[p + 1];
    ndu[0][0] = 1;
    for (int j = 1; j <= p; j++) {
        left[j] = t - U[1 - j];
        right[j] = U[j] - t;
        double saved = 0;
        for (int r = 0; r < j; r++) {
            ndu[j][r] = right[r + 1] + left[j - r];
            double temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for (int j = 0; j <= p; j++)
        ders[0][j] = ndu[j][p];
    double a[2][p + 1];
    for (int r = 0; r <= p; r++) {
        int s1 = 0, s2 = 1;
        a[0][0] = 1;
        for (int kk = 1; kk <= nd; kk++) {
            double d = 0;
            int rk = r - kk, pk = p - kk;
            if (r >= kk) {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            int j1 = rk >= -1 ? 1 : -rk;
            int j2 = r - 1 <= pk ? kk - 1 : p - r;
            for (int j = j1; j <= j2; j++) {
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
                d += a[s2][j] * ndu[rk + j][pk];
            }
            if (r <= pk) {
                a[s2][kk] = -a[s1][kk - 1] / ndu[pk + 1][r];
                d += a[s2][kk] * ndu[r][pk];
            }
            ders[kk][r] = d;
            int tmp = s1;
            s1 = s2;
            s2 = tmp;
        }
    }
    double f = p;
    for (int kk = 1; kk <= nd; kk++) {
        for (int j = 0; j <= p; j++)
            ders[kk][j] *= f;
        f *= p - kk;
    }
}

void trim_eval(const trim_piece *pc, double t, int nd, double out[3][2])
{
    t = trim_wrap(pc, t);
    size_t k = trim_span(pc, t);
    double N[3][TRIM_P + 1];
    trim_basis(pc, k, t, nd, N);
    for (int d = 0; d <= nd; d++) {
        double x = 0, y = 0;
        for (int j = 0; j <= TRIM_P; j++) {
            x += N[d][j] * pc->ctrl[2 * (k + j)];
            y += N[d][j] * pc->ctrl[2 * (k + j) + 1];
        }
        out[d][0] = x;
        out[d][1] = y;
    }
    /* The basis sums to one only up to rounding; a clamped piece must end
     * on its corners exactly so that pieces meet without a gap. */
    if (!pc->periodic && (t <= 0 || t >= pc->len)) {
        const double *c = pc->ctrl + (t <= 0 ? 0 : 2 * (pc->nctrl - 1));
        out[0][0] = c[0];
        out[0][1] = c[1];
    }
}

fm_status trim_make_knots(trim_piece *pc)
{
    enum { p = TRIM_P };
    size_t N = pc->nspans;
    free(pc->knots);
    free(pc->ctrl);
    pc->nctrl = N + p;
    pc->nknots = N + 2 * p + 1;
    pc->knots = malloc(pc->nknots * sizeof *pc->knots);
    pc->ctrl = calloc(2 * pc->nctrl, sizeof *pc->ctrl);
    if (!pc->knots || !pc->ctrl)
        return FM_ERR_NOMEM;
    double *K = pc->knots;
    for (size_t i = 0; i <= N; i++)
        K[p + i] = pc->brk[i];
    for (size_t i = 1; i <= p; i++) {
        if (pc->periodic) {
            /* Periodic extension: the spans beyond either end repeat those at
             * the other, so basis functions wrap round the loop. */
            K[p - i] = pc->brk[N - i] - pc->len;
            K[N + p + i] = pc->brk[i] + pc->len;
        } else {
            K[p - i] = pc->brk[0];
            K[N + p + i] = pc->brk[N];
        }
    }
    return FM_OK;
}
