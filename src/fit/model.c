/* The trimmed surface model of a fault: fit, trim, sample and measure
 * every sheet (see fm_model.h). */
#include "fm_model.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit_internal.h"
#include "fm_clock.h"
#include "fm_closest.h"
#include "fm_sort.h"
#include "model_internal.h"

void fm_model_options_default(fm_model_options *opt)
{
    fm_fit_options_default(&opt->fit);
    fm_trim_options_default(&opt->trim);
    /* The outline target bounds the largest 3D distance, not only the
     * systematic one: refine also where a single boundary vertex is off.
     * Half the 100 m target: the curve is fitted in the parameter plane
     * and lies on a surface that is itself off the boundary by up to tens
     * of metres, and a jog or spike of the boundary (a 230 m step, a
     * 160 m spike on CFM 5.3) left at 80 m ended 105 to 125 m off in 3D. */
    opt->trim.max_deviation = 50;
    opt->sample_levels = 2;
    opt->measure_samples = 1;
}

static void sheet_free(sheet_model *sm)
{
    fm_fit_surface_destroy(sm->surface);
    for (size_t k = 0; k < sm->nloops; k++)
        fm_trim_loop_destroy(sm->loops[k]);
    free(sm->loops);
    free(sm->loop_scale);
    fm_mesh_destroy(sm->samples);
    free(sm->sample_dist);
}

void fm_model_destroy(fm_model *m)
{
    if (!m)
        return;
    for (size_t i = 0; i < m->nsheets; i++)
        sheet_free(&m->sheets[i]);
    free(m->sheets);
    for (size_t i = 0; i < m->ncuts; i++)
        free(m->cuts[i].xyz);
    free(m->cuts);
    free(m);
}

size_t fm_model_nsheets(const fm_model *m) { return m->nsheets; }
const fm_fit_surface *fm_model_surface(const fm_model *m, size_t i) { return m->sheets[i].surface; }
size_t fm_model_nloops(const fm_model *m, size_t i) { return m->sheets[i].nloops; }
const fm_trim_loop *fm_model_loop(const fm_model *m, size_t i, size_t k)
{
    return m->sheets[i].loops[k];
}
const fm_sheet_report *fm_model_report(const fm_model *m, size_t i) { return &m->sheets[i].report; }
const fm_mesh *fm_model_samples(const fm_model *m, size_t i) { return m->sheets[i].samples; }
const double *fm_model_sample_distance(const fm_model *m, size_t i)
{
    return m->sheets[i].sample_dist;
}
size_t fm_model_ncuts(const fm_model *m) { return m->ncuts; }
const double *fm_model_cut(const fm_model *m, size_t c, size_t *npoints, long sheets[2])
{
    *npoints = m->cuts[c].n;
    sheets[0] = m->cuts[c].sheets[0];
    sheets[1] = m->cuts[c].sheets[1];
    return m->cuts[c].xyz;
}

/* Loop order of the model: the outer loop first, then the holes in the
 * order repair found them. */
static size_t repair_loop_index(const fm_surface *s, size_t sheet, size_t k)
{
    long outer = fm_surface_sheet_outer_loop(s, sheet);
    if (outer < 0)
        return k;
    if (k == 0)
        return (size_t)outer;
    return k <= (size_t)outer ? k - 1 : k;
}

static double median_spacing(const double *uv, size_t n)
{
    double *d = malloc(n * sizeof *d);
    if (!d)
        return 0.0;
    for (size_t i = 0; i < n; i++) {
        const double *a = uv + 2 * i, *b = uv + 2 * ((i + 1) % n);
        d[i] = hypot(b[0] - a[0], b[1] - a[1]);
    }
    double med = fm_median(d, n);
    free(d);
    return med;
}

/* First fundamental form E, F, G of the surface at each loop point, for
 * fm_trim_fit_metric: the trimming curves are then fitted to a 3D
 * tolerance, with knots and corner windows in 3D metres, whatever the
 * slope of a height field or the scale of a flattening map. Returns the
 * largest 3D length of a unit (u, v) step over the points. */
