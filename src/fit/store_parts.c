/* The fitted surface and trimming loops of a stored model, field by field
 * (model_store.c frames them; fm_bytes.h writes the numbers). Every
 * field is kept, the statistics and times too, so that a model read back
 * is the one written, bit for bit, and whatever a later stage reads of it
 * is what it would have read of the fit. */
#include "store_parts.h"

#include <stdlib.h>
#include <string.h>

#include "fit_internal.h"
#include "trim_internal.h"

/* A field added to one of these structures must be added below, and
 * FM_MODEL_FORMAT_VERSION raised (fm_model.h): these sizes are those of
 * the fields stored (LP64), so a new one stops the build here. */
#if UINTPTR_MAX == UINT64_MAX
_Static_assert(sizeof(fm_fit_frame) == 152, "store the new fm_fit_frame field");
_Static_assert(sizeof(fm_fit_stats) == 224, "store the new fm_fit_stats field");
_Static_assert(sizeof(struct fm_fit_surface) == 496, "store the new fm_fit_surface field");
_Static_assert(sizeof(fm_trim_stats) == 136, "store the new fm_trim_stats field");
_Static_assert(sizeof(struct fm_trim_loop) == 168, "store the new fm_trim_loop field");
_Static_assert(sizeof(trim_piece) == 160, "store the new trim_piece field");
#endif

static void store_frame(fm_store_out *o, const fm_fit_frame *f)
{
    fm_store_f64s(o, f->origin, 3);
    fm_store_f64s(o, f->u, 3);
    fm_store_f64s(o, f->v, 3);
    fm_store_f64s(o, f->w, 3);
    fm_store_f64(o, f->min_dot);
    fm_store_f64(o, f->optimum_dot);
    fm_store_f64(o, f->mean_dot);
    fm_store_f64(o, f->folded_area);
    fm_store_f64(o, f->area);
    fm_store_f64(o, f->dip_degrees);
    fm_store_i32(o, f->projectable);
    fm_store_i32(o, f->strike_axes);
}

static void load_frame(fm_store_in *in, fm_fit_frame *f)
{
    for (int k = 0; k < 3; k++)
        f->origin[k] = fm_load_f64(in);
    for (int k = 0; k < 3; k++)
        f->u[k] = fm_load_f64(in);
    for (int k = 0; k < 3; k++)
        f->v[k] = fm_load_f64(in);
    for (int k = 0; k < 3; k++)
        f->w[k] = fm_load_f64(in);
    f->min_dot = fm_load_f64(in);
    f->optimum_dot = fm_load_f64(in);
    f->mean_dot = fm_load_f64(in);
    f->folded_area = fm_load_f64(in);
    f->area = fm_load_f64(in);
    f->dip_degrees = fm_load_f64(in);
    f->projectable = fm_load_i32(in);
    f->strike_axes = fm_load_i32(in);
}

static void store_fit_stats(fm_store_out *o, const fm_fit_stats *s)
{
    fm_store_i32(o, (int32_t)s->kind);
    fm_store_i32(o, s->passes);
    fm_store_f64(o, s->overlap);
    fm_store_size(o, s->lscm_flipped);
    fm_store_i32(o, s->convex_map);
    fm_store_size(o, s->vertices);
    fm_store_size(o, s->triangles);
    fm_store_size(o, s->samples);
    fm_store_i32(o, s->degree);
    fm_store_size(o, s->spans_u);
    fm_store_size(o, s->spans_v);
    fm_store_size(o, s->control_u);
    fm_store_size(o, s->control_v);
    fm_store_f64(o, s->knot_spacing);
    fm_store_f64(o, s->edge_median);
    fm_store_f64(o, s->smoothing);
    fm_store_f64(o, s->rms_w);
    fm_store_f64(o, s->max_w);
    fm_store_f64(o, s->rms_dist);
    fm_store_f64(o, s->max_dist);
    fm_store_size(o, s->projection_failures);
    fm_store_f64(o, s->max_border_offset);
    fm_store_size(o, s->stacked);
    fm_store_f64(o, s->time_frame);
    fm_store_f64(o, s->time_param);
    fm_store_f64(o, s->time_assemble);
    fm_store_f64(o, s->time_solve);
    fm_store_f64(o, s->time_stats);
    fm_store_f64(o, s->time_total);
}

