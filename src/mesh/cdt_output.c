/* The result arrays in caller indices: domain triangles in slot order,
 * the segment of every point, and the constrained edges sorted so that
 * the order does not depend on slot reuse. */
#include <stdlib.h>

#include "cdt_internal.h"

static int by_edge(const void *x, const void *y)
{
    const int32_t *p = x, *q = y;
    for (int k = 0; k < 3; k++)
        if (p[k] != q[k])
            return p[k] < q[k] ? -1 : 1;
    return 0;
}

int cdt_build_output(struct fm_cdt *t)
{
    size_t nt = 0, ne = 0;
    for (size_t k = 0; k < t->nt; k++)
        if (t->region[k] == 1) {
            nt++;
            for (int i = 0; i < 3; i++)
                ne += t->tc[3 * k + i] >= 0;
        }
    size_t np = t->np - CDT_NSUPER;
    int32_t *tri = malloc((nt ? 3 * nt : 1) * sizeof *tri);
    int32_t *ps = malloc((np ? np : 1) * sizeof *ps);
    int32_t *ed = malloc((ne ? 3 * ne : 1) * sizeof *ed);
    int32_t *edges = malloc((ne ? 2 * ne : 1) * sizeof *edges);
    int32_t *eid = malloc((ne ? ne : 1) * sizeof *eid);
    if (!tri || !ps || !ed || !edges || !eid) {
        free(tri);
        free(ps);
        free(ed);
        free(edges);
        free(eid);
        return -1;
    }
    size_t j = 0, m = 0;
    for (size_t k = 0; k < t->nt; k++) {
        if (t->region[k] != 1)
            continue;
        for (int i = 0; i < 3; i++)
            tri[3 * j + i] = t->tv[3 * k + i] - CDT_NSUPER;
        j++;
        for (int i = 0; i < 3; i++) {
            int32_t e = (int32_t)(3 * k) + i;
            if (t->tc[e] < 0)
                continue;
            /* An edge with the domain on both sides would be listed twice;
             * segments are domain boundaries, so this only guards. */
            int32_t f = t->tn[e];
            if (f >= 0 && t->region[f / 3] == 1 && f < e)
                continue;
            ed[3 * m] = t->tc[e];
            ed[3 * m + 1] = cdt_org(t, e) - CDT_NSUPER;
            ed[3 * m + 2] = cdt_dst(t, e) - CDT_NSUPER;
            m++;
        }
    }
    qsort(ed, m, 3 * sizeof *ed, by_edge);
    for (size_t k = 0; k < m; k++) {
        edges[2 * k] = ed[3 * k + 1];
        edges[2 * k + 1] = ed[3 * k + 2];
        eid[k] = t->sid[ed[3 * k]];
    }
    free(ed);
    for (size_t i = 0; i < np; i++) {
        int32_t s = t->pseg[i + CDT_NSUPER];
        ps[i] = s >= 0 ? t->sid[s] : -1;
    }
    free(t->out_tri);
    free(t->out_pseg);
    free(t->out_edges);
    free(t->out_eid);
    t->out_tri = tri;
    t->out_pseg = ps;
    t->out_edges = edges;
    t->out_eid = eid;
    t->out_nt = nt;
    t->out_ne = m;
    return 0;
}
