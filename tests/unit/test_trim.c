/* Trimming curves: corners kept, stair-steps smoothed, orientation kept,
 * deterministic, degenerate input refused or handled. Shapes are built
 * with known true curves so the fitted curve is judged against the truth,
 * not against the noisy polyline it came from. */
#include "fm_test.h"
#include "fm_trim.h"

#include <stdint.h>

#define PI 3.14159265358979323846

static uint64_t rng_state;

/* Uniform in [-1, 1), reproducible on every platform. */
static double jitter(void)
{
    rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(rng_state >> 11) / 4503599627370496.0 - 1.0;
}

static double seg_dist(const double p[2], const double a[2], const double b[2])
{
    double ex = b[0] - a[0], ey = b[1] - a[1], l2 = ex * ex + ey * ey;
    double f = l2 > 0 ? ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / l2 : 0;
    f = f < 0 ? 0 : f > 1 ? 1 : f;
    return hypot(p[0] - a[0] - f * ex, p[1] - a[1] - f * ey);
}

static double signed_area(const double *uv, size_t n)
{
    double a = 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = uv + 2 * i, *q = uv + 2 * ((i + 1) % n);
        a += (p[0] - uv[0]) * (q[1] - uv[1]) - (p[1] - uv[1]) * (q[0] - uv[0]);
    }
    return 0.5 * a;
}

static void reverse(double *uv, size_t n)
{
    for (size_t i = 0, j = n - 1; i < j; i++, j--)
        for (int k = 0; k < 2; k++) {
            double t = uv[2 * i + k];
            uv[2 * i + k] = uv[2 * j + k];
            uv[2 * j + k] = t;
        }
}

/* ---- the rectangle: 30 km x 15 km, 500 m points, +-100 m stair-steps ---- */

enum { RECT_N = 180, RECT_SHIFT = 37 };
static const double RECT_W = 30000, RECT_H = 15000;

/* Counter-clockwise from the lower left corner, then rotated so that point
 * 0 lies inside an edge; true corners stay exact, every other point is
 * pushed alternately 100 m in and out across its edge. */
static void make_rect(double *uv, double ox, double oy, size_t corner[4])
{
    double C[5][2] = {{0, 0}, {RECT_W, 0}, {RECT_W, RECT_H}, {0, RECT_H}, {0, 0}};
    int segs[4] = {60, 30, 60, 30};
    double tmp[2 * RECT_N];
    size_t m = 0;
    for (int e = 0; e < 4; e++) {
        double dx = (C[e + 1][0] - C[e][0]) / segs[e], dy = (C[e + 1][1] - C[e][1]) / segs[e];
        double len = hypot(dx, dy), nx = -dy / len, ny = dx / len; /* inward normal */
        for (int k = 0; k < segs[e]; k++) {
            double off = k == 0 ? 0 : (k % 2 ? 100 : -100);
            tmp[2 * m] = C[e][0] + k * dx + off * nx;
            tmp[2 * m + 1] = C[e][1] + k * dy + off * ny;
            m++;
        }
    }
    size_t cs[4] = {0, 60, 90, 150};
    for (size_t i = 0; i < RECT_N; i++) {
        size_t j = (i + RECT_SHIFT) % RECT_N;
        uv[2 * i] = tmp[2 * j] + ox;
        uv[2 * i + 1] = tmp[2 * j + 1] + oy;
    }
    for (int c = 0; c < 4; c++)
        corner[c] = (cs[c] + RECT_N - RECT_SHIFT) % RECT_N;
}

static double rect_dist(const double p[2], double ox, double oy)
{
    double C[5][2] = {{ox, oy}, {ox + RECT_W, oy}, {ox + RECT_W, oy + RECT_H}, {ox, oy + RECT_H},
                      {ox, oy}};
    double d = INFINITY;
    for (int e = 0; e < 4; e++)
        d = fmin(d, seg_dist(p, C[e], C[e + 1]));
    return d;
}

static int cmp_size(const void *a, const void *b)
{
    size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return (x > y) - (x < y);
}

/* Fits the rectangle (reversed when cw) and checks corners, exact joins
 * and distance to the true rectangle; returns the far-from-corner max. */
