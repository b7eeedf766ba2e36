/* Rectangular elements: rows by down-dip distance, columns along each
 * row's middle contour (fm_tile.h). */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "fm_parallel.h"
#include "tile_internal.h"
#include "fm_vec3.h"

#define NBINS 256
/* Below about 2 degrees a depth row no longer says where a tile ends down
 * dip; such tiles keep a width of 1 / sin(2 deg) ~ 29 times their row. */

/* Unit normal of triangle t (zero when degenerate). */
static void tri_normal(const double *x, const int32_t *tri, size_t t, double n[3])
{
    const double *a = x + 3 * (size_t)tri[3 * t], *b = x + 3 * (size_t)tri[3 * t + 1],
                 *c = x + 3 * (size_t)tri[3 * t + 2];
    double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double g[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    fm_cross3(e, g, n);
    double l = sqrt(fm_dot3(n, n));
    for (int d = 0; d < 3; d++)
        n[d] = l > 0 ? n[d] / l : 0;
}

/* Where level (along up) crosses the edge u-v, computed from the
 * lower-numbered end so that both triangles of the edge get the same
 * point. */
static void crossing(const double *x, const double up[3], int32_t u, int32_t v, double level,
                     double p[3])
{
    if (u > v) {
        int32_t w = u;
        u = v;
        v = w;
    }
    const double *a = x + 3 * (size_t)u, *b = x + 3 * (size_t)v;
    double la = tile_level(up, a), t = (level - la) / (tile_level(up, b) - la);
    for (int d = 0; d < 3; d++)
        p[d] = a[d] + t * (b[d] - a[d]);
}

typedef struct tiler {
    const double *x;
    const int32_t *tri;
    const int32_t *nbr;  /* per triangle side: the triangle of the same fault across it, -1 at
                            an outline, a junction or a side of more than two */
    int32_t *stamp;      /* per triangle: the contour that went through it */
    int32_t cur;         /* this contour's stamp */
    double size;
    double up[3];        /* the fault's (tile_fault_best) */
    int extra_rows;      /* added to the row count closest to the size */
    int depth_only;      /* rows by depth only (a part of a fault, tile_fault_parts) */
    double rowdw;        /* the row's width down dip (tile_fault) */
    fm_tiles *out;
    /* one contour */
    double *pt;          /* 3 per point */
    int32_t *seg;        /* triangle of each segment */
    double *s;           /* arc length at each point */
    size_t npt, cap;
} tiler;

static int push_point(tiler *tl, const double p[3], int32_t seg)
{
    if (tl->npt == tl->cap) {
        size_t c = tl->cap ? 2 * tl->cap : 256;
        double *pt = realloc(tl->pt, 3 * c * sizeof *pt);
        if (pt)
            tl->pt = pt;
        int32_t *sg = realloc(tl->seg, c * sizeof *sg);
        if (sg)
            tl->seg = sg;
        double *s = realloc(tl->s, c * sizeof *s);
        if (s)
            tl->s = s;
        if (!pt || !sg || !s)
            return -1;
        tl->cap = c;
    }
    memcpy(tl->pt + 3 * tl->npt, p, 3 * sizeof *p);
    tl->seg[tl->npt] = seg; /* the segment that starts here */
    tl->npt++;
    return 0;
}

int tile_push(fm_tiles *t, const fm_tile *tile, double ztop, double zbot, double dw, int open)
{
    if (t->n == t->cap) {
        size_t c = t->cap ? 2 * t->cap : 256;
        fm_tile *nt = realloc(t->tile, c * sizeof *nt);
        if (nt)
            t->tile = nt;
        double(*nb)[4] = realloc(t->band, c * sizeof *nb);
        if (nb)
            t->band = nb;
        if (!nt || !nb)
            return -1;
        t->cap = c;
    }
    t->band[t->n][0] = ztop;
    t->band[t->n][1] = zbot;
    t->band[t->n][2] = dw;
    t->band[t->n][3] = open;
    t->tile[t->n++] = *tile;
    return 0;
}

/* The sides of triangle t that level crosses (vertices at exactly level
 * were moved off it by the caller): their numbers in k[0], k[1]; 0 when it
 * does not cross. */
static int crossed_sides(const tiler *tl, size_t t, double level, int k[2])
{
    int above[3], m = 0;
    for (int i = 0; i < 3; i++)
        above[i] = tile_level(tl->up, tl->x + 3 * (size_t)tl->tri[3 * t + (size_t)i]) > level;
    for (int i = 0; i < 3; i++)
        if (above[i] != above[(i + 1) % 3])
            k[m++] = i;
    return m == 2;
}

static void side_point(const tiler *tl, size_t t, int k, double level, double p[3])
{
    crossing(tl->x, tl->up, tl->tri[3 * t + (size_t)k], tl->tri[3 * t + (size_t)(k + 1) % 3],
             level, p);
}

/* Point at arc length s along the contour, and the segment it lies on. */
static size_t point_at(const tiler *tl, double s, double p[3])
{
    size_t lo = 0, hi = tl->npt - 1;
    while (hi - lo > 1) {
        size_t mid = (lo + hi) / 2;
        if (tl->s[mid] <= s)
            lo = mid;
        else
            hi = mid;
    }
    double len = tl->s[lo + 1] - tl->s[lo];
    double t = len > 0 ? (s - tl->s[lo]) / len : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    for (int d = 0; d < 3; d++)
        p[d] = tl->pt[3 * lo + d] + t * (tl->pt[3 * (lo + 1) + d] - tl->pt[3 * lo + d]);
    return lo;
}

/* One tile over the contour's piece [sa, sb]. */
static int tile_piece(tiler *tl, int32_t fault, int32_t row, double sa, double sb, double ztop,
                      double zbot, int open)
{
    double pa[3], pb[3], pm[3];
    point_at(tl, sa, pa);
    point_at(tl, sb, pb);
    size_t mseg = point_at(tl, (sa + sb) / 2, pm);
    double st[3] = {pb[0] - pa[0], pb[1] - pa[1], 0};
    double len = hypot(st[0], st[1]);
    if (!(len > 1e-9 * tl->size))
        return 0;
    st[0] /= len;
    st[1] /= len;
    /* The plane's normal lies across the strike: an axial mean (doubled
     * angles) in the plane of r = strike x up and up, so that triangles
     * wound either way agree. */
    double r[3] = {st[1], -st[0], 0};
    double c2 = 0, s2 = 0;
    for (size_t i = 0; i + 1 < tl->npt; i++) {
        double lo = fmax(tl->s[i], sa), hi = fmin(tl->s[i + 1], sb);
        if (hi <= lo)
            continue;
        double n[3];
        tri_normal(tl->x, tl->tri, (size_t)tl->seg[i], n);
        double a = fm_dot3(n, r), b = n[2], q = a * a + b * b;
        if (q < 1e-12)
            continue;
        c2 += (hi - lo) * (a * a - b * b) / q;
        s2 += (hi - lo) * 2 * a * b / q;
    }
    double th = (c2 == 0 && s2 == 0) ? 0 : atan2(s2, c2) / 2;
    double n[3] = {cos(th) * r[0], cos(th) * r[1], sin(th)}, dip[3];
    tile_frame(st, n, dip);
    double sd = fmax(fabs(fm_dot3(dip, tl->up)), tile_min_sin(ztop - zbot, tl->rowdw));
    fm_tile t = {.fault = fault, .triangle = tl->seg[mseg], .row = row, .length = len,
                 .width = (ztop - zbot) / sd};
    memcpy(t.centre, pm, sizeof pm);
    memcpy(t.strike, st, sizeof st);
    memcpy(t.dip, dip, sizeof dip);
    /* looking the other way along the contour swaps its ends */
    if (st[0] * (pb[0] - pa[0]) + st[1] * (pb[1] - pa[1]) < 0)
        open = (open & 1) << 1 | (open & 2) >> 1;
    return tile_push(tl->out, &t, ztop, zbot, tl->rowdw, open);
}

/* Whether p lies under a tile of this row made so far (from first on). */
static int covered(const tiler *tl, size_t first, const double p[3])
{
    for (size_t i = first; i < tl->out->n; i++) {
        double w;
        int inside;
        tile_distance(&tl->out->tile[i], p, &w, &inside);
        if (inside && fabs(w) <= tl->size)
            return 1;
    }
    return 0;
}

/* The stretches of the contour in tl that no tile of the row (from
 * first on) covers, tiled: where the surface does not reach the row's
 * middle depth. */
static int fill_contour(tiler *tl, int32_t fault, int32_t row, size_t first, double ztop,
                        double zbot)
{
    double len = tl->s[tl->npt - 1], step = tl->size / 8;
    long ns = (long)ceil(len / step);
    if (ns < 1)
        return 0;
    double run = -1;
    for (long k = 0; k <= ns + 1; k++) {
        double s = fmin(len, (double)k * len / (double)ns), p[3];
        int open = k <= ns;
        if (open) {
            point_at(tl, s, p);
            open = !covered(tl, first, p);
        }
        if (open && run < 0)
            run = k ? s - len / (double)ns / 2 : 0;
        if (!open && run >= 0) {
            double end = k <= ns ? s - len / (double)ns / 2 : len;
            double l = end - run;
            if (l >= tl->size / 4) {
                long nc = lround(l / tl->size);
                if (nc < 1)
                    nc = 1;
                /* open where the run ends with the contour */
                int ends = (run <= 0 ? 1 : 0) | (end >= len ? 2 : 0);
                for (long j = 0; j < nc; j++)
                    if (tile_piece(tl, fault, row, run + l * (double)j / (double)nc,
                                   run + l * (double)(j + 1) / (double)nc, ztop, zbot,
                                   (j == 0 ? ends & 1 : 0) | (j == nc - 1 ? ends & 2 : 0)))
                        return -1;
            }
            run = -1;
        }
    }
    return 0;
}

/* The contour held in tl cut into tiles; fill (the first tile of the row
 * from fill - 1 on): only what the row's tiles do not cover yet. */
static int tile_contour(tiler *tl, int32_t fault, int32_t row, int closed, double ztop,
                        double zbot, size_t fill)
{
    if (tl->npt < 2)
        return 0;
    tl->s[0] = 0;
    for (size_t i = 1; i < tl->npt; i++) {
        const double *a = tl->pt + 3 * (i - 1), *b = tl->pt + 3 * i;
        tl->s[i] = tl->s[i - 1] + hypot(b[0] - a[0], b[1] - a[1]);
    }
    if (fill)
        return fill_contour(tl, fault, row, fill - 1, ztop, zbot);
    double len = tl->s[tl->npt - 1];
    long ncol = lround(len / tl->size);
    if (closed) {
        if (ncol < 3)
            ncol = 3;
    } else {
        if (len < tl->size / 10)
            return 0; /* a sliver of a tile: left to the area measure */
        if (ncol < 1)
            ncol = 1;
    }
    /* the end pieces of an open contour take the surface past its ends (the
     * outline or junction crossing the row at a slant) into their area */
    for (long j = 0; j < ncol; j++)
        if (tile_piece(tl, fault, row, len * (double)j / (double)ncol,
                       len * (double)(j + 1) / (double)ncol, ztop, zbot,
                       closed ? 0 : (j == 0 ? 1 : 0) | (j == ncol - 1 ? 2 : 0)))
            return -1;
    return 0;
}

/* Follows the contour from triangle t, entered across side kin; the
 * points go into tl. */
static int walk(tiler *tl, size_t t, int kin, double level)
{
    double p[3];
    tl->npt = 0;
    side_point(tl, t, kin, level, p);
    for (;;) {
        tl->stamp[t] = tl->cur;
        int k[2];
        crossed_sides(tl, t, level, k);
        int kout = k[0] == kin ? k[1] : k[0];
        if (push_point(tl, p, (int32_t)t))
            return -1;
        side_point(tl, t, kout, level, p);
        int32_t nt = tl->nbr[3 * t + (size_t)kout];
        if (nt < 0 || tl->stamp[nt] == tl->cur)
            break;
        /* the side of nt that is the same edge */
        kin = fm_triangle_side(tl->tri + 3 * (size_t)nt, tl->tri[3 * t + (size_t)kout],
                               tl->tri[3 * t + (size_t)(kout + 1) % 3]);
        if (kin < 0)
            break;
        t = (size_t)nt;
    }
    return push_point(tl, p, -1);
}

/* Every contour of fault f at level, tiled. */
static int tile_row(tiler *tl, int32_t f, const size_t *tris, size_t n, int32_t row,
                    double level, double ztop, double zbot, size_t fill)
{
    tl->cur++;
    /* open contours first, from their ends, then closed ones */
    for (int pass = 0; pass < 2; pass++)
        for (size_t i = 0; i < n; i++) {
            size_t t = tris[i];
            int k[2];
            if (tl->stamp[t] == tl->cur || !crossed_sides(tl, t, level, k))
                continue;
            int kin = -1;
            if (pass == 0) {
                if (tl->nbr[3 * t + (size_t)k[0]] < 0)
                    kin = k[0];
                else if (tl->nbr[3 * t + (size_t)k[1]] < 0)
                    kin = k[1];
                if (kin < 0)
                    continue;
            } else {
                kin = k[0];
            }
            if (walk(tl, t, kin, level) ||
                tile_contour(tl, f, row, pass == 1, ztop, zbot, fill))
                return -1;
        }
    return 0;
}

/* The level (tile_level) at down-dip distance dv from the bottom (cumulative dd over
 * the bins). */
static double depth_at(const double *dd, double zlo, double dz, double dv)
{
    size_t k = 0;
    while (k + 1 < NBINS && dd[k + 1] < dv)
        k++;
    double span = dd[k + 1] - dd[k];
    double t = span > 0 ? (dv - dd[k]) / span : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return zlo + ((double)k + t) * dz;
}

/* How well levels along g lay a fault out in rows: the area-weighted
 * mean rate at which the level changes along its surface (the sine of
 * the angle between g and each triangle's normal). */
static double level_rate(const tiler *tl, const size_t *tris, size_t n, const double g[3])
{
    double sum = 0, atot = 0;
    for (size_t i = 0; i < n; i++) {
        size_t t = tris[i];
        const double *a = tl->x + 3 * (size_t)tl->tri[3 * t],
                     *b = tl->x + 3 * (size_t)tl->tri[3 * t + 1],
                     *c = tl->x + 3 * (size_t)tl->tri[3 * t + 2];
        double ar = fm_triangle_area(a, b, c), nrm[3];
        tri_normal(tl->x, tl->tri, t, nrm);
        double d = fm_dot3(nrm, g);
        sum += ar * sqrt(fmax(0, 1 - d * d));
        atot += ar;
    }
    return atot > 0 ? sum / atot : 0;
}

/* The other direction fault f's rows may be levels of (into g): up the
 * dip of its mean plane (the plane's normal the principal axis of its
 * triangles' normals, either way round), down-dip distance on that plane,
 * along strike wherever the fault keeps its strike; a fault flat within
 * about a degree takes the horizontal across its longer side. 0 when it
 * is not worth trying: the levels would not change along the surface
 * faster than depth does (for a plane both give the same rows). */
static int fault_up(tiler *tl, const size_t *tris, size_t n, double g[3])
{
    const double z[3] = {0, 0, 1};
    double m[3][3] = {{0}}, cxy[3] = {0, 0, 0}, mc[2] = {0, 0}, atot = 0;
    for (size_t i = 0; i < n; i++) {
        size_t t = tris[i];
        const double *a = tl->x + 3 * (size_t)tl->tri[3 * t],
                     *b = tl->x + 3 * (size_t)tl->tri[3 * t + 1],
                     *c = tl->x + 3 * (size_t)tl->tri[3 * t + 2];
        double ar = fm_triangle_area(a, b, c), nrm[3];
        tri_normal(tl->x, tl->tri, t, nrm);
        for (int p = 0; p < 3; p++)
            for (int q = 0; q < 3; q++)
                m[p][q] += ar * nrm[p] * nrm[q];
        /* the horizontal spread, about the first vertex's place */
        double cx = (a[0] + b[0] + c[0]) / 3 - tl->x[3 * (size_t)tl->tri[3 * tris[0]]];
        double cy = (a[1] + b[1] + c[1]) / 3 - tl->x[3 * (size_t)tl->tri[3 * tris[0]] + 1];
        mc[0] += ar * cx;
        mc[1] += ar * cy;
        cxy[0] += ar * cx * cx;
        cxy[1] += ar * cx * cy;
        cxy[2] += ar * cy * cy;
        atot += ar;
    }
    if (!(atot > 0))
        return 0;
    /* the largest eigenvector by power iteration from the column of the
     * largest diagonal entry (the normal tensor is positive semidefinite) */
    int k0 = m[0][0] >= m[1][1] && m[0][0] >= m[2][2] ? 0 : m[1][1] >= m[2][2] ? 1 : 2;
    double nv[3] = {m[0][k0], m[1][k0], m[2][k0]};
    for (int it = 0; it < 100; it++) {
        double w[3];
        for (int p = 0; p < 3; p++)
            w[p] = m[p][0] * nv[0] + m[p][1] * nv[1] + m[p][2] * nv[2];
        double l = sqrt(fm_dot3(w, w));
        if (!(l > 0))
            return 0;
        for (int p = 0; p < 3; p++)
            nv[p] = w[p] / l;
    }
    g[0] = -nv[2] * nv[0];
    g[1] = -nv[2] * nv[1];
    g[2] = 1 - nv[2] * nv[2];
    double gl = sqrt(fm_dot3(g, g));
    if (gl < 0.02) {
        double sxx = cxy[0] / atot - mc[0] * mc[0] / atot / atot,
               sxy = cxy[1] / atot - mc[0] * mc[1] / atot / atot,
               syy = cxy[2] / atot - mc[1] * mc[1] / atot / atot;
        double th = 0.5 * atan2(2 * sxy, sxx - syy);
        g[0] = -sin(th);
        g[1] = cos(th);
        g[2] = 0;
    } else {
        for (int p = 0; p < 3; p++)
            g[p] /= gl;
    }
    return level_rate(tl, tris, n, g) > level_rate(tl, tris, n, z);
}

static int tile_fault(tiler *tl, int32_t f, const size_t *tris, size_t n)
{
    const double *x = tl->x;
    const int32_t *tri = tl->tri;
    memcpy(tl->out->up[f], tl->up, sizeof tl->up);
    double zlo = INFINITY, zhi = -INFINITY;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            double z = tile_level(tl->up, x + 3 * (size_t)tri[3 * tris[i] + (size_t)k]);
            zlo = fmin(zlo, z);
            zhi = fmax(zhi, z);
        }
    if (!(zhi - zlo > 1e-9 * fmax(1, fabs(zhi))))
        return 0; /* no level range: counted by the caller */
    /* area and area x the level's rate along the surface (sin(dip) for
     * depth) per level band, a triangle shared among the bands it spans
     * by the share of its level range in each */
    double area[NBINS] = {0}, asin[NBINS] = {0}, dd[NBINS + 1];
    double dz = (zhi - zlo) / NBINS, atot = 0, stot = 0;
    for (size_t i = 0; i < n; i++) {
        size_t t = tris[i];
        const double *a = x + 3 * (size_t)tri[3 * t], *b = x + 3 * (size_t)tri[3 * t + 1],
                     *c = x + 3 * (size_t)tri[3 * t + 2];
        double ar = fm_triangle_area(a, b, c), nrm[3];
        tri_normal(x, tri, t, nrm);
        double cu = fm_dot3(nrm, tl->up);
        double sn = tl->up[0] == 0 && tl->up[1] == 0 ? hypot(nrm[0], nrm[1])
                                                     : sqrt(fmax(0, 1 - cu * cu));
        double la = tile_level(tl->up, a), lb = tile_level(tl->up, b), lc = tile_level(tl->up, c);
        double z0 = fmin(la, fmin(lb, lc)), z1 = fmax(la, fmax(lb, lc));
        atot += ar;
        stot += ar * sn;
        long b0 = (long)((z0 - zlo) / dz), b1 = (long)((z1 - zlo) / dz);
        b0 = b0 < 0 ? 0 : b0 >= NBINS ? NBINS - 1 : b0;
        b1 = b1 < 0 ? 0 : b1 >= NBINS ? NBINS - 1 : b1;
        for (long k = b0; k <= b1; k++) {
            double lo = fmax(z0, zlo + (double)k * dz), hi = fmin(z1, zlo + (double)(k + 1) * dz);
            double share = z1 > z0 ? fmax(0, hi - lo) / (z1 - z0) : 1.0 / (double)(b1 - b0 + 1);
            area[k] += ar * share;
            asin[k] += ar * sn * share;
        }
    }
    double sall = atot > 0 ? stot / atot : 1;
    dd[0] = 0;
    for (int k = 0; k < NBINS; k++) {
        double s = area[k] > 0 ? asin[k] / area[k] : sall;
        dd[k + 1] = dd[k] + dz / fmax(s, TILE_MIN_SIN);
    }
    double dtot = dd[NBINS];
    long nrows = lround(dtot / tl->size) + tl->extra_rows;
    /* rows other than the closest count stay within 1.5 times the size of
     * it either way */
    if (nrows < 1 || (tl->extra_rows && !(dtot / (double)nrows <= 1.5 * tl->size &&
                                          dtot / (double)nrows >= tl->size / 1.5)))
        return 0;
    tl->rowdw = dtot / (double)nrows;
    for (long r = 0; r < nrows; r++) {
        double ztop = r == 0 ? zhi : depth_at(dd, zlo, dz, dtot * (double)(nrows - r) / (double)nrows);
        double zbot = r == nrows - 1 ? zlo
                                     : depth_at(dd, zlo, dz, dtot * (double)(nrows - r - 1) /
                                                                 (double)nrows);
        /* the middle level, then a quarter from the top and from the bottom
         * for what the first leaves out */
        size_t first = tl->out->n;
        for (int q = 0; q < 3; q++) {
            double level = q == 0 ? (ztop + zbot) / 2
                           : q == 1 ? ztop - (ztop - zbot) / 4
                                    : zbot + (ztop - zbot) / 4;
            /* no vertex exactly at the level, so that every crossing is on
             * a side between a vertex above and one below */
            for (int again = 1; again;) {
                again = 0;
                for (size_t i = 0; i < n && !again; i++)
                    for (int k = 0; k < 3; k++)
                        if (tile_level(tl->up, x + 3 * (size_t)tri[3 * tris[i] + (size_t)k]) ==
                            level) {
                            level = nextafter(level, -INFINITY);
                            again = 1;
                            break;
                        }
            }
            if (tile_row(tl, f, tris, n, (int32_t)r, level, ztop, zbot, q ? first + 1 : 0))
                return -1;
        }
    }
    return 0;
}

