/* Box queries on the AABB tree of fm_closest.h: the triangles whose
 * bounding boxes overlap a given box, for neighbour search between faults. */
#include "closest_tree.h"

#include <math.h>
#include <stdlib.h>

static int node_overlaps(const closest_node *N, const double lo[3], const double hi[3])
{
    for (int a = 0; a < 3; a++)
        if (!((double)N->lo[a] <= hi[a] && (double)N->hi[a] >= lo[a])) /* NaN: no */
            return 0;
    return 1;
}

static int slot_overlaps(const fm_closest_tree *t, size_t s, const double lo[3],
                         const double hi[3])
{
    const double *x = t->xyz + 3 * (size_t)t->tri[3 * s];
    const double *y = t->xyz + 3 * (size_t)t->tri[3 * s + 1];
    const double *z = t->xyz + 3 * (size_t)t->tri[3 * s + 2];
    for (int a = 0; a < 3; a++) {
        if (!(fmin(x[a], fmin(y[a], z[a])) <= hi[a] && fmax(x[a], fmax(y[a], z[a])) >= lo[a]))
            return 0;
    }
    return 1;
}

size_t fm_closest_tree_box_query(const fm_closest_tree *t, const double lo[3],
                                 const double hi[3], fm_closest_box_fn fn, void *user)
{
    if (!t || t->nnode == 0 || !lo || !hi)
        return 0;
    double rlo[3], rhi[3];
    for (int a = 0; a < 3; a++) {
        rlo[a] = lo[a] - t->centre[a];
        rhi[a] = hi[a] - t->centre[a];
    }
    size_t calls = 0;
    int32_t stack[CLOSEST_STACK];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const closest_node *N = &t->nodes[stack[--sp]];
        if (!node_overlaps(N, rlo, rhi))
            continue;
        if (N->count == 0) {
            /* Right first onto the stack so that slots come out in order. */
            stack[sp++] = N->first + 1;
            stack[sp++] = N->first;
            continue;
        }
        for (size_t s = (size_t)N->first; s < (size_t)N->first + (size_t)N->count; s++) {
            if (!slot_overlaps(t, s, rlo, rhi))
                continue;
            calls++;
            if (fn && fn(t->orig[s], user))
                return calls;
        }
    }
    return calls;
}

typedef struct collector {
    int32_t *v;
    size_t n, cap;
    int failed;
} collector;

static int collect_one(int32_t tri, void *user)
{
    collector *c = user;
    if (c->n == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 64;
        int32_t *v = realloc(c->v, cap * sizeof *v);
        if (!v) {
            c->failed = 1;
            return 1;
        }
        c->v = v;
        c->cap = cap;
    }
    c->v[c->n++] = tri;
    return 0;
}

static int by_index(const void *x, const void *y)
{
    int32_t a = *(const int32_t *)x, b = *(const int32_t *)y;
    return (a > b) - (a < b);
}

fm_status fm_closest_tree_box_collect(const fm_closest_tree *t, const double lo[3],
                                      const double hi[3], int32_t **out, size_t *n,
                                      fm_error *err)
{
    if (!out || !n)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "closest tree: no output array");
    *out = NULL;
    *n = 0;
    collector c = {0};
    fm_closest_tree_box_query(t, lo, hi, collect_one, &c);
    if (c.failed) {
        free(c.v);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "closest tree: out of memory");
    }
    if (c.n)
        qsort(c.v, c.n, sizeof *c.v, by_index);
    *out = c.v;
    *n = c.n;
    return FM_OK;
}
