/** @file
 * faultmesh run: a whole `faultmesh remesh` as a library call.
 *
 * Every fault of the inputs read, repaired, fitted (or read from the fit
 * cache), joined where faults meet (the junction plan, meshing again until
 * every shared curve is in both meshes, the last guard), checked, and then
 * written as one fault set with report.json and report.html.
 *
 * @code
 *   fm_error err;
 *   fm_error_clear(&err);
 *   fm_run *run = fm_run_create(NULL);       // the defaults
 *   fm_run_set_double(run, FM_OPT_SIZE, 1000, &err);
 *   fm_run_add_path(run, "a.ts", &err);      // a call per file or folder
 *   fm_run_result *res = NULL;
 *   if (fm_run_execute(run, &res, &err) == FM_OK)
 *       fm_run_result_write(res, "out", FM_OUT_VTU, &err);
 *   fm_run_result_destroy(res);
 *   fm_run_destroy(run);
 * @endcode
 *
 * The library never prints and never exits: messages go to the log
 * callback, progress to the progress callback (which may cancel), and a
 * run that cannot go on returns an fm_status with the reason in fm_error.
 * A run where some faults fail still returns FM_OK: the result says which
 * failed (fm_run_result_nfailed).
 *
 * Threads: an fm_run is used by one thread at a time; the run itself works
 * on FM_OPT_THREADS threads, and the callbacks may be called from any of
 * them, one call at a time. Process-wide effects: OpenBLAS is told to use
 * one thread (src/fit/solve.c), and the temporary files of writes in
 * progress are registered with the library's atomic writes (so that a
 * signal handler of the program's can remove them); the library installs
 * no signal handler.
 *
 * Memory: strings and arrays the result hands out are borrowed until the
 * result is destroyed; what a call says is malloc'ed is released with
 * fm_free. */
#ifndef FM_RUN_H
#define FM_RUN_H

#include <stddef.h>
#include <stdint.h>

#include "fm_export.h"
#include "fm_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_run fm_run;               /**< options and inputs */
typedef struct fm_run_result fm_run_result; /**< what a run came to */
/** The options as one struct of the stages' option structs: the build
 * tree's fuller interface (src/run/fm_run_options.h, what the tests fill),
 * not installed because its layout follows the stages'. Installed
 * programs pass NULL to fm_run_create and use the setters. */
typedef struct fm_run_options fm_run_options;

/** The outputs (FM_OPT_FORMATS, fm_run_result_write); report.json is
 * always written. Values never change. */
enum {
    FM_OUT_VTU = 1 << 0,    /**< mesh.vtu */
    FM_OUT_MSH = 1 << 1,    /**< mesh.msh (Gmsh) */
    FM_OUT_STL = 1 << 2,    /**< mesh.stl */
    FM_OUT_OBJ = 1 << 3,    /**< mesh.obj */
    FM_OUT_EXO = 1 << 4,    /**< mesh.exo (Exodus II) */
    FM_OUT_TS = 1 << 5,     /**< NAME.ts per fault (GoCAD TSurf) */
    FM_OUT_IGS = 1 << 6,    /**< model.igs (trimmed B-spline surfaces) */
    FM_OUT_RSQSIM = 1 << 7, /**< mesh.rsqsim */
    FM_OUT_EQSIM = 1 << 8,  /**< mesh.eqsim */
    FM_OUT_HTML = 1 << 9,   /**< report.html */
    FM_OUT_NAMES = 1 << 10, /**< names.csv */
    FM_OUT_ALL = (1 << 11) - 1
};

/** Triangles a run may be expected to make by default: what a 24 GB
 * machine holds through the whole pipeline (about 0.75 kB per triangle
 * measured on the whole CFM at 500 m), with room to spare. */
#define FM_RUN_DEFAULT_MAX_TRIANGLES 20000000

/** Sections files FM_OPT_KINEMATICS takes at most. */
#define FM_RUN_MAX_KINEMATICS 4

/** The options one at a time, by a key whose values never change (gaps
 * leave room by group: 1xx mesh, 2xx connect, 3xx threads, 4xx CRS and
 * fit cache, 5xx outputs, 6xx simulator attributes). Strings set are
 * copied and kept by the run and by its results. */
