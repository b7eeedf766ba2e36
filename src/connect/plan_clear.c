/* A junction curve given up for a conflict on one of its sheets while the
 * two sheets still cross there (plan_internal.h). Left as it was, one sheet
 * runs through the other and their meshes cut each other: no simulator can
 * use that. A sheet that was to END at the curve can instead end a little
 * short of the other surface, on its own side: the pair stays unjoined (the
 * report says so, with the gap left), but the meshes no longer touch, and
 * the curve lives on that one sheet only, clear of the conflict on the
 * other. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_predicates.h"
#include "plan_internal.h"
#include "fm_vec3.h"

static void unit_normal(const double du[3], const double dv[3], double n[3])
{
    n[0] = du[1] * dv[2] - du[2] * dv[1];
    n[1] = du[2] * dv[0] - du[0] * dv[2];
    n[2] = du[0] * dv[1] - du[1] * dv[0];
    double l = sqrt(fm_dot3(n, n));
    for (int k = 0; k < 3; k++)
        n[k] = l > 0 ? n[k] / l : 0;
}

/* Where the sheet's edge is to be trimmed: inside its outline, or outside
 * but within `near` of it (an edge that runs along the other surface,
 * now just short of it, now just through it, is trimmed all along, or
 * the next stretch through it would be left). */
static int usable(const pl_outline *o, const double uv[2], double near)
{
    if (pl_outline_inside(o, uv))
        return 1;
    double x[3], foot[3], fuv[2];
    fm_fit_surface_eval(o->surf, uv[0], uv[1], x, NULL, NULL);
    return pl_outline_foot(o, x, foot, fuv) <= near;
}

/* Where the segment from node ia (usable) to node ib (not) stops being
 * usable: bisection, to a metre or so. */
static void leave_point(const pl_outline *o, const double *uv, size_t ia, size_t ib,
                        double near, double out[2])
{
    const double *a = uv + 2 * ia, *b = uv + 2 * ib;
    double lo = 0, hi = 1;
    for (int it = 0; it < 40; it++) {
        double t = 0.5 * (lo + hi), p[2] = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
        if (usable(o, p, near))
            lo = t;
        else
            hi = t;
    }
    out[0] = a[0] + lo * (b[0] - a[0]);
    out[1] = a[1] + lo * (b[1] - a[1]);
}

/* The stretch of curve c that sheet s trims at: its longest run of usable
 * nodes, with an end put where the run leaves them, so that the stretch
 * cuts the sheet from edge to edge. It must hold a node inside both
 * outlines (ot: the other sheet's), or the two do not cross there and
 * there is nothing to clear. uv: side s's, 2 per node, *n nodes. */
static int inside_run(const pl_curve *c, int s, const pl_outline *os, const pl_outline *ot,
                      double H, double near, double *uv, size_t *n)
{
    const double *cu = c->uv[s];
    size_t bf = 0, bt = 0, best = 0;
    for (size_t i = 0; i < c->n; i++) {
        if (!usable(os, cu + 2 * i, near))
            continue;
        size_t t = i;
        while (t + 1 < c->n && usable(os, cu + 2 * t + 2, near))
            t++;
        if (t - i + 1 > best) {
            best = t - i + 1;
            bf = i;
            bt = t;
        }
        i = t;
    }
    /* it starts and ends inside: only a stretch between two inside ones
     * may run just outside (ends out there would fill past the edge) */
    while (best && bf < bt && !pl_outline_inside(os, cu + 2 * bf))
        bf++;
    while (best && bt > bf && !pl_outline_inside(os, cu + 2 * bt))
        bt--;
    if (best && !pl_outline_inside(os, cu + 2 * bf))
        best = 0;
    *n = 0;
    int crosses = 0;
    for (size_t i = bf; best && i <= bt; i++)
        crosses |= pl_outline_inside(os, cu + 2 * i) && pl_outline_inside(ot, c->uv[1 - s] + 2 * i);
    if (!crosses)
        return 0;
    double ends[2][2];
    int has[2] = {bf > 0, bt + 1 < c->n};
    if (has[0])
        leave_point(os, cu, bf, bf - 1, 0, ends[0]);
    if (has[1])
        leave_point(os, cu, bt, bt + 1, 0, ends[1]);
    /* an end within a quarter size of the last inside node replaces it, so
     * that the curve keeps its spacing */
    double q = 0.25 * H;
    for (int e = 0; e < 2; e++) {
        if (!has[e])
            continue;
        const double *p = cu + 2 * (e ? bt : bf);
        if (hypot(ends[e][0] - p[0], ends[e][1] - p[1]) < q && bt > bf) {
            if (e)
                bt--;
            else
                bf++;
        }
    }
    size_t m = 0;
    if (has[0]) {
        uv[2 * m] = ends[0][0];
        uv[2 * m + 1] = ends[0][1];
        m++;
    }
    for (size_t i = bf; i <= bt; i++, m++) {
        uv[2 * m] = cu[2 * i];
        uv[2 * m + 1] = cu[2 * i + 1];
    }
    if (has[1]) {
        uv[2 * m] = ends[1][0];
        uv[2 * m + 1] = ends[1][1];
        m++;
    }
    *n = m;
    return m >= 2;
}

