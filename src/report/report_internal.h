/* faultmesh report: what the builder holds and the pieces of the page
 * (scene drawing, PNG in memory, histograms) shared by its files. */
#ifndef FM_REPORT_INTERNAL_H
#define FM_REPORT_INTERNAL_H

#include <stdio.h>

#include <cairo.h>

#include "fm_report.h"

/* How a fault is shown: its colour on the map and its badge. */
typedef enum rp_kind {
    RP_OK = 0,
    RP_WARNED,  /* meshed, with warnings */
    RP_CARVED,  /* meshed, gave up triangles where it ran through another */
    RP_EMPTY,   /* nothing below sea level */
    RP_FAILED,
    RP_DROPPED, /* near-duplicate of a fault kept */
    RP_EXCLUDED, /* left out by the caller's settings */
    RP_NKINDS
} rp_kind;

extern const double rp_kind_rgb[RP_NKINDS][3];
extern const char *const rp_kind_label[RP_NKINDS];
/* The word on a fault's badge: one per kind, so that no two colours read
 * the same. */
extern const char *const rp_kind_badge[RP_NKINDS];

typedef struct rp_fault {
    char *name, *file, *status, *reason, *join_error;
    char **warnings;
    size_t nwarnings;
    int32_t tag;
    const fm_mesh *original;
    size_t sheets;
    fm_quality q;
    fm_fidelity fid;
    double fitted_area;
    size_t carved;
    double carved_area;
    int has_loss;
    fm_loss_fault loss;
    rp_kind kind;
} rp_fault;

typedef struct rp_junction {
    char *fault[2], *type, *reason;
    double gap, overshoot, length, min_angle;
} rp_junction;

typedef struct rp_elastic_group {
    char *fault[2];
    size_t junction, pairs;
    double max_ratio, min_distance;
    size_t examples[10];
    size_t nexamples;
} rp_elastic_group;

struct fm_report {
    const fm_mesh *set;
    char *title, *crs;
    double size;
    rp_fault *f;
    size_t nf, capf;
    rp_junction *j;
    size_t nj, capj;
    char **fact; /* label, value, label, value, ... */
    size_t nfact, capfact;
    int elastic;                 /* the elastic check ran */
    double elastic_fraction;
    size_t elastic_wrong;
    rp_elastic_group *eg;
    size_t neg, capeg;
};

/* A PNG file in memory. */
typedef struct rp_png {
    unsigned char *data;
    size_t n, cap;
    int width, height;
} rp_png;

/* Encodes s (an ARGB32 or RGB24 image surface) as PNG into out. */
fm_status rp_png_encode(cairo_surface_t *s, rp_png *out);
void rp_png_free(rp_png *p);
/* The PNG as an <img> element with a data: URI. */
void rp_png_write_img(FILE *fp, const rp_png *p, const char *alt);

/* An orthographic camera: right, up and forward (into the screen) unit
 * vectors; light: unit vector towards the light; ambient share of the
 * brightness. */
typedef struct rp_camera {
    double r[3], u[3], d[3];
    double light[3];
    double ambient;
} rp_camera;

/* Triangles projected to the screen (y up), with the depth of their
 * corners along d and their colour. */
typedef struct rp_tri {
    double p[3][2];
    double z[3];
    float rgb[3];
    int edges; /* outline the triangle in a darker shade */
} rp_tri;

typedef struct rp_scene {
    rp_tri *t;
    size_t n, cap;
} rp_scene;

/* Adds the triangles of m tagged tag (tag < 0: all), shaded base colour
 * rgb. -1 when out of memory. */
int rp_scene_add(rp_scene *s, const fm_mesh *m, int32_t tag, const rp_camera *cam,
                 const double rgb[3], int edges);
/* Adds every triangle of m coloured rgb[its tag]; tags past ntags or
 * whose colour has a negative red are left out. */
int rp_scene_add_tagged(rp_scene *s, const fm_mesh *m, const rp_camera *cam,
                        const double (*rgb)[3], size_t ntags, int edges);
/* Screen bounding box; 0 when the scene is empty. */
int rp_scene_bounds(const rp_scene *s, double lo[2], double hi[2]);
/* Empties it, keeping its memory for the next. */
void rp_scene_reset(rp_scene *s);
void rp_scene_free(rp_scene *s);

/* A z-buffer of width x height pixels (supersampled). */
typedef struct rp_raster rp_raster;
rp_raster *rp_raster_create(int width, int height);
/* Empties it for another picture of the same size. */
void rp_raster_clear(rp_raster *r);
void rp_raster_destroy(rp_raster *r);

