/* Where two junction curves on one sheet may meet (plan_internal.h): a
 * three-fault point is not only where the curves cross. A fault that
 * ends against the junction of two others gives a curve whose END stops
 * short of, or just past, the middle of the other curve; two curves at a
 * small angle, or ending near each other, come close without a crossing
 * of their polylines. Newton on the three surfaces, started there, finds
 * the common point when there is one. */
#include <math.h>
#include <string.h>

#include "fm_mesh.h"
#include "fm_predicates.h"
#include "plan_internal.h"

static double dist3(const double *a, const double *b)
{
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* The point of segment p-q nearest x. */
static void segment_foot(const double *x, const double *p, const double *q, double f[3])
{
    double d[3], w[3], dd = 0, t = 0;
    for (int c = 0; c < 3; c++) {
        d[c] = q[c] - p[c];
        w[c] = x[c] - p[c];
        dd += d[c] * d[c];
        t += d[c] * w[c];
    }
    t = dd > 0 ? fmin(1, fmax(0, t / dd)) : 0;
    for (int c = 0; c < 3; c++)
        f[c] = p[c] + t * d[c];
}

/* Distance from x to polyline c and the nearest point on it. */
static double polyline_foot(const pl_curve *c, const double *x, double f[3])
{
    double best = INFINITY;
    for (size_t k = 0; k + 1 < c->n; k++) {
        double d = fm_segment_distance3(x, c->xyz + 3 * k, c->xyz + 3 * k + 3);
        if (d < best) {
            best = d;
            segment_foot(x, c->xyz + 3 * k, c->xyz + 3 * k + 3, f);
        }
    }
    return best;
}

static size_t add_seed(double (*P)[3], size_t n, size_t max, const double p[3], double sep)
{
    if (n == max)
        return n;
    for (size_t i = 0; i < n; i++)
        if (dist3(P[i], p) < sep)
            return n;
    memcpy(P[n], p, 3 * sizeof(double));
    return n + 1;
}

/* Every crossing of the (u, v) polylines (exact orientation tests), as a
 * 3D point interpolated on a. */
static size_t crossing_seeds(const pl_curve *a, int sa, const pl_curve *b, int sb, double sep,
                             double (*P)[3], size_t n, size_t max)
{
    for (size_t i = 0; i + 1 < a->n; i++)
        for (size_t k = 0; k + 1 < b->n; k++) {
            const double *p = a->uv[sa] + 2 * i, *q = p + 2;
            const double *r = b->uv[sb] + 2 * k, *t = r + 2;
            int o1 = fm_orient2d(p, q, r), o2 = fm_orient2d(p, q, t);
            int o3 = fm_orient2d(r, t, p), o4 = fm_orient2d(r, t, q);
            if (!(o1 * o2 <= 0 && o3 * o4 <= 0 && (o1 || o2 || o3 || o4)))
                continue;
            double den = (q[0] - p[0]) * (t[1] - r[1]) - (q[1] - p[1]) * (t[0] - r[0]);
            double s = den != 0 ? ((r[0] - p[0]) * (t[1] - r[1]) - (r[1] - p[1]) * (t[0] - r[0])) / den
                                : 0.5;
            s = fmin(1, fmax(0, s));
            double x[3];
            for (int c = 0; c < 3; c++)
                x[c] = a->xyz[3 * i + c] + s * (a->xyz[3 * (i + 1) + c] - a->xyz[3 * i + c]);
            n = add_seed(P, n, max, x, sep);
        }
    return n;
}

/* For every run of nodes of a within `near` of b: the midpoint between
 * the closest node of the run and its foot on b. */
static size_t near_seeds(const pl_curve *a, const pl_curve *b, double near, double sep,
                         double (*P)[3], size_t n, size_t max)
{
    double best = INFINITY, bp[3] = {0, 0, 0};
    for (size_t i = 0; i <= a->n; i++) {
        double f[3] = {0, 0, 0}, d = i < a->n ? polyline_foot(b, a->xyz + 3 * i, f) : INFINITY;
        if (d < near) {
            if (d < best) {
                best = d;
                for (int c = 0; c < 3; c++)
                    bp[c] = 0.5 * (a->xyz[3 * i + c] + f[c]);
            }
            continue;
        }
        if (best < near)
            n = add_seed(P, n, max, bp, sep);
        best = INFINITY;
    }
    return n;
}

size_t pl_meet_seeds(const pl_curve *a, int sa, const pl_curve *b, int sb, double near,
                     double sep, double (*P)[3], size_t max)
{
    size_t n = crossing_seeds(a, sa, b, sb, sep, P, 0, max);
    n = near_seeds(a, b, near, sep, P, n, max);
    return near_seeds(b, a, near, sep, P, n, max);
}
