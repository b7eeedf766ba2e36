/* Repair: splitting branching surfaces into sheets, junction curves, pinch
 * vertices, determinism and robustness on random soups. */
#include <stdint.h>

#include "test_repair_util.h"

static const double O[3] = {0, 0, 0}, EX[3] = {1, 0, 0}, EY[3] = {0, 1, 0}, EZ[3] = {0, 0, 1};

static void check_junction_line(const fm_surface *s, size_t j, size_t npoints, double x0,
                                double y, double z)
{
    size_t n = 0;
    const double *p = fm_surface_junction_points(s, j, &n);
    CHECK_EQ(n, npoints);
    for (size_t i = 0; i < n && i < npoints; i++) {
        CHECK_NEAR(p[3 * i], x0 + (double)i, 0);
        CHECK_NEAR(p[3 * i + 1], y, 0);
        CHECK_NEAR(p[3 * i + 2], z, 0);
    }
}

/* A main sheet with a splay branching off along y = 1 (a Y in section). */
static fm_mesh *splay_mesh(void)
{
    fm_mesh *m = fm_mesh_create();
    grid(m, 4, 2, O, EX, EY, 0, NULL);
    double p[3] = {0, 1, 0}, dv[3] = {0, 1, 1};
    grid(m, 4, 2, p, EX, dv, 1, NULL);
    return m;
}

static void test_splay(void)
{
    fm_mesh *m = splay_mesh();
    fm_surface *s = repair_default(m);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->welded_exact, 5);
    CHECK_EQ(r->components, 1);
    CHECK_EQ(r->nonmanifold_edges, 4);
    CHECK_EQ(r->nonmanifold_vertices, 0);
    CHECK_EQ(r->sheets, 2);
    CHECK_EQ(r->junctions, 1);
    CHECK_EQ(r->vertices_out, 30);
    CHECK_EQ(r->boundary_loops, 2);
    CHECK_EQ(r->holes, 0);
    /* The main sheet stays whole: its loop is the 4 x 2 perimeter. */
    CHECK_EQ(fm_mesh_ntriangles(fm_surface_sheet_mesh(s, 0)), 16);
    CHECK_EQ(fm_mesh_tags(fm_surface_sheet_mesh(s, 0))[15], 0);
    CHECK_EQ(fm_mesh_ntriangles(fm_surface_sheet_mesh(s, 1)), 16);
    CHECK_EQ(fm_mesh_tags(fm_surface_sheet_mesh(s, 1))[0], 1);
    CHECK_EQ(loop_len(s, 0, 0), 12);
    CHECK_EQ(loop_len(s, 1, 0), 12);
    double n[3];
    fm_surface_sheet_normal(s, 1, n);
    CHECK_NEAR(n[1], -sqrt(0.5), 1e-12);
    CHECK_NEAR(n[2], sqrt(0.5), 1e-12);
    check_junction_line(s, 0, 5, 0, 1, 0);
    CHECK_EQ(fm_surface_junction_closed(s, 0), 0);
    size_t ns = 0, nv = 0;
    const int32_t *js = fm_surface_junction_sheets(s, 0, &ns);
    CHECK_EQ(ns, 2);
    CHECK_EQ(js[0], 0);
    CHECK_EQ(js[1], 1);
    const int32_t *jv = fm_surface_junction_vertex_origin(s, 0, &nv);
    CHECK_EQ(nv, 5);
    CHECK_EQ(jv[0], 5);
    CHECK_EQ(jv[4], 9);
    check_sheets(s, 1);
    fm_surface_destroy(s);

    /* Without splitting: one sheet through everything, junctions kept. */
    fm_repair_options opt;
    fm_repair_options_default(&opt);
    opt.split_nonmanifold = 0;
    s = repair_with(m, &opt);
    r = fm_surface_report(s);
    CHECK_EQ(r->sheets, 1);
    CHECK_EQ(r->nonmanifold_edges, 4);
    CHECK_EQ(r->vertices_out, 25);
    CHECK_EQ(r->triangles_out, 32);
    CHECK_EQ(r->junctions, 1);
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

/* Two planes crossing, given as four half-sheets with their own vertices,
 * interleaved: the flat pairs are found again. */
