/* `faultmesh remesh`: every fault of the inputs read, repaired, fitted and
 * meshed at size H, checked, and written as one fault set (VTU, MSH, STL,
 * OBJ, Exodus II, one TSurf per fault) with report.json. `faultmesh demo` runs it on
 * the synthetic fault system. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <pthread.h>

#include "cli.h"
#include "fm_atomic.h"
#include "fm_clock.h"
#include "fm_synth.h"
#include "fm_reproject.h"
#include "remesh_run.h"

static void told(void *user, size_t done, size_t total)
{
    progress_set(user, done, total, "outlines and pairs");
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
    po.progress_user = cli->prog;
    per_fault pf = {0};
    if (cli->cfg && cli->cfg->nfault && per_fault_make(&pf, res, n, &po)) {
        free(models);
        free(res);
        fprintf(stderr, "faultmesh: out of memory: meshing faults unconnected\n");
        return NULL;
    }
    fm_connect_plan *plan = NULL;
    fm_error err;
    fm_error_clear(&err);
    fm_status st = fm_connect_plan_build(models, n, &po, &plan, &err);
    per_fault_free(&pf);
    free(models);
    if (st != FM_OK) {
        fprintf(stderr, "faultmesh: connecting faults failed, meshing them unconnected: %s\n",
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
        if (d)
            snprintf(msg, sizeof msg,
                     "near-duplicate of %s: %.0f%% of its area lies within %.0f m of the faults "
                     "it pairs with (%.0f%% within %.0f m of that one, which is kept: the %s of "
                     "the two)",
                     res[d->kept]->name, 100 * d->cover, po.duplicates.tolerance,
                     100 * d->share[0], po.duplicates.tolerance,
                     d->area[1] > d->area[0] ? "larger" : "smaller");
        else
            snprintf(msg, sizeof msg, "near-duplicate of another fault");
        r->status = "dropped";
        r->error = strdup(msg);
    }
    free(res);
    return plan;
}

/* The CRS of the run: --crs, else the one the inputs name (all that name
 * one must name the same), else the CFM's. -1 after saying why when the
 * inputs disagree or memory runs out. */
