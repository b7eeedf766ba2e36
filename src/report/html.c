/* report.html: the facts of report.json for a reader, with the pictures
 * drawn here and embedded, written atomically. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "report_internal.h"

static void esc(FILE *fp, const char *s)
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

static double pct(size_t a, size_t b)
{
    return b ? 100.0 * (double)a / (double)b : 0;
}

static const char *style =
    "body{font-family:sans-serif;margin:1.5em;color:#222;max-width:1500px}"
    "h1{font-size:1.5em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ccc}"
    "table{border-collapse:collapse;font-size:0.85em}"
    "td,th{border:1px solid #ddd;padding:2px 6px;vertical-align:top}"
    "th{background:#f2f2f2;text-align:left}td.n{text-align:right;white-space:nowrap}"
    ".sw{display:inline-block;width:0.9em;height:0.9em;margin:0 0.3em 0 1em;"
    "vertical-align:middle;border:1px solid #555}"
    ".b{padding:0 0.4em;border-radius:0.3em;color:#fff;white-space:nowrap}"
    ".w{color:#8a5a00}.why{color:#a33}figure{display:inline-block;margin:0 1em 1em 0}"
    "figcaption{font-size:0.85em;max-width:380px}img{display:block}";

static void colour(FILE *fp, rp_kind k)
{
    fprintf(fp, "#%02x%02x%02x", (int)lround(255 * rp_kind_rgb[k][0]),
            (int)lround(255 * rp_kind_rgb[k][1]), (int)lround(255 * rp_kind_rgb[k][2]));
}

static void badge(FILE *fp, const rp_fault *f)
{
    fputs("<span class=\"b\" style=\"background:", fp);
    colour(fp, f->kind);
    fputs("\">", fp);
    esc(fp, f->status);
    fputs("</span>", fp);
}

static void summary(FILE *fp, const fm_report *r, const size_t kinds[RP_NKINDS])
{
    fputs("<table>\n", fp);
    for (size_t i = 0; i + 1 < r->nfact; i += 2) {
        fputs("<tr><th>", fp);
        esc(fp, r->fact[i]);
        fputs("</th><td>", fp);
        esc(fp, r->fact[i + 1]);
        fputs("</td></tr>\n", fp);
    }
    fputs("<tr><th>faults by outcome</th><td>", fp);
    for (int k = 0; k < RP_NKINDS; k++) {
        fputs("<span class=\"sw\" style=\"background:", fp);
        colour(fp, (rp_kind)k);
        fprintf(fp, "\"></span>%s: %zu", rp_kind_label[k], kinds[k]);
    }
    fputs("</td></tr>\n</table>\n", fp);
}

static fm_status map_section(FILE *fp, const fm_report *r, const size_t kinds[RP_NKINDS])
{
    rp_png png;
    double km_per_px = 0;
    fm_status st = rp_draw_map(r, &png, &km_per_px);
    if (st != FM_OK)
        return st;
    fputs("<h2>Map</h2>\n<p>Every fault seen from above (x east, y north, ", fp);
    esc(fp, r->crs);
    fprintf(fp, "; %.3g km per pixel), the new meshes coloured by outcome and darker "
                "the steeper they dip; faults not meshed are drawn from their originals.</p>\n<p>",
            km_per_px);
    for (int k = 0; k < RP_NKINDS; k++) {
        fputs("<span class=\"sw\" style=\"background:", fp);
        colour(fp, (rp_kind)k);
        fprintf(fp, "\"></span>%s (%zu)", rp_kind_label[k], kinds[k]);
    }
    fputs("</p>\n", fp);
    rp_png_write_img(fp, &png, "map of the faults");
    rp_png_free(&png);
    fputc('\n', fp);
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
    esc(fp, caption);
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
    char cap[4][256];
    size_t below30 = a.under, in_band = 0, far = d.over;
    for (size_t i = 0; i < 30 && a.count; i++)
        below30 += a.count[i];
    for (size_t i = 0; i < e.nbins && e.count; i++)
        in_band += (i >= 14 && i < 28) ? e.count[i] : 0;
    for (size_t i = 20; i < d.nbins && d.count; i++)
        far += d.count[i];
    snprintf(cap[0], sizeof cap[0],
             "%zu triangles, %zu (%.3f%%) with an angle under 30 degrees (target: shaded).",
             a.total, below30, pct(below30, a.total));
    snprintf(cap[1], sizeof cap[1],
             "%zu edges (each once) at H = %g m, %.2f%% within [0.7, 1.4] H (shaded).", e.total,
             r->size, pct(in_band, e.total));
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
        fputs("<h2>Quality, size, fidelity and fit</h2>\n", fp);
    for (int k = 0; k < 4 && st == FM_OK; k++)
        st = figure(fp, h[k], cap[k]);
    rp_hist_free(&a);
    rp_hist_free(&e);
    rp_hist_free(&d);
    rp_hist_free(&c);
    return st;
}

static void junctions(FILE *fp, const fm_report *r)
{
    size_t n[4] = {0, 0, 0, 0};
    static const char *const types[4] = {"crossing", "T", "corner", "unjoined"};
    for (size_t i = 0; i < r->nj; i++)
        for (int t = 0; t < 4; t++)
            n[t] += !strcmp(r->j[i].type, types[t]);
    fprintf(fp, "<h2>Junctions</h2>\n<p>%zu junctions: %zu crossing, %zu T, %zu corner, %zu "
                "unjoined.</p>\n",
            r->nj, n[0], n[1], n[2], n[3]);
    if (!r->nj)
        return;
    fputs("<table>\n<tr><th>#</th><th>fault</th><th>fault</th><th>type</th><th>gap closed, m</th>"
          "<th>overshoot trimmed, m</th><th>curve length, m</th><th>min crossing angle, "
          "deg</th><th>reason</th></tr>\n",
          fp);
    for (size_t i = 0; i < r->nj; i++) {
        const rp_junction *j = &r->j[i];
        fprintf(fp, "<tr><td class=\"n\">%zu</td><td>", i);
        esc(fp, j->fault[0]);
        fputs("</td><td>", fp);
        esc(fp, j->fault[1]);
        fputs("</td><td>", fp);
        esc(fp, j->type);
        fprintf(fp, "</td><td class=\"n\">%.0f</td><td class=\"n\">%.0f</td><td class=\"n\">%.0f"
                    "</td><td class=\"n\">%.1f</td><td>",
                j->gap, j->overshoot, j->length, j->min_angle);
        esc(fp, j->reason);
        fputs("</td></tr>\n", fp);
    }
    fputs("</table>\n", fp);
}

static void problems(FILE *fp, const fm_report *r)
{
    fputs("<h2>Failed, dropped, excluded, unjoined</h2>\n<ul>\n", fp);
    size_t n = 0;
    for (size_t i = 0; i < r->nf; i++) {
        const rp_fault *f = &r->f[i];
        if (f->kind != RP_FAILED && f->kind != RP_DROPPED && f->kind != RP_EMPTY &&
            f->kind != RP_EXCLUDED && !f->join_error && !f->carved)
            continue;
        n++;
        fputs("<li><b>", fp);
        esc(fp, f->name);
        fputs("</b> ", fp);
        badge(fp, f);
        fputs(" <span class=\"why\">", fp);
        if (f->reason)
            esc(fp, f->reason);
        if (f->join_error) {
            fputs(f->reason ? "; " : "", fp);
            fputs("shared curves left out: ", fp);
            esc(fp, f->join_error);
        }
        if (f->carved)
            fprintf(fp, "%s%zu triangles (%.2f km&sup2;) removed where it ran through another "
                        "fault",
                    f->reason || f->join_error ? "; " : "", f->carved, f->carved_area / 1e6);
        fputs("</span></li>\n", fp);
    }
    for (size_t i = 0; i < r->nj; i++) {
        const rp_junction *j = &r->j[i];
        if (strcmp(j->type, "unjoined"))
            continue;
        n++;
        fprintf(fp, "<li>junction %zu, <b>", i);
        esc(fp, j->fault[0]);
        fputs("</b> / <b>", fp);
        esc(fp, j->fault[1]);
        fputs("</b>: unjoined <span class=\"why\">", fp);
        esc(fp, j->reason ? j->reason : "no reason recorded");
        fputs("</span></li>\n", fp);
    }
    if (!n)
        fputs("<li>none</li>\n", fp);
    fputs("</ul>\n", fp);
}

static void figures(FILE *fp, const rp_fault *f)
{
    if (strcmp(f->status, "ok")) {
        fputs("<td colspan=\"7\" class=\"why\">", fp);
        esc(fp, f->reason ? f->reason : "");
        fputs("</td>", fp);
        return;
    }
    const fm_quality *q = &f->q;
    fprintf(fp,
            "<td class=\"n\">%zu</td><td class=\"n\">%.1f</td><td class=\"n\">%.2f</td>"
            "<td class=\"n\">%.1f</td><td class=\"n\">%.1f / %.1f</td><td class=\"n\">%.3f</td>"
            "<td>",
            q->triangles, q->angle_min, pct(q->below_30, q->triangles),
            pct(q->edges_in_band, q->edges), f->fid.rms, f->fid.max,
            f->fitted_area > 0 ? q->area / f->fitted_area : 0);
    for (size_t k = 0; k < f->nwarnings; k++) {
        fputs("<div class=\"w\">", fp);
        esc(fp, f->warnings[k]);
        fputs("</div>", fp);
    }
    if (f->carved)
        fprintf(fp, "<div>%zu triangles carved</div>", f->carved);
    /* what connecting cost it (report.json's connect_measures), when anything */
    const fm_loss_fault *l = &f->loss;
    if (f->has_loss && l->missing_area > 0)
        fprintf(fp, "<div>original area missing: %.3f km&sup2; (%.2f%%), %.3f km&sup2; of it "
                    "away from other faults</div>",
                l->missing_area / 1e6, l->orig_area > 0 ? 100 * l->missing_area / l->orig_area : 0,
                l->missing_away / 1e6);
    if (f->has_loss && l->islands)
        fprintf(fp, "<div>%zu island%s (%zu triangles)</div>", l->islands,
                l->islands > 1 ? "s" : "", l->island_triangles);
    if (f->has_loss && l->moved_max > FM_FIDELITY_TOL)
        fprintf(fp, "<div class=\"w\">inside of the original moved %.0f m</div>", l->moved_max);
    if (f->has_loss && l->gap > 0)
        fprintf(fp, "<div>outline left beside other faults: %.1f km</div>", l->gap / 1e3);
    if (f->join_error) {
        fputs("<div class=\"why\">", fp);
        esc(fp, f->join_error);
        fputs("</div>", fp);
    }
    fputs("</td>", fp);
}

