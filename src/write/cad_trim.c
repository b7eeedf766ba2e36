/* A trim stretch as the C2 cubic through the mesh's boundary nodes.
 *
 * The trims were polygons (degree-1 curves, one span per mesh edge), and
 * OpenCASCADE makes the 3D edge of a parameter-space curve by
 * approximating it, which a curve with a corner at every node makes slow:
 * Gmsh took 63 s to import the whole CFM's model, 8 s once the same
 * control polygons were read as cubics. The interpolating cubic keeps
 * what the trims promise: they pass through every boundary node (so two
 * faults' trims still meet at the nodes their meshes share), and between
 * nodes they stay near the mesh edge, the chord. Knots at the nodes'
 * chord-length parameters (clamped), end tangents along the end chords:
 * a tridiagonal system (de Boor, A Practical Guide to Splines, ch. IV;
 * Piegl and Tiller, The NURBS Book, 9.2). */
#include "cad_internal.h"
#include "fm_predicates.h"
#include "iges_internal.h"
#include "fm_sort.h"

#include <math.h>
#include <stdlib.h>

/* The four cubic basis functions nonzero on span s (U[s] <= t < U[s+1]),
 * N[j] = N_(s-3+j)(t), by the Cox-de Boor recurrence. */
static void basis(const double *U, size_t s, double t, double N[4])
{
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
}

int cad_trim_cubic(const double *q, size_t n, double *ctrl, double *knots, double *work)
{
    if (n < 3)
        return 0;
    size_t m = n - 1;
    double *t = work, *a = work + n, *b = a + n, *c = b + n;
    t[0] = 0;
    for (size_t i = 1; i <= m; i++) {
        double h = hypot(q[2 * i] - q[2 * i - 2], q[2 * i + 1] - q[2 * i - 1]);
        if (!(h > 0) || !isfinite(h))
            return 0; /* a repeated node: left a polygon */
        t[i] = t[i - 1] + h;
    }
    /* scaled to a mean of one per segment: the same curve (an affine
     * change of parameter), at the scale of the polygons it replaces */
    double scale = (double)m / t[m];
    for (size_t i = 1; i <= m; i++)
        t[i] *= scale;
    size_t k = 0;
    for (int r = 0; r < 4; r++)
        knots[k++] = t[0];
    for (size_t i = 1; i < m; i++)
        knots[k++] = t[i];
    for (int r = 0; r < 4; r++)
        knots[k++] = t[m];
    /* The ends leave along their chords, at the chords' speed: two
     * stretches meeting at a sharp corner then part as their polygons do
     * instead of bulging across each other. */
    for (int d = 0; d < 2; d++) {
        ctrl[d] = q[d];
        ctrl[2 + d] = q[d] + (q[2 + d] - q[d]) / 3;
        ctrl[2 * (m + 1) + d] = q[2 * m + d] - (q[2 * m + d] - q[2 * (m - 1) + d]) / 3;
        ctrl[2 * (m + 2) + d] = q[2 * m + d];
    }
    /* D_2 .. D_m from the nodes 1 .. m - 1 (row i - 1: node i; the spline
     * there is N_i D_i + N_(i+1) D_(i+1) + N_(i+2) D_(i+2)) */
    size_t nr = m - 1;
    double *rhs = ctrl + 4; /* D_(j + 2) at rhs[2 j], solved in place */
    for (size_t i = 1; i < m; i++) {
        double N[4];
        basis(knots, 3 + i, t[i], N);
        size_t j = i - 1;
        a[j] = N[0];
        b[j] = N[1];
        c[j] = N[2];
        for (int d = 0; d < 2; d++) {
            double r = q[2 * i + (size_t)d];
            if (i == 1)
                r -= N[0] * ctrl[2 + d];
            if (i == m - 1)
                r -= N[2] * ctrl[2 * (m + 1) + d];
            rhs[2 * j + (size_t)d] = r;
        }
    }
    /* Thomas algorithm: the interpolation matrix of a spline at its knots
     * is totally positive, so elimination without pivoting is stable */
    for (size_t j = 1; j < nr; j++) {
        double w = a[j] / b[j - 1];
        b[j] -= w * c[j - 1];
        rhs[2 * j] -= w * rhs[2 * j - 2];
        rhs[2 * j + 1] -= w * rhs[2 * j - 1];
    }
    for (size_t j = nr; j-- > 0;) {
        if (!(fabs(b[j]) > 0))
            return 0;
        if (j + 1 < nr) {
            rhs[2 * j] -= c[j] * rhs[2 * j + 2];
            rhs[2 * j + 1] -= c[j] * rhs[2 * j + 3];
        }
        rhs[2 * j] /= b[j];
        rhs[2 * j + 1] /= b[j];
    }
    for (size_t i = 0; i < 2 * (m + 3); i++)
        if (!isfinite(ctrl[i]))
            return 0;
    return 1;
}