/* How far fault f's tiles from first on are from what it should get: the
 * share of its area (triangles' area atri) they miss or add, and the share
 * of them the surface departs from by more than a twentieth of the size. */
static double tiling_cost(fm_tiles *t, tile_walk *w, size_t first, double atri)
{
    double area = 0, rough = 0;
    for (size_t i = first; i < t->n; i++) {
        area += t->tile[i].length * t->tile[i].width;
        rough += tile_flat_as_is(w, &t->tile[i]) > t->stats.size / 20;
    }
    return fabs(area / atri - 1) + (t->n > first ? rough / (double)(t->n - first) : 0);
}

/* Fault f tiled in rows by depth and, where it is worth trying
 * (fault_up), by levels up its mean plane's dip; each with the row count
 * closest to the size and up to two rows fewer and more while the rows
 * stay within 1.5 times the size of it (a fault whose down-dip extent
 * falls between two counts, or whose rows' ends meet its outline badly,
 * fits another better). The tiling that costs least (tiling_cost) is
 * kept, the first of a tie within a thousandth: depth, the closest count;
 * one within a hundredth ends the search.
 * Depth lays out every steep fault whatever its strike does; where much
 * of a fault is flat (a detachment, a low-dip thrust, a ramp running into
 * a flat) a few metres of depth are kilometres down dip and a depth band
 * holds pieces of it far apart. But a plane's levels run across the
 * strike where a flat fault's strike turns (a corrugated detachment), so
 * neither is right everywhere. -1 when memory runs out. */
