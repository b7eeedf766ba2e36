/* `faultmesh remesh` and `demo`: where the fit cache lives (the library
 * keys, stores and reads the models, fm_model_cache.h), and what the run
 * says of it. A cache that cannot be had is no reason to fail a run: the
 * faults are then all fitted, and the run says why once. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_model_cache.h"
#include "run_internal.h"

static char *joined(const char *a, const char *b)
{
    size_t n = strlen(a) + strlen(b) + 2;
    char *p = malloc(n);
    if (p)
        snprintf(p, n, "%s/%s", a, b);
    return p;
}

static void note(remesh_cli *cli, const char *why)
{
    size_t n = strlen(why) + 64;
    cli->cache_note = malloc(n);
    if (cli->cache_note)
        snprintf(cli->cache_note, n, "no fit cache, every fault is fitted: %s", why);
    run_log(cli->ctl, FM_LOG_INFO, "note: %s", cli->cache_note ? cli->cache_note : why);
}

void settle_cache(remesh_cli *cli)
{
    cli->cache = NULL;
    cli->cache_note = NULL;
    if (cli->no_cache)
        return;
    /* XDG Base Directory: a relative XDG_CACHE_HOME is to be ignored */
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    char *dir = cli->cache_dir              ? strdup(cli->cache_dir)
                : xdg && xdg[0] == '/'      ? joined(xdg, "faultmesh")
                : home && home[0]           ? joined(home, ".cache/faultmesh")
                                            : NULL;
    if (!dir) {
        note(cli, cli->cache_dir || (home && home[0]) ? "out of memory"
                                                      : "neither XDG_CACHE_HOME nor HOME is set "
                                                        "(give --cache DIR)");
        return;
    }
    fm_error err;
    fm_error_clear(&err);
    if (fm_model_cache_open(dir, &err) != FM_OK) {
        note(cli, err.message);
        free(dir);
        return;
    }
    cli->cache = dir;
}

void release_cache(remesh_cli *cli)
{
    free(cli->cache);
    free(cli->cache_note);
    cli->cache = NULL;
    cli->cache_note = NULL;
}

void cache_json_fault(fm_json *j, const fault_result *r)
{
    if (r->fit_cache != FIT_CACHE_NONE)
        fm_json_kv_bool(j, "fit_cached", r->fit_cache == FIT_CACHE_HIT);
}

typedef struct cache_counts {
    size_t hits, misses, rejected, unstored;
} cache_counts;

static cache_counts count(const run_state *rs)
{
    cache_counts c = {0, 0, 0, 0};
    for (size_t i = 0; i < rs->nres; i++) {
        const fault_result *r = &rs->res[i];
        c.hits += r->fit_cache == FIT_CACHE_HIT;
        c.misses += r->fit_cache == FIT_CACHE_MISS;
        c.rejected += r->cache_rejected != 0;
        c.unstored += r->cache_unstored != 0;
    }
    return c;
}

/* "fit_cache": whether there was one, where, and what it did: hits (models
 * read), misses (fitted, then stored), rejected (a damaged or foreign
 * file under the key: fitted and stored again), not stored (a write that
 * failed: the run is unaffected). */
void cache_json(fm_json *j, const remesh_cli *cli, const run_state *rs)
{
    cache_counts c = count(rs);
    fm_json_key(j, "fit_cache");
    fm_json_begin_object(j);
    fm_json_kv_bool(j, "enabled", cli->cache != NULL);
    if (cli->cache) {
        fm_json_kv_string(j, "dir", cli->cache);
        fm_json_kv_string(j, "code", fm_model_code_id());
    }
    if (cli->cache_note)
        fm_json_kv_string(j, "note", cli->cache_note);
    fm_json_kv_int(j, "hits", (int64_t)c.hits);
    fm_json_kv_int(j, "misses", (int64_t)c.misses);
    fm_json_kv_int(j, "rejected", (int64_t)c.rejected);
    fm_json_kv_int(j, "not_stored", (int64_t)c.unstored);
    /* the junction plan's pairs and near-duplicates (fm_connect.h) */
    static const char *const nb[] = {"not looked up", "read", "found and stored",
                                     "found again over a rejected file", "found, not stored"};
    fm_json_kv_string(j, "connect_neighbours", nb[rs->neighbours]);
    /* of the pairs decided, those whose intersection curves were read */
    fm_json_kv_int(j, "connect_curves_read", (int64_t)rs->curves_kept);
    fm_json_kv_int(j, "connect_curves_traced", (int64_t)rs->curves_traced);
    fm_json_end_object(j);
}

void cache_print(const remesh_cli *cli, const run_state *rs, FILE *fp)
{
    if (!cli->cache)
        return;
    cache_counts c = count(rs);
    fprintf(fp, "  %-14s %zu models read, %zu fitted (%s)", "fit cache", c.hits, c.misses,
            cli->cache);
    if (c.rejected)
        fprintf(fp, "; %zu damaged files fitted again", c.rejected);
    if (c.unstored)
        fprintf(fp, "; %zu models could not be stored", c.unstored);
    if (rs->neighbours == NEIGHBOURS_HIT)
        fprintf(fp, "; junction neighbours read, curves of %zu pairs read, %zu traced",
                rs->curves_kept, rs->curves_traced);
    fputc('\n', fp);
}
