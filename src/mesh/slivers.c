/* Boundary slivers of no width (remesh_internal.h, mesh_collapse_slivers).
 *
 * Where a shared curve ends on the outline at a grazing angle, the
 * outline can run along the curve's last segment for a while: a boundary
 * node then lies on that segment, and the triangle between them has no
 * width (0.02 degrees on Rose Valley, where it meets the Independence
 * fault, at 1 km). No flip or move shapes it: its three nodes are all on
 * the boundary, two of them shared. The outline node goes instead: it is
 * merged into its boundary neighbour, which is where the outline and the
 * curve part anyway, and the sliver disappears with no shared node moved
 * or lost. Only when every triangle that changes keeps its orientation in
 * (u, v) and some area. */
#include <math.h>
#include <stdlib.h>

#include "fm_mesh.h"
#include "fm_predicates.h"
#include "fm_sort.h"
#include "remesh_internal.h"

/* Triangles of each edge: sorted keys. */
static fm_keyed *edges_of(const int32_t *tri, size_t nt, size_t *ne)
{
    fm_keyed *e = malloc((3 * nt + 1) * sizeof *e);
    if (!e)
        return NULL;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++)
            e[3 * t + k] = (fm_keyed){fm_edge_key((uint64_t)tri[3 * t + k],
                                                  (uint64_t)tri[3 * t + (k + 1) % 3]),
                                      t};
    if (fm_sort_keyed(e, 3 * nt)) {
        free(e);
        return NULL;
    }
    *ne = 3 * nt;
    return e;
}

static size_t uses(const fm_keyed *e, size_t n, int32_t a, int32_t b)
{
    uint64_t key = fm_edge_key((uint64_t)a, (uint64_t)b);
    size_t i = fm_keyed_lower_bound(e, n, key), c = 0;
    while (i + c < n && e[i + c].key == key)
        c++;
    return c;
}

/* Whether merging m into p keeps every other triangle of m oriented. */
static int merge_keeps_shape(const double *uv, const int32_t *tri, size_t nt, int32_t m,
                             int32_t p)
{
    for (size_t t = 0; t < nt; t++) {
        const int32_t *v = tri + 3 * t;
        int hm = v[0] == m || v[1] == m || v[2] == m;
        int hp = v[0] == p || v[1] == p || v[2] == p;
        if (!hm || hp)
            continue;
        const double *c[3], *d[3];
        for (int k = 0; k < 3; k++) {
            c[k] = uv + 2 * (size_t)v[k];
            d[k] = uv + 2 * (size_t)(v[k] == m ? p : v[k]);
        }
        int before = fm_orient2d(c[0], c[1], c[2]), after = fm_orient2d(d[0], d[1], d[2]);
        if (after == 0 || after != before)
            return 0;
    }
    return 1;
}

size_t mesh_collapse_slivers(const double *uv, const double *xyz, int32_t *tri, size_t *nt,
                             const int64_t *shared, size_t nshared, double min_angle_deg)
{
    size_t merged = 0;
    for (int changed = 1; changed;) {
        changed = 0;
        size_t ne = 0;
        fm_keyed *e = edges_of(tri, *nt, &ne);
        if (!e)
            return merged;
        for (size_t t = 0; t < *nt && !changed; t++) {
            const int32_t *v = tri + 3 * t;
            double ang[3];
            for (int k = 0; k < 3; k++)
                ang[k] = fm_angle_at(xyz + 3 * (size_t)v[k], xyz + 3 * (size_t)v[(k + 1) % 3],
                                     xyz + 3 * (size_t)v[(k + 2) % 3]);
            int far = ang[0] > ang[1] ? (ang[0] > ang[2] ? 0 : 2) : (ang[1] > ang[2] ? 1 : 2);
            if (fmin(ang[(far + 1) % 3], ang[(far + 2) % 3]) >= min_angle_deg)
                continue;
            /* m, the node across the long side, lies on it */
            int32_t m = v[far];
            if ((size_t)m < nshared && shared && shared[m] >= 0)
                continue;
            for (int s = 1; s <= 2 && !changed; s++) {
                int32_t p = v[(far + s) % 3];
                if (uses(e, ne, m, p) != 1 || !merge_keeps_shape(uv, tri, *nt, m, p))
                    continue;
                /* m into p: its triangles with p go, the others take p */
                size_t w = 0;
                for (size_t u = 0; u < *nt; u++) {
                    int32_t *x = tri + 3 * u;
                    int hm = x[0] == m || x[1] == m || x[2] == m;
                    int hp = x[0] == p || x[1] == p || x[2] == p;
                    if (hm && hp)
                        continue;
                    for (int k = 0; k < 3; k++)
                        tri[3 * w + k] = x[k] == m ? p : x[k];
                    w++;
                }
                *nt = w;
                merged++;
                changed = 1;
            }
        }
        free(e);
    }
    return merged;
}
