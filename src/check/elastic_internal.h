/* faultmesh check, elastic: what elastic.c (the check) and
 * elastic_matrix.c (the full matrices) share: an element as the
 * dislocation sees it, and the traction one element's unit rake slip
 * puts on another (elastic_kernel.c). */
#ifndef FM_CHECK_ELASTIC_INTERNAL_H
#define FM_CHECK_ELASTIC_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fm_check.h"

typedef struct el_elem {
    double tri[3][3];  /* vertices, z moved down to the free surface where above it */
    double c[3];       /* centroid of those */
    double s[3], u[3], r[3], n[3]; /* along strike, up dip, along rake, normal into the
                                      hanging wall (unit) */
    double b[3];       /* unit rake slip in its dislocation frame: strike, dip, tensile */
    double h;          /* size: the edge of an equilateral triangle of its area, m */
    double top;        /* its shallowest depth below the free surface, m (>= 0) */
    int state;         /* EL_OK, EL_ABOVE, EL_DEGENERATE */
} el_elem;

enum { EL_OK = 0, EL_ABOVE = 1, EL_DEGENERATE = 2 };

/* Element t of m with its strike, dip and rake (degrees); its state. */
int el_elem_make(const fm_mesh *m, size_t t, double strike, double dip, double rake,
                 el_elem *e);

/* The free surface's part of the field is that of the source's image
 * (and corrections as far off): it falls off as the cube of the distance
 * to it, at least the source's depth plus the receiver's. Past this many
 * source sizes it is under 5e-4 of the self-stiffness (measured and held
 * in tests/unit/test_elastic_check.c), and the full-space field, a
 * hundred times cheaper, is taken instead. */
#define EL_IMAGE_SIZES 6.0

/* The traction on rcv's plane at its centroid per unit rake slip of src
 * (Pa/m): out[0] along rcv's strike, [1] up its dip, [2] along its rake,
 * [3] normal (positive: tension). 0, or -1 where the field is singular
 * (rcv's centroid on an edge of src) or the dislocation refused. */
int el_traction(const el_elem *src, const el_elem *rcv, const fm_elastic_options *o,
                double out[4]);
/* The same always in the half space (for the test of the above). */
int el_traction_hs(const el_elem *src, const el_elem *rcv, double mu, double nu, double out[4]);

/* The distance between two elements (m): 0 when they touch. Meshes of
 * different faults cross nowhere after the last guard, so the smallest
 * vertex-to-triangle and edge-to-edge distances are the distance. */
double el_distance(const el_elem *a, const el_elem *b);

#endif
