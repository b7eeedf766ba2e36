/* Constrained Delaunay triangulation and refinement (fm_cdt.h): exact
 * validity of every result (orientation by fm_orient2d, every segment
 * present, a manifold whose boundary is exactly the constrained edges, area
 * equal to the polygon's, the constrained Delaunay property), quality and
 * size in the metric, small input angles, frozen segments, the split
 * callback, determinism and bad input. */
#include <stdint.h>

#include "fm_cdt.h"
#include "fm_predicates.h"
#include "fm_test.h"

static uint64_t rng = 42;

static double rnd(void)
{
    uint64_t z = (rng += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (double)((z ^ (z >> 31)) >> 11) * 0x1p-53;
}

/* A domain: loops of points, segment i of a loop joins point i to i+1. */
typedef struct domain {
    double uv[2 * 4096];
    int32_t seg[2 * 4096], sid[4096];
    size_t np, ns;
    double area; /* signed loops summed with outer CCW, holes CW */
} domain;

static void add_loop(domain *d, const double *pts, size_t n, int32_t id0)
{
    size_t base = d->np;
    double a = 0;
    for (size_t i = 0; i < n; i++) {
        d->uv[2 * (base + i)] = pts[2 * i];
        d->uv[2 * (base + i) + 1] = pts[2 * i + 1];
        size_t j = (i + 1) % n;
        d->seg[2 * d->ns] = (int32_t)(base + i);
        d->seg[2 * d->ns + 1] = (int32_t)(base + j);
        d->sid[d->ns] = id0 >= 0 ? id0 + (int32_t)i : (int32_t)d->ns;
        d->ns++;
        a += pts[2 * i] * pts[2 * j + 1] - pts[2 * j] * pts[2 * i + 1];
    }
    d->np += n;
    d->area += 0.5 * a;
}

static void metric_stretch(void *user, const double uv[2], double m[3])
{
    (void)user;
    (void)uv;
    m[0] = 1, m[1] = 0, m[2] = 9;
}

static void metric_varying(void *user, const double uv[2], double m[3])
{
    (void)user;
    /* A sheared, graded form like a tilted surface's. */
    double s = 1.5 + 0.5 * sin(uv[0]);
    m[0] = s * s, m[1] = 0.3 * s, m[2] = 1 + 0.3 * cos(uv[1]);
}

static void metric_at(fm_cdt_metric_fn f, const double uv[2], double m[3])
{
    if (f)
        f(NULL, uv, m);
    else
        m[0] = 1, m[1] = 0, m[2] = 1;
}

static double mlen(fm_cdt_metric_fn f, const double *a, const double *b)
{
    double mid[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])}, m[3];
    metric_at(f, mid, m);
    double dx = b[0] - a[0], dy = b[1] - a[1];
    return sqrt(m[0] * dx * dx + 2 * m[1] * dx * dy + m[2] * dy * dy);
}

/* Smallest angle (degrees) in the metric at the centroid. */
static double mangle(fm_cdt_metric_fn f, const double *a, const double *b, const double *c)
{
    double g[2] = {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3}, m[3];
    metric_at(f, g, m);
    const double *p[3] = {a, b, c};
    double l2[3];
    for (int i = 0; i < 3; i++) {
        const double *x = p[(i + 1) % 3], *y = p[(i + 2) % 3];
        double dx = y[0] - x[0], dy = y[1] - x[1];
        l2[i] = m[0] * dx * dx + 2 * m[1] * dx * dy + m[2] * dy * dy;
    }
    double best = 180;
    for (int i = 0; i < 3; i++) {
        double lj = l2[(i + 1) % 3], lk = l2[(i + 2) % 3];
        double c0 = (lj + lk - l2[i]) / (2 * sqrt(lj * lk));
        double ang = acos(fmax(-1, fmin(1, c0))) * 180 / 3.14159265358979323846;
        if (ang < best)
            best = ang;
    }
    return best;
}

typedef struct edge_rec {
    int32_t a, b;
    int32_t tri;
} edge_rec;

static int by_edge(const void *x, const void *y)
{
    const edge_rec *p = x, *q = y;
    int32_t pa = p->a < p->b ? p->a : p->b, pb = p->a < p->b ? p->b : p->a;
    int32_t qa = q->a < q->b ? q->a : q->b, qb = q->a < q->b ? q->b : q->a;
    if (pa != qa)
        return pa < qa ? -1 : 1;
    if (pb != qb)
        return pb < qb ? -1 : 1;
    return (p->tri > q->tri) - (p->tri < q->tri);
}

/* Exact checks of a result against its domain; returns the number of
 * failures so callers can stop early. */
