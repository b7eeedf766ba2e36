/* The CAD model's pieces: the boundary loops of a mesh in (u, v)
 * (fm_remesh_boundary_of: an annulus, parts touching at a node, a hole
 * touching the outline at a node, a bad mesh) and the IGES faces made
 * from them (fm_cad_face_create / fm_cad_write_iges: loops cut into curves
 * at the corners given, points outside the surface refused, a fixed date
 * without SOURCE_DATE_EPOCH). Gmsh reading whole files is checked by
 * tests/tools/check_cad.py. */
#include "cad_internal.h"
#include "fm_cad_write.h"
#include "fm_fit.h"
#include "fm_mesh.h"
#include "fm_remesh.h"
#include "fm_test.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* The n x n grid of unit cells over [0, n]^2 (z = x + 2 y), two
 * counter-clockwise triangles per cell but for the cells in skip (by
 * index i + n j); uv = (x, y). */
static fm_mesh *grid(int n, const int *skip, int nskip, double **uv)
{
    fm_mesh *m = fm_mesh_create();
    *uv = malloc(2 * (size_t)(n + 1) * (size_t)(n + 1) * sizeof **uv);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            fm_mesh_add_vertex(m, i, j, i + 2.0 * j);
            (*uv)[2 * (j * (n + 1) + i)] = i;
            (*uv)[2 * (j * (n + 1) + i) + 1] = j;
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int skipped = 0;
            for (int k = 0; k < nskip; k++)
                skipped |= skip[k] == i + n * j;
            if (skipped)
                continue;
            int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
            fm_mesh_add_triangle(m, a, b, c, 0);
            fm_mesh_add_triangle(m, a, c, d, 0);
        }
    return m;
}

static double loop_area(const fm_remesh_boundary *b, size_t k)
{
    double s = 0;
    size_t a = b->start[k], n = b->start[k + 1] - a;
    for (size_t i = 0; i < n; i++) {
        const double *p = b->uv + 2 * (a + i), *q = b->uv + 2 * (a + (i + 1) % n);
        s += p[0] * q[1] - q[0] * p[1];
    }
    return s / 2;
}

static void test_annulus(void)
{
    int skip[] = {4}; /* the middle cell of 3 x 3 */
    double *uv;
    fm_mesh *m = grid(3, skip, 1, &uv);
    int64_t ids[16];
    for (int v = 0; v < 16; v++)
        ids[v] = v == 5 ? 42 : -1;
    fm_remesh_boundary b;
    fm_error err;
    CHECK_EQ(fm_remesh_boundary_of(m, uv, ids, &b, &err), FM_OK);
    CHECK_EQ(b.nparts, 1);
    CHECK_EQ(b.nloops, 2);
    if (b.nloops == 2) {
        CHECK_EQ(b.start[1] - b.start[0], 12);
        CHECK_EQ(b.start[2] - b.start[1], 4);
        CHECK_NEAR(loop_area(&b, 0), 9, 1e-12);
        CHECK_NEAR(loop_area(&b, 1), -1, 1e-12);
        int shared = 0;
        for (size_t i = b.start[1]; i < b.start[2]; i++) {
            /* xyz is the mesh's vertex, z = x + 2 y */
            CHECK_NEAR(b.xyz[3 * i + 2], b.uv[2 * i] + 2 * b.uv[2 * i + 1], 0);
            if (b.node[i] == 42) {
                shared++;
                CHECK(b.uv[2 * i] == 1 && b.uv[2 * i + 1] == 1);
            }
        }
        CHECK_EQ(shared, 1);
    }
    fm_remesh_boundary_free(&b);
    free(uv);
    fm_mesh_destroy(m);
}

/* Cells 0 and 4 of 2 x 2... two cells touching at a corner only: two
 * parts, each one outer loop; then a hole touching the outline at a node
 * (3 x 3 without the middle and a corner cell): one part, the node on
 * both loops. */
