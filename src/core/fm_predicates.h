/* faultmesh core: exact geometric predicates.
 *
 * Every decision that changes topology (is this triangle degenerate, which
 * side of an edge is a point on, is a point inside a circumcircle) goes
 * through these. Each first evaluates the determinant in floating point with
 * a forward error bound and, only when the sign is uncertain, recomputes it
 * exactly with floating-point expansion arithmetic (error-free sums and
 * products), after Shewchuk, "Adaptive Precision Floating-Point Arithmetic
 * and Fast Robust Geometric Predicates", DCG 18 (1997). Results are exact for
 * all finite inputs whose intermediate products neither overflow nor
 * underflow: coordinates between about 1e-90 and 1e90 in magnitude for the
 * orientation tests, 1e-65 and 1e75 for fm_incircle (products of four). */
#ifndef FM_PREDICATES_H
#define FM_PREDICATES_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* +1 if a, b, c (2D) turn counter-clockwise, -1 if clockwise, 0 if collinear. */
int fm_orient2d(const double *a, const double *b, const double *c);

/* +1 if d lies on the side opposite the normal (b-a)x(c-a) of the plane
 * through a, b, c (below it when a, b, c turn counter-clockwise seen from
 * above), -1 on the normal's side, 0 coplanar. This is the sign of
 * Shewchuk's orient3d. */
int fm_orient3d(const double *a, const double *b, const double *c, const double *d);

/* +1 if d lies strictly inside the circle through a, b, c (which must be
 * counter-clockwise), -1 outside, 0 on it. */
int fm_incircle(const double *a, const double *b, const double *c, const double *d);

/* 1 if the closed 2D segments pq and rs have a common point (a crossing,
 * an end on the other, a collinear overlap), else 0; exact (contact.c). */
int fm_segments_meet2d(const double *p, const double *q, const double *r, const double *s);

/* 1 if the 3D points a, b, c are exactly collinear (the triangle has zero
 * area), else 0. */
int fm_collinear3d(const double *a, const double *b, const double *c);

/* 1 if the closed triangles a and b (3D, not degenerate) have a common
 * point, else 0; exact (contact.c). */
int fm_triangles_meet(const double *const a[3], const double *const b[3]);

/* Triangles of one mesh, as vertex indices into x (3 doubles a vertex): 1
 * if they meet anywhere but in the corners and side they have in common
 * (the same triangle twice meets), 0 if not or if either is degenerate. */
int fm_triangles_meet_apart(const int32_t ia[3], const int32_t ib[3], const double *x);

#ifdef __cplusplus
}
#endif
#endif