static int settle_crs(const remesh_cli *cli, const file_job *jobs, size_t njobs, run_state *rs)
{
    const char *crs = cli->crs, *from = NULL;
    rs->crs_source = "option";
    if (!crs) {
        for (size_t i = 0; i < njobs; i++)
            for (size_t o = 0; o < jobs[i].nobj; o++) {
                const char *c = fm_tsurf_crs_code(jobs[i].objs[o]);
                if (!c)
                    continue;
                if (crs && strcmp(c, crs) != 0) {
                    fprintf(stderr,
                            "faultmesh: the inputs name different coordinate systems (%s in "
                            "%s, %s in %s): say which with --crs\n",
                            crs, from, c, jobs[i].path);
                    return -1;
                }
                crs = c;
                from = jobs[i].path;
            }
        rs->crs_source = crs ? "input" : "default";
        if (!crs)
            crs = "EPSG:26711";
    }
    fm_error err;
    fm_error_clear(&err);
    if (cli->crs_out && fm_reproject_check(crs, cli->crs_out, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: --crs-out: %s\n", err.message);
        return -1;
    }
    /* EQSim's latitudes and longitudes come from the outputs' CRS */
    const char *out = cli->crs_out ? cli->crs_out : crs;
    if (cli->sim.eqsim == FM_EQSIM_SPHERICAL && fm_eqsim_check_crs(out, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s; give --crs, or --eqsim-coords utm\n", err.message);
        return -1;
    }
    rs->crs = strdup(crs);
    return rs->crs ? 0 : -1;
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
 * triangles than the limit. 1 after saying so. */
static int too_many_triangles(const remesh_cli *cli, const file_job *jobs, size_t n)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t o = 0; jobs[i].model && o < jobs[i].n; o++)
            if (jobs[i].model[o])
                sum += jobs[i].res[o].expected;
    if (!cli->max_triangles || sum <= (double)cli->max_triangles)
        return 0;
    fprintf(stderr,
            "faultmesh: at the sizes asked the faults call for about %.3g triangles, more than "
            "--max-triangles %zu: give a larger size, or raise the limit\n",
            sum, cli->max_triangles);
    return 1;
}

static int run(const remesh_cli *cli, char **files, long nfiles)
{
    fm_error err;
    fm_error_clear(&err);
    if (fm_mkdir_p(cli->dir, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        return FM_EXIT_FAILURES;
    }
    output_log outputs = {.dir = cli->dir};
    run_state rs = {.outputs = &outputs};
    rs.set = fm_mesh_create();
    if (!rs.set)
        return FM_EXIT_FAILURES;
    file_job *jobs = calloc(nfiles > 0 ? (size_t)nfiles : 1, sizeof *jobs);
    if (!jobs) {
        fm_mesh_destroy(rs.set);
        return FM_EXIT_FAILURES;
    }
    for (long i = 0; i < nfiles; i++)
        jobs[i].path = files[i];
    double t0 = fm_clock_seconds();
    run_jobs(cli, NULL, 0, NULL, jobs, (size_t)nfiles);
    if (too_many_triangles(cli, jobs, (size_t)nfiles) || settle_crs(cli, jobs, (size_t)nfiles, &rs)) {
        for (long i = 0; i < nfiles; i++)
            abandon_job(&jobs[i]);
        free(jobs);
        fm_mesh_destroy(rs.set);
        return FM_EXIT_FAILURES;
    }
    double t1 = fm_clock_seconds();
    fm_connect_plan *plan = NULL;
    if (cli->connect) {
        progress_begin(cli->prog, "connect", 0, NULL, 0);
        plan = make_plan(cli, jobs, (size_t)nfiles, &rs);
        progress_end(cli->prog);
    }
    double t2 = fm_clock_seconds();
    run_jobs(cli, plan, 1, NULL, jobs, (size_t)nfiles);
    if (plan)
        settle_curves(cli, plan, jobs, (size_t)nfiles);
    double t3 = fm_clock_seconds();
    progress_begin(cli->prog, "merge and check", 0, NULL, 0);
    rs.plan = plan;
    if (plan) {
        size_t nn = fm_connect_plan_nnodes(plan);
        rs.node_vertex = malloc((nn + 1) * sizeof *rs.node_vertex);
        for (size_t k = 0; rs.node_vertex && k < nn; k++)
            rs.node_vertex[k] = -1;
    }
    for (long i = 0; i < nfiles; i++)
        merge_job(cli, &jobs[i], &rs);
    if (plan && cli->carve)
        carve_set(cli, &rs);
    measure_loss(cli, &rs);
    if (compact_set(&rs))
        fprintf(stderr, "faultmesh: out of memory: the outputs keep points of no triangle\n");
    progress_end(cli->prog);
    double t4 = fm_clock_seconds();
    rs.time[0] = t1 - t0;
    rs.time[1] = t2 - t1;
    rs.time[2] = t3 - t2;
    rs.time[3] = t4 - t3;
    /* report.html is an output, timed with the writes. It needs the
     * originals, which go with the jobs; with threads to spare it is drawn
     * beside the other writers (both only read the run). */
    html_job hj = {cli, &rs, FM_OK, {0}};
    pthread_t html_thread;
    int html_async = 0;
    int html = cli->html && (cli->formats & FMT_HTML);
    if (html && cli->jobs > 1)
        html_async = pthread_create(&html_thread, NULL, html_worker, &hj) == 0;
    if (html && !html_async) {
        progress_begin(cli->prog, "report.html", 0, NULL, 0);
        html_worker(&hj);
        progress_end(cli->prog);
    }
    sim_attrs sa;
    progress_begin(cli->prog, "write", 0, NULL, 0);
    /* noted only on this thread: report.html's does not look at it */
    write_set(cli, &rs, &sa);
    if (html_async)
        pthread_join(html_thread, NULL);
    if (html)
        note_report(&outputs, "report.html", hj.st == FM_OK ? NULL : &hj.err);
    for (long i = 0; i < nfiles; i++)
        release_job(&jobs[i]);
    free(jobs);
    rs.time[4] = fm_clock_seconds() - t4;
    /* report.json even when the meshes could not be written: it says what
     * each fault came to, and which files are missing */
    fm_error_clear(&err);
    fm_status rst = write_report(cli, &rs, sa.slip ? &sa : NULL, &err);
    sim_attrs_free(&sa);
    progress_end(cli->prog);
    note_report(&outputs, "report.json", rst == FM_OK ? NULL : &err);
    if (!cli->quiet)
        print_summary(cli, &rs, stdout);
    for (size_t i = 0; i < rs.nres; i++) {
        free(rs.res[i].file);
        free(rs.res[i].name);
        free(rs.res[i].error);
        free(rs.res[i].join_failed);
        free(rs.res[i].join_error);
        free(rs.res[i].dropped_curves);
        free(rs.res[i].through_curves);
        free(rs.res[i].used_curves);
        free(rs.res[i].curve_pieces);
        for (size_t k = 0; k < rs.res[i].ncad; k++)
            fm_cad_face_destroy(rs.res[i].cad[k]);
        free(rs.res[i].cad);
    }
    free(rs.cad);
    free(rs.res);
    free(rs.set_res);
    free(rs.set_orig);
    free(rs.sheet);
    fm_carve_result_destroy(rs.carve);
    fm_carve_result_destroy(rs.sheet_carve);
    fm_loss_destroy(rs.loss);
    free(rs.sheet_unit_fault);
    free(rs.sheet_unit_first);
    free(rs.names);
    free(rs.node_vertex);
    free(rs.plan_res);
    free(rs.crs);
    fm_connect_plan_destroy(plan);
    fm_mesh_destroy(rs.set);
    int unwritten = outputs.unwritten > 0;
    outputs_free(&outputs);
    return rs.failed || unwritten ? FM_EXIT_FAILURES : FM_EXIT_OK;
}

static int remesh_main(remesh_cli *cli_in, int argc, char **argv, const char **cinputs,
                       size_t ncinputs)
{
    remesh_cli cli = *cli_in;
    char **paths = calloc((size_t)argc + ncinputs, sizeof *paths);
    size_t npaths = 0;
    if (!paths)
        return FM_EXIT_FAILURES;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            remesh_usage(stdout);
            free(paths);
            return FM_EXIT_OK;
        }
        int c = mesh_option(argc, argv, &i, &cli);
        if (c < 0 || (c == 0 && a[0] == '-' && a[1])) {
            /* a bad value was said where it was read */
            if (c == 0)
                fprintf(stderr, "faultmesh: unknown option '%s' (see faultmesh remesh --help)\n",
                        a);
            free(paths);
            return FM_EXIT_USAGE;
        }
        if (c == 0)
            paths[npaths++] = argv[i];
    }
    /* inputs on the command line replace the settings file's */
    for (size_t k = 0; npaths == 0 && k < ncinputs; k++)
        paths[k] = (char *)cinputs[k];
    if (npaths == 0)
        npaths = ncinputs;
    extend_fit(&cli);
    if (settle_msh(&cli) || settle_elements(&cli)) {
        free(paths);
        return FM_EXIT_USAGE;
    }
    if (!cli.dir || npaths == 0) {
        fprintf(stderr, "faultmesh: remesh needs %s (see faultmesh remesh --help)\n",
                !cli.dir ? "-o DIR, the output folder" : "an input FILE or DIR");
        free(paths);
        return FM_EXIT_USAGE;
    }
    cli.sim.quiet = cli.quiet;
    if (sim_cli_load(&cli.sim, cli.crs_out ? cli.crs_out : cli.crs, paths, npaths) != 0) {
        sim_cli_free(&cli.sim);
        free(paths);
        return FM_EXIT_USAGE;
    }
    char **files = NULL;
    long nfiles = fm_input_list_for("remesh", cli.dir, paths, npaths, &files);
    free(paths);
    if (nfiles < 0) {
        sim_cli_free(&cli.sim);
        return FM_EXIT_USAGE;
    }
    cli.prog = progress_create(stderr, cli.quiet     ? PROGRESS_QUIET
                                       : cli.verbose ? PROGRESS_VERBOSE
                                                     : PROGRESS_NORMAL,
                               0);
    settle_cache(&cli);
    int rc = run(&cli, files, nfiles);
    release_cache(&cli);
    progress_destroy(cli.prog);
    fm_input_list_free(files, nfiles);
    sim_cli_free(&cli.sim);
    return rc;
}

