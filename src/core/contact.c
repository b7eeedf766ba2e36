/* faultmesh core: exact contact of two closed triangles (fm_predicates.h).
 *
 * Two closed triangles have a common point exactly when a side of one of
 * them meets the other: their common part is convex, and a point of it
 * farthest along any direction lies on the boundary of one of the two. So
 * six segment-against-triangle tests decide contact, each from signs of
 * orient3d alone.
 *
 * A segment and a triangle: if both ends are strictly on one side of the
 * triangle's plane they are apart. If the segment pierces or touches the
 * plane at one point, the line through it passes through the closed
 * triangle exactly when it does not turn both ways around the triangle's
 * sides (the three orient3d of the segment's ends with a side). If the
 * segment lies in the plane, the test is planar; dropping the coordinate
 * of the normal's largest component maps the plane one-to-one onto a
 * coordinate plane, which keeps every incidence, so 2D orientations there
 * decide it. */
#include <math.h>
#include <stddef.h>

#include "fm_predicates.h"

/* The coordinate to drop so that a, b, c (not collinear) keep an area:
 * the largest component of an approximate normal, then any non-zero one.
 * Any choice with a non-zero exact 2D orientation is exact. */
static int flat_axis(const double *a, const double *b, const double *c)
{
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {fabs(u[1] * v[2] - u[2] * v[1]), fabs(u[2] * v[0] - u[0] * v[2]),
                   fabs(u[0] * v[1] - u[1] * v[0])};
    int order[3] = {0, 1, 2};
    for (int i = 0; i < 3; i++)
        for (int k = i + 1; k < 3; k++)
            if (n[order[k]] > n[order[i]]) {
                int t = order[i];
                order[i] = order[k];
                order[k] = t;
            }
    for (int i = 0; i < 3; i++) {
        int d = order[i];
        double a2[2] = {a[(d + 1) % 3], a[(d + 2) % 3]};
        double b2[2] = {b[(d + 1) % 3], b[(d + 2) % 3]};
        double c2[2] = {c[(d + 1) % 3], c[(d + 2) % 3]};
        if (fm_orient2d(a2, b2, c2))
            return d;
    }
    return -1;
}

static void flatten(const double *p, int d, double out[2])
{
    out[0] = p[(d + 1) % 3];
    out[1] = p[(d + 2) % 3];
}

/* (fm_predicates.h) */
int fm_segments_meet2d(const double *p, const double *q, const double *r, const double *s)
{
    int a = fm_orient2d(p, q, r), b = fm_orient2d(p, q, s);
    int c = fm_orient2d(r, s, p), d = fm_orient2d(r, s, q);
    if (a * b > 0 || c * d > 0)
        return 0;
    if (a || b || c || d)
        return 1; /* proper crossing, or an end on the other's line within reach */
    /* collinear: overlap of the projections on the longer axis */
    int k = fabs(q[0] - p[0]) + fabs(s[0] - r[0]) >= fabs(q[1] - p[1]) + fabs(s[1] - r[1]) ? 0 : 1;
    double lo1 = fmin(p[k], q[k]), hi1 = fmax(p[k], q[k]);
    double lo2 = fmin(r[k], s[k]), hi2 = fmax(r[k], s[k]);
    return lo1 <= hi2 && lo2 <= hi1;
}

/* Point p in the closed 2D triangle abc (either winding, not collinear). */
static int inside2(const double *p, const double *a, const double *b, const double *c)
{
    int s = fm_orient2d(a, b, c);
    return fm_orient2d(a, b, p) * s >= 0 && fm_orient2d(b, c, p) * s >= 0 &&
           fm_orient2d(c, a, p) * s >= 0;
}