/* How triangles are outlined, widths in samples (0: not at all): those
 * with edges set in edge_shade times their colour, the others in their
 * own colour. */
typedef struct rp_lines {
    int edge_width, all_width;
    double edge_shade;
} rp_lines;

/* Draws the scene with screen point p at pixel (ox + k p.x, oy - k p.y). */
void rp_raster_scene(rp_raster *r, const rp_scene *s, double k, double ox, double oy,
                     const rp_lines *lines);
/* The segment a - b (screen points, placed as by rp_raster_scene) over
 * everything, width samples wide. */
void rp_raster_line_over(rp_raster *r, double k, double ox, double oy, const double a[2],
                         const double b[2], const double rgb[3], int width);
/* Averages the samples onto img's pixels from (x, y), what was not drawn
 * leaving img as it was. */
void rp_raster_put(const rp_raster *r, cairo_surface_t *img, int x, int y);

/* The map of every fault, seen from above; frame: x (m) at the picture's
 * left edge, y (m) at its top, pixels per m. */
fm_status rp_draw_map(const fm_report *r, rp_png *out, double *km_per_px, double frame[3]);

/* Looking onto the face of the triangles of m tagged tag (tag < 0: all):
 * right along the strike, from the side that sees it, a little off
 * square and from 25 to 65 degrees above the horizon. */
void rp_camera_for(const fm_mesh *m, int32_t tag, rp_camera *cam);

/* The set's triangles per tag 0..ntags-1 and the outlines of their
 * faults' originals, packed and deflated for the page's script
 * (mesh_pack.c tells the format): grid coordinates of step `step` m from
 * `origin`. */
typedef struct rp_pack {
    unsigned char *data;
    size_t n, raw; /* deflated and raw bytes */
    double origin[3], step;
} rp_pack;
fm_status rp_pack_set(const fm_report *r, size_t ntags, rp_pack *out);

/* Vertex chains: chain k is v[start[k] .. start[k + 1]), n chains. */
typedef struct rp_chains {
    uint32_t *v;
    size_t *start;
    size_t n;
} rp_chains;
/* The outline of m (sides of one triangle) as chains, a closed one ending
 * where it began. */
fm_status rp_outline(const fm_mesh *m, rp_chains *out);
void rp_chains_free(rp_chains *c);

/* n bytes as base64, no line breaks. */
void rp_base64(FILE *fp, const unsigned char *d, size_t n);

/* Pieces of the page (html.c): text escaped for HTML, a percentage, a
 * kind's colour as #rrggbb, a fault's badge. */
void rp_esc(FILE *fp, const char *s);
double rp_pct(size_t a, size_t b);
void rp_colour(FILE *fp, rp_kind k);
void rp_badge(FILE *fp, const rp_fault *f);
/* Its tables (html_tables.c): contents, problems, faults, junctions. */
void rp_toc(FILE *fp, const fm_report *r);
void rp_problems(FILE *fp, const fm_report *r);
/* html_elastic.c: the elastic check's flagged groups, in the problems. */
void rp_elastic(FILE *fp, const fm_report *r);
void rp_fault_table(FILE *fp, const fm_report *r);
void rp_junction_table(FILE *fp, const fm_report *r);

/* The page's own style sheet and script (page.css, page.js, embedded by
 * embed.cmake). */
extern const char rp_page_style[];
extern const char rp_page_script[];

/* A histogram: counts over [lo, hi) in nbins equal bins, what falls
 * outside counted apart; band (if band_lo < band_hi) shaded as the
 * target. */
typedef struct rp_hist {
    double lo, hi;
    size_t nbins;
    size_t *count;
    size_t under, over, total;
    double band_lo, band_hi;
    int log_y;
    const char *xlabel;
} rp_hist;

int rp_hist_init(rp_hist *h, double lo, double hi, size_t nbins, const char *xlabel);
void rp_hist_add(rp_hist *h, double v);
void rp_hist_free(rp_hist *h);
fm_status rp_draw_hist(const rp_hist *h, rp_png *out);

/* The three distributions of the set: smallest angle per triangle, edge
 * length / H (each edge once), node distance to its fault's original. */
fm_status rp_measure(const fm_report *r, rp_hist *angle, rp_hist *edge, rp_hist *dist);

/* Text in a cairo image: the toy API, one font, for axis labels. */
void rp_text(cairo_t *cr, double x, double y, double size, double align, const char *s);

#endif