void cad_loop_breaks(const double *q, size_t n, const unsigned char *corner, unsigned char *brk)
{
    double c = cos(CAD_SHARP_TURN_DEG * 3.14159265358979323846 / 180);
    for (size_t i = 0; i < n; i++) {
        const double *p0 = q + 2 * ((i + n - 1) % n), *p1 = q + 2 * i, *p2 = q + 2 * ((i + 1) % n);
        double e[2] = {p1[0] - p0[0], p1[1] - p0[1]}, g[2] = {p2[0] - p1[0], p2[1] - p1[1]};
        double dot = e[0] * g[0] + e[1] * g[1], len = hypot(e[0], e[1]) * hypot(g[0], g[1]);
        brk[i] = (corner && corner[i]) || !(dot > c * len);
    }
}

void cad_curves_free(cad_curves *cv)
{
    free(cv->first);
    free(cv->count);
    free(cv->kfirst);
    free(cv->loop_first);
    free(cv->degree);
    free(cv->pts);
    free(cv->knots);
    memset(cv, 0, sizeof *cv);
}

/* Points along a curve: a cubic's at CAD_SAMPLES per span, a polygon's
 * nodes; the first is its start, the last its end. */
#define CAD_SAMPLES 8
static size_t curve_samples(const cad_curves *cv, size_t c, double *out)
{
    const double *d = cv->pts + 2 * cv->first[c], *k = cv->knots + cv->kfirst[c];
    size_t n = cv->count[c];
    if (cv->degree[c] == 1) {
        memcpy(out, d, 2 * n * sizeof *out);
        return n;
    }
    const fm_iges_curve2d curve = {3, n, k, d, NULL};
    size_t w = 0;
    for (size_t s = 3; s < n; s++)
        for (int j = 0; j < CAD_SAMPLES; j++)
            iges_curve_eval(&curve, k[s] + (k[s + 1] - k[s]) * j / CAD_SAMPLES, out + 2 * w++);
    memcpy(out + 2 * w++, d + 2 * (n - 1), 2 * sizeof *out);
    return w;
}

/* 1 when the sampled curves of the loops cross one another or
 * themselves anywhere but where consecutive pieces of a loop meet; -1
 * out of memory. Segments are swept in order of their smallest u. */
