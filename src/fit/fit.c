/* fm_fit_sheet: frame, grid, least squares, statistics. */
#include "fit_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FM_PI 3.14159265358979323846

/* No automatic or explicit grid may grow past this many coefficients: the
 * solver's memory, not the geometry, is the limit. */
#define HARD_MAX_COEF ((size_t)4000000)

void fm_fit_options_default(fm_fit_options *opt)
{
    memset(opt, 0, sizeof *opt);
    fm_fit_frame_options_default(&opt->frame);
    opt->degree = 3;
    opt->extend = 2000.0;
    opt->knot_spacing = 0.0;
    opt->knot_factor = 2.0;
    opt->max_control_points = 40000;
    opt->smoothing = 0.0;
    opt->smoothing_wavelength = 2.0;
    opt->chord_passes = 1;
    opt->closest_point_stats = 1;
}

/* k-th smallest by quickselect (deterministic middle pivot). */
static double select_kth(double *a, size_t n, size_t k)
{
    size_t lo = 0, hi = n - 1;
    while (lo < hi) {
        double pivot = a[lo + (hi - lo) / 2];
        size_t i = lo, j = hi;
        while (i <= j) {
            while (a[i] < pivot)
                i++;
            while (a[j] > pivot)
                j--;
            if (i <= j) {
                double t = a[i];
                a[i] = a[j];
                a[j] = t;
                i++;
                if (j == 0)
                    break;
                j--;
            }
        }
        if (k <= j)
            hi = j;
        else if (k >= i)
            lo = i;
        else
            return a[k];
    }
    return a[k];
}

/* Median over triangle sides (an inner edge counts twice, which leaves the
 * median of a regular mesh where it is). */
static fm_status median_edge(const fm_mesh *m, double *out)
{
    const double *X = fm_mesh_vertices(m);
    const int32_t *T = fm_mesh_triangles(m);
    size_t nt = fm_mesh_ntriangles(m), n = 0;
    double *len = malloc(3 * nt * sizeof *len);
    if (!len)
        return FM_ERR_NOMEM;
    for (size_t i = 0; i < nt; i++)
        for (int c = 0; c < 3; c++) {
            const double *a = X + 3 * (size_t)T[3 * i + c], *b = X + 3 * (size_t)T[3 * i + (c + 1) % 3];
            double d = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                            (a[2] - b[2]) * (a[2] - b[2]));
            if (d > 0)
                len[n++] = d;
        }
    *out = n ? select_kth(len, n, n / 2) : 0.0;
    free(len);
    return FM_OK;
}

/* Spans to cover width; capped so that absurd options fail the size check
 * instead of overflowing the conversion. */
static size_t spans_for(double width, double s)
{
    double n = ceil(width / s - 1e-9);
    if (!(n < 1e9))
        return (size_t)1000000000;
    return n < 1 ? 1 : (size_t)n;
}

typedef struct sample_err {
    const fm_fit_surface *s;
    int chord;
    double sum_w, sum_we2;
} sample_err;

static void add_sample_error(void *ctx, const fm_fit_sample *smp)
{
    sample_err *e = ctx;
    double dh[5];
    double d = smp->h - fm_fit_surface_height(e->s, smp->u, smp->v, dh);
    if (e->chord)
        d -= smp->chord[0] * dh[2] + 2 * smp->chord[1] * dh[3] + smp->chord[2] * dh[4];
    e->sum_w += smp->weight;
    e->sum_we2 += smp->weight * d * d;
}

