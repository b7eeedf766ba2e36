/* Knot removal of the IGES writer (src/write/iges_reduce.c): what it must
 * remove, what it must keep, and how far the surface it leaves is from the
 * one given, measured on a dense grid. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_test.h"
#include "fm_test_bspline.h"
#include "iges_internal.h"

#define P 3
#define MAXN 64

/* A net of our own (u fastest), copied into an iges_net for the reducer. */
typedef struct {
    size_t nu, nv;
    double ku[MAXN + P + 1], kv[MAXN + P + 1];
    double c[MAXN * MAXN][3];
} grid;

static void eval(const double *ku, const double *kv, size_t nu, size_t nv, const double *c,
                 double u, double v, double out[3])
{
    double Nu[P + 1], Nv[P + 1];
    size_t iu = fm_test_cubic_basis(ku, nu, u, Nu), iv = fm_test_cubic_basis(kv, nv, v, Nv);
    out[0] = out[1] = out[2] = 0;
    for (size_t b = 0; b <= P; b++)
        for (size_t a = 0; a <= P; a++)
            for (size_t x = 0; x < 3; x++)
                out[x] += Nu[a] * Nv[b] * c[3 * ((iv + b) * nu + iu + a) + x];
}

/* Boehm's insertion of t once, along u (d = 0) or v (d = 1): the same
 * surface on one knot more. */
static void insert(grid *g, int d, double t)
{
    double *U = d ? g->kv : g->ku;
    size_t n = d ? g->nv : g->nu, k = P;
    while (k + 1 < n && U[k + 1] <= t)
        k++;
    static double old[MAXN * MAXN][3];
    memcpy(old, g->c, sizeof old);
    size_t nu = g->nu, nu2 = d ? nu : nu + 1;
    for (size_t j = 0; j < (d ? nu : g->nv); j++)
        for (size_t i = 0; i <= n; i++) {
            double a = i <= k - P ? 1 : i > k ? 0 : (t - U[i]) / (U[i + P] - U[i]);
            for (int x = 0; x < 3; x++) {
                double pi = i < n ? old[d ? i * nu + j : j * nu + i][x] : 0;
                double pm = i > 0 ? old[d ? (i - 1) * nu + j : j * nu + i - 1][x] : 0;
                g->c[d ? i * nu2 + j : j * nu2 + i][x] = a * pi + (1 - a) * pm;
            }
        }
    memmove(U + k + 2, U + k + 1, (n + P - k) * sizeof *U);
    U[k + 1] = t;
    if (d)
        g->nv++;
    else
        g->nu++;
}

/* Clamped cubic knots on [0, 1000 spans] with the given interior knots. */
static void knots(double *U, size_t *n, const double *inner, size_t k, double end)
{
    size_t m = 0;
    for (int i = 0; i <= P; i++)
        U[m++] = 0;
    for (size_t i = 0; i < k; i++)
        U[m++] = inner[i];
    for (int i = 0; i <= P; i++)
        U[m++] = end;
    *n = m - P - 1;
}

static iges_net to_net(const grid *g)
{
    fm_iges_surface s = {P, P, g->nu, g->nv, g->ku, g->kv, &g->c[0][0], NULL, 0, 0, 0, 0};
    iges_window w = {0, g->nu, 0, g->nv, {g->ku[P], g->ku[g->nu], g->kv[P], g->kv[g->nv]}};
    iges_net net;
    CHECK_EQ(iges_net_copy(&s, &w, &net), FM_OK);
    return net;
}

/* Largest distance between the grid's surface and the net's on a k x k
 * grid over the range. */
static double deviation(const grid *g, const iges_net *net, int k)
{
    double worst = 0;
    for (int b = 0; b < k; b++)
        for (int a = 0; a < k; a++) {
            double u = g->ku[P] + (g->ku[g->nu] - g->ku[P]) * a / (k - 1);
            double v = g->kv[P] + (g->kv[g->nv] - g->kv[P]) * b / (k - 1);
            double x[3], y[3];
            eval(g->ku, g->kv, g->nu, g->nv, &g->c[0][0], u, v, x);
            eval(net->knots_u, net->knots_v, net->nu, net->nv, net->ctrl, u, v, y);
            worst = fmax(worst, sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                                     (x[2] - y[2]) * (x[2] - y[2])));
        }
    return worst;
}

