/** @file
 * faultmesh: the work of `faultmesh info` and `faultmesh fit` as calls.
 *
 * Each is an object made with the defaults, told options in the command
 * line's words (as fm_run_take_option tells a run), then run over a list
 * of TSurf files (fm_run_list_inputs makes one from files and folders).
 * What they report goes to the stream the caller gives (text, or info's
 * JSON, a stable interface whose keys are only ever added); what goes
 * wrong with a file goes to the log callback as an FM_LOG_ERROR record,
 * and the file counts as failed while the others go on.
 *
 * @code
 *   fm_info *info = fm_info_create();
 *   const char *argv[] = {"--json"};
 *   int i = 0;
 *   fm_info_take_option(info, 1, argv, &i, &err);
 *   size_t failed = fm_info_write(info, files, nfiles, stdout);
 *   fm_info_destroy(info);
 * @endcode */
#ifndef FM_COMMANDS_H
#define FM_COMMANDS_H

#include <stddef.h>
#include <stdio.h>

#include "fm_export.h"
#include "fm_run.h"
#include "fm_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_info fm_info;       /**< `faultmesh info`: read, repair, describe */
typedef struct fm_fit_job fm_fit_job; /**< `faultmesh fit`: fitted models and their files */

/** The defaults (text, the repair's defaults); NULL when out of memory. */
FM_API fm_info *fm_info_create(void);
FM_API void fm_info_destroy(fm_info *info); /**< NULL ignored */
/** "--json" and the repair options ("--weld-tol" M, ...), as
 * fm_run_take_option: 1 taken (*i on its last word), 0 not one of them,
 * -1 a bad value (err says why). */
FM_API int fm_info_take_option(fm_info *info, int argc, const char *const *argv, int *i,
                               fm_error *err);
/** Where each file that cannot be read or repaired is said (NULL: nowhere). */
FM_API void fm_info_set_log(fm_info *info, fm_log_fn fn, void *user);
/** Reads and repairs every file and describes it on out (per object and
 * per sheet: parts, vertices, triangles, area, components, loops, holes,
 * non-manifold edges, welded duplicates, z range, edge lengths, angles;
 * a summary line when there are several files), or the JSON document of
 * them all. The number of files that failed. */
FM_API size_t fm_info_write(fm_info *info, const char *const *files, size_t nfiles, FILE *out);

/** The defaults (the fit's and the repair's); NULL when out of memory. */
FM_API fm_fit_job *fm_fit_job_create(void);
FM_API void fm_fit_job_destroy(fm_fit_job *job); /**< NULL ignored */
/** The fit's options ("--extend" D, "--knot-spacing" M, "--smoothing" L,
 * "--degree" N, "--target-rms" M, "--target-max" M, "--trim-tol" M,
 * "--trim-max-dev" M, "--corner-angle" DEG) and the repair options, as
 * fm_run_take_option. */
FM_API int fm_fit_job_take_option(fm_fit_job *job, int argc, const char *const *argv, int *i,
                                  fm_error *err);
/** Where each fault that fails and each file not written is said. */
FM_API void fm_fit_job_set_log(fm_fit_job *job, fm_log_fn fn, void *user);
/** Fits every sheet of every fault of the files and writes per fault
 * dir/NAME.model.json, NAME.igs (IGES 5.3) and NAME.vtu, and
 * dir/fit_report.json (dir created if missing); a line per fault and the
 * summary line on out (may be NULL). FM_OK with *nfailed the faults that
 * failed (a file that cannot be read is one, fit_report.json not written
 * one more); an error when dir or fit_report.json cannot be made. */
FM_API fm_status fm_fit_job_write(fm_fit_job *job, const char *dir, const char *const *files,
                                  size_t nfiles, FILE *out, size_t *nfailed, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
