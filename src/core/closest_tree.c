/* Building the AABB tree of fm_closest.h (queries: closest_query.c,
 * closest_box.c).
 *
 * Splits are binned SAH over all three axes; the build reads only the
 * triangles' order and coordinates, so the same mesh always gives the same
 * tree. The quick build sorts the triangles by the Morton code of their
 * centroids and splits that order where the leading bit of the code
 * changes (octree cells): several times faster to build, a little slower
 * to query. */
#include "closest_tree.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define LEAF_MAX 4
#define SAH_BINS 16

/* A triangle while building: its box (rounded outwards) and centroid. */
typedef struct item {
    float lo[3], hi[3], c[3];
    int32_t tri;
} item;

typedef struct builder {
    item *items;
    closest_node *nodes;
    size_t nnode;
} builder;

/* nextafterf(f, up ? INFINITY : -INFINITY) for f not NaN, without the call. */
static float float_step(float f, int up)
{
    if (f == 0)
        return up ? FLT_TRUE_MIN : -FLT_TRUE_MIN;
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    b = (f > 0) == (up != 0) ? b + 1 : b - 1;
    memcpy(&f, &b, sizeof f);
    return f;
}

static float float_down(double x)
{
    float f = (float)x;
    return (double)f > x ? float_step(f, 0) : f;
}

static float float_up(double x)
{
    float f = (float)x;
    return (double)f < x ? float_step(f, 1) : f;
}

static double half_area(const float lo[3], const float hi[3])
{
    double dx = (double)hi[0] - lo[0], dy = (double)hi[1] - lo[1], dz = (double)hi[2] - lo[2];
    return dx * dy + dy * dz + dz * dx;
}

static void box_empty(float lo[3], float hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
}

/* Unconditional stores of the same choice as "if (plo < lo) lo = plo": the
 * compiler makes them min/max instructions instead of branches that random
 * boxes mispredict (same result for every input, zeros and NaN included). */
static void box_grow(float lo[3], float hi[3], const float plo[3], const float phi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = plo[k] < lo[k] ? plo[k] : lo[k];
        hi[k] = phi[k] > hi[k] ? phi[k] : hi[k];
    }
}

static int bin_of(float c, float cmin, double scale)
{
    int k = (int)(((double)c - cmin) * scale);
    return k < SAH_BINS ? k : SAH_BINS - 1;
}

/* Best SAH split of items[b, e): sets *axis and *split (bins <= split go
 * left) and returns 1, or returns 0 when the centroids cannot be told apart. */
static int sah_split(const item *it, size_t b, size_t e, const float cmin[3],
                     const float cmax[3], int *axis, int *split)
{
    double best = INFINITY;
    for (int ax = 0; ax < 3; ax++) {
        double ext = (double)cmax[ax] - cmin[ax];
        if (!(ext > 0))
            continue;
        double scale = SAH_BINS / ext;
        size_t count[SAH_BINS] = {0};
        float lo[SAH_BINS][3], hi[SAH_BINS][3];
        for (int k = 0; k < SAH_BINS; k++)
            box_empty(lo[k], hi[k]);
        for (size_t i = b; i < e; i++) {
            int k = bin_of(it[i].c[ax], cmin[ax], scale);
            count[k]++;
            box_grow(lo[k], hi[k], it[i].lo, it[i].hi);
        }
        double right_cost[SAH_BINS];
        size_t n = 0;
        float rlo[3], rhi[3];
        box_empty(rlo, rhi);
        for (int k = SAH_BINS - 1; k > 0; k--) {
            n += count[k];
            box_grow(rlo, rhi, lo[k], hi[k]);
            right_cost[k] = n ? half_area(rlo, rhi) * (double)n : 0;
        }
        size_t nl = 0;
        float llo[3], lhi[3];
        box_empty(llo, lhi);
        for (int k = 0; k < SAH_BINS - 1; k++) {
            nl += count[k];
            box_grow(llo, lhi, lo[k], hi[k]);
            if (nl == 0 || nl == e - b)
                continue;
            double cost = half_area(llo, lhi) * (double)nl + right_cost[k + 1];
            if (cost < best) {
                best = cost;
                *axis = ax;
                *split = k;
            }
        }
    }
    return best < INFINITY;
}

