/* How many pieces an original has below a level (fm_check_loss's
 * islands are the output's pieces beyond these). An original as read may
 * repeat a vertex under two ids along a seam, so vertices closer than
 * FM_LOSS_TOUCH are one. Clipping a triangle at a level leaves a convex,
 * so connected, part; two neighbours' parts meet when their shared edge
 * reaches below the level, so the pieces follow from the vertices'
 * heights alone. */
#include <math.h>
#include <stdlib.h>

#include "check_internal.h"

typedef struct cell_vertex {
    int64_t c[3];
    int32_t v;
} cell_vertex;

static int cmp_cell(const void *a, const void *b)
{
    const cell_vertex *x = a, *y = b;
    for (int k = 0; k < 3; k++)
        if (x->c[k] != y->c[k])
            return (x->c[k] > y->c[k]) - (x->c[k] < y->c[k]);
    return (x->v > y->v) - (x->v < y->v);
}

/* Vertices within FM_LOSS_TOUCH of each other united in up. */
static int weld(const fm_mesh *o, int32_t *up)
{
    size_t nv = fm_mesh_nvertices(o);
    const double *X = fm_mesh_vertices(o);
    cell_vertex *cv = malloc((nv + 1) * sizeof *cv);
    if (!cv)
        return -1;
    for (size_t v = 0; v < nv; v++) {
        for (int k = 0; k < 3; k++)
            cv[v].c[k] = (int64_t)floor(X[3 * v + k] / FM_LOSS_TOUCH);
        cv[v].v = (int32_t)v;
    }
    qsort(cv, nv, sizeof *cv, cmp_cell);
    /* Each pair of vertices in neighbouring cells is met once, from the
     * one whose cell column (c0, c1) comes first: its own column upwards
     * (in order, so those after it) and the columns (0, 1), (1, -1),
     * (1, 0), (1, 1) away, each a run of the sorted cells from c2 - 1 to
     * c2 + 1; the other half of the 27 neighbours meets it from there.
     * The pieces depend on the sets united, not on the order. */
    static const int step[4][2] = {{0, 1}, {1, -1}, {1, 0}, {1, 1}};
    for (size_t i = 0; i < nv; i++) {
        const int64_t *c = cv[i].c;
        const double *a = X + 3 * cv[i].v;
        for (int s = -1; s < 4; s++) {
            size_t j = i + 1;
            int64_t c0 = c[0], c1 = c[1];
            if (s >= 0) {
                c0 += step[s][0];
                c1 += step[s][1];
                cell_vertex key = {{c0, c1, c[2] - 1}, -1};
                size_t lo = i + 1, hi = nv; /* later columns sort after cv[i] */
                while (lo < hi) {
                    size_t mid = (lo + hi) / 2;
                    if (cmp_cell(&cv[mid], &key) < 0)
                        lo = mid + 1;
                    else
                        hi = mid;
                }
                j = lo;
            }
            for (; j < nv && cv[j].c[0] == c0 && cv[j].c[1] == c1 && cv[j].c[2] <= c[2] + 1;
                 j++) {
                const double *b = X + 3 * cv[j].v;
                double d2 = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                            (a[2] - b[2]) * (a[2] - b[2]);
                if (d2 <= FM_LOSS_TOUCH * FM_LOSS_TOUCH)
                    ck_unite(up, cv[i].v, cv[j].v);
            }
        }
    }
    free(cv);
    return 0;
}

size_t ck_orig_pieces(const fm_mesh *o, double zcut, double minz)
{
    size_t nv = fm_mesh_nvertices(o), nt = fm_mesh_ntriangles(o);
    const double *X = fm_mesh_vertices(o);
    const int32_t *T = fm_mesh_triangles(o);
    int32_t *vup = malloc((nv + 1) * sizeof *vup), *tup = malloc((nt + 1) * sizeof *tup);
    fm_keyed *side = malloc((3 * nt + 1) * sizeof *side);
    double *low = malloc((nt + 1) * sizeof *low);
    size_t pieces = SIZE_MAX;
    if (!vup || !tup || !side || !low)
        goto done;
    for (size_t v = 0; v < nv; v++)
        vup[v] = (int32_t)v;
    if (weld(o, vup))
        goto done;
    size_t ns = 0;
    for (size_t t = 0; t < nt; t++) {
        tup[t] = (int32_t)t;
        low[t] = INFINITY;
        for (int k = 0; k < 3; k++) {
            int32_t a = T[3 * t + k], b = T[3 * t + (k + 1) % 3];
            if (a < 0 || b < 0 || (size_t)a >= nv || (size_t)b >= nv)
                continue;
            low[t] = fmin(low[t], X[3 * a + 2]);
            /* an edge reaching below the level joins its triangles */
            if (fmin(X[3 * a + 2], X[3 * b + 2]) < zcut)
                side[ns++] = (fm_keyed){fm_edge_key((uint64_t)ck_find(vup, a), (uint64_t)ck_find(vup, b)), t};
        }
    }
    if (fm_sort_keyed(side, ns))
        goto done;
    for (size_t i = 1; i < ns; i++)
        if (side[i].key == side[i - 1].key)
            ck_unite(tup, (int32_t)side[i].index, (int32_t)side[i - 1].index);
    /* a piece counts once, when some triangle of it reaches minz */
    double *reach = malloc((nt + 1) * sizeof *reach);
    if (!reach)
        goto done;
    for (size_t t = 0; t < nt; t++)
        reach[t] = INFINITY;
    for (size_t t = 0; t < nt; t++)
        if (low[t] < zcut) {
            int32_t r = ck_find(tup, (int32_t)t);
            reach[r] = fmin(reach[r], low[t]);
        }
    pieces = 0;
    for (size_t t = 0; t < nt; t++)
        if (ck_find(tup, (int32_t)t) == (int32_t)t && reach[t] < minz)
            pieces++;
    free(reach);
done:
    free(vup);
    free(tup);
    free(side);
    free(low);
    return pieces;
}
