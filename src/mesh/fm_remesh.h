/* faultmesh mesh: quality triangle meshes of trimmed spline surfaces.
 *
 * A sheet of a fault model (fm_model.h) is a B-spline surface S(u, v) and
 * trimming loops in its (u, v) plane. Its mesh is made in that plane and
 * measured on the surface:
 *  1. Domain. The trimming curves are sampled at the target size H,
 *     measured along the curve in 3D, every corner a node. With the top
 *     cut (the default) the domain is clipped to z <= sea level: where a
 *     loop crosses sea level the crossing is found on the curve, and the
 *     level curve z(u, v) = 0 of the surface is traced through the domain
 *     from each exit to the next entry (predictor on the level curve's
 *     tangent, Newton corrector along grad z), so that the top of the mesh
 *     is a curve of the surface and its nodes lie on z = 0 exactly.
 *     `extend` first moves the top edge of a fault whose top lies less
 *     than D below sea level up dip along the surface's extension, past
 *     sea level, and then cuts.
 *  2. Constrained Delaunay triangulation of the domain in (u, v) and
 *     Delaunay refinement under the surface's first fundamental form
 *     (fm_cdt.h): triangles about H on the surface in 3D, boundary nodes
 *     placed on the true curves.
 *  3. Optimisation in 3D with nodes kept on the surface: edge flips that
 *     raise the smallest 3D angle, and tangential smoothing (each free node
 *     moved in (u, v) towards the 3D centroid of its neighbours, by a
 *     Gauss-Newton step through the surface's Jacobian). Every move and
 *     flip keeps all triangles counter-clockwise in (u, v), tested with the
 *     exact orient2d, so the mesh never folds; constrained edges never
 *     change.
 * Triangles are counter-clockwise in (u, v), so their normals point to the
 * S_u x S_v side (up for the height fields of dipping faults). */
#ifndef FM_REMESH_H
#define FM_REMESH_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"
#include "fm_fit.h"
#include "fm_mesh.h"
#include "fm_model.h"
#include "fm_sort.h"
#include "fm_trim.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most boundary nodes a sheet's domain may have (all its loops); more is
 * refused with FM_ERR_INVALID. */
#define FM_REMESH_MAX_OUTLINE_NODES 100000

typedef enum fm_top_mode {
    FM_TOP_CUT = 0,   /* clip at sea level (default) */
    FM_TOP_KEEP = 1,  /* keep the fitted (topographic) top */
    FM_TOP_EXTEND = 2 /* extend tops less than top_extend below sea level up to it, then cut */
} fm_top_mode;

typedef struct fm_remesh_options {
    const char *name;      /* FILE in messages; may be NULL */
    double size;           /* target edge length H in metres (> 0) */
    fm_top_mode top;
    double top_extend;     /* metres, for FM_TOP_EXTEND */
    double sea_level;      /* z of the cut, default 0 */
    int optimise_passes;   /* flip + smooth rounds, default 6 */
    size_t max_points;     /* safety bound per sheet; 0 = from area / H^2 */
    double flap_max;       /* metres: the flap beyond a shared curve a sheet ends at is
                              dropped only when it lies within this distance of the
                              curve, else kept (the sheet runs on past the curve there,
                              which stays a shared interior curve); 0 = any flap */
} fm_remesh_options;

void fm_remesh_options_default(fm_remesh_options *opt);

/* The fit options a model meant for this mesher is built with
 * (fm_model_build): fm_model_options_default, with trimming curves held
 * closer to the published boundary (outline nodes lie on them, and on a
 * small fault they are most of the nodes), the trimmed surface sampled one
 * level only (its area is all a caller weighs) and not measured against
 * the original (the check measures the mesh itself). */
void fm_remesh_model_options_default(fm_model_options *opt);

