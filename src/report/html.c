/* report.html: the facts of report.json for a reader, problems first, the
 * overview pictures drawn here and embedded, the tables sortable and
 * filterable, and every fault drawn on demand by the page's own script
 * from the packed triangles (a picture per fault made the CFM's page
 * 10 MB); written atomically. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "report_internal.h"

void rp_esc(FILE *fp, const char *s)
{
    for (; s && *s; s++) {
        switch (*s) {
        case '<': fputs("&lt;", fp); break;
        case '>': fputs("&gt;", fp); break;
        case '&': fputs("&amp;", fp); break;
        case '"': fputs("&quot;", fp); break;
        default: fputc(*s, fp);
        }
    }
}

/* s as a JSON string inside a <script> element: no "</" can end it. */
static void json_str(FILE *fp, const char *s)
{
    fputc('"', fp);
    for (; s && *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(fp, "\\%c", c);
        else if (c < 0x20 || c == '<' || c == '>' || c == '&')
            fprintf(fp, "\\u%04x", c);
        else
            fputc(c, fp);
    }
    fputc('"', fp);
}

double rp_pct(size_t a, size_t b)
{
    return b ? 100.0 * (double)a / (double)b : 0;
}

void rp_colour(FILE *fp, rp_kind k)
{
    fprintf(fp, "#%02x%02x%02x", (int)lround(255 * rp_kind_rgb[k][0]),
            (int)lround(255 * rp_kind_rgb[k][1]), (int)lround(255 * rp_kind_rgb[k][2]));
}

void rp_badge(FILE *fp, const rp_fault *f)
{
    fputs("<span class=\"b\" style=\"background:", fp);
    rp_colour(fp, f->kind);
    fprintf(fp, "\" title=\"%s\">%s</span>", rp_kind_label[f->kind], rp_kind_badge[f->kind]);
}

static void summary(FILE *fp, const fm_report *r, const size_t kinds[RP_NKINDS])
{
    fputs("<h2 id=\"summary\">Summary</h2>\n<table id=\"summary-table\">\n", fp);
    for (size_t i = 0; i + 1 < r->nfact; i += 2) {
        fputs("<tr><th>", fp);
        rp_esc(fp, r->fact[i]);
        fputs("</th><td>", fp);
        rp_esc(fp, r->fact[i + 1]);
        fputs("</td></tr>\n", fp);
    }
    fputs("<tr><th>faults by outcome</th><td>", fp);
    for (int k = 0; k < RP_NKINDS; k++) {
        fputs("<span class=\"sw\" style=\"background:", fp);
        rp_colour(fp, (rp_kind)k);
        fprintf(fp, "\"></span>%s: %zu", rp_kind_label[k], kinds[k]);
    }
    fputs("</td></tr>\n</table>\n", fp);
}

static fm_status map_section(FILE *fp, const fm_report *r, const size_t kinds[RP_NKINDS])
{
    rp_png png;
    double km_per_px = 0, frame[3];
    fm_status st = rp_draw_map(r, &png, &km_per_px, frame);
    if (st != FM_OK)
        return st;
    fputs("<h2 id=\"map\">Map</h2>\n<p>Every fault seen from above (x east, y north, ", fp);
    rp_esc(fp, r->crs);
    fprintf(fp, "; %.3g km per pixel), the new meshes coloured by outcome and darker "
                "the steeper they dip; faults not meshed are drawn from their originals.</p>\n<p>",
            km_per_px);
    for (int k = 0; k < RP_NKINDS; k++) {
        fputs("<span class=\"sw\" style=\"background:", fp);
        rp_colour(fp, (rp_kind)k);
        fprintf(fp, "\"></span>%s (%zu)", rp_kind_label[k], kinds[k]);
    }
    /* the frame lets the script find the fault under a click */
    fprintf(fp, "</p>\n<p>A click on a meshed fault opens it.</p>\n<div id=\"fm-map\" "
                "data-frame=\"%.17g %.17g %.17g\">",
            frame[0], frame[1], frame[2]);
    rp_png_write_img(fp, &png, "map of the faults");
    rp_png_free(&png);
    fputs("</div>\n", fp);
    return FM_OK;
}

static fm_status figure(FILE *fp, const rp_hist *h, const char *caption)
{
    rp_png png;
    fm_status st = rp_draw_hist(h, &png);
    if (st != FM_OK)
        return st;
    fputs("<figure>", fp);
    rp_png_write_img(fp, &png, "histogram");
    fputs("<figcaption>", fp);
    rp_esc(fp, caption);
    fputs("</figcaption></figure>\n", fp);
    rp_png_free(&png);
    return FM_OK;
}

/* Per meshed fault: its mesh's area against its fitted surface's (below
 * sea level when cut), how much of the fit the mesh covers. */
static void coverage(const fm_report *r, rp_hist *c, size_t *low)
{
    *low = 0;
    for (size_t i = 0; i < r->nf; i++) {
        const rp_fault *f = &r->f[i];
        if (f->tag < 0 || !(f->fitted_area > 0))
            continue;
        double v = f->q.area / f->fitted_area;
        rp_hist_add(c, v);
        *low += v < 0.97;
    }
}

