/* Private to the trimming curves (trim_*.c): the cleaned loop, the pieces
 * and the steps fm_trim_fit is built from. */
#ifndef FM_TRIM_INTERNAL_H
#define FM_TRIM_INTERNAL_H

#include <stddef.h>

#include "fm_trim.h"

#define TRIM_P 3 /* degree */

/* The input loop without consecutive repeats. */
typedef struct trim_input {
    size_t n;
    double *xy;     /* 2 n */
    size_t *orig;   /* input index of each point */
    double *M;      /* 3 n first fundamental forms E, F, G; NULL = identity */
    double *s;      /* n + 1 cumulative arc lengths, s[n] = perimeter (in the
                       metric: each segment measured with its end points'
                       mean form) */
    double spacing; /* median segment length (metric) */
} trim_input;

/* One curve: a clamped piece between two corners or the periodic loop. */
typedef struct trim_piece {
    int periodic;
    size_t first;   /* cleaned index of the start point */
    size_t in_first, in_last; /* input indices of the end points */
    size_t npts;    /* data points: clamped both ends included; periodic n */
    double *t;      /* their chord-length parameters, t[0] = 0 */
    double len;     /* parameter length */
    size_t nspans;
    double *brk;    /* nspans + 1 break points, 0 .. len */
    double mu;      /* smoothing multiplier, lowered by refinement */
    size_t nknots, nctrl;
    double *knots;  /* nctrl + TRIM_P + 1 */
    double *ctrl;   /* 2 nctrl */
    int rounds;     /* refinement rounds used */
    /* Measured by trim_measure_piece. */
    double max_dev, sum_dev2, max_curve_dev, max_sys;
    size_t worst_span; /* the span farthest off: holding the point at max_dev,
                          or the curve place at max_curve_dev when further */
} trim_piece;

struct fm_trim_loop {
    fm_trim_stats stats;
    size_t npieces;
    trim_piece *pieces;
    size_t ncorners;
    size_t *corners; /* input indices */
};

/* Data point j of a piece. */
static inline const double *trim_point(const trim_input *in, const trim_piece *pc, size_t j)
{
    return in->xy + 2 * ((pc->first + j) % in->n);
}

/* Metric of data point j of a piece (NULL without a metric). */
static inline const double *trim_point_metric(const trim_input *in, const trim_piece *pc,
                                              size_t j)
{
    return in->M ? in->M + 3 * ((pc->first + j) % in->n) : NULL;
}

/* Squared length of the (u, v) step d in the form M (NULL: identity). */
static inline double trim_norm2(const double *M, const double d[2])
{
    return M ? M[0] * d[0] * d[0] + 2 * M[1] * d[0] * d[1] + M[2] * d[1] * d[1]
             : d[0] * d[0] + d[1] * d[1];
}

/* --- trim_input.c --- */

/* Validates and cleans uv (and the metric, 3 n values or NULL); fills in
 * (freed with trim_input_free). */
fm_status trim_input_make(const double *uv, const double *metric, size_t n, trim_input *in,
                          const char *name, fm_error *err);
void trim_input_free(trim_input *in);
/* The area the loop encloses, in the metric (m^2). */
double trim_input_area(const trim_input *in);
/* Point at arc length s (any real, wrapped) along the closed polyline. */
void trim_input_at(const trim_input *in, double s, double p[2]);

/* --- trim_corners.c --- */

/* Corners (cleaned indices, ascending) into *corners (allocated, n at most
 * in->n); window in metres, angle in radians; corner_at (input indices,
 * may be NULL): forced corners (fm_trim_options). */
fm_status trim_find_corners(const trim_input *in, double window, double angle,
                            const unsigned char *corner_at, size_t **corners, size_t *ncorners);

/* --- trim_basis.c --- */

/* Span (0 .. nspans - 1) of the piece that holds t (clamped into range). */
size_t trim_span(const trim_piece *pc, double t);
/* Maps t into the parameter range: clamps, or wraps a periodic piece. */
double trim_wrap(const trim_piece *pc, double t);
/* Values (ders[0]) and derivatives up to nd (<= 2) of the TRIM_P + 1
 * B-splines alive on span k at t; they belong to control points k .. k + p. */
void trim_basis(const trim_piece *pc, size_t k, double t, int nd, double ders[3][TRIM_P + 1]);
/* C(t) and derivatives: out[0] point, out[1] C', out[2] C'' (up to nd). */
void trim_eval(const trim_piece *pc, double t, int nd, double out[3][2]);
/* Knot vector of the piece from its break points (allocates knots, ctrl). */
fm_status trim_make_knots(trim_piece *pc);

/* --- trim_fit.c --- */

/* Least-squares fit of the piece's control points for its current breaks. */
fm_status trim_fit_piece(const trim_input *in, trim_piece *pc, double beta, const char *name,
                         fm_error *err);

/* --- trim_measure.c --- */

/* Why a span is flagged for refinement: the systematic deviation, or only
 * single points further than max_deviation. */
#define TRIM_FLAG_SYSTEMATIC 1
#define TRIM_FLAG_RAW 2

/* Deviations of the fitted piece; flag[s] gets TRIM_FLAG_SYSTEMATIC for
 * spans holding a point whose tent-averaged signed deviation (half-width
 * H) exceeds tol, TRIM_FLAG_RAW (raw_tol > 0) for those holding a point
 * whose own distance exceeds raw_tol and raw_share times the largest
 * (raw_share > 0: the farthest points first), and with `curve` also for
 * those where the curve (8 places per span) is that much further from the
 * polyline. */
fm_status trim_measure_piece(const trim_input *in, trim_piece *pc, double H, double tol,
                             double raw_tol, double raw_share, int curve, unsigned char *flag);
/* Distance from p to the segment a-b, in the form M (NULL: identity). */
double trim_segment_distance(const double p[2], const double a[2], const double b[2],
                             const double *M);

#endif
