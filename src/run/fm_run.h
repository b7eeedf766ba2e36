/* faultmesh run: a whole `faultmesh remesh` as a library call.
 *
 * Every fault of the inputs read, repaired, fitted (or read from the fit
 * cache), joined where faults meet (the junction plan, meshing again until
 * every shared curve is in both meshes, the last guard), checked, and then
 * written as one fault set with report.json and report.html.
 *
 *   fm_run_options o;
 *   fm_run_options_default(&o);
 *   o.mesh.size = 1000;
 *   fm_run *run = fm_run_create(&o);
 *   fm_run_add_path(run, "a.ts", &err);       ... one call per input file
 *   fm_run_result *res = NULL;
 *   if (fm_run_execute(run, &res, &err) == FM_OK)
 *       fm_run_result_write(res, "out", o.formats, &err);
 *   fm_run_result_destroy(res);
 *   fm_run_destroy(run);
 *
 * The library never prints and never exits: messages go to the log
 * callback, progress to the progress callback (which may cancel), and a
 * run that cannot go on returns an fm_status with the reason in fm_error.
 * A run where some faults fail still returns FM_OK: the result says which
 * failed (fm_run_result_nfailed).
 *
 * Threads: an fm_run is used by one thread at a time; the run itself works
 * on options.jobs threads, and the callbacks may be called from any of
 * them, one call at a time. Process-wide effects: OpenBLAS is told to use
 * one thread (src/fit/solve.c), and the temporary files of writes in
 * progress are registered with fm_atomic.h.
 *
 * This first step exposes the options as a plain struct of the stage
 * options (fm_run_options_default fills it); see docs/library.md. */
#ifndef FM_RUN_H
#define FM_RUN_H

#include <stddef.h>
#include <stdint.h>

#include "fm_connect.h"
#include "fm_core.h"
#include "fm_faultset_write.h"
#include "fm_mesh.h"
#include "fm_remesh.h"
#include "fm_repair.h"
#include "fm_sim_write.h"

