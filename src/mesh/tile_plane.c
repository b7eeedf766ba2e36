/* Rectangular elements: each tile's plane fitted to the surface it
 * stands for (tile_internal.h). The strike stays horizontal, as a
 * rectangle of strike and dip has it, so the fit is a line in the plane
 * across the strike: the principal axis of the surface's samples seen
 * along the strike, within the tile's row and columns. The contour's
 * normals at the row's middle depth, which the tile starts with, miss a
 * row whose dip changes, and give a width that does not match it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tile_internal.h"

typedef struct moments {
    double n, a, b, aa, ab, bb;
    double zlo, zhi; /* the depths its surface spans within its row and columns */
    int spans;
} moments;

typedef struct plane_ctx {
    const fm_tiles *t;
    moments *m;
    const int32_t *part;
    const double *p;
    const double *tri[3]; /* add_extent: the triangle */
    int32_t fault, piece;
} plane_ctx;

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static int add_sample(size_t i, void *user)
{
    plane_ctx *c = user;
    const fm_tile *tl = &c->t->tile[i];
    if (tl->fault != c->fault || c->part[tl->triangle] != c->piece)
        return 0;
    const double *zb = c->t->band[i];
    if (c->p[2] > zb[0] || c->p[2] < zb[1])
        return 0;
    double r[3] = {c->p[0] - tl->centre[0], c->p[1] - tl->centre[1], c->p[2] - tl->centre[2]};
    if (fabs(dot3(r, tl->strike)) > tl->length / 2)
        return 0;
    double rh[3] = {tl->strike[1], -tl->strike[0], 0};
    double a = dot3(r, rh), b = r[2];
    /* the surface the tile stands for, not another fold of its piece */
    double n[3] = {tl->dip[1] * tl->strike[2] - tl->dip[2] * tl->strike[1],
                   tl->dip[2] * tl->strike[0] - tl->dip[0] * tl->strike[2],
                   tl->dip[0] * tl->strike[1] - tl->dip[1] * tl->strike[0]};
    if (fabs(dot3(r, n)) > c->t->stats.size)
        return 0;
    moments *m = &c->m[i];
    m->n += 1;
    m->a += a;
    m->b += b;
    m->aa += a * a;
    m->ab += a * b;
    m->bb += b * b;
    return 0;
}

/* The part of the triangle's depth range within the tile's row, when
 * the triangle reaches into the tile's columns. */
static int add_extent(size_t i, void *user)
{
    plane_ctx *c = user;
    const fm_tile *tl = &c->t->tile[i];
    if (tl->fault != c->fault || c->part[tl->triangle] != c->piece)
        return 0;
    const double *zb = c->t->band[i];
    double ulo = INFINITY, uhi = -INFINITY, z0 = INFINITY, z1 = -INFINITY, wmin = INFINITY;
    double n[3] = {tl->dip[1] * tl->strike[2] - tl->dip[2] * tl->strike[1],
                   tl->dip[2] * tl->strike[0] - tl->dip[0] * tl->strike[2],
                   tl->dip[0] * tl->strike[1] - tl->dip[1] * tl->strike[0]};
    for (int k = 0; k < 3; k++) {
        double r[3] = {c->tri[k][0] - tl->centre[0], c->tri[k][1] - tl->centre[1],
                       c->tri[k][2] - tl->centre[2]};
        double u = dot3(r, tl->strike);
        ulo = fmin(ulo, u);
        uhi = fmax(uhi, u);
        z0 = fmin(z0, c->tri[k][2]);
        z1 = fmax(z1, c->tri[k][2]);
        wmin = fmin(wmin, fabs(dot3(r, n)));
    }
    if (uhi < -tl->length / 2 || ulo > tl->length / 2 || z1 < zb[1] || z0 > zb[0] ||
        wmin > c->t->stats.size)
        return 0;
    moments *m = &c->m[i];
    z0 = fmax(z0, zb[1]);
    z1 = fmin(z1, zb[0]);
    m->zlo = m->spans ? fmin(m->zlo, z0) : z0;
    m->zhi = m->spans ? fmax(m->zhi, z1) : z1;
    m->spans = 1;
    return 0;
}

