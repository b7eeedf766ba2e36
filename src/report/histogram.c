/* Histograms of the set's quality and size, drawn as bar charts. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "report_internal.h"

#define HIST_W 380
#define HIST_H 230
#define HL 52
#define HR 12
#define HT 22
#define HB 40

int rp_hist_init(rp_hist *h, double lo, double hi, size_t nbins, const char *xlabel)
{
    memset(h, 0, sizeof *h);
    h->lo = lo;
    h->hi = hi;
    h->nbins = nbins;
    h->xlabel = xlabel;
    h->count = calloc(nbins, sizeof *h->count);
    return h->count ? 0 : -1;
}

void rp_hist_add(rp_hist *h, double v)
{
    h->total++;
    if (!(v >= h->lo)) {
        h->under++;
        return;
    }
    double at = (v - h->lo) / (h->hi - h->lo) * (double)h->nbins;
    if (at >= (double)h->nbins)
        h->over++;
    else
        h->count[(size_t)at]++;
}

void rp_hist_free(rp_hist *h)
{
    free(h->count);
    h->count = NULL;
}

static double nice(double x)
{
    double p = pow(10, floor(log10(x)));
    return x <= p ? p : x <= 2 * p ? 2 * p : x <= 5 * p ? 5 * p : 10 * p;
}

/* Height of a count on the y axis, 0 .. 1 of the plot. */
static double yfrac(const rp_hist *h, double c, double top)
{
    if (h->log_y)
        return log10(c + 1) / top;
    return c / top;
}

fm_status rp_draw_hist(const rp_hist *h, rp_png *out)
{
    size_t peak = 1;
    for (size_t i = 0; i < h->nbins; i++)
        if (h->count[i] > peak)
            peak = h->count[i];
    double top = h->log_y ? ceil(log10((double)peak + 1)) : nice((double)peak * 1.05);
    if (top <= 0)
        top = 1;
    double pw = HIST_W - HL - HR, ph = HIST_H - HT - HB;
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, HIST_W, HIST_H);
    cairo_t *cr = cairo_create(img);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    double xs = pw / (h->hi - h->lo);
    if (h->band_lo < h->band_hi) {
        double a = fmax(h->band_lo, h->lo), b = fmin(h->band_hi, h->hi);
        cairo_set_source_rgb(cr, 0.88, 0.96, 0.90);
        cairo_rectangle(cr, HL + (a - h->lo) * xs, HT, (b - a) * xs, ph);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0.27, 0.47, 0.70);
    double bw = pw / (double)h->nbins;
    for (size_t i = 0; i < h->nbins; i++) {
        double f = yfrac(h, (double)h->count[i], top);
        if (f > 0)
            cairo_rectangle(cr, HL + (double)i * bw, HT + ph * (1 - f), bw - (bw > 3 ? 1 : 0), ph * f);
    }
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_set_line_width(cr, 1);
    cairo_move_to(cr, HL - 0.5, HT);
    cairo_line_to(cr, HL - 0.5, HT + ph + 0.5);
    cairo_line_to(cr, HL + pw, HT + ph + 0.5);
    cairo_stroke(cr);
    char s[64];
    double step = nice((h->hi - h->lo) / 6);
    for (double v = ceil(h->lo / step) * step; v <= h->hi + 1e-9 * step; v += step) {
        double x = HL + (v - h->lo) * xs;
        cairo_move_to(cr, x, HT + ph);
        cairo_line_to(cr, x, HT + ph + 4);
        cairo_stroke(cr);
        snprintf(s, sizeof s, "%g", v);
        rp_text(cr, x, HT + ph + 15, 10, 0.5, s);
    }
    if (h->log_y) {
        /* bars are log10(count + 1) high: an empty bin has none */
        for (int d = 0; d <= (int)top; d++) {
            double v = pow(10, d), f = log10(v + 1) / top;
            if (f > 1)
                break;
            double y = HT + ph * (1 - f);
            cairo_move_to(cr, HL - 4, y);
            cairo_line_to(cr, HL, y);
            cairo_stroke(cr);
            snprintf(s, sizeof s, "%.0f", v);
            rp_text(cr, HL - 6, y + 4, 10, 1, s);
        }
    } else {
        double ystep = nice(top / 4);
        for (double c = 0; c <= top; c += ystep) {
            double y = HT + ph * (1 - c / top);
            cairo_move_to(cr, HL - 4, y);
            cairo_line_to(cr, HL, y);
            cairo_stroke(cr);
            snprintf(s, sizeof s, "%.0f", c);
            rp_text(cr, HL - 6, y + 4, 10, 1, s);
        }
    }
    rp_text(cr, HL + pw / 2, HIST_H - 6, 11, 0.5, h->xlabel);
    if (h->over || h->under) {
        snprintf(s, sizeof s, "%zu below, %zu above the range", h->under, h->over);
        rp_text(cr, HL + pw, HT - 8, 10, 1, s);
    }
    rp_text(cr, HL, HT - 8, 10, 0, h->log_y ? "count (log)" : "count");
    fm_status st = cairo_status(cr) == CAIRO_STATUS_SUCCESS ? rp_png_encode(img, out) : FM_ERR_NOMEM;
    cairo_destroy(cr);
    cairo_surface_destroy(img);
    return st;
}
