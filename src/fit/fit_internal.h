/* Private to src/fit: the surface object and the pieces fm_fit_sheet is
 * built from. */
#ifndef FM_FIT_INTERNAL_H
#define FM_FIT_INTERNAL_H

#include <stddef.h>

#include "fm_fit.h"

#define FM_FIT_MAX_DEGREE 5

struct fm_fit_surface {
    fm_fit_frame frame;
    fm_fit_stats stats;
    int p;                /* degree */
    double s;             /* knot spacing */
    double u0, v0;        /* lower corner of the rectangle */
    size_t nsu, nsv;      /* spans */
    size_t nu, nv;        /* coefficients: spans + p */
    double *coef;         /* nu * nv heights, u fastest */
    double *knots_u, *knots_v;
};

/* Weight of the thin-plate energy of a facet with squared slope g2 over the
 * plane: (1 + g2)^(-5/2), see fm_fit.h. */
double fm_fit_bending_weight(double g2);

/* --- basis.c --- */

/* Values (k = 0) and first and second derivatives (k = 1, 2), per unit of
 * knot spacing, of the p + 1 uniform B-splines that are non-zero on a span,
 * at local coordinate t (0..1 inside the span; outside it the span's
 * polynomials are continued). */
void fm_fit_basis(int p, double t, double N[3][FM_FIT_MAX_DEGREE + 1]);
/* The same, values (N[0]) only. */
void fm_fit_basis_values(int p, double t, double N[3][FM_FIT_MAX_DEGREE + 1]);

/* One span's 1D Gram matrices of the k-th derivatives for unit spacing:
 * M[k][a][b] = integral over 0..1 of N_a^(k) N_b^(k) dt (exact). */
void fm_fit_span_gram(int p, double M[3][FM_FIT_MAX_DEGREE + 1][FM_FIT_MAX_DEGREE + 1]);

/* Span index (clamped to the rectangle) and local coordinate of x along
 * one axis with n spans of spacing s starting at x0. */
size_t fm_fit_locate(double x, double x0, double s, size_t n, double *t);

/* --- sample.c --- */

/* One quadrature point of the data term. */
typedef struct fm_fit_sample {
    double u, v, h;   /* plane coordinates and height of the facet */
    double weight;    /* share of the projected area */
    /* Chord matrix (C_uu, C_uv, C_vv) of the point in its triangle: a smooth
     * surface through the triangle's corners lies at
     * h - (C_uu h_uu + 2 C_uv h_uv + C_vv h_vv) there, to second order. */
    double chord[3];
    double slope2;    /* |grad h|^2 of the facet */
} fm_fit_sample;

typedef void (*fm_fit_sample_fn)(void *ctx, const fm_fit_sample *smp);

/* Calls fn for every quadrature point of every triangle of the sheet, in
 * triangle order. Triangles whose projected sides are longer than
 * max_side are split regularly first. Returns the number of samples. */
size_t fm_fit_sample_sheet(const fm_mesh *sheet, const fm_fit_frame *frame, double max_side,
                           fm_fit_sample_fn fn, void *ctx);

/* --- assemble.c / solve.c --- */

/* Fills s->coef by least squares on the sheet's samples with the
 * thin-plate smoothing weight lambda; chord_passes more solves with the
 * sample heights corrected by the chord term of the previous solution.
 * Fills the samples count and the assemble and solve times of s->stats. */
fm_status fm_fit_solve_coefficients(fm_fit_surface *s, const fm_mesh *sheet, double lambda,
                                    int chord_passes, const char *name, fm_error *err);

/* A factored symmetric positive definite matrix (CHOLMOD). */
typedef struct fm_fit_spd fm_fit_spd;

/* Factors the matrix given by its upper triangle in compressed columns
 * (sorted rows). */
fm_status fm_fit_spd_factor(size_t n, const size_t *colptr, const size_t *rowind,
                            const double *values, fm_fit_spd **out, const char *name,
                            fm_error *err);
/* x = A^-1 b; x may alias b. */
fm_status fm_fit_spd_solve(fm_fit_spd *f, const double *b, double *x, const char *name,
                           fm_error *err);
void fm_fit_spd_destroy(fm_fit_spd *f);

/* --- time.c --- */
double fm_fit_now(void);

#endif
