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

/* Names inside files, for readers that keep a name short:
 * rsqsim-python-tools reads RSQSim section names as 50-character strings,
 * and many Exodus II readers keep 32 characters of an entity name.
 *
 * The rule, one for both: a name's bytes A-Z a-z 0-9 '.' '-' '_' are
 * kept and every run of other bytes becomes one '_' (one token, as the
 * simulator files' whitespace-separated columns need; an empty name gives
 * "_"). A token of at most max bytes not taken by an earlier name is the
 * name. Otherwise it is cut to max - 5 bytes and given '~' and four
 * base-36 digits [0-9a-z] of the FNV-1a hash of the full name (plus 1,
 * 2, ... until the result is not taken), so the short name of a long name
 * does not depend on the names around it unless two collide. */
#define FM_SECTION_NAME_MAX 50
#define FM_EXODUS_NAME_MAX 32

/* The one-token form of name (the rule above, without cutting),
 * malloc'ed; NULL when memory runs out. */
char *fm_section_name(const char *name);
/* The n short names of at most max (>= 6) bytes, unique, by the rule
 * above, as a malloc'ed array of malloc'ed strings; NULL when memory runs
 * out. */
char **fm_short_names(const char *const *names, size_t n, size_t max);
void fm_short_names_free(char **s, size_t n);

#ifdef __cplusplus
}
#endif
#endif
