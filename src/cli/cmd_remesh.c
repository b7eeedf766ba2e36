/* `faultmesh remesh`: every fault of the inputs read, repaired, fitted and
 * meshed at size H, checked, and written as one fault set (VTU, MSH, STL,
 * OBJ, Exodus II, one TSurf per fault) with report.json. `faultmesh demo` runs it on
 * the synthetic fault system. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "fm_atomic.h"
#include "fm_synth.h"
#include "progress.h"
#include "remesh_cli.h"

/* The run's records, as the command has always printed them: the line of
 * each fault (-v) on stdout, everything else on stderr. */
static void say(void *user, fm_log_level level, const char *message)
{
    (void)user;
    if (level == FM_LOG_DETAIL)
        printf("%s\n", message);
    else
        fprintf(stderr, "faultmesh: %s\n", message);
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

/* A run of the options, said as the command says it. NULL after saying
 * why: memory ran out, or (*usage set) the files its options name cannot
 * be read. */
static fm_run *run_create(remesh_cli *cli, char *const *near, size_t nnear, int *usage)
{
    *usage = 0;
    fm_run *run = settings_rules(cli) ? NULL : fm_run_create(&cli->o);
    if (!run) {
        fprintf(stderr, "faultmesh: out of memory\n");
        return NULL;
    }
    fm_run_set_log(run, cli->quiet ? FM_LOG_WARN : cli->verbose ? FM_LOG_DETAIL : FM_LOG_INFO,
                   say, NULL);
    fm_error err;
    fm_error_clear(&err);
    if (fm_run_prepare(run, (const char *const *)near, nnear, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        fm_run_destroy(run);
        *usage = 1;
        return NULL;
    }
    return run;
}

static int run_files(const remesh_cli *cli, fm_run *run, char **files, long nfiles)
{
    fm_error err;
    fm_error_clear(&err);
    if (fm_mkdir_p(cli->dir, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        return FM_EXIT_FAILURES;
    }
    for (long i = 0; i < nfiles; i++)
        if (fm_run_add_path(run, files[i], &err) != FM_OK) {
            fprintf(stderr, "faultmesh: %s\n", err.message);
            return FM_EXIT_FAILURES;
        }
    progress *bar = progress_create(stderr, cli->quiet     ? PROGRESS_QUIET
                                            : cli->verbose ? PROGRESS_VERBOSE
                                                           : PROGRESS_NORMAL,
                                    0);
    fm_run_set_progress(run, shown, bar);
    fm_run_result *res = NULL;
    int rc = FM_EXIT_FAILURES;
    if (fm_run_execute(run, &res, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
    } else {
        /* every file tried; each one not written is said as it fails */
        fm_run_result_write(res, cli->dir, cli->o.formats, &err);
        if (!cli->quiet) {
            char *summary = fm_run_result_summary(res);
            if (summary)
                fputs(summary, stdout);
            free(summary);
        }
        rc = fm_run_result_nfailed(res) || fm_run_result_unwritten(res) ? FM_EXIT_FAILURES
                                                                        : FM_EXIT_OK;
    }
    fm_run_result_destroy(res);
    progress_destroy(bar);
    return rc;
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
    int usage;
    fm_run *run = run_create(&cli, paths, npaths, &usage);
    if (!run) {
        settings_rules_free(&cli);
        free(paths);
        return usage ? FM_EXIT_USAGE : FM_EXIT_FAILURES;
    }
    char **files = NULL;
    long nfiles = fm_input_list_for("remesh", cli.dir, paths, npaths, &files);
    free(paths);
    int rc = FM_EXIT_USAGE;
    if (nfiles >= 0) {
        rc = run_files(&cli, run, files, nfiles);
        fm_input_list_free(files, nfiles);
    }
    fm_run_destroy(run);
    settings_rules_free(&cli);
    return rc;
}

/* --config FILE, wherever it stands on the command line, is read first:
 * the options given beside it override it. 0 (*cfg NULL when there is
 * none), or -1 after saying why. */
static int load_config(int argc, char **argv, remesh_cli *cli, fm_settings **cfg,
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
        fm_error err;
        if (!(*cfg = fm_settings_read(argv[i + 1], &err))) {
            /* what is wrong in the file reads FILE:LINE: why, as a compiler says it */
            fprintf(stderr, "%s%s\n", err.line > 0 ? "" : "faultmesh: ", err.message);
            return -1;
        }
        if (remesh_config(cli, *cfg, inputs, ninputs))
            return -1;
        i++;
    }
    return 0;
}

int fm_cmd_remesh(int argc, char **argv)
{
    remesh_cli cli;
    cli_defaults(&cli);
    fm_settings *cfg = NULL;
    const char **cinputs = NULL;
    size_t ncinputs = 0;
    if (load_config(argc, argv, &cli, &cfg, &cinputs, &ncinputs)) {
        free(cinputs);
        fm_settings_free(cfg);
        return FM_EXIT_USAGE;
    }
    int rc = remesh_main(&cli, argc, argv, cinputs, ncinputs);
    free(cinputs);
    fm_settings_free(cfg);
    return rc;
}

/* The synthetic fault system written into in, then remeshed. */
static int demo_run(const remesh_cli *cli, fm_run *run, char *in)
{
    fm_synth_options so;
    fm_synth_options_default(&so);
    fm_synth *s = NULL;
    fm_error err;
    fm_error_clear(&err);
    if (fm_synth_create(&so, &s, &err) != FM_OK || fm_synth_write(s, in, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        fm_synth_destroy(s);
        return FM_EXIT_FAILURES;
    }
    fm_synth_destroy(s);
    char *args[1] = {in};
    char **files = NULL;
    long nfiles = fm_input_list(args, 1, &files);
    if (nfiles < 0)
        return FM_EXIT_FAILURES;
    int rc = run_files(cli, run, files, nfiles);
    fm_input_list_free(files, nfiles);
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
    if (settle_msh(&cli) || settle_elements(&cli))
        return FM_EXIT_USAGE;
    if (!cli.dir) {
        fprintf(stderr, "faultmesh: demo needs -o DIR, the output folder (see faultmesh demo "
                        "--help)\n");
        return FM_EXIT_USAGE;
    }
    int usage;
    fm_run *run = run_create(&cli, NULL, 0, &usage);
    if (!run) {
        settings_rules_free(&cli);
        return usage ? FM_EXIT_USAGE : FM_EXIT_FAILURES;
    }
    size_t n = strlen(cli.dir) + 16;
    char *in = malloc(n);
    int rc = FM_EXIT_FAILURES;
    if (in) {
        snprintf(in, n, "%s/input", cli.dir);
        rc = demo_run(&cli, run, in);
    }
    free(in);
    fm_run_destroy(run);
    settings_rules_free(&cli);
    return rc;
}

int fm_cmd_demo(int argc, char **argv)
{
    remesh_cli cli;
    cli_defaults(&cli);
    /* The synthetic faults are 20 to 60 km long: 1 km triangles show
     * their shapes and mesh in a second. Local metres, no real CRS. */
    cli.o.crs = "local metres (synthetic)";
    /* No real CRS to convert from: EQSim in the mesh's metres unless
     * --crs and --eqsim-coords spherical say otherwise. */
    cli.o.eqsim = FM_EQSIM_RECTANGULAR;
    fm_settings *cfg = NULL;
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
    fm_settings_free(cfg);
    return rc;
}
