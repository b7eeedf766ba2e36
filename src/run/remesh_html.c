/* DIR/report.html of `faultmesh remesh`: the run's facts handed to the
 * report module as plain data, the same facts report.json records but
 * no times (the page must not depend on the thread count) and no paths
 * but file names (two runs into different folders give the same page). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_report.h"
#include "run_internal.h"

static const char *base_name(const char *path)
{
    const char *s = path ? strrchr(path, '/') : NULL;
    return s ? s + 1 : path;
}

/* msg with every whole occurrence of path written as its file name (the
 * reasons name the input as given, often an absolute path); malloc'ed,
 * NULL for a NULL msg or when memory runs out. */
static char *names_only(const char *msg, const char *path)
{
    if (!msg)
        return NULL;
    const char *base = base_name(path);
    size_t n = path ? strlen(path) : 0, b = base ? strlen(base) : 0;
    char *out = malloc(strlen(msg) + 1);
    if (!out)
        return NULL;
    size_t w = 0;
    for (const char *p = msg; *p;) {
        if (n > b && !strncmp(p, path, n)) {
            memcpy(out + w, base, b);
            w += b;
            p += n;
        } else {
            out[w++] = *p++;
        }
    }
    out[w] = 0;
    return out;
}

static fm_status add_faults(fm_report *rep, const run_state *rs, fm_error *err)
{
    fm_status st = FM_OK;
    for (size_t i = 0; st == FM_OK && i < rs->nres; i++) {
        const fault_result *r = &rs->res[i];
        char *reason = names_only(r->error, r->file);
        char *join_error = names_only(r->join_error, r->file);
        int ok = r->status && !strcmp(r->status, "ok");
        char w[FM_MAX_WARNINGS][160];
        const char *warn[3] = {w[0], w[1], w[2]};
        fm_report_fault f = {
            .name = r->name,
            .file = base_name(r->file),
            .status = r->status ? r->status : "error",
            .reason = reason ? reason : r->error ? "(out of memory)" : NULL,
            .warnings = warn,
            .nwarnings = ok ? (size_t)fault_warnings(r, w) : 0,
            .join_error = join_error ? join_error : r->join_error ? "(out of memory)" : NULL,
            .tag = r->set_index == SIZE_MAX ? -1 : (int32_t)r->set_index,
            .original = r->orig,
            .sheets = r->sheets,
            .quality = r->q,
            .fidelity = r->fid,
            .fitted_area = r->fitted_area,
            .carved = r->carved,
            .carved_area = r->carved_area,
            .loss = rs->loss && r->set_index < rs->nfaults ? fm_loss_fault_at(rs->loss, r->set_index)
                                                            : NULL,
        };
        st = fm_report_add_fault(rep, &f, err);
        free(reason);
        free(join_error);
    }
    return st;
}

/* The junction table as report.json has it (json_connect). */
static fm_status add_junctions(fm_report *rep, const run_state *rs, fm_error *err)
{
    fm_status st = FM_OK;
    size_t nj = rs->plan ? fm_connect_plan_njunctions(rs->plan) : 0;
    for (size_t i = 0; st == FM_OK && i < nj; i++) {
        const fm_connect_junction *jn = fm_connect_plan_junction(rs->plan, i);
        const char *why;
        size_t which;
        fm_junction_type t = junction_outcome(rs, jn, &why, &which);
        const char *a = rs->res[rs->plan_res[jn->fault[0]]].name;
        const char *b = rs->res[rs->plan_res[jn->fault[1]]].name;
        int cleared = jn->clearance > 0 && which == SIZE_MAX;
        char msg[900];
        msg[0] = '\0';
        if (why && which != SIZE_MAX)
            snprintf(msg, sizeof msg, "%s (%s)", why, rs->res[rs->plan_res[which]].name);
        else if (why)
            snprintf(msg, sizeof msg, "%s", why);
        if (cleared) {
            size_t len = strlen(msg);
            snprintf(msg + len, sizeof msg - len, "%sa gap of %.0f m is left: %s stops short",
                     len ? "; " : "", jn->clearance,
                     rs->res[rs->plan_res[jn->fault[jn->short_side]]].name);
        }
        fm_report_junction row = {
            .fault = {a, b},
            .type = fm_junction_type_name(t),
            .gap_closed = t == FM_JUNCTION_UNJOINED ? 0 : jn->gap,
            .overshoot_trimmed = t != FM_JUNCTION_UNJOINED ? jn->overshoot
                                 : cleared                 ? jn->overshoot + jn->clearance
                                                           : 0,
            .length = jn->length,
            .min_angle = jn->min_angle,
            .reason = msg[0] ? msg : NULL,
        };
        st = fm_report_add_junction(rep, &row, err);
    }
    return st;
}

