/* The outline of a triangulated surface as vertex chains, for the page to
 * draw a fault's original outline over its new mesh: what was trimmed,
 * cut at sea level or extended shows without the original's triangles,
 * which would double the page. */
#include <stdlib.h>
#include <string.h>

#include "fm_sort.h"
#include "report_internal.h"

fm_status rp_outline(const fm_mesh *m, rp_chains *out)
{
    memset(out, 0, sizeof *out);
    size_t ns = 0, nv = fm_mesh_nvertices(m);
    fm_keyed *side = fm_mesh_ntriangles(m) ? fm_mesh_sides(m, &ns) : NULL;
    if (fm_mesh_ntriangles(m) && !side)
        return FM_ERR_NOMEM;
    /* sides of one triangle, as vertex pairs */
    uint32_t (*edge)[2] = malloc((ns + 1) * sizeof *edge);
    size_t ne = 0;
    for (size_t i = 0; edge && i < ns; i++) {
        int alone = (i == 0 || side[i - 1].key != side[i].key) &&
                    (i + 1 == ns || side[i + 1].key != side[i].key);
        if (alone) {
            edge[ne][0] = (uint32_t)(side[i].key >> 32);
            edge[ne][1] = (uint32_t)side[i].key;
            ne++;
        }
    }
    free(side);
    /* per vertex, its outline edges (CSR) */
    size_t *start = calloc(nv + 2, sizeof *start), *at = malloc((2 * ne + 1) * sizeof *at);
    char *used = calloc(ne + 1, 1);
    out->v = malloc((2 * ne + 1) * sizeof *out->v);
    out->start = malloc((ne + 2) * sizeof *out->start);
    if (!edge || !start || !at || !used || !out->v || !out->start) {
        free(edge);
        free(start);
        free(at);
        free(used);
        rp_chains_free(out);
        return FM_ERR_NOMEM;
    }
    for (size_t e = 0; e < ne; e++) {
        start[edge[e][0] + 1]++;
        start[edge[e][1] + 1]++;
    }
    for (size_t v = 0; v < nv; v++)
        start[v + 1] += start[v];
    for (size_t e = 0; e < ne; e++)
        for (int k = 0; k < 2; k++)
            at[start[edge[e][k]]++] = e;
    for (size_t v = nv; v > 0; v--)
        start[v] = start[v - 1];
    start[0] = 0;
    /* walk: from an unused edge on as long as the vertex reached has one */
    size_t n = 0;
    for (size_t e0 = 0; e0 < ne; e0++) {
        if (used[e0])
            continue;
        out->start[out->n++] = n;
        uint32_t v = edge[e0][0];
        out->v[n++] = v;
        for (size_t e = e0; e != SIZE_MAX;) {
            used[e] = 1;
            v = edge[e][0] == v ? edge[e][1] : edge[e][0];
            out->v[n++] = v;
            e = SIZE_MAX;
            for (size_t k = start[v]; k < start[v + 1] && e == SIZE_MAX; k++)
                if (!used[at[k]])
                    e = at[k];
        }
    }
    out->start[out->n] = n;
    free(edge);
    free(start);
    free(at);
    free(used);
    return FM_OK;
}

void rp_chains_free(rp_chains *c)
{
    free(c->v);
    free(c->start);
    memset(c, 0, sizeof *c);
}
