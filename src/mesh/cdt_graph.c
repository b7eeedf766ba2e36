/* The arrangement of a graph CDT (fm_cdt_create_graph): the convex hull
 * made exact, segments cut into pieces, the faces, and the selection of
 * the domain among them.
 *
 * The convex hull's edges are recovered like segments (a finite super
 * triangle can leave a nearly flat stretch of the hull to triangles with a
 * super vertex) and held as hull pieces, so that "inside the hull" is the
 * triangles without a super vertex and every face is closed by constrained
 * edges: refinement then never leaves a face, and treats hull pieces as
 * frozen (no curve is known there to put points on).
 *
 * Pieces are the triangulation edges of the input segments as recovered:
 * an input segment through points lying on it has several. Each piece has
 * one face on either side, which is what makes the selection a per-piece
 * decision, and small angles at a point where a chain ends on a segment are
 * seen by refinement (its apex test looks at the segments ending at a
 * point). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cdt_internal.h"

void cdt_graph_free(cdt_graph *g)
{
    if (!g)
        return;
    void *arrs[] = {g->in_sid, g->pc,    g->pc_orig, g->first, g->left,
                    g->right,  g->area,  g->point,   g->open,  g->tface, g->tc0};
    for (size_t i = 0; i < sizeof arrs / sizeof arrs[0]; i++)
        free(arrs[i]);
    free(g);
}

int32_t cdt_next_on_segment(const struct fm_cdt *t, int32_t v, int32_t prev, int32_t k)
{
    int32_t t0 = t->vtri[v], tri = t0;
    if (t0 < 0)
        return -1;
    /* Round v: each triangle's edge leaving v, then across the edge coming
     * in; the star of a real point is closed. */
    do {
        const int32_t *tv = t->tv + 3 * (size_t)tri;
        int ia = tv[0] == v ? 0 : tv[1] == v ? 1 : 2;
        int32_t w = tv[(ia + 1) % 3];
        if (t->tc[3 * tri + (ia + 2) % 3] == k && w != prev)
            return w;
        int32_t n = t->tn[3 * tri + (ia + 1) % 3];
        if (n < 0)
            return -1;
        tri = n / 3;
    } while (tri != t0);
    return -1;
}

typedef struct xy_key {
    double x, y;
    int32_t v;
} xy_key;

static int by_xy(const void *a, const void *b)
{
    const xy_key *p = a, *q = b;
    if (p->x != q->x)
        return p->x < q->x ? -1 : 1;
    if (p->y != q->y)
        return p->y < q->y ? -1 : 1;
    return (p->v > q->v) - (p->v < q->v);
}

/* Convex hull of the input points, counter-clockwise without collinear
 * points (Andrew's monotone chain, exact orient2d); internal indices into
 * hull (room for ninput + 1). Returns its size, 0 when the points are
 * collinear (or fewer than 3), -1 out of memory. */
static long convex_hull(const struct fm_cdt *t, int32_t *hull)
{
    size_t n = t->ninput;
    if (n < 3)
        return 0;
    xy_key *k = malloc(n * sizeof *k);
    if (!k)
        return -1;
    for (size_t i = 0; i < n; i++) {
        const double *p = cdt_p(t, (int32_t)(i + CDT_NSUPER));
        k[i] = (xy_key){p[0], p[1], (int32_t)(i + CDT_NSUPER)};
    }
    qsort(k, n, sizeof *k, by_xy);
    size_t h = 0;
    for (size_t i = 0; i < n; i++) {
        while (h >= 2 &&
               fm_orient2d(cdt_p(t, hull[h - 2]), cdt_p(t, hull[h - 1]), cdt_p(t, k[i].v)) <= 0)
            h--;
        hull[h++] = k[i].v;
    }
    for (size_t i = n - 1, lo = h + 1; i-- > 0;) {
        while (h >= lo &&
               fm_orient2d(cdt_p(t, hull[h - 2]), cdt_p(t, hull[h - 1]), cdt_p(t, k[i].v)) <= 0)
            h--;
        hull[h++] = k[i].v;
    }
    free(k);
    h--; /* the first point closed the chain */
    return h >= 3 ? (long)h : 0;
}

