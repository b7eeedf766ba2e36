/* Boundary segments whose chord strays far from their trimming curve.
 *
 * Equal steps along a piece put nodes a size apart wherever they fall. A
 * bend the fit did not make a corner (a small fault's outline is rounded
 * over a few stair-steps, or its corner sits a vertex off the apex) can
 * then lie between two nodes, and the chord cuts it off: on
 * Yuha_Well_fault_north_set1 at 1 km one chord cut 0.16 km2, 12 % of the
 * fault. Refinement cannot repair this: it sees only the chord. Such a
 * segment is split at the curve point farthest from its chord. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_predicates.h"
#include "remesh_internal.h"

/* Farthest a chord may stray, as a fraction of the size: a circle of
 * radius 1.25 sizes, so smooth outlines at the target size keep their
 * nodes, while a bend of more than about 45 degrees inside one segment
 * does not. */
#define SAG_FRACTION 0.1
/* Smallest inner angle (degrees, 3D) at a new node. */
#define MIN_TIP 60.0
/* Curve samples per segment when looking for the farthest point. */
#define SAG_SAMPLES 32

static double point_segment_dist(const double p[3], const double a[3], const double b[3])
{
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double w[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double f = dd > 0 ? (w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / dd : 0;
    f = f < 0 ? 0 : f > 1 ? 1 : f;
    double r[3] = {w[0] - f * d[0], w[1] - f * d[1], w[2] - f * d[2]};
    return sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
}

static void eval3(const fm_fit_surface *s, const double uv[2], double p[3])
{
    fm_fit_surface_eval(s, uv[0], uv[1], p, NULL, NULL);
}

/* The parameter of the farthest point of segment i from its chord, or a
 * negative value when the chord stays close enough, when the curve bends
 * away from the domain there (a chord across a notch loses nothing, and
 * nodes in the notches of tangled outlines only made slivers), or when the
 * point is so near an end that splitting there would leave a sliver of a
 * segment. */
static double sag_split_t(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                          const dom_loop *l, size_t i, double h)
{
    const dom_seg *sg = &l->seg[i];
    if (sg->kind != SEG_TRIM)
        return -1;
    /* the domain lies left of the outer loop and right of a hole taken
     * in its own orientation */
    int side = (fm_trim_loop_area(loops[sg->loop]) > 0) == (sg->loop == 0) ? 1 : -1;
    double a[3], b[3];
    eval3(s, l->uv + 2 * i, a);
    eval3(s, l->uv + 2 * ((i + 1) % l->n), b);
    double best = 0, tbest = -1;
    for (int k = 1; k < SAG_SAMPLES; k++) {
        double t = sg->ta + (sg->tb - sg->ta) * (double)k / SAG_SAMPLES, uv[2], p[3];
        fm_trim_loop_eval(loops[sg->loop], sg->piece, t, uv, NULL);
        eval3(s, uv, p);
        double d = point_segment_dist(p, a, b);
        if (d > best) {
            best = d;
            tbest = t;
        }
    }
    if (!(best > SAG_FRACTION * h))
        return -1;
    double uvb[2];
    fm_trim_loop_eval(loops[sg->loop], sg->piece, tbest, uvb, NULL);
    if (fm_orient2d(l->uv + 2 * i, uvb, l->uv + 2 * ((i + 1) % l->n)) * side <= 0)
        return -1;
    /* both parts at least a quarter size along the curve */
    double q = 0.25 * h;
    if (tbest - sg->ta < q || sg->tb - tbest < q)
        return -1;
    /* a node at the tip of a spike (an outline turning back within a
     * segment, as the fit makes of tangled junction outlines) would only
     * seed slivers: the inner angle it makes must leave room for a
     * triangle of MIN_TIP degrees */
    double p[3];
    eval3(s, uvb, p);
    double u[3] = {a[0] - p[0], a[1] - p[1], a[2] - p[2]}, v[3] = {b[0] - p[0], b[1] - p[1], b[2] - p[2]};
    double x[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double ang = atan2(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
    if (ang < MIN_TIP * (3.14159265358979323846 / 180.0))
        return -1;
    return tbest;
}

static int loop_insert(dom_loop *l, size_t at, const double uv[2], const dom_seg *sg)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 16;
        double *nuv = realloc(l->uv, 2 * cap * sizeof *nuv);
        if (nuv)
            l->uv = nuv;
        int *nlev = realloc(l->level, cap * sizeof *nlev);
        if (nlev)
            l->level = nlev;
        dom_seg *ns = realloc(l->seg, cap * sizeof *ns);
        if (ns)
            l->seg = ns;
        if (!nuv || !nlev || !ns)
            return -1;
        l->cap = cap;
    }
    memmove(l->uv + 2 * (at + 1), l->uv + 2 * at, 2 * (l->n - at) * sizeof *l->uv);
    memmove(l->level + at + 1, l->level + at, (l->n - at) * sizeof *l->level);
    memmove(l->seg + at + 1, l->seg + at, (l->n - at) * sizeof *l->seg);
    l->uv[2 * at] = uv[0];
    l->uv[2 * at + 1] = uv[1];
    l->level[at] = 0;
    l->seg[at] = *sg;
    l->n++;
    return 0;
}

int domain_split_sags(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                      remesh_domain *d, double h)
{
    for (size_t k = 0; k < d->n; k++) {
        dom_loop *l = &d->loops[k];
        /* a split segment is looked at again: both halves may still stray */
        for (size_t i = 0; i < l->n;) {
            double t = sag_split_t(s, loops, l, i, h);
            if (t < 0) {
                i++;
                continue;
            }
            dom_seg tail = l->seg[i];
            tail.ta = t;
            l->seg[i].tb = t;
            double uv[2];
            fm_trim_loop_eval(loops[tail.loop], tail.piece, t, uv, NULL);
            if (loop_insert(l, i + 1, uv, &tail))
                return -1;
        }
    }
    return 0;
}
