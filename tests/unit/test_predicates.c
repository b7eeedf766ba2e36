/* Exact geometric predicates (fm_predicates.h) against independent exact
 * references: __int128 arithmetic on integer coordinates, and a small
 * arbitrary-precision integer type for arbitrary doubles (every finite double
 * is an integer times a power of two, so after a common scaling the
 * determinants are integer polynomials). */
#include "fm_test.h"

#include "fm_predicates.h"

#include <stdint.h>

/* ---- deterministic PRNG ------------------------------------------------- */

static uint64_t rng_state;

static void rng_seed(uint64_t s) { rng_state = s; }

static uint64_t splitmix64(void)
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1). */
static double rnd_unit(void) { return (double)(splitmix64() >> 11) * 0x1p-53; }

/* Uniform in [-m, m]. */
static long long rnd_int(long long m)
{
    return (long long)(splitmix64() % (uint64_t)(2 * m + 1)) - m;
}

/* A double with a full random mantissa, of random sign and of one of a few
 * magnitudes, from tiny to UTM northings. */
static double rnd_mixed(void)
{
    static const double scale[] = {1e-3, 0.7, 37.0, 5e5, 4e6};
    double v = scale[splitmix64() % 5] * (1.0 + rnd_unit());
    return (splitmix64() & 1) ? -v : v;
}

/* x moved by k ulps. */
static double ulps(double x, int k)
{
    while (k > 0) {
        x = nextafter(x, INFINITY);
        k--;
    }
    while (k < 0) {
        x = nextafter(x, -INFINITY);
        k++;
    }
    return x;
}

/* ---- arbitrary-precision signed integers -------------------------------- */

#define BIG_LIMBS 48 /* 1536 bits */

typedef struct big {
    int neg, n; /* n = limbs in use, no leading zero limbs; zero has n = 0 */
    uint32_t w[BIG_LIMBS];
} big;

static int big_overflow;

static void big_norm(big *a)
{
    while (a->n > 0 && a->w[a->n - 1] == 0)
        a->n--;
    if (a->n == 0)
        a->neg = 0;
}

static int mag_cmp(const big *a, const big *b)
{
    if (a->n != b->n)
        return a->n < b->n ? -1 : 1;
    for (int i = a->n - 1; i >= 0; i--)
        if (a->w[i] != b->w[i])
            return a->w[i] < b->w[i] ? -1 : 1;
    return 0;
}

static big big_add(big a, big b)
{
    big r;
    memset(&r, 0, sizeof r);
    if (a.neg == b.neg) {
        int n = a.n > b.n ? a.n : b.n;
        uint64_t carry = 0;
        for (int i = 0; i < n; i++) {
            uint64_t s = carry + (i < a.n ? a.w[i] : 0) + (i < b.n ? b.w[i] : 0);
            r.w[i] = (uint32_t)s;
            carry = s >> 32;
        }
        if (carry) {
            if (n >= BIG_LIMBS) {
                big_overflow = 1;
                return r;
            }
            r.w[n++] = (uint32_t)carry;
        }
        r.n = n;
        r.neg = a.neg;
    } else {
        if (mag_cmp(&a, &b) < 0) {
            big t = a;
            a = b;
            b = t;
        }
        int64_t borrow = 0;
        for (int i = 0; i < a.n; i++) {
            int64_t d = (int64_t)a.w[i] - (i < b.n ? b.w[i] : 0) - borrow;
            borrow = d < 0;
            r.w[i] = (uint32_t)(d + (borrow ? ((int64_t)1 << 32) : 0));
        }
        r.n = a.n;
        r.neg = a.neg;
    }
    big_norm(&r);
    return r;
}

static big big_sub(big a, big b)
{
    if (b.n)
        b.neg = !b.neg;
    return big_add(a, b);
}

static big big_mul(big a, big b)
{
    big r;
    memset(&r, 0, sizeof r);
    if (a.n == 0 || b.n == 0)
        return r;
    if (a.n + b.n > BIG_LIMBS) {
        big_overflow = 1;
        return r;
    }
    for (int i = 0; i < a.n; i++) {
        uint64_t carry = 0;
        for (int j = 0; j < b.n; j++) {
            uint64_t t = (uint64_t)a.w[i] * b.w[j] + r.w[i + j] + carry;
            r.w[i + j] = (uint32_t)t;
            carry = t >> 32;
        }
        r.w[i + b.n] = (uint32_t)carry;
    }
    r.n = a.n + b.n;
    r.neg = a.neg != b.neg;
    big_norm(&r);
    return r;
}

static int big_sign(const big *a) { return a->n == 0 ? 0 : (a->neg ? -1 : 1); }

