/* Private to src/fit: the surface object and the pieces fm_fit_sheet is
 * built from. */
#ifndef FM_FIT_INTERNAL_H
#define FM_FIT_INTERNAL_H

#include <stddef.h>

#include <stdint.h>

#include "fm_fit.h"

#define FM_FIT_MAX_DEGREE 5

/* Below this smallest n.w (facets steeper than 73 degrees to the plane) a
 * height field is also fitted as a parametric surface (fm_fit.h). */
#define FM_FIT_STEEP_DOT 0.3

struct fm_fit_surface {
    fm_fit_frame frame;
    fm_fit_stats stats;
    fm_fit_kind kind;
    int ncomp;            /* 1: heights; 3: frame coordinates (a, b, c) of S */
    int p;                /* degree */
    double s;             /* knot spacing */
    double u0, v0;        /* lower corner of the rectangle */
    size_t nsu, nsv;      /* spans */
    size_t nu, nv;        /* coefficients: spans + p */
    double *coef;         /* ncomp blocks of nu * nv, u fastest */
    double *knots_u, *knots_v;
    /* Parametric kind: the parameters of each sheet vertex (2 per vertex),
     * and S at the centre of every span, where a projection starts. */
    size_t nvparams;
    double *vparams;
    double *starts;       /* 3 nsu nsv, frame coordinates */
};

/* Local surface point P = (a, b, c) in frame coordinates and, when D is not
 * NULL, its derivatives D = {P_u, P_v, P_uu, P_uv, P_vv}. */
void fm_fit_local_eval(const fm_fit_surface *s, double u, double v, double P[3],
                       double D[5][3]);

/* One component of the spline (comp < ncomp): value and, when d is not
 * NULL, d = {f_u, f_v, f_uu, f_uv, f_vv}. */
double fm_fit_component(const fm_fit_surface *s, int comp, double u, double v, double d[5]);

/* The spans and basis values at (u, v) (derivatives too when deriv), for
 * evaluating several components at one point: fm_fit_component_at gives
 * exactly what fm_fit_component does (d only when at->deriv). */
typedef struct fm_fit_at {
    size_t ju, jv;
    int deriv;
    double Nu[3][FM_FIT_MAX_DEGREE + 1], Nv[3][FM_FIT_MAX_DEGREE + 1];
} fm_fit_at;
void fm_fit_basis_at(const fm_fit_surface *s, double u, double v, int deriv, fm_fit_at *at);
double fm_fit_component_at(const fm_fit_surface *s, int comp, const fm_fit_at *at, double d[5]);

/* Closest point by Newton iteration from the start parameters uv (updated
 * in place); q in frame coordinates. */
fm_status fm_fit_project_from(const fm_fit_surface *s, const double q[3], double uv[2],
                              double P[3], double *dist);

/* Weight of the thin-plate energy of a facet with squared slope g2 over the
 * plane: (1 + g2)^(-5/2), see fm_fit.h. */
double fm_fit_bending_weight(double g2);

/* --- fit.c --- */

/* fm_fit_sheet in stages, so that a look at a sheet's fit costs no second
 * fit: the split decision (model_split.c) begins the fit, looks at its
 * kind and at a trial with fewer refinements, and the model finishes the
 * same fit with the result fm_fit_sheet would give. */
typedef struct fm_fit_pending fm_fit_pending;

/* Checks the options and does all that comes before the first solve:
 * frame (frame, when not NULL, must be that of opt->frame), vertex
 * parameters, kind. opt NULL for defaults. */
fm_status fm_fit_pending_begin(const fm_mesh *sheet, const fm_fit_options *opt,
                               const fm_fit_frame *frame, fm_fit_pending **out, fm_error *err);
/* Before fm_fit_pending_finish: the frame, and the statistics known so far
 * (kind, overlap, stacked, convex_map, edge_median). */
const fm_fit_frame *fm_fit_pending_frame(const fm_fit_pending *pf);
const fm_fit_stats *fm_fit_pending_stats(const fm_fit_pending *pf);
/* The statistics fm_fit_sheet would give with max_refinements at most
 * `refinements` and closest_point_stats off (the parametric kind too where
 * it would try it); what it solves stays for the finish. */
fm_status fm_fit_pending_trial(fm_fit_pending *pf, int refinements, fm_fit_stats *out);
/* The surface fm_fit_sheet(sheet, opt) gives; pf is consumed. */
fm_status fm_fit_pending_finish(fm_fit_pending *pf, fm_fit_surface **out, fm_error *err);
void fm_fit_pending_destroy(fm_fit_pending *pf);

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

/* The sheet as the fit sees it: every vertex with its parameters (u, v)
 * and the ncomp values the spline is fitted to (the height along w, or the
 * three frame coordinates). */
typedef struct fm_fit_pmesh {
    size_t nv, nt;
    const int32_t *tri;
    double *uv;    /* 2 nv */
    double *val;   /* ncomp nv */
    int ncomp;
} fm_fit_pmesh;

