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
    cli->o.settings_path = cli->cfg->path;
    size_t n;
    cli->rules = fm_settings_rules(cli->cfg, &n);
    if (!cli->rules)
        return n ? -1 : 0;
    cli->o.fault_rules = cli->rules;
    cli->o.nfault_rules = n;
    return 0;
}

void settings_rules_free(remesh_cli *cli)
{
    free(cli->rules);
    cli->rules = NULL;
    cli->o.fault_rules = NULL;
    cli->o.nfault_rules = 0;
}
