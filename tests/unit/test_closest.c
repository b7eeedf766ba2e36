/* Closest-point tree (fm_closest.h) against brute force.
 *
 * The reference is independent of the library's region scheme: the nearest
 * of the three edges and, when it falls inside, the orthogonal projection
 * onto the plane, in long double with coordinates taken relative to the
 * query point (exact for UTM-sized input) and the normal in __float128, so
 * that it stays accurate on slivers where double loses digits. */
#include "fm_test.h"

#include "fm_closest.h"

#include <float.h>
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

static double rnd_unit(void) { return (double)(splitmix64() >> 11) * 0x1p-53; }

static double rnd_range(double lo, double hi) { return lo + (hi - lo) * rnd_unit(); }

static size_t rnd_below(size_t n) { return (size_t)(splitmix64() % n); }

/* ---- reference ---------------------------------------------------------- */

typedef long double ld;

static ld dotl(const ld u[3], const ld v[3]) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

/* Squared distance from the origin to segment xy. */
static ld ref_segment(const ld x[3], const ld y[3])
{
    ld e[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
    ld len = dotl(e, e), t = 0;
    if (len > 0) {
        t = -dotl(x, e) / len;
        t = t < 0 ? 0 : (t > 1 ? 1 : t);
    }
    ld r[3] = {x[0] + t * e[0], x[1] + t * e[1], x[2] + t * e[2]};
    return dotl(r, r);
}

static ld side(const ld x[3], const ld y[3], const ld n[3])
{
    ld c[3] = {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
    return dotl(c, n);
}

static ld ref_triangle(const double p[3], const double *a, const double *b, const double *c)
{
    ld A[3], B[3], C[3];
    for (int k = 0; k < 3; k++) {
        A[k] = (ld)a[k] - p[k];
        B[k] = (ld)b[k] - p[k];
        C[k] = (ld)c[k] - p[k];
    }
    ld best = ref_segment(A, B);
    ld d = ref_segment(B, C);
    best = d < best ? d : best;
    d = ref_segment(C, A);
    best = d < best ? d : best;

    __float128 u[3], v[3];
    for (int k = 0; k < 3; k++) {
        u[k] = (__float128)B[k] - (__float128)A[k];
        v[k] = (__float128)C[k] - (__float128)A[k];
    }
    ld n[3] = {(ld)(u[1] * v[2] - u[2] * v[1]), (ld)(u[2] * v[0] - u[0] * v[2]),
               (ld)(u[0] * v[1] - u[1] * v[0])};
    ld nn = dotl(n, n);
    if (nn > 0) {
        ld s = dotl(n, A) / nn;
        ld F[3] = {s * n[0], s * n[1], s * n[2]};
        ld AF[3], BF[3], CF[3];
        for (int k = 0; k < 3; k++) {
            AF[k] = A[k] - F[k];
            BF[k] = B[k] - F[k];
            CF[k] = C[k] - F[k];
        }
        if (side(BF, CF, n) >= 0 && side(CF, AF, n) >= 0 && side(AF, BF, n) >= 0) {
            d = s * s * nn;
            best = d < best ? d : best;
        }
    }
    return best;
}

typedef struct ref_hit {
    double dist;      /* nearest */
    int32_t triangle; /* lowest index at that distance */
    double second;    /* nearest over the other triangles */
} ref_hit;

static ref_hit brute_force(const fm_mesh *m, const double p[3])
{
    const double *v = fm_mesh_vertices(m);
    const int32_t *t = fm_mesh_triangles(m);
    ld best = INFINITY, second = INFINITY;
    int32_t bi = -1;
    for (size_t i = 0; i < fm_mesh_ntriangles(m); i++) {
        ld d = ref_triangle(p, v + 3 * t[3 * i], v + 3 * t[3 * i + 1], v + 3 * t[3 * i + 2]);
        if (d < best) {
            second = best;
            best = d;
            bi = (int32_t)i;
        } else if (d < second) {
            second = d;
        }
    }
    return (ref_hit){(double)sqrtl(best), bi, (double)sqrtl(second)};
}

static double ref_distance(const fm_mesh *m, int32_t tri, const double p[3])
{
    const double *v = fm_mesh_vertices(m);
    const int32_t *t = fm_mesh_triangles(m) + 3 * tri;
    return (double)sqrtl(ref_triangle(p, v + 3 * t[0], v + 3 * t[1], v + 3 * t[2]));
}

/* ---- meshes -------------------------------------------------------------- */

static void add_tri(fm_mesh *m, const double a[3], const double b[3], const double c[3])
{
    int32_t i = fm_mesh_add_vertex(m, a[0], a[1], a[2]);
    fm_mesh_add_vertex(m, b[0], b[1], b[2]);
    fm_mesh_add_vertex(m, c[0], c[1], c[2]);
    fm_mesh_add_triangle(m, i, i + 1, i + 2, 0);
}

/* Multiples of 1/64 m: sums and differences of a few stay exact, so
 * "collinear" and "coincident" below are exactly that. */
static double grid64(double x) { return rint(x * 64.0) / 64.0; }

/* A soup of triangles in a 2 km box at offset o: ordinary ones, needles,
 * caps (a vertex a hair off the opposite edge) and exactly degenerate ones
 * (collinear corners, two or three coincident corners). */
static fm_mesh *soup(size_t n, const double o[3])
{
    fm_mesh *m = fm_mesh_create();
    for (size_t i = 0; i < n; i++) {
        double a[3], b[3], c[3], d[3];
        for (int k = 0; k < 3; k++)
            a[k] = o[k] + grid64(rnd_range(-1000, 1000));
        double size = pow(10.0, rnd_range(0, 2.5));
        for (int k = 0; k < 3; k++)
            d[k] = grid64(rnd_range(-size, size));
        switch (rnd_below(8)) {
        case 0: /* needle: two corners 1e-4 m apart */
            for (int k = 0; k < 3; k++) {
                b[k] = a[k] + d[k];
                c[k] = b[k] + rnd_range(-1e-4, 1e-4);
            }
            break;
        case 1: { /* cap: c within 1e-9 .. 1e-3 m of the middle of ab */
            double off = pow(10.0, rnd_range(-9, -3));
            for (int k = 0; k < 3; k++)
                b[k] = a[k] + d[k];
            for (int k = 0; k < 3; k++)
                c[k] = 0.5 * (a[k] + b[k]) + (k == 2 ? off : 0.0);
            break;
        }
        case 2: /* collinear, c between or beyond */
            for (int k = 0; k < 3; k++) {
                b[k] = a[k] + d[k];
                c[k] = a[k] + (rnd_below(2) ? 0.5 : 2.0) * d[k];
            }
            break;
        case 3: /* two coincident corners */
            for (int k = 0; k < 3; k++) {
                b[k] = a[k];
                c[k] = a[k] + d[k];
            }
            break;
        case 4: /* a point */
            for (int k = 0; k < 3; k++)
                b[k] = c[k] = a[k];
            break;
        default:
            for (int k = 0; k < 3; k++) {
                b[k] = a[k] + d[k];
                c[k] = a[k] + grid64(rnd_range(-size, size));
            }
        }
        if (rnd_below(2)) /* either orientation */
            add_tri(m, a, c, b);
        else
            add_tri(m, a, b, c);
    }
    return m;
}

/* A wavy, dipping fault-like sheet on an nx x ny grid, with jitter. */
static fm_mesh *wavy(int nx, int ny, const double o[3], double step)
{
    fm_mesh *m = fm_mesh_create();
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            double u = (i + rnd_range(-0.3, 0.3)) * step, w = (j + rnd_range(-0.3, 0.3)) * step;
            fm_mesh_add_vertex(m, o[0] + u + 80 * sin(w / 700), o[1] + 0.5 * w + 300 * sin(u / 900),
                               o[2] - 0.8 * w + 50 * cos(u / 400 + w / 300));
        }
    for (int j = 0; j + 1 < ny; j++)
        for (int i = 0; i + 1 < nx; i++) {
            int32_t v0 = j * nx + i, v1 = v0 + 1, v2 = v0 + nx, v3 = v2 + 1;
            if ((i + j) % 2) {
                fm_mesh_add_triangle(m, v0, v1, v3, 0);
                fm_mesh_add_triangle(m, v0, v3, v2, 0);
            } else {
                fm_mesh_add_triangle(m, v0, v1, v2, 0);
                fm_mesh_add_triangle(m, v1, v3, v2, 0);
            }
        }
    return m;
}

static void mesh_box(const fm_mesh *m, double lo[3], double hi[3])
{
    const double *v = fm_mesh_vertices(m);
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (size_t i = 0; i < fm_mesh_nvertices(m); i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], v[3 * i + k]);
            hi[k] = fmax(hi[k], v[3 * i + k]);
        }
}