static void refit(fm_tile *tl, const moments *m, double ztop, double zbot, double dw)
{
    if (m->n < 3)
        return;
    double ma = m->a / m->n, mb = m->b / m->n;
    double caa = m->aa / m->n - ma * ma, cab = m->ab / m->n - ma * mb,
           cbb = m->bb / m->n - mb * mb;
    /* the surface may fill only part of the row's depth here (a top or
     * bottom edge that climbs along strike): the tile spans what is there */
    double sdmin = tile_min_sin(ztop - zbot, dw);
    double zc = tl->centre[2];
    if (m->spans) {
        ztop = fmin(ztop, m->zhi);
        zbot = fmax(zbot, m->zlo);
    }
    double dz = ztop - zbot;
    if (!(dz > 0))
        return;
    /* samples all at one depth say nothing of the dip */
    if (!(cbb > dz * dz / 400)) {
        double sd = fmax(-tl->dip[2], sdmin);
        for (int d = 0; d < 3; d++)
            tl->centre[d] += ((ztop + zbot) / 2 - zc) / -sd * tl->dip[d] * (sd == -tl->dip[2]);
        tl->centre[2] = (ztop + zbot) / 2;
        tl->width = dz / sd;
        return;
    }
    double phi = 0.5 * atan2(2 * cab, caa - cbb);
    double rh[3] = {tl->strike[1], -tl->strike[0], 0};
    /* the normal is across the principal axis (cos phi, sin phi) */
    double n[3] = {-sin(phi) * rh[0], -sin(phi) * rh[1], cos(phi)};
    if (n[2] < 0)
        for (int d = 0; d < 3; d++)
            n[d] = -n[d];
    double st[3] = {tl->strike[0], tl->strike[1], 0};
    if (n[0] * rh[0] + n[1] * rh[1] < 0) { /* dipping left now */
        st[0] = -st[0];
        st[1] = -st[1];
    }
    if (fabs(n[2]) < 1e-12) {
        double az = atan2(st[0], st[1]);
        if (az < 0 || az >= 3.14159265358979323846) {
            st[0] = -st[0];
            st[1] = -st[1];
            n[0] = -n[0];
            n[1] = -n[1];
        }
    }
    double dip[3] = {st[1] * n[2] - st[2] * n[1], st[2] * n[0] - st[0] * n[2],
                     st[0] * n[1] - st[1] * n[0]};
    double sd = fmax(-dip[2], sdmin);
    /* through the samples' centroid, back to the row's middle depth */
    double q[3] = {tl->centre[0] + ma * rh[0], tl->centre[1] + ma * rh[1], tl->centre[2] + mb};
    double level = (ztop + zbot) / 2, s = dip[2] < -1e-12 ? (level - q[2]) / dip[2] : 0;
    for (int d = 0; d < 3; d++)
        tl->centre[d] = q[d] + s * dip[d];
    if (!(dip[2] < -1e-12))
        tl->centre[2] = level;
    memcpy(tl->strike, st, sizeof st);
    memcpy(tl->dip, dip, sizeof dip);
    tl->width = dz / sd;
}

int tile_fit_planes(fm_tiles *t, const fm_mesh *set, const int32_t *part)
{
    if (!t->n)
        return 0;
    const double *x = fm_mesh_vertices(set);
    const int32_t *tri = fm_mesh_triangles(set), *tag = fm_mesh_tags(set);
    size_t nt = fm_mesh_ntriangles(set);
    double rmax = 0;
    for (size_t i = 0; i < t->n; i++)
        rmax = fmax(rmax, 0.5 * hypot(t->tile[i].length, t->tile[i].width));
    moments *m = calloc(t->n, sizeof *m);
    tile_grid g = {0};
    if (!m || tile_grid_make(&g, t, rmax)) {
        free(m);
        free(g.e);
        return -1;
    }
    for (size_t i = 0; i < nt; i++) {
        const double *c[3] = {x + 3 * (size_t)tri[3 * i], x + 3 * (size_t)tri[3 * i + 1],
                              x + 3 * (size_t)tri[3 * i + 2]};
        /* the depth range the triangle gives each tile it reaches into,
         * and points spread over its area for the planes */
        static const double w[7][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {2.0 / 3, 1.0 / 6, 1.0 / 6},
                                       {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3},
                                       {1.0 / 6, 5.0 / 12, 5.0 / 12},
                                       {5.0 / 12, 1.0 / 6, 5.0 / 12},
                                       {5.0 / 12, 5.0 / 12, 1.0 / 6}};
        double cen[3], rt = 0;
        for (int d = 0; d < 3; d++)
            cen[d] = (c[0][d] + c[1][d] + c[2][d]) / 3;
        for (int k = 0; k < 3; k++)
            rt = fmax(rt, sqrt((c[k][0] - cen[0]) * (c[k][0] - cen[0]) +
                               (c[k][1] - cen[1]) * (c[k][1] - cen[1]) +
                               (c[k][2] - cen[2]) * (c[k][2] - cen[2])));
        plane_ctx ec = {t, m, part, cen, {c[0], c[1], c[2]}, tag[i], part[i]};
        tile_grid_near(&g, cen, rmax + rt, add_extent, &ec);
        for (int k = 0; k < 7; k++) {
            double p[3];
            for (int d = 0; d < 3; d++)
                p[d] = w[k][0] * c[0][d] + w[k][1] * c[1][d] + w[k][2] * c[2][d];
            plane_ctx pc = {t, m, part, p, {NULL, NULL, NULL}, tag[i], part[i]};
            tile_grid_near(&g, p, rmax, add_sample, &pc);
        }
    }
    for (size_t i = 0; i < t->n; i++)
        refit(&t->tile[i], &m[i], t->band[i][0], t->band[i][1], t->band[i][2]);
    free(m);
    free(g.e);
    return 0;
}