static void test_pinches(void)
{
    int skip2[] = {1, 2};
    double *uv;
    fm_mesh *m = grid(2, skip2, 2, &uv);
    fm_remesh_boundary b;
    fm_error err;
    CHECK_EQ(fm_remesh_boundary_of(m, uv, NULL, &b, &err), FM_OK);
    CHECK_EQ(b.nparts, 2);
    CHECK_EQ(b.nloops, 2);
    for (size_t k = 0; k < b.nloops; k++) {
        CHECK_EQ(b.part[k], k);
        CHECK_EQ(b.start[k + 1] - b.start[k], 4);
        CHECK_NEAR(loop_area(&b, k), 1, 1e-12);
        CHECK_EQ(b.node[b.start[k]], -1);
    }
    fm_remesh_boundary_free(&b);
    free(uv);
    fm_mesh_destroy(m);

    int skip3[] = {0, 4};
    m = grid(3, skip3, 2, &uv);
    CHECK_EQ(fm_remesh_boundary_of(m, uv, NULL, &b, &err), FM_OK);
    CHECK_EQ(b.nparts, 1);
    CHECK_EQ(b.nloops, 2);
    if (b.nloops == 2) {
        CHECK_NEAR(loop_area(&b, 0), 8, 1e-12);
        CHECK_NEAR(loop_area(&b, 1), -1, 1e-12);
        CHECK_EQ(b.start[2] - b.start[1], 4);
        CHECK_EQ(b.start[1] - b.start[0], 12);
    }
    fm_remesh_boundary_free(&b);
    free(uv);
    fm_mesh_destroy(m);
}

static void test_bad_mesh(void)
{
    double *uv;
    fm_mesh *m = grid(1, NULL, 0, &uv);
    fm_mesh_add_triangle(m, 0, 1, 3, 0); /* edge 0-1 a second time the same way */
    fm_remesh_boundary b;
    fm_error err;
    CHECK_EQ(fm_remesh_boundary_of(m, uv, NULL, &b, &err), FM_ERR_TOPOLOGY);
    CHECK_EQ(b.nloops, 0);
    CHECK(b.uv == NULL);
    free(uv);
    fm_mesh_destroy(m);
}

/* A fitted plane over 10 km x 8 km. */
static fm_fit_surface *plane(void)
{
    fm_mesh *m = fm_mesh_create();
    int n = 10;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            fm_mesh_add_vertex(m, 400000 + 1000.0 * i, 3700000 + 800.0 * j, -100.0 * i - 500.0 * j);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i;
            fm_mesh_add_triangle(m, a, a + 1, a + n + 2, 0);
            fm_mesh_add_triangle(m, a, a + n + 2, a + n + 1, 0);
        }
    fm_fit_surface *s = NULL;
    fm_error err;
    CHECK_EQ(fm_fit_sheet(m, NULL, &s, &err), FM_OK);
    fm_mesh_destroy(m);
    return s;
}

/* DE entries of type `type` in an IGES file's text. */
static int count_entities(const char *text, int type)
{
    int n = 0;
    for (const char *l = text; *l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : l + strlen(l))
        if (strlen(l) > 80 && l[72] == 'D' && atoi(l + 73) % 2 == 1 && atoi(l) == type)
            n++;
    return n;
}

/* The cubic B-spline (knots k, control points d, 2 each) at t. */
static void eval_cubic(const double *k, size_t n, const double *d, double t, double out[2])
{
    size_t s = 3;
    while (s + 1 < n && k[s + 1] <= t)
        s++;
    double p[4][2];
    for (int j = 0; j < 4; j++)
        memcpy(p[j], d + 2 * (s - 3 + (size_t)j), sizeof p[j]);
    for (int r = 1; r <= 3; r++)
        for (int j = 3; j >= r; j--) {
            size_t i = s - 3 + (size_t)j;
            double a = (t - k[i]) / (k[i + 4 - (size_t)r] - k[i]);
            for (int c = 0; c < 2; c++)
                p[j][c] = (1 - a) * p[j - 1][c] + a * p[j][c];
        }
    memcpy(out, p[3], sizeof p[3]);
}

/* A trim through unevenly spaced nodes on a circle: the cubic passes
 * through every node and stays near the circle between them; too few or
 * repeated nodes are left a polygon; breaks fall at sharp turns only. */