/* Query points: on the surface (also exactly on edges and corners), near it
 * at 1e-4 .. 100 m, anywhere in a box three times the mesh's, and far. */
static void query_point(const fm_mesh *m, double p[3])
{
    const double *v = fm_mesh_vertices(m);
    const int32_t *t = fm_mesh_triangles(m);
    double lo[3], hi[3];
    mesh_box(m, lo, hi);
    size_t kind = rnd_below(10);
    if (kind < 6) {
        const int32_t *tri = t + 3 * rnd_below(fm_mesh_ntriangles(m));
        double w[3] = {rnd_unit(), rnd_unit(), rnd_unit()};
        if (kind == 0)
            w[rnd_below(3)] = 0;
        if (kind == 1)
            w[rnd_below(3)] = w[rnd_below(3)] = 0;
        double s = w[0] + w[1] + w[2];
        if (s == 0)
            w[0] = s = 1;
        double off = kind < 2 ? 0 : pow(10.0, rnd_range(-4, 2));
        double dir[3] = {rnd_range(-1, 1), rnd_range(-1, 1), rnd_range(-1, 1)};
        double dl = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]) + 1e-300;
        for (int k = 0; k < 3; k++)
            p[k] = (w[0] * v[3 * tri[0] + k] + w[1] * v[3 * tri[1] + k] + w[2] * v[3 * tri[2] + k]) / s +
                   off * dir[k] / dl;
    } else if (kind < 9) {
        for (int k = 0; k < 3; k++) {
            double mid = 0.5 * (lo[k] + hi[k]), ext = hi[k] - lo[k] + 1;
            p[k] = rnd_range(mid - 1.5 * ext, mid + 1.5 * ext);
        }
    } else {
        for (int k = 0; k < 3; k++)
            p[k] = 0.5 * (lo[k] + hi[k]) + rnd_range(-1e6, 1e6);
    }
}

/* ---- the brute-force comparison ----------------------------------------- */

/* Absolute error allowed on top of 1e-9 relative: a few ulps of the
 * coordinates relative to the mesh (the library works relative to an
 * integer centre; the reference relative to the query point). */
static double slack(const fm_mesh *m, const double p[3])
{
    double lo[3], hi[3], r = 0;
    mesh_box(m, lo, hi);
    for (int k = 0; k < 3; k++)
        r = fmax(r, fmax(fabs(p[k] - 0.5 * (lo[k] + hi[k])), hi[k] - lo[k]));
    return 64 * DBL_EPSILON * r;
}

