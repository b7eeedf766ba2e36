/* Rectangular elements (fm_tile.h): rows and columns of a planar fault,
 * a curved one, and tiles of two meeting faults that stop at their
 * junction without meeting, with the gap measured. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "fm_test.h"
#include "fm_test_mesh.h"
#include "fm_tile.h"

static const double D45 = 0.70710678118654752440;

/* Strike north, dipping 45 degrees east, top at sea level. */
static void dipping(const void *ctx, double s, double t, double p[3])
{
    (void)ctx;
    p[0] = 500000 + t * D45;
    p[1] = 3700000 + s;
    p[2] = -t * D45;
}

/* A quarter of a vertical cylinder of radius 20 km. */
static void curved(const void *ctx, double s, double t, double p[3])
{
    (void)ctx;
    double a = s / 20000;
    p[0] = 20000 * cos(a);
    p[1] = 20000 * sin(a);
    p[2] = -t;
}

static void test_planar_rows_and_columns(void)
{
    fm_mesh *m = fm_test_grid_mesh(20000, 10000, 500, dipping, NULL);
    fm_tiles *t = NULL;
    CHECK_EQ(fm_tiles_create(m, 1, 2000, &t, NULL), FM_OK);
    CHECK_EQ(fm_tiles_count(t), 50); /* 5 rows of 10 */
    const fm_tile_fault *f = fm_tiles_fault(t, 0);
    CHECK(fabs(f->area_tiles / f->area_triangles - 1) < 1e-6);
    CHECK(f->flatness_max < 1e-6);
    for (size_t i = 0; i < fm_tiles_count(t); i++) {
        const fm_tile *tl = fm_tiles_get(t, i);
        CHECK(fabs(tl->length - 2000) < 1e-6 && fabs(tl->width - 2000) < 1e-6);
        /* strike north, dipping east */
        CHECK(fabs(tl->strike[1] - 1) < 1e-9);
        CHECK(fabs(tl->dip[0] - D45) < 1e-9 && fabs(tl->dip[2] + D45) < 1e-9);
        double c[4][3];
        fm_tile_corners(tl, c);
        /* EQSim's order: top, bottom at the start of the strike, then the
         * end's bottom and top, counterclockwise from above */
        CHECK(c[0][2] > c[1][2] && c[3][2] > c[2][2] && c[0][1] < c[3][1]);
        CHECK(c[0][2] <= 1e-9 && c[1][2] >= -10000 * D45 - 1e-6);
    }
    CHECK_EQ(fm_tiles_get(t, 0)->row, 0);
    CHECK_EQ(fm_tiles_stats(t)->meeting, 0);
    fm_tiles_destroy(t);
    fm_mesh_destroy(m);
}

static void test_curved_area(void)
{
    fm_mesh *m = fm_test_grid_mesh(31416, 12000, 250, curved, NULL);
    fm_tiles *t = NULL;
    CHECK_EQ(fm_tiles_create(m, 1, 2000, &t, NULL), FM_OK);
    const fm_tile_fault *f = fm_tiles_fault(t, 0);
    CHECK(fabs(f->area_tiles / f->area_triangles - 1) < 0.01);
    /* chords of 2 km on a 20 km radius: sagitta 25 m */
    CHECK(fm_tiles_stats(t)->flatness_p99 < 30);
    CHECK(fm_tiles_stats(t)->flatness_p99 > 5);
    fm_tiles_destroy(t);
    fm_mesh_destroy(m);
}

/* Fault 0 the vertical plane x = 0, y in [-10, 10] km; fault 1 a vertical
 * plane from the origin at angle a from fault 0, ending on it; both nz
 * rows of 500 m deep (at most 20), meshed at 500 m with the junction's
 * nodes shared. With slant, fault 1 also leans along fault 0 as far as
 * it is deep, so that their junction (the diagonals of fault 0's
 * squares) runs down at 45 degrees across the rows. */
