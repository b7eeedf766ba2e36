#include "fm_mesh.h"

#include <stdlib.h>
#include <string.h>

struct fm_mesh {
    double *xyz;
    int32_t *tri;
    int32_t *tag;
    size_t nv, nt;
    size_t cap_v, cap_t;
};

fm_mesh *fm_mesh_create(void)
{
    return calloc(1, sizeof(fm_mesh));
}

void fm_mesh_destroy(fm_mesh *m)
{
    if (!m)
        return;
    free(m->xyz);
    free(m->tri);
    free(m->tag);
    free(m);
}

static int grow_vertices(fm_mesh *m, size_t nv)
{
    if (nv <= m->cap_v)
        return 0;
    if (nv > (size_t)INT32_MAX)
        return -1;
    double *p = realloc(m->xyz, nv * 3 * sizeof *p);
    if (!p)
        return -1;
    m->xyz = p;
    m->cap_v = nv;
    return 0;
}

static int grow_triangles(fm_mesh *m, size_t nt)
{
    if (nt <= m->cap_t)
        return 0;
    if (nt > (size_t)INT32_MAX)
        return -1;
    int32_t *p = realloc(m->tri, nt * 3 * sizeof *p);
    if (!p)
        return -1;
    m->tri = p;
    int32_t *q = realloc(m->tag, nt * sizeof *q);
    if (!q)
        return -1;
    m->tag = q;
    m->cap_t = nt;
    return 0;
}

fm_status fm_mesh_reserve(fm_mesh *m, size_t nv, size_t nt)
{
    if (grow_vertices(m, nv) || grow_triangles(m, nt))
        return FM_ERR_NOMEM;
    return FM_OK;
}

fm_mesh *fm_mesh_clone(const fm_mesh *m)
{
    fm_mesh *c = fm_mesh_create();
    if (!c)
        return NULL;
    if (fm_mesh_reserve(c, m->nv, m->nt) != FM_OK) {
        fm_mesh_destroy(c);
        return NULL;
    }
    if (m->nv)
        memcpy(c->xyz, m->xyz, m->nv * 3 * sizeof *m->xyz);
    if (m->nt) {
        memcpy(c->tri, m->tri, m->nt * 3 * sizeof *m->tri);
        memcpy(c->tag, m->tag, m->nt * sizeof *m->tag);
    }
    c->nv = m->nv;
    c->nt = m->nt;
    return c;
}

int32_t fm_mesh_add_vertex(fm_mesh *m, double x, double y, double z)
{
    if (m->nv == m->cap_v && grow_vertices(m, m->cap_v ? m->cap_v * 2 : 64))
        return -1;
    double *p = m->xyz + 3 * m->nv;
    p[0] = x;
    p[1] = y;
    p[2] = z;
    return (int32_t)m->nv++;
}

int32_t fm_mesh_add_triangle(fm_mesh *m, int32_t a, int32_t b, int32_t c, int32_t tag)
{
    if (m->nt == m->cap_t && grow_triangles(m, m->cap_t ? m->cap_t * 2 : 64))
        return -1;
    int32_t *t = m->tri + 3 * m->nt;
    t[0] = a;
    t[1] = b;
    t[2] = c;
    m->tag[m->nt] = tag;
    return (int32_t)m->nt++;
}

size_t fm_mesh_nvertices(const fm_mesh *m) { return m->nv; }
size_t fm_mesh_ntriangles(const fm_mesh *m) { return m->nt; }
const double *fm_mesh_vertices(const fm_mesh *m) { return m->xyz; }
double *fm_mesh_vertices_mut(fm_mesh *m) { return m->xyz; }
const int32_t *fm_mesh_triangles(const fm_mesh *m) { return m->tri; }
int32_t *fm_mesh_triangles_mut(fm_mesh *m) { return m->tri; }
const int32_t *fm_mesh_tags(const fm_mesh *m) { return m->tag; }
int32_t *fm_mesh_tags_mut(fm_mesh *m) { return m->tag; }

fm_status fm_mesh_append(fm_mesh *dst, const fm_mesh *src, int32_t tag)
{
    size_t nv = dst->nv, nt = dst->nt;
    if (fm_mesh_reserve(dst, nv + src->nv, nt + src->nt) != FM_OK)
        return FM_ERR_NOMEM;
    if (src->nv)
        memcpy(dst->xyz + 3 * nv, src->xyz, src->nv * 3 * sizeof *src->xyz);
    for (size_t t = 0; t < src->nt; t++) {
        for (int k = 0; k < 3; k++)
            dst->tri[3 * (nt + t) + k] = src->tri[3 * t + k] + (int32_t)nv;
        dst->tag[nt + t] = tag;
    }
    dst->nv += src->nv;
    dst->nt += src->nt;
    return FM_OK;
}

void fm_mesh_truncate(fm_mesh *m, size_t nv, size_t nt)
{
    if (nv < m->nv)
        m->nv = nv;
    if (nt < m->nt)
        m->nt = nt;
}

size_t fm_mesh_drop_triangles(fm_mesh *m, const unsigned char *gone, int32_t *beside)
{
    size_t kept = 0;
    for (size_t t = 0; t < m->nt; t++) {
        if (gone[t])
            continue;
        memmove(m->tri + 3 * kept, m->tri + 3 * t, 3 * sizeof *m->tri);
        if (beside)
            beside[kept] = beside[t];
        m->tag[kept++] = m->tag[t];
    }
    size_t removed = m->nt - kept;
    m->nt = kept;
    return removed;
}

fm_keyed *fm_mesh_sides(const fm_mesh *m, size_t *n)
{
    size_t nt = fm_mesh_ntriangles(m);
    const int32_t *T = fm_mesh_triangles(m);
    fm_keyed *side = malloc((3 * nt + 1) * sizeof *side);
    *n = 0;
    if (!side)
        return NULL;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++)
            side[3 * t + (size_t)k] = (fm_keyed){
                fm_edge_key((uint32_t)T[3 * t + (size_t)k], (uint32_t)T[3 * t + (size_t)(k + 1) % 3]), t};
    if (fm_sort_keyed(side, 3 * nt)) {
        free(side);
        return NULL;
    }
    *n = 3 * nt;
    return side;
}

size_t fm_used_vertices(const int32_t *tri, size_t nt, size_t nv, int32_t *map)
{
    for (size_t v = 0; v < nv; v++)
        map[v] = -1;
    for (size_t k = 0; k < 3 * nt; k++)
        map[tri[k]] = 0;
    size_t used = 0;
    for (size_t v = 0; v < nv; v++)
        if (map[v] == 0)
            map[v] = (int32_t)used++;
    return used;
}

int fm_triangle_side(const int32_t *tri, int32_t u, int32_t v)
{
    for (int k = 0; k < 3; k++) {
        int32_t a = tri[k], b = tri[(k + 1) % 3];
        if ((a == u && b == v) || (a == v && b == u))
            return k;
    }
    return -1;
}
