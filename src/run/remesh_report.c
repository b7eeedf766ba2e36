/* A run: what each fault and junction came to, in the summary text
 * (fm_run_result_summary; the CLI prints it on stdout), the per-fault log
 * record and report.json. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "remesh_quads.h"
#include "fm_atomic.h"
#include "fm_json.h"
#include "run_internal.h"

/* The name --top and the settings file give a top mode. */
static const char *top_name(fm_top_mode t)
{
    return t == FM_TOP_CUT ? "cut" : t == FM_TOP_KEEP ? "keep" : "extend";
}

/* What a user should look at before trusting a meshed fault: the figures
 * of the check that the mesh issue bounds, when this fault breaks them.
 * Writes up to three messages into w (each up to 160 bytes); returns the
 * count. Nodes of an extended top lie off the original by design. */
int fault_warnings(const fault_result *r, char w[FM_MAX_WARNINGS][160])
{
    int n = 0;
    /* A node past the original's edge is expected where the fault closes
     * a gap to a curve it shares, and at an extended top; over the
     * original's inside, or past its edge on a fault joined to nothing,
     * it means the fit departs from the original. */
    if (r->fid.inside_max > 100.0 && r->ms.extended == 0)
        snprintf(w[n++], 160,
                 "nodes up to %.0f m from the original surface (the fitted surface departs from it)",
                 r->fid.inside_max);
    if (r->fid.beyond_max > 100.0 && r->ms.extended == 0 && r->nused == 0)
        snprintf(w[n++], 160,
                 "nodes up to %.0f m past the original's edge (the fitted outline bulges out)",
                 r->fid.beyond_max);
    /* A size near the fault's own extent leaves a few triangles that
     * follow neither its outline nor its shape. */
    if (r->expected > 0 && r->expected < 8)
        snprintf(w[n++], 160, "size %g m is %s the fault: its %.3g km2 call for %.2g triangles",
                 r->mesh.size, r->expected < 1 ? "larger than" : "about the extent of",
                 r->fitted_area / 1e6, r->expected);
    size_t loose = r->q.below_20 - r->q.below_20_forced;
    if (loose > 0)
        snprintf(w[n++], 160,
                 "%zu triangles under 20 degrees away from sharp outline corners (junction "
                 "nodes among them)",
                 loose);
    return n;
}

static void print_fault(FILE *out, const fault_result *r)
{
    if (strcmp(r->status, "ok")) {
        fprintf(out, "%-64s %s%s%s\n", r->name ? r->name : r->file, r->status, r->error ? ": " : "",
               r->error ? r->error : "");
        return;
    }
    fprintf(out, "%-64s %7zu tri  min %5.1f deg  <30 %5.2f%%  edges in band %5.1f%%  node dist "
           "%5.1f/%6.1f m%s\n",
           r->name, r->q.triangles, r->q.angle_min,
           100.0 * (double)r->q.below_30 / (double)(r->q.triangles ? r->q.triangles : 1),
           100.0 * (double)r->q.edges_in_band / (double)(r->q.edges ? r->q.edges : 1), r->fid.rms,
           r->fid.max, r->ms.cut ? "  cut" : "");
    char w[FM_MAX_WARNINGS][160];
    int nw = fault_warnings(r, w);
    for (int k = 0; k < nw; k++)
        fprintf(out, "    warning: %s\n", w[k]);
}

void log_fault(run_ctl *ctl, const fault_result *r)
{
    char *text = NULL;
    size_t n = 0;
    FILE *out = open_memstream(&text, &n);
    if (!out)
        return;
    print_fault(out, r);
    fclose(out);
    if (n && text[n - 1] == '\n')
        text[n - 1] = 0;
    run_log(ctl, FM_LOG_DETAIL, "%s", text);
    free(text);
}

