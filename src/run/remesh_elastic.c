/* `faultmesh remesh --elastic-check` and `--stiffness-matrix`: the
 * elastic interaction check of the merged set (fm_check.h), with the
 * elements' rake as the simulator files give it (sim_attrs), its pairs
 * grouped by the junctions of report.json; its report.json object, its
 * summary lines, and the full matrices of a small set. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_clock.h"
#include "run_internal.h"

/* Named in report.json at most: the rest are counted. */
#define WRONG_SIGN_LISTED 20

void free_elastic(run_state *rs)
{
    fm_elastic_destroy(rs->elastic);
    if (rs->elastic_attrs)
        sim_attrs_free(rs->elastic_attrs);
    free(rs->elastic_attrs);
    free(rs->elastic_error);
    rs->elastic = NULL;
    rs->elastic_attrs = NULL;
    rs->elastic_error = NULL;
}

/* The element frames: strike and dip from the set, rake as the
 * simulator files have it (--slip, the metadata, the settings file,
 * --kinematics). */
static int make_attrs(const remesh_cli *cli, run_state *rs)
{
    fm_faultset fs = {.mesh = rs->set, .names = (const char *const *)rs->names,
                      .nfaults = rs->nfaults, .crs = rs->crs};
    rs->elastic_attrs = calloc(1, sizeof *rs->elastic_attrs);
    if (!rs->elastic_attrs)
        return -1;
    if (sim_attrs_make(&cli->sim, &fs, rs->elastic_attrs)) {
        free(rs->elastic_attrs);
        rs->elastic_attrs = NULL;
        return -1;
    }
    return 0;
}

/* Junction k of the plan as the check groups by it: its faults in the set
 * and the nodes of its curve (pts: 3 per node, malloc'ed; none when it
 * has no curve). */
static void junction_input(const run_state *rs, size_t k, fm_elastic_junction *ej, double **pts)
{
    const fm_connect_junction *jn = fm_connect_plan_junction(rs->plan, k);
    *pts = NULL;
    *ej = (fm_elastic_junction){{-1, -1}, NULL, 0};
    for (int s = 0; s < 2; s++) {
        size_t si = rs->res[rs->plan_res[jn->fault[s]]].set_index;
        ej->fault[s] = si == SIZE_MAX ? -1 : (int32_t)si;
    }
    if (jn->curve < 0)
        return;
    const double *nodes = fm_connect_plan_nodes(rs->plan);
    for (int s = 0; s < 2; s++) {
        const fm_connect_shared *sh;
        size_t ns = fm_connect_plan_sheet(rs->plan, jn->fault[s], jn->sheet[s], &sh);
        for (size_t q = 0; q < ns; q++) {
            if (sh[q].curve != (size_t)jn->curve)
                continue;
            *pts = malloc(3 * sh[q].n * sizeof **pts);
            if (!*pts)
                return;
            for (size_t p = 0; p < sh[q].n; p++)
                memcpy(*pts + 3 * p, nodes + 3 * (size_t)sh[q].node[p], 3 * sizeof **pts);
            ej->points = *pts;
            ej->npoints = sh[q].n;
            return;
        }
    }
}

static void check_failed(run_state *rs, const char *why)
{
    free(rs->elastic_error);
    rs->elastic_error = strdup(why);
    run_log(rs->ctl, FM_LOG_ERROR, "elastic check: %s", why);
}

