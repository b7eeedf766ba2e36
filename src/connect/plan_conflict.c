/* Conflicts between junction curves on one sheet (plan_internal.h): the
 * mesher takes each sheet's curves as constraints, which must not cross
 * or come closer than a quarter size but at a point they share. Curves
 * are accepted longest first; one that conflicts with an accepted curve
 * keeps its longest stretch clear of all of them (a curve cut short of
 * the other still joins its two faults along most of their line), or is
 * left unjoined when that stretch is short. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_mesh.h"
#include "fm_predicates.h"
#include "plan_internal.h"

static int seg_cross(const double *a, const double *b, const double *c, const double *d)
{
    int o1 = fm_orient2d(a, b, c), o2 = fm_orient2d(a, b, d);
    int o3 = fm_orient2d(c, d, a), o4 = fm_orient2d(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0)
        return 1;
    /* touching or collinear overlap counts too: both would need a common node */
    if (o1 == 0 && o2 == 0)
        return fmax(fmin(a[0], b[0]), fmin(c[0], d[0])) <= fmin(fmax(a[0], b[0]), fmax(c[0], d[0])) &&
               fmax(fmin(a[1], b[1]), fmin(c[1], d[1])) <= fmin(fmax(a[1], b[1]), fmax(c[1], d[1]));
    return (o1 == 0 || o2 == 0 || o3 == 0 || o4 == 0) && o1 * o2 <= 0 && o3 * o4 <= 0;
}

/* Near a point the two curves share (a keyed node of both), they may
 * touch: that is where they meet. */
static int near_common(const pl_curve *x, const pl_curve *y, const double *p, double tol)
{
    if (!x->key || !y->key)
        return 0;
    for (size_t i = 0; i < x->n; i++) {
        if (x->key[i] < 0)
            continue;
        for (size_t k = 0; k < y->n; k++)
            if (y->key[k] == x->key[i]) {
                const double *c = x->xyz + 3 * i;
                double dx = p[0] - c[0], dy = p[1] - c[1], dz = p[2] - c[2];
                if (sqrt(dx * dx + dy * dy + dz * dz) < 2 * tol + 1e-9)
                    return 1;
            }
    }
    return 0;
}

static int find_key(const pl_curve *c, int64_t key)
{
    for (size_t i = 0; i < c->n; i++)
        if (c->key[i] == key)
            return 1;
    return 0;
}

/* Marks the nodes of x that lie within tol of y on a run of such nodes
 * that holds a keyed node x shares with y, up to `reach` from it: where
 * two curves meet at a small angle they stay close for a while on either
 * side of their common point, and that is still the one place where they
 * meet. Farther on they would run side by side along a strip too thin to
 * mesh without slivers: that stays a conflict. */
static void near_runs(const pl_curve *x, const pl_curve *y, double tol, double reach,
                      unsigned char *mark)
{
    size_t run = 0;
    int common = 0;
    for (size_t i = 0; i <= x->n; i++) {
        int near = 0;
        for (size_t k = 0; i < x->n && k + 1 < y->n && !near; k++)
            near = fm_segment_distance3(x->xyz + 3 * i, y->xyz + 3 * k, y->xyz + 3 * k + 3) < tol;
        if (near) {
            common |= x->key && y->key && x->key[i] >= 0 && find_key(y, x->key[i]);
            continue;
        }
        for (size_t r = run; r < i; r++)
            mark[r] = common && near_common(x, y, x->xyz + 3 * r, 0.5 * reach);
        if (i < x->n)
            mark[i] = 0;
        run = i + 1;
        common = 0;
    }
}

/* Sets flag[i] for every node i of x that takes part in a conflict with
 * y (x on side sx, y on side sy of one sheet): it comes within tol of y,
 * a segment at it crosses y, or a node of y comes within tol of such a
 * segment; all away from the points they share (mx, my: near_runs). With
 * flag NULL, stops at the first. Returns whether there is one. */
