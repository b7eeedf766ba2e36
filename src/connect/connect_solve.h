/* faultmesh connect: solving curve points onto two surfaces. */
#ifndef FM_CONNECT_SOLVE_H
#define FM_CONNECT_SOLVE_H

#include "fm_fit.h"

/* Moves x = (uA, vA, uB, vB) to where S_A(uA, vA) = S_B(uB, vB) on the
 * plane through p0 normal to T (unit). Returns |S_A - S_B| reached;
 * *fallback = 1 when damped Newton alone missed tol and alternating
 * projections were used. */
double cn_solve_point(const fm_fit_surface *A, const fm_fit_surface *B, double x[4],
                      const double p0[3], const double T[3], double tol, int *fallback);

/* Angle between the surface normals at x, degrees in [0, 90]. */
double cn_crossing_angle(const fm_fit_surface *A, const fm_fit_surface *B, const double x[4]);

#endif
