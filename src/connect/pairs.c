/* Neighbours: sheets of different faults whose grown surfaces cross or
 * come within D (see fm_connect.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "connect_internal.h"

struct fm_connect_pairs {
    fm_connect_pair *pair;
    size_t n, cap;
    fm_connect_pairs_stats stats;
};

void fm_connect_options_default(fm_connect_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->distance = 1000.0;
    opt->reach = -1.0;
    opt->sample_spacing = 250.0;
    opt->spacing = 250.0;
    opt->tolerance = 1e-6;
    opt->clip_to_reach = 1;
}

void fm_connect_pairs_destroy(fm_connect_pairs *p)
{
    if (!p)
        return;
    free(p->pair);
    free(p);
}

size_t fm_connect_pairs_count(const fm_connect_pairs *p) { return p ? p->n : 0; }

const fm_connect_pair *fm_connect_pairs_get(const fm_connect_pairs *p, size_t i)
{
    return p && i < p->n ? p->pair + i : NULL;
}

const fm_connect_pairs_stats *fm_connect_pairs_get_stats(const fm_connect_pairs *p)
{
    return &p->stats;
}

typedef struct measure_ctx {
    const double *xa;       /* vertices of the A triangle being tested */
    const fm_mesh *mb;
    const double *const *ta;
    int found;
} measure_ctx;

static int test_triangle(int32_t t, void *user)
{
    measure_ctx *c = user;
    const double *X = fm_mesh_vertices(c->mb);
    const int32_t *T = fm_mesh_triangles(c->mb) + 3 * (size_t)t;
    const double *tb[3] = {X + 3 * T[0], X + 3 * T[1], X + 3 * T[2]};
    if (cn_triangles_intersect(c->ta, tb)) {
        c->found = 1;
        return 1;
    }
    return 0;
}

/* Crossing and smallest vertex-to-mesh distance (within maxd) of two clipped
 * meshes; returns the distance (INFINITY: none within maxd). */
static fm_status measure(const fm_mesh *ma, const fm_mesh *mb, double maxd, int *crosses,
                         double pa[3], double pb[3], double *dist, fm_error *err)
{
    *crosses = 0;
    *dist = INFINITY;
    if (!fm_mesh_ntriangles(ma) || !fm_mesh_ntriangles(mb))
        return FM_OK;
    fm_closest_tree *ta = fm_closest_tree_create(ma, err);
    fm_closest_tree *tb = ta ? fm_closest_tree_create(mb, err) : NULL;
    if (!ta || !tb) {
        fm_closest_tree_destroy(ta);
        return err ? err->code : FM_ERR_NOMEM;
    }
    const double *XA = fm_mesh_vertices(ma), *XB = fm_mesh_vertices(mb);
    const int32_t *TA = fm_mesh_triangles(ma);
    size_t nta = fm_mesh_ntriangles(ma);
    for (size_t t = 0; t < nta && !*crosses; t++) {
        const double *tri[3] = {XA + 3 * TA[3 * t], XA + 3 * TA[3 * t + 1], XA + 3 * TA[3 * t + 2]};
        double lo[3], hi[3];
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(fmin(tri[0][k], tri[1][k]), tri[2][k]);
            hi[k] = fmax(fmax(tri[0][k], tri[1][k]), tri[2][k]);
        }
        measure_ctx c = {XA, mb, tri, 0};
        fm_closest_tree_box_query(tb, lo, hi, test_triangle, &c);
        if (c.found) {
            *crosses = 1;
            *dist = 0;
            for (int k = 0; k < 3; k++)
                pa[k] = (tri[0][k] + tri[1][k] + tri[2][k]) / 3.0;
            fm_closest_hit h;
            if (fm_closest_query(tb, pa, INFINITY, &h))
                memcpy(pb, h.foot, sizeof h.foot);
        }
    }
    if (!*crosses) {
        double best = maxd;
        for (int side = 0; side < 2; side++) {
            const fm_mesh *from = side ? mb : ma;
            const fm_closest_tree *to = side ? ta : tb;
            const double *X = side ? XB : XA;
            for (size_t v = 0; v < fm_mesh_nvertices(from); v++) {
                fm_closest_hit h;
                if (fm_closest_query(to, X + 3 * v, best, &h) && h.dist < *dist) {
                    *dist = best = h.dist;
                    memcpy(side ? pb : pa, X + 3 * v, 3 * sizeof(double));
                    memcpy(side ? pa : pb, h.foot, 3 * sizeof(double));
                }
            }
        }
    }
    fm_closest_tree_destroy(ta);
    fm_closest_tree_destroy(tb);
    return FM_OK;
}

static int boxes_near(const cn_sheet *a, const cn_sheet *b, double d)
{
    for (int k = 0; k < 3; k++)
        if (a->lo[k] - d > b->hi[k] || b->lo[k] - d > a->hi[k])
            return 0;
    return 1;
}

static fm_status push_pair(fm_connect_pairs *p, const fm_connect_pair *x)
{
    if (p->n == p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 64;
        fm_connect_pair *np = realloc(p->pair, cap * sizeof *np);
        if (!np)
            return FM_ERR_NOMEM;
        p->pair = np;
        p->cap = cap;
    }
    p->pair[p->n++] = *x;
    return FM_OK;
}

