/* The run module through its public header only (fm_run.h): a whole run of
 * the synthetic fault system, its result and outputs, the same mesh on one
 * thread and on two, per-fault rules, the log and progress callbacks, and
 * cancelling from the progress callback. */
#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fm_atomic.h"
#include "fm_run_options.h"
#include "fm_synth.h"
#include "fm_test.h"
#include "fm_tsurf.h"

#define MAX_FILES 32

static char in_dir[512];
static char *files[MAX_FILES];
static size_t nfiles;

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The synthetic faults, written once; their .ts files in byte order. */
static int inputs(void)
{
    if (nfiles)
        return 0;
    snprintf(in_dir, sizeof in_dir, "%s/test_run/in", FM_TMP_DIR);
    fm_error err;
    fm_error_clear(&err);
    fm_synth_options so;
    fm_synth_options_default(&so);
    fm_synth *s = NULL;
    if (fm_mkdir_p(in_dir, &err) != FM_OK || fm_synth_create(&so, &s, &err) != FM_OK ||
        fm_synth_write(s, in_dir, &err) != FM_OK) {
        fprintf(stderr, "synthetic inputs: %s\n", err.message);
        fm_synth_destroy(s);
        return -1;
    }
    fm_synth_destroy(s);
    DIR *d = opendir(in_dir);
    if (!d)
        return -1;
    struct dirent *e;
    while ((e = readdir(d)) != NULL && nfiles < MAX_FILES) {
        size_t n = strlen(e->d_name);
        if (n < 4 || strcmp(e->d_name + n - 3, ".ts"))
            continue;
        size_t len = strlen(in_dir) + n + 2;
        files[nfiles] = malloc(len);
        snprintf(files[nfiles], len, "%s/%s", in_dir, e->d_name);
        nfiles++;
    }
    closedir(d);
    qsort(files, nfiles, sizeof *files, by_name);
    return nfiles ? 0 : -1;
}

typedef struct seen {
    size_t records[5];
    size_t begins, ends, steps;
    size_t cancel_at; /* STEP events before cancelling; 0: never */
} seen;

static void on_log(void *user, fm_log_level level, const char *message)
{
    seen *s = user;
    if (level >= FM_LOG_ERROR && level <= FM_LOG_DETAIL)
        s->records[level]++;
    CHECK(message && message[0]);
    CHECK(message[strlen(message) - 1] != '\n');
}

static int on_progress(void *user, const fm_progress *p)
{
    seen *s = user;
    s->begins += p->event == FM_PROGRESS_BEGIN;
    s->ends += p->event == FM_PROGRESS_END;
    s->steps += p->event == FM_PROGRESS_STEP;
    return s->cancel_at && s->steps >= s->cancel_at;
}

static void options(fm_run_options *o, int jobs)
{
    fm_run_options_default(o);
    o->jobs = jobs;
    o->no_cache = 1;
    o->html = 0;
    o->eqsim = FM_EQSIM_RECTANGULAR; /* local metres, no real CRS */
    o->crs = "local metres (synthetic)";
}

static fm_run *make_run(const fm_run_options *o, seen *s)
{
    fm_run *run = fm_run_create(o);
    CHECK(run != NULL);
    if (!run)
        return NULL;
    fm_run_set_log(run, FM_LOG_DETAIL, on_log, s);
    fm_run_set_progress(run, on_progress, s);
    fm_error err;
    fm_error_clear(&err);
    for (size_t i = 0; i < nfiles; i++)
        CHECK_EQ(fm_run_add_path(run, files[i], &err), FM_OK);
    return run;
}