/* Signed distance from S(uv) to surface T; sign > 0 on T's normal side. */
static double away(const fm_fit_surface *S, const fm_fit_surface *T, const double uv[2],
                   double x[3])
{
    fm_fit_surface_eval(S, uv[0], uv[1], x, NULL, NULL);
    double tuv[2], d = 0;
    fm_fit_project(T, x, tuv, NULL, &d);
    return d;
}

static int above(const fm_fit_surface *S, const double uv[2], double level)
{
    double x[3];
    fm_fit_surface_eval(S, uv[0], uv[1], x, NULL, NULL);
    return x[2] > level;
}

/* Newton on z(u, v) = level from uv, along the gradient of z. 0: on it
 * (to 1e-9 m); 1: not. */
static int to_level(const fm_fit_surface *S, double level, double uv[2])
{
    for (int it = 0; it < 20; it++) {
        double x[3], du[3], dv[3];
        fm_fit_surface_eval(S, uv[0], uv[1], x, du, dv);
        double f = x[2] - level, g2 = du[2] * du[2] + dv[2] * dv[2];
        if (fabs(f) < 1e-9)
            return 0;
        if (!(g2 > 0))
            return 1;
        uv[0] -= f * du[2] / g2;
        uv[1] -= f * dv[2] / g2;
    }
    return 1;
}

/* Moves every node of the stretch into the kept side of sheet s until it
 * lies `gap` from the other surface (within a size along the sheet: at a
 * grazing angle the clearance may stay under it, never under half of
 * it). 0: done; 1: a node could not be cleared. */
