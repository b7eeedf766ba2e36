/* The exact contact of two triangles (fm_triangles_meet*, core) and the
 * removal of what still crosses between faults (fm_carve.h). */
#include "fm_test.h"

#include "fm_carve.h"
#include "fm_mesh.h"
#include "fm_predicates.h"

#include <stdint.h>
#include <stdlib.h>

static int meet(const double a[3][3], const double b[3][3])
{
    const double *pa[3] = {a[0], a[1], a[2]}, *pb[3] = {b[0], b[1], b[2]};
    return fm_triangles_meet(pa, pb);
}

static void test_contact_cases(void)
{
    const double flat[3][3] = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
    const double pierce[3][3] = {{1, 1, -1}, {1, 1, 1}, {2, 1, 1}};
    const double above[3][3] = {{1, 1, 0.5}, {1, 1, 1}, {2, 1, 1}};
    const double on_face[3][3] = {{1, 1, 0}, {1, 1, 1}, {2, 1, 1}};
    const double on_edge[3][3] = {{2, 0, 0}, {2, -1, 1}, {2, -1, -1}};
    const double past_corner[3][3] = {{4.5, -0.5, 0}, {5, 0, 1}, {5, 0, -1}};
    const double flat_overlap[3][3] = {{1, 1, 0}, {5, 1, 0}, {1, 5, 0}};
    const double flat_apart[3][3] = {{3, 3, 0}, {5, 3, 0}, {3, 5, 0}};
    const double flat_touch[3][3] = {{2, 2, 0}, {5, 2, 0}, {2, 5, 0}};
    CHECK(meet(flat, pierce));
    CHECK(!meet(flat, above));
    CHECK(meet(flat, on_face));
    CHECK(meet(flat, on_edge));
    CHECK(!meet(flat, past_corner));
    CHECK(meet(flat, flat_overlap));
    CHECK(!meet(flat, flat_apart));
    CHECK(meet(flat, flat_touch)); /* (2, 2) lies on the side from (4, 0) to (0, 4) */
    /* symmetric */
    CHECK(meet(pierce, flat));
    CHECK(!meet(flat_apart, flat));
}

static void test_contact_shared(void)
{
    const double x[] = {
        0, 0, 0,  /* 0 */
        4, 0, 0,  /* 1 */
        0, 4, 0,  /* 2 */
        0, 0, 4,  /* 3: above the side 0-1, out of plane */
        2, -3, 0, /* 4: in plane, across the side 0-1 */
        3, 1, 0,  /* 5: in plane, same side of 0-1 as 2 */
        4, 4, -1, /* 6 */
        4, 4, 1,  /* 7 */
        1, 1, 2,  /* 8 */
        1, 1, -2, /* 9 */
    };
    const int32_t t[] = {0, 1, 2};
    CHECK(!fm_triangles_meet_apart(t, (int32_t[]){1, 0, 3}, x)); /* a fold along 0-1 */
    CHECK(!fm_triangles_meet_apart(t, (int32_t[]){0, 1, 4}, x)); /* flat, either side */
    CHECK(fm_triangles_meet_apart(t, (int32_t[]){0, 1, 5}, x));  /* flat, overlapping */
    CHECK(!fm_triangles_meet_apart(t, (int32_t[]){1, 6, 7}, x)); /* a corner only */
    CHECK(fm_triangles_meet_apart(t, (int32_t[]){0, 8, 9}, x));  /* a corner, and through */
    CHECK(fm_triangles_meet_apart(t, (int32_t[]){2, 0, 1}, x));  /* the same triangle */
    CHECK(!fm_triangles_meet_apart(t, (int32_t[]){0, 3, 8}, x)); /* a corner, above */
}

/* Random small-integer triangles, many of them touching or coplanar: the
 * answer may not depend on the order of the triangles or their corners. */
