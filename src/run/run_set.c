/* fm_run_set_int/double/string: the options one at a time by their fixed
 * keys (fm_run_option), each checked against its bounds; strings copied
 * into a block the run and its results share. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run_internal.h"

/* fm_run.h names the stages' values for the installed API, whose programs
 * do not see the stage headers. */
#define SAME(a, b) ((int)(a) == (int)(b))
_Static_assert(SAME(FM_RUN_TOP_CUT, FM_TOP_CUT) && SAME(FM_RUN_TOP_KEEP, FM_TOP_KEEP) &&
                   SAME(FM_RUN_TOP_EXTEND, FM_TOP_EXTEND), "fm_run.h: FM_RUN_TOP_*");
_Static_assert(SAME(FM_RUN_KEEP_SMALLER, FM_CONNECT_KEEP_SMALLER) &&
                   SAME(FM_RUN_KEEP_LARGER, FM_CONNECT_KEEP_LARGER), "fm_run.h: FM_RUN_KEEP_*");
_Static_assert(SAME(FM_RUN_MSH_41, FM_MSH_41) && SAME(FM_RUN_MSH_22, FM_MSH_22),
               "fm_run.h: FM_RUN_MSH_*");
_Static_assert(SAME(FM_RUN_MSH_TAGS_DEFAULT, FM_MSH_TAGS_DEFAULT) &&
                   SAME(FM_RUN_MSH_TAGS_TANDEM, FM_MSH_TAGS_TANDEM) &&
                   SAME(FM_RUN_MSH_TAGS_SEISSOL, FM_MSH_TAGS_SEISSOL) &&
                   SAME(FM_RUN_MSH_TAGS_PYLITH, FM_MSH_TAGS_PYLITH),
               "fm_run.h: FM_RUN_MSH_TAGS_*");
_Static_assert(SAME(FM_RUN_EQSIM_SPHERICAL, FM_EQSIM_SPHERICAL) &&
                   SAME(FM_RUN_EQSIM_RECTANGULAR, FM_EQSIM_RECTANGULAR),
               "fm_run.h: FM_RUN_EQSIM_*");
#undef SAME

run_strings *run_strings_ref(run_strings *s)
{
    if (s)
        atomic_fetch_add(&s->refs, 1);
    return s;
}

void run_strings_unref(run_strings *s)
{
    if (!s || atomic_fetch_sub(&s->refs, 1) != 1)
        return;
    for (size_t i = 0; i < s->n; i++)
        free(s->v[i]);
    free(s->v);
    free(s);
}

/* A copy of v kept by the run (and its results); NULL for NULL, or when
 * memory runs out (*nomem then set). A block a result shares is left to
 * it: the run starts another. */
static const char *keep(fm_run *run, const char *v, int *nomem)
{
    *nomem = 0;
    if (!v)
        return NULL;
    run_strings *s = run->strings;
    if (!s || atomic_load(&s->refs) > 1) {
        run_strings *t = calloc(1, sizeof *t);
        if (!t) {
            *nomem = 1;
            return NULL;
        }
        atomic_init(&t->refs, 1);
        /* the strings the options still point to come along */
        for (size_t i = 0; s && i < s->n; i++) {
            char **g = realloc(t->v, (t->n + 1) * sizeof *g);
            char *c = strdup(s->v[i]);
            if (!g || !c) {
                free(c);
                if (g)
                    t->v = g;
                run_strings_unref(t);
                *nomem = 1;
                return NULL;
            }
            t->v = g;
            t->v[t->n++] = c;
        }
        /* and the options point to the copies */
        fm_run_options *o = &run->opt;
        const char **fields[] = {&o->crs, &o->crs_out, &o->cache_dir, &o->slip_path,
                                 &o->metadata_path, &o->kin_paths[0], &o->kin_paths[1],
                                 &o->kin_paths[2], &o->kin_paths[3]};
        for (size_t f = 0; s && f < sizeof fields / sizeof *fields; f++)
            for (size_t i = 0; *fields[f] && i < s->n; i++)
                if (*fields[f] == s->v[i]) {
                    *fields[f] = t->v[i];
                    break;
                }
        run_strings_unref(s);
        run->strings = s = t;
    }
    char **g = realloc(s->v, (s->n + 1) * sizeof *g);
    char *c = strdup(v);
    if (!g || !c) {
        free(c);
        if (g)
            s->v = g;
        *nomem = 1;
        return NULL;
    }
    s->v = g;
    s->v[s->n++] = c;
    return c;
}

typedef enum { T_INT, T_DOUBLE, T_STRING } opt_type;

typedef struct opt_info {
    fm_run_option opt;
    opt_type type;
    double lo, hi;
    const char *name;
} opt_info;

