/* `faultmesh synth`: write the synthetic fault system as TSurf files. */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "fm_synth.h"

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

int fm_cmd_synth(int argc, char **argv)
{
    fm_synth_options opt;
    fm_synth_options_default(&opt);
    const char *dir = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            synth_usage(stdout);
            return FM_EXIT_OK;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (!val) {
                fm_cli_missing(a);
                return FM_EXIT_USAGE;
            }
            dir = val;
            i++;
        } else if (!strcmp(a, "--spacing")) {
            if (fm_parse_double(a, val, &opt.spacing))
                return FM_EXIT_USAGE;
            if (opt.spacing < 20.0 || opt.spacing > 20000.0) {
                fprintf(stderr, "faultmesh: --spacing needs 20 to 20000 (m), got '%s'\n", val);
                return FM_EXIT_USAGE;
            }
            i++;
        } else if (!strcmp(a, "--seed")) {
            size_t seed;
            if (fm_parse_size(a, val, &seed))
                return FM_EXIT_USAGE;
            opt.seed = (unsigned)seed;
            i++;
        } else {
            fprintf(stderr, "faultmesh: synth: unexpected argument '%s' (see faultmesh synth "
                            "--help)\n",
                    a);
            return FM_EXIT_USAGE;
        }
    }
    if (!dir) {
        synth_usage(stderr);
        return FM_EXIT_USAGE;
    }
    fm_synth *s = NULL;
    fm_error err;
    fm_error_clear(&err);
    if (fm_synth_create(&opt, &s, &err) != FM_OK || fm_synth_write(s, dir, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        fm_synth_destroy(s);
        return FM_EXIT_FAILURES;
    }
    for (size_t i = 0; i < fm_synth_nfaults(s); i++)
        printf("%s/%s.ts  %s\n", dir, fm_synth_fault_name(s, i),
               fm_synth_fault_description(s, i));
    fm_synth_destroy(s);
    return FM_EXIT_OK;
}