static int validate(const fm_cdt *t, const domain *d, int delaunay)
{
    int before = fm_test_failed_checks;
    size_t np = fm_cdt_npoints(t), nt = fm_cdt_ntriangles(t), ne = fm_cdt_nedges(t);
    const double *p = fm_cdt_points(t);
    const int32_t *tri = fm_cdt_triangles(t), *ed = fm_cdt_edges(t);
    CHECK_EQ(fm_cdt_ninput(t), d->np);
    CHECK(nt > 0);
    double area = 0;
    int ccw = 1, range = 1;
    for (size_t k = 0; k < nt; k++) {
        const int32_t *v = tri + 3 * k;
        for (int i = 0; i < 3; i++)
            range &= v[i] >= 0 && (size_t)v[i] < np;
        if (!range)
            break;
        const double *a = p + 2 * v[0], *b = p + 2 * v[1], *c = p + 2 * v[2];
        ccw &= fm_orient2d(a, b, c) > 0;
        area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    CHECK(range);
    if (!range)
        return 1;
    CHECK(ccw);
    CHECK(fabs(area - fabs(d->area)) <= 1e-9 * fabs(d->area));
    /* Directed edges: each at most once; an edge with one triangle is a
     * boundary edge and must be constrained, and every constrained edge
     * has the domain on its left. */
    edge_rec *er = malloc(3 * nt * sizeof *er);
    for (size_t k = 0; k < nt; k++)
        for (int i = 0; i < 3; i++)
            er[3 * k + i] = (edge_rec){tri[3 * k + (i + 1) % 3], tri[3 * k + (i + 2) % 3],
                                       (int32_t)k};
    qsort(er, 3 * nt, sizeof *er, by_edge);
    size_t nbound = 0, nedges = 0, bad_manifold = 0, bad_delaunay = 0;
    for (size_t i = 0; i < 3 * nt;) {
        size_t j = i + 1;
        while (j < 3 * nt && ((er[j].a == er[i].a && er[j].b == er[i].b) ||
                              (er[j].a == er[i].b && er[j].b == er[i].a)))
            j++;
        nedges++;
        if (j - i == 1) {
            nbound++;
            int found = 0;
            for (size_t m = 0; m < ne && !found; m++)
                found = ed[2 * m] == er[i].a && ed[2 * m + 1] == er[i].b;
            if (!found)
                bad_manifold++;
        } else if (j - i == 2) {
            if (er[i].a != er[i + 1].b || er[i].b != er[i + 1].a)
                bad_manifold++;
            else if (delaunay) {
                int constrained = 0;
                for (size_t m = 0; m < ne && !constrained; m++)
                    constrained = (ed[2 * m] == er[i].a && ed[2 * m + 1] == er[i].b) ||
                                  (ed[2 * m] == er[i].b && ed[2 * m + 1] == er[i].a);
                const int32_t *v = tri + 3 * er[i].tri, *w = tri + 3 * er[i + 1].tri;
                int32_t opp = w[0] + w[1] + w[2] - er[i].a - er[i].b;
                if (!constrained &&
                    fm_incircle(p + 2 * v[0], p + 2 * v[1], p + 2 * v[2], p + 2 * opp) > 0)
                    bad_delaunay++;
            }
        } else {
            bad_manifold++;
        }
        i = j;
    }
    free(er);
    CHECK_EQ(bad_manifold, 0);
    CHECK_EQ(bad_delaunay, 0);
    CHECK_EQ(nbound, ne);
    /* Euler: V - E + F = 2 - loops for a connected domain with holes; the
     * callers' domains are connected with one outer loop. */
    size_t nref = 0;
    unsigned char *used = calloc(np, 1);
    for (size_t k = 0; k < 3 * nt; k++)
        used[tri[k]] = 1;
    for (size_t i = 0; i < np; i++)
        nref += used[i];
    free(used);
    size_t nloops = 0;
    for (size_t k = 0; k < d->ns; k++)
        nloops += d->seg[2 * k + 1] < d->seg[2 * k]; /* closing segment of each loop */
    CHECK_EQ((long long)nref - (long long)nedges + (long long)nt, 2 - (long long)nloops);
    /* Every constrained edge lies on its input segment: end points on the
     * segment's line (within rounding) and the id of that segment. */
    const int32_t *eid = fm_cdt_edge_ids(t), *ps = fm_cdt_point_segment(t);
    size_t off = 0;
    for (size_t m = 0; m < ne; m++) {
        int32_t id = eid[m], k = -1;
        for (size_t s = 0; s < d->ns && k < 0; s++)
            if (d->sid[s] == id)
                k = (int32_t)s;
        if (k < 0) {
            off++;
            continue;
        }
        for (int s = 0; s < 2; s++) {
            int32_t v = ed[2 * m + s];
            if (ps[v] < 0)
                off++;
        }
    }
    CHECK_EQ(off, 0);
    /* Points strictly between input indices were added by refinement on a
     * segment or inside; input points keep their coordinates. */
    for (size_t i = 0; i < d->np; i++)
        CHECK(p[2 * i] == d->uv[2 * i] && p[2 * i + 1] == d->uv[2 * i + 1]);
    return fm_test_failed_checks - before;
}

typedef struct quality {
    double angle_ok, len_ok; /* fractions */
    double min_angle;
    size_t nt;
} quality;

/* Angle fraction (>= min_angle) over triangles with no vertex within
 * `exclude` (uv distance) of one of the excl points; length fraction in
 * [0.7, 1.4] size over all edges. */
static quality measure(const fm_cdt *t, fm_cdt_metric_fn f, double size, double min_angle,
                       const double *excl, size_t nexcl, double exclude)
{
    quality q = {0, 0, 180, fm_cdt_ntriangles(t)};
    const double *p = fm_cdt_points(t);
    const int32_t *tri = fm_cdt_triangles(t);
    size_t n = 0, good = 0, ne = 0, lgood = 0;
    for (size_t k = 0; k < q.nt; k++) {
        const int32_t *v = tri + 3 * k;
        for (int i = 0; i < 3; i++) {
            /* Each interior edge twice, boundary once: fine for a fraction. */
            double l = mlen(f, p + 2 * v[i], p + 2 * v[(i + 1) % 3]);
            ne++;
            lgood += l >= 0.7 * size && l <= 1.4 * size;
        }
        int skip = 0;
        for (size_t c = 0; c < nexcl && !skip; c++)
            for (int i = 0; i < 3; i++)
                if (hypot(p[2 * v[i]] - excl[2 * c], p[2 * v[i] + 1] - excl[2 * c + 1]) < exclude)
                    skip = 1;
        if (skip)
            continue;
        double a = mangle(f, p + 2 * v[0], p + 2 * v[1], p + 2 * v[2]);
        n++;
        good += a >= min_angle - 1e-9;
        if (a < q.min_angle)
            q.min_angle = a;
    }
    q.angle_ok = n ? (double)good / (double)n : 1;
    q.len_ok = ne ? (double)lgood / (double)ne : 0;
    return q;
}

static fm_cdt *make(const domain *d, fm_error *err)
{
    fm_cdt *t = NULL;
    fm_status st = fm_cdt_create(d->uv, d->np, d->seg, d->sid, d->ns, &t, err);
    if (st != FM_OK)
        fprintf(stderr, "create: %s\n", err->message);
    return t;
}

static fm_status refine(fm_cdt *t, double size, fm_cdt_metric_fn f)
{
    fm_cdt_refine_options o;
    fm_cdt_refine_options_default(&o);
    o.size = size;
    o.metric = f;
    fm_error err;
    fm_status st = fm_cdt_refine(t, &o, &err);
    if (st != FM_OK)
        fprintf(stderr, "refine: %s\n", err.message);
    return st;
}

static void square(domain *d, double s)
{
    memset(d, 0, sizeof *d);
    double sq[] = {0, 0, s, 0, s, s, 0, s};
    add_loop(d, sq, 4, -1);
}

static void test_square(void)
{
    domain *d = malloc(sizeof *d);
    square(d, 1);
    fm_error err;
    fm_cdt *t = make(d, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    CHECK_EQ(fm_cdt_ntriangles(t), 2);
    CHECK_EQ(fm_cdt_nedges(t), 4);
    validate(t, d, 1);
    CHECK_EQ(refine(t, 0.05, NULL), FM_OK);
    validate(t, d, 1);
    quality q = measure(t, NULL, 0.05, 30, NULL, 0, 0);
    printf("square 0.05: %zu triangles, angle>=30 %.4f, length in [0.7,1.4] %.4f, min %.2f\n",
           q.nt, q.angle_ok, q.len_ok, q.min_angle);
    CHECK(q.angle_ok >= 0.99);
    CHECK(q.len_ok >= 0.95);
    CHECK(q.min_angle >= 20);
    /* About area / (sqrt(3)/4 size^2) triangles. */
    CHECK(q.nt > 700 && q.nt < 1400);
    /* Boundary points sit on the square's sides with their side's id. */
    const double *p = fm_cdt_points(t);
    const int32_t *ps = fm_cdt_point_segment(t);
    size_t onb = 0, bad = 0;
    for (size_t i = 4; i < fm_cdt_npoints(t); i++) {
        double x = p[2 * i], y = p[2 * i + 1];
        int want = y == 0 ? 0 : x == 1 ? 1 : y == 1 ? 2 : x == 0 ? 3 : -1;
        bad += ps[i] != want;
        onb += want >= 0;
    }
    CHECK_EQ(bad, 0);
    CHECK(onb >= 4 * 15);
    fm_cdt_destroy(t);
    free(d);
}

static void test_hole(void)
{
    domain *d = malloc(sizeof *d);
    square(d, 1);
    double hole[] = {0.3, 0.3, 0.3, 0.7, 0.7, 0.7, 0.7, 0.3}; /* clockwise */
    add_loop(d, hole, 4, -1);
    fm_error err;
    fm_cdt *t = make(d, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    CHECK_EQ(fm_cdt_ntriangles(t), 8);
    validate(t, d, 1);
    CHECK_EQ(refine(t, 0.04, NULL), FM_OK);
    validate(t, d, 1);
    quality q = measure(t, NULL, 0.04, 30, NULL, 0, 0);
    printf("hole 0.04: %zu triangles, angle>=30 %.4f, length %.4f, min %.2f\n", q.nt,
           q.angle_ok, q.len_ok, q.min_angle);
    CHECK(q.angle_ok >= 0.99);
    CHECK(q.len_ok >= 0.95);
    /* Nothing inside the hole. */
    const double *p = fm_cdt_points(t);
    size_t inside = 0;
    for (size_t i = 0; i < fm_cdt_npoints(t); i++)
        inside += p[2 * i] > 0.3 && p[2 * i] < 0.7 && p[2 * i + 1] > 0.3 && p[2 * i + 1] < 0.7;
    CHECK_EQ(inside, 0);
    fm_cdt_destroy(t);
    free(d);
}

static void test_nested(void)
{
    /* An island inside a hole: parity gives three regions. */
    domain *d = malloc(sizeof *d);
    square(d, 3);
    double hole[] = {0.5, 0.5, 2.5, 0.5, 2.5, 2.5, 0.5, 2.5}; /* any orientation */
    double island[] = {1, 1, 2, 1, 2, 2, 1, 2};
    add_loop(d, hole, 4, -1);
    add_loop(d, island, 4, -1);
    d->area = 9 - 4 + 1;
    fm_error err;
    fm_cdt *t = make(d, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    CHECK_EQ(refine(t, 0.1, NULL), FM_OK);
    const double *p = fm_cdt_points(t);
    const int32_t *tri = fm_cdt_triangles(t);
    double area = 0;
    size_t in_ring = 0;
    for (size_t k = 0; k < fm_cdt_ntriangles(t); k++) {
        const double *a = p + 2 * tri[3 * k], *b = p + 2 * tri[3 * k + 1], *c = p + 2 * tri[3 * k + 2];
        area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        double gx = (a[0] + b[0] + c[0]) / 3, gy = (a[1] + b[1] + c[1]) / 3;
        int in_hole = gx > 0.5 && gx < 2.5 && gy > 0.5 && gy < 2.5;
        int in_island = gx > 1 && gx < 2 && gy > 1 && gy < 2;
        in_ring += in_hole && !in_island;
    }
    CHECK_NEAR(area, 6, 1e-9);
    CHECK_EQ(in_ring, 0);
    fm_cdt_destroy(t);
    free(d);
}

static void test_lshape(void)
{
    domain *d = malloc(sizeof *d);
    memset(d, 0, sizeof *d);
    double l[] = {0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2};
    add_loop(d, l, 6, -1);
    fm_error err;
    fm_cdt *t = make(d, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    CHECK_EQ(fm_cdt_ntriangles(t), 4);
    validate(t, d, 1);
    CHECK_EQ(refine(t, 0.07, NULL), FM_OK);
    validate(t, d, 1);
    quality q = measure(t, NULL, 0.07, 30, NULL, 0, 0);
    printf("L 0.07: %zu triangles, angle>=30 %.4f, length %.4f, min %.2f\n", q.nt, q.angle_ok,
           q.len_ok, q.min_angle);
    CHECK(q.angle_ok >= 0.99);
    CHECK(q.len_ok >= 0.95);
    fm_cdt_destroy(t);
    free(d);
}

/* A polygon with a 10 degree and a 5 degree corner. */
static void test_small_angles(void)
{
    domain *d = malloc(sizeof *d);
    memset(d, 0, sizeof *d);
    const double pi = 3.14159265358979323846;
    double a10 = 10 * pi / 180, a5 = 5 * pi / 180;
    /* Corner A at the origin between the x axis and the ray at 10 deg;
     * corner B at (4, 0) with 5 degrees between the way back to A and the
     * side going back left to C. */
    double pts[] = {0, 0, 4, 0, 4 - 2 * cos(a5), 2 * sin(a5), 2, 1.5,
                    1.5 * cos(a10), 1.5 * sin(a10)};
    add_loop(d, pts, 5, -1);
    fm_error err;
    fm_cdt *t = make(d, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    validate(t, d, 1);
    fm_status st = refine(t, 0.05, NULL);
    CHECK_EQ(st, FM_OK);
    validate(t, d, 1);
    double corners[] = {0, 0, 4, 0};
    /* The wedge is narrower than the size out to size / angle. */
    quality q = measure(t, NULL, 0.05, 30, corners, 2, 0.05 / sin(a5) * 1.2);
    quality all = measure(t, NULL, 0.05, 30, NULL, 0, 0);
    printf("small angles 0.05: %zu triangles, angle>=30 %.4f (all %.4f), length %.4f, min %.2f (all %.2f)\n",
           q.nt, q.angle_ok, all.angle_ok, all.len_ok, q.min_angle, all.min_angle);
    CHECK(q.angle_ok >= 0.99);
    CHECK(all.len_ok >= 0.90);
    fm_cdt_destroy(t);
    free(d);
}

static void test_collinear(void)
{
    domain *d = malloc(sizeof *d);
    memset(d, 0, sizeof *d);
    /* Points exactly on the square's sides, but the segments run from
     * corner to corner: the segments are split there. The point near the
     * top is 1e-15 inside, so the top side just misses it. */
    double sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
    add_loop(d, sq, 4, -1);
    double extra[] = {0.25, 0, 0.5, 0, 0.75, 0, 1, 0.5, 0.5, 1 - 1e-15, 0.5, 0.5};
    for (int i = 0; i < 6; i++) {
        d->uv[2 * d->np] = extra[2 * i];
        d->uv[2 * d->np + 1] = extra[2 * i + 1];
        d->np++;
    }
    fm_error err;
    fm_cdt *t = make(d, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    validate(t, d, 1);
    /* Bottom split in 4, right in 2, the others whole. */
    CHECK_EQ(fm_cdt_nedges(t), 4 + 2 + 1 + 1);
    const int32_t *ps = fm_cdt_point_segment(t);
    CHECK_EQ(ps[4], 0);
    CHECK_EQ(ps[5], 0);
    CHECK_EQ(ps[6], 0);
    CHECK_EQ(ps[7], 1);
    CHECK_EQ(ps[8], -1);
    CHECK_EQ(ps[9], -1);
    CHECK_EQ(refine(t, 0.1, NULL), FM_OK);
    validate(t, d, 1);
    fm_cdt_destroy(t);

    /* Nearly collinear input: a square whose bottom side has a vertex
     * 1e-15 above the line, and a sliver notch. */
    memset(d, 0, sizeof *d);
    double nc[] = {0, 0, 0.5, 1e-15, 1, 0, 1, 1, 0.5, 1 - 1e-12, 0, 1};
    add_loop(d, nc, 6, -1);
    t = make(d, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    validate(t, d, 1);
    CHECK_EQ(refine(t, 0.05, NULL), FM_OK);
    validate(t, d, 1);
    fm_cdt_destroy(t);
    free(d);
}

static void test_stars(void)
{
    domain *d = malloc(sizeof *d);
    rng = 7;
    size_t total = 0, fails = 0;
    double worst_angle = 1, worst_len = 1;
    for (int s = 0; s < 40; s++) {
        memset(d, 0, sizeof *d);
        int n = 5 + (int)(rnd() * 40);
        double pts[2 * 64];
        double cx = rnd() * 10 - 5, cy = rnd() * 10 - 5;
        for (int i = 0; i < n; i++) {
            double a = 2 * 3.14159265358979323846 * (i + 0.8 * rnd()) / n;
            double r = 1 + 0.6 * rnd();
            pts[2 * i] = cx + r * cos(a);
            pts[2 * i + 1] = cy + r * sin(a);
        }
        add_loop(d, pts, (size_t)n, -1);
        fm_error err;
        fm_cdt *t = make(d, &err);
        CHECK(t != NULL);
        if (!t)
            continue;
        int f = validate(t, d, 1);
        double size = 0.03 + 0.06 * rnd();
        fm_cdt_metric_fn mf = s % 3 == 2 ? metric_varying : NULL;
        fm_status st = refine(t, size, mf);
        CHECK_EQ(st, FM_OK);
        if (st != FM_OK)
            fprintf(stderr, "star %d: %d vertices, size %g\n", s, n, size);
        f += validate(t, d, mf == NULL);
        /* Star vertices can make sharp corners: leave their surroundings
         * out of the angle figure. */
        double *corners = malloc(2 * (size_t)n * sizeof *corners);
        size_t nc = 0;
        for (int i = 0; i < n; i++) {
            const double *a = pts + 2 * ((i + n - 1) % n), *b = pts + 2 * i,
                         *c = pts + 2 * ((i + 1) % n);
            double ux = a[0] - b[0], uy = a[1] - b[1], vx = c[0] - b[0], vy = c[1] - b[1];
            double cosang = (ux * vx + uy * vy) / (hypot(ux, uy) * hypot(vx, vy));
            if (cosang > 0.5) {
                corners[2 * nc] = b[0];
                corners[2 * nc + 1] = b[1];
                nc++;
            }
        }
        quality q = measure(t, mf, size, 30, corners, nc, 3 * size);
        free(corners);
        if (q.angle_ok < worst_angle)
            worst_angle = q.angle_ok;
        if (q.len_ok < worst_len)
            worst_len = q.len_ok;
        CHECK(q.angle_ok >= 0.99);
        CHECK(q.len_ok >= 0.95);
        if (q.angle_ok < 0.99 || q.len_ok < 0.95)
            fprintf(stderr, "star %d: %d vertices, size %g, angle>=30 %.4f, length %.4f\n", s,
                    n, size, q.angle_ok, q.len_ok);
        total += q.nt;
        fails += f != 0;
        fm_cdt_destroy(t);
    }
    printf("stars: 40 polygons, %zu triangles, worst angle>=30 %.4f, worst length %.4f\n",
           total, worst_angle, worst_len);
    CHECK_EQ(fails, 0);
    free(d);
}

static void test_stretched_metric(void)
{
    domain *d = malloc(sizeof *d);
    memset(d, 0, sizeof *d);
    double rect[] = {0, 0, 1, 0, 1, 1.0 / 3, 0, 1.0 / 3}; /* a unit square in the metric */
    add_loop(d, rect, 4, -1);
    double hole[] = {0.4, 0.1, 0.4, 0.2, 0.6, 0.2, 0.6, 0.1};
    add_loop(d, hole, 4, -1);
    fm_error err;
    fm_cdt *t = make(d, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    CHECK_EQ(refine(t, 0.03, metric_stretch), FM_OK);
    validate(t, d, 0);
    quality q = measure(t, metric_stretch, 0.03, 30, NULL, 0, 0);
    quality id = measure(t, NULL, 0.03, 30, NULL, 0, 0);
    printf("stretched (E 1, G 9) 0.03: %zu triangles, metric angle>=30 %.4f, length %.4f, "
           "min %.2f; in (u,v) only %.4f\n",
           q.nt, q.angle_ok, q.len_ok, q.min_angle, id.angle_ok);
    CHECK(q.angle_ok >= 0.99);
    CHECK(q.len_ok >= 0.95);
    /* The mesh is shaped by the metric, not by (u, v). */
    CHECK(id.angle_ok < 0.5);
    fm_cdt_destroy(t);

    /* A varying, sheared metric. */
    square(d, 1);
    t = make(d, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    CHECK_EQ(refine(t, 0.04, metric_varying), FM_OK);
    validate(t, d, 0);
    q = measure(t, metric_varying, 0.04, 30, NULL, 0, 0);
    printf("varying metric 0.04: %zu triangles, angle>=30 %.4f, length %.4f, min %.2f\n", q.nt,
           q.angle_ok, q.len_ok, q.min_angle);
    CHECK(q.angle_ok >= 0.99);
    CHECK(q.len_ok >= 0.93);
    fm_cdt_destroy(t);
    free(d);
}

static void test_frozen(void)
{
    domain *d = malloc(sizeof *d);
    memset(d, 0, sizeof *d);
    /* The bottom side pre-split into 10 pieces with id 7 (a shared curve);
     * the rest of the square's sides ids 0 .. 2. */
    double pts[2 * 13];
    size_t n = 0;
    for (int i = 0; i < 10; i++) {
        pts[2 * n] = 0.1 * i;
        pts[2 * n + 1] = 0;
        n++;
    }
    double rest[] = {1, 0, 1, 1, 0, 1};
    for (int i = 0; i < 3; i++) {
        pts[2 * n] = rest[2 * i];
        pts[2 * n + 1] = rest[2 * i + 1];
        n++;
    }
    add_loop(d, pts, n, -1);
    for (int i = 0; i < 10; i++)
        d->sid[i] = 7;
    d->sid[10] = 0, d->sid[11] = 1, d->sid[12] = 2;
    fm_error err;
    fm_cdt *t = make(d, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    unsigned char frozen[8] = {0, 0, 0, 0, 0, 0, 0, 1};
    fm_cdt_refine_options o;
    fm_cdt_refine_options_default(&o);
    o.size = 0.03;
    o.frozen_ids = frozen;
    o.nfrozen = 8;
    CHECK_EQ(fm_cdt_refine(t, &o, &err), FM_OK);
    validate(t, d, 1);
    size_t n7 = 0;
    const int32_t *eid = fm_cdt_edge_ids(t), *ps = fm_cdt_point_segment(t);
    for (size_t m = 0; m < fm_cdt_nedges(t); m++)
        n7 += eid[m] == 7;
    CHECK_EQ(n7, 10);
    for (size_t i = d->np; i < fm_cdt_npoints(t); i++)
        CHECK(ps[i] != 7 && fm_cdt_points(t)[2 * i + 1] != 0);
    fm_cdt_refine_stats st;
    fm_cdt_refine_get_stats(t, &st);
    printf("frozen: %zu triangles, %zu rejected, %zu bad left\n", fm_cdt_ntriangles(t),
           st.rejected, st.bad_left);
    CHECK(st.inserted_segment > 0);
    fm_cdt_destroy(t);
    free(d);
}

static size_t split_calls;

static void split_circle(void *user, int32_t id, const double a[2], const double b[2], double f,
                         double out[2])
{
    (void)user;
    (void)id;
    split_calls++;
    double ta = atan2(a[1], a[0]), tb = atan2(b[1], b[0]);
    if (tb < ta - 3.14159265358979323846)
        tb += 2 * 3.14159265358979323846;
    if (tb > ta + 3.14159265358979323846)
        tb -= 2 * 3.14159265358979323846;
    double tm = ta + f * (tb - ta);
    out[0] = cos(tm);
    out[1] = sin(tm);
}

static void split_wild(void *user, int32_t id, const double a[2], const double b[2], double f,
                       double out[2])
{
    (void)user;
    (void)id;
    (void)f;
    split_calls++;
    /* Far off the segment, or exactly on an end: never valid. */
    if (split_calls % 2) {
        out[0] = 0.5 * (a[0] + b[0]) + 10;
        out[1] = 0.5 * (a[1] + b[1]) - 3;
    } else {
        out[0] = a[0];
        out[1] = a[1];
    }
}

static void test_split_callback(void)
{
    domain *d = malloc(sizeof *d);
    memset(d, 0, sizeof *d);
    const double pi = 3.14159265358979323846;
    double pts[2 * 8];
    for (int i = 0; i < 8; i++) {
        pts[2 * i] = cos(2 * pi * i / 8);
        pts[2 * i + 1] = sin(2 * pi * i / 8);
    }
    add_loop(d, pts, 8, -1);
    for (int i = 0; i < 8; i++)
        d->sid[i] = 3;
    fm_error err;
    fm_cdt *t = make(d, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    fm_cdt_refine_options o;
    fm_cdt_refine_options_default(&o);
    o.size = 0.08;
    o.split = split_circle;
    split_calls = 0;
    CHECK_EQ(fm_cdt_refine(t, &o, &err), FM_OK);
    CHECK(split_calls > 50);
    const double *p = fm_cdt_points(t);
    const int32_t *ps = fm_cdt_point_segment(t);
    size_t off = 0, nb = 0, wrongid = 0;
    for (size_t i = 0; i < fm_cdt_npoints(t); i++)
        if (ps[i] >= 0) {
            nb++;
            off += fabs(hypot(p[2 * i], p[2 * i + 1]) - 1) > 1e-12;
            wrongid += ps[i] != 3;
        }
    CHECK(nb > 70);
    CHECK_EQ(off, 0);
    CHECK_EQ(wrongid, 0);
    /* Area: the boundary is now a finer polygon inscribed in the circle. */
    const int32_t *tri = fm_cdt_triangles(t);
    double area = 0;
    int ccw = 1;
    for (size_t k = 0; k < fm_cdt_ntriangles(t); k++) {
        const double *a = p + 2 * tri[3 * k], *b = p + 2 * tri[3 * k + 1], *c = p + 2 * tri[3 * k + 2];
        ccw &= fm_orient2d(a, b, c) > 0;
        area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    CHECK(ccw);
    CHECK(area > 3.1 && area < pi);
    quality q = measure(t, NULL, 0.08, 30, NULL, 0, 0);
    printf("circle with split callback: %zu triangles, %zu boundary points, angle>=30 %.4f, "
           "length %.4f\n",
           q.nt, nb, q.angle_ok, q.len_ok);
    CHECK(q.angle_ok >= 0.99);
    fm_cdt_destroy(t);

    /* A callback whose points are never valid: the straight-line points
     * are used and the result is exactly what no callback gives. */
    square(d, 1);
    t = make(d, &err);
    fm_cdt *ref = make(d, &err);
    CHECK(t != NULL && ref != NULL);
    if (!t || !ref)
        return;
    o.size = 0.1;
    o.split = split_wild;
    split_calls = 0;
    CHECK_EQ(fm_cdt_refine(t, &o, &err), FM_OK);
    CHECK(split_calls > 10);
    validate(t, d, 1);
    o.split = NULL;
    CHECK_EQ(fm_cdt_refine(ref, &o, &err), FM_OK);
    CHECK_EQ(fm_cdt_npoints(t), fm_cdt_npoints(ref));
    CHECK_EQ(fm_cdt_ntriangles(t), fm_cdt_ntriangles(ref));
    if (fm_cdt_npoints(t) == fm_cdt_npoints(ref))
        CHECK(memcmp(fm_cdt_points(t), fm_cdt_points(ref),
                     2 * fm_cdt_npoints(t) * sizeof(double)) == 0);
    fm_cdt_destroy(t);
    fm_cdt_destroy(ref);
    free(d);
}

static void test_deterministic(void)
{
    domain *d = malloc(sizeof *d);
    square(d, 1);
    double hole[] = {0.2, 0.2, 0.2, 0.5, 0.6, 0.4};
    add_loop(d, hole, 3, -1);
    fm_error err;
    fm_cdt *a = make(d, &err), *b = make(d, &err);
    CHECK(a && b);
    if (!a || !b)
        return;
    CHECK_EQ(refine(a, 0.03, metric_varying), FM_OK);
    CHECK_EQ(refine(b, 0.03, metric_varying), FM_OK);
    CHECK_EQ(fm_cdt_npoints(a), fm_cdt_npoints(b));
    CHECK_EQ(fm_cdt_ntriangles(a), fm_cdt_ntriangles(b));
    CHECK_EQ(fm_cdt_nedges(a), fm_cdt_nedges(b));
    if (fm_cdt_npoints(a) == fm_cdt_npoints(b) && fm_cdt_ntriangles(a) == fm_cdt_ntriangles(b) &&
        fm_cdt_nedges(a) == fm_cdt_nedges(b)) {
        CHECK(memcmp(fm_cdt_points(a), fm_cdt_points(b), 2 * fm_cdt_npoints(a) * sizeof(double)) == 0);
        CHECK(memcmp(fm_cdt_triangles(a), fm_cdt_triangles(b),
                     3 * fm_cdt_ntriangles(a) * sizeof(int32_t)) == 0);
        CHECK(memcmp(fm_cdt_edges(a), fm_cdt_edges(b), 2 * fm_cdt_nedges(a) * sizeof(int32_t)) == 0);
    }
    /* Refining again with a smaller size continues from the result. */
    size_t before = fm_cdt_ntriangles(a);
    CHECK_EQ(refine(a, 0.015, metric_varying), FM_OK);
    CHECK(fm_cdt_ntriangles(a) > 3 * before);
    validate(a, d, 0);
    fm_cdt_destroy(a);
    fm_cdt_destroy(b);
    free(d);
}

static void test_max_points(void)
{
    domain *d = malloc(sizeof *d);
    square(d, 1);
    fm_error err;
    fm_cdt *t = make(d, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    fm_cdt_refine_options o;
    fm_cdt_refine_options_default(&o);
    o.size = 0.01;
    o.max_points = 500;
    CHECK_EQ(fm_cdt_refine(t, &o, &err), FM_ERR_INVALID);
    CHECK(strstr(err.message, "max_points") != NULL);
    CHECK(fm_cdt_npoints(t) <= 500);
    validate(t, d, 1);
    o.max_points = 0;
    o.size = -1;
    CHECK_EQ(fm_cdt_refine(t, &o, &err), FM_ERR_INVALID);
    fm_cdt_destroy(t);
    free(d);
}

/* The first fundamental form of S = (u - v, b^3), b = u + v - 0.1: singular
 * along the diagonal b = 0 (its null direction along the diagonal's
 * normal), sheared everywhere. */
static void metric_fold(void *user, const double uv[2], double m[3])
{
    (void)user;
    double b = uv[0] + uv[1] - 0.1, c = 3 * b * b;
    m[0] = 1 + c * c, m[1] = -1 + c * c, m[2] = 1 + c * c;
}

/* Nearly singular near the line v = 0.3 (S = (u, (v - 0.3)^3)): the
 * diametral ellipses of segments crossing it reach arbitrarily far. */
static void metric_pinch(void *user, const double uv[2], double m[3])
{
    (void)user;
    double w = uv[1] - 0.3;
    m[0] = 1, m[1] = 0, m[2] = 9 * w * w * w * w;
}

static void test_degenerate_metric(void)
{
    domain *d = malloc(sizeof *d);
    square(d, 1);
    fm_cdt_metric_fn fs[2] = {metric_fold, metric_pinch};
    for (int k = 0; k < 2; k++) {
        fm_error err;
        fm_cdt *t = make(d, &err);
        CHECK(t != NULL);
        if (!t)
            break;
        fm_cdt_refine_options o;
        fm_cdt_refine_options_default(&o);
        o.size = 0.05;
        o.metric = fs[k];
        o.max_anisotropy = 10;
        CHECK_EQ(fm_cdt_refine(t, &o, &err), FM_OK);
        validate(t, d, 0);
        fm_cdt_refine_stats st;
        fm_cdt_refine_get_stats(t, &st);
        printf("degenerate metric %d: %zu points, %zu triangles, %zu clamped, %zu bad left, "
               "capped %d\n",
               k, fm_cdt_npoints(t), fm_cdt_ntriangles(t), st.clamped, st.bad_left, st.capped);
        CHECK(st.clamped > 0);
        CHECK_EQ(st.capped, 0);
        /* About area / size^2 in the clamped metric, not a cascade. */
        CHECK(fm_cdt_npoints(t) < 20000);
        fm_cdt_destroy(t);
    }
    free(d);
}

/* The automatic cap ends refinement without an error: a metric that grows
 * without bound towards a corner asks for ever more points there. */
static void metric_blowup(void *user, const double uv[2], double m[3])
{
    (void)user;
    double r2 = uv[0] * uv[0] + uv[1] * uv[1];
    double s = 1 / (r2 * r2 + 1e-300);
    m[0] = s, m[1] = 0, m[2] = s;
}

static void test_auto_cap(void)
{
    domain *d = malloc(sizeof *d);
    square(d, 1);
    fm_error err;
    fm_cdt *t = make(d, &err);
    CHECK(t != NULL);
    if (t) {
        fm_cdt_refine_options o;
        fm_cdt_refine_options_default(&o);
        o.size = 0.5;
        o.metric = metric_blowup;
        o.min_length = -1; /* no floor: nothing else stops it */
        CHECK_EQ(fm_cdt_refine(t, &o, &err), FM_OK);
        validate(t, d, 0);
        fm_cdt_refine_stats st;
        fm_cdt_refine_get_stats(t, &st);
        printf("blow-up metric: %zu points, capped %d, %zu bad left\n", fm_cdt_npoints(t),
               st.capped, st.bad_left);
        CHECK_EQ(st.capped, 1);
        CHECK(st.bad_left > 0);
        fm_cdt_destroy(t);
    }
    free(d);
}

static void bad_metric(void *user, const double uv[2], double m[3])
{
    (void)user;
    m[0] = 1, m[1] = 2, m[2] = uv[0] > 0.5 ? 1 : 5;
}

static void test_bad_input(void)
{
    fm_error err;
    fm_cdt *t = NULL;
    double dup[] = {0, 0, 1, 0, 1, 1, 0, 1, 1, 0};
    int32_t sq[] = {0, 1, 1, 2, 2, 3, 3, 0};
    CHECK_EQ(fm_cdt_create(dup, 5, sq, NULL, 4, &t, &err), FM_ERR_INVALID);
    CHECK(t == NULL);
    CHECK(strstr(err.message, "points 1 and 4") != NULL);

    /* A bow tie: segments 0 and 2 cross. */
    double bow[] = {0, 0, 1, 1, 1, 0, 0, 1};
    CHECK_EQ(fm_cdt_create(bow, 4, sq, NULL, 4, &t, &err), FM_ERR_TOPOLOGY);
    CHECK(strstr(err.message, "cross") != NULL);
    CHECK(t == NULL);

    /* Two loops that cross. */
    double two[] = {0, 0, 2, 0, 2, 2, 0, 2, 1, 1, 3, 1, 3, 3, 1, 3};
    int32_t two_seg[] = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4};
    CHECK_EQ(fm_cdt_create(two, 8, two_seg, NULL, 8, &t, &err), FM_ERR_TOPOLOGY);

    /* Open chain. */
    CHECK_EQ(fm_cdt_create(bow + 0, 4, sq, NULL, 3, &t, &err), FM_ERR_TOPOLOGY);
    CHECK(strstr(err.message, "closed loops") != NULL);

    /* Overlapping collinear segments. */
    double ov[] = {0, 0, 2, 0, 2, 1, 0, 1, 1, 0, 1, -1};
    int32_t ov_seg[] = {0, 1, 1, 2, 2, 3, 3, 0, 0, 4, 4, 5, 5, 0};
    CHECK_EQ(fm_cdt_create(ov, 6, ov_seg, NULL, 7, &t, &err), FM_ERR_TOPOLOGY);
    CHECK(strstr(err.message, "overlap") != NULL);

    /* Index out of range, repeated segment, degenerate segment, NaN. */
    int32_t oor[] = {0, 1, 1, 2, 2, 9, 3, 0};
    CHECK_EQ(fm_cdt_create(dup, 4, oor, NULL, 4, &t, &err), FM_ERR_INVALID);
    int32_t rep[] = {0, 1, 1, 0, 1, 2, 2, 3, 3, 1};
    CHECK_EQ(fm_cdt_create(dup, 4, rep, NULL, 5, &t, &err), FM_ERR_INVALID);
    int32_t self[] = {0, 0, 1, 2, 2, 3, 3, 1};
    CHECK_EQ(fm_cdt_create(dup, 4, self, NULL, 4, &t, &err), FM_ERR_INVALID);
    double nan[] = {0, 0, 1, 0, 1, NAN, 0, 1};
    CHECK_EQ(fm_cdt_create(nan, 4, sq, NULL, 4, &t, &err), FM_ERR_INVALID);

    /* A metric that is not positive definite somewhere. */
    CHECK_EQ(fm_cdt_create(dup, 4, sq, NULL, 4, &t, &err), FM_OK);
    if (t) {
        fm_cdt_refine_options o;
        fm_cdt_refine_options_default(&o);
        o.size = 0.1;
        o.metric = bad_metric;
        CHECK_EQ(fm_cdt_refine(t, &o, &err), FM_ERR_NUMERIC);
        CHECK(strstr(err.message, "positive definite") != NULL);
        fm_cdt_destroy(t);
    }
}

FM_TEST_MAIN(FM_CASE(test_square), FM_CASE(test_hole), FM_CASE(test_nested),
             FM_CASE(test_lshape), FM_CASE(test_small_angles), FM_CASE(test_collinear),
             FM_CASE(test_stars), FM_CASE(test_stretched_metric), FM_CASE(test_frozen),
             FM_CASE(test_split_callback), FM_CASE(test_deterministic),
             FM_CASE(test_max_points), FM_CASE(test_degenerate_metric),
             FM_CASE(test_auto_cap), FM_CASE(test_bad_input))