#ifdef __cplusplus
extern "C" {
#endif

/* fm_run_execute's status when the caller cancelled: the next value after
 * core's fm_status codes. It joins fm_status in fm_core.h with the step
 * that changes core anyway (any change there changes the fit cache's
 * code digest, and so every cache key and report.json's fit_cache.code). */
#define FM_ERR_CANCELLED ((fm_status)(FM_ERR_NUMERIC + 1))

typedef struct fm_run fm_run;               /* options and inputs */
typedef struct fm_run_result fm_run_result; /* what a run came to */

/* The outputs (fm_run_options.formats, fm_run_result_write); report.json
 * is always written. Values never change. */
enum {
    FM_OUT_VTU = 1 << 0,    /* mesh.vtu */
    FM_OUT_MSH = 1 << 1,    /* mesh.msh (Gmsh) */
    FM_OUT_STL = 1 << 2,    /* mesh.stl */
    FM_OUT_OBJ = 1 << 3,    /* mesh.obj */
    FM_OUT_EXO = 1 << 4,    /* mesh.exo (Exodus II) */
    FM_OUT_TS = 1 << 5,     /* NAME.ts per fault (GoCAD TSurf) */
    FM_OUT_IGS = 1 << 6,    /* model.igs (trimmed B-spline surfaces) */
    FM_OUT_RSQSIM = 1 << 7, /* mesh.rsqsim */
    FM_OUT_EQSIM = 1 << 8,  /* mesh.eqsim */
    FM_OUT_HTML = 1 << 9,   /* report.html */
    FM_OUT_NAMES = 1 << 10, /* names.csv */
    FM_OUT_ALL = (1 << 11) - 1
};

/* Triangles a run may be expected to make by default: what a 24 GB
 * machine holds through the whole pipeline (about 0.75 kB per triangle
 * measured on the whole CFM at 500 m), with room to spare. */
#define FM_RUN_DEFAULT_MAX_TRIANGLES 20000000

#define FM_RUN_MAX_KINEMATICS 4

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
typedef struct fm_run_options {
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
    /* per-fault settings, and where they come from (for messages and the
     * report; NULL: none) */
    const fm_fault_rule *fault_rules;
    size_t nfault_rules;
    const char *settings_path;
} fm_run_options;

void fm_run_options_default(fm_run_options *opt);

/* What a fault's settings come to under the rules (as the run takes
 * them). */
void fm_fault_settings_lookup(const fm_fault_rule *rules, size_t nrules, const char *name,
                              fm_fault_settings *out);

/* The options one at a time, by a key whose values never change (gaps
 * leave room by group), as the installed library and the Python package
 * will set them: fm_run_set_int/double/string on a run's copy of its
 * options. Strings set here are copied and kept by the run and by its
 * results. */
typedef enum fm_run_option {
    FM_OPT_SIZE = 100,         /* double > 0: mesh.size, m */
    FM_OPT_TOP = 101,          /* int: fm_top_mode */
    FM_OPT_TOP_EXTEND = 102,   /* double >= 0: mesh.top_extend, m */
    FM_OPT_SEA_LEVEL = 103,    /* double: mesh.sea_level, m */
    FM_OPT_CONNECT = 200,      /* int 0/1 */
    FM_OPT_JOIN_DISTANCE = 201, /* double > 0, m */
    FM_OPT_KEEP = 202,         /* int: fm_connect_keep */
    FM_OPT_CARVE = 203,        /* int 0/1: the last guard */
    FM_OPT_MAX_TRIANGLES = 204, /* int >= 0 (0: no limit) */
    FM_OPT_THREADS = 300,      /* int 1..1024 */
    FM_OPT_CRS = 400,          /* string; NULL: from the inputs, else EPSG:26711 */
    FM_OPT_CRS_OUT = 401,      /* string; NULL: the run's */
    FM_OPT_CACHE_DIR = 402,    /* string; NULL: the default place */
    FM_OPT_CACHE = 403,        /* int 0/1: the fit cache */
    FM_OPT_MSH_VERSION = 500,  /* int: fm_msh_version */
    FM_OPT_MSH_TAGS = 501,     /* int: fm_msh_tags */
    FM_OPT_FORMATS = 502,      /* int: FM_OUT_* mask, not 0 */
    FM_OPT_REPORT_HTML = 503,  /* int 0/1 */
    FM_OPT_QUADS = 504,        /* int 0/1: rectangles */
    FM_OPT_SLIP = 600,         /* string: slip table CSV; NULL: none */
    FM_OPT_METADATA = 601,     /* string: CFM metadata CSV; NULL: found beside the inputs */
    FM_OPT_EQSIM_COORDS = 602, /* int: fm_eqsim_coords */
    FM_OPT_KINEMATICS = 603,   /* string: one more sections file (at most
                                  FM_RUN_MAX_KINEMATICS); NULL: none again */
    FM_OPT_KINEMATICS_DISTANCE = 604, /* double > 0, m */
    FM_OPT_KINEMATICS_FALLBACK = 605  /* double >= 0, mm/yr */
} fm_run_option;

typedef enum fm_log_level {
    FM_LOG_ERROR = 1,
    FM_LOG_WARN = 2,
    FM_LOG_INFO = 3,  /* notes (no fit cache, no metadata found, ...) */
    FM_LOG_DETAIL = 4 /* a record per fault as it is merged */
} fm_log_level;
/* message: one or more lines, without the last newline. */
typedef void (*fm_log_fn)(void *user, fm_log_level level, const char *message);

typedef enum fm_progress_event {
    FM_PROGRESS_BEGIN = 1, /* a stage of count items (0: of unknown length) of unit,
                              weighing weight */
    FM_PROGRESS_STEP = 2,  /* an item of weight done */
    FM_PROGRESS_SET = 3,   /* done of count items (of unit) */
    FM_PROGRESS_END = 4    /* the stage ended */
} fm_progress_event;

typedef struct fm_progress {
    fm_progress_event event;
    const char *stage; /* BEGIN: its name */
    size_t done, count;
    const char *unit;
    double weight;
} fm_progress;
/* Non-zero cancels the run: fm_run_execute then ends with
 * FM_ERR_CANCELLED (checked between stages and before each file). */
typedef int (*fm_progress_fn)(void *user, const fm_progress *p);

/* The options are copied (their strings borrowed); NULL: out of memory. */
fm_run *fm_run_create(const fm_run_options *opt);
void fm_run_destroy(fm_run *run); /* NULL ignored */
/* Records up to max_level (FM_LOG_ERROR .. FM_LOG_DETAIL) go to fn. */
void fm_run_set_log(fm_run *run, fm_log_level max_level, fm_log_fn fn, void *user);
void fm_run_set_progress(fm_run *run, fm_progress_fn fn, void *user);
/* From any thread: the run ends with FM_ERR_CANCELLED. */
void fm_run_interrupt(fm_run *run);

/* FM_ERR_INVALID (and why) for a value out of the option's bounds, an
 * option of another type, or an unknown one. */
fm_status fm_run_set_int(fm_run *run, fm_run_option opt, int64_t v, fm_error *err);
fm_status fm_run_set_double(fm_run *run, fm_run_option opt, double v, fm_error *err);
fm_status fm_run_set_string(fm_run *run, fm_run_option opt, const char *v, fm_error *err);
/* The bounds of a numeric option; FM_ERR_INVALID for a string or unknown
 * one. */
fm_status fm_run_option_bounds(fm_run_option opt, double *lo, double *hi);
/* The run's options as they stand. */
const fm_run_options *fm_run_get_options(const fm_run *run);

/* An input (copied): a TSurf file, or a folder, whose .ts files are taken
 * as fm_run_list_inputs lists them. Faults come out in the order of the
 * files and of the objects in each. A file that cannot be read is a fault
 * that fails (in the result), as one that cannot be parsed. */
fm_status fm_run_add_path(fm_run *run, const char *path, fm_error *err);

/* The .ts (or .TS) files paths name: files as given, folders searched
 * recursively, each folder's entries in byte order (hidden ones left
 * out), a folder reached again (a symbolic link looping back) skipped
 * with a FM_LOG_WARN record to log (may be NULL). Their number, the list
 * in *out (fm_run_list_free), or -1 and err saying why (a path that is
 * not there, a folder that cannot be read, memory). */
long fm_run_list_inputs(const char *const *paths, size_t npaths, fm_log_fn log, void *user,
                        char ***out, fm_error *err);
void fm_run_list_free(char **list, long n);

/* Reads what the simulator attributes need (the slip table, the CFM
 * metadata named or found beside one of near, the kinematics sections)
 * and checks the EQSim CRS. fm_run_execute does it (with the input files
 * as near) when it was not done; a caller that wants to refuse bad
 * options before the inputs are listed calls it first. */
fm_status fm_run_prepare(fm_run *run, const char *const *near, size_t nnear, fm_error *err);

/* The run up to its outputs. FM_OK with *out set even when some faults
 * failed; an error (*out NULL) when the run could not go on: the faults
 * call for more than max_triangles, the inputs name different CRSs, the
 * CRS is unusable, memory ran out, or FM_ERR_CANCELLED. */
fm_status fm_run_execute(fm_run *run, fm_run_result **out, fm_error *err);

void fm_run_result_destroy(fm_run_result *res); /* NULL ignored */
size_t fm_run_result_nfaults(const fm_run_result *res);
/* Faults that failed ("error"). */
size_t fm_run_result_nfailed(const fm_run_result *res);
const char *fm_run_result_fault_name(const fm_run_result *res, size_t i);
/* "ok", "empty" (nothing below sea level), "error", "dropped" (a
 * near-duplicate), "excluded" (by the per-fault settings); *why (may be
 * NULL) the reason, or NULL. */
const char *fm_run_result_fault_status(const fm_run_result *res, size_t i, const char **why);
/* Every fault's mesh in one (tag: the fault's index in the set written);
 * borrowed until the result is destroyed. */
const fm_mesh *fm_run_result_mesh(const fm_run_result *res);

/* Writes the outputs formats asks for (a subset of the run's
 * options.formats: model.igs and rectangles are made by the run) and
 * report.json into dir (which must exist), each tried even when another
 * failed; once per result. FM_OK when every file was written, else the
 * first failure. */
fm_status fm_run_result_write(fm_run_result *res, const char *dir, unsigned formats,
                              fm_error *err);
/* Files fm_run_result_write could not write. */
size_t fm_run_result_unwritten(const fm_run_result *res);
/* The run's summary as text (what `faultmesh remesh` prints), after
 * fm_run_result_write; malloc'ed (free), NULL when memory runs out. */
char *fm_run_result_summary(const fm_run_result *res);

#ifdef __cplusplus
}
#endif
#endif
