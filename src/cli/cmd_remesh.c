/* `faultmesh remesh`: every fault of the inputs read, repaired, fitted and
 * meshed at size H, checked, and written as one fault set (VTU, MSH, STL,
 * OBJ, Exodus II, one TSurf per fault) with report.json. `faultmesh demo` runs it on
 * the synthetic fault system. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "fm_atomic.h"
#include "fm_carve.h"
#include "fm_check.h"
#include "fm_clock.h"
#include "fm_closest.h"
#include "fm_connect.h"
#include "fm_faultset_write.h"
#include "fm_json.h"
#include "fm_model.h"
#include "fm_remesh.h"
#include "fm_sort.h"
#include "fm_synth.h"
#include "fm_tsurf.h"
#include "sim_attrs.h"
#include "remesh_cad.h"

typedef struct remesh_cli {
    const char *dir;
    fm_repair_options repair;
    fm_model_options model;
    fm_remesh_options mesh;
    fm_msh_version msh;
    int msh_version_given;
    fm_msh_tags msh_tags;
    const char *crs; /* --crs, or NULL: from the inputs, else EPSG:26711 */
    int quiet;
    int jobs;   /* threads */
    int connect;  /* join faults that meet (default 1) */
    double join;  /* D: join tolerance, m */
    fm_connect_keep keep; /* which of two near-duplicate faults is kept */
    int carve;    /* remove what still crosses between faults (default 1 when connecting) */
    sim_cli sim;          /* --slip, --metadata, --eqsim-coords */
} remesh_cli;

/* What one fault came to, for report.json. */
typedef struct fault_result {
    char *file, *name, *error;
    const char *status; /* "ok", "empty" (nothing below sea level), "error" */
    size_t sheets;
    fm_quality q;
    fm_fidelity fid;
    fm_remesh_stats ms;
    double fitted_area;  /* trimmed fitted surface (below sea level when cut), m^2 */
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
    fm_cad_face **cad;          /* its faces in model.igs */
    size_t ncad;
} fault_result;

/* Which pieces of its plan curves fault f holds (an edge between two
 * consecutive nodes of the curve), given the edges of its mesh between
 * shared nodes (fm_remesh_shared_edges): a sheet keeps only part of a
 * curve that another of its curves cuts across. -1: out of memory. */
static int curve_pieces(const fm_connect_plan *plan, size_t f, size_t nsheets,
                        const fm_keyed *edge, size_t ne, fault_result *r)
{
    free(r->curve_pieces);
    r->curve_pieces = NULL;
    r->npieces = 0;
    size_t cap = 0;
    int rc = 0;
    for (size_t s = 0; rc == 0 && s < nsheets; s++) {
        const fm_connect_shared *sh;
        size_t n = fm_connect_plan_sheet(plan, f, s, &sh);
        for (size_t c = 0; rc == 0 && c < n; c++)
            for (size_t i = 0; i + 1 < sh[c].n; i++) {
                uint64_t key = fm_edge_key((uint64_t)sh[c].node[i], (uint64_t)sh[c].node[i + 1]);
                size_t at = fm_keyed_lower_bound(edge, ne, key);
                if (at == ne || edge[at].key != key)
                    continue;
                if (r->npieces == cap) {
                    cap = cap ? 2 * cap : 64;
                    fm_keyed *g = realloc(r->curve_pieces, cap * sizeof *g);
                    if (!g) {
                        rc = -1;
                        break;
                    }
                    r->curve_pieces = g;
                }
                /* by its nodes, not its place in the sheet's list: the
                 * sheets of two faults may hold different stretches */
                r->curve_pieces[r->npieces] = (fm_keyed){key, sh[c].curve};
                r->npieces++;
            }
    }
    /* by key, for share_piece's search */
    if (rc == 0 && fm_sort_keyed(r->curve_pieces, r->npieces))
        rc = -1;
    return rc;
}

/* Whether faults a and b both hold some piece of plan curve c. */
static int share_piece(const fault_result *a, const fault_result *b, size_t c)
{
    for (size_t i = 0; i < a->npieces; i++) {
        if (a->curve_pieces[i].index != c)
            continue;
        uint64_t key = a->curve_pieces[i].key;
        for (size_t at = fm_keyed_lower_bound(b->curve_pieces, b->npieces, key);
             at < b->npieces && b->curve_pieces[at].key == key; at++)
            if (b->curve_pieces[at].index == c)
                return 1;
    }
    return 0;
}

static int push_curve(size_t **list, size_t *n, size_t curve)
{
    size_t *g = realloc(*list, (*n + 1) * sizeof *g);
    if (!g)
        return -1;
    *list = g;
    g[(*n)++] = curve;
    return 0;
}

static void remesh_usage(FILE *fp)
{
    fprintf(fp,
            "usage: faultmesh remesh [options] -o DIR FILE|DIR...\n"
            "Meshes every fault at edge length H with well-shaped triangles on its\n"
            "fitted surface, cut at sea level by default, and writes DIR/mesh.vtu,\n"
            "DIR/mesh.msh, DIR/mesh.stl, DIR/mesh.obj, DIR/mesh.exo (Exodus II),\n"
            "DIR/NAME.ts per fault and DIR/report.json.\n\n"
            "options:\n"
            "  -o, --output DIR      output folder (created if missing)\n"
            "  --size H              target edge length in metres (default 1000)\n"
            "  --top cut|keep        cut at sea level (z = 0, default) or keep the fitted top\n"
            "  --top extend D        extend tops less than D metres below sea level up to it,\n"
            "                        then cut\n"
            "  --msh-version 4.1|2.2 Gmsh MSH format version (default 4.1; 2.2 with\n"
            "                        --msh-tags tandem)\n"
            "  --msh-tags default|tandem|seissol|pylith\n"
            "                        MSH physical tags and names as that code expects\n"
            "                        (default: one group per fault, named after it)\n"
            "  --crs STRING          coordinate reference system recorded in the outputs\n"
            "                        (default: the one the input TSurf files name, e.g.\n"
            "                        NAME EPSG:26711 in their coordinate-system block,\n"
            "                        else EPSG:26711, the CFM's UTM 11N NAD27)\n"
            "  -j, --jobs N          threads (default: all cores); the output is the same\n"
            "                        for any N\n"
            "  --no-connect          mesh every fault on its own (default: faults that meet\n"
            "                        share their nodes along the intersection)\n"
            "  --keep-crossings      when connecting, keep the triangles of two faults that\n"
            "                        still run through each other away from a shared curve\n"
            "                        (default: the one losing the smaller share of its\n"
            "                        area gives way there, reported)\n"
            "  --join D              join faults whose surfaces come within D metres\n"
            "                        (default 1000)\n"
            "  --keep-duplicate smaller|larger\n"
            "                        of two faults that nearly duplicate each other (half\n"
            "                        the area of one within 50 m of the other, as rupture\n"
            "                        composites over their section faults), keep the\n"
            "                        smaller (default: the sections) or the larger\n"
            "  --quiet               no per-fault lines\n"
            SIM_CLI_HELP);
    fputs(fm_cli_repair_help, fp);
}

/* Area of a triangle's part with z <= level. */
static double area_below(const double *a, const double *b, const double *c, double level)
{
    const double *p[3] = {a, b, c};
    double poly[4][3];
    int n = 0;
    for (int i = 0; i < 3; i++) {
        const double *u = p[i], *v = p[(i + 1) % 3];
        double du = u[2] - level, dv = v[2] - level;
        if (du <= 0)
            memcpy(poly[n++], u, sizeof poly[0]);
        if ((du < 0 && dv > 0) || (du > 0 && dv < 0)) {
            double f = du / (du - dv);
            for (int k = 0; k < 3; k++)
                poly[n][k] = u[k] + f * (v[k] - u[k]);
            n++;
        }
    }
    double area = 0;
    for (int i = 1; i + 1 < n; i++)
        area += fm_triangle_area(poly[0], poly[i], poly[i + 1]);
    return area;
}

static double fitted_area(const fm_model *m, int cut, double level)
{
    double area = 0;
    for (size_t i = 0; i < fm_model_nsheets(m); i++) {
        const fm_mesh *s = fm_model_samples(m, i);
        if (!s)
            continue;
        const double *X = fm_mesh_vertices(s);
        const int32_t *T = fm_mesh_triangles(s);
        for (size_t t = 0; t < fm_mesh_ntriangles(s); t++) {
            const double *a = X + 3 * T[3 * t], *b = X + 3 * T[3 * t + 1], *c = X + 3 * T[3 * t + 2];
            area += cut ? area_below(a, b, c, level) : fm_triangle_area(a, b, c);
        }
    }
    return area;
}

/* Repairs and fits one fault (one TSurf object). */
static fm_status fit_object(const remesh_cli *cli, const char *path, const fm_mesh *orig,
                            fault_result *r, fm_model **model, fm_error *err)
{
    fm_surface *surf = NULL;
    double t0 = fm_clock_seconds();
    fm_status st = fm_repair(orig, &cli->repair, &surf, err);
    if (st == FM_OK)
        st = fm_model_build(path, surf, &cli->model, model, err);
    fm_surface_destroy(surf);
    r->t_fit = fm_clock_seconds() - t0;
    return st;
}

/* The shared curves the plan gives each sheet of fault f, as the mesher
 * takes them; *store (free it) holds them. NULL when there are none. */
