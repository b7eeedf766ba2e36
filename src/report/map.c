/* The map: every fault seen from above (x east, y north, one scale for
 * both), coloured by what became of it, shaded by dip so that dipping
 * faults read as areas and vertical ones as lines. */
#include <math.h>
#include <stdlib.h>

#include "report_internal.h"

#define MAP_MAX 1100 /* pixels, the longer side of the map area */
#define ML 58        /* margins: tick labels left and below */
#define MR 16
#define MT 16
#define MB 40

/* 1, 2 or 5 times a power of ten, the first not below x. */
static double nice_step(double x)
{
    double p = pow(10, floor(log10(x)));
    return x <= p ? p : x <= 2 * p ? 2 * p : x <= 5 * p ? 5 * p : 10 * p;
}

static void ticks(cairo_t *cr, double lo, double hi, double k, double ox, double oy, int vertical)
{
    double step = nice_step((hi - lo) / 10);
    char s[32];
    cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
    cairo_set_line_width(cr, 1);
    for (double v = ceil(lo / step) * step; v <= hi; v += step) {
        double at = vertical ? oy - k * (v - lo) : ox + k * (v - lo);
        snprintf(s, sizeof s, "%.0f", v / 1000);
        if (vertical) {
            cairo_move_to(cr, ox - 5, at);
            cairo_line_to(cr, ox, at);
            cairo_stroke(cr);
            rp_text(cr, ox - 7, at + 4, 10, 1, s);
        } else {
            cairo_move_to(cr, at, oy);
            cairo_line_to(cr, at, oy + 5);
            cairo_stroke(cr);
            rp_text(cr, at, oy + 16, 10, 0.5, s);
        }
    }
}

/* A bar of a round number of km, black and white halves, bottom left. */
static void scale_bar(cairo_t *cr, double k, double x, double y, double width)
{
    double km = nice_step(width / 5 / k / 1000);
    double len = km * 1000 * k;
    cairo_set_line_width(cr, 1);
    for (int h = 0; h < 2; h++) {
        cairo_rectangle(cr, x + h * len / 2, y - 6, len / 2, 6);
        if (h == 0)
            cairo_set_source_rgb(cr, 0, 0, 0);
        else
            cairo_set_source_rgb(cr, 1, 1, 1);
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_stroke(cr);
    }
    char s[32];
    snprintf(s, sizeof s, "%g km", km);
    rp_text(cr, x, y - 10, 11, 0, "0");
    rp_text(cr, x + len, y - 10, 11, 0.5, s);
}

static void north_arrow(cairo_t *cr, double x, double y)
{
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_move_to(cr, x, y);
    cairo_line_to(cr, x + 7, y + 20);
    cairo_line_to(cr, x, y + 15);
    cairo_line_to(cr, x - 7, y + 20);
    cairo_close_path(cr);
    cairo_fill(cr);
    rp_text(cr, x, y + 34, 12, 0.5, "N");
}

/* The edges of m used by one triangle, seen from above, over the map. */
static fm_status outline(rp_raster *ras, const fm_mesh *m, double k, double ox, double oy,
                         const double rgb[3])
{
    size_t n = 0;
    fm_keyed *side = fm_mesh_sides(m, &n);
    if (!side && fm_mesh_ntriangles(m))
        return FM_ERR_NOMEM;
    const double *X = fm_mesh_vertices(m);
    for (size_t i = 0; i < n; i++) {
        if ((i > 0 && side[i - 1].key == side[i].key) || (i + 1 < n && side[i + 1].key == side[i].key))
            continue;
        /* fm_edge_key: smaller << 32 | larger */
        const double *a = X + 3 * (size_t)(side[i].key >> 32), *b = X + 3 * (size_t)(uint32_t)side[i].key;
        double p[2] = {a[0], a[1]}, q[2] = {b[0], b[1]};
        rp_raster_line_over(ras, k, ox, oy, p, q, rgb, 2);
    }
    free(side);
    return FM_OK;
}

