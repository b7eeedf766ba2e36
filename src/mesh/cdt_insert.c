/* Point insertion by Bowyer-Watson cavities, split in two steps so that a
 * candidate point can be judged (does it see its whole cavity, does it
 * encroach a segment) before anything changes. */
#include <stdlib.h>
#include <string.h>

#include "cdt_internal.h"

static int grow32(int32_t **p, size_t *cap, size_t need)
{
    if (need <= *cap)
        return 0;
    size_t c = *cap ? *cap : 64;
    while (c < need)
        c *= 2;
    int32_t *np = realloc(*p, c * sizeof *np);
    if (!np)
        return -1;
    *p = np;
    *cap = c;
    return 0;
}

static int add_cav(struct fm_cdt *t, int32_t tri, size_t *nstack)
{
    if (grow32(&t->cav, &t->cavcap, t->ncav + 1) || grow32(&t->stack, &t->stackcap, *nstack + 1))
        return -1;
    t->tmark[tri] = t->epoch;
    t->cav[t->ncav++] = tri;
    t->stack[(*nstack)++] = tri;
    return 0;
}

static int add_bnd(struct fm_cdt *t, int32_t e)
{
    size_t cap = t->bndcap;
    if (grow32(&t->bnde, &cap, t->nbnd + 1))
        return -1;
    if (cap != t->bndcap) {
        cdt_bedge *nb = realloc(t->bnd, cap * sizeof *nb);
        if (!nb)
            return -1;
        t->bnd = nb;
        t->bndcap = cap;
    }
    t->bnde[t->nbnd++] = e;
    return 0;
}

cdt_cavity_result cdt_cavity(struct fm_cdt *t, const double q[2], const int32_t *seeds,
                             size_t nseeds, int32_t force_edge, int32_t *bad)
{
    int32_t force_twin = force_edge >= 0 ? t->tn[force_edge] : -1;
    if (++t->epoch == 0) {
        memset(t->tmark, 0, t->tcap * sizeof *t->tmark);
        t->epoch = 1;
    }
    t->ncav = 0;
    t->nbnd = 0;
    *bad = -1;
    size_t ns = 0;
    for (size_t s = 0; s < nseeds; s++)
        if (t->tmark[seeds[s]] != t->epoch && add_cav(t, seeds[s], &ns))
            return CDT_CAVITY_NOMEM;
    while (ns) {
        int32_t tri = t->stack[--ns];
        for (int i = 0; i < 3; i++) {
            int32_t e = 3 * tri + i, n = t->tn[e];
            int forced = e == force_edge || e == force_twin;
            if (n < 0) {
                if (add_bnd(t, e))
                    return CDT_CAVITY_NOMEM;
                continue;
            }
            int32_t nt = n / 3;
            if (t->tmark[nt] == t->epoch) {
                /* Both sides taken: a segment would vanish inside. With
                 * loops this cannot happen (the domain lies on one side of
                 * a segment). A graph's segment may end inside the domain,
                 * and a cavity could then in principle reach round that
                 * end to its far side; 9 million random cavities next to
                 * a dangling end (with skewed metrics too) never did.
                 * Should it happen the point is not inserted: quality, not
                 * validity. */
                if (t->tc[e] >= 0 && !forced) {
                    *bad = e;
                    return CDT_CAVITY_NOT_STAR;
                }
                continue;
            }
            int take;
            if (t->tc[e] >= 0 && !forced)
                take = 0;
            else if (forced)
                take = 1;
            else if (t->region[nt] != 1 && cdt_has_super(t, nt))
                take = 0;
            else {
                const int32_t *v = t->tv + 3 * (size_t)nt;
                take = cdt_incircle(t, cdt_p(t, v[0]), cdt_p(t, v[1]), cdt_p(t, v[2]), q) > 0;
            }
            if (take ? add_cav(t, nt, &ns) : add_bnd(t, e))
                return CDT_CAVITY_NOMEM;
        }
    }
    /* q must see every boundary edge strictly from inside, and the boundary
     * must be one simple loop (each vertex the origin of one edge). */
    cdt_cavity_result r = CDT_CAVITY_OK;
    size_t k;
    for (k = 0; k < t->nbnd; k++) {
        int32_t e = t->bnde[k];
        int32_t a = cdt_org(t, e), b = cdt_dst(t, e);
        if (t->vmark[a] != -1 || fm_orient2d(cdt_p(t, a), cdt_p(t, b), q) <= 0) {
            *bad = e;
            r = CDT_CAVITY_NOT_STAR;
            break;
        }
        t->vmark[a] = (int32_t)k;
    }
    for (size_t m = 0; m < k; m++)
        t->vmark[cdt_org(t, t->bnde[m])] = -1;
    return r;
}