void check_elastic(const remesh_cli *cli, run_state *rs)
{
    if ((!cli->elastic_check && !cli->stiffness_path) || !rs->nfaults)
        return;
    double t0 = fm_clock_seconds();
    if (make_attrs(cli, rs)) {
        check_failed(rs, "the element attributes (rake) could not be made");
        return;
    }
    if (!cli->elastic_check)
        return;
    size_t nj = rs->plan ? fm_connect_plan_njunctions(rs->plan) : 0;
    fm_elastic_junction *ej = calloc(nj + 1, sizeof *ej);
    double **pts = calloc(nj + 1, sizeof *pts);
    fm_error err;
    fm_error_clear(&err);
    fm_status st = ej && pts ? FM_OK : FM_ERR_NOMEM;
    for (size_t k = 0; st == FM_OK && k < nj; k++)
        junction_input(rs, k, &ej[k], &pts[k]);
    if (st == FM_OK) {
        const sim_attrs *a = rs->elastic_attrs;
        fm_elastic_input in = {rs->set, rs->nfaults, a->strike, a->dip, a->rake_t, ej, nj};
        st = fm_check_elastic(&in, &cli->elastic, &rs->elastic, &err);
    }
    for (size_t k = 0; pts && k < nj; k++)
        free(pts[k]);
    free(pts);
    free(ej);
    if (st != FM_OK) {
        check_failed(rs, st == FM_ERR_NOMEM && !err.message[0] ? "out of memory" : err.message);
        return;
    }
    const fm_elastic_summary *s = fm_elastic_get_summary(rs->elastic);
    size_t ng;
    fm_elastic_groups(rs->elastic, &ng);
    run_log(rs->ctl, FM_LOG_INFO,
            "elastic check: %zu elements, %zu pairs of different faults evaluated, %zu flagged "
            "in %zu groups, %zu self-stiffnesses of the wrong sign, in %.2f s",
            s->elements, s->pairs_evaluated, s->pairs_flagged, ng, s->self_wrong_sign,
            fm_clock_seconds() - t0);
}

static void json_example(fm_json *j, const fm_elastic_pair *p)
{
    fm_json_begin_object(j);
    fm_json_key(j, "elements");
    fm_json_begin_array(j);
    fm_json_int(j, (int64_t)p->i + 1);
    fm_json_int(j, (int64_t)p->j + 1);
    fm_json_end_array(j);
    fm_json_kv_number(j, "ratio", p->ratio);
    fm_json_kv_number(j, "distance_m", p->distance);
    fm_json_kv_number(j, "k_ij_pa_per_m", p->k_ij);
    fm_json_kv_number(j, "k_ji_pa_per_m", p->k_ji);
    fm_json_end_object(j);
}

