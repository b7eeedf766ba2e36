/* faultmesh run: the settings file (fm_settings.h). A line-oriented
 * reader of the TOML subset a settings file needs; anything else is
 * refused with its line, so that a typo never passes silently. */
#include "fm_settings.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static void entry_free(fm_settings_entry *e)
{
    free(e->key);
    free(e->text);
    for (size_t i = 0; i < e->nitems; i++)
        free(e->items[i]);
    free(e->items);
}

static void section_free(fm_settings_section *s)
{
    for (size_t i = 0; i < s->n; i++)
        entry_free(&s->e[i]);
    free(s->e);
    free((void *)s->match);
}

void fm_settings_free(fm_settings *c)
{
    if (!c)
        return;
    section_free(&c->top);
    for (size_t i = 0; i < c->nfault; i++)
        section_free(&c->fault[i]);
    free(c->fault);
    for (size_t i = 0; i < c->nkept; i++)
        free(c->kept[i]);
    free(c->kept);
    free(c->path);
    free(c->dir);
    free(c);
}

typedef struct reader {
    const char *path;
    long line;
    const char *p; /* in the current line */
    fm_error *err;
} reader;

/* The first failure is the one said: later ones are its consequences. */
static int fail(const reader *r, const char *what)
{
    if (!r->err || r->err->code == FM_OK)
        fm_error_set(r->err, strcmp(what, "out of memory") ? FM_ERR_PARSE : FM_ERR_NOMEM, r->path,
                     r->line, "%s", what);
    return -1;
}

static void skip_space(reader *r)
{
    while (*r->p == ' ' || *r->p == '\t')
        r->p++;
}

/* A basic string ("..." with \" \\ \n \t \u-free escapes) or a literal
 * one ('...'); r->p on the opening quote. */
static char *read_string(reader *r)
{
    char q = *r->p++;
    size_t cap = 32, n = 0;
    char *s = malloc(cap);
    if (!s) {
        fail(r, "out of memory");
        return NULL;
    }
    for (;;) {
        char ch = *r->p;
        if (!ch || ch == '\n' || ch == '\r') {
            free(s);
            fail(r, "string not closed on its line");
            return NULL;
        }
        r->p++;
        if (ch == q)
            break;
        if (ch == '\\' && q == '"') {
            char e = *r->p++;
            ch = e == 'n' ? '\n' : e == 't' ? '\t' : e == '"' ? '"' : e == '\\' ? '\\' : 0;
            if (!ch) {
                free(s);
                fail(r, "unknown escape in a string (\\\" \\\\ \\n \\t are known)");
                return NULL;
            }
        }
        if (n + 2 > cap) {
            char *g = realloc(s, cap *= 2);
            if (!g) {
                free(s);
                fail(r, "out of memory");
                return NULL;
            }
            s = g;
        }
        s[n++] = ch;
    }
    s[n] = 0;
    return s;
}

/* What may follow a value: spaces and a comment. */
static int line_end(reader *r)
{
    skip_space(r);
    if (*r->p && *r->p != '#' && *r->p != '\n' && *r->p != '\r')
        return fail(r, "unexpected text after the value");
    return 0;
}

static int read_value(reader *r, fm_settings_entry *e)
{
    skip_space(r);
    const char *p = r->p;
    if (*p == '"' || *p == '\'') {
        e->type = FM_SETTINGS_STRING;
        return (e->text = read_string(r)) ? 0 : -1;
    }
    if (*p == '[') {
        e->type = FM_SETTINGS_ARRAY;
        r->p++;
        for (;;) {
            skip_space(r);
            if (*r->p == ']') {
                r->p++;
                return 0;
            }
            if (*r->p != '"' && *r->p != '\'')
                return fail(r, "arrays hold strings, on one line: [\"a\", \"b\"]");
            char *s = read_string(r);
            if (!s)
                return -1;
            char **g = realloc(e->items, (e->nitems + 1) * sizeof *g);
            if (!g) {
                free(s);
                return fail(r, "out of memory");
            }
            e->items = g;
            e->items[e->nitems++] = s;
            skip_space(r);
            if (*r->p == ',')
                r->p++;
            else if (*r->p != ']')
                return fail(r, "expected , or ] in the array");
        }
    }
    if (!strncmp(p, "true", 4) || !strncmp(p, "false", 5)) {
        e->type = FM_SETTINGS_BOOL;
        int t = p[0] == 't';
        r->p += t ? 4 : 5;
        return (e->text = strdup(t ? "true" : "false")) ? 0 : fail(r, "out of memory");
    }
    /* a number: TOML's digits, sign, point, exponent and _ separators */
    char buf[64];
    size_t n = 0;
    while ((isalnum((unsigned char)*r->p) || strchr("+-._", *r->p)) && n + 1 < sizeof buf) {
        if (*r->p != '_')
            buf[n++] = *r->p;
        r->p++;
    }
    buf[n] = 0;
    char *end;
    double v = n ? strtod(buf, &end) : NAN;
    if (!n || *end || !isfinite(v))
        return fail(r, "expected a value: \"string\", number, true, false or [\"list\"]");
    e->type = FM_SETTINGS_NUMBER;
    return (e->text = strdup(buf)) ? 0 : fail(r, "out of memory");
}

