/* One trimmed sheet to a quality mesh: domain, constrained Delaunay
 * refinement under the surface metric, optimisation in 3D (fm_remesh.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_clock.h"
#include "remesh_internal.h"

void fm_remesh_options_default(fm_remesh_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->size = 1000;
    opt->top = FM_TOP_CUT;
    opt->top_extend = 2000;
    opt->sea_level = 0;
    opt->optimise_passes = 6;
}

void fm_remesh_model_options_default(fm_model_options *opt)
{
    fm_model_options_default(opt);
    /* 15 m systematic, 25 m at any point, not the fit's 50 m: at 1 km,
     * 3 CFM faults were over 10 m RMS node distance, none are with these
     * (at 30 m one Rose Canyon curve overshot 120 m between points). */
    opt->trim.tolerance = 15;
    opt->trim.max_deviation = 25;
    opt->sample_levels = 1;
    opt->measure_samples = 0;
}

/* A triangle with an angle under this lies on a line: no triangle of a
 * mesh meant for a simulator (slivers.c). */
#define SLIVER_DEG 1.0

static fm_status build_domain(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                              size_t nloops, const fm_remesh_options *opt,
                              remesh_domain *dom, fm_remesh_stats *st, fm_error *err)
{
    remesh_domain d0;
    fm_status rc = domain_sample(s, loops, nloops, opt->size, &d0, err, opt->name);
    if (rc != FM_OK)
        return rc;
    /* The outline's clean-up below is quadratic in its nodes; a fitted
     * outline that strays far from its fault (fuzz_fit_mesh found one
     * 400 km long on a 10 km sheet: 818,581 nodes) would run for hours.
     * The CFM's longest outline at 100 m is some 10,000 nodes. */
    size_t nodes = 0;
    for (size_t l = 0; l < d0.n; l++)
        nodes += d0.loops[l].n;
    if (nodes > FM_REMESH_MAX_OUTLINE_NODES) {
        domain_free(&d0);
        return fm_error_set(err, FM_ERR_INVALID, opt->name, 0,
                            "the outline needs %zu nodes at size %g m (at most %d): the fitted "
                            "outline strays from the fault, or the size is far too small for it",
                            nodes, opt->size, FM_REMESH_MAX_OUTLINE_NODES);
    }
    if (domain_split_sags(s, loops, &d0, opt->size)) {
        domain_free(&d0);
        return fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "out of memory");
    }
    /* A merge can leave a spike (the two sides of a slit, their nodes a
     * metre apart, become one node at its tip): despike again. */
    do
        domain_despike(s, &d0, 30.0);
    while (domain_merge_close(s, &d0, opt->size));
    if (opt->top == FM_TOP_EXTEND) {
        rc = domain_extend_top(s, &d0, opt->sea_level, opt->top_extend, opt->size, &st->extended,
                               err, opt->name);
        if (rc != FM_OK) {
            domain_free(&d0);
            return rc;
        }
    }
    if (opt->top == FM_TOP_KEEP) {
        *dom = d0;
        return FM_OK;
    }
    rc = domain_clip(s, loops, &d0, opt->sea_level, opt->size, dom, &st->cut, err, opt->name);
    domain_free(&d0);
    return rc;
}

fm_status fm_remesh_sheet(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                          size_t nloops, const fm_remesh_options *opt, int32_t tag,
                          fm_mesh **out, double **uv_out, fm_remesh_stats *st, fm_error *err)
{
    return fm_remesh_sheet_joined(s, loops, nloops, NULL, 0, opt, tag, out, uv_out, NULL, st, err);
}