static void test_trim_curves(void)
{
    enum { N = 9 };
    const double R = 5000, pi = 3.14159265358979323846;
    static const double ang[N] = {0, 5, 12, 20, 26, 35, 41, 50, 60};
    double q[2 * N], ctrl[2 * (N + 2)], knots[N + 6], work[4 * N];
    for (int i = 0; i < N; i++) {
        q[2 * i] = 400000 + R * cos(ang[i] * pi / 180);
        q[2 * i + 1] = 3700000 + R * sin(ang[i] * pi / 180);
    }
    CHECK_EQ(cad_trim_cubic(q, N, ctrl, knots, work), 1);
    double worst_node = 0, worst_arc = 0;
    for (int i = 0; i < N; i++) {
        double t = i == 0 ? knots[0] : i == N - 1 ? knots[N + 5] : knots[3 + i], p[2];
        eval_cubic(knots, N + 2, ctrl, t, p);
        worst_node = fmax(worst_node, hypot(p[0] - q[2 * i], p[1] - q[2 * i + 1]));
    }
    for (int k = 0; k <= 200; k++) {
        double t = knots[0] + (knots[N + 5] - knots[0]) * k / 200.0, p[2];
        eval_cubic(knots, N + 2, ctrl, t, p);
        worst_arc = fmax(worst_arc, fabs(hypot(p[0] - 400000, p[1] - 3700000) - R));
    }
    CHECK(worst_node < 1e-6);
    /* nearer the circle than the polygon, whose widest gap (9 degrees)
     * is 15.4 m off it at its middle */
    CHECK(worst_arc < R * (1 - cos(4.5 * pi / 180)));
    CHECK_EQ(cad_trim_cubic(q, 2, ctrl, knots, work), 0);
    double rep[6] = {0, 0, 1, 1, 1, 1};
    CHECK_EQ(cad_trim_cubic(rep, 3, ctrl, knots, work), 0);

    double square[] = {0, 0, 50, 0, 100, 0, 100, 100, 50, 110, 0, 100};
    unsigned char brk[6], corner[6] = {0, 1, 0, 0, 0, 0};
    cad_loop_breaks(square, 6, corner, brk);
    static const unsigned char want[6] = {1, 1, 1, 1, 0, 1};
    for (int i = 0; i < 6; i++)
        CHECK_EQ(brk[i], want[i]);
}

/* Smooth trims that would cross keep their polygons: the cubic through a
 * zigzag outline bulges above its chords near the peaks, across a hole
 * the polygons keep clear of. */
static void test_trim_crossing(void)
{
    double uv[] = {0, 0, 10, 3.6, 20, 0, 30, 3.6, 40, 0, 40, 20, 0, 20, /* outer */
                   12, 3.0, 14, 10, 16, 2.2};                         /* hole */
    size_t start[] = {0, 7, 10};
    unsigned char brk[10];
    cad_loop_breaks(uv, 7, NULL, brk);
    cad_loop_breaks(uv + 14, 3, NULL, brk + 7);
    CHECK(!brk[1] && !brk[2] && !brk[3]); /* turns of 40 degrees: one stretch */
    cad_curves cv;
    CHECK_EQ(cad_curves_make(&cv, uv, start, 1, brk), FM_OK);
    int cubic = 0;
    for (size_t c = 0; c < cv.ncurves; c++)
        cubic += cv.degree[c] == 3;
    CHECK_EQ(cubic, 1); /* alone, the zigzag is a cubic */
    cad_curves_free(&cv);
    CHECK_EQ(cad_curves_make(&cv, uv, start, 2, brk), FM_OK);
    CHECK_EQ(cv.nloops, 2);
    for (size_t c = 0; c < cv.ncurves; c++)
        CHECK_EQ(cv.degree[c], 1);
    cad_curves_free(&cv);
}

