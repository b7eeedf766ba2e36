/* faultmesh io: the slip of each fault (rake, slip rate) for the simulator
 * formats, from the CFM metadata table and a user CSV.
 *
 * Both files are CSV (RFC 4180 as spreadsheets write it): fields split at
 * commas, a field in double quotes may hold commas, line breaks and ""
 * for a quote; LF, CRLF or CR line ends; a UTF-8 byte-order mark is
 * skipped; blank lines are skipped. Errors name the file and line.
 *
 * CFM metadata (CFM5.3_Metadata.csv): a header row naming the columns, of
 * which "CFM5.3 Fault Object Name" (any header containing "Fault Object
 * Name") and "Slip Sense" are required. Rows whose fields after the first
 * are all empty are section titles ("SAN ANDREAS FAULT SYSTEM,,,") and
 * skipped. Slip-sense codes and the rake (Aki & Richards: 0 left-lateral,
 * 180 right-lateral, 90 reverse, -90 normal) they stand for:
 *   rlss 180, llss 0, r 90, t 90 (thrust), n -90,
 *   orlr 135, ollr 45, orln -135, olln -45 (oblique: right/left-lateral
 *   with reverse/normal, the two in equal parts);
 * the long forms right-lateral, left-lateral, reverse, thrust, normal and
 * strike-slip (taken as right-lateral) are accepted too, any case.
 *
 * Slip CSV (--slip): one row per rule, `pattern,rake,slip_rate`:
 *   pattern    a fault name or a shell-style glob (fnmatch: * ? [...]);
 *   rake       degrees, Aki & Richards; empty: the metadata's (or default)
 *   slip_rate  mm/yr (what geologists tabulate); empty: the default.
 * A first row whose rake field is not a number is a header. Lines starting
 * with '#' are comments. A rule whose pattern has no glob character
 * matches that name exactly and wins over any glob; otherwise the first
 * matching glob row in file order wins, so put "*" last as a catch-all.
 *
 * A fault name matches a metadata row or a slip rule either as it is or
 * with a trailing resolution suffix "_<digits>m" removed: the CFM's
 * regularised files are named after the object with "_500m" appended. */
#ifndef FM_METADATA_H
#define FM_METADATA_H

#include <stddef.h>

#include "fm_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Defaults when nothing gives a value (see fm_slip_assign). */
#define FM_SLIP_DEFAULT_RAKE 180.0    /* right-lateral: the most common CFM sense */
#define FM_SLIP_DEFAULT_RATE_MM_YR 0.0 /* unknown: no loading */

/* mm/yr to m/s, with the Julian year (365.25 d) of the IAU. */
#define FM_MM_PER_YEAR_TO_M_PER_S (1e-3 / (365.25 * 86400.0))

typedef struct fm_metadata fm_metadata;
typedef struct fm_slip_table fm_slip_table;

fm_status fm_metadata_read(const char *path, fm_metadata **out, fm_error *err);
void fm_metadata_destroy(fm_metadata *m);
/* Fault rows read (title rows not counted). */
size_t fm_metadata_count(const fm_metadata *m);
/* Slip-sense code of the named fault ("" when its cell is empty), or NULL
 * when the name is not in the table. */
const char *fm_metadata_slip_sense(const fm_metadata *m, const char *name);

/* Rake of a slip-sense code (see above): 0 and *rake set, or -1 if the
 * code is empty or unknown. */
int fm_slip_sense_rake(const char *code, double *rake);

fm_status fm_slip_table_read(const char *path, fm_slip_table **out, fm_error *err);
void fm_slip_table_destroy(fm_slip_table *t);

typedef enum fm_slip_source {
    FM_SLIP_FROM_CSV = 0,  /* a --slip rule */
    FM_SLIP_FROM_METADATA, /* the metadata's slip sense */
    FM_SLIP_FROM_DEFAULT,  /* FM_SLIP_DEFAULT_* */
    FM_SLIP_FROM_SETTINGS  /* a project's settings file, over all of the above */
} fm_slip_source;

/* "csv", "metadata", "default", "settings" */
const char *fm_slip_source_name(fm_slip_source s);

typedef struct fm_fault_slip {
    double rake;            /* degrees, in (-180, 180] */
    double slip_rate_mm_yr; /* >= 0 */
    fm_slip_source rake_from, rate_from;
    const char *slip_sense; /* metadata code (owned by the fm_metadata), NULL if not found */
    long csv_line;          /* line of the --slip rule used, 0 if none */
} fm_fault_slip;

/* Rake and slip rate of each of n faults: a --slip rule first (t may be
 * NULL), then the rake of the metadata's slip sense (md may be NULL),
 * then the defaults; rakes are normalised into (-180, 180]. */
void fm_slip_assign(const char *const *names, size_t n, const fm_metadata *md,
                    const fm_slip_table *t, fm_fault_slip *out);
/* Sets what a higher authority gives (rake when rake != NULL, slip rate
 * when rate != NULL), normalised as above, and records where from. */
void fm_slip_override(fm_fault_slip *s, const double *rake, const double *rate_mm_yr,
                      fm_slip_source from);

#ifdef __cplusplus
}
#endif
#endif