static int push_entry(fm_settings_section *s, fm_settings_entry *e)
{
    fm_settings_entry *g = realloc(s->e, (s->n + 1) * sizeof *g);
    if (!g)
        return -1;
    s->e = g;
    s->e[s->n++] = *e;
    return 0;
}

static int number_of(const reader *r, const fm_settings_entry *e, double lo, double *out)
{
    char msg[160];
    if (e->type != FM_SETTINGS_NUMBER || !(strtod(e->text, NULL) >= lo)) {
        snprintf(msg, sizeof msg, "%s takes a number%s", e->key,
                 lo > -INFINITY ? (lo > 0 ? " above 0" : " of 0 or more") : "");
        return fail(r, msg);
    }
    *out = strtod(e->text, NULL);
    return 0;
}

static int bool_of(const reader *r, const fm_settings_entry *e, int *out)
{
    char msg[160];
    if (e->type != FM_SETTINGS_BOOL) {
        snprintf(msg, sizeof msg, "%s takes true or false", e->key);
        return fail(r, msg);
    }
    *out = e->text[0] == 't';
    return 0;
}

/* A [[fault]] entry into the section's overrides. */
static int fault_key(reader *r, fm_settings_section *s, const fm_settings_entry *e)
{
    fm_fault_settings *f = &s->set;
    const char *k = e->key;
    if (!strcmp(k, "match")) {
        size_t n = e->type == FM_SETTINGS_ARRAY ? e->nitems : e->type == FM_SETTINGS_STRING ? 1 : 0;
        if (!n)
            return fail(r, "match takes a fault name pattern or a list of them");
        const char **m = realloc((void *)s->match, (s->nmatch + n) * sizeof *m);
        if (!m)
            return fail(r, "out of memory");
        for (size_t i = 0; i < n; i++)
            m[s->nmatch + i] = e->type == FM_SETTINGS_ARRAY ? e->items[i] : e->text;
        s->match = m;
        s->nmatch += n;
        return 0;
    }
    if (!strcmp(k, "size"))
        return f->has_size = 1, number_of(r, e, 1e-300, &f->size);
    if (!strcmp(k, "join"))
        return f->has_join = 1, number_of(r, e, 1e-300, &f->join);
    if (!strcmp(k, "rake"))
        return f->has_rake = 1, number_of(r, e, -INFINITY, &f->rake);
    if (!strcmp(k, "slip_rate"))
        return f->has_rate = 1, number_of(r, e, 0, &f->slip_rate_mm_yr);
    if (!strcmp(k, "connect"))
        return f->has_connect = 1, bool_of(r, e, &f->connect);
    if (!strcmp(k, "exclude"))
        return f->has_exclude = 1, bool_of(r, e, &f->exclude);
    if (!strcmp(k, "top_extend"))
        return number_of(r, e, 0, &f->top_extend);
    if (!strcmp(k, "top")) {
        f->has_top = 1;
        if (e->type == FM_SETTINGS_STRING && !strcmp(e->text, "cut"))
            f->top = FM_TOP_CUT;
        else if (e->type == FM_SETTINGS_STRING && !strcmp(e->text, "keep"))
            f->top = FM_TOP_KEEP;
        else if (e->type == FM_SETTINGS_STRING && !strcmp(e->text, "extend"))
            f->top = FM_TOP_EXTEND;
        else
            return fail(r, "top takes \"cut\", \"keep\" or \"extend\"");
        return 0;
    }
    char msg[200];
    snprintf(msg, sizeof msg,
             "unknown key '%s' in [[fault]] (match, size, top, top_extend, join, connect, "
             "exclude, rake, slip_rate)",
             k);
    return fail(r, msg);
}

/* A section is checked when it ends: it must say which faults it is for,
 * and top = "extend" needs how far. */
static int fault_done(reader *r, fm_settings_section *s)
{
    long line = r->line;
    r->line = s->line;
    int rc = 0;
    if (!s->nmatch)
        rc = fail(r, "[[fault]] without match = \"PATTERN\"");
    else if (s->set.has_top && s->set.top == FM_TOP_EXTEND && !(s->set.top_extend > 0))
        rc = fail(r, "top = \"extend\" needs top_extend = D (metres)");
    r->line = line;
    return rc;
}

