/* faultmesh check: what a remeshed fault is worth, measured on the output
 * mesh alone (no knowledge of how it was made), so that the figures in
 * report.json are the ones a user's own tools would find.
 *
 * Quality: the smallest 3D angle of every triangle; triangles under 20
 * degrees are "forced" when that angle sits at a corner of the mesh's own
 * boundary whose interior angle (the sum of the triangle angles there) is
 * below 40 degrees: no triangle at such a corner can have its angles
 * above 20 without cutting the corner off. Size: every edge once, against
 * the target H. Fidelity: every node's distance to the original surface
 * (closest point on its triangles). */
#ifndef FM_CHECK_H
#define FM_CHECK_H

#include <stddef.h>
#include <stdint.h>

#include "fm_closest.h"
#include "fm_core.h"
#include "fm_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_quality {
    size_t triangles, nodes, edges;
    double angle_min;          /* degrees, smallest angle of any triangle */
    double angle_mean;         /* mean over triangles of their smallest angle */
    size_t below_30;           /* triangles with an angle under 30 degrees */
    size_t below_20;           /* ... under 20 */
    size_t below_20_forced;    /* ... of which at a boundary corner sharper than 40 */
    size_t sharp_corners;      /* boundary nodes with an interior angle under 40 */
    double edge_min, edge_max, edge_median, edge_p05, edge_p95; /* metres */
    size_t edges_in_band;      /* edges within [0.7 H, 1.4 H] */
    double area;               /* m^2 */
    double zmax;               /* highest node */
} fm_quality;

/* Quality of the triangles of m tagged tag (tag < 0: all). H > 0 is the
 * target edge length. */
fm_status fm_check_quality(const fm_mesh *m, int32_t tag, double H, fm_quality *q);

/* Distance (m) a node may lie from the original: the fidelity criterion. */
#define FM_FIDELITY_TOL 100.0

typedef struct fm_fidelity {
    size_t nodes;
    double rms, max;           /* metres */
    /* The node's nearest point on the original (its foot) tells where a
     * node farther than FM_FIDELITY_TOL lies: with its foot within
     * FM_FIDELITY_TOL of the original's outline (its edges used by one
     * triangle) it is past the original's edge, as over a gap a fault was
     * extended across to a neighbour, else over the original's inside.
     * beyond_max: largest distance of the nodes past the edge
     * (beyond_nodes of them; 0 without orig); inside_max: largest of the
     * others, with inside_over of them over FM_FIDELITY_TOL (without
     * orig every node counts as inside). */
    double beyond_max, inside_max;
    size_t beyond_nodes, inside_over;
} fm_fidelity;

/* Distances of the nodes of m used by triangles tagged tag (tag < 0: all)
 * to the surface in tree, built over orig (orig may be NULL: nothing is
 * then known of its outline and beyond_max stays 0). */
fm_status fm_check_fidelity(const fm_mesh *m, int32_t tag, const fm_mesh *orig,
                            const fm_closest_tree *tree, fm_fidelity *f);

#ifdef __cplusplus
}
#endif
#endif