static fm_remesh_sheet_curves *plan_curves(const fm_connect_plan *plan, size_t f,
                                           const fm_model *m, const unsigned char *excluded,
                                           fm_remesh_curve **store, unsigned char **dropped,
                                           size_t **curve_of, size_t *ntotal)
{
    *store = NULL;
    *dropped = NULL;
    *curve_of = NULL;
    *ntotal = 0;
    if (!plan)
        return NULL;
    size_t ns = fm_model_nsheets(m), total = 0;
    for (size_t i = 0; i < ns; i++) {
        const fm_connect_shared *sh;
        size_t n = fm_connect_plan_sheet(plan, f, i, &sh);
        for (size_t c = 0; c < n; c++)
            total += !(excluded && excluded[sh[c].curve]);
    }
    if (total == 0)
        return NULL;
    fm_remesh_sheet_curves *per = calloc(ns, sizeof *per);
    fm_remesh_curve *cv = malloc(total * sizeof *cv);
    *dropped = calloc(total, 1);
    *curve_of = malloc(total * sizeof **curve_of);
    if (!per || !cv || !*dropped || !*curve_of) {
        free(per);
        free(cv);
        free(*dropped);
        free(*curve_of);
        *dropped = NULL;
        *curve_of = NULL;
        return NULL;
    }
    *ntotal = total;
    size_t k = 0;
    for (size_t i = 0; i < ns; i++) {
        const fm_connect_shared *sh;
        size_t n = fm_connect_plan_sheet(plan, f, i, &sh);
        per[i].curves = cv + k;
        per[i].dropped = *dropped + k;
        for (size_t c = 0; c < n; c++) {
            if (excluded && excluded[sh[c].curve])
                continue;
            per[i].n++;
            (*curve_of)[k] = sh[c].curve;
            cv[k].uv = sh[c].uv;
            cv[k].n = sh[c].n;
            cv[k].node = sh[c].node;
            cv[k].end = sh[c].end;
            k++;
        }
    }
    *store = cv;
    return per;
}

/* Meshes a fitted fault into fault (tags = sheet; ids: shared node per
 * vertex) and checks it against the original. */
static fm_status mesh_object(const remesh_cli *cli, const char *path, const fm_mesh *orig,
                             const fm_model *model, const fm_connect_plan *plan,
                             const unsigned char *excluded, size_t f, fault_result *r,
                             fm_mesh **fault, int64_t **ids, fm_error *err)
{
    double t1 = fm_clock_seconds();
    fm_remesh_options mo = cli->mesh;
    mo.name = path;
    fm_remesh_curve *store = NULL;
    unsigned char *dropped = NULL;
    size_t *curve_of = NULL, ntotal = 0;
    fm_remesh_sheet_curves *per =
        plan_curves(plan, f, model, excluded, &store, &dropped, &curve_of, &ntotal);
    r->sheets = fm_model_nsheets(model);
    r->join_failed = per ? calloc(r->sheets, 1) : NULL;
    fm_error *jerr = per ? calloc(r->sheets, sizeof *jerr) : NULL;
    fm_remesh_boundary *bounds = calloc(r->sheets + 1, sizeof *bounds);
    fm_status st = ((per && (!r->join_failed || !jerr)) || !bounds)
                       ? fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory")
                       : fm_remesh_model_joined(model, per, &mo, fault, ids, r->join_failed, jerr,
                                                &r->ms, bounds, err);
    if (st == FM_OK) {
        /* which sheets have triangles (tag = sheet) */
        unsigned char *meshed = calloc(r->sheets + 1, 1);
        const int32_t *tag = fm_mesh_tags(*fault);
        for (size_t t = 0; meshed && t < fm_mesh_ntriangles(*fault); t++)
            if (tag[t] >= 0 && (size_t)tag[t] < r->sheets)
                meshed[tag[t]] = 1;
        size_t skipped = 0;
        st = meshed ? fm_cli_cad_faces(model, bounds, meshed, r->name,
                                       cli->mesh.top != FM_TOP_KEEP, cli->mesh.sea_level, &r->cad,
                                       &r->ncad, &skipped, err)
                    : fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        free(meshed);
    }
    for (size_t i = 0; bounds && i < r->sheets; i++)
        fm_remesh_boundary_free(&bounds[i]);
    free(bounds);
    /* the first reason a sheet's curves did not fit, for the report */
    for (size_t i = 0; jerr && r->join_failed && i < r->sheets && !r->join_error; i++)
        if (r->join_failed[i])
            r->join_error = strdup(jerr[i].message);
    free(jerr);
    /* the plan curves this fault could not take, for the junction table
     * (kept over meshings: a curve dropped once is excluded after), those
     * it took, which its partners must take too, and those of them it was
     * to end at but runs on past */
    free(r->used_curves);
    r->used_curves = ntotal ? malloc(ntotal * sizeof *r->used_curves) : NULL;
    r->nused = 0;
    free(r->through_curves);
    r->through_curves = NULL;
    r->nthrough = 0;
    for (size_t k = 0; k < ntotal && st == FM_OK; k++) {
        if (dropped[k] == 1) {
            if (push_curve(&r->dropped_curves, &r->ndropped, curve_of[k]))
                st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
            continue;
        }
        if (dropped[k] == 2 && push_curve(&r->through_curves, &r->nthrough, curve_of[k]))
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        if (r->used_curves)
            r->used_curves[r->nused++] = curve_of[k];
    }
    free(dropped);
    free(curve_of);
    free(per);
    free(store);
    r->fitted_area = fitted_area(model, cli->mesh.top != FM_TOP_KEEP, cli->mesh.sea_level);
    /* Shared nodes take the plan's position (on both surfaces), as in the
     * fault set, so that the check measures what is written. */
    if (st == FM_OK && plan && *ids) {
        double *X = fm_mesh_vertices_mut(*fault);
        const double *P = fm_connect_plan_nodes(plan);
        for (size_t v = 0; v < fm_mesh_nvertices(*fault); v++)
            if ((*ids)[v] >= 0)
                memcpy(X + 3 * v, P + 3 * (*ids)[v], 3 * sizeof *X);
        size_t ne;
        fm_keyed *edge = fm_remesh_shared_edges(*fault, *ids, -1, &ne);
        if (!edge || curve_pieces(plan, f, fm_model_nsheets(model), edge, ne, r))
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        free(edge);
    }
    double t2 = fm_clock_seconds();
    r->t_mesh = t2 - t1;
    if (st == FM_OK && fm_mesh_ntriangles(*fault) > 0) {
        fm_closest_tree *tree = fm_closest_tree_create(orig, err);
        st = tree ? fm_check_quality(*fault, -1, cli->mesh.size, &r->q) : FM_ERR_NOMEM;
        if (st == FM_OK)
            st = fm_check_fidelity(*fault, -1, orig, tree, &r->fid);
        if (st != FM_OK && tree)
            fm_error_set(err, st, path, 0, "out of memory");
        fm_closest_tree_destroy(tree);
    }
    r->t_check = fm_clock_seconds() - t2;
    return st;
}

typedef struct run_state {
    fm_mesh *set;       /* all faults; tag = fault index */
    int32_t *sheet;     /* per triangle of set: the sheet of its fault it is on */
    char **names;
    size_t nfaults;
    const fm_connect_plan *plan;
    int32_t *node_vertex; /* per plan node: its vertex in set, -1 until used */
    size_t *plan_res;     /* per plan fault index (objects in input order): its entry in res */
    size_t nplan_faults;
    double time[3];       /* fit, connect, mesh + check (wall clock, s) */
    size_t *set_res;      /* per fault of the set (triangle tag): its entry in res */
    const fm_mesh **set_orig; /* and its original (valid until the jobs are released) */
    fm_carve_result *carve; /* faults that still met after meshing; NULL when not carved */
    fault_result *res;
    size_t nres, cap;
    long failed;
    char *crs;              /* the CRS recorded in every output */
    const char *crs_source; /* "option", "input" or "default" */
    const fm_cad_face **cad; /* the faces of the faults in set, in order */
    size_t ncad;
} run_state;

static fault_result *new_result(run_state *rs)
{
    if (rs->nres == rs->cap) {
        size_t cap = rs->cap ? 2 * rs->cap : 64;
        fault_result *n = realloc(rs->res, cap * sizeof *n);
        if (!n)
            return NULL;
        rs->res = n;
        rs->cap = cap;
    }
    fault_result *r = &rs->res[rs->nres++];
    memset(r, 0, sizeof *r);
    return r;
}

/* What a user should look at before trusting a meshed fault: the figures
 * of the check that the mesh issue bounds, when this fault breaks them.
 * Writes up to two messages into w (each up to 160 bytes); returns the
 * count. Nodes of an extended top lie off the original by design. */
static int fault_warnings(const fault_result *r, char w[2][160])
{
    int n = 0;
    if (r->fid.max > 100.0 && r->ms.extended == 0)
        snprintf(w[n++], 160,
                 "nodes up to %.0f m from the original surface (the fitted surface departs from it)",
                 r->fid.max);
    size_t loose = r->q.below_20 - r->q.below_20_forced;
    if (loose > 0)
        snprintf(w[n++], 160, "%zu triangles under 20 degrees away from sharp outline corners",
                 loose);
    return n;
}

static void print_fault(const fault_result *r, double H)
{
    if (strcmp(r->status, "ok")) {
        printf("%-64s %s%s%s\n", r->name ? r->name : r->file, r->status, r->error ? ": " : "",
               r->error ? r->error : "");
        return;
    }
    printf("%-64s %7zu tri  min %5.1f deg  <30 %5.2f%%  edges in band %5.1f%%  node dist "
           "%5.1f/%6.1f m%s\n",
           r->name, r->q.triangles, r->q.angle_min,
           100.0 * (double)r->q.below_30 / (double)(r->q.triangles ? r->q.triangles : 1),
           100.0 * (double)r->q.edges_in_band / (double)(r->q.edges ? r->q.edges : 1), r->fid.rms,
           r->fid.max, r->ms.cut ? "  cut" : "");
    char w[2][160];
    int nw = fault_warnings(r, w);
    for (int k = 0; k < nw; k++)
        printf("    warning: %s\n", w[k]);
    (void)H;
}

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

