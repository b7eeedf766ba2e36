/* Evaluating a fitted surface: heights, points, derivatives, closest
 * points, and its layout as an ordinary B-spline. */
#include "fit_internal.h"

#include <math.h>
#include <stdlib.h>

void fm_fit_surface_destroy(fm_fit_surface *s)
{
    if (!s)
        return;
    free(s->coef);
    free(s->knots_u);
    free(s->knots_v);
    free(s);
}

const fm_fit_frame *fm_fit_surface_frame(const fm_fit_surface *s) { return &s->frame; }
const fm_fit_stats *fm_fit_surface_stats(const fm_fit_surface *s) { return &s->stats; }
int fm_fit_surface_degree(const fm_fit_surface *s) { return s->p; }

void fm_fit_surface_domain(const fm_fit_surface *s, double dom[4])
{
    dom[0] = s->u0;
    dom[1] = s->u0 + (double)s->nsu * s->s;
    dom[2] = s->v0;
    dom[3] = s->v0 + (double)s->nsv * s->s;
}

const double *fm_fit_surface_knots(const fm_fit_surface *s, int dir, size_t *n)
{
    if (n)
        *n = (dir ? s->nsv : s->nsu) + 2 * (size_t)s->p + 1;
    return dir ? s->knots_v : s->knots_u;
}

const double *fm_fit_surface_heights(const fm_fit_surface *s, size_t *nu, size_t *nv)
{
    if (nu)
        *nu = s->nu;
    if (nv)
        *nv = s->nv;
    return s->coef;
}

void fm_fit_surface_control_points(const fm_fit_surface *s, double *xyz)
{
    /* The Greville abscissa of coefficient i on uniform knots is the mean of
     * its p inner knots: u0 + s (i - (p - 1) / 2). */
    for (size_t j = 0; j < s->nv; j++)
        for (size_t i = 0; i < s->nu; i++) {
            double uvw[3] = {s->u0 + s->s * ((double)i - 0.5 * (s->p - 1)),
                             s->v0 + s->s * ((double)j - 0.5 * (s->p - 1)),
                             s->coef[j * s->nu + i]};
            fm_fit_frame_to_world(&s->frame, uvw, xyz + 3 * (j * s->nu + i));
        }
}

double fm_fit_surface_height(const fm_fit_surface *s, double u, double v, double dh[5])
{
    int p = s->p;
    double tu, tv, Nu[3][FM_FIT_MAX_DEGREE + 1], Nv[3][FM_FIT_MAX_DEGREE + 1];
    size_t ju = fm_fit_locate(u, s->u0, s->s, s->nsu, &tu);
    size_t jv = fm_fit_locate(v, s->v0, s->s, s->nsv, &tv);
    if (dh) {
        fm_fit_basis(p, tu, Nu);
        fm_fit_basis(p, tv, Nv);
    } else {
        fm_fit_basis_values(p, tu, Nu);
        fm_fit_basis_values(p, tv, Nv);
    }
    /* Contract along u first: r[k][b] = sum_a N_u^(k)[a] c[a][b]. */
    double r[3][FM_FIT_MAX_DEGREE + 1];
    int kmax = dh ? 3 : 1;
    for (int b = 0; b <= p; b++) {
        const double *row = s->coef + (jv + (size_t)b) * s->nu + ju;
        for (int k = 0; k < kmax; k++) {
            double acc = 0;
            for (int a = 0; a <= p; a++)
                acc += Nu[k][a] * row[a];
            r[k][b] = acc;
        }
    }
    double h = 0, hu = 0, hv = 0, huu = 0, huv = 0, hvv = 0;
    for (int b = 0; b <= p; b++) {
        h += Nv[0][b] * r[0][b];
        if (dh) {
            hu += Nv[0][b] * r[1][b];
            hv += Nv[1][b] * r[0][b];
            huu += Nv[0][b] * r[2][b];
            huv += Nv[1][b] * r[1][b];
            hvv += Nv[2][b] * r[0][b];
        }
    }
    if (dh) {
        double is = 1.0 / s->s;
        dh[0] = hu * is;
        dh[1] = hv * is;
        dh[2] = huu * is * is;
        dh[3] = huv * is * is;
        dh[4] = hvv * is * is;
    }
    return h;
}