static fm_status recover_hull(struct fm_cdt *t, fm_error *err)
{
    int32_t *hull = malloc((t->ninput + 1) * sizeof *hull);
    if (!hull)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    long h = convex_hull(t, hull);
    if (h < 0) {
        free(hull);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    fm_status st = FM_OK;
    if (h > 0) {
        /* Recovered as segments nseg .. nseg + h - 1 for now; the pieces
         * renumber every constraint afterwards. */
        int32_t *seg = realloc(t->seg, 2 * (t->nseg + (size_t)h) * sizeof *seg);
        if (!seg)
            st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        else
            t->seg = seg;
        for (long i = 0; i < h && st == FM_OK; i++) {
            size_t k = t->nseg + (size_t)i;
            t->seg[2 * k] = hull[i];
            t->seg[2 * k + 1] = hull[(i + 1) % h];
            st = cdt_recover_segment(t, (int32_t)k, 1, err);
        }
    }
    free(hull);
    return st;
}

typedef struct piece_rec {
    int32_t a, b, e;
} piece_rec;

static int by_piece(const void *x, const void *y)
{
    const piece_rec *p = x, *q = y;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    return (p->b > q->b) - (p->b < q->b);
}

static int add_piece(cdt_graph *g, size_t *cap, int32_t a, int32_t b, int32_t orig)
{
    if (g->npc == *cap) {
        size_t c = *cap ? 2 * *cap : 64;
        int32_t *pc = realloc(g->pc, 2 * c * sizeof *pc);
        if (!pc)
            return -1;
        g->pc = pc;
        int32_t *po = realloc(g->pc_orig, c * sizeof *po);
        if (!po)
            return -1;
        g->pc_orig = po;
        *cap = c;
    }
    g->pc[2 * g->npc] = a;
    g->pc[2 * g->npc + 1] = b;
    g->pc_orig[g->npc] = orig;
    g->npc++;
    return 0;
}

/* Every constraint becomes its piece: user pieces walking each input
 * segment from its first point, then hull pieces (the hull's edges no
 * segment holds) in point order. */
static fm_status make_pieces(struct fm_cdt *t, cdt_graph *g, fm_error *err)
{
    size_t nh = 3 * t->nt, cap = 0;
    int32_t *tcn = malloc((nh ? nh : 1) * sizeof *tcn);
    g->first = malloc((g->nin ? g->nin : 1) * sizeof *g->first);
    if (!tcn || !g->first) {
        free(tcn);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (size_t i = 0; i < nh; i++)
        tcn[i] = -1;
    fm_status st = FM_OK;
    for (size_t k = 0; k < g->nin && st == FM_OK; k++) {
        g->first[k] = (int32_t)g->npc;
        int32_t v = t->seg[2 * k], b = t->seg[2 * k + 1], prev = -1;
        for (size_t steps = 0; v != b && st == FM_OK; steps++) {
            int32_t w = cdt_next_on_segment(t, v, prev, (int32_t)k);
            int32_t e = w >= 0 ? cdt_find_edge(t, v, w) : -1;
            if (e < 0 || steps > t->ninput)
                st = fm_error_set(err, FM_ERR_NUMERIC, NULL, 0,
                                  "segment %zu: its recovered edges do not join up", k);
            else if (add_piece(g, &cap, v, w, (int32_t)k))
                st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
            else {
                tcn[e] = (int32_t)g->npc - 1;
                tcn[t->tn[e]] = (int32_t)g->npc - 1;
                prev = v;
                v = w;
            }
        }
    }
    g->nuser = g->npc;
    piece_rec *hp = NULL;
    size_t nhp = 0;
    if (st == FM_OK) {
        for (size_t s = 0; s < t->nt; s++)
            if (t->region[s] != CDT_DEAD && !cdt_has_super(t, (int32_t)s))
                for (int i = 0; i < 3; i++) {
                    int32_t e = (int32_t)(3 * s) + i, f = t->tn[e];
                    nhp += f >= 0 && cdt_has_super(t, f / 3) && tcn[e] < 0;
                }
        hp = malloc((nhp ? nhp : 1) * sizeof *hp);
        if (!hp)
            st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    if (st == FM_OK) {
        size_t m = 0;
        for (size_t s = 0; s < t->nt; s++)
            if (t->region[s] != CDT_DEAD && !cdt_has_super(t, (int32_t)s))
                for (int i = 0; i < 3; i++) {
                    int32_t e = (int32_t)(3 * s) + i, f = t->tn[e];
                    if (f >= 0 && cdt_has_super(t, f / 3) && tcn[e] < 0)
                        hp[m++] = (piece_rec){cdt_org(t, e), cdt_dst(t, e), e};
                }
        qsort(hp, m, sizeof *hp, by_piece);
        for (size_t i = 0; i < m && st == FM_OK; i++) {
            if (add_piece(g, &cap, hp[i].a, hp[i].b, -1)) {
                st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
                break;
            }
            tcn[hp[i].e] = (int32_t)g->npc - 1;
            tcn[t->tn[hp[i].e]] = (int32_t)g->npc - 1;
        }
    }
    free(hp);
    if (st == FM_OK)
        memcpy(t->tc, tcn, nh * sizeof *tcn);
    free(tcn);
    return st;
}

typedef struct face_key {
    int32_t a, b, comp;
} face_key;

static int by_face_key(const void *x, const void *y)
{
    const face_key *p = x, *q = y;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    return (p->b > q->b) - (p->b < q->b);
}

/* Faces: triangles inside the hull joined across unconstrained edges,
 * numbered by their smallest directed boundary piece (the pair of point
 * indices with the face on its left, lexicographic): a key that depends on
 * the arrangement and the point numbering only, not on how the
 * triangulation came out. */
static fm_status make_faces(struct fm_cdt *t, cdt_graph *g, fm_error *err)
{
    size_t nt = t->nt;
    int32_t *comp = malloc((nt ? nt : 1) * sizeof *comp);
    int32_t *queue = malloc((nt ? nt : 1) * sizeof *queue);
    face_key *key = malloc((nt ? nt : 1) * sizeof *key);
    g->tface = malloc((nt ? nt : 1) * sizeof *g->tface);
    if (!comp || !queue || !key || !g->tface) {
        free(comp);
        free(queue);
        free(key);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    size_t nc = 0;
    for (size_t s = 0; s < nt; s++)
        comp[s] = -1;
    for (size_t s = 0; s < nt; s++) {
        if (t->region[s] != 1 || comp[s] >= 0)
            continue;
        size_t head = 0, tail = 0;
        comp[s] = (int32_t)nc;
        queue[tail++] = (int32_t)s;
        key[nc] = (face_key){INT32_MAX, INT32_MAX, (int32_t)nc};
        while (head < tail) {
            int32_t tri = queue[head++];
            for (int i = 0; i < 3; i++) {
                int32_t e = 3 * tri + i, f = t->tn[e];
                if (t->tc[e] >= 0) {
                    face_key k = {cdt_org(t, e) - CDT_NSUPER, cdt_dst(t, e) - CDT_NSUPER, 0};
                    if (by_face_key(&k, &key[nc]) < 0) {
                        key[nc].a = k.a;
                        key[nc].b = k.b;
                    }
                    continue;
                }
                if (f < 0 || t->region[f / 3] != 1 || comp[f / 3] >= 0)
                    continue;
                comp[f / 3] = (int32_t)nc;
                queue[tail++] = f / 3;
            }
        }
        nc++;
    }
    qsort(key, nc, sizeof *key, by_face_key);
    /* queue becomes the face of each component */
    for (size_t f = 0; f < nc; f++)
        queue[key[f].comp] = (int32_t)f;
    g->nfaces = nc;
    g->area = calloc(nc ? nc : 1, sizeof *g->area);
    g->point = calloc(nc ? 2 * nc : 1, sizeof *g->point);
    double *best = malloc((nc ? nc : 1) * sizeof *best);
    fm_status st = FM_OK;
    if (!g->area || !g->point || !best)
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (size_t f = 0; f < nc && st == FM_OK; f++)
        best[f] = -1;
    for (size_t s = 0; s < nt && st == FM_OK; s++) {
        g->tface[s] = comp[s] >= 0 ? queue[comp[s]] : -1;
        if (comp[s] < 0)
            continue;
        int32_t f = g->tface[s];
        const int32_t *v = t->tv + 3 * s;
        const double *a = cdt_p(t, v[0]), *b = cdt_p(t, v[1]), *c = cdt_p(t, v[2]);
        double ar = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        g->area[f] += ar;
        /* The incentre of the triangle with the largest incircle: the
         * point farthest from the face's edges that comes cheaply, so a
         * caller's point-in-polygon test on it is not a close call. */
        double la = hypot(c[0] - b[0], c[1] - b[1]), lb = hypot(a[0] - c[0], a[1] - c[1]),
               lc = hypot(b[0] - a[0], b[1] - a[1]), per = la + lb + lc;
        double r = per > 0 ? 2 * ar / per : 0;
        if (r > best[f]) {
            best[f] = r;
            for (int i = 0; i < 2; i++)
                g->point[2 * f + i] = (la * a[i] + lb * b[i] + lc * c[i]) / per;
        }
    }
    free(best);
    free(comp);
    free(queue);
    free(key);
    if (st != FM_OK)
        return st;
    g->left = malloc((g->npc ? g->npc : 1) * sizeof *g->left);
    g->right = malloc((g->npc ? g->npc : 1) * sizeof *g->right);
    g->open = calloc(nc ? nc : 1, 1);
    if (!g->left || !g->right || !g->open)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (size_t p = 0; p < g->npc; p++) {
        int32_t a = g->pc[2 * p], b = g->pc[2 * p + 1];
        int32_t e = cdt_find_edge(t, a, b), f = cdt_find_edge(t, b, a);
        g->left[p] = e >= 0 ? g->tface[e / 3] : -1;
        g->right[p] = f >= 0 ? g->tface[f / 3] : -1;
        for (int side = 0; side < 2 && p >= g->nuser; side++) {
            int32_t fc = side ? g->right[p] : g->left[p];
            if (fc >= 0)
                g->open[fc] = 1;
        }
    }
    return FM_OK;
}

/* The domain: the faces kept (keep NULL: all). Pieces with a kept face on
 * either side become the segments, numbered in piece order (so user
 * pieces, in input order, come before hull pieces); the others are no
 * constraints any more. Input points take the lowest segment they end. */
static fm_status apply_selection(struct fm_cdt *t, const unsigned char *keep, fm_error *err)
{
    cdt_graph *g = t->graph;
    int32_t *map = malloc((g->npc ? g->npc : 1) * sizeof *map);
    size_t n = 0, nuser = 0;
    if (!map)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (size_t p = 0; p < g->npc; p++) {
        int32_t l = g->left[p], r = g->right[p];
        int live = (l >= 0 && (!keep || keep[l])) || (r >= 0 && (!keep || keep[r]));
        map[p] = live ? (int32_t)n++ : -1;
        nuser += live && p < g->nuser;
    }
    int32_t *seg = malloc((n ? 2 * n : 1) * sizeof *seg);
    int32_t *sid = malloc((n ? n : 1) * sizeof *sid);
    int32_t *sorig = malloc((n ? n : 1) * sizeof *sorig);
    if (!seg || !sid || !sorig) {
        free(map);
        free(seg);
        free(sid);
        free(sorig);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (size_t p = 0; p < g->npc; p++) {
        int32_t j = map[p];
        if (j < 0)
            continue;
        seg[2 * j] = g->pc[2 * p];
        seg[2 * j + 1] = g->pc[2 * p + 1];
        int32_t o = g->pc_orig[p];
        sid[j] = o >= 0 ? g->in_sid[o] : -1;
        sorig[j] = o >= 0 ? o : (int32_t)g->nin;
    }
    free(t->seg);
    free(t->sid);
    free(t->sorig);
    t->seg = seg;
    t->sid = sid;
    t->sorig = sorig;
    t->nseg = n;
    t->nuser = nuser;
    for (size_t s = 0; s < g->nt0; s++) {
        if (t->region[s] == CDT_DEAD)
            continue;
        int32_t f = g->tface[s];
        t->region[s] = f >= 0 && (!keep || keep[f]) ? 1 : 0;
        for (int i = 0; i < 3; i++) {
            int32_t c = g->tc0[3 * s + i];
            t->tc[3 * s + i] = c >= 0 ? map[c] : -1;
        }
    }
    free(map);
    for (size_t i = 0; i < t->ninput; i++)
        t->pseg[i + CDT_NSUPER] = -1;
    for (size_t s = 0; s < g->nt0; s++) {
        if (t->region[s] == CDT_DEAD)
            continue;
        for (int i = 0; i < 3; i++) {
            int32_t e = (int32_t)(3 * s) + i, k = t->tc[e], v = cdt_org(t, e);
            if (k >= 0 && v >= CDT_NSUPER && (t->pseg[v] < 0 || k < t->pseg[v]))
                t->pseg[v] = k;
        }
    }
    return FM_OK;
}

fm_status cdt_graph_build(struct fm_cdt *t, fm_error *err)
{
    cdt_graph *g = calloc(1, sizeof *g);
    if (!g)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    t->graph = g;
    g->nin = t->nseg;
    g->in_sid = malloc((g->nin ? g->nin : 1) * sizeof *g->in_sid);
    if (!g->in_sid)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    if (g->nin)
        memcpy(g->in_sid, t->sid, g->nin * sizeof *g->in_sid);
    fm_status st = recover_hull(t, err);
    if (st == FM_OK)
        st = make_pieces(t, g, err);
    if (st != FM_OK)
        return st;
    for (size_t s = 0; s < t->nt; s++)
        if (t->region[s] != CDT_DEAD)
            t->region[s] = cdt_has_super(t, (int32_t)s) ? 0 : 1;
    st = make_faces(t, g, err);
    if (st != FM_OK)
        return st;
    g->nt0 = t->nt;
    g->tc0 = malloc((t->nt ? 3 * t->nt : 1) * sizeof *g->tc0);
    if (!g->tc0)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    memcpy(g->tc0, t->tc, 3 * t->nt * sizeof *g->tc0);
    return apply_selection(t, NULL, err);
}

fm_status fm_cdt_select_faces(fm_cdt *t, const unsigned char *keep, fm_error *err)
{
    if (!t || (!keep && t->graph && t->graph->nfaces))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "fm_cdt_select_faces: NULL argument");
    if (!t->graph)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "fm_cdt_select_faces: only a CDT from fm_cdt_create_graph has faces");
    if (!t->graph->nt0)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "fm_cdt_select_faces: faces are selected before refinement");
    fm_status st = apply_selection(t, keep, err);
    if (st == FM_OK && cdt_build_output(t))
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    return st;
}

void cdt_graph_refined(struct fm_cdt *t)
{
    cdt_graph *g = t->graph;
    if (!g)
        return;
    free(g->tface);
    free(g->tc0);
    g->tface = g->tc0 = NULL;
    g->nt0 = 0;
}

size_t fm_cdt_nfaces(const fm_cdt *t) { return t->graph ? t->graph->nfaces : 0; }

void fm_cdt_segment_faces(const fm_cdt *t, size_t k, int32_t *left, int32_t *right)
{
    const cdt_graph *g = t->graph;
    int32_t l = -1, r = -1;
    if (g && k < g->nin) {
        l = g->left[g->first[k]];
        r = g->right[g->first[k]];
    }
    if (left)
        *left = l;
    if (right)
        *right = r;
}

const double *fm_cdt_face_areas(const fm_cdt *t) { return t->graph ? t->graph->area : NULL; }
const double *fm_cdt_face_points(const fm_cdt *t) { return t->graph ? t->graph->point : NULL; }
const unsigned char *fm_cdt_face_open(const fm_cdt *t) { return t->graph ? t->graph->open : NULL; }
