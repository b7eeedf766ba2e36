/* faultmesh core: status codes and error reporting shared by every stage.
 *
 * Library code never exits or prints: a failing call returns a non-zero
 * fm_status and, when the caller passed an fm_error, fills it with a
 * message of the form "FILE:LINE: what is wrong" (or "FILE: ..." when no
 * line applies), ready to be shown to a user as is. */
#ifndef FM_CORE_H
#define FM_CORE_H

#include <stddef.h>

/* fm_status, fm_error and the version are installed (include/faultmesh);
 * fm_error_set is how the library fills an fm_error, and stays inside. */
#include "fm_status.h"
#include "fm_version.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fills err (if not NULL) and returns code, so callers can write
 * `return fm_error_set(err, FM_ERR_PARSE, path, line, "...", ...);`.
 * file may be NULL; line <= 0 omits the line number. */
fm_status fm_error_set(fm_error *err, fm_status code, const char *file, long line,
                       const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

#ifdef __cplusplus
}
#endif
#endif
