/* fm_trim_fit: corners, pieces, fit-measure-refine per piece, and the
 * accessors of the result. */
#include "trim_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A window this many times the loop's mean width is cut to it. */
#define THIN_LOOP 8.0

void fm_trim_options_default(fm_trim_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->tolerance = 50;
    opt->corner_angle = 30;
    opt->corner_window = 0;
    opt->knot_spacing = 0;
    opt->knot_factor = 3.0;
    opt->smoothing_wavelength = 2.0;
    opt->max_refinements = 8;
}

static void piece_free(trim_piece *pc)
{
    free(pc->t);
    free(pc->brk);
    free(pc->knots);
    free(pc->ctrl);
}

void fm_trim_loop_destroy(fm_trim_loop *loop)
{
    if (!loop)
        return;
    if (loop->pieces)
        for (size_t i = 0; i < loop->npieces; i++)
            piece_free(&loop->pieces[i]);
    free(loop->pieces);
    free(loop->corners);
    free(loop);
}

static fm_status check_options(const fm_trim_options *o, const char *name, fm_error *err)
{
    if (!(o->tolerance > 0) || !isfinite(o->tolerance))
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "trim: bad tolerance %g", o->tolerance);
    if (!(o->corner_angle > 0 && o->corner_angle <= 180))
        return fm_error_set(err, FM_ERR_INVALID, name, 0,
                            "trim: corner angle must be in (0, 180] degrees, not %g",
                            o->corner_angle);
    if (!(o->corner_window >= 0) || !isfinite(o->corner_window))
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "trim: bad corner window %g",
                            o->corner_window);
    if (!(o->knot_spacing >= 0) || !isfinite(o->knot_spacing))
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "trim: bad knot spacing %g",
                            o->knot_spacing);
    if (!(o->knot_factor > 0) || !isfinite(o->knot_factor))
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "trim: bad knot factor %g",
                            o->knot_factor);
    if (!(o->smoothing_wavelength >= 0) || !isfinite(o->smoothing_wavelength))
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "trim: bad smoothing wavelength %g",
                            o->smoothing_wavelength);
    if (!(o->max_deviation >= 0) || !isfinite(o->max_deviation))
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "trim: bad max deviation %g",
                            o->max_deviation);
    if (o->max_refinements < 0 || o->max_refinements > 30)
        return fm_error_set(err, FM_ERR_INVALID, name, 0,
                            "trim: max_refinements must be 0..30, not %d", o->max_refinements);
    return FM_OK;
}

/* Data points and parameters of the piece from cleaned point `first` over
 * `npts` points, with nspans uniform spans of about h0. */
static fm_status piece_init(const trim_input *in, trim_piece *pc, int periodic, size_t first,
                            size_t npts, double h0)
{
    enum { p = TRIM_P };
    pc->periodic = periodic;
    pc->first = first;
    pc->npts = npts;
    pc->t = malloc(npts * sizeof *pc->t);
    if (!pc->t)
        return FM_ERR_NOMEM;
    pc->t[0] = 0;
    for (size_t j = 1; j < npts; j++) {
        size_t a = (first + j - 1) % in->n;
        pc->t[j] = pc->t[j - 1] + (in->s[a + 1] - in->s[a]);
    }
    pc->len = periodic ? in->s[in->n] : pc->t[npts - 1];
    double spans = round(pc->len / h0);
    size_t N = spans < 1 ? 1 : spans > 1e7 ? 10000000 : (size_t)spans;
    /* Fewer periodic spans would let a basis function meet itself round
     * the loop. */
    if (periodic && N < 2 * p + 2)
        N = 2 * p + 2;
    pc->nspans = N;
    pc->brk = malloc((N + 1) * sizeof *pc->brk);
    if (!pc->brk)
        return FM_ERR_NOMEM;
    for (size_t s = 0; s <= N; s++)
        pc->brk[s] = pc->len * (double)s / (double)N;
    pc->brk[N] = pc->len;
    pc->mu = 1;
    return FM_OK;
}

