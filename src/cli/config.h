/* faultmesh CLI: a project's settings in one file (TOML, the subset a
 * settings file needs).
 *
 *   key = "string" | number | true | false | ["string", ...]
 *   [[fault]]            a per-fault section (array of tables)
 *   # comment
 *
 * Top-level keys are the command's options (config_apply turns them into
 * the same arguments, so they are checked the same way); [[fault]]
 * sections carry `match` (a shell pattern or a list of them, on the fault
 * name) and the overrides the run resolves (fm_fault_settings_lookup). Every error names
 * the file and line. */
#ifndef FM_CLI_CONFIG_H
#define FM_CLI_CONFIG_H

#include <stddef.h>

#include "fm_run_options.h"

typedef enum { CFG_STRING, CFG_NUMBER, CFG_BOOL, CFG_ARRAY } cfg_type;

typedef struct cfg_entry {
    char *key;
    cfg_type type;
    char *text;    /* string: its value; number: as written; bool: "true"/"false" */
    char **items;  /* array of strings */
    size_t nitems;
    long line;
} cfg_entry;


/* What [[fault]] sections say about one fault (fm_run.h): each field is
 * set only where a section gives it (has_*). */
typedef fm_fault_settings fault_config;

typedef struct cfg_section {
    cfg_entry *e;
    size_t n;
    long line;        /* of its [[fault]] header; 0 for the top level */
    fault_config set; /* [[fault]]: what it sets, checked when read */
    const char *const *match; /* [[fault]]: its patterns (in e) */
    size_t nmatch;
} cfg_section;

typedef struct config {
    char *path; /* as given */
    char *dir;  /* its folder: relative paths in it are taken from there */
    cfg_section top;
    cfg_section *fault;
    size_t nfault;
    char **kept; /* strings made from it that options point to (config_keep) */
    size_t nkept;
} config;

/* NULL after printing FILE:LINE: why (or that memory ran out). */
config *config_read(const char *path);
void config_free(config *c);

/* A path in the file, taken from the file's folder; owned by c (NULL when
 * memory runs out). */
const char *config_path(config *c, const char *p);

#endif
