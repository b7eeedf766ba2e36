/* fm_check_elastic on hand-made sets whose answer is known: every
 * self-stiffness restoring; two parallel faults 75 m apart over 6 km
 * (a planted near-overlap: flagged, as no junction); the same faults 5 km
 * apart and a clean T-junction (not flagged); the result the same on 1 and
 * 3 threads; the matrices file's header and a diagonal entry. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "elastic_internal.h"
#include "fm_check.h"
#include "fm_sim_write.h"
#include "fm_test.h"

#define X0 500000.0
#define Y0 3700000.0

/* A vertical rectangle from (x, y) along the unit direction d, length L,
 * from z = -1 km down to -9 km, in squares of h split in two. */
static double wall_top = -1000, wall_depth = 8000;

static void wall(fm_mesh *m, double x, double y, const double d[2], double L, double h,
                 int32_t tag)
{
    int nu = (int)lround(L / h), nw = (int)lround(wall_depth / h);
    int32_t base = (int32_t)fm_mesh_nvertices(m);
    for (int j = 0; j <= nw; j++)
        for (int i = 0; i <= nu; i++)
            fm_mesh_add_vertex(m, X0 + x + i * h * d[0], Y0 + y + i * h * d[1],
                               wall_top - j * h);
    for (int j = 0; j < nw; j++)
        for (int i = 0; i < nu; i++) {
            int32_t a = base + j * (nu + 1) + i, b = a + 1, c = a + nu + 1, e = c + 1;
            if ((i + j) % 2) {
                fm_mesh_add_triangle(m, a, b, e, tag);
                fm_mesh_add_triangle(m, a, e, c, tag);
            } else {
                fm_mesh_add_triangle(m, a, b, c, tag);
                fm_mesh_add_triangle(m, b, e, c, tag);
            }
        }
}

typedef struct set {
    fm_mesh *m;
    double *strike, *dip, *rake;
} set;

/* Frames as the run makes them; every element right-lateral. */
static void frames(set *s, size_t nfaults)
{
    size_t n = fm_mesh_ntriangles(s->m);
    s->strike = malloc(n * sizeof *s->strike);
    s->dip = malloc(n * sizeof *s->dip);
    s->rake = malloc(n * sizeof *s->rake);
    const char *names[2] = {"a", "b"};
    fm_faultset fs = {.mesh = s->m, .names = names, .nfaults = nfaults};
    fm_faultset_strike_dip(&fs, s->strike, s->dip);
    for (size_t t = 0; t < n; t++)
        s->rake[t] = 180;
}

static void set_free(set *s)
{
    fm_mesh_destroy(s->m);
    free(s->strike);
    free(s->dip);
    free(s->rake);
}

static fm_elastic *check(const set *s, int threads, const fm_elastic_junction *jn, size_t nj)
{
    fm_elastic_input in = {s->m, 2, s->strike, s->dip, s->rake, jn, nj};
    fm_elastic_options o;
    fm_elastic_options_default(&o);
    o.threads = threads;
    fm_elastic *e = NULL;
    fm_error err;
    fm_error_clear(&err);
    CHECK(fm_check_elastic(&in, &o, &e, &err) == FM_OK);
    return e;
}

static set parallel(double apart)
{
    set s = {fm_mesh_create(), NULL, NULL, NULL};
    double north[2] = {0, 1};
    wall(s.m, 0, 0, north, 12000, 1000, 0);
    wall(s.m, apart, 6000, north, 12000, 1000, 1);
    frames(&s, 2);
    return s;
}

