/* faultmesh run (fm_run.h): what the files of the run module share.
 * The run flows run.c (fm_run_execute) -> remesh_pool.c (fit and mesh on
 * threads, remesh_fault.c per fault) -> remesh_set.c (merge, last guard,
 * write) -> remesh_report.c (report.json); run_log.c carries messages and
 * progress to the caller's callbacks. Included by the run's .c files
 * only; never by a stage, never installed. */
#ifndef FM_RUN_INTERNAL_H
#define FM_RUN_INTERNAL_H

#include <pthread.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "fm_run_options.h"
#include "fm_cad_write.h"
#include "fm_carve.h"
#include "fm_check.h"
#include "fm_connect.h"
#include "fm_faultset_write.h"
#include "fm_json.h"
#include "fm_model.h"
#include "fm_remesh.h"
#include "fm_reproject.h"
#include "fm_sort.h"
#include "fm_tsurf.h"
#include "sim_attrs.h"

/* The caller's callbacks (fm_run_set_log, fm_run_set_progress), called
 * one at a time under lock, and the cancel flag (run_log.c). */
typedef struct run_ctl {
    fm_log_fn log;
    void *log_user;
    fm_log_level log_max;
    fm_progress_fn progress;
    void *progress_user;
    atomic_int cancelled; /* fm_run_interrupt, or a callback said so */
    pthread_mutex_t lock;
} run_ctl;

