/* fm_fit_job (fm_commands.h): `faultmesh fit`'s work. A trimmed B-spline
 * model of every fault, with its JSON model, IGES and VTU files, and a fit
 * report. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "fm_commands.h"
#include "fm_json.h"
#include "fm_model.h"
#include "fm_model_write.h"
#include "fm_names.h"
#include "fm_opt.h"
#include "fm_sort.h"
#include "fm_tsurf.h"

struct fm_fit_job {
    fm_repair_options repair;
    fm_model_options model;
    fm_log_fn log;
    void *user;
};

/* What a run over the files comes to. */
typedef struct fit_tally {
    const char *dir;
    FILE *out;
    fm_namer *nm;
    fm_json *j;
    double *rms; /* per fault fitted: its worse RMS */
    size_t nrms, within;
} fit_tally;

fm_fit_job *fm_fit_job_create(void)
{
    fm_fit_job *job = calloc(1, sizeof *job);
    if (job) {
        fm_repair_options_default(&job->repair);
        fm_model_options_default(&job->model);
    }
    return job;
}

void fm_fit_job_destroy(fm_fit_job *job)
{
    free(job);
}

void fm_fit_job_set_log(fm_fit_job *job, fm_log_fn fn, void *user)
{
    job->log = fn;
    job->user = user;
}

static fm_fit_options *fit_of(void *t) { return &((fm_fit_job *)t)->model.fit; }

static int extend(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_double(a->name, a->val, &fit_of(t)->extend, err);
}

static int knot_spacing(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_double(a->name, a->val, &fit_of(t)->knot_spacing, err);
}

static int smoothing(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_double(a->name, a->val, &fit_of(t)->smoothing, err);
}

static int degree(void *t, fm_opt_arg *a, fm_error *err)
{
    if (!a->val)
        return fm_opt_missing(a->name, err);
    char *end = NULL;
    double d = strtod(a->val, &end);
    if (end == a->val || *end || d < 2 || d > 5 || d != floor(d)) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s needs 2, 3, 4 or 5, got '%s'", a->name,
                     a->val);
        return -1;
    }
    fit_of(t)->degree = (int)d;
    return 0;
}

static int target_rms(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_positive(a->name, a->val, &fit_of(t)->target_rms, err);
}

static int target_max(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_positive(a->name, a->val, &fit_of(t)->target_max, err);
}

static int trim_tol(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_double(a->name, a->val, &((fm_fit_job *)t)->model.trim.tolerance, err);
}

static int trim_max_dev(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_double(a->name, a->val, &((fm_fit_job *)t)->model.trim.max_deviation, err);
}

static int corner_angle(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_double(a->name, a->val, &((fm_fit_job *)t)->model.trim.corner_angle, err);
}

static const fm_opt_spec table[] = {
    {"--extend", NULL, 1, extend},
    {"--knot-spacing", NULL, 1, knot_spacing},
    {"--smoothing", NULL, 1, smoothing},
    {"--degree", NULL, 1, degree},
    {"--target-rms", NULL, 1, target_rms},
    {"--target-max", NULL, 1, target_max},
    {"--trim-tol", NULL, 1, trim_tol},
    {"--trim-max-dev", NULL, 1, trim_max_dev},
    {"--corner-angle", NULL, 1, corner_angle},
};

int fm_fit_job_take_option(fm_fit_job *job, int argc, const char *const *argv, int *i,
                           fm_error *err)
{
    int rc = fm_opt_take(table, sizeof table / sizeof *table, job, argc, argv, i, err);
    return rc ? rc : fm_repair_take_option(&job->repair, argc, argv, i, err);
}

static void say(const fm_fit_job *job, const char *fmt, const char *a)
{
    char msg[4 * FM_ERROR_MESSAGE_MAX]; /* a message and a path at most */
    snprintf(msg, sizeof msg, fmt, a);
    if (job->log)
        job->log(job->user, FM_LOG_ERROR, msg);
}

/* The three files of a fitted fault (fm_model_write_files), each one not
 * written said. */
