/* faultmesh fit: trimming curves of a sheet in the (u, v) parameter plane.
 *
 * A boundary loop of a sheet (the outer boundary or a hole), mapped into
 * the plane of fm_fit.h, is a closed polyline whose vertices are mesh
 * vertices: it carries the stair-steps of the triangulation (zig-zags at
 * the scale of one triangle) on top of the real shape, and real corners
 * where a fault's top trace meets its lateral edges. fm_trim_fit turns it
 * into cubic B-spline curves that keep the corners and smooth the steps.
 *
 * Metres. The (u, v) plane of a steep or flattened sheet is not isometric
 * to the fault: fm_trim_fit_metric takes the surface's first fundamental
 * form at every point, and then every length below (point spacing, knot
 * spacing, corner window, deviations, tolerance) is measured on the fault
 * in 3D; fm_trim_fit is the same with the identity form.
 *
 * Corners. The turning at vertex i is the angle between the principal
 * directions of the polyline over the arc length `corner_window` before i
 * and the same length after it (each side's direction is the major axis of
 * the second moments of its segments taken as uniform lines, so a zig-zag
 * whose turning cancels inside the window does not tilt it). Vertices
 * whose turning reaches `corner_angle` are corners, strongest first (ties
 * by index), each suppressing weaker candidates closer than one window
 * along the loop. The window defaults to two median point spacings: the
 * smallest that holds a full stair-step on each side. A smooth bend of
 * radius below about window / angle (1.9 km for 500 m points) is, at that
 * point density, indistinguishable from a corner and is taken as one.
 * The turning peaks over a window, and a stair-step next to the apex can
 * move the peak a vertex off it, where a curve pinned to the wrong vertex
 * cuts the real apex by most of an edge (110 to 160 m on CFM faults); so
 * each corner then moves to its apex: of the vertices within half a window,
 * the one farthest from the chord between the loop points a window before
 * and after (unless that brings it within half a window of another
 * corner). 30 degrees: at 35 the bends of 30 to 35 degrees between a
 * fault's trace and its lateral edges were rounded off by over 100 m.
 *
 * Curves. The loop is split at its corners; each piece is a clamped cubic
 * B-spline whose end points are the corner vertices exactly, so pieces join
 * exactly (C0) at corners and are C2 inside. A loop without corners is one
 * periodic cubic B-spline (closed, C2 everywhere). Each curve minimises
 *     sum_j w_j |C(t_j) - P_j|^2 + sum over spans of lambda_s * integral |C''|^2
 * with chord-length parameters t_j (metres), w_j the point's share of the
 * polyline length (so the data term approximates an integral along the
 * loop) and lambda_s = mu (beta h_s / (2 pi))^4 for a span of length h_s:
 * a dense-data smoothing spline then passes a wave of wavelength L with
 * gain 1 / (1 + mu (beta h_s / L)^4), i.e. halves waves of beta knot
 * spacings and keeps long ones. mu starts at 1. The normal equations are
 * banded SPD (the periodic ones after folding the cyclic index order) and
 * solved with LAPACK's dpbsv.
 *
 * Knots start uniform at `knot_spacing`, by default 3 median point
 * spacings: a cubic spline on that grid cannot carry the two-point period
 * of a stair-step, which its least-squares fit averages to its mean; with
 * beta = 2 a wave of 6 spacings (3 km for 500 m points) is halved, one of
 * 20 spacings keeps 99 % of its amplitude.
 *
 * Tolerance. The distance from a point to the curve includes the
 * stair-step itself (about its amplitude), which is meant to be smoothed
 * away; so the tolerance applies to the systematic deviation: the signed
 * point-to-curve distances averaged by a tent of half-width two point
 * spacings along the loop (for evenly spaced points the 1/4, 1/2, 1/4
 * filter, which cancels an alternating step exactly), taken at points at
 * least that far from a corner (nearer, the curve is pinned to the corner
 * and the tent would see half a step). Where it exceeds `tolerance`, the
 * spans holding those points are halved if they are at least two point
 * spacings long; where a flagged span is already that short, the piece's
 * mu drops once to 1/4. With `max_deviation` > 0, spans holding a point
 * further than that from the curve are flagged too; a span flagged only
 * for that may be halved down to half a point spacing, so knots come in
 * around a single far point (a spike or a bend next to a corner, where the
 * systematic measure is not taken) while the rest of the piece keeps its
 * knots and smoothing (less smoothing over the whole piece made the curves
 * wiggle instead). Such a round is kept only if the piece's largest
 * deviation both ways (max_dev, max_curve_dev) does not grow; else the
 * piece returns to the knots before it and goes on splitting only the
 * span of its farthest point, until that too makes it grow. On the CFM
 * 500 m set this took 5 faults' outlines from 105 to 135 m to below
 * 100 m. A fit ends in the best state its rounds went through (within the
 * systematic tolerance first, then the smallest largest deviation both
 * ways). A piece still beyond max_deviation either way is fitted again,
 * up to three more times, and the best fit kept: flagging in each round
 * only the points within 2/3 of the largest deviation (the farthest
 * first: splitting the spans of every point over the limit at once also
 * puts knots beside a spike, and the round is undone with them all; but a
 * jog needs knots at both its ends at once, a spike among lesser points
 * needs them at the spike alone), and each of the two also flagging the
 * spans where the curve (at 8 places per span) strays further than
 * max_deviation from the polyline: a curve within it at every point can
 * swing out between two of them (120 m past a corner of Rose Canyon at
 * 30 m), but flagging those spans from the start changes which spans
 * every round splits, which elsewhere ends worse. On the CFM 500 m set at
 * 15 / 25 m this leaves 118 of 527 loops over 25 m either way (146 with
 * the first two fits only), none worse. The piece is refitted at most
 * `max_refinements` times per fit. Shorter spans (for the
 * systematic deviation) or less smoothing would let the curve follow the
 * stair-steps, which this measure cannot see: so a tolerance below what
 * the stair-steps allow ends with within_tolerance = 0, not with a curve
 * that wiggles.
 * Limitation: a least-squares residual averages to about zero over a knot
 * span, so the systematic deviation understates how much a bend sharper
 * than the knots but below `corner_angle` is rounded off (a 25 degree kink
 * of 500 m points: 34 m reported for a 70 m cut); max_dev, the raw
 * distance, shows it, mixed with the stair-steps.
 *
 * Input orientation is kept: pieces follow the input order, piece 0 starts
 * at the first corner (lowest index) or, without corners, at point 0.
 * Consecutive repeated points (also a repeated closing point) are dropped.
 * The loop is not checked for self-intersection. Deterministic: no threads,
 * fixed summation order, and a band Cholesky that at these band widths
 * (at most 7) runs LAPACK's unblocked code. */
