/* How far a fitted piece is from its points: raw distances both ways, and
 * the stair-step-free systematic deviation that decides refinement. */
#include "trim_internal.h"

#include <math.h>
#include <stdlib.h>

double trim_segment_distance(const double p[2], const double a[2], const double b[2],
                             const double *M)
{
    double e[2] = {b[0] - a[0], b[1] - a[1]}, r[2] = {p[0] - a[0], p[1] - a[1]};
    double l2 = trim_norm2(M, e);
    double re = M ? M[0] * r[0] * e[0] + M[1] * (r[0] * e[1] + r[1] * e[0]) + M[2] * r[1] * e[1]
                  : r[0] * e[0] + r[1] * e[1];
    double f = l2 > 0 ? re / l2 : 0;
    f = f < 0 ? 0 : f > 1 ? 1 : f;
    double d[2] = {r[0] - f * e[0], r[1] - f * e[1]};
    return sqrt(trim_norm2(M, d));
}

/* M x (M NULL: identity). */
static void apply(const double *M, const double x[2], double y[2])
{
    if (M) {
        y[0] = M[0] * x[0] + M[1] * x[1];
        y[1] = M[1] * x[0] + M[2] * x[1];
    } else {
        y[0] = x[0];
        y[1] = x[1];
    }
}

static double dist2_at(const trim_piece *pc, double t, const double P[2], const double *M)
{
    double c[3][2];
    trim_eval(pc, t, 0, c);
    double d[2] = {c[0][0] - P[0], c[0][1] - P[1]};
    return trim_norm2(M, d);
}

/* Closest parameter to P near t0 in the form M (the point's own: the 3D
 * distance to a nearby curve point): a coarse scan (the fit's parameter can
 * be off by a fraction of a span) and then Newton on the squared distance,
 * steps halved until they improve it. */
static double project(const trim_piece *pc, const double P[2], const double *M, double t0,
                      double step)
{
    double best = trim_wrap(pc, t0), bestd = dist2_at(pc, best, P, M);
    for (int k = -4; k <= 4; k++) {
        double t = trim_wrap(pc, t0 + k * step), d = dist2_at(pc, t, P, M);
        if (d < bestd) {
            bestd = d;
            best = t;
        }
    }
    for (int it = 0; it < 30; it++) {
        double c[3][2];
        trim_eval(pc, best, 2, c);
        double r[2] = {c[0][0] - P[0], c[0][1] - P[1]}, Mr[2];
        apply(M, r, Mr);
        double f = Mr[0] * c[1][0] + Mr[1] * c[1][1];
        double g = trim_norm2(M, c[1]);
        double fp = g + Mr[0] * c[2][0] + Mr[1] * c[2][1];
        if (!(fp > 0))
            fp = g;
        if (!(fp > 0))
            break;
        double dt = -f / fp;
        if (fabs(dt) > 4 * step)
            dt = dt > 0 ? 4 * step : -4 * step;
        int moved = 0;
        for (int h = 0; h < 30 && !moved; h++, dt *= 0.5) {
            double t = trim_wrap(pc, best + dt), d = dist2_at(pc, t, P, M);
            if (d < bestd) {
                bestd = d;
                best = t;
                moved = 1;
            }
        }
        if (!moved || fabs(dt) < 1e-9 * (1 + pc->len))
            break;
    }
    return best;
}

/* Share of the piece's polyline length that point j stands for. */
static double point_length(const trim_piece *pc, size_t j)
{
    size_t m = pc->npts;
    double tj = pc->t[j];
    double prev = j > 0 ? tj - pc->t[j - 1] : pc->periodic ? pc->len - pc->t[m - 1] : 0;
    double next = j + 1 < m ? pc->t[j + 1] - tj : pc->periodic ? pc->len - tj : 0;
    return 0.5 * (prev + next);
}

/* Tent average (half-width H along the parameter) of r about point j. */
static double tent_average(const trim_piece *pc, const double *r, size_t j, double H)
{
    size_t m = pc->npts;
    double sw = point_length(pc, j), sr = sw * r[j];
    for (int dir = -1; dir <= 1; dir += 2) {
        for (size_t step = 1; step < m; step++) {
            size_t k;
            double dt;
            if (dir > 0) {
                if (!pc->periodic && j + step >= m)
                    break;
                k = (j + step) % m;
                dt = pc->t[k] - pc->t[j] + (k < j ? pc->len : 0);
            } else {
                if (!pc->periodic && step > j)
                    break;
                k = (j + m - step) % m;
                dt = pc->t[j] - pc->t[k] + (k > j ? pc->len : 0);
            }
            /* Half the loop: further points are reached from the other side. */
            if (dt >= H || (pc->periodic && 2 * step > m))
                break;
            double w = (1 - dt / H) * point_length(pc, k);
            sw += w;
            sr += w * r[k];
        }
    }
    return sw > 0 ? sr / sw : r[j];
}

/* Largest distance from C(t) to the piece's polyline, searching segments
 * whose parameters lie within R of t (the curve follows the polyline's
 * parameterisation, so the nearest segment is among them). */
