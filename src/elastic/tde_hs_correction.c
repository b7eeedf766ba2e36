/* The half space minus the full space: Volterra's integral of the slip
 * against the part of Mindlin's (1936) half-space Green's function that
 * Kelvin's full-space one lacks (the image and free-surface terms). That
 * part is smooth in the solid (its only singularity is the observation
 * point's mirror image above the surface), so it is integrated over the
 * triangle by Gauss rules on panels refined toward the mirror point; the
 * singular full-space part stays analytic (tde_lines_fs.c). */
#include <math.h>
#include <stddef.h>

#include "tde_internal.h"
#include "tde_jet.h"

/* Gauss orders by the panel's distance D from the mirror point over its
 * size h (panels are split until h <= D): an n-point rule's error falls
 * like rho^(-2n), rho ~ 4 D/h the Bernstein ellipse the singularity
 * allows. The table is measured: on 972 points from 3 sizes away to the
 * surface above surface-breaking and shallow triangles, u and its
 * gradient are within 2e-13 and 2e-12 (of their largest component) of
 * 12-point rules on panels four times smaller; 3 points only from 500
 * sizes (from 50 they would be 1e-11 off). */
#ifndef FM_TDE_QUAD_ORDERS /* overridable to measure */
#define FM_TDE_QUAD_ORDERS {12, 8, 5, 3}
#define FM_TDE_QUAD_RATIOS {1, 2, 15, 500}
#endif
enum { NORD = 4, MAXG = 16 };
static const int order[NORD] = FM_TDE_QUAD_ORDERS;
static const double min_ratio[NORD] = FM_TDE_QUAD_RATIOS;
/* Gauss-Legendre on [0,1] by Newton on the Legendre recurrence; computed
 * per call to stay free of shared mutable state (cheap: 16 nodes). */