static fm_mesh *tee_slanted(double a, int slant, int nz)
{
    fm_mesh *m = fm_mesh_create();
    const int ns = 40;
    for (int k = 0; k <= nz; k++)
        for (int i = 0; i <= ns; i++)
            fm_mesh_add_vertex(m, 0, -10000 + 500.0 * i, -500.0 * k);
    int32_t base = (int32_t)fm_mesh_nvertices(m);
    const int nb = 20;
    for (int k = 0; k <= nz; k++)
        for (int i = 1; i <= nb; i++)
            fm_mesh_add_vertex(m, 500.0 * i * sin(a), 500.0 * i * cos(a) + 500.0 * slant * k,
                               -500.0 * k);
    for (int k = 0; k < nz; k++)
        for (int i = 0; i < ns; i++) {
            int32_t p = k * (ns + 1) + i, q = p + 1, r = p + ns + 1, s = r + 1;
            fm_mesh_add_triangle(m, p, q, s, 0);
            fm_mesh_add_triangle(m, p, s, r, 0);
        }
    for (int k = 0; k < nz; k++)
        for (int i = 0; i < nb; i++) {
            /* column 0 of fault 1 is fault 0's node at y = 0 */
            int32_t p = i == 0 ? k * (ns + 1) + ns / 2 + slant * k : base + k * nb + i - 1;
            int32_t r = i == 0 ? (k + 1) * (ns + 1) + ns / 2 + slant * (k + 1)
                               : base + (k + 1) * nb + i - 1;
            int32_t q = base + k * nb + i, s = base + (k + 1) * nb + i;
            fm_mesh_add_triangle(m, p, q, s, 1);
            fm_mesh_add_triangle(m, p, s, r, 1);
        }
    return m;
}

static fm_mesh *tee(double a) { return tee_slanted(a, 0, 20); }

static void test_tee_junction(void)
{
    const double angles[3] = {3.14159265358979 / 2, 3.14159265358979 / 3, 0.3};
    for (int k = 0; k < 3; k++) {
        fm_mesh *m = tee(angles[k]);
        fm_tiles *t = NULL;
        CHECK_EQ(fm_tiles_create(m, 2, 2000, &t, NULL), FM_OK);
        const fm_tile_stats *st = fm_tiles_stats(t);
        CHECK_EQ(st->meeting, 0);
        CHECK_EQ(st->dropped, 0);
        /* fault 0's contour stops at the junction: 2 x 5 columns per row */
        CHECK_EQ(fm_tiles_fault(t, 0)->ntiles, 50);
        CHECK_EQ(fm_tiles_njunctions(t), 1);
        const fm_tile_junction *j = fm_tiles_junction(t, 0);
        CHECK(j->a == 0 && j->b == 1 && fabs(j->length - 10000) < 1e-6);
        CHECK(j->gap_max <= 1000);
        CHECK(j->over_half == 0);
        for (int f = 0; f < 2; f++) {
            const fm_tile_fault *tf = fm_tiles_fault(t, (size_t)f);
            CHECK(tf->area_tiles / tf->area_triangles > 0.97);
            CHECK(tf->area_tiles / tf->area_triangles < 1 + 1e-9);
        }
        fm_tiles_destroy(t);
        fm_mesh_destroy(m);
    }
}

/* A junction that runs across the rows at a slant and meets at a small
 * angle: each row's tiles end on it in a
 * staircase, the cut that keeps the faults apart takes a strip off one
 * tile of each pair, and wedges of surface stay bare between the steps
 * (on the whole CFM at 2 km, 31 faults lost over 3 % of their area so,
 * Ocotillo 22 %). The tiles grow into the strips and squares fill the
 * wedges, so each fault keeps its area within 3 %, the tiles still
 * apart. */