void json_elastic(fm_json *j, const remesh_cli *cli, const run_state *rs)
{
    if (!cli->elastic_check)
        return;
    fm_json_key(j, "elastic");
    fm_json_begin_object(j);
    fm_json_kv_string(j, "medium", cli->elastic.full_space ? "full-space" : "half-space");
    fm_json_kv_number(j, "shear_modulus_pa", cli->elastic.mu);
    fm_json_kv_number(j, "poisson_ratio", cli->elastic.nu);
    fm_json_kv_number(j, "radius_element_sizes", cli->elastic.radius);
    fm_json_kv_number(j, "flag_fraction", cli->elastic.fraction);
    if (!rs->elastic) {
        fm_json_kv_string(j, "error", rs->elastic_error ? rs->elastic_error : "no faults");
        fm_json_end_object(j);
        return;
    }
    const fm_elastic_summary *s = fm_elastic_get_summary(rs->elastic);
    const double *self = fm_elastic_self(rs->elastic);
    const int32_t *tag = fm_mesh_tags(rs->set);
    fm_json_kv_int(j, "elements", (int64_t)s->elements);
    fm_json_kv_int(j, "left_out_above_surface", (int64_t)s->above_surface);
    fm_json_kv_int(j, "left_out_degenerate", (int64_t)s->degenerate);
    fm_json_kv_number(j, "self_stiffness_min_pa_per_m", s->self_min);
    fm_json_kv_number(j, "self_stiffness_max_pa_per_m", s->self_max);
    size_t nw;
    const size_t *wrong = fm_elastic_wrong_sign(rs->elastic, &nw);
    fm_json_kv_int(j, "self_wrong_sign", (int64_t)nw);
    fm_json_key(j, "self_wrong_sign_elements");
    fm_json_begin_array(j);
    for (size_t k = 0; k < nw && k < WRONG_SIGN_LISTED; k++) {
        fm_json_begin_object(j);
        fm_json_kv_int(j, "element", (int64_t)wrong[k] + 1);
        fm_json_kv_string(j, "fault", rs->names[tag[wrong[k]]]);
        if (isfinite(self[wrong[k]]))
            fm_json_kv_number(j, "self_stiffness_pa_per_m", self[wrong[k]]);
        else
            fm_json_kv_string(j, "self_stiffness_pa_per_m", "not finite");
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    fm_json_kv_int(j, "pairs_within_radius", (int64_t)s->pairs_within);
    fm_json_kv_int(j, "pairs_evaluated", (int64_t)s->pairs_evaluated);
    fm_json_kv_int(j, "pairs_singular", (int64_t)s->pairs_singular);
    fm_json_kv_int(j, "pairs_flagged", (int64_t)s->pairs_flagged);
    fm_json_kv_number(j, "max_ratio", s->max_ratio);
    size_t ng, np;
    const fm_elastic_group *g = fm_elastic_groups(rs->elastic, &ng);
    const fm_elastic_pair *p = fm_elastic_pairs(rs->elastic, &np);
    fm_json_key(j, "groups");
    fm_json_begin_array(j);
    for (size_t k = 0; k < ng; k++) {
        fm_json_begin_object(j);
        fm_json_key(j, "faults");
        fm_json_begin_array(j);
        fm_json_string(j, rs->names[g[k].a]);
        fm_json_string(j, rs->names[g[k].b]);
        fm_json_end_array(j);
        /* numbered as connect.junctions is, from 1; null: the two faults
         * have no junction (a near-overlap nothing joined) */
        fm_json_key(j, "junction");
        if (g[k].junction)
            fm_json_int(j, (int64_t)g[k].junction);
        else
            fm_json_null(j);
        fm_json_kv_int(j, "pairs", (int64_t)g[k].pairs);
        fm_json_kv_number(j, "max_ratio", g[k].max_ratio);
        fm_json_kv_number(j, "min_distance_m", g[k].min_distance);
        fm_json_kv_number(j, "max_mutual_pa_per_m", g[k].max_k);
        fm_json_key(j, "examples");
        fm_json_begin_array(j);
        for (size_t e = 0; e < g[k].nexamples; e++)
            json_example(j, &p[g[k].example[e]]);
        fm_json_end_array(j);
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    if (cli->stiffness_path)
        fm_json_kv_string(j, "matrix_file", cli->stiffness_path);
    fm_json_end_object(j);
}

void print_elastic(const run_state *rs, FILE *fp)
{
    if (!rs->elastic)
        return;
    const fm_elastic_summary *s = fm_elastic_get_summary(rs->elastic);
    size_t ng;
    const fm_elastic_group *g = fm_elastic_groups(rs->elastic, &ng);
    fprintf(fp, "  %-14s %zu element pairs of different faults act as one fault (in %zu "
                "groups), largest ratio %.2f; %zu self-stiffnesses of the wrong sign\n",
            "elastic", s->pairs_flagged, ng, s->max_ratio, s->self_wrong_sign);
    for (size_t k = 0; k < ng && k < 5; k++)
        fprintf(fp, "  %-14s %s / %s: %zu pairs, ratio %.2f, %.0f m apart%s\n", "", rs->names[g[k].a],
                rs->names[g[k].b], g[k].pairs, g[k].max_ratio, g[k].min_distance,
                g[k].junction ? "" : " (no junction)");
}

fm_status write_stiffness(const remesh_cli *cli, const run_state *rs, fm_error *err)
{
    if (!rs->elastic_attrs)
        return fm_error_set(err, FM_ERR_INVALID, cli->stiffness_path, 0,
                            "no stiffness matrices: %s",
                            rs->elastic_error ? rs->elastic_error : "no elements");
    const sim_attrs *a = rs->elastic_attrs;
    fm_elastic_input in = {rs->set, rs->nfaults, a->strike, a->dip, a->rake_t, NULL, 0};
    return fm_elastic_write_matrices(&in, &cli->elastic, cli->stiffness_path, err);
}