/* x * 2^s, which must be an integer. */
static big big_from_double(double x, int s)
{
    big r;
    memset(&r, 0, sizeof r);
    if (x == 0.0)
        return r;
    int e;
    double m = frexp(fabs(x), &e);
    uint64_t mant = (uint64_t)ldexp(m, 53);
    int sh = e - 53 + s;
    if (sh < 0 || sh / 32 + 3 > BIG_LIMBS) {
        big_overflow = 1;
        return r;
    }
    int limb = sh / 32, off = sh % 32;
    unsigned __int128 v = (unsigned __int128)mant << off;
    for (int i = 0; i < 3; i++)
        r.w[limb + i] = (uint32_t)(v >> (32 * i));
    r.n = limb + 3;
    r.neg = x < 0.0;
    big_norm(&r);
    return r;
}

/* The common scale making all n coordinates integers. */
static int common_scale(const double *const *p, int npts, int dim)
{
    int s = 0;
    for (int i = 0; i < npts; i++)
        for (int k = 0; k < dim; k++)
            if (p[i][k] != 0.0) {
                int e;
                frexp(p[i][k], &e);
                if (53 - e > s)
                    s = 53 - e;
            }
    return s;
}

static int ref_orient2d(const double *a, const double *b, const double *c)
{
    const double *p[3] = {a, b, c};
    int s = common_scale(p, 3, 2);
    big acx = big_sub(big_from_double(a[0], s), big_from_double(c[0], s));
    big acy = big_sub(big_from_double(a[1], s), big_from_double(c[1], s));
    big bcx = big_sub(big_from_double(b[0], s), big_from_double(c[0], s));
    big bcy = big_sub(big_from_double(b[1], s), big_from_double(c[1], s));
    big det = big_sub(big_mul(acx, bcy), big_mul(acy, bcx));
    return big_sign(&det);
}

/* Shewchuk's orient3d determinant det[a-d; b-d; c-d] (see the header). */
static int ref_orient3d(const double *a, const double *b, const double *c, const double *d)
{
    const double *p[4] = {a, b, c, d};
    int s = common_scale(p, 4, 3);
    big v[3][3];
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            v[i][k] = big_sub(big_from_double(p[i][k], s), big_from_double(d[k], s));
    big det = {0, 0, {0}};
    for (int i = 0; i < 3; i++) {
        const big *r0 = v[i], *r1 = v[(i + 1) % 3], *r2 = v[(i + 2) % 3];
        big m = big_sub(big_mul(r1[0], r2[1]), big_mul(r2[0], r1[1]));
        det = big_add(det, big_mul(r0[2], m));
    }
    return big_sign(&det);
}

static int ref_incircle(const double *a, const double *b, const double *c, const double *d)
{
    const double *p[4] = {a, b, c, d};
    int s = common_scale(p, 4, 2);
    big v[3][3];
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 2; k++)
            v[i][k] = big_sub(big_from_double(p[i][k], s), big_from_double(d[k], s));
        v[i][2] = big_add(big_mul(v[i][0], v[i][0]), big_mul(v[i][1], v[i][1]));
    }
    big det = {0, 0, {0}};
    for (int i = 0; i < 3; i++) {
        const big *r0 = v[i], *r1 = v[(i + 1) % 3], *r2 = v[(i + 2) % 3];
        big m = big_sub(big_mul(r1[0], r2[1]), big_mul(r2[0], r1[1]));
        det = big_add(det, big_mul(r0[2], m));
    }
    return big_sign(&det);
}

/* ---- __int128 references on integer coordinates ------------------------- */

typedef __int128 i128;

static int sgn128(i128 v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

static int i128_orient2d(const double *a, const double *b, const double *c)
{
    i128 acx = (long long)a[0] - (long long)c[0], acy = (long long)a[1] - (long long)c[1];
    i128 bcx = (long long)b[0] - (long long)c[0], bcy = (long long)b[1] - (long long)c[1];
    return sgn128(acx * bcy - acy * bcx);
}

static int i128_orient3d(const double *a, const double *b, const double *c, const double *d)
{
    const double *p[3] = {a, b, c};
    i128 v[3][3];
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            v[i][k] = (i128)(long long)p[i][k] - (long long)d[k];
    i128 det = v[0][2] * (v[1][0] * v[2][1] - v[2][0] * v[1][1]) +
               v[1][2] * (v[2][0] * v[0][1] - v[0][0] * v[2][1]) +
               v[2][2] * (v[0][0] * v[1][1] - v[1][0] * v[0][1]);
    return sgn128(det);
}

static int i128_incircle(const double *a, const double *b, const double *c, const double *d)
{
    const double *p[3] = {a, b, c};
    i128 v[3][3];
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 2; k++)
            v[i][k] = (i128)(long long)p[i][k] - (long long)d[k];
        v[i][2] = v[i][0] * v[i][0] + v[i][1] * v[i][1];
    }
    i128 det = v[0][2] * (v[1][0] * v[2][1] - v[2][0] * v[1][1]) +
               v[1][2] * (v[2][0] * v[0][1] - v[0][0] * v[2][1]) +
               v[2][2] * (v[0][0] * v[1][1] - v[1][0] * v[0][1]);
    return sgn128(det);
}