typedef struct fm_remesh_stats {
    size_t points, triangles;
    size_t boundary_points;    /* on trimming curves or the sea-level line */
    size_t level_points;       /* on the sea-level line (z set to sea level exactly; also
                                  outline nodes less than 1 m below it) */
    size_t clamped;            /* interior nodes a hair above sea level, put on it */
    double clamp_max;          /* largest such move (m) */
    size_t flips, smoothed;    /* optimisation moves accepted */
    size_t collapsed;          /* short edges collapsed */
    size_t slivers;            /* boundary nodes merged away to remove slivers of no width */
    int cut;                   /* 1: the top was cut, 0: wholly below (or keep) */
    int empty;                 /* 1: nothing of the sheet lies below sea level */
    double extended;           /* FM_TOP_EXTEND: largest up-dip extension (m) */
    size_t flaps_kept;         /* flaps beyond shared curves kept as wider than flap_max */
    double time;               /* seconds */
} fm_remesh_stats;

/* Meshes one trimmed sheet. loops[0] is the outer loop (counter-clockwise
 * in (u, v)), the rest holes (clockwise). out receives the mesh in 3D
 * (triangles tagged `tag`); uv_out (may be NULL) the (u, v) of every node
 * (2 per node, malloc'ed, freed by the caller). A sheet wholly above sea
 * level with the top cut gives an empty mesh and stats->empty = 1. */
fm_status fm_remesh_sheet(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                          size_t nloops, const fm_remesh_options *opt, int32_t tag,
                          fm_mesh **out, double **uv_out, fm_remesh_stats *stats,
                          fm_error *err);

/* A curve this sheet shares with a sheet of another fault (an
 * intersection curve from the junction plan, fm_connect.h): its nodes,
 * given in this sheet's (u, v), are nodes of the mesh exactly as given and
 * its segments are edges of it, never split, so that both meshes meet
 * node for node along it. A curve end within a quarter size of the
 * outline (or the sea-level line) becomes a node of it. */
typedef struct fm_remesh_curve {
    const double *uv;     /* 2 per node */
    size_t n;             /* >= 2 */
    const int64_t *node;  /* the caller's id of each node, reported per output vertex */
    int end;              /* 1: the sheet ends at the curve and keeps what lies on its
                             left (going from node 0 to node n-1, outer loops being
                             counter-clockwise): the flap beyond is dropped, a gap
                             before it filled; 0: the curve crosses the sheet */
    int lone;             /* the sheet ends at it alone, short of another surface it
                             would otherwise run through: the flap beyond is dropped
                             whatever its width (fm_remesh_options.flap_max) */
    long partner;         /* the sheet it is shared with, in the caller's numbering (-1:
                             none): a flap the same partner's curve keeps on its other side
                             is that junction's to decide, so it goes whatever its width */
} fm_remesh_curve;

/* fm_remesh_sheet with shared curves. node_out (may be NULL) receives per
 * output vertex the id of the shared node it is, or -1 (malloc'ed, freed by
 * the caller). Fails (FM_ERR_TOPOLOGY, and the mesh is not made) when the
 * curves cannot be fitted into the domain: they cross its loops or each
 * other other than at their ends, a flap to drop would be most of the
 * sheet, or a gap to fill is not closed; the caller may mesh the sheet
 * without them. */
fm_status fm_remesh_sheet_joined(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                                 size_t nloops, const fm_remesh_curve *curves, size_t ncurves,
                                 const fm_remesh_options *opt, int32_t tag, fm_mesh **out,
                                 double **uv_out, int64_t **node_out, fm_remesh_stats *stats,
                                 fm_error *err);

/* Meshes every sheet of a fault model into one mesh (triangles tagged
 * with the model sheet index; sheets are not joined to each other here).
 * stats (may be NULL) receives the sums over sheets (cut, empty: any /
 * all sheets; clamp_max, extended: the largest). */
fm_status fm_remesh_model(const fm_model *m, const fm_remesh_options *opt, fm_mesh **out,
                          fm_remesh_stats *stats, fm_error *err);

