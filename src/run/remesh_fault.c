/* `faultmesh remesh`, one fault: read, repaired and fitted; meshed with
 * the shared curves the plan gives it; checked against the original. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_check.h"
#include "fm_clock.h"
#include "fm_closest.h"
#include "fm_model_cache.h"
#include "fm_sort.h"
#include "fm_tsurf.h"
#include "remesh_cad.h"
#include "run_internal.h"

static int push_curve(size_t **list, size_t *n, size_t curve)
{
    size_t *g = realloc(*list, (*n + 1) * sizeof *g);
    if (!g)
        return -1;
    *list = g;
    g[(*n)++] = curve;
    return 0;
}

/* Which pieces of its plan curves fault f holds (an edge between two
 * consecutive nodes of the curve), given the edges of its mesh between
 * shared nodes (fm_remesh_shared_edges): a sheet keeps only part of a
 * curve that another of its curves cuts across. -1: out of memory. */
int curve_pieces(const fm_connect_plan *plan, size_t f, size_t nsheets,
                 const fm_keyed *edge, size_t ne, fault_result *r)
{
    free(r->curve_pieces);
    r->curve_pieces = NULL;
    r->npieces = 0;
    size_t cap = 0;
    int rc = 0;
    for (size_t s = 0; rc == 0 && s < nsheets; s++) {
        const fm_connect_shared *sh;
        size_t n = fm_connect_plan_sheet(plan, f, s, &sh);
        for (size_t c = 0; rc == 0 && c < n; c++)
            for (size_t i = 0; i + 1 < sh[c].n; i++) {
                uint64_t key = fm_edge_key((uint64_t)sh[c].node[i], (uint64_t)sh[c].node[i + 1]);
                size_t at = fm_keyed_lower_bound(edge, ne, key);
                if (at == ne || edge[at].key != key)
                    continue;
                if (r->npieces == cap) {
                    cap = cap ? 2 * cap : 64;
                    fm_keyed *g = realloc(r->curve_pieces, cap * sizeof *g);
                    if (!g) {
                        rc = -1;
                        break;
                    }
                    r->curve_pieces = g;
                }
                /* by its nodes, not its place in the sheet's list: the
                 * sheets of two faults may hold different stretches */
                r->curve_pieces[r->npieces] = (fm_keyed){key, sh[c].curve};
                r->npieces++;
            }
    }
    /* by key, for share_piece's search */
    if (rc == 0 && fm_sort_keyed(r->curve_pieces, r->npieces))
        rc = -1;
    return rc;
}

/* Whether v (sorted by key) holds the entry (key, index). */
static int keyed_holds(const fm_keyed *v, size_t n, uint64_t key, size_t index)
{
    for (size_t at = fm_keyed_lower_bound(v, n, key); at < n && v[at].key == key; at++)
        if (v[at].index == index)
            return 1;
    return 0;
}

/* Whether b holds piece i of a (of plan curve c). */
static int also_held(const fault_result *a, size_t i, const fault_result *b, size_t c)
{
    return keyed_holds(b->curve_pieces, b->npieces, a->curve_pieces[i].key, c);
}

/* Whether faults a and b both hold some piece of plan curve c. */
int share_piece(const fault_result *a, const fault_result *b, size_t c)
{
    for (size_t i = 0; i < a->npieces; i++)
        if (a->curve_pieces[i].index == c && also_held(a, i, b, c))
            return 1;
    return 0;
}

double shared_length(const fault_result *a, const fault_result *b, size_t c, const double *nodes)
{
    double len = 0;
    for (size_t i = 0; i < a->npieces; i++) {
        if (a->curve_pieces[i].index != c || !also_held(a, i, b, c) ||
            (i > 0 && a->curve_pieces[i - 1].key == a->curve_pieces[i].key &&
             a->curve_pieces[i - 1].index == c))
            continue;
        uint64_t key = a->curve_pieces[i].key;
        const double *p = nodes + 3 * (key >> 32), *q = nodes + 3 * (key & 0xffffffffu);
        len += sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                    (p[2] - q[2]) * (p[2] - q[2]));
    }
    return len;
}