static fm_fit_kind load_kind(fm_store_in *in)
{
    int32_t k = fm_load_i32(in);
    if (k != FM_FIT_AUTO && k != FM_FIT_HEIGHT_FIELD && k != FM_FIT_PARAMETRIC)
        in->failed = 1;
    return (fm_fit_kind)k;
}

static void load_fit_stats(fm_store_in *in, fm_fit_stats *s)
{
    s->kind = load_kind(in);
    s->passes = fm_load_i32(in);
    s->overlap = fm_load_f64(in);
    s->lscm_flipped = fm_load_size(in);
    s->convex_map = fm_load_i32(in);
    s->vertices = fm_load_size(in);
    s->triangles = fm_load_size(in);
    s->samples = fm_load_size(in);
    s->degree = fm_load_i32(in);
    s->spans_u = fm_load_size(in);
    s->spans_v = fm_load_size(in);
    s->control_u = fm_load_size(in);
    s->control_v = fm_load_size(in);
    s->knot_spacing = fm_load_f64(in);
    s->edge_median = fm_load_f64(in);
    s->smoothing = fm_load_f64(in);
    s->rms_w = fm_load_f64(in);
    s->max_w = fm_load_f64(in);
    s->rms_dist = fm_load_f64(in);
    s->max_dist = fm_load_f64(in);
    s->projection_failures = fm_load_size(in);
    s->max_border_offset = fm_load_f64(in);
    s->stacked = fm_load_size(in);
    s->time_frame = fm_load_f64(in);
    s->time_param = fm_load_f64(in);
    s->time_assemble = fm_load_f64(in);
    s->time_solve = fm_load_f64(in);
    s->time_stats = fm_load_f64(in);
    s->time_total = fm_load_f64(in);
}

/* Array lengths that follow from the other fields; an array that is NULL
 * is stored as absent (a flag), so it reads back NULL. */
static size_t knot_count(const fm_fit_surface *s, size_t spans)
{
    return spans + 2 * (size_t)s->p + 1;
}

static void store_array(fm_store_out *o, const double *p, size_t n)
{
    fm_store_u32(o, p != NULL);
    if (p)
        fm_store_f64s(o, p, n);
}

static double *load_array(fm_store_in *in, size_t n)
{
    uint32_t present = fm_load_u32(in);
    if (present > 1 || (present && n == 0))
        in->failed = 1;
    if (!present || in->failed)
        return NULL;
    if (n > (in->n - in->at) / 8) {
        in->failed = 1;
        return NULL;
    }
    return fm_load_f64s(in, n);
}

void store_surface(fm_store_out *o, const fm_fit_surface *s)
{
    store_frame(o, &s->frame);
    store_fit_stats(o, &s->stats);
    fm_store_i32(o, (int32_t)s->kind);
    fm_store_i32(o, s->ncomp);
    fm_store_i32(o, s->p);
    fm_store_f64(o, s->s);
    fm_store_f64(o, s->u0);
    fm_store_f64(o, s->v0);
    fm_store_size(o, s->nsu);
    fm_store_size(o, s->nsv);
    fm_store_size(o, s->nu);
    fm_store_size(o, s->nv);
    store_array(o, s->coef, (size_t)s->ncomp * s->nu * s->nv);
    store_array(o, s->knots_u, knot_count(s, s->nsu));
    store_array(o, s->knots_v, knot_count(s, s->nsv));
    fm_store_size(o, s->nvparams);
    store_array(o, s->vparams, 2 * s->nvparams);
    store_array(o, s->starts, 3 * s->nsu * s->nsv);
}

/* Counts whose products must stay far from overflow (the fit refuses far
 * smaller grids); a damaged file fails on them before any allocation. */
