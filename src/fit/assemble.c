/* The normal equations of the smoothing fit. Every coefficient couples only
 * with the (2p+1)^2 coefficients around it, so the matrix is accumulated in
 * that stencil (one dense row per coefficient of the offsets of its upper
 * half) and only then laid out in compressed columns for the solver. */
#include "fit_internal.h"
#include "fm_clock.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Relative weight of the energy where no facet lies (the margin, holes).
 * There it only has to choose the smoothest continuation, whose shape does
 * not depend on the weight; a full weight would also make the data at the
 * sheet's border compete with the margin's bending and flatten the border
 * of a curved sheet (10 m on a 200 m corrugation). */
#define BARE_WEIGHT 0.01

#define NB_MAX ((FM_FIT_MAX_DEGREE + 1) * (FM_FIT_MAX_DEGREE + 1))

typedef struct normal_eq {
    const fm_fit_surface *s;
    double *A;    /* ncoef x NS: A[i][stencil(du, dv)] = entry (i, i + du + dv nu) */
    double *rhs;  /* ncomp blocks of ncoef */
    size_t ncoef;
    int ncomp;
    int W;
    size_t NS;    /* upper-half stencil: p + 1 + p W offsets */
    double *span_area, *span_bend; /* per span: sum of weights, of weight x bending weight */
    int nb;                        /* coefficients alive on a span, (p + 1)^2 */
    size_t coef_off[NB_MAX];       /* k -> coefficient index relative to the span's first */
    size_t stencil_off[NB_MAX][NB_MAX]; /* (k1, k2 >= k1) -> offset in A's row of k1 */
    /* Samples of one triangle mostly share a span: they are summed into a
     * small dense block first and added to A when the span changes. The
     * first sample of a block sets it (0 + x is x; a -0 there adds to A as
     * +0 would), so a flushed block needs no clearing. */
    int open, fresh;
    size_t ju, jv;
    double blk[NB_MAX * NB_MAX], brhs[3][NB_MAX];
} normal_eq;

/* Where entry (i, i + du + dv nu), dv >= 0 and du >= 0 when dv == 0, lies
 * in the row of i: that row of the grid first, then the p rows above. */
static size_t stencil(int p, int du, int dv)
{
    return dv == 0 ? (size_t)du : (size_t)(p + 1) + (size_t)(dv - 1) * (size_t)(2 * p + 1) +
                                      (size_t)(du + p);
}

double fm_fit_bending_weight(double g2)
{
    double c2 = 1.0 / (1.0 + g2);
    return c2 * c2 * sqrt(c2);
}

static void init_tables(normal_eq *q)
{
    int p = q->s->p, n1 = p + 1;
    q->nb = n1 * n1;
    for (int k1 = 0; k1 < q->nb; k1++) {
        int a1 = k1 % n1, b1 = k1 / n1;
        q->coef_off[k1] = (size_t)b1 * q->s->nu + (size_t)a1;
        /* k2 >= k1 is exactly the upper half: a later row of the grid, or
         * the same row to the right. */
        for (int k2 = k1; k2 < q->nb; k2++) {
            int a2 = k2 % n1, b2 = k2 / n1;
            q->stencil_off[k1][k2] = stencil(p, a2 - a1, b2 - b1);
        }
    }
}

/* Adds the upper half of a span block (nb x nb, row-major) times scale to A. */
static void scatter(normal_eq *q, size_t ju, size_t jv, const double *blk, double scale)
{
    size_t base = jv * q->s->nu + ju;
    for (int k1 = 0; k1 < q->nb; k1++) {
        double *Ar = q->A + (base + q->coef_off[k1]) * q->NS;
        const double *br = blk + k1 * q->nb;
        for (int k2 = k1; k2 < q->nb; k2++)
            Ar[q->stencil_off[k1][k2]] += scale * br[k2];
    }
}

static void flush(normal_eq *q)
{
    if (!q->open)
        return;
    scatter(q, q->ju, q->jv, q->blk, 1.0);
    size_t base = q->jv * q->s->nu + q->ju;
    for (int c = 0; c < q->ncomp; c++)
        for (int k = 0; k < q->nb; k++)
            q->rhs[(size_t)c * q->ncoef + base + q->coef_off[k]] += q->brhs[c][k];
    q->open = 0;
}