static fm_status write_outputs(const fm_fit_job *job, const char *dir, const char *base,
                               const char *name, const fm_model *m, unsigned *missing,
                               fm_error *err)
{
    fm_error errs[FM_MODEL_NFILES];
    fm_status st = fm_model_write_files(dir, base, name, m, missing, errs);
    int first = 1;
    for (int k = 0; k < FM_MODEL_NFILES; k++)
        if (*missing & (1u << k)) {
            say(job, "not written: %s", errs[k].message);
            if (first && err)
                *err = errs[k];
            first = 0;
        }
    return st;
}

/* A fault's entry in the report when it failed. */
static void report_failed(fm_json *j, const char *base, const fm_error *err, unsigned missing)
{
    fm_json_kv_string(j, "status", "error");
    fm_json_kv_string(j, "error", err->message);
    if (!missing)
        return;
    fm_json_key(j, "outputs_missing");
    fm_json_begin_array(j);
    for (int k = 0; k < FM_MODEL_NFILES; k++)
        if (missing & (1u << k)) {
            char f[FM_STEM_MAX + 16];
            snprintf(f, sizeof f, "%s.%s", base, fm_model_file_ext[k]);
            fm_json_string(j, f);
        }
    fm_json_end_array(j);
}

/* A fitted fault: its line on out, its entry in the report. */
static void report_fitted(fit_tally *t, const char *base, const fm_model *model)
{
    fm_json *j = t->j;
    fm_fault_figures f;
    fm_model_fault_figures(model, &f);
    double worst = fmax(f.to_rms, f.from_rms);
    double *grown = realloc(t->rms, (t->nrms + 1) * sizeof *t->rms);
    if (grown) {
        t->rms = grown;
        t->rms[t->nrms++] = worst;
    }
    int ok = f.to_rms <= 10 && f.from_rms <= 10 && f.to_max <= 100 && f.from_max <= 100;
    t->within += ok;
    if (t->out)
        fprintf(t->out,
                "%-70s %zu sheet%s  rms %6.2f/%6.2f m  max %7.2f/%7.2f m  outline %6.1f m%s\n",
                base, fm_model_nsheets(model), fm_model_nsheets(model) == 1 ? " " : "s",
                f.to_rms, f.from_rms, f.to_max, f.from_max, f.outline_max,
                ok ? "" : "  (outside 10/100 m)");
    fm_json_kv_string(j, "status", "ok");
    fm_json_kv_string(j, "output", base);
    fm_json_kv_number(j, "to_surface_rms_m", f.to_rms);
    fm_json_kv_number(j, "to_surface_max_m", f.to_max);
    fm_json_kv_number(j, "from_trimmed_rms_m", f.from_rms);
    fm_json_kv_number(j, "from_trimmed_max_m", f.from_max);
    fm_json_kv_number(j, "outline_max_m", f.outline_max);
    fm_json_kv_bool(j, "within_10_100", ok);
    fm_json_key(j, "sheets");
    fm_json_begin_array(j);
    for (size_t i = 0; i < fm_model_nsheets(model); i++)
        fm_model_write_sheet_report(j, model, i, 1);
    fm_json_end_array(j);
}

/* One object of a file: repaired, fitted, written, reported; 1 if it
 * failed. */
static int fit_object(const fm_fit_job *job, fit_tally *t, const char *path, const fm_tsurf *obj)
{
    fm_error err;
    fm_error_clear(&err);
    const char *name = fm_tsurf_name(obj);
    /* one naming rule with remesh, over the whole run */
    const char *base = fm_namer_next(t->nm, name[0] ? name : path);
    if (!base) {
        say(job, "%s: out of memory", path);
        return 1;
    }
    fm_surface *surf = NULL;
    fm_model *model = NULL;
    fm_status st = fm_repair(fm_tsurf_mesh(obj), &job->repair, &surf, &err);
    /* as remesh: no sheet is nothing fitted, not a fit of nothing */
    if (st == FM_OK && fm_surface_nsheets(surf) == 0)
        st = fm_error_set(&err, FM_ERR_INVALID, path, 0,
                          "%s: nothing left after repair (every triangle degenerate, "
                          "duplicate or in a fragment dropped)",
                          name[0] ? name : base);
    if (st == FM_OK)
        st = fm_model_build(path, surf, &job->model, &model, &err);
    unsigned missing = 0;
    int said = 0;
    if (st == FM_OK) {
        st = write_outputs(job, t->dir, base, name[0] ? name : base, model, &missing, &err);
        said = st != FM_OK;
    }
    fm_json_begin_object(t->j);
    fm_json_kv_string(t->j, "file", path);
    fm_json_kv_string(t->j, "name", name);
    if (st != FM_OK) {
        if (!said)
            say(job, "%s", err.message);
        report_failed(t->j, base, &err, missing);
    } else {
        report_fitted(t, base, model);
    }
    fm_json_end_object(t->j);
    fm_model_destroy(model);
    fm_surface_destroy(surf);
    return st != FM_OK;
}

