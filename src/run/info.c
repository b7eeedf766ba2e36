/* fm_info (fm_commands.h): `faultmesh info`'s work. Read, repair and
 * describe TSurf files, as text or as JSON.
 *
 * The JSON form is a stable interface (scripts and the CFM-wide tests read
 * it): keys are only ever added, never renamed or removed. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_commands.h"
#include "fm_json.h"
#include "fm_mesh.h"
#include "fm_opt.h"
#include "fm_repair.h"
#include "fm_tsurf.h"

struct fm_info {
    int json;
    fm_repair_options repair;
    fm_log_fn log;
    void *user;
};

fm_info *fm_info_create(void)
{
    fm_info *info = calloc(1, sizeof *info);
    if (info)
        fm_repair_options_default(&info->repair);
    return info;
}

void fm_info_destroy(fm_info *info)
{
    free(info);
}

void fm_info_set_log(fm_info *info, fm_log_fn fn, void *user)
{
    info->log = fn;
    info->user = user;
}

static int json(void *t, fm_opt_arg *a, fm_error *err)
{
    (void)a, (void)err;
    ((fm_info *)t)->json = 1;
    return 0;
}

static const fm_opt_spec table[] = {
    {"--json", NULL, 0, json},
};

int fm_info_take_option(fm_info *info, int argc, const char *const *argv, int *i, fm_error *err)
{
    int rc = fm_opt_take(table, sizeof table / sizeof *table, info, argc, argv, i, err);
    return rc ? rc : fm_repair_take_option(&info->repair, argc, argv, i, err);
}

static void say(const fm_info *info, const char *message)
{
    if (info->log)
        info->log(info->user, FM_LOG_ERROR, message);
}

static void print_stats_line(FILE *out, const fm_mesh_stats *st, const char *indent)
{
    fprintf(out,
            "%sz %.1f .. %.1f m; edges min/median/max %.1f/%.1f/%.1f m; "
            "min angle min/p1/mean %.1f/%.1f/%.1f deg (%zu below 20)\n",
            indent, st->zmin, st->zmax, st->edge_min, st->edge_median, st->edge_max,
            st->angle_min, st->angle_min_p01, st->angle_mean, st->angle_below_20);
}

static void print_sheets(FILE *out, const fm_surface *s)
{
    for (size_t i = 0; i < fm_surface_nsheets(s); i++) {
        fm_mesh_stats st;
        fm_mesh_compute_stats(fm_surface_sheet_mesh(s, i), &st);
        fprintf(out,
                "    sheet %zu: %zu vertices, %zu triangles, %.3f km2, %zu loops "
                "(%zu holes)\n",
                i + 1, st.vertices, st.triangles, st.area * 1e-6, fm_surface_sheet_nloops(s, i),
                fm_surface_sheet_nholes(s, i));
        print_stats_line(out, &st, "      ");
    }
    for (size_t k = 0; k < fm_surface_njunctions(s); k++) {
        size_t np, ns;
        fm_surface_junction_points(s, k, &np);
        const int32_t *sh = fm_surface_junction_sheets(s, k, &ns);
        fprintf(out, "    junction %zu: %zu points, %.1f m, sheets", k + 1, np,
                fm_surface_junction_length(s, k));
        for (size_t q = 0; q < ns; q++)
            fprintf(out, " %d", sh[q] + 1);
        fprintf(out, "\n");
    }
}

static void print_object(FILE *out, const fm_tsurf *ts, const fm_surface *s,
                         const fm_mesh_stats *all)
{
    const fm_repair_report *r = fm_surface_report(s);
    const fm_mesh *raw = fm_tsurf_mesh(ts);
    fprintf(out, "  %s: %zu part%s, %zu vertices (%zu welded), %zu triangles, %.3f km2\n",
            fm_tsurf_name(ts)[0] ? fm_tsurf_name(ts) : "(unnamed)", fm_tsurf_nparts(ts),
            fm_tsurf_nparts(ts) == 1 ? "" : "s", fm_mesh_nvertices(raw),
            r->welded_exact + r->welded_tolerance, fm_mesh_ntriangles(raw), all->area * 1e-6);
    fprintf(out,
            "    %zu component%s, %zu sheet%s, %zu boundary loop%s (%zu hole%s), "
            "%zu non-manifold edge%s\n",
            r->components, r->components == 1 ? "" : "s", r->sheets, r->sheets == 1 ? "" : "s",
            r->boundary_loops, r->boundary_loops == 1 ? "" : "s", r->holes,
            r->holes == 1 ? "" : "s", r->nonmanifold_edges,
            r->nonmanifold_edges == 1 ? "" : "s");
    if (r->degenerate_removed || r->duplicates_removed || r->fragments_dropped ||
        r->unused_vertices || r->nonmanifold_vertices || r->triangles_flipped ||
        r->nonorientable_sheets)
        fprintf(out,
                "    repaired: %zu degenerate and %zu duplicate triangles removed, %zu "
                "fragments (%zu triangles) dropped, %zu unused vertices, %zu pinch vertices "
                "split, %zu triangles flipped%s\n",
                r->degenerate_removed, r->duplicates_removed, r->fragments_dropped,
                r->fragment_triangles_dropped, r->unused_vertices, r->nonmanifold_vertices,
                r->triangles_flipped, r->nonorientable_sheets ? ", NON-ORIENTABLE sheet" : "");
    print_stats_line(out, all, "    ");
    if (fm_surface_nsheets(s) > 1)
        print_sheets(out, s);
}

/* One file's objects repaired, each with its figures; -1 (err set) at
 * the first that fails. */