static void test_near_overlap(void)
{
    set s = parallel(75);
    fm_elastic *e = check(&s, 1, NULL, 0);
    const fm_elastic_summary *sum = fm_elastic_get_summary(e);
    size_t n = fm_mesh_ntriangles(s.m);
    CHECK_EQ(sum->elements, n);
    CHECK_EQ(sum->self_wrong_sign, 0);
    CHECK(sum->self_max < 0);
    /* a square patch of side a slipping alone: stress drop about mu / a */
    CHECK(sum->self_min > -3e10 / 1000 * 10 && sum->self_max < -3e10 / 1000 / 10);
    size_t ng, np;
    const fm_elastic_group *g = fm_elastic_groups(e, &ng);
    const fm_elastic_pair *p = fm_elastic_pairs(e, &np);
    printf("near-overlap: %zu pairs evaluated, %zu flagged, max ratio %.3f, self %.4g .. %.4g\n",
           sum->pairs_evaluated, sum->pairs_flagged, sum->max_ratio, sum->self_min,
           sum->self_max);
    CHECK_EQ(ng, 1);
    CHECK_EQ(g[0].a, 0);
    CHECK_EQ(g[0].b, 1);
    CHECK_EQ(g[0].junction, 0);
    /* the 6 km of overlap, 8 km deep, in 1 km squares: each element faces
     * one across */
    CHECK(g[0].pairs >= 48);
    CHECK(g[0].max_ratio > 0.5);
    CHECK_NEAR(g[0].min_distance, 75, 1e-6);
    CHECK(g[0].nexamples == FM_ELASTIC_EXAMPLES);
    for (size_t k = 0; k < np; k++)
        CHECK(fm_mesh_tags(s.m)[p[k].i] == 0 && fm_mesh_tags(s.m)[p[k].j] == 1);
    /* the same on threads */
    fm_elastic *e3 = check(&s, 3, NULL, 0);
    size_t np3;
    const fm_elastic_pair *p3 = fm_elastic_pairs(e3, &np3);
    CHECK_EQ(np3, np);
    CHECK(np == np3 && !memcmp(p, p3, np * sizeof *p));
    CHECK(!memcmp(fm_elastic_self(e), fm_elastic_self(e3), n * sizeof(double)));
    /* a junction of the two faults takes the pairs */
    double pts[6] = {X0, Y0 + 9000, -1000, X0, Y0 + 9000, -9000};
    fm_elastic_junction jn[2] = {{{1, 0}, NULL, 0}, {{0, 1}, pts, 2}};
    fm_elastic *ej = check(&s, 2, jn, 2);
    g = fm_elastic_groups(ej, &ng);
    CHECK_EQ(ng, 1);
    CHECK_EQ(g[0].junction, 2);
    fm_elastic_destroy(ej);
    fm_elastic_destroy(e3);
    fm_elastic_destroy(e);
    set_free(&s);
}

static void test_far_apart(void)
{
    set s = parallel(5000);
    fm_elastic *e = check(&s, 2, NULL, 0);
    const fm_elastic_summary *sum = fm_elastic_get_summary(e);
    printf("5 km apart: %zu pairs evaluated, max ratio %.3f\n", sum->pairs_evaluated,
           sum->max_ratio);
    CHECK_EQ(sum->pairs_flagged, 0);
    CHECK(sum->max_ratio < 0.1);
    fm_elastic_destroy(e);
    set_free(&s);
}

/* b runs east along y = 0; a runs north from it, ending on it. */
static void test_t_junction(void)
{
    set s = {fm_mesh_create(), NULL, NULL, NULL};
    double north[2] = {0, 1}, east[2] = {1, 0};
    wall(s.m, 0, 0, north, 10000, 1000, 0);
    wall(s.m, -10000, 0, east, 20000, 1000, 1);
    frames(&s, 2);
    fm_elastic *e = check(&s, 2, NULL, 0);
    const fm_elastic_summary *sum = fm_elastic_get_summary(e);
    printf("T-junction: %zu pairs evaluated, %zu flagged, max ratio %.3f\n",
           sum->pairs_evaluated, sum->pairs_flagged, sum->max_ratio);
    CHECK(sum->pairs_evaluated > 0);
    CHECK_EQ(sum->pairs_flagged, 0);
    CHECK_EQ(sum->self_wrong_sign, 0);
    fm_elastic_destroy(e);
    set_free(&s);
}

/* The .npy header numpy reads, and the diagonal of the rake matrix equal
 * to the check's self-stiffness (the Python test reads the rest). */