fm_status rp_draw_map(const fm_report *r, rp_png *out, double *km_per_px, double frame[3])
{
    /* from above: depth is -z, the deepest drawn first; brightness by
     * the cosine of the dip */
    rp_camera cam = {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}, 0.6};
    size_t ntags = 0;
    for (size_t i = 0; i < r->nf; i++)
        if (r->f[i].tag >= 0 && (size_t)r->f[i].tag + 1 > ntags)
            ntags = (size_t)r->f[i].tag + 1;
    double(*rgb)[3] = malloc((ntags + 1) * sizeof *rgb);
    rp_scene s = {0};
    if (!rgb)
        return FM_ERR_NOMEM;
    for (size_t t = 0; t < ntags; t++)
        rgb[t][0] = -1;
    for (size_t i = 0; i < r->nf; i++)
        if (r->f[i].tag >= 0)
            for (int c = 0; c < 3; c++)
                rgb[r->f[i].tag][c] = rp_kind_rgb[r->f[i].kind][c];
    int bad = r->set && rp_scene_add_tagged(&s, r->set, &cam, (const double(*)[3])rgb, ntags, 0);
    /* what was not meshed, where its original lies: beneath the meshes
     * (a near-duplicate lies on the fault kept), its outline over them */
    for (size_t i = 0; !bad && i < r->nf; i++)
        if (r->f[i].tag < 0 && r->f[i].original) {
            size_t from = s.n;
            bad = rp_scene_add(&s, r->f[i].original, -1, &cam, rp_kind_rgb[r->f[i].kind], 0);
            for (size_t t = from; !bad && t < s.n; t++)
                for (int v = 0; v < 3; v++)
                    s.t[t].z[v] += 1e7;
        }
    free(rgb);
    if (bad) {
        rp_scene_free(&s);
        return FM_ERR_NOMEM;
    }
    double lo[2] = {0, 0}, hi[2] = {1, 1};
    if (!rp_scene_bounds(&s, lo, hi)) {
        lo[0] = lo[1] = 0;
        hi[0] = hi[1] = 1;
    }
    /* a little room around the faults */
    double pad = 0.02 * fmax(hi[0] - lo[0], hi[1] - lo[1]) + 1;
    for (int c = 0; c < 2; c++) {
        lo[c] -= pad;
        hi[c] += pad;
    }
    double k = MAP_MAX / fmax(hi[0] - lo[0], hi[1] - lo[1]);
    int w = (int)ceil(k * (hi[0] - lo[0])), h = (int)ceil(k * (hi[1] - lo[1]));
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w + ML + MR, h + MT + MB);
    cairo_t *cr = cairo_create(img);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    rp_raster *ras = rp_raster_create(w, h);
    fm_status st = FM_OK;
    if (!ras) {
        rp_scene_free(&s);
        cairo_destroy(cr);
        cairo_surface_destroy(img);
        return FM_ERR_NOMEM;
    }
    rp_lines lines = {0, 2, 1};
    rp_raster_scene(ras, &s, k, -k * lo[0], h + k * lo[1], &lines);
    for (size_t i = 0; i < r->nf && st == FM_OK; i++)
        if (r->f[i].tag < 0 && r->f[i].original)
            st = outline(ras, r->f[i].original, k, -k * lo[0], h + k * lo[1],
                         rp_kind_rgb[r->f[i].kind]);
    rp_raster_put(ras, img, ML, MT);
    rp_raster_destroy(ras);
    rp_scene_free(&s);
    scale_bar(cr, k, ML + 14, MT + h - 12, w);
    north_arrow(cr, ML + w - 24, MT + 10);
    cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, ML - 0.5, MT - 0.5, w + 1, h + 1);
    cairo_stroke(cr);
    ticks(cr, lo[0], hi[0], k, ML, MT + h, 0);
    ticks(cr, lo[1], hi[1], k, ML, MT + h, 1);
    rp_text(cr, ML + w / 2.0, MT + h + 32, 11, 0.5, "x (east), km");
    cairo_save(cr);
    cairo_translate(cr, 14, MT + h / 2.0);
    cairo_rotate(cr, -asin(1.0)); /* a quarter turn anticlockwise */
    rp_text(cr, 0, 0, 11, 0.5, "y (north), km");
    cairo_restore(cr);
    if (st == FM_OK)
        st = cairo_status(cr) == CAIRO_STATUS_SUCCESS ? rp_png_encode(img, out) : FM_ERR_NOMEM;
    cairo_destroy(cr);
    cairo_surface_destroy(img);
    *km_per_px = 1 / k / 1000;
    frame[0] = lo[0] - ML / k;
    frame[1] = lo[1] + (MT + h) / k;
    frame[2] = k;
    return st;
}
