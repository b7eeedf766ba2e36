/* Physical checks of the TDE module on synthetic geometry (no data):
 * the slip jump across the triangle, the traction-free surface of the
 * half space (also for triangles that break the surface), a rectangle of
 * two triangles against Okada's (1985) closed-form surface displacement,
 * and the degenerate geometries where naive formulas divide by zero. */
#include "fm_elastic.h"
#include "fm_test.h"

static const double NU = 0.25;

static double norm3(const double v[3])
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

static int finite_n(const double *v, int n)
{
    for (int k = 0; k < n; k++)
        if (!isfinite(v[k]))
            return 0;
    return 1;
}

/* ---- (a) the jump across the triangle equals Ss s + Ds d + Ts n ---- */

static void check_jump(const double tri[3][3], const double slip[3], int hs, double delta,
                       double tol)
{
    double n[3], s[3], d[3];
    CHECK_EQ(fm_tde_frame(tri, n, s, d), 0);
    static const double bary[4][3] = {
        {1. / 3, 1. / 3, 1. / 3}, {0.6, 0.2, 0.2}, {0.1, 0.2, 0.7}, {0.45, 0.45, 0.1}};
    for (int i = 0; i < 4; i++) {
        double p[3], up[3], um[3];
        for (int k = 0; k < 3; k++)
            p[k] = bary[i][0] * tri[0][k] + bary[i][1] * tri[1][k] + bary[i][2] * tri[2][k];
        double a[3], b[3];
        for (int k = 0; k < 3; k++) {
            a[k] = p[k] + delta * n[k];
            b[k] = p[k] - delta * n[k];
        }
        int r1 = hs ? fm_tde_disp_hs(a, tri, slip, NU, up) : fm_tde_disp_fs(a, tri, slip, NU, up);
        int r2 = hs ? fm_tde_disp_hs(b, tri, slip, NU, um) : fm_tde_disp_fs(b, tri, slip, NU, um);
        CHECK_EQ(r1, 0);
        CHECK_EQ(r2, 0);
        for (int k = 0; k < 3; k++) {
            double want = slip[0] * s[k] + slip[1] * d[k] + slip[2] * n[k];
            CHECK_NEAR(up[k] - um[k], want, tol);
        }
    }
}

static void test_jump(void)
{
    const double dipping[3][3] = {{0, 0.1, -0.4}, {1, -0.2, -1.2}, {1, 1, -0.9}};
    const double vertical[3][3] = {{-1, 0, -2}, {1, 0, -2}, {0, 0, -0.5}};
    const double horizontal[3][3] = {{-1, 0, -1}, {1, 0, -1}, {0, 1, -1}};
    const double breaking[3][3] = {{0, 0, 0}, {1, 0.3, 0}, {0.4, 0.5, -1}};
    const double slips[3][3] = {{1, 0, 0}, {0, 1, 0}, {0.3, -0.7, 1.1}};
    const double (*tris[4])[3] = {dipping, vertical, horizontal, breaking};
    for (int t = 0; t < 4; t++)
        for (int s = 0; s < 3; s++)
            for (int hs = 0; hs < 2; hs++) {
                /* 1e-7 off the plane: the smooth part adds ~1e-7 |grad u| */
                check_jump(tris[t], slips[s], hs, 1e-7, 2e-6);
                check_jump(tris[t], slips[s], hs, 1e-11, 1e-9);
            }
}

/* The sanitizer build runs the surface grids at every GRID_STRIDE-th point:
 * the half space's quadrature near the surface is slow at -O0, and the
 * grids' purpose (every kind of point) holds on the coarser grid too. */
#ifndef GRID_STRIDE
#define GRID_STRIDE 1
#endif

/* ---- (b) the half space's free surface carries no traction ---- */

