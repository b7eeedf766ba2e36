/* GNU option conventions for every command (getopt_long's, for options
 * whose parsers take one argument at a time): the arguments are rewritten
 * into the plain form the commands read, before they read them.
 *
 *   --name=value   ->  --name value      (a value-taking option; a flag
 *                                         given a value is an error)
 *   -jVALUE        ->  -j VALUE          (-o and -j, the short options
 *                                         that take a value)
 *   -qv            ->  -q -v             (bundled short flags)
 *   --             ends the options: every later argument is an input,
 *                  one beginning with '-' passed on as ./-name (the same
 *                  file) so that no command takes it for an option. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

/* Options that take no value; every other option of the form --name
 * takes one (the commands check which they know). */
static const char *const flags[] = {
    "--elastic-check", "--help", "--json", "--keep-crossings", "--keep-fragments",
    "--no-connect", "--no-report-html", "--no-split", "--quiet", "--verbose", "--version",
};

static int is_flag(const char *name, size_t n)
{
    for (size_t i = 0; i < sizeof flags / sizeof *flags; i++)
        if (strlen(flags[i]) == n && !strncmp(flags[i], name, n))
            return 1;
    return 0;
}

/* Short options: flags, and those taking a value. */
static int short_flag(char c) { return c == 'h' || c == 'q' || c == 'v'; }
static int short_value(char c) { return c == 'o' || c == 'j'; }

int fm_cli_normalize_args(int argc, char **argv, int *out_argc, char ***out_argv)
{
    /* room for the longest rewriting: a bundle gives one argument per
     * letter, the others at most two per argument */
    size_t cap = 1;
    for (int i = 0; i < argc; i++) {
        size_t len = strlen(argv[i]);
        cap += len > 2 ? len : 2;
    }
    char **v = calloc(cap, sizeof *v);
    if (!v)
        return -1;
    int n = 0, options = 1;
    for (int i = 0; i < argc; i++) {
        char *a = argv[i];
        if (i == 0 || !options || a[0] != '-' || !a[1]) {
            if (!options && i > 0 && a[0] == '-') {
                size_t len = strlen(a);
                char *p = malloc(len + 3);
                if (!p)
                    goto nomem;
                memcpy(p, "./", 2);
                memcpy(p + 2, a, len + 1);
                v[n++] = p;
            } else if (!(v[n++] = strdup(a))) {
                goto nomem;
            }
            continue;
        }
        if (!strcmp(a, "--")) {
            options = 0;
            continue;
        }
        if (a[1] == '-') {
            const char *eq = strchr(a, '=');
            if (!eq) {
                if (!(v[n++] = strdup(a)))
                    goto nomem;
                continue;
            }
            size_t k = (size_t)(eq - a);
            if (is_flag(a, k)) {
                fprintf(stderr, "faultmesh: option '%.*s' takes no value\n", (int)k, a);
                for (int j = 0; j < n; j++)
                    free(v[j]);
                free(v);
                return 1;
            }
            if (!(v[n] = strndup(a, k)))
                goto nomem;
            n++;
            if (!(v[n++] = strdup(eq + 1)))
                goto nomem;
            continue;
        }
        /* short: -jVALUE, -oDIR, or a bundle of flags (an unknown letter
         * is passed on as it is, for the command to name) */
        if (short_value(a[1]) && a[2]) {
            char opt[3] = {'-', a[1], 0};
            if (!(v[n++] = strdup(opt)) || !(v[n++] = strdup(a + 2)))
                goto nomem;
            continue;
        }
        int bundle = a[2] != 0;
        for (const char *c = a + 1; *c && bundle; c++)
            bundle = short_flag(*c);
        if (!bundle) {
            if (!(v[n++] = strdup(a)))
                goto nomem;
            continue;
        }
        for (const char *c = a + 1; *c; c++) {
            char opt[3] = {'-', *c, 0};
            if (!(v[n++] = strdup(opt)))
                goto nomem;
        }
    }
    v[n] = NULL;
    *out_argc = n;
    *out_argv = v;
    return 0;
nomem:
    for (int j = 0; j < n; j++)
        free(v[j]);
    free(v);
    return -1;
}

void fm_cli_free_args(int argc, char **argv)
{
    for (int i = 0; i < argc; i++)
        free(argv[i]);
    free(argv);
}
