/* Rectangular elements: the surface each tile stands for, and its plane
 * fitted to it (tile_internal.h). The strike stays horizontal, as a
 * rectangle given by strike and dip has it, so the fit is a line across
 * the strike: the principal axis of the surface's samples seen along the
 * strike. The contour's normals at the row's middle level, which a tile
 * starts with, miss a row whose dip changes and give a width that does
 * not match it; and the surface may fill only part of the row's levels
 * at a tile (a top or bottom edge that climbs along strike), so the tile
 * spans the levels its surface does. Levels are depth or, on a fault
 * whose rows follow its mean plane, distance up that plane's dip
 * (tile_level). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tile_internal.h"
#include "fm_vec3.h"

/* Whether triangle t reaches into the tile's columns between zlo and zhi,
 * near its plane: within half the tile's larger side, so that the surface
 * past a bend, which may come back under the tile, is not taken for it. */
static int reaches(const tile_walk *w, size_t t, const fm_tile *tl, double zlo, double zhi)
{
    double ulo = INFINITY, uhi = -INFINITY, z0 = INFINITY, z1 = -INFINITY, wmin = INFINITY;
    double n[3];
    const double *up = w->up[tl->fault];
    tile_normal(tl, n);
    for (int k = 0; k < 3; k++) {
        const double *p = w->x + 3 * (size_t)w->tri[3 * t + (size_t)k];
        double r[3] = {p[0] - tl->centre[0], p[1] - tl->centre[1], p[2] - tl->centre[2]};
        double u = fm_dot3(r, tl->strike);
        ulo = fmin(ulo, u);
        uhi = fmax(uhi, u);
        double z = tile_level(up, p);
        z0 = fmin(z0, z);
        z1 = fmax(z1, z);
        wmin = fmin(wmin, fabs(fm_dot3(r, n)));
    }
    return (uhi >= -tl->length / 2 || (w->open & 1)) && (ulo <= tl->length / 2 || (w->open & 2)) &&
           z1 >= zlo && z0 <= zhi &&
           wmin <= fmax(tl->length, tl->width) / 2;
}

void tile_region(tile_walk *w, const fm_tile *tl, double zlo, double zhi)
{
    w->n = 0;
    if (++w->cur == 0) { /* wrapped: start the stamps again */
        w->cur = 1;
    }
    size_t t0 = (size_t)tl->triangle;
    w->stamp[t0] = w->cur;
    w->list[w->n++] = (int32_t)t0;
    for (size_t head = 0; head < w->n; head++) {
        size_t t = (size_t)w->list[head];
        for (int k = 0; k < 3; k++) {
            int32_t o = w->nbr[3 * t + (size_t)k];
            if (o < 0 || w->stamp[o] == w->cur)
                continue;
            w->stamp[o] = w->cur;
            if (reaches(w, (size_t)o, tl, zlo, zhi))
                w->list[w->n++] = o;
        }
    }
}

/* The part of triangle c between u = -L/2 and L/2 along strike st (from
 * centre o) and between levels zbot and ztop along up: its area, and its
 * area times its centroid added to m[3]. */
static double clipped(const double *const c[3], const double *o, const double *st, double L,
                      int open, const double *up, double zbot, double ztop, double m[3])
{
    double poly[2][12][3];
    int n = 3, cur = 0;
    for (int k = 0; k < 3; k++)
        memcpy(poly[0][k], c[k], sizeof poly[0][k]);
    for (int plane = 0; plane < 4 && n > 0; plane++) {
        if ((plane == 0 && (open & 1)) || (plane == 1 && (open & 2)))
            continue;
        int m2 = 0;
        double f[12];
        for (int k = 0; k < n; k++) {
            const double *p = poly[cur][k];
            double u = (p[0] - o[0]) * st[0] + (p[1] - o[1]) * st[1] + (p[2] - o[2]) * st[2];
            f[k] = plane == 0   ? u + L / 2
                   : plane == 1 ? L / 2 - u
                   : plane == 2 ? tile_level(up, p) - zbot
                                : ztop - tile_level(up, p);
        }
        for (int k = 0; k < n; k++) {
            int j = (k + 1) % n;
            const double *a = poly[cur][k], *b = poly[cur][j];
            if (f[k] >= 0 && m2 < 12)
                memcpy(poly[1 - cur][m2++], a, 3 * sizeof *a);
            if ((f[k] >= 0) != (f[j] >= 0) && m2 < 12) {
                double t = f[k] / (f[k] - f[j]);
                for (int d = 0; d < 3; d++)
                    poly[1 - cur][m2][d] = a[d] + t * (b[d] - a[d]);
                m2++;
            }
        }
        n = m2;
        cur = 1 - cur;
    }
    double area = 0;
    for (int k = 1; k + 1 < n; k++) {
        const double *a = poly[cur][0], *b = poly[cur][k], *d = poly[cur][k + 1];
        double ar = fm_triangle_area(a, b, d);
        area += ar;
        for (int q = 0; q < 3; q++)
            m[q] += ar * (a[q] + b[q] + d[q]) / 3;
    }
    return area;
}

