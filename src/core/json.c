#include "fm_json.h"

#include <inttypes.h>
#include <math.h>

void fm_json_init(fm_json *j, FILE *fp)
{
    j->fp = fp;
    j->depth = 0;
    j->count[0] = 0;
    j->after_key = 0;
}

static void indent(fm_json *j)
{
    fputc('\n', j->fp);
    for (int i = 0; i < j->depth; i++)
        fputs("  ", j->fp);
}

/* Separator and indentation before a value or key at the current depth. */
static void before_item(fm_json *j)
{
    if (j->after_key) {
        j->after_key = 0;
        return;
    }
    if (j->depth > 0) {
        if (j->count[j->depth]++)
            fputc(',', j->fp);
        indent(j);
    }
}

static void open(fm_json *j, char c)
{
    before_item(j);
    fputc(c, j->fp);
    if (j->depth + 1 < FM_JSON_MAX_DEPTH)
        j->depth++;
    j->count[j->depth] = 0;
}

static void close(fm_json *j, char c)
{
    int had = j->count[j->depth];
    if (j->depth > 0)
        j->depth--;
    if (had)
        indent(j);
    fputc(c, j->fp);
    if (j->depth == 0)
        fputc('\n', j->fp);
}

void fm_json_begin_object(fm_json *j) { open(j, '{'); }
void fm_json_end_object(fm_json *j) { close(j, '}'); }
void fm_json_begin_array(fm_json *j) { open(j, '['); }
void fm_json_end_array(fm_json *j) { close(j, ']'); }

static void write_string(FILE *fp, const char *s)
{
    fputc('"', fp);
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        switch (*p) {
        case '"': fputs("\\\"", fp); break;
        case '\\': fputs("\\\\", fp); break;
        case '\n': fputs("\\n", fp); break;
        case '\r': fputs("\\r", fp); break;
        case '\t': fputs("\\t", fp); break;
        default:
            if (*p < 0x20)
                fprintf(fp, "\\u%04x", *p);
            else
                fputc(*p, fp);
        }
    }
    fputc('"', fp);
}

void fm_json_key(fm_json *j, const char *key)
{
    before_item(j);
    write_string(j->fp, key);
    fputs(": ", j->fp);
    j->after_key = 1;
}

void fm_json_string(fm_json *j, const char *s)
{
    before_item(j);
    write_string(j->fp, s ? s : "");
}

void fm_json_int(fm_json *j, int64_t v)
{
    before_item(j);
    fprintf(j->fp, "%" PRId64, v);
}

static void number(fm_json *j, double v, const char *fmt)
{
    before_item(j);
    if (!isfinite(v))
        fputs("null", j->fp);
    else
        fprintf(j->fp, fmt, v == 0.0 ? 0.0 : v); /* no "-0" */
}

void fm_json_number(fm_json *j, double v) { number(j, v, "%.10g"); }
void fm_json_number_exact(fm_json *j, double v) { number(j, v, "%.17g"); }

void fm_json_bool(fm_json *j, int v)
{
    before_item(j);
    fputs(v ? "true" : "false", j->fp);
}

void fm_json_null(fm_json *j)
{
    before_item(j);
    fputs("null", j->fp);
}

void fm_json_kv_string(fm_json *j, const char *key, const char *s)
{
    fm_json_key(j, key);
    fm_json_string(j, s);
}

void fm_json_kv_int(fm_json *j, const char *key, int64_t v)
{
    fm_json_key(j, key);
    fm_json_int(j, v);
}

void fm_json_kv_number(fm_json *j, const char *key, double v)
{
    fm_json_key(j, key);
    fm_json_number(j, v);
}

void fm_json_kv_bool(fm_json *j, const char *key, int v)
{
    fm_json_key(j, key);
    fm_json_bool(j, v);
}
