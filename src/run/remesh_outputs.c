/* `faultmesh remesh`: every output file accounted for. Each file the run
 * was to write is noted as written or not (with the reason) in the order
 * written, so that the log, report.json and the summary can say which are
 * missing, and which faults they leave incomplete. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run_internal.h"

/* The name of path inside the output folder (the path itself if not). */
static const char *in_dir(const output_log *log, const char *path)
{
    size_t n = strlen(log->dir);
    if (!strncmp(path, log->dir, n) && path[n] == '/')
        return path + n + 1;
    return path;
}

void outputs_note(output_log *log, const char *path, size_t fault, output_kind kind,
                  const fm_error *err)
{
    if (err) {
        run_log(log->ctl, FM_LOG_ERROR, "not written: %s", err->message);
        log->unwritten++;
    } else {
        log->written++;
    }
    if (log->n == log->cap) {
        size_t cap = log->cap ? 2 * log->cap : 64;
        output_rec *r = realloc(log->rec, cap * sizeof *r);
        if (!r) {
            log->lost++;
            return;
        }
        log->rec = r;
        log->cap = cap;
    }
    output_rec *r = &log->rec[log->n];
    r->file = strdup(in_dir(log, path));
    r->error = err ? strdup(err->message) : NULL;
    r->fault = fault;
    r->kind = kind;
    if (!r->file || (err && !r->error)) {
        free(r->file);
        free(r->error);
        log->lost++;
        return;
    }
    log->n++;
}

void outputs_done(void *ctx, const char *path, size_t fault, const fm_error *err)
{
    outputs_note(ctx, path, fault, fault == SIZE_MAX ? OUTPUT_SET : OUTPUT_FAULT, err);
}

void outputs_free(output_log *log)
{
    for (size_t i = 0; i < log->n; i++) {
        free(log->rec[i].file);
        free(log->rec[i].error);
    }
    free(log->rec);
    log->rec = NULL;
    log->n = log->cap = 0;
}

/* Whether record r is a file fault f (its index in the set) should be in. */
static int holds(const output_rec *r, size_t f)
{
    return r->kind == OUTPUT_SET || (r->kind == OUTPUT_FAULT && r->fault == f);
}

int outputs_complete(const output_log *log, size_t f)
{
    if (!log)
        return 1;
    if (log->lost)
        return 0; /* not known: not claimed */
    for (size_t i = 0; i < log->n; i++)
        if (log->rec[i].error && holds(&log->rec[i], f))
            return 0;
    return 1;
}

void outputs_json_missing(fm_json *j, const output_log *log, size_t f)
{
    fm_json_key(j, "outputs_missing");
    fm_json_begin_array(j);
    for (size_t i = 0; log && i < log->n; i++)
        if (log->rec[i].error && holds(&log->rec[i], f))
            fm_json_string(j, log->rec[i].file);
    fm_json_end_array(j);
}

void outputs_json(fm_json *j, const output_log *log)
{
    fm_json_key(j, "outputs");
    fm_json_begin_object(j);
    fm_json_kv_int(j, "written", (int64_t)log->written);
    fm_json_kv_int(j, "not_written", (int64_t)log->unwritten);
    /* records memory ran out for: counted above, not listed */
    if (log->lost)
        fm_json_kv_int(j, "not_listed", (int64_t)log->lost);
    fm_json_key(j, "files");
    fm_json_begin_array(j);
    for (size_t i = 0; i < log->n; i++) {
        const output_rec *r = &log->rec[i];
        fm_json_begin_object(j);
        fm_json_kv_string(j, "file", r->file);
        fm_json_kv_bool(j, "written", !r->error);
        if (r->error)
            fm_json_kv_string(j, "error", r->error);
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    fm_json_end_object(j);
}

void outputs_print(const output_log *log, FILE *fp)
{
    fprintf(fp, "  %-14s %zu written, %zu not written\n", "outputs", log->written,
            log->unwritten);
    for (size_t i = 0; i < log->n; i++)
        if (log->rec[i].error)
            fprintf(fp, "  %-14s %s\n", "not written", log->rec[i].error);
}
