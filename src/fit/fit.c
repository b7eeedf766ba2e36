/* fm_fit_sheet: frame, grid, least squares, statistics. */
#include "fit_internal.h"
#include "fm_clock.h"
#include "fm_sort.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
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
    opt->knot_factor = 1.0;
    opt->max_control_points = 40000;
    opt->target_rms = 4.0;
    opt->target_max = 50.0;
    opt->max_refinements = 3;
    opt->smoothing = 0.0;
    opt->smoothing_wavelength = 1.0;
    opt->chord_passes = 1;
    opt->chord_weight = 0.75;
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

/* Distance from the vertex with frame coordinates q and parameters uv to
 * the tangent plane of the surface point at uv: first order in the fit
 * error, and cheap (no projection); *offset gets the distance to the point
 * itself. */
static double tangent_distance(const fm_fit_surface *s, const double q[3], const double uv[2],
                               double *offset)
{
    double P[3], D[5][3];
    fm_fit_local_eval(s, uv[0], uv[1], P, D);
    double r[3] = {P[0] - q[0], P[1] - q[1], P[2] - q[2]};
    double n[3] = {D[0][1] * D[1][2] - D[0][2] * D[1][1], D[0][2] * D[1][0] - D[0][0] * D[1][2],
                   D[0][0] * D[1][1] - D[0][1] * D[1][0]};
    double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    *offset = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    return nn > 0 ? fabs(r[0] * n[0] + r[1] * n[1] + r[2] * n[2]) / nn : *offset;
}

/* Quick vertex errors of the current coefficients (for the refinement). */
static void quick_errors(const fm_fit_surface *s, const fm_fit_pmesh *pm, const double *local,
                         const unsigned char *used, double *rms, double *max)
{
    double s2 = 0, mx = 0;
    size_t n = 0;
    for (size_t i = 0; i < pm->nv; i++) {
        if (!used[i])
            continue;
        double off, d = tangent_distance(s, local + 3 * i, pm->uv + 2 * i, &off);
        s2 += d * d;
        mx = fmax(mx, d);
        n++;
    }
    *rms = n ? sqrt(s2 / (double)n) : 0;
    *max = mx;
}

/* The parameters of the surface point closest to q (frame coordinates),
 * from its own parameters own, when the projection converges and comes
 * closer; else own. The trimming curves run through these (model.c), so
 * the offsets below are taken between them. */
static void snap_param(const fm_fit_surface *s, const double q[3], const double own[2],
                       double out[2])
{
    double P[3], d;
    fm_fit_local_eval(s, own[0], own[1], P, NULL);
    double d0 = sqrt((P[0] - q[0]) * (P[0] - q[0]) + (P[1] - q[1]) * (P[1] - q[1]) +
                     (P[2] - q[2]) * (P[2] - q[2]));
    out[0] = own[0];
    out[1] = own[1];
    double w[2] = {own[0], own[1]};
    if (fm_fit_project_from(s, q, w, P, &d) == FM_OK && fabs(d) < d0) {
        out[0] = w[0];
        out[1] = w[1];
    }
}

/* Largest offset of a boundary edge's midpoint (fm_fit_stats). Boundary
 * edges are those of one triangle. Returns -1 when out of memory. */
static double border_offset(const fm_fit_surface *s, const fm_fit_pmesh *pm, const double *local)
{
    size_t m = 3 * pm->nt;
    fm_keyed *key = malloc((m ? m : 1) * sizeof *key);
    if (!key)
        return -1;
    for (size_t t = 0; t < pm->nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = (uint32_t)pm->tri[3 * t + k], b = (uint32_t)pm->tri[3 * t + (k + 1) % 3];
            key[3 * t + k].key = a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a);
            key[3 * t + k].index = 3 * t + (size_t)k;
        }
    if (fm_sort_keyed(key, m) != 0) {
        free(key);
        return -1;
    }
    double worst = 0;
    for (size_t i = 0; i < m;) {
        size_t j = i;
        while (j < m && key[j].key == key[i].key)
            j++;
        if (j - i == 1) {
            size_t e[2] = {(size_t)(key[i].key >> 32), (size_t)(key[i].key & 0xffffffffu)};
            double uv[2][2], P[3], q[3];
            for (int k = 0; k < 2; k++)
                snap_param(s, local + 3 * e[k], pm->uv + 2 * e[k], uv[k]);
            size_t a = e[0], b = e[1];
            fm_fit_local_eval(s, 0.5 * (uv[0][0] + uv[1][0]), 0.5 * (uv[0][1] + uv[1][1]), P,
                              NULL);
            for (int c = 0; c < 3; c++)
                q[c] = 0.5 * (local[3 * a + c] + local[3 * b + c]) - P[c];
            worst = fmax(worst, sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]));
        }
        i = j;
    }
    free(key);
    return worst;
}

