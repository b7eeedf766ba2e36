/* faultmesh command-line tool: shared pieces of the subcommands.
 *
 * Exit codes (documented in the README and docs/guide.md): 0 all inputs processed, 1 some
 * inputs failed (reported, the others still processed), 2 bad usage. */
#ifndef FM_CLI_H
#define FM_CLI_H

#include <stddef.h>

#include "fm_repair.h"

#define FM_EXIT_OK 0
#define FM_EXIT_FAILURES 1
#define FM_EXIT_USAGE 2

int fm_cmd_info(int argc, char **argv);
int fm_cmd_synth(int argc, char **argv);
int fm_cmd_fit(int argc, char **argv);
int fm_cmd_remesh(int argc, char **argv);
int fm_cmd_demo(int argc, char **argv);

/* SIGINT, SIGTERM and SIGHUP remove the temporary files of the writes in
 * progress (fm_atomic.h) before they end the process. */
void fm_cli_catch_signals(void);

/* Consumes argv[*i] (and its value, advancing *i) if it is a repair
 * option: returns 1 if consumed, 0 if not a repair option, -1 on a bad
 * value (already reported). */
int fm_cli_repair_option(int argc, char **argv, int *i, fm_repair_options *opt);
extern const char *fm_cli_repair_help;

/* Paths of the .ts files named by args: files as given, folders searched
 * recursively, each folder's entries in byte order so runs are
 * reproducible. Returns the number of paths (in *out, to be freed with
 * fm_input_list_free), or -1 after printing why (a missing path). */
long fm_input_list(char *const *args, size_t nargs, char ***out);
void fm_input_list_free(char **list, long n);
/* Refuses (-1, after printing why) an output folder that would put the
 * inputs at risk: the folder an input file lies in (an output of the same
 * name would replace it), or an input folder or one inside it (the
 * outputs would be read as inputs next time). Nothing is created. */
int fm_output_guard(const char *outdir, char *const *args, size_t nargs, char *const *files,
                    long nfiles);
/* The inputs of a command that writes into outdir: fm_input_list, then
 * refused (-1, after printing why, "faultmesh CMD: ...") when there is no
 * .ts file among them or fm_output_guard refuses outdir. */
long fm_input_list_for(const char *cmd, const char *outdir, char *const *args, size_t nargs,
                       char ***out);

/* Parses a non-negative number option value; prints and returns -1 on
 * error. */
int fm_parse_double(const char *opt, const char *s, double *out);
int fm_parse_positive(const char *opt, const char *s, double *out);
/* Says that opt needs a value; -1. */
int fm_cli_missing(const char *opt);
int fm_parse_size(const char *opt, const char *s, size_t *out);

/* args.c: a command's arguments (argv[0] its name) in the plain form the
 * commands parse, from GNU conventions (--name=value, -j2, -oDIR, bundled
 * short flags, --); malloc'ed (fm_cli_free_args). 0; 1 after saying what
 * is wrong (a usage error); -1 when memory runs out. */
int fm_cli_normalize_args(int argc, char **argv, int *out_argc, char ***out_argv);
void fm_cli_free_args(int argc, char **argv);

#endif