static int tile_fault_best(tiler *tl, tile_walk *w, int32_t f, const size_t *tris, size_t n)
{
    fm_tiles *t = tl->out;
    const double z[3] = {0, 0, 1};
    static const int extra[5] = {0, -1, 1, -2, 2};
    double g[3], atri = 0, best = INFINITY, bup[3];
    size_t first = t->n, nb = 0, cap = 0;
    int ndir = tl->depth_only ? 1 : 1 + fault_up(tl, tris, n, g);
    for (size_t i = 0; i < n; i++)
        atri += fm_triangle_area(tl->x + 3 * (size_t)tl->tri[3 * tris[i]],
                                 tl->x + 3 * (size_t)tl->tri[3 * tris[i] + 1],
                                 tl->x + 3 * (size_t)tl->tri[3 * tris[i] + 2]);
    fm_tile *keep = NULL;
    double(*kb)[4] = NULL;
    int bad = 0;
    memcpy(bup, z, sizeof z);
    /* a tiling within a hundredth (its area within 1 %, hardly a tile
     * rough) is good enough: the others are not tried, which saves most
     * of the time on most faults */
    for (int d = 0; d < ndir && !bad && !(best < 0.01); d++)
        for (int e = 0; e < 5 && !bad && !(best < 0.01); e++) {
            t->n = first;
            memcpy(tl->up, d ? g : z, sizeof tl->up);
            tl->extra_rows = extra[e];
            bad = tile_fault(tl, f, tris, n) || tile_fit_planes(t, w, first);
            if (bad || t->n == first)
                continue;
            /* as made, then with its edge tiles refined (tile_refine_edges),
             * which follows the outline closer but leaves the thin gaps
             * between rows that the widths made up for bare */
            for (int r = 0; r < 2 && !bad && !(best < 0.01); r++) {
                if (r && (bad = tile_refine_edges(t, w, first)) != 0)
                    break;
                double c = atri > 0 ? tiling_cost(t, w, first, atri) : 0;
                /* better by a thousandth, not by rounding */
                if (!(c < best - 1e-3))
                    continue;
                best = c;
                memcpy(bup, tl->up, sizeof bup);
                size_t m = t->n - first;
                if (m > cap) {
                    fm_tile *k2 = realloc(keep, m * sizeof *k2);
                    if (k2)
                        keep = k2;
                    double(*b2)[4] = realloc(kb, m * sizeof *b2);
                    if (b2)
                        kb = b2;
                    bad = !k2 || !b2;
                    cap = bad ? cap : m;
                }
                if (!bad) {
                    memcpy(keep, t->tile + first, m * sizeof *keep);
                    memcpy(kb, t->band + first, m * sizeof *kb);
                    nb = m;
                }
            }
        }
    tl->extra_rows = 0;
    t->n = first;
    if (best == INFINITY && n)
        t->stats.unrowed++;
    memcpy(t->up[f], bup, sizeof bup);
    for (size_t i = 0; !bad && best < INFINITY && i < nb; i++)
        bad = tile_push(t, keep + i, kb[i][0], kb[i][1], kb[i][2], (int)kb[i][3]);
    free(keep);
    free(kb);
    return bad ? -1 : 0;
}