static fm_status compute_stats(fm_fit_surface *s, const fm_fit_pmesh *pm, const double *local,
                               const unsigned char *used, int closest)
{
    fm_fit_stats *st = &s->stats;
    double sw2 = 0, sd2 = 0;
    size_t count = 0;
    for (size_t i = 0; i < pm->nv; i++) {
        if (!used[i])
            continue;
        const double *q = local + 3 * i;
        double ew;
        if (s->ncomp == 1)
            ew = fabs(q[2] - fm_fit_surface_height(s, q[0], q[1], NULL));
        else
            tangent_distance(s, q, pm->uv + 2 * i, &ew);
        sw2 += ew * ew;
        if (ew > st->max_w)
            st->max_w = ew;
        if (closest) {
            /* Start at the vertex's own parameters: on a parametric sheet
             * that passes near itself, the right branch. */
            double uv[2] = {pm->uv[2 * i], pm->uv[2 * i + 1]}, P[3], d;
            if (fm_fit_project_from(s, q, uv, P, &d) != FM_OK)
                st->projection_failures++;
            d = fabs(d);
            sd2 += d * d;
            if (d > st->max_dist)
                st->max_dist = d;
        }
        count++;
    }
    if (closest) {
        st->max_border_offset = border_offset(s, pm, local);
        if (st->max_border_offset < 0)
            return FM_ERR_NOMEM;
    }
    st->vertices = count;
    st->rms_w = count ? sqrt(sw2 / (double)count) : 0;
    st->rms_dist = count ? sqrt(sd2 / (double)count) : 0;
    return FM_OK;
}

/* Knots and coefficient storage for spacing sp over [umin, umax] x
 * [vmin, vmax] plus the margin. */
static fm_status make_grid(fm_fit_surface *s, double sp, const double ext[4], double extend,
                           const char *name, fm_error *err)
{
    int p = s->p;
    double width = ext[1] - ext[0] + 2 * extend, height = ext[3] - ext[2] + 2 * extend;
    size_t nsu = spans_for(width, sp), nsv = spans_for(height, sp);
    if ((nsu + (size_t)p) > HARD_MAX_COEF / (nsv + (size_t)p))
        return fm_error_set(err, FM_ERR_INVALID, name, 0,
                            "fit: knot spacing %g m gives %zu x %zu spans, too many", sp, nsu, nsv);
    free(s->coef);
    free(s->knots_u);
    free(s->knots_v);
    s->s = sp;
    s->nsu = nsu;
    s->nsv = nsv;
    s->nu = nsu + (size_t)p;
    s->nv = nsv + (size_t)p;
    /* Centre the whole number of spans on the extent. */
    s->u0 = 0.5 * (ext[0] + ext[1]) - 0.5 * (double)nsu * sp;
    s->v0 = 0.5 * (ext[2] + ext[3]) - 0.5 * (double)nsv * sp;
    s->coef = calloc((size_t)s->ncomp * s->nu * s->nv, sizeof *s->coef);
    s->knots_u = malloc((nsu + 2 * (size_t)p + 1) * sizeof *s->knots_u);
    s->knots_v = malloc((nsv + 2 * (size_t)p + 1) * sizeof *s->knots_v);
    if (!s->coef || !s->knots_u || !s->knots_v)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (coefficients)");
    for (size_t k = 0; k < nsu + 2 * (size_t)p + 1; k++)
        s->knots_u[k] = s->u0 + ((double)k - p) * sp;
    for (size_t k = 0; k < nsv + 2 * (size_t)p + 1; k++)
        s->knots_v[k] = s->v0 + ((double)k - p) * sp;
    fm_fit_stats *fs = &s->stats;
    fs->knot_spacing = sp;
    fs->spans_u = nsu;
    fs->spans_v = nsv;
    fs->control_u = s->nu;
    fs->control_v = s->nv;
    return FM_OK;
}

