/* The domain clipped to z <= sea level.
 *
 * The whole trimmed domain is triangulated at the target size first, and
 * the sea-level curve is found on that triangulation (marching triangles):
 * on every edge whose ends lie on either side, the crossing is located by
 * bisection along the edge in (u, v) with z evaluated on the surface, so
 * it is a point of the surface at sea level to rounding; in every triangle
 * with such edges the curve is the segment between its two crossings.
 * Because each curve point lies on an edge and each curve segment inside
 * one triangle, the curves cannot cross each other or the outline, however
 * closely they run along it (a fault top drawn a few metres above sea
 * level): tracing the curve by steps could not promise that. A node at
 * exactly sea level counts as below.
 *
 * The clipped loops then run: a crossing on the outline (entry), the
 * outline's nodes below sea level, the next crossing (exit), the sea-level
 * curve's points, the next entry... A loop without crossings is kept when
 * below and dropped when above; a closed curve inside the domain is a loop
 * of its own. The curve's points come at the triangulation's spacing
 * (between a sliver and one size apart); those closer than half a size to
 * the last one kept are dropped, where that leaves the loops simple
 * (checked with exact orientation tests), so that the cut does not force
 * tiny triangles. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_predicates.h"
#include "remesh_internal.h"

/* A crossing: the sea-level point on edge (a, b) of the triangulation,
 * a below and b above. */
typedef struct xing {
    int32_t a, b;    /* a below, b above */
    double uv[2];
    int32_t next;    /* the crossing the curve goes to, -1 at the outline */
    int32_t prev;
    int on_outline;  /* the edge is an outline edge */
    int32_t seg;     /* outline edges: the flat segment id */
    int visited;
} xing;

typedef struct edge_key {
    int32_t lo, hi;
    int32_t x;
} edge_key;

static int cmp_key(const void *pa, const void *pb)
{
    const edge_key *a = pa, *b = pb;
    if (a->lo != b->lo)
        return a->lo < b->lo ? -1 : 1;
    return (a->hi > b->hi) - (a->hi < b->hi);
}

typedef struct contour {
    xing *x;
    size_t n, cap;
    edge_key *keys; /* sorted */
    size_t nkeys;
} contour;

static int32_t find_x(const contour *c, int32_t p, int32_t q)
{
    edge_key k = {p < q ? p : q, p < q ? q : p, -1};
    edge_key *f = bsearch(&k, c->keys, c->nkeys, sizeof k, cmp_key);
    return f ? f->x : -1;
}

static void bisect(const fm_fit_surface *s, double level, const double *lo_uv,
                   const double *hi_uv, double out[2])
{
    double lo = 0, hi = 1;
    for (int it = 0; it < 64 && hi - lo > 1e-16; it++) {
        double m = 0.5 * (lo + hi), p[2] = {lo_uv[0] + m * (hi_uv[0] - lo_uv[0]),
                                            lo_uv[1] + m * (hi_uv[1] - lo_uv[1])};
        if (surface_z(s, p, level, NULL) > 0)
            hi = m;
        else
            lo = m;
    }
    double m = 0.5 * (lo + hi);
    out[0] = lo_uv[0] + m * (hi_uv[0] - lo_uv[0]);
    out[1] = lo_uv[1] + m * (hi_uv[1] - lo_uv[1]);
}

/* Crossings of every edge with ends on either side, and the curve
 * segments through the triangles, oriented with the part below sea level
 * on their left (the domain's side for the outline loops). */