#ifndef FM_TRIM_H
#define FM_TRIM_H

#include <stddef.h>

#include "fm_core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_trim_options {
    const char *name;        /* used as FILE in error messages; may be NULL */
    double tolerance;        /* metres, systematic deviation target; default 50 */
    double corner_angle;     /* degrees of turning over the window; default 30 */
    double corner_window;    /* metres each side; 0 = 2 median point spacings (default) */
    double knot_spacing;     /* metres; 0 = knot_factor x median point spacing (default) */
    double knot_factor;      /* default 3.0 */
    double smoothing_wavelength; /* beta, in knot spacings; default 2.0, floor 0.05 */
    int max_refinements;     /* 0..30, default 8 */
    double max_deviation;    /* metres; > 0: also refine where a single point is
                                further than this from the curve; 0 = off (default) */
    /* Per input point, 1 where the loop has a corner whatever its turning
     * over the window (where a cut across a sheet meets its outline: the
     * piece's boundary turns there from the one to the other, often by
     * less than corner_angle over a window but sharply at the point);
     * NULL = none (default). Such corners go first and stay where given. */
    const unsigned char *corner_at;
} fm_trim_options;

void fm_trim_options_default(fm_trim_options *opt);

/* What a fit did and how well it fits; distances in metres (in the metric
 * of fm_trim_fit_metric when one is given). */
typedef struct fm_trim_stats {
    size_t points;           /* input points */
    size_t distinct_points;  /* after dropping consecutive repeats */
    double spacing;          /* median distance between consecutive points */
    double corner_window, knot_spacing; /* as used */
    size_t corners, pieces, spans, control_points; /* spans, control points: sums */
    int refinements;         /* refinement rounds of the worst piece */
    double max_dev, rms_dev; /* input points to the curve (includes the stair-steps) */
    double max_curve_dev;    /* curve samples (8 per span) to the polyline */
    double max_systematic;   /* tent-averaged signed deviation: what tolerance bounds
                                (0 for pieces shorter than four point spacings) */
    int within_tolerance;    /* max_systematic <= tolerance */
    double area;             /* signed area enclosed by the curve (> 0: counter-clockwise) */
    double polygon_area;     /* signed area of the input polygon */
} fm_trim_stats;