/* Field by field (the struct's padding is not its value). */
static int same_tile(const fm_tile *a, const fm_tile *b)
{
    int same = a->fault == b->fault && a->triangle == b->triangle && a->row == b->row &&
               a->length == b->length && a->width == b->width && a->flatness == b->flatness &&
               a->shrunk == b->shrunk && a->part == b->part;
    for (int d = 0; d < 3; d++)
        same &= a->centre[d] == b->centre[d] && a->strike[d] == b->strike[d] &&
                a->dip[d] == b->dip[d];
    return same;
}

static void test_slanted_junction_keeps_area(void)
{
    /* each failed without the growing (fault 1 at 0.963, 0.948, 0.948 and
     * 0.965 of its area) */
    const struct {
        double a;
        int nz;
        double size;
    } c[4] = {{0.5, 8, 2100}, {0.2, 14, 3000}, {0.3, 20, 3000}, {0.8, 8, 2700}};
    for (int k = 0; k < 4; k++) {
        fm_mesh *m = tee_slanted(c[k].a, 1, c[k].nz);
        fm_tiles *t = NULL;
        CHECK_EQ(fm_tiles_create(m, 2, c[k].size, &t, NULL), FM_OK);
        const fm_tile_stats *st = fm_tiles_stats(t);
        CHECK_EQ(st->meeting, 0);
        CHECK(st->flatness_max < 1);
        CHECK_EQ(fm_tiles_njunctions(t), 1);
        CHECK(fm_tiles_junction(t, 0)->over_half == 0);
        for (int f = 0; f < 2; f++) {
            const fm_tile_fault *tf = fm_tiles_fault(t, (size_t)f);
            CHECK(fabs(tf->area_tiles / tf->area_triangles - 1) <= 0.03);
        }
        /* the faults tiled on three threads: the same tiles */
        fm_tiles *t3 = NULL;
        CHECK_EQ(fm_tiles_create_parts(m, NULL, 2, c[k].size, 3, &t3, NULL), FM_OK);
        CHECK_EQ(fm_tiles_count(t3), fm_tiles_count(t));
        for (size_t i = 0; i < fm_tiles_count(t) && i < fm_tiles_count(t3); i++)
            CHECK(same_tile(fm_tiles_get(t, i), fm_tiles_get(t3, i)));
        fm_tiles_destroy(t3);
        fm_tiles_destroy(t);
        fm_mesh_destroy(m);
    }
}

/* One fault of two parts (sheets) forking from a vertical branch line,
 * nothing beyond it: part 0 the plane x = 0, part 1 a plane at angle a
 * from it, each 10 km long and deep, meshed at 500 m sharing the branch
 * line's nodes (as the CFM's Ocotillo fault, whose strands fork at about
 * 25 degrees, 0.78 of its area at 2 km). Tiled whole, a row's contour runs
 * up one strand, round the fork and down the other, and its tiles cut the
 * corner: 0.93 and 0.88 of the area at a = 0.25 and sizes of 1.5 and
 * 3 km. Tiled part by part, each strand keeps its area, and the two
 * strands' tiles are kept apart as two faults' are. */
static fm_mesh *fork_mesh(double a, int32_t *part)
{
    fm_mesh *m = fm_mesh_create();
    const int ns = 20, nz = 20;
    for (int k = 0; k <= nz; k++)
        for (int i = 0; i <= ns; i++)
            fm_mesh_add_vertex(m, 0, 500.0 * i, -500.0 * k);
    int32_t base = (int32_t)fm_mesh_nvertices(m);
    for (int k = 0; k <= nz; k++)
        for (int i = 1; i <= ns; i++)
            fm_mesh_add_vertex(m, 500.0 * i * sin(a), 500.0 * i * cos(a), -500.0 * k);
    size_t np = 0;
    for (int k = 0; k < nz; k++)
        for (int i = 0; i < ns; i++) {
            int32_t p = k * (ns + 1) + i, q = p + 1, r = p + ns + 1, s = r + 1;
            fm_mesh_add_triangle(m, p, q, s, 0);
            fm_mesh_add_triangle(m, p, s, r, 0);
            /* column 0 of part 1 is the branch line, part 0's */
            int32_t p1 = i == 0 ? k * (ns + 1) : base + k * ns + i - 1;
            int32_t r1 = i == 0 ? (k + 1) * (ns + 1) : base + (k + 1) * ns + i - 1;
            int32_t q1 = base + k * ns + i, s1 = base + (k + 1) * ns + i;
            fm_mesh_add_triangle(m, p1, q1, s1, 0);
            fm_mesh_add_triangle(m, p1, s1, r1, 0);
            part[np++] = 0;
            part[np++] = 0;
            part[np++] = 1;
            part[np++] = 1;
        }
    return m;
}