static int offset_stretch(const fm_fit_surface *S, const fm_fit_surface *T, int keep_left,
                          double gap, double H, const double *level, double *uv, double *xyz,
                          size_t n)
{
    double *out = malloc(2 * n * sizeof *out + 1);
    if (!out)
        return -1;
    int rc = 0;
    for (size_t k = 0; k < n && rc == 0; k++) {
        size_t a = k ? k - 1 : 0, b = k + 1 < n ? k + 1 : n - 1;
        double t[2] = {uv[2 * b] - uv[2 * a], uv[2 * b + 1] - uv[2 * a + 1]};
        double lt = hypot(t[0], t[1]);
        if (!(lt > 0)) {
            rc = 1;
            break;
        }
        double dir[2] = {-t[1] / lt, t[0] / lt};
        if (!keep_left) {
            dir[0] = -dir[0];
            dir[1] = -dir[1];
        }
        double x[3], du[3], dv[3];
        fm_fit_surface_eval(S, uv[2 * k], uv[2 * k + 1], x, du, dv);
        /* the top cut put a node on sea level: it stays on it */
        int on_level = level && fabs(x[2] - *level) < 1e-6;
        double w[3] = {du[0] * dir[0] + dv[0] * dir[1], du[1] * dir[0] + dv[1] * dir[1],
                       du[2] * dir[0] + dv[2] * dir[1]};
        double lw = sqrt(fm_dot3(w, w));
        if (!(lw > 0)) {
            rc = 1;
            break;
        }
        /* the node's distance to T grows by sin(angle) per metre moved
         * along S: start there, then secant steps on the true distance */
        double tuv[2], foot[3], d0 = 0;
        fm_fit_project(T, x, tuv, foot, &d0);
        double tdu[3], tdv[3], tn[3], tx[3];
        fm_fit_surface_eval(T, tuv[0], tuv[1], tx, tdu, tdv);
        unit_normal(tdu, tdv, tn);
        double rate = fabs(fm_dot3(tn, w)) / lw;
        double reach = H / lw; /* the most a node may move, in (u, v) */
        double sg = fmin(gap / fmax(rate, 1e-3) / lw, reach);
        double p[2], d = 0;
        for (int it = 0; it < 6; it++) {
            p[0] = uv[2 * k] + sg * dir[0];
            p[1] = uv[2 * k + 1] + sg * dir[1];
            d = fabs(away(S, T, p, x));
            if (fabs(d - gap) < 0.02 * gap || !(d > 0))
                break;
            double next = sg * gap / d;
            if (next > reach) {
                if (sg >= reach)
                    break;
                next = reach;
            }
            sg = next;
        }
        p[0] = uv[2 * k] + sg * dir[0];
        p[1] = uv[2 * k + 1] + sg * dir[1];
        int leveled = level && (on_level || above(S, p, *level));
        if (leveled && to_level(S, *level, p))
            rc = 1;
        d = fabs(away(S, T, p, x));
        if (leveled)
            x[2] = *level; /* within 1e-9 m of it: the cut is exact */
        if (rc || !(d >= 0.5 * gap)) {
            rc = 1;
            rc = 1;
            break;
        }
        out[2 * k] = p[0];
        out[2 * k + 1] = p[1];
        memcpy(xyz + 3 * k, x, sizeof x);
    }
    if (rc == 0) {
        /* an offset that folds (a bend tighter than the gap) is no curve */
        for (size_t i = 0; i + 1 < n && rc == 0; i++)
            for (size_t k = i + 2; k + 1 < n && rc == 0; k++)
                if (fm_orient2d(out + 2 * i, out + 2 * i + 2, out + 2 * k) *
                            fm_orient2d(out + 2 * i, out + 2 * i + 2, out + 2 * k + 2) <
                        0 &&
                    fm_orient2d(out + 2 * k, out + 2 * k + 2, out + 2 * i) *
                            fm_orient2d(out + 2 * k, out + 2 * k + 2, out + 2 * i + 2) <
                        0)
                    rc = 1;
        if (rc == 0)
            memcpy(uv, out, 2 * n * sizeof *uv);
    }
    free(out);
    return rc;
}

int pl_clear_curve(const fm_connect_junction *j, const pl_curve *c, int s,
                   const fm_model *const *models, double H, double gap, const double *level,
                   pl_curve *out)
{
    memset(out, 0, sizeof *out);
    if (!c->end[s])
        return 0;
    const fm_model *ms = models[j->fault[s]], *mt = models[j->fault[1 - s]];
    const fm_fit_surface *S = fm_model_surface(ms, j->sheet[s]);
    const fm_fit_surface *T = fm_model_surface(mt, j->sheet[1 - s]);
    pl_outline o[2];
    memset(o, 0, sizeof o);
    if (pl_outline_build(ms, j->sheet[s], &o[0], NULL) != FM_OK)
        return 0;
    if (pl_outline_build(mt, j->sheet[1 - s], &o[1], NULL) != FM_OK) {
        pl_outline_free(&o[0]);
        return 0;
    }
    double *uv = malloc(2 * (c->n + 2) * sizeof *uv);
    double *xyz = malloc(3 * (c->n + 2) * sizeof *xyz);
    if (!uv || !xyz) {
        free(uv);
        free(xyz);
        pl_outline_free(&o[0]);
        pl_outline_free(&o[1]);
        return -1;
    }
    size_t n = 0;
    /* twice the gap: the fill out to the curve stays within it */
    int r = inside_run(c, s, &o[0], &o[1], H, gap, uv, &n)
                ? offset_stretch(S, T, c->keep_left[s], gap, H, level, uv, xyz, n)
                : 1;
    pl_outline_free(&o[0]);
    pl_outline_free(&o[1]);
    if (r != 0) {
        free(uv);
        free(xyz);
        return r < 0 ? -1 : 0;
    }
    /* the other side's (u, v) stays for the curve's shape only: the
     * curve is not given to that sheet */
    double *uvt = malloc(2 * n * sizeof *uvt);
    if (!uvt) {
        free(uv);
        free(xyz);
        return -1;
    }
    memcpy(uvt, uv, 2 * n * sizeof *uvt);
    out->n = n;
    out->xyz = xyz;
    out->uv[s] = uv;
    out->uv[1 - s] = uvt;
    out->end[s] = 1;
    out->keep_left[s] = c->keep_left[s];
    out->keep_left[1 - s] = 1;
    out->off[1 - s] = 1;
    return 1;
}
