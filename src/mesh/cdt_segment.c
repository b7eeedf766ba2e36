/* Segment recovery by flips (after Sloan 1993, "A fast algorithm for
 * generating constrained Delaunay triangulations"): the edges a segment
 * crosses are flipped, in queue order, until none crosses; the edges made
 * on the way are then flipped back to Delaunay (Lawson). A point lying
 * exactly on the segment (exact orient2d) splits it there, so collinear
 * input never produces a zero-area triangle. */
#include <stdlib.h>
#include <string.h>

#include "cdt_internal.h"

typedef struct pair_queue {
    cdt_pair *v;
    size_t head, n, cap;
} pair_queue;

static int pq_push(pair_queue *q, int32_t a, int32_t b)
{
    if (q->n == q->cap) {
        if (q->head > q->n / 2) {
            memmove(q->v, q->v + q->head, (q->n - q->head) * sizeof *q->v);
            q->n -= q->head;
            q->head = 0;
        } else {
            size_t c = q->cap ? 2 * q->cap : 32;
            cdt_pair *nv = realloc(q->v, c * sizeof *nv);
            if (!nv)
                return -1;
            q->v = nv;
            q->cap = c;
        }
    }
    q->v[q->n].a = a;
    q->v[q->n].b = b;
    q->n++;
    return 0;
}

static fm_status mark(struct fm_cdt *t, int32_t e, int32_t k, int soft, fm_error *err)
{
    if (soft && t->tc[e] >= 0)
        return FM_OK;
    if (t->tc[e] >= 0 && t->tc[e] != k)
        return fm_error_set(err, FM_ERR_TOPOLOGY, NULL, 0,
                            "segments %d and %d overlap (between points %d and %d)", t->tc[e],
                            k, cdt_org(t, e) - CDT_NSUPER, cdt_dst(t, e) - CDT_NSUPER);
    t->tc[e] = k;
    if (t->tn[e] >= 0)
        t->tc[t->tn[e]] = k;
    return FM_OK;
}

static int ahead(const double *a, const double *b, const double *c)
{
    /* c is exactly on line ab here, so the sign of the dot product is never
     * close to a rounding decision. */
    return (c[0] - a[0]) * (b[0] - a[0]) + (c[1] - a[1]) * (b[1] - a[1]) > 0;
}

/* The triangle edge opposite a that ab crosses, or a vertex exactly on ab
 * next to a (*on). */
static int32_t first_crossing(const struct fm_cdt *t, int32_t a, int32_t b, int32_t *on)
{
    const double *pa = cdt_p(t, a), *pb = cdt_p(t, b);
    int32_t t0 = t->vtri[a], tri = t0;
    *on = -1;
    do {
        const int32_t *tv = t->tv + 3 * (size_t)tri;
        int ia = tv[0] == a ? 0 : tv[1] == a ? 1 : 2;
        int32_t v1 = tv[(ia + 1) % 3], v2 = tv[(ia + 2) % 3];
        int o1 = fm_orient2d(pa, cdt_p(t, v1), pb), o2 = fm_orient2d(pa, cdt_p(t, v2), pb);
        if (o1 == 0 && ahead(pa, pb, cdt_p(t, v1))) {
            *on = v1;
            return -1;
        }
        if (o2 == 0 && ahead(pa, pb, cdt_p(t, v2))) {
            *on = v2;
            return -1;
        }
        if (o1 > 0 && o2 < 0)
            return 3 * tri + ia;
        int32_t n = t->tn[3 * tri + (ia + 1) % 3];
        if (n < 0)
            return -1;
        tri = n / 3;
    } while (tri != t0);
    return -1;
}

