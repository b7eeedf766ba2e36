/* faultmesh repair: from a raw triangulation to clean manifold sheets.
 *
 * Input is a triangle soup as read from a file (fm_mesh; tags = parts).
 * The steps run in this order, and each one is counted in the report:
 *  1. weld exactly coincident vertices (bitwise equal coordinates), then,
 *     if weld_tolerance > 0, vertices closer than that tolerance;
 *  2. remove degenerate triangles (a repeated vertex, or zero area decided
 *     with exact predicates) and duplicate triangles (same three vertices,
 *     either orientation);
 *  3. drop small disconnected fragments (components below both
 *     min_fragment_triangles and min_fragment_area_fraction of the largest);
 *  4. split the surface along non-manifold edges into manifold sheets:
 *     at an edge shared by k > 2 triangles, the triangles are paired by the
 *     smallest bend across the edge so that a through-going fault stays one
 *     sheet and a splay becomes another; the edges where sheets branch are
 *     kept as junction curves. Vertices where a sheet is pinched (two fans
 *     meeting at one vertex) are duplicated;
 *  5. orient each sheet consistently, with its area-weighted normal pointing
 *     up (normal z > 0); a vertical sheet (|normal z| < 1e-3) is oriented so
 *     that its normal points to azimuth [90, 270) degrees, i.e. the right of
 *     a strike taken in [0, 180) (Aki-Richards with dip 90);
 *  6. boundary loops per sheet, oriented with the sheet, the outer loop told
 *     apart from holes by its vector area along the sheet normal.
 *
 * Definitions the counts and outputs rely on:
 *  - weld_tolerance welds vertices at distance <= tol, transitively (a chain
 *    of close vertices becomes one); the lowest input index represents a
 *    group and gives it its coordinates;
 *  - components are edge-connected: triangles touching only at a vertex are
 *    separate components (and separate sheets);
 *  - sheets are numbered in order of their first input triangle; a sheet's
 *    triangles keep input order, its vertices are numbered by first use;
 *  - a sheet vertex is a fan of triangles around an input vertex, so a
 *    vertex on a junction appears once in every sheet meeting there, and a
 *    pinched vertex once per fan; the rare triangle that would glue a sheet
 *    to itself along an edge is cut from its fan the same way;
 *  - with split_nonmanifold = 0, sheets are the components, edges of more
 *    than two triangles count as boundary for orientation and loops, and
 *    no vertex is duplicated; junction curves are reported all the same;
 *  - with orient = 0, triangles keep their input orientation (the normal is
 *    still computed from it);
 *  - a loop that cannot be closed (only on a non-orientable sheet) is kept
 *    as an open chain listing its last vertex too. */
#ifndef FM_REPAIR_H
#define FM_REPAIR_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"
#include "fm_json.h"
#include "fm_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_repair_options {
    double weld_tolerance;             /* metres; 0 = exact welding only (default) */
    size_t min_fragment_triangles;     /* default 10 */
    double min_fragment_area_fraction; /* of the largest component; default 0.001 */
    int drop_fragments;                /* default 1 */
    int split_nonmanifold;             /* default 1 */
    int orient;                        /* default 1 */
} fm_repair_options;

void fm_repair_options_default(fm_repair_options *opt);

typedef struct fm_repair_report {
    size_t vertices_in, triangles_in;
    size_t welded_exact;        /* vertices merged into an identical one */
    size_t welded_tolerance;    /* vertices merged within weld_tolerance */
    size_t unused_vertices;     /* welded vertices no clean triangle uses (removed;
                                   fragment vertices are not counted) */
    size_t degenerate_removed;  /* repeated-vertex or zero-area triangles */
    size_t duplicates_removed;  /* same vertex set as an earlier triangle */
    size_t fragments_dropped;   /* components dropped as tiny */
    size_t fragment_triangles_dropped;
    size_t components;          /* components kept (after dropping fragments) */
    size_t nonmanifold_edges;   /* edges with > 2 triangles, before splitting */
    size_t nonmanifold_vertices;/* (vertex, sheet) pairs duplicated: pinches */
    size_t sheets;
    size_t junctions;           /* junction curves between sheets */
    size_t triangles_flipped;   /* reversed w.r.t. the input, in the end */
    size_t nonorientable_sheets;/* sheets that are not orientable (reported, kept) */
    size_t boundary_loops, holes; /* over all sheets */
    size_t vertices_out, triangles_out; /* summed over sheets */
} fm_repair_report;

