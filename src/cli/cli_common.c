/* What the commands share: how they say the library's messages, their
 * inputs and the repair options' help. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

void fm_cli_say(void *user, fm_log_level level, const char *message)
{
    (void)user;
    if (level == FM_LOG_DETAIL)
        printf("%s\n", message);
    else
        fprintf(stderr, "faultmesh: %s\n", message);
}

int fm_cli_fail(const fm_error *err, int code)
{
    /* what is wrong in a settings file reads FILE:LINE: why, as a compiler says it */
    fprintf(stderr, "%s%s\n", err->line > 0 ? "" : "faultmesh: ", err->message);
    return code;
}

int fm_cli_missing(const char *opt)
{
    fprintf(stderr, "faultmesh: %s needs a value\n", opt);
    return -1;
}

int fm_cli_taken(int rc, const fm_error *err)
{
    if (rc < 0)
        fm_cli_fail(err, -1);
    return rc;
}

long fm_input_list(char *const *args, size_t nargs, char ***out)
{
    fm_error err;
    fm_error_clear(&err);
    long n = fm_run_list_inputs(FM_CLI_ARGV(args), nargs, fm_cli_say, NULL, out, &err);
    if (n < 0)
        fm_cli_fail(&err, -1);
    return n;
}

long fm_input_list_for(const char *cmd, const char *outdir, char *const *args, size_t nargs,
                       char ***out)
{
    long n = fm_input_list(args, nargs, out);
    if (n < 0)
        return -1;
    fm_error err;
    fm_error_clear(&err);
    if (n == 0)
        fprintf(stderr, "faultmesh %s: no .ts files found\n", cmd);
    else if (fm_run_check_output_dir(outdir, FM_CLI_ARGV(args), nargs, FM_CLI_ARGV(*out),
                                     (size_t)n, &err) == FM_OK)
        return n;
    else
        fm_cli_fail(&err, -1);
    fm_run_list_free(*out, n);
    *out = NULL;
    return -1;
}

const char *const fm_cli_repair_help =
    "  --weld-tol M               also weld vertices closer than M metres (default 0)\n"
    "  --min-fragment-triangles N fragments with fewer triangles ... (default 10)\n"
    "  --min-fragment-fraction F  ... and less than F of the largest area are dropped\n"
    "                             (default 0.001)\n"
    "  --keep-fragments           drop no fragments\n"
    "  --no-split                 keep non-manifold edges (no sheets split)\n";