static void json_carve(fm_json *j, const run_state *rs)
{
    if (!rs->carve)
        return;
    fm_json_kv_int(j, "carved_triangles", (int64_t)fm_carve_removed(rs->carve));
    fm_json_kv_int(j, "carved_slivers_at_notches", (int64_t)fm_carve_slivers(rs->carve));
    fm_json_key(j, "carved");
    fm_json_begin_array(j);
    for (size_t k = 0; k < fm_carve_npairs(rs->carve); k++) {
        const fm_carve_pair *p = fm_carve_pair_at(rs->carve, k);
        fm_json_begin_object(j);
        fm_json_key(j, "faults");
        fm_json_begin_array(j);
        for (int s = 0; s < 2; s++)
            fm_json_string(j, rs->res[rs->set_res[p->fault[s]]].name);
        fm_json_end_array(j);
        fm_json_kv_int(j, "triangle_pairs_met", (int64_t)p->contacts);
        if (p->kept) {
            fm_json_key(j, "removed_from");
            fm_json_null(j);
        } else {
            fm_json_kv_string(j, "removed_from", rs->res[rs->set_res[p->fault[p->yielded]]].name);
        }
        fm_json_kv_int(j, "triangles_removed", (int64_t)p->removed);
        fm_json_kv_number(j, "area_removed_m2", p->area);
        fm_json_kv_string(j, "reason",
                          p->kept ? "the two meshes run through each other away from any curve "
                                    "they share, and are kept so: either would have lost every "
                                    "triangle it had left (the size is near their extent)"
                                  : "the two meshes ran through each other away from any curve "
                                    "they share; the one losing the smaller share of its area "
                                    "gives way there");
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    if (!rs->sheet_carve)
        return;
    fm_json_kv_int(j, "carved_between_sheets_triangles", (int64_t)fm_carve_removed(rs->sheet_carve));
    fm_json_key(j, "carved_between_sheets");
    fm_json_begin_array(j);
    for (size_t k = 0; k < fm_carve_npairs(rs->sheet_carve); k++) {
        const fm_carve_pair *p = fm_carve_pair_at(rs->sheet_carve, k);
        int32_t f = rs->sheet_unit_fault[p->fault[0]];
        fm_json_begin_object(j);
        fm_json_kv_string(j, "fault", rs->res[rs->set_res[f]].name);
        fm_json_key(j, "sheets");
        fm_json_begin_array(j);
        for (int s2 = 0; s2 < 2; s2++)
            fm_json_int(j, (int64_t)(p->fault[s2] - rs->sheet_unit_first[f]) + 1);
        fm_json_end_array(j);
        fm_json_kv_int(j, "triangle_pairs_met", (int64_t)p->contacts);
        if (p->kept) {
            fm_json_key(j, "removed_from_sheet");
            fm_json_null(j);
        } else {
            fm_json_kv_int(j, "removed_from_sheet",
                           (int64_t)(p->fault[p->yielded] - rs->sheet_unit_first[f]) + 1);
        }
        fm_json_kv_int(j, "triangles_removed", (int64_t)p->removed);
        fm_json_kv_number(j, "area_removed_m2", p->area);
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
}

static void json_quality(fm_json *j, const fault_result *r, double H)
{
    const fm_quality *q = &r->q;
    fm_json_key(j, "quality");
    fm_json_begin_object(j);
    fm_json_kv_number(j, "min_angle_deg", q->angle_min);
    fm_json_kv_number(j, "mean_min_angle_deg", q->angle_mean);
    fm_json_kv_int(j, "triangles_below_30_deg", (int64_t)q->below_30);
    fm_json_kv_int(j, "triangles_below_20_deg", (int64_t)q->below_20);
    fm_json_kv_int(j, "triangles_below_20_deg_at_sharp_corners", (int64_t)q->below_20_forced);
    fm_json_kv_int(j, "sharp_corners", (int64_t)q->sharp_corners);
    fm_json_end_object(j);
    fm_json_key(j, "size");
    fm_json_begin_object(j);
    fm_json_kv_number(j, "target_m", H);
    fm_json_kv_int(j, "edges", (int64_t)q->edges);
    fm_json_kv_int(j, "edges_within_0.7_1.4", (int64_t)q->edges_in_band);
    fm_json_kv_number(j, "edge_min_m", q->edge_min);
    fm_json_kv_number(j, "edge_p05_m", q->edge_p05);
    fm_json_kv_number(j, "edge_median_m", q->edge_median);
    fm_json_kv_number(j, "edge_p95_m", q->edge_p95);
    fm_json_kv_number(j, "edge_max_m", q->edge_max);
    fm_json_end_object(j);
}

static void json_fault(fm_json *j, const remesh_cli *cli, const run_state *rs,
                       const fault_result *r, double H, const sim_attrs *sa)
{
    fm_json_begin_object(j);
    fm_json_kv_string(j, "file", r->file ? r->file : "");
    if (r->name)
        fm_json_kv_string(j, "name", r->name);
    /* meshed, but a file it should be in was not written */
    int incomplete = r->status && !strcmp(r->status, "ok") && r->set_index != SIZE_MAX &&
                     !outputs_complete(rs->outputs, r->set_index);
    fm_json_kv_string(j, "status", incomplete ? "incomplete" : r->status ? r->status : "error");
    if (incomplete)
        outputs_json_missing(j, rs->outputs, r->set_index);
    if (r->error)
        fm_json_kv_string(j, "error", r->error);
    cache_json_fault(j, r);
    if (r->fc.line) {
        /* what the settings file changed for it, and where */
        fm_json_key(j, "settings");
        fm_json_begin_object(j);
        fm_json_kv_int(j, "last_section_line", r->fc.line);
        if (r->fc.has_size)
            fm_json_kv_number(j, "size_m", r->fc.size);
        if (r->fc.has_top)
            fm_json_kv_string(j, "top", top_name(r->fc.top));
        if (r->fc.has_top && r->fc.top == FM_TOP_EXTEND)
            fm_json_kv_number(j, "top_extend_m", r->fc.top_extend);
        if (r->fc.has_join)
            fm_json_kv_number(j, "join_distance_m", r->fc.join);
        if (r->fc.has_connect)
            fm_json_kv_bool(j, "connect", r->fc.connect);
        if (r->fc.has_exclude)
            fm_json_kv_bool(j, "exclude", r->fc.exclude);
        if (r->fc.has_rake)
            fm_json_kv_number(j, "rake_deg", r->fc.rake);
        if (r->fc.has_rate)
            fm_json_kv_number(j, "slip_rate_mm_yr", r->fc.slip_rate_mm_yr);
        fm_json_end_object(j);
    }
    if (r->status && !strcmp(r->status, "ok")) {
        fm_json_kv_int(j, "sheets", (int64_t)r->sheets);
        fm_json_kv_int(j, "triangles", (int64_t)r->q.triangles);
        fm_json_kv_int(j, "nodes", (int64_t)r->q.nodes);
        if (r->carved) {
            fm_json_kv_int(j, "carved_triangles", (int64_t)r->carved);
            fm_json_kv_number(j, "carved_area_m2", r->carved_area);
        }
        /* flaps beyond curves it ends at that reach farther than its join
         * distance: not overshoots, so kept */
        if (r->ms.flaps_kept) {
            fm_json_kv_int(j, "flaps_kept", (int64_t)r->ms.flaps_kept);
        }
        char w[FM_MAX_WARNINGS][160];
        int nw = fault_warnings(r, w);
        fm_json_key(j, "warnings");
        fm_json_begin_array(j);
        for (int k = 0; k < nw; k++)
            fm_json_string(j, w[k]);
        fm_json_end_array(j);
        if (r->join_error)
            fm_json_kv_string(j, "join_error", r->join_error);
        fm_json_kv_number(j, "area_m2", r->q.area);
        json_quality(j, r, H);
        fm_json_key(j, "fidelity");
        fm_json_begin_object(j);
        fm_json_kv_number(j, "node_to_original_rms_m", r->fid.rms);
        fm_json_kv_number(j, "node_to_original_max_m", r->fid.max);
        /* Nodes farther than 100 m whose nearest original point is on
         * (within 100 m of) its outline lie past the original's edge (a
         * fault extended over a closed gap): their largest distance is
         * reported apart from that of the nodes over its inside, so the
         * fidelity proper can be told from the extent of what was filled
         * beyond the edge. */
        fm_json_kv_number(j, "inside_outline_max_m", r->fid.inside_max);
        fm_json_kv_int(j, "inside_outline_nodes_over_100_m", (int64_t)r->fid.inside_over);
        fm_json_kv_number(j, "beyond_outline_max_m", r->fid.beyond_max);
        fm_json_kv_int(j, "beyond_outline_nodes_over_100_m", (int64_t)r->fid.beyond_nodes);
        fm_json_kv_number(j, "fitted_area_m2", r->fitted_area);
        fm_json_kv_number(j, "coverage", r->fitted_area > 0 ? r->q.area / r->fitted_area : 0);
        fm_json_end_object(j);
        fm_json_key(j, "top");
        fm_json_begin_object(j);
        fm_json_kv_bool(j, "cut", r->ms.cut);
        fm_json_kv_int(j, "sea_level_nodes", (int64_t)r->ms.level_points);
        fm_json_kv_number(j, "z_max_m", r->q.zmax);
        fm_json_kv_int(j, "nodes_lowered_to_sea_level", (int64_t)r->ms.clamped);
        fm_json_kv_number(j, "largest_lowering_m", r->ms.clamp_max);
        fm_json_kv_number(j, "extended_m", r->ms.extended);
        fm_json_end_object(j);
        fm_json_key(j, "time_s");
        fm_json_begin_object(j);
        fm_json_kv_number(j, "fit", r->t_fit);
        fm_json_kv_number(j, "mesh", r->t_mesh);
        fm_json_kv_number(j, "check", r->t_check);
        fm_json_end_object(j);
        json_loss_fault(j, rs, r);
    }
    if (sa && r->set_index < sa->nfaults)
        sim_json_fault(j, &cli->sim, sa, r->set_index);
    fm_json_end_object(j);
}

static void json_connect(fm_json *j, const remesh_cli *cli, const run_state *rs,
                         const run_totals *tot)
{
    fm_json_key(j, "connect");
    fm_json_begin_object(j);
    fm_json_kv_bool(j, "enabled", cli->connect && rs->plan);
    fm_json_kv_number(j, "join_distance_m", cli->join);
    if (!rs->plan) {
        fm_json_end_object(j);
        return;
    }
    const fm_connect_plan_stats *ps = fm_connect_plan_get_stats(rs->plan);
    fm_json_kv_int(j, "sheet_pairs_within_join_distance", (int64_t)ps->pairs);
    fm_json_kv_int(j, "near_duplicates_given_up", (int64_t)ps->duplicates);
    fm_json_kv_int(j, "shared_nodes", (int64_t)fm_connect_plan_nnodes(rs->plan));
    fm_json_key(j, "junctions");
    fm_json_begin_array(j);
    for (size_t i = 0; i < fm_connect_plan_njunctions(rs->plan); i++) {
        const fm_connect_junction *jn = fm_connect_plan_junction(rs->plan, i);
        const char *why;
        size_t which;
        fm_junction_type t = junction_outcome(rs, jn, &why, &which);
        fm_json_begin_object(j);
        fm_json_key(j, "faults");
        fm_json_begin_array(j);
        for (int s = 0; s < 2; s++)
            fm_json_string(j, rs->res[rs->plan_res[jn->fault[s]]].name);
        fm_json_end_array(j);
        fm_json_key(j, "sheets");
        fm_json_begin_array(j);
        for (int s = 0; s < 2; s++)
            fm_json_int(j, (int64_t)jn->sheet[s] + 1); /* from 1, as the VTU's sheet */
        fm_json_end_array(j);
        fm_json_kv_string(j, "type", fm_junction_type_name(t));
        /* how each sheet meets the curve, whatever was made of it: tells a
         * reader which fault was meant to end on the other (pairs that never
         * meet have no curve and no roles) */
        if (jn->length > 0) {
            fm_json_key(j, "roles");
            fm_json_begin_array(j);
            for (int s = 0; s < 2; s++)
                fm_json_string(j, jn->role[s] == FM_CONNECT_THROUGH     ? "through"
                                  : jn->role[s] == FM_CONNECT_OVERSHOOT ? "overshoot"
                                                                        : "gap");
            fm_json_end_array(j);
        }
        /* a sheet stopped short of the other lost its flap past it too */
        int cleared = jn->clearance > 0 && which == SIZE_MAX;
        fm_json_kv_number(j, "gap_closed_m", t == FM_JUNCTION_UNJOINED ? 0 : jn->gap);
        fm_json_kv_number(j, "overshoot_trimmed_m",
                          t != FM_JUNCTION_UNJOINED ? jn->overshoot
                          : cleared                 ? jn->overshoot + jn->clearance
                                                    : 0);
        fm_json_kv_number(j, "curve_length_m", jn->length);
        /* what the two meshes hold of it: less where a sheet's domain or its
         * other curves cut it, or a fill was clipped to its partner's */
        if (t != FM_JUNCTION_UNJOINED && jn->curve >= 0)
            fm_json_kv_number(j, "shared_length_m",
                              shared_length(&rs->res[rs->plan_res[jn->fault[0]]],
                                            &rs->res[rs->plan_res[jn->fault[1]]],
                                            (size_t)jn->curve, fm_connect_plan_nodes(rs->plan)));
        fm_json_kv_number(j, "min_crossing_angle_deg", jn->min_angle);
        if (jn->distance > 0)
            fm_json_kv_number(j, "surface_distance_m", jn->distance);
        if (cleared) {
            fm_json_kv_number(j, "gap_left_m", jn->clearance);
            fm_json_kv_string(j, "stops_short",
                              rs->res[rs->plan_res[jn->fault[jn->short_side]]].name);
        }
        /* faults that were to end at the curve but run on past it */
        int kept[2] = {0, 0};
        for (int s = 0; s < 2 && t != FM_JUNCTION_UNJOINED; s++) {
            const fault_result *fr = &rs->res[rs->plan_res[jn->fault[s]]];
            for (size_t k = 0; k < fr->nthrough; k++)
                kept[s] |= fr->through_curves[k] == (size_t)jn->curve;
        }
        if (kept[0] || kept[1]) {
            fm_json_key(j, "flap_kept");
            fm_json_begin_array(j);
            for (int s = 0; s < 2; s++)
                if (kept[s])
                    fm_json_string(j, rs->res[rs->plan_res[jn->fault[s]]].name);
            fm_json_end_array(j);
        }
        if (why) {
            char msg[600];
            const fault_result *wr = which != SIZE_MAX ? &rs->res[rs->plan_res[which]] : NULL;
            if (wr && why == wr->error)
                snprintf(msg, sizeof msg, "%s %s: %s", wr->name,
                         strcmp(wr->status, "empty") ? "failed" : "has no mesh", why);
            else if (wr)
                snprintf(msg, sizeof msg, "%s (%s)", why, wr->name);
            fm_json_kv_string(j, "reason", which != SIZE_MAX ? msg : why);
        }
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    fm_json_kv_int(j, "crossing", (int64_t)tot->junctions[FM_JUNCTION_CROSSING]);
    fm_json_kv_int(j, "T", (int64_t)tot->junctions[FM_JUNCTION_T]);
    fm_json_kv_int(j, "corner", (int64_t)tot->junctions[FM_JUNCTION_CORNER]);
    fm_json_kv_int(j, "unjoined", (int64_t)tot->junctions[FM_JUNCTION_UNJOINED]);
    json_carve(j, rs);
    json_loss(j, rs);
    fm_json_end_object(j);
}

void run_totals_of(const run_state *rs, run_totals *t)
{
    memset(t, 0, sizeof *t);
    t->angle_min = INFINITY;
    t->zmax = -INFINITY;
    for (size_t i = 0; i < rs->nres; i++) {
        const fault_result *r = &rs->res[i];
        const char *st = r->status ? r->status : "error";
        if (!strcmp(st, "dropped"))
            t->dropped++;
        else if (!strcmp(st, "empty"))
            t->empty++;
        else if (!strcmp(st, "excluded"))
            t->excluded++;
        if (strcmp(st, "ok"))
            continue;
        t->ok++;
        char w[FM_MAX_WARNINGS][160];
        t->warned += fault_warnings(r, w) > 0;
        t->sheets += r->sheets;
        t->triangles += r->q.triangles;
        t->below30 += r->q.below_30;
        t->below20 += r->q.below_20;
        t->forced += r->q.below_20_forced;
        t->edges += r->q.edges;
        t->band += r->q.edges_in_band;
        if (r->q.triangles && r->q.angle_min < t->angle_min) {
            t->angle_min = r->q.angle_min;
            t->angle_min_fault = r->name;
        }
        if (r->fid.max > t->worst_dist) {
            t->worst_dist = r->fid.max;
            t->worst_dist_fault = r->name;
        }
        t->zmax = fmax(t->zmax, r->q.zmax);
    }
    for (size_t i = 0; rs->plan && i < fm_connect_plan_njunctions(rs->plan); i++) {
        const char *why;
        size_t which;
        t->junctions[junction_outcome(rs, fm_connect_plan_junction(rs->plan, i), &why, &which)]++;
    }
    /* the sets' counts: a triangle that met two faults is removed once */
    t->carved = fm_carve_removed(rs->carve);
    t->carved_sheets = fm_carve_removed(rs->sheet_carve);
    for (size_t k = 0; k < fm_carve_npairs(rs->carve); k++) {
        if (fm_carve_pair_at(rs->carve, k)->kept)
            t->crossings_kept++;
        else
            t->carved_pairs++;
    }
}

/* The end-of-run table: what a user checks before opening the files. */
void print_summary(const remesh_cli *cli, const run_state *rs, FILE *fp)
{
    run_totals t;
    run_totals_of(rs, &t);
    double T = 0;
    for (int k = 0; k < 5; k++)
        T += rs->time[k];
    fprintf(fp, "\nsummary (%s)\n", cli->dir);
    fprintf(fp, "  %-14s %zu read, %zu meshed (%zu with warnings), %ld failed, %zu near-duplicates "
                "given up, %zu wholly above sea level, %zu excluded\n",
            "faults", rs->nres, t.ok, t.warned, rs->failed, t.dropped, t.empty, t.excluded);
    fprintf(fp, "  %-14s %zu\n", "sheets", t.sheets);
    if (rs->plan)
        fprintf(fp, "  %-14s %zu crossing, %zu T, %zu corner, %zu unjoined (reasons in "
                    "report.json); %zu shared nodes\n",
                "junctions", t.junctions[FM_JUNCTION_CROSSING], t.junctions[FM_JUNCTION_T],
                t.junctions[FM_JUNCTION_CORNER], t.junctions[FM_JUNCTION_UNJOINED],
                fm_connect_plan_nnodes(rs->plan));
    else
        fprintf(fp, "  %-14s not connected\n", "junctions");
    if (rs->carve) {
        fprintf(fp, "  %-14s %zu triangles removed where %zu fault pairs still crossed",
                "last guard", t.carved, t.carved_pairs);
        if (t.crossings_kept)
            fprintf(fp, "; %zu pairs left crossing, as either would have lost all it had",
                    t.crossings_kept);
        if (t.carved_sheets)
            fprintf(fp, "; %zu more where sheets of one fault crossed", t.carved_sheets);
        fputc('\n', fp);
    }
    fprintf(fp, "  %-14s %zu, %.3f%% under 30 deg, %zu under 20 deg (%zu at sharp corners), "
                "edges in [0.7, 1.4] H %.2f%%\n",
            "triangles", t.triangles,
            t.triangles ? 100.0 * (double)t.below30 / (double)t.triangles : 0, t.below20,
            t.forced, t.edges ? 100.0 * (double)t.band / (double)t.edges : 0);
    if (t.angle_min_fault)
        fprintf(fp, "  %-14s smallest angle %.1f deg (%s)\n", "worst quality", t.angle_min,
                t.angle_min_fault);
    print_loss(rs, fp);
    print_elastic(rs, fp);
    if (t.worst_dist_fault)
        fprintf(fp, "  %-14s node %.0f m from the original (%s)\n", "worst fidelity",
                t.worst_dist, t.worst_dist_fault);
    /* the stages of the log, summed where the log splits one: mesh and its
     * rounds of meshing again, write and report.html */
    char again[64] = "";
    if (rs->mesh_rounds)
        snprintf(again, sizeof again, " (with %d round%s of meshing again)", rs->mesh_rounds,
                 rs->mesh_rounds > 1 ? "s" : "");
    fprintf(fp, "  %-14s read and fit %.1f s, connect %.1f s, mesh %.1f s%s, merge and check "
                "%.1f s, write %.1f s; %.1f s in all\n",
            "time", rs->time[0], rs->time[1], rs->time[2], again, rs->time[3], rs->time[4], T);
    cache_print(cli, rs, fp);
    if (rs->outputs)
        outputs_print(rs->outputs, fp);
    for (size_t i = 0; i < rs->nres; i++) {
        const fault_result *r = &rs->res[i];
        if (r->status && !strcmp(r->status, "error"))
            fprintf(fp, "  %-14s %s: %s\n", "failed", r->name ? r->name : r->file,
                    r->error ? r->error : "out of memory");
    }
}

fm_status write_report(const remesh_cli *cli, const run_state *rs, const sim_attrs *sa,
                       fm_error *err)
{
    size_t n = strlen(cli->dir) + 32;
    char *path = malloc(n);
    if (!path)
        return fm_error_set(err, FM_ERR_NOMEM, cli->dir, 0, "out of memory");
    snprintf(path, n, "%s/report.json", cli->dir);
    fm_atomic_file *af = fm_atomic_open(path, err);
    free(path);
    if (!af)
        return err->code;
    fm_json j;
    fm_json_init(&j, fm_atomic_stream(af));
    fm_json_begin_object(&j);
    fm_json_kv_string(&j, "faultmesh_version", FM_VERSION_STRING);
    fm_json_key(&j, "options");
    fm_json_begin_object(&j);
    fm_json_kv_number(&j, "size_m", cli->mesh.size);
    fm_json_kv_string(&j, "top", top_name(cli->mesh.top));
    if (cli->mesh.top == FM_TOP_EXTEND)
        fm_json_kv_number(&j, "top_extend_m", cli->mesh.top_extend);
    fm_json_kv_string(&j, "crs", rs->crs);
    /* --crs-out: the CRS of every output file (the figures here stay in
     * the input's) */
    if (cli->crs_out)
        fm_json_kv_string(&j, "crs_out", cli->crs_out);
    /* where it came from: --crs, the inputs' coordinate-system block, or
     * the CFM's default */
    fm_json_kv_string(&j, "crs_source", rs->crs_source);
    fm_json_kv_string(&j, "msh_tags", fm_msh_tags_name(cli->msh_tags));
    fm_json_kv_string(&j, "elements", cli->quads ? "quad" : "tri");
    fm_json_end_object(&j);
    fm_json_key(&j, "faults");
    fm_json_begin_array(&j);
    for (size_t i = 0; i < rs->nres; i++)
        json_fault(&j, cli, rs, &rs->res[i], rs->res[i].mesh.size, sa);
    fm_json_end_array(&j);
    run_totals t;
    run_totals_of(rs, &t);
    json_connect(&j, cli, rs, &t);
    json_elastic(&j, cli, rs);
    if (sa)
        sim_json_summary(&j, &cli->sim, sa, (const char *const *)rs->names);
    if (sa && sa->tiles)
        quads_json(&j, sa, (const char *const *)rs->names);
    if (rs->outputs)
        outputs_json(&j, rs->outputs);
    cache_json(&j, cli, rs);
    fm_json_key(&j, "summary");
    fm_json_begin_object(&j);
    fm_json_kv_int(&j, "faults", (int64_t)rs->nres);
    fm_json_kv_int(&j, "meshed", (int64_t)t.ok);
    size_t incomplete = 0;
    for (size_t i = 0; i < rs->nres; i++)
        incomplete += rs->res[i].status && !strcmp(rs->res[i].status, "ok") &&
                      rs->res[i].set_index != SIZE_MAX &&
                      !outputs_complete(rs->outputs, rs->res[i].set_index);
    /* meshed, with some of their files not written */
    fm_json_kv_int(&j, "incomplete", (int64_t)incomplete);
    fm_json_kv_int(&j, "failed", rs->failed);
    fm_json_kv_int(&j, "meshed_with_warnings", (int64_t)t.warned);
    fm_json_kv_int(&j, "triangles", (int64_t)t.triangles);
    fm_json_kv_int(&j, "triangles_below_30_deg", (int64_t)t.below30);
    fm_json_kv_int(&j, "triangles_below_20_deg", (int64_t)t.below20);
    fm_json_kv_int(&j, "triangles_below_20_deg_at_sharp_corners", (int64_t)t.forced);
    fm_json_kv_int(&j, "edges", (int64_t)t.edges);
    fm_json_kv_int(&j, "edges_within_0.7_1.4", (int64_t)t.band);
    fm_json_kv_number(&j, "node_to_original_max_m", t.worst_dist);
    fm_json_kv_number(&j, "z_max_m", t.ok ? t.zmax : 0);
    fm_json_kv_number(&j, "time_fit_s", rs->time[0]);
    fm_json_kv_number(&j, "time_connect_s", rs->time[1]);
    fm_json_kv_number(&j, "time_mesh_s", rs->time[2]);
    fm_json_kv_number(&j, "time_merge_s", rs->time[3]);
    fm_json_kv_number(&j, "time_write_s", rs->time[4]);
    fm_json_end_object(&j);
    fm_json_end_object(&j);
    return fm_atomic_commit(af, err);
}