static void test_fork_tiled_by_parts(void)
{
    const double a[2] = {0.6, 0.25}, size[2] = {1500, 3000};
    int32_t *part = malloc(1600 * sizeof *part);
    CHECK(part != NULL);
    for (int k = 0; part && k < 4; k++) {
        fm_mesh *m = fork_mesh(a[k / 2], part);
        CHECK_EQ(fm_mesh_ntriangles(m), 1600);
        fm_tiles *t = NULL;
        CHECK_EQ(fm_tiles_create_parts(m, part, 1, size[k % 2], 1, &t, NULL), FM_OK);
        const fm_tile_fault *tf = fm_tiles_fault(t, 0);
        CHECK(fabs(tf->area_tiles / tf->area_triangles - 1) <= 0.03);
        CHECK_EQ(fm_tiles_stats(t)->meeting, 0);
        /* each tile of one part, and both parts tiled */
        int seen[3] = {0, 0, 0};
        for (size_t i = 0; i < fm_tiles_count(t); i++) {
            int32_t p = fm_tiles_get(t, i)->part;
            CHECK(p >= 0 && p <= 2);
            seen[p >= 0 && p <= 2 ? p : 0] = 1;
        }
        CHECK(seen[1] && seen[2]);
        fm_tiles_destroy(t);
        /* a fault of one part is tiled whole, as without parts */
        for (size_t i = 0; i < 1600; i++)
            part[i] = 7;
        CHECK_EQ(fm_tiles_create_parts(m, part, 1, size[k % 2], 1, &t, NULL), FM_OK);
        for (size_t i = 0; i < fm_tiles_count(t); i++)
            CHECK_EQ(fm_tiles_get(t, i)->part, 0);
        fm_tiles_destroy(t);
        fm_mesh_destroy(m);
    }
    free(part);
}

/* Fault 1 reaching fault 0 only as a strip 500 m tall and 3 km long from
 * its body (the tee's fault 1 with its triangles below 500 m gone for
 * x < 3 km): its rows' contours pass below the strip or leave it to
 * slivers, and the junction was bare of its tiles (as on the CFM's
 * Western Deep fault against Oak Ridge, 2.7 km at 2 km). A tile on the
 * strip's edge covers it. */
static void test_thin_strip_to_junction(void)
{
    fm_mesh *tee_m = tee(3.14159265358979 / 2);
    fm_mesh *m = fm_mesh_create();
    const double *x = fm_mesh_vertices(tee_m);
    for (size_t v = 0; v < fm_mesh_nvertices(tee_m); v++)
        fm_mesh_add_vertex(m, x[3 * v], x[3 * v + 1], x[3 * v + 2]);
    const int32_t *tri = fm_mesh_triangles(tee_m), *tag = fm_mesh_tags(tee_m);
    for (size_t i = 0; i < fm_mesh_ntriangles(tee_m); i++) {
        const double *a = x + 3 * (size_t)tri[3 * i], *b = x + 3 * (size_t)tri[3 * i + 1],
                     *c = x + 3 * (size_t)tri[3 * i + 2];
        double cx = (a[0] + b[0] + c[0]) / 3, cz = (a[2] + b[2] + c[2]) / 3;
        if (tag[i] == 1 && cx < 3000 && cz < -500)
            continue;
        fm_mesh_add_triangle(m, tri[3 * i], tri[3 * i + 1], tri[3 * i + 2], tag[i]);
    }
    fm_tiles *t = NULL;
    CHECK_EQ(fm_tiles_create(m, 2, 2000, &t, NULL), FM_OK);
    CHECK_EQ(fm_tiles_stats(t)->meeting, 0);
    CHECK_EQ(fm_tiles_njunctions(t), 1);
    const fm_tile_junction *j = fm_tiles_junction(t, 0);
    CHECK(fabs(j->length - 500) < 1e-6);
    CHECK(j->gap_max <= 1000);
    fm_tiles_destroy(t);
    fm_mesh_destroy(m);
    fm_mesh_destroy(tee_m);
}