static void check_free_surface(const double tri[3][3], const double slip[3])
{
    double worst = 0, big = 0;
    for (int i = 0; i <= 12; i += GRID_STRIDE)
        for (int j = 0; j <= 12; j += GRID_STRIDE) {
            double x[3] = {-1.5 + 0.25 * i, -1.5 + 0.25 * j + 1e-3, 0}, eps[6], sig[6];
            CHECK_EQ(fm_tde_strain_hs(x, tri, slip, NU, eps), 0);
            if (!finite_n(eps, 6))
                continue; /* on the trace of an edge at the surface */
            fm_tde_stress_from_strain(eps, 1, 2 * NU / (1 - 2 * NU), sig);
            for (int k = 0; k < 6; k++)
                big = fmax(big, fabs(sig[k]));
            worst = fmax(worst, fmax(fabs(sig[2]), fmax(fabs(sig[4]), fabs(sig[5]))));
        }
    printf("free surface: max |szz, sxz, syz| / max |sigma| = %.2e\n", worst / big);
    CHECK(big > 0);
    CHECK(worst <= 1e-10 * big);
}

static void test_free_surface(void)
{
    const double buried[3][3] = {{0, 0.1, -0.1}, {1, -0.2, -0.2}, {1, 1, -0.3}};
    const double one_vertex[3][3] = {{0, 0, 0}, {1, 0.2, -0.6}, {0.2, 1, -0.8}};
    const double two_vertices[3][3] = {{-0.5, 0, 0}, {0.5, 0.2, 0}, {0.1, 0.6, -0.9}};
    const double vertical[3][3] = {{-1, 0, 0}, {1, 0, 0}, {0, 0, -1}};
    const double slip[3] = {1, 0.5, -0.3};
    check_free_surface(buried, slip);
    check_free_surface(one_vertex, slip);
    check_free_surface(two_vertices, slip);
    check_free_surface(vertical, slip);
}

/* ---- (c) a rectangle of two triangles against Okada (1985) ---- */

/* Okada (1985, BSSA 75:1135) surface displacement, eqs. (25)-(30): the
 * integrand f(xi, eta) of Chinnery's notation, for unit U1, U2, U3
 * (strike-slip, dip-slip, tensile), dip delta, mu/(lambda+mu) = 1-2nu. */
static void okada_f(double xi, double eta, double q, double dip, double nu, double out[3][3])
{
    double sd = sin(dip), cd = cos(dip), mr = 1 - 2 * nu;
    double yt = eta * cd + q * sd, dt = eta * sd - q * cd;
    double R = sqrt(xi * xi + eta * eta + q * q), X = sqrt(xi * xi + q * q);
    double th = q == 0 ? 0 : atan(xi * eta / (q * R));
    double I1, I2, I3, I4, I5;
    if (fabs(cd) > 1e-12) {
        I5 = xi == 0 ? 0
                     : mr * 2 / cd *
                           atan((eta * (X + q * cd) + X * (R + X) * sd) / (xi * (R + X) * cd));
        I4 = mr / cd * (log(R + dt) - sd * log(R + eta));
        I3 = mr * (yt / (cd * (R + dt)) - log(R + eta)) + sd / cd * I4;
        I2 = mr * -log(R + eta) - I3;
        I1 = mr * (-xi / (cd * (R + dt))) - sd / cd * I5;
    } else {
        double rd = R + dt;
        I1 = -mr / 2 * xi * q / (rd * rd);
        I3 = mr / 2 * (eta / rd + yt * q / (rd * rd) - log(R + eta));
        I4 = -mr * q / rd;
        I5 = -mr * xi * sd / rd;
        I2 = mr * -log(R + eta) - I3;
    }
    const double c = 1 / (2 * 3.14159265358979323846);
    double Re = R * (R + eta), Rx = R * (R + xi);
    /* strike-slip */
    out[0][0] = -c * (xi * q / Re + th + I1 * sd);
    out[0][1] = -c * (yt * q / Re + q * cd / (R + eta) + I2 * sd);
    out[0][2] = -c * (dt * q / Re + q * sd / (R + eta) + I4 * sd);
    /* dip-slip */
    out[1][0] = -c * (q / R - I3 * sd * cd);
    out[1][1] = -c * (yt * q / Rx + cd * th - I1 * sd * cd);
    out[1][2] = -c * (dt * q / Rx + sd * th - I5 * sd * cd);
    /* tensile */
    out[2][0] = c * (q * q / Re - I3 * sd * sd);
    out[2][1] = c * (-dt * q / Rx - sd * (xi * q / Re - th) - I1 * sd * sd);
    out[2][2] = c * (yt * q / Rx + cd * (xi * q / Re - th) - I5 * sd * sd);
}

