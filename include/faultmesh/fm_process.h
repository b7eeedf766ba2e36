/** @file
 * faultmesh: what a program around the library does once per process.
 *
 * @code
 *   // in a handler of SIGINT/SIGTERM, then let the signal end the process
 *   fm_remove_pending_files();
 *   // before exit, after the last run
 *   fm_report_cleanup();
 * @endcode
 *
 * Every file the library writes is written under a temporary name and
 * renamed into place when complete, so no truncated file appears under a
 * real name; a program that is interrupted removes the temporaries of the
 * writes in progress with fm_remove_pending_files. */
#ifndef FM_PROCESS_H
#define FM_PROCESS_H

#include "fm_export.h"
#include "fm_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Removes the temporary file of every write in progress in any thread.
 * Async-signal-safe (no locks, no allocation): meant for a handler of a
 * fatal signal, after which the process must end. Writes opened after it
 * fail and leave nothing. */
FM_API void fm_remove_pending_files(void);

/** Creates the folder path and its parents where missing. */
FM_API fm_status fm_make_dirs(const char *path, fm_error *err);

/** Frees what cairo and fontconfig keep for the life of the process
 * (their font caches of report.html's pictures), which leak checkers
 * would report: call once before exit, after every run, when no thread
 * uses the library any more. */
FM_API void fm_report_cleanup(void);

#ifdef __cplusplus
}
#endif
#endif
