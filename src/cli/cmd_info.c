/* `faultmesh info`: read, repair and describe TSurf files (the library's
 * fm_info, fm_commands.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static void info_usage(FILE *fp)
{
    fprintf(fp,
            "usage: faultmesh info [options] FILE|DIR...\n"
            "Reads GoCAD TSurf files (folders are searched for *.ts), repairs them\n"
            "and prints per file and per sheet: parts, vertices, triangles, area,\n"
            "components, boundary loops and holes, non-manifold edges, welded\n"
            "duplicates, z range, edge lengths and minimum angles.\n\n"
            "options:\n"
            "  --json                     machine-readable output on stdout\n"
            "  -h, --help                 this text\n");
    fputs(fm_cli_repair_help, fp);
}

/* The options into info, the inputs into paths: FM_EXIT_OK, -1 after
 * --help, or FM_EXIT_USAGE after saying why. */
static int parse(fm_info *info, int argc, char **argv, char **paths, size_t *npaths)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        fm_error err;
        fm_error_clear(&err);
        int taken;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            info_usage(stdout);
            return -1;
        } else if ((taken = fm_info_take_option(info, argc, FM_CLI_ARGV(argv), &i, &err)) != 0) {
            if (fm_cli_taken(taken, &err) < 0)
                return FM_EXIT_USAGE;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "faultmesh: unknown option '%s' (see faultmesh info --help)\n", a);
            return FM_EXIT_USAGE;
        } else {
            paths[(*npaths)++] = argv[i];
        }
    }
    if (*npaths == 0) {
        info_usage(stderr);
        return FM_EXIT_USAGE;
    }
    return FM_EXIT_OK;
}

int fm_cmd_info(int argc, char **argv)
{
    fm_info *info = fm_info_create();
    char **paths = calloc((size_t)argc, sizeof *paths);
    size_t npaths = 0;
    int rc = info && paths ? parse(info, argc, argv, paths, &npaths) : FM_EXIT_FAILURES;
    char **files = NULL;
    long nfiles = rc ? -1 : fm_input_list(paths, npaths, &files);
    free(paths);
    if (rc == 0 && nfiles == 0)
        fprintf(stderr, "faultmesh info: no .ts files found\n");
    if (rc || nfiles <= 0) {
        fm_run_list_free(files, nfiles > 0 ? nfiles : 0);
        fm_info_destroy(info);
        return rc < 0 ? FM_EXIT_OK : rc ? rc : FM_EXIT_USAGE;
    }
    fm_info_set_log(info, fm_cli_say, NULL);
    size_t failed = fm_info_write(info, FM_CLI_ARGV(files), (size_t)nfiles, stdout);
    if (failed)
        fprintf(stderr, "faultmesh info: %zu of %ld file%s failed\n", failed, nfiles,
                nfiles == 1 ? "" : "s");
    fm_run_list_free(files, nfiles);
    fm_info_destroy(info);
    return failed ? FM_EXIT_FAILURES : FM_EXIT_OK;
}
