/* faultmesh core: status codes and error reporting shared by every stage.
 *
 * Library code never exits or prints: a failing call returns a non-zero
 * fm_status and, when the caller passed an fm_error, fills it with a
 * message of the form "FILE:LINE: what is wrong" (or "FILE: ..." when no
 * line applies), ready to be shown to a user as is. */
#ifndef FM_CORE_H
#define FM_CORE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FM_VERSION_STRING "0.1.0"

typedef enum fm_status {
    FM_OK = 0,
    FM_ERR_IO,        /* cannot open, read, write or rename a file */
    FM_ERR_PARSE,     /* malformed input text */
    FM_ERR_NOMEM,     /* allocation failed */
    FM_ERR_INVALID,   /* bad argument or option */
    FM_ERR_TOPOLOGY,  /* input whose topology cannot be repaired */
    FM_ERR_NUMERIC    /* NaN/inf or a numerical failure */
} fm_status;

#define FM_ERROR_MESSAGE_MAX 768

typedef struct fm_error {
    fm_status code;
    long line;                          /* 0 when not tied to a line */
    char message[FM_ERROR_MESSAGE_MAX]; /* "FILE:LINE: what is wrong" */
} fm_error;

/* Short name of a status ("parse error", ...). Never NULL. */
const char *fm_status_string(fm_status s);

/* Fills err (if not NULL) and returns code, so callers can write
 * `return fm_error_set(err, FM_ERR_PARSE, path, line, "...", ...);`.
 * file may be NULL; line <= 0 omits the line number. */
fm_status fm_error_set(fm_error *err, fm_status code, const char *file, long line,
                       const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* Resets err to FM_OK with an empty message. */
void fm_error_clear(fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