/* The plane and level span of tile tl (row ztop..zbot, dw wide down dip at
 * the fault's mean dip) from the surface w found for it. */
static void refit(fm_tile *tl, const tile_walk *w, double ztop, double zbot, double dw)
{
    static const double bw[7][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {2.0 / 3, 1.0 / 6, 1.0 / 6},
                                    {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3},
                                    {1.0 / 6, 5.0 / 12, 5.0 / 12}, {5.0 / 12, 1.0 / 6, 5.0 / 12},
                                    {5.0 / 12, 5.0 / 12, 1.0 / 6}};
    const double *up = w->up[tl->fault];
    double rh[3] = {tl->strike[1], -tl->strike[0], 0};
    double n = 0, sa = 0, sb = 0, saa = 0, sab = 0, sbb = 0, zlo = INFINITY, zhi = -INFINITY;
    for (size_t i = 0; i < w->n; i++) {
        const double *c[3];
        for (int k = 0; k < 3; k++)
            c[k] = w->x + 3 * (size_t)w->tri[3 * (size_t)w->list[i] + (size_t)k];
        double l0 = tile_level(up, c[0]), l1 = tile_level(up, c[1]), l2 = tile_level(up, c[2]);
        zlo = fmin(zlo, fmin(l0, fmin(l1, l2)));
        zhi = fmax(zhi, fmax(l0, fmax(l1, l2)));
        for (int k = 0; k < 7; k++) {
            double p[3], pa[3];
            for (int d = 0; d < 3; d++) {
                pa[d] = bw[k][0] * c[0][d] + bw[k][1] * c[1][d] + bw[k][2] * c[2][d];
                p[d] = pa[d] - tl->centre[d];
            }
            double lv = tile_level(up, pa);
            if (lv > ztop || lv < zbot ||
                fabs(fm_dot3(p, tl->strike)) > tl->length / 2)
                continue;
            double a = fm_dot3(p, rh), b = p[2];
            n += 1;
            sa += a;
            sb += b;
            saa += a * a;
            sab += a * b;
            sbb += b * b;
        }
    }
    double sdmin = tile_min_sin(ztop - zbot, dw);
    if (w->n) {
        ztop = fmin(ztop, zhi);
        zbot = fmax(zbot, zlo);
    }
    double dz = ztop - zbot;
    if (!(dz > 0))
        return;
    double ma = n > 0 ? sa / n : 0, mb = n > 0 ? sb / n : 0;
    double caa = n > 0 ? saa / n - ma * ma : 0, cab = n > 0 ? sab / n - ma * mb : 0,
           cbb = n > 0 ? sbb / n - mb * mb : 0;
    /* the samples' spread in level (seen along the strike) */
    double ga = fm_dot3(up, rh), gb = up[2];
    double cll = ga * ga * caa + 2 * ga * gb * cab + gb * gb * cbb;
    double st[3] = {tl->strike[0], tl->strike[1], 0}, dip[3];
    double q[3] = {tl->centre[0], tl->centre[1], tl->centre[2]};
    /* samples all at one level say nothing of the dip: the plane stays */
    if (n >= 3 && cll > dz * dz / 400) {
        double phi = 0.5 * atan2(2 * cab, caa - cbb);
        /* the normal is across the principal axis (cos phi, sin phi) */
        double nr[3] = {-sin(phi) * rh[0], -sin(phi) * rh[1], cos(phi)};
        tile_frame(st, nr, dip);
        /* through the samples' centroid */
        for (int d = 0; d < 3; d++)
            q[d] += ma * rh[d];
        q[2] += mb;
    } else {
        memcpy(dip, tl->dip, sizeof dip);
    }
    double sd = fmax(fabs(fm_dot3(dip, up)), sdmin);
    /* The tile's width makes its area the surface's within its columns and
     * depth span, and it is centred on that surface's centroid: a top or
     * bottom edge across the column at a slant (a sea floor, a climbing
     * tip) then costs neither overlap nor loss on average. */
    double area = 0, m[3] = {0, 0, 0};
    for (size_t i = 0; i < w->n; i++) {
        const double *c[3];
        for (int k = 0; k < 3; k++)
            c[k] = w->x + 3 * (size_t)w->tri[3 * (size_t)w->list[i] + (size_t)k];
        /* the refit may have turned the strike round: the open ends too */
        int open = w->open;
        if (st[0] * tl->strike[0] + st[1] * tl->strike[1] < 0)
            open = (open & 1) << 1 | (open & 2) >> 1;
        area += clipped(c, tl->centre, st, tl->length, open, up, zbot, ztop, m);
    }
    double width = dz / sd, s = 0;
    if (area > 0 && tl->length > 0) {
        /* within the depth span, at the plane's own dip however flat */
        double du = fm_dot3(dip, up), sdt = fabs(du);
        width = fmin(sdt > 1e-9 ? dz / sdt : INFINITY, area / tl->length);
        /* down the plane to the surface's centroid (across the strike
         * only: along it the columns stay where they are) */
        double r[3] = {m[0] / area - q[0], m[1] / area - q[1], m[2] / area - q[2]};
        s = fm_dot3(r, dip);
        /* and the tile inside its depth span where the plane is steep
         * enough for depth to say where it is; on a flatter one (a
         * detachment) a few metres of depth are kilometres down dip, and
         * the centroid, on the surface, is the better guide */
        if (sdt >= TILE_MIN_SIN) {
            double h = width * sdt / 2, z = tile_level(up, q) + s * du;
            double zc = fmin(fmax(z, zbot + h), ztop - h);
            if (zc != z)
                s = (zc - tile_level(up, q)) / du;
        }
    }
    for (int d = 0; d < 3; d++)
        tl->centre[d] = q[d] + s * dip[d];
    memcpy(tl->strike, st, sizeof st);
    memcpy(tl->dip, dip, sizeof dip);
    tl->width = width;
}