static void test_whole_run(void)
{
    if (inputs())
        return;
    fm_run_options o;
    options(&o, 2);
    seen s = {0};
    fm_run *run = make_run(&o, &s);
    fm_run_result *res = NULL;
    fm_error err;
    fm_error_clear(&err);
    CHECK_EQ(fm_run_execute(run, &res, &err), FM_OK);
    CHECK(res != NULL);
    if (!res) {
        fm_run_destroy(run);
        return;
    }
    CHECK_EQ(fm_run_result_nfaults(res), nfiles);
    CHECK_EQ(fm_run_result_nfailed(res), 0);
    size_t ok = 0;
    for (size_t i = 0; i < fm_run_result_nfaults(res); i++) {
        const char *why = NULL;
        const char *st = fm_run_result_fault_status(res, i, &why);
        CHECK(st != NULL);
        CHECK(fm_run_result_fault_name(res, i) != NULL);
        ok += st && !strcmp(st, "ok");
    }
    CHECK(ok >= nfiles - 1);
    CHECK(fm_run_result_fault_status(res, nfiles, NULL) == NULL);
    const fm_mesh *m = fm_run_result_mesh(res);
    CHECK(m && fm_mesh_ntriangles(m) > 1000);
    /* the installed API's copy of it: the same arrays, and per triangle
     * the fault as the result counts them (the set's tag counts only the
     * faults written) */
    size_t nv = fm_run_result_nvertices(res), nt = fm_run_result_ntriangles(res);
    CHECK(m && nv == fm_mesh_nvertices(m) && nt == fm_mesh_ntriangles(m));
    double *xyz = malloc(3 * nv * sizeof *xyz);
    int32_t *tri = malloc(3 * nt * sizeof *tri), *fault = malloc(nt * sizeof *fault);
    CHECK(xyz && tri && fault);
    if (m && xyz && tri && fault) {
        CHECK_EQ(fm_run_result_copy_mesh(res, xyz, tri, fault, &err), FM_OK);
        CHECK(!memcmp(xyz, fm_mesh_vertices(m), 3 * nv * sizeof *xyz));
        CHECK(!memcmp(tri, fm_mesh_triangles(m), 3 * nt * sizeof *tri));
        size_t bad = 0;
        for (size_t t = 0; t < nt; t++) {
            const char *st = fault[t] >= 0 ? fm_run_result_fault_status(res, (size_t)fault[t], NULL)
                                           : NULL;
            bad += !st || strcmp(st, "ok") != 0;
        }
        CHECK_EQ(bad, 0);
        CHECK_EQ(fm_run_result_copy_mesh(res, NULL, NULL, NULL, &err), FM_OK);
    }
    free(xyz);
    free(tri);
    free(fault);
    CHECK_EQ(fm_run_result_copy_mesh(NULL, NULL, NULL, NULL, &err), FM_ERR_INVALID);
    /* a record per fault (DETAIL), and every stage ended */
    CHECK_EQ(s.records[FM_LOG_DETAIL], nfiles);
    CHECK(s.begins >= 4);
    CHECK_EQ(s.begins, s.ends);

    /* the mesh does not depend on the threads */
    fm_run_options o1;
    options(&o1, 1);
    seen s1 = {0};
    fm_run *run1 = make_run(&o1, &s1);
    fm_run_result *res1 = NULL;
    CHECK_EQ(fm_run_execute(run1, &res1, &err), FM_OK);
    const fm_mesh *m1 = fm_run_result_mesh(res1);
    CHECK(m1 && fm_mesh_nvertices(m1) == fm_mesh_nvertices(m) &&
          fm_mesh_ntriangles(m1) == fm_mesh_ntriangles(m));
    if (m1 && fm_mesh_nvertices(m1) == fm_mesh_nvertices(m) &&
        fm_mesh_ntriangles(m1) == fm_mesh_ntriangles(m)) {
        CHECK(!memcmp(fm_mesh_vertices(m1), fm_mesh_vertices(m),
                      3 * fm_mesh_nvertices(m) * sizeof(double)));
        CHECK(!memcmp(fm_mesh_triangles(m1), fm_mesh_triangles(m),
                      3 * fm_mesh_ntriangles(m) * sizeof(int32_t)));
    }
    fm_run_result_destroy(res1);
    fm_run_destroy(run1);

    /* the run may go before its result: the result's callbacks are its own */
    fm_run_destroy(run);
    char out[600];
    snprintf(out, sizeof out, "%s/test_run/out", FM_TMP_DIR);
    CHECK_EQ(fm_mkdir_p(out, &err), FM_OK);
    /* model.igs and rectangles are made by the run: only what it made */
    fm_run_result *none = NULL;
    CHECK_EQ(fm_run_result_write(none, out, FM_OUT_VTU, &err), FM_ERR_INVALID);
    CHECK_EQ(fm_run_result_write(res, out, FM_OUT_VTU | FM_OUT_MSH | FM_OUT_NAMES, &err), FM_OK);
    CHECK_EQ(fm_run_result_unwritten(res), 0);
    const char *made[] = {"mesh.vtu", "mesh.msh", "names.csv", "report.json"};
    const char *not_made[] = {"mesh.stl", "model.igs", "report.html"};
    for (size_t k = 0; k < 4; k++) {
        char p[700];
        struct stat sb;
        snprintf(p, sizeof p, "%s/%s", out, made[k]);
        CHECK(stat(p, &sb) == 0 && sb.st_size > 0);
    }
    for (size_t k = 0; k < 3; k++) {
        char p[700];
        struct stat sb;
        snprintf(p, sizeof p, "%s/%s", out, not_made[k]);
        CHECK(stat(p, &sb) != 0);
    }
    /* once per result */
    CHECK_EQ(fm_run_result_write(res, out, FM_OUT_VTU, &err), FM_ERR_INVALID);
    char *summary = fm_run_result_summary(res);
    CHECK(summary && strstr(summary, "summary (") && strstr(summary, out));
    free(summary);
    fm_run_result_destroy(res);
    fm_run_result_destroy(NULL);
    fm_run_destroy(NULL);
}

