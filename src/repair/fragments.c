/* Step 3: connected components and tiny fragments.
 *
 * Components are edge-connected: two triangles touching only at a vertex
 * are in different components. Vertex contacts are how separate CFM
 * surfaces often touch (a splay ending on a single point of its main
 * fault), and gluing them would keep slivers attached to big faces by one
 * point. An edge of any number of triangles (including non-manifold ones)
 * connects them all. */
#include "repair_internal.h"

#include <stdlib.h>
#include <string.h>

fm_status rep_drop_fragments(rep_tris *t, const double *xyz, size_t nv,
                             const fm_repair_options *opt, fm_repair_report *r)
{
    size_t n = t->n;
    r->components = 0;
    if (n == 0)
        return FM_OK;
    fm_status st = FM_ERR_NOMEM;
    rep_edges e;
    int32_t *parent = malloc(n * sizeof *parent);
    int32_t *comp = malloc(n * sizeof *comp);
    size_t *count = calloc(n, sizeof *count);
    double *area = calloc(n, sizeof *area);
    uint8_t *drop = calloc(n, 1);
    st = rep_edges_build(t, nv, &e);
    if (st != FM_OK || !parent || !comp || !count || !area || !drop) {
        if (st == FM_OK)
            rep_edges_free(&e);
        st = FM_ERR_NOMEM;
        goto done;
    }
    for (size_t i = 0; i < n; i++)
        parent[i] = (int32_t)i;
    for (size_t k = 0; k < e.ne; k++)
        for (int32_t j = e.off[k] + 1; j < e.off[k + 1]; j++)
            uf_union(parent, e.he[e.off[k]] / 3, e.he[j] / 3);
    rep_edges_free(&e);

    /* Component ids in order of their first triangle (roots are minimal). */
    size_t nc = 0;
    for (size_t i = 0; i < n; i++) {
        int32_t root = uf_find(parent, (int32_t)i);
        comp[i] = root == (int32_t)i ? (int32_t)nc++ : comp[root];
        const int32_t *v = t->v + 3 * i;
        count[comp[i]]++;
        area[comp[i]] += fm_triangle_area(xyz + 3 * (size_t)v[0], xyz + 3 * (size_t)v[1],
                                          xyz + 3 * (size_t)v[2]);
    }
    size_t largest = 0;
    for (size_t c = 1; c < nc; c++)
        if (area[c] > area[largest])
            largest = c;
    size_t kept = nc;
    if (opt->drop_fragments) {
        double limit = opt->min_fragment_area_fraction * area[largest];
        for (size_t c = 0; c < nc; c++) {
            if (c == largest || count[c] >= opt->min_fragment_triangles || area[c] >= limit)
                continue;
            drop[c] = 1;
            kept--;
            r->fragments_dropped++;
            r->fragment_triangles_dropped += count[c];
        }
    }
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        if (drop[comp[i]])
            continue;
        if (m != i) {
            memcpy(t->v + 3 * m, t->v + 3 * i, 3 * sizeof *t->v);
            t->tag[m] = t->tag[i];
            t->orig[m] = t->orig[i];
        }
        m++;
    }
    t->n = m;
    r->components = kept;
    st = FM_OK;
done:
    free(parent);
    free(comp);
    free(count);
    free(area);
    free(drop);
    return st;
}
