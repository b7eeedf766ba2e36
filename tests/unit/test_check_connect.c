/* check_connect (tests/tools, issue 5): the exact contact tests, the grid
 * broad phase against brute force, distances against sampling, and the
 * whole check on hand-built fault sets written as OBJ: crossing faults,
 * conforming T and X junctions, a touch at a coincident but unshared
 * vertex, a 300 m gap, coplanar overlap; then the program itself (exit
 * codes, --criteria, --allow-pairs, FILE:LINE errors, JSON). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "cc_check.h"
#include "cc_geom.h"
#include "cc_grid.h"
#include "cc_obj.h"
#include "fm_test.h"

#define TMP FM_TMP_DIR "/check_connect"

/* ---- exact contact */

static cc_contact classify(const double x[][3], const uint32_t a[3], const uint32_t b[3])
{
    return cc_classify(a, b, &x[0][0]);
}

static void test_contact_basic(void)
{
    /* Corners 0-2: triangle in z = 0; the rest placed per case. */
    double x[][3] = {{0, 0, 0},   {4, 0, 0},   {0, 4, 0},   /* 0-2 T1 */
                     {1, 1, -1},  {1, 1, 1},   {3, 3, 1},   /* 3-5 crosses T1 */
                     {1, 1, 0.5}, {1, 2, 2},   {2, 1, 2},   /* 6-8 above, apart */
                     {1, 1, 0},   {1, 2, 2},   {2, 1, 2},   /* 9-11 vertex 9 touches T1's inside */
                     {0, 0, 0},   {-1, -1, 1}, {-1, 0, 1},  /* 12-14: 12 = 0 by coordinates */
                     {2, 2, 0},   {5, 2, 1},   {2, 5, 1},   /* 15-17: 15 on T1's hypotenuse */
                     {1, 1, 0},   {3, 0.5, 0}, {0.5, 3, 0}, /* 18-20 coplanar inside T1 */
                     {5, 5, 0},   {6, 5, 0},   {5, 6, 0}};  /* 21-23 coplanar, apart */
    uint32_t t1[3] = {0, 1, 2};
    CHECK_EQ(classify(x, t1, (uint32_t[]){3, 4, 5}), CC_VIOLATION);
    CHECK_EQ(classify(x, t1, (uint32_t[]){6, 7, 8}), CC_APART);
    CHECK_EQ(classify(x, t1, (uint32_t[]){9, 10, 11}), CC_VIOLATION);
    /* Same coordinates as corner 0 but another index: touching. */
    CHECK_EQ(classify(x, t1, (uint32_t[]){12, 13, 14}), CC_VIOLATION);
    /* The same vertex by index: only that vertex in common. */
    CHECK_EQ(classify(x, t1, (uint32_t[]){0, 13, 14}), CC_APART);
    CHECK_EQ(classify(x, t1, (uint32_t[]){15, 16, 17}), CC_VIOLATION);
    CHECK_EQ(classify(x, t1, (uint32_t[]){18, 19, 20}), CC_VIOLATION);
    CHECK_EQ(classify(x, t1, (uint32_t[]){21, 22, 23}), CC_APART);
    CHECK_EQ(classify(x, t1, (uint32_t[]){0, 1, 2}), CC_VIOLATION);
    CHECK_EQ(classify(x, t1, (uint32_t[]){2, 0, 1}), CC_VIOLATION);
}

static void test_contact_shared_vertex(void)
{
    double x[][3] = {{0, 0, 0},  {4, 0, 0},  {0, 4, 0}, /* T1 */
                     {1, 1, -1}, {1, 1, 3},             /* 3, 4: with 0, a triangle through T1 */
                     {-1, 0, 1}, {0, -1, 1},            /* 5, 6: with 0, beside it */
                     {2, 0, 0},  {1, -3, 0},            /* 7 on T1's edge 0-1; coplanar */
                     {-2, 0, 0}, {0, -2, 0},            /* 9, 10 coplanar, outside */
                     {4, 0, 0}};                        /* 11 = 1 by coordinates */
    uint32_t t1[3] = {0, 1, 2};
    CHECK_EQ(classify(x, t1, (uint32_t[]){0, 3, 4}), CC_VIOLATION);
    CHECK_EQ(classify(x, t1, (uint32_t[]){0, 5, 6}), CC_APART);
    /* Coplanar, along the edge 0-1 up to 7: overlap beyond the vertex. */
    CHECK_EQ(classify(x, t1, (uint32_t[]){0, 7, 8}), CC_VIOLATION);
    CHECK_EQ(classify(x, t1, (uint32_t[]){0, 9, 10}), CC_APART);
    /* Coplanar, a corner coinciding with corner 1 under another index. */
    CHECK_EQ(classify(x, t1, (uint32_t[]){0, 11, 8}), CC_VIOLATION);
    /* Corners in the other order change nothing. */
    CHECK_EQ(classify(x, (uint32_t[]){2, 0, 1}, (uint32_t[]){4, 0, 3}), CC_VIOLATION);
    CHECK_EQ(classify(x, (uint32_t[]){1, 2, 0}, (uint32_t[]){6, 5, 0}), CC_APART);
}

