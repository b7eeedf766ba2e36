/* Does the plane projection fold the sheet over itself? With every
 * triangle facing w (min n.w > 0) the projection is locally one-to-one,
 * but a sheet that turns far enough (a spiral ramp, a fault curling back
 * under itself) still covers some of the plane twice, and no height field
 * can follow it there. Sums of projected areas cannot tell (for such a map
 * the signed and unsigned sums agree); a point test can: a triangle whose
 * centroid lies inside another one overlaps it. A bucket grid of about one
 * triangle per cell keeps that linear in the sheet's size. */
#include "fit_internal.h"

#include <math.h>
#include <stdlib.h>

static double orient(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
}

double fm_fit_overlap_area(const fm_fit_pmesh *pm)
{
    size_t nt = pm->nt;
    const int32_t *T = pm->tri;
    const double *uv = pm->uv;
    if (nt < 2)
        return 0;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, area = 0;
    for (size_t t = 0; t < nt; t++) {
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < 2; k++) {
                double x = uv[2 * (size_t)T[3 * t + c] + (size_t)k];
                lo[k] = fmin(lo[k], x);
                hi[k] = fmax(hi[k], x);
            }
        area += fabs(orient(uv + 2 * (size_t)T[3 * t], uv + 2 * (size_t)T[3 * t + 1],
                            uv + 2 * (size_t)T[3 * t + 2])) * 0.5;
    }
    if (!(area > 0))
        return 0;
    double cell = sqrt(2 * area / (double)nt);
    size_t gx = (size_t)fmin(ceil((hi[0] - lo[0]) / cell), 4096.0) + 1;
    size_t gy = (size_t)fmin(ceil((hi[1] - lo[1]) / cell), 4096.0) + 1;
    while (gx * gy > 4 * nt + 16) { /* a long thin sheet: coarser cells, bounded memory */
        cell *= 1.5;
        gx = (size_t)ceil((hi[0] - lo[0]) / cell) + 1;
        gy = (size_t)ceil((hi[1] - lo[1]) / cell) + 1;
    }
    size_t ncell = gx * gy;
    size_t *start = calloc(ncell + 1, sizeof *start);
    size_t *box = malloc(4 * nt * sizeof *box);
    if (!start || !box) {
        free(start);
        free(box);
        return 0; /* no memory to look: no overlap found */
    }
    for (size_t t = 0; t < nt; t++) {
        double bl[2] = {INFINITY, INFINITY}, bh[2] = {-INFINITY, -INFINITY};
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < 2; k++) {
                double x = uv[2 * (size_t)T[3 * t + c] + (size_t)k];
                bl[k] = fmin(bl[k], x);
                bh[k] = fmax(bh[k], x);
            }
        box[4 * t] = (size_t)((bl[0] - lo[0]) / cell);
        box[4 * t + 1] = (size_t)((bh[0] - lo[0]) / cell);
        box[4 * t + 2] = (size_t)((bl[1] - lo[1]) / cell);
        box[4 * t + 3] = (size_t)((bh[1] - lo[1]) / cell);
        for (size_t y = box[4 * t + 2]; y <= box[4 * t + 3]; y++)
            for (size_t x = box[4 * t]; x <= box[4 * t + 1]; x++)
                start[y * gx + x + 1]++;
    }
    for (size_t c = 0; c < ncell; c++)
        start[c + 1] += start[c];
    size_t *items = malloc((start[ncell] ? start[ncell] : 1) * sizeof *items);
    size_t *fill = malloc(ncell * sizeof *fill);
    double overlap = 0;
    if (!items || !fill)
        goto done;
    for (size_t c = 0; c < ncell; c++)
        fill[c] = start[c];
    for (size_t t = 0; t < nt; t++)
        for (size_t y = box[4 * t + 2]; y <= box[4 * t + 3]; y++)
            for (size_t x = box[4 * t]; x <= box[4 * t + 1]; x++)
                items[fill[y * gx + x]++] = t;
    for (size_t t = 0; t < nt; t++) {
        const double *a = uv + 2 * (size_t)T[3 * t], *b = uv + 2 * (size_t)T[3 * t + 1];
        const double *c = uv + 2 * (size_t)T[3 * t + 2];
        double at = 0.5 * fabs(orient(a, b, c));
        if (!(at > 0))
            continue;
        double g[2] = {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3};
        size_t cx = (size_t)((g[0] - lo[0]) / cell), cy = (size_t)((g[1] - lo[1]) / cell);
        size_t ci = cy * gx + cx;
        for (size_t k = start[ci]; k < start[ci + 1]; k++) {
            size_t o = items[k];
            if (o == t)
                continue;
            const double *p = uv + 2 * (size_t)T[3 * o], *q = uv + 2 * (size_t)T[3 * o + 1];
            const double *r = uv + 2 * (size_t)T[3 * o + 2];
            double ao = orient(p, q, r);
            /* Well inside (a margin of 1e-6 of the other's doubled area on
             * each barycentric), so that rounding on shared edges of
             * neighbours never counts. */
            double s = ao > 0 ? 1 : -1, m = 1e-6 * fabs(ao);
            if (s * orient(p, q, g) > m && s * orient(q, r, g) > m && s * orient(r, p, g) > m) {
                overlap += at;
                break;
            }
        }
    }
