/* Step 2: degenerate and duplicate triangles, unused vertices. */
#include "repair_internal.h"

#include <stdlib.h>
#include <string.h>

#include "fm_predicates.h"

void rep_tris_free(rep_tris *t)
{
    free(t->v);
    free(t->tag);
    free(t->orig);
    memset(t, 0, sizeof *t);
}

static void sort3(const int32_t *v, int32_t *s)
{
    int32_t a = v[0], b = v[1], c = v[2], x;
    if (a > b) { x = a; a = b; b = x; }
    if (b > c) { x = b; b = c; c = x; }
    if (a > b) { x = a; a = b; b = x; }
    s[0] = a;
    s[1] = b;
    s[2] = c;
}

static uint64_t tri_hash(const int32_t *s)
{
    uint64_t h = rep_mix64(((uint64_t)(uint32_t)s[0] << 32) | (uint32_t)s[1]);
    return rep_mix64(h ^ (uint32_t)s[2]);
}

fm_status rep_clean(const fm_mesh *in, const int32_t *rep, rep_tris *out,
                    fm_repair_report *r)
{
    size_t nt = fm_mesh_ntriangles(in);
    const int32_t *tri = fm_mesh_triangles(in);
    const int32_t *tags = fm_mesh_tags(in);
    const double *xyz = fm_mesh_vertices(in);
    memset(out, 0, sizeof *out);
    size_t size = rep_table_size(nt);
    int32_t *table = size ? malloc(size * sizeof *table) : NULL;
    out->v = malloc((nt ? nt : 1) * 3 * sizeof *out->v);
    out->tag = malloc((nt ? nt : 1) * sizeof *out->tag);
    out->orig = malloc((nt ? nt : 1) * sizeof *out->orig);
    if (!table || !out->v || !out->tag || !out->orig) {
        free(table);
        rep_tris_free(out);
        return FM_ERR_NOMEM;
    }
    memset(table, 0xff, size * sizeof *table);
    size_t mask = size - 1, n = 0;
    for (size_t t = 0; t < nt; t++) {
        int32_t v[3] = {rep[tri[3 * t]], rep[tri[3 * t + 1]], rep[tri[3 * t + 2]]};
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] ||
            fm_collinear3d(xyz + 3 * (size_t)v[0], xyz + 3 * (size_t)v[1],
                           xyz + 3 * (size_t)v[2])) {
            r->degenerate_removed++;
            continue;
        }
        /* The table holds kept triangles; the first of a vertex set wins. */
        int32_t s[3], o[3];
        sort3(v, s);
        size_t slot = (size_t)tri_hash(s) & mask;
        int dup = 0;
        for (;;) {
            int32_t k = table[slot];
            if (k < 0) {
                table[slot] = (int32_t)n;
                break;
            }
            sort3(out->v + 3 * (size_t)k, o);
            if (o[0] == s[0] && o[1] == s[1] && o[2] == s[2]) {
                dup = 1;
                break;
            }
            slot = (slot + 1) & mask;
        }
        if (dup) {
            r->duplicates_removed++;
            continue;
        }
        memcpy(out->v + 3 * n, v, sizeof v);
        out->tag[n] = tags[t];
        out->orig[n] = (int32_t)t;
        n++;
    }
    out->n = n;
    free(table);
    return FM_OK;
}

fm_status rep_count_unused(const rep_tris *t, const int32_t *rep, size_t nv, size_t *unused)
{
    uint8_t *used = calloc(nv ? nv : 1, 1);
    if (!used)
        return FM_ERR_NOMEM;
    for (size_t i = 0; i < 3 * t->n; i++)
        used[t->v[i]] = 1;
    *unused = 0;
    for (size_t v = 0; v < nv; v++)
        if (rep[v] == (int32_t)v && !used[v])
            (*unused)++;
    free(used);
    return FM_OK;
}