/* ---- naive double formulas (to show the tests reach the hard cases) ----- */

static int sgnd(double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

static int naive_orient2d(const double *a, const double *b, const double *c)
{
    return sgnd((a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]));
}

static int naive_orient3d(const double *a, const double *b, const double *c, const double *d)
{
    double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
    double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
    double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];
    return sgnd(adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) +
                cdz * (adx * bdy - bdx * ady));
}

static int naive_incircle(const double *a, const double *b, const double *c, const double *d)
{
    double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
    double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
    double al = adx * adx + ady * ady, bl = bdx * bdx + bdy * bdy, cl = cdx * cdx + cdy * cdy;
    return sgnd(al * (bdx * cdy - cdx * bdy) + bl * (cdx * ady - adx * cdy) +
                cl * (adx * bdy - bdx * ady));
}

/* 1 if some coordinate difference p[i] - p[last] is not exactly representable
 * (the predicates then cannot use the differences). */
static int inexact_differences(const double *const *p, int npts, int dim)
{
    for (int i = 0; i + 1 < npts; i++)
        for (int k = 0; k < dim; k++) {
            double x = p[i][k], y = p[npts - 1][k], s = x - y;
            double bv = x - s, av = s + bv;
            if ((x - av) + (bv - y) != 0.0)
                return 1;
        }
    return 0;
}

/* Per-shape statistics of a random campaign. */
typedef struct stats {
    int cases, zero, naive_wrong, inexact_hard;
} stats;

static void tally(stats *st, int truth, int naive, int inexact)
{
    st->cases++;
    st->zero += truth == 0;
    st->naive_wrong += naive != truth;
    st->inexact_hard += inexact && (truth == 0 || naive != truth);
}

/* ---- permutations ------------------------------------------------------- */

static const int perm4[24][4] = {
    {0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 1, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {0, 3, 2, 1},
    {1, 0, 2, 3}, {1, 0, 3, 2}, {1, 2, 0, 3}, {1, 2, 3, 0}, {1, 3, 0, 2}, {1, 3, 2, 0},
    {2, 0, 1, 3}, {2, 0, 3, 1}, {2, 1, 0, 3}, {2, 1, 3, 0}, {2, 3, 0, 1}, {2, 3, 1, 0},
    {3, 0, 1, 2}, {3, 0, 2, 1}, {3, 1, 0, 2}, {3, 1, 2, 0}, {3, 2, 0, 1}, {3, 2, 1, 0}};

static int parity4(const int *p)
{
    int inv = 0;
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++)
            inv += p[i] > p[j];
    return inv % 2 ? -1 : 1;
}

/* Checks every permutation of the points against sign * parity; returns
 * the number of mismatches. */
static int perm_mismatches_orient2d(double p[3][2], int sign)
{
    int bad = 0;
    for (int i = 0; i < 24; i++) {
        const int *q = perm4[i];
        if (q[3] != 3)
            continue; /* the 6 permutations of the first three */
        bad += fm_orient2d(p[q[0]], p[q[1]], p[q[2]]) != sign * parity4(q);
    }
    return bad;
}

static int perm_mismatches_orient3d(double p[4][3], int sign)
{
    int bad = 0;
    for (int i = 0; i < 24; i++) {
        const int *q = perm4[i];
        bad += fm_orient3d(p[q[0]], p[q[1]], p[q[2]], p[q[3]]) != sign * parity4(q);
    }
    return bad;
}

static int perm_mismatches_incircle(double p[4][2], int sign)
{
    int bad = 0;
    for (int i = 0; i < 24; i++) {
        const int *q = perm4[i];
        bad += fm_incircle(p[q[0]], p[q[1]], p[q[2]], p[q[3]]) != sign * parity4(q);
    }
    return bad;
}

/* ======================================================================== */

