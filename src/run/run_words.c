/* fm_run_take_option, fm_run_set_option: a run's options in the words of
 * the command line and of the settings file (faultmesh(1), docs/guide.md),
 * one table row per option. The values' checks and messages are the
 * CLI's own since its first release; an option more is a row more. */
#include <stdio.h>
#include <string.h>

#include "fm_opt.h"
#include "run_internal.h"

static fm_run_options *opts(void *t) { return &((fm_run *)t)->opt; }

static int set_string(void *t, fm_run_option opt, const char *v, fm_error *err)
{
    return fm_run_set_string(t, opt, v, err) == FM_OK ? 0 : -1;
}

/* "--NAME takes ..." */
static int takes(const fm_opt_arg *a, const char *what, fm_error *err)
{
    fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s takes %s", a->name, what);
    return -1;
}

static int size(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_positive(a->name, a->val, &opts(t)->mesh.size, err);
}

static int top(void *t, fm_opt_arg *a, fm_error *err)
{
    fm_remesh_options *m = &opts(t)->mesh;
    if (a->val && !strcmp(a->val, "cut")) {
        m->top = FM_TOP_CUT;
    } else if (a->val && !strcmp(a->val, "keep")) {
        m->top = FM_TOP_KEEP;
    } else if (a->val && !strcmp(a->val, "extend")) {
        m->top = FM_TOP_EXTEND;
        a->extra = 1;
        return fm_opt_double("--top extend", a->next, &m->top_extend, err);
    } else {
        return takes(a, "cut, keep or extend D", err);
    }
    return 0;
}

static int msh_version(void *t, fm_opt_arg *a, fm_error *err)
{
    if (a->val && !strcmp(a->val, "4.1"))
        opts(t)->msh = FM_MSH_41;
    else if (a->val && !strcmp(a->val, "2.2"))
        opts(t)->msh = FM_MSH_22;
    else
        return takes(a, "4.1 or 2.2", err);
    ((fm_run *)t)->msh_given = 1;
    return 0;
}

static int msh_tags(void *t, fm_opt_arg *a, fm_error *err)
{
    for (int c = FM_MSH_TAGS_DEFAULT; c <= FM_MSH_TAGS_PYLITH; c++)
        if (a->val && !strcmp(a->val, fm_msh_tags_name((fm_msh_tags)c))) {
            opts(t)->msh_tags = (fm_msh_tags)c;
            return 0;
        }
    return takes(a, "default, tandem, seissol or pylith", err);
}

static int crs(void *t, fm_opt_arg *a, fm_error *err)
{
    if (!a->val)
        return fm_opt_missing(a->name, err);
    return set_string(t, FM_OPT_CRS, a->val, err);
}

static int crs_out(void *t, fm_opt_arg *a, fm_error *err)
{
    if (!a->val || !a->val[0])
        return fm_opt_missing(a->name, err);
    return set_string(t, FM_OPT_CRS_OUT, a->val, err);
}

static int jobs(void *t, fm_opt_arg *a, fm_error *err)
{
    size_t n;
    if (fm_opt_size(a->name, a->val, &n, err))
        return -1;
    if (n < 1 || n > 1024) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                     "%s needs a whole number from 1 to 1024, got '%s'", a->name, a->val);
        return -1;
    }
    opts(t)->jobs = (int)n;
    return 0;
}

static int no_connect(void *t, fm_opt_arg *a, fm_error *err)
{
    (void)a, (void)err;
    opts(t)->connect = 0;
    return 0;
}

static int no_report_html(void *t, fm_opt_arg *a, fm_error *err)
{
    (void)a, (void)err;
    opts(t)->html = 0;
    return 0;
}

static int cache(void *t, fm_opt_arg *a, fm_error *err)
{
    if (!a->val || !a->val[0])
        return fm_opt_missing(a->name, err);
    if (set_string(t, FM_OPT_CACHE_DIR, a->val, err))
        return -1;
    opts(t)->no_cache = 0;
    return 0;
}

