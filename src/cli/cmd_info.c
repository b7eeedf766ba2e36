/* `faultmesh info`: read, repair and describe TSurf files.
 *
 * The JSON form is a stable interface (scripts and the CFM-wide tests read
 * it): keys are only ever added, never renamed or removed. */
#include <math.h>
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

/* Geometry of a repaired object as one mesh: its sheets side by side. */
static fm_mesh *sheets_concat(const fm_surface *s)
{
    fm_mesh *all = fm_mesh_create();
    if (!all)
        return NULL;
    for (size_t i = 0; i < fm_surface_nsheets(s); i++)
        if (fm_mesh_append(all, fm_surface_sheet_mesh(s, i), (int32_t)i) != FM_OK) {
            fm_mesh_destroy(all);
            return NULL;
        }
    return all;
}

/* Distinct input vertices the sheets use: a vertex on a junction or a pinch
 * is one vertex of the object although several sheets carry a copy. */
static size_t distinct_vertices(const fm_surface *s, size_t ninput)
{
    unsigned char *seen = calloc(ninput ? ninput : 1, 1);
    if (!seen)
        return 0;
    size_t n = 0;
    for (size_t i = 0; i < fm_surface_nsheets(s); i++) {
        const int32_t *org = fm_surface_sheet_vertex_origin(s, i);
        size_t nv = fm_mesh_nvertices(fm_surface_sheet_mesh(s, i));
        for (size_t v = 0; v < nv; v++)
            if (!seen[org[v]]) {
                seen[org[v]] = 1;
                n++;
            }
    }
    free(seen);
    return n;
}

static size_t sheet_holes(const fm_surface *s, size_t i)
{
    size_t n = fm_surface_sheet_nloops(s, i);
    return fm_surface_sheet_outer_loop(s, i) >= 0 ? n - 1 : n;
}

static double junction_length(const fm_surface *s, size_t j)
{
    size_t n;
    const double *p = fm_surface_junction_points(s, j, &n);
    double len = 0.0;
    size_t segs = fm_surface_junction_closed(s, j) ? n : (n ? n - 1 : 0);
    for (size_t k = 0; k < segs; k++) {
        const double *a = p + 3 * k, *b = p + 3 * ((k + 1) % n);
        double dx = b[0] - a[0], dy = b[1] - a[1], dz = b[2] - a[2];
        len += sqrt(dx * dx + dy * dy + dz * dz);
    }
    return len;
}

static void json_stats(fm_json *j, const fm_mesh_stats *st)
{
    fm_json_kv_int(j, "vertices", (int64_t)st->vertices);
    fm_json_kv_int(j, "triangles", (int64_t)st->triangles);
    fm_json_kv_number(j, "area_km2", st->area * 1e-6);
    fm_json_kv_number(j, "z_min", st->zmin);
    fm_json_kv_number(j, "z_max", st->zmax);
    fm_json_key(j, "edge_length");
    fm_json_begin_object(j);
    fm_json_kv_number(j, "min", st->edge_min);
    fm_json_kv_number(j, "median", st->edge_median);
    fm_json_kv_number(j, "mean", st->edge_mean);
    fm_json_kv_number(j, "max", st->edge_max);
    fm_json_end_object(j);
    fm_json_key(j, "min_angle");
    fm_json_begin_object(j);
    fm_json_kv_number(j, "min", st->angle_min);
    fm_json_kv_number(j, "p01", st->angle_min_p01);
    fm_json_kv_number(j, "mean", st->angle_mean);
    fm_json_kv_int(j, "below_20", (int64_t)st->angle_below_20);
    fm_json_kv_int(j, "below_30", (int64_t)st->angle_below_30);
    fm_json_end_object(j);
}

