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

/* Kept triangles by sorted vertex triple; the key is stored in the slot so
 * a probe costs one cache miss. v[0] < 0 marks an empty slot. */
typedef struct tri_slot {
    int32_t v[3];
} tri_slot;

/* 1 if s (sorted) is already in the table, else inserts it and returns 0. */
static int seen_before(tri_slot *table, size_t mask, const int32_t *s)
{
    size_t slot = (size_t)tri_hash(s) & mask;
    for (;;) {
        tri_slot *e = &table[slot];
        if (e->v[0] < 0) {
            memcpy(e->v, s, sizeof e->v);
            return 0;
        }
        if (e->v[0] == s[0] && e->v[1] == s[1] && e->v[2] == s[2])
            return 1;
        slot = (slot + 1) & mask;
    }
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
    tri_slot *table = size ? malloc(size * sizeof *table) : NULL;
    out->v = malloc((nt ? nt : 1) * 3 * sizeof *out->v);
    out->tag = malloc((nt ? nt : 1) * sizeof *out->tag);
    out->orig = malloc((nt ? nt : 1) * sizeof *out->orig);
    if (!table || !out->v || !out->tag || !out->orig) {
        free(table);
        rep_tris_free(out);
        return FM_ERR_NOMEM;
    }
    memset(table, 0xff, size * sizeof *table);
    size_t n = 0;
    for (size_t t = 0; t < nt; t++) {
        int32_t v[3] = {rep[tri[3 * t]], rep[tri[3 * t + 1]], rep[tri[3 * t + 2]]};
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] ||
            fm_collinear3d(xyz + 3 * (size_t)v[0], xyz + 3 * (size_t)v[1],
                           xyz + 3 * (size_t)v[2])) {
            r->degenerate_removed++;
            continue;
        }
        /* Triangles are tried in input order, so the first copy is kept. */
        int32_t s[3];
        sort3(v, s);
        if (seen_before(table, size - 1, s)) {
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
