/* faultmesh run: a project's settings file (TOML, the subset a settings
 * file needs), read by fm_run_read_settings (the CLI's --config) and by
 * any program that wants the same files.
 *
 *   key = "string" | number | true | false | ["string", ...]
 *   [[fault]]            a per-fault section (array of tables)
 *   # comment
 *
 * Top-level keys are kept as read (fm_run_read_settings applies them as
 * options, so they are checked as the options are); [[fault]] sections carry
 * `match` (a shell pattern or a list of them, on the fault name) and the
 * per-fault settings, checked when read and handed to a run as its rules
 * (fm_settings_rules). Every error names the file and line. Part of the
 * build tree's interface (fm_run_options.h), not installed. */
#ifndef FM_SETTINGS_H
#define FM_SETTINGS_H

#include <stddef.h>

#include "fm_run_options.h"

typedef enum {
    FM_SETTINGS_STRING,
    FM_SETTINGS_NUMBER,
    FM_SETTINGS_BOOL,
    FM_SETTINGS_ARRAY
} fm_settings_type;

typedef struct fm_settings_entry {
    char *key;
    fm_settings_type type;
    char *text;    /* string: its value; number: as written; bool: "true"/"false" */
    char **items;  /* array of strings */
    size_t nitems;
    long line;
} fm_settings_entry;

typedef struct fm_settings_section {
    fm_settings_entry *e;
    size_t n;
    long line;             /* of its [[fault]] header; 0 for the top level */
    fm_fault_settings set; /* [[fault]]: what it sets, checked when read */
    const char *const *match; /* [[fault]]: its patterns (in e) */
    size_t nmatch;
} fm_settings_section;

typedef struct fm_settings {
    char *path; /* as given */
    char *dir;  /* its folder: relative paths in it are taken from there */
    fm_settings_section top;
    fm_settings_section *fault;
    size_t nfault;
    char **kept; /* strings made from it that options point to (fm_settings_path) */
    size_t nkept;
} fm_settings;

/* The file at path, or NULL and err: "PATH:LINE: why" for what is wrong in
 * it (err->line > 0), "PATH: why" when it cannot be read or is a folder. */
fm_settings *fm_settings_read(const char *path, fm_error *err);
void fm_settings_free(fm_settings *s); /* NULL ignored */

/* A path in the file, taken from the file's folder; owned by s (NULL when
 * memory runs out). */
const char *fm_settings_path(fm_settings *s, const char *p);

/* The [[fault]] sections as a run's rules (fm_run_options.fault_rules):
 * malloc'ed (free), pointing into s, which must outlive them; their
 * number in *n. NULL with *n 0 when there are none; NULL with *n 1 when
 * memory runs out. */
fm_fault_rule *fm_settings_rules(const fm_settings *s, size_t *n);

#endif