/* The repaired surface: sheets and the junctions between them. */
typedef struct fm_surface fm_surface;

/* opt may be NULL (defaults). Fails with FM_ERR_INVALID on a bad option or
 * an out-of-range vertex index, FM_ERR_NUMERIC on a non-finite coordinate,
 * FM_ERR_NOMEM; *out is then NULL. Any other mesh, even empty or entirely
 * degenerate (0 sheets), gives a surface. Same input, same output. */
fm_status fm_repair(const fm_mesh *in, const fm_repair_options *opt, fm_surface **out,
                    fm_error *err);
void fm_surface_destroy(fm_surface *s);

const fm_repair_report *fm_surface_report(const fm_surface *s);

size_t fm_surface_nsheets(const fm_surface *s);
/* A sheet's own compact mesh (tags keep the input part of each triangle). */
const fm_mesh *fm_surface_sheet_mesh(const fm_surface *s, size_t sheet);
/* For each sheet vertex, the index of the input vertex it came from (the
 * lowest index of a welded group). */
const int32_t *fm_surface_sheet_vertex_origin(const fm_surface *s, size_t sheet);
/* For each sheet triangle, the index of the input triangle it came from
 * (sheet triangles keep input order). */
const int32_t *fm_surface_sheet_triangle_origin(const fm_surface *s, size_t sheet);
/* Unit area-weighted normal of the sheet, after orientation; (0,0,0) when
 * the sheet's area vector vanishes (a closed sheet). */
void fm_surface_sheet_normal(const fm_surface *s, size_t sheet, double n[3]);

/* Boundary loops of a sheet: closed sequences of sheet vertex indices (the
 * first vertex is not repeated), traversed so that the sheet lies on the
 * left seen from the normal side. */
size_t fm_surface_sheet_nloops(const fm_surface *s, size_t sheet);
const int32_t *fm_surface_sheet_loop(const fm_surface *s, size_t sheet, size_t loop,
                                     size_t *n);
/* Index of the outer loop, or -1 for a closed sheet (no boundary). */
long fm_surface_sheet_outer_loop(const fm_surface *s, size_t sheet);

/* Junction curves: polylines along which sheets branch, as coordinates
 * (3 doubles per point), with the sheets that meet there. A closed
 * junction repeats no point; fm_surface_junction_closed tells. */
size_t fm_surface_njunctions(const fm_surface *s);
const double *fm_surface_junction_points(const fm_surface *s, size_t j, size_t *npoints);
int fm_surface_junction_closed(const fm_surface *s, size_t j);
/* The input vertex (lowest index of its welded group) of each point. */
const int32_t *fm_surface_junction_vertex_origin(const fm_surface *s, size_t j,
                                                 size_t *npoints);
const int32_t *fm_surface_junction_sheets(const fm_surface *s, size_t j, size_t *nsheets);

/* What a surface is (describe.c), as `faultmesh info` says it. */
/* Every sheet side by side in one mesh (tag: the sheet); NULL: memory. */
fm_mesh *fm_surface_concat(const fm_surface *s);
/* Input vertices the sheets use (ninput: the input's vertices): a vertex
 * on a junction or a pinch is one vertex of the object although several
 * sheets carry a copy. 0 when memory runs out. */
size_t fm_surface_distinct_vertices(const fm_surface *s, size_t ninput);
/* Boundary loops of a sheet that are not its outer one. */
size_t fm_surface_sheet_nholes(const fm_surface *s, size_t sheet);
/* Length of junction j (m; a closed one round). */
double fm_surface_junction_length(const fm_surface *s, size_t j);
/* The figures of fm_mesh_compute_stats as keys of the open JSON object. */
void fm_mesh_stats_json(fm_json *j, const fm_mesh_stats *st);
/* The object of `faultmesh info --json` (a stable interface: keys only
 * ever added): name, nparts and raw (as read) from the file, s repaired
 * from raw, all the figures of fm_surface_concat(s). */
void fm_surface_json(fm_json *j, const char *name, size_t nparts, const fm_mesh *raw,
                     const fm_surface *s, const fm_mesh_stats *all);

#ifdef __cplusplus
}
#endif
#endif