static int no_cache(void *t, fm_opt_arg *a, fm_error *err)
{
    (void)a, (void)err;
    opts(t)->no_cache = 1;
    return 0;
}

static int elements(void *t, fm_opt_arg *a, fm_error *err)
{
    if (!a->val)
        return fm_opt_missing(a->name, err);
    if (strcmp(a->val, "tri") && strcmp(a->val, "quad")) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s takes tri or quad, not '%s'", a->name,
                     a->val);
        return -1;
    }
    opts(t)->quads = !strcmp(a->val, "quad");
    return 0;
}

static int formats(void *t, fm_opt_arg *a, fm_error *err)
{
    if (!a->val)
        return fm_opt_missing(a->name, err);
    return run_formats_parse(a->val, &opts(t)->formats, err);
}

static int keep_crossings(void *t, fm_opt_arg *a, fm_error *err)
{
    (void)a, (void)err;
    opts(t)->carve = 0;
    return 0;
}

static int max_triangles(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_size(a->name, a->val, &opts(t)->max_triangles, err);
}

static int join(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_positive(a->name, a->val, &opts(t)->join, err);
}

static int keep_duplicate(void *t, fm_opt_arg *a, fm_error *err)
{
    if (!a->val)
        return fm_opt_missing(a->name, err);
    if (!strcmp(a->val, "smaller")) {
        opts(t)->keep = FM_CONNECT_KEEP_SMALLER;
    } else if (!strcmp(a->val, "larger")) {
        opts(t)->keep = FM_CONNECT_KEEP_LARGER;
    } else {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s takes smaller or larger, not '%s'",
                     a->name, a->val);
        return -1;
    }
    return 0;
}

/* the simulator side (src/run/sim_attrs.c reads the files) */
static int slip(void *t, fm_opt_arg *a, fm_error *err)
{
    return a->val ? set_string(t, FM_OPT_SLIP, a->val, err) : fm_opt_missing(a->name, err);
}

static int metadata(void *t, fm_opt_arg *a, fm_error *err)
{
    return a->val ? set_string(t, FM_OPT_METADATA, a->val, err) : fm_opt_missing(a->name, err);
}

static int kinematics(void *t, fm_opt_arg *a, fm_error *err)
{
    if (!a->val)
        return fm_opt_missing(a->name, err);
    if (opts(t)->nkin == FM_RUN_MAX_KINEMATICS) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s at most %d times", a->name,
                     FM_RUN_MAX_KINEMATICS);
        return -1;
    }
    return set_string(t, FM_OPT_KINEMATICS, a->val, err);
}

static int kinematics_distance(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_positive(a->name, a->val, &opts(t)->kin_distance, err);
}

static int kinematics_fallback(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_double(a->name, a->val, &opts(t)->kin_fallback_rate, err);
}

static int eqsim_coords(void *t, fm_opt_arg *a, fm_error *err)
{
    if (a->val && !strcmp(a->val, "spherical"))
        opts(t)->eqsim = FM_EQSIM_SPHERICAL;
    else if (a->val && (!strcmp(a->val, "utm") || !strcmp(a->val, "rectangular")))
        opts(t)->eqsim = FM_EQSIM_RECTANGULAR;
    else
        return takes(a, "spherical or utm", err);
    return 0;
}

/* the elastic interaction check (remesh_elastic.c) */
static int elastic_check(void *t, fm_opt_arg *a, fm_error *err)
{
    (void)a, (void)err;
    opts(t)->elastic = 1;
    return 0;
}

static int elastic_fraction(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_positive(a->name, a->val, &opts(t)->elastic_fraction, err);
}

static int elastic_radius(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_positive(a->name, a->val, &opts(t)->elastic_radius, err);
}

static int elastic_medium(void *t, fm_opt_arg *a, fm_error *err)
{
    if (a->val && (!strcmp(a->val, "half") || !strcmp(a->val, "full"))) {
        opts(t)->elastic_full_space = !strcmp(a->val, "full");
        return 0;
    }
    return takes(a, "half or full", err);
}