static void test_sign_conventions(void)
{
    double o[2] = {0, 0}, x[2] = {1, 0}, y[2] = {0, 1};
    CHECK_EQ(fm_orient2d(o, x, y), 1);
    CHECK_EQ(fm_orient2d(o, y, x), -1);
    double m[2] = {0.5, 0.5};
    CHECK_EQ(fm_orient2d(x, y, m), 0);

    /* a, b, c counter-clockwise seen from +z: normal (b-a)x(c-a) = +z. */
    double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    double below[3] = {0.2, 0.3, -1}, above[3] = {5, -7, 2}, on[3] = {3, -8, 0};
    CHECK_EQ(fm_orient3d(a, b, c, below), 1);
    CHECK_EQ(fm_orient3d(a, b, c, above), -1);
    CHECK_EQ(fm_orient3d(a, b, c, on), 0);
    CHECK_EQ(fm_orient3d(a, c, b, below), -1);

    /* Circle through (0,0), (1,0), (0,1) (counter-clockwise). */
    double in[2] = {0.25, 0.25}, out[2] = {2, 2}, onc[2] = {1, 1};
    CHECK_EQ(fm_incircle(o, x, y, in), 1);
    CHECK_EQ(fm_incircle(o, x, y, out), -1);
    CHECK_EQ(fm_incircle(o, x, y, onc), 0);
    CHECK_EQ(fm_incircle(o, y, x, in), -1);

    double p0[3] = {1, 2, 3}, p1[3] = {3, 6, 9}, p2[3] = {-1, -2, -3}, p3[3] = {-1, -2, -2.5};
    CHECK_EQ(fm_collinear3d(p0, p1, p2), 1);
    CHECK_EQ(fm_collinear3d(p0, p1, p3), 0);
    CHECK_EQ(fm_collinear3d(p0, p0, p3), 1);
}

/* The bignum reference agrees with __int128 (so it can be trusted where
 * __int128 is not enough). */
static void test_reference_selfcheck(void)
{
    rng_seed(1);
    int bad = 0, nonzero = 0;
    for (int it = 0; it < 3000; it++) {
        double p[4][3];
        long long m = (it % 3 == 0) ? 8 : (1ll << 20);
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                p[i][k] = (double)rnd_int(m);
        int r2 = i128_orient2d(p[0], p[1], p[2]);
        int r3 = i128_orient3d(p[0], p[1], p[2], p[3]);
        int ri = i128_incircle(p[0], p[1], p[2], p[3]);
        bad += ref_orient2d(p[0], p[1], p[2]) != r2;
        bad += ref_orient3d(p[0], p[1], p[2], p[3]) != r3;
        bad += ref_incircle(p[0], p[1], p[2], p[3]) != ri;
        nonzero += r2 != 0 && r3 != 0 && ri != 0;
    }
    CHECK_EQ(bad, 0);
    CHECK(nonzero > 1000);
    CHECK_EQ(big_overflow, 0);
}

static void test_orient2d_integer(void)
{
    rng_seed(2);
    stats st = {0, 0, 0, 0};
    int bad = 0;
    for (int it = 0; it < 200000; it++) {
        double p[3][2];
        long long m = (it % 4 == 0) ? 16 : (1ll << 52);
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 2; k++)
                p[i][k] = (double)rnd_int(m);
        if (it % 2 == 1) { /* exactly collinear: c = a + t (b - a)/g */
            long long dx = rnd_int(1ll << 20), dy = rnd_int(1ll << 20);
            long long t1 = rnd_int(1ll << 30), t2 = rnd_int(1ll << 30);
            p[1][0] = p[0][0] + (double)(t1 * dx);
            p[1][1] = p[0][1] + (double)(t1 * dy);
            p[2][0] = p[0][0] + (double)(t2 * dx);
            p[2][1] = p[0][1] + (double)(t2 * dy);
            if (it % 6 == 1) /* off the line by one unit */
                p[2][splitmix64() & 1] += (splitmix64() & 1) ? 1.0 : -1.0;
            if (fabs(p[1][0]) >= 0x1p53 || fabs(p[1][1]) >= 0x1p53 ||
                fabs(p[2][0]) >= 0x1p53 || fabs(p[2][1]) >= 0x1p53)
                continue;
        }
        int truth = i128_orient2d(p[0], p[1], p[2]);
        tally(&st, truth, naive_orient2d(p[0], p[1], p[2]), 0);
        bad += fm_orient2d(p[0], p[1], p[2]) != truth;
        if (it % 16 == 0)
            bad += perm_mismatches_orient2d(p, truth);
    }
    CHECK_EQ(bad, 0);
    CHECK(st.zero > 20000);
    CHECK(st.naive_wrong > 200);
}

