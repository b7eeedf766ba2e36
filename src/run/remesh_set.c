/* `faultmesh remesh`: the faults merged into one set in input order
 * (shared nodes become one vertex), the last guard against faults that
 * still cross, and the set written in every format. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_check.h"
#include "fm_closest.h"
#include "fm_faultset_write.h"
#include "fm_parallel.h"
#include "remesh_quads.h"
#include "fm_reproject.h"
#include "fm_sort.h"
#include "fm_tsurf.h"
#include "run_internal.h"

static fault_result *new_result(run_state *rs)
{
    if (rs->nres == rs->cap) {
        size_t cap = rs->cap ? 2 * rs->cap : 64;
        fault_result *n = realloc(rs->res, cap * sizeof *n);
        if (!n)
            return NULL;
        rs->res = n;
        rs->cap = cap;
    }
    fault_result *r = &rs->res[rs->nres++];
    memset(r, 0, sizeof *r);
    return r;
}

/* Appends a fault to the set: a shared node is one vertex of the set,
 * made when a fault first uses it, at the plan's position (on both
 * surfaces). */
static fm_status append_fault(run_state *rs, const fm_mesh *fault, const int64_t *ids)
{
    size_t nv = fm_mesh_nvertices(fault), nt = fm_mesh_ntriangles(fault);
    int32_t *map = malloc((nv + 1) * sizeof *map);
    if (!map || fm_mesh_reserve(rs->set, fm_mesh_nvertices(rs->set) + nv,
                                fm_mesh_ntriangles(rs->set) + nt) != FM_OK) {
        free(map);
        return FM_ERR_NOMEM;
    }
    const double *X = fm_mesh_vertices(fault);
    const double *P = rs->plan ? fm_connect_plan_nodes(rs->plan) : NULL;
    for (size_t v = 0; v < nv; v++) {
        int64_t id = ids ? ids[v] : -1;
        if (id >= 0 && rs->node_vertex) {
            if (rs->node_vertex[id] < 0)
                rs->node_vertex[id] =
                    fm_mesh_add_vertex(rs->set, P[3 * id], P[3 * id + 1], P[3 * id + 2]);
            map[v] = rs->node_vertex[id];
        } else {
            map[v] = fm_mesh_add_vertex(rs->set, X[3 * v], X[3 * v + 1], X[3 * v + 2]);
        }
    }
    const int32_t *T = fm_mesh_triangles(fault), *sheet = fm_mesh_tags(fault);
    size_t base = fm_mesh_ntriangles(rs->set);
    int32_t *grown = realloc(rs->sheet, (base + nt + 1) * sizeof *grown);
    if (!grown) {
        free(map);
        return FM_ERR_NOMEM;
    }
    rs->sheet = grown;
    for (size_t t = 0; t < nt; t++) {
        fm_mesh_add_triangle(rs->set, map[T[3 * t]], map[T[3 * t + 1]], map[T[3 * t + 2]],
                             (int32_t)rs->nfaults);
        rs->sheet[base + t] = sheet ? sheet[t] : 0;
    }
    free(map);
    return FM_OK;
}