/* Area of a triangle's part with z <= level. */
static double area_below(const double *a, const double *b, const double *c, double level)
{
    const double *p[3] = {a, b, c};
    double poly[4][3];
    int n = 0;
    for (int i = 0; i < 3; i++) {
        const double *u = p[i], *v = p[(i + 1) % 3];
        double du = u[2] - level, dv = v[2] - level;
        if (du <= 0)
            memcpy(poly[n++], u, sizeof poly[0]);
        if ((du < 0 && dv > 0) || (du > 0 && dv < 0)) {
            double f = du / (du - dv);
            for (int k = 0; k < 3; k++)
                poly[n][k] = u[k] + f * (v[k] - u[k]);
            n++;
        }
    }
    double area = 0;
    for (int i = 1; i + 1 < n; i++)
        area += fm_triangle_area(poly[0], poly[i], poly[i + 1]);
    return area;
}

static double fitted_area(const fm_model *m, int cut, double level)
{
    double area = 0;
    for (size_t i = 0; i < fm_model_nsheets(m); i++) {
        const fm_mesh *s = fm_model_samples(m, i);
        if (!s)
            continue;
        const double *X = fm_mesh_vertices(s);
        const int32_t *T = fm_mesh_triangles(s);
        for (size_t t = 0; t < fm_mesh_ntriangles(s); t++) {
            const double *a = X + 3 * T[3 * t], *b = X + 3 * T[3 * t + 1], *c = X + 3 * T[3 * t + 2];
            area += cut ? area_below(a, b, c, level) : fm_triangle_area(a, b, c);
        }
    }
    return area;
}

/* A fault's own options: the run's, with what the settings file says of
 * it by name. */
static void fault_options(const remesh_cli *cli, fault_result *r)
{
    fm_fault_settings_lookup(cli->rules, cli->nrules, r->name, &r->fc);
    r->mesh = cli->mesh;
    if (r->fc.has_size)
        r->mesh.size = r->fc.size;
    if (r->fc.has_top) {
        r->mesh.top = r->fc.top;
        r->mesh.top_extend = r->fc.top_extend;
    }
    r->join = r->fc.has_join ? r->fc.join : cli->join;
    r->connect = cli->connect && !(r->fc.has_connect && !r->fc.connect);
    r->want_cad = (cli->formats & FMT_IGS) != 0;
}

/* Repairs and fits one fault (one TSurf object). Its surface reaches as
 * far past its outline as its top and its joins need (extend_fit). */
static fm_status fit_object(const remesh_cli *cli, const char *path, const fm_mesh *orig,
                            fault_result *r, fm_model **model, fm_error *err)
{
    fm_surface *surf = NULL;
    double t0 = fm_clock_seconds();
    fm_model_options mopt = cli->model;
    if (r->mesh.top == FM_TOP_EXTEND)
        mopt.fit.extend = fmax(mopt.fit.extend, 1.5 * r->mesh.top_extend + r->mesh.size);
    if (r->connect)
        mopt.fit.extend = fmax(mopt.fit.extend, 2 * r->join);
    /* The cache's key is made of the object as read and the options the
     * fit is given here, so a model read from it is this fault's, with
     * these options, as this build fits it (fm_model_cache.h). A file
     * the cache rejects is fitted again and stored anew. */
    unsigned char key[FM_MODEL_KEY_BYTES];
    if (cli->cache) {
        fm_model_key(orig, &cli->repair, &mopt, key);
        memcpy(r->model_key, key, sizeof key);
        r->has_key = 1;
        fm_error cerr;
        r->cache_rejected = fm_model_cache_get(cli->cache, key, model, &cerr) != FM_OK;
        r->fit_cache = *model ? FIT_CACHE_HIT : FIT_CACHE_MISS;
        if (*model) {
            r->t_fit = fm_clock_seconds() - t0;
            return FM_OK;
        }
    }
    fm_status st = fm_repair(orig, &cli->repair, &surf, err);
    /* else it would pass for a fault wholly above sea level ("empty") */
    if (st == FM_OK && fm_surface_nsheets(surf) == 0)
        st = fm_error_set(err, FM_ERR_INVALID, path, 0,
                          "%s: nothing left after repair (every triangle degenerate, duplicate or "
                          "in a fragment dropped)",
                          r->name);
    if (st == FM_OK)
        st = fm_model_build(path, surf, &mopt, model, err);
    fm_surface_destroy(surf);
    if (st == FM_OK && cli->cache) {
        fm_error cerr;
        r->cache_unstored = fm_model_cache_put(cli->cache, key, *model, &cerr) != FM_OK;
    }
    r->t_fit = fm_clock_seconds() - t0;
    return st;
}

/* Whether the filter keeps edge (a, b) of curve c. */
static int edge_kept(const curve_filter *flt, size_t c, int64_t a, int64_t b)
{
    return keyed_holds(flt->keep, flt->nkeep, fm_edge_key((uint64_t)a, (uint64_t)b), c);
}