static double loop_metric(const fm_fit_surface *surf, const double *luv, size_t np,
                          double *metric)
{
    double smax = 0.0;
    for (size_t q = 0; q < np; q++) {
        double p[3], su[3], sv[3];
        fm_fit_surface_eval(surf, luv[2 * q], luv[2 * q + 1], p, su, sv);
        double E = su[0] * su[0] + su[1] * su[1] + su[2] * su[2];
        double F = su[0] * sv[0] + su[1] * sv[1] + su[2] * sv[2];
        double G = sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2];
        metric[3 * q] = E;
        metric[3 * q + 1] = F;
        metric[3 * q + 2] = G;
        /* largest eigenvalue of the form */
        double h = 0.5 * (E + G), r = sqrt(0.25 * (E - G) * (E - G) + F * F);
        if (isfinite(h + r))
            smax = fmax(smax, sqrt(h + r));
    }
    return smax;
}

/* Fits the trimming loops of one sheet. uv: parameters of the sheet's
 * vertices. */
/* Is p an end of one of the cuts, or a vertex where a cut turns by
 * `angle` degrees or more (exact coordinates: pieces copy them)? A cut
 * runs along the sheet's edges and turns from edge to edge; a trimming
 * curve smoothed over such a turn leaves the cut, which is both the
 * piece's outline and where its neighbour must meet it (Garnet Hill: a
 * 41 degree turn of a cut between 500 m edges, 103 m off). */
static int cut_corner(const double p[3], const fm_split_cut *cuts, size_t ncuts, double angle)
{
    double cmin = cos(angle * 3.14159265358979323846 / 180);
    for (size_t c = 0; c < ncuts; c++) {
        const double *x = cuts[c].xyz;
        size_t n = cuts[c].n;
        for (size_t i = 0; i < n; i++) {
            if (memcmp(p, x + 3 * i, 3 * sizeof *p) != 0)
                continue;
            if (i == 0 || i + 1 == n)
                return 1;
            double a[3], b[3], aa = 0, bb = 0, ab = 0;
            for (int k = 0; k < 3; k++) {
                a[k] = x[3 * i + k] - x[3 * (i - 1) + k];
                b[k] = x[3 * (i + 1) + k] - x[3 * i + k];
                aa += a[k] * a[k];
                bb += b[k] * b[k];
                ab += a[k] * b[k];
            }
            if (aa > 0 && bb > 0 && ab <= cmin * sqrt(aa * bb))
                return 1;
        }
    }
    return 0;
}

static fm_status fit_loops(const char *name, const fm_surface *s, size_t sheet,
                           const double *uv, const fm_trim_options *topt,
                           const fm_split_cut *cuts, size_t ncuts, sheet_model *sm, fm_error *err)
{
    const double *X = fm_mesh_vertices(fm_surface_sheet_mesh(s, sheet));
    size_t n = fm_surface_sheet_nloops(s, sheet);
    sm->loops = calloc(n ? n : 1, sizeof *sm->loops);
    sm->loop_scale = calloc(n ? n : 1, sizeof *sm->loop_scale);
    if (!sm->loops || !sm->loop_scale)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    for (size_t k = 0; k < n; k++) {
        size_t np;
        const int32_t *lv = fm_surface_sheet_loop(s, sheet, repair_loop_index(s, sheet, k), &np);
        double *luv = malloc(2 * (np ? np : 1) * sizeof *luv);
        double *metric = malloc(3 * (np ? np : 1) * sizeof *metric);
        unsigned char *corner = calloc(np ? np : 1, 1);
        if (!luv || !metric || !corner) {
            free(luv);
            free(metric);
            free(corner);
            return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
        }
        int forced = 0;
        for (size_t q = 0; q < np; q++) {
            luv[2 * q] = uv[2 * lv[q]];
            luv[2 * q + 1] = uv[2 * lv[q] + 1];
            /* where a cut meets the outline the piece's boundary turns from
             * the one to the other: a corner of the piece, however gently
             * the two part over the corner window; so where the cut turns */
            corner[q] = (unsigned char)cut_corner(X + 3 * lv[q], cuts, ncuts, topt->corner_angle);
            forced |= corner[q];
        }
        sm->loop_scale[k] = loop_metric(sm->surface, luv, np, metric);
        fm_trim_options o = *topt;
        o.name = name;
        o.corner_at = forced ? corner : NULL;
        fm_status st = fm_trim_fit_metric(luv, metric, np, &o, &sm->loops[k], err);
        free(luv);
        free(metric);
        free(corner);
        if (st != FM_OK)
            return st;
        sm->nloops = k + 1;
        const fm_trim_stats *ts = fm_trim_loop_stats(sm->loops[k]);
        sm->report.corners += ts->corners;
        sm->report.trim_pieces += ts->pieces;
    }
    sm->report.loops = n;
    sm->report.holes = fm_surface_sheet_outer_loop(s, sheet) >= 0 && n ? n - 1 : n;
    return FM_OK;
}

