/** @file
 * faultmesh: status codes and errors, shared by the whole library.
 *
 * Library code never exits or prints: a failing call returns a non-zero
 * fm_status and, when the caller passed an fm_error, fills it with a
 * message of the form "FILE:LINE: what is wrong" (or "FILE: ..." when no
 * line applies), ready to be shown to a user as is. The codes' values and
 * fm_error's layout are part of the ABI: codes are only ever added at the
 * end, never renumbered. */
#ifndef FM_STATUS_H
#define FM_STATUS_H

#include "fm_export.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum fm_status {
    FM_OK = 0,
    FM_ERR_IO = 1,        /**< cannot open, read, write or rename a file */
    FM_ERR_PARSE = 2,     /**< malformed input text */
    FM_ERR_NOMEM = 3,     /**< allocation failed */
    FM_ERR_INVALID = 4,   /**< bad argument or option */
    FM_ERR_TOPOLOGY = 5,  /**< input whose topology cannot be repaired */
    FM_ERR_NUMERIC = 6,   /**< NaN/inf or a numerical failure */
    FM_ERR_CANCELLED = 7  /**< the caller cancelled (fm_run_interrupt, a progress callback) */
} fm_status;

#define FM_ERROR_MESSAGE_MAX 768

typedef struct fm_error {
    fm_status code;
    long line;                          /**< 0 when not tied to a line */
    char message[FM_ERROR_MESSAGE_MAX]; /**< "FILE:LINE: what is wrong" */
} fm_error;

/** Short name of a status ("parse error", ...). Never NULL. */
FM_API const char *fm_status_string(fm_status s);

/** Resets err to FM_OK with an empty message. */
FM_API void fm_error_clear(fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
