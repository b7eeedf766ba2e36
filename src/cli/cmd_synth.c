/* `faultmesh synth`: write the synthetic fault system as TSurf files (the
 * library's fm_synthetic.h). */
#include <stdio.h>
#include <string.h>

#include "cli.h"

static void synth_usage(FILE *fp)
{
    fprintf(fp, "usage: faultmesh synth [options] -o DIR\n"
                "Writes the synthetic fault system (known analytic surfaces) as one\n"
                "TSurf file per fault, plus DIR/faults.json describing them.\n\n"
                "options:\n"
                "  -o, --output DIR   output folder (created if missing)\n"
                "  --spacing M        nominal triangle size in metres (default 500)\n"
                "  --seed N           seed of the noise and irregular triangulation (default 1)\n"
                "  -h, --help         this text\n");
}

/* The options into spec and *dir: FM_EXIT_OK, -1 after --help, or
 * FM_EXIT_USAGE after saying why. */
static int parse(fm_synth_spec *spec, int argc, char **argv, const char **dir)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        fm_error err;
        fm_error_clear(&err);
        int taken;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            synth_usage(stdout);
            return -1;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (i + 1 >= argc)
                return fm_cli_missing(a), FM_EXIT_USAGE;
            *dir = argv[++i];
        } else if ((taken = fm_synth_spec_take_option(spec, argc, FM_CLI_ARGV(argv), &i, &err))) {
            if (fm_cli_taken(taken, &err) < 0)
                return FM_EXIT_USAGE;
        } else {
            fprintf(stderr, "faultmesh: synth: unexpected argument '%s' (see faultmesh synth "
                            "--help)\n",
                    a);
            return FM_EXIT_USAGE;
        }
    }
    if (!*dir) {
        synth_usage(stderr);
        return FM_EXIT_USAGE;
    }
    return FM_EXIT_OK;
}

int fm_cmd_synth(int argc, char **argv)
{
    fm_synth_spec *spec = fm_synth_spec_create();
    const char *dir = NULL;
    int rc = spec ? parse(spec, argc, argv, &dir) : FM_EXIT_FAILURES;
    fm_synth *s = NULL;
    fm_error err;
    fm_error_clear(&err);
    if (rc == 0 && (fm_synth_generate(spec, &s, &err) != FM_OK ||
                    fm_synth_write(s, dir, &err) != FM_OK))
        rc = fm_cli_fail(&err, FM_EXIT_FAILURES);
    for (size_t i = 0; rc == 0 && i < fm_synth_nfaults(s); i++)
        printf("%s/%s.ts  %s\n", dir, fm_synth_fault_name(s, i),
               fm_synth_fault_description(s, i));
    fm_synth_destroy(s);
    fm_synth_spec_destroy(spec);
    return rc < 0 ? FM_EXIT_OK : rc;
}