/* In-memory inputs (fm_run_add_mesh) go through the run as their files
 * do: the same meshes, bit for bit, and the same fault names. */
static void test_mesh_inputs(void)
{
    if (inputs())
        return;
    fm_error err;
    fm_error_clear(&err);
    fm_run_options o;
    options(&o, 2);
    seen s = {0}, sm = {0};
    fm_run *by_path = make_run(&o, &s);
    fm_run *by_mesh = fm_run_create(&o);
    CHECK(by_mesh != NULL);
    if (!by_mesh) {
        fm_run_destroy(by_path);
        return;
    }
    fm_run_set_log(by_mesh, FM_LOG_DETAIL, on_log, &sm);
    for (size_t i = 0; i < nfiles; i++) {
        fm_tsurf **objs = NULL;
        size_t nobj = 0;
        CHECK_EQ(fm_tsurf_read_file(files[i], &objs, &nobj, &err), FM_OK);
        for (size_t k = 0; k < nobj; k++) {
            const fm_mesh *m = fm_tsurf_mesh(objs[k]);
            CHECK_EQ(fm_run_add_mesh(by_mesh, fm_tsurf_name(objs[k]), fm_mesh_vertices(m),
                                     fm_mesh_nvertices(m), fm_mesh_triangles(m),
                                     fm_mesh_ntriangles(m), &err),
                     FM_OK);
        }
        fm_tsurf_free_all(objs, nobj);
    }
    /* refused with a reason: the caller hears of it now */
    double xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    int32_t tri[3] = {0, 1, 2}, bad_tri[3] = {0, 1, 3}, twice[3] = {0, 1, 1};
    CHECK_EQ(fm_run_add_mesh(by_mesh, "x", xyz, 3, bad_tri, 1, &err), FM_ERR_INVALID);
    CHECK(strstr(err.message, "out of range") != NULL);
    CHECK_EQ(fm_run_add_mesh(by_mesh, "x", xyz, 3, twice, 1, &err), FM_ERR_INVALID);
    CHECK_EQ(fm_run_add_mesh(by_mesh, "", xyz, 3, tri, 1, &err), FM_ERR_INVALID);
    CHECK_EQ(fm_run_add_mesh(by_mesh, "x", xyz, 2, tri, 1, &err), FM_ERR_INVALID);
    xyz[4] = nan("");
    CHECK_EQ(fm_run_add_mesh(by_mesh, "x", xyz, 3, tri, 1, &err), FM_ERR_INVALID);

    fm_run_result *rp = NULL, *rm = NULL;
    CHECK_EQ(fm_run_execute(by_path, &rp, &err), FM_OK);
    CHECK_EQ(fm_run_execute(by_mesh, &rm, &err), FM_OK);
    if (rp && rm) {
        CHECK_EQ(fm_run_result_nfaults(rm), fm_run_result_nfaults(rp));
        for (size_t i = 0; i < fm_run_result_nfaults(rp) && i < fm_run_result_nfaults(rm); i++) {
            CHECK(!strcmp(fm_run_result_fault_name(rm, i), fm_run_result_fault_name(rp, i)));
            CHECK(!strcmp(fm_run_result_fault_status(rm, i, NULL),
                          fm_run_result_fault_status(rp, i, NULL)));
        }
        const fm_mesh *a = fm_run_result_mesh(rp), *b = fm_run_result_mesh(rm);
        int same = a && b && fm_mesh_nvertices(a) == fm_mesh_nvertices(b) &&
                   fm_mesh_ntriangles(a) == fm_mesh_ntriangles(b);
        CHECK(same);
        if (same) {
            CHECK(!memcmp(fm_mesh_vertices(a), fm_mesh_vertices(b),
                          3 * fm_mesh_nvertices(a) * sizeof(double)));
            CHECK(!memcmp(fm_mesh_triangles(a), fm_mesh_triangles(b),
                          3 * fm_mesh_ntriangles(a) * sizeof(int32_t)));
        }
        CHECK_EQ(sm.records[FM_LOG_DETAIL], nfiles);
    }
    fm_run_result_destroy(rp);
    fm_run_result_destroy(rm);
    fm_run_destroy(by_path);
    fm_run_destroy(by_mesh);
}