static fm_status compute_stats(fm_fit_surface *s, const fm_mesh *sheet, int closest, int chord,
                               const char *name, fm_error *err)
{
    fm_fit_stats *st = &s->stats;
    size_t nv = fm_mesh_nvertices(sheet), nt = fm_mesh_ntriangles(sheet);
    const double *X = fm_mesh_vertices(sheet);
    const int32_t *T = fm_mesh_triangles(sheet);
    unsigned char *used = calloc(nv ? nv : 1, 1);
    if (!used)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (stats)");
    for (size_t i = 0; i < 3 * nt; i++)
        used[T[i]] = 1;
    double sw2 = 0, sd2 = 0;
    size_t count = 0;
    for (size_t i = 0; i < nv; i++) {
        if (!used[i])
            continue;
        double q[3];
        fm_fit_frame_to_local(&s->frame, X + 3 * i, q);
        double ew = fabs(q[2] - fm_fit_surface_height(s, q[0], q[1], NULL));
        sw2 += ew * ew;
        if (ew > st->max_w)
            st->max_w = ew;
        if (closest) {
            double uv[2], d;
            if (fm_fit_project(s, X + 3 * i, uv, NULL, &d) != FM_OK)
                st->projection_failures++;
            d = fabs(d);
            sd2 += d * d;
            if (d > st->max_dist)
                st->max_dist = d;
        }
        count++;
    }
    free(used);
    st->vertices = count;
    st->rms_w = count ? sqrt(sw2 / (double)count) : 0;
    st->rms_dist = count ? sqrt(sd2 / (double)count) : 0;
    sample_err e = {s, chord, 0, 0};
    fm_fit_sample_sheet(sheet, &s->frame, s->s, add_sample_error, &e);
    st->rms_samples_w = e.sum_w > 0 ? sqrt(e.sum_we2 / e.sum_w) : 0;
    return FM_OK;
}

