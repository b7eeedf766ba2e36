/* The named edge groups of a fault set (faultset_internal.h): each
 * fault's outline by kind, and each junction curve. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "faultset_internal.h"
#include "fm_sort.h"

const char *const fs_edge_kind_names[FS_EDGE_KINDS] = {"top", "buried top", "bottom", "ends"};

/* The kind of outline edge u-v of triangle t (third vertex w): which way
 * it faces within the triangle, against up dip. */
static int edge_kind(const double *x, int32_t u, int32_t v, int32_t w, double zsurf)
{
    const double *pu = x + 3 * (size_t)u, *pv = x + 3 * (size_t)v, *pw = x + 3 * (size_t)w;
    double e1[3], e2[3], n[3];
    for (int d = 0; d < 3; d++) {
        e1[d] = pv[d] - pu[d];
        e2[d] = pw[d] - pu[d];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (nl == 0)
        return FS_EDGE_ENDS;
    for (int d = 0; d < 3; d++)
        n[d] /= nl;
    /* up dip within the triangle: the vertical projected onto it */
    double up[3] = {-n[2] * n[0], -n[2] * n[1], 1 - n[2] * n[2]};
    double ul = sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
    /* outward: from the third vertex to the edge, across the edge */
    double o[3], ee = 0, oe = 0, ol = 0, dot = 0;
    for (int d = 0; d < 3; d++) {
        o[d] = (pu[d] + pv[d]) / 2 - pw[d];
        ee += e1[d] * e1[d];
        oe += o[d] * e1[d];
    }
    for (int d = 0; d < 3; d++) {
        o[d] -= ee > 0 ? oe / ee * e1[d] : 0;
        ol += o[d] * o[d];
        dot += o[d] * up[d];
    }
    ol = sqrt(ol);
    if (ul < 1e-6 || ol == 0)
        return FS_EDGE_ENDS; /* a horizontal triangle has no up dip */
    double c = dot / (ul * ol), c45 = sqrt(0.5);
    if (c > c45)
        return pu[2] >= zsurf && pv[2] >= zsurf ? FS_EDGE_TOP : FS_EDGE_BURIED;
    return c < -c45 ? FS_EDGE_BOTTOM : FS_EDGE_ENDS;
}

/* The next free place in vertex v's list (filled[v]: how many it holds). */
static size_t next_free(const size_t *vs, int32_t *filled, int32_t v)
{
    return vs[v] + (size_t)filled[v]++;
}

static int add_edge(fs_edge_group *g, int32_t u, int32_t v, int32_t t, int side)
{
    if (g->n == g->cap) {
        size_t c = g->cap ? 2 * g->cap : 16;
        int32_t(*e)[4] = realloc(g->edge, c * sizeof *e);
        if (!e)
            return -1;
        g->edge = e;
        g->cap = c;
    }
    g->edge[g->n][0] = u;
    g->edge[g->n][1] = v;
    g->edge[g->n][2] = t;
    g->edge[g->n][3] = side;
    g->n++;
    return 0;
}

void fs_edge_groups_free(fs_edge_group *g, size_t n)
{
    for (size_t i = 0; g && i < n; i++) {
        free(g[i].name);
        free(g[i].edge);
    }
    free(g);
}

int fs_edge_groups_make(const fm_faultset *fs, fs_edge_group **out, size_t *nout)
{
    *out = NULL;
    *nout = 0;
    size_t nf = fs->nfaults, ns = 0, ngroups = FS_EDGE_KINDS * nf + fs->nnodesets;
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh), *tag = fm_mesh_tags(fs->mesh);
    size_t nv = fm_mesh_nvertices(fs->mesh);
    fm_keyed *side = fm_mesh_sides(fs->mesh, &ns);
    fs_edge_group *g = calloc(ngroups + 1, sizeof *g);
    int32_t *filled = calloc(nv + 1, sizeof *filled);
    if (!side || !g || !filled) {
        free(side);
        free(g);
        free(filled);
        return -1;
    }
    int bad = 0;
    /* the surface: a top edge at or above it is the fault's trace */
    const double zsurf = -1e-6;
    for (size_t i = 0; i < ns && !bad;) {
        size_t j = i + 1;
        while (j < ns && side[j].key == side[i].key)
            j++;
        int32_t f0 = tag[side[i].index];
        int one = j - i == 1, shared = 0;
        for (size_t k = i + 1; k < j; k++)
            shared |= tag[side[k].index] != f0;
        if (one && !shared) {
            size_t t = side[i].index;
            int32_t u = (int32_t)(side[i].key >> 32), v = (int32_t)(side[i].key & 0xffffffffu);
            int s = fm_triangle_side(tri + 3 * t, u, v);
            int32_t w = tri[3 * t + (size_t)(s + 2) % 3];
            int kind = edge_kind(x, u, v, w, zsurf);
            bad = add_edge(&g[FS_EDGE_KINDS * (size_t)f0 + (size_t)kind], u, v, (int32_t)t, s);
        }
        i = j;
    }
    /* junction curves: edges of two faults' triangles with both nodes in
     * one node set (the node sets each vertex is in, as lists) */
    size_t *vs = calloc(nv + 2, sizeof *vs), nmem = 0;
    int32_t *vset = NULL;
    bad |= !vs;
    for (size_t k = 0; k < fs->nnodesets && !bad; k++)
        for (size_t q = 0; q < fs->nodesets[k].n; q++) {
            int32_t v = fs->nodesets[k].vertices[q];
            if (v >= 0 && (size_t)v < nv)
                vs[v + 1]++, nmem++;
        }
    for (size_t v = 0; v < nv && !bad; v++)
        vs[v + 1] += vs[v];
    if (!bad && !(vset = malloc((nmem + 1) * sizeof *vset)))
        bad = 1;
    for (size_t k = 0; k < fs->nnodesets && !bad; k++)
        for (size_t q = 0; q < fs->nodesets[k].n; q++) {
            int32_t v = fs->nodesets[k].vertices[q];
            if (v >= 0 && (size_t)v < nv)
                vset[next_free(vs, filled, v)] = (int32_t)k;
        }
    for (size_t i = 0; i < ns && !bad;) {
        size_t j = i + 1;
        int shared = 0;
        while (j < ns && side[j].key == side[i].key) {
            shared |= tag[side[j].index] != tag[side[i].index];
            j++;
        }
        int32_t u = (int32_t)(side[i].key >> 32), v = (int32_t)(side[i].key & 0xffffffffu);
        for (size_t a1 = vs[u]; shared && a1 < vs[u + 1] && !bad; a1++)
            for (size_t b1 = vs[v]; b1 < vs[v + 1] && !bad; b1++) {
                if (vset[a1] != vset[b1])
                    continue;
                /* once per set: the lists may hold a vertex twice */
                int seen = 0;
                for (size_t c1 = vs[u]; c1 < a1; c1++)
                    seen |= vset[c1] == vset[a1];
                if (seen)
                    continue;
                size_t t = side[i].index;
                int s = fm_triangle_side(tri + 3 * t, u, v);
                bad = add_edge(&g[FS_EDGE_KINDS * nf + (size_t)vset[a1]], u, v, (int32_t)t, s);
                break;
            }
        i = j;
    }
    free(vs);
    free(vset);
    /* names; groups without edges are dropped */
    size_t m = 0;
    for (size_t i = 0; i < ngroups; i++) {
        if (!g[i].n || bad) {
            free(g[i].edge);
            continue;
        }
        const char *base = i < FS_EDGE_KINDS * nf ? fs->names[i / FS_EDGE_KINDS]
                                                   : fs->nodesets[i - FS_EDGE_KINDS * nf].name;
        const char *kind = i < FS_EDGE_KINDS * nf ? fs_edge_kind_names[i % FS_EDGE_KINDS] : NULL;
        size_t len = strlen(base) + (kind ? strlen(kind) + 2 : 0) + 1;
        char *name = malloc(len);
        if (!name) {
            bad = 1;
            free(g[i].edge);
            continue;
        }
        if (kind)
            snprintf(name, len, "%s: %s", base, kind);
        else
            snprintf(name, len, "%s", base);
        g[m] = g[i];
        g[m].name = name;
        g[m].fault = i < FS_EDGE_KINDS * nf ? (int32_t)(i / FS_EDGE_KINDS) : -1;
        g[m].kind = i < FS_EDGE_KINDS * nf ? (int)(i % FS_EDGE_KINDS) : -1;
        g[m].set = i < FS_EDGE_KINDS * nf ? -1 : (int32_t)(i - FS_EDGE_KINDS * nf);
        m++;
    }
    free(side);
    free(filled);
    if (bad) {
        fs_edge_groups_free(g, m);
        return -1;
    }
    *out = g;
    *nout = m;
    return 0;
}