static void test_cross(void)
{
    fm_mesh *m = fm_mesh_create();
    double a_left[3] = {0, -2, 0}, b_low[3] = {0, 0, -2};
    grid(m, 4, 2, a_left, EX, EY, 0, NULL);
    grid(m, 4, 2, b_low, EX, EZ, 1, NULL);
    grid(m, 4, 2, O, EX, EY, 2, NULL);
    grid(m, 4, 2, O, EX, EZ, 3, NULL);
    fm_surface *s = repair_default(m);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->welded_exact, 15);
    CHECK_EQ(r->nonmanifold_edges, 4);
    CHECK_EQ(r->sheets, 2);
    CHECK_EQ(r->junctions, 1);
    CHECK_EQ(r->vertices_out, 50);
    for (size_t k = 0; k < 2; k++) {
        const int32_t *tags = fm_mesh_tags(fm_surface_sheet_mesh(s, k));
        CHECK_EQ(fm_mesh_ntriangles(fm_surface_sheet_mesh(s, k)), 32);
        CHECK_EQ(tags[0], (int32_t)k);
        CHECK_EQ(tags[31], (int32_t)k + 2);
        CHECK_EQ(fm_surface_sheet_nloops(s, k), 1);
        CHECK_EQ(loop_len(s, k, 0), 16);
    }
    double n[3];
    fm_surface_sheet_normal(s, 0, n);
    CHECK_NEAR(n[2], 1, 1e-12);
    fm_surface_sheet_normal(s, 1, n);
    CHECK_NEAR(n[1], -1, 1e-12);
    check_junction_line(s, 0, 5, 0, 0, 0);
    size_t ns = 0;
    fm_surface_junction_sheets(s, 0, &ns);
    CHECK_EQ(ns, 2);
    check_sheets(s, 1);
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

/* Eight half-planes around one edge pair into four sheets. */
static void test_fan_of_eight(void)
{
    fm_mesh *m = fm_mesh_create();
    int32_t a = fm_mesh_add_vertex(m, 0, 0, 0), b = fm_mesh_add_vertex(m, 1, 0, 0);
    for (int k = 0; k < 8; k++) {
        /* Shuffled order so that pairs are not neighbours in the input. */
        int q = (k * 3) % 8;
        double ang = q * 3.14159265358979323846 / 4;
        int32_t c = fm_mesh_add_vertex(m, 0.5, 10 * cos(ang), 10 * sin(ang));
        fm_mesh_add_triangle(m, a, b, c, q);
    }
    fm_surface *s = repair_default(m);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->nonmanifold_edges, 1);
    CHECK_EQ(r->sheets, 4);
    CHECK_EQ(r->junctions, 1);
    for (size_t k = 0; k < fm_surface_nsheets(s); k++) {
        const int32_t *tags = fm_mesh_tags(fm_surface_sheet_mesh(s, k));
        CHECK_EQ(fm_mesh_ntriangles(fm_surface_sheet_mesh(s, k)), 2);
        CHECK_EQ((tags[0] + 4) % 8, tags[1]);
    }
    size_t np = 0, ns = 0;
    fm_surface_junction_points(s, 0, &np);
    fm_surface_junction_sheets(s, 0, &ns);
    CHECK_EQ(np, 2);
    CHECK_EQ(ns, 4);
    check_sheets(s, 1);
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

static int skip_diagonal(int i, int j)
{
    return (i == 2 && j == 1) || (i == 1 && j == 2);
}

/* A sheet pinched at vertex (2, 2): two fans meeting at one vertex. */
static void test_pinch(void)
{
    fm_mesh *m = fm_mesh_create();
    grid(m, 4, 4, O, EX, EY, 0, skip_diagonal);
    fm_surface *s = repair_default(m);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->components, 1);
    CHECK_EQ(r->sheets, 1);
    CHECK_EQ(r->nonmanifold_vertices, 1);
    CHECK_EQ(r->vertices_out, 26);
    CHECK_EQ(r->boundary_loops, 2);
    CHECK_EQ(r->holes, 1);
    long outer = fm_surface_sheet_outer_loop(s, 0);
    size_t hole = outer == 0 ? 1 : 0;
    CHECK_EQ(loop_len(s, 0, (size_t)outer), 16);
    CHECK_EQ(loop_len(s, 0, hole), 8);
    CHECK_NEAR(loop_area_z(s, 0, hole), -2, 1e-12);
    const int32_t *vo = fm_surface_sheet_vertex_origin(s, 0);
    int copies = 0;
    for (size_t v = 0; v < 26; v++)
        copies += vo[v] == 12;
    CHECK_EQ(copies, 2);
    check_sheets(s, 1);
    fm_surface_destroy(s);

    /* Touching at a vertex only across components is no pinch. */
    fm_mesh *t = fm_mesh_create();
    grid(t, 2, 2, O, EX, EY, 0, NULL);
    double p[3] = {2, 2, 0};
    grid(t, 2, 2, p, EX, EY, 1, NULL);
    s = repair_default(t);
    CHECK_EQ(fm_surface_report(s)->sheets, 2);
    CHECK_EQ(fm_surface_report(s)->nonmanifold_vertices, 0);
    check_sheets(s, 1);
    fm_surface_destroy(s);
    fm_mesh_destroy(t);
    fm_mesh_destroy(m);
}