static fm_status fact(fm_report *rep, fm_error *err, const char *label, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static fm_status fact(fm_report *rep, fm_error *err, const char *label, const char *fmt, ...)
{
    char v[600];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(v, sizeof v, fmt, ap);
    va_end(ap);
    return fm_report_add_fact(rep, label, v, err);
}

static fm_status add_facts(fm_report *rep, const remesh_cli *cli, const run_state *rs,
                           fm_error *err)
{
    run_totals t;
    run_totals_of(rs, &t);
    const char *top = cli->mesh.top == FM_TOP_CUT ? "cut at sea level"
                      : cli->mesh.top == FM_TOP_KEEP ? "kept"
                                                     : "extended up to sea level, then cut";
    fm_status st = fact(rep, err, "faultmesh", "%s", FM_VERSION_STRING);
    if (st == FM_OK)
        st = fact(rep, err, "target edge length H", "%g m%s", cli->mesh.size,
                  cli->settings_path ? " (faults the settings file names may differ)" : "");
    if (st == FM_OK && cli->mesh.top == FM_TOP_EXTEND)
        st = fact(rep, err, "top", "%s (tops within %g m)", top, cli->mesh.top_extend);
    else if (st == FM_OK)
        st = fact(rep, err, "top", "%s", top);
    if (st == FM_OK)
        st = fact(rep, err, "coordinate system", "%s (%s)", rs->crs ? rs->crs : "",
                  rs->crs_source ? rs->crs_source : "");
    if (st == FM_OK)
        st = fact(rep, err, "MSH tags", "%s", fm_msh_tags_name(cli->msh_tags));
    if (st == FM_OK)
        st = fact(rep, err, "faults",
                  "%zu read, %zu meshed (%zu with warnings), %zu dropped, %zu empty, %zu "
                  "excluded, %ld failed",
                  rs->nres, t.ok, t.warned, t.dropped, t.empty, t.excluded, rs->failed);
    if (st == FM_OK)
        st = fact(rep, err, "triangles",
                  "%zu; %zu (%.3f%%) with an angle under 30 degrees, %zu under 20 (%zu of them "
                  "at sharp outline corners)",
                  t.triangles, t.below30,
                  t.triangles ? 100.0 * (double)t.below30 / (double)t.triangles : 0, t.below20,
                  t.forced);
    if (st == FM_OK)
        st = fact(rep, err, "edges", "%zu; %.2f%% within [0.7, 1.4] H", t.edges,
                  t.edges ? 100.0 * (double)t.band / (double)t.edges : 0);
    if (st == FM_OK)
        st = fact(rep, err, "worst node distance to the original", "%.1f m%s%s", t.worst_dist,
                  t.worst_dist_fault ? ", " : "", t.worst_dist_fault ? t.worst_dist_fault : "");
    if (st == FM_OK && rs->plan)
        st = fact(rep, err, "connection",
                  "faults within %g m joined: %zu crossing, %zu T, %zu corner, %zu unjoined; "
                  "%zu near-duplicate faults given up; %zu shared nodes; %zu triangles carved "
                  "in %zu fault pairs, %zu between sheets of one fault",
                  cli->join, t.junctions[FM_JUNCTION_CROSSING], t.junctions[FM_JUNCTION_T],
                  t.junctions[FM_JUNCTION_CORNER], t.junctions[FM_JUNCTION_UNJOINED],
                  fm_connect_plan_get_stats(rs->plan)->duplicates,
                  fm_connect_plan_nnodes(rs->plan), t.carved, t.carved_pairs, t.carved_sheets);
    else if (st == FM_OK)
        st = fact(rep, err, "connection", "none: every fault meshed on its own");
    loss_totals lt;
    loss_totals_of(rs, &lt);
    if (st == FM_OK && rs->loss)
        st = fact(rep, err, "what connecting cost",
                  "outlines left beside another fault (unclosed gaps) %.1f km in %zu fault pairs "
                  "(%zu over 2 H); original area missing %.2f km\u00b2 (%.3f%%), %.2f "
                  "km\u00b2 of it away from every other fault; inside of an original moved up "
                  "to %.0f m; %zu islands in %zu faults; %zu intersection curves left unjoined",
                  lt.gap / 1e3, lt.gap_pairs, lt.gap_pairs_over_2H, lt.missing / 1e6,
                  lt.orig_area > 0 ? 100 * lt.missing / lt.orig_area : 0, lt.missing_away / 1e6,
                  lt.moved_max, lt.islands, lt.island_faults, lt.unjoined_curves);
    return st;
}

/* The elastic check's groups, numbered as report.json has them. */
static fm_status add_elastic(fm_report *rep, const remesh_cli *cli, const run_state *rs,
                             fm_error *err)
{
    if (!cli->elastic_check || !rs->elastic)
        return FM_OK;
    size_t nw, ng, np;
    fm_elastic_wrong_sign(rs->elastic, &nw);
    fm_report_set_elastic(rep, cli->elastic.fraction, nw);
    const fm_elastic_group *g = fm_elastic_groups(rs->elastic, &ng);
    const fm_elastic_pair *p = fm_elastic_pairs(rs->elastic, &np);
    fm_status st = FM_OK;
    for (size_t k = 0; st == FM_OK && k < ng; k++) {
        size_t ex[2 * FM_ELASTIC_EXAMPLES];
        for (size_t e = 0; e < g[k].nexamples; e++) {
            ex[2 * e] = p[g[k].example[e]].i + 1;
            ex[2 * e + 1] = p[g[k].example[e]].j + 1;
        }
        fm_report_elastic_group rg = {{rs->names[g[k].a], rs->names[g[k].b]}, g[k].junction,
                                      g[k].pairs, g[k].max_ratio, g[k].min_distance, ex,
                                      g[k].nexamples};
        st = fm_report_add_elastic_group(rep, &rg, err);
    }
    return st;
}

fm_status write_report_html(const remesh_cli *cli, const run_state *rs, fm_error *err)
{
    fm_report_info info = {"faultmesh report", rs->crs, cli->mesh.size};
    fm_report *rep = fm_report_create(rs->set, &info, err);
    if (!rep)
        return err->code;
    fm_status st = add_faults(rep, rs, err);
    if (st == FM_OK)
        st = add_junctions(rep, rs, err);
    if (st == FM_OK)
        st = add_facts(rep, cli, rs, err);
    if (st == FM_OK)
        st = add_elastic(rep, cli, rs, err);
    size_t n = strlen(cli->dir) + 32;
    char *path = st == FM_OK ? malloc(n) : NULL;
    if (st == FM_OK && !path)
        st = fm_error_set(err, FM_ERR_NOMEM, cli->dir, 0, "out of memory");
    if (st == FM_OK) {
        snprintf(path, n, "%s/report.html", cli->dir);
        st = fm_report_write_html(rep, path, err);
    }
    free(path);
    fm_report_destroy(rep);
    return st;
}