static double worst_rel; /* largest |d - ref| / (1e-9 ref + slack), reported */

static void compare(const fm_mesh *m, size_t nq, uint64_t seed)
{
    fm_error err;
    fm_closest_tree *t = fm_closest_tree_create(m, &err);
    CHECK(t != NULL);
    if (!t)
        return;
    CHECK_EQ(fm_closest_tree_ntriangles(t), fm_mesh_ntriangles(m));
    const double *v = fm_mesh_vertices(m);
    const int32_t *tri = fm_mesh_triangles(m);
    rng_seed(seed);
    size_t unique = 0, bad = 0;
    for (size_t q = 0; q < nq; q++) {
        double p[3];
        query_point(m, p);
        ref_hit r = brute_force(m, p);
        double tol = 1e-9 * r.dist + slack(m, p);
        fm_closest_hit h;
        memset(&h, 0, sizeof h);
        int found = fm_closest_query(t, p, INFINITY, &h);
        CHECK(found);
        if (!found)
            continue;
        double e = fabs(h.dist - r.dist);
        worst_rel = fmax(worst_rel, e / tol);
        int ok = e <= tol;
        /* The triangle returned is itself at the minimum distance. */
        ok &= h.triangle >= 0 && (size_t)h.triangle < fm_mesh_ntriangles(m) &&
              fabs(ref_distance(m, h.triangle, p) - r.dist) <= tol;
        if (r.second - r.dist > 1e-6 * r.dist + 1e3 * tol) {
            unique++;
            ok &= h.triangle == r.triangle;
        }
        if (ok) {
            /* The foot: on the triangle at the barycentric coordinates, and
             * at the distance reported. */
            /* The foot is rounded to the absolute coordinates. */
            double ftol = 1e-9 * r.dist + 4 * tol +
                          4 * DBL_EPSILON * fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2])));
            const int32_t *c = tri + 3 * h.triangle;
            double fd2 = 0, sum = h.bary[0] + h.bary[1] + h.bary[2];
            ok &= h.bary[0] >= 0 && h.bary[1] >= 0 && h.bary[2] >= 0 && fabs(sum - 1) < 1e-12;
            for (int k = 0; k < 3; k++) {
                double f = h.bary[0] * v[3 * c[0] + k] + h.bary[1] * v[3 * c[1] + k] +
                           h.bary[2] * v[3 * c[2] + k];
                ok &= fabs(f - h.foot[k]) <= ftol;
                fd2 += (p[k] - h.foot[k]) * (p[k] - h.foot[k]);
            }
            ok &= fabs(sqrt(fd2) - h.dist) <= ftol;
        }
        if (!ok && bad++ < 5)
            fprintf(stderr,
                    "query %zu (%.17g, %.17g, %.17g): tree %.17g tri %d bary (%g %g %g), "
                    "reference %.17g tri %d (second %.17g)\n",
                    q, p[0], p[1], p[2], h.dist, (int)h.triangle, h.bary[0], h.bary[1],
                    h.bary[2], r.dist, (int)r.triangle, r.second);
        CHECK(ok);

        /* max_dist: just short of the distance finds nothing, just beyond
         * finds the same hit bit for bit. */
        if (r.dist > 2 * tol) {
            fm_closest_hit h2;
            memset(&h2, 0, sizeof h2);
            CHECK_EQ(fm_closest_query(t, p, r.dist * (1 - 1e-7) - tol, &h2), 0);
            CHECK_EQ(fm_closest_query(t, p, r.dist * (1 + 1e-7) + tol, &h2), 1);
            CHECK(memcmp(&h, &h2, sizeof h) == 0);
        }
    }
    /* Enough of the queries have one clear answer to make the index check
     * mean something. */
    CHECK(unique > nq / 2);
    fm_closest_tree_destroy(t);
}

/* ---- cases --------------------------------------------------------------- */

static const double utm[3] = {512345.25, 3812345.75, -4321.5};
static const double origin[3] = {0, 0, 0};

static void test_soup_utm(void)
{
    rng_seed(1);
    fm_mesh *m = soup(1500, utm);
    compare(m, 3000, 11);
    fm_mesh_destroy(m);
}

static void test_soup_origin(void)
{
    rng_seed(2);
    fm_mesh *m = soup(1500, origin);
    compare(m, 2000, 12);
    fm_mesh_destroy(m);
}

static void test_wavy_utm(void)
{
    rng_seed(3);
    fm_mesh *m = wavy(60, 40, utm, 50);
    compare(m, 3000, 13);
    fm_mesh_destroy(m);
}

/* A single triangle, and fewer triangles than a leaf holds. */
static void test_tiny_meshes(void)
{
    for (size_t n = 1; n <= 5; n++) {
        rng_seed(40 + n);
        fm_mesh *m = soup(n, utm);
        compare(m, 200, 50 + n);
        fm_mesh_destroy(m);
    }
}

/* Known answers, one per region, and the degenerate triangles a region
 * scheme gets wrong when it trusts a zero normal. */