/* The stretches of a sheet's curve the filter keeps, as (first node, nodes)
 * pairs into runs when not NULL (room for sh->n + 1 pairs); their count. */
static size_t kept_runs(const fm_connect_shared *sh, const curve_filter *flt, size_t *runs)
{
    if (flt && flt->excluded[sh->curve])
        return 0;
    if (!flt || !flt->clipped[sh->curve]) {
        if (runs) {
            runs[0] = 0;
            runs[1] = sh->n;
        }
        return 1;
    }
    size_t n = 0, start = SIZE_MAX;
    for (size_t i = 0; i + 1 <= sh->n; i++) {
        int keep = i + 1 < sh->n && edge_kept(flt, sh->curve, sh->node[i], sh->node[i + 1]);
        if (keep && start == SIZE_MAX)
            start = i;
        if (!keep && start != SIZE_MAX) {
            if (runs) {
                runs[2 * n] = start;
                runs[2 * n + 1] = i - start + 1;
            }
            n++;
            start = SIZE_MAX;
        }
    }
    return n;
}

/* Plan curve c as sheet s of fault f holds it: whether it lives on that
 * sheet only (where a junction was given up and one sheet stops short of
 * the other instead), and the sheet it is shared with (fault * 65536 +
 * sheet; -1 when none). */
static int curve_side(const fm_connect_plan *plan, size_t c, size_t f, size_t s, long *partner)
{
    *partner = -1;
    for (size_t i = 0; i < fm_connect_plan_njunctions(plan); i++) {
        const fm_connect_junction *jn = fm_connect_plan_junction(plan, i);
        if (jn->curve != (long)c)
            continue;
        int o = jn->fault[0] == f && jn->sheet[0] == s;
        *partner = (long)(jn->fault[o] * 65536 + jn->sheet[o]);
        return jn->type == FM_JUNCTION_UNJOINED;
    }
    return 0;
}

/* The shared curves the plan gives each sheet of fault f, as the mesher
 * takes them, less what the filter leaves out (a clipped curve may give
 * several); *store (free it) holds them, and per curve given its plan
 * curve and a flag the mesher sets when it drops it. NULL when there are
 * none. */
static fm_remesh_sheet_curves *plan_curves(const fm_connect_plan *plan, size_t f,
                                           const fm_model *m, const curve_filter *flt,
                                           fm_remesh_curve **store, unsigned char **dropped,
                                           size_t **curve_of, size_t *ntotal)
{
    *store = NULL;
    *dropped = NULL;
    *curve_of = NULL;
    *ntotal = 0;
    if (!plan)
        return NULL;
    size_t ns = fm_model_nsheets(m), total = 0, longest = 0;
    for (size_t i = 0; i < ns; i++) {
        const fm_connect_shared *sh;
        size_t n = fm_connect_plan_sheet(plan, f, i, &sh);
        for (size_t c = 0; c < n; c++) {
            total += kept_runs(&sh[c], flt, NULL);
            longest = sh[c].n > longest ? sh[c].n : longest;
        }
    }
    if (total == 0)
        return NULL;
    fm_remesh_sheet_curves *per = calloc(ns, sizeof *per);
    fm_remesh_curve *cv = malloc(total * sizeof *cv);
    size_t *runs = malloc(2 * (longest + 1) * sizeof *runs);
    *dropped = calloc(total, 1);
    *curve_of = malloc(total * sizeof **curve_of);
    if (!per || !cv || !runs || !*dropped || !*curve_of) {
        free(per);
        free(cv);
        free(runs);
        free(*dropped);
        free(*curve_of);
        *dropped = NULL;
        *curve_of = NULL;
        return NULL;
    }
    *ntotal = total;
    size_t k = 0;
    for (size_t i = 0; i < ns; i++) {
        const fm_connect_shared *sh;
        size_t n = fm_connect_plan_sheet(plan, f, i, &sh);
        per[i].curves = cv + k;
        per[i].dropped = *dropped + k;
        for (size_t c = 0; c < n; c++) {
            size_t nr = kept_runs(&sh[c], flt, runs);
            for (size_t q = 0; q < nr; q++) {
                size_t at = runs[2 * q];
                per[i].n++;
                (*curve_of)[k] = sh[c].curve;
                cv[k].uv = sh[c].uv + 2 * at;
                cv[k].n = runs[2 * q + 1];
                cv[k].node = sh[c].node + at;
                cv[k].end = sh[c].end;
                cv[k].lone = curve_side(plan, sh[c].curve, f, i, &cv[k].partner);
                k++;
            }
        }
    }
    free(runs);
    *store = cv;
    return per;
}

