/* Junction curves: the non-manifold edges chained into polylines.
 *
 * A polyline ends at every vertex where other than two junction edges meet
 * (a curve end, or a point where three or more curves branch); what remains
 * after all such walks are closed cycles. Walks start at vertices in
 * increasing index order and take edges in edge-id order, so the output is
 * fixed by the input. */
#include "repair_internal.h"

#include <stdlib.h>
#include <string.h>

typedef struct jctx {
    const rep_tris *t;
    const rep_edges *e;
    const int32_t *sheet;
    const double *xyz;
    const int32_t *jedge; /* junction edge -> edge id */
    int32_t *adj_start, *adj; /* vertex -> incident junction edges */
    int32_t *deg;
    uint8_t *used;
    int32_t *verts, *edges; /* scratch: one walk */
    int32_t *sheets;        /* scratch: sheets met along one walk */
} jctx;

static int cmp_i32(const void *pa, const void *pb)
{
    int32_t a = *(const int32_t *)pa, b = *(const int32_t *)pb;
    return (a > b) - (a < b);
}

static int32_t other_end(const jctx *x, int32_t j, int32_t v)
{
    int32_t h = x->e->he[x->e->off[x->jedge[j]]];
    int32_t tr = h / 3, i = h % 3;
    int32_t a = x->t->v[3 * tr + i], b = x->t->v[3 * tr + (i + 1) % 3];
    return a == v ? b : a;
}

/* First unused junction edge at v, or -1. */
static int32_t next_edge(const jctx *x, int32_t v)
{
    for (int32_t k = x->adj_start[v]; k < x->adj_start[v + 1]; k++)
        if (!x->used[x->adj[k]])
            return x->adj[k];
    return -1;
}

static fm_status emit(fm_surface *s, const jctx *x, size_t np, size_t nedges, int closed)
{
    rep_junction *j = &s->junctions[s->njunctions];
    size_t ns = 0;
    for (size_t k = 0; k < nedges; k++) {
        int32_t ed = x->jedge[x->edges[k]];
        for (int32_t m = x->e->off[ed]; m < x->e->off[ed + 1]; m++)
            x->sheets[ns++] = x->sheet[x->e->he[m] / 3];
    }
    qsort(x->sheets, ns, sizeof *x->sheets, cmp_i32);
    size_t nu = 0;
    for (size_t k = 0; k < ns; k++)
        if (nu == 0 || x->sheets[nu - 1] != x->sheets[k])
            x->sheets[nu++] = x->sheets[k];
    j->points = malloc(3 * np * sizeof *j->points);
    j->vorigin = malloc(np * sizeof *j->vorigin);
    j->sheets = malloc((nu ? nu : 1) * sizeof *j->sheets);
    s->njunctions++; /* counted now so that destroy frees a partial one */
    if (!j->points || !j->vorigin || !j->sheets)
        return FM_ERR_NOMEM;
    for (size_t k = 0; k < np; k++) {
        j->vorigin[k] = x->verts[k];
        memcpy(j->points + 3 * k, x->xyz + 3 * (size_t)x->verts[k], 3 * sizeof *j->points);
    }
    memcpy(j->sheets, x->sheets, nu * sizeof *j->sheets);
    j->npoints = np;
    j->nsheets = nu;
    j->closed = closed;
    return FM_OK;
}

/* Walks from v along junction edge j until a vertex of degree != 2, or
 * back at v (closed). */
static fm_status walk(fm_surface *s, jctx *x, int32_t v, int32_t j)
{
    size_t np = 0, ne = 0;
    int32_t start = v;
    x->verts[np++] = v;
    for (;;) {
        x->used[j] = 1;
        x->edges[ne++] = j;
        v = other_end(x, j, v);
        if (v == start)
            return emit(s, x, np, ne, 1);
        x->verts[np++] = v;
        if (x->deg[v] != 2)
            break;
        j = next_edge(x, v);
        if (j < 0)
            break;
    }
    return emit(s, x, np, ne, 0);
}

fm_status rep_junctions(fm_surface *s, const rep_tris *t, const rep_edges *e,
                        const int32_t *sheet, const double *xyz, size_t nv)
{
    size_t nj = 0, nhe = 0;
    for (size_t k = 0; k < e->ne; k++)
        if (e->off[k + 1] - e->off[k] > 2) {
            nj++;
            nhe += (size_t)(e->off[k + 1] - e->off[k]);
        }
    if (nj == 0)
        return FM_OK;
    fm_status st = FM_ERR_NOMEM;
    jctx x = {t, e, sheet, xyz, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    int32_t *jedge = malloc(nj * sizeof *jedge);
    x.adj_start = calloc(nv + 1, sizeof *x.adj_start);
    x.adj = malloc(2 * nj * sizeof *x.adj);
    x.deg = calloc(nv ? nv : 1, sizeof *x.deg);
    x.used = calloc(nj, 1);
    x.verts = malloc((nj + 1) * sizeof *x.verts);
    x.edges = malloc(nj * sizeof *x.edges);
    x.sheets = malloc(nhe * sizeof *x.sheets);
    s->junctions = calloc(nj, sizeof *s->junctions);
    if (!jedge || !x.adj_start || !x.adj || !x.deg || !x.used || !x.verts || !x.edges ||
        !x.sheets || !s->junctions)
        goto done;
    x.jedge = jedge;
    nj = 0;
    for (size_t k = 0; k < e->ne; k++)
        if (e->off[k + 1] - e->off[k] > 2)
            jedge[nj++] = (int32_t)k;
    for (size_t j = 0; j < nj; j++) {
        int32_t h = e->he[e->off[jedge[j]]], tr = h / 3, i = h % 3;
        x.deg[t->v[3 * tr + i]]++;
        x.deg[t->v[3 * tr + (i + 1) % 3]]++;
    }
    for (size_t v = 0; v < nv; v++)
        x.adj_start[v + 1] = x.adj_start[v] + x.deg[v];
    int32_t *fill = x.deg; /* reuse as cursor, then restore the degrees */
    for (size_t v = 0; v < nv; v++)
        fill[v] = x.adj_start[v];
    for (size_t j = 0; j < nj; j++) {
        int32_t h = e->he[e->off[jedge[j]]], tr = h / 3, i = h % 3;
        x.adj[fill[t->v[3 * tr + i]]++] = (int32_t)j;
        x.adj[fill[t->v[3 * tr + (i + 1) % 3]]++] = (int32_t)j;
    }
    for (size_t v = 0; v < nv; v++)
        x.deg[v] = x.adj_start[v + 1] - x.adj_start[v];

    for (int pass = 0; pass < 2; pass++)
        for (size_t v = 0; v < nv; v++) {
            if (pass == 0 && (x.deg[v] == 2 || x.deg[v] == 0))
                continue; /* first the open curves, from their ends */
            int32_t j;
            while ((j = next_edge(&x, (int32_t)v)) >= 0)
                if ((st = walk(s, &x, (int32_t)v, j)) != FM_OK)
                    goto done;
        }
    st = FM_OK;
done:
    s->report.junctions = s->njunctions;
    free(jedge);
    free(x.adj_start);
    free(x.adj);
    free(x.deg);
    free(x.used);
    free(x.verts);
    free(x.edges);
    free(x.sheets);
    return st;
}
