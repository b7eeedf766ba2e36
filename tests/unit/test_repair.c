/* Repair: welding, cleaning, fragments, loops and orientation on small
 * meshes built in code. Branching surfaces are in test_repair_sheets.c. */
#include "repair_internal.h" /* to check the weld against brute force */
#include "test_repair_util.h"

static const double O[3] = {0, 0, 0}, EX[3] = {1, 0, 0}, EY[3] = {0, 1, 0}, EZ[3] = {0, 0, 1};

static void test_empty(void)
{
    fm_mesh *m = fm_mesh_create();
    fm_surface *s = repair_default(m);
    CHECK(s != NULL);
    CHECK_EQ(fm_surface_nsheets(s), 0);
    CHECK_EQ(fm_surface_njunctions(s), 0);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->vertices_in, 0);
    CHECK_EQ(r->triangles_out, 0);
    CHECK_EQ(r->sheets, 0);
    CHECK(fm_surface_sheet_mesh(s, 0) == NULL);
    CHECK_EQ(fm_surface_sheet_outer_loop(s, 0), -1);
    fm_surface_destroy(s);

    /* Vertices but no triangles: all unused. */
    fm_mesh_add_vertex(m, 0, 0, 0);
    fm_mesh_add_vertex(m, 0, 0, 0);
    fm_mesh_add_vertex(m, 1, 0, 0);
    s = repair_default(m);
    CHECK_EQ(fm_surface_report(s)->welded_exact, 1);
    CHECK_EQ(fm_surface_report(s)->unused_vertices, 2);
    CHECK_EQ(fm_surface_nsheets(s), 0);
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

