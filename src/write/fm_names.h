/* faultmesh write: file names from fault names, one rule for every command
 * that writes files per fault (remesh's NAME.ts, fit's NAME.model.json,
 * NAME.igs, NAME.vtu).
 *
 * A name's bytes A-Z a-z 0-9 '.' '-' '_' are kept, every run of other
 * bytes (spaces, punctuation, separators, each multi-byte UTF-8
 * character) becomes one '_', a leading '.' becomes '_' (no hidden files,
 * no "..") and the result is cut to 200 bytes; an empty name gives
 * "fault". If the stem then equals, ignoring ASCII case (macOS and Windows
 * file systems), one given before, "-2", "-3", ... is appended until it
 * does not. */
#ifndef FM_NAMES_H
#define FM_NAMES_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Longest stem before a "-N" suffix, in bytes. */
#define FM_STEM_MAX 200

typedef struct fm_namer fm_namer;

fm_namer *fm_namer_create(void);
void fm_namer_destroy(fm_namer *n);
/* The stem for the next fault called name (valid until fm_namer_destroy);
 * NULL when out of memory. */
const char *fm_namer_next(fm_namer *n, const char *name);

#ifdef __cplusplus
}
#endif
#endif
