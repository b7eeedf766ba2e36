/* fm_run_read_settings: a settings file's top-level keys applied as the
 * options they name (in the command line's words, fm_run_take_option),
 * its [[fault]] sections kept as the run's rules, its inputs kept for
 * the caller; and fm_run_check_options, which settles the options that
 * depend on each other. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_settings.h"
#include "run_internal.h"

run_config *run_config_ref(run_config *c)
{
    if (c)
        atomic_fetch_add(&c->refs, 1);
    return c;
}

void run_config_unref(run_config *c)
{
    if (!c || atomic_fetch_sub(&c->refs, 1) != 1)
        return;
    free(c->rules);
    free(c->inputs);
    fm_settings_free(c->file);
    free(c);
}

static const char *const format_names[] = {"vtu", "msh",    "stl",   "obj",  "exo",  "ts",
                                           "igs", "rsqsim", "eqsim", "html", "names"};

int run_formats_parse(const char *list, unsigned *out, fm_error *err)
{
    unsigned f = 0;
    const char *p = list;
    while (*p) {
        size_t n = strcspn(p, ",");
        int found = 0;
        for (size_t k = 0; k < sizeof format_names / sizeof *format_names && !found; k++)
            if (n == strlen(format_names[k]) && !strncmp(p, format_names[k], n)) {
                f |= 1u << k;
                found = 1;
            }
        if (!found) {
            fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                         "--formats: '%.*s' is not one of vtu, msh, stl, obj, exo, ts, igs, "
                         "rsqsim, eqsim, html, names",
                         (int)n, p);
            return -1;
        }
        p += n + (p[n] == ',');
    }
    if (!f) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "--formats needs at least one format");
        return -1;
    }
    *out = f;
    return 0;
}

/* Flags whose default is on: `key = false` in a settings file is their
 * --no- option, `key = true` the default. */
static const char *const on_by_default[] = {"connect", "split", "report_html", "cache"};

static int is_on_by_default(const char *key)
{
    for (size_t i = 0; i < sizeof on_by_default / sizeof *on_by_default; i++)
        if (!strcmp(key, on_by_default[i]))
            return 1;
    return 0;
}

/* Paths the file names, taken from its folder. */
static int path_key(const char *key)
{
    return !strcmp(key, "output") || !strcmp(key, "slip") || !strcmp(key, "metadata") ||
           !strcmp(key, "cache") || !strcmp(key, "stiffness_matrix");
}

/* "--key" (or "--no-key"), underscores as dashes. */
static void option_name(char *opt, size_t n, const char *prefix, const char *key)
{
    snprintf(opt, n, "%s%s", prefix, key);
    for (char *q = opt + strlen(prefix); *q; q++)
        if (*q == '_')
            *q = '-';
}

/* Why the file's line is wrong: after what the option said ("--size
 * needs ...\nFILE:LINE: bad value for 'size'", err->line 0, for the
 * caller to show as the command line's messages), or on its own
 * ("FILE:LINE: ...", err->line the line). */
static fm_status bad_line(fm_error *err, const fm_settings *c, long line, int after,
                          const char *fmt, const char *key, const char *more)
{
    char why[256];
    snprintf(why, sizeof why, fmt, key, more);
    if (!after)
        return fm_error_set(err, FM_ERR_INVALID, c->path, line, "%s", why);
    char first[FM_ERROR_MESSAGE_MAX];
    snprintf(first, sizeof first, "%s", err ? err->message : "");
    fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s\n%s:%ld: %s", first, c->path, line, why);
    return FM_ERR_INVALID;
}