static void test_all_degenerate(void)
{
    fm_mesh *m = fm_mesh_create();
    fm_mesh_add_vertex(m, 0, 0, 0);
    fm_mesh_add_vertex(m, 1, 1, 1);
    fm_mesh_add_vertex(m, 2, 2, 2);
    fm_mesh_add_triangle(m, 0, 1, 2, 0); /* collinear */
    fm_mesh_add_triangle(m, 0, 0, 1, 0); /* repeated */
    fm_surface *s = repair_default(m);
    CHECK_EQ(fm_surface_nsheets(s), 0);
    CHECK_EQ(fm_surface_report(s)->degenerate_removed, 2);
    CHECK_EQ(fm_surface_report(s)->unused_vertices, 3);
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

/* Two parts of a 4x4 grid, each with its own copy of the seam vertices
 * (as CFM files store former part borders), plus an ATOM-like copy. */
static void test_grid_seam(void)
{
    fm_mesh *m = fm_mesh_create();
    grid(m, 2, 4, O, EX, EY, 0, NULL);
    double p1[3] = {2, 0, 0};
    grid(m, 2, 4, p1, EX, EY, 1, NULL);
    /* An extra copy of vertex 0 used by one triangle in place of vertex 0;
     * -0.0 must weld with 0.0. */
    int32_t copy = fm_mesh_add_vertex(m, -0.0, 0, -0.0);
    fm_mesh_triangles_mut(m)[0] = copy;
    fm_surface *s = repair_default(m);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->vertices_in, 31);
    CHECK_EQ(r->welded_exact, 6);
    CHECK_EQ(r->welded_tolerance, 0);
    CHECK_EQ(r->unused_vertices, 0);
    CHECK_EQ(r->components, 1);
    CHECK_EQ(r->sheets, 1);
    CHECK_EQ(r->vertices_out, 25);
    CHECK_EQ(r->triangles_out, 32);
    CHECK_EQ(r->triangles_flipped, 0);
    CHECK_EQ(r->boundary_loops, 1);
    CHECK_EQ(r->holes, 0);
    CHECK_EQ(fm_surface_nsheets(s), 1);
    CHECK_EQ(loop_len(s, 0, 0), 16);
    CHECK(loop_area_z(s, 0, 0) > 0);
    double n[3];
    fm_surface_sheet_normal(s, 0, n);
    CHECK_NEAR(n[2], 1.0, 1e-12);
    /* Origins: sheet vertex 0 is input vertex 0 (lowest of its group). */
    const int32_t *vo = fm_surface_sheet_vertex_origin(s, 0);
    CHECK_EQ(vo[0], 0);
    const int32_t *to = fm_surface_sheet_triangle_origin(s, 0);
    CHECK_EQ(to[31], 31);
    /* Tags kept. */
    const int32_t *tags = fm_mesh_tags(fm_surface_sheet_mesh(s, 0));
    CHECK_EQ(tags[0], 0);
    CHECK_EQ(tags[31], 1);
    check_sheets(s, 1);
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

static int skip_center(int i, int j)
{
    return (i == 1 || i == 2) && (j == 1 || j == 2);
}

static void test_hole(void)
{
    fm_mesh *m = fm_mesh_create();
    grid(m, 4, 4, O, EX, EY, 0, skip_center);
    fm_surface *s = repair_default(m);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->sheets, 1);
    CHECK_EQ(r->boundary_loops, 2);
    CHECK_EQ(r->holes, 1);
    CHECK_EQ(r->unused_vertices, 1); /* the centre vertex */
    CHECK_EQ(r->vertices_out, 24);
    CHECK_EQ(fm_surface_sheet_nloops(s, 0), 2);
    long outer = fm_surface_sheet_outer_loop(s, 0);
    CHECK(outer == 0 || outer == 1);
    size_t hole = outer == 0 ? 1 : 0;
    CHECK_EQ(loop_len(s, 0, (size_t)outer), 16);
    CHECK_EQ(loop_len(s, 0, hole), 8);
    /* Sheet on the left: the outer loop runs counter-clockwise seen from
     * the (upward) normal, the hole clockwise. */
    CHECK_NEAR(loop_area_z(s, 0, (size_t)outer), 16.0, 1e-12);
    CHECK_NEAR(loop_area_z(s, 0, hole), -4.0, 1e-12);
    check_sheets(s, 1);
    fm_surface_destroy(s);

    /* Same mesh facing down: oriented up, the same loops come out. */
    int32_t *t = fm_mesh_triangles_mut(m);
    for (size_t i = 0; i < fm_mesh_ntriangles(m); i++) {
        int32_t x = t[3 * i + 1];
        t[3 * i + 1] = t[3 * i + 2];
        t[3 * i + 2] = x;
    }
    s = repair_default(m);
    CHECK_EQ(fm_surface_report(s)->triangles_flipped, fm_mesh_ntriangles(m));
    outer = fm_surface_sheet_outer_loop(s, 0);
    CHECK_NEAR(loop_area_z(s, 0, (size_t)outer), 16.0, 1e-12);
    check_sheets(s, 1);
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

static void test_degenerate_and_duplicates(void)
{
    fm_mesh *m = fm_mesh_create();
    grid(m, 4, 4, O, EX, EY, 0, NULL); /* 32 triangles, vertices 0..24 */
    int32_t far = fm_mesh_add_vertex(m, 2, 0, 0);     /* copy of vertex 2 */
    fm_mesh_add_triangle(m, 0, 1, 2, 5);              /* collinear (y = 0) */
    fm_mesh_add_triangle(m, 1, far, 2, 5);            /* repeated after welding */
    fm_mesh_add_triangle(m, 3, 3, 7, 5);              /* repeated index */
    fm_mesh_add_triangle(m, 0, 1, 6, 7);              /* duplicate of triangle 0 */
    fm_mesh_add_triangle(m, 0, 6, 1, 7);              /* duplicate, reversed */
    fm_mesh_add_triangle(m, 6, 0, 1, 7);              /* duplicate, rotated */
    fm_surface *s = repair_default(m);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->welded_exact, 1);
    CHECK_EQ(r->degenerate_removed, 3);
    CHECK_EQ(r->duplicates_removed, 3);
    CHECK_EQ(r->triangles_out, 32);
    CHECK_EQ(r->sheets, 1);
    /* The first copy is kept: its tag and origin are those of triangle 0. */
    CHECK_EQ(fm_surface_sheet_triangle_origin(s, 0)[0], 0);
    CHECK_EQ(fm_mesh_tags(fm_surface_sheet_mesh(s, 0))[0], 0);
    check_sheets(s, 1);
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

static void test_fragments(void)
{
    fm_mesh *m = fm_mesh_create();
    grid(m, 4, 4, O, EX, EY, 0, NULL);              /* 32 triangles, area 16 */
    double p1[3] = {10, 0, 0};
    grid(m, 3, 3, p1, EX, EY, 1, NULL);             /* 18 triangles: kept */
    double p2[3] = {20, 0, 0}, s1[3] = {0.001, 0, 0}, s2[3] = {0, 0.001, 0};
    grid(m, 1, 1, p2, s1, s2, 2, NULL);             /* 2 tiny triangles: dropped */
    double p3[3] = {30, 0, 0}, b1[3] = {5, 0, 0}, b2[3] = {0, 5, 0};
    grid(m, 1, 1, p3, b1, b2, 3, NULL);             /* 2 big triangles: kept */
    /* Touching the big grid at one vertex only: its own component. */
    int32_t a = fm_mesh_add_vertex(m, 4.001, 4, 0), b = fm_mesh_add_vertex(m, 4, 4.001, 0);
    fm_mesh_add_triangle(m, 24, a, b, 4);
    fm_surface *s = repair_default(m);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->fragments_dropped, 2);
    CHECK_EQ(r->fragment_triangles_dropped, 3);
    CHECK_EQ(r->components, 3);
    CHECK_EQ(r->sheets, 3);
    CHECK_EQ(r->triangles_out, 52);
    CHECK_EQ(fm_mesh_ntriangles(fm_surface_sheet_mesh(s, 0)), 32);
    CHECK_EQ(fm_mesh_ntriangles(fm_surface_sheet_mesh(s, 1)), 18);
    CHECK_EQ(fm_mesh_ntriangles(fm_surface_sheet_mesh(s, 2)), 2);
    check_sheets(s, 1);
    fm_surface_destroy(s);

    /* Not dropped when dropping is off. */
    fm_repair_options opt;
    fm_repair_options_default(&opt);
    opt.drop_fragments = 0;
    s = repair_with(m, &opt);
    CHECK_EQ(fm_surface_report(s)->fragments_dropped, 0);
    CHECK_EQ(fm_surface_report(s)->components, 5);
    CHECK_EQ(fm_surface_nsheets(s), 5);
    fm_surface_destroy(s);

    /* The largest component is never dropped, however small. */
    fm_mesh *tiny = fm_mesh_create();
    grid(tiny, 1, 1, O, s1, s2, 0, NULL);
    s = repair_default(tiny);
    CHECK_EQ(fm_surface_nsheets(s), 1);
    fm_surface_destroy(s);
    fm_mesh_destroy(tiny);
    fm_mesh_destroy(m);
}

