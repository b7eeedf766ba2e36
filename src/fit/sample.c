/* Quadrature points of the data term: the sheet's piecewise-linear values
 * over the parameter plane (heights, or the three coordinates), sampled per
 * triangle so that the fit sees the facets and not only their corners. */
#include "fit_internal.h"

#include <math.h>

/* Symmetric 3-point rule of degree 2, barycentrics (2/3, 1/6, 1/6): with
 * knots about two edges apart a span holds some ten triangles, and the
 * 6-point degree-4 rule was measured to change fit errors by under 3 %
 * at twice the cost. Triangles longer than max_side are split first. */
#define NORBITS 1
static const double RULE_A[NORBITS] = {1.0 / 6.0};
static const double RULE_W[NORBITS] = {1.0 / 3.0};

typedef struct tri {
    double q[3][5]; /* corners: u, v, then the ncomp values */
    int ncomp;
    double d[3][2]; /* plane edge vectors q1-q2, q2-q0, q0-q1 (opposite corner i) */
    double slope2, bend;
} tri;

/* Emits the rule on the sub-triangle with barycentric corners B[0..2] of
 * the whole triangle. */
static void emit_rule(const tri *t, const double B[3][3], double weight, fm_fit_sample_fn fn,
                      void *ctx)
{
    for (int o = 0; o < NORBITS; o++) {
        double x = RULE_A[o], y = 1 - 2 * x;
        const double r[3][3] = {{y, x, x}, {x, y, x}, {x, x, y}};
        for (int k = 0; k < 3; k++) {
            double l[3], smp[5] = {0, 0, 0, 0, 0};
            for (int i = 0; i < 3; i++)
                l[i] = r[k][0] * B[0][i] + r[k][1] * B[1][i] + r[k][2] * B[2][i];
            for (int i = 0; i < 3; i++)
                for (int c = 0; c < 2 + t->ncomp; c++)
                    smp[c] += l[i] * t->q[i][c];
            /* A smooth h differs from the linear interpolant of its corners
             * by -1/2 sum_{i<j} l_i l_j d_ij^T H d_ij (to second order); the
             * edge between corners i and j is the one opposite corner k. */
            double chord[3] = {0, 0, 0};
            for (int e = 0; e < 3; e++) {
                double f = 0.5 * l[(e + 1) % 3] * l[(e + 2) % 3];
                chord[0] += f * t->d[e][0] * t->d[e][0];
                chord[1] += f * t->d[e][0] * t->d[e][1];
                chord[2] += f * t->d[e][1] * t->d[e][1];
            }
            fm_fit_sample out = {smp[0], smp[1], {smp[2], smp[3], smp[4]}, RULE_W[o] * weight,
                                 {chord[0], chord[1], chord[2]}, t->slope2, t->bend};
            fn(ctx, &out);
        }
    }
}

size_t fm_fit_sample_sheet(const fm_fit_pmesh *pm, double max_side, fm_fit_sample_fn fn,
                           void *ctx)
{
    const int32_t *T = pm->tri;
    size_t nt = pm->nt, count = 0;
    int nc = pm->ncomp;
    /* 1e-9 below max_side^2 dwarfs the rounding of squares and hypot. */
    double max2 = max_side * max_side * (1 - 1e-9);
    for (size_t i = 0; i < nt; i++) {
        tri t;
        t.ncomp = nc;
        for (int c = 0; c < 3; c++) {
            size_t vi = (size_t)T[3 * i + c];
            t.q[c][0] = pm->uv[2 * vi];
            t.q[c][1] = pm->uv[2 * vi + 1];
            for (int k = 0; k < nc; k++)
                t.q[c][2 + k] = pm->val[(size_t)nc * vi + (size_t)k];
            for (int k = nc; k < 3; k++)
                t.q[c][2 + k] = 0;
        }
        double longest2 = 0;
        for (int e = 0; e < 3; e++) {
            const double *a = t.q[(e + 1) % 3], *b = t.q[(e + 2) % 3];
            t.d[e][0] = b[0] - a[0];
            t.d[e][1] = b[1] - a[1];
            longest2 = fmax(longest2, t.d[e][0] * t.d[e][0] + t.d[e][1] * t.d[e][1]);
        }
        /* Weighted by parameter area: the data term then approximates the
         * integral over the plane that the thin-plate term is measured in. A
         * folded triangle counts with its area too. */
        double area = 0.5 * fabs(t.d[2][0] * t.d[1][1] - t.d[2][1] * t.d[1][0]);
        if (!(area > 0))
            continue;
        /* Facet gradient from the two edges leaving corner 0; a parametric
         * fit has near-isometric parameters, so no slope to correct for. */
        t.slope2 = 0;
        if (nc == 1) {
            double e1u = t.q[1][0] - t.q[0][0], e1v = t.q[1][1] - t.q[0][1];
            double e1h = t.q[1][2] - t.q[0][2];
            double e2u = t.q[2][0] - t.q[0][0], e2v = t.q[2][1] - t.q[0][1];
            double e2h = t.q[2][2] - t.q[0][2];
            double det = e1u * e2v - e2u * e1v;
            double gu = (e1h * e2v - e2h * e1v) / det, gv = (e1u * e2h - e2u * e1h) / det;
            t.slope2 = gu * gu + gv * gv;
        }
        t.bend = fm_fit_bending_weight(t.slope2);
        /* Squares settle a side well below max_side (the usual case);
         * hypot, as ever, decides near and above it. */
        int m = 1;
        if (!(longest2 <= max2)) {
            double longest = 0;
            for (int e = 0; e < 3; e++)
                longest = fmax(longest, hypot(t.d[e][0], t.d[e][1]));
            if (longest > max_side)
                m = (int)fmin(64.0, ceil(longest / max_side));
        }
        /* Regular split into m^2 similar triangles on a barycentric grid
         * (m = 1: the triangle itself). */
        double sub = area / ((double)m * m);
        for (int a = 0; a < m; a++)
            for (int b = 0; a + b < m; b++) {
                double P[4][3];
                const int ij[4][2] = {{a, b}, {a + 1, b}, {a, b + 1}, {a + 1, b + 1}};
                for (int k = 0; k < 4; k++) {
                    P[k][1] = (double)ij[k][0] / m;
                    P[k][2] = (double)ij[k][1] / m;
                    P[k][0] = 1 - P[k][1] - P[k][2];
                }
                const double up[3][3] = {{P[0][0], P[0][1], P[0][2]},
                                         {P[1][0], P[1][1], P[1][2]},
                                         {P[2][0], P[2][1], P[2][2]}};
                emit_rule(&t, up, sub, fn, ctx);
                count += 3 * NORBITS;
                if (a + b + 2 <= m) {
                    const double down[3][3] = {{P[1][0], P[1][1], P[1][2]},
                                               {P[3][0], P[3][1], P[3][2]},
                                               {P[2][0], P[2][1], P[2][2]}};
                    emit_rule(&t, down, sub, fn, ctx);
                    count += 3 * NORBITS;
                }
            }
    }
    return count;
}