static void test_contact_shared_edge(void)
{
    double x[][3] = {{0, 0, 0},  {4, 0, 0}, {0, 4, 0}, /* T1, edge 0-1 shared */
                     {2, -3, 0},                       /* 3 coplanar, other side */
                     {2, 3, 0},                        /* 4 coplanar, same side: fold */
                     {2, 0, 3},                        /* 5 out of plane */
                     {0, 4, 0}};                       /* 6 = 2 by coordinates */
    uint32_t t1[3] = {0, 1, 2};
    CHECK_EQ(classify(x, t1, (uint32_t[]){1, 0, 3}), CC_APART);
    CHECK_EQ(classify(x, t1, (uint32_t[]){1, 0, 4}), CC_VIOLATION);
    CHECK_EQ(classify(x, t1, (uint32_t[]){0, 5, 1}), CC_APART);
    CHECK_EQ(classify(x, t1, (uint32_t[]){6, 0, 1}), CC_VIOLATION);
}

static void test_contact_degenerate(void)
{
    double x[][3] = {{0, 0, 0},  {4, 0, 0}, {0, 4, 0},   /* T1 */
                     {1, 1, -1}, {1, 1, 1}, {1, 1, 0.5}, /* collinear, through T1 */
                     {1, 1, 1},  {1, 1, 2}, {1, 1, 3},   /* collinear, above */
                     {0, 0, 1},  {0, 0, 2}};             /* with 0: collinear, above */
    uint32_t t1[3] = {0, 1, 2};
    CHECK(cc_degenerate(x[3], x[4], x[5]));
    CHECK(!cc_degenerate(x[0], x[1], x[2]));
    CHECK_EQ(classify(x, t1, (uint32_t[]){3, 4, 5}), CC_VIOLATION);
    CHECK_EQ(classify(x, t1, (uint32_t[]){6, 7, 8}), CC_APART);
    CHECK_EQ(classify(x, t1, (uint32_t[]){0, 9, 10}), CC_SKIPPED);
    CHECK_EQ(classify(x, (uint32_t[]){3, 4, 5}, (uint32_t[]){6, 7, 8}), CC_VIOLATION);
    CHECK_EQ(classify(x, (uint32_t[]){3, 5, 5}, (uint32_t[]){7, 8, 8}), CC_APART);
}

/* Exactness where floating point would guess: UTM-sized coordinates, a
 * corner a few ulps off the other triangle's plane. */
static void test_contact_exact(void)
{
    double e = 3774142.1356237307, n = 435857.86437626905;
    double y[][3] = {{n, e, 0},
                     {n + 1000, e, 0},
                     {n, e + 1000, 0},
                     {n + 100, e + 100, 1e-30},
                     {n + 300, e + 300, 500},
                     {n + 400, e + 100, 600}};
    uint32_t t1[3] = {0, 1, 2}, t2[3] = {3, 4, 5};
    /* Corner 3 just above T1: apart; on it: touching; just below: they
     * cross. */
    CHECK_EQ(classify(y, t1, t2), CC_APART);
    y[3][2] = 0;
    CHECK_EQ(classify(y, t1, t2), CC_VIOLATION);
    y[3][2] = -1e-30;
    CHECK_EQ(classify(y, t1, t2), CC_VIOLATION);
    /* Corner 3 on T1's plane, a hair outside its edge 0-1 (y = e - 1 ulp). */
    y[3][2] = 0;
    y[3][1] = nextafter(e, 0);
    CHECK_EQ(classify(y, t1, t2), CC_APART);
    y[3][1] = e;
    CHECK_EQ(classify(y, t1, t2), CC_VIOLATION);
}

static uint64_t rng_state = 88172645463325252ull;
static uint64_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return rng_state;
}
static double urand(void)
{
    return (double)(rnd() >> 11) * 0x1.0p-53;
}

/* Contact does not depend on which triangle comes first, the order of the
 * corners or their winding, on small integer grids full of touching and
 * coplanar cases. */
static void test_contact_symmetry(void)
{
    int touching = 0, violations = 0;
    for (int it = 0; it < 20000; it++) {
        double x[6][3];
        for (int i = 0; i < 6; i++)
            for (int k = 0; k < 3; k++)
                x[i][k] = (double)(rnd() % 4);
        const double *p[3] = {x[0], x[1], x[2]}, *q[3] = {x[3], x[4], x[5]};
        int r = cc_tri_tri(p, q);
        const double *q2[3] = {x[5], x[3], x[4]}, *p2[3] = {x[1], x[0], x[2]};
        CHECK_EQ(cc_tri_tri(q, p), r);
        CHECK_EQ(cc_tri_tri(p2, q2), r);
        CHECK_EQ(cc_tri_tri(q2, p2), r);
        uint32_t a[3] = {0, 1, 2}, b[3] = {3, 4, 5}, a2[3] = {2, 1, 0}, b2[3] = {4, 5, 3};
        int c = cc_classify(a, b, &x[0][0]);
        CHECK_EQ(c, r ? CC_VIOLATION : CC_APART);
        CHECK_EQ(cc_classify(b2, a2, &x[0][0]), c);
        /* Sharing corner 0 with itself: the verdict is symmetric too. */
        uint32_t s1[3] = {0, 1, 2}, s2[3] = {0, 4, 5}, s3[3] = {5, 0, 4};
        CHECK_EQ(cc_classify(s1, s2, &x[0][0]), cc_classify(s3, a2, &x[0][0]));
        touching += r;
        violations += c == CC_VIOLATION;
    }
    CHECK(touching > 1000);
    CHECK(violations == touching);
}