static size_t grid_size(double sp, const double ext[4], double extend, int p)
{
    size_t a = spans_for(ext[1] - ext[0] + 2 * extend, sp) + (size_t)p;
    size_t b = spans_for(ext[3] - ext[2] + 2 * extend, sp) + (size_t)p;
    return a > HARD_MAX_COEF / b ? HARD_MAX_COEF + 1 : a * b;
}

/* Everything fm_fit_sheet allocates besides the surface. */
typedef struct work {
    fm_fit_pmesh pm;
    double *local;         /* 3 per vertex: frame coordinates */
    unsigned char *used;
    double *plain;         /* the solution without chord correction */
} work;

static void work_free(work *w)
{
    free(w->plain);
    free(w->pm.uv);
    free(w->pm.val);
    free(w->local);
    free(w->used);
}

/* Parameters and values of the chosen kind; vertices the triangles do not
 * use keep their plane projection (they take no part). */
static fm_status parameterize(fm_fit_surface *s, const fm_mesh *sheet, work *w,
                              const fm_fit_options *opt, fm_error *err)
{
    fm_fit_pmesh *pm = &w->pm;
    size_t nv = pm->nv;
    const char *name = opt->name;
    double t0 = fm_clock_seconds();
    for (size_t i = 0; i < nv; i++) {
        pm->uv[2 * i] = w->local[3 * i];
        pm->uv[2 * i + 1] = w->local[3 * i + 1];
    }
    fm_fit_kind kind = opt->kind;
    if (kind == FM_FIT_AUTO) {
        kind = FM_FIT_HEIGHT_FIELD;
        if (!s->frame.projectable) {
            kind = FM_FIT_PARAMETRIC;
        } else {
            pm->ncomp = 1;
            double proj = s->frame.mean_dot * s->frame.area;
            s->stats.overlap = proj > 0 ? fm_fit_overlap_area(pm) / proj : 0;
            if (s->stats.overlap > 0) {
                kind = FM_FIT_PARAMETRIC;
            } else {
                /* Parts of the sheet that the plane stacks within two edges
                 * of each other, at heights a spline on knots of about an
                 * edge cannot switch between (more than half an edge, and
                 * steeper than twice the steepest facet, plus one). */
                double md = s->frame.min_dot, e = s->stats.edge_median;
                double smax = sqrt(fmax(1 - md * md, 0)) / md;
                pm->val = malloc(nv * sizeof *pm->val);
                if (!pm->val)
                    return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory");
                for (size_t i = 0; i < nv; i++)
                    pm->val[i] = w->local[3 * i + 2];
                s->stats.stacked =
                    fm_fit_stacked_vertices(pm, w->used, 2 * e, 0.5 * e, 2 * smax + 1);
                free(pm->val);
                pm->val = NULL;
            }
        }
    }
    s->kind = kind;
    s->stats.kind = kind;
    s->ncomp = kind == FM_FIT_PARAMETRIC ? 3 : 1;
    pm->ncomp = s->ncomp;
    if (kind == FM_FIT_PARAMETRIC) {
        fm_status st = fm_fit_lscm(sheet, pm->uv, &s->stats.lscm_flipped, name, err);
        if (st != FM_OK)
            return st;
        /* The conformal map is one-to-one in practice but not by proof: an
         * unrolled sheet can lap over itself. Then the convex-boundary map,
         * one-to-one by construction, at the price of more distortion. */
        if (s->stats.lscm_flipped > 0 || fm_fit_overlap_area(pm) > 0) {
            st = fm_fit_convex_map(sheet, pm->uv, name, err);
            if (st != FM_OK)
                return st;
            s->stats.convex_map = 1;
        }
        pm->val = malloc(3 * nv * sizeof *pm->val);
        s->vparams = malloc(2 * nv * sizeof *s->vparams);
        if (!pm->val || !s->vparams)
            return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory");
        for (size_t i = 0; i < 3 * nv; i++)
            pm->val[i] = w->local[i];
        for (size_t i = 0; i < 2 * nv; i++)
            s->vparams[i] = pm->uv[i];
        s->nvparams = nv;
    } else {
        pm->val = malloc(nv * sizeof *pm->val);
        if (!pm->val)
            return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory");
        for (size_t i = 0; i < nv; i++)
            pm->val[i] = w->local[3 * i + 2];
    }
    s->stats.time_param = fm_clock_seconds() - t0;
    return FM_OK;
}

/* S at every span centre, where fm_fit_project starts on a parametric
 * surface. */