/* Inconsistent orientation is fixed and the normal ends up up. */
static void test_orientation(void)
{
    fm_mesh *m = fm_mesh_create();
    double dv[3] = {0, 1, 0.5}; /* dipping plane, normal (0, -0.5, 1) */
    grid(m, 4, 4, O, EX, dv, 0, NULL);
    int32_t *t = fm_mesh_triangles_mut(m);
    size_t nflip = 0;
    for (size_t i = 0; i < fm_mesh_ntriangles(m); i += 3) {
        int32_t x = t[3 * i + 1];
        t[3 * i + 1] = t[3 * i + 2];
        t[3 * i + 2] = x;
        nflip++;
    }
    fm_surface *s = repair_default(m);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->triangles_flipped, nflip);
    CHECK_EQ(r->nonorientable_sheets, 0);
    double n[3];
    fm_surface_sheet_normal(s, 0, n);
    CHECK_NEAR(n[0], 0, 1e-12);
    CHECK_NEAR(n[1], -0.5 / sqrt(1.25), 1e-12);
    CHECK_NEAR(n[2], 1 / sqrt(1.25), 1e-12);
    check_sheets(s, 1);
    fm_surface_destroy(s);

    /* orient = 0 leaves the triangles as they are. */
    fm_repair_options opt;
    fm_repair_options_default(&opt);
    opt.orient = 0;
    s = repair_with(m, &opt);
    CHECK_EQ(fm_surface_report(s)->triangles_flipped, 0);
    const int32_t *ot = fm_mesh_triangles(fm_surface_sheet_mesh(s, 0));
    const int32_t *ov = fm_surface_sheet_vertex_origin(s, 0);
    CHECK_EQ(ov[ot[1]], 6); /* triangle 0 reversed in the input: (0, 6, 1) */
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

/* Vertical sheets: the normal points to azimuth [90, 270). */
static void test_vertical(void)
{
    struct {
        double du[3];
        double want[3];
    } cases[] = {
        {{0, 1, 0}, {1, 0, 0}},   /* plane x = 0: normal east (90) */
        {{0, -1, 0}, {1, 0, 0}},  /* same plane built the other way */
        {{1, 0, 0}, {0, -1, 0}},  /* plane y = 0: normal south (180) */
        {{-1, 0, 0}, {0, -1, 0}},
        {{1, 1, 0}, {0.70710678118654752, -0.70710678118654752, 0}}, /* 135 */
        {{1, -1, 0}, {-0.70710678118654752, -0.70710678118654752, 0}}, /* 225 */
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        fm_mesh *m = fm_mesh_create();
        grid(m, 3, 3, O, cases[c].du, EZ, 0, NULL);
        fm_surface *s = repair_default(m);
        double n[3];
        fm_surface_sheet_normal(s, 0, n);
        for (int d = 0; d < 3; d++)
            CHECK_NEAR(n[d], cases[c].want[d], 1e-12);
        check_sheets(s, 1);
        fm_surface_destroy(s);
        fm_mesh_destroy(m);
    }
}

