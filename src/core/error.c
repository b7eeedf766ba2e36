#include "fm_core.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const char *fm_status_string(fm_status s)
{
    switch (s) {
    case FM_OK: return "ok";
    case FM_ERR_IO: return "i/o error";
    case FM_ERR_PARSE: return "parse error";
    case FM_ERR_NOMEM: return "out of memory";
    case FM_ERR_INVALID: return "invalid argument";
    case FM_ERR_TOPOLOGY: return "topology error";
    case FM_ERR_NUMERIC: return "numerical error";
    case FM_ERR_CANCELLED: return "cancelled";
    }
    return "unknown error";
}

void fm_error_clear(fm_error *err)
{
    if (!err)
        return;
    err->code = FM_OK;
    err->line = 0;
    err->message[0] = '\0';
}

fm_status fm_error_set(fm_error *err, fm_status code, const char *file, long line,
                       const char *fmt, ...)
{
    if (!err)
        return code;
    err->code = code;
    err->line = line;
    size_t n = 0;
    int k = 0;
    if (file && line > 0)
        k = snprintf(err->message, sizeof err->message, "%s:%ld: ", file, line);
    else if (file)
        k = snprintf(err->message, sizeof err->message, "%s: ", file);
    if (k > 0)
        n = (size_t)k < sizeof err->message ? (size_t)k : sizeof err->message - 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message + n, sizeof err->message - n, fmt, ap);
    va_end(ap);
    return code;
}
