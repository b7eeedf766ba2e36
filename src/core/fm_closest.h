/* faultmesh core: closest point on a triangle mesh, and bounding-box
 * overlap queries, through an AABB tree.
 *
 * Used wherever a stage measures how far something lies from an original
 * triangulation: the fit stage (fitted surface to CFM triangles), the mesh
 * and check stages (every output node to the CFM surface), and neighbour
 * search between faults.
 *
 * The tree copies the geometry it needs (vertices relative to an integer
 * centre, the triangles' vertex indices), so the mesh may be changed or
 * destroyed once fm_closest_tree_create returns. A built tree is never
 * modified: any number of threads may query it at once, and each query
 * depends only on the mesh and the query point, never on earlier queries.
 *
 * Triangle indices are the mesh's (0-based, as in fm_mesh_triangles);
 * barycentric coordinates refer to its vertex order a, b, c.
 *
 * Accuracy, slivers and degenerate triangles included: distances within
 * 1e-9 relative plus a few ulps of the coordinates measured from the mesh's
 * centre (tests/unit/test_closest.c checks this against an extended
 * precision reference); the foot is then rounded to the mesh's (UTM)
 * coordinates. */
#ifndef FM_CLOSEST_H
#define FM_CLOSEST_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"
#include "fm_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_closest_tree fm_closest_tree;

typedef struct fm_closest_hit {
    double dist;      /* Euclidean distance from the query point to foot */
    double foot[3];   /* closest point on the mesh, in the mesh's coordinates */
    int32_t triangle; /* mesh triangle the foot lies on */
    double bary[3];   /* foot = bary[0] a + bary[1] b + bary[2] c, sum 1, each >= 0 */
} fm_closest_hit;

/* Builds the tree over every triangle of m (unreferenced vertices are
 * ignored). An empty mesh gives a valid tree on which every query finds
 * nothing. Fails with FM_ERR_INVALID for a triangle naming a vertex that
 * does not exist, FM_ERR_NUMERIC for a non-finite coordinate,
 * FM_ERR_NOMEM; returns NULL then and fills err (if not NULL). */
fm_closest_tree *fm_closest_tree_create(const fm_mesh *m, fm_error *err);
/* The same, built about four times faster (triangles sorted by the Morton
 * code of their centroids, split where the code's leading bit changes)
 * into a tree some 1.5 times slower to query: for meshes queried a few
 * times per triangle (bench/bench_closest). Queries give the same answers
 * as on fm_closest_tree_create's tree (answers depend only on the mesh and
 * the query); only the order of box query calls differs. */
fm_closest_tree *fm_closest_tree_create_quick(const fm_mesh *m, fm_error *err);
/* A quick tree of some of m's triangles: part[0 .. n-1], mesh indices (a
 * triangle named twice counts twice). Its queries answer bit for bit as
 * those of a tree of the whole mesh would if the other triangles were not
 * there (the same centre, so the same arithmetic), naming triangles by
 * their mesh index: a caller that knows which triangles can matter to its
 * queries gets the whole tree's answers from a small tree. */
fm_closest_tree *fm_closest_tree_create_part(const fm_mesh *m, const int32_t *part, size_t n,
                                             fm_error *err);
void fm_closest_tree_destroy(fm_closest_tree *t);

size_t fm_closest_tree_ntriangles(const fm_closest_tree *t);

/* Closest point of the mesh to p among points within max_dist of it (pass
 * INFINITY for no bound; the bound is inclusive and compared on squared
 * distances). Returns 1 and fills hit (if not NULL) when there is one,
 * 0 otherwise (empty mesh, nothing close enough, non-finite p). When
 * several triangles are exactly equally close the lowest index wins. */
int fm_closest_query(const fm_closest_tree *t, const double p[3], double max_dist,
                     fm_closest_hit *hit);

/* 1 when fm_closest_query(t, p, max_dist, ...) would find a point, found
 * faster: the search ends at the first triangle within max_dist. hint (may
 * be NULL) speeds up runs of nearby points: start with -1; a call that
 * finds a triangle stores it there, and the next call tries it first. */
int fm_closest_within(const fm_closest_tree *t, const double p[3], double max_dist,
                      int32_t *hint);

/* Called once per triangle found by a box query; a non-zero return stops
 * the query. */
typedef int (*fm_closest_box_fn)(int32_t triangle, void *user);

/* Calls fn for every triangle whose axis-aligned bounding box overlaps the
 * closed box [lo, hi] (touching counts), in an order that depends only on
 * the mesh. Returns the number of calls made. */
size_t fm_closest_tree_box_query(const fm_closest_tree *t, const double lo[3],
                                 const double hi[3], fm_closest_box_fn fn, void *user);

/* The same triangles as fm_closest_tree_box_query, as a malloc'ed array
 * sorted ascending (the caller frees it; NULL when *n is 0). */
fm_status fm_closest_tree_box_collect(const fm_closest_tree *t, const double lo[3],
                                      const double hi[3], int32_t **out, size_t *n,
                                      fm_error *err);

/* Closest point to p on the triangle a, b, c, which may be degenerate (a
 * segment or a point): returns the squared distance, fills foot and bary
 * (both may be NULL). Exposed for stages that hold a single triangle; for
 * precision, pass coordinates relative to a point nearby rather than UTM
 * values. */
double fm_closest_on_triangle(const double p[3], const double a[3], const double b[3],
                              const double c[3], double foot[3], double bary[3]);

#ifdef __cplusplus
}
#endif
#endif
