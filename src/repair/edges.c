/* Undirected edge table. Half-edges are ordered by (min vertex, max vertex)
 * with two stable counting sorts (radix over the two vertex ids): linear in
 * the mesh size and independent of any comparison tie-breaking. */
#include "repair_internal.h"

#include <stdlib.h>
#include <string.h>

void rep_edges_free(rep_edges *e)
{
    free(e->edge_of);
    free(e->off);
    free(e->he);
    memset(e, 0, sizeof *e);
}

static void edge_ends(const rep_tris *t, int32_t h, int32_t *lo, int32_t *hi)
{
    int32_t tr = h / 3, i = h % 3;
    int32_t a = t->v[3 * tr + i], b = t->v[3 * tr + (i + 1) % 3];
    *lo = a < b ? a : b;
    *hi = a < b ? b : a;
}

/* Stable counting sort of src (NULL: the identity 0..nh-1) into dst by one
 * end of the edge. */
static void sort_by(const rep_tris *t, const int32_t *src, int32_t *dst, size_t nh,
                    int32_t *count, size_t nv, int by_lo)
{
    memset(count, 0, (nv + 1) * sizeof *count);
    for (size_t i = 0; i < nh; i++) {
        int32_t lo, hi;
        edge_ends(t, src ? src[i] : (int32_t)i, &lo, &hi);
        count[(by_lo ? lo : hi) + 1]++;
    }
    for (size_t v = 0; v < nv; v++)
        count[v + 1] += count[v];
    for (size_t i = 0; i < nh; i++) {
        int32_t h = src ? src[i] : (int32_t)i, lo, hi;
        edge_ends(t, h, &lo, &hi);
        dst[count[by_lo ? lo : hi]++] = h;
    }
}

fm_status rep_edges_build(const rep_tris *t, size_t nv, rep_edges *e)
{
    size_t nh = 3 * t->n;
    memset(e, 0, sizeof *e);
    int32_t *tmp = malloc((nh ? nh : 1) * sizeof *tmp);
    int32_t *count = malloc((nv + 1) * sizeof *count);
    e->edge_of = malloc((nh ? nh : 1) * sizeof *e->edge_of);
    e->he = malloc((nh ? nh : 1) * sizeof *e->he);
    e->off = malloc((nh + 1) * sizeof *e->off);
    if (!tmp || !count || !e->edge_of || !e->he || !e->off) {
        free(tmp);
        free(count);
        rep_edges_free(e);
        return FM_ERR_NOMEM;
    }
    sort_by(t, NULL, tmp, nh, count, nv, 0);
    sort_by(t, tmp, e->he, nh, count, nv, 1);
    free(tmp);
    free(count);

    size_t ne = 0;
    int32_t plo = -1, phi = -1;
    for (size_t i = 0; i < nh; i++) {
        int32_t lo, hi;
        edge_ends(t, e->he[i], &lo, &hi);
        if (lo != plo || hi != phi) {
            e->off[ne++] = (int32_t)i;
            plo = lo;
            phi = hi;
        }
        e->edge_of[e->he[i]] = (int32_t)(ne - 1);
    }
    e->off[ne] = (int32_t)nh;
    e->ne = ne;
    return FM_OK;
}
