/* Ring-shaped sheets (model_split.c): a vertical band closed on itself has
 * two outer rims and no one-to-one plane or usable flattening; the model
 * cuts it into disks that each fit, and reports the cuts. */
#include <math.h>

#include "fm_model.h"
#include "fm_repair.h"
#include "fm_test.h"

#define R 10000.0 /* radius (m) */
#define H 5000.0  /* height (m) */
#define NT 120    /* around */
#define NZ 10     /* down */
#define FM_PI 3.14159265358979323846

/* A vertical cylindrical band, wavy in depth so it is not a cone-free
 * trivial case, as a triangle soup of one part. */
static fm_mesh *ring_mesh(void)
{
    fm_mesh *m = fm_mesh_create();
    if (!m)
        return NULL;
    for (int j = 0; j <= NZ; j++)
        for (int i = 0; i < NT; i++) {
            double t = 2 * FM_PI * i / NT, z = -H * j / NZ;
            double r = R + 300.0 * sin(2 * t) * (1.0 + z / H);
            fm_mesh_add_vertex(m, 400000.0 + r * cos(t), 3700000.0 + r * sin(t), z);
        }
    for (int j = 0; j < NZ; j++)
        for (int i = 0; i < NT; i++) {
            int32_t a = j * NT + i, b = j * NT + (i + 1) % NT;
            int32_t c = a + NT, d = b + NT;
            fm_mesh_add_triangle(m, a, c, b, 0);
            fm_mesh_add_triangle(m, b, c, d, 0);
        }
    return m;
}

static void test_ring_is_cut_and_fits(void)
{
    fm_mesh *in = ring_mesh();
    CHECK(in != NULL);
    fm_surface *s = NULL;
    fm_error err;
    CHECK(fm_repair(in, NULL, &s, &err) == FM_OK);
    CHECK_EQ(fm_surface_nsheets(s), 1);
    CHECK_EQ(fm_surface_sheet_nloops(s, 0), 2);
    fm_model *m = NULL, *m2 = NULL;
    CHECK(fm_model_build("ring", s, NULL, &m, &err) == FM_OK);
    CHECK(fm_model_build("ring", s, NULL, &m2, &err) == FM_OK);
    if (!m || !m2)
        return;
    size_t ns = fm_model_nsheets(m);
    CHECK(ns >= 2);
    CHECK(fm_model_ncuts(m) >= 2);
    for (size_t i = 0; i < ns; i++) {
        const fm_sheet_report *r = fm_model_report(m, i);
        CHECK_EQ(r->repair_sheet, 0);
        CHECK(r->to_surface_rms < 5.0);
        CHECK(r->to_surface_max < 50.0);
        CHECK(r->from_trimmed_rms < 5.0);
        CHECK(r->from_trimmed_max < 50.0);
        CHECK(r->outline_max < 250.0);
    }
    /* Cuts run rim to rim along the band, between two model sheets, and
     * the same input gives the same cuts. */
    CHECK_EQ(fm_model_ncuts(m), fm_model_ncuts(m2));
    for (size_t c = 0; c < fm_model_ncuts(m); c++) {
        size_t n, n2;
        long sh[2], sh2[2];
        const double *p = fm_model_cut(m, c, &n, sh);
        const double *p2 = fm_model_cut(m2, c, &n2, sh2);
        CHECK(n >= 2);
        CHECK_EQ(n, n2);
        CHECK(sh[0] >= 0 && sh[1] >= 0 && sh[0] != sh[1]);
        CHECK(sh[0] < (long)ns && sh[1] < (long)ns);
        CHECK_EQ(sh[0], sh2[0]);
        CHECK_EQ(sh[1], sh2[1]);
        CHECK(fabs(p[2] - p[3 * (n - 1) + 2]) > 0.99 * H);
        for (size_t q = 0; q < 3 * n && n == n2; q++)
            CHECK(p[q] == p2[q]);
    }
    fm_model_destroy(m);
    fm_model_destroy(m2);
    fm_surface_destroy(s);
    fm_mesh_destroy(in);
}

/* A planar disk with a hole stays one sheet: nothing to cut. */
static void test_flat_annulus_not_cut(void)
{
    fm_mesh *in = fm_mesh_create();
    for (int j = 0; j <= 4; j++)
        for (int i = 0; i < 60; i++) {
            double t = 2 * FM_PI * i / 60, r = 2000.0 + 500.0 * j;
            fm_mesh_add_vertex(in, r * cos(t), r * sin(t), 0.02 * r * cos(t));
        }
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 60; i++) {
            int32_t a = j * 60 + i, b = j * 60 + (i + 1) % 60, c = a + 60, d = b + 60;
            fm_mesh_add_triangle(in, a, b, c, 0);
            fm_mesh_add_triangle(in, b, d, c, 0);
        }
    fm_surface *s = NULL;
    fm_model *m = NULL;
    fm_error err;
    CHECK(fm_repair(in, NULL, &s, &err) == FM_OK);
    CHECK(fm_model_build("annulus", s, NULL, &m, &err) == FM_OK);
    if (m) {
        CHECK_EQ(fm_model_nsheets(m), 1);
        CHECK_EQ(fm_model_ncuts(m), 0);
        CHECK_EQ(fm_model_nloops(m, 0), 2);
    }
    fm_model_destroy(m);
    fm_surface_destroy(s);
    fm_mesh_destroy(in);
}

int main(void)
{
    static const fm_test_case cases[] = {
        {"ring_is_cut_and_fits", test_ring_is_cut_and_fits},
        {"flat_annulus_not_cut", test_flat_annulus_not_cut},
    };
    return fm_test_run(cases, sizeof cases / sizeof cases[0]);
}
