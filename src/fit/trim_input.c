/* Checking and cleaning the input loop: repeated points go, arc lengths
 * and the median spacing that scales every automatic choice. */
#include "fm_sort.h"
#include "trim_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void trim_input_free(trim_input *in)
{
    free(in->xy);
    free(in->orig);
    free(in->M);
    free(in->s);
    memset(in, 0, sizeof *in);
}

/* The form of point i, made safely positive definite: a form that is
 * (nearly) singular would give zero lengths, and the corner frame needs
 * its square root. */
static void clean_form(const double *m, double out[3])
{
    double E = m[0], F = m[1], G = m[2];
    double fl = 1e-9 * (E + G);
    E = fmax(E, fl);
    G = fmax(G, fl);
    double lim = sqrt(E * G) * (1 - 1e-9);
    F = fmax(-lim, fmin(F, lim));
    out[0] = E;
    out[1] = F;
    out[2] = G;
}

fm_status trim_input_make(const double *uv, const double *metric, size_t n, trim_input *in,
                          const char *name, fm_error *err)
{
    memset(in, 0, sizeof *in);
    if (!uv && n > 0)
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "trim: no points");
    if (n < 3)
        return fm_error_set(err, FM_ERR_INVALID, name, 0,
                            "trim: a loop needs at least 3 points, not %zu", n);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 2; k++) {
            double x = uv[2 * i + k];
            if (!isfinite(x))
                return fm_error_set(err, FM_ERR_INVALID, name, 0,
                                    "trim: point %zu has a non-finite coordinate", i);
            lo[k] = fmin(lo[k], x);
            hi[k] = fmax(hi[k], x);
        }
    if (metric)
        for (size_t i = 0; i < n; i++) {
            const double *m = metric + 3 * i;
            if (!isfinite(m[0]) || !isfinite(m[1]) || !isfinite(m[2]) || m[0] < 0 || m[2] < 0 ||
                !(m[0] + m[2] > 0))
                return fm_error_set(err, FM_ERR_INVALID, name, 0,
                                    "trim: point %zu has a bad metric (%g, %g, %g)", i, m[0],
                                    m[1], m[2]);
        }
    /* Points closer than this are the same point written twice (rounding of
     * a projection), not a segment. */
    double eps = 1e-9 * hypot(hi[0] - lo[0], hi[1] - lo[1]);

    in->xy = malloc(2 * n * sizeof *in->xy);
    in->orig = malloc(n * sizeof *in->orig);
    in->s = malloc((n + 1) * sizeof *in->s);
    if (metric)
        in->M = malloc(3 * n * sizeof *in->M);
    double *len = malloc(n * sizeof *len);
    if (!in->xy || !in->orig || !in->s || !len || (metric && !in->M)) {
        free(len);
        trim_input_free(in);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "trim: out of memory (%zu points)", n);
    }
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = uv + 2 * i;
        if (m > 0 && hypot(p[0] - in->xy[2 * m - 2], p[1] - in->xy[2 * m - 1]) <= eps)
            continue;
        in->xy[2 * m] = p[0];
        in->xy[2 * m + 1] = p[1];
        if (metric)
            clean_form(metric + 3 * i, in->M + 3 * m);
        in->orig[m++] = i;
    }
    while (m > 1 && hypot(in->xy[2 * m - 2] - in->xy[0], in->xy[2 * m - 1] - in->xy[1]) <= eps)
        m--;
    in->n = m;
    if (m < 3) {
        free(len);
        trim_input_free(in);
        return fm_error_set(err, FM_ERR_INVALID, name, 0,
                            "trim: a loop needs at least 3 distinct points, not %zu", m);
    }
    in->s[0] = 0;
    for (size_t i = 0; i < m; i++) {
        const double *a = in->xy + 2 * i, *b = in->xy + 2 * ((i + 1) % m);
        double d[2] = {b[0] - a[0], b[1] - a[1]};
        if (in->M) {
            const double *ma = in->M + 3 * i, *mb = in->M + 3 * ((i + 1) % m);
            double mm[3] = {0.5 * (ma[0] + mb[0]), 0.5 * (ma[1] + mb[1]),
                            0.5 * (ma[2] + mb[2])};
            len[i] = sqrt(trim_norm2(mm, d));
        } else {
            len[i] = hypot(d[0], d[1]);
        }
        in->s[i + 1] = in->s[i] + len[i];
    }
    in->spacing = fm_median(len, m);
    free(len);
    return FM_OK;
}

double trim_input_area(const trim_input *in)
{
    /* a fan from the centroid, each triangle scaled by the area element of
     * its edge's mean form */
    double c[2] = {0, 0};
    for (size_t i = 0; i < in->n; i++) {
        c[0] += in->xy[2 * i] / (double)in->n;
        c[1] += in->xy[2 * i + 1] / (double)in->n;
    }
    double area = 0;
    for (size_t i = 0; i < in->n; i++) {
        const double *a = in->xy + 2 * i, *b = in->xy + 2 * ((i + 1) % in->n);
        double t = 0.5 * ((a[0] - c[0]) * (b[1] - c[1]) - (b[0] - c[0]) * (a[1] - c[1]));
        double J = 1;
        if (in->M) {
            const double *ma = in->M + 3 * i, *mb = in->M + 3 * ((i + 1) % in->n);
            double E = 0.5 * (ma[0] + mb[0]), F = 0.5 * (ma[1] + mb[1]),
                   G = 0.5 * (ma[2] + mb[2]);
            J = sqrt(fmax(E * G - F * F, 0));
        }
        area += t * J;
    }
    return fabs(area);
}

void trim_input_at(const trim_input *in, double s, double p[2])
{
    double L = in->s[in->n];
    s = fmod(s, L);
    if (s < 0)
        s += L;
    /* Last segment start <= s. */
    size_t lo = 0, hi = in->n;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (in->s[mid] <= s)
            lo = mid;
        else
            hi = mid;
    }
    const double *a = in->xy + 2 * lo, *b = in->xy + 2 * ((lo + 1) % in->n);
    double l = in->s[lo + 1] - in->s[lo];
    double f = l > 0 ? (s - in->s[lo]) / l : 0;
    p[0] = a[0] + f * (b[0] - a[0]);
    p[1] = a[1] + f * (b[1] - a[1]);
}
