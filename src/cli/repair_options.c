/* The repair options, shared by every command that reads faults. */
#include <string.h>

#include "cli.h"

int fm_cli_repair_option(int argc, char **argv, int *i, fm_repair_options *opt)
{
    const char *a = argv[*i];
    const char *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    int rc = 1;
    if (!strcmp(a, "--weld-tol")) {
        rc = fm_parse_double(a, val, &opt->weld_tolerance) ? -1 : 1;
        (*i)++;
    } else if (!strcmp(a, "--min-fragment-triangles")) {
        rc = fm_parse_size(a, val, &opt->min_fragment_triangles) ? -1 : 1;
        (*i)++;
    } else if (!strcmp(a, "--min-fragment-fraction")) {
        rc = fm_parse_double(a, val, &opt->min_fragment_area_fraction) ? -1 : 1;
        (*i)++;
    } else if (!strcmp(a, "--keep-fragments")) {
        opt->drop_fragments = 0;
    } else if (!strcmp(a, "--no-split")) {
        opt->split_nonmanifold = 0;
    } else {
        rc = 0;
    }
    return rc;
}

const char *fm_cli_repair_help =
    "  --weld-tol M               also weld vertices closer than M metres (default 0)\n"
    "  --min-fragment-triangles N fragments with fewer triangles ... (default 10)\n"
    "  --min-fragment-fraction F  ... and less than F of the largest area are dropped\n"
    "                             (default 0.001)\n"
    "  --keep-fragments           drop no fragments\n"
    "  --no-split                 keep non-manifold edges (no sheets split)\n";