static void test_on_triangle(void)
{
    const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    double f[3], w[3];
    CHECK_NEAR(fm_closest_on_triangle((double[3]){0.25, 0.25, 2}, a, b, c, f, w), 4, 1e-15);
    CHECK_NEAR(w[0], 0.5, 1e-15);
    CHECK_NEAR(w[1], 0.25, 1e-15);
    CHECK_NEAR(w[2], 0.25, 1e-15);
    CHECK_NEAR(f[0], 0.25, 1e-15);
    CHECK_NEAR(f[2], 0, 1e-15);
    CHECK_NEAR(fm_closest_on_triangle((double[3]){-1, -1, 0}, a, b, c, f, w), 2, 0);
    CHECK(w[0] == 1 && f[0] == 0 && f[1] == 0);
    CHECK_NEAR(fm_closest_on_triangle((double[3]){2, -1, 0}, a, b, c, f, w), 2, 0);
    CHECK(w[1] == 1);
    CHECK_NEAR(fm_closest_on_triangle((double[3]){-1, 3, 0}, a, b, c, f, w), 5, 0);
    CHECK(w[2] == 1);
    CHECK_NEAR(fm_closest_on_triangle((double[3]){0.5, -1, 1}, a, b, c, f, w), 2, 1e-15);
    CHECK_NEAR(w[0], 0.5, 1e-15);
    CHECK_NEAR(w[1], 0.5, 1e-15);
    CHECK_NEAR(fm_closest_on_triangle((double[3]){1, 1, 0}, a, b, c, f, w), 0.5, 1e-15);
    CHECK_NEAR(w[1], 0.5, 1e-15);
    CHECK_NEAR(w[2], 0.5, 1e-15);
    CHECK_NEAR(fm_closest_on_triangle((double[3]){-1, 0.25, 0}, a, b, c, f, w), 1, 1e-15);
    CHECK_NEAR(w[2], 0.25, 1e-15);

    /* A point. */
    const double q[3] = {1, 2, 3};
    CHECK_NEAR(fm_closest_on_triangle((double[3]){1, 2, 4}, q, q, q, f, w), 1, 0);
    /* Collinear with c between a and b: the segment ab. */
    CHECK_NEAR(fm_closest_on_triangle((double[3]){1.5, 1, 0}, a, (double[3]){2, 0, 0}, b, f, w),
               1, 1e-15);
    CHECK_NEAR(f[0], 1.5, 1e-15);
    CHECK_NEAR(w[0] * 0 + w[1] * 2 + w[2] * 1, 1.5, 1e-15);
    /* a == b: the foot lies on ac, beyond a along it. */
    CHECK_NEAR(fm_closest_on_triangle((double[3]){0, 1, 1}, a, a, (double[3]){0, 2, 0}, f, w), 1,
               1e-15);
    CHECK_NEAR(f[1], 1, 1e-15);
    /* A cap 1 km long and 1e-9 m high, a millimetre above it. */
    const double ca[3] = {0, 0, 0}, cb[3] = {1000, 0, 0}, cc[3] = {500, 1e-9, 0};
    double d2 = fm_closest_on_triangle((double[3]){250, 2e-10, 1e-3}, ca, cb, cc, f, w);
    CHECK_NEAR(sqrt(d2), 1e-3, 1e-15);
    /* NULL outputs are allowed. */
    CHECK_NEAR(fm_closest_on_triangle((double[3]){0, 0, 1}, a, b, c, NULL, NULL), 1, 0);
}

/* Every triangle twice (the copies at higher indices): the lower one must
 * win every exact tie, whichever leaf the traversal reaches first. */
