/* fm_run_execute and fm_run_result_write: a whole run, in the order
 * `faultmesh remesh` has always taken: every file read and fitted on the
 * threads, the junction plan, the meshes (and rounds of meshing again),
 * the merge, the last guard and the connect measures; then the outputs,
 * report.html beside them, and report.json. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <pthread.h>

#include "fm_clock.h"
#include "fm_reproject.h"
#include "run_internal.h"

static void told(void *user, size_t done, size_t total)
{
    run_progress_set(user, done, total, "outlines and pairs");
}

/* The settings file's per-fault sizes, join distances, tops and joins as
 * the plan takes them. */
typedef struct per_fault {
    double *distance, *size;
    unsigned char *cut, *joins;
} per_fault;

static void per_fault_free(per_fault *pf)
{
    free(pf->distance);
    free(pf->size);
    free(pf->cut);
    free(pf->joins);
}

static int per_fault_make(per_fault *pf, fault_result *const *res, size_t n,
                          fm_connect_plan_options *po)
{
    pf->distance = malloc((n + 1) * sizeof *pf->distance);
    pf->size = malloc((n + 1) * sizeof *pf->size);
    pf->cut = malloc(n + 1);
    pf->joins = malloc(n + 1);
    if (!pf->distance || !pf->size || !pf->cut || !pf->joins) {
        per_fault_free(pf);
        return -1;
    }
    for (size_t f = 0; f < n; f++) {
        const fault_result *r = res[f];
        pf->distance[f] = r->join;
        pf->size[f] = r->mesh.size;
        pf->cut[f] = r->mesh.top != FM_TOP_KEEP;
        pf->joins[f] = (unsigned char)r->connect;
        /* the search reaches the farthest any pair joins; triple points
         * merge at the finest size */
        po->distance = fmax(po->distance, r->join);
        po->size = fmin(po->size, r->mesh.size);
    }
    po->fault_distance = pf->distance;
    po->fault_size = pf->size;
    po->fault_cut = pf->cut;
    po->fault_joins = pf->joins;
    return 0;
}

/* The plan's pairs and near-duplicates as an earlier run on the same
 * models and options kept them in the fit cache's folder (*kept; NULL
 * when none): only when every fault's model has its fit-cache key, which
 * stands for the model bit for bit. Returns whether they were looked up
 * (key made), so that, when not found, the plan's are stored under it. */
static int kept_neighbours(const remesh_cli *cli, fault_result *const *res, size_t n,
                           const fm_connect_plan_options *po,
                           unsigned char key[FM_CONNECT_KEY_BYTES],
                           fm_connect_neighbours **kept, run_state *rs)
{
    *kept = NULL;
    if (!cli->cache || !n)
        return 0;
    for (size_t f = 0; f < n; f++)
        if (!res[f]->has_key)
            return 0;
    unsigned char(*keys)[FM_MODEL_KEY_BYTES] = malloc(n * sizeof *keys);
    if (!keys)
        return 0;
    for (size_t f = 0; f < n; f++)
        memcpy(keys[f], res[f]->model_key, FM_MODEL_KEY_BYTES);
    fm_connect_neighbours_key((const unsigned char(*)[FM_MODEL_KEY_BYTES])keys, n, po, key);
    free(keys);
    fm_error cerr;
    int rejected = fm_connect_neighbours_get(cli->cache, key, n, kept, &cerr) != FM_OK;
    rs->neighbours = *kept ? NEIGHBOURS_HIT : rejected ? NEIGHBOURS_REJECTED : NEIGHBOURS_MISS;
    return 1;
}

/* The junction plan over every fitted fault (objects in input order);
 * faults it gives up as near-duplicates are marked "dropped". NULL when
 * there is nothing to join or the plan failed (reported; the faults are
 * then meshed unconnected). */
