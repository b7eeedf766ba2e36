/* faultmesh CLI, `remesh` and `demo`: what the files of the command share.
 * The run flows cmd_remesh.c (run) -> remesh_pool.c (fit and mesh on
 * threads, remesh_fault.c per fault) -> remesh_set.c (merge, last guard,
 * write) -> remesh_report.c (report.json); remesh_options.c reads the
 * options. */
#ifndef FM_REMESH_RUN_H
#define FM_REMESH_RUN_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "cli.h"
#include "config.h"
#include "progress.h"
#include "fm_cad_write.h"
#include "fm_carve.h"
#include "fm_check.h"
#include "fm_connect.h"
#include "fm_faultset_write.h"
#include "fm_json.h"
#include "fm_model.h"
#include "fm_remesh.h"
#include "fm_sort.h"
#include "fm_tsurf.h"
#include "sim_attrs.h"

typedef struct remesh_cli {
    const char *dir;
    fm_repair_options repair;
    fm_model_options model;
    fm_remesh_options mesh;
    fm_msh_version msh;
    int msh_version_given;
    fm_msh_tags msh_tags;
    const char *crs; /* --crs, or NULL: from the inputs, else EPSG:26711 */
    const char *crs_out; /* --crs-out: the outputs' CRS; NULL: the input's */
    int quiet;
    int verbose;  /* a line per fault */
    progress *prog; /* stderr; NULL: none */
    const config *cfg; /* --config: per-fault settings; NULL: none */
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
} remesh_cli;

/* The outputs --formats chooses among, by name: vtu msh stl obj exo ts igs
 * rsqsim eqsim html names (names.csv). */
enum {
    FMT_VTU = 1 << 0, FMT_MSH = 1 << 1, FMT_STL = 1 << 2, FMT_OBJ = 1 << 3,
    FMT_EXO = 1 << 4, FMT_TS = 1 << 5, FMT_IGS = 1 << 6, FMT_RSQSIM = 1 << 7,
    FMT_EQSIM = 1 << 8, FMT_HTML = 1 << 9, FMT_NAMES = 1 << 10, FMT_ALL = (1 << 11) - 1
};
/* The bits of a comma-separated list of names; -1 after naming a bad one. */
int formats_parse(const char *list, unsigned *out);

/* Triangles a run may be expected to make by default: what a 24 GB
 * machine holds through the whole pipeline (about 0.75 kB per triangle
 * measured on the whole CFM at 500 m), with room to spare. */
#define FM_DEFAULT_MAX_TRIANGLES 20000000

/* Messages fault_warnings gives at most. */
#define FM_MAX_WARNINGS 4

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
    output_rec *rec;
    size_t n, cap;
    size_t written, unwritten;
    size_t lost; /* records memory ran out for */
} output_log;

typedef struct run_state {
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
} run_state;

/* One input file's faults, fitted and then meshed by workers; merged
 * into the run in file order, so the output does not depend on which
 * thread did what. */
typedef struct file_job {
    const char *path;
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

/* remesh_options.c */
void remesh_usage(FILE *fp);
/* Options shared by remesh and demo: 1 if argv[*i] was one (its value
 * consumed), -1 on error, 0 if not one of them. */
int mesh_option(int argc, char **argv, int *i, remesh_cli *cli);
int settle_msh(remesh_cli *cli);
/* --elements quad: the formats that hold rectangles (default) or a usage
 * error for another one asked for; 0 or -1 after saying why. */
int settle_elements(remesh_cli *cli);
void extend_fit(remesh_cli *cli);
void cli_defaults(remesh_cli *cli);
/* The settings file's top-level keys, applied as the options they name
 * (command-line options given after override them); its inputs, if it
 * lists any, in *inputs (free the array, not the strings). 0, or -1
 * after printing FILE:LINE: why. */
int remesh_config(remesh_cli *cli, config *c, const char ***inputs, size_t *ninputs);

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
 * --no-cache, or (cli->cache_note says why, on stderr too unless quiet)
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
void run_jobs(const remesh_cli *cli, const fm_connect_plan *plan, int phase,
              const curve_filter *flt, file_job *jobs, size_t n);
void settle_curves(const remesh_cli *cli, const fm_connect_plan *plan, file_job *jobs,
                   size_t njobs);

/* remesh_outputs.c: an output file written (err NULL) or not (said on
 * stderr); outputs_done is the same as an fm_output_done of the set's
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
void print_fault(const fault_result *r, double H);
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

/* remesh_html.c */
/* DIR/report.html: called while the originals are still there (before
 * the jobs are released). */
fm_status write_report_html(const remesh_cli *cli, const run_state *rs, fm_error *err);

#endif