/* Samples of each trimming loop in (u, v) and on the surface. */
typedef struct {
    double *uv, *xyz;
    size_t n;
    fm_seggrid *grid;
} loop_samples;

static void loop_samples_free(loop_samples *ls, size_t n)
{
    for (size_t k = 0; ls && k < n; k++) {
        free(ls[k].uv);
        free(ls[k].xyz);
        fm_seggrid_destroy(ls[k].grid);
    }
    free(ls);
}

/* Original boundary -> trimmed outline and back, in 3D. The nearest
 * segment in (u, v) locates the neighbourhood; the 3D distance is taken to
 * the segments around it, because the surface's slope makes 3D and
 * parameter distances differ. */
static double near_3d(const double p[3], const double *xyz, size_t n, size_t seg)
{
    double best = INFINITY;
    for (long o = -2; o <= 2; o++) {
        size_t i = (size_t)(((long)seg + o + (long)n) % (long)n);
        double d = fm_segment_distance3(p, xyz + 3 * i, xyz + 3 * ((i + 1) % n));
        best = d < best ? d : best;
    }
    return best;
}

/* The diagonal of sheet's bounding box (m). */
static double sheet_diagonal(const fm_surface *s, size_t sheet)
{
    const fm_mesh *mesh = fm_surface_sheet_mesh(s, sheet);
    const double *X = fm_mesh_vertices(mesh);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < fm_mesh_nvertices(mesh); v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], X[3 * v + k]);
            hi[k] = fmax(hi[k], X[3 * v + k]);
        }
    double d2 = 0;
    for (int k = 0; k < 3; k++)
        d2 += hi[k] > lo[k] ? (hi[k] - lo[k]) * (hi[k] - lo[k]) : 0;
    return sqrt(d2);
}

static fm_status measure_outline(const fm_surface *s, size_t sheet, const double *uv,
                                 const loop_samples *ls, sheet_model *sm)
{
    const fm_mesh *mesh = fm_surface_sheet_mesh(s, sheet);
    const double *X = fm_mesh_vertices(mesh);
    double maxd = 0.0, sum2 = 0.0;
    size_t count = 0;
    for (size_t k = 0; k < sm->nloops; k++) {
        size_t np;
        const int32_t *lv = fm_surface_sheet_loop(s, sheet, repair_loop_index(s, sheet, k), &np);
        double *ouv = malloc(2 * np * sizeof *ouv), *oxyz = malloc(3 * np * sizeof *oxyz);
        if (!ouv || !oxyz) {
            free(ouv);
            free(oxyz);
            return FM_ERR_NOMEM;
        }
        for (size_t q = 0; q < np; q++) {
            memcpy(ouv + 2 * q, uv + 2 * lv[q], 2 * sizeof *ouv);
            memcpy(oxyz + 3 * q, X + 3 * lv[q], 3 * sizeof *oxyz);
        }
        for (size_t q = 0; q < np; q++) {
            double foot[2], t;
            size_t seg = fm_seggrid_nearest(ls[k].grid, ouv + 2 * q, foot, &t);
            double d = near_3d(oxyz + 3 * q, ls[k].xyz, ls[k].n, seg);
            maxd = fmax(maxd, d);
            sum2 += d * d;
            count++;
        }
        fm_seggrid *og = fm_seggrid_create(ouv, np, median_spacing(ouv, np));
        if (!og) {
            free(ouv);
            free(oxyz);
            return FM_ERR_NOMEM;
        }
        for (size_t q = 0; q < ls[k].n; q++) {
            double foot[2], t;
            size_t seg = fm_seggrid_nearest(og, ls[k].uv + 2 * q, foot, &t);
            maxd = fmax(maxd, near_3d(ls[k].xyz + 3 * q, oxyz, np, seg));
        }
        fm_seggrid_destroy(og);
        free(ouv);
        free(oxyz);
    }
    sm->report.outline_max = maxd;
    sm->report.outline_rms = count ? sqrt(sum2 / (double)count) : 0.0;
    return FM_OK;
}

/* The trimmed surface sampled on the subdivided sheet triangulation, its
 * boundary points moved onto the trimming curves. */