static void add_sample(void *ctx, const fm_fit_sample *smp)
{
    normal_eq *q = ctx;
    const fm_fit_surface *s = q->s;
    int p = s->p, nb = q->nb;
    double tu, tv, Nu[3][FM_FIT_MAX_DEGREE + 1], Nv[3][FM_FIT_MAX_DEGREE + 1];
    size_t ju = fm_fit_locate(smp->u, s->u0, s->s, s->nsu, &tu);
    size_t jv = fm_fit_locate(smp->v, s->v0, s->s, s->nsv, &tv);
    if (!q->open || ju != q->ju || jv != q->jv) {
        flush(q);
        q->open = 1;
        q->fresh = 1;
        q->ju = ju;
        q->jv = jv;
    }
    fm_fit_basis_values(p, tu, Nu);
    fm_fit_basis_values(p, tv, Nv);
    q->span_area[jv * s->nsu + ju] += smp->weight;
    q->span_bend[jv * s->nsu + ju] += smp->weight * smp->bend;
    double phi[NB_MAX];
    for (int b = 0; b <= p; b++)
        for (int a = 0; a <= p; a++)
            phi[b * (p + 1) + a] = Nu[0][a] * Nv[0][b];
    if (q->fresh) {
        for (int k1 = 0; k1 < nb; k1++) {
            double wp = smp->weight * phi[k1];
            for (int c = 0; c < q->ncomp; c++)
                q->brhs[c][k1] = wp * smp->val[c];
            double *br = q->blk + k1 * nb;
            for (int k2 = k1; k2 < nb; k2++)
                br[k2] = wp * phi[k2];
        }
        q->fresh = 0;
        return;
    }
    for (int k1 = 0; k1 < nb; k1++) {
        double wp = smp->weight * phi[k1];
        for (int c = 0; c < q->ncomp; c++)
            q->brhs[c][k1] += wp * smp->val[c];
        double *br = q->blk + k1 * nb;
        for (int k2 = k1; k2 < nb; k2++)
            br[k2] += wp * phi[k2];
    }
}

/* The thin-plate energy of one span, the same for every span of a uniform
 * grid up to the span's weight: h_uu^2 + 2 h_uv^2 + h_vv^2 is a sum of
 * tensor products of the 1D Gram matrices, each scaled by s^-2 overall.
 * The span's weight is the area mean of the facets' bending weights, with
 * BARE_WEIGHT for the part of the span no facet covers. */
static void add_energy(normal_eq *q, double lambda)
{
    const fm_fit_surface *s = q->s;
    int p = s->p, nb = (p + 1) * (p + 1);
    double M[3][FM_FIT_MAX_DEGREE + 1][FM_FIT_MAX_DEGREE + 1];
    fm_fit_span_gram(p, M);
    double E[NB_MAX * NB_MAX];
    double scale = lambda / (s->s * s->s);
    for (int k1 = 0; k1 < nb; k1++)
        for (int k2 = 0; k2 < nb; k2++) {
            int a1 = k1 % (p + 1), b1 = k1 / (p + 1), a2 = k2 % (p + 1), b2 = k2 / (p + 1);
            E[k1 * nb + k2] = scale * (M[2][a1][a2] * M[0][b1][b2] + 2 * M[1][a1][a2] * M[1][b1][b2] +
                                 M[0][a1][a2] * M[2][b1][b2]);
        }
    double cell = s->s * s->s;
    for (size_t jv = 0; jv < s->nsv; jv++)
        for (size_t ju = 0; ju < s->nsu; ju++) {
            double covered = q->span_area[jv * s->nsu + ju];
            double bare = covered < cell ? cell - covered : 0.0;
            double omega = (q->span_bend[jv * s->nsu + ju] + BARE_WEIGHT * bare) / (covered + bare);
            scatter(q, ju, jv, E, fmax(omega, 1e-6));
        }
}

typedef struct chord_rhs {
    const fm_fit_surface *s;
    double *rhs;
    size_t ncoef;
} chord_rhs;

/* Right-hand side only, with each facet value moved onto the smooth
 * surface through the triangle's corners as the current fit bends it. */
static void add_sample_rhs(void *ctx, const fm_fit_sample *smp)
{
    chord_rhs *q = ctx;
    double weight = smp->weight;
    const double *chord = smp->chord;
    const fm_fit_surface *s = q->s;
    int p = s->p;
    /* One span lookup and basis for every component; the values N[0] of
     * the basis with derivatives are those of the basis without. */
    fm_fit_at at;
    fm_fit_basis_at(s, smp->u, smp->v, 1, &at);
    size_t ju = at.ju, jv = at.jv;
    for (int c = 0; c < s->ncomp; c++) {
        double d[5];
        fm_fit_component_at(s, c, &at, d);
        double fc = smp->val[c] - (chord[0] * d[2] + 2 * chord[1] * d[3] + chord[2] * d[4]);
        for (int b = 0; b <= p; b++) {
            double *r = q->rhs + (size_t)c * q->ncoef + (jv + (size_t)b) * s->nu + ju;
            double wb = weight * fc * at.Nv[0][b];
            for (int a = 0; a <= p; a++)
                r[a] += wb * at.Nu[0][a];
        }
    }
}

/* Solves every component with the one factor. */
static fm_status solve_all(fm_fit_spd *spd, fm_fit_surface *s, const double *rhs, size_t n,
                           const char *name, fm_error *err)
{
    fm_status st = FM_OK;
    for (int c = 0; c < s->ncomp && st == FM_OK; c++)
        st = fm_fit_spd_solve(spd, rhs + (size_t)c * n, s->coef + (size_t)c * n, name, err);
    return st;
}

