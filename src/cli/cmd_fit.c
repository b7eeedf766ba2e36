/* `faultmesh fit`: a trimmed B-spline model of every fault, with its JSON
 * model, IGES and VTU files and a fit report. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "fm_atomic.h"
#include "fm_json.h"
#include "fm_model.h"
#include "fm_model_write.h"
#include "fm_names.h"
#include "fm_sort.h"
#include "fm_tsurf.h"

static void fit_usage(FILE *fp)
{
    fprintf(fp,
            "usage: faultmesh fit [options] -o DIR FILE|DIR...\n"
            "Fits every sheet of every fault with a smooth B-spline surface trimmed by\n"
            "its fitted outline and holes, and writes per fault DIR/NAME.model.json,\n"
            "DIR/NAME.igs (IGES 5.3) and DIR/NAME.vtu, and DIR/fit_report.json.\n\n"
            "options:\n"
            "  -o, --output DIR     output folder (created if missing)\n"
            "  --extend D           valid surface beyond the outline, metres (default 2000)\n"
            "  --knot-spacing M     surface knot spacing, metres (default: automatic)\n"
            "  --smoothing L        thin-plate weight, m^4 (default: automatic)\n"
            "  --degree N           surface degree 2..5 (default 3)\n"
            "  --target-rms M       refine the knots of a sheet fitted worse than this RMS (m)\n"
            "  --target-max M       ... or this largest vertex distance (m)\n"
            "  --trim-tol M         outline tolerance (averaged deviation), metres (default 50)\n"
            "  --trim-max-dev M     refine the outline where one point is farther (default 50)\n"
            "  --corner-angle DEG   outline corners turn at least this much (default 30)\n"
            "  -h, --help           this text\n");
    fputs(fm_cli_repair_help, fp);
}

typedef struct {
    const char *dir;
    fm_repair_options repair;
    fm_model_options model;
} fit_cli;

/* The three files of a fitted fault (fm_model_write_files), each one not
 * written said on stderr. */
static fm_status write_outputs(const fit_cli *cli, const char *base, const char *name,
                               const fm_model *m, unsigned *missing, fm_error *err)
{
    fm_error errs[FM_MODEL_NFILES];
    fm_status st = fm_model_write_files(cli->dir, base, name, m, missing, errs);
    int first = 1;
    for (int k = 0; k < FM_MODEL_NFILES; k++)
        if (*missing & (1u << k)) {
            fprintf(stderr, "faultmesh: not written: %s\n", errs[k].message);
            if (first && err)
                *err = errs[k];
            first = 0;
        }
    return st;
}

/* Fits one file; appends its faults to the report. Returns the number of
 * faults that failed (a file that cannot be read counts as one). */
