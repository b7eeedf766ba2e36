/* Fine triangulations of the selected cells of a sheet, their clipping to
 * the grown or trimmed region, and the exact triangle tests. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "connect_internal.h"
#include "fm_predicates.h"

int cn_subdivision(const cn_sheet *s, double sample_spacing)
{
    if (!(sample_spacing > 0))
        return 1;
    double k = ceil(s->hs / sample_spacing - 1e-9);
    return k < 1 ? 1 : (k > 16 ? 16 : (int)k);
}

void cn_zone_free(cn_zone *z)
{
    if (!z)
        return;
    free(z->xyz);
    free(z->uv);
    free(z->sd);
    free(z->tri);
    free(z->tedge);
    free(z->ev);
    memset(z, 0, sizeof *z);
}

typedef struct edge_key {
    int32_t a, b; /* a < b */
    int32_t slot; /* 3 t + k */
} edge_key;

static int cmp_edge(const void *x, const void *y)
{
    const edge_key *p = x, *q = y;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    if (p->b != q->b)
        return p->b < q->b ? -1 : 1;
    return (p->slot > q->slot) - (p->slot < q->slot);
}

/* Bilinear outline distance at lattice point (I, J) of subdivision sub. */
static double node_sd(const cn_sheet *s, size_t I, size_t J, int sub)
{
    size_t ci = I / (size_t)sub, cj = J / (size_t)sub;
    if (ci >= s->nsu)
        ci = s->nsu - 1;
    if (cj >= s->nsv)
        cj = s->nsv - 1;
    double fu = (double)(I - ci * (size_t)sub) / sub, fv = (double)(J - cj * (size_t)sub) / sub;
    size_t nu = s->nsu + 1, n00 = cj * nu + ci;
    double a = s->sd[n00], b = s->sd[n00 + 1], c = s->sd[n00 + nu], d = s->sd[n00 + nu + 1];
    return (1 - fv) * ((1 - fu) * a + fu * b) + fv * ((1 - fu) * c + fu * d);
}

fm_status cn_zone_build(const cn_sheet *s, const unsigned char *sel, int sub, int edges,
                        cn_zone *z)
{
    memset(z, 0, sizeof *z);
    size_t NU = s->nsu * (size_t)sub + 1, NV = s->nsv * (size_t)sub + 1;
    size_t ncells = 0;
    for (size_t c = 0; c < s->nsu * s->nsv; c++)
        ncells += sel[c] != 0;
    if (!ncells)
        return FM_OK;
    size_t nf = ncells * (size_t)sub * (size_t)sub;
    size_t vcap = ncells * (size_t)(sub + 1) * (size_t)(sub + 1);
    if (vcap > NU * NV)
        vcap = NU * NV;
    int32_t *map = malloc(NU * NV * sizeof *map);
    z->xyz = malloc(3 * vcap * sizeof *z->xyz);
    z->uv = malloc(2 * vcap * sizeof *z->uv);
    z->sd = malloc(vcap * sizeof *z->sd);
    z->tri = malloc(6 * nf * sizeof *z->tri);
    if (!map || !z->xyz || !z->uv || !z->sd || !z->tri) {
        free(map);
        cn_zone_free(z);
        return FM_ERR_NOMEM;
    }
    for (size_t k = 0; k < NU * NV; k++)
        map[k] = -1;
    double h = s->hs / sub;
    for (size_t cj = 0; cj < s->nsv; cj++)
        for (size_t ci = 0; ci < s->nsu; ci++) {
            if (!sel[cj * s->nsu + ci])
                continue;
            for (int b = 0; b < sub; b++)
                for (int a = 0; a < sub; a++) {
                    int32_t id[4];
                    for (int q = 0; q < 4; q++) {
                        size_t I = ci * (size_t)sub + (size_t)a + (size_t)(q & 1);
                        size_t J = cj * (size_t)sub + (size_t)b + (size_t)(q >> 1);
                        int32_t *slot = map + J * NU + I;
                        if (*slot < 0) {
                            size_t v = z->nv++;
                            double u = s->u0 + (double)I * h, w = s->v0 + (double)J * h;
                            if (I == NU - 1)
                                u = s->u0 + (double)s->nsu * s->hs;
                            if (J == NV - 1)
                                w = s->v0 + (double)s->nsv * s->hs;
                            z->uv[2 * v] = u;
                            z->uv[2 * v + 1] = w;
                            fm_fit_surface_eval(s->surf, u, w, z->xyz + 3 * v, NULL, NULL);
                            z->sd[v] = node_sd(s, I, J, sub);
                            *slot = (int32_t)v;
                        }
                        id[q] = *slot;
                    }
                    int32_t *t = z->tri + 3 * z->nt;
                    t[0] = id[0], t[1] = id[1], t[2] = id[3];
                    t[3] = id[0], t[4] = id[3], t[5] = id[2];
                    z->nt += 2;
                }
        }
    free(map);
    if (!edges)
        return FM_OK;
    edge_key *ek = malloc(3 * z->nt * sizeof *ek);
    z->tedge = malloc(3 * z->nt * sizeof *z->tedge);
    z->ev = malloc(6 * z->nt * sizeof *z->ev);
    if (!ek || !z->tedge || !z->ev) {
        free(ek);
        cn_zone_free(z);
        return FM_ERR_NOMEM;
    }
    for (size_t t = 0; t < z->nt; t++)
        for (int k = 0; k < 3; k++) {
            int32_t a = z->tri[3 * t + k], b = z->tri[3 * t + (k + 1) % 3];
            edge_key *e = ek + 3 * t + k;
            e->a = a < b ? a : b;
            e->b = a < b ? b : a;
            e->slot = (int32_t)(3 * t + (size_t)k);
        }
    qsort(ek, 3 * z->nt, sizeof *ek, cmp_edge);
    for (size_t i = 0; i < 3 * z->nt; i++) {
        if (i == 0 || ek[i].a != ek[i - 1].a || ek[i].b != ek[i - 1].b) {
            z->ev[2 * z->ne] = ek[i].a;
            z->ev[2 * z->ne + 1] = ek[i].b;
            z->ne++;
        }
        z->tedge[ek[i].slot] = (int32_t)(z->ne - 1);
    }
    free(ek);
    return FM_OK;
}

