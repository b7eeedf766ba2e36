/* CFM metadata and --slip CSV files; the slip of each fault from them. */
#include <ctype.h>
#include <errno.h>
#include <fnmatch.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_metadata.h"

/* Far above the CFM table (0.3 MB): a file this large is not one. */
#define CSV_MAX_BYTES (64L << 20)

typedef struct csv {
    const char *path;
    char *buf;
    size_t len, pos;
    long line;          /* current line (1-based) */
    char **field;       /* fields of the last record, NUL-terminated */
    size_t nfield, cap; /* fields in use, capacity */
    long record_line;   /* line the last record started on */
} csv;

static fm_status csv_open(csv *c, const char *path, fm_error *err)
{
    memset(c, 0, sizeof *c);
    c->path = path;
    c->line = 1;
    FILE *f = fopen(path, "rb");
    if (!f)
        return fm_error_set(err, FM_ERR_IO, path, 0, "cannot open: %s", strerror(errno));
    fm_status st = FM_OK;
    if (fseek(f, 0, SEEK_END) != 0) {
        st = fm_error_set(err, FM_ERR_IO, path, 0, "cannot read");
    } else {
        long n = ftell(f);
        if (n < 0 || n > CSV_MAX_BYTES) {
            st = fm_error_set(err, FM_ERR_IO, path, 0, "cannot read (or larger than %ld bytes)",
                              CSV_MAX_BYTES);
        } else if (!(c->buf = malloc((size_t)n + 1))) {
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        } else {
            rewind(f);
            c->len = fread(c->buf, 1, (size_t)n, f);
            if (c->len != (size_t)n || ferror(f))
                st = fm_error_set(err, FM_ERR_IO, path, 0, "read failed");
        }
    }
    fclose(f);
    if (st == FM_OK && c->len >= 3 && !memcmp(c->buf, "\xEF\xBB\xBF", 3))
        c->pos = 3;
    return st;
}

static void csv_clear_fields(csv *c)
{
    for (size_t i = 0; i < c->nfield; i++)
        free(c->field[i]);
    c->nfield = 0;
}

static void csv_close(csv *c)
{
    csv_clear_fields(c);
    free(c->field);
    free(c->buf);
}

static int push_field(csv *c, const char *s, size_t n)
{
    if (c->nfield == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 32;
        char **nf = realloc(c->field, cap * sizeof *nf);
        if (!nf)
            return -1;
        c->field = nf;
        c->cap = cap;
    }
    char *f = malloc(n + 1);
    if (!f)
        return -1;
    memcpy(f, s, n);
    f[n] = 0;
    c->field[c->nfield++] = f;
    return 0;
}

/* Consumes a line end at pos (LF, CRLF or CR); 1 if there was one. */
static int eat_eol(csv *c)
{
    if (c->pos < c->len && c->buf[c->pos] == '\r') {
        c->pos++;
        if (c->pos < c->len && c->buf[c->pos] == '\n')
            c->pos++;
        c->line++;
        return 1;
    }
    if (c->pos < c->len && c->buf[c->pos] == '\n') {
        c->pos++;
        c->line++;
        return 1;
    }
    return 0;
}

/* The next record into c->field: 1, 0 at the end of the file, or an
 * error status (negated) with err set. Blank lines are skipped. */
static int csv_next(csv *c, fm_error *err)
{
    csv_clear_fields(c);
    while (c->pos < c->len && eat_eol(c))
        ;
    if (c->pos >= c->len)
        return 0;
    c->record_line = c->line;
    /* Quoted text is unescaped in place: the buffer is ours and a field
     * never grows by unescaping. */
    for (;;) {
        char *out = c->buf + c->pos, *w = out;
        if (c->buf[c->pos] == '"') {
            long qline = c->line;
            c->pos++;
            for (;;) {
                if (c->pos >= c->len) {
                    fm_error_set(err, FM_ERR_PARSE, c->path, qline, "quoted field never closed");
                    return -FM_ERR_PARSE;
                }
                char ch = c->buf[c->pos];
                if (ch == '"') {
                    if (c->pos + 1 < c->len && c->buf[c->pos + 1] == '"') {
                        *w++ = '"';
                        c->pos += 2;
                        continue;
                    }
                    c->pos++;
                    break;
                }
                if (ch == '\n' || (ch == '\r' && !(c->pos + 1 < c->len && c->buf[c->pos + 1] == '\n')))
                    c->line++;
                *w++ = ch;
                c->pos++;
            }
            if (c->pos < c->len && c->buf[c->pos] != ',' && c->buf[c->pos] != '\n' &&
                c->buf[c->pos] != '\r') {
                fm_error_set(err, FM_ERR_PARSE, c->path, c->line,
                             "text after the closing quote of field %zu", c->nfield + 1);
                return -FM_ERR_PARSE;
            }
        } else {
            while (c->pos < c->len && c->buf[c->pos] != ',' && c->buf[c->pos] != '\n' &&
                   c->buf[c->pos] != '\r')
                *w++ = c->buf[c->pos++];
        }
        if (push_field(c, out, (size_t)(w - out)) != 0) {
            fm_error_set(err, FM_ERR_NOMEM, c->path, c->line, "out of memory");
            return -FM_ERR_NOMEM;
        }
        if (c->pos < c->len && c->buf[c->pos] == ',') {
            c->pos++;
            continue;
        }
        eat_eol(c);
        return 1;
    }
}