done:
    free(start);
    free(box);
    free(items);
    free(fill);
    return overlap;
}

/* A bucket grid of cells of about `radius` finds, for every vertex, the
 * vertices within `radius` in the plane. */
size_t fm_fit_stacked_vertices(const fm_fit_pmesh *pm, const unsigned char *used, double radius,
                               double min_dh, double slope)
{
    size_t nv = pm->nv, count = 0;
    const double *uv = pm->uv, *h = pm->val;
    if (nv < 2 || !(radius > 0))
        return 0;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < nv; i++)
        if (used[i])
            for (int k = 0; k < 2; k++) {
                lo[k] = fmin(lo[k], uv[2 * i + (size_t)k]);
                hi[k] = fmax(hi[k], uv[2 * i + (size_t)k]);
            }
    double cell = radius;
    size_t gx = (size_t)ceil((hi[0] - lo[0]) / cell) + 1;
    size_t gy = (size_t)ceil((hi[1] - lo[1]) / cell) + 1;
    while (gx * gy > 4 * nv + 16) {
        cell *= 1.5;
        gx = (size_t)ceil((hi[0] - lo[0]) / cell) + 1;
        gy = (size_t)ceil((hi[1] - lo[1]) / cell) + 1;
    }
    size_t ncell = gx * gy;
    size_t *start = calloc(ncell + 1, sizeof *start), *items = malloc(nv * sizeof *items);
    size_t *fill = malloc(ncell * sizeof *fill), *cellof = malloc(nv * sizeof *cellof);
    if (!start || !items || !fill || !cellof)
        goto done;
    for (size_t i = 0; i < nv; i++) {
        if (!used[i])
            continue;
        size_t cx = (size_t)((uv[2 * i] - lo[0]) / cell);
        size_t cy = (size_t)((uv[2 * i + 1] - lo[1]) / cell);
        cellof[i] = cy * gx + cx;
        start[cellof[i] + 1]++;
    }
    for (size_t c = 0; c < ncell; c++)
        start[c + 1] += start[c];
    for (size_t c = 0; c < ncell; c++)
        fill[c] = start[c];
    for (size_t i = 0; i < nv; i++)
        if (used[i])
            items[fill[cellof[i]]++] = i;
    /* Relative margins of 1e-9 dwarf the few units in the last place that
     * squares, hypot and the products can be off by. */
    double r2_out = radius * radius * (1 + 1e-9), s2_in = slope * slope * (1 - 1e-9);
    for (size_t i = 0; i < nv; i++) {
        if (!used[i])
            continue;
        long cx = (long)(cellof[i] % gx), cy = (long)(cellof[i] / gx);
        int hit = 0;
        for (long y = cy - 1; y <= cy + 1 && !hit; y++)
            for (long x = cx - 1; x <= cx + 1 && !hit; x++) {
                if (x < 0 || y < 0 || x >= (long)gx || y >= (long)gy)
                    continue;
                size_t c = (size_t)y * gx + (size_t)x;
                for (size_t k = start[c]; k < start[c + 1] && !hit; k++) {
                    size_t j = items[k];
                    double du = uv[2 * j] - uv[2 * i], dv = uv[2 * j + 1] - uv[2 * i + 1];
                    double dh = fabs(h[j] - h[i]);
                    if (!(dh > min_dh))
                        continue;
                    /* Most pairs are settled by squares, well clear of
                     * rounding; only those near a threshold take hypot,
                     * so the count is exactly that of the hypot test. */
                    double d2 = du * du + dv * dv;
                    if (d2 > r2_out || dh * dh < s2_in * d2)
                        continue;
                    double d = hypot(du, dv);
                    if (d < radius && dh > slope * d)
                        hit = 1;
                }
            }
        count += (size_t)hit;
    }
done:
    free(start);
    free(items);
    free(fill);
    free(cellof);
    return count;
}