static void test_contact_invariance(void)
{
    uint64_t s = 12345;
    int mismatches = 0, met = 0;
    for (int n = 0; n < 20000; n++) {
        double a[3][3], b[3][3];
        for (int i = 0; i < 9; i++) {
            s = s * 6364136223846793005ull + 1442695040888963407ull;
            a[i / 3][i % 3] = (double)((s >> 33) % 5);
            s = s * 6364136223846793005ull + 1442695040888963407ull;
            b[i / 3][i % 3] = (double)((s >> 33) % 5);
        }
        if (fm_collinear3d(a[0], a[1], a[2]) || fm_collinear3d(b[0], b[1], b[2]))
            continue;
        const double *pa[3] = {a[0], a[1], a[2]}, *pb[3] = {b[0], b[1], b[2]};
        const double *qa[3] = {a[2], a[0], a[1]}, *qb[3] = {b[1], b[0], b[2]};
        int r = fm_triangles_meet(pa, pb);
        met += r;
        mismatches += r != fm_triangles_meet(pb, pa);
        mismatches += r != fm_triangles_meet(qa, qb);
        mismatches += r != fm_triangles_meet(qb, qa);
    }
    CHECK_EQ(mismatches, 0);
    CHECK(met > 100);
}

/* A grid of n x n squares, two triangles each, in the plane spanned by
 * (o, o + u, o + v), tagged tag. */
static void grid(fm_mesh *m, const double o[3], const double u[3], const double v[3], int n,
                 int32_t tag)
{
    int32_t base = (int32_t)fm_mesh_nvertices(m);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            fm_mesh_add_vertex(m, o[0] + i * u[0] + j * v[0], o[1] + i * u[1] + j * v[1],
                               o[2] + i * u[2] + j * v[2]);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int32_t a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            fm_mesh_add_triangle(m, a, b, d, tag);
            fm_mesh_add_triangle(m, a, d, c, tag);
        }
}

/* Pairs of triangles of different tags that meet, by brute force. */
static size_t contacts(const fm_mesh *m)
{
    size_t nt = fm_mesh_ntriangles(m), n = 0;
    const int32_t *T = fm_mesh_triangles(m), *tag = fm_mesh_tags(m);
    for (size_t a = 0; a < nt; a++)
        for (size_t b = a + 1; b < nt; b++)
            n += tag[a] != tag[b] &&
                 fm_triangles_meet_apart(T + 3 * a, T + 3 * b, fm_mesh_vertices(m));
    return n;
}

static void test_carve_crossing(void)
{
    fm_mesh *m = fm_mesh_create();
    /* a large gently dipping fault and a small vertical one through it */
    grid(m, (double[]){0, 0, -10}, (double[]){1, 0, 0.05}, (double[]){0, 1, 0.1}, 20, 0);
    grid(m, (double[]){5.3, 8.2, -14}, (double[]){1, 0.3, 0}, (double[]){0, 0, 1}, 6, 1);
    size_t before = fm_mesh_ntriangles(m), met = contacts(m);
    CHECK(met > 0);
    int32_t *was = malloc(before * sizeof *was), *tag0 = malloc(before * sizeof *tag0);
    for (size_t t = 0; t < before; t++) {
        was[t] = (int32_t)t;
        tag0[t] = fm_mesh_tags(m)[t];
    }
    fm_carve_result *r = NULL;
    fm_error err;
    fm_error_clear(&err);
    CHECK_EQ(fm_carve_crossings(m, 0, 2, was, &r, &err), FM_OK);
    /* the values beside the triangles follow them, in order */
    for (size_t t = 0; t < fm_mesh_ntriangles(m); t++) {
        CHECK(t == 0 || was[t] > was[t - 1]);
        CHECK_EQ(tag0[was[t]], fm_mesh_tags(m)[t]);
    }
    free(was);
    free(tag0);
    CHECK_EQ(fm_carve_npairs(r), 1);
    const fm_carve_pair *p = fm_carve_pair_at(r, 0);
    CHECK(p && p->fault[0] == 0 && p->fault[1] == 1);
    CHECK(p && p->contacts == met);
    /* the large fault loses the smaller share of its area */
    CHECK(p && p->yielded == 0);
    CHECK(p && p->removed > 0 && p->area > 0);
    CHECK_EQ(fm_mesh_ntriangles(m), before - fm_carve_removed(r));
    CHECK_EQ(contacts(m), 0);
    fm_carve_result_destroy(r);
    /* nothing left to do */
    CHECK_EQ(fm_carve_crossings(m, 0, 1, NULL, &r, &err), FM_OK);
    CHECK_EQ(fm_carve_npairs(r), 0);
    CHECK_EQ(fm_carve_removed(r), 0);
    fm_carve_result_destroy(r);
    fm_mesh_destroy(m);
}