/* Merges a job's faults into the run, in order. */
void merge_job(const remesh_cli *cli, file_job *job, run_state *rs)
{
    if (!job->res) {
        fault_result *r = new_result(rs);
        if (r) {
            r->file = strdup(job->path);
            r->status = "error";
            r->error = strdup("out of memory");
        }
        rs->failed++;
        run_log(cli->ctl, FM_LOG_ERROR, "%s: out of memory", job->path);
        return;
    }
    for (size_t o = 0; o < job->n; o++) {
        fault_result *r = new_result(rs);
        if (!r) {
            rs->failed++;
            continue;
        }
        *r = job->res[o];
        r->orig = job->objs && o < job->nobj ? fm_tsurf_mesh(job->objs[o]) : NULL;
        r->set_index = SIZE_MAX;
        if (rs->plan_res && job->model && job->first + o < rs->nplan_faults)
            rs->plan_res[job->first + o] = rs->nres - 1;
        fm_mesh *fault = job->mesh[o];
        if (fault) {
            char **nn = realloc(rs->names, (rs->nfaults + 1) * sizeof *nn);
            if (nn)
                rs->names = nn;
            size_t *sr = realloc(rs->set_res, (rs->nfaults + 1) * sizeof *sr);
            if (sr)
                rs->set_res = sr;
            const fm_mesh **so = realloc(rs->set_orig, (rs->nfaults + 1) * sizeof *so);
            if (so)
                rs->set_orig = so;
            const fm_cad_face **cad =
                nn ? realloc(rs->cad, (rs->ncad + r->ncad + 1) * sizeof *cad) : NULL;
            if (cad)
                rs->cad = cad;
            if (!nn || !sr || !so || !cad || append_fault(rs, fault, job->ids[o]) != FM_OK) {
                r->status = "error";
                r->error = strdup("out of memory");
            } else {
                rs->set_res[rs->nfaults] = rs->nres - 1;
                rs->set_orig[rs->nfaults] = fm_tsurf_mesh(job->objs[o]);
                r->set_index = rs->nfaults;
                rs->names[rs->nfaults++] = r->name;
                for (size_t k = 0; k < r->ncad; k++)
                    rs->cad[rs->ncad++] = r->cad[k];
            }
        }
        free(job->ids ? job->ids[o] : NULL);
        if (!strcmp(r->status, "error")) {
            run_log(cli->ctl, FM_LOG_ERROR, "%s", r->error ? r->error : "out of memory");
            rs->failed++;
        }
        if (run_log_wants(cli->ctl, FM_LOG_DETAIL))
            log_fault(cli->ctl, r);
        fm_mesh_destroy(fault);
    }
    free(job->res);
    free(job->mesh);
    free(job->ids);
    job->res = NULL;
    job->mesh = NULL;
    job->ids = NULL;
}

/* The pieces of plan curves that fault tag of the set still holds. */
static int set_curve_pieces(const run_state *rs, int32_t tag, fault_result *r)
{
    size_t f = 0, nv = fm_mesh_nvertices(rs->set);
    while (f < rs->nplan_faults && &rs->res[rs->plan_res[f]] != r)
        f++;
    if (f == rs->nplan_faults || !rs->node_vertex)
        return 0;
    int64_t *node = malloc((nv + 1) * sizeof *node);
    if (!node)
        return -1;
    for (size_t v = 0; v < nv; v++)
        node[v] = -1;
    for (size_t k = 0; k < fm_connect_plan_nnodes(rs->plan); k++)
        if (rs->node_vertex[k] >= 0)
            node[rs->node_vertex[k]] = (int64_t)k;
    size_t ne;
    fm_keyed *edge = fm_remesh_shared_edges(rs->set, node, tag, &ne);
    int rc = edge ? curve_pieces(rs->plan, f, r->sheets, edge, ne, r) : -1;
    free(node);
    free(edge);
    return rc;
}

/* A fault that lost triangles is measured again on what is left (the
 * originals must still be there), and what it lost is added up. */
static void measure_again(run_state *rs, int32_t tag)
{
    fm_error err;
    fm_error_clear(&err);
    fault_result *r = &rs->res[rs->set_res[tag]];
    size_t before = r->q.triangles;
    double area = r->q.area;
    fm_closest_tree *tree = fm_closest_tree_create(rs->set_orig[tag], &err);
    if (!tree || fm_check_quality(rs->set, tag, r->mesh.size, &r->q) != FM_OK ||
        fm_check_fidelity(rs->set, tag, rs->set_orig[tag], tree, &r->fid) != FM_OK)
        run_log(rs->ctl, FM_LOG_ERROR, "%s: out of memory measuring it again", r->name);
    fm_closest_tree_destroy(tree);
    r->carved += before - r->q.triangles;
    r->carved_area += area - r->q.area;
    if (set_curve_pieces(rs, tag, r))
        run_log(rs->ctl, FM_LOG_ERROR, "%s: out of memory measuring it again", r->name);
}

typedef struct again_work {
    run_state *rs;
    const int32_t *fault;
} again_work;

static void again_one(void *user, size_t k)
{
    again_work *w = user;
    measure_again(w->rs, w->fault[k]);
}

/* Every fault that gave way in cr measured again, once (unit: the fault
 * of each tag of cr, NULL when the tags are faults). Each reads the set
 * whole and writes only its own result, so they run on the threads. */
