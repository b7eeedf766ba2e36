/* faultmesh core: all-or-nothing output files.
 *
 * Every output is written to a temporary file beside its destination
 * (hidden: `.NAME.tmp.PID.N`) and renamed over it only once complete and
 * flushed, so a failure or an interrupted run never leaves a truncated
 * file under the final name. The temporary names of writes in progress
 * are registered, so that a signal handler can remove them
 * (fm_atomic_remove_pending) before the process ends. */
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

/* For a writer whose library creates the file itself from a name
 * (netCDF): a temporary name beside path with nothing under it yet,
 * registered like fm_atomic_open's. NULL when out of memory (err set). */
typedef struct fm_atomic_name fm_atomic_name;
fm_atomic_name *fm_atomic_name_create(const char *path, fm_error *err);
const char *fm_atomic_name_tmp(const fm_atomic_name *n);
/* Bracket the call that creates the file under the temporary name, so that
 * a signal handler running meanwhile in another thread waits for it and
 * removes it: signals are blocked in this thread in between, which should
 * therefore be short. creating fails (err set, "interrupted") when
 * fm_atomic_remove_pending has run: then create nothing, and do not call
 * created. */
fm_status fm_atomic_name_creating(fm_atomic_name *n, fm_error *err);
void fm_atomic_name_created(fm_atomic_name *n);
/* Syncs the file written under the temporary name (unless synced says it
 * is already) and renames it to path; frees n. On failure the temporary is
 * removed. */
fm_status fm_atomic_name_commit(fm_atomic_name *n, int synced, fm_error *err);
/* Removes whatever is under the temporary name and frees n. NULL is ignored. */
void fm_atomic_name_abort(fm_atomic_name *n);

/* Removes the temporary file of every write in progress in any thread.
 * Async-signal-safe (no locks, no allocation): meant for a handler of a
 * fatal signal, after which the process must end. Writes opened after it
 * fail and leave nothing. */
void fm_atomic_remove_pending(void);
/* Whether fm_atomic_remove_pending has run. */
int fm_atomic_interrupted(void);

/* dir "/" name, with no doubled '/' (malloc'ed; NULL when out of memory). */
char *fm_path_join(const char *dir, const char *name);

/* Creates directory path (and its parents) if missing. */
fm_status fm_mkdir_p(const char *path, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