static fm_status sample_trimmed(const fm_surface *s, size_t sheet, const double *uv,
                                const loop_samples *ls, int levels, int measure,
                                sheet_model *sm)
{
    const fm_mesh *mesh = fm_surface_sheet_mesh(s, sheet);
    size_t nv = fm_mesh_nvertices(mesh), nt = fm_mesh_ntriangles(mesh);
    fm_submesh sub = {0};
    sub.nv = nv;
    sub.nt = nt;
    sub.uv = malloc(2 * nv * sizeof *sub.uv);
    sub.loop = malloc(nv * sizeof *sub.loop);
    sub.tri = malloc(3 * nt * sizeof *sub.tri + 1);
    if (!sub.uv || !sub.loop || !sub.tri) {
        fm_submesh_free(&sub);
        return FM_ERR_NOMEM;
    }
    memcpy(sub.uv, uv, 2 * nv * sizeof *sub.uv);
    memcpy(sub.tri, fm_mesh_triangles(mesh), 3 * nt * sizeof *sub.tri);
    for (size_t v = 0; v < nv; v++)
        sub.loop[v] = -1;
    for (size_t k = 0; k < sm->nloops; k++) {
        size_t np;
        const int32_t *lv = fm_surface_sheet_loop(s, sheet, repair_loop_index(s, sheet, k), &np);
        for (size_t q = 0; q < np; q++)
            sub.loop[lv[q]] = (int32_t)k;
    }
    fm_status st = fm_submesh_refine(&sub, levels);
    if (st != FM_OK) {
        fm_submesh_free(&sub);
        return st;
    }
    unsigned char *on_trim = calloc(sub.nv ? sub.nv : 1, 1);
    if (!on_trim) {
        fm_submesh_free(&sub);
        return FM_ERR_NOMEM;
    }
    for (size_t v = 0; v < sub.nv; v++) {
        if (sub.loop[v] < 0)
            continue;
        on_trim[v] = 1;
        double foot[2], t;
        fm_seggrid_nearest(ls[sub.loop[v]].grid, sub.uv + 2 * v, foot, &t);
        sub.uv[2 * v] = foot[0];
        sub.uv[2 * v + 1] = foot[1];
    }
    sm->samples = fm_mesh_create();
    if (!sm->samples || fm_mesh_reserve(sm->samples, sub.nv, sub.nt) != FM_OK) {
        fm_submesh_free(&sub);
        free(on_trim);
        return FM_ERR_NOMEM;
    }
    for (size_t v = 0; v < sub.nv; v++) {
        double p[3];
        fm_fit_surface_eval(sm->surface, sub.uv[2 * v], sub.uv[2 * v + 1], p, NULL, NULL);
        fm_mesh_add_vertex(sm->samples, p[0], p[1], p[2]);
    }
    for (size_t t = 0; t < sub.nt; t++)
        fm_mesh_add_triangle(sm->samples, sub.tri[3 * t], sub.tri[3 * t + 1], sub.tri[3 * t + 2],
                             (int32_t)sheet);
    fm_submesh_free(&sub);

    size_t ns = fm_mesh_nvertices(sm->samples);
    sm->report.samples = ns;
    if (!measure) {
        free(on_trim);
        return FM_OK;
    }
    /* trimmed surface -> original triangulation */
    fm_closest_tree *tree = fm_closest_tree_create(mesh, NULL);
    sm->sample_dist = malloc((ns ? ns : 1) * sizeof *sm->sample_dist);
    if (!tree || !sm->sample_dist) {
        fm_closest_tree_destroy(tree);
        free(on_trim);
        return FM_ERR_NOMEM;
    }
    const double *S = fm_mesh_vertices(sm->samples);
    double sum2 = 0.0, maxd = 0.0;
    size_t counted = 0;
    for (size_t v = 0; v < ns; v++) {
        fm_closest_hit hit;
        fm_closest_query(tree, S + 3 * v, INFINITY, &hit);
        sm->sample_dist[v] = hit.dist;
        /* Samples moved onto the trimming curves lie off the original
         * outline by the outline deviation, which is measured (and
         * bounded) on its own; counting them here would mix a lateral
         * offset into a distance across the surface. */
        if (on_trim[v])
            continue;
        sum2 += hit.dist * hit.dist;
        maxd = fmax(maxd, hit.dist);
        counted++;
    }
    free(on_trim);
    fm_closest_tree_destroy(tree);
    sm->report.from_trimmed_rms = counted ? sqrt(sum2 / (double)counted) : 0.0;
    sm->report.from_trimmed_max = maxd;
    return FM_OK;
}