run_ctl *run_ctl_create(void);
void run_ctl_destroy(run_ctl *c);
/* A log record (printf format; NULL ctl: dropped). */
void run_log(run_ctl *c, fm_log_level level, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* Whether records of that level reach the caller. */
int run_log_wants(const run_ctl *c, fm_log_level level);
void run_progress_begin(run_ctl *c, const char *stage, size_t count, const char *unit,
                    double weight);
void run_progress_step(run_ctl *c, double weight);
void run_progress_set(run_ctl *c, size_t done, size_t count, const char *unit);
void run_progress_end(run_ctl *c);
int run_cancelled(run_ctl *c);

/* The settings of a run as its files read them: fm_run_options, and what
 * the run settles from them. */
typedef struct remesh_cli {
    const char *dir;
    fm_repair_options repair;
    fm_model_options model;
    fm_remesh_options mesh;
    fm_msh_version msh;
    fm_msh_tags msh_tags;
    const char *crs; /* --crs, or NULL: from the inputs, else EPSG:26711 */
    const char *crs_out; /* --crs-out: the outputs' CRS; NULL: the input's */
    run_ctl *ctl;      /* the caller's callbacks */
    const fm_fault_rule *rules; /* per-fault settings */
    size_t nrules;
    const char *settings_path; /* where they come from; NULL: no settings file */
    int jobs;   /* threads */
    int connect;  /* join faults that meet (default 1) */
    double join;  /* D: join tolerance, m */
    fm_connect_keep keep; /* which of two near-duplicate faults is kept */
    int carve;    /* remove what still crosses between faults (default 1 when connecting) */
    sim_cli sim;          /* --slip, --metadata, --eqsim-coords */
    int html;             /* write report.html (default 1) */
    size_t max_triangles; /* refuse a fault or run expected to need more (0: no limit) */
    unsigned formats;     /* --formats: the outputs written (FMT_* bits; report.json always) */
    int quads;            /* --elements quad: rectangles instead of triangles */
    const char *cache_dir; /* --cache DIR; NULL: the default place (remesh_cache.c) */
    int no_cache;          /* --no-cache */
    char *cache;           /* the fit cache of the run (settle_cache); NULL: none */
    char *cache_note;      /* why there is none, when one was wanted; NULL: none */
    int elastic_check;     /* --elastic-check */
    fm_elastic_options elastic;
    const char *stiffness_path; /* --stiffness-matrix FILE; NULL: none */
} remesh_cli;

/* The outputs (fm_run.h's FM_OUT_*). */
enum {
    FMT_VTU = FM_OUT_VTU, FMT_MSH = FM_OUT_MSH, FMT_STL = FM_OUT_STL, FMT_OBJ = FM_OUT_OBJ,
    FMT_EXO = FM_OUT_EXO, FMT_TS = FM_OUT_TS, FMT_IGS = FM_OUT_IGS, FMT_RSQSIM = FM_OUT_RSQSIM,
    FMT_EQSIM = FM_OUT_EQSIM, FMT_HTML = FM_OUT_HTML, FMT_NAMES = FM_OUT_NAMES,
    FMT_ALL = FM_OUT_ALL
};

typedef fm_fault_settings fault_config;

/* Messages fault_warnings gives at most. */
#define FM_MAX_WARNINGS 4

/* The junction plan's pairs and near-duplicates and the cache
 * (fm_connect_neighbours_get): not looked up (no cache, or a fault without
 * a key), read, found and stored, found again over a rejected file, or
 * found but not stored. */
typedef enum neighbours_use {
    NEIGHBOURS_NONE = 0,
    NEIGHBOURS_HIT,
    NEIGHBOURS_MISS,
    NEIGHBOURS_REJECTED,
    NEIGHBOURS_UNSTORED
} neighbours_use;

/* A fault's model and the fit cache (remesh_cache.c). */
typedef enum fit_cache_use {
    FIT_CACHE_NONE = 0, /* not looked up: no cache, or not fitted */
    FIT_CACHE_MISS,     /* fitted (and stored) */
    FIT_CACHE_HIT       /* read from the cache */
} fit_cache_use;

/* What one fault came to, for report.json. */
typedef struct fault_result {
    char *file, *name, *error;
    const char *status; /* "ok", "empty" (nothing below sea level), "error", "dropped"
                           (a near-duplicate), "excluded" (by the settings file) */
    fault_config fc;       /* what the settings file's [[fault]] sections say of it */
    fm_remesh_options mesh; /* its mesh options: the run's, with fc's size and top */
    double join;           /* its join distance, m */
    int connect;           /* whether it joins other faults */
    size_t sheets;
    fm_quality q;
    fm_fidelity fid;
    fm_remesh_stats ms;
    double fitted_area;  /* trimmed fitted surface (below sea level when cut), m^2 */
    double expected;     /* triangles its size calls for over that area */
    double t_fit, t_mesh, t_check;
    unsigned char *join_failed; /* per sheet: its shared curves did not fit (meshed without) */
    char *join_error;           /* why, for the first such sheet */
    size_t *dropped_curves;     /* plan curves left out of its meshes */
    size_t ndropped;
    size_t *through_curves;     /* plan curves it was to end at but runs on past (as of
                                   its last meshing) */
    size_t nthrough;
    size_t *used_curves;        /* plan curves its meshes took (as of its last meshing) */
    size_t nused;
    fm_keyed *curve_pieces;     /* pieces of plan curves its mesh holds (key: fm_edge_key of
                                   the piece's two nodes, index: the curve), sorted */
    size_t npieces;
    size_t carved;              /* triangles removed where it met another fault */
    double carved_area;         /* their area, m^2 */
    size_t set_index;           /* its fault index in the set written, SIZE_MAX if none */
    const fm_mesh *orig;        /* as read, NULL if not (valid until the jobs are released) */
    int want_cad;               /* model.igs is written: make its faces */
    fm_cad_face **cad;          /* its faces in model.igs */
    size_t ncad;
    fit_cache_use fit_cache;    /* whether its model came from the fit cache */
    int has_key;                /* model_key is its model's fit-cache key */
    unsigned char model_key[FM_MODEL_KEY_BYTES];
    int cache_rejected;         /* a file was there under its key but was rejected */
    int cache_unstored;         /* its model could not be stored */
} fault_result;

/* Which faults an output file holds: all of them (the set's files),
 * one (its TSurf file), or none (the reports). */
typedef enum output_kind { OUTPUT_SET, OUTPUT_FAULT, OUTPUT_REPORT } output_kind;

typedef struct output_rec {
    char *file;  /* inside the output folder */
    char *error; /* why it was not written; NULL when it was */
    size_t fault; /* OUTPUT_FAULT: the fault's index in the set */
    output_kind kind;
} output_rec;

/* Every output file of a run, written or not (remesh_outputs.c). */
typedef struct output_log {
    const char *dir;
    run_ctl *ctl; /* where "not written" is said */
    output_rec *rec;
    size_t n, cap;
    size_t written, unwritten;
    size_t lost; /* records memory ran out for */
} output_log;

typedef struct run_state {
    run_ctl *ctl;       /* the caller's callbacks */
    fm_mesh *set;       /* all faults; tag = fault index */
    int32_t *sheet;     /* per triangle of set: the sheet of its fault it is on */
    char **names;
    size_t nfaults;
    const fm_connect_plan *plan;
    int32_t *node_vertex; /* per plan node: its vertex in set, -1 until used */
    size_t *plan_res;     /* per plan fault index (objects in input order): its entry in res */
    size_t nplan_faults;
    double time[5];       /* read and fit, connect, mesh, merge and check, write (wall
                             clock, s) */
    int mesh_rounds;      /* rounds of meshing again, within time[2] */
    size_t *set_res;      /* per fault of the set (triangle tag): its entry in res */
    const fm_mesh **set_orig; /* and its original (valid until the jobs are released) */
    fm_carve_result *carve; /* faults that still met after meshing; NULL when not carved */
    fm_carve_result *sheet_carve; /* then sheets of one fault that still met (tags: units
                                     of sheet_unit_fault); NULL when none was searched */
    int32_t *sheet_unit_fault;    /* per such unit: its fault */
    int32_t *sheet_unit_first;    /* per fault: its first unit (sheet 0) */
    fault_result *res;
    size_t nres, cap;
    long failed;
    char *crs;              /* the CRS recorded in every output */
    const char *crs_source; /* "option", "input" or "default" */
    const fm_cad_face **cad; /* the faces of the faults in set, in order */
    size_t ncad;
    fm_loss *loss;          /* the connect measures of the final set; NULL if not taken */
    output_log *outputs;    /* what was written; filled while writing */
    neighbours_use neighbours; /* the plan's pairs and near-duplicates and the cache */
    size_t curves_kept, curves_traced; /* the plan's pairs decided from curves kept in the
                                          cache, or traced now (fm_connect_plan_stats) */
    /* the elastic check (remesh_elastic.c): its findings, and the element
     * frames it took (strike, dip, rake per triangle of set), which the
     * stiffness matrices use too; NULL when not made */
    fm_elastic *elastic;
    sim_attrs *elastic_attrs;
    char *elastic_error;     /* why the check could not be made; NULL: none */
} run_state;

/* One input file's faults, fitted and then meshed by workers; merged
 * into the run in file order, so the output does not depend on which
 * thread did what. */
typedef struct file_job {
    const char *path;   /* the file, or the name of an in-memory input */
    const fm_mesh *given; /* an in-memory input (fm_run_add_mesh, the run's), NULL: read path */
    run_ctl *ctl;       /* the caller's callbacks */
    fm_tsurf **objs;
    size_t nobj;
    size_t first;       /* plan fault index of object 0 */
    fault_result *res;  /* per object (one entry if the file could not be read) */
    fm_model **model;   /* per object; NULL unless fitted */
    fm_mesh **mesh;     /* per object; NULL unless meshed */
    int64_t **ids;      /* per object: shared node per mesh vertex */
    unsigned char *redo; /* per object: mesh it again (a curve it took was dropped) */
    size_t n;
} file_job;

/* run.c: the fit's extension widened as --top extend and the join
 * distance need. */
void extend_fit(remesh_cli *cli);

/* Which plan curves, or pieces of them, a round of meshing takes
 * (settle_curves): none of curve c when excluded[c]; when clipped[c], only
 * its edges listed in keep (key: fm_edge_key of two consecutive nodes,
 * index: the curve; sorted), in runs of consecutive kept edges. */
typedef struct curve_filter {
    unsigned char *excluded, *clipped;
    fm_keyed *keep;
    size_t nkeep;
} curve_filter;

/* remesh_cache.c: the fit cache's folder, from --cache DIR, else
 * $XDG_CACHE_HOME/faultmesh, else $HOME/.cache/faultmesh; none with
 * --no-cache, or (cli->cache_note says why, to the log as FM_LOG_INFO)
 * when it cannot be made: the run goes on without. */
void settle_cache(remesh_cli *cli);
void release_cache(remesh_cli *cli);
/* The fit cache's lines: per fault "fit_cached", the run's "fit_cache". */
void cache_json_fault(fm_json *j, const fault_result *r);
void cache_json(fm_json *j, const remesh_cli *cli, const run_state *rs);
void cache_print(const remesh_cli *cli, const run_state *rs, FILE *fp);

/* remesh_fault.c */
int curve_pieces(const fm_connect_plan *plan, size_t f, size_t nsheets, const fm_keyed *edge,
                 size_t ne, fault_result *r);
int share_piece(const fault_result *a, const fault_result *b, size_t c);
/* The length (m) of the pieces of plan curve c that both a and b hold
 * (nodes: the plan's node positions). */
double shared_length(const fault_result *a, const fault_result *b, size_t c, const double *nodes);
void fit_file(const remesh_cli *cli, file_job *job);
/* Each fault with its own options (fault_result.mesh). */
void mesh_file(const fm_connect_plan *plan, const curve_filter *flt, file_job *job, int again);
void release_job(file_job *job);
void abandon_job(file_job *job);

/* remesh_pool.c */
/* Runs one phase of the jobs on cli->jobs threads (the calling one
 * included), a progress stage of its own; run_jobs_open leaves the stage
 * open, for the caller to end when what belongs to it is done too. */
void run_jobs(const remesh_cli *cli, const fm_connect_plan *plan, int phase,
              const curve_filter *flt, file_job *jobs, size_t n);
void run_jobs_open(const remesh_cli *cli, const fm_connect_plan *plan, int phase,
                   const curve_filter *flt, file_job *jobs, size_t n);
/* The number of rounds of meshing again it took. */
int settle_curves(const remesh_cli *cli, const fm_connect_plan *plan, file_job *jobs,
                  size_t njobs);

/* remesh_outputs.c: an output file written (err NULL) or not (said on
 * the log); outputs_done is the same as an fm_output_done of the set's
 * files (ctx: the log). */
void outputs_note(output_log *log, const char *path, size_t fault, output_kind kind,
                  const fm_error *err);
void outputs_done(void *ctx, const char *path, size_t fault, const fm_error *err);
void outputs_free(output_log *log);
/* Whether every file fault f (its index in the set) should be in was
 * written. */
int outputs_complete(const output_log *log, size_t f);
/* "outputs_missing": the files f should be in that were not written. */
void outputs_json_missing(fm_json *j, const output_log *log, size_t f);
/* "outputs": counts, and every file with its outcome. */
void outputs_json(fm_json *j, const output_log *log);
/* The summary's lines: counts, and each file not written with why. */
void outputs_print(const output_log *log, FILE *fp);

/* remesh_names.c: every fault's name as each output has it (number,
 * name, TSurf file, RSQSim/EQSim section name, Exodus II name, MSH
 * physical tag and name), CSV. */
fm_status write_names_csv(const char *path, const fm_faultset *fs, fm_error *err);

/* remesh_set.c */
void merge_job(const remesh_cli *cli, file_job *job, run_state *rs);
void carve_set(const remesh_cli *cli, run_state *rs);

/* The set without vertices no triangle uses; -1 when memory runs out. */
int compact_set(run_state *rs);
/* Junction jn as meshed: the plan's type, unless one of its faults failed
 * or came out empty (*why is then that fault's error, *which the fault),
 * or the mesher could not fit its curve into one of its sheets or the
 * last guard took it away (*why then says so and *which names the fault;
 * else *which is SIZE_MAX). */
fm_junction_type junction_outcome(const run_state *rs, const fm_connect_junction *jn,
                                  const char **why, size_t *which);
/* remesh_side.c: model.igs (SIDE_IGES: path, cad, ncad, crs, rp) or the
 * simulator files (SIDE_SIM: sc, fs, sa, dir, rsqsim, eqsim) written on a
 * thread of their own between side_start and side_join, which notes in
 * log what became of each file and returns the first error. */
typedef enum side_kind { SIDE_IGES, SIDE_SIM } side_kind;

typedef struct side_done {
    char *path;
    size_t fault;
    int failed;
    fm_error err;
} side_done;

typedef struct side_write {
    side_kind kind;
    const char *path;
    const fm_cad_face *const *cad;
    size_t ncad;
    const char *crs;
    fm_reproject *rp;
    const sim_cli *sc;
    const fm_faultset *fs;
    const sim_attrs *sa;
    const char *dir;
    int rsqsim, eqsim;
    /* the outcome */
    fm_status st;
    fm_error err;
    side_done done[2];
    size_t ndone;
    pthread_t thread;
    int threaded;
} side_write;

void side_start(side_write *w);
fm_status side_join(side_write *w, output_log *log);

/* The fault set in every format (remesh_set.c): every file tried even
 * when another failed, each noted in rs->outputs; the first failure's
 * status, FM_OK when all were written. */
fm_status write_set(const remesh_cli *cli, const run_state *rs, sim_attrs *sa);

/* remesh_report.c */
/* The run's figures over all faults and junctions. */
typedef struct run_totals {
    size_t ok, warned, dropped, empty, excluded, sheets;
    size_t triangles, below30, below20, forced, edges, band, carved, carved_pairs;
    size_t crossings_kept; /* fault pairs the last guard left crossing (fm_carve_pair.kept) */
    size_t carved_sheets;  /* triangles it removed where sheets of one fault crossed */
    size_t junctions[4]; /* by fm_junction_type, as meshed */
    double angle_min, worst_dist, zmax;
    const char *angle_min_fault, *worst_dist_fault;
} run_totals;
void run_totals_of(const run_state *rs, run_totals *t);
void print_summary(const remesh_cli *cli, const run_state *rs, FILE *fp);
/* The run's end: every fault's results freed (run.c). */
void run_state_free(run_state *rs);
/* The line (and warnings) of a fault, as -v shows it: FM_LOG_DETAIL. */
void log_fault(run_ctl *ctl, const fault_result *r);
fm_status write_report(const remesh_cli *cli, const run_state *rs, const sim_attrs *sa,
                       fm_error *err);
/* What a user should look at before trusting meshed fault r: up to
 * FM_MAX_WARNINGS messages in w; their count. */
int fault_warnings(const fault_result *r, char w[FM_MAX_WARNINGS][160]);

/* remesh_loss.c */
typedef struct loss_totals {
    double gap, gap_max, orig_area, missing, missing_away, worst_share, moved_max;
    size_t gap_pairs, gap_pairs_over_2H, gap_max_pair, worst_share_fault, moved_fault;
    size_t moved_over, islands, island_faults;
    size_t unjoined_curves; /* junctions with an intersection curve left unjoined */
} loss_totals;
/* Takes the measures of rs->set (the originals must still be there). */
void measure_loss(const remesh_cli *cli, run_state *rs);
void loss_totals_of(const run_state *rs, loss_totals *t);
void json_loss_fault(fm_json *j, const run_state *rs, const fault_result *r);
void json_loss(fm_json *j, const run_state *rs);
void print_loss(const run_state *rs, FILE *fp);

/* remesh_elastic.c: the elastic check of rs->set (--elastic-check; or
 * only the element frames, for --stiffness-matrix), its "elastic" object
 * of report.json, its lines of the summary, its groups for report.html,
 * and the matrices file. */
void check_elastic(const remesh_cli *cli, run_state *rs);
void json_elastic(fm_json *j, const remesh_cli *cli, const run_state *rs);
void print_elastic(const run_state *rs, FILE *fp);
fm_status write_stiffness(const remesh_cli *cli, const run_state *rs, fm_error *err);
void free_elastic(run_state *rs);

/* remesh_html.c */
/* DIR/report.html: called while the originals are still there (before
 * the jobs are released). */
fm_status write_report_html(const remesh_cli *cli, const run_state *rs, fm_error *err);

/* Strings the setters copied (run_set.c), kept while the run or one of
 * its results points into them. */
typedef struct run_strings {
    atomic_int refs;
    char **v;
    size_t n;
} run_strings;
run_strings *run_strings_ref(run_strings *s); /* NULL stays NULL */
void run_strings_unref(run_strings *s);

/* A settings file a run read (run_config.c): its [[fault]] sections as
 * the run's rules, and the inputs it lists; kept while the run or one of
 * its results points into it. */
typedef struct run_config {
    atomic_int refs;
    struct fm_settings *file;
    fm_fault_rule *rules;
    const char **inputs; /* strings of file */
    size_t ninputs;
} run_config;
run_config *run_config_ref(run_config *c); /* NULL stays NULL */
/* The FM_OUT_* bits of a comma-separated list of names ("vtu,msh"); 0,
 * or -1 and err naming a bad one. */
int run_formats_parse(const char *list, unsigned *out, fm_error *err);
void run_config_unref(run_config *c);

/* run_api.c, run_set.c: a run (fm_run.h) */
struct fm_run {
    fm_run_options opt;
    run_ctl *ctl;
    char **paths;         /* the input files, or in-memory inputs' names (owned) */
    fm_mesh **meshes;     /* per input: its mesh when in memory, else NULL (owned) */
    size_t npaths, cap;
    sim_cli sim;  /* the simulator data fm_run_prepare read */
    int prepared;
    run_strings *strings; /* what the setters copied; NULL: none */
    run_config *config;   /* fm_run_read_settings; NULL: none */
    int msh_given;        /* the MSH version was set (fm_run_check_options) */
};
/* Options changed: what fm_run_prepare read is read again. */
void run_unprepare(fm_run *run);

/* run_inputs.c: fm_run_list_inputs with the run's log. */
long run_list_inputs(const char *const *args, size_t nargs, run_ctl *log, char ***out,
                     fm_error *err);
void run_list_free(char **list, long n);

/* run.c, run_api.c: a run's result (fm_run.h) */
struct fm_run_result {
    run_strings *strings; /* the setters' strings its settings point into */
    run_config *config;   /* the settings file its rules point into */
    remesh_cli cli;       /* the run's settings; its sim data and cache are the result's */
    run_state rs;
    output_log outputs;
    file_job *jobs;       /* until the outputs are written */
    size_t njobs;
    fm_connect_plan *plan;
    run_ctl *ctl;         /* the callbacks, once the run is over */
    double t4;            /* when the merge and check ended */
    int written;
    char *dir;            /* where fm_run_result_write wrote (a copy) */
};

/* The run on files into res (cli set, the cache settled); on failure res
 * is destroyed and the error said. */
fm_status run_execute(fm_run_result *res, const char *const *files,
                      const fm_mesh *const *meshes, size_t nfiles, fm_error *err);
/* remesh_fault.c: an in-memory input as the TSurf object a file would
 * give (name in its header, one part). */
fm_status tsurf_of_mesh(const char *name, const fm_mesh *m, fm_tsurf **out, fm_error *err);

#endif