/* Field text without surrounding blanks (in place). */
static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    size_t n = strlen(s);
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t'))
        s[--n] = 0;
    return s;
}

/* 0 and *v if s is one finite decimal number (C locale syntax). */
static int parse_number(const char *s, double *v)
{
    if (!*s)
        return -1;
    char *end;
    errno = 0;
    double d = strtod(s, &end);
    if (end == s || *end || errno == ERANGE || !isfinite(d))
        return -1;
    *v = d;
    return 0;
}

/* Length of name without a trailing "_<digits>m", or 0 if it has none. */
static size_t strip_resolution(const char *name)
{
    size_t n = strlen(name);
    if (n < 4 || name[n - 1] != 'm')
        return 0;
    size_t k = n - 1;
    while (k > 0 && isdigit((unsigned char)name[k - 1]))
        k--;
    if (k == n - 1 || k == 0 || name[k - 1] != '_')
        return 0;
    return k - 1;
}

/* ---- CFM metadata ---- */

typedef struct md_row {
    char *name, *sense;
} md_row;

struct fm_metadata {
    md_row *row; /* sorted by name */
    size_t n;
};

static int row_cmp(const void *a, const void *b)
{
    return strcmp(((const md_row *)a)->name, ((const md_row *)b)->name);
}

void fm_metadata_destroy(fm_metadata *m)
{
    if (!m)
        return;
    for (size_t i = 0; i < m->n; i++) {
        free(m->row[i].name);
        free(m->row[i].sense);
    }
    free(m->row);
    free(m);
}

size_t fm_metadata_count(const fm_metadata *m) { return m ? m->n : 0; }

fm_status fm_metadata_read(const char *path, fm_metadata **out, fm_error *err)
{
    *out = NULL;
    csv c;
    fm_status st = csv_open(&c, path, err);
    fm_metadata *m = calloc(1, sizeof *m);
    size_t cap = 0;
    if (st == FM_OK && !m)
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    long name_col = -1, sense_col = -1, ncols = 0;
    int r = 0;
    if (st == FM_OK) {
        r = csv_next(&c, err);
        if (r < 0)
            st = (fm_status)-r;
        else if (r == 0)
            st = fm_error_set(err, FM_ERR_PARSE, path, 0, "empty file");
    }
    if (st == FM_OK) {
        ncols = (long)c.nfield;
        for (size_t k = 0; k < c.nfield; k++) {
            const char *h = trim(c.field[k]);
            if (name_col < 0 && strstr(h, "Fault Object Name"))
                name_col = (long)k;
            if (sense_col < 0 && !strcmp(h, "Slip Sense"))
                sense_col = (long)k;
        }
        if (name_col < 0 || sense_col < 0)
            st = fm_error_set(err, FM_ERR_PARSE, path, c.record_line,
                              "header has no '%s' column", name_col < 0 ? "Fault Object Name"
                                                                        : "Slip Sense");
    }
    while (st == FM_OK && (r = csv_next(&c, err)) == 1) {
        int title = 1;
        for (size_t k = 1; k < c.nfield; k++)
            if (*trim(c.field[k]))
                title = 0;
        if (title)
            continue;
        if ((long)c.nfield != ncols) {
            st = fm_error_set(err, FM_ERR_PARSE, path, c.record_line,
                              "%zu fields where the header has %ld", c.nfield, ncols);
            break;
        }
        const char *name = trim(c.field[name_col]);
        if (!*name) {
            st = fm_error_set(err, FM_ERR_PARSE, path, c.record_line, "fault name is empty");
            break;
        }
        if (m->n == cap) {
            cap = cap ? 2 * cap : 512;
            md_row *nr = realloc(m->row, cap * sizeof *nr);
            if (!nr) {
                st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
                break;
            }
            m->row = nr;
        }
        md_row row = {strdup(name), strdup(trim(c.field[sense_col]))};
        if (!row.name || !row.sense) {
            free(row.name);
            free(row.sense);
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
            break;
        }
        m->row[m->n++] = row;
    }
    if (st == FM_OK && r < 0)
        st = (fm_status)-r;
    csv_close(&c);
    if (st != FM_OK) {
        fm_metadata_destroy(m);
        return st;
    }
    if (m->n)
        qsort(m->row, m->n, sizeof *m->row, row_cmp);
    /* A name twice with different senses would make the lookup depend on
     * the sort; the CFM table has none, so it is an error. */
    for (size_t i = 1; i < m->n; i++)
        if (!strcmp(m->row[i].name, m->row[i - 1].name) &&
            strcmp(m->row[i].sense, m->row[i - 1].sense)) {
            st = fm_error_set(err, FM_ERR_PARSE, path, 0,
                              "fault '%s' listed twice with different slip senses",
                              m->row[i].name);
            fm_metadata_destroy(m);
            return st;
        }
    *out = m;
    return FM_OK;
}

