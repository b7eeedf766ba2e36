/* Shared by the TSurf tests: exact comparison of two objects. */
#ifndef TEST_TSURF_COMMON_H
#define TEST_TSURF_COMMON_H

#include "fm_test.h"
#include "fm_tsurf.h"

/* Everything the reader keeps, compared exactly (doubles bit for bit). */
static inline int same_object(const fm_tsurf *a, const fm_tsurf *b)
{
    int before = fm_test_failed_checks;
    const fm_mesh *ma = fm_tsurf_mesh(a), *mb = fm_tsurf_mesh(b);
    size_t nv = fm_mesh_nvertices(ma), nt = fm_mesh_ntriangles(ma);
    CHECK_EQ(fm_mesh_nvertices(mb), nv);
    CHECK_EQ(fm_mesh_ntriangles(mb), nt);
    if (fm_test_failed_checks != before)
        return 0;
    CHECK(memcmp(fm_mesh_vertices(ma), fm_mesh_vertices(mb), 3 * nv * sizeof(double)) == 0);
    CHECK(memcmp(fm_mesh_triangles(ma), fm_mesh_triangles(mb), 3 * nt * sizeof(int32_t)) == 0);
    CHECK(memcmp(fm_mesh_tags(ma), fm_mesh_tags(mb), nt * sizeof(int32_t)) == 0);
    CHECK_EQ(fm_tsurf_nparts(a), fm_tsurf_nparts(b));
    CHECK_STR(fm_tsurf_name(a), fm_tsurf_name(b));
    const int64_t *ia = fm_tsurf_vertex_ids(a), *ib = fm_tsurf_vertex_ids(b);
    CHECK((ia == NULL) == (ib == NULL));
    if (ia && ib)
        CHECK(memcmp(ia, ib, nv * sizeof *ia) == 0);
    const int32_t *aa = fm_tsurf_atom_targets(a), *ab = fm_tsurf_atom_targets(b);
    CHECK((aa == NULL) == (ab == NULL));
    if (aa && ab)
        CHECK(memcmp(aa, ab, nv * sizeof *aa) == 0);
    CHECK_EQ(fm_tsurf_nheader(a), fm_tsurf_nheader(b));
    for (size_t i = 0; i < fm_tsurf_nheader(a) && i < fm_tsurf_nheader(b); i++) {
        CHECK_STR(fm_tsurf_header_key(a, i), fm_tsurf_header_key(b, i));
        CHECK_STR(fm_tsurf_header_value(a, i), fm_tsurf_header_value(b, i));
    }
    fm_tsurf_crs ca, cb;
    fm_tsurf_get_crs(a, &ca);
    fm_tsurf_get_crs(b, &cb);
    CHECK_STR(ca.name, cb.name);
    CHECK_STR(ca.projection, cb.projection);
    CHECK_STR(ca.datum, cb.datum);
    CHECK_STR(ca.axis_unit, cb.axis_unit);
    size_t np = fm_tsurf_nprops(a);
    CHECK_EQ(fm_tsurf_nprops(b), np);
    for (size_t i = 0; i < np && i < fm_tsurf_nprops(b); i++)
        CHECK_STR(fm_tsurf_prop_name(a, i), fm_tsurf_prop_name(b, i));
    if (np && np == fm_tsurf_nprops(b)) {
        CHECK(fm_tsurf_prop_values(a) && fm_tsurf_prop_values(b));
        if (fm_tsurf_prop_values(a) && fm_tsurf_prop_values(b))
            CHECK(memcmp(fm_tsurf_prop_values(a), fm_tsurf_prop_values(b),
                         nv * np * sizeof(double)) == 0);
    }
    CHECK_EQ(fm_tsurf_nbstones(a), fm_tsurf_nbstones(b));
    if (fm_tsurf_nbstones(a) == fm_tsurf_nbstones(b) && fm_tsurf_nbstones(a))
        CHECK(memcmp(fm_tsurf_bstones(a), fm_tsurf_bstones(b),
                     fm_tsurf_nbstones(a) * sizeof(int32_t)) == 0);
    CHECK_EQ(fm_tsurf_nborders(a), fm_tsurf_nborders(b));
    if (fm_tsurf_nborders(a) == fm_tsurf_nborders(b) && fm_tsurf_nborders(a))
        CHECK(memcmp(fm_tsurf_borders(a), fm_tsurf_borders(b),
                     3 * fm_tsurf_nborders(a) * sizeof(int32_t)) == 0);
    return fm_test_failed_checks == before;
}

#endif