/* Surface displacement at (x, y, 0) of a fault of length L along x from
 * x = 0, width W up-dip from its lower edge at depth d along y = 0. */
static void okada_surface(double x, double y, double d, double dip, double L, double W,
                          double nu, double u[3][3])
{
    double p = y * cos(dip) + d * sin(dip), q = y * sin(dip) - d * cos(dip);
    double f[3][3];
    for (int t = 0; t < 3; t++)
        for (int k = 0; k < 3; k++)
            u[t][k] = 0;
    const double xs[2] = {x, x - L}, es[2] = {p, p - W};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            okada_f(xs[i], es[j], q, dip, nu, f);
            double sg = (i == j) ? 1 : -1;
            for (int t = 0; t < 3; t++)
                for (int k = 0; k < 3; k++)
                    u[t][k] += sg * f[t][k];
        }
}

static void check_rectangle(double dip, double d, double L, double W)
{
    double cd = cos(dip), sd = sin(dip);
    /* corners: lower edge at depth d on y = 0, up-dip toward +y */
    double c0[3] = {0, 0, -d}, c1[3] = {L, 0, -d};
    double c2[3] = {L, W * cd, -d + W * sd}, c3[3] = {0, W * cd, -d + W * sd};
    /* vertex order: n = (P2-P1)x(P3-P1) points up, toward the hanging
     * wall, so the TD frame (s, d, n) is Okada's (strike, up-dip, normal) */
    double t1[3][3], t2[3][3];
    memcpy(t1[0], c0, sizeof c0);
    memcpy(t1[1], c1, sizeof c1);
    memcpy(t1[2], c2, sizeof c2);
    memcpy(t2[0], c0, sizeof c0);
    memcpy(t2[1], c2, sizeof c2);
    memcpy(t2[2], c3, sizeof c3);
    double worst = 0, big = 0;
    for (int t = 0; t < 3; t++) {
        double slip[3] = {0, 0, 0};
        slip[t] = 1;
        for (int i = 0; i <= 10; i += GRID_STRIDE)
            for (int j = 0; j <= 10; j += GRID_STRIDE) {
                double x[3] = {-2 + 0.5 * i + 0.013, -2.5 + 0.5 * j + 0.007, 0};
                double ua[3], ub[3], uo[3][3];
                CHECK_EQ(fm_tde_disp_hs(x, t1, slip, NU, ua), 0);
                CHECK_EQ(fm_tde_disp_hs(x, t2, slip, NU, ub), 0);
                okada_surface(x[0], x[1], d, dip, L, W, NU, uo);
                for (int k = 0; k < 3; k++) {
                    worst = fmax(worst, fabs(ua[k] + ub[k] - uo[t][k]));
                    big = fmax(big, fabs(uo[t][k]));
                }
            }
    }
    printf("rectangle dip %.0f deg: max |TDE - Okada| / max |Okada| = %.2e\n",
           dip * 180 / 3.14159265358979323846, worst / big);
    CHECK(worst <= 1e-8 * big);
}

static void test_okada_rectangle(void)
{
    const double deg = 3.14159265358979323846 / 180;
    check_rectangle(90 * deg, 2, 2, 1.5);
    check_rectangle(35 * deg, 1.5, 2, 1.2);
    check_rectangle(60 * deg, 1, 1.5, 1.1547005383792515); /* top edge at the surface */
}

/* ---- (d) degenerate geometries ---- */

