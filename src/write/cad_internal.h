/* Private to src/write: the CAD model's trimming curves. */
#ifndef FM_CAD_INTERNAL_H
#define FM_CAD_INTERNAL_H

#include <stddef.h>
#include <string.h>

#include "fm_core.h"

/* A face's trims: loop l is curves loop_first[l] .. loop_first[l + 1] - 1;
 * curve c has degree[c] (3, or 1 where its nodes cannot be interpolated),
 * count[c] control points at pts + 2 first[c] and count[c] + degree[c] +
 * 1 knots at knots + kfirst[c]. */
typedef struct cad_curves {
    size_t ncurves, nloops;
    size_t *first, *count, *kfirst, *loop_first;
    int *degree;
    double *pts, *knots;
} cad_curves;

/* Where the closed polygon q (n points) is cut into curves: brk[i] = 1
 * at a corner (corner[i], may be NULL) and where the polygon turns by
 * more than CAD_SHARP_TURN_DEG, which a smooth curve through the nodes
 * would round off. */
#define CAD_SHARP_TURN_DEG 45.0
void cad_loop_breaks(const double *q, size_t n, const unsigned char *corner,
                     unsigned char *brk);

/* Spans of one trimming curve at most. */
#define CAD_MAX_SPANS 8

/* The curves of loops start[l] .. start[l + 1] - 1 of uv, cut at brk
 * (indexed from start[0]): each stretch from a break to the next one
 * (the whole loop from point 0 when it has none), in chunks of at most
 * CAD_MAX_SPANS segments, the cubic through its points. FM_OK or
 * FM_ERR_NOMEM. */
fm_status cad_curves_make(cad_curves *cv, const double *uv, const size_t *start, size_t nloops,
                          const unsigned char *brk);
void cad_curves_free(cad_curves *cv);

/* The C2 cubic B-spline through the n points q (u, v pairs) at their
 * chord-length parameters, clamped, leaving each end along its chord: n + 2 control points in ctrl (2 each), n + 6 knots; work
 * holds 4 n doubles. 1 on success; 0 (nothing usable written) for fewer
 * than 3 points or a repeated one, which stay a polygon. */
int cad_trim_cubic(const double *q, size_t n, double *ctrl, double *knots, double *work);

#endif
