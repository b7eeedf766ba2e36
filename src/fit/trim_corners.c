/* Corner detection: turning between the principal directions of the loop
 * on either side of a vertex, over a window of arc length (see fm_trim.h). */
#include "trim_internal.h"

#include <math.h>
#include <stdlib.h>

/* Direction of travel along the `window` metres of the loop before
 * (dir < 0) or after (dir > 0) vertex i: the major axis of the segments'
 * second moments, each segment a uniform line. Moments are taken about
 * vertex i, which keeps them small in UTM coordinates. With a metric, the
 * points are first mapped by R, the Cholesky factor of vertex i's form
 * (M = R^T R, R upper with positive diagonal, so orientation is kept): in
 * that frame lengths and angles are those of the surface's tangent plane
 * at i, so the window and the turning are 3D ones. */
static void side_direction(const trim_input *in, size_t i, double window, int dir, double e[2])
{
    size_t n = in->n;
    const double *o = in->xy + 2 * i;
    double R[3] = {1, 0, 1}; /* r11, r12, r22 */
    if (in->M) {
        const double *M = in->M + 3 * i;
        R[0] = sqrt(M[0]);
        R[1] = M[1] / R[0];
        R[2] = sqrt(fmax(M[2] - R[1] * R[1], 1e-18 * M[2]));
    }
    double m = 0, m1[2] = {0, 0}, mxx = 0, mxy = 0, myy = 0;
    double far[2] = {0, 0};
    double rem = window;
    size_t j = i;
    for (size_t step = 0; step < n && rem > 0; step++) {
        size_t k = dir < 0 ? (j + n - 1) % n : (j + 1) % n;
        double bu = in->xy[2 * j] - o[0], bv = in->xy[2 * j + 1] - o[1];
        double au = in->xy[2 * k] - o[0], av = in->xy[2 * k + 1] - o[1];
        double b[2] = {R[0] * bu + R[1] * bv, R[2] * bv};
        double a[2] = {R[0] * au + R[1] * av, R[2] * av};
        double l = hypot(a[0] - b[0], a[1] - b[1]);
        if (l > rem) {
            double f = rem / l;
            a[0] = b[0] + f * (a[0] - b[0]);
            a[1] = b[1] + f * (a[1] - b[1]);
            l = rem;
        }
        m += l;
        m1[0] += l * 0.5 * (a[0] + b[0]);
        m1[1] += l * 0.5 * (a[1] + b[1]);
        mxx += l * (a[0] * a[0] + a[0] * b[0] + b[0] * b[0]) / 3;
        myy += l * (a[1] * a[1] + a[1] * b[1] + b[1] * b[1]) / 3;
        mxy += l * (2 * a[0] * a[1] + a[0] * b[1] + b[0] * a[1] + 2 * b[0] * b[1]) / 6;
        far[0] = a[0];
        far[1] = a[1];
        rem -= l;
        j = k;
    }
    double cx = m1[0] / m, cy = m1[1] / m;
    double sxx = mxx / m - cx * cx, syy = myy / m - cy * cy, sxy = mxy / m - cx * cy;
    double phi = 0.5 * atan2(2 * sxy, sxx - syy);
    e[0] = cos(phi);
    e[1] = sin(phi);
    /* The axis has no sign: take the one along the travel over the window. */
    double chord[2] = {dir < 0 ? -far[0] : far[0], dir < 0 ? -far[1] : far[1]};
    if (e[0] * chord[0] + e[1] * chord[1] < 0) {
        e[0] = -e[0];
        e[1] = -e[1];
    }
}

typedef struct candidate {
    double turn;
    size_t index;
} candidate;

static int cmp_candidate(const void *pa, const void *pb)
{
    const candidate *a = pa, *b = pb;
    if (a->turn != b->turn)
        return a->turn < b->turn ? 1 : -1;
    return (a->index > b->index) - (a->index < b->index);
}

static int cmp_size(const void *pa, const void *pb)
{
    size_t a = *(const size_t *)pa, b = *(const size_t *)pb;
    return (a > b) - (a < b);
}

/* Where exactly the corner near candidate i is: the turning peaks over a
 * window, and a stair-step beside the apex can tilt either side's
 * direction enough to move the peak one vertex off it; a curve pinned
 * there cuts the real apex by most of an edge. Of the vertices within half
 * a window of i, the apex is the one farthest from the chord between the
 * loop points one window before and after i (in i's tangent-plane frame). */
