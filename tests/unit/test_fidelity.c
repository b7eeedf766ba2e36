/* fm_check_fidelity: nodes farther than 100 m from the original are told
 * apart by where their nearest original point lies: past the original's
 * edge (beyond_max, the reach of a filled gap) or over its inside
 * (inside_max, the fidelity proper). */
#include "fm_check.h"
#include "fm_closest.h"
#include "fm_mesh.h"
#include "fm_test.h"

/* The square [0, 2000] x [0, 2000] at z = -1000, as two sheets side by
 * side: their vertices along x = 1000 are distinct ids 2 mm apart, so
 * the edges of that seam are each used by one triangle, yet are no
 * outline. */
static fm_mesh *two_sheets(void)
{
    fm_mesh *o = fm_mesh_create();
    double x0[2] = {0, 1000.002}, x1[2] = {1000, 2000};
    for (int s = 0; s < 2; s++) {
        int32_t a = fm_mesh_add_vertex(o, x0[s], 0, -1000);
        int32_t b = fm_mesh_add_vertex(o, x1[s], 0, -1000);
        int32_t c = fm_mesh_add_vertex(o, x1[s], 2000, -1000);
        int32_t d = fm_mesh_add_vertex(o, x0[s], 2000, -1000);
        fm_mesh_add_triangle(o, a, b, c, 0);
        fm_mesh_add_triangle(o, a, c, d, 0);
    }
    return o;
}

/* One triangle per node p (tiny, so its other corners are near p). */
static void add_node(fm_mesh *m, double x, double y, double z)
{
    int32_t a = fm_mesh_add_vertex(m, x, y, z);
    int32_t b = fm_mesh_add_vertex(m, x + 0.01, y, z);
    int32_t c = fm_mesh_add_vertex(m, x, y + 0.01, z);
    fm_mesh_add_triangle(m, a, b, c, 0);
}

static void test_inside_and_beyond(void)
{
    fm_mesh *o = two_sheets(), *m = fm_mesh_create();
    add_node(m, 500, 500, -1050);   /* 50 m off, inside: within the tolerance */
    add_node(m, 1000, 1000, -1200); /* 200 m over the seam: inside */
    add_node(m, 1500, 1000, -870);  /* 130 m over the inside */
    add_node(m, 2300, 1000, -1000); /* 300 m past the edge x = 2000, in plane */
    add_node(m, 1000, -150, -1000); /* 150 m past the edge y = 0, at the seam's end */
    fm_closest_tree *t = fm_closest_tree_create(o, NULL);
    CHECK(t != NULL);
    fm_fidelity f;
    CHECK_EQ(fm_check_fidelity(m, -1, o, t, &f), FM_OK);
    CHECK_NEAR(f.max, 300, 0.02); /* a node's corners lie 0.01 m apart */
    CHECK_NEAR(f.inside_max, 200, 0.02);
    CHECK_EQ(f.inside_over, (size_t)2 * 3);  /* every corner of the two triangles */
    CHECK_NEAR(f.beyond_max, 300, 0.02);
    CHECK_EQ(f.beyond_nodes, (size_t)2 * 3);
    /* Without the original's mesh nothing is known of its outline: every
     * node counts as inside. */
    CHECK_EQ(fm_check_fidelity(m, -1, NULL, t, &f), FM_OK);
    CHECK_NEAR(f.inside_max, 300, 0.02);
    CHECK_EQ(f.beyond_nodes, (size_t)0);
    fm_closest_tree_destroy(t);
    fm_mesh_destroy(o);
    fm_mesh_destroy(m);
}

FM_TEST_MAIN(FM_CASE(test_inside_and_beyond))