static void fit_file(const remesh_cli *cli, file_job *job)
{
    fm_error err;
    fm_error_clear(&err);
    const char *path = job->path;
    if (fm_tsurf_read_file(path, &job->objs, &job->nobj, &err) != FM_OK) {
        job->res = calloc(1, sizeof *job->res);
        job->mesh = calloc(1, sizeof *job->mesh);
        job->objs = NULL;
        job->nobj = 0;
        if (job->res) {
            job->n = 1;
            job->res->file = strdup(path);
            job->res->status = "error";
            job->res->error = strdup(err.message);
        }
        return;
    }
    size_t nobj = job->nobj;
    job->res = calloc(nobj ? nobj : 1, sizeof *job->res);
    job->mesh = calloc(nobj ? nobj : 1, sizeof *job->mesh);
    job->model = calloc(nobj ? nobj : 1, sizeof *job->model);
    job->ids = calloc(nobj ? nobj : 1, sizeof *job->ids);
    if (!job->res || !job->mesh || !job->model || !job->ids) {
        free(job->res);
        free(job->mesh);
        free(job->model);
        free(job->ids);
        job->res = NULL;
        job->mesh = NULL;
        job->model = NULL;
        job->ids = NULL;
        return;
    }
    job->n = nobj;
    for (size_t o = 0; o < nobj; o++) {
        fault_result *r = &job->res[o];
        const char *name = fm_tsurf_name(job->objs[o]);
        r->file = strdup(path);
        r->name = strdup(name[0] ? name : path);
        fm_error_clear(&err);
        if (fit_object(cli, path, fm_tsurf_mesh(job->objs[o]), r, &job->model[o], &err) != FM_OK) {
            r->status = "error";
            r->error = strdup(err.message);
        }
    }
}

/* A fault's meshing undone before it is meshed again (its dropped
 * curves stay: the report names the fault that could not take them). */
static void reset_result(fault_result *r)
{
    free(r->error);
    free(r->join_failed);
    free(r->join_error);
    for (size_t i = 0; i < r->ncad; i++)
        fm_cad_face_destroy(r->cad[i]);
    free(r->cad);
    r->cad = NULL;
    r->ncad = 0;
    r->error = r->join_error = NULL;
    r->join_failed = NULL;
    r->status = NULL;
    memset(&r->q, 0, sizeof r->q);
    memset(&r->fid, 0, sizeof r->fid);
    memset(&r->ms, 0, sizeof r->ms);
}

/* Meshes the job's faults; again: only those marked in job->redo, with
 * the curves in excluded left out. Models stay for another round
 * (release_job frees them). */
static void mesh_file(const remesh_cli *cli, const fm_connect_plan *plan,
                      const unsigned char *excluded, file_job *job, int again)
{
    if (!job->res || !job->model)
        return;
    fm_error err;
    for (size_t o = 0; o < job->n; o++) {
        fault_result *r = &job->res[o];
        fm_model *model = job->model[o];
        if (!again && model && r->status) {
            /* given up before meshing (a near-duplicate): its model goes here */
            fm_model_destroy(model);
            job->model[o] = NULL;
        }
        if (!model || (again ? !(job->redo && job->redo[o]) : r->status != NULL))
            continue;
        double t_mesh = r->t_mesh, t_check = r->t_check;
        if (again) {
            reset_result(r);
            fm_mesh_destroy(job->mesh[o]);
            job->mesh[o] = NULL;
            free(job->ids[o]);
            job->ids[o] = NULL;
        }
        fm_mesh *fault = NULL;
        fm_error_clear(&err);
        fm_status st = mesh_object(cli, job->path, fm_tsurf_mesh(job->objs[o]), model, plan,
                                   excluded, job->first + o, r, &fault, &job->ids[o], &err);
        /* the time of every meshing counts */
        r->t_mesh += t_mesh;
        r->t_check += t_check;
        if (st == FM_OK && fm_mesh_ntriangles(fault) == 0) {
            r->status = "empty";
            r->error = strdup("nothing of the fault lies below sea level");
            fm_mesh_destroy(fault);
        } else if (st == FM_OK) {
            r->status = "ok";
            job->mesh[o] = fault;
        } else {
            r->status = "error";
            r->error = strdup(err.message);
            fm_mesh_destroy(fault);
        }
    }
}

static void release_job(file_job *job)
{
    for (size_t o = 0; job->model && o < job->n; o++)
        fm_model_destroy(job->model[o]);
    free(job->model);
    job->model = NULL;
    fm_tsurf_free_all(job->objs, job->nobj);
    job->objs = NULL;
    job->nobj = 0;
    free(job->redo);
    job->redo = NULL;
}

/* Frees a job given up after fitting (the run stops before meshing). */
static void abandon_job(file_job *job)
{
    release_job(job);
    for (size_t o = 0; job->res && o < job->n; o++) {
        fault_result *r = &job->res[o];
        free(r->file);
        free(r->name);
        free(r->error);
        free(r->join_failed);
        free(r->join_error);
        free(r->dropped_curves);
        free(r->through_curves);
        free(r->used_curves);
        free(r->curve_pieces);
        fm_mesh_destroy(job->mesh ? job->mesh[o] : NULL);
        free(job->ids ? job->ids[o] : NULL);
    }
    free(job->res);
    free(job->mesh);
    free(job->model);
    free(job->ids);
}

typedef struct pool {
    const remesh_cli *cli;
    const fm_connect_plan *plan;
    int phase;          /* 0: fit, 1: mesh, 2: mesh again those marked */
    const unsigned char *excluded; /* phase 2: plan curves left out */
    file_job *jobs;
    const size_t *order; /* the order jobs are handed out in */
    size_t n, next;
    pthread_mutex_t mu;
} pool;

static void *worker(void *arg)
{
    pool *p = arg;
    for (;;) {
        pthread_mutex_lock(&p->mu);
        size_t i = p->next++;
        pthread_mutex_unlock(&p->mu);
        if (i >= p->n)
            return NULL;
        file_job *job = &p->jobs[p->order ? p->order[i] : i];
        if (p->phase == 0)
            fit_file(p->cli, job);
        else
            mesh_file(p->cli, p->plan, p->excluded, job, p->phase == 2);
    }
}

typedef struct job_key {
    long long bytes;
    size_t index;
} job_key;

static int larger_first(const void *a, const void *b)
{
    const job_key *x = a, *y = b;
    if (x->bytes != y->bytes)
        return x->bytes < y->bytes ? 1 : -1;
    return (x->index > y->index) - (x->index < y->index);
}

/* Largest files first: a large fault started last would keep one thread
 * busy while the others idle (longest-processing-time-first scheduling).
 * Which thread meshes a fault never changes its result, and results are
 * merged in input order, so the order is free. */
static size_t *schedule(const file_job *jobs, size_t n)
{
    size_t *order = malloc((n ? n : 1) * sizeof *order);
    job_key *key = malloc((n ? n : 1) * sizeof *key);
    if (!order || !key) {
        free(key);
        free(order);
        return NULL; /* input order then */
    }
    for (size_t i = 0; i < n; i++) {
        struct stat sb;
        key[i].bytes = stat(jobs[i].path, &sb) == 0 ? (long long)sb.st_size : 0;
        key[i].index = i;
    }
    qsort(key, n, sizeof *key, larger_first);
    for (size_t i = 0; i < n; i++)
        order[i] = key[i].index;
    free(key);
    return order;
}

/* Runs one phase of the jobs on cli->jobs threads (the calling one
 * included). */
static void run_jobs(const remesh_cli *cli, const fm_connect_plan *plan, int phase,
                     const unsigned char *excluded, file_job *jobs, size_t n)
{
    size_t *order = schedule(jobs, n);
    pool p = {cli, plan, phase, excluded, jobs, order, n, 0, PTHREAD_MUTEX_INITIALIZER};
    size_t nt = cli->jobs > 1 ? (size_t)cli->jobs - 1 : 0;
    pthread_t *th = nt ? calloc(nt, sizeof *th) : NULL;
    size_t started = 0;
    for (size_t k = 0; th && k < nt; k++)
        if (pthread_create(&th[k], NULL, worker, &p) == 0)
            started++;
        else
            break;
    worker(&p);
    for (size_t k = 0; k < started; k++)
        pthread_join(th[k], NULL);
    free(th);
    free(order);
}

/* Appends a fault to the set: a shared node is one vertex of the set,
 * made when a fault first uses it, at the plan's position (on both
 * surfaces). */
static fm_status append_fault(run_state *rs, const fm_mesh *fault, const int64_t *ids)
{
    size_t nv = fm_mesh_nvertices(fault), nt = fm_mesh_ntriangles(fault);
    int32_t *map = malloc((nv + 1) * sizeof *map);
    if (!map || fm_mesh_reserve(rs->set, fm_mesh_nvertices(rs->set) + nv,
                                fm_mesh_ntriangles(rs->set) + nt) != FM_OK) {
        free(map);
        return FM_ERR_NOMEM;
    }
    const double *X = fm_mesh_vertices(fault);
    const double *P = rs->plan ? fm_connect_plan_nodes(rs->plan) : NULL;
    for (size_t v = 0; v < nv; v++) {
        int64_t id = ids ? ids[v] : -1;
        if (id >= 0 && rs->node_vertex) {
            if (rs->node_vertex[id] < 0)
                rs->node_vertex[id] =
                    fm_mesh_add_vertex(rs->set, P[3 * id], P[3 * id + 1], P[3 * id + 2]);
            map[v] = rs->node_vertex[id];
        } else {
            map[v] = fm_mesh_add_vertex(rs->set, X[3 * v], X[3 * v + 1], X[3 * v + 2]);
        }
    }
    const int32_t *T = fm_mesh_triangles(fault), *sheet = fm_mesh_tags(fault);
    size_t base = fm_mesh_ntriangles(rs->set);
    int32_t *grown = realloc(rs->sheet, (base + nt + 1) * sizeof *grown);
    if (!grown) {
        free(map);
        return FM_ERR_NOMEM;
    }
    rs->sheet = grown;
    for (size_t t = 0; t < nt; t++) {
        fm_mesh_add_triangle(rs->set, map[T[3 * t]], map[T[3 * t + 1]], map[T[3 * t + 2]],
                             (int32_t)rs->nfaults);
        rs->sheet[base + t] = sheet ? sheet[t] : 0;
    }
    free(map);
    return FM_OK;
}