static fm_status histograms(FILE *fp, const fm_report *r)
{
    rp_hist a, e, d, c;
    int bad = rp_hist_init(&a, 0, 60, 60, "smallest angle of the triangle, degrees");
    bad |= rp_hist_init(&e, 0, 2, 40, "edge length / H");
    bad |= rp_hist_init(&d, 0, 2 * FM_FIDELITY_TOL, 40, "node distance to the original, m");
    bad |= rp_hist_init(&c, 0.8, 1.2, 40, "mesh area / fitted area, per fault");
    fm_status st = bad ? FM_ERR_NOMEM : rp_measure(r, &a, &e, &d);
    size_t low = 0;
    if (!bad)
        coverage(r, &c, &low);
    a.log_y = d.log_y = c.log_y = 1;
    a.band_lo = 30;
    a.band_hi = 60;
    e.band_lo = 0.7;
    e.band_hi = 1.4;
    d.band_lo = 0;
    d.band_hi = FM_FIDELITY_TOL;
    c.band_lo = 0.97;
    c.band_hi = 1.2;
    char cap[4][300];
    size_t below30 = a.under, in_band = 0, far = d.over;
    for (size_t i = 0; i < 30 && a.count; i++)
        below30 += a.count[i];
    for (size_t i = 14; i < 28 && e.count; i++)
        in_band += e.count[i];
    for (size_t i = 20; i < d.nbins && d.count; i++)
        far += d.count[i];
    snprintf(cap[0], sizeof cap[0],
             "%zu triangles, %zu (%.3f%%) with an angle under 30 degrees (target: shaded).",
             a.total, below30, rp_pct(below30, a.total));
    snprintf(cap[1], sizeof cap[1],
             "%zu edges (each once per fault, as report.json counts them: an edge two faults "
             "share counts for both) at H = %g m, %.2f%% within [0.7, 1.4] H (shaded).",
             e.total, r->size, rp_pct(in_band, e.total));
    snprintf(cap[2], sizeof cap[2],
             "%zu nodes (per fault), %zu farther than %g m from their fault's original: "
             "extended tops and gaps closed to a neighbour lie off it by design.",
             d.total, far, FM_FIDELITY_TOL);
    snprintf(cap[3], sizeof cap[3],
             "Fit coverage: %zu meshed faults, %zu covering less than 0.97 of their fitted "
             "surface; above 1 where a fault was extended over a gap.",
             c.total, low);
    const rp_hist *h[4] = {&a, &e, &d, &c};
    if (st == FM_OK)
        fputs("<h2 id=\"quality\">Quality, size, fidelity and fit</h2>\n", fp);
    for (int k = 0; k < 4 && st == FM_OK; k++)
        st = figure(fp, h[k], cap[k]);
    rp_hist_free(&a);
    rp_hist_free(&e);
    rp_hist_free(&d);
    rp_hist_free(&c);
    return st;
}

/* The index of the fault named s, or SIZE_MAX. */
static size_t fault_named(const fm_report *r, const char *s)
{
    for (size_t i = 0; i < r->nf; i++)
        if (!strcmp(r->f[i].name, s))
            return i;
    return SIZE_MAX;
}

static int by_pair(const void *a, const void *b)
{
    const size_t *x = a, *y = b;
    return x[0] != y[0] ? (x[0] < y[0] ? -1 : 1) : x[1] < y[1] ? -1 : x[1] > y[1];
}

/* What the script needs beside the tables: per fault its name, kind, tag,
 * first view and neighbours (the faults it has a junction with, joined
 * or not); the grid of the packed triangles and the colours. */
