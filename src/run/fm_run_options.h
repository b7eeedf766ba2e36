/* faultmesh run, the build tree's fuller interface: the options as one
 * struct of the stages' own option structs (every knob the CLI and its
 * settings file can turn), per-fault rules, and the result's mesh as an
 * fm_mesh. The run module and the tests use it (the CLI uses the
 * installed API only); it is not installed, since its layout follows the
 * stages' structs (installed programs use the setters of fm_run.h, whose
 * keys never change). */
#ifndef FM_RUN_OPTIONS_H
#define FM_RUN_OPTIONS_H

#include <stddef.h>
#include <stdint.h>

#include "fm_connect.h"
#include "fm_core.h"
#include "fm_faultset_write.h"
#include "fm_mesh.h"
#include "fm_remesh.h"
#include "fm_repair.h"
#include "fm_run.h"
#include "fm_sim_write.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What per-fault settings say of one fault: each field counts only where
 * its has_* is set. */
typedef struct fm_fault_settings {
    int has_size, has_top, has_join, has_connect, has_exclude, has_rake, has_rate;
    double size;       /* m */
    fm_top_mode top;
    double top_extend; /* m, with FM_TOP_EXTEND */
    double join;       /* m */
    int connect, exclude;
    double rake, slip_rate_mm_yr;
    long line;         /* where they were said (settings_path:line), 0 if nowhere */
} fm_fault_settings;

/* One per-fault rule: the settings of every fault whose name matches one
 * of the shell patterns (fnmatch). Later rules override earlier ones
 * field by field, as the [[fault]] sections of a settings file. */
typedef struct fm_fault_rule {
    const char *const *match;
    size_t nmatch;
    fm_fault_settings set;
} fm_fault_rule;

/* Everything a run can be told. Strings and arrays are borrowed: they
 * must outlive the run and its result. */
struct fm_run_options {
    fm_repair_options repair;
    fm_model_options model;  /* the fit (its extension is widened as --top extend
                                and the join distance need) */
    fm_remesh_options mesh;  /* size, top, sea level, ... */
    fm_msh_version msh;
    fm_msh_tags msh_tags;
    const char *crs;         /* NULL: the one the inputs name, else EPSG:26711 */
    const char *crs_out;     /* the outputs' CRS; NULL: the run's */
    int jobs;                /* threads (default: the cores, at most 64) */
    int connect;             /* join faults that meet (default 1) */
    double join;             /* join distance, m (default 1000) */
    fm_connect_keep keep;    /* which of two near-duplicate faults is kept */
    int carve;               /* the last guard (default 1) */
    /* simulator attributes */
    const char *slip_path;     /* CSV: pattern,rake,slip_rate; NULL: none */
    const char *metadata_path; /* CFM metadata CSV; NULL: looked for beside the inputs */
    fm_eqsim_coords eqsim;
    const char *kin_paths[FM_RUN_MAX_KINEMATICS]; /* deformation model sections */
    size_t nkin;
    double kin_distance;      /* m (0: the default) */
    double kin_fallback_rate; /* mm/yr of an element without a section */
    int html;                 /* report.html (default 1) */
    size_t max_triangles;     /* refuse a fault or run expected to need more (0: no limit) */
    unsigned formats;         /* FM_OUT_* made by the run (FM_OUT_IGS: the CAD faces) */
    int quads;                /* rectangles instead of triangles */
    const char *cache_dir;    /* the fit cache; NULL: $XDG_CACHE_HOME/faultmesh or
                                 ~/.cache/faultmesh */
    int no_cache;             /* fit every fault, keep no models */
    /* the elastic interaction check (fm_check.h, docs/guide.md): off by
     * default; its constants (Pa, -), search radius (element sizes) and
     * flag ratio; and a file for the full matrices of a small set (NULL:
     * none) */
    int elastic;
    double elastic_mu, elastic_nu, elastic_radius, elastic_fraction;
    int elastic_full_space; /* the full space instead of the half space (a quick look) */
    const char *stiffness_path;
    /* per-fault settings, and where they come from (for messages and the
     * report; NULL: none) */
    const fm_fault_rule *fault_rules;
    size_t nfault_rules;
    const char *settings_path;
};

void fm_run_options_default(fm_run_options *opt);

/* What a fault's settings come to under the rules (as the run takes
 * them). */
void fm_fault_settings_lookup(const fm_fault_rule *rules, size_t nrules, const char *name,
                              fm_fault_settings *out);

/* The run's options as they stand. */
const fm_run_options *fm_run_get_options(const fm_run *run);

/* fm_run_list_inputs, fm_run_list_free: fm_run.h. */

/* Every fault's mesh in one (tag: the fault's index in the set written,
 * not the result's fault index: fm_run_result_copy_mesh gives that);
 * borrowed until the result is destroyed. */
const fm_mesh *fm_run_result_mesh(const fm_run_result *res);

#ifdef __cplusplus
}
#endif
#endif
