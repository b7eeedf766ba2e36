/* The tables of report.html: the contents, the problems (what to look at
 * before trusting the set), every fault and every junction. Rows are
 * plain HTML, so the page reads without its script; the script sorts and
 * filters them and opens a fault's panel from its name (td.fn). Junctions
 * and faults are numbered from 1, as every output numbers them
 * (docs/formats.md). */
#include <stdlib.h>
#include <string.h>

#include "report_internal.h"

static int not_meshed(const rp_fault *f)
{
    return f->kind == RP_FAILED || f->kind == RP_DROPPED || f->kind == RP_EMPTY ||
           f->kind == RP_EXCLUDED;
}

static int cut_back(const rp_fault *f)
{
    return f->carved || f->join_error;
}

static size_t count_unjoined(const fm_report *r)
{
    size_t n = 0;
    for (size_t i = 0; i < r->nj; i++)
        n += !strcmp(r->j[i].type, "unjoined");
    return n;
}

void rp_toc(FILE *fp, const fm_report *r)
{
    size_t nm = 0, nw = 0, nc = 0;
    for (size_t i = 0; i < r->nf; i++) {
        nm += not_meshed(&r->f[i]);
        nw += r->f[i].nwarnings > 0;
        nc += cut_back(&r->f[i]);
    }
    fprintf(fp,
            "<nav class=\"toc\">Contents: <a href=\"#summary\">Summary</a>"
            "<a href=\"#problems\">Problems (%zu faults not meshed, %zu with warnings, %zu "
            "near-overlaps; %zu junctions unjoined)</a><a href=\"#map\">Map</a><a href=\"#quality\">"
            "Quality</a><a href=\"#faults\">Faults (%zu)</a><a href=\"#junctions\">Junctions "
            "(%zu)</a></nav>\n",
            nm, nw, nc, count_unjoined(r), r->nf, r->nj);
}

/* A fault's name, which opens its panel. */
static void name_cell(FILE *fp, const rp_fault *f)
{
    fputs("<td class=\"fn\">", fp);
    rp_esc(fp, f->name);
    fputs("</td>", fp);
}

static void filter_box(FILE *fp, const char *table, int col, const char *const *options,
                       size_t n)
{
    fprintf(fp, "<div class=\"filter\" data-for=\"%s\"><input type=\"search\" "
                "placeholder=\"filter: any text of a row\" aria-label=\"filter\">",
            table);
    if (n) {
        fprintf(fp, " <select data-col=\"%d\" aria-label=\"only\"><option value=\"\">all</option>",
                col);
        for (size_t i = 0; i < n; i++) {
            fputs("<option>", fp);
            rp_esc(fp, options[i]);
            fputs("</option>", fp);
        }
        fputs("</select>", fp);
    }
    fputs("<span class=\"shown\"></span></div>\n", fp);
}

/* Unjoined junctions by reason, the reason up to where it names a fault
 * or a distance. */
static void unjoined_reasons(FILE *fp, const fm_report *r)
{
    size_t nu = count_unjoined(r);
    fprintf(fp, "<h3>Unjoined junctions (%zu of %zu)</h3>\n", nu, r->nj);
    if (!nu) {
        fputs("<p>none</p>\n", fp);
        return;
    }
    fputs("<p>Pairs of faults within the join distance whose meshes do not share a curve, by "
          "reason; a link shows them in the junction table.</p>\n<table class=\"sort\">"
          "<thead><tr><th>reason</th><th>junctions</th></tr></thead><tbody>\n",
          fp);
    char (*key)[160] = calloc(nu, sizeof *key);
    size_t *count = calloc(nu, sizeof *count), nk = 0;
    for (size_t i = 0; key && count && i < r->nj; i++) {
        const rp_junction *j = &r->j[i];
        if (strcmp(j->type, "unjoined"))
            continue;
        const char *why = j->reason ? j->reason : "no reason recorded";
        size_t len = strlen(why);
        const char *p = strstr(why, " ("), *q = strstr(why, "; ");
        if (p && (size_t)(p - why) < len)
            len = (size_t)(p - why);
        if (q && (size_t)(q - why) < len)
            len = (size_t)(q - why);
        if (len >= sizeof key[0])
            len = sizeof key[0] - 1;
        size_t k = 0;
        while (k < nk && (strlen(key[k]) != len || strncmp(key[k], why, len)))
            k++;
        if (k == nk)
            memcpy(key[nk++], why, len);
        count[k]++;
    }
    for (size_t k = 0; k < nk; k++) {
        fputs("<tr><td><a href=\"#junctions\" data-for=\"junction-table\" data-sel=\"unjoined\" "
              "data-q=\"",
              fp);
        rp_esc(fp, key[k]);
        fputs("\">", fp);
        rp_esc(fp, key[k]);
        fprintf(fp, "</a></td><td class=\"n\">%zu</td></tr>\n", count[k]);
    }
    fputs("</tbody></table>\n", fp);
    free(key);
    free(count);
}