static fm_connect_plan *make_plan(const remesh_cli *cli, file_job *jobs, size_t njobs,
                                  run_state *rs)
{
    size_t n = 0;
    for (size_t i = 0; i < njobs; i++) {
        jobs[i].first = n;
        n += jobs[i].model ? jobs[i].n : 0;
    }
    const fm_model **models = calloc(n + 1, sizeof *models);
    fault_result **res = calloc(n + 1, sizeof *res);
    rs->plan_res = calloc(n + 1, sizeof *rs->plan_res);
    if (!models || !res || !rs->plan_res) {
        free(models);
        free(res);
        return NULL;
    }
    rs->nplan_faults = n;
    for (size_t i = 0; i < njobs; i++)
        for (size_t o = 0; jobs[i].model && o < jobs[i].n; o++) {
            models[jobs[i].first + o] = jobs[i].model[o];
            res[jobs[i].first + o] = &jobs[i].res[o];
        }
    fm_connect_plan_options po;
    fm_connect_plan_options_default(&po);
    po.distance = cli->join;
    po.size = cli->mesh.size;
    po.cut = cli->mesh.top != FM_TOP_KEEP;
    po.sea_level = cli->mesh.sea_level;
    po.nthreads = cli->jobs;
    po.duplicates.keep = cli->keep;
    po.progress = told;
    po.progress_user = cli->ctl;
    per_fault pf = {0};
    if (cli->nrules && per_fault_make(&pf, res, n, &po)) {
        free(models);
        free(res);
        run_log(cli->ctl, FM_LOG_WARN, "out of memory: meshing faults unconnected");
        return NULL;
    }
    fm_connect_plan *plan = NULL;
    fm_error err;
    fm_error_clear(&err);
    unsigned char nkey[FM_CONNECT_KEY_BYTES];
    fm_connect_neighbours *kept = NULL;
    int keyed = kept_neighbours(cli, res, n, &po, nkey, &kept, rs);
    po.neighbours = kept;
    fm_status st = fm_connect_plan_build(models, n, &po, &plan, &err);
    fm_connect_neighbours_destroy(kept);
    if (st == FM_OK) {
        rs->curves_kept = fm_connect_plan_get_stats(plan)->pairs_kept;
        rs->curves_traced = fm_connect_plan_get_stats(plan)->pairs_traced;
    }
    if (st == FM_OK && keyed && !kept) {
        fm_error cerr;
        if (fm_connect_neighbours_put(cli->cache, nkey, n, plan, &cerr) != FM_OK)
            rs->neighbours = NEIGHBOURS_UNSTORED;
    }
    per_fault_free(&pf);
    free(models);
    if (st != FM_OK) {
        run_log(cli->ctl, FM_LOG_WARN, "connecting faults failed, meshing them unconnected: %s",
                err.message);
        free(res);
        return NULL;
    }
    for (size_t f = 0; f < n; f++) {
        const fm_connect_duplicate *d;
        if (!fm_connect_plan_dropped(plan, f, &d))
            continue;
        fault_result *r = res[f];
        char msg[512];
        /* the two shares the rule decides on come first: the pair is a
         * near-duplicate because one of them reaches min_share, which the
         * share of the fault given up alone often does not */
        if (d)
            snprintf(msg, sizeof msg,
                     "near-duplicate of %s: %.0f%% of that one's area lies within %.0f m of "
                     "this fault, %.0f%% of this one's within %.0f m of it (a pair is a "
                     "near-duplicate when either share reaches %.0f%%); that one, the %s of the "
                     "two, is kept; the faults this one pairs with cover %.0f%% of it",
                     res[d->kept]->name, 100 * d->share[1], po.duplicates.tolerance,
                     100 * d->share[0], po.duplicates.tolerance, 100 * po.duplicates.min_share,
                     d->area[1] > d->area[0] ? "larger" : "smaller", 100 * d->cover);
        else
            snprintf(msg, sizeof msg, "near-duplicate of another fault");
        r->status = "dropped";
        r->error = strdup(msg);
    }
    free(res);
    return plan;
}

/* The CRS of the run: --crs, else the one the inputs name (all that name
 * one must name the same), else the CFM's. An error saying why when the
 * inputs disagree or memory runs out. */