static const md_row *md_find(const fm_metadata *m, const char *name, size_t len)
{
    size_t lo = 0, hi = m->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        const char *s = m->row[mid].name;
        int c = strncmp(s, name, len);
        if (c == 0 && s[len])
            c = 1;
        if (c == 0)
            return &m->row[mid];
        if (c < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return NULL;
}

const char *fm_metadata_slip_sense(const fm_metadata *m, const char *name)
{
    if (!m || !name)
        return NULL;
    const md_row *r = md_find(m, name, strlen(name));
    size_t k;
    if (!r && (k = strip_resolution(name)) > 0)
        r = md_find(m, name, k);
    return r ? r->sense : NULL;
}

int fm_slip_sense_rake(const char *code, double *rake)
{
    static const struct {
        const char *code;
        double rake;
    } table[] = {
        {"rlss", 180},          {"llss", 0},           {"r", 90},
        {"t", 90},              {"n", -90},            {"orlr", 135},
        {"ollr", 45},           {"orln", -135},        {"olln", -45},
        {"right-lateral", 180}, {"left-lateral", 0},   {"reverse", 90},
        {"thrust", 90},         {"normal", -90},       {"strike-slip", 180},
    };
    if (!code)
        return -1;
    while (*code == ' ')
        code++;
    size_t n = strlen(code);
    while (n && code[n - 1] == ' ')
        n--;
    for (size_t i = 0; i < sizeof table / sizeof *table; i++) {
        size_t m = strlen(table[i].code);
        if (m != n)
            continue;
        size_t k = 0;
        while (k < n && tolower((unsigned char)code[k]) == table[i].code[k])
            k++;
        if (k == n) {
            *rake = table[i].rake;
            return 0;
        }
    }
    return -1;
}

/* ---- --slip CSV ---- */

typedef struct slip_rule {
    char *pattern;
    int glob;
    int has_rake, has_rate;
    double rake, rate;
    long line;
} slip_rule;

struct fm_slip_table {
    slip_rule *rule; /* file order */
    size_t n;
};

void fm_slip_table_destroy(fm_slip_table *t)
{
    if (!t)
        return;
    for (size_t i = 0; i < t->n; i++)
        free(t->rule[i].pattern);
    free(t->rule);
    free(t);
}

fm_status fm_slip_table_read(const char *path, fm_slip_table **out, fm_error *err)
{
    *out = NULL;
    csv c;
    fm_status st = csv_open(&c, path, err);
    fm_slip_table *t = calloc(1, sizeof *t);
    if (st == FM_OK && !t)
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    size_t cap = 0;
    int r = 0, first = 1;
    while (st == FM_OK && (r = csv_next(&c, err)) == 1) {
        const char *pat = trim(c.field[0]);
        if (pat[0] == '#')
            continue;
        size_t nf = c.nfield;
        while (nf > 3 && !*trim(c.field[nf - 1]))
            nf--; /* spreadsheets pad rows with empty cells */
        if (nf != 3) {
            st = fm_error_set(err, FM_ERR_PARSE, path, c.record_line,
                              "%zu fields; expected pattern,rake,slip_rate (mm/yr)", nf);
            break;
        }
        const char *rk = trim(c.field[1]), *rt = trim(c.field[2]);
        slip_rule rule = {0};
        rule.line = c.record_line;
        rule.has_rake = *rk != 0;
        rule.has_rate = *rt != 0;
        if (rule.has_rake && parse_number(rk, &rule.rake) != 0) {
            if (first) {
                first = 0;
                continue; /* header row */
            }
            st = fm_error_set(err, FM_ERR_PARSE, path, c.record_line,
                              "rake '%s' is not a number (degrees)", rk);
            break;
        }
        first = 0;
        if (rule.has_rate && (parse_number(rt, &rule.rate) != 0 || rule.rate < 0)) {
            st = fm_error_set(err, FM_ERR_PARSE, path, c.record_line,
                              "slip rate '%s' is not a number >= 0 (mm/yr)", rt);
            break;
        }
        if (!*pat) {
            st = fm_error_set(err, FM_ERR_PARSE, path, c.record_line, "empty fault name or pattern");
            break;
        }
        rule.glob = strpbrk(pat, "*?[") != NULL;
        if (t->n == cap) {
            cap = cap ? 2 * cap : 64;
            slip_rule *nr = realloc(t->rule, cap * sizeof *nr);
            if (!nr) {
                st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
                break;
            }
            t->rule = nr;
        }
        if (!(rule.pattern = strdup(pat))) {
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
            break;
        }
        t->rule[t->n++] = rule;
    }
    if (st == FM_OK && r < 0)
        st = (fm_status)-r;
    csv_close(&c);
    if (st != FM_OK) {
        fm_slip_table_destroy(t);
        return st;
    }
    *out = t;
    return FM_OK;
}

/* Does rule r match name (as it is, or without its resolution suffix)? */
static int rule_matches(const slip_rule *r, const char *name, const char *base)
{
    if (!r->glob)
        return !strcmp(r->pattern, name) || (base && !strcmp(r->pattern, base));
    return fnmatch(r->pattern, name, 0) == 0 || (base && fnmatch(r->pattern, base, 0) == 0);
}

static const slip_rule *find_rule(const fm_slip_table *t, const char *name)
{
    if (!t)
        return NULL;
    char *base = NULL;
    size_t k = strip_resolution(name);
    if (k && (base = malloc(k + 1))) {
        memcpy(base, name, k);
        base[k] = 0;
    }
    const slip_rule *hit = NULL;
    for (int pass = 0; pass < 2 && !hit; pass++)
        for (size_t i = 0; i < t->n && !hit; i++)
            if (t->rule[i].glob == pass && rule_matches(&t->rule[i], name, base))
                hit = &t->rule[i];
    free(base);
    return hit;
}

const char *fm_slip_source_name(fm_slip_source s)
{
    return s == FM_SLIP_FROM_CSV        ? "csv"
           : s == FM_SLIP_FROM_METADATA ? "metadata"
           : s == FM_SLIP_FROM_SETTINGS ? "settings"
                                        : "default";
}

/* Into (-180, 180]. */
static double normalise_rake(double r)
{
    r = fmod(r, 360.0);
    if (r > 180)
        r -= 360;
    else if (r <= -180)
        r += 360;
    return r;
}

void fm_slip_assign(const char *const *names, size_t n, const fm_metadata *md,
                    const fm_slip_table *t, fm_fault_slip *out)
{
    for (size_t i = 0; i < n; i++) {
        fm_fault_slip *s = &out[i];
        s->rake = FM_SLIP_DEFAULT_RAKE;
        s->slip_rate_mm_yr = FM_SLIP_DEFAULT_RATE_MM_YR;
        s->rake_from = s->rate_from = FM_SLIP_FROM_DEFAULT;
        s->slip_sense = fm_metadata_slip_sense(md, names[i]);
        s->csv_line = 0;
        double rk;
        if (s->slip_sense && fm_slip_sense_rake(s->slip_sense, &rk) == 0) {
            s->rake = rk;
            s->rake_from = FM_SLIP_FROM_METADATA;
        }
        const slip_rule *r = find_rule(t, names[i]);
        if (r) {
            s->csv_line = r->line;
            if (r->has_rake) {
                s->rake = r->rake;
                s->rake_from = FM_SLIP_FROM_CSV;
            }
            if (r->has_rate) {
                s->slip_rate_mm_yr = r->rate;
                s->rate_from = FM_SLIP_FROM_CSV;
            }
        }
        s->rake = normalise_rake(s->rake);
    }
}

void fm_slip_override(fm_fault_slip *s, const double *rake, const double *rate_mm_yr,
                      fm_slip_source from)
{
    if (rake) {
        s->rake = normalise_rake(*rake);
        s->rake_from = from;
    }
    if (rate_mm_yr) {
        s->slip_rate_mm_yr = *rate_mm_yr;
        s->rate_from = from;
    }
}