static fm_status build_contour(const fm_fit_surface *s, double level, const double *uv,
                               const unsigned char *above, const int32_t *tri, size_t nt,
                               contour *c)
{
    size_t nk = 0, capk = 0;
    edge_key *keys = NULL;
    for (size_t t = 0; t < nt; t++) {
        const int32_t *T = tri + 3 * t;
        if (above[T[0]] == above[T[1]] && above[T[1]] == above[T[2]])
            continue;
        for (int i = 0; i < 3; i++) {
            int32_t p = T[i], q = T[(i + 1) % 3];
            if (above[p] == above[q])
                continue;
            if (nk == capk) {
                capk = capk ? 2 * capk : 256;
                edge_key *nkp = realloc(keys, capk * sizeof *nkp);
                if (!nkp) {
                    free(keys);
                    return FM_ERR_NOMEM;
                }
                keys = nkp;
            }
            keys[nk].lo = p < q ? p : q;
            keys[nk].hi = p < q ? q : p;
            keys[nk].x = -1;
            nk++;
        }
    }
    if (nk > 1)
        qsort(keys, nk, sizeof *keys, cmp_key);
    size_t w = 0;
    for (size_t k = 0; k < nk; k++)
        if (w == 0 || keys[k].lo != keys[w - 1].lo || keys[k].hi != keys[w - 1].hi)
            keys[w++] = keys[k];
    c->keys = keys;
    c->nkeys = w;
    c->n = w;
    c->x = calloc(w ? w : 1, sizeof *c->x);
    if (!c->x)
        return FM_ERR_NOMEM;
    for (size_t k = 0; k < w; k++) {
        xing *x = &c->x[k];
        int32_t lo = keys[k].lo, hi = keys[k].hi;
        x->a = above[lo] ? hi : lo;
        x->b = above[lo] ? lo : hi;
        bisect(s, level, uv + 2 * x->a, uv + 2 * x->b, x->uv);
        x->next = x->prev = -1;
        x->seg = -1;
        keys[k].x = (int32_t)k;
    }
    for (size_t t = 0; t < nt; t++) {
        const int32_t *T = tri + 3 * t;
        int32_t from = -1, to = -1;
        for (int i = 0; i < 3; i++) {
            int32_t p = T[i], q = T[(i + 1) % 3];
            if (!above[p] && above[q])
                from = find_x(c, p, q);
            else if (above[p] && !above[q])
                to = find_x(c, p, q);
        }
        if (from >= 0 && to >= 0) {
            c->x[from].next = to;
            c->x[to].prev = from;
        }
    }
    return FM_OK;
}

/* A node of the clipped loops before it is written into a dom_loop. */
typedef struct cnode {
    double uv[2];
    int level;
    dom_seg seg;   /* to the next node */
    int chain;     /* 1: an inner point of a sea-level curve (may be dropped) */
} cnode;

typedef struct cloop {
    cnode *v;
    size_t n, cap;
} cloop;

static int cpush(cloop *l, const double uv[2], int level, const dom_seg *sg, int chain)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 32;
        cnode *nv = realloc(l->v, cap * sizeof *nv);
        if (!nv)
            return -1;
        l->v = nv;
        l->cap = cap;
    }
    cnode *v = &l->v[l->n++];
    v->uv[0] = uv[0];
    v->uv[1] = uv[1];
    v->level = level;
    v->seg = *sg;
    v->chain = chain;
    return 0;
}

/* The part of flat segment k between two of its points. */
static dom_seg sub_seg(const flat_domain *fd, int32_t k, const double *p, const double *q)
{
    dom_seg r = fd->segs[k];
    double fa = chord_fraction(fd->ends + 4 * (size_t)k, p);
    double fb = chord_fraction(fd->ends + 4 * (size_t)k, q);
    double ta = fd->segs[k].ta, tb = fd->segs[k].tb;
    r.ta = ta + fa * (tb - ta);
    r.tb = ta + fb * (tb - ta);
    if (r.tb < r.ta)
        r.tb = r.ta;
    return r;
}

typedef struct clip_ctx {
    const fm_fit_surface *s;
    double level, h;
    const flat_domain *fd;
    const double *uv;          /* triangulation points */
    const unsigned char *above;
    int32_t *bnext;            /* outline: next point along its loop, -1 if none */
    int32_t *bseg;             /* outline: flat segment of the edge to bnext */
    contour c;
} clip_ctx;

static const dom_seg level_seg = {SEG_LEVEL, -1, 0, 0, 0};

/* From the entry crossing e (on outline edge p -> q, p above, q below),
 * builds one clipped loop. */