/* Meshes a fitted fault into fault (tags = sheet; ids: shared node per
 * vertex) with its options (r->mesh) and checks it against the original. */
static fm_status mesh_object(const char *path, const fm_mesh *orig,
                             const fm_model *model, const fm_connect_plan *plan,
                             const curve_filter *flt, size_t f, fault_result *r,
                             fm_mesh **fault, int64_t **ids, run_ctl *ctl, fm_error *err)
{
    double t1 = fm_clock_seconds();
    fm_remesh_options mo = r->mesh;
    mo.name = path;
    mo.flap_max = r->join;
    fm_remesh_curve *store = NULL;
    unsigned char *dropped = NULL;
    size_t *curve_of = NULL, ntotal = 0;
    fm_remesh_sheet_curves *per =
        plan_curves(plan, f, model, flt, &store, &dropped, &curve_of, &ntotal);
    r->sheets = fm_model_nsheets(model);
    r->join_failed = per ? calloc(r->sheets, 1) : NULL;
    fm_error *jerr = per ? calloc(r->sheets, sizeof *jerr) : NULL;
    fm_remesh_boundary *bounds = calloc(r->sheets + 1, sizeof *bounds);
    fm_status st = ((per && (!r->join_failed || !jerr)) || !bounds)
                       ? fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory")
                       : fm_remesh_model_joined(model, per, &mo, fault, ids, r->join_failed, jerr,
                                                &r->ms, bounds, err);
    if (st == FM_OK && r->want_cad) {
        /* which sheets have triangles (tag = sheet) */
        unsigned char *meshed = calloc(r->sheets + 1, 1);
        const int32_t *tag = fm_mesh_tags(*fault);
        for (size_t t = 0; meshed && t < fm_mesh_ntriangles(*fault); t++)
            if (tag[t] >= 0 && (size_t)tag[t] < r->sheets)
                meshed[tag[t]] = 1;
        size_t skipped = 0;
        st = meshed ? run_cad_faces(model, bounds, meshed, r->name,
                                       r->mesh.top != FM_TOP_KEEP, r->mesh.sea_level, &r->cad,
                                       &r->ncad, &skipped, ctl, err)
                    : fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        free(meshed);
    }
    for (size_t i = 0; bounds && i < r->sheets; i++)
        fm_remesh_boundary_free(&bounds[i]);
    free(bounds);
    /* the first reason a sheet's curves did not fit, for the report */
    for (size_t i = 0; jerr && r->join_failed && i < r->sheets && !r->join_error; i++)
        if (r->join_failed[i])
            r->join_error = strdup(jerr[i].message);
    free(jerr);
    /* the plan curves this fault could not take, for the junction table
     * (kept over meshings: a curve dropped once is excluded after), those
     * it took, which its partners must take too, and those of them it was
     * to end at but runs on past */
    free(r->used_curves);
    r->used_curves = ntotal ? malloc(ntotal * sizeof *r->used_curves) : NULL;
    r->nused = 0;
    free(r->through_curves);
    r->through_curves = NULL;
    r->nthrough = 0;
    for (size_t k = 0; k < ntotal && st == FM_OK; k++) {
        if (dropped[k] == 1) {
            if (push_curve(&r->dropped_curves, &r->ndropped, curve_of[k]))
                st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
            continue;
        }
        if (dropped[k] == 2 && push_curve(&r->through_curves, &r->nthrough, curve_of[k]))
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        if (r->used_curves)
            r->used_curves[r->nused++] = curve_of[k];
    }
    free(dropped);
    free(curve_of);
    free(per);
    free(store);
    /* Shared nodes take the plan's position (on both surfaces), as in the
     * fault set, so that the check measures what is written. */
    if (st == FM_OK && plan && *ids) {
        double *X = fm_mesh_vertices_mut(*fault);
        const double *P = fm_connect_plan_nodes(plan);
        for (size_t v = 0; v < fm_mesh_nvertices(*fault); v++)
            if ((*ids)[v] >= 0)
                memcpy(X + 3 * v, P + 3 * (*ids)[v], 3 * sizeof *X);
        size_t ne;
        fm_keyed *edge = fm_remesh_shared_edges(*fault, *ids, -1, &ne);
        if (!edge || curve_pieces(plan, f, fm_model_nsheets(model), edge, ne, r))
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        free(edge);
    }
    double t2 = fm_clock_seconds();
    r->t_mesh = t2 - t1;
    if (st == FM_OK && fm_mesh_ntriangles(*fault) > 0) {
        fm_closest_tree *tree = fm_closest_tree_create_quick(orig, err);
        st = tree ? fm_check_quality(*fault, -1, r->mesh.size, &r->q) : FM_ERR_NOMEM;
        if (st == FM_OK)
            st = fm_check_fidelity(*fault, -1, orig, tree, &r->fid);
        if (st != FM_OK && tree)
            fm_error_set(err, st, path, 0, "out of memory");
        fm_closest_tree_destroy(tree);
    }
    r->t_check = fm_clock_seconds() - t2;
    return st;
}