/* A floating-point interval test (Möller) on random triangles far from
 * any degenerate configuration agrees with the exact one. */
static int float_tri_tri(const double p[3][3], const double q[3][3], int *unsure)
{
    double n1[3], n2[3], e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = p[1][k] - p[0][k];
        e2[k] = p[2][k] - p[0][k];
    }
    n1[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n1[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n1[2] = e1[0] * e2[1] - e1[1] * e2[0];
    for (int k = 0; k < 3; k++) {
        e1[k] = q[1][k] - q[0][k];
        e2[k] = q[2][k] - q[0][k];
    }
    n2[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n2[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n2[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double dq[3], dp[3];
    for (int i = 0; i < 3; i++) {
        dq[i] =
            (q[i][0] - p[0][0]) * n1[0] + (q[i][1] - p[0][1]) * n1[1] + (q[i][2] - p[0][2]) * n1[2];
        dp[i] =
            (p[i][0] - q[0][0]) * n2[0] + (p[i][1] - q[0][1]) * n2[1] + (p[i][2] - q[0][2]) * n2[2];
        if (fabs(dq[i]) < 1e-6 || fabs(dp[i]) < 1e-6)
            *unsure = 1;
    }
    if ((dq[0] > 0 && dq[1] > 0 && dq[2] > 0) || (dq[0] < 0 && dq[1] < 0 && dq[2] < 0))
        return 0;
    if ((dp[0] > 0 && dp[1] > 0 && dp[2] > 0) || (dp[0] < 0 && dp[1] < 0 && dp[2] < 0))
        return 0;
    double dir[3] = {n1[1] * n2[2] - n1[2] * n2[1], n1[2] * n2[0] - n1[0] * n2[2],
                     n1[0] * n2[1] - n1[1] * n2[0]};
    double iv[2][2];
    for (int t = 0; t < 2; t++) {
        const double(*v)[3] = t ? q : p;
        const double *d = t ? dq : dp;
        double lo = INFINITY, hi = -INFINITY;
        for (int i = 0; i < 3; i++) {
            int j = (i + 1) % 3;
            if ((d[i] > 0) == (d[j] > 0))
                continue;
            double s = d[i] / (d[i] - d[j]), proj = 0;
            for (int k = 0; k < 3; k++)
                proj += (v[i][k] + s * (v[j][k] - v[i][k])) * dir[k];
            lo = fmin(lo, proj);
            hi = fmax(hi, proj);
        }
        iv[t][0] = lo;
        iv[t][1] = hi;
    }
    double gap = fmax(iv[1][0] - iv[0][1], iv[0][0] - iv[1][1]);
    if (fabs(gap) < 1e-6)
        *unsure = 1;
    return gap <= 0;
}

static void test_contact_random(void)
{
    int compared = 0, hits = 0;
    for (int it = 0; it < 50000; it++) {
        double p[3][3], q[3][3];
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) {
                p[i][k] = urand();
                q[i][k] = urand();
            }
        int unsure = 0, f = float_tri_tri((const double(*)[3])p, (const double(*)[3])q, &unsure);
        if (unsure)
            continue;
        const double *pp[3] = {p[0], p[1], p[2]}, *qq[3] = {q[0], q[1], q[2]};
        CHECK_EQ(cc_tri_tri(pp, qq), f);
        compared++;
        hits += f;
    }
    CHECK(compared > 40000);
    CHECK(hits > 5000 && hits < compared - 5000);
}

/* ---- distances */

static double sampled_tri_tri(const double *const p[3], const double *const q[3], int n)
{
    double best = INFINITY;
    for (int i = 0; i <= n; i++)
        for (int j = 0; i + j <= n; j++) {
            double a[3];
            for (int k = 0; k < 3; k++)
                a[k] = p[0][k] + (p[1][k] - p[0][k]) * i / n + (p[2][k] - p[0][k]) * j / n;
            for (int u = 0; u <= n; u++)
                for (int v = 0; u + v <= n; v++) {
                    double d = 0;
                    for (int k = 0; k < 3; k++) {
                        double b =
                            q[0][k] + (q[1][k] - q[0][k]) * u / n + (q[2][k] - q[0][k]) * v / n;
                        d += (a[k] - b) * (a[k] - b);
                    }
                    best = fmin(best, sqrt(d));
                }
        }
    return best;
}

static void test_distances(void)
{
    double x[][3] = {{0, 0, 0},   {1000, 0, 0},   {0, 1000, 0},
                     {0, 0, 300}, {1000, 0, 300}, {0, 1000, 300}};
    const double *p[3] = {x[0], x[1], x[2]}, *q[3] = {x[3], x[4], x[5]};
    CHECK_NEAR(cc_dist_tri_tri(p, q), 300, 1e-9);
    CHECK_NEAR(cc_dist_seg_tri(x[3], x[4], p), 300, 1e-9);
    /* A vertical segment whose foot is outside the triangle. */
    double a[3] = {600, 600, 50}, b[3] = {600, 600, 400};
    CHECK_NEAR(cc_dist_seg_tri(a, b, p), 150, 1e-9); /* (600, 600, 50) to (500, 500, 0) */
    double c[3] = {200, 200, -50}, d[3] = {200, 200, 40};
    CHECK_EQ(cc_dist_seg_tri(c, d, p), 0);
    /* Random triangles far from the origin: never above the sampled
     * minimum, never far below it. */
    for (int it = 0; it < 100; it++) {
        double y[6][3];
        for (int i = 0; i < 6; i++)
            for (int k = 0; k < 3; k++)
                y[i][k] = (k == 1 ? 3.7e6 : 4e5) + 1000 * urand() + (i >= 3 ? 800 : 0);
        const double *r[3] = {y[0], y[1], y[2]}, *s[3] = {y[3], y[4], y[5]};
        double dist = cc_dist_tri_tri(r, s), smp = sampled_tri_tri(r, s, 40);
        CHECK(dist <= smp + 1e-6);
        CHECK(dist >= smp - 100); /* lattice spacing: edges up to ~1700 m / 40, on both */
    }
}

/* ---- broad phase */

typedef struct pairs {
    uint32_t (*p)[2];
    size_t n, cap;
} pairs;

static void collect(void *ctx, uint32_t i, uint32_t j)
{
    pairs *ps = ctx;
    if (ps->n == ps->cap) {
        ps->cap = ps->cap ? 2 * ps->cap : 256;
        ps->p = realloc(ps->p, ps->cap * sizeof *ps->p);
    }
    ps->p[ps->n][0] = i;
    ps->p[ps->n][1] = j;
    ps->n++;
}

static int cmp_pair2(const void *a, const void *b)
{
    const uint32_t *x = a, *y = b;
    if (x[0] != y[0])
        return x[0] < y[0] ? -1 : 1;
    return (x[1] > y[1]) - (x[1] < y[1]);
}

static void test_grid(void)
{
    enum { N = 1500 };
    double *box = malloc(6 * N * sizeof *box);
    uint32_t group[N];
    for (int i = 0; i < N; i++) {
        for (int k = 0; k < 3; k++) {
            /* integer corners: boxes that touch exactly are frequent */
            double lo = (double)(rnd() % 100), size = (double)(rnd() % 12);
            if (i % 50 == 0)
                size *= 10;
            box[6 * i + k] = lo + 3.5e6;
            box[6 * i + 3 + k] = lo + size + 3.5e6;
        }
        group[i] = (uint32_t)(rnd() % 7);
    }
    for (int grouped = 0; grouped < 2; grouped++) {
        pairs got = {0};
        CHECK_EQ(cc_grid_pairs(box, N, grouped ? group : NULL, collect, &got), 0);
        qsort(got.p, got.n, sizeof *got.p, cmp_pair2);
        size_t want = 0, k = 0;
        int ok = 1;
        for (uint32_t i = 0; i < N; i++)
            for (uint32_t j = i + 1; j < N; j++) {
                int overlap = 1;
                for (int d = 0; d < 3; d++)
                    overlap &= box[6 * i + d] <= box[6 * j + 3 + d] &&
                               box[6 * j + d] <= box[6 * i + 3 + d];
                if (!overlap || (grouped && group[i] == group[j]))
                    continue;
                want++;
                if (k < got.n && got.p[k][0] == i && got.p[k][1] == j)
                    k++;
                else
                    ok = 0;
            }
        CHECK(ok);
        CHECK_EQ(got.n, want);
        CHECK(want > 1000);
        free(got.p);
    }
    free(box);
}

/* ---- hand-built fault sets */

typedef struct fault {
    const char *name;
    uint32_t *f;
    size_t nf;
} fault;

typedef struct obj {
    double (*v)[3];
    size_t nv;
    fault fault[4];
    int nfaults;
} obj;

static uint32_t add_v(obj *o, double x, double y, double z)
{
    o->v = realloc(o->v, (o->nv + 1) * sizeof *o->v);
    o->v[o->nv][0] = x;
    o->v[o->nv][1] = y;
    o->v[o->nv][2] = z;
    return (uint32_t)o->nv++;
}

static int add_fault(obj *o, const char *name)
{
    o->fault[o->nfaults].name = name;
    return o->nfaults++;
}

static void add_f(obj *o, int f, uint32_t a, uint32_t b, uint32_t c)
{
    fault *fl = &o->fault[f];
    fl->f = realloc(fl->f, (fl->nf + 1) * 3 * sizeof *fl->f);
    fl->f[3 * fl->nf] = a;
    fl->f[3 * fl->nf + 1] = b;
    fl->f[3 * fl->nf + 2] = c;
    fl->nf++;
}

/* A grid surface origin + i du + j dv, i < nu, j < nv; column `take` of
 * the vertex indices comes from `col` when given; column `give` is
 * returned in `out` (when given). */
static void grid(obj *o, int f, const double org[3], const double du[3], const double dv[3], int nu,
                 int nv, int take, const uint32_t *col, int give, uint32_t *out)
{
    uint32_t *id = malloc((size_t)(nu * nv) * sizeof *id);
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            if (col && i == take)
                id[i * nv + j] = col[j];
            else
                id[i * nv + j] =
                    add_v(o, org[0] + i * du[0] + j * dv[0], org[1] + i * du[1] + j * dv[1],
                          org[2] + i * du[2] + j * dv[2]);
            if (out && i == give)
                out[j] = id[i * nv + j];
        }
    for (int i = 0; i + 1 < nu; i++)
        for (int j = 0; j + 1 < nv; j++) {
            uint32_t a = id[i * nv + j], b = id[(i + 1) * nv + j], c = id[(i + 1) * nv + j + 1],
                     d = id[i * nv + j + 1];
            add_f(o, f, a, b, c);
            add_f(o, f, a, c, d);
        }
    free(id);
}

static void write_obj(const obj *o, const char *path)
{
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (!fp)
        return;
    fprintf(fp, "# test fault set\n");
    for (size_t i = 0; i < o->nv; i++)
        fprintf(fp, "v %.17g %.17g %.17g\n", o->v[i][0], o->v[i][1], o->v[i][2]);
    for (int f = 0; f < o->nfaults; f++) {
        fprintf(fp, "o %s\ng %s\n", o->fault[f].name, o->fault[f].name);
        for (size_t t = 0; t < o->fault[f].nf; t++)
            fprintf(fp, "f %u %u %u\n", o->fault[f].f[3 * t] + 1, o->fault[f].f[3 * t + 1] + 1,
                    o->fault[f].f[3 * t + 2] + 1);
    }
    fclose(fp);
}

static void free_obj(obj *o)
{
    free(o->v);
    for (int f = 0; f < o->nfaults; f++)
        free(o->fault[f].f);
    memset(o, 0, sizeof *o);
}

/* Fault "A": the plane x = 0, y in [-1800, 1800], z in [-1800, 0], 600 m
 * cells; its column y = 0 (i = 3) goes to col. */
static void fault_a(obj *o, uint32_t col[4])
{
    int f = add_fault(o, "A");
    grid(o, f, (double[]){0, -1800, -1800}, (double[]){0, 600, 0}, (double[]){0, 0, 600}, 7, 4, -1,
         NULL, 3, col);
}

static const char *path_of(const char *name)
{
    static char buf[512];
    mkdir(FM_TMP_DIR, 0777);
    mkdir(TMP, 0777);
    snprintf(buf, sizeof buf, "%s/%s.obj", TMP, name);
    return buf;
}

/* Writes o to NAME.obj, reads it back and analyses it. */
static int analyse(const obj *o, const char *name, double distance, cc_mesh *m, cc_result *r)
{
    const char *path = path_of(name);
    write_obj(o, path);
    char err[512];
    if (cc_obj_read(path, m, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        CHECK(0);
        return -1;
    }
    cc_options opt = {distance, 1};
    if (cc_analyse(m, &opt, r)) {
        CHECK(0);
        cc_mesh_free(m);
        return -1;
    }
    return 0;
}

static const cc_pair *find_pair(const cc_result *r)
{
    for (size_t i = 0; i < r->npairs; i++)
        if (r->pairs[i].a == 0 && r->pairs[i].b == 1)
            return &r->pairs[i];
    return NULL;
}

static uint64_t self_total(const cc_mesh *m, const cc_result *r)
{
    uint64_t n = 0;
    for (size_t f = 0; f < m->nfaults; f++)
        n += r->self[f].intersections;
    return n;
}

static void test_set_crossing(void)
{
    obj o = {0};
    fault_a(&o, NULL);
    /* "B": the plane y = 250, crossing A, with no vertex in common. */
    int b = add_fault(&o, "B");
    grid(&o, b, (double[]){-1500, 250, -1800}, (double[]){600, 0, 0}, (double[]){0, 0, 600}, 6, 4,
         -1, NULL, -1, NULL);
    cc_mesh m;
    cc_result r;
    if (analyse(&o, "crossing", 1000, &m, &r) == 0) {
        const cc_pair *p = find_pair(&r);
        CHECK(p != NULL);
        if (p) {
            /* The line x = 0, y = 250 runs through 3 cells of each fault,
             * each crossing pair of triangles along it. */
            CHECK(p->intersections >= 6);
            CHECK_EQ(p->shared_vertices, 0);
            CHECK_EQ(p->distance, 0);
            CHECK(p->nexamples == CC_EXAMPLES);
            CHECK(m.fault[p->examples[0][0]] == 0 && m.fault[p->examples[0][1]] == 1);
        }
        CHECK_EQ(self_total(&m, &r), 0);
        CHECK_EQ(r.degenerate_triangles, 0);
        cc_result_free(&r);
        cc_mesh_free(&m);
    }
    free_obj(&o);
}

/* B meets A on the line x = y = 0 through A's vertices there: a T (B on
 * one side) or an X (B on both sides). */
static void build_junction(obj *o, int x_junction, int shared)
{
    uint32_t col[4];
    fault_a(o, col);
    int b = add_fault(o, "B");
    if (x_junction)
        grid(o, b, (double[]){-1800, 0, -1800}, (double[]){600, 0, 0}, (double[]){0, 0, 600}, 7, 4,
             3, shared ? col : NULL, -1, NULL);
    else
        grid(o, b, (double[]){0, 0, -1800}, (double[]){600, 0, 0}, (double[]){0, 0, 600}, 4, 4, 0,
             shared ? col : NULL, -1, NULL);
}

static void test_set_conforming(void)
{
    for (int x_junction = 0; x_junction < 2; x_junction++) {
        obj o = {0};
        build_junction(&o, x_junction, 1);
        cc_mesh m;
        cc_result r;
        if (analyse(&o, x_junction ? "conforming_x" : "conforming_t", 1000, &m, &r) == 0) {
            const cc_pair *p = find_pair(&r);
            CHECK(p != NULL);
            if (p) {
                CHECK_EQ(p->intersections, 0);
                CHECK_EQ(p->shared_vertices, 4);
                CHECK_EQ(p->shared_edges, 3);
                CHECK_EQ(p->distance, 0);
                /* Unjoined boundary edges within 1000 m: A's top and bottom
                 * edges y in +-[600, 1200] (600 m from B; those touching
                 * the junction have a vertex of B); B's top and bottom
                 * edges x in +-[600, 1200]. */
                CHECK_EQ(p->near_edges[0], 4);
                CHECK_EQ(p->near_edges[1], x_junction ? 4 : 2);
                CHECK_NEAR(p->near_min, 600, 1e-6);
                CHECK_NEAR(p->near_length[0] + p->near_length[1], 600.0 * (x_junction ? 8 : 6),
                           1e-6);
            }
            CHECK_EQ(self_total(&m, &r), 0);
            CHECK_EQ(r.npairs, 1);
            CHECK_EQ(r.nonmanifold_edges, 0);
            /* A's outline: 2 * (6 + 3) edges; B's: 2 * (3 or 6 + 3). */
            CHECK_EQ(r.boundary_edges, 18 + (x_junction ? 18 : 12));
            cc_result_free(&r);
            cc_mesh_free(&m);
        }
        free_obj(&o);
        /* The same junction with B's own copies of the line's vertices:
         * coincident coordinates are not shared, every contact counts. */
        build_junction(&o, x_junction, 0);
        if (analyse(&o, x_junction ? "unshared_x" : "unshared_t", 1000, &m, &r) == 0) {
            const cc_pair *p = find_pair(&r);
            CHECK(p != NULL);
            if (p) {
                CHECK(p->intersections >= 6);
                CHECK_EQ(p->shared_vertices, 0);
                CHECK_EQ(p->shared_edges, 0);
            }
            cc_result_free(&r);
            cc_mesh_free(&m);
        }
        free_obj(&o);
    }
}

/* One triangle of B touches A at the corner (0, 0, 0) of A only. */
static void test_set_coincident_vertex(void)
{
    for (int shared = 0; shared < 2; shared++) {
        obj o = {0};
        uint32_t col[4];
        fault_a(&o, col);
        int b = add_fault(&o, "B");
        uint32_t v0 = shared ? col[3] : add_v(&o, 0, 0, 0);
        add_f(&o, b, v0, add_v(&o, 500, 300, -100), add_v(&o, 500, -300, -100));
        cc_mesh m;
        cc_result r;
        if (analyse(&o, shared ? "vertex_shared" : "vertex_unshared", 1000, &m, &r) == 0) {
            const cc_pair *p = find_pair(&r);
            CHECK(p != NULL);
            if (p) {
                /* A's triangles around its top vertex y = 0: three. */
                CHECK_EQ(p->intersections, shared ? 0 : 3);
                CHECK_EQ(p->shared_vertices, shared ? 1 : 0);
                CHECK_EQ(p->distance, 0);
            }
            cc_result_free(&r);
            cc_mesh_free(&m);
        }
        free_obj(&o);
    }
}

/* B as in the T junction but starting 300 m from A. */
static void build_gap(obj *o)
{
    fault_a(o, NULL);
    int b = add_fault(o, "B");
    grid(o, b, (double[]){300, 0, -1800}, (double[]){600, 0, 0}, (double[]){0, 0, 600}, 4, 4, -1,
         NULL, -1, NULL);
}

static void test_set_gap(void)
{
    obj o = {0};
    build_gap(&o);
    for (int near = 1; near >= 0; near--) {
        cc_mesh m;
        cc_result r;
        if (analyse(&o, "gap", near ? 1000 : 100, &m, &r) == 0) {
            const cc_pair *p = find_pair(&r);
            CHECK_EQ(p != NULL, near);
            if (p) {
                CHECK_EQ(p->intersections, 0);
                CHECK_EQ(p->shared_vertices, 0);
                CHECK_NEAR(p->distance, 300, 1e-6);
                /* B's edges at x = 300 (3) and its top and bottom edges
                 * x in [300, 900] and [900, 1500] (300 and 900 m); A's top
                 * and bottom edges y in +-[0, 600] (300 m) and +-[600, 1200]
                 * (sqrt(300^2 + 600^2) = 671 m). */
                CHECK_EQ(p->near_edges[1], 7);
                CHECK_EQ(p->near_edges[0], 8);
                CHECK_NEAR(p->near_min, 300, 1e-6);
            }
            cc_result_free(&r);
            cc_mesh_free(&m);
        }
    }
    free_obj(&o);
}

static void test_set_coplanar(void)
{
    /* B in A's plane, overlapping a corner of it. */
    obj o = {0};
    fault_a(&o, NULL);
    int b = add_fault(&o, "B");
    grid(&o, b, (double[]){0, 1000, -2500}, (double[]){0, 600, 0}, (double[]){0, 0, 600}, 4, 3, -1,
         NULL, -1, NULL);
    cc_mesh m;
    cc_result r;
    if (analyse(&o, "coplanar_overlap", 1000, &m, &r) == 0) {
        const cc_pair *p = find_pair(&r);
        CHECK(p != NULL && p->intersections > 0);
        cc_result_free(&r);
        cc_mesh_free(&m);
    }
    free_obj(&o);
    /* B continues A in its plane beyond A's last column, sharing it (a
     * seam): no overlap. Folded back onto A over that column: overlap. */
    for (int fold = 0; fold < 2; fold++) {
        obj s = {0};
        uint32_t col[4];
        int a = add_fault(&s, "A");
        grid(&s, a, (double[]){0, -1800, -1800}, (double[]){0, 600, 0}, (double[]){0, 0, 600}, 7, 4,
             -1, NULL, 6, col);
        b = add_fault(&s, "B");
        grid(&s, b, (double[]){0, 1800, -1800}, (double[]){0, fold ? -500 : 600, 0},
             (double[]){0, 0, 600}, 3, 4, 0, col, -1, NULL);
        if (analyse(&s, fold ? "coplanar_fold" : "coplanar_seam", 1000, &m, &r) == 0) {
            const cc_pair *p = find_pair(&r);
            CHECK(p != NULL);
            if (p) {
                CHECK_EQ(p->shared_vertices, 4);
                CHECK_EQ(p->shared_edges, 3);
                if (fold)
                    CHECK(p->intersections > 0);
                else
                    CHECK_EQ(p->intersections, 0);
            }
            cc_result_free(&r);
            cc_mesh_free(&m);
        }
        free_obj(&s);
    }
}

static void test_set_self(void)
{
    /* One fault made of A and, under the same name, the crossing B. */
    obj o = {0};
    fault_a(&o, NULL);
    grid(&o, 0, (double[]){-1500, 250, -1800}, (double[]){600, 0, 0}, (double[]){0, 0, 600}, 6, 4,
         -1, NULL, -1, NULL);
    cc_mesh m;
    cc_result r;
    if (analyse(&o, "self", 1000, &m, &r) == 0) {
        CHECK_EQ(m.nfaults, 1);
        CHECK_EQ(r.npairs, 0);
        CHECK(self_total(&m, &r) >= 6);
        cc_result_free(&r);
        cc_mesh_free(&m);
    }
    free_obj(&o);
    /* A alone: neighbours sharing vertices and edges are no violation. */
    fault_a(&o, NULL);
    if (analyse(&o, "single", 1000, &m, &r) == 0) {
        CHECK_EQ(self_total(&m, &r), 0);
        cc_result_free(&r);
        cc_mesh_free(&m);
    }
    free_obj(&o);
}

/* ---- the program */

static int run(const char *args, const char *name)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "'%s' %s >'%s/%s.out' 2>'%s/%s.err'", CC_BINARY, args, TMP, name, TMP,
             name);
    int st = system(cmd);
    return st < 0 || !WIFEXITED(st) ? -1 : WEXITSTATUS(st);
}

static char *slurp(const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", TMP, name);
    char *s = fm_test_read_file(path, NULL);
    CHECK(s != NULL);
    return s ? s : calloc(1, 1);
}

static void write_text(const char *name, const char *text)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", TMP, name);
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (fp) {
        fputs(text, fp);
        fclose(fp);
    }
}