/* A square tube through a plane: a closed junction; the tube is a sheet
 * with two loops and no net normal. */
static void test_closed_junction(void)
{
    fm_mesh *m = fm_mesh_create();
    double p0[3] = {-2, -2, 0};
    grid(m, 4, 4, p0, EX, EY, 0, NULL);
    double c[4][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}};
    double d[4][3] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    for (int k = 0; k < 4; k++)
        grid(m, 2, 2, c[k], d[k], EZ, 1, NULL);
    fm_surface *s = repair_default(m);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->nonmanifold_edges, 8);
    CHECK_EQ(r->sheets, 2);
    CHECK_EQ(r->junctions, 1);
    CHECK_EQ(r->boundary_loops, 3);
    CHECK_EQ(r->holes, 1);
    CHECK_EQ(r->triangles_flipped, 0);
    CHECK_EQ(fm_surface_junction_closed(s, 0), 1);
    size_t np = 0;
    const double *pts = fm_surface_junction_points(s, 0, &np);
    CHECK_EQ(np, 8);
    for (size_t i = 0; i < np; i++) {
        CHECK_NEAR(pts[3 * i + 2], 0, 0);
        CHECK(fabs(pts[3 * i]) == 1 || fabs(pts[3 * i + 1]) == 1);
    }
    CHECK_EQ(fm_mesh_ntriangles(fm_surface_sheet_mesh(s, 1)), 32);
    CHECK_EQ(fm_surface_sheet_nloops(s, 1), 2);
    CHECK_EQ(loop_len(s, 1, 0), 8);
    double n[3];
    fm_surface_sheet_normal(s, 1, n);
    CHECK(n[0] == 0 && n[1] == 0 && n[2] == 0);
    check_sheets(s, 1);
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