static fm_status build_loop_samples(const sheet_model *sm, double spacing, loop_samples **out,
                                    fm_error *err, const char *name)
{
    loop_samples *ls = calloc(sm->nloops ? sm->nloops : 1, sizeof *ls);
    if (!ls)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    for (size_t k = 0; k < sm->nloops; k++) {
        /* spacing is meant in 3D: in (u, v) it shrinks by the loop's
         * largest scale, so a flattening map that shrinks the plane does
         * not coarsen the samples (and the outline measured on them). */
        double sk = spacing;
        if (sm->loop_scale && sm->loop_scale[k] > 1.0)
            sk = spacing / fmin(sm->loop_scale[k], 8.0);
        fm_status st = fm_trim_loop_sample(sm->loops[k], sk, &ls[k].uv, &ls[k].n, NULL, err);
        if (st == FM_OK) {
            ls[k].xyz = malloc(3 * ls[k].n * sizeof *ls[k].xyz);
            ls[k].grid = fm_seggrid_create(ls[k].uv, ls[k].n, 4.0 * spacing);
            if (!ls[k].xyz || !ls[k].grid)
                st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
        }
        if (st != FM_OK) {
            loop_samples_free(ls, sm->nloops);
            return st;
        }
        for (size_t q = 0; q < ls[k].n; q++)
            fm_fit_surface_eval(sm->surface, ls[k].uv[2 * q], ls[k].uv[2 * q + 1],
                                ls[k].xyz + 3 * q, NULL, NULL);
    }
    *out = ls;
    return FM_OK;
}

/* The parameters of the boundary vertices moved to their closest surface
 * points (see fm_model.h): a vertex's own parameters put it where the fit
 * is, not where the surface is nearest to it. Across a steep flank of a
 * height field a small height misfit is a long way along w, and a
 * parametric fit drifts along itself where its map is distorted (corners
 * squeezed by the map); a trimming curve through the own parameters then
 * runs hundreds of metres off the original outline in 3D although the
 * surface passes within metres of it. Only a projection that converged
 * and comes closer is taken. */
static void snap_boundary(const fm_fit_surface *surf, const fm_surface *s, size_t sheet,
                          double *uv)
{
    const fm_mesh *mesh = fm_surface_sheet_mesh(s, sheet);
    const double *X = fm_mesh_vertices(mesh);
    const fm_fit_frame *fr = fm_fit_surface_frame(surf);
    size_t nl = fm_surface_sheet_nloops(s, sheet);
    for (size_t k = 0; k < nl; k++) {
        size_t np;
        const int32_t *lv = fm_surface_sheet_loop(s, sheet, k, &np);
        for (size_t q = 0; q < np; q++) {
            double *t = uv + 2 * lv[q], loc[3], P[3], d, w[2] = {t[0], t[1]};
            fm_fit_frame_to_local(fr, X + 3 * lv[q], loc);
            fm_fit_local_eval(surf, t[0], t[1], P, NULL);
            double d0 = sqrt((P[0] - loc[0]) * (P[0] - loc[0]) + (P[1] - loc[1]) * (P[1] - loc[1]) +
                             (P[2] - loc[2]) * (P[2] - loc[2]));
            if (fm_fit_project_from(surf, loc, w, P, &d) == FM_OK && fabs(d) < d0) {
                t[0] = w[0];
                t[1] = w[1];
            }
        }
    }
}