static fm_status faults(FILE *fp, const fm_report *r)
{
    rp_raster *ras = rp_fault_raster();
    rp_scene sc[2] = {{0}, {0}};
    fm_status st = ras ? FM_OK : FM_ERR_NOMEM;
    fputs("<h2>Faults</h2>\n<p>In the order of report.json. Each picture: the original (left) "
          "and the new mesh (right) at one scale, seen from the side its mean normal faces, "
          "22.5 degrees off square and 25 to 65 degrees above the horizon, its strike across "
          "the picture.</p>\n<table>\n<tr><th>fault</th><th>status</th>"
          "<th>original | new mesh</th><th>triangles</th><th>min angle, deg</th>"
          "<th>% under 30 deg</th><th>% edges in [0.7, 1.4] H</th><th>node distance rms / "
          "max, m</th><th>coverage (area / fitted)</th><th>warnings</th></tr>\n",
          fp);
    for (size_t i = 0; st == FM_OK && i < r->nf; i++) {
        const rp_fault *f = &r->f[i];
        fputs("<tr><td><b>", fp);
        esc(fp, f->name);
        fputs("</b><br><small>", fp);
        esc(fp, f->file);
        fputs("</small></td><td>", fp);
        badge(fp, f);
        fputs("</td><td>", fp);
        if (f->original || f->tag >= 0) {
            rp_png png;
            fm_status drawn = rp_draw_fault(r, f, ras, sc, &png);
            if (drawn == FM_OK)
                rp_png_write_img(fp, &png, "original and new mesh");
            else if (drawn == FM_ERR_NOMEM)
                st = drawn;
            rp_png_free(&png);
        }
        fputs("</td>", fp);
        figures(fp, f);
        fputs("</tr>\n", fp);
    }
    fputs("</table>\n", fp);
    rp_scene_free(&sc[0]);
    rp_scene_free(&sc[1]);
    rp_raster_destroy(ras);
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
    esc(fp, r->title);
    fprintf(fp, "</title>\n<style>%s</style>\n</head>\n<body>\n<h1>", style);
    esc(fp, r->title);
    fputs("</h1>\n", fp);
    summary(fp, r, kinds);
    fm_status st = map_section(fp, r, kinds);
    if (st == FM_OK)
        st = histograms(fp, r);
    if (st == FM_OK) {
        junctions(fp, r);
        problems(fp, r);
        st = faults(fp, r);
    }
    fputs("</body>\n</html>\n", fp);
    if (st != FM_OK) {
        fm_atomic_abort(af);
        return fm_error_set(err, st, path, 0, "out of memory drawing the report");
    }
    return fm_atomic_commit(af, err);
}
