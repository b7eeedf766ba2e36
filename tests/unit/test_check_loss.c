/* fm_check_loss: the connect measures on hand-made sets whose answers are
 * known: an outline left 100 m from a neighbour, a strip of a fault cut
 * away, an interior node pulled aside, a piece cut off. */
#include <math.h>
#include <stdlib.h>

#include "fm_check.h"
#include "fm_test.h"

/* A grid of squares (each split in two) over the rectangle spanned by o +
 * s u + t w, s in [0, nu], t in [0, nw], step 1000 m, tagged tag; squares
 * with keep(i, j) false are left out. */
typedef int (*keep_fn)(int i, int j);

static int keep_all(int i, int j)
{
    (void)i;
    (void)j;
    return 1;
}

static void grid(fm_mesh *m, const double o[3], const double u[3], const double w[3], int nu,
                 int nw, int32_t tag, keep_fn keep)
{
    int32_t base = (int32_t)fm_mesh_nvertices(m);
    for (int j = 0; j <= nw; j++)
        for (int i = 0; i <= nu; i++)
            fm_mesh_add_vertex(m, o[0] + 1000.0 * (i * u[0] + j * w[0]),
                               o[1] + 1000.0 * (i * u[1] + j * w[1]),
                               o[2] + 1000.0 * (i * u[2] + j * w[2]));
    for (int j = 0; j < nw; j++)
        for (int i = 0; i < nu; i++) {
            if (!keep(i, j))
                continue;
            int32_t a = base + j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
            fm_mesh_add_triangle(m, a, b, d, tag);
            fm_mesh_add_triangle(m, a, d, c, tag);
        }
}

static const double X[3] = {1, 0, 0}, Y[3] = {0, 1, 0}, Z[3] = {0, 0, 1};

/* Fault 0: the plane y = 0, x in [0, 10 km], z in [-5 km, 0]. Fault 1: the
 * plane x = 5 km from y = y1 to y1 + 5 km. */
static fm_loss *measure(const fm_mesh *set, const fm_mesh *const *orig, int threads)
{
    double size[2] = {1000, 1000}, join[2] = {500, 500}, zcut[2] = {0, 0};
    fm_loss_input in = {set, NULL, 2, orig, size, join, zcut, threads};
    fm_loss *l = NULL;
    fm_error err;
    CHECK_EQ(fm_check_loss(&in, &l, &err), FM_OK);
    return l;
}

static void two_faults(fm_mesh *m, double y1, keep_fn keep0)
{
    double o0[3] = {0, 0, -5000}, o1[3] = {5000, y1, -5000};
    grid(m, o0, X, Z, 10, 5, 0, keep0);
    grid(m, o1, Y, Z, 5, 5, 1, keep_all);
}

static void test_gap(void)
{
    /* fault 1 stops 100 m short of fault 0: its edge x = 5 km, y = 100,
     * five 1 km edges, is an unclosed gap; fault 0's outline is 510 m
     * from fault 1 at best */
    fm_mesh *m = fm_mesh_create();
    two_faults(m, 100, keep_all);
    fm_loss *l = measure(m, NULL, 1);
    CHECK(l != NULL);
    CHECK_EQ(fm_loss_npairs(l), 1);
    const fm_loss_pair *p = fm_loss_pair_at(l, 0);
    CHECK_EQ(p->a, 0);
    CHECK_EQ(p->b, 1);
    CHECK_NEAR(p->gap_ab, 0, 1e-9);
    CHECK_NEAR(p->gap_ba, 5000, 1e-6);
    CHECK_NEAR(p->gap, 5000, 1e-6);
    CHECK_EQ(p->shared_nodes, 0);
    CHECK_NEAR(fm_loss_fault_at(l, 1)->gap, 5000, 1e-6);
    fm_loss_destroy(l);
    fm_mesh_destroy(m);

    /* the same, but fault 1 ends on fault 0 through shared nodes: no gap */
    m = fm_mesh_create();
    two_faults(m, 0, keep_all);
    /* weld fault 1's nodes at y = 0 onto fault 0's at x = 5 km */
    int32_t *T = fm_mesh_triangles_mut(m);
    const double *V = fm_mesh_vertices(m);
    size_t nt = fm_mesh_ntriangles(m), n0 = 66; /* fault 0's vertices: 11 x 6 */
    for (size_t t = 0; t < 3 * nt; t++)
        if ((size_t)T[t] >= n0 && V[3 * T[t] + 1] == 0)
            T[t] = (int32_t)(5 + 11 * (size_t)((V[3 * T[t] + 2] + 5000) / 1000));
    l = measure(m, NULL, 1);
    CHECK(l != NULL);
    CHECK_EQ(fm_loss_npairs(l), 0);
    CHECK_NEAR(fm_loss_fault_at(l, 1)->gap, 0, 1e-9);
    fm_loss_destroy(l);
    fm_mesh_destroy(m);
}

