/* Test meshes of parametric surfaces (shared by the unit tests). */
#ifndef FM_TEST_MESH_H
#define FM_TEST_MESH_H

#include <math.h>

#include "fm_mesh.h"

/* Point of a surface at (s, t), s in [0, L], t in [0, W]. */
typedef void (*fm_test_surface_fn)(const void *ctx, double s, double t, double p[3]);

/* Regular triangulation of [0, L] x [0, W] at spacing about h, diagonals
 * alternating so that the mesh has no preferred direction. */
static inline fm_mesh *fm_test_grid_mesh(double L, double W, double h, fm_test_surface_fn point,
                                         const void *ctx)
{
    int ns = (int)ceil(L / h), nt = (int)ceil(W / h);
    fm_mesh *m = fm_mesh_create();
    if (!m)
        return NULL;
    for (int j = 0; j <= nt; j++)
        for (int i = 0; i <= ns; i++) {
            double p[3];
            point(ctx, L * i / ns, W * j / nt, p);
            fm_mesh_add_vertex(m, p[0], p[1], p[2]);
        }
    for (int j = 0; j < nt; j++)
        for (int i = 0; i < ns; i++) {
            int32_t a = j * (ns + 1) + i, b = a + 1, c = a + ns + 1, d = c + 1;
            if ((i + j) % 2) {
                fm_mesh_add_triangle(m, a, b, d, 0);
                fm_mesh_add_triangle(m, a, d, c, 0);
            } else {
                fm_mesh_add_triangle(m, a, b, c, 0);
                fm_mesh_add_triangle(m, b, d, c, 0);
            }
        }
    return m;
}

#endif