static double check_rect(double ox, double oy, int cw)
{
    double uv[2 * RECT_N];
    size_t corner[4];
    make_rect(uv, ox, oy, corner);
    if (cw) {
        reverse(uv, RECT_N);
        for (int c = 0; c < 4; c++)
            corner[c] = RECT_N - 1 - corner[c];
    }
    qsort(corner, 4, sizeof corner[0], cmp_size);
    fm_trim_loop *loop = NULL;
    fm_error err;
    CHECK_EQ(fm_trim_fit(uv, RECT_N, NULL, &loop, &err), FM_OK);
    if (!loop)
        return INFINITY;
    const fm_trim_stats *st = fm_trim_loop_stats(loop);
    size_t nc = 0;
    const size_t *cor = fm_trim_loop_corners(loop, &nc);
    CHECK_EQ(nc, 4);
    for (size_t c = 0; c < nc && c < 4; c++)
        CHECK_EQ(cor[c], corner[c]);
    CHECK_EQ(fm_trim_loop_npieces(loop), 4);
    CHECK(st->within_tolerance);
    /* Corners interpolated exactly, pieces joined exactly. */
    for (size_t i = 0; i < fm_trim_loop_npieces(loop); i++) {
        fm_trim_piece pc, next;
        fm_trim_loop_piece(loop, i, &pc);
        fm_trim_loop_piece(loop, (i + 1) % fm_trim_loop_npieces(loop), &next);
        CHECK(!pc.periodic);
        CHECK_EQ(pc.degree, 3);
        CHECK_EQ(pc.nknots, pc.ncontrol + 4);
        CHECK_EQ(pc.first, cor[i]);
        CHECK_EQ(pc.last, next.first);
        double a[2], b[2];
        fm_trim_loop_eval(loop, i, pc.t0, a, NULL);
        fm_trim_loop_eval(loop, i, pc.t1, b, NULL);
        CHECK(a[0] == uv[2 * pc.first] && a[1] == uv[2 * pc.first + 1]);
        CHECK(b[0] == uv[2 * pc.last] && b[1] == uv[2 * pc.last + 1]);
        CHECK(pc.control[0] == a[0] && pc.control[1] == a[1]);
    }
    double *s = NULL;
    size_t ns = 0, *at = NULL;
    CHECK_EQ(fm_trim_loop_sample(loop, 25, &s, &ns, &at, &err), FM_OK);
    double far = 0, all = 0;
    for (size_t i = 0; i < ns; i++) {
        double d = rect_dist(s + 2 * i, ox, oy), dc = INFINITY;
        for (size_t c = 0; c < 4; c++)
            dc = fmin(dc, hypot(s[2 * i] - uv[2 * cor[c]], s[2 * i + 1] - uv[2 * cor[c] + 1]));
        all = fmax(all, d);
        if (dc > 1000)
            far = fmax(far, d);
    }
    for (size_t c = 0; c < 4 && at; c++)
        CHECK(s[2 * at[c]] == uv[2 * cor[c]] && s[2 * at[c] + 1] == uv[2 * cor[c] + 1]);
    double area = RECT_W * RECT_H * (cw ? -1 : 1);
    CHECK_NEAR(st->area, area, 0.005 * fabs(area));
    CHECK(st->area * st->polygon_area > 0);
    CHECK(signed_area(s, ns) * area > 0);
    CHECK(all <= 100);
    printf("rect%s%s: corners %zu spans %zu refinements %d max_dev %.1f rms %.1f curve->poly "
           "%.1f systematic %.2f | vs truth: far %.2f all %.2f m\n",
           cw ? " cw" : "", ox ? " utm" : "", nc, st->spans, st->refinements, st->max_dev,
           st->rms_dev, st->max_curve_dev, st->max_systematic, far, all);
    free(s);
    free(at);
    fm_trim_loop_destroy(loop);
    return far;
}

static void test_rectangle(void)
{
    CHECK(check_rect(0, 0, 0) <= 30);
    CHECK(check_rect(423000, 3712000, 0) <= 30);
}

/* ---- the hole: circle of radius 2 km, 300 m points, jittered ---- */

enum { CIRC_N = 42 };
static const double CIRC_R = 2000, CIRC_X = 5000, CIRC_Y = -3000;

/* Radial stair-steps of +-step (alternating, as a triangulated boundary
 * has them) and a random jitter of up to jit metres in both directions. */
static void make_circle(double *uv, double jit, double step)
{
    rng_state = 12345;
    for (size_t i = 0; i < CIRC_N; i++) {
        double a = 2 * PI * (double)i / CIRC_N + jit / CIRC_R * jitter();
        double r = CIRC_R + jit * jitter() + (i % 2 ? step : -step);
        uv[2 * i] = CIRC_X + r * cos(a);
        uv[2 * i + 1] = CIRC_Y + r * sin(a);
    }
}

/* Largest |distance to the centre - R| over samples of the curve. */
static double circle_error(const fm_trim_loop *loop)
{
    double *s = NULL;
    size_t ns = 0;
    fm_error err;
    CHECK_EQ(fm_trim_loop_sample(loop, 20, &s, &ns, NULL, &err), FM_OK);
    double e = 0;
    for (size_t i = 0; i < ns; i++)
        e = fmax(e, fabs(hypot(s[2 * i] - CIRC_X, s[2 * i + 1] - CIRC_Y) - CIRC_R));
    free(s);
    return e;
}

static void check_circle(int cw)
{
    double uv[2 * CIRC_N];
    make_circle(uv, 15, 50);
    if (cw)
        reverse(uv, CIRC_N);
    fm_trim_loop *loop = NULL;
    fm_error err;
    CHECK_EQ(fm_trim_fit(uv, CIRC_N, NULL, &loop, &err), FM_OK);
    if (!loop)
        return;
    const fm_trim_stats *st = fm_trim_loop_stats(loop);
    size_t nc = 99;
    fm_trim_loop_corners(loop, &nc);
    CHECK_EQ(nc, 0);
    CHECK_EQ(fm_trim_loop_npieces(loop), 1);
    fm_trim_piece pc;
    fm_trim_loop_piece(loop, 0, &pc);
    CHECK(pc.periodic);
    /* Closed and C2 across the seam: the last `degree` controls repeat. */
    for (int k = 0; k < 2 * pc.degree; k++)
        CHECK(pc.control[2 * (pc.ncontrol - pc.degree) + k] == pc.control[k]);
    double a[2], b[2], da[2], db[2];
    fm_trim_loop_eval(loop, 0, pc.t0, a, da);
    fm_trim_loop_eval(loop, 0, pc.t1 * (1 - 1e-12), b, db);
    CHECK_NEAR(a[0], b[0], 1e-3);
    CHECK_NEAR(a[1], b[1], 1e-3);
    CHECK_NEAR(da[0], db[0], 1e-6);
    CHECK_NEAR(da[1], db[1], 1e-6);
    double e = circle_error(loop);
    double area = PI * CIRC_R * CIRC_R * (cw ? -1 : 1);
    CHECK_NEAR(st->area, area, 0.02 * fabs(area));
    CHECK(st->area * st->polygon_area > 0);
    CHECK(st->within_tolerance);
    CHECK(e <= 20);
    printf("circle%s: spans %zu refinements %d max_dev %.1f rms %.1f systematic %.2f | vs truth "
           "%.2f m\n",
           cw ? " cw" : "", st->spans, st->refinements, st->max_dev, st->rms_dev,
           st->max_systematic, e);
    fm_trim_loop_destroy(loop);
}

