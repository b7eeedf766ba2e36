/* faultmesh mesh: constrained Delaunay triangulation of a (u, v) domain and
 * Delaunay refinement under a metric.
 *
 * The surface mesher works in the parameter plane of a spline surface, but
 * the lengths that matter are 3D lengths, given at each (u, v) by the
 * surface's first fundamental form M = [E F; F G]. So the triangulation is
 * built with exact predicates in (u, v) (fm_predicates.h: every topological
 * decision is exact, whatever the metric), while quality and size are
 * judged and new points are placed in the metric: the plane is mapped by the
 * Cholesky factor of M taken at the triangle being fixed, where the metric
 * is locally constant (Ruppert 1995; Shewchuk 2002; Chew 1993 for the idea
 * of refining a constrained Delaunay triangulation).
 *
 * Small input angles: an input vertex where two segments meet at less than
 * 60 degrees (in the metric) is an apex. Sub-segments next to an apex are
 * split on concentric shells (distances from the apex that are powers of
 * two, Ruppert / Miller-Pav-Walkington), and a skinny triangle whose
 * shortest edge joins two segments meeting at an apex is left alone
 * (Shewchuk's rule): its small angle is forced by the input, and trying to
 * fix it would only cascade splits towards the apex.
 *
 * Validity never depends on the metric: every orientation decision is the
 * exact orient2d on the (u, v) points, and a candidate point whose cavity
 * (grown with empty-circle tests in the local metric) it does not see
 * strictly is not inserted. The result is Delaunay in (u, v) without a
 * metric, and close to Delaunay in the local metric with one.
 *
 * Everything is deterministic: no randomness, fixed processing order
 * (priority by badness, ties by triangle slot). */
#ifndef FM_CDT_H
#define FM_CDT_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_cdt fm_cdt;

/* Builds the CDT of the points uv (2 per point) with the constrained
 * segments seg[2k], seg[2k+1] (point indices).
 *
 * Segments must form closed loops (every point has an even number of
 * segments): outer loops and holes, in any orientation, nested as deep as
 * wanted. The domain is what an odd number of segments separates from the
 * convex hull; triangles elsewhere are dropped from the results (the
 * structure keeps them internally so that later boundary splits stay
 * simple). Segments may share end points but must not cross or overlap; a
 * point lying exactly on a segment splits it there (exact test), which is
 * what a sampled curve passing through an input point needs.
 *
 * seg_id[k] (seg_id may be NULL: then k) is the caller's id of segment k:
 * its sub-segments and the points put on it keep that id, and the split
 * callback and frozen flags of refinement are keyed by it. Several
 * segments may share an id (all pieces of one curve).
 *
 * Errors: FM_ERR_INVALID for bad arguments (non-finite coordinates,
 * duplicate points, segment indices out of range or repeated, a segment
 * from a point to itself), FM_ERR_TOPOLOGY for segments that cross or
 * overlap, and for open chains; messages name the indices. */
fm_status fm_cdt_create(const double *uv, size_t npoints, const int32_t *seg,
                        const int32_t *seg_id, size_t nseg, fm_cdt **out, fm_error *err);

/* Like fm_cdt_create, but the segments may form any planar straight-line
 * graph: open chains, dangling ends, isolated segments, points with any
 * number of segments. This is how faults that meet share nodes: a sheet's
 * outline loops and the intersection curves on it (which may end inside
 * the sheet, on its outline or beyond it) make an arrangement, whose faces
 * the caller picks as the domain (fm_cdt_select_faces); a curve with the
 * domain on both sides stays in the mesh as an interior segment, with
 * triangles on both sides and, frozen, the same nodes as the other fault's
 * mesh.
 *
 * No domain is implied: until a selection it is the whole convex hull of
 * the points. The hull's edges are kept as edges of the triangulation
 * (exactly, whatever the super triangle) and bound the domain like
 * segments where no segment runs: in the results they carry id -1 and
 * refinement never splits them (it has no curve to put points on there),
 * so a domain meant to be meshed well should be closed by segments.
 *
 * Same arguments, ids and errors as fm_cdt_create, but for the parity
 * rule: crossing or overlapping segments are FM_ERR_TOPOLOGY, and a point
 * lying exactly on a segment splits it. Segment indices k in the functions
 * below are those of seg here. */
fm_status fm_cdt_create_graph(const double *uv, size_t npoints, const int32_t *seg,
                              const int32_t *seg_id, size_t nseg, fm_cdt **out,
                              fm_error *err);
void fm_cdt_destroy(fm_cdt *t);

