/* Rectangular elements: the surface each tile stands for, and its plane
 * fitted to it (tile_internal.h). The strike stays horizontal, as a
 * rectangle given by strike and dip has it, so the fit is a line across
 * the strike: the principal axis of the surface's samples seen along the
 * strike. The contour's normals at the row's middle depth, which a tile
 * starts with, miss a row whose dip changes and give a width that does
 * not match it; and the surface may fill only part of the row's depth at
 * a tile (a top or bottom edge that climbs along strike), so the tile
 * spans the depths its surface does. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tile_internal.h"

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Whether triangle t reaches into the tile's columns between zlo and zhi. */
static int reaches(const tile_walk *w, size_t t, const fm_tile *tl, double zlo, double zhi)
{
    double ulo = INFINITY, uhi = -INFINITY, z0 = INFINITY, z1 = -INFINITY;
    for (int k = 0; k < 3; k++) {
        const double *p = w->x + 3 * (size_t)w->tri[3 * t + (size_t)k];
        double u = (p[0] - tl->centre[0]) * tl->strike[0] + (p[1] - tl->centre[1]) * tl->strike[1] +
                   (p[2] - tl->centre[2]) * tl->strike[2];
        ulo = fmin(ulo, u);
        uhi = fmax(uhi, u);
        z0 = fmin(z0, p[2]);
        z1 = fmax(z1, p[2]);
    }
    return uhi >= -tl->length / 2 && ulo <= tl->length / 2 && z1 >= zlo && z0 <= zhi;
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

/* The plane and depth span of tile tl (row ztop..zbot, dw wide down dip at
 * the fault's mean dip) from the surface w found for it. */
static void refit(fm_tile *tl, const tile_walk *w, double ztop, double zbot, double dw)
{
    static const double bw[7][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {2.0 / 3, 1.0 / 6, 1.0 / 6},
                                    {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3},
                                    {1.0 / 6, 5.0 / 12, 5.0 / 12}, {5.0 / 12, 1.0 / 6, 5.0 / 12},
                                    {5.0 / 12, 5.0 / 12, 1.0 / 6}};
    double rh[3] = {tl->strike[1], -tl->strike[0], 0};
    double n = 0, sa = 0, sb = 0, saa = 0, sab = 0, sbb = 0, zlo = INFINITY, zhi = -INFINITY;
    for (size_t i = 0; i < w->n; i++) {
        const double *c[3];
        for (int k = 0; k < 3; k++)
            c[k] = w->x + 3 * (size_t)w->tri[3 * (size_t)w->list[i] + (size_t)k];
        zlo = fmin(zlo, fmin(c[0][2], fmin(c[1][2], c[2][2])));
        zhi = fmax(zhi, fmax(c[0][2], fmax(c[1][2], c[2][2])));
        for (int k = 0; k < 7; k++) {
            double p[3];
            for (int d = 0; d < 3; d++)
                p[d] = bw[k][0] * c[0][d] + bw[k][1] * c[1][d] + bw[k][2] * c[2][d] -
                       tl->centre[d];
            if (p[2] + tl->centre[2] > ztop || p[2] + tl->centre[2] < zbot ||
                fabs(dot3(p, tl->strike)) > tl->length / 2)
                continue;
            double a = dot3(p, rh), b = p[2];
            n += 1;
            sa += a;
            sb += b;
            saa += a * a;
            sab += a * b;
            sbb += b * b;
        }
    }
    double sdmin = tile_min_sin(ztop - zbot, dw);
    double zc = tl->centre[2];
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
    double st[3] = {tl->strike[0], tl->strike[1], 0}, dip[3];
    double q[3] = {tl->centre[0], tl->centre[1], tl->centre[2]};
    /* samples all at one depth say nothing of the dip: the plane stays */
    if (n >= 3 && cbb > dz * dz / 400) {
        double phi = 0.5 * atan2(2 * cab, caa - cbb);
        /* the normal is across the principal axis (cos phi, sin phi) */
        double nr[3] = {-sin(phi) * rh[0], -sin(phi) * rh[1], cos(phi)};
        if (nr[2] < 0)
            for (int d = 0; d < 3; d++)
                nr[d] = -nr[d];
        if (nr[0] * rh[0] + nr[1] * rh[1] < 0) { /* dipping left now */
            st[0] = -st[0];
            st[1] = -st[1];
        }
        if (fabs(nr[2]) < 1e-12) {
            double az = atan2(st[0], st[1]);
            if (az < 0 || az >= 3.14159265358979323846) {
                st[0] = -st[0];
                st[1] = -st[1];
                nr[0] = -nr[0];
                nr[1] = -nr[1];
            }
        }
        dip[0] = st[1] * nr[2] - st[2] * nr[1];
        dip[1] = st[2] * nr[0] - st[0] * nr[2];
        dip[2] = st[0] * nr[1] - st[1] * nr[0];
        /* through the samples' centroid */
        for (int d = 0; d < 3; d++)
            q[d] += ma * rh[d];
        q[2] += mb;
    } else {
        memcpy(dip, tl->dip, sizeof dip);
    }
    double sd = fmax(-dip[2], sdmin);
    /* along the dip to the middle of the depth span */
    double level = (ztop + zbot) / 2, s = dip[2] < -1e-12 ? (level - q[2]) / dip[2] : 0;
    for (int d = 0; d < 3; d++)
        tl->centre[d] = q[d] + s * dip[d];
    tl->centre[2] = level;
    (void)zc;
    memcpy(tl->strike, st, sizeof st);
    memcpy(tl->dip, dip, sizeof dip);
    tl->width = dz / sd;
}

int tile_fit_planes(fm_tiles *t, tile_walk *w)
{
    for (size_t i = 0; i < t->n; i++) {
        tile_region(w, &t->tile[i], t->band[i][1], t->band[i][0]);
        refit(&t->tile[i], w, t->band[i][0], t->band[i][1], t->band[i][2]);
    }
    return 0;
}