static void measure_yielded(run_state *rs, const fm_carve_result *cr, const int32_t *unit,
                            int jobs)
{
    size_t np = fm_carve_npairs(cr), n = 0;
    int32_t *fault = malloc((np + 1) * sizeof *fault);
    if (!fault) {
        run_log(rs->ctl, FM_LOG_ERROR, "out of memory measuring the carved faults again");
        return;
    }
    for (size_t k = 0; k < np; k++) {
        const fm_carve_pair *p = fm_carve_pair_at(cr, k);
        int32_t f = p->fault[p->yielded];
        f = unit ? unit[f] : f;
        int seen = p->kept;
        for (size_t i = 0; i < k && !seen; i++) {
            const fm_carve_pair *q = fm_carve_pair_at(cr, i);
            seen = !q->kept && (unit ? unit[q->fault[q->yielded]] : q->fault[q->yielded]) == f;
        }
        if (!seen)
            fault[n++] = f;
    }
    again_work w = {rs, fault};
    fm_parallel_for(n, jobs, again_one, &w, NULL, NULL, 0, n);
    free(fault);
}

/* The triangles the guard between sheets needs to see, as a mesh of the
 * set's vertices (their numbers kept) in the set's order: those of faults
 * of several sheets, and every triangle with two corners among theirs (a
 * side shared with another fault says a sheet's triangle is on a junction
 * there). The rest cannot matter: after the guard between faults, with no
 * pair kept, no triangle of one fault meets another's, and the sheets of a
 * fault of one sheet are never compared. NULL when out of memory; *at
 * gets each triangle's index in the set. */
static fm_mesh *sheet_guard_mesh(const fm_mesh *set, const int32_t *unit_first,
                                 const int32_t *fault_tag, int32_t **at)
{
    size_t nv = fm_mesh_nvertices(set), nt = fm_mesh_ntriangles(set);
    const int32_t *T = fm_mesh_triangles(set), *tag = fm_mesh_tags(set);
    unsigned char *mark = calloc(nv + 1, 1);
    unsigned char *take = calloc(nt + 1, 1);
    fm_mesh *sub = fm_mesh_create();
    *at = NULL;
    if (!mark || !take || !sub) {
        free(mark);
        free(take);
        fm_mesh_destroy(sub);
        return NULL;
    }
    for (size_t t = 0; t < nt; t++) {
        int32_t f = fault_tag[t];
        if (unit_first[f + 1] - unit_first[f] > 1) {
            take[t] = 1;
            for (int c = 0; c < 3; c++)
                mark[T[3 * t + c]] = 1;
        }
    }
    size_t n = 0;
    for (size_t t = 0; t < nt; t++) {
        take[t] |= mark[T[3 * t]] + mark[T[3 * t + 1]] + mark[T[3 * t + 2]] >= 2;
        n += take[t];
    }
    *at = malloc((n + 1) * sizeof **at);
    if (!*at || fm_mesh_reserve(sub, nv, n) != FM_OK) {
        free(mark);
        free(take);
        free(*at);
        *at = NULL;
        fm_mesh_destroy(sub);
        return NULL;
    }
    const double *X = fm_mesh_vertices(set);
    for (size_t v = 0; v < nv; v++)
        fm_mesh_add_vertex(sub, X[3 * v], X[3 * v + 1], X[3 * v + 2]);
    for (size_t t = 0, k = 0; t < nt; t++)
        if (take[t]) {
            fm_mesh_add_triangle(sub, T[3 * t], T[3 * t + 1], T[3 * t + 2], tag[t]);
            (*at)[k++] = (int32_t)t;
        }
    free(mark);
    free(take);
    return sub;
}

/* The same guard between the sheets of each fault (a branching fault's
 * sheets that cross where their junction could not be made, or was made in
 * part): every sheet is a unit of its own for fm_carve_crossings, and the
 * fault tags are put back after. Not when a pair of faults was left
 * crossing: with unit tags it would be carved after all. It runs on the
 * triangles that can matter (sheet_guard_mesh), and what it removes there
 * is removed from the set. */
