/* Steps 4-6 output: one compact mesh per sheet.
 *
 * Sheet triangles keep their input order; sheet vertices are numbered in
 * order of first use by those triangles, so the numbering depends on the
 * input only. */
#include "repair_internal.h"

#include <stdlib.h>
#include <string.h>

typedef struct extract_ctx {
    const rep_tris *t;
    const int32_t *key, *nbr;
    const uint8_t *flip;
    const double *xyz;
    int32_t *map;      /* key -> sheet vertex (-1: not yet numbered), valid where
                          map_sheet == sheet */
    int32_t *map_sheet;
    int32_t *seen_sheet;   /* input vertex already in this sheet */
    int32_t *pinch_sheet;  /* input vertex already counted as pinched here */
    uint8_t *bnd;
} extract_ctx;

static fm_status extract_one(extract_ctx *x, rep_sheet *sh, int32_t s, const int32_t *tris,
                             size_t nt, fm_repair_report *r)
{
    const rep_tris *t = x->t;
    /* First pass: count the sheet's vertices, so everything is sized once. */
    size_t nv = 0;
    for (size_t k = 0; k < nt; k++)
        for (int i = 0; i < 3; i++) {
            int32_t key = x->key[3 * tris[k] + i];
            if (x->map_sheet[key] != s) {
                x->map_sheet[key] = s;
                x->map[key] = -1;
                nv++;
            }
        }
    sh->mesh = fm_mesh_create();
    sh->torigin = malloc((nt ? nt : 1) * sizeof *sh->torigin);
    sh->vorigin = malloc((nv ? nv : 1) * sizeof *sh->vorigin);
    if (!sh->mesh || !sh->torigin || !sh->vorigin || fm_mesh_reserve(sh->mesh, nv, nt) != FM_OK)
        return FM_ERR_NOMEM;
    for (size_t k = 0; k < nt; k++) {
        int32_t tr = tris[k], loc[3];
        for (int i = 0; i < 3; i++) {
            int32_t c = 3 * tr + i, key = x->key[c];
            if (x->map[key] < 0) {
                int32_t v = t->v[c];
                const double *p = x->xyz + 3 * (size_t)v;
                x->map[key] = fm_mesh_add_vertex(sh->mesh, p[0], p[1], p[2]);
                sh->vorigin[x->map[key]] = v;
                if (x->seen_sheet[v] == s && x->pinch_sheet[v] != s) {
                    x->pinch_sheet[v] = s;
                    r->nonmanifold_vertices++;
                }
                x->seen_sheet[v] = s;
            }
            loc[i] = x->map[key];
        }
        /* A flip reverses (a, b, c) to (a, c, b); output edge j then is input
         * edge 2 - j run backwards. */
        int f = x->flip[tr];
        fm_mesh_add_triangle(sh->mesh, loc[0], loc[f ? 2 : 1], loc[f ? 1 : 2], t->tag[tr]);
        for (int j = 0; j < 3; j++)
            x->bnd[3 * k + j] = x->nbr[3 * tr + (f ? 2 - j : j)] < 0;
        sh->torigin[k] = t->orig[tr];
    }
    r->vertices_out += nv;
    r->triangles_out += nt;
    return rep_sheet_loops(sh, x->bnd);
}

fm_status rep_extract_sheets(fm_surface *s, const rep_tris *t, const int32_t *sheet,
                             size_t nsheets, const int32_t *key, size_t nkeys,
                             const int32_t *nbr, const uint8_t *flip, const double *normals,
                             const double *xyz, size_t nv)
{
    fm_repair_report *r = &s->report;
    fm_status st = FM_ERR_NOMEM;
    size_t n = t->n;
    extract_ctx x = {t, key, nbr, flip, xyz, NULL, NULL, NULL, NULL, NULL};
    int32_t *start = calloc(nsheets + 1, sizeof *start);
    int32_t *order = malloc((n ? n : 1) * sizeof *order);
    x.map = malloc((nkeys ? nkeys : 1) * sizeof *x.map);
    x.map_sheet = malloc((nkeys ? nkeys : 1) * sizeof *x.map_sheet);
    x.seen_sheet = malloc((nv ? nv : 1) * sizeof *x.seen_sheet);
    x.pinch_sheet = malloc((nv ? nv : 1) * sizeof *x.pinch_sheet);
    x.bnd = malloc(3 * (n ? n : 1));
    s->sheets = calloc(nsheets ? nsheets : 1, sizeof *s->sheets);
    if (!start || !order || !x.map || !x.map_sheet || !x.seen_sheet || !x.pinch_sheet ||
        !x.bnd || !s->sheets)
        goto done;
    s->nsheets = nsheets;
    memset(x.map_sheet, 0xff, (nkeys ? nkeys : 1) * sizeof *x.map_sheet);
    memset(x.seen_sheet, 0xff, (nv ? nv : 1) * sizeof *x.seen_sheet);
    memset(x.pinch_sheet, 0xff, (nv ? nv : 1) * sizeof *x.pinch_sheet);

    /* Triangles grouped by sheet, in input order within a sheet. */
    for (size_t i = 0; i < n; i++)
        start[sheet[i] + 1]++;
    for (size_t k = 0; k < nsheets; k++)
        start[k + 1] += start[k];
    for (size_t i = 0; i < n; i++)
        order[start[sheet[i]]++] = (int32_t)i;
    for (size_t k = nsheets; k > 0; k--)
        start[k] = start[k - 1];
    start[0] = 0;

    for (size_t k = 0; k < nsheets; k++) {
        rep_sheet *sh = &s->sheets[k];
        memcpy(sh->normal, normals + 3 * k, sizeof sh->normal);
        st = extract_one(&x, sh, (int32_t)k, order + start[k],
                         (size_t)(start[k + 1] - start[k]), r);
        if (st != FM_OK)
            goto done;
        r->boundary_loops += sh->nloops;
        if (sh->nloops > 0)
            r->holes += sh->nloops - 1;
    }
    st = FM_OK;
done:
    free(start);
    free(order);
    free(x.map);
    free(x.map_sheet);
    free(x.seen_sheet);
    free(x.pinch_sheet);
    free(x.bnd);
    return st;
}
