/* faultmesh run: command-line style options, table-driven.
 *
 * Every object of the library that a front end configures from words (the
 * run, info, the fit, the synthetic system) takes its options through one
 * table of these entries: the command line and the settings file then
 * share one spelling, one check and one message per option, and an option
 * more is a row more. Nothing here prints: what is wrong goes to err, in
 * the words the command line has always used ("--size needs a positive
 * number, got 'x'"). */
#ifndef FM_OPT_H
#define FM_OPT_H

#include <stddef.h>

#include "fm_core.h"
#include "fm_repair.h"

/* One option as a handler sees it: its name as given, its value (NULL
 * when there is none), the word after the value (NULL: none), which a
 * handler that takes it (--top extend D) says by setting extra. */
typedef struct fm_opt_arg {
    const char *name;
    const char *val;
    const char *next;
    int extra;
} fm_opt_arg;

/* 0, or -1 after filling err. */
typedef int (*fm_opt_handler)(void *target, fm_opt_arg *a, fm_error *err);

typedef struct fm_opt_spec {
    const char *name;  /* "--size" */
    const char *alias; /* "-j"; NULL: none */
    int takes_value;   /* 1: argv[i + 1] is its value; 0: a flag */
    fm_opt_handler take;
} fm_opt_spec;

/* argv[*i] taken by the table's entry of its name, *i left on the last
 * word taken: 1; 0 when no entry has that name (nothing taken); -1 when
 * its handler refused it (err says why). */
int fm_opt_take(const fm_opt_spec *table, size_t n, void *target, int argc,
                const char *const *argv, int *i, fm_error *err);

/* The values' checks, with their messages: a decimal number >= 0 (> 0:
 * positive) up to 1e12, a whole number >= 0; -1 after filling err ("OPT
 * needs a value" when s is NULL). */
int fm_opt_double(const char *opt, const char *s, double *out, fm_error *err);
int fm_opt_positive(const char *opt, const char *s, double *out, fm_error *err);
int fm_opt_size(const char *opt, const char *s, size_t *out, fm_error *err);
int fm_opt_missing(const char *opt, fm_error *err);

/* repair_words.c: the repair options (--weld-tol M,
 * --min-fragment-triangles N, --min-fragment-fraction F,
 * --keep-fragments, --no-split) as fm_opt_take takes them, shared by
 * every command that reads faults. */
int fm_repair_take_option(fm_repair_options *opt, int argc, const char *const *argv, int *i,
                          fm_error *err);

#endif