static void carve_sheets(run_state *rs, double H, int jobs)
{
    for (size_t k = 0; k < fm_carve_npairs(rs->carve); k++)
        if (fm_carve_pair_at(rs->carve, k)->kept)
            return;
    size_t nt = fm_mesh_ntriangles(rs->set), nf = rs->nfaults;
    int32_t *tag = fm_mesh_tags_mut(rs->set);
    int32_t *first = calloc(nf + 1, sizeof *first);
    if (!first)
        return;
    for (size_t t = 0; t < nt; t++)
        if (rs->sheet[t] + 1 > first[tag[t] + 1])
            first[tag[t] + 1] = rs->sheet[t] + 1;
    for (size_t f = 0; f < nf; f++)
        first[f + 1] += first[f];
    size_t units = (size_t)first[nf];
    int32_t *fault = units > nf ? malloc(units * sizeof *fault) : NULL;
    int32_t *ftag = fault ? malloc((nt + 1) * sizeof *ftag) : NULL;
    if (!ftag) { /* no fault of several sheets, or out of memory */
        free(first);
        free(fault);
        return;
    }
    for (size_t f = 0; f < nf; f++)
        for (int32_t u = first[f]; u < first[f + 1]; u++)
            fault[u] = (int32_t)f;
    memcpy(ftag, tag, nt * sizeof *ftag);
    for (size_t t = 0; t < nt; t++)
        tag[t] = first[tag[t]] + rs->sheet[t];
    int32_t *at = NULL;
    fm_mesh *sub = sheet_guard_mesh(rs->set, first, ftag, &at);
    size_t ntaken = sub ? fm_mesh_ntriangles(sub) : 0;
    unsigned char *gone = sub ? calloc(nt + 1, 1) : NULL;
    fm_error err;
    fm_error_clear(&err);
    fm_carve_result *cr = NULL;
    fm_status st = gone ? FM_OK : fm_error_set(&err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    if (st == FM_OK) {
        /* at: the set's index of each triangle of sub, before and after */
        for (size_t i = 0; i < ntaken; i++)
            gone[at[i]] = 1;
        st = fm_carve_crossings(sub, 2 * H, jobs, at, &cr, &err);
    }
    if (st == FM_OK) {
        for (size_t i = 0; i < fm_mesh_ntriangles(sub); i++)
            gone[at[i]] = 0;
        /* what went from sub goes from the set, the others kept in order */
        fm_mesh_drop_triangles(rs->set, gone, rs->sheet);
    }
    free(gone);
    free(ftag);
    fm_mesh_destroy(sub);
    free(at);
    nt = fm_mesh_ntriangles(rs->set);
    for (size_t t = 0; t < nt; t++)
        tag[t] = fault[tag[t]];
    if (st != FM_OK) {
        run_log(rs->ctl, FM_LOG_WARN, "sheets of a fault that cross each other are left so: %s",
                err.message);
        fm_carve_result_destroy(cr);
        free(first);
        free(fault);
        return;
    }
    rs->sheet_carve = cr;
    rs->sheet_unit_fault = fault;
    rs->sheet_unit_first = first;
    measure_yielded(rs, cr, fault, jobs);
}

/* Where two faults still meet away from their shared curves (fm_carve.h),
 * one of them gives way; then the same between the sheets of a fault. */
void carve_set(const remesh_cli *cli, run_state *rs)
{
    fm_error err;
    fm_error_clear(&err);
    /* the grid's cells hold a few of the largest triangles */
    double H = cli->mesh.size;
    for (size_t f = 0; f < rs->nfaults; f++)
        H = fmax(H, rs->res[rs->set_res[f]].mesh.size);
    if (fm_carve_crossings(rs->set, 2 * H, cli->jobs, rs->sheet, &rs->carve, &err) != FM_OK) {
        run_log(cli->ctl, FM_LOG_WARN, "faults that cross each other are left so: %s",
                err.message);
        return;
    }
    measure_yielded(rs, rs->carve, NULL, cli->jobs);
    carve_sheets(rs, H, cli->jobs);
}

/* The set without vertices no triangle uses (what the last guard's
 * carving left, or a shared node no fault kept), so that no output holds
 * a point of no element; the shared nodes' vertices follow. -1 when
 * memory runs out (the set is then left as it was). */
int compact_set(run_state *rs)
{
    size_t nv = fm_mesh_nvertices(rs->set), nt = fm_mesh_ntriangles(rs->set);
    int32_t *map = malloc((nv + 1) * sizeof *map);
    fm_mesh *out = fm_mesh_create();
    if (!map || !out) {
        free(map);
        fm_mesh_destroy(out);
        return -1;
    }
    const int32_t *T = fm_mesh_triangles(rs->set), *tag = fm_mesh_tags(rs->set);
    size_t used = fm_used_vertices(T, nt, nv, map);
    if (used == nv) {
        free(map);
        fm_mesh_destroy(out);
        return 0;
    }
    if (fm_mesh_reserve(out, used, nt) != FM_OK) {
        free(map);
        fm_mesh_destroy(out);
        return -1;
    }
    const double *X = fm_mesh_vertices(rs->set);
    for (size_t v = 0; v < nv; v++)
        if (map[v] >= 0)
            fm_mesh_add_vertex(out, X[3 * v], X[3 * v + 1], X[3 * v + 2]);
    for (size_t t = 0; t < nt; t++)
        fm_mesh_add_triangle(out, map[T[3 * t]], map[T[3 * t + 1]], map[T[3 * t + 2]], tag[t]);
    for (size_t k = 0; rs->node_vertex && rs->plan && k < fm_connect_plan_nnodes(rs->plan); k++)
        if (rs->node_vertex[k] >= 0)
            rs->node_vertex[k] = map[rs->node_vertex[k]];
    fm_mesh_destroy(rs->set);
    rs->set = out;
    free(map);
    return 0;
}

/* Junction i as meshed: the plan's type, unless one of its faults failed
 * or came out empty (*why is then that fault's error and *which the
 * fault) or the mesher could not fit its curve into one of its sheets
 * (*why then says so and *which names the fault; else *which is
 * SIZE_MAX). */
fm_junction_type junction_outcome(const run_state *rs, const fm_connect_junction *jn,
                                  const char **why, size_t *which)
{
    *why = jn->reason;
    *which = SIZE_MAX;
    if (jn->curve < 0)
        return jn->type;
    for (int s = 0; s < 2; s++) {
        const fault_result *r = &rs->res[rs->plan_res[jn->fault[s]]];
        if (r->status && (!strcmp(r->status, "error") || !strcmp(r->status, "empty"))) {
            *why = r->error ? r->error : "failed";
            *which = jn->fault[s];
            return FM_JUNCTION_UNJOINED;
        }
    }
    for (int s = 0; s < 2; s++) {
        const fault_result *r = &rs->res[rs->plan_res[jn->fault[s]]];
        int left_out = 0;
        for (size_t k = 0; k < r->ndropped; k++)
            left_out |= r->dropped_curves[k] == (size_t)jn->curve;
        if (left_out) {
            *why = "the curve could not be fitted into the outline of one of the sheets";
            *which = jn->fault[s];
            return FM_JUNCTION_UNJOINED;
        }
    }
    if (jn->type != FM_JUNCTION_UNJOINED &&
        !share_piece(&rs->res[rs->plan_res[jn->fault[0]]], &rs->res[rs->plan_res[jn->fault[1]]],
                     (size_t)jn->curve)) {
        /* each holds pieces of it, but none the same: another curve of one
         * of them cut the rest away, or the last guard did */
        int carved = rs->res[rs->plan_res[jn->fault[0]]].carved ||
                     rs->res[rs->plan_res[jn->fault[1]]].carved;
        *why = carved ? "the two sheets keep no common piece of the curve: it was carved away "
                        "where one of them ran through another fault"
                      : "the two sheets keep no common piece of the curve";
        *which = jn->fault[0];
        return FM_JUNCTION_UNJOINED;
    }
    return jn->type;
}

/* Whether edge p-q is an edge of a triangle of fault f (sides: the set's,
 * fm_mesh_sides; tag: the set's triangle tags). */
static int fault_has_edge(const fm_keyed *side, size_t n, const int32_t *tag, int32_t p,
                          int32_t q, size_t f)
{
    uint64_t key = fm_edge_key((uint64_t)p, (uint64_t)q);
    for (size_t i = fm_keyed_lower_bound(side, n, key); i < n && side[i].key == key; i++)
        if ((size_t)tag[side[i].index] == f)
            return 1;
    return 0;
}

/* One node set per junction made: the nodes of its curve (as either
 * sheet sees it) on an edge of both faults' triangles in the set, so that
 * every node is one of both faults, named after the junction's index in
 * report.json and its faults. A junction made whose faults keep no such
 * edge has no set. Arrays malloc'ed (free_junction_sets). */
typedef struct junction_sets {
    fm_faultset_nodeset *set;
    char **names;
    int32_t **vertices;
    size_t n;
} junction_sets;

static void free_junction_sets(junction_sets *js)
{
    for (size_t i = 0; i < js->n; i++) {
        free(js->names[i]);
        free(js->vertices[i]);
    }
    free(js->set);
    free(js->names);
    free(js->vertices);
    memset(js, 0, sizeof *js);
}

/* Junction i's node set into js, if it is made and has one; -1 when out
 * of memory. */
static int junction_set(const run_state *rs, size_t i, const fm_keyed *edges, size_t nedges,
                        junction_sets *js)
{
    const fm_connect_junction *jn = fm_connect_plan_junction(rs->plan, i);
    const char *why;
    size_t which;
    if (junction_outcome(rs, jn, &why, &which) == FM_JUNCTION_UNJOINED || jn->curve < 0)
        return 0;
    const fault_result *ra = &rs->res[rs->plan_res[jn->fault[0]]];
    const fault_result *rb = &rs->res[rs->plan_res[jn->fault[1]]];
    size_t fa = ra->set_index, fb = rb->set_index;
    if (fa == SIZE_MAX || fb == SIZE_MAX)
        return 0;
    const int32_t *tag = fm_mesh_tags(rs->set);
    const fm_connect_shared *c[2] = {NULL, NULL};
    for (int side = 0; side < 2; side++) {
        const fm_connect_shared *sh = NULL;
        size_t ns = fm_connect_plan_sheet(rs->plan, jn->fault[side], jn->sheet[side], &sh);
        for (size_t k = 0; k < ns && !c[side]; k++)
            if (sh[k].curve == (size_t)jn->curve)
                c[side] = &sh[k];
    }
    size_t cap = 2 * ((c[0] ? c[0]->n : 0) + (c[1] ? c[1]->n : 0));
    if (!cap)
        return 0;
    int32_t *v = malloc(cap * sizeof *v);
    if (!v)
        return -1;
    size_t nv = 0;
    for (int side = 0; side < 2; side++)
        for (size_t k = 0; c[side] && k + 1 < c[side]->n; k++) {
            int32_t p = rs->node_vertex[c[side]->node[k]];
            int32_t q = rs->node_vertex[c[side]->node[k + 1]];
            if (p < 0 || q < 0 || !fault_has_edge(edges, nedges, tag, p, q, fa) ||
                !fault_has_edge(edges, nedges, tag, p, q, fb))
                continue;
            v[nv++] = p;
            v[nv++] = q;
        }
    size_t len = strlen(ra->name) + strlen(rb->name) + 48;
    char *name = nv ? malloc(len) : NULL;
    if (!name) {
        free(v);
        return nv ? -1 : 0;
    }
    /* numbered from 1, as every output numbers faults and junctions
     * (docs/formats.md): the junction's line in report.json */
    snprintf(name, len, "junction %zu: %s / %s", i + 1, ra->name, rb->name);
    js->names[js->n] = name;
    js->vertices[js->n] = v;
    js->set[js->n] = (fm_faultset_nodeset){name, v, nv};
    js->n++;
    return 0;
}

static int junction_sets_make(const run_state *rs, junction_sets *js)
{
    memset(js, 0, sizeof *js);
    if (!rs->plan || !rs->node_vertex)
        return 0;
    size_t nj = fm_connect_plan_njunctions(rs->plan), nedges = 0;
    js->set = calloc(nj ? nj : 1, sizeof *js->set);
    js->names = calloc(nj ? nj : 1, sizeof *js->names);
    js->vertices = calloc(nj ? nj : 1, sizeof *js->vertices);
    fm_keyed *edges = fm_mesh_sides(rs->set, &nedges);
    int rc = js->set && js->names && js->vertices && edges ? 0 : -1;
    for (size_t i = 0; rc == 0 && i < nj; i++)
        rc = junction_set(rs, i, edges, nedges, js);
    free(edges);
    return rc;
}

/* The set in CRS `to`: a copy of its mesh with every node converted by
 * one PROJ operation chosen for the set's extent (*rp, for the CAD
 * surfaces too). */
static fm_status convert_set(const run_state *rs, const char *to, const char *dir,
                             fm_mesh **out, fm_reproject **rp, fm_error *err)
{
    *out = NULL;
    *rp = NULL;
    size_t nv = fm_mesh_nvertices(rs->set);
    const double *x = fm_mesh_vertices(rs->set);
    double bb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < nv; v++) {
        bb[0] = fmin(bb[0], x[3 * v]);
        bb[1] = fmin(bb[1], x[3 * v + 1]);
        bb[2] = fmax(bb[2], x[3 * v]);
        bb[3] = fmax(bb[3], x[3 * v + 1]);
    }
    if (!(*rp = fm_reproject_create(rs->crs, to, bb, dir, err)))
        return err ? err->code : FM_ERR_INVALID;
    if (!(*out = fm_mesh_clone(rs->set)))
        return fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    return fm_reproject_points(*rp, fm_mesh_vertices_mut(*out), nv, 3, dir, err);
}