static fm_status walk(clip_ctx *cx, int32_t e0, cloop *L)
{
    int32_t e = e0;
    size_t guard = 0, limit = 4 * (cx->c.n + 16) + 4 * cx->fd->n + 1000000;
    do {
        xing *E = &cx->c.x[e];
        E->visited = 1;
        /* E lies on outline edge (b -> a): b above, a below */
        int32_t p = E->a;
        int32_t seg = cx->bseg[E->b];
        if (cpush(L, E->uv, 1, &level_seg, 0))
            return FM_ERR_NOMEM;
        L->v[L->n - 1].seg = sub_seg(cx->fd, seg, E->uv, cx->uv + 2 * p);
        /* along the outline while below */
        int32_t xi = -1;
        while (guard++ < limit) {
            int32_t q = cx->bnext[p];
            if (q < 0)
                return FM_ERR_TOPOLOGY;
            int32_t sq = cx->bseg[p];
            if (cx->above[q]) {
                xi = find_x(&cx->c, p, q);
                if (xi < 0)
                    return FM_ERR_TOPOLOGY;
                dom_seg sg = sub_seg(cx->fd, sq, cx->uv + 2 * p, cx->c.x[xi].uv);
                if (cpush(L, cx->uv + 2 * p, cx->fd->level && p < (int32_t)cx->fd->n ? cx->fd->level[p] : 0,
                          &sg, 0))
                    return FM_ERR_NOMEM;
                break;
            }
            dom_seg sg = cx->fd->segs[sq];
            sg = sub_seg(cx->fd, sq, cx->uv + 2 * p, cx->uv + 2 * q);
            if (cpush(L, cx->uv + 2 * p, p < (int32_t)cx->fd->n ? cx->fd->level[p] : 0, &sg, 0))
                return FM_ERR_NOMEM;
            p = q;
        }
        if (xi < 0)
            return FM_ERR_TOPOLOGY;
        /* the exit, then the sea-level curve to the next entry */
        xing *X = &cx->c.x[xi];
        X->visited = 1;
        if (cpush(L, X->uv, 1, &level_seg, 0))
            return FM_ERR_NOMEM;
        int32_t k = X->next;
        while (k >= 0 && !cx->c.x[k].on_outline && guard++ < limit) {
            cx->c.x[k].visited = 1;
            if (cpush(L, cx->c.x[k].uv, 1, &level_seg, 1))
                return FM_ERR_NOMEM;
            k = cx->c.x[k].next;
        }
        if (k < 0 || guard >= limit)
            return FM_ERR_TOPOLOGY;
        e = k;
    } while (e != e0 && guard < limit);
    return e == e0 ? FM_OK : FM_ERR_TOPOLOGY;
}

static int same(const double *a, const double *b) { return a[0] == b[0] && a[1] == b[1]; }

/* 1 if segment (a, b) crosses a segment of the loops other than those
 * ending at a or b, skipping removed nodes. */
static int chord_hits(cloop *ls, size_t nl, unsigned char **gone, const double *a, const double *b)
{
    for (size_t l = 0; l < nl; l++) {
        size_t n = ls[l].n, first = 0;
        while (first < n && gone[l][first])
            first++;
        if (first == n)
            continue;
        size_t i = first;
        do {
            size_t j = (i + 1) % n;
            while (gone[l][j])
                j = (j + 1) % n;
            const double *c = ls[l].v[i].uv, *d = ls[l].v[j].uv;
            if (!same(a, c) && !same(a, d) && !same(b, c) && !same(b, d) && segments_cross(a, b, c, d))
                return 1;
            i = j;
        } while (i != first);
    }
    return 0;
}

/* How much a node is worth keeping when it ends a tiny segment: inner
 * points of a sea-level curve least, then outline nodes inside a curve
 * piece, then crossings, then corners of the outline. */
static int keep_rank(const cnode *v, const cnode *prev)
{
    if (v->chain)
        return 0;
    if (!v->level && v->seg.kind == SEG_TRIM && prev->seg.kind == SEG_TRIM &&
        prev->seg.loop == v->seg.loop && prev->seg.piece == v->seg.piece)
        return 1;
    if (v->level)
        return 2;
    return 3;
}

static int loop_alive_next(unsigned char *gone, size_t n, size_t i)
{
    size_t j = (i + 1) % n;
    while (gone[j] && j != i)
        j = (j + 1) % n;
    return (int)j;
}

