/* Step 1: welding coincident vertices.
 *
 * Both welds process vertices in index order and keep the lowest index of
 * each group as representative, so the result does not depend on where a
 * vertex lands in a hash table. */
#include "repair_internal.h"

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
 * transitively (union-find). With cells of size tol every such pair lies in
 * the same or a neighbouring cell, so each representative is compared with
 * the 27 cells around it only; the cost is linear as long as a cell holds a
 * bounded number of vertices, i.e. tol is below the vertex spacing, which
 * is the only sensible use (a larger tol collapses triangles). */
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

static void cell_of(const double *p, double tol, int64_t *k)
{
    for (int d = 0; d < 3; d++)
        k[d] = (int64_t)floor(p[d] / tol);
}

fm_status rep_weld_tolerance(const double *xyz, size_t nv, double tol, int32_t *rep,
                             size_t *nwelded, fm_error *err)
{
    *nwelded = 0;
    /* floor(x / tol) must fit an int64 with room for the +-1 neighbours. */
    for (size_t i = 0; i < 3 * nv; i++)
        if (fabs(xyz[i] / tol) > 4.0e18)
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                "weld tolerance %g is too small for coordinate %g", tol,
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
        cell_of(xyz + 3 * v, tol, k);
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
        const int64_t *k = m.key + 3 * (size_t)cell[v];
        for (int dx = -1; dx <= 1; dx++)
            for (int dy = -1; dy <= 1; dy++)
                for (int dz = -1; dz <= 1; dz++) {
                    int64_t nk[3] = {k[0] + dx, k[1] + dy, k[2] + dz};
                    int32_t c = cell_lookup(&m, nk, 0);
                    if (c < 0)
                        continue;
                    for (int32_t i = m.start[c]; i < m.start[c + 1]; i++) {
                        int32_t w = m.members[i];
                        if (w >= (int32_t)v)
                            break; /* each pair once: members are sorted */
                        if (uf_find(parent, w) == uf_find(parent, (int32_t)v))
                            continue;
                        const double *q = xyz + 3 * (size_t)w;
                        double d0 = p[0] - q[0], d1 = p[1] - q[1], d2 = p[2] - q[2];
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