static int conflict_nodes(const pl_curve *x, int sx, const pl_curve *y, int sy, double tol,
                          const unsigned char *mx, const unsigned char *my, unsigned char *flag)
{
    int any = 0;
    for (size_t i = 0; i + 1 < x->n; i++)
        for (size_t k = 0; k + 1 < y->n; k++)
            if (seg_cross(x->uv[sx] + 2 * i, x->uv[sx] + 2 * i + 2, y->uv[sy] + 2 * k,
                          y->uv[sy] + 2 * k + 2) &&
                !mx[i] && !mx[i + 1] && !my[k] && !my[k + 1] &&
                !near_common(x, y, x->xyz + 3 * i, tol) &&
                !near_common(x, y, x->xyz + 3 * i + 3, tol)) {
                if (!flag)
                    return 1;
                any = flag[i] = flag[i + 1] = 1;
            }
    for (size_t i = 0; i < x->n; i++)
        for (size_t k = 0; k + 1 < y->n; k++)
            if (!mx[i] &&
                fm_segment_distance3(x->xyz + 3 * i, y->xyz + 3 * k, y->xyz + 3 * k + 3) < tol &&
                !near_common(x, y, x->xyz + 3 * i, tol)) {
                if (!flag)
                    return 1;
                any = flag[i] = 1;
            }
    for (size_t k = 0; k < y->n; k++)
        for (size_t i = 0; i + 1 < x->n; i++)
            if (!my[k] &&
                fm_segment_distance3(y->xyz + 3 * k, x->xyz + 3 * i, x->xyz + 3 * i + 3) < tol &&
                !near_common(x, y, y->xyz + 3 * k, tol)) {
                if (!flag)
                    return 1;
                any = flag[i] = flag[i + 1] = 1;
            }
    return any;
}

/* Sets flag[i] for every node i of x (on side sx of a sheet) that lies
 * beyond y, a curve the sheet ends at (side sy): on the side of y the
 * sheet gives up, its nearest point on y (in (u, v)) inside y rather than
 * at an end, more than tol from y and from the points they share, and
 * within reach of y (the farthest a gap is closed: the join distance). The
 * sheet is trimmed at y, so it cannot also reach out past y to x: Big
 * Bear's first sheet ends at its second all along its edge, and a short
 * curve with Santa Ana lay 1 km past that edge in its extension; the gap
 * filled out to it went through the second sheet, nodes 978 m off the
 * original over its inside. flag NULL: stops at the first. */
static int beyond_nodes(const pl_curve *x, int sx, const pl_curve *y, int sy, double tol,
                        double reach, unsigned char *flag)
{
    if (!y->end[sy] || y->n < 2)
        return 0;
    int any = 0;
    for (size_t i = 0; i < x->n; i++) {
        const double *p = x->uv[sx] + 2 * i;
        double best = INFINITY, bt = 0;
        size_t bk = 0;
        for (size_t k = 0; k + 1 < y->n; k++) {
            const double *a = y->uv[sy] + 2 * k, *b = a + 2;
            double dx = b[0] - a[0], dy = b[1] - a[1], L2 = dx * dx + dy * dy;
            double t = L2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / L2 : 0;
            t = t < 0 ? 0 : t > 1 ? 1 : t;
            double ex = a[0] + t * dx - p[0], ey = a[1] + t * dy - p[1];
            double d2 = ex * ex + ey * ey;
            if (d2 < best) {
                best = d2;
                bk = k;
                bt = t;
            }
        }
        /* past an end of y the sheet's edge is some other line */
        if ((bk == 0 && bt <= 0) || (bk + 2 == y->n && bt >= 1))
            continue;
        const double *a = y->uv[sy] + 2 * bk, *b = a + 2;
        int o = fm_orient2d(a, b, p);
        if (o == 0 || (o > 0) == (y->keep_left[sy] != 0))
            continue;
        const double *A = y->xyz + 3 * bk, *B = A + 3;
        double f[3] = {A[0] + bt * (B[0] - A[0]), A[1] + bt * (B[1] - A[1]),
                       A[2] + bt * (B[2] - A[2])};
        const double *q = x->xyz + 3 * i;
        double d = sqrt((q[0] - f[0]) * (q[0] - f[0]) + (q[1] - f[1]) * (q[1] - f[1]) +
                        (q[2] - f[2]) * (q[2] - f[2]));
        if (d <= tol || d > reach || near_common(x, y, q, tol))
            continue;
        if (!flag)
            return 1;
        any = flag[i] = 1;
    }
    return any;
}

/* Whether x and y conflict (flag: as conflict_nodes); -1 out of memory. */
static int curves_conflict(const pl_curve *x, int sx, const pl_curve *y, int sy, double tol,
                           unsigned char *flag)
{
    unsigned char *mx = calloc(x->n + y->n + 1, 1);
    if (!mx)
        return -1;
    unsigned char *my = mx + x->n;
    double reach = 4 * tol; /* a size: curves at 14 degrees or more */
    near_runs(x, y, tol, reach, mx);
    near_runs(y, x, tol, reach, my);
    int r = conflict_nodes(x, sx, y, sy, tol, mx, my, flag);
    free(mx);
    return r;
}

