/* Boundary nodes slid along their curves.
 *
 * Refinement puts nodes on the outline and the sea-level line where
 * encroachment or the shells round a sharp corner ask, and the optimisation
 * keeps them there: only free nodes move. Where the outline meets sea level
 * at a shallow angle the domain is a long thin wedge with no inside node,
 * its triangles spanning from one side to the other, so their shapes are
 * set by where the nodes sit along the two sides (at 500 m, Big Pine east
 * kept an 18.4 degree triangle and West Huasna a 19.9 degree one beside
 * such a corner, all their nodes on the boundary). A node refinement put
 * on a curve may instead move along that curve between its two boundary
 * neighbours, to where the smallest 3D angle around it is largest: the
 * outline stays on the same curve, and the domain's own nodes (corners,
 * the samples of the curves) never move. The move is taken when every
 * triangle around stays counter-clockwise in (u, v) (exact orient2d) and
 * the node's two new boundary edges cross no constrained edge. */
#include <math.h>
#include <stdlib.h>

#include "fm_predicates.h"
#include "remesh_internal.h"

#define SIN30 0.5
/* Where along the span between the neighbours the node is tried: never
 * nearer a neighbour than a quarter of the span (edges that short would
 * trade an angle for a sliver's length). */
#define SLIDE_STEPS 10
#define SLIDE_MIN 0.25

static double ring_min_sin(const double *xyz, const int32_t *tri, const int32_t *ring, size_t n,
                           const double *uv, int *valid)
{
    double q = 1;
    *valid = 1;
    for (size_t k = 0; k < n; k++) {
        const int32_t *T = tri + 3 * ring[k];
        if (fm_orient2d(uv + 2 * T[0], uv + 2 * T[1], uv + 2 * T[2]) <= 0)
            *valid = 0;
        q = fmin(q, fm_triangle_min_angle_sin(xyz + 3 * T[0], xyz + 3 * T[1], xyz + 3 * T[2]));
    }
    return q;
}

/* The point of v's curve at fraction f of the way from neighbour a to
 * neighbour b; 0 when the curve strays so far from the chord there that it
 * turns back on itself (as split_cb in domain_cdt.c refuses it). */
static int curve_point(const fm_fit_surface *s, const opt_curves *cv, int32_t k, const double *a,
                       const double *b, double f, double out[2])
{
    const dom_seg *sg = &cv->segs[k];
    const double *e = cv->ends + 4 * (size_t)k;
    if (sg->kind == SEG_TRIM) {
        double fa = chord_fraction(e, a), fb = chord_fraction(e, b);
        segment_point(s, cv->loops, cv->level, sg, e, e + 2, fa + f * (fb - fa), out);
    } else {
        segment_point(s, cv->loops, cv->level, sg, a, b, f, out);
    }
    double straight[2] = {a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])};
    return hypot(out[0] - straight[0], out[1] - straight[1]) <= 0.25 * hypot(b[0] - a[0], b[1] - a[1]);
}

size_t slide_boundary(const fm_fit_surface *s, const opt_curves *cv, double *uv, double *xyz,
                      size_t np, const int32_t *tri, const size_t *start, const int32_t *list,
                      const int32_t *prev, const int32_t *next, const int32_t *cons,
                      size_t ncons)
{
    size_t moved = 0;
    cons_grid *grid = NULL;
    for (size_t v = cv->ninput; v < np; v++) {
        int32_t k = cv->pseg[v], a = prev[v], b = next[v];
        if (k < 0 || a < 0 || b < 0 || start[v + 1] == start[v])
            continue;
        const int32_t *ring = list + start[v];
        size_t n = start[v + 1] - start[v];
        int valid;
        double before = ring_min_sin(xyz, tri, ring, n, uv, &valid);
        if (!(before < SIN30) || !valid)
            continue;
        double old_uv[2] = {uv[2 * v], uv[2 * v + 1]};
        double old_xyz[3] = {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
        double best = before, best_uv[2] = {old_uv[0], old_uv[1]};
        for (int i = 0; i <= SLIDE_STEPS; i++) {
            double f = SLIDE_MIN + (1 - 2 * SLIDE_MIN) * (double)i / SLIDE_STEPS, p[2];
            if (!curve_point(s, cv, k, uv + 2 * a, uv + 2 * b, f, p))
                continue;
            uv[2 * v] = p[0];
            uv[2 * v + 1] = p[1];
            fm_fit_surface_eval(s, p[0], p[1], xyz + 3 * v, NULL, NULL);
            double q = ring_min_sin(xyz, tri, ring, n, uv, &valid);
            if (valid && q > best + 1e-9) {
                best = q;
                best_uv[0] = p[0];
                best_uv[1] = p[1];
            }
        }
        uv[2 * v] = best_uv[0];
        uv[2 * v + 1] = best_uv[1];
        int ok = 0;
        if (best > before) {
            /* built at the first move tried (most rounds try none), else
             * told where v's constraints now reach */
            if (!grid)
                grid = cons_grid_create(uv, np, cons, ncons);
            else
                cons_grid_moved(grid, uv, (int32_t)v);
            ok = grid && !cons_grid_crosses(grid, uv, a, (int32_t)v) &&
                 !cons_grid_crosses(grid, uv, (int32_t)v, b);
        }
        if (ok) {
            fm_fit_surface_eval(s, uv[2 * v], uv[2 * v + 1], xyz + 3 * v, NULL, NULL);
            moved++;
        } else {
            uv[2 * v] = old_uv[0];
            uv[2 * v + 1] = old_uv[1];
            xyz[3 * v] = old_xyz[0];
            xyz[3 * v + 1] = old_xyz[1];
            xyz[3 * v + 2] = old_xyz[2];
            if (grid)
                cons_grid_moved(grid, uv, (int32_t)v);
        }
    }
    cons_grid_destroy(grid);
    return moved;
}
