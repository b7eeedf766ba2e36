/* fm_run.h: the options and their defaults, the run handle, and what a
 * result says of each fault. */
#include <fnmatch.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "run_internal.h"

void fm_run_options_default(fm_run_options *o)
{
    memset(o, 0, sizeof *o);
    fm_repair_options_default(&o->repair);
    fm_remesh_model_options_default(&o->model);
    fm_remesh_options_default(&o->mesh);
    o->msh = FM_MSH_41;
    o->msh_tags = FM_MSH_TAGS_DEFAULT;
    o->connect = 1;
    o->carve = 1;
    o->html = 1;
    o->formats = FM_OUT_ALL;
    o->join = 1000;
    o->max_triangles = FM_RUN_DEFAULT_MAX_TRIANGLES;
    o->keep = FM_CONNECT_KEEP_SMALLER;
    o->eqsim = FM_EQSIM_SPHERICAL;
    fm_elastic_options eo;
    fm_elastic_options_default(&eo);
    o->elastic_mu = eo.mu;
    o->elastic_nu = eo.nu;
    o->elastic_radius = eo.radius;
    o->elastic_fraction = eo.fraction;
    long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
    o->jobs = ncpu > 0 ? (int)(ncpu < 64 ? ncpu : 64) : 1;
}

void fm_fault_settings_lookup(const fm_fault_rule *rules, size_t nrules, const char *name,
                              fm_fault_settings *out)
{
    memset(out, 0, sizeof *out);
    for (size_t i = 0; rules && i < nrules; i++) {
        const fm_fault_rule *s = &rules[i];
        int hit = 0;
        for (size_t k = 0; k < s->nmatch && !hit; k++)
            hit = fnmatch(s->match[k], name, 0) == 0;
        if (!hit)
            continue;
        const fm_fault_settings *f = &s->set;
        if (f->has_size)
            out->has_size = 1, out->size = f->size;
        if (f->has_top)
            out->has_top = 1, out->top = f->top, out->top_extend = f->top_extend;
        if (f->has_join)
            out->has_join = 1, out->join = f->join;
        if (f->has_connect)
            out->has_connect = 1, out->connect = f->connect;
        if (f->has_exclude)
            out->has_exclude = 1, out->exclude = f->exclude;
        if (f->has_rake)
            out->has_rake = 1, out->rake = f->rake;
        if (f->has_rate)
            out->has_rate = 1, out->slip_rate_mm_yr = f->slip_rate_mm_yr;
        out->line = f->line;
    }
}

fm_run *fm_run_create(const fm_run_options *opt)
{
    fm_run *run = calloc(1, sizeof *run);
    if (!run)
        return NULL;
    if (!(run->ctl = run_ctl_create())) {
        free(run);
        return NULL;
    }
    if (opt)
        run->opt = *opt;
    else
        fm_run_options_default(&run->opt);
    return run;
}

void fm_run_destroy(fm_run *run)
{
    if (!run)
        return;
    run_strings_unref(run->strings);
    run_config_unref(run->config);
    sim_cli_free(&run->sim);
    for (size_t i = 0; i < run->npaths; i++) {
        free(run->paths[i]);
        fm_mesh_destroy(run->meshes[i]);
    }
    free(run->paths);
    free(run->meshes);
    run_ctl_destroy(run->ctl);
    free(run);
}

void fm_run_set_log(fm_run *run, fm_log_level max_level, fm_log_fn fn, void *user)
{
    run->ctl->log = fn;
    run->ctl->log_user = user;
    run->ctl->log_max = max_level;
}

void fm_run_set_progress(fm_run *run, fm_progress_fn fn, void *user)
{
    run->ctl->progress = fn;
    run->ctl->progress_user = user;
}

void fm_run_interrupt(fm_run *run)
{
    if (run)
        atomic_store(&run->ctl->cancelled, 1);
}

/* One input more: a file (a copy of path), or an in-memory mesh named
 * path (mesh, which the run then owns; destroyed on failure). */