static void test_faces(void)
{
    fm_fit_surface *s = plane();
    if (!s)
        return;
    double dom[4];
    fm_fit_surface_domain(s, dom);
    double u0 = dom[0] + 0.2 * (dom[1] - dom[0]), u1 = dom[0] + 0.8 * (dom[1] - dom[0]);
    double v0 = dom[2] + 0.2 * (dom[3] - dom[2]), v1 = dom[2] + 0.8 * (dom[3] - dom[2]);
    double um = (u0 + u1) / 2, vm = (v0 + v1) / 2;
    /* outer: a square of 8 points, corners at 3 of them; hole: a triangle
     * without corners */
    double uv[] = {u0, v0, um, v0, u1, v0, u1, vm, u1, v1, um, v1, u0, v1, u0, vm,
                   um - 100, vm - 100, um + 100, vm - 100, um, vm + 100};
    size_t start[] = {0, 8, 11};
    unsigned char corner[11] = {1, 0, 1, 0, 0, 0, 1};
    fm_cad_face *f[2] = {NULL, NULL};
    fm_error err;
    CHECK_EQ(fm_cad_face_create("SYNT-TEST-fault", s, uv, start, 2, corner, &f[0], &err), FM_OK);
    CHECK_EQ(fm_cad_face_create("second", s, uv, start, 1, NULL, &f[1], &err), FM_OK);
    /* refused: a loop of 2 points, a point off the surface's rectangle */
    fm_cad_face *bad = NULL;
    size_t two[] = {0, 2};
    CHECK_EQ(fm_cad_face_create("x", s, uv, two, 1, NULL, &bad, &err), FM_ERR_INVALID);
    double off[] = {u0, v0, dom[1] + 1, v0, u1, v1};
    size_t three[] = {0, 3};
    CHECK_EQ(fm_cad_face_create("x", s, off, three, 1, NULL, &bad, &err), FM_ERR_INVALID);
    CHECK(bad == NULL);
    if (f[0] && f[1]) {
        mkdir(FM_TMP_DIR, 0777);
        char path[512];
        snprintf(path, sizeof path, "%s/test_cad.igs", FM_TMP_DIR);
        unsetenv("SOURCE_DATE_EPOCH");
        CHECK_EQ(fm_cad_write_iges(path, (const fm_cad_face *const *)f, 2, "EPSG:26711", &err),
                 FM_OK);
        char *text = fm_test_read_file(path, NULL);
        CHECK(text != NULL);
        if (text) {
            CHECK_EQ(count_entities(text, 144), 2);
            CHECK_EQ(count_entities(text, 128), 2);
            /* 4 curves for the outer loop of face 0 (3 corners and
             * the square's fourth, sharp, vertex), 3 for its hole (a
             * triangle: sharp everywhere), 4 for face 1's loop; a
             * composite for each */
            CHECK_EQ(count_entities(text, 126), 11);
            CHECK_EQ(count_entities(text, 102), 3);
            CHECK_EQ(count_entities(text, 142), 3);
            CHECK_EQ(count_entities(text, 406), 2);
            CHECK(strstr(text, "CRS: EPSG:26711") != NULL);
            CHECK(strstr(text, "15H19700101.000000") != NULL);
            free(text);
        }
        setenv("SOURCE_DATE_EPOCH", "86400", 1);
        CHECK_EQ(fm_cad_write_iges(path, (const fm_cad_face *const *)f, 2, NULL, &err), FM_OK);
        text = fm_test_read_file(path, NULL);
        CHECK(text && strstr(text, "15H19700102.000000") && strstr(text, "CRS: not given"));
        free(text);
        setenv("SOURCE_DATE_EPOCH", "yesterday", 1);
        CHECK_EQ(fm_cad_write_iges(path, (const fm_cad_face *const *)f, 2, NULL, &err),
                 FM_ERR_INVALID);
        unsetenv("SOURCE_DATE_EPOCH");
        remove(path);
    }
    fm_cad_face_destroy(f[0]);
    fm_cad_face_destroy(f[1]);
    fm_fit_surface_destroy(s);
}

FM_TEST_MAIN(FM_CASE(test_annulus), FM_CASE(test_pinches), FM_CASE(test_bad_mesh),
             FM_CASE(test_faces), FM_CASE(test_trim_curves),
             FM_CASE(test_trim_crossing))