/* A closed box: no boundary, outer loop -1. */
static void test_closed_sheet(void)
{
    fm_mesh *m = fm_mesh_create();
    double v[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                      {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (int i = 0; i < 8; i++)
        fm_mesh_add_vertex(m, v[i][0], v[i][1], v[i][2]);
    int32_t q[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                       {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    for (int f = 0; f < 6; f++) {
        fm_mesh_add_triangle(m, q[f][0], q[f][1], q[f][2], 0);
        fm_mesh_add_triangle(m, q[f][0], q[f][2], q[f][3], 0);
    }
    fm_surface *s = repair_default(m);
    CHECK_EQ(fm_surface_nsheets(s), 1);
    CHECK_EQ(fm_surface_sheet_nloops(s, 0), 0);
    CHECK_EQ(fm_surface_sheet_outer_loop(s, 0), -1);
    CHECK_EQ(fm_surface_report(s)->boundary_loops, 0);
    check_sheets(s, 1);
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

static uint32_t lcg(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return *state >> 8;
}

static int same_surface(const fm_surface *a, const fm_surface *b)
{
    if (memcmp(fm_surface_report(a), fm_surface_report(b), sizeof(fm_repair_report)) != 0 ||
        fm_surface_nsheets(a) != fm_surface_nsheets(b) ||
        fm_surface_njunctions(a) != fm_surface_njunctions(b))
        return 0;
    for (size_t k = 0; k < fm_surface_nsheets(a); k++) {
        const fm_mesh *ma = fm_surface_sheet_mesh(a, k), *mb = fm_surface_sheet_mesh(b, k);
        size_t nv = fm_mesh_nvertices(ma), nt = fm_mesh_ntriangles(ma);
        if (nv != fm_mesh_nvertices(mb) || nt != fm_mesh_ntriangles(mb) ||
            memcmp(fm_mesh_vertices(ma), fm_mesh_vertices(mb), 3 * nv * sizeof(double)) ||
            memcmp(fm_mesh_triangles(ma), fm_mesh_triangles(mb), 3 * nt * sizeof(int32_t)) ||
            fm_surface_sheet_nloops(a, k) != fm_surface_sheet_nloops(b, k) ||
            fm_surface_sheet_outer_loop(a, k) != fm_surface_sheet_outer_loop(b, k))
            return 0;
        for (size_t l = 0; l < fm_surface_sheet_nloops(a, k); l++) {
            size_t na, nb;
            const int32_t *la = fm_surface_sheet_loop(a, k, l, &na);
            const int32_t *lb = fm_surface_sheet_loop(b, k, l, &nb);
            if (na != nb || memcmp(la, lb, na * sizeof *la))
                return 0;
        }
    }
    for (size_t j = 0; j < fm_surface_njunctions(a); j++) {
        size_t na, nb;
        const double *pa = fm_surface_junction_points(a, j, &na);
        const double *pb = fm_surface_junction_points(b, j, &nb);
        if (na != nb || memcmp(pa, pb, 3 * na * sizeof *pa))
            return 0;
    }
    return 1;
}

/* Random soups on a small lattice: coincident vertices, degenerate and
 * duplicate triangles, fans of many triangles on one edge, pinches. The
 * repair must not fail, must account for every triangle, must produce
 * edge-manifold sheets, and must give the same result twice. */
static void test_random_soups(void)
{
    uint32_t seed = 12345;
    for (int iter = 0; iter < 1000; iter++) {
        fm_mesh *m = fm_mesh_create();
        int nv = 4 + (int)(lcg(&seed) % 40), nt = (int)(lcg(&seed) % 90);
        for (int i = 0; i < nv; i++)
            fm_mesh_add_vertex(m, (double)(lcg(&seed) % 3), (double)(lcg(&seed) % 3),
                               (double)(lcg(&seed) % 2));
        for (int i = 0; i < nt; i++)
            fm_mesh_add_triangle(m, (int32_t)(lcg(&seed) % (uint32_t)nv),
                                 (int32_t)(lcg(&seed) % (uint32_t)nv),
                                 (int32_t)(lcg(&seed) % (uint32_t)nv), i % 3);
        fm_repair_options opt;
        fm_repair_options_default(&opt);
        opt.split_nonmanifold = iter % 5 != 4;
        opt.weld_tolerance = iter % 7 == 3 ? 1.0 : 0.0;
        opt.min_fragment_triangles = 3;
        fm_surface *s = repair_with(m, &opt), *s2 = repair_with(m, &opt);
        if (!s || !s2) {
            fm_surface_destroy(s);
            fm_surface_destroy(s2);
            fm_mesh_destroy(m);
            continue;
        }
        const fm_repair_report *r = fm_surface_report(s);
        CHECK_EQ(r->triangles_out + r->degenerate_removed + r->duplicates_removed +
                     r->fragment_triangles_dropped,
                 (size_t)nt);
        CHECK_EQ(r->sheets, fm_surface_nsheets(s));
        size_t tri = 0, loops = 0;
        for (size_t k = 0; k < fm_surface_nsheets(s); k++) {
            tri += fm_mesh_ntriangles(fm_surface_sheet_mesh(s, k));
            loops += fm_surface_sheet_nloops(s, k);
        }
        CHECK_EQ(tri, r->triangles_out);
        CHECK_EQ(loops, r->boundary_loops);
        if (opt.split_nonmanifold)
            check_sheets(s, r->nonorientable_sheets == 0);
        CHECK(same_surface(s, s2));
        fm_surface_destroy(s);
        fm_surface_destroy(s2);
        fm_mesh_destroy(m);
    }
}

/* A large seamed grid: counts are exact and the run is quick. */
static void test_large_grid(void)
{
    fm_mesh *m = fm_mesh_create();
    const int n = 300, parts = 3, w = n / parts;
    for (int p = 0; p < parts; p++) {
        double p0[3] = {500000.0 + 10.0 * w * p, 3.7e6, -1000}, du[3] = {10, 0, 0},
               dv[3] = {0, 10, 1};
        grid(m, w, n, p0, du, dv, p, NULL);
    }
    fm_surface *s = repair_default(m);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->welded_exact, (size_t)(parts - 1) * (n + 1));
    CHECK_EQ(r->sheets, 1);
    CHECK_EQ(r->vertices_out, (size_t)(n + 1) * (n + 1));
    CHECK_EQ(r->triangles_out, 2 * (size_t)n * n);
    CHECK_EQ(r->boundary_loops, 1);
    CHECK_EQ(loop_len(s, 0, 0), 4 * (size_t)n);
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

FM_TEST_MAIN(FM_CASE(test_splay), FM_CASE(test_cross), FM_CASE(test_fan_of_eight),
             FM_CASE(test_pinch), FM_CASE(test_closed_junction), FM_CASE(test_closed_sheet),
             FM_CASE(test_random_soups), FM_CASE(test_large_grid))