static fm_status settle_crs(const remesh_cli *cli, const file_job *jobs, size_t njobs,
                            run_state *rs, fm_error *err)
{
    const char *crs = cli->crs, *from = NULL;
    rs->crs_source = "option";
    if (!crs) {
        for (size_t i = 0; i < njobs; i++)
            for (size_t o = 0; o < jobs[i].nobj; o++) {
                const char *c = fm_tsurf_crs_code(jobs[i].objs[o]);
                if (!c)
                    continue;
                if (crs && strcmp(c, crs) != 0)
                    return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                        "the inputs name different coordinate systems (%s in "
                                        "%s, %s in %s): say which with --crs",
                                        crs, from, c, jobs[i].path);
                crs = c;
                from = jobs[i].path;
            }
        rs->crs_source = crs ? "input" : "default";
        if (!crs)
            crs = "EPSG:26711";
    }
    fm_error e;
    fm_error_clear(&e);
    if (cli->crs_out && fm_reproject_check(crs, cli->crs_out, &e) != FM_OK)
        return fm_error_set(err, e.code, NULL, 0, "--crs-out: %s", e.message);
    /* EQSim's latitudes and longitudes come from the outputs' CRS */
    const char *out = cli->crs_out ? cli->crs_out : crs;
    if (cli->sim.eqsim == FM_EQSIM_SPHERICAL && fm_eqsim_check_crs(out, &e) != FM_OK)
        return fm_error_set(err, e.code, NULL, 0, "%s; give --crs, or --eqsim-coords utm",
                            e.message);
    rs->crs = strdup(crs);
    return rs->crs ? FM_OK : fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
}

/* A report written (err NULL) or not. */
static void note_report(output_log *log, const char *name, const fm_error *err)
{
    size_t n = strlen(log->dir) + strlen(name) + 2;
    char *p = malloc(n);
    if (p)
        snprintf(p, n, "%s/%s", log->dir, name);
    outputs_note(log, p ? p : name, SIZE_MAX, OUTPUT_REPORT, err);
    free(p);
}

typedef struct html_job {
    const remesh_cli *cli;
    const run_state *rs;
    fm_status st;
    fm_error err;
} html_job;

static void *html_worker(void *arg)
{
    html_job *h = arg;
    fm_error_clear(&h->err);
    h->st = write_report_html(h->cli, h->rs, &h->err);
    return NULL;
}

/* The whole run, bounded as each fault is (fit_file): refused before the
 * junctions and meshes are made when its faults together call for more
 * triangles than the limit. An error saying so. */
static fm_status too_many_triangles(const remesh_cli *cli, const file_job *jobs, size_t n,
                                    fm_error *err)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t o = 0; jobs[i].model && o < jobs[i].n; o++)
            if (jobs[i].model[o])
                sum += jobs[i].res[o].expected;
    if (!cli->max_triangles || sum <= (double)cli->max_triangles)
        return FM_OK;
    return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                        "at the sizes asked the faults call for about %.3g triangles, more "
                        "than --max-triangles %zu: give a larger size, or raise the limit",
                        sum, cli->max_triangles);
}

/* `--top extend D` grows tops over the fitted surface's extension, which
 * must reach that far up dip: D of depth is D / sin(dip) along a fault,
 * so the margin grows with D (the default 2 km is for closing gaps). */
void extend_fit(remesh_cli *cli)
{
    if (cli->mesh.top == FM_TOP_EXTEND)
        cli->model.fit.extend = fmax(cli->model.fit.extend, 1.5 * cli->mesh.top_extend + cli->mesh.size);
    /* A gap of D to a fault met at an angle is longer than D over the
     * ending fault's own surface (D / sin of the angle): twice D covers
     * angles down to 30 degrees (the default 2 km is that for D = 1 km). */
    if (cli->connect)
        cli->model.fit.extend = fmax(cli->model.fit.extend, 2 * cli->join);
}

static void release_jobs(fm_run_result *res)
{
    for (size_t i = 0; res->jobs && i < res->njobs; i++)
        release_job(&res->jobs[i]);
    free(res->jobs);
    res->jobs = NULL;
}

/* The jobs given up before they were merged. */
static fm_status give_up(fm_run_result *res, fm_status st)
{
    for (size_t i = 0; i < res->njobs; i++)
        abandon_job(&res->jobs[i]);
    free(res->jobs);
    res->jobs = NULL;
    fm_run_result_destroy(res);
    return st;
}

static fm_status cancelled(fm_run_result *res, fm_error *err)
{
    fm_error_set(err, FM_ERR_CANCELLED, NULL, 0, "cancelled");
    return give_up(res, FM_ERR_CANCELLED);
}