/* A loop far longer than wide drawn with its four corners only (a
 * 2-triangle fault 10,000 km long, 14 km deep): the two ends are not taken
 * for one corner each, and the curves are the rectangle's sides. */
static void test_long_thin(void)
{
    const double L = 1e7, W = 14000;
    double uv[8] = {0, 0, L, 0, L, W, 0, W};
    fm_trim_loop *loop = NULL;
    fm_error err;
    CHECK_EQ(fm_trim_fit(uv, 4, NULL, &loop, &err), FM_OK);
    if (!loop)
        return;
    size_t nc = 0;
    fm_trim_loop_corners(loop, &nc);
    CHECK_EQ(nc, 4);
    const fm_trim_stats *st = fm_trim_loop_stats(loop);
    CHECK(st->max_curve_dev < 1);
    CHECK_NEAR(st->area, L * W, 1e-6 * L * W);
    fm_trim_loop_destroy(loop);
}

static void test_circle(void)
{
    check_circle(0);
}

/* ---- the trace: wavy top, straight sides, round bottom ---- */

static const double TR_W = 40000, TR_D = 8000, TR_A = 180, TR_L = 7000, TR_PH = 0.3;

static double trace_top(double x)
{
    return TR_A * sin(2 * PI * x / TR_L + TR_PH);
}

/* Distance to the true outline: left and right sides, the bottom
 * half-circle (centre (W/2, -D), radius W/2) and the top graph. */
static double trace_dist(const double p[2])
{
    double tl[2] = {0, trace_top(0)}, bl[2] = {0, -TR_D};
    double tr[2] = {TR_W, trace_top(TR_W)}, br[2] = {TR_W, -TR_D};
    double d = fmin(seg_dist(p, tl, bl), seg_dist(p, tr, br));
    double R = TR_W / 2, cx = R, cy = -TR_D;
    if (p[1] <= cy)
        d = fmin(d, fabs(hypot(p[0] - cx, p[1] - cy) - R));
    if (p[1] > -2000)
        for (double x = fmax(0, p[0] - 1000); x <= fmin(TR_W, p[0] + 1000); x += 1)
            d = fmin(d, hypot(p[0] - x, p[1] - trace_top(x)));
    return d;
}

static size_t make_trace(double *uv, size_t corner[2])
{
    size_t m = 0;
    rng_state = 777;
    /* Down the left side (stair-steps), corner first. */
    corner[0] = m;
    double y0 = trace_top(0);
    int ks = 18;
    for (int k = 0; k < ks; k++) {
        double off = k == 0 ? 0 : (k % 2 ? 60 : -60);
        uv[2 * m] = off;
        uv[2 * m + 1] = y0 + (-TR_D - y0) * k / ks;
        m++;
    }
    /* The bottom half-circle, left to right (counter-clockwise). */
    int kb = 126;
    for (int k = 0; k < kb; k++) {
        double a = PI + PI * k / kb, r = TR_W / 2 + 30 * jitter();
        uv[2 * m] = TR_W / 2 + r * cos(a);
        uv[2 * m + 1] = -TR_D + r * sin(a);
        m++;
    }
    /* Up the right side. */
    double y1 = trace_top(TR_W);
    for (int k = 0; k < ks; k++) {
        double off = k == 0 ? 0 : (k % 2 ? 60 : -60);
        uv[2 * m] = TR_W + off;
        uv[2 * m + 1] = -TR_D + (y1 + TR_D) * k / ks;
        m++;
    }
    /* Along the top, right to left: the corner exact, then stair-steps and
     * jitter. */
    corner[1] = m;
    int kt = 80;
    for (int k = 0; k < kt; k++) {
        double x = TR_W - TR_W * k / kt;
        uv[2 * m] = x;
        double off = k == 0 ? 0 : (k % 2 ? 40 : -40) + 10 * jitter();
        uv[2 * m + 1] = trace_top(x) + off;
        m++;
    }
    return m;
}

