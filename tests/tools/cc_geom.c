/* check_connect: exact contact tests and distances (see cc_geom.h).
 *
 * Contact of two closed triangles: their intersection, when not empty, is
 * a convex set whose extreme points lie on the boundary of one of them
 * (non-coplanar: a segment on the line where the planes meet, ending where
 * it leaves one triangle; coplanar: a convex polygon). So they meet if and
 * only if an edge of one meets the other; six exact segment-triangle tests
 * decide it.
 *
 * Segment-triangle: when the segment crosses or touches the plane at one
 * point, the line through it meets the closed triangle iff the three
 * orientations of the line against the directed edges (Plücker sides,
 * orient3d(a, b, u, v) and so on) do not take both strict signs. When the
 * segment lies in the plane, the question is 2D and goes to a projection on
 * a coordinate plane in which the triangle keeps a non-zero area: dropping a
 * coordinate is an exact affine bijection of that plane, so incidences and
 * the sign of every orientation (up to one global flip) are preserved. */
#include "cc_geom.h"

#include <math.h>
#include <stddef.h>

#include "fm_predicates.h"

static void proj(const double *p, int drop, double o[2])
{
    o[0] = p[drop == 0 ? 1 : 0];
    o[1] = p[drop == 2 ? 1 : 2];
}

/* A coordinate to drop so that u, v, w keep a non-zero area, trying the
 * largest normal component first (any non-zero one is exact); -1 when
 * they are collinear. */
static int drop_axis(const double *u, const double *v, const double *w)
{
    double e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = v[k] - u[k];
        e2[k] = w[k] - u[k];
    }
    n[0] = fabs(e1[1] * e2[2] - e1[2] * e2[1]);
    n[1] = fabs(e1[2] * e2[0] - e1[0] * e2[2]);
    n[2] = fabs(e1[0] * e2[1] - e1[1] * e2[0]);
    int order[3] = {0, 1, 2};
    for (int i = 0; i < 3; i++)
        for (int j = i + 1; j < 3; j++)
            if (n[order[j]] > n[order[i]]) {
                int t = order[i];
                order[i] = order[j];
                order[j] = t;
            }
    for (int i = 0; i < 3; i++) {
        double pu[2], pv[2], pw[2];
        proj(u, order[i], pu);
        proj(v, order[i], pv);
        proj(w, order[i], pw);
        if (fm_orient2d(pu, pv, pw) != 0)
            return order[i];
    }
    return -1;
}

int cc_degenerate(const double *a, const double *b, const double *c)
{
    return drop_axis(a, b, c) < 0;
}

/* Closed 2D segments ab, cd. */
static int seg_seg2(const double *a, const double *b, const double *c, const double *d)
{
    int o1 = fm_orient2d(a, b, c), o2 = fm_orient2d(a, b, d);
    if (o1 * o2 > 0)
        return 0;
    int o3 = fm_orient2d(c, d, a), o4 = fm_orient2d(c, d, b);
    if (o3 * o4 > 0)
        return 0;
    if (o1 || o2 || o3 || o4)
        return 1;
    /* All on one line (or points): they meet iff their boxes do. */
    for (int k = 0; k < 2; k++) {
        double lo1 = fmin(a[k], b[k]), hi1 = fmax(a[k], b[k]);
        double lo2 = fmin(c[k], d[k]), hi2 = fmax(c[k], d[k]);
        if (hi1 < lo2 || hi2 < lo1)
            return 0;
    }
    return 1;
}

/* p in the closed 2D triangle uvw (non-degenerate, either winding). */
static int pt_in_tri2(const double *p, const double *u, const double *v, const double *w)
{
    int o1 = fm_orient2d(u, v, p), o2 = fm_orient2d(v, w, p), o3 = fm_orient2d(w, u, p);
    int pos = o1 > 0 || o2 > 0 || o3 > 0, neg = o1 < 0 || o2 < 0 || o3 < 0;
    return !(pos && neg);
}