/* The two faults as output (fault 1 100 m short of fault 0, fault 0 with
 * the squares keep0 keeps) and their originals, whole: fault 0 with rows0
 * rows of squares from -5 km up (6: rising 1 km above sea level, which
 * does not count). */
typedef struct fixture {
    fm_mesh *m, *orig[2];
} fixture;

static void setup(fixture *fx, keep_fn keep0, int rows0)
{
    fx->m = fm_mesh_create();
    fx->orig[0] = fm_mesh_create();
    fx->orig[1] = fm_mesh_create();
    two_faults(fx->m, 100, keep0);
    double oo[3] = {0, 0, -5000}, o1o[3] = {5000, 100, -5000};
    grid(fx->orig[0], oo, X, Z, 10, rows0, 0, keep_all);
    grid(fx->orig[1], o1o, Y, Z, 5, 5, 0, keep_all);
}

static void teardown(fixture *fx)
{
    fm_mesh_destroy(fx->m);
    fm_mesh_destroy(fx->orig[0]);
    fm_mesh_destroy(fx->orig[1]);
}

/* fault 0 without its two first columns of squares (x < 2 km) */
static int keep_right(int i, int j)
{
    (void)j;
    return i >= 2;
}

static void test_missing(void)
{
    fixture fx;
    setup(&fx, keep_right, 6);
    fm_loss *l = measure(fx.m, (const fm_mesh *const *)fx.orig, 1);
    CHECK(l != NULL);
    const fm_loss_fault *f = fm_loss_fault_at(l, 0);
    CHECK_NEAR(f->orig_area, 50e6, 1);
    /* farther than H/2 = 500 m from the output: x < 1500 m, sampled at
     * 250 m, centroids at 1/3 and 2/3 of the sub-triangles */
    CHECK_NEAR(f->missing_area, 7.5e6, 0.4e6);
    CHECK_NEAR(f->missing_away, f->missing_area, 1e-6); /* fault 1 is 3.5 km off */
    CHECK_NEAR(fm_loss_fault_at(l, 1)->missing_area, 0, 1e-9);
    CHECK_NEAR(f->moved_max, 0, 1e-6);
    CHECK_EQ(f->islands, 0);
    CHECK_EQ(f->pieces, 1);
    CHECK_EQ(f->orig_pieces, 1);
    fm_loss_destroy(l);
    teardown(&fx);
}

static int keep_not_middle(int i, int j)
{
    (void)j;
    return i < 4 || i >= 6;
}

static void test_missing_near_other(void)
{
    fixture fx;
    setup(&fx, keep_not_middle, 5);
    fm_loss *l = measure(fx.m, (const fm_mesh *const *)fx.orig, 2);
    const fm_loss_fault *f = fm_loss_fault_at(l, 0);
    /* x in (4.5, 5.5) km is missing, all of it within 500 m of fault 1 */
    CHECK_NEAR(f->missing_area, 5e6, 0.4e6);
    CHECK_NEAR(f->missing_away, 0, 1e-9);
    /* fault 0 is now two pieces of one sheet, where its original is one */
    CHECK_EQ(f->pieces, 2);
    CHECK_EQ(f->islands, 1);
    CHECK_EQ(f->island_triangles, 40);
    fm_loss_destroy(l);
    teardown(&fx);
}

static void test_moved(void)
{
    fixture fx;
    setup(&fx, keep_all, 5);
    /* fault 0's node (2 km, 0, -3 km), inside, pulled 300 m aside; its
     * node (10 km, 0, -2 km), on the outline, pushed 400 m past it */
    double *V = fm_mesh_vertices_mut(fx.m);
    V[3 * (2 * 11 + 2) + 1] = 300;
    V[3 * (3 * 11 + 10) + 0] += 400;
    fm_loss *l = measure(fx.m, (const fm_mesh *const *)fx.orig, 1);
    const fm_loss_fault *f = fm_loss_fault_at(l, 0);
    CHECK_NEAR(f->moved_max, 300, 1e-6);
    CHECK_EQ(f->moved_over, 1);
    CHECK_NEAR(f->moved_at[0], 2000, 1e-9);
    CHECK_NEAR(fm_loss_fault_at(l, 1)->moved_max, 0, 1e-6);
    fm_loss_destroy(l);
    teardown(&fx);
}

/* Two strands of one fault side by side 400 m apart (a stepover): the
 * plane y = 0 for x in [0, 5 km] and y = 400 m for x in [4, 10 km]. The
 * first is meshed on over its own extension to x = 7 km, beside the
 * second's inside: no inside moved, since the fill is measured from the
 * outline it extends (on the whole original its nearest point is the
 * other strand's inside, 400 m away). A node of the second strand's
 * inside pulled 300 m aside still counts. */