static int loop_alive_prev(unsigned char *gone, size_t n, size_t i)
{
    size_t j = (i + n - 1) % n;
    while (gone[j] && j != i)
        j = (j + n - 1) % n;
    return (int)j;
}

/* Removes nodes that make segments shorter than 0.4 size (the clip makes
 * them where a crossing falls next to an outline node, where the curve's
 * points come close on the triangulation, and where the outline dips
 * briefly below sea level), shortest first, dropping the endpoint that
 * matters less. A node goes only when the chord that replaces its two
 * segments crosses nothing, so the loops stay simple; loops that shrink
 * below three nodes or to a sliver of area go. */
static fm_status thin(const clip_ctx *cx, cloop *ls, size_t nl)
{
    unsigned char **gone = calloc(nl ? nl : 1, sizeof *gone);
    if (!gone)
        return FM_ERR_NOMEM;
    fm_status st = FM_OK;
    for (size_t l = 0; l < nl; l++)
        if (!(gone[l] = calloc(ls[l].n ? ls[l].n : 1, 1)))
            st = FM_ERR_NOMEM;
    for (size_t l = 0; l < nl && st == FM_OK; l++) {
        cloop *L = &ls[l];
        size_t n = L->n, alive = n;
        double *len = malloc((n ? n : 1) * sizeof *len);
        unsigned char *stuck = calloc(n ? n : 1, 1);
        if (!len || !stuck) {
            free(len);
            free(stuck);
            st = FM_ERR_NOMEM;
            break;
        }
        for (size_t i = 0; i < n; i++)
            len[i] = surface_dist(cx->s, L->v[i].uv, L->v[(i + 1) % n].uv);
        while (alive > 3) {
            /* the shortest live segment not yet found stuck */
            size_t best = (size_t)-1;
            for (size_t i = 0; i < n; i++)
                if (!gone[l][i] && !stuck[i] && len[i] < 0.4 * cx->h &&
                    (best == (size_t)-1 || len[i] < len[best]))
                    best = i;
            if (best == (size_t)-1)
                break;
            size_t j = (size_t)loop_alive_next(gone[l], n, best);
            size_t pi = (size_t)loop_alive_prev(gone[l], n, best);
            size_t nj = (size_t)loop_alive_next(gone[l], n, j);
            int ri = keep_rank(&L->v[best], &L->v[pi]), rj = keep_rank(&L->v[j], &L->v[best]);
            /* candidates: the lesser endpoint first */
            size_t cand[2] = {ri <= rj ? best : j, ri <= rj ? j : best};
            int done = 0;
            for (int c = 0; c < 2 && !done; c++) {
                size_t v = cand[c];
                size_t pv = (size_t)loop_alive_prev(gone[l], n, v);
                size_t nv = (size_t)loop_alive_next(gone[l], n, v);
                if (keep_rank(&L->v[v], &L->v[pv]) >= 3 && len[best] > 0)
                    continue; /* corners stay unless they coincide */
                if (len[best] > 0 && chord_hits(ls, nl, gone, L->v[pv].uv, L->v[nv].uv))
                    continue;
                if (L->v[v].seg.kind == SEG_TRIM && L->v[pv].seg.kind == SEG_TRIM &&
                    L->v[v].seg.loop == L->v[pv].seg.loop && L->v[v].seg.piece == L->v[pv].seg.piece)
                    L->v[pv].seg.tb = L->v[v].seg.tb;
                else if (L->v[v].seg.kind != L->v[pv].seg.kind || L->v[v].seg.kind == SEG_TRIM)
                    L->v[pv].seg.kind = SEG_FREE; /* the chord joins two curves */
                gone[l][v] = 1;
                alive--;
                len[pv] = surface_dist(cx->s, L->v[pv].uv, L->v[nv].uv);
                done = 1;
            }
            if (!done)
                stuck[best] = 1;
            (void)nj;
        }
        size_t w = 0;
        for (size_t i = 0; i < n; i++)
            if (!gone[l][i])
                L->v[w++] = L->v[i];
        L->n = w;
        memset(gone[l], 0, n);
        free(len);
        free(stuck);
    }
    for (size_t l = 0; l < nl; l++)
        free(gone[l]);
    free(gone);
    return st;
}

