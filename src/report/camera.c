/* How a fault is first seen on the page: looking onto its face whatever
 * its strike and dip. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "report_internal.h"

#define DEG 0.017453292519943295 /* radians per degree */
#define AZIMUTH_OFF (22.5 * DEG)

/* The horizontal direction of largest spread of m's vertices, pointing
 * east or, for a north-south fault, north: the strike of a fault that
 * lies flat. */
static void spread_of(const fm_mesh *m, double r[3])
{
    size_t nv = fm_mesh_nvertices(m);
    const double *X = fm_mesh_vertices(m);
    double mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
    for (size_t v = 0; v < nv; v++) {
        mx += X[3 * v];
        my += X[3 * v + 1];
    }
    mx /= nv ? (double)nv : 1;
    my /= nv ? (double)nv : 1;
    for (size_t v = 0; v < nv; v++) {
        double dx = X[3 * v] - mx, dy = X[3 * v + 1] - my;
        sxx += dx * dx;
        syy += dy * dy;
        sxy += dx * dy;
    }
    double th = 0.5 * atan2(2 * sxy, sxx - syy);
    r[0] = cos(th);
    r[1] = sin(th);
    r[2] = 0;
}

/* The mean normal of the triangles of m tagged tag (tag < 0: all),
 * whichever way each faces: the leading eigenvector of the sum of
 * area-weighted n n^T, by power iteration; pointing up. */
static void mean_normal(const fm_mesh *m, int32_t tag, double n[3])
{
    double M[3][3] = {{0}};
    const double *X = fm_mesh_vertices(m);
    const int32_t *T = fm_mesh_triangles(m), *tg = fm_mesh_tags(m);
    for (size_t t = 0; t < fm_mesh_ntriangles(m); t++) {
        if (tag >= 0 && tg[t] != tag)
            continue;
        const double *a = X + 3 * T[3 * t], *b = X + 3 * T[3 * t + 1], *c = X + 3 * T[3 * t + 2];
        double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double f[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double v[3] = {e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]};
        double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (len > 0)
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    M[i][j] += v[i] * v[j] / len; /* area-weighted unit normals */
    }
    double x[3] = {0.3, 0.5, 0.8};
    for (int it = 0; it < 60; it++) {
        double y[3], len = 0;
        for (int i = 0; i < 3; i++) {
            y[i] = M[i][0] * x[0] + M[i][1] * x[1] + M[i][2] * x[2];
            len += y[i] * y[i];
        }
        if (!(len > 0))
            break;
        for (int i = 0; i < 3; i++)
            x[i] = y[i] / sqrt(len);
    }
    double s = x[2] < 0 ? -1 : 1;
    for (int i = 0; i < 3; i++)
        n[i] = s * x[i];
}

/* Looking onto the fault's face: right along its strike, from the side
 * that sees it, turned a little off square and from 25 to 65 degrees above
 * the horizon so that a vertical fault still shows its depth and a flat
 * one its outline. */
void rp_camera_for(const fm_mesh *m, int32_t tag, rp_camera *cam)
{
    double n[3], *r = cam->r;
    mean_normal(m, tag, n);
    double h = sqrt(n[0] * n[0] + n[1] * n[1]);
    if (h > 0.05) {
        r[0] = -n[1] / h;
        r[1] = n[0] / h;
        r[2] = 0;
    } else {
        spread_of(m, r);
    }
    if (r[0] < -1e-9 || (fabs(r[0]) <= 1e-9 && r[1] < 0)) {
        r[0] = -r[0];
        r[1] = -r[1];
    }
    double fh[3] = {-r[1], r[0], 0}; /* horizontal, into the screen */
    double a = n[0] * fh[0] + n[1] * fh[1];
    if (a > 0) { /* the other side faces the viewer */
        for (int k = 0; k < 2; k++) {
            fh[k] = -fh[k];
            r[k] = -r[k];
        }
        a = -a;
    }
    /* a quarter of a right angle off square, so that folds and branches
     * show in relief */
    double cz = cos(AZIMUTH_OFF), sz = sin(AZIMUTH_OFF);
    double r0 = r[0], r1 = r[1], f0 = fh[0], f1 = fh[1];
    r[0] = cz * r0 - sz * r1;
    r[1] = sz * r0 + cz * r1;
    fh[0] = cz * f0 - sz * f1;
    fh[1] = sz * f0 + cz * f1;
    a = n[0] * fh[0] + n[1] * fh[1];
    const double lo = 25 * DEG, hi = 65 * DEG;
    double e = fmin(fmax(atan2(n[2], -a), lo), hi), se = sin(e), ce = cos(e);
    for (int k = 0; k < 3; k++) {
        cam->d[k] = ce * fh[k] - (k == 2 ? se : 0);
        cam->u[k] = se * fh[k] + (k == 2 ? ce : 0);
    }
    /* from over the viewer's left shoulder */
    double l[3], len = 0;
    for (int k = 0; k < 3; k++) {
        l[k] = -cam->d[k] + 0.6 * cam->u[k] - 0.4 * cam->r[k];
        len += l[k] * l[k];
    }
    for (int k = 0; k < 3; k++)
        cam->light[k] = l[k] / sqrt(len);
    cam->ambient = 0.45;
}