fm_mesh *cn_zone_clip(const cn_zone *z, double level)
{
    fm_mesh *m = fm_mesh_create();
    if (!m)
        return NULL;
    for (size_t t = 0; t < z->nt; t++) {
        const int32_t *T = z->tri + 3 * t;
        double f[3];
        int nin = 0;
        for (int k = 0; k < 3; k++) {
            f[k] = z->sd[T[k]] - level;
            nin += f[k] <= 0;
        }
        if (nin == 0)
            continue;
        double poly[4][3];
        int np = 0;
        for (int k = 0; k < 3; k++) {
            int k2 = (k + 1) % 3;
            const double *p = z->xyz + 3 * T[k], *q = z->xyz + 3 * T[k2];
            if (f[k] <= 0) {
                memcpy(poly[np++], p, sizeof poly[0]);
            }
            if ((f[k] <= 0) != (f[k2] <= 0) && np < 4) {
                double r = f[k] / (f[k] - f[k2]);
                for (int i = 0; i < 3; i++)
                    poly[np][i] = p[i] + r * (q[i] - p[i]);
                np++;
            }
        }
        if (np < 3)
            continue;
        int32_t base = (int32_t)fm_mesh_nvertices(m);
        for (int i = 0; i < np; i++)
            if (fm_mesh_add_vertex(m, poly[i][0], poly[i][1], poly[i][2]) < 0) {
                fm_mesh_destroy(m);
                return NULL;
            }
        for (int i = 1; i + 1 < np; i++)
            if (fm_mesh_add_triangle(m, base, base + i, base + i + 1, 0) < 0) {
                fm_mesh_destroy(m);
                return NULL;
            }
    }
    return m;
}

int cn_plane_side(const double *a, const double *b, const double *c, const double *p)
{
    int s = fm_orient3d(a, b, c, p);
    return s ? s : 1;
}

/* Sign of orient3d of two edges, each in ascending id order; a zero counts
 * as positive. Swapping the two edges is an even permutation, so the rule
 * gives the same answer from either mesh. */
static int edge_pair_sign(const double *p, const double *q, const double *a, const double *b)
{
    int s = fm_orient3d(p, q, a, b);
    return s ? s : 1;
}

int cn_edge_crosses_triangle(const double *p, const double *q, int64_t ip, int64_t iq,
                             const double *const t[3], const int64_t it[3])
{
    int sp = cn_plane_side(t[0], t[1], t[2], p), sq = cn_plane_side(t[0], t[1], t[2], q);
    if (sp == sq)
        return 0;
    if (ip > iq) {
        const double *x = p;
        p = q;
        q = x;
    }
    int first = 0;
    for (int k = 0; k < 3; k++) {
        int k2 = (k + 1) % 3;
        int s = it[k] < it[k2] ? edge_pair_sign(p, q, t[k], t[k2])
                               : -edge_pair_sign(p, q, t[k2], t[k]);
        if (k == 0)
            first = s;
        else if (s != first)
            return 0;
    }
    return 1;
}

