/* The public TDE entry points: frame, input checks, the vertex/edge NaN
 * rule of the reference, and strains by complex-step differentiation of
 * the displacement (exact to rounding, no step-size trade-off). */
#include <math.h>
#include <stddef.h>

#include "fm_elastic.h"
#include "tde_internal.h"

int fm_tde_frame(const double tri[3][3], double n[3], double s[3], double d[3])
{
    double a[3], b[3];
    for (int k = 0; k < 3; k++) {
        a[k] = tri[1][k] - tri[0][k];
        b[k] = tri[2][k] - tri[0][k];
    }
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double al = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    double bl = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    if (!(nl > 1e-14 * al * bl))
        return FM_ELASTIC_EDEGENERATE;
    for (int k = 0; k < 3; k++)
        n[k] /= nl;
    /* s = z x n = (-ny, nx, 0) */
    double sl = hypot(n[0], n[1]);
    if (sl > 0) {
        s[0] = -n[1] / sl;
        s[1] = n[0] / sl;
        s[2] = 0;
    } else {
        s[0] = 0;
        s[1] = n[2] > 0 ? 1 : -1;
        s[2] = 0;
    }
    d[0] = n[1] * s[2] - n[2] * s[1];
    d[1] = n[2] * s[0] - n[0] * s[2];
    d[2] = n[0] * s[1] - n[1] * s[0];
    return 0;
}

/* Burgers vector in EFCS from slip in the TD frame. */
static int burgers(const double tri[3][3], const double slip[3], double bv[3])
{
    double n[3], s[3], d[3];
    int rc = fm_tde_frame(tri, n, s, d);
    if (rc)
        return rc;
    for (int k = 0; k < 3; k++)
        bv[k] = slip[0] * s[k] + slip[1] * d[k] + slip[2] * n[k];
    return 0;
}

static double edge_len_max(const double tri[3][3])
{
    double m = 0;
    for (int v = 0; v < 3; v++) {
        const double *p = tri[v], *q = tri[(v + 1) % 3];
        double l = sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) +
                        (q[2] - p[2]) * (q[2] - p[2]));
        m = l > m ? l : m;
    }
    return m;
}

/* 1 when x lies on an edge or a vertex (to rounding): the field is
 * singular there and the reference returns NaN. */
static int on_edge(const double x[3], const double tri[3][3], double tol)
{
    for (int v = 0; v < 3; v++) {
        const double *p = tri[v], *q = tri[(v + 1) % 3];
        double e[3], w[3], ee = 0, we = 0;
        for (int k = 0; k < 3; k++) {
            e[k] = q[k] - p[k];
            w[k] = x[k] - p[k];
            ee += e[k] * e[k];
            we += w[k] * e[k];
        }
        double t = we / ee;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        double dd = 0;
        for (int k = 0; k < 3; k++) {
            double c = w[k] - t * e[k];
            dd += c * c;
        }
        if (sqrt(dd) <= tol)
            return 1;
    }
    return 0;
}

void fm_tde_fs_cx(const fm_cx x[3], const double tri[3][3], const double b[3], double nu,
                  fm_cx u[3])
{
    fm_cx ul[3], us[3];
    fm_tde_lines_fs(x, tri, b, nu, ul);
    fm_tde_solid_angle_term(x, tri, b, us);
    for (int k = 0; k < 3; k++)
        u[k] = ul[k] + us[k];
}

static int prepare(const double obs[3], const double tri[3][3], const double slip[3], double nu,
                   int hs, double bv[3])
{
    if (hs) {
        if (obs[2] > 0 || tri[0][2] > 0 || tri[1][2] > 0 || tri[2][2] > 0)
            return FM_ELASTIC_EOUTSIDE;
    }
    if (!(nu > -1 && nu < 0.5))
        return FM_ELASTIC_EDEGENERATE;
    return burgers(tri, slip, bv);
}

static int disp(const double obs[3], const double tri[3][3], const double slip[3], double nu,
                int hs, double u[3])
{
    double bv[3];
    int rc = prepare(obs, tri, slip, nu, hs, bv);
    if (rc)
        return rc;
    if (on_edge(obs, tri, 1e-12 * edge_len_max(tri))) {
        u[0] = u[1] = u[2] = NAN;
        return 0;
    }
    fm_cx x[3] = {obs[0], obs[1], obs[2]}, uc[3];
    fm_tde_fs_cx(x, tri, bv, nu, uc);
    double uh[3] = {0, 0, 0};
    if (hs)
        fm_tde_hs_integral(obs, tri, bv, nu, 0, uh, NULL);
    for (int k = 0; k < 3; k++)
        u[k] = creal(uc[k]) + uh[k];
    return 0;
}

static int strain(const double obs[3], const double tri[3][3], const double slip[3], double nu,
                  int hs, double eps[6])
{
    double bv[3];
    int rc = prepare(obs, tri, slip, nu, hs, bv);
    if (rc)
        return rc;
    double len = edge_len_max(tri);
    if (on_edge(obs, tri, 1e-12 * len)) {
        for (int k = 0; k < 6; k++)
            eps[k] = NAN;
        return 0;
    }
    /* The step only has to keep h^2 terms below rounding of the real
     * parts; 1e-30 of the element size does, and stays far from
     * underflow. */
    double h = 1e-30 * len, g[3][3];
    for (int j = 0; j < 3; j++) {
        fm_cx x[3] = {obs[0], obs[1], obs[2]}, uc[3];
        x[j] += I * h;
        fm_tde_fs_cx(x, tri, bv, nu, uc);
        for (int k = 0; k < 3; k++)
            g[k][j] = cimag(uc[k]) / h; /* du_k / dx_j */
    }
    if (hs) {
        double uh[3], gh[3][3];
        fm_tde_hs_integral(obs, tri, bv, nu, 0, uh, gh);
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++)
                g[k][j] += gh[k][j];
    }
    eps[0] = g[0][0];
    eps[1] = g[1][1];
    eps[2] = g[2][2];
    eps[3] = 0.5 * (g[0][1] + g[1][0]);
    eps[4] = 0.5 * (g[0][2] + g[2][0]);
    eps[5] = 0.5 * (g[1][2] + g[2][1]);
    return 0;
}

int fm_tde_disp_fs(const double obs[3], const double tri[3][3], const double slip[3], double nu,
                   double u[3])
{
    return disp(obs, tri, slip, nu, 0, u);
}

int fm_tde_strain_fs(const double obs[3], const double tri[3][3], const double slip[3], double nu,
                     double eps[6])
{
    return strain(obs, tri, slip, nu, 0, eps);
}

int fm_tde_disp_hs(const double obs[3], const double tri[3][3], const double slip[3], double nu,
                   double u[3])
{
    return disp(obs, tri, slip, nu, 1, u);
}

int fm_tde_strain_hs(const double obs[3], const double tri[3][3], const double slip[3], double nu,
                     double eps[6])
{
    return strain(obs, tri, slip, nu, 1, eps);
}

void fm_tde_stress_from_strain(const double eps[6], double mu, double lambda, double sig[6])
{
    double tr = eps[0] + eps[1] + eps[2];
    for (int k = 0; k < 6; k++)
        sig[k] = 2 * mu * eps[k] + (k < 3 ? lambda * tr : 0);
}