/* Halves flagged spans of two point spacings or more (shorter spans would
 * let the curve follow single stair-steps). A span flagged only because
 * single points lie further than max_deviation (a bend or a spike sharper
 * than the knots, next to a corner) may go down to half a point spacing: the
 * knots come in there alone, where the systematic measure sees nothing to
 * follow, and the rest of the piece keeps its smoothing. When a flagged
 * span is already that short, the piece's smoothing goes down to a quarter
 * instead: for the whole piece, as smoothing that varies from span to span
 * shrinks curves unevenly and puts point-to-point wiggles into the fit.
 * Returns -1 when out of memory, else whether anything changed. */
/* One step down: below it the curve starts to pass stair-steps through. */
#define TRIM_MU_MIN 0.25
/* Shortest span that a flag may still halve. */
static double min_span(unsigned char flag, double spacing)
{
    return flag & TRIM_FLAG_SYSTEMATIC ? 2 * spacing : 0.5 * spacing;
}

static int refine(trim_piece *pc, const unsigned char *flag, double spacing, int *short_split)
{
    size_t N = pc->nspans, M = N;
    int stuck = 0;
    *short_split = 0;
    for (size_t s = 0; s < N; s++) {
        if (!flag[s])
            continue;
        double h = pc->brk[s + 1] - pc->brk[s];
        if (h >= min_span(flag[s], spacing)) {
            M++;
            *short_split |= h < 2 * spacing;
        } else {
            stuck = 1;
        }
    }
    int changed = 0;
    if (stuck && pc->mu > TRIM_MU_MIN) {
        pc->mu *= 0.25;
        changed = 1;
    }
    if (M == N)
        return changed;
    double *brk = malloc((M + 1) * sizeof *brk);
    if (!brk)
        return -1;
    size_t k = 0;
    for (size_t s = 0; s < N; s++) {
        double a = pc->brk[s], b = pc->brk[s + 1];
        brk[k++] = a;
        if (flag[s] && b - a >= min_span(flag[s], spacing))
            brk[k++] = 0.5 * (a + b);
    }
    brk[M] = pc->len;
    free(pc->brk);
    pc->brk = brk;
    pc->nspans = M;
    return 1;
}

/* How good a fitted state of a piece is, smaller better: first whether
 * the systematic deviation is within tolerance, then the largest deviation
 * both ways (points to curve, curve to polyline). */
static double piece_score(const trim_piece *pc, const fm_trim_options *o)
{
    double worst = fmax(pc->max_dev, pc->max_curve_dev);
    /* deviations are metres, far below 1e9 */
    return pc->max_sys <= o->tolerance ? worst : 1e9 + worst;
}

/* Spans below two point spacings (only for points further than
 * max_deviation) can let the curve swing out between the points it now
 * follows: such a round is kept only if the piece's largest deviation both
 * ways (points to curve, curve to polyline) does not grow; otherwise the
 * piece goes back to the knots and smoothing before it and stops there.
 * Rounds that split longer spans can make the curve swing out elsewhere
 * too; the piece ends in the best state it went through (piece_score). */
