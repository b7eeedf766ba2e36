/* Which constrained edges an edge of the (u, v) plane may cross, through a
 * bucket grid: sliding boundary nodes tests each move against the
 * constraints, and a sheet with thousands of boundary nodes (fuzz_fit_mesh
 * found one with 3568, and one whose round took 11 s) made a scan of them
 * all per move quadratic.
 *
 * The constraints' ends move (the nodes slid are theirs), so a cell lists
 * every constraint whose box covered it at any time: cons_grid_moved adds
 * a moved node's constraints to the cells of their new boxes and removes
 * none. A query thus gets a superset of the constraints whose box meets
 * the edge's, and the exact test decides: the answer is the one a full scan
 * gives. Coordinates outside the grid are clamped to its border cells, on
 * insertion and query alike, which keeps overlapping boxes in shared
 * cells. */
#include <math.h>
#include <stdlib.h>

#include "remesh_internal.h"

/* A constraint whose box spans more cells than this is kept in one list
 * tested by every query instead of in each cell. */
#define WIDE_CELLS 64

typedef struct cell_list {
    int32_t *item;
    uint32_t n, cap;
} cell_list;

struct cons_grid {
    const int32_t *cons;
    size_t ncons;
    double lo[2], cell;
    long nx, ny;
    cell_list *cells;
    cell_list wide;
    size_t *at_start; /* the constraints ending at each node (CSR) */
    int32_t *at;
    uint32_t *stamp, query;
    int broken; /* out of memory once: every query scans all */
};

static int list_add(cell_list *l, int32_t k)
{
    if (l->n == l->cap) {
        uint32_t cap = l->cap ? 2 * l->cap : 4;
        int32_t *p = realloc(l->item, cap * sizeof *p);
        if (!p)
            return 0;
        l->item = p;
        l->cap = cap;
    }
    l->item[l->n++] = k;
    return 1;
}


static long cell_of(const cons_grid *g, double x, int axis)
{
    double f = floor((x - g->lo[axis]) / g->cell);
    long hi = axis ? g->ny - 1 : g->nx - 1;
    /* also NaN, which compares false with both */
    return f >= (double)hi ? hi : f > 0 ? (long)f : 0;
}

static void box_cells(const cons_grid *g, const double *a, const double *b, long r[4])
{
    r[0] = cell_of(g, fmin(a[0], b[0]), 0);
    r[1] = cell_of(g, fmax(a[0], b[0]), 0);
    r[2] = cell_of(g, fmin(a[1], b[1]), 1);
    r[3] = cell_of(g, fmax(a[1], b[1]), 1);
}

static int insert(cons_grid *g, const double *uv, size_t k)
{
    long r[4];
    box_cells(g, uv + 2 * g->cons[2 * k], uv + 2 * g->cons[2 * k + 1], r);
    if ((r[1] - r[0] + 1) * (r[3] - r[2] + 1) > WIDE_CELLS)
        return list_add(&g->wide, (int32_t)k);
    for (long j = r[2]; j <= r[3]; j++)
        for (long i = r[0]; i <= r[1]; i++)
            if (!list_add(&g->cells[j * g->nx + i], (int32_t)k))
                return 0;
    return 1;
}

static void release(cons_grid *g)
{
    if (g->cells)
        for (long i = 0; i < g->nx * g->ny; i++)
            free(g->cells[i].item);
    free(g->cells);
    free(g->wide.item);
    free(g->at_start);
    free(g->at);
    free(g->stamp);
    g->cells = NULL;
    g->wide.item = NULL;
    g->at_start = NULL;
    g->at = NULL;
    g->stamp = NULL;
}

/* Out of memory: the grid gives way to a scan of every constraint, slower
 * with the same answers. */
static cons_grid *give_up(cons_grid *g)
{
    release(g);
    g->broken = 1;
    return g;
}

void cons_grid_destroy(cons_grid *g)
{
    if (!g)
        return;
    release(g);
    free(g);
}