fm_status fm_fit_sheet(const fm_mesh *sheet, const fm_fit_options *opt, fm_fit_surface **out,
                       fm_error *err)
{
    fm_fit_options defaults;
    if (!opt) {
        fm_fit_options_default(&defaults);
        opt = &defaults;
    }
    const char *name = opt->name;
    *out = NULL;
    if (!sheet)
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "fit: no sheet");
    if (opt->degree < 2 || opt->degree > FM_FIT_MAX_DEGREE)
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "fit: degree must be 2..%d, not %d",
                            FM_FIT_MAX_DEGREE, opt->degree);
    if (!(opt->extend >= 0) || !(opt->knot_spacing >= 0) || !(opt->smoothing >= 0) ||
        !isfinite(opt->extend) || !isfinite(opt->knot_spacing) || !isfinite(opt->smoothing))
        return fm_error_set(err, FM_ERR_INVALID, name, 0,
                            "fit: extend, knot_spacing and smoothing must be finite and >= 0");
    if (opt->knot_spacing == 0 && !(opt->knot_factor > 0 && isfinite(opt->knot_factor)))
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "fit: knot_factor must be > 0");
    if (opt->smoothing == 0 && !(opt->smoothing_wavelength > 0 && isfinite(opt->smoothing_wavelength)))
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "fit: smoothing_wavelength must be > 0");
    if (opt->chord_passes < 0 || opt->chord_passes > 10)
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "fit: chord_passes must be 0..10");
    int p = opt->degree;
    if (opt->knot_spacing == 0 && opt->max_control_points < (size_t)(p + 1) * (size_t)(p + 1))
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "fit: max_control_points too small");

    double t_start = fm_fit_now();
    fm_fit_surface *s = calloc(1, sizeof *s);
    if (!s)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory");
    fm_status st = fm_fit_reference_frame(sheet, &opt->frame, &s->frame, err);
    if (st != FM_OK) {
        if (err && name) { /* put the sheet's name in front of the frame's message */
            fm_error tmp = *err;
            fm_error_set(err, st, name, 0, "%s", tmp.message);
        }
        fm_fit_surface_destroy(s);
        return st;
    }
    s->p = p;
    s->stats.degree = p;
    s->stats.triangles = fm_mesh_ntriangles(sheet);
    double t_frame = fm_fit_now();

    /* Extent of the projected sheet. */
    const double *X = fm_mesh_vertices(sheet);
    const int32_t *T = fm_mesh_triangles(sheet);
    size_t nt = fm_mesh_ntriangles(sheet);
    double umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
    for (size_t i = 0; i < 3 * nt; i++) {
        double q[3];
        fm_fit_frame_to_local(&s->frame, X + 3 * (size_t)T[i], q);
        umin = fmin(umin, q[0]);
        umax = fmax(umax, q[0]);
        vmin = fmin(vmin, q[1]);
        vmax = fmax(vmax, q[1]);
    }
    double width = umax - umin + 2 * opt->extend, height = vmax - vmin + 2 * opt->extend;

    if (median_edge(sheet, &s->stats.edge_median) != FM_OK) {
        fm_fit_surface_destroy(s);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (edges)");
    }
    double sp = opt->knot_spacing;
    if (sp == 0) {
        sp = opt->knot_factor * s->stats.edge_median;
        if (!(sp > 0)) /* unreachable for a sheet with area; keeps the loop finite */
            sp = fmax(width, height);
        /* Coarse enough for the coefficient budget; growing by 1 % keeps the
         * spacing within 1 % of the finest grid that fits. */
        while ((spans_for(width, sp) + (size_t)p) * (spans_for(height, sp) + (size_t)p) >
               opt->max_control_points)
            sp *= 1.01;
    }
    size_t nsu = spans_for(width, sp), nsv = spans_for(height, sp);
    if ((nsu + (size_t)p) > HARD_MAX_COEF / (nsv + (size_t)p)) {
        fm_fit_surface_destroy(s);
        return fm_error_set(err, FM_ERR_INVALID, name, 0,
                            "fit: knot spacing %g m gives %zu x %zu spans, too many", sp, nsu, nsv);
    }
    s->s = sp;
    s->nsu = nsu;
    s->nsv = nsv;
    s->nu = nsu + (size_t)p;
    s->nv = nsv + (size_t)p;
    /* Centre the whole number of spans on the extent. */
    s->u0 = 0.5 * (umin + umax) - 0.5 * (double)nsu * sp;
    s->v0 = 0.5 * (vmin + vmax) - 0.5 * (double)nsv * sp;
    s->coef = calloc(s->nu * s->nv, sizeof *s->coef);
    s->knots_u = malloc((nsu + 2 * (size_t)p + 1) * sizeof *s->knots_u);
    s->knots_v = malloc((nsv + 2 * (size_t)p + 1) * sizeof *s->knots_v);
    if (!s->coef || !s->knots_u || !s->knots_v) {
        fm_fit_surface_destroy(s);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (coefficients)");
    }
    for (size_t k = 0; k < nsu + 2 * (size_t)p + 1; k++)
        s->knots_u[k] = s->u0 + ((double)k - p) * sp;
    for (size_t k = 0; k < nsv + 2 * (size_t)p + 1; k++)
        s->knots_v[k] = s->v0 + ((double)k - p) * sp;

    double lambda = opt->smoothing;
    if (lambda == 0) {
        /* Tied to the data's spacing, not the knots': the triangles cannot
         * show waves shorter than about two edges, so smoothing those away
         * loses nothing, whatever grid carries the result. */
        double c = opt->smoothing_wavelength * s->stats.edge_median / (2 * FM_PI);
        lambda = c * c * c * c;
    }
    fm_fit_stats *fs = &s->stats;
    fs->knot_spacing = sp;
    fs->smoothing = lambda;
    fs->spans_u = nsu;
    fs->spans_v = nsv;
    fs->control_u = s->nu;
    fs->control_v = s->nv;
    st = fm_fit_solve_coefficients(s, sheet, lambda, opt->chord_passes, name, err);
    if (st != FM_OK) {
        fm_fit_surface_destroy(s);
        return st;
    }
    for (size_t i = 0; i < s->nu * s->nv; i++)
        if (!isfinite(s->coef[i])) {
            fm_fit_surface_destroy(s);
            return fm_error_set(err, FM_ERR_NUMERIC, name, 0, "fit: solution is not finite");
        }
    double t_solved = fm_fit_now();
    st = compute_stats(s, sheet, opt->closest_point_stats, opt->chord_passes > 0, name, err);
    if (st != FM_OK) {
        fm_fit_surface_destroy(s);
        return st;
    }
    double t_end = fm_fit_now();
    fs->time_frame = t_frame - t_start;
    fs->time_stats = t_end - t_solved;
    fs->time_total = t_end - t_start;
    *out = s;
    return FM_OK;
}
