/* Step 1: welding coincident vertices.
 *
 * Both welds process vertices in index order and keep the lowest index of
 * each group as representative, so the result does not depend on where a
 * vertex lands in a hash table. */
#include "repair_internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

size_t rep_table_size(size_t n)
{
    size_t size = 16;
    while (size < 2 * n) {
        if (size > SIZE_MAX / 4)
            return 0;
        size *= 2;
    }
    return size;
}

/* Bit pattern of a coordinate with -0.0 folded onto 0.0, so that equality
 * of keys is equality of values for every finite double. */
static uint64_t coord_key(double x)
{
    uint64_t k;
    if (x == 0.0)
        x = 0.0;
    memcpy(&k, &x, sizeof k);
    return k;
}

static uint64_t point_hash(const double *p)
{
    uint64_t h = rep_mix64(coord_key(p[0]));
    h = rep_mix64(h ^ coord_key(p[1]));
    return rep_mix64(h ^ coord_key(p[2]));
}

static int same_point(const double *a, const double *b)
{
    return coord_key(a[0]) == coord_key(b[0]) && coord_key(a[1]) == coord_key(b[1]) &&
           coord_key(a[2]) == coord_key(b[2]);
}

fm_status rep_weld_exact(const double *xyz, size_t nv, int32_t *rep, size_t *nwelded)
{
    *nwelded = 0;
    size_t size = rep_table_size(nv);
    int32_t *table = size ? malloc(size * sizeof *table) : NULL;
    if (!table)
        return FM_ERR_NOMEM;
    memset(table, 0xff, size * sizeof *table); /* all -1: empty */
    size_t mask = size - 1;
    for (size_t v = 0; v < nv; v++) {
        const double *p = xyz + 3 * v;
        size_t slot = (size_t)point_hash(p) & mask;
        rep[v] = (int32_t)v;
        for (;;) {
            int32_t w = table[slot];
            if (w < 0) {
                table[slot] = (int32_t)v;
                break;
            }
            if (same_point(p, xyz + 3 * (size_t)w)) {
                rep[v] = w;
                (*nwelded)++;
                break;
            }
            slot = (slot + 1) & mask;
        }
    }
    free(table);
    return FM_OK;
}

/* Tolerance weld: vertices within tol of each other end up in one group,
 * transitively (union-find). Cells have size 2 tol, so a point can only
 * reach, along each axis, the neighbour cell on the side of the nearer
 * face (both only when it sits mid-cell); with the edge and corner cells
 * pruned by distance, about 7 cells are probed per vertex instead of 27.
 * The cost is linear as long as a cell holds a bounded number of vertices,
 * i.e. tol is below the vertex spacing, which is the only sensible use (a
 * larger tol collapses triangles). */
typedef struct cell_map {
    size_t mask;
    int32_t *slot_cell; /* hash slot -> cell id, -1 empty */
    int64_t *key;       /* 3 per cell */
    int32_t *start;     /* ncells+1: members[start[c] .. start[c+1]) */
    int32_t *members;
    size_t ncells;
} cell_map;

static uint64_t cell_hash(const int64_t *k)
{
    uint64_t h = rep_mix64((uint64_t)k[0]);
    h = rep_mix64(h ^ (uint64_t)k[1]);
    return rep_mix64(h ^ (uint64_t)k[2]);
}

/* Cell id of key k, or -1; with insert, a new cell is created if absent. */
static int32_t cell_lookup(cell_map *m, const int64_t *k, int insert)
{
    size_t slot = (size_t)cell_hash(k) & m->mask;
    for (;;) {
        int32_t c = m->slot_cell[slot];
        if (c < 0) {
            if (!insert)
                return -1;
            c = (int32_t)m->ncells++;
            memcpy(m->key + 3 * (size_t)c, k, 3 * sizeof *k);
            m->slot_cell[slot] = c;
            return c;
        }
        const int64_t *ck = m->key + 3 * (size_t)c;
        if (ck[0] == k[0] && ck[1] == k[1] && ck[2] == k[2])
            return c;
        slot = (slot + 1) & m->mask;
    }
}

static void cell_of(const double *p, double size, int64_t *k)
{
    for (int d = 0; d < 3; d++)
        k[d] = (int64_t)floor(p[d] / size);
}

/* Neighbour cells of p (cell k, cell size 2 tol) that may hold a point
 * within tol: offsets per axis with the distance to the face crossed. The
 * reach carries a slack, relative and absolute, so that rounding in the
 * face positions (floor(x / size) is monotone in x, so only the distances
 * are off, by a few ulps of |x|) never loses a pair; an extra cell only
 * costs a probe. */
