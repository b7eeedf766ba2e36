/* The boundary loops of a sheet's mesh in its (u, v) plane: the domain
 * the mesher meshed, for the CAD model (fm_remesh.h). */
#include <stdlib.h>
#include <string.h>

#include "fm_remesh.h"
#include "fm_sort.h"

void fm_remesh_boundary_free(fm_remesh_boundary *b)
{
    if (!b)
        return;
    free(b->start);
    free(b->part);
    free(b->uv);
    free(b->xyz);
    free(b->node);
    memset(b, 0, sizeof *b);
}

static uint64_t directed(int32_t a, int32_t b) { return (uint64_t)(uint32_t)a << 32 | (uint32_t)b; }

/* The half-edge a -> b (3 t + k: triangle t, from its k-th corner), or -1. */
static long long find_half(const fm_keyed *h, size_t n, int32_t a, int32_t b)
{
    uint64_t key = directed(a, b);
    size_t at = fm_keyed_lower_bound(h, n, key);
    return at < n && h[at].key == key ? (long long)h[at].index : -1;
}

static size_t find_root(size_t *parent, size_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

typedef struct loop_rec {
    size_t part, first, n; /* first: offset into the traced points */
    int outer;             /* counter-clockwise */
    size_t order;          /* traced order, for a stable sort */
} loop_rec;

static int by_part_outer_first(const void *a, const void *b)
{
    const loop_rec *x = a, *y = b;
    if (x->part != y->part)
        return x->part < y->part ? -1 : 1;
    if (x->outer != y->outer)
        return x->outer ? -1 : 1;
    return (x->order > y->order) - (x->order < y->order);
}

fm_status fm_remesh_boundary_of(const fm_mesh *m, const double *uv, const int64_t *ids,
                                fm_remesh_boundary *b, fm_error *err)
{
    memset(b, 0, sizeof *b);
    size_t nt = fm_mesh_ntriangles(m), nh = 3 * nt;
    const int32_t *T = fm_mesh_triangles(m);
    const double *X = fm_mesh_vertices(m);
    fm_keyed *half = malloc((nh + 1) * sizeof *half);
    size_t *parent = malloc((nt + 1) * sizeof *parent);
    size_t *label = malloc((nt + 1) * sizeof *label);
    unsigned char *seen = calloc(nh + 1, 1);
    size_t *pts = malloc((nh + 1) * sizeof *pts); /* loops: half-edges, loop by loop */
    size_t *cur = malloc((nh + 1) * sizeof *cur);  /* the loop being traced */
    size_t *stack = malloc((nh + 1) * sizeof *stack);
    size_t nv = fm_mesh_nvertices(m);
    long long *at = malloc((nv + 1) * sizeof *at); /* vertex -> place on the stack, or -1 */
    loop_rec *rec = NULL;
    size_t nrec = 0, cap = 0, npts = 0;
    fm_status rc = FM_OK;
    if (!half || !parent || !label || !seen || !pts || !cur || !stack || !at)
        goto nomem;
    for (size_t v = 0; v < nv; v++)
        at[v] = -1;
    for (size_t h = 0; h < nh; h++)
        half[h] = (fm_keyed){directed(T[h], T[h / 3 * 3 + (h % 3 + 1) % 3]), h};
    if (fm_sort_keyed(half, nh))
        goto nomem;
    for (size_t k = 1; k < nh; k++)
        if (half[k].key == half[k - 1].key) {
            rc = fm_error_set(err, FM_ERR_TOPOLOGY, NULL, 0,
                              "mesh boundary: an edge is used twice the same way");
            goto done;
        }
    /* parts: triangles joined across their edges */
    for (size_t t = 0; t < nt; t++)
        parent[t] = t;
    for (size_t h = 0; h < nh; h++) {
        int32_t a = T[h], c = T[h / 3 * 3 + (h % 3 + 1) % 3];
        long long o = find_half(half, nh, c, a);
        if (o >= 0) {
            size_t r1 = find_root(parent, h / 3), r2 = find_root(parent, (size_t)o / 3);
            if (r1 != r2)
                parent[r1 > r2 ? r1 : r2] = r1 > r2 ? r2 : r1;
        }
    }
    for (size_t t = 0; t < nt; t++)
        label[t] = (size_t)-1;
    for (size_t t = 0; t < nt; t++) {
        size_t r = find_root(parent, t);
        if (label[r] == (size_t)-1)
            label[r] = b->nparts++;
        label[t] = label[r];
    }
    /* Loops: from each boundary half-edge not yet used, in key order (the
     * same mesh gives the same loops). The next one from its end b is
     * found by turning around b through the triangles (b -> c of the same
     * triangle, then across to the neighbour's next) until an edge without
     * a twin: that keeps apart two loops that touch at b. */
    for (size_t s = 0; s < nh; s++) {
        size_t h0 = half[s].index;
        int32_t a0 = T[h0], b0 = T[h0 / 3 * 3 + (h0 % 3 + 1) % 3];
        if (seen[h0] || find_half(half, nh, b0, a0) >= 0)
            continue;
        size_t ncur = 0, h = h0;
        for (;;) {
            if (seen[h]) {
                rc = fm_error_set(err, FM_ERR_TOPOLOGY, NULL, 0,
                                  "mesh boundary: a loop runs into another");
                goto done;
            }
            seen[h] = 1;
            cur[ncur++] = h;
            size_t g = h / 3 * 3 + (h % 3 + 1) % 3; /* vb -> next corner */
            for (size_t turns = 0;; turns++) {
                int32_t ga = T[g], gb = T[g / 3 * 3 + (g % 3 + 1) % 3];
                long long tw = find_half(half, nh, gb, ga);
                if (tw < 0)
                    break;
                if (turns > nt) {
                    rc = fm_error_set(err, FM_ERR_TOPOLOGY, NULL, 0,
                                      "mesh boundary: no way on around a node");
                    goto done;
                }
                g = (size_t)tw / 3 * 3 + ((size_t)tw % 3 + 1) % 3;
            }
            h = g;
            if (h == h0)
                break;
        }
        /* A loop through a node twice (a hole touching the outline, or
         * itself, at a node) is cut there into simple loops: each closes
         * when the walk comes back to a node still on the stack. */
        size_t ns = 0;
        for (size_t i = 0; i <= ncur; i++) {
            size_t hh = cur[i % ncur];
            int32_t v = T[hh];
            if (at[v] >= 0) { /* at i == ncur: the loop closes, all that is left */
                size_t from = (size_t)at[v];
                if (nrec == cap) {
                    cap = cap ? 2 * cap : 8;
                    loop_rec *r = realloc(rec, cap * sizeof *r);
                    if (!r)
                        goto nomem;
                    rec = r;
                }
                double area = 0;
                size_t first = npts;
                for (size_t k = from; k < ns; k++) {
                    size_t e = stack[k];
                    int32_t va = T[e], vb = T[e / 3 * 3 + (e % 3 + 1) % 3];
                    area += uv[2 * va] * uv[2 * vb + 1] - uv[2 * vb] * uv[2 * va + 1];
                    pts[npts++] = e;
                    if (k > from)
                        at[va] = -1;
                }
                rec[nrec] = (loop_rec){label[h0 / 3], first, npts - first, area > 0, nrec};
                nrec++;
                ns = from;
                if (i == ncur) {
                    at[v] = -1;
                    break;
                }
            }
            at[v] = (long long)ns;
            stack[ns++] = hh;
        }
    }
    if (nrec > 1)
        qsort(rec, nrec, sizeof *rec, by_part_outer_first);
    for (size_t k = 0; k < nrec; k++) {
        int first_of_part = k == 0 || rec[k].part != rec[k - 1].part;
        if (rec[k].outer != first_of_part) {
            rc = fm_error_set(err, FM_ERR_TOPOLOGY, NULL, 0,
                              "mesh boundary: part %zu has %s outer loop", rec[k].part,
                              first_of_part ? "no" : "more than one");
            goto done;
        }
    }
    b->nloops = nrec;
    b->start = malloc((nrec + 1) * sizeof *b->start);
    b->part = malloc((nrec + 1) * sizeof *b->part);
    b->uv = malloc((2 * npts + 1) * sizeof *b->uv);
    b->xyz = malloc((3 * npts + 1) * sizeof *b->xyz);
    b->node = malloc((npts + 1) * sizeof *b->node);
    if (!b->start || !b->part || !b->uv || !b->xyz || !b->node)
        goto nomem;
    size_t w = 0;
    for (size_t k = 0; k < nrec; k++) {
        b->start[k] = w;
        b->part[k] = rec[k].part;
        for (size_t i = 0; i < rec[k].n; i++, w++) {
            int32_t v = T[pts[rec[k].first + i]];
            memcpy(b->uv + 2 * w, uv + 2 * v, 2 * sizeof *b->uv);
            memcpy(b->xyz + 3 * w, X + 3 * v, 3 * sizeof *b->xyz);
            b->node[w] = ids ? ids[v] : -1;
        }
    }
    b->start[nrec] = w;
    goto done;
nomem:
    rc = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
done:
    if (rc != FM_OK)
        fm_remesh_boundary_free(b);
    free(half);
    free(parent);
    free(label);
    free(seen);
    free(pts);
    free(cur);
    free(stack);
    free(at);
    free(rec);
    return rc;
}