/* Fits one file; appends its faults to the report. Returns the number of
 * faults that failed (a file that cannot be read counts as one). */
static int fit_file(const fm_fit_job *job, fit_tally *t, const char *path)
{
    fm_tsurf **objs = NULL;
    size_t nobj = 0;
    fm_error err;
    fm_error_clear(&err);
    if (fm_tsurf_read_file(path, &objs, &nobj, &err) != FM_OK) {
        say(job, "%s", err.message);
        fm_json_begin_object(t->j);
        fm_json_kv_string(t->j, "file", path);
        fm_json_kv_string(t->j, "status", "error");
        fm_json_kv_string(t->j, "error", err.message);
        fm_json_end_object(t->j);
        return 1;
    }
    int failed = 0;
    for (size_t o = 0; o < nobj; o++)
        failed += fit_object(job, t, path, objs[o]);
    fm_tsurf_free_all(objs, nobj);
    return failed;
}

fm_status fm_fit_job_write(fm_fit_job *job, const char *dir, const char *const *files,
                           size_t nfiles, FILE *out, size_t *nfailed, fm_error *err)
{
    *nfailed = 0;
    if (fm_mkdir_p(dir, err) != FM_OK)
        return err ? err->code : FM_ERR_IO;
    size_t n = strlen(dir) + 32;
    char *report = malloc(n);
    if (!report)
        return fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    snprintf(report, n, "%s/fit_report.json", dir);
    fm_atomic_file *af = fm_atomic_open(report, err);
    free(report);
    if (!af)
        return err ? err->code : FM_ERR_IO;
    fm_json j;
    fm_json_init(&j, fm_atomic_stream(af));
    fm_json_begin_object(&j);
    fm_json_kv_string(&j, "faultmesh_version", FM_VERSION_STRING);
    fm_json_key(&j, "faults");
    fm_json_begin_array(&j);
    fit_tally t = {dir, out, fm_namer_create(), &j, NULL, 0, 0};
    long failed = 0;
    for (size_t i = 0; i < nfiles; i++)
        failed += t.nm ? fit_file(job, &t, files[i]) : 1;
    fm_namer_destroy(t.nm);
    fm_json_end_array(&j);
    double median = fm_median(t.rms, t.nrms);
    size_t nfaults = t.nrms + (size_t)failed;
    fm_json_key(&j, "summary");
    fm_json_begin_object(&j);
    fm_json_kv_int(&j, "faults", (int64_t)nfaults);
    fm_json_kv_int(&j, "failed", failed);
    fm_json_kv_int(&j, "within_10_100", (int64_t)t.within);
    fm_json_kv_number(&j, "median_rms_m", median);
    fm_json_end_object(&j);
    fm_json_end_object(&j);
    free(t.rms);
    fm_error cerr;
    if (fm_atomic_commit(af, &cerr) != FM_OK) {
        say(job, "%s", cerr.message);
        failed++;
    }
    if (out)
        fprintf(out,
                "faults %zu, failed %ld, within 10 m RMS / 100 m max both ways: %zu (%.1f%%), "
                "median RMS %.2f m\n",
                t.nrms + (size_t)failed, failed, t.within,
                t.nrms + (size_t)failed
                    ? 100.0 * (double)t.within / (double)(t.nrms + (size_t)failed)
                    : 0.0,
                median);
    *nfailed = (size_t)failed;
    return FM_OK;
}