/* a, b coplanar with the non-degenerate triangle uvw. */
static int seg_tri_coplanar(const double *a, const double *b, const double *u, const double *v,
                            const double *w)
{
    int drop = drop_axis(u, v, w);
    double pa[2], pb[2], pu[2], pv[2], pw[2];
    proj(a, drop, pa);
    proj(b, drop, pb);
    proj(u, drop, pu);
    proj(v, drop, pv);
    proj(w, drop, pw);
    return pt_in_tri2(pa, pu, pv, pw) || pt_in_tri2(pb, pu, pv, pw) || seg_seg2(pa, pb, pu, pv) ||
           seg_seg2(pa, pb, pv, pw) || seg_seg2(pa, pb, pw, pu);
}

int cc_seg_tri(const double *a, const double *b, const double *u, const double *v, const double *w)
{
    int oa = fm_orient3d(u, v, w, a), ob = fm_orient3d(u, v, w, b);
    if (oa * ob > 0)
        return 0;
    if (oa == 0 && ob == 0)
        return seg_tri_coplanar(a, b, u, v, w);
    /* One point of the segment is on the plane; the line is not parallel to
     * it, so not all three sides can be zero. */
    int s1 = fm_orient3d(a, b, u, v), s2 = fm_orient3d(a, b, v, w), s3 = fm_orient3d(a, b, w, u);
    int pos = s1 > 0 || s2 > 0 || s3 > 0, neg = s1 < 0 || s2 < 0 || s3 < 0;
    return !(pos && neg);
}

int cc_seg_seg(const double *a, const double *b, const double *c, const double *d)
{
    if (fm_orient3d(a, b, c, d) != 0)
        return 0;
    /* Coplanar: project along an axis that keeps some non-collinear triple
     * (then all four, being in its plane, project faithfully). */
    const double *tri[4][3] = {{a, b, c}, {a, b, d}, {c, d, a}, {c, d, b}};
    for (int i = 0; i < 4; i++) {
        int drop = drop_axis(tri[i][0], tri[i][1], tri[i][2]);
        if (drop < 0)
            continue;
        double pa[2], pb[2], pc[2], pd[2];
        proj(a, drop, pa);
        proj(b, drop, pb);
        proj(c, drop, pc);
        proj(d, drop, pd);
        return seg_seg2(pa, pb, pc, pd);
    }
    /* All four on one line: they meet iff their boxes do. */
    for (int k = 0; k < 3; k++) {
        double lo1 = fmin(a[k], b[k]), hi1 = fmax(a[k], b[k]);
        double lo2 = fmin(c[k], d[k]), hi2 = fmax(c[k], d[k]);
        if (hi1 < lo2 || hi2 < lo1)
            return 0;
    }
    return 1;
}

/* The segment a degenerate triangle is: its extreme corners along the axis
 * of largest extent (positive unless all corners coincide). */
static void hull(const double *const t[3], const double **s0, const double **s1)
{
    int axis = 0;
    double best = -1;
    for (int k = 0; k < 3; k++) {
        double lo = fmin(fmin(t[0][k], t[1][k]), t[2][k]);
        double hi = fmax(fmax(t[0][k], t[1][k]), t[2][k]);
        if (hi - lo > best) {
            best = hi - lo;
            axis = k;
        }
    }
    int imin = 0, imax = 0;
    for (int i = 1; i < 3; i++) {
        if (t[i][axis] < t[imin][axis])
            imin = i;
        if (t[i][axis] > t[imax][axis])
            imax = i;
    }
    *s0 = t[imin];
    *s1 = t[imax];
}

/* All three corners strictly on one side of the plane of t. */
static int one_side(const double *const t[3], const double *const q[3])
{
    int o0 = fm_orient3d(t[0], t[1], t[2], q[0]);
    if (o0 == 0)
        return 0;
    return fm_orient3d(t[0], t[1], t[2], q[1]) == o0 && fm_orient3d(t[0], t[1], t[2], q[2]) == o0;
}

int cc_tri_tri(const double *const p[3], const double *const q[3])
{
    int dp = cc_degenerate(p[0], p[1], p[2]), dq = cc_degenerate(q[0], q[1], q[2]);
    const double *a, *b, *c, *d;
    if (dp && dq) {
        hull(p, &a, &b);
        hull(q, &c, &d);
        return cc_seg_seg(a, b, c, d);
    }
    if (dp) {
        hull(p, &a, &b);
        return cc_seg_tri(a, b, q[0], q[1], q[2]);
    }
    if (dq) {
        hull(q, &a, &b);
        return cc_seg_tri(a, b, p[0], p[1], p[2]);
    }
    if (one_side(p, q) || one_side(q, p))
        return 0;
    for (int i = 0; i < 3; i++) {
        if (cc_seg_tri(p[i], p[(i + 1) % 3], q[0], q[1], q[2]) ||
            cc_seg_tri(q[i], q[(i + 1) % 3], p[0], p[1], p[2]))
            return 1;
    }
    return 0;
}