/* The faults' meshes in one set, not sharing nodes, fault f the mesh
 * parts[f]; the parts destroyed. */
static fm_mesh *joined(fm_mesh **parts, int n)
{
    fm_mesh *m = fm_mesh_create();
    for (int f = 0; f < n; f++) {
        int32_t base = (int32_t)fm_mesh_nvertices(m);
        const double *x = fm_mesh_vertices(parts[f]);
        for (size_t v = 0; v < fm_mesh_nvertices(parts[f]); v++)
            fm_mesh_add_vertex(m, x[3 * v], x[3 * v + 1], x[3 * v + 2]);
        const int32_t *tri = fm_mesh_triangles(parts[f]);
        for (size_t i = 0; i < fm_mesh_ntriangles(parts[f]); i++)
            fm_mesh_add_triangle(m, base + tri[3 * i], base + tri[3 * i + 1],
                                 base + tri[3 * i + 2], f);
        fm_mesh_destroy(parts[f]);
    }
    return m;
}

/* Fault 1 crossing fault 0 at a slant: tile corners reach across, and are
 * cut back. */
static void tilted(const void *ctx, double s, double t, double p[3])
{
    (void)ctx;
    p[0] = -5000 + s;
    p[1] = 0.3 * (-5000 + s) + 0.8 * t;
    p[2] = -t;
}

static void vertical(const void *ctx, double s, double t, double p[3])
{
    (void)ctx;
    p[0] = 0;
    p[1] = -10000 + s;
    p[2] = -t;
}

static void test_crossing_faults_cut_apart(void)
{
    /* Two separate meshes in one set, not sharing nodes: the worst case,
     * tiles that run through each other, must still come apart. */
    fm_mesh *parts[2] = {fm_test_grid_mesh(20000, 8000, 500, vertical, NULL),
                         fm_test_grid_mesh(10000, 8000, 500, tilted, NULL)};
    fm_mesh *m = joined(parts, 2);
    fm_tiles *t = NULL;
    CHECK_EQ(fm_tiles_create(m, 2, 2000, &t, NULL), FM_OK);
    CHECK_EQ(fm_tiles_stats(t)->meeting, 0);
    CHECK(fm_tiles_stats(t)->shrunk > 0);
    fm_tiles_destroy(t);
    fm_mesh_destroy(m);
}

/* A small fault dipping 20 degrees east, 6 by 5 km, crossed 880 m apart
 * by five long faults dipping 50 or 70 degrees that strike at an angle to
 * it (as the CFM's Laguna Salada east branch is by its neighbours, 0.956
 * of its area at 2 km): each crossing takes a strip off the small fault,
 * where the cut loses less, and it ended 0.937 and 0.915 of its area
 * while its neighbours kept theirs. Tiled again with its tiles favoured,
 * it keeps its area, and the others stay within 3 % of theirs. */
static double small_dip;

static void low_dip(const void *ctx, double s, double t, double p[3])
{
    (void)ctx;
    p[0] = t * cos(small_dip);
    p[1] = s;
    p[2] = -t * sin(small_dip);
}