void rp_problems(FILE *fp, const fm_report *r)
{
    fputs("<h2 id=\"problems\">Problems</h2>\n", fp);
    size_t n = 0;
    for (size_t i = 0; i < r->nf; i++)
        n += not_meshed(&r->f[i]);
    fprintf(fp, "<h3>Faults not meshed (%zu)</h3>\n", n);
    if (n) {
        fputs("<p>Failed, above sea level, left out by the settings, or given up as a "
              "near-duplicate of another fault (one of a pair is given up when half the area of "
              "either lies within 50 m of the other, and the faults it pairs with cover half of "
              "it).</p>\n<table class=\"sort\"><thead><tr><th>fault</th><th>status</th>"
              "<th>why</th></tr></thead><tbody>\n",
              fp);
        for (size_t i = 0; i < r->nf; i++) {
            const rp_fault *f = &r->f[i];
            if (!not_meshed(f))
                continue;
            fputs("<tr>", fp);
            name_cell(fp, f);
            fputs("<td>", fp);
            rp_badge(fp, f);
            fputs("</td><td class=\"why\">", fp);
            rp_esc(fp, f->reason ? f->reason : "no reason recorded");
            fputs("</td></tr>\n", fp);
        }
        fputs("</tbody></table>\n", fp);
    }
    n = 0;
    for (size_t i = 0; i < r->nf; i++)
        n += r->f[i].nwarnings > 0;
    fprintf(fp, "<h3>Faults with warnings (%zu)</h3>\n", n);
    if (n) {
        fputs("<p>Meshed, but look at them before using them.</p>\n<div class=\"scroll\">"
              "<table class=\"sort\"><thead><tr><th>fault</th><th>status</th><th>warnings</th>"
              "</tr></thead><tbody>\n",
              fp);
        for (size_t i = 0; i < r->nf; i++) {
            const rp_fault *f = &r->f[i];
            if (!f->nwarnings)
                continue;
            fputs("<tr>", fp);
            name_cell(fp, f);
            fputs("<td>", fp);
            rp_badge(fp, f);
            fputs("</td><td>", fp);
            for (size_t k = 0; k < f->nwarnings; k++) {
                fputs(k ? "<br>" : "", fp);
                rp_esc(fp, f->warnings[k]);
            }
            fputs("</td></tr>\n", fp);
        }
        fputs("</tbody></table></div>\n", fp);
    }
    n = 0;
    for (size_t i = 0; i < r->nf; i++)
        n += cut_back(&r->f[i]);
    fprintf(fp, "<h3>Near-overlaps: faults cut back where they ran through another, or with "
                "shared curves left out (%zu)</h3>\n",
            n);
    if (n) {
        fputs("<div class=\"scroll\"><table class=\"sort\"><thead><tr><th>fault</th><th>status"
              "</th><th>triangles removed</th><th>area removed, km&sup2;</th><th>shared curves "
              "left out</th></tr></thead><tbody>\n",
              fp);
        for (size_t i = 0; i < r->nf; i++) {
            const rp_fault *f = &r->f[i];
            if (!cut_back(f))
                continue;
            fputs("<tr>", fp);
            name_cell(fp, f);
            fputs("<td>", fp);
            rp_badge(fp, f);
            fprintf(fp, "</td><td class=\"n\">%zu</td><td class=\"n\">%.3f</td><td class=\"why\">",
                    f->carved, f->carved_area / 1e6);
            rp_esc(fp, f->join_error);
            fputs("</td></tr>\n", fp);
        }
        fputs("</tbody></table></div>\n", fp);
    }
    unjoined_reasons(fp, r);
    rp_elastic(fp, r);
}

/* What else there is to know of a fault: why it is not meshed, its
 * warnings, what connecting cost it. */
static void notes(FILE *fp, const rp_fault *f)
{
    fputs("<td>", fp);
    if (f->reason) {
        fputs("<div class=\"why\">", fp);
        rp_esc(fp, f->reason);
        fputs("</div>", fp);
    }
    for (size_t k = 0; k < f->nwarnings; k++) {
        fputs("<div class=\"w\">", fp);
        rp_esc(fp, f->warnings[k]);
        fputs("</div>", fp);
    }
    if (f->carved)
        fprintf(fp, "<div>%zu triangles carved</div>", f->carved);
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
        fputs("<div class=\"why\">shared curves left out: ", fp);
        rp_esc(fp, f->join_error);
        fputs("</div>", fp);
    }
    fputs("</td>", fp);
}

