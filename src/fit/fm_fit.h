/* faultmesh fit: the smooth surface model of one sheet.
 *
 * A sheet (a manifold, consistently oriented, connected triangle mesh, as
 * the repair stage makes them) becomes, when a plane sees it one-to-one, a
 * height field over that reference plane: a tensor-product B-spline
 * h(u, v) in a right-handed frame (u, v, w) whose w axis is the reference
 * direction. In 3D the surface is
 *     S(u, v) = origin + u U + v V + h(u, v) W,
 * with (u, v) metres in the plane. Otherwise it is a parametric surface
 *     S(u, v) = origin + a(u, v) U + b(u, v) V + c(u, v) W,
 * three B-splines on the same knots over parameters (u, v) of its own
 * (FM_FIT_PARAMETRIC); the height field is the special case a = u, b = v.
 *
 * Which kind (FM_FIT_AUTO): the height field when every triangle normal n
 * has n.W > 0 (fm_fit_frame projectable) and the projection does not fold
 * the sheet over itself (stats.overlap: the share of the projected area
 * whose triangles' centroids fall inside another triangle, found with a
 * bucket grid; a sheet can face w everywhere and still lap over itself).
 * Else the parametric kind, with parameters from
 *  - the least-squares conformal map (LSCM, Levy et al. 2002) of the sheet,
 *    two far-apart vertices pinned, solved with CHOLMOD, turned so that v
 *    runs down dip (u along the long axis when the sheet dips < 10 deg)
 *    and scaled to the sheet's area (metres, nearly isometric on the
 *    near-developable surfaces faults are); or, when that map reverses a
 *    triangle or laps over itself (same overlap test),
 *  - a convex-boundary map (Tutte/Floater: outer boundary on an ellipse of
 *    the conformal layout's shape, by arc length; inner vertices convex
 *    combinations of their neighbours with symmetrized mean-value weights;
 *    holes closed by a virtual centre), one-to-one by construction.
 * A sheet with a few folded triangles (data defects) and no overlap of the
 * conformal map fits as well either way (measured on CFM 5.3); the rule
 * still sends it to the parametric kind, whose parameters stay one-to-one
 * for the trimming curves. Two kinds of sheet pass that rule as height
 * fields and still fit badly as one: a steep sheet (min n.W below 0.3,
 * facets over 73 degrees to the plane, where a height misfit is more than
 * three times the distance and the spline must turn almost parallel to W)
 * and a stacked one (stats.stacked: the plane puts two parts of the sheet
 * within two median edges of each other at heights that differ by more
 * than half an edge and by more than 2 s + 1 times their distance there,
 * s the slope of the steepest facet: a spline on knots of about an edge
 * cannot switch between them). A third kind is a height field that
 * strays more than twice target_max from its outline between the
 * outline's vertices (stats.max_border_offset: a boundary strip nearly
 * parallel to W, whose projection is too thin for the spline to climb
 * it; Southern San Cayetano steep, min n.W 0.35, bulged 158 m off a
 * straight lateral edge whose vertices it passed within 80 m). When such
 * a height field misses the refinement targets, the sheet is also fitted
 * as the parametric kind, and the fit closer to the targets (the larger
 * of vertex RMS / target_rms and of the largest vertex distance and
 * border offset / target_max) is kept. fm_fit_sheet_vertex_params gives
 * every sheet vertex's (u, v) in either kind.
 *
 * Reference direction W: the unit direction that maximises the smallest
 * n.W over the triangle normals. That optimum is the normalised
 * minimum-norm point of the convex hull of the normals (min over the hull
 * of |p| equals max over unit d of min n.d when the hull misses the
 * origin), found exactly with Wolfe's algorithm. Among the directions that
 * lose at most `slack_degrees` of that optimum, the one closest to the
 * area-weighted mean normal is taken, so that a few stray triangles do not
 * tilt the plane away from where most of the area is.
 *
 * In-plane axes: V points down dip (the steepest descent in the plane) and
 * U = V x W is horizontal. With W the upward sheet normal this makes U point
 * opposite to the Aki-Richards strike (a right-handed frame with V down dip
 * and W up cannot have U along it). When the plane dips less than 10
 * degrees, down dip means little: U is then the long axis of the projected
 * sheet (area second moment) and V = W x U.
 *
 * Spline: degree p (default cubic) with uniform, unclamped knots of
 * spacing s over a rectangle [u0, u1] x [v0, v1] covering the projected
 * sheet plus `extend` metres on every side, (spans_u + p) x (spans_v + p)
 * coefficients. Unclamped because every span is then alike (no end spans
 * that bend differently), the energy matrix is one element matrix repeated,
 * and a consumer that wants clamped knots (IGES readers accept both) gets
 * them exactly by knot insertion.
 *
 * Fit: minimise
 *     sum_k a_k (h(u_k, v_k) - h_k)^2
 *         + lambda * sum over spans of omega_span * integral over the span
 *           of (h_uu^2 + 2 h_uv^2 + h_vv^2) du dv
 * where the samples k are 3 quadrature points per triangle (triangles
 * longer than a knot span are split first) weighted by their share a_k of
 * the triangle's projected area, so the data term approximates the integral
 * of the squared height misfit over the projected sheet. The thin-plate
 * energy is integrated exactly (Gauss per span). The normal equations are
 * sparse SPD and are factored once with CHOLMOD (simplicial, so no BLAS).
 *  - Chord correction: a facet lies inside the smooth surface through its
 *    corners by up to h^2 kappa / 8 (10 m for 500 m triangles on a 200 m, 5 km
 *    corrugation), and fitting facets would bake that in. After the first
 *    solve each sample height is moved by the second-order chord term
 *    computed from the fit's own curvature, and the system is solved again
 *    with the same factor (chord_passes, default 1). The surface kept is
 *    the blend chord_weight (0.75) of that solution and 0.25 of the
 *    uncorrected one (which is what moving the heights by 0.75 of the term
 *    gives, the system being linear): between the vertices the facets and
 *    the smooth surface through the vertices are both readings of the
 *    fault, and the fit is measured against both. On CFM 5.3 at 500 m the
 *    full term leaves a median per-fault RMS of 1.8 m vertices -> surface
 *    but 3.3 m surface -> facets; on a smooth synthetic S-fold the surface
 *    departs from the analytic one by 2.9 m RMS with the full term, 4.2 m
 *    with 0.75 and 6.4 m with half of it.
 *  - omega_span is the area mean over the span of (1 + |grad h|^2)^(-5/2)
 *    of the facets in it: the height-field energy overstates the bending of
 *    a surface that is steep in the plane by that factor (squared curvature
 *    h'' / (1 + h'^2)^(3/2) times the area element), which would otherwise
 *    flatten the steep flanks of a near-vertical sheet. Where no facet lies
 *    (the margin, holes) omega is 0.01: there the energy only has to pick
 *    the smoothest continuation, whose shape does not depend on the weight,
 *    and a full weight would make the sheet's border compete with the
 *    margin's bending. Past the data the energy is the only term, so the
 *    surface continues the sheet smoothly and, having zero energy for
 *    planes, reproduces a plane exactly.
 *
 * The parametric kind fits a, b, c as above with the same samples (weighted
 * by parameter area), energy and chord correction per coordinate, sharing
 * one factorisation (three right-hand sides), with omega_span = 1 where
 * facets lie (the parameters are near-isometric: no slope to correct).
 *
 * Automatic choices (options override them):
 *  - knot spacing: starts at s = knot_factor (1.0) x the median edge length
 *    e of the sheet, raised until the coefficients number at most
 *    max_control_points (40000). After the fit the vertices' distances to
 *    the surface are estimated (to its tangent plane at their parameters,
 *    first order, no projection); while their RMS exceeds target_rms
 *    (4 m) or their maximum target_max (50 m), the spacing is halved and
 *    the sheet refitted: once while the grid stays within
 *    max_control_points, and again (at most max_refinements (3) halvings
 *    in all) only while the RMS is still over twice target_rms and the
 *    last halving cut it by a fifth at least, within twice
 *    max_control_points: the few sheets that far off are worth a finer
 *    grid, the many just over the target are not (each halving quadruples
 *    the grid). These errors are those of the fully chord-corrected
 *    solution (see chord_weight). Measured on CFM 5.3 at 500 m (bench/bench_fit):
 *    knots at 2e leave a median per-fault RMS of 9.6 m (the 500 m meshes
 *    carry kinks at the scale of their coarse originals, which a cubic on
 *    1 km knots cannot follow); at e it is 3.0 m with 91 % of faults within
 *    10 m RMS / 100 m max, and the one refinement to e/2 of the ~12 % of
 *    sheets that miss the targets brings that to 98 %; the further
 *    halvings take in small cut pieces and large sheets that the budget
 *    held at e. An explicit knot_spacing turns the refinement off.
 *  - lambda = (beta e / (2 pi))^4 with beta = smoothing_wavelength (1.0).
 *    For dense data this smoothing spline passes a height wave of
 *    wavelength L with gain 1 / (1 + (beta e / L)^4): waves of one edge
 *    length, which the triangles cannot show, are halved; a 5 km wave of a
 *    500 m sheet keeps all but 1e-4 of its amplitude. Tied to the data,
 *    not to the knots, so a finer grid does not smooth less: the thin-plate
 *    term keeps a refined fit from oscillating and the extension smooth.
 *
 * Everything is deterministic: no threads, fixed summation order, CHOLMOD
 * with its fixed ordering. */
