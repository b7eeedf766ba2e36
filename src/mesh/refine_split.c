/* Splitting sub-segments: where (concentric shells next to small-angle
 * apices, the caller's curve), and checked so that a point from the
 * callback can never break the triangulation. */
#include <math.h>
#include <stdlib.h>

#include "cdt_internal.h"

int cdt_frozen(const cdt_refiner *r, int32_t k)
{
    /* Hull pieces of a graph CDT: no curve is known there. */
    if ((size_t)k >= r->t->nuser)
        return 1;
    int32_t id = r->t->sid[k];
    return r->o->frozen_ids && id >= 0 && (size_t)id < r->o->nfrozen && r->o->frozen_ids[id];
}

int cdt_segq_push(cdt_refiner *r, int32_t a, int32_t b)
{
    if (r->nsegq == r->segqcap) {
        size_t c = r->segqcap ? 2 * r->segqcap : 64;
        cdt_seg_item *n = realloc(r->segq, c * sizeof *n);
        if (!n)
            return -1;
        r->segq = n;
        r->segqcap = c;
    }
    r->segq[r->nsegq].a = a;
    r->segq[r->nsegq].b = b;
    r->nsegq++;
    return 0;
}

static int is_input(const struct fm_cdt *t, int32_t v)
{
    return v >= CDT_NSUPER && (size_t)(v - CDT_NSUPER) < t->ninput;
}

static int32_t other_end(const struct fm_cdt *t, int32_t k, int32_t v)
{
    return t->seg[2 * k] == v ? t->seg[2 * k + 1] : t->seg[2 * k];
}

/* Cosine of the angle at v between segments k1 and k2, in the metric at v. */
static double seg_cos(cdt_refiner *r, int32_t v, int32_t k1, int32_t k2)
{
    const struct fm_cdt *t = r->t;
    double m[3];
    if (cdt_metric(r, cdt_p(t, v), m))
        return -1;
    const double *o = cdt_p(t, v), *p = cdt_p(t, other_end(t, k1, v)),
                 *q = cdt_p(t, other_end(t, k2, v));
    double ax = p[0] - o[0], ay = p[1] - o[1], bx = q[0] - o[0], by = q[1] - o[1];
    double ab = m[0] * ax * bx + m[1] * (ax * by + ay * bx) + m[2] * ay * by;
    double aa = m[0] * ax * ax + 2 * m[1] * ax * ay + m[2] * ay * ay;
    double bb = m[0] * bx * bx + 2 * m[1] * bx * by + m[2] * by * by;
    return ab / sqrt(aa * bb);
}