static void test_trace(void)
{
    double uv[2 * 300];
    size_t corner[2];
    size_t n = make_trace(uv, corner);
    /* The corners are 80..100 degrees, as the test means them to be. */
    double s0 = 2 * PI / TR_L * TR_A;
    double a0 = 90 + atan(s0 * cos(TR_PH)) * 180 / PI;
    double a1 = 90 - atan(s0 * cos(2 * PI * TR_W / TR_L + TR_PH)) * 180 / PI;
    CHECK(a0 >= 80 && a0 <= 100 && a1 >= 80 && a1 <= 100);
    fm_trim_loop *loop = NULL;
    fm_error err;
    CHECK_EQ(fm_trim_fit(uv, n, NULL, &loop, &err), FM_OK);
    if (!loop)
        return;
    const fm_trim_stats *st = fm_trim_loop_stats(loop);
    size_t nc = 0;
    const size_t *cor = fm_trim_loop_corners(loop, &nc);
    CHECK_EQ(nc, 2);
    if (nc == 2) {
        CHECK_EQ(cor[0], corner[0]);
        CHECK_EQ(cor[1], corner[1]);
    }
    CHECK_EQ(fm_trim_loop_npieces(loop), 2);
    CHECK(st->within_tolerance);
    double *s = NULL;
    size_t ns = 0;
    CHECK_EQ(fm_trim_loop_sample(loop, 50, &s, &ns, NULL, &err), FM_OK);
    double far = 0, all = 0, top = 0;
    for (size_t i = 0; i < ns; i++) {
        double d = trace_dist(s + 2 * i);
        double dc = fmin(hypot(s[2 * i], s[2 * i + 1] - trace_top(0)),
                         hypot(s[2 * i] - TR_W, s[2 * i + 1] - trace_top(TR_W)));
        all = fmax(all, d);
        if (dc > 1000)
            far = fmax(far, d);
        if (s[2 * i + 1] > -1000 && dc > 1000)
            top = fmax(top, d);
    }
    CHECK(far <= 30);
    CHECK(all <= 80);
    CHECK(st->area > 0);
    printf("trace (corners %.1f and %.1f deg): corners %zu spans %zu refinements %d max_dev %.1f "
           "systematic %.2f | vs truth: far %.2f (top %.2f) all %.2f m\n",
           a0, a1, nc, st->spans, st->refinements, st->max_dev, st->max_systematic, far, top, all);
    free(s);
    fm_trim_loop_destroy(loop);
}

/* ---- orientation ---- */

static void test_orientation(void)
{
    CHECK(check_rect(0, 0, 1) <= 30);
    check_circle(1);
    /* The sampled curve keeps the input's sense too. */
    double uv[2 * CIRC_N];
    make_circle(uv, 15, 50);
    for (int cw = 0; cw < 2; cw++) {
        if (cw)
            reverse(uv, CIRC_N);
        fm_trim_loop *loop = NULL;
        fm_error err;
        CHECK_EQ(fm_trim_fit(uv, CIRC_N, NULL, &loop, &err), FM_OK);
        if (!loop)
            continue;
        double *s = NULL;
        size_t ns = 0;
        CHECK_EQ(fm_trim_loop_sample(loop, 100, &s, &ns, NULL, &err), FM_OK);
        CHECK(signed_area(s, ns) * signed_area(uv, CIRC_N) > 0);
        CHECK(fm_trim_loop_area(loop) * signed_area(uv, CIRC_N) > 0);
        free(s);
        fm_trim_loop_destroy(loop);
    }
}

/* ---- determinism ---- */

static int same_loop(const fm_trim_loop *a, const fm_trim_loop *b)
{
    if (fm_trim_loop_npieces(a) != fm_trim_loop_npieces(b))
        return 0;
    for (size_t i = 0; i < fm_trim_loop_npieces(a); i++) {
        fm_trim_piece p, q;
        fm_trim_loop_piece(a, i, &p);
        fm_trim_loop_piece(b, i, &q);
        if (p.nknots != q.nknots || p.ncontrol != q.ncontrol ||
            memcmp(p.knots, q.knots, p.nknots * sizeof *p.knots) ||
            memcmp(p.control, q.control, 2 * p.ncontrol * sizeof *p.control))
            return 0;
    }
    const fm_trim_stats *s = fm_trim_loop_stats(a), *t = fm_trim_loop_stats(b);
    return s->max_dev == t->max_dev && s->area == t->area && s->corners == t->corners;
}

static void test_determinism(void)
{
    double uv[2 * 300];
    size_t corner[4];
    make_rect(uv, 423000, 3712000, corner);
    for (int shape = 0; shape < 3; shape++) {
        size_t n = RECT_N;
        if (shape == 1) {
            make_circle(uv, 15, 50);
            n = CIRC_N;
        } else if (shape == 2) {
            n = make_trace(uv, corner);
        }
        fm_trim_loop *a = NULL, *b = NULL;
        fm_error err;
        CHECK_EQ(fm_trim_fit(uv, n, NULL, &a, &err), FM_OK);
        CHECK_EQ(fm_trim_fit(uv, n, NULL, &b, &err), FM_OK);
        CHECK(a && b && same_loop(a, b));
        fm_trim_loop_destroy(a);
        fm_trim_loop_destroy(b);
    }
}

/* ---- refinement where the smooth fit misses the tolerance ---- */

/* A 30 x 15 km box with a roof: the top edge bends by 25 degrees in its
 * middle, less than the corner angle, so the apex is fitted smoothly and
 * rounded off until refinement brings knots in. Stair-steps of +-50 m. */
enum { ROOF_V = 5 };
static const double ROOF_P[ROOF_V + 1][2] = {
    {0, 0}, {30000, 0}, {30000, 15000}, {15000, 18325.4}, {0, 15000}, {0, 0}};
static const int ROOF_SEGS[ROOF_V] = {60, 30, 31, 31, 30};

static size_t make_roof(double *uv)
{
    size_t m = 0;
    for (int e = 0; e < ROOF_V; e++) {
        double dx = (ROOF_P[e + 1][0] - ROOF_P[e][0]) / ROOF_SEGS[e];
        double dy = (ROOF_P[e + 1][1] - ROOF_P[e][1]) / ROOF_SEGS[e];
        double len = hypot(dx, dy), nx = -dy / len, ny = dx / len;
        for (int k = 0; k < ROOF_SEGS[e]; k++) {
            double off = k == 0 ? 0 : (k % 2 ? 50 : -50);
            uv[2 * m] = ROOF_P[e][0] + k * dx + off * nx;
            uv[2 * m + 1] = ROOF_P[e][1] + k * dy + off * ny;
            m++;
        }
    }
    return m;
}

