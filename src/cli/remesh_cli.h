/* faultmesh CLI, `remesh` and `demo`: the command line and settings file
 * read into the run's options (fm_run.h); the run itself is the library's
 * (src/run). */
#ifndef FM_REMESH_CLI_H
#define FM_REMESH_CLI_H

#include <stddef.h>
#include <stdio.h>

#include "fm_run_options.h"
#include "fm_settings.h"

typedef struct remesh_cli {
    const char *dir;      /* -o DIR */
    fm_run_options o;     /* everything the run is told */
    int msh_version_given;
    int quiet;
    int verbose;          /* a line per fault */
    const fm_settings *cfg;    /* --config; NULL: none */
    fm_fault_rule *rules; /* its [[fault]] sections as the run takes them */
} remesh_cli;

/* remesh_options.c */
void remesh_usage(FILE *fp);
/* The bits of a comma-separated list of names; -1 after naming a bad one. */
int formats_parse(const char *list, unsigned *out);
/* Options shared by remesh and demo: 1 if argv[*i] was one (its value
 * consumed), -1 on error, 0 if not one of them. */
int mesh_option(int argc, char **argv, int *i, remesh_cli *cli);
int settle_msh(remesh_cli *cli);
/* --elements quad: the formats that hold rectangles (default) or a usage
 * error for another one asked for; 0 or -1 after saying why. */
int settle_elements(remesh_cli *cli);
void cli_defaults(remesh_cli *cli);
/* The settings file's top-level keys, applied as the options they name
 * (command-line options given after override them); its inputs, if it
 * lists any, in *inputs (free the array, not the strings). 0, or -1
 * after printing FILE:LINE: why. */
int remesh_config(remesh_cli *cli, fm_settings *c, const char ***inputs, size_t *ninputs);

/* sim_options.c: --slip, --metadata, --kinematics*, --eqsim-coords: 1 if
 * argv[*i] was one (with *i on its value), 0 if not, -1 bad value. */
int sim_option(int argc, char **argv, int *i, fm_run_options *o);
extern const char *const fm_cli_sim_help;

/* remesh_settings.c: the settings file's [[fault]] sections as the run's
 * per-fault rules (cli->rules, cli->o.fault_rules); 0, -1 when memory
 * runs out. */
int settings_rules(remesh_cli *cli);
void settings_rules_free(remesh_cli *cli);

#endif