cc_contact cc_classify(const uint32_t ia[3], const uint32_t ib[3], const double *x)
{
    const double *pa[3], *pb[3];
    for (int k = 0; k < 3; k++) {
        pa[k] = x + 3 * (size_t)ia[k];
        pb[k] = x + 3 * (size_t)ib[k];
    }
    int da =
        ia[0] == ia[1] || ia[1] == ia[2] || ia[0] == ia[2] || cc_degenerate(pa[0], pa[1], pa[2]);
    int db =
        ib[0] == ib[1] || ib[1] == ib[2] || ib[0] == ib[2] || cc_degenerate(pb[0], pb[1], pb[2]);
    int sa[3], sb[3], nshared = 0; /* which corners are shared */
    for (int i = 0; i < 3; i++) {
        sa[i] = sb[i] = 0;
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (ia[i] == ib[j]) {
                sa[i] = sb[j] = 1;
            }
    for (int i = 0; i < 3; i++)
        nshared += sa[i];
    if (nshared == 0)
        return cc_tri_tri(pa, pb) ? CC_VIOLATION : CC_APART;
    if (da || db)
        return CC_SKIPPED;
    if (nshared == 3)
        return CC_VIOLATION;
    if (nshared == 1) {
        /* Both contain the shared vertex p; any other common point x makes
         * [p, x] common, and the ray from p through x leaves each triangle
         * on its edge opposite p. So they meet beyond p iff the opposite
         * edge of one meets the other (it cannot contain p itself). */
        const double *b[2], *e[2];
        int nb = 0, ne = 0;
        for (int i = 0; i < 3; i++) {
            if (!sa[i])
                b[nb++] = pa[i];
            if (!sb[i])
                e[ne++] = pb[i];
        }
        return cc_seg_tri(b[0], b[1], pb[0], pb[1], pb[2]) ||
                       cc_seg_tri(e[0], e[1], pa[0], pa[1], pa[2])
                   ? CC_VIOLATION
                   : CC_APART;
    }
    /* A shared edge pq: not coplanar, each meets the other's plane exactly
     * in pq; coplanar, they overlap iff the third corners are on the same
     * side of pq. */
    const double *p = NULL, *q = NULL, *c = NULL, *f = NULL;
    for (int i = 0; i < 3; i++) {
        if (sa[i] && !p)
            p = pa[i];
        else if (sa[i])
            q = pa[i];
        else
            c = pa[i];
        if (!sb[i])
            f = pb[i];
    }
    if (fm_orient3d(p, q, c, f) != 0)
        return CC_APART;
    int drop = drop_axis(p, q, c);
    double pp[2], pq[2], pc[2], pf[2];
    proj(p, drop, pp);
    proj(q, drop, pq);
    proj(c, drop, pc);
    proj(f, drop, pf);
    return fm_orient2d(pp, pq, pc) * fm_orient2d(pp, pq, pf) > 0 ? CC_VIOLATION : CC_APART;
}

/* ---- distances (floating point, coordinates relative to a nearby point) */

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double dist_pt_seg(const double *p, const double *a, const double *b)
{
    double d[3], r[3];
    for (int k = 0; k < 3; k++) {
        d[k] = b[k] - a[k];
        r[k] = p[k] - a[k];
    }
    double dd = dot3(d, d), t = dd > 0 ? dot3(r, d) / dd : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    for (int k = 0; k < 3; k++)
        r[k] -= t * d[k];
    return sqrt(dot3(r, r));
}

/* The minimum over the parameter square is the interior stationary point
 * when it is inside, else on a side, where one end is fixed: an
 * endpoint-to-segment distance. Parallel segments take the sides. */
static double dist_seg_seg(const double *a, const double *b, const double *c, const double *d)
{
    double m = fmin(fmin(dist_pt_seg(a, c, d), dist_pt_seg(b, c, d)),
                    fmin(dist_pt_seg(c, a, b), dist_pt_seg(d, a, b)));
    double d1[3], d2[3], r[3];
    for (int k = 0; k < 3; k++) {
        d1[k] = b[k] - a[k];
        d2[k] = d[k] - c[k];
        r[k] = a[k] - c[k];
    }
    double A = dot3(d1, d1), B = dot3(d1, d2), C = dot3(d2, d2), D = dot3(d1, r), E = dot3(d2, r);
    double den = A * C - B * B;
    if (den > 1e-12 * A * C) {
        double s = (B * E - C * D) / den, t = (A * E - B * D) / den;
        if (s >= 0 && s <= 1 && t >= 0 && t <= 1) {
            double w[3];
            for (int k = 0; k < 3; k++)
                w[k] = r[k] + s * d1[k] - t * d2[k];
            m = fmin(m, sqrt(dot3(w, w)));
        }
    }
    return m;
}

/* Distance from p to the triangle t: to the plane when the foot is inside,
 * else to the nearest edge. */
static double dist_pt_tri(const double *p, const double *const t[3])
{
    double e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = t[1][k] - t[0][k];
        e2[k] = t[2][k] - t[0][k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double nn = dot3(n, n);
    if (nn > 0) {
        int inside = 1;
        for (int i = 0; i < 3 && inside; i++) {
            const double *u = t[i], *v = t[(i + 1) % 3];
            double e[3], r[3], c[3];
            for (int k = 0; k < 3; k++) {
                e[k] = v[k] - u[k];
                r[k] = p[k] - u[k];
            }
            c[0] = e[1] * r[2] - e[2] * r[1];
            c[1] = e[2] * r[0] - e[0] * r[2];
            c[2] = e[0] * r[1] - e[1] * r[0];
            inside = dot3(c, n) >= 0;
        }
        if (inside) {
            double r[3] = {p[0] - t[0][0], p[1] - t[0][1], p[2] - t[0][2]};
            return fabs(dot3(r, n)) / sqrt(nn);
        }
    }
    return fmin(fmin(dist_pt_seg(p, t[0], t[1]), dist_pt_seg(p, t[1], t[2])),
                dist_pt_seg(p, t[2], t[0]));
}

static void relative(const double *const in[], int n, const double *origin, double out[][3])
{
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            out[i][k] = in[i][k] - origin[k];
}

double cc_dist_seg_tri(const double *a, const double *b, const double *const t[3])
{
    const double *in[5] = {a, b, t[0], t[1], t[2]};
    double r[5][3];
    int deg = cc_degenerate(t[0], t[1], t[2]);
    if (deg) {
        const double *s0, *s1;
        hull(t, &s0, &s1);
        if (cc_seg_seg(a, b, s0, s1))
            return 0;
    } else if (cc_seg_tri(a, b, t[0], t[1], t[2])) {
        return 0;
    }
    relative(in, 5, t[0], r);
    double m =
        fmin(fmin(dist_seg_seg(r[0], r[1], r[2], r[3]), dist_seg_seg(r[0], r[1], r[3], r[4])),
             dist_seg_seg(r[0], r[1], r[4], r[2]));
    if (!deg) {
        const double *rt[3] = {r[2], r[3], r[4]};
        m = fmin(m, fmin(dist_pt_tri(r[0], rt), dist_pt_tri(r[1], rt)));
    }
    return m;
}

double cc_dist_tri_tri(const double *const p[3], const double *const q[3])
{
    if (cc_tri_tri(p, q))
        return 0;
    const double *in[6] = {p[0], p[1], p[2], q[0], q[1], q[2]};
    double r[6][3];
    relative(in, 6, p[0], r);
    const double *rp[3] = {r[0], r[1], r[2]}, *rq[3] = {r[3], r[4], r[5]};
    double m = INFINITY;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            m = fmin(m, dist_seg_seg(rp[i], rp[(i + 1) % 3], rq[j], rq[(j + 1) % 3]));
    if (!cc_degenerate(q[0], q[1], q[2]))
        for (int i = 0; i < 3; i++)
            m = fmin(m, dist_pt_tri(rp[i], rq));
    if (!cc_degenerate(p[0], p[1], p[2]))
        for (int i = 0; i < 3; i++)
            m = fmin(m, dist_pt_tri(rq[i], rp));
    return m;
}