/* Largest distance of the sampled curve from the true roof outline. */
static double roof_error(const fm_trim_loop *loop)
{
    double *s = NULL;
    size_t ns = 0;
    fm_error err;
    CHECK_EQ(fm_trim_loop_sample(loop, 20, &s, &ns, NULL, &err), FM_OK);
    double e = 0;
    for (size_t i = 0; i < ns; i++) {
        double d = INFINITY;
        for (int k = 0; k < ROOF_V; k++)
            d = fmin(d, seg_dist(s + 2 * i, ROOF_P[k], ROOF_P[k + 1]));
        e = fmax(e, d);
    }
    free(s);
    return e;
}

static void test_refinement(void)
{
    double uv[2 * 200];
    size_t n = make_roof(uv);
    fm_trim_options opt;
    fm_trim_options_default(&opt);
    opt.tolerance = 10;
    fm_trim_loop *loop = NULL, *coarse = NULL;
    fm_error err;
    CHECK_EQ(fm_trim_fit(uv, n, &opt, &loop, &err), FM_OK);
    opt.max_refinements = 0;
    CHECK_EQ(fm_trim_fit(uv, n, &opt, &coarse, &err), FM_OK);
    if (!loop || !coarse) {
        fm_trim_loop_destroy(loop);
        fm_trim_loop_destroy(coarse);
        return;
    }
    const fm_trim_stats *st = fm_trim_loop_stats(loop), *sc = fm_trim_loop_stats(coarse);
    CHECK_EQ(st->corners, 4);
    CHECK(!sc->within_tolerance);
    CHECK(st->within_tolerance);
    CHECK(st->refinements > 0);
    CHECK(st->spans > sc->spans);
    double ec = roof_error(coarse), e = roof_error(loop);
    CHECK(e < 0.5 * ec);
    CHECK(e <= 30);
    printf("refinement (roof, tolerance 10 m): unrefined systematic %.2f m, truth %.2f m, %zu "
           "spans; refined systematic %.2f m, truth %.2f m, %zu spans after %d rounds\n",
           sc->max_systematic, ec, sc->spans, st->max_systematic, e, st->spans, st->refinements);
    fm_trim_loop_destroy(coarse);
    fm_trim_loop_destroy(loop);
}

/* ---- a single point far off, next to a corner ---- */

/* The roof box with the third vertex of the bottom edge pulled 400 m out,
 * next to a corner, where the systematic measure is not taken: only
 * max_deviation asks for knots there, and they come in around the point
 * alone (a few spans), not as less smoothing over the piece. (Here one
 * halving is enough; on the CFM the spans flagged only by max_deviation
 * may go below two point spacings, see trim_loop.c.) */
static void test_spike(void)
{
    double uv[2 * 200];
    size_t n = make_roof(uv);
    uv[2 * 2 + 1] = -400;
    fm_trim_options opt;
    fm_trim_options_default(&opt);
    fm_trim_loop *plain = NULL, *raw = NULL;
    fm_error err;
    CHECK_EQ(fm_trim_fit(uv, n, &opt, &plain, &err), FM_OK);
    opt.max_deviation = 80;
    CHECK_EQ(fm_trim_fit(uv, n, &opt, &raw, &err), FM_OK);
    if (!plain || !raw) {
        fm_trim_loop_destroy(plain);
        fm_trim_loop_destroy(raw);
        return;
    }
    const fm_trim_stats *sp = fm_trim_loop_stats(plain), *sr = fm_trim_loop_stats(raw);
    printf("spike 400 m by a corner: max_dev %.1f m (%zu spans), with max_deviation 80: %.1f m "
           "(%zu spans, %d rounds)\n",
           sp->max_dev, sp->spans, sr->max_dev, sr->spans, sr->refinements);
    CHECK(sp->max_dev > 150);
    CHECK(sr->max_dev <= 80);
    CHECK(sr->spans <= sp->spans + 8);
    fm_trim_loop_destroy(plain);
    fm_trim_loop_destroy(raw);
}

/* ---- forced corners ---- */

/* A 10 x 4 km loop at 500 m points whose bottom edge bends by 20 degrees
 * at x = 5 km: below corner_angle, so the curve rounds the bend; forced
 * there with corner_at (where a cut meets or turns along a sheet's
 * outline), it is a corner and the curve passes through it. */
static void test_forced_corner(void)
{
    double uv[2 * 64];
    size_t n = 0, kink = 0;
    double t20 = tan(20 * 3.14159265358979323846 / 180);
    for (int i = 0; i <= 20; i++) { /* bottom, bending up at i = 10 */
        double x = 500.0 * i;
        if (i == 10)
            kink = n;
        uv[2 * n] = x;
        uv[2 * n + 1] = x > 5000 ? (x - 5000) * t20 : 0;
        n++;
    }
    double top = 4000 + 5000 * t20;
    for (int i = 1; i <= 8; i++) { /* right side */
        uv[2 * n] = 10000;
        uv[2 * n + 1] = 5000 * t20 + (top - 5000 * t20) * i / 8;
        n++;
    }
    for (int i = 19; i >= 0; i--) { /* top */
        uv[2 * n] = 500.0 * i;
        uv[2 * n + 1] = top;
        n++;
    }
    for (int i = 7; i >= 1; i--) { /* left side */
        uv[2 * n] = 0;
        uv[2 * n + 1] = top * i / 8;
        n++;
    }
    fm_trim_options opt;
    fm_trim_options_default(&opt);
    fm_trim_loop *plain = NULL, *forced = NULL;
    fm_error err;
    CHECK_EQ(fm_trim_fit(uv, n, &opt, &plain, &err), FM_OK);
    unsigned char at[64] = {0};
    at[kink] = 1;
    opt.corner_at = at;
    CHECK_EQ(fm_trim_fit(uv, n, &opt, &forced, &err), FM_OK);
    if (!plain || !forced) {
        fm_trim_loop_destroy(plain);
        fm_trim_loop_destroy(forced);
        return;
    }
    size_t np, nf;
    const size_t *cp = fm_trim_loop_corners(plain, &np), *cf = fm_trim_loop_corners(forced, &nf);
    int has = 0;
    for (size_t i = 0; i < nf; i++)
        has |= cf[i] == kink;
    for (size_t i = 0; i < np; i++)
        CHECK(cp[i] != kink);
    printf("20 degree bend: corners %zu, forced %zu; max_dev %.1f -> %.1f m\n", np, nf,
           fm_trim_loop_stats(plain)->max_dev, fm_trim_loop_stats(forced)->max_dev);
    CHECK(has);
    CHECK_EQ(nf, np + 1);
    CHECK(fm_trim_loop_stats(forced)->max_dev < fm_trim_loop_stats(plain)->max_dev);
    fm_trim_loop_destroy(plain);
    fm_trim_loop_destroy(forced);
}