static fm_status fit_piece(const trim_input *in, trim_piece *pc, double beta, double raw_share,
                           int curve, const fm_trim_options *o, fm_error *err)
{
    unsigned char *flag = NULL;
    double *saved = NULL, saved_mu = 0, prev_worst = 0;
    size_t saved_n = 0;
    int guard = 0, restored = 0, narrow = 0;
    double *best = NULL, best_mu = 0, best_score = INFINITY;
    size_t best_n = 0;
    int best_rounds = 0;
    fm_status st = FM_OK;
    for (int round = 0;; round++) {
        st = trim_fit_piece(in, pc, beta, o->name, err);
        if (st != FM_OK)
            break;
        unsigned char *f = realloc(flag, pc->nspans);
        if (!f || trim_measure_piece(in, pc, 2 * in->spacing, o->tolerance, o->max_deviation,
                                     raw_share, curve, f) != FM_OK) {
            free(f ? f : flag);
            free(saved);
            free(best);
            return fm_error_set(err, FM_ERR_NOMEM, o->name, 0, "trim: out of memory (measure)");
        }
        flag = f;
        double score = piece_score(pc, o);
        if (score < best_score) {
            double *b = realloc(best, (pc->nspans + 1) * sizeof *b);
            if (!b) {
                st = fm_error_set(err, FM_ERR_NOMEM, o->name, 0, "trim: out of memory (refine)");
                break;
            }
            best = b;
            memcpy(best, pc->brk, (pc->nspans + 1) * sizeof *best);
            best_n = pc->nspans;
            best_mu = pc->mu;
            best_score = score;
            best_rounds = pc->rounds;
        }
        if (restored)
            break;
        double worst = fmax(pc->max_dev, pc->max_curve_dev);
        if (guard && worst > prev_worst) {
            free(pc->brk);
            pc->brk = saved;
            pc->nspans = saved_n;
            pc->mu = saved_mu;
            saved = NULL;
            /* The round that split every flagged span made the curve swing
             * out somewhere; the farthest point alone may still be
             * followed (a spike among points just over max_deviation):
             * from the knots before, one span at a time, and stop at the
             * next swing. */
            restored = narrow;
            narrow = 1;
            guard = 0;
            pc->rounds = round - 1;
            continue;
        }
        free(saved);
        saved = NULL;
        guard = 0;
        int raw_ok = !(o->max_deviation > 0) ||
                     (pc->max_dev <= o->max_deviation &&
                      (!curve || pc->max_curve_dev <= o->max_deviation));
        if ((pc->max_sys <= o->tolerance && raw_ok) || round >= o->max_refinements)
            break;
        saved = malloc((pc->nspans + 1) * sizeof *saved);
        if (!saved) {
            st = fm_error_set(err, FM_ERR_NOMEM, o->name, 0, "trim: out of memory (refine)");
            break;
        }
        memcpy(saved, pc->brk, (pc->nspans + 1) * sizeof *saved);
        saved_n = pc->nspans;
        saved_mu = pc->mu;
        if (narrow)
            for (size_t sp = 0; sp < pc->nspans; sp++)
                if (sp != pc->worst_span)
                    flag[sp] = 0;
        int short_split = 0;
        int changed = refine(pc, flag, in->spacing, &short_split);
        if (changed < 0) {
            st = fm_error_set(err, FM_ERR_NOMEM, o->name, 0, "trim: out of memory (refine)");
            break;
        }
        if (!changed)
            break;
        guard = short_split;
        prev_worst = worst;
        pc->rounds = round + 1;
    }
    if (st == FM_OK && best && best_score < piece_score(pc, o)) {
        free(pc->brk);
        pc->brk = best;
        pc->nspans = best_n;
        pc->mu = best_mu;
        pc->rounds = best_rounds;
        best = NULL;
        st = trim_fit_piece(in, pc, beta, o->name, err);
        unsigned char *f = st == FM_OK ? realloc(flag, pc->nspans) : NULL;
        if (f)
            flag = f;
        if (st == FM_OK && (!f || trim_measure_piece(in, pc, 2 * in->spacing, o->tolerance,
                                                     o->max_deviation, raw_share, curve, f) != FM_OK))
            st = fm_error_set(err, FM_ERR_NOMEM, o->name, 0, "trim: out of memory (measure)");
    }
    free(best);
    free(saved);
    free(flag);
    return st;
}

static double polygon_area(const trim_input *in)
{
    const double *o = in->xy;
    double a = 0;
    for (size_t i = 0; i < in->n; i++) {
        const double *p = in->xy + 2 * i, *q = in->xy + 2 * ((i + 1) % in->n);
        a += (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0]);
    }
    return 0.5 * a;
}