/* Orders items by centroid on one axis, then by triangle index, so that a
 * median split is well defined even among equal centroids. */
static int item_before(const item *x, const item *y, int ax)
{
    if (x->c[ax] != y->c[ax])
        return x->c[ax] < y->c[ax];
    return x->tri < y->tri;
}

static void sift_down(item *it, size_t root, size_t n, int ax)
{
    for (;;) {
        size_t child = 2 * root + 1;
        if (child >= n)
            return;
        if (child + 1 < n && item_before(&it[child], &it[child + 1], ax))
            child++;
        if (!item_before(&it[root], &it[child], ax))
            return;
        item tmp = it[root];
        it[root] = it[child];
        it[child] = tmp;
        root = child;
    }
}

/* Heapsort: in place, O(n log n) in every case, and no comparator context
 * through globals (builds may run on several threads). */
static void sort_items(item *it, size_t n, int ax)
{
    for (size_t i = n / 2; i-- > 0;)
        sift_down(it, i, n, ax);
    for (size_t end = n; end-- > 1;) {
        item tmp = it[0];
        it[0] = it[end];
        it[end] = tmp;
        sift_down(it, 0, end, ax);
    }
}

static void build_node(builder *B, size_t node, size_t b, size_t e, int depth)
{
    item *it = B->items;
    closest_node *N = &B->nodes[node];
    float cmin[3], cmax[3];
    box_empty(N->lo, N->hi);
    box_empty(cmin, cmax);
    for (size_t i = b; i < e; i++) {
        box_grow(N->lo, N->hi, it[i].lo, it[i].hi);
        box_grow(cmin, cmax, it[i].c, it[i].c);
    }
    if (e - b <= LEAF_MAX) {
        N->first = (int32_t)b;
        N->count = (int32_t)(e - b);
        return;
    }
    size_t mid = b + (e - b) / 2;
    int axis = 0, split = 0;
    if (depth < CLOSEST_SAH_DEPTH && sah_split(it, b, e, cmin, cmax, &axis, &split)) {
        double scale = SAH_BINS / ((double)cmax[axis] - cmin[axis]);
        size_t i = b, j = e;
        while (i < j) {
            if (bin_of(it[i].c[axis], cmin[axis], scale) <= split) {
                i++;
            } else {
                item tmp = it[i];
                it[i] = it[--j];
                it[j] = tmp;
            }
        }
        mid = i;
    } else if (depth >= CLOSEST_SAH_DEPTH) {
        int ax = 0;
        for (int k = 1; k < 3; k++)
            if ((double)cmax[k] - cmin[k] > (double)cmax[ax] - cmin[ax])
                ax = k;
        sort_items(it + b, e - b, ax);
    }
    /* else: all centroids coincide; halving the range is as good as any. */
    size_t left = B->nnode;
    B->nnode += 2;
    N->first = (int32_t)left;
    N->count = 0;
    build_node(B, left, b, mid, depth + 1);
    build_node(B, left + 1, mid, e, depth + 1);
}

/* ---- Quick build: Morton order ---- */

#define MORTON_BITS 16 /* per axis */

/* The low 21 bits of x spread to every third bit. */
static uint64_t spread(uint64_t x)
{
    x &= 0x1fffffu;
    x = (x | x << 32) & 0x1f00000000ffffull;
    x = (x | x << 16) & 0x1f0000ff0000ffull;
    x = (x | x << 8) & 0x100f00f00f00f00full;
    x = (x | x << 4) & 0x10c30c30c30c30c3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
}

/* Items in Morton order of their centroids (16 bits per axis over the
 * centroids' box): a stable radix sort of (code, index) pairs, so ties
 * stay in triangle order, then the items moved once. *codes receives
 * the sorted codes. */
