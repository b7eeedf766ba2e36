/* The connect issue's measures of a run (fm_check_loss): taken once the
 * set is final (after the last guard), while the originals are there;
 * kept per fault and per pair for report.json and the summary. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run_internal.h"

void measure_loss(const remesh_cli *cli, run_state *rs)
{
    size_t nf = rs->nfaults;
    if (!nf || !rs->set_orig)
        return;
    double *size = malloc(nf * sizeof *size), *join = malloc(nf * sizeof *join);
    double *zcut = malloc(nf * sizeof *zcut);
    fm_error err;
    fm_error_clear(&err);
    fm_status st = size && join && zcut ? FM_OK : FM_ERR_NOMEM;
    for (size_t f = 0; st == FM_OK && f < nf; f++) {
        const fault_result *r = &rs->res[rs->set_res[f]];
        size[f] = r->mesh.size;
        join[f] = r->join;
        zcut[f] = r->mesh.top == FM_TOP_KEEP ? INFINITY : r->mesh.sea_level;
    }
    if (st == FM_OK) {
        fm_loss_input in = {rs->set, rs->sheet, nf, rs->set_orig, size, join, zcut, cli->jobs};
        st = fm_check_loss(&in, &rs->loss, &err);
    }
    if (st != FM_OK)
        run_log(cli->ctl, FM_LOG_WARN, "the connect measures are left out: %s",
                st == FM_ERR_NOMEM ? "out of memory" : err.message);
    free(size);
    free(join);
    free(zcut);
}

void loss_totals_of(const run_state *rs, loss_totals *t)
{
    memset(t, 0, sizeof *t);
    if (!rs->loss)
        return;
    for (size_t f = 0; f < rs->nfaults; f++) {
        const fm_loss_fault *m = fm_loss_fault_at(rs->loss, f);
        t->orig_area += m->orig_area;
        t->missing += m->missing_area;
        t->missing_away += m->missing_away;
        if (m->orig_area > 0 && m->missing_area / m->orig_area > t->worst_share) {
            t->worst_share = m->missing_area / m->orig_area;
            t->worst_share_fault = f;
        }
        if (m->moved_max > t->moved_max) {
            t->moved_max = m->moved_max;
            t->moved_fault = f;
        }
        t->moved_over += m->moved_over;
        t->island_faults += m->islands > 0;
        t->islands += m->islands;
    }
    for (size_t k = 0; k < fm_loss_npairs(rs->loss); k++) {
        const fm_loss_pair *p = fm_loss_pair_at(rs->loss, k);
        t->gap += p->gap;
        t->gap_pairs++;
        double H = fmax(rs->res[rs->set_res[p->a]].mesh.size, rs->res[rs->set_res[p->b]].mesh.size);
        t->gap_pairs_over_2H += p->gap > 2 * H;
        if (p->gap > t->gap_max) {
            t->gap_max = p->gap;
            t->gap_max_pair = k;
        }
    }
    for (size_t i = 0; rs->plan && i < fm_connect_plan_njunctions(rs->plan); i++) {
        const fm_connect_junction *jn = fm_connect_plan_junction(rs->plan, i);
        const char *why;
        size_t which;
        if (jn->length > 0 && junction_outcome(rs, jn, &why, &which) == FM_JUNCTION_UNJOINED)
            t->unjoined_curves++;
    }
}

void json_loss_fault(fm_json *j, const run_state *rs, const fault_result *r)
{
    if (!rs->loss || r->set_index >= rs->nfaults)
        return;
    const fm_loss_fault *m = fm_loss_fault_at(rs->loss, r->set_index);
    fm_json_key(j, "connect_measures");
    fm_json_begin_object(j);
    fm_json_kv_number(j, "original_area_m2", m->orig_area);
    fm_json_kv_number(j, "missing_area_m2", m->missing_area);
    fm_json_kv_number(j, "missing_area_away_m2", m->missing_away);
    fm_json_kv_number(j, "interior_moved_max_m", m->moved_max);
    fm_json_kv_int(j, "interior_moved_nodes_over_100_m", (int64_t)m->moved_over);
    if (m->moved_max > 0) {
        fm_json_key(j, "interior_moved_at");
        fm_json_begin_array(j);
        for (int k = 0; k < 3; k++)
            fm_json_number(j, m->moved_at[k]);
        fm_json_end_array(j);
    }
    fm_json_kv_int(j, "pieces", (int64_t)m->pieces);
    fm_json_kv_int(j, "original_pieces", (int64_t)m->orig_pieces);
    fm_json_kv_int(j, "sheets_meshed", (int64_t)m->sheets);
    fm_json_kv_int(j, "islands", (int64_t)m->islands);
    fm_json_kv_int(j, "island_triangles", (int64_t)m->island_triangles);
    fm_json_kv_number(j, "unclosed_gap_m", m->gap);
    fm_json_end_object(j);
}

void json_loss(fm_json *j, const run_state *rs)
{
    if (!rs->loss)
        return;
    loss_totals t;
    loss_totals_of(rs, &t);
    fm_json_key(j, "connect_measures");
    fm_json_begin_object(j);
    fm_json_kv_number(j, "unclosed_gap_m", t.gap);
    fm_json_kv_int(j, "unclosed_gap_pairs", (int64_t)t.gap_pairs);
    fm_json_kv_int(j, "unclosed_gap_pairs_over_2H", (int64_t)t.gap_pairs_over_2H);
    fm_json_kv_number(j, "original_area_m2", t.orig_area);
    fm_json_kv_number(j, "missing_area_m2", t.missing);
    fm_json_kv_number(j, "missing_area_away_m2", t.missing_away);
    fm_json_kv_number(j, "interior_moved_max_m", t.moved_max);
    fm_json_kv_int(j, "interior_moved_nodes_over_100_m", (int64_t)t.moved_over);
    fm_json_kv_int(j, "faults_with_islands", (int64_t)t.island_faults);
    fm_json_kv_int(j, "islands", (int64_t)t.islands);
    fm_json_kv_int(j, "intersections_unjoined", (int64_t)t.unjoined_curves);
    fm_json_key(j, "unclosed_gaps");
    fm_json_begin_array(j);
    for (size_t k = 0; k < fm_loss_npairs(rs->loss); k++) {
        const fm_loss_pair *p = fm_loss_pair_at(rs->loss, k);
        fm_json_begin_object(j);
        fm_json_key(j, "faults");
        fm_json_begin_array(j);
        fm_json_string(j, rs->res[rs->set_res[p->a]].name);
        fm_json_string(j, rs->res[rs->set_res[p->b]].name);
        fm_json_end_array(j);
        fm_json_key(j, "gap_m");
        fm_json_begin_array(j);
        fm_json_number(j, p->gap_ab);
        fm_json_number(j, p->gap_ba);
        fm_json_end_array(j);
        fm_json_kv_int(j, "shared_nodes", (int64_t)p->shared_nodes);
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    fm_json_end_object(j);
}

void print_loss(const run_state *rs, FILE *fp)
{
    if (!rs->loss)
        return;
    loss_totals t;
    loss_totals_of(rs, &t);
    fprintf(fp, "  %-14s unclosed gaps %.1f km in %zu fault pairs (%zu over 2 H); missing area "
                "%.2f km2 (%.3f%%), %.2f km2 away from other faults; interior moved up to %.0f m; "
                "%zu islands in %zu faults; %zu intersections unjoined\n",
            "connect", t.gap / 1e3, t.gap_pairs, t.gap_pairs_over_2H, t.missing / 1e6,
            t.orig_area > 0 ? 100 * t.missing / t.orig_area : 0, t.missing_away / 1e6, t.moved_max,
            t.islands, t.island_faults, t.unjoined_curves);
}