fm_status fm_trim_fit(const double *uv, size_t n, const fm_trim_options *opt,
                      fm_trim_loop **out, fm_error *err)
{
    return fm_trim_fit_metric(uv, NULL, n, opt, out, err);
}

fm_status fm_trim_fit_metric(const double *uv, const double *metric, size_t n,
                             const fm_trim_options *opt, fm_trim_loop **out, fm_error *err)
{
    fm_trim_options o;
    if (opt)
        o = *opt;
    else
        fm_trim_options_default(&o);
    if (!out)
        return fm_error_set(err, FM_ERR_INVALID, o.name, 0, "trim: no output");
    *out = NULL;
    fm_status st = check_options(&o, o.name, err);
    if (st != FM_OK)
        return st;
    trim_input in;
    st = trim_input_make(uv, metric, n, &in, o.name, err);
    if (st != FM_OK)
        return st;

    double L = in.s[in.n];
    double window = o.corner_window > 0 ? o.corner_window : 2 * in.spacing;
    /* Both sides of a vertex must fit in the loop with room to spare, and
     * across it: a window many times the loop's mean width (2 area /
     * perimeter) takes the two ends of a long thin loop (a fault far longer
     * than wide, drawn with few points: 10,000 km by 14 km in 2 triangles)
     * each for one corner, so it is cut to that width. A loop merely
     * narrower than the window (a small sheet of a dozen points) keeps it:
     * there a smaller window finds stair-steps as corners. */
    window = fmin(window, 0.25 * L);
    double width = 2 * trim_input_area(&in) / L;
    if (window > THIN_LOOP * width)
        window = width;
    double h0 = o.knot_spacing > 0 ? o.knot_spacing : o.knot_factor * in.spacing;
    double beta = fmax(o.smoothing_wavelength, 0.05);

    size_t *corners = NULL, nc = 0;
    fm_trim_loop *loop = calloc(1, sizeof *loop);
    if (!loop || trim_find_corners(&in, window, o.corner_angle * 3.14159265358979323846 / 180,
                                   o.corner_at, &corners, &nc) != FM_OK) {
        st = fm_error_set(err, FM_ERR_NOMEM, o.name, 0, "trim: out of memory (corners)");
        goto fail;
    }
    loop->npieces = nc ? nc : 1;
    loop->pieces = calloc(loop->npieces, sizeof *loop->pieces);
    loop->corners = malloc((nc ? nc : 1) * sizeof *loop->corners);
    if (!loop->pieces || !loop->corners) {
        st = fm_error_set(err, FM_ERR_NOMEM, o.name, 0, "trim: out of memory (pieces)");
        goto fail;
    }
    loop->ncorners = nc;
    for (size_t i = 0; i < nc; i++)
        loop->corners[i] = in.orig[corners[i]];

    fm_trim_stats *S = &loop->stats;
    S->points = n;
    S->distinct_points = in.n;
    S->spacing = in.spacing;
    S->corner_window = window;
    S->knot_spacing = h0;
    S->corners = nc;
    S->pieces = loop->npieces;
    double sum2 = 0;
    for (size_t i = 0; i < loop->npieces; i++) {
        trim_piece *pc = &loop->pieces[i];
        size_t first = nc ? corners[i] : 0, npts = in.n;
        if (nc == 1)
            npts = in.n + 1; /* round the loop, back to the one corner */
        else if (nc > 1)
            npts = (corners[(i + 1) % nc] + in.n - first) % in.n + 1;
        if (piece_init(&in, pc, nc == 0, first, npts, h0) != FM_OK) {
            st = fm_error_set(err, FM_ERR_NOMEM, o.name, 0, "trim: out of memory (piece)");
            goto fail;
        }
        st = fit_piece(&in, pc, beta, 0.0, 0, &o, err);
        if (st != FM_OK)
            goto fail;
        /* Still beyond max_deviation either way: refining the spans of
         * every point over it at once also moves knots next to the
         * farthest one, and when the curve then swings out the round is
         * undone with all its spans (a 160 m spike among 50 m points
         * stayed 120 m off); refining the farthest points first (those
         * within 2/3 of the largest deviation) can follow it, but leaves a
         * jog whose two ends need knots together (a 230 m step, 123 m
         * off). A curve within it at the points can swing out between them
         * (past a corner of Rose Canyon, 120 m); flagging such spans too
         * brings knots in there, but changes which spans the rounds split
         * elsewhere. So up to four fits, and the best kept (piece_score:
         * the systematic tolerance, then the largest deviation both ways);
         * on the CFM 500 m set at 15 / 25 m, 118 of 527 loops stay over
         * 25 m either way (146 with the first two only). */
        static const struct {
            double share;
            int curve;
        } alts[3] = {{2.0 / 3.0, 0}, {0.0, 1}, {2.0 / 3.0, 1}};
        for (int a = 0; a < 3 && o.max_deviation > 0 &&
                        fmax(pc->max_dev, pc->max_curve_dev) > o.max_deviation;
             a++) {
            trim_piece alt;
            memset(&alt, 0, sizeof alt);
            if (piece_init(&in, &alt, nc == 0, first, npts, h0) != FM_OK) {
                piece_free(&alt);
                st = fm_error_set(err, FM_ERR_NOMEM, o.name, 0, "trim: out of memory (piece)");
                goto fail;
            }
            st = fit_piece(&in, &alt, beta, alts[a].share, alts[a].curve, &o, err);
            if (st != FM_OK) {
                piece_free(&alt);
                goto fail;
            }
            if (piece_score(&alt, &o) < piece_score(pc, &o)) {
                piece_free(pc);
                *pc = alt;
            } else {
                piece_free(&alt);
            }
        }
        S->spans += pc->nspans;
        S->control_points += pc->nctrl;
        S->refinements = pc->rounds > S->refinements ? pc->rounds : S->refinements;
        S->max_dev = fmax(S->max_dev, pc->max_dev);
        S->max_curve_dev = fmax(S->max_curve_dev, pc->max_curve_dev);
        S->max_systematic = fmax(S->max_systematic, pc->max_sys);
        sum2 += pc->sum_dev2;
        pc->in_first = in.orig[first];
        pc->in_last = in.orig[(first + npts - 1) % in.n];
    }
    S->rms_dev = sqrt(sum2 / (double)in.n);
    S->within_tolerance = S->max_systematic <= o.tolerance;
    S->area = fm_trim_loop_area(loop);
    S->polygon_area = polygon_area(&in);
    free(corners);
    trim_input_free(&in);
    *out = loop;
    return FM_OK;
fail:
    free(corners);
    trim_input_free(&in);
    fm_trim_loop_destroy(loop);
    return st;
}