static int repair_all(const fm_info *info, const char *path, fm_tsurf **objs, size_t nobj,
                      fm_surface **surf, fm_mesh_stats *all, fm_error *err)
{
    for (size_t i = 0; i < nobj; i++) {
        if (fm_repair(fm_tsurf_mesh(objs[i]), &info->repair, &surf[i], err) != FM_OK)
            return -1;
        fm_mesh *cat = fm_surface_concat(surf[i]);
        int bad = !cat || fm_mesh_compute_stats(cat, &all[i]) != FM_OK;
        fm_mesh_destroy(cat);
        if (bad) {
            fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
            return -1;
        }
    }
    return 0;
}

/* Processes one file; returns 0 if it was read and repaired. */
static int info_file(const fm_info *info, const char *path, FILE *out, fm_json *j)
{
    fm_tsurf **objs = NULL;
    size_t nobj = 0;
    fm_error err;
    fm_error_clear(&err);
    fm_status st = fm_tsurf_read_file(path, &objs, &nobj, &err);
    if (j) {
        fm_json_begin_object(j);
        fm_json_kv_string(j, "path", path);
    }
    if (st != FM_OK) {
        say(info, err.message);
        if (j) {
            fm_json_kv_string(j, "status", "error");
            fm_json_kv_string(j, "error", err.message);
            fm_json_end_object(j);
        }
        return -1;
    }
    /* Repair every object first so a failure is reported before any of the
     * file's figures are printed. */
    fm_surface **surf = calloc(nobj, sizeof *surf);
    fm_mesh_stats *all = calloc(nobj, sizeof *all);
    int bad = !surf || !all;
    if (bad)
        fm_error_set(&err, FM_ERR_NOMEM, path, 0, "out of memory");
    else
        bad = repair_all(info, path, objs, nobj, surf, all, &err);
    if (bad) {
        if (!strncmp(err.message, path, strlen(path))) {
            say(info, err.message);
        } else {
            char msg[FM_ERROR_MESSAGE_MAX + 1024];
            snprintf(msg, sizeof msg, "%s: %s", path, err.message);
            say(info, msg);
        }
        if (j) {
            fm_json_kv_string(j, "status", "error");
            fm_json_kv_string(j, "error", err.message);
        }
    } else if (j) {
        fm_json_kv_string(j, "status", "ok");
        fm_json_key(j, "objects");
        fm_json_begin_array(j);
        for (size_t i = 0; i < nobj; i++)
            fm_surface_json(j, fm_tsurf_name(objs[i]), fm_tsurf_nparts(objs[i]),
                            fm_tsurf_mesh(objs[i]), surf[i], &all[i]);
        fm_json_end_array(j);
    } else {
        fprintf(out, "%s\n", path);
        for (size_t i = 0; i < nobj; i++)
            print_object(out, objs[i], surf[i], &all[i]);
    }
    if (j)
        fm_json_end_object(j);
    for (size_t i = 0; surf && i < nobj; i++)
        fm_surface_destroy(surf[i]);
    free(surf);
    free(all);
    fm_tsurf_free_all(objs, nobj);
    return bad ? -1 : 0;
}

size_t fm_info_write(fm_info *info, const char *const *files, size_t nfiles, FILE *out)
{
    fm_json j;
    if (info->json) {
        fm_json_init(&j, out);
        fm_json_begin_object(&j);
        fm_json_kv_string(&j, "faultmesh_version", FM_VERSION_STRING);
        fm_json_key(&j, "files");
        fm_json_begin_array(&j);
    }
    long failed = 0, n = (long)nfiles;
    for (size_t i = 0; i < nfiles; i++)
        if (info_file(info, files[i], out, info->json ? &j : NULL))
            failed++;
    if (info->json) {
        fm_json_end_array(&j);
        fm_json_key(&j, "summary");
        fm_json_begin_object(&j);
        fm_json_kv_int(&j, "files", n);
        fm_json_kv_int(&j, "failed", failed);
        fm_json_end_object(&j);
        fm_json_end_object(&j);
    } else if (n > 1) {
        fprintf(out, "%ld file%s, %ld failed\n", n, n == 1 ? "" : "s", failed);
    }
    return (size_t)failed;
}