typedef enum fm_run_option {
    FM_OPT_SIZE = 100,         /**< double > 0: triangle size, m (default 1000) */
    FM_OPT_TOP = 101,          /**< int: FM_RUN_TOP_* (default FM_RUN_TOP_CUT) */
    FM_OPT_TOP_EXTEND = 102,   /**< double >= 0: with FM_RUN_TOP_EXTEND, m */
    FM_OPT_SEA_LEVEL = 103,    /**< double: the cut's level, m (default 0) */
    FM_OPT_CONNECT = 200,      /**< int 0/1: join faults that meet (default 1) */
    FM_OPT_JOIN_DISTANCE = 201, /**< double > 0, m (default 1000) */
    FM_OPT_KEEP = 202,         /**< int: FM_RUN_KEEP_*, which of two near-duplicates is kept */
    FM_OPT_CARVE = 203,        /**< int 0/1: the last guard (default 1) */
    FM_OPT_MAX_TRIANGLES = 204, /**< int >= 0 (0: no limit) */
    FM_OPT_THREADS = 300,      /**< int 1..1024 (default: the cores, at most 64) */
    FM_OPT_CRS = 400,          /**< string; NULL: from the inputs, else EPSG:26711 */
    FM_OPT_CRS_OUT = 401,      /**< string; NULL: the run's */
    FM_OPT_CACHE_DIR = 402,    /**< string; NULL: $XDG_CACHE_HOME/faultmesh, ~/.cache/faultmesh */
    FM_OPT_CACHE = 403,        /**< int 0/1: the fit cache (default 1) */
    FM_OPT_MSH_VERSION = 500,  /**< int: FM_RUN_MSH_41, FM_RUN_MSH_22 */
    FM_OPT_MSH_TAGS = 501,     /**< int: FM_RUN_MSH_TAGS_* */
    FM_OPT_FORMATS = 502,      /**< int: FM_OUT_* mask, not 0 (default FM_OUT_ALL) */
    FM_OPT_REPORT_HTML = 503,  /**< int 0/1 (default 1) */
    FM_OPT_QUADS = 504,        /**< int 0/1: rectangles */
    FM_OPT_SLIP = 600,         /**< string: slip table CSV; NULL: none */
    FM_OPT_METADATA = 601,     /**< string: CFM metadata CSV; NULL: found beside the inputs */
    FM_OPT_EQSIM_COORDS = 602, /**< int: FM_RUN_EQSIM_* */
    FM_OPT_KINEMATICS = 603,   /**< string: one more sections file (at most
                                  FM_RUN_MAX_KINEMATICS); NULL: none again */
    FM_OPT_KINEMATICS_DISTANCE = 604, /**< double > 0, m */
    FM_OPT_KINEMATICS_FALLBACK = 605, /**< double >= 0, mm/yr */
    FM_OPT_ELASTIC = 700,          /**< int 0/1: the elastic interaction check (default 0) */
    FM_OPT_ELASTIC_FRACTION = 701, /**< double > 0: pairs coupled above it flagged (0.5) */
    FM_OPT_ELASTIC_RADIUS = 702,   /**< double > 0: pairs within it, element sizes (3) */
    FM_OPT_ELASTIC_MEDIUM = 703,   /**< int: FM_RUN_ELASTIC_* (half space) */
    FM_OPT_SHEAR_MODULUS = 704,    /**< double > 0, Pa (3e10) */
    FM_OPT_POISSON_RATIO = 705,    /**< double in (0, 0.5) (0.25) */
    FM_OPT_STIFFNESS_MATRIX = 706  /**< string: .npy file of the interaction
                                      matrices (Pa/m); NULL: none */
} fm_run_option;

/** Values of the int options above. They are the stages' own values (the
 * build checks that they agree), named here because the stage headers
 * are not installed. */