static fm_status to_domain(cloop *ls, size_t nl, remesh_domain *out)
{
    for (size_t l = 0; l < nl; l++) {
        if (ls[l].n < 3)
            continue;
        dom_loop *D = domain_add_loop(out);
        if (!D)
            return FM_ERR_NOMEM;
        for (size_t i = 0; i < ls[l].n; i++)
            if (loop_push(D, ls[l].v[i].uv, ls[l].v[i].level, &ls[l].v[i].seg))
                return FM_ERR_NOMEM;
    }
    return FM_OK;
}

static fm_status clip_loops(clip_ctx *cx, const fm_cdt *cdt, cloop **out, size_t *nout)
{
    cloop *ls = NULL;
    size_t nl = 0, cap = 0;
#define NEW_LOOP()                                                       \
    do {                                                                 \
        if (nl == cap) {                                                 \
            cap = cap ? 2 * cap : 8;                                     \
            cloop *nls = realloc(ls, cap * sizeof *nls);                 \
            if (!nls)                                                    \
                goto nomem;                                              \
            ls = nls;                                                    \
        }                                                                \
        memset(&ls[nl++], 0, sizeof *ls);                                \
    } while (0)
    fm_status st = FM_OK;
    /* entries: crossings on outline edges whose outline direction goes
     * from above to below */
    for (size_t k = 0; k < cx->c.n && st == FM_OK; k++) {
        xing *x = &cx->c.x[k];
        if (!x->on_outline || x->visited || cx->bnext[x->b] != x->a)
            continue;
        NEW_LOOP();
        st = walk(cx, (int32_t)k, &ls[nl - 1]);
    }
    /* outline loops that never cross: kept whole when below */
    size_t np = fm_cdt_npoints(cdt);
    unsigned char *seen = calloc(np ? np : 1, 1);
    if (!seen)
        goto nomem;
    for (size_t k = 0; k < cx->c.n; k++)
        if (cx->c.x[k].on_outline)
            seen[cx->c.x[k].a] = seen[cx->c.x[k].b] = 2;
    for (size_t p0 = 0; p0 < np && st == FM_OK; p0++) {
        if (cx->bnext[p0] < 0 || seen[p0])
            continue;
        /* a loop is crossed if any of its points was marked */
        int crossed = 0, above = 0;
        size_t guard = 0;
        int32_t p = (int32_t)p0;
        do {
            crossed |= seen[p] == 2;
            above |= cx->above[p];
            p = cx->bnext[p];
        } while (p >= 0 && p != (int32_t)p0 && guard++ < np);
        p = (int32_t)p0;
        guard = 0;
        if (!crossed && !above)
            NEW_LOOP();
        do {
            seen[p] = 1;
            if (!crossed && !above) {
                dom_seg sg = sub_seg(cx->fd, cx->bseg[p], cx->uv + 2 * p, cx->uv + 2 * cx->bnext[p]);
                if (cpush(&ls[nl - 1], cx->uv + 2 * p, p < (int32_t)cx->fd->n ? cx->fd->level[p] : 0,
                          &sg, 0)) {
                    free(seen);
                    goto nomem;
                }
            }
            p = cx->bnext[p];
        } while (p >= 0 && p != (int32_t)p0 && guard++ < np);
    }
    free(seen);
    /* closed sea-level curves inside the domain */
    for (size_t k = 0; k < cx->c.n && st == FM_OK; k++) {
        if (cx->c.x[k].visited || cx->c.x[k].on_outline)
            continue;
        NEW_LOOP();
        int32_t j = (int32_t)k;
        size_t guard = 0;
        do {
            cx->c.x[j].visited = 1;
            if (cpush(&ls[nl - 1], cx->c.x[j].uv, 1, &level_seg, 1))
                goto nomem;
            j = cx->c.x[j].next;
        } while (j >= 0 && j != (int32_t)k && guard++ < cx->c.n);
        if (j != (int32_t)k)
            st = FM_ERR_TOPOLOGY;
    }
#undef NEW_LOOP
    *out = ls;
    *nout = nl;
    return st;
nomem:
    *out = ls;
    *nout = nl;
    return FM_ERR_NOMEM;
}