#ifndef FM_FIT_H
#define FM_FIT_H

#include <stddef.h>

#include "fm_core.h"
#include "fm_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The reference frame of a sheet. */
typedef struct fm_fit_frame {
    double origin[3];   /* area-weighted centroid of the sheet */
    double u[3], v[3], w[3]; /* orthonormal, right-handed, w = reference direction */
    double min_dot;     /* smallest n.w over triangle normals (cos of the steepest slope) */
    double optimum_dot; /* the largest min_dot any direction achieves */
    double mean_dot;    /* area-weighted mean of n.w */
    double folded_area; /* area (m^2) of triangles with n.w <= 0 */
    double area;        /* total area (m^2) */
    double dip_degrees; /* angle between w and vertical */
    int projectable;    /* min_dot > 0: the projection onto the plane is one-to-one
                           for every triangle (the sheet may still overlap itself
                           across the plane; later checks tell) */
    int strike_axes;    /* 1: v is down dip; 0: u is the long axis (plane dips < 10 deg) */
} fm_fit_frame;

typedef struct fm_fit_frame_options {
    /* If not all zero: use this direction (normalised) as w instead of the
     * optimum, e.g. for a fallback that chose its own. Default zero. */
    double direction[3];
    /* Angle (degrees) by which the worst triangle may be steeper than in the
     * optimum when moving w towards the area-weighted mean normal.
     * Default 5. 0 = the pure max-min direction. */
    double slack_degrees;
} fm_fit_frame_options;

