/* Knot removal within a bound: fewer control points for a surface that
 * stays within a chosen distance of the one given.
 *
 * Why: a surface's control net is nearly all of an IGES file (a 128 is
 * some 50 bytes a control point), and where a fitted surface is smooth
 * across a knot, that knot carries nothing the tolerance can see.
 *
 * Removing one knot (Tiller, "Knot-removal algorithms for NURBS curves
 * and surfaces", CAD 24(8), 1992; The NURBS Book, 2nd ed., 5.4): along
 * one direction each row of control points is a B-spline curve. Removing
 * the knot u = U_r of multiplicity s once leaves control points Q, one
 * fewer; inserting u back into them (exact) gives P', equal to P but at
 * k = r - p .. r - s, where
 *     P'_k = a_k Q_k + (1 - a_k) Q_(k-1),   a_k = (u - U_k) / (U_(k+p+1) - U_k),
 * m = p - s + 1 equations for m - 1 unknown points (the outer Q are P's
 * neighbours). One vector condition is left over: with z the left null
 * vector of the system (z_0 = 1, z_(k+1) = -z_k a_k / (1 - a_(k+1))), the
 * differences D = P - P' satisfy sum z_k D_k = C (C = sum z_k b_k, b the
 * P with the known neighbours moved over) whatever Q is. The smallest
 * largest |D_k| is |C| / sum |z_k|, reached with D_k = sign(z_k) C /
 * sum |z_k|; Q then solves the equations for P - D, swept from both ends
 * towards the middle as in Tiller's algorithm.
 *
 * The bound: the old curve minus the new one is sum_k D_k N_k(t) on the
 * old knots; the N_k are non-negative and sum to 1, so the difference is
 * at most max |D_k|, and nothing outside the support [U_(r-p),
 * U_(r-s+p+1)] of the changed N_k. For the surface, S - S' = sum_j N_j(v)
 * sum_k D_kj N_k(u): at (u, v) at most the largest |D_kj| over the rows j
 * whose N_j(v) is non-zero. D is measured from the Q actually computed (P'
 * by insertion), so the rounding of the solve is in it (what is left, the
 * rounding of that insertion, is some 1e-16 of the coordinates).
 *
 * Removals add up (triangle inequality), so the bound is kept per cell of
 * the given knot grid: each removal adds its bound on the cell (the
 * largest |D| over the rows active there) to every cell of its support,
 * and a knot is removed only when no cell of the parameter range goes
 * over the budget. The surface written is then within the budget of the
 * given one at every point of its range, for u and v removals together.
 *
 * Order: sweeps over the knots of both directions remove each knot whose
 * own bound is within a threshold and that fits the budget, the threshold
 * doubling from budget / 128 to budget, so that the cheapest knots go
 * first (a removal spends budget its neighbours might use better).
 * Rational nets are left alone (their bound would need the weights).
 *
 * A knot's own bound depends only on the points and knots near it, and
 * few knots are removed: each bound is kept until a removal changes what
 * it was computed from, so that the sweeps of the eight thresholds cost
 * about one evaluation of every knot, with the same removals in the same
 * order as evaluating each knot at every visit. */
#include "iges_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_P 25 /* the writer's degree limit */
#define LEVELS 8 /* thresholds budget / 2^7 .. budget */

typedef struct reducer {
    iges_net *net;
    double budget;
    double *brk[2];         /* the given net's distinct knots, per direction */
    size_t ncell[2];        /* cells: the spans between them */
    unsigned char *live[2]; /* the cell meets the parameter range: its bound counts */
    double *acc;            /* ncell[0] x ncell[1], u fastest: the bound so far */
    size_t *span;           /* per cell across: the current span holding it */
    double *e;              /* per row: the candidate's largest |D| */
    double *inc;            /* per cell across: the candidate's bound there */
    double *q;              /* per row: the candidate's new points, MAX_P each */
    double *tmp;            /* one row of the net */
    double *known[2];       /* per knot index: its removal's bound, NAN = to compute */
} reducer;

static size_t count(const iges_net *n, int d) { return d ? n->nv : n->nu; }
static int degree(const iges_net *n, int d) { return d ? n->pv : n->pu; }
static double *knots(const iges_net *n, int d) { return d ? n->knots_v : n->knots_u; }