static void test_orient3d_integer(void)
{
    rng_seed(3);
    stats st = {0, 0, 0, 0};
    int bad = 0;
    for (int it = 0; it < 100000; it++) {
        double p[4][3];
        long long m = (it % 4 == 0) ? 8 : (1ll << 38);
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                p[i][k] = (double)rnd_int(m);
        if (it % 2 == 1) { /* exactly coplanar: d = a + s (b-a) + t (c-a) */
            long long s = rnd_int(3), t = rnd_int(3);
            for (int k = 0; k < 3; k++) {
                p[1][k] = p[0][k] + (double)rnd_int(1ll << 35);
                p[2][k] = p[0][k] + (double)rnd_int(1ll << 35);
                p[3][k] = p[0][k] + (double)(s * (long long)(p[1][k] - p[0][k]) +
                                             t * (long long)(p[2][k] - p[0][k]));
            }
            if (it % 6 == 1)
                p[3][splitmix64() % 3] += (splitmix64() & 1) ? 1.0 : -1.0;
        }
        int truth = i128_orient3d(p[0], p[1], p[2], p[3]);
        tally(&st, truth, naive_orient3d(p[0], p[1], p[2], p[3]), 0);
        bad += fm_orient3d(p[0], p[1], p[2], p[3]) != truth;
        if (it % 16 == 0)
            bad += perm_mismatches_orient3d(p, truth);
    }
    CHECK_EQ(bad, 0);
    CHECK(st.zero > 10000);
    CHECK(st.naive_wrong > 1000);
}

/* Lattice points on the circle of radius 5525 = 5^2 * 13 * 17 (many). */
static int circle_points(long long r, long long (*pts)[2], int max)
{
    int n = 0;
    for (long long x = -r; x <= r; x++) {
        long long y2 = r * r - x * x;
        long long y = (long long)sqrt((double)y2);
        while (y * y > y2)
            y--;
        while ((y + 1) * (y + 1) <= y2)
            y++;
        if (y * y == y2) {
            if (n < max)
                pts[n++][0] = x, pts[n - 1][1] = y;
            if (y != 0 && n < max)
                pts[n++][0] = x, pts[n - 1][1] = -y;
        }
    }
    return n;
}

static void test_incircle_integer(void)
{
    rng_seed(4);
    long long cp[512][2];
    int ncp = circle_points(5525, cp, 512);
    CHECK(ncp > 100);
    stats st = {0, 0, 0, 0};
    int bad = 0;
    for (int it = 0; it < 100000; it++) {
        double p[4][2];
        long long m = (it % 4 == 0) ? 8 : (1ll << 20);
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 2; k++)
                p[i][k] = (double)rnd_int(m);
        if (it % 2 == 1) { /* exactly cocircular */
            long long cx = rnd_int((1ll << 20) - 5526), cy = rnd_int((1ll << 20) - 5526);
            for (int i = 0; i < 4; i++) {
                int j = (int)(splitmix64() % (uint64_t)ncp);
                p[i][0] = (double)(cx + cp[j][0]);
                p[i][1] = (double)(cy + cp[j][1]);
            }
            if (it % 6 == 1)
                p[3][splitmix64() & 1] += (splitmix64() & 1) ? 1.0 : -1.0;
        } else if (it % 10 == 2) { /* four collinear points: also degenerate */
            for (int i = 1; i < 4; i++) {
                long long t = rnd_int(16);
                p[i][0] = p[0][0] + (double)(t * 1021);
                p[i][1] = p[0][1] + (double)(t * 977);
            }
        }
        int truth = i128_incircle(p[0], p[1], p[2], p[3]);
        tally(&st, truth, naive_incircle(p[0], p[1], p[2], p[3]), 0);
        bad += fm_incircle(p[0], p[1], p[2], p[3]) != truth;
        if (it % 16 == 0)
            bad += perm_mismatches_incircle(p, truth);
    }
    CHECK_EQ(bad, 0);
    CHECK(st.zero > 10000); /* (the naive formula is rarely wrong at this size) */
}

/* Larger integer coordinates for incircle, still within __int128: 2^27. */
static void test_incircle_integer_large(void)
{
    rng_seed(5);
    int bad = 0, zero = 0;
    for (int it = 0; it < 50000; it++) {
        double p[4][2];
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 2; k++)
                p[i][k] = (double)rnd_int(1ll << 27);
        if (it % 2) { /* d repeats a, b or c: exactly degenerate */
            p[3][0] = p[it % 3][0];
            p[3][1] = p[it % 3][1];
        }
        int truth = i128_incircle(p[0], p[1], p[2], p[3]);
        zero += truth == 0;
        bad += fm_incircle(p[0], p[1], p[2], p[3]) != truth;
        bad += ref_incircle(p[0], p[1], p[2], p[3]) != truth;
    }
    CHECK_EQ(bad, 0);
    CHECK(zero > 20000);
}

/* Near-collinear UTM-like points: c is computed on the line ab in double and
 * then moved by a few ulps. */