static int parse(reader *r, FILE *fp, fm_settings *c)
{
    char *buf = NULL;
    size_t cap = 0;
    fm_settings_section *cur = &c->top;
    int rc = 0;
    while (rc == 0 && getline(&buf, &cap, fp) != -1) {
        r->line++;
        r->p = buf;
        skip_space(r);
        if (!*r->p || *r->p == '#' || *r->p == '\n' || *r->p == '\r')
            continue;
        if (*r->p == '[') {
            if (strncmp(r->p, "[[fault]]", 9)) {
                rc = fail(r, "the only section is [[fault]]");
                break;
            }
            r->p += 9;
            if ((rc = line_end(r)) != 0)
                break;
            if (cur != &c->top && (rc = fault_done(r, cur)) != 0)
                break;
            fm_settings_section *g = realloc(c->fault, (c->nfault + 1) * sizeof *g);
            if (!g) {
                rc = fail(r, "out of memory");
                break;
            }
            c->fault = g;
            cur = &c->fault[c->nfault++];
            memset(cur, 0, sizeof *cur);
            cur->line = r->line;
            continue;
        }
        const char *k = r->p;
        while (isalnum((unsigned char)*r->p) || *r->p == '_' || *r->p == '-')
            r->p++;
        size_t klen = (size_t)(r->p - k);
        skip_space(r);
        if (!klen || *r->p != '=') {
            rc = fail(r, "expected key = value");
            break;
        }
        r->p++;
        fm_settings_entry e;
        memset(&e, 0, sizeof e);
        e.line = r->line;
        e.key = strndup(k, klen);
        if (!e.key || read_value(r, &e) || line_end(r)) {
            if (!e.key)
                fail(r, "out of memory");
            entry_free(&e);
            rc = -1;
            break;
        }
        for (size_t i = 0; i < cur->n; i++)
            if (!strcmp(cur->e[i].key, e.key)) {
                rc = fail(r, "key given twice in one section");
                break;
            }
        if (rc || push_entry(cur, &e)) {
            if (!rc)
                rc = fail(r, "out of memory");
            entry_free(&e);
            break;
        }
        if (cur != &c->top)
            rc = fault_key(r, cur, &cur->e[cur->n - 1]);
    }
    if (rc == 0 && cur != &c->top)
        rc = fault_done(r, cur);
    free(buf);
    return rc;
}

fm_settings *fm_settings_read(const char *path, fm_error *err)
{
    fm_error_clear(err);
    struct stat sb;
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) {
        fm_error_set(err, FM_ERR_INVALID, path, 0, "a folder, not a settings file");
        return NULL;
    }
    FILE *fp = fopen(path, "r");
    if (!fp) {
        fm_error_set(err, FM_ERR_IO, path, 0, "cannot read the settings file: %s",
                     strerror(errno));
        return NULL;
    }
    fm_settings *c = calloc(1, sizeof *c);
    reader r = {path, 0, NULL, err};
    if (c) {
        c->path = strdup(path);
        const char *slash = strrchr(path, '/');
        c->dir = slash ? strndup(path, (size_t)(slash - path + 1)) : strdup("");
    }
    int rc = (!c || !c->path || !c->dir) ? fail(&r, "out of memory") : parse(&r, fp, c);
    fclose(fp);
    if (rc) {
        fm_settings_free(c);
        return NULL;
    }
    return c;
}

const char *fm_settings_path(fm_settings *c, const char *p)
{
    size_t n = strlen(c->dir) + strlen(p) + 1;
    char *s = malloc(n);
    char **g = realloc(c->kept, (c->nkept + 1) * sizeof *g);
    if (g)
        c->kept = g;
    if (!s || !g) {
        free(s);
        return NULL;
    }
    snprintf(s, n, "%s%s", p[0] == '/' ? "" : c->dir, p);
    c->kept[c->nkept++] = s;
    return s;
}

fm_fault_rule *fm_settings_rules(const fm_settings *s, size_t *n)
{
    *n = 0;
    if (!s || !s->nfault)
        return NULL;
    fm_fault_rule *rules = calloc(s->nfault, sizeof *rules);
    if (!rules) {
        *n = 1;
        return NULL;
    }
    for (size_t i = 0; i < s->nfault; i++) {
        const fm_settings_section *f = &s->fault[i];
        rules[i].match = f->match;
        rules[i].nmatch = f->nmatch;
        rules[i].set = f->set;
        rules[i].set.line = f->line;
    }
    *n = s->nfault;
    return rules;
}
