/* Arc length, enclosed area and sampling of the fitted curves. */
#include "trim_internal.h"

#include <math.h>
#include <stdlib.h>

static const double g5x[5] = {0.04691007703066800, 0.23076534494715845, 0.5,
                              0.76923465505284155, 0.95308992296933200};
static const double g5w[5] = {0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                              0.23931433524968324, 0.11846344252809454};

/* Within one span a piece is a cubic, so its derivative is a quadratic:
 * three evaluations give it exactly (up to rounding), and the many speed
 * evaluations of arc lengths and their inversion cost a few multiplies
 * each instead of a B-spline basis. */
typedef struct {
    double a, h;     /* the span [a, a + h] */
    double q[2][3];  /* derivative = q0 + q1 e + q2 e^2, e = (t - a) / h - 1/2 */
} span_speed;

static void span_speed_init(const trim_piece *pc, size_t k, span_speed *sp)
{
    sp->a = pc->brk[k];
    sp->h = pc->brk[k + 1] - pc->brk[k];
    double d[3][2];
    for (int i = 0; i < 3; i++) {
        double c[3][2];
        /* Interior points: the span's own polynomial, whatever the ends
         * wrap or clamp to. */
        trim_eval(pc, sp->a + 0.25 * (i + 1) * sp->h, 1, c);
        d[i][0] = c[1][0];
        d[i][1] = c[1][1];
    }
    for (int x = 0; x < 2; x++) {
        sp->q[x][0] = d[1][x];
        sp->q[x][1] = 2 * (d[2][x] - d[0][x]);
        sp->q[x][2] = 8 * (d[0][x] - 2 * d[1][x] + d[2][x]);
    }
}

static double speed(const span_speed *sp, double t)
{
    double e = (t - sp->a) / sp->h - 0.5;
    double x = sp->q[0][0] + e * (sp->q[0][1] + e * sp->q[0][2]);
    double y = sp->q[1][0] + e * (sp->q[1][1] + e * sp->q[1][2]);
    /* Parameter-plane derivatives: no overflow for hypot to guard. */
    return sqrt(x * x + y * y);
}

/* Within one span the speed is smooth, so five Gauss points are plenty. */
static double span_arc(const span_speed *sp, double a, double b)
{
    double s = 0;
    for (int g = 0; g < 5; g++)
        s += g5w[g] * speed(sp, a + g5x[g] * (b - a));
    return s * (b - a);
}

double fm_trim_loop_area(const fm_trim_loop *loop)
{
    /* The area of a closed curve does not depend on the origin; taking one
     * on the curve avoids cancellation in UTM coordinates. */
    const double *o = loop->pieces[0].ctrl;
    static const double gx[3] = {0.11270166537925831, 0.5, 0.88729833462074169};
    static const double gw[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
    double area = 0;
    for (size_t i = 0; i < loop->npieces; i++) {
        const trim_piece *pc = &loop->pieces[i];
        for (size_t k = 0; k < pc->nspans; k++) {
            double h = pc->brk[k + 1] - pc->brk[k], s = 0;
            /* x y' - y x' of a cubic is of degree 5: exact with 3 points. */
            for (int g = 0; g < 3; g++) {
                double c[3][2];
                trim_eval(pc, pc->brk[k] + gx[g] * h, 1, c);
                s += gw[g] * ((c[0][0] - o[0]) * c[1][1] - (c[0][1] - o[1]) * c[1][0]);
            }
            area += 0.5 * s * h;
        }
    }
    return area;
}

/* Parameter at arc length `target` from the start of span k, whose arc
 * length is `total`: Newton on the arc length kept inside a bracket. */
static double invert_in_span(const span_speed *sp, double target, double total)
{
    double a = sp->a, b = sp->a + sp->h;
    double lo = a, hi = b;
    double t = a + (b - a) * (total > 0 ? target / total : 0);
    for (int it = 0; it < 50; it++) {
        double f = span_arc(sp, a, t) - target;
        if (fabs(f) <= 1e-9 * (1 + total))
            break;
        if (f > 0)
            hi = t;
        else
            lo = t;
        double v = speed(sp, t);
        double tn = v > 0 ? t - f / v : 0.5 * (lo + hi);
        if (!(tn > lo && tn < hi))
            tn = 0.5 * (lo + hi);
        t = tn;
    }
    return t;
}

fm_status fm_trim_loop_sample(const fm_trim_loop *loop, double spacing, double **uv,
                              size_t *n, size_t **corner_at, fm_error *err)
{
    *uv = NULL;
    *n = 0;
    if (corner_at)
        *corner_at = NULL;
    if (!(spacing > 0) || !isfinite(spacing))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "trim: bad sample spacing %g", spacing);
    size_t np = loop->npieces, total = 0;
    size_t *count = malloc(np * sizeof *count);
    double **cum = calloc(np, sizeof *cum);
    fm_status st = FM_OK;
    if (!count || !cum) {
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "trim: out of memory (sampling)");
        goto done;
    }
    for (size_t i = 0; i < np; i++) {
        const trim_piece *pc = &loop->pieces[i];
        cum[i] = malloc((pc->nspans + 1) * sizeof *cum[i]);
        if (!cum[i]) {
            st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "trim: out of memory (sampling)");
            goto done;
        }
        cum[i][0] = 0;
        for (size_t k = 0; k < pc->nspans; k++) {
            span_speed sp;
            span_speed_init(pc, k, &sp);
            cum[i][k + 1] = cum[i][k] + span_arc(&sp, sp.a, sp.a + sp.h);
        }
        double parts = ceil(cum[i][pc->nspans] / spacing);
        if (!(parts < 1e8) || total > (size_t)1e8) {
            st = fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                              "trim: spacing %g gives too many samples", spacing);
            goto done;
        }
        count[i] = parts < 1 ? 1 : (size_t)parts;
        total += count[i];
    }
    *uv = malloc(2 * total * sizeof **uv);
    if (corner_at && loop->ncorners)
        *corner_at = malloc(loop->ncorners * sizeof **corner_at);
    if (!*uv || (corner_at && loop->ncorners && !*corner_at)) {
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "trim: out of memory (%zu samples)", total);
        goto done;
    }
    size_t at = 0;
    for (size_t i = 0; i < np; i++) {
        const trim_piece *pc = &loop->pieces[i];
        double length = cum[i][pc->nspans];
        if (corner_at && !pc->periodic)
            (*corner_at)[i] = at;
        size_t k = 0, have = (size_t)-1;
        span_speed sp;
        /* The piece's end is the next piece's start (or, periodic, its own). */
        for (size_t j = 0; j < count[i]; j++, at++) {
            double target = length * (double)j / (double)count[i], t = 0;
            if (j > 0) {
                while (k + 1 < pc->nspans && cum[i][k + 1] <= target)
                    k++;
                if (have != k) {
                    span_speed_init(pc, k, &sp);
                    have = k;
                }
                t = invert_in_span(&sp, target - cum[i][k], cum[i][k + 1] - cum[i][k]);
            }
            double c[3][2];
            trim_eval(pc, t, 0, c);
            (*uv)[2 * at] = c[0][0];
            (*uv)[2 * at + 1] = c[0][1];
        }
    }
    *n = total;
done:
    if (cum)
        for (size_t i = 0; i < np; i++)
            free(cum[i]);
    free(cum);
    free(count);
    if (st != FM_OK) {
        free(*uv);
        *uv = NULL;
        if (corner_at) {
            free(*corner_at);
            *corner_at = NULL;
        }
    }
    return st;
}