#define STORE_MAX_COUNT ((size_t)1 << 40)

fm_fit_surface *load_surface(fm_store_in *in)
{
    fm_fit_surface *s = calloc(1, sizeof *s);
    if (!s) {
        in->failed = 1;
        return NULL;
    }
    load_frame(in, &s->frame);
    load_fit_stats(in, &s->stats);
    s->kind = load_kind(in);
    s->ncomp = fm_load_i32(in);
    s->p = fm_load_i32(in);
    s->s = fm_load_f64(in);
    s->u0 = fm_load_f64(in);
    s->v0 = fm_load_f64(in);
    s->nsu = fm_load_size(in);
    s->nsv = fm_load_size(in);
    s->nu = fm_load_size(in);
    s->nv = fm_load_size(in);
    if ((s->ncomp != 1 && s->ncomp != 3) || s->p < 1 || s->p > FM_FIT_MAX_DEGREE ||
        s->nsu > STORE_MAX_COUNT || s->nsv > STORE_MAX_COUNT ||
        s->nu != s->nsu + (size_t)s->p || s->nv != s->nsv + (size_t)s->p ||
        (s->nsu && s->nsv > STORE_MAX_COUNT / s->nsu))
        in->failed = 1;
    if (!in->failed) {
        s->coef = load_array(in, (size_t)s->ncomp * s->nu * s->nv);
        s->knots_u = load_array(in, knot_count(s, s->nsu));
        s->knots_v = load_array(in, knot_count(s, s->nsv));
        s->nvparams = fm_load_size(in);
        if (s->nvparams > STORE_MAX_COUNT)
            in->failed = 1;
        else
            s->vparams = load_array(in, 2 * s->nvparams);
        s->starts = load_array(in, 3 * s->nsu * s->nsv);
    }
    /* what every evaluation reads */
    if (!s->coef || !s->knots_u || !s->knots_v)
        in->failed = 1;
    if (in->failed) {
        fm_fit_surface_destroy(s);
        return NULL;
    }
    return s;
}

static void store_trim_stats(fm_store_out *o, const fm_trim_stats *s)
{
    fm_store_size(o, s->points);
    fm_store_size(o, s->distinct_points);
    fm_store_f64(o, s->spacing);
    fm_store_f64(o, s->corner_window);
    fm_store_f64(o, s->knot_spacing);
    fm_store_size(o, s->corners);
    fm_store_size(o, s->pieces);
    fm_store_size(o, s->spans);
    fm_store_size(o, s->control_points);
    fm_store_i32(o, s->refinements);
    fm_store_f64(o, s->max_dev);
    fm_store_f64(o, s->rms_dev);
    fm_store_f64(o, s->max_curve_dev);
    fm_store_f64(o, s->max_systematic);
    fm_store_i32(o, s->within_tolerance);
    fm_store_f64(o, s->area);
    fm_store_f64(o, s->polygon_area);
}

static void load_trim_stats(fm_store_in *in, fm_trim_stats *s)
{
    s->points = fm_load_size(in);
    s->distinct_points = fm_load_size(in);
    s->spacing = fm_load_f64(in);
    s->corner_window = fm_load_f64(in);
    s->knot_spacing = fm_load_f64(in);
    s->corners = fm_load_size(in);
    s->pieces = fm_load_size(in);
    s->spans = fm_load_size(in);
    s->control_points = fm_load_size(in);
    s->refinements = fm_load_i32(in);
    s->max_dev = fm_load_f64(in);
    s->rms_dev = fm_load_f64(in);
    s->max_curve_dev = fm_load_f64(in);
    s->max_systematic = fm_load_f64(in);
    s->within_tolerance = fm_load_i32(in);
    s->area = fm_load_f64(in);
    s->polygon_area = fm_load_f64(in);
}