/* A long strip and a small fault through its middle, across its whole
 * width: by the share of area the strip would give way, but that cuts it
 * in two; the small one gives way instead, which leaves it whole. */
static void test_carve_no_island(void)
{
    fm_mesh *m = fm_mesh_create();
    grid(m, (double[]){0, 0, -1}, (double[]){1, 0, 0}, (double[]){0, 0, 0.025}, 40, 0);
    grid(m, (double[]){10.5, -0.5, -2}, (double[]){0, 0.5, 0}, (double[]){0, 0, 0.5}, 6, 1);
    CHECK(contacts(m) > 0);
    fm_carve_result *r = NULL;
    fm_error err;
    fm_error_clear(&err);
    CHECK_EQ(fm_carve_crossings(m, 0, 2, NULL, &r, &err), FM_OK);
    CHECK_EQ(fm_carve_npairs(r), 1);
    const fm_carve_pair *p = fm_carve_pair_at(r, 0);
    CHECK(p && p->yielded == 1 && !p->kept);
    CHECK_EQ(contacts(m), 0);
    /* the strip keeps every triangle */
    size_t strip = 0;
    for (size_t t = 0; t < fm_mesh_ntriangles(m); t++)
        strip += fm_mesh_tags(m)[t] == 0;
    CHECK_EQ(strip, 2 * 40 * 40);
    fm_carve_result_destroy(r);
    fm_mesh_destroy(m);
}

static void test_carve_conforming(void)
{
    /* two faults sharing the nodes of their common edge: nothing to remove */
    fm_mesh *m = fm_mesh_create();
    grid(m, (double[]){0, 0, 0}, (double[]){1, 0, 0}, (double[]){0, 1, 0}, 4, 0);
    int32_t nv = (int32_t)fm_mesh_nvertices(m);
    for (int j = 1; j <= 4; j++)
        for (int i = 0; i <= 4; i++)
            fm_mesh_add_vertex(m, i, 0, -j);
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            int32_t a = j == 0 ? i : nv + (j - 1) * 5 + i, b = a + 1;
            int32_t c = nv + j * 5 + i, d = c + 1;
            fm_mesh_add_triangle(m, a, b, d, 1);
            fm_mesh_add_triangle(m, a, d, c, 1);
        }
    size_t before = fm_mesh_ntriangles(m);
    fm_carve_result *r = NULL;
    fm_error err;
    fm_error_clear(&err);
    CHECK_EQ(fm_carve_crossings(m, 0.5, 1, NULL, &r, &err), FM_OK);
    CHECK_EQ(fm_carve_npairs(r), 0);
    CHECK_EQ(fm_mesh_ntriangles(m), before);
    fm_carve_result_destroy(r);
    fm_mesh_destroy(m);
}

/* No fault is emptied: a fault of two triangles that both cross a large
 * one keeps them, although the large one holds a junction there (which
 * would spare it), and two faults of one triangle each that cross are
 * kept as they are. */