fm_status fm_remesh_sheet_joined(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                                 size_t nloops, const fm_remesh_curve *curves, size_t ncurves,
                                 const fm_remesh_options *opt, int32_t tag, fm_mesh **out,
                                 double **uv_out, int64_t **node_out, fm_remesh_stats *st,
                                 fm_error *err)
{
    double t0 = fm_clock_seconds();
    memset(st, 0, sizeof *st);
    *out = NULL;
    if (uv_out)
        *uv_out = NULL;
    if (node_out)
        *node_out = NULL;
    if (!(opt->size > 0) || !isfinite(opt->size))
        return fm_error_set(err, FM_ERR_INVALID, opt->name, 0, "mesh size must be positive");
    if (nloops == 0)
        return fm_error_set(err, FM_ERR_INVALID, opt->name, 0, "sheet without outline");
    fm_mesh *mesh = fm_mesh_create();
    if (!mesh)
        return fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "out of memory");
    remesh_domain dom = {0};
    flat_domain fd = {0};
    fm_cdt *cdt = NULL;
    double *uv = NULL, *xyz = NULL;
    unsigned char *fixed = NULL;
    int32_t *tri = NULL;
    fm_status rc = build_domain(s, loops, nloops, opt, &dom, st, err);
    if (rc != FM_OK)
        goto done;
    if (dom.n == 0) {
        st->empty = 1;
        goto done;
    }
    if (ncurves > 0) {
        rc = domain_join(s, &dom, curves, ncurves, opt->size, opt->sea_level, &fd, err, opt->name);
        if (rc != FM_OK)
            goto done;
        fd.surf = s;
        fd.flap_max = opt->flap_max;
    }
    fd.flaps_kept = 0;
    rc = domain_triangulate(s, loops, opt->sea_level, &dom, opt->size, opt->max_points, &fd, &cdt,
                            err, opt->name);
    if (rc != FM_OK)
        goto done;
    st->flaps_kept = fd.flaps_kept;

    size_t np = fm_cdt_npoints(cdt), nt = fm_cdt_ntriangles(cdt), ne = fm_cdt_nedges(cdt);
    size_t ninput = fm_cdt_ninput(cdt);
    const int32_t *pseg = fm_cdt_point_segment(cdt);
    uv = malloc(2 * np * sizeof *uv + 1);
    xyz = malloc(3 * np * sizeof *xyz + 1);
    fixed = malloc(np + 1);
    tri = malloc(3 * nt * sizeof *tri + 1);
    if (!uv || !xyz || !fixed || !tri)
        goto nomem;
    memcpy(uv, fm_cdt_points(cdt), 2 * np * sizeof *uv);
    memcpy(tri, fm_cdt_triangles(cdt), 3 * nt * sizeof *tri);
    for (size_t i = 0; i < np; i++) {
        fixed[i] = pseg[i] >= 0;
        fm_fit_surface_eval(s, uv[2 * i], uv[2 * i + 1], xyz + 3 * i, NULL, NULL);
    }
    opt_result orr;
    opt_curves cv = {loops, opt->sea_level, fd.segs, fd.ends, pseg, ninput};
    rc = optimise_mesh(s, uv, xyz, fixed, np, tri, &nt, fm_cdt_edges(cdt), ne, &cv,
                       opt->optimise_passes, opt->size, &orr);
    if (rc != FM_OK)
        goto nomem;
    st->flips = orr.flips;
    st->smoothed = orr.smoothed;
    st->collapsed = orr.collapsed;
    st->slivers = mesh_collapse_slivers(uv, xyz, tri, &nt, fd.shared, fd.shared ? fd.npoints : 0,
                                        SLIVER_DEG);

    /* Only nodes used by triangles go out (input points outside the
     * domain are not). */
    int32_t *map = malloc(np * sizeof *map + 1);
    if (!map)
        goto nomem;
    size_t nout = fm_used_vertices(tri, nt, np, map);
    double *uvo = uv_out ? malloc(2 * nout * sizeof *uvo + 1) : NULL;
    int64_t *ido = node_out ? malloc(nout * sizeof *ido + 1) : NULL;
    if ((uv_out && !uvo) || (node_out && !ido) || fm_mesh_reserve(mesh, nout, nt) != FM_OK) {
        free(map);
        free(uvo);
        free(ido);
        goto nomem;
    }
    int cut = opt->top != FM_TOP_KEEP;
    for (size_t i = 0; i < np; i++) {
        if (map[i] < 0)
            continue;
        double *p = xyz + 3 * i;
        int on_level = i < ninput ? fd.level[i] : (pseg[i] >= 0 && fd.segs[pseg[i]].kind == SEG_LEVEL);
        /* An outline node within a metre below sea level is on the top
         * trace of a fault whose original was cut at sea level already:
         * it goes onto the line, so the top edge is exactly z = 0. */
        if (cut && (on_level || (fixed[i] && p[2] > opt->sea_level - 1.0))) {
            p[2] = opt->sea_level;
            st->level_points++;
        } else if (cut && p[2] > opt->sea_level) {
            /* A node between two sea-level nodes can sit a hair above
             * the line where the level curve bends between them. */
            st->clamp_max = fmax(st->clamp_max, p[2] - opt->sea_level);
            p[2] = opt->sea_level;
            st->clamped++;
        }
        st->boundary_points += fixed[i];
        fm_mesh_add_vertex(mesh, p[0], p[1], p[2]);
        if (uvo)
            memcpy(uvo + 2 * map[i], uv + 2 * i, 2 * sizeof *uvo);
        if (ido)
            ido[map[i]] = fd.shared && i < fd.npoints ? fd.shared[i] : -1;
    }
    for (size_t t = 0; t < nt; t++)
        fm_mesh_add_triangle(mesh, map[tri[3 * t]], map[tri[3 * t + 1]], map[tri[3 * t + 2]], tag);
    free(map);
    if (uv_out)
        *uv_out = uvo;
    if (node_out)
        *node_out = ido;
    st->points = nout;
    st->triangles = nt;
    goto done;
nomem:
    rc = fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "out of memory");
done:
    fm_cdt_destroy(cdt);
    flat_free(&fd);
    domain_free(&dom);
    free(uv);
    free(xyz);
    free(fixed);
    free(tri);
    st->time = fm_clock_seconds() - t0;
    if (rc != FM_OK) {
        fm_mesh_destroy(mesh);
        return rc;
    }
    *out = mesh;
    return FM_OK;
}