static int loops_cross(const cad_curves *cv)
{
    size_t ns = 0;
    for (size_t c = 0; c < cv->ncurves; c++)
        ns += cv->degree[c] == 1 ? cv->count[c] : (cv->count[c] - 3) * CAD_SAMPLES + 1;
    double *x = malloc((2 * ns + 1) * sizeof *x);
    size_t *loop = malloc((ns + 1) * sizeof *loop), *first = malloc((ns + 1) * sizeof *first);
    fm_keyed *order = malloc((ns + 1) * sizeof *order);
    int crossed = 0;
    if (!x || !loop || !first || !order) {
        crossed = -1;
        goto done;
    }
    /* polyline of each loop: point i joined to point i + 1 of its loop,
     * the last to the loop's first (samples shared at curve ends are
     * kept twice: a zero-length segment, skipped) */
    size_t w = 0;
    for (size_t l = 0; l < cv->nloops; l++) {
        size_t l0 = w;
        for (size_t c = cv->loop_first[l]; c < cv->loop_first[l + 1]; c++)
            w += curve_samples(cv, c, x + 2 * w);
        for (size_t i = l0; i < w; i++) {
            loop[i] = l;
            first[i] = l0;
        }
    }
    ns = w;
    size_t nseg = 0;
    for (size_t i = 0; i < ns; i++) {
        size_t j = i + 1 < ns && loop[i + 1] == loop[i] ? i + 1 : first[i];
        if (x[2 * i] == x[2 * j] && x[2 * i + 1] == x[2 * j + 1])
            continue;
        order[nseg].key = (uint64_t)nseg; /* replaced below */
        order[nseg].index = i;
        nseg++;
    }
    /* by smallest u: keys ordered as the doubles are (all finite) */
    for (size_t s = 0; s < nseg; s++) {
        size_t i = order[s].index, j = i + 1 < ns && loop[i + 1] == loop[i] ? i + 1 : first[i];
        double u = fmin(x[2 * i], x[2 * j]);
        uint64_t bits;
        memcpy(&bits, &u, sizeof bits);
        order[s].key = bits >> 63 ? ~bits : bits | (1ull << 63);
    }
    if (fm_sort_keyed(order, nseg)) {
        crossed = -1;
        goto done;
    }
    for (size_t s = 0; s < nseg && !crossed; s++) {
        size_t i = order[s].index, ni = i + 1 < ns && loop[i + 1] == loop[i] ? i + 1 : first[i];
        double umax = fmax(x[2 * i], x[2 * ni]);
        for (size_t r = s + 1; r < nseg && !crossed; r++) {
            size_t j = order[r].index, nj = j + 1 < ns && loop[j + 1] == loop[j] ? j + 1 : first[j];
            if (fmin(x[2 * j], x[2 * nj]) > umax)
                break;
            /* neighbours along a loop share an end (or a zero-length
             * segment between them): they meet there by construction */
            if (ni == j || nj == i || (x[2 * ni] == x[2 * j] && x[2 * ni + 1] == x[2 * j + 1]) ||
                (x[2 * nj] == x[2 * i] && x[2 * nj + 1] == x[2 * i + 1]))
                continue;
            crossed = fm_segments_meet2d(x + 2 * i, x + 2 * ni, x + 2 * j, x + 2 * nj);
        }
    }
done:
    free(x);
    free(loop);
    free(first);
    free(order);
    return crossed;
}

/* Segments from point i of a loop of n points to the next break (back
 * to i itself when it is the only one, or when there is none). */
static size_t stretch_length(const unsigned char *b, size_t n, size_t i)
{
    size_t len = 1;
    while (len < n && !b[(i + len) % n])
        len++;
    return len;
}

static size_t chunks(size_t len)
{
    return (len + CAD_MAX_SPANS - 1) / CAD_MAX_SPANS;
}