int cdt_commit(struct fm_cdt *t, int32_t v, int32_t force_edge, int32_t split_seg)
{
    size_t nb = t->nbnd;
    if (grow32(&t->newt, &t->newcap, nb) || grow32(&t->freel, &t->freecap, t->nfree + t->ncav) ||
        cdt_reserve_triangles(t, t->nt + nb))
        return -1;
    int32_t sa = -1, sb = -1;
    if (split_seg >= 0) {
        sa = cdt_org(t, force_edge);
        sb = cdt_dst(t, force_edge);
    }
    for (size_t k = 0; k < nb; k++) {
        int32_t e = t->bnde[k];
        cdt_bedge *be = &t->bnd[k];
        be->org = cdt_org(t, e);
        be->dst = cdt_dst(t, e);
        be->twin = t->tn[e];
        be->cons = t->tc[e];
        be->region = t->region[e / 3];
    }
    for (size_t k = t->ncav; k-- > 0;)
        cdt_free_triangle(t, t->cav[k]);
    for (size_t k = 0; k < nb; k++) {
        int32_t T = cdt_new_triangle(t);
        const cdt_bedge *be = &t->bnd[k];
        t->newt[k] = T;
        t->tv[3 * T] = v;
        t->tv[3 * T + 1] = be->org;
        t->tv[3 * T + 2] = be->dst;
        t->tn[3 * T] = be->twin;
        t->tc[3 * T] = be->cons;
        if (be->twin >= 0)
            t->tn[be->twin] = 3 * T;
        t->region[T] = be->region;
        t->vmark[be->org] = T;
        t->vtri[be->org] = T;
    }
    for (size_t k = 0; k < nb; k++) {
        int32_t T = t->newt[k];
        const cdt_bedge *be = &t->bnd[k];
        int32_t U = t->vmark[be->dst];
        t->tn[3 * T + 1] = 3 * U + 2;
        t->tn[3 * U + 2] = 3 * T + 1;
        if (split_seg >= 0) {
            if (be->dst == sa || be->dst == sb)
                t->tc[3 * T + 1] = split_seg;
            if (be->org == sa || be->org == sb)
                t->tc[3 * T + 2] = split_seg;
        }
    }
    for (size_t k = 0; k < nb; k++)
        t->vmark[t->bnd[k].org] = -1;
    t->vtri[v] = t->newt[0];
    t->last = t->newt[0];
    if (t->touch)
        for (size_t k = 0; k < nb; k++)
            t->touch(t, t->newt[k]);
    return 0;
}

int32_t cdt_locate(struct fm_cdt *t, const double q[2])
{
    int32_t tri = t->last;
    if (tri < 0 || (size_t)tri >= t->nt || t->region[tri] == CDT_DEAD) {
        tri = -1;
        for (size_t k = 0; k < t->nt && tri < 0; k++)
            if (t->region[k] != CDT_DEAD)
                tri = (int32_t)k;
        if (tri < 0)
            return -1;
    }
    int32_t from = -1;
    /* A visibility walk ends in a Delaunay triangulation; the cap only
     * guards against a corrupted structure. */
    for (size_t steps = 0; steps <= 4 * t->nt + 16; steps++) {
        int moved = 0;
        for (int i = 0; i < 3; i++) {
            int32_t e = 3 * tri + i;
            if (e == from || t->tn[e] < 0)
                continue;
            if (fm_orient2d(cdt_p(t, cdt_org(t, e)), cdt_p(t, cdt_dst(t, e)), q) < 0) {
                from = t->tn[e];
                tri = from / 3;
                moved = 1;
                break;
            }
        }
        if (!moved)
            return tri;
    }
    return -1;
}