static const opt_info infos[] = {
    {FM_OPT_SIZE, T_DOUBLE, 1e-9, HUGE_VAL, "size"},
    {FM_OPT_TOP, T_INT, FM_TOP_CUT, FM_TOP_EXTEND, "top"},
    {FM_OPT_TOP_EXTEND, T_DOUBLE, 0, HUGE_VAL, "top_extend"},
    {FM_OPT_SEA_LEVEL, T_DOUBLE, -HUGE_VAL, HUGE_VAL, "sea_level"},
    {FM_OPT_CONNECT, T_INT, 0, 1, "connect"},
    {FM_OPT_JOIN_DISTANCE, T_DOUBLE, 1e-9, HUGE_VAL, "join"},
    {FM_OPT_KEEP, T_INT, FM_CONNECT_KEEP_SMALLER, FM_CONNECT_KEEP_LARGER, "keep"},
    {FM_OPT_CARVE, T_INT, 0, 1, "carve"},
    {FM_OPT_MAX_TRIANGLES, T_INT, 0, 9.0e15, "max_triangles"},
    {FM_OPT_THREADS, T_INT, 1, 1024, "threads"},
    {FM_OPT_CRS, T_STRING, 0, 0, "crs"},
    {FM_OPT_CRS_OUT, T_STRING, 0, 0, "crs_out"},
    {FM_OPT_CACHE_DIR, T_STRING, 0, 0, "cache_dir"},
    {FM_OPT_CACHE, T_INT, 0, 1, "cache"},
    {FM_OPT_MSH_VERSION, T_INT, FM_MSH_41, FM_MSH_22, "msh_version"},
    {FM_OPT_MSH_TAGS, T_INT, FM_MSH_TAGS_DEFAULT, FM_MSH_TAGS_PYLITH, "msh_tags"},
    {FM_OPT_FORMATS, T_INT, 1, FM_OUT_ALL, "formats"},
    {FM_OPT_REPORT_HTML, T_INT, 0, 1, "report_html"},
    {FM_OPT_QUADS, T_INT, 0, 1, "quads"},
    {FM_OPT_SLIP, T_STRING, 0, 0, "slip"},
    {FM_OPT_METADATA, T_STRING, 0, 0, "metadata"},
    {FM_OPT_EQSIM_COORDS, T_INT, FM_EQSIM_SPHERICAL, FM_EQSIM_RECTANGULAR, "eqsim_coords"},
    {FM_OPT_KINEMATICS, T_STRING, 0, 0, "kinematics"},
    {FM_OPT_KINEMATICS_DISTANCE, T_DOUBLE, 1e-9, HUGE_VAL, "kinematics_distance"},
    {FM_OPT_KINEMATICS_FALLBACK, T_DOUBLE, 0, HUGE_VAL, "kinematics_fallback"},
    {FM_OPT_ELASTIC, T_INT, 0, 1, "elastic_check"},
    {FM_OPT_ELASTIC_FRACTION, T_DOUBLE, 1e-9, HUGE_VAL, "elastic_fraction"},
    {FM_OPT_ELASTIC_RADIUS, T_DOUBLE, 1e-9, HUGE_VAL, "elastic_radius"},
    {FM_OPT_ELASTIC_MEDIUM, T_INT, FM_RUN_ELASTIC_HALF, FM_RUN_ELASTIC_FULL, "elastic_medium"},
    {FM_OPT_SHEAR_MODULUS, T_DOUBLE, 1e-9, HUGE_VAL, "shear_modulus"},
    {FM_OPT_POISSON_RATIO, T_DOUBLE, 1e-9, 0.4999999999, "poisson_ratio"},
    {FM_OPT_STIFFNESS_MATRIX, T_STRING, 0, 0, "stiffness_matrix"},
};

static const opt_info *info_of(fm_run_option opt)
{
    for (size_t i = 0; i < sizeof infos / sizeof *infos; i++)
        if (infos[i].opt == opt)
            return &infos[i];
    return NULL;
}

fm_status fm_run_option_bounds(fm_run_option opt, double *lo, double *hi)
{
    const opt_info *in = info_of(opt);
    if (!in || in->type == T_STRING)
        return FM_ERR_INVALID;
    if (lo)
        *lo = in->lo;
    if (hi)
        *hi = in->hi;
    return FM_OK;
}

const fm_run_options *fm_run_get_options(const fm_run *run)
{
    return run ? &run->opt : NULL;
}

/* The option's entry when it is of type t; NULL after saying why. */
static const opt_info *checked(const fm_run *run, fm_run_option opt, opt_type t, fm_error *err)
{
    static const char *const tname[] = {"int", "double", "string"};
    const opt_info *in = info_of(opt);
    if (!run || !in) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s", run ? "unknown option" : "no run");
        return NULL;
    }
    if (in->type != t) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "option %s takes a %s, not a %s", in->name,
                     tname[in->type], tname[t]);
        return NULL;
    }
    return in;
}