/* Merges a job's faults into the run, in order. */
static void merge_job(const remesh_cli *cli, file_job *job, run_state *rs)
{
    if (!job->res) {
        fault_result *r = new_result(rs);
        if (r) {
            r->file = strdup(job->path);
            r->status = "error";
            r->error = strdup("out of memory");
        }
        rs->failed++;
        fprintf(stderr, "faultmesh: %s: out of memory\n", job->path);
        return;
    }
    for (size_t o = 0; o < job->n; o++) {
        fault_result *r = new_result(rs);
        if (!r) {
            rs->failed++;
            continue;
        }
        *r = job->res[o];
        r->set_index = SIZE_MAX;
        if (rs->plan_res && job->model && job->first + o < rs->nplan_faults)
            rs->plan_res[job->first + o] = rs->nres - 1;
        fm_mesh *fault = job->mesh[o];
        if (fault) {
            char **nn = realloc(rs->names, (rs->nfaults + 1) * sizeof *nn);
            if (nn)
                rs->names = nn;
            size_t *sr = realloc(rs->set_res, (rs->nfaults + 1) * sizeof *sr);
            if (sr)
                rs->set_res = sr;
            const fm_mesh **so = realloc(rs->set_orig, (rs->nfaults + 1) * sizeof *so);
            if (so)
                rs->set_orig = so;
            const fm_cad_face **cad =
                nn ? realloc(rs->cad, (rs->ncad + r->ncad + 1) * sizeof *cad) : NULL;
            if (cad)
                rs->cad = cad;
            if (!nn || !sr || !so || !cad || append_fault(rs, fault, job->ids[o]) != FM_OK) {
                r->status = "error";
                r->error = strdup("out of memory");
            } else {
                rs->set_res[rs->nfaults] = rs->nres - 1;
                rs->set_orig[rs->nfaults] = fm_tsurf_mesh(job->objs[o]);
                r->set_index = rs->nfaults;
                rs->names[rs->nfaults++] = r->name;
                for (size_t k = 0; k < r->ncad; k++)
                    rs->cad[rs->ncad++] = r->cad[k];
            }
        }
        free(job->ids ? job->ids[o] : NULL);
        if (!strcmp(r->status, "error")) {
            fprintf(stderr, "faultmesh: %s\n", r->error ? r->error : "out of memory");
            rs->failed++;
        }
        if (!cli->quiet)
            print_fault(r, cli->mesh.size);
        fm_mesh_destroy(fault);
    }
    free(job->res);
    free(job->mesh);
    free(job->ids);
    job->res = NULL;
    job->mesh = NULL;
    job->ids = NULL;
}

/* The pieces of plan curves that fault tag of the set still holds. */
static int set_curve_pieces(const run_state *rs, int32_t tag, fault_result *r)
{
    size_t f = 0, nv = fm_mesh_nvertices(rs->set);
    while (f < rs->nplan_faults && &rs->res[rs->plan_res[f]] != r)
        f++;
    if (f == rs->nplan_faults || !rs->node_vertex)
        return 0;
    int64_t *node = malloc((nv + 1) * sizeof *node);
    if (!node)
        return -1;
    for (size_t v = 0; v < nv; v++)
        node[v] = -1;
    for (size_t k = 0; k < fm_connect_plan_nnodes(rs->plan); k++)
        if (rs->node_vertex[k] >= 0)
            node[rs->node_vertex[k]] = (int64_t)k;
    size_t ne;
    fm_keyed *edge = fm_remesh_shared_edges(rs->set, node, tag, &ne);
    int rc = edge ? curve_pieces(rs->plan, f, r->sheets, edge, ne, r) : -1;
    free(node);
    free(edge);
    return rc;
}

/* Where two faults still meet away from their shared curves (fm_carve.h),
 * one of them gives way. A fault that lost triangles is measured again on
 * what is left (the originals must still be there). */
static void carve_set(const remesh_cli *cli, run_state *rs)
{
    fm_error err;
    fm_error_clear(&err);
    if (fm_carve_crossings(rs->set, 2 * cli->mesh.size, rs->sheet, &rs->carve, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: faults that cross each other are left so: %s\n",
                err.message);
        return;
    }
    for (size_t k = 0; k < fm_carve_npairs(rs->carve); k++) {
        const fm_carve_pair *p = fm_carve_pair_at(rs->carve, k);
        fault_result *r = &rs->res[rs->set_res[p->fault[p->yielded]]];
        if (r->carved)
            continue; /* measured already */
        int32_t tag = p->fault[p->yielded];
        size_t before = r->q.triangles;
        double area = r->q.area;
        fm_closest_tree *tree = fm_closest_tree_create(rs->set_orig[tag], &err);
        if (!tree || fm_check_quality(rs->set, tag, cli->mesh.size, &r->q) != FM_OK ||
            fm_check_fidelity(rs->set, tag, rs->set_orig[tag], tree, &r->fid) != FM_OK)
            fprintf(stderr, "faultmesh: %s: out of memory measuring it again\n", r->name);
        fm_closest_tree_destroy(tree);
        r->carved = before - r->q.triangles;
        r->carved_area = area - r->q.area;
        if (set_curve_pieces(rs, tag, r))
            fprintf(stderr, "faultmesh: %s: out of memory measuring it again\n", r->name);
    }
}

