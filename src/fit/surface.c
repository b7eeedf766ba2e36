/* Evaluating a fitted surface: heights, points, derivatives, closest
 * points, and its layout as an ordinary B-spline. */
#include "fit_internal.h"

#include <math.h>
#include <stdlib.h>
#include "fm_vec3.h"

void fm_fit_surface_destroy(fm_fit_surface *s)
{
    if (!s)
        return;
    free(s->coef);
    free(s->knots_u);
    free(s->knots_v);
    free(s->vparams);
    free(s->starts);
    free(s);
}

fm_fit_kind fm_fit_surface_kind(const fm_fit_surface *s) { return s->kind; }
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
    /* The parametric kind's w coordinate is its last block. */
    return s->coef + (size_t)(s->ncomp - 1) * s->nu * s->nv;
}

void fm_fit_surface_control_points(const fm_fit_surface *s, double *xyz)
{
    /* The Greville abscissa of coefficient i on uniform knots is the mean of
     * its p inner knots: u0 + s (i - (p - 1) / 2). */
    for (size_t j = 0; j < s->nv; j++)
        for (size_t i = 0; i < s->nu; i++) {
            size_t k = j * s->nu + i, n = s->nu * s->nv;
            double uvw[3];
            if (s->ncomp == 3) {
                /* Linear in the coefficients: the control net is theirs. */
                uvw[0] = s->coef[k];
                uvw[1] = s->coef[n + k];
                uvw[2] = s->coef[2 * n + k];
            } else {
                uvw[0] = s->u0 + s->s * ((double)i - 0.5 * (s->p - 1));
                uvw[1] = s->v0 + s->s * ((double)j - 0.5 * (s->p - 1));
                uvw[2] = s->coef[k];
            }
            fm_fit_frame_to_world(&s->frame, uvw, xyz + 3 * k);
        }
}

double fm_fit_surface_height(const fm_fit_surface *s, double u, double v, double dh[5])
{
    return fm_fit_component(s, s->ncomp - 1, u, v, dh);
}

void fm_fit_basis_at(const fm_fit_surface *s, double u, double v, int deriv, fm_fit_at *at)
{
    double tu, tv;
    at->ju = fm_fit_locate(u, s->u0, s->s, s->nsu, &tu);
    at->jv = fm_fit_locate(v, s->v0, s->s, s->nsv, &tv);
    at->deriv = deriv;
    if (deriv) {
        fm_fit_basis(s->p, tu, at->Nu);
        fm_fit_basis(s->p, tv, at->Nv);
    } else {
        fm_fit_basis_values(s->p, tu, at->Nu);
        fm_fit_basis_values(s->p, tv, at->Nv);
    }
}

/* The contraction for degree p; inlined with p a constant for cubics, so
 * that its loops unroll (the same operations in the same order). */
