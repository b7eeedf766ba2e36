/* faultmesh CLI: progress of a long run on stderr.
 *
 * On a terminal, one bar redrawn in place (stage, count, share done, ETA);
 * otherwise plain log lines at each quarter of a stage and at its end, so
 * that a log file of a batch run stays readable. Quiet: nothing. Steps may
 * come from any thread; nothing here reaches an output file. */
#ifndef FM_PROGRESS_H
#define FM_PROGRESS_H

#include <stddef.h>
#include <stdio.h>

typedef struct progress progress;

typedef enum { PROGRESS_QUIET, PROGRESS_NORMAL, PROGRESS_VERBOSE } progress_level;

/* NULL when out of memory (every call then does nothing). A terminal is
 * told by isatty(fp), unless force_plain. */
progress *progress_create(FILE *fp, progress_level level, int force_plain);
void progress_destroy(progress *p);

/* Starts a stage of count items (what they are: unit, e.g. "files")
 * weighing weight in all (bytes of input, say: the ETA follows weight, as
 * large faults take longer). count 0: a stage of unknown length, shown
 * without bar or ETA. */
void progress_begin(progress *p, const char *stage, size_t count, const char *unit,
                    double weight);
/* One item done, of that weight. Thread-safe. */
void progress_step(progress *p, double weight);
/* Sets how many items the stage has (when known only once it has begun)
 * and how many are done. Thread-safe. */
void progress_set(progress *p, size_t done, size_t count, const char *unit);
/* Ends the stage: its time, on the bar's line or as a log line. Returns
 * the stage's wall time in seconds. */
double progress_end(progress *p);

#endif
