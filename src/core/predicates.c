#include "fm_predicates.h"

#include <math.h>

/* Error-free transformations: a+b = s+e and a*b = p+e exactly. The product
 * uses fma, which C17 guarantees to round once. */
static inline void two_sum(double a, double b, double *s, double *e)
{
    double x = a + b;
    double bv = x - a;
    double av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

static inline void two_product(double a, double b, double *p, double *e)
{
    double x = a * b;
    *p = x;
    *e = fma(a, b, -x);
}

/* Adds b to the nonoverlapping expansion e[0..n) (increasing magnitude);
 * the result, still nonoverlapping, has n+1 components. */
static int grow_expansion(double *e, int n, double b)
{
    double q = b;
    for (int i = 0; i < n; i++) {
        double s, h;
        two_sum(q, e[i], &s, &h);
        e[i] = h;
        q = s;
    }
    e[n] = q;
    return n + 1;
}

static int expansion_sign(const double *e, int n)
{
    for (int i = n - 1; i >= 0; i--)
        if (e[i] != 0.0)
            return e[i] > 0.0 ? 1 : -1;
    return 0;
}

#define EPSILON 1.1102230246251565e-16 /* 2^-53 */
#define CCW_ERRBOUND ((3.0 + 16.0 * EPSILON) * EPSILON)

/* The determinant expanded into products of raw coordinates, so that no
 * rounded difference enters the exact path:
 * ax*by - ax*cy - cx*by - ay*bx + ay*cx + cy*bx. */
static int orient2d_exact(const double *a, const double *b, const double *c)
{
    double e[12];
    int n = 0;
    const double f[6][2] = {{a[0], b[1]},  {-a[0], c[1]}, {-c[0], b[1]},
                            {-a[1], b[0]}, {a[1], c[0]},  {c[1], b[0]}};
    for (int i = 0; i < 6; i++) {
        double p, q;
        two_product(f[i][0], f[i][1], &p, &q);
        n = grow_expansion(e, n, q);
        n = grow_expansion(e, n, p);
    }
    return expansion_sign(e, n);
}

int fm_orient2d(const double *a, const double *b, const double *c)
{
    double l = (a[0] - c[0]) * (b[1] - c[1]);
    double r = (a[1] - c[1]) * (b[0] - c[0]);
    double det = l - r;
    double bound = CCW_ERRBOUND * (fabs(l) + fabs(r));
    if (det > bound)
        return 1;
    if (-det > bound)
        return -1;
    return orient2d_exact(a, b, c);
}

int fm_collinear3d(const double *a, const double *b, const double *c)
{
    /* Zero cross product <=> every coordinate projection is collinear. */
    for (int k = 0; k < 3; k++) {
        int i = k, j = (k + 1) % 3;
        double pa[2] = {a[i], a[j]}, pb[2] = {b[i], b[j]}, pc[2] = {c[i], c[j]};
        if (fm_orient2d(pa, pb, pc) != 0)
            return 0;
    }
    return 1;
}