void fm_fit_surface_eval(const fm_fit_surface *s, double u, double v, double xyz[3],
                         double du[3], double dv[3])
{
    double dh[5];
    double h = fm_fit_surface_height(s, u, v, dh);
    const fm_fit_frame *f = &s->frame;
    double uvw[3] = {u, v, h};
    fm_fit_frame_to_world(f, uvw, xyz);
    for (int k = 0; k < 3; k++) {
        if (du)
            du[k] = f->u[k] + dh[0] * f->w[k];
        if (dv)
            dv[k] = f->v[k] + dh[1] * f->w[k];
    }
}

/* Half the squared distance from the local point q to S(u, v). */
static double half_dist2(const fm_fit_surface *s, const double q[3], double u, double v)
{
    double h = fm_fit_surface_height(s, u, v, NULL);
    double a = u - q[0], b = v - q[1], c = h - q[2];
    return 0.5 * (a * a + b * b + c * c);
}

fm_status fm_fit_project(const fm_fit_surface *s, const double p[3], double uv[2],
                         double foot[3], double *dist)
{
    /* In the orthonormal local frame S(u, v) = (u, v, h(u, v)), so the
     * gradient and Hessian of f = |S - q|^2 / 2 need only h and its first
     * and second derivatives. Newton where the Hessian is positive
     * definite, Gauss-Newton (always descent) elsewhere, with halving
     * line search so f never increases. */
    double q[3];
    fm_fit_frame_to_local(&s->frame, p, q);
    double u = q[0], v = q[1];
    double tol = 1e-9 * (s->s + fabs(u) + fabs(v));
    fm_status st = FM_ERR_NUMERIC;
    double dh[5], h = fm_fit_surface_height(s, u, v, dh);
    double f = 0.5 * ((h - q[2]) * (h - q[2]));
    for (int it = 0; it < 60; it++) {
        double e = h - q[2];
        double gu = (u - q[0]) + e * dh[0], gv = (v - q[1]) + e * dh[1];
        double Huu = 1 + dh[0] * dh[0] + e * dh[2];
        double Huv = dh[0] * dh[1] + e * dh[3];
        double Hvv = 1 + dh[1] * dh[1] + e * dh[4];
        double det = Huu * Hvv - Huv * Huv;
        if (!(Huu > 0 && det > 1e-12 * Huu * Hvv)) {
            Huu = 1 + dh[0] * dh[0];
            Huv = dh[0] * dh[1];
            Hvv = 1 + dh[1] * dh[1];
            det = Huu * Hvv - Huv * Huv;
        }
        double su = -(Hvv * gu - Huv * gv) / det, sv = -(-Huv * gu + Huu * gv) / det;
        if (!isfinite(su) || !isfinite(sv))
            break;
        double step = 1.0, fn = f, un = u, vn = v;
        for (int ls = 0; ls < 40; ls++) {
            un = u + step * su;
            vn = v + step * sv;
            fn = half_dist2(s, q, un, vn);
            if (fn <= f)
                break;
            step *= 0.5;
        }
        if (!(fn <= f))
            break;
        double moved = step * hypot(su, sv);
        u = un;
        v = vn;
        f = fn;
        h = fm_fit_surface_height(s, u, v, dh);
        if (moved <= tol) {
            st = FM_OK;
            break;
        }
    }
    if (st != FM_OK) {
        /* Converged to rounding even if the last step was refused? */
        double e = h - q[2];
        double g = hypot((u - q[0]) + e * dh[0], (v - q[1]) + e * dh[1]);
        if (g <= 1e-9 * (1 + sqrt(2 * f)))
            st = FM_OK;
    }
    uv[0] = u;
    uv[1] = v;
    double loc[3] = {u, v, h};
    if (foot)
        fm_fit_frame_to_world(&s->frame, loc, foot);
    if (dist) {
        /* Normal of (u, v, h) is (-h_u, -h_v, 1): sign of the w side. */
        double nn = sqrt(1 + dh[0] * dh[0] + dh[1] * dh[1]);
        *dist = (-(q[0] - u) * dh[0] - (q[1] - v) * dh[1] + (q[2] - h)) / nn;
    }
    return st;
}
