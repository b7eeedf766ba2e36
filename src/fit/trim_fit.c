/* Regularised least squares for one piece: assembles the banded normal
 * equations and solves them with LAPACK's band Cholesky (dpbsv). */
#include "trim_internal.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>

#include <lapacke.h>

/* Position of unknown u (0 .. n-1, cyclic) in the order 0, n-1, 1, n-2, ...:
 * cyclic neighbours within p then sit within 2p + 1 of each other, so the
 * periodic system, banded but for its corners, becomes plainly banded. */
static size_t fold(size_t u, size_t n)
{
    size_t h = (n + 1) / 2;
    return u < h ? 2 * u : 2 * (n - 1 - u) + 1;
}

typedef struct band_system {
    size_t n, kd, ldab;
    double *ab;        /* upper band, column major: A(i, j) at ab[kd + i - j + j ldab] */
    double *rhs;       /* n x 2, column major */
    const long *map;   /* control index -> unknown, -1 for a fixed control */
    const double *fixed; /* 2 nctrl: fixed controls (relative) */
    int band_ok;
} band_system;

/* Adds w (sum_a A[a] c_{k+a}) . (sum_b B[b] c_{k+b} - q) to the normal
 * equations: the data term (A = B = values, q the point) and the smoothing
 * term (A = B = second derivatives, q = 0) both have this form. */
static void add_term(band_system *S, size_t k, const double *A, const double *B, double w,
                     const double q[2])
{
    for (int a = 0; a <= TRIM_P; a++) {
        long ia = S->map[k + a];
        if (ia < 0)
            continue;
        double wa = w * A[a];
        if (q) {
            S->rhs[ia] += wa * q[0];
            S->rhs[S->n + ia] += wa * q[1];
        }
        for (int b = 0; b <= TRIM_P; b++) {
            long ib = S->map[k + b];
            double c = wa * B[b];
            if (ib < 0) {
                S->rhs[ia] -= c * S->fixed[2 * (k + b)];
                S->rhs[S->n + ia] -= c * S->fixed[2 * (k + b) + 1];
            } else if (ia <= ib) {
                if ((size_t)(ib - ia) > S->kd) {
                    S->band_ok = 0;
                    continue;
                }
                S->ab[S->kd + (size_t)ia - (size_t)ib + (size_t)ib * S->ldab] += c;
            }
        }
    }
}

fm_status trim_fit_piece(const trim_input *in, trim_piece *pc, double beta, const char *name,
                         fm_error *err)
{
    enum { p = TRIM_P };
    if (trim_make_knots(pc) != FM_OK)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "trim: out of memory (knots)");
    size_t N = pc->nspans, nc = pc->nctrl;
    size_t n = pc->periodic ? N : nc - 2;
    size_t kd = pc->periodic ? 2 * p + 1 : p;
    if (kd > n - 1)
        kd = n - 1;
    if (n > INT_MAX / 4)
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "trim: %zu unknowns is too many", n);

    long *map = malloc(nc * sizeof *map);
    double *fixed = calloc(2 * nc, sizeof *fixed);
    double *ab = calloc((kd + 1) * n, sizeof *ab);
    double *rhs = calloc(2 * n, sizeof *rhs);
    if (!map || !fixed || !ab || !rhs) {
        free(map);
        free(fixed);
        free(ab);
        free(rhs);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "trim: out of memory (%zu unknowns)", n);
    }
    /* Coordinates relative to the first point keep the right-hand sides
     * small next to UTM offsets. */
    const double *o = trim_point(in, pc, 0);
    const double *last = trim_point(in, pc, pc->npts - 1);
    for (size_t c = 0; c < nc; c++)
        map[c] = pc->periodic ? (long)fold(c % N, N) : (long)c - 1;
    if (!pc->periodic) {
        map[nc - 1] = -1;
        fixed[2 * (nc - 1)] = last[0] - o[0];
        fixed[2 * (nc - 1) + 1] = last[1] - o[1];
    }
    band_system S = {n, kd, kd + 1, ab, rhs, map, fixed, 1};

    double B[3][p + 1];
    for (size_t j = 0; j < pc->npts; j++) {
        double tj = pc->t[j];
        double prev = j > 0 ? tj - pc->t[j - 1] : pc->periodic ? pc->len - pc->t[pc->npts - 1] : 0;
        double next = j + 1 < pc->npts ? pc->t[j + 1] - tj : pc->periodic ? pc->len - tj : 0;
        const double *P = trim_point(in, pc, j);
        double q[2] = {P[0] - o[0], P[1] - o[1]};
        size_t k = trim_span(pc, tj);
        trim_basis(pc, k, tj, 0, B);
        add_term(&S, k, B[0], B[0], 0.5 * (prev + next), q);
    }
    /* C'' is linear on a span, so three Gauss points integrate |C''|^2
     * exactly. */
    static const double gx[3] = {0.11270166537925831, 0.5, 0.88729833462074169};
    static const double gw[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
    for (size_t s = 0; s < N; s++) {
        double h = pc->brk[s + 1] - pc->brk[s];
        double lam = pc->mu * pow(beta * h / (2 * 3.14159265358979323846), 4);
        for (int g = 0; g < 3; g++) {
            double t = pc->brk[s] + gx[g] * h;
            trim_basis(pc, s, t, 2, B);
            add_term(&S, s, B[2], B[2], lam * h * gw[g], NULL);
        }
    }
    fm_status st = FM_OK;
    if (!S.band_ok) {
        st = fm_error_set(err, FM_ERR_NUMERIC, name, 0, "trim: normal matrix is not banded");
        goto done;
    }
    lapack_int info = LAPACKE_dpbsv(LAPACK_COL_MAJOR, 'U', (lapack_int)n, (lapack_int)kd, 2, ab,
                                    (lapack_int)(kd + 1), rhs, (lapack_int)n);
    if (info != 0) {
        st = fm_error_set(err, FM_ERR_NUMERIC, name, 0,
                          "trim: band Cholesky failed (info %d, %zu unknowns)", (int)info, n);
        goto done;
    }
    for (size_t c = 0; c < nc; c++) {
        if (map[c] < 0)
            continue;
        pc->ctrl[2 * c] = o[0] + rhs[map[c]];
        pc->ctrl[2 * c + 1] = o[1] + rhs[n + map[c]];
    }
    if (!pc->periodic) {
        pc->ctrl[0] = o[0];
        pc->ctrl[1] = o[1];
        pc->ctrl[2 * (nc - 1)] = last[0];
        pc->ctrl[2 * (nc - 1) + 1] = last[1];
    }
done:
    free(map);
    free(fixed);
    free(ab);
    free(rhs);
    return st;
}