double tile_flatness(const tile_walk *w, const fm_tile *tl)
{
    double flat = 0;
    for (size_t k = 0; k < w->n; k++) {
        const double *v[3];
        for (int q = 0; q < 3; q++)
            v[q] = w->x + 3 * (size_t)w->tri[3 * (size_t)w->list[k] + (size_t)q];
        for (int q = 0; q < 7; q++) {
            double p[3];
            for (int d = 0; d < 3; d++)
                p[d] = q < 3   ? v[q][d]
                       : q < 6 ? (v[q - 3][d] + v[(q - 2) % 3][d]) / 2
                               : (v[0][d] + v[1][d] + v[2][d]) / 3;
            double wd;
            int inside;
            tile_distance(tl, p, &wd, &inside);
            if (inside)
                flat = fmax(flat, fabs(wd));
        }
    }
    return flat;
}

/* The level span of a tile as it stands. */
static void span(const tile_walk *w, const fm_tile *tl, double *ztop, double *zbot)
{
    const double *up = w->up[tl->fault];
    double h = fabs(fm_dot3(tl->dip, up)) * tl->width / 2, c = tile_level(up, tl->centre);
    *ztop = c + h;
    *zbot = c - h;
}

double tile_flat_as_is(tile_walk *w, const fm_tile *tl)
{
    double lo, hi;
    span(w, tl, &hi, &lo);
    tile_region(w, tl, lo, hi);
    return tile_flatness(w, tl);
}

/* The flatness of a tile as it stands; its triangle made the one of its
 * surface nearest its centre (a half's centre is not its whole's), and
 * *off how far that triangle's centroid is. */
static double flat_of(tile_walk *w, fm_tile *tl, double *off)
{
    double lo, hi;
    span(w, tl, &hi, &lo);
    tile_region(w, tl, lo, hi);
    double best = INFINITY;
    for (size_t k = 0; k < w->n; k++) {
        double c[3] = {0, 0, 0};
        for (int q = 0; q < 3; q++)
            for (int d = 0; d < 3; d++)
                c[d] += w->x[3 * (size_t)w->tri[3 * (size_t)w->list[k] + (size_t)q] + (size_t)d] / 3;
        double d2 = (c[0] - tl->centre[0]) * (c[0] - tl->centre[0]) +
                    (c[1] - tl->centre[1]) * (c[1] - tl->centre[1]) +
                    (c[2] - tl->centre[2]) * (c[2] - tl->centre[2]);
        if (d2 < best) {
            best = d2;
            tl->triangle = w->list[k];
        }
    }
    *off = sqrt(best);
    return tile_flatness(w, tl);
}

/* A tile made for row band b (ztop, zbot, dw, its columns open at its ends as
 * b[3] says), fitted; its flatness. Where the fit turned the strike round,
 * b's open ends are turned with it, for the halves and the edges
 * (tile_refine_edges) that read them later. */