/* Inputs the entry lists, appended to the config's. */
static fm_status add_inputs(run_config *cfg, const fm_settings_entry *e, fm_error *err)
{
    fm_settings *c = cfg->file;
    size_t n = e->type == FM_SETTINGS_ARRAY ? e->nitems : e->type == FM_SETTINGS_STRING ? 1 : 0;
    const char **g = n ? realloc(cfg->inputs, (cfg->ninputs + n) * sizeof *g) : NULL;
    if (!g)
        return bad_line(err, c, e->line, 0, "%s takes a path or a list of paths%s", e->key, "");
    cfg->inputs = g;
    for (size_t k = 0; k < n; k++)
        if (!(g[cfg->ninputs++] =
                  fm_settings_path(c, e->type == FM_SETTINGS_ARRAY ? e->items[k] : e->text)))
            return fm_error_set(err, FM_ERR_NOMEM, c->path, 0, "out of memory");
    return FM_OK;
}

/* formats = ["vtu", "msh"]: the run's formats. */
static fm_status formats_list(fm_run *run, const fm_settings *c, const fm_settings_entry *e,
                              fm_error *err)
{
    unsigned all = 0;
    for (size_t k = 0; k < e->nitems; k++) {
        unsigned f;
        if (run_formats_parse(e->items[k], &f, err))
            return bad_line(err, c, e->line, 1, "%s: see above%s", e->key, "");
        all |= f;
    }
    if (!all)
        return bad_line(err, c, e->line, 0, "%s needs at least one format%s", e->key, "");
    run->opt.formats = all;
    return FM_OK;
}

/* One top-level key as the option it names. */
static fm_status apply(fm_run *run, fm_settings *c, const fm_settings_entry *e,
                       const fm_settings_entry *extend, fm_option_fn other, void *user,
                       fm_error *err)
{
    char opt[96];
    const char *argv[4] = {opt, NULL, NULL, NULL};
    int argc = 1;
    option_name(opt, sizeof opt, "--", e->key);
    if (e->type == FM_SETTINGS_BOOL) {
        int on = e->text[0] == 't';
        if (is_on_by_default(e->key) && !on)
            option_name(opt, sizeof opt, "--no-", e->key);
        else if (is_on_by_default(e->key) || !on)
            return FM_OK; /* the default */
    } else if (e->type == FM_SETTINGS_ARRAY && !strcmp(e->key, "formats")) {
        return formats_list(run, c, e, err);
    } else if (e->type == FM_SETTINGS_ARRAY) {
        return bad_line(err, c, e->line, 0, "%s takes one value, not a list%s", e->key, "");
    } else {
        argv[argc++] = path_key(e->key) ? fm_settings_path(c, e->text) : e->text;
        if (!argv[1])
            return fm_error_set(err, FM_ERR_NOMEM, c->path, 0, "out of memory");
        if (!strcmp(e->key, "top") && !strcmp(e->text, "extend")) {
            if (!extend || extend->type != FM_SETTINGS_NUMBER)
                return bad_line(err, c, e->line, 0,
                                "%s = \"extend\" needs top_extend = D (metres)%s", e->key, "");
            argv[argc++] = extend->text;
        }
    }
    int k = 0;
    int rc = fm_run_take_option(run, argc, argv, &k, err);
    if (rc == 0 && other)
        rc = other(user, argc, argv, &k, err);
    if (rc == 0 || (rc > 0 && k + 1 != argc))
        return bad_line(err, c, e->line, 0, "unknown setting '%s'%s", e->key,
                        rc > 0 ? " (it takes no value here)" : "");
    if (rc < 0)
        return bad_line(err, c, e->line, 1, "bad value for '%s'%s", e->key, "");
    return FM_OK;
}