/* ---- the curve between the points ---- */

/* Largest distance of the curve, sampled every 10 m, from the polyline. */
static double curve_to_polyline(const fm_trim_loop *loop, const double *uv, size_t n)
{
    double *s = NULL;
    size_t ns = 0;
    fm_error err;
    CHECK_EQ(fm_trim_loop_sample(loop, 10, &s, &ns, NULL, &err), FM_OK);
    double e = 0;
    for (size_t i = 0; i < ns; i++) {
        double d = INFINITY;
        for (size_t k = 0; k < n; k++)
            d = fmin(d, seg_dist(s + 2 * i, uv + 2 * k, uv + 2 * ((k + 1) % n)));
        e = fmax(e, d);
    }
    free(s);
    return e;
}

/* A box of 20 x 8 km at 500 m points with one point of its bottom edge
 * 100 m out, fitted as the mesher asks (15 m systematic, 25 m at any
 * point). The knots max_deviation brings in for that point make the curve
 * swing out between it and its neighbours: every point within 25 m, the
 * curve 32 m from the polyline between two of them. Spans where the curve
 * strays are refined too, and the curve keeps within 25 m everywhere. */
static void test_curve_between_points(void)
{
    double uv[2 * 200];
    size_t n = 0;
    for (int i = 0; i < 40; i++, n++) {
        uv[2 * n] = 500.0 * i;
        uv[2 * n + 1] = i == 12 ? -100 : 0;
    }
    for (int i = 0; i < 16; i++, n++) {
        uv[2 * n] = 20000;
        uv[2 * n + 1] = 500.0 * i;
    }
    for (int i = 40; i > 0; i--, n++) {
        uv[2 * n] = 500.0 * i;
        uv[2 * n + 1] = 8000;
    }
    for (int i = 16; i > 0; i--, n++) {
        uv[2 * n] = 0;
        uv[2 * n + 1] = 500.0 * i;
    }
    fm_trim_options opt;
    fm_trim_options_default(&opt);
    opt.tolerance = 15;
    opt.max_deviation = 25;
    fm_trim_loop *loop = NULL;
    fm_error err;
    CHECK_EQ(fm_trim_fit(uv, n, &opt, &loop, &err), FM_OK);
    if (!loop)
        return;
    const fm_trim_stats *st = fm_trim_loop_stats(loop);
    double between = curve_to_polyline(loop, uv, n);
    printf("one point 100 m out: points within %.1f m, curve (every 10 m) within %.1f m of the "
           "polyline, %zu spans, %d rounds\n",
           st->max_dev, between, st->spans, st->refinements);
    CHECK(st->max_dev <= 25);
    CHECK(st->max_curve_dev <= 25);
    CHECK(between <= 26);
    fm_trim_loop_destroy(loop);
}

/* ---- degenerate input ---- */

static void expect_invalid(const double *uv, size_t n, const fm_trim_options *opt)
{
    fm_trim_loop *loop = (fm_trim_loop *)&rng_state; /* must be reset */
    fm_error err;
    fm_error_clear(&err);
    CHECK_EQ(fm_trim_fit(uv, n, opt, &loop, &err), FM_ERR_INVALID);
    CHECK(loop == NULL);
    CHECK(strncmp(err.message, "trim: ", 6) == 0);
}