/* A coarse surface in UTM-like coordinates: 6 x 5 points, interior knots
 * u 400, v 500 (metres), heights from a fixed formula (no symmetry that
 * could make a knot removable). */
static void coarse(grid *g)
{
    static const double iu[] = {400, 700}, iv[] = {500};
    knots(g->ku, &g->nu, iu, 2, 1000);
    knots(g->kv, &g->nv, iv, 1, 1000);
    for (size_t j = 0; j < g->nv; j++)
        for (size_t i = 0; i < g->nu; i++) {
            double *c = g->c[j * g->nu + i];
            c[0] = 400000 + 200.0 * (double)i;
            c[1] = 3750000 + 250.0 * (double)j;
            c[2] = -2000 + 13.0 * (double)((i * 7 + j * 3) % 5) + 5.0 * (double)(i * j);
        }
}

/* Knots inserted into a simpler surface all go again, and only they: the
 * net comes back to the simpler one's knots, its points within the
 * rounding of the insertion. */
static void test_inserted_knots_go(void)
{
    grid g, fine;
    coarse(&g);
    fine = g;
    const double tu[] = {100, 250, 400, 550, 850, 900}, tv[] = {120, 333, 500, 640, 910};
    for (size_t i = 0; i < sizeof tu / sizeof *tu; i++)
        insert(&fine, 0, tu[i]);
    for (size_t i = 0; i < sizeof tv / sizeof *tv; i++)
        insert(&fine, 1, tv[i]);
    CHECK_EQ(fine.nu, g.nu + 6);
    CHECK_EQ(fine.nv, g.nv + 5);
    iges_net net = to_net(&fine);
    /* the insertion itself is exact: the fine net is the same surface */
    CHECK(deviation(&g, &net, 60) < 1e-6);
    CHECK_EQ(iges_reduce(&net, 0.01), FM_OK);
    CHECK_EQ(net.nu, g.nu);
    CHECK_EQ(net.nv, g.nv);
    if (net.nu == g.nu && net.nv == g.nv) {
        for (size_t i = 0; i < g.nu + P + 1; i++)
            CHECK(net.knots_u[i] == g.ku[i]);
        for (size_t j = 0; j < g.nv + P + 1; j++)
            CHECK(net.knots_v[j] == g.kv[j]);
        double worst = 0;
        for (size_t k = 0; k < g.nu * g.nv; k++)
            for (int x = 0; x < 3; x++)
                worst = fmax(worst, fabs(net.ctrl[3 * k + (size_t)x] - g.c[k][x]));
        CHECK(worst < 1e-6);
    }
    CHECK(net.removal < 1e-6);
    iges_net_free(&net);
}

/* A surface whose only interior knots carry a feature (a control point
 * 40 m off the plane) keeps them; the same surface without the feature
 * (a plane) loses them all. */
static void test_feature_keeps_its_knot(void)
{
    grid g;
    static const double iu[] = {500}, iv[] = {450};
    knots(g.ku, &g.nu, iu, 1, 1000);
    knots(g.kv, &g.nv, iv, 1, 1000);
    for (size_t j = 0; j < g.nv; j++)
        for (size_t i = 0; i < g.nu; i++) {
            /* a dipping plane: its control points at the Greville abscissae */
            double u = (g.ku[i + 1] + g.ku[i + 2] + g.ku[i + 3]) / 3;
            double v = (g.kv[j + 1] + g.kv[j + 2] + g.kv[j + 3]) / 3;
            double *c = g.c[j * g.nu + i];
            c[0] = 500000 + u;
            c[1] = 3800000 + 0.5 * v;
            c[2] = -1000 - 0.8 * v;
        }
    grid flat = g;
    iges_net net = to_net(&flat);
    CHECK_EQ(iges_reduce(&net, 0.01), FM_OK);
    CHECK_EQ(net.nu, 4);
    CHECK_EQ(net.nv, 4);
    CHECK(deviation(&g, &net, 50) < 1e-6);
    iges_net_free(&net);

    g.c[2 * g.nu + 2][2] += 40; /* the feature: under both interior knots */
    net = to_net(&g);
    CHECK_EQ(iges_reduce(&net, 0.5), FM_OK);
    CHECK_EQ(net.nu, 5);
    CHECK_EQ(net.nv, 5);
    CHECK(net.nu == 5 && net.knots_u[4] == 500);
    CHECK(net.nv == 5 && net.knots_v[4] == 450);
    CHECK_EQ(net.removal, 0.0);
    iges_net_free(&net);
}