static void test_carve_never_empties(void)
{
    fm_mesh *m = fm_mesh_create();
    grid(m, (double[]){0, 0, -10}, (double[]){1, 0, 0.05}, (double[]){0, 1, 0.1}, 20, 0);
    /* a third fault hanging from the grid line y = 8, sharing its sides
     * (a junction) with the triangles the small one crosses */
    for (int i = 4; i < 10; i++) {
        const double *x = fm_mesh_vertices(m) + 3 * (8 * 21 + i);
        int32_t apex = fm_mesh_add_vertex(m, x[0] + 0.5, 8, x[2] - 3);
        fm_mesh_add_triangle(m, 8 * 21 + i, 8 * 21 + i + 1, apex, 2);
    }
    /* one cell, standing through the large fault: all it has meets it */
    grid(m, (double[]){5.3, 8.2, -12}, (double[]){3, 0.9, 0}, (double[]){0, 0, 4}, 1, 1);
    size_t before = fm_mesh_ntriangles(m);
    fm_carve_result *r = NULL;
    fm_error err;
    fm_error_clear(&err);
    CHECK_EQ(fm_carve_crossings(m, 0, 2, NULL, &r, &err), FM_OK);
    CHECK_EQ(fm_carve_npairs(r), 1);
    const fm_carve_pair *p = fm_carve_pair_at(r, 0);
    CHECK(p && p->fault[0] == 0 && p->fault[1] == 1);
    CHECK(p && !p->kept && p->yielded == 0 && p->removed > 0);
    size_t small = 0;
    for (size_t t = 0; t < fm_mesh_ntriangles(m); t++)
        small += fm_mesh_tags(m)[t] == 1;
    CHECK_EQ(small, 2);
    CHECK_EQ(fm_mesh_ntriangles(m), before - fm_carve_removed(r));
    CHECK_EQ(contacts(m), 0);
    fm_carve_result_destroy(r);
    fm_mesh_destroy(m);

    m = fm_mesh_create();
    fm_mesh_add_vertex(m, 0, 0, 0);
    fm_mesh_add_vertex(m, 4, 0, 0);
    fm_mesh_add_vertex(m, 0, 4, 0);
    fm_mesh_add_vertex(m, 1, 1, -1);
    fm_mesh_add_vertex(m, 1, 1, 1);
    fm_mesh_add_vertex(m, 2, 1, 1);
    fm_mesh_add_triangle(m, 0, 1, 2, 0);
    fm_mesh_add_triangle(m, 3, 4, 5, 1);
    CHECK_EQ(fm_carve_crossings(m, 0, 1, NULL, &r, &err), FM_OK);
    CHECK_EQ(fm_carve_npairs(r), 1);
    p = fm_carve_pair_at(r, 0);
    CHECK(p && p->kept && p->removed == 0 && p->area == 0);
    CHECK_EQ(fm_carve_removed(r), 0);
    CHECK_EQ(fm_mesh_ntriangles(m), 2);
    fm_carve_result_destroy(r);
    fm_mesh_destroy(m);
}

/* The removal the carve ends with (fm_mesh.h): the others in order with
 * their corners, tags and values beside. */
static void test_drop_triangles(void)
{
    fm_mesh *m = fm_mesh_create();
    for (int v = 0; v < 7; v++)
        fm_mesh_add_vertex(m, v, v * v, 0);
    for (int t = 0; t < 5; t++)
        fm_mesh_add_triangle(m, t, t + 1, t + 2, 10 + t);
    unsigned char gone[5] = {1, 0, 1, 0, 0};
    int32_t beside[5] = {100, 101, 102, 103, 104};
    CHECK_EQ(fm_mesh_drop_triangles(m, gone, beside), 2);
    CHECK_EQ(fm_mesh_ntriangles(m), 3);
    CHECK_EQ(fm_mesh_nvertices(m), 7);
    const int32_t keep[3] = {1, 3, 4};
    for (int k = 0; k < 3; k++) {
        CHECK_EQ(fm_mesh_triangles(m)[3 * k], keep[k]);
        CHECK_EQ(fm_mesh_triangles(m)[3 * k + 2], keep[k] + 2);
        CHECK_EQ(fm_mesh_tags(m)[k], 10 + keep[k]);
        CHECK_EQ(beside[k], 100 + keep[k]);
    }
    unsigned char none[3] = {0, 0, 0};
    CHECK_EQ(fm_mesh_drop_triangles(m, none, NULL), 0);
    CHECK_EQ(fm_mesh_ntriangles(m), 3);
    fm_mesh_destroy(m);
}

FM_TEST_MAIN(FM_CASE(test_drop_triangles), FM_CASE(test_contact_cases), FM_CASE(test_contact_shared),
             FM_CASE(test_contact_invariance), FM_CASE(test_carve_crossing),
             FM_CASE(test_carve_no_island), FM_CASE(test_carve_conforming), FM_CASE(test_carve_never_empties))