static double tiles_area(const fm_tiles *t, size_t first)
{
    double a = 0;
    for (size_t i = first; i < t->n; i++)
        a += t->tile[i].length * t->tile[i].width;
    return a;
}

/* Fault f tiled whole (tile_fault_best) and, where that comes over 3 %
 * from its area (its triangles', atri) and it has several parts, part by
 * part in rows by depth (nbr_part: nbr cut where the part changes), the
 * closer to its area kept (fm_tiles_create_parts); -1 when memory runs
 * out. */
static int tile_fault_parts(tiler *tl, tile_walk *w, int32_t f, const size_t *tris, size_t n,
                            double atri, const int32_t *part, const int32_t *nbr_part)
{
    fm_tiles *t = tl->out;
    size_t first = t->n;
    if (tile_fault_best(tl, w, f, tris, n))
        return -1;
    int several = 0;
    for (size_t i = 1; part && i < n; i++)
        several |= part[tris[i]] != part[tris[0]];
    double whole = several && atri > 0 ? fabs(tiles_area(t, first) / atri - 1) : 0;
    if (!(whole > 0.03))
        return 0;
    size_t m = t->n - first, unrowed = t->stats.unrowed;
    fm_tile *keep = malloc((m + 1) * sizeof *keep);
    double(*kb)[4] = malloc((m + 1) * sizeof *kb), up[3];
    fm_keyed *by = malloc((n + 1) * sizeof *by);
    size_t *run = malloc((n + 1) * sizeof *run);
    int bad = !keep || !kb || !by || !run;
    if (!bad) {
        memcpy(keep, t->tile + first, m * sizeof *keep);
        memcpy(kb, t->band + first, m * sizeof *kb);
        memcpy(up, t->up[f], sizeof up);
        /* the triangles part by part, each part's in their order */
        for (size_t i = 0; i < n; i++)
            by[i] = (fm_keyed){(uint64_t)(uint32_t)part[tris[i]] << 32 | (uint64_t)i, tris[i]};
        bad = fm_sort_keyed(by, n);
    }
    const int32_t *nbr0 = tl->nbr, *wnbr0 = w->nbr;
    tl->nbr = w->nbr = nbr_part;
    tl->depth_only = 1;
    t->n = first;
    for (size_t i = 0; !bad && i < n;) {
        size_t j = i;
        while (j < n && by[j].key >> 32 == by[i].key >> 32)
            j++;
        for (size_t k = i; k < j; k++)
            run[k - i] = by[k].index;
        size_t s0 = t->n;
        bad = tile_fault_best(tl, w, f, run, j - i) != 0;
        for (size_t k = s0; k < t->n; k++)
            t->tile[k].part = (int32_t)(by[i].key >> 32) + 1;
        i = j;
    }
    tl->nbr = nbr0;
    w->nbr = wnbr0;
    tl->depth_only = 0;
    if (!bad && !(fabs(tiles_area(t, first) / atri - 1) < whole - 1e-3)) {
        /* the whole tiling stays */
        t->n = first;
        t->stats.unrowed = unrowed;
        memcpy(t->up[f], up, sizeof up);
        for (size_t i = 0; !bad && i < m; i++)
            bad = tile_push(t, keep + i, kb[i][0], kb[i][1], kb[i][2], (int)kb[i][3]);
    }
    free(keep);
    free(kb);
    free(by);
    free(run);
    return bad ? -1 : 0;
}