static void test_degenerate(void)
{
    double tri[] = {0, 0, 1000, 0, 500, 800};
    expect_invalid(NULL, 0, NULL);
    expect_invalid(tri, 2, NULL);
    double nan_tri[] = {0, 0, NAN, 0, 500, 800};
    expect_invalid(nan_tri, 3, NULL);
    double same[] = {7, 7, 7, 7, 7, 7, 7, 7};
    expect_invalid(same, 4, NULL);
    double two[] = {0, 0, 0, 0, 10, 0, 10, 0, 0, 0};
    expect_invalid(two, 5, NULL);
    fm_trim_options bad;
    fm_trim_options_default(&bad);
    bad.tolerance = 0;
    expect_invalid(tri, 3, &bad);
    fm_trim_options_default(&bad);
    bad.corner_angle = NAN;
    expect_invalid(tri, 3, &bad);
    fm_trim_options_default(&bad);
    bad.knot_spacing = -1;
    expect_invalid(tri, 3, &bad);
    fm_trim_options_default(&bad);
    bad.max_refinements = 99;
    expect_invalid(tri, 3, &bad);

    /* Repeated points and a repeated closing point: a triangle, exactly. */
    double rep[] = {0, 0, 0, 0, 1000, 0, 1000, 0, 1000, 0, 500, 800, 0, 0};
    fm_trim_loop *loop = NULL;
    fm_error err;
    CHECK_EQ(fm_trim_fit(rep, 7, NULL, &loop, &err), FM_OK);
    if (loop) {
        size_t nc = 0;
        const size_t *c = fm_trim_loop_corners(loop, &nc);
        CHECK_EQ(nc, 3);
        if (nc == 3) {
            CHECK_EQ(c[0], 0);
            CHECK_EQ(c[1], 2);
            CHECK_EQ(c[2], 5);
        }
        const fm_trim_stats *st = fm_trim_loop_stats(loop);
        CHECK_EQ(st->distinct_points, 3);
        CHECK(st->max_dev < 1e-6 && st->max_curve_dev < 1e-6);
        CHECK_NEAR(st->area, 400000, 1e-3);
        fm_trim_loop_destroy(loop);
    }

    /* The rectangle with its closing point repeated and a doubled point
     * gives the same corners (as input indices) and the same curves. */
    double uv[2 * (RECT_N + 2)];
    size_t corner[4];
    make_rect(uv, 0, 0, corner);
    fm_trim_loop *ref = NULL;
    CHECK_EQ(fm_trim_fit(uv, RECT_N, NULL, &ref, &err), FM_OK);
    memmove(uv + 2 * 11, uv + 2 * 10, 2 * (RECT_N - 10) * sizeof *uv);
    uv[2 * (RECT_N + 1)] = uv[0];
    uv[2 * (RECT_N + 1) + 1] = uv[1];
    CHECK_EQ(fm_trim_fit(uv, RECT_N + 2, NULL, &loop, &err), FM_OK);
    if (loop && ref) {
        size_t na = 0, nb = 0;
        const size_t *ca = fm_trim_loop_corners(ref, &na), *cb = fm_trim_loop_corners(loop, &nb);
        CHECK_EQ(na, nb);
        for (size_t i = 0; i < na && i < nb; i++)
            CHECK_EQ(cb[i], ca[i] + (ca[i] > 10));
        CHECK(same_loop(ref, loop) || fabs(fm_trim_loop_area(ref) - fm_trim_loop_area(loop)) < 1);
    }
    fm_trim_loop_destroy(loop);
    fm_trim_loop_destroy(ref);

    /* Out and back along a line: no area, but no crash either. */
    double line[] = {0, 0, 1000, 0, 2000, 0, 3000, 0, 2000, 0, 1000, 0};
    loop = NULL;
    fm_status s = fm_trim_fit(line, 6, NULL, &loop, &err);
    CHECK(s == FM_OK || s == FM_ERR_INVALID);
    if (loop) {
        CHECK_NEAR(fm_trim_loop_area(loop), 0, 1);
        double *smp = NULL;
        size_t ns = 0;
        CHECK_EQ(fm_trim_loop_sample(loop, 0, &smp, &ns, NULL, &err), FM_ERR_INVALID);
        CHECK(smp == NULL && ns == 0);
        CHECK_EQ(fm_trim_loop_sample(loop, 1e9, &smp, &ns, NULL, &err), FM_OK);
        CHECK(ns == fm_trim_loop_npieces(loop));
        free(smp);
        fm_trim_loop_destroy(loop);
    }

    /* A sliver: three nearly collinear points. */
    double sliver[] = {0, 0, 5000, 1, 10000, 0};
    loop = NULL;
    s = fm_trim_fit(sliver, 3, NULL, &loop, &err);
    CHECK(s == FM_OK || s == FM_ERR_INVALID);
    fm_trim_loop_destroy(loop);
    fm_trim_loop_destroy(NULL);
}

/* A loop on the steep plane S(u, v) = (u, v, sqrt(15) v): a unit step in v
 * is 4 m long in 3D, one in u 1 m. The top edge carries a wave along u
 * that the smoothing halves: its residual passes the tolerance in (u, v)
 * but is four times larger in 3D. With the metric the fit must see that
 * and meet the tolerance in 3D, which is checked here against the curve
 * sampled densely, independently of the fit's own stats. */
#define STEEP_G 16.0

static size_t steep_loop(double *uv)
{
    size_t n = 0;
    for (int i = 0; i < 40; i++, n++) { /* bottom, u 0 .. 20 km */
        uv[2 * n] = 500.0 * i;
        uv[2 * n + 1] = 0;
    }
    for (int i = 0; i < 10; i++, n++) { /* right side, 125 m in v = 500 m in 3D */
        uv[2 * n] = 20000;
        uv[2 * n + 1] = 125.0 * i;
    }
    for (int i = 0; i < 40; i++, n++) { /* top, wavy, back along u */
        double u = 20000 - 500.0 * i;
        uv[2 * n] = u;
        uv[2 * n + 1] = 1250 + 40 * sin(2 * PI * u / 3000);
    }
    for (int i = 0; i < 10; i++, n++) { /* left side */
        uv[2 * n] = 0;
        uv[2 * n + 1] = 1250 - 125.0 * i;
    }
    return n;
}

/* Largest 3D distance from the top edge's points (away from its corners)
 * to the curve sampled every metre. */