/* Faces of a graph CDT: the regions inside the convex hull that segments
 * separate, i.e. maximal sets of triangles joined across unconstrained
 * edges. They are numbered 0 .. nfaces - 1 by the smallest directed piece
 * of their boundary (the pair of point indices, lexicographic, with the
 * face on its left): a key of the arrangement and the point numbering
 * alone, so the same input always numbers its faces the same way, whatever
 * the triangulation looks like. They describe the arrangement as created:
 * selection and refinement leave them as they are. A CDT from
 * fm_cdt_create has no faces (0, NULL, -1). */
size_t fm_cdt_nfaces(const fm_cdt *t);
/* The faces on the left and on the right of input segment k as directed
 * seg[2k] -> seg[2k+1]; -1 beyond the convex hull (or k out of range). A
 * segment split by points lying on it, where other segments end, can have
 * other faces further along; these are the faces of its first piece, from
 * seg[2k] to the first point on it. */
void fm_cdt_segment_faces(const fm_cdt *t, size_t k, int32_t *left, int32_t *right);
/* Per face: its area in (u, v) (the sum of its triangles', positive), and
 * a point strictly inside it, 2 per face: the incentre of its triangle with
 * the largest incircle, so that a caller classifying faces by
 * point-in-polygon against the curves that bound them is not at the mercy
 * of rounding. */
const double *fm_cdt_face_areas(const fm_cdt *t);
const double *fm_cdt_face_points(const fm_cdt *t);
/* Per face: 1 when an edge of the convex hull that no segment holds bounds
 * it, i.e. the segments do not close it off (a pocket between a concave
 * stretch of a loop and the hull); such a face kept puts an edge on the
 * domain's boundary that refinement never splits. */
const unsigned char *fm_cdt_face_open(const fm_cdt *t);

/* The domain becomes the union of the faces f with keep[f] != 0 (keep has
 * fm_cdt_nfaces entries). A piece of a segment (the whole segment unless
 * points lie on it) with kept faces on both sides stays as an interior
 * segment; with a kept face on one side it is a boundary; with none it is
 * no constraint any more, and points on it only are no longer on a
 * segment (point_segment -1) and, outside kept faces, in no triangle of the
 * results. May be called again, each time from the arrangement as created,
 * but only before fm_cdt_refine (which changes the triangles the faces are
 * made of): FM_ERR_INVALID afterwards, for a CDT from fm_cdt_create, or
 * for NULL arguments. */
fm_status fm_cdt_select_faces(fm_cdt *t, const unsigned char *keep, fm_error *err);

/* The metric at uv: m = {E, F, G}, symmetric positive definite. Called at
 * triangle centroids and segment points; it must be deterministic. */
typedef void (*fm_cdt_metric_fn)(void *user, const double uv[2], double m[3]);

/* Places the point that splits the sub-segment (a, b) of a segment with
 * caller id seg_id, at fraction f in (0, 1) of its way from a (0.5 but for
 * the concentric shells next to an apex): the caller puts it on the true
 * curve. The point is checked with exact orient2d; if it would invert a
 * triangle or cross another segment, the straight-line point at f, then
 * the midpoint, is used instead, so a careless callback costs accuracy,
 * never validity. */
typedef void (*fm_cdt_split_fn)(void *user, int32_t seg_id, const double a[2],
                                const double b[2], double f, double out_uv[2]);

typedef struct fm_cdt_refine_options {
    /* Target edge length in the metric (metres in 3D for a surface). A
     * triangle whose longest edge exceeds 1.4 size is split, at a point
     * that makes its new edges about size, which leaves edges mostly
     * (over 95 % in the tests) between 0.7 and 1.4 size. */
    double size;
    /* Smallest angle aimed at, degrees in the metric. Default 30. Theory
     * guarantees termination up to about 20.7 degrees; 30 works in
     * practice, and max_points stops a run that would not end. */
    double min_angle;
    fm_cdt_metric_fn metric; /* NULL: identity (lengths in (u, v)) */
    void *metric_user;
    fm_cdt_split_fn split;   /* NULL: straight-line points */
    void *split_user;
    /* frozen_ids[id] != 0 (id < nfrozen): sub-segments with that caller id
     * are never split, so a curve shared by two meshes keeps the same nodes
     * on both sides. A point that would encroach on one is not inserted, so
     * triangles next to frozen curves may stay above size or below the
     * angle. */
    const unsigned char *frozen_ids;
    size_t nfrozen;
    /* Cap on the total number of points; 0: automatic, 16 times the
     * points the metric area and boundary length call for, plus slack.
     * Reaching a cap given here is an error; reaching the automatic one
     * ends refinement early (stats.capped), the mesh valid and its bad
     * triangles counted: a metric the refiner cannot satisfy costs quality,
     * never the result. */
    size_t max_points;
    /* When the points the metric area and boundary length call for
     * (stats.expected_points, taken before any split) exceed this,
     * refinement does not start: stats.capped is set and the mesh is the
     * triangulation as it was. For a caller with a cheaper metric to fall
     * back on. 0: no limit. */
    size_t expected_limit;
    /* Largest ratio of the metric's principal stretches (square root of
     * the ratio of its eigenvalues) that refinement takes as it is; a
     * metric more anisotropic than this, or positive semi-definite only
     * within rounding (a surface whose parametrisation folds or pinches),
     * has its small eigenvalue raised to match. Near such a point the
     * diametral ellipses of segments and the circumcentres of triangles
     * reach arbitrarily far in (u, v), so splits chase the point for ever.
     * 0: no clamp (then a metric that is not positive definite is an
     * error). */
    double max_anisotropy;
    /* Smallest edge length refinement works at, in the metric: a triangle
     * whose edges are all shorter is not refined for its angles, a
     * sub-segment shorter is not split for encroachment, and a point
     * closer than half of it to a vertex of its cavity is not inserted.
     * This bounds refinement where the input or a varying metric forces
     * small features (such triangles are counted in bad_left). 0:
     * automatic, size / 16; negative: none. */
    double min_length;
} fm_cdt_refine_options;