static void test_orient2d_near_degenerate(void)
{
    rng_seed(6);
    stats st = {0, 0, 0, 0};
    int bad = 0;
    for (int it = 0; it < 100000; it++) {
        double p[3][2];
        for (int i = 0; i < 2; i++) {
            p[i][0] = 5e5 + 2e4 * rnd_unit();
            p[i][1] = 4e6 + 2e4 * rnd_unit();
        }
        if (it % 3 == 0) { /* spread over several binades: inexact differences */
            p[0][0] = rnd_mixed();
            p[0][1] = rnd_mixed();
        }
        double t = -1.0 + 3.0 * rnd_unit();
        p[2][0] = p[0][0] + t * (p[1][0] - p[0][0]);
        p[2][1] = p[0][1] + t * (p[1][1] - p[0][1]);
        p[2][splitmix64() & 1] = ulps(p[2][splitmix64() & 1], (int)rnd_int(2));
        const double *q[3] = {p[0], p[1], p[2]};
        int truth = ref_orient2d(p[0], p[1], p[2]);
        tally(&st, truth, naive_orient2d(p[0], p[1], p[2]), inexact_differences(q, 3, 2));
        bad += fm_orient2d(p[0], p[1], p[2]) != truth;
        if (it % 8 == 0)
            bad += perm_mismatches_orient2d(p, truth);
    }
    CHECK_EQ(bad, 0);
    CHECK(st.naive_wrong > 1000);
    CHECK(st.inexact_hard > 100);
    CHECK_EQ(big_overflow, 0);
}

/* Near-coplanar UTM-like points (x ~ 5e5, y ~ 4e6, z ~ +-2e3). */
static void test_orient3d_near_degenerate(void)
{
    rng_seed(7);
    stats st = {0, 0, 0, 0};
    int bad = 0;
    for (int it = 0; it < 60000; it++) {
        double p[4][3];
        for (int i = 0; i < 3; i++) {
            p[i][0] = 5e5 + 1e4 * rnd_unit();
            p[i][1] = 4e6 + 1e4 * rnd_unit();
            p[i][2] = -2e3 + 4e3 * rnd_unit();
        }
        if (it % 3 == 0) /* one point of different magnitude: inexact differences */
            for (int k = 0; k < 3; k++)
                p[splitmix64() % 3][k] = rnd_mixed();
        double s = -1.0 + 3.0 * rnd_unit(), t = -1.0 + 3.0 * rnd_unit();
        for (int k = 0; k < 3; k++)
            p[3][k] = p[0][k] + s * (p[1][k] - p[0][k]) + t * (p[2][k] - p[0][k]);
        int k = (int)(splitmix64() % 3);
        p[3][k] = ulps(p[3][k], (int)rnd_int(2));
        const double *q[4] = {p[0], p[1], p[2], p[3]};
        int truth = ref_orient3d(p[0], p[1], p[2], p[3]);
        tally(&st, truth, naive_orient3d(p[0], p[1], p[2], p[3]), inexact_differences(q, 4, 3));
        bad += fm_orient3d(p[0], p[1], p[2], p[3]) != truth;
        if (it % 8 == 0)
            bad += perm_mismatches_orient3d(p, truth);
    }
    CHECK_EQ(bad, 0);
    CHECK(st.naive_wrong > 500);
    CHECK(st.inexact_hard > 100);
    CHECK_EQ(big_overflow, 0);
}

/* Near-cocircular UTM-like points: d computed on the circle, moved by ulps. */
static void test_incircle_near_degenerate(void)
{
    rng_seed(8);
    stats st = {0, 0, 0, 0};
    int bad = 0;
    for (int it = 0; it < 60000; it++) {
        double p[4][2];
        double cx = 5e5 + 1e4 * rnd_unit(), cy = 4e6 + 1e4 * rnd_unit();
        double r = (it % 2) ? 1e4 * rnd_unit() + 1e-3 : 0.5 + rnd_unit();
        for (int i = 0; i < 4; i++) {
            double th = 6.283185307179586 * rnd_unit();
            p[i][0] = cx + r * cos(th);
            p[i][1] = cy + r * sin(th);
        }
        if (it % 4 == 0) { /* collinear-ish, spread over binades */
            double x0 = rnd_mixed(), y0 = rnd_mixed(), dx = rnd_mixed(), dy = rnd_mixed();
            for (int i = 0; i < 4; i++) {
                double tt = -2.0 + 4.0 * rnd_unit();
                p[i][0] = x0 + tt * dx;
                p[i][1] = y0 + tt * dy;
            }
        }
        int k = (int)(splitmix64() % 2);
        p[3][k] = ulps(p[3][k], (int)rnd_int(2));
        const double *q[4] = {p[0], p[1], p[2], p[3]};
        int truth = ref_incircle(p[0], p[1], p[2], p[3]);
        tally(&st, truth, naive_incircle(p[0], p[1], p[2], p[3]), inexact_differences(q, 4, 2));
        bad += fm_incircle(p[0], p[1], p[2], p[3]) != truth;
        if (it % 8 == 0)
            bad += perm_mismatches_incircle(p, truth);
    }
    CHECK_EQ(bad, 0);
    CHECK(st.naive_wrong > 500);
    CHECK(st.inexact_hard > 100);
    CHECK_EQ(big_overflow, 0);
}

