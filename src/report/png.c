/* Pictures as PNG bytes in memory, and those bytes as a data: URI, so the
 * page is one file. */
#include <stdlib.h>
#include <string.h>

#include <fontconfig/fontconfig.h>

#include "report_internal.h"

static cairo_status_t append(void *closure, const unsigned char *data, unsigned int length)
{
    rp_png *p = closure;
    if (p->n + length > p->cap) {
        size_t cap = p->cap ? p->cap : 4096;
        while (cap < p->n + length)
            cap *= 2;
        unsigned char *g = realloc(p->data, cap);
        if (!g)
            return CAIRO_STATUS_NO_MEMORY;
        p->data = g;
        p->cap = cap;
    }
    memcpy(p->data + p->n, data, length);
    p->n += length;
    return CAIRO_STATUS_SUCCESS;
}

fm_status rp_png_encode(cairo_surface_t *s, rp_png *out)
{
    memset(out, 0, sizeof *out);
    cairo_surface_flush(s);
    out->width = cairo_image_surface_get_width(s);
    out->height = cairo_image_surface_get_height(s);
    if (cairo_surface_write_to_png_stream(s, append, out) != CAIRO_STATUS_SUCCESS) {
        rp_png_free(out);
        return FM_ERR_NOMEM;
    }
    return FM_OK;
}

void rp_png_free(rp_png *p)
{
    free(p->data);
    memset(p, 0, sizeof *p);
}

void rp_base64(FILE *fp, const unsigned char *d, size_t n)
{
    static const char abc[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char line[4 * 1024 + 4];
    size_t k = 0;
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)d[i] << 16;
        if (i + 1 < n)
            v |= (unsigned)d[i + 1] << 8;
        if (i + 2 < n)
            v |= d[i + 2];
        line[k++] = abc[v >> 18 & 63];
        line[k++] = abc[v >> 12 & 63];
        line[k++] = i + 1 < n ? abc[v >> 6 & 63] : '=';
        line[k++] = i + 2 < n ? abc[v & 63] : '=';
        if (k >= 4 * 1024) {
            fwrite(line, 1, k, fp);
            k = 0;
        }
    }
    fwrite(line, 1, k, fp);
}

void rp_png_write_img(FILE *fp, const rp_png *p, const char *alt)
{
    fprintf(fp, "<img width=\"%d\" height=\"%d\" alt=\"%s\" src=\"data:image/png;base64,",
            p->width, p->height, alt);
    rp_base64(fp, p->data, p->n);
    fputs("\">", fp);
}

void rp_text(cairo_t *cr, double x, double y, double size, double align, const char *s)
{
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
    cairo_text_extents_t e;
    cairo_text_extents(cr, s, &e);
    cairo_move_to(cr, x - align * (e.width + e.x_bearing), y);
    cairo_show_text(cr, s);
}

void fm_report_cleanup(void)
{
    cairo_debug_reset_static_data();
    FcFini();
}
