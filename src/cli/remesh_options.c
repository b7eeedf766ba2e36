/* `faultmesh remesh` and `faultmesh demo`: their options. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "remesh_cli.h"

void remesh_usage(FILE *fp)
{
    fprintf(fp,
            "usage: faultmesh remesh [options] -o DIR FILE|DIR...\n"
            "Meshes every fault at edge length H with well-shaped triangles on its\n"
            "fitted surface, cut at sea level by default, the faults that meet\n"
            "sharing their nodes, and writes into DIR:\n"
            "  mesh.vtu, mesh.msh (Gmsh), mesh.stl, mesh.obj, mesh.exo (Exodus II),\n"
            "  NAME.ts per fault (GoCAD TSurf), model.igs (trimmed B-spline surfaces,\n"
            "  IGES), mesh.rsqsim (RSQSim), mesh.eqsim (EQSim), names.csv (every\n"
            "  fault's name in each file), report.json and report.html (the report\n"
            "  with pictures); --formats chooses among them.\n\n"
            "options (GNU style: --size=1000 or --size 1000, -j2, -oDIR, --):\n"
            "  -o, --output DIR      output folder (created if missing)\n"
            "  --size H              target edge length in metres (default 1000)\n"
            "  --top cut|keep        cut at sea level (z = 0, default) or keep the fitted top\n"
            "  --top extend D        extend tops less than D metres below sea level up to it,\n"
            "                        then cut\n"
            "  --msh-version 4.1|2.2 Gmsh MSH format version (default 4.1; 2.2 with\n"
            "                        --msh-tags tandem)\n"
            "  --msh-tags default|tandem|seissol|pylith\n"
            "                        MSH physical tags and names as that code expects\n"
            "                        (default: one group per fault, named after it)\n"
            "  --crs STRING          coordinate reference system recorded in the outputs\n"
            "                        (default: the one the input TSurf files name, e.g.\n"
            "                        NAME EPSG:26711 in their coordinate-system block,\n"
            "                        else EPSG:26711, the CFM's UTM 11N NAD27)\n"
            "  --crs-out STRING      write every output in this CRS (any PROJ CRS, e.g.\n"
            "                        EPSG:32611, UTM 11N WGS 84): nodes and CAD control\n"
            "                        points converted by one PROJ operation for the set\n"
            "  -j, --jobs N          threads (default: all cores); the output is the same\n"
            "                        for any N\n"
            "  --no-connect          mesh every fault on its own (default: faults that meet\n"
            "                        share their nodes along the intersection)\n"
            "  --keep-crossings      when connecting, keep the triangles of two faults that\n"
            "                        still run through each other away from a shared curve\n"
            "                        (default: the one losing the smaller share of its\n"
            "                        area gives way there, reported)\n"
            "  --join D              join faults whose surfaces come within D metres\n"
            "                        (default 1000)\n"
            "  --max-triangles N     refuse a fault, or the run, whose size calls for more\n"
            "                        than N triangles over its fitted area (default\n"
            "                        20000000, what a 24 GB machine holds; 0: no limit)\n"
            "  --keep-duplicate smaller|larger\n"
            "                        of two faults that nearly duplicate each other (half\n"
            "                        the area of one within 50 m of the other, as rupture\n"
            "                        composites over their section faults), keep the\n"
            "                        smaller (default: the sections) or the larger; the\n"
            "                        other goes only if the faults it pairs with cover\n"
            "                        half of it\n"
            "  --config FILE         settings from a TOML file: the options as keys, and\n"
            "                        [[fault]] sections with per-fault size, top, join,\n"
            "                        connect, exclude, rake, slip_rate by name pattern\n"
            "                        (options beside it override it; see docs/guide.md)\n"
            "  --no-report-html      skip DIR/report.html\n"
            "  --elastic-check       the elastic interaction check: element pairs of two\n"
            "                        faults that load each other about as much as\n"
            "                        themselves (half-space dislocations), in report.json\n"
            "                        and report.html (docs/guide.md)\n"
            "  --elastic-fraction F  flag pairs above F of the smaller self-stiffness\n"
            "                        (default 0.5)\n"
            "  --elastic-radius R    pairs within R element sizes (default 3)\n"
            "  --elastic-medium half|full\n"
            "                        half space (default; free surface at sea level) or\n"
            "                        full space, a quick look: no free surface, elements\n"
            "                        at the surface off by up to a quarter, much faster\n"
            "  --shear-modulus PA    of the check and matrices (default 3e10)\n"
            "  --poisson-ratio NU    of the check and matrices (default 0.25)\n"
            "  --stiffness-matrix FILE\n"
            "                        write the full interaction matrices (Pa/m) of a set of\n"
            "                        at most 10000 elements as a NumPy .npy file\n"
            "                        (docs/formats.md)\n"
            "  --cache DIR           keep each fault's fitted model in DIR and read it back\n"
            "                        in later runs (another size, a few faults changed, a\n"
            "                        new release): only what changed is fitted again, with\n"
            "                        the same outputs byte for byte (default: on, in\n"
            "                        $XDG_CACHE_HOME/faultmesh or ~/.cache/faultmesh; safe\n"
            "                        to delete; see docs/guide.md)\n"
            "  --no-cache            fit every fault, reading and keeping no models\n"
            "  --elements tri|quad   triangles (default), or rectangles of about SIZE x SIZE\n"
            "                        along strike and down dip for the simulators that read\n"
            "                        only rectangles: mesh.vtu, mesh.msh, mesh.rsqsim and\n"
            "                        mesh.eqsim then hold rectangles (see docs/formats.md)\n"
            "  --formats LIST        the outputs to write, comma-separated, of vtu, msh,\n"
            "                        stl, obj, exo, ts (NAME.ts), igs (model.igs), rsqsim,\n"
            "                        eqsim, html (report.html), names (names.csv); default\n"
            "                        all; report.json is always written\n"
            "  -h, --help            this text\n"
            "  -q, --quiet           errors only (no progress, no summary)\n"
            "  -v, --verbose         a line per fault and per stage as well\n"
            "                        (default: a progress bar on a terminal, log lines\n"
            "                        otherwise, on stderr; the summary on stdout)\n"
            );
    fputs(fm_cli_sim_help, fp);
    fputs(fm_cli_repair_help, fp);
}

static const char *const format_names[] = {"vtu", "msh",    "stl",   "obj",  "exo",  "ts",
                                           "igs", "rsqsim", "eqsim", "html", "names"};

int formats_parse(const char *list, unsigned *out)
{
    unsigned f = 0;
    const char *p = list;
    while (*p) {
        size_t n = strcspn(p, ",");
        int found = 0;
        for (size_t k = 0; k < sizeof format_names / sizeof *format_names && !found; k++)
            if (n == strlen(format_names[k]) && !strncmp(p, format_names[k], n)) {
                f |= 1u << k;
                found = 1;
            }
        if (!found) {
            fprintf(stderr, "faultmesh: --formats: '%.*s' is not one of vtu, msh, stl, obj, exo, "
                            "ts, igs, rsqsim, eqsim, html, names\n",
                    (int)n, p);
            return -1;
        }
        p += n + (p[n] == ',');
    }
    if (!f) {
        fprintf(stderr, "faultmesh: --formats needs at least one format\n");
        return -1;
    }
    *out = f;
    return 0;
}

int mesh_option(int argc, char **argv, int *i, remesh_cli *cli)
{
    const char *a = argv[*i], *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    int sc = sim_option(argc, argv, i, &cli->o);
    if (sc != 0)
        return sc;
    if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
        if (!val)
            return fm_cli_missing(a);
        cli->dir = val;
    } else if (!strcmp(a, "--size")) {
        if (fm_parse_positive(a, val, &cli->o.mesh.size))
            return -1;
    } else if (!strcmp(a, "--top")) {
        if (val && !strcmp(val, "cut")) {
            cli->o.mesh.top = FM_TOP_CUT;
        } else if (val && !strcmp(val, "keep")) {
            cli->o.mesh.top = FM_TOP_KEEP;
        } else if (val && !strcmp(val, "extend")) {
            cli->o.mesh.top = FM_TOP_EXTEND;
            (*i)++;
            const char *d = *i + 1 < argc ? argv[*i + 1] : NULL;
            if (fm_parse_double("--top extend", d, &cli->o.mesh.top_extend))
                return -1;
        } else {
            fprintf(stderr, "faultmesh: --top takes cut, keep or extend D\n");
            return -1;
        }
    } else if (!strcmp(a, "--msh-version")) {
        if (val && !strcmp(val, "4.1"))
            cli->o.msh = FM_MSH_41;
        else if (val && !strcmp(val, "2.2"))
            cli->o.msh = FM_MSH_22;
        else {
            fprintf(stderr, "faultmesh: --msh-version takes 4.1 or 2.2\n");
            return -1;
        }
        cli->msh_version_given = 1;
    } else if (!strcmp(a, "--msh-tags")) {
        int found = 0;
        for (int c = FM_MSH_TAGS_DEFAULT; c <= FM_MSH_TAGS_PYLITH && !found; c++)
            if (val && !strcmp(val, fm_msh_tags_name((fm_msh_tags)c))) {
                cli->o.msh_tags = (fm_msh_tags)c;
                found = 1;
            }
        if (!found) {
            fprintf(stderr, "faultmesh: --msh-tags takes default, tandem, seissol or pylith\n");
            return -1;
        }
    } else if (!strcmp(a, "--config")) {
        if (!val)
            return fm_cli_missing(a); /* read before the other options (load_config) */
    } else if (!strcmp(a, "--crs")) {
        if (!val)
            return fm_cli_missing(a);
        cli->o.crs = val;
    } else if (!strcmp(a, "--crs-out")) {
        if (!val || !val[0])
            return fm_cli_missing(a);
        cli->o.crs_out = val;
    } else if (!strcmp(a, "--jobs") || !strcmp(a, "-j")) {
        size_t n;
        if (fm_parse_size(a, val, &n))
            return -1;
        if (n < 1 || n > 1024) {
            fprintf(stderr, "faultmesh: %s needs a whole number from 1 to 1024, got '%s'\n", a,
                    val);
            return -1;
        }
        cli->o.jobs = (int)n;
    } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
        cli->quiet = 1;
        cli->verbose = 0;
        return 1;
    } else if (!strcmp(a, "--verbose") || !strcmp(a, "-v")) {
        cli->verbose = 1;
        cli->quiet = 0;
        return 1;
    } else if (!strcmp(a, "--no-connect")) {
        cli->o.connect = 0;
        return 1;
    } else if (!strcmp(a, "--elastic-check")) {
        cli->o.elastic = 1;
        return 1;
    } else if (!strcmp(a, "--elastic-fraction")) {
        if (fm_parse_positive(a, val, &cli->o.elastic_fraction))
            return -1;
    } else if (!strcmp(a, "--elastic-radius")) {
        if (fm_parse_positive(a, val, &cli->o.elastic_radius))
            return -1;
    } else if (!strcmp(a, "--elastic-medium")) {
        if (!val)
            return fm_cli_missing(a);
        if (strcmp(val, "half") && strcmp(val, "full")) {
            fprintf(stderr, "faultmesh: --elastic-medium takes half or full, not '%s'\n", val);
            return -1;
        }
        cli->o.elastic_full_space = !strcmp(val, "full");
    } else if (!strcmp(a, "--shear-modulus")) {
        if (fm_parse_positive(a, val, &cli->o.elastic_mu))
            return -1;
    } else if (!strcmp(a, "--poisson-ratio")) {
        if (fm_parse_positive(a, val, &cli->o.elastic_nu))
            return -1;
        if (cli->o.elastic_nu >= 0.5) {
            fprintf(stderr, "faultmesh: --poisson-ratio must be under 0.5\n");
            return -1;
        }
    } else if (!strcmp(a, "--stiffness-matrix")) {
        if (!val || !val[0])
            return fm_cli_missing(a);
        cli->o.stiffness_path = val;
    } else if (!strcmp(a, "--no-report-html")) {
        cli->o.html = 0;
        return 1;
    } else if (!strcmp(a, "--cache")) {
        if (!val || !val[0])
            return fm_cli_missing(a);
        cli->o.cache_dir = val;
        cli->o.no_cache = 0;
    } else if (!strcmp(a, "--no-cache")) {
        cli->o.no_cache = 1;
        return 1;
    } else if (!strcmp(a, "--elements")) {
        if (!val)
            return fm_cli_missing(a);
        if (strcmp(val, "tri") && strcmp(val, "quad")) {
            fprintf(stderr, "faultmesh: --elements takes tri or quad, not '%s'\n", val);
            return -1;
        }
        cli->o.quads = !strcmp(val, "quad");
    } else if (!strcmp(a, "--formats")) {
        if (!val)
            return fm_cli_missing(a);
        if (formats_parse(val, &cli->o.formats))
            return -1;
    } else if (!strcmp(a, "--keep-crossings")) {
        cli->o.carve = 0;
        return 1;
    } else if (!strcmp(a, "--max-triangles")) {
        if (fm_parse_size(a, val, &cli->o.max_triangles))
            return -1;
    } else if (!strcmp(a, "--join")) {
        if (fm_parse_positive(a, val, &cli->o.join))
            return -1;
    } else if (!strcmp(a, "--keep-duplicate")) {
        if (!val) {
            return fm_cli_missing(a);
        } else if (!strcmp(val, "smaller")) {
            cli->o.keep = FM_CONNECT_KEEP_SMALLER;
        } else if (!strcmp(val, "larger")) {
            cli->o.keep = FM_CONNECT_KEEP_LARGER;
        } else {
            fprintf(stderr, "faultmesh: --keep-duplicate takes smaller or larger, not '%s'\n",
                    val);
            return -1;
        }
    } else {
        return fm_cli_repair_option(argc, argv, i, &cli->o.repair);
    }
    (*i)++;
    return 1;
}

