/* The repair pipeline: input checks, then the six steps of fm_repair.h in
 * order. Each step lives in its own file; this one only sequences them and
 * owns the working arrays. */
#include "repair_internal.h"

#include <math.h>
#include <stdlib.h>

void fm_repair_options_default(fm_repair_options *opt)
{
    if (!opt)
        return;
    opt->weld_tolerance = 0.0;
    opt->min_fragment_triangles = 10;
    opt->min_fragment_area_fraction = 0.001;
    opt->drop_fragments = 1;
    opt->split_nonmanifold = 1;
    opt->orient = 1;
}

static fm_status check_input(const fm_mesh *in, const fm_repair_options *opt, fm_error *err)
{
    if (!(opt->weld_tolerance >= 0) || !isfinite(opt->weld_tolerance))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "repair: bad weld tolerance %g",
                            opt->weld_tolerance);
    if (!(opt->min_fragment_area_fraction >= 0) || !isfinite(opt->min_fragment_area_fraction))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "repair: bad fragment area fraction %g",
                            opt->min_fragment_area_fraction);
    size_t nv = fm_mesh_nvertices(in), nt = fm_mesh_ntriangles(in);
    /* Half-edges and corners (3 per triangle) are numbered in int32. */
    if (nt > (size_t)INT32_MAX / 3)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "repair: %zu triangles exceed the supported maximum", nt);
    const double *xyz = fm_mesh_vertices(in);
    for (size_t i = 0; i < 3 * nv; i++)
        if (!isfinite(xyz[i]))
            return fm_error_set(err, FM_ERR_NUMERIC, NULL, 0,
                                "repair: vertex %zu has a non-finite coordinate", i / 3);
    const int32_t *tri = fm_mesh_triangles(in);
    for (size_t i = 0; i < 3 * nt; i++)
        if (tri[i] < 0 || (size_t)tri[i] >= nv)
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                "repair: triangle %zu uses vertex %ld of %zu", i / 3,
                                (long)tri[i], nv);
    return FM_OK;
}

/* Working arrays of one run, freed together. */
typedef struct work {
    int32_t *rep;
    rep_tris tris;
    rep_edges edges;
    int32_t *nbr, *sheet, *key;
    uint8_t *flip;
    double *normals;
} work;

static void work_free(work *w)
{
    free(w->rep);
    rep_tris_free(&w->tris);
    rep_edges_free(&w->edges);
    free(w->nbr);
    free(w->sheet);
    free(w->key);
    free(w->flip);
    free(w->normals);
}

static fm_status run(const fm_mesh *in, const fm_repair_options *opt, fm_surface *s, work *w,
                     fm_error *err)
{
    fm_repair_report *r = &s->report;
    size_t nv = fm_mesh_nvertices(in);
    const double *xyz = fm_mesh_vertices(in);
    fm_status st;

    w->rep = malloc((nv ? nv : 1) * sizeof *w->rep);
    if (!w->rep)
        return FM_ERR_NOMEM;
    if ((st = rep_weld_exact(xyz, nv, w->rep, &r->welded_exact)) != FM_OK)
        return st;
    if (opt->weld_tolerance > 0 &&
        (st = rep_weld_tolerance(xyz, nv, opt->weld_tolerance, w->rep, &r->welded_tolerance,
                                 err)) != FM_OK)
        return st;

    if ((st = rep_clean(in, w->rep, &w->tris, r)) != FM_OK ||
        (st = rep_count_unused(&w->tris, w->rep, nv, &r->unused_vertices)) != FM_OK ||
        (st = rep_drop_fragments(&w->tris, xyz, nv, opt, r)) != FM_OK)
        return st;

    size_t n = w->tris.n, nsheets = 0;
    int split = opt->split_nonmanifold != 0;
    if ((st = rep_edges_build(&w->tris, nv, &w->edges)) != FM_OK)
        return st;
    w->nbr = malloc(3 * (n ? n : 1) * sizeof *w->nbr);
    w->key = malloc(3 * (n ? n : 1) * sizeof *w->key);
    w->sheet = malloc((n ? n : 1) * sizeof *w->sheet);
    w->flip = malloc(n ? n : 1);
    if (!w->nbr || !w->key || !w->sheet || !w->flip)
        return FM_ERR_NOMEM;
    if ((st = rep_pair_edges(&w->tris, &w->edges, xyz, split, w->nbr, &r->nonmanifold_edges)) !=
            FM_OK ||
        (st = rep_corner_keys(&w->tris, w->nbr, split, w->key)) != FM_OK ||
        (st = rep_sheets(&w->tris, &w->edges, w->nbr, split, w->sheet, &nsheets)) != FM_OK)
        return st;
    r->sheets = nsheets;

    w->normals = malloc(3 * (nsheets ? nsheets : 1) * sizeof *w->normals);
    if (!w->normals)
        return FM_ERR_NOMEM;
    if ((st = rep_orient(&w->tris, w->nbr, w->sheet, nsheets, xyz, opt->orient != 0, w->flip,
                         w->normals, r)) != FM_OK)
        return st;
    size_t nkeys = split ? 3 * n : nv;
    if ((st = rep_extract_sheets(s, &w->tris, w->sheet, nsheets, w->key, nkeys, w->nbr, w->flip,
                                 w->normals, xyz, nv)) != FM_OK)
        return st;
    return rep_junctions(s, &w->tris, &w->edges, w->sheet, xyz, nv);
}

fm_status fm_repair(const fm_mesh *in, const fm_repair_options *opt, fm_surface **out,
                    fm_error *err)
{
    if (out)
        *out = NULL;
    if (!in || !out)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "repair: no mesh or no output");
    fm_repair_options defaults;
    if (!opt) {
        fm_repair_options_default(&defaults);
        opt = &defaults;
    }
    fm_status st = check_input(in, opt, err);
    if (st != FM_OK)
        return st;
    fm_surface *s = rep_surface_create();
    if (!s)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "repair: out of memory");
    s->report.vertices_in = fm_mesh_nvertices(in);
    s->report.triangles_in = fm_mesh_ntriangles(in);
    work w = {0};
    st = run(in, opt, s, &w, err);
    work_free(&w);
    if (st != FM_OK) {
        fm_surface_destroy(s);
        if (st == FM_ERR_NOMEM)
            return fm_error_set(err, st, NULL, 0, "repair: out of memory");
        return st; /* err already filled by the step */
    }
    *out = s;
    return FM_OK;
}