static void test_moved_strands(void)
{
    fm_mesh *orig = fm_mesh_create(), *set = fm_mesh_create();
    double oa[3] = {0, 0, -5000}, ob[3] = {4000, 400, -5000};
    grid(orig, oa, X, Z, 5, 5, 0, keep_all);
    grid(orig, ob, X, Z, 6, 5, 0, keep_all);
    grid(set, oa, X, Z, 7, 5, 0, keep_all);
    size_t first_b = fm_mesh_nvertices(set), na = fm_mesh_ntriangles(set);
    grid(set, ob, X, Z, 6, 5, 0, keep_all);
    size_t nt = fm_mesh_ntriangles(set);
    int32_t *sheet = malloc(nt * sizeof *sheet);
    for (size_t t = 0; t < nt; t++)
        sheet[t] = t >= na;
    double size[1] = {1000}, join[1] = {1000}, zcut[1] = {0};
    const fm_mesh *o1[1] = {orig};
    fm_loss_input in = {set, sheet, 1, o1, size, join, zcut, 1};
    fm_loss *l = NULL;
    fm_error err;
    CHECK_EQ(fm_check_loss(&in, &l, &err), FM_OK);
    CHECK_NEAR(fm_loss_fault_at(l, 0)->moved_max, 0, 1e-6);
    CHECK_EQ(fm_loss_fault_at(l, 0)->moved_over, 0);
    fm_loss_destroy(l);
    /* the second strand's node (7 km, 400 m, -3 km) pulled to y = 700 m */
    fm_mesh_vertices_mut(set)[3 * (first_b + 2 * 7 + 3) + 1] = 700;
    CHECK_EQ(fm_check_loss(&in, &l, &err), FM_OK);
    CHECK_NEAR(fm_loss_fault_at(l, 0)->moved_max, 300, 1e-6);
    CHECK_EQ(fm_loss_fault_at(l, 0)->moved_over, 1);
    CHECK_NEAR(fm_loss_fault_at(l, 0)->moved_at[0], 7000, 1e-9);
    fm_loss_destroy(l);
    /* without the sheets, the whole original: the fill counts (400 m) */
    fm_mesh_vertices_mut(set)[3 * (first_b + 2 * 7 + 3) + 1] = 400;
    in.sheet = NULL;
    CHECK_EQ(fm_check_loss(&in, &l, &err), FM_OK);
    CHECK_NEAR(fm_loss_fault_at(l, 0)->moved_max, 400, 1e-6);
    fm_loss_destroy(l);
    free(sheet);
    fm_mesh_destroy(set);
    fm_mesh_destroy(orig);
}

/* The same answers on any number of threads. */
static void test_threads(void)
{
    fixture fx;
    setup(&fx, keep_not_middle, 5);
    fm_loss *a = measure(fx.m, (const fm_mesh *const *)fx.orig, 1), *b = measure(fx.m, (const fm_mesh *const *)fx.orig, 3);
    for (size_t f = 0; f < 2; f++)
        CHECK(!memcmp(fm_loss_fault_at(a, f), fm_loss_fault_at(b, f), sizeof(fm_loss_fault)));
    CHECK_EQ(fm_loss_npairs(a), fm_loss_npairs(b));
    for (size_t k = 0; k < fm_loss_npairs(a) && k < fm_loss_npairs(b); k++)
        CHECK(!memcmp(fm_loss_pair_at(a, k), fm_loss_pair_at(b, k), sizeof(fm_loss_pair)));
    fm_loss_destroy(a);
    fm_loss_destroy(b);
    teardown(&fx);
}

/* A tag out of range is refused, not read past. */
static void test_bad_tag(void)
{
    fm_mesh *m = fm_mesh_create();
    two_faults(m, 100, keep_all);
    fm_mesh_tags_mut(m)[3] = 7;
    double size[2] = {1000, 1000}, join[2] = {500, 500}, zcut[2] = {0, 0};
    fm_loss_input in = {m, NULL, 2, NULL, size, join, zcut, 1};
    fm_loss *l = NULL;
    fm_error err;
    CHECK_EQ(fm_check_loss(&in, &l, &err), FM_ERR_INVALID);
    CHECK(l == NULL);
    fm_mesh_destroy(m);
}

FM_TEST_MAIN(FM_CASE(test_gap), FM_CASE(test_missing), FM_CASE(test_missing_near_other),
             FM_CASE(test_moved), FM_CASE(test_moved_strands), FM_CASE(test_threads), FM_CASE(test_bad_tag))