/* pf: the sheet's fit as the split decision began it (consumed), or NULL. */
static fm_status build_sheet(const char *name, const fm_surface *s, size_t sheet,
                             const fm_model_options *opt, const fm_split_cut *cuts,
                             size_t ncuts, fm_fit_pending *pf, sheet_model *sm, fm_error *err)
{
    double t0 = fm_clock_seconds();
    const fm_mesh *mesh = fm_surface_sheet_mesh(s, sheet);
    sm->report.vertices = fm_mesh_nvertices(mesh);
    sm->report.triangles = fm_mesh_ntriangles(mesh);
    fm_fit_options fo = opt->fit;
    fo.name = name;
    fm_status st = pf ? fm_fit_pending_finish(pf, &sm->surface, err)
                      : fm_fit_sheet(mesh, &fo, &sm->surface, err);
    if (st != FM_OK)
        return st;
    const fm_fit_stats *fs = fm_fit_surface_stats(sm->surface);
    sm->report.to_surface_rms = fs->rms_dist;
    sm->report.to_surface_max = fs->max_dist;

    double *uv = malloc(2 * (sm->report.vertices ? sm->report.vertices : 1) * sizeof *uv);
    if (!uv)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    st = fm_fit_sheet_vertex_params(sm->surface, mesh, uv, err);
    if (st == FM_OK)
        snap_boundary(sm->surface, s, sheet, uv);
    if (st == FM_OK)
        st = fit_loops(name, s, sheet, uv, &opt->trim, cuts, ncuts, sm, err);
    loop_samples *ls = NULL;
    double spacing = 0.25 * (fs->edge_median > 0 ? fs->edge_median : 100.0);
    if (st == FM_OK)
        st = build_loop_samples(sm, spacing, &ls, err, name);
    if (st == FM_OK) {
        st = sample_trimmed(s, sheet, uv, ls, opt->sample_levels, opt->measure_samples, sm);
        if (st == FM_OK)
            st = measure_outline(s, sheet, uv, ls, sm);
        if (st != FM_OK) {
            fm_error_set(err, st, name, 0, "sheet %zu: %s", sheet, fm_status_string(st));
        } else {
            /* A fitted outline farther from the original's than the sheet
             * is across is no fit of it (a crumpled surface: its outline
             * runs thousands of kilometres, and meshing it would take
             * minutes for nothing); the CFM's farthest is under 100 m. */
            double d = sheet_diagonal(s, sheet);
            if (sm->report.outline_max > d)
                st = fm_error_set(err, FM_ERR_NUMERIC, name, 0,
                                  "sheet %zu: the fit failed: its outline strays %.0f m from the "
                                  "original's, which is %.0f m across",
                                  sheet, sm->report.outline_max, d);
        }
    }
    loop_samples_free(ls, sm->nloops);
    free(uv);
    sm->report.time = fm_clock_seconds() - t0;
    return st;
}

/* Repaired sheet i as one model sheet, or as the disks a ring is cut
 * into (model_split.c), appended to m. */
static fm_status fm_model_build_split(fm_model *m, const char *name, const fm_surface *s,
                                      size_t i, const fm_model_options *opt, fm_error *err)
{
    fm_model_split sp;
    fm_status st = fm_model_split_sheet(name, s, i, &opt->fit, &sp, err);
    size_t base = m->nsheets, add = sp.npieces ? sp.npieces : 1;
    sheet_model *sh = st == FM_OK ? realloc(m->sheets, (base + add) * sizeof *sh) : NULL;
    fm_split_cut *cu = st == FM_OK ? realloc(m->cuts, (m->ncuts + sp.ncuts + 1) * sizeof *cu) : NULL;
    if (sh)
        m->sheets = sh;
    if (cu)
        m->cuts = cu;
    if (st == FM_OK && (!sh || !cu))
        st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    for (size_t k = 0; st == FM_OK && k < add; k++) {
        sheet_model *sm = &m->sheets[m->nsheets++];
        memset(sm, 0, sizeof *sm);
        fm_fit_pending **pf = sp.npieces ? &sp.fits[k] : &sp.whole;
        fm_fit_pending *fit = *pf;
        *pf = NULL;
        st = sp.npieces ? build_sheet(name, sp.pieces[k], 0, opt, sp.cuts, sp.ncuts, fit, sm, err)
                        : build_sheet(name, s, i, opt, NULL, 0, fit, sm, err);
        sm->report.repair_sheet = i;
    }
    for (size_t c = 0; st == FM_OK && c < sp.ncuts; c++) {
        m->cuts[m->ncuts] = sp.cuts[c];
        for (int k = 0; k < 2; k++)
            if (sp.cuts[c].sheets[k] >= 0)
                m->cuts[m->ncuts].sheets[k] += (long)base;
        m->ncuts++;
        sp.cuts[c].xyz = NULL;
    }
    fm_model_split_free(&sp);
    return st;
}

fm_status fm_model_build(const char *name, const fm_surface *s, const fm_model_options *opt,
                         fm_model **out, fm_error *err)
{
    fm_model_options def;
    if (!opt) {
        fm_model_options_default(&def);
        opt = &def;
    }
    *out = NULL;
    fm_model *m = calloc(1, sizeof *m);
    size_t n = fm_surface_nsheets(s);
    if (m)
        m->sheets = calloc(n ? n : 1, sizeof *m->sheets);
    if (!m || !m->sheets) {
        free(m);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    }
    for (size_t i = 0; i < n; i++) {
        fm_status st = fm_model_build_split(m, name, s, i, opt, err);
        if (st != FM_OK) {
            fm_model_destroy(m);
            return st;
        }
    }
    *out = m;
    return FM_OK;
}