static void test_rules(void)
{
    const char *const a[] = {"SYNT-*"}, *const b[] = {"*XOVR*", "nothing"};
    fm_fault_rule rules[2];
    memset(rules, 0, sizeof rules);
    rules[0].match = a;
    rules[0].nmatch = 1;
    rules[0].set.has_size = 1;
    rules[0].set.size = 800;
    rules[0].set.line = 3;
    rules[1].match = b;
    rules[1].nmatch = 2;
    rules[1].set.has_size = 1;
    rules[1].set.size = 1500;
    rules[1].set.has_exclude = 1;
    rules[1].set.exclude = 1;
    rules[1].set.line = 9;
    fm_fault_settings fs;
    fm_fault_settings_lookup(rules, 2, "SYNT-MAIN-XOVR-x", &fs);
    CHECK(fs.has_size && fs.size == 1500 && fs.has_exclude && fs.exclude && fs.line == 9);
    fm_fault_settings_lookup(rules, 2, "SYNT-MAIN-SS-x", &fs);
    CHECK(fs.has_size && fs.size == 800 && !fs.has_exclude && fs.line == 3);
    fm_fault_settings_lookup(rules, 2, "other", &fs);
    CHECK(!fs.has_size && fs.line == 0);

    if (inputs())
        return;
    fm_run_options o;
    options(&o, 2);
    o.fault_rules = rules + 1;
    o.nfault_rules = 1;
    seen s = {0};
    fm_run *run = make_run(&o, &s);
    fm_run_result *res = NULL;
    fm_error err;
    fm_error_clear(&err);
    CHECK_EQ(fm_run_execute(run, &res, &err), FM_OK);
    size_t excluded = 0;
    for (size_t i = 0; res && i < fm_run_result_nfaults(res); i++) {
        const char *why = NULL;
        const char *st = fm_run_result_fault_status(res, i, &why);
        if (st && !strcmp(st, "excluded")) {
            excluded++;
            CHECK(strstr(fm_run_result_fault_name(res, i), "XOVR") != NULL);
            CHECK_STR(why, "excluded by the per-fault settings");
        }
    }
    CHECK_EQ(excluded, 1);
    fm_run_result_destroy(res);
    fm_run_destroy(run);
}

static void test_cancel(void)
{
    if (inputs())
        return;
    fm_run_options o;
    options(&o, 2);
    seen s = {0};
    s.cancel_at = 1;
    fm_run *run = make_run(&o, &s);
    fm_run_result *res = (fm_run_result *)run; /* overwritten with NULL */
    fm_error err;
    fm_error_clear(&err);
    CHECK_EQ(fm_run_execute(run, &res, &err), FM_ERR_CANCELLED);
    CHECK(res == NULL);
    CHECK_EQ(err.code, FM_ERR_CANCELLED);
    /* the run can go again, and then runs to the end */
    s.cancel_at = 0;
    CHECK_EQ(fm_run_execute(run, &res, &err), FM_OK);
    CHECK(res && fm_run_result_nfaults(res) == nfiles);
    fm_run_result_destroy(res);
    /* interrupted before it began */
    fm_run_interrupt(run);
    fm_run_destroy(run);
}