/* --config FILE, wherever it stands on the command line, is read first:
 * the options given beside it override it. 0 (*cfg NULL when there is
 * none), or -1 after saying why. */
static int load_config(int argc, char **argv, remesh_cli *cli, config **cfg,
                       const char ***inputs, size_t *ninputs)
{
    *cfg = NULL;
    *inputs = NULL;
    *ninputs = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--config"))
            continue;
        if (*cfg || i + 1 >= argc) {
            fprintf(stderr, "faultmesh: --config takes one settings file\n");
            return -1;
        }
        if (!(*cfg = config_read(argv[i + 1])) || remesh_config(cli, *cfg, inputs, ninputs))
            return -1;
        i++;
    }
    return 0;
}

int fm_cmd_remesh(int argc, char **argv)
{
    remesh_cli cli;
    cli_defaults(&cli);
    config *cfg = NULL;
    const char **cinputs = NULL;
    size_t ncinputs = 0;
    if (load_config(argc, argv, &cli, &cfg, &cinputs, &ncinputs)) {
        free(cinputs);
        config_free(cfg);
        return FM_EXIT_USAGE;
    }
    int rc = remesh_main(&cli, argc, argv, cinputs, ncinputs);
    free(cinputs);
    config_free(cfg);
    return rc;
}

static int demo_main(remesh_cli *cli_in, int argc, char **argv)
{
    remesh_cli cli = *cli_in;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            printf("usage: faultmesh demo [options] -o DIR\n"
                   "Generates the synthetic fault system in DIR/input and remeshes it into DIR:\n"
                   "the same outputs and options as `faultmesh remesh`, which follow.\n\n");
            remesh_usage(stdout);
            return FM_EXIT_OK;
        }
        int c = mesh_option(argc, argv, &i, &cli);
        if (c <= 0) {
            /* a bad value was said where it was read */
            if (c == 0)
                fprintf(stderr, "faultmesh: demo: unexpected argument '%s' (see faultmesh demo "
                                "--help)\n",
                        a);
            return FM_EXIT_USAGE;
        }
    }
    extend_fit(&cli);
    if (settle_msh(&cli) || settle_elements(&cli))
        return FM_EXIT_USAGE;
    if (!cli.dir) {
        fprintf(stderr, "faultmesh: demo needs -o DIR, the output folder (see faultmesh demo "
                        "--help)\n");
        return FM_EXIT_USAGE;
    }
    cli.sim.quiet = cli.quiet;
    if (sim_cli_load(&cli.sim, cli.crs_out ? cli.crs_out : cli.crs, NULL, 0) != 0) {
        sim_cli_free(&cli.sim);
        return FM_EXIT_USAGE;
    }
    size_t n = strlen(cli.dir) + 16;
    char *in = malloc(n);
    if (!in) {
        sim_cli_free(&cli.sim);
        return FM_EXIT_FAILURES;
    }
    snprintf(in, n, "%s/input", cli.dir);
    fm_synth_options so;
    fm_synth_options_default(&so);
    fm_synth *s = NULL;
    fm_error err;
    fm_error_clear(&err);
    if (fm_synth_create(&so, &s, &err) != FM_OK || fm_synth_write(s, in, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        fm_synth_destroy(s);
        free(in);
        sim_cli_free(&cli.sim);
        return FM_EXIT_FAILURES;
    }
    fm_synth_destroy(s);
    char *args[1] = {in};
    char **files = NULL;
    long nfiles = fm_input_list(args, 1, &files);
    cli.prog = progress_create(stderr, cli.quiet     ? PROGRESS_QUIET
                                       : cli.verbose ? PROGRESS_VERBOSE
                                                     : PROGRESS_NORMAL,
                               0);
    settle_cache(&cli);
    int rc = nfiles < 0 ? FM_EXIT_FAILURES : run(&cli, files, nfiles);
    release_cache(&cli);
    progress_destroy(cli.prog);
    if (nfiles >= 0)
        fm_input_list_free(files, nfiles);
    free(in);
    sim_cli_free(&cli.sim);
    return rc;
}

int fm_cmd_demo(int argc, char **argv)
{
    remesh_cli cli;
    cli_defaults(&cli);
    /* The synthetic faults are 20 to 60 km long: 1 km triangles show
     * their shapes and mesh in a second. Local metres, no real CRS. */
    cli.crs = "local metres (synthetic)";
    /* No real CRS to convert from: EQSim in the mesh's metres unless
     * --crs and --eqsim-coords spherical say otherwise. */
    cli.sim.eqsim = FM_EQSIM_RECTANGULAR;
    config *cfg = NULL;
    const char **cinputs = NULL;
    size_t ncinputs = 0;
    int rc = FM_EXIT_USAGE;
    if (load_config(argc, argv, &cli, &cfg, &cinputs, &ncinputs) == 0) {
        if (ncinputs)
            fprintf(stderr, "faultmesh demo: %s: the demo makes its own inputs\n", cfg->path);
        else
            rc = demo_main(&cli, argc, argv);
    }
    free(cinputs);
    config_free(cfg);
    return rc;
}