static fm_status make_starts(fm_fit_surface *s)
{
    free(s->starts);
    s->starts = malloc(3 * s->nsu * s->nsv * sizeof *s->starts);
    if (!s->starts)
        return FM_ERR_NOMEM;
    for (size_t j = 0; j < s->nsv; j++)
        for (size_t i = 0; i < s->nsu; i++)
            fm_fit_local_eval(s, s->u0 + ((double)i + 0.5) * s->s, s->v0 + ((double)j + 0.5) * s->s,
                              s->starts + 3 * (j * s->nsu + i), NULL);
    return FM_OK;
}

/* One fit of one kind, run in stages so that a caller can look at it
 * before it is finished (fm_fit_pending): begun up to the first solve,
 * passes solved up to a refinement limit, then finished. */
typedef struct fit_run {
    fm_fit_surface *s;
    work w;
    fm_fit_options opt;
    double ext[4], sp, lambda, prev_rms;
    int refine, blend;
    int pass;   /* the pass being worked on */
    int solved; /* pass `pass` is solved, its refinement decision not yet taken */
    int done;   /* no pass follows */
    double time; /* active time so far */
} fit_run;

static void run_destroy(fit_run *r)
{
    if (!r)
        return;
    fm_fit_surface_destroy(r->s);
    work_free(&r->w);
    free(r);
}

/* The options check, frame (computed unless given: it must be the one of
 * opt->frame), parameters and grid spacing of fm_fit_sheet's fit. */
static fm_status run_begin(const fm_mesh *sheet, const fm_fit_options *opt,
                           const fm_fit_frame *frame, fit_run **out, fm_error *err)
{
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
    if (!(opt->chord_weight >= 0 && opt->chord_weight <= 1))
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "fit: chord_weight must be in 0..1");
    if (opt->kind < FM_FIT_AUTO || opt->kind > FM_FIT_PARAMETRIC)
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "fit: unknown kind %d", (int)opt->kind);
    if (opt->max_refinements < 0 || opt->max_refinements > 4 || !(opt->target_rms > 0) ||
        !(opt->target_max > 0))
        return fm_error_set(err, FM_ERR_INVALID, name, 0,
                            "fit: max_refinements must be 0..4, target_rms and target_max > 0");
    int p = opt->degree;
    if (opt->knot_spacing == 0 && opt->max_control_points < (size_t)(p + 1) * (size_t)(p + 1))
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "fit: max_control_points too small");

    double t_start = fm_clock_seconds();
    fit_run *r = calloc(1, sizeof *r);
    fm_fit_surface *s = calloc(1, sizeof *s);
    if (!r || !s) {
        free(r);
        free(s);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory");
    }
    r->s = s;
    r->opt = *opt;
    work *w = &r->w;
    fm_status st = FM_OK;
    if (frame) {
        s->frame = *frame;
    } else {
        st = fm_fit_reference_frame(sheet, &opt->frame, &s->frame, err);
        if (st != FM_OK) {
            if (err && name) { /* put the sheet's name in front of the frame's message */
                fm_error tmp = *err;
                fm_error_set(err, st, name, 0, "%s", tmp.message);
            }
            run_destroy(r);
            return st;
        }
    }
    s->p = p;
    s->stats.degree = p;
    s->stats.triangles = fm_mesh_ntriangles(sheet);
    double t_frame = fm_clock_seconds();

    const double *X = fm_mesh_vertices(sheet);
    const int32_t *T = fm_mesh_triangles(sheet);
    size_t nt = fm_mesh_ntriangles(sheet), nv = fm_mesh_nvertices(sheet);
    w->pm.nv = nv;
    w->pm.nt = nt;
    w->pm.tri = T;
    w->local = malloc((nv ? nv : 1) * 3 * sizeof *w->local);
    w->pm.uv = malloc((nv ? nv : 1) * 2 * sizeof *w->pm.uv);
    w->used = calloc(nv ? nv : 1, 1);
    if (!w->local || !w->pm.uv || !w->used || median_edge(sheet, &s->stats.edge_median) != FM_OK) {
        run_destroy(r);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory");
    }
    for (size_t i = 0; i < nv; i++)
        fm_fit_frame_to_local(&s->frame, X + 3 * i, w->local + 3 * i);
    for (size_t i = 0; i < 3 * nt; i++)
        w->used[T[i]] = 1;
    st = parameterize(s, sheet, w, opt, err);
    if (st != FM_OK) {
        run_destroy(r);
        return st;
    }

    /* Extent of the sheet in the parameter plane. */
    double *ext = r->ext;
    ext[0] = ext[2] = INFINITY;
    ext[1] = ext[3] = -INFINITY;
    for (size_t i = 0; i < nv; i++)
        if (w->used[i]) {
            ext[0] = fmin(ext[0], w->pm.uv[2 * i]);
            ext[1] = fmax(ext[1], w->pm.uv[2 * i]);
            ext[2] = fmin(ext[2], w->pm.uv[2 * i + 1]);
            ext[3] = fmax(ext[3], w->pm.uv[2 * i + 1]);
        }

    double e = s->stats.edge_median;
    double sp = opt->knot_spacing;
    r->refine = sp == 0 ? opt->max_refinements : 0;
    if (sp == 0) {
        sp = opt->knot_factor * e;
        if (!(sp > 0)) /* unreachable for a sheet with area; keeps the loop finite */
            sp = fmax(ext[1] - ext[0], ext[3] - ext[2]) + 2 * opt->extend + 1;
        /* Coarse enough for the coefficient budget; growing by 1 % keeps the
         * spacing within 1 % of the finest grid that fits. */
        while (grid_size(sp, ext, opt->extend, p) > opt->max_control_points)
            sp *= 1.01;
    }
    r->sp = sp;
    double lambda = opt->smoothing;
    if (lambda == 0) {
        /* Tied to the data's spacing, not the knots': the triangles cannot
         * show waves shorter than about two edges, so smoothing those away
         * loses nothing, whatever grid carries the result. */
        double c = opt->smoothing_wavelength * e / (2 * FM_PI);
        lambda = c * c * c * c;
    }
    r->lambda = lambda;
    s->stats.smoothing = lambda;
    /* A partial chord correction is the blend of the uncorrected and the
     * corrected solution (the right-hand side is linear in the values).
     * The refinement judges the corrected one, which passes through the
     * vertices where the grid can follow the sheet: the offset the blend
     * leaves at the vertices is meant, not a sign of too coarse a grid. */
    r->blend = opt->chord_passes > 0 && opt->chord_weight < 1;
    r->prev_rms = INFINITY;
    s->stats.time_frame = t_frame - t_start;
    r->time = fm_clock_seconds() - t_start;
    *out = r;
    return FM_OK;
}