static void test_tolerance_weld(void)
{
    fm_mesh *m = fm_mesh_create();
    grid(m, 2, 4, O, EX, EY, 0, NULL);
    double p1[3] = {2.0004, 0.0003, 0};
    grid(m, 2, 4, p1, EX, EY, 1, NULL);
    fm_surface *s = repair_default(m);
    CHECK_EQ(fm_surface_report(s)->welded_exact, 0);
    CHECK_EQ(fm_surface_nsheets(s), 2);
    fm_surface_destroy(s);

    fm_repair_options opt;
    fm_repair_options_default(&opt);
    opt.weld_tolerance = 0.001;
    s = repair_with(m, &opt);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->welded_exact, 0);
    CHECK_EQ(r->welded_tolerance, 5);
    CHECK_EQ(r->sheets, 1);
    CHECK_EQ(r->vertices_out, 25);
    /* Representatives keep the lowest index, hence the first grid's
     * coordinates. */
    const fm_mesh *sm = fm_surface_sheet_mesh(s, 0);
    const int32_t *vo = fm_surface_sheet_vertex_origin(s, 0);
    size_t from_second = 0;
    for (size_t v = 0; v < fm_mesh_nvertices(sm); v++)
        from_second += vo[v] >= 15;
    CHECK_EQ(from_second, 10);
    check_sheets(s, 1);
    fm_surface_destroy(s);

    /* Too small a tolerance merges nothing. */
    opt.weld_tolerance = 0.0004;
    s = repair_with(m, &opt);
    CHECK_EQ(fm_surface_report(s)->welded_tolerance, 0);
    fm_surface_destroy(s);

    /* Chains merge transitively: 0 - 0.6 - 1.2 with tolerance 0.7. */
    fm_mesh *c = fm_mesh_create();
    fm_mesh_add_vertex(c, 0, 0, 0);
    fm_mesh_add_vertex(c, 0.6, 0, 0);
    fm_mesh_add_vertex(c, 1.2, 0, 0);
    fm_mesh_add_vertex(c, 5, 0, 0);
    fm_mesh_add_vertex(c, 5, 5, 0);
    fm_mesh_add_triangle(c, 2, 3, 4, 0);
    opt.weld_tolerance = 0.7;
    s = repair_with(c, &opt);
    CHECK_EQ(fm_surface_report(s)->welded_tolerance, 2);
    CHECK_EQ(fm_surface_sheet_vertex_origin(s, 0)[0], 0);
    fm_surface_destroy(s);
    fm_mesh_destroy(c);
    fm_mesh_destroy(m);
}

static uint32_t lcg(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return *state >> 8;
}

/* The cell pruning of the tolerance weld finds exactly the groups of an
 * all-pairs search: random points at UTM-sized offsets, and lattice points
 * on cell faces at exactly tol from each other (which must merge). */
static void test_tolerance_weld_brute_force(void)
{
    uint32_t seed = 7;
    for (int round = 0; round < 6; round++) {
        size_t n = 1500;
        double tol = round < 3 ? 0.3 : 0.25, off = round % 3 == 0 ? 0 : 3.7e6;
        double *xyz = malloc(3 * n * sizeof *xyz);
        int32_t *rep = malloc(n * sizeof *rep), *parent = malloc(n * sizeof *parent);
        for (size_t i = 0; i < 3 * n; i++) {
            double u = round < 3 ? (double)(lcg(&seed) % 100000) / 10000.0
                                 : 0.25 * (double)(lcg(&seed) % 16);
            xyz[i] = (i % 3 == 1 ? off : 0) + u;
        }
        size_t nw = 0, nt = 0;
        CHECK_EQ(rep_weld_exact(xyz, n, rep, &nw), FM_OK);
        CHECK_EQ(rep_weld_tolerance(xyz, n, tol, rep, &nt, NULL), FM_OK);
        for (size_t i = 0; i < n; i++)
            parent[i] = (int32_t)i;
        for (size_t i = 0; i < n; i++)
            for (size_t j = 0; j < i; j++) {
                double d0 = xyz[3 * i] - xyz[3 * j], d1 = xyz[3 * i + 1] - xyz[3 * j + 1];
                double d2 = xyz[3 * i + 2] - xyz[3 * j + 2];
                if (d0 * d0 + d1 * d1 + d2 * d2 <= tol * tol)
                    uf_union(parent, (int32_t)i, (int32_t)j);
            }
        size_t mismatches = 0, groups = 0;
        for (size_t i = 0; i < n; i++) {
            mismatches += rep[i] != uf_find(parent, (int32_t)i);
            groups += rep[i] == (int32_t)i;
        }
        CHECK_EQ(mismatches, 0);
        CHECK_EQ(nw + nt, n - groups);
        CHECK(nt > 0);
        free(xyz);
        free(rep);
        free(parent);
    }
}

