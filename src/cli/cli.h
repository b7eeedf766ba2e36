/* faultmesh command-line tool: shared pieces of the subcommands. The
 * commands' work is the library's (include/faultmesh, its public API
 * only); here are the words, the help texts, the messages and the exit
 * codes.
 *
 * Exit codes (documented in the README and docs/guide.md): 0 all inputs processed, 1 some
 * inputs failed (reported, the others still processed), 2 bad usage. */
#ifndef FM_CLI_H
#define FM_CLI_H

#include <stddef.h>
#include <stdio.h>

#include <faultmesh/faultmesh.h>

#define FM_EXIT_OK 0
#define FM_EXIT_FAILURES 1
#define FM_EXIT_USAGE 2

int fm_cmd_info(int argc, char **argv);
int fm_cmd_synth(int argc, char **argv);
int fm_cmd_fit(int argc, char **argv);
int fm_cmd_remesh(int argc, char **argv);
int fm_cmd_demo(int argc, char **argv);

/* SIGINT, SIGTERM and SIGHUP remove the temporary files of the writes in
 * progress (fm_process.h) before they end the process. */
void fm_cli_catch_signals(void);

/* cli_common.c: the library's records as the commands have always said
 * them: FM_LOG_DETAIL (a fault's line) on stdout, the rest on stderr
 * after "faultmesh: ". */
void fm_cli_say(void *user, fm_log_level level, const char *message);
/* err's message said as above (err->line > 0, a settings file's
 * "FILE:LINE: why", without the prefix); returns code. */
int fm_cli_fail(const fm_error *err, int code);
/* Says that opt needs a value; -1. */
int fm_cli_missing(const char *opt);
/* A library option taker's answer said: -1 after saying why, else rc. */
int fm_cli_taken(int rc, const fm_error *err);
/* The library's taker of options as the commands call it on argv. */
#define FM_CLI_ARGV(argv) ((const char *const *)(argv))
extern const char *const fm_cli_repair_help;
extern const char *const fm_cli_sim_help;

/* The .ts files args name (fm_run_list_inputs): their number (the list in
 * *out, fm_run_list_free) or -1 after saying why. */
long fm_input_list(char *const *args, size_t nargs, char ***out);
/* The inputs of a command that writes into outdir: fm_input_list, then
 * refused (-1, after saying why, "faultmesh CMD: ...") when there is no
 * .ts file among them or fm_run_check_output_dir refuses outdir. */
long fm_input_list_for(const char *cmd, const char *outdir, char *const *args, size_t nargs,
                       char ***out);

/* remesh_help.c */
void remesh_usage(FILE *fp);

/* args.c: a command's arguments (argv[0] its name) in the plain form the
 * commands parse, from GNU conventions (--name=value, -j2, -oDIR, bundled
 * short flags, --); malloc'ed (fm_cli_free_args). 0; 1 after saying what
 * is wrong (a usage error); -1 when memory runs out. */
int fm_cli_normalize_args(int argc, char **argv, int *out_argc, char ***out_argv);
void fm_cli_free_args(int argc, char **argv);

#endif