/* Closed segment pq against the closed triangle t (not degenerate). */
static int segment_meets_triangle(const double *p, const double *q, const double *const t[3])
{
    int sp = fm_orient3d(t[0], t[1], t[2], p), sq = fm_orient3d(t[0], t[1], t[2], q);
    if (sp * sq > 0)
        return 0;
    if (sp == 0 && sq == 0) {
        int d = flat_axis(t[0], t[1], t[2]);
        double p2[2], q2[2], t2[3][2];
        flatten(p, d, p2);
        flatten(q, d, q2);
        for (int k = 0; k < 3; k++)
            flatten(t[k], d, t2[k]);
        if (inside2(p2, t2[0], t2[1], t2[2]) || inside2(q2, t2[0], t2[1], t2[2]))
            return 1;
        for (int k = 0; k < 3; k++)
            if (fm_segments_meet2d(p2, q2, t2[k], t2[(k + 1) % 3]))
                return 1;
        return 0;
    }
    int pos = 0, neg = 0;
    for (int k = 0; k < 3; k++) {
        int s = fm_orient3d(p, q, t[k], t[(k + 1) % 3]);
        pos |= s > 0;
        neg |= s < 0;
    }
    return !(pos && neg);
}

static int all_beside(const double *const t[3], const double *const other[3])
{
    int s0 = fm_orient3d(t[0], t[1], t[2], other[0]);
    int s1 = fm_orient3d(t[0], t[1], t[2], other[1]);
    int s2 = fm_orient3d(t[0], t[1], t[2], other[2]);
    return s0 != 0 && s0 == s1 && s1 == s2;
}

int fm_triangles_meet(const double *const a[3], const double *const b[3])
{
    if (all_beside(a, b) || all_beside(b, a))
        return 0;
    for (int k = 0; k < 3; k++)
        if (segment_meets_triangle(a[k], a[(k + 1) % 3], b) ||
            segment_meets_triangle(b[k], b[(k + 1) % 3], a))
            return 1;
    return 0;
}

int fm_triangles_meet_apart(const int32_t ia[3], const int32_t ib[3], const double *x)
{
    const double *a[3], *b[3];
    int in_b[3] = {0, 0, 0}, common = 0;
    for (int k = 0; k < 3; k++) {
        a[k] = x + 3 * (size_t)ia[k];
        b[k] = x + 3 * (size_t)ib[k];
        for (int m = 0; m < 3; m++)
            if (ia[k] == ib[m])
                in_b[k] = 1;
        common += in_b[k];
    }
    if (fm_collinear3d(a[0], a[1], a[2]) || fm_collinear3d(b[0], b[1], b[2]))
        return 0;
    if (common == 0)
        return fm_triangles_meet(a, b);
    if (common == 3)
        return 1;
    if (common == 1) {
        /* With a corner v in common, a second common point w makes all of
         * [v, w] common; followed on from v, that ray leaves the first of
         * the two triangles it leaves through the side facing v, at a point
         * still in both. Conversely a side facing v never contains v. */
        int k = in_b[0] ? 0 : in_b[1] ? 1 : 2, m = 0;
        while (ib[m] != ia[k])
            m++;
        return segment_meets_triangle(a[(k + 1) % 3], a[(k + 2) % 3], b) ||
               segment_meets_triangle(b[(m + 1) % 3], b[(m + 2) % 3], a);
    }
    /* A side in common: out of one plane, each meets the other's plane in
     * that side only; in one plane, they overlap when the corners off the
     * side lie on the same side of it. */
    int k = !in_b[0] ? 0 : !in_b[1] ? 1 : 2, m = 0;
    while (ib[m] == ia[(k + 1) % 3] || ib[m] == ia[(k + 2) % 3])
        m++;
    const double *u = a[(k + 1) % 3], *v = a[(k + 2) % 3], *c = a[k], *f = b[m];
    if (fm_orient3d(u, v, c, f) != 0)
        return 0;
    int d = flat_axis(u, v, c);
    double u2[2], v2[2], c2[2], f2[2];
    flatten(u, d, u2);
    flatten(v, d, v2);
    flatten(c, d, c2);
    flatten(f, d, f2);
    return fm_orient2d(u2, v2, c2) * fm_orient2d(u2, v2, f2) > 0;
}