cons_grid *cons_grid_create(const double *uv, size_t np, const int32_t *cons, size_t ncons)
{
    cons_grid *g = calloc(1, sizeof *g);
    if (!g)
        return NULL;
    g->cons = cons;
    g->ncons = ncons;
    g->nx = g->ny = 1;
    double hi[2] = {-INFINITY, -INFINITY};
    g->lo[0] = g->lo[1] = INFINITY;
    for (size_t k = 0; k < 2 * ncons; k++)
        for (int a = 0; a < 2; a++) {
            double x = uv[2 * (size_t)cons[k] + a];
            if (isfinite(x)) {
                g->lo[a] = fmin(g->lo[a], x);
                hi[a] = fmax(hi[a], x);
            }
        }
    double w = hi[0] - g->lo[0], h = hi[1] - g->lo[1];
    if (!(w >= 0 && h >= 0)) {
        w = h = 0;
        g->lo[0] = g->lo[1] = 0;
    }
    /* about one cell per constraint, square unless the box is a sliver */
    double n = (double)(ncons ? ncons : 1);
    g->cell = fmax(sqrt(w * h / n), fmax(w, h) / n);
    if (!(g->cell > 0) || !isfinite(g->cell))
        g->cell = 1;
    while ((w / g->cell + 1) * (h / g->cell + 1) > 4 * n + 16)
        g->cell *= 1.5;
    g->nx = (long)(w / g->cell) + 1;
    g->ny = (long)(h / g->cell) + 1;
    g->cells = calloc((size_t)(g->nx * g->ny), sizeof *g->cells);
    g->at_start = calloc(np + 1, sizeof *g->at_start);
    g->at = malloc((2 * ncons + 1) * sizeof *g->at);
    g->stamp = calloc(ncons + 1, sizeof *g->stamp);
    if (!g->cells || !g->at_start || !g->at || !g->stamp)
        return give_up(g);
    for (size_t k = 0; k < 2 * ncons; k++)
        g->at_start[cons[k] + 1]++;
    for (size_t v = 0; v < np; v++)
        g->at_start[v + 1] += g->at_start[v];
    for (size_t k = 0; k < 2 * ncons; k++)
        g->at[g->at_start[cons[k]]++] = (int32_t)(k / 2);
    for (size_t v = np; v > 0; v--)
        g->at_start[v] = g->at_start[v - 1];
    g->at_start[0] = 0;
    for (size_t k = 0; k < ncons; k++)
        if (!insert(g, uv, k))
            return give_up(g);
    return g;
}

void cons_grid_moved(cons_grid *g, const double *uv, int32_t v)
{
    if (g->broken)
        return;
    for (size_t i = g->at_start[v]; i < g->at_start[v + 1]; i++)
        if (!insert(g, uv, (size_t)g->at[i])) {
            give_up(g);
            return;
        }
}

/* The exact test of one constraint against edge (p, q), after the box
 * test that passes most over cheaply. */
static int crosses_one(const double *uv, const int32_t *cons, size_t k, int32_t p, int32_t q)
{
    int32_t c = cons[2 * k], d = cons[2 * k + 1];
    if (c == p || c == q || d == p || d == q)
        return 0;
    const double *a = uv + 2 * p, *b = uv + 2 * q, *x = uv + 2 * c, *y = uv + 2 * d;
    if ((x[0] < a[0] && x[0] < b[0] && y[0] < a[0] && y[0] < b[0]) ||
        (x[0] > a[0] && x[0] > b[0] && y[0] > a[0] && y[0] > b[0]) ||
        (x[1] < a[1] && x[1] < b[1] && y[1] < a[1] && y[1] < b[1]) ||
        (x[1] > a[1] && x[1] > b[1] && y[1] > a[1] && y[1] > b[1]))
        return 0;
    return segments_cross(a, b, x, y);
}

static int seen(cons_grid *g, int32_t k)
{
    if (g->stamp[k] == g->query)
        return 1;
    g->stamp[k] = g->query;
    return 0;
}

int cons_grid_crosses(cons_grid *g, const double *uv, int32_t p, int32_t q)
{
    if (g->broken) {
        for (size_t k = 0; k < g->ncons; k++)
            if (crosses_one(uv, g->cons, k, p, q))
                return 1;
        return 0;
    }
    if (++g->query == 0) { /* wrapped: old stamps could match again */
        for (size_t k = 0; k < g->ncons; k++)
            g->stamp[k] = 0;
        g->query = 1;
    }
    for (uint32_t i = 0; i < g->wide.n; i++) {
        int32_t k = g->wide.item[i];
        if (!seen(g, k) && crosses_one(uv, g->cons, (size_t)k, p, q))
            return 1;
    }
    long r[4];
    box_cells(g, uv + 2 * p, uv + 2 * q, r);
    for (long j = r[2]; j <= r[3]; j++)
        for (long i = r[0]; i <= r[1]; i++) {
            const cell_list *l = &g->cells[j * g->nx + i];
            for (uint32_t m = 0; m < l->n; m++)
                if (!seen(g, l->item[m]) && crosses_one(uv, g->cons, (size_t)l->item[m], p, q))
                    return 1;
        }
    return 0;
}
