/** @file
 * faultmesh synth: the synthetic fault system, written as TSurf files.
 *
 * A dozen faults with known analytic surfaces (gaps, overshoots, holes,
 * splays, seams): the embedded default for new users (`faultmesh demo`)
 * and the ground truth of the tests.
 *
 * @code
 *   fm_error err;
 *   fm_synth *s = NULL;
 *   if (fm_synth_generate(NULL, &s, &err) == FM_OK)   // the defaults
 *       fm_synth_write(s, "input", &err);
 *   fm_synth_destroy(s);
 * @endcode */
#ifndef FM_SYNTHETIC_H
#define FM_SYNTHETIC_H

#include <stddef.h>

#include "fm_export.h"
#include "fm_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_synth fm_synth;           /**< the fault system in memory */
typedef struct fm_synth_spec fm_synth_spec; /**< how it is made */

/** The defaults: 500 m triangles, seed 1; NULL when out of memory. */
FM_API fm_synth_spec *fm_synth_spec_create(void);
FM_API void fm_synth_spec_destroy(fm_synth_spec *spec); /**< NULL ignored */
/** The option argv[*i] names, in the command line's words ("--spacing"
 * M, 20 to 20000; "--seed" N), as fm_run_take_option takes a run's: 1,
 * *i on its value; 0: not one of them; -1: a bad value (err says why). */
FM_API int fm_synth_spec_take_option(fm_synth_spec *spec, int argc, const char *const *argv,
                                     int *i, fm_error *err);

/** Builds the fault system in memory (the same for the same spec; NULL:
 * the defaults). */
FM_API fm_status fm_synth_generate(const fm_synth_spec *spec, fm_synth **out, fm_error *err);
FM_API void fm_synth_destroy(fm_synth *s); /**< NULL ignored */
FM_API size_t fm_synth_nfaults(const fm_synth *s);
/** Fault i's name (its file is NAME.ts). */
FM_API const char *fm_synth_fault_name(const fm_synth *s, size_t i);
/** One line on what fault i exercises ("gap of 300 m to ...", ...). */
FM_API const char *fm_synth_fault_description(const fm_synth *s, size_t i);
/** Writes one NAME.ts per fault and faults.json (the analytic descriptions
 * and the expected relations: gaps, overshoots, holes, seams) into dir
 * (created if missing), atomically per file. */
FM_API fm_status fm_synth_write(const fm_synth *s, const char *dir, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
