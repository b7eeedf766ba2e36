/* faultmesh core: all-or-nothing output files.
 *
 * Every output is written to a temporary file beside its destination and
 * renamed over it only once complete and flushed, so a failure or an
 * interrupted run never leaves a truncated file under the final name. */
#ifndef FM_ATOMIC_H
#define FM_ATOMIC_H

#include <stdio.h>

#include "fm_core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_atomic_file fm_atomic_file;

/* Opens a temporary file in the directory of path. NULL on failure (err set).
 * Safe to call from several threads at once (different paths). */
fm_atomic_file *fm_atomic_open(const char *path, fm_error *err);

/* The stream to write to. */
FILE *fm_atomic_stream(fm_atomic_file *f);

/* Flushes, syncs and renames the temporary file to its final name, then
 * frees f. On any failure the temporary is removed and nothing appears
 * under the final name. */
fm_status fm_atomic_commit(fm_atomic_file *f, fm_error *err);

/* Discards the temporary file and frees f. NULL is ignored. */
void fm_atomic_abort(fm_atomic_file *f);

/* Creates directory path (and its parents) if missing. */
fm_status fm_mkdir_p(const char *path, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