/* Tandem reads MSH 2.2 only; -1 (after saying why) when asked for 4.1. */
int settle_elements(remesh_cli *cli)
{
    const unsigned tri_only = FM_OUT_STL | FM_OUT_OBJ | FM_OUT_EXO | FM_OUT_TS | FM_OUT_IGS;
    if (!cli->o.quads)
        return 0;
    if (cli->o.formats == FM_OUT_ALL) {
        cli->o.formats &= ~tri_only;
        return 0;
    }
    if (cli->o.formats & tri_only) {
        fprintf(stderr, "faultmesh: --elements quad writes vtu, msh, rsqsim, eqsim, html and "
                        "names; stl, obj, exo, ts and igs hold triangles only\n");
        return -1;
    }
    return 0;
}

int settle_msh(remesh_cli *cli)
{
    if (cli->o.msh_tags != FM_MSH_TAGS_TANDEM)
        return 0;
    if (cli->msh_version_given && cli->o.msh != FM_MSH_22) {
        fprintf(stderr, "faultmesh: --msh-tags tandem needs MSH 2.2 (Tandem reads no other)\n");
        return -1;
    }
    cli->o.msh = FM_MSH_22;
    return 0;
}

void cli_defaults(remesh_cli *cli)
{
    memset(cli, 0, sizeof *cli);
    fm_run_options_default(&cli->o);
}

