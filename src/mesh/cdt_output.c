/* The result arrays in caller indices: domain triangles in slot order,
 * the segment of every point, and the constrained edges sorted so that
 * the order does not depend on slot reuse: boundary edges with the domain
 * on their left, interior ones (graph CDTs) once each, along their
 * input segment. */
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

/* One constrained edge: sort key (input segment, points), segment,
 * interior flag. */
enum { ED_KEY = 0, ED_SEG = 3, ED_INT = 4, ED_N = 5 };

static void put_edge(const struct fm_cdt *t, int32_t *ed, size_t *m, int32_t k, int32_t a,
                     int32_t b, int interior)
{
    int32_t *r = ed + ED_N * (*m)++;
    r[ED_KEY] = t->sorig ? t->sorig[k] : k;
    r[ED_KEY + 1] = a - CDT_NSUPER;
    r[ED_KEY + 2] = b - CDT_NSUPER;
    r[ED_SEG] = k;
    r[ED_INT] = interior;
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
    int32_t *ed = malloc((ne ? ED_N * ne : 1) * sizeof *ed);
    int32_t *edges = malloc((ne ? 2 * ne : 1) * sizeof *edges);
    int32_t *eid = malloc((ne ? ne : 1) * sizeof *eid);
    unsigned char *eint = malloc(ne ? ne : 1);
    unsigned char *inner = calloc(t->nseg ? t->nseg : 1, 1);
    if (!tri || !ps || !ed || !edges || !eid || !eint || !inner) {
        free(tri);
        free(ps);
        free(ed);
        free(edges);
        free(eid);
        free(eint);
        free(inner);
        return -1;
    }
    size_t j = 0, m = 0;
    int any_inner = 0;
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
            /* The domain on both sides: an interior segment (only graph
             * CDTs have them), listed below along its input segment. */
            int32_t f = t->tn[e];
            if (f >= 0 && t->region[f / 3] == 1) {
                inner[t->tc[e]] = 1;
                any_inner = 1;
                continue;
            }
            put_edge(t, ed, &m, t->tc[e], cdt_org(t, e), cdt_dst(t, e), 0);
        }
    }
    /* A segment's sides are faces, kept or not as a whole, so a segment
     * with one interior edge is interior from end to end: walk it. */
    for (size_t k = 0; k < t->nseg && any_inner; k++) {
        if (!inner[k])
            continue;
        int32_t v = t->seg[2 * k], b = t->seg[2 * k + 1], prev = -1;
        for (size_t steps = 0; v != b && m < ne && steps < np; steps++) {
            int32_t w = cdt_next_on_segment(t, v, prev, (int32_t)k);
            if (w < 0)
                break;
            put_edge(t, ed, &m, (int32_t)k, v, w, 1);
            prev = v;
            v = w;
        }
    }
    free(inner);
    qsort(ed, m, ED_N * sizeof *ed, by_edge);
    for (size_t k = 0; k < m; k++) {
        edges[2 * k] = ed[ED_N * k + ED_KEY + 1];
        edges[2 * k + 1] = ed[ED_N * k + ED_KEY + 2];
        eid[k] = t->sid[ed[ED_N * k + ED_SEG]];
        eint[k] = (unsigned char)ed[ED_N * k + ED_INT];
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
    free(t->out_eint);
    t->out_tri = tri;
    t->out_pseg = ps;
    t->out_edges = edges;
    t->out_eid = eid;
    t->out_eint = eint;
    t->out_nt = nt;
    t->out_ne = m;
    return 0;
}
