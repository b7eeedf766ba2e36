/* What a repaired surface is, as `faultmesh info` and any other program
 * describe it: its sheets as one mesh, its distinct vertices, holes and
 * junction lengths, and the JSON object of `faultmesh info --json` (a
 * stable interface: keys are only ever added, never renamed or removed). */
#include <math.h>
#include <stdlib.h>

#include "fm_repair.h"

fm_mesh *fm_surface_concat(const fm_surface *s)
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

size_t fm_surface_distinct_vertices(const fm_surface *s, size_t ninput)
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

size_t fm_surface_sheet_nholes(const fm_surface *s, size_t i)
{
    size_t n = fm_surface_sheet_nloops(s, i);
    return fm_surface_sheet_outer_loop(s, i) >= 0 ? n - 1 : n;
}

double fm_surface_junction_length(const fm_surface *s, size_t j)
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

void fm_mesh_stats_json(fm_json *j, const fm_mesh_stats *st)
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

void fm_surface_json(fm_json *j, const char *name, size_t nparts, const fm_mesh *raw,
                     const fm_surface *s, const fm_mesh_stats *all)
{
    const fm_repair_report *r = fm_surface_report(s);
    fm_json_begin_object(j);
    fm_json_kv_string(j, "name", name);
    fm_json_kv_int(j, "parts", (int64_t)nparts);
    fm_json_kv_int(j, "file_vertices", (int64_t)fm_mesh_nvertices(raw));
    fm_json_kv_int(j, "file_triangles", (int64_t)fm_mesh_ntriangles(raw));
    /* After repair; "vertices" counts each welded vertex once, however many
     * sheets share it ("sheet_vertices" counts the copies). */
    fm_mesh_stats whole = *all;
    whole.vertices = fm_surface_distinct_vertices(s, fm_mesh_nvertices(raw));
    fm_mesh_stats_json(j, &whole);
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
        fm_json_kv_int(j, "index", (int64_t)i + 1); /* from 1, as outputs number sheets */
        fm_mesh_stats_json(j, &st);
        fm_json_kv_int(j, "boundary_loops", (int64_t)fm_surface_sheet_nloops(s, i));
        fm_json_kv_int(j, "holes", (int64_t)fm_surface_sheet_nholes(s, i));
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
            fm_json_int(j, (int64_t)sh[q] + 1);
        fm_json_end_array(j);
        fm_json_kv_int(j, "points", (int64_t)np);
        fm_json_kv_bool(j, "closed", fm_surface_junction_closed(s, k));
        fm_json_kv_number(j, "length_m", fm_surface_junction_length(s, k));
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    fm_json_end_object(j);
}