static void store_piece(fm_store_out *o, const trim_piece *pc)
{
    fm_store_i32(o, pc->periodic);
    fm_store_size(o, pc->first);
    fm_store_size(o, pc->in_first);
    fm_store_size(o, pc->in_last);
    fm_store_size(o, pc->npts);
    store_array(o, pc->t, pc->npts);
    fm_store_f64(o, pc->len);
    fm_store_size(o, pc->nspans);
    store_array(o, pc->brk, pc->nspans + 1);
    fm_store_f64(o, pc->mu);
    fm_store_size(o, pc->nknots);
    fm_store_size(o, pc->nctrl);
    store_array(o, pc->knots, pc->nknots);
    store_array(o, pc->ctrl, 2 * pc->nctrl);
    fm_store_i32(o, pc->rounds);
    fm_store_f64(o, pc->max_dev);
    fm_store_f64(o, pc->sum_dev2);
    fm_store_f64(o, pc->max_curve_dev);
    fm_store_f64(o, pc->max_sys);
    fm_store_size(o, pc->worst_span);
}

static void load_piece(fm_store_in *in, trim_piece *pc)
{
    pc->periodic = fm_load_i32(in);
    pc->first = fm_load_size(in);
    pc->in_first = fm_load_size(in);
    pc->in_last = fm_load_size(in);
    pc->npts = fm_load_size(in);
    if (pc->npts > STORE_MAX_COUNT)
        in->failed = 1;
    pc->t = in->failed ? NULL : load_array(in, pc->npts);
    pc->len = fm_load_f64(in);
    pc->nspans = fm_load_size(in);
    if (pc->nspans > STORE_MAX_COUNT)
        in->failed = 1;
    pc->brk = in->failed ? NULL : load_array(in, pc->nspans + 1);
    pc->mu = fm_load_f64(in);
    pc->nknots = fm_load_size(in);
    pc->nctrl = fm_load_size(in);
    if (pc->nknots > STORE_MAX_COUNT || pc->nctrl > STORE_MAX_COUNT)
        in->failed = 1;
    pc->knots = in->failed ? NULL : load_array(in, pc->nknots);
    pc->ctrl = in->failed ? NULL : load_array(in, 2 * pc->nctrl);
    pc->rounds = fm_load_i32(in);
    pc->max_dev = fm_load_f64(in);
    pc->sum_dev2 = fm_load_f64(in);
    pc->max_curve_dev = fm_load_f64(in);
    pc->max_sys = fm_load_f64(in);
    pc->worst_span = fm_load_size(in);
    /* what evaluation reads: the knots and control points of a cubic */
    if (!pc->brk || !pc->knots || !pc->ctrl || pc->nspans == 0 ||
        pc->nctrl != pc->nspans + TRIM_P || pc->nknots != pc->nspans + 2 * TRIM_P + 1)
        in->failed = 1;
}

void store_loop(fm_store_out *o, const fm_trim_loop *l)
{
    store_trim_stats(o, &l->stats);
    fm_store_size(o, l->npieces);
    for (size_t i = 0; i < l->npieces; i++)
        store_piece(o, &l->pieces[i]);
    fm_store_size(o, l->ncorners);
    fm_store_sizes(o, l->corners, l->ncorners);
}

fm_trim_loop *load_loop(fm_store_in *in)
{
    fm_trim_loop *l = calloc(1, sizeof *l);
    if (!l) {
        in->failed = 1;
        return NULL;
    }
    load_trim_stats(in, &l->stats);
    /* a piece takes well over 100 bytes */
    size_t np = fm_load_count(in, 100);
    l->pieces = np ? calloc(np, sizeof *l->pieces) : NULL;
    if (np && !l->pieces)
        in->failed = 1;
    else
        l->npieces = np;
    for (size_t i = 0; i < l->npieces && !in->failed; i++)
        load_piece(in, &l->pieces[i]);
    l->ncorners = fm_load_count(in, 8);
    l->corners = fm_load_sizes(in, l->ncorners);
    if (!in->failed && l->npieces == 0)
        in->failed = 1;
    if (in->failed) {
        fm_trim_loop_destroy(l);
        return NULL;
    }
    return l;
}