static inline __attribute__((always_inline)) double
contract(const fm_fit_surface *s, int p, int comp, const fm_fit_at *at, double dh[5])
{
    const double *coef = s->coef + (size_t)comp * s->nu * s->nv;
    size_t ju = at->ju, jv = at->jv;
    const double(*Nu)[FM_FIT_MAX_DEGREE + 1] = at->Nu, (*Nv)[FM_FIT_MAX_DEGREE + 1] = at->Nv;
    /* Contract along u first: r[k][b] = sum_a N_u^(k)[a] c[a][b]. */
    double r[3][FM_FIT_MAX_DEGREE + 1];
    int kmax = dh ? 3 : 1;
    for (int b = 0; b <= p; b++) {
        const double *row = coef + (jv + (size_t)b) * s->nu + ju;
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

double fm_fit_component_at(const fm_fit_surface *s, int comp, const fm_fit_at *at, double dh[5])
{
    if (s->p == 3)
        return dh ? contract(s, 3, comp, at, dh) : contract(s, 3, comp, at, NULL);
    return contract(s, s->p, comp, at, dh);
}

double fm_fit_component(const fm_fit_surface *s, int comp, double u, double v, double dh[5])
{
    fm_fit_at at;
    fm_fit_basis_at(s, u, v, dh != NULL, &at);
    return fm_fit_component_at(s, comp, &at, dh);
}

void fm_fit_local_eval(const fm_fit_surface *s, double u, double v, double P[3],
                       double D[5][3])
{
    double d[5];
    if (s->ncomp == 1) {
        /* The height field is the parametric surface (u, v, h(u, v)). */
        P[0] = u;
        P[1] = v;
        P[2] = fm_fit_component(s, 0, u, v, D ? d : NULL);
        if (D) {
            static const double plane[5][2] = {{1, 0}, {0, 1}, {0, 0}, {0, 0}, {0, 0}};
            for (int k = 0; k < 5; k++) {
                D[k][0] = plane[k][0];
                D[k][1] = plane[k][1];
                D[k][2] = d[k];
            }
        }
        return;
    }
    fm_fit_at at;
    fm_fit_basis_at(s, u, v, D != NULL, &at);
    for (int c = 0; c < 3; c++) {
        P[c] = fm_fit_component_at(s, c, &at, D ? d : NULL);
        if (D)
            for (int k = 0; k < 5; k++)
                D[k][c] = d[k];
    }
}

void fm_fit_surface_eval(const fm_fit_surface *s, double u, double v, double xyz[3],
                         double du[3], double dv[3])
{
    double P[3], D[5][3];
    int deriv = du || dv;
    fm_fit_local_eval(s, u, v, P, deriv ? D : NULL);
    const fm_fit_frame *f = &s->frame;
    fm_fit_frame_to_world(f, P, xyz);
    for (int k = 0; k < 3; k++) {
        if (du)
            du[k] = D[0][0] * f->u[k] + D[0][1] * f->v[k] + D[0][2] * f->w[k];
        if (dv)
            dv[k] = D[1][0] * f->u[k] + D[1][1] * f->v[k] + D[1][2] * f->w[k];
    }
}

/* Half the squared distance from the local point q to S(u, v). */
static double half_dist2(const fm_fit_surface *s, const double q[3], double u, double v)
{
    double P[3];
    fm_fit_local_eval(s, u, v, P, NULL);
    double a = P[0] - q[0], b = P[1] - q[1], c = P[2] - q[2];
    return 0.5 * (a * a + b * b + c * c);
}

fm_status fm_fit_project_from(const fm_fit_surface *s, const double q[3], double uv[2],
                              double P[3], double *dist)
{
    /* f = |S - q|^2 / 2 has gradient J^T r and Hessian J^T J + r . S'' (r =
     * S - q). Newton where that Hessian is positive definite, Gauss-Newton
     * (always descent) elsewhere, with halving line search so f never
     * increases. */
    double u = uv[0], v = uv[1];
    double tol = 1e-9 * (s->s + fabs(u) + fabs(v));
    fm_status st = FM_ERR_NUMERIC;
    double D[5][3], r[3];
    fm_fit_local_eval(s, u, v, P, D);
    for (int k = 0; k < 3; k++)
        r[k] = P[k] - q[k];
    double f = 0.5 * fm_dot3(r, r);
    for (int it = 0; it < 60; it++) {
        double gu = fm_dot3(D[0], r), gv = fm_dot3(D[1], r);
        double Juu = fm_dot3(D[0], D[0]), Juv = fm_dot3(D[0], D[1]), Jvv = fm_dot3(D[1], D[1]);
        double Huu = Juu + fm_dot3(r, D[2]), Huv = Juv + fm_dot3(r, D[3]), Hvv = Jvv + fm_dot3(r, D[4]);
        double det = Huu * Hvv - Huv * Huv;
        if (!(Huu > 0 && det > 1e-12 * Huu * Hvv)) {
            Huu = Juu;
            Huv = Juv;
            Hvv = Jvv;
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
        fm_fit_local_eval(s, u, v, P, D);
        for (int k = 0; k < 3; k++)
            r[k] = P[k] - q[k];
        if (moved <= tol) {
            st = FM_OK;
            break;
        }
    }
    if (st != FM_OK) {
        /* Converged to rounding even if the last step was refused? The
         * gradient is measured against the parameter speed. */
        double g = hypot(fm_dot3(D[0], r), fm_dot3(D[1], r));
        double speed = sqrt(fmax(fm_dot3(D[0], D[0]), fm_dot3(D[1], D[1])));
        if (g <= 1e-9 * speed * (1 + sqrt(2 * f)))
            st = FM_OK;
    }
    uv[0] = u;
    uv[1] = v;
    if (dist) {
        /* Positive on the side S_u x S_v points to: w for a height field. */
        double n[3] = {D[0][1] * D[1][2] - D[0][2] * D[1][1], D[0][2] * D[1][0] - D[0][0] * D[1][2],
                       D[0][0] * D[1][1] - D[0][1] * D[1][0]};
        double nn = sqrt(fm_dot3(n, n)), d = sqrt(2 * f);
        *dist = nn > 0 ? -fm_dot3(r, n) / nn : d;
        /* Off the foot's normal only when the iteration stopped early. */
        if (fabs(*dist) < d * (1 - 1e-6))
            *dist = *dist < 0 ? -d : d;
    }
    return st;
}

fm_status fm_fit_project(const fm_fit_surface *s, const double p[3], double uv[2],
                         double foot[3], double *dist)
{
    double q[3], P[3];
    fm_fit_frame_to_local(&s->frame, p, q);
    if (s->ncomp == 1) {
        /* The plane projection of p is on the way to its foot. */
        uv[0] = q[0];
        uv[1] = q[1];
    } else {
        /* A parametric sheet can pass a point several times: start at the
         * nearest span centre. */
        size_t best = 0, n = s->nsu * s->nsv;
        double bd = INFINITY;
        for (size_t k = 0; k < n; k++) {
            const double *c = s->starts + 3 * k;
            double d = (c[0] - q[0]) * (c[0] - q[0]) + (c[1] - q[1]) * (c[1] - q[1]) +
                       (c[2] - q[2]) * (c[2] - q[2]);
            if (d < bd) {
                bd = d;
                best = k;
            }
        }
        uv[0] = s->u0 + ((double)(best % s->nsu) + 0.5) * s->s;
        uv[1] = s->v0 + ((double)(best / s->nsu) + 0.5) * s->s;
    }
    fm_status st = fm_fit_project_from(s, q, uv, P, dist);
    if (foot)
        fm_fit_frame_to_world(&s->frame, P, foot);
    return st;
}

fm_status fm_fit_sheet_vertex_params(const fm_fit_surface *s, const fm_mesh *sheet, double *uv,
                                     fm_error *err)
{
    size_t nv = fm_mesh_nvertices(sheet);
    if (s->kind == FM_FIT_PARAMETRIC) {
        if (nv != s->nvparams)
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                "fit: sheet has %zu vertices, the fitted one %zu", nv,
                                s->nvparams);
        for (size_t i = 0; i < 2 * nv; i++)
            uv[i] = s->vparams[i];
        return FM_OK;
    }
    const double *X = fm_mesh_vertices(sheet);
    for (size_t i = 0; i < nv; i++) {
        double q[3];
        fm_fit_frame_to_local(&s->frame, X + 3 * i, q);
        uv[2 * i] = q[0];
        uv[2 * i + 1] = q[1];
    }
    return FM_OK;
}