static void test_ties(void)
{
    rng_seed(5);
    fm_mesh *m = wavy(30, 20, utm, 80);
    size_t nt = fm_mesh_ntriangles(m);
    fm_mesh *twice = fm_mesh_clone(m);
    const int32_t *t = fm_mesh_triangles(m);
    for (size_t i = 0; i < nt; i++)
        fm_mesh_add_triangle(twice, t[3 * i], t[3 * i + 1], t[3 * i + 2], 0);
    /* and the copies first, so that the lower index is the copy */
    fm_mesh *first = fm_mesh_create();
    const double *v = fm_mesh_vertices(m);
    for (size_t i = 0; i < fm_mesh_nvertices(m); i++)
        fm_mesh_add_vertex(first, v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    for (size_t i = 0; i < nt; i++)
        fm_mesh_add_triangle(first, t[3 * (nt - 1 - i)], t[3 * (nt - 1 - i) + 1],
                             t[3 * (nt - 1 - i) + 2], 0);
    for (size_t i = 0; i < nt; i++)
        fm_mesh_add_triangle(first, t[3 * i], t[3 * i + 1], t[3 * i + 2], 0);

    fm_closest_tree *t1 = fm_closest_tree_create(m, NULL);
    fm_closest_tree *t2 = fm_closest_tree_create(twice, NULL);
    fm_closest_tree *t3 = fm_closest_tree_create(first, NULL);
    CHECK(t1 && t2 && t3);
    size_t wrong = 0;
    for (int q = 0; q < 3000 && t1 && t2 && t3; q++) {
        double p[3];
        query_point(m, p);
        fm_closest_hit h1, h2, h3;
        CHECK(fm_closest_query(t1, p, INFINITY, &h1));
        CHECK(fm_closest_query(t2, p, INFINITY, &h2));
        CHECK(fm_closest_query(t3, p, INFINITY, &h3));
        /* Same geometry, so the same distance; the index is the lowest. */
        wrong += h2.triangle >= (int32_t)nt || h2.dist != h1.dist;
        wrong += h3.triangle >= (int32_t)nt || h3.dist != h1.dist;
        wrong += h2.triangle != h1.triangle;
    }
    CHECK_EQ(wrong, 0);
    fm_closest_tree_destroy(t1);
    fm_closest_tree_destroy(t2);
    fm_closest_tree_destroy(t3);
    fm_mesh_destroy(m);
    fm_mesh_destroy(twice);
    fm_mesh_destroy(first);
}

/* Exact ties between different leaves: triangles mirrored across the
 * plane x = utm[0], on multiples of 1/8 m so that every difference the
 * library forms is exact and fm_closest_on_triangle on the mesh's own
 * coordinates repeats its arithmetic bit for bit. Brute force with it then
 * gives the exact minimum and its lowest index, and the tree must match,
 * which it only does if it opens boxes at exactly the best distance. Pairs
 * alternate which side comes first; some share a corner on the plane. */
static void test_exact_ties(void)
{
    rng_seed(10);
    fm_mesh *m = fm_mesh_create();
    double corners[600][3];
    for (int k = 0; k < 200; k++) {
        double tri[3][3];
        for (int j = 0; j < 3; j++) {
            tri[j][0] = -rint(rnd_range(8, 8000)) / 8;
            tri[j][1] = rint(rnd_range(-8000, 8000)) / 8;
            tri[j][2] = rint(rnd_range(-8000, 8000)) / 8;
        }
        if (k % 3 == 0)
            tri[0][0] = 0;
        double mir[3][3];
        for (int j = 0; j < 3; j++) {
            mir[j][0] = utm[0] - tri[j][0];
            tri[j][0] += utm[0];
            for (int a = 1; a < 3; a++)
                mir[j][a] = tri[j][a] += utm[a];
            memcpy(corners[3 * k + j], tri[j], sizeof tri[j]);
        }
        if (k % 2) {
            add_tri(m, mir[0], mir[1], mir[2]);
            add_tri(m, tri[0], tri[1], tri[2]);
        } else {
            add_tri(m, tri[0], tri[1], tri[2]);
            add_tri(m, mir[0], mir[1], mir[2]);
        }
    }
    fm_closest_tree *t = fm_closest_tree_create(m, NULL);
    CHECK(t != NULL);
    const double *v = fm_mesh_vertices(m);
    const int32_t *tr = fm_mesh_triangles(m);
    size_t wrong = 0, tied = 0;
    for (int q = 0; q < 3000 && t; q++) {
        double p[3];
        if (q % 4 == 0) {
            memcpy(p, corners[rnd_below(600)], sizeof p);
        } else {
            for (int a = 0; a < 3; a++)
                p[a] = utm[a] + rint(rnd_range(-9000, 9000)) / 8;
            if (q % 4 != 3)
                p[0] = utm[0];
        }
        double best = INFINITY;
        int32_t bi = -1, ties = 0;
        for (size_t i = 0; i < fm_mesh_ntriangles(m); i++) {
            const int32_t *c = tr + 3 * i;
            double d2 = fm_closest_on_triangle(p, v + 3 * c[0], v + 3 * c[1], v + 3 * c[2], NULL,
                                               NULL);
            if (d2 < best) {
                best = d2;
                bi = (int32_t)i;
                ties = 0;
            } else if (d2 == best) {
                ties++;
            }
        }
        tied += ties > 0;
        fm_closest_hit h;
        int found = fm_closest_query(t, p, INFINITY, &h);
        wrong += !found || h.triangle != bi || h.dist != sqrt(best);
    }
    CHECK_EQ(wrong, 0);
    CHECK(tied > 1000);
    fm_closest_tree_destroy(t);
    fm_mesh_destroy(m);
}

/* Two trees of the same mesh answer bit for bit alike, also after the mesh
 * is gone (the tree holds its own copy; ASan would see a stale read). */
static void test_determinism(void)
{
    rng_seed(6);
    fm_mesh *m = soup(3000, utm);
    fm_mesh *copy = fm_mesh_clone(m);
    fm_closest_tree *t1 = fm_closest_tree_create(m, NULL);
    fm_closest_tree *t2 = fm_closest_tree_create(copy, NULL);
    fm_mesh_destroy(copy);
    CHECK(t1 && t2);
    rng_seed(7);
    size_t differ = 0;
    for (int q = 0; q < 5000 && t1 && t2; q++) {
        double p[3];
        query_point(m, p);
        fm_closest_hit h1, h2;
        memset(&h1, 0, sizeof h1);
        memset(&h2, 0, sizeof h2);
        int f1 = fm_closest_query(t1, p, q % 2 ? INFINITY : 10.0, &h1);
        int f2 = fm_closest_query(t2, p, q % 2 ? INFINITY : 10.0, &h2);
        differ += f1 != f2 || memcmp(&h1, &h2, sizeof h1) != 0;
    }
    CHECK_EQ(differ, 0);
    fm_closest_tree_destroy(t1);
    fm_closest_tree_destroy(t2);
    fm_mesh_destroy(m);
}

static int32_t *brute_box(const fm_mesh *m, const double lo[3], const double hi[3], size_t *n)
{
    const double *v = fm_mesh_vertices(m);
    const int32_t *t = fm_mesh_triangles(m);
    int32_t *out = malloc((fm_mesh_ntriangles(m) + 1) * sizeof *out);
    *n = 0;
    for (size_t i = 0; i < fm_mesh_ntriangles(m); i++) {
        int hit = 1;
        for (int k = 0; k < 3; k++) {
            double a = v[3 * t[3 * i] + k], b = v[3 * t[3 * i + 1] + k], c = v[3 * t[3 * i + 2] + k];
            hit &= fmin(a, fmin(b, c)) <= hi[k] && fmax(a, fmax(b, c)) >= lo[k];
        }
        if (hit)
            out[(*n)++] = (int32_t)i;
    }
    return out;
}

static int stop_at_first(int32_t tri, void *user)
{
    *(int32_t *)user = tri;
    return 1;
}

static int count_calls(int32_t tri, void *user)
{
    (void)tri;
    ++*(size_t *)user;
    return 0;
}

static void test_box(void)
{
    rng_seed(8);
    fm_mesh *m = soup(2000, utm);
    fm_closest_tree *t = fm_closest_tree_create(m, NULL);
    CHECK(t != NULL);
    double mlo[3], mhi[3];
    mesh_box(m, mlo, mhi);
    const double *v = fm_mesh_vertices(m);
    size_t mismatched = 0, nonempty = 0;
    for (int q = 0; q < 1000 && t; q++) {
        double lo[3], hi[3];
        if (q % 4 == 0) { /* a box that is one vertex: touching counts */
            const double *x = v + 3 * rnd_below(fm_mesh_nvertices(m));
            memcpy(lo, x, sizeof lo);
            memcpy(hi, x, sizeof hi);
        } else {
            double size = pow(10.0, rnd_range(-1, 3.5));
            for (int k = 0; k < 3; k++) {
                lo[k] = rnd_range(mlo[k] - 200, mhi[k] + 200);
                hi[k] = lo[k] + size * rnd_range(0.2, 1);
            }
        }
        size_t nb, nt;
        int32_t *ref = brute_box(m, lo, hi, &nb);
        int32_t *got = NULL;
        CHECK(fm_closest_tree_box_collect(t, lo, hi, &got, &nt, NULL) == FM_OK);
        mismatched += nb != nt || (nb && memcmp(ref, got, nb * sizeof *ref) != 0);
        nonempty += nb > 0;
        size_t calls = 0;
        CHECK_EQ(fm_closest_tree_box_query(t, lo, hi, count_calls, &calls), nb);
        CHECK_EQ(calls, nb);
        int32_t first = -1;
        CHECK_EQ(fm_closest_tree_box_query(t, lo, hi, stop_at_first, &first), nb ? 1 : 0);
        if (nb) {
            int found = 0;
            for (size_t i = 0; i < nb; i++)
                found |= ref[i] == first;
            CHECK(found);
        }
        free(ref);
        free(got);
    }
    CHECK_EQ(mismatched, 0);
    /* Both kinds of answer occur often enough to count. */
    CHECK(nonempty > 300 && nonempty < 900);
    /* An inverted box holds nothing. */
    size_t n = 1;
    int32_t *got = NULL;
    CHECK(fm_closest_tree_box_collect(t, mhi, mlo, &got, &n, NULL) == FM_OK);
    CHECK(n == 0 && got == NULL);
    /* So does a box with a NaN bound. */
    double nan_lo[3] = {NAN, mlo[1], mlo[2]};
    CHECK_EQ(fm_closest_tree_box_query(t, nan_lo, mhi, NULL, NULL), 0);
    fm_closest_tree_destroy(t);
    fm_mesh_destroy(m);
}

static void test_empty_and_bad_input(void)
{
    fm_error err;
    fm_mesh *m = fm_mesh_create();
    fm_mesh_add_vertex(m, 1, 2, 3); /* unreferenced */
    fm_closest_tree *t = fm_closest_tree_create(m, &err);
    CHECK(t != NULL);
    fm_closest_hit h;
    CHECK_EQ(fm_closest_query(t, (double[3]){1, 2, 3}, INFINITY, &h), 0);
    size_t n = 7;
    int32_t *out = (int32_t *)&n;
    CHECK(fm_closest_tree_box_collect(t, (double[3]){-1e9, -1e9, -1e9},
                                      (double[3]){1e9, 1e9, 1e9}, &out, &n, NULL) == FM_OK);
    CHECK(n == 0 && out == NULL);
    CHECK_EQ(fm_closest_tree_ntriangles(t), 0);
    fm_closest_tree_destroy(t);
    fm_closest_tree_destroy(NULL);

    fm_mesh_add_vertex(m, 4, 5, 6);
    fm_mesh_add_vertex(m, 7, 8, 10);
    fm_mesh_add_triangle(m, 0, 1, 2, 0);
    t = fm_closest_tree_create(m, &err);
    CHECK(t != NULL);
    /* Bounds and non-finite arguments. */
    /* (0, 1, 2) lies in the region of corner (1, 2, 3), sqrt(3) away. */
    CHECK_EQ(fm_closest_query(t, (double[3]){0, 1, 2}, 1.75, &h), 1);
    CHECK_NEAR(h.dist, sqrt(3.0), 1e-15);
    CHECK_EQ(h.triangle, 0);
    CHECK(h.bary[0] == 1 && h.foot[0] == 1 && h.foot[1] == 2 && h.foot[2] == 3);
    CHECK_EQ(fm_closest_query(t, (double[3]){0, 1, 2}, 1.7, &h), 0);
    CHECK_EQ(fm_closest_query(t, (double[3]){0, 1, 2}, -1.0, &h), 0);
    CHECK_EQ(fm_closest_query(t, (double[3]){0, 1, 2}, NAN, &h), 0);
    CHECK_EQ(fm_closest_query(t, (double[3]){NAN, 1, 2}, INFINITY, &h), 0);
    CHECK_EQ(fm_closest_query(t, (double[3]){4, 5, 6}, 0.0, &h), 1);
    CHECK_EQ(fm_closest_query(t, (double[3]){4, 5, 6}, INFINITY, NULL), 1);
    fm_closest_tree_destroy(t);

    fm_mesh_add_triangle(m, 0, 1, 3, 0);
    CHECK(fm_closest_tree_create(m, &err) == NULL);
    CHECK_EQ(err.code, FM_ERR_INVALID);
    CHECK(strstr(err.message, "triangle 1") != NULL);
    fm_mesh_truncate(m, 3, 1);
    fm_mesh_vertices_mut(m)[4] = NAN;
    CHECK(fm_closest_tree_create(m, &err) == NULL);
    CHECK_EQ(err.code, FM_ERR_NUMERIC);
    CHECK(fm_closest_tree_create(NULL, &err) == NULL);
    CHECK_EQ(err.code, FM_ERR_INVALID);
    fm_mesh_destroy(m);
}

/* Many triangles with one centroid (a fan of slivers through one point)
 * cannot be split by position; the build must still end with small leaves
 * and answer correctly. */
static void test_coincident_centroids(void)
{
    fm_mesh *m = fm_mesh_create();
    for (int i = 0; i < 300; i++) {
        double ang = i * 0.01;
        double d[3] = {100 * cos(ang), 100 * sin(ang), 0};
        double a[3] = {utm[0] - d[0], utm[1] - d[1], utm[2]};
        double b[3] = {utm[0] + d[0], utm[1] + d[1], utm[2]};
        add_tri(m, a, b, utm);
    }
    compare(m, 500, 9);
    fm_mesh_destroy(m);
}

/* Triangles ever smaller and closer together (gaps shrinking by 0.8): a
 * strongly graded distribution, as refined meshes have, for the binning. */
static void test_skewed(void)
{
    fm_mesh *m = fm_mesh_create();
    for (int i = 0; i < 150; i++) {
        double g = 2000 * pow(0.8, i), x = utm[0] + 1e4 - 5 * g;
        add_tri(m, (double[3]){x, utm[1], utm[2]}, (double[3]){x + 0.1 * g, utm[1] + g, utm[2]},
                (double[3]){x, utm[1] + 0.5 * g, utm[2] + g});
    }
    compare(m, 1000, 14);
    fm_mesh_destroy(m);
}

/* The quick build gives another tree over the same mesh, never other
 * answers: closest queries bit for bit, box queries the same triangles;
 * fm_closest_within says what the closest query says, whatever its hint. */
static void same_answers(fm_mesh *m, size_t nq, uint64_t seed)
{
    fm_closest_tree *t1 = fm_closest_tree_create(m, NULL);
    fm_closest_tree *t2 = fm_closest_tree_create_quick(m, NULL);
    CHECK(t1 && t2);
    CHECK_EQ(fm_closest_tree_ntriangles(t2), fm_mesh_ntriangles(m));
    rng_seed(seed);
    size_t differ = 0, boxes_differ = 0, within_differ = 0;
    int32_t hint = -1;
    for (size_t q = 0; q < nq && t1 && t2; q++) {
        double p[3];
        query_point(m, p);
        fm_closest_hit h1, h2;
        memset(&h1, 0, sizeof h1);
        memset(&h2, 0, sizeof h2);
        double bound = q % 3 == 0 ? INFINITY : pow(10.0, rnd_range(-3, 3));
        int f1 = fm_closest_query(t1, p, bound, &h1);
        int f2 = fm_closest_query(t2, p, bound, &h2);
        differ += f1 != f2 || memcmp(&h1, &h2, sizeof h1) != 0;
        /* within: the same yes or no, with and without a hint, on both trees */
        within_differ += fm_closest_within(t1, p, bound, NULL) != f1;
        within_differ += fm_closest_within(t2, p, bound, &hint) != f1;
        double lo[3], hi[3], size = pow(10.0, rnd_range(-2, 3));
        for (int k = 0; k < 3; k++) {
            lo[k] = p[k] - size * rnd_unit();
            hi[k] = p[k] + size * rnd_unit();
        }
        int32_t *g1 = NULL, *g2 = NULL;
        size_t n1 = 0, n2 = 0;
        CHECK(fm_closest_tree_box_collect(t1, lo, hi, &g1, &n1, NULL) == FM_OK);
        CHECK(fm_closest_tree_box_collect(t2, lo, hi, &g2, &n2, NULL) == FM_OK);
        boxes_differ += n1 != n2 || (n1 && memcmp(g1, g2, n1 * sizeof *g1) != 0);
        CHECK_EQ(fm_closest_tree_box_query(t2, lo, hi, NULL, NULL), n1);
        free(g1);
        free(g2);
    }
    CHECK_EQ(differ, 0);
    CHECK_EQ(boxes_differ, 0);
    CHECK_EQ(within_differ, 0);
    fm_closest_tree_destroy(t1);
    fm_closest_tree_destroy(t2);
    fm_mesh_destroy(m);
}

static void test_quick(void)
{
    rng_seed(15);
    same_answers(soup(4000, utm), 4000, 16);
    rng_seed(17);
    same_answers(wavy(120, 90, utm, 50), 4000, 18);
    fm_mesh *fan = fm_mesh_create(); /* one centroid: nothing to sort by */
    for (int i = 0; i < 300; i++) {
        double d[3] = {100 * cos(i * 0.01), 100 * sin(i * 0.01), 0};
        add_tri(fan, (double[3]){utm[0] - d[0], utm[1] - d[1], utm[2]},
                (double[3]){utm[0] + d[0], utm[1] + d[1], utm[2]}, utm);
    }
    same_answers(fan, 1000, 19);
    fm_mesh *one = fm_mesh_create();
    add_tri(one, utm, (double[3]){utm[0] + 10, utm[1], utm[2]},
            (double[3]){utm[0], utm[1] + 10, utm[2]});
    same_answers(one, 200, 20);
    fm_mesh *none = fm_mesh_create();
    fm_closest_tree *t = fm_closest_tree_create_quick(none, NULL);
    CHECK(t && fm_closest_tree_ntriangles(t) == 0 && !fm_closest_query(t, utm, INFINITY, NULL));
    fm_closest_tree_destroy(t);
    fm_mesh_destroy(none);
    CHECK(fm_closest_tree_create_quick(NULL, NULL) == NULL);
    /* within on bad input, and a hint that names no triangle */
    fm_mesh *m = fm_mesh_create();
    add_tri(m, utm, (double[3]){utm[0] + 10, utm[1], utm[2]},
            (double[3]){utm[0], utm[1] + 10, utm[2]});
    t = fm_closest_tree_create_quick(m, NULL);
    double nan_p[3] = {NAN, utm[1], utm[2]};
    int32_t hint = 1 << 30;
    CHECK(!fm_closest_within(NULL, utm, 1, NULL));
    CHECK(!fm_closest_within(t, nan_p, 1, NULL));
    CHECK(!fm_closest_within(t, utm, -1, NULL));
    CHECK(fm_closest_within(t, utm, 0, &hint) && hint == 0);
    CHECK(!fm_closest_within(t, (double[3]){utm[0], utm[1], utm[2] + 2}, 1.5, &hint));
    CHECK(fm_closest_within(t, (double[3]){utm[0], utm[1], utm[2] + 2}, 2, &hint));
    fm_closest_tree_destroy(t);
    fm_mesh_destroy(m);
}

/* A tree of part of a mesh answers as the whole mesh's tree wherever the
 * answer lies in the part: all triangles in reverse order, and per query
 * only the triangles whose boxes come within the bound. */
static void test_part(void)
{
    rng_seed(21);
    fm_mesh *m = wavy(60, 50, utm, 40);
    size_t nt = fm_mesh_ntriangles(m);
    const double *v = fm_mesh_vertices(m);
    const int32_t *tri = fm_mesh_triangles(m);
    int32_t *part = malloc(nt * sizeof *part);
    for (size_t i = 0; i < nt; i++)
        part[i] = (int32_t)(nt - 1 - i);
    fm_closest_tree *whole = fm_closest_tree_create(m, NULL);
    fm_closest_tree *rev = fm_closest_tree_create_part(m, part, nt, NULL);
    CHECK(whole && rev);
    size_t differ = 0, nonempty = 0;
    for (int q = 0; q < 2000 && whole && rev; q++) {
        double p[3];
        query_point(m, p);
        double bound = q % 4 == 0 ? INFINITY : pow(10.0, rnd_range(-1, 2.5));
        fm_closest_hit h1, h2, h3;
        memset(&h1, 0, sizeof h1);
        memset(&h2, 0, sizeof h2);
        memset(&h3, 0, sizeof h3);
        int f1 = fm_closest_query(whole, p, bound, &h1);
        int f2 = fm_closest_query(rev, p, bound, &h2);
        differ += f1 != f2 || memcmp(&h1, &h2, sizeof h1) != 0;
        if (!isfinite(bound))
            continue;
        size_t n = 0;
        for (size_t i = 0; i < nt; i++) {
            int in = 1;
            for (int k = 0; k < 3; k++) {
                double a = v[3 * tri[3 * i] + k], b = v[3 * tri[3 * i + 1] + k],
                       c = v[3 * tri[3 * i + 2] + k];
                in &= fmin(a, fmin(b, c)) <= p[k] + bound + 1 &&
                      fmax(a, fmax(b, c)) >= p[k] - bound - 1;
            }
            if (in)
                part[n++] = (int32_t)i;
        }
        nonempty += n > 0;
        fm_closest_tree *local = fm_closest_tree_create_part(m, part, n, NULL);
        CHECK(local != NULL);
        int f3 = fm_closest_query(local, p, bound, &h3);
        differ += f1 != f3 || memcmp(&h1, &h3, sizeof h1) != 0;
        differ += fm_closest_within(local, p, bound, NULL) != f1;
        fm_closest_tree_destroy(local);
    }
    CHECK_EQ(differ, 0);
    CHECK(nonempty > 100);
    fm_error err;
    part[0] = (int32_t)nt;
    CHECK(fm_closest_tree_create_part(m, part, 1, &err) == NULL && err.code == FM_ERR_INVALID);
    CHECK(fm_closest_tree_create_part(m, NULL, 1, &err) == NULL && err.code == FM_ERR_INVALID);
    fm_closest_tree *none = fm_closest_tree_create_part(m, NULL, 0, NULL);
    CHECK(none && fm_closest_tree_ntriangles(none) == 0);
    CHECK(!fm_closest_query(none, utm, INFINITY, NULL));
    fm_closest_tree_destroy(none);
    fm_closest_tree_destroy(whole);
    fm_closest_tree_destroy(rev);
    free(part);
    fm_mesh_destroy(m);
}

static void report(void)
{
    printf("worst error / tolerance: %.3g\n", worst_rel);
    CHECK(worst_rel <= 1);
}

FM_TEST_MAIN(FM_CASE(test_on_triangle), FM_CASE(test_soup_utm), FM_CASE(test_soup_origin),
             FM_CASE(test_wavy_utm), FM_CASE(test_tiny_meshes), FM_CASE(test_coincident_centroids), FM_CASE(test_skewed),
             FM_CASE(test_ties), FM_CASE(test_exact_ties), FM_CASE(test_determinism), FM_CASE(test_box),
             FM_CASE(test_quick), FM_CASE(test_part), FM_CASE(test_empty_and_bad_input),
             FM_CASE(report))