static int fit_file(const fit_cli *cli, fm_namer *nm, const char *path, fm_json *j,
                    double **rms, size_t *nrms, size_t *within)
{
    fm_tsurf **objs = NULL;
    size_t nobj = 0;
    fm_error err;
    fm_error_clear(&err);
    if (fm_tsurf_read_file(path, &objs, &nobj, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        fm_json_begin_object(j);
        fm_json_kv_string(j, "file", path);
        fm_json_kv_string(j, "status", "error");
        fm_json_kv_string(j, "error", err.message);
        fm_json_end_object(j);
        return 1;
    }
    int failed = 0;
    for (size_t o = 0; o < nobj; o++) {
        const char *name = fm_tsurf_name(objs[o]);
        /* one naming rule with remesh, over the whole run */
        const char *base = fm_namer_next(nm, name[0] ? name : path);
        if (!base) {
            fprintf(stderr, "faultmesh: %s: out of memory\n", path);
            failed++;
            continue;
        }
        fm_surface *surf = NULL;
        fm_model *model = NULL;
        fm_status st = fm_repair(fm_tsurf_mesh(objs[o]), &cli->repair, &surf, &err);
        /* as remesh: no sheet is nothing fitted, not a fit of nothing */
        if (st == FM_OK && fm_surface_nsheets(surf) == 0)
            st = fm_error_set(&err, FM_ERR_INVALID, path, 0,
                              "%s: nothing left after repair (every triangle degenerate, "
                              "duplicate or in a fragment dropped)",
                              name[0] ? name : base);
        if (st == FM_OK)
            st = fm_model_build(path, surf, &cli->model, &model, &err);
        unsigned missing = 0;
        int said = 0;
        if (st == FM_OK) {
            st = write_outputs(cli, base, name[0] ? name : base, model, &missing, &err);
            said = st != FM_OK;
        }
        fm_json_begin_object(j);
        fm_json_kv_string(j, "file", path);
        fm_json_kv_string(j, "name", name);
        if (st != FM_OK) {
            failed++;
            if (!said)
                fprintf(stderr, "faultmesh: %s\n", err.message);
            fm_json_kv_string(j, "status", "error");
            fm_json_kv_string(j, "error", err.message);
            if (missing) {
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
        } else {
            fm_fault_figures f;
            fm_model_fault_figures(model, &f);
            double worst = fmax(f.to_rms, f.from_rms);
            double *grown = realloc(*rms, (*nrms + 1) * sizeof **rms);
            if (grown) {
                *rms = grown;
                (*rms)[(*nrms)++] = worst;
            }
            int ok = f.to_rms <= 10 && f.from_rms <= 10 && f.to_max <= 100 && f.from_max <= 100;
            *within += ok;
            printf("%-70s %zu sheet%s  rms %6.2f/%6.2f m  max %7.2f/%7.2f m  outline %6.1f m%s\n",
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
        fm_json_end_object(j);
        fm_model_destroy(model);
        fm_surface_destroy(surf);
    }
    fm_tsurf_free_all(objs, nobj);
    return failed;
}

int fm_cmd_fit(int argc, char **argv)
{
    fit_cli cli = {0};
    fm_repair_options_default(&cli.repair);
    fm_model_options_default(&cli.model);
    char **paths = calloc((size_t)argc, sizeof *paths);
    size_t npaths = 0;
    if (!paths)
        return FM_EXIT_FAILURES;
    int rc = 0;
    for (int i = 1; i < argc && !rc; i++) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        int consumed;
        double d;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            fit_usage(stdout);
            free(paths);
            return FM_EXIT_OK;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            cli.dir = val;
            rc = val ? 0 : (fm_cli_missing(a), FM_EXIT_USAGE);
            i++;
        } else if (!strcmp(a, "--extend")) {
            rc = fm_parse_double(a, val, &cli.model.fit.extend) ? FM_EXIT_USAGE : 0;
            i++;
        } else if (!strcmp(a, "--knot-spacing")) {
            rc = fm_parse_double(a, val, &cli.model.fit.knot_spacing) ? FM_EXIT_USAGE : 0;
            i++;
        } else if (!strcmp(a, "--smoothing")) {
            rc = fm_parse_double(a, val, &cli.model.fit.smoothing) ? FM_EXIT_USAGE : 0;
            i++;
        } else if (!strcmp(a, "--degree")) {
            rc = !val ? (fm_cli_missing(a), FM_EXIT_USAGE) : 0;
            char *end = NULL;
            d = val ? strtod(val, &end) : 0;
            if (!rc && (end == val || *end || d < 2 || d > 5 || d != floor(d))) {
                fprintf(stderr, "faultmesh: --degree needs 2, 3, 4 or 5, got '%s'\n", val);
                rc = FM_EXIT_USAGE;
            }
            cli.model.fit.degree = (int)d;
            i++;
        } else if (!strcmp(a, "--target-rms")) {
            rc = fm_parse_positive(a, val, &cli.model.fit.target_rms) ? FM_EXIT_USAGE : 0;
            i++;
        } else if (!strcmp(a, "--target-max")) {
            rc = fm_parse_positive(a, val, &cli.model.fit.target_max) ? FM_EXIT_USAGE : 0;
            i++;
        } else if (!strcmp(a, "--trim-tol")) {
            rc = fm_parse_double(a, val, &cli.model.trim.tolerance) ? FM_EXIT_USAGE : 0;
            i++;
        } else if (!strcmp(a, "--trim-max-dev")) {
            rc = fm_parse_double(a, val, &cli.model.trim.max_deviation) ? FM_EXIT_USAGE : 0;
            i++;
        } else if (!strcmp(a, "--corner-angle")) {
            rc = fm_parse_double(a, val, &cli.model.trim.corner_angle) ? FM_EXIT_USAGE : 0;
            i++;
        } else if ((consumed = fm_cli_repair_option(argc, argv, &i, &cli.repair)) != 0) {
            rc = consumed < 0 ? FM_EXIT_USAGE : 0;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "faultmesh: unknown option '%s' (see faultmesh fit --help)\n", a);
            rc = FM_EXIT_USAGE;
        } else {
            paths[npaths++] = argv[i];
        }
    }
    if (!rc && (!cli.dir || npaths == 0)) {
        fprintf(stderr, "faultmesh: fit needs %s (see faultmesh fit --help)\n",
                !cli.dir ? "-o DIR, the output folder" : "an input FILE or DIR");
        rc = FM_EXIT_USAGE;
    }
    char **files = NULL;
    long nfiles = rc ? -1 : fm_input_list_for("fit", cli.dir, paths, npaths, &files);
    free(paths);
    if (rc || nfiles < 0)
        return FM_EXIT_USAGE;
    fm_error err;
    fm_error_clear(&err);
    if (fm_mkdir_p(cli.dir, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        fm_input_list_free(files, nfiles);
        return FM_EXIT_FAILURES;
    }

    size_t n = strlen(cli.dir) + 32;
    char *report = malloc(n);
    fm_atomic_file *af = report ? (snprintf(report, n, "%s/fit_report.json", cli.dir),
                                   fm_atomic_open(report, &err))
                                : NULL;
    free(report);
    if (!af) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        fm_input_list_free(files, nfiles);
        return FM_EXIT_FAILURES;
    }
    fm_json j;
    fm_json_init(&j, fm_atomic_stream(af));
    fm_json_begin_object(&j);
    fm_json_kv_string(&j, "faultmesh_version", FM_VERSION_STRING);
    fm_json_key(&j, "faults");
    fm_json_begin_array(&j);
    double *rms = NULL;
    size_t nrms = 0, within = 0;
    long failed = 0;
    fm_namer *nm = fm_namer_create();
    for (long i = 0; i < nfiles; i++)
        failed += nm ? fit_file(&cli, nm, files[i], &j, &rms, &nrms, &within) : 1;
    fm_namer_destroy(nm);
    fm_json_end_array(&j);
    double median = fm_median(rms, nrms);
    fm_json_key(&j, "summary");
    fm_json_begin_object(&j);
    fm_json_kv_int(&j, "faults", (int64_t)(nrms + (size_t)failed));
    fm_json_kv_int(&j, "failed", failed);
    fm_json_kv_int(&j, "within_10_100", (int64_t)within);
    fm_json_kv_number(&j, "median_rms_m", median);
    fm_json_end_object(&j);
    fm_json_end_object(&j);
    free(rms);
    if (fm_atomic_commit(af, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        failed++;
    }
    printf("faults %zu, failed %ld, within 10 m RMS / 100 m max both ways: %zu (%.1f%%), "
           "median RMS %.2f m\n",
           nrms + (size_t)failed, failed, within,
           nrms + (size_t)failed ? 100.0 * (double)within / (double)(nrms + (size_t)failed) : 0.0,
           median);
    fm_input_list_free(files, nfiles);
    return failed ? FM_EXIT_FAILURES : FM_EXIT_OK;
}