static fm_status out_of_bounds(const opt_info *in, double v, fm_error *err)
{
    return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "option %s: %g is not in [%g, %g]",
                        in->name, v, in->lo, in->hi);
}

fm_status fm_run_set_int(fm_run *run, fm_run_option opt, int64_t v, fm_error *err)
{
    const opt_info *in = checked(run, opt, T_INT, err);
    if (!in)
        return FM_ERR_INVALID;
    if ((double)v < in->lo || (double)v > in->hi)
        return out_of_bounds(in, (double)v, err);
    if (opt == FM_OPT_FORMATS && (v & ~(int64_t)FM_OUT_ALL))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "option formats: unknown bits");
    fm_run_options *o = &run->opt;
    switch (opt) {
    case FM_OPT_TOP: o->mesh.top = (fm_top_mode)v; break;
    case FM_OPT_CONNECT: o->connect = (int)v; break;
    case FM_OPT_KEEP: o->keep = (fm_connect_keep)v; break;
    case FM_OPT_CARVE: o->carve = (int)v; break;
    case FM_OPT_MAX_TRIANGLES: o->max_triangles = (size_t)v; break;
    case FM_OPT_THREADS: o->jobs = (int)v; break;
    case FM_OPT_CACHE: o->no_cache = !v; break;
    case FM_OPT_MSH_VERSION: o->msh = (fm_msh_version)v, run->msh_given = 1; break;
    case FM_OPT_MSH_TAGS: o->msh_tags = (fm_msh_tags)v; break;
    case FM_OPT_FORMATS: o->formats = (unsigned)v; break;
    case FM_OPT_REPORT_HTML: o->html = (int)v; break;
    case FM_OPT_QUADS: o->quads = (int)v; break;
    case FM_OPT_EQSIM_COORDS: o->eqsim = (fm_eqsim_coords)v; break;
    case FM_OPT_ELASTIC: o->elastic = (int)v; break;
    case FM_OPT_ELASTIC_MEDIUM: o->elastic_full_space = v == FM_RUN_ELASTIC_FULL; break;
    default: break;
    }
    run_unprepare(run);
    return FM_OK;
}

fm_status fm_run_set_double(fm_run *run, fm_run_option opt, double v, fm_error *err)
{
    const opt_info *in = checked(run, opt, T_DOUBLE, err);
    if (!in)
        return FM_ERR_INVALID;
    if (!(v >= in->lo && v <= in->hi) || !isfinite(v))
        return out_of_bounds(in, v, err);
    fm_run_options *o = &run->opt;
    switch (opt) {
    case FM_OPT_SIZE: o->mesh.size = v; break;
    case FM_OPT_TOP_EXTEND: o->mesh.top_extend = v; break;
    case FM_OPT_SEA_LEVEL: o->mesh.sea_level = v; break;
    case FM_OPT_JOIN_DISTANCE: o->join = v; break;
    case FM_OPT_KINEMATICS_DISTANCE: o->kin_distance = v; break;
    case FM_OPT_KINEMATICS_FALLBACK: o->kin_fallback_rate = v; break;
    case FM_OPT_ELASTIC_FRACTION: o->elastic_fraction = v; break;
    case FM_OPT_ELASTIC_RADIUS: o->elastic_radius = v; break;
    case FM_OPT_SHEAR_MODULUS: o->elastic_mu = v; break;
    case FM_OPT_POISSON_RATIO: o->elastic_nu = v; break;
    default: break;
    }
    run_unprepare(run);
    return FM_OK;
}

fm_status fm_run_set_string(fm_run *run, fm_run_option opt, const char *v, fm_error *err)
{
    const opt_info *in = checked(run, opt, T_STRING, err);
    if (!in)
        return FM_ERR_INVALID;
    fm_run_options *o = &run->opt;
    if (opt == FM_OPT_KINEMATICS && v && o->nkin == FM_RUN_MAX_KINEMATICS)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "option kinematics: at most %d files",
                            FM_RUN_MAX_KINEMATICS);
    int nomem;
    const char *c = keep(run, v, &nomem);
    if (nomem)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    switch (opt) {
    case FM_OPT_CRS: o->crs = c; break;
    case FM_OPT_CRS_OUT: o->crs_out = c; break;
    case FM_OPT_CACHE_DIR: o->cache_dir = c; break;
    case FM_OPT_SLIP: o->slip_path = c; break;
    case FM_OPT_METADATA: o->metadata_path = c; break;
    case FM_OPT_STIFFNESS_MATRIX: o->stiffness_path = c; break;
    case FM_OPT_KINEMATICS:
        if (c)
            o->kin_paths[o->nkin++] = c;
        else
            o->nkin = 0;
        break;
    default: break;
    }
    run_unprepare(run);
    return FM_OK;
}