fm_status cdt_apex_init(cdt_refiner *r)
{
    struct fm_cdt *t = r->t;
    size_t n = t->ninput;
    free(t->apex);
    t->apex = calloc(n ? n : 1, 1);
    r->adj_off = calloc(n + 1, sizeof *r->adj_off);
    r->adj = malloc((t->nseg ? 2 * t->nseg : 1) * sizeof *r->adj);
    if (!t->apex || !r->adj_off || !r->adj)
        return fm_error_set(r->err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (size_t k = 0; k < t->nseg; k++)
        for (int s = 0; s < 2; s++)
            r->adj_off[t->seg[2 * k + s] - CDT_NSUPER + 1]++;
    for (size_t i = 0; i < n; i++)
        r->adj_off[i + 1] += r->adj_off[i];
    int32_t *fill = calloc(n ? n : 1, sizeof *fill);
    if (!fill)
        return fm_error_set(r->err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (size_t k = 0; k < t->nseg; k++)
        for (int s = 0; s < 2; s++) {
            int32_t i = t->seg[2 * k + s] - CDT_NSUPER;
            r->adj[r->adj_off[i] + fill[i]++] = (int32_t)k;
        }
    free(fill);
    /* Below 60 degrees Ruppert's splits can chase each other round the
     * apex; above, the plain algorithm terminates. */
    for (size_t i = 0; i < n; i++)
        for (int32_t x = r->adj_off[i]; x < r->adj_off[i + 1] && !t->apex[i]; x++)
            for (int32_t y = x + 1; y < r->adj_off[i + 1]; y++)
                if (seg_cos(r, (int32_t)i + CDT_NSUPER, r->adj[x], r->adj[y]) > 0.5) {
                    t->apex[i] = 1;
                    break;
                }
    return r->st;
}

/* Apices p sits next to, with the segment leading there. */
static int apex_candidates(const cdt_refiner *r, int32_t p, int32_t *segs, int32_t *apx, int cap)
{
    const struct fm_cdt *t = r->t;
    int n = 0;
    if (is_input(t, p)) {
        int32_t i = p - CDT_NSUPER;
        for (int32_t x = r->adj_off[i]; x < r->adj_off[i + 1] && n < cap; x++) {
            int32_t k = r->adj[x], o = other_end(t, k, p);
            if (t->apex[o - CDT_NSUPER]) {
                segs[n] = k;
                apx[n++] = o;
            }
        }
    } else if (t->pseg[p] >= 0) {
        int32_t k = t->pseg[p];
        for (int s = 0; s < 2 && n < cap; s++)
            if (t->apex[t->seg[2 * k + s] - CDT_NSUPER]) {
                segs[n] = k;
                apx[n++] = t->seg[2 * k + s];
            }
    }
    return n;
}

int cdt_apex_exempt(cdt_refiner *r, int32_t p, int32_t q)
{
    if (r->t->pseg[p] < 0 || r->t->pseg[q] < 0)
        return 0;
    int32_t sp[8], ap[8], sq[8], aq[8];
    int np = apex_candidates(r, p, sp, ap, 8), nq = apex_candidates(r, q, sq, aq, 8);
    for (int i = 0; i < np; i++)
        for (int j = 0; j < nq; j++)
            if (ap[i] == aq[j] && sp[i] != sq[j] && seg_cos(r, ap[i], sp[i], sq[j]) > 0.5)
                return 1;
    return 0;
}

/* Fraction of the way from a: the midpoint, or next to an apex the power
 * of two (of metric length, measured at the apex so that every segment
 * there uses the same shells) nearest to the middle. */
static double split_fraction(cdt_refiner *r, int32_t a, int32_t b)
{
    const struct fm_cdt *t = r->t;
    int aa = is_input(t, a) && t->apex[a - CDT_NSUPER];
    int ba = is_input(t, b) && t->apex[b - CDT_NSUPER];
    if (aa == ba)
        return 0.5;
    int32_t v = aa ? a : b;
    double m[3];
    if (cdt_metric(r, cdt_p(t, v), m))
        return 0.5;
    double dx = cdt_p(t, b)[0] - cdt_p(t, a)[0], dy = cdt_p(t, b)[1] - cdt_p(t, a)[1];
    double L = sqrt(m[0] * dx * dx + 2 * m[1] * dx * dy + m[2] * dy * dy);
    if (!(L > 0) || !isfinite(L))
        return 0.5;
    double d = ldexp(1.0, (int)lround(log2(0.5 * L)));
    double f = d / L;
    if (!(f > 0.25 && f < 0.75))
        return 0.5;
    return aa ? f : 1 - f;
}

int cdt_split_subsegment(cdt_refiner *r, int32_t a, int32_t b)
{
    struct fm_cdt *t = r->t;
    int32_t e = cdt_find_edge(t, a, b);
    if (e < 0 || t->tc[e] < 0 || t->tn[e] < 0)
        return 0;
    int32_t k = t->tc[e];
    if (cdt_frozen(r, k))
        return 0;
    const double *pa = cdt_p(t, a), *pb = cdt_p(t, b);
    /* Nothing representable lies strictly between. */
    if (fabs(pb[0] - pa[0]) + fabs(pb[1] - pa[1]) <=
        1e-13 * (fabs(pa[0]) + fabs(pa[1]) + fabs(pb[0]) + fabs(pb[1]))) {
        r->t->stats.rejected++;
        return 0;
    }
    /* Pieces below min_length / 2 would only feed a cascade. */
    if (r->min_len > 0) {
        double mm[3], dx = pb[0] - pa[0], dy = pb[1] - pa[1];
        double mid0[2] = {0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])};
        if (cdt_metric(r, mid0, mm))
            return 0;
        if (mm[0] * dx * dx + 2 * mm[1] * dx * dy + mm[2] * dy * dy < r->min_len * r->min_len) {
            r->t->stats.rejected++;
            return 0;
        }
    }
    double f = split_fraction(r, a, b);
    double cand[3][2];
    int nc = 0;
    if (r->o->split) {
        double ca[2] = {pa[0], pa[1]}, cb[2] = {pb[0], pb[1]};
        r->o->split(r->o->split_user, t->sid[k], ca, cb, f, cand[nc]);
        if (isfinite(cand[nc][0]) && isfinite(cand[nc][1]))
            nc++;
    }
    cand[nc][0] = pa[0] + f * (pb[0] - pa[0]);
    cand[nc][1] = pa[1] + f * (pb[1] - pa[1]);
    nc++;
    if (f != 0.5) {
        cand[nc][0] = 0.5 * (pa[0] + pb[0]);
        cand[nc][1] = 0.5 * (pa[1] + pb[1]);
        nc++;
    }
    int32_t seeds[2] = {e / 3, t->tn[e] / 3}, bad;
    int nomem = 0;
    double mid[2] = {0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])}, m[3];
    if (cdt_metric(r, mid, m))
        return 0;
    cdt_use_metric(r, m);
    for (int c = 0; c < nc && !nomem; c++) {
        cdt_cavity_result cr = cdt_cavity(t, cand[c], seeds, 2, e, &bad);
        if (cr == CDT_CAVITY_NOMEM) {
            nomem = 1;
            break;
        }
        if (cr != CDT_CAVITY_OK)
            continue;
        int32_t v = cdt_add_point(t, cand[c], k);
        size_t from = t->npairs;
        /* The forced triangles need not have held the point in their
         * circumcircles: flip the cavity's rim back to Delaunay. */
        for (size_t i = 0; i < t->nbnd && v >= 0; i++)
            if (cdt_push_pair(t, cdt_org(t, t->bnde[i]), cdt_dst(t, t->bnde[i])))
                v = -1;
        if (v < 0 || cdt_commit(t, v, e, k)) {
            if (v >= 0)
                t->np--; /* the point was never linked */
            t->npairs = from;
            nomem = 1;
            break;
        }
        cdt_legalize(t, from);
        t->stats.inserted_segment++;
        return 1;
    }
    if (nomem && r->st == FM_OK)
        r->st = fm_error_set(r->err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    t->stats.rejected++;
    return 0;
}