static void test_program(void)
{
    obj o = {0};
    fault_a(&o, NULL);
    int b = add_fault(&o, "B");
    grid(&o, b, (double[]){-1500, 250, -1800}, (double[]){600, 0, 0}, (double[]){0, 0, 600}, 6, 4,
         -1, NULL, -1, NULL);
    write_obj(&o, path_of("crossing"));
    free_obj(&o);
    build_junction(&o, 1, 1);
    write_obj(&o, path_of("conforming_x"));
    free_obj(&o);
    build_gap(&o);
    write_obj(&o, path_of("gap"));
    free_obj(&o);
    char args[1024];

    snprintf(args, sizeof args, "--criteria --json '%s/crossing.json' '%s/crossing.obj'", TMP, TMP);
    CHECK_EQ(run(args, "crossing"), 1);
    char *out = slurp("crossing.out"), *json = slurp("crossing.json");
    CHECK(strstr(out, "criteria: FAILED: 1 fault pairs intersect") != NULL);
    CHECK(strstr(out, "A x B:") != NULL);
    CHECK(strstr(out, "a triangle") != NULL); /* an example with coordinates */
    CHECK(strstr(json, "\"intersections\": {\"triangle_pairs\": ") != NULL);
    CHECK(strstr(json, "\"fault_pairs\": 1, \"allowed_triangle_pairs\": 0") != NULL);
    CHECK(strstr(json, "{\"a\": \"A\", \"b\": \"B\", \"triangle_pairs\": ") != NULL);
    free(out);
    free(json);

    /* Without --criteria a violation is only reported. */
    snprintf(args, sizeof args, "'%s/crossing.obj'", TMP);
    CHECK_EQ(run(args, "crossing_plain"), 0);
    /* A documented pair is exempt, in either order. */
    write_text("allow.txt", "# documented\nB\tA\n");
    snprintf(args, sizeof args, "--criteria --allow-pairs '%s/allow.txt' '%s/crossing.obj'", TMP,
             TMP);
    CHECK_EQ(run(args, "crossing_allowed"), 0);
    write_text("allow_bad.txt", "A B\n");
    snprintf(args, sizeof args, "--criteria --allow-pairs '%s/allow_bad.txt' '%s/crossing.obj'",
             TMP, TMP);
    CHECK_EQ(run(args, "allow_bad"), 2);
    out = slurp("allow_bad.err");
    CHECK(strstr(out, "allow_bad.txt:1: ") != NULL);
    free(out);

    snprintf(args, sizeof args, "--criteria --json '%s/conforming.json' '%s/conforming_x.obj'", TMP,
             TMP);
    CHECK_EQ(run(args, "conforming"), 0);
    json = slurp("conforming.json");
    CHECK(strstr(json, "\"intersections\": {\"triangle_pairs\": 0, \"fault_pairs\": 0") != NULL);
    CHECK(strstr(json, "\"sharing\": {\"fault_pairs\": 1, \"vertices\": 4, \"edges\": 3}") != NULL);
    CHECK(
        strstr(json,
               "{\"a\": \"A\", \"b\": \"B\", \"shared_vertices\": 4, \"shared_edges\": 3, "
               "\"intersections\": 0, \"distance\": 0, \"near_edges_a\": 4, \"near_edges_b\": 4") !=
        NULL);
    CHECK(strstr(json, "\"near_pairs_not_sharing\": []") != NULL);
    free(json);

    snprintf(args, sizeof args, "--criteria --json '%s/gap.json' '%s/gap.obj'", TMP, TMP);
    CHECK_EQ(run(args, "gap"), 0);
    json = slurp("gap.json");
    const char *key =
        "\"near_pairs_not_sharing\": [\n    {\"a\": \"A\", \"b\": \"B\", \"distance\": ";
    const char *at = strstr(json, key);
    CHECK(at != NULL);
    if (at)
        CHECK_NEAR(strtod(at + strlen(key), NULL), 300, 1e-6);
    free(json);
    snprintf(args, sizeof args, "--distance 100 --json '%s/gap100.json' '%s/gap.obj'", TMP, TMP);
    CHECK_EQ(run(args, "gap100"), 0);
    json = slurp("gap100.json");
    CHECK(strstr(json, "\"near_pairs_not_sharing\": []") != NULL);
    CHECK(strstr(json, "\"pairs\": []") != NULL);
    free(json);

    /* Unreadable input: exit 2 with FILE:LINE. */
    write_text("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\no X\nf 1 2 3\nf 1 2 9\n");
    snprintf(args, sizeof args, "'%s/bad.obj'", TMP);
    CHECK_EQ(run(args, "bad"), 2);
    out = slurp("bad.err");
    CHECK(strstr(out, "bad.obj:6: vertex index 9 not defined") != NULL);
    free(out);
    write_text("quad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n");
    snprintf(args, sizeof args, "'%s/quad.obj'", TMP);
    CHECK_EQ(run(args, "quad"), 2);
    out = slurp("quad.err");
    CHECK(strstr(out, "quad.obj:5: face with 4 corners") != NULL);
    free(out);
    write_text("nan.obj", "v 0 0 0\nv nan 0 0\n");
    snprintf(args, sizeof args, "'%s/nan.obj'", TMP);
    CHECK_EQ(run(args, "nan"), 2);
    out = slurp("nan.err");
    CHECK(strstr(out, "nan.obj:2: coordinate is not finite") != NULL);
    free(out);
    snprintf(args, sizeof args, "'%s/missing.obj'", TMP);
    CHECK_EQ(run(args, "missing"), 2);
    out = slurp("missing.err");
    CHECK(strstr(out, "missing.obj: cannot open") != NULL);
    free(out);
    CHECK_EQ(run("--distance -1 x.obj", "usage"), 2);
}

FM_TEST_MAIN(FM_CASE(test_contact_basic), FM_CASE(test_contact_shared_vertex),
             FM_CASE(test_contact_shared_edge), FM_CASE(test_contact_degenerate),
             FM_CASE(test_contact_exact), FM_CASE(test_contact_symmetry),
             FM_CASE(test_contact_random), FM_CASE(test_distances), FM_CASE(test_grid),
             FM_CASE(test_set_crossing), FM_CASE(test_set_conforming),
             FM_CASE(test_set_coincident_vertex), FM_CASE(test_set_gap), FM_CASE(test_set_coplanar),
             FM_CASE(test_set_self), FM_CASE(test_program))
