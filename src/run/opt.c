/* fm_opt.h: options taken through a table, and the checks of their
 * values (the CLI's words since its first release). */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "fm_opt.h"

int fm_opt_take(const fm_opt_spec *table, size_t n, void *target, int argc,
                const char *const *argv, int *i, fm_error *err)
{
    const char *name = argv[*i];
    for (size_t k = 0; k < n; k++) {
        const fm_opt_spec *s = &table[k];
        if (strcmp(name, s->name) && !(s->alias && !strcmp(name, s->alias)))
            continue;
        fm_opt_arg a = {name, *i + 1 < argc ? argv[*i + 1] : NULL,
                        *i + 2 < argc ? argv[*i + 2] : NULL, 0};
        if (!s->takes_value)
            a.val = a.next = NULL;
        if (s->take(target, &a, err))
            return -1;
        *i += s->takes_value + a.extra;
        return 1;
    }
    return 0;
}

int fm_opt_missing(const char *opt, fm_error *err)
{
    fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s needs a value", opt);
    return -1;
}

/* A decimal number (strtod also takes hexadecimal, inf and nan) in
 * [lo, 1e12] (above lo when open); -1 after saying what it needs. */
static int number(const char *opt, const char *s, double lo, int open, const char *need,
                  double *out, fm_error *err)
{
    if (!s)
        return fm_opt_missing(opt, err);
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    int decimal = s[strspn(s, "0123456789.eE+-")] == '\0';
    if (!decimal || end == s || *end || errno || !(open ? v > lo : v >= lo) || v > 1e12) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s needs %s, got '%s'", opt, need, s);
        return -1;
    }
    *out = v;
    return 0;
}

int fm_opt_double(const char *opt, const char *s, double *out, fm_error *err)
{
    return number(opt, s, 0, 0, "a non-negative number", out, err);
}

int fm_opt_positive(const char *opt, const char *s, double *out, fm_error *err)
{
    return number(opt, s, 0, 1, "a positive number", out, err);
}

int fm_opt_size(const char *opt, const char *s, size_t *out, fm_error *err)
{
    if (!s)
        return fm_opt_missing(opt, err);
    char *end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (end == s || *end || errno || s[0] == '-') {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s needs a non-negative integer, got '%s'",
                     opt, s);
        return -1;
    }
    *out = (size_t)v;
    return 0;
}
