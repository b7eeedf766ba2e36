/* Shared curves into the domain: their ends put on the loops, connectors
 * from the open ends of curves a sheet ends at, and the whole flattened
 * into one planar graph of points and segments (remesh_internal.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "remesh_internal.h"

typedef struct seg_hit {
    size_t loop, i;   /* segment from node i to node i + 1 of the loop */
    double t;         /* fraction along it of the nearest point */
    double d;         /* 3D distance */
} seg_hit;

static void eval3(const fm_fit_surface *s, const double uv[2], double p[3])
{
    fm_fit_surface_eval(s, uv[0], uv[1], p, NULL, NULL);
}

static double dist3(const double *a, const double *b)
{
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* The loop segment nearest to P in 3D (chords between the nodes' surface
 * points: at most a size long, within a tenth of it of the curve). */
static seg_hit nearest_segment(const fm_fit_surface *s, const remesh_domain *dom, const double P[3])
{
    seg_hit best = {0, 0, 0, INFINITY};
    for (size_t l = 0; l < dom->n; l++) {
        const dom_loop *lp = &dom->loops[l];
        if (lp->n < 2)
            continue;
        double a[3], b[3];
        eval3(s, lp->uv, a);
        for (size_t i = 0; i < lp->n; i++) {
            eval3(s, lp->uv + 2 * ((i + 1) % lp->n), b);
            double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            double ap[3] = {P[0] - a[0], P[1] - a[1], P[2] - a[2]};
            double L2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
            double t = L2 > 0 ? (ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / L2 : 0;
            t = t < 0 ? 0 : t > 1 ? 1 : t;
            double f[3] = {a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]};
            double d = dist3(f, P);
            if (d < best.d) {
                best.loop = l;
                best.i = i;
                best.t = t;
                best.d = d;
            }
            memcpy(a, b, sizeof a);
        }
    }
    return best;
}

static int pt_eq(const double *a, const double *b) { return a[0] == b[0] && a[1] == b[1]; }

/* Loop nodes already taken by a shared node: never moved again. */
typedef struct taken {
    double *uv;
    size_t n, cap;
} taken;

static int is_taken(const taken *tk, const double *uv)
{
    for (size_t k = 0; k < tk->n; k++)
        if (tk->uv[2 * k] == uv[0] && tk->uv[2 * k + 1] == uv[1])
            return 1;
    return 0;
}

static int take(taken *tk, const double *uv)
{
    if (tk->n == tk->cap) {
        size_t cap = tk->cap ? 2 * tk->cap : 16;
        double *n = realloc(tk->uv, 2 * cap * sizeof *n);
        if (!n)
            return -1;
        tk->uv = n;
        tk->cap = cap;
    }
    tk->uv[2 * tk->n] = uv[0];
    tk->uv[2 * tk->n + 1] = uv[1];
    tk->n++;
    return 0;
}

/* Node i of loop l may move to uv: its two segments then cross no other
 * loop segment. */
static int movable(const remesh_domain *dom, size_t l, size_t i, const double uv[2])
{
    const dom_loop *lp = &dom->loops[l];
    size_t n = lp->n;
    const double *nb[2] = {lp->uv + 2 * ((i + n - 1) % n), lp->uv + 2 * ((i + 1) % n)};
    for (size_t m = 0; m < dom->n; m++) {
        const dom_loop *o = &dom->loops[m];
        for (size_t k = 0; k < o->n; k++) {
            size_t k1 = (k + 1) % o->n;
            if (m == l && (k == i || k1 == i))
                continue;
            const double *a = o->uv + 2 * k, *b = o->uv + 2 * k1;
            for (int e = 0; e < 2; e++) {
                if (a == nb[e] || b == nb[e])
                    continue;
                if (segments_cross(uv, nb[e], a, b))
                    return 0;
            }
        }
    }
    return 1;
}

/* Splits segment i of loop lp at fraction t (its parameter on a trimming
 * piece) with the node c; the new node is on sea level when the segment is
 * the sea-level curve or c evaluates to it. Returns -1 when out of memory. */
static int split_segment(const fm_fit_surface *s, dom_loop *lp, size_t i, double t,
                         const double c[2], double level)
{
    dom_seg s1 = lp->seg[i], s2 = lp->seg[i];
    if (s1.kind == SEG_TRIM) {
        double tm = s1.ta + t * (s1.tb - s1.ta);
        s1.tb = tm;
        s2.ta = tm;
    }
    double C[3];
    eval3(s, c, C);
    int lev = s1.kind == SEG_LEVEL || fabs(C[2] - level) < 1e-6;
    lp->seg[i] = s1;
    return loop_insert(lp, i + 1, c, lev, &s2);
}

/* Puts uv on segment h of the loops: moves the nearer end node there when
 * it is within tol (and free), else inserts a node. at receives the node's
 * final uv. */
static int put_on_loop(const fm_fit_surface *s, remesh_domain *dom, const seg_hit *h,
                       const double uv[2], double level, double tol, int move, taken *tk,
                       double at[2])
{
    dom_loop *lp = &dom->loops[h->loop];
    size_t ia = h->i, ib = (h->i + 1) % lp->n;
    double P[3], A[3], B[3];
    eval3(s, uv, P);
    eval3(s, lp->uv + 2 * ia, A);
    eval3(s, lp->uv + 2 * ib, B);
    double da = dist3(A, P), db = dist3(B, P);
    size_t near = da <= db ? ia : ib;
    if (pt_eq(lp->uv + 2 * near, uv)) {
        /* another curve already ends here (where three faults meet) */
        at[0] = uv[0];
        at[1] = uv[1];
        return 0;
    }
    /* A connector may end on any node (even one a curve ends on); a curve
     * end moves a node only when no other curve end is there. */
    double fn = da <= db ? h->t : 1 - h->t;
    /* A connector's foot within tol of a node would leave an outline piece
     * that short next to the connector (a curve end beyond the sheet's
     * corner: a node 0.2 m from the corner, triangles of 0 degrees): the
     * connector goes to the node. */
    if (!move && (fmin(da, db) <= tol || fn * dist3(A, B) <= tol)) {
        at[0] = lp->uv[2 * near];
        at[1] = lp->uv[2 * near + 1];
        return is_taken(tk, at) ? 0 : take(tk, at);
    }
    /* Sliding a node along its own curve to the curve end spares a short
     * edge (a sliver) up to half a size; a node where two kinds of
     * boundary meet (a corner, the end of the sea-level line) stays. */
    size_t prev = (near + lp->n - 1) % lp->n;
    int same_kind = lp->seg[prev].kind == lp->seg[near].kind;
    double reach = same_kind ? 2 * tol * 0.9 : tol;
    if (move && fmin(da, db) <= reach && !is_taken(tk, lp->uv + 2 * near) &&
        movable(dom, h->loop, near, uv)) {
        if (move) {
            lp->uv[2 * near] = uv[0];
            lp->uv[2 * near + 1] = uv[1];
            if (fabs(P[2] - level) < 1e-6)
                lp->level[near] = 1;
        }
        at[0] = lp->uv[2 * near];
        at[1] = lp->uv[2 * near + 1];
        return take(tk, at);
    }
    const double *a = lp->uv + 2 * ia, *b = lp->uv + 2 * ib;
    double q[2];
    if (move) {
        q[0] = uv[0];
        q[1] = uv[1];
    } else {
        q[0] = a[0] + h->t * (b[0] - a[0]);
        q[1] = a[1] + h->t * (b[1] - a[1]);
    }
    if (split_segment(s, lp, ia, h->t, q, level))
        return -1;
    at[0] = q[0];
    at[1] = q[1];
    return take(tk, at);
}

/* Distance in (u, v) from p to segment a-b. */
static double uv_seg_dist(const double *p, const double *a, const double *b, double *t)
{
    double d[2] = {b[0] - a[0], b[1] - a[1]}, L2 = d[0] * d[0] + d[1] * d[1];
    double f = L2 > 0 ? ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / L2 : 0;
    f = f < 0 ? 0 : f > 1 ? 1 : f;
    *t = f;
    return hypot(p[0] - a[0] - f * d[0], p[1] - a[1] - f * d[1]);
}

/* If curve segment p-q crosses a loop segment other than at shared end
 * points, puts the curve node nearer that segment into the loop there;
 * 1 when the loops changed, 0 when nothing crosses, -1 out of memory. */
static int reroute(const fm_fit_surface *s, remesh_domain *dom, const double *p, const double *q,
                   double level, taken *tk)
{
    for (size_t l = 0; l < dom->n; l++) {
        dom_loop *lp = &dom->loops[l];
        for (size_t i = 0; i < lp->n; i++) {
            size_t j = (i + 1) % lp->n;
            const double *a = lp->uv + 2 * i, *b = lp->uv + 2 * j;
            if (pt_eq(a, p) || pt_eq(a, q) || pt_eq(b, p) || pt_eq(b, q))
                continue;
            if (!segments_cross(a, b, p, q))
                continue;
            double tp, tq;
            double dp = uv_seg_dist(p, a, b, &tp), dq = uv_seg_dist(q, a, b, &tq);
            const double *c = dp <= dq ? p : q;
            double t = dp <= dq ? tp : tq;
            int on = 0;
            for (size_t k = 0; k < lp->n; k++)
                on |= pt_eq(lp->uv + 2 * k, c);
            if (on) {
                /* the nearer node is on the loop already: take the other */
                c = dp <= dq ? q : p;
                t = dp <= dq ? tq : tp;
                for (size_t k = 0; k < lp->n; k++)
                    if (pt_eq(lp->uv + 2 * k, c))
                        return 0; /* both are: a crossing we cannot mend */
            }
            dom_seg s0 = lp->seg[i];
            if (split_segment(s, lp, i, t, c, level))
                return -1;
            if (!movable(dom, l, i + 1, c)) {
                /* the detour would cross the outline elsewhere: undo it */
                memmove(lp->uv + 2 * (i + 1), lp->uv + 2 * (i + 2),
                        2 * (lp->n - i - 2) * sizeof *lp->uv);
                memmove(lp->level + i + 1, lp->level + i + 2, (lp->n - i - 2) * sizeof *lp->level);
                memmove(lp->seg + i + 1, lp->seg + i + 2, (lp->n - i - 2) * sizeof *lp->seg);
                lp->n--;
                lp->seg[i] = s0;
                return 0;
            }
            if (!is_taken(tk, c) && take(tk, c))
                return -1;
            return 1;
        }
    }
    return 0;
}

/* Where segment a-b first crosses a loop segment (from a), other than at
 * b: that point is put into the loop and returned in out (0); 1 when
 * nothing crosses; -1 out of memory. */
static int first_crossing(const fm_fit_surface *s, remesh_domain *dom, const double a[2],
                          const double b[2], double level, taken *tk, double out[2])
{
    double best = INFINITY, bx[2] = {0, 0};
    size_t bl = 0, bi = 0;
    double bt = 0;
    for (size_t l = 0; l < dom->n; l++) {
        const dom_loop *lp = &dom->loops[l];
        for (size_t i = 0; i < lp->n; i++) {
            const double *p = lp->uv + 2 * i, *q = lp->uv + 2 * ((i + 1) % lp->n);
            if (pt_eq(p, b) || pt_eq(q, b) || pt_eq(p, a) || pt_eq(q, a))
                continue;
            if (!segments_cross(a, b, p, q))
                continue;
            double d1[2] = {b[0] - a[0], b[1] - a[1]}, d2[2] = {q[0] - p[0], q[1] - p[1]};
            double den = d1[0] * d2[1] - d1[1] * d2[0];
            if (den == 0)
                continue;
            double ta = ((p[0] - a[0]) * d2[1] - (p[1] - a[1]) * d2[0]) / den;
            double tp = ((p[0] - a[0]) * d1[1] - (p[1] - a[1]) * d1[0]) / den;
            if (ta < best) {
                best = ta;
                bl = l;
                bi = i;
                bt = fmin(1, fmax(0, tp));
                bx[0] = p[0] + bt * d2[0];
                bx[1] = p[1] + bt * d2[1];
            }
        }
    }
    if (!isfinite(best))
        return 1;
    if (split_segment(s, &dom->loops[bl], bi, bt, bx, level))
        return -1;
    if (!is_taken(tk, bx) && take(tk, bx))
        return -1;
    out[0] = bx[0];
    out[1] = bx[1];
    return 0;
}

typedef struct connector {
    double a[2], b[2]; /* curve end, loop node */
    int64_t node;      /* the curve end's shared node */
    size_t curve;      /* the curve it ends */
    int level;
} connector;

/* End e of curve c is where another curve the sheet ends at carries on in
 * the same direction: the two are one boundary and that node is no open
 * end. (Each gave it a connector to the nearest outline point, the second
 * to a point the first had just put a metre off it: a wedge of zero width
 * between the two, refined into triangles of 2 degrees.) */
static int end_continues(const fm_remesh_curve *cv, size_t nc, size_t c, int e)
{
    int64_t id = cv[c].node[e ? cv[c].n - 1 : 0];
    for (size_t k = 0; k < nc; k++)
        if (k != c && cv[k].end && cv[k].node[e ? 0 : cv[k].n - 1] == id)
            return 1;
    return 0;
}

static int has_connector(const connector *cn, size_t ncn, int64_t node)
{
    for (size_t k = 0; k < ncn; k++)
        if (cn[k].node == node)
            return 1;
    return 0;
}

/* The loop segment (among the first nl, segment k starting at point k)
 * joining points a and b either way, or -1. */
static int32_t loop_segment(const flat_domain *fd, size_t nl, int32_t a, int32_t b)
{
    if ((size_t)a >= nl || (size_t)b >= nl)
        return -1;
    if (fd->seg[2 * (size_t)a + 1] == b)
        return a;
    if (fd->seg[2 * (size_t)b + 1] == a)
        return b;
    return -1;
}

static int has_segment(const flat_domain *fd, size_t ns, int32_t a, int32_t b)
{
    for (size_t k = 0; k < ns; k++)
        if ((fd->seg[2 * k] == a && fd->seg[2 * k + 1] == b) ||
            (fd->seg[2 * k] == b && fd->seg[2 * k + 1] == a))
            return 1;
    return 0;
}

static int32_t find_point(const flat_domain *fd, size_t n, const double uv[2])
{
    for (size_t i = 0; i < n; i++)
        if (fd->uv[2 * i] == uv[0] && fd->uv[2 * i + 1] == uv[1])
            return (int32_t)i;
    return -1;
}

/* 1 if the chord from point a to point b crosses one of the first ns
 * segments of fd (those ending at a or b aside). */
static int chord_blocked(const flat_domain *fd, size_t ns, int32_t a, int32_t b)
{
    const double *pa = fd->uv + 2 * a, *pb = fd->uv + 2 * b;
    for (size_t k = 0; k < ns; k++) {
        int32_t p = fd->seg[2 * k], q = fd->seg[2 * k + 1];
        if (p == a || p == b || q == a || q == b)
            continue;
        if (segments_cross(pa, pb, fd->uv + 2 * p, fd->uv + 2 * q))
            return 1;
    }
    return 0;
}

/* The loop node (among the first nl points) nearest to point a in 3D,
 * within reach, whose chord from a crosses none of the first ns segments,
 * or -1. When that chord passes within `clear` of a curve node (another
 * curve's open end, among points nl to np), the connector goes to that
 * node instead, if it reaches it uncrossed: refinement splits a
 * constrained edge that close to a node into pieces that short
 * (Newport-Inglewood/Rose Canyon link: a connector passing 56 m from a
 * curve end left five outline pieces of 130 to 270 m and triangles of 4
 * degrees). */
static int32_t reachable_node(const fm_fit_surface *s, const flat_domain *fd, size_t nl,
                              size_t ns, size_t np, int32_t a, double reach, double clear)
{
    double A[3];
    eval3(s, fd->uv + 2 * a, A);
    int32_t best = -1;
    double bd = reach;
    for (size_t i = 0; i < nl; i++) {
        double Q[3];
        eval3(s, fd->uv + 2 * i, Q);
        double d = dist3(A, Q);
        if (d < bd && (int32_t)i != a && !has_segment(fd, ns, a, (int32_t)i) &&
            !chord_blocked(fd, ns, a, (int32_t)i)) {
            bd = d;
            best = (int32_t)i;
        }
    }
    if (best < 0)
        return best;
    /* the nearest curve node the chord passes within clear of, if any */
    double B[3];
    eval3(s, fd->uv + 2 * best, B);
    int32_t via = -1;
    double vd = INFINITY;
    for (size_t k = nl; k < np; k++) {
        if ((int32_t)k == a)
            continue;
        double K[3];
        eval3(s, fd->uv + 2 * k, K);
        double d = dist3(A, K);
        if (fm_segment_distance3(K, A, B) <= clear && d < vd && !has_segment(fd, ns, a, (int32_t)k) &&
            !chord_blocked(fd, ns, a, (int32_t)k)) {
            vd = d;
            via = (int32_t)k;
        }
    }
    return via >= 0 ? via : best;
}

/* With no loop node in reach, a curve end blocked by another curve (a
 * T-curve that stops just short of one that crosses the sheet) is closed
 * off by that curve: the connector goes to the nearest node of another
 * curve (points nl to np, none of own's) it reaches uncrossed, within
 * reach, or -1. */
static int32_t reachable_curve_node(const fm_fit_surface *s, const flat_domain *fd, size_t nl,
                                    size_t ns, size_t np, int32_t a, double reach,
                                    const fm_remesh_curve *own)
{
    double A[3];
    eval3(s, fd->uv + 2 * a, A);
    int32_t best = -1;
    double bd = reach;
    for (size_t k = nl; k < np; k++) {
        int mine = 0;
        for (size_t i = 0; i < own->n && !mine; i++)
            mine = fd->shared[k] == own->node[i];
        if (mine || (int32_t)k == a)
            continue;
        double K[3];
        eval3(s, fd->uv + 2 * k, K);
        double d = dist3(A, K);
        if (d < bd && !chord_blocked(fd, ns, a, (int32_t)k)) {
            bd = d;
            best = (int32_t)k;
        }
    }
    return best;
}

/* The outline node next to loop node b (among the first nl points) that
 * is a curve's node, within `near` of b in 3D and reached from point a
 * without crossing anything (the nearer to a of two), or -1. A
 * connector whose foot is an outline node that close to where a curve
 * meets the outline leaves an outline piece that short between them,
 * refined into slivers (Laguna Salada east branch: a foot 391 m from a
 * curve's end, a triangle of 12 degrees). */
static int32_t curve_node_beside(const fm_fit_surface *s, const flat_domain *fd, size_t nl,
                                 size_t ns, int32_t a, int32_t b, double near)
{
    int32_t nb[2] = {fd->seg[2 * (size_t)b + 1], -1};
    for (size_t k = 0; k < nl; k++)
        if (fd->seg[2 * k + 1] == b)
            nb[1] = (int32_t)k;
    double A[3], B[3];
    eval3(s, fd->uv + 2 * a, A);
    eval3(s, fd->uv + 2 * b, B);
    int32_t best = -1;
    double bd = INFINITY;
    for (int k = 0; k < 2; k++) {
        int32_t c = nb[k];
        if (c < 0 || c == a || fd->shared[c] < 0 || has_segment(fd, ns, a, c))
            continue;
        double C[3];
        eval3(s, fd->uv + 2 * c, C);
        if (dist3(B, C) <= near && dist3(A, C) < bd && !chord_blocked(fd, ns, a, c)) {
            bd = dist3(A, C);
            best = c;
        }
    }
    return best;
}

/* 3D distance from P to the curve's polyline between nodes i0 and i1. */
static double curve_dist(const fm_fit_surface *s, const fm_remesh_curve *c, size_t i0, size_t i1,
                         const double P[3])
{
    double best = INFINITY, a[3], b[3];
    eval3(s, c->uv + 2 * i0, a);
    for (size_t i = i0; i < i1; i++) {
        eval3(s, c->uv + 2 * (i + 1), b);
        best = fmin(best, fm_segment_distance3(P, a, b));
        memcpy(a, b, sizeof a);
    }
    return best;
}

static int find_loop_node(const remesh_domain *dom, const double uv[2], size_t *l, size_t *k)
{
    for (size_t m = 0; m < dom->n; m++)
        for (size_t i = 0; i < dom->loops[m].n; i++)
            if (pt_eq(dom->loops[m].uv + 2 * i, uv)) {
                *l = m;
                *k = i;
                return 1;
            }
    return 0;
}

/* Where a curve runs along the outline (a T whose sheet already ends at
 * the other fault), the outline is rerouted through some of its nodes and
 * keeps its own nodes in between, metres off the curve: the faces between
 * are slivers that, kept as gaps, become triangles of 180 degrees. The
 * outline between two consecutive curve nodes on it is replaced by the
 * curve there when every outline node in between lies within `near` of
 * the curve and is no other curve's or connector's. Returns -1 when out
 * of memory. */
static int hug_curves(const fm_fit_surface *s, remesh_domain *dom, const fm_remesh_curve *cv,
                      size_t nc, double near, double level, const taken *tk)
{
    for (size_t c = 0; c < nc; c++) {
        size_t pi = 0, pl = 0, pk = 0;
        int have = 0;
        for (size_t i = 0; i < cv[c].n; i++) {
            size_t l, k;
            if (!find_loop_node(dom, cv[c].uv + 2 * i, &l, &k))
                continue;
            if (have && l == pl) {
                dom_loop *lp = &dom->loops[l];
                size_t n = lp->n;
                /* dir 0: the loop runs from pk forward to k; 1: k to pk */
                for (int dir = 0; dir < 2; dir++) {
                    size_t from = dir ? k : pk, to = dir ? pk : k;
                    size_t cnt = (to + n - from) % n - 1; /* nodes strictly between */
                    if (to == from || cnt == 0 || cnt > i - pi + 2 || cnt + 3 > n)
                        continue;
                    int ok = 1;
                    for (size_t q = 1; q <= cnt && ok; q++) {
                        const double *u = lp->uv + 2 * ((from + q) % n);
                        double P[3];
                        eval3(s, u, P);
                        ok = !is_taken(tk, u) && curve_dist(s, &cv[c], pi, i, P) <= near;
                    }
                    if (!ok)
                        continue;
                    /* remove the nodes between, then put the curve's in */
                    dom_seg sg = lp->seg[from];
                    for (size_t q = 0; q < cnt; q++) {
                        size_t at = (from + 1) % lp->n;
                        memmove(lp->uv + 2 * at, lp->uv + 2 * (at + 1),
                                2 * (lp->n - at - 1) * sizeof *lp->uv);
                        memmove(lp->level + at, lp->level + at + 1,
                                (lp->n - at - 1) * sizeof *lp->level);
                        memmove(lp->seg + at, lp->seg + at + 1, (lp->n - at - 1) * sizeof *lp->seg);
                        lp->n--;
                        if (at < from)
                            from--;
                    }
                    sg.kind = SEG_FREE;
                    lp->seg[from] = sg;
                    for (size_t q = 1; q < i - pi; q++) {
                        const double *u = cv[c].uv + 2 * (dir ? i - q : pi + q);
                        double P[3];
                        eval3(s, u, P);
                        if (loop_insert(lp, from + q, u, fabs(P[2] - level) < 1e-6, &sg))
                            return -1;
                    }
                    break;
                }
                find_loop_node(dom, cv[c].uv + 2 * i, &l, &k);
            }
            have = 1;
            pi = i;
            pl = l;
            pk = k;
        }
    }
    return 0;
}

/* 1 if a and b are consecutive nodes of one of the curves. */
static int curve_piece(const fm_remesh_curve *cv, size_t nc, const double *a, const double *b)
{
    for (size_t c = 0; c < nc; c++)
        for (size_t i = 0; i + 1 < cv[c].n; i++) {
            const double *p = cv[c].uv + 2 * i, *q = p + 2;
            if ((pt_eq(p, a) && pt_eq(q, b)) || (pt_eq(p, b) && pt_eq(q, a)))
                return 1;
        }
    return 0;
}

/* Puts the curve ends within tol of the loops onto them (pass 0), or
 * gives the open ends of curves the sheet ends at their connectors (pass
 * 1, on the outline as rerouted and hugging the curves). Connectors come
 * last: one aimed at the outline before a curve end was put on it went to
 * the node that end would have moved, and the end was inserted beside it
 * on the connector's way (Agua Caliente: a sea-level connector along the
 * top trace passed 1.9 m from a curve end put 80 m short of its foot,
 * refined into triangles of 0 to 10 degrees); one aimed before the
 * outline hugged a curve kept an outline node metres off the curve
 * (Rose Canyon's corner with San Onofre: a spike of 4 degrees). Returns
 * -1 when out of memory. */
static int place_ends(const fm_fit_surface *s, remesh_domain *dom, const fm_remesh_curve *cv,
                      size_t nc, double tol, double level, taken *tk, unsigned char *snapped,
                      connector *cn, size_t *ncn, int pass)
{
    for (size_t c = 0; c < nc; c++)
        for (int e = 0; e < 2; e++) {
            if (snapped[2 * c + (size_t)e])
                continue;
            const double *uv = cv[c].uv + 2 * (e ? cv[c].n - 1 : 0);
            double P[3], at[2];
            eval3(s, uv, P);
            seg_hit hh = nearest_segment(s, dom, P);
            if (!isfinite(hh.d))
                continue;
            if (hh.d <= tol) {
                if (put_on_loop(s, dom, &hh, uv, level, tol, 1, tk, at))
                    return -1;
                snapped[2 * c + (size_t)e] = 1;
            } else if (pass && cv[c].end && !end_continues(cv, nc, c, e) &&
                       !has_connector(cn, *ncn, cv[c].node[e ? cv[c].n - 1 : 0])) {
                /* a foot on a piece of another curve the outline runs
                 * along would be a node of that curve the other sheet
                 * has not: the outline and the curve would part there, a
                 * face of no width (Banning strand: a triangle of 0.04
                 * degrees); the connector goes to the nearer end */
                const dom_loop *lp = &dom->loops[hh.loop];
                const double *a = lp->uv + 2 * hh.i, *b = lp->uv + 2 * ((hh.i + 1) % lp->n);
                if (curve_piece(cv, nc, a, b)) {
                    double A[3], B[3];
                    eval3(s, a, A);
                    eval3(s, b, B);
                    hh.t = dist3(A, P) <= dist3(B, P) ? 0 : 1;
                }
                if (put_on_loop(s, dom, &hh, uv, level, tol, 0, tk, at))
                    return -1;
                /* a connector that would cross the outline on its way ends
                 * where it first meets it */
                if (first_crossing(s, dom, uv, at, level, tk, at) < 0)
                    return -1;
                connector *k = &cn[(*ncn)++];
                memcpy(k->a, uv, sizeof k->a);
                memcpy(k->b, at, sizeof k->b);
                k->node = cv[c].node[e ? cv[c].n - 1 : 0];
                k->curve = c;
                double B[3];
                eval3(s, at, B);
                k->level = fabs(P[2] - level) < 1e-6 && fabs(B[2] - level) < 1e-6;
            }
        }
    return 0;
}

fm_status domain_join(const fm_fit_surface *s, remesh_domain *dom, const fm_remesh_curve *cv,
                      size_t nc, double h, double level, flat_domain *fd, fm_error *err,
                      const char *name)
{
    memset(fd, 0, sizeof *fd);
    double tol = 0.25 * h;
    taken tk = {0};
    connector *cn = malloc((2 * nc + 1) * sizeof *cn);
    unsigned char *snapped = calloc(2 * nc + 1, 1);
    size_t ncn = 0;
    fm_status st = FM_OK;
    if (!cn || !snapped)
        goto nomem;
    for (size_t c = 0; c < nc; c++)
        if (cv[c].n < 2) {
            st = fm_error_set(err, FM_ERR_INVALID, name, 0, "shared curve %zu has fewer than 2 nodes",
                              c);
            goto done;
        }
    /* Curve ends on the outline first, then the outline rerouted and
     * hugging the curves, and connectors aimed at it last (place_ends). */
    if (place_ends(s, dom, cv, nc, tol, level, &tk, snapped, cn, &ncn, 0))
        goto nomem;
    /* A curve may cross the sampled outline between its nodes (the
     * outline's chords are not the plan's outline): the outline, which
     * belongs to this sheet alone, is rerouted through the curve node
     * nearer the crossing, so the curve touches it there instead. */
    for (int pass = 0; pass < 8; pass++) {
        int changed = 0;
        for (size_t c = 0; c < nc; c++)
            for (size_t i = 0; i + 1 < cv[c].n; i++) {
                const double *p = cv[c].uv + 2 * i, *q = p + 2;
                int hit = reroute(s, dom, p, q, level, &tk);
                if (hit < 0)
                    goto nomem;
                changed |= hit;
            }
        if (!changed)
            break;
    }
    /* a strip narrower than 0.3 H between the outline and a curve holds
     * no triangle of size H: only slivers (Agua Caliente's seams, 0.05
     * degrees); 0.45 H changes nothing more on the CFM */
    if (hug_curves(s, dom, cv, nc, 0.3 * h, level, &tk))
        goto nomem;
    if (place_ends(s, dom, cv, nc, tol, level, &tk, snapped, cn, &ncn, 1))
        goto nomem;
    /* flatten: loops first (as domain_triangulate always did), then the
     * curves' own nodes and segments, then the connectors */
    size_t nl = 0, extra_p = 0, extra_s = ncn;
    for (size_t l = 0; l < dom->n; l++)
        nl += dom->loops[l].n;
    for (size_t c = 0; c < nc; c++) {
        extra_p += cv[c].n;
        extra_s += cv[c].n - 1;
    }
    size_t P = nl + extra_p, S = nl + extra_s;
    fd->uv = malloc(2 * P * sizeof *fd->uv + 1);
    fd->level = malloc(P * sizeof *fd->level + 1);
    fd->shared = malloc(P * sizeof *fd->shared + 1);
    fd->seg = malloc(2 * S * sizeof *fd->seg + 1);
    fd->segs = malloc(S * sizeof *fd->segs + 1);
    fd->ends = malloc(4 * S * sizeof *fd->ends + 1);
    fd->curve = malloc(S * sizeof *fd->curve + 1);
    fd->end = malloc(S + 1);
    fd->partner = malloc((nc + 1) * sizeof *fd->partner);
    if (!fd->uv || !fd->level || !fd->shared || !fd->seg || !fd->segs || !fd->ends || !fd->curve ||
        !fd->end || !fd->partner)
        goto nomem;
    for (size_t c = 0; c < nc; c++)
        fd->partner[c] = cv[c].partner;
    size_t np = 0, ns = 0;
    for (size_t l = 0; l < dom->n; l++) {
        const dom_loop *lp = &dom->loops[l];
        size_t base = np;
        for (size_t i = 0; i < lp->n; i++) {
            memcpy(fd->uv + 2 * np, lp->uv + 2 * i, 2 * sizeof *fd->uv);
            fd->level[np] = lp->level[i];
            fd->shared[np] = -1;
            np++;
        }
        for (size_t i = 0; i < lp->n; i++) {
            size_t k = base + i, nx = base + (i + 1) % lp->n;
            fd->seg[2 * ns] = (int32_t)k;
            fd->seg[2 * ns + 1] = (int32_t)nx;
            fd->segs[ns] = lp->seg[i];
            memcpy(fd->ends + 4 * ns, lp->uv + 2 * i, 2 * sizeof *fd->ends);
            memcpy(fd->ends + 4 * ns + 2, lp->uv + 2 * ((i + 1) % lp->n), 2 * sizeof *fd->ends);
            fd->curve[ns] = -1;
            fd->end[ns] = 0;
            ns++;
        }
    }
    fd->n = nl;
    for (size_t c = 0; c < nc; c++) {
        int32_t prev = -1;
        for (size_t i = 0; i < cv[c].n; i++) {
            const double *uv = cv[c].uv + 2 * i;
            int32_t pi = -1;
            /* ends put on the loops, nodes the loops were rerouted through,
             * and points curves share where three faults meet */
            pi = find_point(fd, np, uv);
            /* a node another curve has already (one node, however its
             * (u, v) was rounded on the way) */
            for (size_t q = 0; pi < 0 && q < np; q++)
                if (fd->shared[q] == cv[c].node[i])
                    pi = (int32_t)q;
            if (pi < 0) {
                pi = (int32_t)np;
                memcpy(fd->uv + 2 * np, uv, 2 * sizeof *fd->uv);
                double Q[3];
                eval3(s, uv, Q);
                fd->level[np] = fabs(Q[2] - level) < 1e-6;
                np++;
            }
            fd->shared[pi] = cv[c].node[i];
            int32_t dup = prev >= 0 ? loop_segment(fd, nl, prev, pi) : -1;
            if (prev == pi || (dup < 0 && prev >= 0 && has_segment(fd, ns, prev, pi))) {
                /* a zero-length piece, or one another curve already has
                 * (curves that share points where three faults meet) */
            } else if (dup >= 0) {
                /* the curve runs along the outline here: that piece of the
                 * outline is the shared curve */
                fd->segs[dup].kind = SEG_SHARED;
                fd->curve[dup] = (int32_t)c;
            } else if (prev >= 0) {
                fd->seg[2 * ns] = prev;
                fd->seg[2 * ns + 1] = pi;
                memset(&fd->segs[ns], 0, sizeof fd->segs[ns]);
                fd->segs[ns].kind = SEG_SHARED;
                memcpy(fd->ends + 4 * ns, fd->uv + 2 * prev, 2 * sizeof *fd->ends);
                memcpy(fd->ends + 4 * ns + 2, uv, 2 * sizeof *fd->ends);
                fd->curve[ns] = (int32_t)c;
                /* 2: an end whose flap goes whatever its width */
                fd->end[ns] = (unsigned char)(cv[c].end == 0 ? 0 : cv[c].lone ? 2 : 1);
                ns++;
            }
            prev = pi;
        }
    }
    for (size_t k = 0; k < ncn; k++) {
        int32_t a = find_point(fd, np, cn[k].a), b = find_point(fd, nl, cn[k].b);
        /* a curve end the outline was rerouted through needs none */
        if (a < 0 || b < 0 || a == b || (size_t)a < nl)
            continue;
        int lev = cn[k].level;
        if (chord_blocked(fd, ns, a, b) || has_segment(fd, ns, a, b)) {
            /* The node nearest the curve end can lie beyond another curve
             * (a short one near a corner of the outline), or be the
             * curve's own next node, where the outline hugs the curve
             * (Mission Creek strand steep: a curve turning back off the
             * outline at its end): the connector goes to the nearest
             * loop node it reaches without crossing anything, at most a
             * size farther (a longer one would cut off a strip of the
             * sheet: slivers), or the sheet is left to fail as before. */
            double A[3], B[3];
            eval3(s, fd->uv + 2 * a, A);
            eval3(s, fd->uv + 2 * b, B);
            int32_t c = reachable_node(s, fd, nl, ns, np, a, dist3(A, B) + h, 0.25 * h);
            if (c < 0)
                c = reachable_curve_node(s, fd, nl, ns, np, a, dist3(A, B) + h,
                                         &cv[cn[k].curve]);
            if (c >= 0) {
                b = c;
                lev = fd->level[a] && fd->level[b];
            }
        } else if (fd->shared[b] < 0) {
            int32_t c = curve_node_beside(s, fd, nl, ns, a, b, 0.5 * h);
            if (c >= 0) {
                b = c;
                lev = fd->level[a] && fd->level[b];
            }
        }
        /* the loop or a curve may join the two already (a connector to
         * the curve's own next node: Pezzoni Casmalia's sheet failed and
         * was meshed without its T with Los Alamos) */
        if (has_segment(fd, ns, a, b))
            continue;
        fd->seg[2 * ns] = a;
        fd->seg[2 * ns + 1] = b;
        memset(&fd->segs[ns], 0, sizeof fd->segs[ns]);
        fd->segs[ns].kind = lev ? SEG_LEVEL : SEG_FREE;
        memcpy(fd->ends + 4 * ns, fd->uv + 2 * a, 2 * sizeof *fd->ends);
        memcpy(fd->ends + 4 * ns + 2, fd->uv + 2 * b, 2 * sizeof *fd->ends);
        fd->curve[ns] = -1;
        fd->end[ns] = 0;
        ns++;
    }
    fd->npoints = np;
    fd->nseg = ns;
    goto done;
nomem:
    st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
done:
    free(tk.uv);
    free(cn);
    free(snapped);
    if (st != FM_OK)
        flat_free(fd);
    return st;
}

/* ---- Which faces of the arrangement are the domain ---- */

static int32_t uf_find(int32_t *par, int32_t a)
{
    while (par[a] != a) {
        par[a] = par[par[a]];
        a = par[a];
    }
    return a;
}

static fm_status join_classify(fm_cdt *cdt, const flat_domain *fd, unsigned char *keep_out,
                               size_t *kept, fm_error *err);

fm_status join_select(fm_cdt *cdt, const flat_domain *fd, fm_error *err)
{
    unsigned char *keep = calloc(fm_cdt_nfaces(cdt) + 1, 1);
    if (!keep)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    fm_status st = join_classify(cdt, fd, keep, NULL, err);
    if (st == FM_OK)
        st = fm_cdt_select_faces(cdt, keep, err);
    free(keep);
    return st;
}

/* The domain's boundary after the choice of faces, and the shared curves
 * inside it; loop pieces and connectors with the domain on both sides are
 * no constraint any more (a filled gap's old edge would force slivers). */
fm_status join_reduce(fm_cdt *cdt, flat_domain *fd, fm_error *err)
{
    size_t nf = fm_cdt_nfaces(cdt), ns = fd->nseg;
    unsigned char *keep = calloc(nf + 1, 1);
    unsigned char *what = calloc(ns + 1, 1); /* 1 boundary, 2 flipped boundary, 3 interior */
    if (!keep || !what) {
        free(keep);
        free(what);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    fm_status st = join_classify(cdt, fd, keep, &fd->flaps_kept, err);
    size_t nb = 0, ni = 0;
    for (size_t k = 0; k < ns && st == FM_OK; k++) {
        int32_t l, r;
        fm_cdt_segment_faces(cdt, k, &l, &r);
        int kl = l >= 0 && keep[l], kr = r >= 0 && keep[r];
        if (kl && kr)
            what[k] = fd->segs[k].kind == SEG_SHARED ? 3 : 0;
        else if (kl || kr)
            what[k] = kl ? 1 : 2;
        nb += what[k] == 1 || what[k] == 2;
        ni += what[k] == 3;
    }
    if (st != FM_OK) {
        free(keep);
        free(what);
        return st;
    }
    /* rebuild in place: boundary pieces first, domain on their left */
    int32_t *seg = malloc(2 * (nb + ni) * sizeof *seg + 1);
    dom_seg *segs = malloc((nb + ni) * sizeof *segs + 1);
    double *ends = malloc(4 * (nb + ni) * sizeof *ends + 1);
    int32_t *curve = malloc((nb + ni) * sizeof *curve + 1);
    unsigned char *end = malloc(nb + ni + 1);
    if (!seg || !segs || !ends || !curve || !end) {
        free(seg), free(segs), free(ends), free(curve), free(end);
        free(keep);
        free(what);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    size_t q = 0;
    for (int pass = 0; pass < 2; pass++)
        for (size_t k = 0; k < ns; k++) {
            int w = what[k];
            if (pass == 0 ? !(w == 1 || w == 2) : w != 3)
                continue;
            int flip = w == 2;
            seg[2 * q] = fd->seg[2 * k + flip];
            seg[2 * q + 1] = fd->seg[2 * k + 1 - flip];
            segs[q] = fd->segs[k];
            const double *e = fd->ends + 4 * k;
            if (flip) {
                double t = segs[q].ta;
                segs[q].ta = segs[q].tb;
                segs[q].tb = t;
                ends[4 * q] = e[2], ends[4 * q + 1] = e[3], ends[4 * q + 2] = e[0],
                ends[4 * q + 3] = e[1];
            } else {
                memcpy(ends + 4 * q, e, 4 * sizeof *ends);
            }
            curve[q] = fd->curve[k];
            end[q] = 0;
            q++;
        }
    /* Points of no remaining segment (the old edge of a filled gap) would
     * be mesh nodes where no curve runs: they go. */
    int32_t *map = malloc((fd->npoints + 1) * sizeof *map);
    if (!map) {
        free(seg), free(segs), free(ends), free(curve), free(end);
        free(keep);
        free(what);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (size_t i = 0; i < fd->npoints; i++)
        map[i] = -1;
    for (size_t k = 0; k < 2 * q; k++)
        map[seg[k]] = 0;
    size_t np = 0;
    for (size_t i = 0; i < fd->npoints; i++) {
        if (map[i] < 0)
            continue;
        map[i] = (int32_t)np;
        memmove(fd->uv + 2 * np, fd->uv + 2 * i, 2 * sizeof *fd->uv);
        fd->level[np] = fd->level[i];
        fd->shared[np] = fd->shared[i];
        np++;
    }
    for (size_t k = 0; k < 2 * q; k++)
        seg[k] = map[seg[k]];
    free(map);
    fd->npoints = np;
    free(fd->seg), free(fd->segs), free(fd->ends), free(fd->curve), free(fd->end);
    fd->seg = seg;
    fd->segs = segs;
    fd->ends = ends;
    fd->curve = curve;
    fd->end = end;
    fd->nseg = q;
    fd->n = nb;
    free(keep);
    free(what);
    return FM_OK;
}

/* How far flap f reaches from the curves it is cut off by (m): the
 * largest distance in 3D of a node on its boundary to the nearest of
 * those curves' segments; 0 when only lone curves cut it off. */
static double flap_width(fm_cdt *cdt, const flat_domain *fd, int32_t f)
{
    size_t ns = fd->nseg, ncut = 0;
    double (*cut)[6] = malloc((ns + 1) * sizeof *cut);
    if (!cut)
        return INFINITY;
    for (size_t k = fd->n; k < ns; k++) {
        int32_t l, r;
        fm_cdt_segment_faces(cdt, k, &l, &r);
        if (fd->curve[k] < 0 || fd->end[k] != 1 || r != f)
            continue;
        eval3(fd->surf, fd->ends + 4 * k, cut[ncut]);
        eval3(fd->surf, fd->ends + 4 * k + 2, cut[ncut] + 3);
        ncut++;
    }
    double width = 0;
    for (size_t k = 0; k < ns && ncut; k++) {
        int32_t l, r;
        fm_cdt_segment_faces(cdt, k, &l, &r);
        if (l != f && r != f)
            continue;
        const double *e = fd->ends + 4 * k;
        double uv[3][2] = {{e[0], e[1]}, {e[2], e[3]}, {0.5 * (e[0] + e[2]), 0.5 * (e[1] + e[3])}};
        for (int q = 0; q < 3; q++) {
            double p[3], d = INFINITY;
            eval3(fd->surf, uv[q], p);
            for (size_t c = 0; c < ncut; c++)
                d = fmin(d, fm_segment_distance3(p, cut[c], cut[c] + 3));
            width = fmax(width, d);
        }
    }
    free(cut);
    return width;
}

/* Whether face f may be kept as a flap: no curve shared with a partner
 * that cuts f off also keeps f on its other side. Such a face lies beyond
 * one curve of a pair of sheets and before another of the same pair (two
 * faults meeting again): it is that second junction's to decide, and
 * keeping it would run the sheet through the other. */
static int flap_alone(fm_cdt *cdt, const flat_domain *fd, int32_t f)
{
    for (size_t k = fd->n; k < fd->nseg; k++) {
        int32_t l, r;
        fm_cdt_segment_faces(cdt, k, &l, &r);
        if (fd->curve[k] < 0 || !fd->end[k] || l != f)
            continue;
        long pk = fd->partner[fd->curve[k]];
        for (size_t q = fd->n; q < fd->nseg; q++) {
            int32_t lq, rq;
            fm_cdt_segment_faces(cdt, q, &lq, &rq);
            if (fd->curve[q] >= 0 && fd->end[q] == 1 && rq == f &&
                fd->partner[fd->curve[q]] == pk)
                return 0;
        }
    }
    return 1;
}

static fm_status join_classify(fm_cdt *cdt, const flat_domain *fd, unsigned char *keep_out,
                               size_t *kept, fm_error *err)
{
    size_t nf = fm_cdt_nfaces(cdt), ns = fd->nseg;
    int32_t *par = malloc((nf + 1) * sizeof *par);
    signed char *in = malloc(nf + 1);
    unsigned char *drop = calloc(nf + 1, 1), *fill = calloc(nf + 1, 1), *keep = calloc(nf + 1, 1);
    double *bound_right = calloc(nf + 1, sizeof *bound_right);
    double *bound_left = calloc(nf + 1, sizeof *bound_left);
    fm_status st = FM_OK;
    if (!par || !in || !drop || !fill || !keep || !bound_right || !bound_left) {
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        goto done;
    }
    for (size_t f = 0; f < nf; f++) {
        par[f] = (int32_t)f;
        in[f] = -1;
    }
    /* Curves and connectors do not bound the domain: the faces on their
     * two sides are on the same side of the loops. */
    for (size_t k = fd->n; k < ns; k++) {
        int32_t l, r;
        fm_cdt_segment_faces(cdt, k, &l, &r);
        if (l >= 0 && r >= 0)
            par[uf_find(par, l)] = uf_find(par, r);
    }
    double loop_len = 0;
    for (size_t k = 0; k < fd->n; k++) {
        int32_t l, r;
        fm_cdt_segment_faces(cdt, k, &l, &r);
        const double *e = fd->ends + 4 * k;
        double len = hypot(e[2] - e[0], e[3] - e[1]);
        loop_len += len;
        /* loops run with the domain on their left */
        if (l >= 0) {
            int32_t g = uf_find(par, l);
            if (in[g] == 0)
                st = FM_ERR_TOPOLOGY;
            in[g] = 1;
            bound_left[l] += len;
        }
        if (r >= 0) {
            int32_t g = uf_find(par, r);
            if (in[g] == 1)
                st = FM_ERR_TOPOLOGY;
            in[g] = 0;
            bound_right[r] += len;
        }
    }
    if (st != FM_OK) {
        fm_error_set(err, st, NULL, 0, "shared curves cross the outline");
        goto done;
    }
    /* A face the convex hull bounds is not closed off by the curve: a
     * curve that leaves the outline and comes back has on its left the
     * hull's pocket beyond the outline, whose hull edge would become a
     * boundary edge no refinement splits. */
    const unsigned char *open = fm_cdt_face_open(cdt);
    for (size_t k = fd->n; k < ns; k++) {
        if (fd->curve[k] < 0 || !fd->end[k])
            continue;
        int32_t l, r;
        fm_cdt_segment_faces(cdt, k, &l, &r);
        if (r >= 0 && in[uf_find(par, r)] == 1)
            drop[r] = 1;
        if (l >= 0 && in[uf_find(par, l)] != 1 && !open[l])
            fill[l] = 1;
    }
    /* A flap is what overshoots the other fault: one reaching farther from
     * the curve than the join distance is a part of this fault the other
     * does not explain, and stays (the sheet runs on past the curve there;
     * the gap on the curve's other side is filled all the same). */
    for (size_t f = 0; fd->flap_max > 0 && fd->surf && f < nf; f++)
        if (drop[f] && !fill[f] && flap_alone(cdt, fd, (int32_t)f) &&
            flap_width(cdt, fd, (int32_t)f) > fd->flap_max) {
            drop[f] = 0;
            if (kept)
                (*kept)++;
        }
    const double *area = fm_cdt_face_areas(cdt);
    double inside_area = 0;
    for (size_t f = 0; f < nf; f++)
        if (in[uf_find(par, (int32_t)f)] == 1)
            inside_area += area[f];
    for (size_t f = 0; f < nf; f++) {
        int inside = in[uf_find(par, (int32_t)f)] == 1;
        if (drop[f] && fill[f]) {
            st = fm_error_set(err, FM_ERR_TOPOLOGY, NULL, 0,
                              "a shared curve has the sheet on both of its sides");
            goto done;
        }
        /* A flap or a gap is a small part of the outline's length; one that
         * takes half of it means the curve does not close it off. */
        if (drop[f] && (bound_left[f] > 0.5 * loop_len || area[f] > 0.25 * inside_area)) {
            st = fm_error_set(err, FM_ERR_TOPOLOGY, NULL, 0,
                              "the flap beyond a shared curve would be most of the sheet");
            goto done;
        }
        if (fill[f] && bound_right[f] > 0.5 * loop_len) {
            st = fm_error_set(err, FM_ERR_TOPOLOGY, NULL, 0,
                              "the gap before a shared curve is not closed off");
            goto done;
        }
        keep[f] = (unsigned char)((inside && !drop[f]) || fill[f]);
    }
    memcpy(keep_out, keep, nf);
done:
    free(par);
    free(in);
    free(drop);
    free(fill);
    free(keep);
    free(bound_right);
    free(bound_left);
    return st;
}
