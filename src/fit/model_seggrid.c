/* Nearest-segment queries on closed 2D polylines through a bucket grid:
 * trimming loops have thousands of points and every boundary sample needs
 * its nearest segment, so a linear scan per query would be quadratic. */
#include <math.h>
#include <stdlib.h>

#include "model_internal.h"

struct fm_seggrid {
    const double *uv;
    size_t n;
    double lo[2], cell;
    long nx, ny;
    size_t *start; /* nx*ny + 1 offsets into items (CSR) */
    size_t *items; /* segment indices */
};

static long clampl(long v, long lo, long hi) { return v < lo ? lo : v > hi ? hi : v; }

static void cell_range(const fm_seggrid *g, size_t i, long r[4])
{
    const double *a = g->uv + 2 * i, *b = g->uv + 2 * ((i + 1) % g->n);
    r[0] = clampl((long)floor((fmin(a[0], b[0]) - g->lo[0]) / g->cell), 0, g->nx - 1);
    r[1] = clampl((long)floor((fmax(a[0], b[0]) - g->lo[0]) / g->cell), 0, g->nx - 1);
    r[2] = clampl((long)floor((fmin(a[1], b[1]) - g->lo[1]) / g->cell), 0, g->ny - 1);
    r[3] = clampl((long)floor((fmax(a[1], b[1]) - g->lo[1]) / g->cell), 0, g->ny - 1);
}

fm_seggrid *fm_seggrid_create(const double *uv, size_t n, double cell)
{
    if (n < 2 || !(cell > 0))
        return NULL;
    fm_seggrid *g = calloc(1, sizeof *g);
    if (!g)
        return NULL;
    g->uv = uv;
    g->n = n;
    double hi[2] = {uv[0], uv[1]};
    g->lo[0] = uv[0];
    g->lo[1] = uv[1];
    for (size_t i = 1; i < n; i++)
        for (int k = 0; k < 2; k++) {
            g->lo[k] = fmin(g->lo[k], uv[2 * i + k]);
            hi[k] = fmax(hi[k], uv[2 * i + k]);
        }
    /* Keep the grid to about 4 cells per segment at most. */
    double w = hi[0] - g->lo[0], h = hi[1] - g->lo[1];
    while ((w / cell + 1) * (h / cell + 1) > 4.0 * (double)n + 16.0)
        cell *= 1.5;
    g->cell = cell;
    g->nx = (long)(w / cell) + 1;
    g->ny = (long)(h / cell) + 1;
    size_t ncell = (size_t)(g->nx * g->ny);
    g->start = calloc(ncell + 1, sizeof *g->start);
    if (!g->start) {
        fm_seggrid_destroy(g);
        return NULL;
    }
    long r[4];
    for (size_t i = 0; i < n; i++) {
        cell_range(g, i, r);
        for (long y = r[2]; y <= r[3]; y++)
            for (long x = r[0]; x <= r[1]; x++)
                g->start[y * g->nx + x + 1]++;
    }
    for (size_t c = 0; c < ncell; c++)
        g->start[c + 1] += g->start[c];
    g->items = malloc((g->start[ncell] ? g->start[ncell] : 1) * sizeof *g->items);
    size_t *fill = malloc(ncell * sizeof *fill);
    if (!g->items || !fill) {
        free(fill);
        fm_seggrid_destroy(g);
        return NULL;
    }
    for (size_t c = 0; c < ncell; c++)
        fill[c] = g->start[c];
    for (size_t i = 0; i < n; i++) {
        cell_range(g, i, r);
        for (long y = r[2]; y <= r[3]; y++)
            for (long x = r[0]; x <= r[1]; x++)
                g->items[fill[y * g->nx + x]++] = i;
    }
    free(fill);
    return g;
}

void fm_seggrid_destroy(fm_seggrid *g)
{
    if (!g)
        return;
    free(g->start);
    free(g->items);
    free(g);
}

static double seg_dist2(const double *a, const double *b, const double p[2], double *t)
{
    double dx = b[0] - a[0], dy = b[1] - a[1];
    double len2 = dx * dx + dy * dy;
    double s = len2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2 : 0.0;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    double fx = a[0] + s * dx - p[0], fy = a[1] + s * dy - p[1];
    *t = s;
    return fx * fx + fy * fy;
}

size_t fm_seggrid_nearest(const fm_seggrid *g, const double p[2], double foot[2], double *t)
{
    long cx = (long)floor((p[0] - g->lo[0]) / g->cell);
    long cy = (long)floor((p[1] - g->lo[1]) / g->cell);
    double best = INFINITY, bt = 0.0;
    size_t bi = 0;
    long maxr = (g->nx > g->ny ? g->nx : g->ny) + labs(cx) + labs(cy) + 1;
    for (long r = 0; r <= maxr; r++) {
        /* Everything in rings beyond r is at least (r - 1) cells away from p
         * when p lies in the grid, and farther still when it lies outside. */
        if (r > 1 && best < ((double)(r - 1) * g->cell) * ((double)(r - 1) * g->cell))
            break;
        for (long y = cy - r; y <= cy + r; y++) {
            if (y < 0 || y >= g->ny)
                continue;
            int edge_row = (y == cy - r || y == cy + r);
            for (long x = cx - r; x <= cx + r; x += edge_row ? 1 : 2 * r) {
                if (x >= 0 && x < g->nx) {
                    size_t c = (size_t)(y * g->nx + x);
                    for (size_t k = g->start[c]; k < g->start[c + 1]; k++) {
                        size_t i = g->items[k];
                        double s;
                        double d = seg_dist2(g->uv + 2 * i, g->uv + 2 * ((i + 1) % g->n), p, &s);
                        if (d < best || (d == best && i < bi)) {
                            best = d;
                            bi = i;
                            bt = s;
                        }
                    }
                }
                if (r == 0)
                    break;
            }
        }
    }
    const double *a = g->uv + 2 * bi, *b = g->uv + 2 * ((bi + 1) % g->n);
    foot[0] = a[0] + bt * (b[0] - a[0]);
    foot[1] = a[1] + bt * (b[1] - a[1]);
    *t = bt;
    return bi;
}
