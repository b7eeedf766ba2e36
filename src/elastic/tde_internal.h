/* Internals of the TDE module: every field is evaluated in complex
 * arithmetic so that one code path gives both the displacement (real
 * part, zero imaginary perturbation) and, by complex-step
 * differentiation, its exact derivatives (Squire & Trapp 1998): the
 * formulas use only +, -, *, /, sqrt and log of quantities kept away from
 * their branch cuts, so Im u(x + ih e_k) / h is du/dx_k to rounding. */
#ifndef FM_TDE_INTERNAL_H
#define FM_TDE_INTERNAL_H

#include <complex.h>

typedef double complex fm_cx;

#define FM_TDE_PI 3.14159265358979323846

/* Incomplete full-space field of the closed triangle P1 P2 P3 (Burgers
 * vector b, EFCS) at x: the line terms of Burgers' formula, without the
 * solid-angle term (fm_tde_solid_angle_term adds it). */
void fm_tde_lines_fs(const fm_cx x[3], const double tri[3][3], const double b[3], double nu,
                     fm_cx u[3]);

/* -b * Omega / (4 pi) with the sign such that u(+n) - u(-n) = b, Omega
 * the solid angle of the triangle seen from x (Van Oosterom & Strackee
 * 1983). On the triangle itself it takes the +n side's value. */
void fm_tde_solid_angle_term(const fm_cx x[3], const double tri[3][3], const double b[3],
                             fm_cx u[3]);

/* Complete full-space displacement (lines + solid angle). */
void fm_tde_fs_cx(const fm_cx x[3], const double tri[3][3], const double b[3], double nu,
                  fm_cx u[3]);

/* Half space minus full space at x (real: integrated by quadrature, see
 * tde_hs_correction.c): u, and grad[m][j] = du_m/dx_j if grad is not NULL.
 * kelvin = 1 integrates the full-space kernel instead (tests only). */
void fm_tde_hs_integral(const double x[3], const double tri[3][3], const double b[3],
                        double nu, int kelvin, double u[3], double grad[3][3]);

#endif