/* Control point i along direction d in row j (across it). */
static double *point(const iges_net *n, int d, size_t i, size_t j)
{
    return n->ctrl + 3 * (d ? i * n->nu + j : j * n->nu + i);
}

/* The cell of brk starting at the knot value x (a knot of the given net). */
static size_t cell_of(const double *brk, size_t ncell, double x)
{
    size_t lo = 0, hi = ncell;
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (brk[mid] < x)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* Span index, in the current knots across d, of every cell across. */
static void spans_across(reducer *rd, int d)
{
    int o = 1 - d, p = degree(rd->net, o);
    const double *V = knots(rd->net, o);
    size_t n = count(rd->net, o), t = (size_t)p;
    for (size_t c = 0; c < rd->ncell[o]; c++) {
        while (t + 1 < n && V[t + 1] <= rd->brk[o][c])
            t++;
        rd->span[c] = t;
    }
}

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* The removal of U_r (multiplicity s) along d, computed into rd->q; its
 * bound per cell across into rd->inc. Returns its largest bound (cost);
 * *fits is 1 when the cells of the range stay within the budget. */
static double evaluate(reducer *rd, int d, size_t r, size_t s, int *fits)
{
    const iges_net *net = rd->net;
    int p = degree(net, d), o = 1 - d, po = degree(net, o);
    const double *U = knots(net, d);
    size_t first = r - (size_t)p, last = r - s, m = last - first + 1, rows = count(net, o);
    double u = U[r], a[MAX_P + 1], z[MAX_P + 1], zs = 0;
    for (size_t k = 0; k < m; k++)
        a[k] = (u - U[first + k]) / (U[first + k + (size_t)p + 1] - U[first + k]);
    z[0] = 1;
    for (size_t k = 0; k + 1 < m; k++)
        z[k + 1] = -z[k] * a[k] / (1 - a[k + 1]);
    for (size_t k = 0; k < m; k++)
        zs += fabs(z[k]);
    size_t h = (m - 1) / 2; /* Q_0 .. Q_(h-1) from the left, the rest from the right */
    for (size_t j = 0; j < rows; j++) {
        double b[MAX_P + 1][3], c[3] = {0, 0, 0};
        const double *left = point(net, d, first - 1, j), *right = point(net, d, last + 1, j);
        for (size_t k = 0; k < m; k++)
            memcpy(b[k], point(net, d, first + k, j), sizeof b[k]);
        for (int x = 0; x < 3; x++) {
            b[0][x] -= (1 - a[0]) * left[x];
            b[m - 1][x] -= a[m - 1] * right[x];
        }
        for (size_t k = 0; k < m; k++)
            for (int x = 0; x < 3; x++)
                c[x] += z[k] * b[k][x];
        for (size_t k = 0; k < m; k++)
            for (int x = 0; x < 3; x++)
                b[k][x] -= (z[k] > 0 ? c[x] : -c[x]) / zs;
        double *Q = rd->q + 3 * MAX_P * j;
        for (size_t k = 0; k < h; k++)
            for (int x = 0; x < 3; x++)
                Q[3 * k + (size_t)x] =
                    (b[k][x] - (k ? (1 - a[k]) * Q[3 * (k - 1) + (size_t)x] : 0)) / a[k];
        for (size_t k = m - 1; k > h; k--)
            for (int x = 0; x < 3; x++)
                Q[3 * (k - 1) + (size_t)x] =
                    (b[k][x] - (k + 1 < m ? a[k] * Q[3 * k + (size_t)x] : 0)) / (1 - a[k]);
        /* P' by inserting u back: the differences actually made */
        double worst = 0;
        for (size_t k = 0; k < m; k++) {
            const double *lo = k ? Q + 3 * (k - 1) : left, *hi = k + 1 < m ? Q + 3 * k : right;
            double pk[3];
            for (int x = 0; x < 3; x++)
                pk[x] = a[k] * hi[x] + (1 - a[k]) * lo[x];
            worst = fmax(worst, dist3(pk, point(net, d, first + k, j)));
        }
        rd->e[j] = worst;
    }
    double cost = 0;
    for (size_t c = 0; c < rd->ncell[o]; c++) {
        rd->inc[c] = 0;
        if (!rd->live[o][c])
            continue;
        size_t t = rd->span[c];
        for (size_t j = t - (size_t)po; j <= t; j++)
            rd->inc[c] = fmax(rd->inc[c], rd->e[j]);
        cost = fmax(cost, rd->inc[c]);
    }
    size_t lo = cell_of(rd->brk[d], rd->ncell[d], U[first]);
    size_t hi = cell_of(rd->brk[d], rd->ncell[d], U[last + (size_t)p + 1]);
    *fits = 1;
    for (size_t cd = lo; cd < hi && *fits; cd++) {
        if (!rd->live[d][cd])
            continue;
        for (size_t c = 0; c < rd->ncell[o]; c++) {
            double acc = rd->acc[d ? cd * rd->ncell[0] + c : c * rd->ncell[0] + cd];
            if (rd->live[o][c] && !(acc + rd->inc[c] <= rd->budget)) {
                *fits = 0;
                break;
            }
        }
    }
    return cost;
}

/* Makes the removal evaluate computed: the new points in, one knot and
 * one point per row out, its bound added to the cells of its support. */
static void apply(reducer *rd, int d, size_t r, size_t s)
{
    iges_net *net = rd->net;
    int p = degree(net, d), o = 1 - d;
    double *U = knots(net, d);
    size_t first = r - (size_t)p, last = r - s, m = last - first + 1;
    size_t n = count(net, d), rows = count(net, o), nu = net->nu;
    size_t lo = cell_of(rd->brk[d], rd->ncell[d], U[first]);
    size_t hi = cell_of(rd->brk[d], rd->ncell[d], U[last + (size_t)p + 1]);
    for (size_t cd = lo; cd < hi; cd++)
        for (size_t c = 0; c < rd->ncell[o]; c++)
            rd->acc[d ? cd * rd->ncell[0] + c : c * rd->ncell[0] + cd] += rd->inc[c];
    if (d == 0) {
        /* each row one point shorter; rows move down in place, each read
         * into tmp before its new place (never after its old one) is
         * written */
        for (size_t j = 0; j < rows; j++) {
            const double *row = net->ctrl + 3 * j * nu;
            memcpy(rd->tmp, row, 3 * first * sizeof *rd->tmp);
            memcpy(rd->tmp + 3 * first, rd->q + 3 * MAX_P * j, 3 * (m - 1) * sizeof *rd->tmp);
            memcpy(rd->tmp + 3 * (last), row + 3 * (last + 1),
                   3 * (n - last - 1) * sizeof *rd->tmp);
            memcpy(net->ctrl + 3 * j * (nu - 1), rd->tmp, 3 * (nu - 1) * sizeof *rd->tmp);
        }
        net->nu--;
    } else {
        for (size_t k = 0; k + 1 < m; k++)
            for (size_t i = 0; i < rows; i++)
                memcpy(point(net, 1, first + k, i), rd->q + 3 * MAX_P * i + 3 * k,
                       3 * sizeof *net->ctrl);
        memmove(point(net, 1, last, 0), point(net, 1, last + 1, 0),
                3 * (n - last - 1) * nu * sizeof *net->ctrl);
        net->nv--;
    }
    memmove(U + r, U + r + 1, (n + (size_t)p - r) * sizeof *U);
    /* What a bound reads (points first - 1 .. last + 1, knots r - p ..
     * r + p + 1 of its knot) moved down by one past r and changed within
     * p + 1 of it; across, every row changed. */
    double *kn = rd->known[d];
    memmove(kn + r, kn + r + 1, (n + (size_t)p - r) * sizeof *kn);
    size_t w = 2 * (size_t)p + 2, a = r > w ? r - w : 0, b = r + w < n + (size_t)p ? r + w : n + (size_t)p;
    for (size_t i = a; i < b; i++)
        kn[i] = NAN;
    for (size_t i = 0; i < count(net, o) + (size_t)degree(net, o) + 1; i++)
        rd->known[o][i] = NAN;
}

static void reducer_free(reducer *rd)
{
    for (int d = 0; d < 2; d++) {
        free(rd->brk[d]);
        free(rd->live[d]);
        free(rd->known[d]);
    }
    free(rd->acc);
    free(rd->span);
    free(rd->e);
    free(rd->inc);
    free(rd->q);
    free(rd->tmp);
}

static fm_status reducer_init(reducer *rd, iges_net *net, double budget)
{
    memset(rd, 0, sizeof *rd);
    rd->net = net;
    rd->budget = budget;
    size_t most = net->nu > net->nv ? net->nu : net->nv, cells = 0;
    for (int d = 0; d < 2; d++) {
        const double *U = knots(net, d);
        size_t len = count(net, d) + (size_t)degree(net, d) + 1, nb = 0;
        rd->brk[d] = malloc(len * sizeof *rd->brk[d]);
        rd->live[d] = malloc(len);
        rd->known[d] = malloc(len * sizeof *rd->known[d]);
        if (!rd->brk[d] || !rd->live[d] || !rd->known[d])
            return FM_ERR_NOMEM;
        for (size_t i = 0; i < len; i++)
            rd->known[d][i] = NAN;
        for (size_t i = 0; i < len; i++)
            if (nb == 0 || U[i] > rd->brk[d][nb - 1])
                rd->brk[d][nb++] = U[i];
        rd->ncell[d] = nb - 1;
        for (size_t c = 0; c + 1 < nb; c++)
            rd->live[d][c] = rd->brk[d][c] < net->r[2 * d + 1] && rd->brk[d][c + 1] > net->r[2 * d];
        cells = cells > nb ? cells : nb;
    }
    rd->acc = calloc(rd->ncell[0] * rd->ncell[1] + 1, sizeof *rd->acc);
    rd->span = malloc(cells * sizeof *rd->span);
    rd->e = malloc(most * sizeof *rd->e);
    rd->inc = malloc(cells * sizeof *rd->inc);
    rd->q = malloc(3 * MAX_P * most * sizeof *rd->q);
    rd->tmp = malloc(3 * most * sizeof *rd->tmp);
    if (!rd->acc || !rd->span || !rd->e || !rd->inc || !rd->q || !rd->tmp)
        return FM_ERR_NOMEM;
    return FM_OK;
}

fm_status iges_reduce(iges_net *net, double budget)
{
    net->removal = 0;
    if (net->weights || !(budget > 0))
        return FM_OK;
    reducer rd;
    if (reducer_init(&rd, net, budget) != FM_OK) {
        reducer_free(&rd);
        return FM_ERR_NOMEM;
    }
    for (int level = LEVELS - 1; level >= 0; level--) {
        double threshold = ldexp(budget, -level);
        int changed;
        do {
            changed = 0;
            for (int d = 0; d < 2; d++) {
                int p = degree(net, d);
                spans_across(&rd, d);
                size_t r = (size_t)p + 1;
                while (r < count(net, d)) {
                    const double *U = knots(net, d);
                    size_t n = count(net, d), s = 1;
                    /* r the last index of an interior knot value */
                    if (U[r] == U[r + 1] || !(U[r] > U[p]) || !(U[r] < U[n])) {
                        r++;
                        continue;
                    }
                    while (U[r - s] == U[r])
                        s++;
                    /* a bound over the threshold stays over it */
                    if (rd.known[d][r] > threshold) {
                        r++;
                        continue;
                    }
                    int fits;
                    double cost = evaluate(&rd, d, r, s, &fits);
                    rd.known[d][r] = cost;
                    if (fits && cost <= threshold) {
                        apply(&rd, d, r, s);
                        changed = 1;
                    } else {
                        r++;
                    }
                }
            }
        } while (changed);
    }
    for (size_t cv = 0; cv < rd.ncell[1]; cv++)
        for (size_t cu = 0; cu < rd.ncell[0]; cu++)
            if (rd.live[0][cu] && rd.live[1][cv])
                net->removal = fmax(net->removal, rd.acc[cv * rd.ncell[0] + cu]);
    reducer_free(&rd);
    return FM_OK;
}