static int shear_modulus(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_positive(a->name, a->val, &opts(t)->elastic_mu, err);
}

static int poisson_ratio(void *t, fm_opt_arg *a, fm_error *err)
{
    if (fm_opt_positive(a->name, a->val, &opts(t)->elastic_nu, err))
        return -1;
    if (opts(t)->elastic_nu >= 0.5) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s must be under 0.5", a->name);
        return -1;
    }
    return 0;
}

static int stiffness_matrix(void *t, fm_opt_arg *a, fm_error *err)
{
    if (!a->val || !a->val[0])
        return fm_opt_missing(a->name, err);
    return set_string(t, FM_OPT_STIFFNESS_MATRIX, a->val, err);
}

/* Every option of a run in the command line's words; the repair options
 * follow (fm_repair_take_option). */
static const fm_opt_spec table[] = {
    {"--size", NULL, 1, size},
    {"--top", NULL, 1, top},
    {"--msh-version", NULL, 1, msh_version},
    {"--msh-tags", NULL, 1, msh_tags},
    {"--crs", NULL, 1, crs},
    {"--crs-out", NULL, 1, crs_out},
    {"--jobs", "-j", 1, jobs},
    {"--no-connect", NULL, 0, no_connect},
    {"--no-report-html", NULL, 0, no_report_html},
    {"--cache", NULL, 1, cache},
    {"--no-cache", NULL, 0, no_cache},
    {"--elements", NULL, 1, elements},
    {"--formats", NULL, 1, formats},
    {"--keep-crossings", NULL, 0, keep_crossings},
    {"--max-triangles", NULL, 1, max_triangles},
    {"--join", NULL, 1, join},
    {"--keep-duplicate", NULL, 1, keep_duplicate},
    {"--slip", NULL, 1, slip},
    {"--metadata", NULL, 1, metadata},
    {"--kinematics", NULL, 1, kinematics},
    {"--kinematics-distance", NULL, 1, kinematics_distance},
    {"--kinematics-fallback", NULL, 1, kinematics_fallback},
    {"--eqsim-coords", NULL, 1, eqsim_coords},
    {"--elastic-check", NULL, 0, elastic_check},
    {"--elastic-fraction", NULL, 1, elastic_fraction},
    {"--elastic-radius", NULL, 1, elastic_radius},
    {"--elastic-medium", NULL, 1, elastic_medium},
    {"--shear-modulus", NULL, 1, shear_modulus},
    {"--poisson-ratio", NULL, 1, poisson_ratio},
    {"--stiffness-matrix", NULL, 1, stiffness_matrix},
};

int fm_run_take_option(fm_run *run, int argc, const char *const *argv, int *i, fm_error *err)
{
    if (!run || !argv || !i || *i < 0 || *i >= argc) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "no run or no argument");
        return -1;
    }
    int rc = fm_opt_take(table, sizeof table / sizeof *table, run, argc, argv, i, err);
    if (rc == 0)
        rc = fm_repair_take_option(&run->opt.repair, argc, argv, i, err);
    if (rc > 0)
        run_unprepare(run); /* what fm_run_prepare read may be read otherwise now */
    return rc;
}

fm_status fm_run_set_option(fm_run *run, const char *key, const char *value, fm_error *err)
{
    char opt[96];
    if (!key || strlen(key) + 3 > sizeof opt)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "unknown option '%s'",
                            key ? key : "(null)");
    snprintf(opt, sizeof opt, "--%s", key);
    for (char *q = opt + 2; *q; q++)
        if (*q == '_')
            *q = '-';
    const char *argv[3] = {opt, value, NULL};
    int argc = value ? 2 : 1, k = 0;
    int rc = fm_run_take_option(run, argc, argv, &k, err);
    if (rc < 0)
        return err && err->code != FM_OK ? err->code : FM_ERR_INVALID;
    if (rc == 0 || k + 1 != argc)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "unknown option '%s'%s", key,
                            rc > 0 ? " (it takes no value)" : "");
    return FM_OK;
}