fm_status tsurf_of_mesh(const char *name, const fm_mesh *m, fm_tsurf **out, fm_error *err)
{
    *out = NULL;
    fm_tsurf *ts = fm_tsurf_create(name); /* its header names it */
    fm_status st = ts ? FM_OK : FM_ERR_NOMEM;
    if (st == FM_OK && fm_tsurf_add_part(ts) < 0)
        st = FM_ERR_NOMEM;
    if (st == FM_OK)
        st = fm_mesh_append(fm_tsurf_mesh_mut(ts), m, 0);
    if (st != FM_OK) {
        fm_tsurf_destroy(ts);
        return fm_error_set(err, st, name, 0, "out of memory");
    }
    *out = ts;
    return FM_OK;
}

/* The input's objects: the file's, or the in-memory mesh's one. */
static fm_status read_input(const file_job *job, fm_tsurf ***objs, size_t *nobj, fm_error *err)
{
    if (!job->given)
        return fm_tsurf_read_file(job->path, objs, nobj, err);
    *objs = calloc(1, sizeof **objs);
    *nobj = 0;
    if (!*objs)
        return fm_error_set(err, FM_ERR_NOMEM, job->path, 0, "out of memory");
    fm_status st = tsurf_of_mesh(job->path, job->given, &(*objs)[0], err);
    if (st != FM_OK) {
        free(*objs);
        *objs = NULL;
        return st;
    }
    *nobj = 1;
    return FM_OK;
}

void fit_file(const remesh_cli *cli, file_job *job)
{
    fm_error err;
    fm_error_clear(&err);
    const char *path = job->path;
    if (read_input(job, &job->objs, &job->nobj, &err) != FM_OK) {
        job->res = calloc(1, sizeof *job->res);
        job->mesh = calloc(1, sizeof *job->mesh);
        job->objs = NULL;
        job->nobj = 0;
        if (job->res) {
            job->n = 1;
            job->res->file = strdup(path);
            job->res->status = "error";
            job->res->error = strdup(err.message);
        }
        return;
    }
    size_t nobj = job->nobj;
    job->res = calloc(nobj ? nobj : 1, sizeof *job->res);
    job->mesh = calloc(nobj ? nobj : 1, sizeof *job->mesh);
    job->model = calloc(nobj ? nobj : 1, sizeof *job->model);
    job->ids = calloc(nobj ? nobj : 1, sizeof *job->ids);
    if (!job->res || !job->mesh || !job->model || !job->ids) {
        free(job->res);
        free(job->mesh);
        free(job->model);
        free(job->ids);
        job->res = NULL;
        job->mesh = NULL;
        job->model = NULL;
        job->ids = NULL;
        return;
    }
    job->n = nobj;
    for (size_t o = 0; o < nobj; o++) {
        fault_result *r = &job->res[o];
        const char *name = fm_tsurf_name(job->objs[o]);
        r->file = strdup(path);
        r->name = strdup(name[0] ? name : path);
        if (!r->file || !r->name) {
            r->status = "error";
            continue;
        }
        fault_options(cli, r);
        if (r->fc.has_exclude && r->fc.exclude) {
            char msg[256];
            if (cli->settings_path)
                snprintf(msg, sizeof msg, "excluded by %s:%ld", cli->settings_path, r->fc.line);
            else
                snprintf(msg, sizeof msg, "excluded by the per-fault settings");
            r->status = "excluded";
            r->error = strdup(msg);
            continue;
        }
        fm_error_clear(&err);
        if (fit_object(cli, path, fm_tsurf_mesh(job->objs[o]), r, &job->model[o], &err) != FM_OK) {
            r->status = "error";
            r->error = strdup(err.message);
            continue;
        }
        /* what its size asks for, before anything is spent on it: an
         * equilateral triangle of side H covers sqrt(3)/4 H^2 */
        r->fitted_area =
            fitted_area(job->model[o], r->mesh.top != FM_TOP_KEEP, r->mesh.sea_level);
        r->expected = r->fitted_area / (0.4330127018922193 * r->mesh.size * r->mesh.size);
        if (cli->max_triangles && r->expected > (double)cli->max_triangles) {
            char msg[400];
            snprintf(msg, sizeof msg,
                     "%s: at size %g m its %.3g km2 call for about %.3g triangles, more than "
                     "--max-triangles %zu: give a larger size, or raise the limit",
                     path, r->mesh.size, r->fitted_area / 1e6, r->expected, cli->max_triangles);
            r->status = "error";
            r->error = strdup(msg);
            fm_model_destroy(job->model[o]);
            job->model[o] = NULL;
        }
    }
}