/* One thread's means to tile a fault: its own scratch (stamps per
 * triangle, contour buffers) and an fm_tiles of its own that the fault's
 * tiles go to, sharing the set's per-fault row directions (each fault
 * writes only its own). */
typedef struct tile_scratch {
    tiler tl;
    tile_walk w;
    fm_tiles out;
} tile_scratch;

typedef struct fault_tiling {
    fm_tile *tile;
    double (*band)[4];
    size_t n, unrowed;
} fault_tiling;

typedef struct tile_par {
    tile_scratch *sc;
    int *idle;
    int nidle;
    pthread_mutex_t mu;
    const size_t *order, *start;
    const int32_t *part, *nbr_part;
    const fm_tile_fault *fault; /* per fault: its triangles' area */
    fault_tiling *res;          /* per fault */
    int bad;
} tile_par;

/* Fault f tiled on whichever scratch is idle; what it gets does not depend
 * on which, nor on the other faults. */
static void tile_one_fault(void *user, size_t f)
{
    tile_par *p = user;
    pthread_mutex_lock(&p->mu);
    int k = p->idle[--p->nidle], bad = p->bad;
    pthread_mutex_unlock(&p->mu);
    tile_scratch *s = &p->sc[k];
    if (!bad) {
        s->out.n = 0;
        s->out.stats.unrowed = 0;
        bad = tile_fault_parts(&s->tl, &s->w, (int32_t)f, p->order + p->start[f],
                               p->start[f + 1] - p->start[f], p->fault[f].area_triangles,
                               p->part, p->nbr_part) != 0;
        fault_tiling *r = &p->res[f];
        r->n = s->out.n;
        r->unrowed = s->out.stats.unrowed;
        if (!bad && r->n) {
            r->tile = malloc(r->n * sizeof *r->tile);
            r->band = malloc(r->n * sizeof *r->band);
            bad = !r->tile || !r->band;
            if (!bad) {
                memcpy(r->tile, s->out.tile, r->n * sizeof *r->tile);
                memcpy(r->band, s->out.band, r->n * sizeof *r->band);
            }
        }
    }
    pthread_mutex_lock(&p->mu);
    p->idle[p->nidle++] = k;
    p->bad |= bad;
    pthread_mutex_unlock(&p->mu);
}