/* Solves passes and refines the grid until the fit is done or pass `limit`
 * is solved; a later call with a higher limit goes on from there, exactly
 * as if it had never stopped. */
static fm_status run_passes(fit_run *r, int limit, fm_error *err)
{
    double t0 = fm_clock_seconds();
    fm_fit_surface *s = r->s;
    work *w = &r->w;
    const fm_fit_options *opt = &r->opt;
    const char *name = opt->name;
    int p = s->p;
    fm_status st = FM_OK;
    while (!r->done && st == FM_OK) {
        if (!r->solved) {
            st = make_grid(s, r->sp, r->ext, opt->extend, name, err);
            if (st == FM_OK && r->blend) {
                free(w->plain);
                w->plain = malloc((size_t)s->ncomp * s->nu * s->nv * sizeof *w->plain);
                if (!w->plain)
                    st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory");
            }
            if (st == FM_OK)
                st = fm_fit_solve_coefficients(s, &w->pm, r->lambda, opt->chord_passes, w->plain,
                                               name, err);
            for (size_t i = 0; st == FM_OK && i < (size_t)s->ncomp * s->nu * s->nv; i++)
                if (!isfinite(s->coef[i]))
                    st = fm_error_set(err, FM_ERR_NUMERIC, name, 0, "fit: solution is not finite");
            if (st != FM_OK)
                break;
            s->stats.passes = r->pass;
            r->solved = 1;
        }
        if (r->pass >= r->refine) {
            r->done = 1;
            break;
        }
        if (r->pass >= limit)
            break;
        /* Refine while the vertices miss the target: half the spacing, as
         * long as the grid stays in the budget. */
        double rms, max;
        quick_errors(s, &w->pm, w->local, w->used, &rms, &max);
        r->done = 1;
        if (rms <= opt->target_rms && max <= opt->target_max)
            break;
        /* Near the targets one halving is worth its cost; a sheet whose
         * RMS is still twice the target may halve again, and on up to twice
         * the budget (a single far vertex, a flap of a triangle or two, is
         * not worth a grid four times as large). */
        int far = rms > 2 * opt->target_rms;
        /* ... and only while halving pays: a sheet whose misfit is not at
         * the scale of the knots (a fold of a few triangles, a distorted
         * map) gains nothing from a finer grid but its cost. */
        if (r->pass >= 1 && (!far || rms > 0.8 * r->prev_rms))
            break;
        r->prev_rms = rms;
        size_t budget = far ? 2 * opt->max_control_points : opt->max_control_points;
        if (grid_size(0.5 * r->sp, r->ext, opt->extend, p) > budget)
            break;
        r->sp *= 0.5;
        r->pass++;
        r->solved = 0;
        r->done = 0;
    }
    r->time += fm_clock_seconds() - t0;
    return st;
}

