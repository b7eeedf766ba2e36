/* `faultmesh remesh`: every fault of the inputs read, repaired, fitted and
 * meshed at size H, checked, and written as one fault set (VTU, MSH, STL,
 * OBJ, Exodus II, one TSurf per fault) with report.json. `faultmesh demo` runs it on
 * the synthetic fault system. The run and its options are the library's
 * (fm_run.h); the command's own are the output folder, --config and how
 * much it says. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "progress.h"

typedef struct remesh_cli {
    fm_run *run;     /* everything the run is told */
    const char *dir; /* -o DIR */
    int quiet;
    int verbose;     /* a line per fault */
} remesh_cli;

/* The command's own options, on the command line and in the settings
 * file (fm_run_read_settings hands them over): fm_option_fn's contract. */
static int own_option(void *user, int argc, const char *const *argv, int *i, fm_error *err)
{
    remesh_cli *cli = user;
    const char *a = argv[*i], *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    int output = !strcmp(a, "-o") || !strcmp(a, "--output");
    if (output || !strcmp(a, "--config")) {
        if (!val) {
            err->code = FM_ERR_INVALID;
            snprintf(err->message, sizeof err->message, "%s needs a value", a);
            return -1;
        }
        if (output)
            cli->dir = val;
        /* --config: read before the other options (load_config) */
        (*i)++;
    } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
        cli->quiet = 1;
        cli->verbose = 0;
    } else if (!strcmp(a, "--verbose") || !strcmp(a, "-v")) {
        cli->verbose = 1;
        cli->quiet = 0;
    } else {
        return 0;
    }
    return 1;
}

/* argv[*i]: the command's option or the run's; 1 taken, 0 neither, -1
 * after saying why. */
static int option(remesh_cli *cli, int argc, char **argv, int *i)
{
    fm_error err;
    fm_error_clear(&err);
    int rc = own_option(cli, argc, FM_CLI_ARGV(argv), i, &err);
    if (rc == 0)
        rc = fm_run_take_option(cli->run, argc, FM_CLI_ARGV(argv), i, &err);
    return fm_cli_taken(rc, &err);
}

/* The run's progress on the bar (progress.c). */
static int shown(void *user, const fm_progress *p)
{
    progress *bar = user;
    switch (p->event) {
    case FM_PROGRESS_BEGIN:
        progress_begin(bar, p->stage, p->count, p->unit, p->weight);
        break;
    case FM_PROGRESS_STEP:
        progress_step(bar, p->weight);
        break;
    case FM_PROGRESS_SET:
        progress_set(bar, p->done, p->count, p->unit);
        break;
    case FM_PROGRESS_END:
        progress_end(bar);
        break;
    }
    return 0;
}

/* The options settled and the files they name read, said as the command
 * says it: FM_EXIT_OK, or FM_EXIT_USAGE after saying why. */
static int settle(remesh_cli *cli, char *const *near, size_t nnear)
{
    fm_error err;
    fm_error_clear(&err);
    fm_run_set_log(cli->run,
                   cli->quiet ? FM_LOG_WARN : cli->verbose ? FM_LOG_DETAIL : FM_LOG_INFO,
                   fm_cli_say, NULL);
    if (fm_run_prepare(cli->run, FM_CLI_ARGV(near), nnear, &err) != FM_OK)
        return fm_cli_fail(&err, FM_EXIT_USAGE);
    return FM_EXIT_OK;
}

static int run_files(const remesh_cli *cli, char **files, long nfiles)
{
    fm_error err;
    fm_error_clear(&err);
    if (fm_make_dirs(cli->dir, &err) != FM_OK)
        return fm_cli_fail(&err, FM_EXIT_FAILURES);
    for (long i = 0; i < nfiles; i++)
        if (fm_run_add_path(cli->run, files[i], &err) != FM_OK)
            return fm_cli_fail(&err, FM_EXIT_FAILURES);
    progress *bar = progress_create(stderr, cli->quiet     ? PROGRESS_QUIET
                                            : cli->verbose ? PROGRESS_VERBOSE
                                                           : PROGRESS_NORMAL,
                                    0);
    fm_run_set_progress(cli->run, shown, bar);
    fm_run_result *res = NULL;
    int rc = FM_EXIT_FAILURES;
    int64_t formats = FM_OUT_ALL;
    fm_run_get_int(cli->run, FM_OPT_FORMATS, &formats);
    if (fm_run_execute(cli->run, &res, &err) != FM_OK) {
        fm_cli_fail(&err, 0);
    } else {
        /* every file tried; each one not written is said as it fails */
        fm_run_result_write(res, cli->dir, (unsigned)formats, &err);
        if (!cli->quiet) {
            char *summary = fm_run_result_summary(res);
            if (summary)
                fputs(summary, stdout);
            fm_free(summary);
        }
        rc = fm_run_result_nfailed(res) || fm_run_result_unwritten(res) ? FM_EXIT_FAILURES
                                                                        : FM_EXIT_OK;
    }
    fm_run_result_destroy(res);
    progress_destroy(bar);
    return rc;
}

/* The options settled, or FM_EXIT_USAGE after saying why. */
static int checked(remesh_cli *cli)
{
    fm_error err;
    fm_error_clear(&err);
    return fm_run_check_options(cli->run, &err) ? fm_cli_fail(&err, FM_EXIT_USAGE) : FM_EXIT_OK;
}

