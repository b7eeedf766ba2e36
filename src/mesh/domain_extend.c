/* `--top extend D`: a fault whose top lies less than D below sea level is
 * grown up dip to it. The nodes of the outer loop's top edge (those whose
 * outward direction on the surface points within 60 degrees of up) move
 * along the surface's steepest ascent, over its fitted extension, until
 * they are a little above sea level; the cut that follows then makes the
 * new top exactly z = sea level. Lateral edges stay where they are, so the
 * fault's length along strike does not change. */
#include <math.h>
#include <stdlib.h>

#include "remesh_internal.h"

/* Outward direction of the loop at node i on the surface, as the cosine
 * of its angle with straight up. */
static double outward_up(const fm_fit_surface *s, const dom_loop *l, size_t i)
{
    const double *a = l->uv + 2 * ((i + l->n - 1) % l->n), *b = l->uv + 2 * ((i + 1) % l->n);
    double t[2] = {b[0] - a[0], b[1] - a[1]};
    double nrm[2] = {t[1], -t[0]}; /* right of a counter-clockwise loop: outside */
    double P[3], du[3], dv[3], o[3];
    fm_fit_surface_eval(s, l->uv[2 * i], l->uv[2 * i + 1], P, du, dv);
    /* The outward direction is the tangent-plane direction perpendicular
     * to the loop's 3D tangent, not the image of the (u, v) normal. */
    double T[3], N[3];
    for (int k = 0; k < 3; k++)
        T[k] = du[k] * t[0] + dv[k] * t[1];
    double sn[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2],
                    du[0] * dv[1] - du[1] * dv[0]};
    N[0] = T[1] * sn[2] - T[2] * sn[1];
    N[1] = T[2] * sn[0] - T[0] * sn[2];
    N[2] = T[0] * sn[1] - T[1] * sn[0];
    for (int k = 0; k < 3; k++)
        o[k] = du[k] * nrm[0] + dv[k] * nrm[1];
    if (N[0] * o[0] + N[1] * o[1] + N[2] * o[2] < 0)
        for (int k = 0; k < 3; k++)
            N[k] = -N[k];
    double len = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
    return len > 0 ? N[2] / len : 0;
}

/* Steepest ascent on the surface from uv until z > target; returns the 3D
 * path length, or -1 when it leaves the spline or stalls. */
static double climb(const fm_fit_surface *s, double uv[2], double target, double h,
                    double max_len, const double dom[4])
{
    double len = 0;
    for (int it = 0; it < 100000; it++) {
        double P[3], du[3], dv[3];
        fm_fit_surface_eval(s, uv[0], uv[1], P, du, dv);
        if (P[2] >= target)
            return len;
        double E = du[0] * du[0] + du[1] * du[1] + du[2] * du[2];
        double F = du[0] * dv[0] + du[1] * dv[1] + du[2] * dv[2];
        double G = dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2];
        double det = E * G - F * F;
        if (!(det > 0))
            return -1;
        /* gradient of z on the surface, in (u, v): M^-1 grad z */
        double d[2] = {(G * du[2] - F * dv[2]) / det, (E * dv[2] - F * du[2]) / det};
        double sp = sqrt(E * d[0] * d[0] + 2 * F * d[0] * d[1] + G * d[1] * d[1]);
        if (!(sp > 1e-12))
            return -1;
        double step = fmin(0.5 * h, 1.05 * (target - P[2]) / (du[2] * d[0] + dv[2] * d[1]) * sp);
        step = fmax(step, 1e-3 * h);
        uv[0] += step / sp * d[0];
        uv[1] += step / sp * d[1];
        len += step;
        if (len > max_len || uv[0] < dom[0] || uv[0] > dom[1] || uv[1] < dom[2] || uv[1] > dom[3])
            return -1;
    }
    return -1;
}

fm_status domain_extend_top(const fm_fit_surface *s, remesh_domain *d, double level,
                            double reach, double h, double *moved, fm_error *err,
                            const char *name)
{
    *moved = 0;
    if (d->n == 0)
        return FM_OK;
    dom_loop *l = &d->loops[0];
    double ztop = -INFINITY;
    for (size_t i = 0; i < l->n; i++)
        ztop = fmax(ztop, surface_z(s, l->uv + 2 * i, level, NULL));
    if (ztop >= 0 || ztop < -reach)
        return FM_OK;
    unsigned char *top = calloc(l->n, 1);
    if (!top)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    for (size_t i = 0; i < l->n; i++)
        top[i] = outward_up(s, l, i) > 0.5;
    double dom[4];
    fm_fit_surface_domain(s, dom);
    /* Past sea level by a fraction of a triangle, so the cut is clean. */
    double target = level + 0.3 * h;
    /* All or nothing: a top edge moved only in part would be jagged. */
    double *moved_uv = malloc(2 * l->n * sizeof *moved_uv);
    if (!moved_uv) {
        free(top);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    }
    double longest = 0;
    int ok = 1;
    for (size_t i = 0; i < l->n && ok; i++) {
        moved_uv[2 * i] = l->uv[2 * i];
        moved_uv[2 * i + 1] = l->uv[2 * i + 1];
        if (!top[i])
            continue;
        double len = climb(s, moved_uv + 2 * i, target, h, 4.0 * reach + 2.0 * h, dom);
        ok = len >= 0;
        longest = fmax(longest, len);
    }
    for (size_t i = 0; ok && i < l->n; i++) {
        if (!top[i])
            continue;
        l->uv[2 * i] = moved_uv[2 * i];
        l->uv[2 * i + 1] = moved_uv[2 * i + 1];
        l->seg[i].kind = SEG_FREE;
        l->seg[(i + l->n - 1) % l->n].kind = SEG_FREE;
    }
    if (ok)
        *moved = longest;
    free(moved_uv);
    free(top);
    return FM_OK;
}