/* One quadrature point of the data term. */
typedef struct fm_fit_sample {
    double u, v;      /* parameters */
    double val[3];    /* the facet's values there (ncomp of them) */
    double weight;    /* share of the parameter area */
    /* Chord matrix (C_uu, C_uv, C_vv) of the point in its triangle: a smooth
     * f through the triangle's corners lies at
     * f - (C_uu f_uu + 2 C_uv f_uv + C_vv f_vv) there, to second order. */
    double chord[3];
    double slope2;    /* |grad h|^2 of the facet (heights only, else 0) */
    double bend;      /* fm_fit_bending_weight(slope2), once per facet */
} fm_fit_sample;

typedef void (*fm_fit_sample_fn)(void *ctx, const fm_fit_sample *smp);

/* Calls fn for every quadrature point of every triangle, in triangle order.
 * Triangles whose sides in the parameter plane are longer than max_side
 * are split regularly first. Returns the number of samples. */
size_t fm_fit_sample_sheet(const fm_fit_pmesh *pm, double max_side, fm_fit_sample_fn fn,
                           void *ctx);

/* --- sparse.c --- */

/* Contributions to a symmetric sparse matrix (upper triangle kept). */
typedef struct fm_fit_triplet {
    size_t row, col;
    double val;
} fm_fit_triplet;
typedef struct fm_fit_triplets {
    fm_fit_triplet *e;
    size_t n, cap;
} fm_fit_triplets;
/* Adds v at (r, c) if r <= c (the lower half is implied); -1 on no memory. */
int fm_fit_triplets_add(fm_fit_triplets *q, size_t r, size_t c, double v);
void fm_fit_triplets_free(fm_fit_triplets *q);
/* Sums the contributions into compressed upper columns of an n x n matrix
 * (arrays malloc'ed here), in an order fixed by the input alone. */
fm_status fm_fit_triplets_compress(const fm_fit_triplets *q, size_t n, size_t **colptr,
                                   size_t **rowind, double **val);

/* --- lscm.c --- */

/* Least-squares conformal map of a sheet (any manifold, oriented sheet
 * with a boundary): uv gets 2 values per vertex, in metres (the parameter
 * area equals the sheet's area), v along the steepest descent of z. Sets
 * *flipped to the number of triangles whose orientation the map reverses. */
fm_status fm_fit_lscm(const fm_mesh *sheet, double *uv, size_t *flipped, const char *name,
                      fm_error *err);

/* --- convex_map.c --- */

/* One-to-one parameters for a sheet whose conformal map overlaps itself:
 * the outer boundary on an ellipse shaped after the conformal layout uv
 * (input), every other vertex a convex combination of its neighbours
 * (Tutte/Floater). Result in uv, area equal to the sheet's. */
fm_status fm_fit_convex_map(const fm_mesh *sheet, double *uv, const char *name, fm_error *err);

/* --- overlap.c --- */

/* Area (parameter units) of the triangles whose centroid lies inside
 * another, non-adjacent triangle in the parameter plane: the part of the
 * sheet the map folds over another part. */
double fm_fit_overlap_area(const fm_fit_pmesh *pm);

/* Vertices (of those marked used) with a vertex within `radius` in the
 * plane whose height (pm->val, one per vertex) differs by more than min_dh
 * and more than `slope` times their distance there: parts of the sheet
 * that the projection stacks close together. */
size_t fm_fit_stacked_vertices(const fm_fit_pmesh *pm, const unsigned char *used, double radius,
                               double min_dh, double slope);

/* --- assemble.c / solve.c --- */

/* Fills s->coef by least squares on the samples with the thin-plate
 * smoothing weight lambda; chord_passes more solves with the sample values
 * corrected by the chord term of the previous solution. When plain is not
 * NULL it receives the first, uncorrected solution (ncomp nu nv values).
 * Adds to the samples count and the assemble and solve times of s->stats. */
fm_status fm_fit_solve_coefficients(fm_fit_surface *s, const fm_fit_pmesh *pm, double lambda,
                                    int chord_passes, double *plain, const char *name,
                                    fm_error *err);

/* A factored symmetric positive definite matrix (CHOLMOD). */
typedef struct fm_fit_spd fm_fit_spd;

/* Factors the matrix given by its upper triangle in compressed columns
 * (sorted rows). */
fm_status fm_fit_spd_factor(size_t n, const size_t *colptr, const size_t *rowind,
                            const double *values, fm_fit_spd **out, const char *name,
                            fm_error *err);
/* The same with a fill-reducing order given (perm[k]: the k-th unknown to
 * eliminate), NULL for CHOLMOD's own. */
fm_status fm_fit_spd_factor_ordered(size_t n, const size_t *colptr, const size_t *rowind,
                                    const double *values, const int *perm, fm_fit_spd **out,
                                    const char *name, fm_error *err);
/* Nested dissection of an nu x nv grid of coefficients (u fastest) whose
 * stencil reaches p apart: perm of nu nv entries. */
void fm_fit_grid_order(size_t nu, size_t nv, int p, int *perm);
/* x = A^-1 b; x may alias b. */
fm_status fm_fit_spd_solve(fm_fit_spd *f, const double *b, double *x, const char *name,
                           fm_error *err);
void fm_fit_spd_destroy(fm_fit_spd *f);


#endif
