/* cons_grid (src/mesh/cons_grid.c) against a scan of every constraint:
 * random edges against random constraints, on a coarse lattice so that
 * touching, collinear and shared ends are common, with nodes moved in
 * between (in and out of the grid's first box) as slide_boundary moves
 * them; the answers must be the same, query by query. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "fm_test.h"
#include "remesh_internal.h"

static uint64_t state = 0x2545f4914f6cdd1du;

static unsigned rnd(unsigned n)
{
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return (unsigned)(state % n);
}

static int scan(const double *uv, const int32_t *cons, size_t ncons, int32_t p, int32_t q)
{
    for (size_t k = 0; k < ncons; k++) {
        int32_t c = cons[2 * k], d = cons[2 * k + 1];
        if (c == p || c == q || d == p || d == q)
            continue;
        if (segments_cross(uv + 2 * p, uv + 2 * q, uv + 2 * c, uv + 2 * d))
            return 1;
    }
    return 0;
}

/* np nodes on a lattice of side `side` (spread: a few far outliers make
 * long constraints and a wide grid), ncons constraints among them. */
static void check_round(size_t np, size_t ncons, unsigned side, int outliers)
{
    double *uv = malloc(2 * np * sizeof *uv);
    int32_t *cons = calloc(2 * (ncons ? ncons : 1), sizeof *cons);
    CHECK(uv && cons);
    if (!uv || !cons) {
        free(uv);
        free(cons);
        return;
    }
    /* a walk, as a boundary's nodes are, with jumps */
    for (size_t v = 0; v < np; v++) {
        int jump = v == 0 || rnd(20) == 0;
        uv[2 * v] = jump ? rnd(side) : fabs(uv[2 * v - 2] + rnd(3) - 1.0);
        uv[2 * v + 1] = jump ? rnd(side) : fabs(uv[2 * v - 1] + rnd(3) - 1.0);
        if (outliers && rnd(50) == 0)
            uv[2 * v] += 1000.0 * side;
    }
    for (size_t k = 0; k < ncons; k++) {
        cons[2 * k] = (int32_t)rnd((unsigned)np);
        /* mostly short ones, as boundary edges are */
        cons[2 * k + 1] = rnd(20) ? (int32_t)((cons[2 * k] + 1) % (int32_t)np)
                                 : (int32_t)rnd((unsigned)np);
    }
    cons_grid *g = cons_grid_create(uv, np, cons, ncons);
    CHECK(g != NULL);
    size_t crossing = 0, wrong = 0;
    for (int i = 0; g && i < 4000; i++) {
        if (rnd(3) == 0) { /* a node moves, at times far off */
            int32_t v = (int32_t)rnd((unsigned)np);
            int far = rnd(10) == 0;
            uv[2 * v] = far ? -3.0 * side : uv[2 * v] + 0.5 * rnd(5) - 1.0;
            uv[2 * v + 1] = far ? rnd(side) : uv[2 * v + 1] + 0.5 * rnd(5) - 1.0;
            cons_grid_moved(g, uv, v);
        }
        /* mostly short edges, as the moves' are */
        int32_t p = (int32_t)rnd((unsigned)np);
        int32_t q = rnd(8) ? (int32_t)(((size_t)p + 1 + rnd(3)) % np) : (int32_t)rnd((unsigned)np);
        int want = scan(uv, cons, ncons, p, q);
        crossing += (size_t)want;
        wrong += (size_t)(cons_grid_crosses(g, uv, p, q) != want);
    }
    CHECK_EQ(wrong, 0);
    if (ncons > 10) /* the test asks about both answers */
        CHECK(crossing > 200 && crossing < 3800);
    cons_grid_destroy(g);
    free(uv);
    free(cons);
}

static void test_small(void) { check_round(12, 8, 4, 0); }
static void test_lattice(void) { check_round(400, 300, 100, 0); }
static void test_outliers(void) { check_round(600, 500, 120, 1); }
static void test_no_constraints(void) { check_round(5, 0, 3, 0); }

int main(void)
{
    static const fm_test_case cases[] = {FM_CASE(test_small), FM_CASE(test_lattice),
                                         FM_CASE(test_outliers), FM_CASE(test_no_constraints)};
    return fm_test_run(cases, sizeof cases / sizeof cases[0]);
}