/* Exactly degenerate configurations whose coordinate differences are not
 * representable (points on y = 2x, z = 2x, or repeated points, with full
 * mantissas over many binades), so the exact raw-coordinate stage decides. */
static void test_exact_degenerate_mixed_magnitudes(void)
{
    rng_seed(9);
    int bad = 0, inexact = 0;
    for (int it = 0; it < 20000; it++) {
        double p[4][3];
        for (int i = 0; i < 4; i++) {
            p[i][0] = rnd_mixed();
            p[i][1] = 2.0 * p[i][0];
            p[i][2] = rnd_mixed();
        }
        const double *q[4] = {p[0], p[1], p[2], p[3]};
        inexact += inexact_differences(q, 4, 2);
        bad += fm_orient2d(p[0], p[1], p[2]) != 0;
        bad += fm_incircle(p[0], p[1], p[2], p[3]) != 0;
        /* coplanar: all on the plane y = 2x */
        double r[4][3];
        for (int i = 0; i < 4; i++)
            r[i][0] = p[i][0], r[i][1] = p[i][2], r[i][2] = p[i][1];
        bad += fm_orient3d(r[0], r[1], r[2], r[3]) != 0; /* z = 2x */
        bad += fm_collinear3d(p[0], p[1], (double[3]){p[0][0], p[0][1], p[0][2]}) != 1;
        /* a repeated point */
        double u[4][3];
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                u[i][k] = rnd_mixed();
        bad += fm_orient3d(u[0], u[1], u[2], u[it % 3]) != 0;
        bad += fm_incircle(u[0], u[1], u[2], u[it % 3]) != 0;
        bad += fm_orient2d(u[0], u[1], u[it % 2]) != 0;
        /* and one ulp away from degenerate: compare with the reference */
        int k = (int)(splitmix64() % 2);
        p[3][k] = ulps(p[3][k], (splitmix64() & 1) ? 1 : -1);
        bad += fm_incircle(p[0], p[1], p[2], p[3]) != ref_incircle(p[0], p[1], p[2], p[3]);
        bad += fm_orient2d(p[0], p[1], p[3]) != ref_orient2d(p[0], p[1], p[3]);
        r[3][2] = ulps(r[3][2], 1);
        bad += fm_orient3d(r[0], r[1], r[2], r[3]) != ref_orient3d(r[0], r[1], r[2], r[3]);
    }
    CHECK_EQ(bad, 0);
    CHECK(inexact > 10000);
    CHECK_EQ(big_overflow, 0);
}

/* Translating all points by an offset (exactly: every translated coordinate
 * representable) does not change any predicate. */
static int translate_exact(const double *p, double *q, const double *off, int dim)
{
    for (int k = 0; k < dim; k++) {
        q[k] = p[k] + off[k];
        if (q[k] - off[k] != p[k] || q[k] - p[k] != off[k])
            return 0;
    }
    return 1;
}

static void test_translation_invariance(void)
{
    rng_seed(10);
    int bad = 0, used = 0;
    for (int it = 0; it < 40000; it++) {
        /* Near-degenerate points on a 2^-16 grid around UTM coordinates. */
        double p[4][3];
        double base[3] = {5e5, 4e6, 0.0};
        long long dir[2][3];
        for (int k = 0; k < 3; k++)
            dir[0][k] = rnd_int(1 << 20), dir[1][k] = rnd_int(1 << 20);
        for (int i = 0; i < 4; i++) {
            long long s = rnd_int(64), t = rnd_int(64);
            for (int k = 0; k < 3; k++)
                p[i][k] = base[k] + (double)(s * dir[0][k] + t * dir[1][k]) * 0x1p-16;
        }
        p[3][splitmix64() % 3] += (double)rnd_int(1) * 0x1p-16;
        double off[3];
        for (int k = 0; k < 3; k++)
            off[k] = (double)rnd_int(1ll << 30) * ((it % 2) ? 0x1p-16 : 1.0);
        double q[4][3];
        int ok = 1;
        for (int i = 0; i < 4; i++)
            ok &= translate_exact(p[i], q[i], off, 3);
        if (!ok)
            continue;
        used++;
        int o3 = fm_orient3d(p[0], p[1], p[2], p[3]);
        int ic = fm_incircle(p[0], p[1], p[2], p[3]);
        int o2 = fm_orient2d(p[0], p[1], p[3]);
        bad += o3 != ref_orient3d(p[0], p[1], p[2], p[3]);
        bad += ic != ref_incircle(p[0], p[1], p[2], p[3]);
        bad += o2 != ref_orient2d(p[0], p[1], p[3]);
        bad += fm_orient3d(q[0], q[1], q[2], q[3]) != o3;
        bad += fm_incircle(q[0], q[1], q[2], q[3]) != ic;
        bad += fm_orient2d(q[0], q[1], q[3]) != o2;
        bad += fm_collinear3d(q[0], q[1], q[2]) != fm_collinear3d(p[0], p[1], p[2]);
    }
    CHECK_EQ(bad, 0);
    CHECK(used > 30000);
}

