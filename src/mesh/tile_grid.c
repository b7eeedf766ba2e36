/* Points in cubic cells (tile_internal.h). */
#include <math.h>
#include <stdlib.h>

#include "tile_internal.h"

static uint64_t cell_key(const tile_grid *g, const double p[3], const long off[3])
{
    uint64_t key = 0;
    for (int d = 0; d < 3; d++) {
        long c = (long)floor((p[d] - g->lo[d]) / g->cell) + off[d];
        c = c < 0 ? 0 : c > 0x1fffff ? 0x1fffff : c;
        key = key << 21 | (uint64_t)c;
    }
    return key;
}

static const double *point(const void *base, size_t stride, size_t i)
{
    return (const double *)((const char *)base + i * stride);
}

int tile_grid_make_points(tile_grid *g, const void *base, size_t stride, size_t n, double reach)
{
    double hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int d = 0; d < 3; d++)
        g->lo[d] = INFINITY;
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) {
            g->lo[d] = fmin(g->lo[d], point(base, stride, i)[d]);
            hi[d] = fmax(hi[d], point(base, stride, i)[d]);
        }
    g->cell = reach > 0 ? reach : 1;
    for (int d = 0; d < 3; d++) {
        g->lo[d] -= 4 * g->cell;
        if ((hi[d] - g->lo[d]) / g->cell > 1e6)
            g->cell = (hi[d] - g->lo[d]) / 1e6;
    }
    g->n = n;
    g->e = malloc((n + 1) * sizeof *g->e);
    if (!g->e)
        return -1;
    static const long zero[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++)
        g->e[i] = (fm_keyed){cell_key(g, point(base, stride, i), zero), i};
    return fm_sort_keyed(g->e, g->n);
}

int tile_grid_make(tile_grid *g, const fm_tiles *t, double reach)
{
    return tile_grid_make_points(g, t->n ? t->tile[0].centre : NULL, sizeof *t->tile, t->n,
                                 reach);
}

void tile_grid_near(const tile_grid *g, const double p[3], double reach, tile_grid_fn fn,
                    void *user)
{
    long k = (long)ceil(reach / g->cell);
    long off[3];
    for (off[0] = -k; off[0] <= k; off[0]++)
        for (off[1] = -k; off[1] <= k; off[1]++)
            for (off[2] = -k; off[2] <= k; off[2]++) {
                uint64_t key = cell_key(g, p, off);
                for (size_t i = fm_keyed_lower_bound(g->e, g->n, key);
                     i < g->n && g->e[i].key == key; i++)
                    if (fn(g->e[i].index, user))
                        return;
            }
}
