/* Solving a curve point onto both surfaces. */
#include <math.h>
#include <string.h>

#include "connect_internal.h"
#include "connect_solve.h"
#include "fm_vec3.h"

/* Residual F (4) and Jacobian J (4 x 4, row-major) at x. */
static void residual(const fm_fit_surface *A, const fm_fit_surface *B, const double x[4],
                     const double p0[3], const double T[3], double F[4], double J[16])
{
    double sa[3], sau[3], sav[3], sb[3], sbu[3], sbv[3];
    fm_fit_surface_eval(A, x[0], x[1], sa, sau, sav);
    fm_fit_surface_eval(B, x[2], x[3], sb, sbu, sbv);
    for (int k = 0; k < 3; k++) {
        F[k] = sa[k] - sb[k];
        if (J) {
            J[4 * k + 0] = sau[k];
            J[4 * k + 1] = sav[k];
            J[4 * k + 2] = -sbu[k];
            J[4 * k + 3] = -sbv[k];
        }
    }
    double d[3] = {sa[0] - p0[0], sa[1] - p0[1], sa[2] - p0[2]};
    F[3] = fm_dot3(T, d);
    if (J) {
        J[12] = fm_dot3(T, sau);
        J[13] = fm_dot3(T, sav);
        J[14] = 0;
        J[15] = 0;
    }
}

static double gap_norm(const double F[4]) { return sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]); }

/* Solves the 4 x 4 SPD system M y = r by Cholesky; 0 when not definite. */
static int chol4(double M[16], double r[4])
{
    for (int j = 0; j < 4; j++) {
        double d = M[5 * j];
        for (int k = 0; k < j; k++)
            d -= M[4 * j + k] * M[4 * j + k];
        if (!(d > 0))
            return 0;
        d = sqrt(d);
        M[5 * j] = d;
        for (int i = j + 1; i < 4; i++) {
            double s = M[4 * i + j];
            for (int k = 0; k < j; k++)
                s -= M[4 * i + k] * M[4 * j + k];
            M[4 * i + j] = s / d;
        }
    }
    for (int i = 0; i < 4; i++) {
        double s = r[i];
        for (int k = 0; k < i; k++)
            s -= M[4 * i + k] * r[k];
        r[i] = s / M[5 * i];
    }
    for (int i = 3; i >= 0; i--) {
        double s = r[i];
        for (int k = i + 1; k < 4; k++)
            s -= M[4 * k + i] * r[k];
        r[i] = s / M[5 * i];
    }
    return 1;
}

/* Levenberg-Marquardt on the residual; returns the final gap. */
static double lm(const fm_fit_surface *A, const fm_fit_surface *B, double x[4], const double p0[3],
                 const double T[3], double tol)
{
    double F[4], J[16];
    residual(A, B, x, p0, T, F, J);
    double f = fm_dot3(F, F) + F[3] * F[3];
    double mu = 1e-12;
    for (int it = 0; it < 60 && gap_norm(F) > tol; it++) {
        double M[16], g[4];
        for (int i = 0; i < 4; i++) {
            g[i] = 0;
            for (int r = 0; r < 4; r++)
                g[i] -= J[4 * r + i] * F[r];
            for (int j = 0; j < 4; j++) {
                double s = 0;
                for (int r = 0; r < 4; r++)
                    s += J[4 * r + i] * J[4 * r + j];
                M[4 * i + j] = s;
            }
        }
        int accepted = 0;
        for (int tries = 0; tries < 12 && !accepted; tries++) {
            double Mk[16], y[4];
            memcpy(Mk, M, sizeof Mk);
            memcpy(y, g, sizeof y);
            for (int i = 0; i < 4; i++)
                Mk[5 * i] += mu * (M[5 * i] + 1e-12);
            if (!chol4(Mk, y)) {
                mu = mu * 100 + 1e-12;
                continue;
            }
            double xn[4] = {x[0] + y[0], x[1] + y[1], x[2] + y[2], x[3] + y[3]}, Fn[4], Jn[16];
            residual(A, B, xn, p0, T, Fn, Jn);
            double fn = fm_dot3(Fn, Fn) + Fn[3] * Fn[3];
            if (isfinite(fn) && fn <= f) {
                memcpy(x, xn, sizeof xn);
                memcpy(F, Fn, sizeof Fn);
                memcpy(J, Jn, sizeof Jn);
                double step = fabs(y[0]) + fabs(y[1]) + fabs(y[2]) + fabs(y[3]);
                accepted = 1;
                mu = fmax(mu * 0.1, 1e-15);
                if (fn == f && step == 0)
                    return gap_norm(F);
                f = fn;
            } else {
                mu *= 10;
            }
        }
        if (!accepted)
            break;
    }
    return gap_norm(F);
}

double cn_solve_point(const fm_fit_surface *A, const fm_fit_surface *B, double x[4],
                      const double p0[3], const double T[3], double tol, int *fallback)
{
    double x0[4];
    memcpy(x0, x, sizeof x0);
    double g = lm(A, B, x, p0, T, tol);
    *fallback = 0;
    if (g <= tol)
        return g;
    /* Alternating closest-point projections from the start point, then
     * another damped Newton from where they end. */
    double p[3], fa[3], fb[3], uva[2], uvb[2];
    memcpy(p, p0, sizeof p);
    for (int it = 0; it < 400; it++) {
        fm_fit_project(A, p, uva, fa, NULL);
        fm_fit_project(B, fa, uvb, fb, NULL);
        double d[3] = {fa[0] - fb[0], fa[1] - fb[1], fa[2] - fb[2]};
        memcpy(p, fb, sizeof p);
        if (sqrt(fm_dot3(d, d)) <= tol)
            break;
    }
    double y[4] = {uva[0], uva[1], uvb[0], uvb[1]};
    double gy = lm(A, B, y, p, T, tol);
    *fallback = 1;
    if (gy < g) {
        memcpy(x, y, sizeof y);
        g = gy;
    }
    return g;
}

double cn_crossing_angle(const fm_fit_surface *A, const fm_fit_surface *B, const double x[4])
{
    double p[3], au[3], av[3], bu[3], bv[3];
    fm_fit_surface_eval(A, x[0], x[1], p, au, av);
    fm_fit_surface_eval(B, x[2], x[3], p, bu, bv);
    double na[3] = {au[1] * av[2] - au[2] * av[1], au[2] * av[0] - au[0] * av[2],
                    au[0] * av[1] - au[1] * av[0]};
    double nb[3] = {bu[1] * bv[2] - bu[2] * bv[1], bu[2] * bv[0] - bu[0] * bv[2],
                    bu[0] * bv[1] - bu[1] * bv[0]};
    double c = fabs(fm_dot3(na, nb)) / sqrt(fm_dot3(na, na) * fm_dot3(nb, nb));
    double cr[3] = {na[1] * nb[2] - na[2] * nb[1], na[2] * nb[0] - na[0] * nb[2],
                    na[0] * nb[1] - na[1] * nb[0]};
    double s = sqrt(fm_dot3(cr, cr)) / sqrt(fm_dot3(na, na) * fm_dot3(nb, nb));
    return atan2(s, c) * (180.0 / 3.14159265358979323846);
}