/* Flags whose default is on: `key = false` in a settings file is their
 * --no- option, `key = true` the default. */
static const char *const on_by_default[] = {"connect", "split", "report_html", "cache"};

static int is_on_by_default(const char *key)
{
    for (size_t i = 0; i < sizeof on_by_default / sizeof *on_by_default; i++)
        if (!strcmp(key, on_by_default[i]))
            return 1;
    return 0;
}

/* Paths the file names, taken from its folder. */
static int path_key(const char *key)
{
    return !strcmp(key, "output") || !strcmp(key, "slip") || !strcmp(key, "metadata") ||
           !strcmp(key, "cache") || !strcmp(key, "stiffness_matrix");
}

int remesh_config(remesh_cli *cli, fm_settings *c, const char ***inputs, size_t *ninputs)
{
    *inputs = NULL;
    *ninputs = 0;
    const fm_settings_section *s = &c->top;
    const fm_settings_entry *extend = NULL;
    for (size_t i = 0; i < s->n; i++)
        if (!strcmp(s->e[i].key, "top_extend"))
            extend = &s->e[i];
    for (size_t i = 0; i < s->n; i++) {
        const fm_settings_entry *e = &s->e[i];
        char opt[96];
        const char *argv[4] = {opt, NULL, NULL, NULL};
        int argc = 1;
        snprintf(opt, sizeof opt, "--%s", e->key);
        for (char *q = opt + 2; *q; q++)
            if (*q == '_')
                *q = '-';
        if (!strcmp(e->key, "inputs") || !strcmp(e->key, "input")) {
            size_t n = e->type == FM_SETTINGS_ARRAY ? e->nitems : e->type == FM_SETTINGS_STRING ? 1 : 0;
            const char **g = n ? realloc(*inputs, (*ninputs + n) * sizeof *g) : NULL;
            if (!g) {
                fprintf(stderr, "%s:%ld: %s takes a path or a list of paths\n", c->path, e->line,
                        e->key);
                return -1;
            }
            *inputs = g;
            for (size_t k = 0; k < n; k++)
                if (!(g[(*ninputs)++] = fm_settings_path(c, e->type == FM_SETTINGS_ARRAY ? e->items[k] : e->text)))
                    return -1;
            continue;
        }
        if (!strcmp(e->key, "top_extend")) {
            continue; /* with top = "extend" */
        } else if (e->type == FM_SETTINGS_BOOL) {
            int on = e->text[0] == 't';
            if (is_on_by_default(e->key) && !on) {
                snprintf(opt, sizeof opt, "--no-%s", e->key);
                for (char *q = opt + 5; *q; q++)
                    if (*q == '_')
                        *q = '-';
            }
            else if (is_on_by_default(e->key) || !on)
                continue; /* the default */
        } else if (e->type == FM_SETTINGS_ARRAY && !strcmp(e->key, "formats")) {
            unsigned all = 0;
            for (size_t k = 0; k < e->nitems; k++) {
                unsigned f;
                if (formats_parse(e->items[k], &f)) {
                    fprintf(stderr, "%s:%ld: formats: see above\n", c->path, e->line);
                    return -1;
                }
                all |= f;
            }
            if (!all) {
                fprintf(stderr, "%s:%ld: formats needs at least one format\n", c->path, e->line);
                return -1;
            }
            cli->o.formats = all;
            continue;
        } else if (e->type == FM_SETTINGS_ARRAY) {
            fprintf(stderr, "%s:%ld: %s takes one value, not a list\n", c->path, e->line, e->key);
            return -1;
        } else {
            argv[argc++] = path_key(e->key) ? fm_settings_path(c, e->text) : e->text;
            if (!argv[1])
                return -1;
            if (!strcmp(e->key, "top") && !strcmp(e->text, "extend")) {
                if (!extend || extend->type != FM_SETTINGS_NUMBER) {
                    fprintf(stderr, "%s:%ld: top = \"extend\" needs top_extend = D (metres)\n",
                            c->path, e->line);
                    return -1;
                }
                argv[argc++] = extend->text;
            }
        }
        int k = 0;
        int rc = mesh_option(argc, (char **)argv, &k, cli);
        if (rc == 0 || (rc > 0 && k + 1 != argc)) {
            fprintf(stderr, "%s:%ld: unknown setting '%s'%s\n", c->path, e->line, e->key,
                    rc > 0 ? " (it takes no value here)" : "");
            return -1;
        }
        if (rc < 0) {
            fprintf(stderr, "%s:%ld: bad value for '%s'\n", c->path, e->line, e->key);
            return -1;
        }
    }
    cli->cfg = c;
    return 0;
}
