/* Checks on the faces before anything is written, and the sense of each
 * trimming loop. */
#include "iges_internal.h"

#include <math.h>
#include <string.h>

/* Samples per knot span for the loop area and the range check: enough to
 * get the sign of any loop whose area is not tiny against its curvature. */
#define SAMPLES_PER_SPAN 8
/* Gaps between curves and distances outside the range, relative to the
 * diagonal of the (u, v) range. */
#define REL_TOL 1e-7
#define MAX_DEGREE 25

void iges_face_range(const fm_iges_surface *s, double r[4])
{
    r[0] = s->u0;
    r[1] = s->u1;
    r[2] = s->v0;
    r[3] = s->v1;
    if (s->u0 == s->u1) {
        r[0] = s->knots_u[s->degree_u];
        r[1] = s->knots_u[s->nu];
    }
    if (s->v0 == s->v1) {
        r[2] = s->knots_v[s->degree_v];
        r[3] = s->knots_v[s->nv];
    }
}

void iges_curve_eval(const fm_iges_curve2d *c, double t, double uv[2])
{
    int p = c->degree;
    size_t n = c->n;
    const double *k = c->knots;
    if (t < k[p])
        t = k[p];
    if (t > k[n])
        t = k[n];
    /* Span s with k[s] <= t < k[s + 1]; the last non-empty one at the end. */
    size_t s = (size_t)p;
    while (s + 1 < n && k[s + 1] <= t)
        s++;
    double d[MAX_DEGREE + 1][3];
    for (int j = 0; j <= p; j++) {
        size_t i = s - (size_t)p + (size_t)j;
        double w = c->weights ? c->weights[i] : 1.0;
        d[j][0] = c->ctrl[2 * i] * w;
        d[j][1] = c->ctrl[2 * i + 1] * w;
        d[j][2] = w;
    }
    /* de Boor in homogeneous coordinates. */
    for (int r = 1; r <= p; r++) {
        for (int j = p; j >= r; j--) {
            size_t i = s - (size_t)p + (size_t)j;
            double den = k[i + (size_t)p + 1 - (size_t)r] - k[i];
            double a = den > 0 ? (t - k[i]) / den : 0.0;
            for (int m = 0; m < 3; m++)
                d[j][m] = (1 - a) * d[j - 1][m] + a * d[j][m];
        }
    }
    uv[0] = d[p][0] / d[p][2];
    uv[1] = d[p][1] / d[p][2];
}

static int all_finite(const double *x, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}

/* NULL when the knot vector is acceptable, else what is wrong. */
static const char *check_knots(const double *k, size_t n, int p)
{
    size_t m = n + (size_t)p + 1;
    if (!all_finite(k, m))
        return "a knot is not finite";
    for (size_t i = 1; i < m; i++)
        if (k[i] < k[i - 1])
            return "knots decrease";
    if (!(k[p] < k[n]))
        return "the knot range is empty";
    /* Interior knots of multiplicity p + 1 would split the spline into
     * pieces; OpenCASCADE refuses them. */
    for (size_t i = (size_t)p + 1; i < n; i++) {
        size_t mult = 1;
        while (i + mult < m && k[i + mult] == k[i])
            mult++;
        if (i + mult <= n && mult > (size_t)p)
            return "an interior knot has multiplicity above the degree";
        i += mult - 1;
    }
    return NULL;
}

static const char *check_weights(const double *w, size_t n)
{
    if (!w)
        return NULL;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(w[i]) || !(w[i] > 0))
            return "a weight is not positive and finite";
    return NULL;
}

static const char *check_curve(const fm_iges_curve2d *c)
{
    if (c->degree < 1 || c->degree > MAX_DEGREE)
        return "curve degree outside 1..25";
    if (c->n <= (size_t)c->degree)
        return "curve has no more control points than its degree";
    if (!c->knots || !c->ctrl)
        return "curve knots or control points missing";
    const char *why = check_knots(c->knots, c->n, c->degree);
    if (why)
        return why;
    if (!all_finite(c->ctrl, 2 * c->n))
        return "a curve control point is not finite";
    return check_weights(c->weights, c->n);
}

