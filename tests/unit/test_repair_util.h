/* Helpers shared by the repair tests: building small meshes in code and
 * checking the invariants every repaired sheet must satisfy. */
#ifndef TEST_REPAIR_UTIL_H
#define TEST_REPAIR_UTIL_H

#include <stdint.h>

#include "fm_mesh.h"
#include "fm_repair.h"
#include "fm_test.h"

/* A grid of nx x ny quads with corners p0 + i*du + j*dv, each quad split
 * into (00,10,11) and (00,11,01): counter-clockwise seen from du x dv.
 * skip(i, j) (may be NULL) leaves a quad out. Returns the first vertex. */
static inline int32_t grid(fm_mesh *m, int nx, int ny, const double *p0, const double *du,
                           const double *dv, int32_t tag, int (*skip)(int, int))
{
    int32_t base = (int32_t)fm_mesh_nvertices(m);
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++)
            fm_mesh_add_vertex(m, p0[0] + i * du[0] + j * dv[0], p0[1] + i * du[1] + j * dv[1],
                               p0[2] + i * du[2] + j * dv[2]);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            if (skip && skip(i, j))
                continue;
            int32_t v00 = base + j * (nx + 1) + i, v10 = v00 + 1;
            int32_t v01 = v00 + nx + 1, v11 = v01 + 1;
            fm_mesh_add_triangle(m, v00, v10, v11, tag);
            fm_mesh_add_triangle(m, v00, v11, v01, tag);
        }
    return base;
}

static inline fm_surface *repair_with(const fm_mesh *m, const fm_repair_options *opt)
{
    fm_surface *s = NULL;
    fm_error err;
    fm_error_clear(&err);
    fm_status st = fm_repair(m, opt, &s, &err);
    if (st != FM_OK)
        fprintf(stderr, "fm_repair: %s\n", err.message);
    CHECK_EQ(st, FM_OK);
    return s;
}

static inline fm_surface *repair_default(const fm_mesh *m)
{
    return repair_with(m, NULL);
}

/* Number of triangles of mesh m having the undirected edge (a, b), and
 * among them those running a -> b. Brute force: tests are small. */
static inline void edge_use(const fm_mesh *m, int32_t a, int32_t b, int *all, int *forward)
{
    const int32_t *t = fm_mesh_triangles(m);
    *all = *forward = 0;
    for (size_t i = 0; i < fm_mesh_ntriangles(m); i++)
        for (int j = 0; j < 3; j++) {
            int32_t p = t[3 * i + j], q = t[3 * i + (j + 1) % 3];
            if (p == a && q == b) {
                (*all)++;
                (*forward)++;
            } else if (p == b && q == a) {
                (*all)++;
            }
        }
}

/* Invariants of every sheet: edge-manifold, consistently oriented (unless
 * the sheet is not orientable), loops made of exactly the boundary edges,
 * each run the way its triangle runs. */
static inline void check_sheets(const fm_surface *s, int orientable)
{
    for (size_t k = 0; k < fm_surface_nsheets(s); k++) {
        const fm_mesh *m = fm_surface_sheet_mesh(s, k);
        const int32_t *t = fm_mesh_triangles(m);
        size_t nt = fm_mesh_ntriangles(m), nboundary = 0;
        CHECK(fm_surface_sheet_vertex_origin(s, k) != NULL);
        for (size_t i = 0; i < nt; i++)
            for (int j = 0; j < 3; j++) {
                int all, fwd;
                edge_use(m, t[3 * i + j], t[3 * i + (j + 1) % 3], &all, &fwd);
                CHECK(all <= 2);
                if (orientable)
                    CHECK_EQ(fwd, 1);
                nboundary += all == 1;
            }
        size_t nloop_edges = 0;
        for (size_t l = 0; l < fm_surface_sheet_nloops(s, k); l++) {
            size_t n;
            const int32_t *lv = fm_surface_sheet_loop(s, k, l, &n);
            nloop_edges += n;
            for (size_t i = 0; i < n && orientable; i++) {
                int all, fwd;
                edge_use(m, lv[i], lv[(i + 1) % n], &all, &fwd);
                CHECK_EQ(all, 1);
                CHECK_EQ(fwd, 1);
            }
        }
        if (orientable)
            CHECK_EQ(nloop_edges, nboundary);
        if (fm_surface_sheet_nloops(s, k) == 0)
            CHECK_EQ(fm_surface_sheet_outer_loop(s, k), -1);
        else
            CHECK(fm_surface_sheet_outer_loop(s, k) >= 0);
    }
}

/* Length of loop l of sheet k. */
static inline size_t loop_len(const fm_surface *s, size_t k, size_t l)
{
    size_t n = 0;
    fm_surface_sheet_loop(s, k, l, &n);
    return n;
}

/* z of the vector area of loop l of sheet k (positive: counter-clockwise
 * seen from above). */
static inline double loop_area_z(const fm_surface *s, size_t k, size_t l)
{
    size_t n = 0;
    const int32_t *lv = fm_surface_sheet_loop(s, k, l, &n);
    const double *xyz = fm_mesh_vertices(fm_surface_sheet_mesh(s, k));
    double a = 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = xyz + 3 * (size_t)lv[i], *q = xyz + 3 * (size_t)lv[(i + 1) % n];
        a += 0.5 * (p[0] * q[1] - p[1] * q[0]);
    }
    return a;
}

#endif