void fm_fit_frame_options_default(fm_fit_frame_options *opt);

/* Reference frame of a sheet (triangles with zero area are ignored).
 * opt may be NULL for defaults. Fails on a sheet without area or with
 * non-finite coordinates. */
fm_status fm_fit_reference_frame(const fm_mesh *sheet, const fm_fit_frame_options *opt,
                                 fm_fit_frame *out, fm_error *err);

/* Frame conversions: uvw[2] is the height along w. */
void fm_fit_frame_to_local(const fm_fit_frame *f, const double xyz[3], double uvw[3]);
void fm_fit_frame_to_world(const fm_fit_frame *f, const double uvw[3], double xyz[3]);

/* How the surface is parameterized. */
typedef enum fm_fit_kind {
    FM_FIT_AUTO = 0,         /* options only: the rule above */
    FM_FIT_HEIGHT_FIELD = 1, /* S = origin + u U + v V + h(u, v) W */
    FM_FIT_PARAMETRIC = 2    /* S = origin + a(u, v) U + b(u, v) V + c(u, v) W, (u, v) LSCM */
} fm_fit_kind;

typedef struct fm_fit_options {
    const char *name;       /* used as FILE in error messages; may be NULL */
    fm_fit_kind kind;       /* default FM_FIT_AUTO */
    fm_fit_frame_options frame;
    int degree;             /* 2..5, default 3 */
    double extend;          /* metres beyond the projected sheet, default 2000 */
    double knot_spacing;    /* metres; 0 = automatic (default) */
    double knot_factor;     /* first automatic spacing / median edge length, default 1.0 */
    size_t max_control_points; /* bound for the automatic spacing, default 40000 */
    double target_rms;      /* refinement goal for the vertex RMS distance (m), default 4 */
    double target_max;      /* ... and for the largest one (m), default 50 */
    int max_refinements;    /* halvings of the automatic spacing, 0..4, default 3 (see above) */
    double smoothing;       /* lambda (m^4); 0 = automatic (default) */
    double smoothing_wavelength; /* beta of the automatic rule, default 1.0 */
    int chord_passes;       /* refits with chord-corrected sample heights, 0..10; default 1 */
    double chord_weight;    /* share of the chord correction applied, 0..1; default 0.75 */
    int closest_point_stats; /* 1: also true distances (one projection per vertex); default 1 */
} fm_fit_options;

void fm_fit_options_default(fm_fit_options *opt);

/* What a fit did and how well it fits. Distances in metres, times in
 * seconds (wall clock; the only non-deterministic fields). */
