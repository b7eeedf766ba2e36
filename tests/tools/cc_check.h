/* check_connect: the analysis of a fault-set mesh (cc_obj.h) for issue 5,
 * conforming meshes where faults meet. Independent of the faultmesh
 * library but for its exact orientation predicates.
 *
 * 1. Intersections: pairs of triangles that meet anywhere other than along
 *    shared vertices / edges (cc_classify in cc_geom.h; sharing is by
 *    vertex index), between different faults and, separately, within one
 *    fault (self-intersections).
 * 2. Sharing: per fault pair the vertices used by both and the edges used
 *    by triangles of both.
 * 3. Proximity (distance D): boundary edges of a fault (used by one of its
 *    triangles) within D of another fault's triangles with neither end
 *    vertex used by that fault, "unjoined near edges"; and the closest
 *    distance between the two meshes, so that pairs within D sharing no
 *    vertex can be listed. */
#ifndef CC_CHECK_H
#define CC_CHECK_H

#include <stddef.h>
#include <stdint.h>

#include "cc_obj.h"

#define CC_EXAMPLES 3

typedef struct cc_pair {
    uint32_t a, b; /* fault indices, a < b */
    uint64_t shared_vertices, shared_edges;
    uint64_t intersections; /* violating triangle pairs */
    /* The first violating (triangle of a, triangle of b) in index order. */
    uint32_t examples[CC_EXAMPLES][2];
    int nexamples;
    /* Closest distance between the two meshes: 0 when they share a vertex,
     * computed when within D, else INFINITY. */
    double distance;
    /* Unjoined near boundary edges of a ([0]) and of b ([1]): count,
     * total length, and the smallest distance of any of them (INFINITY
     * when none). */
    uint64_t near_edges[2];
    double near_length[2];
    double near_min;
    int allowed; /* set by the caller (--allow-pairs) */
} cc_pair;

typedef struct cc_self {
    uint64_t intersections;
    uint32_t examples[CC_EXAMPLES][2];
    int nexamples;
} cc_self;

typedef struct cc_options {
    double distance; /* D */
    int self;        /* also look for self-intersections */
} cc_options;

typedef struct cc_result {
    cc_pair *pairs; /* sorted by (a, b); every pair with something to report */
    size_t npairs;
    cc_self *self; /* per fault */
    uint64_t degenerate_triangles;
    uint64_t skipped_pairs;     /* degenerate triangles sharing a vertex: not classified */
    uint64_t boundary_edges;    /* summed over faults */
    uint64_t nonmanifold_edges; /* used by more than two triangles of one fault */
    double seconds[3];          /* topology, intersections, proximity */
} cc_result;

/* 0, or -1 when out of memory. */
int cc_analyse(const cc_mesh *m, const cc_options *opt, cc_result *r);
void cc_result_free(cc_result *r);

#endif
