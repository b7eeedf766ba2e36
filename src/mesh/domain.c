/* The meshing domain: trimming loops sampled at the target size along
 * their length in 3D, and the surface helpers the other steps share. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_predicates.h"
#include "remesh_internal.h"

void domain_free(remesh_domain *d)
{
    for (size_t i = 0; i < d->n; i++) {
        free(d->loops[i].uv);
        free(d->loops[i].level);
        free(d->loops[i].seg);
    }
    free(d->loops);
    memset(d, 0, sizeof *d);
}

dom_loop *domain_add_loop(remesh_domain *d)
{
    if (d->n == d->cap) {
        size_t cap = d->cap ? 2 * d->cap : 4;
        dom_loop *nl = realloc(d->loops, cap * sizeof *nl);
        if (!nl)
            return NULL;
        d->loops = nl;
        d->cap = cap;
    }
    dom_loop *l = &d->loops[d->n++];
    memset(l, 0, sizeof *l);
    return l;
}

int loop_insert(dom_loop *l, size_t at, const double uv[2], int level, const dom_seg *seg)
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
    l->level[at] = level;
    l->seg[at] = *seg;
    l->n++;
    return 0;
}

int loop_push(dom_loop *l, const double uv[2], int level, const dom_seg *seg)
{
    return loop_insert(l, l->n, uv, level, seg);
}

double surface_z(const fm_fit_surface *s, const double uv[2], double level, double grad[2])
{
    double p[3], du[3], dv[3];
    fm_fit_surface_eval(s, uv[0], uv[1], p, grad ? du : NULL, grad ? dv : NULL);
    if (grad) {
        grad[0] = du[2];
        grad[1] = dv[2];
    }
    return p[2] - level;
}

double level_project(const fm_fit_surface *s, double uv[2], double level)
{
    double g[2], z = surface_z(s, uv, level, g);
    for (int it = 0; it < 12 && fabs(z) > 1e-9; it++) {
        double g2 = g[0] * g[0] + g[1] * g[1];
        if (!(g2 > 0))
            break;
        uv[0] -= z * g[0] / g2;
        uv[1] -= z * g[1] / g2;
        z = surface_z(s, uv, level, g);
    }
    return fabs(z);
}

double surface_dist(const fm_fit_surface *s, const double a[2], const double b[2])
{
    double pa[3], pb[3];
    fm_fit_surface_eval(s, a[0], a[1], pa, NULL, NULL);
    fm_fit_surface_eval(s, b[0], b[1], pb, NULL, NULL);
    return sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                (pa[2] - pb[2]) * (pa[2] - pb[2]));
}

void segment_point(const fm_fit_surface *s, const fm_trim_loop *const *loops, double level,
                   const dom_seg *sg, const double a[2], const double b[2], double f,
                   double out[2])
{
    if (sg->kind == SEG_TRIM) {
        double d[2];
        fm_trim_loop_eval(loops[sg->loop], sg->piece, sg->ta + f * (sg->tb - sg->ta), out, d);
        return;
    }
    out[0] = a[0] + f * (b[0] - a[0]);
    out[1] = a[1] + f * (b[1] - a[1]);
    if (sg->kind == SEG_LEVEL)
        level_project(s, out, level);
}

/* 3D length of a curve piece between ta and tb, by chords at a spacing
 * well below the knots: the t of a trimming curve is already close to 3D
 * arc length, this only corrects it. */
static double piece_length(const fm_fit_surface *s, const fm_trim_loop *l, size_t piece,
                           double ta, double tb, double h)
{
    size_t n = (size_t)ceil((tb - ta) / (0.25 * h));
    n = n < 4 ? 4 : n > 4096 ? 4096 : n;
    double prev[2], len = 0;
    fm_trim_loop_eval(l, piece, ta, prev, NULL);
    for (size_t i = 1; i <= n; i++) {
        double p[2];
        fm_trim_loop_eval(l, piece, ta + (tb - ta) * (double)i / (double)n, p, NULL);
        len += surface_dist(s, prev, p);
        prev[0] = p[0];
        prev[1] = p[1];
    }
    return len;
}

fm_status domain_sample(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                        size_t nloops, double h, remesh_domain *out, fm_error *err,
                        const char *name)
{
    memset(out, 0, sizeof *out);
    for (size_t k = 0; k < nloops; k++) {
        size_t np = fm_trim_loop_npieces(loops[k]);
        double *len = malloc(np * sizeof *len);
        size_t *cnt = malloc(np * sizeof *cnt);
        if (!len || !cnt) {
            free(len);
            free(cnt);
            goto nomem;
        }
        double total = 0;
        size_t nodes = 0;
        for (size_t p = 0; p < np; p++) {
            fm_trim_piece pc;
            fm_trim_loop_piece(loops[k], p, &pc);
            len[p] = piece_length(s, loops[k], p, pc.t0, pc.t1, h);
            total += len[p];
            cnt[p] = (size_t)lround(len[p] / h);
            cnt[p] = cnt[p] < 1 ? 1 : cnt[p];
            nodes += cnt[p];
        }
        /* A hole smaller than about two triangles cannot be meshed at this
         * size; it is closed over (the surface spans it smoothly). */
        if (k > 0 && total < 2.5 * h) {
            free(len);
            free(cnt);
            continue;
        }
        /* A loop needs three nodes: a sheet smaller than one triangle
         * still gets one, on the longest pieces. */
        while (nodes < 3) {
            size_t best = 0;
            for (size_t p = 1; p < np; p++)
                if (len[p] / (double)cnt[p] > len[best] / (double)cnt[best])
                    best = p;
            cnt[best]++;
            nodes++;
        }
        dom_loop *l = domain_add_loop(out);
        if (!l) {
            free(len);
            free(cnt);
            goto nomem;
        }
        for (size_t p = 0; p < np; p++) {
            fm_trim_piece pc;
            fm_trim_loop_piece(loops[k], p, &pc);
            size_t n = cnt[p];
            /* Equal steps in t: t is within a few per cent of 3D arc length. */
            for (size_t i = 0; i < n; i++) {
                dom_seg sg = {SEG_TRIM, (int)k, p, pc.t0 + (pc.t1 - pc.t0) * (double)i / (double)n,
                              pc.t0 + (pc.t1 - pc.t0) * (double)(i + 1) / (double)n};
                double uv[2];
                fm_trim_loop_eval(loops[k], p, sg.ta, uv, NULL);
                if (loop_push(l, uv, 0, &sg)) {
                    free(len);
                    free(cnt);
                    goto nomem;
                }
            }
        }
        free(len);
        free(cnt);
    }
    return FM_OK;
nomem:
    domain_free(out);
    return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
}

