/* The part of a trimmed surface worth writing.
 *
 * A fitted fault surface extends well past its trimming loop (the fit's
 * extension margin, and the rectangle around a slanting outline), and on
 * the whole CFM a third of its control points only shape that unused
 * part. A B-spline restricted to a run of its knot spans is exactly the
 * same surface on them, so the window keeps the spans the outer loop's
 * control polygon touches: the loop lies inside that polygon's bounding
 * box (convex hull property, weights positive), and so inside the spans. */
#include "iges_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Control points [*i0, *i0 + *ni) and the parameter interval [*a, *b] for
 * the spans of knots (degree p, n control points) that meet [lo, hi]
 * within the range [r0, r1]. */
static void window_1d(const double *knots, int p, size_t n, double lo, double hi, double r0,
                      double r1, size_t *i0, size_t *ni, double *a, double *b)
{
    size_t pp = (size_t)p;
    *i0 = 0;
    *ni = n;
    *a = r0;
    *b = r1;
    lo = fmax(lo, r0);
    hi = fmin(hi, r1);
    if (!(lo < hi))
        return;
    size_t ks = pp, ke = n - 1;
    while (ks < n - 1 && !(knots[ks + 1] > lo))
        ks++;
    while (ke > pp && !(knots[ke] < hi))
        ke--;
    if (ks > ke)
        return;
    *i0 = ks - pp;
    *ni = ke - ks + 1 + pp;
    *a = fmax(r0, knots[ks]);
    *b = fmin(r1, knots[ke + 1]);
}

void iges_face_window(const fm_iges_face *f, iges_window *w)
{
    const fm_iges_surface *s = &f->surface;
    iges_face_range(s, w->r);
    w->i0 = w->j0 = 0;
    w->ni = s->nu;
    w->nj = s->nv;
    if (!f->outer)
        return;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t k = 0; k < f->outer->ncurves; k++) {
        const fm_iges_curve2d *c = &f->outer->curves[k];
        for (size_t i = 0; i < c->n; i++)
            for (int d = 0; d < 2; d++) {
                lo[d] = fmin(lo[d], c->ctrl[2 * i + (size_t)d]);
                hi[d] = fmax(hi[d], c->ctrl[2 * i + (size_t)d]);
            }
    }
    double r[4] = {w->r[0], w->r[1], w->r[2], w->r[3]};
    window_1d(s->knots_u, s->degree_u, s->nu, lo[0], hi[0], r[0], r[1], &w->i0, &w->ni, &w->r[0],
              &w->r[1]);
    window_1d(s->knots_v, s->degree_v, s->nv, lo[1], hi[1], r[2], r[3], &w->j0, &w->nj, &w->r[2],
              &w->r[3]);
}

void iges_net_free(iges_net *net)
{
    free(net->knots_u);
    free(net->knots_v);
    free(net->ctrl);
    free(net->weights);
    memset(net, 0, sizeof *net);
}

fm_status iges_net_copy(const fm_iges_surface *s, const iges_window *w, iges_net *net)
{
    memset(net, 0, sizeof *net);
    net->pu = s->degree_u;
    net->pv = s->degree_v;
    net->nu = w->ni;
    net->nv = w->nj;
    size_t mu = w->ni + (size_t)s->degree_u + 1, mv = w->nj + (size_t)s->degree_v + 1;
    size_t n = w->ni * w->nj;
    net->knots_u = malloc(mu * sizeof *net->knots_u);
    net->knots_v = malloc(mv * sizeof *net->knots_v);
    net->ctrl = malloc(3 * n * sizeof *net->ctrl);
    net->weights = s->weights ? malloc(n * sizeof *net->weights) : NULL;
    if (!net->knots_u || !net->knots_v || !net->ctrl || (s->weights && !net->weights)) {
        iges_net_free(net);
        return FM_ERR_NOMEM;
    }
    memcpy(net->knots_u, s->knots_u + w->i0, mu * sizeof *net->knots_u);
    memcpy(net->knots_v, s->knots_v + w->j0, mv * sizeof *net->knots_v);
    for (size_t j = 0; j < w->nj; j++) {
        size_t from = (w->j0 + j) * s->nu + w->i0;
        memcpy(net->ctrl + 3 * j * w->ni, s->ctrl + 3 * from, 3 * w->ni * sizeof *net->ctrl);
        if (s->weights)
            memcpy(net->weights + j * w->ni, s->weights + from, w->ni * sizeof *net->weights);
    }
    memcpy(net->r, w->r, sizeof net->r);
    return FM_OK;
}