fm_status fm_run_read_settings(fm_run *run, const char *path, fm_option_fn other, void *user,
                               fm_error *err)
{
    if (!run || !path)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "no run or no settings file");
    run_config *cfg = calloc(1, sizeof *cfg);
    if (!cfg)
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    atomic_init(&cfg->refs, 1);
    if (!(cfg->file = fm_settings_read(path, err))) {
        run_config_unref(cfg);
        return err ? err->code : FM_ERR_INVALID;
    }
    fm_settings *c = cfg->file;
    const fm_settings_section *s = &c->top;
    const fm_settings_entry *extend = NULL;
    for (size_t i = 0; i < s->n; i++)
        if (!strcmp(s->e[i].key, "top_extend"))
            extend = &s->e[i];
    fm_status st = FM_OK;
    for (size_t i = 0; i < s->n && st == FM_OK; i++) {
        const fm_settings_entry *e = &s->e[i];
        if (!strcmp(e->key, "inputs") || !strcmp(e->key, "input"))
            st = add_inputs(cfg, e, err);
        else if (strcmp(e->key, "top_extend")) /* top_extend goes with top = "extend" */
            st = apply(run, c, e, extend, other, user, err);
    }
    size_t n = 0;
    if (st == FM_OK && !(cfg->rules = fm_settings_rules(c, &n)) && n)
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    if (st != FM_OK) {
        run_config_unref(cfg);
        return st;
    }
    /* the file's rules replace those of a file read before */
    run_config_unref(run->config);
    run->config = cfg;
    run->opt.settings_path = c->path;
    run->opt.fault_rules = cfg->rules;
    run->opt.nfault_rules = cfg->rules ? n : 0;
    run_unprepare(run);
    return FM_OK;
}

size_t fm_run_settings_ninputs(const fm_run *run)
{
    return run && run->config ? run->config->ninputs : 0;
}

const char *fm_run_settings_input(const fm_run *run, size_t i)
{
    return i < fm_run_settings_ninputs(run) ? run->config->inputs[i] : NULL;
}

const char *fm_run_settings_path(const fm_run *run)
{
    return run && run->config ? run->config->file->path : NULL;
}

fm_status fm_run_check_options(fm_run *run, fm_error *err)
{
    if (!run)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "no run");
    fm_run_options *o = &run->opt;
    /* Tandem reads MSH 2.2 only */
    if (o->msh_tags == FM_MSH_TAGS_TANDEM) {
        if (run->msh_given && o->msh != FM_MSH_22)
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                "--msh-tags tandem needs MSH 2.2 (Tandem reads no other)");
        o->msh = FM_MSH_22;
    }
    /* rectangles: the formats that hold them (the default), or an error
     * for another one asked for */
    const unsigned tri_only = FM_OUT_STL | FM_OUT_OBJ | FM_OUT_EXO | FM_OUT_TS | FM_OUT_IGS;
    if (o->quads && o->formats == FM_OUT_ALL)
        o->formats &= ~tri_only;
    else if (o->quads && (o->formats & tri_only))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "--elements quad writes vtu, msh, rsqsim, eqsim, html and names; "
                            "stl, obj, exo, ts and igs hold triangles only");
    return FM_OK;
}

fm_status fm_run_get_int(const fm_run *run, fm_run_option opt, int64_t *v)
{
    if (!run || !v)
        return FM_ERR_INVALID;
    const fm_run_options *o = &run->opt;
    switch (opt) {
    case FM_OPT_TOP: *v = o->mesh.top; break;
    case FM_OPT_CONNECT: *v = o->connect; break;
    case FM_OPT_KEEP: *v = o->keep; break;
    case FM_OPT_CARVE: *v = o->carve; break;
    case FM_OPT_MAX_TRIANGLES: *v = (int64_t)o->max_triangles; break;
    case FM_OPT_THREADS: *v = o->jobs; break;
    case FM_OPT_CACHE: *v = !o->no_cache; break;
    case FM_OPT_MSH_VERSION: *v = o->msh; break;
    case FM_OPT_MSH_TAGS: *v = o->msh_tags; break;
    case FM_OPT_FORMATS: *v = o->formats; break;
    case FM_OPT_REPORT_HTML: *v = o->html; break;
    case FM_OPT_QUADS: *v = o->quads; break;
    case FM_OPT_EQSIM_COORDS: *v = o->eqsim; break;
    case FM_OPT_ELASTIC: *v = o->elastic; break;
    case FM_OPT_ELASTIC_MEDIUM: *v = o->elastic_full_space ? FM_RUN_ELASTIC_FULL : FM_RUN_ELASTIC_HALF; break;
    default: return FM_ERR_INVALID;
    }
    return FM_OK;
}