static int pt_same(const double *a, const double *b) { return a[0] == b[0] && a[1] == b[1]; }

int segments_cross(const double *a, const double *b, const double *c, const double *d)
{
    int o1 = fm_orient2d(a, b, c), o2 = fm_orient2d(a, b, d);
    int o3 = fm_orient2d(c, d, a), o4 = fm_orient2d(c, d, b);
    if (o1 * o2 > 0 || o3 * o4 > 0)
        return 0;
    if (o1 == 0 && o2 == 0) {
        int ax = a[0] != b[0];
        double lo1 = fmin(a[!ax], b[!ax]), hi1 = fmax(a[!ax], b[!ax]);
        double lo2 = fmin(c[!ax], d[!ax]), hi2 = fmax(c[!ax], d[!ax]);
        return lo1 < hi2 && lo2 < hi1;
    }
    return 1;
}

int chord_crosses_segment(const double *a, const double *b, const double box[4],
                          const double *c, const double *e)
{
    if ((c[0] < box[0] && e[0] < box[0]) || (c[0] > box[1] && e[0] > box[1]) ||
        (c[1] < box[2] && e[1] < box[2]) || (c[1] > box[3] && e[1] > box[3]))
        return 0;
    if (pt_same(a, c) || pt_same(a, e) || pt_same(b, c) || pt_same(b, e))
        return 0;
    return segments_cross(a, b, c, e);
}

/* 1 if the chord (a, b) crosses a segment of d not ending at a or b.
 * Despiking asks it of sharp nodes only; merging, which asks it of every
 * close pair, keeps a grid of the segments (domain_merge.c). */
static int chord_crosses(const remesh_domain *d, const double *a, const double *b)
{
    double box[4] = {fmin(a[0], b[0]), fmax(a[0], b[0]), fmin(a[1], b[1]), fmax(a[1], b[1])};
    for (size_t l = 0; l < d->n; l++) {
        const dom_loop *lp = &d->loops[l];
        for (size_t i = 0; i < lp->n; i++)
            if (chord_crosses_segment(a, b, box, lp->uv + 2 * i, lp->uv + 2 * ((i + 1) % lp->n)))
                return 1;
    }
    return 0;
}

/* Angle (degrees, 3D) at node i between its two segments. */
static double node_angle(const fm_fit_surface *s, const dom_loop *l, size_t i)
{
    double a[3], b[3], c[3];
    size_t n = l->n;
    fm_fit_surface_eval(s, l->uv[2 * ((i + n - 1) % n)], l->uv[2 * ((i + n - 1) % n) + 1], a, NULL, NULL);
    fm_fit_surface_eval(s, l->uv[2 * i], l->uv[2 * i + 1], b, NULL, NULL);
    fm_fit_surface_eval(s, l->uv[2 * ((i + 1) % n)], l->uv[2 * ((i + 1) % n) + 1], c, NULL, NULL);
    return fm_angle_at(b, a, c);
}

void domain_despike(const fm_fit_surface *s, remesh_domain *d, double min_angle)
{
    for (size_t l = 0; l < d->n; l++) {
        dom_loop *lp = &d->loops[l];
        int changed = 1;
        while (changed && lp->n > 3) {
            changed = 0;
            for (size_t i = 0; i < lp->n && lp->n > 3; i++) {
                if (node_angle(s, lp, i) >= min_angle)
                    continue;
                size_t n = lp->n, ip = (i + n - 1) % n, in = (i + 1) % n;
                if (chord_crosses(d, lp->uv + 2 * ip, lp->uv + 2 * in))
                    continue;
                dom_seg *sp = &lp->seg[ip], *si = &lp->seg[i];
                if (sp->kind == SEG_TRIM && si->kind == SEG_TRIM && sp->loop == si->loop &&
                    sp->piece == si->piece)
                    sp->tb = si->tb;
                else if (sp->kind != si->kind || sp->kind == SEG_TRIM)
                    sp->kind = SEG_FREE;
                memmove(lp->uv + 2 * i, lp->uv + 2 * (i + 1), 2 * (n - i - 1) * sizeof *lp->uv);
                memmove(lp->level + i, lp->level + i + 1, (n - i - 1) * sizeof *lp->level);
                memmove(lp->seg + i, lp->seg + i + 1, (n - i - 1) * sizeof *lp->seg);
                lp->n--;
                changed = 1;
            }
        }
    }
}