/* The shared curves of one sheet. */
typedef struct fm_remesh_sheet_curves {
    const fm_remesh_curve *curves;
    size_t n;
    unsigned char *dropped; /* per curve (may be NULL): set to 1 when the curve was left
                               out, 2 when the sheet was to end at it but could take it
                               only as an interior curve (it runs on past it: the flap
                               beyond stays) */
} fm_remesh_sheet_curves;

/* The domain a sheet's mesh covers, as its boundary in the sheet's (u, v)
 * plane: the outline as clipped, extended or trimmed at shared curves and
 * cut at sea level, exactly as meshed. Loop k is the closed polygon of
 * points start[k] .. start[k + 1] - 1 (the last joins the first), through
 * the mesh's boundary nodes in order. The mesh may fall into several
 * parts (edge-connected): part[k] numbers them from 0 in the order of
 * their first triangle; each part has one outer loop, counter-clockwise
 * in (u, v) and listed first, then its holes, clockwise. Loops are
 * simple: at a node where the boundary passes twice (parts touching at a
 * node, a hole touching the outline) the walk turns around the node
 * through its own part's triangles, and a loop that still comes back to a
 * node is cut there. Every array is malloc'ed; fm_remesh_boundary_free
 * releases them. */
typedef struct fm_remesh_boundary {
    size_t nloops, nparts;
    size_t *start;   /* nloops + 1 */
    size_t *part;    /* nloops */
    double *uv;      /* 2 per point */
    double *xyz;     /* 3 per point: the mesh node */
    int64_t *node;   /* per point: its shared node id (fm_remesh_curve.node) or -1 */
} fm_remesh_boundary;

void fm_remesh_boundary_free(fm_remesh_boundary *b);

/* The boundary of mesh m (triangles counter-clockwise in the (u, v) of
 * its vertices, 2 per vertex; ids may be NULL) into *b. FM_ERR_TOPOLOGY
 * when it is not a surface the loops of which can be traced (an edge used
 * twice the same way, a part with no or two outer loops); FM_ERR_NOMEM. */
fm_status fm_remesh_boundary_of(const fm_mesh *m, const double *uv, const int64_t *ids,
                                fm_remesh_boundary *b, fm_error *err);

/* fm_remesh_model with shared curves: curves[i] for sheet i (curves may be
 * NULL). node_out (may be NULL) receives per vertex of the mesh the shared
 * node id or -1. A sheet whose curves do not fit its domain together
 * (fm_remesh_sheet_joined fails other than for memory) is meshed with as
 * many as fit, taken one at a time, most nodes first (one it was to end
 * at that does not fit so is tried as an interior curve: the two faults
 * still share its nodes); curves[i].dropped marks the others,
 * join_failed[i] (may be NULL) is set to 1 and
 * join_errors[i] (may be NULL) given the first failure. bounds (may be
 * NULL, else one per sheet) receives each sheet's domain, as meshed (no
 * loops for a sheet left empty, or whose boundary fm_remesh_boundary_of
 * cannot trace: the mesh is kept); the caller frees each. */
/* The edges of the triangles of mesh m tagged tag (every triangle when
 * tag < 0) both of whose ends carry a shared node (ids: per vertex the
 * shared node id or -1, as fm_remesh_model_joined gives them), keyed
 * fm_edge_key(id a, id b) and sorted by key; *n of them (malloc'ed; free
 * it). NULL when out of memory. */
fm_keyed *fm_remesh_shared_edges(const fm_mesh *m, const int64_t *ids, int32_t tag, size_t *n);

fm_status fm_remesh_model_joined(const fm_model *m, const fm_remesh_sheet_curves *curves,
                                 const fm_remesh_options *opt, fm_mesh **out, int64_t **node_out,
                                 unsigned char *join_failed, fm_error *join_errors,
                                 fm_remesh_stats *stats, fm_remesh_boundary *bounds,
                                 fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
