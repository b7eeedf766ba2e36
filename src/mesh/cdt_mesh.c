/* Storage of the CDT and the edge operations everything else builds on:
 * growing the arrays, finding an edge by its end points, flipping, and
 * Lawson's flips back to (constrained) Delaunay. */
#include <stdlib.h>
#include <string.h>

#include "cdt_internal.h"

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return 0;
    size_t c = *cap ? *cap : 64;
    while (c < need)
        c *= 2;
    void *np = realloc(*p, c * elem);
    if (!np)
        return -1;
    *p = np;
    *cap = c;
    return 0;
}

int cdt_reserve_points(struct fm_cdt *t, size_t n)
{
    if (n <= t->pcap)
        return 0;
    size_t c = t->pcap ? t->pcap : 64;
    while (c < n)
        c *= 2;
    double *xy = realloc(t->xy, 2 * c * sizeof *xy);
    if (!xy)
        return -1;
    t->xy = xy;
    int32_t **arrs[3] = {&t->pseg, &t->vtri, &t->vmark};
    for (int k = 0; k < 3; k++) {
        int32_t *a = realloc(*arrs[k], c * sizeof *a);
        if (!a)
            return -1;
        *arrs[k] = a;
    }
    for (size_t i = t->pcap; i < c; i++)
        t->vmark[i] = -1;
    t->pcap = c;
    return 0;
}

int32_t cdt_add_point(struct fm_cdt *t, const double p[2], int32_t pseg)
{
    if (t->np >= (size_t)INT32_MAX || cdt_reserve_points(t, t->np + 1))
        return -1;
    size_t v = t->np++;
    t->xy[2 * v] = p[0];
    t->xy[2 * v + 1] = p[1];
    t->pseg[v] = pseg;
    t->vtri[v] = -1;
    t->vmark[v] = -1;
    return (int32_t)v;
}

int cdt_reserve_triangles(struct fm_cdt *t, size_t n)
{
    if (n <= t->tcap)
        return 0;
    /* Handles 3t+i must fit in an int32. */
    if (n > (size_t)INT32_MAX / 3 - 3)
        return -1;
    size_t c = t->tcap ? t->tcap : 128;
    while (c < n)
        c *= 2;
    if (c > (size_t)INT32_MAX / 3 - 3)
        c = (size_t)INT32_MAX / 3 - 3;
    int32_t **arrs[3] = {&t->tv, &t->tn, &t->tc};
    for (int k = 0; k < 3; k++) {
        int32_t *a = realloc(*arrs[k], 3 * c * sizeof *a);
        if (!a)
            return -1;
        *arrs[k] = a;
    }
    uint8_t *r = realloc(t->region, c);
    if (!r)
        return -1;
    t->region = r;
    uint32_t *s = realloc(t->stamp, c * sizeof *s);
    if (!s)
        return -1;
    t->stamp = s;
    uint32_t *m = realloc(t->tmark, c * sizeof *m);
    if (!m)
        return -1;
    t->tmark = m;
    for (size_t i = t->tcap; i < c; i++) {
        t->stamp[i] = 0;
        t->tmark[i] = 0;
        t->region[i] = CDT_DEAD;
    }
    t->tcap = c;
    return 0;
}

int32_t cdt_new_triangle(struct fm_cdt *t)
{
    int32_t tri;
    if (t->nfree) {
        tri = t->freel[--t->nfree];
    } else {
        if (cdt_reserve_triangles(t, t->nt + 1))
            return -1;
        tri = (int32_t)t->nt++;
    }
    t->stamp[tri]++;
    t->region[tri] = 1;
    for (int i = 0; i < 3; i++) {
        t->tn[3 * tri + i] = -1;
        t->tc[3 * tri + i] = -1;
    }
    return tri;
}

void cdt_free_triangle(struct fm_cdt *t, int32_t tri)
{
    /* Room for every slot is reserved as slots are made, so this cannot
     * fail once the slot exists. */
    if (grow((void **)&t->freel, &t->freecap, t->nfree + 1, sizeof *t->freel))
        return;
    t->region[tri] = CDT_DEAD;
    t->stamp[tri]++;
    t->freel[t->nfree++] = tri;
}

int cdt_push_pair(struct fm_cdt *t, int32_t a, int32_t b)
{
    if (grow((void **)&t->pairs, &t->paircap, t->npairs + 1, sizeof *t->pairs))
        return -1;
    t->pairs[t->npairs].a = a;
    t->pairs[t->npairs].b = b;
    t->npairs++;
    return 0;
}

static int local_index(const struct fm_cdt *t, int32_t tri, int32_t v)
{
    const int32_t *tv = t->tv + 3 * (size_t)tri;
    return tv[0] == v ? 0 : tv[1] == v ? 1 : 2;
}