static void gauss_legendre(int n, double x[], double w[])
{
    for (int i = 0; i < n; i++) {
        double t = cos(FM_TDE_PI * (i + 0.75) / (n + 0.5)), dp = 0;
        for (int it = 0; it < 100; it++) {
            double p0 = 1, p1 = t;
            for (int k = 2; k <= n; k++) {
                double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (t * p1 - p0) / (t * t - 1);
            double dt = p1 / dp;
            t -= dt;
            if (fabs(dt) < 1e-16)
                break;
        }
        x[i] = 0.5 * (1 - t);
        w[i] = 1 / ((1 - t * t) * dp * dp);
    }
}

/* Mindlin's Green's function, without Kelvin's terms (kelvin = 0) or
 * with only them (kelvin = 1, used by the tests of this construction),
 * in Mindlin's frame (x, y, depth), shear modulus 1:
 * g[k][m] = displacement m for a unit force k. X, Y: horizontal offset of
 * the observation point from the source, z, c: their depths. */
static void mindlin(fm_jet X, fm_jet Y, fm_jet z, fm_jet c, double nu, int kelvin,
                    fm_jet g[3][3])
{
    const double K = 1 / (16 * FM_TDE_PI * (1 - nu)), k1 = 3 - 4 * nu,
                 k2 = 4 * (1 - nu) * (1 - 2 * nu);
    fm_jet hor = jadd(jmul(X, X), jmul(Y, Y));
    fm_jet zmc = jsub(z, c), zpc = jadd(z, c);
    fm_jet H[2] = {X, Y};
    if (kelvin) {
        fm_jet iR = jinv(jsqrt(jadd(hor, jmul(zmc, zmc))));
        fm_jet iR3 = jpowi(iR, 3);
        fm_jet V[3] = {X, Y, zmc};
        for (int k = 0; k < 3; k++)
            for (int m = 0; m < 3; m++) {
                fm_jet t = jmul(jmul(V[k], V[m]), iR3);
                if (k == m)
                    t = jlin(t, 1, iR, k1);
                g[k][m] = jscale(t, K);
            }
        return;
    }
    fm_jet R = jsqrt(jadd(hor, jmul(zpc, zpc)));
    fm_jet iR = jinv(R), iR2 = jmul(iR, iR);
    fm_jet iR3 = jmul(iR2, iR), iR5 = jmul(iR3, iR2);
    fm_jet iA = jinv(jadd(R, zpc));
    fm_jet cz = jmul(c, z);
    for (int k = 0; k < 2; k++) {
        int o = 1 - k;
        fm_jet Hk = H[k], Ho = H[o], Hk2 = jmul(Hk, Hk);
        /* along the force */
        fm_jet t = jadd(iR, jscale(jmul(Hk2, iR3), k1));
        t = jadd(t, jscale(jmul(jmul(cz, iR3), jaddc(jscale(jmul(Hk2, iR2), -3), 1)), 2));
        t = jadd(t, jscale(jmul(iA, jaddc(jscale(jmul(jmul(Hk2, iR), iA), -1), 1)), k2));
        g[k][k] = jscale(t, K);
        /* the other horizontal direction */
        fm_jet s = jsub(jscale(iR3, k1), jscale(jmul(cz, iR5), 6));
        s = jsub(s, jscale(jmul(iR, jmul(iA, iA)), k2));
        g[k][o] = jscale(jmul(jmul(Hk, Ho), s), K);
        /* depth */
        fm_jet d = jsub(jscale(jmul(zmc, iR3), k1), jscale(jmul(jmul(cz, zpc), iR5), 6));
        d = jadd(d, jscale(jmul(iR, iA), k2));
        g[k][2] = jscale(jmul(Hk, d), K);
        /* vertical force, horizontal displacement */
        fm_jet v = jsub(jscale(jmul(zmc, iR3), k1), jscale(jmul(iR, iA), k2));
        v = jadd(v, jscale(jmul(jmul(cz, zpc), iR5), 6));
        g[2][k] = jscale(jmul(Hk, v), K);
    }
    fm_jet w = jscale(iR, 8 * (1 - nu) * (1 - nu) - k1);
    w = jadd(w, jmul(jsub(jscale(jmul(zpc, zpc), k1), jscale(cz, 2)), iR3));
    w = jadd(w, jscale(jmul(jmul(cz, jmul(zpc, zpc)), iR5), 6));
    g[2][2] = jscale(w, K);
}

typedef struct quad_ctx {
    double x[3], xm[3]; /* observation point and its mirror image */
    double mom[3][3];   /* moment density per unit area */
    double nu, tiny;
    double gx[NORD][MAXG], gw[NORD][MAXG];
    int kelvin;
    double u[3], grad[3][3];
} quad_ctx;

/* One Gauss node: adds w * M_kl dG_km/dxi_l (and its observation
 * gradient) in EFCS. */
static void node(quad_ctx *q, const double xi[3], double w)
{
    fm_jet X = jc(q->x[0] - xi[0]), Y = jc(q->x[1] - xi[1]);
    fm_jet z = jc(-q->x[2]), c = jc(-xi[2]);
    X.a[0] = -1;
    X.b[0] = 1;
    Y.a[1] = -1;
    Y.b[1] = 1;
    c.a[2] = -1;
    z.b[2] = -1;
    fm_jet g[3][3];
    mindlin(X, Y, z, c, q->nu, q->kelvin, g);
    static const double sgn[3] = {1, 1, -1};
    for (int k = 0; k < 3; k++)
        for (int m = 0; m < 3; m++) {
            double s = sgn[k] * sgn[m] * w;
            for (int l = 0; l < 3; l++) {
                if (q->mom[k][l] == 0)
                    continue;
                double f = s * q->mom[k][l];
                q->u[m] += f * g[k][m].a[l];
                for (int j = 0; j < 3; j++)
                    q->grad[m][j] += f * g[k][m].ab[l][j];
            }
        }
}

static void rule(quad_ctx *q, const double p[3][3], int o)
{
    double e1[3], e2[3], nn[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = p[1][k] - p[0][k];
        e2[k] = p[2][k] - p[1][k];
    }
    nn[0] = e1[1] * e2[2] - e1[2] * e2[1];
    nn[1] = e1[2] * e2[0] - e1[0] * e2[2];
    nn[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double area2 = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
    /* collapsed square (Duffy): xi = p0 + u e1 + u v e2, dA = 2A u du dv */
    const int ng = order[o];
    const double *gx = q->gx[o], *gw = q->gw[o];
    for (int i = 0; i < ng; i++)
        for (int j = 0; j < ng; j++) {
            double u = gx[i], v = gx[j], xi[3];
            for (int k = 0; k < 3; k++)
                xi[k] = p[0][k] + u * e1[k] + u * v * e2[k];
            node(q, xi, gw[i] * gw[j] * area2 * u);
        }
}

static double seg_dist2(const double x[3], const double a[3], const double b[3])
{
    double e[3], w[3], ee = 0, we = 0, d2 = 0;
    for (int k = 0; k < 3; k++) {
        e[k] = b[k] - a[k];
        w[k] = x[k] - a[k];
        ee += e[k] * e[k];
        we += w[k] * e[k];
    }
    double t = ee > 0 ? we / ee : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    for (int k = 0; k < 3; k++) {
        double c = w[k] - t * e[k];
        d2 += c * c;
    }
    return d2;
}

/* distance from x to the triangle p */
static double tri_dist(const double x[3], const double p[3][3])
{
    double e1[3], e2[3], w[3], n[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = p[1][k] - p[0][k];
        e2[k] = p[2][k] - p[0][k];
        w[k] = x[k] - p[0][k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    double wn = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
    /* barycentric coordinates of the projection */
    double a11 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
    double a12 = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2];
    double a22 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
    double b1 = w[0] * e1[0] + w[1] * e1[1] + w[2] * e1[2];
    double b2 = w[0] * e2[0] + w[1] * e2[1] + w[2] * e2[2];
    double det = a11 * a22 - a12 * a12;
    double u = (a22 * b1 - a12 * b2) / det, v = (a11 * b2 - a12 * b1) / det;
    if (u >= 0 && v >= 0 && u + v <= 1)
        return fabs(wn) / sqrt(nn);
    double d2 = seg_dist2(x, p[0], p[1]);
    d2 = fmin(d2, seg_dist2(x, p[1], p[2]));
    d2 = fmin(d2, seg_dist2(x, p[2], p[0]));
    return sqrt(d2);
}

#ifndef FM_TDE_QUAD_ETA
#define FM_TDE_QUAD_ETA 1.0
#endif

static void panel(quad_ctx *q, const double p[3][3], int depth)
{
    double h = 0;
    for (int v = 0; v < 3; v++) {
        double l = 0;
        for (int k = 0; k < 3; k++) {
            double t = p[(v + 1) % 3][k] - p[v][k];
            l += t * t;
        }
        h = fmax(h, sqrt(l));
    }
    double dist = tri_dist(q->xm, p);
    if (depth >= 40 || h <= q->tiny || h <= FM_TDE_QUAD_ETA * dist) {
        int o = 0;
        while (o + 1 < NORD && dist >= min_ratio[o + 1] * h)
            o++;
        rule(q, p, o);
        return;
    }
    double m[3][3];
    for (int v = 0; v < 3; v++)
        for (int k = 0; k < 3; k++)
            m[v][k] = 0.5 * (p[v][k] + p[(v + 1) % 3][k]);
    const double sub[4][3][3] = {
        {{p[0][0], p[0][1], p[0][2]}, {m[0][0], m[0][1], m[0][2]}, {m[2][0], m[2][1], m[2][2]}},
        {{m[0][0], m[0][1], m[0][2]}, {p[1][0], p[1][1], p[1][2]}, {m[1][0], m[1][1], m[1][2]}},
        {{m[2][0], m[2][1], m[2][2]}, {m[1][0], m[1][1], m[1][2]}, {p[2][0], p[2][1], p[2][2]}},
        {{m[0][0], m[0][1], m[0][2]}, {m[1][0], m[1][1], m[1][2]}, {m[2][0], m[2][1], m[2][2]}},
    };
    for (int s = 0; s < 4; s++)
        panel(q, sub[s], depth + 1);
}

void fm_tde_hs_integral(const double x[3], const double tri[3][3], const double b[3],
                        double nu, int kelvin, double u[3], double grad[3][3])
{
    quad_ctx q = {.nu = nu, .kelvin = kelvin};
    for (int o = 0; o < NORD; o++)
        gauss_legendre(order[o], q.gx[o], q.gw[o]);
    for (int k = 0; k < 3; k++) {
        q.x[k] = x[k];
        q.xm[k] = k == 2 && !kelvin ? -x[k] : x[k];
    }
    double n[3], e1[3], e2[3], h = 0;
    for (int k = 0; k < 3; k++) {
        e1[k] = tri[1][k] - tri[0][k];
        e2[k] = tri[2][k] - tri[0][k];
        h = fmax(h, fabs(e1[k]) + fabs(e2[k]));
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        n[k] /= nl;
    q.tiny = 1e-12 * h;
    /* moment density of the slip, shear modulus 1 */
    double lam = 2 * nu / (1 - 2 * nu), bn = b[0] * n[0] + b[1] * n[1] + b[2] * n[2];
    for (int k = 0; k < 3; k++)
        for (int l = 0; l < 3; l++)
            q.mom[k][l] = (k == l ? lam * bn : 0) + b[k] * n[l] + b[l] * n[k];
    panel(&q, tri, 0);
    for (int m = 0; m < 3; m++) {
        u[m] = q.u[m];
        if (grad)
            for (int j = 0; j < 3; j++)
                grad[m][j] = q.grad[m][j];
    }
}