static int morton_order(item **items, size_t n, uint64_t **codes)
{
    float cmin[3], cmax[3];
    box_empty(cmin, cmax);
    for (size_t i = 0; i < n; i++)
        box_grow(cmin, cmax, (*items)[i].c, (*items)[i].c);
    uint64_t *code = malloc(n * sizeof *code), *code2 = malloc(n * sizeof *code2);
    uint32_t *idx = malloc(n * sizeof *idx), *idx2 = malloc(n * sizeof *idx2);
    size_t *count = malloc(4097 * sizeof *count);
    item *sorted = malloc(n * sizeof *sorted);
    if (!code || !code2 || !idx || !idx2 || !count || !sorted) {
        free(code);
        free(code2);
        free(idx);
        free(idx2);
        free(count);
        free(sorted);
        return -1;
    }
    const double top = (double)((1u << MORTON_BITS) - 1);
    double scale[3];
    for (int a = 0; a < 3; a++) {
        double ext = (double)cmax[a] - cmin[a];
        scale[a] = ext > 0 ? top / ext : 0.0;
    }
    for (size_t i = 0; i < n; i++) {
        uint64_t c = 0;
        for (int a = 0; a < 3; a++) {
            double q = ((double)(*items)[i].c[a] - cmin[a]) * scale[a];
            uint64_t b = q > 0 ? (uint64_t)(q + 0.5) : 0u;
            c |= spread(b > (uint64_t)top ? (uint64_t)top : b) << a;
        }
        code[i] = c;
        idx[i] = (uint32_t)i;
    }
    for (int pass = 0; pass < 4; pass++) { /* 48 bits, 12 per pass */
        int shift = 12 * pass;
        memset(count, 0, 4097 * sizeof *count);
        for (size_t i = 0; i < n; i++)
            count[((code[i] >> shift) & 0xfffu) + 1]++;
        for (int b = 0; b < 4096; b++)
            count[b + 1] += count[b];
        for (size_t i = 0; i < n; i++) {
            size_t to = count[(code[i] >> shift) & 0xfffu]++;
            code2[to] = code[i];
            idx2[to] = idx[i];
        }
        uint64_t *tc = code;
        code = code2;
        code2 = tc;
        uint32_t *ti = idx;
        idx = idx2;
        idx2 = ti;
    }
    for (size_t i = 0; i < n; i++)
        sorted[i] = (*items)[idx[i]];
    free(*items);
    *items = sorted;
    free(code2);
    free(idx);
    free(idx2);
    free(count);
    *codes = code;
    return 0;
}

/* Splits [b, e) where the highest bit in which its codes differ turns
 * from 0 to 1 (an octree cell into two halves), or halves it when all
 * codes are equal. */
static void build_quick(builder *B, const uint64_t *code, size_t node, size_t b, size_t e)
{
    closest_node *N = &B->nodes[node];
    box_empty(N->lo, N->hi);
    if (e - b <= LEAF_MAX) {
        for (size_t i = b; i < e; i++)
            box_grow(N->lo, N->hi, B->items[i].lo, B->items[i].hi);
        N->first = (int32_t)b;
        N->count = (int32_t)(e - b);
        return;
    }
    size_t mid = b + (e - b) / 2;
    uint64_t diff = code[b] ^ code[e - 1];
    if (diff) {
        int bit = 63;
        while (!(diff >> bit & 1u))
            bit--;
        /* first index in [b, e) with that bit set (codes are sorted) */
        size_t lo = b, hi = e - 1;
        while (lo < hi) {
            size_t m = lo + (hi - lo) / 2;
            if (code[m] >> bit & 1u)
                hi = m;
            else
                lo = m + 1;
        }
        mid = lo;
    }
    size_t left = B->nnode;
    B->nnode += 2;
    build_quick(B, code, left, b, mid);
    build_quick(B, code, left + 1, mid, e);
    N->first = (int32_t)left;
    N->count = 0;
    box_grow(N->lo, N->hi, B->nodes[left].lo, B->nodes[left].hi);
    box_grow(N->lo, N->hi, B->nodes[left + 1].lo, B->nodes[left + 1].hi);
}