/* Signed area of the loop (as given), or NAN with *why set. */
static double loop_area(const fm_iges_loop *lp, const double r[4], const char **why)
{
    double diag = hypot(r[1] - r[0], r[3] - r[2]), tol = REL_TOL * diag;
    double area = 0, first[2] = {0, 0}, prev[2] = {0, 0}, end[2] = {0, 0};
    int have = 0;
    if (!lp->curves || lp->ncurves == 0) {
        *why = "loop without curves";
        return NAN;
    }
    for (size_t c = 0; c < lp->ncurves; c++) {
        const fm_iges_curve2d *cv = &lp->curves[c];
        if ((*why = check_curve(cv)) != NULL)
            return NAN;
        double start[2];
        iges_curve_eval(cv, cv->knots[cv->degree], start);
        if (c > 0 && hypot(start[0] - end[0], start[1] - end[1]) > tol) {
            *why = "a curve does not start where the previous one ends";
            return NAN;
        }
        for (size_t s = (size_t)cv->degree; s < cv->n; s++) {
            double a = cv->knots[s], b = cv->knots[s + 1];
            if (!(b > a))
                continue;
            for (int q = 0; q < SAMPLES_PER_SPAN; q++) {
                double p[2];
                iges_curve_eval(cv, a + (b - a) * q / SAMPLES_PER_SPAN, p);
                if (p[0] < r[0] - tol || p[0] > r[1] + tol || p[1] < r[2] - tol ||
                    p[1] > r[3] + tol) {
                    *why = "a trimming curve leaves the surface's parameter range";
                    return NAN;
                }
                if (have)
                    area += prev[0] * p[1] - p[0] * prev[1];
                else
                    memcpy(first, p, sizeof first);
                memcpy(prev, p, sizeof prev);
                have = 1;
            }
        }
        iges_curve_eval(cv, cv->knots[cv->n], end);
    }
    if (hypot(end[0] - first[0], end[1] - first[1]) > tol) {
        *why = "the loop is not closed";
        return NAN;
    }
    area += prev[0] * first[1] - first[0] * prev[1];
    area *= 0.5;
    if (!(fabs(area) > 1e-12 * (r[1] - r[0]) * (r[3] - r[2]))) {
        *why = "the loop encloses no area";
        return NAN;
    }
    return area;
}

static const char *check_surface(const fm_iges_surface *s)
{
    if (s->degree_u < 1 || s->degree_u > MAX_DEGREE || s->degree_v < 1 ||
        s->degree_v > MAX_DEGREE)
        return "surface degree outside 1..25";
    if (s->nu <= (size_t)s->degree_u || s->nv <= (size_t)s->degree_v)
        return "surface has no more control points than its degree";
    if (!s->knots_u || !s->knots_v || !s->ctrl)
        return "surface knots or control points missing";
    const char *why = check_knots(s->knots_u, s->nu, s->degree_u);
    if (!why)
        why = check_knots(s->knots_v, s->nv, s->degree_v);
    if (why)
        return why;
    if (s->nu > ((size_t)-1) / 3 / s->nv)
        return "too many control points";
    if (!all_finite(s->ctrl, 3 * s->nu * s->nv))
        return "a surface control point is not finite";
    if ((why = check_weights(s->weights, s->nu * s->nv)) != NULL)
        return why;
    double r[4];
    iges_face_range(s, r);
    if (!all_finite(r, 4) || !(r[0] < r[1]) || !(r[2] < r[3]))
        return "the parameter range is empty or not finite";
    if (r[0] < s->knots_u[s->degree_u] || r[1] > s->knots_u[s->nu] ||
        r[2] < s->knots_v[s->degree_v] || r[3] > s->knots_v[s->nv])
        return "the parameter range exceeds the knot range";
    return NULL;
}

fm_status iges_check_face(const char *path, size_t index, const fm_iges_face *f,
                          unsigned char *rev, fm_error *err)
{
    const char *name = f->name && *f->name ? f->name : "(unnamed)";
    if (!iges_printable(f->name))
        return fm_error_set(err, FM_ERR_INVALID, path, 0,
                            "face %zu: the name has characters other than printable ASCII",
                            index);
    const char *why = check_surface(&f->surface);
    if (why)
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "face %zu (%s): %s", index, name, why);
    if (f->nholes && !f->holes)
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "face %zu (%s): holes missing", index,
                            name);
    double r[4];
    iges_face_range(&f->surface, r);
    size_t nloops = (f->outer ? 1 : 0) + f->nholes;
    for (size_t k = 0; k < nloops; k++) {
        const fm_iges_loop *lp = f->outer ? (k == 0 ? f->outer : &f->holes[k - 1]) : &f->holes[k];
        int is_outer = f->outer && k == 0;
        double a = loop_area(lp, r, &why);
        if (isnan(a))
            return fm_error_set(err, FM_ERR_INVALID, path, 0, "face %zu (%s), %s %zu: %s", index,
                                name, is_outer ? "outer loop" : "hole",
                                is_outer ? (size_t)0 : k - (f->outer ? 1 : 0), why);
        rev[f->outer ? k : k + 1] = is_outer ? a < 0 : a > 0;
    }
    return FM_OK;
}