const fm_trim_stats *fm_trim_loop_stats(const fm_trim_loop *loop)
{
    return &loop->stats;
}

const size_t *fm_trim_loop_corners(const fm_trim_loop *loop, size_t *n)
{
    *n = loop->ncorners;
    return loop->corners;
}

size_t fm_trim_loop_npieces(const fm_trim_loop *loop)
{
    return loop->npieces;
}

void fm_trim_loop_piece(const fm_trim_loop *loop, size_t i, fm_trim_piece *out)
{
    const trim_piece *pc = &loop->pieces[i];
    out->degree = TRIM_P;
    out->periodic = pc->periodic;
    out->nknots = pc->nknots;
    out->knots = pc->knots;
    out->ncontrol = pc->nctrl;
    out->control = pc->ctrl;
    out->t0 = 0;
    out->t1 = pc->len;
    out->first = pc->in_first;
    out->last = pc->in_last;
}

void fm_trim_loop_eval(const fm_trim_loop *loop, size_t piece, double t, double p[2],
                       double d[2])
{
    double c[3][2];
    trim_eval(&loop->pieces[piece], t, d ? 1 : 0, c);
    p[0] = c[0][0];
    p[1] = c[0][1];
    if (d) {
        d[0] = c[1][0];
        d[1] = c[1][1];
    }
}