/* Every fault tiled (tile_fault_parts) on up to jobs threads, the tiles
 * then taken in fault order; -1 when memory runs out. */
static int tile_faults(fm_tiles *t, const tiler *proto, const tile_walk *wproto, size_t nt,
                       const size_t *order, const size_t *start, const int32_t *part,
                       const int32_t *nbr_part, int jobs)
{
    int ns = jobs > 1 ? jobs : 1;
    if ((size_t)ns > t->nfaults)
        ns = t->nfaults > 0 ? (int)t->nfaults : 1;
    tile_par p = {.sc = calloc((size_t)ns, sizeof *p.sc), .idle = malloc((size_t)ns * sizeof(int)),
                  .order = order, .start = start, .part = part, .nbr_part = nbr_part,
                  .fault = t->fault,
                  .res = calloc(t->nfaults + 1, sizeof *p.res)};
    int bad = !p.sc || !p.idle || !p.res;
    for (int k = 0; !bad && k < ns; k++) {
        tile_scratch *s = &p.sc[k];
        s->tl = (tiler){.x = proto->x, .tri = proto->tri, .nbr = proto->nbr,
                        .stamp = calloc(nt + 1, sizeof(int32_t)), .size = proto->size,
                        .out = &s->out};
        s->w = *wproto;
        s->w.stamp = calloc(nt + 1, sizeof(uint32_t));
        s->w.list = malloc((nt + 1) * sizeof(int32_t));
        s->out.nfaults = t->nfaults;
        s->out.up = t->up;
        s->out.stats.size = t->stats.size;
        bad = !s->tl.stamp || !s->w.stamp || !s->w.list;
        p.idle[p.nidle++] = k;
    }
    if (!bad) {
        pthread_mutex_init(&p.mu, NULL);
        fm_parallel_for(t->nfaults, ns, tile_one_fault, &p, NULL, NULL, 0, t->nfaults);
        pthread_mutex_destroy(&p.mu);
        bad = p.bad;
    }
    for (size_t f = 0; p.res && f < t->nfaults; f++) {
        fault_tiling *r = &p.res[f];
        t->stats.unrowed += r->unrowed;
        for (size_t i = 0; !bad && i < r->n; i++)
            bad = tile_push(t, &r->tile[i], r->band[i][0], r->band[i][1], r->band[i][2],
                            (int)r->band[i][3]);
        free(r->tile);
        free(r->band);
    }
    for (int k = 0; p.sc && k < ns; k++) {
        tile_scratch *s = &p.sc[k];
        free(s->tl.stamp);
        free(s->tl.pt);
        free(s->tl.seg);
        free(s->tl.s);
        free(s->w.stamp);
        free(s->w.list);
        free(s->out.tile);
        free(s->out.band);
    }
    free(p.sc);
    free(p.idle);
    free(p.res);
    return bad ? -1 : 0;
}