static void test_bad_options(void)
{
    if (inputs())
        return;
    fm_run_options o;
    options(&o, 1);
    o.slip_path = "/nonexistent/slip.csv";
    fm_run *run = fm_run_create(&o);
    fm_error err;
    fm_error_clear(&err);
    CHECK(fm_run_prepare(run, NULL, 0, &err) != FM_OK);
    CHECK(strstr(err.message, "/nonexistent/slip.csv") != NULL);
    fm_run_result *res = NULL;
    CHECK(fm_run_execute(run, &res, &err) != FM_OK);
    CHECK(res == NULL);
    fm_run_destroy(run);

    /* the whole run over the limit: refused before meshing */
    options(&o, 1);
    o.max_triangles = 2000;
    seen s = {0};
    run = make_run(&o, &s);
    fm_error_clear(&err);
    CHECK_EQ(fm_run_execute(run, &res, &err), FM_ERR_INVALID);
    CHECK(res == NULL && strstr(err.message, "--max-triangles 2000") != NULL);
    fm_run_destroy(run);
}

/* The setters by key: bounds, types, strings kept by the run and its
 * results, the same run as the options struct gives. */
static void test_setters(void)
{
    fm_run *run = fm_run_create(NULL);
    fm_error err;
    fm_error_clear(&err);
    const fm_run_options *o = fm_run_get_options(run);
    CHECK_EQ(fm_run_set_double(run, FM_OPT_SIZE, 2000, &err), FM_OK);
    CHECK(o->mesh.size == 2000);
    CHECK_EQ(fm_run_set_double(run, FM_OPT_SIZE, -1, &err), FM_ERR_INVALID);
    CHECK(strstr(err.message, "size") != NULL);
    CHECK_EQ(fm_run_set_int(run, FM_OPT_SIZE, 5, &err), FM_ERR_INVALID);
    CHECK_EQ(fm_run_set_int(run, (fm_run_option)9999, 5, &err), FM_ERR_INVALID);
    CHECK_EQ(fm_run_set_int(run, FM_OPT_THREADS, 0, &err), FM_ERR_INVALID);
    CHECK_EQ(fm_run_set_int(run, FM_OPT_THREADS, 2, &err), FM_OK);
    CHECK_EQ(o->jobs, 2);
    CHECK_EQ(fm_run_set_int(run, FM_OPT_TOP, FM_TOP_KEEP, &err), FM_OK);
    CHECK_EQ(o->mesh.top, FM_TOP_KEEP);
    CHECK_EQ(fm_run_set_int(run, FM_OPT_FORMATS, 0, &err), FM_ERR_INVALID);
    CHECK_EQ(fm_run_set_int(run, FM_OPT_CACHE, 0, &err), FM_OK);
    CHECK_EQ(o->no_cache, 1);
    double lo, hi;
    CHECK_EQ(fm_run_option_bounds(FM_OPT_THREADS, &lo, &hi), FM_OK);
    CHECK(lo == 1 && hi == 1024);
    CHECK_EQ(fm_run_option_bounds(FM_OPT_CRS, &lo, &hi), FM_ERR_INVALID);
    char crs[64];
    snprintf(crs, sizeof crs, "%s", "local metres (synthetic)");
    CHECK_EQ(fm_run_set_string(run, FM_OPT_CRS, crs, &err), FM_OK);
    memset(crs, 'x', sizeof crs - 1); /* copied: the caller's buffer is free again */
    CHECK_STR(o->crs, "local metres (synthetic)");
    CHECK_EQ(fm_run_set_double(run, FM_OPT_SIZE, 1000, &err), FM_OK);
    CHECK_EQ(fm_run_set_int(run, FM_OPT_TOP, FM_TOP_CUT, &err), FM_OK);
    CHECK_EQ(fm_run_set_int(run, FM_OPT_REPORT_HTML, 0, &err), FM_OK);
    CHECK_EQ(fm_run_set_int(run, FM_OPT_EQSIM_COORDS, FM_EQSIM_RECTANGULAR, &err), FM_OK);
    for (int k = 0; k < FM_RUN_MAX_KINEMATICS; k++)
        CHECK_EQ(fm_run_set_string(run, FM_OPT_KINEMATICS, "k.geojson", &err), FM_OK);
    CHECK_EQ(fm_run_set_string(run, FM_OPT_KINEMATICS, "k.geojson", &err), FM_ERR_INVALID);
    CHECK_EQ(fm_run_set_string(run, FM_OPT_KINEMATICS, NULL, &err), FM_OK);
    CHECK_EQ(o->nkin, 0);
    if (inputs()) {
        fm_run_destroy(run);
        return;
    }
    for (size_t i = 0; i < nfiles; i++)
        fm_run_add_path(run, files[i], &err);
    fm_run_result *res = NULL;
    CHECK_EQ(fm_run_execute(run, &res, &err), FM_OK);
    /* a string set after the run went leaves the result's alone */
    CHECK_EQ(fm_run_set_string(run, FM_OPT_CRS, "EPSG:32611", &err), FM_OK);
    CHECK_STR(o->crs, "EPSG:32611");

    /* the same as the options struct */
    fm_run_options ref;
    options(&ref, 2);
    seen s = {0};
    fm_run *run2 = make_run(&ref, &s);
    fm_run_result *res2 = NULL;
    CHECK_EQ(fm_run_execute(run2, &res2, &err), FM_OK);
    const fm_mesh *a = fm_run_result_mesh(res), *b = fm_run_result_mesh(res2);
    CHECK(a && b && fm_mesh_ntriangles(a) == fm_mesh_ntriangles(b) &&
          fm_mesh_nvertices(a) == fm_mesh_nvertices(b));
    fm_run_destroy(run);
    char out[600];
    snprintf(out, sizeof out, "%s/test_run/out_set", FM_TMP_DIR);
    CHECK_EQ(fm_mkdir_p(out, &err), FM_OK);
    CHECK_EQ(fm_run_result_write(res, out, FM_OUT_VTU, &err), FM_OK);
    char path[700];
    snprintf(path, sizeof path, "%s/report.json", out);
    char *json = fm_test_read_file(path, NULL);
    CHECK(json && strstr(json, "\"crs\": \"local metres (synthetic)\""));
    free(json);
    fm_run_result_destroy(res);
    fm_run_result_destroy(res2);
    fm_run_destroy(run2);
}