/* Checks the mesh and picks the centre: the rounded middle of the box of
 * the referenced vertices. An integer keeps UTM coordinates exact when
 * subtracted (both are multiples of the coordinates' ulp). */
static fm_status check_mesh(const fm_mesh *m, double centre[3], fm_error *err)
{
    size_t nv = fm_mesh_nvertices(m), nt = fm_mesh_ntriangles(m);
    const double *v = fm_mesh_vertices(m);
    const int32_t *t = fm_mesh_triangles(m);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < nt; i++) {
        for (int k = 0; k < 3; k++) {
            int32_t vi = t[3 * i + k];
            if (vi < 0 || (size_t)vi >= nv)
                return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                    "closest tree: triangle %zu names vertex %d of %zu", i,
                                    (int)vi, nv);
            const double *x = v + 3 * (size_t)vi;
            for (int a = 0; a < 3; a++) {
                if (!isfinite(x[a]))
                    return fm_error_set(err, FM_ERR_NUMERIC, NULL, 0,
                                        "closest tree: vertex %d has a non-finite coordinate",
                                        (int)vi);
                lo[a] = x[a] < lo[a] ? x[a] : lo[a];
                hi[a] = x[a] > hi[a] ? x[a] : hi[a];
            }
        }
    }
    for (int a = 0; a < 3; a++)
        centre[a] = nt ? rint(0.5 * lo[a] + 0.5 * hi[a]) : 0.0;
    return FM_OK;
}

/* Items of the triangles part[0 .. n-1] (NULL: all, in order). */
static void make_items(const fm_mesh *m, const double centre[3], const int32_t *part, size_t nt,
                       item *items)
{
    const double *v = fm_mesh_vertices(m);
    const int32_t *t = fm_mesh_triangles(m);
    for (size_t j = 0; j < nt; j++) {
        size_t i = part ? (size_t)part[j] : j;
        item *it = &items[j];
        it->tri = (int32_t)i;
        for (int a = 0; a < 3; a++) {
            double r[3];
            for (int k = 0; k < 3; k++)
                r[k] = v[3 * (size_t)t[3 * i + k] + a] - centre[a];
            double lo = fmin(r[0], fmin(r[1], r[2])), hi = fmax(r[0], fmax(r[1], r[2]));
            it->lo[a] = float_down(lo);
            it->hi[a] = float_up(hi);
            it->c[a] = (float)((r[0] + r[1] + r[2]) / 3.0);
        }
    }
}

/* Leaf order and vertex numbering by first use keep the triangles of a
 * leaf, and their vertices, close together in memory. */
static fm_status pack(fm_closest_tree *t, const fm_mesh *m, const item *items)
{
    size_t nv = fm_mesh_nvertices(m), nt = t->ntri;
    const double *v = fm_mesh_vertices(m);
    const int32_t *tri = fm_mesh_triangles(m);
    int32_t *renum = malloc((nv ? nv : 1) * sizeof *renum);
    t->tri = malloc(3 * nt * sizeof *t->tri);
    t->orig = malloc(nt * sizeof *t->orig);
    t->xyz = malloc(3 * (nv < 3 * nt ? nv : 3 * nt) * sizeof *t->xyz);
    if (!renum || !t->tri || !t->orig || !t->xyz) {
        free(renum);
        return FM_ERR_NOMEM;
    }
    for (size_t i = 0; i < nv; i++)
        renum[i] = -1;
    int32_t used = 0;
    for (size_t s = 0; s < nt; s++) {
        int32_t orig = items[s].tri;
        t->orig[s] = orig;
        for (int k = 0; k < 3; k++) {
            int32_t vi = tri[3 * (size_t)orig + k];
            if (renum[vi] < 0) {
                for (int a = 0; a < 3; a++)
                    t->xyz[3 * (size_t)used + a] = v[3 * (size_t)vi + a] - t->centre[a];
                renum[vi] = used++;
            }
            t->tri[3 * s + k] = renum[vi];
        }
    }
    free(renum);
    double *shrunk = realloc(t->xyz, 3 * (size_t)(used ? used : 1) * sizeof *t->xyz);
    if (shrunk)
        t->xyz = shrunk;
    return FM_OK;
}

