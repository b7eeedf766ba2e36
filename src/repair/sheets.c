/* Step 4b: sheets and their vertices.
 *
 * A sheet is a set of triangles linked through the neighbour relation of
 * pairing.c. Its vertices are not the input vertices but the fans around
 * them: corners of triangles linked through an edge at that vertex. This
 * one rule splits a pinched (bowtie) vertex into one copy per fan, and also
 * keeps apart the corners of a triangle that a splay reconnects to its own
 * sheet elsewhere, so every sheet mesh is edge-manifold. */
#include "repair_internal.h"

#include <stdlib.h>

fm_status rep_sheets(const rep_tris *t, const rep_edges *e, const int32_t *nbr, int split,
                     int32_t *sheet, size_t *nsheets)
{
    size_t n = t->n;
    *nsheets = 0;
    int32_t *parent = malloc((n ? n : 1) * sizeof *parent);
    if (!parent)
        return FM_ERR_NOMEM;
    for (size_t i = 0; i < n; i++)
        parent[i] = (int32_t)i;
    if (split) {
        for (size_t h = 0; h < 3 * n; h++)
            if (nbr[h] >= 0)
                uf_union(parent, (int32_t)(h / 3), nbr[h] / 3);
    } else {
        for (size_t k = 0; k < e->ne; k++)
            for (int32_t j = e->off[k] + 1; j < e->off[k + 1]; j++)
                uf_union(parent, e->he[e->off[k]] / 3, e->he[j] / 3);
    }
    for (size_t i = 0; i < n; i++) {
        int32_t root = uf_find(parent, (int32_t)i);
        sheet[i] = root == (int32_t)i ? (int32_t)(*nsheets)++ : sheet[root];
    }
    free(parent);
    return FM_OK;
}

static int32_t slot_of(const int32_t *tv, int32_t v)
{
    return tv[0] == v ? 0 : tv[1] == v ? 1 : 2;
}

static void fan_keys(const rep_tris *t, const int32_t *nbr, int32_t *key)
{
    size_t nc = 3 * t->n;
    for (size_t c = 0; c < nc; c++)
        key[c] = (int32_t)c;
    for (size_t h = 0; h < nc; h++) {
        int32_t g = nbr[h];
        if (g < (int32_t)h)
            continue; /* unlinked, or the pair was seen from g */
        int32_t tr = (int32_t)(h / 3), i = (int32_t)(h % 3), u = g / 3;
        int32_t a = t->v[3 * tr + i], b = t->v[3 * tr + (i + 1) % 3];
        const int32_t *uv = t->v + 3 * (size_t)u;
        uf_union(key, 3 * tr + i, 3 * u + slot_of(uv, a));
        uf_union(key, 3 * tr + (i + 1) % 3, 3 * u + slot_of(uv, b));
    }
    for (size_t c = 0; c < nc; c++)
        key[c] = uf_find(key, (int32_t)c);
}

static void unlink_he(int32_t *nbr, int32_t h, size_t *cuts)
{
    if (nbr[h] < 0)
        return;
    nbr[nbr[h]] = -1;
    nbr[h] = -1;
    (*cuts)++;
}

/* Fans can still glue a sheet to itself along an edge: a triangle left
 * unpaired at a non-manifold edge whose corners are, around both ends, in
 * the fans of the pair that continues there (the sheet wraps round and
 * touches itself). The sheet mesh would then hold that edge three times,
 * or twice without a link. Each such extra triangle is cut from its fan at
 * one end of the edge (its other edge there is unlinked), which gives it
 * its own copy of that vertex. Cuts only split fans, so no new glued edge
 * appears and one round resolves all; a second round checks. Never
 * happens on sane input. */
static fm_status untangle(const rep_tris *t, int32_t *nbr, int32_t *key, size_t *cuts)
{
    rep_tris kt = {t->n, key, NULL, NULL};
    rep_edges ke;
    fm_status st = rep_edges_build(&kt, 3 * t->n, &ke);
    if (st != FM_OK)
        return st;
    for (size_t e = 0; e < ke.ne; e++) {
        int32_t first = ke.off[e], last = ke.off[e + 1];
        if (last - first == 1)
            continue;
        /* Keep one linked pair of the group (or its first half-edge). */
        int32_t keep_a = ke.he[first], keep_b = -1;
        for (int32_t k = first; k < last; k++) {
            int32_t h = ke.he[k];
            if (nbr[h] >= 0 && ke.edge_of[nbr[h]] == (int32_t)e) {
                keep_a = h;
                keep_b = nbr[h];
                break;
            }
        }
        /* Every extra is cut at the same end (the lower key), so that two
         * extras linked to each other leave the fan together. */
        int32_t h0 = ke.he[first];
        int32_t lo = key[h0] < key[h0 - h0 % 3 + (h0 % 3 + 1) % 3]
                         ? key[h0]
                         : key[h0 - h0 % 3 + (h0 % 3 + 1) % 3];
        for (int32_t k = first; k < last; k++) {
            int32_t h = ke.he[k], base = h - h % 3, i = h % 3;
            if (h == keep_a || h == keep_b)
                continue;
            /* The other edge at corner i is (i+2)%3, at corner i+1 it is
             * (i+1)%3. */
            unlink_he(nbr, base + (key[h] == lo ? (i + 2) % 3 : (i + 1) % 3), cuts);
        }
    }
    rep_edges_free(&ke);
    return FM_OK;
}

/* Bounds the untangling rounds; each round cuts at least one link, and one
 * round suffices in every case seen, so this is only a safety net. */
#define MAX_UNTANGLE_ROUNDS 64

fm_status rep_corner_keys(const rep_tris *t, int32_t *nbr, int split, int32_t *key)
{
    size_t nc = 3 * t->n;
    if (!split) {
        for (size_t c = 0; c < nc; c++)
            key[c] = t->v[c];
        return FM_OK;
    }
    for (int round = 0; round < MAX_UNTANGLE_ROUNDS; round++) {
        size_t cuts = 0;
        fan_keys(t, nbr, key);
        fm_status st = untangle(t, nbr, key, &cuts);
        if (st != FM_OK)
            return st;
        if (cuts == 0)
            return FM_OK;
    }
    fan_keys(t, nbr, key);
    return FM_OK;
}