static fm_status data_island(FILE *fp, const fm_report *r, size_t ntags, const rp_pack *pk)
{
    size_t *nb = malloc((2 * r->nj + 1) * 2 * sizeof *nb);
    if (!nb)
        return FM_ERR_NOMEM;
    size_t n = 0;
    for (size_t j = 0; j < r->nj; j++) {
        size_t a = fault_named(r, r->j[j].fault[0]), b = fault_named(r, r->j[j].fault[1]);
        if (a == SIZE_MAX || b == SIZE_MAX || a == b)
            continue;
        nb[2 * n] = a;
        nb[2 * n + 1] = b;
        nb[2 * n + 2] = b;
        nb[2 * n + 3] = a;
        n += 2;
    }
    qsort(nb, n, 2 * sizeof *nb, by_pair);
    fprintf(fp, "<script type=\"application/json\" id=\"fm-data\">{\"H\":%.17g,\"step\":%.17g,"
                "\"origin\":[%.17g,%.17g,%.17g],\"ntags\":%zu,\"rgb\":[",
            r->size, pk->step, pk->origin[0], pk->origin[1], pk->origin[2], ntags);
    for (int k = 0; k < RP_NKINDS; k++)
        fprintf(fp, "%s[%.3f,%.3f,%.3f]", k ? "," : "", rp_kind_rgb[k][0], rp_kind_rgb[k][1],
                rp_kind_rgb[k][2]);
    fputs("],\"f\":[\n", fp);
    size_t at = 0;
    for (size_t i = 0; i < r->nf; i++) {
        const rp_fault *f = &r->f[i];
        fputs(i ? ",\n{\"n\":" : "{\"n\":", fp);
        json_str(fp, f->name);
        fprintf(fp, ",\"k\":%d,\"g\":%d,\"c\":", (int)f->kind, (int)f->tag);
        if (f->tag >= 0 && r->set) {
            rp_camera cam;
            rp_camera_for(f->original ? f->original : r->set, f->original ? -1 : f->tag, &cam);
            fprintf(fp, "[%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f]", cam.r[0], cam.r[1],
                    cam.r[2], cam.u[0], cam.u[1], cam.u[2], cam.d[0], cam.d[1], cam.d[2]);
        } else {
            fputs("null", fp);
        }
        fputs(",\"nb\":[", fp);
        for (size_t k = 0; at < n && nb[2 * at] == i; at++)
            if (!at || nb[2 * at - 2] != i || nb[2 * at + 1] != nb[2 * at - 1])
                fprintf(fp, "%s%zu", k++ ? "," : "", nb[2 * at + 1]);
        fputs("]}", fp);
    }
    fputs("]}</script>\n", fp);
    free(nb);
    return FM_OK;
}

static const char *const panel_html =
    "<section id=\"fm-panel\" hidden aria-label=\"fault\">\n"
    "<button id=\"fm-close\" title=\"close (Esc)\">&times; close</button>\n"
    "<h2 id=\"fm-name\"></h2>\n"
    "<p>Neighbours (a junction with it, joined or not): <span id=\"fm-neighbours\"></span></p>\n"
    "<p id=\"fm-note\" class=\"why\"></p>\n"
    "<h3>The new mesh</h3>\n<p>Seen onto its face (22.5 degrees off square, 25 to 65 degrees "
    "above the horizon, its strike across), triangles outlined where they are large enough "
    "to see; its junction curves (edges it shares with another fault) thick and black; the "
    "outline of its original (as read) dashed. Nodes are drawn on a grid of H/16.</p>\n"
    "<canvas id=\"fm-picture\" width=\"1200\" height=\"620\"></canvas>\n"
    "<h3>In 3D with its neighbours</h3>\n<p>The fault in its colour, its neighbours grey. "
    "Drag to turn, wheel to zoom, shift-drag to pan, double click to go back.</p>\n"
    "<canvas id=\"fm-3d\" width=\"1200\" height=\"620\"></canvas>\n"
    "<h3>Figures</h3>\n<table id=\"fm-facts\"></table>\n"
    "</section>\n";

static fm_status script(FILE *fp, const fm_report *r)
{
    size_t ntags = 0;
    if (r->set) {
        const int32_t *tag = fm_mesh_tags(r->set);
        for (size_t t = 0; t < fm_mesh_ntriangles(r->set); t++)
            if (tag[t] >= 0 && (size_t)tag[t] + 1 > ntags)
                ntags = (size_t)tag[t] + 1;
    }
    rp_pack pk;
    fm_status st = rp_pack_set(r, ntags, &pk);
    if (st != FM_OK)
        return st;
    fputs(panel_html, fp);
    st = data_island(fp, r, ntags, &pk);
    if (st == FM_OK) {
        fputs("<script type=\"application/octet-stream\" id=\"fm-mesh\">", fp);
        rp_base64(fp, pk.data, pk.n);
        fprintf(fp, "</script>\n<script>\n%s</script>\n", rp_page_script);
    }
    free(pk.data);
    return st;
}

fm_status fm_report_write_html(fm_report *r, const char *path, fm_error *err)
{
    fm_atomic_file *af = fm_atomic_open(path, err);
    if (!af)
        return err ? err->code : FM_ERR_IO;
    FILE *fp = fm_atomic_stream(af);
    size_t kinds[RP_NKINDS] = {0};
    for (size_t i = 0; i < r->nf; i++)
        kinds[r->f[i].kind]++;
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>", fp);
    rp_esc(fp, r->title);
    fprintf(fp, "</title>\n<style>\n%s</style>\n</head>\n<body>\n<h1>", rp_page_style);
    rp_esc(fp, r->title);
    fputs("</h1>\n", fp);
    rp_toc(fp, r);
    summary(fp, r, kinds);
    rp_problems(fp, r);
    fm_status st = map_section(fp, r, kinds);
    if (st == FM_OK)
        st = histograms(fp, r);
    if (st == FM_OK) {
        rp_fault_table(fp, r);
        rp_junction_table(fp, r);
        st = script(fp, r);
    }
    fputs("</body>\n</html>\n", fp);
    if (st != FM_OK) {
        fm_atomic_abort(af);
        return fm_error_set(err, st, path, 0, "out of memory drawing the report");
    }
    return fm_atomic_commit(af, err);
}