/* Neighbours across sides within a fault, and which sides are junctions. */
static int make_sides(const fm_mesh *set, tile_sides *sd, int32_t *nbr)
{
    const int32_t *tri = fm_mesh_triangles(set), *tag = fm_mesh_tags(set);
    size_t nt = fm_mesh_ntriangles(set);
    sd->side = fm_mesh_sides(set, &sd->n);
    sd->junction = sd->side ? calloc(sd->n + 1, 1) : NULL;
    if (!sd->side || !sd->junction)
        return -1;
    for (size_t i = 0; i < 3 * nt; i++)
        nbr[i] = -1;
    for (size_t i = 0; i < sd->n;) {
        size_t j = i + 1;
        int junction = 0;
        while (j < sd->n && sd->side[j].key == sd->side[i].key) {
            junction |= tag[sd->side[j].index] != tag[sd->side[i].index];
            j++;
        }
        for (size_t k = i; k < j; k++)
            sd->junction[k] = (unsigned char)junction;
        if (!junction && j - i == 2) {
            size_t t0 = sd->side[i].index, t1 = sd->side[i + 1].index;
            int32_t u = (int32_t)(sd->side[i].key >> 32), v = (int32_t)(sd->side[i].key & 0xffffffffu);
            for (int pass = 0; pass < 2; pass++) {
                size_t t = pass ? t1 : t0, o = pass ? t0 : t1;
                int k = fm_triangle_side(tri + 3 * t, u, v);
                if (k >= 0)
                    nbr[3 * t + (size_t)k] = (int32_t)o;
            }
        }
        i = j;
    }
    return 0;
}

fm_status fm_tiles_create(const fm_mesh *set, size_t nfaults, double size, fm_tiles **out,
                          fm_error *err)
{
    return fm_tiles_create_parts(set, NULL, nfaults, size, 1, out, err);
}