/* size 0 (must be set), min_angle 30, no metric, no callback, nothing
 * frozen, automatic max_points, no expected_limit, no anisotropy clamp, automatic
 * min_length. */
void fm_cdt_refine_options_default(fm_cdt_refine_options *o);

/* Refines the domain: inserts points until every triangle is within size
 * and angle (apex triangles exempt from the angle), or nothing more may be
 * inserted. Points are only ever inserted inside the domain or on its
 * segments. Interior segments are treated like boundaries: no cavity
 * crosses them, an encroached one is split (both sides retriangulated)
 * unless frozen. FM_ERR_INVALID for bad options or when a max_points given
 * would be exceeded; FM_ERR_NUMERIC for a metric that is not positive
 * definite (and cannot be clamped, see max_anisotropy). On
 * error the triangulation stays valid (partly refined) and the results
 * below describe it. May be called again, e.g. with a smaller size. */
fm_status fm_cdt_refine(fm_cdt *t, const fm_cdt_refine_options *opt, fm_error *err);

/* Results. Input points keep their indices 0 .. ninput - 1; points added
 * by refinement follow. Arrays stay valid until the next call that
 * modifies t. */
size_t fm_cdt_ninput(const fm_cdt *t);
size_t fm_cdt_npoints(const fm_cdt *t);
const double *fm_cdt_points(const fm_cdt *t);      /* 2 per point */
size_t fm_cdt_ntriangles(const fm_cdt *t);
const int32_t *fm_cdt_triangles(const fm_cdt *t);  /* 3 per triangle, CCW in (u, v) */
/* Per point: the caller id of the segment it lies on, -1 when on none
 * (interior points, and input points outside the domain). An input point
 * shared by several segments reports the one with the lowest index; it is
 * an input point when its index is below fm_cdt_ninput. Points on interior
 * segments report them like points on boundaries. */
const int32_t *fm_cdt_point_segment(const fm_cdt *t);
/* The constrained edges of the result: 2 point indices per edge, and the
 * caller id of each (-1 for the convex hull's edges bounding a graph CDT's
 * domain where no segment runs). A boundary edge is oriented with the
 * domain on its left. An interior edge (graph CDTs: the domain on both
 * sides) is listed once, oriented as its input segment, seg[2k] towards
 * seg[2k+1], so a chain reads in order; edge_interior is 1 for those, 0
 * for boundary edges. Sorted by input segment (hull edges last), then by
 * point indices. */
size_t fm_cdt_nedges(const fm_cdt *t);
const int32_t *fm_cdt_edges(const fm_cdt *t);
const int32_t *fm_cdt_edge_ids(const fm_cdt *t);
const unsigned char *fm_cdt_edge_interior(const fm_cdt *t);

/* What the last fm_cdt_refine did: points inserted inside and on segments,
 * candidate points rejected (frozen segments, no valid place, below
 * min_length), triangles still bad at the end (above 1.4 size or below the
 * angle, apex triangles not counted), metric evaluations clamped
 * (max_anisotropy), and capped = 1 when the automatic max_points ended
 * refinement early. */
typedef struct fm_cdt_refine_stats {
    size_t inserted_interior, inserted_segment, rejected, bad_left;
    size_t clamped;
    int capped;
    /* Points the metric area and the boundary length call for at the size
     * (an equilateral mesh): how many a run that ends well comes near. */
    size_t expected_points;
} fm_cdt_refine_stats;
void fm_cdt_refine_get_stats(const fm_cdt *t, fm_cdt_refine_stats *st);

#ifdef __cplusplus
}
#endif
#endif
