/* check_connect: uniform-grid broad phase (see cc_grid.h). */
#include "cc_grid.h"

#include <math.h>
#include <stdlib.h>

#include "cc_sort.h"

typedef struct grid {
    double origin[3], h;
    int64_t n[3]; /* cells per axis */
} grid;

/* floor((x - origin) / h) is monotone in x, so a box's cells and the cell
 * of any point inside it agree, and the cell of the larger of two values
 * is the larger cell; x >= origin, so it is never negative. Capped (the
 * caller then takes coarser cells). */
#define CELL_CAP ((int64_t)1 << 40)
static int64_t cell(const grid *g, int k, double x)
{
    double c = floor((x - g->origin[k]) / g->h);
    return c < (double)CELL_CAP ? (int64_t)c : CELL_CAP;
}

/* Sets the cell counts and returns the number of (cell, box) entries, or
 * SIZE_MAX when the cells are too fine to number in 62 bits. */
static size_t layout(grid *g, const double *box, size_t n)
{
    for (int k = 0; k < 3; k++)
        g->n[k] = 1;
    size_t total = 0;
    for (size_t i = 0; i < n; i++) {
        size_t c = 1;
        for (int k = 0; k < 3; k++) {
            int64_t lo = cell(g, k, box[6 * i + (size_t)k]),
                    hi = cell(g, k, box[6 * i + 3 + (size_t)k]);
            if (hi >= CELL_CAP)
                return SIZE_MAX;
            if (hi + 1 > g->n[k])
                g->n[k] = hi + 1;
            c *= (size_t)(hi - lo + 1);
        }
        total += c;
        if (total > SIZE_MAX / 64)
            return SIZE_MAX;
    }
    if (cc_bits((uint64_t)g->n[0]) + cc_bits((uint64_t)g->n[1]) + cc_bits((uint64_t)g->n[2]) > 62)
        return SIZE_MAX;
    return total;
}

typedef struct local {
    double *box;
    int64_t *lo; /* low cell of each box */
    uint32_t *item, *group;
    size_t cap;
} local;

static int local_reserve(local *l, size_t k)
{
    if (k <= l->cap)
        return 0;
    size_t cap = l->cap ? l->cap : 64;
    while (cap < k)
        cap *= 2;
    double *b = realloc(l->box, 6 * cap * sizeof *b);
    if (b)
        l->box = b;
    int64_t *lo = b ? realloc(l->lo, 3 * cap * sizeof *lo) : NULL;
    if (lo)
        l->lo = lo;
    uint32_t *it = lo ? realloc(l->item, cap * sizeof *it) : NULL;
    if (it)
        l->item = it;
    uint32_t *gr = it ? realloc(l->group, cap * sizeof *gr) : NULL;
    if (gr)
        l->group = gr;
    if (!gr)
        return -1;
    l->cap = cap;
    return 0;
}

int cc_grid_pairs(const double *box, size_t n, const uint32_t *group, cc_pair_fn fn, void *ctx)
{
    if (n < 2)
        return 0;
    grid g = {{INFINITY, INFINITY, INFINITY}, 0, {1, 1, 1}};
    double ext = 0;
    for (size_t i = 0; i < n; i++) {
        double e = 0;
        for (int k = 0; k < 3; k++) {
            g.origin[k] = fmin(g.origin[k], box[6 * i + (size_t)k]);
            e = fmax(e, box[6 * i + 3 + (size_t)k] - box[6 * i + (size_t)k]);
        }
        ext += e;
    }
    /* Cells about the mean box size: a few cells per box, few boxes per
     * cell. Huge boxes or a huge domain make them coarser. */
    g.h = 1.5 * ext / (double)n;
    if (!(g.h > 0))
        g.h = 1;
    size_t total;
    while ((total = layout(&g, box, n)) > 32 * n)
        g.h *= 2;

    /* Items in (group, item) order, then entries stably sorted by cell:
     * within a cell, by group and item. */
    int rc = -1;
    cc_rec *order = malloc(n * sizeof *order), *ent = malloc(total * sizeof *ent);
    local l = {0};
    if (!order || !ent)
        goto done;
    for (size_t i = 0; i < n; i++)
        order[i] = (cc_rec){group ? group[i] : 0, (uint32_t)i, 0};
    if (group && cc_radix_sort(order, n, 32))
        goto done;
    size_t m = 0;
    for (size_t o = 0; o < n; o++) {
        size_t i = order[o].a;
        const double *b = box + 6 * i;
        int64_t lo[3], hi[3], c[3];
        for (int k = 0; k < 3; k++) {
            lo[k] = cell(&g, k, b[k]);
            hi[k] = cell(&g, k, b[3 + k]);
        }
        for (c[0] = lo[0]; c[0] <= hi[0]; c[0]++)
            for (c[1] = lo[1]; c[1] <= hi[1]; c[1]++)
                for (c[2] = lo[2]; c[2] <= hi[2]; c[2]++)
                    ent[m++] = (cc_rec){(uint64_t)((c[0] * g.n[1] + c[1]) * g.n[2] + c[2]),
                                        (uint32_t)i, (uint32_t)order[o].key};
    }
    free(order);
    order = NULL;
    if (cc_radix_sort(ent, m, cc_bits((uint64_t)(g.n[0] * g.n[1] * g.n[2]))))
        goto done;
    for (size_t s = 0; s < m;) {
        size_t e = s;
        while (e < m && ent[e].key == ent[s].key)
            e++;
        size_t k = e - s;
        if (k > 1) {
            if (local_reserve(&l, k))
                goto done;
            for (size_t i = 0; i < k; i++) {
                uint32_t it = ent[s + i].a;
                l.item[i] = it;
                l.group[i] = ent[s + i].b;
                for (int d = 0; d < 6; d++)
                    l.box[6 * i + (size_t)d] = box[6 * (size_t)it + (size_t)d];
                for (int d = 0; d < 3; d++)
                    l.lo[3 * i + (size_t)d] = cell(&g, d, l.box[6 * i + (size_t)d]);
            }
            uint64_t key = ent[s].key;
            int64_t here[3] = {(int64_t)(key / (uint64_t)(g.n[1] * g.n[2])),
                               (int64_t)(key / (uint64_t)g.n[2] % (uint64_t)g.n[1]),
                               (int64_t)(key % (uint64_t)g.n[2])};
            for (size_t i = 0; i < k; i++) {
                size_t j = i + 1;
                if (group)
                    while (j < k && l.group[j] == l.group[i])
                        j++;
                const double *bi = l.box + 6 * i;
                const int64_t *ci = l.lo + 3 * i;
                for (; j < k; j++) {
                    const double *bj = l.box + 6 * j;
                    if (bi[0] > bj[3] || bj[0] > bi[3] || bi[1] > bj[4] || bj[1] > bi[4] ||
                        bi[2] > bj[5] || bj[2] > bi[5])
                        continue;
                    /* Report in the cell of the common box's low corner. */
                    const int64_t *cj = l.lo + 3 * j;
                    if ((ci[0] > cj[0] ? ci[0] : cj[0]) != here[0] ||
                        (ci[1] > cj[1] ? ci[1] : cj[1]) != here[1] ||
                        (ci[2] > cj[2] ? ci[2] : cj[2]) != here[2])
                        continue;
                    uint32_t a = l.item[i], b = l.item[j];
                    if (a < b)
                        fn(ctx, a, b);
                    else
                        fn(ctx, b, a);
                }
            }
        }
        s = e;
    }
    rc = 0;
done:
    free(order);
    free(ent);
    free(l.box);
    free(l.lo);
    free(l.item);
    free(l.group);
    return rc;
}