static void curve_box(const pl_curve *c, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (size_t i = 0; i < c->n; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], c->xyz[3 * i + k]);
            hi[k] = fmax(hi[k], c->xyz[3 * i + k]);
        }
}

typedef struct cand {
    size_t junction;
    pl_curve *c;
    double len;
    double lo[3], hi[3];
} cand;

static int longer_first(const void *a, const void *b)
{
    const cand *x = a, *y = b;
    if (x->len != y->len)
        return x->len > y->len ? -1 : 1;
    return (x->junction > y->junction) - (x->junction < y->junction);
}

static int same_sheet(const fm_connect_junction *a, int sa, const fm_connect_junction *b, int sb)
{
    return a->fault[sa] == b->fault[sb] && a->sheet[sa] == b->sheet[sb];
}

/* Does candidate c conflict with any accepted one? flag: as
 * conflict_nodes, over all of them. 1: they cross or near, 2 (or'ed): one
 * lies beyond the other; -1 out of memory. */
static int conflicts(const fm_connect_junction *J, const cand *cs, const size_t *acc, size_t na,
                     const cand *c, double tol, double reach, unsigned char *flag)
{
    const fm_connect_junction *ji = &J[c->junction];
    int bad = 0;
    for (size_t a = 0; a < na && (flag || !bad); a++) {
        const cand *o = &cs[acc[a]];
        const fm_connect_junction *jo = &J[o->junction];
        int far = 0;
        for (int q = 0; q < 3; q++)
            far |= c->lo[q] > o->hi[q] + reach || o->lo[q] > c->hi[q] + reach;
        if (far)
            continue;
        for (int s = 0; s < 2 && (flag || !bad); s++)
            for (int t = 0; t < 2 && (flag || !bad); t++)
                if (!c->c->off[s] && !o->c->off[t] && same_sheet(ji, s, jo, t)) {
                    int r = curves_conflict(c->c, s, o->c, t, tol, flag);
                    if (r < 0)
                        return -1;
                    bad |= r;
                    /* neither may lie beyond the other where the sheet
                     * ends at it (a curve that ends is never cut short:
                     * c beyond o is all there is to flag) */
                    if (jo->fault[0] == jo->fault[1])
                        bad |= 2 * beyond_nodes(c->c, s, o->c, t, tol, reach, flag);
                    if (ji->fault[0] == ji->fault[1])
                        bad |= 2 * beyond_nodes(o->c, t, c->c, s, tol, reach, NULL);
                }
    }
    return bad;
}

static double stretch_length(const pl_curve *c, size_t from, size_t to)
{
    double len = 0;
    for (size_t i = from; i < to; i++) {
        const double *p = c->xyz + 3 * i, *q = p + 3;
        len += sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) +
                    (q[2] - p[2]) * (q[2] - p[2]));
    }
    return len;
}

/* Keeps nodes from .. to of c. */
static void keep_stretch(pl_curve *c, size_t from, size_t to)
{
    size_t m = to - from + 1;
    memmove(c->xyz, c->xyz + 3 * from, 3 * m * sizeof *c->xyz);
    for (int s = 0; s < 2; s++)
        memmove(c->uv[s], c->uv[s] + 2 * from, 2 * m * sizeof *c->uv[s]);
    if (c->key)
        memmove(c->key, c->key + from, m * sizeof *c->key);
    c->n = m;
}

/* Cuts candidate c to its longest stretch of nodes clear of every
 * accepted curve, when that is at least `least` long and then conflicts
 * with none. 1: cut and clear; 0: not; -1: out of memory. */
static int cut_short(const fm_connect_junction *J, const cand *cs, const size_t *acc, size_t na,
                     cand *c, double tol, double reach, double least)
{
    unsigned char *flag = calloc(c->c->n + 1, 1);
    if (!flag)
        return -1;
    if (conflicts(J, cs, acc, na, c, tol, reach, flag) < 0) {
        free(flag);
        return -1;
    }
    size_t bf = 0, bt = 0;
    double best = 0;
    for (size_t i = 0; i < c->c->n; i++) {
        if (flag[i])
            continue;
        size_t t = i;
        while (t + 1 < c->c->n && !flag[t + 1])
            t++;
        double len = stretch_length(c->c, i, t);
        if (len > best) {
            best = len;
            bf = i;
            bt = t;
        }
        i = t;
    }
    free(flag);
    if (!(best >= least))
        return 0;
    keep_stretch(c->c, bf, bt);
    curve_box(c->c, c->lo, c->hi);
    int r = conflicts(J, cs, acc, na, c, tol, reach, NULL);
    return r < 0 ? -1 : !r;
}

