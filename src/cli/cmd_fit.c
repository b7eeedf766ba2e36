/* `faultmesh fit`: a trimmed B-spline model of every fault, with its JSON
 * model, IGES and VTU files and a fit report (the library's fm_fit_job,
 * fm_commands.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

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

/* The options into job and *dir, the inputs into paths: FM_EXIT_OK, -1
 * after --help, or FM_EXIT_USAGE after saying why. */
static int parse(fm_fit_job *job, int argc, char **argv, const char **dir, char **paths,
                 size_t *npaths)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        fm_error err;
        fm_error_clear(&err);
        int taken;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            fit_usage(stdout);
            return -1;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (i + 1 >= argc)
                return fm_cli_missing(a), FM_EXIT_USAGE;
            *dir = argv[++i];
        } else if ((taken = fm_fit_job_take_option(job, argc, FM_CLI_ARGV(argv), &i, &err))) {
            if (fm_cli_taken(taken, &err) < 0)
                return FM_EXIT_USAGE;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "faultmesh: unknown option '%s' (see faultmesh fit --help)\n", a);
            return FM_EXIT_USAGE;
        } else {
            paths[(*npaths)++] = argv[i];
        }
    }
    if (!*dir || *npaths == 0) {
        fprintf(stderr, "faultmesh: fit needs %s (see faultmesh fit --help)\n",
                !*dir ? "-o DIR, the output folder" : "an input FILE or DIR");
        return FM_EXIT_USAGE;
    }
    return FM_EXIT_OK;
}

int fm_cmd_fit(int argc, char **argv)
{
    fm_fit_job *job = fm_fit_job_create();
    char **paths = calloc((size_t)argc, sizeof *paths);
    size_t npaths = 0;
    const char *dir = NULL;
    int rc = job && paths ? parse(job, argc, argv, &dir, paths, &npaths) : FM_EXIT_FAILURES;
    char **files = NULL;
    long nfiles = rc ? -1 : fm_input_list_for("fit", dir, paths, npaths, &files);
    free(paths);
    if (rc || nfiles < 0) {
        fm_fit_job_destroy(job);
        return rc < 0 ? FM_EXIT_OK : rc ? rc : FM_EXIT_USAGE;
    }
    fm_fit_job_set_log(job, fm_cli_say, NULL);
    fm_error err;
    fm_error_clear(&err);
    size_t failed = 0;
    rc = fm_fit_job_write(job, dir, FM_CLI_ARGV(files), (size_t)nfiles, stdout, &failed, &err)
             ? fm_cli_fail(&err, FM_EXIT_FAILURES)
         : failed ? FM_EXIT_FAILURES
                  : FM_EXIT_OK;
    fm_run_list_free(files, nfiles);
    fm_fit_job_destroy(job);
    return rc;
}