enum {
    FM_RUN_TOP_CUT = 0,           /**< FM_OPT_TOP: clip at sea level */
    FM_RUN_TOP_KEEP = 1,          /**< keep the fitted (topographic) top */
    FM_RUN_TOP_EXTEND = 2,        /**< extend tops less than FM_OPT_TOP_EXTEND below sea level */
    FM_RUN_KEEP_SMALLER = 0,      /**< FM_OPT_KEEP */
    FM_RUN_KEEP_LARGER = 1,
    FM_RUN_MSH_41 = 0,            /**< FM_OPT_MSH_VERSION: Gmsh 4.1 */
    FM_RUN_MSH_22 = 1,            /**< Gmsh 2.2 */
    FM_RUN_MSH_TAGS_DEFAULT = 0,  /**< FM_OPT_MSH_TAGS */
    FM_RUN_MSH_TAGS_TANDEM = 1,
    FM_RUN_MSH_TAGS_SEISSOL = 2,
    FM_RUN_MSH_TAGS_PYLITH = 3,
    FM_RUN_EQSIM_SPHERICAL = 0,   /**< FM_OPT_EQSIM_COORDS: lat/lon (WGS 84) */
    FM_RUN_EQSIM_RECTANGULAR = 1, /**< the mesh's own x, y */
    FM_RUN_ELASTIC_HALF = 0,      /**< FM_OPT_ELASTIC_MEDIUM: half space, free surface at sea level */
    FM_RUN_ELASTIC_FULL = 1       /**< full space: a quick look */
};

typedef enum fm_log_level {
    FM_LOG_ERROR = 1,
    FM_LOG_WARN = 2,
    FM_LOG_INFO = 3,  /**< notes (no fit cache, no metadata found, ...) */
    FM_LOG_DETAIL = 4 /**< a record per fault as it is merged */
} fm_log_level;
/** message: one or more lines, without the last newline. */
typedef void (*fm_log_fn)(void *user, fm_log_level level, const char *message);

typedef enum fm_progress_event {
    FM_PROGRESS_BEGIN = 1, /**< a stage of count items (0: of unknown length) of unit,
                              weighing weight */
    FM_PROGRESS_STEP = 2,  /**< an item of weight done */
    FM_PROGRESS_SET = 3,   /**< done of count items (of unit) */
    FM_PROGRESS_END = 4    /**< the stage ended */
} fm_progress_event;

typedef struct fm_progress {
    fm_progress_event event;
    const char *stage; /**< BEGIN: its name */
    size_t done, count;
    const char *unit;
    double weight;
} fm_progress;
/** Non-zero cancels the run: fm_run_execute then ends with
 * FM_ERR_CANCELLED (checked between stages and before each file). */
typedef int (*fm_progress_fn)(void *user, const fm_progress *p);

/** A run with the default options (opt NULL; in the build tree, a copy of
 * *opt, its strings borrowed); NULL: out of memory. */
FM_API fm_run *fm_run_create(const fm_run_options *opt);
FM_API void fm_run_destroy(fm_run *run); /**< NULL ignored */
/** Records up to max_level (FM_LOG_ERROR .. FM_LOG_DETAIL) go to fn. */
FM_API void fm_run_set_log(fm_run *run, fm_log_level max_level, fm_log_fn fn, void *user);
FM_API void fm_run_set_progress(fm_run *run, fm_progress_fn fn, void *user);
/** From any thread: the run ends with FM_ERR_CANCELLED. */
FM_API void fm_run_interrupt(fm_run *run);

/** FM_ERR_INVALID (and why) for a value out of the option's bounds, an
 * option of another type, or an unknown one. */
FM_API fm_status fm_run_set_int(fm_run *run, fm_run_option opt, int64_t v, fm_error *err);
FM_API fm_status fm_run_set_double(fm_run *run, fm_run_option opt, double v, fm_error *err);
FM_API fm_status fm_run_set_string(fm_run *run, fm_run_option opt, const char *v,
                                   fm_error *err);
/** The bounds of a numeric option; FM_ERR_INVALID for a string or unknown
 * one. */
FM_API fm_status fm_run_option_bounds(fm_run_option opt, double *lo, double *hi);

/** A handler of options in the command line's words (fm_run_take_option's
 * contract): argv[*i] and its values taken, *i left on the last word
 * taken: 1; 0: not an option it knows; -1: a bad value (err says why). */
typedef int (*fm_option_fn)(void *user, int argc, const char *const *argv, int *i,
                            fm_error *err);

