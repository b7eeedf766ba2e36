/* `faultmesh remesh` and `demo`: the settings file's [[fault]] sections
 * handed to the run as its per-fault rules (fm_run_options.fault_rules);
 * they point into the parsed file, which outlives the run. */
#include <stdlib.h>

#include "remesh_cli.h"

int settings_rules(remesh_cli *cli)
{
    cli->rules = NULL;
    if (!cli->cfg)
        return 0;
    const config *c = cli->cfg;
    cli->o.settings_path = c->path;
    if (!c->nfault)
        return 0;
    cli->rules = calloc(c->nfault, sizeof *cli->rules);
    if (!cli->rules)
        return -1;
    for (size_t i = 0; i < c->nfault; i++) {
        const cfg_section *s = &c->fault[i];
        cli->rules[i].match = s->match;
        cli->rules[i].nmatch = s->nmatch;
        cli->rules[i].set = s->set;
        cli->rules[i].set.line = s->line;
    }
    cli->o.fault_rules = cli->rules;
    cli->o.nfault_rules = c->nfault;
    return 0;
}

void settings_rules_free(remesh_cli *cli)
{
    free(cli->rules);
    cli->rules = NULL;
    cli->o.fault_rules = NULL;
    cli->o.nfault_rules = 0;
}