/* The final coefficients of the passes solved so far (the blend of a
 * partial chord correction) in s->coef. */
static void run_blend(fit_run *r)
{
    fm_fit_surface *s = r->s;
    if (r->blend) {
        double cw = r->opt.chord_weight;
        for (size_t i = 0; i < (size_t)s->ncomp * s->nu * s->nv; i++)
            s->coef[i] = cw * s->coef[i] + (1 - cw) * r->w.plain[i];
    }
}

/* The statistics the fit would have if it were finished now without
 * closest points (vertex errors along w or at the own parameters), the
 * run left as it was. */
static fm_status run_peek(fit_run *r, fm_fit_stats *out)
{
    fm_fit_surface *s = r->s;
    size_t n = (size_t)s->ncomp * s->nu * s->nv;
    double *keep = malloc((n ? n : 1) * sizeof *keep);
    if (!keep)
        return FM_ERR_NOMEM;
    memcpy(keep, s->coef, n * sizeof *keep);
    fm_fit_stats saved = s->stats;
    run_blend(r);
    fm_status st = compute_stats(s, &r->w.pm, r->w.local, r->w.used, 0);
    *out = s->stats;
    s->stats = saved;
    memcpy(s->coef, keep, n * sizeof *keep);
    free(keep);
    return st;
}

/* The finished surface (fm_fit_sheet's statistics); r is consumed. */
static fm_status run_finish(fit_run *r, fm_fit_surface **out, fm_error *err)
{
    double t0 = fm_clock_seconds();
    fm_fit_surface *s = r->s;
    const char *name = r->opt.name;
    *out = NULL;
    run_blend(r);
    if (s->kind == FM_FIT_PARAMETRIC && make_starts(s) != FM_OK) {
        run_destroy(r);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory");
    }
    double t_solved = fm_clock_seconds();
    if (compute_stats(s, &r->w.pm, r->w.local, r->w.used, r->opt.closest_point_stats) != FM_OK) {
        run_destroy(r);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory");
    }
    double t_end = fm_clock_seconds();
    fm_fit_stats *fs = &s->stats;
    fs->time_stats = t_end - t_solved;
    fs->time_total = r->time + (t_end - t0);
    r->s = NULL;
    run_destroy(r);
    *out = s;
    return FM_OK;
}

/* How far a fit is from its targets: the worse of the vertex RMS and
 * largest distance, each over its target (true distances when measured). */
static double fit_score(const fm_fit_stats *st, const fm_fit_options *opt)
{
    double rms = st->rms_dist > 0 ? st->rms_dist : st->rms_w;
    double max = st->max_dist > 0 ? st->max_dist : st->max_w;
    /* Between the outline's vertices too: the trimming curve runs there. */
    max = fmax(max, st->max_border_offset);
    return fmax(rms / opt->target_rms, max / opt->target_max);
}

/* A steep or stacked height field that misses the targets (see fm_fit.h)
 * is fitted as a parametric surface too, and the closer of the two to the
 * targets is kept. */
static int wants_parametric(const fm_fit_options *opt, const fm_fit_frame *frame,
                            const fm_fit_stats *st)
{
    return opt->kind == FM_FIT_AUTO && st->kind == FM_FIT_HEIGHT_FIELD &&
           (frame->min_dot < FM_FIT_STEEP_DOT || st->stacked > 0 ||
            st->max_border_offset > 2 * opt->target_max) &&
           fit_score(st, opt) > 1;
}

struct fm_fit_pending {
    const fm_mesh *sheet;
    fm_fit_options opt;
    fm_fit_frame frame;
    fit_run *run; /* the fit of the options' kind */
    fit_run *alt; /* the parametric one, when a trial looked at it */
    int alt_failed;
};