/* A folder as input: its .ts files in byte order, as the CLI lists them. */
static void test_folder(void)
{
    if (inputs())
        return;
    fm_error err;
    fm_error_clear(&err);
    char **list = NULL;
    const char *dir = in_dir;
    seen s = {0};
    long n = fm_run_list_inputs(&dir, 1, on_log, &s, &list, &err);
    CHECK_EQ(n, (long)nfiles);
    for (long i = 0; i < n && (size_t)i < nfiles; i++)
        CHECK_STR(list[i], files[i]);
    fm_run_list_free(list, n);
    const char *missing = "/nonexistent/folder";
    CHECK_EQ(fm_run_list_inputs(&missing, 1, NULL, NULL, &list, &err), -1);
    CHECK(strstr(err.message, missing) != NULL);

    fm_run_options o;
    options(&o, 2);
    fm_run *run = fm_run_create(&o);
    /* a file that is not there: a fault that fails */
    CHECK_EQ(fm_run_add_path(run, missing, &err), FM_OK);
    char copy[512];
    snprintf(copy, sizeof copy, "%s", in_dir);
    CHECK_EQ(fm_run_add_path(run, copy, &err), FM_OK);
    memset(copy, 0, sizeof copy); /* copied */
    fm_run_result *res = NULL;
    CHECK_EQ(fm_run_execute(run, &res, &err), FM_OK);
    CHECK_EQ(fm_run_result_nfaults(res), nfiles + 1);
    CHECK_EQ(fm_run_result_nfailed(res), 1);
    CHECK_STR(fm_run_result_fault_status(res, 0, NULL), "error");
    fm_run_result_destroy(res);
    fm_run_destroy(run);
}

FM_TEST_MAIN(FM_CASE(test_whole_run), FM_CASE(test_mesh_inputs), FM_CASE(test_folder),
             FM_CASE(test_rules), FM_CASE(test_cancel), FM_CASE(test_bad_options),
             FM_CASE(test_setters))
