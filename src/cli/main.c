/* faultmesh: triangulated fault surfaces in, simulator-ready meshes out. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

static const struct {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} commands[] = {
    {"info", fm_cmd_info, "read, repair and describe TSurf files"},
    {"fit", fm_cmd_fit, "fit trimmed B-spline models (JSON, IGES, VTU)"},
    {"remesh", fm_cmd_remesh,
     "mesh faults at a chosen size, connected (VTU, MSH, STL, OBJ, Exodus II, TSurf, IGES,\n"
     "           RSQSim, EQSim, names.csv, report.json, report.html)"},
    {"demo", fm_cmd_demo, "remesh the synthetic fault system (the embedded default)"},
    {"synth", fm_cmd_synth, "generate the synthetic fault system (TSurf)"},
};

static void usage(FILE *fp)
{
    fprintf(fp, "usage: faultmesh COMMAND [options] ...\n\ncommands:\n");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        fprintf(fp, "  %-8s %s\n", commands[i].name, commands[i].summary);
    fprintf(fp, "\n`faultmesh COMMAND --help` describes a command's options;\n"
                "`faultmesh --version` prints the version.\n"
                "Exit status: 0 success, 1 some inputs or outputs failed, 2 bad usage.\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return FM_EXIT_USAGE;
    }
    fm_cli_catch_signals();
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        usage(stdout);
        return FM_EXIT_OK;
    }
    if (!strcmp(cmd, "--version")) {
        printf("faultmesh %s\n", FM_VERSION_STRING);
        return FM_EXIT_OK;
    }
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (!strcmp(cmd, commands[i].name)) {
            int n;
            char **args;
            int bad = fm_cli_normalize_args(argc - 1, argv + 1, &n, &args);
            if (bad)
                return bad < 0 ? FM_EXIT_FAILURES : FM_EXIT_USAGE;
            int rc = commands[i].run(n, args);
            fm_cli_free_args(n, args);
            fm_report_cleanup(); /* the font caches of report.html's pictures */
            return rc;
        }
    fprintf(stderr, "faultmesh: unknown command '%s'\n", cmd);
    usage(stderr);
    return FM_EXIT_USAGE;
}
