/* Neighbours: sheets of different faults whose grown surfaces cross or
 * come within D (see fm_connect.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "connect_internal.h"
#include "fm_predicates.h"

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
    opt->nthreads = 1;
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

fm_connect_pairs *cn_pairs_copy(const fm_connect_pair *pair, size_t n)
{
    fm_connect_pairs *p = calloc(1, sizeof *p);
    if (p)
        p->pair = malloc((n + 1) * sizeof *p->pair);
    if (!p || !p->pair) {
        fm_connect_pairs_destroy(p);
        return NULL;
    }
    if (n)
        memcpy(p->pair, pair, n * sizeof *pair);
    p->n = p->cap = n;
    return p;
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
    /* any common point counts (a touch too): no perturbation needed */
    if (fm_triangles_meet(c->ta, tb)) {
        c->found = 1;
        return 1;
    }
    return 0;
}

/* Crossing and smallest vertex-to-mesh distance (within maxd) of two clipped
 * meshes; returns the distance (INFINITY: none within maxd). The crossing
 * test needs only B's tree: A's is built when they do not cross. */
static fm_status measure(const fm_mesh *ma, const fm_mesh *mb, double maxd, int *crosses,
                         double pa[3], double pb[3], double *dist, fm_error *err)
{
    *crosses = 0;
    *dist = INFINITY;
    if (!fm_mesh_ntriangles(ma) || !fm_mesh_ntriangles(mb))
        return FM_OK;
    fm_closest_tree *tb = fm_closest_tree_create_quick(mb, err), *ta = NULL;
    if (!tb)
        return err ? err->code : FM_ERR_NOMEM;
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
        ta = fm_closest_tree_create_quick(ma, err);
        if (!ta) {
            fm_closest_tree_destroy(tb);
            return err ? err->code : FM_ERR_NOMEM;
        }
        /* Every 16th vertex first: the smallest distance among them bounds
         * the result from above, and the pass below, bounded by it (a hair
         * more, so that a vertex at exactly that distance still finds it),
         * prunes far sooner. It finds the same smallest distance at the
         * same first vertex, with the same foot, as a pass bounded by maxd:
         * vertices beyond the bound could only have been replaced later. */
        double best = maxd;
        for (int side = 0; side < 2; side++) {
            const fm_mesh *from = side ? mb : ma;
            const fm_closest_tree *to = side ? ta : tb;
            const double *X = side ? XB : XA;
            for (size_t v = 0; v < fm_mesh_nvertices(from); v += 16) {
                fm_closest_hit h;
                if (fm_closest_query(to, X + 3 * v, best, &h) && h.dist < best)
                    best = h.dist;
            }
        }
        if (best < maxd)
            best = fmin(maxd, best * (1 + 1e-9) + 1e-9);
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
    fm_status st = cn_zone_build(a, sel_a, cn_subdivision(a, o->sample_spacing), 0, &za);
    if (st == FM_OK &&
        (st = cn_zone_build(b, sel_b, cn_subdivision(b, o->sample_spacing), 0, &zb)) != FM_OK)
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

/* Candidates measured on N threads, each into its own slot. */
typedef struct measure_work {
    const cn_sheet *sh;
    const size_t (*cand)[2];
    const fm_connect_options *o;
    double reach;
    fm_connect_pair *pair;
    unsigned char *keep, *meshed;
    fm_status *st;
    fm_error *err;
} measure_work;

static void measure_task(void *user, size_t k)
{
    measure_work *w = user;
    const cn_sheet *a = &w->sh[w->cand[k][0]], *b = &w->sh[w->cand[k][1]];
    unsigned char *sel_a = malloc(a->nsu * a->nsv + 1), *sel_b = malloc(b->nsu * b->nsv + 1);
    int keep = 0, meshed = 0;
    if (!sel_a || !sel_b)
        w->st[k] = fm_error_set(&w->err[k], FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    else
        w->st[k] = measure_pair(a, b, w->o, w->reach, sel_a, sel_b, &w->pair[k], &keep, &meshed,
                                &w->err[k]);
    w->keep[k] = (unsigned char)keep;
    w->meshed[k] = (unsigned char)meshed;
    free(sel_a);
    free(sel_b);
}

fm_status cn_find_pairs(const cn_sheet *sh, size_t ns, const fm_connect_options *opt,
                        fm_connect_pairs **out, fm_error *err)
{
    const fm_connect_options *o = opt;
    double reach = o->reach < 0 ? o->distance : o->reach;
    *out = NULL;
    fm_connect_pairs *p = calloc(1, sizeof *p);
    if (!p)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    for (size_t k = 0; k < ns; k++)
        p->stats.cells += sh[k].nactive;
    p->stats.sheets = ns;
    double t1 = fm_clock_seconds();
    fm_status st = FM_OK;
    /* candidates, in the order of the sheets */
    size_t nc = 0, cap = 0;
    size_t(*cand)[2] = NULL;
    for (size_t i = 0; i < ns && st == FM_OK; i++)
        for (size_t j = i + 1; j < ns && st == FM_OK; j++) {
            if (!sh[i].nactive || !sh[j].nactive ||
                !boxes_near(&sh[i], &sh[j], o->distance))
                continue;
            if (nc == cap) {
                cap = cap ? 2 * cap : 256;
                size_t(*nw)[2] = realloc(cand, cap * sizeof *nw);
                if (!nw) {
                    st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
                    break;
                }
                cand = nw;
            }
            cand[nc][0] = i;
            cand[nc][1] = j;
            nc++;
        }
    double t2 = fm_clock_seconds();
    p->stats.time_candidates = t2 - t1;
    p->stats.candidates = nc;
    measure_work mw = {sh, (const size_t(*)[2])cand, o, reach, NULL, NULL, NULL, NULL, NULL};
    if (st == FM_OK && nc) {
        mw.pair = malloc(nc * sizeof *mw.pair);
        mw.keep = calloc(nc, 1);
        mw.meshed = calloc(nc, 1);
        mw.st = calloc(nc, sizeof *mw.st);
        mw.err = calloc(nc, sizeof *mw.err);
        if (!mw.pair || !mw.keep || !mw.meshed || !mw.st || !mw.err)
            st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
        else
            cn_parallel_for(nc, o->nthreads, measure_task, &mw);
    }
    /* the first candidate in order that failed decides the error, as on one thread */
    size_t nkeep = 0;
    for (size_t k = 0; k < nc && st == FM_OK; k++) {
        if (mw.st[k] != FM_OK) {
            st = mw.st[k];
            if (err)
                *err = mw.err[k];
            break;
        }
        nkeep += mw.keep[k];
    }
    if (st == FM_OK && nkeep) {
        p->pair = malloc(nkeep * sizeof *p->pair);
        if (!p->pair)
            st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
        p->cap = nkeep;
    }
    for (size_t k = 0; k < nc && st == FM_OK; k++) {
        p->stats.measured += mw.meshed[k];
        if (mw.keep[k])
            p->pair[p->n++] = mw.pair[k];
    }
    p->stats.time_measure = fm_clock_seconds() - t2;
    free(mw.pair);
    free(mw.keep);
    free(mw.meshed);
    free(mw.st);
    free(mw.err);
    free(cand);
    if (st != FM_OK) {
        fm_connect_pairs_destroy(p);
        return st;
    }
    *out = p;
    return FM_OK;
}

void cn_pairs_set_time_sample(fm_connect_pairs *p, double seconds)
{
    p->stats.time_sample = seconds;
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
    cn_sheet *sh = NULL;
    size_t ns = 0;
    double t0 = fm_clock_seconds();
    fm_status st = cn_sheets_build(models, n, reach, o.nthreads, &sh, &ns, err);
    if (st != FM_OK)
        return st;
    double t1 = fm_clock_seconds();
    st = cn_find_pairs(sh, ns, &o, out, err);
    if (st == FM_OK)
        cn_pairs_set_time_sample(*out, t1 - t0);
    cn_sheets_free(sh, ns);
    return st;
}
