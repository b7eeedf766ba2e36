/* Midpoint subdivision of a sheet's triangulation in the parameter plane:
 * the fitted surface evaluated at these points samples it finely while the
 * original connectivity keeps the sampling inside the fault's outline. */
#include <stdlib.h>
#include <string.h>

#include "fm_sort.h"
#include "model_internal.h"

static fm_status refine_once(fm_submesh *m)
{
    size_t ne = 3 * m->nt;
    fm_keyed *e = malloc((ne ? ne : 1) * sizeof *e);
    int32_t *mid = malloc((ne ? ne : 1) * sizeof *mid);
    if (!e || !mid) {
        free(e);
        free(mid);
        return FM_ERR_NOMEM;
    }
    for (size_t t = 0; t < m->nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = (uint32_t)m->tri[3 * t + k], b = (uint32_t)m->tri[3 * t + (k + 1) % 3];
            e[3 * t + k].key = a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a);
            e[3 * t + k].index = 3 * t + (size_t)k;
        }
    /* By edge, then (as made) by triangle and side. */
    if (fm_sort_keyed(e, ne) != 0) {
        free(e);
        free(mid);
        return FM_ERR_NOMEM;
    }
    size_t nedges = 0;
    for (size_t i = 0; i < ne; i++)
        if (i == 0 || e[i].key != e[i - 1].key)
            nedges++;
    size_t nv = m->nv + nedges;
    double *uv = realloc(m->uv, nv * 2 * sizeof *uv);
    if (uv)
        m->uv = uv;
    int32_t *loop = realloc(m->loop, nv * sizeof *loop);
    if (loop)
        m->loop = loop;
    int32_t *tri = malloc(4 * m->nt * 3 * sizeof *tri + 1);
    if (!uv || !loop || !tri) {
        free(tri);
        free(e);
        free(mid);
        return FM_ERR_NOMEM;
    }
    size_t v = m->nv;
    for (size_t i = 0; i < ne;) {
        size_t j = i + 1;
        while (j < ne && e[j].key == e[i].key)
            j++;
        uint32_t a = (uint32_t)(e[i].key >> 32), b = (uint32_t)(e[i].key & 0xffffffffu);
        m->uv[2 * v] = 0.5 * (m->uv[2 * a] + m->uv[2 * b]);
        m->uv[2 * v + 1] = 0.5 * (m->uv[2 * a + 1] + m->uv[2 * b + 1]);
        /* A midpoint is on the boundary only if its edge is (one triangle). */
        m->loop[v] = (j - i == 1 && m->loop[a] >= 0 && m->loop[a] == m->loop[b]) ? m->loop[a] : -1;
        for (size_t k = i; k < j; k++)
            mid[e[k].index] = (int32_t)v;
        v++;
        i = j;
    }
    for (size_t t = 0; t < m->nt; t++) {
        int32_t a = m->tri[3 * t], b = m->tri[3 * t + 1], c = m->tri[3 * t + 2];
        int32_t ab = mid[3 * t], bc = mid[3 * t + 1], ca = mid[3 * t + 2];
        int32_t q[12] = {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca};
        memcpy(tri + 12 * t, q, sizeof q);
    }
    free(m->tri);
    m->tri = tri;
    m->nt *= 4;
    m->nv = nv;
    free(e);
    free(mid);
    return FM_OK;
}

fm_status fm_submesh_refine(fm_submesh *m, int levels)
{
    for (int l = 0; l < levels; l++) {
        fm_status s = refine_once(m);
        if (s != FM_OK)
            return s;
    }
    return FM_OK;
}

void fm_submesh_free(fm_submesh *m)
{
    free(m->uv);
    free(m->loop);
    free(m->tri);
    memset(m, 0, sizeof *m);
}