typedef struct crosser {
    double x0, strike, dip;
} crosser;

static void crossing(const void *ctx, double s, double t, double p[3])
{
    const crosser *c = ctx;
    double h = t * cos(c->dip);
    p[0] = c->x0 + (s - 8000) * sin(c->strike) + h * cos(c->strike);
    p[1] = 3000 + (s - 8000) * cos(c->strike) - h * sin(c->strike);
    p[2] = -t * sin(c->dip);
}

static void test_crossed_fault_keeps_area(void)
{
    const double deg = 3.14159265358979323846 / 180;
    const struct {
        double strike, dip;
    } c[2] = {{0.3, 50 * deg}, {0.5, 70 * deg}};
    small_dip = 20 * deg;
    for (int k = 0; k < 2; k++) {
        crosser cr[5];
        fm_mesh *parts[6] = {fm_test_grid_mesh(6000, 5000, 250, low_dip, NULL)};
        for (int j = 0; j < 5; j++) {
            cr[j] = (crosser){500 + 880.0 * j, c[k].strike, c[k].dip};
            parts[j + 1] = fm_test_grid_mesh(16000, 6000, 250, crossing, &cr[j]);
        }
        fm_mesh *m = joined(parts, 6);
        fm_tiles *t = NULL;
        CHECK_EQ(fm_tiles_create(m, 6, 2000, &t, NULL), FM_OK);
        CHECK_EQ(fm_tiles_stats(t)->meeting, 0);
        for (size_t f = 0; f < 6; f++) {
            const fm_tile_fault *tf = fm_tiles_fault(t, f);
            CHECK(fabs(tf->area_tiles / tf->area_triangles - 1) <= 0.03);
        }
        fm_tiles_destroy(t);
        fm_mesh_destroy(m);
    }
}

/* A vertical fault whose top edge climbs along strike, from 4 km deep to
 * sea level over 20 km (as a blind tip or a sea floor does): the middle
 * contour of the top rows misses the deep end, which the quarter contours
 * tile, and each tile's width follows the surface in its columns. Found on
 * CFM faults (Padre Juan, San Pedro Escarpment) whose tiled area was 20 %
 * short or 150 % over. */
static void climbing(const void *ctx, double s, double t, double p[3])
{
    (void)ctx;
    double top = -4000 + 4000 * s / 20000, bottom = -10000;
    p[0] = 0;
    p[1] = s;
    p[2] = top + (bottom - top) * t / 10000;
}

static void test_climbing_top_edge(void)
{
    fm_mesh *m = fm_test_grid_mesh(20000, 10000, 250, climbing, NULL);
    fm_tiles *t = NULL;
    CHECK_EQ(fm_tiles_create(m, 1, 2000, &t, NULL), FM_OK);
    const fm_tile_fault *f = fm_tiles_fault(t, 0);
    /* 1.005; 0.973 without the quarter contours */
    CHECK(fabs(f->area_tiles / f->area_triangles - 1) < 0.02);
    for (size_t i = 0; i < fm_tiles_count(t); i++) {
        const fm_tile *tl = fm_tiles_get(t, i);
        CHECK(tl->width <= 1.5 * 2000);
    }
    fm_tiles_destroy(t);
    fm_mesh_destroy(m);
}

/* A top edge with a valley: at sea level, dipping to 1.8 km deep over
 * 8 km in the middle (a sea-floor canyon). The top row's middle contour
 * stops on both sides of the valley; what lies below it must be counted
 * about once. It is not quite: the contour's open ends and the quarter
 * contours' tiles both take some of it (1.023 of the area). */
static void valley(const void *ctx, double s, double t, double p[3])
{
    (void)ctx;
    double d = fabs(s - 10000), top = d < 4000 ? -1800 * (1 - d / 4000) : 0, bottom = -10000;
    p[0] = 0;
    p[1] = s;
    p[2] = top + (bottom - top) * t / 10000;
}