static double steep_top_3d(const fm_trim_loop *loop, const double *uv)
{
    double *smp = NULL;
    size_t ns = 0;
    fm_error err;
    CHECK_EQ(fm_trim_loop_sample(loop, 1.0, &smp, &ns, NULL, &err), FM_OK);
    double worst = 0;
    for (size_t j = 53; j < 87; j++) {
        double best = INFINITY;
        for (size_t q = 0; q < ns; q++) {
            double du = smp[2 * q] - uv[2 * j], dv = smp[2 * q + 1] - uv[2 * j + 1];
            if (fabs(du) > 1500)
                continue;
            best = fmin(best, sqrt(du * du + STEEP_G * dv * dv));
        }
        worst = fmax(worst, best);
    }
    free(smp);
    return worst;
}

static void test_metric(void)
{
    double uv[2 * 100], metric[3 * 100];
    size_t n = steep_loop(uv);
    CHECK_EQ(n, 100);
    for (size_t i = 0; i < n; i++) {
        metric[3 * i] = 1;
        metric[3 * i + 1] = 0;
        metric[3 * i + 2] = STEEP_G;
    }
    fm_trim_options opt;
    fm_trim_options_default(&opt);
    /* In 3D the wave turns by up to 20 degrees; keep it off the corners. */
    opt.corner_angle = 60;
    fm_error err;

    /* Without the metric the fit is content in (u, v) ... */
    fm_trim_loop *flat = NULL;
    CHECK_EQ(fm_trim_fit(uv, n, &opt, &flat, &err), FM_OK);
    const fm_trim_stats *fs = fm_trim_loop_stats(flat);
    CHECK(fs->within_tolerance);
    CHECK_EQ(fs->corners, 4);
    double flat3d = steep_top_3d(flat, uv);
    /* ... but misses the tolerance in 3D. */
    CHECK(flat3d > 1.3 * opt.tolerance);

    /* NULL metric is fm_trim_fit exactly. */
    fm_trim_loop *same = NULL;
    CHECK_EQ(fm_trim_fit_metric(uv, NULL, n, &opt, &same, &err), FM_OK);
    CHECK_EQ(fm_trim_loop_stats(same)->spans, fs->spans);
    CHECK_EQ(fm_trim_loop_stats(same)->max_dev, fs->max_dev);
    fm_trim_loop_destroy(same);

    fm_trim_loop *steep = NULL;
    CHECK_EQ(fm_trim_fit_metric(uv, metric, n, &opt, &steep, &err), FM_OK);
    const fm_trim_stats *ss = fm_trim_loop_stats(steep);
    CHECK(ss->within_tolerance);
    CHECK_EQ(ss->corners, 4);
    CHECK(ss->spans > fs->spans); /* refined where 3D asked for it */
    /* 3D spacing: the sides' 125 m steps are 500 m long. */
    CHECK_NEAR(ss->spacing, 500, 1);
    double steep3d = steep_top_3d(steep, uv);
    /* The tolerance bounds the tent-averaged deviation; a wave's crest
     * sits a little further out than that average. */
    CHECK(ss->max_systematic <= opt.tolerance);
    CHECK(steep3d <= 1.25 * opt.tolerance);
    CHECK(steep3d < 0.6 * flat3d);
    /* The stats are 3D distances: the raw maximum matches the independent
     * measure (the largest deviation lies on the top edge). */
    CHECK_NEAR(ss->max_dev, steep3d, 0.05 * steep3d + 1);
    printf("metric: flat fit %.1f m in 3D (%zu spans), metric fit %.1f m (%zu spans)\n", flat3d,
           fs->spans, steep3d, ss->spans);

    /* Raw bound: a 3D tolerance so loose that the systematic test passes,
     * with max_deviation asking for the single points. */
    fm_trim_options raw = opt;
    raw.tolerance = 1000;
    raw.max_deviation = 0.5 * flat3d;
    fm_trim_loop *rl = NULL;
    CHECK_EQ(fm_trim_fit_metric(uv, metric, n, &raw, &rl, &err), FM_OK);
    CHECK(fm_trim_loop_stats(rl)->max_dev <= raw.max_deviation);
    fm_trim_loop_destroy(rl);

    /* Bad metrics are refused, a singular one is tolerated. */
    fm_trim_loop *bad = NULL;
    metric[3 * 7 + 2] = -1;
    CHECK_EQ(fm_trim_fit_metric(uv, metric, n, &opt, &bad, &err), FM_ERR_INVALID);
    metric[3 * 7 + 2] = NAN;
    CHECK_EQ(fm_trim_fit_metric(uv, metric, n, &opt, &bad, &err), FM_ERR_INVALID);
    metric[3 * 7] = metric[3 * 7 + 1] = metric[3 * 7 + 2] = 0;
    CHECK_EQ(fm_trim_fit_metric(uv, metric, n, &opt, &bad, &err), FM_ERR_INVALID);
    metric[3 * 7] = 1;
    metric[3 * 7 + 1] = 4;
    metric[3 * 7 + 2] = 16; /* E G = F^2 */
    CHECK_EQ(fm_trim_fit_metric(uv, metric, n, &opt, &bad, &err), FM_OK);
    fm_trim_loop_destroy(bad);
    opt.max_deviation = -1;
    CHECK_EQ(fm_trim_fit_metric(uv, NULL, n, &opt, &bad, &err), FM_ERR_INVALID);

    fm_trim_loop_destroy(flat);
    fm_trim_loop_destroy(steep);
}

FM_TEST_MAIN(FM_CASE(test_rectangle), FM_CASE(test_long_thin), FM_CASE(test_circle), FM_CASE(test_trace),
             FM_CASE(test_orientation), FM_CASE(test_determinism), FM_CASE(test_refinement),
             FM_CASE(test_spike), FM_CASE(test_forced_corner), FM_CASE(test_curve_between_points),
             FM_CASE(test_degenerate), FM_CASE(test_metric))