/* Measures one candidate pair; *keep is set when it is within D. */
static fm_status measure_pair(const cn_sheet *a, const cn_sheet *b, const fm_connect_options *o,
                              double reach, unsigned char *sel_a, unsigned char *sel_b,
                              fm_connect_pair *out, int *keep, int *meshed, fm_error *err)
{
    *keep = 0;
    *meshed = 0;
    double D = o->distance;
    if (!cn_select_cells(a, b, D, sel_a) || !cn_select_cells(b, a, D, sel_b))
        return FM_OK;
    *meshed = 1;
    cn_zone za, zb;
    fm_status st = cn_zone_build(a, sel_a, cn_subdivision(a, o->sample_spacing), &za);
    if (st == FM_OK && (st = cn_zone_build(b, sel_b, cn_subdivision(b, o->sample_spacing), &zb)) != FM_OK)
        cn_zone_free(&za);
    if (st != FM_OK)
        return fm_error_set(err, st, NULL, 0, "connect: out of memory");
    fm_mesh *ga = cn_zone_clip(&za, reach), *gb = cn_zone_clip(&zb, reach);
    fm_mesh *ra = NULL, *rb = NULL;
    memset(out, 0, sizeof *out);
    out->fault_a = a->fault;
    out->sheet_a = a->sheet;
    out->fault_b = b->fault;
    out->sheet_b = b->sheet;
    if (!ga || !gb) {
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
        goto done;
    }
    st = measure(ga, gb, D, &out->crosses, out->point_a, out->point_b, &out->distance, err);
    if (st != FM_OK || !(out->distance <= D))
        goto done;
    *keep = 1;
    ra = cn_zone_clip(&za, 0.0);
    rb = cn_zone_clip(&zb, 0.0);
    if (!ra || !rb) {
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
        goto done;
    }
    double pa[3], pb[3];
    st = measure(ra, rb, D + 2 * reach, &out->trimmed_crosses, pa, pb, &out->trimmed_distance, err);
done:
    fm_mesh_destroy(ga);
    fm_mesh_destroy(gb);
    fm_mesh_destroy(ra);
    fm_mesh_destroy(rb);
    cn_zone_free(&za);
    cn_zone_free(&zb);
    return st;
}

fm_status fm_connect_find_pairs(const fm_model *const *models, size_t n,
                                const fm_connect_options *opt, fm_connect_pairs **out,
                                fm_error *err)
{
    fm_connect_options o;
    if (opt)
        o = *opt;
    else
        fm_connect_options_default(&o);
    *out = NULL;
    if (!(o.distance >= 0) || !isfinite(o.distance))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "connect: bad distance %g", o.distance);
    double reach = o.reach < 0 ? o.distance : o.reach;
    fm_connect_pairs *p = calloc(1, sizeof *p);
    size_t ns = 0;
    for (size_t i = 0; i < n; i++)
        ns += models && models[i] ? fm_model_nsheets(models[i]) : 0;
    cn_sheet *sh = calloc(ns ? ns : 1, sizeof *sh);
    if (!p || !sh) {
        free(p);
        free(sh);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    }
    fm_status st = FM_OK;
    double t0 = fm_clock_seconds();
    size_t built = 0, maxcells = 0;
    for (size_t i = 0; i < n && st == FM_OK; i++) {
        if (!models[i])
            continue;
        for (size_t k = 0; k < fm_model_nsheets(models[i]) && st == FM_OK; k++) {
            st = cn_sheet_build(models[i], i, k, reach, &sh[built], err);
            if (st == FM_OK) {
                p->stats.cells += sh[built].nactive;
                if (sh[built].nsu * sh[built].nsv > maxcells)
                    maxcells = sh[built].nsu * sh[built].nsv;
                built++;
            }
        }
    }
    p->stats.sheets = built;
    double t1 = fm_clock_seconds();
    p->stats.time_sample = t1 - t0;
    unsigned char *sel_a = malloc(maxcells ? maxcells : 1), *sel_b = malloc(maxcells ? maxcells : 1);
    if (st == FM_OK && (!sel_a || !sel_b))
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    double tc = 0;
    for (size_t i = 0; i < built && st == FM_OK; i++)
        for (size_t j = i + 1; j < built && st == FM_OK; j++) {
            if (sh[i].fault == sh[j].fault || !sh[i].nactive || !sh[j].nactive)
                continue;
            double c0 = fm_clock_seconds();
            int near = boxes_near(&sh[i], &sh[j], o.distance);
            tc += fm_clock_seconds() - c0;
            if (!near)
                continue;
            p->stats.candidates++;
            fm_connect_pair x;
            int keep, meshed;
            st = measure_pair(&sh[i], &sh[j], &o, reach, sel_a, sel_b, &x, &keep, &meshed, err);
            p->stats.measured += (size_t)meshed;
            if (st == FM_OK && keep && push_pair(p, &x) != FM_OK)
                st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
        }
    p->stats.time_candidates = tc;
    p->stats.time_measure = fm_clock_seconds() - t1 - tc;
    free(sel_a);
    free(sel_b);
    for (size_t i = 0; i < built; i++)
        cn_sheet_free(&sh[i]);
    free(sh);
    if (st != FM_OK) {
        fm_connect_pairs_destroy(p);
        return st;
    }
    *out = p;
    return FM_OK;
}
