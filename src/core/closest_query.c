/* Closest point queries on the AABB tree of fm_closest.h, and the closest
 * point on one triangle they rest on.
 *
 * The triangle routine follows the Voronoi-region scheme (Ericson, Real-Time
 * Collision Detection, 5.1.5): vertex regions from dot products along the
 * edges, then edge regions, then the interior. Two changes make it hold up
 * on CFM slivers: the side of each edge is the triple product of the normal
 * with (edge x vertex-to-point), not the book's differences of dot
 * products, which cancel catastrophically on thin triangles; and the normal
 * is taken at the largest angle, recomputed with compensated products when
 * even that angle is close to 180 degrees. Triangles whose normal is still
 * zero (collinear or coincident corners) are their three edges. */
#include "closest_tree.h"

#include <math.h>
#include <stdint.h>

static double dot3(const double u[3], const double v[3])
{
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

static void sub3(double r[3], const double u[3], const double v[3])
{
    r[0] = u[0] - v[0];
    r[1] = u[1] - v[1];
    r[2] = u[2] - v[2];
}

static void cross3(double r[3], const double u[3], const double v[3])
{
    r[0] = u[1] * v[2] - u[2] * v[1];
    r[1] = u[2] * v[0] - u[0] * v[2];
    r[2] = u[0] * v[1] - u[1] * v[0];
}

static double triple(const double n[3], const double u[3], const double v[3])
{
    double w[3];
    cross3(w, u, v);
    return dot3(n, w);
}

/* a*b - c*d within about one ulp (Kahan: fma recovers the rounding error
 * of c*d exactly). */
static double diff_products(double a, double b, double c, double d)
{
    double cd = c * d;
    double err = fma(-c, d, cd);
    return fma(a, b, -cd) + err;
}

static void cross3_compensated(double r[3], const double u[3], const double v[3])
{
    r[0] = diff_products(u[1], v[2], u[2], v[1]);
    r[1] = diff_products(u[2], v[0], u[0], v[2]);
    r[2] = diff_products(u[0], v[1], u[1], v[0]);
}

/* Foot at x + t (y - x); xp = p - x, e = y - x. */
static double on_edge(const double x[3], const double e[3], const double xp[3], double t,
                      double foot[3])
{
    double r[3];
    for (int k = 0; k < 3; k++) {
        foot[k] = x[k] + t * e[k];
        r[k] = xp[k] - t * e[k];
    }
    return dot3(r, r);
}

static double clamp01(double t)
{
    return t < 0 ? 0 : (t > 1 ? 1 : t);
}

static double at_vertex(const double x[3], const double xp[3], double foot[3])
{
    foot[0] = x[0];
    foot[1] = x[1];
    foot[2] = x[2];
    return dot3(xp, xp);
}

static void set3(double w[3], double a, double b, double c)
{
    w[0] = a;
    w[1] = b;
    w[2] = c;
}

/* A triangle without a usable normal: the nearest of its three edges, the
 * first in the order ab, bc, ca on a tie. */
static double three_edges(const double *v[3], const double p[3], double foot[3], double bary[3])
{
    double best = INFINITY;
    for (int k = 0; k < 3; k++) {
        const double *x = v[k], *y = v[(k + 1) % 3];
        double e[3], xp[3], f[3];
        sub3(e, y, x);
        sub3(xp, p, x);
        double len = dot3(e, e);
        double t = len > 0 ? clamp01(dot3(e, xp) / len) : 0;
        double d2 = on_edge(x, e, xp, t, f);
        if (d2 < best || k == 0) {
            best = d2;
            foot[0] = f[0];
            foot[1] = f[1];
            foot[2] = f[2];
            bary[k] = 1 - t;
            bary[(k + 1) % 3] = t;
            bary[(k + 2) % 3] = 0;
        }
    }
    return best;
}

static double closest_on_triangle(const double p[3], const double a[3], const double b[3],
                                  const double c[3], double foot[3], double bary[3])
{
    double ab[3], bc[3], ca[3], ap[3], bp[3], cp[3];
    sub3(ab, b, a);
    sub3(ap, p, a);
    sub3(ca, a, c);
    double ab_ap = dot3(ab, ap), ca_ap = dot3(ca, ap);
    if (ab_ap <= 0 && ca_ap >= 0) {
        set3(bary, 1, 0, 0);
        return at_vertex(a, ap, foot);
    }
    sub3(bc, c, b);
    sub3(bp, p, b);
    double ab_bp = dot3(ab, bp), bc_bp = dot3(bc, bp);
    if (ab_bp >= 0 && bc_bp <= 0) {
        set3(bary, 0, 1, 0);
        return at_vertex(b, bp, foot);
    }
    sub3(cp, p, c);
    double bc_cp = dot3(bc, cp), ca_cp = dot3(ca, cp);
    if (bc_cp >= 0 && ca_cp <= 0) {
        set3(bary, 0, 0, 1);
        return at_vertex(c, cp, foot);
    }

    /* Corners x, y, z with xy the longest edge: the normal from the two
     * edges at z (the largest angle) is the best conditioned of the three
     * cross products, and xy is the base for the barycentric coordinates. */
    const double *edge[3] = {ab, bc, ca};
    double len[3] = {dot3(ab, ab), dot3(bc, bc), dot3(ca, ca)};
    double along[3] = {ab_ap, bc_bp, ca_cp}; /* edge i . (p - corner i) */
    int x = 0;
    if (len[1] >= len[0] && len[1] >= len[2])
        x = 1;
    else if (len[2] >= len[0] && len[2] >= len[1])
        x = 2;
    int y = (x + 1) % 3, z = (x + 2) % 3;
    double n[3];
    cross3(n, edge[y], edge[z]);
    double nn = dot3(n, n);
    if (nn < 1e-4 * len[y] * len[z]) { /* sine of the largest angle below 1e-2 */
        cross3_compensated(n, edge[y], edge[z]);
        nn = dot3(n, n);
    }
    const double *corner[3] = {a, b, c};
    if (!(nn > 0))
        return three_edges(corner, p, foot, bary);

    double wc = triple(n, ab, ap);
    if (wc <= 0 && ab_ap >= 0 && ab_bp <= 0) {
        double t = clamp01(ab_ap / len[0]);
        set3(bary, 1 - t, t, 0);
        return on_edge(a, ab, ap, t, foot);
    }
    double wa = triple(n, bc, bp);
    if (wa <= 0 && bc_bp >= 0 && bc_cp <= 0) {
        double t = clamp01(bc_bp / len[1]);
        set3(bary, 0, 1 - t, t);
        return on_edge(b, bc, bp, t, foot);
    }
    double wb = triple(n, ca, cp);
    if (wb <= 0 && ca_cp >= 0 && ca_ap <= 0) {
        double t = clamp01(ca_cp / len[2]);
        set3(bary, t, 0, 1 - t);
        return on_edge(c, ca, cp, t, foot);
    }
    /* Exact arithmetic never gets here with a weight <= 0; rounding can, on
     * the brink of an edge region, and then the edges decide. */
    if (!(wa > 0 && wb > 0 && wc > 0))
        return three_edges(corner, p, foot, bary);

    /* On a sliver the weights are individually uncertain (intrinsically: a
     * tiny move of the foot changes them a lot). Taking z's from its weight
     * and y's from the position along xy keeps sum(bary * corner) on the
     * foot whatever that uncertainty. */
    double w[3] = {wa, wb, wc};
    double bz = clamp01(w[z] / (wa + wb + wc));
    double by = (along[x] + bz * dot3(edge[z], edge[x])) / len[x];
    by = by < 0 ? 0 : (by > 1 - bz ? 1 - bz : by);
    bary[z] = bz;
    bary[y] = by;
    bary[x] = fmax(0, 1 - by - bz);
    /* Orthogonal projection: its distance is exact up to rounding, whatever
     * the accuracy of the weights. */
    double h = dot3(n, ap);
    double s = h / nn;
    for (int k = 0; k < 3; k++)
        foot[k] = p[k] - s * n[k];
    return h * h / nn;
}

double fm_closest_on_triangle(const double p[3], const double a[3], const double b[3],
                              const double c[3], double foot[3], double bary[3])
{
    double f[3], w[3];
    double d2 = closest_on_triangle(p, a, b, c, f, w);
    for (int k = 0; k < 3; k++) {
        if (foot)
            foot[k] = f[k];
        if (bary)
            bary[k] = w[k];
    }
    return d2;
}

static double box_dist2(const closest_node *N, const double q[3])
{
    double d2 = 0;
    for (int a = 0; a < 3; a++) {
        double lo = N->lo[a], hi = N->hi[a];
        double d = q[a] < lo ? lo - q[a] : (q[a] > hi ? q[a] - hi : 0);
        d2 += d * d;
    }
    return d2;
}

#if defined(__GNUC__)
#define PREFETCH(p) __builtin_prefetch(p)
#else
#define PREFETCH(p) ((void)(p))
#endif

/* Random queries on a large mesh wait on memory, not arithmetic: what lies
 * below a child is requested while the children's boxes are measured. */
static void prefetch_below(const fm_closest_tree *t, const closest_node *c)
{
    if (c->count)
        PREFETCH(t->tri + 3 * (size_t)c->first);
    else
        PREFETCH(&t->nodes[c->first]);
}

/* p in the tree's frame (coordinates relative to its centre, where the
 * boxes and triangles are stored): 0 when there is nothing to search (no
 * tree, a negative bound, a non-finite point). */
static int query_point(const fm_closest_tree *t, const double p[3], double max_dist, double q[3])
{
    if (!t || t->nnode == 0 || !p || !(max_dist >= 0))
        return 0;
    for (int a = 0; a < 3; a++) {
        q[a] = p[a] - t->centre[a];
        if (!isfinite(q[a]))
            return 0;
    }
    return 1;
}

typedef struct pending {
    int32_t node;
    double d2;
} pending;

/* Boxes at exactly the best distance are still opened (<=, not <), so that
 * an equally close triangle of lower index is never pruned away. */
int fm_closest_query(const fm_closest_tree *t, const double p[3], double max_dist,
                     fm_closest_hit *hit)
{
    double q[3];
    if (!query_point(t, p, max_dist, q))
        return 0;
    double best = max_dist * max_dist, best_foot[3] = {0}, best_bary[3] = {0};
    int32_t best_tri = -1;
    pending stack[CLOSEST_STACK];
    int sp = 0;
    int32_t node = 0;
    if (box_dist2(&t->nodes[0], q) > best)
        return 0;
    for (;;) {
        const closest_node *N = &t->nodes[node];
        if (N->count == 0) {
            int32_t near = N->first, far = near + 1;
            prefetch_below(t, &t->nodes[near]);
            prefetch_below(t, &t->nodes[far]);
            double dn = box_dist2(&t->nodes[near], q), df = box_dist2(&t->nodes[far], q);
            if (df < dn) {
                int32_t tn = near;
                near = far, far = tn;
                double td = dn;
                dn = df, df = td;
            }
            if (dn <= best) {
                if (df <= best)
                    stack[sp++] = (pending){far, df};
                node = near;
                continue;
            }
        } else {
            for (size_t s = (size_t)N->first; s < (size_t)N->first + (size_t)N->count; s++) {
                const int32_t *v = t->tri + 3 * s;
                double f[3], w[3];
                double d2 = closest_on_triangle(q, t->xyz + 3 * (size_t)v[0],
                                                t->xyz + 3 * (size_t)v[1],
                                                t->xyz + 3 * (size_t)v[2], f, w);
                int32_t orig = t->orig[s];
                if (d2 < best || (d2 == best && (best_tri < 0 || orig < best_tri))) {
                    best = d2;
                    best_tri = orig;
                    for (int k = 0; k < 3; k++) {
                        best_foot[k] = f[k];
                        best_bary[k] = w[k];
                    }
                }
            }
        }
        do {
            if (sp == 0)
                goto done;
            sp--;
        } while (stack[sp].d2 > best);
        node = stack[sp].node;
    }
done:
    if (best_tri < 0)
        return 0;
    if (hit) {
        hit->dist = sqrt(best);
        hit->triangle = best_tri;
        for (int k = 0; k < 3; k++) {
            hit->foot[k] = best_foot[k] + t->centre[k];
            hit->bary[k] = best_bary[k];
        }
    }
    return 1;
}

static double slot_dist2(const fm_closest_tree *t, size_t s, const double q[3])
{
    const int32_t *v = t->tri + 3 * s;
    double f[3], w[3];
    return closest_on_triangle(q, t->xyz + 3 * (size_t)v[0], t->xyz + 3 * (size_t)v[1],
                               t->xyz + 3 * (size_t)v[2], f, w);
}

/* The same search and the same test per triangle as fm_closest_query, but
 * done at the first triangle within the bound; the hint's triangle (a
 * slot) is tried before any search. */
int fm_closest_within(const fm_closest_tree *t, const double p[3], double max_dist,
                      int32_t *hint)
{
    double q[3];
    if (!query_point(t, p, max_dist, q))
        return 0;
    double best = max_dist * max_dist;
    if (hint && *hint >= 0 && (size_t)*hint < t->ntri && slot_dist2(t, (size_t)*hint, q) <= best)
        return 1;
    int32_t stack[CLOSEST_STACK];
    int sp = 0;
    int32_t node = 0;
    if (box_dist2(&t->nodes[0], q) > best)
        return 0;
    for (;;) {
        const closest_node *N = &t->nodes[node];
        if (N->count == 0) {
            int32_t near = N->first, far = near + 1;
            prefetch_below(t, &t->nodes[near]);
            prefetch_below(t, &t->nodes[far]);
            double dn = box_dist2(&t->nodes[near], q), df = box_dist2(&t->nodes[far], q);
            if (df < dn) {
                int32_t tn = near;
                near = far, far = tn;
                double td = dn;
                dn = df, df = td;
            }
            if (dn <= best) {
                if (df <= best)
                    stack[sp++] = far;
                node = near;
                continue;
            }
        } else {
            for (size_t s = (size_t)N->first; s < (size_t)N->first + (size_t)N->count; s++)
                if (slot_dist2(t, s, q) <= best) {
                    if (hint)
                        *hint = (int32_t)s;
                    return 1;
                }
        }
        if (sp == 0)
            return 0;
        node = stack[--sp];
    }
}
