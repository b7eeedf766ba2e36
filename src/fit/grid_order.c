/* A fill-reducing elimination order for the tensor-product fit's normal
 * equations: nested dissection of the coefficient grid.
 *
 * A coefficient couples with those up to p apart in u and in v, so p whole
 * columns (or rows) of the grid separate the two sides of a rectangle.
 * Eliminating each side first (recursively) and the separator last keeps
 * the fill to the separators: O(n log n) entries and O(n^1.5) work for the
 * 2D grid (George 1973), against the minimum-degree order's larger fill on
 * grids. The separators become the large dense supernodes that BLAS
 * factors fastest. */
#include "fit_internal.h"

typedef struct grid {
    size_t nu;
    int p;
    int *perm;
    size_t k; /* next position */
} grid;

/* Below this many coefficients a rectangle goes in grid order. */
#define LEAF 16

static void put_rect(grid *g, size_t u0, size_t u1, size_t v0, size_t v1)
{
    for (size_t v = v0; v < v1; v++)
        for (size_t u = u0; u < u1; u++)
            g->perm[g->k++] = (int)(v * g->nu + u);
}

static void dissect(grid *g, size_t u0, size_t u1, size_t v0, size_t v1)
{
    size_t w = u1 - u0, h = v1 - v0, p = (size_t)g->p;
    int along_u = w >= h;
    size_t len = along_u ? w : h;
    if (w * h <= LEAF || len < 2 * p + 2) {
        put_rect(g, u0, u1, v0, v1);
        return;
    }
    size_t m = (len - p) / 2; /* first separator line, relative */
    if (along_u) {
        dissect(g, u0, u0 + m, v0, v1);
        dissect(g, u0 + m + p, u1, v0, v1);
        put_rect(g, u0 + m, u0 + m + p, v0, v1);
    } else {
        dissect(g, u0, u1, v0, v0 + m);
        dissect(g, u0, u1, v0 + m + p, v1);
        put_rect(g, u0, u1, v0 + m, v0 + m + p);
    }
}

void fm_fit_grid_order(size_t nu, size_t nv, int p, int *perm)
{
    grid g = {nu, p, perm, 0};
    dissect(&g, 0, nu, 0, nv);
}