fm_status run_execute(fm_run_result *res, const char *const *files,
                      const fm_mesh *const *meshes, size_t nfiles, fm_error *err)
{
    const remesh_cli *cli = &res->cli;
    run_state *rs = &res->rs;
    rs->ctl = cli->ctl;
    rs->outputs = &res->outputs;
    res->outputs.ctl = cli->ctl;
    rs->set = fm_mesh_create();
    file_job *jobs = calloc(nfiles > 0 ? nfiles : 1, sizeof *jobs);
    res->jobs = jobs;
    res->njobs = nfiles;
    if (!rs->set || !jobs) {
        fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        return give_up(res, FM_ERR_NOMEM);
    }
    for (size_t i = 0; i < nfiles; i++) {
        jobs[i].path = files[i];
        jobs[i].given = meshes[i];
        jobs[i].ctl = cli->ctl;
    }
    double t0 = fm_clock_seconds();
    /* the checks of what was read belong to its stage, so that the log's
     * time for it is the summary's */
    run_jobs_open(cli, NULL, 0, NULL, jobs, nfiles);
    fm_status st = FM_OK;
    if (!run_cancelled(cli->ctl)) {
        st = too_many_triangles(cli, jobs, nfiles, err);
        if (st == FM_OK)
            st = settle_crs(cli, jobs, nfiles, rs, err);
    }
    run_progress_end(cli->ctl);
    double t1 = fm_clock_seconds();
    if (run_cancelled(cli->ctl))
        return cancelled(res, err);
    if (st != FM_OK)
        return give_up(res, st);
    fm_connect_plan *plan = NULL;
    if (cli->connect) {
        run_progress_begin(cli->ctl, "connect", 0, NULL, 0);
        plan = make_plan(cli, jobs, nfiles, rs);
        run_progress_end(cli->ctl);
    }
    res->plan = plan;
    if (run_cancelled(cli->ctl))
        return cancelled(res, err);
    double t2 = fm_clock_seconds();
    run_jobs(cli, plan, 1, NULL, jobs, nfiles);
    if (plan && !run_cancelled(cli->ctl))
        rs->mesh_rounds = settle_curves(cli, plan, jobs, nfiles);
    if (run_cancelled(cli->ctl))
        return cancelled(res, err);
    double t3 = fm_clock_seconds();
    run_progress_begin(cli->ctl, "merge and check", 0, NULL, 0);
    rs->plan = plan;
    if (plan) {
        size_t nn = fm_connect_plan_nnodes(plan);
        rs->node_vertex = malloc((nn + 1) * sizeof *rs->node_vertex);
        for (size_t k = 0; rs->node_vertex && k < nn; k++)
            rs->node_vertex[k] = -1;
    }
    for (size_t i = 0; i < nfiles; i++)
        merge_job(cli, &jobs[i], rs);
    if (plan && cli->carve)
        carve_set(cli, rs);
    measure_loss(cli, rs);
    if (compact_set(rs))
        run_log(cli->ctl, FM_LOG_WARN, "out of memory: the outputs keep points of no triangle");
    check_elastic(cli, rs);
    run_progress_end(cli->ctl);
    res->t4 = fm_clock_seconds();
    rs->time[0] = t1 - t0;
    rs->time[1] = t2 - t1;
    rs->time[2] = t3 - t2;
    rs->time[3] = res->t4 - t3;
    return FM_OK;
}