fm_status domain_clip(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                      const remesh_domain *in, double level, double h, remesh_domain *out,
                      int *cut, fm_error *err, const char *name)
{
    memset(out, 0, sizeof *out);
    *cut = 0;
    /* Nothing above on the outline: nothing to cut (a fault's top is on
     * its outline; an island above sea level inside would be clamped). */
    int any = 0;
    for (size_t l = 0; l < in->n && !any; l++)
        for (size_t i = 0; i < in->loops[l].n && !any; i++)
            any = surface_z(s, in->loops[l].uv + 2 * i, level, NULL) > 0;
    if (!any) {
        for (size_t l = 0; l < in->n; l++) {
            dom_loop *D = domain_add_loop(out);
            if (!D)
                goto nomem0;
            for (size_t i = 0; i < in->loops[l].n; i++)
                if (loop_push(D, in->loops[l].uv + 2 * i, in->loops[l].level[i], &in->loops[l].seg[i]))
                    goto nomem0;
        }
        return FM_OK;
    }
    *cut = 1;
    flat_domain fd = {0};
    fm_cdt *cdt = NULL;
    fm_status st = domain_triangulate(s, loops, level, in, h, 0, &fd, &cdt, err, name);
    if (st != FM_OK)
        return st;
    size_t np = fm_cdt_npoints(cdt), nt = fm_cdt_ntriangles(cdt), ne = fm_cdt_nedges(cdt);
    const double *uv = fm_cdt_points(cdt);
    const int32_t *tri = fm_cdt_triangles(cdt), *edges = fm_cdt_edges(cdt),
                  *eid = fm_cdt_edge_ids(cdt);
    clip_ctx cx = {s, level, h, &fd, uv, NULL, NULL, NULL, {0}};
    unsigned char *above = malloc(np + 1);
    cx.bnext = malloc((np + 1) * sizeof *cx.bnext);
    cx.bseg = malloc((np + 1) * sizeof *cx.bseg);
    cloop *ls = NULL;
    size_t nl = 0;
    if (!above || !cx.bnext || !cx.bseg) {
        st = FM_ERR_NOMEM;
        goto done;
    }
    cx.above = above;
    for (size_t i = 0; i < np; i++) {
        above[i] = surface_z(s, uv + 2 * i, level, NULL) > 0;
        cx.bnext[i] = cx.bseg[i] = -1;
    }
    for (size_t k = 0; k < ne; k++) {
        cx.bnext[edges[2 * k]] = edges[2 * k + 1];
        cx.bseg[edges[2 * k]] = eid[k];
    }
    st = build_contour(s, level, uv, above, tri, nt, &cx.c);
    if (st != FM_OK)
        goto done;
    for (size_t k = 0; k < cx.c.n; k++) {
        xing *x = &cx.c.x[k];
        if (cx.bnext[x->a] == x->b || cx.bnext[x->b] == x->a) {
            x->on_outline = 1;
            x->seg = cx.bnext[x->a] == x->b ? cx.bseg[x->a] : cx.bseg[x->b];
        }
    }
    st = clip_loops(&cx, cdt, &ls, &nl);
    if (st == FM_OK) {
        st = thin(&cx, ls, nl);
    }
    if (st == FM_OK)
        st = to_domain(ls, nl, out);
done:
    if (st == FM_ERR_TOPOLOGY)
        fm_error_set(err, st, name, 0, "the sea-level curve does not close up within the outline");
    else if (st != FM_OK)
        fm_error_set(err, st, name, 0, "out of memory");
    if (st != FM_OK)
        domain_free(out);
    for (size_t l = 0; l < nl; l++)
        free(ls[l].v);
    free(ls);
    free(cx.c.x);
    free(cx.c.keys);
    free(above);
    free(cx.bnext);
    free(cx.bseg);
    fm_cdt_destroy(cdt);
    flat_free(&fd);
    return st;
nomem0:
    domain_free(out);
    return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
}