/* Scaling by a power of two is exact and does not change any predicate. */
static void test_power_of_two_scaling(void)
{
    rng_seed(11);
    int bad = 0;
    static const double sc[] = {0x1p-40, 0x1p-7, 0x1p9, 0x1p50};
    for (int it = 0; it < 20000; it++) {
        double p[4][3], q[4][3];
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                p[i][k] = rnd_mixed();
        for (int k = 0; k < 3; k++) /* near-coplanar d */
            p[3][k] = p[0][k] + 0.5 * (p[1][k] - p[0][k]) + 0.25 * (p[2][k] - p[0][k]);
        double s = sc[it % 4];
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                q[i][k] = p[i][k] * s;
        bad += fm_orient3d(q[0], q[1], q[2], q[3]) != fm_orient3d(p[0], p[1], p[2], p[3]);
        bad += fm_incircle(q[0], q[1], q[2], q[3]) != fm_incircle(p[0], p[1], p[2], p[3]);
        bad += fm_orient3d(p[0], p[1], p[2], p[3]) != ref_orient3d(p[0], p[1], p[2], p[3]);
    }
    CHECK_EQ(bad, 0);
}

/* Exactly collinear 3D points with large (UTM-sized, fractional) coordinates,
 * and the same moved off the line by one ulp. */
static void test_collinear3d(void)
{
    rng_seed(12);
    int bad = 0, collinear = 0, off_line = 0;
    for (int it = 0; it < 50000; it++) {
        double a[3], b[3], c[3];
        double base[3] = {5e5, 4e6, -1e3};
        long long dir[3];
        for (int k = 0; k < 3; k++) {
            dir[k] = rnd_int(1 << 16);
            a[k] = base[k] + (double)rnd_int(1ll << 30) * 0x1p-20;
        }
        long long j = rnd_int(1 << 10), m = rnd_int(1 << 10);
        for (int k = 0; k < 3; k++) {
            b[k] = a[k] + (double)(j * dir[k]) * 0x1p-20;
            c[k] = a[k] + (double)(m * dir[k]) * 0x1p-20;
        }
        if (it % 5 == 0) { /* integer coordinates up to 2^50 */
            for (int k = 0; k < 3; k++) {
                a[k] = (double)rnd_int(1ll << 49);
                b[k] = a[k] + (double)(j * dir[k]) * 1024.0;
                c[k] = a[k] + (double)(m * dir[k]) * 1024.0;
            }
        }
        int got = fm_collinear3d(a, b, c);
        bad += got != 1;
        collinear += got;
        bad += fm_collinear3d(c, a, b) != 1;
        int k = (int)(splitmix64() % 3);
        c[k] = ulps(c[k], (splitmix64() & 1) ? 1 : -1);
        int truth = 1;
        for (int q = 0; q < 3; q++) {
            int u = q, v = (q + 1) % 3;
            double pa[2] = {a[u], a[v]}, pb[2] = {b[u], b[v]}, pc[2] = {c[u], c[v]};
            if (ref_orient2d(pa, pb, pc) != 0)
                truth = 0;
        }
        bad += fm_collinear3d(a, b, c) != truth;
        off_line += truth == 0;
    }
    CHECK_EQ(bad, 0);
    CHECK(collinear == 50000);
    CHECK(off_line > 40000);
    CHECK_EQ(big_overflow, 0);
}

FM_TEST_MAIN(FM_CASE(test_sign_conventions), FM_CASE(test_reference_selfcheck),
             FM_CASE(test_orient2d_integer), FM_CASE(test_orient3d_integer),
             FM_CASE(test_incircle_integer), FM_CASE(test_incircle_integer_large),
             FM_CASE(test_orient2d_near_degenerate), FM_CASE(test_orient3d_near_degenerate),
             FM_CASE(test_incircle_near_degenerate),
             FM_CASE(test_exact_degenerate_mixed_magnitudes),
             FM_CASE(test_translation_invariance), FM_CASE(test_power_of_two_scaling),
             FM_CASE(test_collinear3d))
