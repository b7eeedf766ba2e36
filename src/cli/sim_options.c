/* `faultmesh remesh` and `demo`: the simulator side's options (the run
 * reads the files they name, src/run/sim_attrs.c). */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "remesh_cli.h"

const char *const fm_cli_sim_help =
    "simulator files: DIR/mesh.rsqsim (RSQSim) and DIR/mesh.eqsim (EQSim geometry)\n"
    "  --slip FILE           rake and slip rate per fault: CSV rows pattern,rake,slip_rate\n"
    "                        (fault name or shell glob, degrees Aki & Richards, mm/yr)\n"
    "  --metadata FILE       CFM metadata CSV whose Slip Sense gives each fault's rake\n"
    "                        (default: CFM5.3_Metadata.csv in the parent folder of an\n"
    "                        input folder, if there is one)\n"
    "  --kinematics FILE     deformation model fault sections (GeoJSON, e.g. NSHM23's\n"
    "                        NSHM23_FSD_v3.geojson and, again, its geologic deformation\n"
    "                        model): each element's slip rate and rake from the nearest\n"
    "                        section (--slip and the settings file still override)\n"
    "  --kinematics-distance M  farthest an element takes a section from (default 3000)\n"
    "  --kinematics-fallback MM_YR  slip rate of an element without a section (default 0;\n"
    "                        its rake then from the slip sense)\n"
    "  --eqsim-coords spherical|utm\n"
    "                        EQSim geometry in WGS 84 lat/lon via PROJ (default) or in\n"
    "                        the mesh's own metres (rectangular)\n";

int sim_option(int argc, char **argv, int *i, fm_run_options *sc)
{
    const char *a = argv[*i], *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    if (!strcmp(a, "--slip")) {
        if (!val)
            return fm_cli_missing(a);
        sc->slip_path = val;
    } else if (!strcmp(a, "--metadata")) {
        if (!val)
            return fm_cli_missing(a);
        sc->metadata_path = val;
    } else if (!strcmp(a, "--kinematics")) {
        if (!val)
            return fm_cli_missing(a);
        if (sc->nkin == FM_RUN_MAX_KINEMATICS) {
            fprintf(stderr, "faultmesh: --kinematics at most %d times\n", FM_RUN_MAX_KINEMATICS);
            return -1;
        }
        sc->kin_paths[sc->nkin++] = val;
    } else if (!strcmp(a, "--kinematics-distance")) {
        if (fm_parse_positive(a, val, &sc->kin_distance))
            return -1;
    } else if (!strcmp(a, "--kinematics-fallback")) {
        if (fm_parse_double(a, val, &sc->kin_fallback_rate))
            return -1;
    } else if (!strcmp(a, "--eqsim-coords")) {
        if (val && !strcmp(val, "spherical")) {
            sc->eqsim = FM_EQSIM_SPHERICAL;
        } else if (val && (!strcmp(val, "utm") || !strcmp(val, "rectangular"))) {
            sc->eqsim = FM_EQSIM_RECTANGULAR;
        } else {
            fprintf(stderr, "faultmesh: --eqsim-coords takes spherical or utm\n");
            return -1;
        }
    } else {
        return 0;
    }
    (*i)++;
    return 1;
}