fm_status cdt_recover_segment(struct fm_cdt *t, int32_t k, int soft, fm_error *err)
{
    int32_t a = t->seg[2 * k], b = t->seg[2 * k + 1];
    pair_queue q = {0};
    fm_status st = FM_OK;
    while (a != b && st == FM_OK) {
        int32_t e = cdt_find_edge(t, a, b);
        if (e >= 0) {
            st = mark(t, e, k, soft, err);
            break;
        }
        int32_t on;
        int32_t cur = first_crossing(t, a, b, &on);
        if (on >= 0) {
            st = mark(t, cdt_find_edge(t, a, on), k, soft, err);
            if (!soft && t->pseg[on] < 0)
                t->pseg[on] = k;
            a = on;
            continue;
        }
        if (cur < 0) {
            st = fm_error_set(err, FM_ERR_NUMERIC, NULL, 0,
                              "segment %d: no triangle at point %d faces point %d", k,
                              a - CDT_NSUPER, b - CDT_NSUPER);
            break;
        }
        const double *pa = cdt_p(t, a), *pb = cdt_p(t, b);
        int32_t tgt = b;
        q.head = q.n = 0;
        for (;;) {
            if (t->tc[cur] >= 0) {
                st = fm_error_set(err, FM_ERR_TOPOLOGY, NULL, 0,
                                  "segments %d and %d cross (points %d-%d and %d-%d)", k,
                                  t->tc[cur], t->seg[2 * k] - CDT_NSUPER,
                                  t->seg[2 * k + 1] - CDT_NSUPER,
                                  t->seg[2 * t->tc[cur]] - CDT_NSUPER,
                                  t->seg[2 * t->tc[cur] + 1] - CDT_NSUPER);
                break;
            }
            if (pq_push(&q, cdt_org(t, cur), cdt_dst(t, cur))) {
                st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
                break;
            }
            int32_t f = t->tn[cur], w = t->tv[f];
            if (w == b)
                break;
            int o = fm_orient2d(pa, pb, cdt_p(t, w));
            if (o == 0) {
                tgt = w;
                break;
            }
            int32_t u = f / 3, j = f % 3;
            cur = o < 0 ? 3 * u + (j + 2) % 3 : 3 * u + (j + 1) % 3;
        }
        if (st != FM_OK)
            break;
        const double *pt = cdt_p(t, tgt);
        size_t legal_from = t->npairs;
        size_t initial = q.n, iter = 0, cap = 64 + 16 * initial * initial;
        while (q.head < q.n) {
            if (++iter > cap) {
                st = fm_error_set(err, FM_ERR_NUMERIC, NULL, 0,
                                  "segment %d: edge flips do not converge", k);
                break;
            }
            cdt_pair pr = q.v[q.head++];
            int32_t fe = cdt_find_edge(t, pr.a, pr.b);
            int32_t p = t->tv[fe], w = t->tv[t->tn[fe]];
            const double *pp = cdt_p(t, p), *pw = cdt_p(t, w);
            int convex = fm_orient2d(pp, cdt_p(t, pr.a), pw) > 0 &&
                         fm_orient2d(pw, cdt_p(t, pr.b), pp) > 0;
            int32_t na = pr.a, nb = pr.b;
            if (convex) {
                cdt_flip(t, fe);
                na = p;
                nb = w;
                int op = fm_orient2d(pa, pt, pp), ow = fm_orient2d(pa, pt, pw);
                if (!(op * ow < 0)) {
                    if (!((p == a && w == tgt) || (p == tgt && w == a)) &&
                        cdt_push_pair(t, p, w)) {
                        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
                        break;
                    }
                    continue;
                }
            }
            if (pq_push(&q, na, nb)) {
                st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
                break;
            }
        }
        if (st != FM_OK)
            break;
        e = cdt_find_edge(t, a, tgt);
        if (e < 0) {
            st = fm_error_set(err, FM_ERR_NUMERIC, NULL, 0, "segment %d was not recovered", k);
            break;
        }
        st = mark(t, e, k, soft, err);
        cdt_legalize(t, legal_from);
        if (!soft && tgt != b && t->pseg[tgt] < 0)
            t->pseg[tgt] = k;
        a = tgt;
    }
    free(q.v);
    return st;
}