fm_status fm_fit_solve_coefficients(fm_fit_surface *s, const fm_fit_pmesh *pm, double lambda,
                                    int chord_passes, double *plain, const char *name,
                                    fm_error *err)
{
    double t0 = fm_clock_seconds();
    int p = s->p, W = 2 * p + 1;
    size_t n = s->nu * s->nv, WW = (size_t)W * (size_t)W;
    size_t nspans = s->nsu * s->nsv;
    normal_eq q;
    memset(&q, 0, sizeof q);
    q.s = s;
    q.W = W;
    q.NS = (size_t)(p + 1) + (size_t)p * (size_t)W;
    q.ncoef = n;
    q.ncomp = s->ncomp;
    q.A = calloc(n * q.NS, sizeof(double));
    q.rhs = calloc((size_t)s->ncomp * n, sizeof(double));
    q.span_area = calloc(nspans, sizeof(double));
    q.span_bend = calloc(nspans, sizeof(double));
    /* Upper triangle in compressed columns: at most (W^2 + 1) / 2 per column. */
    size_t cap = n * ((WW + 1) / 2);
    size_t *colptr = malloc((n + 1) * sizeof *colptr);
    size_t *rowind = malloc(cap * sizeof *rowind);
    double *val = malloc(cap * sizeof *val);
    fm_fit_spd *spd = NULL;
    fm_status st = FM_OK;
    /* Facets up to one and a half spans long are sampled whole: on a third
     * of the CFM 500 m set, splitting every facet longer than one span
     * took 2.5 times as long to assemble for the same per-fault RMS and
     * max (median 1.88 vs 1.86 m, the same faults within 10/100 m). */
    double max_side = 1.5 * s->s;
    if (!q.A || !q.rhs || !q.span_area || !q.span_bend || !colptr || !rowind || !val) {
        st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (%zu coefficients)", n);
        goto done;
    }
    init_tables(&q);
    s->stats.samples = fm_fit_sample_sheet(pm, max_side, add_sample, &q);
    flush(&q);
    add_energy(&q, lambda);

    size_t nnz = 0;
    for (size_t cv = 0; cv < s->nv; cv++)
        for (size_t cu = 0; cu < s->nu; cu++) {
            colptr[cv * s->nu + cu] = nnz;
            size_t rv0 = cv >= (size_t)p ? cv - (size_t)p : 0;
            for (size_t rv = rv0; rv <= cv; rv++) {
                size_t ru0 = cu >= (size_t)p ? cu - (size_t)p : 0;
                size_t ru1 = rv == cv ? cu : (cu + (size_t)p < s->nu ? cu + (size_t)p : s->nu - 1);
                for (size_t ru = ru0; ru <= ru1; ru++) {
                    size_t row = rv * s->nu + ru;
                    int du = (int)cu - (int)ru, dv = (int)(cv - rv);
                    rowind[nnz] = row;
                    val[nnz] = q.A[row * q.NS + stencil(p, du, dv)];
                    nnz++;
                }
            }
        }
    colptr[n] = nnz;
    free(q.A);
    q.A = NULL;
    double t1 = fm_clock_seconds();
    s->stats.time_assemble += t1 - t0;
    /* The grid's own nested dissection: some 20 % less factorization time
     * than CHOLMOD's minimum degree on these stencils (NULL: out of memory,
     * CHOLMOD orders). */
    int *perm = malloc(n * sizeof *perm);
    if (perm)
        fm_fit_grid_order(s->nu, s->nv, p, perm);
    st = fm_fit_spd_factor_ordered(n, colptr, rowind, val, perm, &spd, name, err);
    free(perm);
    if (st == FM_OK)
        st = solve_all(spd, s, q.rhs, n, name, err);
    if (st == FM_OK && plain)
        memcpy(plain, s->coef, (size_t)s->ncomp * n * sizeof *plain);
    double t2 = fm_clock_seconds();
    s->stats.time_solve += t2 - t1;
    /* The matrix does not change with the heights: each chord pass is one
     * more right-hand side for the same factor. */
    for (int pass = 0; pass < chord_passes && st == FM_OK; pass++) {
        double ta = fm_clock_seconds();
        memset(q.rhs, 0, (size_t)s->ncomp * n * sizeof *q.rhs);
        chord_rhs cr = {s, q.rhs, n};
        fm_fit_sample_sheet(pm, max_side, add_sample_rhs, &cr);
        double tb = fm_clock_seconds();
        st = solve_all(spd, s, q.rhs, n, name, err);
        s->stats.time_assemble += tb - ta;
        s->stats.time_solve += fm_clock_seconds() - tb;
    }
done:
    fm_fit_spd_destroy(spd);
    free(q.A);
    free(q.rhs);
    free(q.span_area);
    free(q.span_bend);
    free(colptr);
    free(rowind);
    free(val);
    return st;
}