/* Queries always read both children of a node: with 32-byte nodes, pairs
 * at even slots and a 64-byte aligned array, that is one cache line. */
static closest_node *aligned_nodes(const closest_node *nodes, size_t n)
{
    size_t bytes = (n * sizeof *nodes + 63) / 64 * 64;
    closest_node *out = aligned_alloc(64, bytes);
    if (out)
        memcpy(out, nodes, n * sizeof *nodes);
    return out;
}

/* The tree of all of m's triangles (part NULL) or of part[0 .. npart-1]. */
static fm_closest_tree *create(const fm_mesh *m, const int32_t *part, size_t npart, int quick,
                               fm_error *err)
{
    if (!m) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "closest tree: no mesh");
        return NULL;
    }
    fm_closest_tree *t = calloc(1, sizeof *t);
    if (!t) {
        fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "closest tree: out of memory");
        return NULL;
    }
    if (check_mesh(m, t->centre, err) != FM_OK) {
        free(t);
        return NULL;
    }
    t->ntri = part ? npart : fm_mesh_ntriangles(m);
    for (size_t k = 0; part && k < npart; k++)
        if (part[k] < 0 || (size_t)part[k] >= fm_mesh_ntriangles(m)) {
            fm_error_set(err, FM_ERR_INVALID, NULL, 0, "closest tree: no triangle %d in %zu",
                         (int)part[k], fm_mesh_ntriangles(m));
            free(t);
            return NULL;
        }
    if (t->ntri == 0)
        return t;
    builder B = {0};
    B.items = malloc(t->ntri * sizeof *B.items);
    /* A binary tree whose leaves are non-empty has fewer than 2n nodes;
     * one more pads the root so that sibling pairs start at even slots. */
    B.nodes = malloc((2 * t->ntri + 1) * sizeof *B.nodes);
    fm_status st = FM_ERR_NOMEM;
    if (B.items && B.nodes) {
        make_items(m, t->centre, part, t->ntri, B.items);
        B.nnode = 2;
        int ok = 1;
        uint64_t *code = NULL;
        if (!quick)
            build_node(&B, 0, 0, t->ntri, 0);
        else if ((ok = morton_order(&B.items, t->ntri, &code) == 0))
            build_quick(&B, code, 0, 0, t->ntri);
        free(code);
        if (ok) {
            memset(&B.nodes[1], 0, sizeof B.nodes[1]);
            t->nodes = aligned_nodes(B.nodes, B.nnode);
            t->nnode = B.nnode;
            if (t->nodes)
                st = pack(t, m, B.items);
        }
    }
    free(B.items);
    free(B.nodes);
    if (st != FM_OK) {
        size_t nt = t->ntri;
        fm_closest_tree_destroy(t);
        fm_error_set(err, st, NULL, 0, "closest tree: out of memory for %zu triangles", nt);
        return NULL;
    }
    return t;
}

fm_closest_tree *fm_closest_tree_create(const fm_mesh *m, fm_error *err)
{
    return create(m, NULL, 0, 0, err);
}

fm_closest_tree *fm_closest_tree_create_quick(const fm_mesh *m, fm_error *err)
{
    return create(m, NULL, 0, 1, err);
}

fm_closest_tree *fm_closest_tree_create_part(const fm_mesh *m, const int32_t *part, size_t n,
                                             fm_error *err)
{
    static const int32_t none[1] = {0};
    if (!part && n) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "closest tree: no triangle list");
        return NULL;
    }
    return create(m, part ? part : none, n, 1, err);
}

void fm_closest_tree_destroy(fm_closest_tree *t)
{
    if (!t)
        return;
    free(t->nodes);
    free(t->tri);
    free(t->orig);
    free(t->xyz);
    free(t);
}

size_t fm_closest_tree_ntriangles(const fm_closest_tree *t)
{
    return t ? t->ntri : 0;
}