/* Every file of the set as not written, for one reason (the set could not
 * be prepared). */
static fm_status none_written(output_log *log, const char *dir, const fm_error *why)
{
    static const char *const files[] = {"mesh.vtu",   "mesh.msh",    "mesh.stl",
                                        "mesh.obj",   "mesh.exo",    "NAME.ts",
                                        "model.igs",  "mesh.rsqsim", "mesh.eqsim",
                                        "names.csv"};
    size_t n = strlen(dir) + 32;
    char *path = malloc(n);
    for (size_t k = 0; k < sizeof files / sizeof *files; k++) {
        if (path)
            snprintf(path, n, "%s/%s", dir, files[k]);
        outputs_note(log, path ? path : files[k], SIZE_MAX, OUTPUT_SET, why);
    }
    free(path);
    return why->code;
}

/* The fault set in every format, the files shared among cli->jobs threads
 * (the bytes do not depend on how many); model.igs and the simulator
 * files after them, each tried whatever became of the others. *sa gets the
 * element attributes (cleared when there are no faults). */
fm_status write_set(const remesh_cli *cli, const run_state *rs, sim_attrs *sa)
{
    memset(sa, 0, sizeof *sa);
    if (!rs->nfaults)
        return FM_OK;
    fm_error err;
    fm_error_clear(&err);
    junction_sets js = {0};
    int32_t *tags = malloc(rs->nfaults * sizeof *tags);
    char **pnames = NULL;
    fm_status st = FM_OK;
    if (!tags || junction_sets_make(rs, &js))
        st = fm_error_set(&err, FM_ERR_NOMEM, cli->dir, 0, "out of memory");
    if (st == FM_OK)
        st = fm_msh_tags_make(cli->msh_tags, (const char *const *)rs->names, rs->nfaults, tags,
                              &pnames, &err);
    /* --crs-out: the set converted node by node, by one operation */
    fm_mesh *converted = NULL;
    fm_reproject *rp = NULL;
    if (st == FM_OK && cli->crs_out)
        st = convert_set(rs, cli->crs_out, cli->dir, &converted, &rp, &err);
    fm_faultset fs = {.mesh = converted ? converted : rs->set,
                      .names = (const char *const *)rs->names,
                      .nfaults = rs->nfaults,
                      .physical_tags = tags,
                      .physical_names = (const char *const *)pnames,
                      .msh_dense_nodes = cli->msh_tags == FM_MSH_TAGS_TANDEM,
                      /* Tandem and SeisSol read only their own tags */
                      .msh_no_curves = cli->msh_tags == FM_MSH_TAGS_TANDEM ||
                                       cli->msh_tags == FM_MSH_TAGS_SEISSOL,
                      .crs = cli->crs_out ? cli->crs_out : rs->crs,
                      .nodesets = js.set,
                      .nnodesets = js.n};
    int made = st == FM_OK ? sim_attrs_make(&cli->sim, &fs, sa) : 0;
    if (made == -1)
        st = fm_error_set(&err, FM_ERR_NOMEM, cli->dir, 0, "out of memory");
    else if (made)
        st = fm_error_set(&err, FM_ERR_INVALID, cli->dir, 0,
                          "the element attributes could not be made (--kinematics, above)");
    /* the element attributes, and which sheet of its fault a triangle is on
     * (the repair stage's sheets: the parts of a branching fault), numbered
     * from 1 as faults are */
    size_t ntri = fm_mesh_ntriangles(rs->set);
    int32_t *sheet = malloc((ntri + 1) * sizeof *sheet);
    if (!sheet && st == FM_OK)
        st = fm_error_set(&err, FM_ERR_NOMEM, cli->dir, 0, "out of memory");
    for (size_t t = 0; sheet && t < ntri; t++)
        sheet[t] = rs->sheet[t] + 1;
    fm_vtu_array cells[sizeof sa->cells / sizeof *sa->cells + 1];
    memcpy(cells, sa->cells, sizeof sa->cells);
    cells[sizeof sa->cells / sizeof *sa->cells] = (fm_vtu_array){"sheet", FM_VTU_INT32, 1, sheet};
    fs.cell_data = cells;
    fs.ncell_data = sizeof cells / sizeof *cells;
    size_t n = strlen(cli->dir) + 32;
    char *path = st == FM_OK ? malloc(6 * n) : NULL;
    if (st == FM_OK && !path)
        st = fm_error_set(&err, FM_ERR_NOMEM, cli->dir, 0, "out of memory");
    if (st != FM_OK) {
        none_written(rs->outputs, cli->dir, &err);
    } else {
        const char *ext[6] = {"vtu", "msh", "stl", "obj", "exo", "igs"};
        for (int k = 0; k < 6; k++)
            snprintf(path + (size_t)k * n, n, "%s/%s.%s", cli->dir, k < 5 ? "mesh" : "model",
                     ext[k]);
        unsigned fm = cli->formats;
        fm_faultset_outputs out = {.vtu = fm & FMT_VTU ? path : NULL,
                                   .msh = fm & FMT_MSH ? path + n : NULL,
                                   .stl = fm & FMT_STL ? path + 2 * n : NULL,
                                   .obj = fm & FMT_OBJ ? path + 3 * n : NULL,
                                   .exo = fm & FMT_EXO ? path + 4 * n : NULL,
                                   .msh_version = cli->msh,
                                   .tsurf_dir = fm & FMT_TS ? cli->dir : NULL,
                                   .done = outputs_done,
                                   .done_ctx = rs->outputs};
        fm_status cst = FM_OK, sst = FM_OK, nst = FM_OK;
        /* model.igs and the simulator files beside the others (remesh_side.c) */
        side_write igs = {.kind = SIDE_IGES, .path = path + 5 * n, .cad = rs->cad,
                          .ncad = rs->ncad, .crs = fs.crs, .rp = rp};
        /* RSQSim's and EQSim's files each on a thread: either alone was
         * the write stage's longest at fine sizes */
        side_write sim[2];
        for (int k = 0; k < 2; k++)
            sim[k] = (side_write){.kind = SIDE_SIM, .sc = &cli->sim, .fs = &fs, .sa = sa,
                                  .dir = cli->dir, .rsqsim = !k && (fm & FMT_RSQSIM),
                                  .eqsim = k && (fm & FMT_EQSIM)};
        int want_sim = !cli->quads && (fm & (FMT_RSQSIM | FMT_EQSIM));
        if (want_sim)
            sim_say(&cli->sim, &fs, sa);
        if (fm & FMT_IGS)
            side_start(&igs);
        for (int k = 0; k < 2 && want_sim; k++)
            if (sim[k].rsqsim || sim[k].eqsim)
                side_start(&sim[k]);
        if (cli->quads)
            sst = write_quads(cli, &fs, rs->sheet, sa, rs->outputs, &err);
        else if (fm & (FMT_ALL & ~(FMT_IGS | FMT_RSQSIM | FMT_EQSIM | FMT_HTML | FMT_NAMES)))
            st = fm_faultset_write_all(&fs, &out, cli->jobs, &err);
        if (fm & FMT_IGS)
            cst = side_join(&igs, rs->outputs);
        for (int k = 0; k < 2 && want_sim; k++)
            if (sim[k].rsqsim || sim[k].eqsim) {
                fm_status ks = side_join(&sim[k], rs->outputs);
                sst = sst != FM_OK ? sst : ks;
            }
        if (fm & FMT_NAMES) {
            char *names = path; /* the first path's room, free again */
            snprintf(names, n, "%s/names.csv", cli->dir);
            nst = write_names_csv(names, &fs, &err);
            outputs_note(rs->outputs, names, SIZE_MAX, OUTPUT_REPORT, nst == FM_OK ? NULL : &err);
        }
        st = st != FM_OK ? st : cst != FM_OK ? cst : sst != FM_OK ? sst : nst;
    }
    free(path);
    free(tags);
    free(sheet);
    fm_faultset_free_file_names(pnames, rs->nfaults);
    free_junction_sets(&js);
    fm_mesh_destroy(converted);
    fm_reproject_destroy(rp);
    return st;
}
