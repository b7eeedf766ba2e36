/* faultmesh run: the simulator side of a run (the options --slip,
 * --metadata, --eqsim-coords, --kinematics); per-element attributes (strike, dip, rake,
 * slip rate) for the VTU and report.json; the RSQSim and EQSim files. */
#ifndef FM_RUN_SIM_ATTRS_H
#define FM_RUN_SIM_ATTRS_H

#include <stddef.h>

#include "fm_faultset_write.h"
#include "fm_run_options.h"
#include "fm_json.h"
#include "fm_metadata.h"
#include "fm_sections.h"
#include "fm_sim_write.h"

#define SIM_MAX_KINEMATICS FM_RUN_MAX_KINEMATICS

struct run_ctl;

typedef struct sim_cli {
    const char *slip_path;     /* --slip */
    const char *metadata_path; /* --metadata; NULL: looked for beside the inputs */
    fm_eqsim_coords eqsim;     /* --eqsim-coords */
    const fm_fault_rule *rules; /* per-fault settings: their rake and slip_rate come first */
    size_t nrules;
    struct run_ctl *ctl;       /* where messages go */
    const char *kin_paths[SIM_MAX_KINEMATICS]; /* --kinematics files (merged) */
    size_t nkin;
    double kin_distance;       /* --kinematics-distance, m (0: the default) */
    double kin_fallback_rate;  /* --kinematics-fallback: mm/yr of an element without a
                                  section (default 0) */
    struct fm_sections *sections; /* read by sim_cli_load */
    /* Read by sim_cli_load. */
    fm_metadata *md;
    fm_slip_table *slip;
    char *metadata_found; /* the metadata file used (malloc'ed), NULL if none */
} sim_cli;

/* Reads --slip and the metadata (--metadata, or the first
 * CFM5.3_Metadata.csv in the parent folder of an input folder, or of a
 * file's folder) and, for spherical EQSim, checks that PROJ can convert
 * from crs (when given: else settle_crs checks the CRS the inputs name);
 * FM_OK, or an error saying why. */
fm_status sim_cli_load(sim_cli *sc, const char *crs, const char *const *paths, size_t npaths,
                       fm_error *err);
void sim_cli_free(sim_cli *sc);

/* Everything the outputs need, for a fault set of nfaults faults. */
typedef struct sim_attrs {
    size_t nfaults, ntriangles;
    fm_fault_slip *slip;            /* per fault */
    double *rake_f, *rate_f;        /* per fault: degrees, m/s */
    double *strike, *dip;           /* per triangle, degrees (grid north) */
    double *rake_t, *rate_t;        /* per triangle: degrees, m/s */
    double *mean_strike, *mean_dip; /* per fault (area-weighted; strike axial) */
    fm_vtu_array cells[4];          /* strike, dip, rake, slip_rate */
    /* --kinematics (NULL without): per triangle the section it took; per
     * fault its area, the area that took a section, the part of that whose
     * rake disagrees with the slip sense, the rates taken (mm/yr); per
     * fault the sections taken and their areas (CSR over ksec_start) */
    struct fm_element_kinematics *kin;
    /* --elements quad: the rectangles written (remesh_quads.c); NULL without */
    struct fm_tiles *tiles;
    double *k_area, *k_matched, *k_disagree, *k_rmin, *k_rmax;
    size_t *ksec_start;
    int32_t *ksec_id;
    double *ksec_area;
} sim_attrs;

/* -1 when memory runs out (sim_attrs_free also then). */
int sim_attrs_make(const sim_cli *sc, const fm_faultset *fs, sim_attrs *a);
void sim_attrs_free(sim_attrs *a);

/* What the simulator files will hold that a user should know (the
 * kinematics' cover, elements left with default rakes and rates): logged
 * once, before they are written. */
void sim_say(const sim_cli *sc, const fm_faultset *fs, const sim_attrs *a);

/* DIR/mesh.rsqsim and DIR/mesh.eqsim (those asked for), each tried, each
 * told to done; the first failure's status. Logs nothing: one call per
 * file may run on threads of their own. */
fm_status sim_write(const sim_cli *sc, const fm_faultset *fs, const sim_attrs *a,
                    const char *dir, int rsqsim, int eqsim, fm_output_done done, void *ctx);

/* sim_kinematics.c: each element's rake and rate from the sections
 * (under the --slip rules and the settings file, over the fallback); 0,
 * -1 when memory runs out, -2 after logging why it failed. */
int sim_kinematics_apply(const sim_cli *sc, const fm_faultset *fs, sim_attrs *a);
void sim_kinematics_free(sim_attrs *a);
/* Whether triangle t of fault f carries the default rake. */
int sim_kinematics_rake_default(const sim_attrs *a, size_t t, size_t f);
/* report.json: fault f's "kinematics" (in its attributes), and the run's. */
void sim_kinematics_json_fault(fm_json *j, const sim_cli *sc, const sim_attrs *a, size_t f);
void sim_kinematics_json_summary(fm_json *j, const sim_cli *sc, const sim_attrs *a,
                                 const char *const *names);

/* Fault f's "attributes" object of report.json. */
void sim_json_fault(fm_json *j, const sim_cli *sc, const sim_attrs *a, size_t f);
/* The report's "simulator" object (files, metadata, defaults used). */
void sim_json_summary(fm_json *j, const sim_cli *sc, const sim_attrs *a,
                      const char *const *names);

#endif