void fm_fit_pending_destroy(fm_fit_pending *pf)
{
    if (!pf)
        return;
    run_destroy(pf->run);
    run_destroy(pf->alt);
    free(pf);
}

fm_status fm_fit_pending_begin(const fm_mesh *sheet, const fm_fit_options *opt,
                               const fm_fit_frame *frame, fm_fit_pending **out, fm_error *err)
{
    fm_fit_options defaults;
    if (!opt) {
        fm_fit_options_default(&defaults);
        opt = &defaults;
    }
    *out = NULL;
    fm_fit_pending *pf = calloc(1, sizeof *pf);
    if (!pf)
        return fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "fit: out of memory");
    pf->sheet = sheet;
    pf->opt = *opt;
    fm_status st = run_begin(sheet, opt, frame, &pf->run, err);
    if (st != FM_OK) {
        free(pf);
        return st;
    }
    pf->frame = pf->run->s->frame;
    *out = pf;
    return FM_OK;
}

const fm_fit_frame *fm_fit_pending_frame(const fm_fit_pending *pf) { return &pf->frame; }
const fm_fit_stats *fm_fit_pending_stats(const fm_fit_pending *pf) { return &pf->run->s->stats; }

/* The parametric run of a height field that wants one, begun when needed;
 * NULL when it failed (as fm_fit_sheet, the height field then stays). */
static fit_run *pending_alt(fm_fit_pending *pf)
{
    if (!pf->alt && !pf->alt_failed) {
        fm_fit_options po = pf->opt;
        po.kind = FM_FIT_PARAMETRIC;
        fm_error e2;
        if (run_begin(pf->sheet, &po, &pf->frame, &pf->alt, &e2) != FM_OK)
            pf->alt_failed = 1;
    }
    return pf->alt;
}

static void alt_failed(fm_fit_pending *pf)
{
    run_destroy(pf->alt);
    pf->alt = NULL;
    pf->alt_failed = 1;
}

fm_status fm_fit_pending_trial(fm_fit_pending *pf, int refinements, fm_fit_stats *out)
{
    fm_error e;
    fm_fit_options to = pf->opt;
    to.closest_point_stats = 0;
    fm_status st = run_passes(pf->run, refinements, &e);
    if (st == FM_OK)
        st = run_peek(pf->run, out);
    if (st != FM_OK || !wants_parametric(&to, &pf->frame, out))
        return st;
    fit_run *alt = pending_alt(pf);
    if (alt && run_passes(alt, refinements, &e) != FM_OK)
        alt_failed(pf);
    fm_fit_stats as;
    if (!pf->alt || run_peek(pf->alt, &as) != FM_OK)
        return FM_OK;
    if (fit_score(&as, &to) < fit_score(out, &to))
        *out = as;
    return FM_OK;
}

fm_status fm_fit_pending_finish(fm_fit_pending *pf, fm_fit_surface **out, fm_error *err)
{
    *out = NULL;
    fit_run *run = pf->run;
    pf->run = NULL;
    fm_status st = run_passes(run, INT_MAX, err);
    if (st != FM_OK) {
        run_destroy(run);
        fm_fit_pending_destroy(pf);
        return st;
    }
    const fm_fit_options *opt = &pf->opt;
    st = run_finish(run, out, err);
    if (st != FM_OK || !wants_parametric(opt, &(*out)->frame, &(*out)->stats)) {
        fm_fit_pending_destroy(pf);
        return st;
    }
    fit_run *alt = pending_alt(pf);
    pf->alt = NULL;
    fm_fit_surface *as = NULL;
    fm_error e2;
    if (alt && run_passes(alt, INT_MAX, &e2) == FM_OK)
        run_finish(alt, &as, &e2);
    else
        run_destroy(alt);
    if (as && fit_score(&as->stats, opt) < fit_score(&(*out)->stats, opt)) {
        fm_fit_surface_destroy(*out);
        *out = as;
    } else {
        fm_fit_surface_destroy(as);
    }
    fm_fit_pending_destroy(pf);
    return FM_OK;
}

fm_status fm_fit_sheet(const fm_mesh *sheet, const fm_fit_options *opt, fm_fit_surface **out,
                       fm_error *err)
{
    fm_fit_pending *pf = NULL;
    *out = NULL;
    fm_status st = fm_fit_pending_begin(sheet, opt, NULL, &pf, err);
    return st == FM_OK ? fm_fit_pending_finish(pf, out, err) : st;
}