static double curve_to_polyline(const trim_input *in, const trim_piece *pc, double t,
                                const double C[2], double R)
{
    size_t m = pc->npts, nseg = pc->periodic ? m : m - 1;
    double best = INFINITY;
    for (int shift = -1; shift <= 1; shift++) {
        if (shift != 0 && !pc->periodic)
            continue;
        double lo = t + shift * pc->len - R, hi = t + shift * pc->len + R;
        if (hi < 0 || lo > pc->len)
            continue;
        /* First segment whose end is at or beyond lo. */
        size_t a = 0, b = nseg;
        while (a < b) {
            size_t mid = a + (b - a) / 2;
            double te = mid + 1 < m ? pc->t[mid + 1] : pc->len;
            if (te < lo)
                a = mid + 1;
            else
                b = mid;
        }
        for (size_t j = a; j < nseg && pc->t[j] <= hi; j++) {
            const double *Ma = trim_point_metric(in, pc, j), *Mb = trim_point_metric(in, pc, j + 1);
            double mm[3];
            if (Ma)
                for (int q = 0; q < 3; q++)
                    mm[q] = 0.5 * (Ma[q] + Mb[q]);
            double d = trim_segment_distance(C, trim_point(in, pc, j), trim_point(in, pc, j + 1),
                                             Ma ? mm : NULL);
            if (d < best)
                best = d;
        }
    }
    return best;
}

fm_status trim_measure_piece(const trim_input *in, trim_piece *pc, double H, double tol,
                             double raw_tol, double raw_share, int curve, unsigned char *flag)
{
    size_t m = pc->npts;
    double *r = malloc(m * sizeof *r);
    if (!r)
        return FM_ERR_NOMEM;
    double hmin = INFINITY, hmax = 0;
    for (size_t s = 0; s < pc->nspans; s++) {
        double h = pc->brk[s + 1] - pc->brk[s];
        hmin = fmin(hmin, h);
        hmax = fmax(hmax, h);
    }
    pc->max_dev = pc->sum_dev2 = pc->max_curve_dev = pc->max_sys = 0;
    pc->worst_span = 0;
    for (size_t j = 0; j < m; j++) {
        r[j] = 0;
        /* A clamped piece passes through its end points by construction. */
        if (!pc->periodic && (j == 0 || j == m - 1))
            continue;
        const double *P = trim_point(in, pc, j), *M = trim_point_metric(in, pc, j);
        double t = project(pc, P, M, pc->t[j], 0.25 * hmin);
        double c[3][2];
        trim_eval(pc, t, 1, c);
        double dx = P[0] - c[0][0], dy = P[1] - c[0][1];
        double dd[2] = {dx, dy};
        double d = sqrt(trim_norm2(M, dd));
        r[j] = c[1][0] * dy - c[1][1] * dx >= 0 ? d : -d;
        if (d > pc->max_dev) {
            pc->max_dev = d;
            pc->worst_span = trim_span(pc, pc->t[j]);
        }
        pc->sum_dev2 += d * d;
    }
    for (size_t s = 0; s < pc->nspans; s++)
        flag[s] = 0;
    /* A single point far off: a bend sharper than the knots (rounded off
     * while its residuals still average to zero) or a point next to a
     * corner, where the tent is not taken. */
    if (raw_tol > 0) {
        double cut = fmax(raw_tol, raw_share * pc->max_dev);
        for (size_t j = 0; j < m; j++)
            if (fabs(r[j]) > cut)
                flag[trim_span(pc, pc->t[j])] |= TRIM_FLAG_RAW;
    }
    for (size_t j = 0; j < m; j++) {
        /* Near a corner the tent would hold the corner, which carries no
         * stair-step, and one step without its partner: the average would
         * show half a step that is not there. The curve is pinned to the
         * corner there anyway. */
        if (!pc->periodic && (pc->t[j] < H || pc->t[j] > pc->len - H))
            continue;
        double f = fabs(tent_average(pc, r, j, H));
        pc->max_sys = fmax(pc->max_sys, f);
        if (f > tol)
            flag[trim_span(pc, pc->t[j])] |= TRIM_FLAG_SYSTEMATIC;
    }
    free(r);
    /* The curve between the points: eight places per span, each measured
     * to the polyline. A curve within max_deviation at every point can
     * still swing out between two of them (one overshot 120 m past a
     * corner of Rose Canyon); with `curve`, such a span is flagged like a
     * far point. */
    double R = 2 * H + hmax;
    double *cd = malloc((8 * pc->nspans + 1) * sizeof *cd);
    size_t curve_span = 0;
    if (!cd)
        return FM_ERR_NOMEM;
    for (size_t s = 0; s < pc->nspans; s++) {
        double h = pc->brk[s + 1] - pc->brk[s];
        for (int i = 0; i < 8; i++) {
            double t = pc->brk[s] + (i + 0.5) / 8 * h, c[3][2];
            trim_eval(pc, t, 0, c);
            cd[8 * s + (size_t)i] = curve_to_polyline(in, pc, t, c[0], R);
            if (cd[8 * s + (size_t)i] > pc->max_curve_dev) {
                pc->max_curve_dev = cd[8 * s + (size_t)i];
                curve_span = s;
            }
        }
    }
    /* the span refinement narrows down to (fit_piece): the farthest either way */
    if (curve && pc->max_curve_dev > pc->max_dev)
        pc->worst_span = curve_span;
    if (raw_tol > 0 && curve) {
        double cut = fmax(raw_tol, raw_share * pc->max_curve_dev);
        for (size_t k = 0; k < 8 * pc->nspans; k++)
            if (cd[k] > cut)
                flag[k / 8] |= TRIM_FLAG_RAW;
    }
    free(cd);
    return FM_OK;
}
