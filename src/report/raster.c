/* A small z-buffer rasterizer for the scenes: cairo drew a fault's
 * triangles one path at a time, some 20 microseconds each, which for the
 * 1.5 million triangles of the CFM's originals took half a minute. Here a
 * triangle costs a few pixel tests. Supersampled RP_SS x RP_SS per pixel
 * and averaged, so edges are smoothed as cairo's were. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "report_internal.h"

#define RP_SS 2

struct rp_raster {
    int w, h;       /* samples */
    float *z;       /* depth per sample, INFINITY where nothing was drawn */
    uint32_t *rgb;  /* 0x00RRGGBB per sample */
};

rp_raster *rp_raster_create(int width, int height)
{
    rp_raster *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->w = width * RP_SS;
    r->h = height * RP_SS;
    size_t n = (size_t)r->w * (size_t)r->h;
    r->z = malloc((n ? n : 1) * sizeof *r->z);
    r->rgb = malloc((n ? n : 1) * sizeof *r->rgb);
    if (!r->z || !r->rgb) {
        rp_raster_destroy(r);
        return NULL;
    }
    for (size_t i = 0; i < n; i++)
        r->z[i] = INFINITY;
    return r;
}

void rp_raster_clear(rp_raster *r)
{
    size_t n = (size_t)r->w * (size_t)r->h;
    for (size_t i = 0; i < n; i++)
        r->z[i] = INFINITY;
}

void rp_raster_destroy(rp_raster *r)
{
    if (!r)
        return;
    free(r->z);
    free(r->rgb);
    free(r);
}

static uint32_t pack(const float rgb[3], double f)
{
    uint32_t c = 0;
    for (int k = 0; k < 3; k++) {
        long v = lround(255 * fmin(fmax(rgb[k] * f, 0), 1));
        c = c << 8 | (uint32_t)v;
    }
    return c;
}

static double edge_fn(const double *a, const double *b, double x, double y)
{
    return (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
}

/* Samples whose centre is inside the triangle (in sample coordinates, the
 * edges included, so that neighbours leave no seam) and nearer than what
 * is there. */
static void fill(rp_raster *r, const double (*p)[2], const double *z, uint32_t c)
{
    double area = edge_fn(p[0], p[1], p[2][0], p[2][1]);
    if (area == 0)
        return;
    double inv = 1 / area;
    int x0 = (int)fmax(floor(fmin(fmin(p[0][0], p[1][0]), p[2][0])), 0);
    int x1 = (int)fmin(ceil(fmax(fmax(p[0][0], p[1][0]), p[2][0])), r->w - 1);
    int y0 = (int)fmax(floor(fmin(fmin(p[0][1], p[1][1]), p[2][1])), 0);
    int y1 = (int)fmin(ceil(fmax(fmax(p[0][1], p[1][1]), p[2][1])), r->h - 1);
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            double cx = x + 0.5, cy = y + 0.5;
            /* barycentric weights times the area: all of its sign inside */
            double w0 = edge_fn(p[1], p[2], cx, cy) * inv, w1 = edge_fn(p[2], p[0], cx, cy) * inv,
                   w2 = edge_fn(p[0], p[1], cx, cy) * inv;
            if (w0 < 0 || w1 < 0 || w2 < 0)
                continue;
            double d = w0 * z[0] + w1 * z[1] + w2 * z[2];
            size_t i = (size_t)y * (size_t)r->w + (size_t)x;
            if (d < r->z[i]) {
                r->z[i] = (float)d;
                r->rgb[i] = c;
            }
        }
}

/* A line of width samples, drawn where it is not behind a surface by
 * more than bias. */