/* A Moebius strip: reported, kept, no crash. */
static void test_mobius(void)
{
    fm_mesh *m = fm_mesh_create();
    const int n = 16;
    for (int i = 0; i < n; i++) {
        double phi = 2 * 3.14159265358979323846 * i / n;
        for (int k = 0; k < 2; k++) {
            double w = k ? 0.5 : -0.5;
            double r = 3 + w * cos(phi / 2);
            fm_mesh_add_vertex(m, r * cos(phi), r * sin(phi), w * sin(phi / 2));
        }
    }
    for (int i = 0; i < n; i++) {
        int32_t a = 2 * i, b = 2 * i + 1, c, d;
        if (i + 1 < n) {
            c = 2 * (i + 1);
            d = c + 1;
        } else { /* the half twist: the strip comes back upside down */
            c = 1;
            d = 0;
        }
        fm_mesh_add_triangle(m, a, c, d, 0);
        fm_mesh_add_triangle(m, a, d, b, 0);
    }
    fm_surface *s = repair_default(m);
    const fm_repair_report *r = fm_surface_report(s);
    CHECK_EQ(r->sheets, 1);
    CHECK_EQ(r->nonorientable_sheets, 1);
    CHECK_EQ(r->triangles_out, 2 * (size_t)n);
    check_sheets(s, 0);
    fm_surface_destroy(s);
    fm_mesh_destroy(m);
}

static void test_invalid_input(void)
{
    fm_mesh *m = fm_mesh_create();
    fm_mesh_add_vertex(m, 0, 0, 0);
    fm_mesh_add_vertex(m, 1, 0, 0);
    fm_mesh_add_vertex(m, 0, 1, 0);
    fm_mesh_add_triangle(m, 0, 1, 3, 0);
    static int dummy;
    fm_surface *s = (fm_surface *)(void *)&dummy; /* must be reset to NULL */
    fm_error err;
    CHECK_EQ(fm_repair(m, NULL, &s, &err), FM_ERR_INVALID);
    CHECK(s == NULL);
    CHECK(strstr(err.message, "triangle 0") != NULL);
    fm_mesh_triangles_mut(m)[2] = 2;
    fm_mesh_vertices_mut(m)[4] = NAN;
    CHECK_EQ(fm_repair(m, NULL, &s, &err), FM_ERR_NUMERIC);
    fm_mesh_vertices_mut(m)[4] = 0;
    fm_repair_options opt;
    fm_repair_options_default(&opt);
    opt.weld_tolerance = -1;
    CHECK_EQ(fm_repair(m, &opt, &s, &err), FM_ERR_INVALID);
    opt.weld_tolerance = 1e-300;
    fm_mesh_vertices_mut(m)[0] = 1e10;
    CHECK_EQ(fm_repair(m, &opt, &s, &err), FM_ERR_INVALID);
    CHECK_EQ(fm_repair(NULL, NULL, &s, NULL), FM_ERR_INVALID);
    CHECK_EQ(fm_repair(m, NULL, NULL, NULL), FM_ERR_INVALID);
    /* Accessors on NULL are total. */
    CHECK_EQ(fm_surface_nsheets(NULL), 0);
    CHECK(fm_surface_report(NULL) == NULL);
    fm_surface_destroy(NULL);
    fm_mesh_destroy(m);
}

FM_TEST_MAIN(FM_CASE(test_empty), FM_CASE(test_all_degenerate), FM_CASE(test_grid_seam),
             FM_CASE(test_hole), FM_CASE(test_degenerate_and_duplicates),
             FM_CASE(test_fragments), FM_CASE(test_orientation), FM_CASE(test_vertical),
             FM_CASE(test_tolerance_weld), FM_CASE(test_tolerance_weld_brute_force),
             FM_CASE(test_mobius), FM_CASE(test_invalid_input))