static fm_status add_input(fm_run *run, const char *path, fm_mesh *mesh, fm_error *err)
{
    if (run->npaths == run->cap) {
        size_t cap = run->cap ? 2 * run->cap : 16;
        char **p = realloc(run->paths, cap * sizeof *p);
        if (p)
            run->paths = p;
        fm_mesh **m = p ? realloc(run->meshes, cap * sizeof *m) : NULL;
        if (!m) {
            fm_mesh_destroy(mesh);
            return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        }
        run->meshes = m;
        run->cap = cap;
    }
    if (!(run->paths[run->npaths] = strdup(path))) {
        fm_mesh_destroy(mesh);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    run->meshes[run->npaths] = mesh;
    run->npaths++;
    return FM_OK;
}

static fm_status add_file(fm_run *run, const char *path, fm_error *err)
{
    return add_input(run, path, NULL, err);
}

fm_status fm_run_add_mesh(fm_run *run, const char *name, const double *xyz, size_t nv,
                          const int32_t *tri, size_t nt, fm_error *err)
{
    if (!run || !name || !name[0])
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "an in-memory input needs a name");
    if (!xyz || !tri || nv < 3 || nt < 1 || nv > INT32_MAX || nt > INT32_MAX)
        return fm_error_set(err, FM_ERR_INVALID, name, 0,
                            "an in-memory input needs 3 or more vertices and a triangle");
    /* checked here, where the caller can be told, rather than failing the
     * fault later with a message about a file that does not exist */
    for (size_t i = 0; i < 3 * nv; i++)
        if (!isfinite(xyz[i]))
            return fm_error_set(err, FM_ERR_INVALID, name, 0, "vertex %zu is not finite", i / 3);
    for (size_t t = 0; t < nt; t++) {
        const int32_t *v = tri + 3 * t;
        for (int k = 0; k < 3; k++)
            if (v[k] < 0 || (size_t)v[k] >= nv)
                return fm_error_set(err, FM_ERR_INVALID, name, 0,
                                    "triangle %zu: vertex %ld out of range (%zu vertices)", t,
                                    (long)v[k], nv);
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
            return fm_error_set(err, FM_ERR_INVALID, name, 0,
                                "triangle %zu: a vertex twice", t);
    }
    fm_mesh *m = fm_mesh_create();
    if (!m || fm_mesh_reserve(m, nv, nt) != FM_OK) {
        fm_mesh_destroy(m);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    }
    for (size_t i = 0; i < nv; i++)
        fm_mesh_add_vertex(m, xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    for (size_t t = 0; t < nt; t++)
        fm_mesh_add_triangle(m, tri[3 * t], tri[3 * t + 1], tri[3 * t + 2], 0);
    return add_input(run, name, m, err);
}

fm_status fm_run_add_path(fm_run *run, const char *path, fm_error *err)
{
    if (!run || !path)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "no input path");
    /* a file that cannot be read (gone, a dangling link) is a fault that
     * fails, said in the result, as when it cannot be parsed */
    struct stat sb;
    if (stat(path, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return add_file(run, path, err);
    char **list = NULL;
    long n = run_list_inputs(&path, 1, run->ctl, &list, err);
    if (n < 0)
        return err ? err->code : FM_ERR_IO;
    fm_status st = FM_OK;
    for (long i = 0; i < n && st == FM_OK; i++)
        st = add_file(run, list[i], err);
    run_list_free(list, n);
    return st;
}

void run_unprepare(fm_run *run)
{
    sim_cli_free(&run->sim);
    memset(&run->sim, 0, sizeof run->sim);
    run->prepared = 0;
}

fm_status fm_run_prepare(fm_run *run, const char *const *near, size_t nnear, fm_error *err)
{
    const fm_run_options *o = &run->opt;
    run_unprepare(run);
    sim_cli *sc = &run->sim;
    sc->slip_path = o->slip_path;
    sc->metadata_path = o->metadata_path;
    sc->eqsim = o->eqsim;
    sc->rules = o->fault_rules;
    sc->nrules = o->nfault_rules;
    sc->ctl = run->ctl;
    sc->nkin = o->nkin < SIM_MAX_KINEMATICS ? o->nkin : SIM_MAX_KINEMATICS;
    for (size_t k = 0; k < sc->nkin; k++)
        sc->kin_paths[k] = o->kin_paths[k];
    sc->kin_distance = o->kin_distance;
    sc->kin_fallback_rate = o->kin_fallback_rate;
    fm_status st = sim_cli_load(sc, o->crs_out ? o->crs_out : o->crs, near, nnear, err);
    if (st != FM_OK) {
        sim_cli_free(sc);
        return st;
    }
    run->prepared = 1;
    return FM_OK;
}

/* The run's settings as its files read them. */
static void settings_of(const fm_run *run, remesh_cli *cli)
{
    const fm_run_options *o = &run->opt;
    memset(cli, 0, sizeof *cli);
    cli->repair = o->repair;
    cli->model = o->model;
    cli->mesh = o->mesh;
    cli->msh = o->msh;
    cli->msh_tags = o->msh_tags;
    cli->crs = o->crs;
    cli->crs_out = o->crs_out;
    cli->rules = o->fault_rules;
    cli->nrules = o->nfault_rules;
    cli->settings_path = o->settings_path;
    cli->jobs = o->jobs > 0 ? o->jobs : 1;
    cli->connect = o->connect;
    cli->join = o->join;
    cli->keep = o->keep;
    cli->carve = o->carve;
    cli->html = o->html;
    cli->max_triangles = o->max_triangles;
    cli->formats = o->formats;
    cli->quads = o->quads;
    cli->cache_dir = o->cache_dir;
    cli->no_cache = o->no_cache;
    cli->elastic_check = o->elastic;
    cli->stiffness_path = o->stiffness_path;
    fm_elastic_options_default(&cli->elastic);
    cli->elastic.mu = o->elastic_mu;
    cli->elastic.nu = o->elastic_nu;
    cli->elastic.radius = o->elastic_radius;
    cli->elastic.fraction = o->elastic_fraction;
    cli->elastic.full_space = o->elastic_full_space;
    cli->elastic.threads = cli->jobs;
}

/* From here on the result's callbacks are its own (the run may go first). */
static void adopt_ctl(fm_run_result *res)
{
    res->cli.ctl = res->ctl;
    res->cli.sim.ctl = res->ctl;
    res->rs.ctl = res->ctl;
    res->outputs.ctl = res->ctl;
    for (size_t i = 0; res->jobs && i < res->njobs; i++)
        res->jobs[i].ctl = res->ctl;
}

fm_status fm_run_execute(fm_run *run, fm_run_result **out, fm_error *err)
{
    *out = NULL;
    if (!run)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "no run");
    if (!run->prepared) {
        /* the simulator data are looked for beside the files only: an
         * in-memory input's name is no place */
        const char **near = malloc((run->npaths ? run->npaths : 1) * sizeof *near);
        if (!near)
            return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        size_t nnear = 0;
        for (size_t i = 0; i < run->npaths; i++)
            if (!run->meshes[i])
                near[nnear++] = run->paths[i];
        fm_status st = fm_run_prepare(run, near, nnear, err);
        free(near);
        if (st != FM_OK)
            return st;
    }
    fm_run_result *res = calloc(1, sizeof *res);
    run_ctl *ctl = res ? run_ctl_create() : NULL;
    if (!ctl) {
        free(res);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    ctl->log = run->ctl->log;
    ctl->log_user = run->ctl->log_user;
    ctl->log_max = run->ctl->log_max;
    ctl->progress = run->ctl->progress;
    ctl->progress_user = run->ctl->progress_user;
    res->ctl = ctl;
    res->strings = run_strings_ref(run->strings);
    res->config = run_config_ref(run->config);
    settings_of(run, &res->cli);
    res->cli.ctl = run->ctl;
    /* the simulator data go with the result */
    res->cli.sim = run->sim;
    res->cli.sim.ctl = run->ctl;
    memset(&run->sim, 0, sizeof run->sim);
    run->prepared = 0;
    extend_fit(&res->cli);
    settle_cache(&res->cli);
    fm_status st = run_execute(res, (const char *const *)run->paths,
                               (const fm_mesh *const *)run->meshes, run->npaths, err);
    /* a cancel ends this execution only */
    atomic_store(&run->ctl->cancelled, 0);
    if (st != FM_OK)
        return st;
    adopt_ctl(res);
    *out = res;
    return FM_OK;
}

size_t fm_run_result_nfaults(const fm_run_result *res)
{
    return res ? res->rs.nres : 0;
}

size_t fm_run_result_nfailed(const fm_run_result *res)
{
    return res ? (size_t)res->rs.failed : 0;
}

const char *fm_run_result_fault_name(const fm_run_result *res, size_t i)
{
    if (!res || i >= res->rs.nres)
        return NULL;
    const fault_result *r = &res->rs.res[i];
    return r->name ? r->name : r->file;
}

const char *fm_run_result_fault_status(const fm_run_result *res, size_t i, const char **why)
{
    if (why)
        *why = NULL;
    if (!res || i >= res->rs.nres)
        return NULL;
    const fault_result *r = &res->rs.res[i];
    if (why)
        *why = r->error;
    return r->status;
}

const fm_mesh *fm_run_result_mesh(const fm_run_result *res)
{
    return res ? res->rs.set : NULL;
}

size_t fm_run_result_nvertices(const fm_run_result *res)
{
    return res && res->rs.set ? fm_mesh_nvertices(res->rs.set) : 0;
}

size_t fm_run_result_ntriangles(const fm_run_result *res)
{
    return res && res->rs.set ? fm_mesh_ntriangles(res->rs.set) : 0;
}

fm_status fm_run_result_copy_mesh(const fm_run_result *res, double *xyz, int32_t *tri,
                                  int32_t *fault, fm_error *err)
{
    if (!res)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "no result");
    const fm_mesh *m = res->rs.set;
    if (!m)
        return FM_OK; /* no fault was meshed: nothing to copy */
    size_t nv = fm_mesh_nvertices(m), nt = fm_mesh_ntriangles(m);
    if (xyz && nv)
        memcpy(xyz, fm_mesh_vertices(m), 3 * nv * sizeof *xyz);
    if (tri && nt)
        memcpy(tri, fm_mesh_triangles(m), 3 * nt * sizeof *tri);
    /* the set's tags count the faults written; callers count the result's
     * faults (fm_run_result_fault_name), which also holds those that
     * failed or were dropped */
    const int32_t *tag = fm_mesh_tags(m);
    for (size_t t = 0; fault && t < nt; t++)
        fault[t] = (int32_t)res->rs.set_res[tag[t]];
    return FM_OK;
}

void fm_free(void *p)
{
    free(p);
}

int fm_version_number(void)
{
    return FM_VERSION_NUMBER;
}

const char *fm_version_string(void)
{
    return FM_VERSION_STRING;
}

size_t fm_run_result_unwritten(const fm_run_result *res)
{
    return res ? res->outputs.unwritten : 0;
}