static size_t locate_apex(const trim_input *in, size_t i, double window)
{
    size_t n = in->n;
    double R[3] = {1, 0, 1};
    if (in->M) {
        const double *M = in->M + 3 * i;
        R[0] = sqrt(M[0]);
        R[1] = M[1] / R[0];
        R[2] = sqrt(fmax(M[2] - R[1] * R[1], 1e-18 * M[2]));
    }
    double A[2], B[2];
    trim_input_at(in, in->s[i] - window, A);
    trim_input_at(in, in->s[i] + window, B);
    const double *o = in->xy + 2 * i;
    double a[2] = {R[0] * (A[0] - o[0]) + R[1] * (A[1] - o[1]), R[2] * (A[1] - o[1])};
    double b[2] = {R[0] * (B[0] - o[0]) + R[1] * (B[1] - o[1]), R[2] * (B[1] - o[1])};
    double e[2] = {b[0] - a[0], b[1] - a[1]}, l = hypot(e[0], e[1]);
    if (!(l > 0))
        return i;
    size_t best = i;
    double bestd = -1;
    double L = in->s[n];
    for (long off = -(long)n / 2; off <= (long)n / 2; off++) {
        size_t j = (size_t)(((long)i + off + (long)n) % (long)n);
        double ds = fabs(in->s[j] - in->s[i]);
        if (fmin(ds, L - ds) > 0.5 * window)
            continue;
        double x[2] = {R[0] * (in->xy[2 * j] - o[0]) + R[1] * (in->xy[2 * j + 1] - o[1]),
                       R[2] * (in->xy[2 * j + 1] - o[1])};
        double d = fabs(e[0] * (x[1] - a[1]) - e[1] * (x[0] - a[0])) / l;
        if (d > bestd + 1e-9 * l || (fabs(d - bestd) <= 1e-9 * l && j == i)) {
            bestd = d;
            best = j;
        }
    }
    return best;
}

fm_status trim_find_corners(const trim_input *in, double window, double angle,
                            const unsigned char *corner_at, size_t **corners, size_t *ncorners)
{
    size_t n = in->n;
    double L = in->s[n];
    *corners = NULL;
    *ncorners = 0;
    candidate *cand = malloc(n * sizeof *cand);
    size_t *out = malloc(n * sizeof *out);
    if (!cand || !out) {
        free(cand);
        free(out);
        return FM_ERR_NOMEM;
    }
    size_t nc = 0;
    for (size_t i = 0; i < n; i++) {
        double el[2], er[2];
        side_direction(in, i, window, -1, el);
        side_direction(in, i, window, +1, er);
        double turn = fabs(atan2(el[0] * er[1] - el[1] * er[0], el[0] * er[0] + el[1] * er[1]));
        if (corner_at && corner_at[in->orig[i]])
            turn = 4 + turn; /* above any turning (at most pi): first */
        if (turn >= angle)
            cand[nc++] = (candidate){turn, i};
    }
    qsort(cand, nc, sizeof *cand, cmp_candidate);
    size_t k = 0;
    for (size_t c = 0; c < nc; c++) {
        int keep = 1;
        for (size_t a = 0; a < k && keep; a++) {
            double d = fabs(in->s[cand[c].index] - in->s[out[a]]);
            if (fmin(d, L - d) < window)
                keep = 0;
        }
        if (keep)
            out[k++] = cand[c].index;
    }
    /* Each corner onto its apex, unless that brings it within half a
     * window of another (the pieces between corners keep a few points). */
    for (size_t a = 0; a < k; a++) {
        if (corner_at && corner_at[in->orig[out[a]]])
            continue;
        size_t j = locate_apex(in, out[a], window);
        int ok = 1;
        for (size_t b = 0; b < k && ok; b++) {
            double d = fabs(in->s[j] - in->s[out[b]]);
            if (b != a && fmin(d, L - d) < 0.5 * window)
                ok = 0;
        }
        if (ok)
            out[a] = j;
    }
    qsort(out, k, sizeof *out, cmp_size);
    free(cand);
    *corners = out;
    *ncorners = k;
    return FM_OK;
}