fm_status fm_run_result_write(fm_run_result *res, const char *dir, unsigned formats,
                              fm_error *err)
{
    if (!res || !dir || res->written || (formats & ~res->cli.formats))
        return fm_error_set(err, FM_ERR_INVALID, dir, 0,
                            !res || !dir || res->written
                                ? "a run's outputs are written once, into a folder"
                                : "outputs asked for that the run's options did not include");
    /* the summary names the folder after the call: a copy, since a
     * caller's string (a binding's temporary) need not live that long */
    res->dir = strdup(dir);
    if (!res->dir)
        return fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    res->written = 1;
    /* the write's time runs from here: what the caller did between the
     * run and its writing is no stage of the log */
    double tw = fm_clock_seconds();
    remesh_cli *cli = &res->cli;
    run_state *rs = &res->rs;
    cli->dir = res->dir;
    cli->formats = formats;
    res->outputs.dir = res->dir;
    output_log *outputs = &res->outputs;
    /* report.html is an output, timed with the writes. It needs the
     * originals, which go with the jobs; with threads to spare it is drawn
     * beside the other writers (both only read the run). */
    html_job hj = {cli, rs, FM_OK, {0}};
    pthread_t html_thread;
    int html_async = 0;
    int html = cli->html && (cli->formats & FMT_HTML);
    if (html && cli->jobs > 1)
        html_async = pthread_create(&html_thread, NULL, html_worker, &hj) == 0;
    if (html && !html_async) {
        run_progress_begin(cli->ctl, "write report.html", 0, NULL, 0);
        html_worker(&hj);
        run_progress_end(cli->ctl);
    }
    sim_attrs sa;
    run_progress_begin(cli->ctl, "write", 0, NULL, 0);
    /* noted only on this thread: report.html's does not look at it */
    fm_status first = write_set(cli, rs, &sa);
    /* --stiffness-matrix: a file of the user's naming, anywhere */
    if (cli->stiffness_path) {
        fm_error serr;
        fm_error_clear(&serr);
        fm_status sst = write_stiffness(cli, rs, &serr);
        outputs_note(outputs, cli->stiffness_path, SIZE_MAX, OUTPUT_REPORT,
                     sst == FM_OK ? NULL : &serr);
        if (first == FM_OK && sst != FM_OK) {
            first = sst;
            if (err)
                *err = serr;
        }
    }
    if (html_async)
        pthread_join(html_thread, NULL);
    if (html)
        note_report(outputs, "report.html", hj.st == FM_OK ? NULL : &hj.err);
    if (first == FM_OK && html && hj.st != FM_OK) {
        first = hj.st;
        if (err)
            *err = hj.err;
    }
    release_jobs(res);
    rs->time[4] = fm_clock_seconds() - tw;
    /* the stage ends with the time report.json records for it, so that
     * the log and the summary agree */
    run_progress_end(cli->ctl);
    /* report.json even when the meshes could not be written: it says what
     * each fault came to, and which files are missing */
    fm_error rerr;
    fm_error_clear(&rerr);
    fm_status rst = write_report(cli, rs, sa.slip ? &sa : NULL, &rerr);
    sim_attrs_free(&sa);
    note_report(outputs, "report.json", rst == FM_OK ? NULL : &rerr);
    if (first == FM_OK && rst != FM_OK) {
        first = rst;
        if (err)
            *err = rerr;
    }
    if (first == FM_OK && outputs->unwritten)
        first = fm_error_set(err, FM_ERR_IO, dir, 0, "%zu files not written",
                             outputs->unwritten);
    return first;
}

char *fm_run_result_summary(const fm_run_result *res)
{
    char *text = NULL;
    size_t n = 0;
    FILE *out = open_memstream(&text, &n);
    if (!out)
        return NULL;
    print_summary(&res->cli, &res->rs, out);
    if (fclose(out)) {
        free(text);
        return NULL;
    }
    return text;
}

void run_state_free(run_state *rs)
{
    for (size_t i = 0; i < rs->nres; i++) {
        free(rs->res[i].file);
        free(rs->res[i].name);
        free(rs->res[i].error);
        free(rs->res[i].join_failed);
        free(rs->res[i].join_error);
        free(rs->res[i].dropped_curves);
        free(rs->res[i].through_curves);
        free(rs->res[i].used_curves);
        free(rs->res[i].curve_pieces);
        for (size_t k = 0; k < rs->res[i].ncad; k++)
            fm_cad_face_destroy(rs->res[i].cad[k]);
        free(rs->res[i].cad);
    }
    free(rs->cad);
    free(rs->res);
    free(rs->set_res);
    free(rs->set_orig);
    free(rs->sheet);
    fm_carve_result_destroy(rs->carve);
    fm_carve_result_destroy(rs->sheet_carve);
    fm_loss_destroy(rs->loss);
    free_elastic(rs);
    free(rs->sheet_unit_fault);
    free(rs->sheet_unit_first);
    free(rs->names);
    free(rs->node_vertex);
    free(rs->plan_res);
    free(rs->crs);
    fm_mesh_destroy(rs->set);
    memset(rs, 0, sizeof *rs);
}

void fm_run_result_destroy(fm_run_result *res)
{
    if (!res)
        return;
    release_jobs(res);
    run_state_free(&res->rs);
    fm_connect_plan_destroy(res->plan);
    outputs_free(&res->outputs);
    release_cache(&res->cli);
    sim_cli_free(&res->cli.sim);
    run_ctl_destroy(res->ctl);
    run_strings_unref(res->strings);
    run_config_unref(res->config);
    free(res->dir);
    free(res);
}
