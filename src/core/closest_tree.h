/* Private layout of fm_closest_tree, shared by the builder (closest_tree.c)
 * and the queries (closest_query.c, closest_box.c). */
#ifndef FM_CLOSEST_TREE_H
#define FM_CLOSEST_TREE_H

#include "fm_closest.h"

#include <stdint.h>

/* Node boxes are floats rounded outwards: half the memory and cache traffic
 * of doubles, and a box that is only ever too big keeps pruning exact. */
typedef struct closest_node {
    float lo[3], hi[3];
    int32_t first; /* leaf: first triangle slot; inner: left child (right is +1) */
    int32_t count; /* leaf: number of triangles (> 0); inner: 0 */
} closest_node;
_Static_assert(sizeof(closest_node) == 32, "two sibling nodes fill one cache line");

/* The builder falls back to median splits below this depth, so no path is
 * longer than it plus log2(INT32_MAX); queries size their stacks by it. */
#ifndef CLOSEST_SAH_DEPTH /* overridable to exercise the fallback */
#define CLOSEST_SAH_DEPTH 40
#endif
#define CLOSEST_STACK 80

struct fm_closest_tree {
    double centre[3];     /* integer point subtracted from every coordinate */
    size_t ntri, nnode;
    closest_node *nodes;  /* root at 0; empty when ntri is 0 */
    int32_t *tri;         /* 3 per slot, in leaf order, indices into xyz */
    int32_t *orig;        /* mesh triangle index of each slot */
    double *xyz;          /* referenced vertices relative to centre, by first use */
};

#endif