static fm_status make(cad_curves *cv, const double *uv, const size_t *start, size_t nloops,
                      const unsigned char *brk, int polygons)
{
    memset(cv, 0, sizeof *cv);
    size_t ncurves = 0, npts = 0;
    for (size_t l = 0; l < nloops; l++) {
        size_t n = start[l + 1] - start[l];
        const unsigned char *b = brk + (start[l] - start[0]);
        size_t s0 = 0;
        while (s0 < n && !b[s0])
            s0++;
        if (s0 == n)
            s0 = 0;
        for (size_t done = 0; done < n;) {
            size_t len = stretch_length(b, n, (s0 + done) % n), q = chunks(len);
            ncurves += q;
            npts += len + q; /* its points, each chunk's last one repeated */
            done += len;
        }
    }
    size_t ncp = npts + 2 * ncurves; /* a cubic has 2 more control points than nodes */
    cv->first = malloc((ncurves + 1) * sizeof *cv->first);
    cv->count = malloc((ncurves + 1) * sizeof *cv->count);
    cv->kfirst = malloc((ncurves + 1) * sizeof *cv->kfirst);
    cv->degree = malloc((ncurves + 1) * sizeof *cv->degree);
    cv->loop_first = malloc((nloops + 1) * sizeof *cv->loop_first);
    cv->pts = malloc((2 * ncp + 1) * sizeof *cv->pts);
    cv->knots = malloc((ncp + 4 * ncurves + 1) * sizeof *cv->knots);
    if (!cv->first || !cv->count || !cv->kfirst || !cv->degree || !cv->loop_first || !cv->pts ||
        !cv->knots) {
        cad_curves_free(cv);
        return FM_ERR_NOMEM;
    }
    double poly[2 * (CAD_MAX_SPANS + 1)], work[4 * (CAD_MAX_SPANS + 1)];
    size_t pw = 0, kw = 0;
    for (size_t l = 0; l < nloops; l++) {
        size_t a = start[l], n = start[l + 1] - start[l];
        const unsigned char *b = brk + (a - start[0]);
        /* the first break starts the first curve; none: point 0 */
        size_t s0 = 0;
        while (s0 < n && !b[s0])
            s0++;
        if (s0 == n)
            s0 = 0;
        cv->loop_first[l] = cv->ncurves;
        for (size_t done = 0; done < n;) {
            size_t len = stretch_length(b, n, (s0 + done) % n), q = chunks(len);
            /* a long stretch in chunks of nearly equal counts: a 3D edge
             * is made from each, and OpenCASCADE makes it of a bounded
             * number of pieces, missing the nodes of a curve of many
             * spans by hundreds of metres */
            for (size_t j = 0; j < q; j++) {
                size_t from = len * j / q, to = len * (j + 1) / q, cnt = 0;
                for (size_t i = from; i <= to; i++)
                    memcpy(poly + 2 * cnt++, uv + 2 * (a + (s0 + done + i) % n), sizeof poly[0] * 2);
                size_t c = cv->ncurves++;
                cv->first[c] = pw;
                cv->kfirst[c] = kw;
                if (!polygons && cad_trim_cubic(poly, cnt, cv->pts + 2 * pw, cv->knots + kw, work)) {
                    cv->degree[c] = 3;
                    cv->count[c] = cnt + 2;
                } else {
                    /* a polygon: clamped, degree 1, one span per segment */
                    cv->degree[c] = 1;
                    cv->count[c] = cnt;
                    memcpy(cv->pts + 2 * pw, poly, 2 * cnt * sizeof *poly);
                    cv->knots[kw] = 0;
                    for (size_t i = 0; i < cnt; i++)
                        cv->knots[kw + 1 + i] = (double)i;
                    cv->knots[kw + cnt + 1] = (double)(cnt - 1);
                }
                pw += cv->count[c];
                kw += cv->count[c] + (size_t)cv->degree[c] + 1;
            }
            done += len;
        }
    }
    cv->loop_first[nloops] = cv->ncurves;
    cv->nloops = nloops;
    return FM_OK;
}

fm_status cad_curves_make(cad_curves *cv, const double *uv, const size_t *start, size_t nloops,
                          const unsigned char *brk)
{
    fm_status st = make(cv, uv, start, nloops, brk, 0);
    if (st != FM_OK)
        return st;
    /* smooth curves that would cross (a sliver's sharp corner, a hole
     * near the outline): the polygons, which the mesh's boundary keeps
     * apart */
    int crossed = loops_cross(cv);
    if (crossed == 0)
        return FM_OK;
    cad_curves_free(cv);
    return crossed < 0 ? FM_ERR_NOMEM : make(cv, uv, start, nloops, brk, 1);
}