/* A fault's meshing undone before it is meshed again (its dropped
 * curves stay: the report names the fault that could not take them). */
static void reset_result(fault_result *r)
{
    free(r->error);
    free(r->join_failed);
    free(r->join_error);
    for (size_t i = 0; i < r->ncad; i++)
        fm_cad_face_destroy(r->cad[i]);
    free(r->cad);
    r->cad = NULL;
    r->ncad = 0;
    r->error = r->join_error = NULL;
    r->join_failed = NULL;
    r->status = NULL;
    memset(&r->q, 0, sizeof r->q);
    memset(&r->fid, 0, sizeof r->fid);
    memset(&r->ms, 0, sizeof r->ms);
}

/* Meshes the job's faults; again: only those marked in job->redo, with
 * the curves in excluded left out. Models stay for another round
 * (release_job frees them). */
void mesh_file(const fm_connect_plan *plan, const curve_filter *flt, file_job *job, int again)
{
    if (!job->res || !job->model)
        return;
    fm_error err;
    for (size_t o = 0; o < job->n; o++) {
        fault_result *r = &job->res[o];
        fm_model *model = job->model[o];
        if (!again && model && r->status) {
            /* given up before meshing (a near-duplicate): its model goes here */
            fm_model_destroy(model);
            job->model[o] = NULL;
        }
        if (!model || (again ? !(job->redo && job->redo[o]) : r->status != NULL))
            continue;
        double t_mesh = r->t_mesh, t_check = r->t_check;
        if (again) {
            reset_result(r);
            fm_mesh_destroy(job->mesh[o]);
            job->mesh[o] = NULL;
            free(job->ids[o]);
            job->ids[o] = NULL;
        }
        fm_mesh *fault = NULL;
        fm_error_clear(&err);
        fm_status st = mesh_object(job->path, fm_tsurf_mesh(job->objs[o]), model, plan,
                                   flt, job->first + o, r, &fault, &job->ids[o], job->ctl, &err);
        /* the time of every meshing counts */
        r->t_mesh += t_mesh;
        r->t_check += t_check;
        if (st == FM_OK && fm_mesh_ntriangles(fault) == 0) {
            r->status = "empty";
            r->error = strdup("nothing of the fault lies below sea level");
            fm_mesh_destroy(fault);
        } else if (st == FM_OK) {
            r->status = "ok";
            job->mesh[o] = fault;
        } else {
            r->status = "error";
            r->error = strdup(err.message);
            fm_mesh_destroy(fault);
        }
    }
}

void release_job(file_job *job)
{
    for (size_t o = 0; job->model && o < job->n; o++)
        fm_model_destroy(job->model[o]);
    free(job->model);
    job->model = NULL;
    fm_tsurf_free_all(job->objs, job->nobj);
    job->objs = NULL;
    job->nobj = 0;
    free(job->redo);
    job->redo = NULL;
}

/* Frees a job given up after fitting (the run stops before meshing). */
void abandon_job(file_job *job)
{
    release_job(job);
    for (size_t o = 0; job->res && o < job->n; o++) {
        fault_result *r = &job->res[o];
        free(r->file);
        free(r->name);
        free(r->error);
        free(r->join_failed);
        free(r->join_error);
        free(r->dropped_curves);
        free(r->through_curves);
        free(r->used_curves);
        free(r->curve_pieces);
        for (size_t k = 0; k < r->ncad; k++)
            fm_cad_face_destroy(r->cad[k]);
        free(r->cad);
        fm_mesh_destroy(job->mesh ? job->mesh[o] : NULL);
        free(job->ids ? job->ids[o] : NULL);
    }
    free(job->res);
    free(job->mesh);
    free(job->model);
    free(job->ids);
}