void rp_fault_table(FILE *fp, const fm_report *r)
{
    fprintf(fp, "<h2 id=\"faults\">Faults (%zu)</h2>\n<p>In the order of report.json; # is the "
                "fault's number in every output (from 1). Click a name to see the fault, its "
                "junction curves and its neighbours.</p>\n",
            r->nf);
    const char *opts[RP_NKINDS];
    size_t nopts = 0;
    for (int k = 0; k < RP_NKINDS; k++)
        for (size_t i = 0; i < r->nf; i++)
            if (r->f[i].kind == (rp_kind)k) {
                opts[nopts++] = rp_kind_badge[k];
                break;
            }
    filter_box(fp, "fault-table", 2, opts, nopts);
    fputs("<table class=\"sort\" id=\"fault-table\"><thead><tr><th>#</th><th>fault</th>"
          "<th>status</th><th>triangles</th><th>min angle, deg</th><th>% under 30 deg</th>"
          "<th>% edges in [0.7, 1.4] H</th><th>node distance rms, m</th><th>node distance max, "
          "m</th><th>coverage (area / fitted)</th><th>notes</th></tr></thead><tbody>\n",
          fp);
    for (size_t i = 0; i < r->nf; i++) {
        const rp_fault *f = &r->f[i];
        fprintf(fp, "<tr id=\"fault-%zu\"><td class=\"n\">", i);
        if (f->tag >= 0)
            fprintf(fp, "%d", (int)f->tag + 1);
        fputs("</td>", fp);
        name_cell(fp, f);
        fputs("<td>", fp);
        rp_badge(fp, f);
        fputs("</td>", fp);
        if (!strcmp(f->status, "ok")) {
            const fm_quality *q = &f->q;
            fprintf(fp,
                    "<td class=\"n\">%zu</td><td class=\"n\">%.1f</td><td class=\"n\">%.2f</td>"
                    "<td class=\"n\">%.2f</td><td class=\"n\">%.1f</td><td class=\"n\">%.1f</td>"
                    "<td class=\"n\">%.3f</td>",
                    q->triangles, q->angle_min, rp_pct(q->below_30, q->triangles),
                    rp_pct(q->edges_in_band, q->edges), f->fid.rms, f->fid.max,
                    f->fitted_area > 0 ? q->area / f->fitted_area : 0);
        } else {
            fputs("<td></td><td></td><td></td><td></td><td></td><td></td><td></td>", fp);
        }
        notes(fp, f);
        fputs("</tr>\n", fp);
    }
    fputs("</tbody></table>\n", fp);
}

void rp_junction_table(FILE *fp, const fm_report *r)
{
    size_t n[4] = {0, 0, 0, 0};
    static const char *const types[4] = {"crossing", "T", "corner", "unjoined"};
    for (size_t i = 0; i < r->nj; i++)
        for (int t = 0; t < 4; t++)
            n[t] += !strcmp(r->j[i].type, types[t]);
    fprintf(fp, "<h2 id=\"junctions\">Junctions (%zu)</h2>\n<p>%zu junctions: %zu crossing, %zu T, "
                "%zu corner, %zu unjoined. # is the junction's number in report.json's list and "
                "in the junction curves of mesh.msh and mesh.exo (from 1).</p>\n",
            r->nj, r->nj, n[0], n[1], n[2], n[3]);
    if (!r->nj)
        return;
    filter_box(fp, "junction-table", 3, types, 4);
    fputs("<table class=\"sort\" id=\"junction-table\"><thead><tr><th>#</th><th>fault</th>"
          "<th>fault</th><th>type</th><th>gap closed, m</th><th>overshoot trimmed, m</th>"
          "<th>curve length, m</th><th>min crossing angle, deg</th><th>reason</th></tr></thead>"
          "<tbody>\n",
          fp);
    for (size_t i = 0; i < r->nj; i++) {
        const rp_junction *j = &r->j[i];
        fprintf(fp, "<tr><td class=\"n\">%zu</td><td class=\"fn\">", i + 1);
        rp_esc(fp, j->fault[0]);
        fputs("</td><td class=\"fn\">", fp);
        rp_esc(fp, j->fault[1]);
        fputs("</td><td>", fp);
        rp_esc(fp, j->type);
        fprintf(fp, "</td><td class=\"n\">%.0f</td><td class=\"n\">%.0f</td><td class=\"n\">%.0f"
                    "</td><td class=\"n\">%.1f</td><td>",
                j->gap, j->overshoot, j->length, j->min_angle);
        rp_esc(fp, j->reason);
        fputs("</td></tr>\n", fp);
    }
    fputs("</tbody></table>\n", fp);
}
