/* mesh_collapse_slivers (slivers.c): a boundary node lying on a shared
 * curve's last segment makes a triangle of no width; it is merged into
 * its boundary neighbour, no shared node moves or goes, and nothing is
 * merged where the shapes would fold or the node is shared. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fm_test.h"
#include "remesh_internal.h"

/* The curve's last segment T-E (both shared) on y = 0, the outline node M
 * between them a hair off it, and nodes A, B above: triangles (T, E, M)
 * the sliver, (E, A, M) and (M, A, B). T is the tip of the spike: the
 * boundary runs E-T (the curve) and back T-M (the outline). */
static void fan(double uv[10], double xyz[15], int32_t tri[12])
{
    const double p[5][2] = {{0, 0}, {346, 0.01}, {1015, 0}, {700, 600}, {200, 500}};
    for (int k = 0; k < 5; k++) {
        uv[2 * k] = p[k][0];
        uv[2 * k + 1] = p[k][1];
        xyz[3 * k] = p[k][0];
        xyz[3 * k + 1] = p[k][1];
        xyz[3 * k + 2] = 0;
    }
    /* T 0, M 1, E 2, A 3, B 4; counter-clockwise in uv */
    const int32_t t[12] = {0, 2, 1, 2, 3, 1, 1, 3, 4, 0, 0, 0};
    memcpy(tri, t, sizeof t);
}

static void test_merges_outline_node(void)
{
    double uv[10], xyz[15];
    int32_t tri[12];
    fan(uv, xyz, tri);
    int64_t shared[5] = {7, -1, 8, -1, -1};
    size_t nt = 3;
    CHECK_EQ(mesh_collapse_slivers(uv, xyz, tri, &nt, shared, 5, 1.0), 1);
    CHECK_EQ(nt, 2);
    int uses_m = 0, uses_t = 0, uses_e = 0;
    for (size_t k = 0; k < 3 * nt; k++) {
        uses_m += tri[k] == 1;
        uses_t += tri[k] == 0;
        uses_e += tri[k] == 2;
    }
    CHECK_EQ(uses_m, 0); /* the outline node went */
    CHECK(uses_t > 0 && uses_e > 0); /* the shared ones stay */
}

static void test_keeps_shared_or_folding(void)
{
    double uv[10], xyz[15];
    int32_t tri[12];
    fan(uv, xyz, tri);
    int64_t shared[5] = {7, 9, 8, -1, -1}; /* M shared: it stays */
    size_t nt = 3;
    CHECK_EQ(mesh_collapse_slivers(uv, xyz, tri, &nt, shared, 5, 1.0), 0);
    CHECK_EQ(nt, 3);
    /* B placed so that (M, A, B) would turn over as (T, A, B): kept */
    fan(uv, xyz, tri);
    uv[8] = xyz[12] = 150;
    uv[9] = xyz[13] = 60;
    int64_t fold[5] = {7, -1, 8, -1, -1};
    CHECK_EQ(mesh_collapse_slivers(uv, xyz, tri, &nt, fold, 5, 1.0), 0);
    CHECK_EQ(nt, 3);
    /* no sliver: nothing to do */
    fan(uv, xyz, tri);
    uv[3] = xyz[4] = 200; /* M well off the line */
    int64_t none[5] = {7, -1, 8, -1, -1};
    CHECK_EQ(mesh_collapse_slivers(uv, xyz, tri, &nt, none, 5, 1.0), 0);
    CHECK_EQ(nt, 3);
}

FM_TEST_MAIN(FM_CASE(test_merges_outline_node), FM_CASE(test_keeps_shared_or_folding))