/* The gap a sheet trimmed short of another keeps: clear of the other's
 * mesh, whose triangles stray from its surface by their sag (metres to
 * tens of metres at these sizes), and small beside the join distance. */
#define CLEAR_GAP 0.1

int pl_resolve_conflicts(fm_connect_junction *J, pl_curve *C, size_t nj,
                         const fm_model *const *models, double H, double D, const double *level)
{
    size_t nc = 0;
    for (size_t i = 0; i < nj; i++)
        nc += C[i].n > 0;
    cand *cs = malloc((nc + 1) * sizeof *cs);
    size_t *acc = malloc((nc + 1) * sizeof *acc);
    if (!cs || !acc) {
        free(cs);
        free(acc);
        return -1;
    }
    size_t k = 0;
    for (size_t i = 0; i < nj; i++)
        if (C[i].n > 0) {
            cs[k].junction = i;
            cs[k].c = &C[i];
            cs[k].len = J[i].length;
            curve_box(&C[i], cs[k].lo, cs[k].hi);
            k++;
        }
    qsort(cs, nc, sizeof *cs, longer_first);
    size_t na = 0;
    double tol = 0.25 * H, reach = fmax(D, tol);
    int st = 0;
    for (size_t i = 0; i < nc && st == 0; i++) {
        int bad = conflicts(J, cs, acc, na, &cs[i], tol, reach, NULL);
        if (bad > 0) {
            /* a sheet that ends at a curve needs all of it to end on */
            int cut = cs[i].c->end[0] || cs[i].c->end[1]
                          ? 0
                          : cut_short(J, cs, acc, na, &cs[i], tol, reach, H);
            if (cut > 0) {
                J[cs[i].junction].length = stretch_length(cs[i].c, 0, cs[i].c->n - 1);
                bad = 0;
            }
            if (cut < 0)
                bad = -1;
        }
        if (bad > 0) {
            fm_connect_junction *j = &J[cs[i].junction];
            j->type = FM_JUNCTION_UNJOINED;
            j->reason = bad & 1 ? "crosses or nears another junction curve on one of its sheets "
                                  "away from any point of the three faults found on both"
                                : "lies beyond the curve where one of its sheets ends at another "
                                  "sheet of its fault, or that curve beyond it";
            /* unjoined, the sheets would still run through each other:
             * one that was to end there stops short instead, the one that
             * overshoots first (it is the one that runs into the other) */
            pl_curve *c = cs[i].c;
            int first = c->end[1] && j->role[1] == FM_CONNECT_OVERSHOOT &&
                        j->role[0] != FM_CONNECT_OVERSHOOT;
            for (int q = 0; q < 2 && st == 0; q++) {
                int s = q ? !first : first;
                pl_curve one;
                int r = pl_clear_curve(j, c, s, models, H, CLEAR_GAP * H, level, &one);
                if (r > 0) {
                    pl_curve raw = *c;
                    *c = one;
                    curve_box(c, cs[i].lo, cs[i].hi);
                    r = conflicts(J, cs, acc, na, &cs[i], tol, reach, NULL);
                    /* one that nears a curve of its own sheet keeps its
                     * longest clear stretch: the mesher closes the cut
                     * off through that curve */
                    if (r > 0)
                        r = cut_short(J, cs, acc, na, &cs[i], 2 * tol, reach, H) > 0 ? 0 : 1;
                    if (r == 0) {
                        pl_curve_free(&raw);
                        j->clearance = CLEAR_GAP * H;
                        j->short_side = s;
                        j->reason = bad & 1 ? "crosses or nears another junction curve on one of "
                                              "its sheets away from any point of the three "
                                              "faults found on both; one stops short of the "
                                              "other instead"
                                            : "lies beyond the curve where one of its sheets "
                                              "ends at another sheet of its fault, or that "
                                              "curve beyond it; one stops short of the other "
                                              "instead";
                        break;
                    }
                    *c = raw;
                    pl_curve_free(&one);
                    curve_box(c, cs[i].lo, cs[i].hi);
                }
                if (r < 0)
                    st = -1;
            }
            if (j->clearance > 0) {
                acc[na++] = i;
                continue;
            }
            pl_curve_free(cs[i].c);
        } else if (bad < 0) {
            st = -1;
        } else {
            acc[na++] = i;
        }
    }
    free(cs);
    free(acc);
    return st;
}