fm_status fm_tiles_create_parts(const fm_mesh *set, const int32_t *part, size_t nfaults,
                                double size, int jobs, fm_tiles **out, fm_error *err)
{
    *out = NULL;
    if (!(size > 0) || !isfinite(size))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "tile size must be positive");
    size_t nt = fm_mesh_ntriangles(set);
    const int32_t *tag = fm_mesh_tags(set);
    for (size_t t = 0; t < nt; t++)
        if (tag[t] < 0 || (size_t)tag[t] >= nfaults)
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                "triangle %zu has fault %d, not one of 0..%zu", t, (int)tag[t],
                                nfaults ? nfaults - 1 : 0);
    fm_tiles *t = calloc(1, sizeof *t);
    int32_t *nbr = malloc((3 * nt + 1) * sizeof *nbr);
    size_t *start = calloc(nfaults + 2, sizeof *start), *order = malloc((nt + 1) * sizeof *order);
    tile_sides sd = {0};
    /* what every fault's tiler shares (tile_faults) */
    tiler tl = {.x = fm_mesh_vertices(set), .tri = fm_mesh_triangles(set), .nbr = nbr,
                .size = size, .out = t};
    int bad = !t || !nbr || !start || !order;
    if (!bad) {
        t->nfaults = nfaults;
        t->fault = calloc(nfaults + 1, sizeof *t->fault);
        t->left_out = calloc(nfaults + 1, sizeof *t->left_out);
        t->up = calloc(nfaults + 1, sizeof *t->up);
        t->stats.size = size;
        bad = !t->fault || !t->left_out || !t->up || make_sides(set, &sd, nbr);
        for (size_t f = 0; !bad && f < nfaults; f++)
            t->up[f][2] = 1;
    }
    if (!bad) {
        for (size_t i = 0; i < nt; i++)
            start[tag[i] + 1]++;
        for (size_t f = 0; f < nfaults; f++)
            start[f + 1] += start[f];
    }
    /* each fault's triangles, in order, and their area */
    if (!bad) {
        size_t *pos = malloc((nfaults + 1) * sizeof *pos);
        bad = !pos;
        if (pos) {
            memcpy(pos, start, nfaults * sizeof *pos);
            for (size_t i = 0; i < nt; i++)
                order[pos[tag[i]]++] = i;
            free(pos);
        }
        const double *x = tl.x;
        for (size_t i = 0; i < nt; i++)
            t->fault[tag[i]].area_triangles +=
                fm_triangle_area(x + 3 * (size_t)tl.tri[3 * i], x + 3 * (size_t)tl.tri[3 * i + 1],
                                 x + 3 * (size_t)tl.tri[3 * i + 2]);
    }
    tile_walk w = {.x = tl.x, .up = t ? (const double(*)[3])t->up : NULL, .tri = tl.tri,
                   .nbr = nbr, .stamp = calloc(nt + 1, sizeof(uint32_t)),
                   .list = malloc((nt + 1) * sizeof(int32_t))};
    bad = bad || !w.stamp || !w.list;
    /* the sides across which the part changes cut too */
    int32_t *nbr_part = part && !bad ? malloc((3 * nt + 1) * sizeof *nbr_part) : NULL;
    bad = bad || (part && !nbr_part);
    for (size_t i = 0; nbr_part && i < 3 * nt; i++)
        nbr_part[i] = nbr[i] >= 0 && part[nbr[i]] == part[i / 3] ? nbr[i] : -1;
    if (!bad)
        bad = tile_faults(t, &tl, &w, nt, order, start, part, nbr_part, jobs);
    free(nbr_part);
    if (!bad)
        bad = tile_fill_junctions(t, set, &sd) || tile_settle(t, set, &w, order, start) ||
              tile_measure(t, set, &sd, &w);
    free(w.stamp);
    free(w.list);
    if (t) {
        free(t->band);
        t->band = NULL;
    }
    free(nbr);
    free(start);
    free(order);
    free(sd.side);
    free(sd.junction);
    if (bad) {
        fm_tiles_destroy(t);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    *out = t;
    return FM_OK;
}

void fm_tiles_destroy(fm_tiles *t)
{
    if (!t)
        return;
    free(t->tile);
    free(t->fault);
    free(t->left_out);
    free(t->up);
    free(t->junction);
    free(t);
}

size_t fm_tiles_count(const fm_tiles *t) { return t->n; }
const fm_tile *fm_tiles_get(const fm_tiles *t, size_t i) { return &t->tile[i]; }
size_t fm_tiles_nfaults(const fm_tiles *t) { return t->nfaults; }
const fm_tile_fault *fm_tiles_fault(const fm_tiles *t, size_t f) { return &t->fault[f]; }
size_t fm_tiles_njunctions(const fm_tiles *t) { return t->njunctions; }
const fm_tile_junction *fm_tiles_junction(const fm_tiles *t, size_t i) { return &t->junction[i]; }
const fm_tile_stats *fm_tiles_stats(const fm_tiles *t) { return &t->stats; }

void fm_tile_corners(const fm_tile *t, double c[4][3])
{
    static const double su[4] = {-0.5, -0.5, 0.5, 0.5}, sv[4] = {-0.5, 0.5, 0.5, -0.5};
    for (int k = 0; k < 4; k++)
        for (int d = 0; d < 3; d++)
            c[k][d] = t->centre[d] + su[k] * t->length * t->strike[d] +
                      sv[k] * t->width * t->dip[d];
}