int32_t cdt_find_edge(const struct fm_cdt *t, int32_t a, int32_t b)
{
    int32_t t0 = t->vtri[a];
    if (t0 < 0)
        return -1;
    /* Counter-clockwise round a; the stars of real points are closed, only
     * super vertices need the way back. */
    for (int dir = 0; dir < 2; dir++) {
        int32_t tri = t0;
        int open = 0;
        do {
            int ia = local_index(t, tri, a);
            const int32_t *tv = t->tv + 3 * (size_t)tri;
            if (tv[(ia + 1) % 3] == b)
                return 3 * tri + (ia + 2) % 3;
            int32_t n = t->tn[3 * tri + (dir == 0 ? (ia + 1) % 3 : (ia + 2) % 3)];
            if (n < 0) {
                open = 1;
                break;
            }
            tri = n / 3;
        } while (tri != t0);
        if (!open)
            return -1;
    }
    return -1;
}

void cdt_flip(struct fm_cdt *t, int32_t e)
{
    int32_t ta = e / 3, i = e % 3;
    int32_t f = t->tn[e];
    int32_t ub = f / 3, j = f % 3;
    int32_t p = t->tv[3 * ta + i], a = t->tv[3 * ta + (i + 1) % 3];
    int32_t b = t->tv[3 * ta + (i + 2) % 3], w = t->tv[3 * ub + j];
    int32_t e_bp = 3 * ta + (i + 1) % 3, e_pa = 3 * ta + (i + 2) % 3;
    int32_t e_aw = 3 * ub + (j + 1) % 3, e_wb = 3 * ub + (j + 2) % 3;
    int32_t n_bp = t->tn[e_bp], c_bp = t->tc[e_bp];
    int32_t n_pa = t->tn[e_pa], c_pa = t->tc[e_pa];
    int32_t n_aw = t->tn[e_aw], c_aw = t->tc[e_aw];
    int32_t n_wb = t->tn[e_wb], c_wb = t->tc[e_wb];
    int32_t *tv = t->tv, *tn = t->tn, *tc = t->tc;
    tv[3 * ta] = p, tv[3 * ta + 1] = a, tv[3 * ta + 2] = w;
    tv[3 * ub] = w, tv[3 * ub + 1] = b, tv[3 * ub + 2] = p;
    tn[3 * ta] = n_aw, tc[3 * ta] = c_aw;
    tn[3 * ta + 2] = n_pa, tc[3 * ta + 2] = c_pa;
    tn[3 * ub] = n_bp, tc[3 * ub] = c_bp;
    tn[3 * ub + 2] = n_wb, tc[3 * ub + 2] = c_wb;
    tn[3 * ta + 1] = 3 * ub + 1, tc[3 * ta + 1] = -1;
    tn[3 * ub + 1] = 3 * ta + 1, tc[3 * ub + 1] = -1;
    if (n_aw >= 0)
        tn[n_aw] = 3 * ta;
    if (n_pa >= 0)
        tn[n_pa] = 3 * ta + 2;
    if (n_bp >= 0)
        tn[n_bp] = 3 * ub;
    if (n_wb >= 0)
        tn[n_wb] = 3 * ub + 2;
    t->vtri[p] = ta, t->vtri[a] = ta, t->vtri[w] = ta, t->vtri[b] = ub;
    t->stamp[ta]++;
    t->stamp[ub]++;
    t->last = ta;
    if (t->touch) {
        t->touch(t, ta);
        t->touch(t, ub);
    }
}

void cdt_legalize(struct fm_cdt *t, size_t from)
{
    while (t->npairs > from) {
        cdt_pair pr = t->pairs[--t->npairs];
        int32_t e = cdt_find_edge(t, pr.a, pr.b);
        if (e < 0 || t->tc[e] >= 0 || t->tn[e] < 0)
            continue;
        int32_t f = t->tn[e];
        /* Outside the domain nothing needs to be Delaunay. */
        if (t->region[e / 3] != 1 || t->region[f / 3] != 1)
            continue;
        const int32_t *v = t->tv + 3 * (size_t)(e / 3);
        int32_t p = t->tv[e], w = t->tv[f];
        if (cdt_incircle(t, cdt_p(t, v[0]), cdt_p(t, v[1]), cdt_p(t, v[2]), cdt_p(t, w)) <= 0)
            continue;
        int32_t a = cdt_org(t, e), b = cdt_dst(t, e);
        /* Exact convexity: a metric circle test does not imply it. */
        if (fm_orient2d(cdt_p(t, p), cdt_p(t, a), cdt_p(t, w)) <= 0 ||
            fm_orient2d(cdt_p(t, w), cdt_p(t, b), cdt_p(t, p)) <= 0)
            continue;
        cdt_flip(t, e);
        /* Out of memory only stops the flips early: the triangulation is
         * valid, merely not Delaunay everywhere. */
        if (cdt_push_pair(t, a, w) || cdt_push_pair(t, w, b) || cdt_push_pair(t, b, p) ||
            cdt_push_pair(t, p, a))
            return;
    }
}