static void json_object(fm_json *j, const fm_tsurf *ts, const fm_surface *s,
                        const fm_mesh_stats *all)
{
    const fm_repair_report *r = fm_surface_report(s);
    const fm_mesh *raw = fm_tsurf_mesh(ts);
    fm_json_begin_object(j);
    fm_json_kv_string(j, "name", fm_tsurf_name(ts));
    fm_json_kv_int(j, "parts", (int64_t)fm_tsurf_nparts(ts));
    fm_json_kv_int(j, "file_vertices", (int64_t)fm_mesh_nvertices(raw));
    fm_json_kv_int(j, "file_triangles", (int64_t)fm_mesh_ntriangles(raw));
    /* After repair; "vertices" counts each welded vertex once, however many
     * sheets share it ("sheet_vertices" counts the copies). */
    fm_mesh_stats whole = *all;
    whole.vertices = distinct_vertices(s, fm_mesh_nvertices(raw));
    json_stats(j, &whole);
    fm_json_kv_int(j, "sheet_vertices", (int64_t)all->vertices);
    fm_json_kv_int(j, "components", (int64_t)r->components);
    fm_json_kv_int(j, "sheets", (int64_t)r->sheets);
    fm_json_kv_int(j, "boundary_loops", (int64_t)r->boundary_loops);
    fm_json_kv_int(j, "holes", (int64_t)r->holes);
    fm_json_kv_int(j, "nonmanifold_edges", (int64_t)r->nonmanifold_edges);
    fm_json_kv_int(j, "duplicates_welded", (int64_t)(r->welded_exact + r->welded_tolerance));
    fm_json_key(j, "repair");
    fm_json_begin_object(j);
    fm_json_kv_int(j, "welded_exact", (int64_t)r->welded_exact);
    fm_json_kv_int(j, "welded_tolerance", (int64_t)r->welded_tolerance);
    fm_json_kv_int(j, "unused_vertices", (int64_t)r->unused_vertices);
    fm_json_kv_int(j, "degenerate_removed", (int64_t)r->degenerate_removed);
    fm_json_kv_int(j, "duplicates_removed", (int64_t)r->duplicates_removed);
    fm_json_kv_int(j, "fragments_dropped", (int64_t)r->fragments_dropped);
    fm_json_kv_int(j, "fragment_triangles_dropped", (int64_t)r->fragment_triangles_dropped);
    fm_json_kv_int(j, "nonmanifold_vertices", (int64_t)r->nonmanifold_vertices);
    fm_json_kv_int(j, "triangles_flipped", (int64_t)r->triangles_flipped);
    fm_json_kv_int(j, "nonorientable_sheets", (int64_t)r->nonorientable_sheets);
    fm_json_end_object(j);

    fm_json_key(j, "sheet_list");
    fm_json_begin_array(j);
    for (size_t i = 0; i < fm_surface_nsheets(s); i++) {
        fm_mesh_stats st;
        fm_mesh_compute_stats(fm_surface_sheet_mesh(s, i), &st);
        fm_json_begin_object(j);
        fm_json_kv_int(j, "index", (int64_t)i);
        json_stats(j, &st);
        fm_json_kv_int(j, "boundary_loops", (int64_t)fm_surface_sheet_nloops(s, i));
        fm_json_kv_int(j, "holes", (int64_t)sheet_holes(s, i));
        long outer = fm_surface_sheet_outer_loop(s, i);
        size_t outer_n = 0;
        if (outer >= 0)
            fm_surface_sheet_loop(s, i, (size_t)outer, &outer_n);
        fm_json_kv_int(j, "outer_loop_vertices", (int64_t)outer_n);
        double n[3];
        fm_surface_sheet_normal(s, i, n);
        fm_json_key(j, "normal");
        fm_json_begin_array(j);
        for (int k = 0; k < 3; k++)
            fm_json_number(j, n[k]);
        fm_json_end_array(j);
        fm_json_end_object(j);
    }
    fm_json_end_array(j);

    fm_json_key(j, "junction_list");
    fm_json_begin_array(j);
    for (size_t k = 0; k < fm_surface_njunctions(s); k++) {
        size_t np, ns;
        fm_surface_junction_points(s, k, &np);
        const int32_t *sh = fm_surface_junction_sheets(s, k, &ns);
        fm_json_begin_object(j);
        fm_json_key(j, "sheets");
        fm_json_begin_array(j);
        for (size_t q = 0; q < ns; q++)
            fm_json_int(j, sh[q]);
        fm_json_end_array(j);
        fm_json_kv_int(j, "points", (int64_t)np);
        fm_json_kv_bool(j, "closed", fm_surface_junction_closed(s, k));
        fm_json_kv_number(j, "length_m", junction_length(s, k));
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    fm_json_end_object(j);
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
                   i, st.vertices, st.triangles, st.area * 1e-6, fm_surface_sheet_nloops(s, i),
                   sheet_holes(s, i));
            print_stats_line(&st, "      ");
        }
        for (size_t k = 0; k < fm_surface_njunctions(s); k++) {
            size_t np, ns;
            fm_surface_junction_points(s, k, &np);
            const int32_t *sh = fm_surface_junction_sheets(s, k, &ns);
            printf("    junction %zu: %zu points, %.1f m, sheets", k, np, junction_length(s, k));
            for (size_t q = 0; q < ns; q++)
                printf(" %d", sh[q]);
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
        fm_mesh *cat = sheets_concat(surf[i]);
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
            json_object(j, objs[i], surf[i], &all[i]);
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