typedef struct fm_trim_loop fm_trim_loop;

/* Fits the closed polyline uv[2 i], uv[2 i + 1], i < n (no repeated closing
 * point needed). opt may be NULL for defaults. Fails (FM_ERR_INVALID) on
 * fewer than 3 distinct points, non-finite coordinates, a loop of zero
 * length or bad options. A fit that misses the tolerance is not an error:
 * see stats->within_tolerance. */
fm_status fm_trim_fit(const double *uv, size_t n, const fm_trim_options *opt,
                      fm_trim_loop **out, fm_error *err);
/* The same with a metric: metric[3 i .. 3 i + 2] = E, F, G, the first
 * fundamental form S_u.S_u, S_u.S_v, S_v.S_v of the surface S(u, v) at
 * point i, so that a small step (du, dv) there is
 * sqrt(E du^2 + 2 F du dv + G dv^2) long in 3D. Every length of the fit is
 * then a 3D one: segment lengths (each segment with its end points' mean
 * form), hence the chord-length parameters, the median spacing and with
 * it the default knot spacing and corner window; the corner turning
 * (measured in the tangent plane of the vertex: the loop mapped by the
 * Cholesky factor of its form); and every deviation in the stats, so the
 * tolerance bounds the 3D systematic deviation. The curves themselves
 * stay in (u, v). metric NULL is the identity (fm_trim_fit). Fails
 * (FM_ERR_INVALID) on a non-finite form or one with E < 0, G < 0 or
 * E + G = 0; a (nearly) singular form is made slightly definite. */
fm_status fm_trim_fit_metric(const double *uv, const double *metric, size_t n,
                             const fm_trim_options *opt, fm_trim_loop **out, fm_error *err);
void fm_trim_loop_destroy(fm_trim_loop *loop);

const fm_trim_stats *fm_trim_loop_stats(const fm_trim_loop *loop);
/* Corners as indices into the input polyline, ascending. */
const size_t *fm_trim_loop_corners(const fm_trim_loop *loop, size_t *n);
size_t fm_trim_loop_npieces(const fm_trim_loop *loop);

/* One piece as a plain (non-rational) B-spline, ready for IGES entity 126:
 * C(t) = sum_i N_{i,degree}(t) control[i] over t0 <= t <= t1, knots of
 * count ncontrol + degree + 1. A clamped piece starts and ends on its corner
 * vertices exactly. A periodic piece (the whole loop, no corners) has
 * unclamped knots extended periodically and its last `degree` control
 * points repeat the first ones; C(t0) = C(t1) and it is C2 there. */
typedef struct fm_trim_piece {
    int degree;
    int periodic;
    size_t nknots;
    const double *knots;
    size_t ncontrol;
    const double *control;   /* 2 ncontrol: u, v */
    double t0, t1;           /* parameter range (metres of chord length, 3D with a metric) */
    size_t first, last;      /* input indices of the start and end vertices */
} fm_trim_piece;

/* Fills *out for piece i < fm_trim_loop_npieces; the pointers live as long
 * as the loop. */
void fm_trim_loop_piece(const fm_trim_loop *loop, size_t i, fm_trim_piece *out);

/* C(t) of piece i and (d may be NULL) C'(t). t is clamped to [t0, t1]
 * (wrapped for a periodic piece); at t0 and t1 a clamped piece gives its end
 * vertices exactly. */
void fm_trim_loop_eval(const fm_trim_loop *loop, size_t piece, double t, double p[2],
                       double d[2]);

/* Signed area enclosed by the curves (exact for the cubic pieces). */
double fm_trim_loop_area(const fm_trim_loop *loop);

/* The curves as a closed polyline (no repeated closing point): each piece
 * divided into ceil(length / spacing) parts of equal arc length, every
 * corner a vertex exactly, in input orientation. *uv (2 *n values) is
 * allocated here and freed by the caller with free(). corner_at (may be
 * NULL) receives, allocated the same way, the sample index of each corner. */
fm_status fm_trim_loop_sample(const fm_trim_loop *loop, double spacing, double **uv,
                              size_t *n, size_t **corner_at, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
