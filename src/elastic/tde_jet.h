/* A forward-mode derivative "jet" for the half-space correction kernel:
 * value, gradient in the source point (a), gradient in the observation
 * point (b) and the mixed second derivatives (ab). The Volterra integral
 * needs the source gradient of Mindlin's Green's function, the strain its
 * observation gradient too; jets give both exactly, with no step size. */
#ifndef FM_TDE_JET_H
#define FM_TDE_JET_H

#include <math.h>

typedef struct fm_jet {
    double v, a[3], b[3], ab[3][3];
} fm_jet;

static inline fm_jet jc(double v)
{
    fm_jet r = {0};
    r.v = v;
    return r;
}

static inline fm_jet jlin(fm_jet x, double s, fm_jet y, double t) /* s x + t y */
{
    fm_jet r;
    r.v = s * x.v + t * y.v;
    for (int i = 0; i < 3; i++) {
        r.a[i] = s * x.a[i] + t * y.a[i];
        r.b[i] = s * x.b[i] + t * y.b[i];
        for (int j = 0; j < 3; j++)
            r.ab[i][j] = s * x.ab[i][j] + t * y.ab[i][j];
    }
    return r;
}

static inline fm_jet jadd(fm_jet x, fm_jet y) { return jlin(x, 1, y, 1); }
static inline fm_jet jsub(fm_jet x, fm_jet y) { return jlin(x, 1, y, -1); }
static inline fm_jet jscale(fm_jet x, double s) { return jlin(x, s, x, 0); }

static inline fm_jet jaddc(fm_jet x, double c)
{
    x.v += c;
    return x;
}

static inline fm_jet jmul(fm_jet x, fm_jet y)
{
    fm_jet r;
    r.v = x.v * y.v;
    for (int i = 0; i < 3; i++) {
        r.a[i] = x.v * y.a[i] + x.a[i] * y.v;
        r.b[i] = x.v * y.b[i] + x.b[i] * y.v;
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r.ab[i][j] = x.v * y.ab[i][j] + x.ab[i][j] * y.v + x.a[i] * y.b[j] +
                         y.a[i] * x.b[j];
    return r;
}

/* f(x) given f, f', f'' at x.v */
static inline fm_jet jfun(fm_jet x, double f, double f1, double f2)
{
    fm_jet r;
    r.v = f;
    for (int i = 0; i < 3; i++) {
        r.a[i] = f1 * x.a[i];
        r.b[i] = f1 * x.b[i];
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r.ab[i][j] = f1 * x.ab[i][j] + f2 * x.a[i] * x.b[j];
    return r;
}

static inline fm_jet jinv(fm_jet x)
{
    double i = 1 / x.v;
    return jfun(x, i, -i * i, 2 * i * i * i);
}

static inline fm_jet jdiv(fm_jet x, fm_jet y) { return jmul(x, jinv(y)); }

static inline fm_jet jsqrt(fm_jet x)
{
    double s = sqrt(x.v);
    return jfun(x, s, 0.5 / s, -0.25 / (s * x.v));
}

static inline fm_jet jpowi(fm_jet x, int n) /* x^n, n >= 1 */
{
    fm_jet r = x;
    for (int k = 1; k < n; k++)
        r = jmul(r, x);
    return r;
}

#endif
