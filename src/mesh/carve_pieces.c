/* Edge-connected pieces of each fault of a set (carve_pieces.h). */
#include <stdlib.h>

#include "carve_pieces.h"
#include "fm_sort.h"

struct cv_pieces {
    const fm_mesh *m;
    size_t *adj_first; /* per triangle: its neighbours adj[adj_first[t] ..] */
    int32_t *adj;
    size_t *tri_first; /* per fault: its triangles tri[tri_first[f] ..] */
    int32_t *tri;
    size_t nf;
    int32_t *seen;     /* per triangle: the count that last reached it */
    int32_t visit;
    unsigned char *out; /* the triangles a count leaves out */
    int32_t *stack;
};

void cv_pieces_destroy(cv_pieces *p)
{
    if (!p)
        return;
    free(p->adj_first);
    free(p->adj);
    free(p->tri_first);
    free(p->tri);
    free(p->seen);
    free(p->out);
    free(p->stack);
    free(p);
}

/* Pairs of triangles of one fault that share a side: counted (adj NULL)
 * or listed into adj at each triangle's next free place (at). */
static void side_pairs(const fm_keyed *side, size_t ns, const int32_t *tag, size_t *count,
                       int32_t *adj, size_t *at)
{
    for (size_t s = 0, e; s < ns; s = e) {
        for (e = s + 1; e < ns && side[e].key == side[s].key; e++)
            ;
        for (size_t i = s; i < e; i++)
            for (size_t j = i + 1; j < e; j++) {
                size_t a = side[i].index, b = side[j].index;
                if (tag[a] != tag[b] || a == b)
                    continue;
                if (adj) {
                    adj[at[a]++] = (int32_t)b;
                    adj[at[b]++] = (int32_t)a;
                } else {
                    count[a + 1]++;
                    count[b + 1]++;
                }
            }
    }
}

cv_pieces *cv_pieces_create(const fm_mesh *m)
{
    size_t nt = fm_mesh_ntriangles(m), ns = 0, nf = 0;
    const int32_t *tag = fm_mesh_tags(m);
    for (size_t t = 0; t < nt; t++)
        if (tag[t] >= 0 && (size_t)tag[t] + 1 > nf)
            nf = (size_t)tag[t] + 1;
    cv_pieces *p = calloc(1, sizeof *p);
    fm_keyed *side = p ? fm_mesh_sides(m, &ns) : NULL;
    if (p) {
        p->m = m;
        p->nf = nf;
        p->adj_first = calloc(nt + 2, sizeof *p->adj_first);
        p->tri_first = calloc(nf + 2, sizeof *p->tri_first);
        p->tri = malloc((nt + 1) * sizeof *p->tri);
        p->seen = calloc(nt + 1, sizeof *p->seen);
        p->out = calloc(nt + 1, 1);
        p->stack = malloc((nt + 1) * sizeof *p->stack);
    }
    size_t *at = malloc((nt + nf + 2) * sizeof *at);
    if (!side || !at || !p->adj_first || !p->tri_first || !p->tri || !p->seen || !p->out ||
        !p->stack) {
        free(side);
        free(at);
        cv_pieces_destroy(p);
        return NULL;
    }
    side_pairs(side, ns, tag, p->adj_first, NULL, NULL);
    for (size_t t = 0; t < nt; t++)
        p->adj_first[t + 1] += p->adj_first[t];
    p->adj = malloc((p->adj_first[nt] + 1) * sizeof *p->adj);
    if (!p->adj) {
        free(side);
        free(at);
        cv_pieces_destroy(p);
        return NULL;
    }
    for (size_t t = 0; t < nt; t++)
        at[t] = p->adj_first[t];
    side_pairs(side, ns, tag, NULL, p->adj, at);
    free(side);
    for (size_t t = 0; t < nt; t++)
        if (tag[t] >= 0)
            p->tri_first[tag[t] + 1]++;
    for (size_t f = 0; f < nf; f++)
        p->tri_first[f + 1] += p->tri_first[f];
    for (size_t f = 0; f < nf; f++)
        at[f] = p->tri_first[f];
    for (size_t t = 0; t < nt; t++)
        if (tag[t] >= 0)
            p->tri[at[tag[t]]++] = (int32_t)t;
    free(at);
    return p;
}

size_t cv_pieces_count(cv_pieces *p, int32_t f, const unsigned char *gone, const int32_t *t,
                       size_t n)
{
    if (f < 0 || (size_t)f >= p->nf)
        return 0;
    for (size_t k = 0; k < n; k++)
        p->out[t[k]] = 1;
    int32_t v = ++p->visit;
    size_t pieces = 0;
    for (size_t i = p->tri_first[f]; i < p->tri_first[f + 1]; i++) {
        int32_t s = p->tri[i];
        if (gone[s] || p->out[s] || p->seen[s] == v)
            continue;
        pieces++;
        size_t top = 0;
        p->stack[top++] = s;
        p->seen[s] = v;
        while (top) {
            int32_t a = p->stack[--top];
            for (size_t k = p->adj_first[a]; k < p->adj_first[a + 1]; k++) {
                int32_t b = p->adj[k];
                if (!gone[b] && !p->out[b] && p->seen[b] != v) {
                    p->seen[b] = v;
                    p->stack[top++] = b;
                }
            }
        }
    }
    for (size_t k = 0; k < n; k++)
        p->out[t[k]] = 0;
    return pieces;
}