/* A smooth surface that is no polynomial: some knots go, not all, and on
 * a dense grid (20 samples a span) the result stays within the budget. */
static void test_within_budget(void)
{
    grid g;
    double inner[MAXN];
    size_t k = 0;
    for (int i = 1; i < 40; i++)
        inner[k++] = 250.0 * i;
    knots(g.ku, &g.nu, inner, k, 10000);
    knots(g.kv, &g.nv, inner, 23, 6000);
    for (size_t j = 0; j < g.nv; j++)
        for (size_t i = 0; i < g.nu; i++) {
            double u = (g.ku[i + 1] + g.ku[i + 2] + g.ku[i + 3]) / 3;
            double v = (g.kv[j + 1] + g.kv[j + 2] + g.kv[j + 3]) / 3;
            double *c = g.c[j * g.nu + i];
            c[0] = 400000 + u;
            c[1] = 3700000 + v * 0.6;
            /* a long smooth bend with a short ripple at one end */
            c[2] = -v * 0.8 + 300 * sin(u / 3000) + 8 * exp(-u / 800) * cos(u / 90 + v / 150);
        }
    const double budgets[] = {0.01, 0.1, 0.5};
    size_t before = g.nu * g.nv, last = before;
    for (int b = 0; b < 3; b++) {
        iges_net net = to_net(&g);
        CHECK_EQ(iges_reduce(&net, budgets[b]), FM_OK);
        size_t after = net.nu * net.nv;
        double dev = deviation(&g, &net, 20 * 40 + 1);
        printf("budget %.2f m: %zu -> %zu control points, bound %.4f m, measured %.4f m\n",
               budgets[b], before, after, net.removal, dev);
        CHECK(after < before);       /* something went */
        CHECK(after <= last);        /* more with a larger budget */
        CHECK(net.nu > 4 && net.nv >= 4); /* not everything: the ripple stays */
        CHECK(net.removal <= budgets[b]);
        CHECK(dev <= net.removal + 1e-9); /* the bound holds */
        CHECK(dev > 0);
        last = after;
        iges_net_free(&net);
    }
}

/* A rational net, or no budget: nothing removed. */
static void test_left_alone(void)
{
    grid g, fine;
    coarse(&g);
    fine = g;
    insert(&fine, 0, 250);
    iges_net net = to_net(&fine);
    CHECK_EQ(iges_reduce(&net, 0), FM_OK);
    CHECK_EQ(net.nu, fine.nu);
    double w[MAXN * MAXN];
    for (size_t i = 0; i < fine.nu * fine.nv; i++)
        w[i] = 1;
    net.weights = malloc(sizeof w);
    CHECK(net.weights != NULL);
    if (net.weights) {
        memcpy(net.weights, w, fine.nu * fine.nv * sizeof *w);
        CHECK_EQ(iges_reduce(&net, 1), FM_OK);
        CHECK_EQ(net.nu, fine.nu);
    }
    iges_net_free(&net);
}

int main(void)
{
    static const fm_test_case cases[] = {
        FM_CASE(test_inserted_knots_go),
        FM_CASE(test_feature_keeps_its_knot),
        FM_CASE(test_within_budget),
        FM_CASE(test_left_alone),
    };
    return fm_test_run(cases, sizeof cases / sizeof cases[0]);
}
