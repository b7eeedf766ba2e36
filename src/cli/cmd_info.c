/* `faultmesh info`: read, repair and describe TSurf files.
 *
 * The JSON form is a stable interface (scripts and the CFM-wide tests read
 * it): keys are only ever added, never renamed or removed. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "fm_json.h"
#include "fm_mesh.h"
#include "fm_repair.h"
#include "fm_tsurf.h"

typedef struct {
    int json;
    fm_repair_options repair;
} info_options;

static void info_usage(FILE *fp)
{
    fprintf(fp,
            "usage: faultmesh info [options] FILE|DIR...\n"
            "Reads GoCAD TSurf files (folders are searched for *.ts), repairs them\n"
            "and prints per file and per sheet: parts, vertices, triangles, area,\n"
            "components, boundary loops and holes, non-manifold edges, welded\n"
            "duplicates, z range, edge lengths and minimum angles.\n\n"
            "options:\n"
            "  --json                     machine-readable output on stdout\n"
            "  -h, --help                 this text\n");
    fputs(fm_cli_repair_help, fp);
}

static void print_stats_line(const fm_mesh_stats *st, const char *indent)
{
    printf("%sz %.1f .. %.1f m; edges min/median/max %.1f/%.1f/%.1f m; "
           "min angle min/p1/mean %.1f/%.1f/%.1f deg (%zu below 20)\n",
           indent, st->zmin, st->zmax, st->edge_min, st->edge_median, st->edge_max,
           st->angle_min, st->angle_min_p01, st->angle_mean, st->angle_below_20);
}

static void print_object(const fm_tsurf *ts, const fm_surface *s, const fm_mesh_stats *all)
{
    const fm_repair_report *r = fm_surface_report(s);
    const fm_mesh *raw = fm_tsurf_mesh(ts);
    printf("  %s: %zu part%s, %zu vertices (%zu welded), %zu triangles, %.3f km2\n",
           fm_tsurf_name(ts)[0] ? fm_tsurf_name(ts) : "(unnamed)", fm_tsurf_nparts(ts),
           fm_tsurf_nparts(ts) == 1 ? "" : "s", fm_mesh_nvertices(raw),
           r->welded_exact + r->welded_tolerance, fm_mesh_ntriangles(raw), all->area * 1e-6);
    printf("    %zu component%s, %zu sheet%s, %zu boundary loop%s (%zu hole%s), "
           "%zu non-manifold edge%s\n",
           r->components, r->components == 1 ? "" : "s", r->sheets, r->sheets == 1 ? "" : "s",
           r->boundary_loops, r->boundary_loops == 1 ? "" : "s", r->holes,
           r->holes == 1 ? "" : "s", r->nonmanifold_edges, r->nonmanifold_edges == 1 ? "" : "s");
    if (r->degenerate_removed || r->duplicates_removed || r->fragments_dropped ||
        r->unused_vertices || r->nonmanifold_vertices || r->triangles_flipped ||
        r->nonorientable_sheets)
        printf("    repaired: %zu degenerate and %zu duplicate triangles removed, %zu "
               "fragments (%zu triangles) dropped, %zu unused vertices, %zu pinch vertices "
               "split, %zu triangles flipped%s\n",
               r->degenerate_removed, r->duplicates_removed, r->fragments_dropped,
               r->fragment_triangles_dropped, r->unused_vertices, r->nonmanifold_vertices,
               r->triangles_flipped, r->nonorientable_sheets ? ", NON-ORIENTABLE sheet" : "");
    print_stats_line(all, "    ");
    if (fm_surface_nsheets(s) > 1) {
        for (size_t i = 0; i < fm_surface_nsheets(s); i++) {
            fm_mesh_stats st;
            fm_mesh_compute_stats(fm_surface_sheet_mesh(s, i), &st);
            printf("    sheet %zu: %zu vertices, %zu triangles, %.3f km2, %zu loops "
                   "(%zu holes)\n",
                   i + 1, st.vertices, st.triangles, st.area * 1e-6, fm_surface_sheet_nloops(s, i),
                   fm_surface_sheet_nholes(s, i));
            print_stats_line(&st, "      ");
        }
        for (size_t k = 0; k < fm_surface_njunctions(s); k++) {
            size_t np, ns;
            fm_surface_junction_points(s, k, &np);
            const int32_t *sh = fm_surface_junction_sheets(s, k, &ns);
            printf("    junction %zu: %zu points, %.1f m, sheets", k + 1, np,
                   fm_surface_junction_length(s, k));
            for (size_t q = 0; q < ns; q++)
                printf(" %d", sh[q] + 1);
            printf("\n");
        }
    }
}

/* Processes one file; returns 0 if it was read and repaired. */
static int info_file(const char *path, const info_options *opt, fm_json *j)
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
        fprintf(stderr, "faultmesh: %s\n", err.message);
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
    for (size_t i = 0; i < nobj && !bad; i++) {
        if (fm_repair(fm_tsurf_mesh(objs[i]), &opt->repair, &surf[i], &err) != FM_OK) {
            bad = 1;
            break;
        }
        fm_mesh *cat = fm_surface_concat(surf[i]);
        if (!cat || fm_mesh_compute_stats(cat, &all[i]) != FM_OK) {
            fm_error_set(&err, FM_ERR_NOMEM, path, 0, "out of memory");
            bad = 1;
        }
        fm_mesh_destroy(cat);
    }
    if (bad) {
        if (!strncmp(err.message, path, strlen(path)))
            fprintf(stderr, "faultmesh: %s\n", err.message);
        else
            fprintf(stderr, "faultmesh: %s: %s\n", path, err.message);
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
        printf("%s\n", path);
        for (size_t i = 0; i < nobj; i++)
            print_object(objs[i], surf[i], &all[i]);
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

int fm_cmd_info(int argc, char **argv)
{
    info_options opt = {0};
    fm_repair_options_default(&opt.repair);
    char **paths = calloc((size_t)argc, sizeof *paths);
    size_t npaths = 0;
    if (!paths)
        return FM_EXIT_FAILURES;
    int rc = FM_EXIT_OK;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int consumed;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            info_usage(stdout);
            free(paths);
            return FM_EXIT_OK;
        } else if (!strcmp(a, "--json")) {
            opt.json = 1;
        } else if ((consumed = fm_cli_repair_option(argc, argv, &i, &opt.repair)) != 0) {
            if (consumed < 0)
                rc = FM_EXIT_USAGE;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, "faultmesh: unknown option '%s' (see faultmesh info --help)\n", a);
            rc = FM_EXIT_USAGE;
        } else {
            paths[npaths++] = argv[i];
        }
        if (rc)
            break;
    }
    if (!rc && npaths == 0) {
        info_usage(stderr);
        rc = FM_EXIT_USAGE;
    }
    char **files = NULL;
    long nfiles = rc ? -1 : fm_input_list(paths, npaths, &files);
    free(paths);
    if (rc)
        return rc;
    if (nfiles < 0)
        return FM_EXIT_USAGE;
    if (nfiles == 0) {
        fprintf(stderr, "faultmesh info: no .ts files found\n");
        return FM_EXIT_USAGE;
    }

    fm_json j;
    if (opt.json) {
        fm_json_init(&j, stdout);
        fm_json_begin_object(&j);
        fm_json_kv_string(&j, "faultmesh_version", FM_VERSION_STRING);
        fm_json_key(&j, "files");
        fm_json_begin_array(&j);
    }
    long failed = 0;
    for (long i = 0; i < nfiles; i++)
        if (info_file(files[i], &opt, opt.json ? &j : NULL))
            failed++;
    if (opt.json) {
        fm_json_end_array(&j);
        fm_json_key(&j, "summary");
        fm_json_begin_object(&j);
        fm_json_kv_int(&j, "files", nfiles);
        fm_json_kv_int(&j, "failed", failed);
        fm_json_end_object(&j);
        fm_json_end_object(&j);
    } else if (nfiles > 1) {
        printf("%ld file%s, %ld failed\n", nfiles, nfiles == 1 ? "" : "s", failed);
    }
    if (failed) {
        fprintf(stderr, "faultmesh info: %ld of %ld file%s failed\n", failed, nfiles,
                nfiles == 1 ? "" : "s");
    }
    fm_input_list_free(files, nfiles);
    return failed ? FM_EXIT_FAILURES : FM_EXIT_OK;
}