static void test_valley_in_top_edge(void)
{
    fm_mesh *m = fm_test_grid_mesh(20000, 10000, 250, valley, NULL);
    fm_tiles *t = NULL;
    CHECK_EQ(fm_tiles_create(m, 1, 2000, &t, NULL), FM_OK);
    const fm_tile_fault *f = fm_tiles_fault(t, 0);
    CHECK(fabs(f->area_tiles / f->area_triangles - 1) < 0.03);
    fm_tiles_destroy(t);
    fm_mesh_destroy(m);
}

/* A detachment: 20 x 20 km dipping about one degree east, undulating by
 * 60 m along strike. A depth row holds kilometres of it down dip; the
 * tiles must still sit on it (a centre moved down such a plane to a row's
 * level went thousands of kilometres on the CFM's detachments). */
static void detachment(const void *ctx, double s, double t, double p[3])
{
    (void)ctx;
    p[0] = 400000 + t;
    p[1] = 3700000 + s;
    p[2] = -5000 - 0.0005 * t + 60 * sin(s / 3000) + 40 * sin(t / 1700);
}

static void test_detachment_tiles_on_it(void)
{
    fm_mesh *m = fm_test_grid_mesh(20000, 20000, 500, detachment, NULL);
    fm_tiles *t = NULL;
    CHECK_EQ(fm_tiles_create(m, 1, 2000, &t, NULL), FM_OK);
    const double *x = fm_mesh_vertices(m);
    double worst = 0;
    for (size_t i = 0; i < fm_tiles_count(t); i++) {
        const fm_tile *tl = fm_tiles_get(t, i);
        double best = INFINITY;
        for (size_t v = 0; v < fm_mesh_nvertices(m); v++)
            best = fmin(best, hypot(hypot(x[3 * v] - tl->centre[0], x[3 * v + 1] - tl->centre[1]),
                                    x[3 * v + 2] - tl->centre[2]));
        worst = fmax(worst, best);
    }
    CHECK(fm_tiles_count(t) > 0);
    CHECK(worst < 500); /* within a grid spacing of a vertex: on the surface */
    fm_tiles_destroy(t);
    fm_mesh_destroy(m);
}

/* A ramp running into a flat, as the CFM's Padre Juan fault (lower) and
 * many thrusts and detachments do: 5 km down dip at 60 degrees, then
 * 15 km at 4 degrees the same way, 24 km along strike. Rows by depth put
 * the whole flat in one or two bands, its tiles anywhere in them (0.74 of
 * Padre Juan's area at 2 km; here the flat's tiles stand off it, flatness
 * p99 over 5 % of the size); rows by levels up the mean plane's dip follow
 * the flat down dip. */
static void ramp_flat(const void *ctx, double s, double t, double p[3])
{
    (void)ctx;
    const double c60 = 0.5, s60 = 0.86602540378443865, c4 = 0.99756405025982425,
                 s4 = 0.069756473744125301;
    double r = fmin(t, 5000), f = fmax(t - 5000, 0);
    p[0] = 300000 + r * c60 + f * c4;
    p[1] = 3800000 + s;
    p[2] = -500 - r * s60 - f * s4;
}

static void test_ramp_into_flat(void)
{
    fm_mesh *m = fm_test_grid_mesh(24000, 20000, 500, ramp_flat, NULL);
    fm_tiles *t = NULL;
    CHECK_EQ(fm_tiles_create(m, 1, 2000, &t, NULL), FM_OK);
    const fm_tile_fault *f = fm_tiles_fault(t, 0);
    CHECK(fabs(f->area_tiles / f->area_triangles - 1) < 0.03);
    CHECK(fm_tiles_stats(t)->flatness_p99 < 0.05 * 2000);
    /* every tile on the surface: its centre within a grid cell of a vertex */
    const double *x = fm_mesh_vertices(m);
    double worst = 0;
    for (size_t i = 0; i < fm_tiles_count(t); i++) {
        const fm_tile *tl = fm_tiles_get(t, i);
        double best = INFINITY;
        for (size_t v = 0; v < fm_mesh_nvertices(m); v++)
            best = fmin(best, hypot(hypot(x[3 * v] - tl->centre[0], x[3 * v + 1] - tl->centre[1]),
                                    x[3 * v + 2] - tl->centre[2]));
        worst = fmax(worst, best);
    }
    CHECK(worst < 500);
    fm_tiles_destroy(t);
    fm_mesh_destroy(m);
}