static int remesh_main(remesh_cli *cli, int argc, char **argv)
{
    size_t ncinputs = fm_run_settings_ninputs(cli->run);
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
        int c = option(cli, argc, argv, &i);
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
        paths[k] = (char *)fm_run_settings_input(cli->run, k);
    if (npaths == 0)
        npaths = ncinputs;
    int rc = checked(cli);
    if (rc == FM_EXIT_OK && (!cli->dir || npaths == 0)) {
        fprintf(stderr, "faultmesh: remesh needs %s (see faultmesh remesh --help)\n",
                !cli->dir ? "-o DIR, the output folder" : "an input FILE or DIR");
        rc = FM_EXIT_USAGE;
    }
    if (rc == FM_EXIT_OK)
        rc = settle(cli, paths, npaths);
    char **files = NULL;
    long nfiles = rc ? -1 : fm_input_list_for("remesh", cli->dir, paths, npaths, &files);
    free(paths);
    if (rc || nfiles < 0)
        return rc ? rc : FM_EXIT_USAGE;
    rc = run_files(cli, files, nfiles);
    fm_run_list_free(files, nfiles);
    return rc;
}

/* --config FILE, wherever it stands on the command line, is read first:
 * the options given beside it override it. 0, or -1 after saying why. */
static int load_config(int argc, char **argv, remesh_cli *cli)
{
    int read = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--config"))
            continue;
        if (read || i + 1 >= argc) {
            fprintf(stderr, "faultmesh: --config takes one settings file\n");
            return -1;
        }
        fm_error err;
        fm_error_clear(&err);
        if (fm_run_read_settings(cli->run, argv[i + 1], own_option, cli, &err) != FM_OK)
            return fm_cli_fail(&err, -1);
        read = 1;
        i++;
    }
    return 0;
}

/* A run of the defaults (NULL after saying why). */
static fm_run *run_create(void)
{
    fm_run *run = fm_run_create(NULL);
    if (!run)
        fprintf(stderr, "faultmesh: out of memory\n");
    return run;
}

int fm_cmd_remesh(int argc, char **argv)
{
    remesh_cli cli = {run_create(), NULL, 0, 0};
    if (!cli.run)
        return FM_EXIT_FAILURES;
    int rc = load_config(argc, argv, &cli) ? FM_EXIT_USAGE : remesh_main(&cli, argc, argv);
    fm_run_destroy(cli.run);
    return rc;
}

/* The synthetic fault system written into in, then remeshed. */
static int demo_run(const remesh_cli *cli, char *in)
{
    fm_synth *s = NULL;
    fm_error err;
    fm_error_clear(&err);
    if (fm_synth_generate(NULL, &s, &err) != FM_OK || fm_synth_write(s, in, &err) != FM_OK) {
        fm_synth_destroy(s);
        return fm_cli_fail(&err, FM_EXIT_FAILURES);
    }
    fm_synth_destroy(s);
    char *args[1] = {in};
    char **files = NULL;
    long nfiles = fm_input_list(args, 1, &files);
    if (nfiles < 0)
        return FM_EXIT_FAILURES;
    int rc = run_files(cli, files, nfiles);
    fm_run_list_free(files, nfiles);
    return rc;
}

static int demo_main(remesh_cli *cli, int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            printf("usage: faultmesh demo [options] -o DIR\n"
                   "Generates the synthetic fault system in DIR/input and remeshes it into DIR:\n"
                   "the same outputs and options as `faultmesh remesh`, which follow.\n\n");
            remesh_usage(stdout);
            return FM_EXIT_OK;
        }
        int c = option(cli, argc, argv, &i);
        if (c <= 0) {
            /* a bad value was said where it was read */
            if (c == 0)
                fprintf(stderr, "faultmesh: demo: unexpected argument '%s' (see faultmesh demo "
                                "--help)\n",
                        a);
            return FM_EXIT_USAGE;
        }
    }
    if (checked(cli))
        return FM_EXIT_USAGE;
    if (!cli->dir) {
        fprintf(stderr, "faultmesh: demo needs -o DIR, the output folder (see faultmesh demo "
                        "--help)\n");
        return FM_EXIT_USAGE;
    }
    int rc = settle(cli, NULL, 0);
    if (rc)
        return rc;
    size_t n = strlen(cli->dir) + 16;
    char *in = malloc(n);
    rc = FM_EXIT_FAILURES;
    if (in) {
        snprintf(in, n, "%s/input", cli->dir);
        rc = demo_run(cli, in);
    }
    free(in);
    return rc;
}

int fm_cmd_demo(int argc, char **argv)
{
    remesh_cli cli = {run_create(), NULL, 0, 0};
    if (!cli.run)
        return FM_EXIT_FAILURES;
    /* The synthetic faults are 20 to 60 km long: 1 km triangles show
     * their shapes and mesh in a second. Local metres, no real CRS. No
     * real CRS to convert from either: EQSim in the mesh's metres unless
     * --crs and --eqsim-coords spherical say otherwise. */
    fm_run_set_string(cli.run, FM_OPT_CRS, "local metres (synthetic)", NULL);
    fm_run_set_int(cli.run, FM_OPT_EQSIM_COORDS, FM_RUN_EQSIM_RECTANGULAR, NULL);
    int rc = FM_EXIT_USAGE;
    if (load_config(argc, argv, &cli) == 0) {
        if (fm_run_settings_ninputs(cli.run))
            fprintf(stderr, "faultmesh demo: %s: the demo makes its own inputs\n",
                    fm_run_settings_path(cli.run));
        else
            rc = demo_main(&cli, argc, argv);
    }
    fm_run_destroy(cli.run);
    return rc;
}