static void json_carve(fm_json *j, const run_state *rs)
{
    if (!rs->carve)
        return;
    fm_json_kv_int(j, "carved_triangles", (int64_t)fm_carve_removed(rs->carve));
    fm_json_kv_int(j, "carved_slivers_at_notches", (int64_t)fm_carve_slivers(rs->carve));
    fm_json_key(j, "carved");
    fm_json_begin_array(j);
    for (size_t k = 0; k < fm_carve_npairs(rs->carve); k++) {
        const fm_carve_pair *p = fm_carve_pair_at(rs->carve, k);
        fm_json_begin_object(j);
        fm_json_key(j, "faults");
        fm_json_begin_array(j);
        for (int s = 0; s < 2; s++)
            fm_json_string(j, rs->res[rs->set_res[p->fault[s]]].name);
        fm_json_end_array(j);
        fm_json_kv_int(j, "triangle_pairs_met", (int64_t)p->contacts);
        fm_json_kv_string(j, "removed_from", rs->res[rs->set_res[p->fault[p->yielded]]].name);
        fm_json_kv_int(j, "triangles_removed", (int64_t)p->removed);
        fm_json_kv_number(j, "area_removed_m2", p->area);
        fm_json_kv_string(j, "reason",
                          "the two meshes ran through each other away from any curve they "
                          "share; the one losing the smaller share of its area gives way there");
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
}

static void json_quality(fm_json *j, const fault_result *r, double H)
{
    const fm_quality *q = &r->q;
    fm_json_key(j, "quality");
    fm_json_begin_object(j);
    fm_json_kv_number(j, "min_angle_deg", q->angle_min);
    fm_json_kv_number(j, "mean_min_angle_deg", q->angle_mean);
    fm_json_kv_int(j, "triangles_below_30_deg", (int64_t)q->below_30);
    fm_json_kv_int(j, "triangles_below_20_deg", (int64_t)q->below_20);
    fm_json_kv_int(j, "triangles_below_20_deg_at_sharp_corners", (int64_t)q->below_20_forced);
    fm_json_kv_int(j, "sharp_corners", (int64_t)q->sharp_corners);
    fm_json_end_object(j);
    fm_json_key(j, "size");
    fm_json_begin_object(j);
    fm_json_kv_number(j, "target_m", H);
    fm_json_kv_int(j, "edges", (int64_t)q->edges);
    fm_json_kv_int(j, "edges_within_0.7_1.4", (int64_t)q->edges_in_band);
    fm_json_kv_number(j, "edge_min_m", q->edge_min);
    fm_json_kv_number(j, "edge_p05_m", q->edge_p05);
    fm_json_kv_number(j, "edge_median_m", q->edge_median);
    fm_json_kv_number(j, "edge_p95_m", q->edge_p95);
    fm_json_kv_number(j, "edge_max_m", q->edge_max);
    fm_json_end_object(j);
}

static void json_fault(fm_json *j, const fault_result *r, double H, const sim_attrs *sa)
{
    fm_json_begin_object(j);
    fm_json_kv_string(j, "file", r->file ? r->file : "");
    if (r->name)
        fm_json_kv_string(j, "name", r->name);
    fm_json_kv_string(j, "status", r->status ? r->status : "error");
    if (r->error)
        fm_json_kv_string(j, "error", r->error);
    if (r->status && !strcmp(r->status, "ok")) {
        fm_json_kv_int(j, "sheets", (int64_t)r->sheets);
        fm_json_kv_int(j, "triangles", (int64_t)r->q.triangles);
        fm_json_kv_int(j, "nodes", (int64_t)r->q.nodes);
        if (r->carved) {
            fm_json_kv_int(j, "carved_triangles", (int64_t)r->carved);
            fm_json_kv_number(j, "carved_area_m2", r->carved_area);
        }
        char w[2][160];
        int nw = fault_warnings(r, w);
        fm_json_key(j, "warnings");
        fm_json_begin_array(j);
        for (int k = 0; k < nw; k++)
            fm_json_string(j, w[k]);
        fm_json_end_array(j);
        if (r->join_error)
            fm_json_kv_string(j, "join_error", r->join_error);
        fm_json_kv_number(j, "area_m2", r->q.area);
        json_quality(j, r, H);
        fm_json_key(j, "fidelity");
        fm_json_begin_object(j);
        fm_json_kv_number(j, "node_to_original_rms_m", r->fid.rms);
        fm_json_kv_number(j, "node_to_original_max_m", r->fid.max);
        /* Nodes farther than 100 m whose nearest original point is on
         * (within 100 m of) its outline lie past the original's edge (a
         * fault extended over a closed gap): their largest distance is
         * reported apart from that of the nodes over its inside, so the
         * fidelity proper can be told from the extent of what was filled
         * beyond the edge. */
        fm_json_kv_number(j, "inside_outline_max_m", r->fid.inside_max);
        fm_json_kv_int(j, "inside_outline_nodes_over_100_m", (int64_t)r->fid.inside_over);
        fm_json_kv_number(j, "beyond_outline_max_m", r->fid.beyond_max);
        fm_json_kv_int(j, "beyond_outline_nodes_over_100_m", (int64_t)r->fid.beyond_nodes);
        fm_json_kv_number(j, "fitted_area_m2", r->fitted_area);
        fm_json_kv_number(j, "coverage", r->fitted_area > 0 ? r->q.area / r->fitted_area : 0);
        fm_json_end_object(j);
        fm_json_key(j, "top");
        fm_json_begin_object(j);
        fm_json_kv_bool(j, "cut", r->ms.cut);
        fm_json_kv_int(j, "sea_level_nodes", (int64_t)r->ms.level_points);
        fm_json_kv_number(j, "z_max_m", r->q.zmax);
        fm_json_kv_int(j, "nodes_lowered_to_sea_level", (int64_t)r->ms.clamped);
        fm_json_kv_number(j, "largest_lowering_m", r->ms.clamp_max);
        fm_json_kv_number(j, "extended_m", r->ms.extended);
        fm_json_end_object(j);
        fm_json_key(j, "time_s");
        fm_json_begin_object(j);
        fm_json_kv_number(j, "fit", r->t_fit);
        fm_json_kv_number(j, "mesh", r->t_mesh);
        fm_json_kv_number(j, "check", r->t_check);
        fm_json_end_object(j);
    }
    if (sa && r->set_index < sa->nfaults)
        sim_json_fault(j, sa, r->set_index);
    fm_json_end_object(j);
}

/* Junction i as meshed: the plan's type, unless the mesher could not fit
 * its curve into one of its sheets (*why then says so and *which names
 * the fault; else *which is SIZE_MAX). */
static fm_junction_type junction_outcome(const run_state *rs, const fm_connect_junction *jn,
                                         const char **why, size_t *which)
{
    *why = jn->reason;
    *which = SIZE_MAX;
    if (jn->curve < 0)
        return jn->type;
    for (int s = 0; s < 2; s++) {
        const fault_result *r = &rs->res[rs->plan_res[jn->fault[s]]];
        int left_out = 0;
        for (size_t k = 0; k < r->ndropped; k++)
            left_out |= r->dropped_curves[k] == (size_t)jn->curve;
        if (left_out) {
            *why = "the curve could not be fitted into the outline of one of the sheets";
            *which = jn->fault[s];
            return FM_JUNCTION_UNJOINED;
        }
    }
    if (jn->type != FM_JUNCTION_UNJOINED &&
        !share_piece(&rs->res[rs->plan_res[jn->fault[0]]], &rs->res[rs->plan_res[jn->fault[1]]],
                     (size_t)jn->curve)) {
        /* each holds pieces of it, but none the same: another curve of one
         * of them cut the rest away, or the last guard did */
        int carved = rs->res[rs->plan_res[jn->fault[0]]].carved ||
                     rs->res[rs->plan_res[jn->fault[1]]].carved;
        *why = carved ? "the two sheets keep no common piece of the curve: it was carved away "
                        "where one of them ran through another fault"
                      : "the two sheets keep no common piece of the curve";
        *which = jn->fault[0];
        return FM_JUNCTION_UNJOINED;
    }
    return jn->type;
}

static void json_connect(fm_json *j, const remesh_cli *cli, const run_state *rs, size_t count[4])
{
    memset(count, 0, 4 * sizeof *count);
    fm_json_key(j, "connect");
    fm_json_begin_object(j);
    fm_json_kv_bool(j, "enabled", cli->connect && rs->plan);
    fm_json_kv_number(j, "join_distance_m", cli->join);
    if (!rs->plan) {
        fm_json_end_object(j);
        return;
    }
    const fm_connect_plan_stats *ps = fm_connect_plan_get_stats(rs->plan);
    fm_json_kv_int(j, "sheet_pairs_within_join_distance", (int64_t)ps->pairs);
    fm_json_kv_int(j, "near_duplicates_given_up", (int64_t)ps->duplicates);
    fm_json_kv_int(j, "shared_nodes", (int64_t)fm_connect_plan_nnodes(rs->plan));
    fm_json_key(j, "junctions");
    fm_json_begin_array(j);
    for (size_t i = 0; i < fm_connect_plan_njunctions(rs->plan); i++) {
        const fm_connect_junction *jn = fm_connect_plan_junction(rs->plan, i);
        const char *why;
        size_t which;
        fm_junction_type t = junction_outcome(rs, jn, &why, &which);
        count[t]++;
        fm_json_begin_object(j);
        fm_json_key(j, "faults");
        fm_json_begin_array(j);
        for (int s = 0; s < 2; s++)
            fm_json_string(j, rs->res[rs->plan_res[jn->fault[s]]].name);
        fm_json_end_array(j);
        fm_json_key(j, "sheets");
        fm_json_begin_array(j);
        for (int s = 0; s < 2; s++)
            fm_json_int(j, (int64_t)jn->sheet[s]);
        fm_json_end_array(j);
        fm_json_kv_string(j, "type", fm_junction_type_name(t));
        /* how each sheet meets the curve, whatever was made of it: tells a
         * reader which fault was meant to end on the other (pairs that never
         * meet have no curve and no roles) */
        if (jn->length > 0) {
            fm_json_key(j, "roles");
            fm_json_begin_array(j);
            for (int s = 0; s < 2; s++)
                fm_json_string(j, jn->role[s] == FM_CONNECT_THROUGH     ? "through"
                                  : jn->role[s] == FM_CONNECT_OVERSHOOT ? "overshoot"
                                                                        : "gap");
            fm_json_end_array(j);
        }
        /* a sheet stopped short of the other lost its flap past it too */
        int cleared = jn->clearance > 0 && which == SIZE_MAX;
        fm_json_kv_number(j, "gap_closed_m", t == FM_JUNCTION_UNJOINED ? 0 : jn->gap);
        fm_json_kv_number(j, "overshoot_trimmed_m",
                          t != FM_JUNCTION_UNJOINED ? jn->overshoot
                          : cleared                 ? jn->overshoot + jn->clearance
                                                    : 0);
        fm_json_kv_number(j, "curve_length_m", jn->length);
        fm_json_kv_number(j, "min_crossing_angle_deg", jn->min_angle);
        if (jn->distance > 0)
            fm_json_kv_number(j, "surface_distance_m", jn->distance);
        if (cleared) {
            fm_json_kv_number(j, "gap_left_m", jn->clearance);
            fm_json_kv_string(j, "stops_short",
                              rs->res[rs->plan_res[jn->fault[jn->short_side]]].name);
        }
        /* faults that were to end at the curve but run on past it */
        int kept[2] = {0, 0};
        for (int s = 0; s < 2 && t != FM_JUNCTION_UNJOINED; s++) {
            const fault_result *fr = &rs->res[rs->plan_res[jn->fault[s]]];
            for (size_t k = 0; k < fr->nthrough; k++)
                kept[s] |= fr->through_curves[k] == (size_t)jn->curve;
        }
        if (kept[0] || kept[1]) {
            fm_json_key(j, "flap_kept");
            fm_json_begin_array(j);
            for (int s = 0; s < 2; s++)
                if (kept[s])
                    fm_json_string(j, rs->res[rs->plan_res[jn->fault[s]]].name);
            fm_json_end_array(j);
        }
        if (why) {
            char msg[600];
            if (which != SIZE_MAX)
                snprintf(msg, sizeof msg, "%s (%s)", why, rs->res[rs->plan_res[which]].name);
            fm_json_kv_string(j, "reason", which != SIZE_MAX ? msg : why);
        }
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    fm_json_kv_int(j, "crossing", (int64_t)count[FM_JUNCTION_CROSSING]);
    fm_json_kv_int(j, "T", (int64_t)count[FM_JUNCTION_T]);
    fm_json_kv_int(j, "corner", (int64_t)count[FM_JUNCTION_CORNER]);
    fm_json_kv_int(j, "unjoined", (int64_t)count[FM_JUNCTION_UNJOINED]);
    json_carve(j, rs);
    fm_json_end_object(j);
}

static fm_status write_report(const remesh_cli *cli, const run_state *rs, const sim_attrs *sa,
                              fm_error *err)
{
    size_t n = strlen(cli->dir) + 32;
    char *path = malloc(n);
    if (!path)
        return fm_error_set(err, FM_ERR_NOMEM, cli->dir, 0, "out of memory");
    snprintf(path, n, "%s/report.json", cli->dir);
    fm_atomic_file *af = fm_atomic_open(path, err);
    free(path);
    if (!af)
        return err->code;
    fm_json j;
    fm_json_init(&j, fm_atomic_stream(af));
    fm_json_begin_object(&j);
    fm_json_kv_string(&j, "faultmesh_version", FM_VERSION_STRING);
    fm_json_key(&j, "options");
    fm_json_begin_object(&j);
    fm_json_kv_number(&j, "size_m", cli->mesh.size);
    fm_json_kv_string(&j, "top", cli->mesh.top == FM_TOP_CUT    ? "cut"
                                 : cli->mesh.top == FM_TOP_KEEP ? "keep"
                                                                : "extend");
    if (cli->mesh.top == FM_TOP_EXTEND)
        fm_json_kv_number(&j, "top_extend_m", cli->mesh.top_extend);
    fm_json_kv_string(&j, "crs", rs->crs);
    /* where it came from: --crs, the inputs' coordinate-system block, or
     * the CFM's default */
    fm_json_kv_string(&j, "crs_source", rs->crs_source);
    fm_json_kv_string(&j, "msh_tags", fm_msh_tags_name(cli->msh_tags));
    fm_json_end_object(&j);
    fm_json_key(&j, "faults");
    fm_json_begin_array(&j);
    size_t tris = 0, below30 = 0, below20 = 0, forced = 0, edges = 0, band = 0, ok = 0, warned = 0;
    double worst_dist = 0, zmax = -INFINITY;
    for (size_t i = 0; i < rs->nres; i++) {
        const fault_result *r = &rs->res[i];
        json_fault(&j, r, cli->mesh.size, sa);
        if (!r->status || strcmp(r->status, "ok"))
            continue;
        ok++;
        char w[2][160];
        warned += fault_warnings(r, w) > 0;
        tris += r->q.triangles;
        below30 += r->q.below_30;
        below20 += r->q.below_20;
        forced += r->q.below_20_forced;
        edges += r->q.edges;
        band += r->q.edges_in_band;
        worst_dist = fmax(worst_dist, r->fid.max);
        zmax = fmax(zmax, r->q.zmax);
    }
    fm_json_end_array(&j);
    size_t jcount[4];
    json_connect(&j, cli, rs, jcount);
    if (sa)
        sim_json_summary(&j, &cli->sim, sa);
    fm_json_key(&j, "summary");
    fm_json_begin_object(&j);
    fm_json_kv_int(&j, "faults", (int64_t)rs->nres);
    fm_json_kv_int(&j, "meshed", (int64_t)ok);
    fm_json_kv_int(&j, "failed", rs->failed);
    fm_json_kv_int(&j, "meshed_with_warnings", (int64_t)warned);
    fm_json_kv_int(&j, "triangles", (int64_t)tris);
    fm_json_kv_int(&j, "triangles_below_30_deg", (int64_t)below30);
    fm_json_kv_int(&j, "triangles_below_20_deg", (int64_t)below20);
    fm_json_kv_int(&j, "triangles_below_20_deg_at_sharp_corners", (int64_t)forced);
    fm_json_kv_int(&j, "edges", (int64_t)edges);
    fm_json_kv_int(&j, "edges_within_0.7_1.4", (int64_t)band);
    fm_json_kv_number(&j, "node_to_original_max_m", worst_dist);
    fm_json_kv_number(&j, "z_max_m", ok ? zmax : 0);
    fm_json_kv_number(&j, "time_fit_s", rs->time[0]);
    fm_json_kv_number(&j, "time_connect_s", rs->time[1]);
    fm_json_kv_number(&j, "time_mesh_s", rs->time[2]);
    fm_json_end_object(&j);
    fm_json_end_object(&j);
    if (!cli->quiet && rs->plan)
        printf("junctions: %zu crossing, %zu T, %zu corner, %zu unjoined; %zu near-duplicate "
               "faults given up; %zu shared nodes\n",
               jcount[0], jcount[1], jcount[2], jcount[3],
               fm_connect_plan_get_stats(rs->plan)->duplicates,
               fm_connect_plan_nnodes(rs->plan));
    if (!cli->quiet)
        printf("faults %zu, meshed %zu (%zu with warnings), failed %ld; triangles %zu, below 30 deg "
               "%.3f%%, below 20 deg %zu (%zu at sharp corners), edges in [0.7, 1.4] H %.2f%%, "
               "worst node distance %.1f m\n",
               rs->nres, ok, warned, rs->failed, tris,
               tris ? 100.0 * (double)below30 / (double)tris : 0,
               below20, forced, edges ? 100.0 * (double)band / (double)edges : 0, worst_dist);
    return fm_atomic_commit(af, err);
}

/* Whether edge p-q is an edge of a triangle of fault f (sides: the set's,
 * fm_mesh_sides; tag: the set's triangle tags). */
static int fault_has_edge(const fm_keyed *side, size_t n, const int32_t *tag, int32_t p,
                          int32_t q, size_t f)
{
    uint64_t key = fm_edge_key((uint64_t)p, (uint64_t)q);
    for (size_t i = fm_keyed_lower_bound(side, n, key); i < n && side[i].key == key; i++)
        if ((size_t)tag[side[i].index] == f)
            return 1;
    return 0;
}

/* One node set per junction made: the nodes of its curve (as either
 * sheet sees it) on an edge of both faults' triangles in the set, so that
 * every node is one of both faults, named after the junction's index in
 * report.json and its faults. A junction made whose faults keep no such
 * edge has no set. Arrays malloc'ed (free_junction_sets). */
typedef struct junction_sets {
    fm_faultset_nodeset *set;
    char **names;
    int32_t **vertices;
    size_t n;
} junction_sets;

static void free_junction_sets(junction_sets *js)
{
    for (size_t i = 0; i < js->n; i++) {
        free(js->names[i]);
        free(js->vertices[i]);
    }
    free(js->set);
    free(js->names);
    free(js->vertices);
    memset(js, 0, sizeof *js);
}

/* Junction i's node set into js, if it is made and has one; -1 when out
 * of memory. */
static int junction_set(const run_state *rs, size_t i, const fm_keyed *edges, size_t nedges,
                        junction_sets *js)
{
    const fm_connect_junction *jn = fm_connect_plan_junction(rs->plan, i);
    const char *why;
    size_t which;
    if (junction_outcome(rs, jn, &why, &which) == FM_JUNCTION_UNJOINED || jn->curve < 0)
        return 0;
    const fault_result *ra = &rs->res[rs->plan_res[jn->fault[0]]];
    const fault_result *rb = &rs->res[rs->plan_res[jn->fault[1]]];
    size_t fa = ra->set_index, fb = rb->set_index;
    if (fa == SIZE_MAX || fb == SIZE_MAX)
        return 0;
    const int32_t *tag = fm_mesh_tags(rs->set);
    const fm_connect_shared *c[2] = {NULL, NULL};
    for (int side = 0; side < 2; side++) {
        const fm_connect_shared *sh = NULL;
        size_t ns = fm_connect_plan_sheet(rs->plan, jn->fault[side], jn->sheet[side], &sh);
        for (size_t k = 0; k < ns && !c[side]; k++)
            if (sh[k].curve == (size_t)jn->curve)
                c[side] = &sh[k];
    }
    size_t cap = 2 * ((c[0] ? c[0]->n : 0) + (c[1] ? c[1]->n : 0));
    if (!cap)
        return 0;
    int32_t *v = malloc(cap * sizeof *v);
    if (!v)
        return -1;
    size_t nv = 0;
    for (int side = 0; side < 2; side++)
        for (size_t k = 0; c[side] && k + 1 < c[side]->n; k++) {
            int32_t p = rs->node_vertex[c[side]->node[k]];
            int32_t q = rs->node_vertex[c[side]->node[k + 1]];
            if (p < 0 || q < 0 || !fault_has_edge(edges, nedges, tag, p, q, fa) ||
                !fault_has_edge(edges, nedges, tag, p, q, fb))
                continue;
            v[nv++] = p;
            v[nv++] = q;
        }
    size_t len = strlen(ra->name) + strlen(rb->name) + 48;
    char *name = nv ? malloc(len) : NULL;
    if (!name) {
        free(v);
        return nv ? -1 : 0;
    }
    snprintf(name, len, "junction %zu: %s / %s", i, ra->name, rb->name);
    js->names[js->n] = name;
    js->vertices[js->n] = v;
    js->set[js->n] = (fm_faultset_nodeset){name, v, nv};
    js->n++;
    return 0;
}

static int junction_sets_make(const run_state *rs, junction_sets *js)
{
    memset(js, 0, sizeof *js);
    if (!rs->plan || !rs->node_vertex)
        return 0;
    size_t nj = fm_connect_plan_njunctions(rs->plan), nedges = 0;
    js->set = calloc(nj ? nj : 1, sizeof *js->set);
    js->names = calloc(nj ? nj : 1, sizeof *js->names);
    js->vertices = calloc(nj ? nj : 1, sizeof *js->vertices);
    fm_keyed *edges = fm_mesh_sides(rs->set, &nedges);
    int rc = js->set && js->names && js->vertices && edges ? 0 : -1;
    for (size_t i = 0; rc == 0 && i < nj; i++)
        rc = junction_set(rs, i, edges, nedges, js);
    free(edges);
    return rc;
}

/* The fault set in every format, the files shared among cli->jobs threads
 * (the bytes do not depend on how many); the simulator files after them.
 * *sa gets the element attributes (cleared when there are no faults). */
static fm_status write_set(const remesh_cli *cli, const run_state *rs, sim_attrs *sa,
                           fm_error *err)
{
    memset(sa, 0, sizeof *sa);
    if (!rs->nfaults)
        return FM_OK;
    junction_sets js = {0};
    int32_t *tags = malloc(rs->nfaults * sizeof *tags);
    char **pnames = NULL;
    fm_status st = FM_OK;
    if (!tags || junction_sets_make(rs, &js))
        st = fm_error_set(err, FM_ERR_NOMEM, cli->dir, 0, "out of memory");
    if (st == FM_OK)
        st = fm_msh_tags_make(cli->msh_tags, (const char *const *)rs->names, rs->nfaults, tags,
                              &pnames, err);
    fm_faultset fs = {.mesh = rs->set,
                      .names = (const char *const *)rs->names,
                      .nfaults = rs->nfaults,
                      .physical_tags = tags,
                      .physical_names = (const char *const *)pnames,
                      .msh_dense_nodes = cli->msh_tags == FM_MSH_TAGS_TANDEM,
                      .crs = rs->crs,
                      .nodesets = js.set,
                      .nnodesets = js.n};
    if (st == FM_OK && sim_attrs_make(&cli->sim, &fs, sa) != 0)
        st = fm_error_set(err, FM_ERR_NOMEM, cli->dir, 0, "out of memory");
    /* the element attributes, and which sheet of its fault a triangle is on
     * (the repair stage's sheets: the parts of a branching fault) */
    fm_vtu_array cells[sizeof sa->cells / sizeof *sa->cells + 1];
    memcpy(cells, sa->cells, sizeof sa->cells);
    cells[sizeof sa->cells / sizeof *sa->cells] =
        (fm_vtu_array){"sheet", FM_VTU_INT32, 1, rs->sheet};
    fs.cell_data = cells;
    fs.ncell_data = sizeof cells / sizeof *cells;
    size_t n = strlen(cli->dir) + 32;
    char *path = st == FM_OK ? malloc(5 * n) : NULL;
    if (st == FM_OK && !path)
        st = fm_error_set(err, FM_ERR_NOMEM, cli->dir, 0, "out of memory");
    if (st == FM_OK) {
        const char *ext[5] = {"vtu", "msh", "stl", "obj", "exo"};
        for (int k = 0; k < 5; k++)
            snprintf(path + (size_t)k * n, n, "%s/mesh.%s", cli->dir, ext[k]);
        fm_faultset_outputs out = {.vtu = path,
                                   .msh = path + n,
                                   .stl = path + 2 * n,
                                   .obj = path + 3 * n,
                                   .exo = path + 4 * n,
                                   .msh_version = cli->msh,
                                   .tsurf_dir = cli->dir};
        st = fm_faultset_write_all(&fs, &out, cli->jobs, err);
    }
    if (st == FM_OK) {
        snprintf(path, n, "%s/model.igs", cli->dir);
        st = fm_cad_write_iges(path, rs->cad, rs->ncad, rs->crs, err);
    }
    free(path);
    if (st == FM_OK)
        st = sim_write(&cli->sim, &fs, sa, cli->dir, err);
    free(tags);
    fm_faultset_free_file_names(pnames, rs->nfaults);
    free_junction_sets(&js);
    return st;
}

/* The junction plan over every fitted fault (objects in input order);
 * faults it gives up as near-duplicates are marked "dropped". NULL when
 * there is nothing to join or the plan failed (reported; the faults are
 * then meshed unconnected). */
static fm_connect_plan *make_plan(const remesh_cli *cli, file_job *jobs, size_t njobs,
                                  run_state *rs)
{
    size_t n = 0;
    for (size_t i = 0; i < njobs; i++) {
        jobs[i].first = n;
        n += jobs[i].model ? jobs[i].n : 0;
    }
    const fm_model **models = calloc(n + 1, sizeof *models);
    fault_result **res = calloc(n + 1, sizeof *res);
    rs->plan_res = calloc(n + 1, sizeof *rs->plan_res);
    if (!models || !res || !rs->plan_res) {
        free(models);
        free(res);
        return NULL;
    }
    rs->nplan_faults = n;
    for (size_t i = 0; i < njobs; i++)
        for (size_t o = 0; jobs[i].model && o < jobs[i].n; o++) {
            models[jobs[i].first + o] = jobs[i].model[o];
            res[jobs[i].first + o] = &jobs[i].res[o];
        }
    fm_connect_plan_options po;
    fm_connect_plan_options_default(&po);
    po.distance = cli->join;
    po.size = cli->mesh.size;
    po.cut = cli->mesh.top != FM_TOP_KEEP;
    po.sea_level = cli->mesh.sea_level;
    po.nthreads = cli->jobs;
    po.duplicates.keep = cli->keep;
    fm_connect_plan *plan = NULL;
    fm_error err;
    fm_error_clear(&err);
    if (fm_connect_plan_build(models, n, &po, &plan, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: connecting faults failed, meshing them unconnected: %s\n",
                err.message);
        free(models);
        free(res);
        return NULL;
    }
    free(models);
    for (size_t f = 0; f < n; f++) {
        const fm_connect_duplicate *d;
        if (!fm_connect_plan_dropped(plan, f, &d))
            continue;
        fault_result *r = res[f];
        char msg[512];
        snprintf(msg, sizeof msg,
                 "near-duplicate of %s (%.0f%% of its area within %.0f m of it); that one is "
                 "kept (the %s of the two)",
                 d ? res[d->kept]->name : "another fault", d ? 100 * d->share[0] : 0,
                 po.duplicates.tolerance,
                 po.duplicates.keep == FM_CONNECT_KEEP_LARGER ? "larger" : "smaller");
        r->status = "dropped";
        r->error = strdup(msg);
    }
    free(res);
    return plan;
}

/* A junction is made only when both sheets take its curve. Faults are
 * meshed each on its own, so a curve one sheet could not fit is still in
 * the other's mesh: that sheet trimmed its flap or filled its gap to a
 * curve it shares with nobody (San Pedro Escarpment YngB: filled 1 km past
 * its edge towards a curve F could not take). Those faults are meshed
 * again without such curves, until no curve a mesh took was dropped by
 * another (the set of dropped curves only grows, so this ends). */
static void settle_curves(const remesh_cli *cli, const fm_connect_plan *plan, file_job *jobs,
                          size_t njobs)
{
    size_t nc = fm_connect_plan_get_stats(plan)->curves;
    unsigned char *excluded = calloc(nc + 1, 1);
    if (!excluded)
        return;
    for (;;) {
        size_t added = 0, again = 0;
        for (size_t i = 0; i < njobs; i++)
            for (size_t o = 0; jobs[i].res && o < jobs[i].n; o++) {
                const fault_result *r = &jobs[i].res[o];
                for (size_t k = 0; k < r->ndropped; k++)
                    if (r->dropped_curves[k] < nc && !excluded[r->dropped_curves[k]]) {
                        excluded[r->dropped_curves[k]] = 1;
                        added++;
                    }
            }
        if (!added)
            break;
        for (size_t i = 0; i < njobs; i++) {
            file_job *job = &jobs[i];
            if (!job->res || !job->model)
                continue;
            for (size_t o = 0; o < job->n; o++) {
                const fault_result *r = &job->res[o];
                int redo = 0;
                for (size_t k = 0; k < r->nused && !redo; k++)
                    redo = r->used_curves[k] < nc && excluded[r->used_curves[k]];
                if (!redo || !job->model[o] || !r->status || strcmp(r->status, "ok"))
                    continue;
                if (!job->redo)
                    job->redo = calloc(job->n, 1);
                if (!job->redo)
                    continue;
                job->redo[o] = 1;
                again++;
            }
        }
        if (!again)
            break;
        run_jobs(cli, plan, 2, excluded, jobs, njobs);
        for (size_t i = 0; i < njobs; i++)
            if (jobs[i].redo)
                memset(jobs[i].redo, 0, jobs[i].n);
    }
    free(excluded);
}

/* The CRS of the run: --crs, else the one the inputs name (all that name
 * one must name the same), else the CFM's. -1 after saying why when the
 * inputs disagree or memory runs out. */
static int settle_crs(const remesh_cli *cli, const file_job *jobs, size_t njobs, run_state *rs)
{
    const char *crs = cli->crs, *from = NULL;
    rs->crs_source = "option";
    if (!crs) {
        for (size_t i = 0; i < njobs; i++)
            for (size_t o = 0; o < jobs[i].nobj; o++) {
                const char *c = fm_tsurf_crs_code(jobs[i].objs[o]);
                if (!c)
                    continue;
                if (crs && strcmp(c, crs) != 0) {
                    fprintf(stderr,
                            "faultmesh: the inputs name different coordinate systems (%s in "
                            "%s, %s in %s): say which with --crs\n",
                            crs, from, c, jobs[i].path);
                    return -1;
                }
                crs = c;
                from = jobs[i].path;
            }
        rs->crs_source = crs ? "input" : "default";
        if (!crs)
            crs = "EPSG:26711";
    }
    fm_error err;
    fm_error_clear(&err);
    if (cli->sim.eqsim == FM_EQSIM_SPHERICAL && fm_eqsim_check_crs(crs, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s; give --crs, or --eqsim-coords utm\n", err.message);
        return -1;
    }
    rs->crs = strdup(crs);
    return rs->crs ? 0 : -1;
}

static int run(const remesh_cli *cli, char **files, long nfiles)
{
    fm_error err;
    fm_error_clear(&err);
    if (fm_mkdir_p(cli->dir, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        return FM_EXIT_FAILURES;
    }
    run_state rs = {0};
    rs.set = fm_mesh_create();
    if (!rs.set)
        return FM_EXIT_FAILURES;
    file_job *jobs = calloc(nfiles > 0 ? (size_t)nfiles : 1, sizeof *jobs);
    if (!jobs) {
        fm_mesh_destroy(rs.set);
        return FM_EXIT_FAILURES;
    }
    for (long i = 0; i < nfiles; i++)
        jobs[i].path = files[i];
    double t0 = fm_clock_seconds();
    run_jobs(cli, NULL, 0, NULL, jobs, (size_t)nfiles);
    if (settle_crs(cli, jobs, (size_t)nfiles, &rs)) {
        for (long i = 0; i < nfiles; i++)
            abandon_job(&jobs[i]);
        free(jobs);
        fm_mesh_destroy(rs.set);
        return FM_EXIT_FAILURES;
    }
    double t1 = fm_clock_seconds();
    fm_connect_plan *plan = NULL;
    if (cli->connect)
        plan = make_plan(cli, jobs, (size_t)nfiles, &rs);
    double t2 = fm_clock_seconds();
    run_jobs(cli, plan, 1, NULL, jobs, (size_t)nfiles);
    if (plan)
        settle_curves(cli, plan, jobs, (size_t)nfiles);
    double t3 = fm_clock_seconds();
    rs.plan = plan;
    if (plan) {
        size_t nn = fm_connect_plan_nnodes(plan);
        rs.node_vertex = malloc((nn + 1) * sizeof *rs.node_vertex);
        for (size_t k = 0; rs.node_vertex && k < nn; k++)
            rs.node_vertex[k] = -1;
    }
    for (long i = 0; i < nfiles; i++)
        merge_job(cli, &jobs[i], &rs);
    if (plan && cli->carve)
        carve_set(cli, &rs);
    for (long i = 0; i < nfiles; i++)
        release_job(&jobs[i]);
    free(jobs);
    rs.time[0] = t1 - t0;
    rs.time[1] = t2 - t1;
    rs.time[2] = t3 - t2;
    sim_attrs sa;
    fm_status st = write_set(cli, &rs, &sa, &err);
    if (st == FM_OK)
        st = write_report(cli, &rs, rs.nfaults ? &sa : NULL, &err);
    sim_attrs_free(&sa);
    if (st != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        rs.failed++;
    }
    for (size_t i = 0; i < rs.nres; i++) {
        free(rs.res[i].file);
        free(rs.res[i].name);
        free(rs.res[i].error);
        free(rs.res[i].join_failed);
        free(rs.res[i].join_error);
        free(rs.res[i].dropped_curves);
        free(rs.res[i].through_curves);
        free(rs.res[i].used_curves);
        free(rs.res[i].curve_pieces);
        for (size_t k = 0; k < rs.res[i].ncad; k++)
            fm_cad_face_destroy(rs.res[i].cad[k]);
        free(rs.res[i].cad);
    }
    free(rs.cad);
    free(rs.res);
    free(rs.set_res);
    free(rs.set_orig);
    free(rs.sheet);
    fm_carve_result_destroy(rs.carve);
    free(rs.names);
    free(rs.node_vertex);
    free(rs.plan_res);
    free(rs.crs);
    fm_connect_plan_destroy(plan);
    fm_mesh_destroy(rs.set);
    return rs.failed ? FM_EXIT_FAILURES : FM_EXIT_OK;
}

/* Options shared by remesh and demo; returns 1 if consumed, -1 on error,
 * 0 if not one of them. */
static int mesh_option(int argc, char **argv, int *i, remesh_cli *cli)
{
    const char *a = argv[*i], *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    int sc = sim_cli_option(argc, argv, i, &cli->sim);
    if (sc != 0)
        return sc;
    if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
        if (!val)
            return -1;
        cli->dir = val;
    } else if (!strcmp(a, "--size")) {
        if (fm_parse_double(a, val, &cli->mesh.size) || !(cli->mesh.size > 0))
            return -1;
    } else if (!strcmp(a, "--top")) {
        if (val && !strcmp(val, "cut")) {
            cli->mesh.top = FM_TOP_CUT;
        } else if (val && !strcmp(val, "keep")) {
            cli->mesh.top = FM_TOP_KEEP;
        } else if (val && !strcmp(val, "extend")) {
            cli->mesh.top = FM_TOP_EXTEND;
            (*i)++;
            const char *d = *i + 1 < argc ? argv[*i + 1] : NULL;
            if (fm_parse_double("--top extend", d, &cli->mesh.top_extend))
                return -1;
        } else {
            fprintf(stderr, "faultmesh: --top takes cut, keep or extend D\n");
            return -1;
        }
    } else if (!strcmp(a, "--msh-version")) {
        if (val && !strcmp(val, "4.1"))
            cli->msh = FM_MSH_41;
        else if (val && !strcmp(val, "2.2"))
            cli->msh = FM_MSH_22;
        else {
            fprintf(stderr, "faultmesh: --msh-version takes 4.1 or 2.2\n");
            return -1;
        }
        cli->msh_version_given = 1;
    } else if (!strcmp(a, "--msh-tags")) {
        int found = 0;
        for (int c = FM_MSH_TAGS_DEFAULT; c <= FM_MSH_TAGS_PYLITH && !found; c++)
            if (val && !strcmp(val, fm_msh_tags_name((fm_msh_tags)c))) {
                cli->msh_tags = (fm_msh_tags)c;
                found = 1;
            }
        if (!found) {
            fprintf(stderr, "faultmesh: --msh-tags takes default, tandem, seissol or pylith\n");
            return -1;
        }
    } else if (!strcmp(a, "--crs")) {
        if (!val)
            return -1;
        cli->crs = val;
    } else if (!strcmp(a, "--jobs") || !strcmp(a, "-j")) {
        size_t n;
        if (fm_parse_size(a, val, &n) || n < 1 || n > 1024)
            return -1;
        cli->jobs = (int)n;
    } else if (!strcmp(a, "--quiet")) {
        cli->quiet = 1;
        return 1;
    } else if (!strcmp(a, "--no-connect")) {
        cli->connect = 0;
        return 1;
    } else if (!strcmp(a, "--keep-crossings")) {
        cli->carve = 0;
        return 1;
    } else if (!strcmp(a, "--join")) {
        if (fm_parse_double(a, val, &cli->join) || !(cli->join > 0))
            return -1;
    } else if (!strcmp(a, "--keep-duplicate")) {
        if (!val) {
            return -1;
        } else if (!strcmp(val, "smaller")) {
            cli->keep = FM_CONNECT_KEEP_SMALLER;
        } else if (!strcmp(val, "larger")) {
            cli->keep = FM_CONNECT_KEEP_LARGER;
        } else {
            fprintf(stderr, "faultmesh remesh: --keep-duplicate takes smaller or larger, not '%s'\n",
                    val);
            return -1;
        }
    } else {
        return fm_cli_repair_option(argc, argv, i, &cli->repair);
    }
    (*i)++;
    return 1;
}

/* `--top extend D` grows tops over the fitted surface's extension, which
 * must reach that far up dip: D of depth is D / sin(dip) along a fault,
 * so the margin grows with D (the default 2 km is for closing gaps). */
/* Tandem reads MSH 2.2 only; -1 (after saying why) when asked for 4.1. */
static int settle_msh(remesh_cli *cli)
{
    if (cli->msh_tags != FM_MSH_TAGS_TANDEM)
        return 0;
    if (cli->msh_version_given && cli->msh != FM_MSH_22) {
        fprintf(stderr, "faultmesh: --msh-tags tandem needs MSH 2.2 (Tandem reads no other)\n");
        return -1;
    }
    cli->msh = FM_MSH_22;
    return 0;
}

static void extend_fit(remesh_cli *cli)
{
    if (cli->mesh.top == FM_TOP_EXTEND)
        cli->model.fit.extend = fmax(cli->model.fit.extend, 1.5 * cli->mesh.top_extend + cli->mesh.size);
    /* A gap of D to a fault met at an angle is longer than D over the
     * ending fault's own surface (D / sin of the angle): twice D covers
     * angles down to 30 degrees (the default 2 km is that for D = 1 km). */
    if (cli->connect)
        cli->model.fit.extend = fmax(cli->model.fit.extend, 2 * cli->join);
}

static void cli_defaults(remesh_cli *cli)
{
    memset(cli, 0, sizeof *cli);
    fm_repair_options_default(&cli->repair);
    fm_remesh_model_options_default(&cli->model);
    fm_remesh_options_default(&cli->mesh);
    cli->msh = FM_MSH_41;
    cli->crs = NULL;
    cli->connect = 1;
    cli->carve = 1;
    cli->join = 1000;
    cli->keep = FM_CONNECT_KEEP_SMALLER;
    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    cli->jobs = ncpu > 0 ? (int)(ncpu < 64 ? ncpu : 64) : 1;
}

int fm_cmd_remesh(int argc, char **argv)
{
    remesh_cli cli;
    cli_defaults(&cli);
    char **paths = calloc((size_t)argc, sizeof *paths);
    size_t npaths = 0;
    if (!paths)
        return FM_EXIT_FAILURES;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            remesh_usage(stdout);
            free(paths);
            return FM_EXIT_OK;
        }
        int c = mesh_option(argc, argv, &i, &cli);
        if (c < 0 || (c == 0 && a[0] == '-' && a[1])) {
            if (c == 0)
                fprintf(stderr, "faultmesh remesh: unknown option '%s'\n", a);
            else
                fprintf(stderr, "faultmesh remesh: bad or missing value for '%s'\n", a);
            free(paths);
            return FM_EXIT_USAGE;
        }
        if (c == 0)
            paths[npaths++] = argv[i];
    }
    extend_fit(&cli);
    if (settle_msh(&cli)) {
        free(paths);
        return FM_EXIT_USAGE;
    }
    if (!cli.dir || npaths == 0) {
        remesh_usage(stderr);
        free(paths);
        return FM_EXIT_USAGE;
    }
    if (sim_cli_load(&cli.sim, cli.crs, paths, npaths) != 0) {
        sim_cli_free(&cli.sim);
        free(paths);
        return FM_EXIT_USAGE;
    }
    char **files = NULL;
    long nfiles = fm_input_list(paths, npaths, &files);
    free(paths);
    if (nfiles < 0) {
        sim_cli_free(&cli.sim);
        return FM_EXIT_USAGE;
    }
    int rc = run(&cli, files, nfiles);
    fm_input_list_free(files, nfiles);
    sim_cli_free(&cli.sim);
    return rc;
}

int fm_cmd_demo(int argc, char **argv)
{
    remesh_cli cli;
    cli_defaults(&cli);
    /* The synthetic faults are 20 to 60 km long: 1 km triangles show
     * their shapes and mesh in a second. Local metres, no real CRS. */
    cli.crs = "local metres (synthetic)";
    /* No real CRS to convert from: EQSim in the mesh's metres unless
     * --crs and --eqsim-coords spherical say otherwise. */
    cli.sim.eqsim = FM_EQSIM_RECTANGULAR;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            printf("usage: faultmesh demo [options] -o DIR\n"
                   "Generates the synthetic fault system in DIR/input and remeshes it into DIR\n"
                   "(same outputs and options as `faultmesh remesh`).\n");
            return FM_EXIT_OK;
        }
        int c = mesh_option(argc, argv, &i, &cli);
        if (c <= 0) {
            fprintf(stderr, "faultmesh demo: bad argument '%s'\n", a);
            return FM_EXIT_USAGE;
        }
    }
    extend_fit(&cli);
    if (settle_msh(&cli))
        return FM_EXIT_USAGE;
    if (!cli.dir) {
        fprintf(stderr, "usage: faultmesh demo [options] -o DIR\n");
        return FM_EXIT_USAGE;
    }
    if (sim_cli_load(&cli.sim, cli.crs, NULL, 0) != 0) {
        sim_cli_free(&cli.sim);
        return FM_EXIT_USAGE;
    }
    size_t n = strlen(cli.dir) + 16;
    char *in = malloc(n);
    if (!in) {
        sim_cli_free(&cli.sim);
        return FM_EXIT_FAILURES;
    }
    snprintf(in, n, "%s/input", cli.dir);
    fm_synth_options so;
    fm_synth_options_default(&so);
    fm_synth *s = NULL;
    fm_error err;
    fm_error_clear(&err);
    if (fm_synth_create(&so, &s, &err) != FM_OK || fm_synth_write(s, in, &err) != FM_OK) {
        fprintf(stderr, "faultmesh: %s\n", err.message);
        fm_synth_destroy(s);
        free(in);
        sim_cli_free(&cli.sim);
        return FM_EXIT_FAILURES;
    }
    fm_synth_destroy(s);
    char *args[1] = {in};
    char **files = NULL;
    long nfiles = fm_input_list(args, 1, &files);
    int rc = nfiles < 0 ? FM_EXIT_FAILURES : run(&cli, files, nfiles);
    if (nfiles >= 0)
        fm_input_list_free(files, nfiles);
    free(in);
    sim_cli_free(&cli.sim);
    return rc;
}