/* A vertical fault, a parallelogram 9 km along strike and 5 km down,
 * whose ends slant at 35 degrees from the vertical and whose top and
 * bottom edges climb 1 km in 2 along strike (p = (0, s + 0.7 t,
 * -t - s / 2)), as outlines and junctions crossing the rows at a slant do:
 * a row's end tile stands past the edge on one side of its middle and
 * leaves a wedge bare on the other, and on so small a fault the two do not
 * even out (1.09 of the area with 17 tiles). Its edge tiles cut into a
 * quadtree of smaller rectangles follow the outline: within 3 %, and no
 * rectangle's centre past it. */
static void sheared(const void *ctx, double s, double t, double p[3])
{
    (void)ctx;
    p[0] = 0;
    p[1] = s + 0.7 * t;
    p[2] = -t - 0.5 * s;
}

static void test_slanted_edges(void)
{
    fm_mesh *m = fm_test_grid_mesh(9000, 5000, 250, sheared, NULL);
    fm_tiles *t = NULL;
    CHECK_EQ(fm_tiles_create(m, 1, 2000, &t, NULL), FM_OK);
    const fm_tile_fault *f = fm_tiles_fault(t, 0);
    CHECK(fabs(f->area_tiles / f->area_triangles - 1) < 0.03);
    CHECK(fm_tiles_stats(t)->flatness_max < 1e-6);
    for (size_t i = 0; i < fm_tiles_count(t); i++) {
        const fm_tile *tl = fm_tiles_get(t, i);
        /* the centre's (s, t) on the parallelogram */
        double s = (tl->centre[1] + 0.7 * tl->centre[2]) / 0.65, d = -tl->centre[2] - 0.5 * s;
        CHECK(s >= -1e-6 && s <= 9000 + 1e-6 && d >= -1e-6 && d <= 5000 + 1e-6);
    }
    fm_tiles_destroy(t);
    fm_mesh_destroy(m);
}

static void test_bad_input(void)
{
    fm_mesh *m = fm_test_grid_mesh(2000, 2000, 500, vertical, NULL);
    fm_tiles *t = NULL;
    CHECK_EQ(fm_tiles_create(m, 1, 0, &t, NULL), FM_ERR_INVALID);
    CHECK_EQ(fm_tiles_create(m, 1, NAN, &t, NULL), FM_ERR_INVALID);
    CHECK_EQ(fm_tiles_create(m, 0, 1000, &t, NULL), FM_ERR_INVALID); /* tag 0 not < 0 faults */
    CHECK(t == NULL);
    fm_mesh_destroy(m);
}

FM_TEST_MAIN(FM_CASE(test_planar_rows_and_columns), FM_CASE(test_curved_area),
             FM_CASE(test_tee_junction), FM_CASE(test_slanted_junction_keeps_area),
             FM_CASE(test_fork_tiled_by_parts), FM_CASE(test_crossing_faults_cut_apart),
             FM_CASE(test_crossed_fault_keeps_area),
             FM_CASE(test_climbing_top_edge), FM_CASE(test_valley_in_top_edge),
             FM_CASE(test_detachment_tiles_on_it), FM_CASE(test_ramp_into_flat),
             FM_CASE(test_thin_strip_to_junction), FM_CASE(test_slanted_edges),
             FM_CASE(test_bad_input))