typedef struct fm_fit_stats {
    fm_fit_kind kind;            /* height field or parametric */
    int passes;                  /* refinement passes after the first fit */
    double overlap;              /* fraction of the area the plane projection folds
                                    over another part of the sheet (see above) */
    size_t lscm_flipped;         /* parametric: triangles the conformal map turns over */
    int convex_map;              /* parametric: 1 when the conformal map overlapped itself
                                    and the convex-boundary map replaced it */
    size_t vertices, triangles, samples;
    int degree;
    size_t spans_u, spans_v;     /* knot spans over the rectangle */
    size_t control_u, control_v; /* coefficients: spans + degree */
    double knot_spacing;
    double edge_median;          /* of the sheet, base of the automatic spacing and lambda */
    double smoothing;            /* lambda used */
    double rms_w, max_w;         /* vertices: |height - h(u, v)| along w; parametric:
                                    distance to the surface point at their parameters */
    double rms_dist, max_dist;   /* vertices: distance to the closest surface point
                                    (0 when closest_point_stats is off) */
    size_t projection_failures;  /* vertices whose projection did not converge */
    double max_border_offset;    /* largest distance from the midpoint of a boundary
                                    edge to the surface point midway between the
                                    closest-point parameters of its ends (0 when
                                    closest_point_stats is off): how far the surface
                                    strays from the outline between its vertices,
                                    where the trimming curve runs */
    size_t stacked;              /* height field: vertices the plane stacks near a far
                                    part of the sheet (see above) */
    double time_frame, time_param, time_assemble, time_solve, time_stats, time_total;
} fm_fit_stats;

/* The fitted surface of one sheet. */
typedef struct fm_fit_surface fm_fit_surface;

/* Fits the sheet. opt may be NULL for defaults. */
fm_status fm_fit_sheet(const fm_mesh *sheet, const fm_fit_options *opt, fm_fit_surface **out,
                       fm_error *err);
void fm_fit_surface_destroy(fm_fit_surface *s);

/* FM_FIT_HEIGHT_FIELD or FM_FIT_PARAMETRIC. */
fm_fit_kind fm_fit_surface_kind(const fm_fit_surface *s);

/* The parameters (u, v) of every vertex of the sheet the surface was
 * fitted to (2 per vertex into uv): its projection onto the plane for a
 * height field, its LSCM coordinates for a parametric surface (kept at fit
 * time; fails with FM_ERR_INVALID if the vertex count differs). Both are
 * one-to-one on the sheet, so boundary loops map to simple polygons. */
fm_status fm_fit_sheet_vertex_params(const fm_fit_surface *s, const fm_mesh *sheet, double *uv,
                                     fm_error *err);

const fm_fit_frame *fm_fit_surface_frame(const fm_fit_surface *s);
const fm_fit_stats *fm_fit_surface_stats(const fm_fit_surface *s);

/* The rectangle the spline is defined on: u0, u1, v0, v1 (metres in the
 * plane). Evaluation outside it continues the polynomials of the border
 * spans (fine for a Newton step, not meant as surface). */
void fm_fit_surface_domain(const fm_fit_surface *s, double dom[4]);
int fm_fit_surface_degree(const fm_fit_surface *s);
/* Knot vector along u (dir 0) or v (dir 1): spans + 2 degree + 1 values,
 * the first `degree` and last `degree` lying outside the rectangle. */
const double *fm_fit_surface_knots(const fm_fit_surface *s, int dir, size_t *n);
/* Coefficients: nu x nv heights, u index fastest. For the parametric kind
 * the coefficients of c, the coordinate along w. */
const double *fm_fit_surface_heights(const fm_fit_surface *s, size_t *nu, size_t *nv);
/* The same surface as an ordinary 3D tensor-product B-spline (same knots,
 * control point (i, j) at xyz[3 (j nu + i)]): for a height field u and v
 * are reproduced by their Greville abscissae, so this is exact, ready for
 * IGES entity 128; for the parametric kind it is its own control net. */
void fm_fit_surface_control_points(const fm_fit_surface *s, double *xyz);

/* Height h(u, v); dh (may be NULL) gets h_u, h_v, h_uu, h_uv, h_vv. For the
 * parametric kind: c(u, v), the w coordinate of S(u, v), and its
 * derivatives. */
double fm_fit_surface_height(const fm_fit_surface *s, double u, double v, double dh[5]);
/* Point S(u, v) and its first derivatives (du, dv may be NULL). */
void fm_fit_surface_eval(const fm_fit_surface *s, double u, double v, double xyz[3],
                         double du[3], double dv[3]);

/* Closest point of the surface to p, by Newton iteration on the squared
 * distance starting from the projection of p onto the plane (height field)
 * or from the nearest span centre of the surface (parametric). uv receives
 * the parameters, foot (may be NULL) the surface point, dist (may be NULL)
 * the signed distance (positive on the side of S_u x S_v: the w side of a
 * height field, the sheet's normal side). Returns FM_OK, or FM_ERR_NUMERIC
 * when the iteration did not converge (the outputs then hold the best
 * point found). */
fm_status fm_fit_project(const fm_fit_surface *s, const double p[3], double uv[2],
                         double foot[3], double *dist);

#ifdef __cplusplus
}
#endif
#endif