static double fitted(tile_walk *w, fm_tile *tl, double b[4])
{
    double ztop = b[0], zbot = b[1], dw = b[2];
    int open = (int)b[3];
    fm_tile before = *tl;
    w->open = open;
    tile_region(w, tl, zbot, ztop);
    refit(tl, w, ztop, zbot, dw);
    w->open = 0;
    double off, flat = flat_of(w, tl, &off);
    /* Where the fault is nearly flat, a depth band holds pieces of it
     * scattered far apart, and a plane through them all can stand off
     * the surface (by kilometres on the CFM's detachments): the tile
     * keeps the frame it was made with, centred on its contour. */
    if (off > fmax(before.length, before.width)) {
        *tl = before;
        flat = flat_of(w, tl, &off);
    }
    if (tl->strike[0] * before.strike[0] + tl->strike[1] * before.strike[1] < 0)
        b[3] = (double)((open & 1) << 1 | (open & 2) >> 1);
    return flat;
}

/* Halves of tile tl (of row band b): along strike (dip 0) or down dip. */
static void halves(const tile_walk *w, const fm_tile *tl, const double b[4], int dip, fm_tile h[2],
                   double hb[2][4])
{
    double ztop, zbot;
    span(w, tl, &ztop, &zbot);
    const double *up = w->up[tl->fault];
    double zc = tile_level(up, tl->centre);
    /* the half down dip is the lower one unless the tile dips against up */
    int low = fm_dot3(tl->dip, up) > 0 ? 0 : 1;
    for (int k = 0; k < 2; k++) {
        h[k] = *tl;
        double sg = k ? 0.5 : -0.5;
        if (!dip) {
            h[k].length = tl->length / 2;
            for (int d = 0; d < 3; d++)
                h[k].centre[d] += sg * tl->length / 2 * tl->strike[d];
            hb[k][0] = ztop;
            hb[k][1] = zbot;
        } else {
            h[k].width = tl->width / 2;
            for (int d = 0; d < 3; d++)
                h[k].centre[d] += sg * tl->width / 2 * tl->dip[d];
            hb[k][0] = k == low ? zc : ztop;
            hb[k][1] = k == low ? zbot : zc;
            h[k].row = tl->row + k; /* only the upper half keeps the top edge */
        }
        hb[k][2] = b[2] / (dip ? 2 : 1);
        int open = (int)b[3];
        hb[k][3] = dip ? open : open & (k ? 2 : 1);
    }
}

int tile_fit_planes(fm_tiles *t, tile_walk *w, size_t first)
{
    double tol = t->stats.size / 25, least = t->stats.size / 8;
    for (size_t i = first; i < t->n; i++) {
        if (!t->band) /* after a failed push */
            return -1;
        double flat = fitted(w, &t->tile[i], t->band[i]);
        /* A tile much wider than the size (a surface flatter in its row
         * than the fault's mean dip there says) is halved down dip until it
         * is not; then one the surface departs from too far is split until
         * flat enough or small. The halves join the list. */
        while (t->tile[i].width > 1.5 * t->stats.size) {
            fm_tile h[2];
            double hb[2][4];
            halves(w, &t->tile[i], t->band[i], 1, h, hb);
            fitted(w, &h[1], hb[1]);
            flat = fitted(w, &h[0], hb[0]);
            t->tile[i] = h[0];
            memcpy(t->band[i], hb[0], sizeof hb[0]);
            if (tile_push(t, &h[1], hb[1][0], hb[1][1], hb[1][2], (int)hb[1][3]))
                return -1;
        }
        while (flat > tol) {
            fm_tile best[2];
            double bb[2][4], bf = flat, bf0 = flat;
            int found = 0;
            for (int dip = 0; dip < 2; dip++) {
                const fm_tile *tl = &t->tile[i];
                if ((dip ? tl->width : tl->length) / 2 < least)
                    continue;
                fm_tile h[2];
                double hb[2][4];
                halves(w, tl, t->band[i], dip, h, hb);
                double f0 = fitted(w, &h[0], hb[0]);
                double f1 = fitted(w, &h[1], hb[1]);
                if (fmax(f0, f1) < bf) {
                    bf = fmax(f0, f1);
                    bf0 = f0;
                    memcpy(best, h, sizeof best);
                    memcpy(bb, hb, sizeof bb);
                    found = 1;
                }
            }
            if (!found)
                break;
            t->tile[i] = best[0];
            memcpy(t->band[i], bb[0], sizeof bb[0]);
            if (tile_push(t, &best[1], bb[1][0], bb[1][1], bb[1][2], (int)bb[1][3]))
                return -1;
            flat = bf0; /* the kept half's, as fitted */
        }
        /* A tile still standing off its surface (its centre over 1.5
         * times the size from the nearest centroid of the triangles it
         * stands for: on an undulating detachment neither its row's
         * contour nor a fitted plane found the surface) stands for
         * nothing: given up (tile_separate counts it). */
        double off;
        flat_of(w, &t->tile[i], &off);
        if (off > 1.5 * t->stats.size)
            t->tile[i].length = t->tile[i].width = 0;
    }
    return 0;
}