/** The run option argv[*i] names, in the words of the command line and of
 * faultmesh(1) ("--size" "1000", "-j" "2", "--no-connect", "--top"
 * "extend" "500", the repair options), with its value(s): 1, *i left on
 * the last word taken; 0 when argv[*i] is no run option (nothing taken);
 * -1 for a bad or missing value, err saying why in the words the command
 * has always used ("--size needs a positive number, got 'x'"). A front
 * end gives its own options (the output folder, how much it says) first
 * and the rest to this. */
FM_API int fm_run_take_option(fm_run *run, int argc, const char *const *argv, int *i,
                              fm_error *err);
/** One option by its settings-file key and value as text ("size",
 * "1000"; "no_connect", NULL; '_' or '-' alike): what
 * fm_run_take_option takes as "--size" "1000". FM_ERR_INVALID (and why)
 * for an unknown key, a bad value, or a value given to a flag. */
FM_API fm_status fm_run_set_option(fm_run *run, const char *key, const char *value,
                                   fm_error *err);

/** Reads a settings file (TOML, docs/guide.md): its top-level keys are
 * applied as the options they name (as fm_run_take_option takes them;
 * keys it does not know go to other, which may be NULL: the front end's
 * own, such as output), its [[fault]] sections become the run's
 * per-fault rules (they replace those of a file read before), and the
 * inputs it lists are kept (fm_run_settings_input). Paths in it are
 * taken from its folder. Options set after it override it. What is wrong
 * in the file: err "FILE:LINE: why" with err->line > 0; a value an option
 * refused: the option's message, then a line "FILE:LINE: bad value for 'KEY'"
 * (err->line 0); a file that cannot be read: "FILE: why". */
FM_API fm_status fm_run_read_settings(fm_run *run, const char *path, fm_option_fn other,
                                      void *user, fm_error *err);
/** The inputs (files or folders) the settings file lists, as paths from
 * the current folder; borrowed while the run lives. */
FM_API size_t fm_run_settings_ninputs(const fm_run *run);
FM_API const char *fm_run_settings_input(const fm_run *run, size_t i);
/** The settings file read, as given; NULL: none. */
FM_API const char *fm_run_settings_path(const fm_run *run);

/** Settles the options that depend on each other, before a front end
 * goes on: FM_OPT_MSH_TAGS tandem makes MSH 2.2 (FM_ERR_INVALID when
 * another version was set), FM_OPT_QUADS keeps the formats that hold
 * rectangles out of the default FM_OUT_ALL (FM_ERR_INVALID when one of
 * the triangle-only formats was asked for). */
FM_API fm_status fm_run_check_options(fm_run *run, fm_error *err);
/** The value of an int option as it stands; FM_ERR_INVALID for another
 * option. */
FM_API fm_status fm_run_get_int(const fm_run *run, fm_run_option opt, int64_t *v);

/** The .ts (or .TS) files paths name, as fm_run_add_path takes them:
 * files as given, folders searched recursively, each folder's entries in
 * byte order (hidden ones left out), a folder reached again (a symbolic
 * link looping back) skipped with a FM_LOG_WARN record to log (may be
 * NULL). Their number, the list in *out (fm_run_list_free), or -1 and err
 * saying why (a path that is not there, a folder that cannot be read,
 * memory). */
FM_API long fm_run_list_inputs(const char *const *paths, size_t npaths, fm_log_fn log,
                               void *user, char ***out, fm_error *err);
FM_API void fm_run_list_free(char **list, long n); /**< NULL ignored */

/** Refuses (FM_ERR_INVALID, and why) an output folder that would put the
 * inputs at risk: a file, the folder an input file lies in (an output of
 * the same name would replace it), or an input folder or one inside it
 * (the outputs would be read as inputs next time). args: the paths as
 * given, files: the files they name (fm_run_list_inputs). Creates
 * nothing. */
FM_API fm_status fm_run_check_output_dir(const char *outdir, const char *const *args,
                                         size_t nargs, const char *const *files, size_t nfiles,
                                         fm_error *err);

/** An input (copied): a TSurf file, or a folder, whose .ts files are taken
 * recursively, each folder's entries in byte order (hidden ones left
 * out). Faults come out in the order of the files and of the objects in
 * each. A file that cannot be read is a fault that fails (in the result),
 * as one that cannot be parsed. */
FM_API fm_status fm_run_add_path(fm_run *run, const char *path, fm_error *err);