static int reachable_cells(const double *p, const int64_t *k, double tol, int64_t (*out)[3])
{
    double size = 2 * tol;
    double reach = 1.01 * tol + 8 * DBL_EPSILON * (fabs(p[0]) + fabs(p[1]) + fabs(p[2]) + size);
    int off[3][3], noff[3];
    double dist[3][3];
    for (int d = 0; d < 3; d++) {
        double lo = p[d] - (double)k[d] * size, hi = size - lo;
        noff[d] = 0;
        off[d][noff[d]] = 0;
        dist[d][noff[d]++] = 0;
        if (lo <= reach) {
            off[d][noff[d]] = -1;
            dist[d][noff[d]++] = lo > 0 ? lo : 0;
        }
        if (hi <= reach) { /* both sides only for a point mid-cell */
            off[d][noff[d]] = 1;
            dist[d][noff[d]++] = hi > 0 ? hi : 0;
        }
    }
    int n = 0;
    for (int i = 0; i < noff[0]; i++)
        for (int j = 0; j < noff[1]; j++)
            for (int l = 0; l < noff[2]; l++) {
                double d2 = dist[0][i] * dist[0][i] + dist[1][j] * dist[1][j] +
                            dist[2][l] * dist[2][l];
                if (d2 > reach * reach)
                    continue;
                out[n][0] = k[0] + off[0][i];
                out[n][1] = k[1] + off[1][j];
                out[n][2] = k[2] + off[2][l];
                n++;
            }
    return n;
}

fm_status rep_weld_tolerance(const double *xyz, size_t nv, double tol, int32_t *rep,
                             size_t *nwelded, fm_error *err)
{
    *nwelded = 0;
    /* Cell indices floor(x / 2 tol) must fit an int64 with room for the
     * +-1 neighbours. */
    for (size_t i = 0; i < 3 * nv; i++)
        if (fabs(xyz[i] / tol) > 4.0e18)
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                "repair: weld tolerance %g is too small for coordinate %g", tol,
                                xyz[i]);
    fm_status st = FM_ERR_NOMEM;
    cell_map m = {0};
    int32_t *cell = malloc((nv ? nv : 1) * sizeof *cell);
    int32_t *parent = malloc((nv ? nv : 1) * sizeof *parent);
    size_t size = rep_table_size(nv);
    m.mask = size - 1;
    m.slot_cell = size ? malloc(size * sizeof *m.slot_cell) : NULL;
    m.key = malloc((nv ? nv : 1) * 3 * sizeof *m.key);
    m.start = calloc(nv + 2, sizeof *m.start);
    m.members = malloc((nv ? nv : 1) * sizeof *m.members);
    if (!cell || !parent || !m.slot_cell || !m.key || !m.start || !m.members)
        goto done;
    memset(m.slot_cell, 0xff, size * sizeof *m.slot_cell);

    /* Bucket the exact-weld representatives by cell (counting sort, so the
     * members of a cell are in index order). */
    for (size_t v = 0; v < nv; v++) {
        parent[v] = (int32_t)v;
        cell[v] = -1;
        if (rep[v] != (int32_t)v)
            continue;
        int64_t k[3];
        cell_of(xyz + 3 * v, 2 * tol, k);
        cell[v] = cell_lookup(&m, k, 1);
        m.start[cell[v] + 1]++;
    }
    for (size_t c = 0; c < m.ncells; c++)
        m.start[c + 1] += m.start[c];
    for (size_t v = 0; v < nv; v++)
        if (cell[v] >= 0)
            m.members[m.start[cell[v]]++] = (int32_t)v;
    for (size_t c = m.ncells; c > 0; c--)
        m.start[c] = m.start[c - 1];
    m.start[0] = 0;

    double tol2 = tol * tol;
    for (size_t v = 0; v < nv; v++) {
        if (cell[v] < 0)
            continue;
        const double *p = xyz + 3 * v;
        int64_t near[27][3];
        int nn = reachable_cells(p, m.key + 3 * (size_t)cell[v], tol, near);
        for (int q = 0; q < nn; q++) {
            int32_t c = q == 0 ? cell[v] : cell_lookup(&m, near[q], 0);
            if (c < 0)
                continue;
            for (int32_t i = m.start[c]; i < m.start[c + 1]; i++) {
                int32_t w = m.members[i];
                if (w >= (int32_t)v)
                    break; /* each pair once: members are sorted */
                if (uf_find(parent, w) == uf_find(parent, (int32_t)v))
                    continue;
                const double *o = xyz + 3 * (size_t)w;
                double d0 = p[0] - o[0], d1 = p[1] - o[1], d2 = p[2] - o[2];
                if (d0 * d0 + d1 * d1 + d2 * d2 <= tol2)
                    uf_union(parent, w, (int32_t)v);
            }
        }
    }
    for (size_t v = 0; v < nv; v++) {
        if (cell[v] < 0)
            continue;
        int32_t root = uf_find(parent, (int32_t)v);
        if (root != (int32_t)v)
            (*nwelded)++;
    }
    /* Roots are the smallest representative of each group, hence also the
     * smallest input index. */
    for (size_t v = 0; v < nv; v++)
        rep[v] = uf_find(parent, rep[v]);
    st = FM_OK;
done:
    free(cell);
    free(parent);
    free(m.slot_cell);
    free(m.key);
    free(m.start);
    free(m.members);
    return st;
}