/* finite at x and within tol of the value 1e-9 away along dir */
static void check_continuous(const double x[3], const double dir[3], const double tri[3][3],
                             const double slip[3], int hs, double tol)
{
    double u0[3], u1[3], e0[6], e1[6], y[3];
    for (int k = 0; k < 3; k++)
        y[k] = x[k] + 1e-9 * dir[k];
    int r = hs ? fm_tde_disp_hs(x, tri, slip, NU, u0) : fm_tde_disp_fs(x, tri, slip, NU, u0);
    r |= hs ? fm_tde_disp_hs(y, tri, slip, NU, u1) : fm_tde_disp_fs(y, tri, slip, NU, u1);
    r |= hs ? fm_tde_strain_hs(x, tri, slip, NU, e0) : fm_tde_strain_fs(x, tri, slip, NU, e0);
    r |= hs ? fm_tde_strain_hs(y, tri, slip, NU, e1) : fm_tde_strain_fs(y, tri, slip, NU, e1);
    CHECK_EQ(r, 0);
    CHECK(finite_n(u0, 3) && finite_n(e0, 6));
    double du[3] = {u0[0] - u1[0], u0[1] - u1[1], u0[2] - u1[2]};
    CHECK(norm3(du) <= tol);
    for (int k = 0; k < 6; k++)
        CHECK(fabs(e0[k] - e1[k]) <= 1e3 * tol);
    if (!(norm3(du) <= tol))
        fprintf(stderr, "  at (%.17g, %.17g, %.17g) hs %d: |du| %g\n", x[0], x[1], x[2], hs,
                norm3(du));
}

static void test_degenerate(void)
{
    const double slip[3] = {0.7, -0.4, 0.5};
    /* in the plane z = -1: a horizontal triangle */
    const double hz[3][3] = {{-1, 0, -1}, {1, 0, -1}, {0, 1, -1}};
    const double up[3] = {0, 0, 1}, side[3] = {0.6, 0.8, 0};
    for (int hs = 0; hs < 2; hs++) {
        /* on the plane inside: the +n side's value (n = +z here) */
        const double in[3] = {0.1, 0.3, -1};
        check_continuous(in, up, hz, slip, hs, 1e-7);
        /* on the plane outside, and on the extensions of the edges */
        const double outside[4][3] = {{2, 2, -1}, {3, 0, -1}, {-3, 0, -1}, {-0.5, 1.5, -1}};
        for (int i = 0; i < 4; i++) {
            check_continuous(outside[i], up, hz, slip, hs, 1e-7);
            check_continuous(outside[i], side, hz, slip, hs, 1e-7);
            double down[3] = {0, 0, -1};
            check_continuous(outside[i], down, hz, slip, hs, 1e-7);
        }
        /* directly below and above a vertex */
        const double below[3] = {0, 1, -2.5}, above[3] = {1, 0, -0.2};
        check_continuous(below, side, hz, slip, hs, 1e-7);
        check_continuous(above, side, hz, slip, hs, 1e-7);
        /* on an edge or a vertex: NaN, as the reference */
        const double on_edge[3] = {0.5, 0.5, -1}, on_vertex[3] = {1, 0, -1};
        double u[3], e[6];
        CHECK_EQ(hs ? fm_tde_disp_hs(on_edge, hz, slip, NU, u)
                    : fm_tde_disp_fs(on_edge, hz, slip, NU, u), 0);
        CHECK(isnan(u[0]) && isnan(u[1]) && isnan(u[2]));
        CHECK_EQ(hs ? fm_tde_strain_hs(on_vertex, hz, slip, NU, e)
                    : fm_tde_strain_fs(on_vertex, hz, slip, NU, e), 0);
        CHECK(isnan(e[0]) && isnan(e[5]));
    }
    /* a dipping triangle: its plane's points and its edges' extensions */
    const double dp[3][3] = {{0, 0.1, -0.4}, {1, -0.2, -1.2}, {1, 1, -0.9}};
    double n[3], s[3], d[3];
    fm_tde_frame(dp, n, s, d);
    for (int hs = 0; hs < 2; hs++)
        for (int v = 0; v < 3; v++) {
            const double *a = dp[v], *b = dp[(v + 1) % 3];
            for (int t = 0; t < 2; t++) {
                double f = t ? 1.7 : -0.6, x[3];
                for (int k = 0; k < 3; k++)
                    x[k] = a[k] + f * (b[k] - a[k]);
                if (hs && x[2] > 0)
                    continue;
                check_continuous(x, n, dp, slip, hs, 1e-7);
                check_continuous(x, s, dp, slip, hs, 1e-7);
                check_continuous(x, d, dp, slip, hs, 1e-7);
            }
        }
    /* vertices at the surface: points on the surface along the trace */
    const double br[3][3] = {{-0.5, 0, 0}, {0.5, 0.2, 0}, {0.1, 0.6, -0.9}};
    const double tr[3] = {1, 0.2, 0}, dn[3] = {0, 0, -1};
    const double on_trace[3][3] = {{1.5, 0.4, 0}, {-1.5, -0.2, 0}, {0.1, 0.1, 0}};
    for (int i = 0; i < 3; i++) {
        check_continuous(on_trace[i], tr, br, slip, 1, 1e-7);
        check_continuous(on_trace[i], dn, br, slip, 1, 1e-7);
    }
    /* obs directly below a surface vertex */
    const double under[3] = {-0.5, 0, -0.7};
    check_continuous(under, tr, br, slip, 1, 1e-7);
}

