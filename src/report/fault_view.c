/* One fault in 3D: its original (left) beside the new mesh (right), both
 * seen the same way at the same scale, looking onto the fault's face
 * whatever its strike and dip. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "report_internal.h"

#define VIEW_W 360
#define VIEW_H 200
#define PANEL (VIEW_W / 2)
#define PAD 8
#define DEG 0.017453292519943295 /* radians per degree */
#define AZIMUTH_OFF (22.5 * DEG)

static const double original_rgb[3] = {0.62, 0.66, 0.74};

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
static void camera_for(const fm_mesh *m, int32_t tag, rp_camera *cam)
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

/* A scale bar of a round number of km, bottom left of the left panel. */
static void view_scale(cairo_t *cr, double k)
{
    double target = PANEL / 3.0 / k / 1000, km = pow(10, floor(log10(target)));
    if (target >= 5 * km)
        km *= 5;
    else if (target >= 2 * km)
        km *= 2;
    char s[32];
    snprintf(s, sizeof s, "%g km", km);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_set_line_width(cr, 2);
    cairo_move_to(cr, PAD, VIEW_H - 5);
    cairo_line_to(cr, PAD + km * 1000 * k, VIEW_H - 5);
    cairo_stroke(cr);
    rp_text(cr, PAD + km * 1000 * k + 4, VIEW_H - 2, 9, 0, s);
}

rp_raster *rp_fault_raster(void)
{
    return rp_raster_create(PANEL, VIEW_H);
}

fm_status rp_draw_fault(const fm_report *r, const rp_fault *f, rp_raster *ras, rp_scene sc[2],
                        rp_png *out)
{
    memset(out, 0, sizeof *out);
    int meshed = f->tag >= 0 && r->set;
    const fm_mesh *shape = f->original ? f->original : meshed ? r->set : NULL;
    if (!shape)
        return FM_ERR_INVALID;
    rp_camera cam;
    camera_for(shape, f->original ? -1 : f->tag, &cam);
    rp_scene *orig = &sc[0], *now = &sc[1];
    rp_scene_reset(orig);
    rp_scene_reset(now);
    int bad = (f->original && rp_scene_add(orig, f->original, -1, &cam, original_rgb, 0)) ||
              (meshed && rp_scene_add(now, r->set, f->tag, &cam, rp_kind_rgb[f->kind], 1));
    double lo[2], hi[2], lo2[2], hi2[2];
    int any = rp_scene_bounds(orig, lo, hi), any2 = rp_scene_bounds(now, lo2, hi2);
    if (bad || (!any && !any2))
        return bad ? FM_ERR_NOMEM : FM_ERR_INVALID;
    for (int c = 0; c < 2 && any2; c++) {
        lo[c] = any ? fmin(lo[c], lo2[c]) : lo2[c];
        hi[c] = any ? fmax(hi[c], hi2[c]) : hi2[c];
    }
    double wx = fmax(hi[0] - lo[0], 1), wy = fmax(hi[1] - lo[1], 1);
    double k = fmin((PANEL - 2 * PAD) / wx, (VIEW_H - 2 * PAD - 10) / wy);
    double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, VIEW_W, VIEW_H);
    cairo_t *cr = cairo_create(img);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    /* edges fade out where triangles shrink to a few pixels (a long
     * fault), or they would hide the faces */
    double px = r->size * k, shown = fmin(fmax((px - 2) / 4, 0), 1);
    rp_lines lines = {shown > 0 ? 1 : 0, 0, 1 - 0.45 * shown};
    for (int side = 0; side < 2; side++) {
        rp_raster_clear(ras);
        rp_raster_scene(ras, side ? now : orig, k, PANEL / 2.0 - k * cx, VIEW_H / 2.0 + 2 + k * cy,
                        &lines);
        rp_raster_put(ras, img, side * PANEL, 0);
    }
    cairo_set_source_rgb(cr, 0.8, 0.8, 0.8);
    cairo_set_line_width(cr, 1);
    cairo_move_to(cr, PANEL + 0.5, 0);
    cairo_line_to(cr, PANEL + 0.5, VIEW_H);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    rp_text(cr, 4, 11, 9, 0, f->original ? "original" : "original not read");
    rp_text(cr, PANEL + 4, 11, 9, 0, meshed ? "new mesh" : "not meshed");
    view_scale(cr, k);
    fm_status st = cairo_status(cr) == CAIRO_STATUS_SUCCESS ? rp_png_encode(img, out) : FM_ERR_NOMEM;
    cairo_destroy(cr);
    cairo_surface_destroy(img);
    return st;
}
