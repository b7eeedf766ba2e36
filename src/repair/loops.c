/* Step 6: boundary loops of one sheet.
 *
 * Boundary half-edges are directed as their triangle runs, so the sheet
 * lies on the left of each loop seen from the normal side. After the fan
 * split of sheets.c a boundary vertex has one outgoing boundary edge; where
 * it has several anyway (an edge of more than two sheet triangles, a
 * non-orientable sheet), the first unused one in (vertex, triangle) order
 * is taken, and a walk that cannot close is kept as a loop as it stands. */
#include "repair_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Vector area of a loop, relative to its centroid so that UTM-sized
 * coordinates do not swamp the cross products. */
static void loop_area(const double *xyz, const int32_t *lv, size_t n, double *area)
{
    double c[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++)
            c[d] += xyz[3 * (size_t)lv[i] + d];
    for (int d = 0; d < 3; d++)
        c[d] /= (double)(n ? n : 1);
    area[0] = area[1] = area[2] = 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = xyz + 3 * (size_t)lv[i], *q = xyz + 3 * (size_t)lv[(i + 1) % n];
        double a[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
        double b[3] = {q[0] - c[0], q[1] - c[1], q[2] - c[2]};
        area[0] += 0.5 * (a[1] * b[2] - a[2] * b[1]);
        area[1] += 0.5 * (a[2] * b[0] - a[0] * b[2]);
        area[2] += 0.5 * (a[0] * b[1] - a[1] * b[0]);
    }
}

static void pick_outer(rep_sheet *sh)
{
    const double *xyz = fm_mesh_vertices(sh->mesh);
    const double *n = sh->normal;
    int has_normal = n[0] != 0 || n[1] != 0 || n[2] != 0;
    double best = 0;
    sh->outer = -1;
    for (size_t l = 0; l < sh->nloops; l++) {
        double a[3];
        loop_area(xyz, sh->loop_v + sh->loop_off[l], sh->loop_off[l + 1] - sh->loop_off[l], a);
        double score = has_normal ? a[0] * n[0] + a[1] * n[1] + a[2] * n[2]
                                  : sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        if (sh->outer < 0 || score > best) {
            best = score;
            sh->outer = (long)l;
        }
    }
}

fm_status rep_sheet_loops(rep_sheet *sh, const uint8_t *bnd)
{
    size_t nv = fm_mesh_nvertices(sh->mesh), nt = fm_mesh_ntriangles(sh->mesh);
    const int32_t *tri = fm_mesh_triangles(sh->mesh);
    size_t nb = 0;
    for (size_t h = 0; h < 3 * nt; h++)
        nb += bnd[h] != 0;
    sh->nloops = 0;
    sh->outer = -1;
    sh->loop_off = malloc((nb + 1) * sizeof *sh->loop_off);
    /* An open chain also lists its last vertex: at most 2 entries per edge. */
    sh->loop_v = malloc((2 * nb + 1) * sizeof *sh->loop_v);
    int32_t *start = calloc(nv + 1, sizeof *start); /* outgoing edges by vertex */
    int32_t *out = malloc((nb ? nb : 1) * sizeof *out);
    int32_t *cursor = malloc((nv ? nv : 1) * sizeof *cursor);
    uint8_t *used = calloc(nb ? nb : 1, 1);
    if (!sh->loop_off || !sh->loop_v || !start || !out || !cursor || !used) {
        free(start);
        free(out);
        free(cursor);
        free(used);
        return FM_ERR_NOMEM;
    }
    for (size_t h = 0; h < 3 * nt; h++)
        if (bnd[h])
            start[tri[h] + 1]++;
    for (size_t v = 0; v < nv; v++)
        start[v + 1] += start[v];
    memcpy(cursor, start, nv * sizeof *cursor);
    for (size_t h = 0; h < 3 * nt; h++)
        if (bnd[h])
            out[cursor[tri[h]]++] = (int32_t)h;
    memcpy(cursor, start, nv * sizeof *cursor);

    /* used[] is indexed by position in out[]; cursor[v] skips the used
     * prefix of v's edges so the whole walk stays linear. */
    size_t nl = 0, len = 0;
    sh->loop_off[0] = 0;
    for (size_t v0 = 0; v0 < nv; v0++) {
        while (cursor[v0] < start[v0 + 1]) {
            int32_t pos = cursor[v0];
            int32_t first = tri[out[pos]];
            for (;;) {
                used[pos] = 1;
                int32_t h = out[pos], from = tri[h], to = tri[h - h % 3 + (h % 3 + 1) % 3];
                sh->loop_v[len++] = from;
                while (cursor[from] < start[from + 1] && used[cursor[from]])
                    cursor[from]++;
                if (to == first)
                    break;
                while (cursor[to] < start[to + 1] && used[cursor[to]])
                    cursor[to]++;
                if (cursor[to] == start[to + 1]) {
                    /* Stuck (inconsistent boundary): keep the open chain. */
                    sh->loop_v[len++] = to;
                    break;
                }
                pos = cursor[to];
            }
            sh->loop_off[++nl] = len;
        }
    }
    sh->nloops = nl;
    free(start);
    free(out);
    free(cursor);
    free(used);
    pick_outer(sh);
    return FM_OK;
}