static void test_matrices(void)
{
    wall_depth = 4000;
    set s = parallel(75);
    wall_depth = 8000;
    fm_elastic_input in = {s.m, 2, s.strike, s.dip, s.rake, NULL, 0};
    fm_elastic_options o;
    fm_elastic_options_default(&o);
    o.threads = 2;
    char path[] = "/tmp/fm_elastic_matrix_XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    fm_error err;
    fm_error_clear(&err);
    CHECK(fm_elastic_write_matrices(&in, &o, path, &err) == FM_OK);
    size_t n = fm_mesh_ntriangles(s.m);
    FILE *fp = fopen(path, "rb");
    CHECK(fp != NULL);
    unsigned char head[10];
    CHECK(fread(head, 1, 10, fp) == 10);
    CHECK(!memcmp(head, "\x93NUMPY\x01\x00", 8));
    size_t hlen = head[8] | (size_t)head[9] << 8;
    CHECK((10 + hlen) % 64 == 0);
    fseek(fp, 0, SEEK_END);
    CHECK_EQ((size_t)ftell(fp), 10 + hlen + n * n * 4 * 8);
    fm_elastic *e = check(&s, 1, NULL, 0);
    const double *self = fm_elastic_self(e);
    for (size_t i = 0; i < n; i += 37) {
        double v;
        fseek(fp, (long)(10 + hlen + ((i * n + i) * 4 + 2) * 8), SEEK_SET);
        CHECK(fread(&v, 8, 1, fp) == 1);
        CHECK(v == self[i]);
    }
    fclose(fp);
    remove(path);
    fm_elastic_destroy(e);
    set_free(&s);
}

/* Where the full space stands in for the half space (EL_IMAGE_SIZES),
 * the difference is under 5e-4 of the receiver's self-stiffness: two
 * faults 1 km apart from 500 m down to 20 km, every component. */
static void test_image_cutoff(void)
{
    wall_top = -500;
    wall_depth = 20000;
    set s = parallel(1000);
    wall_top = -1000;
    wall_depth = 8000;
    size_t n = fm_mesh_ntriangles(s.m), used = 0;
    el_elem *el = malloc(n * sizeof *el);
    for (size_t t = 0; t < n; t++)
        CHECK_EQ(el_elem_make(s.m, t, s.strike[t], s.dip[t], s.rake[t], &el[t]), 0);
    double worst = 0;
    for (size_t i = 0; i < n; i += 13) {
        double self[4];
        CHECK_EQ(el_traction_hs(&el[i], &el[i], 3e10, 0.25, self), 0);
        for (size_t j = 0; j < n; j += 17) {
            if (el[j].top - el[i].c[2] < EL_IMAGE_SIZES * el[j].h)
                continue;
            double a[4], b[4];
            fm_elastic_options o;
            fm_elastic_options_default(&o);
            CHECK_EQ(el_traction(&el[j], &el[i], &o, a), 0);
            CHECK_EQ(el_traction_hs(&el[j], &el[i], 3e10, 0.25, b), 0);
            for (int c = 0; c < 4; c++)
                worst = fmax(worst, fabs(a[c] - b[c]) / fabs(self[2]));
            used++;
        }
    }
    printf("full space for the half space: %zu pairs, largest difference %.2e of K_ii\n", used,
           worst);
    CHECK(used > 100);
    CHECK(worst < 5e-4);
    free(el);
    set_free(&s);
}

/* The screen of elastic.c: with every pair evaluated (a fraction under
 * its 0.25), faults facing each other 0.3 and 0.5 element sizes apart
 * couple under 0.25 (and the closest faults of the test above, 75 m, far
 * over): what is not evaluated could not have been flagged. Deep, where
 * the full space is exact enough and quick. */
static void test_screen(void)
{
    double offsets[2] = {300, 500};
    for (int k = 0; k < 2; k++) {
        wall_top = -20000;
        set s = parallel(offsets[k]);
        wall_top = -1000;
        fm_elastic_input in = {s.m, 2, s.strike, s.dip, s.rake, NULL, 0};
        fm_elastic_options o;
        fm_elastic_options_default(&o);
        o.fraction = 0.01;
        o.threads = 2;
        fm_elastic *e = NULL;
        fm_error err;
        fm_error_clear(&err);
        CHECK(fm_check_elastic(&in, &o, &e, &err) == FM_OK);
        const fm_elastic_summary *sum = fm_elastic_get_summary(e);
        printf("%.0f m apart, every pair: %zu evaluated, largest coupling %.3f\n", offsets[k],
               sum->pairs_evaluated, sum->max_ratio);
        CHECK_EQ(sum->pairs_evaluated, sum->pairs_within);
        CHECK(sum->pairs_evaluated > 100);
        CHECK(sum->max_ratio < 0.25);
        fm_elastic_destroy(e);
        set_free(&s);
    }
}

FM_TEST_MAIN(FM_CASE(test_image_cutoff), FM_CASE(test_screen), FM_CASE(test_near_overlap), FM_CASE(test_far_apart), FM_CASE(test_t_junction),
             FM_CASE(test_matrices))