static void test_outside_and_codes(void)
{
    const double tri[3][3] = {{0, 0, -1}, {1, 0, -1}, {0, 1, -1}};
    const double slip[3] = {1, 0, 0}, above[3] = {0, 0, 0.1};
    double u[3], e[6];
    CHECK_EQ(fm_tde_disp_hs(above, tri, slip, NU, u), FM_ELASTIC_EOUTSIDE);
    CHECK_EQ(fm_tde_strain_hs(above, tri, slip, NU, e), FM_ELASTIC_EOUTSIDE);
    CHECK(FM_ELASTIC_EOUTSIDE < 0);
    const double high[3][3] = {{0, 0, 0.5}, {1, 0, -1}, {0, 1, -1}}, x[3] = {0, 0, -2};
    CHECK_EQ(fm_tde_disp_hs(x, high, slip, NU, u), FM_ELASTIC_EOUTSIDE);
    CHECK_EQ(fm_tde_disp_fs(x, high, slip, NU, u), 0);
    const double flat[3][3] = {{0, 0, -1}, {1, 0, -1}, {2, 0, -1}};
    CHECK(fm_tde_disp_fs(x, flat, slip, NU, u) < 0);
    /* the frame of the README's complex case */
    const double cx[3][3] = {{0, 0.1, 0.1}, {1, -0.2, -0.2}, {1, 1, 0.3}};
    double n[3], s[3], d[3];
    CHECK_EQ(fm_tde_frame(cx, n, s, d), 0);
    CHECK_NEAR(n[0], 0.159471, 1e-6);
    CHECK_NEAR(s[1], 0.387232, 1e-6);
    CHECK_NEAR(d[2], 0.411823, 1e-6);
    /* horizontal, n down: s = -y */
    const double hdown[3][3] = {{0, 0, -1}, {0, 1, -1}, {1, 0, -1}};
    CHECK_EQ(fm_tde_frame(hdown, n, s, d), 0);
    CHECK_NEAR(s[1], -1, 0);
    /* Hooke */
    const double eps[6] = {1, 2, 3, 4, 5, 6};
    double sig[6];
    fm_tde_stress_from_strain(eps, 2, 3, sig);
    CHECK_NEAR(sig[0], 2 * 2 * 1 + 3 * 6, 0);
    CHECK_NEAR(sig[3], 2 * 2 * 4, 0);
}

FM_TEST_MAIN(FM_CASE(test_jump), FM_CASE(test_free_surface), FM_CASE(test_okada_rectangle),
             FM_CASE(test_degenerate), FM_CASE(test_outside_and_codes))
