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
                          const dom_loop *l, size_t i, double h, long *area_loop, double *area)
{
    const dom_seg *sg = &l->seg[i];
    if (sg->kind != SEG_TRIM)
        return -1;
    /* the domain lies left of the outer loop and right of a hole taken
     * in its own orientation (the area of the loop of the last segment
     * kept: a loop's segments come in a row) */
    if (*area_loop != (long)sg->loop) {
        *area_loop = (long)sg->loop;
        *area = fm_trim_loop_area(loops[sg->loop]);
    }
    int side = (*area > 0) == (sg->loop == 0) ? 1 : -1;
    double a[3], b[3];
    eval3(s, l->uv + 2 * i, a);
    eval3(s, l->uv + 2 * ((i + 1) % l->n), b);
    double best = 0, tbest = -1;
    for (int k = 1; k < SAG_SAMPLES; k++) {
        double t = sg->ta + (sg->tb - sg->ta) * (double)k / SAG_SAMPLES, uv[2], p[3];
        fm_trim_loop_eval(loops[sg->loop], sg->piece, t, uv, NULL);
        eval3(s, uv, p);
        double d = fm_segment_distance3(p, a, b);
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
    if (fm_angle_at(p, a, b) < MIN_TIP)
        return -1;
    return tbest;
}

int domain_split_sags(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                      remesh_domain *d, double h)
{
    long area_loop = -1;
    double area = 0;
    for (size_t k = 0; k < d->n; k++) {
        dom_loop *l = &d->loops[k];
        /* a split segment is looked at again: both halves may still stray */
        for (size_t i = 0; i < l->n;) {
            double t = sag_split_t(s, loops, l, i, h, &area_loop, &area);
            if (t < 0) {
                i++;
                continue;
            }
            dom_seg tail = l->seg[i];
            tail.ta = t;
            l->seg[i].tb = t;
            double uv[2];
            fm_trim_loop_eval(loops[tail.loop], tail.piece, t, uv, NULL);
            if (loop_insert(l, i + 1, uv, 0, &tail))
                return -1;
        }
    }
    return 0;
}