static void line(rp_raster *r, const double *a, const double *b, double za, double zb,
                 uint32_t c, int width, double bias)
{
    double dx = b[0] - a[0], dy = b[1] - a[1];
    int n = (int)ceil(fmax(fabs(dx), fabs(dy))) + 1;
    for (int s = 0; s <= n; s++) {
        double t = (double)s / n;
        int x = (int)floor(a[0] + t * dx - 0.5 * (width - 1));
        int y = (int)floor(a[1] + t * dy - 0.5 * (width - 1));
        double d = za + t * (zb - za) - bias;
        for (int j = 0; j < width; j++)
            for (int i = 0; i < width; i++) {
                int px = x + i, py = y + j;
                if (px < 0 || py < 0 || px >= r->w || py >= r->h)
                    continue;
                size_t k = (size_t)py * (size_t)r->w + (size_t)px;
                if (d <= r->z[k]) {
                    r->z[k] = (float)fmin(r->z[k], d + bias);
                    r->rgb[k] = c;
                }
            }
    }
}

void rp_raster_scene(rp_raster *r, const rp_scene *s, double k, double ox, double oy,
                     const rp_lines *lines)
{
    double zlo = INFINITY, zhi = -INFINITY;
    for (size_t i = 0; i < s->n; i++)
        for (int v = 0; v < 3; v++) {
            zlo = fmin(zlo, s->t[i].z[v]);
            zhi = fmax(zhi, s->t[i].z[v]);
        }
    double bias = s->n ? 0.01 * (zhi - zlo) + 1 : 0;
    for (size_t i = 0; i < s->n; i++) {
        const rp_tri *t = &s->t[i];
        double p[3][2];
        for (int v = 0; v < 3; v++) {
            p[v][0] = RP_SS * (ox + k * t->p[v][0]);
            p[v][1] = RP_SS * (oy - k * t->p[v][1]);
        }
        fill(r, (const double(*)[2])p, t->z, pack(t->rgb, 1));
        /* outlines: the mesh's edges in a darker shade, or (from above)
         * every triangle in its own colour so that a fault seen edge-on
         * still shows as a line */
        int width = t->edges ? lines->edge_width : lines->all_width;
        if (width <= 0)
            continue;
        uint32_t c = pack(t->rgb, t->edges ? lines->edge_shade : 1);
        for (int v = 0; v < 3; v++)
            line(r, p[v], p[(v + 1) % 3], t->z[v], t->z[(v + 1) % 3], c, width, bias);
    }
}

void rp_raster_line_over(rp_raster *r, double k, double ox, double oy, const double a[2],
                         const double b[2], const double rgb[3], int width)
{
    double p[2] = {RP_SS * (ox + k * a[0]), RP_SS * (oy - k * a[1])};
    double q[2] = {RP_SS * (ox + k * b[0]), RP_SS * (oy - k * b[1])};
    float c[3] = {(float)rgb[0], (float)rgb[1], (float)rgb[2]};
    line(r, p, q, -1e30, -1e30, pack(c, 1), width, 0); /* nearer than anything */
}

void rp_raster_put(const rp_raster *r, cairo_surface_t *img, int x0, int y0)
{
    cairo_surface_flush(img);
    unsigned char *data = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img);
    int iw = cairo_image_surface_get_width(img), ih = cairo_image_surface_get_height(img);
    for (int y = 0; y < r->h / RP_SS; y++)
        for (int x = 0; x < r->w / RP_SS; x++) {
            int px = x0 + x, py = y0 + y;
            if (px < 0 || py < 0 || px >= iw || py >= ih)
                continue;
            uint32_t *dst = (uint32_t *)(data + (size_t)py * (size_t)stride) + px;
            unsigned sum[3] = {0, 0, 0}, bg[3] = {*dst >> 16 & 255, *dst >> 8 & 255, *dst & 255};
            for (int j = 0; j < RP_SS; j++)
                for (int i = 0; i < RP_SS; i++) {
                    size_t k = (size_t)(y * RP_SS + j) * (size_t)r->w + (size_t)(x * RP_SS + i);
                    int drawn = r->z[k] != INFINITY;
                    for (int c = 0; c < 3; c++)
                        sum[c] += drawn ? r->rgb[k] >> (16 - 8 * c) & 255 : bg[c];
                }
            *dst = (sum[0] / (RP_SS * RP_SS)) << 16 | (sum[1] / (RP_SS * RP_SS)) << 8 |
                   sum[2] / (RP_SS * RP_SS);
        }
    cairo_surface_mark_dirty(img);
}