/** An input in memory (copied, as MMG's bulk setters copy): one fault
 * named name, xyz 3 * nv doubles (x east, y north, z up, m), tri 3 * nt
 * vertex indices from 0. It goes through the run as a TSurf file of that
 * name would, in the order of the inputs; report.json gives the name as
 * its file, and no CRS (FM_OPT_CRS, else the inputs', else EPSG:26711).
 * FM_ERR_INVALID (and why) without a name, with fewer than 3 vertices or
 * no triangle, a coordinate not finite, an index out of range or a
 * triangle using a vertex twice. */
FM_API fm_status fm_run_add_mesh(fm_run *run, const char *name, const double *xyz, size_t nv,
                                 const int32_t *tri, size_t nt, fm_error *err);

/** Reads what the simulator attributes need (the slip table, the CFM
 * metadata named or found beside one of near, the kinematics sections)
 * and checks the EQSim CRS. fm_run_execute does it (with the input files
 * as near) when it was not done; a caller that wants to refuse bad
 * options before the inputs are listed calls it first. */
FM_API fm_status fm_run_prepare(fm_run *run, const char *const *near, size_t nnear,
                                fm_error *err);

/** The run up to its outputs. FM_OK with *out set even when some faults
 * failed; an error (*out NULL) when the run could not go on: the faults
 * call for more than FM_OPT_MAX_TRIANGLES, the inputs name different
 * CRSs, the CRS is unusable, memory ran out, or FM_ERR_CANCELLED. */
FM_API fm_status fm_run_execute(fm_run *run, fm_run_result **out, fm_error *err);

FM_API void fm_run_result_destroy(fm_run_result *res); /**< NULL ignored; may outlive its run */
FM_API size_t fm_run_result_nfaults(const fm_run_result *res);
/** Faults that failed ("error"). */
FM_API size_t fm_run_result_nfailed(const fm_run_result *res);
/** Fault i (0 .. nfaults - 1) in input order; NULL past the end. */
FM_API const char *fm_run_result_fault_name(const fm_run_result *res, size_t i);
/** "ok", "empty" (nothing below sea level), "error", "dropped" (a
 * near-duplicate), "excluded" (by the per-fault settings); *why (may be
 * NULL) the reason, or NULL. */
FM_API const char *fm_run_result_fault_status(const fm_run_result *res, size_t i,
                                              const char **why);

/** The meshes of every fault as one mesh: nodes where faults meet are one
 * node, used by the triangles of each (the shared nodes). Sizes, then a
 * copy into arrays the caller allocates (as MMG's bulk getters do):
 * xyz 3 * nvertices doubles (x east, y north, z up, m, in the run's
 * CRS), tri 3 * ntriangles vertex indices from 0 (the triangles of the
 * written mesh files, in their order), fault ntriangles indices of the
 * fault (as fm_run_result_fault_name counts them) each triangle belongs
 * to. Any of the three may be NULL. FM_ERR_INVALID without a result. */
FM_API size_t fm_run_result_nvertices(const fm_run_result *res);
FM_API size_t fm_run_result_ntriangles(const fm_run_result *res);
FM_API fm_status fm_run_result_copy_mesh(const fm_run_result *res, double *xyz, int32_t *tri,
                                         int32_t *fault, fm_error *err);

/** Writes the outputs formats asks for (a subset of FM_OPT_FORMATS:
 * model.igs and rectangles are made by the run; 0: report.json alone)
 * and report.json into dir (which must exist), each tried even when
 * another failed; once per result. FM_OK when every file was written,
 * else the first failure. */
FM_API fm_status fm_run_result_write(fm_run_result *res, const char *dir, unsigned formats,
                                     fm_error *err);
/** Files fm_run_result_write could not write. */
FM_API size_t fm_run_result_unwritten(const fm_run_result *res);
/** The run's summary as text (what `faultmesh remesh` prints), after
 * fm_run_result_write; malloc'ed (fm_free), NULL when memory runs out. */
FM_API char *fm_run_result_summary(const fm_run_result *res);

/** Frees what a faultmesh call handed over as malloc'ed (from a program or
 * binding that may not share the library's malloc). NULL ignored. */
FM_API void fm_free(void *p);

#ifdef __cplusplus
}
#endif
#endif
