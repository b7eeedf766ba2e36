/* Rectangular elements: tiles added where a fault's rows leave a junction
 * bare (tile_internal.h). A fault's surface may reach a junction only as
 * a thin strip (a tip running up to the other fault, a branch ending on
 * it between two rows) that its rows' contours miss or leave to slivers,
 * and then the gap at the junction is the distance to its nearest row
 * tile, kilometres at times. There, a square of half the size on the
 * triangle that holds the junction edge, in that triangle's plane, its
 * edge on the junction point, covers it; cutting tiles apart
 * (tile_separate) then keeps it off the other fault's tiles like any
 * other. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tile_internal.h"
#include "fm_vec3.h"

int tile_square(const double *x, const int32_t *tri, size_t k, int32_t f, const double c[3],
                double s, const double level[3], fm_tile *out)
{
    const double *a = x + 3 * (size_t)tri[3 * k], *b = x + 3 * (size_t)tri[3 * k + 1],
                 *cc = x + 3 * (size_t)tri[3 * k + 2];
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double e2[3] = {cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]}, n[3];
    fm_cross3(e1, e2, n);
    double ln = sqrt(fm_dot3(n, n));
    if (!(ln > 0))
        return 0;
    for (int d = 0; d < 3; d++)
        n[d] /= ln;
    /* the strike horizontal in the triangle's plane; on a level triangle,
     * along level */
    double st[3] = {-n[1], n[0], 0};
    double ls = hypot(st[0], st[1]);
    if (ls < 1e-9) {
        st[0] = level[0];
        st[1] = level[1];
        ls = hypot(st[0], st[1]);
        if (!(ls > 0))
            return 0;
    }
    st[0] /= ls;
    st[1] /= ls;
    double dip[3];
    tile_frame(st, n, dip);
    fm_tile tl = {.fault = f, .triangle = (int32_t)k, .row = 1, .length = s, .width = s};
    memcpy(tl.centre, c, sizeof tl.centre);
    memcpy(tl.strike, st, sizeof st);
    memcpy(tl.dip, dip, sizeof dip);
    *out = tl;
    return 1;
}

/* The filling tile of fault f at junction point p on the edge u-v of its
 * triangle k; 0 when that triangle has no plane. */
static int make_fill(const double *x, const int32_t *tri, size_t k, int32_t f, const double p[3],
                     int32_t u, int32_t v, double s, fm_tile *out)
{
    const double *a = x + 3 * (size_t)tri[3 * k], *b = x + 3 * (size_t)tri[3 * k + 1],
                 *c = x + 3 * (size_t)tri[3 * k + 2];
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]}, n[3];
    fm_cross3(e1, e2, n);
    const double *pu = x + 3 * (size_t)u, *pv = x + 3 * (size_t)v;
    double e[3] = {pv[0] - pu[0], pv[1] - pu[1], pv[2] - pu[2]}, in[3];
    fm_cross3(n, e, in);
    double li = sqrt(fm_dot3(in, in));
    if (!(li > 0))
        return 0;
    /* into the triangle: towards its centroid */
    double g[3] = {(a[0] + b[0] + c[0]) / 3 - p[0], (a[1] + b[1] + c[1]) / 3 - p[1],
                   (a[2] + b[2] + c[2]) / 3 - p[2]};
    double sg = fm_dot3(in, g) < 0 ? -1 : 1, centre[3];
    for (int d = 0; d < 3; d++)
        centre[d] = p[d] + sg * in[d] / li * s / 2;
    return tile_square(x, tri, k, f, centre, s, e, out);
}

int tile_fill_junctions(fm_tiles *t, const fm_mesh *set, const tile_sides *sd)
{
    if (!t->n)
        return 0;
    const double *x = fm_mesh_vertices(set);
    const int32_t *tri = fm_mesh_triangles(set), *tag = fm_mesh_tags(set);
    double size = t->stats.size, rmax = 0;
    for (size_t i = 0; i < t->n; i++)
        rmax = fmax(rmax, 0.5 * hypot(t->tile[i].length, t->tile[i].width));
    tile_grid g = {0};
    if (tile_grid_make(&g, t, rmax)) {
        free(g.e);
        return -1;
    }
    size_t n0 = t->n; /* the grid holds the tiles before the fillers */
    int bad = 0;
    for (size_t i = 0; i < sd->n && !bad;) {
        size_t j = i + 1;
        while (j < sd->n && sd->side[j].key == sd->side[i].key)
            j++;
        if (!sd->junction[i]) {
            i = j;
            continue;
        }
        int32_t u = (int32_t)(sd->side[i].key >> 32), v = (int32_t)(sd->side[i].key & 0xffffffffu);
        const double *a = x + 3 * (size_t)u, *b = x + 3 * (size_t)v;
        for (size_t q = i; q < j && !bad; q++) {
            size_t k = sd->side[q].index;
            int32_t f = tag[k];
            /* one triangle of each fault fills: the first of its run */
            int first = 1;
            for (size_t r = i; r < q; r++)
                first &= tag[sd->side[r].index] != f;
            if (!first)
                continue;
            /* the points the gap is measured at (tile_measure) */
            for (int h = 1; h <= 3 && !bad; h++) {
                double p[3];
                for (int d = 0; d < 3; d++)
                    p[d] = a[d] + (b[d] - a[d]) * h / 4.0;
                double best = tile_nearest_of_fault(&g, t, p, rmax + size, f, INFINITY);
                for (size_t m = n0; m < t->n; m++)
                    if (t->tile[m].fault == f)
                        best = fmin(best, tile_distance(&t->tile[m], p, NULL, NULL));
                if (best <= 0.4 * size)
                    continue;
                fm_tile tl;
                if (make_fill(x, tri, k, f, p, u, v, size / 2, &tl))
                    bad = tile_push(t, &tl, 0, 0, 0, 0) != 0;
            }
        }
        i = j;
    }
    free(g.e);
    return bad ? -1 : 0;
}
